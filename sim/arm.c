/* SPDX-License-Identifier: MIT */
/* arm.c - the emulated arms as data, and their kinematics; see arm.h. Sources of
 * the numbers: docs/fbrlsim.md ("The arm models"). */
#include "arm.h"
#include "sim_errors.h"

#include <ctype.h>
#include <math.h>
#include <string.h>

#define PI     3.14159265358979323846
#define RAD(d) ((d) * (PI / 180.0))
#define DEG(r) ((r) * (180.0 / PI))
#define MM(x)  ((x) / 25.4)

const fbrl_sim_model fbrl_sim_models[] = {
    /* CRS A255 (DESIGN 6; reference/rapl-research.md 3.1): 10 + 10 + 10 in, 2 in to the flange. */
    {"A255",
     5,
     FBRL_SIM_KIN_5R,
     10.0,
     10.0,
     10.0,
     2.0,
     19.685,
     {200.0, 200.0, 200.0, 44.44, 22.22},
     {-175.0, 0.0, -130.0, -110.0, -180.0},
     {175.0, 110.0, 0.0, 110.0, 180.0},
     {60.0, 60.0, 60.0, 180.0, 180.0},
     {0.0, 90.0, -90.0, 0.0, 0.0}},
    /* CRS A465: DH d1 330, a2 305, d4 330, d6 76 mm; limits and speeds as published
     * with the CRS A465 models of ReaK (rapl-research.md 3.3, S12). Pulses per degree
     * are not published: [D] 1000-count encoders behind 100:1 (J1-J3) and 50:1 (J4-J6). */
    {"A465",
     6,
     FBRL_SIM_KIN_6R,
     MM(330.0),
     MM(305.0),
     MM(330.0),
     MM(76.0),
     19.685,
     {277.78, 277.78, 277.78, 138.89, 138.89, 138.89},
     {-175.0, -90.0, -110.0, -180.0, -105.0, -180.0},
     {175.0, 90.0, 110.0, 180.0, 105.0, 180.0},
     {180.0, 180.0, 180.0, 171.0, 173.0, 171.0},
     {0.0, 0.0, 90.0, 0.0, 0.0, 0.0}},
};
const int fbrl_sim_nmodels = (int)(sizeof fbrl_sim_models / sizeof fbrl_sim_models[0]);

/* Joint angles a hair outside a limit (rounding of an exact target) count as inside. */
#define LIMIT_EPS  1e-9
#define AXIS_EPS   1e-9  /* in: closer to the base axis than this, the waist is free */
#define WRIST_EPS  1e-9  /* sin of the wrist bend below which the two rolls are one */
#define REACH_EPS  1e-12 /* a fully stretched arm is still reachable */
#define LINE_STEP  0.05  /* in between the samples of a straight line */
#define LINE_ASTEP 0.5   /* degrees of orientation between the samples */
#define LINE_MIN   20
#define LINE_MAX   100000
#define LINE_JUMP  20.0 /* degrees a joint may move between two samples */

const fbrl_sim_model *fbrl_sim_model_find(const char *name)
{
    int i;
    for (i = 0; name && i < fbrl_sim_nmodels; i++) {
        const char *a = fbrl_sim_models[i].name, *b = name;
        while (*a && toupper((unsigned char)*b) == *a) {
            a++;
            b++;
        }
        if (!*a && !*b)
            return &fbrl_sim_models[i];
    }
    return NULL;
}

double fbrl_sim_arm_wrap(double deg)
{
    double d = fmod(deg, 360.0);
    if (d > 180.0)
        d -= 360.0;
    else if (d <= -180.0)
        d += 360.0;
    return d;
}

/* ---- 3x3 rotations --------------------------------------------------- */

typedef double mat3[3][3];

static void mul(mat3 a, mat3 b, mat3 out)
{
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++)
            out[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
}

static void rot(int axis, double deg, mat3 r)
{
    double c = cos(RAD(deg)), s = sin(RAD(deg));
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++)
            r[i][j] = i == j;
    if (axis == 0) {
        r[1][1] = c, r[1][2] = -s, r[2][1] = s, r[2][2] = c;
    } else if (axis == 1) {
        r[0][0] = c, r[0][2] = s, r[2][0] = -s, r[2][2] = c;
    } else {
        r[0][0] = c, r[0][1] = -s, r[1][0] = s, r[1][1] = c;
    }
}

/* Orientation of a pose: Rz(yaw) Ry(-pitch) Rx(roll). */
static void pose_rot(const double pose[6], mat3 r)
{
    mat3 a, b, t;
    rot(2, pose[3], a);
    rot(1, -pose[4], b);
    mul(a, b, t);
    rot(0, pose[5], a);
    mul(t, a, r);
}

/* yaw, pitch, roll of an orientation; yaw_free when the tool axis is vertical. */
static void rot_pose(mat3 r, double yaw_free, double pose[6])
{
    double h = hypot(r[0][0], r[1][0]);
    mat3 a, b, t, m;
    pose[4] = DEG(atan2(r[2][0], h));
    pose[3] = h > WRIST_EPS ? DEG(atan2(r[1][0], r[0][0])) : fbrl_sim_arm_wrap(yaw_free);
    rot(1, pose[4], a);
    rot(2, -pose[3], b);
    mul(a, b, t);
    mul(t, r, m); /* = Rx(roll) */
    pose[5] = DEG(atan2(m[2][1], m[1][1]));
}

/* ---- 5R: the A255 ---------------------------------------------------- */

static void fk5(const fbrl_sim_model *m, const double *q, double tool_len, double pose[6])
{
    double a2 = RAD(q[1]), a3 = RAD(q[1] + q[2]), p = RAD(q[1] + q[2] + q[3]);
    double tl = m->flange + tool_len;
    double r = m->upper * cos(a2) + m->fore * cos(a3) + tl * cos(p);
    double z = m->base_h + m->upper * sin(a2) + m->fore * sin(a3) + tl * sin(p);
    pose[0] = r * cos(RAD(q[0]));
    pose[1] = r * sin(RAD(q[0]));
    pose[2] = z;
    pose[3] = q[0];
    pose[4] = fbrl_sim_arm_wrap(q[1] + q[2] + q[3]);
    pose[5] = q[4];
}

/* Solves with the waist at `waist` and the tool point at signed distance s
 * from the base axis along the waist direction. */
static int solve5(const fbrl_sim_model *m, const double pose[6], double tl, double waist, double s, double *q)
{
    const double l2 = m->upper, l3 = m->fore;
    double p = RAD(pose[4]);
    /* The wrist pitch axis, in the arm's vertical plane. */
    double rw = s - tl * cos(p);
    double zw = pose[2] - m->base_h - tl * sin(p);
    double c3 = (rw * rw + zw * zw - l2 * l2 - l3 * l3) / (2.0 * l2 * l3);
    double t3, t2;

    if (!isfinite(c3) || !isfinite(waist))
        return SIM_E_TRANSFORM;
    if (c3 > 1.0 || c3 < -1.0) {
        if (fabs(c3) > 1.0 + REACH_EPS)
            return SIM_E_TRANSFORM;
        c3 = c3 > 0 ? 1.0 : -1.0;
    }
    t3 = -acos(c3); /* elbow bends down: the only branch inside -130..0 */
    t2 = atan2(zw, rw) - atan2(l3 * sin(t3), l2 + l3 * cos(t3));
    q[0] = fbrl_sim_arm_wrap(waist);
    q[1] = DEG(t2);
    q[2] = DEG(t3);
    q[3] = fbrl_sim_arm_wrap(pose[4] - q[1] - q[2]);
    q[4] = fbrl_sim_arm_wrap(pose[5]);
    return fbrl_sim_arm_check(m, q);
}

static int ik5(const fbrl_sim_model *m, const double pose[6], double tool_len, const double *hint, double *q)
{
    double tl = m->flange + tool_len;
    double r = hypot(pose[0], pose[1]), alt[FBRL_SIM_ARM_MAX_AXES];
    double waist = r < AXIS_EPS ? hint[0] : DEG(atan2(pose[1], pose[0]));
    int e;

    if (!isfinite(r))
        return SIM_E_TRANSFORM;
    /* Reach forward: the waist points at the target. */
    e = solve5(m, pose, tl, waist, r, q);
    if (e == 0)
        return 0;
    /* Reach backward over the shoulder: waist turned away, target behind the base axis. */
    if (solve5(m, pose, tl, waist + 180.0, -r, alt) == 0) {
        memcpy(q, alt, (size_t)m->naxes * sizeof *q);
        return 0;
    }
    return e;
}

/* ---- 6R: the A465 ---------------------------------------------------- */

/* The frame at the wrist centre before the wrist joints: x along the forearm,
 * y horizontal across the arm's plane. phi = forearm angle from vertical. */
static void forearm_rot(double waist, double phi, mat3 r)
{
    double cw = cos(RAD(waist)), sw = sin(RAD(waist)), cp = cos(RAD(phi)), sp = sin(RAD(phi));
    /* x3 = sp e_r + cp e_z, y3 = e_y, z3 = sp e_z - cp e_r */
    r[0][0] = sp * cw, r[1][0] = sp * sw, r[2][0] = cp;
    r[0][1] = -sw, r[1][1] = cw, r[2][1] = 0.0;
    r[0][2] = -cp * cw, r[1][2] = -cp * sw, r[2][2] = sp;
}

/* Wrist: Rx(q4) Ry(q5) Rx(q6). */
static void wrist_rot(const double *q, mat3 r)
{
    mat3 a, b, t;
    rot(0, q[3], a);
    rot(1, q[4], b);
    mul(a, b, t);
    rot(0, q[5], a);
    mul(t, a, r);
}

static void fk6(const fbrl_sim_model *m, const double *q, double tool_len, double pose[6])
{
    double t2 = RAD(q[1]), phi = q[1] + q[2], w = RAD(q[0]);
    double s = m->upper * sin(t2) + m->fore * sin(RAD(phi));
    double z = m->base_h + m->upper * cos(t2) + m->fore * cos(RAD(phi));
    double tl = m->flange + tool_len;
    mat3 r03, r36, r;
    forearm_rot(q[0], phi, r03);
    wrist_rot(q, r36);
    mul(r03, r36, r);
    pose[0] = s * cos(w) + tl * r[0][0];
    pose[1] = s * sin(w) + tl * r[1][0];
    pose[2] = z + tl * r[2][0];
    rot_pose(r, q[0], pose);
}

/* The wrist joints for a desired wrist rotation m36: the two solutions (bend
 * positive and negative), nearer to hint first. Returns how many (2, or 1 when
 * the wrist is straight and the rolls are one: then q4 keeps hint's). */
static int wrist_solve(mat3 m36, const double *hint, double out[2][3])
{
    double c5 = m36[0][0], s5 = sqrt(fmax(0.0, 1.0 - c5 * c5));
    if (s5 < WRIST_EPS) {
        double sum = DEG(atan2(m36[2][1], m36[1][1]));
        out[0][0] = fbrl_sim_arm_wrap(hint[3]);
        out[0][1] = c5 > 0 ? 0.0 : 180.0;
        /* Rx(a) Ry(180) Rx(c) = Ry(180) Rx(c - a) */
        out[0][2] = fbrl_sim_arm_wrap(c5 > 0 ? sum - out[0][0] : out[0][0] - sum);
        return 1;
    }
    out[0][1] = DEG(atan2(s5, c5));
    out[0][0] = DEG(atan2(m36[1][0], -m36[2][0]));
    out[0][2] = DEG(atan2(m36[0][1], m36[0][2]));
    out[1][1] = -out[0][1];
    out[1][0] = fbrl_sim_arm_wrap(out[0][0] + 180.0);
    out[1][2] = fbrl_sim_arm_wrap(out[0][2] + 180.0);
    if (fabs(fbrl_sim_arm_wrap(out[1][0] - hint[3])) < fabs(fbrl_sim_arm_wrap(out[0][0] - hint[3]))) {
        double t[3];
        memcpy(t, out[0], sizeof t);
        memcpy(out[0], out[1], sizeof t);
        memcpy(out[1], t, sizeof t);
    }
    return 2;
}

static int ik6(const fbrl_sim_model *m, const double pose[6], double tool_len, const double *hint, double *q)
{
    double tl = m->flange + tool_len, wx, wy, wz, rxy, first[FBRL_SIM_ARM_MAX_AXES];
    int reach, elbow, first_err = 0;
    mat3 r;

    for (reach = 0; reach < 6; reach++)
        if (!isfinite(pose[reach]))
            return SIM_E_TRANSFORM;
    pose_rot(pose, r);
    wx = pose[0] - tl * r[0][0];
    wy = pose[1] - tl * r[1][0];
    wz = pose[2] - tl * r[2][0] - m->base_h;
    rxy = hypot(wx, wy);
    for (reach = 0; reach < 2; reach++) {
        double waist = rxy < AXIS_EPS ? hint[0] : DEG(atan2(wy, wx));
        double s = reach ? -rxy : rxy;
        double u = m->upper, f = m->fore;
        double c3 = (s * s + wz * wz - u * u - f * f) / (2.0 * u * f);
        if (reach)
            waist += 180.0;
        if (!isfinite(c3) || fabs(c3) > 1.0 + REACH_EPS)
            return SIM_E_TRANSFORM;
        c3 = fmax(-1.0, fmin(1.0, c3));
        for (elbow = 0; elbow < 2; elbow++) {
            double t3 = elbow ? -acos(c3) : acos(c3);
            double t2 = atan2(s, wz) - atan2(f * sin(t3), u + f * cos(t3));
            double w[2][3];
            mat3 r03, rt, m36;
            int i, j, k, n;
            forearm_rot(waist, DEG(t2 + t3), r03);
            for (i = 0; i < 3; i++)
                for (j = 0; j < 3; j++)
                    rt[i][j] = r03[j][i];
            mul(rt, r, m36);
            n = wrist_solve(m36, hint, w);
            for (k = 0; k < n; k++) {
                int e;
                q[0] = fbrl_sim_arm_wrap(waist);
                q[1] = DEG(t2);
                q[2] = DEG(t3);
                q[3] = w[k][0];
                q[4] = w[k][1];
                q[5] = w[k][2];
                e = fbrl_sim_arm_check(m, q);
                if (e == 0)
                    return 0;
                if (!first_err) {
                    first_err = e;
                    memcpy(first, q, sizeof first);
                }
            }
        }
    }
    memcpy(q, first, sizeof first);
    return first_err;
}

/* ---- either ---------------------------------------------------------- */

void fbrl_sim_arm_fk(const fbrl_sim_model *m, const double *q, double tool_len, double pose[6])
{
    if (m->kin == FBRL_SIM_KIN_6R)
        fk6(m, q, tool_len, pose);
    else
        fk5(m, q, tool_len, pose);
}

int fbrl_sim_arm_ik(const fbrl_sim_model *m, const double pose[6], double tool_len, const double *hint,
                    double *q)
{
    return m->kin == FBRL_SIM_KIN_6R ? ik6(m, pose, tool_len, hint, q) : ik5(m, pose, tool_len, hint, q);
}

int fbrl_sim_arm_check(const fbrl_sim_model *m, const double *q)
{
    int i;
    for (i = 0; i < m->naxes; i++) {
        if (!isfinite(q[i]) || q[i] < m->min[i] - LIMIT_EPS || q[i] > m->max[i] + LIMIT_EPS)
            return sim_error_joint(i);
    }
    return 0;
}

long fbrl_sim_arm_pulses(const fbrl_sim_model *m, int axis, double deg) { return lround(deg * m->ppd[axis]); }

double fbrl_sim_arm_degrees(const fbrl_sim_model *m, int axis, long pulses)
{
    return (double)pulses / m->ppd[axis];
}

void fbrl_sim_arm_lerp(const double a[6], const double b[6], double f, double out[6])
{
    int i;
    for (i = 0; i < 6; i++)
        out[i] = a[i] + (b[i] - a[i]) * f;
}

int fbrl_sim_arm_check_line(const fbrl_sim_model *m, const double a[6], const double b[6], double tool_len,
                            const double *hint)
{
    double d =
        sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
    double ang = fabs(b[3] - a[3]) + fabs(b[4] - a[4]) + fabs(b[5] - a[5]);
    int n;
    double prev[FBRL_SIM_ARM_MAX_AXES], q[FBRL_SIM_ARM_MAX_AXES], pose[6];
    int i, j;

    if (m->kin == FBRL_SIM_KIN_5R)
        ang -= fabs(b[3] - a[3]); /* a 5-axis arm ignores yaw */
    n = (int)ceil(d / LINE_STEP + ang / LINE_ASTEP);
    if (n < LINE_MIN)
        n = LINE_MIN;
    if (n > LINE_MAX)
        n = LINE_MAX;
    memcpy(prev, hint, (size_t)m->naxes * sizeof *prev);
    for (i = 0; i <= n; i++) {
        fbrl_sim_arm_lerp(a, b, (double)i / n, pose);
        if (fbrl_sim_arm_ik(m, pose, tool_len, prev, q) != 0)
            return SIM_E_STRAIGHT_LINE;
        /* A joint that jumps (the waist next to the base axis, or a switch from one
         * configuration to another) is not a line the arm can follow; the first
         * sample is compared with the arm's joints (the waist only on a 5-axis arm,
         * whose other joints follow from the pose). */
        for (j = 0; j < (i == 0 && m->kin == FBRL_SIM_KIN_5R ? 1 : m->naxes); j++)
            if (fabs(fbrl_sim_arm_wrap(q[j] - prev[j])) > LINE_JUMP)
                return SIM_E_STRAIGHT_LINE;
        memcpy(prev, q, sizeof prev);
    }
    return 0;
}
