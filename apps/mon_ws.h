/* mon_ws.h - fbrlmon's workspace at start and exit (docs/workspace.md): --workspace FILE
 * loads it, and leaving a terminal session with unsaved changes offers to save them. */
#ifndef FBRLMON_WS_H
#define FBRLMON_WS_H

#include "mon.h"

/* --workspace path: load it if it exists (a file that cannot be loaded is an error: -1,
 * reported), else remember it as the file to save to. */
int mon_ws_start(mon *m, const char *path);

/* At exit: when the workspace changed since it was loaded or saved, ask on a terminal
 * whether to save it (to the --workspace file, or a name the user types); without a
 * terminal, say on stderr that it was not saved (only when --workspace was given). */
void mon_ws_finish(mon *m);

#endif
