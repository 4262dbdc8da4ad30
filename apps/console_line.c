/* SPDX-License-Identifier: MIT */
/* console_line.c - the operator console's typed line, above the keys (enum con_line): a
 * Forth line for the engine (programmer), the level to switch to, the name of a composed
 * method, and signing in with the lab's users (the name, then the password, shown as *). */
#include "console_line.h"

#include <string.h>
#include <curses.h>

#include "fbrl/vmx.h"
#include "console_compose.h"
#include "console_text.h"
#include "console_users.h"

const char *const con_level_names[] = {"operator", "developer", "programmer"};

void con_line_open(console *c, enum con_line mode)
{
    c->line.mode = mode;
    c->line.len = 0;
    c->line.typed[0] = '\0';
}

int con_line_signing_in(const console *c)
{
    return c->line.mode == LINE_SIGN_IN || c->line.mode == LINE_PASSWORD;
}

void con_line_ask_sign_in(console *c, const char *why)
{
    con_line_open(c, LINE_SIGN_IN);
    c->level = LEVEL_OPERATOR;
    con_hint(c, "%s", why);
}

/* Down is free; up as far as the signed-in user's role allows (the lab's users: --lab). */
static void set_level(console *c, enum con_level want)
{
    if (want > c->level && !cu_lab()) {
        con_hint(c, "switching up needs the lab's users (--lab DIR), or start with --level %s",
                 con_level_names[want]);
        return;
    }
    if ((int)want > cu_level_max() && want > c->level) {
        con_hint(c, "%s's role (%s) allows the %s level: F9 s signs out for another user",
                 c->log->operator_id, cu_role(), con_level_names[cu_level_max()]);
        return;
    }
    c->level = want;
    con_hint(c, "level: %s", con_level_names[want]);
    cu_action("level", con_level_names[want], NULL);
}

/* A Forth line: its output under Messages, its error under Last errors; recorded. */
static void run_forth(console *c, const char *typed, size_t len)
{
    char text[sizeof c->line.typed];
    memcpy(text, typed, len + 1);
    con_push_msg(c, text);
    cu_action("forth", text, NULL);
    c->in_vm++;
    fbrl_status st = fbrl_vm_eval(c->m->vm, text, strlen(text));
    c->in_vm--;
    fbrl_vmx_take_interrupt(c->m->vm);
    if (st != FBRL_OK) {
        char msg[400];
        con_engine_error(c, msg, sizeof msg);
        con_push_error(c, "console", msg);
    }
    con_flush_partial(c);
}

/* Enter: what the line's mode does with what was typed. */
static void typed_done(console *c)
{
    enum con_line mode = c->line.mode;
    c->line.mode = LINE_NONE;
    if (mode == LINE_SIGN_IN) {
        con_textf(c->line.who, sizeof c->line.who, "%s", c->line.typed);
        c->line.mode = c->line.len ? LINE_PASSWORD : LINE_SIGN_IN;
    } else if (mode == LINE_PASSWORD) {
        char msg[200];
        if (cu_sign_in(c->line.who, c->line.typed, msg, sizeof msg) == 0) {
            c->level = (enum con_level)cu_level_max();
            con_hint(c, "%s", msg);
        } else {
            con_line_ask_sign_in(c, msg);
        }
    } else if (mode == LINE_METHOD_NAME) {
        con_compose_save(c, c->line.typed);
    } else if (mode == LINE_FORTH && c->line.len > 0) {
        run_forth(c, c->line.typed, c->line.len);
        c->line.mode = LINE_FORTH; /* the prompt stays until Esc */
    }
    memset(c->line.typed, 0, sizeof c->line.typed); /* a password too */
    c->line.len = 0;
}

void con_line_key(console *c, int ch)
{
    size_t cap = c->line.mode == LINE_LEVEL     ? 1
                 : c->line.mode == LINE_SIGN_IN ? FBRL_AUDIT_NAME_MAX - 1
                                                : sizeof c->line.typed - 1;
    if (c->line.mode == LINE_LEVEL) { /* one key */
        c->line.mode = LINE_NONE;
        if (ch >= '1' && ch <= '3')
            set_level(c, (enum con_level)(ch - '1'));
        else if ((ch == 's' || ch == 'S') && cu_lab()) {
            cu_sign_out("signed out");
            con_line_ask_sign_in(c, "signed out: the next user signs in");
        }
        return;
    }
    if (ch == KEY_ESCAPE && con_line_signing_in(c)) { /* no way around signing in: start again */
        con_line_ask_sign_in(c, "sign in: your name, Enter, then your password");
    } else if (ch == KEY_ESCAPE) {
        con_line_open(c, LINE_NONE);
    } else if (ch == '\n' || ch == '\r' || ch == KEY_ENTER) {
        typed_done(c);
    } else if ((ch == KEY_BACKSPACE || ch == 127 || ch == 8) && c->line.len > 0) {
        c->line.typed[--c->line.len] = '\0';
    } else if (ch >= 0x20 && ch < 0x7f && c->line.len < cap) {
        c->line.typed[c->line.len++] = (char)ch;
        c->line.typed[c->line.len] = '\0';
    }
}

void con_line_draw(console *c)
{
    const int row = MIN_ROWS - 2;
    switch (c->line.mode) {
    case LINE_FORTH: con_put_row(row, "ok> %s", c->line.typed); break;
    case LINE_LEVEL:
        con_put_row(row, "level: 1 operator  2 developer  3 programmer%s ?", cu_lab() ? "  s sign out" : "");
        break;
    case LINE_METHOD_NAME: con_put_row(row, "name of the new method: %s", c->line.typed); break;
    case LINE_SIGN_IN:
    case LINE_PASSWORD:
        con_put_row(row - 1, " %s", c->hint); /* why the last sign-in failed, or what to do */
        if (c->line.mode == LINE_SIGN_IN)
            con_put_row(row, "sign in: name: %s", c->line.typed);
        else
            con_put_row(row, "sign in: password for %s: %.*s", c->line.who,
                        (int)(c->line.len < 16 ? c->line.len : 16), "****************");
        break;
    default: con_put_row(row, "%s", c->hint); break;
    }
}
