/* SPDX-License-Identifier: MIT */
/* bench_link_fate: what the exactly-once rules (docs/link.md 3.9) cost.
 *  1. On a clean paced line (fbrlsim --baud 9600): a command not safe to repeat
 *     (V3=V3+1) and one that is (V3=1234) as shares of their echo bound: the rules send
 *     no extra byte when nothing goes wrong.
 *  2. W2 position reads per second: believed on the block's own consistency (one read)
 *     against the older rule of two agreeing replies (forced with an arm model that never
 *     agrees).
 *  3. On the burst-loss line (tests/burst_relay: 50-byte runs at 0.2 % per byte, when the
 *     tests are built): 1000 commands not safe to repeat against 1000 safe ones, with the
 *     reads of STATUS that settle damaged replies and the share reported "may have run".
 * Usage: bench_link_fate [FBRLSIM] [RELAY]  (defaults ./sim/fbrlsim ./tests/burst_relay) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../tests/e2e/rapl_harness.h"

static double run_lines(fbrl_link *l, const char *line, int count, long *maybe)
{
    uint64_t t0 = fbrl_clock_now_us();
    for (int i = 0; i < count; i++) {
        fbrl_status st = fbrl_link_raw(l, line);
        if (st == FBRL_EMAYBE && maybe)
            (*maybe)++;
        else if (st != FBRL_OK && !maybe) {
            fprintf(stderr, "%s: %s\n", line, fbrl_status_name(st));
            return 0;
        }
    }
    return count / ((fbrl_clock_now_us() - t0) / 1e6);
}

static double run_w2(fbrl_link *l, int count)
{
    uint64_t t0 = fbrl_clock_now_us();
    for (int i = 0; i < count; i++)
        if (fbrl_link_where(l, FBRL_RAPL_W2, NULL) != FBRL_OK)
            return 0;
    return count / ((fbrl_clock_now_us() - t0) / 1e6);
}

static void clean_line(const char *sim)
{
    const char *args[] = {"--baud", "9600", NULL};
    fbrl_link_config cfg;
    fbrl_link_config_init(&cfg);
    cfg.check_units = 0; /* the command rate is measured, not the connect */
    rig r;
    if (rig_start(&r, sim, args, 9600, FBRL_FLOW_NONE, &cfg) != 0 || fbrl_link_connect(&r.link) != FBRL_OK) {
        fprintf(stderr, "cannot start %s\n", sim);
        exit(1);
    }
    (void)fbrl_link_raw(&r.link, "V3=0");
    static const char *const lines[] = {"V3=V3+1", "V3=1234"};
    for (int k = 0; k < 2; k++) {
        size_t n = strlen(lines[k]);
        double cps = run_lines(&r.link, lines[k], 30, NULL), bound = 960.0 / (double)(n + 4);
        printf("9600 baud, clean: %-8s (%s) %5.1f cmd/s = %5.1f %% of its echo bound %.1f\n", lines[k],
               fbrl_link_line_safe(lines[k]) ? "safe to repeat    " : "not safe to repeat", cps,
               100.0 * cps / bound, bound);
    }
    (void)fbrl_link_raw(&r.link, "HOME");
    (void)fbrl_link_finish(&r.link);
    double one = run_w2(&r.link, 6);
    fbrl_link_stats s;
    fbrl_link_get_stats(&r.link, &s);
    rig_stop(&r);
    /* the same with an arm that never agrees: two equal replies needed */
    static fbrl_arm other;
    other = *fbrl_arm_model(0);
    for (unsigned k = 0; k < other.naxes; k++)
        other.ppd[k] = 1.0;
    cfg.arm = &other;
    if (rig_start(&r, sim, args, 9600, FBRL_FLOW_NONE, &cfg) != 0 || fbrl_link_connect(&r.link) != FBRL_OK)
        exit(1);
    double two = run_w2(&r.link, 6);
    rig_stop(&r);
    printf(
        "9600 baud: W2 %.2f reads/s believed on its own consistency, %.2f reads/s with two agreeing replies "
        "(%.2fx)\n",
        one, two, two > 0 ? one / two : 0.0);
}

static void burst_line(const char *sim, const char *relay)
{
    if (access(relay, X_OK) != 0) {
        printf("burst line: %s not built (configure with the tests)\n", relay);
        return;
    }
    static const char *const lines[] = {"V3=V3+1", "V3=1234", "V3=V3+1", "V3=1234"};
    for (int k = 0; k < 4; k++) {
        rig r;
        const char *args[] = {NULL};
        fbrl_link_config cfg;
        fbrl_link_config_init(&cfg);
        cfg.check_units = 0; /* the command rate is measured, not the connect */
        cfg.echo_timeout_ms = 10;
        cfg.max_attempts = 60;
        /* fbrlsim, then the relay in front of it; the rig's uart is reopened on the relay */
        if (rig_start(&r, sim, args, 115200, FBRL_FLOW_NONE, &cfg) != 0)
            exit(1);
        fbrl_uart_close(&r.uart);
        int fd[2];
        if (pipe(fd) != 0)
            exit(1);
        pid_t rp = fork();
        if (rp == 0) {
            dup2(fd[1], 1);
            close(fd[0]);
            execl(relay, relay, r.path, "0.002", "50", k < 2 ? "7" : "11",
                  (char *)NULL); /* the same bursts for both */
            _exit(127);
        }
        close(fd[1]);
        char path[256];
        size_t n = 0;
        char c;
        while (n + 1 < sizeof path && read(fd[0], &c, 1) == 1 && c != '\n')
            path[n++] = c;
        path[n] = '\0';
        close(fd[0]);
        fbrl_uart_config uc = FBRL_UART_CONFIG_DEFAULT;
        uc.baud = 115200;
        uc.flow = FBRL_FLOW_NONE;
        if (fbrl_uart_posix_open(&r.port, &r.uart, path, &uc, r.rx, sizeof r.rx, r.tx, sizeof r.tx, NULL) !=
                FBRL_OK ||
            fbrl_link_init(&r.link, &r.uart, &cfg) != FBRL_OK || fbrl_link_connect(&r.link) != FBRL_OK)
            exit(1);
        long maybe = 0;
        for (int t = 0; t < 20 && fbrl_link_raw(&r.link, "V3=0") != FBRL_OK; t++)
            ; /* defined, so that V3=V3+1 is not refused */
        double cps = run_lines(&r.link, lines[k], 1000, &maybe);
        fbrl_link_stats s;
        fbrl_link_get_stats(&r.link, &s);
        kill(rp, SIGTERM);
        waitpid(rp, NULL, 0);
        rig_stop(&r);
        printf("burst line (50-byte runs, 0.2 %%/byte): 1000 x %-8s %6.1f cmd/s, %4.1f %% may have run, %llu "
               "damaged "
               "replies settled by STATUS, %llu typed again without proof, %llu not typed again\n",
               lines[k], cps, maybe / 10.0, (unsigned long long)s.settled,
               (unsigned long long)(s.cr_unconfirmed), (unsigned long long)s.not_retyped);
    }
}

int main(int argc, char **argv)
{
    const char *sim = argc > 1 ? argv[1] : "./sim/fbrlsim",
               *relay = argc > 2 ? argv[2] : "./tests/burst_relay";
    clean_line(sim);
    burst_line(sim, relay);
    return 0;
}
