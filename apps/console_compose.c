/* SPDX-License-Identifier: MIT */
/* console_compose.c - the operator console's composer (SCREEN_COMPOSE, method developer):
 * a new method from the chosen method's steps, saved into the library as a method file
 * that loads the chosen method's file and shares its parameters. */
#include "console_compose.h"

#include <ctype.h>
#include <errno.h>
#include <string.h>
#include <unistd.h>
#include <curses.h>

#include "fbrl/vmx.h"
#include "console_library.h"
#include "console_text.h"
#include "console_users.h"

void con_compose_open(console *c)
{
    if (c->level < LEVEL_DEVELOPER) {
        con_hint(c, "composing a method needs the developer level (F9)");
        return;
    }
    c->screen = SCREEN_COMPOSE;
    c->compose.sel = c->compose.npicked = 0;
    con_hint(c, "Enter adds the highlighted step to the new method; F5 saves it");
}

/* The chosen method's steps on the left, the new method's on the right. */
void con_compose_draw(console *c)
{
    const fbrl_method *m = c->meth;
    con_put_row(1, " Compose a method from the steps of %s", m->name);
    for (size_t k = 0; k < BODY_ROWS; k++) {
        int row = BODY_TOP + (int)k;
        con_put_row(row, " ");
        if (k < m->nsteps) {
            if (k == c->compose.sel)
                attron(A_REVERSE);
            con_put_at(row, 1, "%-14.14s %-10s", m->steps[k].name,
                       m->steps[k].per_sample ? "per sample" : "");
            if (k == c->compose.sel)
                attroff(A_REVERSE);
        }
        con_put_at(row, 34, "|");
        if (k < c->compose.npicked)
            con_put_at(row, 36, "%2zu. %-14.14s %.24s", k + 1, m->steps[c->compose.picked[k]].name,
                       m->steps[c->compose.picked[k]].text);
    }
}

int con_compose_key(console *c, int ch)
{
    if (ch == KEY_UP && c->compose.sel > 0)
        c->compose.sel--;
    else if (ch == KEY_DOWN && c->compose.sel + 1 < c->meth->nsteps)
        c->compose.sel++;
    else if ((ch == '\n' || ch == '\r' || ch == KEY_ENTER || ch == ' ') &&
             c->compose.npicked < FBRL_METHOD_MAX_STEPS)
        c->compose.picked[c->compose.npicked++] = c->compose.sel;
    else if ((ch == KEY_BACKSPACE || ch == 127 || ch == 8) && c->compose.npicked > 0)
        c->compose.npicked--;
    else if (ch == KEY_ESCAPE)
        c->screen = SCREEN_FORM;
    else if (ch == KEY_F(5))
        return 1;
    return 0;
}

typedef struct xt_find {
    fbrl_vm *vm;
    fbrl_cell xt;
    char name[FBRL_VMX_NAME_MAX + 1];
} xt_find;

static int find_xt(void *ctx, const char *name, size_t len)
{
    xt_find *f = ctx;
    fbrl_cell xt;
    if (len <= FBRL_VMX_NAME_MAX && fbrl_vmx_find(f->vm, name, len, &xt) == FBRL_OK && xt == f->xt) {
        memcpy(f->name, name, len);
        f->name[len] = '\0';
        return 1;
    }
    return 0;
}

/* The name that runs xt now (a step's word), or "" if none does. */
static const char *word_of(console *c, fbrl_cell xt, xt_find *f)
{
    memset(f, 0, sizeof *f);
    f->vm = c->m->vm;
    f->xt = xt;
    fbrl_vm_words(c->m->vm, find_xt, f);
    return f->name;
}

/* Write DIR/name.fbrl: it loads the chosen method's file, shares its parameters and
 * declares the picked steps. */
void con_compose_save(console *c, const char *typed)
{
    const fbrl_method *m = c->meth;
    const size_t *picked = c->compose.picked;
    size_t npicked = c->compose.npicked;
    const char *dir = c->methods;
    const char *src = c->entry ? strrchr(c->entry->path, '/') : NULL;
    char name[FBRL_METHOD_NAME_MAX + 1], path[MON_RUNLOG_PATH_MAX], file[FBRL_METHOD_NAME_MAX + 1];
    size_t n = strlen(typed);
    xt_find f;
    if (n == 0 || n > FBRL_METHOD_NAME_MAX) {
        con_hint(c, "not saved: a name of 1..%d letters, digits and -", FBRL_METHOD_NAME_MAX);
        return;
    }
    for (size_t i = 0; i <= n; i++) {
        char ch = (char)toupper((unsigned char)typed[i]);
        if (ch && !isalnum((unsigned char)ch) && ch != '-') {
            con_hint(c, "not saved: '%s': only letters, digits and - in a name", typed);
            return;
        }
        name[i] = ch;
        file[i] = ch == '-' ? '_' : (char)tolower((unsigned char)ch);
    }
    for (size_t i = 0; i < c->nlib; i++)
        if (strcmp(c->lib[i].name, name) == 0) {
            con_hint(c, "not saved: the library has %s already", name);
            return;
        }
    if (src == NULL || npicked == 0) {
        con_hint(c, "not saved: %s", npicked ? "the method's file is unknown" : "no steps");
        return;
    }
    con_textf(path, sizeof path, "%s/%s.fbrl", dir, file);
    if (access(path, F_OK) == 0) {
        con_hint(c, "not saved: %s exists", path);
        return;
    }
    for (size_t k = 0; k < npicked; k++)
        if (!word_of(c, m->steps[picked[k]].xt, &f)[0]) {
            con_hint(c, "not saved: step %s has no word name", m->steps[picked[k]].name);
            return;
        }
    FILE *out = fopen(path, "wx");
    if (out == NULL) {
        con_hint(c, "not saved: %s: %s", path, strerror(errno));
        return;
    }
    fprintf(out, "\\ %s.fbrl - composed in the operator console from the steps of %s (%s)\n", file, m->name,
            c->log->operator_id);
    fprintf(out, "INCLUDE %s\n", src + 1);
    fprintf(out, "METHOD %s  %s steps:", name, m->name);
    for (size_t k = 0; k < npicked; k++)
        fprintf(out, " %s", m->steps[picked[k]].name);
    fprintf(out, "\n%s USE-PARAMS\n", m->name);
    for (size_t k = 0; k < npicked; k++) {
        const fbrl_method_step *st = &m->steps[picked[k]];
        fprintf(out, "' %s %s %s  %s\n", word_of(c, st->xt, &f), st->per_sample ? "SAMPLE-STEP" : "STEP",
                st->name, st->text);
    }
    if (m->abort_xt && word_of(c, m->abort_xt, &f)[0])
        fprintf(out, "' %s ON-ABORT\n", f.name);
    fprintf(out, "END-METHOD\n");
    if (fclose(out) != 0) {
        con_hint(c, "not saved: %s: %s", path, strerror(errno));
        remove(path);
        return;
    }
    con_library_scan(c);
    c->screen = SCREEN_LIBRARY;
    for (size_t i = 0; i < c->nlib; i++)
        if (strcmp(c->lib[i].name, name) == 0)
            c->sel = i;
    con_hint(c, "saved %s as %s.fbrl in the library: Enter opens it", name, file);
    cu_action("compose", name, path);
}
