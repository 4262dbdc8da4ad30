/* SPDX-License-Identifier: MIT */
/* run.h - a method run as one thing: the console, fbrlmon, Python, a SiLA station and a
 * browser page drive the same run and see the same truth.
 *
 * A run executes a method (fbrl/method.h) on the thread that starts it: the engine is
 * single-threaded. Everything else may come from any thread:
 *
 *   engine thread                           any thread
 *   -------------                           ----------
 *   fbrl_run_start(r, "SAMPLE-PREP", v, n)  fbrl_run_pause(r, "ann")   after the current step
 *     steps, samples, ASK ...               fbrl_run_resume(r, "ann")
 *     observers told of each event          fbrl_run_abort(r, "ann")   halt, outputs off, ON-ABORT
 *   returns when the run has its outcome    fbrl_run_answer(r, FBRL_RUN_RETRY, "ann")
 *                                           fbrl_run_snapshot(r, &snap)
 *
 * Outcomes. Each sample of a run (SAMPLES-PARAM) ends succeeded, failed (with a reason)
 * or skipped (with a reason). A method says it with the words SAMPLE-FAILED and
 * SAMPLE-SKIPPED, or a corrective action skips it (ON-FAILURE ... SKIP, or the operator's
 * Skip), or a step fails while it works on the sample (the run then stops). A sample no
 * one marked is succeeded once the method's last per-sample step has ended for it. The run
 * is `completed` when it reached its end and every sample succeeded, `failed` when no
 * sample succeeded, `partial` otherwise, and `aborted` after an abort.
 *
 * The words (installed by fbrl_run_install):
 *   RUN-METHOD      ( method -- )          run it (throws when a step failed or it was aborted)
 *   SAMPLE-FAILED   ( n c-addr u -- )      sample n (0..) failed, for the reason given
 *   SAMPLE-SKIPPED  ( n c-addr u -- )      sample n was not done, for the reason given
 *   SAMPLE-OK?      ( n -- flag )          sample n has neither failed nor been skipped
 * docs/console.md tells the words, docs/c-programs.md the C side. */
#ifndef FBRL_RUN_H
#define FBRL_RUN_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/method.h"
#include "fbrl/recover.h"
#include "fbrl/robot.h"
#include "fbrl/status.h"
#include "fbrl/vm.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FBRL_RUN_MAX_SAMPLES 96  /* samples one run tracks (a 96-well plate) */
#define FBRL_RUN_REASON_MAX  95  /* a sample's reason (longer ones are cut) */
#define FBRL_RUN_TEXT_MAX    255 /* a question, an error */
#define FBRL_RUN_WHO_MAX     63  /* who asked for a pause, resume, abort or answer */
#define FBRL_RUN_OBSERVERS   6
#define FBRL_RUN_POLL_MS     20 /* how often a waiting run (paused, asking) looks at its requests */

typedef enum fbrl_run_state {
    FBRL_RUN_IDLE = 0, /* no run has started yet */
    FBRL_RUN_RUNNING,
    FBRL_RUN_PAUSING,  /* a pause is asked for: it takes effect after the current step */
    FBRL_RUN_PAUSED,   /* between two steps, until resumed or aborted */
    FBRL_RUN_ABORTING, /* an abort is asked for or under way (safe stop, ON-ABORT) */
    FBRL_RUN_FINISHED  /* the last run has its outcome */
} fbrl_run_state;

typedef enum fbrl_run_outcome {
    FBRL_RUN_NONE = 0, /* not finished */
    FBRL_RUN_COMPLETED,
    FBRL_RUN_PARTIAL,
    FBRL_RUN_FAILED,
    FBRL_RUN_ABORTED
} fbrl_run_outcome;

typedef enum fbrl_run_sample_outcome {
    FBRL_SAMPLE_PENDING = 0, /* not done yet */
    FBRL_SAMPLE_SUCCEEDED,
    FBRL_SAMPLE_FAILED,
    FBRL_SAMPLE_SKIPPED
} fbrl_run_sample_outcome;

/* The operator's answer to a corrective action's question (ON-FAILURE ... ASK). */
typedef enum fbrl_run_choice {
    FBRL_RUN_RETRY = 1, /* run the step again */
    FBRL_RUN_SKIP,      /* give the sample up (skipped), go on with the next */
    FBRL_RUN_STOP       /* abort the run */
} fbrl_run_choice;

typedef struct fbrl_run_sample {
    uint8_t outcome; /* fbrl_run_sample_outcome */
    char reason[FBRL_RUN_REASON_MAX + 1];
} fbrl_run_sample;

/* What a run looks like from outside, copied whole (fbrl_run_snapshot). */
typedef struct fbrl_run_snap {
    unsigned long version; /* grows with every change (a front end redraws when it differs) */
    int state;             /* fbrl_run_state */
    int outcome;           /* fbrl_run_outcome: the last run's once FINISHED, else NONE */
    char method[FBRL_METHOD_NAME_MAX + 1];
    long nsteps;
    char step_name[FBRL_METHOD_MAX_STEPS][FBRL_METHOD_NAME_MAX + 1];
    uint8_t per_sample[FBRL_METHOD_MAX_STEPS];
    long step_runs[FBRL_METHOD_MAX_STEPS]; /* how often each step runs in this run */
    long step_done[FBRL_METHOD_MAX_STEPS]; /* how often it ended without error */
    uint8_t step_failed[FBRL_METHOD_MAX_STEPS];
    long step;         /* the current step (the last one after the end), -1 before the first */
    long sample;       /* the current sample 0.., -1 none */
    long samples;      /* the run's samples (0: the method counts none) */
    long samples_done; /* samples that have their outcome */
    fbrl_run_sample outcomes[FBRL_RUN_MAX_SAMPLES];
    int question; /* while a question waits for fbrl_run_answer: its number in the run (1, 2 ...), else 0 */
    char question_text[FBRL_RUN_TEXT_MAX + 1];
    char error[FBRL_RUN_TEXT_MAX + 1]; /* what ended the run (or the last failure), "" none */
    char who[FBRL_RUN_WHO_MAX + 1];    /* who paused (PAUSING, PAUSED) or aborted (ABORTING, aborted) */
    long elapsed_ms;   /* since the run began, pauses included; frozen at its end */
    long remaining_ms; /* predicted time still to go, -1 unknown (see fbrl_run_predict) */
} fbrl_run_snap;

typedef enum fbrl_run_event_kind {
    FBRL_RUN_EV_BEGIN,      /* a run starts; an observer's non-zero return refuses it */
    FBRL_RUN_EV_STEP_BEGIN, /* step, sample */
    FBRL_RUN_EV_STEP_END,   /* step, sample; text: the error, NULL when it ended well */
    FBRL_RUN_EV_SAMPLE,     /* sample, outcome (fbrl_run_sample_outcome), text: the reason */
    FBRL_RUN_EV_RECOVERY,   /* a corrective action: where (its step), kind, text (what), action */
    FBRL_RUN_EV_QUESTION,   /* text: the question; the run waits for fbrl_run_answer */
    FBRL_RUN_EV_ANSWER,     /* choice, who */
    FBRL_RUN_EV_PAUSE,      /* the run pauses before step (sample); who asked */
    FBRL_RUN_EV_RESUME,     /* who */
    FBRL_RUN_EV_ABORT,      /* the abort takes effect; who asked */
    FBRL_RUN_EV_SAFE_STOP,  /* status: the stop's result; text: what was done */
    FBRL_RUN_EV_ON_ABORT,   /* the method's ON-ABORT word ran; text: its error, NULL none */
    FBRL_RUN_EV_END,        /* outcome (fbrl_run_outcome), text: the error that ended it or NULL */
    FBRL_RUN_EV_WAIT        /* the run waits (paused, asking): return non-zero if you waited
                               (e.g. read keys for a while); else the run sleeps FBRL_RUN_POLL_MS */
} fbrl_run_event_kind;

typedef struct fbrl_run_event {
    fbrl_run_event_kind kind;
    const fbrl_method *method;
    long step;          /* -1: none */
    long sample;        /* 0.., -1: none */
    int outcome;        /* SAMPLE, END */
    int choice;         /* ANSWER: fbrl_run_choice */
    fbrl_status status; /* SAFE_STOP */
    const char *text;   /* see the kinds; may be NULL */
    const char *who;    /* PAUSE, RESUME, ABORT, ANSWER: "" when not said */
    const char *where;  /* RECOVERY: the step the rule belongs to */
    const char *kind_name, *action; /* RECOVERY: "PART-MISSING", "retry 1 of 2" */
} fbrl_run_event;

struct fbrl_run;
/* Called on the engine's thread. The return value counts for BEGIN and WAIT only. */
typedef int (*fbrl_run_observer_fn)(void *ctx, struct fbrl_run *r, const fbrl_run_event *ev);

/* What the engine publishes for other threads: the snapshot and what the remaining time
 * is computed from (private). */
typedef struct fbrl_run_published {
    fbrl_run_snap s;
    double est_ms[FBRL_METHOD_MAX_STEPS]; /* one run of each step (0: unknown) */
    long ended[FBRL_METHOD_MAX_STEPS];    /* runs of each step over, well or not */
    uint64_t t0_us, step_t0_us, end_us;
} fbrl_run_published;
#define FBRL_RUN_PUB_WORDS_ ((sizeof(fbrl_run_published) + sizeof(size_t) - 1) / sizeof(size_t))

/* Caller-owned, at a fixed address while the VM lives; fields private. Other threads read
 * the published words without a lock (a sequence counter); requests take a short lock. */
typedef struct fbrl_run {
    fbrl_vm *vm;
    fbrl_method_set *methods;
    fbrl_recover *rc;
    fbrl_robot *robot;
    fbrl_cell run_xt; /* RUN-METHOD */
    struct {
        fbrl_run_observer_fn fn;
        void *ctx;
    } obs[FBRL_RUN_OBSERVERS];
    fbrl_recover_ask_fn outer_ask; /* rc's ask and note before the run took them over */
    void *outer_ask_ctx;
    fbrl_recover_note_fn outer_note;
    void *outer_note_ctx;
    /* the engine's side */
    const fbrl_method *m;
    int active, began, aborted, interrupted, last_sample_step, questions;
    uint8_t marked[FBRL_RUN_MAX_SAMPLES];
    char abort_who[FBRL_RUN_WHO_MAX + 1];
    char pred_method[FBRL_METHOD_NAME_MAX + 1], meas_method[FBRL_METHOD_NAME_MAX + 1];
    double pred_ms[FBRL_METHOD_MAX_STEPS], meas_ms[FBRL_METHOD_MAX_STEPS];
    fbrl_run_published work; /* being made; published whole */
    /* shared between threads */
    size_t lock, seq, active_flag;
    size_t req_pause, req_abort, req_answer, asking;
    char req_who[4][FBRL_RUN_WHO_MAX + 1]; /* pause, resume, abort, answer: under lock */
    size_t pub[FBRL_RUN_PUB_WORDS_];
} fbrl_run;

/* Define RUN-METHOD SAMPLE-FAILED SAMPLE-SKIPPED SAMPLE-OK? in vm, which has the method
 * words (fbrl_method_install: methods). rc (fbrl_recover_install, may be NULL): the run
 * takes over its ask and note while a run goes, using the ones set before outside a run.
 * robot (may be NULL): the safe stop after an abort or a failure. */
FBRL_API fbrl_status fbrl_run_install(fbrl_run *r, fbrl_vm *vm, fbrl_method_set *methods, fbrl_recover *rc,
                                      fbrl_robot *robot);

/* Tell fn of every event of every run (up to FBRL_RUN_OBSERVERS, in the order added; one
 * removed and added again comes last): FBRL_EFULL when there is no room; removing one that
 * is not there is FBRL_ENOENT. Not while a run goes (FBRL_ESTATE). */
FBRL_API fbrl_status fbrl_run_observe(fbrl_run *r, fbrl_run_observer_fn fn, void *ctx);
FBRL_API fbrl_status fbrl_run_unobserve(fbrl_run *r, fbrl_run_observer_fn fn, void *ctx);

/* Run the method named (a complete one) on this thread, with its parameters set first to
 * values[0..n) in declaration order (values NULL and n 0: as they are). Returns when the
 * run has its outcome (fbrl_run_snapshot): FBRL_OK whatever the outcome; FBRL_ENOENT no such
 * method, FBRL_ESTATE incomplete or a run goes, FBRL_EINVAL n is not the parameter count,
 * FBRL_ERANGE a value outside its range (*bad, if not NULL, its index; nothing set), else
 * the engine's status when the run could not begin (an observer refused it: the VM's error
 * says why). */
FBRL_API fbrl_status fbrl_run_start(fbrl_run *r, const char *method, const long *values, size_t n, size_t *bad);

/* The time one run of each step takes, ms[0..n) (0: unknown), for runs of that method
 * (e.g. a dry run's): the remaining time follows it. Without one, a step's time measured in
 * this run or the run before of the same method counts. Engine thread, not while it runs. */
FBRL_API fbrl_status fbrl_run_predict(fbrl_run *r, const char *method, const double *ms, size_t n);

/* Requests, from any thread: FBRL_OK, or FBRL_ESTATE when no run goes (pause, abort), none
 * is paused or pausing (resume), no question waits (answer). who names the person or client
 * for the run log (NULL: ""). An abort interrupts the running word at once. */
FBRL_API fbrl_status fbrl_run_pause(fbrl_run *r, const char *who);
FBRL_API fbrl_status fbrl_run_resume(fbrl_run *r, const char *who);
FBRL_API fbrl_status fbrl_run_abort(fbrl_run *r, const char *who);
FBRL_API fbrl_status fbrl_run_answer(fbrl_run *r, fbrl_run_choice choice, const char *who);

/* The run as it stands, from any thread (the VM host's clock must then be thread-safe).
 * FBRL_EBUSY if the engine kept changing it (try again). */
FBRL_API fbrl_status fbrl_run_snapshot(const fbrl_run *r, fbrl_run_snap *out);

/* Mark sample index (0..) of the running method: FBRL_SAMPLE_FAILED or _SKIPPED with a
 * reason (SAMPLE-FAILED, SAMPLE-SKIPPED do this). The first mark of a sample stands.
 * FBRL_ESTATE when no run goes, FBRL_ERANGE for a sample the run has not. Engine thread. */
FBRL_API fbrl_status fbrl_run_mark(fbrl_run *r, long sample, fbrl_run_sample_outcome outcome, const char *reason);

/* Names: "idle" "running" "pausing" "paused" "aborting" "finished"; "" "completed"
 * "partial" "failed" "aborted"; "pending" "succeeded" "failed" "skipped". */
FBRL_API const char *fbrl_run_state_name(fbrl_run_state s);
FBRL_API const char *fbrl_run_outcome_name(fbrl_run_outcome o);
FBRL_API const char *fbrl_run_sample_name(fbrl_run_sample_outcome o);

#ifdef __cplusplus
}
#endif
#endif
