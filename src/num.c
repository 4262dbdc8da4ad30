/* SPDX-License-Identifier: MIT */
/* num.c - locale-free, exact decimal <-> double conversion; see num.h.
 *
 * Both directions work on exact big integers, so there is no rounding but the one asked
 * for. Printing: a finite double is m * 2^e exactly; m * 2^e (e >= 0) or m * 5^-e / 10^-e
 * (e < 0) gives its complete decimal expansion (at most 767 significant digits), which is
 * then rounded as text. Parsing: the digits D and exponent E of the input give D * 10^E;
 * the top 64 bits of that value (a product, or a quotient by long division) and whether
 * anything non-zero lies below them decide the rounding to 53 bits (or fewer, for a
 * subnormal). Short inputs take the exact one-operation path of Clinger (1990). */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>
#include "fbrl/num.h"

/* ---- big unsigned integers (fixed capacity; every use below stays within it) ---- */

#define BN_WORDS 128 /* 4096 bits: 10^1130 * 2^63, the largest parse intermediate, fits */

typedef struct {
    uint32_t w[BN_WORDS]; /* little-endian words */
    int n;                /* words in use; w[n-1] != 0 unless n == 0 */
} bn;

static void bn_set(bn *a, uint64_t v)
{
    a->n = 0;
    while (v) {
        a->w[a->n++] = (uint32_t)v;
        v >>= 32;
    }
}

static void bn_mul_small(bn *a, uint32_t m)
{
    uint64_t carry = 0;
    int i;
    for (i = 0; i < a->n; i++) {
        uint64_t p = (uint64_t)a->w[i] * m + carry;
        a->w[i] = (uint32_t)p;
        carry = p >> 32;
    }
    if (carry && a->n < BN_WORDS)
        a->w[a->n++] = (uint32_t)carry;
}

static void bn_add_small(bn *a, uint32_t v)
{
    int i = 0;
    uint64_t carry = v;
    while (carry && i < a->n) {
        uint64_t s = (uint64_t)a->w[i] + carry;
        a->w[i++] = (uint32_t)s;
        carry = s >> 32;
    }
    if (carry && a->n < BN_WORDS)
        a->w[a->n++] = (uint32_t)carry;
}

/* a *= base^k, in steps of chunk = base^chunk_k (chunk < 2^32). */
static void bn_mul_pow(bn *a, uint32_t base, uint32_t chunk, int chunk_k, int k)
{
    for (; k >= chunk_k; k -= chunk_k)
        bn_mul_small(a, chunk);
    while (k-- > 0)
        bn_mul_small(a, base);
}

static void bn_shl(bn *a, int bits)
{
    int words = bits / 32, r = bits % 32, i;
    if (a->n == 0 || bits == 0)
        return;
    if (r) {
        uint32_t carry = 0;
        for (i = 0; i < a->n; i++) {
            uint32_t w = a->w[i];
            a->w[i] = (w << r) | carry;
            carry = w >> (32 - r);
        }
        if (carry && a->n < BN_WORDS)
            a->w[a->n++] = carry;
    }
    if (words) {
        for (i = a->n - 1; i >= 0; i--)
            if (i + words < BN_WORDS)
                a->w[i + words] = a->w[i];
        for (i = 0; i < words; i++)
            a->w[i] = 0;
        a->n = a->n + words > BN_WORDS ? BN_WORDS : a->n + words;
    }
}

static void bn_shr1(bn *a)
{
    int i;
    for (i = 0; i < a->n; i++)
        a->w[i] = (a->w[i] >> 1) | (i + 1 < a->n ? a->w[i + 1] << 31 : 0);
    while (a->n && a->w[a->n - 1] == 0)
        a->n--;
}

static int bn_cmp(const bn *a, const bn *b)
{
    int i;
    if (a->n != b->n)
        return a->n < b->n ? -1 : 1;
    for (i = a->n - 1; i >= 0; i--)
        if (a->w[i] != b->w[i])
            return a->w[i] < b->w[i] ? -1 : 1;
    return 0;
}

/* a -= b, a >= b. */
static void bn_sub(bn *a, const bn *b)
{
    int64_t borrow = 0;
    int i;
    for (i = 0; i < a->n; i++) {
        int64_t d = (int64_t)a->w[i] - (i < b->n ? (int64_t)b->w[i] : 0) - borrow;
        borrow = d < 0;
        a->w[i] = (uint32_t)(d + (borrow ? ((int64_t)1 << 32) : 0));
    }
    while (a->n && a->w[a->n - 1] == 0)
        a->n--;
}

/* a /= d, returns the remainder. */
static uint32_t bn_div_small(bn *a, uint32_t d)
{
    uint64_t rem = 0;
    int i;
    for (i = a->n - 1; i >= 0; i--) {
        uint64_t cur = (rem << 32) | a->w[i];
        a->w[i] = (uint32_t)(cur / d);
        rem = cur % d;
    }
    while (a->n && a->w[a->n - 1] == 0)
        a->n--;
    return (uint32_t)rem;
}

static int bn_bits(const bn *a)
{
    uint32_t top;
    int b;
    if (a->n == 0)
        return 0;
    top = a->w[a->n - 1];
    for (b = 0; top; b++)
        top >>= 1;
    return 32 * (a->n - 1) + b;
}

static int bn_bit(const bn *a, int i)
{
    return i >= 0 && i / 32 < a->n ? (int)((a->w[i / 32] >> (i % 32)) & 1u) : 0;
}

/* The top 64 bits of a (a != 0) with their top bit set: a = hi * 2^(*exp2) + lower bits,
 * *sticky |= whether the lower bits are non-zero. With fewer than 64 bits, hi is a
 * shifted up and *exp2 negative. */
static uint64_t bn_top64(const bn *a, int *exp2, int *sticky)
{
    int len = bn_bits(a), shift = len - 64, i;
    uint64_t hi = 0;
    for (i = 0; i < 64; i++)
        hi = (hi << 1) | (uint64_t)bn_bit(a, len - 1 - i);
    for (i = 0; shift > 0 && i < shift; i++)
        if (bn_bit(a, i)) {
            *sticky = 1;
            break;
        }
    *exp2 = shift;
    return hi;
}

/* ---- parsing ---- */

/* Significant digits kept; beyond them only "was anything non-zero" counts. Decimal
 * midpoints between doubles have at most 767 significant digits, so this is exact. */
#define NUM_SIG_MAX 800
#define NUM_EXP_CAP 100000 /* exponents are saturated here; far past any double */
#define NUM_MAX_DEC 310    /* D * 10^E with nd + E above this is past DBL_MAX */
#define NUM_MIN_DEC (-330) /* ... and below this, under half the smallest subnormal */

/* hi * 2^exp2 (top bit of hi set; sticky: something non-zero lies below hi) rounded to a
 * double, nearest with ties to even, subnormals included. */
static fbrl_status round_to_double(uint64_t hi, int exp2, int sticky, int neg, double *out)
{
    int top = exp2 + 63, keep, shift;
    uint64_t kept, rem, half;
    double d;
    if (top > DBL_MAX_EXP - 1)
        return FBRL_EOVERFLOW;
    keep = top >= DBL_MIN_EXP - 1 ? DBL_MANT_DIG : DBL_MANT_DIG - (DBL_MIN_EXP - 1 - top);
    shift = 64 - keep;
    if (shift > 64) { /* below half the smallest subnormal */
        kept = 0;
        rem = 0;
        half = 1;
    } else if (shift == 64) {
        kept = 0;
        rem = hi;
        half = (uint64_t)1 << 63;
    } else {
        kept = hi >> shift;
        rem = hi & (((uint64_t)1 << shift) - 1);
        half = (uint64_t)1 << (shift - 1);
    }
    if (rem > half || (rem == half && (sticky || (kept & 1u))))
        kept++;
    d = ldexp((double)kept, exp2 + shift);
    if (isinf(d))
        return FBRL_EOVERFLOW;
    *out = neg ? -d : d;
    return FBRL_OK;
}

static const double exact_pow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                     1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/* D (nd digits, no leading zero) * 10^e10, correctly rounded. */
static fbrl_status decimal_to_double(const char *dig, int nd, long e10, int sticky, int neg, double *out)
{
    bn x, y;
    int i, exp2 = 0;
    uint64_t hi;
    if (nd + e10 > NUM_MAX_DEC)
        return FBRL_EOVERFLOW;
    if (nd + e10 < NUM_MIN_DEC) {
        *out = neg ? -0.0 : 0.0;
        return FBRL_OK;
    }
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD == 0
    /* Both operands exact doubles, one correctly rounded operation. */
    if (!sticky && nd <= 15 && e10 >= -22 && e10 <= 22) {
        double d = 0.0;
        for (i = 0; i < nd; i++)
            d = d * 10.0 + (dig[i] - '0');
        d = e10 < 0 ? d / exact_pow10[-e10] : d * exact_pow10[e10];
        *out = neg ? -d : d;
        return FBRL_OK;
    }
#else
    (void)exact_pow10;
#endif
    bn_set(&x, 0);
    for (i = 0; i < nd; i++) {
        bn_mul_small(&x, 10);
        bn_add_small(&x, (uint32_t)(dig[i] - '0'));
    }
    if (e10 >= 0) {
        bn_mul_pow(&x, 10, 1000000000u, 9, (int)e10);
        hi = bn_top64(&x, &exp2, &sticky);
        return round_to_double(hi, exp2, sticky, neg, out);
    } else {
        /* q = floor(x * 2^s / 10^-e10) with s chosen so that q has 63 or 64 bits. */
        uint64_t q = 0;
        int s, b;
        bn_set(&y, 1);
        bn_mul_pow(&y, 10, 1000000000u, 9, (int)-e10);
        s = bn_bits(&y) - bn_bits(&x) + 63;
        if (s > 0)
            bn_shl(&x, s);
        else
            bn_shl(&y, -s);
        bn_shl(&y, 63);
        for (b = 63; b >= 0; b--) {
            if (bn_cmp(&x, &y) >= 0) {
                bn_sub(&x, &y);
                q |= (uint64_t)1 << b;
            }
            bn_shr1(&y);
        }
        if (x.n)
            sticky = 1;
        exp2 = -s;
        while (!(q >> 63)) {
            q <<= 1;
            exp2--;
        }
        return round_to_double(q, exp2, sticky, neg, out);
    }
}

static int is_dig(char c) { return c >= '0' && c <= '9'; }

fbrl_status fbrl_num_parse(const char *s, size_t len, double *out)
{
    char dig[NUM_SIG_MAX];
    size_t i = 0;
    int nd = 0, neg = 0, sticky = 0, mant = 0;
    long e10 = 0, ev = 0;
    if (!s || !out)
        return FBRL_EINVAL;
    if (i < len && (s[i] == '+' || s[i] == '-'))
        neg = s[i++] == '-';
    for (; i < len && is_dig(s[i]); i++, mant++) {
        if (nd == 0 && s[i] == '0')
            continue;
        if (nd < NUM_SIG_MAX)
            dig[nd++] = s[i];
        else {
            e10 += e10 < NUM_EXP_CAP;
            sticky |= s[i] != '0';
        }
    }
    if (i < len && s[i] == '.') {
        for (i++; i < len && is_dig(s[i]); i++, mant++) {
            if (nd == 0 && s[i] == '0') {
                e10 -= e10 > -NUM_EXP_CAP;
                continue;
            }
            if (nd < NUM_SIG_MAX) {
                dig[nd++] = s[i];
                e10 -= e10 > -NUM_EXP_CAP;
            } else
                sticky |= s[i] != '0';
        }
    }
    if (!mant)
        return FBRL_ESYNTAX;
    if (i < len && (s[i] == 'e' || s[i] == 'E')) {
        int eneg = 0, edig = 0;
        i++;
        if (i < len && (s[i] == '+' || s[i] == '-'))
            eneg = s[i++] == '-';
        for (; i < len && is_dig(s[i]); i++, edig++)
            if (ev < NUM_EXP_CAP)
                ev = ev * 10 + (s[i] - '0');
        if (!edig)
            return FBRL_ESYNTAX;
        e10 += eneg ? -ev : ev;
    }
    if (i != len)
        return FBRL_ESYNTAX;
    if (nd == 0) {
        *out = neg ? -0.0 : 0.0;
        return FBRL_OK;
    }
    /* Trailing zeros only make the integer bigger. */
    while (nd > 1 && dig[nd - 1] == '0') {
        nd--;
        e10++;
    }
    return decimal_to_double(dig, nd, e10, sticky, neg, out);
}

/* ---- printing ---- */

#define NUM_EXACT_MAX 800 /* a double has at most 767 significant decimal digits */

/* The complete decimal expansion of v (finite, > 0): v = 0.dig[0..nd) * 10^(*dexp). */
static int exact_digits(double v, char *dig, int *dexp)
{
    bn a;
    char chunk[NUM_EXACT_MAX / 9 + 2][9];
    int e, k = 0, nchunks = 0, nd = 0, i, j;
    uint64_t m = (uint64_t)ldexp(frexp(v, &e), DBL_MANT_DIG);
    e -= DBL_MANT_DIG;
    while (!(m & 1u)) {
        m >>= 1;
        e++;
    }
    bn_set(&a, m);
    if (e >= 0)
        bn_shl(&a, e);
    else {
        k = -e; /* m * 2^e = m * 5^k / 10^k */
        bn_mul_pow(&a, 5, 1220703125u, 13, k);
    }
    while (a.n) {
        uint32_t r = bn_div_small(&a, 1000000000u);
        for (j = 8; j >= 0; j--) {
            chunk[nchunks][j] = (char)('0' + r % 10);
            r /= 10;
        }
        nchunks++;
    }
    for (i = nchunks - 1; i >= 0; i--)
        for (j = 0; j < 9; j++)
            if (nd || chunk[i][j] != '0')
                dig[nd++] = chunk[i][j];
    *dexp = nd - k;
    return nd;
}

/* Keep the first n digits of dig (nd of them), rounding half to even on the exact
 * rest; a carry out of the first digit makes "1" and raises *dexp. Returns the new nd. */
static int round_at(char *dig, int nd, int n, int *dexp)
{
    int up, i;
    if (n >= nd)
        return nd;
    if (n < 0)
        return 0;
    if (dig[n] != '5')
        up = dig[n] > '5';
    else {
        up = n > 0 && ((dig[n - 1] - '0') & 1);
        for (i = n + 1; i < nd && !up; i++)
            up = dig[i] != '0';
    }
    nd = n;
    if (up) {
        for (i = n - 1; i >= 0 && dig[i] == '9'; i--)
            dig[i] = '0';
        if (i >= 0)
            dig[i]++;
        else {
            dig[0] = '1';
            nd = n > 0 ? n : 1;
            (*dexp)++;
        }
    }
    return nd;
}

typedef struct {
    char *buf;
    size_t size, len; /* len counts every character, also those that did not fit */
} sink;

static void put(sink *o, char c)
{
    if (o->len + 1 < o->size)
        o->buf[o->len] = c;
    o->len++;
}

static fbrl_status finish(sink *o, size_t *len)
{
    o->buf[o->len < o->size ? o->len : o->size - 1] = '\0';
    if (len)
        *len = o->len < o->size ? o->len : o->size - 1;
    return o->len < o->size ? FBRL_OK : FBRL_ENOSPC;
}

/* The body of a fixed-point number (no sign): digits of |v| rounded to `decimals`. */
static int fixed_body(double av, int decimals, char *out)
{
    char dig[NUM_EXACT_MAX + 2];
    int nd = 0, dexp = 0, k = 0, j;
    if (av != 0.0) {
        nd = exact_digits(av, dig, &dexp);
        nd = round_at(dig, nd, dexp + decimals, &dexp);
    }
    if (nd == 0)
        dexp = 0;
    if (dexp <= 0)
        out[k++] = '0';
    for (j = 0; j < dexp; j++)
        out[k++] = j < nd ? dig[j] : '0';
    if (decimals > 0) {
        out[k++] = '.';
        for (j = dexp; j < dexp + decimals; j++)
            out[k++] = j >= 0 && j < nd ? dig[j] : '0';
    }
    return k;
}

/* Sign, padding and body into o, as printf lays out a field of `width`. */
static void field(sink *o, int neg, unsigned flags, int width, const char *body, int blen, int zero_ok)
{
    int signlen = neg || (flags & FBRL_NUM_PLUS), pad = width - blen - signlen, i;
    if (!(zero_ok && (flags & FBRL_NUM_ZERO)))
        for (i = 0; i < pad; i++)
            put(o, ' ');
    if (signlen)
        put(o, neg ? '-' : '+');
    if (zero_ok && (flags & FBRL_NUM_ZERO))
        for (i = 0; i < pad; i++)
            put(o, '0');
    for (i = 0; i < blen; i++)
        put(o, body[i]);
}

fbrl_status fbrl_num_fixed(char *buf, size_t size, double v, int width, int decimals, unsigned flags,
                           size_t *len)
{
    char body[DBL_MAX_10_EXP + FBRL_NUM_DECIMALS_MAX + 4];
    sink o;
    if (!buf || size == 0)
        return FBRL_EINVAL;
    buf[0] = '\0';
    if (decimals < 0 || decimals > FBRL_NUM_DECIMALS_MAX || width < 0)
        return FBRL_ERANGE;
    o.buf = buf;
    o.size = size;
    o.len = 0;
    if (isnan(v))
        field(&o, 0, flags & ~FBRL_NUM_PLUS, width, "nan", 3, 0);
    else if (isinf(v))
        field(&o, v < 0, flags, width, "inf", 3, 0);
    else
        field(&o, signbit(v) != 0, flags, width, body, fixed_body(fabs(v), decimals, body), 1);
    return finish(&o, len);
}

fbrl_status fbrl_num_digits(double v, int ndig, char *digits, int *exp10)
{
    char dig[NUM_EXACT_MAX + 2];
    int nd, dexp, i;
    if (!digits || !exp10)
        return FBRL_EINVAL;
    if (ndig < 1 || ndig > FBRL_NUM_DIGITS_MAX)
        return FBRL_ERANGE;
    if (!isfinite(v))
        return FBRL_ENONFINITE;
    if (v == 0.0) {
        memset(digits, '0', (size_t)ndig);
        *exp10 = 0;
        return FBRL_OK;
    }
    nd = exact_digits(fabs(v), dig, &dexp);
    nd = round_at(dig, nd, ndig, &dexp);
    for (i = 0; i < ndig; i++)
        digits[i] = i < nd ? dig[i] : '0';
    *exp10 = dexp - 1;
    return FBRL_OK;
}

fbrl_status fbrl_num_general(char *buf, size_t size, double v, int prec, size_t *len)
{
    char dig[FBRL_NUM_DIGITS_MAX], body[DBL_MAX_10_EXP + FBRL_NUM_DIGITS_MAX + 8];
    int x, k = 0, i;
    sink o;
    if (!buf || size == 0)
        return FBRL_EINVAL;
    buf[0] = '\0';
    if (prec < 1 || prec > FBRL_NUM_DIGITS_MAX)
        return FBRL_ERANGE;
    if (!isfinite(v))
        return fbrl_num_fixed(buf, size, v, 0, 0, 0, len);
    fbrl_num_digits(v, prec, dig, &x);
    if (x >= -4 && x < prec) { /* %f with prec - 1 - x decimals */
        k = fixed_body(fabs(v), prec - 1 - x, body);
    } else { /* %e with prec - 1 decimals */
        int ax = x < 0 ? -x : x, nexp = 0;
        char e[8];
        body[k++] = dig[0];
        if (prec > 1) {
            body[k++] = '.';
            for (i = 1; i < prec; i++)
                body[k++] = dig[i];
        }
        do {
            e[nexp++] = (char)('0' + ax % 10);
            ax /= 10;
        } while (ax);
        if (nexp < 2)
            e[nexp++] = '0';
        /* the exponent goes after the trimming below */
        {
            int t = k;
            if (memchr(body, '.', (size_t)t)) {
                while (body[t - 1] == '0')
                    t--;
                if (body[t - 1] == '.')
                    t--;
            }
            k = t;
        }
        body[k++] = 'e';
        body[k++] = x < 0 ? '-' : '+';
        while (nexp)
            body[k++] = e[--nexp];
        o.buf = buf;
        o.size = size;
        o.len = 0;
        field(&o, signbit(v) != 0, 0, 0, body, k, 0);
        return finish(&o, len);
    }
    if (memchr(body, '.', (size_t)k)) {
        while (body[k - 1] == '0')
            k--;
        if (body[k - 1] == '.')
            k--;
    }
    o.buf = buf;
    o.size = size;
    o.len = 0;
    field(&o, signbit(v) != 0, 0, 0, body, k, 0);
    return finish(&o, len);
}
