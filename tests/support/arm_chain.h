/* SPDX-License-Identifier: MIT */
/* arm_chain.h - an arm of fbrl/arm.h's table built independently of src/arm.c, for the
 * tests: the physical chain of rotations and links its published geometry describes (A255:
 * DESIGN 6; A465: the DH lengths d1 330, a2 305, d4 330, d6 76 mm), frame by frame. Static
 * inline, like vm_host.h. */
#ifndef FBRL_TEST_ARM_CHAIN_H
#define FBRL_TEST_ARM_CHAIN_H

#include <math.h>
#include <string.h>

#include "fbrl/arm.h"

typedef struct ac_frame {
    double r[3][3], p[3]; /* the axes (columns) and the origin */
} ac_frame;

static inline void ac_ident(ac_frame *f)
{
    memset(f, 0, sizeof *f);
    f->r[0][0] = f->r[1][1] = f->r[2][2] = 1.0;
}

/* f = f * (rotation about its own axis by deg) */
static inline void ac_rot(ac_frame *f, int axis, double deg)
{
    double c = cos(deg * M_PI / 180.0), s = sin(deg * M_PI / 180.0), m[3][3] = {{0}}, o[3][3];
    int a = (axis + 1) % 3, b = (axis + 2) % 3;
    m[axis][axis] = 1.0;
    m[a][a] = c, m[a][b] = -s, m[b][a] = s, m[b][b] = c;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            o[i][j] = 0;
            for (int k = 0; k < 3; k++)
                o[i][j] += f->r[i][k] * m[k][j];
        }
    memcpy(f->r, o, sizeof o);
}

/* f = f * (translation along its own axis) */
static inline void ac_move(ac_frame *f, int axis, double d)
{
    for (int i = 0; i < 3; i++)
        f->p[i] += f->r[i][axis] * d;
}

/* The arm at joints q: joint[] the shoulder, the elbow, the wrist centre and the tool point
 * tool inches past the flange; *tool the tool's frame there, whose axis *tool_axis (0 or 2)
 * is the tool axis (the other of 0 and 2 turns with the roll). */
static inline void ac_chain(const fbrl_arm *m, const double *q, double tool, double joint[4][3], ac_frame *tf,
                            int *tool_axis)
{
    ac_frame f;
    ac_ident(&f);
    ac_rot(&f, 2, q[0]);
    ac_move(&f, 2, m->base_h);
    memcpy(joint[0], f.p, sizeof f.p);
    if (m->form == FBRL_ARM_5R) {
        /* links along local x; shoulder, elbow, wrist pitch raise it; roll about it */
        ac_rot(&f, 1, -q[1]);
        ac_move(&f, 0, m->upper);
        memcpy(joint[1], f.p, sizeof f.p);
        ac_rot(&f, 1, -q[2]);
        ac_move(&f, 0, m->fore);
        memcpy(joint[2], f.p, sizeof f.p);
        ac_rot(&f, 1, -q[3]);
        ac_move(&f, 0, m->flange + tool);
        ac_rot(&f, 0, q[4]);
        *tool_axis = 0;
    } else {
        /* links along local z (upright at zero); shoulder and elbow lean forward; forearm
         * roll, wrist bend, tool roll */
        ac_rot(&f, 1, q[1]);
        ac_move(&f, 2, m->upper);
        memcpy(joint[1], f.p, sizeof f.p);
        ac_rot(&f, 1, q[2]);
        ac_move(&f, 2, m->fore);
        memcpy(joint[2], f.p, sizeof f.p);
        ac_rot(&f, 2, q[3]);
        ac_rot(&f, 1, q[4]);
        ac_move(&f, 2, m->flange + tool);
        ac_rot(&f, 2, q[5]);
        *tool_axis = 2;
    }
    memcpy(joint[3], f.p, sizeof f.p);
    if (tf)
        *tf = f;
}

#endif
