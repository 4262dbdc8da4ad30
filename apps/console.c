/* SPDX-License-Identifier: MIT */
/* console.c - the operator console (fbrlmon --console), on ncurses: its frame (the title,
 * the screen shown, the messages, the errors, the typed line and the keys), the key
 * dispatch, and the loop.
 *
 * One thread: the method runs in the FBRL engine (the method run, fbrl/run.h), and the
 * screen is kept alive from inside it: at the run's events (the console observes the run
 * as the run log does), while the run waits (paused, a question), at every command the
 * controller executed (the link's on_exec), in every host sleep slice (mon_host.tick) and
 * in the robot words' progress of long waits. Keys read there are requests to the run
 * (console_run.c). The screens are a file each (console_state.h lists them). */
#define _GNU_SOURCE /* fopencookie: the engine's output into the console's message pane */
#include "console.h"

#include <errno.h>
#include <string.h>
#include <unistd.h>
#include <curses.h>

#include "fbrl/vmx.h"
#include "console_cell.h"
#include "console_compose.h"
#include "console_form.h"
#include "console_library.h"
#include "console_line.h"
#include "console_run.h"
#include "console_text.h"
#include "console_users.h"

#define PUMP_MS 20 /* the screen is redrawn at most this often from inside a run */

static uint64_t now_us(void) { return mon_runlog_now_us(NULL); }

/* ---- drawing ---- */

static void draw_bar(console *c)
{
    const char *keys;
    if (c->line.mode == LINE_FORTH)
        keys = "Enter run the line   Esc back";
    else if (c->line.mode != LINE_NONE)
        keys = "Enter confirm   Esc cancel";
    else if (c->screen == SCREEN_LIBRARY)
        keys = "Up/Down choose  Enter open  F9 Level  F10 Quit";
    else if (c->screen == SCREEN_FORM)
        keys = c->level >= LEVEL_DEVELOPER ? "F5 Start  F2 Methods  F4 Compose  F6 Cell  F9 Level  F10 Quit"
                                           : "Up/Down field  F5 Start  F2 Methods  F9 Level  F10 Quit";
    else if (c->screen == SCREEN_COMPOSE)
        keys = "Up/Down step  Enter add  Bksp remove  F5 Save  Esc back";
    else if (c->screen == SCREEN_CELL)
        keys = "Up/Down choose  t TEACH the place  Esc back";
    else if (c->state == ST_RUNNING || c->state == ST_PAUSING || c->state == ST_ABORTING)
        keys = "F6 Pause  F8 Abort";
    else if (c->state == ST_PAUSED)
        keys = "F7 Resume  F8 Abort";
    else
        keys = "F5 Run again  F3 Parameters  F2 Methods  F9 Level  F10 Quit";
    if (c->abort_confirm && con_running(c))
        keys = "Abort the run?  y or F8 Abort   any other key Go on";
    attron(A_REVERSE);
    con_put_row(MIN_ROWS - 1, " %s%s", keys,
                c->level == LEVEL_PROGRAMMER && c->line.mode == LINE_NONE && c->state != ST_RUNNING &&
                        c->state != ST_PAUSED
                    ? "  F11 Forth"
                    : "");
    attroff(A_REVERSE);
}

static void draw(console *c)
{
    const int msg_row = BODY_TOP + BODY_ROWS, err_row = msg_row + 1 + MSG_LINES;
    int rows, cols;
    getmaxyx(stdscr, rows, cols);
    if (rows < MIN_ROWS || cols < MIN_COLS) {
        erase();
        con_put_row(0, "the console needs %dx%d (this terminal: %dx%d)", MIN_COLS, MIN_ROWS, cols, rows);
        refresh();
        return;
    }
    attron(A_REVERSE);
    con_put_row(0, " FBRL console | %-16s | level: %-10s | operator: %s",
                c->meth ? c->meth->name : "no method", con_level_names[c->level],
                c->log->operator_id[0] ? c->log->operator_id : "-");
    attroff(A_REVERSE);
    switch (c->screen) {
    case SCREEN_LIBRARY: con_library_draw(c); break;
    case SCREEN_FORM: con_form_draw(c); break;
    case SCREEN_COMPOSE: con_compose_draw(c); break;
    case SCREEN_CELL: con_cell_draw(c); break;
    case SCREEN_RUN: con_run_draw(c); break;
    }
    con_put_row(msg_row, "-- Messages ");
    con_put_at(msg_row, 40, " last command: %.26s", c->last_cmd);
    for (int i = 0; i < MSG_LINES; i++)
        con_put_row(msg_row + 1 + i, " %s", c->msgs[i]);
    con_put_row(err_row, "-- Last errors");
    con_put_row(err_row + 1, " %s", c->errs[0]);
    con_put_row(err_row + 2, "   %s", c->errs[0][0] ? c->advice[0] : "");
    con_line_draw(c);
    draw_bar(c);
    refresh();
    c->last_draw = now_us();
}

/* ---- keys ---- */

/* Keys outside a run: the function keys of the frame first, then the screen's own. */
static void idle_key(console *c, int ch)
{
    if (ch == KEY_F(10) || (ch == 'q' && c->screen != SCREEN_FORM))
        c->quit = 1;
    else if (ch == KEY_F(9))
        con_line_open(c, LINE_LEVEL);
    else if (ch == KEY_F(11) && c->level == LEVEL_PROGRAMMER)
        con_line_open(c, LINE_FORTH);
    else if (ch == KEY_F(4) && c->meth != NULL)
        con_compose_open(c);
    else if (ch == KEY_F(6))
        con_cell_open(c);
    else if (c->screen == SCREEN_CELL)
        con_cell_key(c, ch);
    else if (c->screen == SCREEN_COMPOSE) {
        if (con_compose_key(c, ch))
            con_line_open(c, LINE_METHOD_NAME);
    } else if (ch == KEY_F(2))
        con_library_open(c);
    else if (c->screen == SCREEN_LIBRARY)
        con_library_key(c, ch);
    else if (c->screen == SCREEN_FORM) {
        if (con_form_key(c, ch))
            con_run_start(c);
    } else if (ch == KEY_F(5)) /* a finished run */
        con_run_start(c);
    else if (ch == KEY_F(3)) {
        c->screen = SCREEN_FORM;
        c->state = ST_IDLE;
    }
}

static void key(console *c, int ch)
{
    if (ch == ERR || ch == KEY_RESIZE)
        return;
    cu_touch();
    if (cu_lab() && !cu_signed_in() && !con_running(c)) { /* nothing but signing in (or F10) */
        if (ch == KEY_F(10))
            c->quit = 1;
        else {
            if (!con_line_signing_in(c))
                con_line_ask_sign_in(c, "sign in: your name, Enter, then your password");
            con_line_key(c, ch);
        }
        return;
    }
    if (c->in_vm && !con_running(c) && c->state != ST_PAUSED) {
        if (ch == KEY_CTRL_C) /* the engine runs a typed line or loads a file: only Ctrl-C */
            fbrl_vm_interrupt(c->m->vm);
        return;
    }
    if (c->line.mode != LINE_NONE && !con_running(c))
        con_line_key(c, ch);
    else if (con_running(c) || c->state == ST_PAUSED)
        con_run_key(c, ch);
    else
        idle_key(c, ch);
}

/* From inside a run: read every key waiting, redraw now and then. */
static void pump(console *c, int force)
{
    int ch;
    if (c->outside)
        return;
    nodelay(stdscr, TRUE);
    while ((ch = getch()) != ERR)
        key(c, ch), force = 1;
    if (force || now_us() - c->last_draw >= PUMP_MS * 1000u)
        draw(c);
}

/* ---- hooks inside a run: the run screen takes what happened, then the screen lives ---- */

static void watch_arm(void *ctx, fbrl_robot *r)
{
    console *c = ctx;
    (void)r;
    if (con_run_watch(c))
        pump(c, 1);
}

static int hook_tick(void *ctx)
{
    console *c = ctx;
    pump(c, 0);
    return c->abort_asked;
}

static void hook_progress(void *ctx, const char *text)
{
    console *c = ctx;
    con_run_progress(c, text);
    pump(c, 1);
}

static void hook_exec(void *ctx, const char *line, size_t len, fbrl_status result)
{
    console *c = ctx;
    con_run_exec(c, line, len, result);
    pump(c, 0);
}

/* The console observes the run (as the run log does): what it shows follows the events. */
static int observe(void *ctx, fbrl_run *run, const fbrl_run_event *ev)
{
    console *c = ctx;
    if (ev->kind == FBRL_RUN_EV_WAIT) { /* paused or asking: the keys, the screen */
        draw(c);
        nodelay(stdscr, FALSE);
        timeout(200);
        key(c, getch());
        return 1;
    }
    con_run_event(c, run, ev);
    if (ev->kind == FBRL_RUN_EV_BEGIN)
        draw(c); /* the run view at once */
    pump(c, 1);
    return 0;
}

/* ---- the console's options and its loop ---- */

int console_option(console_options *o, const char *a, const char *v)
{
    if (strcmp(a, "--methods") == 0)
        o->methods = v;
    else if (strcmp(a, "--run-log") == 0)
        o->run_log = v;
    else if (strcmp(a, "--operator") == 0)
        o->operator_id = v;
    else if (strcmp(a, "--level") == 0) {
        if (strcmp(v, "operator") != 0 && strcmp(v, "developer") != 0 && strcmp(v, "programmer") != 0)
            return -1;
        o->level = v;
    } else
        return 1;
    return 0;
}

int console_run(mon *m, mon_runlog *log, const console_options *o)
{
    static console con; /* large; one console per process */
    console *c = &con;
    cookie_io_functions_t io = {NULL, con_out_write, NULL, NULL};
    FILE *old_out = m->host.out;
    int old_tty = m->host.out_is_tty;

    if (!isatty(STDIN_FILENO) || !isatty(STDOUT_FILENO)) {
        fprintf(stderr, "fbrlmon: --console needs a terminal\n");
        return -1;
    }
    memset(c, 0, sizeof *c);
    c->m = m;
    c->log = log;
    c->methods = o->methods ? o->methods : "methods";
    for (int l = LEVEL_OPERATOR; l <= LEVEL_PROGRAMMER; l++)
        if (o->level && strcmp(o->level, con_level_names[l]) == 0)
            c->level = (enum con_level)l;
    c->out = fopencookie(c, "w", io);
    if (c->out == NULL) {
        fprintf(stderr, "fbrlmon: --console: %s\n", strerror(errno));
        return -1;
    }
    setvbuf(c->out, NULL, _IONBF, 0);
    /* first the console, then the run log: the console's last reading of the arm at the
     * end of a run is a command of that run, in its log */
    if (fbrl_run_observe(&m->run, observe, c) != FBRL_OK || mon_runlog_observe_again(log) != 0) {
        fprintf(stderr, "fbrlmon: --console: cannot watch the method runs\n");
        fbrl_run_unobserve(&m->run, observe, c);
        fclose(c->out);
        return -1;
    }
    m->host.out = c->out;
    m->host.out_is_tty = 0;
    m->host.width = 0;
    m->host.tick = hook_tick;
    m->host.tick_ctx = c;
    fbrl_robot_set_console(&m->robot, hook_progress, c, 0);
    fbrl_robot_set_watch(&m->robot, watch_arm, c);
    log->exec_hook = hook_exec;
    log->exec_hook_ctx = c;
    log->error_hook = con_run_log_failed;
    log->error_hook_ctx = c;
    log->quiet = 1;

    initscr();
    raw();
    noecho();
    keypad(stdscr, TRUE);
    set_escdelay(100); /* Esc leaves the Forth line at once, not after a second */
    curs_set(0);
    con_library_scan(c);
    if (c->nlib > 0 && !c->hint[0])
        con_hint(c, "choose a method and press Enter");
    cu_start(log);
    if (cu_lab())
        con_line_ask_sign_in(c, "sign in: your name, Enter, then your password");
    while (!c->quit && !fbrl_vm_bye(m->vm)) {
        draw(c);
        nodelay(stdscr, FALSE);
        timeout(1000); /* the clock and the arm panel stay fresh */
        key(c, getch());
        if (cu_idle(con_running(c)))
            con_line_ask_sign_in(c, "signed out: the console was idle; sign in again");
    }
    endwin();
    cu_end();

    fbrl_run_unobserve(&m->run, observe, c);
    log->error_hook = NULL;
    log->quiet = 0;
    log->exec_hook = NULL;
    fbrl_robot_set_console(&m->robot, NULL, NULL, 0);
    fbrl_robot_set_watch(&m->robot, NULL, NULL);
    m->host.tick = NULL;
    m->host.out = old_out;
    m->host.out_is_tty = old_tty;
    fclose(c->out);
    return 0;
}
