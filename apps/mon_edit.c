/* SPDX-License-Identifier: MIT */
/* mon_edit.c - the interactive session: prompt, line editing, history and TAB
 * completion of word names with libedit (<histedit.h>), or a plain line loop
 * when fbrlmon was built without libedit. */
#include "mon.h"
#include "mon_safe.h"
#include "mon_tasks.h"

#include <ctype.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* "ok" when interpreting, "compiling" while a definition is open. */
static const char *prompt_text(const mon *m) { return fbrl_vm_compiling(m->vm) ? "compiling> " : "ok> "; }

/* Evaluate one typed line; errors print but do not count toward the exit status.
 * Ctrl-C (mon_safe.c) interrupts it and ends in the safe stop; one that came after
 * Enter but before the line started cancels the line. */
static void eval_line(mon *m, const char *line, size_t len)
{
    while (len > 0 && (line[len - 1] == '\n' || line[len - 1] == '\r'))
        len--;
    if (mon_safe_pending()) {
        mon_host_newline(&m->host);
        fputs("error: user interrupt (the line did not run)\n", stderr);
        mon_safe_stop(m, NULL, 0);
        return;
    }
    if (m->typed_hook != NULL && len > 0)
        m->typed_hook(m->typed_ctx, line, len);
    mon_safe_begin(m);
    m->typed = 1;
    if (mon_eval(m, line, len, NULL, 0, 0) == 0 && m->host.interrupted) {
        /* The engine stops at its next call or loop step; a line that ended
         * before one (e.g. a lone MS cut short) still says it was interrupted. */
        mon_host_newline(&m->host);
        fputs("error: user interrupt\n", stderr);
    }
    m->typed = 0;
    mon_safe_end(m, "typed line", 0);
    m->host.interrupted = 0;
    mon_host_newline(&m->host);
}

#ifdef FBRLMON_HAVE_LIBEDIT
#include <errno.h>
#include <histedit.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <unistd.h>
#include <wchar.h>

static mon *g_mon; /* the session libedit's callbacks serve (one per process) */

/* libedit's key reader, replaced so that Ctrl-C is never lost: libedit retries
 * a read() that a signal interrupted, so the flag is checked here instead (poll
 * wakes on the signal; the timeout covers a signal that came just before it). */
static int read_key(EditLine *el, wchar_t *wc)
{
    mbstate_t mb;
    (void)el;
    memset(&mb, 0, sizeof mb);
    for (;;) {
        struct pollfd p;
        unsigned char b;
        ssize_t r;
        size_t k;
        if (mon_safe_pending() || (g_mon != NULL && g_mon->host.interrupted)) {
            errno = EINTR;
            return -1;
        }
        p.fd = STDIN_FILENO;
        p.events = POLLIN;
        p.revents = 0;
        /* the tasks run while the prompt waits for a key (mon_tasks.c) */
        if (poll(&p, 1, g_mon != NULL ? mon_tasks_poll_ms(g_mon, 100) : 100) <= 0)
            continue;
        r = read(STDIN_FILENO, &b, 1);
        if (r == 0)
            return 0;
        if (r < 0) {
            if (errno == EINTR || errno == EAGAIN)
                continue;
            return -1;
        }
        k = mbrtowc(wc, (const char *)&b, 1, &mb);
        if (k == (size_t)-2)
            continue; /* more bytes of a multibyte character to come */
        if (k == (size_t)-1)
            *wc = (wchar_t)b; /* not valid here: take the byte as it is */
        return 1;
    }
}

/* Read one line; NULL at end of input or when a second Ctrl-C ends fbrlmon. Ctrl-C at
 * the prompt discards the line being typed and makes the safe stop (mon_safe.c: its
 * handler stays installed; libedit passes the signal on to it). */
static const char *read_line(EditLine *el, int *count)
{
    const char *line;
    for (;;) {
        line = el_gets(el, count);
        if (!mon_safe_pending())
            return line;
        el_reset(el); /* drop the half-typed line */
        fputs("\n", stdout);
        mon_safe_stop(g_mon, NULL, 0);
        if (mon_safe_quit())
            return NULL;
    }
}

static const char *g_alt_prompt; /* a word's own prompt (GET-CAL-POINTS' "cal 1> ") */
static History *g_hist;

static char *el_prompt(EditLine *el)
{
    (void)el;
    return (char *)(g_alt_prompt != NULL ? g_alt_prompt : prompt_text(g_mon));
}

/* A line for a word that reads the console while a typed line runs (mon_host's
 * read_line): the same editor, history and completion as the prompt. NULL at the end of
 * input or on Ctrl-C (the line's Ctrl-C handler has told the engine). */
static const char *edit_line(void *ctx, const char *prompt, size_t *len)
{
    EditLine *el = ctx;
    HistEvent ev;
    const char *line;
    size_t n, k;
    int count = 0;
    g_alt_prompt = prompt;
    line = el_gets(el, &count);
    g_alt_prompt = NULL;
    if (line == NULL || count <= 0 || g_mon->host.interrupted) {
        if (g_mon->host.interrupted) {
            el_reset(el);
            fputs("\n", stdout);
        }
        return NULL;
    }
    n = strlen(line);
    for (k = n; k > 0 && isspace((unsigned char)line[k - 1]); k--)
        ;
    if (k > 0 && g_hist != NULL)
        history(g_hist, &ev, H_ENTER, line);
    while (n > 0 && (line[n - 1] == '\n' || line[n - 1] == '\r'))
        n--;
    *len = n;
    return line;
}

/* Words whose name starts with a prefix, gathered from fbrl_vm_words(). */
typedef struct matches {
    const char *prefix;
    size_t plen;
    char **names;
    size_t n, cap;
} matches;

static int has_name(const matches *mt, const char *name, size_t len)
{
    size_t i;
    for (i = 0; i < mt->n; i++)
        if (strlen(mt->names[i]) == len && strncasecmp(mt->names[i], name, len) == 0)
            return 1;
    return 0;
}

static int collect(void *ctx, const char *name, size_t len)
{
    matches *mt = ctx;
    char *copy;
    if (len < mt->plen || strncasecmp(name, mt->prefix, mt->plen) != 0 || has_name(mt, name, len))
        return 0;
    if (mt->n == mt->cap) {
        size_t cap = mt->cap ? mt->cap * 2 : 64;
        char **p = realloc(mt->names, cap * sizeof *p);
        if (p == NULL)
            return 1;
        mt->names = p;
        mt->cap = cap;
    }
    copy = malloc(len + 1);
    if (copy == NULL)
        return 1;
    memcpy(copy, name, len);
    copy[len] = '\0';
    mt->names[mt->n++] = copy;
    return 0;
}

static int cmp_name(const void *a, const void *b) { return strcasecmp(*(char *const *)a, *(char *const *)b); }

/* Names are case-insensitive: a prefix typed in lower case completes in lower case. */
static void insert_completion(EditLine *el, const char *text, size_t len, int lower)
{
    char buf[256];
    size_t i;
    if (len >= sizeof buf)
        len = sizeof buf - 1;
    for (i = 0; i < len; i++)
        buf[i] = lower ? (char)tolower((unsigned char)text[i]) : text[i];
    buf[len] = '\0';
    el_insertstr(el, buf);
}

static void list_matches(const matches *mt)
{
    struct winsize ws;
    size_t i, width = 0, cols, col = 0;
    int term = 80;
    if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0)
        term = ws.ws_col;
    for (i = 0; i < mt->n; i++)
        if (strlen(mt->names[i]) > width)
            width = strlen(mt->names[i]);
    width += 2;
    cols = (size_t)term / width ? (size_t)term / width : 1;
    fputc('\n', stdout);
    for (i = 0; i < mt->n; i++) {
        fprintf(stdout, "%-*s", (int)width, mt->names[i]);
        if (++col == cols || i + 1 == mt->n) {
            fputc('\n', stdout);
            col = 0;
        }
    }
    fflush(stdout);
}

/* TAB: complete the word before the cursor to the longest common prefix of the
 * matching names (adding a space when only one matches); if that adds nothing,
 * list the candidates. */
static unsigned char el_complete(EditLine *el, int ch)
{
    const LineInfo *li = el_line(el);
    const char *start = li->cursor;
    matches mt;
    size_t i, common;
    int lower = 0, upper = 0;
    unsigned char ret;
    (void)ch;

    while (start > li->buffer && !isspace((unsigned char)start[-1]))
        start--;
    memset(&mt, 0, sizeof mt);
    mt.prefix = start;
    mt.plen = (size_t)(li->cursor - start);
    for (i = 0; i < mt.plen; i++) {
        lower |= islower((unsigned char)start[i]) != 0;
        upper |= isupper((unsigned char)start[i]) != 0;
    }
    fbrl_vm_words(g_mon->vm, collect, &mt);
    if (mt.n == 0)
        return CC_REFRESH_BEEP;
    qsort(mt.names, mt.n, sizeof *mt.names, cmp_name);
    common = strlen(mt.names[0]);
    for (i = 1; i < mt.n; i++) {
        size_t k = 0;
        while (k < common && mt.names[i][k] &&
               tolower((unsigned char)mt.names[i][k]) == tolower((unsigned char)mt.names[0][k]))
            k++;
        common = k;
    }
    if (common > mt.plen || mt.n == 1) {
        insert_completion(el, mt.names[0] + mt.plen, common - mt.plen, lower && !upper);
        if (mt.n == 1)
            el_insertstr(el, " ");
        ret = CC_REFRESH;
    } else {
        list_matches(&mt);
        ret = CC_REDISPLAY;
    }
    for (i = 0; i < mt.n; i++)
        free(mt.names[i]);
    free(mt.names);
    return ret;
}

/* $FBRLMON_HISTORY, else ~/.fbrlmon_history; NULL if neither can be named. */
static char *history_path(void)
{
    const char *env = getenv("FBRLMON_HISTORY");
    const char *home = getenv("HOME");
    char *p;
    if (env != NULL && env[0])
        return strdup(env);
    if (home == NULL || !home[0])
        return NULL;
    p = malloc(strlen(home) + sizeof "/.fbrlmon_history");
    if (p != NULL)
        sprintf(p, "%s/.fbrlmon_history", home);
    return p;
}

void mon_interactive(mon *m)
{
    EditLine *el;
    History *hist;
    HistEvent ev;
    char *hpath = history_path();
    const char *line;
    int count;

    g_mon = m;
    hist = history_init();
    el = el_init("fbrlmon", stdin, stdout, stderr);
    if (hist == NULL || el == NULL) {
        fprintf(stderr, "fbrlmon: line editing unavailable\n");
        if (el != NULL)
            el_end(el);
        if (hist != NULL)
            history_end(hist);
        free(hpath);
        return;
    }
    history(hist, &ev, H_SETSIZE, 1000);
    history(hist, &ev, H_SETUNIQUE, 1);
    if (hpath != NULL)
        history(hist, &ev, H_LOAD, hpath); /* a missing file is a fresh history */

    el_set(el, EL_EDITOR, "emacs");
    el_set(el, EL_SIGNAL, 1);
    el_set(el, EL_PROMPT, el_prompt);
    el_set(el, EL_GETCFN, read_key);
    el_set(el, EL_HIST, history, hist);
    el_set(el, EL_ADDFN, "fbrl-complete", "complete an FBRL word name", el_complete);
    el_set(el, EL_BIND, "^I", "fbrl-complete", NULL);
    el_source(el, NULL); /* the user's ~/.editrc, if any */
    g_hist = hist;
    m->host.edit_line = edit_line;
    m->host.edit_ctx = el;

    while (!fbrl_vm_bye(m->vm) && !mon_safe_quit() && (line = read_line(el, &count)) != NULL && count > 0) {
        size_t len = strlen(line);
        size_t k = len;
        while (k > 0 && isspace((unsigned char)line[k - 1]))
            k--;
        if (k > 0) {
            history(hist, &ev, H_ENTER, line);
            if (hpath != NULL)
                history(hist, &ev, H_SAVE, hpath); /* saved at once: survives a crash */
        }
        eval_line(m, line, len);
    }
    if (!fbrl_vm_bye(m->vm) && !mon_safe_quit())
        fputc('\n', stdout); /* end of input (Ctrl-D) leaves the cursor after the prompt */
    m->host.edit_line = NULL;
    m->host.edit_ctx = NULL;
    g_hist = NULL;
    el_end(el);
    history_end(hist);
    free(hpath);
    g_mon = NULL;
}

#else /* no libedit: a plain line loop */

void mon_interactive(mon *m)
{
    const char *line;
    size_t len;
    for (;;) {
        if (fbrl_vm_bye(m->vm) || mon_safe_quit())
            break;
        fputs(prompt_text(m), stdout);
        fflush(stdout);
        line = mon_host_read_line(&m->host, &len);
        if (line == NULL)
            break;
        if (mon_safe_pending()) { /* Ctrl-C at the prompt: seen once Enter is pressed */
            mon_safe_stop(m, NULL, 0);
            continue;
        }
        eval_line(m, line, len);
    }
}

#endif
