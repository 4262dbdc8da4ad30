/* SPDX-License-Identifier: MIT */
/* test_robot.c - the robot words without a controller: installation, the offline error,
 * parameters on the stack or after the word (I-6), argument checks made before anything
 * is sent, the host-side words (I-8 line building, serial settings, devices, timers,
 * SHIFT-RIGHT, BASE-OFFSET), and several independent VMs with their own robots.
 * Everything that talks to a controller is tested end to end against fbrlsim
 * (tests/e2e/robot.cmake). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>
#include <cmocka.h>

#include "fbrl/clock.h"
#include "fbrl/glossary.h"
#include "fbrl/robot.h"
#include "fbrl/vm.h"
#include "support/vm_host.h"

#define OFFLINE_CODE (-300 + (int)FBRL_EOFFLINE)

typedef struct fixture {
    unsigned char *mem;
    fbrl_vm *vm;
    fbrl_glossary g;
    fbrl_robot r;
    char out[8192];
    size_t n;
} fixture;

static void h_write(void *user, const char *s, size_t n)
{
    fixture *f = user;
    if (f->n + n >= sizeof f->out)
        f->n = 0;
    memcpy(f->out + f->n, s, n);
    f->n += n;
    f->out[f->n] = 0;
}

static fixture *make(void)
{
    fixture *f = calloc(1, sizeof *f);
    assert_non_null(f);
    f->mem = malloc(2 << 20) /* glibc: 16-byte aligned */;
    assert_non_null(f->mem);
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = f->mem;
    cfg.mem_size = 2 << 20;
    cfg.host.user = f;
    cfg.host.write = h_write;
    cfg.host.now_us = vmh_now_us; /* the timers; no time_date (vmh_use_clock would add it) */
    cfg.host.sleep_ms = vmh_sleep_ms;
    assert_int_equal(fbrl_vm_create(&f->vm, &cfg), FBRL_OK);
    assert_int_equal(fbrl_glossary_install(f->vm, &f->g), FBRL_OK);
    assert_int_equal(fbrl_robot_install(f->vm, &f->r, NULL, &f->g), FBRL_OK);
    return f;
}

static int setup(void **state)
{
    *state = make();
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    free(f->mem);
    free(f);
    return 0;
}

static fbrl_status ev(fixture *f, const char *text) { return fbrl_vm_eval(f->vm, text, strlen(text)); }

/* Evaluate text that must throw code; return the message. */
static const char *throws(fixture *f, const char *text, int code)
{
    fbrl_status st = ev(f, text);
    const fbrl_vm_error *e = fbrl_vm_last_error(f->vm);
    if (st == FBRL_OK || e->throw_code != code)
        print_error("'%s': wanted throw %d, got status %d throw %d (%s)\n", text, code, st, e->throw_code,
                    e->message);
    assert_int_not_equal(st, FBRL_OK);
    assert_int_equal(e->throw_code, code);
    return e->message;
}

static fbrl_cell pop(fixture *f)
{
    fbrl_cell v = 0;
    assert_int_equal(fbrl_vm_pop(f->vm, &v), FBRL_OK);
    return v;
}

static double fpop(fixture *f)
{
    double v = 0;
    assert_int_equal(fbrl_vm_fpop(f->vm, &v), FBRL_OK);
    return v;
}

/* ---- installation ---- */

static void install_checks_arguments(void **state)
{
    fixture *f = *state;
    fbrl_robot r;
    assert_int_equal(fbrl_robot_install(NULL, &r, NULL, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_robot_install(f->vm, NULL, NULL, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_robot_set_link(NULL, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_robot_last_error(NULL), -1);
    assert_int_equal(fbrl_robot_last_error(&f->r), -1);
}

static void install_fails_cleanly_when_the_dictionary_is_full(void **state)
{
    (void)state;
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    fbrl_robot *r = malloc(sizeof *r);
    assert_non_null(r);
    /* the smallest dictionary the engine starts with, nearly filled: no room for the robot words */
    for (size_t dict = 4096;; dict += 4096) {
        assert_true(dict < (8u << 20));
        size_t size = fbrl_vm_size_for(&cfg, dict);
        unsigned char *mem = malloc(size);
        assert_non_null(mem);
        cfg.mem = mem;
        cfg.mem_size = size;
        fbrl_vm *vm;
        if (fbrl_vm_create(&vm, &cfg) == FBRL_OK) {
            assert_int_equal(fbrl_vm_eval(vm, "UNUSED 1024 - ALLOT", 19), FBRL_OK);
            assert_int_equal(fbrl_robot_install(vm, r, NULL, NULL), FBRL_ENOMEM);
            /* the VM still works */
            assert_int_equal(fbrl_vm_eval(vm, "1 2 +", 5), FBRL_OK);
            free(mem);
            break;
        }
        free(mem);
    }
    free(r);
}

static void every_word_has_help(void **state)
{
    fixture *f = *state;
    /* every word of the real tables (fbrl_robot_word), not a hand list */
    size_t k;
    for (k = 0; fbrl_robot_word(k); k++) {
        const char *name = fbrl_robot_word(k), *stack = NULL, *help = NULL;
        if (fbrl_vm_help(f->vm, name, &stack, &help) != FBRL_OK)
            print_error("no word %s\n", name);
        assert_int_equal(fbrl_vm_help(f->vm, name, &stack, &help), FBRL_OK);
        assert_true(stack[0] == '(' && strlen(help) > 10);
    }
    assert_true(k >= 110); /* I-4, I-5, I-6, I-8, devices and timers */
    /* the DOS-only words of I-4 are not bound (docs/glossary.md) */
    assert_int_equal(fbrl_vm_help(f->vm, "INSTALL-INTERRUPT", NULL, NULL), FBRL_ENOENT);
    assert_int_equal(fbrl_vm_help(f->vm, "COMM-INT-ENABLE", NULL, NULL), FBRL_ENOENT);
}

/* ---- offline ---- */

static void offline_words_throw_a_clear_error(void **state)
{
    fixture *f = *state;
    static const char *const lines[] = {
        "HOME",
        "READY",
        "50 SPEED",
        "SPEED 50",
        "1 30 JOINT",
        "JOG 1 0 0",
        "1E0 DEPART",
        "HALT",
        "FINISH",
        "CREATE-LOC P1 P1 MOV",
        "P1 MOV-STRT",
        "P1 2E0 APPROACH",
        "P1 ARM-HERE",
        "P1 ACTUAL",
        "ACTUAL CTL1",
        "P1 TOOL",
        "TRUE ARM",
        "3 LIMP",
        "NOLIMP",
        "2 LOCK",
        "0 UNLOCK",
        "1 2E0 GAIN",
        "50 1E0 GRIP",
        "CLOSE-GRIP",
        "W2",
        "W1",
        "ROBOT-STATUS",
        "SERIAL",
        "5 OUTPORT",
        "255 OUT2BYTE",
        "3 WAITPORT",
        "TYPEINT V1",
        "TYPEREAL V1",
        "WGRIP V1",
        "RAPL SPEED 5",
        "SET-RAPL-INT V1 3",
        "RAPL-HERE L1",
        "RAPL-RUN PROG",
        "RAPL-SET A B",
        "RAPL-SHIFTA A B",
        "RAPL-POINT L1 P1",
        "6 XHOME",
        "0 9600 ASC N 8 1 ASC X 1 CONFIG",
        "MANUAL",
        "5 FLASH",
        "CREATE-CAL K1 K1 GET-CAL-POINTS",
        "1 SETUPUART",
        "65 EMIT-COM",
        "GET-COM",
        "1 RESET-COMM",
        "16 SEND-COM 5 SEND-INT SEND-CR",
        "5 OUTPUT-DEVICE V1 V1 ON",
        "100 V1 PULSE",
        "3 INPUT-DEVICE S1 S1 INPUT?",
        ".COMM",
        "CONFIG 1 9600 E 7 2 X 1",
        "S1 TRUE 100 WAIT-INPUT",
        "V1 OFF",
        "ALIGNTOOL",
        "NOTEACH",
    };
    for (size_t k = 0; k < sizeof lines / sizeof lines[0]; k++) {
        const char *msg = throws(f, lines[k], OFFLINE_CODE);
        assert_non_null(strstr(msg, "no controller connected: start fbrlmon with --sim or --port"));
    }
}

/* The safe stop offline: nothing to halt, said so in the report, nothing thrown (a robot
 * word that failed just before does not change that). */
static void safe_stop_offline(void **state)
{
    fixture *f = *state;
    fbrl_robot_stop so;
    assert_int_equal(fbrl_robot_safe_stop(&f->r, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_robot_safe_stop(NULL, &so), FBRL_EINVAL);
    throws(f, "7 OUTPORT", OFFLINE_CODE);
    assert_int_equal(fbrl_robot_safe_stop(&f->r, &so), FBRL_EOFFLINE);
    assert_int_equal(so.result, FBRL_EOFFLINE);
    assert_int_equal(so.stop.halted, 0);
    assert_int_equal(so.stop.switched_off, 0);
    assert_int_equal(fbrl_robot_lost(&f->r), 0);
    assert_int_equal(fbrl_robot_set_relink(NULL, NULL, NULL), FBRL_EINVAL);
}

/* A motion from C (fbrl_robot_motion): the robot words' gate without the VM's throw: the
 * status and the message a word would have thrown; the VM is left as it was. */
static void motion_from_c_offline(void **state)
{
    fixture *f = *state;
    fbrl_robot_move m;
    char msg[160];
    memset(&m, 0, sizeof m);
    m.kind = FBRL_ROBOT_MOVE_JOG;
    m.word = "JOG";
    assert_int_equal(fbrl_robot_motion(&f->r, &m, msg, sizeof msg), FBRL_EOFFLINE);
    assert_string_equal(msg, "no controller connected: start fbrlmon with --sim or --port");
    assert_int_equal(fbrl_robot_motion(&f->r, &m, NULL, 0), FBRL_EOFFLINE);
    m.kind = FBRL_ROBOT_MOVE_OTHER;
    assert_int_equal(fbrl_robot_motion(&f->r, &m, msg, sizeof msg), FBRL_EINVAL);
    m.kind = FBRL_ROBOT_MOVE_MOTOR;
    m.v[0] = 1, m.v[1] = 0.5; /* pulses are whole */
    assert_int_equal(fbrl_robot_motion(&f->r, &m, msg, sizeof msg), FBRL_EINVAL);
    assert_int_equal(fbrl_robot_motion(NULL, &m, msg, sizeof msg), FBRL_EINVAL);
    assert_int_equal(fbrl_robot_motion(&f->r, NULL, msg, sizeof msg), FBRL_EINVAL);
    assert_int_equal(ev(f, "1 2 + ."), FBRL_OK); /* nothing thrown is left pending */
    assert_non_null(strstr(f->out, "3 "));
    /* a guard's refusal from inside a word is thrown as the word's error */
    assert_int_equal(fbrl_robot_fail(&f->r, FBRL_ROBOT_THROW_REFUSED, "X: would hit Y"), FBRL_ETHROW);
    assert_int_equal(fbrl_robot_fail(NULL, FBRL_ROBOT_THROW_REFUSED, "X"), FBRL_EINVAL);
}

/* For a host that drives the link itself: the stop without a context says offline; a
 * line's effect is what the robot words take it for (a motion, FINISH, HALT, the outputs
 * OUTPUT switches on; an unknown command may move the arm, an assignment never does);
 * a W5 line shows rest only when every velocity is zero and it came undamaged. */
static void host_side_helpers(void **state)
{
    (void)state;
    fbrl_robot_stop so;
    unsigned e = 99;
    uint32_t on = 99;
    assert_int_equal(fbrl_robot_safe_stop_link(NULL, 0, NULL, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_robot_safe_stop_link(NULL, 0x5u, "MOVE P1", &so), FBRL_EOFFLINE);
    assert_int_equal(so.result, FBRL_EOFFLINE);
    assert_int_equal(so.was_moving, 1);
    assert_string_equal(so.motion, "MOVE P1");
    assert_int_equal(so.stop.halted, 0);
    assert_int_equal(fbrl_robot_safe_stop_link(NULL, 0, NULL, &so), FBRL_EOFFLINE);
    assert_int_equal(so.was_moving, 0);

    assert_int_equal(fbrl_robot_line_effect(NULL, &e, &on), FBRL_EINVAL);
    assert_int_equal(fbrl_robot_line_effect("MOVE P1", NULL, &on), FBRL_EINVAL);
    static const struct {
        const char *line;
        unsigned effect;
        uint32_t on;
    } cases[] = {
        {"MOVE P1", FBRL_ROBOT_LINE_MOTION, 0},   {"  appro p1,2", FBRL_ROBOT_LINE_MOTION, 0},
        {"RUN PROG", FBRL_ROBOT_LINE_MOTION, 0},  {"FROB 3", FBRL_ROBOT_LINE_MOTION, 0},
        {"FINISH", FBRL_ROBOT_LINE_FINISH, 0},    {"HALT", FBRL_ROBOT_LINE_HALT, 0},
        {"V1=3", 0, 0},                           {"W2", 0, 0},
        {"OUTPUT 3", 0, 0x4u},                    {"OUTPUT 1,-2,16", 0, 0x8001u},
        {"OUTPUT -5", 0, 0},                      {"OUTPUT 17,99999999999999999999", 0, 0},
        {"OUTPUT +2", 0, 0x2u},                   {"STATUS", 0, 0},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        assert_int_equal(fbrl_robot_line_effect(cases[k].line, &e, &on), FBRL_OK);
        if (e != cases[k].effect || on != cases[k].on)
            print_error("'%s': effect %u outputs %#x\n", cases[k].line, e, (unsigned)on);
        assert_int_equal(e, cases[k].effect);
        assert_int_equal(on, cases[k].on);
    }
    assert_int_equal(fbrl_robot_line_effect("OUTPUT 4", &e, NULL), FBRL_OK);

    static const char rest[] = "+0000000000 +0000000000 +0000000000 +0000000000 +0000000000";
    static const char moving[] = "+0000000000 +0000000012 +0000000000 +0000000000 +0000000000";
    assert_true(fbrl_robot_still_line(rest, sizeof rest - 1, 0));
    assert_false(fbrl_robot_still_line(rest, sizeof rest - 1, 1)); /* damaged: no proof */
    assert_false(fbrl_robot_still_line(moving, sizeof moving - 1, 0));
    assert_false(fbrl_robot_still_line("COMMANDED VELOCITY:", 19, 0)); /* the title */
    assert_false(fbrl_robot_still_line(NULL, 0, 0));
}

static void print_loc_needs_the_port(void **state)
{
    fixture *f = *state;
    /* PRINT-LOC's port is the controller's line: none while offline */
    throws(f, "CREATE-LOC PP PP PRINT-LOC", OFFLINE_CODE);
    assert_non_null(strstr(fbrl_vm_last_error(f->vm)->message, "no communication port"));
}

static void arguments_are_checked_before_anything_is_sent(void **state)
{
    fixture *f = *state;
    /* range errors win over the offline error: they are the caller's mistake */
    throws(f, "0 SPEED", -24);
    throws(f, "101 SPEED", -24);
    throws(f, "6 1 JOINT", -24);
    throws(f, "7 5 MOTOR", -24);
    throws(f, "6 LIMP", -24);
    throws(f, "0 LOCK", -24);
    throws(f, "9 XCAL", -24);
    throws(f, "0 1E0 GRIP", -24);
    throws(f, "50 -1E0 GRIP", -24);
    throws(f, "1 -1E0 GAIN", -24);
    throws(f, "17 OUTPORT", -24);
    throws(f, "-17 WAITPORT", -24);
    throws(f, "65536 OUT2BYTE", -24);
    throws(f, "2 9600 ASC N 8 1 0 1 CONFIG", -24);
    throws(f, "0 1234 ASC N 8 1 0 1 CONFIG", -24);
    throws(f, "0 9600 ASC Q 8 1 0 1 CONFIG", -24);
    throws(f, "0 9600 ASC N 6 1 0 1 CONFIG", -24);
    throws(f, "0 9600 ASC N 8 1 ASC Q 1 CONFIG", -24);
    /* non-finite numbers */
    throws(f, "1E7 0E0 0E0 JOG", -302);
    throws(f, "-1E7 DEPART", -302);
    /* not a location */
    throws(f, "12345 MOV", -9);
    /* a location holding a NaN (the VM cannot compute one: it is poked in) */
    assert_int_equal(ev(f, "CREATE-LOC PN PN"), FBRL_OK);
    double *pn = (double *)pop(f);
    pn[2] = NAN;
    throws(f, "PN MOV", -303);
    throws(f, "PN SEND-LOC", -303);
    /* controller names */
    throws(f, "S\" TOOLONGNAME\" RAPL-HERE", -324);
    throws(f, "S\" \" RAPL-RUN", -324);
}

/* ---- I-6: parameters ---- */

static void getreal_getint_getstring(void **state)
{
    fixture *f = *state;
    assert_int_equal(ev(f, "GETREAL 2.5 GETREAL -1E2 GETREAL 3 GETREAL .25 GETREAL +1.5e1"), FBRL_OK);
    assert_true(fpop(f) == 15.0);
    assert_true(fpop(f) == 0.25);
    assert_true(fpop(f) == 3.0);
    assert_true(fpop(f) == -100.0);
    assert_true(fpop(f) == 2.5);
    assert_int_equal(ev(f, "GETREAL 0.1"), FBRL_OK);
    assert_true(fpop(f) == 0.1); /* correctly rounded */
    assert_int_equal(ev(f, "GETINT 42 GETINT -7 GETINT $1F GETINT #12"), FBRL_OK);
    assert_int_equal(pop(f), 12);
    assert_int_equal(pop(f), 31);
    assert_int_equal(pop(f), -7);
    assert_int_equal(pop(f), 42);
    assert_int_equal(ev(f, "GETSTRING hello"), FBRL_OK);
    assert_int_equal(pop(f), 5);
    assert_memory_equal((const char *)pop(f), "hello", 5);
    assert_int_equal(ev(f, "GETSTRING \"two words\" 7"), FBRL_OK);
    assert_int_equal(pop(f), 7);
    assert_int_equal(pop(f), 9);
    assert_memory_equal((const char *)pop(f), "two words", 9);
    /* constants and values stand for their numbers; variables do not */
    assert_int_equal(ev(f, "30 CONSTANT C30 2.5E0 FCONSTANT F25 8 VALUE V8 VARIABLE VV"), FBRL_OK);
    assert_int_equal(ev(f, "GETINT C30 GETINT V8 GETREAL F25 GETREAL C30"), FBRL_OK);
    assert_true(fpop(f) == 30.0);
    assert_true(fpop(f) == 2.5);
    assert_int_equal(pop(f), 8);
    assert_int_equal(pop(f), 30);
    throws(f, "GETINT F25", -24);
    throws(f, "GETREAL VV", -24);
    throws(f, "GETINT 1.5", -24);
    throws(f, "GETREAL 1.2.3", -24);
    throws(f, "GETREAL abc", -24);
    throws(f, "GETINT", -16);
    throws(f, "GETSTRING \"open", -39);
    /* inside a definition they read the input at run time */
    assert_int_equal(ev(f, ": TWICE GETINT 2 * ; TWICE 21"), FBRL_OK);
    assert_int_equal(pop(f), 42);
    assert_int_equal(fbrl_vm_depth(f->vm), 0);
    assert_int_equal(fbrl_vm_fdepth(f->vm), 0);
}

static void parameters_come_from_the_stacks_or_the_line(void **state)
{
    fixture *f = *state;
    /* both forms reach the same word (offline: the offline error, after parsing) */
    throws(f, "50 SPEED", OFFLINE_CODE);
    throws(f, "SPEED 50", OFFLINE_CODE);
    throws(f, "SPEED 500", -24); /* parsed from the line, then checked */
    throws(f, "SPEED", -16);     /* nothing anywhere */
    assert_non_null(strstr(fbrl_vm_last_error(f->vm)->message, "SPEED needs an integer"));
    /* the stacks are used when they can supply everything: the line stays untouched */
    assert_int_equal(ev(f, "5 SHIFT-RIGHT 7"), FBRL_OK);
    assert_int_equal(pop(f), 7);
    assert_int_equal(pop(f), 1);
    assert_int_equal(pop(f), 2);
    assert_int_equal(ev(f, "SHIFT-RIGHT 6"), FBRL_OK);
    assert_int_equal(pop(f), 0);
    assert_int_equal(pop(f), 3);
    /* mixed: GRIP ( torque -- | F: distance ) needs a float; with none on the float stack
     * both come from the line, so "50 GRIP 1.5" reads 1.5 as the torque and refuses it */
    throws(f, "50 GRIP 1.5", -24);
    assert_non_null(strstr(fbrl_vm_last_error(f->vm)->message, "'1.5' is not an integer"));
    throws(f, "GRIP 50 1.5", OFFLINE_CODE);
    throws(f, "50 1.5E0 GRIP", OFFLINE_CODE);
    /* a location parameter must name a data word; code is never run to get one */
    throws(f, "MOV HOME", -24);
    throws(f, "MOV 12", -24);
    assert_int_equal(ev(f, "VARIABLE RAN  0 RAN !  : MAKER CREATE 48 ALLOT DOES> 1 RAN +! ;  MAKER DL"),
                     FBRL_OK);
    throws(f, "MOV DL", -24);
    assert_int_equal(ev(f, "RAN @"), FBRL_OK);
    assert_int_equal(pop(f), 0); /* DL's DOES> code never ran */
    assert_int_equal(ev(f, "CREATE-LOC P2  1E0 2E0 3E0 0E0 -90E0 0E0 P2 DEFINE-LOC"), FBRL_OK);
    throws(f, "MOV P2", OFFLINE_CODE);
    throws(f, "P2 MOV", OFFLINE_CODE);
    /* ACTUAL: a host location, or a controller name when the word is no FBRL word */
    throws(f, "ACTUAL P2", OFFLINE_CODE);
    throws(f, "ACTUAL CTLX", OFFLINE_CODE);
    throws(f, "ACTUAL DUP", -24);
    assert_int_equal(fbrl_vm_depth(f->vm), 0);
}

/* ---- host-side words ---- */

static void send_words_build_a_line(void **state)
{
    fixture *f = *state;
    assert_int_equal(ev(f, "CREATE-LOC PS  1E0 -2.5E0 3E0 0E0 -90E0 45E0 PS DEFINE-LOC"), FBRL_OK);
    assert_int_equal(ev(f, "2 SEND-COM S\" PX\" SEND-TEXT SEND-COMMA 1.5E0 SEND-REAL SEND-STRT"), FBRL_OK);
    assert_string_equal(f->r.line, "APPRO PX,1.5,S");
    assert_int_equal(ev(f, "50 SEND-COM S\" PY\" SEND-TEXT SEND-COMMA PS SEND-LOC"), FBRL_OK);
    assert_string_equal(f->r.line, "POINT PY,1,-2.5,3,0,-90,45");
    assert_int_equal(ev(f, "6 SEND-COM 1 SEND-INT SEND-COMMA -30 SEND-INT"), FBRL_OK);
    assert_string_equal(f->r.line, "JOINT 1,-30");
    assert_int_equal(ev(f, "20 SEND-COM"), FBRL_OK);
    assert_string_equal(f->r.line, "HOME");
    throws(f, "999 SEND-COM", -24);
    throws(f, "SEND-CR", OFFLINE_CODE); /* the line is dropped either way */
    assert_int_equal(f->r.len, 0);
    throws(f, "SEND-CR", -24);
}

static void serial_settings_are_collected_offline(void **state)
{
    fixture *f = *state;
    assert_int_equal(ev(f, "2400 ASC E 1 7 COMMSET"), FBRL_OK);
    assert_int_equal(f->r.comm.baud, 2400);
    assert_int_equal(f->r.comm.parity, FBRL_PARITY_EVEN);
    assert_int_equal(f->r.comm.stop_bits, 1);
    assert_int_equal(f->r.comm.data_bits, 7);
    assert_int_equal(ev(f, "SETBAUDRATE 19200 SETPARITY O SETSTOPBITS 2 SETWORDLENGTH 8"), FBRL_OK);
    assert_int_equal(f->r.comm.baud, 19200);
    assert_int_equal(f->r.comm.parity, FBRL_PARITY_ODD);
    assert_int_equal(f->r.comm.stop_bits, 2);
    assert_int_equal(f->r.comm.data_bits, 8);
    assert_int_equal(ev(f, "SETPARITY 'e'"), FBRL_OK);
    assert_int_equal(f->r.comm.parity, FBRL_PARITY_EVEN);
    assert_int_equal(ev(f, "SETPARITY 78"), FBRL_OK); /* a character code */
    assert_int_equal(f->r.comm.parity, FBRL_PARITY_NONE);
    throws(f, "SETPARITY EVEN", -24);
    throws(f, "4 SETWORDLENGTH", -24);
    throws(f, "0 SETSTOPBITS", -24);
    throws(f, "ASC X SETPARITY", -24);
    throws(f, "10 SETBAUDRATE", -24);
    throws(f, "9600 ASC N 1 9 COMMSET", -24);
    assert_int_equal(f->r.comm.baud, 19200); /* a refused COMMSET changes nothing */
    throws(f, "2 SETUPUART", -24);
    throws(f, "3 9600 ASC N 1 8 COMM-SETUP", -24);
    assert_int_equal(ev(f, "ASC E : P ASC O ; P"), FBRL_OK);
    assert_int_equal(pop(f), 'O');
    assert_int_equal(pop(f), 'E');
}

static void devices_timers_and_fpc_on_off(void **state)
{
    fixture *f = *state;
    assert_int_equal(ev(f, "5 OUTPUT-DEVICE VALVE 3 INPUT-DEVICE SENSOR"), FBRL_OK);
    throws(f, "SENSOR ON", -24);
    throws(f, "VALVE INPUT?", -24);
    throws(f, "VALVE TRUE 100 WAIT-INPUT", -24);
    throws(f, "SENSOR TRUE -1 WAIT-INPUT", -24);
    throws(f, "0 OUTPUT-DEVICE D0", -24);
    throws(f, "17 INPUT-DEVICE D17", -24);
    throws(f, "0 VALVE PULSE-WIDTH", -24);
    throws(f, "VALVE 1.5E0 DISPENSE", -24);
    throws(f, "VALVE -2E0 DISPENSE", -24);
    throws(f, "VALVE 2E0 DISPENSE", OFFLINE_CODE);
    throws(f, "-5 VALVE PULSE", -24);
    throws(f, "12345 ON", -9);
    /* ON / OFF at a variable keep F-PC's meaning */
    assert_int_equal(ev(f, "VARIABLE FL FL ON FL @ FL OFF FL @"), FBRL_OK);
    assert_int_equal(pop(f), 0);
    assert_int_equal(pop(f), -1);
    /* devices take their table slots; too many are refused */
    char text[64];
    for (int k = 2; k < FBRL_ROBOT_MAX_DEVICES; k++) {
        snprintf(text, sizeof text, "1 OUTPUT-DEVICE DEV%d", k);
        assert_int_equal(ev(f, text), FBRL_OK);
    }
    throws(f, "1 OUTPUT-DEVICE ONE-TOO-MANY", -306);
    /* timers */
    throws(f, "ELAPSED", -24);
    assert_int_equal(ev(f, "START-TIMER 30 WAIT-UNTIL ELAPSED"), FBRL_OK);
    fbrl_cell ms = pop(f);
    assert_true(ms >= 30 && ms < 5000);
    throws(f, "-1 WAIT-UNTIL", -24);
}

static void base_offset_and_last_error(void **state)
{
    fixture *f = *state;
    assert_int_equal(ev(f, "1E0 2E0 3E0 90E0 BASE-OFFSET"), FBRL_OK);
    assert_true(f->r.base[0] == 1.0 && f->r.base[1] == 2.0 && f->r.base[2] == 3.0 && f->r.base[3] == 90.0);
    assert_int_equal(ev(f, "METRIC-ON 2.54E0 0E0 0E0 0E0 BASE-OFFSET METRIC-OFF"), FBRL_OK);
    assert_true(f->r.base[0] == 1.0);
    assert_int_equal(ev(f, "RAPL-ERROR"), FBRL_OK);
    assert_int_equal(pop(f), -1);
}

static void two_vms_have_their_own_robots(void **state)
{
    fixture *a = *state, *b = make();
    assert_int_equal(ev(a, "1E0 0E0 0E0 0E0 BASE-OFFSET 2 OUTPUT-DEVICE PUMP 16 SEND-COM"), FBRL_OK);
    assert_true(b->r.base[0] == 0.0);
    assert_string_equal(b->r.line, "");
    assert_int_equal(b->r.dev[0].addr, 0);
    throws(b, "PUMP ON", -13);
    assert_int_equal(ev(b, "4800 SETBAUDRATE"), FBRL_OK);
    assert_int_equal(a->r.comm.baud, 9600);
    free(b->mem);
    free(b);
}

/* Random lines of robot words and odd tokens: every one ends with FBRL_OK or a clean
 * exception, and the VM keeps working (run under ASan/UBSan in CI). */
static void random_lines_never_break_the_vm(void **state)
{
    fixture *f = *state;
    static const char *const tok[] = {
        "MOV",
        "APPROACH",
        "JOG",
        "SPEED",
        "GRIP",
        "CONFIG",
        "RAPL",
        "SEND-COM",
        "SEND-LOC",
        "SEND-CR",
        "SEND-TEXT",
        "GETREAL",
        "GETINT",
        "GETSTRING",
        "TYPEINT",
        "SET-RAPL-REAL",
        "RAPL-POINT",
        "ACTUAL",
        "ON",
        "OFF",
        "PULSE",
        "DISPENSE",
        "WAIT-INPUT",
        "SETPARITY",
        "COMMSET",
        "TYPE-COM",
        "ASC",
        "GET-CAL-POINTS",
        "BASE-OFFSET",
        "OUT2BYTE",
        "SHIFT-RIGHT",
        "ELAPSED",
        "P",
        "CAL",
        "VALVE",
        "SENSOR",
        "1",
        "-7",
        "0",
        "65535",
        "2.5",
        "1E300",
        "-1E-300",
        "$FF",
        "'E'",
        "\"",
        "\"a b\"",
        "E",
        "X",
        "HERE",
        "DUP",
        "S\" P\"",
        "12345678901234567890",
        "#",
        "-",
        ".",
        ",",
        "\\",
    };
    char line[256];
    unsigned seed = 12345;
    assert_int_equal(ev(f, "CREATE-LOC P CREATE-CAL CAL 5 OUTPUT-DEVICE VALVE 3 INPUT-DEVICE SENSOR"),
                     FBRL_OK);
    for (int k = 0; k < 3000; k++) {
        size_t n = 0;
        int words = 1 + (int)((seed = seed * 1103515245u + 12345u) >> 16) % 6;
        for (int w = 0; w < words; w++) {
            seed = seed * 1103515245u + 12345u;
            const char *t = tok[(seed >> 16) % (sizeof tok / sizeof tok[0])];
            if (n + strlen(t) + 2 >= sizeof line)
                break;
            n += (size_t)snprintf(line + n, sizeof line - n, "%s ", t);
        }
        ev(f, line); /* any result but a crash */
        assert_int_equal(ev(f, "1 2 +"), FBRL_OK);
        assert_int_equal(pop(f), 3);
        while (fbrl_vm_depth(f->vm))
            pop(f);
        while (fbrl_vm_fdepth(f->vm))
            fpop(f);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(install_checks_arguments, setup, teardown),
        cmocka_unit_test(install_fails_cleanly_when_the_dictionary_is_full),
        cmocka_unit_test_setup_teardown(every_word_has_help, setup, teardown),
        cmocka_unit_test_setup_teardown(offline_words_throw_a_clear_error, setup, teardown),
        cmocka_unit_test_setup_teardown(print_loc_needs_the_port, setup, teardown),
        cmocka_unit_test_setup_teardown(motion_from_c_offline, setup, teardown),
        cmocka_unit_test_setup_teardown(safe_stop_offline, setup, teardown),
        cmocka_unit_test_setup_teardown(host_side_helpers, setup, teardown),
        cmocka_unit_test_setup_teardown(arguments_are_checked_before_anything_is_sent, setup, teardown),
        cmocka_unit_test_setup_teardown(getreal_getint_getstring, setup, teardown),
        cmocka_unit_test_setup_teardown(parameters_come_from_the_stacks_or_the_line, setup, teardown),
        cmocka_unit_test_setup_teardown(send_words_build_a_line, setup, teardown),
        cmocka_unit_test_setup_teardown(serial_settings_are_collected_offline, setup, teardown),
        cmocka_unit_test_setup_teardown(devices_timers_and_fpc_on_off, setup, teardown),
        cmocka_unit_test_setup_teardown(base_offset_and_last_error, setup, teardown),
        cmocka_unit_test_setup_teardown(two_vms_have_their_own_robots, setup, teardown),
        cmocka_unit_test_setup_teardown(random_lines_never_break_the_vm, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
