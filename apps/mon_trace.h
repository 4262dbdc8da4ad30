/* mon_trace.h - fbrlmon's trace: each robot command the controller ran, with the plan
 * line that sent it (mon_trace.c); each word entered (TRACE-WORDS, mon_step.c). */
#ifndef FBRLMON_TRACE_H
#define FBRLMON_TRACE_H

#include <stdio.h>
#include "fbrl/link.h"

typedef struct mon_trace {
    int commands;           /* TRACE-ON: robot commands */
    int words;              /* TRACE-WORDS: also every colon definition entered */
    FILE *file;             /* TRACE-TO: the trace's file (NULL: the terminal) */
    fbrl_link_exec_fn prev; /* the link's handler before ours (the run log), called on */
    void *prev_ctx;
    int hooked;
} mon_trace;

struct mon;
/* Define TRACE-ON TRACE-TO in m->vm. */
fbrl_status mon_trace_install(struct mon *m);
/* Where trace lines go. */
FILE *mon_trace_out(struct mon *m);
/* Commands no longer traced, the trace file closed (TRACE-OFF). */
void mon_trace_stop(struct mon *m);
/* Close a trace file (at exit). */
void mon_trace_close(struct mon *m);

#endif
