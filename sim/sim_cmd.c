/* SPDX-License-Identifier: MIT */
/* sim_cmd.c - what a command line means: the command table (keyword, unique
 * prefix or /NNN token, flags, HELP hint, handler), variable assignment, the
 * common checks before a motion command, and RUN, which feeds a program's lines
 * back through the same dispatch. The handlers are in sim_h_*.c by group. */
#include "sim_cmd.h"
#include "fbrl/rapl_encode.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#define F_MOTION            1    /* waits for the previous motion; needs power, HOME, no LIMP */
#define F_RAW               2    /* takes the raw rest of the line */
#define F_TOP               4    /* only typed, not inside RUN */
#define RUN_STEPS_PER_SLICE 1000 /* program lines (and passes) RUN executes per event-loop slice */

static int exec_line(fbrl_sim *s, const char *text, int top, int *block);

static int run_continue(fbrl_sim *s, int *block)
{
    int budget = RUN_STEPS_PER_SLICE;
    while (s->run.left > 0) {
        if (budget-- <= 0) { /* a long RUN yields, so the event loop goes on (I/O, stop) */
            *block = 1;
            return 0;
        }
        while (s->run.pc < s->run.prog->n) {
            int b = 0, e;
            if (budget-- <= 0) {
                *block = 1;
                return 0;
            }
            e = exec_line(s, s->run.prog->lines[s->run.pc], 0, &b);
            if (b) {
                *block = 1;
                return 0;
            }
            s->run.pc++;
            if (e) {
                s->term.last_prog_line = s->run.pc; /* STATUS: where the program stopped, why */
                s->term.last_prog_err = e;
                s->run.prog = NULL;
                return e;
            }
        }
        s->term.last_prog_line = s->run.pc;
        s->run.pc = 0;
        s->run.left--;
    }
    s->run.prog = NULL;
    return 0;
}

int sim_h_run(fbrl_sim *s, args *a, int *b)
{
    char name[SIM_NAME_MAX + 1];
    long count = 1;
    int e = sim_args_want(a, 1, 2), i;
    if (e || (e = sim_name_parse(a->v[0], NULL, name)) || (a->n == 2 && (e = sim_arg_int(s, a, 1, &count))))
        return e;
    if (count < 1)
        return SIM_E_ILLEGAL_ARG;
    for (i = 0; i < s->mem.nprogs; i++)
        if (!strcmp(s->mem.progs[i].name, name))
            break;
    if (i == s->mem.nprogs)
        return SIM_E_PROGRAM_NOT_FOUND;
    s->run.prog = &s->mem.progs[i];
    snprintf(s->term.last_prog, sizeof s->term.last_prog, "%s", name);
    s->term.last_prog_line = 0;
    s->term.last_prog_err = -1;
    s->run.pc = 0;
    s->run.left = count;
    return run_continue(s, b);
}

typedef struct cmd {
    const char *name; /* its /NNN token: libfbrl's command table (rapl_encode.c) */
    int flags;
    const char *hint;
    handler fn;
} cmd;

static const cmd cmds[] = {
    {"ACTUAL", 0, "<LOC>", sim_h_here},
    {"ALIGN", F_MOTION, "", sim_h_align},
    {"APPRO", F_MOTION, "<LOC>,<DIST>[,S]", sim_h_appro},
    {"ARM", 0, "<ON|OFF>", sim_h_arm},
    {"CLOSE", 0, "[FORCE]", sim_h_close},
    {"CONFIG", 0, "<DEV#>,<BAUD>,<PARITY>,<#DATA>,<#STOP>,<HANDSHAKE>,<ECHO>", sim_h_config},
    {"DEPART", F_MOTION, "<DIST>[,S]", sim_h_depart},
    {"DIR", 0, "[1]", sim_h_dir},
    {"DISABLE", 0, "<ARM>", sim_h_disable},
    {"DLOCN", 0, "<LOC>", sim_h_dlocn},
    {"DVAR", 0, "<VAR>", sim_h_dvar},
    {"EDIT", F_TOP, "[PROG]", sim_h_edit},
    {"ENABLE", 0, "<ARM>", sim_h_enable},
    {"FINISH", 0, "", sim_h_finish},
    {"FLASH", 0, "[INTERVAL]", sim_h_flash},
    {"FREE", 0, "[1]", sim_h_free},
    {"GAIN", 0, "<MOTOR#>[,<P>[,<I>,<D>]]", sim_h_gain},
    {"GRIP", 0, "<DIST>[,FORCE]", sim_h_grip},
    {"HALT", 0, "", sim_h_halt},
    {"HELP", 0, "", sim_h_help},
    {"HERE", 0, "<LOC>", sim_h_here},
    {"HOME", 0, "", sim_h_home},
    {"JOG", F_MOTION, "<DX>,<DY>,<DZ>", sim_h_jog},
    {"JOINT", F_MOTION, "<JOINT#>,<DEGREES>", sim_h_joint},
    {"LIMP", 0, "[AXIS#,...]", sim_h_limp},
    {"LISTL", 0, "[LOC]", sim_h_listl},
    {"LISTP", 0, "<PROG>[,0|1]", sim_h_listp},
    {"LISTV", 0, "[VAR]", sim_h_listv},
    {"LOCK", 0, "<JOINT#,...>", sim_h_lock},
    {"MA", F_MOTION, "<J1>,...,<JN>[,S]", sim_h_ma},
    {"MANUAL", 0, "[JOI|CYL]", sim_h_manual},
    {"METRIC", 0, "", sim_h_metric},
    {"MI", F_MOTION, "<J1>,...,<JN>[,S]", sim_h_mi},
    {"MOTOR", F_MOTION, "<MOTOR#>,<PULSES>", sim_h_motor},
    {"MOVE", F_MOTION, "<LOC>[,S]", sim_h_move},
    {"NOFLASH", 0, "", sim_h_noflash},
    {"NOHELP", 0, "", sim_h_nohelp},
    {"NOLIMP", 0, "", sim_h_nolimp},
    {"NOMANUAL", 0, "", sim_h_nomanual},
    {"NOMETRIC", 0, "", sim_h_nometric},
    {"NOTEACH", 0, "", sim_h_noteach},
    {"ONPOWER", 0, "", sim_h_onpower},
    {"OPEN", 0, "[FORCE]", sim_h_open},
    {"OUTPUT", 0, "<[-]OUT#,...>", sim_h_output},
    {"POINT", 0, "<LOC>,<X>,<Y>,<Z>,<YAW>,<PITCH>,<ROLL>", sim_h_point},
    {"READY", F_MOTION, "", sim_h_ready},
    {"RUN", F_TOP, "<PROG>[,<COUNT>]", sim_h_run},
    {"SERIAL", 0, "", sim_h_serial},
    {"SET", F_RAW, "<LOC1>=<LOC2>", sim_h_set},
    {"SHIFT", 0, "<LOC>,<DX>,<DY>,<DZ>", sim_h_shift},
    {"SHIFTA", F_RAW, "<LOC1>,<LOC2>", sim_h_shifta},
    {"SPEED", 0, "<PERCENT>", sim_h_speed},
    {"STATUS", 0, "", sim_h_status},
    {"TEACH", 0, "<NAME>", sim_h_teach},
    {"TOOL", 0, "[LOC]", sim_h_tool},
    {"TYPE", F_RAW, "<TEXT>", sim_h_type},
    {"TYPEI", F_RAW, "<EXPR>", sim_h_typei},
    {"TYPEV", F_RAW, "<EXPR>", sim_h_typev},
    {"UNLOCK", 0, "[JOINT#,...]", sim_h_unlock},
    {"W0", 0, "", sim_h_w0},
    {"W1", F_TOP, "", sim_h_w1},
    {"W2", 0, "", sim_h_w2},
    {"W3", F_TOP, "", sim_h_w3},
    {"W4", 0, "", sim_h_w4},
    {"W5", F_TOP, "", sim_h_w5},
    {"WAIT", 0, "<[-]IN#,...>", sim_h_wait},
    {"WE1", F_TOP, "", sim_h_we1},
    {"WE3", F_TOP, "", sim_h_we3},
    {"WE5", F_TOP, "", sim_h_we5},
    {"XCAL", 0, "<AXIS#>", sim_h_xcal},
    {"XHOME", 0, "<AXIS#>", sim_h_xhome},
    {"XZERO", 0, "<AXIS#>", sim_h_xzero},
};

#define NCMDS ((int)(sizeof cmds / sizeof cmds[0]))

/* Finds a command by keyword, unique prefix or /NNN token; 0 or 12/50. */
static int lookup(const char *word, const cmd **out)
{
    int i, found = -1, count = 0;
    size_t n = strlen(word);
    if (word[0] == '/') {
        int t;
        if (n != 4 || !isdigit((unsigned char)word[1]) || !isdigit((unsigned char)word[2]) ||
            !isdigit((unsigned char)word[3]))
            return SIM_E_COMMAND;
        t = atoi(word + 1);
        /* the numbers are the library's: one table for the host and the emulator */
        for (i = 0; i < FBRL_RAPL_NCMDS; i++) {
            const fbrl_rapl_cmdinfo *ci = fbrl_rapl_cmd_info((fbrl_rapl_cmd)i);
            int k;
            if (!ci->token || ci->token != t)
                continue;
            for (k = 0; k < NCMDS; k++)
                if (!strcmp(cmds[k].name, ci->keyword)) {
                    *out = &cmds[k];
                    return 0;
                }
        }
        return SIM_E_COMMAND;
    }
    if (!n)
        return SIM_E_COMMAND;
    for (i = 0; i < NCMDS; i++) {
        if (!strcmp(cmds[i].name, word)) {
            *out = &cmds[i];
            return 0;
        }
        if (!strncmp(cmds[i].name, word, n)) {
            found = i;
            count++;
        }
    }
    if (count == 1) {
        *out = &cmds[found];
        return 0;
    }
    return count ? SIM_E_AMBIGUOUS : SIM_E_COMMAND;
}

const char *sim_help_hint(const char *word)
{
    const cmd *c;
    return lookup(word, &c) == 0 ? c->hint : NULL;
}

static int assign(fbrl_sim *s, const char *text)
{
    char name[SIM_NAME_MAX + 1], tok[SIM_LINE_MAX + 1];
    const char *eq = strchr(text, '=');
    size_t n = (size_t)(eq - text);
    double v;
    int e;
    sim_var *var;
    while (n && text[n - 1] == ' ')
        n--;
    memcpy(tok, text, n);
    tok[n] = 0;
    if ((e = sim_name_parse(tok, NULL, name)) || (e = sim_eval(s, eq + 1, &v)))
        return e;
    var = sim_var_find(s, name);
    if (!var) {
        if (s->mem.nvars == SIM_MAX_VARS)
            return SIM_E_TABLE_FULL;
        var = &s->mem.vars[s->mem.nvars++];
        strcpy(var->name, name);
    }
    var->v = v;
    s->dirty = 1;
    return 0;
}

static int exec_line(fbrl_sim *s, const char *text, int top, int *block)
{
    char word[SIM_LINE_MAX + 1];
    const char *p = text, *w;
    const cmd *c;
    args a;
    size_t n;
    int e;

    *block = 0;
    while (*p == ' ')
        p++;
    if (!*p)
        return 0;
    w = p;
    while (*p && *p != ' ' && *p != ',' && *p != '=')
        p++;
    n = (size_t)(p - w);
    memcpy(word, w, n);
    word[n] = 0;
    {
        const char *q = p;
        while (*q == ' ')
            q++;
        if (*q == '=' && word[0] != '/')
            return assign(s, w);
    }
    if ((e = lookup(word, &c)))
        return e;
    if ((c->flags & F_TOP) && !top)
        return SIM_E_ILLEGAL_ARG;
    if ((e = sim_args_split(p, &a)) && !(c->flags & F_RAW))
        return e;
    a.rest = p;
    if (*a.rest == ',')
        a.rest++;
    if (c->flags & F_MOTION) {
        if (s->arm.moving || s->arm.xmoving) {
            *block = 1;
            return 0;
        }
        if (!s->arm.power)
            return SIM_E_POWER_OFF;
        if (!s->arm.homed)
            return SIM_E_NOT_HOMED;
        for (n = 0; n < (size_t)sim_naxes(s); n++)
            if (s->arm.limp[n])
                return SIM_E_ILLEGAL_ARG;
    }
    return c->fn(s, &a, block);
}

int sim_exec(fbrl_sim *s, const char *line, int *err)
{
    if (line != s->term.cur)
        snprintf(s->term.cur, sizeof s->term.cur, "%s", line);
    s->run.prog = NULL;
    return sim_exec_step(s, err);
}

int sim_exec_step(fbrl_sim *s, int *err)
{
    int block = 0, e;
    sim_arm_update(s);
    if (s->arm.collide) { /* a motion met the cell: it answers when the arm stands */
        if (s->arm.moving)
            return EXEC_BLOCK;
        s->arm.collide = 0;
        *err = SIM_E_COLLISION;
        return EXEC_DONE;
    }
    e = s->run.prog ? run_continue(s, &block) : exec_line(s, s->term.cur, 1, &block);
    if (!e && !block && s->arm.collide && s->arm.moving)
        return EXEC_BLOCK;
    if (!e && !block && s->arm.collide) { /* met at once: stopped where it stood */
        s->arm.collide = 0;
        e = SIM_E_COLLISION;
    }
    if (block)
        return EXEC_BLOCK;
    *err = e ? e : -1;
    return EXEC_DONE;
}
