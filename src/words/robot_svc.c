/* SPDX-License-Identifier: MIT */
/* robot_svc.c - what every robot word uses from the VM: throwing an error (with the
 * word's name), Ctrl-C while a word waits, console output and the host's clock; and the
 * motion guard's hook (robot_gate.c makes every motion pass it). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "robot_internal.h"

fbrl_status rb_fail(fbrl_robot *r, int code, const char *msg)
{
    if (r->c_msg) { /* a C caller's motion (fbrl_robot_motion): the first error is its message */
        if (!r->c_code) {
            r->c_code = code;
            if (msg)
                snprintf(r->c_msg, r->c_cap, "%s", msg);
            else
                snprintf(r->c_msg, r->c_cap, "error (THROW %d)", code);
        }
        return FBRL_ETHROW;
    }
    return fbrl_vm_throw(r->vm, code, msg);
}

fbrl_status rb_fail_st(fbrl_robot *r, const rb_word *w, fbrl_status st, const char *what)
{
    char msg[128];
    snprintf(msg, sizeof msg, "%s: %s%s%s", w->name, what ? what : "", what ? ": " : "", fbrl_status_str(st));
    return rb_fail(r, FBRL_VM_THROW_OF_STATUS(st), msg);
}

/* Ctrl-C while a robot word waits on the controller: take the VM's interrupt request
 * here (the engine would deliver it only after the word returns) and throw -28. A
 * command the controller already has stays with the link (the next robot word, or
 * fbrl_robot_safe_stop, lets it end first); the arm keeps moving until the host stops
 * it (fbrl_robot_safe_stop: fbrlmon does on every Ctrl-C). */
fbrl_status rb_interrupted(fbrl_robot *r)
{
    if (!fbrl_vmx_take_interrupt(r->vm))
        return FBRL_OK;
    return rb_fail(r, FBRL_THROW_INTERRUPT, "user interrupt");
}

void rb_puts(fbrl_robot *r, const char *s) { fbrl_vmx_write(r->vm, s, strlen(s)); }

int rb_metric(const fbrl_robot *r)
{
    int on = 0;
    return r->g && fbrl_units_is_metric(fbrl_glossary_units(r->g), &on) == FBRL_OK && on;
}

fbrl_status rb_now_ms(fbrl_robot *r, uint64_t *ms)
{
    const fbrl_vm_host *h = fbrl_vmx_host(r->vm);
    if (!h->now_us)
        return rb_fail(r, FBRL_THROW_UNSUPPORTED, "no clock in this host");
    *ms = h->now_us(h->user) / 1000u;
    return FBRL_OK;
}

fbrl_status rb_sleep_ms(fbrl_robot *r, uint32_t ms)
{
    const fbrl_vm_host *h = fbrl_vmx_host(r->vm);
    if (!h->sleep_ms)
        return rb_fail(r, FBRL_THROW_UNSUPPORTED, "no clock in this host");
    if (ms)
        h->sleep_ms(h->user, ms);
    return FBRL_OK;
}

/* A timed wait of a word; at a terminal (a progress callback) a long one counts down
 * the seconds left, once a second, and is erased when it ends. Ctrl-C ends it at once,
 * as it ends the host's sleep (the engine then throws). */
fbrl_status rb_wait_ms(fbrl_robot *r, const char *who, uint32_t ms)
{
    if (!r->progress || ms < 2 * FBRL_ROBOT_PROGRESS_MS)
        return rb_sleep_ms(r, ms);
    fbrl_status st = FBRL_OK;
    uint32_t left = ms;
    char line[96];
    while (left > 0 && st == FBRL_OK && !fbrl_vm_interrupt_pending(r->vm)) {
        uint32_t slice = left % 1000u ? left % 1000u : 1000u; /* whole seconds left after it */
        snprintf(line, sizeof line, "%s: %lu s left", who, (unsigned long)((left + 999u) / 1000u));
        r->progress(r->progress_ctx, line);
        st = rb_sleep_ms(r, slice);
        left -= slice;
    }
    r->progress(r->progress_ctx, NULL);
    return st;
}

/* ---- the motion guard's hook ---- */

fbrl_status fbrl_robot_set_guard(fbrl_robot *r, const fbrl_robot_guard *g)
{
    if (!r)
        return FBRL_EINVAL;
    if (g)
        r->guard = *g;
    else
        memset(&r->guard, 0, sizeof r->guard);
    return FBRL_OK;
}

unsigned long fbrl_robot_where_epoch(const fbrl_robot *r) { return r ? r->where_epoch : 0; }

void rb_where_lost(fbrl_robot *r) { r->where_epoch++; }

/* Beside other tasks (fbrl_vmx_tasking): wait until the host clock reaches until_us,
 * letting them run. FBRL_OK when the time has come; otherwise return the status at once
 * (fbrl_vmx_yielded: the word runs again when its task resumes). */
fbrl_status rb_pause_until(fbrl_robot *r, uint64_t until_us)
{
    const fbrl_vm_host *h = fbrl_vmx_host(r->vm);
    if (!h->now_us)
        return rb_fail(r, FBRL_THROW_UNSUPPORTED, "no clock in this host");
    while (h->now_us(h->user) < until_us) {
        fbrl_status st = fbrl_vmx_pause(r->vm, until_us);
        if (st != FBRL_OK)
            return st;
    }
    return FBRL_OK;
}

uint64_t rb_now_us(fbrl_robot *r)
{
    const fbrl_vm_host *h = fbrl_vmx_host(r->vm);
    return h->now_us ? h->now_us(h->user) : 0;
}
