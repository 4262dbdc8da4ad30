/* SPDX-License-Identifier: MIT */
/* sim_mem.c - the controller's memory of names: variables and locations (and
 * the programs the state file holds). Names enter it upper-cased. */
#include "sim_cmd.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

/* Checks a location or variable name; *prec gets the '#' flag (if prec). */
int sim_name_parse(const char *tok, int *prec, char name[SIM_NAME_MAX + 1])
{
    size_t i, n;
    int p = tok[0] == '#';
    if (p && !prec)
        return SIM_E_ILLEGAL_ARG;
    tok += p;
    n = strlen(tok);
    if (n == 0 || n > SIM_NAME_MAX || !isalpha((unsigned char)tok[0]))
        return SIM_E_ILLEGAL_ARG;
    for (i = 0; i < n; i++) {
        if (!isalnum((unsigned char)tok[i]) && tok[i] != '_')
            return SIM_E_ILLEGAL_ARG;
        /* upper case wherever a name enters memory (a program line is not typed) */
        name[i] = (char)toupper((unsigned char)tok[i]);
    }
    name[n] = 0;
    if (prec)
        *prec = p;
    return 0;
}

sim_var *sim_var_find(fbrl_sim *s, const char *name)
{
    int i;
    for (i = 0; i < s->mem.nvars; i++)
        if (!strcmp(s->mem.vars[i].name, name))
            return &s->mem.vars[i];
    return NULL;
}

sim_loc *sim_loc_find(fbrl_sim *s, const char *name, int prec)
{
    int i;
    for (i = 0; i < s->mem.nlocs; i++)
        if (s->mem.locs[i].precision == prec && !strcmp(s->mem.locs[i].name, name))
            return &s->mem.locs[i];
    return NULL;
}

int sim_loc_new(fbrl_sim *s, const char *name, int prec, sim_loc **out)
{
    sim_loc *l = sim_loc_find(s, name, prec);
    if (!l) {
        if (s->mem.nlocs == SIM_MAX_LOCS)
            return SIM_E_TABLE_FULL;
        l = &s->mem.locs[s->mem.nlocs++];
        memset(l, 0, sizeof *l);
        strcpy(l->name, name);
        l->precision = prec;
    }
    *out = l;
    s->dirty = 1;
    return 0;
}

int sim_loc_cart(fbrl_sim *s, const char *tok, sim_loc **out)
{
    char name[SIM_NAME_MAX + 1];
    int prec, e = sim_name_parse(tok, &prec, name);
    if (e)
        return e;
    if (prec)
        return SIM_E_PRECISION_POINT;
    if (!(*out = sim_loc_find(s, name, 0)))
        return SIM_E_LOCATION_UNDEFINED;
    return 0;
}

void sim_free_memory(fbrl_sim *s)
{
    int i, j;
    for (i = 0; i < s->mem.nprogs; i++) {
        for (j = 0; j < s->mem.progs[i].n; j++)
            free(s->mem.progs[i].lines[j]);
        free(s->mem.progs[i].lines);
    }
    free(s->mem.progs);
    s->mem.progs = NULL;
    s->mem.nprogs = 0;
}
