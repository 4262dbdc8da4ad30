/* SPDX-License-Identifier: MIT */
/* console_run.c - the operator console's run screen (SCREEN_RUN): the run is the library's
 * (fbrl/run.h) and the console one observer of it. What the screen shows of a run is the
 * run's snapshot and its events; the live panel (arm, gripper, devices) follows what the
 * controller executed; keys are requests to the run: pause (after the current step),
 * resume, abort, an answer to a question. */
#include "console_run.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>
#include <curses.h>

#include "console_form.h"
#include "console_text.h"
#include "console_users.h"
#include "fbrl/clock.h"

#define RIGHT_COL     50 /* the live panel (arm, gripper, devices) starts here */
#define DEVICES_SHOWN 8

static const char *const state_names[] = {"READY",   "RUNNING",  "PAUSING (after this step)",
                                          "PAUSED",  "ABORTING", "DONE",
                                          "ABORTED", "FAILED",   "PARTIAL"};

int con_running(const console *c) { return c->state >= ST_RUNNING && c->state <= ST_ABORTING; }

/* ---- drawing ---- */

static void draw_live(console *c)
{
    const fbrl_rapl_pos *p = c->have_pos ? &c->pos : NULL;
    int row = BODY_TOP, shown = 0;
    con_put_at(row++, RIGHT_COL, "| Arm %s", c->have_pos ? c->pos_when : "(read when it stands)");
    if (p != NULL && p->nworld >= 6)
        con_put_at(row++, RIGHT_COL, "|  X%7.2f Y%7.2f Z%7.2f", p->world[0], p->world[1], p->world[2]);
    else
        con_put_at(row++, RIGHT_COL, "|  not read yet (in, deg)");
    if (p != NULL && p->nworld >= 6)
        con_put_at(row++, RIGHT_COL, "|  pitch%7.1f roll%7.1f", p->world[4], p->world[5]);
    else
        con_put_at(row++, RIGHT_COL, "|");
    con_put_at(row++, RIGHT_COL, "| Gripper: %s", c->grip[0] ? c->grip : "not used yet");
    con_put_at(row++, RIGHT_COL, "| Devices");
    for (int n = 1; n <= FBRL_ROBOT_IO_MAX && shown < DEVICES_SHOWN; n++) {
        int on = (c->outputs >> (n - 1)) & 1u;
        if (!c->devname[n][0] && !on)
            continue;
        con_put_at(row++, RIGHT_COL, "|  %-18.18s %s", c->devname[n][0] ? c->devname[n] : "output",
                   on ? "ON" : "off");
        shown++;
    }
    while (row < BODY_TOP + BODY_ROWS)
        con_put_at(row++, RIGHT_COL, "|");
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
    con_put_row(row, "%s", line);
}

void con_run_draw(console *c)
{
    const fbrl_run_snap *s = &c->snap;
    char el[16], left[16];
    long nsteps, rows = BODY_ROWS;
    int live;
    if (fbrl_run_snapshot(&c->m->run, &c->snap) == FBRL_OK && con_running(c)) {
        /* a request the run has not taken yet shows at once (the run's own view) */
        if (c->snap.state == FBRL_RUN_PAUSING)
            c->state = ST_PAUSING;
        else if (c->snap.state == FBRL_RUN_ABORTING)
            c->state = ST_ABORTING;
    }
    nsteps = s->nsteps < rows ? s->nsteps : rows;
    live = c->state != ST_IDLE && c->state < ST_DONE;
    con_fmt_time(el, sizeof el, (double)s->elapsed_ms);
    if (c->state >= ST_DONE)
        con_textf(left, sizeof left, "0:00");
    else if (s->remaining_ms >= 0)
        con_fmt_time(left, sizeof left, (double)s->remaining_ms), memmove(left + 1, left, strlen(left) + 1),
            left[0] = '~';
    else
        con_textf(left, sizeof left, "--:--");
    attron(A_BOLD);
    con_put_row(1, " %-26s elapsed %s  remaining %s", state_names[c->state], el, left);
    attroff(A_BOLD);
    for (long k = 0; k < nsteps; k++) {
        const char *mark = s->step_failed[k]                    ? "!!"
                           : s->step_done[k] >= s->step_runs[k] ? "ok"
                           : k == s->step && live               ? "->"
                                                                : "  ";
        char prog[24] = "";
        if (s->per_sample[k]) /* progress counts samples done, not samples started */
            con_textf(prog, sizeof prog, "sample %ld/%ld", s->step_done[k], s->step_runs[k]);
        if (k == s->step && live)
            attron(A_REVERSE);
        con_put_row(BODY_TOP + (int)k, " %s %2ld %-14.14s %-16s", mark, k + 1, s->step_name[k], prog);
        if (k == s->step && live)
            attroff(A_REVERSE);
    }
    for (long k = nsteps; k < rows; k++)
        con_put_row(BODY_TOP + (int)k, " ");
    if (nsteps < rows) /* below the steps, a row between when there is room */
        draw_samples(c, BODY_TOP + (int)nsteps + (nsteps < rows - 1));
    draw_live(c);
}

/* ---- keys ---- */

static void request_abort(console *c)
{
    c->abort_confirm = 0;
    if (fbrl_run_abort(&c->m->run, c->log->operator_id) != FBRL_OK)
        return; /* it has just ended */
    c->abort_asked = 1;
    c->state = ST_ABORTING;
    con_hint(c, "aborting: the arm goes to its safe place, the outputs go off");
}

/* What a key did stays readable for a while: the wait's progress would replace it at its next tick. */
#define CON_ANSWER_HOLD_US 3000000u

static void answer_shown(console *c) { c->hint_held_until_us = fbrl_clock_now_us() + CON_ANSWER_HOLD_US; }

void con_run_key(console *c, int ch)
{
    int up = ch >= 0 && ch < 256 ? toupper(ch) : 0;
    if (ch == KEY_CTRL_C) {
        request_abort(c);
    } else if (c->asking && (up == 'R' || up == 'S' || up == 'A')) {
        fbrl_run_choice choice = up == 'R' ? FBRL_RUN_RETRY : up == 'S' ? FBRL_RUN_SKIP : FBRL_RUN_STOP;
        if (fbrl_run_answer(&c->m->run, choice, c->log->operator_id) == FBRL_OK) {
            c->asking = 0;
            con_hint(c, "answered: %s", up == 'R' ? "retry" : up == 'S' ? "skip" : "abort");
            answer_shown(c);
        }
    } else if (c->abort_confirm) {
        if (ch == 'y' || ch == 'Y' || ch == KEY_F(8))
            request_abort(c);
        else {
            c->abort_confirm = 0;
            con_hint(c, "not aborted: the method goes on");
            answer_shown(c);
        }
    } else if (ch == KEY_F(8) || ch == 'a') {
        c->abort_confirm = 1;
        con_hint(c, "Abort the run? y or F8 = abort, any other key = go on");
    } else if ((ch == KEY_F(6) || ch == 'p') && c->state == ST_RUNNING) {
        if (fbrl_run_pause(&c->m->run, c->log->operator_id) == FBRL_OK) {
            c->state = ST_PAUSING;
            con_hint(c, "pausing after the current step ...");
            answer_shown(c);
        }
    } else if ((ch == KEY_F(7) || ch == 'r') && (c->state == ST_PAUSED || c->state == ST_PAUSING)) {
        if (fbrl_run_resume(&c->m->run, c->log->operator_id) == FBRL_OK) {
            c->state = ST_RUNNING;
            con_hint(c, "resumed");
            answer_shown(c);
        }
    }
}

/* ---- starting ---- */

void con_run_start(console *c)
{
    long v[FBRL_METHOD_MAX_PARAMS];
    size_t bad = 0;
    if (con_form_commit(c, v) != 0) {
        c->screen = SCREEN_FORM;
        c->state = ST_IDLE;
        return;
    }
    con_textf(c->log->source, sizeof c->log->source, "%s", c->entry ? c->entry->path : "");
    for (size_t k = 0; k < c->meth->nparams; k++) { /* a parameter changed: who, from what, to what */
        long old = 0;
        char what[2 * FBRL_METHOD_NAME_MAX + 2], detail[96];
        if (fbrl_method_param_get(&c->m->methods, c->meth, k, &old) == FBRL_OK && old != v[k]) {
            con_textf(what, sizeof what, "%s %s", c->meth->name, c->meth->params[k].name);
            con_textf(detail, sizeof detail, "%ld -> %ld %s", old, v[k], c->meth->params[k].unit);
            cu_action("parameter", what, detail);
        }
    }
    c->log->audit.err[0] = '\0';
    c->in_vm++;
    fbrl_status st = fbrl_run_start(&c->m->run, c->meth->name, v, c->meth->nparams, &bad);
    c->in_vm--;
    con_flush_partial(c);
    con_form_fill(c);                            /* the values as set */
    if (st != FBRL_OK && c->log->audit.err[0]) { /* refused before it began: why, nothing ran */
        con_push_error(c, NULL, c->log->audit.err);
        con_textf(c->advice[0], sizeof c->advice[0], "-> nothing ran");
        con_hint(c, "the run did not start: see the errors");
        c->screen = SCREEN_FORM;
        c->state = ST_IDLE;
    } else if (st != FBRL_OK) { /* it did not begin: the reason shown, the form back */
        char msg[400];
        con_engine_error(c, msg, sizeof msg);
        con_push_error(c, NULL, st == FBRL_ETHROW ? msg : fbrl_status_str(st));
        if (c->log->write_failed) /* the run log could not be written: that is the reason */
            con_push_error(c, "run log", c->log->write_error);
        c->screen = SCREEN_FORM;
        c->state = ST_IDLE;
        con_hint(c, "the run did not start: see the errors");
    }
}

/* ---- inside a run ---- */

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
        con_push_error(c, "reading the arm's position", fbrl_status_str(st));
    else if (p.nworld >= 6) {
        c->pos = p;
        c->have_pos = 1;
        con_textf(c->pos_when, sizeof c->pos_when, "%s", when);
    }
}

/* While a robot word waits for the arm to stop (fbrl_robot_set_watch): W2 gives a
 * consistent reading during a motion. A reading that fails is not an error of the method:
 * the panel keeps the last one. */
int con_run_watch(console *c)
{
    fbrl_rapl_pos p;
    char t[12];
    if (c->m->link == NULL || fbrl_link_busy(c->m->link))
        return 0;
    if (fbrl_link_where(c->m->link, FBRL_RAPL_W2, &p) != FBRL_OK || p.nworld < 6)
        return 0;
    c->pos = p;
    c->have_pos = 1;
    fbrl_run_snapshot(&c->m->run, &c->snap);
    con_fmt_time(t, sizeof t, (double)c->snap.elapsed_ms);
    con_textf(c->pos_when, sizeof c->pos_when, "(moving, at %s)", t);
    return 1;
}

void con_run_progress(console *c, const char *text)
{
    /* a question or a request the operator made stays visible over the wait's progress */
    if (text != NULL && !c->abort_confirm && c->state == ST_RUNNING &&
        fbrl_clock_now_us() >= c->hint_held_until_us)
        con_hint(c, "%s", text);
}

/* The live view follows the truth: what the controller executed. */
void con_run_exec(console *c, const char *line, size_t len, fbrl_status result)
{
    char l[FBRL_LINK_LINE_MAX + 1];
    if (len > FBRL_LINK_LINE_MAX)
        len = FBRL_LINK_LINE_MAX;
    memcpy(l, line, len);
    l[len] = '\0';
    memcpy(c->last_cmd, l, len + 1);
    if (result != FBRL_OK)
        return;
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
        con_textf(c->grip, sizeof c->grip, "width %s in", l + 5);
    } else if (strcmp(l, "OPEN") == 0 || strcmp(l, "CLOSE") == 0) {
        con_textf(c->grip, sizeof c->grip, "%s", l[0] == 'O' ? "open" : "closed");
    }
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
    con_hint(c, "running %s", m->name);
}

/* The run is over: where the arm stands (still inside the run, so in its log), the outcome
 * on the state line and the hint, and every sample that did not succeed under Messages. */
static void run_ends(console *c, fbrl_run *run, const fbrl_run_event *ev)
{
    fbrl_run_snap *s = &c->snap;
    long ok = 0, failed = 0, skipped = 0;
    char line[MIN_COLS + 1];
    read_arm(c, ev->outcome == FBRL_RUN_ABORTED ? "(safe place)" /* after the safe stop and ON-ABORT */
                : ev->text != NULL              ? "(halted)"     /* stopped by a failed step */
                                                : "(finished)");
    fbrl_run_snapshot(run, s);
    con_flush_partial(c);
    if (ev->text != NULL && ev->outcome != FBRL_RUN_COMPLETED && !c->errs[0][0])
        con_push_error(c, ev->method->name, ev->text); /* (a failed step has said it already) */
    for (long i = 0; i < s->samples; i++) {
        const fbrl_run_sample *o = &s->outcomes[i];
        ok += o->outcome == FBRL_SAMPLE_SUCCEEDED;
        failed += o->outcome == FBRL_SAMPLE_FAILED;
        skipped += o->outcome == FBRL_SAMPLE_SKIPPED;
        if (o->outcome == FBRL_SAMPLE_FAILED || o->outcome == FBRL_SAMPLE_SKIPPED) {
            con_textf(line, sizeof line, "sample %ld %s: %s", i + 1,
                      fbrl_run_sample_name((fbrl_run_sample_outcome)o->outcome), o->reason);
            con_push_msg(c, line);
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
        con_textf(line, sizeof line, ": %ld of %ld samples succeeded", ok, s->samples);
    else
        line[0] = '\0';
    if (ev->outcome == FBRL_RUN_ABORTED)
        con_hint(c, "%s aborted%s; arm at safe place, outputs off", ev->method->name, line);
    else if (ev->outcome == FBRL_RUN_COMPLETED)
        con_hint(c, "%s completed%s; F5 runs it again", ev->method->name, line);
    else if (ev->text != NULL)
        con_hint(c, "%s %s%s; arm halted, outputs off", ev->method->name,
                 fbrl_run_outcome_name((fbrl_run_outcome)ev->outcome), line);
    else
        con_hint(c, "%s %s%s (%ld failed, %ld skipped)", ev->method->name,
                 fbrl_run_outcome_name((fbrl_run_outcome)ev->outcome), line, failed, skipped);
}

void con_run_event(console *c, fbrl_run *run, const fbrl_run_event *ev)
{
    char where[64];
    switch (ev->kind) {
    case FBRL_RUN_EV_BEGIN: run_begins(c, ev->method); break;
    case FBRL_RUN_EV_STEP_END:
        if (ev->text != NULL) {
            if (ev->sample >= 0)
                con_textf(where, sizeof where, "%s, sample %ld", ev->method->steps[ev->step].name,
                          ev->sample + 1);
            else
                con_textf(where, sizeof where, "%s", ev->method->steps[ev->step].name);
            con_push_error(c, where, ev->text);
        }
        break;
    case FBRL_RUN_EV_QUESTION: /* a corrective action's ASK: R, S or A answers */
        c->asking = 1;
        con_push_error(c, "asked", ev->text);
        con_textf(c->advice[0], sizeof c->advice[0],
                  "-> R retries the step, S skips this sample, A aborts the run");
        con_hint(c, "R retry, S skip this sample, A abort: %s", ev->text);
        break;
    case FBRL_RUN_EV_ANSWER: c->asking = 0; break;
    case FBRL_RUN_EV_PAUSE:
        c->state = ST_PAUSED;
        con_hint(c, "paused before step %ld (%s): F7 resumes, F8 aborts", ev->step + 1,
                 ev->method->steps[ev->step].name);
        read_arm(c, "(paused)");
        break;
    case FBRL_RUN_EV_RESUME:
        if (c->state == ST_PAUSED)
            c->state = ST_RUNNING;
        break;
    case FBRL_RUN_EV_ABORT:
        c->state = ST_ABORTING;
        con_hint(c, "aborted: the arm goes to its safe place ...");
        break;
    case FBRL_RUN_EV_SAFE_STOP:
        if (ev->status != FBRL_OK)
            con_push_error(c, "safe stop", fbrl_status_str(ev->status));
        break;
    case FBRL_RUN_EV_ON_ABORT:
        if (ev->text != NULL)
            con_push_error(c, "ON-ABORT", ev->text);
        break;
    case FBRL_RUN_EV_END: run_ends(c, run, ev); break;
    default: break;
    }
}

void con_run_log_failed(void *ctx, const char *message)
{
    console *c = ctx;
    con_push_error(c, "run log", message);
    if (message == c->log->audit.err) /* the run was refused before it began */
        con_textf(c->advice[0], sizeof c->advice[0], "-> nothing ran: see why above");
    else
        con_textf(c->advice[0], sizeof c->advice[0],
                  "-> the run goes on without a full log: free space, then check the log");
}
