/* SPDX-License-Identifier: MIT */
/* num.h - decimal numbers to and from doubles, the same whatever locale the host sets.
 *
 * strtod and printf's %f/%e/%g follow the C locale of the process (LC_NUMERIC): a host
 * that calls setlocale(LC_ALL, "") under de_DE makes them read and write "14,5". The
 * language, locations and the wire must not change with the host's locale, so libfbrl
 * converts with these functions: '.' is always the decimal point, there are no thousands
 * separators, and conversions are exact (parse rounds correctly to nearest, ties to even;
 * printing rounds the exact binary value the same way), so a number printed with 17
 * significant digits reads back bit for bit. No OS headers, no allocation. */
#ifndef FBRL_NUM_H
#define FBRL_NUM_H

#include "fbrl/export.h"

#include <stddef.h>
#include "fbrl/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Flags of fbrl_num_fixed, as printf's. */
#define FBRL_NUM_PLUS 1u /* '+' before a number that is not negative ("%+f") */
#define FBRL_NUM_ZERO 2u /* pad to the width with zeros after the sign ("%0Wf") */

/* Most digits after the point fbrl_num_fixed writes; most significant digits of
 * fbrl_num_digits / fbrl_num_general (17 round-trip every double). */
#define FBRL_NUM_DECIMALS_MAX 40
#define FBRL_NUM_DIGITS_MAX   40

/* Parse all of s[0..len): [+|-] digits [. digits] [(e|E) [+|-] digits], at least one
 * digit in the mantissa, nothing else (no spaces, no "inf", no hex). Correctly rounded.
 * FBRL_ESYNTAX for anything else, FBRL_EOVERFLOW when the magnitude is too large for a
 * double; a magnitude below the smallest subnormal reads as zero (with its sign), as
 * strtod does. *out changes only on success. */
FBRL_API fbrl_status fbrl_num_parse(const char *s, size_t len, double *out);

/* printf("%[+][0]<width>.<decimals>f", v) into buf (NUL-terminated), locale-free: the
 * exact value rounded half to even at the last decimal. NaN and infinities print "nan",
 * "inf", "-inf" (padded with spaces). *len (may be NULL) gets the length without the NUL.
 * FBRL_ENOSPC when the text does not fit (buf then holds as much as fits),
 * FBRL_ERANGE for decimals outside 0..FBRL_NUM_DECIMALS_MAX or a negative width. */
FBRL_API fbrl_status fbrl_num_fixed(char *buf, size_t size, double v, int width, int decimals, unsigned flags,
                                    size_t *len);

/* printf("%.<digits-1>e", v) split up: |v| rounded to ndig significant digits
 * (1..FBRL_NUM_DIGITS_MAX, half to even), digits[0..ndig) get '0'..'9' (no NUL) and *exp10
 * the decimal exponent of the first digit: |v| = d0.d1d2... x 10^exp10. Zero gives zeros
 * and exponent 0. FBRL_ENONFINITE for NaN or infinity, FBRL_ERANGE for a bad ndig. */
FBRL_API fbrl_status fbrl_num_digits(double v, int ndig, char *digits, int *exp10);

/* printf("%.<prec>g", v) into buf, locale-free (prec 1..FBRL_NUM_DIGITS_MAX; exponent
 * written e+XX / e-XX with at least two digits). Errors as fbrl_num_fixed. */
FBRL_API fbrl_status fbrl_num_general(char *buf, size_t size, double v, int prec, size_t *len);

#ifdef __cplusplus
}
#endif
#endif
