/* SPDX-License-Identifier: MIT */
/* console_state.h - what the operator console's files share: its state, and its screens
 * and modes by name. Each file below has its header; a file calls only the files below
 * it (no call circles: the test call_circles checks fbrlmon's objects):
 *
 *   console.c          the frame: drawing, key dispatch, the loop, the hooks inside a run
 *   console_line.c     the typed line (enum con_line): the Forth line, the level, a new
 *                      method's name, signing in
 *   console_compose.c  the composer (SCREEN_COMPOSE)
 *   console_run.c      the run screen (SCREEN_RUN): start, progress, pause, resume, abort
 *   console_library.c  the method library (SCREEN_LIBRARY)
 *   console_cell.c     the work cell (SCREEN_CELL) and TEACH
 *   console_form.c     the parameter form (SCREEN_FORM)
 *   console_text.c     texts, rows, the message and error panes
 *   console_users.c    sign-in, the levels a role allows, recorded actions
 *
 * A screen's key function answers what it asks of a file above it (the form's F5: start
 * the run; the composer's F5: ask for a name), and the frame does it. docs/console.md
 * tells how to use the console. */
#ifndef FBRLMON_CONSOLE_STATE_H
#define FBRLMON_CONSOLE_STATE_H

#include <stdint.h>
#include <stdio.h>

#include "mon.h"
#include "mon_runlog.h"

#define MSG_LINES  4   /* method output lines shown */
#define ERR_LINES  2   /* last errors kept (each with what to do) */
#define FIELD_MAX  12  /* characters of a parameter's field */
#define LIB_MAX    64  /* method files shown */
#define CELL_MAX   128 /* named places and devices the work-cell view lists */
#define MIN_COLS   80
#define MIN_ROWS   24
#define BODY_TOP   2  /* the screen's body (a list, a form, the steps) starts on this row */
#define BODY_ROWS  12 /* ... and has this many rows; the messages follow */
#define KEY_CTRL_C 3
#define KEY_ESCAPE 27

/* The levels (thesis 6.2), each allowing what the one below does and more. */
enum con_level { LEVEL_OPERATOR, LEVEL_DEVELOPER, LEVEL_PROGRAMMER };

/* The screens: what the body of the console shows. */
enum con_screen {
    SCREEN_LIBRARY, /* the method library: choose a method */
    SCREEN_FORM,    /* the chosen method's parameters */
    SCREEN_RUN,     /* a run: its steps, samples, the arm, the devices */
    SCREEN_COMPOSE, /* a new method from the chosen method's steps (developer) */
    SCREEN_CELL     /* the work cell's places and devices, TEACH (developer) */
};

/* The typed line above the keys: what is typed there, if anything. While it is open it
 * takes the keys (outside a run). */
enum con_line {
    LINE_NONE,
    LINE_FORTH,       /* ok> a line for the engine (programmer, F11) */
    LINE_LEVEL,       /* the level to switch to: 1 2 3, or s to sign out (F9) */
    LINE_METHOD_NAME, /* the name of a composed method (the composer's F5) */
    LINE_SIGN_IN,     /* signing in: the name */
    LINE_PASSWORD     /* signing in: the password */
};

/* The run as the console shows it (the state line; console_run.c names them in this order). */
enum con_state {
    ST_IDLE,
    ST_RUNNING,
    ST_PAUSING,
    ST_PAUSED,
    ST_ABORTING,
    ST_DONE,
    ST_ABORTED,
    ST_FAILED,
    ST_PARTIAL
};

typedef struct lib_entry {
    char path[MON_RUNLOG_PATH_MAX];
    char name[FBRL_METHOD_NAME_MAX + 1];
    char text[FBRL_METHOD_TEXT_MAX + 1];
} lib_entry;

typedef struct console {
    mon *m;
    mon_runlog *log;
    const char *methods; /* the method library's folder (--methods, default "methods") */
    enum con_level level;
    enum con_screen screen;
    enum con_state state;
    int quit;
    /* the library (console_library.c) */
    lib_entry lib[LIB_MAX];
    size_t nlib, sel;
    const fbrl_method *meth;
    const lib_entry *entry;
    /* the parameter form (console_form.c) */
    struct {
        char field[FBRL_METHOD_MAX_PARAMS][FIELD_MAX + 1];
        size_t sel;
        int fresh; /* the selected field was just entered: the first character typed replaces it */
    } form;
    /* the run: what it shows is the run's snapshot; the state follows its events */
    fbrl_run_snap snap;
    int abort_asked, abort_confirm, asking;
    int in_vm; /* the engine runs a line of the console's (Forth line, loading, a run) */
    uint64_t last_draw;
    /* the live view, from what the controller executed (console_run.c) */
    uint32_t outputs;
    fbrl_rapl_pos pos; /* W2, read when the arm stands still: paused, stopped, finished */
    int have_pos;
    char pos_when[24];
    char grip[40];
    char last_cmd[FBRL_LINK_LINE_MAX + 1];
    char devname[FBRL_ROBOT_IO_MAX + 1][FBRL_METHOD_NAME_MAX + 1]; /* by output port */
    /* method output and errors (console_text.c) */
    char msgs[MSG_LINES][MIN_COLS + 1];
    char partial[MIN_COLS + 1];
    size_t plen;
    char errs[ERR_LINES][160];
    char advice[ERR_LINES][160];
    char hint[160]; /* the line above the keys, when nothing is typed there */
    uint64_t hint_held_until_us; /* an answer to the operator's key outlives the wait's progress */
    /* the typed line (console_line.c) */
    struct {
        enum con_line mode;
        char who[FBRL_AUDIT_NAME_MAX + 1]; /* the name being signed in */
        char typed[128];
        size_t len;
    } line;
    /* composing a method from the chosen method's steps (console_compose.c) */
    struct {
        size_t sel, picked[FBRL_METHOD_MAX_STEPS], npicked;
    } compose;
    /* the work cell: places and devices by name (console_cell.c) */
    struct {
        char row[CELL_MAX][MIN_COLS];
        size_t n, top, pick;  /* pick: the selected row */
        enum con_screen back; /* the screen Esc goes back to */
    } cell;
    int outside; /* curses is off (TEACH has the terminal): nothing is drawn */
    FILE *out;   /* the engine's output, into the message pane */
} console;

#endif
