/* SPDX-License-Identifier: MIT */
/* mon_ws.h - fbrlmon's workspace at start and exit (docs/workspace.md): --workspace FILE
 * loads it, and leaving a terminal session with unsaved changes lists what a save would
 * change in the file and offers to save them (defaulting to keeping the file when a save
 * would replace or drop what it holds). The places it brought and those taught in the
 * session are taught places: a method file the console opens does not overwrite them. */
#ifndef FBRLMON_WS_H
#define FBRLMON_WS_H

#include "mon.h"

/* --workspace path: load it if it exists (a file that cannot be loaded is an error: -1,
 * reported), else remember it as the file to save to. */
int mon_ws_start(mon *m, const char *path);

/* At exit: when the workspace changed since it was loaded or saved and the session has
 * a workspace file (--workspace, or one saved or loaded), ask on a terminal whether to
 * save it there; without a file, or without a terminal, say on stderr what was not saved
 * (without a terminal only when --workspace was given). */
void mon_ws_finish(mon *m);

/* A place taught in this session (TEACH in the console's work cell). */
void mon_ws_taught(mon *m, const char *name);
/* Around loading a file (the console opening a method): mon_ws_protect notes the taught
 * places' values; mon_ws_restore gives back every one the file changed (a new word of the
 * name gets the taught value) and tells each (the taught value, the file's); how many. */
void mon_ws_protect(mon *m);
size_t mon_ws_restore(mon *m, void (*tell)(void *ctx, const char *name, const fbrl_loc *taught_value,
                                            const fbrl_loc *file_value),
                      void *ctx);

#endif
