/* SPDX-License-Identifier: MIT */
/* fuzz_sim_state.c - fuzz target for fbrlsim's state file loader.
 *
 * The input is a state file, optionally followed by a line "%%" and what a
 * host then types (as in fuzz_sim_cmd.c, without control lines). A file the
 * loader refuses must give a message and stay as it was (a refused file is
 * never written back). A file it accepts is used: the typed part, or else
 * "RUN name" for each of its programs; then fbrlsim saves, and the saved state
 * must load and save again unchanged. */
#include "fuzz_sim.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char state[512], err[512];
    const uint8_t *typed;
    size_t head, typed_n, n;
    unsigned char *after;
    fbrl_sim *s;

    fuzz_split(data, size, &head, &typed, &typed_n);
    fuzz_path(state, sizeof state, "state.state");
    fuzz_write_file(state, data, head);
    s = fuzz_sim_new(state, NULL, NULL, err, sizeof err);
    if (!s) {
        after = fuzz_read_file(state, &n);
        if (!after || n != head || (head && memcmp(after, data, head) != 0))
            fuzz_fail("a refused state file was changed (%s)", err);
        if (strncmp(err, state, strlen(state)) != 0)
            fuzz_fail("the message does not name the file: %s", err);
        free(after);
        return 0;
    }
    if (typed_n) {
        fuzz_sim_type(s, typed, typed_n);
    } else {
        int i;
        for (i = 0; i < s->mem.nprogs; i++) {
            char line[SIM_NAME_MAX + 8];
            snprintf(line, sizeof line, "RUN %s\r", s->mem.progs[i].name);
            fuzz_sim_type(s, line, strlen(line));
        }
    }
    fuzz_sim_free(s);
    fuzz_sim_reload_check(state);
    return 0;
}
