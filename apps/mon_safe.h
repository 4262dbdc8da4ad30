/* SPDX-License-Identifier: MIT */
/* mon_safe.h - Ctrl-C in fbrlmon: one SIGINT handler for the whole run, and the safe
 * stop (the arm halted, the outputs the session switched on switched off, a report of
 * where it stopped) that every Ctrl-C ends in, in a plan, a typed line or at the prompt.
 * docs/fbrlmon.md "Ctrl-C" tells the rules. */
#ifndef FBRLMON_SAFE_H
#define FBRLMON_SAFE_H

#include "mon.h"

/* A second Ctrl-C within this time of the one before ends fbrlmon (after the safe stop). */
#define MON_QUIT_WINDOW_MS 2000
/* Exit status after Ctrl-C ended fbrlmon (128 + SIGINT, as shells report it). */
#define MON_EXIT_INTERRUPT 130

/* Install the handler for session m (once, after mon_open). */
void mon_safe_install(mon *m);

/* Around every evaluation (a file, -e text, a typed or piped line): Ctrl-C in between
 * interrupts the engine. mon_safe_end() makes the safe stop if a Ctrl-C came and
 * returns 1 then (0 otherwise); `where` / `line` name the source for the report when
 * the engine's error does not (a typed line: NULL). */
void mon_safe_begin(mon *m);
int mon_safe_end(mon *m, const char *where, unsigned long line);

/* A Ctrl-C came that no safe stop has handled yet (at the prompt, or before a line ran). */
int mon_safe_pending(void);
/* The safe stop for a Ctrl-C outside an evaluation (at the prompt): where = NULL. */
void mon_safe_stop(mon *m, const char *where, unsigned long line);
/* A second Ctrl-C asked fbrlmon to end (after its safe stop). */
int mon_safe_quit(void);

#endif
