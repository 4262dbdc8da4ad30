/* SPDX-License-Identifier: MIT */
/* mon_dry.h - the dry run (fbrlmon --dry-run, docs/workcell.md): a plan run against the
 * built-in emulator with every wait skipped, then a report of what it did.
 *
 * The host and the emulator share one clock that runs with real time and jumps forward
 * whenever the plan waits (MS, PULSE, WAIT-UNTIL, the wait for the arm between motions), so
 * the simulated duration is what a real-time run takes while the dry run takes as long as
 * the commands alone. The plan runs in a scratch directory (its relative files land there
 * and are removed) unless keep_files. */
#ifndef FBRLMON_DRY_H
#define FBRLMON_DRY_H

#include <stddef.h>
#include <stdio.h>
#include "mon.h"
#include "mon_conn.h"
#include "mon_runlog.h"

#define MON_DRY_EVENTS 4096 /* output pulses, waits and errors the report lists */

typedef enum mon_dry_kind { MON_DRY_PULSE, MON_DRY_WAIT, MON_DRY_ERROR, MON_DRY_TIMEOUT } mon_dry_kind;

typedef struct mon_dry_event {
    mon_dry_kind kind;
    double t, len;  /* simulated s since the start; a pulse's or wait's length (s) */
    int output;     /* MON_DRY_PULSE: the output */
    char text[600]; /* MON_DRY_ERROR, MON_DRY_TIMEOUT: what and where */
} mon_dry_event;

/* What a dry run found (the C entry point's result). */
typedef struct mon_dry_report {
    double duration;        /* simulated seconds from the first action to the end */
    double wall;            /* real seconds the dry run took */
    unsigned long commands; /* controller commands that ran */
    unsigned long moves;    /* motion commands that ran */
    unsigned long errors;   /* errors (guard refusals, controller errors, the plan's) */
    const fbrl_cell_stats *cell;
    unsigned long timeouts; /* waits that gave up (WAIT-INPUT not seen in time) */
    /* the last method run: each step's time for one run (simulated ms, 0 not run), the
     * predicted outcome of the run and of each sample */
    int have_run;
    double step_ms[FBRL_METHOD_MAX_STEPS];
    fbrl_run_snap run;
    size_t nevents;
    mon_dry_event ev[MON_DRY_EVENTS];
} mon_dry_report;

typedef struct mon_dry_options {
    int keep_files;   /* run in the current directory: the plan's files are written */
    const char *json; /* --dry-run-json: each motion the guard checked, a JSON line (NULL: none) */
} mon_dry_options;

/* Before the connection opens: the built-in emulator on the shared clock (conn's kind, clock
 * and run log), the host's clock, the scratch directory. -1 and a message on failure. */
int mon_dry_setup(const mon_dry_options *o, mon_conn_options *conn);
/* The session is open: start counting (the runs, and through log the device events). */
void mon_dry_start(mon *m, mon_runlog *log);
/* The plan ran: fill r (may be NULL), print the report to out, write the picture, leave
 * (svg: its file, NULL none) and remove the scratch directory. Returns 0, or -1 if the picture could not be written. */
int mon_dry_finish(mon *m, mon_dry_report *r, FILE *out, const char *svg);

#endif
