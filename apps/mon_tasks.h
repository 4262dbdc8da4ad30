/* SPDX-License-Identifier: MIT */
/* mon_tasks.h - fbrlmon and the engine's cooperative tasks (docs/tasks.md): the tasks run
 * while the prompt waits for keys, and a file's tasks run to their end before fbrlmon
 * exits. */
#ifndef FBRLMON_TASKS_H
#define FBRLMON_TASKS_H

#include "mon.h"

/* Run the tasks that are due; the milliseconds (at most max_ms) to wait for a key before
 * calling again. */
int mon_tasks_poll_ms(mon *m, int max_ms);

/* Before exit: run the tasks still alive to their end (Ctrl-C stops them). */
void mon_tasks_finish(mon *m);

#endif
