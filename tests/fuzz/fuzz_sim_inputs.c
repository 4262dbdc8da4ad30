/* SPDX-License-Identifier: MIT */
/* fuzz_sim_inputs.c - fuzz target for fbrlsim's --inputs parser and the
 * control lines it schedules.
 *
 * The input is an --inputs file ("2.5 IN 3 1" lines), optionally followed by a
 * line "%%" and what a host types at time 0 (the scripted lines fire while it
 * runs, e.g. a WAIT for the input they set). A refused file must give a
 * message naming it; an accepted one runs to its last line (up to a simulated
 * FUZZ_INPUTS_HORIZON), and the state fbrlsim then saves must load again. */
#include "fuzz_sim.h"

#include <string.h>
#include <unistd.h>

#define FUZZ_INPUTS_HORIZON 1e6 /* simulated s: lines later than this never run in a test */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char inputs[512], state[512], err[512];
    const uint8_t *typed;
    size_t head, typed_n;
    fbrl_sim *s;

    fuzz_split(data, size, &head, &typed, &typed_n);
    fuzz_path(inputs, sizeof inputs, "inputs.txt");
    fuzz_path(state, sizeof state, "inputs.state");
    fuzz_write_file(inputs, data, head);
    unlink(state);
    s = fuzz_sim_new(state, inputs, NULL, err, sizeof err);
    if (!s) {
        if (strncmp(err, inputs, strlen(inputs)) != 0)
            fuzz_fail("the message does not name the file: %s", err);
        return 0;
    }
    if (typed_n)
        fuzz_sim_type(s, typed, typed_n);
    fuzz_sim_run_events(s, FUZZ_INPUTS_HORIZON);
    fuzz_sim_free(s);
    fuzz_sim_reload_check(state);
    return 0;
}
