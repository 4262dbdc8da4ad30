/* sim_arm_test.c - the emulated arm's kinematics (sim/arm.c). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <math.h>
#include <stdlib.h>
#include <cmocka.h>

#include "arm.h"

static void near(double a, double b, double eps)
{
    if (fabs(a - b) > eps)
        fail_msg("%.9f != %.9f (eps %g)", a, b, eps);
}

static void ready_pose(void **st)
{
    double p[6];
    (void)st;
    fbrl_sim_arm_fk(fbrl_sim_arm_ready, 0.0, p);
    near(p[0], 12.0, 1e-12);
    near(p[1], 0.0, 1e-12);
    near(p[2], 20.0, 1e-12);
    near(p[3], 0.0, 1e-12);
    near(p[4], 0.0, 1e-12);
    near(p[5], 0.0, 1e-12);
    /* a tool adds its length along the tool axis */
    fbrl_sim_arm_fk(fbrl_sim_arm_ready, 3.0, p);
    near(p[0], 15.0, 1e-12);
}

static void pointing_down(void **st)
{
    double q[5] = { 90.0, 45.0, -90.0, -45.0, 30.0 }, p[6];
    (void)st;
    fbrl_sim_arm_fk(q, 0.0, p);
    /* pitch = 45 - 90 - 45 = -90: tool straight down, flange 2 in below the wrist */
    near(p[4], -90.0, 1e-12);
    near(p[0], 0.0, 1e-9);
    near(p[1], 10.0 * cos(M_PI / 4) + 10.0 * cos(-M_PI / 4), 1e-9);
    near(p[2], 10.0 + 10.0 * sin(M_PI / 4) - 10.0 * sin(M_PI / 4) - 2.0, 1e-9);
    near(p[3], 90.0, 1e-12);
    near(p[5], 30.0, 1e-12);
}

/* Every pose the arm can take is found again by IK: FK(IK(FK(q))) == FK(q),
 * and for a forward reach IK returns q itself. */
static void round_trip(void **st)
{
    unsigned long x = 12345;
    int n, same = 0, other = 0;
    (void)st;
    for (n = 0; n < 20000; n++) {
        double q[5], p[6], r[6], back[5];
        int i;
        for (i = 0; i < 5; i++) {
            x = x * 6364136223846793005UL + 1442695040888963407UL;
            q[i] = fbrl_sim_arm_min[i]
                 + (fbrl_sim_arm_max[i] - fbrl_sim_arm_min[i]) * ((x >> 11) / 9007199254740992.0);
        }
        if (fabs(q[2]) < 1e-3)
            continue; /* a straight elbow is singular */
        fbrl_sim_arm_fk(q, 0.5, p);
        if (hypot(p[0], p[1]) < 1e-3)
            continue; /* on the base axis the waist is free */
        assert_int_equal(fbrl_sim_arm_ik(p, 0.5, 0.0, back), 0);
        assert_int_equal(fbrl_sim_arm_check(back), 0);
        fbrl_sim_arm_fk(back, 0.5, r);
        for (i = 0; i < 3; i++)
            near(r[i], p[i], 1e-9);
        near(r[4], p[4], 1e-9);
        near(r[5], p[5], 1e-9);
        if (fabs(fbrl_sim_arm_wrap(back[0] - q[0])) < 1e-6) {
            same++;
            for (i = 0; i < 5; i++)
                near(back[i], q[i], 1e-6);
        } else {
            other++; /* a second configuration reaching the same pose */
            /* a straight line cannot start by switching from one configuration to the other */
            assert_int_equal(fbrl_sim_arm_check_line(p, p, 0.5, q[0]), 68);
            assert_int_equal(fbrl_sim_arm_check_line(p, p, 0.5, back[0]), 0);
        }
    }
    assert_true(same > 10000);
    assert_true(other > 0);
}

static void unreachable(void **st)
{
    double p[6] = { 30.0, 0.0, 10.0, 0.0, 0.0, 0.0 }, q[5];
    double nan_pose[6] = { NAN, 0, 0, 0, 0, 0 };
    (void)st;
    assert_int_equal(fbrl_sim_arm_ik(p, 0.0, 0.0, q), 29);
    assert_int_equal(fbrl_sim_arm_ik(nan_pose, 0.0, 0.0, q), 29);
    /* full stretch is still reachable: 22 in out at shoulder height */
    p[0] = 22.0;
    assert_int_equal(fbrl_sim_arm_ik(p, 0.0, 0.0, q), 0);
    near(q[1], 0.0, 1e-6);
    near(q[2], 0.0, 1e-6);
}

static void limits(void **st)
{
    int i;
    (void)st;
    for (i = 0; i < 5; i++) {
        double q[5];
        int k;
        for (k = 0; k < 5; k++)
            q[k] = fbrl_sim_arm_ready[k];
        q[i] = fbrl_sim_arm_max[i];
        assert_int_equal(fbrl_sim_arm_check(q), 0);
        q[i] = fbrl_sim_arm_max[i] + 0.01;
        assert_int_equal(fbrl_sim_arm_check(q), 42 + i);
        q[i] = fbrl_sim_arm_min[i] - 0.01;
        assert_int_equal(fbrl_sim_arm_check(q), 42 + i);
    }
}

static void pulses(void **st)
{
    (void)st;
    assert_int_equal(fbrl_sim_arm_pulses(1, 90.0), 18000);
    assert_int_equal(fbrl_sim_arm_pulses(2, -90.0), -18000);
    assert_int_equal(fbrl_sim_arm_pulses(3, 10.0), 444);
    assert_int_equal(fbrl_sim_arm_pulses(4, -10.0), -222);
    near(fbrl_sim_arm_degrees(3, 4444), 100.0, 1e-9);
    near(fbrl_sim_arm_wrap(190.0), -170.0, 1e-12);
    near(fbrl_sim_arm_wrap(-180.0), 180.0, 1e-12);
}

static void straight_lines(void **st)
{
    double a[6] = { 14.0, 0.0, 10.0, 0.0, -90.0, 0.0 }, b[6] = { 10.0, 8.0, 4.0, 0.0, -90.0, 0.0 };
    double c[6] = { -14.0, 0.0, 10.0, 0.0, -90.0, 0.0 }, far[6] = { 14.0, 0.0, 30.0, 0.0, -90.0, 0.0 };
    double m[6];
    (void)st;
    assert_int_equal(fbrl_sim_arm_check_line(a, b, 0.0, 0.0), 0);
    /* through the base axis: the waist would have to whip round */
    assert_int_equal(fbrl_sim_arm_check_line(a, c, 0.0, 0.0), 68);
    /* up out of reach */
    assert_int_equal(fbrl_sim_arm_check_line(a, far, 0.0, 0.0), 68);
    fbrl_sim_arm_lerp(a, b, 0.5, m);
    near(m[0], 12.0, 1e-12);
    near(m[1], 4.0, 1e-12);
    near(m[2], 7.0, 1e-12);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(ready_pose),  cmocka_unit_test(pointing_down), cmocka_unit_test(round_trip),
        cmocka_unit_test(unreachable), cmocka_unit_test(limits),        cmocka_unit_test(pulses),
        cmocka_unit_test(straight_lines),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
