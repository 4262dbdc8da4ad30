/* SPDX-License-Identifier: MIT */
/* console_cell.c - the operator console's work cell (SCREEN_CELL, method developer): every
 * named place (CREATE-LOC) and device by name, and TEACH for a place: fbrlmon's keyboard
 * pendant gets the terminal, as at the prompt. */
#include "console_cell.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <curses.h>

#include "fbrl/glossary.h"
#include "fbrl/vmx.h"
#include "console_text.h"
#include "console_users.h"
#include "mon_ws.h"

/* A row of the work cell for a named location or device, newest definitions first. */
static int add_cell(void *ctx, const char *name, size_t len)
{
    console *c = ctx;
    fbrl_cell xt, addr;
    fbrl_loc *l;
    fbrl_robot_device d;
    char nm[FBRL_VMX_NAME_MAX + 1];
    if (c->cell.n >= CELL_MAX || len > FBRL_VMX_NAME_MAX ||
        fbrl_vmx_find(c->m->vm, name, len, &xt) != FBRL_OK)
        return c->cell.n >= CELL_MAX;
    memcpy(nm, name, len);
    nm[len] = '\0';
    for (size_t i = 0; i < c->cell.n; i++) /* a name defined again: the newest only */
        if (strncmp(c->cell.row[i] + 1, nm, len) == 0 && c->cell.row[i][1 + len] == ' ')
            return 0;
    if (fbrl_glossary_loc_word(c->m->vm, xt, &addr) == FBRL_OK &&
        fbrl_glossary_loc(c->m->vm, addr, &l) == FBRL_OK)
        con_textf(c->cell.row[c->cell.n++], sizeof c->cell.row[0],
                  " %-17s place X%7.2f Y%7.2f Z%7.2f  pitch%6.1f roll%6.1f", nm, l->x, l->y, l->z, l->a,
                  l->t);
    else if (fbrl_robot_device_of(&c->m->robot, xt, &d) == FBRL_OK)
        con_textf(c->cell.row[c->cell.n++], sizeof c->cell.row[0], " %-17s %-6s controller %s %d", nm,
                  d.output ? "device" : "sensor", d.output ? "output" : "input", d.port);
    return 0;
}

static int by_text(const void *a, const void *b) { return strcmp((const char *)a, (const char *)b); }

static void scan_cell(console *c)
{
    c->cell.n = c->cell.top = c->cell.pick = 0;
    fbrl_vm_words(c->m->vm, add_cell, c);
    qsort(c->cell.row, c->cell.n, sizeof c->cell.row[0], by_text); /* by name */
}

void con_cell_open(console *c)
{
    if (c->level < LEVEL_DEVELOPER) {
        con_hint(c, "the work-cell view needs the developer level (F9)");
        return;
    }
    c->cell.back = c->screen;
    c->screen = SCREEN_CELL;
    scan_cell(c);
    c->hint[0] = '\0';
}

void con_cell_draw(console *c)
{
    con_put_row(1, " Work cell: %zu named places and devices (in, deg)", c->cell.n);
    for (size_t k = 0; k < BODY_ROWS; k++) {
        size_t i = c->cell.top + k;
        if (i == c->cell.pick)
            attron(A_REVERSE);
        con_put_row(BODY_TOP + (int)k, "%s", i < c->cell.n ? c->cell.row[i] : "");
        if (i == c->cell.pick)
            attroff(A_REVERSE);
    }
}

/* TEACH a place of the work cell: fbrlmon's keyboard pendant (docs/fbrlmon.md "TEACH")
 * gets the terminal, as at the prompt; Enter there stores the arm's position into it. */
static void teach_place(console *c, const char *row)
{
    char name[FBRL_VMX_NAME_MAX + 1], text[FBRL_VMX_NAME_MAX + 8], before[MIN_COLS];
    size_t n = strcspn(row + 1, " ");
    FILE *out = c->m->host.out;
    int tty = c->m->host.out_is_tty, width = c->m->host.width;
    if (strstr(row, " place ") == NULL || n == 0 || n > FBRL_VMX_NAME_MAX) {
        con_hint(c, "only a place can be taught");
        return;
    }
    memcpy(name, row + 1, n);
    name[n] = '\0';
    con_textf(before, sizeof before, "%s", row);
    con_textf(text, sizeof text, "TEACH %s", name);
    def_prog_mode();
    endwin();
    c->outside = 1;
    c->m->host.out = stdout;
    c->m->host.out_is_tty = isatty(STDOUT_FILENO);
    c->m->host.width = COLS;
    printf("\n%s (Enter stores the arm's position into %s, Esc leaves it)\n", text, name);
    fflush(stdout);
    c->in_vm++;
    fbrl_status st = fbrl_vm_eval(c->m->vm, text, strlen(text));
    c->in_vm--;
    fbrl_vmx_take_interrupt(c->m->vm);
    c->m->host.out = out;
    c->m->host.out_is_tty = tty;
    c->m->host.width = width;
    c->outside = 0;
    reset_prog_mode();
    clearok(stdscr, TRUE);
    if (st != FBRL_OK) {
        char msg[400];
        con_engine_error(c, msg, sizeof msg);
        con_push_error(c, "TEACH", msg);
    } else {
        mon_ws_taught(c->m, name); /* a method file opened later does not overwrite it */
    }
    scan_cell(c);
    for (size_t i = 0; i < c->cell.n; i++)
        if (strncmp(c->cell.row[i] + 1, name, n) == 0 && c->cell.row[i][1 + n] == ' ') {
            c->cell.pick = i, c->cell.top = i >= BODY_ROWS ? i - (BODY_ROWS - 1) : 0;
            if (strcmp(c->cell.row[i], before) != 0) { /* taught: the place as it was and is */
                char detail[2 * MIN_COLS + 16];
                const char *was = strstr(before, " place "), *now = strstr(c->cell.row[i], " place ");
                con_textf(detail, sizeof detail, "was %s; now %s", was ? was + 7 : before,
                          now ? now + 7 : c->cell.row[i]);
                cu_action("teach", name, detail);
            }
        }
    con_hint(c, "TEACH %s %s", name, st == FBRL_OK ? "done" : "did not store it");
}

void con_cell_key(console *c, int ch)
{
    if (ch == KEY_UP && c->cell.pick > 0)
        c->cell.pick--;
    else if (ch == KEY_DOWN && c->cell.pick + 1 < c->cell.n)
        c->cell.pick++;
    else if ((ch == 't' || ch == 'T' || ch == '\n' || ch == '\r' || ch == KEY_ENTER) &&
             c->cell.pick < c->cell.n)
        teach_place(c, c->cell.row[c->cell.pick]);
    else if (ch == KEY_ESCAPE)
        c->screen = c->cell.back;
    if (c->cell.pick < c->cell.top) /* the selected row stays in view */
        c->cell.top = c->cell.pick;
    else if (c->cell.pick >= c->cell.top + BODY_ROWS)
        c->cell.top = c->cell.pick - (BODY_ROWS - 1);
}
