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
#include <stdarg.h>
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

void sim_control_say(fbrl_sim *s, const char *fmt, ...)
{
    va_list ap;
    if (!s || !s->ctl_out)
        return;
    va_start(ap, fmt);
    vfprintf(s->ctl_out, fmt, ap);
    va_end(ap);
    fputc('\n', s->ctl_out);
    fflush(s->ctl_out);
}

/* Why a line was refused: the first thing wrong with it. */
static int refuse(char *why, size_t n, const char *fmt, const char *arg)
{
    if (why && n)
        snprintf(why, n, fmt, arg);
    return -1;
}

/* GET item: a look inside the controller, answered on the control output. */
static int query(fbrl_sim *s, const char *item, char *why, size_t whylen)
{
    static const char *const items[] = {"POSITION", "OUTPUTS", "INPUTS", "ERROR", "MOTION", "LINE"};
    size_t k;
    int i;
    for (k = 0; k < sizeof items / sizeof items[0]; k++)
        if (!strcmp(item, items[k]))
            break;
    if (k == sizeof items / sizeof items[0])
        return refuse(why, whylen, "GET: unknown item '%s' (POSITION, OUTPUTS, INPUTS, ERROR, MOTION, LINE)",
                      item);
    if (!s)
        return 0;
    sim_arm_update(s);
    if (k == 0) {
        double q[FBRL_ARM_AXES_MAX], pose[6];
        char b[256];
        size_t n = 0;
        sim_joints_now(s, q);
        fbrl_arm_fk(s->arm.model, q, sim_tool_len(s), pose);
        n += (size_t)snprintf(b + n, sizeof b - n, "POSITION JOINTS");
        for (i = 0; i < sim_naxes(s); i++)
            n += (size_t)snprintf(b + n, sizeof b - n, " %+.4f", q[i] + 0.0);
        n += (size_t)snprintf(b + n, sizeof b - n, " WORLD");
        for (i = 0; i < 6; i++) /* inches, like every control line, whatever METRIC says */
            n += (size_t)snprintf(b + n, sizeof b - n, " %+.4f", pose[i] + 0.0);
        sim_control_say(s, "%s", b);
    } else if (k == 1 || k == 2) {
        char bits[SIM_IO + 1];
        for (i = 0; i < SIM_IO; i++)
            bits[i] = (char)('0' + (k == 1 ? s->dev.out_[i] : s->dev.in[i]));
        bits[SIM_IO] = 0;
        sim_control_say(s, "%s %s", items[k], bits);
    } else if (k == 3) {
        if (s->term.last_error < 0)
            sim_control_say(s, "ERROR NONE");
        else
            sim_control_say(s, "ERROR %03d-%s.", s->term.last_error, sim_error_text(s->term.last_error));
    } else if (k == 5) {
        sim_control_say(s, "LINE OVERRUNS %ld IGNORED-XOFF %ld PARITY-IN %ld PARITY-OUT %ld",
                        s->line.overruns, s->line.ignored_xoff, s->line.parity_in, s->line.parity_out);
    } else {
        static const char *const cmd[] = {"IDLE", "BUSY", "STREAMING", "READING"}; /* by PS_* */
        sim_control_say(s, "MOTION %s EXTRA %s POWER %s HOMED %s COMMAND %s",
                        s->arm.moving ? "MOVING" : "STOPPED", s->arm.xmoving ? "MOVING" : "STOPPED",
                        s->arm.power ? "ON" : "OFF", s->arm.homed ? "YES" : "NO", cmd[s->term.ps]);
    }
    return 0;
}

int sim_control(fbrl_sim *s, const char *line) { return sim_control_why(s, line, NULL, 0); }

int sim_control_why(fbrl_sim *s, const char *line, char *why, size_t whylen)
{
    char w[CTL_WORDS][CTL_WORD_MAX];
    long i1, i2;
    double x;
    int n = ctl_split(line, w);
    if (n < 0)
        return refuse(why, whylen, "%stoo many words or a word too long", "");
    if (n < 1)
        return refuse(why, whylen, "%sempty line", "");
    if (!strcmp(w[0], "GET")) {
        if (n != 2)
            return refuse(why, whylen, "%sGET takes one item", "");
        return query(s, w[1], why, whylen);
    }
    if (!strcmp(w[0], "IN")) {
        if (n != 3)
            return refuse(why, whylen, "%sIN takes an input and 0 or 1", "");
        if (ctl_int(w[1], 1, SIM_IO, &i1))
            return refuse(why, whylen, "IN: input '%s' is not a whole number 1-16", w[1]);
        if (ctl_int(w[2], 0, 1, &i2))
            return refuse(why, whylen, "IN: value '%s' is not 0 or 1", w[2]);
        if (s)
            s->dev.in[i1 - 1] = (int)i2;
        return 0;
    }
    if (!strcmp(w[0], "AIN")) {
        if (n != 3)
            return refuse(why, whylen, "%sAIN takes a channel and volts", "");
        if (ctl_int(w[1], 1, SIM_AIN, &i1))
            return refuse(why, whylen, "AIN: channel '%s' is not a whole number 1-8", w[1]);
        if (ctl_real(w[2], -AIN_VOLTS_MAX, AIN_VOLTS_MAX, &x))
            return refuse(why, whylen, "AIN: '%s' is not a decimal number of volts in -10..10", w[2]);
        if (s)
            s->dev.ain[i1 - 1] = x;
        return 0;
    }
    if (!strcmp(w[0], "POWER")) {
        if (n != 2 || ctl_int(w[1], 0, 1, &i1))
            return refuse(why, whylen, "%sPOWER takes 0 or 1", "");
        if (s) {
            if (!i1)
                sim_halt(s);
            s->arm.power = (int)i1;
        }
        return 0;
    }
    if (!strcmp(w[0], "OBJECT")) {
        if (n != 2 || ctl_real(w[1], 0, SIM_GRIP_MAX, &x))
            return refuse(why, whylen, "%sOBJECT takes a width in inches, 0..2", "");
        if (s)
            s->dev.object = x;
        return 0;
    }
    if (!strcmp(w[0], "TEACH") && n == 1) {
        if (s && s->mem.teach && s->mem.teach_next <= 999) {
            char name[32];
            double q[FBRL_ARM_AXES_MAX];
            sim_loc *l;
            int i;
            snprintf(name, sizeof name, "%.5s%03d", s->mem.teach_name, s->mem.teach_next);
            if (sim_loc_new(s, name, s->mem.teach == 2, &l) == 0) {
                sim_joints_now(s, q);
                if (s->mem.teach == 2)
                    for (i = 0; i < sim_naxes(s); i++)
                        l->p[i] = fbrl_arm_pulses(s->arm.model, i, q[i]);
                else
                    fbrl_arm_fk(s->arm.model, q, sim_tool_len(s), l->v);
                s->mem.teach_next++;
                if (s->state_path)
                    sim_state_save(s);
                s->dirty = 0;
            }
        }
        return 0;
    }
    if (!strcmp(w[0], "TEACH"))
        return refuse(why, whylen, "%sTEACH takes nothing after it", "");
    return refuse(why, whylen, "unknown control word '%s' (IN, AIN, POWER, OBJECT, TEACH, GET)", w[0]);
}
