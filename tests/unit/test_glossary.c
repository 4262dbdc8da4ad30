/* SPDX-License-Identifier: MIT */
/* test_glossary.c - the data glossary words (locations, matrices, calibration, metric,
 * files): the Forth conformance files tests/forth/glossary_*.fs, the printed texts, the
 * C interface the robot words use, and the file table's commit-on-finish. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>
#include <unistd.h>
#include <sys/stat.h>
#include <cmocka.h>

#include "fbrl/calib.h"
#include "fbrl/fileio.h"
#include "fbrl/glossary.h"
#include "fbrl/vm.h"
#include "fbrl/vmx.h"
#include "support/vm_host.h"

#define FORTH_DIR    FBRL_TEST_SRCDIR "/tests/forth/"
#define FILE_STORAGE (8 * 8192) /* 8 KB of records per open file */

/* ---- a host: console and port output into texts, source files through stdio
 * (support/vm_host.h) ---- */
typedef struct fixture {
    void *mem;
    vmh_text out, port;
    fbrl_vm *vm;
    fbrl_glossary g;
    unsigned char files[FILE_STORAGE];
    char dir[256];
    char cwd[512];
} fixture;

/* A VM with the glossary installed, working in a fresh empty directory. */
static fixture *new_vm(void)
{
    fixture *f = calloc(1, sizeof *f);
    assert_non_null(f);
    size_t mem_size = 4 << 20;
    f->mem = malloc(mem_size);
    assert_non_null(f->mem);
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = f->mem;
    cfg.mem_size = mem_size;
    cfg.host.user = &f->out;
    cfg.host.write = vmh_write;
    vmh_use_files(&cfg.host);
    assert_int_equal(fbrl_vm_create(&f->vm, &cfg), FBRL_OK);
    assert_int_equal(fbrl_glossary_install(f->vm, &f->g), FBRL_OK);
    assert_int_equal(fbrl_glossary_set_file_storage(&f->g, f->files, sizeof f->files), FBRL_OK);
    assert_non_null(getcwd(f->cwd, sizeof f->cwd));
    snprintf(f->dir, sizeof f->dir, "%s/glossary-XXXXXX", FBRL_TEST_BINDIR);
    assert_non_null(mkdtemp(f->dir));
    assert_int_equal(chdir(f->dir), 0);
    return f;
}

static void rm_tree(const char *dir)
{
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
}

static void free_vm(fixture *f)
{
    assert_int_equal(fbrl_glossary_finish(&f->g), FBRL_OK);
    assert_int_equal(chdir(f->cwd), 0);
    rm_tree(f->dir);
    free(f->mem);
    free(f);
}

static fbrl_status ev(fixture *f, const char *src) { return fbrl_vm_eval(f->vm, src, strlen(src)); }

static void ok(fixture *f, const char *src)
{
    fbrl_status st = ev(f, src);
    if (st != FBRL_OK) {
        const fbrl_vm_error *e = fbrl_vm_last_error(f->vm);
        print_error("'%s': error %d (%s) at '%s'\n", src, e->throw_code, e->message, e->word);
    }
    assert_int_equal(st, FBRL_OK);
}

/* src must throw `code` with a message containing `msg`. */
static void throws(fixture *f, const char *src, int code, const char *msg)
{
    assert_int_not_equal(ev(f, src), FBRL_OK);
    const fbrl_vm_error *e = fbrl_vm_last_error(f->vm);
    if (e->throw_code != code || !strstr(e->message, msg))
        print_error("'%s': got %d '%s'\n", src, e->throw_code, e->message);
    assert_int_equal(e->throw_code, code);
    assert_non_null(strstr(e->message, msg));
}

static void clear(fixture *f)
{
    f->out.n = 0;
    f->out.s[0] = 0;
    f->port.n = 0;
    f->port.s[0] = 0;
}

static fbrl_cell pop1(fixture *f)
{
    fbrl_cell v = 0;
    assert_int_equal(fbrl_vm_pop(f->vm, &v), FBRL_OK);
    return v;
}

/* ---- the Forth files ---- */
static void run_forth_file(const char *name)
{
    fixture *f = new_vm();
    char path[512];
    assert_int_equal(fbrl_vm_include(f->vm, FORTH_DIR "tester.fs"), FBRL_OK);
    snprintf(path, sizeof path, "%s%s", FORTH_DIR, name);
    fbrl_status st = fbrl_vm_include(f->vm, path);
    if (st != FBRL_OK) {
        const fbrl_vm_error *e = fbrl_vm_last_error(f->vm);
        print_error("%s: error %d (%s) at word '%s' %s:%lu\n%s\n", name, e->throw_code, e->message, e->word,
                    e->file, e->line, f->out.s);
    }
    assert_int_equal(st, FBRL_OK);
    ok(f, "#ERRORS @ #TESTS @");
    fbrl_cell tests = pop1(f), errors = pop1(f);
    if (errors)
        print_error("%s: %ld failures:\n%s\n", name, (long)errors, f->out.s);
    assert_int_equal(errors, 0);
    assert_true(tests > 10);
    print_message("%s: %ld tests passed\n", name, (long)tests);
    free_vm(f);
}

/* fbrl_glossary_loc_word: CREATE-LOC words, and no other */
static void loc_words_are_known(void **state)
{
    (void)state;
    fixture *f = new_vm();
    fbrl_cell xt = 0, addr = 0;
    fbrl_loc *loc = NULL;
    ok(f, "CREATE-LOC P1 1E0 2E0 3E0 0E0 -90E0 0E0 P1 DEFINE-LOC VARIABLE V CREATE-LOC P2");
    assert_int_equal(fbrl_vmx_find(f->vm, "P1", 2, &xt), FBRL_OK);
    assert_int_equal(fbrl_glossary_loc_word(f->vm, xt, &addr), FBRL_OK);
    assert_int_equal(fbrl_glossary_loc(f->vm, addr, &loc), FBRL_OK);
    assert_true(loc->y == 2.0 && loc->a == -90.0);
    ok(f, "P1");
    assert_int_equal(pop1(f), addr);
    assert_int_equal(fbrl_vmx_find(f->vm, "V", 1, &xt), FBRL_OK);
    assert_int_equal(fbrl_glossary_loc_word(f->vm, xt, &addr), FBRL_ETYPE);
    assert_int_equal(fbrl_vmx_find(f->vm, "DUP", 3, &xt), FBRL_OK);
    assert_int_equal(fbrl_glossary_loc_word(f->vm, xt, &addr), FBRL_ETYPE);
    assert_int_equal(fbrl_vmx_find(f->vm, "P2", 2, &xt), FBRL_OK);
    assert_int_equal(fbrl_glossary_loc_word(f->vm, xt, &addr), FBRL_OK);
    assert_int_equal(fbrl_glossary_loc_word(f->vm, xt, NULL), FBRL_EINVAL);
    free_vm(f);
}

static void forth_loc(void **state)
{
    (void)state;
    run_forth_file("glossary_loc.fs");
}
static void forth_cal(void **state)
{
    (void)state;
    run_forth_file("glossary_cal.fs");
}
static void forth_file(void **state)
{
    (void)state;
    run_forth_file("glossary_file.fs");
}

/* ---- every word has HELP text ---- */
static const char *const all_words[] = {
    "CREATE-LOC",
    "GETX",
    "GETY",
    "GETZ",
    "GETO",
    "GETA",
    "GETT",
    "SETX",
    "SETY",
    "SETZ",
    "SETO",
    "SETA",
    "SETT",
    "SET-LOC",
    "DEFINE-LOC",
    "SHIFTA",
    "DISPLAY-LOC",
    "PRINT-LOC",
    "RECTMAT",
    "AUTOMAT",
    "RADMAT",
    "SHOW-AUTOMAT",
    "SHOW-RADMAT",
    "METRIC-ON",
    "METRIC-OFF",
    "METRIC?",
    "CM->IN",
    "IN->CM",
    "METRIC-IN",
    "METRIC-OUT",
    "MAP-ON",
    "MAP-OFF",
    "MAPPING?",
    "WITH-CAL",
    "CREATE-CAL",
    "CAL-ADDR",
    "SET-CAL",
    "GET-CAL",
    "CREATE-CAL-STRU",
    "CAL-STRU@",
    "CAL-STRU!",
    "NUM-CAL-CELLS",
    "ANG-FROM-ORIGIN",
    "ROTATE",
    "CALIBRATE",
    "(MAP)",
    "UNMAP",
    "CALIBRATE-N",
    "CREATE-FILE",
    "OPEN-FILE",
    "RESET-FILE",
    "APPEND-FILE",
    "CLOSE-FILE",
    "WRITE-FILE",
    "READ-FILE",
    "SAVE-CAL",
    "LOAD-CAL",
};

static void every_word_has_help(void **state)
{
    (void)state;
    fixture *f = new_vm();
    for (size_t i = 0; i < sizeof all_words / sizeof all_words[0]; i++) {
        const char *stack = NULL, *help = NULL;
        assert_int_equal(fbrl_vm_help(f->vm, all_words[i], &stack, &help), FBRL_OK);
        assert_true(stack[0] == '(' && strlen(help) > 10);
    }
    clear(f);
    ok(f, "HELP CAL-STRU@");
    assert_non_null(strstr(f->out.s, "( cal-stru index -- ) ( F: -- v )"));
    ok(f, "CREATE-LOC HOME");
    assert_int_equal(fbrl_vm_help(f->vm, "home", NULL, NULL), FBRL_OK);
    free_vm(f);
}

static void install_checks_arguments(void **state)
{
    (void)state;
    fbrl_glossary g;
    fbrl_loc *loc;
    assert_int_equal(fbrl_glossary_install(NULL, &g), FBRL_EINVAL);
    fixture *f = new_vm();
    assert_int_equal(fbrl_glossary_install(f->vm, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_glossary_finish(NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_glossary_set_file_storage(NULL, f->files, 16), FBRL_EINVAL);
    assert_int_equal(fbrl_glossary_map_out(NULL, &(fbrl_loc){0}, NULL, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_glossary_map_in(&f->g, NULL, NULL), FBRL_EINVAL);
    assert_null(fbrl_glossary_units(NULL));
    assert_int_equal(fbrl_glossary_loc(NULL, 0, &loc), FBRL_EINVAL);
    assert_int_equal(fbrl_glossary_loc(f->vm, 0, &loc), FBRL_ERANGE);
    ok(f, "CREATE-LOC P");
    ok(f, "P");
    fbrl_cell p = pop1(f);
    assert_int_equal(fbrl_glossary_loc(f->vm, p, &loc), FBRL_OK);
    assert_int_equal(fbrl_glossary_loc(f->vm, p + 4, &loc), FBRL_ERANGE); /* misaligned */
    assert_int_equal(fbrl_glossary_loc(f->vm, p, NULL), FBRL_EINVAL);
    /* CREATE-CAL slots from C: the same memory CAL-ADDR gives */
    fbrl_calpts *c;
    ok(f, "CREATE-CAL C C C 2 CAL-ADDR");
    fbrl_cell slot2 = pop1(f), cal = pop1(f);
    assert_int_equal(fbrl_glossary_calpts(f->vm, cal, &c), FBRL_OK);
    assert_ptr_equal(&c->p[1], (void *)slot2);
    assert_int_equal(fbrl_glossary_calpts(f->vm, p, &c), FBRL_ETYPE);
    assert_int_equal(fbrl_glossary_calpts(f->vm, 0, &c), FBRL_ERANGE);
    assert_int_equal(fbrl_glossary_calpts(NULL, cal, &c), FBRL_EINVAL);
    free_vm(f);
}

/* ---- printed texts ---- */
static void display_loc_text(void **state)
{
    (void)state;
    fixture *f = new_vm();
    ok(f, "CREATE-LOC P 12E0 -3.5E0 1.25E0 90E0 -90E0 0E0 P DEFINE-LOC");
    clear(f);
    ok(f, "P DISPLAY-LOC");
    assert_string_equal(f->out.s,
                        "X   +12.0000 Y    -3.5000 Z    +1.2500 in  O  +90.000 A  -90.000 T   +0.000 deg\n");
    clear(f);
    ok(f, "METRIC-ON P DISPLAY-LOC METRIC-OFF");
    assert_string_equal(f->out.s,
                        "X   +30.4800 Y    -8.8900 Z    +3.1750 cm  O  +90.000 A  -90.000 T   +0.000 deg\n");
    /* with mapping on, the location the arm is sent to: block turned 90 deg about z, moved (10,5,0) */
    ok(f, "CREATE-CAL-STRU S 0E0 S 1 CAL-STRU! -1E0 S 2 CAL-STRU! 10E0 S 4 CAL-STRU! "
          "1E0 S 5 CAL-STRU! 0E0 S 6 CAL-STRU! 5E0 S 8 CAL-STRU! S WITH-CAL MAP-ON");
    clear(f);
    ok(f, "P DISPLAY-LOC");
    /* the waist points at (13.5, 17): yaw atan2(17, 13.5) = 51.546; the grip heading
     * (waist - roll + 90) was -16.260 + 90 = 73.740 and turns by 90 to 163.740, so roll =
     * 51.546 + 90 - 163.740 = -22.194 (docs/calibration.md) */
    assert_string_equal(f->out.s,
                        "X   +13.5000 Y   +17.0000 Z    +1.2500 in  O  +51.546 A  -90.000 T  -22.194 deg\n");
    ok(f, "MAP-OFF P GETX"); /* the stored location is unchanged */
    double x;
    assert_int_equal(fbrl_vm_fpop(f->vm, &x), FBRL_OK);
    assert_true(x == 12.0);
    /* mapping on, but the selected structure was overwritten since */
    ok(f, "MAP-ON 0 S !");
    throws(f, "P DISPLAY-LOC", -325, "DISPLAY-LOC: mapping on but the WITH-CAL structure is unusable");
    free_vm(f);
}

static void port_writer(void *ctx, const char *s, size_t n) { vmh_put(ctx, s, n); }

static void print_loc_port(void **state)
{
    (void)state;
    fixture *f = new_vm();
    ok(f, "CREATE-LOC P 1E0 2E0 3E0 4E0 5E0 6E0 P DEFINE-LOC");
    throws(f, "P PRINT-LOC", -330, "PRINT-LOC: no communication port");
    fbrl_glossary_set_port_writer(&f->g, port_writer, &f->port);
    clear(f);
    ok(f, "P PRINT-LOC P DISPLAY-LOC");
    assert_string_equal(
        f->port.s, "X    +1.0000 Y    +2.0000 Z    +3.0000 in  O   +4.000 A   +5.000 T   +6.000 deg\r\n");
    assert_int_equal(strncmp(f->port.s, f->out.s, strlen(f->out.s) - 1), 0); /* the same text */
    throws(f, "0 PRINT-LOC", -9, "PRINT-LOC: address is not a location");
    fbrl_glossary_set_port_writer(&f->g, NULL, NULL);
    throws(f, "P PRINT-LOC", -330, "no communication port");
    free_vm(f);
}

static void show_matrices(void **state)
{
    (void)state;
    fixture *f = new_vm();
    ok(f, "CREATE-LOC B 1E0 2E0 3E0 0E0 -90E0 0E0 B DEFINE-LOC B 0.75E0 -1.25E0 0.5E0 RECTMAT MAT");
    ok(f, "10E0 0E0 2E0 0E0 -90E0 0E0 B DEFINE-LOC B 0.2E0 0.5E0 1E0 RADMAT RM");
    clear(f);
    ok(f, "' MAT SHOW-AUTOMAT");
    assert_string_equal(f->out.s,
                        "RECTMAT base X    +1.0000 Y    +2.0000 Z    +3.0000 in  O   +0.000 A  -90.000 "
                        "T   +0.000 deg  step X    +0.7500 Y    -1.2500 Z    +0.5000 in\n");
    clear(f);
    ok(f, "METRIC-ON ' RM SHOW-RADMAT");
    assert_string_equal(f->out.s,
                        "RADMAT base X   +25.4000 Y    +0.0000 Z    +5.0800 cm  O   +0.000 A  -90.000 "
                        "T   +0.000 deg  inc +0.200000 rad  ring    +1.2700 Z    +2.5400 cm  "
                        "radius   +25.4000 cm  angle +0.000000 rad\n");
    throws(f, "' DUP SHOW-RADMAT", -12, "SHOW-RADMAT: not a RADMAT");
    free_vm(f);
}

static void calibrate_n_report(void **state)
{
    (void)state;
    fixture *f = new_vm();
    /* four corners of a 4 x 3 block shifted by (1, 2, 0), one taught 0.1 in too high */
    ok(f, "4 LOCATION ARRAY C 4 LOCATION ARRAY R CREATE-CAL-STRU S "
          ": PT ( a -- ) ( F: x y z -- ) >R 0E0 0E0 0E0 R> DEFINE-LOC ; "
          "0E0 0E0 0E0 0 C PT 4E0 0E0 0E0 1 C PT 0E0 3E0 0E0 2 C PT 4E0 3E0 0E0 3 C PT "
          "1E0 2E0 0E0 0 R PT 5E0 2E0 0E0 1 R PT 1E0 5E0 0E0 2 R PT 5E0 5E0 0E0 3 R PT");
    clear(f);
    ok(f, "4 0 C 0 R S CALIBRATE-N");
    assert_string_equal(f->out.s, "point   0 residual     0.0000 in\n"
                                  "point   1 residual     0.0000 in\n"
                                  "point   2 residual     0.0000 in\n"
                                  "point   3 residual     0.0000 in\n"
                                  "RMS 0.0000 in, worst point 0 (0.0000 in)\n");
    double rms;
    assert_int_equal(fbrl_vm_fpop(f->vm, &rms), FBRL_OK);
    assert_true(rms < 1e-9);
    pop1(f);
    ok(f, "S 4 CAL-STRU@ S 8 CAL-STRU@");
    double tx, ty;
    fbrl_vm_fpop(f->vm, &ty);
    fbrl_vm_fpop(f->vm, &tx);
    assert_true(fabs(tx - 1.0) < 1e-12 && fabs(ty - 2.0) < 1e-12);
    ok(f, "0.1E0 2 R SETZ");
    clear(f);
    ok(f, "METRIC-ON 4 0 C 0 R S CALIBRATE-N METRIC-OFF");
    assert_int_equal(pop1(f), 2);
    assert_int_equal(fbrl_vm_fpop(f->vm, &rms), FBRL_OK);
    /* the residuals' RMS in cm, as printed */
    char want[64];
    snprintf(want, sizeof want, "RMS %.4f cm, worst point 2", rms);
    assert_non_null(strstr(f->out.s, want));
    assert_true(rms > 0.01 && rms < 0.254);
    assert_int_equal((int)(strstr(f->out.s, "point   3") != NULL), 1);
    free_vm(f);
}

/* ---- the C interface of the robot words ---- */
static void mapping_interface(void **state)
{
    (void)state;
    fixture *f = new_vm();
    fbrl_loc l = {2, 3, 1, 30, -45, 10}, m;
    /* mapping off: unchanged */
    m = l;
    assert_int_equal(fbrl_glossary_map_out(&f->g, &m, NULL, NULL), FBRL_OK);
    assert_memory_equal(&m, &l, sizeof m);
    assert_int_equal(fbrl_glossary_map_in(&f->g, &m, NULL), FBRL_OK);
    assert_memory_equal(&m, &l, sizeof m);
    /* a block taught, moved (turned 90 degrees, shifted (10, 5, 0)) and re-taught */
    ok(f, "CREATE-CAL C CREATE-CAL R CREATE-CAL-STRU S CREATE-LOC T "
          ": TEACH ( cal slot -- ) ( F: x y z -- ) T >R 0E0 0E0 0E0 R> DEFINE-LOC T SET-CAL ; "
          "0E0 0E0 0E0 C 1 TEACH 1E0 0E0 0E0 C 2 TEACH 0E0 1E0 0E0 C 3 TEACH "
          "10E0 5E0 0E0 R 1 TEACH 10E0 6E0 0E0 R 2 TEACH 9E0 5E0 0E0 R 3 TEACH R C S CALIBRATE S WITH-CAL");
    m = l;
    assert_int_equal(fbrl_glossary_map_out(&f->g, &m, NULL, NULL), FBRL_OK); /* still off */
    assert_memory_equal(&m, &l, sizeof m);
    ok(f, "MAP-ON");
    /* tilted 45 degrees: after the turn its axis heads 146.3 where the waist heads 45, so
     * it would lie 43.9 degrees across the arm: refused, loc unchanged, the angle told */
    double off = 0;
    assert_int_equal(fbrl_glossary_map_out(&f->g, &m, NULL, &off), FBRL_ERANGE);
    assert_memory_equal(&m, &l, sizeof m);
    assert_true(fabs(off - asin(cos(FBRL_PI / 4) * sin(atan2(3, 2) + FBRL_PI / 2 - FBRL_PI / 4)) * 180 /
                               FBRL_PI) < 1e-9);
    /* straight down: the grip (heading waist - roll + 90) turns by the block's 90 degrees */
    m.a = -90;
    assert_int_equal(fbrl_glossary_map_out(&f->g, &m, NULL, &off), FBRL_OK);
    double w0 = atan2(3, 2) * 180 / FBRL_PI;
    assert_true(fabs(m.x - 7) < 1e-12 && fabs(m.y - 7) < 1e-12 && fabs(m.z - 1) < 1e-12);
    assert_true(fabs(m.o - 45) < 1e-9 && fabs(m.a + 90) < 1e-9 && fabs(off) < 1e-9);
    assert_true(fabs(m.t - (45 + 90 - (w0 - 10 + 90 + 90))) < 1e-9);
    assert_int_equal(fbrl_glossary_map_in(&f->g, &m, NULL), FBRL_OK);
    assert_true(fabs(m.x - 2) < 1e-12 && fabs(m.y - 3) < 1e-12 && fabs(m.o - w0) < 1e-9);
    assert_true(fabs(m.t - 10) < 1e-9);
    /* the arm's base axis elsewhere (BASE-OFFSET): the waist is measured from there */
    double axis[2] = {7, 0};
    m = l;
    m.a = -90;
    assert_int_equal(fbrl_glossary_map_out(&f->g, &m, axis, NULL), FBRL_OK);
    assert_true(fabs(m.o - 90) < 1e-9);
    /* a taught location (moved frame) stored through map_in is the original-frame one */
    fbrl_loc taught = {10, 5, 0, 90, -90, 0};
    assert_int_equal(fbrl_glossary_map_in(&f->g, &taught, NULL), FBRL_OK);
    assert_true(fabs(taught.x) < 1e-12 && fabs(taught.y) < 1e-12);
    /* non-finite input: error, loc unchanged */
    fbrl_loc bad = {0, 0, 1.0 / 0.0, 0, 0, 0}, bad0 = bad;
    assert_int_equal(fbrl_glossary_map_out(&f->g, &bad, NULL, NULL), FBRL_ENONFINITE);
    assert_memory_equal(&bad, &bad0, sizeof bad);
    /* the selected structure overwritten: ESTATE */
    ok(f, "0 S !");
    m = l;
    assert_int_equal(fbrl_glossary_map_out(&f->g, &m, NULL, NULL), FBRL_ESTATE);
    assert_int_equal(fbrl_glossary_map_in(&f->g, &m, NULL), FBRL_ESTATE);
    assert_memory_equal(&m, &l, sizeof m);
    ok(f, "MAP-OFF");
    assert_int_equal(fbrl_glossary_map_out(&f->g, &m, NULL, NULL), FBRL_OK);
    /* metric state */
    const fbrl_units *u = fbrl_glossary_units(&f->g);
    int on = 1;
    assert_int_equal(fbrl_units_is_metric(u, &on), FBRL_OK);
    assert_int_equal(on, 0);
    ok(f, "METRIC-ON");
    assert_int_equal(fbrl_units_is_metric(u, &on), FBRL_OK);
    assert_int_equal(on, 1);
    free_vm(f);
}

static void vms_are_independent(void **state)
{
    (void)state;
    fixture *a = new_vm(), *b = new_vm();
    ok(a, "METRIC-ON METRIC?");
    ok(b, "METRIC?");
    assert_int_equal(pop1(a), -1);
    assert_int_equal(pop1(b), 0);
    free_vm(b);
    free_vm(a);
}

/* ---- files: the table, its limits, commit on finish ---- */
static void file_table(void **state)
{
    (void)state;
    fixture *f = new_vm();
    FILE *t = fopen("text.txt", "w");
    assert_non_null(t);
    fputs("not a data file\n", t);
    fclose(t);
    throws(f, "OPEN-FILE H text.txt", -310, "OPEN-FILE text.txt: not a libfbrl data file");
    /* eight open files at most */
    ok(f, "CREATE-FILE d.fbd");
    char src[64];
    for (int i = 0; i < FBRL_GLOSSARY_FILES; i++) {
        snprintf(src, sizeof src, "OPEN-FILE H%d d.fbd", i);
        ok(f, src);
    }
    throws(f, "OPEN-FILE H8 d.fbd", -306, "too many open files");
    ok(f, "H3 CLOSE-FILE");
    assert_int_equal(pop1(f), 0);
    ok(f, "OPEN-FILE H8 d.fbd");
    /* storage cannot change while files are open */
    assert_int_equal(fbrl_glossary_set_file_storage(&f->g, f->files, sizeof f->files), FBRL_ESTATE);
    /* written, never closed: fbrl_glossary_finish commits */
    ok(f, "CREATE-LOC P 1E0 2E0 3E0 4E0 5E0 6E0 P DEFINE-LOC P LOCATION H8 WRITE-FILE");
    assert_int_equal(fbrl_glossary_finish(&f->g), FBRL_OK);
    fbrl_file file;
    static unsigned char buf[4096];
    fbrl_loc l;
    assert_int_equal(fbrl_file_open(&file, "d.fbd", buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_read_loc(&file, &l), FBRL_OK);
    assert_true(l.x == 1 && l.y == 2 && l.z == 3 && l.o == 4 && l.a == 5 && l.t == 6);
    assert_int_equal(fbrl_file_discard(&file), FBRL_OK);
    throws(f, "H8 RESET-FILE", -325, "RESET-FILE: file handle not open");
    /* a wrong-type read says what is there, and reads nothing */
    ok(f, "OPEN-FILE H8 d.fbd FVARIABLE R");
    throws(f, "R REAL H8 READ-FILE", -314,
           "READ-FILE: next record is LOCATION (48 bytes), not REAL (8 bytes); nothing read");
    ok(f, "CREATE-LOC L L LOCATION H8 READ-FILE L GETT F>S H8 CLOSE-FILE");
    assert_int_equal(pop1(f), 0);
    assert_int_equal(pop1(f), 6);
    throws(f, "PAD 12 H8 READ-FILE", -325, "READ-FILE: file handle not open");
    throws(f, "PAD 12 PAD READ-FILE", -12, "READ-FILE: unknown file handle (OPEN-FILE makes one)");
    /* a file name too long for the file system layer */
    char longname[400] = "CREATE-FILE ";
    memset(longname + 12, 'a', 300);
    throws(f, longname, -324, "CREATE-FILE");
    /* a file fills its share of the storage: 8 KB holds 146 location records of 56 bytes */
    ok(f,
       "CREATE-FILE full.fbd OPEN-FILE HF full.fbd : FILL-UP ( -- ) BEGIN P LOCATION HF WRITE-FILE AGAIN ;");
    throws(f, "FILL-UP", -304, "WRITE-FILE: file full (8192 bytes of records per open file)");
    ok(f, "HF CLOSE-FILE");
    assert_int_equal(pop1(f), 0);
    uint32_t count = 0;
    assert_int_equal(fbrl_file_open(&file, "full.fbd", buf, sizeof buf), FBRL_ENOSPC); /* 4 KB: too small */
    static unsigned char big[16384];
    assert_int_equal(fbrl_file_open(&file, "full.fbd", big, sizeof big), FBRL_OK);
    assert_int_equal(fbrl_file_tell(&file, NULL, &count), FBRL_OK);
    assert_int_equal(count, 8192 / 56);
    assert_int_equal(fbrl_file_discard(&file), FBRL_OK);
    /* no storage: a clear error */
    assert_int_equal(fbrl_glossary_set_file_storage(&f->g, NULL, 0), FBRL_OK);
    throws(f, "OPEN-FILE H9 d.fbd", -21, "no file storage");
    free_vm(f);
}

static void close_failure_keeps_file_open(void **state)
{
    (void)state;
    fixture *f = new_vm();
    assert_int_equal(mkdir("sub", 0700), 0);
    ok(f, "CREATE-FILE sub/d.fbd OPEN-FILE H sub/d.fbd 65 PAD C! PAD CHR H WRITE-FILE");
    assert_int_equal(unlink("sub/d.fbd"), 0);
    assert_int_equal(rmdir("sub"), 0);
    ok(f, "H CLOSE-FILE");
    fbrl_cell code = pop1(f);
    assert_true(code < 0);                                  /* the commit failed: the code, not a throw */
    ok(f, "H RESET-FILE PAD 1+ CHR H READ-FILE PAD 1+ C@"); /* still open, the record still there */
    assert_int_equal(pop1(f), 65);
    assert_int_equal(mkdir("sub", 0700), 0);
    ok(f, "H CLOSE-FILE"); /* the cause fixed: closes and saves */
    assert_int_equal(pop1(f), 0);
    ok(f, "OPEN-FILE H sub/d.fbd PAD 2 + CHR H READ-FILE PAD 2 + C@");
    assert_int_equal(pop1(f), 65);
    /* finish reports a commit it could not make, and still closes the file */
    ok(f, "H APPEND-FILE PAD CHR H WRITE-FILE");
    assert_int_equal(unlink("sub/d.fbd"), 0);
    assert_int_equal(rmdir("sub"), 0);
    assert_int_not_equal(fbrl_glossary_finish(&f->g), FBRL_OK);
    throws(f, "H RESET-FILE", -325, "not open");
    free_vm(f);
}

/* ---- a full dictionary: the defining words fail cleanly ---- */
static void dictionary_full(void **state)
{
    (void)state;
    fixture *f = new_vm();
    ok(f, "CREATE-LOC P 1E0 2E0 3E0 0E0 0E0 0E0 P DEFINE-LOC CREATE-FILE d.fbd UNUSED 3000 - ALLOT");
    const char *makers[] = {"P 1E0 1E0 1E0 RECTMAT", "P 0.1E0 1E0 1E0 RADMAT", "CREATE-LOC", "CREATE-CAL",
                            "CREATE-CAL-STRU"};
    char src[96];
    int made = 0;
    for (int m = 0; m < 5; m++) {
        for (int n = 0;; n++) {
            snprintf(src, sizeof src, "%s W%d-%d", makers[m], m, n);
            if (ev(f, src) != FBRL_OK) {
                assert_int_equal(fbrl_vm_last_error(f->vm)->throw_code, -8); /* dictionary overflow */
                snprintf(src, sizeof src, "[DEFINED] W%d-%d", m, n);
                ok(f, src);
                assert_int_equal(pop1(f), 0); /* no half-made word */
                break;
            }
            made++;
        }
    }
    assert_true(made > 5);
    ok(f, "1 0 0 P W0-0 P GETX F>S 2 3 +"); /* the words made before still work, and the VM does */
    assert_int_equal(pop1(f), 5);
    assert_int_equal(pop1(f), 2);
    free_vm(f);
}

/* ---- the example plan examples/heater_block.fbrl ---- */
static void example_plan(void **state)
{
    (void)state;
    fixture *f = new_vm();
    fbrl_status st = fbrl_vm_include(f->vm, FBRL_TEST_SRCDIR "/examples/heater_block.fbrl");
    if (st != FBRL_OK)
        print_error("%s\n%s\n", fbrl_vm_last_error(f->vm)->message, f->out.s);
    assert_int_equal(st, FBRL_OK);
    /* tube (2, 3) = corner (10, -2) + (1.5, 2.25); the block turned 90 degrees about z and
     * its P1 moved from (10, -2) to (12, 1): (1.5, 2.25) -> (-2.25, 1.5) -> (9.75, 2.5).
     * Orientation for the 5-axis arm (docs/calibration.md): the waist turns from
     * atan2(0.25, 11.5) = 1.245 to atan2(2.5, 9.75) = 14.381, the grip heading (waist -
     * roll + 90) from 91.245 by the block's 90 to 181.245: roll 14.381 + 90 - 181.245. */
    assert_string_equal(
        f->out.s,
        "the rack as taught:\n"
        "RECTMAT base X   +10.0000 Y    -2.0000 Z    +1.0000 in  O   +0.000 A  -90.000 T   +0.000 deg  "
        "step X    +0.7500 Y    +0.7500 Z    +0.0000 in\n"
        "tube 2 3, stored:\n"
        "X   +11.5000 Y    +0.2500 Z    +1.0000 in  O   +0.000 A  -90.000 T   +0.000 deg\n"
        "tube 2 3, where the arm goes now:\n"
        "X    +9.7500 Y    +2.5000 Z    +1.0000 in  O  +14.381 A  -90.000 T  -76.864 deg\n"
        "taught on the moved block, stored:\n"
        "X   +11.5000 Y    +0.2500 Z    +1.0000 in  O   +1.245 A  -90.000 T  +76.864 deg\n"
        "saved, code 0 \n"
        "tube 2 3 through the loaded calibration, in cm:\n"
        "X   +24.7650 Y    +6.3500 Z    +2.5400 cm  O  +14.381 A  -90.000 T  -76.864 deg\n");
    free_vm(f);
}

/* ---- robustness: every word on hostile arguments ----
 * Each word runs many times on random mixes of arguments: addresses of real structures of
 * every kind, those addresses shifted by a few bytes, addresses outside the data space,
 * random cells, and floats including NaN, infinities and huge values. Whatever the word
 * throws, the VM must stay sound (run under ASan+UBSan in CI) and keep working. Writes go
 * only to the structures made here (and to nothing when an address is refused), so the
 * VM's own variables are never the target. */
static uint64_t rng_state = 0x9E3779B97F4A7C15u;
static uint64_t rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return rng_state;
}

static void hostile_arguments(void **state)
{
    (void)state;
    fixture *f = new_vm();
    ok(f, "CREATE-LOC P 1E0 2E0 3E0 4E0 5E0 6E0 P DEFINE-LOC CREATE-LOC Q CREATE-CAL C CREATE-CAL-STRU S "
          "P 1E0 1E0 1E0 RECTMAT MAT P 0.1E0 1E0 1E0 RADMAT RM 4 LOCATION ARRAY LS "
          "CREATE-FILE fz.fbd OPEN-FILE H fz.fbd");
    ok(f, "P Q C S ' MAT ' RM 0 LS H HERE");
    fbrl_cell addr[9];
    for (int i = 8; i >= 0; i--)
        addr[i] = pop1(f);
    const double fl[] = {0.0, 1.0, -1.0, 0.5, 3.0, 1e308, -1e308, 1e-310, 12345.678};
    /* the API refuses to push non-finite floats; Forth code can make them from bits */
    ok(f, "FVARIABLE NANV HEX 7FF8000000000000 NANV ! FVARIABLE INFV 7FF0000000000000 INFV ! "
          "FVARIABLE -INFV FFF0000000000000 -INFV ! DECIMAL");
    static const char *const nonfinite[] = {"NANV F@ ", "INFV F@ ", "-INFV F@ "};
    /* every word that takes arguments from the stacks (the parsing ones take names) */
    static const char *const words[] = {
        "GETX",       "GETO",         "SETY",        "SETT",       "SET-LOC",
        "DEFINE-LOC", "SHIFTA",       "DISPLAY-LOC", "PRINT-LOC",  "MAT",
        "RM",         "SHOW-AUTOMAT", "SHOW-RADMAT", "METRIC-IN",  "METRIC-OUT",
        "CM->IN",     "IN->CM",       "WITH-CAL",    "MAP-ON",     "CAL-ADDR",
        "SET-CAL",    "GET-CAL",      "CAL-STRU@",   "CAL-STRU!",  "ANG-FROM-ORIGIN",
        "ROTATE",     "CALIBRATE",    "(MAP)",       "UNMAP",      "CALIBRATE-N",
        "RESET-FILE", "APPEND-FILE",  "WRITE-FILE",  "READ-FILE",  "SAVE-CAL",
        "LOAD-CAL",   "DISPLAY-LOC",  "METRIC-ON",   "METRIC-OFF", "MAP-OFF",
    };
    fbrl_glossary_set_port_writer(&f->g, port_writer, &f->port);
    int thrown = 0, done = 0;
    for (int n = 0; n < 20000; n++) {
        const char *w = words[rnd() % (sizeof words / sizeof words[0])];
        int ncells = (int)(rnd() % 5), nfl = (int)(rnd() % 7);
        for (int k = 0; k < ncells; k++) {
            fbrl_cell v;
            switch (rnd() % 6) {
            case 0: v = addr[rnd() % 9]; break;
            case 1: v = addr[rnd() % 9] + (fbrl_cell)(rnd() % 97) - 48; break;
            case 2: v = (fbrl_cell)(rnd() % 16) - 3; break; /* small numbers: indices, sizes */
            case 3: v = (fbrl_cell)rnd(); break;
            case 4: v = (fbrl_cell)(rnd() % 120); break;
            default: v = addr[rnd() % 9] + 48 * (fbrl_cell)(rnd() % 4); break;
            }
            assert_int_equal(fbrl_vm_push(f->vm, v), FBRL_OK);
        }
        char src[128] = "";
        for (int k = 0; k < nfl; k++) {
            if (rnd() % 4 == 0)
                strcat(src, nonfinite[rnd() % 3]);
            else
                assert_int_equal(fbrl_vm_fpush(f->vm, fl[rnd() % (sizeof fl / sizeof fl[0])]), FBRL_OK);
        }
        strcat(src, w);
        if (ev(f, src) == FBRL_OK)
            done++;
        else
            thrown++;
        while (fbrl_vm_depth(f->vm))
            pop1(f);
        double d;
        while (fbrl_vm_fdepth(f->vm))
            fbrl_vm_fpop(f->vm, &d);
        if (f->out.n > sizeof f->out.s / 2)
            clear(f);
    }
    assert_true(thrown > 1000 && done > 1000);
    ok(f, "MAP-OFF METRIC-OFF 2 3 +");
    assert_int_equal(pop1(f), 5);
    print_message("hostile arguments: %d ran, %d refused\n", done, thrown);
    free_vm(f); /* H may have been overwritten: finish still closes its file */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(loc_words_are_known), cmocka_unit_test(forth_loc),
        cmocka_unit_test(forth_cal),           cmocka_unit_test(forth_file),
        cmocka_unit_test(every_word_has_help), cmocka_unit_test(install_checks_arguments),
        cmocka_unit_test(display_loc_text),    cmocka_unit_test(print_loc_port),
        cmocka_unit_test(show_matrices),       cmocka_unit_test(calibrate_n_report),
        cmocka_unit_test(mapping_interface),   cmocka_unit_test(vms_are_independent),
        cmocka_unit_test(file_table),          cmocka_unit_test(close_failure_keeps_file_open),
        cmocka_unit_test(hostile_arguments),   cmocka_unit_test(example_plan),
        cmocka_unit_test(dictionary_full),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
