/* SPDX-License-Identifier: MIT */
/* arm.c - the arm models as data, and their kinematics (arm.h). Sources of the numbers:
 * docs/robot.md, "The arm models". No arm number lives anywhere else (test arm_facts). */
#include "fbrl/arm.h"

#include <math.h>
#include <string.h>

#define PI     3.14159265358979323846
#define RAD(d) ((d) * (PI / 180.0))
#define DEG(r) ((r) * (180.0 / PI))
#define MM(x)  ((x) / 25.4)

static const fbrl_arm models[] = {
    /* CRS A255 (DESIGN 6; reference/rapl-research.md 3.1): 10 + 10 + 10 in, 2 in to the
     * flange. The body's radii are not published [D]: a 2.5 in upper arm and a 2 in forearm
     * and wrist housing, measured from no arm (docs/robot.md says how to change them). */
    {"A255",
     5,
     FBRL_ARM_5R,
     10.0,
     10.0,
     10.0,
     2.0,
     1.25,
     1.0,
     19.685,
     {200.0, 200.0, 200.0, 44.44, 22.22},
     {-175.0, 0.0, -130.0, -110.0, -180.0},
     {175.0, 110.0, 0.0, 110.0, 180.0},
     {60.0, 60.0, 60.0, 180.0, 180.0},
     {0.0, 90.0, -90.0, 0.0, 0.0}},
    /* CRS A465: DH d1 330, a2 305, d4 330, d6 76 mm; limits and speeds as published with the
     * CRS A465 models of ReaK (rapl-research.md 3.3, S12). Pulses per degree are not
     * published: [D] 1000-count encoders behind 100:1 (J1-J3) and 50:1 (J4-J6). The body's
     * radii [D]: a 100 mm upper arm, an 80 mm forearm and wrist housing. */
    {"A465",
     6,
     FBRL_ARM_6R,
     MM(330.0),
     MM(305.0),
     MM(330.0),
     MM(76.0),
     MM(50.0),
     MM(40.0),
     19.685,
     {277.78, 277.78, 277.78, 138.89, 138.89, 138.89},
     {-175.0, -90.0, -110.0, -180.0, -105.0, -180.0},
     {175.0, 90.0, 110.0, 180.0, 105.0, 180.0},
     {180.0, 180.0, 180.0, 171.0, 173.0, 171.0},
     {0.0, 0.0, 90.0, 0.0, 0.0, 0.0}},
};
#define NMODELS (sizeof models / sizeof models[0])

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

const fbrl_arm *fbrl_arm_model(size_t i) { return i < NMODELS ? &models[i] : NULL; }

static int upcase(int ch) { return ch >= 'a' && ch <= 'z' ? ch - 'a' + 'A' : ch; }

const fbrl_arm *fbrl_arm_find(const char *name)
{
    for (size_t i = 0; name && i < NMODELS; i++) {
        const char *a = models[i].name, *b = name;
        while (*a && upcase((unsigned char)*b) == *a) {
            a++;
            b++;
        }
        if (!*a && !*b)
            return &models[i];
    }
    return NULL;
}

static void put(char *buf, size_t cap, size_t *n, int ch)
{
    if (buf && *n + 1 < cap)
        buf[*n] = (char)ch;
    (*n)++;
}

size_t fbrl_arm_names(char *buf, size_t cap, char sep)
{
    size_t n = 0;
    for (size_t i = 0; i < NMODELS; i++) {
        if (i)
            put(buf, cap, &n, sep);
        for (const char *c = models[i].name; *c; c++)
            put(buf, cap, &n, *c >= 'A' && *c <= 'Z' ? *c - 'A' + 'a' : *c);
    }
    if (buf && cap)
        buf[n < cap ? n : cap - 1] = '\0';
    return n;
}

double fbrl_arm_wrap(double deg)
{
    if (deg > -180.0 && deg <= 180.0) /* most angles are: no division */
        return deg;
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
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            out[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
}

static void rot(int axis, double deg, mat3 r)
{
    double c = cos(RAD(deg)), s = sin(RAD(deg));
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
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
    pose[3] = h > WRIST_EPS ? DEG(atan2(r[1][0], r[0][0])) : fbrl_arm_wrap(yaw_free);
    rot(1, pose[4], a);
    rot(2, -pose[3], b);
    mul(a, b, t);
    mul(t, r, m); /* = Rx(roll) */
    pose[5] = DEG(atan2(m[2][1], m[1][1]));
}

static int limit_axis(const fbrl_arm *m, const double *q)
{
    for (unsigned i = 0; i < m->naxes; i++)
        if (!isfinite(q[i]) || q[i] < m->min[i] - LIMIT_EPS || q[i] > m->max[i] + LIMIT_EPS)
            return (int)i;
    return -1;
}

/* ---- 5R: the A255 ---------------------------------------------------- */

/* The wrist pitch axis at distance rw from the base axis along the waist, height zw. */
static void wrist5(const fbrl_arm *m, const double *q, double *rw, double *zw)
{
    double a2 = RAD(q[1]), a3 = RAD(q[1] + q[2]);
    *rw = m->upper * cos(a2) + m->fore * cos(a3);
    *zw = m->base_h + m->upper * sin(a2) + m->fore * sin(a3);
}

static void fk5(const fbrl_arm *m, const double *q, double tool, double pose[6])
{
    double p = RAD(q[1] + q[2] + q[3]), tl = m->flange + tool, rw, zw;
    wrist5(m, q, &rw, &zw);
    double r = rw + tl * cos(p);
    pose[0] = r * cos(RAD(q[0]));
    pose[1] = r * sin(RAD(q[0]));
    pose[2] = zw + tl * sin(p);
    pose[3] = q[0];
    pose[4] = fbrl_arm_wrap(q[1] + q[2] + q[3]);
    pose[5] = q[4];
}

/* Solves with the waist at `waist` and the tool point at signed distance s from the base
 * axis along the waist direction: 0 (inside the limits), -2 out of reach, or the first
 * joint past a limit + 1 (q holds it). */
static int solve5(const fbrl_arm *m, const double pose[6], double tl, double waist, double s, double *q)
{
    const double l2 = m->upper, l3 = m->fore;
    double p = RAD(pose[4]);
    /* The wrist pitch axis, in the arm's vertical plane. */
    double rw = s - tl * cos(p);
    double zw = pose[2] - m->base_h - tl * sin(p);
    double c3 = (rw * rw + zw * zw - l2 * l2 - l3 * l3) / (2.0 * l2 * l3);
    double t3, t2;

    if (!isfinite(c3) || !isfinite(waist) || fabs(c3) > 1.0 + REACH_EPS)
        return -2;
    c3 = c3 > 1.0 ? 1.0 : c3 < -1.0 ? -1.0 : c3;
    t3 = -acos(c3); /* elbow bends down: the only branch inside -130..0 */
    t2 = atan2(zw, rw) - atan2(l3 * sin(t3), l2 + l3 * cos(t3));
    q[0] = fbrl_arm_wrap(waist);
    q[1] = DEG(t2);
    q[2] = DEG(t3);
    q[3] = fbrl_arm_wrap(pose[4] - q[1] - q[2]);
    q[4] = fbrl_arm_wrap(pose[5]);
    return limit_axis(m, q) + 1;
}

static int ik5(const fbrl_arm *m, const double pose[6], double tool, const double *hint, double *q)
{
    double tl = m->flange + tool;
    double r = hypot(pose[0], pose[1]), alt[FBRL_ARM_AXES_MAX];
    double waist = r < AXIS_EPS ? hint[0] : DEG(atan2(pose[1], pose[0]));
    /* Reach forward: the waist points at the target. */
    int e = solve5(m, pose, tl, waist, r, q);
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

/* The frame at the wrist centre before the wrist joints: x along the forearm, y horizontal
 * across the arm's plane. phi = forearm angle from vertical. */
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

/* The wrist centre at distance s from the base axis along the waist, height z. */
static void wrist6(const fbrl_arm *m, const double *q, double *s, double *z)
{
    double t2 = RAD(q[1]), phi = RAD(q[1] + q[2]);
    *s = m->upper * sin(t2) + m->fore * sin(phi);
    *z = m->base_h + m->upper * cos(t2) + m->fore * cos(phi);
}

static void fk6(const fbrl_arm *m, const double *q, double tool, double pose[6])
{
    double w = RAD(q[0]), tl = m->flange + tool, s, z;
    mat3 r03, r36, r;
    wrist6(m, q, &s, &z);
    forearm_rot(q[0], q[1] + q[2], r03);
    wrist_rot(q, r36);
    mul(r03, r36, r);
    pose[0] = s * cos(w) + tl * r[0][0];
    pose[1] = s * sin(w) + tl * r[1][0];
    pose[2] = z + tl * r[2][0];
    rot_pose(r, q[0], pose);
}

/* The wrist joints for a desired wrist rotation m36: the two solutions (bend positive and
 * negative), nearer to hint first. Returns how many (2, or 1 when the wrist is straight and
 * the rolls are one: then q4 keeps hint's). */
static int wrist_solve(mat3 m36, const double *hint, double out[2][3])
{
    double c5 = m36[0][0], s5 = sqrt(fmax(0.0, 1.0 - c5 * c5));
    if (s5 < WRIST_EPS) {
        double sum = DEG(atan2(m36[2][1], m36[1][1]));
        out[0][0] = fbrl_arm_wrap(hint[3]);
        out[0][1] = c5 > 0 ? 0.0 : 180.0;
        /* Rx(a) Ry(180) Rx(c) = Ry(180) Rx(c - a) */
        out[0][2] = fbrl_arm_wrap(c5 > 0 ? sum - out[0][0] : out[0][0] - sum);
        return 1;
    }
    out[0][1] = DEG(atan2(s5, c5));
    out[0][0] = DEG(atan2(m36[1][0], -m36[2][0]));
    out[0][2] = DEG(atan2(m36[0][1], m36[0][2]));
    out[1][1] = -out[0][1];
    out[1][0] = fbrl_arm_wrap(out[0][0] + 180.0);
    out[1][2] = fbrl_arm_wrap(out[0][2] + 180.0);
    if (fabs(fbrl_arm_wrap(out[1][0] - hint[3])) < fabs(fbrl_arm_wrap(out[0][0] - hint[3]))) {
        double t[3];
        memcpy(t, out[0], sizeof t);
        memcpy(out[0], out[1], sizeof t);
        memcpy(out[1], t, sizeof t);
    }
    return 2;
}

static int ik6(const fbrl_arm *m, const double pose[6], double tool, const double *hint, double *q)
{
    double tl = m->flange + tool, wx, wy, wz, rxy, first[FBRL_ARM_AXES_MAX];
    int first_err = 0;
    mat3 r;

    pose_rot(pose, r);
    wx = pose[0] - tl * r[0][0];
    wy = pose[1] - tl * r[1][0];
    wz = pose[2] - tl * r[2][0] - m->base_h;
    rxy = hypot(wx, wy);
    for (int reach = 0; reach < 2; reach++) {
        double waist = rxy < AXIS_EPS ? hint[0] : DEG(atan2(wy, wx));
        double s = reach ? -rxy : rxy;
        double u = m->upper, f = m->fore;
        double c3 = (s * s + wz * wz - u * u - f * f) / (2.0 * u * f);
        if (reach)
            waist += 180.0;
        if (!isfinite(c3) || fabs(c3) > 1.0 + REACH_EPS)
            return -2;
        c3 = fmax(-1.0, fmin(1.0, c3));
        for (int elbow = 0; elbow < 2; elbow++) {
            double t3 = elbow ? -acos(c3) : acos(c3);
            double t2 = atan2(s, wz) - atan2(f * sin(t3), u + f * cos(t3));
            double w[2][3];
            mat3 r03, rt, m36;
            forearm_rot(waist, DEG(t2 + t3), r03);
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++)
                    rt[i][j] = r03[j][i];
            mul(rt, r, m36);
            int n = wrist_solve(m36, hint, w);
            for (int k = 0; k < n; k++) {
                q[0] = fbrl_arm_wrap(waist);
                q[1] = DEG(t2);
                q[2] = DEG(t3);
                q[3] = w[k][0];
                q[4] = w[k][1];
                q[5] = w[k][2];
                int e = limit_axis(m, q) + 1;
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

static int usable(const fbrl_arm *m) { return m && m->naxes >= 5 && m->naxes <= FBRL_ARM_AXES_MAX; }

fbrl_status fbrl_arm_fk(const fbrl_arm *m, const double *q, double tool, double pose[6])
{
    if (!usable(m) || !q || !pose)
        return FBRL_EINVAL;
    if (m->form == FBRL_ARM_6R)
        fk6(m, q, tool, pose);
    else
        fk5(m, q, tool, pose);
    return FBRL_OK;
}

fbrl_status fbrl_arm_ik(const fbrl_arm *m, const double pose[6], double tool, const double *hint, double *q,
                        int *axis)
{
    int e;
    if (axis)
        *axis = -1;
    if (!usable(m) || !pose || !hint || !q)
        return FBRL_EINVAL;
    for (int i = 0; i < 6; i++)
        if (!isfinite(pose[i]))
            return FBRL_ENONFINITE;
    if (!isfinite(tool))
        return FBRL_ENONFINITE;
    e = m->form == FBRL_ARM_6R ? ik6(m, pose, tool, hint, q) : ik5(m, pose, tool, hint, q);
    if (e == 0)
        return FBRL_OK;
    if (axis && e > 0)
        *axis = e - 1;
    return FBRL_ERANGE;
}

fbrl_status fbrl_arm_check(const fbrl_arm *m, const double *q, int *axis)
{
    if (!usable(m) || !q)
        return FBRL_EINVAL;
    int a = limit_axis(m, q);
    if (axis)
        *axis = a;
    return a < 0 ? FBRL_OK : FBRL_ERANGE;
}

long fbrl_arm_pulses(const fbrl_arm *m, unsigned axis, double deg)
{
    return m && axis < m->naxes ? lround(deg * m->ppd[axis]) : 0;
}

double fbrl_arm_degrees(const fbrl_arm *m, unsigned axis, long pulses)
{
    return m && axis < m->naxes ? (double)pulses / m->ppd[axis] : 0.0;
}

void fbrl_arm_lerp(const double a[6], const double b[6], double f, double out[6])
{
    for (int i = 0; i < 6; i++)
        out[i] = a[i] + (b[i] - a[i]) * f;
}

fbrl_status fbrl_arm_check_line(const fbrl_arm *m, const double a[6], const double b[6], double tool,
                                const double *hint)
{
    double prev[FBRL_ARM_AXES_MAX], q[FBRL_ARM_AXES_MAX], pose[6], d, ang;
    int n;
    if (!usable(m) || !a || !b || !hint)
        return FBRL_EINVAL;
    d = sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
    ang = fabs(b[4] - a[4]) + fabs(b[5] - a[5]);
    if (m->form == FBRL_ARM_6R)
        ang += fabs(b[3] - a[3]); /* a 5-axis arm ignores yaw */
    if (!isfinite(d) || !isfinite(ang))
        return FBRL_ERANGE;
    n = (int)ceil(d / LINE_STEP + ang / LINE_ASTEP);
    n = n < LINE_MIN ? LINE_MIN : n > LINE_MAX ? LINE_MAX : n;
    memcpy(prev, hint, (size_t)m->naxes * sizeof *prev);
    for (int i = 0; i <= n; i++) {
        fbrl_arm_lerp(a, b, (double)i / n, pose);
        if (fbrl_arm_ik(m, pose, tool, prev, q, NULL) != FBRL_OK)
            return FBRL_ERANGE;
        /* A joint that jumps (the waist next to the base axis, or a switch from one
         * configuration to another) is not a line the arm can follow; the first sample is
         * compared with the arm's joints (the waist only on a 5-axis arm, whose other joints
         * follow from the pose). */
        unsigned nj = i == 0 && m->form == FBRL_ARM_5R ? 1 : m->naxes;
        for (unsigned j = 0; j < nj; j++)
            if (fabs(fbrl_arm_wrap(q[j] - prev[j])) > LINE_JUMP)
                return FBRL_ERANGE;
        memcpy(prev, q, sizeof prev);
    }
    return FBRL_OK;
}

fbrl_status fbrl_arm_back_off(const fbrl_arm *m, const double pose[6], double waist, double dist,
                              double out[6])
{
    double w, p;
    if (!usable(m) || !pose || !out)
        return FBRL_EINVAL;
    if (m->form == FBRL_ARM_6R)
        w = RAD(pose[3]);
    else
        w = hypot(pose[0], pose[1]) > AXIS_EPS ? atan2(pose[1], pose[0]) : RAD(waist);
    p = RAD(pose[4]);
    memmove(out, pose, 6 * sizeof *out);
    out[0] -= dist * cos(p) * cos(w);
    out[1] -= dist * cos(p) * sin(w);
    out[2] -= dist * sin(p);
    return FBRL_OK;
}

fbrl_status fbrl_arm_chain(const fbrl_arm *m, const double *q, double tool, double p[FBRL_ARM_CHAIN][3])
{
    /* the path checks take the chain at every sample: each angle's sine and cosine once */
    double cw, sw, e, ez, w, wz, axis[3], tl;
    if (!usable(m) || !q || !p)
        return FBRL_EINVAL;
    cw = cos(RAD(q[0])), sw = sin(RAD(q[0])), tl = m->flange + tool;
    if (m->form == FBRL_ARM_6R) {
        double t2 = RAD(q[1]), cp = cos(RAD(q[1] + q[2])), sp = sin(RAD(q[1] + q[2]));
        double c4 = cos(RAD(q[3])), s4 = sin(RAD(q[3])), c5 = cos(RAD(q[4])), s5 = sin(RAD(q[4]));
        /* the tool axis: the wrist's Rx(q4) Ry(q5) e_x in the forearm's frame (forearm_rot's
         * columns: along the forearm, across the arm's plane, and their cross) */
        double a = c5, b = s4 * s5, c = -c4 * s5;
        axis[0] = a * sp * cw - b * sw - c * cp * cw;
        axis[1] = a * sp * sw + b * cw - c * cp * sw;
        axis[2] = a * cp + c * sp;
        e = m->upper * sin(t2), ez = m->base_h + m->upper * cos(t2);
        w = e + m->fore * sp, wz = ez + m->fore * cp;
    } else {
        double a2 = RAD(q[1]), a3 = RAD(q[1] + q[2]), pr = RAD(q[1] + q[2] + q[3]);
        e = m->upper * cos(a2), ez = m->base_h + m->upper * sin(a2);
        w = e + m->fore * cos(a3), wz = ez + m->fore * sin(a3);
        axis[0] = cos(pr) * cw, axis[1] = cos(pr) * sw, axis[2] = sin(pr);
    }
    p[0][0] = 0.0, p[0][1] = 0.0, p[0][2] = m->base_h;
    p[1][0] = e * cw, p[1][1] = e * sw, p[1][2] = ez;
    p[2][0] = w * cw, p[2][1] = w * sw, p[2][2] = wz;
    for (int i = 0; i < 3; i++)
        p[3][i] = p[2][i] + tl * axis[i];
    return FBRL_OK;
}

fbrl_status fbrl_arm_body(const fbrl_arm *m, const double *q, double tool, double tool_r,
                          fbrl_arm_capsule body[FBRL_ARM_PARTS])
{
    double p[FBRL_ARM_CHAIN][3];
    fbrl_status st = body ? fbrl_arm_chain(m, q, tool, p) : FBRL_EINVAL;
    if (st != FBRL_OK)
        return st;
    /* shoulder-elbow, elbow-wrist, wrist-tool's end: the tool starts at the wrist centre, so a
     * tool as thin as its radius still covers the flange (the wrist's housing is the forearm's
     * round end) */
    for (int k = 0; k < FBRL_ARM_PARTS; k++) {
        memcpy(body[k].a, p[k], sizeof body[k].a);
        memcpy(body[k].b, p[k + 1], sizeof body[k].b);
    }
    body[FBRL_ARM_UPPER].r = m->r_upper;
    body[FBRL_ARM_FORE].r = m->r_fore;
    body[FBRL_ARM_TOOL].r = tool_r;
    return FBRL_OK;
}

const char *fbrl_arm_part_name(int part)
{
    static const char *const names[FBRL_ARM_PARTS] = {"upper arm", "forearm", "tool"};
    return part >= 0 && part < FBRL_ARM_PARTS ? names[part] : "arm";
}

fbrl_status fbrl_arm_levers(const fbrl_arm *m, int point, double tool, double k[FBRL_ARM_AXES_MAX])
{
    if (!usable(m) || !k || !isfinite(tool))
        return FBRL_EINVAL;
    if (point < 1 || point >= FBRL_ARM_CHAIN)
        return FBRL_ERANGE;
    /* the point's reach from the shoulder, the elbow and the wrist centre along the chain */
    double hand = point == 3 ? fabs(m->flange + tool) : 0.0, fore = point >= 2 ? m->fore : 0.0;
    for (unsigned i = 0; i < FBRL_ARM_AXES_MAX; i++)
        k[i] = 0.0;
    /* the shoulder lies on the waist's axis, so both see the whole chain */
    k[0] = k[1] = m->upper + fore + hand;
    k[2] = fore + hand;
    /* the wrist's axes pass through its centre; the last joint rolls about the tool axis */
    for (unsigned i = 3; i + 1 < m->naxes; i++)
        k[i] = hand;
    return FBRL_OK;
}
