/* arm.c - kinematics of the emulated arm; see arm.h. */
#include "arm.h"
#include "sim_errors.h"

#include <math.h>

#define PI 3.14159265358979323846
#define RAD(d) ((d) * (PI / 180.0))
#define DEG(r) ((r) * (180.0 / PI))

const double fbrl_sim_arm_ppd[FBRL_SIM_ARM_AXES] = { 200.0, 200.0, 200.0, 44.44, 22.22 };
const double fbrl_sim_arm_min[FBRL_SIM_ARM_AXES] = { -175.0, 0.0, -130.0, -110.0, -180.0 };
const double fbrl_sim_arm_max[FBRL_SIM_ARM_AXES] = { 175.0, 110.0, 0.0, 110.0, 180.0 };
const double fbrl_sim_arm_speed[FBRL_SIM_ARM_AXES] = { 60.0, 60.0, 60.0, 180.0, 180.0 };
const double fbrl_sim_arm_ready[FBRL_SIM_ARM_AXES] = { 0.0, 90.0, -90.0, 0.0, 0.0 };

/* Joint angles a hair outside a limit (rounding of an exact target) count as inside. */
#define LIMIT_EPS 1e-9

double fbrl_sim_arm_wrap(double deg)
{
    double d = fmod(deg, 360.0);
    if (d > 180.0)
        d -= 360.0;
    else if (d <= -180.0)
        d += 360.0;
    return d;
}

void fbrl_sim_arm_fk(const double q[FBRL_SIM_ARM_AXES], double tool_len, double pose[6])
{
    double a2 = RAD(q[1]), a3 = RAD(q[1] + q[2]), p = RAD(q[1] + q[2] + q[3]);
    double tl = FBRL_SIM_ARM_FLANGE + tool_len;
    double r = FBRL_SIM_ARM_UPPER * cos(a2) + FBRL_SIM_ARM_FORE * cos(a3) + tl * cos(p);
    double z = FBRL_SIM_ARM_BASE_H + FBRL_SIM_ARM_UPPER * sin(a2) + FBRL_SIM_ARM_FORE * sin(a3)
             + tl * sin(p);
    pose[0] = r * cos(RAD(q[0]));
    pose[1] = r * sin(RAD(q[0]));
    pose[2] = z;
    pose[3] = q[0];
    pose[4] = fbrl_sim_arm_wrap(q[1] + q[2] + q[3]);
    pose[5] = q[4];
}

/* Solves with the waist at `waist` and the tool point at signed distance s
 * from the base axis along the waist direction. */
static int solve(const double pose[6], double tl, double waist, double s, double q[FBRL_SIM_ARM_AXES])
{
    const double l2 = FBRL_SIM_ARM_UPPER, l3 = FBRL_SIM_ARM_FORE;
    double p = RAD(pose[4]);
    /* The wrist pitch axis, in the arm's vertical plane. */
    double rw = s - tl * cos(p);
    double zw = pose[2] - FBRL_SIM_ARM_BASE_H - tl * sin(p);
    double c3 = (rw * rw + zw * zw - l2 * l2 - l3 * l3) / (2.0 * l2 * l3);
    double t3, t2;

    if (!isfinite(c3) || !isfinite(waist))
        return SIM_E_TRANSFORM;
    if (c3 > 1.0 || c3 < -1.0) {
        if (fabs(c3) > 1.0 + 1e-12)
            return SIM_E_TRANSFORM;
        c3 = c3 > 0 ? 1.0 : -1.0; /* a fully stretched arm is still reachable */
    }
    t3 = -acos(c3); /* elbow bends down: the only branch inside -130..0 */
    t2 = atan2(zw, rw) - atan2(l3 * sin(t3), l2 + l3 * cos(t3));
    q[0] = fbrl_sim_arm_wrap(waist);
    q[1] = DEG(t2);
    q[2] = DEG(t3);
    q[3] = fbrl_sim_arm_wrap(pose[4] - q[1] - q[2]);
    q[4] = fbrl_sim_arm_wrap(pose[5]);
    return fbrl_sim_arm_check(q);
}

int fbrl_sim_arm_ik(const double pose[6], double tool_len, double waist_hint,
                    double q[FBRL_SIM_ARM_AXES])
{
    double tl = FBRL_SIM_ARM_FLANGE + tool_len;
    double r = hypot(pose[0], pose[1]), alt[FBRL_SIM_ARM_AXES];
    double waist = r < 1e-9 ? waist_hint : DEG(atan2(pose[1], pose[0]));
    int e, i;

    if (!isfinite(r))
        return SIM_E_TRANSFORM;
    /* Reach forward: the waist points at the target. */
    e = solve(pose, tl, waist, r, q);
    if (e == 0)
        return 0;
    /* Reach backward over the shoulder: waist turned away, target behind the base axis. */
    if (solve(pose, tl, waist + 180.0, -r, alt) == 0) {
        for (i = 0; i < FBRL_SIM_ARM_AXES; i++)
            q[i] = alt[i];
        return 0;
    }
    return e;
}

int fbrl_sim_arm_check(const double q[FBRL_SIM_ARM_AXES])
{
    int i;
    for (i = 0; i < FBRL_SIM_ARM_AXES; i++) {
        if (!isfinite(q[i]) || q[i] < fbrl_sim_arm_min[i] - LIMIT_EPS
            || q[i] > fbrl_sim_arm_max[i] + LIMIT_EPS)
            return sim_error_joint(i);
    }
    return 0;
}

long fbrl_sim_arm_pulses(int axis, double deg)
{
    return lround(deg * fbrl_sim_arm_ppd[axis]);
}

double fbrl_sim_arm_degrees(int axis, long pulses)
{
    return (double)pulses / fbrl_sim_arm_ppd[axis];
}

void fbrl_sim_arm_lerp(const double a[6], const double b[6], double f, double out[6])
{
    int i;
    for (i = 0; i < 6; i++)
        out[i] = a[i] + (b[i] - a[i]) * f;
}

int fbrl_sim_arm_check_line(const double a[6], const double b[6], double tool_len,
                            double waist_hint)
{
    double d = sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1])
                    + (b[2] - a[2]) * (b[2] - a[2]));
    double ang = fabs(b[4] - a[4]) + fabs(b[5] - a[5]);
    int n = (int)ceil(d / 0.05 + ang / 0.5);
    double prev = waist_hint, q[FBRL_SIM_ARM_AXES], pose[6];
    int i;

    if (n < 20)
        n = 20;
    if (n > 100000)
        n = 100000;
    for (i = 0; i <= n; i++) {
        fbrl_sim_arm_lerp(a, b, (double)i / n, pose);
        if (fbrl_sim_arm_ik(pose, tool_len, prev, q) != 0)
            return SIM_E_STRAIGHT_LINE;
        /* A waist that jumps (next to the base axis, or from one reach to the other) is
         * not a line the arm can follow; the first sample is compared with the arm's waist. */
        if (fabs(fbrl_sim_arm_wrap(q[0] - prev)) > 20.0)
            return SIM_E_STRAIGHT_LINE;
        prev = q[0];
    }
    return 0;
}
