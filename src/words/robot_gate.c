/* SPDX-License-Identifier: MIT */
/* robot_gate.c - the one gate every motion passes (docs/workcell.md "The guard").
 *
 * A motion is one step that no other task can enter: first the waits (another task's claim
 * on the arm, the end of the last motion: other tasks run meanwhile), then, with nothing
 * run in between, the guard's check (it reads where the arm stands), the scratch point and
 * the motion line, then the guard's notice of the result. The link's gate (rb_link_gate,
 * on the robot's link) sees every line just before it is typed: it lets through the one
 * motion line the step checked, and refuses any other motion while the guard is on (a
 * line on the link from C or Python), unless its caller went around the guard explicitly
 * (fbrl_link_unguarded), which the run log is told. Robot words, RAPL lines, TEACH and C
 * callers (fbrl_robot_motion) all come through rb_motion. */
#include <stdio.h>
#include <string.h>

#include "robot_internal.h"

static fbrl_robot_guard_state guard_state(const fbrl_robot *r)
{
    if (!r->guard.check)
        return FBRL_ROBOT_GUARD_EMPTY;
    return r->guard.state ? r->guard.state(r->guard.ctx) : FBRL_ROBOT_GUARD_ON;
}

fbrl_status rb_link_gate(void *ctx, const char *line, size_t len, int unguarded)
{
    fbrl_robot *r = ctx;
    fbrl_rapl_cmd cmd = FBRL_RAPL_NCMDS;
    rb_line_kind k = rb_line_cmd(line, len, &cmd);
    if (rb_line_loses(k, cmd))
        rb_where_lost(r);
    if (!rb_line_moves(k, cmd))
        return FBRL_OK;
    if (r->armed && strlen(r->armed) == len && memcmp(r->armed, line, len) == 0) {
        r->armed = NULL; /* the motion the step just checked */
        return FBRL_OK;
    }
    if (guard_state(r) == FBRL_ROBOT_GUARD_ON && !unguarded)
        return FBRL_EGUARD;
    /* it goes out unchecked: the arm goes where the guard cannot follow, and may still be
     * moving when the next motion comes */
    rb_where_lost(r);
    r->moving = 1;
    snprintf(r->motion, sizeof r->motion, "%.*s", (int)len, line);
    if (unguarded && r->on_event) {
        fbrl_robot_event ev;
        memset(&ev, 0, sizeof ev);
        ev.word = "UNGUARDED";
        ev.line = r->motion;
        ev.planned_ms = ev.actual_ms = -1;
        r->on_event(r->event_ctx, &ev);
    }
    return FBRL_OK;
}

/* The arm is ours and stands: no other task holds it, the last motion has ended. Both
 * waits may let other tasks run, and what they do (claim the arm, start a motion) is
 * looked at again until neither wait had to wait. */
static fbrl_status arm_ready(fbrl_robot *r, const rb_word *w)
{
    fbrl_status st;
    do {
        if ((st = fbrl_vmx_claim_wait(r->vm, FBRL_VMX_ARM)) != FBRL_OK || (st = rb_still(r, w)) != FBRL_OK ||
            (st = fbrl_vmx_claim_wait(r->vm, FBRL_VMX_ARM)) != FBRL_OK)
            return st;
    } while (r->moving);
    return FBRL_OK;
}

fbrl_status rb_motion(fbrl_robot *r, const rb_word *w, fbrl_robot_move *m, rb_out *o)
{
    const char *name;
    fbrl_status st = rb_online(r);
    /* a raw line is in the controller's units as typed; the words' lengths are inches */
    if (st == FBRL_OK && !o->raw)
        st = rb_units(r, w);
    if (st == FBRL_OK)
        st = arm_ready(r, w);
    if (st != FBRL_OK) {
        r->have_target = 0;
        return st;
    }
    /* from here to the motion line nothing lets another task run */
    m->word = w->name;
    int checked = r->guard.check != NULL;
    if (checked && (st = r->guard.check(r->guard.ctx, r, m)) != FBRL_OK) {
        if (r->c_msg && r->c_code == FBRL_ROBOT_THROW_REFUSED)
            r->c_refused = 1;
        r->have_target = 0;
        return st;
    }
    if (o->point && (st = rb_scratch_point(r, w, o->point, &name)) == FBRL_OK)
        o->a[0] = fbrl_rapl_str(name);
    if (st == FBRL_OK)
        st = o->raw ? rb_raw_send(r, w, o->raw, o->print, 1) : rb_send(r, w, o->cmd, o->a, o->n, o->straight, 1);
    r->have_target = 0;
    if (checked && r->guard.done)
        r->guard.done(r->guard.ctx, r, m, st);
    return st;
}

/* Is line a read-only query the link would read twice (W0 W2 W4 STATUS TYPEI TYPEV)? */
static int display_query(const char *line)
{
    fbrl_rapl_cmd c;
    if (rb_line_cmd(line, strlen(line), &c) != RB_LINE_CMD)
        return 0;
    fbrl_rapl_reply kind = fbrl_rapl_cmd_info(c)->reply; /* the table says what it prints */
    return kind >= FBRL_RAPL_REPLY_POS && kind <= FBRL_RAPL_REPLY_REAL;
}

fbrl_status rb_raw(fbrl_robot *r, const rb_word *w, const char *line, int print)
{
    fbrl_rapl_cmd cmd = FBRL_RAPL_NCMDS;
    size_t len = strlen(line);
    if (print && display_query(line))
        return rb_show(r, w, line, NULL, NULL);
    fbrl_status st = rb_online(r);
    if (st != FBRL_OK)
        return st;
    rb_line_kind k = rb_line_cmd(line, len, &cmd);
    if (rb_line_moves(k, cmd)) {
        fbrl_robot_move m;
        rb_out o;
        rb_line_move(line, len, &m); /* what the guard can follow of it; the rest it refuses */
        memset(&o, 0, sizeof o);
        o.raw = line;
        o.print = print;
        return rb_motion(r, w, &m, &o);
    }
    unsigned effect = 0;
    uint32_t on = 0;
    (void)fbrl_robot_line_effect(line, &effect, &on);
    r->outputs_on |= on; /* remembered for the safe stop */
    if (k == RB_LINE_CMD && cmd == FBRL_RAPL_FINISH && (st = rb_still(r, w)) != FBRL_OK)
        return st;
    st = rb_raw_send(r, w, line, print, 0);
    if (st == FBRL_OK && k == RB_LINE_CMD && cmd == FBRL_RAPL_HALT)
        r->moving = 0;
    return st;
}

/* ---- from C ---- */

fbrl_status fbrl_robot_fail(fbrl_robot *r, int code, const char *msg)
{
    if (!r)
        return FBRL_EINVAL;
    return rb_fail(r, code, msg);
}

/* The command that makes move m (its arguments in a[], m's numbers). */
static fbrl_status out_of(const fbrl_robot_move *m, rb_out *o, fbrl_rapl_arg *a, fbrl_loc *pt)
{
    memset(o, 0, sizeof *o);
    o->a = a;
    o->straight = m->straight;
    switch (m->kind) {
    case FBRL_ROBOT_MOVE_POSE:
        pt->x = m->v[0], pt->y = m->v[1], pt->z = m->v[2], pt->o = m->v[3], pt->a = m->v[4], pt->t = m->v[5];
        o->point = pt;
        o->cmd = m->dist != 0.0 ? FBRL_RAPL_APPRO : FBRL_RAPL_MOVE;
        a[1] = fbrl_rapl_real(m->dist);
        o->n = m->dist != 0.0 ? 2 : 1;
        return FBRL_OK;
    case FBRL_ROBOT_MOVE_DEPART:
        o->cmd = FBRL_RAPL_DEPART;
        a[0] = fbrl_rapl_real(m->dist);
        o->n = 1;
        return FBRL_OK;
    case FBRL_ROBOT_MOVE_JOG:
        o->cmd = FBRL_RAPL_JOG;
        o->straight = 0; /* always straight; JOG takes no ,S */
        for (int k = 0; k < 3; k++)
            a[k] = fbrl_rapl_real(m->v[k]);
        o->n = 3;
        return FBRL_OK;
    case FBRL_ROBOT_MOVE_JOINTS:
    case FBRL_ROBOT_MOVE_DJOINTS: /* MA MI take radians */
        o->cmd = m->kind == FBRL_ROBOT_MOVE_JOINTS ? FBRL_RAPL_MA : FBRL_RAPL_MI;
        return FBRL_OK; /* the axes: the caller knows them */
    case FBRL_ROBOT_MOVE_MOTOR:
        o->cmd = FBRL_RAPL_MOTOR;
        o->straight = 0;
        a[0] = fbrl_rapl_int((long)m->v[0]);
        a[1] = fbrl_rapl_int((long)m->v[1]);
        o->n = 2;
        return m->v[0] == (double)(long)m->v[0] && m->v[1] == (double)(long)m->v[1] ? FBRL_OK : FBRL_EINVAL;
    case FBRL_ROBOT_MOVE_READY:
    case FBRL_ROBOT_MOVE_HOME:
        o->cmd = m->kind == FBRL_ROBOT_MOVE_READY ? FBRL_RAPL_READY : FBRL_RAPL_HOME;
        o->straight = 0;
        return FBRL_OK;
    default: return FBRL_EINVAL;
    }
}

fbrl_status fbrl_robot_motion(fbrl_robot *r, const fbrl_robot_move *m, char *msg, size_t cap)
{
    char none[1];
    fbrl_rapl_arg a[FBRL_RAPL_ARM_AXES_MAX];
    fbrl_loc pt;
    rb_out o;
    rb_word w;
    fbrl_robot_move mv;
    if (msg && cap)
        msg[0] = '\0';
    if (!r || !m)
        return FBRL_EINVAL;
    if (r->c_msg)
        return FBRL_ESTATE;
    fbrl_status st = out_of(m, &o, a, &pt);
    if (st != FBRL_OK)
        return st;
    if (m->kind == FBRL_ROBOT_MOVE_JOINTS || m->kind == FBRL_ROBOT_MOVE_DJOINTS) {
        unsigned n = rb_naxes(r);
        for (unsigned k = 0; k < n && k < FBRL_RAPL_ARM_AXES_MAX && k < 6; k++)
            a[k] = fbrl_rapl_real(m->v[k] * (3.14159265358979323846 / 180.0));
        o.n = n < 6 ? n : 6;
    }
    memset(&w, 0, sizeof w);
    w.name = m->word ? m->word : "MOTION";
    mv = *m;
    r->c_msg = msg && cap ? msg : none;
    r->c_cap = msg && cap ? cap : sizeof none;
    r->c_code = 0;
    r->c_refused = 0;
    st = rb_motion(r, &w, &mv, &o);
    if (st != FBRL_OK) {
        int code = r->c_code;
        if (r->c_refused)
            st = FBRL_EGUARD;
        else if (code <= FBRL_VM_THROW_OF_STATUS(-1) && code >= FBRL_VM_THROW_OF_STATUS(FBRL_STATUS_MIN))
            st = (fbrl_status)(code - FBRL_VM_THROW_OF_STATUS(0));
        else
            st = FBRL_ETHROW;
        if (!code)
            snprintf(r->c_msg, r->c_cap, "%s: interrupted", w.name);
    }
    r->c_msg = NULL;
    return st;
}
