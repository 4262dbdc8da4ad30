/* SPDX-License-Identifier: MIT */
/* bench_calib.c - calibration mapping throughput (points per second).
 * Position map: fbrl_calib_map_points over a block of points that stays in cache, the
 * 3x4 motion held in registers (target >= 50 M points/s). Full map: fbrl_calib_map of
 * whole locations, orientation included. Unmap and the calibration solves for scale. */
#include <stdio.h>
#include <string.h>
#include <time.h>
#include "fbrl/calib.h"
#include "bench_util.h"

#define NPTS 4096

static void report(const char *what, double count, double secs)
{
    printf("%-44s %10.2f M/s  (%.0f in %.3f s)\n", what, count / secs / 1e6, count, secs);
}

int main(void)
{
    static double in[3 * NPTS], out[3 * NPTS];
    static fbrl_loc locs[NPTS], mapped[NPTS];
    fbrl_calpts cal, recal;
    fbrl_calib c;
    double t0, secs, sink = 0.0;
    long reps, r;
    size_t i;
    fbrl_loc c1 = {10, 2, 0.5, 0, -90, 0}, c2 = {16, 2, 0.5, 0, -90, 0}, c3 = {10, 7, 0.5, 0, -90, 0};

    /* A moved block: turned 30 degrees about z, tilted slightly about x. */
    {
        fbrl_calib truth;
        fbrl_rot turn;
        double p[3];
        fbrl_calib_orient_to_matrix(30, 0, 2, &turn);
        memcpy(truth.r, turn.m, sizeof truth.r);
        truth.t[0] = 1;
        truth.t[1] = -0.5;
        truth.t[2] = 0.2;
        cal.p[0] = c1;
        cal.p[1] = c2;
        cal.p[2] = c3;
        for (i = 0; i < 3; i++) {
            p[0] = cal.p[i].x;
            p[1] = cal.p[i].y;
            p[2] = cal.p[i].z;
            fbrl_calib_map_points(&truth, p, p, 1);
            recal.p[i] = cal.p[i];
            recal.p[i].x = p[0];
            recal.p[i].y = p[1];
            recal.p[i].z = p[2];
        }
    }
    if (fbrl_calib_3point(&c, &cal, &recal) != FBRL_OK) {
        fprintf(stderr, "calibration failed\n");
        return 1;
    }
    for (i = 0; i < NPTS; i++) {
        in[3 * i] = 10.0 + (double)(i % 64) * 0.25;
        in[3 * i + 1] = 2.0 + (double)(i / 64) * 0.25;
        in[3 * i + 2] = 0.5 + (double)(i % 7) * 0.1;
        fbrl_loc l = {in[3 * i],
                      in[3 * i + 1],
                      in[3 * i + 2],
                      (double)(i % 360) - 180.0,
                      -90.0 + (double)(i % 91),
                      (double)(i % 180)};
        locs[i] = l;
    }

    printf("bench_calib: %d points per pass\n", NPTS);
    reps = 20000;
    t0 = bench_now();
    for (r = 0; r < reps; r++) {
        fbrl_calib_map_points(&c, in, out, NPTS);
        sink += out[r % (3 * NPTS)];
    }
    secs = bench_now() - t0;
    report("position map (map_points, 3x4, out of place)", (double)reps * NPTS, secs);

    t0 = bench_now();
    for (r = 0; r < reps; r++) {
        fbrl_calib_map_points(&c, out, out, NPTS); /* in place */
        sink += out[r % (3 * NPTS)];
    }
    secs = bench_now() - t0;
    report("position map (map_points, in place)", (double)reps * NPTS, secs);

    reps = 5000;
    t0 = bench_now();
    for (r = 0; r < reps; r++)
        for (i = 0; i < NPTS; i++) {
            fbrl_calib_map_points(&c, &in[3 * i], &out[3 * i], 1);
        }
    sink += out[7];
    secs = bench_now() - t0;
    report("position map (one call per point)", (double)reps * NPTS, secs);

    reps = 300;
    t0 = bench_now();
    for (r = 0; r < reps; r++)
        for (i = 0; i < NPTS; i++)
            fbrl_calib_map(&c, &locs[i], &mapped[i]);
    secs = bench_now() - t0;
    sink += mapped[5].o;
    report("full location map (position + orientation)", (double)reps * NPTS, secs);

    t0 = bench_now();
    for (r = 0; r < reps; r++)
        for (i = 0; i < NPTS; i++)
            fbrl_calib_unmap(&c, &mapped[i], &locs[i]);
    secs = bench_now() - t0;
    sink += locs[5].o;
    report("full location unmap", (double)reps * NPTS, secs);

    reps = 1000000;
    t0 = bench_now();
    for (r = 0; r < reps; r++) {
        cal.p[0].x = 10.0 + (double)(r & 1) * 1e-6;
        fbrl_calib_3point(&c, &cal, &recal);
    }
    secs = bench_now() - t0;
    sink += c.t[0];
    report("3-point calibrations", (double)reps, secs);

    {
        fbrl_loc a[8], b[8];
        double res[8], rms;
        size_t worst;
        for (i = 0; i < 8; i++) {
            fbrl_loc l = {10.0 + (double)(i & 1) * 6,
                          2.0 + (double)((i >> 1) & 1) * 5,
                          0.5 + (double)(i >> 2) * 2,
                          0,
                          0,
                          0};
            a[i] = l;
            fbrl_calib_map(&c, &a[i], &b[i]);
        }
        reps = 200000;
        t0 = bench_now();
        for (r = 0; r < reps; r++) {
            b[0].x += 1e-9;
            fbrl_calib_npoint(&c, a, b, 8, res, &rms, &worst);
        }
        secs = bench_now() - t0;
        sink += rms;
        report("8-point least-squares calibrations", (double)reps, secs);
    }
    printf("(checksum %g)\n", sink);
    return 0;
}
