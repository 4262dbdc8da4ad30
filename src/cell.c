/* SPDX-License-Identifier: MIT */
/* cell.c - the work cell's geometry and the path check (cell.h, docs/workcell.md). */
#include <math.h>
#include <string.h>

#include "fbrl/cell.h"

#define CELL_MAGIC 0x43454C4Cu /* "CELL" */
#define PI         3.14159265358979323846
#define RAD(d)     ((d) * (PI / 180.0))

#define AXIS_EPS  1e-9 /* in: closer to a cylinder's axis than this, its direction is free */
#define GOLDEN_IT 48   /* golden-section steps for a segment against a cylinder */
/* in: the step near an obstacle. A point that moves at most this far per step cannot pass
 * through a slab at least this thick without a sample inside it (and the bound on the
 * motion is generous: the body moves less). */
#define MIN_STEP    (FBRL_CELL_THIN * 0.9)
#define MAX_SAMPLES 100000u /* a path check gives up (FBRL_ERANGE) beyond this */
#define LINE_HALVE  30      /* step halvings on a straight line before it counts as a jump */
#define LINE_SLACK  1.25    /* margin for the bend of a straight line's joint path between samples */
#define LINE_GUESS  1.1     /* a straight line's next step aims this much below the length allowed */

static int ok(const fbrl_cell_model *c) { return c && c->magic == CELL_MAGIC; }

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
    c->arm = fbrl_arm_model(0);
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

fbrl_status fbrl_cell_set_arm(fbrl_cell_model *c, const fbrl_arm *arm, double tcp)
{
    if (!ok(c) || !arm)
        return FBRL_EINVAL;
    if (!isfinite(tcp))
        return FBRL_ENONFINITE;
    if (arm->naxes > FBRL_CELL_AXES || !(arm->upper > 0) || !(arm->fore > 0) || !(arm->flange >= 0) ||
        !(arm->r_upper >= 0) || !(arm->r_fore >= 0) || !isfinite(arm->base_h) || tcp < 0)
        return FBRL_ERANGE;
    c->arm = arm;
    c->tcp = tcp;
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

/* ---- the arm's body at a pose ---- */

/* The whole arm at joints q: upper arm, forearm (with the wrist housing) and the tool from the
 * wrist centre through the tool point to tool_len beyond it (fbrl_arm_body). */
static void body(const fbrl_cell_model *c, const double *q, fbrl_arm_capsule s[FBRL_ARM_PARTS])
{
    fbrl_arm_body(c->arm, q, c->tcp + c->tool_len, c->tool_r, s);
}

/* What a path check remembers between samples: for each part of the arm and each obstacle a
 * lower bound of their clearance (the distance when last measured, less how far the body may
 * have moved since). A sample measures the pairs nearest first and stops at the first bound
 * above the least distance found: on a path past one obstacle the others, and the parts far
 * from it, cost nothing. */
#define TRACK_MAX FBRL_CELL_MAX_OBJ /* obstacles tracked, the words' cell's (beyond: every sample) */
typedef struct track {
    double lb[FBRL_ARM_PARTS][TRACK_MAX];
    int fresh; /* no sample yet: no bounds */
} track;

/* A lower bound of a capsule's distance to the box lo..hi, cheap: the gap between the box and
 * the capsule's own bounding box. */
static double box_gap(const double lo[3], const double hi[3], const double a[3], const double b[3], double r)
{
    double g = 0.0;
    for (int i = 0; i < 3; i++) {
        double cl = a[i] < b[i] ? a[i] : b[i], ch = a[i] < b[i] ? b[i] : a[i];
        double d = cl > hi[i] ? cl - hi[i] : lo[i] > ch ? lo[i] - ch : 0.0;
        g += d * d;
    }
    return sqrt(g) - r;
}

/* The box around obstacle o (a cylinder's is nearer than the cylinder). */
static void bounds(const fbrl_cell_obj *o, double lo[3], double hi[3])
{
    if (o->kind == FBRL_CELL_CYLINDER) {
        lo[0] = o->c[0] - o->r, lo[1] = o->c[1] - o->r, lo[2] = o->lo[2];
        hi[0] = o->c[0] + o->r, hi[1] = o->c[1] + o->r, hi[2] = o->hi[2];
    } else {
        memcpy(lo, o->lo, 3 * sizeof *lo);
        memcpy(hi, o->hi, 3 * sizeof *hi);
    }
}

/* A cheap lower bound of the part's distance to obstacle k. */
static double rough(const fbrl_cell_model *c, size_t k, const fbrl_arm_capsule *s)
{
    const fbrl_cell_obj *o = &c->obj[k];
    double oa[3], ob[3], lo[3], hi[3];
    to_obj(c, o, s->a, oa);
    to_obj(c, o, s->b, ob);
    bounds(o, lo, hi);
    return box_gap(lo, hi, oa, ob, s->r);
}

/* The part's distance to obstacle k (negative: inside) and the obstacle's nearest point; or,
 * when a cheaper lower bound already exceeds `above`, that bound (*exact = 0). */
static double measure(const fbrl_cell_model *c, size_t k, const fbrl_arm_capsule *s, double above,
                      double near[3], int *exact)
{
    const fbrl_cell_obj *o = &c->obj[k];
    double oa[3], ob[3], nb[3], lo[3], hi[3], d;
    to_obj(c, o, s->a, oa);
    to_obj(c, o, s->b, ob);
    bounds(o, lo, hi);
    *exact = 0;
    if ((d = box_gap(lo, hi, oa, ob, s->r)) > above)
        return d;
    d = seg_box(lo, hi, oa, ob, nb) - s->r;
    if (o->kind == FBRL_CELL_CYLINDER) {
        if (d > above) /* the exact distance to a cylinder costs more */
            return d;
        d = seg_cyl(o, oa, ob, nb) - s->r;
    }
    *exact = 1;
    from_obj(c, o, nb, near);
    return d;
}

/* What a clearance found nearest: the obstacle (or the table), the part, the point. */
typedef struct nearest {
    double d;
    size_t obj;
    int part;
    double at[3];
} nearest;

static void note(nearest *n, double d, size_t obj, int part, const double at[3])
{
    if (d < n->d) {
        n->d = d, n->obj = obj, n->part = part;
        memcpy(n->at, at, sizeof n->at);
    }
}

/* Clearance of the body: the least over its parts against the table and every obstacle. The
 * pairs whose bound lies below the least so far are taken nearest bound first, each measured
 * exactly only while its bound still lies below the least distance found; the others keep
 * their bound (in t). Without bounds (a fresh track, or none) each pair's is a cheap one. */
static void clearance(const fbrl_cell_model *c, const fbrl_arm_capsule *s, track *t, nearest *n)
{
    double nb[3], bound[FBRL_ARM_PARTS * TRACK_MAX];
    unsigned short pair[FBRL_ARM_PARTS * TRACK_MAX]; /* part * TRACK_MAX + obstacle */
    size_t nt = c->n < TRACK_MAX ? c->n : TRACK_MAX, np = 0;
    int exact, bounded = t && !t->fresh;
    n->d = INFINITY, n->obj = FBRL_CELL_NONE, n->part = FBRL_ARM_TOOL;
    for (int j = FBRL_ARM_PARTS - 1; j >= 0 && c->have_table; j--) {
        const fbrl_arm_capsule *p = &s[j];
        const double *low = p->a[2] < p->b[2] ? p->a : p->b;
        double at[3] = {low[0], low[1], c->table_z};
        note(n, low[2] - c->table_z - p->r, FBRL_CELL_TABLE, j, at);
    }
    for (size_t k = nt; k < c->n; k++) /* untracked: every part, every sample */
        for (int j = FBRL_ARM_PARTS - 1; j >= 0; j--) {
            double d = measure(c, k, &s[j], n->d, nb, &exact);
            if (exact)
                note(n, d, k, j, nb);
        }
    for (int j = FBRL_ARM_PARTS - 1; j >= 0; j--) /* the candidates, by bound (insertion) */
        for (size_t k = 0; k < nt; k++) {
            double b = bounded ? t->lb[j][k] : rough(c, k, &s[j]);
            if (t && !bounded) /* a fresh track: every pair gets its cheap bound, at least */
                t->lb[j][k] = b;
            if (b >= n->d)
                continue;
            size_t at = np++;
            for (; at > 0 && bound[at - 1] > b; at--) {
                bound[at] = bound[at - 1];
                pair[at] = pair[at - 1];
            }
            bound[at] = b;
            pair[at] = (unsigned short)(j * TRACK_MAX + (int)k);
        }
    for (size_t i = 0; i < np && bound[i] < n->d; i++) {
        int j = pair[i] / TRACK_MAX;
        size_t k = pair[i] % TRACK_MAX;
        double d = measure(c, k, &s[j], n->d, nb, &exact);
        if (t)
            t->lb[j][k] = d;
        if (exact)
            note(n, d, k, j, nb);
    }
    if (t)
        t->fresh = 0;
}

/* Each part of the body moved at most dist[part] since the bounds were taken. */
static void track_moved(track *t, size_t n, const double dist[FBRL_ARM_PARTS])
{
    for (int j = 0; t && j < FBRL_ARM_PARTS; j++)
        for (size_t k = 0; k < n && k < TRACK_MAX; k++)
            t->lb[j][k] -= dist[j];
}

/* How far each part of the body moves at most over the joint move a -> b. A capsule is its
 * axis grown by its radius, so a capsule whose axis' ends each moved at most d lies within d
 * of where it was (every point of the axis is a mix of its ends, and the radius only adds the
 * same ball to both): the ends of the axes are what counts, and fbrl_arm_levers bounds how
 * far they go per joint (the part's far end, point part + 1 of the chain, goes furthest). */
static void moved(const fbrl_cell_model *c, const double *a, const double *b, double len[FBRL_ARM_PARTS])
{
    double k[FBRL_CELL_AXES];
    for (int j = 0; j < FBRL_ARM_PARTS; j++) {
        fbrl_arm_levers(c->arm, j + 1, c->tcp + c->tool_len, k);
        len[j] = 0.0;
        for (unsigned i = 0; i < c->arm->naxes; i++)
            len[j] += k[i] * RAD(fabs(b[i] - a[i]));
    }
}

static void begin(fbrl_cell_hit *h)
{
    memset(h, 0, sizeof *h);
    h->obj = h->near_obj = FBRL_CELL_NONE;
    h->part = FBRL_ARM_TOOL;
    h->clearance = INFINITY;
}

/* One sample: note the clearance; 1 if it hits. s: the body at q, or NULL to compute it. */
static int sample(const fbrl_cell_model *c, const double *q, double f, fbrl_cell_hit *h, double *d, track *t,
                  const fbrl_arm_capsule *s)
{
    nearest n;
    fbrl_arm_capsule e[FBRL_ARM_PARTS];
    if (!s) {
        body(c, q, e);
        s = e;
    }
    clearance(c, s, t, &n);
    *d = n.d;
    h->samples++;
    if (n.d < h->clearance) {
        h->clearance = n.d;
        h->near_obj = n.obj;
        h->part = n.part;
        memcpy(h->near, n.at, sizeof n.at);
    }
    if (n.d <= 0.0 && n.obj != FBRL_CELL_NONE) {
        h->hit = 1;
        h->obj = n.obj;
        h->fraction = f;
        memcpy(h->at, n.at, sizeof n.at);
        memcpy(h->q_end, q, c->arm->naxes * sizeof *q);
        return 1;
    }
    return 0;
}

static double step_for(double d) { return d > MIN_STEP ? d : MIN_STEP; }

fbrl_status fbrl_cell_check_pose(const fbrl_cell_model *c, const double *q, fbrl_cell_hit *h)
{
    double d;
    if (!ok(c) || !q || !h)
        return FBRL_EINVAL;
    begin(h);
    memcpy(h->q_end, q, c->arm->naxes * sizeof *q);
    (void)sample(c, q, 0.0, h, &d, NULL, NULL);
    return FBRL_OK;
}

fbrl_status fbrl_cell_check_joints(const fbrl_cell_model *c, const double *q0, const double *q1,
                                   fbrl_cell_hit *h)
{
    double len[FBRL_ARM_PARTS], f = 0.0, d, q[FBRL_CELL_AXES], step[FBRL_ARM_PARTS];
    track t;
    if (!ok(c) || !q0 || !q1 || !h)
        return FBRL_EINVAL;
    unsigned n = c->arm->naxes;
    begin(h);
    t.fresh = 1;
    moved(c, q0, q1, len); /* in of motion of each part over the whole move; the tool's is most */
    for (;;) {
        for (unsigned i = 0; i < n; i++)
            q[i] = q0[i] + (q1[i] - q0[i]) * f;
        if (sample(c, q, f, h, &d, &t, NULL))
            return FBRL_OK;
        if (f >= 1.0 || len[FBRL_ARM_TOOL] <= 0.0)
            break;
        if (h->samples >= MAX_SAMPLES)
            return FBRL_ERANGE;
        double nf = f + step_for(d) / len[FBRL_ARM_TOOL];
        if (nf > 1.0)
            nf = 1.0;
        for (int j = 0; j < FBRL_ARM_PARTS; j++)
            step[j] = (nf - f) * len[j];
        track_moved(&t, c->n, step);
        f = nf;
    }
    memcpy(h->q_end, q1, n * sizeof *q1);
    return FBRL_OK;
}

/* How far each part of the body moves between two nearby samples of a straight line: as far
 * as the ends of its capsule's axis (see moved), times LINE_SLACK for the bend of the joints'
 * path between the two samples; the most of them. */
static double body_moved(const fbrl_arm_capsule *s, const fbrl_arm_capsule *sn, double part[FBRL_ARM_PARTS])
{
    double most = 0.0;
    for (int j = 0; j < FBRL_ARM_PARTS; j++) {
        double m = 0.0;
        for (int e = 0; e < 2; e++) {
            const double *p = e ? s[j].b : s[j].a, *pn = e ? sn[j].b : sn[j].a;
            double d = (pn[0] - p[0]) * (pn[0] - p[0]) + (pn[1] - p[1]) * (pn[1] - p[1]) +
                       (pn[2] - p[2]) * (pn[2] - p[2]);
            m = d > m ? d : m;
        }
        part[j] = LINE_SLACK * sqrt(m);
        most = part[j] > most ? part[j] : most;
    }
    return most;
}

fbrl_status fbrl_cell_check_line(const fbrl_cell_model *c, const double *q0, const double pose1[6],
                                 fbrl_cell_hit *h)
{
    double p0[6], pose[6], f = 0.0, d, q[FBRL_CELL_AXES], qn[FBRL_CELL_AXES], rate, turn, most = 0.0,
                           step[FBRL_ARM_PARTS];
    fbrl_arm_capsule s[FBRL_ARM_PARTS], sn[FBRL_ARM_PARTS];
    track t;
    if (!ok(c) || !q0 || !pose1 || !h)
        return FBRL_EINVAL;
    unsigned n = c->arm->naxes;
    size_t bytes = n * sizeof *q;
    begin(h);
    t.fresh = 1;
    fbrl_arm_fk(c->arm, q0, c->tcp, p0);
    memcpy(q, q0, bytes);
    body(c, q, s);
    /* how far the body goes per unit of the line, for the first step's length: a guess from the
     * tool's way, then as measured at the step before (halving corrects a step too long) */
    turn = fabs(pose1[4] - p0[4]) + fabs(pose1[5] - p0[5]) +
           (c->arm->form == FBRL_ARM_6R ? fabs(pose1[3] - p0[3]) : 0.0); /* a 5R's yaw is not its own */
    rate =
        LINE_SLACK * (sqrt((pose1[0] - p0[0]) * (pose1[0] - p0[0]) + (pose1[1] - p0[1]) * (pose1[1] - p0[1]) +
                           (pose1[2] - p0[2]) * (pose1[2] - p0[2])) +
                      RAD(turn) * (c->arm->flange + c->tcp + c->tool_len + c->tool_r));
    for (;;) {
        if (sample(c, q, f, h, &d, &t, s))
            return FBRL_OK;
        if (f >= 1.0)
            break;
        if (h->samples >= MAX_SAMPLES)
            return FBRL_ERANGE;
        /* the step the clearance allows, halved until the joints' motion keeps to it */
        double allow = step_for(d), df = rate > 0 ? allow / (rate * LINE_GUESS) : 1.0, nf = 0.0;
        int tries;
        for (tries = 0; tries < LINE_HALVE; tries++, df *= 0.5) {
            nf = f + df > 1.0 ? 1.0 : f + df;
            fbrl_arm_lerp(p0, pose1, nf, pose);
            if (fbrl_arm_ik(c->arm, pose, c->tcp, q, qn, NULL) != FBRL_OK) {
                memcpy(h->q_end, q, bytes);
                h->fraction = f;
                return FBRL_ERANGE; /* the controller refuses such a line (068) */
            }
            body(c, qn, sn);
            if ((most = body_moved(s, sn, step)) <= allow)
                break;
        }
        if (tries == LINE_HALVE) {
            memcpy(h->q_end, q, bytes);
            h->fraction = f;
            return FBRL_ERANGE; /* a joint jumps: not a line the arm can follow */
        }
        track_moved(&t, c->n, step);
        memcpy(q, qn, bytes);
        memcpy(s, sn, sizeof s);
        if (nf > f && most > 0.0)
            rate = most / (nf - f);
        f = nf;
    }
    memcpy(h->q_end, q, bytes);
    return FBRL_OK;
}
