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
/* Keep a line typed at the prompt that defined words, for LOCATE and SAVE-DEFINITIONS. */
void mon_debug_typed(mon *m, const char *text, size_t len);

#endif
