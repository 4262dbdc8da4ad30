/* SPDX-License-Identifier: MIT */
/* sim_h_motion.c - the commands that move the arm or decide whether it may move
 * (MOVE, APPRO, DEPART, JOG, JOINT, MOTOR, MI/MA, READY, FINISH, HALT, SPEED,
 * HOME, LIMP/LOCK, ARM, the extra axis). They share the motion model's checks:
 * a command either starts a motion that is valid along its whole path or
 * changes nothing and returns the RAPL error. */
#include "sim_cmd.h"

#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846

int sim_h_align(fbrl_sim *s, args *a, int *b)
{
    double pose[6];
    int e = sim_args_want(a, 0, 0);
    (void)b;
    if (e)
        return e;
    sim_current_pose(s, pose);
    pose[4] = pose[4] < -45.0 ? -90.0 : pose[4] > 45.0 ? 90.0 : 0.0;
    return sim_move_pose(s, pose);
}

int sim_h_appro(fbrl_sim *s, args *a, int *b)
{
    double pose[6], q[FBRL_ARM_AXES_MAX], t[6], d;
    int S = sim_args_take_s(a, 2), prec, e = sim_args_want(a, 2, 2);
    (void)b;
    if (e || (e = sim_loc_value(s, a->v[0], pose, q, &prec)) || (e = sim_arg_len(s, a, 1, &d)))
        return e;
    fbrl_arm_back_off(s->arm.model, pose, prec ? q[0] : s->arm.q[0], d, t);
    return S ? sim_move_line(s, t, NULL) : sim_move_pose(s, t);
}

int sim_h_depart(fbrl_sim *s, args *a, int *b)
{
    double pose[6], t[6], d;
    int S = sim_args_take_s(a, 1), e = sim_args_want(a, 1, 1);
    (void)b;
    if (e || (e = sim_arg_len(s, a, 0, &d)))
        return e;
    sim_current_pose(s, pose);
    fbrl_arm_back_off(s->arm.model, pose, s->arm.q[0], d, t);
    return S ? sim_move_line(s, t, NULL) : sim_move_pose(s, t);
}

int sim_h_move(fbrl_sim *s, args *a, int *b)
{
    double pose[6], q[FBRL_ARM_AXES_MAX];
    int S = sim_args_take_s(a, 1), prec, e = sim_args_want(a, 1, 1);
    (void)b;
    if (e || (e = sim_loc_value(s, a->v[0], pose, q, &prec)))
        return e;
    if (S)
        return sim_move_line(s, pose, prec ? q : NULL);
    return prec ? sim_move_joints(s, q) : sim_move_pose(s, pose);
}

int sim_h_jog(fbrl_sim *s, args *a, int *b)
{
    double pose[6], d[3];
    int i, e = sim_args_want(a, 3, 3);
    (void)b;
    for (i = 0; !e && i < 3; i++)
        e = sim_arg_len(s, a, i, &d[i]);
    if (e)
        return e;
    sim_current_pose(s, pose);
    for (i = 0; i < 3; i++)
        pose[i] += d[i];
    return sim_move_line(s, pose, NULL);
}

int sim_h_joint(fbrl_sim *s, args *a, int *b)
{
    double q[FBRL_ARM_AXES_MAX], d;
    long j;
    int e = sim_args_want(a, 2, 2);
    (void)b;
    if (e || (e = sim_arg_axis(s, a, 0, sim_naxes(s), &j)) || (e = sim_arg_num(s, a, 1, &d)))
        return e;
    memcpy(q, s->arm.q, sizeof q);
    q[j - 1] += d;
    return sim_move_joints(s, q);
}

int sim_h_motor(fbrl_sim *s, args *a, int *b)
{
    long m, p;
    int e;
    (void)b;
    if (a->n > 2)
        return SIM_E_NOT_AVAILABLE;
    if ((e = sim_args_want(a, 2, 2)) || (e = sim_arg_axis(s, a, 0, sim_naxes(s) + 1, &m)) ||
        (e = sim_arg_int(s, a, 1, &p)))
        return e;
    if (m == sim_naxes(s) + 1) {
        s->arm.xtarget = s->arm.xpos + (double)p;
        s->arm.xt0 = sim_now(s);
        s->arm.xt1 = s->arm.xt0 + fabs((double)p) / (SIM_EXTRA_RATE * s->arm.speed / 100.0);
        s->arm.xmoving = p != 0;
        s->dirty = 1;
        return 0;
    } else {
        double q[FBRL_ARM_AXES_MAX];
        memcpy(q, s->arm.q, sizeof q);
        q[m - 1] += fbrl_arm_degrees(s->arm.model, (int)m - 1, p);
        return sim_move_joints(s, q);
    }
}

static int h_mi_ma(fbrl_sim *s, args *a, int rel)
{
    double q[FBRL_ARM_AXES_MAX], pose[6];
    int S = sim_args_take_s(a, sim_naxes(s)), e = sim_args_want(a, sim_naxes(s), sim_naxes(s)), i;
    for (i = 0; !e && i < sim_naxes(s); i++) {
        double r;
        e = sim_arg_num(s, a, i, &r);
        q[i] = (rel ? s->arm.q[i] : 0.0) + r * 180.0 / PI;
    }
    if (e)
        return e;
    if (!S)
        return sim_move_joints(s, q);
    if ((e = sim_arm_check(s->arm.model, q)))
        return e;
    fbrl_arm_fk(s->arm.model, q, sim_tool_len(s), pose);
    return sim_move_line(s, pose, q);
}

int sim_h_mi(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return h_mi_ma(s, a, 1);
}

int sim_h_ma(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return h_mi_ma(s, a, 0);
}

int sim_h_ready(fbrl_sim *s, args *a, int *b)
{
    int e = sim_args_want(a, 0, 0);
    (void)b;
    if (e)
        return e;
    memset(s->arm.locked, 0, sizeof s->arm.locked);
    return sim_move_joints(s, s->arm.model->ready);
}

int sim_h_finish(fbrl_sim *s, args *a, int *b)
{
    int e = sim_args_want(a, 0, 0);
    if (!e && (s->arm.moving || s->arm.xmoving))
        *b = 1;
    return e;
}

int sim_h_halt(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    if (a->n)
        return SIM_E_NOT_AVAILABLE;
    sim_halt(s);
    return 0;
}

int sim_h_speed(fbrl_sim *s, args *a, int *b)
{
    double v;
    int e = sim_args_want(a, 1, 1);
    (void)b;
    if (e || (e = sim_arg_num(s, a, 0, &v)))
        return e;
    if (v > 100.0)
        return SIM_E_ARG_TOO_BIG;
    if (v <= 0.0)
        return SIM_E_ILLEGAL_ARG;
    s->arm.speed = v;
    s->dirty = 1;
    return 0;
}

int sim_h_home(fbrl_sim *s, args *a, int *b)
{
    int e = sim_args_want(a, 0, 0);
    (void)b;
    if (e)
        return e;
    if (!s->arm.power)
        return SIM_E_POWER_OFF;
    s->arm.homed = 1;
    return 0;
}

/* Lists of axis numbers for LIMP, LOCK, UNLOCK: flags[i] = on. */
static int axis_list(fbrl_sim *s, args *a, int *flags, int on, int empty_all)
{
    int i, sel[FBRL_ARM_AXES_MAX] = {0};
    if (a->n == 0) {
        if (!empty_all)
            return SIM_E_ARG_MISSING;
        for (i = 0; i < sim_naxes(s); i++)
            sel[i] = 1;
    }
    for (i = 0; i < a->n; i++) {
        long ax;
        int e = sim_arg_axis(s, a, i, sim_naxes(s), &ax);
        if (e)
            return e;
        sel[ax - 1] = 1;
    }
    for (i = 0; i < sim_naxes(s); i++)
        if (sel[i])
            flags[i] = on;
    return 0;
}

int sim_h_limp(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    if (s->arm.moving)
        sim_halt(s);
    return axis_list(s, a, s->arm.limp, 1, 1);
}

int sim_h_nolimp(fbrl_sim *s, args *a, int *b)
{
    int e = sim_args_want(a, 0, 0);
    (void)b;
    if (!e)
        memset(s->arm.limp, 0, sizeof s->arm.limp);
    return e;
}

int sim_h_lock(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return axis_list(s, a, s->arm.locked, 1, 0);
}

int sim_h_unlock(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return axis_list(s, a, s->arm.locked, 0, 1);
}

int sim_h_arm(fbrl_sim *s, args *a, int *b)
{
    int e = sim_args_want(a, 1, 1);
    (void)b;
    if (e)
        return e;
    if (!strcmp(a->v[0], "OFF")) {
        sim_halt(s);
        s->arm.power = 0;
    } else if (!strcmp(a->v[0], "ON")) {
        s->arm.power = 1;
    } else {
        return SIM_E_ILLEGAL_ARG;
    }
    return 0;
}

/* ENABLE ARM / DISABLE ARM (S1 /176 /177 "ENABLE [item]"; S2 sends ENABLE ARM): arm
 * power on / off, like ARM ON / OFF [D]. Other items are documented forms fbrlsim
 * does not have: 066. */
static int h_enable(fbrl_sim *s, args *a, int on)
{
    int e = sim_args_want(a, 1, 1);
    if (e)
        return e;
    if (strcmp(a->v[0], "ARM"))
        return SIM_E_NOT_AVAILABLE;
    if (!on)
        sim_halt(s);
    s->arm.power = on;
    return 0;
}

int sim_h_enable(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return h_enable(s, a, 1);
}

int sim_h_disable(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return h_enable(s, a, 0);
}

/* ONPOWER: waits until arm power is on (S3: "blocks until motors come on"). */
int sim_h_onpower(fbrl_sim *s, args *a, int *b)
{
    int e = sim_args_want(a, 0, 0);
    if (!e && !s->arm.power)
        *b = 1;
    return e;
}

static int h_xaxis(fbrl_sim *s, args *a, int which, int *b)
{
    long ax;
    int e = sim_args_want(a, 1, 1);
    (void)b;
    if (e || (e = sim_arg_axis(s, a, 0, sim_naxes(s) + 1, &ax)))
        return e;
    if (ax != sim_naxes(s) + 1)
        return SIM_E_BAD_AXIS;
    if (which == 0) { /* XCAL */
        s->arm.xhome = sim_extra_now(s);
    } else if (which == 1) { /* XHOME */
        if (s->arm.xmoving) {
            *b = 1;
            return 0;
        }
        if (!s->arm.power)
            return SIM_E_POWER_OFF;
        s->arm.xtarget = s->arm.xhome;
        s->arm.xt0 = sim_now(s);
        s->arm.xt1 = s->arm.xt0 + fabs(s->arm.xhome - s->arm.xpos) / (SIM_EXTRA_RATE * s->arm.speed / 100.0);
        s->arm.xmoving = s->arm.xhome != s->arm.xpos;
        s->arm.xhomed = 1;
    } else { /* XZERO */
        if (s->arm.xmoving)
            sim_halt(s);
        s->arm.xpos = 0;
    }
    s->dirty = 1;
    return 0;
}

int sim_h_xcal(fbrl_sim *s, args *a, int *b) { return h_xaxis(s, a, 0, b); }

int sim_h_xhome(fbrl_sim *s, args *a, int *b) { return h_xaxis(s, a, 1, b); }

int sim_h_xzero(fbrl_sim *s, args *a, int *b) { return h_xaxis(s, a, 2, b); }
