/* SPDX-License-Identifier: MIT */
/* robot_io.c - peripherals by name, as the thesis asked for instead of RAPL's numbered
 * OUTPUT bits (3.4), and the real-time clock for timed reaction steps.
 *
 *   5 OUTPUT-DEVICE VACUUM-VALVE   3 INPUT-DEVICE TUBE-SENSOR
 *   VACUUM-VALVE ON   500 VACUUM-VALVE PULSE   2E0 PUMP DISPENSE
 *   TUBE-SENSOR TRUE 3000 WAIT-INPUT ( flag )   START-TIMER ... 60000 WAIT-UNTIL
 *
 * Outputs are switched with the controller's OUTPUT command, inputs read with
 * TYPEI SIG(n). Every wait is bounded: WAIT-INPUT polls the input and gives up at its
 * timeout, so a sensor that never answers cannot hang a plan. Time comes from the VM
 * host's clock (now_us, sleep_ms). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "robot_internal.h"

/* A device word's data: this magic, then its port number (the table in the robot is what
 * counts; the data only marks the word as a device). */
static const fbrl_vmx_type device_type = {"device", (fbrl_cell)0x44455643 /* "DEVC" */};
#define DEFAULT_PULSE_MS 100u
#define POLL_MS          20u
#define EDGE_POLL_MS     5u        /* INPUT-EDGE, under ONSIG: well inside a 20 ms reaction */
#define MAX_WAIT_MS      86400000L /* one day */

static fbrl_robot_device *device_at(const fbrl_robot *r, fbrl_cell addr)
{
    for (size_t k = 0; k < FBRL_ROBOT_MAX_DEVICES; k++) {
        fbrl_robot_device *d = (fbrl_robot_device *)&r->dev[k];
        if (d->addr && d->addr == addr && fbrl_vmx_data(r->vm, addr, &device_type, sizeof(fbrl_cell)))
            return d;
    }
    return NULL;
}

static fbrl_status device(fbrl_robot *r, const rb_word *w, fbrl_cell addr, int output,
                          fbrl_robot_device **out)
{
    char msg[96];
    fbrl_robot_device *d = device_at(r, addr);
    if (!d) {
        snprintf(msg, sizeof msg, "%s: not a device (use an OUTPUT-DEVICE or INPUT-DEVICE name)", w->name);
        return rb_fail(r, FBRL_THROW_BAD_NUMBER, msg);
    }
    if (output >= 0 && d->output != output) {
        snprintf(msg, sizeof msg, "%s: that is an %s device (port %d)", w->name,
                 d->output ? "output" : "input", d->port);
        return rb_fail(r, FBRL_THROW_BAD_NUMBER, msg);
    }
    *out = d;
    return FBRL_OK;
}

/* A new device word (name NULL: parsed from the input) in a free slot of the table. */
static fbrl_status make_device(fbrl_robot *r, const char *name, size_t len, int port, int output,
                               uint32_t pulse_ms)
{
    size_t k;
    fbrl_cell addr, cell = port;
    void *p;
    for (k = 0; k < FBRL_ROBOT_MAX_DEVICES && device_at(r, r->dev[k].addr); k++)
        ;
    if (k == FBRL_ROBOT_MAX_DEVICES)
        return FBRL_EFULL;
    fbrl_status st = fbrl_vmx_create(r->vm, name, len, &device_type, sizeof(fbrl_cell), NULL, NULL,
                                     FBRL_DOC_TEXT("( -- dev )"),
                                     FBRL_DOC_TEXT(output ? "output device" : "input device"), &addr, &p);
    if (st != FBRL_OK)
        return st;
    memcpy(p, &cell, sizeof cell);
    for (size_t j = 0; j < FBRL_ROBOT_MAX_DEVICES;
         j++) /* an entry left by forgotten words (fbrl_vmx_forget) */
        if (r->dev[j].addr == addr)
            r->dev[j].addr = 0;
    r->dev[k].addr = addr;
    r->dev[k].port = port;
    r->dev[k].output = output;
    r->dev[k].pulse_ms = pulse_ms;
    return FBRL_OK;
}

fbrl_status fbrl_robot_device_of(const fbrl_robot *r, fbrl_cell xt, fbrl_robot_device *d)
{
    fbrl_cell addr;
    const void *tag;
    if (!r || !r->vm || !d)
        return FBRL_EINVAL;
    const fbrl_robot_device *dev =
        fbrl_vmx_tag(r->vm, xt, &tag, &addr) == FBRL_OK ? device_at(r, addr) : NULL;
    if (!dev)
        return FBRL_ENOENT;
    *d = *dev;
    return FBRL_OK;
}

fbrl_status fbrl_robot_define_device(fbrl_robot *r, const char *name, size_t len, int port, int output,
                                     uint32_t pulse_ms)
{
    fbrl_cell xt, cell = port;
    fbrl_robot_device old;
    if (!r || !r->vm || !name)
        return FBRL_EINVAL;
    if (port < 1 || port > FBRL_ROBOT_IO_MAX || pulse_ms < FBRL_ROBOT_PULSE_MIN ||
        pulse_ms > FBRL_ROBOT_PULSE_MAX)
        return FBRL_ERANGE;
    if (fbrl_vmx_find(r->vm, name, len, &xt) == FBRL_OK && fbrl_robot_device_of(r, xt, &old) == FBRL_OK) {
        fbrl_robot_device *d = device_at(r, old.addr);
        d->port = port;
        d->output = output != 0;
        d->pulse_ms = pulse_ms;
        memcpy((unsigned char *)old.addr + FBRL_VMX_PAYLOAD, &cell, sizeof cell);
        return FBRL_OK;
    }
    return make_device(r, name, len, port, output != 0, pulse_ms);
}

size_t fbrl_robot_devices_free(const fbrl_robot *r)
{
    size_t n = 0;
    for (size_t k = 0; r && k < FBRL_ROBOT_MAX_DEVICES; k++)
        n += device_at(r, r->dev[k].addr) == NULL;
    return n;
}

/* OUTPUT-DEVICE / INPUT-DEVICE ( port "name" -- ) */
static fbrl_status w_make_device(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    char msg[96];
    if (v[0].i < 1 || v[0].i > FBRL_ROBOT_IO_MAX) {
        snprintf(msg, sizeof msg, "%s: port %ld outside 1..%d", w->name, (long)v[0].i, FBRL_ROBOT_IO_MAX);
        return rb_fail(r, FBRL_THROW_BAD_NUMBER, msg);
    }
    fbrl_status st = make_device(r, NULL, 0, (int)v[0].i, (int)w->arg, DEFAULT_PULSE_MS);
    if (st == FBRL_EFULL)
        return rb_fail(r, FBRL_VM_THROW_OF_STATUS(FBRL_EFULL), "too many devices");
    return st;
}

static fbrl_status set_output(fbrl_robot *r, const rb_word *w, const fbrl_robot_device *d, int on)
{
    fbrl_rapl_arg a = fbrl_rapl_int(on ? d->port : -d->port);
    return rb_cmd(r, w, FBRL_RAPL_OUTPUT, &a, 1, 0);
}

void fbrl_robot_set_events(fbrl_robot *r, fbrl_robot_event_fn fn, void *ctx)
{
    if (r) {
        r->on_event = fn;
        r->event_ctx = ctx;
    }
}

/* The host clock in ms for told(); 0 without one (then actual times read 0). */
static uint64_t t_ms(fbrl_robot *r)
{
    const fbrl_vm_host *h = fbrl_vmx_host(r->vm);
    return h->now_us ? h->now_us(h->user) / 1000u : 0;
}

/* Tell the run log what a device word did: planned and actual time (since t0). */
static fbrl_status told(fbrl_robot *r, const rb_word *w, const fbrl_robot_device *d, double amount,
                        long planned, uint64_t t0, int seen, fbrl_status st)
{
    if (!r->on_event)
        return st;
    uint64_t now = t_ms(r);
    fbrl_robot_event ev;
    memset(&ev, 0, sizeof ev);
    ev.word = w->name;
    ev.device = d ? d->addr : 0;
    ev.port = d ? d->port : 0;
    ev.amount = amount;
    ev.planned_ms = planned;
    ev.actual_ms = now >= t0 ? (long)(now - t0) : 0;
    ev.seen = seen;
    ev.status = st;
    r->on_event(r->event_ctx, &ev);
    return st;
}

/* ON / OFF ( dev -- ); for any other address, F-PC's ( a -- ) stores true / false */
static fbrl_status w_on_off(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_robot_device *d = device_at(r, v[0].i);
    if (!d) {
        fbrl_cell flag = w->arg ? -1 : 0;
        if (!fbrl_vm_addr(r->vm, v[0].i, sizeof(fbrl_cell)))
            return rb_fail(r, FBRL_THROW_BAD_ADDRESS, NULL);
        memcpy((void *)v[0].i, &flag, sizeof flag);
        return FBRL_OK;
    }
    if (!d->output) {
        char msg[96];
        snprintf(msg, sizeof msg, "%s: input device (port %d) cannot be switched", w->name, d->port);
        return rb_fail(r, FBRL_THROW_BAD_NUMBER, msg);
    }
    uint64_t t0 = t_ms(r);
    fbrl_status st = set_output(r, w, d, (int)w->arg);
    return told(r, w, d, 0, -1, t0, 0, st);
}

static fbrl_status ms_arg(fbrl_robot *r, const rb_word *w, fbrl_cell ms)
{
    if (ms >= 0 && ms <= MAX_WAIT_MS)
        return FBRL_OK;
    char msg[96];
    snprintf(msg, sizeof msg, "%s: time %ld ms outside 0..%ld", w->name, (long)ms, MAX_WAIT_MS);
    return rb_fail(r, FBRL_THROW_BAD_NUMBER, msg);
}

/* Beside other tasks, a pulse is steps the word's wait record counts (the word runs again
 * after each yield): memo[0] steps done (on, hold, off, gap; n pulses), memo[1] the time
 * the current step began. The output is switched off even when the wait fails. */
static fbrl_status pulses_beside_tasks(fbrl_robot *r, const rb_word *w, const fbrl_robot_device *d,
                                       uint32_t ms, long n)
{
    fbrl_vmx_wait *wt = fbrl_vmx_wait_state(r->vm);
    fbrl_status st = FBRL_OK;
    while (st == FBRL_OK && wt->memo[0] < 2 * (fbrl_cell)n - 1) {
        int on = wt->memo[0] % 2 == 0;
        if (on && !wt->memo[2]) {
            if ((st = set_output(r, w, d, 1)) != FBRL_OK)
                return st;
            wt->memo[2] = 1;
            wt->memo[1] = (fbrl_cell)rb_now_us(r);
        }
        st = rb_pause_until(r, (uint64_t)wt->memo[1] + (uint64_t)ms * RB_US_PER_MS);
        if (st != FBRL_OK && fbrl_vmx_yielded(r->vm))
            return st;
        if (on) {
            fbrl_status off = set_output(r, w, d, 0);
            wt->memo[2] = 0;
            if (st == FBRL_OK)
                st = off;
        }
        wt->memo[0]++;
        wt->memo[1] = (fbrl_cell)rb_now_us(r);
    }
    return st;
}

/* One pulse: on, hold, off. The output is switched off even when the wait fails. */
static fbrl_status pulse(fbrl_robot *r, const rb_word *w, const fbrl_robot_device *d, uint32_t ms)
{
    if (fbrl_vmx_tasking(r->vm))
        return pulses_beside_tasks(r, w, d, ms, 1);
    fbrl_status st = set_output(r, w, d, 1);
    if (st != FBRL_OK)
        return st;
    fbrl_status slept = rb_wait_ms(r, w->name, ms);
    st = set_output(r, w, d, 0);
    return slept != FBRL_OK ? slept : st;
}

/* PULSE ( ms dev -- ) */
static fbrl_status w_pulse(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_robot_device *d = NULL;
    fbrl_status st = ms_arg(r, w, v[0].i);
    if (st == FBRL_OK)
        st = device(r, w, v[1].i, 1, &d);
    if (st == FBRL_OK)
        st = rb_online(r);
    if (st != FBRL_OK)
        return st;
    uint64_t t0 = t_ms(r);
    return told(r, w, d, 0, (long)v[0].i, t0, 0, pulse(r, w, d, (uint32_t)v[0].i));
}

/* PULSE-WIDTH ( ms dev -- ): one DISPENSE pulse lasts ms, and so does the gap after it */
static fbrl_status w_pulse_width(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_robot_device *d = NULL;
    fbrl_status st = device(r, w, v[1].i, 1, &d);
    if (st != FBRL_OK)
        return st;
    if (v[0].i < (fbrl_cell)FBRL_ROBOT_PULSE_MIN || v[0].i > (fbrl_cell)FBRL_ROBOT_PULSE_MAX) {
        char msg[64];
        snprintf(msg, sizeof msg, "PULSE-WIDTH: %u..%u ms", FBRL_ROBOT_PULSE_MIN, FBRL_ROBOT_PULSE_MAX);
        return rb_fail(r, FBRL_THROW_BAD_NUMBER, msg);
    }
    d->pulse_ms = (uint32_t)v[0].i;
    return FBRL_OK;
}

/* DISPENSE ( dev -- ) ( F: ml -- ): one pulse per ml */
static fbrl_status w_dispense(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_robot_device *d = NULL;
    fbrl_status st = device(r, w, v[0].i, 1, &d);
    if (st != FBRL_OK)
        return st;
    double ml = v[1].f, n = floor(ml + 0.5);
    if (!isfinite(ml) || ml < 0 || ml > 10000 || fabs(ml - n) > 1e-6)
        return rb_fail(r, FBRL_THROW_BAD_NUMBER,
                       "DISPENSE: a whole number of ml, 0..10000 (one pulse per ml)");
    if ((st = rb_online(r)) != FBRL_OK)
        return st;
    uint64_t t0 = t_ms(r);
    long planned = n > 0 ? (long)d->pulse_ms * (2 * (long)n - 1) : 0; /* pulses and the gaps between */
    if (fbrl_vmx_tasking(r->vm)) {
        st = n > 0 ? pulses_beside_tasks(r, w, d, d->pulse_ms, (long)n) : FBRL_OK;
        return st != FBRL_OK && fbrl_vmx_yielded(r->vm) ? st : told(r, w, d, n, planned, t0, 0, st);
    }
    for (long k = 0; k < (long)n && st == FBRL_OK; k++) {
        st = pulse(r, w, d, d->pulse_ms);
        if (st == FBRL_OK && k + 1 < (long)n)
            st = rb_sleep_ms(r, d->pulse_ms);
        if (st == FBRL_OK)
            st = rb_interrupted(r);
    }
    return told(r, w, d, n, planned, t0, 0, st);
}

static fbrl_status read_input(fbrl_robot *r, const rb_word *w, const fbrl_robot_device *d, int *on)
{
    fbrl_status st = rb_online(r);
    if (st != FBRL_OK)
        return st;
    return rb_link_result(r, w, fbrl_link_input(r->link, d->port, on));
}

/* INPUT? ( dev -- flag ) */
static fbrl_status w_input_q(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_robot_device *d = NULL;
    int on = 0;
    fbrl_status st = device(r, w, v[0].i, 0, &d);
    if (st == FBRL_OK)
        st = read_input(r, w, d, &on);
    if (st != FBRL_OK)
        return st;
    return fbrl_vm_push(r->vm, on ? -1 : 0) == FBRL_OK ? FBRL_OK
                                                       : rb_fail(r, FBRL_THROW_STACK_OVERFLOW, NULL);
}

/* WAIT-INPUT ( dev state ms -- flag ): true once the input has the state (a flag),
 * false when ms passed first. Polls every 20 ms; never waits much longer than ms. */
static fbrl_status w_wait_input(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_robot_device *d = NULL;
    uint64_t t0, now;
    int on = 0, want = v[1].i != 0;
    fbrl_status st = device(r, w, v[0].i, 0, &d);
    if (st == FBRL_OK)
        st = ms_arg(r, w, v[2].i);
    if (st == FBRL_OK)
        st = rb_now_ms(r, &t0);
    if (st != FBRL_OK)
        return st;
    int tasking = fbrl_vmx_tasking(r->vm);
    if (tasking) /* its timeout holds from the first call, however often it runs again */
        t0 = fbrl_vmx_wait_state(r->vm)->since_us / RB_US_PER_MS;
    uint64_t shown = 0;
    int count_down = !tasking && r->progress && v[2].i >= 2 * (fbrl_cell)FBRL_ROBOT_PROGRESS_MS;
    for (;;) {
        if ((st = read_input(r, w, d, &on)) != FBRL_OK)
            break;
        if (on == want)
            break;
        if ((st = rb_now_ms(r, &now)) != FBRL_OK)
            break;
        uint64_t left = t0 + (uint64_t)v[2].i > now ? t0 + (uint64_t)v[2].i - now : 0;
        if (left == 0)
            break;
        if (count_down && (left + 999u) / 1000u != shown) { /* at a terminal: the seconds left */
            char line[96];
            shown = (left + 999u) / 1000u;
            snprintf(line, sizeof line, "%s: waiting for input %d, %lu s left", w->name, d->port,
                     (unsigned long)shown);
            r->progress(r->progress_ctx, line);
        }
        if (tasking)
            st = rb_pause_until(r, (now + (left < POLL_MS ? left : POLL_MS)) * RB_US_PER_MS);
        else
            st = rb_sleep_ms(r, (uint32_t)(left < POLL_MS ? left : POLL_MS));
        if (st != FBRL_OK)
            break;
        if ((st = rb_interrupted(r)) != FBRL_OK)
            break;
    }
    if (shown)
        r->progress(r->progress_ctx, NULL);
    told(r, w, d, want, (long)v[2].i, t0, st == FBRL_OK && on == want, st);
    if (st != FBRL_OK)
        return st;
    return fbrl_vm_push(r->vm, on == want ? -1 : 0) == FBRL_OK ? FBRL_OK
                                                               : rb_fail(r, FBRL_THROW_STACK_OVERFLOW, NULL);
}

/* INPUT-EDGE ( dev state -- ): until the input turns to state (a flag) from the other
 * state (the ONSIG idea); memo[0]: the other state was seen. Polls every EDGE_POLL_MS,
 * letting other tasks run. */
static fbrl_status w_input_edge(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_robot_device *d = NULL;
    int want = v[1].i != 0, on = 0;
    fbrl_status st = device(r, w, v[0].i, 0, &d);
    if (st != FBRL_OK)
        return st;
    fbrl_vmx_wait *wt = fbrl_vmx_wait_state(r->vm);
    for (;;) {
        if ((st = read_input(r, w, d, &on)) != FBRL_OK)
            return st;
        if (on != want)
            wt->memo[0] = 1;
        else if (wt->memo[0])
            return FBRL_OK;
        if (fbrl_vmx_tasking(r->vm))
            st = rb_pause_until(r, rb_now_us(r) + EDGE_POLL_MS * RB_US_PER_MS);
        else if ((st = rb_sleep_ms(r, EDGE_POLL_MS)) == FBRL_OK)
            st = rb_interrupted(r);
        if (st != FBRL_OK)
            return st;
    }
}

/* START-TIMER ( -- ) */
static fbrl_status w_start_timer(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    (void)w;
    (void)v;
    fbrl_vmx_timer *t = fbrl_vmx_task_timer(r->vm); /* each task has its own */
    fbrl_status st = rb_now_ms(r, &t->mark_ms);
    t->set = st == FBRL_OK;
    return st;
}

static fbrl_status elapsed(fbrl_robot *r, const rb_word *w, uint64_t *ms)
{
    uint64_t now;
    char msg[64];
    const fbrl_vmx_timer *t = fbrl_vmx_task_timer(r->vm);
    if (!t->set) {
        snprintf(msg, sizeof msg, "%s: no timer started (START-TIMER)", w->name);
        return rb_fail(r, FBRL_THROW_BAD_NUMBER, msg);
    }
    fbrl_status st = rb_now_ms(r, &now);
    if (st != FBRL_OK)
        return st;
    *ms = now - t->mark_ms;
    return FBRL_OK;
}

/* ELAPSED ( -- ms ) */
static fbrl_status w_elapsed(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    uint64_t ms = 0;
    (void)v;
    fbrl_status st = elapsed(r, w, &ms);
    if (st != FBRL_OK)
        return st;
    return fbrl_vm_push(r->vm, (fbrl_cell)ms) == FBRL_OK ? FBRL_OK
                                                         : rb_fail(r, FBRL_THROW_STACK_OVERFLOW, NULL);
}

/* WAIT-UNTIL ( ms -- ): until ms after START-TIMER (at once if that has passed) */
static fbrl_status w_wait_until(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    uint64_t ms = 0;
    fbrl_status st = ms_arg(r, w, v[0].i);
    if (st == FBRL_OK)
        st = elapsed(r, w, &ms);
    if (st != FBRL_OK)
        return st;
    long left = ms < (uint64_t)v[0].i ? (long)((uint64_t)v[0].i - ms) : 0;
    uint64_t t0 = t_ms(r);
    if (left > 0 && fbrl_vmx_tasking(r->vm)) {
        st = rb_pause_until(r, (fbrl_vmx_task_timer(r->vm)->mark_ms + (uint64_t)v[0].i) * RB_US_PER_MS);
        return st != FBRL_OK && fbrl_vmx_yielded(r->vm) ? st : told(r, w, NULL, 0, left, t0, 0, st);
    }
    return told(r, w, NULL, 0, left, t0, 0, left > 0 ? rb_wait_ms(r, w->name, (uint32_t)left) : FBRL_OK);
}

/* TIME-OF-DAY ( -- seconds ): seconds since local midnight */
static fbrl_status w_time_of_day(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    int t[6];
    (void)w;
    (void)v;
    const fbrl_vm_host *h = fbrl_vmx_host(r->vm);
    if (!h->time_date)
        return rb_fail(r, FBRL_THROW_UNSUPPORTED, "no clock in this host");
    h->time_date(h->user, t);
    return fbrl_vm_push(r->vm, (fbrl_cell)t[2] * 3600 + t[1] * 60 + t[0]) == FBRL_OK
               ? FBRL_OK
               : rb_fail(r, FBRL_THROW_STACK_OVERFLOW, NULL);
}

const rb_word rb_io_words[] = {
    {"OUTPUT-DEVICE", w_make_device, "I", 0, -1, 1,
     FBRL_DOC("( port \"name\" -- )", "name a controller output (1..16); name pushes the device")},
    {"INPUT-DEVICE", w_make_device, "I", 0, -1, 0,
     FBRL_DOC("( port \"name\" -- )", "name a controller input (1..16); name pushes the device")},
    {"ON", w_on_off, "A", 0, -1, 1,
     FBRL_DOC("( dev -- ) or ( a -- )", "switch an output device on (OUTPUT n); at a variable, store true")},
    {"OFF", w_on_off, "A", 0, -1, 0,
     FBRL_DOC("( dev -- ) or ( a -- )",
              "switch an output device off (OUTPUT -n); at a variable, store false")},
    {"PULSE", w_pulse, "IA", 0, -1, 0,
     FBRL_DOC("( ms dev -- )", "switch an output device on for ms milliseconds")},
    {"PULSE-WIDTH", w_pulse_width, "IA", 0, -1, 0,
     FBRL_DOC("( ms dev -- )", "length of one DISPENSE pulse and of the gap after it (100 ms)")},
    {"DISPENSE", w_dispense, "AR", 0, -1, 0,
     FBRL_DOC("( dev -- ) ( F: ml -- )", "dispense ml millilitres: one pulse per ml")},
    {"INPUT?", w_input_q, "A", 0, -1, 0, FBRL_DOC("( dev -- flag )", "true if the input device is on")},
    {"WAIT-INPUT", w_wait_input, "AII", 0, -1, 0,
     FBRL_DOC("( dev state ms -- flag )", "wait up to ms for the input to reach state; false on timeout")},
    {"INPUT-EDGE", w_input_edge, "AI", 0, -1, 0,
     FBRL_DOC("( dev state -- )",
              "wait until the input device turns to state (a flag) from the other state")},
    {"START-TIMER", w_start_timer, "", 0, -1, 0, FBRL_DOC("( -- )", "mark the start of a timed step")},
    {"ELAPSED", w_elapsed, "", 0, -1, 0, FBRL_DOC("( -- ms )", "milliseconds since START-TIMER")},
    {"WAIT-UNTIL", w_wait_until, "I", 0, -1, 0, FBRL_DOC("( ms -- )", "wait until ms after START-TIMER")},
    {"TIME-OF-DAY", w_time_of_day, "", 0, -1, 0, FBRL_DOC("( -- seconds )", "seconds since local midnight")},
};

const size_t rb_io_nwords = sizeof rb_io_words / sizeof rb_io_words[0];
