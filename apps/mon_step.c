/* SPDX-License-Identifier: MIT */
/* mon_step.c - fbrlmon's debugger (docs/debugging.md): breakpoints on a word or on a
 * file:line, and at each stop step into / next (step over) / finish / continue / quit,
 * with the stacks and the source line shown and any Forth (W2, .S, TEACH ...) run at the
 * stop on a copy of the stacks. Built on the engine's step hook (fbrl_vm_step_hook): the
 * hook is set only while there is something to stop for, so a plan runs at full speed
 * otherwise. The arm is idle at a stop: the plan sends nothing until it goes on. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "fbrl/vm_throw.h"
#include "fbrl/vmx.h"
#include "mon.h"
#include "mon_debug.h"
#include "mon_step.h"
#include "mon_trace.h"

/* What to stop at next, besides breakpoints. */
enum { STEP_RUN, STEP_INTO, STEP_OVER, STEP_FINISH };

/* at_word: a word about to run (the word hook), else a definition starting (step hook) */
static void put_stop(mon *m, const fbrl_vm_stop *s, int at_word)
{
    FILE *out = m->host.out;
    mon_host_newline(&m->host);
    fprintf(out, "stop: %s", s->word[0] ? s->word : ":NONAME");
    if (s->file[0])
        fprintf(out, " (%s:%lu)", s->file, s->line);
    if (s->caller[0])
        fprintf(out, at_word ? ", in %s" : ", called by %s", s->caller);
    if (s->call_file[0] && s->call_line)
        fprintf(out, " at %s:%lu", s->call_file, s->call_line);
    fputc('\n', out);
    if (s->call_file[0] && s->call_line)
        mon_debug_show_lines(out, s->call_file, s->call_line, 1);
}

/* The data and float stacks, as .S and F.S would show them. */
static void put_stacks(mon *m, fbrl_vm *vm)
{
    int code = 0;
    char msg[8];
    fbrl_vmx_evaluate_catch(vm, ".S", 2, &code, msg, sizeof msg);
    if (fbrl_vm_fdepth(vm) > 0)
        fbrl_vmx_evaluate_catch(vm, "F.S", 3, &code, msg, sizeof msg);
    mon_host_newline(&m->host);
}

/* Forth typed at a stop runs on a copy of the stacks: the plan goes on with its own. */
static void eval_at_stop(mon *m, fbrl_vm *vm, const char *text, size_t len)
{
    fbrl_cell cells[MON_STEP_STACK_COPY];
    double floats[MON_STEP_STACK_COPY];
    size_t n = fbrl_vm_depth(vm), nf = fbrl_vm_fdepth(vm), i;
    if (n > MON_STEP_STACK_COPY || nf > MON_STEP_STACK_COPY) {
        fputs("debug: the stacks are too deep to keep a copy; only s n f c q a work here\n", m->host.out);
        return;
    }
    for (i = n; i-- > 0;)
        fbrl_vm_pop(vm, &cells[i]);
    for (i = nf; i-- > 0;)
        fbrl_vm_fpop(vm, &floats[i]);
    for (i = 0; i < n; i++)
        fbrl_vm_push(vm, cells[i]);
    for (i = 0; i < nf; i++)
        fbrl_vm_fpush(vm, floats[i]);
    int code = 0;
    char msg[256];
    fbrl_status st = fbrl_vmx_evaluate_catch(vm, text, len, &code, msg, sizeof msg);
    mon_host_newline(&m->host);
    if (st != FBRL_OK || code != 0)
        fprintf(stderr, "debug: error: %s\n", msg[0] ? msg : fbrl_status_str(st));
    fbrl_cell junk;
    double fjunk;
    while (fbrl_vm_depth(vm) > 0)
        fbrl_vm_pop(vm, &junk);
    while (fbrl_vm_fdepth(vm) > 0)
        fbrl_vm_fpop(vm, &fjunk);
    for (i = 0; i < n; i++)
        fbrl_vm_push(vm, cells[i]);
    for (i = 0; i < nf; i++)
        fbrl_vm_fpush(vm, floats[i]);
}

/* Does breakpoint b (FILE:LINE, FILE the path or its end after a '/') name file:line? */
static int at_line(const mon_break *b, const char *file, unsigned long line)
{
    size_t n = strlen(b->where), fl = strlen(file);
    return b->line && line == b->line && fl >= n && strcmp(file + fl - n, b->where) == 0 &&
           (fl == n || file[fl - n - 1] == '/');
}

static void update_hook(mon *m);

/* TRACE-WORDS: "trace: > WORD (file:line) <depth> top cells" for each word entered. */
static void trace_word(mon *m, fbrl_vm *vm, const fbrl_vm_stop *s)
{
    FILE *out = mon_trace_out(m);
    fbrl_cell cells[MON_STEP_TRACE_CELLS];
    size_t depth = fbrl_vm_depth(vm), k = depth < MON_STEP_TRACE_CELLS ? depth : MON_STEP_TRACE_CELLS, i;
    for (i = 0; i < k; i++)
        fbrl_vm_pop(vm, &cells[k - 1 - i]);
    for (i = 0; i < k; i++)
        fbrl_vm_push(vm, cells[i]);
    if (out == m->host.out)
        mon_host_newline(&m->host);
    fprintf(out, "trace: > %s", s->word[0] ? s->word : ":NONAME");
    if (s->call_file[0] && s->call_line)
        fprintf(out, " (%s:%lu)", s->call_file, s->call_line);
    fprintf(out, " <%zu>%s", depth, depth > k ? " ..." : "");
    for (i = 0; i < k; i++)
        fprintf(out, " %ld", (long)cells[i]);
    fputc('\n', out);
    fflush(out);
}

/* A stop: show where, then take the keys (or Forth to run at the stop) until one goes on. */
static int stop_here(mon *m, fbrl_vm *vm, const fbrl_vm_stop *s, int at_word)
{
    mon_step *d = &m->step;
    put_stop(m, s, at_word);
    put_stacks(m, vm);
    if (!d->hinted) {
        fputs("at a stop: s step (into a definition), n next word, f finish the definition,\n"
              "c continue, q quit debugging, a abort; other text runs as Forth on a copy of the\n"
              "stacks (W2 .S TEACH ...)\n",
              m->host.out);
        d->hinted = 1;
    }
    for (;;) {
        fputs("debug> ", m->host.out);
        fflush(m->host.out);
        size_t len;
        const char *line = mon_host_read_line(&m->host, &len);
        m->host.column = 0;
        if (!line) { /* end of input: run on without stopping */
            d->mode = STEP_RUN;
            d->nbreaks = 0;
            update_hook(m);
            return 0;
        }
        if (!m->host.in_is_tty) /* piped: show what was read, so the transcript reads as a session */
            fprintf(m->host.out, "%.*s\n", (int)len, line);
        while (len > 0 && isspace((unsigned char)line[len - 1]))
            len--;
        while (len > 0 && isspace((unsigned char)*line))
            line++, len--;
        char c = len == 1 ? (char)tolower((unsigned char)line[0]) : 0;
        switch (c) {
        case 's': d->mode = STEP_INTO; break;
        case 'n': /* the next word here; at a definition's start, the word after its call */
            d->mode = STEP_OVER;
            d->depth = at_word ? s->depth : s->depth - 1;
            break;
        case 'f':
            d->mode = STEP_FINISH;
            d->depth = s->depth;
            break;
        case 'c': d->mode = STEP_RUN; break;
        case 'q':
            d->mode = STEP_RUN;
            d->nbreaks = 0;
            fputs("debugger off: the plan runs on\n", m->host.out);
            break;
        case 'a': fputs("aborted at the stop\n", m->host.out); return FBRL_THROW_ABORT;
        default:
            if (len > 0)
                eval_at_stop(m, vm, line, len);
            continue;
        }
        update_hook(m);
        return 0;
    }
}

/* The step hook: a colon definition starts. Breakpoints on a word stop here, and on a
 * FILE:LINE where a definition starts; TRACE-WORDS traces it. Steps stop at words. */
static int on_step(void *ctx, fbrl_vm *vm, const fbrl_vm_stop *s)
{
    mon *m = ctx;
    mon_step *d = &m->step;
    int stop = 0;
    if (m->trace.words)
        trace_word(m, vm, s);
    for (size_t i = 0; !stop && i < d->nbreaks; i++)
        stop = d->breaks[i].line ? at_line(&d->breaks[i], s->file, s->line)
                                 : strcasecmp(d->breaks[i].where, s->word) == 0;
    /* its first word, on the same line, is no new line for a line breakpoint */
    d->last_file = s->file, d->last_line = s->line, d->last_depth = s->depth;
    return stop ? stop_here(m, vm, s, 0) : 0;
}

/* The word hook: a word is about to run. Steps stop here; a FILE:LINE breakpoint stops at
 * the first word of its line each time the line is reached. */
static int on_word(void *ctx, fbrl_vm *vm, const fbrl_vm_stop *s)
{
    mon *m = ctx;
    mon_step *d = &m->step;
    int stop = d->mode == STEP_INTO || (d->mode == STEP_OVER && s->depth <= d->depth) ||
               (d->mode == STEP_FINISH && s->depth < d->depth);
    int same_line = s->call_file == d->last_file && s->call_line == d->last_line && s->depth == d->last_depth;
    d->last_file = s->call_file, d->last_line = s->call_line, d->last_depth = s->depth;
    for (size_t i = 0; !stop && !same_line && i < d->nbreaks; i++)
        stop = at_line(&d->breaks[i], s->call_file, s->call_line);
    return stop ? stop_here(m, vm, s, 1) : 0;
}

/* The hooks only while there is something to stop for: the step hook for breakpoints and
 * TRACE-WORDS, the word hook (slower) for steps and line breakpoints. */
static void update_hook(mon *m)
{
    const mon_step *d = &m->step;
    int lines = 0;
    for (size_t i = 0; i < d->nbreaks; i++)
        lines |= d->breaks[i].line != 0;
    int enter = d->nbreaks > 0 || m->trace.words, words = lines || d->mode != STEP_RUN;
    fbrl_vm_step_hook(m->vm, enter ? on_step : NULL, enter ? m : NULL);
    fbrl_vm_word_hook(m->vm, words ? on_word : NULL, words ? m : NULL);
}

void mon_step_end(mon *m)
{
    if (m->step.mode == STEP_RUN)
        return;
    m->step.mode = STEP_RUN; /* what was stepped ended: the next line runs on */
    update_hook(m);
}

static fbrl_status parse_where(fbrl_vm *vm, const char *who, mon_break *b)
{
    const char *p;
    size_t n;
    char msg[160];
    fbrl_vm_parse_name(vm, &p, &n);
    if (n == 0 || n >= sizeof b->where) {
        snprintf(msg, sizeof msg, "%s: name a word or FILE:LINE, e.g. %s PICK-TUBE or %s plan.fbrl:12", who,
                 who, who);
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, msg);
    }
    memcpy(b->where, p, n);
    b->where[n] = 0;
    b->line = 0;
    char *colon = strrchr(b->where, ':');
    if (colon && colon != b->where && colon[1]) {
        char *end;
        unsigned long line = strtoul(colon + 1, &end, 10);
        if (*end == 0 && line > 0) {
            *colon = 0;
            b->line = line;
            return FBRL_OK;
        }
    }
    const char *file;
    unsigned long line;
    if (fbrl_vm_locate(vm, b->where, &file, &line) != FBRL_OK) {
        snprintf(msg, sizeof msg, "%s: %.60s is not a word (or FILE:LINE)", who, b->where);
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, msg);
    }
    return FBRL_OK;
}

/* BREAK ( "name" | "file:line" -- ) */
static fbrl_status w_break(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    mon *m = arg;
    mon_step *d = &m->step;
    mon_break b;
    fbrl_status st = parse_where(vm, "BREAK", &b);
    if (st != FBRL_OK)
        return st;
    if (d->nbreaks >= MON_STEP_BREAKS)
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, "BREAK: too many breakpoints (UNBREAK one)");
    d->breaks[d->nbreaks++] = b;
    update_hook(m);
    return FBRL_OK;
}

/* UNBREAK ( "name" | "file:line" | "ALL" -- ) */
static fbrl_status w_unbreak(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    mon *m = arg;
    mon_step *d = &m->step;
    const char *p;
    size_t n, kept = 0, was = d->nbreaks;
    fbrl_vm_parse_name(vm, &p, &n);
    int all = n == 3 && strncasecmp(p, "ALL", 3) == 0;
    for (size_t i = 0; i < d->nbreaks; i++) {
        char text[sizeof d->breaks[i].where + 24];
        if (d->breaks[i].line)
            snprintf(text, sizeof text, "%s:%lu", d->breaks[i].where, d->breaks[i].line);
        else
            snprintf(text, sizeof text, "%s", d->breaks[i].where);
        if (!all && !(strlen(text) == n && strncasecmp(text, p, n) == 0))
            d->breaks[kept++] = d->breaks[i];
    }
    d->nbreaks = kept;
    if (all) /* nothing stops any more, a step under way included */
        d->mode = STEP_RUN;
    update_hook(m);
    if (kept == was && was > 0 && !all)
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, "UNBREAK: no such breakpoint (BREAKS lists them)");
    return FBRL_OK;
}

/* BREAKS ( -- ) */
static fbrl_status w_breaks(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    mon *m = arg;
    (void)vm;
    mon_host_newline(&m->host);
    if (m->step.nbreaks == 0)
        fputs("no breakpoints\n", m->host.out);
    for (size_t i = 0; i < m->step.nbreaks; i++) {
        const mon_break *b = &m->step.breaks[i];
        if (b->line)
            fprintf(m->host.out, "break at %s:%lu\n", b->where, b->line);
        else
            fprintf(m->host.out, "break at %s\n", b->where);
    }
    fflush(m->host.out);
    m->host.column = 0;
    return FBRL_OK;
}

/* TRACE-WORDS ( -- ) */
static fbrl_status w_trace_words(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    mon *m = arg;
    (void)vm;
    m->trace.words = 1;
    update_hook(m);
    return FBRL_OK;
}

/* TRACE-OFF ( -- ): words and commands; a trace file is closed */
static fbrl_status w_trace_off(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    mon *m = arg;
    (void)vm;
    m->trace.words = 0;
    update_hook(m);
    mon_trace_stop(m);
    return FBRL_OK;
}

fbrl_status mon_step_install(mon *m)
{
    static const fbrl_vmx_reg words[] = {
        {"BREAK", w_break, "", 0, 0, 0,
         FBRL_DOC("( \"name\" | \"file:line\" -- )",
                  "stop before name runs, or at the calls made on that line (the debugger)")},
        {"UNBREAK", w_unbreak, "", 0, 0, 0,
         FBRL_DOC("( \"name\" | \"file:line\" | \"ALL\" -- )", "remove a breakpoint (ALL: every one)")},
        {"BREAKS", w_breaks, "", 0, 0, 0, FBRL_DOC("( -- )", "list the breakpoints")},
        {"TRACE-WORDS", w_trace_words, "", 0, 0, 0,
         FBRL_DOC("( -- )", "trace each word entered, with the line of the call and the data stack")},
        {"TRACE-OFF", w_trace_off, "", 0, 0, 0,
         FBRL_DOC("( -- )", "stop tracing words and commands (and close TRACE-TO's file)")},
    };
    return fbrl_vmx_define_table(m->vm, words, sizeof words / sizeof words[0], m);
}
