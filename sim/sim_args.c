/* SPDX-License-Identifier: MIT */
/* sim_args.c - a command line's arguments: split on commas and spaces, counted,
 * and read as numbers through the expression evaluator, as RAPL-II takes them. */
#include "sim_cmd.h"

#include "fbrl/units.h"

#include <math.h>
#include <string.h>

#define MM_PER_IN (FBRL_CM_PER_IN * 10.0) /* METRIC: the controller's lengths are millimetres */

/* Splits rest on commas and spaces; 0 or 14 (empty or too many arguments). */
int sim_args_split(const char *rest, args *a)
{
    char *p;
    a->n = 0;
    a->rest = rest;
    snprintf(a->buf, sizeof a->buf, "%s", rest);
    p = a->buf;
    while (*p == ' ')
        p++;
    if (*p == ',') /* "JOINT,1,5": a comma may end the command word */
        p++;
    for (;;) {
        while (*p == ' ')
            p++;
        if (!*p)
            return 0;
        if (*p == ',')
            return SIM_E_BAD_SYNTAX;
        if (a->n == MAXARGS)
            return SIM_E_BAD_SYNTAX;
        a->v[a->n++] = p;
        while (*p && *p != ' ' && *p != ',')
            p++;
        if (!*p)
            return 0;
        if (*p == ',') {
            *p++ = 0;
            while (*p == ' ')
                p++;
            if (!*p || *p == ',')
                return SIM_E_BAD_SYNTAX;
            continue;
        }
        *p++ = 0;
        while (*p == ' ')
            p++;
        if (*p == ',') {
            p++;
            while (*p == ' ')
                p++;
            if (!*p || *p == ',')
                return SIM_E_BAD_SYNTAX;
        }
    }
}

/* Removes a trailing ",S" argument; returns 1 if it was there. */
int sim_args_take_s(args *a, int need)
{
    if (a->n == need + 1 && !strcmp(a->v[a->n - 1], "S")) {
        a->n--;
        return 1;
    }
    return 0;
}

int sim_arg_num(fbrl_sim *s, args *a, int i, double *v)
{
    if (i >= a->n)
        return SIM_E_ARG_MISSING;
    return sim_eval(s, a->v[i], v);
}

int sim_arg_int(fbrl_sim *s, args *a, int i, long *v)
{
    double d;
    int e = sim_arg_num(s, a, i, &d);
    if (!e && fabs(d) > 1e12)
        e = SIM_E_ARG_TOO_BIG;
    if (!e)
        *v = lround(d);
    return e;
}

int sim_args_want(args *a, int lo, int hi)
{
    if (a->n < lo)
        return SIM_E_ARG_MISSING;
    if (a->n > hi)
        return SIM_E_BAD_SYNTAX;
    return 0;
}

/* A command without arguments that sets a mode flag (TEACH off, MANUAL off, HELP). */
int sim_arg_mode(args *a, int *flag, int on)
{
    int e = sim_args_want(a, 0, 0);
    if (!e)
        *flag = on;
    return e;
}

int sim_arg_axis(fbrl_sim *s, args *a, int i, int hi, long *ax)
{
    int e = sim_arg_int(s, a, i, ax);
    if (!e && (*ax < 1 || *ax > hi))
        e = SIM_E_BAD_AXIS;
    return e;
}

/* SET A=B and SHIFTA A,B take two names separated by '=' or ','. */
int sim_args_two_names(args *a, char *x, char *y)
{
    const char *r = a->rest, *sep;
    size_t n;
    while (*r == ' ')
        r++;
    sep = strpbrk(r, "=,");
    if (!*r)
        return SIM_E_ARG_MISSING;
    if (!sep)
        return a->n < 2   ? SIM_E_ARG_MISSING
               : a->n > 2 ? SIM_E_BAD_SYNTAX
                          : (strcpy(x, a->v[0]), strcpy(y, a->v[1]), 0);
    n = (size_t)(sep - r);
    while (n && r[n - 1] == ' ')
        n--;
    memcpy(x, r, n);
    x[n] = 0;
    sep++;
    while (*sep == ' ')
        sep++;
    strcpy(y, sep);
    n = strlen(y);
    while (n && y[n - 1] == ' ')
        y[--n] = 0;
    if (!*x || !*y)
        return SIM_E_ARG_MISSING;
    if (strpbrk(x, " =,") || strpbrk(y, " =,"))
        return SIM_E_BAD_SYNTAX;
    return 0;
}

/* Lengths: kept in inches inside; typed and shown in the controller's units (METRIC). */
double sim_len_out(const fbrl_sim *s, double inches) { return s->dev.metric ? inches * MM_PER_IN : inches; }

double sim_len_in(const fbrl_sim *s, double user) { return s->dev.metric ? user / MM_PER_IN : user; }

int sim_arg_len(fbrl_sim *s, args *a, int i, double *inches)
{
    double v;
    int e = sim_arg_num(s, a, i, &v);
    if (!e)
        *inches = sim_len_in(s, v);
    return e;
}
