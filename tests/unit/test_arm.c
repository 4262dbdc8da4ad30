/* SPDX-License-Identifier: MIT */
/* test_arm.c - the arm models and their kinematics (fbrl/arm.h), for every row of the table.
 *
 * The truth for forward kinematics is computed here independently: each arm as the physical
 * chain of rotations and links its published geometry describes (A255: DESIGN 6; A465: the
 * DH lengths d1 330, a2 305, d4 330, d6 76 mm), and the pose compared as three points of
 * the tool frame, so yaw, pitch and roll are checked too; the chain's joints (shoulder,
 * elbow, wrist centre) come from the same frames. Inverse kinematics is checked by round
 * trips, the levers by moving the arm and measuring how far its points went. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/arm.h"
#include "support/arm_chain.h"

#define ROUND_TRIPS 10000
#define TOL_IN      1e-6 /* in: the round trip's bound */

static void near(double a, double b, double eps)
{
    if (!(fabs(a - b) <= eps))
        fail_msg("%.9f != %.9f (eps %g)", a, b, eps);
}

static const fbrl_arm *model(const char *name)
{
    const fbrl_arm *m = fbrl_arm_find(name);
    assert_non_null(m);
    return m;
}

/* ---- the independent chain (tests/support/arm_chain.h) ------------------- */

/* Three points of the tool frame: the tool point, 1 in along the tool axis and 1 in along
 * the tool's y axis. */
typedef struct pts {
    double v[3][3];
} pts;

static void frame_pts(const ac_frame *f, int tool_axis, int y_axis, pts *out)
{
    for (int i = 0; i < 3; i++) {
        out->v[0][i] = f->p[i];
        out->v[1][i] = f->p[i] + f->r[i][tool_axis];
        out->v[2][i] = f->p[i] + f->r[i][y_axis];
    }
}

/* The same three points from a pose X Y Z yaw pitch roll: Rz(yaw) Ry(-pitch) Rx(roll). */
static void pose_pts(const double pose[6], pts *out)
{
    ac_frame f;
    ac_ident(&f);
    f.p[0] = pose[0], f.p[1] = pose[1], f.p[2] = pose[2];
    ac_rot(&f, 2, pose[3]);
    ac_rot(&f, 1, -pose[4]);
    ac_rot(&f, 0, pose[5]);
    frame_pts(&f, 0, 1, out);
}

/* The arm as its physical chain: the tool frame's points, and the joints' places (the
 * shoulder, the elbow, the wrist centre, the tool point) in joint[]. */
static void chain(const fbrl_arm *m, const double *q, double tool, pts *out, double joint[4][3])
{
    ac_frame f;
    int axis;
    ac_chain(m, q, tool, joint, &f, &axis);
    frame_pts(&f, axis, 1, out);
}

static double pts_dist(const pts *a, const pts *b)
{
    double worst = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            worst = fmax(worst, fabs(a->v[i][j] - b->v[i][j]));
    return worst;
}

static double dist3(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

static unsigned long g_x = 12345;

static double rnd01(void)
{
    g_x = g_x * 6364136223846793005UL + 1442695040888963407UL;
    return (double)(g_x >> 11) / 9007199254740992.0;
}

static void random_joints(const fbrl_arm *m, double *q)
{
    for (unsigned i = 0; i < m->naxes; i++)
        q[i] = m->min[i] + (m->max[i] - m->min[i]) * rnd01();
}

/* ---- the table ----------------------------------------------------------- */

static void table(void **st)
{
    size_t k;
    const fbrl_arm *m;
    (void)st;
    assert_string_equal(fbrl_arm_model(0)->name, "A255"); /* the default */
    for (k = 0; (m = fbrl_arm_model(k)) != NULL; k++) {
        char lower[16];
        size_t n = strlen(m->name);
        assert_true(n < sizeof lower);
        for (size_t i = 0; i <= n; i++)
            lower[i] = (char)(m->name[i] >= 'A' && m->name[i] <= 'Z' ? m->name[i] - 'A' + 'a' : m->name[i]);
        assert_ptr_equal(fbrl_arm_find(m->name), m);
        assert_ptr_equal(fbrl_arm_find(lower), m);
        assert_true(m->naxes >= 5 && m->naxes <= FBRL_ARM_AXES_MAX);
        assert_true(m->form == FBRL_ARM_5R || m->form == FBRL_ARM_6R);
        assert_true(m->upper > 0 && m->fore > 0 && m->flange > 0 && m->base_h > 0);
        assert_true(m->r_upper > 0 && m->r_fore > 0 && m->linear > 0);
        for (unsigned i = 0; i < m->naxes; i++) {
            assert_true(m->min[i] < m->max[i] && m->ppd[i] > 0 && m->speed[i] > 0);
            assert_true(m->ready[i] >= m->min[i] && m->ready[i] <= m->max[i]);
        }
    }
    assert_int_equal(k, 2);
    assert_null(fbrl_arm_find("a999"));
    assert_null(fbrl_arm_find("a25"));
    assert_null(fbrl_arm_find("a2555"));
    assert_null(fbrl_arm_find(NULL));
}

/* ---- every model ------------------------------------------------------- */

/* fbrl_arm_fk and fbrl_arm_chain agree with the physical chain everywhere in the joint
 * space. */
static void fk_matches_chain(void **st)
{
    const fbrl_arm *m;
    (void)st;
    for (size_t k = 0; (m = fbrl_arm_model(k)) != NULL; k++) {
        for (int n = 0; n < 2000; n++) {
            double q[FBRL_ARM_AXES_MAX], p[6], tool = n % 2 ? 0.0 : 1.25, truth[4][3], got[FBRL_ARM_CHAIN][3];
            pts a, b;
            random_joints(m, q);
            assert_int_equal(fbrl_arm_fk(m, q, tool, p), FBRL_OK);
            pose_pts(p, &a);
            chain(m, q, tool, &b, truth);
            if (pts_dist(&a, &b) > 1e-9)
                fail_msg("%s: FK differs from the chain by %g in", m->name, pts_dist(&a, &b));
            assert_int_equal(fbrl_arm_chain(m, q, tool, got), FBRL_OK);
            for (int i = 0; i < FBRL_ARM_CHAIN; i++)
                if (dist3(got[i], truth[i]) > 1e-9)
                    fail_msg("%s: chain point %d off by %g in", m->name, i, dist3(got[i], truth[i]));
        }
    }
}

/* 10,000 random reachable poses of each arm: IK finds joints inside the limits whose pose is
 * the same within 1e-6 in (three points of the tool frame), and IK of that answer's own pose,
 * with the answer as the arm's joints, gives the answer again (one configuration, no
 * drift). */
static void round_trip(void **st)
{
    const fbrl_arm *m;
    (void)st;
    for (size_t k = 0; (m = fbrl_arm_model(k)) != NULL; k++) {
        int done = 0, same = 0, tries = 0;
        double worst = 0;
        while (done < ROUND_TRIPS) {
            double q[FBRL_ARM_AXES_MAX], back[FBRL_ARM_AXES_MAX], again[FBRL_ARM_AXES_MAX],
                hint[FBRL_ARM_AXES_MAX];
            double p[6], r[6], tool = 0.5;
            pts a, b;
            unsigned i;
            int axis = 99;
            fbrl_status e;
            assert_true(++tries < 3 * ROUND_TRIPS);
            random_joints(m, q);
            if (fabs(q[2]) < 1e-3)
                continue; /* a straight elbow is singular */
            fbrl_arm_fk(m, q, tool, p);
            if (hypot(p[0], p[1]) < 1e-3)
                continue; /* on the base axis the waist is free */
            /* half the time the arm starts elsewhere (READY), half where the pose is */
            memcpy(hint, done % 2 ? m->ready : q, sizeof hint);
            e = fbrl_arm_ik(m, p, tool, hint, back, &axis);
            if (e != FBRL_OK)
                fail_msg("%s: IK of a reachable pose gave %d, axis %d (q %g %g %g %g %g %g)", m->name, e,
                         axis, q[0], q[1], q[2], q[3], q[4], q[5]);
            assert_int_equal(axis, -1);
            assert_int_equal(fbrl_arm_check(m, back, NULL), FBRL_OK);
            fbrl_arm_fk(m, back, tool, r);
            if (m->form == FBRL_ARM_5R) {
                /* a 5-axis arm cannot choose its yaw (reaching backward turns it round): the
                 * tool point, the tool axis's elevation and the roll are the pose */
                double d = 0;
                for (i = 0; i < 3; i++)
                    d = fmax(d, fabs(r[i] - p[i]));
                d = fmax(d, fabs(fbrl_arm_wrap(r[4] - p[4])) * M_PI / 180.0);
                d = fmax(d, fabs(fbrl_arm_wrap(r[5] - p[5])) * M_PI / 180.0);
                worst = fmax(worst, d);
                if (d > TOL_IN)
                    fail_msg("%s: round trip off by %g in", m->name, d);
            } else {
                pose_pts(p, &a);
                pose_pts(r, &b);
                worst = fmax(worst, pts_dist(&a, &b));
                if (pts_dist(&a, &b) > TOL_IN)
                    fail_msg("%s: round trip off by %g in", m->name, pts_dist(&a, &b));
            }
            assert_int_equal(fbrl_arm_ik(m, r, tool, back, again, NULL), FBRL_OK);
            for (i = 0; i < m->naxes; i++)
                if (fabs(fbrl_arm_wrap(again[i] - back[i])) > 1e-6)
                    fail_msg("%s: IK(FK(q)) moved joint %u from %.9f to %.9f", m->name, i + 1, back[i],
                             again[i]);
            for (i = 0; i < m->naxes && fabs(fbrl_arm_wrap(back[i] - q[i])) < 1e-6; i++)
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
    const fbrl_arm *m;
    (void)st;
    for (size_t k = 0; (m = fbrl_arm_model(k)) != NULL; k++) {
        for (unsigned i = 0; i < m->naxes; i++) {
            double q[FBRL_ARM_AXES_MAX], bad[] = {m->max[i] + 0.01, m->min[i] - 0.01, NAN, INFINITY};
            int axis = 99;
            memcpy(q, m->ready, sizeof q);
            assert_int_equal(fbrl_arm_check(m, q, &axis), FBRL_OK);
            assert_int_equal(axis, -1);
            q[i] = m->max[i];
            assert_int_equal(fbrl_arm_check(m, q, NULL), FBRL_OK);
            q[i] = m->min[i] - 1e-10; /* a rounding hair past it */
            assert_int_equal(fbrl_arm_check(m, q, NULL), FBRL_OK);
            for (size_t b = 0; b < sizeof bad / sizeof bad[0]; b++) {
                q[i] = bad[b];
                assert_int_equal(fbrl_arm_check(m, q, &axis), FBRL_ERANGE);
                assert_int_equal(axis, (int)i);
            }
        }
    }
    assert_int_equal(fbrl_arm_check(NULL, model("a255")->ready, NULL), FBRL_EINVAL);
}

/* IK never returns joints outside the limits as a success: random poses (many out of reach,
 * many past a limit) give FBRL_OK with joints inside, or FBRL_ERANGE naming the joint past
 * its limit in the configuration it would have taken (or none: out of reach). */
static void ik_respects_limits(void **st)
{
    const fbrl_arm *m;
    (void)st;
    for (size_t k = 0; (m = fbrl_arm_model(k)) != NULL; k++) {
        int ok = 0, reach = 0, limit = 0;
        for (int n = 0; n < 5000; n++) {
            double p[6], q[FBRL_ARM_AXES_MAX];
            int i, axis;
            for (i = 0; i < 3; i++)
                p[i] = -40.0 + 80.0 * rnd01();
            for (i = 3; i < 6; i++)
                p[i] = -180.0 + 360.0 * rnd01();
            fbrl_status e = fbrl_arm_ik(m, p, 0.0, m->ready, q, &axis);
            if (e == FBRL_OK) {
                assert_int_equal(fbrl_arm_check(m, q, NULL), FBRL_OK);
                ok++;
            } else {
                int again;
                assert_int_equal(e, FBRL_ERANGE);
                assert_true(axis >= -1 && axis < (int)m->naxes);
                if (axis < 0) {
                    reach++;
                    continue;
                }
                limit++;
                assert_int_equal(fbrl_arm_check(m, q, &again), FBRL_ERANGE);
                assert_int_equal(again, axis);
            }
        }
        print_message("%s: %d in reach, %d out of reach, %d past a limit\n", m->name, ok, reach, limit);
        assert_true(ok > 0 && reach > 0 && limit > 0);
    }
}

static void unreachable(void **st)
{
    const fbrl_arm *m;
    (void)st;
    for (size_t k = 0; (m = fbrl_arm_model(k)) != NULL; k++) {
        double reach = m->upper + m->fore + m->flange, q[FBRL_ARM_AXES_MAX];
        double far[6] = {reach + 5.0, 0.0, m->base_h, 0.0, 0.0, 0.0};
        double nan_pose[6] = {NAN, 0, 0, 0, 0, 0};
        double stretched[6] = {reach, 0.0, m->base_h, 0.0, 0.0, 0.0};
        int axis = 99;
        assert_int_equal(fbrl_arm_ik(m, far, 0.0, m->ready, q, &axis), FBRL_ERANGE);
        assert_int_equal(axis, -1);
        assert_int_equal(fbrl_arm_ik(m, nan_pose, 0.0, m->ready, q, &axis), FBRL_ENONFINITE);
        assert_int_equal(fbrl_arm_ik(m, stretched, NAN, m->ready, q, &axis), FBRL_ENONFINITE);
        /* full stretch, horizontal at shoulder height, is still reachable for the A255; the
         * A465's shoulder stops at 90 degrees from vertical: just inside */
        assert_int_equal(fbrl_arm_ik(m, stretched, 0.0, m->ready, q, NULL), FBRL_OK);
        if (m->form == FBRL_ARM_5R) {
            near(q[1], 0.0, 1e-6);
            near(q[2], 0.0, 1e-6);
        } else {
            near(q[1], 90.0, 1e-6);
        }
    }
}

/* Each chain point moves no further than its levers say, and no point before it further, over
 * random joint moves (the points measured at 200 steps along the move: the bound holds for
 * every part of it). */
static void levers_bound_the_motion(void **state)
{
    const fbrl_arm *m;
    (void)state;
    for (size_t k = 0; (m = fbrl_arm_model(k)) != NULL; k++) {
        double worst[FBRL_ARM_CHAIN] = {0};
        for (int n = 0; n < 500; n++) {
            double q0[FBRL_ARM_AXES_MAX], q1[FBRL_ARM_AXES_MAX], lk[FBRL_ARM_AXES_MAX], p0[FBRL_ARM_CHAIN][3];
            double tool = n % 3 ? 1.5 : 0.0, bound[FBRL_ARM_CHAIN] = {0};
            random_joints(m, q0);
            random_joints(m, q1);
            for (int pt = 1; pt < FBRL_ARM_CHAIN; pt++) {
                assert_int_equal(fbrl_arm_levers(m, pt, tool, lk), FBRL_OK);
                for (unsigned i = 0; i < m->naxes; i++)
                    bound[pt] += lk[i] * fabs(q1[i] - q0[i]) * M_PI / 180.0;
            }
            fbrl_arm_chain(m, q0, tool, p0);
            for (int s = 1; s <= 200; s++) {
                double q[FBRL_ARM_AXES_MAX], p[FBRL_ARM_CHAIN][3];
                for (unsigned i = 0; i < m->naxes; i++)
                    q[i] = q0[i] + (q1[i] - q0[i]) * s / 200.0;
                fbrl_arm_chain(m, q, tool, p);
                for (int pt = 1; pt < FBRL_ARM_CHAIN; pt++)
                    for (int j = 0; j <= pt; j++) {
                        double d = dist3(p[j], p0[j]), b = bound[pt] * s / 200.0;
                        if (j == pt)
                            worst[pt] = fmax(worst[pt], d / bound[pt]);
                        if (d > b + 1e-9)
                            fail_msg("%s: point %d moved %g in, more than point %d's levers allow (%g)",
                                     m->name, j, d, pt, b);
                    }
            }
        }
        print_message("%s: the elbow, wrist and tool point moved at most %.2f, %.2f, %.2f of their bounds\n",
                      m->name, worst[1], worst[2], worst[3]);
        /* bounds, and not loose ones: some move comes close to each */
        assert_true(worst[1] > 0.5 && worst[2] > 0.5 && worst[3] > 0.5);
    }
    double lk[FBRL_ARM_AXES_MAX];
    assert_int_equal(fbrl_arm_levers(model("a255"), 3, 0.0, lk), FBRL_OK);
    near(lk[4], 0.0, 0.0); /* the tool roll turns the tool about its own axis */
    near(lk[0], 22.0, 1e-12);
    assert_int_equal(fbrl_arm_levers(model("a255"), 1, 0.0, lk), FBRL_OK);
    near(lk[2], 0.0, 0.0); /* the elbow does not turn itself */
    assert_int_equal(fbrl_arm_levers(model("a255"), 0, 0.0, lk), FBRL_ERANGE);
    assert_int_equal(fbrl_arm_levers(model("a255"), 4, 0.0, lk), FBRL_ERANGE);
}

/* APPRO and DEPART: dist back along the tool axis of the pose (the tool frame's x axis of an
 * A465 pose; the waist's direction on the A255, whose yaw is not its own). */
static void back_off(void **st)
{
    const fbrl_arm *a255 = model("a255"), *a465 = model("a465");
    double down[6] = {12.0, 5.0, 3.0, 77.0, -90.0, 10.0}, level[6] = {6.0, 8.0, 10.0, 0.0, 0.0, 0.0}, out[6];
    double axis_pose[6] = {0.0, 0.0, 12.0, 0.0, 0.0, 0.0};
    (void)st;
    /* pointing down: 2 in back is 2 in up, whatever the yaw says */
    assert_int_equal(fbrl_arm_back_off(a255, down, 0.0, 2.0, out), FBRL_OK);
    near(out[0], 12.0, 1e-12);
    near(out[1], 5.0, 1e-12);
    near(out[2], 5.0, 1e-12);
    near(out[3], 77.0, 0.0);
    near(out[5], 10.0, 0.0);
    /* level on the A255: back toward the base along the waist's direction (6, 8 is 10 out) */
    assert_int_equal(fbrl_arm_back_off(a255, level, 0.0, 5.0, out), FBRL_OK);
    near(out[0], 3.0, 1e-12);
    near(out[1], 4.0, 1e-12);
    near(out[2], 10.0, 1e-12);
    /* on the base axis the waist given is the direction */
    assert_int_equal(fbrl_arm_back_off(a255, axis_pose, 90.0, 1.0, out), FBRL_OK);
    near(out[0], 0.0, 1e-12);
    near(out[1], -1.0, 1e-12);
    /* the A465's tool axis is its own: random poses, against the tool frame's x axis */
    for (int n = 0; n < 1000; n++) {
        double p[6], d = 5.0 * rnd01();
        pts f;
        for (int i = 0; i < 3; i++)
            p[i] = -20.0 + 40.0 * rnd01();
        for (int i = 3; i < 6; i++)
            p[i] = -180.0 + 360.0 * rnd01();
        pose_pts(p, &f);
        assert_int_equal(fbrl_arm_back_off(a465, p, 0.0, d, out), FBRL_OK);
        for (int i = 0; i < 3; i++)
            near(out[i], p[i] - d * (f.v[1][i] - f.v[0][i]), 1e-9);
        for (int i = 3; i < 6; i++)
            near(out[i], p[i], 0.0);
    }
    /* in place */
    memcpy(out, down, sizeof out);
    assert_int_equal(fbrl_arm_back_off(a465, out, 0.0, 1.0, out), FBRL_OK);
    near(out[2], 4.0, 1e-12);
    assert_int_equal(fbrl_arm_back_off(NULL, down, 0.0, 1.0, out), FBRL_EINVAL);
}

static void wrap(void **st)
{
    static const double in[][2] = {{190.0, -170.0}, {-180.0, 180.0}, {180.0, 180.0},    {540.0, 180.0},
                                   {-540.0, 180.0}, {-190.0, 170.0}, {359.5, -0.5},     {0.0, 0.0},
                                   {-0.0, 0.0},     {720.25, 0.25},  {-179.75, -179.75}};
    (void)st;
    for (size_t k = 0; k < sizeof in / sizeof in[0]; k++)
        near(fbrl_arm_wrap(in[k][0]), in[k][1], 1e-12);
    for (int n = 0; n < 10000; n++) {
        double a = -3600.0 + 7200.0 * rnd01(), w = fbrl_arm_wrap(a);
        assert_true(w > -180.0 && w <= 180.0);
        near(fmod(fabs(w - a), 360.0) < 180.0 ? fmod(fabs(w - a), 360.0) : 360.0 - fmod(fabs(w - a), 360.0),
             0.0, 1e-9);
    }
}

/* ---- the A255 ---------------------------------------------------------- */

static void a255_ready(void **st)
{
    const fbrl_arm *m = model("a255");
    double p[6];
    (void)st;
    assert_int_equal(m->naxes, 5);
    fbrl_arm_fk(m, m->ready, 0.0, p);
    near(p[0], 12.0, 1e-12);
    near(p[1], 0.0, 1e-12);
    near(p[2], 20.0, 1e-12);
    near(p[3], 0.0, 1e-12);
    near(p[4], 0.0, 1e-12);
    near(p[5], 0.0, 1e-12);
    /* a tool adds its length along the tool axis */
    fbrl_arm_fk(m, m->ready, 3.0, p);
    near(p[0], 15.0, 1e-12);
}

static void a255_pointing_down(void **st)
{
    const fbrl_arm *m = model("A255");
    double q[5] = {90.0, 45.0, -90.0, -45.0, 30.0}, p[6];
    (void)st;
    fbrl_arm_fk(m, q, 0.0, p);
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
    const fbrl_arm *m = model("a255");
    int other = 0;
    (void)st;
    for (int n = 0; n < 20000 && other < 50; n++) {
        double q[5], p[6], back[5];
        random_joints(m, q);
        if (fabs(q[2]) < 1e-3)
            continue;
        fbrl_arm_fk(m, q, 0.5, p);
        if (hypot(p[0], p[1]) < 1e-3)
            continue;
        assert_int_equal(fbrl_arm_ik(m, p, 0.5, m->ready, back, NULL), FBRL_OK);
        if (fabs(fbrl_arm_wrap(back[0] - q[0])) > 1e-6) {
            other++;
            assert_int_equal(fbrl_arm_check_line(m, p, p, 0.5, q), FBRL_ERANGE);
            assert_int_equal(fbrl_arm_check_line(m, p, p, 0.5, back), FBRL_OK);
        }
    }
    assert_true(other > 0);
}

static void a255_pulses(void **st)
{
    const fbrl_arm *m = model("a255");
    (void)st;
    assert_int_equal(fbrl_arm_pulses(m, 1, 90.0), 18000);
    assert_int_equal(fbrl_arm_pulses(m, 2, -90.0), -18000);
    assert_int_equal(fbrl_arm_pulses(m, 3, 10.0), 444);
    assert_int_equal(fbrl_arm_pulses(m, 4, -10.0), -222);
    near(fbrl_arm_degrees(m, 3, 4444), 100.0, 1e-9);
    assert_int_equal(fbrl_arm_pulses(m, 5, 10.0), 0); /* no sixth joint */
}

static void a255_straight_lines(void **st)
{
    const fbrl_arm *m = model("a255");
    double a[6] = {14.0, 0.0, 10.0, 0.0, -90.0, 0.0}, b[6] = {10.0, 8.0, 4.0, 0.0, -90.0, 0.0};
    double c[6] = {-14.0, 0.0, 10.0, 0.0, -90.0, 0.0}, far[6] = {14.0, 0.0, 30.0, 0.0, -90.0, 0.0};
    double mid[6], q[5];
    (void)st;
    assert_int_equal(fbrl_arm_ik(m, a, 0.0, m->ready, q, NULL), FBRL_OK);
    assert_int_equal(fbrl_arm_check_line(m, a, b, 0.0, q), FBRL_OK);
    /* through the base axis: the waist would have to whip round */
    assert_int_equal(fbrl_arm_check_line(m, a, c, 0.0, q), FBRL_ERANGE);
    /* up out of reach */
    assert_int_equal(fbrl_arm_check_line(m, a, far, 0.0, q), FBRL_ERANGE);
    fbrl_arm_lerp(a, b, 0.5, mid);
    near(mid[0], 12.0, 1e-12);
    near(mid[1], 4.0, 1e-12);
    near(mid[2], 7.0, 1e-12);
}

/* ---- the A465 ---------------------------------------------------------- */

static void a465_ready(void **st)
{
    const fbrl_arm *m = model("a465");
    double p[6], q[6];
    (void)st;
    assert_int_equal(m->naxes, 6);
    /* upper arm upright, forearm and tool horizontal: 330 + 76 mm out, 330 + 305 mm up */
    fbrl_arm_fk(m, m->ready, 0.0, p);
    near(p[0], 406.0 / 25.4, 1e-9);
    near(p[1], 0.0, 1e-9);
    near(p[2], 635.0 / 25.4, 1e-9);
    near(p[4], 0.0, 1e-9);
    /* a 6-axis arm chooses its yaw: the tool turned 30 degrees off the waist's direction */
    p[3] = 30.0;
    p[0] -= 1.0;
    assert_int_equal(fbrl_arm_ik(m, p, 0.0, m->ready, q, NULL), FBRL_OK);
    {
        double r[6];
        fbrl_arm_fk(m, q, 0.0, r);
        near(r[3], 30.0, 1e-9);
        near(r[0], p[0], 1e-9);
        near(r[1], p[1], 1e-9);
        near(r[2], p[2], 1e-9);
    }
    /* pulses: joint 6 counts too */
    assert_int_equal(fbrl_arm_pulses(m, 5, 10.0), lround(10.0 * m->ppd[5]));
}

/* Straight lines keep the configuration; a line through the wrist's reach limit fails. */
static void a465_straight_lines(void **st)
{
    const fbrl_arm *m = model("a465");
    double a[6] = {16.0, 0.0, 10.0, 0.0, -90.0, 0.0}, b[6] = {15.0, 5.0, 9.0, 20.0, -80.0, 10.0};
    double far[6] = {16.0, 0.0, 60.0, 0.0, -90.0, 0.0}, q[6];
    (void)st;
    assert_int_equal(fbrl_arm_ik(m, a, 0.0, m->ready, q, NULL), FBRL_OK);
    assert_int_equal(fbrl_arm_check_line(m, a, b, 0.0, q), FBRL_OK);
    assert_int_equal(fbrl_arm_check_line(m, a, far, 0.0, q), FBRL_ERANGE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(table),
        cmocka_unit_test(fk_matches_chain),
        cmocka_unit_test(round_trip),
        cmocka_unit_test(limits),
        cmocka_unit_test(ik_respects_limits),
        cmocka_unit_test(unreachable),
        cmocka_unit_test(levers_bound_the_motion),
        cmocka_unit_test(back_off),
        cmocka_unit_test(wrap),
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
