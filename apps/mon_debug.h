/* SPDX-License-Identifier: MIT */
/* mon_debug.h - fbrlmon's LOCATE, EDIT and SAVE-DEFINITIONS (mon_debug.c). */
#ifndef FBRLMON_DEBUG_H
#define FBRLMON_DEBUG_H

#include <stdio.h>
#include "mon.h"

#define MON_EDIT_PATH_MAX      256 /* a plan file's path (the engine's own limit) */
#define MON_EDIT_PATH_MAX_TEXT "256"
#define MON_EDIT_MSG           640

/* Define the words in m->vm. */
fbrl_status mon_debug_install(mon *m);
/* Print a file's lines from first, each with its number, up to the one that holds ';'
 * (a definition's end) or max lines; -1 if none could be read. */
int mon_debug_show_lines(FILE *out, const char *path, unsigned long first, int max);
/* A line typed at the prompt was evaluated (ok: without an error; open_before, open_after:
 * a definition was open before it, is open after it; defined: it made words). Lines that
 * defined words are kept for LOCATE and SAVE-DEFINITIONS; those of a definition only once
 * it ended, and none of one that an error abandoned. */
void mon_debug_typed(mon *m, const char *text, size_t len, int ok, int open_before, int open_after,
                     int defined);

#endif
