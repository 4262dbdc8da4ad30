/* SPDX-License-Identifier: MIT */
/* robot_internal.h - shared by the robot words' sources (private to the library):
 *   robot.c        binding the tables into a VM (fbrl_robot_install)
 *   robot_svc.c    errors, Ctrl-C, console, clock, the motion guard's hook
 *   robot_rline.c  what a raw RAPL line is, and the motion it makes
 *   robot_link.c   commands to the controller through the link
 *   robot_param.c  parameters from the stacks or the input (I-6), their checks
 *   robot_loc.c    locations: mapping, base offset, scratch points, the arm's position
 *   robot_motion.c robot_rapl.c robot_teach.c robot_line.c robot_comm.c robot_io.c
 *   robot_import.c: the words
 *   robot_gate.c   the one gate every motion passes (rb_motion, the link's gate, C callers)
 *   robot_safe.c   the safe stop after an abort (fbrl_robot_safe_stop)
 *   robot_guard.c  the arm's joints for a motion guard (fbrl_robot_joints)
 * Calls go downwards in that list (tables up to robot.c), never in a circle. */
#ifndef FBRL_LANG_ROBOT_INTERNAL_H
#define FBRL_LANG_ROBOT_INTERNAL_H

#include "internal_names.h"

#include "fbrl/loc.h"
#include "fbrl/robot.h"
#include "fbrl/vmx.h"

/* One parameter, as fetched by rb_params(): i for I C L A (L: the location's address),
 * f for R, s n for S T and for X given as a controller name. */
typedef fbrl_vmx_val rb_val;

#define RB_MAXP FBRL_VMX_MAXARGS

/* A robot word's row: vmx.h's one row type. spec lists the parameters in stack-effect
 * order: vmx.h's letters (I R C S T) and L location address, X location or controller
 * location name, A device address, J one real per joint of the arm; code is the
 * fbrl_rapl_cmd of the generic command words (-1 otherwise), arg the word's own number.
 * A row is five words on a 32-bit target (the firmware has about 200 rows). */
typedef fbrl_vmx_reg rb_word;
/* Every command number fits the row's code (C99 has no static assertion: a negative array
 * size fails to compile). */
typedef char rb_word_cmds_fit[FBRL_RAPL_NCMDS - 1 <= INT16_MAX ? 1 : -1];

/* Every robot word begins so (as a Lua function with luaL_check*): its robot (ctx), its row
 * (word) and its parameters v fetched by the one rule (rb_params); a failure is thrown and
 * returned before the word does anything. */
#define RB_WORD(vm, ctx, word)                   \
    fbrl_robot *r = (ctx);                       \
    const rb_word *w = (word);                   \
    rb_val v[RB_MAXP];                           \
    fbrl_status rb_word_st_ = rb_fetch(r, w, v); \
    (void)(vm);                                  \
    (void)v;                                     \
    if (rb_word_st_ != FBRL_OK)                  \
    return rb_word_st_

/* Throw a Forth exception with a message (the message is copied). */
fbrl_status rb_fail(fbrl_robot *r, int code, const char *msg);
/* Throw for a libfbrl status, prefixed with the word's name. */
fbrl_status rb_fail_st(fbrl_robot *r, const rb_word *w, fbrl_status st, const char *what);
/* Throw unless a controller is connected; a command an interrupted word left running
 * in the link is finished first. */
fbrl_status rb_online(fbrl_robot *r);
/* Lengths go out in inches: refused (nothing sent) while the link knows the controller
 * works in millimetres (the connect's STATUS, a later one, METRIC run: fbrl_link_units;
 * docs/robot.md). */
fbrl_status rb_units(fbrl_robot *r, const rb_word *w);
/* Throw -28 "user interrupt" if Ctrl-C (fbrl_vm_interrupt) was pressed (for words that
 * wait or loop); FBRL_OK otherwise. */
fbrl_status rb_interrupted(fbrl_robot *r);

/* Run one command from the RAPL table; controller errors become exceptions whose
 * message holds the controller's code and text. */
fbrl_status rb_cmd(fbrl_robot *r, const rb_word *w, fbrl_rapl_cmd cmd, const fbrl_rapl_arg *a, size_t n,
                   int straight);
/* Send a command, no waits (rb_cmd without its waits for claims and the arm; checked: the
 * step rb_motion checked it, the link's gate lets it through). */
fbrl_status rb_send(fbrl_robot *r, const rb_word *w, fbrl_rapl_cmd cmd, const fbrl_rapl_arg *a, size_t n,
                    int straight, int checked);
/* Send a raw line (checked: as rb_send); its output lines go to the console when print != 0. */
fbrl_status rb_raw_send(fbrl_robot *r, const rb_word *w, const char *line, int print, int checked);

/* Wait until a motion this context sent has ended (the commanded velocity, W5, one line
 * a round, a round every RB_STILL_POLL_MS or as fast as the line allows, until it reads
 * zero; Ctrl-C throws), so that the next motion or FINISH never waits inside the
 * controller, deaf to HALT. */
#define RB_STILL_POLL_MS 50u
fbrl_status rb_still(fbrl_robot *r, const rb_word *w);
/* Run a raw line; its output lines go to fn(ctx, ...). */
fbrl_status rb_raw_lines(fbrl_robot *r, const rb_word *w, const char *line,
                         void (*fn)(void *, const char *, size_t, int), void *ctx);
/* METRIC-ON: lengths the user sees are centimetres. */
int rb_metric(const fbrl_robot *r);
fbrl_status rb_show(fbrl_robot *r, const rb_word *w, const char *line, fbrl_link_line_fn fn, void *ctx);
/* Convert a finished link call's status (st) into an exception, or FBRL_OK. */
fbrl_status rb_link_result(fbrl_robot *r, const rb_word *w, fbrl_status st);

/* Console output. */
void rb_puts(fbrl_robot *r, const char *s);

/* Metric: lengths the user gives (cm when METRIC-ON) -> inches. */
double rb_len_in(const fbrl_robot *r, double v);

/* Host clock and sleep (throw when the host has none). */
fbrl_status rb_now_ms(fbrl_robot *r, uint64_t *ms);
fbrl_status rb_sleep_ms(fbrl_robot *r, uint32_t ms);
fbrl_status rb_wait_ms(fbrl_robot *r, const char *who, uint32_t ms);

/* Beside other tasks: wait until until_us (host clock) letting them run; FBRL_OK when
 * it has come, else return the status (a yield: the word runs again, see vmx.h). */
fbrl_status rb_pause_until(fbrl_robot *r, uint64_t until_us);
uint64_t rb_now_us(fbrl_robot *r);
#define RB_US_PER_MS 1000u

/* Any control character counts as blank (as the engine's parser has it). */
static inline int rb_blank(char c) { return (unsigned char)c <= ' '; }

/* robot_link.c: W1 W3 W5 WE1 WE3 WE5 readings on the console */
fbrl_status rb_stream(fbrl_robot *r, const rb_word *w, fbrl_rapl_cmd cmd);

/* robot_param.c: I-6: parse one parameter of the given kind from the input after the word;
 * all of a word's parameters (docs/robot.md's one rule); argument checks that throw naming
 * the word. */
fbrl_status rb_parse_param(fbrl_robot *r, const rb_word *w, char kind, rb_val *v);
fbrl_status rb_params(fbrl_robot *r, const rb_word *w, rb_val *v);
/* rb_params into all RB_MAXP values, those past the word's parameters zero. */
fbrl_status rb_fetch(fbrl_robot *r, const rb_word *w, rb_val *v);
/* The arm's axes: the link's configuration (5 when offline). Parameter letter J in a
 * word's spec stands for one real per axis. */
unsigned rb_naxes(const fbrl_robot *r);
fbrl_status rb_name_arg(fbrl_robot *r, const rb_word *w, const rb_val *v, char *buf, size_t cap);
fbrl_status rb_range(fbrl_robot *r, const rb_word *w, const char *what, fbrl_cell v, fbrl_cell lo,
                     fbrl_cell hi);
fbrl_status rb_finite(fbrl_robot *r, const rb_word *w, const rb_val *v, size_t n);

/* robot_loc.c: a host location read (finite) or written, naming the word; the user's frame
 * to the arm's (MAP-ON, BASE-OFFSET) and back (map = 0: no unmapping); a scratch controller
 * point at arm coordinates; the arm's position from W2 (after FINISH when finish != 0). */
fbrl_status rb_loc_read(fbrl_robot *r, const rb_word *w, fbrl_cell addr, fbrl_loc *out);
fbrl_status rb_loc_write(fbrl_robot *r, const rb_word *w, fbrl_cell addr, const fbrl_loc *in);
fbrl_status rb_to_arm(fbrl_robot *r, const rb_word *w, const fbrl_loc *user, fbrl_loc *arm);
fbrl_status rb_from_arm(fbrl_robot *r, const rb_word *w, const fbrl_loc *arm, fbrl_loc *user, int map);
fbrl_status rb_scratch_point(fbrl_robot *r, const rb_word *w, const fbrl_loc *arm, const char **name);
fbrl_status rb_arm_where(fbrl_robot *r, const rb_word *w, int finish, fbrl_loc *arm);

/* robot_svc.c: the arm's position became unknown to the host (fbrl_robot_where_epoch). */
void rb_where_lost(fbrl_robot *r);

/* robot_rline.c: what a raw RAPL line is (its first word), whether it can move the arm (a
 * motion, RUN, or a word the host does not know), whether it leaves the arm where the host
 * cannot tell (HALT, LIMP, MANUAL, TEACH), and the motion it makes as the guard sees it
 * (FBRL_ROBOT_MOVE_OTHER: one the guard cannot follow, e.g. MOVE to a controller location). */
typedef enum rb_line_kind { RB_LINE_EMPTY, RB_LINE_CMD, RB_LINE_ASSIGN, RB_LINE_UNKNOWN } rb_line_kind;
rb_line_kind rb_line_cmd(const char *line, size_t len, fbrl_rapl_cmd *cmd);
int rb_line_moves(rb_line_kind k, fbrl_rapl_cmd cmd);
int rb_line_loses(rb_line_kind k, fbrl_rapl_cmd cmd);
void rb_line_move(const char *line, size_t len, fbrl_robot_move *m);

/* robot_gate.c: one motion as one step no other task can enter (waits first, then the
 * guard's check, the scratch point and the motion line, then the guard's notice). o says
 * what to send: cmd with a[n] (point != NULL: POINT a scratch location there first, a[0]
 * becomes its name), or the raw line (print: its output lines to the console). */
typedef struct rb_out {
    fbrl_rapl_cmd cmd;
    fbrl_rapl_arg *a;
    size_t n;
    int straight;
    const fbrl_loc *point;
    const char *raw;
    int print;
} rb_out;
fbrl_status rb_motion(fbrl_robot *r, const rb_word *w, fbrl_robot_move *m, rb_out *o);
/* The link's gate (fbrl_link_set_gate) a robot puts on its link. */
fbrl_status rb_link_gate(void *ctx, const char *line, size_t len, int unguarded);
/* A raw line from RAPL, SEND-CR, IMPORT-LOC ...: a motion through rb_motion, else sent. */
fbrl_status rb_raw(fbrl_robot *r, const rb_word *w, const char *line, int print);

/* robot_comm.c: resynchronise the link after raw output; point PRINT-LOC at the port */
fbrl_status rb_resync(fbrl_robot *r);
void rb_port_writer(fbrl_robot *r);

/* The word tables, in the order robot.c defines them. */
extern const rb_word rb_motion_words[], rb_rapl_words[], rb_teach_words[], rb_param_words[], rb_line_words[],
    rb_comm_words[], rb_io_words[], rb_comm_asc, rb_import_words[];
extern const size_t rb_motion_nwords, rb_rapl_nwords, rb_teach_nwords, rb_param_nwords, rb_line_nwords,
    rb_comm_nwords, rb_io_nwords, rb_import_nwords;

#endif
