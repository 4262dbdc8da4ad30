/* SPDX-License-Identifier: MIT */
/* mon_dry.c - fbrlmon --dry-run (see mon_dry.h, docs/workcell.md). */
#define _GNU_SOURCE /* mkdtemp, nftw */
#include "mon_dry.h"
#include "mon_host.h"

#include <errno.h>
#include <ftw.h>
#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "fbrl/num.h"
#include "fbrl/rapl_encode.h"

#define WAIT_MIN_S 0.1 /* shorter sleeps (the 50 ms polls of a moving arm) are not listed */

/* The shared clock: real time plus every wait skipped. The emulator's thread reads it. */
static struct {
    pthread_mutex_t mu;
    double skipped; /* s */
    double real0;   /* real monotonic s at setup */
    double start;   /* clock at mon_dry_start */
    double wall0;   /* real s at mon_dry_start */
    time_t date0;   /* the date at setup, for TIME-OF-DAY */
    int on;
} g_clk = {PTHREAD_MUTEX_INITIALIZER, 0, 0, 0, 0, 0, 0};

static mon_dry_report g_rep;
static double g_step_t0, g_step_sum[FBRL_METHOD_MAX_STEPS]; /* simulated s */
static long g_step_n[FBRL_METHOD_MAX_STEPS];
static long g_step = -1, g_sample = -1; /* where the method run is */
static double g_on_at[FBRL_ROBOT_IO_MAX + 1]; /* when each output went on (-1: off) */
static unsigned long g_cmds_at_wait;          /* commands seen when the last wait was listed */
static char g_scratch[PATH_MAX], g_cwd[PATH_MAX];
static mon *g_mon;
static FILE *g_json; /* --dry-run-json */

#define JSON_PATH_STEPS 8 /* a joint move's tool path: its start and 8 more points (the picture's) */

static double real_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

static double clk_now(void)
{
    double t;
    pthread_mutex_lock(&g_clk.mu);
    t = real_now() - g_clk.real0 + g_clk.skipped;
    pthread_mutex_unlock(&g_clk.mu);
    return t;
}

static double sim_clock(void *ctx)
{
    (void)ctx;
    return clk_now();
}

static void sim_skip(void *ctx, double s)
{
    (void)ctx;
    pthread_mutex_lock(&g_clk.mu);
    g_clk.skipped += s;
    pthread_mutex_unlock(&g_clk.mu);
}

static double since_start(void) { return clk_now() - g_clk.start; }

static void add_event(mon_dry_kind kind, double t, double len, int output, const char *text)
{
    mon_dry_event *e;
    if (g_rep.nevents >= MON_DRY_EVENTS)
        return;
    e = &g_rep.ev[g_rep.nevents++];
    memset(e, 0, sizeof *e);
    e->kind = kind;
    e->t = t;
    e->len = len;
    e->output = output;
    if (text)
        snprintf(e->text, sizeof e->text, "%s", text);
}

static uint64_t host_now_us(void *user)
{
    (void)user;
    return (uint64_t)(clk_now() * 1e6) + 1000000u; /* never 0 */
}

/* A wait of the plan: skipped, and listed when long enough (consecutive ones as one). */
static void host_sleep_ms(void *user, uint32_t ms)
{
    double t = since_start();
    (void)user;
    pthread_mutex_lock(&g_clk.mu);
    g_clk.skipped += ms / 1000.0;
    pthread_mutex_unlock(&g_clk.mu);
    if (!g_clk.on || ms / 1000.0 < WAIT_MIN_S)
        return;
    if (g_rep.nevents && g_rep.ev[g_rep.nevents - 1].kind == MON_DRY_WAIT && g_cmds_at_wait == g_rep.commands)
        g_rep.ev[g_rep.nevents - 1].len += ms / 1000.0;
    else
        add_event(MON_DRY_WAIT, t, ms / 1000.0, 0, NULL);
    g_cmds_at_wait = g_rep.commands;
}

static void host_time_date(void *user, int out[6])
{
    time_t t = g_clk.date0 + (time_t)(clk_now());
    struct tm tm;
    (void)user;
    memset(&tm, 0, sizeof tm);
    localtime_r(&t, &tm);
    out[0] = tm.tm_sec, out[1] = tm.tm_min, out[2] = tm.tm_hour;
    out[3] = tm.tm_mday, out[4] = tm.tm_mon + 1, out[5] = tm.tm_year + 1900;
}

/* Every command the controller ran (the link's run log): counted, outputs paired into
 * pulses, errors listed. */
static void on_exec(void *ctx, const char *line, size_t len, fbrl_status result)
{
    char text[200];
    fbrl_rapl_cmd cmd;
    const char *args;
    double t = since_start();
    (void)ctx;
    if (!g_clk.on)
        return;
    if (result == FBRL_EMAYBE)
        return;
    g_rep.commands++;
    if (fbrl_rapl_line_cmd(line, &cmd, &args) == FBRL_OK) { /* the link's lines end in a NUL */
        if (fbrl_rapl_cmd_info(cmd)->flags & FBRL_RAPL_F_MOTION)
            g_rep.moves++;
        if (cmd == FBRL_RAPL_OUTPUT && result == FBRL_OK) {
            const char *p = args;
            while (p < line + len) {
                char *end;
                long n = strtol(p, &end, 10);
                if (end == p) {
                    p++;
                    continue;
                }
                p = end;
                if (n >= 1 && n <= FBRL_ROBOT_IO_MAX) {
                    g_on_at[n] = t;
                } else if (n <= -1 && n >= -FBRL_ROBOT_IO_MAX && g_on_at[-n] >= 0) {
                    add_event(MON_DRY_PULSE, g_on_at[-n], t - g_on_at[-n], (int)-n, NULL);
                    g_on_at[-n] = -1;
                }
            }
        }
    }
    if (result == FBRL_ECONTROLLER && g_mon && g_mon->link) {
        int code = -1;
        const char *etext = "";
        fbrl_link_error(g_mon->link, &code, &etext);
        snprintf(text, sizeof text, "controller error %03d-%s after %.*s", code, etext, (int)len, line);
        add_event(MON_DRY_ERROR, t, 0, 0, text);
        g_rep.errors++;
    }
}

int mon_dry_setup(const mon_dry_options *o, mon_conn_options *conn)
{
    memset(&g_rep, 0, sizeof g_rep);
    for (int k = 0; k <= FBRL_ROBOT_IO_MAX; k++)
        g_on_at[k] = -1;
    g_clk.real0 = real_now();
    g_clk.skipped = 0;
    g_clk.date0 = time(NULL);
    conn->kind = MON_CONN_SIM;
    conn->sim_clock = sim_clock;
    conn->sim_skip = sim_skip;
    conn->sim_clock_ctx = NULL;
    conn->on_exec = on_exec;
    conn->exec_ctx = NULL;
    mon_host_use_clock(host_now_us, host_sleep_ms, host_time_date);
    g_scratch[0] = '\0';
    if (o->json && (g_json = fopen(o->json, "w")) == NULL) { /* before the scratch directory: where the user is */
        fprintf(stderr, "fbrlmon: --dry-run-json %s: %s\n", o->json, strerror(errno));
        return -1;
    }
    if (!o->keep_files) {
        const char *tmp = getenv("TMPDIR");
        if (getcwd(g_cwd, sizeof g_cwd) == NULL) {
            fprintf(stderr, "fbrlmon: --dry-run: the current directory: %s\n", strerror(errno));
            return -1;
        }
        snprintf(g_scratch, sizeof g_scratch, "%s/fbrlmon-dry-XXXXXX", tmp && *tmp ? tmp : "/tmp");
        if (mkdtemp(g_scratch) == NULL || chdir(g_scratch) != 0) {
            fprintf(stderr, "fbrlmon: --dry-run: a scratch directory: %s\n", strerror(errno));
            g_scratch[0] = '\0';
            return -1;
        }
    }
    return 0;
}

static void fmt_s(char *buf, size_t cap, double s);

/* A time-out (WAIT-INPUT that gave up) is listed where its wait began, with the step. */
static void on_device(void *ctx, const fbrl_robot_event *ev, const char *device)
{
    char where[96] = "", a[32];
    (void)ctx;
    if (!g_clk.on || strcmp(ev->word, "WAIT-INPUT") != 0 || ev->seen || ev->status != FBRL_OK)
        return;
    if (g_step >= 0 && g_rep.run.nsteps > g_step && g_sample >= 0)
        snprintf(where, sizeof where, " (%s, sample %ld)", g_rep.run.step_name[g_step], g_sample + 1);
    else if (g_step >= 0 && g_rep.run.nsteps > g_step)
        snprintf(where, sizeof where, " (%s)", g_rep.run.step_name[g_step]);
    fmt_s(a, sizeof a, ev->planned_ms / 1000.0);
    char text[200];
    snprintf(text, sizeof text, "time-out: WAIT-INPUT %s %s not seen within %s s%s", device,
             ev->amount != 0 ? "on" : "off", a, where);
    add_event(MON_DRY_TIMEOUT, since_start() - ev->actual_ms / 1000.0, ev->actual_ms / 1000.0, 0, text);
    g_rep.timeouts++;
}

/* The method run: each step's simulated time, and its predicted outcomes at the end. */
static int on_run(void *ctx, fbrl_run *run, const fbrl_run_event *ev)
{
    (void)ctx;
    if (!g_clk.on)
        return 0;
    if (ev->kind == FBRL_RUN_EV_BEGIN) {
        memset(g_step_sum, 0, sizeof g_step_sum);
        memset(g_step_n, 0, sizeof g_step_n);
        fbrl_run_snapshot(run, &g_rep.run);
    } else if (ev->kind == FBRL_RUN_EV_STEP_BEGIN) {
        g_step = ev->step;
        g_sample = ev->sample;
        g_step_t0 = since_start();
    } else if (ev->kind == FBRL_RUN_EV_STEP_END) {
        g_step_sum[ev->step] += since_start() - g_step_t0;
        g_step_n[ev->step]++;
    } else if (ev->kind == FBRL_RUN_EV_END) {
        fbrl_run_snapshot(run, &g_rep.run);
        for (long k = 0; k < g_rep.run.nsteps; k++)
            g_rep.step_ms[k] = g_step_n[k] ? g_step_sum[k] * 1000.0 / (double)g_step_n[k] : 0;
        g_rep.have_run = 1;
        g_step = g_sample = -1;
    }
    return 0;
}

/* ---- --dry-run-json: the path as the guard checked it, one motion a line ---- */

static void json_str(FILE *f, const char *t)
{
    fputc('"', f);
    for (; t && *t; t++) {
        unsigned char ch = (unsigned char)*t;
        if (ch == '"' || ch == '\\')
            fprintf(f, "\\%c", ch);
        else if (ch < 0x20)
            fprintf(f, "\\u%04x", ch);
        else
            fputc(ch, f);
    }
    fputc('"', f);
}

static void json_num(FILE *f, double v)
{
    char buf[48];
    fputs(isfinite(v) && fbrl_num_fixed(buf, sizeof buf, v, 0, 4, 0, NULL) == FBRL_OK ? buf : "null", f);
}

static void json_point(FILE *f, const fbrl_cell_model *c, const double *q)
{
    double pose[6];
    fbrl_arm_fk(c->arm, q, c->tcp, pose);
    fprintf(f, "[");
    for (int i = 0; i < 3; i++) {
        json_num(f, pose[i]);
        fputs(i < 2 ? "," : "]", f);
    }
}

/* A motion the guard checked: its tool points (the ends of a straight line; along a joint
 * move, the points of the joints interpolated as the guard checks them), its clearance
 * (the whole arm's, to near), and a refused one's contact and message. */
static void on_check(void *ctx, const fbrl_cell_check *ck)
{
    const fbrl_cell_model *c = ctx;
    const fbrl_cell_hit *h = ck->path ? ck->hit : NULL;
    FILE *f = g_json;
    int n = ck->naxes == 0 ? 0 : !ck->path ? 1 : ck->line ? 2 : JSON_PATH_STEPS + 1;
    fprintf(f, "{\"t\":");
    json_num(f, since_start());
    fprintf(f, ",\"word\":");
    json_str(f, ck->word);
    fprintf(f, ",\"step\":");
    if (g_step >= 0 && g_rep.run.nsteps > g_step)
        json_str(f, g_rep.run.step_name[g_step]);
    else
        fputs("null", f);
    fprintf(f, ",\"sample\":%ld,\"sent\":%s,\"line\":%s,\"points\":[", g_sample >= 0 ? g_sample + 1 : 0,
            ck->sent ? "true" : "false", ck->line ? "true" : "false");
    for (int k = 0; k < n; k++) {
        double q[FBRL_CELL_AXES];
        double s = n == 1 ? 0.0 : (double)k / (n - 1);
        for (int i = 0; i < FBRL_CELL_AXES; i++)
            q[i] = ck->q0[i] + (ck->q1[i] - ck->q0[i]) * s;
        if (k)
            fputc(',', f);
        json_point(f, c, q);
    }
    fprintf(f, "],\"clearance\":");
    if (h && isfinite(h->clearance)) {
        json_num(f, h->clearance);
        fprintf(f, ",\"near\":");
        json_str(f, fbrl_cell_obj_name(c, h->near_obj));
    } else {
        fprintf(f, "null,\"near\":null");
    }
    fprintf(f, ",\"hit\":");
    if (h && h->hit) {
        json_str(f, fbrl_cell_obj_name(c, h->obj));
        fprintf(f, ",\"at\":[");
        for (int i = 0; i < 3; i++) {
            json_num(f, h->at[i]);
            fputs(i < 2 ? "," : "]", f);
        }
    } else {
        fprintf(f, "null,\"at\":null");
    }
    fprintf(f, ",\"message\":");
    if (ck->message)
        json_str(f, ck->message);
    else
        fputs("null", f);
    fputs("}\n", f);
}

void mon_dry_start(mon *m, mon_runlog *log)
{
    if (g_json && m->cell)
        fbrl_cell_set_observer(m->cell, on_check, &m->cell->model);
    g_mon = m;
    log->event_hook = on_device;
    log->event_hook_ctx = NULL;
    fbrl_run_observe(&m->run, on_run, NULL);
    g_clk.start = clk_now();
    g_clk.wall0 = real_now();
    g_clk.on = 1;
}

static int rm_one(const char *path, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb, (void)flag, (void)ftw;
    return remove(path);
}

static void fmt_s(char *buf, size_t cap, double s)
{
    if (fbrl_num_fixed(buf, cap, s, 0, 3, 0, NULL) != FBRL_OK)
        snprintf(buf, cap, "?");
}

/* The predicted run: its outcome, each sample's, each step's time (what fbrl_run_predict
 * takes, so a front end can show the time left from the start). */
static void report_run(FILE *out)
{
    const fbrl_run_snap *s = &g_rep.run;
    char a[32], b[32];
    fprintf(out, "predicted run of %s: %s\n", s->method, fbrl_run_outcome_name((fbrl_run_outcome)s->outcome));
    for (long i = 0; i < s->samples; i++)
        fprintf(out, "  sample %ld: %s%s%s\n", i + 1,
                fbrl_run_sample_name((fbrl_run_sample_outcome)s->outcomes[i].outcome),
                s->outcomes[i].reason[0] ? ": " : "", s->outcomes[i].reason);
    for (long k = 0; k < s->nsteps; k++) {
        if (g_step_n[k] == 0) {
            fprintf(out, "  step %-14s not run\n", s->step_name[k]);
            continue;
        }
        fmt_s(a, sizeof a, g_rep.step_ms[k] / 1000.0);
        fmt_s(b, sizeof b, g_rep.step_ms[k] * (double)g_step_n[k] / 1000.0);
        fprintf(out, "  step %-14s %ld x %s s = %s s\n", s->step_name[k], g_step_n[k], a, b);
    }
}

int mon_dry_finish(mon *m, mon_dry_report *r, FILE *out, const char *svg)
{
    char a[32], b[32], c[32], d[32];
    int st = 0;
    const fbrl_cell_stats *cs = m->cell ? fbrl_cell_stats_get(m->cell) : NULL;
    g_rep.duration = since_start();
    g_rep.wall = real_now() - g_clk.wall0;
    g_clk.on = 0;
    g_rep.cell = cs;
    if (cs)
        g_rep.errors += cs->refused;
    if (m->errors) {
        const fbrl_vm_error *e = fbrl_vm_last_error(m->vm);
        char text[600];
        snprintf(text, sizeof text, "the plan stopped: %.200s (%.300s:%lu)", e->message,
                 e->file[0] ? e->file : "-e", e->line);
        add_event(MON_DRY_ERROR, g_rep.duration, 0, 0, text);
        if (!cs || !cs->refused)
            g_rep.errors++;
    }
    fmt_s(a, sizeof a, g_rep.duration);
    fmt_s(b, sizeof b, g_rep.wall);
    fprintf(out, "---- dry run ----\n");
    fprintf(out, "simulated duration %s s (the dry run took %s s)\n", a, b);
    fprintf(out, "commands %lu, moves %lu, errors %lu, time-outs %lu\n", g_rep.commands, g_rep.moves, g_rep.errors,
            g_rep.timeouts);
    if (cs && isfinite(cs->clearance)) {
        fmt_s(a, sizeof a, cs->clearance);
        fmt_s(b, sizeof b, cs->near[0]);
        fmt_s(c, sizeof c, cs->near[1]);
        fmt_s(d, sizeof d, cs->near[2]);
        fprintf(out, "smallest clearance %s in to %s at X %s Y %s Z %s (%s)\n", a,
                fbrl_cell_obj_name(&m->cell->model, cs->near_obj), b, c, d, cs->near_word);
    } else {
        fprintf(out, "smallest clearance: no work cell described (CELL-BOX ...), nothing checked\n");
    }
    for (unsigned k = 0; cs && k < cs->nrefusals; k++)
        fprintf(out, "refused: %s\n", cs->refusals[k]);
    for (size_t k = 0; k < g_rep.nevents; k++) {
        const mon_dry_event *e = &g_rep.ev[k];
        fmt_s(a, sizeof a, e->t);
        fmt_s(b, sizeof b, e->len);
        if (e->kind == MON_DRY_PULSE)
            fprintf(out, "%10s s  output %d pulse %s s\n", a, e->output, b);
        else if (e->kind == MON_DRY_WAIT)
            fprintf(out, "%10s s  wait %s s\n", a, b);
        else if (e->kind == MON_DRY_TIMEOUT)
            fprintf(out, "%10s s  %s\n", a, e->text);
        else
            fprintf(out, "%10s s  error: %s\n", a, e->text);
    }
    if (g_rep.have_run) /* what a real run of the method is predicted to do */
        report_run(out);
    if (g_json) {
        if (m->cell)
            fbrl_cell_set_observer(m->cell, NULL, NULL);
        if (fclose(g_json) != 0) {
            fprintf(stderr, "fbrlmon: --dry-run-json: %s\n", strerror(errno));
            st = -1;
        }
        g_json = NULL;
    }
    if (g_scratch[0]) {
        if (chdir(g_cwd) != 0)
            fprintf(stderr, "fbrlmon: --dry-run: back to %s: %s\n", g_cwd, strerror(errno));
        nftw(g_scratch, rm_one, 16, FTW_DEPTH | FTW_PHYS);
        g_scratch[0] = '\0';
    }
    if (svg && m->cell) {
        fbrl_status ws = mon_save_svg(NULL, svg, m->cell);
        if (ws != FBRL_OK) {
            fprintf(stderr, "fbrlmon: --svg %s: %s\n", svg, fbrl_status_str(ws));
            st = -1;
        } else {
            fprintf(out, "picture: %s\n", svg);
        }
    }
    if (r)
        *r = g_rep;
    return st;
}
