/* SPDX-License-Identifier: MIT */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <math.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/matrix.h"

/* Doubles within an absolute tolerance (cmocka's float assertion is single precision). */
#define assert_near(a, b, tol) assert_near_((a), (b), (tol), __FILE__, __LINE__)
static void assert_near_(double a, double b, double tol, const char *file, int line)
{
    if (!(fabs(a - b) <= tol)) {
        print_error("%.17g != %.17g (tolerance %g)\n", a, b, tol);
        _fail(file, line);
    }
}

#define assert_loc(l, X, Y, Z, O, A, T, tol) \
    do {                                     \
        assert_near((l).x, (X), (tol));      \
        assert_near((l).y, (Y), (tol));      \
        assert_near((l).z, (Z), (tol));      \
        assert_near((l).o, (O), (tol));      \
        assert_near((l).a, (A), (tol));      \
        assert_near((l).t, (T), (tol));      \
    } while (0)

static void one_d_array_cells(void **state)
{
    double store[5];
    fbrl_array a;
    void *cell;
    (void)state;
    assert_int_equal(fbrl_array_init(&a, store, sizeof store, sizeof(double), 5), FBRL_OK);
    for (size_t i = 0; i < 5; i++) {
        assert_int_equal(fbrl_array_cell(&a, i, &cell), FBRL_OK);
        assert_ptr_equal(cell, &store[i]);
        *(double *)cell = (double)i * 1.5;
    }
    assert_true(store[4] == 6.0);
    assert_int_equal(fbrl_array_cell(&a, 5, &cell), FBRL_ERANGE);
    assert_int_equal(fbrl_array_cell(&a, SIZE_MAX, &cell), FBRL_ERANGE);
    /* Storage one byte short of five cells. */
    assert_int_equal(fbrl_array_init(&a, store, sizeof store - 1, sizeof(double), 5), FBRL_ENOSPC);
}

static void two_d_array_cells_row_by_row(void **state)
{
    /* 3 rows x 4 columns of 6-byte cells: cell (r, c) at (r*4 + c) * 6. */
    unsigned char store[3 * 4 * 6];
    fbrl_array a;
    void *cell;
    size_t bytes;
    (void)state;
    assert_int_equal(fbrl_array_bytes(6, 3, 4, &bytes), FBRL_OK);
    assert_int_equal(bytes, 72);
    assert_int_equal(fbrl_array2_init(&a, store, sizeof store, 6, 3, 4), FBRL_OK);
    assert_int_equal(fbrl_array2_cell(&a, 0, 0, &cell), FBRL_OK);
    assert_ptr_equal(cell, store);
    assert_int_equal(fbrl_array2_cell(&a, 0, 3, &cell), FBRL_OK);
    assert_ptr_equal(cell, store + 18);
    assert_int_equal(fbrl_array2_cell(&a, 1, 0, &cell), FBRL_OK);
    assert_ptr_equal(cell, store + 24);
    assert_int_equal(fbrl_array2_cell(&a, 2, 3, &cell), FBRL_OK);
    assert_ptr_equal(cell, store + 66);
    assert_int_equal(fbrl_array_cell(&a, 11, &cell), FBRL_OK); /* flat index, last cell */
    assert_ptr_equal(cell, store + 66);
    assert_int_equal(fbrl_array2_cell(&a, 3, 0, &cell), FBRL_ERANGE);
    assert_int_equal(fbrl_array2_cell(&a, 0, 4, &cell), FBRL_ERANGE);
    assert_int_equal(fbrl_array_cell(&a, 12, &cell), FBRL_ERANGE);
    /* Every cell distinct and inside storage: write each cell's own index. */
    for (size_t r = 0; r < 3; r++)
        for (size_t c = 0; c < 4; c++) {
            assert_int_equal(fbrl_array2_cell(&a, r, c, &cell), FBRL_OK);
            memset(cell, (int)(r * 4 + c), 6);
        }
    for (size_t i = 0; i < sizeof store; i++)
        assert_int_equal(store[i], i / 6);
}

static void array_bad_input(void **state)
{
    unsigned char store[16];
    fbrl_array a, zero;
    void *cell = NULL;
    size_t bytes;
    (void)state;
    memset(&zero, 0, sizeof zero);
    assert_int_equal(fbrl_array_init(NULL, store, 16, 1, 16), FBRL_EINVAL);
    assert_int_equal(fbrl_array_init(&a, NULL, 16, 1, 16), FBRL_EINVAL);
    assert_int_equal(fbrl_array_init(&a, store, 16, 0, 16), FBRL_EINVAL);
    assert_int_equal(fbrl_array_init(&a, store, 16, 1, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_array2_init(&a, store, 16, 1, 0, 4), FBRL_EINVAL);
    assert_int_equal(fbrl_array2_init(&a, store, 16, 1, 4, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_array2_init(&a, store, 16, 2, 3, 3), FBRL_ENOSPC);
    assert_int_equal(fbrl_array_bytes(SIZE_MAX / 2, 3, 1, &bytes), FBRL_EOVERFLOW);
    assert_int_equal(fbrl_array_bytes(1, SIZE_MAX / 2, 3, &bytes), FBRL_EOVERFLOW);
    assert_int_equal(fbrl_array2_init(&a, store, SIZE_MAX, 16, SIZE_MAX / 8, 4), FBRL_EOVERFLOW);
    assert_int_equal(fbrl_array_bytes(1, 1, 1, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_array_cell(NULL, 0, &cell), FBRL_EINVAL);
    assert_int_equal(fbrl_array_cell(&zero, 0, &cell), FBRL_EINVAL);
    assert_int_equal(fbrl_array2_cell(&zero, 0, 0, &cell), FBRL_EINVAL);
    assert_int_equal(fbrl_array_init(&a, store, 16, 1, 16), FBRL_OK);
    assert_int_equal(fbrl_array_cell(&a, 0, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_array2_cell(&a, 0, 0, NULL), FBRL_EINVAL);
    assert_null(cell);
}

/* RECTMAT: base (10, 5, 1) with yaw 0, pitch -90, roll 45; spacing dx 0.75, dy -1.25,
 * dz 0.5. Expected values worked by hand (all exact in binary: multiples of 0.25). */
static void rectmat_hand_values(void **state)
{
    fbrl_loc base = {10, 5, 1, 0, -90, 45}, l;
    fbrl_rectmat m;
    (void)state;
    assert_int_equal(fbrl_rectmat_init(&m, &base, 0.75, -1.25, 0.5), FBRL_OK);
    /* (0,0,0): the base itself. */
    assert_int_equal(fbrl_rectmat_loc(&m, 0, 0, 0, &l), FBRL_OK);
    assert_memory_equal(&l, &base, sizeof l);
    /* (3,5,0): x 10+2.25 = 12.25, y 5-6.25 = -1.25, z 1. */
    assert_int_equal(fbrl_rectmat_loc(&m, 3, 5, 0, &l), FBRL_OK);
    assert_loc(l, 12.25, -1.25, 1.0, 0, -90, 45, 0.0);
    /* (1,1,1): 10.75, 3.75, 1.5. */
    assert_int_equal(fbrl_rectmat_loc(&m, 1, 1, 1, &l), FBRL_OK);
    assert_loc(l, 10.75, 3.75, 1.5, 0, -90, 45, 0.0);
    /* (-2,4,2): 10-1.5 = 8.5, 5-5 = 0, 1+1 = 2. Negative indices reach behind the base. */
    assert_int_equal(fbrl_rectmat_loc(&m, -2, 4, 2, &l), FBRL_OK);
    assert_loc(l, 8.5, 0.0, 2.0, 0, -90, 45, 0.0);
    /* (7,-3,-1): 10+5.25 = 15.25, 5+3.75 = 8.75, 1-0.5 = 0.5. */
    assert_int_equal(fbrl_rectmat_loc(&m, 7, -3, -1, &l), FBRL_OK);
    assert_loc(l, 15.25, 8.75, 0.5, 0, -90, 45, 0.0);
    /* (100,0,-8): 10+75 = 85, 5, 1-4 = -3. */
    assert_int_equal(fbrl_rectmat_loc(&m, 100, 0, -8, &l), FBRL_OK);
    assert_loc(l, 85.0, 5.0, -3.0, 0, -90, 45, 0.0);
    /* The thesis example LOC 1.0 2.0 3.0 RECTMAT MAT, (1,1,1) from base (0,0,0): 1, 2, 3. */
    fbrl_loc zero = {0, 0, 0, 0, 0, 0};
    assert_int_equal(fbrl_rectmat_init(&m, &zero, 1.0, 2.0, 3.0), FBRL_OK);
    assert_int_equal(fbrl_rectmat_loc(&m, 1, 1, 1, &l), FBRL_OK);
    assert_loc(l, 1.0, 2.0, 3.0, 0, 0, 0, 0.0);
}

/* RADMAT 1: base (6, 8, 2) yaw 30, pitch -90, roll 0: radius 10, direction (0.6, 0.8).
 * Quarter turns (inc pi/2), rings 2.5 apart, levels 1.5 apart. Turning (0.6, 0.8) by
 * +90 gives (-0.8, 0.6), by 180 (-0.6, -0.8), by -90 (0.8, -0.6), by 360 itself. */
static void radmat_hand_values_quarter_turns(void **state)
{
    fbrl_loc base = {6, 8, 2, 30, -90, 0}, l;
    fbrl_radmat m;
    const double tol = 1e-12;
    (void)state;
    assert_int_equal(fbrl_radmat_init(&m, &base, FBRL_PI / 2, 2.5, 1.5), FBRL_OK);
    assert_near(m.r0, 10.0, tol);
    /* (0,0,0): the base itself, bit for bit. */
    assert_int_equal(fbrl_radmat_loc(&m, 0, 0, 0, &l), FBRL_OK);
    assert_memory_equal(&l, &base, sizeof l);
    /* (0,0,3): same x, y exactly; z 2 + 4.5 = 6.5. */
    assert_int_equal(fbrl_radmat_loc(&m, 0, 0, 3, &l), FBRL_OK);
    assert_true(l.x == 6.0 && l.y == 8.0 && l.z == 6.5 && l.o == 30.0);
    /* (1,1,0): radius 12.5, direction (-0.8, 0.6) -> (-10, 7.5), z 2, yaw 30+90 = 120. */
    assert_int_equal(fbrl_radmat_loc(&m, 1, 1, 0, &l), FBRL_OK);
    assert_loc(l, -10.0, 7.5, 2.0, 120.0, -90.0, 0.0, tol);
    /* (0,2,1): radius 10, direction (-0.6, -0.8) -> (-6, -8), z 3.5, yaw 210. */
    assert_int_equal(fbrl_radmat_loc(&m, 0, 2, 1, &l), FBRL_OK);
    assert_loc(l, -6.0, -8.0, 3.5, 210.0, -90.0, 0.0, tol);
    /* (-2,-1,-2): radius 10-5 = 5, direction (0.8, -0.6) -> (4, -3), z 2-3 = -1, yaw -60. */
    assert_int_equal(fbrl_radmat_loc(&m, -2, -1, -2, &l), FBRL_OK);
    assert_loc(l, 4.0, -3.0, -1.0, -60.0, -90.0, 0.0, tol);
    /* (4,4,0): radius 20, full turn -> (12, 16), yaw 30+360 = 390 (not wrapped). */
    assert_int_equal(fbrl_radmat_loc(&m, 4, 4, 0, &l), FBRL_OK);
    assert_loc(l, 12.0, 16.0, 2.0, 390.0, -90.0, 0.0, tol);
    /* (-4,1,0): radius 0: the centre. (-5,0,0): radius -2.5, through the centre: refused. */
    assert_int_equal(fbrl_radmat_loc(&m, -4, 1, 0, &l), FBRL_OK);
    assert_loc(l, 0.0, 0.0, 2.0, 120.0, -90.0, 0.0, tol);
    assert_int_equal(fbrl_radmat_loc(&m, -5, 0, 0, &l), FBRL_ERANGE);
}

/* RADMAT 2: the thesis's example 0.2 0.5 1.0 LOC RADMAT MAT with base (10, 0, 5), yaw 0.
 * cos 0.2 = 0.98006657784124163, sin 0.2 = 0.19866933079506122 (tables);
 * cos 0.6 = 0.82533561490967829, sin 0.6 = 0.56464247339503535; 0.2 rad = 11.459155902616465 deg. */
static void radmat_hand_values_thesis_example(void **state)
{
    fbrl_loc base = {10, 0, 5, 0, -90, 15}, l;
    fbrl_radmat m;
    const double tol = 1e-12;
    (void)state;
    assert_int_equal(fbrl_radmat_init(&m, &base, 0.2, 0.5, 1.0), FBRL_OK);
    /* 1 1 2 <loc> MAT: radius 10.5 at 0.2 rad, z 7:
     * x = 10.5 * 0.98006657784124163 = 10.290699067333037
     * y = 10.5 * 0.19866933079506122 = 2.0860279733481428 */
    assert_int_equal(fbrl_radmat_loc(&m, 1, 1, 2, &l), FBRL_OK);
    assert_loc(l, 10.290699067333037, 2.0860279733481428, 7.0, 11.459155902616465, -90, 15, tol);
    /* (-1,-3,-1): radius 9.5 at -0.6 rad, z 4:
     * x = 9.5 * 0.82533561490967829 = 7.8406883416419438
     * y = -9.5 * 0.56464247339503535 = -5.3641034972528358, yaw -34.377467707849396 */
    assert_int_equal(fbrl_radmat_loc(&m, -1, -3, -1, &l), FBRL_OK);
    assert_loc(l, 7.8406883416419438, -5.3641034972528358, 4.0, -34.377467707849396, -90, 15, tol);
    /* (2,0,0): radius 11 on the x axis. */
    assert_int_equal(fbrl_radmat_loc(&m, 2, 0, 0, &l), FBRL_OK);
    assert_loc(l, 11.0, 0.0, 5.0, 0.0, -90, 15, tol);
}

static void matrix_bad_input(void **state)
{
    fbrl_loc base = {6, 8, 2, 30, -90, 0}, l = base, axis = {0, 0, 3, 0, 0, 0};
    fbrl_rectmat rm;
    fbrl_radmat dm;
    (void)state;
    assert_int_equal(fbrl_rectmat_init(NULL, &base, 1, 1, 1), FBRL_EINVAL);
    assert_int_equal(fbrl_rectmat_init(&rm, NULL, 1, 1, 1), FBRL_EINVAL);
    assert_int_equal(fbrl_rectmat_init(&rm, &base, NAN, 1, 1), FBRL_ENONFINITE);
    assert_int_equal(fbrl_rectmat_init(&rm, &base, 1, 1, INFINITY), FBRL_ENONFINITE);
    base.o = NAN;
    assert_int_equal(fbrl_rectmat_init(&rm, &base, 1, 1, 1), FBRL_ENONFINITE);
    assert_int_equal(fbrl_radmat_init(&dm, &base, 1, 1, 1), FBRL_ENONFINITE);
    base.o = 30;
    assert_int_equal(fbrl_rectmat_init(&rm, &base, 1e308, 1, 1), FBRL_OK);
    assert_int_equal(fbrl_rectmat_loc(&rm, 10, 0, 0, &l), FBRL_EOVERFLOW);
    assert_int_equal(fbrl_rectmat_loc(&rm, 0, 0, 0, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_rectmat_loc(NULL, 0, 0, 0, &l), FBRL_EINVAL);
    assert_memory_equal(&l, &base, sizeof l);
    assert_int_equal(fbrl_radmat_init(NULL, &base, 1, 1, 1), FBRL_EINVAL);
    assert_int_equal(fbrl_radmat_init(&dm, NULL, 1, 1, 1), FBRL_EINVAL);
    assert_int_equal(fbrl_radmat_init(&dm, &base, 1, NAN, 1), FBRL_ENONFINITE);
    assert_int_equal(fbrl_radmat_init(&dm, &axis, 0.1, 1, 1), FBRL_ERANGE);
    assert_int_equal(fbrl_radmat_init(&dm, &base, 0.1, 1, 1), FBRL_OK);
    assert_int_equal(fbrl_radmat_loc(NULL, 0, 0, 0, &l), FBRL_EINVAL);
    assert_int_equal(fbrl_radmat_loc(&dm, 0, 0, 0, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_radmat_loc(&dm, -11, 0, 0, &l), FBRL_ERANGE); /* radius -1 */
    fbrl_radmat zeroed;
    memset(&zeroed, 0, sizeof zeroed);
    assert_int_equal(fbrl_radmat_loc(&zeroed, 0, 0, 0, &l), FBRL_EINVAL);
    assert_int_equal(fbrl_radmat_init(&dm, &base, 0.1, 1e308, 1), FBRL_OK);
    assert_int_equal(fbrl_radmat_loc(&dm, 10, 0, 0, &l), FBRL_EOVERFLOW);
    assert_memory_equal(&l, &base, sizeof l);
}

static void show_matrices(void **state)
{
    fbrl_loc base = {10, 0, 5, 0, -90, 0};
    fbrl_rectmat rm;
    fbrl_radmat dm;
    char buf[FBRL_MATRIX_TEXT_SIZE], small[20];
    (void)state;
    fbrl_rectmat_init(&rm, &base, 0.75, -1.25, 0.5);
    assert_int_equal(fbrl_rectmat_format(&rm, 0, buf, sizeof buf), FBRL_OK);
    assert_string_equal(buf, "RECTMAT base X   +10.0000 Y    +0.0000 Z    +5.0000 in  "
                             "O   +0.000 A  -90.000 T   +0.000 deg  "
                             "step X    +0.7500 Y    -1.2500 Z    +0.5000 in");
    assert_int_equal(fbrl_rectmat_format(&rm, 1, buf, sizeof buf), FBRL_OK);
    assert_string_equal(buf, "RECTMAT base X   +25.4000 Y    +0.0000 Z   +12.7000 cm  "
                             "O   +0.000 A  -90.000 T   +0.000 deg  "
                             "step X    +1.9050 Y    -3.1750 Z    +1.2700 cm");
    fbrl_radmat_init(&dm, &base, 0.2, 0.5, 1.0);
    assert_int_equal(fbrl_radmat_format(&dm, 0, buf, sizeof buf), FBRL_OK);
    assert_string_equal(buf, "RADMAT base X   +10.0000 Y    +0.0000 Z    +5.0000 in  "
                             "O   +0.000 A  -90.000 T   +0.000 deg  "
                             "inc +0.200000 rad  ring    +0.5000 Z    +1.0000 in  "
                             "radius   +10.0000 in  angle +0.000000 rad");
    /* The documented size holds the widest values (every shown number near -1e9). */
    fbrl_loc wide = {-7e8, -7e8, -999999999, -999999999, -999999999, -999999999};
    fbrl_radmat wm;
    fbrl_rectmat wr;
    assert_int_equal(fbrl_radmat_init(&wm, &wide, -999999999, -999999999, -999999999), FBRL_OK);
    assert_int_equal(fbrl_radmat_format(&wm, 0, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_rectmat_init(&wr, &wide, -999999999, -999999999, -999999999), FBRL_OK);
    assert_int_equal(fbrl_rectmat_format(&wr, 0, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_radmat_format(&dm, 0, small, sizeof small), FBRL_ENOSPC);
    assert_int_equal(strlen(small), sizeof small - 1);
    assert_int_equal(fbrl_rectmat_format(&rm, 0, small, sizeof small), FBRL_ENOSPC);
    assert_int_equal(fbrl_rectmat_format(NULL, 0, buf, sizeof buf), FBRL_EINVAL);
    assert_int_equal(fbrl_rectmat_format(&rm, 0, NULL, sizeof buf), FBRL_EINVAL);
    assert_int_equal(fbrl_radmat_format(&dm, 0, buf, 0), FBRL_EINVAL);
    rm.dx = 1e308;
    assert_int_equal(fbrl_rectmat_format(&rm, 1, buf, sizeof buf), FBRL_EOVERFLOW);
    dm.inc_angle = NAN;
    assert_int_equal(fbrl_radmat_format(&dm, 0, buf, sizeof buf), FBRL_ENONFINITE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(one_d_array_cells),
        cmocka_unit_test(two_d_array_cells_row_by_row),
        cmocka_unit_test(array_bad_input),
        cmocka_unit_test(rectmat_hand_values),
        cmocka_unit_test(radmat_hand_values_quarter_turns),
        cmocka_unit_test(radmat_hand_values_thesis_example),
        cmocka_unit_test(matrix_bad_input),
        cmocka_unit_test(show_matrices),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
