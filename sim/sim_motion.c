/* sim_motion.c - the arm in motion: one segment at a time (joint-interpolated or
 * straight), evaluated from simulated time, so any readout at any moment shows
 * where the arm is. The kinematics are arm.c's; this file plans and times. */
#include "sim_cmd.h"

#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846

double sim_tool_len(fbrl_sim *s)
{
    return s->tool_set ? s->tool[2] : 0.0;
}

static void pulses_to_joints(const long p[NAXES], double q[NAXES])
{
    int i;
    for (i = 0; i < NAXES; i++)
        q[i] = fbrl_sim_arm_degrees(i, p[i]);
}

/* Location by token: pose always; joints too for a precision point (*is_prec). */
int sim_loc_value(fbrl_sim *s, const char *tok, double pose[6], double q[NAXES], int *is_prec)
{
    char name[SIM_NAME_MAX + 1];
    int prec, e = sim_name_parse(tok, &prec, name);
    sim_loc *l;
    if (e)
        return e;
    l = sim_loc_find(s, name, prec);
    if (!l)
        return 11;
    *is_prec = prec;
    if (prec) {
        pulses_to_joints(l->p, q);
        fbrl_sim_arm_fk(q, sim_tool_len(s), pose);
    } else {
        memcpy(pose, l->v, sizeof l->v);
    }
    return 0;
}


void sim_joints_now(fbrl_sim *s, double q[NAXES])
{
    double f, pose[6];
    if (!s->moving) {
        memcpy(q, s->q, sizeof s->q);
        return;
    }
    f = (sim_now(s) - s->mt0) / (s->mt1 - s->mt0);
    if (f >= 1.0) {
        memcpy(q, s->qt, sizeof s->qt);
        return;
    }
    if (f < 0)
        f = 0;
    if (s->straight) {
        fbrl_sim_arm_lerp(s->pa, s->pb, f, pose);
        if (fbrl_sim_arm_ik(pose, sim_tool_len(s), s->q[0], q) == 0)
            return;
    }
    {
        int i;
        for (i = 0; i < NAXES; i++)
            q[i] = s->q[i] + (s->qt[i] - s->q[i]) * f;
    }
}

double sim_extra_now(fbrl_sim *s)
{
    double f;
    if (!s->xmoving)
        return s->xpos;
    f = (sim_now(s) - s->xt0) / (s->xt1 - s->xt0);
    if (f >= 1.0)
        return s->xtarget;
    return s->xpos + (s->xtarget - s->xpos) * (f < 0 ? 0 : f);
}

void sim_arm_update(fbrl_sim *s)
{
    double now = sim_now(s);
    if (s->moving && now >= s->mt1) {
        memcpy(s->q, s->qt, sizeof s->q);
        s->moving = 0;
    }
    if (s->xmoving && now >= s->xt1) {
        s->xpos = s->xtarget;
        s->xmoving = 0;
    }
}

void sim_halt(fbrl_sim *s)
{
    double q[NAXES];
    sim_joints_now(s, q);
    memcpy(s->q, q, sizeof q);
    s->moving = 0;
    s->xpos = sim_extra_now(s);
    s->xmoving = 0;
    s->dirty = 1;
}

static double joint_time(fbrl_sim *s, const double a[NAXES], const double b[NAXES])
{
    double t = 0;
    int i;
    for (i = 0; i < NAXES; i++) {
        double ti = fabs(b[i] - a[i]) / (fbrl_sim_arm_speed[i] * s->speed / 100.0);
        if (ti > t)
            t = ti;
    }
    return t;
}

static void begin(fbrl_sim *s, const double qt[NAXES], double t, int straight)
{
    memcpy(s->qt, qt, sizeof s->qt);
    s->straight = straight;
    s->mt0 = sim_now(s);
    s->mt1 = s->mt0 + t;
    s->moving = t > 0;
    if (!s->moving)
        memcpy(s->q, qt, sizeof s->q);
    s->dirty = 1;
}

/* Joint-interpolated move to joint angles; locked joints stay. */
int sim_move_joints(fbrl_sim *s, const double target[NAXES])
{
    double qt[NAXES];
    int i, e;
    for (i = 0; i < NAXES; i++)
        qt[i] = s->locked[i] ? s->q[i] : target[i];
    e = fbrl_sim_arm_check(qt);
    if (e)
        return e;
    begin(s, qt, joint_time(s, s->q, qt), 0);
    return 0;
}

int sim_pose_joints(fbrl_sim *s, const double pose[6], double q[NAXES])
{
    int e = fbrl_sim_arm_ik(pose, sim_tool_len(s), s->q[0], q);
    return e ? e : fbrl_sim_arm_check(q);
}

/* Joint-interpolated move to a cartesian pose. */
int sim_move_pose(fbrl_sim *s, const double pose[6])
{
    double q[NAXES];
    int e = sim_pose_joints(s, pose, q);
    return e ? e : sim_move_joints(s, q);
}

/* Straight-line move to a pose (target joints qt if known, else from IK). */
int sim_move_line(fbrl_sim *s, const double pose[6], const double *qknown)
{
    double qt[NAXES], from[6], t, d;
    int e, i;
    if (qknown) {
        memcpy(qt, qknown, sizeof qt);
        e = fbrl_sim_arm_check(qt);
    } else {
        e = sim_pose_joints(s, pose, qt);
    }
    if (e)
        return e;
    for (i = 0; i < NAXES; i++)
        if (s->locked[i] && fabs(qt[i] - s->q[i]) > 1e-9)
            return 68;
    fbrl_sim_arm_fk(s->q, sim_tool_len(s), from);
    fbrl_sim_arm_fk(qt, sim_tool_len(s), s->pb);
    if (fbrl_sim_arm_check_line(from, s->pb, sim_tool_len(s), s->q[0]) != 0)
        return 68;
    {
        /* the line must end in the target's own configuration (a precision point may
         * hold the other reach) */
        double qe[NAXES];
        if (fbrl_sim_arm_ik(s->pb, sim_tool_len(s), s->q[0], qe) != 0
            || fabs(fbrl_sim_arm_wrap(qe[0] - qt[0])) > 1e-6)
            return 68;
    }
    memcpy(s->pa, from, sizeof from);
    d = sqrt((s->pb[0] - from[0]) * (s->pb[0] - from[0]) + (s->pb[1] - from[1]) * (s->pb[1] - from[1])
             + (s->pb[2] - from[2]) * (s->pb[2] - from[2]));
    t = d / (FBRL_SIM_ARM_LINEAR * s->speed / 100.0);
    if (joint_time(s, s->q, qt) > t)
        t = joint_time(s, s->q, qt);
    begin(s, qt, t, 1);
    return 0;
}

void sim_current_pose(fbrl_sim *s, double pose[6])
{
    double q[NAXES];
    sim_joints_now(s, q);
    fbrl_sim_arm_fk(q, sim_tool_len(s), pose);
}

/* The point dist back along a pose's tool axis. */
void sim_back_off(const double pose[6], double waist, double dist, double out[6])
{
    double w = (hypot(pose[0], pose[1]) > 1e-9 ? atan2(pose[1], pose[0]) : waist * PI / 180.0);
    double p = pose[4] * PI / 180.0;
    memcpy(out, pose, 6 * sizeof *out);
    out[0] -= dist * cos(p) * cos(w);
    out[1] -= dist * cos(p) * sin(w);
    out[2] -= dist * sin(p);
}
