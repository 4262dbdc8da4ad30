/* SPDX-License-Identifier: MIT */
/* method_run.c - a method run as one thing (include/fbrl/run.h): the steps in order on the
 * engine's thread, per-sample and per-run outcomes, pause, resume, abort and answers
 * asked for from any thread, a snapshot any thread reads, events to the observers.
 *
 * The run is the layer above the word sets (docs: DESIGN 10): it reaches the engine
 * through fbrl/vmx.h alone, as a word set does (test word_set_boundary reads this file
 * too), and lives beside the core for src/atomic.h, which its threads need (named apart
 * from the engine's src/lang/run.c, the inner interpreter).
 *
 * Threads. The engine's thread alone writes `work` and publishes it into `pub` word by
 * word between two increments of `seq` (odd while it writes); a reader copies the words
 * and keeps the copy when `seq` was even and the same before and after. Requests set their
 * flag (and who asked) under `lock`, a spin lock held for a few stores; an abort also
 * interrupts the engine there, so the engine, taking the same lock when it ends a run,
 * never leaves an interrupt behind for the next thing the engine runs. */
#include "fbrl/run.h"

#include <stdio.h>
#include <string.h>

#include "atomic.h"
#include "fbrl/vm_throw.h"
#include "fbrl/vmx.h"

#define SPINS_BEFORE_SLEEP 1000
#define SNAPSHOT_TRIES     1000 /* sleeps of 1 ms before a reader gives up */

enum { WHO_PAUSE, WHO_RESUME, WHO_ABORT, WHO_ANSWER };

static const char *const state_names[] = {"idle", "running", "pausing", "paused", "aborting", "finished"};
static const char *const outcome_names[] = {"", "completed", "partial", "failed", "aborted"};
static const char *const sample_names[] = {"pending", "succeeded", "failed", "skipped"};

const char *fbrl_run_state_name(fbrl_run_state s)
{
    return (unsigned)s < sizeof state_names / sizeof state_names[0] ? state_names[s] : "";
}

const char *fbrl_run_outcome_name(fbrl_run_outcome o)
{
    return (unsigned)o < sizeof outcome_names / sizeof outcome_names[0] ? outcome_names[o] : "";
}

const char *fbrl_run_sample_name(fbrl_run_sample_outcome o)
{
    return (unsigned)o < sizeof sample_names / sizeof sample_names[0] ? sample_names[o] : "";
}

static void copy_text(char *dst, size_t cap, const char *s)
{
    snprintf(dst, cap, "%s", s ? s : "");
}

/* ---- time, through the VM's host ---- */

static uint64_t now_us(const fbrl_run *r)
{
    const fbrl_vm_host *h = fbrl_vmx_host(r->vm);
    return h && h->now_us ? h->now_us(h->user) : 0;
}

static void sleep_ms(const fbrl_run *r, uint32_t ms)
{
    const fbrl_vm_host *h = fbrl_vmx_host(r->vm);
    if (h && h->sleep_ms)
        h->sleep_ms(h->user, ms);
}

/* ---- the request lock ---- */

static void lock(fbrl_run *r)
{
    unsigned spins = 0;
    while (!fbrl_cas_acq(&r->lock, 0, 1))
        if (++spins % SPINS_BEFORE_SLEEP == 0)
            sleep_ms(r, 1); /* its holder was put to sleep: let it run */
}

static void unlock(fbrl_run *r) { fbrl_store_rel(&r->lock, 0); }

/* ---- publishing (engine thread) and reading (any thread) ---- */

static void publish(fbrl_run *r)
{
    const unsigned char *src = (const unsigned char *)&r->work;
    size_t seq = fbrl_load_rlx(&r->seq);
    r->work.s.version++;
    fbrl_store_rlx(&r->seq, seq + 1);
    for (size_t i = 0; i < FBRL_RUN_PUB_WORDS_; i++) {
        size_t v = 0, off = i * sizeof v, n = sizeof(fbrl_run_published) - off;
        memcpy(&v, src + off, n < sizeof v ? n : sizeof v);
        fbrl_store_rel(&r->pub[i], v); /* release: the odd count is seen first */
    }
    fbrl_store_rel(&r->seq, seq + 2);
}

static fbrl_status read_published(const fbrl_run *r, fbrl_run_published *out)
{
    unsigned char *dst = (unsigned char *)out;
    for (unsigned tries = 0; tries < SNAPSHOT_TRIES * SPINS_BEFORE_SLEEP; tries++) {
        size_t s1 = fbrl_load_acq(&r->seq);
        if (s1 & 1u) {
            if ((tries + 1) % SPINS_BEFORE_SLEEP == 0)
                sleep_ms(r, 1);
            continue;
        }
        for (size_t i = 0; i < FBRL_RUN_PUB_WORDS_; i++) {
            size_t v = fbrl_load_acq(&r->pub[i]), off = i * sizeof v, n = sizeof(fbrl_run_published) - off;
            memcpy(dst + off, &v, n < sizeof v ? n : sizeof v);
        }
        if (fbrl_load_rlx(&r->seq) == s1)
            return FBRL_OK;
    }
    return FBRL_ETIMEOUT;
}

/* The time left: the rest of the current step's run and every run still to come, each at
 * its known time (a step not known counts as the average of those known). */
static long remaining(const fbrl_run_published *p, uint64_t now)
{
    const fbrl_run_snap *s = &p->s;
    double known = 0, sum = 0;
    long nknown = 0;
    if (s->state == FBRL_RUN_FINISHED)
        return 0;
    if (s->state == FBRL_RUN_IDLE)
        return -1;
    for (long k = 0; k < s->nsteps; k++)
        if (p->est_ms[k] > 0)
            known += p->est_ms[k], nknown++;
    if (nknown == 0)
        return -1;
    for (long k = 0; k < s->nsteps; k++) {
        double one = p->est_ms[k] > 0 ? p->est_ms[k] : known / (double)nknown;
        long todo = s->step_runs[k] - p->ended[k];
        if (k == s->step && todo > 0 && s->state != FBRL_RUN_PAUSED) {
            double in = now > p->step_t0_us ? (double)(now - p->step_t0_us) / 1000.0 : 0;
            sum += one > in ? one - in : 0;
            todo--;
        }
        if (todo > 0)
            sum += one * (double)todo;
    }
    return (long)(sum + 0.5);
}

fbrl_status fbrl_run_snapshot(const fbrl_run *r, fbrl_run_snap *out)
{
    static fbrl_run_published zero;
    fbrl_run_published p = zero;
    if (r == NULL || out == NULL || r->vm == NULL)
        return FBRL_EINVAL;
    fbrl_status st = read_published(r, &p);
    if (st != FBRL_OK)
        return st;
    uint64_t now = now_us(r), end = p.end_us ? p.end_us : now;
    p.s.elapsed_ms = p.s.state != FBRL_RUN_IDLE && end > p.t0_us ? (long)((end - p.t0_us) / 1000u) : 0;
    p.s.remaining_ms = remaining(&p, now);
    /* a request the engine has not taken yet shows at once */
    if (p.s.state == FBRL_RUN_RUNNING || p.s.state == FBRL_RUN_PAUSED) {
        fbrl_run *w = (fbrl_run *)r; /* the lock is the only thing written */
        lock(w);
        if (fbrl_load_rlx(&r->req_abort)) {
            p.s.state = FBRL_RUN_ABORTING;
            copy_text(p.s.who, sizeof p.s.who, r->req_who[WHO_ABORT]);
        } else if (p.s.state == FBRL_RUN_RUNNING && fbrl_load_rlx(&r->req_pause)) {
            p.s.state = FBRL_RUN_PAUSING;
            copy_text(p.s.who, sizeof p.s.who, r->req_who[WHO_PAUSE]);
        }
        unlock(w);
    }
    *out = p.s;
    return FBRL_OK;
}

/* ---- events ---- */

static int emit(fbrl_run *r, fbrl_run_event *ev)
{
    int any = 0;
    ev->method = r->m;
    for (size_t i = 0; i < FBRL_RUN_OBSERVERS; i++)
        if (r->obs[i].fn && r->obs[i].fn(r->obs[i].ctx, r, ev) != 0)
            any = 1;
    return any;
}

static void event(fbrl_run_event *ev, fbrl_run_event_kind kind, long step, long sample, const char *text)
{
    memset(ev, 0, sizeof *ev);
    ev->kind = kind;
    ev->step = step;
    ev->sample = sample;
    ev->text = text;
    ev->who = "";
}

/* Nothing to do but wait for a request: the observers may wait (reading keys), or the
 * host's clock sleeps. */
static void wait_once(fbrl_run *r)
{
    fbrl_run_event ev;
    event(&ev, FBRL_RUN_EV_WAIT, r->work.s.step, r->work.s.sample, NULL);
    if (!emit(r, &ev))
        sleep_ms(r, FBRL_RUN_POLL_MS);
}

fbrl_status fbrl_run_observe(fbrl_run *r, fbrl_run_observer_fn fn, void *ctx)
{
    if (r == NULL || fn == NULL)
        return FBRL_EINVAL;
    if (r->active)
        return FBRL_ESTATE;
    for (size_t i = 0; i < FBRL_RUN_OBSERVERS; i++)
        if (r->obs[i].fn == NULL) {
            r->obs[i].fn = fn;
            r->obs[i].ctx = ctx;
            return FBRL_OK;
        }
    return FBRL_EFULL;
}

fbrl_status fbrl_run_unobserve(fbrl_run *r, fbrl_run_observer_fn fn, void *ctx)
{
    if (r == NULL || fn == NULL)
        return FBRL_EINVAL;
    if (r->active)
        return FBRL_ESTATE;
    for (size_t i = 0; i < FBRL_RUN_OBSERVERS; i++)
        if (r->obs[i].fn == fn && r->obs[i].ctx == ctx) { /* the others keep their order */
            memmove(&r->obs[i], &r->obs[i + 1], (FBRL_RUN_OBSERVERS - 1 - i) * sizeof r->obs[0]);
            r->obs[FBRL_RUN_OBSERVERS - 1].fn = NULL;
            r->obs[FBRL_RUN_OBSERVERS - 1].ctx = NULL;
            return FBRL_OK;
        }
    return FBRL_ENOENT;
}

/* ---- requests (any thread) ---- */

static fbrl_status request(fbrl_run *r, size_t *flag, size_t value, int slot, const char *who, int when)
{
    fbrl_status st = FBRL_ESTATE;
    if (r == NULL || r->vm == NULL)
        return FBRL_EINVAL;
    lock(r);
    if (when) {
        copy_text(r->req_who[slot], sizeof r->req_who[slot], who);
        fbrl_store_rel(flag, value);
        st = FBRL_OK;
    }
    unlock(r);
    return st;
}

fbrl_status fbrl_run_pause(fbrl_run *r, const char *who)
{
    if (r == NULL)
        return FBRL_EINVAL;
    return request(r, &r->req_pause, 1, WHO_PAUSE, who, fbrl_load_acq(&r->active_flag) != 0);
}

fbrl_status fbrl_run_resume(fbrl_run *r, const char *who)
{
    if (r == NULL)
        return FBRL_EINVAL;
    return request(r, &r->req_pause, 0, WHO_RESUME, who,
                   fbrl_load_acq(&r->active_flag) != 0 && fbrl_load_acq(&r->req_pause) != 0);
}

fbrl_status fbrl_run_answer(fbrl_run *r, fbrl_run_choice choice, const char *who)
{
    if (r == NULL || (choice != FBRL_RUN_RETRY && choice != FBRL_RUN_SKIP && choice != FBRL_RUN_STOP))
        return FBRL_EINVAL;
    return request(r, &r->req_answer, (size_t)choice, WHO_ANSWER, who, fbrl_load_acq(&r->asking) != 0);
}

fbrl_status fbrl_run_abort(fbrl_run *r, const char *who)
{
    fbrl_status st = FBRL_ESTATE;
    if (r == NULL || r->vm == NULL)
        return FBRL_EINVAL;
    lock(r);
    if (fbrl_load_rlx(&r->active_flag)) {
        if (!fbrl_load_rlx(&r->req_abort)) { /* asked twice: one abort, one interrupt */
            copy_text(r->req_who[WHO_ABORT], sizeof r->req_who[WHO_ABORT], who);
            fbrl_store_rel(&r->req_abort, 1);
            fbrl_vm_interrupt(r->vm); /* the running word throws -28 */
        }
        st = FBRL_OK;
    }
    unlock(r);
    return st;
}

/* The engine takes an abort asked for: once, with the interrupt it made (already thrown,
 * or taken here so it does not hit the safe stop or ON-ABORT). 1 if the run is aborted. */
static int take_abort(fbrl_run *r)
{
    if (r->aborted)
        return 1;
    if (!fbrl_load_acq(&r->req_abort))
        return 0;
    lock(r);
    copy_text(r->abort_who, sizeof r->abort_who, r->req_who[WHO_ABORT]);
    fbrl_vmx_take_interrupt(r->vm);
    unlock(r);
    r->aborted = 1;
    return 1;
}

/* ---- samples ---- */

static void set_sample(fbrl_run *r, long i, fbrl_run_sample_outcome o, const char *reason)
{
    fbrl_run_sample *s = &r->work.s.outcomes[i];
    fbrl_run_event ev;
    if (s->outcome == FBRL_SAMPLE_PENDING)
        r->work.s.samples_done++;
    s->outcome = (uint8_t)o;
    copy_text(s->reason, sizeof s->reason, reason);
    publish(r);
    event(&ev, FBRL_RUN_EV_SAMPLE, r->work.s.step, i, s->reason);
    ev.outcome = (int)o;
    emit(r, &ev);
}

fbrl_status fbrl_run_mark(fbrl_run *r, long sample, fbrl_run_sample_outcome outcome, const char *reason)
{
    if (r == NULL || (outcome != FBRL_SAMPLE_FAILED && outcome != FBRL_SAMPLE_SKIPPED))
        return FBRL_EINVAL;
    if (!r->active)
        return FBRL_ESTATE;
    if (sample < 0 || sample >= r->work.s.samples)
        return FBRL_ERANGE;
    if (r->marked[sample]) /* the first mark stands; it replaces only a success no one marked */
        return FBRL_OK;
    r->marked[sample] = 1;
    set_sample(r, sample, outcome, reason && reason[0] ? reason : fbrl_run_sample_name(outcome));
    return FBRL_OK;
}

/* ---- the corrective actions' hooks (fbrl/recover.h) ---- */

static int run_ask(void *ctx, const char *question)
{
    fbrl_run *r = ctx;
    fbrl_run_event ev;
    size_t choice = 0;
    char who[FBRL_RUN_WHO_MAX + 1] = "";
    if (!r->active)
        return r->outer_ask ? r->outer_ask(r->outer_ask_ctx, question) : 'A';
    r->work.s.question = ++r->questions;
    copy_text(r->work.s.question_text, sizeof r->work.s.question_text, question);
    lock(r);
    fbrl_store_rlx(&r->req_answer, 0);
    fbrl_store_rel(&r->asking, 1);
    unlock(r);
    publish(r);
    event(&ev, FBRL_RUN_EV_QUESTION, r->work.s.step, r->work.s.sample, r->work.s.question_text);
    emit(r, &ev);
    while (!fbrl_load_acq(&r->req_answer) && !fbrl_load_acq(&r->req_abort) && !fbrl_vm_interrupt_pending(r->vm))
        wait_once(r);
    lock(r);
    choice = fbrl_load_rlx(&r->req_answer);
    copy_text(who, sizeof who, r->req_who[WHO_ANSWER]);
    fbrl_store_rlx(&r->asking, 0);
    fbrl_store_rlx(&r->req_answer, 0);
    unlock(r);
    r->work.s.question = 0;
    r->work.s.question_text[0] = '\0';
    publish(r);
    if (choice == 0) { /* aborted, or interrupted from outside (fbrlmon's Ctrl-C), while it asked */
        if (!take_abort(r))
            r->interrupted = 1;
        return 'A';
    }
    event(&ev, FBRL_RUN_EV_ANSWER, r->work.s.step, r->work.s.sample, NULL);
    ev.choice = (int)choice;
    ev.who = who;
    emit(r, &ev);
    if (choice == FBRL_RUN_STOP) { /* the operator's abort: the safe place after the stop */
        r->aborted = 1;
        copy_text(r->abort_who, sizeof r->abort_who, who);
    }
    return choice == FBRL_RUN_RETRY ? 'R' : choice == FBRL_RUN_SKIP ? 'S' : 'A';
}

static void run_note(void *ctx, const char *step, const char *kind, const char *what, const char *action,
                     long sample)
{
    fbrl_run *r = ctx;
    if (r->active) {
        fbrl_run_event ev;
        event(&ev, FBRL_RUN_EV_RECOVERY, r->work.s.step, r->work.s.sample, what);
        ev.where = step;
        ev.kind_name = kind;
        ev.action = action;
        emit(r, &ev);
        if (r->work.s.sample >= 0) /* the run's own sample number, not RUN-SAMPLE's count */
            sample = r->work.s.sample + 1;
    }
    if (r->outer_note)
        r->outer_note(r->outer_note_ctx, step, kind, what, action, sample);
}

static void run_skip(void *ctx, const char *reason)
{
    fbrl_run *r = ctx;
    if (r->active && r->work.s.sample >= 0)
        fbrl_run_mark(r, r->work.s.sample, FBRL_SAMPLE_SKIPPED, reason);
}

/* ---- the run (engine thread) ---- */

static void begin(fbrl_run *r, const fbrl_method *m, long samples)
{
    fbrl_run_published *w = &r->work;
    unsigned long version = w->s.version;
    memset(w, 0, sizeof *w);
    w->s.version = version;
    w->s.state = FBRL_RUN_RUNNING;
    copy_text(w->s.method, sizeof w->s.method, m->name);
    w->s.nsteps = (long)m->nsteps;
    w->s.step = -1;
    w->s.sample = -1;
    w->s.samples = samples;
    if (strcmp(r->meas_method, m->name) != 0) { /* what was measured of another method does not count */
        memset(r->meas_ms, 0, sizeof r->meas_ms);
        copy_text(r->meas_method, sizeof r->meas_method, m->name);
    }
    r->last_sample_step = -1;
    for (size_t k = 0; k < m->nsteps; k++) {
        copy_text(w->s.step_name[k], sizeof w->s.step_name[k], m->steps[k].name);
        w->s.per_sample[k] = (uint8_t)(m->steps[k].per_sample != 0);
        w->s.step_runs[k] = m->steps[k].per_sample ? samples : 1;
        w->est_ms[k] = strcmp(r->pred_method, m->name) == 0 && r->pred_ms[k] > 0 ? r->pred_ms[k] : r->meas_ms[k];
        if (m->steps[k].per_sample)
            r->last_sample_step = (int)k;
    }
    memset(r->marked, 0, sizeof r->marked);
    w->t0_us = now_us(r);
    r->m = m;
    r->aborted = r->interrupted = 0;
    r->questions = 0;
    r->abort_who[0] = '\0';
    lock(r);
    fbrl_store_rlx(&r->req_pause, 0);
    fbrl_store_rlx(&r->req_abort, 0);
    fbrl_store_rlx(&r->req_answer, 0);
    fbrl_store_rel(&r->active_flag, 1);
    unlock(r);
    r->active = 1;
    if (r->rc)
        r->rc->sample = 0; /* RUN-SAMPLE counts this run's samples */
}

/* Before each run of a step: an abort asked for ends the run (1); a pause waits here. */
static int between(fbrl_run *r, long step, long sample)
{
    fbrl_run_event ev;
    char who[FBRL_RUN_WHO_MAX + 1];
    if (take_abort(r))
        return 1;
    if (!fbrl_load_acq(&r->req_pause))
        return 0;
    lock(r);
    copy_text(who, sizeof who, r->req_who[WHO_PAUSE]);
    unlock(r);
    r->work.s.state = FBRL_RUN_PAUSED;
    r->work.s.step = step;
    r->work.s.sample = sample;
    copy_text(r->work.s.who, sizeof r->work.s.who, who);
    publish(r);
    event(&ev, FBRL_RUN_EV_PAUSE, step, sample, NULL);
    ev.who = who;
    emit(r, &ev);
    while (fbrl_load_acq(&r->req_pause) && !fbrl_load_acq(&r->req_abort) && !fbrl_vm_interrupt_pending(r->vm))
        wait_once(r);
    if (take_abort(r))
        return 1;
    if (fbrl_vm_interrupt_pending(r->vm)) { /* interrupted from outside while paused: no resume */
        r->interrupted = 1;
        return 1;
    }
    lock(r);
    copy_text(who, sizeof who, r->req_who[WHO_RESUME]);
    unlock(r);
    r->work.s.state = FBRL_RUN_RUNNING;
    r->work.s.who[0] = '\0';
    publish(r);
    event(&ev, FBRL_RUN_EV_RESUME, step, sample, NULL);
    ev.who = who;
    emit(r, &ev);
    return 0;
}

/* One run of step k (sample, or -1): 0 when it ended well, else its THROW code with why. */
static int run_step(fbrl_run *r, size_t k, long sample, char *why, size_t cap)
{
    const fbrl_method *m = r->m;
    fbrl_run_event ev;
    char text[64];
    int code = 0;
    uint64_t t0 = now_us(r);
    r->work.s.step = (long)k;
    r->work.s.sample = sample;
    r->work.step_t0_us = t0;
    publish(r);
    event(&ev, FBRL_RUN_EV_STEP_BEGIN, (long)k, sample, NULL);
    emit(r, &ev);
    /* EXECUTE under a catch, to have the step's own message (the arguments are in the
     * text, decimal whatever BASE is) */
    if (sample >= 0)
        snprintf(text, sizeof text, "#%ld #%ld EXECUTE", sample, (long)m->steps[k].xt);
    else
        snprintf(text, sizeof text, "#%ld EXECUTE", (long)m->steps[k].xt);
    why[0] = '\0';
    fbrl_status st = fbrl_vmx_evaluate_catch(r->vm, text, strlen(text), &code, why, cap);
    if (st != FBRL_OK) { /* not a THROW: the engine itself (BYE, QUIT) */
        snprintf(why, cap, "%s", fbrl_status_str(st));
        code = FBRL_VM_THROW_OF_STATUS(st);
    }
    r->work.ended[k]++;
    if (code == 0) {
        r->work.s.step_done[k]++;
        r->meas_ms[k] = (double)(now_us(r) - t0) / 1000.0;
        if (r->work.est_ms[k] <= 0 || strcmp(r->pred_method, m->name) != 0)
            r->work.est_ms[k] = r->meas_ms[k];
    } else if (code != FBRL_RECOVER_THROW_SKIP || sample < 0) {
        r->work.s.step_failed[k] = 1;
        copy_text(r->work.s.error, sizeof r->work.s.error, why);
    }
    publish(r);
    event(&ev, FBRL_RUN_EV_STEP_END, (long)k, sample, code ? why : NULL);
    emit(r, &ev);
    if (code == FBRL_RECOVER_THROW_SKIP && sample >= 0) { /* given up, not failed: the next sample */
        fbrl_run_mark(r, sample, FBRL_SAMPLE_SKIPPED, why);
        return 0;
    }
    if (code == 0 && sample >= 0 && (int)k == r->last_sample_step &&
        r->work.s.outcomes[sample].outcome == FBRL_SAMPLE_PENDING)
        set_sample(r, sample, FBRL_SAMPLE_SUCCEEDED, "");
    return code;
}

/* The safe stop after an abort or a failure: halt, outputs off (fbrl_robot_safe_stop). */
static void safe_stop(fbrl_run *r)
{
    fbrl_robot_stop stop;
    fbrl_run_event ev;
    char text[160];
    if (r->robot == NULL)
        return;
    memset(&stop, 0, sizeof stop);
    fbrl_robot_safe_stop(r->robot, &stop);
    if (stop.result == FBRL_OK)
        snprintf(text, sizeof text, "arm halted, outputs switched off");
    else
        snprintf(text, sizeof text, "incomplete: %s", fbrl_status_str(stop.result));
    event(&ev, FBRL_RUN_EV_SAFE_STOP, r->work.s.step, r->work.s.sample, text);
    ev.status = stop.result;
    emit(r, &ev);
}

static void on_abort(fbrl_run *r)
{
    fbrl_run_event ev;
    char text[48], msg[FBRL_RUN_TEXT_MAX + 1] = "";
    int code = 0;
    if (r->m->abort_xt == 0)
        return;
    snprintf(text, sizeof text, "#%ld EXECUTE", (long)r->m->abort_xt);
    fbrl_status st = fbrl_vmx_evaluate_catch(r->vm, text, strlen(text), &code, msg, sizeof msg);
    if (st != FBRL_OK)
        snprintf(msg, sizeof msg, "%s", fbrl_status_str(st));
    event(&ev, FBRL_RUN_EV_ON_ABORT, r->work.s.step, r->work.s.sample, st != FBRL_OK || code ? msg : NULL);
    emit(r, &ev);
}

/* Every sample still without an outcome gets one, then the run its outcome. */
static fbrl_run_outcome settle(fbrl_run *r, int code, int reached_end, const char *why)
{
    fbrl_run_snap *s = &r->work.s;
    char reason[FBRL_RUN_REASON_MAX + 1];
    long ok = 0;
    const char *step = s->step >= 0 ? s->step_name[s->step] : "";
    for (long i = 0; i < s->samples; i++) {
        if (s->outcomes[i].outcome != FBRL_SAMPLE_PENDING)
            continue;
        if (reached_end) {
            set_sample(r, i, FBRL_SAMPLE_SUCCEEDED, "");
            continue;
        }
        if (i == s->sample && s->step >= 0 && s->per_sample[s->step]) { /* the sample it worked on */
            if (r->aborted)
                snprintf(reason, sizeof reason, "aborted during %s", step);
            else
                snprintf(reason, sizeof reason, "%.31s: %.62s", step, why); /* cut: what fits */
            set_sample(r, i, FBRL_SAMPLE_FAILED, reason);
        } else {
            snprintf(reason, sizeof reason, "not done: the run %s at %s", r->aborted ? "was aborted" : "stopped",
                     step);
            set_sample(r, i, FBRL_SAMPLE_SKIPPED, reason);
        }
    }
    for (long i = 0; i < s->samples; i++)
        ok += s->outcomes[i].outcome == FBRL_SAMPLE_SUCCEEDED;
    if (r->aborted || r->interrupted || code == FBRL_THROW_INTERRUPT)
        return FBRL_RUN_ABORTED;
    if (reached_end && ok == s->samples)
        return FBRL_RUN_COMPLETED;
    return ok == 0 ? FBRL_RUN_FAILED : FBRL_RUN_PARTIAL;
}

/* The end of a run: the safe stop, ON-ABORT, the outcomes, the last snapshot. */
static fbrl_run_outcome finish(fbrl_run *r, int code, int reached_end, const char *why)
{
    fbrl_run_event ev;
    int asked = take_abort(r), external = code == FBRL_THROW_INTERRUPT && !asked;
    if (r->aborted) {
        fbrl_run_event ab;
        event(&ab, FBRL_RUN_EV_ABORT, r->work.s.step, r->work.s.sample, NULL);
        ab.who = r->abort_who;
        r->work.s.state = FBRL_RUN_ABORTING;
        copy_text(r->work.s.who, sizeof r->work.s.who, r->abort_who);
        publish(r);
        emit(r, &ab);
    }
    /* the safe stop: not after a corrective action's STOP (it made one), nor after an
     * interrupt from outside the run (whoever interrupted stops the cell: fbrlmon's Ctrl-C) */
    if (!reached_end && code != FBRL_RECOVER_THROW_STOPPED && !external)
        safe_stop(r);
    if (r->aborted)
        on_abort(r);
    fbrl_run_outcome o = settle(r, code, reached_end, why);
    if (!reached_end && !r->work.s.error[0])
        copy_text(r->work.s.error, sizeof r->work.s.error, why);
    lock(r); /* from here no request reaches this run, and no stray interrupt the next thing */
    fbrl_store_rel(&r->active_flag, 0);
    fbrl_store_rlx(&r->req_pause, 0);
    fbrl_store_rlx(&r->asking, 0);
    if (fbrl_load_rlx(&r->req_abort))
        fbrl_vmx_take_interrupt(r->vm);
    fbrl_store_rlx(&r->req_abort, 0);
    unlock(r);
    r->active = 0;
    r->methods->running = NULL;
    r->work.s.state = FBRL_RUN_FINISHED;
    r->work.s.outcome = (int)o;
    r->work.s.question = 0;
    if (!r->aborted)
        r->work.s.who[0] = '\0';
    r->work.end_us = now_us(r);
    publish(r);
    event(&ev, FBRL_RUN_EV_END, r->work.s.step, -1, reached_end ? NULL : why);
    ev.outcome = (int)o;
    emit(r, &ev);
    return o;
}

static fbrl_status run_method(fbrl_run *r, const fbrl_method *m)
{
    fbrl_vm *vm = r->vm;
    fbrl_run_event ev;
    char why[FBRL_RUN_TEXT_MAX + 1] = "";
    long samples = 0;
    int code = 0, reached_end = 1;
    if (!m->complete)
        return fbrl_vmx_throwf(vm, FBRL_THROW_BAD_NAME_ARG, "RUN-METHOD: %s is not complete (END-METHOD missing)",
                               m->name);
    if (r->active)
        return fbrl_vmx_throwf(vm, FBRL_THROW_BAD_NAME_ARG, "RUN-METHOD: %s is running already", r->m->name);
    if (m->samples >= 0 && fbrl_method_param_get(r->methods, m, (size_t)m->samples, &samples) != FBRL_OK)
        samples = 0;
    if (samples < 0 || samples > FBRL_RUN_MAX_SAMPLES)
        return fbrl_vmx_throwf(vm, FBRL_THROW_BAD_NUMBER, "RUN-METHOD: %s: %ld samples (a run has at most %d)",
                               m->name, samples, FBRL_RUN_MAX_SAMPLES);
    begin(r, m, samples);
    r->methods->running = m;
    publish(r);
    event(&ev, FBRL_RUN_EV_BEGIN, -1, -1, NULL);
    if (emit(r, &ev)) { /* refused: as if it never began */
        lock(r);
        fbrl_store_rel(&r->active_flag, 0);
        unlock(r);
        r->active = 0;
        r->methods->running = NULL;
        r->work.s.state = FBRL_RUN_FINISHED;
        r->work.s.outcome = FBRL_RUN_NONE;
        r->work.end_us = r->work.t0_us;
        publish(r);
        return fbrl_vmx_throwf(vm, FBRL_THROW_FILE_IO, "RUN-METHOD: %s: the run could not start (its run log?)",
                               m->name);
    }
    r->began = 1;
    for (size_t k = 0; k < m->nsteps && reached_end; k++) {
        long runs = m->steps[k].per_sample ? samples : 1;
        for (long i = 0; i < runs && reached_end; i++) {
            long sample = m->steps[k].per_sample ? i : -1;
            if (between(r, (long)k, sample)) {
                snprintf(why, sizeof why, "RUN-METHOD: %s aborted by the operator", m->name);
                code = FBRL_THROW_INTERRUPT;
                reached_end = 0;
            } else if ((code = run_step(r, k, sample, why, sizeof why)) != 0) {
                reached_end = 0;
            }
        }
    }
    finish(r, code, reached_end, why);
    return reached_end ? FBRL_OK : fbrl_vm_throw(vm, code, why);
}

/* ---- the words ---- */

/* RUN-METHOD ( method -- ) */
static fbrl_status w_run_method(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_run *r = ctx;
    fbrl_vmx_val v[1];
    fbrl_status st = fbrl_vmx_check(vm, word, v);
    if (st != FBRL_OK)
        return st;
    for (size_t i = 0; i < r->methods->count; i++)
        if (r->methods->methods[i].addr == v[0].i)
            return run_method(r, &r->methods->methods[i]);
    return fbrl_vmx_throwf(vm, FBRL_THROW_TYPE_MISMATCH, "RUN-METHOD: not a method");
}

/* The sample word's parameters (its row's spec: the sample first), in a running method. */
static fbrl_status sample_arg(fbrl_run *r, const void *row, fbrl_vmx_val *v)
{
    const char *word = ((const fbrl_vmx_reg *)row)->name;
    fbrl_status st = fbrl_vmx_check(r->vm, row, v);
    if (st != FBRL_OK)
        return st;
    if (!r->active)
        return fbrl_vmx_throwf(r->vm, FBRL_THROW_BAD_NAME_ARG, "%s: no method is running", word);
    if (v[0].i < 0 || v[0].i >= r->work.s.samples)
        return fbrl_vmx_throwf(r->vm, FBRL_THROW_BAD_NUMBER, "%s: sample %ld: this run of %s has %ld (0..)", word,
                               (long)v[0].i, r->m->name, r->work.s.samples);
    return FBRL_OK;
}

/* SAMPLE-FAILED / SAMPLE-SKIPPED ( n c-addr u -- ) */
static fbrl_status w_sample_mark(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_run *r = ctx;
    int skipped = ((const fbrl_vmx_reg *)word)->arg != 0;
    char reason[FBRL_RUN_REASON_MAX + 1];
    fbrl_vmx_val v[2];
    (void)vm;
    fbrl_status st = sample_arg(r, word, v);
    if (st != FBRL_OK)
        return st;
    snprintf(reason, sizeof reason, "%.*s", (int)(v[1].n < sizeof reason ? v[1].n : sizeof reason - 1), v[1].s);
    return fbrl_run_mark(r, (long)v[0].i, skipped ? FBRL_SAMPLE_SKIPPED : FBRL_SAMPLE_FAILED, reason);
}

/* SAMPLE-OK? ( n -- flag ) */
static fbrl_status w_sample_ok(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_run *r = ctx;
    fbrl_vmx_val v[1];
    fbrl_status st = sample_arg(r, word, v);
    if (st != FBRL_OK)
        return st;
    uint8_t o = r->work.s.outcomes[v[0].i].outcome;
    return fbrl_vmx_push(vm, o == FBRL_SAMPLE_PENDING || o == FBRL_SAMPLE_SUCCEEDED ? -1 : 0);
}

/* The rows (vmx.h): arg 1 is SAMPLE-SKIPPED. */
static const fbrl_vmx_reg words[] = {
    {"RUN-METHOD", w_run_method, "A", FBRL_VMX_PARSE, 0, 0,
     FBRL_DOC("( method -- )", "run the method's steps in order: outcomes per sample and per run (console, run log)")},
    {"SAMPLE-FAILED", w_sample_mark, "IS", 0, 0, 0,
     FBRL_DOC("( n c-addr u -- )", "in a running method: sample n (0..) failed, for the reason given")},
    {"SAMPLE-SKIPPED", w_sample_mark, "IS", 0, 0, 1,
     FBRL_DOC("( n c-addr u -- )", "in a running method: sample n (0..) is not done, for the reason given")},
    {"SAMPLE-OK?", w_sample_ok, "I", 0, 0, 0,
     FBRL_DOC("( n -- flag )", "in a running method: true unless sample n (0..) failed or was skipped")},
};

fbrl_status fbrl_run_install(fbrl_run *r, fbrl_vm *vm, fbrl_method_set *methods, fbrl_recover *rc,
                             fbrl_robot *robot)
{
    if (r == NULL || vm == NULL || methods == NULL)
        return FBRL_EINVAL;
    memset(r, 0, sizeof *r);
    r->vm = vm;
    r->methods = methods;
    r->rc = rc;
    r->robot = robot;
    r->work.s.step = -1;
    r->work.s.sample = -1;
    fbrl_status st = fbrl_vmx_define_table(vm, words, sizeof words / sizeof words[0], r);
    if (st == FBRL_OK)
        st = fbrl_vmx_find(vm, "RUN-METHOD", 10, &r->run_xt);
    if (st != FBRL_OK)
        return st;
    if (rc != NULL) {
        r->outer_ask = rc->ask;
        r->outer_ask_ctx = rc->ask_ctx;
        r->outer_note = rc->note;
        r->outer_note_ctx = rc->note_ctx;
        fbrl_recover_set_ask(rc, run_ask, r);
        fbrl_recover_set_note(rc, run_note, r);
        fbrl_recover_set_skip(rc, run_skip, r);
    }
    publish(r);
    return FBRL_OK;
}

fbrl_status fbrl_run_start(fbrl_run *r, const char *method, const long *values, size_t n, size_t *bad)
{
    const fbrl_method *m;
    char text[64];
    if (r == NULL || r->vm == NULL || method == NULL || (values == NULL && n != 0))
        return FBRL_EINVAL;
    m = fbrl_method_find(r->methods, method);
    if (m == NULL)
        return FBRL_ENOENT;
    if (!m->complete || r->active)
        return FBRL_ESTATE;
    if (values != NULL) {
        if (n != m->nparams)
            return FBRL_EINVAL;
        for (size_t k = 0; k < n; k++) /* all checked before any is set */
            if (values[k] < m->params[k].min || values[k] > m->params[k].max) {
                if (bad)
                    *bad = k;
                return FBRL_ERANGE;
            }
        for (size_t k = 0; k < n; k++) {
            fbrl_status st = fbrl_method_param_set(r->methods, m, k, values[k]);
            if (st != FBRL_OK)
                return st;
        }
    }
    r->began = 0;
    snprintf(text, sizeof text, "#%ld #%ld EXECUTE", (long)m->addr, (long)r->run_xt);
    fbrl_status st = fbrl_vm_eval(r->vm, text, strlen(text));
    return r->began ? FBRL_OK : st;
}

fbrl_status fbrl_run_predict(fbrl_run *r, const char *method, const double *ms, size_t n)
{
    if (r == NULL || method == NULL || (ms == NULL && n != 0) || n > FBRL_METHOD_MAX_STEPS)
        return FBRL_EINVAL;
    if (r->active)
        return FBRL_ESTATE;
    memset(r->pred_ms, 0, sizeof r->pred_ms);
    for (size_t k = 0; k < n; k++)
        r->pred_ms[k] = ms[k] > 0 ? ms[k] : 0;
    copy_text(r->pred_method, sizeof r->pred_method, method);
    return FBRL_OK;
}
