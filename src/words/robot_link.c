/* robot_link.c - robot words talking to the controller through the fbrl_link: one
 * command (echo-verified), a raw line, a stream of readings; controller errors become
 * exceptions, and a command an interrupted word left running is finished first. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "robot_internal.h"

static const char OFFLINE[] = "no controller connected: start fbrlmon with --sim or --port";

/* Run the link's current command to its end in slices, looking for Ctrl-C between
 * them. Interrupted, the command stays in the link (the controller cannot take a
 * line back): rb_online() finishes it before the next command. */
static fbrl_status rb_drive(fbrl_robot *r, fbrl_status *result)
{
    for (;;) {
        int done = 0;
        fbrl_status st = fbrl_link_poll(r->link, 100, &done);
        if (done || st != FBRL_OK) {
            *result = st;
            return FBRL_OK;
        }
        if ((st = rb_interrupted(r)) != FBRL_OK) return st;
    }
}

fbrl_status rb_online(fbrl_robot *r)
{
    if (!r->link) return rb_fail(r, FBRL_VM_THROW_OF_STATUS(FBRL_EOFFLINE), OFFLINE);
    if (fbrl_link_busy(r->link)) { /* left running by an interrupted word: end it first */
        fbrl_status res = FBRL_OK, st = rb_drive(r, &res);
        if (st != FBRL_OK) return st;
        if (res == FBRL_ECONTROLLER) fbrl_link_error(r->link, &r->last_error, NULL);
    }
    return FBRL_OK;
}

fbrl_status rb_link_result(fbrl_robot *r, const rb_word *w, fbrl_status st)
{
    char msg[128];
    if (st == FBRL_OK) return FBRL_OK;
    if (st == FBRL_ECONTROLLER) {
        int code = FBRL_THROW_ABORT;
        const char *text = "";
        fbrl_link_error(r->link, &code, &text);
        r->last_error = code;
        snprintf(msg, sizeof msg, "%s: controller error %03d-%s", w->name, code, text);
        return rb_fail(r, FBRL_VM_THROW_OF_STATUS(st), msg);
    }
    if (st == FBRL_EINVAL || st == FBRL_ENAME || st == FBRL_ERANGE || st == FBRL_ENONFINITE)
        return rb_fail_st(r, w, st, "cannot encode the command");
    return rb_fail_st(r, w, st, "link");
}

fbrl_status rb_cmd(fbrl_robot *r, const rb_word *w, fbrl_rapl_cmd cmd, const fbrl_rapl_arg *a, size_t n,
                   int straight)
{
    fbrl_status st = rb_online(r);
    if (st != FBRL_OK) return st;
    const fbrl_rapl_cmdinfo *ci = fbrl_rapl_cmd_info(cmd);
    if (!ci || !((ci->flags & FBRL_RAPL_F_MOTION) || cmd == FBRL_RAPL_FINISH || cmd == FBRL_RAPL_WAIT ||
                 cmd == FBRL_RAPL_RUN))
        return rb_link_result(r, w, fbrl_link_cmd(r->link, cmd, a, n, straight));
    /* A command that may wait for the arm or an input (no reply but the prompt): run it
     * step by step so that Ctrl-C is noticed while it waits. */
    char text[FBRL_RAPL_LINE_MAX];
    size_t len;
    fbrl_rapl_form form = FBRL_RAPL_KEYWORD;
    (void)fbrl_link_get_form(r->link, &form);
    fbrl_status res = fbrl_rapl_encode(text, sizeof text, &len, form, cmd, a, n, straight);
    if (res == FBRL_OK && len > FBRL_LINK_LINE_MAX) res = FBRL_ERANGE;
    if (res == FBRL_OK) res = fbrl_link_start(r->link, text, FBRL_LINK_REPLY_NONE);
    if (res == FBRL_OK && (st = rb_drive(r, &res)) != FBRL_OK) return st;
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

fbrl_status rb_raw(fbrl_robot *r, const rb_word *w, const char *line, int print)
{
    void (*fn)(void *, const char *, size_t, int);
    void *ctx;
    fbrl_status st = rb_online(r);
    if (st != FBRL_OK) return st;
    if (print) borrow_lines(r, &fn, &ctx);
    st = fbrl_link_raw(r->link, line);
    if (print) return_lines(r, fn, ctx);
    return rb_link_result(r, w, st);
}

fbrl_status rb_stream(fbrl_robot *r, const rb_word *w, fbrl_rapl_cmd cmd)
{
    void (*fn)(void *, const char *, size_t, int);
    void *ctx;
    fbrl_status st = rb_online(r);
    if (st != FBRL_OK) return st;
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
    if (st != FBRL_OK) return st;
    (void)fbrl_link_set_line_handler(r->link, fn, ctx, &old, &old_ctx);
    st = fbrl_link_raw(r->link, line);
    return_lines(r, old, old_ctx);
    return rb_link_result(r, w, st);
}
