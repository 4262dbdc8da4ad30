/* SPDX-License-Identifier: MIT */
/* mon_host.h - the operating-system services fbrlmon gives the FBRL engine:
 * console output, keyboard input, source files (stdio), time. */
#ifndef FBRLMON_HOST_H
#define FBRLMON_HOST_H

#include <signal.h>
#include <stdio.h>
#include "fbrl/vm.h"

typedef struct mon_host {
    FILE *out;      /* console output (stdout) */
    int out_is_tty; /* flush every write so output shows before long words */
    int column;     /* bytes written since the last newline */
    int width;      /* terminal columns (0: not a terminal) */
    int in_fd;      /* keyboard for KEY / KEY? (stdin) */
    int in_is_tty;
    /* Ctrl-C presses while a line is evaluated: waits in MS and KEY end early so
     * the engine sees its interrupt request (fbrl_vm_interrupt) at once. */
    volatile sig_atomic_t interrupted;
    /* Read-ahead of in_fd shared by the line reader and KEY, so a program that
     * reads keys from piped input gets the bytes after the current line. */
    unsigned char inbuf[4096];
    size_t inpos, inlen;
    int in_eof;
    char *line; /* mon_host_read_line()'s growing buffer */
    size_t line_cap;
    int file_depth; /* source files open (INCLUDED nests) */
    /* RESUME: the next open of skip_path reads its first skip_lines lines as empty
     * (so line numbers stay right) */
    const char *skip_path;
    unsigned long skip_lines;
    /* The line editor while the interactive session runs (mon_edit.c): the engine's
     * read_line (GET-CAL-POINTS) edits console lines with it. NULL: plain lines. */
    const char *(*edit_line)(void *ctx, const char *prompt, size_t *len);
    void *edit_ctx;
    int progress_shown; /* a progress line is on the screen (mon_host_progress) */
    /* Called every ~100 ms of a sleep (MS, PULSE, WAIT-UNTIL ...); non-zero ends the
     * sleep early (the console: keys read, screen redrawn, abort asked). NULL: none. */
    int (*tick)(void *ctx);
    void *tick_ctx;
    int line_too_long; /* a line passed MON_HOST_LINE_MAX: input was stopped there */
} mon_host;

/* The longest input line read from stdin (far above the engine's own line limit, so
 * the engine still names the line; a stream with no line end stops here). */
#define MON_HOST_LINE_MAX (1L << 20)

/* Fill h (output to `out`, keys from file descriptor `in_fd`) and the engine's
 * callback table that points at it. */
void mon_host_init(mon_host *h, FILE *out, int in_fd, fbrl_vm_host *cb);
/* Before mon_host_init: the clock the engine gets instead of the real one (the dry run's). */
void mon_host_use_clock(uint64_t (*now_us)(void *user), void (*sleep_ms)(void *user, uint32_t ms),
                        void (*time_date)(void *user, int out[6]));

/* Next line of input from in_fd without its end (LF or CRLF); NULL at end of
 * input. The line stays valid until the next call. A line reaching MON_HOST_LINE_MAX
 * bytes is handed over as read so far, and input ends there (h->line_too_long set):
 * a stream without line ends (/dev/zero) cannot keep fbrlmon reading. */
const char *mon_host_read_line(mon_host *h, size_t *len);

/* A robot word's progress line (fbrl_robot_progress_fn; ctx is the mon_host): shown in
 * place on a terminal at the start of a line, erased with NULL. Never on a file or pipe,
 * and never over output that does not end in a newline. */
void mon_host_progress(void *ctx, const char *text);

/* Release what the host allocated. */
void mon_host_free(mon_host *h);

/* On a terminal, start the next output on a fresh line (before a prompt or an
 * error line); flush the output either way. */
void mon_host_newline(mon_host *h);

#endif
