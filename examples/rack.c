/* SPDX-License-Identifier: MIT */
/* rack.c - a 4 x 6 tube rack: locations from a rectangular matrix, a calibration taught on
 * the rack where it was first set up, a recalibration after it was moved, and the rack's
 * locations in both frames.  Usage: rack [--metric] */
#include <stdio.h>
#include <string.h>
#include "fbrl/loc.h"
#include "fbrl/units.h"
#include "fbrl/matrix.h"
#include "fbrl/calib.h"

#define ROWS 4
#define COLS 6

static int check(fbrl_status st, const char *what)
{
    if (st != FBRL_OK) {
        fprintf(stderr, "rack: %s: %s\n", what, fbrl_status_str(st));
        return 1;
    }
    return 0;
}

/* The move we pretend happened (in real use it is unknown: the arm is guided to the three
 * calibration points on the moved rack and they are taught again). */
static fbrl_status move_rack(const fbrl_loc *in, fbrl_loc *out)
{
    fbrl_calib moved;
    fbrl_rot turn;
    fbrl_status st = fbrl_calib_orient_to_matrix(12.0, 0.0, 0.0, &turn); /* 12 deg about z */
    if (st != FBRL_OK)
        return st;
    memcpy(moved.r, turn.m, sizeof moved.r);
    moved.t[0] = 1.50; /* then shifted 1.5 in along x, -0.75 in along y, 0.25 in up */
    moved.t[1] = -0.75;
    moved.t[2] = 0.25;
    return fbrl_calib_map(&moved, in, out);
}

int main(int argc, char **argv)
{
    fbrl_units units = FBRL_UNITS_INIT;
    fbrl_loc a1, tube, moved, back, taught;
    fbrl_rectmat rack;
    fbrl_calpts cal, recal;
    fbrl_calib c, reloaded;
    unsigned char saved[FBRL_CALIB_BYTES];
    char text[FBRL_LOC_TEXT_SIZE];
    const char *unit = "in";
    double worst_back = 0.0;
    int metric = argc > 1 && strcmp(argv[1], "--metric") == 0;
    long row, col;
    int i;

    if (argc > 1 && !metric) {
        fprintf(stderr, "usage: %s [--metric]\n", argv[0]);
        return 2;
    }
    if (metric) {
        fbrl_units_metric_on(&units);
        unit = "cm";
    }

    /* Tube A1 taught at (12, -3, 2) in with the gripper straight down; tubes 0.75 in
     * apart along x (columns 1..6) and 0.75 in apart along y (rows A..D). */
    if (check(fbrl_loc_define(&a1, 12.0, -3.0, 2.0, 0.0, -90.0, 0.0), "define A1") ||
        check(fbrl_rectmat_init(&rack, &a1, 0.75, 0.75, 0.0), "RECTMAT"))
        return 1;

    /* Calibration points on the rack's base plate: P1 a corner, P2 along the long edge,
     * P3 along the short edge. */
    {
        fbrl_loc p1 = {11.5, -3.5, 1.0, 0, -90, 0}, p2 = {16.25, -3.5, 1.0, 0, -90, 0},
                 p3 = {11.5, -0.25, 1.0, 0, -90, 0};
        if (check(fbrl_calpts_set(&cal, 1, &p1), "SET-CAL 1") ||
            check(fbrl_calpts_set(&cal, 2, &p2), "SET-CAL 2") ||
            check(fbrl_calpts_set(&cal, 3, &p3), "SET-CAL 3"))
            return 1;
    }
    /* The rack is moved; the same three points are taught again where they now are. */
    for (i = 1; i <= 3; i++)
        if (check(move_rack(&cal.p[i - 1], &taught), "move") ||
            check(fbrl_calpts_set(&recal, i, &taught), "SET-CAL (moved)"))
            return 1;
    if (check(fbrl_calib_3point(&c, &cal, &recal), "CALIBRATE"))
        return 1;

    /* The calibration survives a save and load (fileio stores these bytes). */
    if (check(fbrl_calib_save(&c, saved, sizeof saved), "save") ||
        check(fbrl_calib_load(&reloaded, saved, sizeof saved), "load"))
        return 1;

    printf("libfbrl rack example: %d x %d tube rack, RECTMAT spacing 0.75 in x 0.75 in\n", ROWS, COLS);
    printf("units: %s (lengths), degrees (angles)\n\n", metric ? "centimetres" : "inches");
    printf("calibration points     original block                     moved block\n");
    for (i = 0; i < 3; i++) {
        fbrl_loc o, m;
        fbrl_units_loc_out(&units, &cal.p[i], &o);
        fbrl_units_loc_out(&units, &recal.p[i], &m);
        printf("  P%d            (%8.4f, %8.4f, %8.4f) %s   (%8.4f, %8.4f, %8.4f) %s\n", i + 1, o.x, o.y, o.z,
               unit, m.x, m.y, m.z, unit);
    }
    printf("saved calibration: %d bytes, reloaded %s\n\n", FBRL_CALIB_BYTES,
           memcmp(&c, &reloaded, sizeof c) == 0 ? "identical" : "DIFFERENT");

    printf("%-4s  %9s %9s %9s  |  %9s %9s %9s %8s\n", "tube", "orig x", "y", "z", "moved x", "y", "z", "yaw");
    printf("----  -----------------------------  |  --------------------------------------\n");
    for (row = 0; row < ROWS; row++)
        for (col = 0; col < COLS; col++) {
            fbrl_loc o, m;
            double d;
            /* Columns run along x (i), rows along y (j). */
            if (check(fbrl_rectmat_loc(&rack, col, row, 0, &tube), "rack location") ||
                check(fbrl_calib_map(&reloaded, &tube, &moved), "MAP") ||
                check(fbrl_calib_unmap(&reloaded, &moved, &back), "UNMAP") ||
                check(fbrl_loc_distance(&tube, &back, &d), "distance"))
                return 1;
            if (d > worst_back)
                worst_back = d;
            fbrl_units_loc_out(&units, &tube, &o);
            fbrl_units_loc_out(&units, &moved, &m);
            printf("%c%-3ld  %9.4f %9.4f %9.4f  |  %9.4f %9.4f %9.4f %8.3f\n", (char)('A' + row), col + 1,
                   o.x, o.y, o.z, m.x, m.y, m.z, m.o);
        }

    /* One tube in full, the way DISPLAY-LOC shows it. */
    if (check(fbrl_rectmat_loc(&rack, 5, 3, 0, &tube), "rack location") ||
        check(fbrl_calib_map(&reloaded, &tube, &moved), "MAP"))
        return 1;
    printf("\nD6 original: ");
    if (check(fbrl_loc_format(&tube, metric, text, sizeof text), "format"))
        return 1;
    printf("%s\nD6 moved:    ", text);
    if (check(fbrl_loc_format(&moved, metric, text, sizeof text), "format"))
        return 1;
    printf("%s\n", text);
    {
        fbrl_loc truth;
        double err;
        if (check(move_rack(&tube, &truth), "move") ||
            check(fbrl_loc_distance(&truth, &moved, &err), "distance"))
            return 1;
        printf("\ncheck: D6 mapped vs the true move: %.2e in; map then unmap over all %d tubes: "
               "worst %.2e in\n",
               err, ROWS * COLS, worst_back);
    }
    return 0;
}
