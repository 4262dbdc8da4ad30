/* SPDX-License-Identifier: MIT */
/* test_run.c - a method run (fbrl/run.h): outcomes per sample and per run from the method's
 * own words, failing steps and corrective actions; the observers' events; parameters checked
 * before a run; the remaining time; and the requests of other threads (pause, resume, abort,
 * an answer) while the engine runs, with a third thread reading snapshots all the while. */
/* ctest-labels: threads */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/clock.h"
#include "fbrl/glossary.h"
#include "fbrl/method.h"
#include "fbrl/recover.h"
#include "fbrl/robot.h"
#include "fbrl/run.h"
#include "fbrl/vm.h"
#include "fbrl/vmx.h"
#include "support/vm_host.h"

typedef struct fixture {
    void *mem;
    vmh_text out;
    fbrl_vm *vm;
    fbrl_glossary g;
    fbrl_robot robot;
    fbrl_method_set set;
    fbrl_recover rc;
    fbrl_run run;
    char events[8192]; /* what the observer saw (engine thread) */
    int refuse;        /* the observer refuses the next run */
    uint64_t fake_us;  /* the host's clock when fake */
    int fake;
    long rem[32]; /* the remaining time as each step began */
    int nrem;
} fixture;

static uint64_t f_now(void *user)
{
    fixture *f = (fixture *)((char *)user - offsetof(fixture, out));
    return f->fake ? f->fake_us : fbrl_clock_now_us();
}

/* A host's sleep that an interrupt cuts short, as fbrlmon's does (MS relies on it). */
static void f_sleep(void *user, uint32_t ms)
{
    fixture *f = (fixture *)((char *)user - offsetof(fixture, out));
    if (f->fake) {
        f->fake_us += (uint64_t)ms * 1000u;
        return;
    }
    for (uint32_t t = 0; t < ms && !fbrl_vm_interrupt_pending(f->vm); t += 10)
        fbrl_clock_sleep_us((uint64_t)(ms - t < 10 ? ms - t : 10) * 1000u);
}

static void ev_add(fixture *f, const char *fmt, ...)
{
    va_list ap;
    size_t n = strlen(f->events);
    va_start(ap, fmt);
    vsnprintf(f->events + n, sizeof f->events - n, fmt, ap);
    va_end(ap);
}

static int observe(void *ctx, fbrl_run *r, const fbrl_run_event *ev)
{
    fixture *f = ctx;
    switch (ev->kind) {
    case FBRL_RUN_EV_BEGIN: ev_add(f, "begin %s;", ev->method->name); return f->refuse;
    case FBRL_RUN_EV_STEP_BEGIN: {
        fbrl_run_snap s;
        ev_add(f, "start %s %ld;", ev->method->steps[ev->step].name, ev->sample);
        if (f->fake && f->nrem < 32 && fbrl_run_snapshot(r, &s) == FBRL_OK)
            f->rem[f->nrem++] = s.remaining_ms;
        break;
    }
    case FBRL_RUN_EV_STEP_END:
        ev_add(f, "%s %s %ld%s%s;", ev->text ? "failed" : "ok", ev->method->steps[ev->step].name, ev->sample,
               ev->text ? " " : "", ev->text ? ev->text : "");
        break;
    case FBRL_RUN_EV_SAMPLE:
        ev_add(f, "sample %ld %s%s%s;", ev->sample, fbrl_run_sample_name((fbrl_run_sample_outcome)ev->outcome),
               ev->text[0] ? " " : "", ev->text);
        break;
    case FBRL_RUN_EV_RECOVERY: ev_add(f, "recovery %s %s %s;", ev->where, ev->kind_name, ev->action); break;
    case FBRL_RUN_EV_QUESTION: ev_add(f, "question;"); break;
    case FBRL_RUN_EV_ANSWER: ev_add(f, "answer %d by %s;", ev->choice, ev->who); break;
    case FBRL_RUN_EV_PAUSE: ev_add(f, "pause before %ld %ld by %s;", ev->step, ev->sample, ev->who); break;
    case FBRL_RUN_EV_RESUME: ev_add(f, "resume by %s;", ev->who); break;
    case FBRL_RUN_EV_ABORT: ev_add(f, "abort by %s;", ev->who); break;
    case FBRL_RUN_EV_SAFE_STOP: ev_add(f, "safe-stop %s;", fbrl_status_name(ev->status)); break;
    case FBRL_RUN_EV_ON_ABORT: ev_add(f, "on-abort%s%s;", ev->text ? " " : "", ev->text ? ev->text : ""); break;
    case FBRL_RUN_EV_END:
        ev_add(f, "end %s%s%s;", fbrl_run_outcome_name((fbrl_run_outcome)ev->outcome), ev->text ? " " : "",
               ev->text ? ev->text : "");
        break;
    case FBRL_RUN_EV_WAIT: break;
    }
    return 0;
}

static fixture *new_run(void)
{
    fixture *f = calloc(1, sizeof *f);
    assert_non_null(f);
    f->mem = malloc(2 << 20);
    assert_non_null(f->mem);
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = f->mem;
    cfg.mem_size = 2 << 20;
    cfg.host.user = &f->out;
    cfg.host.write = vmh_write;
    cfg.host.now_us = f_now;
    cfg.host.sleep_ms = f_sleep;
    vmh_use_files(&cfg.host);
    assert_int_equal(fbrl_vm_create(&f->vm, &cfg), FBRL_OK);
    assert_int_equal(fbrl_glossary_install(f->vm, &f->g), FBRL_OK);
    assert_int_equal(fbrl_robot_install(f->vm, &f->robot, NULL, &f->g), FBRL_OK); /* offline */
    assert_int_equal(fbrl_method_install(f->vm, &f->set), FBRL_OK);
    assert_int_equal(fbrl_recover_install(f->vm, &f->rc, &f->robot), FBRL_OK);
    assert_int_equal(fbrl_run_install(&f->run, f->vm, &f->set, &f->rc, &f->robot), FBRL_OK);
    assert_int_equal(fbrl_run_observe(&f->run, observe, f), FBRL_OK);
    return f;
}

static void drop(fixture *f)
{
    fbrl_glossary_finish(&f->g);
    free(f->mem);
    free(f);
}

/* Each line evaluated alone: a declaration takes the rest of its line. */
static void lines(fixture *f, const char *src)
{
    const char *p = src, *e;
    while ((e = strchr(p, '\n')) != NULL) {
        fbrl_status st = fbrl_vm_eval(f->vm, p, (size_t)(e - p));
        if (st != FBRL_OK)
            print_error("'%.*s': %s\n", (int)(e - p), p, fbrl_vm_last_error(f->vm)->message);
        assert_int_equal(st, FBRL_OK);
        p = e + 1;
    }
}

/* The events contain text; on failure, say what they were. */
#define SAW(f, text)                                                          \
    do {                                                                      \
        if (strstr((f)->events, (text)) == NULL)                              \
            print_error("events: %s\nwanted: %s\n", (f)->events, (text));     \
        assert_non_null(strstr((f)->events, (text)));                         \
    } while (0)

static fbrl_run_snap snap(fixture *f)
{
    fbrl_run_snap s;
    assert_int_equal(fbrl_run_snapshot(&f->run, &s), FBRL_OK);
    return s;
}

/* SAMPLE-FAILED BAD? is true for sample n when BAD holds n + 1 in its bits. */
static const char marks_src[] = "VARIABLE BAD  0 BAD !\n"
                                "VARIABLE SAFE 0 SAFE !\n"
                                ": PREP ; : LAST ;\n"
                                ": EACH ( i -- ) 1 OVER LSHIFT BAD @ AND IF S\" tube never reached the sensor\" "
                                "SAMPLE-FAILED ELSE DROP THEN ;\n"
                                ": TO-SAFE 1 SAFE ! ;\n"
                                "METHOD M  three samples\n"
                                "1 8 3 SAMPLES-PARAM N tubes  the samples\n"
                                "1 50 20 PARAM V ml  a volume\n"
                                "' PREP STEP Prep  first\n"
                                "' EACH SAMPLE-STEP Each  each sample\n"
                                "' LAST STEP Last  last\n"
                                "' TO-SAFE ON-ABORT\n"
                                "END-METHOD\n";

static void outcomes_from_the_method(void **state)
{
    (void)state;
    fixture *f = new_run();
    lines(f, marks_src);
    /* every sample succeeds: completed */
    assert_int_equal(fbrl_run_start(&f->run, "M", NULL, 0, NULL), FBRL_OK);
    fbrl_run_snap s = snap(f);
    assert_int_equal(s.state, FBRL_RUN_FINISHED);
    assert_int_equal(s.outcome, FBRL_RUN_COMPLETED);
    assert_int_equal(s.samples, 3);
    assert_int_equal(s.samples_done, 3);
    assert_string_equal(f->events, "begin M;start Prep -1;ok Prep -1;start Each 0;ok Each 0;sample 0 succeeded;"
                                   "start Each 1;ok Each 1;sample 1 succeeded;start Each 2;ok Each 2;"
                                   "sample 2 succeeded;start Last -1;ok Last -1;end completed;");
    /* sample 2 (index 1) marked failed: partial, with the reason */
    f->events[0] = '\0';
    lines(f, "2 BAD !\n");
    assert_int_equal(fbrl_run_start(&f->run, "M", NULL, 0, NULL), FBRL_OK);
    s = snap(f);
    assert_int_equal(s.outcome, FBRL_RUN_PARTIAL);
    assert_int_equal(s.outcomes[0].outcome, FBRL_SAMPLE_SUCCEEDED);
    assert_int_equal(s.outcomes[1].outcome, FBRL_SAMPLE_FAILED);
    assert_string_equal(s.outcomes[1].reason, "tube never reached the sensor");
    assert_int_equal(s.outcomes[2].outcome, FBRL_SAMPLE_SUCCEEDED);
    SAW(f, "start Each 1;sample 1 failed tube never reached the sensor;ok Each 1;start Each 2");
    SAW(f, "end partial;");
    /* every sample failed: failed; RUN-METHOD itself does not throw (the run reached its end) */
    lines(f, "7 BAD !\n");
    lines(f, "M RUN-METHOD\n");
    assert_int_equal(snap(f).outcome, FBRL_RUN_FAILED);
    /* the parameters, checked before a run: nothing is set when one is out of range */
    long v[2] = {2, 51}, n = 0;
    size_t bad = 99;
    assert_int_equal(fbrl_run_start(&f->run, "M", v, 2, &bad), FBRL_ERANGE);
    assert_int_equal(bad, 1);
    assert_int_equal(fbrl_method_param_get(&f->set, fbrl_method_find(&f->set, "M"), 0, &n), FBRL_OK);
    assert_int_equal(n, 3);
    assert_int_equal(fbrl_run_start(&f->run, "M", v, 1, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_run_start(&f->run, "NOPE", NULL, 0, NULL), FBRL_ENOENT);
    v[1] = 50;
    lines(f, "0 BAD !\n");
    assert_int_equal(fbrl_run_start(&f->run, "M", v, 2, NULL), FBRL_OK);
    s = snap(f);
    assert_int_equal(s.samples, 2);
    assert_int_equal(s.outcome, FBRL_RUN_COMPLETED);
    /* SAMPLE-SKIPPED, and SAMPLE-OK? for a later step to leave a sample alone; the first
     * mark of a sample stands */
    fbrl_cell oks = 0;
    lines(f, "VARIABLE OKS 0 OKS !\n"
             ": SKIP3 ( i -- ) 2 = IF 2 S\" no tube in the rack\" SAMPLE-SKIPPED 2 S\" later\" SAMPLE-FAILED THEN ;\n"
             ": LOOK ( i -- ) DUP SAMPLE-OK? IF 1 SWAP LSHIFT OKS @ OR OKS ! ELSE DROP THEN ;\n"
             "METHOD K  skips the third\n"
             "1 8 3 SAMPLES-PARAM KN tubes  the samples\n"
             "' SKIP3 SAMPLE-STEP Rack  from the rack\n"
             "' LOOK SAMPLE-STEP Look  only those still good\n"
             "END-METHOD\n");
    assert_int_equal(fbrl_run_start(&f->run, "K", NULL, 0, NULL), FBRL_OK);
    s = snap(f);
    assert_int_equal(s.outcome, FBRL_RUN_PARTIAL);
    assert_int_equal(s.outcomes[2].outcome, FBRL_SAMPLE_SKIPPED);
    assert_string_equal(s.outcomes[2].reason, "no tube in the rack");
    assert_int_equal(fbrl_vm_eval(f->vm, "OKS @", 5), FBRL_OK);
    assert_int_equal(fbrl_vm_pop(f->vm, &oks), FBRL_OK);
    assert_int_equal(oks, 3);
    /* the words outside a run */
    assert_int_not_equal(fbrl_vm_eval(f->vm, "0 S\" x\" SAMPLE-FAILED", 21), FBRL_OK);
    assert_non_null(strstr(fbrl_vm_last_error(f->vm)->message, "no method is running"));
    assert_int_equal(fbrl_run_mark(&f->run, 0, FBRL_SAMPLE_FAILED, "x"), FBRL_ESTATE);
    drop(f);
}

static void a_failing_step_stops_the_run(void **state)
{
    (void)state;
    fixture *f = new_run();
    lines(f, marks_src);
    lines(f, ": BOOM ( i -- ) 1 = ABORT\" the gripper slipped\" ;\n"
             "METHOD F  fails at the second sample\n"
             "1 8 3 SAMPLES-PARAM FN tubes  the samples\n"
             "' BOOM SAMPLE-STEP Grip  grip it\n"
             "' PREP STEP After  after\n"
             "END-METHOD\n");
    assert_int_equal(fbrl_run_start(&f->run, "F", NULL, 0, NULL), FBRL_OK);
    fbrl_run_snap s = snap(f);
    assert_int_equal(s.outcome, FBRL_RUN_PARTIAL); /* sample 1 was through its last step */
    assert_int_equal(s.outcomes[0].outcome, FBRL_SAMPLE_SUCCEEDED);
    assert_int_equal(s.outcomes[1].outcome, FBRL_SAMPLE_FAILED);
    assert_string_equal(s.outcomes[1].reason, "Grip: the gripper slipped");
    assert_int_equal(s.outcomes[2].outcome, FBRL_SAMPLE_SKIPPED);
    assert_string_equal(s.outcomes[2].reason, "not done: the run stopped at Grip");
    assert_string_equal(s.error, "the gripper slipped");
    assert_int_equal(s.step_failed[0], 1);
    /* the safe stop (offline here: it says so); no ON-ABORT after a failure */
    SAW(f, "failed Grip 1 the gripper slipped;safe-stop FBRL_EOFFLINE;sample 1 failed");
    assert_null(strstr(f->events, "on-abort"));
    SAW(f, "end partial the gripper slipped;");
    /* RUN-METHOD throws the step's error */
    assert_int_not_equal(fbrl_vm_eval(f->vm, "F RUN-METHOD", 12), FBRL_OK);
    assert_string_equal(fbrl_vm_last_error(f->vm)->message, "the gripper slipped");
    /* failing at the first sample of a step before the last per-sample one: none succeeded */
    lines(f, "METHOD G  fails early\n"
             "1 8 2 SAMPLES-PARAM GN tubes  the samples\n"
             "' BOOM SAMPLE-STEP Grip  grip it\n"
             "' EACH SAMPLE-STEP Each  each\n"
             "END-METHOD\n");
    assert_int_equal(fbrl_run_start(&f->run, "G", NULL, 0, NULL), FBRL_OK);
    s = snap(f);
    assert_int_equal(s.outcome, FBRL_RUN_FAILED);
    assert_int_equal(s.outcomes[0].outcome, FBRL_SAMPLE_SKIPPED); /* not through Each */
    assert_int_equal(s.outcomes[1].outcome, FBRL_SAMPLE_FAILED);
    drop(f);
}

static void corrective_actions_skip_samples(void **state)
{
    (void)state;
    fixture *f = new_run();
    lines(f, marks_src);
    /* a rule's SKIP, uncaught in the step: the sample is skipped and the run goes on; inside
     * RUN-SAMPLE (the flag dropped): the run still knows */
    lines(f, ": CHECK ( -- ) FAILURE PART-MISSING ;\n"
             "ON-FAILURE CHECK PART-MISSING SKIP\n"
             ": MAYBE ( i -- ) 1 = IF ['] CHECK ATTEMPT THEN ;\n");
    lines(f, ": MAYBE-ONE ['] CHECK ATTEMPT ;\n"
             ": INSIDE ( i -- ) 2 = IF ['] MAYBE-ONE RUN-SAMPLE DROP THEN ;\n"
             "METHOD S  skips\n"
             "1 8 3 SAMPLES-PARAM SN tubes  the samples\n"
             "' MAYBE SAMPLE-STEP Look  is it there?\n"
             "' INSIDE SAMPLE-STEP Again  once more\n"
             "END-METHOD\n");
    assert_int_equal(fbrl_run_start(&f->run, "S", NULL, 0, NULL), FBRL_OK);
    fbrl_run_snap s = snap(f);
    assert_int_equal(s.outcome, FBRL_RUN_PARTIAL);
    assert_int_equal(s.outcomes[0].outcome, FBRL_SAMPLE_SUCCEEDED);
    assert_int_equal(s.outcomes[1].outcome, FBRL_SAMPLE_SKIPPED);
    assert_string_equal(s.outcomes[1].reason, "CHECK failed (PART-MISSING): sample skipped");
    assert_int_equal(s.outcomes[2].outcome, FBRL_SAMPLE_SKIPPED);
    SAW(f, "recovery CHECK PART-MISSING skip the sample;failed Look 1 CHECK failed");
    SAW(f, "sample 1 skipped CHECK failed (PART-MISSING): sample skipped;start Look 2");
    /* the step that skipped is not a failed step, and the run went on to its end */
    assert_int_equal(s.step_failed[0], 0);
    SAW(f, "ok Again 2;end partial;");
    drop(f);
}

/* Two more observers that only say they were called (BEGIN and END). */
static int order_a(void *ctx, fbrl_run *r, const fbrl_run_event *ev)
{
    (void)r;
    if (ev->kind == FBRL_RUN_EV_BEGIN || ev->kind == FBRL_RUN_EV_END)
        ev_add(ctx, "A;");
    return 0;
}

static int order_b(void *ctx, fbrl_run *r, const fbrl_run_event *ev)
{
    (void)r;
    if (ev->kind == FBRL_RUN_EV_BEGIN || ev->kind == FBRL_RUN_EV_END)
        ev_add(ctx, "B;");
    return 0;
}

static void observers_and_the_remaining_time(void **state)
{
    (void)state;
    fixture *f = new_run();
    f->fake = 1;
    lines(f, ": A 1000 MS ; : B ( i -- ) DROP 500 MS ; : C ;\n"
             "METHOD T  timed\n"
             "1 8 4 SAMPLES-PARAM TN tubes  the samples\n"
             "' A STEP A  a second\n"
             "' B SAMPLE-STEP B  half a second each\n"
             "' C STEP C  at once\n"
             "END-METHOD\n");
    /* an observer that refuses: the run never begins */
    f->events[0] = '\0';
    f->refuse = 1;
    assert_int_not_equal(fbrl_run_start(&f->run, "T", NULL, 0, NULL), FBRL_OK);
    assert_null(strstr(f->events, "start"));
    assert_int_equal(snap(f).outcome, FBRL_RUN_NONE);
    f->refuse = 0;
    /* the first run, nothing known: unknown until a step has been measured; then a step not
     * yet measured counts as the average of those that were (A 1000, then B 500: 750) */
    f->nrem = 0;
    assert_int_equal(fbrl_run_start(&f->run, "T", NULL, 0, NULL), FBRL_OK);
    fbrl_run_snap s = snap(f);
    assert_int_equal(s.elapsed_ms, 3000); /* 1000 + 4 x 500 on the fake clock */
    assert_int_equal(s.remaining_ms, 0);
    long first[] = {-1, 4000 + 1000, 1500 + 750, 1000 + 750, 500 + 750, 750};
    assert_int_equal(f->nrem, 6);
    for (int i = 0; i < 6; i++)
        assert_int_equal(f->rem[i], first[i]);
    /* the next run of the method: what the one before measured */
    f->nrem = 0;
    assert_int_equal(fbrl_run_start(&f->run, "T", NULL, 0, NULL), FBRL_OK);
    assert_int_equal(f->rem[0], 1000 + 2000 + 750); /* C took no time: unknown, the average */
    assert_int_equal(f->rem[1], 2000 + 750);
    /* a prediction (a dry run's) is what counts, from the start */
    double pred[3] = {2000, 250, 100};
    assert_int_equal(fbrl_run_predict(&f->run, "T", pred, 3), FBRL_OK);
    f->nrem = 0;
    assert_int_equal(fbrl_run_start(&f->run, "T", NULL, 0, NULL), FBRL_OK);
    assert_int_equal(f->rem[0], 2000 + 1000 + 100);
    assert_int_equal(f->rem[1], 1000 + 100);
    assert_int_equal(f->rem[5], 100);
    /* observers in the order added; one removed and added again comes last */
    assert_int_equal(fbrl_run_observe(&f->run, order_a, f), FBRL_OK);
    assert_int_equal(fbrl_run_observe(&f->run, order_b, f), FBRL_OK);
    assert_int_equal(fbrl_run_unobserve(&f->run, order_a, f), FBRL_OK);
    assert_int_equal(fbrl_run_unobserve(&f->run, order_a, f), FBRL_ENOENT);
    assert_int_equal(fbrl_run_observe(&f->run, order_a, f), FBRL_OK);
    f->events[0] = '\0';
    assert_int_equal(fbrl_run_start(&f->run, "T", NULL, 0, NULL), FBRL_OK);
    SAW(f, "begin T;B;A;start A -1;");
    SAW(f, "end completed;B;A;");
    assert_int_equal(fbrl_run_unobserve(&f->run, order_a, f), FBRL_OK);
    assert_int_equal(fbrl_run_unobserve(&f->run, order_b, f), FBRL_OK);
    f->fake = 0;
    drop(f);
}

/* ---- threads: the engine runs on one, requests come from another, a third reads ---- */

typedef struct shared {
    fixture *f;
    int stop_reader;
    long reads, bad_reads;
    unsigned long last_version;
} shared;

static void *engine(void *arg)
{
    fixture *f = arg;
    fbrl_status st = fbrl_run_start(&f->run, "P", NULL, 0, NULL);
    return (void *)(intptr_t)st;
}

/* Every snapshot is whole: its counts agree with its outcomes, versions never go back. */
static void *reader(void *arg)
{
    shared *sh = arg;
    while (!__atomic_load_n(&sh->stop_reader, __ATOMIC_ACQUIRE)) {
        fbrl_run_snap s;
        if (fbrl_run_snapshot(&sh->f->run, &s) != FBRL_OK)
            continue;
        long done = 0;
        for (long i = 0; i < s.samples; i++)
            done += s.outcomes[i].outcome != FBRL_SAMPLE_PENDING;
        if (done != s.samples_done || s.version < sh->last_version)
            sh->bad_reads++;
        sh->last_version = s.version;
        sh->reads++;
    }
    return NULL;
}

static fbrl_run_snap wait_state(fixture *f, int state, int ms)
{
    fbrl_run_snap s;
    for (int i = 0; i < ms; i++) {
        assert_int_equal(fbrl_run_snapshot(&f->run, &s), FBRL_OK);
        if (s.state == state)
            return s;
        fbrl_clock_sleep_us(1000);
    }
    print_error("state %s not reached: %s\n", fbrl_run_state_name((fbrl_run_state)state),
                fbrl_run_state_name((fbrl_run_state)s.state));
    fail();
    return s;
}

static const char threads_src[] = "VARIABLE STEPS 0 STEPS !  VARIABLE SAFE 0 SAFE !\n"
                                   ": WORK ( i -- ) DROP 1 STEPS +! 30 MS ;\n"
                                   ": LONG ( i -- ) DROP 1 STEPS +! 5000 MS ;\n"
                                   ": TO-SAFE 1 SAFE ! ;\n"
                                   "METHOD P  threads\n"
                                   "1 20 6 SAMPLES-PARAM PN tubes  the samples\n"
                                   "' WORK SAMPLE-STEP Work  a little\n"
                                   "' LONG SAMPLE-STEP Long  a long wait\n"
                                   "' TO-SAFE ON-ABORT\n"
                                   "END-METHOD\n";

static void pause_resume_abort_from_another_thread(void **state)
{
    (void)state;
    fixture *f = new_run();
    shared sh;
    pthread_t eng, rd;
    void *res;
    fbrl_cell steps = 0, steps2 = 0, safe = 0;
    memset(&sh, 0, sizeof sh);
    sh.f = f;
    lines(f, threads_src);
    /* nothing to pause, resume, abort or answer while no run goes */
    assert_int_equal(fbrl_run_pause(&f->run, "ann"), FBRL_ESTATE);
    assert_int_equal(fbrl_run_resume(&f->run, "ann"), FBRL_ESTATE);
    assert_int_equal(fbrl_run_abort(&f->run, "ann"), FBRL_ESTATE);
    assert_int_equal(fbrl_run_answer(&f->run, FBRL_RUN_RETRY, "ann"), FBRL_ESTATE);
    assert_int_equal(pthread_create(&rd, NULL, reader, &sh), 0);
    assert_int_equal(pthread_create(&eng, NULL, engine, f), 0);
    wait_state(f, FBRL_RUN_RUNNING, 2000);
    assert_int_equal(fbrl_run_pause(&f->run, "ann"), FBRL_OK);
    fbrl_run_snap s;
    assert_int_equal(fbrl_run_snapshot(&f->run, &s), FBRL_OK);
    assert_true(s.state == FBRL_RUN_PAUSING || s.state == FBRL_RUN_PAUSED); /* at once */
    assert_string_equal(s.who, "ann");
    s = wait_state(f, FBRL_RUN_PAUSED, 3000);
    assert_int_equal(s.step, 0); /* still in the short step: paused between two of its samples */
    fbrl_clock_sleep_us(150000);
    assert_int_equal(snap(f).state, FBRL_RUN_PAUSED);
    /* resumed: the steps go on; then aborted in the middle of the long wait */
    assert_int_equal(fbrl_run_resume(&f->run, "bob"), FBRL_OK);
    s = wait_state(f, FBRL_RUN_RUNNING, 2000);
    for (int i = 0; i < 5000 && s.step != 1; i++) {
        fbrl_clock_sleep_us(1000);
        s = snap(f);
    }
    assert_int_equal(s.step, 1);
    uint64_t t0 = fbrl_clock_now_us();
    assert_int_equal(fbrl_run_abort(&f->run, "cy"), FBRL_OK);
    assert_int_equal(fbrl_run_abort(&f->run, "cy again"), FBRL_OK); /* one abort */
    assert_int_equal(pthread_join(eng, &res), 0);
    uint64_t took = fbrl_clock_now_us() - t0;
    if (took >= 1000000)
        print_message("the abort took %lu ms\n", (unsigned long)(took / 1000));
    __atomic_store_n(&sh.stop_reader, 1, __ATOMIC_RELEASE);
    assert_int_equal(pthread_join(rd, NULL), 0);
    assert_int_equal((intptr_t)res, FBRL_OK);
    s = snap(f);
    assert_int_equal(s.state, FBRL_RUN_FINISHED);
    assert_int_equal(s.outcome, FBRL_RUN_ABORTED);
    assert_string_equal(s.who, "cy");
    assert_int_equal(s.outcomes[0].outcome, FBRL_SAMPLE_FAILED);
    assert_string_equal(s.outcomes[0].reason, "aborted during Long");
    assert_int_equal(s.outcomes[5].outcome, FBRL_SAMPLE_SKIPPED);
    assert_true(sh.reads > 10);
    assert_int_equal(sh.bad_reads, 0);
    /* the run log's story: who paused, resumed, aborted; the safe stop and ON-ABORT */
    SAW(f, "pause before 0 ");
    SAW(f, " by ann;");
    SAW(f, "resume by bob;");
    SAW(f, "failed Long 0 user interrupt;abort by cy;safe-stop FBRL_EOFFLINE;on-abort;");
    SAW(f, "end aborted");
    assert_int_equal(fbrl_vm_eval(f->vm, "SAFE @", 6), FBRL_OK);
    assert_int_equal(fbrl_vm_pop(f->vm, &safe), FBRL_OK);
    assert_int_equal(safe, 1);
    /* no interrupt is left over for what the engine runs next */
    assert_int_equal(fbrl_vm_eval(f->vm, "STEPS @ 10 MS STEPS @", 21), FBRL_OK);
    assert_int_equal(fbrl_vm_pop(f->vm, &steps2), FBRL_OK);
    assert_int_equal(fbrl_vm_pop(f->vm, &steps), FBRL_OK);
    assert_int_equal(steps, steps2);
    assert_int_equal(fbrl_run_pause(&f->run, "late"), FBRL_ESTATE);
    drop(f);
}

/* An interrupt from outside the run (fbrlmon's Ctrl-C is fbrl_vm_interrupt) while it is
 * paused: aborted, and neither a resume nor the safe stop and ON-ABORT, which are whoever
 * interrupted's to make. */
static void an_interrupt_from_outside_while_paused(void **state)
{
    (void)state;
    fixture *f = new_run();
    pthread_t eng;
    void *res;
    fbrl_cell safe = -1;
    lines(f, threads_src);
    assert_int_equal(pthread_create(&eng, NULL, engine, f), 0);
    wait_state(f, FBRL_RUN_RUNNING, 2000);
    assert_int_equal(fbrl_run_pause(&f->run, "ann"), FBRL_OK);
    wait_state(f, FBRL_RUN_PAUSED, 3000);
    fbrl_vm_interrupt(f->vm);
    assert_int_equal(pthread_join(eng, &res), 0);
    assert_int_equal((intptr_t)res, FBRL_OK);
    fbrl_run_snap s = snap(f);
    assert_int_equal(s.outcome, FBRL_RUN_ABORTED);
    SAW(f, " by ann;");
    SAW(f, ";end aborted");
    assert_null(strstr(f->events, "resume"));
    assert_null(strstr(f->events, "safe-stop"));
    assert_null(strstr(f->events, "on-abort"));
    assert_int_equal(fbrl_vm_eval(f->vm, "SAFE @", 6), FBRL_OK);
    assert_int_equal(fbrl_vm_pop(f->vm, &safe), FBRL_OK);
    assert_int_equal(safe, 0);
    drop(f);
}

typedef struct answerer {
    fixture *f;
    fbrl_run_choice choices[4];
    int n;
} answerer;

/* Answers each question as it comes, from its own thread: a question is known by its number. */
static void *answer_them(void *arg)
{
    answerer *a = arg;
    int last = 0;
    for (int k = 0; k < a->n; k++) {
        fbrl_run_snap s;
        int tries = 0;
        do {
            fbrl_clock_sleep_us(2000);
            if (fbrl_run_snapshot(&a->f->run, &s) != FBRL_OK)
                s.question = 0;
        } while (s.question <= last && ++tries < 3000);
        last = s.question;
        fbrl_run_answer(&a->f->run, a->choices[k], "dee");
    }
    return NULL;
}

static void questions_answered_from_another_thread(void **state)
{
    (void)state;
    fixture *f = new_run();
    pthread_t eng, ans;
    answerer a = {f, {FBRL_RUN_SKIP, FBRL_RUN_RETRY, FBRL_RUN_STOP}, 3};
    void *res;
    fbrl_cell safe = 0;
    lines(f, "VARIABLE TRIES 0 TRIES !  VARIABLE SAFE 0 SAFE !\n"
             ": CHECK ( -- ) 1 TRIES +! TRIES @ 2 <> IF FAILURE PART-MISSING THEN ;\n"
             "ON-FAILURE CHECK PART-MISSING ASK\n"
             ": ONE ( i -- ) DROP ['] CHECK ATTEMPT ;\n"
             ": TO-SAFE 1 SAFE ! ;\n"
             "METHOD P  asks\n"
             "1 20 4 SAMPLES-PARAM PN tubes  the samples\n"
             "' ONE SAMPLE-STEP Check  is it there?\n"
             "' TO-SAFE ON-ABORT\n"
             "END-METHOD\n");
    assert_int_equal(pthread_create(&ans, NULL, answer_them, &a), 0);
    assert_int_equal(pthread_create(&eng, NULL, engine, f), 0);
    assert_int_equal(pthread_join(eng, &res), 0);
    assert_int_equal(pthread_join(ans, NULL), 0);
    assert_int_equal((intptr_t)res, FBRL_OK);
    fbrl_run_snap s = snap(f);
    if (s.outcomes[0].outcome != FBRL_SAMPLE_SKIPPED)
        print_error("events: %s\n", f->events);
    /* sample 0: asked, skipped; sample 1: there at once (try 2); sample 2: asked, retried,
     * asked again, stopped by the operator: an abort (ON-ABORT runs); sample 3 not done */
    assert_int_equal(s.outcome, FBRL_RUN_ABORTED);
    assert_int_equal(s.outcomes[0].outcome, FBRL_SAMPLE_SKIPPED);
    assert_string_equal(s.outcomes[0].reason, "CHECK failed (PART-MISSING): the operator skipped the sample");
    assert_int_equal(s.outcomes[1].outcome, FBRL_SAMPLE_SUCCEEDED);
    assert_int_equal(s.outcomes[2].outcome, FBRL_SAMPLE_FAILED);
    assert_int_equal(s.outcomes[3].outcome, FBRL_SAMPLE_SKIPPED);
    assert_int_equal(s.question, 0);
    SAW(f, "question;answer 2 by dee;recovery CHECK PART-MISSING ask: skip the sample;");
    SAW(f, "question;answer 1 by dee;recovery CHECK PART-MISSING ask: retry;");
    SAW(f, "question;answer 3 by dee;recovery CHECK PART-MISSING ask: abort;");
    /* the corrective action made the safe stop; the run adds ON-ABORT, not a second stop */
    SAW(f, "abort by dee;on-abort;");
    assert_null(strstr(f->events, "safe-stop"));
    assert_int_equal(fbrl_vm_eval(f->vm, "SAFE @", 6), FBRL_OK);
    assert_int_equal(fbrl_vm_pop(f->vm, &safe), FBRL_OK);
    assert_int_equal(safe, 1);
    drop(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(outcomes_from_the_method),
        cmocka_unit_test(a_failing_step_stops_the_run),
        cmocka_unit_test(corrective_actions_skip_samples),
        cmocka_unit_test(observers_and_the_remaining_time),
        cmocka_unit_test(pause_resume_abort_from_another_thread),
        cmocka_unit_test(an_interrupt_from_outside_while_paused),
        cmocka_unit_test(questions_answered_from_another_thread),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
