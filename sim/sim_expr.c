/* SPDX-License-Identifier: MIT */
/* sim_expr.c - RAPL-II expressions: numbers, variables, + - * / and
 * parentheses, degree trigonometry, SIG/OSIG/ADC and GRIPPER. Errors are RAPL
 * codes (014 syntax, 010 undefined, 018 not a finite result). */
#include "sim_cmd.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

typedef struct expr {
    fbrl_sim *s;
    const char *p;
    int err;
} expr;

static double e_sum(expr *e);

static void e_space(expr *e)
{
    while (*e->p == ' ')
        e->p++;
}

static double e_io(expr *e, const int *bits, double n)
{
    long i = lround(n);
    if (e->err)
        return 0;
    if (i < 1 || i > SIM_IO) {
        e->err = SIM_E_IO_ADDRESS;
        return 0;
    }
    return bits[i - 1] ? 1.0 : 0.0;
}

/* ADC(n): analog input n in volts; a channel outside 1..8 is 024, as on the controller. */
static double e_adc(expr *e, double n)
{
    long i = lround(n);
    if (e->err)
        return 0;
    if (i < 1 || i > SIM_AIN) {
        e->err = SIM_E_AD_CHANNEL;
        return 0;
    }
    return e->s->dev.ain[i - 1];
}

static double e_primary(expr *e)
{
    e_space(e);
    if (isdigit((unsigned char)*e->p) || *e->p == '.') {
        const char *q = e->p;
        char num[64];
        size_t n;
        while (isdigit((unsigned char)*q))
            q++;
        if (*q == '.')
            q++;
        while (isdigit((unsigned char)*q))
            q++;
        if (q == e->p + 1 && *e->p == '.') {
            e->err = SIM_E_BAD_SYNTAX;
            return 0;
        }
        if (*q == 'E' && (isdigit((unsigned char)q[1]) ||
                          ((q[1] == '+' || q[1] == '-') && isdigit((unsigned char)q[2])))) {
            q += 2;
            while (isdigit((unsigned char)*q))
                q++;
        }
        n = (size_t)(q - e->p);
        if (n >= sizeof num) {
            e->err = SIM_E_BAD_SYNTAX;
            return 0;
        }
        memcpy(num, e->p, n);
        num[n] = 0;
        e->p = q;
        return strtod(num, NULL);
    }
    if (*e->p == '(') {
        double v;
        e->p++;
        v = e_sum(e);
        e_space(e);
        if (*e->p != ')') {
            if (!e->err)
                e->err = SIM_E_BAD_SYNTAX;
            return 0;
        }
        e->p++;
        return v;
    }
    if (isalpha((unsigned char)*e->p)) {
        char id[32];
        size_t n = 0;
        static const char *fn[] = {"SIN", "COS",  "TAN", "ASIN", "ACOS", "ATAN",
                                   "ABS", "SQRT", "INT", "SIG",  "OSIG", "ADC"};
        size_t i;
        while ((isalnum((unsigned char)*e->p) || *e->p == '_') && n < sizeof id - 1)
            id[n++] = *e->p++;
        id[n] = 0;
        e_space(e);
        for (i = 0; i < sizeof fn / sizeof fn[0]; i++) {
            double x, r = 0;
            if (strcmp(id, fn[i]) != 0)
                continue;
            if (*e->p != '(') {
                e->err = SIM_E_BAD_SYNTAX;
                return 0;
            }
            e->p++;
            x = e_sum(e);
            e_space(e);
            if (*e->p != ')') {
                if (!e->err)
                    e->err = SIM_E_BAD_SYNTAX;
                return 0;
            }
            e->p++;
            switch (i) {
            case 0: r = sin(x * PI / 180.0); break;
            case 1: r = cos(x * PI / 180.0); break;
            case 2: r = tan(x * PI / 180.0); break;
            case 3: r = asin(x) * 180.0 / PI; break;
            case 4: r = acos(x) * 180.0 / PI; break;
            case 5: r = atan(x) * 180.0 / PI; break;
            case 6: r = fabs(x); break;
            case 7: r = sqrt(x); break;
            case 8: r = trunc(x); break;
            case 9: return e_io(e, e->s->dev.in, x);
            case 10: return e_io(e, e->s->dev.out_, x);
            default: return e_adc(e, x);
            }
            if (!isfinite(r) && !e->err)
                e->err = SIM_E_ILLEGAL_ARG;
            return r;
        }
        if (!strcmp(id, "GRIPPER"))
            return e->s->dev.grip;
        {
            sim_var *v = strlen(id) <= SIM_NAME_MAX ? sim_var_find(e->s, id) : NULL;
            if (!v) {
                if (!e->err)
                    e->err = SIM_E_SYMBOL_UNDEFINED;
                return 0;
            }
            return v->v;
        }
    }
    if (!e->err)
        e->err = SIM_E_BAD_SYNTAX;
    return 0;
}

static double e_unary(expr *e)
{
    e_space(e);
    if (*e->p == '-') {
        e->p++;
        return -e_unary(e);
    }
    if (*e->p == '+') {
        e->p++;
        return e_unary(e);
    }
    return e_primary(e);
}

static double e_product(expr *e)
{
    double v = e_unary(e);
    for (;;) {
        e_space(e);
        if (*e->p == '*') {
            e->p++;
            v *= e_unary(e);
        } else if (*e->p == '/') {
            double d;
            e->p++;
            d = e_unary(e);
            if (d == 0.0) {
                if (!e->err)
                    e->err = SIM_E_ILLEGAL_ARG;
                return 0;
            }
            v /= d;
        } else {
            return v;
        }
    }
}

static double e_sum(expr *e)
{
    double v = e_product(e);
    for (;;) {
        e_space(e);
        if (*e->p == '+') {
            e->p++;
            v += e_product(e);
        } else if (*e->p == '-') {
            e->p++;
            v -= e_product(e);
        } else {
            return v;
        }
    }
}

/* Evaluates a whole expression text; 0 or an error code. */
int sim_eval(fbrl_sim *s, const char *text, double *v)
{
    expr e;
    e.s = s;
    e.p = text;
    e.err = 0;
    *v = e_sum(&e);
    e_space(&e);
    if (!e.err && *e.p)
        e.err = SIM_E_BAD_SYNTAX;
    if (!e.err && !isfinite(*v))
        e.err = SIM_E_ILLEGAL_ARG;
    return e.err;
}
