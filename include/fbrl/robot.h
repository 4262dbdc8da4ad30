/* SPDX-License-Identifier: MIT */
/* robot.h - FBRL's robot-side words: communications (thesis I-4), robot commands (I-5),
 * parameter input (I-6), RAPL line building (I-8), named peripherals and timers.
 *
 * fbrl_robot_install() binds the words into a VM. The robot context is caller-owned
 * and holds everything the words keep between calls (the line being built by SEND-*,
 * pending serial settings, the device table, the timer mark, the base offset), so
 * several VMs may drive several robots in one process. Words that talk to the
 * controller go through an fbrl_link (echo-verified RAPL session); without one
 * (link NULL) they throw "no controller connected: start fbrlmon with --sim or --port".
 *
 * Locations are the glossary's 6-float templates (X Y Z O A T, inches and degrees) in
 * the VM's data space. With a glossary, MAP-ON mapping applies to every location sent
 * to the controller and its inverse to every location read back, and METRIC-ON to the
 * lengths the user types (docs/robot.md). Words: docs/glossary.md. */
#ifndef FBRL_ROBOT_H
#define FBRL_ROBOT_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"
#include "fbrl/vm.h"
#include "fbrl/link.h"
#include "fbrl/uart.h"
#include "fbrl/glossary.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Named peripherals (OUTPUT-DEVICE, INPUT-DEVICE) a robot context can hold. */
#define FBRL_ROBOT_MAX_DEVICES 32
/* Controller digital inputs and outputs are numbered 1..FBRL_ROBOT_IO_MAX. */
#define FBRL_ROBOT_IO_MAX FBRL_LINK_IO_MAX
/* Lines a continuous readout (W1 W3 W5 WE1 WE3 WE5) shows before it is stopped. */
#define FBRL_ROBOT_STREAM_LINES 10

typedef struct fbrl_robot_device {
    fbrl_cell addr;    /* the device word's data address (what its name pushes); 0 = free */
    int port;          /* 1..16 */
    int output;        /* 1 = output device, 0 = input device */
    uint32_t pulse_ms; /* output: width of one DISPENSE pulse (and the gap after it) */
} fbrl_robot_device;

/* Progress of a long wait, for a person watching the console: text is one short line
 * ("FINISH: waiting for the arm, 3 s"; "WAIT-UNTIL: 12 s left"), about once a second,
 * from FBRL_ROBOT_PROGRESS_MS into the wait; NULL when the wait is over (erase it). */
typedef void (*fbrl_robot_progress_fn)(void *ctx, const char *text);
#define FBRL_ROBOT_PROGRESS_MS 1000u

struct fbrl_robot;
/* A watcher of a moving arm (fbrl_robot_set_watch): called while a robot word waits for
 * the arm to stop, between two of its W5 readings, when the link is free, at most once
 * every FBRL_ROBOT_WATCH_MS and first that long into the wait. It may use the link for a
 * reading (fbrl_link_where W2 reads the arm as it moves) but must not move the arm. */
typedef void (*fbrl_robot_watch_fn)(void *ctx, struct fbrl_robot *r);
#define FBRL_ROBOT_WATCH_MS 1000u

/* A device action or a timed wait, as it happened (for a run log): told once per word
 * (ON OFF PULSE DISPENSE WAIT-INPUT WAIT-UNTIL) when it ends, also when it failed; and
 * "UNGUARDED" when a motion line went around the guard (fbrl_link_unguarded): line. */
typedef struct fbrl_robot_event {
    const char *word;   /* the word's name */
    fbrl_cell device;   /* what the device's name pushes (0: WAIT-UNTIL) */
    int port;           /* the device's port (0: WAIT-UNTIL) */
    double amount;      /* DISPENSE: ml; WAIT-INPUT: the state waited for (1 on, 0 off) */
    long planned_ms;    /* the time it should take (-1: none, ON and OFF) */
    long actual_ms;     /* the time it took (host clock) */
    int seen;           /* WAIT-INPUT: 1 the input came, 0 the time ran out */
    fbrl_status status; /* FBRL_OK, or how the word failed (FBRL_ETHROW: interrupted ...) */
    const char *line;   /* "UNGUARDED": the motion line sent around the guard; else NULL */
} fbrl_robot_event;
typedef void (*fbrl_robot_event_fn)(void *ctx, const fbrl_robot_event *ev);

/* Room for one console line GET-CAL-POINTS reads. */
#define FBRL_ROBOT_TIB 256

struct fbrl_robot;

/* A motion as a robot word is about to send it, for a guard (fbrl_robot_set_guard).
 * Poses are in the arm's frame (after MAP-ON mapping and BASE-OFFSET), inches and degrees. */
typedef enum fbrl_robot_move_kind {
    FBRL_ROBOT_MOVE_POSE = 1, /* to pose v[0..5], or dist back from it along the tool axis (APPRO) */
    FBRL_ROBOT_MOVE_DEPART,   /* dist back along the tool axis from where the arm stands */
    FBRL_ROBOT_MOVE_JOG,      /* by v[0..2] (always straight) */
    FBRL_ROBOT_MOVE_JOINTS,   /* to joint angles v[0..4], degrees (MA) */
    FBRL_ROBOT_MOVE_DJOINTS,  /* by joint increments v[0..4], degrees (MI, JOINT) */
    FBRL_ROBOT_MOVE_MOTOR,    /* motor v[0] (1..) by v[1] encoder pulses */
    FBRL_ROBOT_MOVE_READY,    /* to the arm's READY position */
    FBRL_ROBOT_MOVE_HOME,     /* HOME: the position registers are set, the arm does not move */
    FBRL_ROBOT_MOVE_OTHER     /* a motion the host cannot follow (ALIGNTOOL, a raw RAPL line) */
} fbrl_robot_move_kind;

typedef struct fbrl_robot_move {
    fbrl_robot_move_kind kind;
    int straight; /* a straight-line motion (,S) */
    double v[6];
    double dist;      /* POSE: the approach distance (0: the pose itself); DEPART: the distance */
    const char *word; /* the FBRL word sending it */
} fbrl_robot_move;

/* What a guard can check now (fbrl_robot_guard.state). */
typedef enum fbrl_robot_guard_state {
    FBRL_ROBOT_GUARD_EMPTY = 0, /* nothing described: nothing to check */
    FBRL_ROBOT_GUARD_OFF = 1,   /* a cell is described and the guard switched off (CELL-GUARD-OFF) */
    FBRL_ROBOT_GUARD_ON = 2     /* every motion is checked */
} fbrl_robot_guard_state;

/* The guard every motion passes (docs/workcell.md "The guard"). The robot layer makes each
 * motion one step that no other task can enter: it waits for the arm (other tasks' claims,
 * the last motion's end), then calls check, defines the scratch point and sends the motion,
 * then calls done with the motion command's result (FBRL_OK: the controller took it), all
 * without letting another task run. check may read the arm (fbrl_robot_joints: the arm
 * stands by then) and returns FBRL_OK to let the motion go; it refuses with
 * fbrl_robot_fail(r, FBRL_ROBOT_THROW_REFUSED, message) (nothing is sent). state says
 * whether a motion the robot layer did not check (a line sent on the link directly,
 * fbrl_link_set_gate) must be refused (FBRL_ROBOT_GUARD_ON); NULL: as ON. */
typedef struct fbrl_robot_guard {
    fbrl_status (*check)(void *ctx, struct fbrl_robot *r, const fbrl_robot_move *m);
    void (*done)(void *ctx, struct fbrl_robot *r, const fbrl_robot_move *m, fbrl_status result);
    void *ctx;
    fbrl_robot_guard_state (*state)(void *ctx);
} fbrl_robot_guard;

/* What a guard throws when it refuses a motion (catchable; the work cell's -302). */
#define FBRL_ROBOT_THROW_REFUSED FBRL_VM_THROW_OF_STATUS(FBRL_ERANGE)

/* A robot context: caller-owned, fields private. Keep it at a fixed address while the
 * VM uses it (the words point at it) and while its link is in use (the link's gate points
 * at it: fbrl_robot_set_link(r, NULL) lets the link go on without it). */
typedef struct fbrl_robot {
    fbrl_vm *vm;
    fbrl_link *link;  /* NULL = offline */
    fbrl_glossary *g; /* NULL = no mapping, no metric */
    /* I-8: the command line being built by SEND-* (sent by SEND-CR) */
    char line[FBRL_LINK_LINE_MAX + 1];
    size_t len;
    int line_bad; /* the line overflowed: SEND-CR refuses it */
    /* I-4: settings collected by SETBAUDRATE ... and applied by SETUPUART */
    fbrl_uart_config comm;
    /* scratch controller points (alternating, so a running motion keeps its target) */
    unsigned scratch;
    /* BASE-OFFSET: the user's world frame as seen from the arm's base */
    double base[4]; /* dx dy dz (in), dO (deg) */
    /* timers */
    uint64_t mark_ms; /* unused: START-TIMER marks are per task (fbrl_vmx_task_timer) */
    int mark_set;
    int teaching; /* GET-CAL-POINTS is running */
    /* devices */
    fbrl_robot_device dev[FBRL_ROBOT_MAX_DEVICES];
    /* raw output (TYPE-COM, EMIT-COM, PRINT-LOC): an unfinished raw line is on the
     * controller's line while the link has sent nothing since (raw_link_mark) */
    int raw_open;
    uint64_t raw_link_mark;
    size_t raw_len; /* that line's length; its text after the tib (FBRL_ROBOT_TIB) */
    /* the controller's last error code seen by a robot word (-1 none) */
    int last_error;
    /* safety (docs/robot.md, "Stopping safely"): a motion was sent and not yet seen to
     * end (the next motion or FINISH first waits for it, reading W5, so the controller
     * never sits in a queued command that HALT could not reach), its line, and the
     * outputs this context ever switched on (bit n-1 = output n) */
    int moving;
    char motion[FBRL_LINK_LINE_MAX + 1];
    uint32_t outputs_on;
    /* the controller went away (a word saw FBRL_EDISCONNECTED); relink, if set, brings
     * it back before the next robot word (fbrl_robot_set_relink) */
    int lost;
    fbrl_status (*relink)(void *ctx, struct fbrl_robot *r);
    void *relink_ctx;
    /* a person at a terminal (fbrl_robot_set_console): progress of long waits, and
     * (tell) what a motion started and when a wait for it ended */
    fbrl_robot_progress_fn progress;
    void *progress_ctx;
    int tell;
    fbrl_robot_event_fn on_event; /* fbrl_robot_set_events */
    void *event_ctx;
    fbrl_robot_watch_fn watch; /* fbrl_robot_set_watch */
    void *watch_ctx;
    fbrl_loc target; /* tell: the location a motion word is sending the arm to */
    int have_target;
    /* the guard on every motion (fbrl_robot_set_guard), and a count that changes whenever
     * the arm may have gone where the host cannot tell (a link set, HALT, a safe stop, a
     * motion the guard did not check) */
    fbrl_robot_guard guard;
    unsigned long where_epoch;
    /* the link's gate (fbrl_link_set_gate): the one motion line the robot layer checked and
     * is sending now (NULL none) */
    const char *armed;
    /* a C caller's motion (fbrl_robot_motion): errors go to its message, not thrown */
    char *c_msg;
    size_t c_cap;
    int c_code;    /* the Forth code the error would have thrown (0 none) */
    int c_refused; /* the guard refused it */
    /* scratch storage in the VM's data space (made at install) */
    fbrl_cell tib; /* FBRL_ROBOT_TIB bytes, then FBRL_LINK_LINE_MAX for the raw line */
} fbrl_robot;

/* Bind every robot word into vm. link NULL = offline (the words exist and throw when
 * used); g NULL = no mapping and no metric conversion. r must stay valid as long as
 * the VM runs. FBRL_EINVAL for a NULL vm or r; FBRL_ENOMEM if the dictionary is full. */
FBRL_API fbrl_status fbrl_robot_install(fbrl_vm *vm, fbrl_robot *r, fbrl_link *link, fbrl_glossary *g);

/* Connect (or, with NULL, disconnect) a controller later, e.g. after the monitor
 * opened a port. The link should already be connected (fbrl_link_connect). The robot
 * puts its gate on the link (fbrl_link_set_gate) and takes it off the link it leaves: a
 * motion line that did not pass the guard is refused there (FBRL_EGUARD) while the guard
 * is on, unless its caller went around the guard explicitly (fbrl_link_unguarded; told to
 * the event callback as "UNGUARDED"). */
FBRL_API fbrl_status fbrl_robot_set_link(fbrl_robot *r, fbrl_link *link);

/* What fbrl_robot_safe_stop() found and did: result FBRL_OK, or why the stop is incomplete
 * (FBRL_EOFFLINE, or the link's stop's, stop.result); whether a motion had been sent and
 * not seen to end, and its line ("" none); the link's safe stop (halted, the outputs
 * switched off, left on and not known, STATUS, where the arm stands). */
typedef struct fbrl_robot_stop {
    fbrl_status result;
    int was_moving;
    char motion[FBRL_LINK_LINE_MAX + 1];
    fbrl_link_stop stop;
} fbrl_robot_stop;

/* Make the cell safe after an abort (Ctrl-C): fbrl_link_safe_stop() with the outputs this
 * context switched on, after a command the controller already has ended (at most
 * FBRL_ROBOT_STOP_DRAIN_MS). Never throws; blocking, bounded by the link's timeouts. out
 * must not be NULL. */
#define FBRL_ROBOT_STOP_DRAIN_MS 5000u
FBRL_API fbrl_status fbrl_robot_safe_stop(fbrl_robot *r, fbrl_robot_stop *out);

/* ---- for a host that sends the commands on a link itself (the Python bindings) ---- */

/* The same stop without a robot context, in the same report: fbrl_link_safe_stop() with
 * the outputs the host switched on (bit n-1 = output n) and motion, the last motion line it
 * sent and has not seen end (NULL: none), named in the report. FBRL_EOFFLINE for a NULL
 * link. */
FBRL_API fbrl_status fbrl_robot_safe_stop_link(fbrl_link *link, uint32_t outputs, const char *motion,
                                               fbrl_robot_stop *out);

/* What a command line does to the cell, as the robot words class a raw line by its first
 * word (docs/robot.md, "Stopping safely"): *effect gets the bits below (0: none of them),
 * *outputs_on (may be NULL) the outputs an OUTPUT line switches on (bit n-1 = output n). */
#define FBRL_ROBOT_LINE_MOTION 0x1u /* it may move the arm: a motion, RUN, or a command the
                                     * library does not know */
#define FBRL_ROBOT_LINE_FINISH 0x2u /* FINISH: its prompt comes once the motion has ended */
#define FBRL_ROBOT_LINE_HALT   0x4u /* HALT: the arm stops where it is */
FBRL_API fbrl_status fbrl_robot_line_effect(const char *line, unsigned *effect, uint32_t *outputs_on);

/* Does a value line of the W5 readout (len bytes) show the arm at rest, every commanded
 * velocity zero? A title line or a damaged one (flawed != 0) does not (0). The test the
 * robot words make before a motion or FINISH, so the controller never waits inside one,
 * deaf to HALT. */
FBRL_API int fbrl_robot_still_line(const char *line, size_t len, int flawed);

/* A function that reconnects the controller (reopens the port, fbrl_link_init,
 * fbrl_link_connect, fbrl_robot_set_link) and tells the user its state. The next robot
 * word calls it after the controller went away (FBRL_EDISCONNECTED); NULL (the default)
 * = that word throws "controller disconnected" instead. */
FBRL_API fbrl_status fbrl_robot_set_relink(fbrl_robot *r, fbrl_status (*fn)(void *ctx, fbrl_robot *r),
                                           void *ctx);

/* Non-zero after a robot word found the controller gone, until it is connected again
 * (fbrl_robot_set_link). */
FBRL_API int fbrl_robot_lost(const fbrl_robot *r);
/* For a person at a terminal: progress (may be NULL) shows long waits as they go
 * (motions, FINISH, timed waits, WAIT-INPUT); with tell != 0 a motion word also says
 * what it started ("MOV: the arm is moving to X ... in") and a word that waited for the
 * arm says when it stopped. Off by default (plans, pipes and programs get no chatter). */
FBRL_API void fbrl_robot_set_console(fbrl_robot *r, fbrl_robot_progress_fn progress, void *ctx, int tell);
/* Tell fn of every device action and timed wait (fbrl_robot_event; NULL: nobody). */
FBRL_API void fbrl_robot_set_events(fbrl_robot *r, fbrl_robot_event_fn fn, void *ctx);
/* Let fn look at the arm while it moves (fbrl_robot_watch_fn; NULL: nobody): a live view. */
FBRL_API void fbrl_robot_set_watch(fbrl_robot *r, fbrl_robot_watch_fn fn, void *ctx);

/* The name of robot word i (0, 1, ...) in the order fbrl_robot_install() defines them;
 * NULL past the last. (ASC is among them; a VM that has its own ASC keeps it.) */
FBRL_API const char *fbrl_robot_word(size_t i);

/* Limits of a device's DISPENSE pulse (PULSE-WIDTH), ms. */
#define FBRL_ROBOT_PULSE_MIN 1u
#define FBRL_ROBOT_PULSE_MAX 60000u

/* Named devices, as a workspace keeps them (fbrl/workspace.h). device_of: the device the
 * word xt names (its port, direction and pulse width in *d; d->addr its data address), or
 * FBRL_ENOENT. define_device: make the word `name` a device as OUTPUT-DEVICE / INPUT-DEVICE
 * would, or, when name already is a device word, change that device in place.
 * FBRL_ERANGE for a port outside 1..FBRL_ROBOT_IO_MAX or a pulse width outside
 * FBRL_ROBOT_PULSE_MIN..MAX, FBRL_EFULL when the table is full, FBRL_ETHROW (thrown in the
 * VM, no word left) when the word cannot be made. devices_free: free table slots. */
FBRL_API fbrl_status fbrl_robot_device_of(const fbrl_robot *r, fbrl_cell xt, fbrl_robot_device *d);
FBRL_API fbrl_status fbrl_robot_define_device(fbrl_robot *r, const char *name, size_t len, int port,
                                              int output, uint32_t pulse_ms);
FBRL_API size_t fbrl_robot_devices_free(const fbrl_robot *r);

/* Set (or with NULL remove) the guard every motion word consults (fbrl/cell.h installs one). */
FBRL_API fbrl_status fbrl_robot_set_guard(fbrl_robot *r, const fbrl_robot_guard *g);
/* A guard's (or a robot word's) error: thrown in the VM as code with msg, or, inside
 * fbrl_robot_motion(), handed to its caller as the message. Returns FBRL_ETHROW. */
FBRL_API fbrl_status fbrl_robot_fail(fbrl_robot *r, int code, const char *msg);
/* A motion from C (TEACH, a console, a station), through the same gate as the robot words:
 * m->kind says what (FBRL_ROBOT_MOVE_POSE: POINT a scratch location at v[0..5], in the arm's
 * frame, then MOVE there, or APPRO when dist != 0; DEPART; JOG; JOINTS (MA) and DJOINTS (MI)
 * in degrees; MOTOR; READY; HOME), m->straight adds ,S where the command takes it, m->word
 * names it in messages (NULL: "MOTION"). Returns once the controller has taken the motion
 * (the next motion waits for its end): FBRL_OK; FBRL_EGUARD when the guard refused it
 * (nothing was sent); FBRL_ECONTROLLER when the controller refused it (fbrl_robot_last_error
 * has the code); FBRL_EINVAL for a kind it cannot send; else the status that stopped it
 * (FBRL_EOFFLINE, FBRL_EDISCONNECTED, FBRL_EMAYBE ...). msg (cap bytes, may be NULL) gets the
 * message a robot word would have thrown ("JOG: would hit POST at ...; nothing was sent"),
 * or "" on success. Not from inside a robot word. */
FBRL_API fbrl_status fbrl_robot_motion(fbrl_robot *r, const fbrl_robot_move *m, char *msg, size_t cap);
/* Changes whenever the arm may have moved where the host cannot follow it. */
FBRL_API unsigned long fbrl_robot_where_epoch(const fbrl_robot *r);
/* The arm's joint angles (degrees) read from the controller (W2) once the motion in progress
 * has ended; *n gets how many (up to FBRL_RAPL_MAX_AXES). Throws in the VM on error
 * (FBRL_ETHROW-like statuses as the robot words return them), naming word. */
FBRL_API fbrl_status fbrl_robot_joints(fbrl_robot *r, const char *word, double *q, unsigned *n);
/* The same reading whole: pulses, joints and world (W2). */
FBRL_API fbrl_status fbrl_robot_position(fbrl_robot *r, const char *word, fbrl_rapl_pos *p);
/* The arm's motor pulses once the motion in progress has ended: one line of W1, about a
 * quarter of W2 on the wire (*n values, up to FBRL_RAPL_MAX_AXES). FBRL_EPROTOCOL, without
 * a throw, when the reading was not one clean line (read W2 instead); other errors throw
 * as fbrl_robot_joints. */
FBRL_API fbrl_status fbrl_robot_pulses(fbrl_robot *r, const char *word, long *pulses, unsigned *n);

/* BASE-OFFSET: dX dY dZ (inches) dO (degrees). set refuses a non-finite value (FBRL_ENONFINITE). */
FBRL_API fbrl_status fbrl_robot_base_offset(const fbrl_robot *r, double base[4]);
FBRL_API fbrl_status fbrl_robot_set_base_offset(fbrl_robot *r, const double base[4]);

/* The controller error code of the last robot word that failed with a controller
 * error (e.g. 29), -1 if none; the same number RAPL-ERROR pushes. */
FBRL_API int fbrl_robot_last_error(const fbrl_robot *r);

#ifdef __cplusplus
}
#endif
#endif
