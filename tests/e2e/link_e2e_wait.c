/* SPDX-License-Identifier: MIT */
/* link_e2e_wait: the probes a waiting command sends leave nothing for the next command
 * (docs/link.md 3.3). On fbrlsim's strict --baud 9600 line a FINISH waits long enough
 * for idle probes to go out; the FINISH erases their markers itself, so the next command
 * is typed at once onto an empty line: no probe, one typing, no echo mismatch, and
 * fbrlsim's log (the truth) shows exactly the commands sent, no marker line.
 * Usage: link_e2e_wait FBRLSIM */
#include <string.h>

#include "rapl_harness.h"

#define CHECK(c)                                                         \
    do {                                                                 \
        if (!(c)) {                                                      \
            fprintf(stderr, "FAIL %s:%d: %s\n", __FILE__, __LINE__, #c); \
            return 1;                                                    \
        }                                                                \
    } while (0)

int main(int argc, char **argv)
{
    if (argc < 2)
        return 2;
    char dir[64], log[128];
    rig_tmpdir(dir, sizeof dir, "wait");
    CHECK(dir[0] != '\0');
    snprintf(log, sizeof log, "%s/log", dir);
    const char *args[] = {"--baud", "9600", "--log", log, NULL};
    fbrl_link_config cfg;
    fbrl_link_config_init(&cfg);
    rig r;
    CHECK(rig_start(&r, argv[1], args, 9600, FBRL_FLOW_NONE, &cfg) == 0);
    CHECK(fbrl_link_connect(&r.link) == FBRL_OK);
    CHECK(fbrl_link_raw(&r.link, "HOME") == FBRL_OK);
    CHECK(fbrl_link_raw(&r.link, "FINISH") == FBRL_OK);
    CHECK(fbrl_link_raw(&r.link, "JOINT 1,16") == FBRL_OK);
    fbrl_link_stats s0, s1, s2;
    fbrl_link_get_stats(&r.link, &s0);
    CHECK(fbrl_link_raw(&r.link, "FINISH") == FBRL_OK);
    fbrl_link_get_stats(&r.link, &s1);
    CHECK(s1.probes > s0.probes);      /* it waited: probes went out, markers were left */
    CHECK(s1.cleans == s0.cleans + 1); /* and the FINISH erased them */
    CHECK(fbrl_link_raw(&r.link, "SPEED 50") == FBRL_OK);
    fbrl_link_get_stats(&r.link, &s2);
    CHECK(s2.probes == s1.probes); /* no erase probe before the next command */
    CHECK(s2.attempts == s1.attempts + 1);
    CHECK(s2.echo_mismatch == s1.echo_mismatch && s2.echo_timeout == s1.echo_timeout);
    rig_stop(&r);
    /* the log: every line one of ours, none with a probe's characters */
    FILE *f = fopen(log, "r");
    CHECK(f != NULL);
    char line[256];
    int speed = 0, n = 0;
    while (fgets(line, sizeof line, f)) {
        n++;
        CHECK(strpbrk(line, "!$@^|'?") == NULL);
        if (strstr(line, "SPEED 50"))
            speed++;
    }
    fclose(f);
    remove(log);
    rmdir(dir);
    CHECK(speed == 1 && n >= 5);
    printf(
        "link_e2e_wait: %llu probes while waiting, markers erased by the FINISH, next command typed once\n",
        (unsigned long long)(s1.probes - s0.probes));
    return 0;
}
