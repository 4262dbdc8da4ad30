/* SPDX-License-Identifier: MIT */
/* cm3_engine_test.c - the language engine as the Cortex-M3 firmware builds it
 * (FBRL_SMALL_HEADERS, FBRL_NO_HELP, 256-byte lines, 4 nested sources,
 * 2 S" buffers: ports/cortex-m3/CMakeLists.txt), run on the host against the Forth
 * conformance suite in tests/forth and the cases those options change: names that live
 * in the dictionary, MARKER and FORGET taking them away, HELP without texts. The QEMU
 * tests run the same engine on the chip; this one runs it under the host's sanitizers. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/glossary.h"
#include "fbrl/vm.h"
#include "fbrl/vmx.h"
#include "support/vm_host.h"

#define FORTH_DIR FBRL_TEST_SRCDIR "/tests/forth/"
#define VM_BYTES  (1u << 20)

typedef struct fixture {
    void *mem;
    vmh_text out;
    fbrl_vm *vm;
    fbrl_glossary g;
} fixture;

/* No console input: KEY sees the end of input, KEY? nothing waiting. */
static int no_key(void *user)
{
    (void)user;
    return -1;
}

static int no_key_ready(void *user)
{
    (void)user;
    return 0;
}

static fixture *new_vm(void)
{
    fixture *f = calloc(1, sizeof *f);
    fbrl_vm_config cfg;
    assert_non_null(f);
    f->mem = calloc(1, VM_BYTES);
    assert_non_null(f->mem);
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = f->mem;
    cfg.mem_size = VM_BYTES;
    cfg.host.user = &f->out;
    cfg.host.write = vmh_write;
    cfg.host.key = no_key;
    cfg.host.key_ready = no_key_ready;
    vmh_use_files(&cfg.host);
    vmh_use_clock(&cfg.host);
    assert_int_equal(fbrl_vm_create(&f->vm, &cfg), FBRL_OK);
    assert_int_equal(fbrl_vmx_data_words(f->vm), FBRL_OK); /* fbrl.fs tests them too */
    return f;
}

static void free_vm(fixture *f)
{
    free(f->mem);
    free(f);
}

static fbrl_status ev(fixture *f, const char *text) { return fbrl_vm_eval(f->vm, text, strlen(text)); }

static fbrl_cell pop1(fixture *f)
{
    fbrl_cell v = 0;
    assert_int_equal(fbrl_vm_pop(f->vm, &v), FBRL_OK);
    return v;
}

static void run_forth_file(const char *name)
{
    fixture *f = new_vm();
    char path[512];
    assert_int_equal(fbrl_vm_include(f->vm, FORTH_DIR "tester.fs"), FBRL_OK);
    snprintf(path, sizeof path, "%s%s", FORTH_DIR, name);
    fbrl_status st = fbrl_vm_include(f->vm, path);
    if (st != FBRL_OK) {
        const fbrl_vm_error *e = fbrl_vm_last_error(f->vm);
        print_error("%s: error %d (%s) at word '%s' %s:%lu\n", name, e->throw_code, e->message, e->word,
                    e->file, e->line);
    }
    assert_int_equal(st, FBRL_OK);
    assert_int_equal(ev(f, "#ERRORS @ #TESTS @"), FBRL_OK);
    fbrl_cell tests = pop1(f), errors = pop1(f);
    if (errors)
        print_error("%s: %ld failures:\n%s\n", name, (long)errors, f->out.s);
    assert_int_equal(errors, 0);
    assert_true(tests > 10);
    free_vm(f);
}

#define FORTH_TEST(fn, file)     \
    static void fn(void **state) \
    {                            \
        (void)state;             \
        run_forth_file(file);    \
    }
FORTH_TEST(forth_core, "core.fs")
FORTH_TEST(forth_coreext, "coreext.fs")
FORTH_TEST(forth_exception, "exception.fs")
FORTH_TEST(forth_double, "double.fs")
FORTH_TEST(forth_float, "float.fs")
FORTH_TEST(forth_string, "string.fs")
FORTH_TEST(forth_tools, "tools.fs")
FORTH_TEST(forth_fbrl, "fbrl.fs")

/* A header points at its name: a user word's name is in the dictionary, 31 characters
 * still fit, and MARKER / FORGET / a failed definition take the name with the word. */
static void names_in_the_dictionary(void **state)
{
    fixture *f = new_vm();
    (void)state;
    assert_int_equal(ev(f, ": ABCDEFGHIJKLMNOPQRSTUVWXYZ01234 42 ; ABCDEFGHIJKLMNOPQRSTUVWXYZ01234"),
                     FBRL_OK);
    assert_int_equal(pop1(f), 42);
    assert_int_equal(ev(f, ": ABCDEFGHIJKLMNOPQRSTUVWXYZ012345 1 ;"), FBRL_ETHROW); /* 32: too long */
    assert_int_equal(ev(f, "UNUSED MARKER GONE : W1 1 ; CREATE W2 100 ALLOT GONE UNUSED -"), FBRL_OK);
    assert_int_equal(pop1(f), 0); /* everything after the marker, names included, is back */
    assert_int_equal(ev(f, "W1"), FBRL_ETHROW);
    assert_int_equal(ev(f, "VARIABLE U0 UNUSED U0 !"), FBRL_OK);
    assert_int_equal(ev(f, ": BROKEN 1 UNDEFINED-WORD"), FBRL_ETHROW);
    assert_int_equal(ev(f, "UNUSED U0 @ -"), FBRL_OK);
    assert_int_equal(pop1(f), 0);                         /* the failed definition's name went with it */
    assert_int_equal(ev(f, ": w3 7 ; W3 w3 +"), FBRL_OK); /* any case */
    assert_int_equal(pop1(f), 14);
    free_vm(f);
}

/* HELP without texts says so; the stack effects and texts live in docs/glossary.md. */
static void help_without_texts(void **state)
{
    fixture *f = new_vm();
    const char *stack = "x", *help = "x";
    (void)state;
    assert_int_equal(ev(f, "HELP DUP"), FBRL_OK);
    assert_non_null(strstr(f->out.s, "DUP: this build has no HELP texts"));
    assert_int_equal(fbrl_vm_help(f->vm, "DUP", &stack, &help), FBRL_OK);
    assert_string_equal(stack, "");
    assert_string_equal(help, "");
    free_vm(f);
}

/* The glossary's words install and run with the small headers. */
static void glossary_words(void **state)
{
    fixture *f = new_vm();
    (void)state;
    assert_int_equal(fbrl_glossary_install(f->vm, &f->g), FBRL_OK);
    assert_int_equal(ev(f, "CREATE-LOC P 1E0 2E0 3E0 0E0 -90E0 0E0 P DEFINE-LOC P GETY F>S"), FBRL_OK);
    assert_int_equal(pop1(f), 2);
    free_vm(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(forth_core),
        cmocka_unit_test(forth_coreext),
        cmocka_unit_test(forth_exception),
        cmocka_unit_test(forth_double),
        cmocka_unit_test(forth_float),
        cmocka_unit_test(forth_string),
        cmocka_unit_test(forth_tools),
        cmocka_unit_test(forth_fbrl),
        cmocka_unit_test(names_in_the_dictionary),
        cmocka_unit_test(help_without_texts),
        cmocka_unit_test(glossary_words),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
