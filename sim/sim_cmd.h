/* SPDX-License-Identifier: MIT */
/* sim_cmd.h - what the command side of the emulator shares: a command's
 * arguments, the helpers every handler group uses, and the handlers the command
 * table (sim_cmd.c) dispatches to. Calls go one way: sim_cmd.c -> handlers ->
 * motion / expressions / arguments -> names. */
#ifndef FBRL_SIM_CMD_H
#define FBRL_SIM_CMD_H

#include "sim_internal.h"

#define MAXARGS 12

typedef struct args {
    int n;
    char *v[MAXARGS];
    char buf[SIM_LINE_MAX + 1];
    const char *rest; /* raw text after the command word */
} args;

typedef int (*handler)(fbrl_sim *s, args *a, int *block);

/* sim_args.c */
/* Splits rest on commas and spaces; 0 or 014 (empty or too many arguments). */
int sim_args_split(const char *rest, args *a);
/* Removes a trailing ",S" argument; returns 1 if it was there. */
int sim_args_take_s(args *a, int need);
int sim_args_want(args *a, int lo, int hi);
/* A command without arguments that sets a mode flag (TEACH off, MANUAL off, HELP). */
int sim_arg_mode(args *a, int *flag, int on);
int sim_arg_num(fbrl_sim *s, args *a, int i, double *v);
int sim_arg_int(fbrl_sim *s, args *a, int i, long *v);
int sim_arg_axis(fbrl_sim *s, args *a, int i, int hi, long *ax);
/* A length in the controller's units (inches, or mm after METRIC) as inches. */
int sim_arg_len(fbrl_sim *s, args *a, int i, double *inches);
double sim_len_in(const fbrl_sim *s, double user);
double sim_len_out(const fbrl_sim *s, double inches);
/* SET A=B and SHIFTA A,B take two names separated by '=' or ','. */
int sim_args_two_names(args *a, char *x, char *y);

/* sim_mem.c */
/* Checks a location or variable name and upper-cases it; *prec gets the '#' flag (if prec). */
int sim_name_parse(const char *tok, int *prec, char name[SIM_NAME_MAX + 1]);
sim_var *sim_var_find(fbrl_sim *s, const char *name);
sim_loc *sim_loc_find(fbrl_sim *s, const char *name, int prec);
int sim_loc_new(fbrl_sim *s, const char *name, int prec, sim_loc **out);
int sim_loc_cart(fbrl_sim *s, const char *tok, sim_loc **out);

/* sim_expr.c */
/* Evaluates a whole expression text; 0 or an error code. */
int sim_eval(fbrl_sim *s, const char *text, double *v);

/* sim_motion.c */
double sim_tool_len(fbrl_sim *s);
/* Location by token: pose always; joints too for a precision point (*is_prec). */
int sim_loc_value(fbrl_sim *s, const char *tok, double pose[6], double q[FBRL_ARM_AXES_MAX], int *is_prec);
double sim_extra_now(fbrl_sim *s);
void sim_halt(fbrl_sim *s);
int sim_move_joints(fbrl_sim *s, const double target[FBRL_ARM_AXES_MAX]);
int sim_pose_joints(fbrl_sim *s, const double pose[6], double q[FBRL_ARM_AXES_MAX]);
int sim_move_pose(fbrl_sim *s, const double pose[6]);
int sim_move_line(fbrl_sim *s, const double pose[6], const double *qknown);
void sim_current_pose(fbrl_sim *s, double pose[6]);

/* sim_h_motion.c, sim_h_mem.c, sim_h_io.c, sim_h_read.c, sim_cmd.c: the handlers */
int sim_h_align(fbrl_sim *s, args *a, int *b);
int sim_h_appro(fbrl_sim *s, args *a, int *b);
int sim_h_depart(fbrl_sim *s, args *a, int *b);
int sim_h_move(fbrl_sim *s, args *a, int *b);
int sim_h_jog(fbrl_sim *s, args *a, int *b);
int sim_h_joint(fbrl_sim *s, args *a, int *b);
int sim_h_motor(fbrl_sim *s, args *a, int *b);
int sim_h_mi(fbrl_sim *s, args *a, int *b);
int sim_h_ma(fbrl_sim *s, args *a, int *b);
int sim_h_ready(fbrl_sim *s, args *a, int *b);
int sim_h_finish(fbrl_sim *s, args *a, int *b);
int sim_h_halt(fbrl_sim *s, args *a, int *b);
int sim_h_speed(fbrl_sim *s, args *a, int *b);
int sim_h_home(fbrl_sim *s, args *a, int *b);
int sim_h_here(fbrl_sim *s, args *a, int *b);
int sim_h_limp(fbrl_sim *s, args *a, int *b);
int sim_h_nolimp(fbrl_sim *s, args *a, int *b);
int sim_h_lock(fbrl_sim *s, args *a, int *b);
int sim_h_unlock(fbrl_sim *s, args *a, int *b);
int sim_h_open(fbrl_sim *s, args *a, int *b);
int sim_h_close(fbrl_sim *s, args *a, int *b);
int sim_h_grip(fbrl_sim *s, args *a, int *b);
int sim_h_teach(fbrl_sim *s, args *a, int *b);
int sim_h_noteach(fbrl_sim *s, args *a, int *b);
int sim_h_manual(fbrl_sim *s, args *a, int *b);
int sim_h_nomanual(fbrl_sim *s, args *a, int *b);
int sim_h_flash(fbrl_sim *s, args *a, int *b);
int sim_h_noflash(fbrl_sim *s, args *a, int *b);
int sim_h_nohelp(fbrl_sim *s, args *a, int *b);
int sim_h_help(fbrl_sim *s, args *a, int *b);
int sim_h_point(fbrl_sim *s, args *a, int *b);
int sim_h_set(fbrl_sim *s, args *a, int *b);
int sim_h_shift(fbrl_sim *s, args *a, int *b);
int sim_h_shifta(fbrl_sim *s, args *a, int *b);
int sim_h_tool(fbrl_sim *s, args *a, int *b);
int sim_h_listl(fbrl_sim *s, args *a, int *b);
int sim_h_listv(fbrl_sim *s, args *a, int *b);
int sim_h_dlocn(fbrl_sim *s, args *a, int *b);
int sim_h_dvar(fbrl_sim *s, args *a, int *b);
int sim_h_type(fbrl_sim *s, args *a, int *b);
int sim_h_typei(fbrl_sim *s, args *a, int *b);
int sim_h_typev(fbrl_sim *s, args *a, int *b);
int sim_h_output(fbrl_sim *s, args *a, int *b);
int sim_h_wait(fbrl_sim *s, args *a, int *b);
int sim_h_config(fbrl_sim *s, args *a, int *b);
int sim_h_serial(fbrl_sim *s, args *a, int *b);
/* sim_h_prog.c */
int sim_h_free(fbrl_sim *s, args *a, int *b);
int sim_h_dir(fbrl_sim *s, args *a, int *b);
int sim_h_listp(fbrl_sim *s, args *a, int *b);
int sim_h_edit(fbrl_sim *s, args *a, int *b);
int sim_h_gain(fbrl_sim *s, args *a, int *b);
int sim_h_arm(fbrl_sim *s, args *a, int *b);
int sim_h_xcal(fbrl_sim *s, args *a, int *b);
int sim_h_xhome(fbrl_sim *s, args *a, int *b);
int sim_h_xzero(fbrl_sim *s, args *a, int *b);
int sim_h_w0(fbrl_sim *s, args *a, int *b);
int sim_h_w2(fbrl_sim *s, args *a, int *b);
int sim_h_w4(fbrl_sim *s, args *a, int *b);
int sim_h_w1(fbrl_sim *s, args *a, int *b);
int sim_h_w3(fbrl_sim *s, args *a, int *b);
int sim_h_w5(fbrl_sim *s, args *a, int *b);
int sim_h_we1(fbrl_sim *s, args *a, int *b);
int sim_h_we3(fbrl_sim *s, args *a, int *b);
int sim_h_we5(fbrl_sim *s, args *a, int *b);
int sim_h_status(fbrl_sim *s, args *a, int *b);
int sim_h_run(fbrl_sim *s, args *a, int *b);

/* sim_h_motion.c: arm power and units (ENABLE/DISABLE ARM, ONPOWER, METRIC/NOMETRIC) */
int sim_h_enable(fbrl_sim *s, args *a, int *block);
int sim_h_disable(fbrl_sim *s, args *a, int *block);
int sim_h_onpower(fbrl_sim *s, args *a, int *block);
int sim_h_metric(fbrl_sim *s, args *a, int *block);
int sim_h_nometric(fbrl_sim *s, args *a, int *block);

#endif
