/* SPDX-License-Identifier: MIT */
/* console_run.h - the operator console's run screen (SCREEN_RUN): the console as one
 * observer of the library's method run. */
#ifndef FBRLMON_CONSOLE_RUN_H
#define FBRLMON_CONSOLE_RUN_H

#include "console_state.h"

/* A run goes on or is being paused or aborted. */
int con_running(const console *c);
/* The run's state line, steps, samples and the live panel (arm, gripper, devices). */
void con_run_draw(console *c);
/* The keys while a method runs or is paused: pause, resume, abort, an answer. */
void con_run_key(console *c, int ch);
/* F5: start the chosen method with the form's values; the form back when it did not start. */
void con_run_start(console *c);
/* The run's events (all but FBRL_RUN_EV_WAIT, which is the frame's). */
void con_run_event(console *c, fbrl_run *run, const fbrl_run_event *ev);
/* What the controller executed: the outputs and the gripper. */
void con_run_exec(console *c, const char *line, size_t len, fbrl_status result);
/* A robot word's progress text over a long wait. */
void con_run_progress(console *c, const char *text);
/* While a motion ends: where the arm is on its way; 1 if it was read. */
int con_run_watch(console *c);
/* The run log could not be written (mon_runlog's error_hook; ctx is the console). */
void con_run_log_failed(void *ctx, const char *message);

#endif
