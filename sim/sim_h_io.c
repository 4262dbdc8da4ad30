/* SPDX-License-Identifier: MIT */
/* sim_h_io.c - the commands for everything around the arm that is not motion:
 * the gripper, digital outputs and WAIT on inputs, text output (TYPE, TYPEI,
 * TYPEV), the serial channels (CONFIG, SERIAL), motor gains and the modes of the
 * pendant and terminal (FLASH, MANUAL, HELP). */
#include "sim_cmd.h"

#include <math.h>
#include <string.h>

static int force_arg(fbrl_sim *s, args *a, int i)
{
    double f;
    int e;
    if (i >= a->n)
        return 0;
    if ((e = sim_arg_num(s, a, i, &f)))
        return e;
    if (f > 100.0)
        return SIM_E_ARG_TOO_BIG;
    if (f < 1.0)
        return SIM_E_ILLEGAL_ARG;
    s->dev.grip_force = f;
    return 0;
}

/* Moves the gripper towards d; an object between the fingers stops it. */
static void grip_to(fbrl_sim *s, double d)
{
    if (s->dev.object > 0 && d < s->dev.object && s->dev.grip >= s->dev.object)
        d = s->dev.object;
    s->dev.grip = d;
    s->dirty = 1;
}

/* OPEN and CLOSE [force]: the gripper fully open or closed. */
static int open_close(fbrl_sim *s, args *a, double d)
{
    int e = sim_args_want(a, 0, 1);
    if (e || (e = force_arg(s, a, 0)))
        return e;
    grip_to(s, d);
    return 0;
}

int sim_h_open(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return open_close(s, a, SIM_GRIP_MAX);
}

int sim_h_close(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return open_close(s, a, 0.0);
}

int sim_h_grip(fbrl_sim *s, args *a, int *b)
{
    double d;
    int e = sim_args_want(a, 1, 2);
    (void)b;
    if (e || (e = sim_arg_len(s, a, 0, &d)))
        return e;
    if (d > SIM_GRIP_MAX + 1e-9)
        return SIM_E_ARG_TOO_BIG;
    if (d < 0)
        return SIM_E_ILLEGAL_ARG;
    if ((e = force_arg(s, a, 1)))
        return e;
    grip_to(s, d);
    return 0;
}

int sim_h_manual(fbrl_sim *s, args *a, int *b)
{
    int e = sim_args_want(a, 0, 1);
    (void)b;
    if (e)
        return e;
    if (a->n && strcmp(a->v[0], "JOI") && strcmp(a->v[0], "CYL"))
        return SIM_E_ILLEGAL_ARG;
    s->dev.manual = 1;
    return 0;
}

int sim_h_nomanual(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return sim_arg_mode(a, &s->dev.manual, 0);
}

int sim_h_flash(fbrl_sim *s, args *a, int *b)
{
    double v;
    int e = sim_args_want(a, 0, 1);
    (void)b;
    if (e || (a->n && (e = sim_arg_num(s, a, 0, &v))))
        return e;
    if (a->n && v < 0)
        return SIM_E_ILLEGAL_ARG;
    s->dev.flash = 1;
    s->dirty = 1;
    return 0;
}

int sim_h_noflash(fbrl_sim *s, args *a, int *b)
{
    int e = sim_args_want(a, 0, 0);
    (void)b;
    if (!e) {
        s->dev.flash = 0;
        s->dirty = 1;
    }
    return e;
}

int sim_h_nohelp(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return sim_arg_mode(a, &s->term.help, 0);
}

int sim_h_help(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return sim_arg_mode(a, &s->term.help, 1);
}

int sim_h_type(fbrl_sim *s, args *a, int *b)
{
    const char *r = a->rest;
    size_t n;
    (void)b;
    while (*r == ' ')
        r++;
    n = strlen(r);
    while (n && r[n - 1] == ' ')
        n--;
    if (n >= 2 && r[0] == '"' && r[n - 1] == '"') {
        r++;
        n -= 2;
    }
    sim_out_printf(&s->term.out, "%.*s\r\n", (int)n, r);
    return 0;
}

int sim_h_typei(fbrl_sim *s, args *a, int *b)
{
    double v;
    int e;
    (void)b;
    if (!a->n)
        return SIM_E_ARG_MISSING;
    if ((e = sim_eval(s, a->rest, &v)))
        return e;
    if (fabs(v) > 9.2e18)
        return SIM_E_ARG_TOO_BIG;
    sim_out_printf(&s->term.out, "%ld\r\n", lround(v));
    return 0;
}

int sim_h_typev(fbrl_sim *s, args *a, int *b)
{
    double v;
    int e;
    (void)b;
    if (!a->n)
        return SIM_E_ARG_MISSING;
    if ((e = sim_eval(s, a->rest, &v)))
        return e;
    sim_out_printf(&s->term.out, "%+.6f\r\n", v);
    return 0;
}

/* OUTPUT and WAIT: "[-]n,..." -> n (1..16) and on/off. */
static int io_item(fbrl_sim *s, const char *tok, int *n, int *on)
{
    double v;
    int e;
    *on = *tok != '-';
    if (*tok == '-' || *tok == '+')
        tok++;
    if ((e = sim_eval(s, tok, &v)))
        return e;
    if (lround(v) < 1 || lround(v) > SIM_IO)
        return SIM_E_IO_ADDRESS;
    *n = (int)lround(v);
    return 0;
}

int sim_h_output(fbrl_sim *s, args *a, int *b)
{
    int i, n, on, e;
    (void)b;
    if (!a->n)
        return SIM_E_ARG_MISSING;
    for (i = 0; i < a->n; i++)
        if ((e = io_item(s, a->v[i], &n, &on)))
            return e;
    for (i = 0; i < a->n; i++) {
        io_item(s, a->v[i], &n, &on);
        s->dev.out_[n - 1] = on;
    }
    s->dirty = 1;
    return 0;
}

int sim_h_wait(fbrl_sim *s, args *a, int *b)
{
    int i, n, on, e;
    if (!a->n)
        return SIM_E_ARG_MISSING;
    for (i = 0; i < a->n; i++) {
        if ((e = io_item(s, a->v[i], &n, &on)))
            return e;
        if (s->dev.in[n - 1] != on)
            *b = 1;
    }
    return 0;
}

static int word_is(const char *w, const char *a, const char *b) { return !strcmp(w, a) || !strcmp(w, b); }

int sim_h_config(fbrl_sim *s, args *a, int *b)
{
    static const long bauds[] = {300, 600, 1200, 2400, 4800, 9600, 19200, 38400};
    sim_chan c;
    long dev, baud, data, stop;
    const char *w;
    int e = sim_args_want(a, 7, 7), ok = 0;
    size_t i;
    (void)b;
    if (e || (e = sim_arg_int(s, a, 0, &dev)))
        return e;
    if (dev != 0 && dev != 1)
        return SIM_E_ILLEGAL_CHANNEL;
    if ((e = sim_arg_int(s, a, 1, &baud)) || (e = sim_arg_int(s, a, 3, &data)) ||
        (e = sim_arg_int(s, a, 4, &stop)))
        return e;
    for (i = 0; i < sizeof bauds / sizeof bauds[0]; i++)
        ok |= bauds[i] == baud;
    if (!ok || (data != 7 && data != 8) || (stop != 1 && stop != 2))
        return SIM_E_ILLEGAL_ARG;
    c.baud = baud;
    c.data = (int)data;
    c.stop = (int)stop;
    w = a->v[2];
    if (word_is(w, "N", "NONE"))
        c.parity = 'N';
    else if (word_is(w, "E", "EVEN"))
        c.parity = 'E';
    else if (word_is(w, "O", "ODD"))
        c.parity = 'O';
    else
        return SIM_E_ILLEGAL_ARG;
    w = a->v[5];
    if (word_is(w, "N", "NONE"))
        c.handshake = 'N';
    else if (word_is(w, "X", "XON"))
        c.handshake = 'X';
    else
        return SIM_E_ILLEGAL_ARG;
    w = a->v[6];
    if (word_is(w, "1", "ON"))
        c.echo = 1;
    else if (word_is(w, "0", "OFF"))
        c.echo = 0;
    else
        return SIM_E_ILLEGAL_ARG;
    s->dev.chan[dev] = c;
    s->dirty = 1;
    return 0;
}

int sim_h_serial(fbrl_sim *s, args *a, int *b)
{
    int e = sim_args_want(a, 0, 0), i;
    (void)b;
    if (e)
        return e;
    for (i = 0; i < 2; i++) {
        const sim_chan *c = &s->dev.chan[i];
        sim_out_printf(&s->term.out,
                       "CHANNEL %d: BAUD %ld PARITY %c DATA %d STOP %d HANDSHAKE %c ECHO %d\r\n", i, c->baud,
                       c->parity, c->data, c->stop, c->handshake, c->echo);
    }
    return 0;
}

static void print_gain(fbrl_sim *s, int m)
{
    const double *g = s->dev.gain[m];
    sim_out_printf(&s->term.out, "GAIN MOTOR %d: %+.4f,%+.4f,%+.4f\r\n", m, g[0], g[1], g[2]);
}

/* GAIN m[,p[,i,d]] [S1 /150: "a motor number of 0 will set all motors"; the three values
 * as a lab set them, GAIN 0,5,.25,100 (S11)]: m alone shows motor m (0: every motor);
 * one value sets the first parameter, three set all three [D: the layout shown]. */
int sim_h_gain(fbrl_sim *s, args *a, int *b)
{
    long m;
    double v[SIM_GAIN_PARAMS];
    int e = sim_args_want(a, 1, 1 + SIM_GAIN_PARAMS), i, k;
    (void)b;
    if (e || (e = sim_arg_int(s, a, 0, &m)))
        return e;
    if (m < 0 || m > sim_naxes(s))
        return SIM_E_BAD_AXIS;
    if (a->n == 1) {
        for (i = 1; i <= sim_naxes(s); i++)
            if (m == 0 || m == i)
                print_gain(s, i);
        return 0;
    }
    if (a->n != 2 && a->n != 1 + SIM_GAIN_PARAMS)
        return SIM_E_ARG_MISSING; /* GAIN m,p,i: d is missing */
    for (k = 0; k + 1 < a->n; k++) {
        if ((e = sim_arg_num(s, a, k + 1, &v[k])))
            return e;
        if (v[k] < 0)
            return SIM_E_ILLEGAL_ARG;
    }
    for (i = 1; i <= sim_naxes(s); i++)
        if (m == 0 || m == i)
            memcpy(s->dev.gain[i], v, (size_t)(a->n - 1) * sizeof v[0]);
    s->dirty = 1;
    return 0;
}

/* METRIC / NOMETRIC [D: the RAPL-II word is not known]: lengths typed and shown in
 * mm / inches; STATUS's last line says which; kept in the state file. */
static int h_units(fbrl_sim *s, args *a, int metric)
{
    int e = sim_args_want(a, 0, 0);
    if (e)
        return e;
    if (s->dev.metric != metric)
        s->dirty = 1;
    s->dev.metric = metric;
    return 0;
}

int sim_h_metric(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return h_units(s, a, 1);
}

int sim_h_nometric(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return h_units(s, a, 0);
}
