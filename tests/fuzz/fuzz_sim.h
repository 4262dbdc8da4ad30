/* SPDX-License-Identifier: MIT */
/* fuzz_sim.h - what fbrlsim's fuzz targets share: an emulator without a
 * client (TCP listener only), driven on simulated time by the harness, files in
 * a private temporary directory, and the round trip "what it saves it loads". */
#ifndef FBRL_FUZZ_SIM_H
#define FBRL_FUZZ_SIM_H

#include <stddef.h>
#include <stdint.h>

#include "fuzz_util.h"
#include "sim_internal.h"

/* The harness's own clock (fuzz_sim_clock.c). */
void fuzz_sim_advance(double seconds);
/* Back to its start; only while no emulator exists (fuzz_sim_new does it). */
void fuzz_sim_clock_reset(void);

/* An emulator on a TCP listener nobody connects to, the control FIFO replaced by
 * a pipe the harness writes; model as --model (NULL: the state file's); NULL
 * with err set when fbrl_sim_create refuses. */
fbrl_sim *fuzz_sim_new(const char *state_path, const char *inputs_path, const char *model, char *err,
                       size_t errlen);
void fuzz_sim_free(fbrl_sim *s);

/* Bytes onto the serial line, then the emulator runs (simulated time moving on)
 * until it waits for the host, or a bounded number of slices. */
void fuzz_sim_type(fbrl_sim *s, const void *bytes, size_t n);
/* Bytes into the control FIFO, read as the event loop reads them. */
void fuzz_sim_control(fbrl_sim *s, const void *bytes, size_t n);
/* Runs the scripted control lines due up to `until` simulated seconds. */
void fuzz_sim_run_events(fbrl_sim *s, double until);

/* The state file fbrlsim wrote at path must load, and save again unchanged. */
void fuzz_sim_reload_check(const char *state_path);

#endif
