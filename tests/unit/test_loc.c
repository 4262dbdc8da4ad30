/* SPDX-License-Identifier: MIT */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <math.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/loc.h"

static const fbrl_loc sample = {12.0, -3.5, 1.25, 90.0, -90.0, 0.0};

static void get_and_set_each_axis(void **state)
{
    fbrl_loc l = sample;
    double v;
    (void)state;
    assert_int_equal(fbrl_loc_get(&l, FBRL_LOC_X, &v), FBRL_OK);
    assert_true(v == 12.0);
    assert_int_equal(fbrl_loc_get(&l, FBRL_LOC_Y, &v), FBRL_OK);
    assert_true(v == -3.5);
    assert_int_equal(fbrl_loc_get(&l, FBRL_LOC_Z, &v), FBRL_OK);
    assert_true(v == 1.25);
    assert_int_equal(fbrl_loc_get(&l, FBRL_LOC_O, &v), FBRL_OK);
    assert_true(v == 90.0);
    assert_int_equal(fbrl_loc_get(&l, FBRL_LOC_A, &v), FBRL_OK);
    assert_true(v == -90.0);
    assert_int_equal(fbrl_loc_get(&l, FBRL_LOC_T, &v), FBRL_OK);
    assert_true(v == 0.0);
    /* Setting one axis changes that field only. */
    for (int ax = FBRL_LOC_X; ax < FBRL_LOC_NAXES; ax++) {
        fbrl_loc m = sample;
        assert_int_equal(fbrl_loc_set(&m, (fbrl_loc_axis)ax, 100.0 + ax), FBRL_OK);
        assert_true(m.x == (ax == FBRL_LOC_X ? 100.0 : sample.x));
        assert_true(m.y == (ax == FBRL_LOC_Y ? 101.0 : sample.y));
        assert_true(m.z == (ax == FBRL_LOC_Z ? 102.0 : sample.z));
        assert_true(m.o == (ax == FBRL_LOC_O ? 103.0 : sample.o));
        assert_true(m.a == (ax == FBRL_LOC_A ? 104.0 : sample.a));
        assert_true(m.t == (ax == FBRL_LOC_T ? 105.0 : sample.t));
        assert_int_equal(fbrl_loc_get(&m, (fbrl_loc_axis)ax, &v), FBRL_OK);
        assert_true(v == 100.0 + ax);
    }
}

static void define_copy_shift(void **state)
{
    fbrl_loc a, b, c;
    (void)state;
    assert_int_equal(fbrl_loc_define(&a, 1, 2, 3, 4, 5, 6), FBRL_OK);
    assert_true(a.x == 1 && a.y == 2 && a.z == 3 && a.o == 4 && a.a == 5 && a.t == 6);
    assert_int_equal(fbrl_loc_copy(&b, &a), FBRL_OK);
    assert_memory_equal(&a, &b, sizeof a);
    assert_int_equal(fbrl_loc_copy(&b, &b), FBRL_OK);
    assert_memory_equal(&a, &b, sizeof a);
    assert_int_equal(fbrl_loc_define(&c, 0.5, -1, 10, -4, 0.25, 180), FBRL_OK);
    assert_int_equal(fbrl_loc_shift(&a, &c), FBRL_OK);
    assert_true(a.x == 1.5 && a.y == 1 && a.z == 13 && a.o == 0 && a.a == 5.25 && a.t == 186);
    /* Shifting by itself doubles. */
    assert_int_equal(fbrl_loc_shift(&c, &c), FBRL_OK);
    assert_true(c.x == 1 && c.y == -2 && c.z == 20 && c.o == -8 && c.a == 0.5 && c.t == 360);
}

static void distance_is_euclidean_on_position(void **state)
{
    fbrl_loc a = {1, 2, 3, 0, 0, 0}, b = {4, 6, 15, 90, 45, 30};
    double d;
    (void)state;
    /* (3, 4, 12) -> 13; orientation ignored. */
    assert_int_equal(fbrl_loc_distance(&a, &b, &d), FBRL_OK);
    assert_true(d == 13.0);
    assert_int_equal(fbrl_loc_distance(&b, &a, &d), FBRL_OK);
    assert_true(d == 13.0);
    /* Large but finite coordinates do not overflow the squares. */
    fbrl_loc big1 = {1e200, 0, 0, 0, 0, 0}, big2 = {-1e200, 0, 0, 0, 0, 0};
    assert_int_equal(fbrl_loc_distance(&big1, &big2, &d), FBRL_OK);
    assert_true(d == 2e200);
    fbrl_loc huge1 = {1.5e308, 0, 0, 0, 0, 0}, huge2 = {-1.5e308, 0, 0, 0, 0, 0};
    assert_int_equal(fbrl_loc_distance(&huge1, &huge2, &d), FBRL_EOVERFLOW);
}

static void format_fixed_and_metric(void **state)
{
    char buf[FBRL_LOC_TEXT_SIZE];
    (void)state;
    assert_int_equal(fbrl_loc_format(&sample, 0, buf, sizeof buf), FBRL_OK);
    assert_string_equal(buf,
                        "X   +12.0000 Y    -3.5000 Z    +1.2500 in  O  +90.000 A  -90.000 T   +0.000 deg");
    /* Metric: lengths * 2.54, angles unchanged. */
    assert_int_equal(fbrl_loc_format(&sample, 1, buf, sizeof buf), FBRL_OK);
    assert_string_equal(buf,
                        "X   +30.4800 Y    -8.8900 Z    +3.1750 cm  O  +90.000 A  -90.000 T   +0.000 deg");
    /* Fixed width: a different location has the same length. */
    fbrl_loc other = {-0.0001, 999.5, -17, -179.5, 12.25, 1};
    char buf2[FBRL_LOC_TEXT_SIZE];
    assert_int_equal(fbrl_loc_format(&other, 0, buf2, sizeof buf2), FBRL_OK);
    assert_int_equal(strlen(buf), strlen(buf2));
    /* Values that round to zero show as +0, never -0. */
    fbrl_loc tiny = {-1e-9, -0.0, -0.00004, -1e-12, -0.0004, -0.0};
    assert_int_equal(fbrl_loc_format(&tiny, 0, buf2, sizeof buf2), FBRL_OK);
    assert_string_equal(buf2,
                        "X    +0.0000 Y    +0.0000 Z    +0.0000 in  O   +0.000 A   +0.000 T   +0.000 deg");
    /* Largest documented values fit. */
    fbrl_loc wide = {-999999999.0, -999999999.0, -999999999.0, -999999999.0, -999999999.0, -999999999.0};
    assert_int_equal(fbrl_loc_format(&wide, 0, buf2, sizeof buf2), FBRL_OK);
    /* Too small a buffer: ENOSPC and a terminated prefix. */
    char small[10];
    assert_int_equal(fbrl_loc_format(&sample, 0, small, sizeof small), FBRL_ENOSPC);
    assert_string_equal(small, "X   +12.0");
    assert_int_equal(fbrl_loc_format(&sample, 0, small, 0), FBRL_EINVAL);
}

static void bad_input(void **state)
{
    fbrl_loc l = sample, before;
    double v = 7.0;
    char buf[FBRL_LOC_TEXT_SIZE];
    (void)state;
    assert_int_equal(fbrl_loc_get(NULL, FBRL_LOC_X, &v), FBRL_EINVAL);
    assert_int_equal(fbrl_loc_get(&l, FBRL_LOC_X, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_loc_get(&l, FBRL_LOC_NAXES, &v), FBRL_ERANGE);
    assert_int_equal(fbrl_loc_get(&l, (fbrl_loc_axis)-1, &v), FBRL_ERANGE);
    assert_true(v == 7.0);
    assert_int_equal(fbrl_loc_set(NULL, FBRL_LOC_X, 1), FBRL_EINVAL);
    assert_int_equal(fbrl_loc_set(&l, (fbrl_loc_axis)6, 1), FBRL_ERANGE);
    assert_int_equal(fbrl_loc_set(&l, (fbrl_loc_axis)1000, 1), FBRL_ERANGE);
    assert_int_equal(fbrl_loc_set(&l, FBRL_LOC_Z, NAN), FBRL_ENONFINITE);
    assert_int_equal(fbrl_loc_set(&l, FBRL_LOC_T, -INFINITY), FBRL_ENONFINITE);
    assert_memory_equal(&l, &sample, sizeof l);
    assert_int_equal(fbrl_loc_define(NULL, 1, 2, 3, 4, 5, 6), FBRL_EINVAL);
    assert_int_equal(fbrl_loc_define(&l, 1, 2, 3, 4, 5, NAN), FBRL_ENONFINITE);
    assert_int_equal(fbrl_loc_define(&l, INFINITY, 2, 3, 4, 5, 6), FBRL_ENONFINITE);
    assert_memory_equal(&l, &sample, sizeof l);
    assert_int_equal(fbrl_loc_copy(NULL, &l), FBRL_EINVAL);
    assert_int_equal(fbrl_loc_copy(&l, NULL), FBRL_EINVAL);
    fbrl_loc bad = sample;
    bad.a = NAN;
    assert_int_equal(fbrl_loc_check(&bad), FBRL_ENONFINITE);
    assert_int_equal(fbrl_loc_check(NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_loc_check(&sample), FBRL_OK);
    assert_int_equal(fbrl_loc_copy(&l, &bad), FBRL_ENONFINITE);
    assert_int_equal(fbrl_loc_shift(&l, &bad), FBRL_ENONFINITE);
    assert_int_equal(fbrl_loc_shift(&bad, &l), FBRL_ENONFINITE);
    assert_int_equal(fbrl_loc_shift(NULL, &l), FBRL_EINVAL);
    assert_int_equal(fbrl_loc_shift(&l, NULL), FBRL_EINVAL);
    assert_memory_equal(&l, &sample, sizeof l);
    fbrl_loc big = {1.7e308, 0, 0, 0, 0, 0};
    before = big;
    assert_int_equal(fbrl_loc_shift(&big, &before), FBRL_EOVERFLOW);
    assert_memory_equal(&big, &before, sizeof big);
    assert_int_equal(fbrl_loc_distance(NULL, &l, &v), FBRL_EINVAL);
    assert_int_equal(fbrl_loc_distance(&l, NULL, &v), FBRL_EINVAL);
    assert_int_equal(fbrl_loc_distance(&l, &l, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_loc_distance(&l, &bad, &v), FBRL_ENONFINITE);
    assert_int_equal(fbrl_loc_format(NULL, 0, buf, sizeof buf), FBRL_EINVAL);
    assert_int_equal(fbrl_loc_format(&l, 0, NULL, sizeof buf), FBRL_EINVAL);
    assert_int_equal(fbrl_loc_format(&bad, 0, buf, sizeof buf), FBRL_ENONFINITE);
    assert_string_equal(buf, "");
    /* Metric display of a huge inch value overflows the conversion. */
    assert_int_equal(fbrl_loc_format(&big, 1, buf, sizeof buf), FBRL_EOVERFLOW);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(get_and_set_each_axis),
        cmocka_unit_test(define_copy_shift),
        cmocka_unit_test(distance_is_euclidean_on_position),
        cmocka_unit_test(format_fixed_and_metric),
        cmocka_unit_test(bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
