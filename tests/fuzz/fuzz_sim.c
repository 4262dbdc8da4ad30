/* SPDX-License-Identifier: MIT */
/* fuzz_sim.c - the harness fbrlsim's fuzz targets share (fuzz_sim.h).
 *
 * The emulator is created as fbrlsim creates it (fbrl_sim_create: options,
 * state file, --inputs file), on a TCP listener that no client ever reaches,
 * and then driven slice by slice as fbrl_sim_step drives it, without poll():
 * host bytes come from a pipe through the line's own reader, controller output
 * falls off the line (no client), and time is the harness's clock
 * (fuzz_sim_clock.c), moved forward a little more on each slice, so motions,
 * WAITs, readouts and scripted inputs all happen without real waiting. */
#include "fuzz_sim.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>

#define FUZZ_SLICES       300   /* event-loop slices at most per typed chunk */
#define FUZZ_DT_MIN       0.001 /* s: the first step of the clock while the controller works */
#define FUZZ_DT_MAX       30.0  /* s: the longest step (a slow motion ends in a few) */
#define FUZZ_STREAM_LINES 3     /* readout lines let out before the harness stops waiting */
#define FUZZ_EVENT_ROUNDS 8     /* settles per scripted line at most */

static int serial[2] = {-1, -1}; /* host -> controller */
static int control_w = -1;       /* write end of the control "FIFO" */

fbrl_sim *fuzz_sim_new(const char *state_path, const char *inputs_path, const char *model, char *err,
                       size_t errlen)
{
    fbrl_sim_options o;
    fbrl_sim *s = NULL;
    int ctl[2];
    fuzz_sim_clock_reset(); /* every input the same run, at full precision */
    fbrl_sim_options_init(&o);
    o.tcp_port = 0;
    o.state_path = state_path;
    o.inputs_path = inputs_path;
    o.model = model;
    err[0] = 0;
    if (fbrl_sim_create(&s, &o, err, errlen) != FBRL_OK) {
        if (!err[0])
            fuzz_fail("fbrl_sim_create failed without a message");
        return NULL;
    }
    if (pipe2(serial, O_NONBLOCK | O_CLOEXEC) != 0 || pipe2(ctl, O_NONBLOCK | O_CLOEXEC) != 0)
        fuzz_fail("pipe: %s", strerror(errno));
    s->events.ctl = ctl[0]; /* the emulator closes it, as it closes its FIFO */
    control_w = ctl[1];
    return s;
}

void fuzz_sim_free(fbrl_sim *s)
{
    fbrl_sim_destroy(s);
    if (serial[0] >= 0)
        close(serial[0]);
    if (serial[1] >= 0)
        close(serial[1]);
    if (control_w >= 0)
        close(control_w);
    serial[0] = serial[1] = control_w = -1;
}

static int serial_waiting(void)
{
    int n = 0;
    if (ioctl(serial[0], FIONREAD, &n) != 0)
        return 0;
    return n;
}

static int show_output(void)
{
    static int show = -1;
    if (show < 0) {
        const char *e = getenv("FBRL_FUZZ_SHOW");
        show = e && *e == '1';
    }
    return show;
}

/* One slice of fbrl_sim_step without the poll: read the host, do the work, write. */
static void slice(fbrl_sim *s)
{
    sim_line_read(s, serial[0], sim_real_now(s));
    sim_arm_update(s);
    sim_events_run(s);
    sim_line_deliver(s, sim_real_now(s));
    sim_term_process(s);
    if (show_output())
        sim_line_write(s, STDERR_FILENO, HUGE_VAL); /* FBRL_FUZZ_SHOW=1: what a client would read */
    sim_line_write(s, -1, sim_real_now(s));         /* no client: the output falls off the line */
}

/* The controller waits for the host: nothing typed is left, no motion runs. */
static int waiting_for_host(const fbrl_sim *s)
{
    return (s->term.ps == PS_IDLE || s->term.ps == PS_STREAM) && s->line.rxcount == 0 && s->line.wn == 0 &&
           serial_waiting() == 0 && !s->arm.moving && !s->arm.xmoving;
}

static void settle(fbrl_sim *s)
{
    double dt = FUZZ_DT_MIN;
    int i, stream = 0;
    for (i = 0; i < FUZZ_SLICES; i++) {
        slice(s);
        if (waiting_for_host(s) && (s->term.ps != PS_STREAM || ++stream > FUZZ_STREAM_LINES))
            return;
        fuzz_sim_advance(dt);
        if (dt < FUZZ_DT_MAX)
            dt *= 2;
    }
}

void fuzz_sim_type(fbrl_sim *s, const void *bytes, size_t n)
{
    const char *p = bytes;
    while (n > 0) {
        ssize_t w = write(serial[1], p, n);
        if (w < 0 && errno != EAGAIN)
            fuzz_fail("write: %s", strerror(errno));
        if (w > 0) {
            p += w;
            n -= (size_t)w;
        }
        settle(s);
        if (w <= 0 && serial_waiting() > 0)
            return; /* the controller stopped reading (blocked): the rest is never read */
    }
    settle(s);
}

void fuzz_sim_control(fbrl_sim *s, const void *bytes, size_t n)
{
    const char *p = bytes;
    while (n > 0) {
        ssize_t w = write(control_w, p, n);
        if (w <= 0)
            fuzz_fail("write: %s", strerror(errno));
        p += w;
        n -= (size_t)w;
        /* as fbrl_sim_step does on POLLIN: one read per wake-up */
        for (;;) {
            int left = 0;
            if (ioctl(s->events.ctl, FIONREAD, &left) != 0 || left == 0)
                break;
            sim_events_read_fifo(s);
        }
    }
    settle(s);
}

void fuzz_sim_run_events(fbrl_sim *s, double until)
{
    while (s->events.next < s->events.n) {
        int k = s->events.next, round;
        double t = s->events.list[k].t;
        if (t > until)
            break;
        for (round = 0; round < FUZZ_EVENT_ROUNDS && s->events.next == k; round++) {
            double now = sim_now(s);
            if (t > now)
                fuzz_sim_advance((t - now) / s->opt.time_scale * (1 + 1e-12) + 1e-9);
            settle(s);
        }
        if (s->events.next == k)
            fuzz_fail("scripted line %d at %g s did not run (simulated time %g s)", k, t, sim_now(s));
    }
}

void fuzz_sim_reload_check(const char *state_path)
{
    char err[512];
    size_t n1, n2;
    unsigned char *a = fuzz_read_file(state_path, &n1), *b;
    fbrl_sim *s;
    if (!a)
        fuzz_fail("fbrlsim saved no state at %s", state_path);
    s = fuzz_sim_new(state_path, NULL, NULL, err, sizeof err);
    if (!s)
        fuzz_fail("the state fbrlsim saved does not load: %s\n---\n%.*s---", err, (int)n1, (const char *)a);
    fuzz_sim_free(s);
    b = fuzz_read_file(state_path, &n2);
    if (!b || n1 != n2 || memcmp(a, b, n1) != 0)
        fuzz_fail("a saved state changes when loaded and saved again");
    free(a);
    free(b);
}
