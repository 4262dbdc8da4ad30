/* SPDX-License-Identifier: MIT */
/* cell.c - the work cell's geometry and the path check (cell.h, docs/workcell.md). */
#include <math.h>
#include <string.h>

#include "fbrl/cell.h"

#define CELL_MAGIC 0x43454C4Cu /* "CELL" */
#define PI         3.14159265358979323846
#define RAD(d)     ((d) * (PI / 180.0))
#define DEG(r)     ((r) * (180.0 / PI))

#define LIMIT_EPS 1e-9  /* degrees: a joint this far past a limit (rounding) is inside */
#define AXIS_EPS  1e-9  /* in: closer to the base axis than this, the waist is free */
#define REACH_EPS 1e-12 /* a fully stretched arm still reaches */
#define GOLDEN_IT 48    /* golden-section steps for a segment against a cylinder */
/* in: the step near an obstacle. A point that moves at most this far per step cannot pass
 * through a slab at least this thick without a sample inside it (and the bound on the
 * motion is generous: the envelope moves less). */
#define MIN_STEP    (FBRL_CELL_THIN * 0.9)
#define MAX_SAMPLES 100000u /* a path check gives up (FBRL_ERANGE) beyond this */
#define LINE_HALVE  30      /* step halvings on a straight line before it counts as a jump */
#define LINE_SLACK  1.25    /* margin for the bend of a straight line's joint path between samples */

const fbrl_cell_arm fbrl_cell_arm_a255 = {
    10.0, 10.0, 10.0, 2.0, {-175.0, 0.0, -130.0, -110.0, -180.0}, {175.0, 110.0, 0.0, 110.0, 180.0}};

static int ok(const fbrl_cell_model *c) { return c && c->magic == CELL_MAGIC; }

static double wrap180(double a)
{
    a = fmod(a, 360.0);
    if (a > 180.0)
        a -= 360.0;
    else if (a <= -180.0)
        a += 360.0;
    return a;
}

static int upcase(int ch) { return ch >= 'a' && ch <= 'z' ? ch - 'a' + 'A' : ch; }

static int same_name(const char *a, const char *b, size_t len)
{
    size_t k;
    for (k = 0; k < len; k++)
        if (!a[k] || upcase((unsigned char)a[k]) != upcase((unsigned char)b[k]))
            return 0;
    return a[len] == '\0';
}

/* ---- the model ---- */

fbrl_status fbrl_cell_init(fbrl_cell_model *c, fbrl_cell_obj *storage, size_t cap)
{
    if (!c || (!storage && cap))
        return FBRL_EINVAL;
    memset(c, 0, sizeof *c);
    c->magic = CELL_MAGIC;
    c->obj = storage;
    c->cap = cap;
    c->arm = fbrl_cell_arm_a255;
    return FBRL_OK;
}

fbrl_status fbrl_cell_clear(fbrl_cell_model *c)
{
    if (!ok(c))
        return FBRL_EINVAL;
    c->n = 0;
    c->nblocks = 0;
    c->have_table = 0;
    return FBRL_OK;
}

fbrl_status fbrl_cell_set_table(fbrl_cell_model *c, double z)
{
    if (!ok(c))
        return FBRL_EINVAL;
    if (!isfinite(z))
        return FBRL_ENONFINITE;
    c->have_table = 1;
    c->table_z = z;
    return FBRL_OK;
}

fbrl_status fbrl_cell_set_tool(fbrl_cell_model *c, double len, double radius)
{
    if (!ok(c))
        return FBRL_EINVAL;
    if (!isfinite(len) || !isfinite(radius))
        return FBRL_ENONFINITE;
    if (len < 0 || radius < 0)
        return FBRL_ERANGE;
    c->tool_len = len;
    c->tool_r = radius;
    return FBRL_OK;
}

fbrl_status fbrl_cell_set_arm(fbrl_cell_model *c, const fbrl_cell_arm *arm)
{
    if (!ok(c) || !arm)
        return FBRL_EINVAL;
    if (!(arm->upper > 0) || !(arm->fore > 0) || !(arm->flange >= 0) || !isfinite(arm->base_h))
        return FBRL_ERANGE;
    c->arm = *arm;
    return FBRL_OK;
}

fbrl_status fbrl_cell_block(fbrl_cell_model *c, const char *name, size_t len, int *index)
{
    size_t k;
    if (!ok(c) || !name || !index)
        return FBRL_EINVAL;
    if (len == 0 || len > FBRL_CELL_NAME_MAX)
        return FBRL_ENAME;
    for (k = 0; k < c->nblocks; k++)
        if (same_name(c->block_name[k], name, len)) {
            *index = (int)k;
            return FBRL_OK;
        }
    if (c->nblocks == FBRL_CELL_BLOCKS)
        return FBRL_EFULL;
    memcpy(c->block_name[k], name, len);
    c->block_name[k][len] = '\0';
    fbrl_calib_identity(&c->block[k]);
    c->nblocks++;
    *index = (int)k;
    return FBRL_OK;
}

fbrl_status fbrl_cell_set_block(fbrl_cell_model *c, int index, const fbrl_calib *m)
{
    if (!ok(c) || !m)
        return FBRL_EINVAL;
    if (index < 0 || (size_t)index >= c->nblocks)
        return FBRL_ERANGE;
    for (int i = 0; i < 3; i++) {
        if (!isfinite(m->t[i]))
            return FBRL_ENONFINITE;
        for (int j = 0; j < 3; j++)
            if (!isfinite(m->r[i][j]))
                return FBRL_ENONFINITE;
    }
    c->block[index] = *m;
    return FBRL_OK;
}

fbrl_status fbrl_cell_find(const fbrl_cell_model *c, const char *name, size_t len, size_t *index)
{
    if (!ok(c) || !name || !index)
        return FBRL_EINVAL;
    for (size_t k = 0; k < c->n; k++)
        if (same_name(c->obj[k].name, name, len)) {
            *index = k;
            return FBRL_OK;
        }
    return FBRL_ENOENT;
}

fbrl_status fbrl_cell_add(fbrl_cell_model *c, const fbrl_cell_obj *o)
{
    size_t len, dup;
    if (!ok(c) || !o)
        return FBRL_EINVAL;
    len = strlen(o->name);
    if (len == 0 || len > FBRL_CELL_NAME_MAX || fbrl_cell_find(c, o->name, len, &dup) == FBRL_OK)
        return FBRL_ENAME;
    for (int i = 0; i < 3; i++)
        if (!isfinite(o->lo[i]) || !isfinite(o->hi[i]))
            return FBRL_ENONFINITE;
    if (!isfinite(o->c[0]) || !isfinite(o->c[1]) || !isfinite(o->r))
        return FBRL_ENONFINITE;
    if (o->block < -1 || o->block >= (int)c->nblocks)
        return FBRL_ERANGE;
    switch (o->kind) {
    case FBRL_CELL_BOX:
    case FBRL_CELL_KEEPOUT:
        if (!(o->hi[0] > o->lo[0] && o->hi[1] > o->lo[1] && o->hi[2] > o->lo[2]))
            return FBRL_ERANGE;
        break;
    case FBRL_CELL_CYLINDER:
        if (!(o->r > 0 && o->hi[2] > o->lo[2]))
            return FBRL_ERANGE;
        break;
    default: return FBRL_ERANGE;
    }
    if (c->n == c->cap)
        return FBRL_EFULL;
    c->obj[c->n++] = *o;
    return FBRL_OK;
}

const fbrl_cell_obj *fbrl_cell_get(const fbrl_cell_model *c, size_t i)
{
    return ok(c) && i < c->n ? &c->obj[i] : NULL;
}

const char *fbrl_cell_obj_name(const fbrl_cell_model *c, size_t i)
{
    if (i == FBRL_CELL_TABLE)
        return "the table";
    return ok(c) && i < c->n ? c->obj[i].name : "nothing";
}

/* ---- distances ---- */

/* A point in the frame where obstacle o was described (its block carried back). */
static void to_obj(const fbrl_cell_model *c, const fbrl_cell_obj *o, const double p[3], double out[3])
{
    if (o->block < 0) {
        memcpy(out, p, 3 * sizeof *p);
        return;
    }
    const fbrl_calib *m = &c->block[o->block];
    double d[3] = {p[0] - m->t[0], p[1] - m->t[1], p[2] - m->t[2]};
    for (int i = 0; i < 3; i++)
        out[i] = m->r[0][i] * d[0] + m->r[1][i] * d[1] + m->r[2][i] * d[2];
}

static void from_obj(const fbrl_cell_model *c, const fbrl_cell_obj *o, const double p[3], double out[3])
{
    if (o->block < 0) {
        memcpy(out, p, 3 * sizeof *p);
        return;
    }
    const fbrl_calib *m = &c->block[o->block];
    for (int i = 0; i < 3; i++)
        out[i] = m->r[i][0] * p[0] + m->r[i][1] * p[1] + m->r[i][2] * p[2] + m->t[i];
}

/* Signed distance of a point to a box (negative inside); nearest point of the surface. */
static double point_box(const double lo[3], const double hi[3], const double p[3], double near[3])
{
    double out = 0.0, in = INFINITY;
    int inside = 1, face = 0;
    for (int i = 0; i < 3; i++) {
        double q = p[i] < lo[i] ? lo[i] : p[i] > hi[i] ? hi[i] : p[i];
        near[i] = q;
        out += (p[i] - q) * (p[i] - q);
        if (p[i] < lo[i] || p[i] > hi[i])
            inside = 0;
        if (p[i] - lo[i] < in)
            in = p[i] - lo[i], face = i;
        if (hi[i] - p[i] < in)
            in = hi[i] - p[i], face = i + 3;
    }
    if (!inside)
        return sqrt(out);
    near[face % 3] = face < 3 ? lo[face] : hi[face - 3];
    return -in;
}

static double point_cyl(const fbrl_cell_obj *o, const double p[3], double near[3])
{
    double dx = p[0] - o->c[0], dy = p[1] - o->c[1], rho = hypot(dx, dy);
    double er = rho - o->r, ez = p[2] < o->lo[2] ? o->lo[2] - p[2] : p[2] > o->hi[2] ? p[2] - o->hi[2] : 0.0;
    double ux = rho > AXIS_EPS ? dx / rho : 1.0, uy = rho > AXIS_EPS ? dy / rho : 0.0;
    double nr = rho < o->r ? rho : o->r;
    near[0] = o->c[0] + ux * nr;
    near[1] = o->c[1] + uy * nr;
    near[2] = p[2] < o->lo[2] ? o->lo[2] : p[2] > o->hi[2] ? o->hi[2] : p[2];
    if (er <= 0 && ez <= 0) { /* inside: the nearest face */
        double down = p[2] - o->lo[2], up = o->hi[2] - p[2], side = o->r - rho;
        if (side <= down && side <= up) {
            near[0] = o->c[0] + ux * o->r, near[1] = o->c[1] + uy * o->r;
            return -side;
        }
        near[0] = p[0], near[1] = p[1], near[2] = down < up ? o->lo[2] : o->hi[2];
        return -(down < up ? down : up);
    }
    return hypot(er > 0 ? er : 0.0, ez);
}

static void lerp3(const double a[3], const double b[3], double t, double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = a[i] + (b[i] - a[i]) * t;
}

/* Distance of the segment a-b to a box: on each piece between the parameters where a
 * coordinate crosses a face, the squared distance outside is a quadratic in t. Inside
 * the box (the segment passes through it) the deepest sampled point's signed distance. */
static double seg_box(const double lo[3], const double hi[3], const double a[3], const double b[3],
                      double near[3])
{
    double ts[8], best = INFINITY, d[3];
    int n = 0;
    ts[n++] = 0.0;
    ts[n++] = 1.0;
    for (int i = 0; i < 3; i++) {
        d[i] = b[i] - a[i];
        if (d[i] != 0.0) {
            double t1 = (lo[i] - a[i]) / d[i], t2 = (hi[i] - a[i]) / d[i];
            if (t1 > 0 && t1 < 1)
                ts[n++] = t1;
            if (t2 > 0 && t2 < 1)
                ts[n++] = t2;
        }
    }
    for (int i = 1; i < n; i++) /* insertion sort: at most 8 */
        for (int j = i; j > 0 && ts[j] < ts[j - 1]; j--) {
            double t = ts[j];
            ts[j] = ts[j - 1];
            ts[j - 1] = t;
        }
    for (int k = 0; k + 1 < n; k++) {
        double t0 = ts[k], t1 = ts[k + 1], mid = 0.5 * (t0 + t1), qa = 0.0, qb = 0.0, t, p[3], nb[3], dist;
        /* on this piece each coordinate is below lo, above hi or between: the same sign */
        for (int i = 0; i < 3; i++) {
            double x = a[i] + d[i] * mid, e0;
            if (x < lo[i])
                e0 = a[i] - lo[i];
            else if (x > hi[i])
                e0 = a[i] - hi[i];
            else
                continue;
            qa += d[i] * d[i];
            qb += 2.0 * e0 * d[i];
        }
        t = qa > 0 ? -qb / (2.0 * qa) : t0;
        t = t < t0 ? t0 : t > t1 ? t1 : t;
        lerp3(a, b, t, p);
        dist = point_box(lo, hi, p, nb);
        if (dist < best) {
            best = dist;
            memcpy(near, nb, sizeof nb);
        }
    }
    if (best <= 0.0) { /* through the box: how deep its middle goes */
        double p[3], nb[3];
        for (int k = 0; k + 1 < n; k++) {
            lerp3(a, b, 0.5 * (ts[k] + ts[k + 1]), p);
            double dist = point_box(lo, hi, p, nb);
            if (dist < best) {
                best = dist;
                memcpy(near, nb, sizeof nb);
            }
        }
    }
    return best;
}

/* A segment against a cylinder: the distance to a convex solid along a segment is convex
 * in t (outside), so a golden-section search finds its least value. */
static double seg_cyl(const fbrl_cell_obj *o, const double a[3], const double b[3], double near[3])
{
    const double g = 0.5 * (sqrt(5.0) - 1.0);
    double lo = 0.0, hi = 1.0, p[3], nb[3], x1, x2, f1, f2, best, ends;
    x1 = hi - g * (hi - lo);
    x2 = lo + g * (hi - lo);
    lerp3(a, b, x1, p);
    f1 = point_cyl(o, p, nb);
    lerp3(a, b, x2, p);
    f2 = point_cyl(o, p, nb);
    for (int it = 0; it < GOLDEN_IT; it++) {
        if (f1 < f2) {
            hi = x2, x2 = x1, f2 = f1;
            x1 = hi - g * (hi - lo);
            lerp3(a, b, x1, p);
            f1 = point_cyl(o, p, nb);
        } else {
            lo = x1, x1 = x2, f1 = f2;
            x2 = lo + g * (hi - lo);
            lerp3(a, b, x2, p);
            f2 = point_cyl(o, p, nb);
        }
    }
    lerp3(a, b, 0.5 * (lo + hi), p);
    best = point_cyl(o, p, near);
    ends = point_cyl(o, a, nb);
    if (ends < best) {
        best = ends;
        memcpy(near, nb, sizeof nb);
    }
    ends = point_cyl(o, b, nb);
    if (ends < best) {
        best = ends;
        memcpy(near, nb, sizeof nb);
    }
    return best;
}

fbrl_status fbrl_cell_point_clearance(const fbrl_cell_model *c, const double p[3], int block, double *d,
                                      size_t *obj)
{
    double best = INFINITY, q[3], nb[3];
    size_t which = FBRL_CELL_NONE;
    if (!ok(c) || !p || !d)
        return FBRL_EINVAL;
    for (size_t k = 0; k < c->n; k++) {
        const fbrl_cell_obj *o = &c->obj[k];
        if (block != -2 && o->block != block)
            continue;
        memcpy(q, p, sizeof q); /* as taught: no block motion */
        double v = o->kind == FBRL_CELL_CYLINDER ? point_cyl(o, q, nb) : point_box(o->lo, o->hi, q, nb);
        if (v < best)
            best = v, which = k;
    }
    *d = best;
    if (obj)
        *obj = which;
    return FBRL_OK;
}

/* ---- kinematics (A255 type, DESIGN 6) ---- */

fbrl_status fbrl_cell_fk(const fbrl_cell_arm *m, const double q[FBRL_CELL_AXES], double pose[6])
{
    if (!m || !q || !pose)
        return FBRL_EINVAL;
    double a2 = RAD(q[1]), a3 = RAD(q[1] + q[2]), p = RAD(q[1] + q[2] + q[3]);
    double r = m->upper * cos(a2) + m->fore * cos(a3) + m->flange * cos(p);
    double z = m->base_h + m->upper * sin(a2) + m->fore * sin(a3) + m->flange * sin(p);
    pose[0] = r * cos(RAD(q[0]));
    pose[1] = r * sin(RAD(q[0]));
    pose[2] = z;
    pose[3] = q[0];
    pose[4] = wrap180(q[1] + q[2] + q[3]);
    pose[5] = q[4];
    return FBRL_OK;
}

static int in_limits(const fbrl_cell_arm *m, const double q[FBRL_CELL_AXES])
{
    for (int i = 0; i < FBRL_CELL_AXES; i++)
        if (!isfinite(q[i]) || q[i] < m->min[i] - LIMIT_EPS || q[i] > m->max[i] + LIMIT_EPS)
            return 0;
    return 1;
}

/* The joints with the waist at `waist` and the tool point at signed distance s from the
 * base axis along the waist's direction (elbow down: the only branch in -130..0). */
static int solve(const fbrl_cell_arm *m, const double pose[6], double waist, double s,
                 double q[FBRL_CELL_AXES])
{
    double p = RAD(pose[4]), l2 = m->upper, l3 = m->fore;
    double rw = s - m->flange * cos(p), zw = pose[2] - m->base_h - m->flange * sin(p);
    double c3 = (rw * rw + zw * zw - l2 * l2 - l3 * l3) / (2.0 * l2 * l3), t3, t2;
    if (!isfinite(c3) || fabs(c3) > 1.0 + REACH_EPS)
        return 0;
    c3 = c3 > 1.0 ? 1.0 : c3 < -1.0 ? -1.0 : c3;
    t3 = -acos(c3);
    t2 = atan2(zw, rw) - atan2(l3 * sin(t3), l2 + l3 * cos(t3));
    q[0] = wrap180(waist);
    q[1] = DEG(t2);
    q[2] = DEG(t3);
    q[3] = wrap180(pose[4] - q[1] - q[2]);
    q[4] = wrap180(pose[5]);
    return in_limits(m, q);
}

fbrl_status fbrl_cell_ik(const fbrl_cell_arm *m, const double pose[6], const double hint[FBRL_CELL_AXES],
                         double q[FBRL_CELL_AXES])
{
    double alt[FBRL_CELL_AXES], r, waist;
    if (!m || !pose || !hint || !q)
        return FBRL_EINVAL;
    for (int i = 0; i < 6; i++)
        if (!isfinite(pose[i]))
            return FBRL_ENONFINITE;
    r = hypot(pose[0], pose[1]);
    waist = r < AXIS_EPS ? hint[0] : DEG(atan2(pose[1], pose[0]));
    if (solve(m, pose, waist, r, q))
        return FBRL_OK;
    if (solve(m, pose, waist + 180.0, -r, alt)) { /* backward over the shoulder */
        memcpy(q, alt, sizeof alt);
        return FBRL_OK;
    }
    return FBRL_ERANGE;
}

void fbrl_cell_back_off(const double pose[6], double waist, double dist, double out[6])
{
    double w = hypot(pose[0], pose[1]) > AXIS_EPS ? atan2(pose[1], pose[0]) : RAD(waist);
    double p = RAD(pose[4]);
    memcpy(out, pose, 6 * sizeof *out);
    out[0] -= dist * cos(p) * cos(w);
    out[1] -= dist * cos(p) * sin(w);
    out[2] -= dist * sin(p);
}

/* ---- the envelope at a pose ---- */

/* The capsule's axis: the wrist pitch axis to the tool's far end. */
static void envelope(const fbrl_cell_model *c, const double q[FBRL_CELL_AXES], double a[3], double b[3])
{
    const fbrl_cell_arm *m = &c->arm;
    double a2 = RAD(q[1]), a3 = RAD(q[1] + q[2]), p = RAD(q[1] + q[2] + q[3]);
    double cw = cos(RAD(q[0])), sw = sin(RAD(q[0]));
    double rw = m->upper * cos(a2) + m->fore * cos(a3),
           zw = m->base_h + m->upper * sin(a2) + m->fore * sin(a3);
    double reach = m->flange + c->tool_len;
    a[0] = rw * cw, a[1] = rw * sw, a[2] = zw;
    b[0] = (rw + reach * cos(p)) * cw, b[1] = (rw + reach * cos(p)) * sw, b[2] = zw + reach * sin(p);
}

/* What a path check remembers between samples: for each obstacle a lower bound of its
 * clearance (its distance when last measured, less how far the envelope may have moved
 * since). An obstacle far from the envelope is measured again only when its bound comes
 * near the smallest one: on a path past one obstacle the others cost nothing. */
#define TRACK_MAX    64  /* obstacles tracked (beyond: measured at every sample) */
#define TRACK_NEAR   1.0 /* in: obstacles bounded closer than this are always measured */
#define TRACK_FACTOR 2.0 /* ... and those within this factor of the nearest bound */
typedef struct track {
    double lb[TRACK_MAX];
    int fresh; /* no sample yet: measure everything */
} track;

static double measure(const fbrl_cell_model *c, size_t k, const double a[3], const double b[3],
                      double near[3])
{
    const fbrl_cell_obj *o = &c->obj[k];
    double oa[3], ob[3], nb[3], d;
    to_obj(c, o, a, oa);
    to_obj(c, o, b, ob);
    d = (o->kind == FBRL_CELL_CYLINDER ? seg_cyl(o, oa, ob, nb) : seg_box(o->lo, o->hi, oa, ob, nb)) -
        c->tool_r;
    from_obj(c, o, nb, near);
    return d;
}

/* Clearance of the envelope at q: the least over the table and every obstacle (a lower
 * bound for obstacles t says are far; exact for the nearest). */
static double clearance(const fbrl_cell_model *c, const double a[3], const double b[3], track *t,
                        size_t *which, double near[3])
{
    double best = INFINITY, nb[3], floor_lb = INFINITY;
    *which = FBRL_CELL_NONE;
    if (c->have_table) {
        int lower = a[2] < b[2];
        best = (lower ? a[2] : b[2]) - c->table_z - c->tool_r;
        memcpy(near, lower ? a : b, sizeof nb);
        near[2] = c->table_z;
        *which = FBRL_CELL_TABLE;
    }
    if (t && !t->fresh)
        for (size_t k = 0; k < c->n && k < TRACK_MAX; k++)
            if (t->lb[k] < floor_lb)
                floor_lb = t->lb[k];
    for (size_t k = 0; k < c->n; k++) {
        double d;
        if (t && !t->fresh && k < TRACK_MAX && t->lb[k] > TRACK_NEAR && t->lb[k] > TRACK_FACTOR * floor_lb &&
            t->lb[k] > best) {
            continue; /* far: its bound stands for it, and it cannot be the least */
        }
        if (c->obj[k].kind == FBRL_CELL_CYLINDER) {
            /* the box around the cylinder is nearer than the cylinder: if even that is further
             * than the least so far, its distance is bound enough (the exact one costs more) */
            const fbrl_cell_obj *o = &c->obj[k];
            double lo[3] = {o->c[0] - o->r, o->c[1] - o->r, o->lo[2]},
                   hi[3] = {o->c[0] + o->r, o->c[1] + o->r, o->hi[2]};
            double oa[3], ob[3], bd;
            to_obj(c, o, a, oa);
            to_obj(c, o, b, ob);
            bd = seg_box(lo, hi, oa, ob, nb) - c->tool_r;
            if (bd > best) {
                if (t && k < TRACK_MAX)
                    t->lb[k] = bd;
                continue;
            }
        }
        d = measure(c, k, a, b, nb);
        if (t && k < TRACK_MAX)
            t->lb[k] = d;
        if (d < best) {
            best = d;
            *which = k;
            memcpy(near, nb, sizeof nb);
        }
    }
    if (t)
        t->fresh = 0;
    return best;
}

/* The envelope moved at most dist since the bounds were taken. */
static void track_moved(track *t, size_t n, double dist)
{
    for (size_t k = 0; t && k < n && k < TRACK_MAX; k++)
        t->lb[k] -= dist;
}

/* How far (in) any point of the envelope can move per degree of each joint: its largest
 * distance from that joint's axis (roll turns the capsule about its own axis: nothing). */
static void lever(const fbrl_cell_model *c, double k[FBRL_CELL_AXES])
{
    const fbrl_cell_arm *m = &c->arm;
    double tool = m->flange + c->tool_len + c->tool_r;
    k[0] = k[1] = RAD(m->upper + m->fore + tool);
    k[2] = RAD(m->fore + tool);
    k[3] = RAD(tool);
    k[4] = 0.0;
}

static double moved(const double k[FBRL_CELL_AXES], const double a[FBRL_CELL_AXES],
                    const double b[FBRL_CELL_AXES])
{
    double s = 0.0;
    for (int i = 0; i < FBRL_CELL_AXES; i++)
        s += k[i] * fabs(b[i] - a[i]);
    return s;
}

static void begin(fbrl_cell_hit *h)
{
    memset(h, 0, sizeof *h);
    h->obj = h->near_obj = FBRL_CELL_NONE;
    h->clearance = INFINITY;
}

/* One sample: note the clearance; 1 if it hits. */
/* ab: the envelope's axis at q (a then b), or NULL to compute it. */
static int sample(const fbrl_cell_model *c, const double q[FBRL_CELL_AXES], double f, fbrl_cell_hit *h,
                  double *d, track *t, const double *ab)
{
    size_t which;
    double near[3], e[6];
    if (!ab) {
        envelope(c, q, e, e + 3);
        ab = e;
    }
    *d = clearance(c, ab, ab + 3, t, &which, near);
    h->samples++;
    if (*d < h->clearance) {
        h->clearance = *d;
        h->near_obj = which;
        memcpy(h->near, near, sizeof near);
    }
    if (*d <= 0.0 && which != FBRL_CELL_NONE) {
        h->hit = 1;
        h->obj = which;
        h->fraction = f;
        memcpy(h->at, near, sizeof near);
        memcpy(h->q_end, q, sizeof h->q_end);
        return 1;
    }
    return 0;
}

static double step_for(double d) { return d > MIN_STEP ? d : MIN_STEP; }

fbrl_status fbrl_cell_check_pose(const fbrl_cell_model *c, const double q[FBRL_CELL_AXES], fbrl_cell_hit *h)
{
    double d;
    if (!ok(c) || !q || !h)
        return FBRL_EINVAL;
    begin(h);
    memcpy(h->q_end, q, sizeof h->q_end);
    (void)sample(c, q, 0.0, h, &d, NULL, NULL);
    return FBRL_OK;
}

fbrl_status fbrl_cell_check_joints(const fbrl_cell_model *c, const double q0[FBRL_CELL_AXES],
                                   const double q1[FBRL_CELL_AXES], fbrl_cell_hit *h)
{
    double k[FBRL_CELL_AXES], len, f = 0.0, d, q[FBRL_CELL_AXES];
    track t;
    if (!ok(c) || !q0 || !q1 || !h)
        return FBRL_EINVAL;
    begin(h);
    t.fresh = 1;
    lever(c, k);
    len = moved(k, q0, q1); /* in of motion of the fastest envelope point over the whole move */
    for (;;) {
        for (int i = 0; i < FBRL_CELL_AXES; i++)
            q[i] = q0[i] + (q1[i] - q0[i]) * f;
        if (sample(c, q, f, h, &d, &t, NULL))
            return FBRL_OK;
        if (f >= 1.0 || len <= 0.0)
            break;
        if (h->samples >= MAX_SAMPLES)
            return FBRL_ERANGE;
        double nf = f + step_for(d) / len;
        if (nf > 1.0)
            nf = 1.0;
        track_moved(&t, c->n, (nf - f) * len);
        f = nf;
    }
    memcpy(h->q_end, q1, sizeof h->q_end);
    return FBRL_OK;
}

/* How far any point of the envelope moves between two nearby poses of a straight line: its
 * axis' ends move that far, its surface as much more as the axis turns (waist, pitch), and
 * LINE_SLACK for the bend of the path between the two samples. */
static double env_moved(const fbrl_cell_model *c, const double q[FBRL_CELL_AXES], const double ab[6],
                        const double qn[FBRL_CELL_AXES], double abn[6])
{
    const double *a = ab, *b = ab + 3;
    double *an = abn, *bn = abn + 3, da = 0.0, db = 0.0;
    envelope(c, qn, an, bn);
    for (int i = 0; i < 3; i++) {
        da += (an[i] - a[i]) * (an[i] - a[i]);
        db += (bn[i] - b[i]) * (bn[i] - b[i]);
    }
    double turn = fabs(qn[0] - q[0]) + fabs((qn[1] + qn[2] + qn[3]) - (q[1] + q[2] + q[3]));
    return LINE_SLACK * (sqrt(da > db ? da : db) + c->tool_r * RAD(turn));
}

fbrl_status fbrl_cell_check_line(const fbrl_cell_model *c, const double q0[FBRL_CELL_AXES],
                                 const double pose1[6], fbrl_cell_hit *h)
{
    double p0[6], pose[6], f = 0.0, d, q[FBRL_CELL_AXES], qn[FBRL_CELL_AXES], dist, ab[6], abn[6], step = 0.0;
    track t;
    if (!ok(c) || !q0 || !pose1 || !h)
        return FBRL_EINVAL;
    begin(h);
    t.fresh = 1;
    fbrl_cell_fk(&c->arm, q0, p0);
    memcpy(q, q0, sizeof q);
    envelope(c, q, ab, ab + 3);
    dist = sqrt((pose1[0] - p0[0]) * (pose1[0] - p0[0]) + (pose1[1] - p0[1]) * (pose1[1] - p0[1]) +
                (pose1[2] - p0[2]) * (pose1[2] - p0[2])) +
           RAD(fabs(pose1[4] - p0[4])) * (c->arm.flange + c->tool_len + c->tool_r);
    for (;;) {
        if (sample(c, q, f, h, &d, &t, ab))
            return FBRL_OK;
        if (f >= 1.0)
            break;
        if (h->samples >= MAX_SAMPLES)
            return FBRL_ERANGE;
        /* the step the clearance allows, halved until the joints' motion keeps to it */
        double allow = step_for(d), df = dist > 0 ? allow / (dist * LINE_SLACK * LINE_SLACK) : 1.0, nf = 0.0;
        int tries;
        for (tries = 0; tries < LINE_HALVE; tries++, df *= 0.5) {
            nf = f + df > 1.0 ? 1.0 : f + df;
            for (int i = 0; i < 6; i++)
                pose[i] = p0[i] + (pose1[i] - p0[i]) * nf;
            if (fbrl_cell_ik(&c->arm, pose, q, qn) != FBRL_OK) {
                memcpy(h->q_end, q, sizeof h->q_end);
                h->fraction = f;
                return FBRL_ERANGE; /* the controller refuses such a line (068) */
            }
            if ((step = env_moved(c, q, ab, qn, abn)) <= allow)
                break;
        }
        if (tries == LINE_HALVE) {
            memcpy(h->q_end, q, sizeof h->q_end);
            h->fraction = f;
            return FBRL_ERANGE; /* a joint jumps: not a line the arm can follow */
        }
        track_moved(&t, c->n, step);
        memcpy(q, qn, sizeof q);
        memcpy(ab, abn, sizeof ab);
        f = nf;
    }
    memcpy(h->q_end, q, sizeof h->q_end);
    return FBRL_OK;
}
