/* SPDX-License-Identifier: MIT */
/* robot_link.c - robot words talking to the controller through the fbrl_link: one
 * command (echo-verified), a raw line, a stream of readings; controller errors become
 * exceptions, and a command an interrupted word left running is finished first. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "fbrl/num.h"

#include "robot_internal.h"

static const char OFFLINE[] = "no controller connected: start fbrlmon with --sim or --port";

/* A wait a person may watch: at a terminal (r->progress) it shows how long it has been,
 * about once a second, and (r->tell) how long it took. */
typedef struct rb_wait {
    uint64_t t0;
    unsigned long shown; /* seconds shown so far */
    int timed;
} rb_wait;

static void wait_begin(fbrl_robot *r, rb_wait *wt)
{
    wt->t0 = 0;
    wt->shown = 0;
    wt->timed = r->progress && fbrl_vmx_host(r->vm)->now_us && rb_now_ms(r, &wt->t0) == FBRL_OK;
}

static void wait_tick(fbrl_robot *r, rb_wait *wt, const char *who, const char *what)
{
    uint64_t now = 0;
    if (wt->timed && rb_now_ms(r, &now) == FBRL_OK && now - wt->t0 >= FBRL_ROBOT_PROGRESS_MS &&
        (now - wt->t0) / 1000u != wt->shown) {
        char line[96];
        wt->shown = (unsigned long)((now - wt->t0) / 1000u);
        snprintf(line, sizeof line, "%s: waiting for %s, %lu s", who, what, wt->shown);
        r->progress(r->progress_ctx, line);
    }
}

static void wait_end(fbrl_robot *r, rb_wait *wt, const char *who, const char *what)
{
    uint64_t now = 0;
    if (!wt->shown)
        return;
    r->progress(r->progress_ctx, NULL);
    if (r->tell && rb_now_ms(r, &now) == FBRL_OK) {
        char line[96], secs[24]; /* "%.1f" through fbrl_num_fixed: the firmware's printf has no %f */
        fbrl_num_fixed(secs, sizeof secs, (double)(now - wt->t0) / 1000.0, 0, 1, 0, NULL);
        snprintf(line, sizeof line, "%s: waited %s s for %s\n", who, secs, what);
        rb_puts(r, line);
    }
}

/* Run the link's current command to its end in slices, looking for Ctrl-C between
 * them. Interrupted, the command stays in the link (the controller cannot take a
 * line back): rb_online() finishes it before the next command. */
static fbrl_status rb_drive_for(fbrl_robot *r, const char *who, const char *what, fbrl_status *result)
{
    rb_wait wt;
    fbrl_status st, interrupted = FBRL_OK;
    wait_begin(r, &wt);
    for (;;) {
        int done = 0;
        st = fbrl_link_poll(r->link, 100, &done);
        if (done || st != FBRL_OK) {
            *result = st;
            break;
        }
        if ((interrupted = rb_interrupted(r)) != FBRL_OK)
            break;
        wait_tick(r, &wt, who, what);
    }
    wait_end(r, &wt, who, what);
    return interrupted;
}

static fbrl_status rb_drive(fbrl_robot *r, fbrl_status *result)
{
    return rb_drive_for(r, "the controller", "the last command", result);
}

fbrl_status rb_online(fbrl_robot *r)
{
    if (!r->link)
        return rb_fail(r, FBRL_VM_THROW_OF_STATUS(FBRL_EOFFLINE), OFFLINE);
    if (r->lost) { /* the controller went away: reconnect first, if the host can */
        char msg[160];
        fbrl_status st = r->relink ? r->relink(r->relink_ctx, r) : FBRL_EDISCONNECTED;
        if (st != FBRL_OK || r->lost || !r->link) {
            snprintf(msg, sizeof msg, "controller disconnected%s%s (RECONNECT when it is back)",
                     r->relink ? ": reconnecting failed: " : "", r->relink ? fbrl_status_str(st) : "");
            return rb_fail(r, FBRL_VM_THROW_OF_STATUS(FBRL_EDISCONNECTED), msg);
        }
    }
    if (fbrl_link_busy(r->link)) { /* left running by an interrupted word: end it first */
        fbrl_status res = FBRL_OK, st = rb_drive(r, &res);
        if (st != FBRL_OK)
            return st;
        if (res == FBRL_ECONTROLLER)
            fbrl_link_error(r->link, &r->last_error, NULL);
        if (res == FBRL_EDISCONNECTED)
            r->lost = 1;
    }
    return FBRL_OK;
}

fbrl_status rb_units(fbrl_robot *r, const rb_word *w)
{
    if (fbrl_link_units(r->link) != FBRL_LINK_UNITS_MM)
        return FBRL_OK;
    char msg[240];
    snprintf(msg, sizeof msg,
             "%s: the controller works in millimetres (STATUS: METRIC UNITS.) and the robot words send "
             "inches: not sent; switch it to inches (RAPL NOMETRIC) first",
             w->name);
    return rb_fail(r, FBRL_VM_THROW_OF_STATUS(FBRL_ESTATE), msg);
}

/* What to do about an error, as things stand here: after the controller's 190-COLLISION
 * that depends on the guard (no cell described, the guard off, or a cell that lacks what
 * the arm met). "" when there is nothing to add, and under FBRL_NO_HELP, which leaves the
 * controller's error advice out (fbrl_rapl_error_help). */
static const char *rb_advice(const fbrl_robot *r, int code)
{
#ifdef FBRL_NO_HELP
    (void)r;
    (void)code;
    return "";
#else
    if (fbrl_rapl_error_class(code) != FBRL_RAPL_ERRC_COLLISION)
        return "";
    fbrl_robot_guard_state g = !r->guard.check ? FBRL_ROBOT_GUARD_EMPTY
                               : r->guard.state ? r->guard.state(r->guard.ctx)
                                                : FBRL_ROBOT_GUARD_ON;
    if (g == FBRL_ROBOT_GUARD_EMPTY)
        return ": describe the cell on the host too (CELL-BOX ...), so that the guard refuses such a move "
               "before it is sent";
    if (g == FBRL_ROBOT_GUARD_OFF)
        return ": the guard is off (CELL-GUARD-OFF); CELL-GUARD-ON checks every motion before it is sent";
    return ": the guard let it pass, so the host's cell lacks what the arm met: describe it as the "
           "controller's cell has it";
#endif
}

fbrl_status rb_link_result(fbrl_robot *r, const rb_word *w, fbrl_status st)
{
    char msg[240];
    if (st == FBRL_OK)
        return FBRL_OK;
    if (st == FBRL_EDISCONNECTED) {
        r->lost = 1;
        return rb_fail(r, FBRL_VM_THROW_OF_STATUS(st), "controller disconnected (RECONNECT when it is back)");
    }
    if (st == FBRL_ECONTROLLER) {
        int code = FBRL_THROW_ABORT;
        const char *text = "", *help;
        fbrl_link_error(r->link, &code, &text);
        r->last_error = code;
        help = fbrl_rapl_error_help(code); /* its meaning and what to do, in plain words */
        if (code < 0)                      /* docs/link.md 3.9: refused all the same */
            snprintf(msg, sizeof msg, "%s: controller error, code unknown (its error line came damaged)",
                     w->name);
        else
            snprintf(msg, sizeof msg, "%s: controller error %03d-%s%s%s%s%s", w->name, code, text,
                     help ? " (" : "", help ? help : "", help ? ")" : "", rb_advice(r, code));
        return rb_fail(r, FBRL_VM_THROW_OF_STATUS(st), msg);
    }
    if (st == FBRL_EMAYBE) {
        /* docs/link.md 3.9: say it plainly, with what the controller was last seen doing */
        fbrl_link_outcome o;
        (void)fbrl_link_outcome_get(r->link, &o);
        if (o.cause == FBRL_EPROTOCOL || o.cause == FBRL_OK)
            snprintf(msg, sizeof msg, "%s: may have run: %s; check the robot before repeating it", w->name,
                     o.seen);
        else
            snprintf(msg, sizeof msg, "%s: may have run: %s (%s); check the robot first", w->name, o.seen,
                     fbrl_status_str(o.cause));
        return rb_fail(r, FBRL_VM_THROW_OF_STATUS(st), msg);
    }
    if (st == FBRL_EINVAL || st == FBRL_ENAME || st == FBRL_ERANGE || st == FBRL_ENONFINITE)
        return rb_fail_st(r, w, st, "cannot encode the command");
    return rb_fail_st(r, w, st, "link");
}

/* rb_still reads the controller's commanded velocity (W5): the motion is over when a
 * value line is all zero. Far shorter on the wire than STATUS (60 bytes a line against
 * some 900), so the next motion follows the end of the last one closely even at 9600
 * baud. A zero read just as a motion starts would only let the controller queue the
 * next motion (as it did before this wait): nothing runs early or twice. */
typedef struct still_read {
    unsigned zeros; /* consecutive all-zero value lines, up to the last one */
} still_read;

int fbrl_robot_still_line(const char *line, size_t len, int flawed)
{
    long v[FBRL_RAPL_MAX_AXES];
    size_t n = 0, k;
    if (!line || flawed) /* a damaged line is no proof of rest */
        return 0;
    if (fbrl_rapl_parse_ints(line, len, v, FBRL_RAPL_MAX_AXES, &n) != FBRL_OK || n == 0)
        return 0; /* title */
    for (k = 0; k < n && v[k] == 0; k++)
        ;
    return k == n;
}

static void still_line(void *ctx, const char *line, size_t len, int flawed)
{
    still_read *sr = ctx;
    long v[FBRL_RAPL_MAX_AXES];
    size_t n = 0;
    if (fbrl_rapl_parse_ints(line, len, v, FBRL_RAPL_MAX_AXES, &n) != FBRL_OK || n == 0)
        return; /* a title leaves the count as it is */
    sr->zeros = fbrl_robot_still_line(line, len, flawed) ? sr->zeros + 1 : 0;
}

fbrl_status rb_still(fbrl_robot *r, const rb_word *w)
{
    rb_wait wt;
    fbrl_status st = rb_online(r);
    uint64_t watched = rb_now_us(r); /* the last look of the watcher (fbrl_robot_set_watch) */
    wait_begin(r, &wt);
    while (st == FBRL_OK && r->moving) {
        still_read sr;
        fbrl_link_line_fn fn;
        void *ctx;
        fbrl_status res = FBRL_OK;
        memset(&sr, 0, sizeof sr);
        (void)fbrl_link_set_line_handler(r->link, still_line, &sr, &fn, &ctx);
        st = fbrl_link_start_stream(r->link, FBRL_RAPL_W5, 1);
        if (st == FBRL_OK)
            st = rb_drive_for(r, w->name, "the arm", &res);
        else
            res = st, st = FBRL_OK;
        (void)fbrl_link_set_line_handler(r->link, fn, ctx, NULL, NULL);
        if (st != FBRL_OK)
            break;                     /* interrupted: the stream ends in the link, unread */
        if (res == FBRL_ECONTROLLER) { /* no W5 here: the controller's own queue decides */
            r->moving = 0;
            break;
        }
        if ((st = rb_link_result(r, w, res)) != FBRL_OK)
            break;
        if (sr.zeros > 0) {
            r->moving = 0;
            break;
        }
        if (r->watch && rb_now_us(r) - watched >= FBRL_ROBOT_WATCH_MS * RB_US_PER_MS) {
            r->watch(r->watch_ctx, r); /* the link is free between two W5 rounds */
            watched = rb_now_us(r);
        }
        if (fbrl_vmx_tasking(r->vm)) { /* the others run (the link is free between rounds) */
            st = rb_pause_until(r, rb_now_us(r) + RB_STILL_POLL_MS * RB_US_PER_MS);
        } else {
            const fbrl_vm_host *h = fbrl_vmx_host(r->vm);
            if (h->sleep_ms)
                h->sleep_ms(h->user, RB_STILL_POLL_MS); /* none: W5 rounds pace it */
            st = rb_interrupted(r);
            wait_tick(r, &wt, w->name, "the arm");
        }
    }
    wait_end(r, &wt, w->name, "the arm");
    return st;
}

/* Outputs switched on by a command (OUTPUT n,-m,...): remembered for the safe stop. */
static void note_outputs(fbrl_robot *r, const fbrl_rapl_arg *a, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (a[k].kind == FBRL_RAPL_ARG_INT && a[k].i >= 1 && a[k].i <= FBRL_ROBOT_IO_MAX)
            r->outputs_on |= 1u << (a[k].i - 1);
}

/* At a terminal: what the motion just started. The prompt comes back while the arm moves
 * (the next motion or FINISH waits for it). */
static void tell_motion(fbrl_robot *r, const rb_word *w, const char *text)
{
    char line[256];
    if (r->have_target) {
        int metric = rb_metric(r);
        double k = metric ? FBRL_CM_PER_IN : 1.0;
        char x[24], y[24], z[24]; /* "%+.4f" through fbrl_num_fixed: the firmware's printf has no %f */
        fbrl_num_fixed(x, sizeof x, r->target.x * k, 0, 4, FBRL_NUM_PLUS, NULL);
        fbrl_num_fixed(y, sizeof y, r->target.y * k, 0, 4, FBRL_NUM_PLUS, NULL);
        fbrl_num_fixed(z, sizeof z, r->target.z * k, 0, 4, FBRL_NUM_PLUS, NULL);
        snprintf(line, sizeof line, "%s: the arm is moving to X %s Y %s Z %s %s (%s)\n", w->name, x, y, z,
                 metric ? "cm" : "in", text);
    } else {
        snprintf(line, sizeof line, "%s: the arm is moving (%s)\n", w->name, text);
    }
    rb_puts(r, line);
}

fbrl_status rb_cmd(fbrl_robot *r, const rb_word *w, fbrl_rapl_cmd cmd, const fbrl_rapl_arg *a, size_t n,
                   int straight)
{
    fbrl_status st = rb_online(r);
    if (st != FBRL_OK)
        return st;
    /* lengths, and points made of them, are inches: not for a controller in millimetres
     * (the unit switches themselves and the reads that tell the units go through) */
    if (cmd != FBRL_RAPL_METRIC && cmd != FBRL_RAPL_NOMETRIC && cmd != FBRL_RAPL_STATUS &&
        (st = rb_units(r, w)) != FBRL_OK)
        return st;
    const fbrl_rapl_cmdinfo *ci = fbrl_rapl_cmd_info(cmd);
    int motion = ci && (ci->flags & FBRL_RAPL_F_MOTION);
    /* beside other tasks: never cut into a manoeuvre another task has claimed the arm for */
    if ((motion || cmd == FBRL_RAPL_OPEN || cmd == FBRL_RAPL_CLOSE || cmd == FBRL_RAPL_GRIP) &&
        (st = fbrl_vmx_claim_wait(r->vm, FBRL_VMX_ARM)) != FBRL_OK)
        return st;
    /* a motion or FINISH behind a running motion would make the controller wait, deaf
     * to HALT: wait here instead, where Ctrl-C can stop the arm */
    if ((motion || cmd == FBRL_RAPL_FINISH) && (st = rb_still(r, w)) != FBRL_OK) {
        r->have_target = 0;
        return st;
    }
    return rb_send(r, w, cmd, a, n, straight, 0);
}

fbrl_status rb_send(fbrl_robot *r, const rb_word *w, fbrl_rapl_cmd cmd, const fbrl_rapl_arg *a, size_t n,
                    int straight, int checked)
{
    fbrl_status st;
    const fbrl_rapl_cmdinfo *ci = fbrl_rapl_cmd_info(cmd);
    int motion = ci && (ci->flags & FBRL_RAPL_F_MOTION);
    if (cmd == FBRL_RAPL_OUTPUT)
        note_outputs(r, a, n);
    if (!ci || !(ci->flags & FBRL_RAPL_F_WAITS)) { /* the table: its prompt never comes late */
        fbrl_status res = fbrl_link_cmd(r->link, cmd, a, n, straight);
        if (res == FBRL_OK && cmd == FBRL_RAPL_HALT)
            r->moving = 0;
        return rb_link_result(r, w, res);
    }
    /* A command that may wait for the arm or an input (no reply but the prompt): run it
     * step by step so that Ctrl-C is noticed while it waits. */
    char text[FBRL_RAPL_LINE_MAX];
    size_t len;
    fbrl_rapl_form form = FBRL_RAPL_KEYWORD;
    (void)fbrl_link_get_form(r->link, &form);
    fbrl_status res = fbrl_rapl_encode(text, sizeof text, &len, form, cmd, a, n, straight);
    if (res == FBRL_OK && len > FBRL_LINK_LINE_MAX)
        res = FBRL_ERANGE;
    if (res == FBRL_OK && checked)
        r->armed = text; /* the gate lets this one line through */
    if (res == FBRL_OK)
        res = fbrl_link_start(r->link, text, FBRL_LINK_REPLY_NONE);
    r->armed = NULL;
    if (res == FBRL_OK && motion) {
        /* sent (its fate may stay unknown): count it as running until W5 says not */
        r->moving = 1;
        memcpy(r->motion, text, len + 1); /* len <= FBRL_LINK_LINE_MAX */
    }
    if (res == FBRL_OK &&
        (st = rb_drive_for(r, w->name, cmd == FBRL_RAPL_WAIT ? "the input" : "the arm", &res)) != FBRL_OK) {
        r->have_target = 0;
        return st; /* interrupted: the command stays with the link */
    }
    if (res == FBRL_ECONTROLLER && motion)
        r->moving = 0; /* refused: nothing started */
    if (res == FBRL_OK && cmd == FBRL_RAPL_FINISH)
        r->moving = 0;
    if (res == FBRL_OK && r->tell && motion && !r->c_msg) /* a C caller shows its own */
        tell_motion(r, w, text);
    r->have_target = 0;
    return rb_link_result(r, w, res);
}

static void print_line(void *ctx, const char *line, size_t len, int flawed)
{
    fbrl_robot *r = ctx;
    fbrl_vmx_write(r->vm, line, len);
    fbrl_vmx_write(r->vm, flawed ? " (damaged)\n" : "\n", flawed ? 12 : 1);
}

/* The robot borrows the link's line handler for one command (docs/robot.md) and puts
 * the owner's back. */
static void borrow_lines(fbrl_robot *r, void (**fn)(void *, const char *, size_t, int), void **ctx)
{
    (void)fbrl_link_set_line_handler(r->link, print_line, r, fn, ctx);
}

static void return_lines(fbrl_robot *r, void (*fn)(void *, const char *, size_t, int), void *ctx)
{
    (void)fbrl_link_set_line_handler(r->link, fn, ctx, NULL, NULL);
}

typedef struct rb_show_ctx {
    fbrl_robot *r;
    fbrl_link_line_fn fn;
    void *ctx;
} rb_show_ctx;

static void show_line(void *ctx, const char *line, size_t len, int flawed)
{
    rb_show_ctx *c = ctx;
    print_line(c->r, line, len, flawed);
    if (c->fn)
        c->fn(c->ctx, line, len, flawed);
}

/* A display (W0 W2 W4, ROBOT-STATUS, SERIAL, a query typed with RAPL) shows what the
 * controller printed, once: one reading, sent once. The link reads a value a program
 * uses (STATUS, TYPEV, W2 for ARM-HERE) until two readings agree; a display needs no
 * second reading (a damaged line is shown marked), and a position read while the arm
 * moves could never agree. Each line also goes to fn (may be NULL). */
fbrl_status rb_show(fbrl_robot *r, const rb_word *w, const char *line, fbrl_link_line_fn fn, void *ctx)
{
    fbrl_link_line_fn old_fn = NULL;
    void *old_ctx = NULL;
    rb_show_ctx c = {r, fn, ctx};
    fbrl_status res, st = rb_online(r);
    if (st != FBRL_OK)
        return st;
    (void)fbrl_link_set_line_handler(r->link, show_line, &c, &old_fn, &old_ctx);
    res = fbrl_link_start(r->link, line, FBRL_LINK_REPLY_LINES);
    if (res == FBRL_OK)
        st = rb_drive(r, &res);
    (void)fbrl_link_set_line_handler(r->link, old_fn, old_ctx, NULL, NULL);
    if (st != FBRL_OK)
        return st;
    return rb_link_result(r, w, res);
}

fbrl_status rb_raw_send(fbrl_robot *r, const rb_word *w, const char *line, int print, int motion)
{
    void (*fn)(void *, const char *, size_t, int);
    void *ctx;
    fbrl_status st;
    if (motion) {
        r->armed = line; /* checked: the gate lets it through */
        r->moving = 1;
        snprintf(r->motion, sizeof r->motion, "%s", line);
    }
    if (print)
        borrow_lines(r, &fn, &ctx);
    st = fbrl_link_raw(r->link, line);
    r->armed = NULL;
    if (print)
        return_lines(r, fn, ctx);
    return rb_link_result(r, w, st);
}

fbrl_status rb_stream(fbrl_robot *r, const rb_word *w, fbrl_rapl_cmd cmd)
{
    void (*fn)(void *, const char *, size_t, int);
    void *ctx;
    fbrl_status st = rb_online(r);
    if (st != FBRL_OK)
        return st;
    borrow_lines(r, &fn, &ctx);
    st = fbrl_link_stream(r->link, cmd, FBRL_ROBOT_STREAM_LINES);
    return_lines(r, fn, ctx);
    return rb_link_result(r, w, st);
}

fbrl_status rb_raw_lines(fbrl_robot *r, const rb_word *w, const char *line,
                         void (*fn)(void *, const char *, size_t, int), void *ctx)
{
    void (*old)(void *, const char *, size_t, int);
    void *old_ctx;
    fbrl_status st = rb_online(r);
    if (st != FBRL_OK)
        return st;
    (void)fbrl_link_set_line_handler(r->link, fn, ctx, &old, &old_ctx);
    st = fbrl_link_raw(r->link, line);
    return_lines(r, old, old_ctx);
    return rb_link_result(r, w, st);
}
