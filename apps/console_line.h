/* SPDX-License-Identifier: MIT */
/* console_line.h - the operator console's typed line (enum con_line) and its levels. */
#ifndef FBRLMON_CONSOLE_LINE_H
#define FBRLMON_CONSOLE_LINE_H

#include "console_state.h"

extern const char *const con_level_names[]; /* by enum con_level */

/* Open the line in mode (empty). */
void con_line_open(console *c, enum con_line mode);
/* Signing in is asked for (the name first); why on the hint line. The level is operator. */
void con_line_ask_sign_in(console *c, const char *why);
/* Is the line asking for a name or a password to sign in? */
int con_line_signing_in(const console *c);
/* A key while the line is open. */
void con_line_key(console *c, int ch);
/* The line (row 22, and why a sign-in failed above it) as its mode shows it. */
void con_line_draw(console *c);

#endif
