/* SPDX-License-Identifier: MIT */
/* bench_cell.c - the motion guard's cost per move (docs/workcell.md; the bound is 50 us): the
 * whole arm (upper arm, forearm, tool) in the ASPS cell of examples/asps_cell_objects.fbrl
 * (table, 7 obstacles, one of them on a moved block), and the moves of the sample plan's
 * kind: joint moves between stations, straight approaches and departs next to the blocks,
 * and a worst case that skims 0.1 in over the heating block the whole way (the smallest
 * steps); the A255's moves, then the A465's. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fbrl/cell.h"
#include "bench_util.h"

#define BOUND_US 50.0

static fbrl_cell_obj store[16];
static fbrl_cell_model cell;

static void add(const char *name, int kind, int block, double x0, double y0, double z0, double x1, double y1,
                double z1)
{
    fbrl_cell_obj o;
    memset(&o, 0, sizeof o);
    snprintf(o.name, sizeof o.name, "%s", name);
    o.kind = kind;
    o.block = block;
    o.lo[0] = x0, o.lo[1] = y0, o.lo[2] = z0, o.hi[0] = x1, o.hi[1] = y1, o.hi[2] = z1;
    if (kind == FBRL_CELL_CYLINDER)
        o.c[0] = x0, o.c[1] = y0, o.r = x1, o.hi[2] = z1;
    if (fbrl_cell_add(&cell, &o) != FBRL_OK) {
        fprintf(stderr, "%s refused\n", name);
        exit(1);
    }
}

typedef struct move {
    const char *arm, *what;
    double a[6], b[6];
    int straight;
} move;

int main(void)
{
    static const move moves[] = {
        {"a255", "joint: syringe stand -> tube A1", {7, 6, 7, 0, -90, 0}, {10, -2, 3.5, 0, -90, 0}, 0},
        {"a255", "joint: tube A1 -> vial 1", {10, -2, 3.5, 0, -90, 0}, {7, 8.5, 5, 0, -90, 0}, 0},
        {"a255", "joint: dispenser rest -> separator", {6, -8, 7, 0, -90, 0}, {15, 5, 6, 0, -90, 0}, 0},
        {"a255", "joint: READY -> rinse rest", {12, 0, 20, 0, 0, 0}, {14, -6, 7, 0, -90, 0}, 0},
        {"a255", "straight: approach into tube A1 (2 in)", {10, -2, 5, 0, -90, 0}, {10, -2, 3, 0, -90, 0}, 1},
        {"a255", "straight: depart from the separator", {15, 5, 4, 0, -90, 0}, {15, 5, 6, 0, -90, 0}, 1},
        {"a255",
         "straight: skim 0.1 in over the block",
         {9.2, -2.8, 2.05, 0, -90, 0},
         {13.8, 2.8, 2.05, 0, -90, 0},
         1},
        {"a255", "joint: skim over the block", {9.2, -2.8, 2.06, 0, -90, 0}, {13.8, 2.8, 2.06, 0, -90, 0}, 0},
        /* the A465 reaches the far side of the cell (its elbow stops at 110 degrees) */
        {"a465", "joint: over the separator -> over rinse", {16, 4, 6, 0, -90, 0}, {16, -4, 6, 0, -90, 0}, 0},
        {"a465", "joint: READY -> over the block", {15.98, 0, 25, 0, 0, 0}, {13.8, 0, 4, 0, -90, 0}, 0},
        {"a465",
         "straight: approach the block (1.5 in)",
         {13.8, 0, 4, 0, -90, 0},
         {13.8, 0, 2.5, 0, -90, 0},
         1},
        {"a465",
         "straight: skim 0.1 in over the block",
         {13.8, -2.8, 2.05, 0, -90, 0},
         {13.8, 2.8, 2.05, 0, -90, 0},
         1},
    };
    const size_t nm = sizeof moves / sizeof moves[0];
    double worst = 0.0, total = 0.0;
    int blk;
    fbrl_calib m;

    fbrl_cell_init(&cell, store, 16);
    fbrl_cell_set_table(&cell, 0.0);
    fbrl_cell_set_tool(&cell, 0.0, 0.2);
    fbrl_cell_block(&cell, "HEATING-BLOCK", 13, &blk);
    add("HEATING-BLOCK-BODY", FBRL_CELL_BOX, blk, 9, -3, 0, 14, 3, 1.75);
    add("SYRINGE-STAND", FBRL_CELL_BOX, -1, 6.5, 5.5, 0, 10.5, 6.5, 3);
    add("VIAL-RACK", FBRL_CELL_BOX, -1, 6.5, 8, 0, 10.5, 9, 3);
    add("DISPENSER-STAND", FBRL_CELL_BOX, -1, 5.5, -8.5, 0, 14, -7.5, 3);
    add("SEPARATION-UNIT", FBRL_CELL_CYLINDER, -1, 15, 5, 0, 1, 0, 3);
    add("RINSE-STAND", FBRL_CELL_BOX, -1, 13.5, -6.5, 0, 14.5, -5.5, 3);
    add("OPERATOR-SIDE", FBRL_CELL_KEEPOUT, -1, -24, -24, 0, -6, 24, 30);
    fbrl_calib_identity(&m);
    m.t[0] = 0.05, m.t[1] = -0.1; /* the block put back a little off */
    fbrl_cell_set_block(&cell, blk, &m);

    printf("%-47s %9s %8s %6s %s\n", "move (ASPS cell, 7 obstacles + table)", "us/move", "samples", "hit",
           "ratio to 50 us");
    for (size_t k = 0; k < nm; k++) {
        const move *mv = &moves[k];
        double q0[FBRL_ARM_AXES_MAX], q1[FBRL_ARM_AXES_MAX], t0, secs, us;
        fbrl_cell_hit h;
        long reps = 0;
        fbrl_cell_set_arm(&cell, fbrl_arm_find(mv->arm), 0.0);
        if (fbrl_arm_ik(cell.arm, mv->a, 0.0, cell.arm->ready, q0, NULL) != FBRL_OK ||
            fbrl_arm_ik(cell.arm, mv->b, 0.0, q0, q1, NULL) != FBRL_OK) {
            fprintf(stderr, "%s: out of reach\n", mv->what);
            return 1;
        }
        t0 = bench_now();
        do {
            for (int i = 0; i < 100; i++) {
                if (mv->straight)
                    fbrl_cell_check_line(&cell, q0, mv->b, &h);
                else
                    fbrl_cell_check_joints(&cell, q0, q1, &h);
            }
            reps += 100;
            secs = bench_now() - t0;
        } while (secs < 0.2);
        us = secs / (double)reps * 1e6;
        total += us;
        if (us > worst)
            worst = us;
        printf("%s %-42s %9.2f %8u %6s %.3f\n", cell.arm->name, mv->what, us, h.samples, h.hit ? "yes" : "no",
               us / BOUND_US);
    }
    printf("mean %.2f us, worst %.2f us per move (bound %.0f us: worst is %.1f%% of it)\n",
           total / (double)nm, worst, BOUND_US, 100.0 * worst / BOUND_US);
    return 0;
}
