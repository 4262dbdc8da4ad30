/* SPDX-License-Identifier: MIT */
/* cell_words.h - the CELL word set (src/words/robot_cell.c): CELL-BOX ... CELL-SVG describe
 * the work cell (fbrl/cell.h's model) in FBRL, and the guard they install checks every robot
 * motion against it before a byte is sent (fbrl_robot_set_guard). docs/workcell.md tells
 * the words. */
#ifndef FBRL_CELL_WORDS_H
#define FBRL_CELL_WORDS_H

#include "fbrl/export.h"

#include <stddef.h>
#include "fbrl/status.h"
#include "fbrl/cell.h"
#include "fbrl/vm.h"
#include "fbrl/robot.h"
#include "fbrl/glossary.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The words' state's sizes (and FBRL_CELL_MAX_OBJ, fbrl/cell.h); a small build (the firmware, docs/firmware.md) sets smaller ones
 * for all its sources. */
#ifndef FBRL_CELL_PATH_MAX
#define FBRL_CELL_PATH_MAX 512 /* tool points of the path kept for the picture */
#endif
#ifndef FBRL_CELL_LOG_MAX
#define FBRL_CELL_LOG_MAX 16 /* refused motions kept for the report */
#endif
#ifndef FBRL_CELL_PICTURE
/* 0: no picture (the firmware): CELL-RACK checks its matrix and keeps nothing, no refused
 * motion is kept for drawing, fbrl_cell_svg is FBRL_EUNSUPPORTED */
#define FBRL_CELL_PICTURE 1
#endif
#ifndef FBRL_CELL_RACKS
#define FBRL_CELL_RACKS 8 /* matrices the picture draws whole (CELL-RACK) */
#endif
#define FBRL_CELL_RACK_MAX    64  /* rows (rings) or columns (radials) of one rack */
#define FBRL_CELL_REFUSED_PTS 9   /* tool points kept of a refused motion, for the picture */
#define FBRL_CELL_MSG_MAX     192 /* a refusal's message, its end included */
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

/* A matrix the picture draws whole: positions (i, j, 0), i < rows, j < cols (RECTMAT), or
 * (ring, radial, 0) of a RADMAT. */
typedef struct fbrl_cell_rack {
    char name[FBRL_CELL_NAME_MAX + 1];
    int rows, cols;
} fbrl_cell_rack;

/* A refused motion as the picture draws it: the tool point from the start up to the contact
 * (or towards a target the guard could not check), and the contact. */
typedef struct fbrl_cell_refusal {
    double pts[FBRL_CELL_REFUSED_PTS][3];
    unsigned npts;
    int hit;    /* 1: it would hit obj at `at`; 0: the guard could not check it */
    size_t obj; /* the obstacle (FBRL_CELL_TABLE, ...) when hit */
    double at[3];
    char word[FBRL_CELL_NAME_MAX + 1];
} fbrl_cell_refusal;

/* One motion the guard checked, for an observer (fbrl_cell_set_observer): a refused motion
 * when the guard refused it, a passed one once the controller took it. */
typedef struct fbrl_cell_check {
    const char *word;    /* the FBRL word that sent or would have sent it */
    int sent;            /* 1: passed and taken by the controller; 0: refused, nothing sent */
    int line;            /* 1: a straight line (the tool point moves straight); 0: joint-interpolated */
    int path;            /* 1: the path was computed: q1 and hit hold; 0: the guard could not follow it */
    unsigned naxes;      /* joints in q0 and q1 (0: not even the start was read) */
    double q0[FBRL_CELL_AXES]; /* where it starts (the joints the guard read) */
    double q1[FBRL_CELL_AXES]; /* where it ends; refused on a hit: where the check stopped, at the contact */
    const fbrl_cell_hit *hit;  /* path: what the check found (clearance, near_obj; hit, obj, at) */
    const char *message;       /* refused: the refusal's message */
} fbrl_cell_check;

/* Called for every motion the guard checked (the check's own step: do not run FBRL in it). */
typedef void (*fbrl_cell_observe_fn)(void *ctx, const fbrl_cell_check *c);

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
#if FBRL_CELL_PICTURE
    fbrl_cell_rack racks[FBRL_CELL_RACKS];        /* CELL-RACK */
    size_t nracks;
    fbrl_cell_refusal refused[FBRL_CELL_LOG_MAX]; /* the first refused motions, drawn */
    unsigned nrefused;
#endif
    fbrl_cell_save_fn save;
    void *save_ctx;
    int line;          /* the motion being sent is a straight line (done reports it) */
    fbrl_cell_observe_fn observe;
    void *observe_ctx;
} fbrl_cell_words;

/* Define the words in vm, guarding robot r's motions (fbrl_robot_set_guard); g (may be NULL)
 * gives the calibrations that carry blocks and the named locations a new obstacle must not
 * hold. FBRL_EINVAL for NULLs, FBRL_ENOMEM when the dictionary is full. */
FBRL_API fbrl_status fbrl_cell_install(fbrl_vm *vm, fbrl_cell_words *cw, fbrl_robot *r, fbrl_glossary *g);
/* Where CELL-SVG saves its picture (NULL: it throws "no file output"). */
FBRL_API void fbrl_cell_set_save(fbrl_cell_words *cw, fbrl_cell_save_fn fn, void *ctx);
/* Who sees each motion the guard checked (NULL: no one): a dry run's path, segment by segment. */
FBRL_API void fbrl_cell_set_observer(fbrl_cell_words *cw, fbrl_cell_observe_fn fn, void *ctx);
/* The guard's record. */
FBRL_API const fbrl_cell_stats *fbrl_cell_stats_get(const fbrl_cell_words *cw);
/* The SVG picture written through fn (src/words/cell_svg.c): top and side views at one scale
 * whose frame fits the cell, the locations and the path, with a scale bar and a legend;
 * obstacles, the named locations, every position of a CELL-RACK, the tool path, the closest
 * approach and each refused motion (red, naming what it would hit); labels never overlap
 * (one that finds no free place is left to its element's tooltip). FBRL_EUNSUPPORTED in a
 * build without the picture (FBRL_CELL_PICTURE 0). */
FBRL_API fbrl_status fbrl_cell_svg(fbrl_cell_words *cw, fbrl_cell_write_fn fn, void *ctx);

#ifdef __cplusplus
}
#endif
#endif
