/* SPDX-License-Identifier: MIT */
/* sim_core.c - fbrlsim's event loop: creates the parts (line, transport,
 * terminal, control lines, memory), runs one slice at a time and tears them
 * down. Each part lives in its own file; this one only wires them together. */
#include "sim_internal.h"

#include <errno.h>
#include <fcntl.h>
#include <locale.h>
#include <math.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif
#include <time.h>
#include <unistd.h>

#define LOOP_SLICE_MS 200 /* fbrl_sim_run's longest wait, so fbrl_sim_stop is seen soon */

static char *dupstr(const char *p)
{
    char *d;
    if (!p)
        return NULL;
    d = malloc(strlen(p) + 1);
    if (d)
        strcpy(d, p);
    return d;
}

void fbrl_sim_options_init(fbrl_sim_options *o)
{
    if (!o)
        return;
    memset(o, 0, sizeof *o);
    o->tcp_port = -1;
    o->time_scale = 1.0;
    o->rx_buffer = SIM_RX_DEFAULT;
}

fbrl_status fbrl_sim_create(fbrl_sim **out, const fbrl_sim_options *o, char *err, size_t errlen)
{
    fbrl_sim *s;
    if (!out || !o) {
        sim_seterr(err, errlen, "null argument");
        return FBRL_EINVAL;
    }
    *out = NULL;
    if (!(o->time_scale > 0) || !isfinite(o->time_scale) || o->baud < 0 || o->rx_buffer < 0 ||
        o->tcp_port > 65535 || !(o->cmd_time_ms >= 0) || o->cmd_time_ms > SIM_CMD_TIME_MAX_MS) {
        sim_seterr(err, errlen, "bad option value");
        return FBRL_EINVAL;
    }
    s = calloc(1, sizeof *s);
    if (!s)
        return FBRL_ENOMEM;
    s->opt = *o;
    s->io.master = s->io.slave = s->io.lfd = s->io.conn = s->io.fd = s->io.ino = s->events.ctl = -1;
    s->wake[0] = s->wake[1] = -1;
    s->state_path = dupstr(o->state_path);
    s->log_path = dupstr(o->log_path);
    s->control_path = dupstr(o->control_path);
    s->io.link_path = o->tcp_port < 0 ? dupstr(o->link_path) : NULL;
    s->opt.state_path = s->opt.log_path = s->opt.control_path = s->opt.link_path = NULL;
    s->opt.inputs_path = s->opt.faults = s->opt.control_out = NULL;
    s->arm.model = o->model ? fbrl_arm_find(o->model) : fbrl_arm_model(0);
    s->model_given = o->model != NULL;
    s->opt.model = NULL;
    if (!s->arm.model) {
        char names[64];
        fbrl_arm_names(names, sizeof names, '|');
        sim_seterr(err, errlen, "unknown arm model '%s' (%s)", o->model, names);
        free(s->state_path);
        s->state_path = NULL;
        fbrl_sim_destroy(s);
        return FBRL_EINVAL;
    }
    sim_defaults(s);
    if (sim_line_init(&s->line, o->baud, o->rx_buffer) != 0)
        goto fail_mem;
    if (o->faults && sim_line_faults(&s->line, o->faults, err, errlen) != 0)
        goto fail;
    if (s->state_path && sim_state_load(s, err, errlen) != 0)
        goto fail;
    if (o->baud > 0)
        s->dev.chan[0].baud = o->baud;
    if (o->parity) {
        if (o->parity != 'N' && o->parity != 'E' && o->parity != 'O') {
            sim_seterr(err, errlen, "parity must be N, E or O");
            goto fail;
        }
        s->dev.chan[0].parity = o->parity;
    }
    if (o->cell_path && sim_cell_load(s, o->cell_path, err, errlen) != 0)
        goto fail;
    if (o->inputs_path && sim_events_load(&s->events, o->inputs_path, err, errlen) != 0)
        goto fail;
    if (s->log_path && !(s->log = fopen(s->log_path, "ae"))) {
        sim_seterr(err, errlen, "%s: %s", s->log_path, strerror(errno));
        goto fail;
    }
    if (o->control_out && !(s->ctl_out = fopen(o->control_out, "ae"))) {
        sim_seterr(err, errlen, "%s: %s", o->control_out, strerror(errno));
        goto fail;
    }
    if (!s->ctl_out && o->control_out_stdout)
        s->ctl_out = stdout;
    s->term.aci = o->aci; /* a controller that powers up in ACI mode */
    if (pipe(s->wake) != 0) {
        sim_seterr(err, errlen, "pipe: %s", strerror(errno));
        goto fail;
    }
    fcntl(s->wake[0], F_SETFL, O_NONBLOCK);
    fcntl(s->wake[1], F_SETFL, O_NONBLOCK);
    if ((o->tcp_port >= 0 ? sim_io_open_tcp(&s->io, o->tcp_port, err, errlen)
                          : sim_io_open_pty(&s->io, o->greet_pty, err, errlen)) != 0)
        goto fail;
    if (s->control_path && sim_events_open_fifo(&s->events, s->control_path, err, errlen) != 0)
        goto fail;
    s->t0 = sim_mono();
    *out = s;
    return FBRL_OK;
fail_mem:
    sim_seterr(err, errlen, "out of memory");
fail:
    free(s->state_path); /* nothing was loaded into a file: do not write it back */
    s->state_path = NULL;
    fbrl_sim_destroy(s);
    return FBRL_EIO;
}

const char *fbrl_sim_path(const fbrl_sim *s) { return s ? s->io.path : ""; }

int fbrl_sim_axes(const fbrl_sim *s) { return s ? sim_naxes(s) : 0; }

const fbrl_arm *fbrl_sim_arm(const fbrl_sim *s) { return s ? s->arm.model : NULL; }

/* The client went away: what was on the line and half-typed is lost with it. */
static void client_gone(fbrl_sim *s)
{
    if (sim_io_close_client(&s->io)) {
        sim_line_reset(&s->line);
        sim_term_reset(&s->term);
    }
}

static void do_read(fbrl_sim *s, double now)
{
    int r = sim_line_read(s, s->io.fd, now);
    if (r != 0 && s->io.conn >= 0)
        client_gone(s);
}

static void do_write(fbrl_sim *s, double now)
{
    if (sim_line_write(s, s->io.fd, now) != 0 && s->io.conn >= 0)
        client_gone(s);
}

/* Real seconds until something is due, capped by limit. */
static double due_in(fbrl_sim *s, double limit)
{
    double r = limit, now = sim_real_now(s), t;
    if (s->arm.moving || s->arm.xmoving) {
        double end = s->arm.moving ? s->arm.mt1 : s->arm.xt1;
        if (s->arm.moving && s->arm.xmoving && s->arm.xt1 < end)
            end = s->arm.xt1;
        t = (end - sim_now(s)) / s->opt.time_scale;
        if (t < r)
            r = t;
    }
    r = sim_term_due(&s->term, &s->line, now, r);
    r = sim_events_due(s, r);
    r = sim_line_due(&s->line, now, r);
    return r < 0 ? 0 : r;
}

/* On a given clock with skip: a command waiting in the controller for the arm or a scripted
 * input makes the clock jump to when that comes (a dry run waits for nothing). */
static void skip_wait(fbrl_sim *s)
{
    double now, next = INFINITY;
    if (!s->opt.skip || !s->opt.clock || s->term.ps != PS_BUSY)
        return;
    now = sim_now(s);
    if (s->arm.moving)
        next = s->arm.mt1;
    if (s->arm.xmoving && s->arm.xt1 < next)
        next = s->arm.xt1;
    if (!isfinite(next)) {
        double r = sim_events_due(s, INFINITY);
        if (isfinite(r) && r > 0)
            next = now + r;
    }
    if (isfinite(next) && next > now)
        s->opt.skip(s->opt.clock_ctx, next - now);
}

static void work(fbrl_sim *s)
{
    double now = sim_real_now(s);
    skip_wait(s);
    sim_arm_update(s);
    sim_events_run(s);
    sim_line_hold_check(&s->line, s->io.fd, now, s->dev.chan[0].handshake == 'X',
                        s->line.byte_time > 0 ? sim_io_host_ixon(&s->io) : -1);
    sim_line_deliver(s, now);
    sim_term_process(s);
    do_write(s, sim_real_now(s));
}

fbrl_status fbrl_sim_step(fbrl_sim *s, int timeout_ms)
{
    struct pollfd p[5];
    struct timespec ts;
    int np = 0, iw, ictl = -1, iio = -1, ilfd = -1, iino = -1;
    double now, wait;

    if (!s)
        return FBRL_EINVAL;
    work(s);
    now = sim_real_now(s);
    wait = due_in(s, timeout_ms < 0 ? 1.0 : timeout_ms / 1000.0);
    ts.tv_sec = (time_t)wait;
    ts.tv_nsec = (long)((wait - (double)ts.tv_sec) * 1e9);
    iw = np;
    p[np].fd = s->wake[0];
    p[np++].events = POLLIN;
    if (s->events.ctl >= 0) {
        ictl = np;
        p[np].fd = s->events.ctl;
        p[np++].events = POLLIN;
    }
    if (s->io.lfd >= 0) {
        ilfd = np;
        p[np].fd = s->io.lfd;
        p[np++].events = POLLIN;
    }
    if (s->io.ino >= 0) {
        iino = np;
        p[np].fd = s->io.ino;
        p[np++].events = POLLIN;
    }
    if (s->io.fd >= 0) {
        short ev = 0;
        if (sim_line_rx_allow(&s->line, now) > 0)
            ev |= POLLIN;
        if (sim_line_wants_write(&s->line, now))
            ev |= POLLOUT;
        iio = np;
        p[np].fd = s->io.fd;
        p[np++].events = ev;
    }
    if (ppoll(p, (nfds_t)np, &ts, NULL) < 0) {
        if (errno == EINTR)
            return FBRL_OK;
        return FBRL_EIO;
    }
    now = sim_real_now(s);
    if (p[iw].revents & POLLIN) {
        char b[64];
        while (read(s->wake[0], b, sizeof b) > 0)
            ;
    }
    if (ictl >= 0 && (p[ictl].revents & POLLIN))
        sim_events_read_fifo(s);
    if (ilfd >= 0 && (p[ilfd].revents & POLLIN) && sim_io_accept(&s->io)) {
        /* A connection is an event the controller can see: greet it with the prompt,
         * so a user at nc or telnet knows the controller is there. */
        sim_term_greet(s);
    }
    if (iino >= 0 && (p[iino].revents & POLLIN) && sim_io_pty_opened(&s->io) > 0)
        sim_term_greet(s); /* before what the new client typed */
    if (iio >= 0 && s->io.fd >= 0 && (p[iio].revents & (POLLIN | POLLHUP | POLLERR)))
        do_read(s, now);
    work(s);
    return FBRL_OK;
}

static int stopping(fbrl_sim *s) { return __atomic_load_n(&s->stop, __ATOMIC_ACQUIRE); }

/* The line's byte clock is kept by ppoll timeouts, which Linux lets run late by the
 * thread's timer slack (50 us by default: more than half a byte time at 115200 baud).
 * The emulator's thread asks for none, so its bytes go out when they are due. */
static void sharp_timers(void)
{
#ifdef PR_SET_TIMERSLACK
    (void)prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
#endif
}

fbrl_status fbrl_sim_run(fbrl_sim *s)
{
    if (!s)
        return FBRL_EINVAL;
    sharp_timers();
    while (!stopping(s)) {
        fbrl_status st = fbrl_sim_step(s, LOOP_SLICE_MS);
        if (st != FBRL_OK)
            return st;
    }
    return FBRL_OK;
}

static void *thread_main(void *arg)
{
    /* RAPL replies and the state file are "C" text whatever locale the host process set
     * (a program embedding the emulator may call setlocale(LC_ALL, "")). */
    locale_t c = newlocale(LC_ALL_MASK, "C", (locale_t)0);
    if (c)
        uselocale(c);
    fbrl_sim_run(arg);
    if (c) {
        uselocale(LC_GLOBAL_LOCALE);
        freelocale(c);
    }
    return NULL;
}

fbrl_status fbrl_sim_start(fbrl_sim *s)
{
    if (!s || s->thread_started)
        return FBRL_EINVAL;
    if (pthread_create(&s->thread, NULL, thread_main, s) != 0)
        return FBRL_EIO;
    s->thread_started = 1;
    return FBRL_OK;
}

void fbrl_sim_stop(fbrl_sim *s)
{
    char b = 1;
    ssize_t r;
    if (!s)
        return;
    __atomic_store_n(&s->stop, 1, __ATOMIC_RELEASE);
    r = write(s->wake[1], &b, 1);
    (void)r;
}

void fbrl_sim_destroy(fbrl_sim *s)
{
    if (!s)
        return;
    if (s->thread_started) {
        fbrl_sim_stop(s);
        pthread_join(s->thread, NULL);
        s->thread_started = 0;
    }
    if (s->state_path) {
        sim_arm_update(s);
        sim_state_save(s);
    }
    sim_io_close(&s->io);
    sim_events_free(&s->events);
    if (s->wake[0] >= 0)
        close(s->wake[0]);
    if (s->wake[1] >= 0)
        close(s->wake[1]);
    if (s->log)
        fclose(s->log);
    if (s->ctl_out && s->ctl_out != stdout)
        fclose(s->ctl_out);
    sim_free_memory(s);
    free(s->term.out.buf);
    sim_line_free(&s->line);
    free(s->state_path);
    free(s->log_path);
    free(s->cell_obj);
    free(s->control_path);
    free(s);
}
