/* SPDX-License-Identifier: MIT */
/* sim_arm_test.c - the emulated arms' kinematics (sim/arm.c), for every model.
 *
 * The truth for forward kinematics is computed here independently: each arm as
 * the physical chain of rotations and links its published geometry describes
 * (A255: DESIGN 6; A465: the DH lengths d1 330, a2 305, d4 330, d6 76 mm), and
 * the pose compared as three points of the tool frame, so yaw, pitch and roll
 * are checked too. Inverse kinematics is checked by round trips. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "arm.h"

#define ROUND_TRIPS 10000
#define TOL_IN      1e-6 /* in: the round trip's bound */

static void near(double a, double b, double eps)
{
    if (fabs(a - b) > eps)
        fail_msg("%.9f != %.9f (eps %g)", a, b, eps);
}

static const fbrl_sim_model *model(const char *name)
{
    const fbrl_sim_model *m = fbrl_sim_model_find(name);
    assert_non_null(m);
    return m;
}

/* ---- an independent chain ---------------------------------------------- */

typedef struct frame {
    double r[3][3], p[3];
} frame;

static void f_ident(frame *f)
{
    memset(f, 0, sizeof *f);
    f->r[0][0] = f->r[1][1] = f->r[2][2] = 1.0;
}

/* f = f * (rotation about local axis by deg) */
static void f_rot(frame *f, int axis, double deg)
{
    double c = cos(deg * M_PI / 180.0), s = sin(deg * M_PI / 180.0), m[3][3] = {{0}}, o[3][3];
    int i, j, k;
    int a = (axis + 1) % 3, b = (axis + 2) % 3;
    m[axis][axis] = 1.0;
    m[a][a] = c, m[a][b] = -s, m[b][a] = s, m[b][b] = c;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            o[i][j] = 0;
            for (k = 0; k < 3; k++)
                o[i][j] += f->r[i][k] * m[k][j];
        }
    memcpy(f->r, o, sizeof o);
}

/* f = f * (translation along local axis) */
static void f_move(frame *f, int axis, double d)
{
    int i;
    for (i = 0; i < 3; i++)
        f->p[i] += f->r[i][axis] * d;
}

/* Three points of the tool frame: the tool point, 1 in along the tool axis and
 * 1 in along the tool's y axis. */
typedef struct pts {
    double v[3][3];
} pts;

static void frame_pts(const frame *f, int tool_axis, int y_axis, double ysign, pts *out)
{
    int i;
    for (i = 0; i < 3; i++) {
        out->v[0][i] = f->p[i];
        out->v[1][i] = f->p[i] + f->r[i][tool_axis];
        out->v[2][i] = f->p[i] + ysign * f->r[i][y_axis];
    }
}

/* The same three points from a pose X Y Z yaw pitch roll: Rz(yaw) Ry(-pitch) Rx(roll). */
static void pose_pts(const double pose[6], pts *out)
{
    frame f;
    f_ident(&f);
    f.p[0] = pose[0], f.p[1] = pose[1], f.p[2] = pose[2];
    f_rot(&f, 2, pose[3]);
    f_rot(&f, 1, -pose[4]);
    f_rot(&f, 0, pose[5]);
    frame_pts(&f, 0, 1, 1.0, out);
}

/* The arm as its physical chain. */
static void chain(const fbrl_sim_model *m, const double *q, double tool, pts *out)
{
    frame f;
    f_ident(&f);
    f_rot(&f, 2, q[0]);
    f_move(&f, 2, m->base_h);
    if (m->kin == FBRL_SIM_KIN_5R) {
        /* links along local x; shoulder, elbow, wrist pitch raise it; roll about it */
        f_rot(&f, 1, -q[1]);
        f_move(&f, 0, m->upper);
        f_rot(&f, 1, -q[2]);
        f_move(&f, 0, m->fore);
        f_rot(&f, 1, -q[3]);
        f_move(&f, 0, m->flange + tool);
        f_rot(&f, 0, q[4]);
        frame_pts(&f, 0, 1, 1.0, out);
    } else {
        /* links along local z (upright at zero); shoulder and elbow lean forward;
         * forearm roll, wrist bend, tool roll */
        f_rot(&f, 1, q[1]);
        f_move(&f, 2, m->upper);
        f_rot(&f, 1, q[2]);
        f_move(&f, 2, m->fore);
        f_rot(&f, 2, q[3]);
        f_rot(&f, 1, q[4]);
        f_move(&f, 2, m->flange + tool);
        f_rot(&f, 2, q[5]);
        frame_pts(&f, 2, 1, 1.0, out);
    }
}

static double pts_dist(const pts *a, const pts *b)
{
    double worst = 0;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++)
            if (fabs(a->v[i][j] - b->v[i][j]) > worst)
                worst = fabs(a->v[i][j] - b->v[i][j]);
    return worst;
}

static unsigned long g_x = 12345;

static double rnd01(void)
{
    g_x = g_x * 6364136223846793005UL + 1442695040888963407UL;
    return (double)(g_x >> 11) / 9007199254740992.0;
}

static void random_joints(const fbrl_sim_model *m, double *q)
{
    int i;
    for (i = 0; i < m->naxes; i++)
        q[i] = m->min[i] + (m->max[i] - m->min[i]) * rnd01();
}

/* ---- both models ------------------------------------------------------- */

/* fbrl_sim_arm_fk agrees with the physical chain everywhere in the joint space. */
static void fk_matches_chain(void **st)
{
    int k, n;
    (void)st;
    for (k = 0; k < fbrl_sim_nmodels; k++) {
        const fbrl_sim_model *m = &fbrl_sim_models[k];
        for (n = 0; n < 2000; n++) {
            double q[FBRL_SIM_ARM_MAX_AXES], p[6], tool = n % 2 ? 0.0 : 1.25;
            pts a, b;
            random_joints(m, q);
            fbrl_sim_arm_fk(m, q, tool, p);
            pose_pts(p, &a);
            chain(m, q, tool, &b);
            if (pts_dist(&a, &b) > 1e-9)
                fail_msg("%s: FK differs from the chain by %g in", m->name, pts_dist(&a, &b));
        }
    }
}

/* 10,000 random reachable poses of each arm: IK finds joints inside the limits
 * whose pose is the same within 1e-6 in (three points of the tool frame). */
static void round_trip(void **st)
{
    int k;
    (void)st;
    for (k = 0; k < fbrl_sim_nmodels; k++) {
        const fbrl_sim_model *m = &fbrl_sim_models[k];
        int done = 0, same = 0, tries = 0;
        double worst = 0;
        while (done < ROUND_TRIPS) {
            double q[FBRL_SIM_ARM_MAX_AXES], back[FBRL_SIM_ARM_MAX_AXES], hint[FBRL_SIM_ARM_MAX_AXES];
            double p[6], r[6], tool = 0.5;
            pts a, b;
            int i, e;
            assert_true(++tries < 3 * ROUND_TRIPS);
            random_joints(m, q);
            if (fabs(q[2]) < 1e-3)
                continue; /* a straight elbow is singular */
            fbrl_sim_arm_fk(m, q, tool, p);
            if (hypot(p[0], p[1]) < 1e-3)
                continue; /* on the base axis the waist is free */
            /* half the time the arm starts elsewhere (READY), half where the pose is */
            memcpy(hint, done % 2 ? m->ready : q, sizeof hint);
            e = fbrl_sim_arm_ik(m, p, tool, hint, back);
            if (e != 0)
                fail_msg("%s: IK of a reachable pose gave %d (q %g %g %g %g %g %g)", m->name, e, q[0], q[1],
                         q[2], q[3], q[4], q[5]);
            assert_int_equal(fbrl_sim_arm_check(m, back), 0);
            fbrl_sim_arm_fk(m, back, tool, r);
            if (m->kin == FBRL_SIM_KIN_5R) {
                /* a 5-axis arm cannot choose its yaw (reaching backward turns it round):
                 * the tool point, the tool axis's elevation and the roll are the pose */
                double d = 0;
                for (i = 0; i < 3; i++)
                    d = fmax(d, fabs(r[i] - p[i]));
                d = fmax(d, fabs(fbrl_sim_arm_wrap(r[4] - p[4])) * M_PI / 180.0);
                d = fmax(d, fabs(fbrl_sim_arm_wrap(r[5] - p[5])) * M_PI / 180.0);
                worst = fmax(worst, d);
                if (d > TOL_IN)
                    fail_msg("%s: round trip off by %g in", m->name, d);
            } else {
                pose_pts(p, &a);
                pose_pts(r, &b);
                if (pts_dist(&a, &b) > worst)
                    worst = pts_dist(&a, &b);
                if (pts_dist(&a, &b) > TOL_IN)
                    fail_msg("%s: round trip off by %g in", m->name, pts_dist(&a, &b));
            }
            for (i = 0; i < m->naxes && fabs(fbrl_sim_arm_wrap(back[i] - q[i])) < 1e-6; i++)
                ;
            same += i == m->naxes;
            done++;
        }
        print_message("%s: %d round trips, worst %.3g in, %d in the same configuration\n", m->name, done,
                      worst, same);
        assert_true(same > ROUND_TRIPS / 4);
    }
}

static void limits(void **st)
{
    int k, i;
    (void)st;
    for (k = 0; k < fbrl_sim_nmodels; k++) {
        const fbrl_sim_model *m = &fbrl_sim_models[k];
        for (i = 0; i < m->naxes; i++) {
            double q[FBRL_SIM_ARM_MAX_AXES];
            int want = i < 5 ? 42 + i : 48;
            memcpy(q, m->ready, sizeof q);
            assert_int_equal(fbrl_sim_arm_check(m, q), 0);
            q[i] = m->max[i];
            assert_int_equal(fbrl_sim_arm_check(m, q), 0);
            q[i] = m->min[i];
            assert_int_equal(fbrl_sim_arm_check(m, q), 0);
            q[i] = m->max[i] + 0.01;
            assert_int_equal(fbrl_sim_arm_check(m, q), want);
            q[i] = m->min[i] - 0.01;
            assert_int_equal(fbrl_sim_arm_check(m, q), want);
            q[i] = NAN;
            assert_int_equal(fbrl_sim_arm_check(m, q), want);
        }
    }
}

/* IK never returns joints outside the limits as a success: random poses (many out
 * of reach, many past a limit) give 0 with joints inside, or an error. */
static void ik_respects_limits(void **st)
{
    int k, n;
    (void)st;
    for (k = 0; k < fbrl_sim_nmodels; k++) {
        const fbrl_sim_model *m = &fbrl_sim_models[k];
        int ok = 0, refused = 0;
        for (n = 0; n < 5000; n++) {
            double p[6], q[FBRL_SIM_ARM_MAX_AXES];
            int i, e;
            for (i = 0; i < 3; i++)
                p[i] = -40.0 + 80.0 * rnd01();
            for (i = 3; i < 6; i++)
                p[i] = -180.0 + 360.0 * rnd01();
            e = fbrl_sim_arm_ik(m, p, 0.0, m->ready, q);
            if (e == 0) {
                assert_int_equal(fbrl_sim_arm_check(m, q), 0);
                ok++;
            } else {
                assert_true(e == 29 || (e >= 42 && e <= 48 && e != 47));
                refused++;
            }
        }
        assert_true(ok > 0);
        assert_true(refused > 0);
    }
}

static void unreachable(void **st)
{
    int k;
    (void)st;
    for (k = 0; k < fbrl_sim_nmodels; k++) {
        const fbrl_sim_model *m = &fbrl_sim_models[k];
        double reach = m->upper + m->fore + m->flange, q[FBRL_SIM_ARM_MAX_AXES];
        double far[6] = {reach + 5.0, 0.0, m->base_h, 0.0, 0.0, 0.0};
        double nan_pose[6] = {NAN, 0, 0, 0, 0, 0};
        double stretched[6] = {reach, 0.0, m->base_h, 0.0, 0.0, 0.0};
        assert_int_equal(fbrl_sim_arm_ik(m, far, 0.0, m->ready, q), 29);
        assert_int_equal(fbrl_sim_arm_ik(m, nan_pose, 0.0, m->ready, q), 29);
        /* full stretch, horizontal at shoulder height, is still reachable for the A255;
         * the A465's shoulder stops at 90 degrees from vertical: just inside */
        if (m->kin == FBRL_SIM_KIN_5R) {
            assert_int_equal(fbrl_sim_arm_ik(m, stretched, 0.0, m->ready, q), 0);
            near(q[1], 0.0, 1e-6);
            near(q[2], 0.0, 1e-6);
        } else {
            assert_int_equal(fbrl_sim_arm_ik(m, stretched, 0.0, m->ready, q), 0);
            near(q[1], 90.0, 1e-6);
        }
    }
}

/* ---- the A255 ---------------------------------------------------------- */

static void a255_ready(void **st)
{
    const fbrl_sim_model *m = model("a255");
    double p[6];
    (void)st;
    assert_int_equal(m->naxes, 5);
    fbrl_sim_arm_fk(m, m->ready, 0.0, p);
    near(p[0], 12.0, 1e-12);
    near(p[1], 0.0, 1e-12);
    near(p[2], 20.0, 1e-12);
    near(p[3], 0.0, 1e-12);
    near(p[4], 0.0, 1e-12);
    near(p[5], 0.0, 1e-12);
    /* a tool adds its length along the tool axis */
    fbrl_sim_arm_fk(m, m->ready, 3.0, p);
    near(p[0], 15.0, 1e-12);
}

static void a255_pointing_down(void **st)
{
    const fbrl_sim_model *m = model("A255");
    double q[5] = {90.0, 45.0, -90.0, -45.0, 30.0}, p[6];
    (void)st;
    fbrl_sim_arm_fk(m, q, 0.0, p);
    /* pitch = 45 - 90 - 45 = -90: tool straight down, flange 2 in below the wrist */
    near(p[4], -90.0, 1e-12);
    near(p[0], 0.0, 1e-9);
    near(p[1], 10.0 * cos(M_PI / 4) + 10.0 * cos(-M_PI / 4), 1e-9);
    near(p[2], 10.0 + 10.0 * sin(M_PI / 4) - 10.0 * sin(M_PI / 4) - 2.0, 1e-9);
    near(p[3], 90.0, 1e-12);
    near(p[5], 30.0, 1e-12);
}

/* A second configuration reaching the same pose cannot start a straight line. */
static void a255_configurations(void **st)
{
    const fbrl_sim_model *m = model("a255");
    int n, other = 0;
    (void)st;
    for (n = 0; n < 20000 && other < 50; n++) {
        double q[5], p[6], back[5];
        random_joints(m, q);
        if (fabs(q[2]) < 1e-3)
            continue;
        fbrl_sim_arm_fk(m, q, 0.5, p);
        if (hypot(p[0], p[1]) < 1e-3)
            continue;
        assert_int_equal(fbrl_sim_arm_ik(m, p, 0.5, m->ready, back), 0);
        if (fabs(fbrl_sim_arm_wrap(back[0] - q[0])) > 1e-6) {
            other++;
            assert_int_equal(fbrl_sim_arm_check_line(m, p, p, 0.5, q), 68);
            assert_int_equal(fbrl_sim_arm_check_line(m, p, p, 0.5, back), 0);
        }
    }
    assert_true(other > 0);
}

static void a255_pulses(void **st)
{
    const fbrl_sim_model *m = model("a255");
    (void)st;
    assert_int_equal(fbrl_sim_arm_pulses(m, 1, 90.0), 18000);
    assert_int_equal(fbrl_sim_arm_pulses(m, 2, -90.0), -18000);
    assert_int_equal(fbrl_sim_arm_pulses(m, 3, 10.0), 444);
    assert_int_equal(fbrl_sim_arm_pulses(m, 4, -10.0), -222);
    near(fbrl_sim_arm_degrees(m, 3, 4444), 100.0, 1e-9);
    near(fbrl_sim_arm_wrap(190.0), -170.0, 1e-12);
    near(fbrl_sim_arm_wrap(-180.0), 180.0, 1e-12);
}

static void a255_straight_lines(void **st)
{
    const fbrl_sim_model *m = model("a255");
    double a[6] = {14.0, 0.0, 10.0, 0.0, -90.0, 0.0}, b[6] = {10.0, 8.0, 4.0, 0.0, -90.0, 0.0};
    double c[6] = {-14.0, 0.0, 10.0, 0.0, -90.0, 0.0}, far[6] = {14.0, 0.0, 30.0, 0.0, -90.0, 0.0};
    double mid[6], q[5];
    (void)st;
    assert_int_equal(fbrl_sim_arm_ik(m, a, 0.0, m->ready, q), 0);
    assert_int_equal(fbrl_sim_arm_check_line(m, a, b, 0.0, q), 0);
    /* through the base axis: the waist would have to whip round */
    assert_int_equal(fbrl_sim_arm_check_line(m, a, c, 0.0, q), 68);
    /* up out of reach */
    assert_int_equal(fbrl_sim_arm_check_line(m, a, far, 0.0, q), 68);
    fbrl_sim_arm_lerp(a, b, 0.5, mid);
    near(mid[0], 12.0, 1e-12);
    near(mid[1], 4.0, 1e-12);
    near(mid[2], 7.0, 1e-12);
}

/* ---- the A465 ---------------------------------------------------------- */

static void a465_ready(void **st)
{
    const fbrl_sim_model *m = model("a465");
    double p[6], q[6];
    (void)st;
    assert_int_equal(m->naxes, 6);
    assert_null(fbrl_sim_model_find("a999"));
    /* upper arm upright, forearm and tool horizontal: 330 + 76 mm out, 330 + 305 mm up */
    fbrl_sim_arm_fk(m, m->ready, 0.0, p);
    near(p[0], 406.0 / 25.4, 1e-9);
    near(p[1], 0.0, 1e-9);
    near(p[2], 635.0 / 25.4, 1e-9);
    near(p[4], 0.0, 1e-9);
    /* a 6-axis arm chooses its yaw: the tool turned 30 degrees off the waist's direction */
    p[3] = 30.0;
    p[0] -= 1.0;
    assert_int_equal(fbrl_sim_arm_ik(m, p, 0.0, m->ready, q), 0);
    {
        double r[6];
        fbrl_sim_arm_fk(m, q, 0.0, r);
        near(r[3], 30.0, 1e-9);
        near(r[0], p[0], 1e-9);
        near(r[1], p[1], 1e-9);
        near(r[2], p[2], 1e-9);
    }
    /* pulses: joint 6 counts too */
    assert_int_equal(fbrl_sim_arm_pulses(m, 5, 10.0), lround(10.0 * m->ppd[5]));
}

/* Straight lines keep the configuration; a line through the wrist's reach limit fails. */
static void a465_straight_lines(void **st)
{
    const fbrl_sim_model *m = model("a465");
    double a[6] = {16.0, 0.0, 10.0, 0.0, -90.0, 0.0}, b[6] = {15.0, 5.0, 9.0, 20.0, -80.0, 10.0};
    double far[6] = {16.0, 0.0, 60.0, 0.0, -90.0, 0.0}, q[6];
    (void)st;
    assert_int_equal(fbrl_sim_arm_ik(m, a, 0.0, m->ready, q), 0);
    assert_int_equal(fbrl_sim_arm_check_line(m, a, b, 0.0, q), 0);
    assert_int_equal(fbrl_sim_arm_check_line(m, a, far, 0.0, q), 68);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(fk_matches_chain),
        cmocka_unit_test(round_trip),
        cmocka_unit_test(limits),
        cmocka_unit_test(ik_respects_limits),
        cmocka_unit_test(unreachable),
        cmocka_unit_test(a255_ready),
        cmocka_unit_test(a255_pointing_down),
        cmocka_unit_test(a255_configurations),
        cmocka_unit_test(a255_pulses),
        cmocka_unit_test(a255_straight_lines),
        cmocka_unit_test(a465_ready),
        cmocka_unit_test(a465_straight_lines),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
