/* sim_internal.h - state shared by the emulator's source files. */
#ifndef FBRL_SIM_INTERNAL_H
#define FBRL_SIM_INTERNAL_H

#include <pthread.h>
#include <stdio.h>

#include "arm.h"
#include "fbrlsim.h"

#define SIM_LINE_MAX 80   /* longest command line (error 025 beyond) */
#define SIM_NAME_MAX 8
#define SIM_MAX_LOCS 100
#define SIM_MAX_VARS 100
#define SIM_IO 16
#define SIM_AIN 8      /* analog inputs (A/D channels), volts */
#define SIM_GRIP_MAX 2.0  /* servo gripper fully open, in */
#define SIM_EXTRA_RATE 10000.0 /* extra axis, pulses/s at 100 % */

typedef struct sim_loc {
    char name[SIM_NAME_MAX + 1]; /* without '#' */
    int precision;               /* 1: pulses in p, 0: cartesian in v */
    double v[6];
    long p[FBRL_SIM_ARM_AXES];
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
    char parity;    /* N E O */
    int data, stop;
    char handshake; /* N X */
    int echo;
} sim_chan;

/* Output text collected for the reply of one command. */
typedef struct sim_out {
    char *buf;
    size_t len, cap;
} sim_out;

enum { PS_IDLE, PS_BUSY, PS_STREAM };

struct fbrl_sim {
    fbrl_sim_options opt;
    char *state_path, *log_path, *control_path, *link_path;
    char path[256];
    /* I/O */
    int master, slave;   /* pty (slave kept open so the master never hangs up) */
    int lfd, conn;       /* TCP listener and client */
    int io;              /* fd the line uses: master or conn, -1 if none */
    int wake[2];
    int ctl;             /* control FIFO */
    char ctlbuf[256];
    size_t ctllen;
    FILE *log;
    int stop;            /* set by fbrl_sim_stop (atomic builtins) */
    pthread_t thread;
    int thread_started;
    double t0;           /* real monotonic start */
    /* line pacing and flow control */
    unsigned char *rx;
    int rxcap, rxhead, rxcount;
    double rx_credit, tx_credit, credit_time;
    int xoff_sent, peer_xoff;
    int urgent;          /* XON/XOFF waiting to go out first, -1 none */
    long overruns;
    unsigned char *tx;
    size_t txlen, txcap, txoff;
    double tx_hold_until;
    /* faults */
    double f_drop, f_corrupt, f_noise;
    int f_stall;
    long parity_in, parity_out; /* parity errors: dropped by our UART / marked for the host */
    unsigned long long rng;
    /* line editor */
    char line[SIM_LINE_MAX + 1];
    int len, overlong, last_cr, help;
    /* command processor */
    int ps;
    char cur[SIM_LINE_MAX + 1]; /* line being executed while PS_BUSY */
    sim_out out;
    int stream_kind;            /* W1 W3 W5 / WE1 WE3 WE5: 1,3,5, 11,13,15 */
    double stream_next;
    /* program being RUN */
    sim_prog *run_prog;
    int run_pc;
    long run_left;
    /* controller memory */
    sim_loc locs[SIM_MAX_LOCS];
    int nlocs;
    sim_var vars[SIM_MAX_VARS];
    int nvars;
    sim_prog *progs;
    int nprogs;
    int last_error;             /* -1 none */
    double speed;
    int homed, power, manual, flash, teach;
    char teach_name[SIM_NAME_MAX + 1];
    int teach_next;
    int locked[FBRL_SIM_ARM_AXES], limp[FBRL_SIM_ARM_AXES];
    double gain[FBRL_SIM_ARM_AXES + 1];
    int tool_set;
    char tool_name[SIM_NAME_MAX + 1];
    double tool[6];
    int in[SIM_IO], out_[SIM_IO];
    double ain[SIM_AIN];      /* analog inputs: live signals, not kept in the state file */
    double grip, grip_force, object;
    sim_chan chan[2];
    /* the arm: one motion segment at a time, evaluated from simulated time */
    double q[FBRL_SIM_ARM_AXES];      /* joints at the segment's start (or at rest) */
    double qt[FBRL_SIM_ARM_AXES];     /* joints at its end */
    double pa[6], pb[6];              /* straight-line segment poses */
    int moving, straight;
    double mt0, mt1;                  /* simulated start and end */
    double xpos, xtarget, xhome, xt0, xt1; /* extra axis 6, pulses */
    int xmoving, xhomed;
    /* scripted inputs */
    struct sim_event { double t; char *cmd; } *events;
    int nevents, next_event;
    int dirty;
    int save_warned;   /* told stderr once that the state file cannot be written */
};

/* sim_core.c */
double sim_now(fbrl_sim *s);          /* simulated seconds since start */
void sim_emit(fbrl_sim *s, const char *bytes, size_t n);
int sim_control(fbrl_sim *s, const char *line); /* 0 ok, -1 bad line */
/* An error message into err[errlen] (nothing when err is NULL or errlen 0). */
void sim_seterr(char *err, size_t errlen, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* sim_cmd.c */
enum { EXEC_DONE, EXEC_BLOCK };
int sim_exec(fbrl_sim *s, const char *line, int *err); /* EXEC_*; *err = RAPL code or -1 */
int sim_exec_step(fbrl_sim *s, int *err);  /* continue a blocked or running command */
void sim_out_printf(sim_out *o, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
const char *sim_error_text(int code);
const char *sim_help_hint(const char *word);  /* HELP-mode hint for a first word, or NULL */
void sim_arm_update(fbrl_sim *s);             /* finish motions whose time has come */
void sim_joints_now(fbrl_sim *s, double q[FBRL_SIM_ARM_AXES]);
void sim_stream_line(fbrl_sim *s, sim_out *o);
void sim_state_defaults(fbrl_sim *s);
void sim_free_memory(fbrl_sim *s);

/* sim_state.c */
int sim_state_load(fbrl_sim *s, char *err, size_t errlen); /* 0 ok (missing file = ok) */
int sim_state_save(fbrl_sim *s);

#endif
