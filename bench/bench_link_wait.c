/* SPDX-License-Identifier: MIT */
/* bench_link_wait: the next command after a wait against a fresh one (issue 11, item 4).
 * On fbrlsim's strict --baud 9600 line: SPEED 50 right after another SPEED 50 (fresh),
 * and SPEED 50 right after a FINISH that waited for a motion (JOINT 1,+-D) long enough
 * for the link's liveness probes to go out. Prints both, their ratio, the FINISH's own
 * time and the probes sent per wait.
 * Usage: bench_link_wait [FBRLSIM] [ROUNDS]  (defaults ./sim/fbrlsim 10) */
#include <stdio.h>
#include <stdlib.h>

#include "../tests/e2e/rapl_harness.h"

static uint64_t timed(fbrl_link *l, const char *line)
{
    uint64_t t0 = fbrl_clock_now_us();
    fbrl_status st = fbrl_link_raw(l, line);
    if (st != FBRL_OK) {
        fprintf(stderr, "%s: %s\n", line, fbrl_status_name(st));
        exit(1);
    }
    return fbrl_clock_now_us() - t0;
}

int main(int argc, char **argv)
{
    const char *sim = argc > 1 ? argv[1] : "./sim/fbrlsim";
    int rounds = argc > 2 ? atoi(argv[2]) : 10;
    const char *args[] = {"--baud", "9600", NULL};
    fbrl_link_config cfg;
    fbrl_link_config_init(&cfg);
    cfg.check_units = 0; /* the command rate is measured, not the connect */
    rig r;
    if (rounds < 1 || rig_start(&r, sim, args, 9600, FBRL_FLOW_NONE, &cfg) != 0 ||
        fbrl_link_connect(&r.link) != FBRL_OK) {
        fprintf(stderr, "cannot start %s\n", sim);
        return 1;
    }
    (void)timed(&r.link, "HOME"); /* motions are refused before the arm is homed */
    (void)timed(&r.link, "FINISH");
    (void)timed(&r.link, "SPEED 50");
    uint64_t fresh = 0, after = 0, fin = 0;
    unsigned long long probes = 0;
    for (int i = 0; i < rounds; i++) {
        (void)timed(&r.link, "SPEED 50");
        fresh += timed(&r.link, "SPEED 50");
        (void)timed(&r.link, i % 2 ? "JOINT 1,-16" : "JOINT 1,16");
        fbrl_link_stats s0, s1;
        fbrl_link_get_stats(&r.link, &s0);
        fin += timed(&r.link, "FINISH");
        fbrl_link_get_stats(&r.link, &s1);
        probes += s1.probes - s0.probes;
        after += timed(&r.link, "SPEED 50");
    }
    rig_stop(&r);
    double f = fresh / 1e3 / rounds, a = after / 1e3 / rounds;
    printf("9600 baud, strict line: FINISH waited %.0f ms (%.1f probes per wait); SPEED 50 fresh %.1f ms, "
           "right after "
           "the FINISH %.1f ms: %.2fx (target <= 1.10x)\n",
           fin / 1e3 / rounds, (double)probes / rounds, f, a, a / f);
    printf("| next command after a FINISH that waited %.0f ms, 9600 baud | %.1f ms (fresh: %.1f ms) | %.2fx "
           "a fresh "
           "one |\n",
           fin / 1e3 / rounds, a, f, a / f);
    return 0;
}
