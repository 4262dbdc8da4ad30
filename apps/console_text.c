/* SPDX-License-Identifier: MIT */
/* console_text.c - the operator console's texts and rows, and its two panes: Messages (the
 * method's output, whole lines) and Last errors (each with what to do). */
#include "console_text.h"

#include <stdarg.h>
#include <string.h>
#include <curses.h>

#include "fbrl/vmx.h"

void con_textf(char *buf, size_t cap, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, cap, fmt, ap);
    va_end(ap);
}

void con_hint(console *c, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->hint, sizeof c->hint, fmt, ap);
    va_end(ap);
}

void con_put_row(int row, const char *fmt, ...)
{
    char buf[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    buf[MIN_COLS] = '\0';
    mvaddstr(row, 0, buf);
    clrtoeol();
}

void con_put_at(int row, int col, const char *fmt, ...)
{
    char buf[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    if (col < MIN_COLS)
        buf[MIN_COLS - col] = '\0';
    mvaddstr(row, col, buf);
}

void con_fmt_time(char *buf, size_t cap, double ms)
{
    long s = ms < 0 ? 0 : (long)(ms / 1000.0 + 0.5);
    con_textf(buf, cap, "%ld:%02ld", s / 60, s % 60);
}

void con_push_msg(console *c, const char *s)
{
    memmove(c->msgs[0], c->msgs[1], sizeof c->msgs[0] * (MSG_LINES - 1));
    con_textf(c->msgs[MSG_LINES - 1], sizeof c->msgs[0], "%s", s);
}

void con_push_error(console *c, const char *where, const char *msg)
{
    memmove(c->errs[1], c->errs[0], sizeof c->errs[0] * (ERR_LINES - 1));
    memmove(c->advice[1], c->advice[0], sizeof c->advice[0] * (ERR_LINES - 1));
    con_textf(c->errs[0], sizeof c->errs[0], "%s%s%s", where ? where : "", where ? ": " : "", msg);
    con_textf(c->advice[0], sizeof c->advice[0], "-> %s", fbrl_runlog_advice(msg));
}

ssize_t con_out_write(void *ctx, const char *s, size_t n)
{
    console *c = ctx;
    for (size_t i = 0; i < n; i++) {
        if (s[i] == '\n' || c->plen + 1 >= sizeof c->partial) {
            c->partial[c->plen] = '\0';
            con_push_msg(c, c->partial);
            c->plen = 0;
            if (s[i] == '\n')
                continue;
        }
        if ((unsigned char)s[i] >= 0x20)
            c->partial[c->plen++] = s[i];
    }
    return (ssize_t)n;
}

void con_flush_partial(console *c)
{
    if (c->plen > 0) {
        c->partial[c->plen] = '\0';
        con_push_msg(c, c->partial);
        c->plen = 0;
    }
}

void con_engine_error(console *c, char *buf, size_t cap)
{
    const fbrl_vm_error *e = fbrl_vm_last_error(c->m->vm);
    if (e == NULL) {
        con_textf(buf, cap, "error");
        return;
    }
    if (e->file[0] && e->line > 0)
        con_textf(buf, cap, "%s:%lu: %s%s%s", e->file, e->line, e->message, e->word[0] ? " in " : "",
                  e->word);
    else
        con_textf(buf, cap, "%s%s%s", e->message, e->word[0] ? " in " : "", e->word);
}
