/* SPDX-License-Identifier: MIT */
/* mon_runlog.h - the run log in fbrlmon and its console: every RUN-METHOD writes a JSON
 * Lines record of the run (include/fbrl/runlog.h) to the file chosen with --run-log or
 * RUN-LOG: the header, each step, each command the controller executed (from the link's
 * on_exec), errors in plain words with what to do, and the summary. docs/console.md. */
#ifndef FBRLMON_RUNLOG_H
#define FBRLMON_RUNLOG_H

#include <stdint.h>
#include <stdio.h>
#include "fbrl/link.h"
#include "fbrl/method.h"
#include "fbrl/runlog.h"
#include "mon_audit.h"

struct mon;

#define MON_RUNLOG_PATH_MAX 512

typedef struct mon_runlog {
    struct mon *m;
    fbrl_runlog log;
    mon_audit audit;                  /* the run log's file: a hash-chained audit trail */
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
    fbrl_method_observer chain; /* another observer (the console), called after the log's */
    /* every executed line, after the log has it (the console's live view) */
    void (*exec_hook)(void *ctx, const char *line, size_t len, fbrl_status result);
    void *exec_hook_ctx;
} mon_runlog;

/* Take over m's method observer, define RUN-LOG and NO-RUN-LOG. controller describes the
 * connection (may be NULL). 0, or -1 if the words could not be defined. */
int mon_runlog_install(mon_runlog *r, struct mon *m, const char *program, const char *controller);
/* Log every following run to path (appended; "" or NULL: no log). */
void mon_runlog_set_path(mon_runlog *r, const char *path);
/* The link's on_exec (mon_conn_options.on_exec, ctx = the mon_runlog). */
void mon_runlog_exec(void *ctx, const char *line, size_t len, fbrl_status result);
/* What to do about an error message, in plain words (never NULL). */
const char *mon_runlog_advice(const char *message);
/* Microseconds of the monotonic clock. */
uint64_t mon_runlog_now_us(void *ctx);

#endif
