/* SPDX-License-Identifier: MIT */
/* task.c - cooperative tasks: several procedures at once (docs/tasks.md).
 *
 * The main task is whatever fbrl_vm_eval() runs, on the caller's C stack. Every other
 * task runs in slices: fbrl__run() from the task's saved ip, with its own data, return
 * and float stacks (allotted in data space by TASK), until a waiting word yields or the
 * task's word ends. A waiting word in a background task returns THROW_YIELD (through
 * fbrl_vmx_pause); run.c then ends the slice, keeping the word to run again, so no task
 * needs a C stack of its own. A waiting word in the main task (or deeper inside a C word
 * of a background task) waits in place instead, running the other tasks' slices
 * meanwhile and sleeping until the next one is due. With no background task, every wait
 * behaves as it always did. Tasks also own the clock of their timed steps (AT EVERY
 * DEADLINE LATENESS) and claims on shared things (the arm, devices: CLAIM RELEASE). */
#include <stdio.h>
#include <string.h>
#include "atomic.h"
#include "fbrl/num.h"
#include "words.h"

#define TASK_DS           64 /* cells of each task's stacks */
#define TASK_RS           64
#define TASK_FS           16
#define US_PER_MS         1000u
#define TASK_SPARE        16        /* bytes below the data and float stacks (run.c's cached top) */
#define TASK_MAX_MS       86400000L /* the longest timed step: one day */
#define SLEEP_MAX_MS      1000u /* the longest sleep before the wait looks again (Ctrl-C, a task) */
#define NO_WAKE           FBRL_TASK_NEVER
#define TASK_MEM                                                                           \
    (TASK_SPARE + TASK_DS * sizeof(fbrl_cell) + TASK_RS * sizeof(fbrl_cell) + TASK_SPARE + \
     TASK_FS * sizeof(double))

static const char *const state_names[] = {"free",    "made", "ready",  "waiting",
                                          "running", "done", "failed", "stopped"};

static uint64_t now_us(fbrl_vm *vm) { return vm->host.now_us ? vm->host.now_us(vm->host.user) : 0; }

static fbrl_status tk_throw(fbrl_vm *vm, int code, const char *msg)
{
    vm->pending_throw = code;
    if (msg)
        fbrl__throw_msg(vm, code, msg);
    return FBRL_ETHROW;
}

static fbrl_status tk_pop(fbrl_vm *vm, fbrl_cell *v)
{
    if (vm->sp <= vm->ds0)
        return tk_throw(vm, FBRL_THROW_STACK_UNDERFLOW, NULL);
    *v = *--vm->sp;
    return FBRL_OK;
}

static fbrl_status tk_push(fbrl_vm *vm, fbrl_cell v)
{
    if (vm->sp >= vm->ds_end)
        return tk_throw(vm, FBRL_THROW_STACK_OVERFLOW, NULL);
    *vm->sp++ = v;
    return FBRL_OK;
}

static const char *task_name(const fbrl_vm *vm, int i)
{
    if (i == 0)
        return "MAIN";
    const fbrl_task *t = &vm->tasks[i];
    return t->word && t->word - 1 < vm->nwords ? HDR(vm, t->word - 1)->name : "?";
}

static void say(fbrl_vm *vm, const char *s) { fbrl__write(vm, s, strlen(s)); }

/* ---- switching stacks ---- */
static void ctx_save(fbrl_vm *vm, fbrl_task *t)
{
    t->ds0 = vm->ds0, t->ds_end = vm->ds_end, t->sp = vm->sp;
    t->rs0 = vm->rs0, t->rs_end = vm->rs_end, t->rp = vm->rp;
    t->fs0 = vm->fs0, t->fs_end = vm->fs_end, t->fp = vm->fp;
    t->handler = vm->handler;
}

static void ctx_load(fbrl_vm *vm, const fbrl_task *t)
{
    vm->ds0 = t->ds0, vm->ds_end = t->ds_end, vm->sp = t->sp;
    vm->rs0 = t->rs0, vm->rs_end = t->rs_end, vm->rp = t->rp;
    vm->fs0 = t->fs0, vm->fs_end = t->fs_end, vm->fp = t->fp;
    vm->handler = t->handler;
}

/* ---- claims ---- */
static fbrl_claim *claim_of(fbrl_vm *vm, fbrl_cell key, int make)
{
    fbrl_claim *free_c = NULL;
    for (int k = 0; k < FBRL_CLAIMS_MAX; k++) {
        fbrl_claim *c = &vm->claims[k];
        if (c->key == key && key)
            return c;
        if (!c->key && !free_c)
            free_c = c;
    }
    if (!make || !free_c)
        return NULL;
    memset(free_c, 0, sizeof *free_c);
    free_c->key = key;
    free_c->owner = -1;
    return free_c;
}

static void claim_tidy(fbrl_claim *c)
{
    if (c->owner < 0 && c->nq == 0)
        c->key = 0;
}

static void unqueue(fbrl_claim *c, int i)
{
    int n = 0;
    for (int k = 0; k < c->nq; k++)
        if (c->queue[k] != i)
            c->queue[n++] = c->queue[k];
    c->nq = n;
}

static void claim_name(const fbrl_vm *vm, fbrl_cell key, char *buf, size_t cap)
{
    if (key == FBRL_VMX_ARM)
        snprintf(buf, cap, "the arm");
    else {
        int found = 0;
        for (uint32_t k = 0; k < vm->nwords && !found; k++) { /* a named device: its word's name */
            const fbrl_hdr *h = HDR(vm, k);
            if (h->body == key && !(h->flags & FH) && h->len)
                found = snprintf(buf, cap, "%s", h->name) > 0;
        }
        if (!found)
            snprintf(buf, cap, "%ld", (long)key);
    }
}

/* A task ends (done, failed, stopped): what it held is free again; after a failure the
 * others are told on the console. */
static void release_all(fbrl_vm *vm, int i, int failed)
{
    for (int k = 0; k < FBRL_CLAIMS_MAX; k++) {
        fbrl_claim *c = &vm->claims[k];
        if (!c->key)
            continue;
        unqueue(c, i);
        if (c->owner == i) {
            c->owner = -1;
            c->depth = 0;
            if (failed) {
                char line[160], what[40];
                claim_name(vm, c->key, what, sizeof what);
                snprintf(line, sizeof line, "task %s: released %s (it failed holding it)\n", task_name(vm, i),
                         what);
                say(vm, line);
            }
        }
        claim_tidy(c);
    }
}

/* A task ended or released a claim: the tasks that wait for another task (AWAIT, CLAIM)
 * look again at once; nothing else wakes them, so they cost nothing while they wait. */
static void signal_tasks(fbrl_vm *vm)
{
    vm->task_signals++;
    for (int i = 1; i < FBRL_TASKS_MAX; i++) {
        fbrl_task *t = &vm->tasks[i];
        if (t->state == TK_WAIT && t->on_signal)
            t->wake_us = 0, t->on_signal = 0;
    }
}

static void end_task(fbrl_vm *vm, int i, int state)
{
    fbrl_task *t = &vm->tasks[i];
    int was_live = t->state == TK_READY || t->state == TK_WAIT || t->state == TK_RUN;
    t->state = state;
    if (was_live && vm->ntasks > 0)
        vm->ntasks--;
    release_all(vm, i, state == TK_FAILED);
    signal_tasks(vm);
}

static void slice(fbrl_vm *vm, int i);

/* End task i; 1 if it was live. tidy: a task waiting inside a word (a PULSE with its output
 * on) runs once more, its stop asked: the wait says "stopped" and the word tidies up (the
 * output off) before the task ends at that wait, or at its next. Ctrl-C (not tidy) ends it
 * at once: the host's safe stop makes the cell safe. */
static int stop_task(fbrl_vm *vm, int i, int tidy)
{
    fbrl_task *t = &vm->tasks[i];
    if (t->state == TK_WAIT && t->resuming && tidy) {
        t->stop_req = 1;
        slice(vm, i);
        if (t->state == TK_READY || t->state == TK_WAIT)
            end_task(vm, i, TK_STOPPED);
        return 1;
    }
    if (t->state == TK_READY || t->state == TK_WAIT) {
        end_task(vm, i, TK_STOPPED);
        return 1;
    }
    if (t->state == TK_RUN) /* waiting in place under the running task: it ends when it gets back */
        t->stop_req = 1;
    return t->state == TK_RUN;
}

static void stop_all(fbrl_vm *vm, const char *why)
{
    int n = 0;
    for (int i = 1; i < FBRL_TASKS_MAX; i++)
        n += stop_task(vm, i, why == NULL);
    if (n && why) {
        char line[96];
        snprintf(line, sizeof line, "tasks stopped (%s)\n", why);
        say(vm, line);
    }
}

/* ---- running a slice ---- */
typedef struct err_keep {
    int err_captured, pending_throw, pending_code;
    const char *pending_msg;
    char throw_msg[sizeof((fbrl_vm *)0)->throw_msg];
    char cur_word[sizeof((fbrl_vm *)0)->cur_word];
} err_keep;

static void slice(fbrl_vm *vm, int i)
{
    fbrl_task *t = &vm->tasks[i], *cur = &vm->tasks[vm->cur_task];
    int prev = vm->cur_task, prev_slice = vm->slice_nest;
    err_keep k;
    k.err_captured = vm->err_captured, k.pending_throw = vm->pending_throw, k.pending_code = vm->pending_code;
    k.pending_msg = vm->pending_msg;
    memcpy(k.throw_msg, vm->throw_msg, sizeof k.throw_msg);
    memcpy(k.cur_word, vm->cur_word, sizeof k.cur_word);

    ctx_save(vm, cur);
    ctx_load(vm, t);
    vm->cur_task = i;
    t->state = TK_RUN;
    vm->slice_nest = vm->nest + 1;
    vm->resume_ip = t->ip;
    vm->resuming = t->resuming;
    t->resuming = 0;
    t->on_signal = 0;
    vm->pending_msg = NULL;
    int code = fbrl__run(vm, t->w);
    ctx_save(vm, t);
    t->ip = vm->resume_at;
    t->w = vm->resume_w;
    vm->resume_ip = NULL;
    vm->resuming = 0;

    char line[200];
    if (code == THROW_YIELD && !t->stop_req) {
        t->state = TK_WAIT;
        t->resuming = 1;
    } else if (code == 0) {
        end_task(vm, i, TK_DONE);
    } else if (code == THROW_YIELD || code == THROW_STOP) {
        end_task(vm, i, TK_STOPPED);
    } else {
        const char *m =
            (vm->pending_msg && vm->pending_code == code) ? vm->pending_msg : fbrl__throw_text(code);
        t->code = code;
        snprintf(t->msg, sizeof t->msg, "%s%s%s", m, code == FBRL_THROW_UNDEFINED ? " " : "",
                 code == FBRL_THROW_UNDEFINED ? vm->cur_word : "");
        snprintf(line, sizeof line, "task %s: %s (THROW %d)\n", task_name(vm, i), t->msg, code);
        say(vm, line);
        end_task(vm, i, TK_FAILED);
        if (code == FBRL_THROW_INTERRUPT) { /* Ctrl-C stops every task, and the main program */
            stop_all(vm, "Ctrl-C");
            fbrl_store_rlx(&vm->interrupt, 1);
        }
    }
    t->stop_req = 0;
    ctx_load(vm, cur);
    vm->cur_task = prev;
    vm->slice_nest = prev_slice;
    vm->err_captured = k.err_captured, vm->pending_throw = k.pending_throw, vm->pending_code = k.pending_code;
    vm->pending_msg = k.pending_msg;
    memcpy(vm->throw_msg, k.throw_msg, sizeof k.throw_msg);
    memcpy(vm->cur_word, k.cur_word, sizeof k.cur_word);
}

/* A task whose stacks or word a MARKER took back never runs again. */
static int forgotten(const fbrl_vm *vm, const fbrl_task *t)
{
    return t->word - 1 >= vm->nwords || t->mem_lo + TASK_MEM > vm->here;
}

static int due(const fbrl_task *t, uint64_t now)
{
    return t->state == TK_READY || (t->state == TK_WAIT && now >= t->wake_us);
}

/* One round: each task that is due runs one slice, in turn. */
static void run_round(fbrl_vm *vm)
{
    uint64_t now = now_us(vm);
    for (int n = 1; n < FBRL_TASKS_MAX; n++) {
        int i = n; /* in slot order: each due task one slice a round */
        fbrl_task *t = &vm->tasks[i];
        if (i == 0 || !t->word)
            continue;
        if ((t->state == TK_READY || t->state == TK_WAIT) && forgotten(vm, t)) {
            end_task(vm, i, TK_STOPPED);
            t->word = 0;
            continue;
        }
        if (due(t, now)) {
            slice(vm, i);
            now = now_us(vm);
        }
    }
}

static uint64_t next_wake(const fbrl_vm *vm, uint64_t limit)
{
    for (int i = 1; i < FBRL_TASKS_MAX; i++) {
        const fbrl_task *t = &vm->tasks[i];
        if (t->state == TK_READY)
            return 0;
        if (t->state == TK_WAIT && t->wake_us < limit)
            limit = t->wake_us;
    }
    return limit;
}

/* Sleep until when (or SLEEP_MAX_MS, then the caller looks again): whole ms, rounded up,
 * so a wait never spins on the last part of a ms; it ends up to a ms late. */
static void sleep_until(fbrl_vm *vm, uint64_t when)
{
    uint64_t now = now_us(vm);
    if (when > now && vm->host.sleep_ms) {
        uint64_t ms = (when - now + US_PER_MS - 1) / US_PER_MS;
        vm->host.sleep_ms(vm->host.user, (uint32_t)(ms > SLEEP_MAX_MS ? SLEEP_MAX_MS : ms));
    }
}

/* The waits' one way of letting others run (vm->task_pause): 0 when wake_us has come (or,
 * on_signal, when another task ended or released a claim), THROW_YIELD for a background
 * task's slice to end, or a throw. */
static int task_pause(fbrl_vm *vm, uint64_t wake_us, int on_signal)
{
    fbrl_task *me = &vm->tasks[vm->cur_task];
    unsigned long seen = vm->task_signals;
    if (me->stop_req)
        return THROW_STOP;
    if (vm->cur_task != 0 && vm->slice_nest == vm->nest) {
        me->wake_us = wake_us;
        me->on_signal = on_signal;
        return THROW_YIELD;
    }
    for (;;) { /* in place: the main task, or a task waiting inside a C word */
        if (fbrl__take_interrupt(vm)) {
            stop_all(vm, "Ctrl-C");
            return FBRL_THROW_INTERRUPT;
        }
        run_round(vm);
        if (me->stop_req)
            return THROW_STOP;
        if (on_signal && vm->task_signals != seen)
            return 0;
        uint64_t now = now_us(vm);
        if (now >= wake_us || !vm->host.now_us)
            return 0;
        sleep_until(vm, next_wake(vm, wake_us));
    }
}

fbrl_status fbrl_vm_run_tasks(fbrl_vm *vm, uint64_t *wake_us, int *live)
{
    if (!vm || !wake_us)
        return FBRL_EINVAL;
    if (vm->running)
        return FBRL_ESTATE;
    if (fbrl__take_interrupt(vm))
        stop_all(vm, "Ctrl-C");
    vm->running = 1;
    for (int rounds = 0; rounds < FBRL_TASKS_MAX; rounds++) { /* until none is due now */
        run_round(vm);
        if (next_wake(vm, NO_WAKE) > now_us(vm))
            break;
    }
    vm->running = 0;
    *wake_us = vm->ntasks ? next_wake(vm, NO_WAKE) : NO_WAKE;
    if (live)
        *live = vm->ntasks;
    return FBRL_OK;
}

/* ---- the words ---- */
static fbrl_status task_arg(fbrl_vm *vm, fbrl_cell v, int *i)
{
    if (v < 1 || v >= FBRL_TASKS_MAX || !vm->tasks[v].word || forgotten(vm, &vm->tasks[v]))
        return tk_throw(vm, FBRL_THROW_BAD_NUMBER, "not a task (use a TASK name)");
    *i = (int)v;
    return FBRL_OK;
}

static fbrl_status need_clock(fbrl_vm *vm)
{
    return vm->host.now_us && vm->host.sleep_ms
               ? FBRL_OK
               : tk_throw(vm, FBRL_THROW_UNSUPPORTED, "no clock in this host");
}

/* The slot of the task "name" already names when it is not running (a file loaded again,
 * EDIT: its TASK lines make the same tasks again), or 0. The input is left as it was. */
static int same_task(fbrl_vm *vm)
{
    fbrl_cell in = *vm->toin, v;
    const char *name;
    size_t len;
    fbrl__parse_name(vm, &name, &len);
    int k = fbrl__find(vm, name, len);
    *vm->toin = in;
    if (k < 0 || HDR(vm, k)->kind != K_CONST || !fbrl__addr_ok(vm, HDR(vm, k)->body, sizeof v))
        return 0;
    memcpy(&v, (const void *)HDR(vm, k)->body, sizeof v);
    if (v < 1 || v >= FBRL_TASKS_MAX || vm->tasks[v].word != (uint32_t)k + 1)
        return 0;
    int s = vm->tasks[v].state;
    return s == TK_READY || s == TK_WAIT || s == TK_RUN ? 0 : (int)v;
}

/* TASK ( "name" -- ): a task with its own stacks; name ( -- task ). A name that already
 * is a task that is not running gets that task's slot (loading a file again leaks none). */
static fbrl_status w_task(fbrl_vm *vm, void *arg)
{
    (void)arg;
    int i, r;
    fbrl_hdr *h;
    if ((i = same_task(vm)) == 0)
        for (i = 1; i < FBRL_TASKS_MAX; i++) {
            fbrl_task *t = &vm->tasks[i];
            if (!t->word || ((t->state == TK_IDLE || t->state >= TK_DONE) && forgotten(vm, t)))
                break;
        }
    if (i == FBRL_TASKS_MAX)
        return tk_throw(vm, FBRL_THROW_UNSUPPORTED, "TASK: no room for another task (16 at most)");
    unsigned char *here0 = vm->here;
    uint32_t nwords0 = vm->nwords;
    if ((r = fbrl__create(vm, K_CONST, "( -- task )", "a task", &h)) || (r = fbrl__emit(vm, i)) ||
        (r = fbrl__align(vm)) || (r = fbrl__allot(vm, (fbrl_cell)(TASK_MEM + 16)))) {
        fbrl__forget(vm, here0, nwords0, vm->req_used);
        return tk_throw(vm, r, NULL);
    }
    fbrl_task *t = &vm->tasks[i];
    memset(t, 0, sizeof *t);
    t->word = nwords0 + 1;
    t->state = TK_IDLE;
    unsigned char *m = (unsigned char *)(((uintptr_t)vm->here - TASK_MEM) & ~(uintptr_t)15);
    t->mem_lo = m;
    t->ds0 = (fbrl_cell *)(void *)(m + TASK_SPARE);
    t->ds_end = t->ds0 + TASK_DS;
    t->rs0 = t->ds_end;
    t->rs_end = t->rs0 + TASK_RS;
    t->fs0 = (double *)(void *)((unsigned char *)t->rs_end + TASK_SPARE);
    t->fs_end = t->fs0 + TASK_FS;
    return FBRL_OK;
}

/* START-WITH ( x1..xn n xt task -- ) and START ( xt task -- ) */
static fbrl_status start(fbrl_vm *vm, int with)
{
    fbrl_cell tv, xt, n = 0;
    int i;
    fbrl_status st;
    if ((st = need_clock(vm)) || (st = tk_pop(vm, &tv)) || (st = task_arg(vm, tv, &i)) ||
        (st = tk_pop(vm, &xt)))
        return st;
    if (with && (st = tk_pop(vm, &n)))
        return st;
    fbrl_task *t = &vm->tasks[i];
    if (n < 0 || n > TASK_DS / 2 || n > vm->sp - vm->ds0)
        return tk_throw(vm, FBRL_THROW_BAD_NUMBER, "START-WITH: 0..32 cells, all on the stack");
    if (t->state == TK_READY || t->state == TK_WAIT || t->state == TK_RUN)
        return tk_throw(vm, FBRL_THROW_UNSUPPORTED, "START: that task is running (STOP it first)");
    if (!fbrl__xt_hdr(vm, xt))
        return tk_throw(vm, FBRL_THROW_UNDEFINED, "START: not an execution token");
    t->sp = t->ds0;
    memcpy(t->sp, vm->sp - n, (size_t)n * sizeof(fbrl_cell));
    t->sp += n;
    vm->sp -= n;
    t->rp = t->rs0;
    t->fp = t->fs0;
    t->handler = 0;
    t->ip = (const fbrl_cell *)vm->guard_addr; /* HALT: where the word returns to */
    t->w = xt;
    t->resuming = t->stop_req = 0;
    t->origin_us = t->every_due_us = now_us(vm);
    t->steps = t->missed = 0;
    t->late_max_us = t->late_sum_us = 0;
    t->code = 0;
    t->msg[0] = 0;
    memset(&t->timer, 0, sizeof t->timer);
    t->state = TK_READY;
    vm->ntasks++;
    return FBRL_OK;
}
static fbrl_status w_start(fbrl_vm *vm, void *arg) { return start(vm, arg != NULL); }

/* STOP ( task -- ) */
static fbrl_status w_stop(fbrl_vm *vm, void *arg)
{
    (void)arg;
    fbrl_cell v;
    int i;
    fbrl_status st;
    if ((st = tk_pop(vm, &v)) || (st = task_arg(vm, v, &i)))
        return st;
    if (i == vm->cur_task)
        return tk_throw(vm, THROW_STOP, NULL);
    stop_task(vm, i, 1);
    return FBRL_OK;
}

static fbrl_status w_stop_tasks(fbrl_vm *vm, void *arg)
{
    (void)arg;
    stop_all(vm, NULL);
    return vm->cur_task ? tk_throw(vm, THROW_STOP, NULL) : FBRL_OK;
}

/* PAUSE ( -- ) */
static fbrl_status w_pause(fbrl_vm *vm, void *arg)
{
    (void)arg;
    if (!vm->ntasks)
        return FBRL_OK;
    if (fbrl__wait_begin(vm)->resumed)
        return FBRL_OK;
    int code = task_pause(vm, now_us(vm), 0);
    return code ? tk_throw(vm, code, NULL) : FBRL_OK;
}

static fbrl_status w_me(fbrl_vm *vm, void *arg)
{
    (void)arg;
    return tk_push(vm, vm->cur_task);
}

/* AWAIT ( task -- ): until the task has ended */
static fbrl_status w_await(fbrl_vm *vm, void *arg)
{
    (void)arg;
    fbrl_cell v;
    int i;
    fbrl_status st;
    if ((st = tk_pop(vm, &v)) || (st = task_arg(vm, v, &i)))
        return st;
    if (i == vm->cur_task)
        return tk_throw(vm, FBRL_THROW_UNSUPPORTED, "AWAIT: a task cannot wait for itself");
    fbrl__wait_begin(vm);
    for (;;) {
        int s = vm->tasks[i].state;
        if (s != TK_READY && s != TK_WAIT && s != TK_RUN)
            return FBRL_OK;
        int code = task_pause(vm, NO_WAKE, 1); /* until a task ends */
        if (code)
            return tk_throw(vm, code, NULL);
    }
}

/* TASKS ( -- ): each task, its state, its timed steps */
static fbrl_status w_tasks(fbrl_vm *vm, void *arg)
{
    (void)arg;
    char line[256];
    uint64_t now = now_us(vm);
    for (int i = 0; i < FBRL_TASKS_MAX; i++) {
        const fbrl_task *t = &vm->tasks[i];
        if (i && (!t->word || forgotten(vm, t)))
            continue;
        int s = i == 0 ? TK_RUN : t->state;
        int n = snprintf(line, sizeof line, "%-16s %-8s", task_name(vm, i), state_names[s]);
        if (s == TK_WAIT && t->wake_us > now)
            n += snprintf(line + n, sizeof line - (size_t)n, " due in %lu ms",
                          (unsigned long)((t->wake_us - now) / US_PER_MS));
        if (t->steps) {
            /* floats through fbrl_num_fixed ("%.1f"): the firmware's printf has no %f */
            char late[24];
            fbrl_num_fixed(late, sizeof late, (double)t->late_max_us / US_PER_MS, 0, 1, 0, NULL);
            n += snprintf(line + n, sizeof line - (size_t)n, " steps %lu late max %s ms", t->steps, late);
        }
        if (s == TK_FAILED)
            n += snprintf(line + n, sizeof line - (size_t)n, " (%s)", t->msg);
        for (int k = 0; k < FBRL_CLAIMS_MAX; k++)
            if (vm->claims[k].key && vm->claims[k].owner == i) {
                char what[40];
                claim_name(vm, vm->claims[k].key, what, sizeof what);
                n += snprintf(line + n, sizeof line - (size_t)n, " holds %s", what);
            }
        (void)n;
        say(vm, line);
        say(vm, "\n");
    }
    return FBRL_OK;
}

/* TASK-STATE ( task -- n ): 1 made, 2 ready, 3 waiting, 4 running, 5 done, 6 failed, 7 stopped */
static fbrl_status w_task_state(fbrl_vm *vm, void *arg)
{
    (void)arg;
    fbrl_cell v;
    int i;
    fbrl_status st;
    if ((st = tk_pop(vm, &v)) || (st = task_arg(vm, v, &i)))
        return st;
    return tk_push(vm, vm->tasks[i].state);
}

/* ---- claims: CLAIM ( key -- ) RELEASE ( key -- ) ARM ( -- key ) ---- */
static fbrl_status claim(fbrl_vm *vm, fbrl_cell key)
{
    if (key == 0)
        return tk_throw(vm, FBRL_THROW_BAD_NUMBER, "CLAIM: 0 is no resource (THE-ARM, or a device)");
    fbrl__wait_begin(vm);
    for (;;) {
        fbrl_claim *c = claim_of(vm, key, 1);
        int me = vm->cur_task;
        if (!c)
            return tk_throw(vm, FBRL_THROW_UNSUPPORTED, "CLAIM: too many things claimed at once (16)");
        if (c->owner == me) {
            c->depth++;
            return FBRL_OK;
        }
        if (c->owner < 0 && (c->nq == 0 || c->queue[0] == me)) {
            unqueue(c, me);
            c->owner = me;
            c->depth = 1;
            return FBRL_OK;
        }
        int k;
        for (k = 0; k < c->nq && c->queue[k] != me; k++)
            ;
        if (k == c->nq)
            c->queue[c->nq++] = me; /* claims wait in order */
        int code = task_pause(vm, NO_WAKE, 1); /* until the holder releases it */
        if (code) {
            if (code != THROW_YIELD)
                unqueue(c, me), claim_tidy(c);
            return tk_throw(vm, code, NULL);
        }
    }
}

/* CLAIM ( key -- ) CLAIM-ARM ( -- ): the key stays on the stack while the claim waits */
static fbrl_status w_claim(fbrl_vm *vm, void *arg)
{
    fbrl_cell key = FBRL_VMX_ARM;
    fbrl_status st;
    if (!arg && (st = tk_pop(vm, &key)))
        return st;
    return claim(vm, key);
}

static fbrl_status release(fbrl_vm *vm, fbrl_cell key)
{
    fbrl_claim *c = claim_of(vm, key, 0);
    if (!c || c->owner != vm->cur_task)
        return tk_throw(vm, FBRL_THROW_UNSUPPORTED, "RELEASE: this task does not hold that");
    if (--c->depth <= 0) {
        c->owner = -1;
        c->depth = 0;
        claim_tidy(c);
        signal_tasks(vm); /* the next in its queue takes it */
    }
    return FBRL_OK;
}

/* RELEASE ( key -- ) RELEASE-ARM ( -- ) */
static fbrl_status w_release(fbrl_vm *vm, void *arg)
{
    fbrl_cell key = FBRL_VMX_ARM;
    fbrl_status st;
    if (!arg && (st = tk_pop(vm, &key)))
        return st;
    return release(vm, key);
}

static fbrl_status w_arm(fbrl_vm *vm, void *arg)
{
    (void)arg;
    return tk_push(vm, FBRL_VMX_ARM);
}

/* ---- timed steps ---- */
static fbrl_status ms_pop(fbrl_vm *vm, fbrl_cell *ms, int peek)
{
    if (vm->sp <= vm->ds0)
        return tk_throw(vm, FBRL_THROW_STACK_UNDERFLOW, NULL);
    *ms = vm->sp[-1];
    if (*ms < 0 || *ms > TASK_MAX_MS)
        return tk_throw(vm, FBRL_THROW_BAD_NUMBER, "a time in ms, 0 .. 86400000 (a day)");
    if (!peek)
        vm->sp--;
    return need_clock(vm);
}

static void note_late(fbrl_task *t, uint64_t due_us, uint64_t now)
{
    uint64_t late = now > due_us ? now - due_us : 0;
    t->steps++;
    t->late_sum_us += late;
    if (late > t->late_max_us)
        t->late_max_us = late;
}

/* wait until due_us; the word's argument stays on the stack until it is over */
static fbrl_status wait_step(fbrl_vm *vm, uint64_t due_us)
{
    for (;;) {
        uint64_t now = now_us(vm);
        if (now >= due_us) {
            note_late(&vm->tasks[vm->cur_task], due_us, now);
            vm->sp--;
            return FBRL_OK;
        }
        int code = task_pause(vm, due_us, 0);
        if (code)
            return tk_throw(vm, code, NULL);
    }
}

/* ZERO-CLOCK ( -- ): the task's clock starts now (START starts it too) */
static fbrl_status w_zero_clock(fbrl_vm *vm, void *arg)
{
    (void)arg;
    fbrl_status st = need_clock(vm);
    fbrl_task *t = &vm->tasks[vm->cur_task];
    if (st)
        return st;
    t->origin_us = t->every_due_us = now_us(vm);
    return FBRL_OK;
}

/* CLOCK ( -- ms ): ms on the task's clock */
static fbrl_status w_clock(fbrl_vm *vm, void *arg)
{
    (void)arg;
    fbrl_status st = need_clock(vm);
    if (st)
        return st;
    return tk_push(vm, (fbrl_cell)((now_us(vm) - vm->tasks[vm->cur_task].origin_us) / US_PER_MS));
}

/* AT ( ms -- ): wait until ms on the task's clock (a timed step; how late it ran is kept) */
static fbrl_status w_at(fbrl_vm *vm, void *arg)
{
    (void)arg;
    fbrl_cell ms;
    fbrl_status st = ms_pop(vm, &ms, 1);
    if (st)
        return st;
    fbrl__wait_begin(vm);
    return wait_step(vm, vm->tasks[vm->cur_task].origin_us + (uint64_t)ms * US_PER_MS);
}

/* EVERY ( ms -- ): wait for the next period of ms on the task's clock; periods already
 * past are skipped and counted as missed */
static fbrl_status w_every(fbrl_vm *vm, void *arg)
{
    (void)arg;
    fbrl_cell ms;
    fbrl_status st = ms_pop(vm, &ms, 1);
    if (st)
        return st;
    if (ms == 0)
        return tk_throw(vm, FBRL_THROW_BAD_NUMBER, "EVERY: a period of 1 ms or more");
    fbrl_task *t = &vm->tasks[vm->cur_task];
    fbrl_vmx_wait *wt = fbrl__wait_begin(vm);
    if (!wt->resumed) {
        uint64_t now = now_us(vm), p = (uint64_t)ms * US_PER_MS;
        t->every_due_us += p;
        if (now > t->every_due_us + p) { /* more than one whole period late */
            uint64_t skip = (now - t->every_due_us) / p;
            t->missed += (unsigned long)skip;
            t->every_due_us += skip * p;
        }
    }
    return wait_step(vm, t->every_due_us);
}

/* DEADLINE ( ms -- ): throw if the task's clock is already past ms (counted as missed) */
static fbrl_status w_deadline(fbrl_vm *vm, void *arg)
{
    (void)arg;
    fbrl_cell ms;
    fbrl_status st = ms_pop(vm, &ms, 0);
    if (st)
        return st;
    fbrl_task *t = &vm->tasks[vm->cur_task];
    uint64_t now = now_us(vm), due_us = t->origin_us + (uint64_t)ms * US_PER_MS;
    if (now <= due_us)
        return FBRL_OK;
    t->missed++;
    char msg[96];
    snprintf(msg, sizeof msg, "DEADLINE: %ld ms missed by %lu ms", (long)ms,
             (unsigned long)((now - due_us) / US_PER_MS));
    return tk_throw(vm, FBRL_VM_THROW_OF_STATUS(FBRL_ETIMEOUT), msg);
}

/* LATE-MAX ( task -- us ) */
static fbrl_status w_late_max(fbrl_vm *vm, void *arg)
{
    (void)arg;
    fbrl_cell v;
    int i = 0;
    fbrl_status st;
    if ((st = tk_pop(vm, &v)))
        return st;
    if (v != 0 && (st = task_arg(vm, v, &i)))
        return st;
    return tk_push(vm, (fbrl_cell)vm->tasks[i].late_max_us);
}

/* LATENESS ( -- ): how late each task's timed steps ran */
static fbrl_status w_lateness(fbrl_vm *vm, void *arg)
{
    (void)arg;
    char line[200];
    say(vm, "task             steps  late max ms  late mean ms  missed\n");
    for (int i = 0; i < FBRL_TASKS_MAX; i++) {
        const fbrl_task *t = &vm->tasks[i];
        if ((i && !t->word) || (!t->steps && !t->missed))
            continue;
        char late_max[24], late_mean[24]; /* "%11.1f" "%12.1f": the firmware's printf has no %f */
        fbrl_num_fixed(late_max, sizeof late_max, (double)t->late_max_us / US_PER_MS, 11, 1, 0, NULL);
        fbrl_num_fixed(late_mean, sizeof late_mean,
                       t->steps ? (double)t->late_sum_us / (double)t->steps / US_PER_MS : 0.0, 12, 1, 0,
                       NULL);
        snprintf(line, sizeof line, "%-16s %5lu  %s  %s  %6lu\n", task_name(vm, i), t->steps, late_max,
                 late_mean, t->missed);
        say(vm, line);
    }
    return FBRL_OK;
}

static const struct {
    const char *name;
    fbrl_vm_prim fn;
    int arg;
    FBRL_DOC_FIELDS
} task_words[] = {
    {"TASK", w_task, 0, FBRL_DOC("( \"name\" -- )", "make a task with its own stacks; name pushes it")},
    {"START", w_start, 0, FBRL_DOC("( xt task -- )", "run xt as the task, beside the others")},
    {"START-WITH", w_start, 1,
     FBRL_DOC("( x1..xn n xt task -- )", "START, with n cells on the task's stack")},
    {"STOP", w_stop, 0,
     FBRL_DOC("( task -- )", "end a task (what it claimed is released; a word it waits in tidies up)")},
    {"STOP-TASKS", w_stop_tasks, 0, FBRL_DOC("( -- )", "end every task but the main one")},
    {"PAUSE", w_pause, 0, FBRL_DOC("( -- )", "let the other tasks run")},
    {"ME", w_me, 0, FBRL_DOC("( -- task )", "the running task (0: the main one)")},
    {"AWAIT", w_await, 0, FBRL_DOC("( task -- )", "wait until the task has ended")},
    {"TASKS", w_tasks, 0, FBRL_DOC("( -- )", "list the tasks: state, timed steps, what they hold")},
    {"TASK-STATE", w_task_state, 0,
     FBRL_DOC("( task -- n )", "1 made 2 ready 3 waiting 4 running 5 done 6 failed 7 stopped")},
    {"CLAIM", w_claim, 0,
     FBRL_DOC("( key -- )", "take a device (or THE-ARM) for this task; claims wait in turn")},
    {"RELEASE", w_release, 0, FBRL_DOC("( key -- )", "give back what CLAIM took")},
    {"CLAIM-ARM", w_claim, 1, FBRL_DOC("( -- )", "take the arm for a manoeuvre; other tasks' moves wait")},
    {"RELEASE-ARM", w_release, 1, FBRL_DOC("( -- )", "give the arm back to the other tasks")},
    {"THE-ARM", w_arm, 0, FBRL_DOC("( -- key )", "the arm, for CLAIM and RELEASE")},
    {"ZERO-CLOCK", w_zero_clock, 0, FBRL_DOC("( -- )", "the task's clock starts now (START starts it too)")},
    {"CLOCK", w_clock, 0, FBRL_DOC("( -- ms )", "milliseconds on the task's clock")},
    {"AT", w_at, 0, FBRL_DOC("( ms -- )", "wait until ms on the task's clock (a timed step)")},
    {"EVERY", w_every, 0, FBRL_DOC("( ms -- )", "wait for the task's next period of ms")},
    {"DEADLINE", w_deadline, 0, FBRL_DOC("( ms -- )", "throw if the task's clock is past ms")},
    {"LATE-MAX", w_late_max, 0, FBRL_DOC("( task -- us )", "how late the task's latest-run timed step was")},
    {"LATENESS", w_lateness, 0, FBRL_DOC("( -- )", "how late each task's timed steps ran")},
};

int fbrl__task_words(fbrl_vm *vm)
{
    vm->slice_nest = -1;
    vm->tasks[0].state = TK_RUN;
    vm->tasks[0].origin_us = vm->tasks[0].every_due_us = now_us(vm);
    vm->task_pause = task_pause;
    for (size_t k = 0; k < sizeof task_words / sizeof task_words[0]; k++)
        if (fbrl_vm_define(vm, task_words[k].name, task_words[k].fn, task_words[k].arg ? (void *)vm : NULL,
                           FBRL_DOC_STACK(task_words[k]), FBRL_DOC_HELP(task_words[k])) != FBRL_OK)
            return -1;
    return 0;
}
