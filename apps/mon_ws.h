/* SPDX-License-Identifier: MIT */
/* mon_ws.h - fbrlmon's workspace at start and exit (docs/workspace.md): --workspace FILE
 * loads it, and leaving a terminal session with unsaved changes offers to save them. */
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

#endif
