/* SPDX-License-Identifier: MIT */
/* sim_motion.c - the arm in motion: one segment at a time (joint-interpolated or
 * straight), evaluated from simulated time, so any readout at any moment shows
 * where the arm is. The kinematics are the library's (fbrl/arm.h); this file plans
 * and times. */
#include "sim_cmd.h"

#include <math.h>
#include <string.h>

double sim_tool_len(fbrl_sim *s) { return s->mem.tool_set ? s->mem.tool[2] : 0.0; }

static void pulses_to_joints(const fbrl_sim *s, const long p[FBRL_ARM_AXES_MAX], double q[FBRL_ARM_AXES_MAX])
{
    int i;
    for (i = 0; i < sim_naxes(s); i++)
        q[i] = fbrl_arm_degrees(s->arm.model, i, p[i]);
}

/* Location by token: pose always; joints too for a precision point (*is_prec). */
int sim_loc_value(fbrl_sim *s, const char *tok, double pose[6], double q[FBRL_ARM_AXES_MAX], int *is_prec)
{
    char name[SIM_NAME_MAX + 1];
    int prec, e = sim_name_parse(tok, &prec, name);
    sim_loc *l;
    if (e)
        return e;
    l = sim_loc_find(s, name, prec);
    if (!l)
        return SIM_E_LOCATION_UNDEFINED;
    *is_prec = prec;
    if (prec) {
        pulses_to_joints(s, l->p, q);
        fbrl_arm_fk(s->arm.model, q, sim_tool_len(s), pose);
    } else {
        memcpy(pose, l->v, sizeof l->v);
    }
    return 0;
}

int sim_arm_ik(const fbrl_arm *m, const double pose[6], double tool, const double *hint, double *q)
{
    int axis;
    fbrl_status st = fbrl_arm_ik(m, pose, tool, hint, q, &axis);
    return st == FBRL_OK ? 0 : axis >= 0 ? sim_error_joint(axis) : SIM_E_TRANSFORM;
}

int sim_arm_check(const fbrl_arm *m, const double *q)
{
    int axis;
    return fbrl_arm_check(m, q, &axis) == FBRL_OK ? 0 : sim_error_joint(axis);
}

void sim_joints_now(fbrl_sim *s, double q[FBRL_ARM_AXES_MAX])
{
    double f, pose[6];
    if (!s->arm.moving) {
        memcpy(q, s->arm.q, sizeof s->arm.q);
        return;
    }
    f = (sim_now(s) - s->arm.mt0) / (s->arm.mt1 - s->arm.mt0);
    if (f >= 1.0) {
        memcpy(q, s->arm.qt, sizeof s->arm.qt);
        return;
    }
    if (f < 0)
        f = 0;
    if (s->arm.straight) {
        fbrl_arm_lerp(s->arm.pa, s->arm.pb, f, pose);
        if (fbrl_arm_ik(s->arm.model, pose, sim_tool_len(s), s->arm.q, q, NULL) == FBRL_OK)
            return;
    }
    {
        int i;
        for (i = 0; i < sim_naxes(s); i++)
            q[i] = s->arm.q[i] + (s->arm.qt[i] - s->arm.q[i]) * f;
    }
}

double sim_extra_now(fbrl_sim *s)
{
    double f;
    if (!s->arm.xmoving)
        return s->arm.xpos;
    f = (sim_now(s) - s->arm.xt0) / (s->arm.xt1 - s->arm.xt0);
    if (f >= 1.0)
        return s->arm.xtarget;
    return s->arm.xpos + (s->arm.xtarget - s->arm.xpos) * (f < 0 ? 0 : f);
}

void sim_arm_update(fbrl_sim *s)
{
    double now = sim_now(s);
    if (s->arm.moving && now >= s->arm.mt1) {
        memcpy(s->arm.q, s->arm.qt, sizeof s->arm.q);
        s->arm.moving = 0;
    }
    if (s->arm.xmoving && now >= s->arm.xt1) {
        s->arm.xpos = s->arm.xtarget;
        s->arm.xmoving = 0;
    }
}

void sim_halt(fbrl_sim *s)
{
    double q[FBRL_ARM_AXES_MAX];
    sim_joints_now(s, q);
    memcpy(s->arm.q, q, sizeof q);
    s->arm.moving = 0;
    s->arm.xpos = sim_extra_now(s);
    s->arm.xmoving = 0;
    s->dirty = 1;
}

static double joint_time(fbrl_sim *s, const double a[FBRL_ARM_AXES_MAX], const double b[FBRL_ARM_AXES_MAX])
{
    double t = 0;
    int i;
    for (i = 0; i < sim_naxes(s); i++) {
        double ti = fabs(b[i] - a[i]) / (s->arm.model->speed[i] * s->arm.speed / 100.0);
        if (ti > t)
            t = ti;
    }
    return t;
}

static void begin(fbrl_sim *s, const double qt[FBRL_ARM_AXES_MAX], double t, int straight)
{
    memcpy(s->arm.qt, qt, sizeof s->arm.qt);
    s->arm.straight = straight;
    s->arm.mt0 = sim_now(s);
    s->arm.mt1 = s->arm.mt0 + t;
    s->arm.moving = t > 0;
    if (!s->arm.moving)
        memcpy(s->arm.q, qt, sizeof s->arm.q);
    s->dirty = 1;
}

/* Joint-interpolated move to joint angles; locked joints stay. */
int sim_move_joints(fbrl_sim *s, const double target[FBRL_ARM_AXES_MAX])
{
    double qt[FBRL_ARM_AXES_MAX];
    int i, e;
    for (i = 0; i < sim_naxes(s); i++)
        qt[i] = s->arm.locked[i] ? s->arm.q[i] : target[i];
    e = sim_arm_check(s->arm.model, qt);
    if (e)
        return e;
    {
        /* the work cell: the arm goes as far as the contact and stops there */
        double qs[FBRL_ARM_AXES_MAX], f;
        memcpy(qs, qt, sizeof qs);
        f = sim_cell_stop(s, sim_tool_len(s), qt, NULL, qs);
        begin(s, qs, joint_time(s, s->arm.q, qt) * (f < 1.0 ? f : 1.0), 0);
        s->arm.collide = f < 1.0;
    }
    return 0;
}

int sim_pose_joints(fbrl_sim *s, const double pose[6], double q[FBRL_ARM_AXES_MAX])
{
    int e = sim_arm_ik(s->arm.model, pose, sim_tool_len(s), s->arm.q, q);
    return e ? e : sim_arm_check(s->arm.model, q);
}

/* Joint-interpolated move to a cartesian pose. */
int sim_move_pose(fbrl_sim *s, const double pose[6])
{
    double q[FBRL_ARM_AXES_MAX];
    int e = sim_pose_joints(s, pose, q);
    return e ? e : sim_move_joints(s, q);
}

/* Straight-line move to a pose (target joints qt if known, else from IK). */
int sim_move_line(fbrl_sim *s, const double pose[6], const double *qknown)
{
    double qt[FBRL_ARM_AXES_MAX], from[6], t, d;
    int e, i;
    if (qknown) {
        memcpy(qt, qknown, sizeof qt);
        e = sim_arm_check(s->arm.model, qt);
    } else {
        e = sim_pose_joints(s, pose, qt);
    }
    if (e)
        return e;
    for (i = 0; i < sim_naxes(s); i++)
        if (s->arm.locked[i] && fabs(qt[i] - s->arm.q[i]) > 1e-9)
            return SIM_E_STRAIGHT_LINE;
    fbrl_arm_fk(s->arm.model, s->arm.q, sim_tool_len(s), from);
    fbrl_arm_fk(s->arm.model, qt, sim_tool_len(s), s->arm.pb);
    if (fbrl_arm_check_line(s->arm.model, from, s->arm.pb, sim_tool_len(s), s->arm.q) != FBRL_OK)
        return SIM_E_STRAIGHT_LINE;
    {
        /* the line must end in the target's own configuration (a precision point may
         * hold the other reach) */
        double qe[FBRL_ARM_AXES_MAX];
        if (fbrl_arm_ik(s->arm.model, s->arm.pb, sim_tool_len(s), s->arm.q, qe, NULL) != FBRL_OK ||
            fabs(fbrl_arm_wrap(qe[0] - qt[0])) > 1e-6)
            return SIM_E_STRAIGHT_LINE;
    }
    memcpy(s->arm.pa, from, sizeof from);
    d = sqrt((s->arm.pb[0] - from[0]) * (s->arm.pb[0] - from[0]) +
             (s->arm.pb[1] - from[1]) * (s->arm.pb[1] - from[1]) +
             (s->arm.pb[2] - from[2]) * (s->arm.pb[2] - from[2]));
    t = d / (s->arm.model->linear * s->arm.speed / 100.0);
    if (joint_time(s, s->arm.q, qt) > t)
        t = joint_time(s, s->arm.q, qt);
    {
        /* the work cell: the line ends at the contact */
        double qs[FBRL_ARM_AXES_MAX], f;
        memcpy(qs, qt, sizeof qs);
        f = sim_cell_stop(s, sim_tool_len(s), qt, s->arm.pb, qs);
        if (f < 1.0) {
            double end[6];
            fbrl_arm_lerp(from, s->arm.pb, f, end);
            memcpy(s->arm.pb, end, sizeof end);
            begin(s, qs, t * f, 1);
            s->arm.collide = 1;
            return 0;
        }
    }
    begin(s, qt, t, 1);
    s->arm.collide = 0;
    return 0;
}

void sim_current_pose(fbrl_sim *s, double pose[6])
{
    double q[FBRL_ARM_AXES_MAX];
    sim_joints_now(s, q);
    fbrl_arm_fk(s->arm.model, q, sim_tool_len(s), pose);
}
