/* robot_internal.h - shared by robot.c (I-5, I-6, I-8), robot_comm.c (I-4) and
 * robot_io.c (peripherals, timers). Private to the library. */
#ifndef FBRL_LANG_ROBOT_INTERNAL_H
#define FBRL_LANG_ROBOT_INTERNAL_H

#include "fbrl/loc.h"
#include "fbrl/robot.h"
#include "words.h"

/* One parameter, as fetched by rb_params(). */
typedef struct rb_val {
    fbrl_cell i;       /* 'I': integer; 'L': the location's address */
    double f;          /* 'R' */
    const char *s;     /* 'S': text (in the VM's data space) */
    size_t n;
} rb_val;

#define RB_MAXP 8

/* Word flags. */
#define RB_PAR 1u      /* parameters always come from the input line (thesis "PAR:") */

struct rb_word;
typedef fbrl_status (*rb_fn)(fbrl_robot *r, const struct rb_word *w, rb_val *v);

/* A table entry. spec lists the parameters in stack-effect order:
 * I integer, R real (float stack), L location address, S string (c-addr u). */
typedef struct rb_word {
    const char *name;
    rb_fn fn;
    const char *spec;
    unsigned flags;
    int cmd;           /* fbrl_rapl_cmd for the generic command words, -1 otherwise */
    intptr_t arg;      /* word-specific */
    const char *stack, *help;
} rb_word;

/* Define every word of a table (each bound to r). */
fbrl_status rb_define(fbrl_robot *r, const rb_word *t, size_t n);

/* Throw a Forth exception with a message (the message is copied). */
fbrl_status rb_fail(fbrl_robot *r, int code, const char *msg);
/* Throw for a libfbrl status, prefixed with the word's name. */
fbrl_status rb_fail_st(fbrl_robot *r, const rb_word *w, fbrl_status st, const char *what);
/* Throw unless a controller is connected; a command an interrupted word left running
 * in the link is finished first. */
fbrl_status rb_online(fbrl_robot *r);
/* Throw -28 "user interrupt" if Ctrl-C (fbrl_vm_interrupt) was pressed (for words that
 * wait or loop); FBRL_OK otherwise. */
fbrl_status rb_interrupted(fbrl_robot *r);

/* Run one command from the RAPL table; controller errors become exceptions whose
 * message holds the controller's code and text. */
fbrl_status rb_cmd(fbrl_robot *r, const rb_word *w, fbrl_rapl_cmd cmd, const fbrl_rapl_arg *a, size_t n,
                   int straight);
/* Run a raw line; its output lines go to the console when print != 0. */
fbrl_status rb_raw(fbrl_robot *r, const rb_word *w, const char *line, int print);
/* Convert a finished link call's status (st) into an exception, or FBRL_OK. */
fbrl_status rb_link_result(fbrl_robot *r, const rb_word *w, fbrl_status st);

/* Console output. */
void rb_puts(fbrl_robot *r, const char *s);

/* Metric: lengths the user gives (cm when METRIC-ON) -> inches. */
double rb_len_in(const fbrl_robot *r, double v);

/* Host clock and sleep (throw when the host has none). */
fbrl_status rb_now_ms(fbrl_robot *r, uint64_t *ms);
fbrl_status rb_sleep_ms(fbrl_robot *r, uint32_t ms);

/* I-6: parse one parameter of the given kind from the input after the word. */
fbrl_status rb_parse_param(fbrl_robot *r, const rb_word *w, char kind, rb_val *v);

/* robot_comm.c: resynchronise the link after raw output; point PRINT-LOC at the port */
fbrl_status rb_resync(fbrl_robot *r);
void rb_port_writer(fbrl_robot *r);

fbrl_status rb_install_comm(fbrl_robot *r);
fbrl_status rb_install_io(fbrl_robot *r);

#endif
