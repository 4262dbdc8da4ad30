/* SPDX-License-Identifier: MIT */
/* console_form.c - the operator console's parameter form (SCREEN_FORM): one field for each
 * of the chosen method's parameters, each checked against its range; the run starts only
 * when every field is good. */
#include "console_form.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <curses.h>

#include "console_text.h"

void con_form_fill(console *c)
{
    for (size_t k = 0; c->meth && k < c->meth->nparams; k++) {
        long v = 0;
        fbrl_method_param_get(&c->m->methods, c->meth, k, &v);
        con_textf(c->form.field[k], sizeof c->form.field[k], "%ld", v);
    }
    c->form.sel = 0;
    c->form.fresh = 1;
}

/* 0 and *v if the text is a whole number in range; else -1 and why in msg. */
static int check_field(const fbrl_method_param *p, const char *text, long *v, char *msg, size_t cap)
{
    char *end;
    const char *s = text;
    while (*s == ' ')
        s++;
    if (*s == '\0') {
        con_textf(msg, cap, "%s is empty: enter a whole number %ld..%ld %s", p->name, p->min, p->max,
                  p->unit);
        return -1;
    }
    errno = 0;
    long n = strtol(s, &end, 10);
    while (*end == ' ')
        end++;
    if (*end != '\0' || errno != 0) {
        con_textf(msg, cap, "%s: '%s' is not a whole number: enter %ld..%ld %s", p->name, s, p->min, p->max,
                  p->unit);
        return -1;
    }
    if (n < p->min || n > p->max) {
        con_textf(msg, cap, "%s: %ld is outside the allowed range %ld..%ld %s", p->name, n, p->min, p->max,
                  p->unit);
        return -1;
    }
    *v = n;
    return 0;
}

int con_form_commit(console *c, long *v)
{
    char msg[160];
    for (size_t k = 0; k < c->meth->nparams; k++)
        if (check_field(&c->meth->params[k], c->form.field[k], &v[k], msg, sizeof msg) != 0) {
            c->form.sel = k;
            c->form.fresh = 1;
            con_hint(c, "refused: %s", msg);
            return -1;
        }
    return 0;
}

void con_form_draw(console *c)
{
    const fbrl_method *m = c->meth;
    con_put_row(1, " Parameters of %s (%s)", m->name, m->text);
    for (size_t k = 0; k < BODY_ROWS; k++) {
        int row = BODY_TOP + (int)k;
        if (k < m->nparams) {
            const fbrl_method_param *p = &m->params[k];
            con_put_row(row, " %-14.14s [", p->name);
            if (k == c->form.sel)
                attron(A_REVERSE);
            con_put_at(row, 17, "%-*s", FIELD_MAX, c->form.field[k]);
            if (k == c->form.sel)
                attroff(A_REVERSE);
            con_put_at(row, 17 + FIELD_MAX, "] %-7.7s %ld..%ld  %.30s", p->unit, p->min, p->max, p->text);
        } else {
            con_put_row(row, " ");
        }
    }
}

int con_form_key(console *c, int ch)
{
    const fbrl_method *m = c->meth;
    char *f = c->form.field[c->form.sel];
    size_t n = strlen(f);
    int fresh = c->form.fresh;
    c->form.fresh = 0;
    if (ch == KEY_UP && c->form.sel > 0)
        c->form.sel--, c->form.fresh = 1;
    else if ((ch == KEY_DOWN || ch == '\t') && c->form.sel + 1 < m->nparams)
        c->form.sel++, c->form.fresh = 1;
    else if (ch == '\n' || ch == '\r' || ch == KEY_ENTER) {
        long v;
        char msg[160];
        if (check_field(&m->params[c->form.sel], f, &v, msg, sizeof msg) != 0)
            con_hint(c, "refused: %s", msg);
        else {
            con_hint(c, "%s = %ld %s", m->params[c->form.sel].name, v, m->params[c->form.sel].unit);
            if (c->form.sel + 1 < m->nparams)
                c->form.sel++, c->form.fresh = 1;
        }
    } else if ((ch == KEY_BACKSPACE || ch == 127 || ch == 8) && n > 0)
        f[n - 1] = '\0';
    else if (ch == KEY_DC)
        f[0] = '\0';
    else if (ch >= 0x20 && ch < 0x7f && (n < FIELD_MAX || fresh)) {
        if (fresh)
            n = 0;
        f[n] = (char)ch;
        f[n + 1] = '\0';
    } else if (ch == KEY_F(5))
        return 1;
    return 0;
}
