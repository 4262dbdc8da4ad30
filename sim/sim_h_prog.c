/* SPDX-License-Identifier: MIT */
/* sim_h_prog.c - the controller's programs as a person at its terminal manages them
 * (a lab's steps, S11: "Programs are displayed, listed, etc using commands 'free', 'dir',
 * 'listp', 'edit', 'run'"): FREE (the memory's tables), DIR (the programs and their
 * size), LISTP (one program's lines), EDIT (the program that typed lines go into).
 * RAPL-II's S1 table says what each one does; no source shows their output, so the
 * layouts are fbrlsim's (docs/fbrlsim.md, "Behaviours and their evidence"). */
#include "sim_cmd.h"

#include <stdlib.h>
#include <string.h>

/* The optional device argument of FREE [1], DIR [1] and LISTP prog[,0|1] (S1): 0 the
 * terminal; 1 the printer, whose channel fbrlsim does not have (018 rather than output
 * that would go nowhere). */
static int to_terminal(fbrl_sim *s, args *a, int i)
{
    long dev;
    int e;
    if (i >= a->n)
        return 0;
    if ((e = sim_arg_int(s, a, i, &dev)))
        return e;
    return dev == 0 ? 0 : SIM_E_ILLEGAL_ARG;
}

static sim_prog *find(fbrl_sim *s, const char *name)
{
    for (int i = 0; i < s->mem.nprogs; i++)
        if (!strcmp(s->mem.progs[i].name, name))
            return &s->mem.progs[i];
    return NULL;
}

/* FREE [0|1]: each table of the memory, what is used of it */
int sim_h_free(fbrl_sim *s, args *a, int *b)
{
    int e = sim_args_want(a, 0, 1);
    (void)b;
    if (e || (e = to_terminal(s, a, 0)))
        return e;
    sim_out_printf(&s->term.out, "PROGRAMS  : %05d OF %05d\r\n", s->mem.nprogs, SIM_MAX_PROGS);
    sim_out_printf(&s->term.out, "VARIABLES : %05d OF %05d\r\n", s->mem.nvars, SIM_MAX_VARS);
    sim_out_printf(&s->term.out, "LOCATIONS : %05d OF %05d\r\n", s->mem.nlocs, SIM_MAX_LOCS);
    return 0;
}

static int cmp_prog(const void *x, const void *y)
{
    return strcmp((*(const sim_prog *const *)x)->name, (*(const sim_prog *const *)y)->name);
}

/* DIR [0|1]: each program, sorted by name, with its lines and bytes (a CR each); the
 * table itself keeps its order (RUN holds a place in it) */
int sim_h_dir(fbrl_sim *s, args *a, int *b)
{
    const sim_prog *sorted[SIM_MAX_PROGS];
    int e = sim_args_want(a, 0, 1), n = 0;
    (void)b;
    if (e || (e = to_terminal(s, a, 0)))
        return e;
    for (int i = 0; i < s->mem.nprogs && n < SIM_MAX_PROGS; i++)
        sorted[n++] = &s->mem.progs[i];
    qsort(sorted, (size_t)n, sizeof sorted[0], cmp_prog);
    for (int i = 0; i < n; i++) {
        size_t bytes = 0;
        for (int k = 0; k < sorted[i]->n; k++)
            bytes += strlen(sorted[i]->lines[k]) + 1;
        sim_out_printf(&s->term.out, "%-8s %05d LINES %05lu BYTES\r\n", sorted[i]->name, sorted[i]->n,
                       (unsigned long)bytes);
    }
    return 0;
}

/* LISTP prog[,0|1]: its lines, numbered as STATUS numbers a program's line (#00005) */
int sim_h_listp(fbrl_sim *s, args *a, int *b)
{
    char name[SIM_NAME_MAX + 1];
    const sim_prog *p;
    int e = sim_args_want(a, 1, 2);
    (void)b;
    if (e || (e = sim_name_parse(a->v[0], NULL, name)) || (e = to_terminal(s, a, 1)))
        return e;
    if (!(p = find(s, name)))
        return SIM_E_PROGRAM_NOT_FOUND;
    for (int k = 0; k < p->n; k++)
        sim_out_printf(&s->term.out, "#%05d %s\r\n", k + 1, p->lines[k]);
    return 0;
}

/* EDIT [prog]: prog (created when it does not exist, S1) is the program being edited;
 * the lines typed next are its next lines, kept and not run, until an empty line
 * (sim_prog_edit). Without a name: the program EDIT named before. */
int sim_h_edit(fbrl_sim *s, args *a, int *b)
{
    char name[SIM_NAME_MAX + 1];
    int e = sim_args_want(a, 0, 1);
    (void)b;
    if (e)
        return e;
    if (a->n == 0) {
        if (!s->term.edit_prog[0])
            return SIM_E_ARG_MISSING;
        snprintf(name, sizeof name, "%s", s->term.edit_prog);
    } else if ((e = sim_name_parse(a->v[0], NULL, name))) {
        return e;
    }
    if (!find(s, name)) {
        sim_prog *np;
        if (s->mem.nprogs >= SIM_MAX_PROGS)
            return SIM_E_TABLE_FULL;
        np = realloc(s->mem.progs, (size_t)(s->mem.nprogs + 1) * sizeof *np);
        if (!np)
            return SIM_E_NO_ROOM;
        s->mem.progs = np;
        np = &s->mem.progs[s->mem.nprogs++];
        memset(np, 0, sizeof *np);
        snprintf(np->name, sizeof np->name, "%s", name);
        s->dirty = 1;
    }
    snprintf(s->term.edit_prog, sizeof s->term.edit_prog, "%s", name);
    s->term.editing = 1;
    return 0;
}

/* A line typed in edit mode: an empty one ends the mode (0); any other is the edited
 * program's next line. Returns 0 or an error code (the line is then not kept). */
int sim_prog_edit(fbrl_sim *s, const char *line, int blank)
{
    sim_prog *p = find(s, s->term.edit_prog);
    char **nl, *copy;
    if (blank || !p) {
        s->term.editing = 0;
        return 0;
    }
    copy = malloc(strlen(line) + 1);
    nl = copy ? realloc(p->lines, (size_t)(p->n + 1) * sizeof *nl) : NULL;
    if (!nl) {
        free(copy);
        return SIM_E_NO_ROOM;
    }
    strcpy(copy, line);
    p->lines = nl;
    p->lines[p->n++] = copy;
    s->dirty = 1;
    return 0;
}
