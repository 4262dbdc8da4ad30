/* SPDX-License-Identifier: MIT */
/* link_e2e_multi: one thread drives two robots (two fbrlsim processes on two ptys)
 * through fbrl_link_start() + fbrl_link_poll_many(): each robot works through its own
 * command list while the other's commands are in flight; both end where they were sent.
 * Usage: link_e2e_multi FBRLSIM */
#include <math.h>

#include "rapl_harness.h"

typedef struct step {
    const char *line;
    fbrl_link_reply kind;
} step;

static const step plan_a[] = {
    {"HOME", FBRL_LINK_REPLY_NONE},
    {"SPEED 80", FBRL_LINK_REPLY_NONE},
    {"POINT A1,14.0000,2.0000,8.0000,0.0000,-90.0000,0.0000", FBRL_LINK_REPLY_NONE},
    {"MOVE A1", FBRL_LINK_REPLY_NONE},
    {"DEPART 2.0000", FBRL_LINK_REPLY_NONE},
    {"FINISH", FBRL_LINK_REPLY_NONE},
    {"W2", FBRL_LINK_REPLY_POS},
};
static const step plan_b[] = {
    {"HOME", FBRL_LINK_REPLY_NONE},
    {"READY", FBRL_LINK_REPLY_NONE},
    {"JOINT 1,30.0000", FBRL_LINK_REPLY_NONE},
    {"V1=4.5000", FBRL_LINK_REPLY_NONE},
    {"TYPEV V1", FBRL_LINK_REPLY_REAL},
    {"MOVE NOWHERE", FBRL_LINK_REPLY_NONE},
    {"FINISH", FBRL_LINK_REPLY_NONE},
    {"W2", FBRL_LINK_REPLY_POS},
};

int main(int argc, char **argv)
{
    if (argc < 2)
        return 2;
    const char *args[] = {"--time-scale", "20", NULL};
    fbrl_link_config cfg;
    fbrl_link_config_init(&cfg);
    cfg.wait_timeout_ms = 30000;
    static rig ra, rb;
    if (rig_start(&ra, argv[1], args, 115200, FBRL_FLOW_NONE, &cfg) != 0 ||
        rig_start(&rb, argv[1], args, 115200, FBRL_FLOW_NONE, &cfg) != 0)
        return 1;
    if (fbrl_link_connect(&ra.link) != FBRL_OK || fbrl_link_connect(&rb.link) != FBRL_OK)
        return 1;
    const step *plans[2] = {plan_a, plan_b};
    size_t len[2] = {sizeof plan_a / sizeof plan_a[0], sizeof plan_b / sizeof plan_b[0]};
    size_t next[2] = {0, 0};
    fbrl_link *links[2] = {&ra.link, &rb.link};
    int failures = 0, overlap = 0;
    for (int k = 0; k < 2; k++)
        if (fbrl_link_start(links[k], plans[k][next[k]++].line, plans[k][0].kind) != FBRL_OK)
            return 1;
    uint64_t end = fbrl_clock_now_us() + 60000000u;
    while ((fbrl_link_busy(links[0]) || fbrl_link_busy(links[1])) && fbrl_clock_now_us() < end) {
        size_t idx;
        overlap += fbrl_link_busy(links[0]) && fbrl_link_busy(links[1]);
        fbrl_status st = fbrl_link_poll_many(links, 2, 50, &idx);
        if (idx >= 2)
            continue;
        const step *done = &plans[idx][next[idx] - 1];
        int want_err = !strcmp(done->line, "MOVE NOWHERE");
        if ((st == FBRL_ECONTROLLER) != want_err || (st != FBRL_OK && st != FBRL_ECONTROLLER)) {
            fprintf(stderr, "robot %c: %s: %s\n", 'A' + (int)idx, done->line, fbrl_status_name(st));
            failures++;
        }
        if (want_err) {
            int code;
            fbrl_link_error(links[idx], &code, NULL);
            if (code != 11) {
                fprintf(stderr, "robot B: MOVE NOWHERE gave %d\n", code);
                failures++;
            }
        }
        if (done->kind == FBRL_LINK_REPLY_REAL) {
            double v;
            if (fbrl_link_last_real(links[idx], &v) != FBRL_OK || v != 4.5) {
                fprintf(stderr, "robot B: TYPEV V1 wrong\n");
                failures++;
            }
        }
        if (next[idx] < len[idx]) {
            const step *s = &plans[idx][next[idx]++];
            if (fbrl_link_start(links[idx], s->line, s->kind) != FBRL_OK)
                failures++;
        }
    }
    const fbrl_rapl_pos *pa = fbrl_link_last_pos(links[0]), *pb = fbrl_link_last_pos(links[1]);
    if (next[0] != len[0] || next[1] != len[1] || fbrl_link_busy(links[0]) || fbrl_link_busy(links[1])) {
        fprintf(stderr, "plans not finished\n");
        failures++;
    }
    if (fabs(pa->world[0] - 14) > 0.001 || fabs(pa->world[1] - 2) > 0.001 ||
        fabs(pa->world[2] - 10) > 0.001) {
        fprintf(stderr, "robot A at %.4f %.4f %.4f\n", pa->world[0], pa->world[1], pa->world[2]);
        failures++;
    }
    if (fabs(pb->joints[0] - 30) > 0.001 || fabs(pb->joints[1] - 90) > 0.001) {
        fprintf(stderr, "robot B joints %.4f %.4f\n", pb->joints[0], pb->joints[1]);
        failures++;
    }
    rig_stop(&ra);
    rig_stop(&rb);
    printf("two robots from one thread: %d polls with both busy, %s\n", overlap, failures ? "FAILED" : "ok");
    return failures ? 1 : 0;
}
