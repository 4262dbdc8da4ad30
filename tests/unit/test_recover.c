/* SPDX-License-Identifier: MIT */
/* test_recover.c - corrective actions (fbrl/recover.h): rules per step and kind, retries
 * counted per ATTEMPT, a recovery word before the retry, skip, the operator's three
 * answers, the safe stop, failures classed from THROW codes and controller errors, and
 * one clear error for each bad declaration. (With fbrlsim: tests/e2e/recover_session.sh.) */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/rapl_reply.h"
#include "fbrl/recover.h"
#include "fbrl/vm.h"
#include "fbrl/vmx.h"

#define MEM_SIZE (2u << 20)

typedef struct fixture {
    unsigned char *mem;
    fbrl_vm *vm;
    fbrl_recover rc;
    const char *answers; /* the operator's answers, one character each */
    int asked;
    char notes[2048]; /* "STEP KIND ACTION sample;" each */
} fixture;

static int ask(void *ctx, const char *question)
{
    fixture *f = ctx;
    assert_non_null(strstr(question, "failed"));
    f->asked++;
    return *f->answers ? *f->answers++ : 'A';
}

static void note(void *ctx, const char *step, const char *kind, const char *what, const char *action,
                 long sample)
{
    fixture *f = ctx;
    size_t n = strlen(f->notes);
    assert_true(what[0] != 0);
    snprintf(f->notes + n, sizeof f->notes - n, "%s %s %s %ld;", step, kind, action, sample);
}

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    assert_non_null(f);
    f->mem = malloc(MEM_SIZE);
    assert_non_null(f->mem);
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = f->mem;
    cfg.mem_size = MEM_SIZE;
    assert_int_equal(fbrl_vm_create(&f->vm, &cfg), FBRL_OK);
    assert_int_equal(fbrl_recover_install(f->vm, &f->rc, NULL), FBRL_OK);
    fbrl_recover_set_ask(&f->rc, ask, f);
    fbrl_recover_set_note(&f->rc, note, f);
    f->answers = "";
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    free(f->mem);
    free(f);
    return 0;
}

static int ev(fixture *f, const char *text)
{
    fbrl_status st = fbrl_vm_eval(f->vm, text, strlen(text));
    return st == FBRL_OK ? 0 : fbrl_vm_last_error(f->vm)->throw_code;
}

static fbrl_cell pop(fixture *f)
{
    fbrl_cell v = 0;
    assert_int_equal(fbrl_vm_pop(f->vm, &v), FBRL_OK);
    return v;
}

/* FLAKY fails with GRIP-EMPTY until it has run `n` times. */
static const char steps[] = "VARIABLE TRIES  VARIABLE NEED  VARIABLE FIXES\n"
                            ": FLAKY ( -- ) 1 TRIES +! TRIES @ NEED @ < IF FAILURE GRIP-EMPTY THEN ;\n"
                            ": FIX ( -- ) 1 FIXES +! ;\n"
                            ": MISSING ( -- ) FAILURE PART-MISSING ;\n"
                            ": SLOW ( -- ) FAILURE DEVICE-TIMEOUT ;\n"
                            ": OTHER ( -- ) 7 THROW ;\n";

static void retries_are_counted_per_attempt(void **state)
{
    fixture *f = *state;
    assert_int_equal(ev(f, steps), 0);
    assert_int_equal(ev(f, "ON-FAILURE FLAKY GRIP-EMPTY RETRY 2"), 0);
    /* two failures, then it works: done */
    assert_int_equal(ev(f, "0 TRIES ! 3 NEED ! ' FLAKY ATTEMPT TRIES @"), 0);
    assert_int_equal(pop(f), 3);
    assert_string_equal(f->notes, "FLAKY GRIP-EMPTY retry 1 of 2 0;FLAKY GRIP-EMPTY retry 2 of 2 0;");
    /* the next ATTEMPT counts anew; three failures are one too many: the failure is thrown on */
    assert_int_equal(ev(f, "0 TRIES ! 4 NEED ! ' FLAKY ATTEMPT"),
                     FBRL_RECOVER_THROW(FBRL_RECOVER_GRIP_EMPTY));
    assert_string_equal(fbrl_vm_last_error(f->vm)->message, "GRIP-EMPTY: the gripper closed on nothing");
    /* a failure no rule names goes through untouched */
    assert_int_equal(ev(f, "' OTHER ATTEMPT"), 7);
    assert_int_equal(ev(f, "' MISSING ATTEMPT"), FBRL_RECOVER_THROW(FBRL_RECOVER_PART_MISSING));
    assert_int_equal(f->asked, 0);
}

static void a_recovery_word_runs_before_the_retry(void **state)
{
    fixture *f = *state;
    assert_int_equal(ev(f, steps), 0);
    assert_int_equal(ev(f, "ON-FAILURE FLAKY GRIP-EMPTY RUN FIX 1"), 0);
    assert_int_equal(ev(f, "ON-FAILURE FLAKY GRIP-EMPTY SKIP"), 0); /* after the one try */
    assert_int_equal(ev(f, "0 TRIES ! 0 FIXES ! 2 NEED ! ' FLAKY ATTEMPT FIXES @ TRIES @"), 0);
    assert_int_equal(pop(f), 2);
    assert_int_equal(pop(f), 1);
    /* fails twice: fix and retry once, then the next rule skips the sample */
    assert_int_equal(ev(f, ": ONE ['] FLAKY ATTEMPT ; 0 TRIES ! 9 NEED ! ' ONE RUN-SAMPLE ' ONE RUN-SAMPLE"),
                     0);
    assert_int_equal(pop(f), 0); /* false: skipped */
    assert_int_equal(pop(f), 0);
    assert_non_null(
        strstr(f->notes, "FLAKY GRIP-EMPTY run FIX, retry 1 of 1 1;FLAKY GRIP-EMPTY skip the sample 1;"));
    assert_non_null(strstr(f->notes, "skip the sample 2;"));
    /* a sample that works says so */
    assert_int_equal(ev(f, "0 TRIES ! 0 NEED ! ' ONE RUN-SAMPLE"), 0);
    assert_int_equal(pop(f), -1);
}

static void the_operator_answers(void **state)
{
    fixture *f = *state;
    assert_int_equal(ev(f, steps), 0);
    assert_int_equal(ev(f, "ON-FAILURE * PART-MISSING ASK"), 0);
    assert_int_equal(ev(f, ": ONE ['] MISSING ATTEMPT ;"), 0);
    f->answers = "S";
    assert_int_equal(ev(f, "' ONE RUN-SAMPLE"), 0);
    assert_int_equal(pop(f), 0);
    f->answers = "RRA"; /* retry twice, then abort: a safe stop that ends the plan */
    assert_int_equal(ev(f, "' ONE RUN-SAMPLE"), FBRL_RECOVER_THROW_STOPPED);
    assert_int_equal(f->asked, 4);
    assert_non_null(strstr(fbrl_vm_last_error(f->vm)->message, "stopped safely: MISSING failed at sample 2"));
    assert_non_null(strstr(
        f->notes, "ask: retry 2;MISSING PART-MISSING ask: retry 2;MISSING PART-MISSING ask: abort 2;"));
    /* STOP: no question */
    assert_int_equal(ev(f, "ON-FAILURE SLOW DEVICE-TIMEOUT STOP ' SLOW ATTEMPT"), FBRL_RECOVER_THROW_STOPPED);
    assert_int_equal(f->asked, 4);
    /* without an operator, ASK stops safely */
    fbrl_recover_set_ask(&f->rc, NULL, NULL);
    assert_int_equal(ev(f, "' ONE RUN-SAMPLE"), FBRL_RECOVER_THROW_STOPPED);
}

static void failures_are_classed(void **state)
{
    fixture *f = *state;
    assert_int_equal(fbrl_recover_classify(&f->rc, FBRL_RECOVER_THROW(FBRL_RECOVER_GRIP_EMPTY)),
                     FBRL_RECOVER_GRIP_EMPTY);
    assert_int_equal(fbrl_recover_classify(&f->rc, FBRL_VM_THROW_OF_STATUS(FBRL_EDISCONNECTED)),
                     FBRL_RECOVER_COMM_LOST);
    assert_int_equal(fbrl_recover_classify(&f->rc, FBRL_VM_THROW_OF_STATUS(FBRL_EOFFLINE)),
                     FBRL_RECOVER_COMM_LOST);
    /* no robot: a controller error is only that */
    assert_int_equal(fbrl_recover_classify(&f->rc, FBRL_VM_THROW_OF_STATUS(FBRL_ECONTROLLER)),
                     FBRL_RECOVER_CONTROLLER);
    assert_int_equal(fbrl_recover_classify(&f->rc, -13), FBRL_RECOVER_NONE);
    assert_int_equal(fbrl_recover_classify(&f->rc, FBRL_RECOVER_THROW_SKIP), FBRL_RECOVER_NONE);
    /* the controller's numbers, as the RAPL-II table has them */
    assert_int_equal(fbrl_rapl_error_class(29), FBRL_RAPL_ERRC_REACH);
    assert_int_equal(fbrl_rapl_error_class(68), FBRL_RAPL_ERRC_REACH);
    assert_int_equal(fbrl_rapl_error_class(42), FBRL_RAPL_ERRC_JOINT_LIMIT);
    assert_int_equal(fbrl_rapl_error_class(46), FBRL_RAPL_ERRC_JOINT_LIMIT);
    assert_int_equal(fbrl_rapl_error_class(48), FBRL_RAPL_ERRC_JOINT_LIMIT);
    assert_int_equal(fbrl_rapl_error_class(41), FBRL_RAPL_ERRC_OTHER);
    assert_int_equal(fbrl_rapl_error_class(190), FBRL_RAPL_ERRC_COLLISION);
    assert_string_equal(fbrl_recover_kind_name(FBRL_RECOVER_JOINT_LIMIT), "JOINT-LIMIT");
}

static void bad_declarations_get_one_clear_error(void **state)
{
    fixture *f = *state;
    static const struct {
        const char *text, *says;
    } bad[] = {
        {"ON-FAILURE FLAKY BOGUS RETRY 1", "BOGUS is not a failure kind: REACH JOINT-LIMIT"},
        {"ON-FAILURE NOPE REACH SKIP", "NOPE is not a word"},
        {"ON-FAILURE FLAKY REACH JUMP", "JUMP is not an action"},
        {"ON-FAILURE FLAKY REACH RETRY 0", "RETRY needs a count 1..1000"},
        {"ON-FAILURE FLAKY REACH RETRY", "RETRY needs a count"},
        {"ON-FAILURE FLAKY REACH RUN NOPE 1", "RUN needs a recovery word"},
        {"ON-FAILURE FLAKY", "say the step, the kind and the action"},
        {"FAILURE REACH", "REACH is not a failure a plan raises"},
        {": X FAILURE NOPE ;", "NOPE is not a failure a plan raises"},
    };
    assert_int_equal(ev(f, steps), 0);
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(ev(f, bad[i].text), -2);
        if (!strstr(fbrl_vm_last_error(f->vm)->message, bad[i].says))
            fail_msg("%s: said \"%s\"", bad[i].text, fbrl_vm_last_error(f->vm)->message);
    }
    assert_int_equal(f->rc.nrules, 0); /* none of them was kept */
    assert_int_equal(ev(f, "RECOVERY-RULES"), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(retries_are_counted_per_attempt, setup, teardown),
        cmocka_unit_test_setup_teardown(a_recovery_word_runs_before_the_retry, setup, teardown),
        cmocka_unit_test_setup_teardown(the_operator_answers, setup, teardown),
        cmocka_unit_test_setup_teardown(failures_are_classed, setup, teardown),
        cmocka_unit_test_setup_teardown(bad_declarations_get_one_clear_error, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
