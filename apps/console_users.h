/* SPDX-License-Identifier: MIT */
/* console_users.h - the console's users (fbrlmon --console --lab DIR): sign-in with the
 * lab's users instead of a shared PIN, the level a role allows, sign-out after the lab's
 * idle time, and the console's actions that change something recorded in the audit chain
 * with the user's name. docs/console.md "Levels", docs/compliance.md. */
#ifndef FBRLMON_CONSOLE_USERS_H
#define FBRLMON_CONSOLE_USERS_H

#include <stddef.h>
#include <stdint.h>

#include "mon_runlog.h"

/* Start: the lab is the run log's (log->audit.lab; NULL: no lab, no sign-in). */
void cu_start(mon_runlog *log);
/* Is there a lab? Is someone signed in? */
int cu_lab(void);
int cu_signed_in(void);
/* Sign in name with password (checked, counted, recorded; the password is wiped). 0, or -1
 * with the reason in msg. On success the run log's operator is name. */
int cu_sign_in(const char *name, char *password, char *msg, size_t cap);
/* Sign out (recorded with the reason: "signed out", "idle for 600 s"). */
void cu_sign_out(const char *reason);
/* The highest console level (0 operator, 1 developer, 2 programmer) the signed-in user's
 * role allows, and the role's name. */
int cu_level_max(void);
const char *cu_role(void);
/* A key was pressed (the idle clock starts again). */
void cu_touch(void);
/* Sign out when idle longer than the lab's idle_s (not while a run goes on): 1 if it did. */
int cu_idle(int running);
/* The console ends: signed out, what the session wrote sealed. */
void cu_end(void);
/* An action that changed something: recorded in the chain by the signed-in user (or the
 * named operator without a lab). what and detail in words (detail may be NULL). */
void cu_action(const char *action, const char *what, const char *detail);

#endif
