/* SPDX-License-Identifier: MIT */
/* mon_runlog.c - the run log's file, header and run observer; RUN-LOG and NO-RUN-LOG. */
#include "mon_runlog.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "fbrl/vmx.h"
#include "mon.h"

uint64_t mon_runlog_now_us(void *ctx)
{
    struct timespec ts;
    (void)ctx;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

/* The log could not be written: told once per run, and an error of fbrlmon (its exit
 * status). */
static void write_failed(mon_runlog *r, const char *what, int err)
{
    if (r->write_failed)
        return;
    r->write_failed = 1;
    snprintf(r->write_error, sizeof r->write_error, "run log %s: %s: %s", r->path, what, strerror(err));
    r->m->errors++;
    if (r->error_hook)
        r->error_hook(r->error_hook_ctx, r->write_error);
    else
        fprintf(stderr, "fbrlmon: error: %s\n", r->write_error);
}

/* The run log's file is the audit chain (mon_audit.c): each record appended and synced;
 * a write that failed is told once and the chain's writer stops. */
static int chain_write(void *ctx, const char *s, size_t n)
{
    mon_runlog *r = ctx;
    errno = 0;
    if (mon_audit_sink(&r->audit, s, n) == 0)
        return 0;
    write_failed(r, "a record was not written", errno ? errno : EIO); /* the store kept the write's errno */
    return -1;
}

/* The calibration in force, in words: the WITH-CAL structure's name and MAP-ON/OFF. */
typedef struct cal_find {
    mon *m;
    char name[64];
} cal_find;

static int find_cal(void *ctx, const char *name, size_t len)
{
    cal_find *c = ctx;
    fbrl_cell xt, addr;
    const void *tag;
    if (fbrl_vmx_find(c->m->vm, name, len, &xt) == FBRL_OK &&
        fbrl_vmx_tag(c->m->vm, xt, &tag, &addr) == FBRL_OK && addr == c->m->glossary.with_cal &&
        len < sizeof c->name) {
        memcpy(c->name, name, len);
        c->name[len] = '\0';
        return 1;
    }
    return 0;
}

static void calibration_text(mon *m, char *buf, size_t cap)
{
    cal_find c;
    memset(&c, 0, sizeof c);
    c.m = m;
    if (m->glossary.with_cal == 0) {
        snprintf(buf, cap, "none (no WITH-CAL)");
        return;
    }
    fbrl_vm_words(m->vm, find_cal, &c);
    snprintf(buf, cap, "WITH-CAL %s, %s", c.name[0] ? c.name : "(unnamed)",
             m->glossary.map_on ? "MAP-ON" : "MAP-OFF");
}

static void version_line(void *ctx, const char *line, size_t len, int flawed)
{
    mon_runlog *r = ctx;
    const char *v = len >= 7 ? strstr(line, "Version") : NULL;
    if (flawed || v == NULL || v >= line + len || r->version[0])
        return;
    while (len > 0 && (line[len - 1] == ' ' || line[len - 1] == '\r'))
        len--;
    snprintf(r->version, sizeof r->version, "%.*s", (int)len, line);
    for (char *p = r->version; *p; p++) /* "RAPL-II Version 2.60     A255": one blank each */
        while (p[0] == ' ' && p[1] == ' ')
            memmove(p, p + 1, strlen(p));
}

/* The controller's version: STATUS, its lines read as they come (the header's
 * "controller"); the command is the run's first, written after the header. */
static void read_version(mon_runlog *r)
{
    fbrl_link *l = r->m->link;
    fbrl_link_line_fn old_fn = NULL;
    void *old_ctx = NULL;
    int done = 0;
    r->version[0] = '\0';
    if (l == NULL || fbrl_link_busy(l) || fbrl_robot_lost(&r->m->robot))
        return;
    if (fbrl_link_set_line_handler(l, version_line, r, &old_fn, &old_ctx) != FBRL_OK)
        return;
    fbrl_status st = fbrl_link_start(l, "STATUS", FBRL_LINK_REPLY_LINES);
    while (st == FBRL_OK && !done)
        st = fbrl_link_poll(l, 100, &done);
    fbrl_link_set_line_handler(l, old_fn, old_ctx, NULL, NULL);
}

/* A run begins: the file opened, the header written (the run is refused, 1, when not). */
static int log_begin(mon_runlog *r, const fbrl_method *meth)
{
    fbrl_runlog_param p[FBRL_METHOD_MAX_PARAMS];
    fbrl_runlog_header h;
    char when[32], cal[128], ctl[sizeof r->version + sizeof r->controller + 2];
    time_t now = time(NULL);
    struct tm tm;
    r->step_t0_us = 0;
    r->write_failed = 0;
    if (!r->path[0])
        return 0;
    memset(&h, 0, sizeof h);
    for (size_t k = 0; k < meth->nparams; k++) {
        p[k].name = meth->params[k].name;
        p[k].unit = meth->params[k].unit;
        p[k].value = 0;
        fbrl_method_param_get(&r->m->methods, meth, k, &p[k].value);
    }
    /* the audit chain verified and the method's release checked (in a lab) before the
     * controller hears anything of the run */
    snprintf(r->audit.path, sizeof r->audit.path, "%s", r->path);
    if (!r->audit.user[0])
        mon_audit_set_user(&r->audit, r->operator_id, 0, FBRL_ROLE_OPERATOR);
    int refused = mon_audit_run_begin(&r->audit, meth, r->source);
    if (refused != 0) {
        if (refused == -1)
            r->m->errors++; /* no trail for the run: an error of fbrlmon (its exit status) */
        if (r->error_hook)
            r->error_hook(r->error_hook_ctx, r->audit.err);
        else
            fprintf(stderr, "fbrlmon: error: %s\n", r->audit.err);
        return 1;
    }
    localtime_r(&now, &tm);
    strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%S%z", &tm);
    calibration_text(r->m, cal, sizeof cal);
    r->opening = 1;
    r->npending = 0;
    read_version(r);
    r->opening = 0;
    if (r->version[0] && r->controller[0] && strlen(r->version) + 2 < sizeof ctl) {
        snprintf(ctl, sizeof ctl, "%s; %s", r->version, r->controller);
        h.controller = ctl;
    } else {
        h.controller = r->version[0] ? r->version : r->controller[0] ? r->controller : NULL;
    }
    h.method = meth->name;
    h.source = r->source[0] ? r->source : NULL;
    h.operator_id = r->operator_id;
    h.started = when;
    h.program = r->program;
    h.calibration = cal;
    h.params = p;
    h.nparams = meth->nparams;
    memset(&r->log, 0, sizeof r->log);
    if (fbrl_runlog_begin(&r->log, chain_write, r, mon_runlog_now_us, NULL, &h) != FBRL_OK) {
        mon_audit_run_end(&r->audit);
        return 1;
    }
    for (int k = 0; k < r->npending; k++)
        fbrl_runlog_command(&r->log, r->pending[k], strlen(r->pending[k]), r->pending_st[k], -1);
    return 0;
}

/* A run that did not complete, told on stderr (fbrlmon without the console): the outcome,
 * and every sample that did not succeed with why. */
static void tell_outcome(mon_runlog *r, fbrl_run *run, const fbrl_run_event *ev)
{
    static fbrl_run_snap s;
    long ok = 0;
    if (ev->outcome == FBRL_RUN_COMPLETED || r->quiet || fbrl_run_snapshot(run, &s) != FBRL_OK)
        return;
    for (long i = 0; i < s.samples; i++)
        ok += s.outcomes[i].outcome == FBRL_SAMPLE_SUCCEEDED;
    mon_host_newline(&r->m->host);
    fprintf(stderr, "fbrlmon: %s: %s", s.method, fbrl_run_outcome_name((fbrl_run_outcome)ev->outcome));
    if (s.samples > 0)
        fprintf(stderr, ": %ld of %ld samples succeeded", ok, s.samples);
    if (ev->text != NULL)
        fprintf(stderr, " (%s)", ev->text);
    fprintf(stderr, "%s%s\n", r->path[0] ? "; run log " : "", r->path);
    for (long i = 0; i < s.samples; i++)
        if (s.outcomes[i].outcome == FBRL_SAMPLE_FAILED || s.outcomes[i].outcome == FBRL_SAMPLE_SKIPPED)
            fprintf(stderr, "  sample %ld %s: %s\n", i + 1,
                    fbrl_run_sample_name((fbrl_run_sample_outcome)s.outcomes[i].outcome), s.outcomes[i].reason);
    fflush(stderr);
}

static int observe(void *ctx, fbrl_run *run, const fbrl_run_event *ev)
{
    static fbrl_run_snap snap; /* large: one run log per process */
    mon_runlog *r = ctx;
    fbrl_runlog *l = &r->log;
    if (ev->kind == FBRL_RUN_EV_END && ev->outcome != FBRL_RUN_COMPLETED && r->m->counting)
        r->m->runs_incomplete++; /* fbrlmon's exit status: a run from a file, -e or a pipe */
    if (ev->kind == FBRL_RUN_EV_END)
        tell_outcome(r, run, ev);
    if (ev->kind == FBRL_RUN_EV_BEGIN)
        return log_begin(r, ev->method);
    if (!fbrl_runlog_is_open(l))
        return 0;
    fbrl_runlog_event(l, run, ev, &snap); /* the records, as every program writes them */
    if (ev->kind == FBRL_RUN_EV_END)
        mon_audit_run_end(&r->audit); /* sealed */
    return 0;
}

void mon_runlog_exec(void *ctx, const char *line, size_t len, fbrl_status result)
{
    mon_runlog *r = ctx;
    int code = -1;
    const char *text;
    if (r == NULL)
        return;
    if (r->opening && r->npending < (int)(sizeof r->pending / sizeof r->pending[0])) {
        snprintf(r->pending[r->npending], sizeof r->pending[0], "%.*s", (int)len, line);
        r->pending_st[r->npending++] = result;
    }
    if (fbrl_runlog_is_open(&r->log)) {
        unsigned runs = 0, maybe = 0;
        if (result == FBRL_ECONTROLLER && r->m->link != NULL)
            fbrl_link_error(r->m->link, &code, &text);
        if (r->m->link != NULL)
            fbrl_link_get_runs(r->m->link, &runs, &maybe); /* a line the link typed again */
        fbrl_runlog_command_run(&r->log, line, len, result, code, runs + maybe);
    }
    if (r->exec_hook)
        r->exec_hook(r->exec_hook_ctx, line, len, result);
}

/* The name of the device word whose data field is addr. */
typedef struct dev_find {
    mon *m;
    fbrl_cell addr;
    char name[40];
} dev_find;

static int find_dev(void *ctx, const char *name, size_t len)
{
    dev_find *f = ctx;
    fbrl_cell xt;
    fbrl_robot_device d;
    if (len < sizeof f->name && fbrl_vmx_find(f->m->vm, name, len, &xt) == FBRL_OK &&
        fbrl_robot_device_of(&f->m->robot, xt, &d) == FBRL_OK && d.addr == f->addr) {
        memcpy(f->name, name, len);
        f->name[len] = '\0';
        return 1;
    }
    return 0;
}

/* Device actions and timed waits (fbrl_robot_set_events), planned against actual. */
static void on_event(void *ctx, const fbrl_robot_event *ev)
{
    mon_runlog *r = ctx;
    dev_find f;
    char what[96];
    const char *failed = ev->status == FBRL_OK ? "" : " (failed)";
    if (!fbrl_runlog_is_open(&r->log) && r->event_hook == NULL)
        return;
    if (ev->line != NULL) { /* a motion sent around the guard on purpose (fbrl_link_unguarded) */
        if (fbrl_runlog_is_open(&r->log))
            fbrl_runlog_note(&r->log, "unguarded", NULL, ev->line);
        return;
    }
    memset(&f, 0, sizeof f);
    f.m = r->m;
    f.addr = ev->device;
    if (ev->device)
        fbrl_vm_words(r->m->vm, find_dev, &f);
    if (!f.name[0])
        snprintf(f.name, sizeof f.name, "port %d", ev->port);
    if (r->event_hook)
        r->event_hook(r->event_hook_ctx, ev, f.name);
    if (!fbrl_runlog_is_open(&r->log))
        return;
    if (strcmp(ev->word, "WAIT-UNTIL") == 0) {
        snprintf(what, sizeof what, "WAIT-UNTIL%s", failed);
        fbrl_runlog_wait(&r->log, what, ev->planned_ms, ev->actual_ms);
    } else if (strcmp(ev->word, "WAIT-INPUT") == 0) {
        snprintf(what, sizeof what, "WAIT-INPUT %s %s: %s%s", f.name, ev->amount != 0 ? "on" : "off",
                 ev->seen ? "seen" : "not seen", failed);
        fbrl_runlog_wait(&r->log, what, ev->planned_ms, ev->actual_ms);
    } else {
        if (strcmp(ev->word, "DISPENSE") == 0)
            snprintf(what, sizeof what, "dispense %.0f ml%s", ev->amount, failed);
        else
            snprintf(what, sizeof what, "%s%s", ev->word, failed);
        for (char *p = what; *p && *p != ' '; p++)
            *p = (char)tolower((unsigned char)*p);
        fbrl_runlog_device(&r->log, f.name, what, ev->planned_ms, ev->actual_ms);
    }
}

int mon_runlog_observe_again(mon_runlog *r)
{
    if (fbrl_run_unobserve(&r->m->run, observe, r) != FBRL_OK || fbrl_run_observe(&r->m->run, observe, r) != FBRL_OK)
        return -1;
    return 0;
}

void mon_runlog_set_path(mon_runlog *r, const char *path)
{
    snprintf(r->path, sizeof r->path, "%s", path ? path : "");
}

/* RUN-LOG ( "file" -- ) */
static fbrl_status w_run_log(fbrl_vm *vm, void *ctx, const void *word)
{
    mon_runlog *r = ctx;
    const char *name;
    size_t len;
    FILE *f;
    (void)word;
    fbrl_status st = fbrl_vm_parse_name(vm, &name, &len);
    if (st != FBRL_OK)
        return st;
    if (len == 0 || len >= sizeof r->path)
        return fbrl_vmx_throwf(vm, FBRL_THROW_NO_NAME, "RUN-LOG: a file name is needed");
    memcpy(r->path, name, len);
    r->path[len] = '\0';
    f = fopen(r->path, "a"); /* say now, not at the run, that it cannot be written */
    if (f == NULL) {
        int e = errno;
        r->path[0] = '\0';
        return fbrl_vmx_throwf(vm, FBRL_THROW_FILE_IO, "RUN-LOG: %.*s: %s", (int)len, name, strerror(e));
    }
    fclose(f);
    return FBRL_OK;
}

/* NO-RUN-LOG ( -- ) */
static fbrl_status w_no_run_log(fbrl_vm *vm, void *ctx, const void *word)
{
    mon_runlog *r = ctx;
    (void)vm, (void)word;
    r->path[0] = '\0';
    return FBRL_OK;
}

int mon_runlog_install(mon_runlog *r, mon *m, const char *program, const char *controller)
{
    const char *who = getenv("USER");
    r->m = m;
    r->program = program;
    snprintf(r->operator_id, sizeof r->operator_id, "%s", who ? who : "");
    snprintf(r->controller, sizeof r->controller, "%s", controller ? controller : "");
    fbrl_robot_set_events(&m->robot, on_event, r);
    static const fbrl_vmx_reg words[] = {
        {"RUN-LOG", w_run_log, "", 0, 0, 0,
         FBRL_DOC("( \"file\" -- )", "every following RUN-METHOD appends its run log (JSON lines) to file")},
        {"NO-RUN-LOG", w_no_run_log, "", 0, 0, 0, FBRL_DOC("( -- )", "stop writing run logs")},
    };
    if (fbrl_run_observe(&m->run, observe, r) != FBRL_OK ||
        fbrl_vmx_define_table(m->vm, words, sizeof words / sizeof words[0], r) != FBRL_OK)
        return -1;
    return 0;
}
