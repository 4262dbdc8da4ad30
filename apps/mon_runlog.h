/* SPDX-License-Identifier: MIT */
/* mon_runlog.h - the run log in fbrlmon and its console: an observer of the method run
 * (fbrl/run.h) that writes a JSON Lines record of every run (include/fbrl/runlog.h) to the
 * file chosen with --run-log or RUN-LOG: the header, each step, each command the controller
 * executed (from the link's on_exec), each sample's outcome, pauses and aborts with who
 * asked, errors in plain words with what to do, and the summary. Every write is checked: a
 * failed one is told at once (stderr, or the console's hook) and counts as an error of
 * fbrlmon, and the record it cut is taken back off the file. docs/console.md. */
#ifndef FBRLMON_RUNLOG_H
#define FBRLMON_RUNLOG_H

#include <stdint.h>
#include <stdio.h>
#include "fbrl/link.h"
#include "fbrl/robot.h"
#include "fbrl/run.h"
#include "fbrl/runlog.h"
#include "mon_audit.h"

struct mon;

#define MON_RUNLOG_PATH_MAX 512

typedef struct mon_runlog {
    struct mon *m;
    fbrl_runlog log;
    mon_audit audit;                  /* the file: a hash-chained audit trail, open while a run is logged */
    char path[MON_RUNLOG_PATH_MAX];   /* "" = no log */
    char source[MON_RUNLOG_PATH_MAX]; /* the method's file, for the header ("" unknown) */
    char operator_id[64];
    char controller[256];
    const char *program;
    uint64_t step_t0_us;
    /* the controller's version line (STATUS, read as each run begins) and the lines the
     * controller executed while the header was not written yet (they follow it) */
    char version[80];
    int opening;
    char pending[4][FBRL_LINK_LINE_MAX + 1];
    fbrl_status pending_st[4];
    int npending;
    /* every executed line, after the log has it (the console's live view) */
    void (*exec_hook)(void *ctx, const char *line, size_t len, fbrl_status result);
    void *exec_hook_ctx;
    /* every device action and timed wait with the device's name (the dry run's report) */
    void (*event_hook)(void *ctx, const fbrl_robot_event *ev, const char *device);
    void *event_hook_ctx;
    /* the run log could not be written: told here (the console) instead of stderr */
    void (*error_hook)(void *ctx, const char *message);
    void *error_hook_ctx;
    int quiet;        /* a screen shows the outcomes (the console): not told on stderr */
    int write_failed; /* in this run: told once */
    char write_error[MON_RUNLOG_PATH_MAX + 96];
} mon_runlog;

/* Observe m's method runs, take m's device events, define RUN-LOG and NO-RUN-LOG.
 * controller describes the connection (may be NULL). *r must be all zero, as static
 * storage is (clearing it again would make its 47 KB resident). 0, or -1 if that failed. */
int mon_runlog_install(mon_runlog *r, struct mon *m, const char *program, const char *controller);
/* Observe the runs again, after the observers added since (the console: its last reading of
 * the arm at a run's end belongs to that run's log). 0, or -1. */
int mon_runlog_observe_again(mon_runlog *r);
/* Log every following run to path (appended; "" or NULL: no log). */
void mon_runlog_set_path(mon_runlog *r, const char *path);
/* The link's on_exec (mon_conn_options.on_exec, ctx = the mon_runlog). */
void mon_runlog_exec(void *ctx, const char *line, size_t len, fbrl_status result);
/* Microseconds of the monotonic clock. */
uint64_t mon_runlog_now_us(void *ctx);

#endif
