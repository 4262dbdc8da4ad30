/* SPDX-License-Identifier: MIT */
/* test_method.c - the method words (tests/forth/method.fs) and their C side: the
 * declared methods and parameters set with their ranges checked. The runs the Forth test
 * makes are the run module's RUN-METHOD (tests/unit/test_run.c tests the run itself). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/method.h"
#include "fbrl/run.h"
#include "fbrl/vm.h"
#include "support/vm_host.h"

#define FORTH_DIR FBRL_TEST_SRCDIR "/tests/forth/"

typedef struct fixture {
    void *mem;
    vmh_text out;
    fbrl_vm *vm;
    fbrl_method_set set;
    fbrl_run run;
} fixture;

static fixture *new_vm(void)
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
    vmh_use_files(&cfg.host);
    assert_int_equal(fbrl_vm_create(&f->vm, &cfg), FBRL_OK);
    assert_int_equal(fbrl_method_install(f->vm, &f->set), FBRL_OK);
    assert_int_equal(fbrl_run_install(&f->run, f->vm, &f->set, NULL, NULL), FBRL_OK);
    return f;
}

static void ok(fixture *f, const char *src)
{
    fbrl_status st = fbrl_vm_eval(f->vm, src, strlen(src));
    if (st != FBRL_OK)
        print_error("'%s': %s\n", src, fbrl_vm_last_error(f->vm)->message);
    assert_int_equal(st, FBRL_OK);
}

static void forth_method_words(void **state)
{
    (void)state;
    fixture *f = new_vm();
    fbrl_cell errors = -1;
    assert_int_equal(fbrl_vm_include(f->vm, FORTH_DIR "tester.fs"), FBRL_OK);
    fbrl_status st = fbrl_vm_include(f->vm, FORTH_DIR "method.fs");
    if (st != FBRL_OK)
        print_error("method.fs: %s (line %lu)\n", fbrl_vm_last_error(f->vm)->message,
                    fbrl_vm_last_error(f->vm)->line);
    assert_int_equal(st, FBRL_OK);
    ok(f, "#ERRORS @");
    assert_int_equal(fbrl_vm_pop(f->vm, &errors), FBRL_OK);
    if (errors != 0)
        print_error("%s", f->out.s);
    assert_int_equal(errors, 0);
    /* EMPTY declared twice is one method */
    assert_non_null(fbrl_method_find(&f->set, "empty"));
    assert_int_equal(f->set.count, 4); /* DEMO EMPTY FAILING PART */
    free(f->mem);
    free(f);
}

static const char method_src[] = "VARIABLE DONE 0 DONE !\n"
                                 ": A 1 DONE +! ; : B DROP 10 DONE +! ;\n"
                                 "METHOD M  the method\n"
                                 "1 8 3 SAMPLES-PARAM N samples  the samples\n"
                                 "5 50 20 PARAM V ml  the volume\n"
                                 "' A STEP First  first\n"
                                 "' B SAMPLE-STEP Each  each sample\n"
                                 "' A STEP Last  last\n"
                                 "END-METHOD\n";

static void declare(fixture *f)
{
    const char *p = method_src, *e;
    while ((e = strchr(p, '\n')) != NULL) { /* one line at a time: a description ends at its line's end */
        assert_int_equal(fbrl_vm_eval(f->vm, p, (size_t)(e - p)), FBRL_OK);
        p = e + 1;
    }
}

static void c_side_sees_the_declaration(void **state)
{
    (void)state;
    fixture *f = new_vm();
    long v = 0;
    declare(f);
    const fbrl_method *m = fbrl_method_find(&f->set, "M");
    assert_non_null(m);
    assert_ptr_equal(fbrl_method_at(&f->set, 0), m);
    assert_null(fbrl_method_at(&f->set, 1));
    assert_string_equal(m->text, "the method");
    assert_int_equal(m->nparams, 2);
    assert_int_equal(m->samples, 0);
    assert_string_equal(m->params[1].name, "V");
    assert_string_equal(m->params[1].unit, "ml");
    assert_string_equal(m->params[1].text, "the volume");
    assert_int_equal(m->params[1].min, 5);
    assert_int_equal(m->params[1].max, 50);
    assert_int_equal(m->nsteps, 3);
    assert_string_equal(m->steps[1].name, "Each");
    assert_true(m->steps[1].per_sample);
    assert_int_equal(fbrl_method_step_runs(&f->set, m, 1), 3);
    assert_int_equal(fbrl_method_step_runs(&f->set, m, 2), 1);
    /* ranges */
    assert_int_equal(fbrl_method_param_set(&f->set, m, 1, 51), FBRL_ERANGE);
    assert_int_equal(fbrl_method_param_set(&f->set, m, 1, 4), FBRL_ERANGE);
    assert_int_equal(fbrl_method_param_get(&f->set, m, 1, &v), FBRL_OK);
    assert_int_equal(v, 20);
    assert_int_equal(fbrl_method_param_set(&f->set, m, 1, 50), FBRL_OK);
    assert_int_equal(fbrl_method_param_set(&f->set, m, 2, 1), FBRL_EINVAL);
    ok(f, "V");
    fbrl_cell c = 0;
    assert_int_equal(fbrl_vm_pop(f->vm, &c), FBRL_OK);
    assert_int_equal(c, 50);
    /* .METHOD shows it */
    f->out.n = 0;
    ok(f, "M .METHOD");
    assert_non_null(strstr(f->out.s, "V                  50 ml       (5..50, default 20) the volume"));
    assert_non_null(strstr(f->out.s, "2. Each           [each sample] each sample"));
    free(f->mem);
    free(f);
}

/* parameters cannot change while their method runs */
static void parameters_are_fixed_while_it_runs(void **state)
{
    (void)state;
    fixture *f = new_vm();
    declare(f);
    ok(f, "METHOD G  sets its own parameter while it runs");
    ok(f, "1 3 2 SAMPLES-PARAM GN n  n");
    ok(f, ": SETGN S\" 1 PARAM! GN\" EVALUATE ; ' SETGN STEP Set  set");
    ok(f, "END-METHOD");
    assert_int_not_equal(fbrl_vm_eval(f->vm, "G RUN-METHOD", 12), FBRL_OK);
    assert_non_null(strstr(fbrl_vm_last_error(f->vm)->message, "GN: G is running"));
    assert_int_equal(fbrl_method_param_set(&f->set, fbrl_method_find(&f->set, "G"), 0, 1), FBRL_OK);
    free(f->mem);
    free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(forth_method_words),
        cmocka_unit_test(c_side_sees_the_declaration),
        cmocka_unit_test(parameters_are_fixed_while_it_runs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
