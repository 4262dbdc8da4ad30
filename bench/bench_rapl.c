/* SPDX-License-Identifier: MIT */
/* bench_rapl: RAPL command throughput of the echo-verified link against fbrlsim with
 * baud pacing, as a fraction of the line-rate limit, and the encoder's cost.
 * Usage: bench_rapl [FBRLSIM] (default: ./sim/fbrlsim from the build directory)
 *
 * Line-rate limit: a command of n characters needs n + 1 bytes (with the CR) from the
 * host, so at most (baud / 10) / (n + 1) commands per second fit on an 8N1 line.
 * Echo bound: the controller sends back n + 4 bytes per command (the echo, CR LF and the
 * prompt ">>") at the same rate, so no client that reads the echo can exceed
 * (baud / 10) / (n + 4), i.e. (n + 1) / (n + 4) of the line-rate limit. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../tests/e2e/rapl_harness.h"

static double encode_ns(void)
{
    const fbrl_rapl_arg args[] = {fbrl_rapl_str("P1"),    fbrl_rapl_real(14.25), fbrl_rapl_real(-2.5),
                                  fbrl_rapl_real(8.125),  fbrl_rapl_real(0.0),   fbrl_rapl_real(-90.0),
                                  fbrl_rapl_real(12.3456)};
    char buf[FBRL_RAPL_LINE_MAX];
    size_t len, total = 0;
    const long n = 1000000;
    uint64_t t0 = fbrl_clock_now_us();
    for (long i = 0; i < n; i++) {
        fbrl_rapl_arg a[7];
        memcpy(a, args, sizeof a);
        a[1].r += (double)(i & 1023) * 0.001; /* defeat hoisting */
        if (fbrl_rapl_encode(buf, sizeof buf, &len, FBRL_RAPL_KEYWORD, FBRL_RAPL_POINT, a, 7, 0) == FBRL_OK)
            total += len;
    }
    uint64_t t1 = fbrl_clock_now_us();
    const fbrl_rapl_arg margs[] = {fbrl_rapl_str("P1")};
    for (long i = 0; i < n; i++)
        if (fbrl_rapl_encode(buf, sizeof buf, &len, FBRL_RAPL_KEYWORD, FBRL_RAPL_MOVE, margs, 1, 1) ==
            FBRL_OK)
            total += len;
    uint64_t t2 = fbrl_clock_now_us();
    printf("encode POINT (6 reals): %.0f ns/command; MOVE P1,S: %.0f ns/command (%zu bytes)\n",
           (t1 - t0) * 1000.0 / n, (t2 - t1) * 1000.0 / n, total);
    return (t1 - t0) * 1000.0 / n;
}

/* Run `count` copies of line through the link; returns commands per second. */
static double run(fbrl_link *l, const char *line, int count)
{
    uint64_t t0 = fbrl_clock_now_us();
    for (int i = 0; i < count; i++) {
        fbrl_status st = fbrl_link_raw(l, line);
        if (st != FBRL_OK) {
            fprintf(stderr, "%s: %s\n", line, fbrl_status_name(st));
            return 0;
        }
    }
    return count / ((fbrl_clock_now_us() - t0) / 1e6);
}

int main(int argc, char **argv)
{
    const char *sim = argc > 1 ? argv[1] : "./sim/fbrlsim";
    encode_ns();
    static const char *const lines[] = {"SPEED 50", "V1=123.4567",
                                        "POINT P1,14.2500,2.5000,8.1250,0.0000,90.0000,12.3456"};
    static const long bauds[] = {9600, 38400, 0};
    for (size_t b = 0; b < sizeof bauds / sizeof bauds[0]; b++) {
        char baud[16];
        snprintf(baud, sizeof baud, "%ld", bauds[b]);
        const char *args_paced[] = {"--baud", baud, NULL};
        const char *args_free[] = {NULL};
        fbrl_link_config cfg;
        fbrl_link_config_init(&cfg);
        cfg.check_units = 0; /* the command rate is measured, not the connect */
        rig r;
        if (rig_start(&r, sim, bauds[b] ? args_paced : args_free, bauds[b] ? (uint32_t)bauds[b] : 115200,
                      FBRL_FLOW_NONE, &cfg) != 0)
            return 1;
        if (fbrl_link_connect(&r.link) != FBRL_OK) {
            fprintf(stderr, "connect failed\n");
            return 1;
        }
        for (size_t k = 0; k < sizeof lines / sizeof lines[0]; k++) {
            size_t n = strlen(lines[k]);
            int count = bauds[b] == 9600 ? 20 : bauds[b] == 38400 ? 60 : 500;
            double cps = run(&r.link, lines[k], count);
            if (bauds[b]) {
                double limit = (bauds[b] / 10.0) / (double)(n + 1),
                       bound = (bauds[b] / 10.0) / (double)(n + 4);
                printf("%5ld baud  %-56s %3zu+1 bytes: %6.1f cmd/s = %5.1f %% of the line-rate limit %6.1f"
                       " (%5.1f %% of the echo bound %6.1f)\n",
                       bauds[b], lines[k], n, cps, 100.0 * cps / limit, limit, 100.0 * cps / bound, bound);
            } else {
                printf("unpaced     %-56s %3zu+1 bytes: %7.1f cmd/s (pty round trips)\n", lines[k], n, cps);
            }
        }
        fbrl_link_stats s;
        fbrl_link_get_stats(&r.link, &s);
        if (s.attempts != s.commands)
            printf("            (retypes: %llu of %llu commands)\n",
                   (unsigned long long)(s.attempts - s.commands), (unsigned long long)s.commands);
        rig_stop(&r);
    }
    return 0;
}
