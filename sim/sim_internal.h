/* SPDX-License-Identifier: MIT */
/* sim_internal.h - state shared by the emulator's source files. */
#ifndef FBRL_SIM_INTERNAL_H
#define FBRL_SIM_INTERNAL_H

#include <pthread.h>
#include <stdio.h>

#include "fbrl/arm.h"
#include "sim_errors.h"
#include "fbrlsim.h"
#include "fbrl/cell.h"

#define SIM_LINE_MAX   80 /* longest command line (error 025 beyond) */
#define SIM_NAME_MAX   8
#define SIM_MAX_LOCS   100
#define SIM_MAX_VARS   100
#define SIM_MAX_PROGS  16 /* the program table (S1 ALLOC: "leaving 16 programs") */
#define SIM_IO         16
#define SIM_AIN        8       /* analog inputs (A/D channels), volts */
#define SIM_GRIP_MAX   2.0     /* servo gripper fully open, in */
#define SIM_EXTRA_RATE 10000.0 /* extra axis, pulses/s at 100 % */

typedef struct sim_loc {
    char name[SIM_NAME_MAX + 1]; /* without '#' */
    int precision;               /* 1: pulses in p, 0: cartesian in v */
    double v[6];
    long p[FBRL_ARM_AXES_MAX];
} sim_loc;

typedef struct sim_var {
    char name[SIM_NAME_MAX + 1];
    double v;
} sim_var;

typedef struct sim_prog {
    char name[SIM_NAME_MAX + 1];
    char **lines;
    int n;
} sim_prog;

typedef struct sim_chan {
    long baud;
    char parity; /* N E O */
    int data, stop;
    char handshake; /* N X */
    int echo;
} sim_chan;

/* Output text collected for the reply of one command. */
typedef struct sim_out {
    char *buf;
    size_t len, cap;
} sim_out;

enum { PS_IDLE, PS_BUSY, PS_STREAM, PS_THINK };

#define SIM_RX_DEFAULT      128    /* the controller's receive buffer with --baud */
#define SIM_RX_UNPACED      65536  /* without --baud: stands in for the kernel's buffer */
#define SIM_WIRE_MAX        256    /* host bytes taken off the OS but still on the wire */
#define SIM_MARK            (-1.0) /* queue time of a PARMRK mark: no line time of its own */
#define SIM_STALL_MAX_MS    600000
#define SIM_CMD_TIME_MAX_MS 10000.0
#define SIM_POLL_BUSY       0.005 /* s: how often WAIT and RUN look at their conditions */
#define SIM_LISTEN_BACKLOG  4

/* sim_line.c: how fast characters are handed over (a bucket of about 1 ms). */
typedef struct sim_pace {
    double tokens, t;
} sim_pace;

/* sim_line.c: the serial line, each direction a UART (pacing, faults, parity, XON/XOFF). */
typedef struct sim_line {
    double byte_time; /* 10 bit times with --baud; 0: unpaced */
    double f_drop, f_corrupt, f_noise;
    int f_stall; /* ms */
    unsigned long long rng;
    long parity_in, parity_out; /* parity errors: dropped by our UART / marked for the host */
    /* host -> controller: on the wire (end times), then the receive buffer */
    unsigned char wire[SIM_WIRE_MAX];
    double wire_end[SIM_WIRE_MAX];
    int whead, wn;
    double rx_free; /* when the last byte on the wire is complete */
    int backlog;    /* bytes seen waiting in the OS at the last read */
    unsigned char *rx;
    double *rx_t; /* when each byte in the receive buffer arrived (its last bit) */
    int rxcap, rxhead, rxcount;
    int rx_stale; /* bytes that were in the buffer before this round's deliveries */
    double pop_t; /* when the controller took the byte it is acting on (sim_emit) */
    int pop_valid;
    long overruns;
    int xoff_sent, peer_xoff;
    /* After our XOFF has reached the host, its bytes stay where they are (in the kernel,
     * as in a real host's UART) until our XON, unless the host goes on sending: */
    int holding;       /* our XOFF is out: nothing more is taken off the OS */
    double hold_from;  /* when the host had our XOFF (real s) */
    int hold_base;     /* bytes the host had sent by then plus a grace; -1 not yet measured */
    int host_ignores;  /* the host sent more after our XOFF: its bytes flow (and overrun) */
    long ignored_xoff; /* times a host was seen ignoring our XOFF */
    int flow;          /* XON/XOFF on (channel 0), as last seen */
    int host_ixon;     /* the host's tty has IXON (1), not (0), unknown: TCP (-1) */
    /* controller -> host */
    int urgent; /* XON/XOFF waiting to go out first, -1 none */
    double urgent_q;
    unsigned char *tx;
    double *txq; /* when each byte was queued (SIM_MARK for marks) */
    size_t txlen, txcap, txoff;
    double tx_free;            /* when the last byte sent is complete */
    double tx_resume;          /* the host's XON: nothing starts before it */
    double tx_hold_until;      /* stall fault */
    sim_pace tx_pace, rx_pace; /* hand-over pace in each direction */
} sim_line;

/* sim_io.c: the transport under the line. */
typedef struct sim_io {
    char path[256];
    char *link_path;
    int master, slave; /* pty (slave kept open so the master never hangs up) */
    int lfd, conn;     /* TCP listener and client */
    int fd;            /* fd the line uses: master or conn, -1 if none */
    int ino;           /* --greet-pty: inotify on the pty slave (a client opened it), -1 none */
} sim_io;

/* sim_term.c: terminal mode (line editor, reply framing, streams). */
typedef struct sim_term {
    char line[SIM_LINE_MAX + 1];
    int len, overlong, last_cr, help;
    int ps;
    char cur[SIM_LINE_MAX + 1]; /* line being executed while PS_BUSY / PS_THINK */
    sim_out out;
    int stream_kind; /* W1 W3 W5 / WE1 WE3 WE5: 1,3,5, 11,13,15 */
    double stream_next;
    double think_until; /* PS_THINK: the controller is still reading the line */
    int last_error;     /* -1 none (STATUS shows it) */
    int aci;            /* 1: ACI (binary host protocol) mode, not terminal mode */
    int aci_st, aci_n;  /* sim_aci.c: where the host is in the switch handshake */
    unsigned char aci_pkt[16];
    int ctrl_z;                       /* the previous byte was Ctrl-Z (two of them: back to ACI mode) */
    double cmd_t;                     /* simulated time the running line was submitted (stamped log) */
    int cmd_logged;                   /* the running line is to be logged when it ends (stamped log) */
    char last_prog[SIM_NAME_MAX + 1]; /* STATUS's program line: the last program RUN */
    int last_prog_line, last_prog_err;
    char edit_prog[SIM_NAME_MAX + 1]; /* EDIT's program (sim_h_prog.c) */
    int editing;                      /* edit mode: typed lines go into edit_prog */
} sim_term;

/* sim_events.c: control lines from the FIFO and the --inputs script. */
struct sim_event {
    double t;
    char *cmd;
};
typedef struct sim_events {
    int ctl; /* control FIFO */
    char ctlbuf[256];
    size_t ctllen;
    int ctl_overlong; /* the FIFO line being read is longer than ctlbuf: dropped */
    struct sim_event *list;
    int n, next;
} sim_events;

/* sim_mem.c: the controller's battery-backed memory of names (and the tool). */
typedef struct sim_mem {
    sim_loc locs[SIM_MAX_LOCS];
    int nlocs;
    sim_var vars[SIM_MAX_VARS];
    int nvars;
    sim_prog *progs;
    int nprogs;
    int tool_set;
    char tool_name[SIM_NAME_MAX + 1];
    double tool[6];
    int teach; /* TEACH mode: 1 cartesian, 2 precision points */
    char teach_name[SIM_NAME_MAX + 1];
    int teach_next;
} sim_mem;

/* sim_motion.c: the arm, one motion segment at a time, evaluated from simulated time. */
typedef struct sim_arm {
    double q[FBRL_ARM_AXES_MAX];  /* joints at the segment's start (or at rest) */
    double qt[FBRL_ARM_AXES_MAX]; /* joints at its end */
    double pa[6], pb[6];          /* straight-line segment poses */
    int collide;                  /* this segment ends at a collision: its command answers
                                       * SIM_E_COLLISION once the arm stands */
    int moving, straight;
    double mt0, mt1;                       /* simulated start and end */
    double xpos, xtarget, xhome, xt0, xt1; /* extra axis, pulses */
    int xmoving, xhomed;
    const fbrl_arm *model; /* the arm: geometry, limits, speeds, axes */
    double speed;
    int homed, power;
    int locked[FBRL_ARM_AXES_MAX], limp[FBRL_ARM_AXES_MAX];
} sim_arm;

/* GAIN: each motor's three servo parameters, in the order GAIN takes them; a lab's
 * controller showed 8,.25,100 (docs/fbrlsim.md). They do not change the ideal servo model. */
#define SIM_GAIN_PARAMS 3

/* sim_h_io.c: what surrounds the arm: I/O, gripper, serial channels, pendant. */
typedef struct sim_dev {
    int in[SIM_IO], out_[SIM_IO];
    double ain[SIM_AIN]; /* analog inputs: live signals, not kept in the state file */
    double grip, grip_force, object;
    sim_chan chan[2];
    int flash, manual;
    int metric; /* METRIC: lengths typed and shown in mm (kept in the state file) */
    double gain[FBRL_ARM_AXES_MAX + 1][SIM_GAIN_PARAMS]; /* [motor 1..n] */
} sim_dev;

/* sim_cmd.c: the program being RUN. */
typedef struct sim_run {
    sim_prog *prog;
    int pc;
    long left;
} sim_run;

struct fbrl_sim {
    fbrl_sim_options opt;
    char *state_path, *log_path, *control_path;
    FILE *log;
    FILE *ctl_out; /* control-line answers and refusals, or NULL */
    int wake[2];
    int stop; /* set by fbrl_sim_stop (atomic builtins) */
    pthread_t thread;
    int thread_started;
    double t0;         /* real monotonic start */
    double clock_back; /* with opt.clock: sim_now reads this much earlier (W5's difference) */
    sim_line line;
    sim_io io;
    sim_term term;
    sim_events events;
    sim_mem mem;
    sim_arm arm;
    sim_dev dev;
    sim_run run;
    fbrl_cell_model cell; /* --cell: the work cell (sim_cell.c) */
    fbrl_cell_obj *cell_obj;
    int cell_on;
    int model_given; /* --model was given: the state file must be of that arm */
    int dirty;
    int save_warned; /* told stderr once that the state file cannot be written */
};

/* The arm's axis count (its model's). */
static inline int sim_naxes(const fbrl_sim *s) { return (int)s->arm.model->naxes; }

/* sim_cell.c: the work cell (--cell); where a motion to qt (or straight to pose pb, of the
 * tool point tool inches past the flange) meets it: the fraction of the way and the joints
 * there (1.0: clear). */
#define SIM_CELL_MAX 256
int sim_cell_load(fbrl_sim *s, const char *path, char *err, size_t errlen);
double sim_cell_stop(fbrl_sim *s, double tool, const double *qt, const double *pb, double *qstop);

/* sim_clock.c */
double sim_mono(void);
double sim_real_now(const fbrl_sim *s); /* real seconds since start */
double sim_now(const fbrl_sim *s);      /* simulated seconds since start */

/* sim_msg.c */
/* An error message into err[errlen] (nothing when err is NULL or errlen 0). */
void sim_seterr(char *err, size_t errlen, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* sim_line.c */
int sim_line_init(sim_line *l, long baud, int rx_buffer);
void sim_line_free(sim_line *l);
int sim_line_faults(sim_line *l, const char *spec, char *err, size_t errlen);
void sim_emit(fbrl_sim *s, const char *bytes, size_t n); /* controller output onto the line */
int sim_line_tx_pending(const sim_line *l);
void sim_line_hold(sim_line *l, double until);
int sim_line_write(fbrl_sim *s, int fd, double now);
int sim_line_read(fbrl_sim *s, int fd, double now);
void sim_line_deliver(fbrl_sim *s, double now);
int sim_line_rx_pop(fbrl_sim *s);
int sim_line_rx_allow(const sim_line *l, double now);
/* Does the host honour our XOFF? flow: XON/XOFF is on (channel 0's handshake). */
void sim_line_hold_check(sim_line *l, int fd, double now, int flow, int host_ixon);
double sim_line_due(const sim_line *l, double now, double limit);
int sim_line_wants_write(const sim_line *l, double now);
void sim_line_reset(sim_line *l);

/* sim_io.c */
int sim_io_open_pty(sim_io *io, int greet, char *err, size_t errlen); /* greet: watch opens */
int sim_io_open_tcp(sim_io *io, int port, char *err, size_t errlen);
int sim_io_accept(sim_io *io);          /* 1: a new client */
int sim_io_close_client(sim_io *io);    /* 1: a client was closed */
int sim_io_pty_opened(sim_io *io);      /* times the pty was opened since the last call */
int sim_io_host_ixon(const sim_io *io); /* the host's tty has IXON: 1, 0; -1 not a pty */
void sim_io_close(sim_io *io);

/* sim_term.c */
void sim_term_reset(sim_term *t);
void sim_term_greet(fbrl_sim *s);
void sim_term_process(fbrl_sim *s);
double sim_term_due(const sim_term *t, const sim_line *l, double now, double limit);

/* sim_aci.c: ACI mode, the binary host protocol a controller may power up in */
int sim_aci_byte(fbrl_sim *s, unsigned char b); /* 1: the byte is terminal mode's now */
void sim_aci_enter(fbrl_sim *s);                /* Ctrl-Z Ctrl-Z from terminal mode */

/* sim_events.c */
int sim_events_open_fifo(sim_events *ev, const char *path, char *err, size_t errlen);
void sim_events_read_fifo(fbrl_sim *s);
int sim_events_load(sim_events *ev, const char *path, char *err, size_t errlen);
void sim_events_run(fbrl_sim *s);
double sim_events_due(const fbrl_sim *s, double limit);
void sim_events_free(sim_events *ev);

/* sim_cmd.c */
enum { EXEC_DONE, EXEC_BLOCK };
int sim_exec(fbrl_sim *s, const char *line, int *err); /* EXEC_*; *err = RAPL code or -1 */
int sim_exec_step(fbrl_sim *s, int *err);              /* continue a blocked or running command */
const char *sim_help_hint(const char *word);           /* HELP-mode hint for a first word, or NULL */

/* sim_out.c */
void sim_out_printf(sim_out *o, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* sim_motion.c */
void sim_arm_update(fbrl_sim *s); /* finish motions whose time has come */
void sim_joints_now(fbrl_sim *s, double q[FBRL_ARM_AXES_MAX]);
/* The arm's inverse kinematics and limits (fbrl/arm.h) as the controller reports them: 0,
 * 029 (out of reach) or the joint's out-of-range code. */
int sim_arm_ik(const fbrl_arm *m, const double pose[6], double tool, const double *hint, double *q);
int sim_arm_check(const fbrl_arm *m, const double *q);

/* sim_h_read.c */
void sim_stream_line(fbrl_sim *s, sim_out *o); /* the next line of a W1/W3/W5 readout */

/* sim_control.c */
int sim_control(fbrl_sim *s, const char *line); /* 0 ok, -1 bad line; s NULL: only check */
/* The same, with the reason for a refusal in why[whylen]; answers queries to s->ctl_out. */
int sim_control_why(fbrl_sim *s, const char *line, char *why, size_t whylen);
/* Writes a control answer or refusal line to s->ctl_out (if any). */
void sim_control_say(fbrl_sim *s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* sim_mem.c */
void sim_free_memory(fbrl_sim *s);

/* sim_h_prog.c: a line typed in edit mode (EDIT); 0 or a RAPL error code */
int sim_prog_edit(fbrl_sim *s, const char *line, int blank);

/* sim_defaults.c */
void sim_defaults(fbrl_sim *s); /* power-up settings for the arm model in s->arm.model */

/* sim_state.c */
int sim_state_load(fbrl_sim *s, char *err, size_t errlen); /* 0 ok (missing file = ok) */
int sim_state_save(fbrl_sim *s);

#endif
