/* SPDX-License-Identifier: MIT */
/* robot_e2e: the robot words end to end. Starts the real fbrlsim binary on a pty (fast
 * simulated time, a command log, a control FIFO, optional scripted inputs), connects a
 * link over the POSIX uart backend, makes a VM with the data glossary and the robot
 * words, and runs one Forth test file (tests/forth/robot_*.fs) with the tester harness.
 *
 * Test-only words the file can use:
 *   LOG: text     the next command fbrlsim executed was exactly `text` (fails otherwise;
 *                 `?` stands for any one character, e.g. the scratch point FBRLT?).
 *                 W5 and STATUS lines before it are passed over unless text is one of
 *                 them: the robot words read the velocity (W5) before a motion while the
 *                 arm moves, as often as timing has it (docs/robot.md "Stopping safely"),
 *                 and the link asks STATUS when a prompt came later than its echo
 *                 timeout (a busy host: the suite under ASan) to learn whether a line ran
 *   LOG-SKIP      forget the commands logged so far
 *   LOG-COUNT" text"  ( -- n ) how many of the commands logged since the last LOG-SKIP
 *                 or LOG: equal text (they stay unread)
 *   SIM: line     a control line for fbrlsim (IN n 0|1, POWER 0|1, OBJECT w, TEACH)
 *   OUT-CLEAR / OUT"  text"  ( -- flag ) console output since OUT-CLEAR contains text
 *   WORLD@ ( -- ) ( F: x y z o a t ) the arm's actual position from W2, raw
 * Usage: robot_e2e FBRLSIM FILE.fs [INPUTS-FILE|-] [STATE-FILE]
 * INPUTS-FILE: fbrlsim --inputs script; STATE-FILE: copied to fbrlsim's state file before
 * it starts (e.g. programs for RAPL-RUN). */
#include <fcntl.h>
#include <fnmatch.h>
#include <math.h>
#include <time.h>

#include "rapl_harness.h"
#include "fbrl/glossary.h"
#include "fbrl/robot.h"
#include "fbrl/vm.h"
#include "support/vm_host.h"

static rig R;
static fbrl_vm *vm;
static fbrl_glossary G;
static fbrl_robot robot;
static char outbuf[1 << 18];
static size_t outlen;
static char log_path[512], ctl_path[512];
static FILE *logf_;
static int c_failures;
static const char *keys = "";

static void h_write(void *user, const char *s, size_t n)
{
    (void)user;
    fwrite(s, 1, n, stdout);
    if (outlen + n >= sizeof outbuf)
        outlen = 0;
    memcpy(outbuf + outlen, s, n);
    outlen += n;
    outbuf[outlen] = 0;
}

static int h_key(void *user)
{
    (void)user;
    return *keys ? (unsigned char)*keys++ : -1;
}

/* ---- test words ---- */

static fbrl_status fail(const char *what, const char *a, const char *b)
{
    fprintf(stderr, "FAIL %s wanted '%s', got '%s'\n", what, a, b);
    c_failures++;
    return FBRL_OK;
}

static void rest_of_line(char *buf, size_t cap)
{
    const char *s;
    size_t n, k = 0;
    /* the rest of the line, word by word, single spaces */
    for (;;) {
        fbrl_vm_parse_name(vm, &s, &n);
        if (n == 0)
            break;
        if (k && k + 1 < cap)
            buf[k++] = ' ';
        for (size_t i = 0; i < n && k + 1 < cap; i++)
            buf[k++] = s[i];
    }
    buf[k] = 0;
}

static int next_log_line(char *buf, size_t cap)
{
    long pos = ftell(logf_);
    if (!fgets(buf, (int)cap, logf_) || !strchr(buf, '\n')) {
        clearerr(logf_);
        fseek(logf_, pos, SEEK_SET);
        return 0;
    }
    buf[strcspn(buf, "\r\n")] = 0;
    return 1;
}

static fbrl_status t_log(fbrl_vm *v, void *arg)
{
    char want[256], got[256];
    (void)v;
    (void)arg;
    rest_of_line(want, sizeof want);
    do {
        if (!next_log_line(got, sizeof got))
            return fail("LOG:", want, "(nothing)");
    } while ((strcmp(got, "W5") == 0 || strcmp(got, "STATUS") == 0) && fnmatch(want, got, 0) != 0);
    if (fnmatch(want, got, 0) != 0)
        return fail("LOG:", want, got);
    return FBRL_OK;
}

static fbrl_status t_log_skip(fbrl_vm *v, void *arg)
{
    char got[256];
    (void)v;
    (void)arg;
    while (next_log_line(got, sizeof got))
        ;
    return FBRL_OK;
}

static fbrl_status t_log_count(fbrl_vm *v, void *arg)
{
    const char *s;
    size_t n;
    char want[256], got[256];
    fbrl_cell a, u;
    (void)arg;
    (void)s;
    (void)n;
    fbrl_vm_pop(v, &u);
    fbrl_vm_pop(v, &a);
    snprintf(want, sizeof want, "%.*s", (int)u, (const char *)a);
    long pos = ftell(logf_);
    fbrl_cell count = 0;
    while (next_log_line(got, sizeof got))
        if (strcmp(got, want) == 0)
            count++;
    fseek(logf_, pos, SEEK_SET);
    return fbrl_vm_push(v, count);
}

static fbrl_status t_sim(fbrl_vm *v, void *arg)
{
    char line[256];
    (void)v;
    (void)arg;
    rest_of_line(line, sizeof line - 1);
    strcat(line, "\n");
    int fd = open(ctl_path, O_WRONLY | O_NONBLOCK);
    if (fd < 0 || write(fd, line, strlen(line)) != (ssize_t)strlen(line)) {
        fprintf(stderr, "SIM: cannot write control FIFO %s\n", ctl_path);
        c_failures++;
    }
    if (fd >= 0)
        close(fd);
    fbrl_clock_sleep_us(100000); /* let the emulator read it */
    return FBRL_OK;
}

static fbrl_status t_out_clear(fbrl_vm *v, void *arg)
{
    (void)v;
    (void)arg;
    outlen = 0;
    outbuf[0] = 0;
    return FBRL_OK;
}

static fbrl_status t_out_has(fbrl_vm *v, void *arg)
{
    fbrl_cell a, u;
    char want[256];
    (void)arg;
    fbrl_vm_pop(v, &u);
    fbrl_vm_pop(v, &a);
    snprintf(want, sizeof want, "%.*s", (int)u, (const char *)a);
    return fbrl_vm_push(v, strstr(outbuf, want) ? -1 : 0);
}

static fbrl_status t_world(fbrl_vm *v, void *arg)
{
    fbrl_rapl_pos p;
    (void)arg;
    if (fbrl_link_finish(&R.link) != FBRL_OK || fbrl_link_where(&R.link, FBRL_RAPL_W2, &p) != FBRL_OK)
        return fbrl_vm_throw(v, -300, "WORLD@: W2 failed");
    for (int k = 0; k < 6; k++)
        fbrl_vm_fpush(v, p.world[k]);
    return t_log_skip(v, NULL); /* its own FINISH and W2 are no test's business */
}

static fbrl_status t_keys(fbrl_vm *v, void *arg)
{
    static char buf[1024];
    fbrl_cell a, u;
    (void)arg;
    fbrl_vm_pop(v, &u);
    fbrl_vm_pop(v, &a);
    snprintf(buf, sizeof buf, "%.*s", (int)u, (const char *)a);
    for (char *p = buf; *p; p++)
        if (*p == '|')
            *p = '\n';
    keys = buf;
    return FBRL_OK;
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: robot_e2e FBRLSIM FILE.fs [INPUTS]\n");
        return 2;
    }
    char dir[256];
    rig_tmpdir(dir, sizeof dir, "robot");
    snprintf(log_path, sizeof log_path, "%s/log", dir);
    snprintf(ctl_path, sizeof ctl_path, "%s/ctl", dir);
    char state[512];
    snprintf(state, sizeof state, "%s/state", dir);
    const char *args[16] = {"--time-scale", "20", "--log", log_path, "--control", ctl_path, "--state", state};
    int na = 8;
    if (argc > 3 && strcmp(argv[3], "-") != 0) {
        args[na++] = "--inputs";
        args[na++] = argv[3];
    }
    if (argc > 4) { /* the emulator's battery-backed memory to start from */
        FILE *in = fopen(argv[4], "r"), *out = fopen(state, "w");
        int c;
        if (!in || !out) {
            fprintf(stderr, "cannot copy %s to %s\n", argv[4], state);
            return 1;
        }
        while ((c = fgetc(in)) != EOF)
            fputc(c, out);
        fclose(in);
        fclose(out);
    }
    args[na] = NULL;
    fbrl_link_config lc;
    fbrl_link_config_init(&lc);
    /* One reading per query, so that the log shows every command the robot words sent
     * exactly once (confirmed reads are the link's own business and tested there). */
    lc.query_reads = 1;
    /* A loaded CI machine can stall this process past the default 100 ms; the link then
     * probes, which is correct but shows up in the log (and a stream's stop can meet a
     * probe: reported to the link's owner). The robot words are what is tested here. */
    lc.echo_timeout_ms = 500;
    if (rig_start(&R, argv[1], args, 38400, FBRL_FLOW_XONXOFF, &lc) != 0)
        return 1;
    if (fbrl_link_connect(&R.link) != FBRL_OK) {
        fprintf(stderr, "connect failed\n");
        rig_stop(&R);
        return 1;
    }
    logf_ = fopen(log_path, "r");
    if (!logf_) {
        fprintf(stderr, "no log %s\n", log_path);
        rig_stop(&R);
        return 1;
    }

    static unsigned char mem[4 << 20] __attribute__((aligned(16)));
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = mem;
    cfg.mem_size = sizeof mem;
    cfg.host.write = h_write;
    cfg.host.key = h_key;
    vmh_use_files(&cfg.host);
    vmh_use_clock(&cfg.host);
    if (fbrl_vm_create(&vm, &cfg) != FBRL_OK || fbrl_glossary_install(vm, &G) != FBRL_OK ||
        fbrl_robot_install(vm, &robot, &R.link, &G) != FBRL_OK) {
        fprintf(stderr, "VM setup failed\n");
        rig_stop(&R);
        return 1;
    }
    fbrl_vm_define(vm, "LOG:", t_log, NULL, "( \"text\" -- )", "test: next logged command");
    fbrl_vm_define(vm, "LOG-SKIP", t_log_skip, NULL, "( -- )", "test: drop logged commands");
    fbrl_vm_define(vm, "(LOG-COUNT)", t_log_count, NULL, "( a u -- n )", "test");
    fbrl_vm_define(vm, "SIM:", t_sim, NULL, "( \"line\" -- )", "test: control line");
    fbrl_vm_define(vm, "OUT-CLEAR", t_out_clear, NULL, "( -- )", "test");
    fbrl_vm_define(vm, "(OUT-HAS)", t_out_has, NULL, "( a u -- flag )", "test");
    fbrl_vm_define(vm, "WORLD@", t_world, NULL, "( F: -- x y z o a t )", "test: raw W2 WORLD");
    fbrl_vm_define(vm, "KEYS!", t_keys, NULL, "( a u -- )", "test: console input ('|' = newline)");
    const char *defs = ": LOG-COUNT\" [CHAR] \" PARSE (LOG-COUNT) ;\n"
                       ": OUT\" [CHAR] \" PARSE (OUT-HAS) ;\n";
    fbrl_status st = fbrl_vm_eval(vm, defs, strlen(defs));
    if (st == FBRL_OK)
        st = fbrl_vm_include(vm, FBRL_TEST_SRCDIR "/tests/forth/tester.fs");
    if (st == FBRL_OK)
        st = fbrl_vm_include(vm, argv[2]);
    int rc = 0;
    if (st != FBRL_OK) {
        const fbrl_vm_error *e = fbrl_vm_last_error(vm);
        fprintf(stderr, "\n%s: error %d (%s) at word '%s' %s:%lu\n", argv[2], e->throw_code, e->message,
                e->word, e->file, e->line);
        rc = 1;
    } else {
        fbrl_cell tests = 0, errors = 0;
        fbrl_vm_eval(vm, "#ERRORS @ #TESTS @", 18);
        fbrl_vm_pop(vm, &tests);
        fbrl_vm_pop(vm, &errors);
        printf("\n%s: %ld tests, %ld failures, %d log/harness failures\n", argv[2], (long)tests, (long)errors,
               c_failures);
        if (errors || c_failures || tests < 1)
            rc = 1;
    }
    if (rc) {
        fbrl_link_stats ls;
        fbrl_link_get_stats(&R.link, &ls);
        fprintf(stderr,
                "link: %llu commands, %llu attempts, %llu echo mismatches, %llu echo timeouts, "
                "%llu probes, %llu prompts lost, %llu requeries\n",
                (unsigned long long)ls.commands, (unsigned long long)ls.attempts,
                (unsigned long long)ls.echo_mismatch, (unsigned long long)ls.echo_timeout,
                (unsigned long long)ls.probes, (unsigned long long)ls.prompt_lost,
                (unsigned long long)ls.requeries);
    }
    fbrl_glossary_finish(&G);
    fclose(logf_);
    rig_stop(&R);
    unlink(log_path);
    unlink(state);
    unlink(ctl_path);
    rmdir(dir);
    return rc;
}
