/* SPDX-License-Identifier: MIT */
/* test_cell.c - the work cell's geometry: path checks of the whole arm (upper arm, forearm,
 * tool) against a brute-force dense sampling of the same motion with the arm built
 * independently (tests/support/arm_chain.h), for both arm models and random cluttered
 * cells; thin obstacles; the forearm over a tall rack; blocks carried by their calibration;
 * bad descriptions. The tests of the tool's envelope alone use an arm whose upper arm and
 * forearm have no thickness, so their hand-computed figures stay exact. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <math.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/cell.h"
#include "support/arm_chain.h"

#define PI 3.14159265358979323846

static fbrl_cell_obj store[16];
static fbrl_cell_model cell;
static fbrl_arm thin; /* the A255 with no thickness but the tool's */

/* The A255's tool envelope alone: the upper arm and forearm as lines. */
static void setup_cell(void)
{
    thin = *fbrl_arm_model(0);
    thin.r_upper = thin.r_fore = 0.0;
    assert_int_equal(fbrl_cell_init(&cell, store, 16), FBRL_OK);
    assert_int_equal(fbrl_cell_set_arm(&cell, &thin, 0.0), FBRL_OK);
    assert_int_equal(fbrl_cell_set_table(&cell, 0.0), FBRL_OK);
    assert_int_equal(fbrl_cell_set_tool(&cell, 1.0, 0.25), FBRL_OK);
}

static fbrl_cell_obj box(const char *name, double x0, double y0, double z0, double x1, double y1, double z1)
{
    fbrl_cell_obj o;
    memset(&o, 0, sizeof o);
    strcpy(o.name, name);
    o.kind = FBRL_CELL_BOX;
    o.block = -1;
    o.lo[0] = x0, o.lo[1] = y0, o.lo[2] = z0, o.hi[0] = x1, o.hi[1] = y1, o.hi[2] = z1;
    return o;
}

/* ---- the independent truth ---- */

/* Signed distance of a point to a box (negative inside: the depth). */
static double point_box(const fbrl_cell_obj *o, const double p[3])
{
    double out = 0.0, in = INFINITY;
    for (int i = 0; i < 3; i++) {
        double d = p[i] < o->lo[i] ? o->lo[i] - p[i] : p[i] > o->hi[i] ? p[i] - o->hi[i] : 0.0;
        out += d * d;
        in = fmin(in, fmin(p[i] - o->lo[i], o->hi[i] - p[i]));
    }
    return out > 0.0 ? sqrt(out) : -in;
}

/* The arm at q as NPTS points along each of its three capsules' axes (each a ball of the
 * capsule's radius) against boxes o[0..n) and the table at table_z: the least clearance, and
 * the part it belongs to (0 upper arm, 1 forearm, 2 tool). */
#define NPTS 60
static double brute_pose(const fbrl_arm *m, const double *q, double tool_len, double tool_r, double table_z,
                         const fbrl_cell_obj *o, int n, int *part)
{
    double j[4][3], end[4][3], r[3] = {m->r_upper, m->r_fore, tool_r}, best = INFINITY;
    int axis;
    ac_chain(m, q, 0.0, j, NULL, &axis);
    ac_chain(m, q, tool_len, end, NULL, &axis); /* end[3]: the tool's far end */
    for (int c = 0; c < 3; c++) {
        const double *a = j[c], *b = c == 2 ? end[3] : j[c + 1];
        for (int k = 0; k <= NPTS; k++) {
            double t = (double)k / NPTS, p[3], d;
            for (int i = 0; i < 3; i++)
                p[i] = a[i] + (b[i] - a[i]) * t;
            d = p[2] - table_z - r[c];
            for (int i = 0; i < n; i++)
                d = fmin(d, point_box(&o[i], p) - r[c]);
            if (d < best) {
                best = d;
                if (part)
                    *part = c;
            }
        }
    }
    return best;
}

/* A motion for the brute force: the joints at fraction f (0 if it has none there). */
typedef int (*motion_fn)(const void *ctx, double f, double *q);

typedef struct joint_move {
    const fbrl_arm *m;
    const double *q0, *q1;
} joint_move;

static int along_joints(const void *ctx, double f, double *q)
{
    const joint_move *j = ctx;
    for (unsigned i = 0; i < j->m->naxes; i++)
        q[i] = j->q0[i] + (j->q1[i] - j->q0[i]) * f;
    return 1;
}

/* A straight line of the tool point, its joints solved sample by sample from the last. */
typedef struct line_move {
    const fbrl_arm *m;
    double p0[6], p1[6], q[FBRL_ARM_AXES_MAX];
} line_move;

static int along_line(const void *ctx, double f, double *q)
{
    line_move *l = (line_move *)ctx;
    double pose[6];
    for (int i = 0; i < 6; i++)
        pose[i] = l->p0[i] + (l->p1[i] - l->p0[i]) * f;
    if (fbrl_arm_ik(l->m, pose, 0.0, l->q, q, NULL) != FBRL_OK)
        return 0;
    memcpy(l->q, q, sizeof l->q);
    return 1;
}

/* The least clearance over the motion from fraction 0 to `to` at steps + 1 evenly spaced
 * poses; *res: how far the truth may lie below it (half the most any chain point moved
 * between two samples, and half the points' spacing); NAN when the motion has no joints
 * somewhere. */
static double brute_motion(const fbrl_arm *m, motion_fn fn, const void *ctx, double to, int steps,
                           double tool_len, double tool_r, double table_z, const fbrl_cell_obj *o, int n,
                           int *part, double *res)
{
    double best = INFINITY, prev[4][3], moved = 0.0;
    double gap = fmax(fmax(m->upper, m->fore), m->flange + tool_len) / NPTS / 2.0;
    for (int s = 0; s <= steps; s++) {
        double q[FBRL_ARM_AXES_MAX], j[4][3];
        int p, axis;
        if (!fn(ctx, to * s / steps, q))
            return NAN;
        ac_chain(m, q, tool_len, j, NULL, &axis);
        for (int k = 0; s > 0 && k < 4; k++)
            moved = fmax(moved, sqrt((j[k][0] - prev[k][0]) * (j[k][0] - prev[k][0]) +
                                     (j[k][1] - prev[k][1]) * (j[k][1] - prev[k][1]) +
                                     (j[k][2] - prev[k][2]) * (j[k][2] - prev[k][2])));
        memcpy(prev, j, sizeof prev);
        double d = brute_pose(m, q, tool_len, tool_r, table_z, o, n, &p);
        if (d < best) {
            best = d;
            if (part)
                *part = p;
        }
    }
    if (res)
        *res = moved / 2.0 + gap;
    return best;
}

/* Along the joint path q0 -> q1. */
static double brute_path(const fbrl_arm *m, const double *q0, const double *q1, int steps, double tool_len,
                         double tool_r, double table_z, const fbrl_cell_obj *o, int n, int *part)
{
    joint_move j = {m, q0, q1};
    return brute_motion(m, along_joints, &j, 1.0, steps, tool_len, tool_r, table_z, o, n, part, NULL);
}

/* A joint move whose end points are clear but whose path sweeps through a box. */
static void joint_path_through_box(void **state)
{
    fbrl_cell_hit h;
    double q0[5], q1[5];
    double p0[6] = {12, -8, 4, 0, -90, 0}, p1[6] = {12, 8, 4, 0, -90, 0}, hint[5] = {0, 90, -90, 0, 0};
    (void)state;
    setup_cell();
    fbrl_cell_obj b = box("POST", 13, -1, 0, 15, 1, 6);
    assert_int_equal(fbrl_cell_add(&cell, &b), FBRL_OK);
    assert_int_equal(fbrl_arm_ik(cell.arm, p0, 0.0, hint, q0, NULL), FBRL_OK);
    assert_int_equal(fbrl_arm_ik(cell.arm, p1, 0.0, hint, q1, NULL), FBRL_OK);
    assert_int_equal(fbrl_cell_check_pose(&cell, q0, &h), FBRL_OK);
    assert_false(h.hit);
    assert_int_equal(fbrl_cell_check_pose(&cell, q1, &h), FBRL_OK);
    assert_false(h.hit);
    assert_int_equal(fbrl_cell_check_joints(&cell, q0, q1, &h), FBRL_OK);
    assert_true(h.hit);
    assert_int_equal(h.obj, 0);
    assert_string_equal(fbrl_cell_obj_name(&cell, h.obj), "POST");
    assert_true(h.fraction > 0.2 && h.fraction < 0.5);
    assert_true(brute_path(&thin, q0, q1, 4000, 1.0, 0.25, -INFINITY, &b, 1, NULL) <
                0); /* the truth agrees */
    /* the point of contact lies on the box */
    assert_true(h.at[0] >= 13 - 1e-9 && h.at[0] <= 15 + 1e-9 && h.at[1] >= -1 - 1e-9 && h.at[1] <= 1 + 1e-9);
}

/* A clear joint path: the smallest clearance agrees with the brute force within the
 * brute force's own resolution, and is never larger than it (no pass is skipped). */
static void clearance_matches_brute_force(void **state)
{
    fbrl_cell_hit h;
    double q0[5] = {-40, 40, -80, -50, 0}, q1[5] = {40, 50, -70, -70, 0};
    (void)state;
    setup_cell();
    assert_int_equal(fbrl_cell_set_table(&cell, -20.0), FBRL_OK); /* the table far away */
    fbrl_cell_obj b = box("CRATE", 10, -2, 0, 16, 2, 3.0);
    assert_int_equal(fbrl_cell_add(&cell, &b), FBRL_OK);
    assert_int_equal(fbrl_cell_check_joints(&cell, q0, q1, &h), FBRL_OK);
    double truth = brute_path(&thin, q0, q1, 4000, 1.0, 0.25, -INFINITY, &b, 1, NULL);
    assert_false(h.hit);
    assert_true(truth > 0);
    assert_true(fabs(h.clearance - truth) < 0.05);
    assert_true(h.samples < 2000);
}

/* A wall 0.1 in thick across a fast waist swing far out (the tool point moves 0.35 in per
 * degree): the check must not step over it. */
static void thin_wall_is_not_skipped(void **state)
{
    fbrl_cell_hit h;
    double q0[5] = {-60, 20, -40, -70, 0}, q1[5] = {60, 20, -40, -70, 0};
    (void)state;
    setup_cell();
    assert_int_equal(fbrl_cell_set_tool(&cell, 0.0, 0.0), FBRL_OK);
    fbrl_cell_obj w = box("FOIL", 5, -0.05, 0, 30, 0.05, 30);
    assert_int_equal(fbrl_cell_add(&cell, &w), FBRL_OK);
    assert_int_equal(fbrl_cell_check_joints(&cell, q0, q1, &h), FBRL_OK);
    assert_true(h.hit);
    assert_true(fabs(h.fraction - 0.5) < 0.01);
}

/* A straight line through a keep-out zone; the same line ending short of it is clear. */
static void straight_line_through_keepout(void **state)
{
    fbrl_cell_hit h;
    double hint[5] = {0, 90, -90, 0, 0}, q0[5], p0[6] = {10, -6, 5, 0, -90, 0}, p1[6] = {10, 6, 5, 0, -90, 0};
    double p2[6] = {10, -2, 5, 0, -90, 0};
    (void)state;
    setup_cell();
    fbrl_cell_obj k = box("NO-GO", 8, -1, 0, 12, 1, 6); /* below the forearm (7 in up and higher) */
    k.kind = FBRL_CELL_KEEPOUT;
    assert_int_equal(fbrl_cell_add(&cell, &k), FBRL_OK);
    assert_int_equal(fbrl_arm_ik(cell.arm, p0, 0.0, hint, q0, NULL), FBRL_OK);
    assert_int_equal(fbrl_cell_check_line(&cell, q0, p1, &h), FBRL_OK);
    assert_true(h.hit);
    assert_true(h.at[1] <= -1 + 1e-6); /* met where it enters, at y = -1 */
    assert_int_equal(fbrl_cell_check_line(&cell, q0, p2, &h), FBRL_OK);
    assert_false(h.hit);
    assert_true(fabs(h.clearance - (1.0 - 0.25)) < 1e-6); /* tool radius short of y = -1 */
}

static void table_and_cylinder(void **state)
{
    fbrl_cell_hit h;
    double hint[5] = {0, 90, -90, 0, 0}, q[5], below[6] = {12, 0, -0.5, 0, -90, 0};
    (void)state;
    setup_cell();
    assert_int_equal(fbrl_arm_ik(cell.arm, below, 0.0, hint, q, NULL), FBRL_OK);
    assert_int_equal(fbrl_cell_check_pose(&cell, q, &h), FBRL_OK);
    assert_true(h.hit);
    assert_int_equal(h.obj, FBRL_CELL_TABLE);
    fbrl_cell_obj cyl;
    memset(&cyl, 0, sizeof cyl);
    strcpy(cyl.name, "VIAL");
    cyl.kind = FBRL_CELL_CYLINDER;
    cyl.block = -1;
    cyl.c[0] = 14, cyl.c[1] = 0, cyl.r = 1, cyl.lo[2] = 0, cyl.hi[2] = 4;
    assert_int_equal(fbrl_cell_add(&cell, &cyl), FBRL_OK);
    double above[6] = {14, 0, 5.5, 0, -90, 0}; /* tool end 1 in further down: 4.5; radius 0.25 */
    assert_int_equal(fbrl_arm_ik(cell.arm, above, 0.0, hint, q, NULL), FBRL_OK);
    assert_int_equal(fbrl_cell_check_pose(&cell, q, &h), FBRL_OK);
    assert_false(h.hit);
    assert_true(fabs(h.clearance - 0.25) < 1e-6);
    above[2] = 5.0;
    assert_int_equal(fbrl_arm_ik(cell.arm, above, 0.0, hint, q, NULL), FBRL_OK);
    assert_int_equal(fbrl_cell_check_pose(&cell, q, &h), FBRL_OK);
    assert_true(h.hit);
    assert_string_equal(fbrl_cell_obj_name(&cell, h.obj), "VIAL");
}

/* A block's keep-out box moves with the block: clear before, hit after. */
static void block_carries_its_box(void **state)
{
    fbrl_cell_hit h;
    int blk;
    double hint[5] = {0, 90, -90, 0, 0}, q[5], pose[6] = {12, 3, 2.1, 0, -90, 0};
    fbrl_calib m;
    (void)state;
    setup_cell();
    assert_int_equal(fbrl_cell_set_tool(&cell, 0.0, 0.2), FBRL_OK);
    assert_int_equal(fbrl_cell_block(&cell, "HEATER", 6, &blk), FBRL_OK);
    fbrl_cell_obj b = box("HEATER-BODY", 10, -2, 0, 14, 2, 2);
    b.block = blk;
    assert_int_equal(fbrl_cell_add(&cell, &b), FBRL_OK);
    assert_int_equal(fbrl_arm_ik(cell.arm, pose, 0.0, hint, q, NULL), FBRL_OK);
    assert_int_equal(fbrl_cell_check_pose(&cell, q, &h), FBRL_OK);
    assert_false(h.hit);
    fbrl_calib_identity(&m);
    m.t[1] = 1.5; /* the block put back 1.5 in to the left */
    assert_int_equal(fbrl_cell_set_block(&cell, blk, &m), FBRL_OK);
    assert_int_equal(fbrl_cell_check_pose(&cell, q, &h), FBRL_OK);
    assert_true(h.hit);
    assert_string_equal(fbrl_cell_obj_name(&cell, h.obj), "HEATER-BODY");
    /* a quarter turn about z instead: the box now spans x 10..14 -> y 10..14 */
    memset(&m, 0, sizeof m);
    m.r[0][1] = -1, m.r[1][0] = 1, m.r[2][2] = 1;
    assert_int_equal(fbrl_cell_set_block(&cell, blk, &m), FBRL_OK);
    double side[6] = {0, 12, 1.5, 0, -90, 0};
    assert_int_equal(fbrl_arm_ik(cell.arm, side, 0.0, hint, q, NULL), FBRL_OK);
    assert_int_equal(fbrl_cell_check_pose(&cell, q, &h), FBRL_OK);
    assert_true(h.hit);
}

static void bad_descriptions(void **state)
{
    (void)state;
    setup_cell();
    fbrl_cell_obj b = box("RACK", 0, 0, 0, 1, 1, 1);
    assert_int_equal(fbrl_cell_add(&cell, &b), FBRL_OK);
    assert_int_equal(fbrl_cell_add(&cell, &b), FBRL_ENAME); /* the name again */
    strcpy(b.name, "rack");
    assert_int_equal(fbrl_cell_add(&cell, &b), FBRL_ENAME); /* names are case-insensitive */
    b = box("FLAT", 0, 0, 1, 1, 1, 1);
    assert_int_equal(fbrl_cell_add(&cell, &b), FBRL_ERANGE);
    b = box("INSIDE-OUT", 2, 0, 0, 1, 1, 1);
    assert_int_equal(fbrl_cell_add(&cell, &b), FBRL_ERANGE);
    b = box("NAN", 0, 0, 0, NAN, 1, 1);
    assert_int_equal(fbrl_cell_add(&cell, &b), FBRL_ENONFINITE);
    b = box("", 0, 0, 0, 1, 1, 1);
    assert_int_equal(fbrl_cell_add(&cell, &b), FBRL_ENAME);
    assert_int_equal(fbrl_cell_set_tool(&cell, -1, 0), FBRL_ERANGE);
    b = box("ORPHAN", 0, 0, 0, 1, 1, 1);
    b.block = 3;
    assert_int_equal(fbrl_cell_add(&cell, &b), FBRL_ERANGE);
    double p[3] = {0.5, 0.5, 0.5}, d;
    size_t which;
    assert_int_equal(fbrl_cell_point_clearance(&cell, p, -2, &d, &which), FBRL_OK);
    assert_true(d < 0);
    assert_int_equal(which, 0);
    fbrl_cell_obj full[1];
    fbrl_cell_model small;
    assert_int_equal(fbrl_cell_init(&small, full, 1), FBRL_OK);
    b = box("A", 0, 0, 0, 1, 1, 1);
    assert_int_equal(fbrl_cell_add(&small, &b), FBRL_OK);
    b = box("B", 0, 0, 0, 1, 1, 1);
    assert_int_equal(fbrl_cell_add(&small, &b), FBRL_EFULL);
}

/* ---- the whole arm ---- */

static unsigned long g_x = 4321;

static double rnd(double lo, double hi)
{
    g_x = g_x * 6364136223846793005UL + 1442695040888963407UL;
    return lo + (hi - lo) * (double)(g_x >> 11) / 9007199254740992.0;
}

static void random_joints(const fbrl_arm *m, double *q)
{
    for (unsigned i = 0; i < m->naxes; i++)
        q[i] = rnd(m->min[i], m->max[i]);
}

/* Random cluttered cells (the table and five boxes in the arm's reach) and random joint
 * moves and straight lines from a clear start, for both arms: wherever the brute force finds
 * the arm (any of its three parts) inside something, the check finds a hit, and it finds
 * none where the brute force finds no contact; a hit is the first contact (the path before
 * it is clear). */
#define RANDOM_MOVES 40
static void whole_arm_matches_brute_force(void **state)
{
    const fbrl_arm *m;
    fbrl_cell_obj o[5];
    (void)state;
    for (size_t k = 0; (m = fbrl_arm_model(k)) != NULL; k++) {
        int hits[3] = {0, 0, 0}, clear = 0, lines = 0;
        double reach = m->upper + m->fore + m->flange;
        for (int trial = 0; trial < RANDOM_MOVES; trial++) {
            double q0[FBRL_ARM_AXES_MAX], q1[FBRL_ARM_AXES_MAX], res, truth, before;
            fbrl_cell_hit h, h0;
            fbrl_status st;
            int part = -1, tries = 0, straight = trial % 3 == 2;
            do { /* the moves from a clear start, one box near where the tool goes */
                double end[6];
                assert_true(++tries < 1000);
                random_joints(m, q0);
                random_joints(m, q1);
                fbrl_arm_fk(m, q1, 0.5, end);
                assert_int_equal(fbrl_cell_init(&cell, store, 16), FBRL_OK);
                assert_int_equal(fbrl_cell_set_arm(&cell, m, 0.0), FBRL_OK);
                assert_int_equal(fbrl_cell_set_table(&cell, 0.0), FBRL_OK);
                assert_int_equal(fbrl_cell_set_tool(&cell, 0.5, 0.2), FBRL_OK);
                for (int b = 0; b < 5; b++) {
                    double r = rnd(4.0, reach), a = rnd(-PI, PI), z = rnd(0.0, 2.0 * m->base_h);
                    double x = r * cos(a), y = r * sin(a), w = rnd(0.3, 4.0), d = rnd(0.3, 4.0),
                           hgt = rnd(0.3, 6.0);
                    char name[8] = {'B', (char)('0' + b), 0};
                    if (b == 0)
                        x = end[0] + rnd(-2, 2), y = end[1] + rnd(-2, 2), z = end[2] + rnd(-2, 1);
                    o[b] = box(name, x - w / 2, y - d / 2, z, x + w / 2, y + d / 2, z + hgt);
                    assert_int_equal(fbrl_cell_add(&cell, &o[b]), FBRL_OK);
                }
                fbrl_cell_check_pose(&cell, q0, &h0);
            } while (h0.hit);
            if (straight) {
                line_move l;
                l.m = m;
                fbrl_arm_fk(m, q0, 0.0, l.p0);
                fbrl_arm_fk(m, q1, 0.0, l.p1);
                memcpy(l.q, q0, sizeof l.q);
                st = fbrl_cell_check_line(&cell, q0, l.p1, &h);
                if (st != FBRL_OK)
                    continue; /* a line the arm cannot follow */
                truth = brute_motion(m, along_line, &l, 1.0, 600, 0.5, 0.2, 0.0, o, 5, &part, &res);
                if (isnan(truth))
                    continue;
                memcpy(l.q, q0, sizeof l.q);
                before =
                    h.hit ? brute_motion(m, along_line, &l, h.fraction, 600, 0.5, 0.2, 0.0, o, 5, NULL, NULL)
                          : INFINITY;
                lines++;
            } else {
                joint_move j = {m, q0, q1};
                assert_int_equal(fbrl_cell_check_joints(&cell, q0, q1, &h), FBRL_OK);
                truth = brute_motion(m, along_joints, &j, 1.0, 600, 0.5, 0.2, 0.0, o, 5, &part, &res);
                before = h.hit ? brute_motion(m, along_joints, &j, h.fraction, 600, 0.5, 0.2, 0.0, o, 5, NULL,
                                              NULL)
                               : INFINITY;
            }
            if (h.hit) {
                if (!(truth <= res))
                    fail_msg("%s move %d: a hit of the %s that the brute force does not see (%g, res %g)",
                             m->name, trial, fbrl_arm_part_name(h.part), truth, res);
                if (!(before >= -res))
                    fail_msg("%s move %d: a contact (%g) before the hit the check reports", m->name, trial,
                             before);
                hits[h.part]++;
            } else {
                if (!(truth >= -res))
                    fail_msg("%s move %d: the %s goes %g in deep into the cell, and the check saw nothing",
                             m->name, trial, fbrl_arm_part_name(part), -truth);
                clear++;
            }
        }
        print_message(
            "%s: %d moves clear, hits by the upper arm %d, the forearm %d, the tool %d (%d lines)\n", m->name,
            clear, hits[0], hits[1], hits[2], lines);
        assert_true(clear > 0 && hits[0] + hits[1] > 0 && hits[2] > 0 && lines > 0);
    }
}

/* The forearm over a tall rack: the tool reaches beyond the rack, clear of it, while the
 * forearm sweeps through its top; refused, naming the forearm, for both arms. The tool's
 * envelope alone (the thin arm) passes: what the guard checked before. */
static void forearm_over_a_tall_rack(void **state)
{
    static const struct {
        const char *arm;
        double start[6], target[6], rack[6];
    } cases[] = {
        /* the A255 reaching 16 in out over a rack 1 in thick, 9 in tall, 12-13 in out */
        {"a255", {12, -8, 13, 0, -90, 0}, {16, 0, 4, 0, -90, 0}, {12, -3, 0, 13, 3, 9}},
        /* the A465 reaching 17 in out over a rack 14-15 in out, 11 in tall */
        {"a465", {17, -8, 14, 0, -90, 0}, {17, 0, 5, 0, -90, 0}, {14, -3, 0, 15, 3, 11}},
    };
    (void)state;
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const fbrl_arm *m = fbrl_arm_find(cases[k].arm);
        const double *r = cases[k].rack;
        double q0[FBRL_ARM_AXES_MAX], q1[FBRL_ARM_AXES_MAX];
        fbrl_cell_hit h;
        int part;
        fbrl_cell_obj rack = box("TALL-RACK", r[0], r[1], r[2], r[3], r[4], r[5]);
        assert_int_equal(fbrl_arm_ik(m, cases[k].start, 0.0, m->ready, q0, NULL), FBRL_OK);
        assert_int_equal(fbrl_arm_ik(m, cases[k].target, 0.0, q0, q1, NULL), FBRL_OK);
        assert_int_equal(fbrl_cell_init(&cell, store, 16), FBRL_OK);
        assert_int_equal(fbrl_cell_set_tool(&cell, 0.5, 0.2), FBRL_OK);
        assert_int_equal(fbrl_cell_add(&cell, &rack), FBRL_OK);
        /* the tool alone: clear all the way */
        thin = *m;
        thin.r_upper = thin.r_fore = 0.0;
        assert_int_equal(fbrl_cell_set_arm(&cell, &thin, 0.0), FBRL_OK);
        assert_int_equal(fbrl_cell_check_joints(&cell, q0, q1, &h), FBRL_OK);
        assert_false(h.hit);
        /* the whole arm: the forearm meets the rack */
        assert_int_equal(fbrl_cell_set_arm(&cell, m, 0.0), FBRL_OK);
        assert_int_equal(fbrl_cell_check_pose(&cell, q1, &h), FBRL_OK);
        assert_true(h.hit);
        assert_int_equal(h.part, FBRL_ARM_FORE);
        assert_string_equal(fbrl_cell_obj_name(&cell, h.obj), "TALL-RACK");
        assert_true(brute_pose(m, q1, 0.5, 0.2, -INFINITY, &rack, 1, &part) < 0);
        assert_int_equal(part, FBRL_ARM_FORE);
        assert_int_equal(fbrl_cell_check_joints(&cell, q0, q1, &h), FBRL_OK);
        assert_true(h.hit);
        assert_int_equal(h.part, FBRL_ARM_FORE);
        assert_true(h.at[2] <= r[5] + 1e-9); /* met on the rack's top, not beyond it */
    }
}

/* A shelf over the A255 at READY: the elbow stands 20 in up, the upper arm's round end 1.25 in
 * above it, the forearm's 1 in; a shelf 0.9 in over the elbow is met by the upper arm. */
static void upper_arm_under_a_shelf(void **state)
{
    const fbrl_arm *m = fbrl_arm_model(0);
    fbrl_cell_hit h;
    int part;
    (void)state;
    fbrl_cell_obj shelf = box("SHELF", -3, -3, 20.9, 3, 3, 21.5);
    assert_int_equal(fbrl_cell_init(&cell, store, 16), FBRL_OK);
    assert_int_equal(fbrl_cell_add(&cell, &shelf), FBRL_OK);
    assert_int_equal(fbrl_cell_check_pose(&cell, m->ready, &h), FBRL_OK);
    assert_true(h.hit);
    assert_int_equal(h.part, FBRL_ARM_UPPER);
    assert_true(fabs(h.clearance - (0.9 - 1.25)) < 1e-9);
    assert_true(brute_pose(m, m->ready, 0.0, 0.0, -INFINITY, &shelf, 1, &part) < 0);
    assert_int_equal(part, FBRL_ARM_UPPER);
}

/* A foil 0.1 in thick that only the forearm crosses, in a fast waist swing, the forearm as
 * thin as a line: not skipped. */
static void thin_foil_for_the_forearm(void **state)
{
    double q0[5] = {-60, 20, -40, -70, 0}, q1[5] = {60, 20, -40, -70, 0};
    fbrl_cell_hit h;
    (void)state;
    /* the forearm runs 9.4 to 18.8 in out at 13.4 down to 10 in up; the tool is further out */
    fbrl_cell_obj foil = box("FOIL", 11, -0.05, 11, 14, 0.05, 13);
    setup_cell();
    assert_int_equal(fbrl_cell_set_tool(&cell, 0.0, 0.0), FBRL_OK);
    assert_int_equal(fbrl_cell_add(&cell, &foil), FBRL_OK);
    assert_int_equal(fbrl_cell_check_joints(&cell, q0, q1, &h), FBRL_OK);
    assert_true(h.hit);
    assert_int_equal(h.part, FBRL_ARM_FORE);
    assert_true(fabs(h.fraction - 0.5) < 0.01);
    assert_true(brute_path(&thin, q0, q1, 4000, 0.0, 0.0, -INFINITY, &foil, 1, NULL) < 0.01);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(joint_path_through_box),    cmocka_unit_test(clearance_matches_brute_force),
        cmocka_unit_test(thin_wall_is_not_skipped),  cmocka_unit_test(straight_line_through_keepout),
        cmocka_unit_test(table_and_cylinder),        cmocka_unit_test(block_carries_its_box),
        cmocka_unit_test(bad_descriptions),          cmocka_unit_test(whole_arm_matches_brute_force),
        cmocka_unit_test(forearm_over_a_tall_rack),  cmocka_unit_test(upper_arm_under_a_shelf),
        cmocka_unit_test(thin_foil_for_the_forearm),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
