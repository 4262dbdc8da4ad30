/* SPDX-License-Identifier: MIT */
/* sim_control.c - control lines: the world outside the serial line (inputs,
 * analog inputs, the arm power switch, an object in the gripper, the teach
 * pendant's button), from the --control FIFO or the --inputs script.
 *
 * A control line is strict, like the state file: exactly its words, channels
 * and switch values as whole decimal numbers, volts and widths as finite
 * decimal numbers, each in range, nothing after them ("IN 3 1 junk", "IN 3.5 1",
 * "AIN 1 nan" and "IN 0x3 1" are refused). */
#include "sim_cmd.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CTL_WORDS     3 /* the longest control line: keyword and two values */
#define CTL_WORD_MAX  32
#define AIN_VOLTS_MAX 10.0 /* an A/D channel reads -10..+10 V */

/* Splits on spaces and tabs; the number of words, or -1 when there are too many or one is too long. */
static int ctl_split(const char *line, char w[CTL_WORDS][CTL_WORD_MAX])
{
    int n = 0;
    for (;;) {
        size_t len;
        line += strspn(line, " \t");
        if (!*line)
            return n;
        len = strcspn(line, " \t");
        if (n == CTL_WORDS || len >= CTL_WORD_MAX)
            return -1;
        memcpy(w[n], line, len);
        w[n++][len] = 0;
        line += len;
    }
}

/* A whole decimal number (optional sign) in lo..hi. */
static int ctl_int(const char *t, long lo, long hi, long *v)
{
    const char *d = t + (*t == '+' || *t == '-');
    char *end;
    if (!*d || strspn(d, "0123456789") != strlen(d))
        return -1;
    errno = 0;
    *v = strtol(t, &end, 10);
    return *end || errno == ERANGE || *v < lo || *v > hi ? -1 : 0;
}

/* A finite decimal number (no hex, nan or inf) in lo..hi. */
static int ctl_real(const char *t, double lo, double hi, double *v)
{
    char *end;
    if (!*t || strspn(t, "0123456789+-.eE") != strlen(t))
        return -1;
    errno = 0;
    *v = strtod(t, &end);
    return end == t || *end || errno == ERANGE || !isfinite(*v) || *v < lo || *v > hi ? -1 : 0;
}

int sim_control(fbrl_sim *s, const char *line)
{
    char w[CTL_WORDS][CTL_WORD_MAX];
    long i1, i2;
    double x;
    int n = ctl_split(line, w);
    if (n < 1)
        return -1;
    if (!strcmp(w[0], "IN") && n == 3 && !ctl_int(w[1], 1, SIM_IO, &i1) && !ctl_int(w[2], 0, 1, &i2)) {
        if (s)
            s->dev.in[i1 - 1] = (int)i2;
        return 0;
    }
    if (!strcmp(w[0], "AIN") && n == 3 && !ctl_int(w[1], 1, SIM_AIN, &i1) &&
        !ctl_real(w[2], -AIN_VOLTS_MAX, AIN_VOLTS_MAX, &x)) {
        if (s)
            s->dev.ain[i1 - 1] = x;
        return 0;
    }
    if (!strcmp(w[0], "POWER") && n == 2 && !ctl_int(w[1], 0, 1, &i1)) {
        if (s) {
            if (!i1)
                sim_halt(s);
            s->arm.power = (int)i1;
        }
        return 0;
    }
    if (!strcmp(w[0], "OBJECT") && n == 2 && !ctl_real(w[1], 0, SIM_GRIP_MAX, &x)) {
        if (s)
            s->dev.object = x;
        return 0;
    }
    if (!strcmp(w[0], "TEACH") && n == 1) {
        if (s && s->mem.teach && s->mem.teach_next <= 999) {
            char name[32];
            double q[FBRL_SIM_ARM_MAX_AXES];
            sim_loc *l;
            int i;
            snprintf(name, sizeof name, "%.5s%03d", s->mem.teach_name, s->mem.teach_next);
            if (sim_loc_new(s, name, s->mem.teach == 2, &l) == 0) {
                sim_joints_now(s, q);
                if (s->mem.teach == 2)
                    for (i = 0; i < sim_naxes(s); i++)
                        l->p[i] = fbrl_sim_arm_pulses(s->arm.model, i, q[i]);
                else
                    fbrl_sim_arm_fk(s->arm.model, q, sim_tool_len(s), l->v);
                s->mem.teach_next++;
                if (s->state_path)
                    sim_state_save(s);
                s->dirty = 0;
            }
        }
        return 0;
    }
    return -1;
}
