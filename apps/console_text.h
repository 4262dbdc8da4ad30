/* SPDX-License-Identifier: MIT */
/* console_text.h - the operator console's texts and rows, and its two panes: Messages and
 * Last errors. */
#ifndef FBRLMON_CONSOLE_TEXT_H
#define FBRLMON_CONSOLE_TEXT_H

#include <sys/types.h>

#include "console_state.h"

#if defined(__GNUC__)
#define CON_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define CON_PRINTF(f, a)
#endif

/* snprintf for the screen's texts: cutting a text at its field's end is what is meant */
void con_textf(char *buf, size_t cap, const char *fmt, ...) CON_PRINTF(3, 4);
/* The line above the keys. */
void con_hint(console *c, const char *fmt, ...) CON_PRINTF(2, 3);
/* A whole row (cut at the screen's width, the rest cleared), or text from a column on. */
void con_put_row(int row, const char *fmt, ...) CON_PRINTF(2, 3);
void con_put_at(int row, int col, const char *fmt, ...) CON_PRINTF(3, 4);
/* m:ss */
void con_fmt_time(char *buf, size_t cap, double ms);
/* A line under Messages (the oldest goes). */
void con_push_msg(console *c, const char *s);
/* An error in plain words with what to do, under Last errors; the newest is shown first. */
void con_push_error(console *c, const char *where, const char *msg);
/* The engine's output (the console's FILE *out): whole lines into the message pane. */
ssize_t con_out_write(void *ctx, const char *s, size_t n);
/* Method output without a line end yet: show it. */
void con_flush_partial(console *c);
/* The last error of the engine as "file:line: message [in WORD]" (the form editors parse). */
void con_engine_error(console *c, char *buf, size_t cap);

#endif
