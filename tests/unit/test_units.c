/* SPDX-License-Identifier: MIT */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <math.h>
#include <cmocka.h>

#include "fbrl/units.h"

/* Doubles within an absolute tolerance (cmocka's float assertion is single precision). */
#define assert_near(a, b, tol) assert_near_((a), (b), (tol), __FILE__, __LINE__)
static void assert_near_(double a, double b, double tol, const char *file, int line)
{
    if (!(fabs(a - b) <= tol)) {
        print_error("%.17g != %.17g (tolerance %g)\n", a, b, tol);
        _fail(file, line);
    }
}

static void switch_is_per_owner(void **state)
{
    fbrl_units a, b = FBRL_UNITS_INIT;
    int on = 7;
    (void)state;
    assert_int_equal(fbrl_units_init(&a), FBRL_OK);
    assert_int_equal(fbrl_units_is_metric(&a, &on), FBRL_OK);
    assert_int_equal(on, 0);
    assert_int_equal(fbrl_units_metric_on(&a), FBRL_OK);
    assert_int_equal(fbrl_units_is_metric(&a, &on), FBRL_OK);
    assert_int_equal(on, 1);
    /* Two VMs: switching one leaves the other alone. */
    assert_int_equal(fbrl_units_is_metric(&b, &on), FBRL_OK);
    assert_int_equal(on, 0);
    assert_int_equal(fbrl_units_metric_off(&a), FBRL_OK);
    assert_int_equal(fbrl_units_is_metric(&a, &on), FBRL_OK);
    assert_int_equal(on, 0);
}

static void conversions_use_2_54_exactly(void **state)
{
    double v;
    (void)state;
    assert_int_equal(fbrl_units_in_to_cm(1.0, &v), FBRL_OK);
    assert_true(v == 2.54);
    assert_int_equal(fbrl_units_in_to_cm(10.0, &v), FBRL_OK);
    assert_true(v == 25.4);
    assert_int_equal(fbrl_units_in_to_cm(-4.0, &v), FBRL_OK);
    assert_true(v == -10.16);
    assert_int_equal(fbrl_units_cm_to_in(2.54, &v), FBRL_OK);
    assert_true(v == 1.0);
    assert_int_equal(fbrl_units_cm_to_in(25.4, &v), FBRL_OK);
    assert_true(v == 10.0);
    assert_int_equal(fbrl_units_cm_to_in(100.0, &v), FBRL_OK);
    assert_near(v, 39.37007874015748, 1e-13);
    assert_int_equal(fbrl_units_cm_to_in(0.0, &v), FBRL_OK);
    assert_true(v == 0.0);
}

static void metric_in_and_out(void **state)
{
    fbrl_units u = FBRL_UNITS_INIT;
    double v;
    (void)state;
    /* Metric off: identity both ways. */
    assert_int_equal(fbrl_units_in(&u, 3.5, &v), FBRL_OK);
    assert_true(v == 3.5);
    assert_int_equal(fbrl_units_out(&u, 3.5, &v), FBRL_OK);
    assert_true(v == 3.5);
    fbrl_units_metric_on(&u);
    assert_int_equal(fbrl_units_in(&u, 25.4, &v), FBRL_OK);
    assert_true(v == 10.0);
    assert_int_equal(fbrl_units_out(&u, 10.0, &v), FBRL_OK);
    assert_true(v == 25.4);

    /* Locations: lengths convert, angles never. */
    fbrl_loc in = {10.0, -2.0, 0.5, 45.0, -90.0, 30.0}, out, back;
    assert_int_equal(fbrl_units_loc_out(&u, &in, &out), FBRL_OK);
    assert_true(out.x == 25.4 && out.y == -5.08 && out.z == 1.27);
    assert_true(out.o == 45.0 && out.a == -90.0 && out.t == 30.0);
    assert_int_equal(fbrl_units_loc_in(&u, &out, &back), FBRL_OK);
    assert_near(back.x, 10.0, 1e-15);
    assert_near(back.y, -2.0, 1e-15);
    assert_near(back.z, 0.5, 1e-15);
    assert_true(back.o == 45.0 && back.a == -90.0 && back.t == 30.0);
    /* In place. */
    assert_int_equal(fbrl_units_loc_in(&u, &out, &out), FBRL_OK);
    assert_near(out.x, 10.0, 1e-15);
    fbrl_units_metric_off(&u);
    assert_int_equal(fbrl_units_loc_in(&u, &in, &out), FBRL_OK);
    assert_memory_equal(&in, &out, sizeof in);
}

static void bad_input(void **state)
{
    fbrl_units u = FBRL_UNITS_INIT;
    double v = 9.0;
    int on = 9;
    fbrl_loc l = {1, 2, 3, 4, 5, 6}, o = l, bad = l;
    (void)state;
    assert_int_equal(fbrl_units_init(NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_units_metric_on(NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_units_metric_off(NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_units_is_metric(NULL, &on), FBRL_EINVAL);
    assert_int_equal(fbrl_units_is_metric(&u, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_units_in_to_cm(1.0, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_units_cm_to_in(1.0, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_units_in_to_cm(NAN, &v), FBRL_ENONFINITE);
    assert_int_equal(fbrl_units_cm_to_in(INFINITY, &v), FBRL_ENONFINITE);
    assert_int_equal(fbrl_units_in_to_cm(1.5e308, &v), FBRL_EOVERFLOW);
    assert_true(v == 9.0);
    assert_int_equal(fbrl_units_in(NULL, 1.0, &v), FBRL_EINVAL);
    assert_int_equal(fbrl_units_out(NULL, 1.0, &v), FBRL_EINVAL);
    assert_int_equal(fbrl_units_in(&u, 1.0, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_units_in(&u, NAN, &v), FBRL_ENONFINITE);
    fbrl_units_metric_on(&u);
    assert_int_equal(fbrl_units_out(&u, -INFINITY, &v), FBRL_ENONFINITE);
    assert_int_equal(fbrl_units_out(&u, -1e308, &v), FBRL_EOVERFLOW);
    assert_true(v == 9.0);
    assert_int_equal(fbrl_units_loc_in(NULL, &l, &o), FBRL_EINVAL);
    assert_int_equal(fbrl_units_loc_in(&u, NULL, &o), FBRL_EINVAL);
    assert_int_equal(fbrl_units_loc_out(&u, &l, NULL), FBRL_EINVAL);
    bad.t = NAN;
    assert_int_equal(fbrl_units_loc_out(&u, &bad, &o), FBRL_ENONFINITE);
    bad.t = 0;
    bad.z = 1e308;
    assert_int_equal(fbrl_units_loc_out(&u, &bad, &o), FBRL_EOVERFLOW);
    assert_memory_equal(&o, &l, sizeof o);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(switch_is_per_owner),
        cmocka_unit_test(conversions_use_2_54_exactly),
        cmocka_unit_test(metric_in_and_out),
        cmocka_unit_test(bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
