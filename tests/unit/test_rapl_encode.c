/* SPDX-License-Identifier: MIT */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "fbrl/rapl_encode.h"

#define A(...)  ((const fbrl_rapl_arg[]){__VA_ARGS__})
#define NA(...) (sizeof((const fbrl_rapl_arg[]){__VA_ARGS__}) / sizeof(fbrl_rapl_arg))
/* constant-expression argument builders, usable in static tables */
#define I(v)                           \
    {                                  \
        FBRL_RAPL_ARG_INT, (v), 0.0, 0 \
    }
#define R(v)                          \
    {                                 \
        FBRL_RAPL_ARG_REAL, 0, (v), 0 \
    }
#define S(v)                           \
    {                                  \
        FBRL_RAPL_ARG_STR, 0, 0.0, (v) \
    }

/* One expected encoding per command, in keyword and token form. */
typedef struct golden {
    fbrl_rapl_cmd cmd;
    fbrl_rapl_arg args[7];
    size_t nargs;
    int straight;
    const char *keyword, *token;
} golden;

#define G(cmd, st, kw, tok, ...)                         \
    {                                                    \
        cmd, {__VA_ARGS__}, NA(__VA_ARGS__), st, kw, tok \
    }
#define G0(cmd, kw, tok)                                     \
    {                                                        \
        cmd, {{FBRL_RAPL_ARG_INT, 0, 0.0, 0}}, 0, 0, kw, tok \
    }

static golden goldens[] = {
    G(FBRL_RAPL_ACTUAL, 0, "ACTUAL P1", "/152 P1", S("p1")),
    G(FBRL_RAPL_ACTUAL, 0, "ACTUAL #PP", "/152 #PP", S("#pp")),
    G0(FBRL_RAPL_ALIGN, "ALIGN", "/001"),
    G(FBRL_RAPL_APPRO, 0, "APPRO P1,2.5", "/002 P1,2.5", S("P1"), R(2.5)),
    G(FBRL_RAPL_APPRO, 1, "APPRO P1,-1,S", "/002 P1,-1,S", S("P1"), R(-1.0)),
    G(FBRL_RAPL_ARM, 0, "ARM OFF", "/142 OFF", S("off")),
    G0(FBRL_RAPL_CLOSE, "CLOSE", "/038"),
    G(FBRL_RAPL_CLOSE, 0, "CLOSE 30", "/038 30", I(30)),
    G(FBRL_RAPL_CONFIG, 0, "CONFIG 0,9600,N,8,1,X,1", "/110 0,9600,N,8,1,X,1", I(0), I(9600), S("n"), I(8),
      I(1), S("X"), I(1)),
    G(FBRL_RAPL_DEPART, 0, "DEPART 1.25", "/004 1.25", R(1.25)),
    G(FBRL_RAPL_DEPART, 1, "DEPART 1.25,S", "/004 1.25,S", R(1.25)),
    G0(FBRL_RAPL_FINISH, "FINISH", "/010"),
    G(FBRL_RAPL_FLASH, 0, "FLASH 5", "/084 5", I(5)),
    G(FBRL_RAPL_GAIN, 0, "GAIN 0,1.5", "/150 0,1.5", I(0), R(1.5)),
    G(FBRL_RAPL_GAIN, 0, "GAIN 2", "/150 2", I(2)),
    G(FBRL_RAPL_GRIP, 0, "GRIP 0.75", "/039 0.75", R(0.75)),
    G(FBRL_RAPL_GRIP, 0, "GRIP 1,40", "/039 1,40", R(1.0), I(40)),
    G0(FBRL_RAPL_HALT, "HALT", "/154"),
    G(FBRL_RAPL_HERE, 0, "HERE HOLD", "/024 HOLD", S("Hold")),
    G0(FBRL_RAPL_HOME, "HOME", "/020"),
    G(FBRL_RAPL_JOG, 0, "JOG 1,-2,0.0001", "/005 1,-2,0.0001", R(1), R(-2), R(0.0001)),
    G(FBRL_RAPL_JOINT, 0, "JOINT 3,-45", "/006 3,-45", I(3), R(-45.0)),
    G0(FBRL_RAPL_LIMP, "LIMP", "/007"),
    G(FBRL_RAPL_LIMP, 0, "LIMP 2,3", "/007 2,3", I(2), I(3)),
    G(FBRL_RAPL_LOCK, 0, "LOCK 1,4", "/009 1,4", I(1), I(4)),
    G(FBRL_RAPL_MA, 1, "MA 0,0,0,0,0,S", "/132 0,0,0,0,0,S", R(0), R(0), R(0), R(0), R(0)),
    G(FBRL_RAPL_MA, 0, "MA 0,1.5708,-1.5708,0,0.1", "/132 0,1.5708,-1.5708,0,0.1", R(0), R(1.5707963),
      R(-1.5707963), R(0), R(0.1)),
    G0(FBRL_RAPL_MANUAL, "MANUAL", "/045"),
    G(FBRL_RAPL_MANUAL, 0, "MANUAL CYL", "/045 CYL", S("cyl")),
    G(FBRL_RAPL_MI, 1, "MI 0.01,0,0,0,0,S", "/131 0.01,0,0,0,0,S", R(0.01), R(0), R(0), R(0), R(0)),
    G(FBRL_RAPL_MOTOR, 0, "MOTOR 1,-200", "/011 1,-200", I(1), I(-200)),
    G(FBRL_RAPL_MOVE, 0, "MOVE P2", "MOVE P2", S("P2")),
    G(FBRL_RAPL_MOVE, 1, "MOVE #P2,S", "MOVE #P2,S", S("#P2")),
    G0(FBRL_RAPL_NOFLASH, "NOFLASH", "NOFLASH"),
    G0(FBRL_RAPL_NOHELP, "NOHELP", "NOHELP"),
    G0(FBRL_RAPL_NOMANUAL, "NOMANUAL", "NOMANUAL"),
    G0(FBRL_RAPL_NOTEACH, "NOTEACH", "NOTEACH"),
    G0(FBRL_RAPL_NOLIMP, "NOLIMP", "NOLIMP"),
    G0(FBRL_RAPL_OPEN, "OPEN", "/040"),
    G(FBRL_RAPL_OPEN, 0, "OPEN 50", "/040 50", I(50)),
    G(FBRL_RAPL_OUTPUT, 0, "OUTPUT -3,5", "/089 -3,5", I(-3), I(5)),
    G(FBRL_RAPL_POINT, 0, "POINT A,10,0,5,0,-90,0", "/050 A,10,0,5,0,-90,0", S("A"), R(10), R(0), R(5), R(0),
      R(-90), R(0)),
    G(FBRL_RAPL_POINT, 0, "POINT #B,100,-200,300,0,22", "/050 #B,100,-200,300,0,22", S("#b"), I(100), I(-200),
      I(300), I(0), I(22)),
    G0(FBRL_RAPL_READY, "READY", "/015"),
    G(FBRL_RAPL_RUN, 0, "RUN CAL", "/109 CAL", S("CAL")),
    G(FBRL_RAPL_RUN, 0, "RUN CAL,3", "/109 CAL,3", S("CAL"), I(3)),
    G0(FBRL_RAPL_SERIAL, "SERIAL", "/111"),
    G(FBRL_RAPL_SET, 0, "SET A=B", "/051 A=B", S("A"), S("B")),
    G(FBRL_RAPL_SHIFTA, 0, "SHIFTA A,D", "/053 A,D", S("A"), S("D")),
    G(FBRL_RAPL_SPEED, 0, "SPEED 50", "/016 50", I(50)),
    G0(FBRL_RAPL_STATUS, "STATUS", "/025"),
    G(FBRL_RAPL_TEACH, 0, "TEACH T1", "/044 T1", S("T1")),
    G(FBRL_RAPL_TOOL, 0, "TOOL TL", "/054 TL", S("TL")),
    G0(FBRL_RAPL_TOOL, "TOOL", "/054"),
    G(FBRL_RAPL_TYPEI, 0, "TYPEI COUNT", "/059 COUNT", S("count")),
    G(FBRL_RAPL_TYPEV, 0, "TYPEV X", "/060 X", S("X")),
    G(FBRL_RAPL_UNLOCK, 0, "UNLOCK 1", "/017 1", I(1)),
    G0(FBRL_RAPL_UNLOCK, "UNLOCK", "/017"),
    G0(FBRL_RAPL_W0, "W0", "/027"),
    G0(FBRL_RAPL_W1, "W1", "/029"),
    G0(FBRL_RAPL_W2, "W2", "/031"),
    G0(FBRL_RAPL_W3, "W3", "/033"),
    G0(FBRL_RAPL_W4, "W4", "/035"),
    G0(FBRL_RAPL_W5, "W5", "/037"),
    G(FBRL_RAPL_WAIT, 0, "WAIT -7", "/094 -7", I(-7)),
    G(FBRL_RAPL_WAIT, 0, "WAIT 1,-2", "/094 1,-2", I(1), I(-2)),
    G0(FBRL_RAPL_WE1, "WE1", "/028"),
    G0(FBRL_RAPL_WE3, "WE3", "/032"),
    G0(FBRL_RAPL_WE5, "WE5", "/036"),
    G(FBRL_RAPL_XCAL, 0, "XCAL 6", "/157 6", I(6)),
    G(FBRL_RAPL_XHOME, 0, "XHOME 6", "/158 6", I(6)),
    G(FBRL_RAPL_XZERO, 0, "XZERO 6", "/159 6", I(6)),
    G(FBRL_RAPL_ASSIGN, 0, "V1=2.5", "V1=2.5", S("v1"), R(2.5)),
    G(FBRL_RAPL_ASSIGN, 0, "N=7", "N=7", S("N"), I(7)),
    G(FBRL_RAPL_DLOCN, 0, "DLOCN P1", "/048 P1", S("p1")),
    G(FBRL_RAPL_DVAR, 0, "DVAR V1", "/067 V1", S("V1")),
    G0(FBRL_RAPL_HELP, "HELP", "/095"),
    G0(FBRL_RAPL_LISTL, "LISTL", "/049"),
    G(FBRL_RAPL_LISTL, 0, "LISTL P1", "/049 P1", S("P1")),
    G0(FBRL_RAPL_LISTV, "LISTV", "/069"),
    G(FBRL_RAPL_SHIFT, 0, "SHIFT P1,1,0,-2.25", "/052 P1,1,0,-2.25", S("P1"), R(1), R(0), R(-2.25)),
    G(FBRL_RAPL_TYPE, 0, "TYPE HELLO, WORLD", "/058 HELLO, WORLD", S("Hello, world")),
    G(FBRL_RAPL_ENABLE, 0, "ENABLE ARM", "/176 ARM", S("arm")),
    G(FBRL_RAPL_DISABLE, 0, "DISABLE ARM", "/177 ARM", S("ARM")),
    G0(FBRL_RAPL_ONPOWER, "ONPOWER", "ONPOWER"),
    G0(FBRL_RAPL_METRIC, "METRIC", "METRIC"),
    G0(FBRL_RAPL_NOMETRIC, "NOMETRIC", "NOMETRIC"),
};

static void every_command_encodes_in_both_forms(void **state)
{
    (void)state;
    int seen[FBRL_RAPL_NCMDS] = {0};
    for (size_t g = 0; g < sizeof goldens / sizeof goldens[0]; g++) {
        const golden *e = &goldens[g];
        char buf[FBRL_RAPL_LINE_MAX];
        size_t len = 99;
        assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, FBRL_RAPL_KEYWORD, e->cmd, e->args, e->nargs,
                                          e->straight),
                         FBRL_OK);
        assert_string_equal(buf, e->keyword);
        assert_int_equal(len, strlen(e->keyword));
        assert_int_equal(
            fbrl_rapl_encode(buf, sizeof buf, &len, FBRL_RAPL_TOKEN, e->cmd, e->args, e->nargs, e->straight),
            FBRL_OK);
        assert_string_equal(buf, e->token);
        assert_int_equal(len, strlen(e->token));
        /* exactly one byte too few for the line and its NUL gives ENOSPC and an empty buffer */
        assert_int_equal(fbrl_rapl_encode(buf, strlen(e->keyword), &len, FBRL_RAPL_KEYWORD, e->cmd, e->args,
                                          e->nargs, e->straight),
                         FBRL_ENOSPC);
        assert_string_equal(buf, "");
        seen[e->cmd] = 1;
    }
    for (int c = 0; c < FBRL_RAPL_NCMDS; c++)
        assert_true(seen[c]);
}

/* fbrl_rapl_line_cmd: the first word of a line, by keyword or token; an assignment first. */
static void lines_name_their_command(void **state)
{
    (void)state;
    fbrl_rapl_cmd c = FBRL_RAPL_NCMDS;
    const char *args = NULL;
    assert_int_equal(fbrl_rapl_line_cmd("  output 3,-4", &c, &args), FBRL_OK);
    assert_int_equal(c, FBRL_RAPL_OUTPUT);
    assert_string_equal(args, "3,-4");
    assert_int_equal(fbrl_rapl_line_cmd("/089 3", &c, &args), FBRL_OK);
    assert_int_equal(c, FBRL_RAPL_OUTPUT);
    assert_string_equal(args, "3");
    assert_int_equal(fbrl_rapl_line_cmd("MOVE,P1", &c, &args), FBRL_OK); /* a ',' ends the word */
    assert_int_equal(c, FBRL_RAPL_MOVE);
    assert_int_equal(fbrl_rapl_line_cmd("GRIP = 2", &c, &args), FBRL_OK); /* a variable named GRIP */
    assert_int_equal(c, FBRL_RAPL_ASSIGN);
    assert_string_equal(args, "= 2");
    assert_int_equal(fbrl_rapl_line_cmd("V1=V1+1", &c, &args), FBRL_OK);
    assert_int_equal(c, FBRL_RAPL_ASSIGN);
    assert_int_equal(fbrl_rapl_line_cmd("STATUS", &c, NULL), FBRL_OK);
    assert_int_equal(c, FBRL_RAPL_STATUS);
    c = FBRL_RAPL_NCMDS;
    assert_int_equal(fbrl_rapl_line_cmd("=5", &c, NULL), FBRL_ENOENT); /* no name: no assignment */
    assert_int_equal(fbrl_rapl_line_cmd("STATUSX", &c, NULL), FBRL_ENOENT);
    assert_int_equal(fbrl_rapl_line_cmd("/0089", &c, NULL), FBRL_OK); /* the controller reads a number */
    assert_int_equal(fbrl_rapl_line_cmd("/12345678901", &c, NULL), FBRL_ENOENT);
    assert_int_equal(fbrl_rapl_line_cmd("/", &c, NULL), FBRL_ENOENT);
    assert_int_equal(fbrl_rapl_line_cmd("/08x", &c, NULL), FBRL_ENOENT);
    assert_int_equal(fbrl_rapl_line_cmd("", &c, NULL), FBRL_ENOENT);
    assert_int_equal(fbrl_rapl_line_cmd(NULL, &c, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_line_cmd("HOME", NULL, NULL), FBRL_EINVAL);
    /* safe to type twice: the table, or an assignment that does not read its target */
    assert_true(fbrl_rapl_line_safe("MOVE P1"));
    assert_false(fbrl_rapl_line_safe("JOG 0,0,1"));
    assert_false(fbrl_rapl_line_safe("HERE H1"));
    assert_true(fbrl_rapl_line_safe("V1 = 2.5"));
    assert_false(fbrl_rapl_line_safe("V1=V1+1"));
    assert_false(fbrl_rapl_line_safe("v1=2*V1"));
    assert_true(fbrl_rapl_line_safe("V1=V10+1"));
    assert_false(fbrl_rapl_line_safe("FROB 1"));
    assert_false(fbrl_rapl_line_safe(NULL));
    for (int k = 0; k < FBRL_RAPL_NCMDS; k++) { /* every keyword and token names its command */
        const fbrl_rapl_cmdinfo *ci = fbrl_rapl_cmd_info((fbrl_rapl_cmd)k);
        char text[16];
        if (ci->keyword[0]) {
            snprintf(text, sizeof text, "%s 1", ci->keyword);
            assert_int_equal(fbrl_rapl_line_cmd(text, &c, NULL), FBRL_OK);
            assert_int_equal(c, k);
        }
        if (ci->token) {
            snprintf(text, sizeof text, "/%03u", (unsigned)ci->token);
            assert_int_equal(fbrl_rapl_line_cmd(text, &c, NULL), FBRL_OK);
            assert_int_equal(c, k);
        }
    }
}

static void table_is_complete_and_lookups_work(void **state)
{
    (void)state;
    for (int c = 0; c < FBRL_RAPL_NCMDS; c++) {
        const fbrl_rapl_cmdinfo *ci = fbrl_rapl_cmd_info((fbrl_rapl_cmd)c);
        assert_non_null(ci);
        assert_non_null(ci->keyword);
        assert_non_null(ci->sig);
        assert_true(ci->token < 1000);
        if (ci->keyword[0]) {
            fbrl_rapl_cmd found;
            assert_int_equal(fbrl_rapl_cmd_find(ci->keyword, &found), FBRL_OK);
            assert_int_equal(found, c);
        }
        /* tokens are unique */
        for (int d = c + 1; d < FBRL_RAPL_NCMDS && ci->token; d++)
            assert_int_not_equal(ci->token, fbrl_rapl_cmd_info((fbrl_rapl_cmd)d)->token);
    }
    fbrl_rapl_cmd c;
    assert_int_equal(fbrl_rapl_cmd_find("appro", &c), FBRL_OK);
    assert_int_equal(c, FBRL_RAPL_APPRO);
    assert_int_equal(fbrl_rapl_cmd_find("APPROX", &c), FBRL_ENOENT);
    assert_int_equal(fbrl_rapl_cmd_find("APP", &c), FBRL_ENOENT);
    assert_int_equal(fbrl_rapl_cmd_find("", &c), FBRL_ENOENT);
    assert_int_equal(fbrl_rapl_cmd_find(NULL, &c), FBRL_EINVAL);
    assert_null(fbrl_rapl_cmd_info(FBRL_RAPL_NCMDS));
    assert_null(fbrl_rapl_cmd_info((fbrl_rapl_cmd)-1));
    assert_true(fbrl_rapl_cmd_info(FBRL_RAPL_MOVE)->flags & FBRL_RAPL_F_MOTION);
    assert_true(fbrl_rapl_cmd_info(FBRL_RAPL_W1)->flags & FBRL_RAPL_F_STREAM);
    assert_false(fbrl_rapl_cmd_info(FBRL_RAPL_W2)->flags & FBRL_RAPL_F_STREAM);
}

/* One place for each fact: the table's flags agree with each other and with the reply
 * kinds, and the enum values never move (bindings store them). */
static void table_facts_agree(void **state)
{
    (void)state;
    int waits = 0, unsafe = 0;
    for (int c = 0; c < FBRL_RAPL_NCMDS; c++) {
        const fbrl_rapl_cmdinfo *ci = fbrl_rapl_cmd_info((fbrl_rapl_cmd)c);
        /* a motion may wait for the one before it; a straight line is a motion */
        if (ci->flags & FBRL_RAPL_F_MOTION)
            assert_true(ci->flags & FBRL_RAPL_F_WAITS);
        if (ci->flags & FBRL_RAPL_F_STRAIGHT)
            assert_true(ci->flags & FBRL_RAPL_F_MOTION);
        /* streams, and only streams, have the stream reply */
        assert_int_equal(!!(ci->flags & FBRL_RAPL_F_STREAM), ci->reply == FBRL_RAPL_REPLY_STREAM);
        /* every query (a reply with values) is read-only, so safe to repeat */
        if (ci->reply != FBRL_RAPL_REPLY_NONE && ci->reply != FBRL_RAPL_REPLY_LINES)
            assert_true(ci->flags & FBRL_RAPL_F_SAFE);
        waits += !!(ci->flags & FBRL_RAPL_F_WAITS);
        unsafe += !(ci->flags & FBRL_RAPL_F_SAFE);
    }
    /* the commands a second run changes (issues 9 and 28): relative ones, counters, deletions,
     * program runs, those that store where the arm is, WAIT */
    static const fbrl_rapl_cmd never_twice[] = {
        FBRL_RAPL_JOG,    FBRL_RAPL_DEPART, FBRL_RAPL_APPRO, FBRL_RAPL_MI,
        FBRL_RAPL_JOINT,  FBRL_RAPL_MOTOR,  FBRL_RAPL_RUN,   FBRL_RAPL_SHIFTA,
        FBRL_RAPL_SHIFT,  FBRL_RAPL_DLOCN,  FBRL_RAPL_DVAR,  FBRL_RAPL_HERE,
        FBRL_RAPL_ACTUAL, FBRL_RAPL_XCAL,   FBRL_RAPL_XZERO, FBRL_RAPL_WAIT};
    for (size_t k = 0; k < sizeof never_twice / sizeof never_twice[0]; k++)
        assert_false(fbrl_rapl_cmd_info(never_twice[k])->flags & FBRL_RAPL_F_SAFE);
    assert_int_equal(unsafe, (int)(sizeof never_twice / sizeof never_twice[0]));
    assert_true(fbrl_rapl_cmd_info(FBRL_RAPL_FINISH)->flags & FBRL_RAPL_F_WAITS);
    assert_true(fbrl_rapl_cmd_info(FBRL_RAPL_WAIT)->flags & FBRL_RAPL_F_WAITS);
    assert_true(fbrl_rapl_cmd_info(FBRL_RAPL_RUN)->flags & FBRL_RAPL_F_WAITS);
    assert_true(waits > 3);
    assert_int_equal(fbrl_rapl_cmd_info(FBRL_RAPL_W2)->reply, FBRL_RAPL_REPLY_POS);
    assert_int_equal(fbrl_rapl_cmd_info(FBRL_RAPL_STATUS)->reply, FBRL_RAPL_REPLY_STATUS);
    assert_int_equal(fbrl_rapl_cmd_info(FBRL_RAPL_TYPEI)->reply, FBRL_RAPL_REPLY_INT);
    assert_int_equal(fbrl_rapl_cmd_info(FBRL_RAPL_TYPEV)->reply, FBRL_RAPL_REPLY_REAL);
    /* stable values: the first, one in the middle, the last of each release */
    assert_int_equal(FBRL_RAPL_ACTUAL, 0);
    assert_int_equal(FBRL_RAPL_MOVE, 22);
    assert_int_equal(FBRL_RAPL_ASSIGN, 56);
    assert_int_equal(FBRL_RAPL_TYPE, 63);
    assert_int_equal(FBRL_RAPL_REPLY_STREAM, 6);
}

static void reals_are_short_and_have_no_exponent(void **state)
{
    (void)state;
    static const struct {
        double v;
        const char *txt;
    } cases[] = {
        {0.0, "0"},
        {-0.0, "0"},
        {-0.00004, "0"},
        {0.00005, "0.0001"},
        {-0.00005, "-0.0001"},
        {1e-9, "0"},
        {123.45678, "123.4568"},
        {-7.5, "-7.5"},
        {999999.9999, "999999.9999"},
        {-999999.9999, "-999999.9999"},
        {1e5, "100000"},
        {0.1, "0.1"},
        {2.675, "2.675"},
        {-0.0125, "-0.0125"},
        {10.0, "10"},
        {0.99996, "1"},
        {-90.0, "-90"},
        {1.20004, "1.2"},
        {0.0001, "0.0001"},
        {0.001, "0.001"},
    };
    char buf[32];
    size_t len;
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        assert_int_equal(fbrl_rapl_format_real(buf, sizeof buf, &len, cases[k].v), FBRL_OK);
        assert_string_equal(buf, cases[k].txt);
        assert_int_equal(len, strlen(cases[k].txt));
        assert_null(strchr(buf, 'e'));
    }
    assert_int_equal(fbrl_rapl_format_real(buf, sizeof buf, &len, NAN), FBRL_ENONFINITE);
    assert_int_equal(fbrl_rapl_format_real(buf, sizeof buf, &len, INFINITY), FBRL_ENONFINITE);
    assert_int_equal(fbrl_rapl_format_real(buf, sizeof buf, &len, -INFINITY), FBRL_ENONFINITE);
    assert_int_equal(fbrl_rapl_format_real(buf, sizeof buf, &len, 1e6), FBRL_ERANGE);
    assert_int_equal(fbrl_rapl_format_real(buf, sizeof buf, &len, -1e300), FBRL_ERANGE);
    assert_int_equal(fbrl_rapl_format_real(buf, 3, &len, 1.5), FBRL_ENOSPC);
    assert_int_equal(fbrl_rapl_format_real(buf, 4, &len, 1.5), FBRL_OK);
    assert_int_equal(fbrl_rapl_format_real(NULL, 7, &len, 1.5), FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_format_real(buf, 0, &len, 1.5), FBRL_EINVAL);
}

/* xorshift64*: a fixed sequence, so a failure repeats. */
static uint64_t rng_next(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return *s * 2685821657736338717ull;
}

/* The controller reads a number as the emulator does (sim_cmd.c e_primary): the
 * digits with strtod. For random values over every magnitude, the short text gives the
 * very value the four-decimal text ("%.4f", the old encoding) gives, and it is that
 * text with its trailing zeros (and a bare dot) cut off. */
static void short_reals_read_back_as_four_decimals(void **state)
{
    (void)state;
    uint64_t seed = 0x9e3779b97f4a7c15ull;
    size_t saved = 0, total = 0;
    for (int k = 0; k < 200000; k++) {
        uint64_t r = rng_next(&seed);
        double mag = pow(10.0, (double)(r % 11u) - 5.0); /* 1e-5 .. 1e5 */
        double v = (double)(rng_next(&seed) >> 11) / 9007199254740992.0 * 10.0 * mag;
        switch (r >> 60) {
        case 0: v = floor(v); break;                     /* whole numbers */
        case 1: v = floor(v * 100.0) / 100.0; break;     /* two decimals */
        case 2: v = floor(v * 10000.0) / 10000.0; break; /* exactly four */
        default: break;
        }
        if ((r >> 59) & 1u)
            v = -v;
        if (v > FBRL_RAPL_REAL_MAX || v < -FBRL_RAPL_REAL_MAX)
            continue;
        char shortest[32], four[48];
        size_t len;
        assert_int_equal(fbrl_rapl_format_real(shortest, sizeof shortest, &len, v), FBRL_OK);
        snprintf(four, sizeof four, "%.4f", v);
        if (strcmp(four, "-0.0000") == 0)
            memmove(four, four + 1, strlen(four));
        if (strtod(shortest, NULL) != strtod(four, NULL)) {
            print_error("%.17g: '%s' reads %.17g, '%s' reads %.17g\n", v, shortest, strtod(shortest, NULL),
                        four, strtod(four, NULL));
            fail();
        }
        /* shortest = four without trailing zeros */
        size_t n4 = strlen(four);
        while (four[n4 - 1] == '0')
            n4--;
        if (four[n4 - 1] == '.')
            n4--;
        assert_int_equal(len, n4);
        assert_memory_equal(shortest, four, n4);
        saved += strlen(four) - len;
        total += strlen(four);
    }
    assert_true(saved > 0 && total > 0);
}

static void names_are_validated(void **state)
{
    (void)state;
    assert_int_equal(fbrl_rapl_name_check("A", 0), FBRL_OK);
    assert_int_equal(fbrl_rapl_name_check("abcdefgh", 0), FBRL_OK);
    assert_int_equal(fbrl_rapl_name_check("P12", 0), FBRL_OK);
    assert_int_equal(fbrl_rapl_name_check("#P12", 1), FBRL_OK);
    assert_int_equal(fbrl_rapl_name_check("#ABCDEFGH", 1), FBRL_OK);
    assert_int_equal(fbrl_rapl_name_check("#P12", 0), FBRL_ENAME);
    assert_int_equal(fbrl_rapl_name_check("abcdefghi", 0), FBRL_ENAME);
    assert_int_equal(fbrl_rapl_name_check("", 0), FBRL_ENAME);
    assert_int_equal(fbrl_rapl_name_check("#", 1), FBRL_ENAME);
    assert_int_equal(fbrl_rapl_name_check("1A", 0), FBRL_ENAME);
    assert_int_equal(fbrl_rapl_name_check("A B", 0), FBRL_ENAME);
    assert_int_equal(fbrl_rapl_name_check("A,B", 0), FBRL_ENAME);
    assert_int_equal(fbrl_rapl_name_check("A\r", 0), FBRL_ENAME);
    assert_int_equal(fbrl_rapl_name_check("##A", 1), FBRL_ENAME);
    assert_int_equal(fbrl_rapl_name_check("A_B", 0), FBRL_OK);
    assert_int_equal(fbrl_rapl_name_check("_AB", 0), FBRL_ENAME);
    assert_int_equal(fbrl_rapl_name_check(NULL, 0), FBRL_EINVAL);

    char buf[FBRL_RAPL_LINE_MAX];
    size_t len;
    assert_int_equal(
        fbrl_rapl_encode(buf, sizeof buf, &len, FBRL_RAPL_KEYWORD, FBRL_RAPL_MOVE, A(S("TOOLONGNM")), 1, 0),
        FBRL_ENAME);
    assert_int_equal(
        fbrl_rapl_encode(buf, sizeof buf, &len, FBRL_RAPL_KEYWORD, FBRL_RAPL_TYPEI, A(S("#V")), 1, 0),
        FBRL_ENAME); /* variables have no '#' */
    assert_int_equal(
        fbrl_rapl_encode(buf, sizeof buf, &len, FBRL_RAPL_KEYWORD, FBRL_RAPL_HERE, A(S("P;1")), 1, 0),
        FBRL_ENAME);
    assert_int_equal(
        fbrl_rapl_encode(buf, sizeof buf, &len, FBRL_RAPL_KEYWORD, FBRL_RAPL_SET, A(S("A"), S("B C")), 2, 0),
        FBRL_ENAME);
}

static void arguments_are_checked(void **state)
{
    (void)state;
    char buf[FBRL_RAPL_LINE_MAX];
    size_t len;
    fbrl_rapl_form kw = FBRL_RAPL_KEYWORD;
    /* wrong counts */
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_APPRO, A(S("P1")), 1, 0),
                     FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_HOME, A(I(1)), 1, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_LOCK, NULL, 0, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_LOCK,
                                      A(I(1), I(2), I(3), I(4), I(5), I(6), I(7), I(8), I(1)), 9, 0),
                     FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_LOCK,
                                      A(I(1), I(2), I(3), I(4), I(5), I(6), I(7), I(8)), 8, 0),
                     FBRL_OK);
    assert_string_equal(buf, "LOCK 1,2,3,4,5,6,7,8");
    /* a precision point and MA/MI carry one value per axis: 5 (A255) or 6 (A465) */
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_POINT,
                                      A(S("#B"), I(1), I(2), I(3), I(4), I(5), I(6), I(7)), 8, 0),
                     FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_POINT,
                                      A(S("#B"), I(1), I(2), I(3), I(4)), 5, 0),
                     FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_POINT,
                                      A(S("#B"), I(1), I(2), I(3), I(4), I(5), I(6)), 7, 0),
                     FBRL_OK);
    assert_string_equal(buf, "POINT #B,1,2,3,4,5,6");
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_MA,
                                      A(R(1), R(2), R(3), R(4), R(5), R(6)), 6, 0),
                     FBRL_OK);
    assert_string_equal(buf, "MA 1,2,3,4,5,6");
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_MA,
                                      A(R(1), R(2), R(3), R(4), R(5), R(6), R(7)), 7, 0),
                     FBRL_EINVAL);
    assert_int_equal(
        fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_MI, A(R(1), R(2), R(3), R(4)), 4, 0),
        FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_POINT,
                                      A(S("#B"), R(1), I(2), I(3), I(4), I(5)), 6, 0),
                     FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_POINT, NULL, 0, 0), FBRL_EINVAL);
    /* wrong kinds */
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_JOINT, A(R(1), R(2)), 2, 0),
                     FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_MOVE, A(I(1)), 1, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_MOVE, A(S(NULL)), 1, 0),
                     FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_ARM, A(S("MAYBE")), 1, 0),
                     FBRL_ERANGE);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_ARM, A(S("O")), 1, 0),
                     FBRL_ERANGE);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_ARM, A(S("ONN")), 1, 0),
                     FBRL_ERANGE);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_CONFIG,
                                      A(I(0), I(9600), S("X"), I(8), I(1), S("N"), I(1)), 7, 0),
                     FBRL_ERANGE);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_CONFIG,
                                      A(I(0), I(9600), S("E"), I(8), I(1), S("E"), I(1)), 7, 0),
                     FBRL_ERANGE);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_ARM, A(S("on")), 1, 0), FBRL_OK);
    assert_string_equal(buf, "ARM ON");
    /* numbers */
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_JOG, A(R(1), R(NAN), R(0)), 3, 0),
                     FBRL_ENONFINITE);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_DEPART, A(R(-INFINITY)), 1, 0),
                     FBRL_ENONFINITE);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_DEPART, A(R(2e6)), 1, 0),
                     FBRL_ERANGE);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_DEPART, A(I(2000000)), 1, 0),
                     FBRL_ERANGE);
    assert_int_equal(
        fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_MOTOR, A(I(1), I(-2147483647L)), 2, 0),
        FBRL_OK);
    assert_string_equal(buf, "MOTOR 1,-2147483647");
    /* ",S" only where allowed */
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_JOG, A(R(1), R(1), R(0)), 3, 1),
                     FBRL_EINVAL);
    /* bad parameters */
    assert_int_equal(fbrl_rapl_encode(NULL, 10, &len, kw, FBRL_RAPL_HOME, NULL, 0, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_encode(buf, 0, &len, kw, FBRL_RAPL_HOME, NULL, 0, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, NULL, kw, FBRL_RAPL_HOME, NULL, 0, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_NCMDS, NULL, 0, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, (fbrl_rapl_form)7, FBRL_RAPL_HOME, NULL, 0, 0),
                     FBRL_EINVAL);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, kw, FBRL_RAPL_SPEED, NULL, 1, 0), FBRL_EINVAL);
}

static void longest_line_fits_line_max(void **state)
{
    (void)state;
    char buf[FBRL_RAPL_LINE_MAX];
    size_t len;
    double m = -FBRL_RAPL_REAL_MAX;
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, FBRL_RAPL_TOKEN, FBRL_RAPL_POINT,
                                      A(S("ABCDEFGH"), R(m), R(m), R(m), R(m), R(m), R(m)), 7, 0),
                     FBRL_OK);
    assert_true(len < FBRL_RAPL_LINE_MAX);
    assert_int_equal(fbrl_rapl_encode(buf, sizeof buf, &len, FBRL_RAPL_KEYWORD, FBRL_RAPL_POINT,
                                      A(S("ABCDEFGH"), R(m), R(m), R(m), R(m), R(m), R(m)), 7, 0),
                     FBRL_OK);
    assert_true(len < FBRL_RAPL_LINE_MAX);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_command_encodes_in_both_forms),
        cmocka_unit_test(table_is_complete_and_lookups_work),
        cmocka_unit_test(lines_name_their_command),
        cmocka_unit_test(table_facts_agree),
        cmocka_unit_test(reals_are_short_and_have_no_exponent),
        cmocka_unit_test(short_reals_read_back_as_four_decimals),
        cmocka_unit_test(names_are_validated),
        cmocka_unit_test(arguments_are_checked),
        cmocka_unit_test(longest_line_fits_line_max),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
