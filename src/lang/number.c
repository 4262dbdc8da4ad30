/* number.c - reading numbers: integers and doubles in BASE, floats in the
 * standard's form (the text interpreter and >NUMBER >FLOAT use it). */
#include <math.h>
#include <string.h>
#include "fbrl/num.h"
#include "words.h"

/* ---- numbers ---- */
static int digit_of(unsigned char c, fbrl_cell base)
{
    int d;
    if (c >= '0' && c <= '9')
        d = c - '0';
    else if (c >= 'A' && c <= 'Z')
        d = c - 'A' + 10;
    else if (c >= 'a' && c <= 'z')
        d = c - 'a' + 10;
    else
        return -1;
    return d < base ? d : -1;
}

/* ud = ud*base + d, wrapping (cells hold the double as lo, hi). */
static void ud_mul_add(fbrl_ucell *lo, fbrl_ucell *hi, fbrl_ucell base, fbrl_ucell d)
{
    const int hb = CELL_BITS / 2;
    const fbrl_ucell mask = ((fbrl_ucell)1 << hb) - 1;
    fbrl_ucell l0 = *lo & mask, l1 = *lo >> hb;
    fbrl_ucell p0 = l0 * base + d; /* base <= 36 and halves keep these exact */
    fbrl_ucell p1 = l1 * base + (p0 >> hb);
    *lo = (p0 & mask) | (p1 << hb);
    *hi = *hi * base + (p1 >> hb);
}

/* >NUMBER on a C string: converts while digits remain; returns chars consumed. */
size_t fbrl__to_number(const char *s, size_t n, fbrl_cell base, fbrl_ucell *lo, fbrl_ucell *hi)
{
    size_t i = 0;
    for (; i < n; i++) {
        int d = digit_of((unsigned char)s[i], base);
        if (d < 0)
            break;
        ud_mul_add(lo, hi, (fbrl_ucell)base, (fbrl_ucell)d);
    }
    return i;
}

/* The text interpreter's number syntax. kind: 1 single, 2 double, 3 float; 0 not a number. */
int fbrl__parse_number(fbrl_vm *vm, const char *s, size_t n, fbrl_cell v[2], double *f)
{
    fbrl_cell base = *vm->base;
    if (n == 3 && s[0] == '\'' && s[2] == '\'') {
        v[0] = (unsigned char)s[1];
        return 1;
    }
    const char *p = s;
    size_t k = n;
    if (k > 1 && (*p == '#' || *p == '$' || *p == '%')) {
        base = *p == '#' ? 10 : *p == '$' ? 16 : 2;
        p++;
        k--;
    }
    if (base >= 2 && base <= 36) {
        int neg = 0, dbl = 0;
        const char *q = p;
        size_t m = k;
        if (m > 1 && *q == '-') {
            neg = 1;
            q++;
            m--;
        }
        if (m > 1 && q[m - 1] == '.') {
            dbl = 1;
            m--;
        }
        fbrl_ucell lo = 0, hi = 0;
        if (m > 0 && fbrl__to_number(q, m, base, &lo, &hi) == m) {
            if (neg) {
                lo = ~lo + 1;
                hi = ~hi + (lo == 0);
            }
            v[0] = (fbrl_cell)lo;
            v[1] = (fbrl_cell)hi;
            return dbl ? 2 : 1;
        }
    }
    if (p == s && *vm->base == 10 && fbrl__parse_float(s, n, 1, f))
        return 3;
    return 0;
}

int fbrl__parse_float(const char *s, size_t n, int need_e, double *out)
{
    char b[400];
    size_t i = 0, k = 0;
    int nd = 0, nfrac = 0;
    if (n > 350)
        return 0;
    if (i < n && (s[i] == '+' || s[i] == '-'))
        b[k++] = s[i++];
    while (i < n && s[i] >= '0' && s[i] <= '9') {
        b[k++] = s[i++];
        nd++;
    }
    if (i < n && s[i] == '.') {
        b[k++] = s[i++];
        while (i < n && s[i] >= '0' && s[i] <= '9') {
            b[k++] = s[i++];
            nd++;
            nfrac++;
        }
    }
    if (nd == 0)
        return 0;
    if (i < n && (s[i] == 'E' || s[i] == 'e' || s[i] == 'D' || s[i] == 'd')) {
        i++;
        b[k++] = 'e';
        if (i < n && (s[i] == '+' || s[i] == '-'))
            b[k++] = s[i++];
        int ed = 0;
        while (i < n && s[i] >= '0' && s[i] <= '9') {
            b[k++] = s[i++];
            ed++;
        }
        if (!ed)
            b[k++] = '0';
    } else if (need_e && nfrac == 0) {
        /* FBRL (as the thesis writes `0.2 0.5 1.0 LOC RADMAT MAT`): digits after a
         * decimal point make a float; a trailing point alone still makes a double. */
        return 0;
    } else if (i < n && (s[i] == '+' || s[i] == '-')) {
        b[k++] = 'e';
        b[k++] = s[i++];
        int ed = 0;
        while (i < n && s[i] >= '0' && s[i] <= '9') {
            b[k++] = s[i++];
            ed++;
        }
        if (!ed)
            return 0;
    }
    if (i != n)
        return 0;
    double v;
    /* fbrl_num_parse, not strtod: a host's locale must not change what a number is */
    if (fbrl_num_parse(b, k, &v) != FBRL_OK || !isfinite(v))
        return 0;
    *out = v;
    return 1;
}
