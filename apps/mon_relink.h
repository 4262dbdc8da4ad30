/* SPDX-License-Identifier: MIT */
/* mon_relink.h - RECONNECT and RESUME: going on after the controller went away
 * (mon_relink.c). */
#ifndef FBRLMON_RELINK_H
#define FBRLMON_RELINK_H

#include <stddef.h>
#include "mon.h"

/* Define RECONNECT and RESUME, and let the next robot word typed at the prompt
 * reconnect by itself. Call after mon_open, with m->conn set. */
fbrl_status mon_relink_install(mon *m);

/* Open m->conn's port again, run the connect handshake, hand the new link to the
 * robot words and print the controller's state; on failure err says why. */
fbrl_status mon_relink(mon *m, char *err, size_t errlen);

#endif
