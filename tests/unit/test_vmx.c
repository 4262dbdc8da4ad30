/* SPDX-License-Identifier: MIT */
/* test_vmx.c - the extension interface for word sets (fbrl/vmx.h): words with flags and two
 * context pointers, typed data made all or nothing, the one argument parser (stacks or the
 * input after the word, the engine's number syntax), the rule for integers given where a
 * real is expected (table-driven over every word set word that takes reals), parsing,
 * compiling a literal, executing. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/glossary.h"
#include "fbrl/robot.h"
#include "fbrl/vm.h"
#include "fbrl/vmx.h"

#define OFFLINE_CODE FBRL_VM_THROW_OF_STATUS(FBRL_EOFFLINE)
#define MEM_SIZE     (2u << 20)

typedef struct fixture {
    unsigned char *mem;
    fbrl_vm *vm;
    fbrl_glossary g;
    fbrl_robot r;
} fixture;

static fixture *make(void)
{
    fixture *f = calloc(1, sizeof *f);
    assert_non_null(f);
    f->mem = malloc(MEM_SIZE); /* glibc: 16-byte aligned */
    assert_non_null(f->mem);
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = f->mem;
    cfg.mem_size = MEM_SIZE;
    assert_int_equal(fbrl_vm_create(&f->vm, &cfg), FBRL_OK);
    assert_int_equal(fbrl_glossary_install(f->vm, &f->g), FBRL_OK);
    assert_int_equal(fbrl_robot_install(f->vm, &f->r, NULL, &f->g), FBRL_OK);
    return f;
}

static void drop(fixture *f)
{
    free(f->mem);
    free(f);
}

static int setup(void **state)
{
    *state = make();
    return 0;
}

static int teardown(void **state)
{
    drop(*state);
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

static int defined(fixture *f, const char *name)
{
    fbrl_cell xt;
    return fbrl_vmx_find(f->vm, name, strlen(name), &xt) == FBRL_OK;
}

/* ---- typed data: all or nothing ---- */

static void failed_creation_leaves_no_word(void **state)
{
    /* a VM with a dictionary of 256 KB, as a small embedded one */
    fixture *f = calloc(1, sizeof *f);
    assert_non_null(f);
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.mem_size = fbrl_vm_size_for(&cfg, 256u << 10);
    f->mem = malloc(cfg.mem_size);
    assert_non_null(f->mem);
    cfg.mem = f->mem;
    assert_int_equal(fbrl_vm_create(&f->vm, &cfg), FBRL_OK);
    assert_int_equal(fbrl_vmx_data_words(f->vm), FBRL_OK);
    (void)state;
    /* regressions: both failed with "dictionary overflow" and yet left the name defined */
    assert_int_equal(ev(f, "MARKER CLEAN UNUSED"), 0);
    fbrl_cell unused = pop(f);
    assert_int_equal(ev(f, "8000000 CREATE-Q BIGQ"), FBRL_THROW_DICT_OVERFLOW);
    assert_false(defined(f, "BIGQ"));
    assert_int_equal(ev(f, "60000 8 ARRAY BIGA"), FBRL_THROW_DICT_OVERFLOW);
    assert_false(defined(f, "BIGA"));
    assert_int_equal(ev(f, "60000 60000 8 2ARRAY BIGB"), FBRL_THROW_DICT_OVERFLOW);
    assert_false(defined(f, "BIGB"));
    assert_int_equal(ev(f, "65535 STRING S1 65535 STRING S2 65535 STRING S3 65535 STRING S4 65535 STRING S5"),
                     FBRL_THROW_DICT_OVERFLOW);
    assert_true(defined(f, "S1") && !defined(f, "S5"));
    /* nothing of data space was kept either */
    assert_int_equal(ev(f, "CLEAN MARKER CLEAN UNUSED"), 0);
    assert_int_equal(pop(f), unused);
    /* a good one after the failures works */
    assert_int_equal(ev(f, "8 CREATE-Q Q  65 Q ENQ  Q DEQ"), 0);
    assert_int_equal(pop(f), 65);
    drop(f);
}

static const fbrl_vmx_type thing = {"thing", (fbrl_cell)0x54484E47};

static fbrl_status w_make_thing(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_cell addr;
    void *p;
    (void)ctx;
    (void)word;
    fbrl_status st = fbrl_vmx_create(vm, NULL, 0, &thing, 64, NULL, NULL, "( -- t )", "a thing", &addr, &p);
    if (st == FBRL_OK)
        memset(p, 7, 64);
    return st;
}

static fbrl_status w_thing_q(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_cell a;
    (void)ctx;
    (void)word;
    if (fbrl_vm_pop(vm, &a) != FBRL_OK)
        return fbrl_vm_throw(vm, FBRL_THROW_STACK_UNDERFLOW, NULL);
    const unsigned char *p = fbrl_vmx_data(vm, a, &thing, 64);
    return fbrl_vmx_push(vm, p && p[63] == 7 ? -1 : 0);
}

static void typed_data_is_checked(void **state)
{
    fixture *f = *state;
    assert_int_equal(fbrl_vmx_define(f->vm, "THING", w_make_thing, NULL, NULL, 0, "( \"name\" -- )", "make"),
                     FBRL_OK);
    assert_int_equal(fbrl_vmx_define(f->vm, "THING?", w_thing_q, NULL, NULL, 0, "( a -- f )", "check"),
                     FBRL_OK);
    assert_int_equal(ev(f, "THING T1  T1 THING?  HERE THING?  0 THING?  T1 1+ THING?"), 0);
    assert_int_equal(pop(f), 0);
    assert_int_equal(pop(f), 0);
    assert_int_equal(pop(f), 0);
    assert_int_equal(pop(f), -1);
    assert_int_equal(ev(f, "0 T1 !  T1 THING?"), 0); /* overwritten magic */
    assert_int_equal(pop(f), 0);
    assert_int_equal(ev(f, "THING"), FBRL_THROW_NO_NAME);
    assert_int_equal(fbrl_vm_depth(f->vm), 0);
}

/* ---- defining: flags and context pointers ---- */

typedef struct entry {
    const char *name;
    fbrl_cell value;
} entry;

static fbrl_status w_entry(fbrl_vm *vm, void *ctx, const void *word)
{
    const entry *e = word;
    return fbrl_vmx_push(vm, e->value + *(fbrl_cell *)ctx);
}

static fbrl_status w_lit99(fbrl_vm *vm, void *ctx, const void *word)
{
    (void)ctx;
    (void)word;
    return fbrl_vmx_compiling(vm) ? fbrl_vmx_compile_lit(vm, 99) : fbrl_vmx_push(vm, 99);
}

static void words_have_flags_and_two_contexts(void **state)
{
    fixture *f = *state;
    static const entry table[] = {{"E-ONE", 1}, {"E-TWO", 2}};
    fbrl_cell base = 100;
    for (size_t k = 0; k < 2; k++)
        assert_int_equal(
            fbrl_vmx_define(f->vm, table[k].name, w_entry, &base, &table[k], 0, "( -- n )", "entry"),
            FBRL_OK);
    assert_int_equal(ev(f, "E-ONE E-TWO"), 0);
    assert_int_equal(pop(f), 102);
    assert_int_equal(pop(f), 101);
    assert_int_equal(
        fbrl_vmx_define(f->vm, "LIT99", w_lit99, NULL, NULL, FBRL_VMX_IMMEDIATE, "( -- 99 )", "x"), FBRL_OK);
    assert_int_equal(ev(f, ": T99 LIT99 1+ ; T99 LIT99"), 0);
    assert_int_equal(pop(f), 99);
    assert_int_equal(pop(f), 100);
    assert_int_equal(fbrl_vmx_define(f->vm, "C99", w_lit99, NULL, NULL,
                                     FBRL_VMX_IMMEDIATE | FBRL_VMX_COMPILE_ONLY, "( -- )", "x"),
                     FBRL_OK);
    assert_int_equal(ev(f, "C99"), FBRL_THROW_COMPILE_ONLY);
    assert_int_equal(ev(f, ": TC C99 ; TC"), 0);
    assert_int_equal(pop(f), 99);
    /* ASC is immediate by its flag: it compiles a literal */
    assert_int_equal(ev(f, ": TA ASC Q ; TA"), 0);
    assert_int_equal(pop(f), 'Q');
    assert_int_equal(fbrl_vmx_define(f->vm, "BAD", w_lit99, NULL, NULL, 64u, "", ""), FBRL_EINVAL);
    assert_int_equal(fbrl_vmx_define(f->vm, "TWO WORDS", w_lit99, NULL, NULL, 0, "", ""), FBRL_ENAME);
}

/* ---- a word set's table and its one argument idiom ---- */

/* ( a b -- a-b+arg ) with arg the row's own number; ctx counts the calls */
static fbrl_status w_sub(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_vmx_val v[2];
    fbrl_status st = fbrl_vmx_check(vm, word, v);
    if (st != FBRL_OK)
        return st;
    ++*(int *)ctx;
    return fbrl_vmx_push(vm, v[0].i - v[1].i + ((const fbrl_vmx_reg *)word)->arg);
}

static void a_word_set_is_a_table(void **state)
{
    fixture *f = *state;
    static const fbrl_vmx_reg rows[] = {
        {"T-SUB", w_sub, "II", 0, 0, 0, FBRL_DOC("( a b -- a-b )", "subtract")},
        {"T-SUB10", w_sub, "II", FBRL_VMX_PARSE, 0, 10, FBRL_DOC("( a b -- a-b+10 )", "subtract, add 10")},
        {"T-LIT", w_lit99, "", FBRL_VMX_IMMEDIATE, 0, 0, FBRL_DOC("( -- 99 )", "x")},
    };
    int calls = 0;
    fbrl_cell xt;
    assert_int_equal(fbrl_vmx_define_table(f->vm, rows, 3, &calls), FBRL_OK);
    assert_int_equal(ev(f, "7 3 T-SUB  7 3 T-SUB10"), 0);
    assert_int_equal(pop(f), 14);
    assert_int_equal(pop(f), 4);
    assert_int_equal(calls, 2);
    /* the row's flags: typed after the word (PARSE), immediate */
    assert_int_equal(ev(f, "T-SUB10 $20 2"), 0);
    assert_int_equal(pop(f), 40);
    assert_int_equal(ev(f, ": TL T-LIT ; TL"), 0);
    assert_int_equal(pop(f), 99);
    /* uniform errors: too few is -4 and takes nothing; a word without PARSE parses nothing */
    assert_int_equal(ev(f, "5 T-SUB"), FBRL_THROW_STACK_UNDERFLOW);
    assert_int_equal(ev(f, "T-SUB 7 3"), FBRL_THROW_STACK_UNDERFLOW);
    assert_int_equal(calls, 3);
    /* a bad row stops the table there; NULLs are refused */
    static const fbrl_vmx_reg bad[] = {{"T-OK", w_lit99, "", 0, 0, 0, FBRL_DOC("", "")},
                                       {"T BAD", w_lit99, "", 0, 0, 0, FBRL_DOC("", "")}};
    assert_int_equal(fbrl_vmx_define_table(f->vm, bad, 2, NULL), FBRL_ENAME);
    assert_int_equal(fbrl_vmx_find(f->vm, "T-OK", 4, &xt), FBRL_OK);
    assert_int_equal(fbrl_vmx_define_table(NULL, rows, 1, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_vmx_define_table(f->vm, NULL, 1, NULL), FBRL_EINVAL);
}

/* The engine installs no word set: a bare VM has none of the data words, the host adds them. */
static void the_engine_installs_no_word_set(void **state)
{
    fbrl_vm_config cfg;
    fbrl_vm *bare;
    fbrl_cell xt;
    (void)state;
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = malloc(MEM_SIZE);
    assert_non_null(cfg.mem);
    cfg.mem_size = MEM_SIZE;
    assert_int_equal(fbrl_vm_create(&bare, &cfg), FBRL_OK);
    assert_int_equal(fbrl_vmx_find(bare, "CREATE-Q", 8, &xt), FBRL_ENOENT);
    assert_int_equal(fbrl_vmx_find(bare, "LOCATION", 8, &xt), FBRL_ENOENT);
    assert_int_equal(fbrl_vmx_data_words(bare), FBRL_OK);
    assert_int_equal(fbrl_vmx_find(bare, "CREATE-Q", 8, &xt), FBRL_OK);
    assert_int_equal(fbrl_vm_eval(bare, "8 CREATE-Q Q 65 Q ENQ Q DEQ", 27), FBRL_OK);
    fbrl_cell c = 0;
    assert_int_equal(fbrl_vm_pop(bare, &c), FBRL_OK);
    assert_int_equal(c, 65);
    free(cfg.mem);
}

/* ---- the one parser ---- */

static void parameters_parse_as_the_interpreter(void **state)
{
    fixture *f = *state;
    /* regression: `SPEED 'A'` was refused while `'A' SPEED` was accepted */
    assert_int_equal(ev(f, "'(' SPEED"), OFFLINE_CODE); /* 40: taken, then offline */
    assert_int_equal(ev(f, "SPEED '('"), OFFLINE_CODE);
    assert_int_equal(ev(f, "'z' SPEED"), FBRL_THROW_BAD_NUMBER); /* 122: taken, then out of 1..100 */
    assert_int_equal(ev(f, "SPEED 'z'"), FBRL_THROW_BAD_NUMBER);
    assert_non_null(strstr(fbrl_vm_last_error(f->vm)->message, "speed 122 outside 1..100"));
    assert_int_equal(ev(f, "GETINT 'A' GETINT $10 GETINT %101"), 0);
    assert_int_equal(pop(f), 5);
    assert_int_equal(pop(f), 16);
    assert_int_equal(pop(f), 65);
    assert_int_equal(ev(f, "GETINT -#12"), FBRL_THROW_BAD_NUMBER); /* the interpreter's rule too */
    assert_int_equal(ev(f, "-#12"), FBRL_THROW_UNDEFINED);
    /* BASE applies after the word as before it */
    assert_int_equal(ev(f, "HEX GETINT 10 DECIMAL"), 0);
    assert_int_equal(pop(f), 16);
    double d = 0;
    assert_int_equal(ev(f, "GETREAL 2 GETREAL 'A'"), 0);
    assert_int_equal(fbrl_vm_fpop(f->vm, &d), FBRL_OK);
    assert_true(d == 65.0);
    assert_int_equal(fbrl_vm_fpop(f->vm, &d), FBRL_OK);
    assert_true(d == 2.0);
}

/* ---- integers where reals are expected: one rule, every word ---- */

/* Each word that takes reals, given them as floats and as integers (the integers beneath
 * the word's other parameters, docs/language.md); probe shows the effect. Offline, the
 * robot words reach the offline error only when their parameters were taken. */
typedef struct form {
    const char *word, *setup, *floats, *ints, *probe;
    int code;
} form;

#define LOC "CREATE-LOC P 14E0 2E0 8E0 0E0 -90E0 0E0 P DEFINE-LOC CREATE-LOC Q "
#define XYZ " Q GETX Q GETY Q GETZ Q GETO Q GETA Q GETT"
static const form forms[] = {
    {"DEFINE-LOC", "CREATE-LOC Q", "14E0 2E0 8E0 0E0 -90E0 0E0 Q DEFINE-LOC", "14 2 8 0 -90 0 Q DEFINE-LOC",
     XYZ, 0},
    {"SETX", LOC, "5E0 Q SETX", "5 Q SETX", XYZ, 0},
    {"SETY", LOC, "-5E0 Q SETY", "-5 Q SETY", XYZ, 0},
    {"SETZ", LOC, "3E0 Q SETZ", "3 Q SETZ", XYZ, 0},
    {"SETO", LOC, "45E0 Q SETO", "45 Q SETO", XYZ, 0},
    {"SETA", LOC, "-90E0 Q SETA", "-90 Q SETA", XYZ, 0},
    {"SETT", LOC, "30E0 Q SETT", "30 Q SETT", XYZ, 0},
    {"RECTMAT", LOC, "P 1E0 2E0 0E0 RECTMAT M", "1 2 0 P RECTMAT M", " 2 1 0 Q M" XYZ, 0},
    {"AUTOMAT", LOC, "P 1E0 2E0 0E0 AUTOMAT M", "1 2 0 P AUTOMAT M", " 2 1 0 Q M" XYZ, 0},
    {"RADMAT", LOC, "P 1E0 2E0 3E0 RADMAT M", "1 2 3 P RADMAT M", " 1 1 1 Q M" XYZ, 0},
    {"CM->IN", "", "254E0 CM->IN", "254 CM->IN", "", 0},
    {"IN->CM", "", "3E0 IN->CM", "3 IN->CM", "", 0},
    {"METRIC-IN", "METRIC-ON", "254E0 METRIC-IN", "254 METRIC-IN", "", 0},
    {"METRIC-OUT", "METRIC-ON", "2E0 METRIC-OUT", "2 METRIC-OUT", "", 0},
    {"CAL-STRU!", "CREATE-CAL-STRU S", "2E0 S 1 CAL-STRU!", "2 S 1 CAL-STRU!", " S 1 CAL-STRU@", 0},
    {"ROTATE", "", "1E0 2E0 3E0 ROTATE", "1 2 3 ROTATE", "", 0},
    {"ANG-FROM-ORIGIN", "", "0E0 0E0 1E0 1E0 ANG-FROM-ORIGIN", "0 0 1 1 ANG-FROM-ORIGIN", "", 0},
    {"JOG", "", "0E0 0E0 -1E0 JOG", "0 0 -1 JOG", "", OFFLINE_CODE},
    {"DEPART", "", "2E0 DEPART", "2 DEPART", "", OFFLINE_CODE},
    {"DEPART-STRT", "", "2E0 DEPART-STRT", "2 DEPART-STRT", "", OFFLINE_CODE},
    {"APPROACH", LOC, "P 2E0 APPROACH", "2 P APPROACH", "", OFFLINE_CODE},
    {"APPROACH-STRT", LOC, "P 2E0 APPROACH-STRT", "2 P APPROACH-STRT", "", OFFLINE_CODE},
    {"MA", "", "0E0 1E0 -1E0 0E0 0E0 MA", "0 1 -1 0 0 MA", "", OFFLINE_CODE},
    {"MI", "", "0E0 1E0 -1E0 0E0 0E0 MI", "0 1 -1 0 0 MI", "", OFFLINE_CODE},
    {"GAIN", "", "1 2E0 GAIN", "2 1 GAIN", "", OFFLINE_CODE},
    {"GRIP", "", "50 1E0 GRIP", "1 50 GRIP", "", OFFLINE_CODE},
    {"BASE-OFFSET", "", "1E0 2E0 3E0 90E0 BASE-OFFSET", "1 2 3 90 BASE-OFFSET", "", 0},
    {"SET-RAPL-REAL", "", "S\" V1\" 2E0 SET-RAPL-REAL", "2 S\" V1\" SET-RAPL-REAL", "", OFFLINE_CODE},
    {"F.-COM", "", "2E0 F.-COM", "2 F.-COM", "", OFFLINE_CODE},
    {"SEND-REAL", "16 SEND-COM", "2E0 SEND-REAL", "2 SEND-REAL", "", 0},
    {"DISPENSE", "5 OUTPUT-DEVICE PUMP", "PUMP 2E0 DISPENSE", "2 PUMP DISPENSE", "", OFFLINE_CODE},
};

typedef struct outcome {
    int code;
    size_t depth, fdepth;
    fbrl_cell cells[16];
    double reals[16];
    char line[96];
    double base[4];
} outcome;

static void run_form(const form *fm, const char *body, outcome *o)
{
    fixture *f = make();
    char text[512];
    memset(o, 0, sizeof *o);
    assert_int_equal(ev(f, fm->setup), 0);
    snprintf(text, sizeof text, "%s%s", body, fm->probe);
    o->code = ev(f, text);
    o->depth = fbrl_vm_depth(f->vm);
    o->fdepth = fbrl_vm_fdepth(f->vm);
    assert_true(o->depth <= 16 && o->fdepth <= 16);
    for (size_t k = 0; k < o->depth; k++)
        fbrl_vm_pop(f->vm, &o->cells[k]);
    for (size_t k = 0; k < o->fdepth; k++)
        fbrl_vm_fpop(f->vm, &o->reals[k]);
    memcpy(o->line, f->r.line, sizeof o->line < sizeof f->r.line ? sizeof o->line : sizeof f->r.line);
    memcpy(o->base, f->r.base, sizeof o->base);
    drop(f);
}

/* Words that take reals: "( F: x ... -- ..." with something before the "--". */
static int takes_reals(const char *stack)
{
    const char *p = strstr(stack, "F:");
    if (!p)
        return 0;
    for (p += 2; *p == ' '; p++) {
    }
    return strncmp(p, "--", 2) != 0;
}

static int collect(void *ctx, const char *name, size_t len)
{
    fixture *f = ctx;
    char w[64];
    const char *stack = NULL;
    if (len >= sizeof w)
        return 0;
    memcpy(w, name, len);
    w[len] = 0;
    if (fbrl_vm_help(f->vm, w, &stack, NULL) != FBRL_OK || !takes_reals(stack))
        return 0;
    size_t k;
    for (k = 0; k < sizeof forms / sizeof forms[0]; k++)
        if (strcmp(forms[k].word, w) == 0)
            break;
    if (k == sizeof forms / sizeof forms[0]) {
        /* a word set word that takes reals and has no row: the bare engine lacks it */
        fbrl_cell xt;
        unsigned char *mem = malloc(MEM_SIZE);
        fbrl_vm_config cfg;
        fbrl_vm *bare;
        memset(&cfg, 0, sizeof cfg);
        cfg.mem = mem;
        cfg.mem_size = MEM_SIZE;
        assert_int_equal(fbrl_vm_create(&bare, &cfg), FBRL_OK);
        int engine = fbrl_vmx_find(bare, w, len, &xt) == FBRL_OK;
        free(mem);
        if (!engine) {
            print_error("%s takes reals %s but has no row in forms[]\n", w, stack);
            fail();
        }
    }
    return 0;
}

static void integers_stand_for_reals(void **state)
{
    fixture *f = *state;
    /* the table covers every word set word that takes reals */
    fbrl_vm_words(f->vm, collect, f);
    for (size_t k = 0; k < sizeof forms / sizeof forms[0]; k++) {
        outcome a, b;
        run_form(&forms[k], forms[k].floats, &a);
        run_form(&forms[k], forms[k].ints, &b);
        if (a.code != forms[k].code || b.code != forms[k].code)
            print_error("%s: floats gave %d, integers %d, want %d\n", forms[k].word, a.code, b.code,
                        forms[k].code);
        assert_int_equal(a.code, forms[k].code);
        assert_int_equal(b.code, forms[k].code);
        assert_int_equal(a.depth, b.depth);
        assert_int_equal(a.fdepth, b.fdepth);
        assert_memory_equal(a.cells, b.cells, sizeof a.cells);
        assert_memory_equal(a.reals, b.reals, sizeof a.reals);
        assert_memory_equal(a.line, b.line, sizeof a.line);
        assert_memory_equal(a.base, b.base, sizeof a.base);
    }
    /* the effects are real ones (not two equal failures) */
    outcome o;
    run_form(&forms[0], forms[0].ints, &o);
    assert_int_equal(o.fdepth, 6);
    assert_true(o.reals[5] == 14.0 && o.reals[4] == 2.0 && o.reals[1] == -90.0);
    /* too few of both: the float stack is what is missing */
    assert_int_equal(ev(f, "CREATE-LOC R 1 2 R DEFINE-LOC"), FBRL_THROW_FSTACK_UNDERFLOW);
    assert_int_equal(ev(f, "DEFINE-LOC"), FBRL_THROW_STACK_UNDERFLOW);
}

/* ---- parsing, execute, evaluate ---- */

static fbrl_status w_twice(fbrl_vm *vm, void *ctx, const void *word)
{
    const char *name;
    size_t n;
    fbrl_cell xt;
    (void)ctx;
    (void)word;
    if (fbrl_vm_parse_name(vm, &name, &n) != FBRL_OK || n == 0)
        return fbrl_vm_throw(vm, FBRL_THROW_NO_NAME, NULL);
    if (fbrl_vmx_find(vm, name, n, &xt) != FBRL_OK)
        return fbrl_vm_throw(vm, FBRL_THROW_UNDEFINED, NULL);
    fbrl_status st = fbrl_vmx_execute(vm, xt);
    return st == FBRL_OK ? fbrl_vmx_execute(vm, xt) : st;
}

static fbrl_status w_quoted(fbrl_vm *vm, void *ctx, const void *word)
{
    const char *s;
    size_t n;
    (void)ctx;
    (void)word;
    int q = fbrl_vmx_parse_quoted(vm, &s, &n);
    if (q <= 0)
        return fbrl_vm_throw(vm, q ? FBRL_THROW_BAD_NUMBER : FBRL_THROW_UNEXPECTED_EOF, NULL);
    return fbrl_vmx_evaluate(vm, s, n);
}

static void parse_execute_evaluate(void **state)
{
    fixture *f = *state;
    assert_int_equal(fbrl_vmx_define(f->vm, "TWICE", w_twice, NULL, NULL, 0, "( \"name\" -- )", "x"),
                     FBRL_OK);
    assert_int_equal(fbrl_vmx_define(f->vm, "EVAL-Q", w_quoted, NULL, NULL, 0, "( \"text\" -- )", "x"),
                     FBRL_OK);
    assert_int_equal(ev(f, "VARIABLE N 0 N ! : BUMP 1 N +! ; TWICE BUMP N @"), 0);
    assert_int_equal(pop(f), 2);
    assert_int_equal(ev(f, "EVAL-Q   \"3 4 +\" 10 *"), 0);
    assert_int_equal(pop(f), 70);
    assert_int_equal(ev(f, "EVAL-Q \"1 0 /\""), FBRL_THROW_DIV_ZERO);
    assert_int_equal(ev(f, "EVAL-Q \"3 4"), FBRL_THROW_UNEXPECTED_EOF);
    assert_int_equal(ev(f, "EVAL-Q 3"), FBRL_THROW_BAD_NUMBER);
    assert_int_equal(ev(f, "TWICE NOSUCHWORD"), FBRL_THROW_UNDEFINED);
    assert_int_equal(fbrl_vm_depth(f->vm), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(failed_creation_leaves_no_word),
        cmocka_unit_test_setup_teardown(typed_data_is_checked, setup, teardown),
        cmocka_unit_test_setup_teardown(words_have_flags_and_two_contexts, setup, teardown),
        cmocka_unit_test_setup_teardown(a_word_set_is_a_table, setup, teardown),
        cmocka_unit_test(the_engine_installs_no_word_set),
        cmocka_unit_test_setup_teardown(parameters_parse_as_the_interpreter, setup, teardown),
        cmocka_unit_test_setup_teardown(integers_stand_for_reals, setup, teardown),
        cmocka_unit_test_setup_teardown(parse_execute_evaluate, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
