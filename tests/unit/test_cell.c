/* SPDX-License-Identifier: MIT */
/* test_cell.c - the work cell's geometry: kinematics against hand-computed poses, path
 * checks against a brute-force dense sampling of the same motion, thin obstacles, blocks
 * carried by their calibration, and bad descriptions. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <math.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/cell.h"

#define PI 3.14159265358979323846

static fbrl_cell_obj store[16];
static fbrl_cell_model cell;

static void setup_cell(void)
{
    assert_int_equal(fbrl_cell_init(&cell, store, 16), FBRL_OK);
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

/* READY: upper arm vertical, forearm and flange horizontal: 10 + 2 in ahead, 20 in up. */
static void fk_by_hand(void **state)
{
    double q[5] = {0, 90, -90, 0, 0}, p[6];
    (void)state;
    fbrl_cell_fk(&fbrl_cell_arm_a255, q, p);
    assert_true(fabs(p[0] - 12.0) < 1e-9 && fabs(p[1]) < 1e-9 && fabs(p[2] - 20.0) < 1e-9);
    assert_true(fabs(p[4]) < 1e-9);
    /* waist 90, shoulder 0 (upper arm forward), elbow 0, wrist -90: tool down at 20 in */
    double q2[5] = {90, 0, 0, -90, 30};
    fbrl_cell_fk(&fbrl_cell_arm_a255, q2, p);
    assert_true(fabs(p[0]) < 1e-9 && fabs(p[1] - 20.0) < 1e-9 && fabs(p[2] - 8.0) < 1e-9);
    assert_true(fabs(p[4] + 90.0) < 1e-9 && fabs(p[5] - 30.0) < 1e-9);
}

static void ik_round_trip(void **state)
{
    double hint[5] = {0, 90, -90, 0, 0};
    (void)state;
    for (double x = 9; x <= 16; x += 3.5)
        for (double y = -6; y <= 6; y += 4)
            for (double z = 2; z <= 11; z += 3) {
                double pose[6] = {x, y, z, 0, -90, 10}, q[5], back[6];
                assert_int_equal(fbrl_cell_ik(&fbrl_cell_arm_a255, pose, hint, q), FBRL_OK);
                fbrl_cell_fk(&fbrl_cell_arm_a255, q, back);
                for (int i = 0; i < 3; i++)
                    assert_true(fabs(back[i] - pose[i]) < 1e-9);
                assert_true(fabs(q[0] - atan2(y, x) * 180 / PI) < 1e-9); /* the waist points at it */
            }
    double far[6] = {30, 0, 5, 0, -90, 0}, q[5];
    assert_int_equal(fbrl_cell_ik(&fbrl_cell_arm_a255, far, hint, q), FBRL_ERANGE);
}

/* Independent truth: the capsule as 200 points along its axis (each a ball of the tool's
 * radius), the path as 4000 evenly spaced poses; distance of a point to a box. */
static double brute_box_clearance(const fbrl_cell_obj *o, const double q0[5], const double q1[5])
{
    const fbrl_cell_arm *m = &fbrl_cell_arm_a255;
    double best = INFINITY;
    for (int s = 0; s <= 4000; s++) {
        double f = s / 4000.0, q[5];
        for (int i = 0; i < 5; i++)
            q[i] = q0[i] + (q1[i] - q0[i]) * f;
        double a2 = q[1] * PI / 180, a3 = (q[1] + q[2]) * PI / 180, p = (q[1] + q[2] + q[3]) * PI / 180;
        double rw = m->upper * cos(a2) + m->fore * cos(a3),
               zw = m->base_h + m->upper * sin(a2) + m->fore * sin(a3);
        for (int k = 0; k <= 200; k++) {
            double t = (m->flange + 1.0) * k / 200.0, r = rw + t * cos(p), z = zw + t * sin(p);
            double pt[3] = {r * cos(q[0] * PI / 180), r * sin(q[0] * PI / 180), z}, e = 0;
            for (int i = 0; i < 3; i++) {
                double d = pt[i] < o->lo[i] ? o->lo[i] - pt[i] : pt[i] > o->hi[i] ? pt[i] - o->hi[i] : 0;
                e += d * d;
            }
            if (sqrt(e) - 0.25 < best)
                best = sqrt(e) - 0.25;
        }
    }
    return best;
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
    assert_int_equal(fbrl_cell_ik(&cell.arm, p0, hint, q0), FBRL_OK);
    assert_int_equal(fbrl_cell_ik(&cell.arm, p1, hint, q1), FBRL_OK);
    assert_int_equal(fbrl_cell_check_pose(&cell, q0, &h), FBRL_OK);
    assert_false(h.hit);
    assert_int_equal(fbrl_cell_check_pose(&cell, q1, &h), FBRL_OK);
    assert_false(h.hit);
    assert_int_equal(fbrl_cell_check_joints(&cell, q0, q1, &h), FBRL_OK);
    assert_true(h.hit);
    assert_int_equal(h.obj, 0);
    assert_string_equal(fbrl_cell_obj_name(&cell, h.obj), "POST");
    assert_true(h.fraction > 0.2 && h.fraction < 0.5);
    assert_true(brute_box_clearance(&b, q0, q1) < 0); /* the truth agrees it hits */
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
    double truth = brute_box_clearance(&b, q0, q1);
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
    fbrl_cell_obj k = box("NO-GO", 8, -1, 0, 12, 1, 20);
    k.kind = FBRL_CELL_KEEPOUT;
    assert_int_equal(fbrl_cell_add(&cell, &k), FBRL_OK);
    assert_int_equal(fbrl_cell_ik(&cell.arm, p0, hint, q0), FBRL_OK);
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
    assert_int_equal(fbrl_cell_ik(&cell.arm, below, hint, q), FBRL_OK);
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
    assert_int_equal(fbrl_cell_ik(&cell.arm, above, hint, q), FBRL_OK);
    assert_int_equal(fbrl_cell_check_pose(&cell, q, &h), FBRL_OK);
    assert_false(h.hit);
    assert_true(fabs(h.clearance - 0.25) < 1e-6);
    above[2] = 5.0;
    assert_int_equal(fbrl_cell_ik(&cell.arm, above, hint, q), FBRL_OK);
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
    assert_int_equal(fbrl_cell_ik(&cell.arm, pose, hint, q), FBRL_OK);
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
    assert_int_equal(fbrl_cell_ik(&cell.arm, side, hint, q), FBRL_OK);
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(fk_by_hand),
        cmocka_unit_test(ik_round_trip),
        cmocka_unit_test(joint_path_through_box),
        cmocka_unit_test(clearance_matches_brute_force),
        cmocka_unit_test(thin_wall_is_not_skipped),
        cmocka_unit_test(straight_line_through_keepout),
        cmocka_unit_test(table_and_cylinder),
        cmocka_unit_test(block_carries_its_box),
        cmocka_unit_test(bad_descriptions),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
