/* SPDX-License-Identifier: MIT */
/* runlog.c - the run log: JSON Lines records built in a fixed buffer, one sink write each;
 * a poll repeated while the controller is waited for is one record with its count. */
#include "fbrl/runlog.h"
#include "fbrl/run.h"

#include <stdio.h>
#include <string.h>

#define CUT_MARK "..."
/* What a summary keeps free for what follows its samples ("]", the count left out, "}") */
#define SUMMARY_TAIL 64
/* The lines the human summary names one by one (samples that did not succeed) */
#define TEXT_SAMPLES 10

/* ---- one record in l->line ---- */

static void put_raw(fbrl_runlog *l, const char *s, size_t n)
{
    /* room is kept for the closing "}\n" */
    size_t room = l->cap - 2 - l->len;
    if (n > room)
        n = room, l->full = 1;
    memcpy(l->line + l->len, s, n);
    l->len += n;
}

static void put(fbrl_runlog *l, const char *s) { put_raw(l, s, strlen(s)); }

/* A JSON string: quotes, backslash and control characters escaped; other bytes as they
 * are (UTF-8 text stays UTF-8). A text that does not fit is cut with "...". */
static void put_str(fbrl_runlog *l, const char *s, size_t n)
{
    static const char hex[] = "0123456789abcdef";
    const size_t tail = sizeof CUT_MARK + 2; /* the mark, the quote, a comma */
    put(l, "\"");
    for (size_t i = 0; i < n; i++) {
        unsigned char c = (unsigned char)s[i];
        char esc[7];
        size_t k = 0;
        if (c == '"' || c == '\\') {
            esc[k++] = '\\';
            esc[k++] = (char)c;
        } else if (c == '\n') {
            esc[k++] = '\\';
            esc[k++] = 'n';
        } else if (c < 0x20 || c == 0x7f) {
            memcpy(esc, "\\u00", 4);
            esc[4] = hex[c >> 4];
            esc[5] = hex[c & 15];
            k = 6;
        } else {
            esc[k++] = (char)c;
        }
        if (l->len + k + tail + 2 > l->cap) {
            put(l, CUT_MARK);
            l->full = 1;
            break;
        }
        put_raw(l, esc, k);
    }
    put(l, "\"");
}

static void field_str(fbrl_runlog *l, const char *key, const char *v)
{
    put(l, ",\"");
    put(l, key);
    put(l, "\":");
    if (v == NULL)
        put(l, "null");
    else
        put_str(l, v, strlen(v));
}

static void field_long(fbrl_runlog *l, const char *key, long v)
{
    char num[32];
    snprintf(num, sizeof num, "%ld", v);
    put(l, ",\"");
    put(l, key);
    put(l, "\":");
    put(l, num);
}

static uint64_t now_ms(const fbrl_runlog *l)
{
    uint64_t t = l->now_us ? l->now_us(l->clock_ctx) : 0;
    return t >= l->t0_us ? (t - l->t0_us) / 1000u : 0;
}

static fbrl_status finish(fbrl_runlog *l);

/* Start a record at t ms: {"t":ms,"type":"..." */
static void start_at(fbrl_runlog *l, const char *type, uint64_t t)
{
    char num[32];
    snprintf(num, sizeof num, "{\"t\":%llu", (unsigned long long)t);
    l->len = 0;
    l->cap = FBRL_RUNLOG_LINE_MAX;
    l->full = 0;
    put(l, num);
    field_str(l, "type", type);
}

/* The poll being folded, written (before any other record, and at the end). */
static fbrl_status flush_poll(fbrl_runlog *l)
{
    unsigned long n = l->poll_count;
    if (n == 0)
        return FBRL_OK;
    l->poll_count = 0;
    start_at(l, "command", l->poll_t0);
    field_str(l, "line", l->poll);
    field_str(l, "status", "ran");
    if (n > 1) {
        field_long(l, "count", (long)n);
        field_long(l, "last_t", (long)l->poll_t1);
    }
    return finish(l);
}

/* Start a record now (a poll being folded goes first). */
static void start(fbrl_runlog *l, const char *type)
{
    flush_poll(l);
    start_at(l, type, now_ms(l));
}

static fbrl_status finish(fbrl_runlog *l)
{
    l->line[l->len++] = '}';
    l->line[l->len++] = '\n';
    if (l->write(l->write_ctx, l->line, l->len) != 0) {
        if (l->failed == FBRL_OK)
            l->failed = FBRL_EIO;
        return FBRL_EIO;
    }
    return FBRL_OK;
}

/* ---- the records ---- */

fbrl_status fbrl_runlog_begin(fbrl_runlog *l, fbrl_runlog_write_fn write, void *write_ctx,
                              fbrl_runlog_clock_fn now_us, void *clock_ctx, const fbrl_runlog_header *h)
{
    if (l == NULL || write == NULL || h == NULL || h->method == NULL || (h->nparams && h->params == NULL) ||
        h->nparams > FBRL_RUNLOG_MAX_PARAMS)
        return FBRL_EINVAL;
    if (l->open)
        return FBRL_ESTATE;
    memset(l, 0, sizeof *l);
    l->write = write;
    l->write_ctx = write_ctx;
    l->now_us = now_us;
    l->clock_ctx = clock_ctx;
    l->t0_us = now_us ? now_us(clock_ctx) : 0;
    snprintf(l->method, sizeof l->method, "%s", h->method);
    start(l, "header");
    field_str(l, "method", h->method);
    field_str(l, "source", h->source);
    field_str(l, "operator", h->operator_id);
    field_str(l, "started", h->started);
    field_str(l, "controller", h->controller);
    field_str(l, "program", h->program);
    field_str(l, "calibration", h->calibration);
    put(l, ",\"parameters\":[");
    for (size_t i = 0; i < h->nparams; i++) {
        const fbrl_runlog_param *p = &h->params[i];
        put(l, i ? ",{\"name\":" : "{\"name\":");
        put_str(l, p->name ? p->name : "", p->name ? strlen(p->name) : 0);
        field_long(l, "value", p->value);
        field_str(l, "unit", p->unit);
        put(l, "}");
    }
    put(l, "]");
    if (finish(l) != FBRL_OK)
        return FBRL_EIO;
    l->open = 1;
    return FBRL_OK;
}

int fbrl_runlog_is_open(const fbrl_runlog *l) { return l != NULL && l->open; }

static fbrl_status opened(const fbrl_runlog *l)
{
    return l == NULL ? FBRL_EINVAL : l->open ? FBRL_OK : FBRL_ESTATE;
}

fbrl_status fbrl_runlog_step_start(fbrl_runlog *l, const char *step, long sample)
{
    fbrl_status st = opened(l);
    if (st != FBRL_OK || step == NULL)
        return st != FBRL_OK ? st : FBRL_EINVAL;
    start(l, "step_start");
    field_str(l, "step", step);
    if (sample >= 0)
        field_long(l, "sample", sample);
    return finish(l);
}

fbrl_status fbrl_runlog_step_end(fbrl_runlog *l, const char *step, long sample, const char *error)
{
    fbrl_status st = opened(l);
    if (st != FBRL_OK || step == NULL)
        return st != FBRL_OK ? st : FBRL_EINVAL;
    l->steps++;
    if (error != NULL)
        l->aborted_steps++;
    start(l, "step_end");
    field_str(l, "step", step);
    if (sample >= 0)
        field_long(l, "sample", sample);
    field_str(l, "status", error ? "failed" : "ok");
    if (error != NULL)
        field_str(l, "error", error);
    return finish(l);
}

/* A query the robot words repeat while they wait: the velocity (W5) while a motion ends,
 * an input (TYPEI SIG(n)) until it changes, a variable (TYPEI, TYPEV). */
static int is_poll(const char *line, size_t len)
{
    static const char *const polls[] = {"W5", "TYPEI ", "TYPEV "};
    for (size_t i = 0; i < sizeof polls / sizeof polls[0]; i++) {
        size_t n = strlen(polls[i]);
        if (len >= n && memcmp(line, polls[i], n) == 0 && (polls[i][n - 1] == ' ' || len == n))
            return len <= FBRL_RUNLOG_POLL_MAX;
    }
    return 0;
}

fbrl_status fbrl_runlog_command(fbrl_runlog *l, const char *line, size_t len, fbrl_status result, int code)
{
    return fbrl_runlog_command_run(l, line, len, result, code, 1);
}

fbrl_status fbrl_runlog_command_run(fbrl_runlog *l, const char *line, size_t len, fbrl_status result, int code,
                                    unsigned run)
{
    fbrl_status st = opened(l);
    const char *how = "ran";
    if (st != FBRL_OK || line == NULL)
        return st != FBRL_OK ? st : FBRL_EINVAL;
    if (result == FBRL_OK && is_poll(line, len)) {
        uint64_t t = now_ms(l);
        l->commands++;
        if (l->poll_count > 0 && strlen(l->poll) == len && memcmp(l->poll, line, len) == 0) {
            l->poll_count++;
            l->poll_t1 = t;
            return FBRL_OK;
        }
        st = flush_poll(l);
        memcpy(l->poll, line, len);
        l->poll[len] = '\0';
        l->poll_count = 1;
        l->poll_t0 = l->poll_t1 = t;
        return st;
    }
    if (result == FBRL_ECONTROLLER)
        how = "refused", l->refused++;
    else if (result == FBRL_EMAYBE)
        how = "may-have-run", l->maybe++;
    else if (result == FBRL_EPROTOCOL)
        how = "reply-damaged"; /* a query the link ran again: it did run */
    else if (result != FBRL_OK)
        how = "not-run", l->not_run++;
    l->commands++;
    start(l, "command");
    put(l, ",\"line\":");
    put_str(l, line, len);
    field_str(l, "status", how);
    if (result == FBRL_ECONTROLLER && code >= 0)
        field_long(l, "code", code);
    if (run > 1)
        field_long(l, "run", (long)run);
    return finish(l);
}

static fbrl_status timed(fbrl_runlog *l, const char *type, const char *key, const char *what,
                         const char *action, long planned_ms, long actual_ms)
{
    fbrl_status st = opened(l);
    if (st != FBRL_OK || what == NULL)
        return st != FBRL_OK ? st : FBRL_EINVAL;
    start(l, type);
    field_str(l, key, what);
    if (action != NULL)
        field_str(l, "action", action);
    if (planned_ms >= 0)
        field_long(l, "planned_ms", planned_ms);
    field_long(l, "actual_ms", actual_ms);
    return finish(l);
}

fbrl_status fbrl_runlog_device(fbrl_runlog *l, const char *device, const char *action, long planned_ms,
                               long actual_ms)
{
    if (action == NULL)
        return FBRL_EINVAL;
    fbrl_status st = timed(l, "device", "device", device, action, planned_ms, actual_ms);
    if (st == FBRL_OK)
        l->devices++;
    return st;
}

fbrl_status fbrl_runlog_wait(fbrl_runlog *l, const char *what, long planned_ms, long actual_ms)
{
    fbrl_status st = timed(l, "wait", "wait", what, NULL, planned_ms, actual_ms);
    if (st == FBRL_OK)
        l->waits++;
    return st;
}

fbrl_status fbrl_runlog_error(fbrl_runlog *l, const char *where, const char *message, const char *advice)
{
    fbrl_status st = opened(l);
    if (st != FBRL_OK || message == NULL)
        return st != FBRL_OK ? st : FBRL_EINVAL;
    l->errors++;
    start(l, "error");
    field_str(l, "where", where);
    field_str(l, "message", message);
    field_str(l, "advice", advice);
    return finish(l);
}

fbrl_status fbrl_runlog_note(fbrl_runlog *l, const char *event, const char *who, const char *text)
{
    fbrl_status st = opened(l);
    if (st != FBRL_OK || event == NULL)
        return st != FBRL_OK ? st : FBRL_EINVAL;
    start(l, "note");
    field_str(l, "event", event);
    if (who != NULL)
        field_str(l, "operator", who);
    field_str(l, "text", text);
    return finish(l);
}

fbrl_status fbrl_runlog_sample(fbrl_runlog *l, long sample, const char *outcome, const char *reason)
{
    fbrl_status st = opened(l);
    if (st != FBRL_OK || outcome == NULL)
        return st != FBRL_OK ? st : FBRL_EINVAL;
    start(l, "sample");
    field_long(l, "sample", sample);
    field_str(l, "outcome", outcome);
    field_str(l, "reason", reason ? reason : "");
    return finish(l);
}

static fbrl_status text_line(fbrl_runlog *l, const char *text)
{
    start(l, "text");
    field_str(l, "text", text);
    return finish(l);
}

/* The samples into the summary being made, as many as fit; the rest counted. */
static void put_samples(fbrl_runlog *l, const fbrl_runlog_outcome *samples, size_t n)
{
    size_t i;
    put(l, ",\"samples\":[");
    l->cap = FBRL_RUNLOG_LINE_MAX - SUMMARY_TAIL;
    for (i = 0; i < n; i++) {
        size_t mark = l->len;
        char num[24];
        snprintf(num, sizeof num, "%ld", samples[i].sample);
        put(l, i ? ",{\"sample\":" : "{\"sample\":");
        put(l, num);
        field_str(l, "outcome", samples[i].outcome ? samples[i].outcome : "");
        field_str(l, "reason", samples[i].reason ? samples[i].reason : "");
        put(l, "}");
        if (l->full) { /* this one does not fit whole: it and the rest are counted */
            l->len = mark;
            l->full = 0;
            break;
        }
    }
    l->cap = FBRL_RUNLOG_LINE_MAX;
    put(l, "]");
    if (i < n)
        field_long(l, "samples_left_out", (long)(n - i));
}

fbrl_status fbrl_runlog_end(fbrl_runlog *l, const char *outcome, const fbrl_runlog_outcome *samples, size_t n)
{
    fbrl_status st = opened(l);
    char buf[256];
    uint64_t ms;
    unsigned long ok = 0, failed = 0, skipped = 0, named = 0;
    if (st != FBRL_OK || outcome == NULL || (samples == NULL && n != 0))
        return st != FBRL_OK ? st : FBRL_EINVAL;
    ms = now_ms(l);
    start(l, "summary");
    field_str(l, "outcome", outcome);
    field_long(l, "elapsed_ms", (long)ms);
    field_long(l, "steps", (long)l->steps);
    field_long(l, "commands", (long)l->commands);
    field_long(l, "refused", (long)l->refused);
    field_long(l, "may_have_run", (long)l->maybe);
    field_long(l, "devices", (long)l->devices);
    field_long(l, "waits", (long)l->waits);
    field_long(l, "errors", (long)l->errors);
    put_samples(l, samples, n);
    st = finish(l);
    /* the human summary: what a person reads first */
    snprintf(buf, sizeof buf, "%s: %s after %lu.%01lu s", l->method, outcome, (unsigned long)(ms / 1000u),
             (unsigned long)(ms % 1000u / 100u));
    if (st == FBRL_OK)
        st = text_line(l, buf);
    for (size_t i = 0; i < n; i++) {
        const char *o = samples[i].outcome ? samples[i].outcome : "";
        ok += strcmp(o, "succeeded") == 0;
        failed += strcmp(o, "failed") == 0;
        skipped += strcmp(o, "skipped") == 0;
    }
    if (n > 0) {
        snprintf(buf, sizeof buf, "%lu sample%s: %lu succeeded, %lu failed, %lu skipped", (unsigned long)n,
                 n == 1 ? "" : "s", ok, failed, skipped);
        if (st == FBRL_OK)
            st = text_line(l, buf);
    }
    for (size_t i = 0; i < n && st == FBRL_OK; i++) {
        const char *o = samples[i].outcome ? samples[i].outcome : "";
        if (strcmp(o, "succeeded") == 0)
            continue;
        if (++named > TEXT_SAMPLES) {
            snprintf(buf, sizeof buf, "... and %lu more (the summary record lists every sample)",
                     failed + skipped - TEXT_SAMPLES);
            st = text_line(l, buf);
            break;
        }
        snprintf(buf, sizeof buf, "sample %ld %s: %.200s", samples[i].sample, o,
                 samples[i].reason && samples[i].reason[0] ? samples[i].reason : "(no reason given)");
        st = text_line(l, buf);
    }
    snprintf(buf, sizeof buf, "%lu steps done (%lu failed), %lu commands (%lu refused, %lu may have run)",
             l->steps, l->aborted_steps, l->commands, l->refused, l->maybe);
    if (st == FBRL_OK)
        st = text_line(l, buf);
    snprintf(buf, sizeof buf, "%lu device actions, %lu timed waits, %lu errors%s", l->devices, l->waits,
             l->errors, l->failed != FBRL_OK ? " (the log missed records: a write failed)" : "");
    if (st == FBRL_OK)
        st = text_line(l, buf);
    l->open = 0;
    return st != FBRL_OK ? st : l->failed;
}

/* ---- a run's records ---- */

const char *fbrl_runlog_advice(const char *msg)
{
    static const struct {
        const char *seen, *advice;
    } table[] = {
        {"aborted by the operator", "arm at its safe place, outputs off: start again when ready"},
        {"user interrupt", "arm at its safe place, outputs off: start again when ready"},
        {"HAS NOT BEEN HOMED", "home the arm (HOME at the prompt, or the pendant), then start again"},
        {"ARM POWER", "switch the arm's power on, then start again"},
        {"TRANSFORM ILLEGAL", "a position is out of the arm's reach: have the method developer check it"},
        {"OUT OF RANGE", "a joint would pass its limit: have the method developer check positions"},
        {"disconnected", "check the cable and the controller's power, then reconnect (RECONNECT)"},
        {"timed out", "the controller did not answer: check cable and controller, then retry"},
        {"not separated", "check that the tube is in the gripper and the sensor is clean"},
        {"undefined word", "the method file has an error: tell the method developer"},
    };
    for (size_t i = 0; msg && i < sizeof table / sizeof table[0]; i++)
        if (strstr(msg, table[i].seen))
            return table[i].advice;
    return "read the message, fix the cause, and start the method again";
}

/* "Buffer, sample 2" (samples numbered from 1, as people do), or the step alone. */
static const char *where_of(const fbrl_run_event *ev, char *buf, size_t cap)
{
    const char *step = ev->step >= 0 ? ev->method->steps[ev->step].name : ev->method->name;
    if (ev->sample >= 0)
        snprintf(buf, cap, "%s, sample %ld", step, ev->sample + 1);
    else
        snprintf(buf, cap, "%s", step);
    return buf;
}

/* The summary: every sample's outcome from the run's snapshot. */
static fbrl_status log_end(fbrl_runlog *l, fbrl_run *run, const fbrl_run_event *ev, fbrl_run_snap *s)
{
    fbrl_runlog_outcome out[FBRL_RUN_MAX_SAMPLES];
    size_t n = 0;
    if (fbrl_run_snapshot(run, s) == FBRL_OK)
        for (long i = 0; i < s->samples && i < FBRL_RUN_MAX_SAMPLES; i++, n++) {
            out[n].sample = i + 1;
            out[n].outcome = fbrl_run_sample_name((fbrl_run_sample_outcome)s->outcomes[i].outcome);
            out[n].reason = s->outcomes[i].reason;
        }
    return fbrl_runlog_end(l, fbrl_run_outcome_name((fbrl_run_outcome)ev->outcome), out, n);
}

fbrl_status fbrl_runlog_event(fbrl_runlog *l, fbrl_run *run, const fbrl_run_event *ev, fbrl_run_snap *scratch)
{
    static const char *const choices[] = {"", "retry", "skip the sample", "abort"};
    char where[96], text[320];
    if (!l || !run || !ev || !scratch)
        return FBRL_EINVAL;
    if (!fbrl_runlog_is_open(l) || ev->method == NULL)
        return FBRL_OK;
    switch (ev->kind) {
    case FBRL_RUN_EV_STEP_BEGIN:
        return fbrl_runlog_step_start(l, ev->method->steps[ev->step].name, ev->sample >= 0 ? ev->sample + 1 : -1);
    case FBRL_RUN_EV_STEP_END:
        if (ev->text)
            fbrl_runlog_error(l, where_of(ev, where, sizeof where), ev->text, fbrl_runlog_advice(ev->text));
        return fbrl_runlog_step_end(l, ev->method->steps[ev->step].name, ev->sample >= 0 ? ev->sample + 1 : -1,
                                    ev->text);
    case FBRL_RUN_EV_SAMPLE:
        return fbrl_runlog_sample(l, ev->sample + 1, fbrl_run_sample_name((fbrl_run_sample_outcome)ev->outcome),
                                  ev->text);
    case FBRL_RUN_EV_RECOVERY: /* a corrective action taken (ON-FAILURE) */
        if (ev->sample >= 0)
            snprintf(where, sizeof where, "%s, sample %ld", ev->where, ev->sample + 1);
        else
            snprintf(where, sizeof where, "%s", ev->where);
        snprintf(text, sizeof text, "%s: %s", ev->kind_name, ev->text);
        fbrl_runlog_error(l, where, text, ev->action);
        snprintf(text, sizeof text, "%s: %s (%s): %s", where, ev->kind_name, ev->text, ev->action);
        return fbrl_runlog_note(l, "recovery", NULL, text);
    case FBRL_RUN_EV_QUESTION: return fbrl_runlog_note(l, "question", NULL, ev->text);
    case FBRL_RUN_EV_ANSWER:
        return fbrl_runlog_note(l, "answer", ev->who, ev->choice >= 1 && ev->choice <= 3 ? choices[ev->choice] : "");
    case FBRL_RUN_EV_PAUSE:
        snprintf(text, sizeof text, "before %s", where_of(ev, where, sizeof where));
        return fbrl_runlog_note(l, "pause", ev->who, text);
    case FBRL_RUN_EV_RESUME: return fbrl_runlog_note(l, "resume", ev->who, NULL);
    case FBRL_RUN_EV_ABORT: return fbrl_runlog_note(l, "abort", ev->who, NULL);
    case FBRL_RUN_EV_SAFE_STOP: return fbrl_runlog_note(l, "safe-stop", NULL, ev->text);
    case FBRL_RUN_EV_ON_ABORT:
        if (ev->text)
            return fbrl_runlog_error(l, "ON-ABORT", ev->text, "check where the arm is before the next run");
        return fbrl_runlog_note(l, "on-abort", NULL, "the method's way to its safe place ran");
    case FBRL_RUN_EV_END: return log_end(l, run, ev, scratch);
    default: return FBRL_OK;
    }
}
