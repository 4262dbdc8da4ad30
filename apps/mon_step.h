/* SPDX-License-Identifier: MIT */
/* mon_step.h - fbrlmon's debugger: BREAK, UNBREAK, BREAKS and the stops (mon_step.c). */
#ifndef FBRLMON_STEP_H
#define FBRLMON_STEP_H

#include "fbrl/vm.h"

#define MON_STEP_BREAKS      16  /* breakpoints at once */
#define MON_STEP_STACK_COPY  256 /* stack cells a stop keeps while Forth runs there */
#define MON_STEP_TRACE_CELLS 8   /* top cells TRACE-WORDS shows */

typedef struct mon_break {
    char where[128];    /* a word's name, or a file (its path or the end of it) */
    unsigned long line; /* 0: where is a word */
} mon_break;

typedef struct mon_step {
    mon_break breaks[MON_STEP_BREAKS];
    size_t nbreaks;
    int mode;     /* what to stop at next (mon_step.c) */
    size_t depth; /* the depth (definitions running) that stop compares with */
    int hinted;   /* the keys were explained at the first stop */
    /* where the last word was: a line breakpoint stops where its line begins */
    const char *last_file;
    unsigned long last_line;
    size_t last_depth;
} mon_step;

struct mon;
/* Define the words in m->vm. */
fbrl_status mon_step_install(struct mon *m);
/* A line typed (or a file) ended: a step under way ends with it. */
void mon_step_end(struct mon *m);

#endif
