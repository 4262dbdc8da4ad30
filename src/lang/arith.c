/* arith.c - double-cell arithmetic (portable: half-cell products, shift-subtract
 * division) and conversions between doubles and floats. */
#include <math.h>
#include "words.h"

#define U(x) ((fbrl_ucell)(x))

void fbrl__dneg(fbrl_ucell *lo, fbrl_ucell *hi)
{
    *lo = ~*lo + 1;
    *hi = ~*hi + (*lo == 0);
}

/* ---- double-cell arithmetic (portable: half-cell products, shift-subtract division) ---- */
void fbrl__umul(fbrl_ucell a, fbrl_ucell b, fbrl_ucell *hi, fbrl_ucell *lo)
{
    const int hb = CELL_BITS / 2;
    const fbrl_ucell m = ((fbrl_ucell)1 << hb) - 1;
    fbrl_ucell a0 = a & m, a1 = a >> hb, b0 = b & m, b1 = b >> hb;
    fbrl_ucell p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    fbrl_ucell mid = (p00 >> hb) + (p01 & m) + (p10 & m);
    *lo = (p00 & m) | (mid << hb);
    *hi = p11 + (p01 >> hb) + (p10 >> hb) + (mid >> hb);
}

/* (hi:lo) / d with hi < d */
void fbrl__udiv(fbrl_ucell hi, fbrl_ucell lo, fbrl_ucell d, fbrl_ucell *q, fbrl_ucell *r)
{
    for (int i = 0; i < CELL_BITS; i++) {
        fbrl_ucell top = hi >> (CELL_BITS - 1);
        hi = (hi << 1) | (lo >> (CELL_BITS - 1));
        lo <<= 1;
        if (top || hi >= d) {
            hi -= d;
            lo |= 1;
        }
    }
    *q = lo;
    *r = hi;
}

void fbrl__mstar(fbrl_cell a, fbrl_cell b, fbrl_cell *lo, fbrl_cell *hi)
{
    fbrl_ucell ua = a < 0 ? 0 - U(a) : U(a), ub = b < 0 ? 0 - U(b) : U(b), h, l;
    fbrl__umul(ua, ub, &h, &l);
    if ((a < 0) != (b < 0))
        fbrl__dneg(&l, &h);
    *lo = (fbrl_cell)l;
    *hi = (fbrl_cell)h;
}

int fbrl__dsdiv(fbrl_cell lo, fbrl_cell hi, fbrl_cell n, int floored, fbrl_cell *q, fbrl_cell *r)
{
    if (n == 0)
        return FBRL_THROW_DIV_ZERO;
    fbrl_ucell l = U(lo), h = U(hi), un = n < 0 ? 0 - U(n) : U(n), uq, ur;
    int nd = hi < 0, nn = n < 0;
    if (nd)
        fbrl__dneg(&l, &h);
    if (h >= un)
        return FBRL_THROW_RESULT_RANGE;
    fbrl__udiv(h, l, un, &uq, &ur);
    const fbrl_ucell maxpos = (~(fbrl_ucell)0) >> 1;
    fbrl_cell qs, rs;
    if (nd != nn) {
        if (uq > maxpos + 1)
            return FBRL_THROW_RESULT_RANGE;
        qs = (fbrl_cell)(0 - uq);
    } else {
        if (uq > maxpos)
            return FBRL_THROW_RESULT_RANGE;
        qs = (fbrl_cell)uq;
    }
    rs = nd ? (fbrl_cell)(0 - ur) : (fbrl_cell)ur;
    if (floored && rs != 0 && ((rs < 0) != (n < 0))) {
        if (qs == (fbrl_cell)(maxpos + 1))
            return FBRL_THROW_RESULT_RANGE;
        qs--;
        rs = (fbrl_cell)(U(rs) + U(n));
    }
    *q = qs;
    *r = rs;
    return 0;
}

int fbrl__starslash(fbrl_cell a, fbrl_cell b, fbrl_cell c, fbrl_cell *q, fbrl_cell *r)
{
    fbrl_cell lo, hi;
    fbrl__mstar(a, b, &lo, &hi);
    return fbrl__dsdiv(lo, hi, c, 1, q, r);
}

int fbrl__mstarslash(fbrl_cell *lo, fbrl_cell *hi, fbrl_cell n, fbrl_cell div)
{
    if (div == 0)
        return FBRL_THROW_DIV_ZERO;
    if (div < 0)
        return FBRL_THROW_BAD_NUMBER;
    fbrl_ucell l = U(*lo), h = U(*hi), un = n < 0 ? 0 - U(n) : U(n), ud = U(div);
    int neg = (*hi < 0) != (n < 0);
    if (*hi < 0)
        fbrl__dneg(&l, &h);
    fbrl_ucell h1, l1, h2, l2, t0, t1, t2, q0, q1, r;
    fbrl__umul(l, un, &h1, &l1);
    fbrl__umul(h, un, &h2, &l2);
    t0 = l1;
    t1 = h1 + l2;
    t2 = h2 + (t1 < h1);
    if (t2 >= ud)
        return FBRL_THROW_RESULT_RANGE;
    fbrl__udiv(t2, t1, ud, &q1, &r);
    fbrl__udiv(r, t0, ud, &q0, &r);
    if (neg && r) {
        q0++;
        q1 += q0 == 0;
    }
    if (q1 >> (CELL_BITS - 1))
        return FBRL_THROW_RESULT_RANGE;
    if (neg)
        fbrl__dneg(&q0, &q1);
    *lo = (fbrl_cell)q0;
    *hi = (fbrl_cell)q1;
    return 0;
}

double fbrl__d_to_f(fbrl_cell lo, fbrl_cell hi)
{
    fbrl_ucell l = U(lo), h = U(hi);
    int neg = hi < 0;
    if (neg)
        fbrl__dneg(&l, &h); /* magnitude first: a negative sum would cancel to 0 */
    double r = (double)h * ldexp(1.0, CELL_BITS) + (double)l;
    return neg ? -r : r;
}

int fbrl__f_to_d(double r, fbrl_cell *lo, fbrl_cell *hi)
{
    double t = trunc(r), a = fabs(t), base = ldexp(1.0, CELL_BITS);
    if (!(a < base * base / 2))
        return FBRL_THROW_RESULT_RANGE;
    fbrl_ucell h = (fbrl_ucell)floor(a / base);
    fbrl_ucell l = (fbrl_ucell)(a - (double)h * base);
    if (t < 0)
        fbrl__dneg(&l, &h);
    *lo = (fbrl_cell)l;
    *hi = (fbrl_cell)h;
    return 0;
}
