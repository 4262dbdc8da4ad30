/* SPDX-License-Identifier: MIT */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <math.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/calib.h"
#include "fbrl/crc32.h"

/* Doubles within an absolute tolerance (cmocka's float assertion is single precision). */
#define assert_near(a, b, tol) assert_near_((a), (b), (tol), __FILE__, __LINE__)
static void assert_near_(double a, double b, double tol, const char *file, int line)
{
    if (!(fabs(a - b) <= tol)) {
        print_error("%.17g != %.17g (tolerance %g)\n", a, b, tol);
        _fail(file, line);
    }
}

/* ---- a fixed-seed PRNG (splitmix64), so every run checks the same cases ---- */
static uint64_t rng_state;
static uint64_t rng_next(void)
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
static double uniform(double lo, double hi)
{
    return lo + (hi - lo) * ((double)(rng_next() >> 11) / 9007199254740992.0);
}

/* ---- the test's own rigid-motion algebra (independent of calib.c) ---- */
typedef struct {
    double r[3][3], t[3];
} motion;

static void rot_axis(int axis, double rad, double r[3][3])
{
    double c = cos(rad), s = sin(rad);
    memset(r, 0, 9 * sizeof(double));
    r[axis][axis] = 1.0;
    int a = (axis + 1) % 3, b = (axis + 2) % 3;
    r[a][a] = c;
    r[a][b] = -s;
    r[b][a] = s;
    r[b][b] = c;
}

static void matmul(double a[3][3], double b[3][3], double out[3][3])
{
    double r[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
    memcpy(out, r, sizeof r);
}

/* Uniformly random rotation (Shoemake's unit quaternion). */
static void random_rotation(double r[3][3])
{
    double u1 = uniform(0, 1), u2 = uniform(0, 2 * FBRL_PI), u3 = uniform(0, 2 * FBRL_PI);
    double w = sqrt(1 - u1) * sin(u2), x = sqrt(1 - u1) * cos(u2);
    double y = sqrt(u1) * sin(u3), z = sqrt(u1) * cos(u3);
    r[0][0] = 1 - 2 * (y * y + z * z);
    r[0][1] = 2 * (x * y - w * z);
    r[0][2] = 2 * (x * z + w * y);
    r[1][0] = 2 * (x * y + w * z);
    r[1][1] = 1 - 2 * (x * x + z * z);
    r[1][2] = 2 * (y * z - w * x);
    r[2][0] = 2 * (x * z - w * y);
    r[2][1] = 2 * (y * z + w * x);
    r[2][2] = 1 - 2 * (x * x + y * y);
}

static void apply(const motion *m, const double p[3], double out[3])
{
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = m->r[i][0] * p[0] + m->r[i][1] * p[1] + m->r[i][2] * p[2] + m->t[i];
    memcpy(out, r, sizeof r);
}

static fbrl_loc loc_at(const double p[3], double o, double a, double t)
{
    fbrl_loc l = {p[0], p[1], p[2], o, a, t};
    return l;
}

/* The tool rotation by the documented convention, built from elementary rotations. */
static void tool_matrix(double yaw, double pitch, double roll, double r[3][3])
{
    double z[3][3], y[3][3], x[3][3];
    rot_axis(2, yaw * FBRL_PI / 180, z);
    rot_axis(1, -pitch * FBRL_PI / 180, y);
    rot_axis(0, roll * FBRL_PI / 180, x);
    matmul(z, y, r);
    matmul(r, x, r);
}

static double matdiff(double a[3][3], double b[3][3])
{
    double m = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            m = fmax(m, fabs(a[i][j] - b[i][j]));
    return m;
}

static double dist3(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

/* ---- the convention ---- */

static void orientation_convention(void **state)
{
    fbrl_rot rot;
    double *r = &rot.m[0][0], m[3][3];
    double yaw, pitch, roll;
    (void)state;
    /* Tool straight down: axis (0, 0, -1). */
    assert_int_equal(fbrl_calib_orient_to_matrix(0, -90, 0, &rot), FBRL_OK);
    assert_near(r[0], 0, 1e-15);
    assert_near(r[3], 0, 1e-15);
    assert_near(r[6], -1, 1e-15);
    /* Yaw 90, pitch 0: tool axis along +y. Pitch 30 at yaw 0: (cos 30, 0, sin 30). */
    assert_int_equal(fbrl_calib_orient_to_matrix(90, 0, 0, &rot), FBRL_OK);
    assert_near(r[0], 0, 1e-15);
    assert_near(r[3], 1, 1e-15);
    assert_near(r[6], 0, 1e-15);
    assert_int_equal(fbrl_calib_orient_to_matrix(0, 30, 0, &rot), FBRL_OK);
    assert_near(r[0], 0.86602540378443865, 1e-15);
    assert_near(r[6], 0.5, 1e-15);
    rng_state = 42;
    for (int i = 0; i < 2000; i++) {
        double y0 = uniform(-179.9, 180), p0 = uniform(-89.9, 89.9), t0 = uniform(-179.9, 180);
        assert_int_equal(fbrl_calib_orient_to_matrix(y0, p0, t0, &rot), FBRL_OK);
        tool_matrix(y0, p0, t0, m);
        assert_true(matdiff(rot.m, m) < 1e-14);
        assert_int_equal(fbrl_calib_matrix_to_orient(&rot, 0, &yaw, &pitch, &roll), FBRL_OK);
        assert_near(yaw, y0, 1e-9);
        assert_near(pitch, p0, 1e-9);
        assert_near(roll, t0, 1e-9);
    }
    /* Vertical tool: yaw comes from the hint and roll carries the turn. For pitch -90 the
     * matrix depends on roll - yaw only: (yaw 30, roll 50) = (yaw 100, roll 120). */
    assert_int_equal(fbrl_calib_orient_to_matrix(30, -90, 50, &rot), FBRL_OK);
    assert_int_equal(fbrl_calib_matrix_to_orient(&rot, 100, &yaw, &pitch, &roll), FBRL_OK);
    assert_near(yaw, 100, 1e-9);
    assert_near(pitch, -90, 1e-9);
    assert_near(roll, 120, 1e-9);
    assert_int_equal(fbrl_calib_matrix_to_orient(&rot, 30, &yaw, &pitch, &roll), FBRL_OK);
    assert_near(yaw, 30, 1e-9);
    assert_near(roll, 50, 1e-9);
}

/* ---- the thesis's planar helpers ---- */

static void ang_from_origin_and_rotate(void **state)
{
    double a, x, y;
    (void)state;
    assert_int_equal(fbrl_calib_ang_from_origin(0, 0, 1, 1, &a), FBRL_OK);
    assert_near(a, FBRL_PI / 4, 1e-15);
    /* P2 at smaller x than P1: atan(0 / -1) would say 0; the answer is pi. */
    assert_int_equal(fbrl_calib_ang_from_origin(1, 0, 0, 0, &a), FBRL_OK);
    assert_near(a, FBRL_PI, 1e-15);
    assert_int_equal(fbrl_calib_ang_from_origin(2, 2, 1, 1, &a), FBRL_OK);
    assert_near(a, -3 * FBRL_PI / 4, 1e-15);
    assert_int_equal(fbrl_calib_ang_from_origin(5, 1, 5, 4, &a), FBRL_OK);
    assert_near(a, FBRL_PI / 2, 1e-15);
    assert_int_equal(fbrl_calib_ang_from_origin(3, 3, 3, 3, &a), FBRL_EDEGENERATE);
    assert_int_equal(fbrl_calib_rotate(1, 0, FBRL_PI / 2, &x, &y), FBRL_OK);
    assert_near(x, 0, 1e-15);
    assert_near(y, 1, 1e-15);
    /* (3, 4) by -90 degrees: (4, -3). */
    assert_int_equal(fbrl_calib_rotate(3, 4, -FBRL_PI / 2, &x, &y), FBRL_OK);
    assert_near(x, 4, 1e-14);
    assert_near(y, -3, 1e-14);
}

/* ---- hand-computed 3-point cases (the 5-axis model, docs/calibration.md) ---- */

static double rad_deg(double d) { return d * FBRL_PI / 180; }

static void three_point_hand_cases(void **state)
{
    fbrl_calpts cal, recal;
    fbrl_calib c;
    fbrl_loc l, out;
    double off = -1;
    (void)state;
    /* A block along +x, turned half a turn about the base axis: (x, y, z) -> (-x, -y, z).
     * P2 then lies at smaller x than P1 (the case the thesis's atan gets wrong). */
    fbrl_loc c1 = {10, 0, 0, 0, 0, 0}, c2 = {15, 0, 0, 0, 0, 0}, c3 = {10, 3, 0, 0, 0, 0};
    fbrl_loc r1 = {-10, 0, 0, 0, 0, 0}, r2 = {-15, 0, 0, 0, 0, 0}, r3 = {-10, -3, 0, 0, 0, 0};
    fbrl_calpts_set(&cal, 1, &c1);
    fbrl_calpts_set(&cal, 2, &c2);
    fbrl_calpts_set(&cal, 3, &c3);
    fbrl_calpts_set(&recal, 1, &r1);
    fbrl_calpts_set(&recal, 2, &r2);
    fbrl_calpts_set(&recal, 3, &r3);
    assert_int_equal(fbrl_calib_3point(&c, &cal, &recal), FBRL_OK);
    /* The arm only turns its waist by 180: (12, 1, 2) pitch 0 roll 20 -> (-12, -1, 2), the
     * waist (the reported yaw) atan2(-1, -12) = -175.236, pitch and roll as they were. */
    fbrl_loc p = {12, 1, 2, 10, 0, 20};
    assert_int_equal(fbrl_calib_map_arm(&c, NULL, &p, &out, &off), FBRL_OK);
    assert_near(out.x, -12, 1e-12);
    assert_near(out.y, -1, 1e-12);
    assert_near(out.z, 2, 1e-12);
    assert_near(out.o, atan2(-1, -12) * 180 / FBRL_PI, 1e-9);
    assert_near(out.a, 0, 1e-9);
    assert_near(out.t, 20, 1e-9);
    assert_near(off, 0, 1e-9);
    fbrl_loc down = {12, 1, 2, 30, -90, 0};
    assert_int_equal(fbrl_calib_map(&c, &down, &out), FBRL_OK);
    assert_near(out.a, -90, 1e-9);
    assert_near(out.t, 0, 1e-9);
    assert_int_equal(fbrl_calib_unmap(&c, &out, &l), FBRL_OK);
    assert_near(l.x, 12, 1e-12);
    assert_near(l.y, 1, 1e-12);
    assert_near(l.z, 2, 1e-12);
    assert_near(l.o, atan2(1, 12) * 180 / FBRL_PI, 1e-9);
    assert_near(l.a, -90, 1e-9);
    assert_near(l.t, 0, 1e-9);

    /* A block turned +90 degrees about its own corner (10, 0): (x, y) -> (10 - y, x - 10).
     * (12, 0, 2) straight down, roll 0: waist 0, so the grip's heading (waist - roll + 90,
     * docs/calibration.md) is 90. Mapped to (10, 2, 2): the waist turns only to
     * atan2(2, 10) = 11.3099, the grip must head 180, so roll = 11.3099 + 90 - 180. */
    fbrl_loc k1 = {10, 0, 0, 0, 0, 0}, k2 = {14, 0, 0, 0, 0, 0}, k3 = {10, 3, 0, 0, 0, 0};
    fbrl_loc m1 = {10, 0, 0, 0, 0, 0}, m2 = {10, 4, 0, 0, 0, 0}, m3 = {7, 0, 0, 0, 0, 0};
    fbrl_calpts_set(&cal, 1, &k1);
    fbrl_calpts_set(&cal, 2, &k2);
    fbrl_calpts_set(&cal, 3, &k3);
    fbrl_calpts_set(&recal, 1, &m1);
    fbrl_calpts_set(&recal, 2, &m2);
    fbrl_calpts_set(&recal, 3, &m3);
    assert_int_equal(fbrl_calib_3point(&c, &cal, &recal), FBRL_OK);
    fbrl_loc t1 = {12, 0, 2, 0, -90, 0};
    assert_int_equal(fbrl_calib_map_arm(&c, NULL, &t1, &out, &off), FBRL_OK);
    double w1 = atan2(2, 10) * 180 / FBRL_PI;
    assert_near(out.x, 10, 1e-12);
    assert_near(out.y, 2, 1e-12);
    assert_near(out.z, 2, 1e-12);
    assert_near(out.o, w1, 1e-9);
    assert_near(out.a, -90, 1e-9);
    assert_near(out.t, w1 + 90 - 180, 1e-9);
    assert_near(off, 0, 1e-9);
    /* The arm's base axis elsewhere (a BASE-OFFSET): the waist is measured from it. */
    double axis[2] = {0, 10};
    assert_int_equal(fbrl_calib_map_arm(&c, axis, &t1, &out, &off), FBRL_OK);
    double w0b = atan2(0 - 10, 12 - 0) * 180 / FBRL_PI, w1b = atan2(2 - 10, 10 - 0) * 180 / FBRL_PI;
    assert_near(out.o, w1b, 1e-9);
    assert_near(out.t, w1b - (w0b - 0 + 90 + 90) + 90, 1e-9);

    /* A block tipped a quarter turn about x: (x, y, z) -> (x, -z, y). A horizontal tool at
     * (1, 2, 3) heading along its waist (63.43) would have to point (0.447, 0, 0.894) at
     * (1, -3, 2), where the waist is -71.57: that tilts 25 degrees across the arm, which a
     * 5-axis arm cannot do. map_arm reports it; map refuses. */
    fbrl_loc d1 = {0, 0, 0, 0, 0, 0}, d2 = {5, 0, 0, 0, 0, 0}, d3 = {0, 4, 0, 0, 0, 0};
    fbrl_loc e1 = {0, 0, 0, 0, 0, 0}, e2 = {5, 0, 0, 0, 0, 0}, e3 = {0, 0, 4, 0, 0, 0};
    fbrl_calpts_set(&cal, 1, &d1);
    fbrl_calpts_set(&cal, 2, &d2);
    fbrl_calpts_set(&cal, 3, &d3);
    fbrl_calpts_set(&recal, 1, &e1);
    fbrl_calpts_set(&recal, 2, &e2);
    fbrl_calpts_set(&recal, 3, &e3);
    assert_int_equal(fbrl_calib_3point(&c, &cal, &recal), FBRL_OK);
    fbrl_loc q = {1, 2, 3, 0, 0, 0};
    assert_int_equal(fbrl_calib_map_arm(&c, NULL, &q, &out, &off), FBRL_OK);
    assert_near(out.x, 1, 1e-12);
    assert_near(out.y, -3, 1e-12);
    assert_near(out.z, 2, 1e-12);
    double dx = 1 / sqrt(5), dz = 2 / sqrt(5), wr = atan2(-3, 1);
    double across = -sin(wr) * dx, along = cos(wr) * dx;
    assert_near(off, asin(fabs(across)) * 180 / FBRL_PI, 1e-9);
    assert_near(out.a, atan2(dz, along) * 180 / FBRL_PI, 1e-9);
    assert_true(off > FBRL_CALIB_AXIS_MAX);
    l = q;
    assert_int_equal(fbrl_calib_map(&c, &q, &l), FBRL_ERANGE);
    assert_memory_equal(&l, &q, sizeof q); /* unchanged */

    /* A shift along the waist direction: (7, 7, 7) -> (8, 8, 7.5); a tilted tool keeps
     * pitch and roll. A shift across it would turn the waist under a tilted tool: the
     * tool axis (pitch -30, heading 45) then lies 11.2 degrees off the waist at (8, 5). */
    fbrl_loc f1 = {1, 1, 0.5, 0, 0, 0}, f2 = {6, 1, 0.5, 0, 0, 0}, f3 = {1, 5, 0.5, 0, 0, 0};
    fbrl_calpts_set(&cal, 1, &d1);
    fbrl_calpts_set(&cal, 2, &d2);
    fbrl_calpts_set(&cal, 3, &d3);
    fbrl_calpts_set(&recal, 1, &f1);
    fbrl_calpts_set(&recal, 2, &f2);
    fbrl_calpts_set(&recal, 3, &f3);
    assert_int_equal(fbrl_calib_3point(&c, &cal, &recal), FBRL_OK);
    fbrl_loc g = {7, 7, 7, 45, -30, 12};
    assert_int_equal(fbrl_calib_map(&c, &g, &out), FBRL_OK);
    assert_near(out.x, 8, 1e-12);
    assert_near(out.y, 8, 1e-12);
    assert_near(out.z, 7.5, 1e-12);
    assert_near(out.o, 45, 1e-9);
    assert_near(out.a, -30, 1e-9);
    assert_near(out.t, 12, 1e-9);
    fbrl_loc f1b = {1, -2, 0.5, 0, 0, 0}, f2b = {6, -2, 0.5, 0, 0, 0}, f3b = {1, 2, 0.5, 0, 0, 0};
    fbrl_calpts_set(&recal, 1, &f1b);
    fbrl_calpts_set(&recal, 2, &f2b);
    fbrl_calpts_set(&recal, 3, &f3b);
    assert_int_equal(fbrl_calib_3point(&c, &cal, &recal), FBRL_OK);
    assert_int_equal(fbrl_calib_map_arm(&c, NULL, &g, &out, &off), FBRL_OK);
    assert_near(off, asin(cos(rad_deg(30)) * sin(rad_deg(45) - atan2(5, 8))) * 180 / FBRL_PI, 1e-9);
    /* Identity: position, pitch and roll unchanged; yaw reported as the waist. */
    fbrl_loc h = {7, 7, 7, 0, -30, 12};
    assert_int_equal(fbrl_calib_identity(&c), FBRL_OK);
    assert_int_equal(fbrl_calib_map(&c, &h, &out), FBRL_OK);
    assert_memory_equal(&out.x, &h.x, 3 * sizeof(double));
    assert_near(out.o, 45, 1e-12);
    assert_near(out.a, -30, 1e-12);
    assert_near(out.t, 12, 1e-12);
    /* On the base axis the location's own yaw stands for the waist. */
    fbrl_loc on_axis = {0, 0, 20, 30, -90, 5};
    assert_int_equal(fbrl_calib_map(&c, &on_axis, &out), FBRL_OK);
    assert_near(out.o, 30, 1e-12);
    assert_near(out.t, 5, 1e-12);
}

/* ---- 10,000 random rigid motions ---- */

static void block_points(double local[3][3])
{
    /* P1 at the block origin, P2 on its x axis, P3 in its xy plane, well off the axis. */
    local[0][0] = 0;
    local[0][1] = 0;
    local[0][2] = 0;
    local[1][0] = uniform(2, 10);
    local[1][1] = 0;
    local[1][2] = 0;
    local[2][0] = uniform(-5, 5);
    local[2][1] = (rng_next() & 1 ? 1 : -1) * uniform(1, 8);
    local[2][2] = 0;
}

/* Rotation angle (degrees) of a rotation matrix. */
static double rot_angle(double r[3][3])
{
    double c = (r[0][0] + r[1][1] + r[2][2] - 1) / 2;
    double s = sqrt((r[2][1] - r[1][2]) * (r[2][1] - r[1][2]) + (r[0][2] - r[2][0]) * (r[0][2] - r[2][0]) +
                    (r[1][0] - r[0][1]) * (r[1][0] - r[0][1])) /
               2;
    return atan2(s, c) * 180 / FBRL_PI;
}

/* The angle (degrees) between the tool frames a and b: that of a * b^T. */
static double frame_angle(double a[3][3], double b[3][3])
{
    double bt[3][3], d[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            bt[i][j] = b[j][i];
    matmul(a, bt, d);
    return rot_angle(d);
}

/* Every rigid motion, any orientation: the position is the true motion's; the mapped
 * tool frame F (the documented convention, with yaw = the waist at the mapped position)
 * is the wanted frame W (true rotation times the frame the arm had) turned by the
 * smallest rotation that brings W's axis into the waist's vertical plane. Checked from
 * its definition: F's axis lies in that plane, the angle between F's and W's axes is
 * the reported off and is the smallest possible (W's axis's angle to the plane), and F
 * differs from W by a rotation of exactly that angle (only the smallest rotation does). */
static void random_rigid_motions(void **state)
{
    int trials = 10000, kinds[4] = {0, 0, 0, 0}, checked = 0;
    double worst_map = 0, worst_round = 0, worst_orient = 0, worst_back = 0;
    (void)state;
    rng_state = 0x5EEDF00Dull;
    for (int trial = 0; trial < trials; trial++) {
        motion pose, truth;
        double local[3][3], p[3];
        fbrl_calpts cal, recal;
        fbrl_calib c;
        int kind = trial % 4;
        kinds[kind]++;
        block_points(local);
        /* Where the block was taught: flat and square (kinds 0, 1) or anywhere, tilted. */
        if (kind <= 1)
            rot_axis(2, 0, pose.r);
        else
            random_rotation(pose.r);
        for (int i = 0; i < 3; i++)
            pose.t[i] = uniform(-20, 20);
        /* How it moved: about the base axis (kind 0, half a turn: P2 ends at smaller x
         * than P1), a tilt and turn (kind 1), or any rotation (kinds 2, 3). */
        if (kind == 0)
            rot_axis(2, FBRL_PI, truth.r);
        else if (kind == 1) {
            double tilt[3][3], turn[3][3];
            rot_axis(rng_next() & 1 ? 0 : 1, uniform(-FBRL_PI / 2, FBRL_PI / 2), tilt);
            rot_axis(2, uniform(-FBRL_PI, FBRL_PI), turn);
            matmul(turn, tilt, truth.r);
        } else
            random_rotation(truth.r);
        for (int i = 0; i < 3; i++)
            truth.t[i] = kind == 0 ? 0 : uniform(-15, 15);
        for (int k = 0; k < 3; k++) {
            double w[3], m[3];
            apply(&pose, local[k], w);
            apply(&truth, w, m);
            cal.p[k] = loc_at(w, 0, 0, 0);
            recal.p[k] = loc_at(m, 0, 0, 0);
        }
        if (kind == 0) /* the case the thesis's atan mishandles really occurs */
            assert_true(recal.p[1].x < recal.p[0].x);
        assert_int_equal(fbrl_calib_3point(&c, &cal, &recal), FBRL_OK);
        for (int k = 0; k < 4; k++) {
            double local_p[3] = {uniform(-5, 15), uniform(-10, 10), uniform(-3, 6)}, want[3];
            double pitch = k == 0 ? -90 : uniform(-90, 90), roll = uniform(-180, 180), off;
            fbrl_loc in, mapped, back;
            apply(&pose, local_p, p);
            apply(&truth, p, want);
            if (hypot(p[0], p[1]) < 0.5 || hypot(want[0], want[1]) < 0.5)
                continue; /* next to the base axis the waist has no direction */
            in = loc_at(p, uniform(-180, 180), pitch, roll);
            assert_int_equal(fbrl_calib_map_arm(&c, NULL, &in, &mapped, &off), FBRL_OK);
            double got[3] = {mapped.x, mapped.y, mapped.z};
            worst_map = fmax(worst_map, dist3(got, want));
            double w0 = atan2(p[1], p[0]) * 180 / FBRL_PI, w1 = atan2(want[1], want[0]);
            assert_near(mapped.o, w1 * 180 / FBRL_PI, 1e-9);
            double t_in[3][3], t_want[3][3], t_got[3][3];
            tool_matrix(w0, pitch, roll, t_in);
            matmul(truth.r, t_in, t_want);
            tool_matrix(mapped.o, mapped.a, mapped.t, t_got);
            /* W's axis's angle to the plane through the base axis and the target */
            double across = -sin(w1) * t_want[0][0] + cos(w1) * t_want[1][0];
            double to_plane = asin(fmin(1, fabs(across))) * 180 / FBRL_PI;
            if (to_plane > 80)
                continue; /* nearly square to the plane: no nearest axis to speak of */
            checked++;
            worst_orient = fmax(worst_orient, fabs(off - to_plane));
            double ga[3] = {t_got[0][0], t_got[1][0], t_got[2][0]};
            double wa[3] = {t_want[0][0], t_want[1][0], t_want[2][0]};
            double cx = ga[1] * wa[2] - ga[2] * wa[1], cy = ga[2] * wa[0] - ga[0] * wa[2];
            double cz = ga[0] * wa[1] - ga[1] * wa[0];
            double axis_gap =
                atan2(sqrt(cx * cx + cy * cy + cz * cz), ga[0] * wa[0] + ga[1] * wa[1] + ga[2] * wa[2]) *
                180 / FBRL_PI;
            worst_orient = fmax(worst_orient, fabs(axis_gap - off));
            worst_orient = fmax(worst_orient, fabs(frame_angle(t_got, t_want) - off));
            /* And back: the position exactly; the orientation too when nothing was lost. */
            assert_int_equal(fbrl_calib_unmap(&c, &mapped, &back), FBRL_OK);
            double round[3] = {back.x, back.y, back.z};
            worst_round = fmax(worst_round, dist3(round, p));
            if (off < 1e-9) {
                double t_back[3][3];
                tool_matrix(back.o, back.a, back.t, t_back);
                worst_back = fmax(worst_back, frame_angle(t_back, t_in));
            }
        }
        /* The three calibration points themselves. */
        for (int k = 0; k < 3; k++) {
            double q[3] = {cal.p[k].x, cal.p[k].y, cal.p[k].z},
                   want[3] = {recal.p[k].x, recal.p[k].y, recal.p[k].z};
            assert_int_equal(fbrl_calib_map_points(&c, q, q, 1), FBRL_OK);
            worst_map = fmax(worst_map, dist3(q, want));
            assert_int_equal(fbrl_calib_unmap_points(&c, q, q, 1), FBRL_OK);
            double orig[3] = {cal.p[k].x, cal.p[k].y, cal.p[k].z};
            worst_round = fmax(worst_round, dist3(q, orig));
        }
    }
    print_message("      %d motions, %d locations: worst map error %.3g in, map+unmap %.3g in, "
                  "smallest-rotation error %.3g deg, unmap of a reachable map %.3g deg\n",
                  trials, checked, worst_map, worst_round, worst_orient, worst_back);
    assert_int_equal(kinds[0] + kinds[1] + kinds[2] + kinds[3], 10000);
    assert_true(checked > 30000);
    assert_true(worst_map < 1e-9);
    assert_true(worst_round < 1e-9);
    assert_true(worst_orient < 1e-6);
    assert_true(worst_back < 1e-6);
}

static void set3(fbrl_calpts *c, double ax, double ay, double az, double bx, double by, double bz, double cx,
                 double cy, double cz)
{
    fbrl_loc a = {ax, ay, az, 0, 0, 0}, b = {bx, by, bz, 0, 0, 0}, d = {cx, cy, cz, 0, 0, 0};
    fbrl_calpts_set(c, 1, &a);
    fbrl_calpts_set(c, 2, &b);
    fbrl_calpts_set(c, 3, &d);
}

static void degenerate_sets_refused(void **state)
{
    fbrl_calpts good, bad;
    fbrl_calib c, before;
    (void)state;
    set3(&good, 0, 0, 0, 5, 0, 0, 0, 4, 0);
    fbrl_calib_identity(&c);
    before = c;
    /* All three coincident. */
    set3(&bad, 1, 2, 3, 1, 2, 3, 1, 2, 3);
    assert_int_equal(fbrl_calib_3point(&c, &bad, &good), FBRL_EDEGENERATE);
    assert_int_equal(fbrl_calib_3point(&c, &good, &bad), FBRL_EDEGENERATE);
    /* P2 on P1 (no x axis), P3 on P1, P3 on P2. */
    set3(&bad, 1, 2, 3, 1, 2, 3, 5, 5, 5);
    assert_int_equal(fbrl_calib_3point(&c, &bad, &good), FBRL_EDEGENERATE);
    set3(&bad, 1, 2, 3, 6, 2, 3, 1, 2, 3);
    assert_int_equal(fbrl_calib_3point(&c, &good, &bad), FBRL_EDEGENERATE);
    set3(&bad, 1, 2, 3, 6, 2, 3, 6, 2, 3);
    assert_int_equal(fbrl_calib_3point(&c, &good, &bad), FBRL_EDEGENERATE);
    /* Exactly collinear, in a slanted line, P3 beyond P2 and between. */
    set3(&bad, 0, 0, 0, 1, 2, 3, 3, 6, 9);
    assert_int_equal(fbrl_calib_3point(&c, &bad, &good), FBRL_EDEGENERATE);
    set3(&bad, 0, 0, 0, 2, 4, 6, 1, 2, 3);
    assert_int_equal(fbrl_calib_3point(&c, &good, &bad), FBRL_EDEGENERATE);
    /* Nearly collinear: P3 0.004 in off a 10 in line (4e-4 of the spread) is refused;
     * 0.02 in off (2e-3) is accepted. P2 0.005 in from P1 across a 10 in spread too. */
    set3(&bad, 0, 0, 0, 10, 0, 0, 5, 0.004, 0);
    assert_int_equal(fbrl_calib_3point(&c, &bad, &good), FBRL_EDEGENERATE);
    set3(&bad, 0, 0, 0, 0.005, 0, 0, 0, 10, 0);
    assert_int_equal(fbrl_calib_3point(&c, &bad, &good), FBRL_EDEGENERATE);
    assert_memory_equal(&c, &before, sizeof c);
    set3(&bad, 0, 0, 0, 10, 0, 0, 5, 0.02, 0);
    assert_int_equal(fbrl_calib_3point(&c, &bad, &bad), FBRL_OK);

    /* N points: all on one line, or all on one spot. */
    fbrl_loc line[6], spot[4],
        ok[4] = {{0, 0, 0, 0, 0, 0}, {5, 0, 0, 0, 0, 0}, {0, 4, 0, 0, 0, 0}, {5, 4, 1, 0, 0, 0}};
    for (int i = 0; i < 6; i++) {
        fbrl_loc l = {1 + 2.0 * i, -1 - 1.0 * i, 0.5 * i, 0, 0, 0};
        line[i] = l;
    }
    for (int i = 0; i < 4; i++) {
        fbrl_loc l = {3, 3, 3, 0, 0, 0};
        spot[i] = l;
    }
    assert_int_equal(fbrl_calib_npoint(&c, line, line, 6, NULL, NULL, NULL), FBRL_EDEGENERATE);
    assert_int_equal(fbrl_calib_npoint(&c, spot, ok, 4, NULL, NULL, NULL), FBRL_EDEGENERATE);
    assert_int_equal(fbrl_calib_npoint(&c, ok, spot, 4, NULL, NULL, NULL), FBRL_EDEGENERATE);
    assert_memory_equal(&c, &before, sizeof c);
}

/* ---- N-point least squares ---- */

static void npoint_recovers_motion_and_names_the_bad_point(void **state)
{
    enum { N = 8 };
    fbrl_loc cal[N], recal[N];
    double res[N], rms;
    size_t worst;
    fbrl_calib c;
    (void)state;
    rng_state = 7;
    for (int trial = 0; trial < 500; trial++) {
        motion truth;
        random_rotation(truth.r);
        for (int i = 0; i < 3; i++)
            truth.t[i] = uniform(-15, 15);
        for (int i = 0; i < N; i++) {
            double p[3] = {uniform(-10, 10), uniform(-10, 10), uniform(-4, 4)}, m[3];
            apply(&truth, p, m);
            cal[i] = loc_at(p, 0, 0, 0);
            recal[i] = loc_at(m, 0, 0, 0);
        }
        assert_int_equal(fbrl_calib_npoint(&c, cal, recal, N, res, &rms, &worst), FBRL_OK);
        assert_true(matdiff(c.r, truth.r) < 1e-9);
        for (int i = 0; i < 3; i++)
            assert_near(c.t[i], truth.t[i], 1e-9);
        assert_true(rms < 1e-9);
        for (int i = 0; i < N; i++)
            assert_true(res[i] < 1e-9);

        /* One point taught 0.1 in off: it has the largest residual by far. */
        int bad = trial % N;
        double dir[3] = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
        double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
        recal[bad].x += 0.1 * dir[0] / len;
        recal[bad].y += 0.1 * dir[1] / len;
        recal[bad].z += 0.1 * dir[2] / len;
        assert_int_equal(fbrl_calib_npoint(&c, cal, recal, N, res, &rms, &worst), FBRL_OK);
        assert_int_equal(worst, bad);
        for (int i = 0; i < N; i++)
            if (i != bad)
                assert_true(res[i] < res[bad]);
        /* The fit absorbs part of the error (more for a point far from the centroid),
         * never more than all of it. */
        assert_true(res[bad] > 0.01 && res[bad] < 0.1 + 1e-9);
        assert_true(rms > 0.005 && rms < 0.1);
        double ss = 0;
        for (int i = 0; i < N; i++)
            ss += res[i] * res[i];
        assert_near(rms, sqrt(ss / N), 1e-15);
    }
    /* A mirror image is no rigid motion: the fit is still a proper rotation (det +1). */
    for (int i = 0; i < N; i++) {
        cal[i] = loc_at((double[3]){uniform(-10, 10), uniform(-10, 10), uniform(-4, 4)}, 0, 0, 0);
        recal[i] = cal[i];
        recal[i].z = -recal[i].z;
    }
    assert_int_equal(fbrl_calib_npoint(&c, cal, recal, N, NULL, &rms, NULL), FBRL_OK);
    double det = c.r[0][0] * (c.r[1][1] * c.r[2][2] - c.r[1][2] * c.r[2][1]) -
                 c.r[0][1] * (c.r[1][0] * c.r[2][2] - c.r[1][2] * c.r[2][0]) +
                 c.r[0][2] * (c.r[1][0] * c.r[2][1] - c.r[1][1] * c.r[2][0]);
    assert_near(det, 1.0, 1e-12);
    assert_true(rms > 0.1);
}

/* ---- save and load ---- */

static void save_and_load(void **state)
{
    unsigned char buf[FBRL_CALIB_BYTES + 4], copy[FBRL_CALIB_BYTES];
    fbrl_calib c, d;
    fbrl_calpts cal, recal;
    (void)state;
    set3(&cal, 0, 0, 0, 5, 0, 0, 0, 4, 0);
    set3(&recal, 10, 1, 0.5, 10, 6, 0.5, 6, 1, 0.5); /* turned 90 degrees, shifted */
    assert_int_equal(fbrl_calib_3point(&c, &cal, &recal), FBRL_OK);
    assert_int_equal(fbrl_calib_save(&c, buf, FBRL_CALIB_BYTES - 1), FBRL_ENOSPC);
    assert_int_equal(fbrl_calib_save(&c, buf, sizeof buf), FBRL_OK);
    /* The documented layout. */
    assert_memory_equal(buf, "FBCL", 4);
    assert_int_equal(buf[4], 1);
    assert_int_equal(buf[5], 0);
    assert_int_equal(buf[6], 0);
    assert_int_equal(buf[7], 0);
    uint64_t bits = 0;
    for (int i = 0; i < 8; i++)
        bits |= (uint64_t)buf[80 + i] << (8 * i);
    double t0;
    memcpy(&t0, &bits, 8);
    assert_true(t0 == c.t[0]);
    uint32_t crc =
        (uint32_t)buf[104] | (uint32_t)buf[105] << 8 | (uint32_t)buf[106] << 16 | (uint32_t)buf[107] << 24;
    assert_int_equal(crc, fbrl_crc32(0, buf, 104));
    /* Round trip is exact. */
    assert_int_equal(fbrl_calib_load(&d, buf, FBRL_CALIB_BYTES), FBRL_OK);
    assert_memory_equal(&c, &d, sizeof c);
    /* Every single-bit flip anywhere is refused and leaves the target alone. */
    memcpy(copy, buf, sizeof copy);
    fbrl_calib_identity(&d);
    fbrl_calib id = d;
    for (size_t i = 0; i < FBRL_CALIB_BYTES; i++)
        for (int b = 0; b < 8; b++) {
            copy[i] ^= (unsigned char)(1u << b);
            fbrl_status st = fbrl_calib_load(&d, copy, sizeof copy);
            assert_true(st == FBRL_ECHECKSUM || st == FBRL_EFORMAT || st == FBRL_EVERSION);
            copy[i] ^= (unsigned char)(1u << b);
        }
    assert_memory_equal(&d, &id, sizeof d);
    /* Short input, wrong magic, other version. */
    assert_int_equal(fbrl_calib_load(&d, buf, FBRL_CALIB_BYTES - 1), FBRL_ETRUNCATED);
    assert_int_equal(fbrl_calib_load(&d, buf, 0), FBRL_ETRUNCATED);
    memcpy(copy, buf, sizeof copy);
    copy[0] = 'X';
    assert_int_equal(fbrl_calib_load(&d, copy, sizeof copy), FBRL_EFORMAT);
    memcpy(copy, buf, sizeof copy);
    copy[4] = 2;
    assert_int_equal(fbrl_calib_load(&d, copy, sizeof copy), FBRL_EVERSION);
    /* A correct checksum over a matrix that is no rotation (scaled by 2). */
    memcpy(copy, buf, sizeof copy);
    { /* r[0][0] = 2.0, checksum recomputed */
        double two = 2.0;
        uint64_t v;
        memcpy(&v, &two, 8);
        for (int i = 0; i < 8; i++)
            copy[8 + i] = (unsigned char)(v >> (8 * i));
        uint32_t k = fbrl_crc32(0, copy, 104);
        for (int i = 0; i < 4; i++)
            copy[104 + i] = (unsigned char)(k >> (8 * i));
    }
    assert_int_equal(fbrl_calib_load(&d, copy, sizeof copy), FBRL_EFORMAT);
    assert_memory_equal(&d, &id, sizeof d);
    /* Random bodies under a valid header and a correct checksum: any bit pattern (NaN,
     * infinities, subnormals) is read safely and refused unless it is a rotation. */
    rng_state = 99;
    for (int trial = 0; trial < 10000; trial++) {
        memcpy(copy, buf, 8);
        for (int i = 8; i < 104; i++)
            copy[i] = (unsigned char)rng_next();
        uint32_t k = fbrl_crc32(0, copy, 104);
        for (int i = 0; i < 4; i++)
            copy[104 + i] = (unsigned char)(k >> (8 * i));
        assert_int_equal(fbrl_calib_load(&d, copy, sizeof copy), FBRL_EFORMAT);
    }
    assert_memory_equal(&d, &id, sizeof d);
    /* Saving something that is no rigid motion is refused. */
    d.r[1][1] = -1; /* a reflection */
    assert_int_equal(fbrl_calib_save(&d, buf, sizeof buf), FBRL_EINVAL);
}

/* ---- bad input ---- */

static void bad_input(void **state)
{
    fbrl_calpts pts;
    fbrl_calib c, nan_c;
    fbrl_loc l = {1, 2, 3, 4, 5, 6}, out, bad = l, pts4[4];
    double p[3] = {1, 2, 3}, a, b, cc;
    fbrl_rot r9;
    unsigned char bytes[FBRL_CALIB_BYTES];
    size_t w;
    (void)state;
    memset(&pts, 0, sizeof pts);
    fbrl_calib_identity(&c);
    nan_c = c;
    nan_c.t[1] = NAN;
    bad.y = INFINITY;
    assert_int_equal(fbrl_calpts_set(NULL, 1, &l), FBRL_EINVAL);
    assert_int_equal(fbrl_calpts_set(&pts, 1, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_calpts_set(&pts, 0, &l), FBRL_ERANGE);
    assert_int_equal(fbrl_calpts_set(&pts, 4, &l), FBRL_ERANGE);
    assert_int_equal(fbrl_calpts_set(&pts, 2, &bad), FBRL_ENONFINITE);
    assert_int_equal(fbrl_calpts_set(&pts, 3, &l), FBRL_OK);
    assert_int_equal(fbrl_calpts_get(&pts, 3, &out), FBRL_OK);
    assert_memory_equal(&out, &l, sizeof l);
    assert_int_equal(fbrl_calpts_get(&pts, -1, &out), FBRL_ERANGE);
    assert_int_equal(fbrl_calpts_get(NULL, 1, &out), FBRL_EINVAL);
    assert_int_equal(fbrl_calpts_get(&pts, 1, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_identity(NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_frame(NULL, &c), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_frame(&pts, NULL), FBRL_EINVAL);
    pts.p[0].z = NAN;
    assert_int_equal(fbrl_calib_frame(&pts, &c), FBRL_ENONFINITE);
    assert_int_equal(fbrl_calib_3point(&c, &pts, &pts), FBRL_ENONFINITE);
    assert_int_equal(fbrl_calib_3point(NULL, &pts, &pts), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_3point(&c, NULL, &pts), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_3point(&c, &pts, NULL), FBRL_EINVAL);
    set3(&pts, 0, 0, 0, 1e308, 0, 0, -1e308, 1e308, 0);
    assert_int_equal(fbrl_calib_frame(&pts, &c), FBRL_EOVERFLOW);
    fbrl_calib_identity(&c);
    for (int i = 0; i < 4; i++)
        pts4[i] = l;
    pts4[1].x = 5;
    pts4[2].y = 7;
    pts4[3].z = 9;
    assert_int_equal(fbrl_calib_npoint(&c, pts4, pts4, 2, NULL, NULL, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_npoint(&c, pts4, pts4, 0, NULL, NULL, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_npoint(NULL, pts4, pts4, 4, NULL, NULL, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_npoint(&c, NULL, pts4, 4, NULL, NULL, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_npoint(&c, pts4, NULL, 4, NULL, NULL, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_npoint(&c, pts4, pts4, 4, NULL, NULL, &w), FBRL_OK);
    pts4[2].x = NAN;
    assert_int_equal(fbrl_calib_npoint(&c, pts4, pts4, 4, NULL, NULL, NULL), FBRL_ENONFINITE);
    assert_int_equal(fbrl_calib_map(NULL, &l, &out), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_map(&c, NULL, &out), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_map(&c, &l, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_map(&nan_c, &l, &out), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_unmap(&nan_c, &l, &out), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_map(&c, &bad, &out), FBRL_ENONFINITE);
    assert_int_equal(fbrl_calib_unmap(&c, &bad, &out), FBRL_ENONFINITE);
    assert_int_equal(fbrl_calib_unmap(NULL, &l, &out), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_map_points(&c, NULL, p, 1), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_map_points(&c, p, NULL, 1), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_map_points(&nan_c, p, p, 1), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_map_points(&c, p, p, 0), FBRL_OK);
    double two[6] = {1, 2, 3, 4, NAN, 6}, before[6];
    memcpy(before, two, sizeof two);
    assert_int_equal(fbrl_calib_map_points(&c, two, two, 2), FBRL_ENONFINITE);
    c.t[0] = 1e308;
    double big[3] = {1e308, 0, 0};
    assert_int_equal(fbrl_calib_map_points(&c, big, big, 1), FBRL_EOVERFLOW);
    assert_true(big[0] == 1e308);
    assert_int_equal(fbrl_calib_invert(NULL, &c), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_invert(&c, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_invert(&nan_c, &c), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_orient_to_matrix(0, 0, 0, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_orient_to_matrix(NAN, 0, 0, &r9), FBRL_ENONFINITE);
    assert_int_equal(fbrl_calib_orient_to_matrix(0, 0, 0, &r9), FBRL_OK);
    assert_int_equal(fbrl_calib_matrix_to_orient(NULL, 0, &a, &b, &cc), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_matrix_to_orient(&r9, 0, NULL, &b, &cc), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_matrix_to_orient(&r9, INFINITY, &a, &b, &cc), FBRL_ENONFINITE);
    r9.m[1][1] = NAN;
    assert_int_equal(fbrl_calib_matrix_to_orient(&r9, 0, &a, &b, &cc), FBRL_ENONFINITE);
    assert_int_equal(fbrl_calib_save(NULL, bytes, sizeof bytes), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_save(&nan_c, bytes, sizeof bytes), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_load(NULL, bytes, sizeof bytes), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_load(&c, NULL, 200), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_ang_from_origin(0, 0, 1, 1, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_ang_from_origin(0, NAN, 1, 1, &a), FBRL_ENONFINITE);
    assert_int_equal(fbrl_calib_ang_from_origin(-1e308, 0, 1e308, 0, &a), FBRL_EOVERFLOW);
    assert_int_equal(fbrl_calib_rotate(1, 1, 1, NULL, &b), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_rotate(1, 1, 1, &a, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_calib_rotate(1, 1, INFINITY, &a, &b), FBRL_ENONFINITE);
    assert_int_equal(fbrl_calib_rotate(1.5e308, 1.5e308, FBRL_PI / 4, &a, &b), FBRL_EOVERFLOW);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(orientation_convention),
        cmocka_unit_test(ang_from_origin_and_rotate),
        cmocka_unit_test(three_point_hand_cases),
        cmocka_unit_test(random_rigid_motions),
        cmocka_unit_test(degenerate_sets_refused),
        cmocka_unit_test(npoint_recovers_motion_and_names_the_bad_point),
        cmocka_unit_test(save_and_load),
        cmocka_unit_test(bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
