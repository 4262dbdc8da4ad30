/* SPDX-License-Identifier: MIT */
/* recover.h - corrective actions (thesis 4.1: "corrective actions should be provided for
 * problems which arise more frequently"): per step of a plan, what to do when a named kind
 * of failure happens - retry, run a recovery word and retry, skip the sample, ask the
 * operator, or stop safely. docs/debugging.md shows the words:
 *
 *   ON-FAILURE PICK-UP GRIP-EMPTY RETRY 1      \ a pick-up that finds nothing: once more,
 *   ON-FAILURE PICK-UP GRIP-EMPTY ASK          \ then ask the operator
 *   ON-FAILURE LOAD-TUBE PART-MISSING ASK
 *   ON-FAILURE * COMM-LOST STOP                \ any step
 *   : ONE-SAMPLE ['] LOAD-TUBE ATTEMPT ['] PICK-UP ATTEMPT ... ;
 *   ['] ONE-SAMPLE RUN-SAMPLE ( -- flag )      \ false: the sample was skipped
 *
 * A step is a word without stack effect ( -- ). The plan itself raises the failures only
 * it can see: `PART-MISSING FAILURE` (a sensor), `GRIP-EMPTY FAILURE` (the gripper's
 * opening). Controller errors are classified from the controller's error number, a lost
 * controller from the link. */
#ifndef FBRL_RECOVER_H
#define FBRL_RECOVER_H

#include "fbrl/export.h"

#include "fbrl/robot.h"
#include "fbrl/vm.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The kinds of failure, each with a name the words use. */
typedef enum fbrl_recover_kind {
    FBRL_RECOVER_NONE = 0,       /* not a failure a rule can name */
    FBRL_RECOVER_REACH = 1,      /* the controller: the place is out of the arm's reach */
    FBRL_RECOVER_JOINT_LIMIT,    /* the controller: a joint would pass its limit */
    FBRL_RECOVER_COLLISION,      /* refused by the work-cell guard, or the controller stopped */
    FBRL_RECOVER_CONTROLLER,     /* any other controller error */
    FBRL_RECOVER_COMM_LOST,      /* the controller stopped answering */
    FBRL_RECOVER_GRIP_EMPTY,     /* the gripper closed on nothing (the plan raises it) */
    FBRL_RECOVER_PART_MISSING,   /* a sensor says the part is missing (the plan raises it) */
    FBRL_RECOVER_DEVICE_TIMEOUT, /* a device did not answer in time (the plan raises it) */
    FBRL_RECOVER_KINDS
} fbrl_recover_kind;

/* What a rule does. */
typedef enum fbrl_recover_action {
    FBRL_RECOVER_RETRY = 1, /* run the step again, up to the rule's count */
    FBRL_RECOVER_RUN,       /* run the rule's recovery word, then the step again (count) */
    FBRL_RECOVER_SKIP,      /* give up this sample: RUN-SAMPLE returns false */
    FBRL_RECOVER_ASK,       /* ask the operator: Retry, Skip or Abort */
    FBRL_RECOVER_STOP       /* stop safely: halt, outputs off, the plan ends with an error */
} fbrl_recover_action;

/* THROW codes (in the system's range -256 .. -4095): a failure a plan raises
 * (FBRL_RECOVER_THROW(kind)), a skipped sample, a safe stop. */
#define FBRL_RECOVER_THROW(kind)   (-400 - (int)(kind))
#define FBRL_RECOVER_THROW_SKIP    (-420)
#define FBRL_RECOVER_THROW_STOPPED (-421)

#define FBRL_RECOVER_RULES 64 /* rules one session holds */

/* The operator's answer to ASK: 'R' retry, 'S' skip the sample, 'A' abort (stop safely). */
typedef int (*fbrl_recover_ask_fn)(void *ctx, const char *question);
/* Told of every failure a rule handled and the action taken (a run log, the terminal):
 * step, kind name, what was wrong in plain words, the action ("retry 1 of 2", "skip",
 * "ask: skip", "stop") and the sample number (0: none). */
typedef void (*fbrl_recover_note_fn)(void *ctx, const char *step, const char *kind, const char *what,
                                     const char *action, long sample);
/* Told when RUN-SAMPLE gave a sample up (a rule's SKIP or the operator's Skip), with why:
 * the method run marks the sample skipped (fbrl/run.h). */
typedef void (*fbrl_recover_skip_fn)(void *ctx, const char *reason);

typedef struct fbrl_recover_rule {
    fbrl_cell step; /* the step's xt; 0: any step */
    char step_name[32];
    uint8_t kind, action;
    uint16_t limit; /* RETRY / RUN: how many times */
    fbrl_cell word; /* RUN: the recovery word's xt */
    char word_name[32];
    uint16_t used; /* this ATTEMPT's retries so far */
} fbrl_recover_rule;

typedef struct fbrl_recover {
    fbrl_vm *vm;
    fbrl_robot *robot; /* controller errors, the safe stop; may be NULL */
    fbrl_recover_rule rules[FBRL_RECOVER_RULES];
    size_t nrules;
    long sample;   /* RUN-SAMPLE's count: which sample a note is about */
    char step[32]; /* the step that failed last (for the notes and messages) */
    fbrl_recover_ask_fn ask;
    void *ask_ctx;
    fbrl_recover_note_fn note;
    void *note_ctx;
    fbrl_recover_skip_fn skip;
    void *skip_ctx;
    char skip_reason[128]; /* the last skip's message */
} fbrl_recover;

/* Define ON-FAILURE FAILURE ATTEMPT RUN-SAMPLE RECOVERY-RULES in vm; rc must live as long.
 * robot may be NULL (then controller errors are not classified and STOP only ends the plan). */
FBRL_API fbrl_status fbrl_recover_install(fbrl_vm *vm, fbrl_recover *rc, fbrl_robot *robot);
/* How ASK reaches the operator (NULL: ASK stops safely) and who is told of each action. */
FBRL_API fbrl_status fbrl_recover_set_ask(fbrl_recover *rc, fbrl_recover_ask_fn fn, void *ctx);
FBRL_API fbrl_status fbrl_recover_set_note(fbrl_recover *rc, fbrl_recover_note_fn fn, void *ctx);
FBRL_API fbrl_status fbrl_recover_set_skip(fbrl_recover *rc, fbrl_recover_skip_fn fn, void *ctx);
/* The kind of a THROW code (with the robot's last controller error), FBRL_RECOVER_NONE if
 * no rule can name it; its name ("GRIP-EMPTY") and plain words. */
FBRL_API fbrl_recover_kind fbrl_recover_classify(const fbrl_recover *rc, int throw_code);
FBRL_API const char *fbrl_recover_kind_name(fbrl_recover_kind kind);
FBRL_API const char *fbrl_recover_kind_text(fbrl_recover_kind kind);

#ifdef __cplusplus
}
#endif
#endif
