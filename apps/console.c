/* SPDX-License-Identifier: MIT */
/* console.c - the operator console (fbrlmon --console), on ncurses.
 *
 * One thread: the method runs in the FBRL engine (the method run, fbrl/run.h), and the
 * screen is kept alive from inside it: at the run's events (the console observes the run
 * as the run log does), while the run waits (paused, a question), at every command the
 * controller executed (the link's on_exec), in every host sleep slice (mon_host.tick) and
 * in the robot words' progress of long waits. Keys read there are requests to the run:
 * pause (after the current step), resume, abort (the running word stops at once; the run
 * makes the safe stop and runs the method's ON-ABORT), an answer. What the screen shows
 * of a run is the run's snapshot. docs/console.md. */
#define _GNU_SOURCE /* fopencookie: the engine's output into the console's message pane */
#include "console.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <curses.h>

#include "fbrl/glossary.h"
#include "fbrl/vmx.h"
#include "mon.h"
#include "mon_recover.h"
#include "console_users.h"
#include "mon_runlog.h"
#include "mon_ws.h"

#define LIB_MAX       64 /* method files shown */
#define LIB_HEAD_BYTES 65536 /* the head of a method file looked at for its METHOD line */
#define MSG_LINES     4  /* method output lines shown */
#define ERR_LINES     2  /* last errors shown (each with what to do) */
#define FIELD_MAX     12 /* characters of a parameter's field */
#define MIN_COLS      80
#define MIN_ROWS      24
#define KEY_CTRL_C    3
#define KEY_ESCAPE    27
#define PUMP_MS       20 /* the screen is redrawn at most this often from inside a run */
#define RIGHT_COL     50 /* the live panel (arm, gripper, devices) starts here */
#define DEVICES_SHOWN 8
#define CELL_MAX      128 /* named places and devices the work-cell view lists */

enum level { LEVEL_OPERATOR, LEVEL_DEVELOPER, LEVEL_PROGRAMMER };
static const char *const level_names[] = {"operator", "developer", "programmer"};

enum con_screen { SCREEN_LIBRARY, SCREEN_FORM, SCREEN_RUN, SCREEN_COMPOSE, SCREEN_CELL };
enum state { ST_IDLE, ST_RUNNING, ST_PAUSING, ST_PAUSED, ST_ABORTING, ST_DONE, ST_ABORTED, ST_FAILED, ST_PARTIAL };
static const char *const state_names[] = {"READY",   "RUNNING", "PAUSING (after this step)",
                                          "PAUSED",  "ABORTING", "DONE",
                                          "ABORTED", "FAILED",   "PARTIAL"};

typedef struct lib_entry {
    char path[MON_RUNLOG_PATH_MAX];
    char name[FBRL_METHOD_NAME_MAX + 1];
    char text[FBRL_METHOD_TEXT_MAX + 1];
} lib_entry;

typedef struct console {
    mon *m;
    mon_runlog *log;
    const console_options *o;
    int level;
    enum con_screen screen;
    enum state state;
    int quit;
    /* the library */
    lib_entry lib[LIB_MAX];
    size_t nlib, sel;
    const fbrl_method *meth;
    const lib_entry *entry;
    /* the parameter form */
    char field[FBRL_METHOD_MAX_PARAMS][FIELD_MAX + 1];
    size_t fsel;
    int fresh; /* the selected field was just entered: the first character typed replaces it */
    /* the run: what it shows is the run's snapshot; the state follows its events */
    fbrl_run_snap snap;
    int abort_asked, abort_confirm, asking;
    int in_vm; /* the engine runs a line of the console's (Forth line, loading, a run) */
    uint64_t last_draw;
    /* the live view, from what the controller executed */
    uint32_t outputs;
    fbrl_rapl_pos pos; /* W2, read when the arm stands still: paused, stopped, finished */
    int have_pos;
    char pos_when[24];
    char grip[40];
    char last_cmd[FBRL_LINK_LINE_MAX + 1];
    char devname[FBRL_ROBOT_IO_MAX + 1][FBRL_METHOD_NAME_MAX + 1];
    /* method output and errors */
    char msgs[MSG_LINES][MIN_COLS + 1];
    char partial[MIN_COLS + 1];
    size_t plen;
    char errs[ERR_LINES][160];
    char advice[ERR_LINES][160];
    char hint[160];
    /* a line being typed: Forth (programmer), or signing in */
    int typing; /* 0 none, 1 Forth, 3 level choice, 4 a new method's name, 5 sign-in name, 6 password */
    char who[FBRL_AUDIT_NAME_MAX + 1]; /* the name being signed in */
    /* composing a method from the chosen method's steps (method developer) */
    size_t csel, picked[FBRL_METHOD_MAX_STEPS], npicked;
    /* the work-cell view: locations and devices by name (method developer) */
    char cell[CELL_MAX][MIN_COLS];
    size_t ncell, ctop, cpick; /* cpick: the selected row */
    int outside;               /* curses is off (TEACH has the terminal): nothing is drawn */
    enum con_screen cell_back; /* the screen Esc goes back to */
    char typed[128];
    size_t tlen;
    FILE *out;
} console;

/* ---- text helpers ---- */

/* snprintf for the screen's texts: cutting a text at its field's end is what is meant */
static void textf(char *buf, size_t cap, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static void textf(char *buf, size_t cap, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, cap, fmt, ap);
    va_end(ap);
}

static void put_row(int row, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static void put_row(int row, const char *fmt, ...)
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

static void put_at(int row, int col, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static void put_at(int row, int col, const char *fmt, ...)
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

static void fmt_time(char *buf, size_t cap, double ms)
{
    long s = ms < 0 ? 0 : (long)(ms / 1000.0 + 0.5);
    textf(buf, cap, "%ld:%02ld", s / 60, s % 60);
}

static void push_msg(console *c, const char *s)
{
    memmove(c->msgs[0], c->msgs[1], sizeof c->msgs[0] * (MSG_LINES - 1));
    textf(c->msgs[MSG_LINES - 1], sizeof c->msgs[0], "%s", s);
}

/* An error in plain words with what to do; the newest is shown first. */
static void push_error(console *c, const char *where, const char *msg)
{
    memmove(c->errs[1], c->errs[0], sizeof c->errs[0] * (ERR_LINES - 1));
    memmove(c->advice[1], c->advice[0], sizeof c->advice[0] * (ERR_LINES - 1));
    textf(c->errs[0], sizeof c->errs[0], "%s%s%s", where ? where : "", where ? ": " : "", msg);
    textf(c->advice[0], sizeof c->advice[0], "-> %s", mon_runlog_advice(msg));
}

/* The engine's output: whole lines into the message pane. */
static ssize_t cookie_write(void *ctx, const char *s, size_t n)
{
    console *c = ctx;
    for (size_t i = 0; i < n; i++) {
        if (s[i] == '\n' || c->plen + 1 >= sizeof c->partial) {
            c->partial[c->plen] = '\0';
            push_msg(c, c->partial);
            c->plen = 0;
            if (s[i] == '\n')
                continue;
        }
        if ((unsigned char)s[i] >= 0x20)
            c->partial[c->plen++] = s[i];
    }
    return (ssize_t)n;
}

/* Method output without a line end yet: show it. */
static void flush_partial(console *c)
{
    if (c->plen > 0) {
        c->partial[c->plen] = '\0';
        push_msg(c, c->partial);
        c->plen = 0;
    }
}

/* The last error of the engine as "file:line: message [in WORD]" (the form editors parse). */
static void engine_error(console *c, char *buf, size_t cap)
{
    const fbrl_vm_error *e = fbrl_vm_last_error(c->m->vm);
    if (e == NULL) {
        textf(buf, cap, "error");
        return;
    }
    if (e->file[0] && e->line > 0)
        textf(buf, cap, "%s:%lu: %s%s%s", e->file, e->line, e->message, e->word[0] ? " in " : "", e->word);
    else
        textf(buf, cap, "%s%s%s", e->message, e->word[0] ? " in " : "", e->word);
}

/* ---- the method library: a folder of method files ---- */

/* The first "METHOD name text" line of a file, read as text (the file is loaded only when
 * it is chosen): 1 found, 0 none, -1 not a regular file (a device such as /dev/zero, a
 * FIFO: opened without waiting for a writer, and never read). Only the head is read. */
static int scan_method_file(const char *path, lib_entry *e)
{
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    struct stat sb;
    FILE *f;
    char line[512];
    long head = 0;
    int found = 0;
    if (fd < 0)
        return 0;
    if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
        close(fd);
        return -1;
    }
    f = fdopen(fd, "r");
    if (f == NULL) {
        close(fd);
        return 0;
    }
    while (!found && head < LIB_HEAD_BYTES && fgets(line, sizeof line, f) != NULL) {
        head += (long)strlen(line);
        char *p = line;
        while (*p == ' ' || *p == '\t')
            p++;
        if (strncasecmp(p, "METHOD", 6) != 0 || (p[6] != ' ' && p[6] != '\t'))
            continue;
        p += 6;
        while (*p == ' ' || *p == '\t')
            p++;
        size_t n = strcspn(p, " \t\r\n");
        if (n == 0 || n > FBRL_METHOD_NAME_MAX)
            continue;
        memcpy(e->name, p, n);
        e->name[n] = '\0';
        p += n;
        while (*p == ' ' || *p == '\t')
            p++;
        p[strcspn(p, "\r\n")] = '\0';
        textf(e->text, sizeof e->text, "%s", p);
        textf(e->path, sizeof e->path, "%s", path);
        found = 1;
    }
    fclose(f);
    return found;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(((const lib_entry *)a)->name, ((const lib_entry *)b)->name);
}

static void scan_library(console *c)
{
    const char *dir = c->o->methods ? c->o->methods : "methods";
    DIR *d = opendir(dir);
    struct dirent *de;
    char odd[64] = "";
    size_t nodd = 0;
    c->nlib = 0;
    if (d == NULL) {
        textf(c->hint, sizeof c->hint, "method library %s: %s", dir, strerror(errno));
        return;
    }
    while ((de = readdir(d)) != NULL && c->nlib < LIB_MAX) {
        size_t n = strlen(de->d_name);
        char path[MON_RUNLOG_PATH_MAX];
        if (n < 6 || strcmp(de->d_name + n - 5, ".fbrl") != 0)
            continue;
        textf(path, sizeof path, "%s/%s", dir, de->d_name);
        int got = scan_method_file(path, &c->lib[c->nlib]);
        if (got > 0)
            c->nlib++;
        else if (got < 0 && nodd++ == 0)
            textf(odd, sizeof odd, "%s", de->d_name);
    }
    closedir(d);
    qsort(c->lib, c->nlib, sizeof c->lib[0], by_name);
    if (nodd > 0) /* said, so a method that is missing from the list is explained */
        textf(c->hint, sizeof c->hint, "left out %s%s: not a regular file", odd,
              nodd > 1 ? " and others" : "");
    else if (c->nlib == 0)
        textf(c->hint, sizeof c->hint, "no method files (*.fbrl with a METHOD line) in %s", dir);
}

/* Device names: the words the cell file made with OUTPUT-DEVICE. */
static int find_device(void *ctx, const char *name, size_t len)
{
    console *c = ctx;
    fbrl_cell xt;
    fbrl_robot_device d;
    if (len <= FBRL_METHOD_NAME_MAX && fbrl_vmx_find(c->m->vm, name, len, &xt) == FBRL_OK &&
        fbrl_robot_device_of(&c->m->robot, xt, &d) == FBRL_OK && d.output && !c->devname[d.port][0]) {
        memcpy(c->devname[d.port], name, len);
        c->devname[d.port][len] = '\0';
    }
    return 0;
}

static void fill_form(console *c)
{
    for (size_t k = 0; c->meth && k < c->meth->nparams; k++) {
        long v = 0;
        fbrl_method_param_get(&c->m->methods, c->meth, k, &v);
        textf(c->field[k], sizeof c->field[k], "%ld", v);
    }
    c->fsel = 0;
    c->fresh = 1;
}

/* A taught place the method file defined again keeps its taught value: said under Messages. */
static void kept_taught(void *ctx, const char *name, const fbrl_loc *taught, const fbrl_loc *file)
{
    console *c = ctx;
    char line[MIN_COLS + 1];
    textf(line, sizeof line, "kept taught %s X%.2f Y%.2f Z%.2f (file: X%.2f Y%.2f Z%.2f)", name, taught->x,
          taught->y, taught->z, file->x, file->y, file->z);
    push_msg(c, line);
}

static void choose_method(console *c, const lib_entry *e)
{
    const fbrl_method *meth = fbrl_method_find(&c->m->methods, e->name);
    size_t kept = 0;
    if (meth == NULL || !meth->complete) {
        textf(c->hint, sizeof c->hint, "loading %s ...", e->path);
        fflush(c->out);
        mon_ws_protect(c->m); /* the method file's DEFINE-LOC does not overwrite a taught place */
        c->in_vm++;
        fbrl_status st = fbrl_vm_include(c->m->vm, e->path);
        c->in_vm--;
        kept = mon_ws_restore(c->m, kept_taught, c);
        if (st != FBRL_OK) {
            char msg[400];
            engine_error(c, msg, sizeof msg);
            fbrl_vm_reset(c->m->vm);
            push_error(c, NULL, msg);
            textf(c->hint, sizeof c->hint, "%s did not load: see the errors", e->path);
            return;
        }
        meth = fbrl_method_find(&c->m->methods, e->name);
    }
    if (meth == NULL || !meth->complete) {
        textf(c->hint, sizeof c->hint, "%s: no complete METHOD %s in it", e->path, e->name);
        return;
    }
    c->meth = meth;
    c->entry = e;
    memset(c->devname, 0, sizeof c->devname);
    fbrl_vm_words(c->m->vm, find_device, c);
    fill_form(c);
    c->screen = SCREEN_FORM;
    c->state = ST_IDLE;
    if (kept > 0)
        textf(c->hint, sizeof c->hint, "%zu taught place%s kept over the method file's (see Messages); F5 starts",
              kept, kept == 1 ? "" : "s");
    else
        textf(c->hint, sizeof c->hint, "fill in the parameters, then F5 to start");
}

/* ---- the parameter form: each field checked against its range ---- */

/* 0 and *v if the text is a whole number in range; else -1 and why in msg. */
static int check_field(const fbrl_method_param *p, const char *text, long *v, char *msg, size_t cap)
{
    char *end;
    const char *s = text;
    while (*s == ' ')
        s++;
    if (*s == '\0') {
        textf(msg, cap, "%s is empty: enter a whole number %ld..%ld %s", p->name, p->min, p->max, p->unit);
        return -1;
    }
    errno = 0;
    long n = strtol(s, &end, 10);
    while (*end == ' ')
        end++;
    if (*end != '\0' || errno != 0) {
        textf(msg, cap, "%s: '%s' is not a whole number: enter %ld..%ld %s", p->name, s, p->min, p->max,
              p->unit);
        return -1;
    }
    if (n < p->min || n > p->max) {
        textf(msg, cap, "%s: %ld is outside the allowed range %ld..%ld %s", p->name, n, p->min, p->max,
              p->unit);
        return -1;
    }
    *v = n;
    return 0;
}

/* Every field checked; the first bad one selected and named. 0 and the values in v if all
 * are good (the run sets them). */
static int commit_form(console *c, long *v)
{
    char msg[160];
    for (size_t k = 0; k < c->meth->nparams; k++)
        if (check_field(&c->meth->params[k], c->field[k], &v[k], msg, sizeof msg) != 0) {
            c->fsel = k;
            c->fresh = 1;
            textf(c->hint, sizeof c->hint, "refused: %s", msg);
            return -1;
        }
    return 0;
}

/* ---- drawing ---- */

static uint64_t now_us(void) { return mon_runlog_now_us(NULL); }

static int running(const console *c) { return c->state >= ST_RUNNING && c->state <= ST_ABORTING; }

static void draw_bar(console *c)
{
    const char *keys;
    if (c->typing == 1)
        keys = "Enter run the line   Esc back";
    else if (c->typing)
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
    if (c->abort_confirm && running(c))
        keys = "Abort the run?  y or F8 Abort   any other key Go on";
    attron(A_REVERSE);
    put_row(MIN_ROWS - 1, " %s%s", keys,
            c->level == LEVEL_PROGRAMMER && !c->typing && c->state != ST_RUNNING && c->state != ST_PAUSED
                ? "  F11 Forth"
                : "");
    attroff(A_REVERSE);
}

static void draw_live(console *c)
{
    const fbrl_rapl_pos *p = c->have_pos ? &c->pos : NULL;
    int row = 2, shown = 0;
    put_at(row++, RIGHT_COL, "| Arm %s", c->have_pos ? c->pos_when : "(read when it stands)");
    if (p != NULL && p->nworld >= 6)
        put_at(row++, RIGHT_COL, "|  X%7.2f Y%7.2f Z%7.2f", p->world[0], p->world[1], p->world[2]);
    else
        put_at(row++, RIGHT_COL, "|  not read yet (in, deg)");
    if (p != NULL && p->nworld >= 6)
        put_at(row++, RIGHT_COL, "|  pitch%7.1f roll%7.1f", p->world[4], p->world[5]);
    else
        put_at(row++, RIGHT_COL, "|");
    put_at(row++, RIGHT_COL, "| Gripper: %s", c->grip[0] ? c->grip : "not used yet");
    put_at(row++, RIGHT_COL, "| Devices");
    for (int n = 1; n <= FBRL_ROBOT_IO_MAX && shown < DEVICES_SHOWN; n++) {
        int on = (c->outputs >> (n - 1)) & 1u;
        if (!c->devname[n][0] && !on)
            continue;
        put_at(row++, RIGHT_COL, "|  %-18.18s %s", c->devname[n][0] ? c->devname[n] : "output",
               on ? "ON" : "off");
        shown++;
    }
    while (row < 14)
        put_at(row++, RIGHT_COL, "|");
}

/* The samples and their outcomes so far, on one line of the left half: "1 ok 2 FAILED ...". */
static void draw_samples(console *c, int row)
{
    const fbrl_run_snap *s = &c->snap;
    char line[RIGHT_COL + 1];
    size_t n;
    if (s->samples <= 0)
        return;
    n = (size_t)snprintf(line, sizeof line, " samples %ld/%ld done:", s->samples_done, s->samples);
    for (long i = 0; i < s->samples && n + 1 < sizeof line; i++) {
        static const char *const marks[] = {"..", "ok", "FAILED", "skipped"};
        uint8_t o = s->outcomes[i].outcome;
        int k = snprintf(line + n, sizeof line - n, " %ld %s", i + 1, o < 4 ? marks[o] : "?");
        if (k < 0 || (size_t)k >= sizeof line - n) { /* no room for the rest: say so */
            memcpy(line + sizeof line - 5, " ...", 5);
            break;
        }
        n += (size_t)k;
    }
    put_row(row, "%s", line);
}

static void draw_run(console *c)
{
    const fbrl_run_snap *s = &c->snap;
    char el[16], left[16];
    long nsteps = s->nsteps < 12 ? s->nsteps : 12;
    int live = c->state != ST_IDLE && c->state < ST_DONE;
    fmt_time(el, sizeof el, (double)s->elapsed_ms);
    if (c->state >= ST_DONE)
        textf(left, sizeof left, "0:00");
    else if (s->remaining_ms >= 0)
        fmt_time(left, sizeof left, (double)s->remaining_ms), memmove(left + 1, left, strlen(left) + 1),
            left[0] = '~';
    else
        textf(left, sizeof left, "--:--");
    attron(A_BOLD);
    put_row(1, " %-26s elapsed %s  remaining %s", state_names[c->state], el, left);
    attroff(A_BOLD);
    for (long k = 0; k < nsteps; k++) {
        const char *mark = s->step_failed[k]              ? "!!"
                           : s->step_done[k] >= s->step_runs[k] ? "ok"
                           : k == s->step && live          ? "->"
                                                           : "  ";
        char prog[24] = "";
        if (s->per_sample[k]) /* progress counts samples done, not samples started */
            textf(prog, sizeof prog, "sample %ld/%ld", s->step_done[k], s->step_runs[k]);
        if (k == s->step && live)
            attron(A_REVERSE);
        put_row(2 + (int)k, " %s %2ld %-14.14s %-16s", mark, k + 1, s->step_name[k], prog);
        if (k == s->step && live)
            attroff(A_REVERSE);
    }
    for (long k = nsteps; k < 12; k++)
        put_row(2 + (int)k, " ");
    if (nsteps < 12)
        draw_samples(c, 2 + (int)nsteps + (nsteps < 11));
}

static void draw_library(console *c)
{
    put_row(1, " Method library: %s", c->o->methods ? c->o->methods : "methods");
    for (size_t i = 0; i < 12; i++) {
        if (i < c->nlib) {
            if (i == c->sel)
                attron(A_REVERSE);
            put_row(2 + (int)i, " %-16s %s", c->lib[i].name, c->lib[i].text);
            if (i == c->sel)
                attroff(A_REVERSE);
        } else {
            put_row(2 + (int)i, " ");
        }
    }
}

static void draw_form(console *c)
{
    const fbrl_method *m = c->meth;
    put_row(1, " Parameters of %s (%s)", m->name, m->text);
    for (size_t k = 0; k < 12; k++) {
        if (k < m->nparams) {
            const fbrl_method_param *p = &m->params[k];
            put_row(2 + (int)k, " %-14.14s [", p->name);
            if (k == c->fsel)
                attron(A_REVERSE);
            put_at(2 + (int)k, 17, "%-*s", FIELD_MAX, c->field[k]);
            if (k == c->fsel)
                attroff(A_REVERSE);
            put_at(2 + (int)k, 17 + FIELD_MAX, "] %-7.7s %ld..%ld  %.30s", p->unit, p->min, p->max, p->text);
        } else {
            put_row(2 + (int)k, " ");
        }
    }
}

/* The composer: the chosen method's steps on the left, the new method's on the right. */
static void draw_compose(console *c)
{
    const fbrl_method *m = c->meth;
    put_row(1, " Compose a method from the steps of %s", m->name);
    for (size_t k = 0; k < 12; k++) {
        put_row(2 + (int)k, " ");
        if (k < m->nsteps) {
            if (k == c->csel)
                attron(A_REVERSE);
            put_at(2 + (int)k, 1, "%-14.14s %-10s", m->steps[k].name,
                   m->steps[k].per_sample ? "per sample" : "");
            if (k == c->csel)
                attroff(A_REVERSE);
        }
        put_at(2 + (int)k, 34, "|");
        if (k < c->npicked)
            put_at(2 + (int)k, 36, "%2zu. %-14.14s %.24s", k + 1, m->steps[c->picked[k]].name,
                   m->steps[c->picked[k]].text);
    }
}

/* The work cell: every named location (CREATE-LOC) and device, newest definitions first. */
static int add_cell(void *ctx, const char *name, size_t len)
{
    console *c = ctx;
    fbrl_cell xt, addr;
    fbrl_loc *l;
    fbrl_robot_device d;
    char nm[FBRL_VMX_NAME_MAX + 1];
    if (c->ncell >= CELL_MAX || len > FBRL_VMX_NAME_MAX || fbrl_vmx_find(c->m->vm, name, len, &xt) != FBRL_OK)
        return c->ncell >= CELL_MAX;
    memcpy(nm, name, len);
    nm[len] = '\0';
    for (size_t i = 0; i < c->ncell; i++) /* a name defined again: the newest only */
        if (strncmp(c->cell[i] + 1, nm, len) == 0 && c->cell[i][1 + len] == ' ')
            return 0;
    if (fbrl_glossary_loc_word(c->m->vm, xt, &addr) == FBRL_OK &&
        fbrl_glossary_loc(c->m->vm, addr, &l) == FBRL_OK)
        textf(c->cell[c->ncell++], sizeof c->cell[0],
              " %-17s place X%7.2f Y%7.2f Z%7.2f  pitch%6.1f roll%6.1f", nm, l->x, l->y, l->z, l->a, l->t);
    else if (fbrl_robot_device_of(&c->m->robot, xt, &d) == FBRL_OK)
        textf(c->cell[c->ncell++], sizeof c->cell[0], " %-17s %-6s controller %s %d", nm,
              d.output ? "device" : "sensor", d.output ? "output" : "input", d.port);
    return 0;
}

static int by_text(const void *a, const void *b) { return strcmp((const char *)a, (const char *)b); }

static void scan_cell(console *c)
{
    c->ncell = c->ctop = c->cpick = 0;
    fbrl_vm_words(c->m->vm, add_cell, c);
    qsort(c->cell, c->ncell, sizeof c->cell[0], by_text); /* by name */
}

static void draw_cell(console *c)
{
    put_row(1, " Work cell: %zu named places and devices (in, deg)", c->ncell);
    for (size_t k = 0; k < 12; k++) {
        if (c->ctop + k == c->cpick)
            attron(A_REVERSE);
        put_row(2 + (int)k, "%s", c->ctop + k < c->ncell ? c->cell[c->ctop + k] : "");
        if (c->ctop + k == c->cpick)
            attroff(A_REVERSE);
    }
}

static void draw(console *c)
{
    int rows, cols;
    getmaxyx(stdscr, rows, cols);
    if (rows < MIN_ROWS || cols < MIN_COLS) {
        erase();
        put_row(0, "the console needs %dx%d (this terminal: %dx%d)", MIN_COLS, MIN_ROWS, cols, rows);
        refresh();
        return;
    }
    if (c->screen == SCREEN_RUN && fbrl_run_snapshot(&c->m->run, &c->snap) == FBRL_OK && running(c)) {
        /* a request the run has not taken yet shows at once (the run's own view) */
        if (c->snap.state == FBRL_RUN_PAUSING)
            c->state = ST_PAUSING;
        else if (c->snap.state == FBRL_RUN_ABORTING)
            c->state = ST_ABORTING;
    }
    attron(A_REVERSE);
    put_row(0, " FBRL console | %-16s | level: %-10s | operator: %s", c->meth ? c->meth->name : "no method",
            level_names[c->level], c->log->operator_id[0] ? c->log->operator_id : "-");
    attroff(A_REVERSE);
    if (c->screen == SCREEN_LIBRARY)
        draw_library(c);
    else if (c->screen == SCREEN_FORM)
        draw_form(c);
    else if (c->screen == SCREEN_COMPOSE)
        draw_compose(c);
    else if (c->screen == SCREEN_CELL)
        draw_cell(c);
    else
        draw_run(c);
    if (c->screen == SCREEN_RUN)
        draw_live(c);
    put_row(14, "-- Messages %s", c->last_cmd[0] ? "" : "");
    put_at(14, 40, " last command: %.26s", c->last_cmd);
    for (int i = 0; i < MSG_LINES; i++)
        put_row(15 + i, " %s", c->msgs[i]);
    put_row(19, "-- Last errors");
    for (int i = 0; i < ERR_LINES; i++) {
        put_row(20 + i * 0, " ");
    }
    put_row(20, " %s", c->errs[0]);
    put_row(21, "   %s", c->errs[0][0] ? c->advice[0] : "");
    if (c->typing >= 5) /* why the last sign-in failed, or what to do */
        put_row(21, " %s", c->hint);
    if (c->typing == 1)
        put_row(22, "ok> %s", c->typed);
    else if (c->typing == 3)
        put_row(22, "level: 1 operator  2 developer  3 programmer%s ?", cu_lab() ? "  s sign out" : "");
    else if (c->typing == 5)
        put_row(22, "sign in: name: %s", c->typed);
    else if (c->typing == 6)
        put_row(22, "sign in: password for %s: %.*s", c->who, (int)(c->tlen < 16 ? c->tlen : 16), "****************");
    else if (c->typing == 4)
        put_row(22, "name of the new method: %s", c->typed);
    else
        put_row(22, "%s", c->hint);
    draw_bar(c);
    refresh();
    c->last_draw = now_us();
}

/* ---- composing a method (method developer): saved as a method file ---- */

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
 * declares the picked steps. Nothing is written when anything is wrong. */
static void save_composed(console *c, const char *typed)
{
    const fbrl_method *m = c->meth;
    const char *dir = c->o->methods ? c->o->methods : "methods";
    const char *src = c->entry ? strrchr(c->entry->path, '/') : NULL;
    char name[FBRL_METHOD_NAME_MAX + 1], path[MON_RUNLOG_PATH_MAX], file[FBRL_METHOD_NAME_MAX + 1];
    size_t n = strlen(typed);
    xt_find f;
    if (n == 0 || n > FBRL_METHOD_NAME_MAX) {
        textf(c->hint, sizeof c->hint, "not saved: a name of 1..%d letters, digits and -",
              FBRL_METHOD_NAME_MAX);
        return;
    }
    for (size_t i = 0; i <= n; i++) {
        char ch = (char)toupper((unsigned char)typed[i]);
        if (ch && !isalnum((unsigned char)ch) && ch != '-') {
            textf(c->hint, sizeof c->hint, "not saved: '%s': only letters, digits and - in a name", typed);
            return;
        }
        name[i] = ch;
        file[i] = ch == '-' ? '_' : (char)tolower((unsigned char)ch);
    }
    for (size_t i = 0; i < c->nlib; i++)
        if (strcmp(c->lib[i].name, name) == 0) {
            textf(c->hint, sizeof c->hint, "not saved: the library has %s already", name);
            return;
        }
    if (src == NULL || c->npicked == 0) {
        textf(c->hint, sizeof c->hint, "not saved: %s",
              c->npicked ? "the method's file is unknown" : "no steps");
        return;
    }
    textf(path, sizeof path, "%s/%s.fbrl", dir, file);
    if (access(path, F_OK) == 0) {
        textf(c->hint, sizeof c->hint, "not saved: %s exists", path);
        return;
    }
    for (size_t k = 0; k < c->npicked; k++)
        if (!word_of(c, m->steps[c->picked[k]].xt, &f)[0]) {
            textf(c->hint, sizeof c->hint, "not saved: step %s has no word name",
                  m->steps[c->picked[k]].name);
            return;
        }
    FILE *out = fopen(path, "wx");
    if (out == NULL) {
        textf(c->hint, sizeof c->hint, "not saved: %s: %s", path, strerror(errno));
        return;
    }
    fprintf(out, "\\ %s.fbrl - composed in the operator console from the steps of %s (%s)\n", file, m->name,
            c->log->operator_id);
    fprintf(out, "INCLUDE %s\n", src + 1);
    fprintf(out, "METHOD %s  %s steps:", name, m->name);
    for (size_t k = 0; k < c->npicked; k++)
        fprintf(out, " %s", m->steps[c->picked[k]].name);
    fprintf(out, "\n%s USE-PARAMS\n", m->name);
    for (size_t k = 0; k < c->npicked; k++) {
        const fbrl_method_step *st = &m->steps[c->picked[k]];
        fprintf(out, "' %s %s %s  %s\n", word_of(c, st->xt, &f), st->per_sample ? "SAMPLE-STEP" : "STEP",
                st->name, st->text);
    }
    if (m->abort_xt && word_of(c, m->abort_xt, &f)[0])
        fprintf(out, "' %s ON-ABORT\n", f.name);
    fprintf(out, "END-METHOD\n");
    if (fclose(out) != 0) {
        textf(c->hint, sizeof c->hint, "not saved: %s: %s", path, strerror(errno));
        remove(path);
        return;
    }
    scan_library(c);
    c->screen = SCREEN_LIBRARY;
    for (size_t i = 0; i < c->nlib; i++)
        if (strcmp(c->lib[i].name, name) == 0)
            c->sel = i;
    textf(c->hint, sizeof c->hint, "saved %s as %s.fbrl in the library: Enter opens it", name, file);
    cu_action("compose", name, path);
}

static void compose_key(console *c, int ch)
{
    if (ch == KEY_UP && c->csel > 0)
        c->csel--;
    else if (ch == KEY_DOWN && c->csel + 1 < c->meth->nsteps)
        c->csel++;
    else if ((ch == '\n' || ch == '\r' || ch == KEY_ENTER || ch == ' ') && c->npicked < FBRL_METHOD_MAX_STEPS)
        c->picked[c->npicked++] = c->csel;
    else if ((ch == KEY_BACKSPACE || ch == 127 || ch == 8) && c->npicked > 0)
        c->npicked--;
    else if (ch == KEY_ESCAPE)
        c->screen = SCREEN_FORM;
    else if (ch == KEY_F(5)) {
        c->typing = 4;
        c->tlen = 0;
        c->typed[0] = '\0';
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
        textf(c->hint, sizeof c->hint, "only a place can be taught");
        return;
    }
    memcpy(name, row + 1, n);
    name[n] = '\0';
    textf(before, sizeof before, "%s", row);
    textf(text, sizeof text, "TEACH %s", name);
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
        engine_error(c, msg, sizeof msg);
        push_error(c, "TEACH", msg);
    } else {
        mon_ws_taught(c->m, name); /* a method file opened later does not overwrite it */
    }
    scan_cell(c);
    for (size_t i = 0; i < c->ncell; i++)
        if (strncmp(c->cell[i] + 1, name, n) == 0 && c->cell[i][1 + n] == ' ') {
            c->cpick = i, c->ctop = i >= 12 ? i - 11 : 0;
            if (strcmp(c->cell[i], before) != 0) { /* taught: the place as it was and is */
                char detail[2 * MIN_COLS + 16];
                const char *was = strstr(before, " place "), *now = strstr(c->cell[i], " place ");
                textf(detail, sizeof detail, "was %s; now %s", was ? was + 7 : before, now ? now + 7 : c->cell[i]);
                cu_action("teach", name, detail);
            }
        }
    textf(c->hint, sizeof c->hint, "TEACH %s %s", name, st == FBRL_OK ? "done" : "did not store it");
}

/* ---- keys ---- */

static void start_run(console *c);

/* Down is free; up as far as the signed-in user's role allows (the lab's users: --lab). */
static void set_level(console *c, int want)
{
    if (want > c->level && !cu_lab()) {
        textf(c->hint, sizeof c->hint, "switching up needs the lab's users (--lab DIR), or start with --level %s",
              level_names[want]);
        return;
    }
    if (want > cu_level_max() && want > c->level) {
        textf(c->hint, sizeof c->hint, "%s's role (%s) allows the %s level: F9 s signs out for another user",
              c->log->operator_id, cu_role(), level_names[cu_level_max()]);
        return;
    }
    c->level = want;
    textf(c->hint, sizeof c->hint, "level: %s", level_names[want]);
    cu_action("level", level_names[want], NULL);
}

static void ask_sign_in(console *c, const char *why)
{
    c->typing = 5;
    c->tlen = 0;
    c->typed[0] = '\0';
    c->level = LEVEL_OPERATOR;
    textf(c->hint, sizeof c->hint, "%s", why);
}

static void typed_done(console *c)
{
    int mode = c->typing;
    c->typing = 0;
    if (mode == 5) {
        textf(c->who, sizeof c->who, "%s", c->typed);
        c->typing = c->tlen ? 6 : 5;
    } else if (mode == 6) {
        char msg[200];
        if (cu_sign_in(c->who, c->typed, msg, sizeof msg) == 0) {
            c->level = cu_level_max();
            textf(c->hint, sizeof c->hint, "%s", msg);
        } else {
            ask_sign_in(c, msg);
        }
    } else if (mode == 4) {
        save_composed(c, c->typed);
    } else if (mode == 1 && c->tlen > 0) {
        char text[sizeof c->typed];
        memcpy(text, c->typed, c->tlen + 1);
        push_msg(c, text);
        cu_action("forth", text, NULL);
        c->in_vm++;
        fbrl_status st = fbrl_vm_eval(c->m->vm, text, strlen(text));
        c->in_vm--;
        fbrl_vmx_take_interrupt(c->m->vm);
        if (st != FBRL_OK) {
            char msg[400];
            engine_error(c, msg, sizeof msg);
            push_error(c, "console", msg);
        }
        flush_partial(c);
        c->typing = 1; /* the prompt stays until Esc */
    }
    memset(c->typed, 0, sizeof c->typed); /* a password too */
    c->tlen = 0;
}

static void type_key(console *c, int ch)
{
    size_t cap = c->typing == 3 ? 1 : c->typing == 5 ? FBRL_AUDIT_NAME_MAX - 1 : sizeof c->typed - 1;
    if (c->typing == 3) {
        c->typing = 0;
        if (ch >= '1' && ch <= '3')
            set_level(c, ch - '1');
        else if ((ch == 's' || ch == 'S') && cu_lab()) {
            cu_sign_out("signed out");
            ask_sign_in(c, "signed out: the next user signs in");
        }
        return;
    }
    if (ch == KEY_ESCAPE && c->typing >= 5) { /* no way around signing in: start again */
        ask_sign_in(c, "sign in: your name, Enter, then your password");
    } else if (ch == KEY_ESCAPE) {
        c->typing = 0;
        c->tlen = 0;
        c->typed[0] = '\0';
    } else if (ch == '\n' || ch == '\r' || ch == KEY_ENTER) {
        typed_done(c);
    } else if ((ch == KEY_BACKSPACE || ch == 127 || ch == 8) && c->tlen > 0) {
        c->typed[--c->tlen] = '\0';
    } else if (ch >= 0x20 && ch < 0x7f && c->tlen < cap) {
        c->typed[c->tlen++] = (char)ch;
        c->typed[c->tlen] = '\0';
    }
}

static void request_abort(console *c)
{
    c->abort_confirm = 0;
    if (fbrl_run_abort(&c->m->run, c->log->operator_id) != FBRL_OK)
        return; /* it has just ended */
    c->abort_asked = 1;
    c->state = ST_ABORTING;
    textf(c->hint, sizeof c->hint, "aborting: the arm goes to its safe place, the outputs go off");
}

/* Keys while a method runs: pause, resume, abort, and the answer to a question. */
static void run_key(console *c, int ch)
{
    int up = ch >= 0 && ch < 256 ? toupper(ch) : 0;
    if (ch == KEY_CTRL_C) {
        request_abort(c);
    } else if (c->asking && (up == 'R' || up == 'S' || up == 'A')) {
        fbrl_run_choice choice = up == 'R' ? FBRL_RUN_RETRY : up == 'S' ? FBRL_RUN_SKIP : FBRL_RUN_STOP;
        if (fbrl_run_answer(&c->m->run, choice, c->log->operator_id) == FBRL_OK) {
            c->asking = 0;
            textf(c->hint, sizeof c->hint, "answered: %s", up == 'R' ? "retry" : up == 'S' ? "skip" : "abort");
        }
    } else if (c->abort_confirm) {
        if (ch == 'y' || ch == 'Y' || ch == KEY_F(8))
            request_abort(c);
        else {
            c->abort_confirm = 0;
            textf(c->hint, sizeof c->hint, "not aborted: the method goes on");
        }
    } else if (ch == KEY_F(8) || ch == 'a') {
        c->abort_confirm = 1;
        textf(c->hint, sizeof c->hint, "Abort the run? y or F8 = abort, any other key = go on");
    } else if ((ch == KEY_F(6) || ch == 'p') && c->state == ST_RUNNING) {
        if (fbrl_run_pause(&c->m->run, c->log->operator_id) == FBRL_OK) {
            c->state = ST_PAUSING;
            textf(c->hint, sizeof c->hint, "pausing after the current step ...");
        }
    } else if ((ch == KEY_F(7) || ch == 'r') && (c->state == ST_PAUSED || c->state == ST_PAUSING)) {
        if (fbrl_run_resume(&c->m->run, c->log->operator_id) == FBRL_OK) {
            c->state = ST_RUNNING;
            textf(c->hint, sizeof c->hint, "resumed");
        }
    }
}

static void idle_key(console *c, int ch)
{
    if (ch == KEY_F(10) || (ch == 'q' && c->screen != SCREEN_FORM)) {
        c->quit = 1;
    } else if (ch == KEY_F(9)) {
        c->typing = 3;
    } else if (ch == KEY_F(11) && c->level == LEVEL_PROGRAMMER) {
        c->typing = 1;
        c->tlen = 0;
        c->typed[0] = '\0';
    } else if (ch == KEY_F(4) && c->meth != NULL) {
        if (c->level < LEVEL_DEVELOPER)
            textf(c->hint, sizeof c->hint, "composing a method needs the developer level (F9)");
        else {
            c->screen = SCREEN_COMPOSE;
            c->csel = c->npicked = 0;
            textf(c->hint, sizeof c->hint, "Enter adds the highlighted step to the new method; F5 saves it");
        }
    } else if (ch == KEY_F(6)) {
        if (c->level < LEVEL_DEVELOPER)
            textf(c->hint, sizeof c->hint, "the work-cell view needs the developer level (F9)");
        else {
            c->cell_back = c->screen;
            c->screen = SCREEN_CELL;
            scan_cell(c);
            c->hint[0] = '\0';
        }
    } else if (c->screen == SCREEN_CELL) {
        if (ch == KEY_UP && c->cpick > 0)
            c->cpick--;
        else if (ch == KEY_DOWN && c->cpick + 1 < c->ncell)
            c->cpick++;
        else if ((ch == 't' || ch == 'T' || ch == '\n' || ch == '\r' || ch == KEY_ENTER) &&
                 c->cpick < c->ncell)
            teach_place(c, c->cell[c->cpick]);
        else if (ch == KEY_ESCAPE)
            c->screen = c->cell_back;
        if (c->cpick < c->ctop)
            c->ctop = c->cpick;
        else if (c->cpick >= c->ctop + 12)
            c->ctop = c->cpick - 11;
    } else if (c->screen == SCREEN_COMPOSE) {
        compose_key(c, ch);
    } else if (ch == KEY_F(2)) {
        c->screen = SCREEN_LIBRARY;
        scan_library(c);
        c->hint[0] = '\0';
    } else if (c->screen == SCREEN_LIBRARY) {
        if (ch == KEY_UP && c->sel > 0)
            c->sel--;
        else if (ch == KEY_DOWN && c->sel + 1 < c->nlib)
            c->sel++;
        else if ((ch == '\n' || ch == '\r' || ch == KEY_ENTER) && c->sel < c->nlib)
            choose_method(c, &c->lib[c->sel]);
    } else if (c->screen == SCREEN_FORM) {
        char *f = c->field[c->fsel];
        size_t n = strlen(f);
        int fresh = c->fresh;
        c->fresh = 0;
        if (ch == KEY_UP && c->fsel > 0)
            c->fsel--, c->fresh = 1;
        else if ((ch == KEY_DOWN || ch == '\t') && c->fsel + 1 < c->meth->nparams)
            c->fsel++, c->fresh = 1;
        else if (ch == '\n' || ch == '\r' || ch == KEY_ENTER) {
            long v;
            char msg[160];
            if (check_field(&c->meth->params[c->fsel], f, &v, msg, sizeof msg) != 0)
                textf(c->hint, sizeof c->hint, "refused: %s", msg);
            else {
                textf(c->hint, sizeof c->hint, "%s = %ld %s", c->meth->params[c->fsel].name, v,
                      c->meth->params[c->fsel].unit);
                if (c->fsel + 1 < c->meth->nparams)
                    c->fsel++, c->fresh = 1;
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
            start_run(c);
    } else { /* a finished run */
        if (ch == KEY_F(5))
            start_run(c);
        else if (ch == KEY_F(3)) {
            c->screen = SCREEN_FORM;
            c->state = ST_IDLE;
        }
    }
}

static void key(console *c, int ch)
{
    if (ch == ERR || ch == KEY_RESIZE)
        return;
    cu_touch();
    if (cu_lab() && !cu_signed_in() && !running(c)) { /* nothing but signing in (or F10) */
        if (ch == KEY_F(10))
            c->quit = 1;
        else {
            if (c->typing < 5)
                ask_sign_in(c, "sign in: your name, Enter, then your password");
            type_key(c, ch);
        }
        return;
    }
    if (c->in_vm && !running(c) && c->state != ST_PAUSED) {
        if (ch == KEY_CTRL_C) /* the engine runs a typed line or loads a file: only Ctrl-C */
            fbrl_vm_interrupt(c->m->vm);
        return;
    }
    if (c->typing && !running(c))
        type_key(c, ch);
    else if (running(c) || c->state == ST_PAUSED)
        run_key(c, ch);
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

/* ---- hooks inside a run ---- */

/* Where the arm stands once its motion has ended (FINISH, W2: commands like any other, so
 * the run log has them too). */
static void read_arm(console *c, const char *when)
{
    fbrl_rapl_pos p;
    fbrl_status st;
    if (c->m->link == NULL || fbrl_link_busy(c->m->link) || fbrl_robot_lost(&c->m->robot))
        return;
    st = fbrl_link_finish(c->m->link);
    if (st == FBRL_OK)
        st = fbrl_link_where(c->m->link, FBRL_RAPL_W2, &p);
    if (st != FBRL_OK)
        push_error(c, "reading the arm's position", fbrl_status_str(st));
    else if (p.nworld >= 6) {
        c->pos = p;
        c->have_pos = 1;
        textf(c->pos_when, sizeof c->pos_when, "%s", when);
    }
}

/* While a robot word waits for the arm to stop (fbrl_robot_set_watch): where the arm is on
 * its way, read live (W2 gives a consistent reading during a motion). A reading that fails
 * is not an error of the method: the panel keeps the last one. */
static void watch_arm(void *ctx, fbrl_robot *r)
{
    console *c = ctx;
    fbrl_rapl_pos p;
    char t[12];
    (void)r;
    if (c->m->link == NULL || fbrl_link_busy(c->m->link))
        return;
    if (fbrl_link_where(c->m->link, FBRL_RAPL_W2, &p) != FBRL_OK || p.nworld < 6)
        return;
    c->pos = p;
    c->have_pos = 1;
    fbrl_run_snapshot(&c->m->run, &c->snap);
    fmt_time(t, sizeof t, (double)c->snap.elapsed_ms);
    textf(c->pos_when, sizeof c->pos_when, "(moving, at %s)", t);
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
    /* a question or a request the operator made stays visible over the wait's progress */
    if (text != NULL && !c->abort_confirm && c->state == ST_RUNNING)
        textf(c->hint, sizeof c->hint, "%s", text);
    pump(c, 1);
}

/* What the controller executed: the live view follows the truth. */
static void hook_exec(void *ctx, const char *line, size_t len, fbrl_status result)
{
    console *c = ctx;
    char l[FBRL_LINK_LINE_MAX + 1];
    if (len > FBRL_LINK_LINE_MAX)
        len = FBRL_LINK_LINE_MAX;
    memcpy(l, line, len);
    l[len] = '\0';
    memcpy(c->last_cmd, l, len + 1);
    if (result == FBRL_OK) {
        if (strncmp(l, "OUTPUT ", 7) == 0) {
            for (char *p = l + 6; p && *p;) {
                long n = strtol(p + 1, &p, 10);
                if (n > 0 && n <= FBRL_ROBOT_IO_MAX)
                    c->outputs |= 1u << (n - 1);
                else if (n < 0 && -n <= FBRL_ROBOT_IO_MAX)
                    c->outputs &= ~(1u << (-n - 1));
                p = strchr(p, ',');
            }
        } else if (strncmp(l, "GRIP ", 5) == 0) {
            char *comma = strchr(l, ',');
            if (comma)
                *comma = '\0';
            textf(c->grip, sizeof c->grip, "width %s in", l + 5);
        } else if (strcmp(l, "OPEN") == 0 || strcmp(l, "CLOSE") == 0) {
            textf(c->grip, sizeof c->grip, "%s", l[0] == 'O' ? "open" : "closed");
        }
    }
    pump(c, 0);
}

/* A run starts (from F5, or RUN-METHOD typed on the Forth line): the run view. */
static void run_begins(console *c, const fbrl_method *m)
{
    if (m != c->meth) {
        c->meth = m;
        c->entry = NULL;
        for (size_t i = 0; i < c->nlib; i++)
            if (strcmp(c->lib[i].name, m->name) == 0)
                c->entry = &c->lib[i];
    }
    c->screen = SCREEN_RUN;
    c->state = ST_RUNNING;
    c->abort_asked = c->abort_confirm = c->asking = 0;
    memset(c->errs, 0, sizeof c->errs); /* the last errors and the messages are this run's */
    memset(c->msgs, 0, sizeof c->msgs);
    textf(c->hint, sizeof c->hint, "running %s", m->name);
    draw(c);
}

/* The run is over: where the arm stands (still inside the run, so in its log), the outcome
 * on the state line and the hint, and every sample that did not succeed under Messages. */
static void run_ends(console *c, fbrl_run *run, const fbrl_run_event *ev)
{
    fbrl_run_snap *s = &c->snap;
    long ok = 0, failed = 0, skipped = 0;
    char line[MIN_COLS + 1];
    read_arm(c, ev->outcome == FBRL_RUN_ABORTED ? "(safe place)" /* after the safe stop and ON-ABORT */
                : ev->text != NULL                  ? "(halted)"     /* stopped by a failed step */
                                                    : "(finished)");
    fbrl_run_snapshot(run, s);
    flush_partial(c);
    if (ev->text != NULL && ev->outcome != FBRL_RUN_COMPLETED && !c->errs[0][0])
        push_error(c, ev->method->name, ev->text); /* (a failed step has said it already) */
    for (long i = 0; i < s->samples; i++) {
        const fbrl_run_sample *o = &s->outcomes[i];
        ok += o->outcome == FBRL_SAMPLE_SUCCEEDED;
        failed += o->outcome == FBRL_SAMPLE_FAILED;
        skipped += o->outcome == FBRL_SAMPLE_SKIPPED;
        if (o->outcome == FBRL_SAMPLE_FAILED || o->outcome == FBRL_SAMPLE_SKIPPED) {
            textf(line, sizeof line, "sample %ld %s: %s", i + 1,
                  fbrl_run_sample_name((fbrl_run_sample_outcome)o->outcome), o->reason);
            push_msg(c, line);
        }
    }
    c->abort_asked = c->abort_confirm = c->asking = 0;
    c->state = ev->outcome == FBRL_RUN_COMPLETED ? ST_DONE
               : ev->outcome == FBRL_RUN_ABORTED ? ST_ABORTED
               : ev->outcome == FBRL_RUN_PARTIAL ? ST_PARTIAL
                                                 : ST_FAILED;
    /* one line: the outcome, the samples, then what matters next (the samples line and
     * Messages say which failed and why) */
    if (s->samples > 0)
        textf(line, sizeof line, ": %ld of %ld samples succeeded", ok, s->samples);
    else
        line[0] = '\0';
    if (ev->outcome == FBRL_RUN_ABORTED)
        textf(c->hint, sizeof c->hint, "%s aborted%s; arm at safe place, outputs off", ev->method->name, line);
    else if (ev->outcome == FBRL_RUN_COMPLETED)
        textf(c->hint, sizeof c->hint, "%s completed%s; F5 runs it again", ev->method->name, line);
    else if (ev->text != NULL)
        textf(c->hint, sizeof c->hint, "%s %s%s; arm halted, outputs off", ev->method->name,
              fbrl_run_outcome_name((fbrl_run_outcome)ev->outcome), line);
    else
        textf(c->hint, sizeof c->hint, "%s %s%s (%ld failed, %ld skipped)", ev->method->name,
              fbrl_run_outcome_name((fbrl_run_outcome)ev->outcome), line, failed, skipped);
}

/* The console observes the run (as the run log does): what it shows follows the events. */
static int observe(void *ctx, fbrl_run *run, const fbrl_run_event *ev)
{
    console *c = ctx;
    char where[64];
    switch (ev->kind) {
    case FBRL_RUN_EV_BEGIN: run_begins(c, ev->method); break;
    case FBRL_RUN_EV_STEP_END:
        if (ev->text != NULL) {
            if (ev->sample >= 0)
                textf(where, sizeof where, "%s, sample %ld", ev->method->steps[ev->step].name, ev->sample + 1);
            else
                textf(where, sizeof where, "%s", ev->method->steps[ev->step].name);
            push_error(c, where, ev->text);
        }
        break;
    case FBRL_RUN_EV_QUESTION: /* a corrective action's ASK: R, S or A answers */
        c->asking = 1;
        push_error(c, "asked", ev->text);
        textf(c->advice[0], sizeof c->advice[0], "-> R retries the step, S skips this sample, A aborts the run");
        textf(c->hint, sizeof c->hint, "R retry, S skip this sample, A abort: %s", ev->text);
        break;
    case FBRL_RUN_EV_ANSWER: c->asking = 0; break;
    case FBRL_RUN_EV_PAUSE:
        c->state = ST_PAUSED;
        textf(c->hint, sizeof c->hint, "paused before step %ld (%s): F7 resumes, F8 aborts", ev->step + 1,
              ev->method->steps[ev->step].name);
        read_arm(c, "(paused)");
        break;
    case FBRL_RUN_EV_RESUME:
        if (c->state == ST_PAUSED)
            c->state = ST_RUNNING;
        break;
    case FBRL_RUN_EV_ABORT:
        c->state = ST_ABORTING;
        textf(c->hint, sizeof c->hint, "aborted: the arm goes to its safe place ...");
        break;
    case FBRL_RUN_EV_SAFE_STOP:
        if (ev->status != FBRL_OK)
            push_error(c, "safe stop", fbrl_status_str(ev->status));
        break;
    case FBRL_RUN_EV_ON_ABORT:
        if (ev->text != NULL)
            push_error(c, "ON-ABORT", ev->text);
        break;
    case FBRL_RUN_EV_END: run_ends(c, run, ev); break;
    case FBRL_RUN_EV_WAIT: { /* paused or asking: the keys, the screen */
        int ch;
        draw(c);
        nodelay(stdscr, FALSE);
        timeout(200);
        ch = getch();
        key(c, ch);
        return 1;
    }
    default: break;
    }
    pump(c, 1);
    return 0;
}

/* The run log could not be written: the operator sees it at once. */
static void log_failed(void *ctx, const char *message)
{
    console *c = ctx;
    push_error(c, "run log", message);
    if (message == c->log->audit.err) /* the run was refused before it began */
        textf(c->advice[0], sizeof c->advice[0], "-> nothing ran: see why above");
    else
        textf(c->advice[0], sizeof c->advice[0], "-> the run goes on without a full log: free space, then check the log");
}

/* ---- running ---- */

static void start_run(console *c)
{
    long v[FBRL_METHOD_MAX_PARAMS];
    size_t bad = 0;
    if (commit_form(c, v) != 0) {
        c->screen = SCREEN_FORM;
        c->state = ST_IDLE;
        return;
    }
    textf(c->log->source, sizeof c->log->source, "%s", c->entry ? c->entry->path : "");
    for (size_t k = 0; k < c->meth->nparams; k++) { /* a parameter changed: who, from what, to what */
        long old = 0;
        char what[2 * FBRL_METHOD_NAME_MAX + 2], detail[96];
        if (fbrl_method_param_get(&c->m->methods, c->meth, k, &old) == FBRL_OK && old != v[k]) {
            textf(what, sizeof what, "%s %s", c->meth->name, c->meth->params[k].name);
            textf(detail, sizeof detail, "%ld -> %ld %s", old, v[k], c->meth->params[k].unit);
            cu_action("parameter", what, detail);
        }
    }
    c->log->audit.err[0] = '\0';
    c->in_vm++;
    fbrl_status st = fbrl_run_start(&c->m->run, c->meth->name, v, c->meth->nparams, &bad);
    c->in_vm--;
    flush_partial(c);
    fill_form(c); /* the values as set */
    if (st != FBRL_OK && c->log->audit.err[0]) { /* refused before it began: why, nothing ran */
        push_error(c, NULL, c->log->audit.err);
        textf(c->advice[0], sizeof c->advice[0], "-> nothing ran");
        textf(c->hint, sizeof c->hint, "the run did not start: see the errors");
        c->screen = SCREEN_FORM;
        c->state = ST_IDLE;
    } else if (st != FBRL_OK) { /* it did not begin: the reason shown, the form back */
        char msg[400];
        engine_error(c, msg, sizeof msg);
        push_error(c, NULL, st == FBRL_ETHROW ? msg : fbrl_status_str(st));
        if (c->log->write_failed) /* the run log could not be written: that is the reason */
            push_error(c, "run log", c->log->write_error);
        c->screen = SCREEN_FORM;
        c->state = ST_IDLE;
        textf(c->hint, sizeof c->hint, "the run did not start: see the errors");
    }
    draw(c);
}

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
    cookie_io_functions_t io = {NULL, cookie_write, NULL, NULL};
    FILE *old_out = m->host.out;
    int old_tty = m->host.out_is_tty;

    if (!isatty(STDIN_FILENO) || !isatty(STDOUT_FILENO)) {
        fprintf(stderr, "fbrlmon: --console needs a terminal\n");
        return -1;
    }
    memset(c, 0, sizeof *c);
    c->m = m;
    c->log = log;
    c->o = o;
    for (int l = 0; l <= LEVEL_PROGRAMMER; l++)
        if (o->level && strcmp(o->level, level_names[l]) == 0)
            c->level = l;
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
    log->error_hook = log_failed;
    log->error_hook_ctx = c;
    log->quiet = 1;

    initscr();
    raw();
    noecho();
    keypad(stdscr, TRUE);
    set_escdelay(100); /* Esc leaves the Forth line at once, not after a second */
    curs_set(0);
    scan_library(c);
    if (c->nlib > 0 && !c->hint[0])
        textf(c->hint, sizeof c->hint, "choose a method and press Enter");
    cu_start(log);
    if (cu_lab())
        ask_sign_in(c, "sign in: your name, Enter, then your password");
    while (!c->quit && !fbrl_vm_bye(m->vm)) {
        draw(c);
        nodelay(stdscr, FALSE);
        timeout(1000); /* the clock and the arm panel stay fresh */
        key(c, getch());
        if (cu_idle(running(c)))
            ask_sign_in(c, "signed out: the console was idle; sign in again");
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
