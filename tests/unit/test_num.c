/* SPDX-License-Identifier: MIT */
/* test_num.c - locale-free number conversion against the C library in the "C" locale
 * (which the test never leaves): parse against strtod, printing against snprintf, over
 * random doubles of every magnitude, exact ties, subnormals and long inputs. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/num.h"

static uint64_t rng_state;
static uint64_t rng_next(void)
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Any finite double, every exponent equally likely (bit patterns). */
static double random_double(void)
{
    for (;;) {
        uint64_t b = rng_next();
        double d;
        memcpy(&d, &b, sizeof d);
        if (isfinite(d))
            return d;
    }
}

/* Doubles a robot program meets: inches and degrees with a few decimals. */
static double random_everyday(void)
{
    double v = (double)(int64_t)(rng_next() % 4000001) / 10000.0 - 200.0;
    return (rng_next() & 3) ? v : v * 1e-3;
}

static void same_bits(double a, double b, const char *text)
{
    if (memcmp(&a, &b, sizeof a) != 0) {
        print_error("'%s': got %.17g, strtod %.17g\n", text, a, b);
        fail();
    }
}

static void check_parse(const char *text)
{
    double got = 0.0, want = strtod(text, NULL);
    fbrl_status st = fbrl_num_parse(text, strlen(text), &got);
    if (isinf(want)) {
        assert_int_equal(st, FBRL_EOVERFLOW);
        return;
    }
    if (st != FBRL_OK) {
        print_error("'%s': status %d\n", text, st);
        fail();
    }
    same_bits(got, want, text);
}

static void parse_matches_strtod(void **state)
{
    char text[1200];
    int i;
    (void)state;
    rng_state = 7;
    for (i = 0; i < 20000; i++) {
        double d = i & 1 ? random_double() : random_everyday();
        int prec = 1 + (int)(rng_next() % 19);
        snprintf(text, sizeof text, "%.*e", prec - 1, d);
        check_parse(text);
        snprintf(text, sizeof text, "%.17g", d);
        check_parse(text);
        snprintf(text, sizeof text, "%.4f", random_everyday());
        check_parse(text);
    }
    /* Exact midpoints between neighbouring doubles (the exact decimal of the mean, all
     * digits printed by glibc), and one digit either side of them. */
    for (i = 0; i < 3000; i++) {
        double d = i % 3 ? random_double() : random_everyday(), up = nextafter(d, INFINITY);
        long double mid;
        size_t n;
        if (!isfinite(up) || d == 0.0)
            continue;
        mid = ((long double)d + (long double)up) / 2; /* exact in x87 extended */
        snprintf(text, sizeof text, "%.780Le", mid);
        check_parse(text);
        n = strlen(text);
        /* just above: the midpoint with a 1 somewhere past the 770th digit */
        char *e = strchr(text, 'e');
        char tail[16];
        snprintf(tail, sizeof tail, "%s", e);
        snprintf(e, sizeof text - (size_t)(e - text), "1%s", tail);
        check_parse(text);
        (void)n;
    }
    /* Hand cases: subnormals, the largest double and past it, zeros, long inputs. */
    static const char *const hand[] = {
        "0",
        "-0",
        "0.0",
        ".5",
        "5.",
        "1E0",
        "1.5E0",
        "1.5e+3",
        "-2.5E-3",
        "4.9406564584124654e-324",
        "2.4703282292062327e-324",
        "2.4703282292062328e-324",
        "2.2250738585072011e-308",
        "2.2250738585072014e-308",
        "1.7976931348623157e308",
        "1.7976931348623158e308",
        "1.7976931348623159e308",
        "1e309",
        "1e-400",
        "123456789012345678901234567890",
        "0.000000000000000000000000000000000000000000001",
        "9007199254740993",
        "9007199254740992.5",
        "1e22",
        "1e23",
        "8.98846567431158e307",
        "0.1",
        "0.2",
        "0.3",
        "14.5",
        "+14.5000",
    };
    for (i = 0; i < (int)(sizeof hand / sizeof hand[0]); i++)
        check_parse(hand[i]);
    /* 2,000 digits: only the first 800 are kept, the rest still decide the rounding. */
    memset(text, '1', 1100);
    text[0] = '9';
    text[1100] = 0;
    check_parse(text);
    memcpy(text, "0.", 2);
    check_parse(text);
}

static void parse_refuses_non_numbers(void **state)
{
    static const char *const bad[] = {"",     "+",    "-",       ".",   "e5",    "1e",  "1e+",
                                      "1.5E", "1,5",  "14,5000", " 1",  "1 ",    "inf", "nan",
                                      "0x10", "1..2", "1e5.5",   "--1", "1.5F0", "1d0"};
    double v = 42.0;
    size_t i;
    (void)state;
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        if (fbrl_num_parse(bad[i], strlen(bad[i]), &v) != FBRL_ESYNTAX) {
            print_error("'%s' accepted\n", bad[i]);
            fail();
        }
    }
    assert_true(v == 42.0);
    assert_int_equal(fbrl_num_parse("1e99999999999999999999", 22, &v), FBRL_EOVERFLOW);
    assert_int_equal(fbrl_num_parse("1e-99999999999999999999", 23, &v), FBRL_OK);
    assert_true(v == 0.0);
    /* only len characters count */
    assert_int_equal(fbrl_num_parse("2.5junk", 3, &v), FBRL_OK);
    assert_true(v == 2.5);
    assert_int_equal(fbrl_num_parse(NULL, 0, &v), FBRL_EINVAL);
    assert_int_equal(fbrl_num_parse("1", 1, NULL), FBRL_EINVAL);
}

static void check_fixed(double v, int width, int dec, unsigned flags)
{
    char got[512], want[512], fmt[32];
    size_t len = 0;
    snprintf(fmt, sizeof fmt, "%%%s%s%d.%df", flags & FBRL_NUM_PLUS ? "+" : "",
             flags & FBRL_NUM_ZERO ? "0" : "", width, dec);
    snprintf(want, sizeof want, fmt, v);
    assert_int_equal(fbrl_num_fixed(got, sizeof got, v, width, dec, flags, &len), FBRL_OK);
    if (strcmp(got, want) != 0) {
        print_error("%s of %.17g: got '%s', printf '%s'\n", fmt, v, got, want);
        fail();
    }
    assert_int_equal(len, strlen(want));
}

static void fixed_matches_printf(void **state)
{
    int i;
    (void)state;
    rng_state = 11;
    for (i = 0; i < 20000; i++) {
        double v = i % 4 ? random_everyday() : random_double();
        int dec = (int)(rng_next() % 12), width = (int)(rng_next() % 14);
        unsigned flags = (unsigned)(rng_next() % 4);
        if (fabs(v) > 1e30 && i % 8)
            v = random_everyday();
        check_fixed(v, width, dec, flags);
        check_fixed(v, 10, 4, FBRL_NUM_PLUS);                /* fbrl_loc_format's layout */
        check_fixed(v, 9, 4, FBRL_NUM_PLUS | FBRL_NUM_ZERO); /* the wire's %+09.4f */
    }
    /* Exact ties round to even, as printf does; values printed whole. */
    static const double ties[] = {
        0.125, 0.375, 2.5,     3.5,    -0.5, 0.5, 1.5, 1e22, DBL_MAX, DBL_MIN, 4.9406564584124654e-324,
        -0.0,  0.0,   9.99995, 0.00005};
    for (i = 0; i < (int)(sizeof ties / sizeof ties[0]); i++) {
        check_fixed(ties[i], 0, 0, 0);
        check_fixed(ties[i], 0, 2, 0);
        check_fixed(ties[i], 12, 4, FBRL_NUM_PLUS);
        check_fixed(ties[i], 0, 40, 0);
    }
    check_fixed(14.5, 10, 4, FBRL_NUM_PLUS);
    /* Not finite, as printf ("%f" of NaN: "nan"). */
    char b[16];
    assert_int_equal(fbrl_num_fixed(b, sizeof b, INFINITY, 6, 2, 0, NULL), FBRL_OK);
    assert_string_equal(b, "   inf");
    assert_int_equal(fbrl_num_fixed(b, sizeof b, -INFINITY, 0, 2, FBRL_NUM_ZERO, NULL), FBRL_OK);
    assert_string_equal(b, "-inf");
    assert_int_equal(fbrl_num_fixed(b, sizeof b, NAN, 0, 2, 0, NULL), FBRL_OK);
    assert_string_equal(b, "nan");
    /* Too small a buffer: as much as fits, and the caller is told. */
    size_t len = 99;
    assert_int_equal(fbrl_num_fixed(b, 5, 123.456, 0, 3, 0, &len), FBRL_ENOSPC);
    assert_string_equal(b, "123.");
    assert_int_equal(len, 4);
    assert_int_equal(fbrl_num_fixed(b, sizeof b, 1.0, 0, FBRL_NUM_DECIMALS_MAX + 1, 0, NULL), FBRL_ERANGE);
    assert_int_equal(fbrl_num_fixed(b, sizeof b, 1.0, -1, 2, 0, NULL), FBRL_ERANGE);
    assert_int_equal(fbrl_num_fixed(NULL, 4, 1.0, 0, 2, 0, NULL), FBRL_EINVAL);
}

static void digits_and_general_match_printf(void **state)
{
    char got[512], want[512], dig[FBRL_NUM_DIGITS_MAX];
    int i, x;
    (void)state;
    rng_state = 13;
    for (i = 0; i < 20000; i++) {
        double v = i % 3 ? random_double() : random_everyday();
        int prec = 1 + (int)(rng_next() % 17);
        /* digits: "%.{prec-1}e" without the point */
        snprintf(want, sizeof want, "%.*e", prec - 1, fabs(v));
        assert_int_equal(fbrl_num_digits(v, prec, dig, &x), FBRL_OK);
        char *e = strchr(want, 'e');
        int k = 0;
        for (char *q = want; q < e; q++)
            if (*q != '.')
                assert_int_equal(dig[k++], *q);
        assert_int_equal(k, prec);
        assert_int_equal(x, v == 0.0 ? 0 : atoi(e + 1));
        /* general: "%.{prec}g", and 17 digits read back bit for bit */
        snprintf(want, sizeof want, "%.*g", prec, v);
        assert_int_equal(fbrl_num_general(got, sizeof got, v, prec, NULL), FBRL_OK);
        if (strcmp(got, want) != 0) {
            print_error("%%.%dg of %.17g: got '%s', printf '%s'\n", prec, v, got, want);
            fail();
        }
        double back;
        assert_int_equal(fbrl_num_general(got, sizeof got, v, 17, NULL), FBRL_OK);
        assert_int_equal(fbrl_num_parse(got, strlen(got), &back), FBRL_OK);
        same_bits(back, v, got);
    }
    assert_int_equal(fbrl_num_digits(NAN, 3, dig, &x), FBRL_ENONFINITE);
    assert_int_equal(fbrl_num_digits(1.0, 0, dig, &x), FBRL_ERANGE);
    assert_int_equal(fbrl_num_general(got, sizeof got, 0.0, 17, NULL), FBRL_OK);
    assert_string_equal(got, "0");
    assert_int_equal(fbrl_num_general(got, sizeof got, 99999.5, 5, NULL), FBRL_OK);
    assert_string_equal(got, "1e+05");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(parse_matches_strtod),
        cmocka_unit_test(parse_refuses_non_numbers),
        cmocka_unit_test(fixed_matches_printf),
        cmocka_unit_test(digits_and_general_match_printf),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
