/* SPDX-License-Identifier: MIT */
/* sim_h_mem.c - the commands that define, change, list and delete locations and
 * variables (HERE/ACTUAL, POINT, SET, SHIFT, SHIFTA, TOOL, LISTL, LISTV, DLOCN,
 * DVAR, TEACH). Everything they change is kept in the state file (dirty). */
#include "sim_cmd.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* HERE and ACTUAL: the emulated servo has no following error, so both are the same. */
int sim_h_here(fbrl_sim *s, args *a, int *b)
{
    char name[SIM_NAME_MAX + 1];
    double q[FBRL_ARM_AXES_MAX];
    int prec, e = sim_args_want(a, 1, 1), i;
    sim_loc *l;
    (void)b;
    if (e || (e = sim_name_parse(a->v[0], &prec, name)) || (e = sim_loc_new(s, name, prec, &l)))
        return e;
    sim_joints_now(s, q);
    if (prec)
        for (i = 0; i < sim_naxes(s); i++)
            l->p[i] = fbrl_arm_pulses(s->arm.model, i, q[i]);
    else
        fbrl_arm_fk(s->arm.model, q, sim_tool_len(s), l->v);
    return 0;
}

int sim_h_teach(fbrl_sim *s, args *a, int *b)
{
    char name[SIM_NAME_MAX + 1];
    int prec, e = sim_args_want(a, 1, 1);
    (void)b;
    if (e || (e = sim_name_parse(a->v[0], &prec, name)))
        return e;
    if (strlen(name) > SIM_NAME_MAX - 3)
        return SIM_E_ILLEGAL_ARG;
    s->mem.teach = 1 + prec; /* 2: precision points */
    strcpy(s->mem.teach_name, name);
    s->mem.teach_next = 1;
    return 0;
}

int sim_h_noteach(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return sim_arg_mode(a, &s->mem.teach, 0);
}

int sim_h_point(fbrl_sim *s, args *a, int *b)
{
    char name[SIM_NAME_MAX + 1];
    int prec, e, i, need;
    double v[6];
    sim_loc *l;
    (void)b;
    if (a->n < 1)
        return SIM_E_ARG_MISSING;
    if ((e = sim_name_parse(a->v[0], &prec, name)))
        return e;
    need = prec ? sim_naxes(s) : 6;
    if ((e = sim_args_want(a, need + 1, need + 1)))
        return e;
    for (i = 0; i < need; i++) {
        if ((e = !prec && i < 3 ? sim_arg_len(s, a, i + 1, &v[i]) : sim_arg_num(s, a, i + 1, &v[i])))
            return e;
        if (prec && fabs(v[i]) > 9999999999.0)
            return SIM_E_ARG_TOO_BIG;
    }
    if ((e = sim_loc_new(s, name, prec, &l)))
        return e;
    for (i = 0; i < need; i++) {
        if (prec)
            l->p[i] = lround(v[i]);
        else
            l->v[i] = v[i];
    }
    return 0;
}

int sim_h_set(fbrl_sim *s, args *a, int *b)
{
    char x[SIM_LINE_MAX + 1], y[SIM_LINE_MAX + 1], name[SIM_NAME_MAX + 1];
    double pose[6], q[FBRL_ARM_AXES_MAX];
    int prec, sprec, e, i;
    sim_loc *l;
    (void)b;
    if ((e = sim_args_two_names(a, x, y)) || (e = sim_name_parse(x, &prec, name)) ||
        (e = sim_loc_value(s, y, pose, q, &sprec)))
        return e;
    if (prec && !sprec) {
        if ((e = sim_arm_ik(s->arm.model, pose, sim_tool_len(s), s->arm.q, q)) ||
            (e = sim_arm_check(s->arm.model, q)))
            return e;
    }
    if ((e = sim_loc_new(s, name, prec, &l)))
        return e;
    if (prec)
        for (i = 0; i < sim_naxes(s); i++)
            l->p[i] = fbrl_arm_pulses(s->arm.model, i, q[i]);
    else
        memcpy(l->v, pose, sizeof pose);
    return 0;
}

int sim_h_shift(fbrl_sim *s, args *a, int *b)
{
    sim_loc *l;
    double d[3];
    int e = sim_args_want(a, 4, 4), i;
    (void)b;
    if (e || (e = sim_loc_cart(s, a->v[0], &l)))
        return e;
    for (i = 0; i < 3; i++)
        if ((e = sim_arg_len(s, a, i + 1, &d[i])))
            return e;
    for (i = 0; i < 3; i++)
        l->v[i] += d[i];
    s->dirty = 1;
    return 0;
}

int sim_h_shifta(fbrl_sim *s, args *a, int *b)
{
    char x[SIM_LINE_MAX + 1], y[SIM_LINE_MAX + 1];
    sim_loc *l, *m;
    int e, i;
    (void)b;
    if ((e = sim_args_two_names(a, x, y)) || (e = sim_loc_cart(s, x, &l)) || (e = sim_loc_cart(s, y, &m)))
        return e;
    for (i = 0; i < 6; i++)
        l->v[i] += m->v[i];
    s->dirty = 1;
    return 0;
}

int sim_h_tool(fbrl_sim *s, args *a, int *b)
{
    sim_loc *l;
    int e = sim_args_want(a, 0, 1), i;
    (void)b;
    if (e)
        return e;
    if (!a->n) {
        s->mem.tool_set = 0;
        memset(s->mem.tool, 0, sizeof s->mem.tool);
        s->dirty = 1;
        return 0;
    }
    if ((e = sim_loc_cart(s, a->v[0], &l)))
        return e;
    for (i = 0; i < 6; i++)
        if (i != 2 && l->v[i] != 0.0)
            return SIM_E_ILLEGAL_ARG;
    if (s->arm.moving)
        sim_halt(s); /* the joints stay; the tool point moves with the new tool */
    s->mem.tool_set = 1;
    strcpy(s->mem.tool_name, l->name);
    memcpy(s->mem.tool, l->v, sizeof s->mem.tool);
    s->dirty = 1;
    return 0;
}

static int cmp_loc(const void *x, const void *y)
{
    const sim_loc *a = x, *b = y;
    int c = strcmp(a->name, b->name);
    return c ? c : a->precision - b->precision;
}

static void print_loc(fbrl_sim *s, sim_out *o, const sim_loc *l)
{
    int i;
    if (l->precision) {
        char n[SIM_NAME_MAX + 2];
        snprintf(n, sizeof n, "#%s", l->name);
        sim_out_printf(o, "%-9s", n);
        for (i = 0; i < sim_naxes(s); i++)
            sim_out_printf(o, " %+011ld", l->p[i]);
    } else {
        sim_out_printf(o, "%-9s", l->name);
        for (i = 0; i < 6; i++)
            sim_out_printf(o, " %+09.4f", (i < 3 ? sim_len_out(s, l->v[i]) : l->v[i]) + 0.0);
    }
    sim_out_printf(o, "\r\n");
}

int sim_h_listl(fbrl_sim *s, args *a, int *b)
{
    int e = sim_args_want(a, 0, 1), i;
    (void)b;
    if (e)
        return e;
    if (a->n) {
        char name[SIM_NAME_MAX + 1];
        int prec;
        sim_loc *l;
        if ((e = sim_name_parse(a->v[0], &prec, name)))
            return e;
        if (!(l = sim_loc_find(s, name, prec)))
            return SIM_E_LOCATION_UNDEFINED;
        print_loc(s, &s->term.out, l);
        return 0;
    }
    qsort(s->mem.locs, (size_t)s->mem.nlocs, sizeof s->mem.locs[0], cmp_loc);
    for (i = 0; i < s->mem.nlocs; i++)
        print_loc(s, &s->term.out, &s->mem.locs[i]);
    return 0;
}

static int cmp_var(const void *x, const void *y)
{
    return strcmp(((const sim_var *)x)->name, ((const sim_var *)y)->name);
}

int sim_h_listv(fbrl_sim *s, args *a, int *b)
{
    int e = sim_args_want(a, 0, 1), i;
    (void)b;
    if (e)
        return e;
    if (a->n) {
        char name[SIM_NAME_MAX + 1];
        sim_var *v;
        if ((e = sim_name_parse(a->v[0], NULL, name)))
            return e;
        if (!(v = sim_var_find(s, name)))
            return SIM_E_SYMBOL_UNDEFINED;
        sim_out_printf(&s->term.out, "%-8s = %+.6f\r\n", v->name, v->v);
        return 0;
    }
    qsort(s->mem.vars, (size_t)s->mem.nvars, sizeof s->mem.vars[0], cmp_var);
    for (i = 0; i < s->mem.nvars; i++)
        sim_out_printf(&s->term.out, "%-8s = %+.6f\r\n", s->mem.vars[i].name, s->mem.vars[i].v);
    return 0;
}

int sim_h_dlocn(fbrl_sim *s, args *a, int *b)
{
    char name[SIM_NAME_MAX + 1];
    int prec, e = sim_args_want(a, 1, 1);
    sim_loc *l;
    (void)b;
    if (e || (e = sim_name_parse(a->v[0], &prec, name)))
        return e;
    if (!(l = sim_loc_find(s, name, prec)))
        return SIM_E_LOCATION_UNDEFINED;
    *l = s->mem.locs[--s->mem.nlocs];
    s->dirty = 1;
    return 0;
}

int sim_h_dvar(fbrl_sim *s, args *a, int *b)
{
    char name[SIM_NAME_MAX + 1];
    int e = sim_args_want(a, 1, 1);
    sim_var *v;
    (void)b;
    if (e || (e = sim_name_parse(a->v[0], NULL, name)))
        return e;
    if (!(v = sim_var_find(s, name)))
        return SIM_E_SYMBOL_UNDEFINED;
    *v = s->mem.vars[--s->mem.nvars];
    s->dirty = 1;
    return 0;
}
