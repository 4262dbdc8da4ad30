/* SPDX-License-Identifier: MIT */
/* fbrlsim.h - the RAPL-II controller emulator as an embeddable library.
 *
 * fbrl_sim_create() opens a pseudo-terminal (or a TCP port on 127.0.0.1) and
 * loads the persistent state; fbrl_sim_step() runs one slice of the event loop,
 * fbrl_sim_run() loops until fbrl_sim_stop(), fbrl_sim_start() runs that loop
 * in its own thread. All emulator state belongs to the loop's thread; only
 * fbrl_sim_stop() may be called from another thread. Unlike libfbrl, the
 * emulator allocates and uses the OS. Wire grammar: docs/rapl-commands.md. */
#ifndef FBRL_SIM_H
#define FBRL_SIM_H

#include <stddef.h>

#include "fbrl/status.h"
#include "fbrl/arm.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fbrl_sim fbrl_sim;

typedef struct fbrl_sim_options {
    int tcp_port;             /* -1: pseudo-terminal (default); 0: any free TCP port; >0: that port */
    const char *link_path;    /* pty only: a symlink to the slave device (replaced if present) */
    long baud;                /* > 0: each direction a UART at this rate (8N1: at most baud/10
                               * bytes/s, none before its start + 10 bit times), finite
                               * receive buffer */
    double time_scale;        /* simulated time runs this many times faster than real time (1) */
    const char *state_path;   /* persistent memory (locations, variables, I/O, settings) or NULL */
    const char *log_path;     /* one line per command executed, or NULL */
    const char *inputs_path;  /* time-stamped control lines "T IN 3 1", or NULL */
    const char *control_path; /* FIFO created for control lines "IN 3 1", or NULL */
    const char *faults;       /* "drop=P,corrupt=P,noise=P,stall=MS,seed=S" or NULL */
    int rx_buffer;            /* receive buffer size with baud pacing (128) */
    const char *model;        /* the arm: a name of fbrl/arm.h's table ("a255", "a465"); NULL: the
                               * state file's, else the A255 */
    double cmd_time_ms;       /* the controller's own time to read a command line before it
                               * acts, in simulated ms (0: none; docs/fbrlsim.md) */
    char parity;              /* 'N' 'E' 'O': the host channel's parity (CONFIG 0 sets it
                               * too); 0 = from the state file, else N. With E or O a
                               * corrupted byte is a parity error (docs/fbrlsim.md) */
    const char *cell_path;    /* the work cell (docs/workcell.md): motions stop where they meet
                               * it and answer 190-COLLISION; NULL: none */
    /* The simulated clock (s), instead of real time x time_scale: a dry run's virtual clock;
     * NULL: real time */
    double (*clock)(void *ctx);
    /* With clock: moves that clock forward by s when the controller itself waits for the
     * arm or a scripted input (a command blocked in it): the dry run skips that wait too */
    void (*skip)(void *ctx, double s);
    void *clock_ctx;
    /* What real clients see (docs/fbrlsim.md "Behaviours and their evidence"): */
    int aci;                 /* start in ACI (binary host protocol) mode; Ctrl-Z Ctrl-Z
                                 * returns to it from terminal mode */
    int nak;                 /* send NAK (0x15) before every error line */
    int status_extra;        /* STATUS adds fbrlsim's own lines after the 2.60 sample's */
    int echo_as_typed;       /* echo lower case as typed (the line still runs upper-cased) */
    int greet_pty;           /* send the prompt when a program opens the pty (a serial line's
                                 * controller cannot see that: off by default) */
    int log_stamped;         /* --log lines: "T STATUS LINE" (simulated s, OK/NNN) */
    const char *control_out; /* file that control-line answers and refusals are appended
                                 * to; NULL: stdout for the program, nowhere embedded */
    int control_out_stdout;  /* answer control lines on stdout (the program's default) */
} fbrl_sim_options;

void fbrl_sim_options_init(fbrl_sim_options *o);

/* Creates the emulator; on failure *out is NULL and err (if given) explains. */
fbrl_status fbrl_sim_create(fbrl_sim **out, const fbrl_sim_options *o, char *err, size_t errlen);

/* The device path of the pty slave, or "tcp:127.0.0.1:PORT". */
const char *fbrl_sim_path(const fbrl_sim *s);

/* One slice of the event loop, waiting at most timeout_ms for I/O. */
fbrl_status fbrl_sim_step(fbrl_sim *s, int timeout_ms);

/* Loops in the calling thread until fbrl_sim_stop(). */
fbrl_status fbrl_sim_run(fbrl_sim *s);

/* The emulated arm's axis count (5 for the A255, 6 for the A465): W2 and STATUS
 * show that many. Fixed after fbrl_sim_create. */
int fbrl_sim_axes(const fbrl_sim *s);
/* The emulated arm: its row of fbrl/arm.h's table. Fixed after fbrl_sim_create. */
const fbrl_arm *fbrl_sim_arm(const fbrl_sim *s);

/* Runs the loop in a new thread. */
fbrl_status fbrl_sim_start(fbrl_sim *s);

/* Asks the loop to end; callable from any thread and from a signal handler. */
void fbrl_sim_stop(fbrl_sim *s);

/* Stops and joins the loop's thread, saves the state, closes everything and
 * removes the link. NULL is ignored. */
void fbrl_sim_destroy(fbrl_sim *s);

#ifdef __cplusplus
}
#endif
#endif
