/* SPDX-License-Identifier: MIT */
/* calib.c - 3-point and N-point calibration of work blocks, mapping of locations.
 *
 * The thesis (appendix II) chains planar rotations found with atan; that is the rigid
 * motion M = F_R * F_C^-1 written out, with quadrant and ordering errors (DESIGN 8).
 * Here the frames are built from orthonormal axes and M is kept as a rotation matrix and
 * a shift, so map and unmap are one matrix product each and are exact inverses. */
#include <math.h>
#include <stdint.h>
#include <string.h>
#include "fbrl/arm.h"
#include "fbrl/calib.h"
#include "fbrl/crc32.h"
#include "le.h"

/* ---- small vector helpers ---- */

static void sub3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[0] - b[0];
    out[1] = a[1] - b[1];
    out[2] = a[2] - b[2];
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    double x = a[1] * b[2] - a[2] * b[1];
    double y = a[2] * b[0] - a[0] * b[2];
    double z = a[0] * b[1] - a[1] * b[0];
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

static double norm3(const double a[3]) { return hypot(hypot(a[0], a[1]), a[2]); }

static void pos_of(const fbrl_loc *l, double p[3])
{
    p[0] = l->x;
    p[1] = l->y;
    p[2] = l->z;
}

static int finite3(const double p[3]) { return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]); }

static int calib_finite(const fbrl_calib *c)
{
    int i;
    for (i = 0; i < 3; i++)
        if (!finite3(c->r[i]) || !isfinite(c->t[i]))
            return 0;
    return 1;
}

/* A finite motion whose r is a proper rotation to 1e-9: r r^T = I and det r = +1. */
static int is_rigid(const fbrl_calib *c)
{
    const double(*r)[3] = c->r;
    int i, j;
    double det;
    if (!calib_finite(c))
        return 0;
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++) {
            double d = r[i][0] * r[j][0] + r[i][1] * r[j][1] + r[i][2] * r[j][2];
            if (fabs(d - (i == j)) > 1e-9)
                return 0;
        }
    }
    det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) -
          r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
          r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
    return det > 0.0;
}

/* ---- calibration points ---- */

fbrl_status fbrl_calpts_set(fbrl_calpts *c, int index, const fbrl_loc *loc)
{
    fbrl_status st;
    if (!c || !loc)
        return FBRL_EINVAL;
    if (index < 1 || index > 3)
        return FBRL_ERANGE;
    if ((st = fbrl_loc_check(loc)) != FBRL_OK)
        return st;
    c->p[index - 1] = *loc;
    return FBRL_OK;
}

fbrl_status fbrl_calpts_get(const fbrl_calpts *c, int index, fbrl_loc *loc)
{
    if (!c || !loc)
        return FBRL_EINVAL;
    if (index < 1 || index > 3)
        return FBRL_ERANGE;
    *loc = c->p[index - 1];
    return FBRL_OK;
}

/* ---- frames and 3-point calibration ---- */

fbrl_status fbrl_calib_identity(fbrl_calib *c)
{
    int i, j;
    if (!c)
        return FBRL_EINVAL;
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++)
            c->r[i][j] = i == j;
        c->t[i] = 0.0;
    }
    return FBRL_OK;
}

fbrl_status fbrl_calib_frame(const fbrl_calpts *pts, fbrl_calib *frame)
{
    double p1[3], p2[3], p3[3], x[3], w[3], y[3], z[3], spread, lx, lz;
    int i;
    if (!pts || !frame)
        return FBRL_EINVAL;
    pos_of(&pts->p[0], p1);
    pos_of(&pts->p[1], p2);
    pos_of(&pts->p[2], p3);
    if (!finite3(p1) || !finite3(p2) || !finite3(p3))
        return FBRL_ENONFINITE;
    sub3(p2, p1, x);
    sub3(p3, p1, w);
    sub3(p3, p2, y); /* only for the spread */
    lx = norm3(x);
    spread = fmax(lx, fmax(norm3(w), norm3(y)));
    if (!isfinite(spread))
        return FBRL_EOVERFLOW;
    /* P2 must be clearly apart from P1 (the x axis), P3 clearly off that axis. */
    if (!(spread > 0.0) || lx <= FBRL_CALIB_TOL * spread)
        return FBRL_EDEGENERATE;
    for (i = 0; i < 3; i++)
        x[i] /= lx;
    cross3(x, w, z);
    lz = norm3(z); /* = distance of P3 from the line P1 P2 */
    if (lz <= FBRL_CALIB_TOL * spread)
        return FBRL_EDEGENERATE;
    for (i = 0; i < 3; i++)
        z[i] /= lz;
    cross3(z, x, y);
    for (i = 0; i < 3; i++) {
        frame->r[i][0] = x[i];
        frame->r[i][1] = y[i];
        frame->r[i][2] = z[i];
        frame->t[i] = p1[i];
    }
    return FBRL_OK;
}

/* out = a * b for rigid motions (apply b, then a). */
static void compose(const fbrl_calib *a, const fbrl_calib *b, fbrl_calib *out)
{
    fbrl_calib r;
    int i, j;
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++)
            r.r[i][j] = a->r[i][0] * b->r[0][j] + a->r[i][1] * b->r[1][j] + a->r[i][2] * b->r[2][j];
        r.t[i] = a->r[i][0] * b->t[0] + a->r[i][1] * b->t[1] + a->r[i][2] * b->t[2] + a->t[i];
    }
    *out = r;
}

fbrl_status fbrl_calib_invert(const fbrl_calib *c, fbrl_calib *inv)
{
    fbrl_calib r;
    int i, j;
    if (!c || !inv || !calib_finite(c))
        return FBRL_EINVAL;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++)
            r.r[i][j] = c->r[j][i];
    for (i = 0; i < 3; i++)
        r.t[i] = -(r.r[i][0] * c->t[0] + r.r[i][1] * c->t[1] + r.r[i][2] * c->t[2]);
    *inv = r;
    return FBRL_OK;
}

fbrl_status fbrl_calib_3point(fbrl_calib *c, const fbrl_calpts *cal, const fbrl_calpts *recal)
{
    fbrl_calib fc, fr, fc_inv;
    fbrl_status st;
    if (!c || !cal || !recal)
        return FBRL_EINVAL;
    if ((st = fbrl_calib_frame(cal, &fc)) != FBRL_OK || (st = fbrl_calib_frame(recal, &fr)) != FBRL_OK)
        return st;
    fbrl_calib_invert(&fc, &fc_inv);
    compose(&fr, &fc_inv, c);
    return FBRL_OK;
}

/* ---- N-point least squares (Horn 1987, closed form with unit quaternions) ---- */

/* Refuse sets whose points all lie (within the tolerance) on one line or one spot:
 * the farthest point from the centroid fixes a line; some point must leave it. */
static fbrl_status check_spread(const fbrl_loc *pts, size_t n, double centroid[3])
{
    double c[3] = {0, 0, 0}, d[3], u[3], e[3], far = 0.0, off = 0.0;
    size_t i, ifar = 0;
    for (i = 0; i < n; i++) {
        pos_of(&pts[i], d);
        if (!finite3(d))
            return FBRL_ENONFINITE;
        c[0] += d[0] / (double)n;
        c[1] += d[1] / (double)n;
        c[2] += d[2] / (double)n;
    }
    for (i = 0; i < n; i++) {
        double l;
        pos_of(&pts[i], d);
        sub3(d, c, d);
        l = norm3(d);
        if (l > far) {
            far = l;
            ifar = i;
        }
    }
    if (!isfinite(far))
        return FBRL_EOVERFLOW;
    if (!(far > 0.0))
        return FBRL_EDEGENERATE;
    pos_of(&pts[ifar], u);
    sub3(u, c, u);
    u[0] /= far;
    u[1] /= far;
    u[2] /= far;
    for (i = 0; i < n; i++) {
        pos_of(&pts[i], d);
        sub3(d, c, d);
        cross3(d, u, e);
        off = fmax(off, norm3(e));
    }
    /* far is half the spread or more; 2*far bounds the largest pairwise distance. */
    if (off <= FBRL_CALIB_TOL * 2.0 * far)
        return FBRL_EDEGENERATE;
    memcpy(centroid, c, sizeof c);
    return FBRL_OK;
}

/* Eigen-decomposition of a symmetric 4x4 matrix by cyclic Jacobi rotations: a ends
 * diagonal (the eigenvalues), the columns of v are the eigenvectors. */
static void jacobi4(double a[4][4], double v[4][4])
{
    int sweep, p, q, k;
    double total = 0.0;
    for (p = 0; p < 4; p++)
        for (q = 0; q < 4; q++) {
            v[p][q] = p == q;
            total += a[p][q] * a[p][q];
        }
    for (sweep = 0; sweep < 100; sweep++) {
        double off = 0.0;
        for (p = 0; p < 4; p++)
            for (q = p + 1; q < 4; q++)
                off += a[p][q] * a[p][q];
        if (off <= 1e-36 * total)
            break;
        for (p = 0; p < 4; p++)
            for (q = p + 1; q < 4; q++) {
                double theta, t, c, s;
                if (a[p][q] == 0.0)
                    continue;
                theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                if (fabs(theta) > 1e150)
                    t = 0.5 / theta;
                else
                    t = (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
                c = 1.0 / sqrt(t * t + 1.0);
                s = t * c;
                for (k = 0; k < 4; k++) {
                    double kp = a[k][p], kq = a[k][q];
                    a[k][p] = c * kp - s * kq;
                    a[k][q] = s * kp + c * kq;
                }
                for (k = 0; k < 4; k++) {
                    double pk = a[p][k], qk = a[q][k];
                    a[p][k] = c * pk - s * qk;
                    a[q][k] = s * pk + c * qk;
                }
                for (k = 0; k < 4; k++) {
                    double kp = v[k][p], kq = v[k][q];
                    v[k][p] = c * kp - s * kq;
                    v[k][q] = s * kp + c * kq;
                }
            }
    }
}

fbrl_status fbrl_calib_npoint(fbrl_calib *c, const fbrl_loc *cal, const fbrl_loc *recal, size_t n,
                              double *residuals, double *rms, size_t *worst)
{
    double ca[3], cb[3], s[3][3] = {{0}}, nm[4][4], v[4][4], q[4], a[3], b[3], qn;
    double sum2 = 0.0, big = -1.0;
    size_t i, iworst = 0;
    int j, k, best;
    fbrl_calib m;
    fbrl_status st;
    if (!c || !cal || !recal || n < 3)
        return FBRL_EINVAL;
    if ((st = check_spread(cal, n, ca)) != FBRL_OK || (st = check_spread(recal, n, cb)) != FBRL_OK)
        return st;
    /* Cross-covariance of the centred sets. */
    for (i = 0; i < n; i++) {
        pos_of(&cal[i], a);
        pos_of(&recal[i], b);
        sub3(a, ca, a);
        sub3(b, cb, b);
        for (j = 0; j < 3; j++)
            for (k = 0; k < 3; k++)
                s[j][k] += a[j] * b[k];
    }
    /* Horn's symmetric matrix: its top eigenvector is the best rotation as a unit
     * quaternion, which is always a proper rotation (never a reflection). */
    nm[0][0] = s[0][0] + s[1][1] + s[2][2];
    nm[1][1] = s[0][0] - s[1][1] - s[2][2];
    nm[2][2] = -s[0][0] + s[1][1] - s[2][2];
    nm[3][3] = -s[0][0] - s[1][1] + s[2][2];
    nm[0][1] = nm[1][0] = s[1][2] - s[2][1];
    nm[0][2] = nm[2][0] = s[2][0] - s[0][2];
    nm[0][3] = nm[3][0] = s[0][1] - s[1][0];
    nm[1][2] = nm[2][1] = s[0][1] + s[1][0];
    nm[1][3] = nm[3][1] = s[2][0] + s[0][2];
    nm[2][3] = nm[3][2] = s[1][2] + s[2][1];
    jacobi4(nm, v);
    best = 0;
    for (j = 1; j < 4; j++)
        if (nm[j][j] > nm[best][best])
            best = j;
    for (j = 0; j < 4; j++)
        q[j] = v[j][best];
    qn = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(qn > 0.0) || !isfinite(qn))
        return FBRL_EDEGENERATE;
    for (j = 0; j < 4; j++)
        q[j] /= qn;
    {
        double w = q[0], x = q[1], y = q[2], z = q[3];
        m.r[0][0] = w * w + x * x - y * y - z * z;
        m.r[0][1] = 2.0 * (x * y - w * z);
        m.r[0][2] = 2.0 * (x * z + w * y);
        m.r[1][0] = 2.0 * (x * y + w * z);
        m.r[1][1] = w * w - x * x + y * y - z * z;
        m.r[1][2] = 2.0 * (y * z - w * x);
        m.r[2][0] = 2.0 * (x * z - w * y);
        m.r[2][1] = 2.0 * (y * z + w * x);
        m.r[2][2] = w * w - x * x - y * y + z * z;
    }
    for (j = 0; j < 3; j++)
        m.t[j] = cb[j] - (m.r[j][0] * ca[0] + m.r[j][1] * ca[1] + m.r[j][2] * ca[2]);
    /* Residuals: where each original point lands against where it was taught. */
    for (i = 0; i < n; i++) {
        double d;
        pos_of(&cal[i], a);
        pos_of(&recal[i], b);
        if ((st = fbrl_calib_map_points(&m, a, a, 1)) != FBRL_OK)
            return st;
        sub3(a, b, a);
        d = norm3(a);
        if (d > big) {
            big = d;
            iworst = i;
        }
        sum2 += d * d;
        if (residuals)
            residuals[i] = d;
    }
    if (!isfinite(sum2))
        return FBRL_EOVERFLOW;
    if (rms)
        *rms = sqrt(sum2 / (double)n);
    if (worst)
        *worst = iworst;
    *c = m;
    return FBRL_OK;
}

/* ---- mapping ---- */

fbrl_status fbrl_calib_map_points(const fbrl_calib *c, const double *in, double *out, size_t n)
{
    double r00, r01, r02, r10, r11, r12, r20, r21, r22, t0, t1, t2;
    size_t i;
    if (!c || !in || !out || !calib_finite(c))
        return FBRL_EINVAL;
    r00 = c->r[0][0];
    r01 = c->r[0][1];
    r02 = c->r[0][2];
    r10 = c->r[1][0];
    r11 = c->r[1][1];
    r12 = c->r[1][2];
    r20 = c->r[2][0];
    r21 = c->r[2][1];
    r22 = c->r[2][2];
    t0 = c->t[0];
    t1 = c->t[1];
    t2 = c->t[2];
    for (i = 0; i < n; i++) {
        double x = in[3 * i], y = in[3 * i + 1], z = in[3 * i + 2];
        double mx = r00 * x + r01 * y + r02 * z + t0;
        double my = r10 * x + r11 * y + r12 * z + t1;
        double mz = r20 * x + r21 * y + r22 * z + t2;
        /* A NaN or infinity in the input always reaches the output (0 * inf is NaN), so
         * one test on the result catches both bad input and overflow. */
        if (!isfinite(mx) || !isfinite(my) || !isfinite(mz))
            return isfinite(x) && isfinite(y) && isfinite(z) ? FBRL_EOVERFLOW : FBRL_ENONFINITE;
        out[3 * i] = mx;
        out[3 * i + 1] = my;
        out[3 * i + 2] = mz;
    }
    return FBRL_OK;
}

fbrl_status fbrl_calib_unmap_points(const fbrl_calib *c, const double *in, double *out, size_t n)
{
    fbrl_calib inv;
    fbrl_status st;
    if ((st = fbrl_calib_invert(c, &inv)) != FBRL_OK)
        return st;
    return fbrl_calib_map_points(&inv, in, out, n);
}

fbrl_status fbrl_calib_orient_to_matrix(double yaw, double pitch, double roll, fbrl_rot *rot)
{
    double cy, sy, cp, sp, cr, sr, *r;
    if (!rot)
        return FBRL_EINVAL;
    r = &rot->m[0][0];
    if (!isfinite(yaw) || !isfinite(pitch) || !isfinite(roll))
        return FBRL_ENONFINITE;
    cy = cos(FBRL_RAD(yaw));
    sy = sin(FBRL_RAD(yaw));
    cp = cos(FBRL_RAD(pitch));
    sp = sin(FBRL_RAD(pitch));
    cr = cos(FBRL_RAD(roll));
    sr = sin(FBRL_RAD(roll));
    /* Rz(yaw) * Ry(-pitch) * Rx(roll), multiplied out. */
    r[0] = cy * cp;
    r[1] = -cy * sp * sr - sy * cr;
    r[2] = -cy * sp * cr + sy * sr;
    r[3] = sy * cp;
    r[4] = -sy * sp * sr + cy * cr;
    r[5] = -sy * sp * cr - cy * sr;
    r[6] = sp;
    r[7] = cp * sr;
    r[8] = cp * cr;
    return FBRL_OK;
}

fbrl_status fbrl_calib_matrix_to_orient(const fbrl_rot *rot, double yaw_hint, double *yaw, double *pitch,
                                        double *roll)
{
    double horiz, p, y, cy, sy, cp, sp, u0, q11, q21;
    const double *r;
    int i;
    if (!rot || !yaw || !pitch || !roll)
        return FBRL_EINVAL;
    r = &rot->m[0][0];
    for (i = 0; i < 3; i++)
        if (!finite3(rot->m[i]))
            return FBRL_ENONFINITE;
    if (!isfinite(yaw_hint))
        return FBRL_ENONFINITE;
    horiz = hypot(r[0], r[3]); /* cos pitch: the tool axis's horizontal part */
    p = atan2(r[6], horiz);
    /* A vertical tool axis has no heading; then take the caller's yaw and let roll
     * carry the turn. */
    y = horiz > 1e-10 ? atan2(r[3], r[0]) : FBRL_RAD(fbrl_arm_wrap(yaw_hint));
    /* Roll from Rx(roll) = Ry(pitch) Rz(-yaw) R, column 1: consistent with the yaw just
     * chosen, so the three angles rebuild R even close to the vertical. */
    cy = cos(y);
    sy = sin(y);
    cp = cos(p);
    sp = sin(p);
    u0 = cy * r[1] + sy * r[4];
    q11 = -sy * r[1] + cy * r[4];
    q21 = -sp * u0 + cp * r[7];
    *yaw = fbrl_arm_wrap(FBRL_DEG(y));
    *pitch = FBRL_DEG(p);
    *roll = fbrl_arm_wrap(FBRL_DEG(atan2(q21, q11)));
    return FBRL_OK;
}

/* ---- mapping what a 5-axis arm can do ----
 *
 * The arm's tool frame at a location is Rz(waist) * Ry(-pitch) * Rx(roll) (the
 * orient_to_matrix convention with yaw = waist): the waist, not the location's yaw, sets
 * the heading, and the controller points the waist at the target (DESIGN 6). So a location
 * is mapped by turning the tool frame the arm really has there with the block, then
 * finding the frame the arm can have at the mapped position: the waist points at it, the
 * tool axis is the wanted one brought into the waist's vertical plane by the smallest
 * rotation (its angle is the part the arm cannot follow, reported), and the roll is what
 * that same rotation leaves of the wanted grip. docs/calibration.md has the model. */

/* The waist direction (degrees) for a position: the heading of (x, y) from the arm's base
 * axis; on the axis itself (no heading) the caller's fallback. */
static double waist_of(const double p[3], const double axis[2], double fallback)
{
    double dx = p[0] - axis[0], dy = p[1] - axis[1];
    return hypot(dx, dy) > FBRL_CALIB_AXIS_R ? FBRL_DEG(atan2(dy, dx)) : fallback;
}

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

fbrl_status fbrl_calib_map_arm(const fbrl_calib *c, const double axis[2], const fbrl_loc *in, fbrl_loc *out,
                               double *off)
{
    static const double origin[2] = {0.0, 0.0};
    double p[3], q[3], w0, w1, hx, hy, d[3], g[3], h[3], n[3], a[3], v[3], vg[3], vvg[3];
    double f2[3], f3[3], dh, dz, cs, ch, pitch, cp, sp, cw, sw, roll, dev;
    fbrl_rot tool;
    fbrl_loc res;
    fbrl_status st;
    int i;
    if (!c || !in || !out || !calib_finite(c))
        return FBRL_EINVAL;
    if (!axis)
        axis = origin;
    if (!isfinite(axis[0]) || !isfinite(axis[1]))
        return FBRL_ENONFINITE;
    if ((st = fbrl_loc_check(in)) != FBRL_OK)
        return st;
    pos_of(in, p);
    if ((st = fbrl_calib_map_points(c, p, q, 1)) != FBRL_OK)
        return st;
    /* The tool frame the arm has at the original location, turned with the block:
     * d its wanted axis, g its wanted grip direction (the tool's y axis). */
    w0 = waist_of(p, axis, in->o);
    fbrl_calib_orient_to_matrix(w0, in->a, in->t, &tool);
    for (i = 0; i < 3; i++) {
        d[i] = c->r[i][0] * tool.m[0][0] + c->r[i][1] * tool.m[1][0] + c->r[i][2] * tool.m[2][0];
        g[i] = c->r[i][0] * tool.m[0][1] + c->r[i][1] * tool.m[1][1] + c->r[i][2] * tool.m[2][1];
    }
    /* The waist at the mapped position; on the base axis, the original waist's heading
     * turned with the block. */
    hx = c->r[0][0] * cos(FBRL_RAD(w0)) + c->r[0][1] * sin(FBRL_RAD(w0));
    hy = c->r[1][0] * cos(FBRL_RAD(w0)) + c->r[1][1] * sin(FBRL_RAD(w0));
    w1 = waist_of(q, axis, hypot(hx, hy) > 1e-9 ? FBRL_DEG(atan2(hy, hx)) : w0);
    cw = cos(FBRL_RAD(w1));
    sw = sin(FBRL_RAD(w1));
    h[0] = cw;
    h[1] = sw;
    h[2] = 0.0; /* along the arm, horizontal */
    n[0] = -sw;
    n[1] = cw;
    n[2] = 0.0; /* across the arm: what the arm cannot tilt to */
    /* The reachable axis nearest d: d without its part across the arm. Pitch may pass
     * -90 or 90 (tool leaning back toward the base), so a straight-down tool on a slightly
     * tilted block has no flip in it. */
    dh = dot3(d, h);
    dz = d[2];
    ch = hypot(dh, dz);
    if (ch > 1e-12) {
        pitch = atan2(dz, dh);
        dev = atan2(fabs(dot3(d, n)), ch);
    } else { /* the wanted axis points straight across the arm: no nearest one */
        pitch = FBRL_RAD(in->a);
        dev = FBRL_PI / 2.0;
    }
    cp = cos(pitch);
    sp = sin(pitch);
    for (i = 0; i < 3; i++)
        a[i] = cp * h[i] + (i == 2 ? sp : 0.0);
    /* Bring g along with the smallest rotation taking d to a (Rodrigues with v = d x a,
     * cos = d.a >= 0 here since a is d's projection): R g = g + v x g + v x (v x g)/(1+cos). */
    cross3(d, a, v);
    cs = dot3(d, a);
    cross3(v, g, vg);
    cross3(v, vg, vvg);
    for (i = 0; i < 3; i++)
        g[i] += vg[i] + vvg[i] / (1.0 + cs);
    /* Roll: g = cos(roll) f2 + sin(roll) f3 in the arm's frame Rz(w1) Ry(-pitch). */
    f2[0] = -sw;
    f2[1] = cw;
    f2[2] = 0.0;
    f3[0] = -cw * sp;
    f3[1] = -sw * sp;
    f3[2] = cp;
    roll = atan2(dot3(g, f3), dot3(g, f2));
    if (!isfinite(roll) || !isfinite(pitch))
        return FBRL_EOVERFLOW;
    res.x = q[0];
    res.y = q[1];
    res.z = q[2];
    res.o = fbrl_arm_wrap(w1);
    res.a = fbrl_arm_wrap(FBRL_DEG(pitch));
    res.t = fbrl_arm_wrap(FBRL_DEG(roll));
    if (off)
        *off = FBRL_DEG(dev);
    *out = res;
    return FBRL_OK;
}

fbrl_status fbrl_calib_unmap_arm(const fbrl_calib *c, const double axis[2], const fbrl_loc *in, fbrl_loc *out,
                                 double *off)
{
    fbrl_calib inv;
    fbrl_status st;
    if (!in || !out)
        return FBRL_EINVAL;
    if ((st = fbrl_calib_invert(c, &inv)) != FBRL_OK)
        return st;
    return fbrl_calib_map_arm(&inv, axis, in, out, off);
}

fbrl_status fbrl_calib_map(const fbrl_calib *c, const fbrl_loc *in, fbrl_loc *out)
{
    fbrl_loc res;
    double off;
    fbrl_status st = out ? fbrl_calib_map_arm(c, NULL, in, &res, &off) : FBRL_EINVAL;
    if (st != FBRL_OK)
        return st;
    if (off > FBRL_CALIB_AXIS_MAX)
        return FBRL_ERANGE;
    *out = res;
    return FBRL_OK;
}

fbrl_status fbrl_calib_unmap(const fbrl_calib *c, const fbrl_loc *in, fbrl_loc *out)
{
    return fbrl_calib_unmap_arm(c, NULL, in, out, NULL);
}

/* ---- the thesis's planar helpers ---- */

fbrl_status fbrl_calib_ang_from_origin(double x1, double y1, double x2, double y2, double *ang)
{
    double dx = x2 - x1, dy = y2 - y1;
    if (!ang)
        return FBRL_EINVAL;
    if (!isfinite(x1) || !isfinite(y1) || !isfinite(x2) || !isfinite(y2))
        return FBRL_ENONFINITE;
    if (!isfinite(dx) || !isfinite(dy))
        return FBRL_EOVERFLOW;
    if (dx == 0.0 && dy == 0.0)
        return FBRL_EDEGENERATE;
    *ang = atan2(dy, dx);
    return FBRL_OK;
}

fbrl_status fbrl_calib_rotate(double x, double y, double ang, double *xr, double *yr)
{
    double c, s, rx, ry;
    if (!xr || !yr)
        return FBRL_EINVAL;
    if (!isfinite(x) || !isfinite(y) || !isfinite(ang))
        return FBRL_ENONFINITE;
    c = cos(ang);
    s = sin(ang);
    rx = x * c - y * s;
    ry = x * s + y * c;
    if (!isfinite(rx) || !isfinite(ry))
        return FBRL_EOVERFLOW;
    *xr = rx;
    *yr = ry;
    return FBRL_OK;
}

/* ---- save and load ---- */

#define CAL_CRC_AT 104

fbrl_status fbrl_calib_save(const fbrl_calib *c, unsigned char *buf, size_t size)
{
    int i, j;
    if (!c || !buf || !is_rigid(c))
        return FBRL_EINVAL;
    if (size < FBRL_CALIB_BYTES)
        return FBRL_ENOSPC;
    memcpy(buf, "FBCL", 4);
    fbrl_le_put16(buf + 4, FBRL_CALIB_VERSION);
    fbrl_le_put16(buf + 6, 0);
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++)
            fbrl_le_put_double(buf + 8 + 8 * (3 * i + j), c->r[i][j]);
    for (i = 0; i < 3; i++)
        fbrl_le_put_double(buf + 80 + 8 * i, c->t[i]);
    fbrl_le_put32(buf + CAL_CRC_AT, fbrl_crc32(0, buf, CAL_CRC_AT));
    return FBRL_OK;
}

fbrl_status fbrl_calib_load(fbrl_calib *c, const unsigned char *buf, size_t size)
{
    fbrl_calib r;
    int i, j;
    if (!c || !buf)
        return FBRL_EINVAL;
    if (size < FBRL_CALIB_BYTES)
        return FBRL_ETRUNCATED;
    if (memcmp(buf, "FBCL", 4) != 0)
        return FBRL_EFORMAT;
    if (fbrl_le_get16(buf + 4) != FBRL_CALIB_VERSION)
        return FBRL_EVERSION;
    if (fbrl_le_get32(buf + CAL_CRC_AT) != fbrl_crc32(0, buf, CAL_CRC_AT))
        return FBRL_ECHECKSUM;
    if (fbrl_le_get16(buf + 6) != 0)
        return FBRL_EFORMAT;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++)
            r.r[i][j] = fbrl_le_get_double(buf + 8 + 8 * (3 * i + j));
    for (i = 0; i < 3; i++)
        r.t[i] = fbrl_le_get_double(buf + 80 + 8 * i);
    if (!is_rigid(&r))
        return FBRL_EFORMAT;
    *c = r;
    return FBRL_OK;
}
