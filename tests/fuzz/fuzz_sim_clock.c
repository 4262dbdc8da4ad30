/* SPDX-License-Identifier: MIT */
/* fuzz_sim_clock.c - fbrlsim's clocks for the fuzz targets, in place of
 * sim/sim_clock.c: the monotonic clock is a number the harness moves forward
 * (fuzz_sim_advance), so no input waits on real time and every run of an input
 * is the same run. The two derived clocks keep sim_clock.c's definitions.
 * Each emulator starts the clock afresh: carried over from input to input it
 * grew so large that a step of 0.5 s was lost in rounding. */
#include "sim_internal.h"

#include "fuzz_sim.h"

#define FUZZ_CLOCK_START 1.0

static double fuzz_clock = FUZZ_CLOCK_START;

double sim_mono(void) { return fuzz_clock; }

double sim_real_now(const fbrl_sim *s) { return sim_mono() - s->t0; }

double sim_now(const fbrl_sim *s) { return (sim_mono() - s->t0) * s->opt.time_scale; }

void fuzz_sim_advance(double seconds)
{
    if (seconds > 0)
        fuzz_clock += seconds;
}

void fuzz_sim_clock_reset(void) { fuzz_clock = FUZZ_CLOCK_START; }
