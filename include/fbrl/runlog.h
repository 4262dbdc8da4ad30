/* SPDX-License-Identifier: MIT */
/* runlog.h - the run log a lab keeps: one JSON object per line (JSON Lines).
 *
 * A run of a method writes a header (method, parameters, operator, time, controller and
 * program versions, calibration in force), then in order every step's start and end,
 * every command the controller executed with its reply status (a poll repeated while it
 * waits, W5 or TYPEI, as one record with its count), device actions and timed waits
 * (planned and actual milliseconds), each sample's outcome, notes (pause, resume, abort,
 * with who asked) and errors, and at the end a summary: the outcome, every sample's
 * outcome, counts, and a few lines of plain text for a person. docs/console.md lists
 * every field.
 *
 * The log writes through the caller's sink (a file, a buffer) and reads the caller's
 * clock; it never allocates, prints or opens anything itself. Any part of a program (the
 * console, fbrlmon, a debugger) adds records with these calls while the log is open. */
#ifndef FBRL_RUNLOG_H
#define FBRL_RUNLOG_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The sink: write n bytes (one whole line each call); 0 = written, -1 = failed. */
typedef int (*fbrl_runlog_write_fn)(void *ctx, const char *s, size_t n);
/* Monotonic microseconds. */
typedef uint64_t (*fbrl_runlog_clock_fn)(void *ctx);

/* The longest record line (longer texts are cut, with "..." at the cut; a summary with
 * more samples than fit names how many it left out). */
#define FBRL_RUNLOG_LINE_MAX 8192
/* The longest poll line folded (longer ones are each a record). */
#define FBRL_RUNLOG_POLL_MAX 32
/* Parameters one header can name. */
#define FBRL_RUNLOG_MAX_PARAMS 32

typedef struct fbrl_runlog_param {
    const char *name;
    long value;
    const char *unit; /* may be NULL */
} fbrl_runlog_param;

typedef struct fbrl_runlog_header {
    const char *method;      /* the method's name (required) */
    const char *source;      /* the method's file, or NULL */
    const char *operator_id; /* who runs it, or NULL */
    const char *started;     /* local date and time, ISO 8601 text, or NULL */
    const char *controller;  /* the controller's version (STATUS), or NULL */
    const char *program;     /* the program and its version ("fbrlmon 0.1.0"), or NULL */
    const char *calibration; /* the calibration in force, in words, or NULL */
    const fbrl_runlog_param *params;
    size_t nparams;
} fbrl_runlog_header;

/* A sample's outcome for the summary: its number (1..), "succeeded", "failed" or
 * "skipped", and why (may be NULL or ""). */
typedef struct fbrl_runlog_outcome {
    long sample;
    const char *outcome;
    const char *reason;
} fbrl_runlog_outcome;

/* Caller-owned; fields private. */
typedef struct fbrl_runlog {
    fbrl_runlog_write_fn write;
    void *write_ctx;
    fbrl_runlog_clock_fn now_us;
    void *clock_ctx;
    uint64_t t0_us;
    int open;
    fbrl_status failed; /* the first failed write (the log is then incomplete) */
    char method[64];
    unsigned long commands, refused, not_run, maybe, steps, errors, waits, devices;
    unsigned long aborted_steps;
    char line[FBRL_RUNLOG_LINE_MAX + 2];
    size_t len, cap; /* cap: where the record being made must end */
    int full;        /* the record met cap: something was cut */
    /* the poll being folded: its line, how often, when first and last */
    char poll[FBRL_RUNLOG_POLL_MAX + 1];
    unsigned long poll_count;
    uint64_t poll_t0, poll_t1;
} fbrl_runlog;

/* Open the log and write its header record ("type":"header"). FBRL_EINVAL for NULLs or
 * more than FBRL_RUNLOG_MAX_PARAMS parameters, FBRL_ESTATE if it is open, FBRL_EIO if the
 * sink failed (the log stays closed). */
FBRL_API fbrl_status fbrl_runlog_begin(fbrl_runlog *l, fbrl_runlog_write_fn write, void *write_ctx,
                                       fbrl_runlog_clock_fn now_us, void *clock_ctx,
                                       const fbrl_runlog_header *h);

/* Is it open? */
FBRL_API int fbrl_runlog_is_open(const fbrl_runlog *l);

/* A step started ("step_start") or ended ("step_end", with "status": "ok" or the error
 * text). sample < 0: a step done once for the run; else the sample's number (1..). */
FBRL_API fbrl_status fbrl_runlog_step_start(fbrl_runlog *l, const char *step, long sample);
FBRL_API fbrl_status fbrl_runlog_step_end(fbrl_runlog *l, const char *step, long sample, const char *error);

/* A command line the controller executed (or may have: FBRL_EMAYBE), with its result as
 * the link reported it (fbrl_link_config.on_exec has this shape). "status" is "ran",
 * "refused" (with the controller's "code" when code >= 0), "may-have-run" or "not-run".
 * A poll (W5, TYPEI ...) that ran as the one before it is folded into that one's record,
 * written when another record comes: "count" times, the last at "last_t". */
FBRL_API fbrl_status fbrl_runlog_command(fbrl_runlog *l, const char *line, size_t len, fbrl_status result,
                                         int code);
/* The same for the run-th run of one command (fbrl_link_get_runs: the link typed it again,
 * docs/link.md 3.9): above 1 the record says so ("run": 2). */
FBRL_API fbrl_status fbrl_runlog_command_run(fbrl_runlog *l, const char *line, size_t len, fbrl_status result,
                                             int code, unsigned run);

/* A device action ("device": name, "action": "on", "off", "pulse", "dispense" ...) and a
 * timed wait ("wait": what), each with planned and actual milliseconds (planned < 0: none). */
FBRL_API fbrl_status fbrl_runlog_device(fbrl_runlog *l, const char *device, const char *action,
                                        long planned_ms, long actual_ms);
FBRL_API fbrl_status fbrl_runlog_wait(fbrl_runlog *l, const char *what, long planned_ms, long actual_ms);

/* An error in plain words: where (a step, "file:line", or NULL), what happened, and what
 * to do about it (NULL: nothing to add). */
FBRL_API fbrl_status fbrl_runlog_error(fbrl_runlog *l, const char *where, const char *message,
                                       const char *advice);

/* A note: "pause", "resume", "abort", "safe-stop" ... with who asked for it ("operator",
 * NULL: none) and free text (may be NULL). */
FBRL_API fbrl_status fbrl_runlog_note(fbrl_runlog *l, const char *event, const char *who, const char *text);

/* A sample has its outcome ("sample": 1.., "outcome", "reason"). */
FBRL_API fbrl_status fbrl_runlog_sample(fbrl_runlog *l, long sample, const char *outcome, const char *reason);

/* Close the log: a "summary" record (outcome "completed", "partial", "failed" or
 * "aborted", elapsed ms, the counts, then "samples": samples[0..n) as {sample, outcome,
 * reason}) and the human summary as "text" records, one line each. The status is the
 * first failed write of the whole log (FBRL_EIO: it misses records), else FBRL_OK. */
FBRL_API fbrl_status fbrl_runlog_end(fbrl_runlog *l, const char *outcome, const fbrl_runlog_outcome *samples,
                                     size_t n);

/* ---- a run's records (fbrl/run.h) ---- */

struct fbrl_run;
struct fbrl_run_event;
struct fbrl_run_snap;

/* The record(s) of one event of a method run (an fbrl_run_observer_fn passes it on), as
 * every program that keeps run logs writes them: a step's start and end (a failed one
 * with an "error" record in plain words), a sample's outcome, a corrective action, a
 * question and its answer, pause, resume and abort with who asked, the safe stop and
 * ON-ABORT; at the end the summary with every sample's outcome (fbrl_runlog_end; the
 * run's snapshot is read into scratch). BEGIN writes nothing: the caller opens the log
 * with its header (fbrl_runlog_begin), which only it knows. A log that is not open
 * writes nothing (FBRL_OK). FBRL_EINVAL for NULLs; else as the record's write. */
FBRL_API fbrl_status fbrl_runlog_event(fbrl_runlog *l, struct fbrl_run *run, const struct fbrl_run_event *ev,
                                       struct fbrl_run_snap *scratch);
/* Plain words for what to do about an error an operator meets (a run's failure text):
 * never NULL. */
FBRL_API const char *fbrl_runlog_advice(const char *msg);

#ifdef __cplusplus
}
#endif
#endif
