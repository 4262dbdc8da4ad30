/* SPDX-License-Identifier: MIT */
/* sim_defaults.c - the controller at power-up, before its state file is read:
 * the settings of every part for the arm model already chosen. The state file
 * (sim_state.c) calls it again when its MODEL line names another arm. */
#include "sim_internal.h"

#include <string.h>

/* GAIN's parameters as a lab's RAPL-II controller showed them (S11, docs/fbrlsim.md) */
static const double gain_default[SIM_GAIN_PARAMS] = {8.0, 0.25, 100.0};

void sim_defaults(fbrl_sim *s)
{
    int i;
    s->term.last_error = -1;
    s->arm.speed = 50.0;
    s->arm.power = 1;
    s->term.help = 1;
    s->dev.grip = SIM_GRIP_MAX;
    s->dev.grip_force = 50.0;
    for (i = 0; i <= sim_naxes(s); i++)
        memcpy(s->dev.gain[i], gain_default, sizeof s->dev.gain[i]);
    memcpy(s->arm.q, s->arm.model->ready, (size_t)sim_naxes(s) * sizeof *s->arm.q);
    memcpy(s->arm.qt, s->arm.q, sizeof s->arm.q);
    for (i = 0; i < 2; i++) {
        s->dev.chan[i].baud = 9600;
        s->dev.chan[i].parity = 'N';
        s->dev.chan[i].data = 8;
        s->dev.chan[i].stop = 1;
        s->dev.chan[i].handshake = i == 0 ? 'X' : 'N';
        s->dev.chan[i].echo = 1;
    }
}
