/* SPDX-License-Identifier: MIT */
/* sim_clock.c - the emulator's two clocks: real seconds since start (the line,
 * replies) and simulated seconds (the arm, scripted inputs), which run
 * --time-scale times faster. */
#include "sim_internal.h"

#include <time.h>

double sim_mono(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

double sim_real_now(const fbrl_sim *s) { return sim_mono() - s->t0; }

double sim_now(const fbrl_sim *s)
{
    if (s->opt.clock)
        return s->opt.clock(s->opt.clock_ctx) - s->clock_back;
    return (sim_mono() - s->t0) * s->opt.time_scale;
}
