/* SPDX-License-Identifier: MIT */
/* fuzz_sim_cmd.c - fuzz target for fbrlsim's command line and control lines.
 *
 * The input is what a host types, line by line ('\n' ends a chunk; CR, BS,
 * Ctrl-X, XON/XOFF and any other byte inside a chunk go to the controller as
 * they are); a chunk that starts with '@' is a control line written to the
 * control FIFO instead ("@IN 3 1"). A first line "@MODEL a465" picks the arm
 * (--model) instead of the default A255. After each chunk the emulator runs on
 * simulated time until it waits for the host. The state file lives in a private
 * temporary directory; at the end fbrlsim saves it, and what it saved must load
 * and save again unchanged (issue 20: a lower-case name once made fbrlsim save
 * a state it refused to load). ASan and UBSan catch the rest. */
#include "fuzz_sim.h"

#include <string.h>
#include <unistd.h>

#define MODEL_LINE     "@MODEL "
#define MODEL_NAME_MAX 15

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char state[512], err[512], model[MODEL_NAME_MAX + 1] = "";
    fbrl_sim *s;
    size_t i = 0;

    fuzz_path(state, sizeof state, "cmd.state");
    unlink(state);
    if (size > sizeof MODEL_LINE - 1 && !memcmp(data, MODEL_LINE, sizeof MODEL_LINE - 1)) {
        const uint8_t *nl = memchr(data, '\n', size);
        size_t n = (nl ? (size_t)(nl - data) : size) - (sizeof MODEL_LINE - 1);
        if (n > MODEL_NAME_MAX)
            return 0;
        memcpy(model, data + sizeof MODEL_LINE - 1, n);
        model[n] = 0;
        i = nl ? (size_t)(nl - data) + 1 : size;
    }
    s = fuzz_sim_new(state, NULL, model[0] ? model : NULL, err, sizeof err);
    if (!s) {
        if (model[0])
            return 0; /* not a model fbrlsim knows: refused, as --model refuses it */
        fuzz_fail("fbrl_sim_create: %s", err);
    }
    while (i < size) {
        const uint8_t *nl = memchr(data + i, '\n', size - i);
        size_t end = nl ? (size_t)(nl - data) + 1 : size;
        if (data[i] == '@') {
            fuzz_sim_control(s, data + i + 1, end - i - 1);
            if (!nl)
                fuzz_sim_control(s, "\n", 1);
        } else {
            fuzz_sim_type(s, data + i, end - i);
        }
        i = end;
    }
    fuzz_sim_free(s);
    fuzz_sim_reload_check(state);
    return 0;
}
