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
 * The FBRL words (CELL-BOX ... CELL-SVG) are installed by fbrl_cell_install (src/words/
 * robot_cell.c); they guard every robot motion through fbrl_robot_set_guard. */
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

/* ---- the FBRL words (src/words/robot_cell.c) ---- */

#include "fbrl/vm.h"
#include "fbrl/robot.h"
#include "fbrl/glossary.h"

/* The words' state's sizes; a small build (the firmware, docs/firmware.md) sets smaller ones
 * for all its sources. */
#ifndef FBRL_CELL_MAX_OBJ
#define FBRL_CELL_MAX_OBJ 64 /* obstacles the words' cell holds */
#endif
#ifndef FBRL_CELL_PATH_MAX
#define FBRL_CELL_PATH_MAX 512 /* tool points of the path kept for the picture */
#endif
#ifndef FBRL_CELL_LOG_MAX
#define FBRL_CELL_LOG_MAX 16 /* refused motions kept for the report */
#endif
#define FBRL_CELL_MSG_MAX 192 /* a refusal's message, its end included */
/* What a refused motion throws (catchable): the code of FBRL_ERANGE. */
#define FBRL_CELL_THROW_COLLISION FBRL_ROBOT_THROW_REFUSED

/* A text sink (the SVG picture). */
typedef void (*fbrl_cell_write_fn)(void *ctx, const char *s, size_t n);
struct fbrl_cell_words;
/* Writes the picture of cw to the file path (the host's, for CELL-SVG: it opens the file and
 * calls fbrl_cell_svg with a writer into it); FBRL_OK or why not. */
typedef fbrl_status (*fbrl_cell_save_fn)(void *ctx, const char *path, struct fbrl_cell_words *cw);

/* What the guard saw since install or CELL-CLEAR, for a report. */
typedef struct fbrl_cell_stats {
    unsigned long moves;   /* motions checked and sent */
    unsigned long refused; /* motions refused */
    double clearance;      /* smallest clearance of any motion (INFINITY: none) */
    size_t near_obj;
    double near[3];
    char near_word[FBRL_CELL_NAME_MAX + 1];              /* the word whose motion came closest */
    char refusals[FBRL_CELL_LOG_MAX][FBRL_CELL_MSG_MAX]; /* their messages */
    unsigned nrefusals;
} fbrl_cell_stats;

/* The words' state: caller-owned, fields private but model, the cell the words describe
 * (fbrl_cell_set_arm(&cw->model, ...) chooses the arm the guard computes); keep it at a
 * fixed address. */
typedef struct fbrl_cell_words {
    fbrl_cell_model model;
    fbrl_cell_obj obj[FBRL_CELL_MAX_OBJ];
    char block_cal[FBRL_CELL_BLOCKS][FBRL_CELL_NAME_MAX + 1]; /* the CREATE-CAL-STRU of each block */
    fbrl_vm *vm;
    fbrl_robot *r;
    fbrl_glossary *g;
    int guard; /* CELL-GUARD-ON (the default) / CELL-GUARD-OFF */
    int block; /* CELL-BLOCK: the block later obstacles belong to, -1 none */
    int checked;                    /* the motion being sent was checked (done records it) */
    int pulses_ok;                  /* a W2 showed pulses = joints x pulses per degree (as of epoch):
                                     * one W1 line tells where the arm stands */
    unsigned long epoch;
    int expect;                      /* the last motion sent ends at pending (until the next check) */
    double q[FBRL_CELL_AXES];       /* where it starts: the joints read for its check */
    double pending[FBRL_CELL_AXES]; /* where it ends */
    fbrl_cell_hit last;
    fbrl_cell_stats stats;
    double path[FBRL_CELL_PATH_MAX][3];
    size_t npath;
    fbrl_cell_save_fn save;
    void *save_ctx;
} fbrl_cell_words;

/* Define the words in vm, guarding robot r's motions (fbrl_robot_set_guard); g (may be NULL)
 * gives the calibrations that carry blocks and the named locations a new obstacle must not
 * hold. FBRL_EINVAL for NULLs, FBRL_ENOMEM when the dictionary is full. */
FBRL_API fbrl_status fbrl_cell_install(fbrl_vm *vm, fbrl_cell_words *cw, fbrl_robot *r, fbrl_glossary *g);
/* Where CELL-SVG saves its picture (NULL: it throws "no file output"). */
FBRL_API void fbrl_cell_set_save(fbrl_cell_words *cw, fbrl_cell_save_fn fn, void *ctx);
/* The guard's record. */
FBRL_API const fbrl_cell_stats *fbrl_cell_stats_get(const fbrl_cell_words *cw);
/* The SVG picture (top and side views to scale, obstacles, the named locations, the tool
 * path, the closest approach) written through fn. */
FBRL_API fbrl_status fbrl_cell_svg(fbrl_cell_words *cw, fbrl_cell_write_fn fn, void *ctx);

#ifdef __cplusplus
}
#endif
#endif
