/* SPDX-License-Identifier: MIT */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <stdint.h>
#include <cmocka.h>

#include "fbrl/rapl_reply.h"

/* Feed a string; collect lines (joined by '|') and count prompts. */
typedef struct collected {
    char lines[2048];
    int prompts, flawed;
} collected;

static void feed(fbrl_rapl_reader *r, const char *bytes, size_t n, collected *c)
{
    for (size_t i = 0; i < n; i++) {
        fbrl_rapl_event ev = fbrl_rapl_reader_feed(r, (uint8_t)bytes[i]);
        if (ev == FBRL_RAPL_EV_PROMPT) {
            c->prompts++;
            strcat(c->lines, ">>|");
        } else if (ev == FBRL_RAPL_EV_LINE) {
            size_t len;
            int fl;
            const char *l = fbrl_rapl_reader_line(r, &len, &fl);
            assert_int_equal(strlen(l), len);
            strcat(c->lines, l);
            strcat(c->lines, "|");
            c->flawed += fl;
        }
    }
}

/* The framing of a reply read from its CR on (fbrl_rapl_reader_whole and the fields). */
static fbrl_rapl_reader framed(const char *bytes, size_t n)
{
    fbrl_rapl_reader r;
    collected c;
    memset(&c, 0, sizeof c);
    fbrl_rapl_reader_init(&r);
    feed(&r, bytes, n, &c);
    return r;
}

static void reader_keeps_the_framing(void **state)
{
    (void)state;
    fbrl_rapl_reader r = framed("\r\n>>", 4);
    assert_true(fbrl_rapl_reader_whole(&r));
    assert_int_equal(r.bytes, 4);
    assert_int_equal(r.eols, 1);
    assert_int_equal(r.lines, 0);
    assert_int_equal(r.ends, FBRL_RAPL_END_CR | FBRL_RAPL_END_CRLF);
    assert_true(r.gtgt);
    r = framed("\r\n011-LOCATION UNDEFINED.\r\n>>", 29);
    assert_true(fbrl_rapl_reader_whole(&r));
    assert_int_equal(r.eols, 2);
    assert_int_equal(r.lines, 1);
    r = framed("\n>>", 3); /* the CR lost */
    assert_false(r.began);
    assert_false(fbrl_rapl_reader_whole(&r));
    assert_int_equal(r.ends, FBRL_RAPL_END_LF);
    r = framed("\r\nAB\r>>", 7); /* an LF lost */
    assert_true(r.broken);
    assert_false(fbrl_rapl_reader_whole(&r));
    r = framed("\r\nA\x01B\r\n>>", 9); /* a damaged line */
    assert_true(r.damaged);
    assert_false(r.broken);
    assert_false(fbrl_rapl_reader_whole(&r));
    r = framed("\r\n>", 3); /* no prompt yet */
    assert_false(r.prompt);
    assert_false(fbrl_rapl_reader_whole(&r));
    fbrl_rapl_reader_lost(&r); /* a parity error: a byte lost */
    assert_int_equal(r.bytes, 4);
    assert_true(r.broken);
    fbrl_rapl_reader_lost(NULL);
    assert_false(fbrl_rapl_reader_whole(NULL));
}

static void reader_cuts_lines_and_finds_prompts(void **state)
{
    (void)state;
    fbrl_rapl_reader r;
    collected c = {"", 0, 0};
    fbrl_rapl_reader_init(&r);
    static const char in[] =
        "SPEED 50\r\n>>HOME\r\n041-ROBOT HAS NOT BEEN HOMED.\r\n>>W2\r\n\r\nA\rB\nC\n\rD\r\n>>";
    feed(&r, in, sizeof in - 1, &c);
    assert_string_equal(c.lines, "SPEED 50|>>|HOME|041-ROBOT HAS NOT BEEN HOMED.|>>|W2|A|B|C|D|>>|");
    assert_int_equal(c.prompts, 3);
    assert_int_equal(c.flawed, 0);

    /* '>' inside a line is no prompt; a control byte flaws the line and is dropped */
    collected d = {"", 0, 0};
    fbrl_rapl_reader_init(&r);
    static const char in2[] = "A>>B\r\nX\x01Y\r\n\x15>>\r\n";
    feed(&r, in2, sizeof in2 - 1, &d);
    assert_string_equal(d.lines, "A>>B|XY|>>|");
    assert_int_equal(d.prompts, 0);
    assert_int_equal(d.flawed, 2);
}

static void reader_cuts_long_lines_safely(void **state)
{
    (void)state;
    fbrl_rapl_reader r;
    fbrl_rapl_reader_init(&r);
    for (int i = 0; i < 1000; i++)
        assert_int_equal(fbrl_rapl_reader_feed(&r, 'Q'), FBRL_RAPL_EV_NONE);
    assert_int_equal(fbrl_rapl_reader_feed(&r, '\r'), FBRL_RAPL_EV_LINE);
    size_t len;
    int fl;
    const char *l = fbrl_rapl_reader_line(&r, &len, &fl);
    assert_int_equal(len, FBRL_RAPL_REPLY_LINE_MAX);
    assert_int_equal(strlen(l), len);
    assert_int_equal(fl, 1);
    assert_int_equal(fbrl_rapl_reader_feed(NULL, 'x'), FBRL_RAPL_EV_NONE);
}

static void error_lines_are_checked_against_the_table(void **state)
{
    (void)state;
    int code = -5;
    char text[64];
    const char *l = "029-TRANSFORM ILLEGAL.";
    assert_int_equal(fbrl_rapl_parse_error(l, strlen(l), &code, text, sizeof text), FBRL_OK);
    assert_int_equal(code, 29);
    assert_string_equal(text, "TRANSFORM ILLEGAL");
    l = "043-JOINT #2 OUT OF RANGE.";
    assert_int_equal(fbrl_rapl_parse_error(l, strlen(l), &code, text, sizeof text), FBRL_OK);
    assert_int_equal(code, 43);
    l = "016-I/O ADDRESS ERROR.";
    assert_int_equal(fbrl_rapl_parse_error(l, strlen(l), &code, NULL, 0), FBRL_OK);
    assert_int_equal(code, 16);
    /* a corrupted digit or letter: shape right, code and text disagree */
    l = "028-TRANSFORM ILLEGAL.";
    assert_int_equal(fbrl_rapl_parse_error(l, strlen(l), &code, text, sizeof text), FBRL_ECHECKSUM);
    assert_int_equal(code, 28);
    l = "029-TRANSFORM ILLEGAK.";
    assert_int_equal(fbrl_rapl_parse_error(l, strlen(l), &code, text, sizeof text), FBRL_ECHECKSUM);
    l = "999-NO SUCH ERROR.";
    assert_int_equal(fbrl_rapl_parse_error(l, strlen(l), &code, text, sizeof text), FBRL_ECHECKSUM);
    /* not error lines */
    static const char *const bad[] = {"29-TRANSFORM ILLEGAL.",
                                      "029-TRANSFORM ILLEGAL",
                                      "029 TRANSFORM ILLEGAL.",
                                      "029-transform illegal.",
                                      "029-.",
                                      "",
                                      "+0000000100",
                                      "LAST ERROR CODE: NONE",
                                      "029-TRANSFORM,ILLEGAL."};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        assert_int_equal(fbrl_rapl_parse_error(bad[k], strlen(bad[k]), &code, text, sizeof text),
                         FBRL_ESYNTAX);
    l = "029-TRANSFORM ILLEGAL.";
    assert_int_equal(fbrl_rapl_parse_error(l, strlen(l), &code, text, 17), FBRL_ENOSPC);
    assert_int_equal(fbrl_rapl_parse_error(l, strlen(l), &code, text, 18), FBRL_OK);
    assert_int_equal(fbrl_rapl_parse_error(NULL, 3, &code, text, 18), FBRL_EINVAL);
    assert_string_equal(fbrl_rapl_error_text(41), "ROBOT HAS NOT BEEN HOMED");
    assert_string_equal(fbrl_rapl_error_text(46), "JOINT #5 OUT OF RANGE");
    assert_null(fbrl_rapl_error_text(-1));
    assert_null(fbrl_rapl_error_text(30));
    assert_null(fbrl_rapl_error_text(1000));
}

/* Every code the controller documents comes with its meaning and what to do; the ones it
 * does not have none; 029 says "out of reach" (issue 10: 029-TRANSFORM ILLEGAL). */
static void every_error_has_its_meaning(void **state)
{
    (void)state;
    int with_text = 0;
    for (int code = -1; code < 1000; code++) {
        const char *t = fbrl_rapl_error_text(code), *h = fbrl_rapl_error_help(code);
        if (t == NULL) {
            assert_null(h);
            continue;
        }
        with_text++;
        assert_non_null(h);
        assert_true(strlen(h) > 10);
    }
    assert_true(with_text >= 50);
    assert_non_null(strstr(fbrl_rapl_error_help(29), "out of the arm's reach"));
    assert_non_null(strstr(fbrl_rapl_error_help(41), "HOME"));
}

static void values_parse_without_locale(void **state)
{
    (void)state;
    double v;
    long i;
    assert_int_equal(fbrl_rapl_parse_real("+12.500000", 10, &v), FBRL_OK);
    assert_true(v == 12.5);
    assert_int_equal(fbrl_rapl_parse_real("-0.000100", 9, &v), FBRL_OK);
    assert_true(v == -0.0001);
    assert_int_equal(fbrl_rapl_parse_real("  7 ", 4, &v), FBRL_OK);
    assert_true(v == 7.0);
    assert_int_equal(fbrl_rapl_parse_int("-3", 2, &i), FBRL_OK);
    assert_int_equal(i, -3);
    assert_int_equal(fbrl_rapl_parse_int("2147483647", 10, &i), FBRL_OK);
    assert_int_equal(i, 2147483647L);
    assert_int_equal(fbrl_rapl_parse_int("2147483648", 10, &i), FBRL_ERANGE);
    assert_int_equal(fbrl_rapl_parse_int("1.5", 3, &i), FBRL_ESYNTAX);
    static const char *const bad[] = {
        "", " ", "+", "-.5", "1.", "1e3", "1,5", "12a", "--1", "1 2", "1234567890123456"};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        assert_int_equal(fbrl_rapl_parse_real(bad[k], strlen(bad[k]), &v), FBRL_ESYNTAX);
    /* length is respected: the digits after len are not read */
    assert_int_equal(fbrl_rapl_parse_int("123", 2, &i), FBRL_OK);
    assert_int_equal(i, 12);

    long vals[8];
    size_t n;
    const char *l = "+0000000100 -0000018000 +0000000000 +0000000004 -0000000022";
    assert_int_equal(fbrl_rapl_parse_ints(l, strlen(l), vals, 8, &n), FBRL_OK);
    assert_int_equal(n, 5);
    assert_int_equal(vals[1], -18000);
    assert_int_equal(vals[4], -22);
    assert_int_equal(fbrl_rapl_parse_ints(l, strlen(l), vals, 4, &n), FBRL_ESYNTAX);
    l = "+0000000100 -000001800";
    assert_int_equal(fbrl_rapl_parse_ints(l, strlen(l), vals, 8, &n), FBRL_ESYNTAX);
    l = "ACTUAL POSITION (MOTOR PULSES):";
    assert_int_equal(fbrl_rapl_parse_ints(l, strlen(l), vals, 8, &n), FBRL_ESYNTAX);
}

/* The W2 block exactly as docs/rapl-commands.md 4.1 shows it. */
static const char *const w2[] = {
    "CURRENT ACTUAL POSITION :",
    "NAME       AX#1        AX#2        AX#3        AX#4        AX#5",
    "PULSES   +0000000000 +0000018000 -0000018000 +0000000000 +0000000000",
    "NAME       JT#1      JT#2      JT#3      JT#4      JT#5",
    "JOINTS   +000.0000 +090.0000 -090.0000 +000.0000 +000.0000",
    "WORLD     +012.0000 +000.0000 +020.0000 +000.0000 +000.0000 +000.0000",
};

static void position_blocks_parse(void **state)
{
    (void)state;
    fbrl_rapl_pos p;
    fbrl_rapl_pos_init(&p);
    for (size_t k = 0; k < 6; k++) {
        assert_int_equal(fbrl_rapl_pos_line(&p, w2[k], strlen(w2[k])), FBRL_OK);
        assert_int_equal(fbrl_rapl_pos_complete(&p, 5), k == 5);
    }
    assert_int_equal(p.kind, 'A');
    assert_int_equal(p.pulses[1], 18000);
    assert_int_equal(p.pulses[2], -18000);
    assert_true(p.joints[1] == 90.0);
    assert_true(p.world[0] == 12.0 && p.world[2] == 20.0);
    assert_false(fbrl_rapl_pos_complete(&p, 6));

    /* six axes wrap as in the research sample (continuation lines) */
    static const char *const w0[] = {
        "CURRENT COMMAND POSITION :", "PULSES   -0000000001 -0000000001 -0000000001 -0000000001 -0000000001",
        "         -0000000114",       "JOINTS   +000.0150 +000.0150 +000.0150 +000.0071 +000.0036",
        "         +000.8126",         "WORLD     +000.0198 +000.0149 -076.1849 +000.0000 +089.9964 +000.8198",
    };
    fbrl_rapl_pos_init(&p);
    for (size_t k = 0; k < 6; k++)
        assert_int_equal(fbrl_rapl_pos_line(&p, w0[k], strlen(w0[k])), FBRL_OK);
    assert_true(fbrl_rapl_pos_complete(&p, 6));
    assert_int_equal(p.kind, 'C');
    assert_int_equal(p.pulses[5], -114);
    assert_true(p.joints[5] == 0.8126);
    assert_true(p.world[2] == -76.1849);

    /* corrupted lines are refused, never half-read as numbers */
    static const char *const bad[] = {
        "PULSES   +0000000000 +00000180O0 -0000018000 +0000000000 +0000000000",
        "PULSES   +0000000000 +000018000 -0000018000 +0000000000 +0000000000",
        "JOINTS   +000.0000 +090.000 -090.0000 +000.0000 +000.0000",
        "JOINTS   +000.0000 +090.0000-090.0000 +000.0000 +000.0000",
        "WORLD     +012.0000 +000.0000 +020.0000 +000.0000 +000.0000 +000.0000 +000.0000",
        "WORLD     012.0000 +000.0000 +020.0000 +000.0000 +000.0000 +000.0000",
        "WORLDS    +012.0000",
        "PULSES",
        "   ",
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        fbrl_rapl_pos_init(&p);
        assert_int_equal(fbrl_rapl_pos_line(&p, w2[0], strlen(w2[0])), FBRL_OK);
        assert_int_equal(fbrl_rapl_pos_line(&p, bad[k], strlen(bad[k])), FBRL_ESYNTAX);
    }
    /* a section seen twice is refused; lines before a title too */
    fbrl_rapl_pos_init(&p);
    assert_int_equal(fbrl_rapl_pos_line(&p, w2[2], strlen(w2[2])), FBRL_ESYNTAX);
    assert_int_equal(fbrl_rapl_pos_line(&p, w2[0], strlen(w2[0])), FBRL_OK);
    assert_int_equal(fbrl_rapl_pos_line(&p, w2[2], strlen(w2[2])), FBRL_OK);
    assert_int_equal(fbrl_rapl_pos_line(&p, w2[2], strlen(w2[2])), FBRL_ESYNTAX);
}

static void status_blocks_parse(void **state)
{
    (void)state;
    static const char *const lines[] = {
        "RAPL-II Version 2.60     A255 Robot (fbrlsim)",
        "LAST ERROR CODE: 029-TRANSFORM ILLEGAL.",
        "SPEED (% OF FULL) :    +50",
        "MAX LINEAR SPEED: +019.7000",
        "CURRENT PROGRAM EXECUTING:",
        "JOINT LIMIT CHECK IS ON",
        "CONTROLLER IS HOMED",
        "TOOL TRANSFORM",
        "NULL      +000.0000 +000.0000 +000.0000 +000.0000 +000.0000 +000.0000",
        "GRIPPER TYPE:  SERVO",
        "AXIS#        1 2 3 4 5",
        "LOCK         N Y N N N",
        "DONE         Y Y Y Y N",
        "LIMP         N N N N N",
        "HOMED        Y Y Y Y Y",
        "MANUAL MODE STATUS IS OFF",
        "INPUTS  1-16: 1000000000000001",
        "OUTPUTS 1-16: 0100000000000000",
        "INCH UNITS.",
    };
    fbrl_rapl_status_info s;
    fbrl_rapl_status_init(&s);
    for (size_t k = 0; k < sizeof lines / sizeof lines[0]; k++) {
        fbrl_status st = fbrl_rapl_status_line(&s, lines[k], strlen(lines[k]));
        assert_true(st == FBRL_OK || st == FBRL_ENOENT);
    }
    assert_int_equal(s.have, 0x3ffu);
    assert_int_equal(s.metric, 0);
    assert_int_equal(fbrl_rapl_status_line(&s, "METRIC UNITS.", 13), FBRL_OK);
    assert_int_equal(s.metric, 1);
    assert_int_equal(s.last_error, 29);
    assert_true(s.speed == 50.0);
    assert_int_equal(s.homed, 1);
    assert_int_equal(s.naxes, 5);
    assert_int_equal(s.lock[1], 1);
    assert_int_equal(s.lock[0], 0);
    assert_int_equal(s.done[4], 0);
    assert_int_equal(s.axis_homed[2], 1);
    assert_int_equal(s.inputs, 0x8001u);
    assert_int_equal(s.outputs, 0x2u);

    const char *l = "LAST ERROR CODE: NONE";
    assert_int_equal(fbrl_rapl_status_line(&s, l, strlen(l)), FBRL_OK);
    assert_int_equal(s.last_error, -1);
    l = "CONTROLLER IS NOT HOMED";
    assert_int_equal(fbrl_rapl_status_line(&s, l, strlen(l)), FBRL_OK);
    assert_int_equal(s.homed, 0);
    static const char *const bad[] = {
        "LAST ERROR CODE: 029-TRANSFORM ILLEGAK.", "LOCK         N Y N N",       "DONE         Y X Y Y Y",
        "INPUTS  1-16: 100000000000000",           "SPEED (% OF FULL) :    50x", "LIMP         NN N N N N"};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        assert_int_equal(fbrl_rapl_status_line(&s, bad[k], strlen(bad[k])), FBRL_ESYNTAX);
}

/* Random and mutated input through every parser: nothing may read out of bounds (run
 * under ASan in CI) and the reader's lines always have the length they claim. */
static void garbage_is_survived(void **state)
{
    (void)state;
    uint32_t x = 12345u;
    char line[200];
    fbrl_rapl_reader r;
    fbrl_rapl_reader_init(&r);
    fbrl_rapl_pos p;
    fbrl_rapl_pos_init(&p);
    fbrl_rapl_status_info s;
    fbrl_rapl_status_init(&s);
    for (int round = 0; round < 20000; round++) {
        x = x * 1664525u + 1013904223u;
        size_t len = (x >> 8) % sizeof line;
        const char *base = w2[(x >> 4) % 6];
        for (size_t k = 0; k < len; k++) {
            x = x * 1664525u + 1013904223u;
            /* mostly real text with a few random bytes */
            line[k] = (x >> 24) < 20 ? (char)(x >> 16)
                                     : (k < strlen(base) ? base[k] : (char)(' ' + (x >> 16) % 64));
        }
        int code;
        char text[80];
        double v;
        long iv, vals[8];
        size_t n;
        (void)fbrl_rapl_parse_error(line, len, &code, text, sizeof text);
        (void)fbrl_rapl_parse_real(line, len, &v);
        (void)fbrl_rapl_parse_int(line, len, &iv);
        (void)fbrl_rapl_parse_ints(line, len, vals, 8, &n);
        if (fbrl_rapl_pos_line(&p, line, len) != FBRL_OK)
            fbrl_rapl_pos_init(&p);
        (void)fbrl_rapl_status_line(&s, line, len);
        assert_true(p.npulses <= FBRL_RAPL_MAX_AXES && p.njoints <= FBRL_RAPL_MAX_AXES && p.nworld <= 6);
        assert_true(s.naxes <= FBRL_RAPL_MAX_AXES);
        for (size_t k = 0; k < len; k++) {
            if (fbrl_rapl_reader_feed(&r, (uint8_t)line[k]) == FBRL_RAPL_EV_LINE) {
                size_t ll;
                const char *l = fbrl_rapl_reader_line(&r, &ll, NULL);
                assert_true(ll <= FBRL_RAPL_REPLY_LINE_MAX);
                assert_int_equal(strlen(l), ll);
            }
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(reader_cuts_lines_and_finds_prompts),
        cmocka_unit_test(reader_keeps_the_framing),
        cmocka_unit_test(reader_cuts_long_lines_safely),
        cmocka_unit_test(error_lines_are_checked_against_the_table),
        cmocka_unit_test(every_error_has_its_meaning),
        cmocka_unit_test(values_parse_without_locale),
        cmocka_unit_test(position_blocks_parse),
        cmocka_unit_test(status_blocks_parse),
        cmocka_unit_test(garbage_is_survived),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
