/* SPDX-License-Identifier: MIT */
/* console.h - the operator console (fbrlmon --console): a full-screen ncurses view to
 * pick a method from the method library, fill in its parameters (ranges checked), start,
 * pause after the current step, resume and abort it, and watch its progress, the arm,
 * the gripper, the devices and the last errors; with levels (operator, method developer,
 * programmer). docs/console.md tells how to use it. */
#ifndef FBRLMON_CONSOLE_H
#define FBRLMON_CONSOLE_H

struct mon;
struct mon_runlog;

typedef struct console_options {
    int on;                  /* --console */
    const char *methods;     /* --methods DIR: the method library (default "methods") */
    const char *level;       /* --level operator|developer|programmer (the configured setting) */
    const char *run_log;     /* --run-log FILE (fbrlmon too) */
    const char *operator_id; /* --operator NAME */
} console_options;

/* The console's own command-line options (a value option a with value v): 0 if it was
 * one of them and is valid, 1 if it is not one of them, -1 for a bad value. */
int console_option(console_options *o, const char *a, const char *v);

/* Run the console on the terminal until the user quits. 0, or -1 if it could not start
 * (not a terminal, no ncurses: the reason on stderr). */
int console_run(struct mon *m, struct mon_runlog *log, const console_options *o);

#endif
