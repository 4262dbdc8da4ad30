/* SPDX-License-Identifier: MIT */
/* link_e2e_aci.c - the link's connect step against the real fbrlsim: a controller that
 * powers up in ACI mode (fbrlsim --aci) is switched to terminal mode; one already in
 * terminal mode has the switch's bytes erased; the link learns the units from STATUS.
 * fbrlsim's command log is the truth for what ran.
 * Usage: link_e2e_aci FBRLSIM */
#include "rapl_harness.h"

static int failures;

#define CHECK(c)                                                                  \
    do {                                                                          \
        if (!(c)) {                                                               \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #c); \
            failures++;                                                           \
        }                                                                         \
    } while (0)

static void slurp(const char *path, char *buf, size_t cap)
{
    FILE *f = fopen(path, "r");
    size_t n = 0;
    if (f) {
        n = fread(buf, 1, cap - 1, f);
        fclose(f);
    }
    buf[n] = '\0';
}

/* Connects with cfg.aci to fbrlsim started with the given first option; returns the
 * connect status and leaves the rig running. */
static fbrl_status connect_to(rig *r, const char *sim, const char *opt, const char *log, int aci,
                              unsigned attempts)
{
    const char *args[] = {"--log", log, "--time-scale", "100", opt, NULL};
    fbrl_link_config cfg;
    fbrl_link_config_init(&cfg);
    cfg.aci = aci;
    cfg.max_attempts = attempts;
    cfg.reply_timeout_ms = 1000;
    if (rig_start(r, sim, args, 38400, FBRL_FLOW_XONXOFF, &cfg) != 0)
        return FBRL_EIO;
    return fbrl_link_connect(&r->link);
}

int main(int argc, char **argv)
{
    char dir[64], log[128], text[4096];
    rig r;
    fbrl_rapl_status_info st;
    if (argc != 2) {
        fprintf(stderr, "usage: link_e2e_aci FBRLSIM\n");
        return 2;
    }
    rig_tmpdir(dir, sizeof dir, "aci");
    if (!dir[0])
        return 1;

    /* 1. ACI at power-up: the switch, then NOHELP; METRIC is seen in STATUS */
    snprintf(log, sizeof log, "%s/aci.log", dir);
    CHECK(connect_to(&r, argv[1], "--aci", log, 1, 12) == FBRL_OK);
    CHECK(fbrl_link_status(&r.link, &st) == FBRL_OK);
    CHECK((st.have & FBRL_RAPL_ST_UNITS) && st.metric == 0);
    CHECK(fbrl_link_cmd(&r.link, FBRL_RAPL_METRIC, 0, 0, 0) == FBRL_OK);
    CHECK(fbrl_link_status(&r.link, &st) == FBRL_OK);
    CHECK((st.have & FBRL_RAPL_ST_UNITS) && st.metric == 1);
    CHECK(fbrl_link_last_status(&r.link)->metric == 1);
    rig_stop(&r);
    slurp(log, text, sizeof text);
    CHECK(strncmp(text, "# ACI: TERMINAL MODE\nNOHELP\nSTATUS\n", 35) == 0);
    CHECK(strstr(text, "\nMETRIC\n") != NULL);
    CHECK(strstr(text, "R!") == NULL);

    /* 2. a controller already in terminal mode: "R!" is erased, nothing extra runs */
    snprintf(log, sizeof log, "%s/term.log", dir);
    CHECK(connect_to(&r, argv[1], "--nak", log, 1, 12) == FBRL_OK);
    CHECK(fbrl_link_status(&r.link, &st) == FBRL_OK);
    CHECK(st.last_error == -1); /* no 012 from a stray line */
    rig_stop(&r);
    slurp(log, text, sizeof text);
    CHECK(strncmp(text, "NOHELP\nSTATUS", 13) == 0);

    /* 3. without the switch an ACI-mode controller never answers: nothing runs */
    snprintf(log, sizeof log, "%s/none.log", dir);
    CHECK(connect_to(&r, argv[1], "--aci", log, 0, 2) != FBRL_OK);
    rig_stop(&r);
    slurp(log, text, sizeof text);
    CHECK(text[0] == '\0');

    snprintf(text, sizeof text, "rm -rf '%s'", dir);
    if (system(text) != 0)
        fprintf(stderr, "could not remove %s\n", dir);
    if (failures)
        fprintf(stderr, "link_e2e_aci: %d failure(s)\n", failures);
    return failures ? 1 : 0;
}
