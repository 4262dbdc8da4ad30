/* SPDX-License-Identifier: MIT */
/* test_vm.c - the FBRL language engine: the Forth conformance suite in tests/forth
 * (each file must report zero failures) and the C embedding API. */
/* ctest-labels: threads */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <pthread.h>
#include <sys/resource.h>
#include <sys/mman.h>
#include <cmocka.h>

#include "fbrl/vm.h"
#include "fbrl/vmx.h"
#include "support/vm_host.h"
#include "mon_files.h"

#define FORTH_DIR FBRL_TEST_SRCDIR "/tests/forth/"

/* ---- a host: output into a buffer, keys from a string, files and clock (support/vm_host.h) ---- */
typedef struct host {
    vmh_text out;
    const char *keys; /* input for KEY/ACCEPT */
} host;

static void h_write(void *user, const char *s, size_t n)
{
    host *h = user;
    vmh_put(&h->out, s, n);
}

static int h_key(void *user)
{
    host *h = user;
    if (!h->keys || !*h->keys)
        return -1;
    return (unsigned char)*h->keys++;
}

static int h_key_ready(void *user)
{
    host *h = user;
    return h->keys && *h->keys;
}

typedef struct fixture {
    void *mem;
    host h;
    fbrl_vm *vm;
} fixture;

static fixture *new_vm_clock(size_t mem_size, uint64_t (*now_us)(void *), void (*sleep_ms)(void *, uint32_t));

static fixture *new_vm(size_t mem_size) { return new_vm_clock(mem_size, NULL, NULL); }

/* now_us and sleep_ms: the host's clock (NULL: the real one) */
static fixture *new_vm_clock(size_t mem_size, uint64_t (*now_us)(void *), void (*sleep_ms)(void *, uint32_t))
{
    fixture *f = calloc(1, sizeof *f);
    assert_non_null(f);
    f->mem = malloc(mem_size);
    assert_non_null(f->mem);
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = f->mem;
    cfg.mem_size = mem_size;
    cfg.host.user = &f->h;
    cfg.host.write = h_write;
    cfg.host.key = h_key;
    cfg.host.key_ready = h_key_ready;
    vmh_use_files(&cfg.host);
    vmh_use_clock(&cfg.host);
    if (now_us)
        cfg.host.now_us = now_us, cfg.host.sleep_ms = sleep_ms;
    cfg.host.files = mon_files(); /* fbrlmon's file system for the standard FILE words */
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

/* ---- the Forth suite ---- */
static void run_forth_file(const char *name)
{
    fixture *f = new_vm(4 << 20);
    char path[512];
    fbrl_status st = fbrl_vm_include(f->vm, FORTH_DIR "tester.fs");
    assert_int_equal(st, FBRL_OK);
    snprintf(path, sizeof path, "%s%s", FORTH_DIR, name);
    st = fbrl_vm_include(f->vm, path);
    if (st != FBRL_OK) {
        const fbrl_vm_error *e = fbrl_vm_last_error(f->vm);
        print_error("%s: error %d (%s) at word '%s' %s:%lu\n", name, e->throw_code, e->message, e->word,
                    e->file, e->line);
    }
    assert_int_equal(st, FBRL_OK);
    assert_int_equal(ev(f, "#ERRORS @ #TESTS @"), FBRL_OK);
    fbrl_cell tests = pop1(f), errors = pop1(f);
    if (errors)
        print_error("%s: %ld failures:\n%s\n", name, (long)errors, f->h.out.s);
    assert_int_equal(errors, 0);
    assert_true(tests > 10);
    print_message("%s: %ld tests passed\n", name, (long)tests);
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
FORTH_TEST(forth_search, "search.fs")
FORTH_TEST(forth_locals, "locals.fs")
FORTH_TEST(forth_memory, "memory.fs")
FORTH_TEST(forth_file, "file.fs")

/* ---- the C API ---- */
static void create_rejects_bad_config(void **state)
{
    (void)state;
    static unsigned char small[4096];
    fbrl_vm *vm;
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    assert_int_equal(fbrl_vm_create(&vm, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_vm_create(&vm, &cfg), FBRL_EINVAL);
    cfg.mem = small;
    cfg.mem_size = sizeof small;
    assert_int_equal(fbrl_vm_create(&vm, &cfg), FBRL_ENOSPC);
}

/* The caller's promise of zeroed memory (mem_zeroed) lets a big dictionary cost
 * only the pages a program uses; without it the engine clears the block itself. */
static long max_rss_kb(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (long)ru.ru_maxrss; /* kilobytes on Linux */
}

static fbrl_cell eval_pop(fbrl_vm *vm, const char *text)
{
    fbrl_cell v = 0;
    assert_int_equal(fbrl_vm_eval(vm, text, strlen(text)), FBRL_OK);
    assert_int_equal(fbrl_vm_pop(vm, &v), FBRL_OK);
    return v;
}

static void zeroed_memory_is_used_lazily(void **state)
{
    (void)state;
    enum { GARBAGE = 0xA5, SMALL = 1 << 20, BIG = 64 << 20 };
    fbrl_vm *vm;
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    /* Not promised zero: the engine clears the dictionary, whatever the block held. */
    void *mem = malloc(SMALL);
    assert_non_null(mem);
    memset(mem, GARBAGE, SMALL);
    cfg.mem = mem;
    cfg.mem_size = SMALL;
    assert_int_equal(fbrl_vm_create(&vm, &cfg), FBRL_OK);
    assert_int_equal(eval_pop(vm, "HERE 4096 + @  UNUSED 64 - HERE + @ OR"), 0);
    free(mem);

    /* Promised zero: a 64 MB dictionary works in full, but creating it and
     * running a little code touches a small part of it. */
    long rss0 = max_rss_kb();
    /* Fresh anonymous pages, as fbrlmon's calloc gets them from the OS: a sanitizer's
     * calloc (TSan's) clears the block itself and would touch every page. */
    mem = mmap(NULL, BIG, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    assert_true(mem != MAP_FAILED);
    cfg.mem = mem;
    cfg.mem_size = BIG;
    cfg.mem_zeroed = 1;
    assert_int_equal(fbrl_vm_create(&vm, &cfg), FBRL_OK);
    assert_int_equal(eval_pop(vm, ": SQ DUP * ; 12 SQ"), 144);
    assert_int_equal(eval_pop(vm, "HERE 4096 + @  UNUSED 64 - HERE + @ OR"), 0);
    fbrl_cell unused = eval_pop(vm, "UNUSED");
    assert_true(unused > BIG - (1 << 20));
#ifdef __linux__
    long grew_kb = max_rss_kb() - rss0;
    print_message("64 MB dictionary: peak memory grew by %ld KB\n", grew_kb);
    assert_true(grew_kb < 24 * 1024); /* clearing it would have added 65536 KB */
#else
    (void)rss0;
#endif
    /* ... and all of it can be filled */
    assert_int_equal(fbrl_vm_eval(vm, "UNUSED 4096 - ALLOT  1 ,", 24), FBRL_OK);
    munmap(mem, BIG);
}

static int count_words(void *ctx, const char *name, size_t len)
{
    (void)name;
    (void)len;
    ++*(int *)ctx;
    return 0;
}

static void size_for_is_enough(void **state)
{
    (void)state;
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    size_t need = fbrl_vm_size_for(&cfg, 10000);
    void *mem = malloc(need);
    cfg.mem = mem;
    cfg.mem_size = need;
    fbrl_vm *vm;
    assert_int_equal(fbrl_vm_create(&vm, &cfg), FBRL_OK);
    assert_int_equal(fbrl_vm_eval(vm, "UNUSED", 6), FBRL_OK);
    fbrl_cell unused;
    assert_int_equal(fbrl_vm_pop(vm, &unused), FBRL_OK);
    assert_true(unused >= 10000);
    /* dictionary exhaustion is an error, not a crash, and the VM still works */
    assert_int_equal(fbrl_vm_eval(vm, "UNUSED 16 + ALLOT", 17), FBRL_ETHROW);
    assert_int_equal(fbrl_vm_last_error(vm)->throw_code, -8);
    const char *fill = ": F BEGIN 1 , AGAIN ; F";
    assert_int_equal(fbrl_vm_eval(vm, fill, strlen(fill)), FBRL_ETHROW);
    assert_int_equal(fbrl_vm_last_error(vm)->throw_code, -8);
    assert_int_equal(fbrl_vm_eval(vm, "1 2 +", 5), FBRL_OK);
    assert_int_equal(fbrl_vm_pop(vm, &unused), FBRL_OK);
    assert_int_equal(unused, 3);
    int n = 0;
    fbrl_vm_words(vm, count_words, &n);
    assert_true(n > 300);
    free(mem);
    /* too small by a little */
    cfg.mem_size = fbrl_vm_size_for(&cfg, 0) / 2;
    mem = malloc(cfg.mem_size);
    cfg.mem = mem;
    assert_int_equal(fbrl_vm_create(&vm, &cfg), FBRL_ENOSPC);
    free(mem);
}

static void two_vms_are_independent(void **state)
{
    (void)state;
    fixture *a = new_vm(1 << 20), *b = new_vm(1 << 20);
    assert_int_equal(ev(a, ": TWICE 2 * ; 21 TWICE HEX"), FBRL_OK);
    assert_int_equal(ev(b, "TWICE"), FBRL_ETHROW);
    assert_int_equal(fbrl_vm_last_error(b->vm)->throw_code, -13);
    assert_int_equal(ev(b, "10"), FBRL_OK);
    assert_int_equal(pop1(b), 10); /* b is still decimal */
    assert_int_equal(ev(a, "10"), FBRL_OK);
    assert_int_equal(pop1(a), 16);
    assert_int_equal(pop1(a), 42);
    free_vm(a);
    free_vm(b);
}

static fbrl_status c_add(fbrl_vm *vm, void *arg)
{
    fbrl_cell x, y;
    fbrl_status st;
    if ((st = fbrl_vm_pop(vm, &y)) || (st = fbrl_vm_pop(vm, &x)))
        return fbrl_vm_throw(vm, -4, NULL);
    return fbrl_vm_push(vm, x + y + *(fbrl_cell *)arg);
}

static fbrl_status c_fail(fbrl_vm *vm, void *arg)
{
    (void)arg;
    return fbrl_vm_throw(vm, -1001, "arm is not homed");
}

static fbrl_status c_offline(fbrl_vm *vm, void *arg)
{
    (void)vm;
    (void)arg;
    return FBRL_EOFFLINE;
}

static fbrl_status c_parse(fbrl_vm *vm, void *arg)
{
    const char *name;
    size_t len;
    (void)arg;
    fbrl_vm_parse_name(vm, &name, &len);
    return fbrl_vm_push(vm, (fbrl_cell)len);
}

/* The dictionary's index grows with it (dict.c): 30,000 words, shadowed names, synonyms made
 * just as the index doubles, a MARKER that shrinks it again: find gives the newest word of
 * each name all along, and forgotten words are gone. */
static int is_power_of_two(size_t n) { return n && !(n & (n - 1)); }

static void dictionary_index_grows(void **state)
{
    (void)state;
    enum { N = 30000 };
    static fbrl_cell want[N], want_half[N];
    fixture *f = new_vm(16 << 20);
    char src[128];
    size_t synonyms_at_doubling = 0;
    for (int k = 0; k < N; k++) {
        snprintf(src, sizeof src, ": W%d %d ;", k, k);
        assert_int_equal(ev(f, src), FBRL_OK);
        want[k] = k;
        if (is_power_of_two(fbrl_vm_word_count(f->vm) + 1)) { /* the next header doubles the index */
            snprintf(src, sizeof src, "SYNONYM S%d W%d", k, k);
            assert_int_equal(ev(f, src), FBRL_OK);
            synonyms_at_doubling++;
            for (int i = 0; i <= k; i++) { /* before anything else grows it */
                snprintf(src, sizeof src, "W%d", i);
                assert_int_equal(eval_pop(f->vm, src), want[i]);
            }
        }
        if (k % 7 == 3) { /* a newer word of an older name shadows it */
            snprintf(src, sizeof src, ": W%d %d ;", k / 2, -k);
            assert_int_equal(ev(f, src), FBRL_OK);
            want[k / 2] = -k;
        }
        if (k == N / 2) {
            assert_int_equal(ev(f, "MARKER HALF"), FBRL_OK);
            memcpy(want_half, want, sizeof want);
        }
    }
    assert_true(synonyms_at_doubling >= 4);
    for (int k = 0; k < N; k++) {
        snprintf(src, sizeof src, "W%d", k);
        assert_int_equal(eval_pop(f->vm, src), want[k]);
        snprintf(src, sizeof src, "S%d", k);
        if (fbrl_vm_help(f->vm, src, NULL, NULL) == FBRL_OK)
            assert_int_equal(eval_pop(f->vm, src), k); /* W(k) as it was when the synonym was made */
    }
    /* forget the second half: its words are gone, the first half's are found as they were */
    size_t before = fbrl_vm_word_count(f->vm);
    assert_int_equal(ev(f, "HALF"), FBRL_OK);
    assert_true(fbrl_vm_word_count(f->vm) < before / 2 + 1000);
    for (int k = 0; k < N; k++) {
        snprintf(src, sizeof src, "W%d", k);
        if (k > N / 2)
            assert_int_equal(fbrl_vm_help(f->vm, src, NULL, NULL), FBRL_ENOENT);
        else
            assert_int_equal(eval_pop(f->vm, src), want_half[k]);
    }
    /* and it grows again */
    for (int k = 0; k < N / 2; k++) {
        snprintf(src, sizeof src, ": X%d %d ;", k, 3 * k);
        assert_int_equal(ev(f, src), FBRL_OK);
    }
    for (int k = 0; k < N / 2; k++) {
        snprintf(src, sizeof src, "X%d", k);
        assert_int_equal(eval_pop(f->vm, src), 3 * k);
    }
    assert_int_equal(eval_pop(f->vm, "1 2 + DUP *"), 9); /* the built-in words too */
    free_vm(f);
}

static void c_words(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    static fbrl_cell bias = 100;
    assert_int_equal(fbrl_vm_define(f->vm, "C-ADD", c_add, &bias, "( a b -- a+b+100 )", "adds with bias"),
                     FBRL_OK);
    assert_int_equal(fbrl_vm_define(f->vm, "C-FAIL", c_fail, NULL, "( -- )", "always fails"), FBRL_OK);
    assert_int_equal(fbrl_vm_define(f->vm, "C-OFF", c_offline, NULL, "( -- )", "offline"), FBRL_OK);
    assert_int_equal(fbrl_vm_define(f->vm, "C-PARSE", c_parse, NULL, "( \"name\" -- len )", "parses"),
                     FBRL_OK);
    assert_int_equal(fbrl_vm_define(f->vm, "BAD NAME", c_add, NULL, "", ""), FBRL_ENAME);
    assert_int_equal(fbrl_vm_define(f->vm, "", c_add, NULL, "", ""), FBRL_ENAME);
    assert_int_equal(fbrl_vm_define(f->vm, "X", NULL, NULL, "", ""), FBRL_EINVAL);
    assert_int_equal(ev(f, "1 2 c-add : T C-ADD ; 3 4 T C-PARSE abcde"), FBRL_OK);
    assert_int_equal(pop1(f), 5);
    assert_int_equal(pop1(f), 107);
    assert_int_equal(pop1(f), 103);
    const char *se, *help;
    assert_int_equal(fbrl_vm_help(f->vm, "c-add", &se, &help), FBRL_OK);
    assert_string_equal(se, "( a b -- a+b+100 )");
    assert_string_equal(help, "adds with bias");
    assert_int_equal(fbrl_vm_help(f->vm, "nope", &se, &help), FBRL_ENOENT);
    /* errors raised in C carry their code and message */
    assert_int_equal(ev(f, "1 2 C-FAIL 3"), FBRL_ETHROW);
    assert_int_equal(fbrl_vm_last_error(f->vm)->throw_code, -1001);
    assert_string_equal(fbrl_vm_last_error(f->vm)->message, "arm is not homed");
    assert_string_equal(fbrl_vm_last_error(f->vm)->word, "C-FAIL");
    assert_int_equal(fbrl_vm_depth(f->vm), 0);
    /* a plain status becomes that status, catchable in Forth */
    assert_int_equal(ev(f, "C-OFF"), FBRL_EOFFLINE);
    assert_string_equal(fbrl_vm_last_error(f->vm)->message, fbrl_status_str(FBRL_EOFFLINE));
    assert_int_equal(ev(f, "' C-FAIL CATCH ' C-OFF CATCH"), FBRL_OK);
    assert_int_equal(pop1(f), -300 + FBRL_EOFFLINE);
    assert_int_equal(pop1(f), -1001);
    assert_int_equal(ev(f, "C-ADD"), FBRL_ETHROW);
    assert_int_equal(fbrl_vm_last_error(f->vm)->throw_code, -4);
    free_vm(f);
}

static void api_stacks(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    double d;
    fbrl_cell v;
    assert_int_equal(fbrl_vm_pop(f->vm, &v), FBRL_EEMPTY);
    assert_int_equal(fbrl_vm_fpop(f->vm, &d), FBRL_EEMPTY);
    assert_int_equal(fbrl_vm_fpush(f->vm, 1.0 / 0.0), FBRL_ENONFINITE);
    assert_int_equal(fbrl_vm_fpush(f->vm, 2.5), FBRL_OK);
    assert_int_equal(fbrl_vm_push(f->vm, 3), FBRL_OK);
    assert_int_equal(ev(f, "S>F F* F>S"), FBRL_OK);
    assert_int_equal(fbrl_vm_depth(f->vm), 1);
    assert_int_equal(fbrl_vm_fdepth(f->vm), 0);
    assert_int_equal(pop1(f), 7);
    for (int i = 0; i < 256; i++)
        assert_int_equal(fbrl_vm_push(f->vm, i), FBRL_OK);
    assert_int_equal(fbrl_vm_push(f->vm, 0), FBRL_ENOMEM);
    assert_int_equal(ev(f, "1"), FBRL_ETHROW);
    assert_int_equal(fbrl_vm_last_error(f->vm)->throw_code, -3);
    assert_int_equal(fbrl_vm_depth(f->vm), 0);
    /* fbrl_vm_addr only maps the VM's own data space */
    assert_int_equal(ev(f, "HERE"), FBRL_OK);
    v = pop1(f);
    assert_non_null(fbrl_vm_addr(f->vm, v, 16));
    assert_null(fbrl_vm_addr(f->vm, 0, 1));
    assert_null(fbrl_vm_addr(f->vm, (fbrl_cell)f, 1));
    assert_null(fbrl_vm_addr(f->vm, v, (size_t)1 << 40));
    free_vm(f);
}

static void errors_carry_word_file_line(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    const fbrl_vm_error *e = fbrl_vm_last_error(f->vm);
    assert_int_equal(ev(f, "1 2\n3 4\n: X 5 FROB ;\n6"), FBRL_ETHROW);
    assert_int_equal(e->throw_code, -13);
    assert_string_equal(e->message, "undefined word");
    assert_string_equal(e->word, "FROB");
    assert_string_equal(e->file, "");
    assert_int_equal(e->line, 3);
    assert_int_equal(fbrl_vm_depth(f->vm), 0);
    assert_false(fbrl_vm_compiling(f->vm));
    assert_int_equal(ev(f, "X"), FBRL_ETHROW); /* the half-made X is gone */
    assert_string_equal(e->word, "X");

    assert_int_equal(fbrl_vm_include(f->vm, FORTH_DIR "files/bad.fs"), FBRL_ETHROW);
    assert_int_equal(e->throw_code, -13);
    assert_string_equal(e->word, "NO-SUCH-WORD");
    assert_string_equal(e->file, FORTH_DIR "files/bad.fs");
    assert_int_equal(e->line, 4);
    assert_int_equal(ev(f, "GOOD"), FBRL_OK); /* words before the error stay */
    assert_int_equal(pop1(f), 1);
    assert_int_equal(ev(f, "HALF"), FBRL_ETHROW);

    /* errors in nested files name the inner file */
    assert_int_equal(ev(f, "S\" " FORTH_DIR "files/bad.fs\" INCLUDED"), FBRL_ETHROW);
    assert_string_equal(e->file, FORTH_DIR "files/bad.fs");
    assert_int_equal(e->line, 4);

    assert_int_equal(fbrl_vm_include(f->vm, FORTH_DIR "files/unterminated.fs"), FBRL_ETHROW);
    assert_int_equal(e->throw_code, -39);
    assert_false(fbrl_vm_compiling(f->vm));
    assert_int_equal(ev(f, "OPEN"), FBRL_ETHROW);

    assert_int_equal(fbrl_vm_include(f->vm, FORTH_DIR "files/no-such-file.fs"), FBRL_ETHROW);
    assert_int_equal(e->throw_code, -38);

    /* ABORT" carries its text */
    assert_int_equal(ev(f, ": CHECK ABORT\" gripper open\" ; 0 CHECK 1 CHECK"), FBRL_ETHROW);
    assert_int_equal(e->throw_code, -2);
    assert_string_equal(e->message, "gripper open");
    assert_string_equal(e->word, "CHECK");
    free_vm(f);
}

/* An error inside colon definitions names the word it happened in and keeps the
 * chain of calls with their files and lines, and the data stack then. */
static void backtraces_name_the_failing_word(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    const fbrl_vm_error *e = fbrl_vm_last_error(f->vm);
    fbrl_vm_frame bt[FBRL_VM_BACKTRACE_MAX];
    fbrl_cell cells[FBRL_VM_BACKTRACE_STACK];
    size_t omitted = 99;
    const char *file = FORTH_DIR "files/chain.fs";

    assert_int_equal(fbrl_vm_include(f->vm, file), FBRL_OK);
    assert_int_equal(ev(f, "7 OUTER"), FBRL_ETHROW);
    assert_int_equal(e->throw_code, -10);
    assert_string_equal(e->word, "INNER"); /* not OUTER, the word typed */
    assert_int_equal(fbrl_vm_backtrace(f->vm, bt, 4, &omitted), 3);
    assert_int_equal(omitted, 0);
    assert_string_equal(bt[0].word, "INNER");
    assert_string_equal(bt[0].file, file);
    assert_int_equal(bt[0].line, 2);
    assert_string_equal(bt[1].word, "MIDDLE");
    assert_int_equal(bt[1].line, 5); /* the line of the call, not of the colon */
    assert_string_equal(bt[2].word, "OUTER");
    assert_int_equal(bt[2].line, 6);
    assert_int_equal(fbrl_vm_error_stack(f->vm, cells, FBRL_VM_BACKTRACE_STACK), 3);
    assert_int_equal(cells[0], 7);
    assert_int_equal(cells[1], 8);
    assert_int_equal(cells[2], 0);
    assert_int_equal(fbrl_vm_error_stack(f->vm, cells, 1), 3); /* the top cell only */
    assert_int_equal(cells[0], 0);

    /* caught: no backtrace is left over */
    assert_int_equal(ev(f, "CAUGHT"), FBRL_OK);
    assert_int_equal(pop1(f), -10);
    assert_int_equal(fbrl_vm_backtrace(f->vm, bt, 4, NULL), 0);
    /* outside any definition: none */
    assert_int_equal(ev(f, "FROB"), FBRL_ETHROW);
    assert_int_equal(fbrl_vm_backtrace(f->vm, bt, 4, NULL), 0);
    assert_string_equal(e->word, "FROB");

    /* typed words have no file; loop parameters and >R values are not callers */
    assert_int_equal(ev(f, ": T1 5 0 DO I >R 1 0 / LOOP ;\n: T2\n T1 ;\nT2"), FBRL_ETHROW);
    assert_int_equal(fbrl_vm_backtrace(f->vm, bt, 4, NULL), 2);
    assert_string_equal(bt[0].word, "T1");
    assert_string_equal(bt[0].file, "");
    assert_int_equal(bt[0].line, 1);
    assert_string_equal(bt[1].word, "T2");
    assert_int_equal(bt[1].line, 3);

    /* a deep chain keeps its innermost and outermost calls */
    assert_int_equal(ev(f, ": R DUP IF 1- RECURSE ELSE 1 0 / THEN ; 40 R"), FBRL_ETHROW);
    assert_int_equal(fbrl_vm_backtrace(f->vm, bt, FBRL_VM_BACKTRACE_MAX, &omitted), FBRL_VM_BACKTRACE_MAX);
    assert_int_equal(omitted, 41 - FBRL_VM_BACKTRACE_MAX);
    assert_string_equal(bt[FBRL_VM_BACKTRACE_MAX - 1].word, "R");
    free_vm(f);
}

static void include_relative_and_require(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    assert_int_equal(fbrl_vm_include(f->vm, FORTH_DIR "files/outer.fs"), FBRL_OK);
    assert_int_equal(ev(f, "OUTER-SUM INNER-LOADS @"), FBRL_OK);
    assert_int_equal(pop1(f), 1);
    assert_int_equal(pop1(f), 3);
    assert_int_equal(ev(f, "S\" " FORTH_DIR "files/inner.fs\" REQUIRED INNER-LOADS @"), FBRL_OK);
    assert_int_equal(pop1(f), 1);
    assert_int_equal(ev(f, "S\" " FORTH_DIR "files/inner.fs\" INCLUDED INNER-LOADS @"), FBRL_OK);
    assert_int_equal(pop1(f), 2);
    free_vm(f);
}

static void multi_line_definitions_and_bye(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    assert_int_equal(ev(f, ": SQ ( n -- n*n ) \\ square a number"), FBRL_OK);
    assert_true(fbrl_vm_compiling(f->vm));
    assert_int_equal(ev(f, "  DUP *"), FBRL_OK);
    assert_int_equal(ev(f, ";"), FBRL_OK);
    assert_false(fbrl_vm_compiling(f->vm));
    assert_int_equal(ev(f, "7 SQ"), FBRL_OK);
    assert_int_equal(pop1(f), 49);
    const char *se, *help;
    assert_int_equal(fbrl_vm_help(f->vm, "sq", &se, &help), FBRL_OK);
    assert_string_equal(se, "( n -- n*n )");
    assert_string_equal(help, "square a number");
    f->h.out.n = 0;
    assert_int_equal(ev(f, "HELP SQ HELP DUP"), FBRL_OK);
    assert_string_equal(f->h.out.s,
                        "SQ ( n -- n*n ) square a number\nDUP ( x -- x x ) duplicate the top cell\n");
    /* a definition abandoned in interpretation state */
    assert_int_equal(ev(f, ": HALF 1 ["), FBRL_OK);
    assert_true(fbrl_vm_compiling(f->vm));
    assert_int_equal(ev(f, ": WHOLE 2 ; WHOLE"), FBRL_OK);
    assert_false(fbrl_vm_compiling(f->vm));
    assert_int_equal(pop1(f), 2);
    assert_int_equal(ev(f, "HALF"), FBRL_ETHROW);
    /* fbrl_vm_reset drops an open definition and the stacks */
    assert_int_equal(ev(f, "1 2 3 : OPEN 4"), FBRL_OK);
    assert_true(fbrl_vm_compiling(f->vm));
    fbrl_vm_reset(f->vm);
    assert_false(fbrl_vm_compiling(f->vm));
    assert_int_equal(fbrl_vm_depth(f->vm), 0);
    assert_int_equal(ev(f, "OPEN"), FBRL_ETHROW);
    assert_int_equal(ev(f, "#! /usr/bin/env fbrlmon\n5"), FBRL_OK);
    assert_int_equal(pop1(f), 5);
    assert_int_equal(ev(f, "1 BYE 2"), FBRL_OK);
    assert_true(fbrl_vm_bye(f->vm));
    assert_int_equal(fbrl_vm_depth(f->vm), 1);
    free_vm(f);
}

static int check_help(void *ctx, const char *name, size_t len)
{
    fixture *f = ctx;
    char n[64];
    const char *se = NULL, *help = NULL;
    memcpy(n, name, len);
    n[len] = 0;
    assert_int_equal(fbrl_vm_help(f->vm, n, &se, &help), FBRL_OK);
    if (!se[0] || strlen(help) < 4)
        print_error("word %s lacks help\n", n);
    assert_true(se[0] == '(');
    assert_true(strlen(help) >= 4);
    return 0;
}

static void every_word_has_help(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    fbrl_vm_words(f->vm, check_help, f);
    f->h.out.n = 0;
    assert_int_equal(ev(f, "WORDS"), FBRL_OK);
    assert_non_null(strstr(f->h.out.s, " DUP "));
    free_vm(f);
}

/* What the printing words print. */
static void expect_output(fixture *f, const char *src, const char *want)
{
    f->h.out.n = 0;
    f->h.out.s[0] = 0;
    fbrl_status st = ev(f, src);
    if (st != FBRL_OK)
        print_error("'%s': %s\n", src, fbrl_vm_last_error(f->vm)->message);
    assert_int_equal(st, FBRL_OK);
    if (strcmp(f->h.out.s, want) != 0)
        print_error("'%s' printed '%s', expected '%s'\n", src, f->h.out.s, want);
    assert_string_equal(f->h.out.s, want);
}

static void output_formats(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    expect_output(f, "1 . -1 . 0 .", "1 -1 0 ");
    expect_output(f, "-1 U.", sizeof(fbrl_cell) == 8 ? "18446744073709551615 " : "4294967295 ");
    expect_output(f, "42 5 .R -42 5 .R 7 3 U.R 12345 2 .R", "   42  -42  712345");
    expect_output(f, "255 HEX . -1 . DECIMAL", "FF -1 ");
    expect_output(f, "5 2 BASE ! . DECIMAL 35 36 BASE ! . DECIMAL", "101 Z ");
    expect_output(f, "123. D. -5. D. 7. 4 D.R 5. UD.", "123 -5    75 ");
    expect_output(f, "1 2 3 .S DROP DROP DROP", "<3> 1 2 3 \n");
    expect_output(f, "VARIABLE V 77 V ! V ?", "77 ");
    expect_output(f, "65 EMIT 3 SPACES 66 EMIT CR S\" ok\" TYPE SPACE .( paren) .\" x\"", "A   B\nok parenx");
    expect_output(f, ": DQ .\" in def\" ; DQ", "in def");
    expect_output(f, "1.5E0 F. 2E0 F. 0.125E0 F. 1234.5E0 F. -3.25E0 F. 0E0 F.",
                  "1.5 2. 0.125 1234.5 -3.25 0. ");
    expect_output(f, "1234.5E0 FS. 1234.5E0 FE. 0.5E0 FE. -2E0 FS.",
                  "1.23450E3 1.23450E3 500.000E-3 -2.00000E0 ");
    expect_output(f, "3 SET-PRECISION 3.14159E0 F. 2E0 FSQRT FS. 6 SET-PRECISION", "3.14 1.41E0 ");
    expect_output(f, "1E0 2E0 .S FDROP FDROP", "<0> F: <2> 1.00000E0 2.00000E0 \n");
    expect_output(f, ": SQ ( n -- n*n ) DUP * ; SEE SQ", ": SQ DUP * ;\n");
    expect_output(f, ": SW 1 IF 2 ELSE 3 THEN S\" s\" ; SEE SW",
                  ": SW 1 0BRANCH(4) 2 BRANCH(2) 3 S\" s\" ;\n");
    expect_output(f, "5 CONSTANT FIVE SEE FIVE", "FIVE is a constant = 5\n");
    expect_output(f, "HELP SQ", "SQ ( n -- n*n ) colon definition\n");
    expect_output(f, "HELP ENQ", "ENQ ( c q-addr -- ) add a character to the queue (throws when full)\n");
    assert_int_equal(ev(f, "CREATE DD 65 C, 66 C,"), FBRL_OK);
    f->h.out.n = 0;
    assert_int_equal(ev(f, "DD 2 DUMP"), FBRL_OK);
    assert_non_null(strstr(f->h.out.s, " 41 42 "));
    assert_non_null(strstr(f->h.out.s, "AB\n"));
    f->h.out.n = 0;
    assert_int_equal(ev(f, ": NEWEST ; WORDS"), FBRL_OK);
    assert_int_equal(strncmp(f->h.out.s, "NEWEST DD ", 10), 0);
    free_vm(f);
}

/* EKEY decodes the terminal's cursor and function keys; other bytes are characters. */
static void ekey_decodes_terminal_keys(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    f->h.keys = "\033[Ax\033OP\033[3~\033[1;5C";
    assert_int_equal(ev(f, "EKEY K-UP = EKEY EKEY K-F1 = EKEY K-DELETE = EKEY K-RIGHT K-CTRL-MASK OR ="),
                     FBRL_OK);
    for (int i = 0; i < 3; i++) /* F1, DELETE, ctrl-RIGHT */
        assert_int_equal(pop1(f), -1);
    assert_int_equal(pop1(f), 'x');
    assert_int_equal(pop1(f), -1);
    assert_int_equal(ev(f, "3 4 AT-XY PAGE"), FBRL_OK);
    assert_string_equal(f->h.out.s, "\033[5;4H\033[2J\033[H");
    free_vm(f);
}

static void console_input(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    f->h.keys = "xyz\nHello arm\nrest";
    assert_int_equal(ev(f, "KEY KEY? PAD 40 ACCEPT PAD SWAP"), FBRL_OK);
    fbrl_cell n = pop1(f), a = pop1(f);
    assert_int_equal(n, 2);
    assert_memory_equal((void *)a, "yz", 2);
    assert_int_equal(pop1(f), -1);
    assert_int_equal(pop1(f), 'x');
    assert_int_equal(ev(f, "20 STRING S S GET-STRING S STRING-TEXT"), FBRL_OK);
    n = pop1(f);
    a = pop1(f);
    assert_int_equal(n, 9);
    assert_memory_equal((void *)a, "Hello arm", 9);
    assert_int_equal(ev(f, "PAD 2 ACCEPT"), FBRL_OK); /* keeps 2 of "rest" */
    assert_int_equal(pop1(f), 2);
    assert_int_equal(ev(f, "KEY"), FBRL_ETHROW); /* end of input */
    assert_int_equal(fbrl_vm_last_error(f->vm)->throw_code, -57);
    free_vm(f);
}

/* Wrong programs must give errors, never crashes (run under ASan+UBSan in CI). */
/* The compiler fuses common pairs (a literal and an operator, a comparison and a
 * branch) and folds literals; each fused form must do exactly what the words do
 * one at a time (run here through EXECUTE, which nothing fuses), including errors. */
static void fused_code_keeps_meaning(void **state)
{
    (void)state;
    static const char *const binops[] = {"+", "-", "*", "AND", "=", "<>", "<", ">"};
    static const fbrl_cell vals[] = {0, 1, -1, 2, 7, -9, 1000000007, INTPTR_MAX, INTPTR_MIN};
    fixture *f = new_vm(1 << 20);
    char src[256];
    for (size_t o = 0; o < sizeof binops / sizeof binops[0]; o++) {
        for (size_t i = 0; i < sizeof vals / sizeof vals[0]; i++) {
            /* x LIT op  and  x y op IF ... THEN */
            snprintf(src, sizeof src,
                     ": F1 %ld %s ; : F2 %ld %s IF 1 ELSE 2 THEN ; : F3 %s IF 1 ELSE 2 THEN ;", (long)vals[i],
                     binops[o], (long)vals[i], binops[o], binops[o]);
            assert_int_equal(ev(f, src), FBRL_OK);
            for (size_t j = 0; j < sizeof vals / sizeof vals[0]; j++) {
                snprintf(src, sizeof src, "%ld F1  %ld %ld ' %s EXECUTE", (long)vals[j], (long)vals[j],
                         (long)vals[i], binops[o]);
                fbrl_cell want = eval_pop(f->vm, src);
                assert_int_equal(pop1(f), want);
                snprintf(src, sizeof src, "%ld F2  %ld %ld F3", (long)vals[j], (long)vals[j], (long)vals[i]);
                want = eval_pop(f->vm, src);
                assert_int_equal(pop1(f), want);
                assert_int_equal(fbrl_vm_depth(f->vm), 0);
            }
            /* an empty stack is still an underflow */
            assert_int_equal(ev(f, "F1"), FBRL_ETHROW);
            assert_int_equal(fbrl_vm_last_error(f->vm)->throw_code, -4);
            assert_int_equal(ev(f, "1 F3"), FBRL_ETHROW);
            assert_int_equal(fbrl_vm_last_error(f->vm)->throw_code, -4);
        }
    }
    /* folded literals and PICK with a literal */
    assert_int_equal(eval_pop(f->vm, ": G1 3 CELLS 1+ 2* NEGATE ; G1"),
                     -2 * (3 * (fbrl_cell)sizeof(fbrl_cell) + 1));
    assert_int_equal(eval_pop(f->vm, ": G2 10 20 30 2 PICK 1 PICK 0 PICK ; G2"), 30);
    static const fbrl_cell picked[] = {30, 10, 30, 20, 10};
    for (size_t i = 0; i < sizeof picked / sizeof picked[0]; i++)
        assert_int_equal(pop1(f), picked[i]);
    assert_int_equal(ev(f, ": G3 2 PICK ; 1 2 G3"), FBRL_ETHROW);
    assert_int_equal(fbrl_vm_last_error(f->vm)->throw_code, -4);
    assert_int_equal(eval_pop(f->vm, "VARIABLE V 41 V ! : G4 V @ 1+ DUP V ! ; G4"), 42);
    /* a branch target between a literal and its operator must stay a separate op */
    assert_int_equal(eval_pop(f->vm, ": G5 IF DROP 100 THEN + ; 1 2 0 G5"), 3);
    assert_int_equal(eval_pop(f->vm, "1 2 -1 G5"), 101);
    assert_int_equal(eval_pop(f->vm, ": G6 0 BEGIN 1 + DUP 10 < WHILE REPEAT ; G6"), 10);
    assert_int_equal(eval_pop(f->vm, ": G7 5 [ HERE DROP ] + ; 1 G7"), 6);
    /* fusion where C, left HERE unaligned (compiled only: such code is garbage) */
    assert_int_equal(ev(f, ": G9 [ 1 C, ] 5 + 2 PICK ;"), FBRL_OK);
    /* SEE shows fused code as the words it came from */
    expect_output(f, ": G8 DUP 2 < IF 1 - THEN OVER + ; SEE G8", ": G8 DUP 2 < 0BRANCH(2) 1 - OVER + ;\n");
    free_vm(f);
}

/* Run `input NAME` and keep what it left: the status, the THROW code, the stack (bottom
 * first) and the 32 bytes at BUF. The stack is emptied after. */
typedef struct run_result {
    fbrl_status st;
    int code, depth, fdepth;
    fbrl_cell cells[16];
    double floats[8];
    unsigned char buf[32];
} run_result;

static run_result run_word(fixture *f, const char *input, const char *name)
{
    run_result r;
    char src[256];
    memset(&r, 0, sizeof r);
    snprintf(src, sizeof src, "BUF 32 ERASE %s %s", input, name);
    r.st = ev(f, src);
    r.code = r.st == FBRL_OK ? 0 : fbrl_vm_last_error(f->vm)->throw_code;
    r.depth = (int)fbrl_vm_depth(f->vm);
    assert_true(r.depth <= 16);
    for (int i = r.depth - 1; i >= 0; i--)
        r.cells[i] = pop1(f);
    r.fdepth = (int)fbrl_vm_fdepth(f->vm);
    assert_true(r.fdepth <= 8);
    for (int i = r.fdepth - 1; i >= 0; i--)
        assert_int_equal(fbrl_vm_fpop(f->vm, &r.floats[i]), FBRL_OK);
    fbrl_cell buf = eval_pop(f->vm, "BUF");
    memcpy(r.buf, (const void *)buf, sizeof r.buf);
    return r;
}

/* The superinstructions (a DUP or 2DUP before a compare and branch, DROP and a literal,
 * I before a fetch or store, a literal or DUP before +LOOP, OVER/2 PICK before @, * +, a
 * literal + before a fetch or store, an ELSE branch that lands on ;, I S>F, FOVER FOVER,
 * FDUP F*, I J) against the same words kept apart by HERE (which ends every fusion): the same
 * stacks, memory and errors. */
static void superinstructions_keep_meaning(void **state)
{
    (void)state;
    static const char *const bodies[] = {
        "DUP 5 = IF 1 ELSE 2 THEN",  "DUP 5 <> IF 1 ELSE 2 THEN", "DUP 5 < IF 1 ELSE 2 THEN",
        "DUP 5 > IF 1 ELSE 2 THEN",  "2DUP = IF 1 ELSE 2 THEN",   "2DUP <> IF 1 ELSE 2 THEN",
        "2DUP < IF 1 ELSE 2 THEN",   "2DUP > IF 1 ELSE 2 THEN",   "DROP 7",
        "DROP BUF @",                "DROP 3 +",
        "DUP 1+ SWAP DO I @ LOOP",   "DUP 1+ SWAP DO I C@ LOOP",  "DUP 1+ SWAP DO I 2@ LOOP",
        "DUP 1+ SWAP DO 123 I ! LOOP", "DUP 1+ SWAP DO 45 I C! LOOP", "DUP 1+ SWAP DO 6 7 I 2! LOOP",
        "10 0 DO I + 3 +LOOP",       "-10 0 DO I + -2 +LOOP",     "10 0 DO I + 2 DUP +LOOP",
        "OVER @",                    "2 PICK @",                  "* +",
        "8 + @",                     "3 + C@",                    "8 + !",
        "3 + C!",                    "IF 1 ELSE 2 THEN",          "CASE 1 OF 10 ENDOF 2 OF 20 ENDOF 30 SWAP ENDCASE",
        "DUP 1+ SWAP DO I S>F LOOP", "S>F 2E0 FOVER FOVER",       "S>F FDUP F*",
        "3 0 DO 2 0 DO I J LOOP LOOP",
    };
    static const char *const inputs[] = {
        "",          "0",         "5",           "9",         "BUF",     "3 4",   "4 4",
        "5 3",       "10",        "-10",         "BUF 5 BUF", "0 BUF",   "1 2 3", "-1 BUF 0",
        "BUF 1 BUF", "77 BUF",    "77 BUF 4000000000000 +", "2",
    };
    fixture *f = new_vm(1 << 20);
    char src[512];
    assert_int_equal(ev(f, "CREATE BUF 32 ALLOT"), FBRL_OK);
    for (size_t b = 0; b < sizeof bodies / sizeof bodies[0]; b++) {
        /* SU: the same words, each followed by HERE DROP at compile time */
        char apart[400] = "", word[64];
        const char *p = bodies[b];
        int n;
        while (sscanf(p, "%63s%n", word, &n) == 1) {
            strcat(apart, word);
            strcat(apart, " [ HERE DROP ] ");
            p += n;
        }
        /* each fused form is really there: the fused code is shorter (but for ELSE
         * landing on ; and ENDOF, whose branch becomes an exit of the same size) */
        snprintf(src, sizeof src, "HERE : SF %s ; HERE SWAP -  HERE : SU %s ; HERE SWAP -", bodies[b], apart);
        fbrl_cell plain_size = eval_pop(f->vm, src), fused_size = pop1(f);
        if (strncmp(bodies[b], "IF ", 3) != 0 && strncmp(bodies[b], "CASE", 4) != 0 && fused_size >= plain_size)
            fail_msg("\"%s\" was not fused (%ld bytes, apart %ld)", bodies[b], (long)fused_size, (long)plain_size);
        for (size_t i = 0; i < sizeof inputs / sizeof inputs[0]; i++) {
            run_result fused = run_word(f, inputs[i], "SF"), plain = run_word(f, inputs[i], "SU");
            if (memcmp(&fused, &plain, sizeof fused) != 0)
                fail_msg("\"%s\" on \"%s\": fused st %d code %d depth %d top %ld, apart st %d code %d depth %d top %ld",
                         bodies[b], inputs[i], fused.st, fused.code, fused.depth,
                         (long)(fused.depth ? fused.cells[fused.depth - 1] : 0), plain.st, plain.code, plain.depth,
                         (long)(plain.depth ? plain.cells[plain.depth - 1] : 0));
        }
    }
    /* SEE shows them as the words they came from */
    expect_output(f, ": S1 DUP 3 < IF DROP 0 THEN ; SEE S1", ": S1 DUP 3 < 0BRANCH(2) DROP 0 ;\n");
    expect_output(f, ": S2 10 0 DO I @ DUP +LOOP ; SEE S2", ": S2 10 0 DO I @ DUP +LOOP ;\n");
    expect_output(f, ": S3 3 0 DO I S>F FDUP F* FOVER FOVER LOOP ; SEE S3",
                  ": S3 3 0 DO I S>F FDUP F* FOVER FOVER LOOP ;\n");
    expect_output(f, ": S4 2 0 DO 2 0 DO I J XOR LOOP LOOP ; SEE S4", ": S4 2 0 DO 2 0 DO I J XOR LOOP LOOP ;\n");
    free_vm(f);
}

static void hostile_programs_fail_cleanly(void **state)
{
    (void)state;
    static const struct {
        const char *src;
        int code;
    } cases[] = {
        {"0 @", -9},
        {"-1 @", -9},
        {"HERE 1000000000 + C@", -9},
        {"1 0 !", -9},
        {"0 100 ERASE", -9},
        {"HERE 0 1000000 MOVE", -9},
        {"0 10 TYPE", -9},
        {"DROP", -4},
        {"1 2 3 2ROT", -4},
        {"5 PICK", -4},
        {"F+", -45},
        {": R1 RECURSE ; R1", -5},
        {": D1 1 1 RECURSE ; D1", -3},
        {": F1 1E0 RECURSE ; F1", -44},
        {": B1 BEGIN 1 AGAIN ; B1", -3},
        {"1 0 /", -10},
        {"1 0 MOD", -10},
        {"1 0 0 UM/MOD", -10},
        {"1E30 F>S", -11},
        {"R>", -14},
        {": X1 R> R> R> R> ; X1", -6},
        {": X2 12345 >R ; X2", -9},
        {": X3 HERE >R ; X3", -9},
        {": X4 -8 >R ; X4", -9},
        {"THEN", -14},
        {": X5 THEN ;", -22},
        {": X6 IF ;", -22},
        {": X7 BEGIN UNTIL UNTIL ;", -22},
        {": X8 DO IF LOOP ;", -22},
        {": X9 ELSE ;", -22},
        {": XA 1 ; ;", -14},
        {": XB [ : Y ;", 0},
        {": ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789 ;", -19},
        {"CREATE", -16},
        {"S\" abc", -39},
        {"( abc", -39},
        {".( abc", -39},
        {"12X3", -13},
        {"--5", -13},
        {"1.2.3", -13},
        {"$", -13},
        {"'ab'", -13},
        {"1E", 0},
        {"' DUP 99999 + EXECUTE", -13},
        {"0 EXECUTE", -13},
        {"-1 EXECUTE", -13},
        {"123 THROW", 123},
        {"ABORT", -1},
        {"DEFER DF DF", -21},
        {"1 2 3 4 5 6 7 8 9 10 2 ROLL 100 ROLL", -4},
        {": X10 0 >R EXIT ; X10", -9},
        {"10 0 BASE ! .", -24},
        {"1 BASE ! 10", -13},
        {"S\" foo\" 2DROP 0 -1 EVALUATE", -24},
        {"PAD 0 EVALUATE", 0},
        {"-1 ALLOT", 0},
        {"-1000000000 ALLOT", -9},
        {"1000000000000 ALLOT", -8},
        {"0 1 1 FM/MOD", -11},
        {"1 1 1 SM/REM", -11},
        {"MAX-D", -13},
        {"' + >BODY", -31},
        {"1 TO DUP", -32},
        {"5 IS DUP", -32},
        {"DOES>", -14},
        {"-5 SPACES 0 0 D. : HO <# 300 0 DO 65 HOLD LOOP ; HO", -17},
        {"<# #S", -4},
        {"INCLUDE", -38},
        {"S\" \" INCLUDED", -38},
        {"KEY KEY", -57},
        {"1 RDROP", -14},
        {"CATCH", -4},
        {"5 CATCH -13 <> THROW", 0},
        {"' DROP CATCH", 0},
        {"MARKER M1 : X11 ; M1 X11", -13},
        {"' EXIT EXECUTE", -6},
        {"MARKER MM : XM [ MM ] ;", -29},
        {"XM", -13},
        {"8 CREATE-Q QQ 0 QQ ! 1 QQ ENQ", -12},
        {"8 CREATE-Q QR QR CELL+ 3 CELLS 0 FILL 1 QR ENQ", -9},
        {"4 CHR ARRAY AR 0 ' AR >BODY", -31},
        {"HERE 4 ALLOT 1 SWAP STRING-CNT", -12},
    };
    fixture *f = new_vm(1 << 20);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        fbrl_status st = ev(f, cases[i].src);
        int code = st == FBRL_OK ? 0 : fbrl_vm_last_error(f->vm)->throw_code;
        if (code != cases[i].code)
            print_error("'%s' gave %d, expected %d\n", cases[i].src, code, cases[i].code);
        assert_int_equal(code, cases[i].code);
        if (code)
            assert_int_equal(fbrl_vm_depth(f->vm), 0);
        fbrl_vm_eval(f->vm, "DECIMAL", 7);
        while (fbrl_vm_depth(f->vm))
            pop1(f);
        double d;
        while (fbrl_vm_fdepth(f->vm))
            fbrl_vm_fpop(f->vm, &d);
        /* the VM keeps working */
        assert_int_equal(ev(f, "2 3 *"), FBRL_OK);
        assert_int_equal(pop1(f), 6);
    }
    /* an over-long line */
    char *line = malloc(5000);
    memset(line, ' ', 4999);
    line[4999] = 0;
    assert_int_equal(ev(f, line), FBRL_ETHROW);
    assert_int_equal(fbrl_vm_last_error(f->vm)->throw_code, -18);
    free(line);
    free_vm(f);
}

/* Overwrite freshly compiled code with pseudo-random cells and run it: every
 * corrupted instruction stream must end in a THROW or normally, never a crash. */
static fixture *mixer_vm(void)
{
    fixture *f = new_vm(1 << 20);
    assert_int_equal(ev(f, "VARIABLE SEED : RND SEED @ 1103515245 * 12345 + DUP SEED ! 16 RSHIFT ;"),
                     FBRL_OK);
    assert_int_equal(ev(f, ": MIX ( a n -- ) 0 DO RND 3 AND CASE 0 OF RND 400 MOD ENDOF 1 OF RND ENDOF "
                           "2 OF RND 50 MOD 4096 + ENDOF DUP OF HERE RND 64 MOD CELLS - ENDOF ENDCASE "
                           "OVER I CELLS + ! LOOP DROP ;"),
                     FBRL_OK);
    return f;
}

static void corrupted_code_is_contained(void **state)
{
    (void)state;
    fixture *f = mixer_vm();
    int ok = 0, thrown = 0;
    for (int seed = 1; seed <= 300; seed++) {
        char src[256];
        snprintf(src, sizeof src,
                 "MARKER GONE : VICTIM 1 2 3 4 5 6 7 8 9 10 11 12 ; %d SEED ! HERE 13 CELLS - 13 MIX VICTIM",
                 seed);
        fbrl_status st = ev(f, src);
        if (st == FBRL_OK)
            ok++;
        else
            thrown++;
        if (fbrl_vm_bye(f->vm)) { /* a random BYE opcode: that VM is finished */
            free_vm(f);
            f = mixer_vm();
            continue;
        }
        fbrl_vm_eval(f->vm, "GONE DECIMAL", 12);
        fbrl_vm_reset(f->vm);
    }
    assert_true(thrown > 0);
    assert_int_equal(ok + thrown, 300);
    assert_int_equal(ev(f, "2 3 +"), FBRL_OK);
    assert_int_equal(pop1(f), 5);
    free_vm(f);
}

/* fbrl_vm_interrupt from another thread stops an endless loop with -28. The
 * interrupter repeats its request until the evaluation has returned, so a slow
 * start of the evaluation cannot make the test hang. */
typedef struct stopper {
    fbrl_vm *vm;
    int done;
} stopper;

static void *interrupter(void *arg)
{
    stopper *s = arg;
    while (!__atomic_load_n(&s->done, __ATOMIC_ACQUIRE)) {
        vmh_sleep_ms(NULL, 5);
        fbrl_vm_interrupt(s->vm);
    }
    return NULL;
}

static fbrl_status eval_interrupted(fixture *f, const char *src)
{
    stopper s = {f->vm, 0};
    pthread_t t;
    assert_int_equal(pthread_create(&t, NULL, interrupter, &s), 0);
    fbrl_status st = ev(f, src);
    __atomic_store_n(&s.done, 1, __ATOMIC_RELEASE);
    pthread_join(t, NULL);
    return st;
}

static void interrupt_stops_endless_loops(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    assert_int_equal(eval_interrupted(f, ": SPIN BEGIN AGAIN ; SPIN"), FBRL_ETHROW);
    assert_int_equal(fbrl_vm_last_error(f->vm)->throw_code, -28);
    assert_string_equal(fbrl_vm_last_error(f->vm)->message, "user interrupt");
    assert_string_equal(fbrl_vm_last_error(f->vm)->word, "SPIN");
    assert_int_equal(eval_interrupted(f, ": R RECURSE ; : LOOPS 0 BEGIN 1+ DUP 0< UNTIL ; LOOPS"),
                     FBRL_ETHROW);
    assert_int_equal(fbrl_vm_last_error(f->vm)->throw_code, -28);
    assert_int_equal(eval_interrupted(f, ": DL -1 0 DO LOOP ; DL"), FBRL_ETHROW);
    assert_int_equal(fbrl_vm_last_error(f->vm)->throw_code, -28);
    assert_int_equal(eval_interrupted(f, "' SPIN CATCH"), FBRL_OK); /* catchable */
    assert_int_equal(pop1(f), -28);
    fbrl_vm_interrupt(f->vm); /* a request made before an evaluation is dropped */
    assert_int_equal(ev(f, ": FIVE 0 5 0 DO 1+ LOOP ; FIVE"), FBRL_OK);
    assert_int_equal(pop1(f), 5);
    free_vm(f);
}

/* Output padding of any width and C words that wait are interruptible too: a huge
 * SPACES or U.R ends, and code after an interrupted C word does not run. */
static fbrl_status c_wait_for_interrupt(fbrl_vm *vm, void *arg)
{
    (void)arg;
    while (!fbrl_vm_interrupt_pending(vm))
        vmh_sleep_ms(NULL, 1);
    return FBRL_OK;
}

static void interrupt_stops_padding_and_waiting_c_words(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    assert_int_equal(eval_interrupted(f, "100000000000 SPACES"), FBRL_ETHROW);
    assert_int_equal(fbrl_vm_last_error(f->vm)->throw_code, -28);
    assert_int_equal(eval_interrupted(f, "1 100000000000 U.R"), FBRL_ETHROW);
    assert_int_equal(fbrl_vm_last_error(f->vm)->throw_code, -28);
    assert_int_equal(
        fbrl_vm_define(f->vm, "C-WAIT", c_wait_for_interrupt, NULL, "( -- )", "waits for Ctrl-C"), FBRL_OK);
    assert_int_equal(ev(f, "VARIABLE RAN 0 RAN ! : P C-WAIT 1 RAN ! ;"), FBRL_OK);
    assert_int_equal(eval_interrupted(f, "P"), FBRL_ETHROW);
    assert_int_equal(fbrl_vm_last_error(f->vm)->throw_code, -28);
    assert_int_equal(ev(f, "RAN @"), FBRL_OK);
    assert_int_equal(pop1(f), 0);
    assert_int_equal(ev(f, "3 SPACES 7 5 U.R"), FBRL_OK); /* still pads normally */
    free_vm(f);
}

/* Random token streams built from the dictionary's own words: whatever they do,
 * the VM must answer with OK or an error and stay usable. */
typedef struct names {
    char list[700][40];
    int n;
} names;

static int collect(void *ctx, const char *name, size_t len)
{
    names *nm = ctx;
    /* words that could wait or loop for ever on random input (legitimately) */
    static const char *const skip[] = {
        "BYE",   "MS",    "SPACES", ".R",         "U.R", "D.R",        "QUIT",          "DUMP",
        "WORDS", "KEY",   "ACCEPT", "GET-STRING", ">IN", "SAVE-INPUT", "RESTORE-INPUT", "BEGIN",
        "AGAIN", "UNTIL", "WHILE",  "REPEAT",     "DO",  "?DO",        "LOOP",          "+LOOP"};
    for (size_t i = 0; i < sizeof skip / sizeof skip[0]; i++)
        if (strlen(skip[i]) == len && memcmp(skip[i], name, len) == 0)
            return 0;
    if (nm->n < 700 && len < 39) {
        memcpy(nm->list[nm->n], name, len);
        nm->list[nm->n][len] = 0;
        nm->n++;
    }
    return 0;
}

/* A host without a file system (the firmware) has no standard FILE words at all. */
static void no_file_system_no_file_words(void **state)
{
    (void)state;
    fixture *f = calloc(1, sizeof *f);
    assert_non_null(f);
    f->mem = malloc(1 << 20);
    assert_non_null(f->mem);
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = f->mem;
    cfg.mem_size = 1 << 20;
    cfg.host.user = &f->h;
    cfg.host.write = h_write;
    assert_int_equal(fbrl_vm_create(&f->vm, &cfg), FBRL_OK);
    assert_int_equal(ev(f, "[DEFINED] R/O [DEFINED] READ-LINE FORTH-2012 [DEFINED] OPEN-FILE"), FBRL_OK);
    assert_int_equal(pop1(f), 0);
    assert_int_equal(pop1(f), 0);
    assert_int_equal(pop1(f), 0);
    /* the rest of the standard words are there */
    assert_int_equal(ev(f, "10 ALLOCATE SWAP FREE [DEFINED] {:"), FBRL_OK);
    assert_int_equal(pop1(f), -1);
    assert_int_equal(pop1(f), 0);
    assert_int_equal(pop1(f), 0);
    free_vm(f);
}

static int waits(const char *w)
{
    static const char *const names[] = {"MS",        "AT",    "EVERY",     "AWAIT", "KEY",
                                        "ACCEPT",    "PAUSE", "CLAIM",     "START", "START-WITH",
                                        "CLAIM-ARM", "EKEY",  "STOP-TASKS"};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
        if (!strcmp(w, names[k]))
            return 1;
    return 0;
}

static void random_programs_are_contained(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    static names nm;
    static const char *const extra[] = {"0",   "1",    "-1",   "3",    "100",    "65535",   "-9999999999",
                                        "PAD", "HERE", "1E0",  "0E0",  "-2.5E3", "S\" x\"", ":",
                                        ";",   "IF",   "THEN", "ELSE", "CASE",   "OF",      "ENDOF",
                                        "'",   "[']",  "X",    "Y"};
    nm.n = 0;
    fbrl_vm_words(f->vm, collect, &nm);
    assert_true(nm.n > 300);
    uint32_t seed = 12345;
    int errors = 0;
    /* a random line may legitimately redefine any word (CREATE *): forget them all at the end */
    assert_int_equal(ev(f, "MARKER -RANDOM"), FBRL_OK);
    for (int line = 0; line < 3000; line++) {
        char src[512];
        size_t n = 0;
        for (int t = 0; t < 10; t++) {
            seed = seed * 1103515245u + 12345u;
            uint32_t r = seed >> 8;
            const char *w = (r & 1) ? nm.list[(r >> 1) % (uint32_t)nm.n]
                                    : extra[(r >> 1) % (sizeof extra / sizeof extra[0])];
            if (waits(w)) /* a wait for a random time (65535 MS) is legal, and slow */
                w = "DUP";
            n += (size_t)snprintf(src + n, sizeof src - n, "%s ", w);
        }
        f->h.out.n = 0;
        if (ev(f, src) != FBRL_OK)
            errors++;
        if (line % 100 == 99) {
            while (fbrl_vm_depth(f->vm))
                pop1(f);
            ev(f, "; DECIMAL");
        }
    }
    assert_true(errors > 0);
    /* (a random line may have redefined ; itself: back to a clean prompt through the API) */
    fbrl_vm_reset(f->vm);
    assert_false(fbrl_vm_compiling(f->vm));
    while (fbrl_vm_depth(f->vm))
        pop1(f);
    assert_int_equal(ev(f, "-RANDOM DECIMAL 6 7 *"), FBRL_OK);
    assert_int_equal(pop1(f), 42);
    free_vm(f);
}

/* ---- tasks (docs/tasks.md) ---- */

/* Round robin at PAUSE, own stacks, START-WITH, CATCH inside a task, a failing task named
 * in its message, STOP, MARKER taking a task's memory back. */
static void tasks_in_the_engine(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    assert_int_equal(ev(f, "TASK TA TASK TB CREATE TRACE 16 CELLS ALLOT VARIABLE #T 0 #T !"), FBRL_OK);
    assert_int_equal(ev(f, ": NOTE ( n -- ) TRACE #T @ CELLS + !  1 #T +! ;"), FBRL_OK);
    assert_int_equal(ev(f, ": RUN-A ( -- ) 3 0 DO 10 I + NOTE PAUSE LOOP ;"), FBRL_OK);
    assert_int_equal(ev(f, ": RUN-B ( x y -- ) + 3 0 DO DUP I + NOTE PAUSE LOOP DROP ;"), FBRL_OK);
    /* nothing runs until the main task waits */
    assert_int_equal(ev(f, "' RUN-A TA START  20 0 2 ' RUN-B TB START-WITH  #T @"), FBRL_OK);
    assert_int_equal(pop1(f), 0);
    assert_int_equal(ev(f, "TA AWAIT TB AWAIT #T @ TA TASK-STATE TB TASK-STATE DEPTH"), FBRL_OK);
    assert_int_equal(pop1(f), 3); /* the main stack: only what it pushed */
    assert_int_equal(pop1(f), 5);
    assert_int_equal(pop1(f), 5);
    assert_int_equal(pop1(f), 6);
    /* they took turns: a, b, a, b, a, b (whichever began) */
    assert_int_equal(ev(f, ": WANT TRACE @ 10 = IF 10 20 11 21 12 22 ELSE 20 10 21 11 22 12 THEN ; WANT"),
                     FBRL_OK);
    for (int k = 5; k >= 0; k--) {
        fbrl_cell want = pop1(f), got = 0;
        char q[64];
        snprintf(q, sizeof q, "TRACE %d CELLS + @", k);
        assert_int_equal(ev(f, q), FBRL_OK);
        got = pop1(f);
        assert_int_equal(got, want);
    }
    /* an error in a task: named, the task failed, the main task unharmed; CATCH works inside */
    f->h.out.n = 0;
    assert_int_equal(
        ev(f, ": BAD ( -- ) 5 MS  1 0 ['] / CATCH DROP 2DROP  1 0 / ;  ' BAD TA START 1 2 TA AWAIT"),
        FBRL_OK);
    assert_non_null(strstr(f->h.out.s, "task TA: division by zero"));
    assert_int_equal(ev(f, "TA TASK-STATE"), FBRL_OK);
    assert_int_equal(pop1(f), 6);
    assert_int_equal(pop1(f), 2);
    assert_int_equal(pop1(f), 1);
    /* STOP ends a waiting task; a stopped task can start again */
    assert_int_equal(ev(f, ": FOREVER ( -- ) BEGIN 1 MS AGAIN ;  ' FOREVER TA START 20 MS TA TASK-STATE"),
                     FBRL_OK);
    assert_int_equal(pop1(f), 3);
    assert_int_equal(ev(f, "TA STOP TA TASK-STATE"), FBRL_OK);
    assert_int_equal(pop1(f), 7);
    /* a task cannot start twice; STOP-TASKS from a task ends it too */
    assert_int_equal(ev(f, "' FOREVER TA START ' FOREVER TA START"), FBRL_ETHROW);
    assert_int_equal(ev(f, "STOP-TASKS TA TASK-STATE"), FBRL_OK);
    assert_int_equal(pop1(f), 7);
    /* a MARKER that takes a task's memory back takes the task too */
    assert_int_equal(ev(f, "MARKER -T TASK TC ' FOREVER TC START -T 5 MS TASKS"), FBRL_OK);
    assert_null(strstr(f->h.out.s, "TC "));
    free_vm(f);
}

/* The task's clock: ME, ZERO-CLOCK, CLOCK, EVERY (periods without drift), DEADLINE (a
 * missed one throws -316 and counts), LATENESS reports them. */
static void task_clock_words(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    assert_int_equal(ev(f, "ME ZERO-CLOCK CLOCK"), FBRL_OK);
    assert_true(pop1(f) < 5);
    assert_int_equal(pop1(f), 0);
    assert_int_equal(ev(f, "TASK TP VARIABLE WHO  : PER ( -- ) ME WHO !  5 0 DO 20 EVERY LOOP  CLOCK ;"),
                     FBRL_OK);
    assert_int_equal(ev(f, "' PER TP START TP AWAIT WHO @ TP = TP LATE-MAX"), FBRL_OK);
    assert_true(pop1(f) < 20000);
    assert_int_equal(pop1(f), -1);
    assert_int_equal(ev(f, "ZERO-CLOCK 1000 DEADLINE 10 MS 5 ' DEADLINE CATCH"), FBRL_OK);
    assert_int_equal(pop1(f), FBRL_VM_THROW_OF_STATUS(FBRL_ETIMEOUT));
    f->h.out.n = 0;
    assert_int_equal(ev(f, "DROP LATENESS"), FBRL_OK);
    assert_non_null(strstr(f->h.out.s, "TP                   5"));
    assert_non_null(strstr(f->h.out.s, "MAIN"));
    free_vm(f);
}

/* A host drives the tasks from its own event loop: fbrl_vm_run_tasks runs what is due and
 * says when to call again; timed steps keep their times. */
static void tasks_from_a_host_loop(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    uint64_t wake = 0;
    int live = -1, calls = 0;
    assert_int_equal(fbrl_vm_run_tasks(f->vm, &wake, &live), FBRL_OK);
    assert_int_equal(live, 0);
    assert_true(wake == UINT64_MAX);
    assert_int_equal(ev(f, "TASK T1 VARIABLE N 0 N !  : STEPS ( -- ) 4 1 DO I 50 * AT 1 N +! LOOP ;"),
                     FBRL_OK);
    assert_int_equal(ev(f, "' STEPS T1 START"), FBRL_OK);
    uint64_t t0 = fbrl_clock_now_us();
    do {
        assert_int_equal(fbrl_vm_run_tasks(f->vm, &wake, &live), FBRL_OK);
        calls++;
        if (live && wake > fbrl_clock_now_us())
            fbrl_clock_sleep_us(wake - fbrl_clock_now_us());
    } while (live);
    uint64_t took = fbrl_clock_now_us() - t0;
    assert_true(took >= 150000 && took < 1000000);
    assert_true(calls >= 4 && calls < 100); /* told when to call: no busy polling */
    assert_int_equal(ev(f, "N @ T1 LATE-MAX"), FBRL_OK);
    assert_true(pop1(f) < 20000);
    assert_int_equal(pop1(f), 3);
    free_vm(f);
}

/* A clock that moves only when the engine sleeps (and 1 us for each look at it, so a wait
 * that never sleeps still ends): how often the engine sleeps and looks while tasks wait. */
typedef struct vclock {
    uint64_t now;
    unsigned long looks, sleeps;
} vclock;
static vclock g_vc;
static uint64_t vc_now_us(void *user)
{
    (void)user;
    g_vc.looks++;
    return ++g_vc.now;
}
static void vc_sleep_ms(void *user, uint32_t ms)
{
    (void)user;
    g_vc.sleeps++;
    g_vc.now += (uint64_t)ms * 1000u;
}

/* Waiting costs nothing: six tasks waiting 60 s on their clocks (AT, MS) while the main
 * task AWAITs them make the engine sleep about once a second (its longest sleep) and look
 * at the clock about as often, not poll (AWAIT looked every 2 ms: 30,000 sleeps); a task
 * that ends wakes its AWAIT at once; CLAIM waits for RELEASE the same way. */
static void waiting_costs_nothing(void **state)
{
    (void)state;
    memset(&g_vc, 0, sizeof g_vc);
    fixture *f = new_vm_clock(1 << 20, vc_now_us, vc_sleep_ms);
    assert_int_equal(ev(f, "TASK T0 TASK T1 TASK T2 TASK T3 TASK T4 TASK T5 "
                           "CREATE TS T0 , T1 , T2 , T3 , T4 , T5 , "
                           ": NAP ( -- ) 60000 AT ;  : NAP-MS ( -- ) 60000 MS ; "
                           ": GO ( xt -- ) 6 0 DO DUP I CELLS TS + @ START LOOP DROP "
                           "  6 0 DO I CELLS TS + @ AWAIT LOOP ;"),
                     FBRL_OK);
    g_vc.looks = g_vc.sleeps = 0;
    uint64_t t0 = g_vc.now;
    assert_int_equal(ev(f, "' NAP GO"), FBRL_OK);
    assert_true(g_vc.now - t0 >= 60000000u && g_vc.now - t0 < 60000000u + 2000u); /* ends in time */
    assert_true(g_vc.sleeps >= 60 && g_vc.sleeps <= 70);
    assert_true(g_vc.looks < 2000);
    g_vc.looks = g_vc.sleeps = 0;
    assert_int_equal(ev(f, "' NAP-MS GO"), FBRL_OK);
    assert_true(g_vc.sleeps >= 60 && g_vc.sleeps <= 70);
    assert_true(g_vc.looks < 2000);
    /* AWAIT of a task that ends at 5 s and a CLAIM held for 5 s: each wakes when it happens */
    assert_int_equal(ev(f, "VARIABLE WOKE  : HOLD ( -- ) CLAIM-ARM 5000 AT RELEASE-ARM 55000 AT ; "
                           ": TAKE ( -- ) 100 AT CLAIM-ARM CLOCK WOKE ! RELEASE-ARM ; "),
                     FBRL_OK);
    g_vc.sleeps = 0;
    assert_int_equal(ev(f, "' HOLD T0 START ' TAKE T1 START T1 AWAIT WOKE @"), FBRL_OK);
    fbrl_cell woke = pop1(f);
    assert_true(woke >= 5000 && woke < 5002);
    assert_true(g_vc.sleeps <= 8);
    assert_int_equal(ev(f, "T0 AWAIT"), FBRL_OK);
    free_vm(f);
}

/* TASK of a name that already is a task that is not running (a file loaded again, EDIT)
 * takes that task's slot again: 100 loads of three tasks fit in 16; a running task keeps
 * its slot and the new name gets another. */
static void task_again_reuses_its_slot(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    for (int i = 0; i < 100; i++)
        assert_int_equal(ev(f, "TASK TR TASK TS TASK TT : NOP ; ' NOP TS START TS AWAIT"), FBRL_OK);
    assert_int_equal(ev(f, "TR TS TT"), FBRL_OK);
    fbrl_cell tt = pop1(f), ts = pop1(f), tr = pop1(f);
    assert_true(tr >= 1 && ts == tr + 1 && tt == ts + 1);
    assert_int_equal(ev(f, ": LONG ( -- ) 200 MS ;  ' LONG TR START  TASK TR  TR TASK-STATE"), FBRL_OK);
    assert_int_equal(pop1(f), 1); /* the new TR: made, not started */
    assert_int_equal(ev(f, "TR"), FBRL_OK);
    assert_true(pop1(f) != tr);
    assert_int_equal(ev(f, "STOP-TASKS"), FBRL_OK);
    free_vm(f);
}

/* The word hook (a debugger's single steps): every word a definition runs, built-ins,
 * numbers and superinstructions by their source words, and the interpreter's words, with
 * where each is and how deep; a non-zero return throws there; cleared, nothing more. */
typedef struct seen {
    char words[512];
    size_t depth[32];
    int n, stop_at;
} seen;
static int record_word(void *ctx, fbrl_vm *vm, const fbrl_vm_stop *st)
{
    seen *w = ctx;
    (void)vm;
    strncat(w->words, st->word, sizeof w->words - strlen(w->words) - 2);
    strncat(w->words, "|", sizeof w->words - strlen(w->words) - 1);
    if (w->n < 32)
        w->depth[w->n] = st->depth;
    w->n++;
    if (!strcmp(st->word, "DROP"))
        assert_string_equal(st->caller, "STEPPED");
    return w->n == w->stop_at ? -1 : 0;
}

static void word_hook_sees_every_word(void **state)
{
    (void)state;
    fixture *f = new_vm(1 << 20);
    seen w;
    memset(&w, 0, sizeof w);
    assert_int_equal(ev(f, "VARIABLE V : STEPPED ( -- ) 1 2 + DROP V @ DROP ;"), FBRL_OK);
    assert_int_equal(fbrl_vm_word_hook(f->vm, record_word, &w), FBRL_OK);
    assert_int_equal(ev(f, "STEPPED"), FBRL_OK);
    assert_string_equal(w.words, "STEPPED|1|2 +|DROP|V @|DROP|;|"); /* V @: one superinstruction */
    assert_true(w.depth[1] == w.depth[0] + 1); /* inside the definition: one deeper */
    memset(&w, 0, sizeof w);
    w.stop_at = 4; /* a hook's throw stops the word there: DROP never runs */
    assert_int_equal(ev(f, "STEPPED"), FBRL_ETHROW);
    assert_string_equal(w.words, "STEPPED|1|2 +|DROP|");
    assert_int_equal(fbrl_vm_depth(f->vm), 0);
    assert_int_equal(fbrl_vm_word_hook(f->vm, NULL, NULL), FBRL_OK);
    memset(&w, 0, sizeof w);
    assert_int_equal(ev(f, "STEPPED"), FBRL_OK);
    assert_int_equal(w.n, 0);
    assert_int_equal(fbrl_vm_word_hook(NULL, record_word, &w), FBRL_EINVAL);
    free_vm(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(waiting_costs_nothing),
        cmocka_unit_test(word_hook_sees_every_word),
        cmocka_unit_test(task_again_reuses_its_slot),
        cmocka_unit_test(forth_core),
        cmocka_unit_test(forth_coreext),
        cmocka_unit_test(forth_exception),
        cmocka_unit_test(forth_double),
        cmocka_unit_test(forth_float),
        cmocka_unit_test(forth_string),
        cmocka_unit_test(forth_tools),
        cmocka_unit_test(forth_fbrl),
        cmocka_unit_test(forth_search),
        cmocka_unit_test(forth_locals),
        cmocka_unit_test(forth_memory),
        cmocka_unit_test(forth_file),
        cmocka_unit_test(no_file_system_no_file_words),
        cmocka_unit_test(ekey_decodes_terminal_keys),
        cmocka_unit_test(output_formats),
        cmocka_unit_test(console_input),
        cmocka_unit_test(create_rejects_bad_config),
        cmocka_unit_test(size_for_is_enough),
        cmocka_unit_test(zeroed_memory_is_used_lazily),
        cmocka_unit_test(two_vms_are_independent),
        cmocka_unit_test(dictionary_index_grows),
        cmocka_unit_test(c_words),
        cmocka_unit_test(api_stacks),
        cmocka_unit_test(errors_carry_word_file_line),
        cmocka_unit_test(backtraces_name_the_failing_word),
        cmocka_unit_test(include_relative_and_require),
        cmocka_unit_test(multi_line_definitions_and_bye),
        cmocka_unit_test(every_word_has_help),
        cmocka_unit_test(fused_code_keeps_meaning),
        cmocka_unit_test(superinstructions_keep_meaning),
        cmocka_unit_test(hostile_programs_fail_cleanly),
        cmocka_unit_test(corrupted_code_is_contained),
        cmocka_unit_test(tasks_in_the_engine),
        cmocka_unit_test(tasks_from_a_host_loop),
        cmocka_unit_test(task_clock_words),
        cmocka_unit_test(random_programs_are_contained),
        cmocka_unit_test(interrupt_stops_endless_loops),
        cmocka_unit_test(interrupt_stops_padding_and_waiting_c_words),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
