/* SPDX-License-Identifier: MIT */
/* cell.h - the work cell: the table plane, boxes, cylinders and keep-out zones, the tool
 * envelope, and the check of the whole arm's path against them (docs/workcell.md).
 *
 * Geometry only: no OS, no allocation (the caller gives the obstacle storage). Lengths
 * are inches, angles degrees, in the arm's frame (x forward, y left, z up from the base
 * axis at the table). An obstacle may belong to a block: it is described where the block
 * stood when it was taught and carried along by the block's calibration
 * (fbrl_cell_set_block), as MAP-ON carries the block's locations.
 *
 * The arm is a row of the arm model table (fbrl/arm.h: the A255 unless fbrl_cell_set_arm
 * chooses another), of either kinematic form; the guard computes its path as the controller
 * does. The whole arm is checked, as three capsules (fbrl_arm_body): the upper arm and the
 * forearm with the wrist housing, of the arm's own radii, and the tool envelope of radius
 * tool_r from the wrist centre through the tool point (the pose the controller moves to) and
 * tool_len beyond it along the tool axis.
 *
 * Path checks sample the motion adaptively: each step moves no point of the arm further than
 * the clearance just measured (nothing can be met in between), and never further than
 * 0.9 * FBRL_CELL_THIN close to an obstacle, so no obstacle at least FBRL_CELL_THIN thick is
 * skipped (and a hit is found at most that far past the first contact).
 *
 * The FBRL words (CELL-BOX ... CELL-SVG) that describe a cell and guard every robot motion
 * with it are a word set of their own: fbrl/cell_words.h. */
#ifndef FBRL_CELL_H
#define FBRL_CELL_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"
#include "fbrl/arm.h"
#include "fbrl/calib.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FBRL_CELL_NAME_MAX 31                /* obstacle and block names */
#define FBRL_CELL_THIN     0.1               /* in: the thinnest obstacle a path check cannot skip */
#ifndef FBRL_CELL_BLOCKS
#define FBRL_CELL_BLOCKS 8 /* blocks whose calibration carries obstacles (a small build sets fewer) */
#endif
#define FBRL_CELL_AXES     FBRL_ARM_AXES_MAX /* joints in a hit's q_end and the words' state */
#define FBRL_CELL_TABLE    ((size_t)-1)      /* "obstacle" index of the table plane */
#define FBRL_CELL_NONE     ((size_t)-2)      /* no obstacle at all */

/* Obstacles the path check tracks between samples (more are measured at every sample), and
 * the number the CELL words' cell holds (fbrl/cell_words.h); a small build (the firmware,
 * docs/firmware.md) sets a smaller one for all its sources. */
#ifndef FBRL_CELL_MAX_OBJ
#define FBRL_CELL_MAX_OBJ 64
#endif

typedef enum fbrl_cell_kind {
    FBRL_CELL_BOX = 1,      /* a solid box: block, rack, instrument */
    FBRL_CELL_CYLINDER = 2, /* a solid upright cylinder */
    FBRL_CELL_KEEPOUT = 3   /* a box of space the tool must not enter (nothing solid there) */
} fbrl_cell_kind;

/* One obstacle. Box / keep-out: lo < hi, opposite corners. Cylinder: axis vertical through
 * (c[0], c[1]) from z lo[2] to hi[2], radius r (lo/hi x y are ignored). */
typedef struct fbrl_cell_obj {
    char name[FBRL_CELL_NAME_MAX + 1];
    int kind;  /* fbrl_cell_kind */
    int block; /* the block that carries it (0..), -1: fixed in the cell */
    double lo[3], hi[3];
    double c[2], r;
} fbrl_cell_obj;

/* Caller-owned; fields private (use the functions). */
typedef struct fbrl_cell_model {
    uint32_t magic;
    fbrl_cell_obj *obj;
    size_t n, cap;
    char block_name[FBRL_CELL_BLOCKS][FBRL_CELL_NAME_MAX + 1];
    fbrl_calib block[FBRL_CELL_BLOCKS]; /* where each block is now (identity: as taught) */
    size_t nblocks;
    int have_table;
    double table_z;
    double tool_len, tool_r;
    const fbrl_arm *arm; /* a row of the model table (or the caller's, kept while in use) */
    double tcp;          /* the controller's tool point past the flange (its TOOL), in */
} fbrl_cell_model;

/* What a check found. Points are in the arm's frame. */
typedef struct fbrl_cell_hit {
    int hit;                      /* 1: the arm meets obstacle `obj` */
    size_t obj;                   /* index, FBRL_CELL_TABLE, or FBRL_CELL_NONE */
    double at[3];                 /* the point of contact: on the obstacle's surface nearest the envelope */
    double fraction;              /* how far along the move (0 start .. 1 end) */
    double clearance;             /* smallest clearance along the path (negative: inside), in */
    size_t near_obj;              /* the obstacle of that smallest clearance */
    int part;                     /* the arm's part there (fbrl_arm_part), which met obj on a hit */
    double near[3];               /* the point of the obstacle where it was smallest */
    double q_end[FBRL_CELL_AXES]; /* the joints at the end of the move (or of the check) */
    unsigned samples;             /* poses checked */
} fbrl_cell_hit;

/* An empty cell (no table, no tool envelope radius, the A255) keeping its obstacles in
 * storage[0..cap). FBRL_EINVAL for NULLs. */
FBRL_API fbrl_status fbrl_cell_init(fbrl_cell_model *c, fbrl_cell_obj *storage, size_t cap);
/* Forget every obstacle, block and the table (the tool and arm stay). */
FBRL_API fbrl_status fbrl_cell_clear(fbrl_cell_model *c);
/* The table top at height z (FBRL_ENONFINITE). */
FBRL_API fbrl_status fbrl_cell_set_table(fbrl_cell_model *c, double z);
/* The tool envelope (FBRL_ERANGE for a negative length or radius). */
FBRL_API fbrl_status fbrl_cell_set_tool(fbrl_cell_model *c, double len, double radius);
/* The arm (a row of fbrl/arm.h's table, or one the caller keeps while the cell uses it) and
 * where the controller's tool point is, tcp inches past the flange along the tool axis (its
 * TOOL; 0 when the controller has none): poses are of that point. FBRL_ERANGE for a length
 * not positive, more than FBRL_CELL_AXES joints or tcp negative; FBRL_ENONFINITE. */
FBRL_API fbrl_status fbrl_cell_set_arm(fbrl_cell_model *c, const fbrl_arm *arm, double tcp);

/* The block named name[0..len): its index, made (identity placement) if new. FBRL_ENAME for
 * an empty or too long name, FBRL_EFULL beyond FBRL_CELL_BLOCKS. */
FBRL_API fbrl_status fbrl_cell_block(fbrl_cell_model *c, const char *name, size_t len, int *index);
/* Where block index stands now: the rigid motion from where it was taught (a calibration). */
FBRL_API fbrl_status fbrl_cell_set_block(fbrl_cell_model *c, int index, const fbrl_calib *m);

/* Add an obstacle (copied). FBRL_ENAME: empty, too long, or the name of an obstacle
 * already in the cell; FBRL_ERANGE: a size not positive (hi <= lo, r <= 0) or an unknown
 * kind or block; FBRL_ENONFINITE; FBRL_EFULL when the storage is full. */
FBRL_API fbrl_status fbrl_cell_add(fbrl_cell_model *c, const fbrl_cell_obj *o);
/* The obstacle of that name (case-insensitive): FBRL_OK and *index, or FBRL_ENOENT. */
FBRL_API fbrl_status fbrl_cell_find(const fbrl_cell_model *c, const char *name, size_t len, size_t *index);
/* Obstacle i (NULL past the end), as described (where its block was taught). */
FBRL_API const fbrl_cell_obj *fbrl_cell_get(const fbrl_cell_model *c, size_t i);
/* The name of obstacle index i, "the table" or "nothing". */
FBRL_API const char *fbrl_cell_obj_name(const fbrl_cell_model *c, size_t i);

/* Clearance of a point (no envelope) to the obstacles of block `block` (-2: all, -1: the
 * fixed ones) as they were taught, the table not counted: *d negative inside. */
FBRL_API fbrl_status fbrl_cell_point_clearance(const fbrl_cell_model *c, const double p[3], int block,
                                               double *d, size_t *obj);

/* Checks: the arm at joints q; along the joint-interpolated path q0 -> q1; along the
 * straight line from the arm at q0 to pose1 (position and angles interpolated, as the
 * controller moves: fbrl_arm_lerp). Joint arrays hold the arm's naxes values. h gets what
 * was found (h->hit). FBRL_ERANGE: a straight line the arm cannot follow (a sample out of
 * reach or past a limit), h up to there. */
FBRL_API fbrl_status fbrl_cell_check_pose(const fbrl_cell_model *c, const double *q, fbrl_cell_hit *h);
FBRL_API fbrl_status fbrl_cell_check_joints(const fbrl_cell_model *c, const double *q0, const double *q1,
                                            fbrl_cell_hit *h);
FBRL_API fbrl_status fbrl_cell_check_line(const fbrl_cell_model *c, const double *q0, const double pose1[6],
                                          fbrl_cell_hit *h);

#ifdef __cplusplus
}
#endif
#endif
