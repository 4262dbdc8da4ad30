/* SPDX-License-Identifier: MIT */
/* rapl_encode.c - the RAPL command table and the line encoder (no OS header). */
#include "fbrl/rapl_encode.h"

#define MOT   (FBRL_RAPL_F_MOTION | FBRL_RAPL_F_WAITS)
#define STR   FBRL_RAPL_F_STRAIGHT
#define STM   FBRL_RAPL_F_STREAM
#define WTS   FBRL_RAPL_F_WAITS
#define SAF   FBRL_RAPL_F_SAFE
#define NONE  FBRL_RAPL_REPLY_NONE
#define POS   FBRL_RAPL_REPLY_POS
#define LINES FBRL_RAPL_REPLY_LINES

/* The one command table, indexed by fbrl_rapl_cmd: every fact about a command lives
 * here (keyword, /NNN token, arguments, motion, waiting, safe to repeat, reply). Tokens
 * are the RAPL-II manual's /NNN numbers (DESIGN 5); 0 = none known. Safe to repeat (SAF)
 * is decided by what a second run does: not safe are relative motions (APPRO DEPART JOG
 * JOINT MI MOTOR), program runs, SHIFT(A) (adds to a location), the deletions (a second
 * one reports "undefined"), the commands that store where the arm is (HERE ACTUAL, XCAL
 * XZERO for the extra axis: a second run while it moves stores another place) and WAIT (a
 * second one waits again, for an input that may have come and gone). */
static const fbrl_rapl_cmdinfo table[FBRL_RAPL_NCMDS] = {
    [FBRL_RAPL_ACTUAL] = {"ACTUAL", 152, "L", 0, 0, NONE},
    [FBRL_RAPL_ALIGN] = {"ALIGN", 1, "", 0, MOT | SAF, NONE},
    [FBRL_RAPL_APPRO] = {"APPRO", 2, "LR", 0, MOT | STR, NONE},
    [FBRL_RAPL_ARM] = {"ARM", 142, "W", "ON|OFF", SAF, NONE},
    [FBRL_RAPL_CLOSE] = {"CLOSE", 38, "[I", 0, SAF, NONE},
    [FBRL_RAPL_CONFIG] = {"CONFIG", 110, "IIWIIWI", "N|E|O;N|X", SAF, NONE},
    [FBRL_RAPL_DEPART] = {"DEPART", 4, "R", 0, MOT | STR, NONE},
    [FBRL_RAPL_FINISH] = {"FINISH", 10, "", 0, WTS | SAF, NONE},
    [FBRL_RAPL_FLASH] = {"FLASH", 84, "[I", 0, SAF, NONE},
    [FBRL_RAPL_GAIN] = {"GAIN", 150, "I[R", 0, SAF, LINES},
    [FBRL_RAPL_GRIP] = {"GRIP", 39, "R[I", 0, SAF, NONE},
    [FBRL_RAPL_HALT] = {"HALT", 154, "", 0, SAF, NONE},
    [FBRL_RAPL_HERE] = {"HERE", 24, "L", 0, 0, NONE},
    [FBRL_RAPL_HOME] = {"HOME", 20, "", 0, MOT | SAF, NONE},
    [FBRL_RAPL_JOG] = {"JOG", 5, "RRR", 0, MOT, NONE},
    [FBRL_RAPL_JOINT] = {"JOINT", 6, "IR", 0, MOT, NONE},
    [FBRL_RAPL_LIMP] = {"LIMP", 7, "[I*", 0, SAF, NONE},
    [FBRL_RAPL_LOCK] = {"LOCK", 9, "I*", 0, SAF, NONE},
    [FBRL_RAPL_MA] = {"MA", 132, "RRRRR[R]", 0, MOT | STR | SAF, NONE},
    [FBRL_RAPL_MANUAL] = {"MANUAL", 45, "[W", "JOI|CYL", SAF, NONE},
    [FBRL_RAPL_MI] = {"MI", 131, "RRRRR[R]", 0, MOT | STR, NONE},
    [FBRL_RAPL_MOTOR] = {"MOTOR", 11, "II", 0, MOT, NONE},
    [FBRL_RAPL_MOVE] = {"MOVE", 0, "L", 0, MOT | STR | SAF, NONE},
    [FBRL_RAPL_NOFLASH] = {"NOFLASH", 0, "", 0, SAF, NONE},
    [FBRL_RAPL_NOHELP] = {"NOHELP", 0, "", 0, SAF, NONE},
    [FBRL_RAPL_NOLIMP] = {"NOLIMP", 0, "", 0, SAF, NONE},
    [FBRL_RAPL_NOMANUAL] = {"NOMANUAL", 0, "", 0, SAF, NONE},
    [FBRL_RAPL_NOTEACH] = {"NOTEACH", 0, "", 0, SAF, NONE},
    [FBRL_RAPL_OPEN] = {"OPEN", 40, "[I", 0, SAF, NONE},
    [FBRL_RAPL_OUTPUT] = {"OUTPUT", 89, "I*", 0, SAF, NONE},
    [FBRL_RAPL_POINT] = {"POINT", 50, "L", 0, SAF, NONE}, /* coordinates: see point_sig() */
    [FBRL_RAPL_READY] = {"READY", 15, "", 0, MOT | SAF, NONE},
    [FBRL_RAPL_RUN] = {"RUN", 109, "N[I", 0, WTS, NONE},
    [FBRL_RAPL_SERIAL] = {"SERIAL", 111, "", 0, SAF, LINES},
    [FBRL_RAPL_SET] = {"SET", 51, "L=L", 0, SAF, NONE},
    [FBRL_RAPL_SHIFTA] = {"SHIFTA", 53, "LL", 0, 0, NONE},
    [FBRL_RAPL_SPEED] = {"SPEED", 16, "I", 0, SAF, NONE},
    [FBRL_RAPL_STATUS] = {"STATUS", 25, "", 0, SAF, FBRL_RAPL_REPLY_STATUS},
    [FBRL_RAPL_TEACH] = {"TEACH", 44, "L", 0, SAF, NONE},
    [FBRL_RAPL_TOOL] = {"TOOL", 54, "[L", 0, SAF, NONE},
    [FBRL_RAPL_TYPEI] = {"TYPEI", 59, "V", 0, SAF, FBRL_RAPL_REPLY_INT},
    [FBRL_RAPL_TYPEV] = {"TYPEV", 60, "V", 0, SAF, FBRL_RAPL_REPLY_REAL},
    [FBRL_RAPL_UNLOCK] = {"UNLOCK", 17, "[I*", 0, SAF, NONE},
    [FBRL_RAPL_W0] = {"W0", 27, "", 0, SAF, POS},
    [FBRL_RAPL_W1] = {"W1", 29, "", 0, STM | SAF, FBRL_RAPL_REPLY_STREAM},
    [FBRL_RAPL_W2] = {"W2", 31, "", 0, SAF, POS},
    [FBRL_RAPL_W3] = {"W3", 33, "", 0, STM | SAF, FBRL_RAPL_REPLY_STREAM},
    [FBRL_RAPL_W4] = {"W4", 35, "", 0, SAF, POS},
    [FBRL_RAPL_W5] = {"W5", 37, "", 0, STM | SAF, FBRL_RAPL_REPLY_STREAM},
    [FBRL_RAPL_WAIT] = {"WAIT", 94, "I*", 0, WTS, NONE},
    [FBRL_RAPL_WE1] = {"WE1", 28, "", 0, STM | SAF, FBRL_RAPL_REPLY_STREAM},
    [FBRL_RAPL_WE3] = {"WE3", 32, "", 0, STM | SAF, FBRL_RAPL_REPLY_STREAM},
    [FBRL_RAPL_WE5] = {"WE5", 36, "", 0, STM | SAF, FBRL_RAPL_REPLY_STREAM},
    [FBRL_RAPL_XCAL] = {"XCAL", 157, "I", 0, 0, NONE},
    [FBRL_RAPL_XHOME] = {"XHOME", 158, "I", 0, SAF, NONE},
    [FBRL_RAPL_XZERO] = {"XZERO", 159, "I", 0, 0, NONE},
    /* a constant value; a raw line whose value reads its own target (V1=V1+1) is not safe */
    [FBRL_RAPL_ASSIGN] = {"", 0, "V=R", 0, SAF, NONE}, /* RAPL-II /070; fbrlsim: no token */
    [FBRL_RAPL_DLOCN] = {"DLOCN", 48, "L", 0, 0, NONE},
    [FBRL_RAPL_DVAR] = {"DVAR", 67, "V", 0, 0, NONE},
    [FBRL_RAPL_HELP] = {"HELP", 95, "", 0, SAF, NONE},
    [FBRL_RAPL_LISTL] = {"LISTL", 49, "[L", 0, SAF, LINES},
    [FBRL_RAPL_LISTV] = {"LISTV", 69, "[V", 0, SAF, LINES},
    [FBRL_RAPL_SHIFT] = {"SHIFT", 52, "LRRR", 0, 0, NONE},
    [FBRL_RAPL_TYPE] = {"TYPE", 58, "T", 0, SAF, LINES},
    [FBRL_RAPL_ENABLE] = {"ENABLE", 176, "W", "ARM", SAF, NONE},
    [FBRL_RAPL_DISABLE] = {"DISABLE", 177, "W", "ARM", SAF, NONE},
    [FBRL_RAPL_ONPOWER] = {"ONPOWER", 0, "", 0, WTS | SAF, NONE},
    /* the unit words are fbrlsim's choice [D]: no source names RAPL-II's */
    [FBRL_RAPL_METRIC] = {"METRIC", 0, "", 0, SAF, NONE},
    [FBRL_RAPL_NOMETRIC] = {"NOMETRIC", 0, "", 0, SAF, NONE},
};

#define MAX_REPEAT     8 /* arguments a '*' list may hold in all */
#define NAME_MAX_CHARS 8

const fbrl_rapl_cmdinfo *fbrl_rapl_cmd_info(fbrl_rapl_cmd cmd)
{
    if ((int)cmd < 0 || cmd >= FBRL_RAPL_NCMDS)
        return 0;
    return &table[cmd];
}

static char upper(char c) { return (c >= 'a' && c <= 'z') ? (char)(c - 'a' + 'A') : c; }
static int is_alpha(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
static int is_digit(char c) { return c >= '0' && c <= '9'; }

/* The command whose keyword is the n characters at s (case-insensitive, the whole span). */
static fbrl_status find_span(const char *s, size_t n, fbrl_rapl_cmd *cmd)
{
    for (int c = 0; c < FBRL_RAPL_NCMDS; c++) {
        const char *k = table[c].keyword;
        size_t i = 0;
        if (!*k)
            continue;
        while (i < n && k[i] && upper(s[i]) == k[i])
            i++;
        if (i == n && !k[i]) {
            *cmd = (fbrl_rapl_cmd)c;
            return FBRL_OK;
        }
    }
    return FBRL_ENOENT;
}

fbrl_status fbrl_rapl_cmd_find(const char *keyword, fbrl_rapl_cmd *cmd)
{
    size_t n = 0;
    if (!keyword || !cmd)
        return FBRL_EINVAL;
    while (keyword[n])
        n++;
    return find_span(keyword, n, cmd);
}

fbrl_status fbrl_rapl_line_cmd(const char *line, fbrl_rapl_cmd *cmd, const char **args)
{
    size_t n = 0;
    if (!line || !cmd)
        return FBRL_EINVAL;
    while (*line == ' ')
        line++;
    while (line[n] && line[n] != ' ' && line[n] != ',' && line[n] != '=')
        n++;
    const char *rest = line + n;
    while (*rest == ' ')
        rest++;
    if (args)
        *args = rest;
    if (*rest == '=' && n > 0) { /* checked before the keywords: GRIP=2 sets a variable */
        *cmd = FBRL_RAPL_ASSIGN;
        return FBRL_OK;
    }
    if (line[0] != '/')
        return find_span(line, n, cmd);
    unsigned tok = 0;
    for (size_t d = 1; d < n; d++) {
        if (!is_digit(line[d]) || tok > 999u)
            return FBRL_ENOENT;
        tok = tok * 10u + (unsigned)(line[d] - '0');
    }
    for (int c = 0; c < FBRL_RAPL_NCMDS && n > 1; c++)
        if (table[c].token && table[c].token == tok) {
            *cmd = (fbrl_rapl_cmd)c;
            return FBRL_OK;
        }
    return FBRL_ENOENT;
}

static int is_name_char(char c) { return is_alpha(c) || is_digit(c) || c == '_'; }

int fbrl_rapl_line_safe(const char *line)
{
    fbrl_rapl_cmd c;
    const char *eq = 0;
    if (fbrl_rapl_line_cmd(line, &c, &eq) != FBRL_OK)
        return 0;
    if (c != FBRL_RAPL_ASSIGN)
        return (fbrl_rapl_cmd_info(c)->flags & FBRL_RAPL_F_SAFE) != 0;
    /* NAME=value: safe unless the value names NAME (V1=V1+1 counts) */
    const char *name = line;
    while (*name == ' ')
        name++;
    size_t n = 0;
    while (is_name_char(name[n]))
        n++;
    if (n == 0)
        return 0;
    for (const char *p = eq + 1; *p; p++) {
        if (is_name_char(*p) && (p == eq + 1 || !is_name_char(p[-1]))) {
            size_t k = 0;
            while (k < n && is_name_char(p[k]) && upper(p[k]) == upper(name[k]))
                k++;
            if (k == n && !is_name_char(p[k]))
                return 0;
        }
    }
    return 1;
}

fbrl_status fbrl_rapl_name_check(const char *name, int hash_ok)
{
    if (!name)
        return FBRL_EINVAL;
    if (*name == '#') {
        if (!hash_ok)
            return FBRL_ENAME;
        name++;
    }
    if (!is_alpha(*name))
        return FBRL_ENAME;
    size_t n = 0;
    for (; name[n]; n++)
        if (n >= NAME_MAX_CHARS || !is_name_char(name[n]))
            return FBRL_ENAME;
    return FBRL_OK;
}

/* A bounded writer: every put checks the room, the first failure sticks. */
typedef struct out {
    char *buf;
    size_t cap, len; /* cap includes the NUL */
    fbrl_status st;
} out;

static void put(out *o, char c)
{
    if (o->st != FBRL_OK)
        return;
    if (o->len + 1 >= o->cap) {
        o->st = FBRL_ENOSPC;
        return;
    }
    o->buf[o->len++] = c;
}

static void puts_upper(out *o, const char *s)
{
    while (*s)
        put(o, upper(*s++));
}

static void put_uint(out *o, unsigned long long v, int min_digits)
{
    char d[24];
    int n = 0;
    do {
        d[n++] = (char)('0' + v % 10u);
        v /= 10u;
    } while (v || n < min_digits);
    while (n)
        put(o, d[--n]);
}

static void put_int(out *o, long v)
{
    if (v < 0) {
        put(o, '-');
        put_uint(o, (unsigned long long)(-(long long)v), 1);
    } else {
        put_uint(o, (unsigned long long)v, 1);
    }
}

static fbrl_status check_real(double v)
{
    if (v != v || v - v != 0.0) /* NaN, or infinity (inf - inf is NaN) */
        return FBRL_ENONFINITE;
    if (v > FBRL_RAPL_REAL_MAX || v < -FBRL_RAPL_REAL_MAX)
        return FBRL_ERANGE;
    return FBRL_OK;
}

/* The controller keeps four decimals (it prints %+09.4f, reference/rapl-research.md
 * 1.4): a real is rounded to that precision in fixed point (ten-thousandths, so the
 * text never depends on the locale or printf), then written as the shortest text with
 * that value: trailing zeros and a bare dot dropped ("2.5", "90", "-0.0125"). The
 * leading zero stays: no client shows a real controller reading ".5". */
#define REAL_SCALE 10000LL
typedef char
    real_scale_is_ten_to_the_decimals[REAL_SCALE == 10000LL && FBRL_RAPL_REAL_DECIMALS == 4 ? 1 : -1];
static void put_real(out *o, double v)
{
    double scaled = v * (double)REAL_SCALE;
    long long q = (long long)(scaled < 0 ? scaled - 0.5 : scaled + 0.5);
    if (q < 0) {
        put(o, '-');
        q = -q;
    }
    put_uint(o, (unsigned long long)(q / REAL_SCALE), 1);
    long long frac = q % REAL_SCALE;
    if (frac == 0)
        return;
    int digits = FBRL_RAPL_REAL_DECIMALS;
    while (frac % 10 == 0) {
        frac /= 10;
        digits--;
    }
    put(o, '.');
    put_uint(o, (unsigned long long)frac, digits);
}

fbrl_status fbrl_rapl_format_real(char *buf, size_t cap, size_t *len, double v)
{
    if (!buf || !len || cap == 0)
        return FBRL_EINVAL;
    fbrl_status st = check_real(v);
    if (st != FBRL_OK)
        return st;
    out o = {buf, cap, 0, FBRL_OK};
    put_real(&o, v);
    if (o.st != FBRL_OK)
        o.len = 0;
    buf[o.len] = '\0';
    *len = o.len;
    return o.st;
}

/* Is word one of the '|'-separated entries of list (case-insensitive)? The list ends at
 * NUL or ';' (the next W slot's list). */
static int word_allowed(const char *list, const char *word)
{
    while (list && *list && *list != ';') {
        const char *w = word;
        while (*list && *list != '|' && *list != ';' && *w && upper(*w) == *list) {
            list++;
            w++;
        }
        if (!*w && (!*list || *list == '|' || *list == ';'))
            return 1;
        while (*list && *list != '|' && *list != ';')
            list++;
        if (*list == '|')
            list++;
    }
    return 0;
}

/* Free text (TYPE): printable ASCII only, so it cannot end or edit the line. */
static int text_ok(const char *s)
{
    if (!s || !*s)
        return 0;
    for (; *s; s++)
        if (*s < 0x20 || *s > 0x7e)
            return 0;
    return 1;
}

/* Validate one argument against its signature kind. */
static fbrl_status check_arg(char kind, const fbrl_rapl_arg *a, const char *words)
{
    switch (kind) {
    case 'L':
    case 'V':
    case 'N':
        if (a->kind != FBRL_RAPL_ARG_STR)
            return FBRL_EINVAL;
        return fbrl_rapl_name_check(a->s, kind == 'L');
    case 'W':
        if (a->kind != FBRL_RAPL_ARG_STR || !a->s)
            return FBRL_EINVAL;
        return word_allowed(words, a->s) ? FBRL_OK : FBRL_ERANGE;
    case 'T': return a->kind == FBRL_RAPL_ARG_STR && text_ok(a->s) ? FBRL_OK : FBRL_EINVAL;
    case 'I':
        if (a->kind != FBRL_RAPL_ARG_INT)
            return FBRL_EINVAL;
        return (a->i > FBRL_RAPL_INT_MAX || a->i < -FBRL_RAPL_INT_MAX) ? FBRL_ERANGE : FBRL_OK;
    case 'R':
        if (a->kind == FBRL_RAPL_ARG_INT)
            return check_real((double)a->i);
        if (a->kind != FBRL_RAPL_ARG_REAL)
            return FBRL_EINVAL;
        return check_real(a->r);
    default: return FBRL_EINVAL;
    }
}

static void put_arg(out *o, char kind, const fbrl_rapl_arg *a)
{
    if (a->kind == FBRL_RAPL_ARG_STR)
        puts_upper(o, a->s);
    else if (a->kind == FBRL_RAPL_ARG_INT)
        kind == 'R' ? put_real(o, (double)a->i) : put_int(o, a->i);
    else
        put_real(o, a->r);
}

/* The signature spelled out: kind and '=' flag per slot, required and allowed counts. */
typedef struct sigdesc {
    char kind[MAX_REPEAT];
    char eq[MAX_REPEAT];
    size_t min, max;
} sigdesc;

static void sig_parse(const char *sig, sigdesc *d)
{
    size_t n = 0;
    int optional = 0, pending_eq = 0;
    d->min = 0;
    for (const char *p = sig; *p && n < MAX_REPEAT; p++) {
        if (*p == '[') {
            optional = 1;
        } else if (*p == '=') {
            pending_eq = 1;
        } else if (*p == '*') {
            while (n > 0 && n < MAX_REPEAT) {
                d->kind[n] = d->kind[n - 1];
                d->eq[n++] = 0;
            }
        } else {
            d->kind[n] = *p;
            d->eq[n++] = (char)pending_eq;
            pending_eq = 0;
            if (!optional)
                d->min = n;
        }
    }
    d->max = n;
}

static void encode_args(out *o, const sigdesc *d, const fbrl_rapl_arg *args, size_t nargs)
{
    for (size_t k = 0; k < nargs; k++) {
        put(o, k == 0 ? ' ' : (d->eq[k] ? '=' : ','));
        put_arg(o, d->kind[k], &args[k]);
    }
}

/* POINT name,x,y,z,yaw,pitch,roll or POINT #name,p1,...,pn: one pulse count per axis
 * (5 on the A255, 6 on the A465). */
static fbrl_status point_sig(const fbrl_rapl_arg *args, size_t nargs, sigdesc *d)
{
    if (nargs < 1 || args[0].kind != FBRL_RAPL_ARG_STR || !args[0].s)
        return FBRL_EINVAL;
    int precision = args[0].s[0] == '#';
    size_t n = precision ? 1 + FBRL_RAPL_ARM_AXES_MAX : 7;
    d->kind[0] = 'L';
    for (size_t k = 0; k < n; k++)
        d->eq[k] = 0;
    for (size_t k = 1; k < n; k++)
        d->kind[k] = precision ? 'I' : 'R';
    d->min = precision ? 1 + FBRL_RAPL_ARM_AXES_MIN : n;
    d->max = n;
    return FBRL_OK;
}

fbrl_status fbrl_rapl_encode(char *buf, size_t cap, size_t *len, fbrl_rapl_form form, fbrl_rapl_cmd cmd,
                             const fbrl_rapl_arg *args, size_t nargs, int straight)
{
    const fbrl_rapl_cmdinfo *ci = fbrl_rapl_cmd_info(cmd);
    if (!buf || !len || cap == 0 || !ci || (nargs && !args))
        return FBRL_EINVAL;
    if (form != FBRL_RAPL_KEYWORD && form != FBRL_RAPL_TOKEN)
        return FBRL_EINVAL;
    buf[0] = '\0';
    *len = 0;
    if (straight && !(ci->flags & FBRL_RAPL_F_STRAIGHT))
        return FBRL_EINVAL;

    sigdesc d;
    if (cmd == FBRL_RAPL_POINT) {
        fbrl_status st = point_sig(args, nargs, &d);
        if (st != FBRL_OK)
            return st;
    } else {
        sig_parse(ci->sig, &d);
    }
    if (nargs < d.min || nargs > d.max)
        return FBRL_EINVAL;
    const char *words = ci->words; /* the list of the next 'W' slot */
    for (size_t k = 0; k < nargs; k++) {
        fbrl_status st = check_arg(d.kind[k], &args[k], words);
        if (st != FBRL_OK)
            return st;
        if (d.kind[k] == 'W' && words) {
            while (*words && *words != ';')
                words++;
            if (*words == ';')
                words++;
        }
    }

    out o = {buf, cap, 0, FBRL_OK};
    if (form == FBRL_RAPL_TOKEN && ci->token) {
        put(&o, '/');
        put_uint(&o, ci->token, 3);
    } else {
        puts_upper(&o, ci->keyword);
    }
    if (cmd == FBRL_RAPL_ASSIGN && (form == FBRL_RAPL_KEYWORD || !ci->token)) {
        /* "NAME=value": no keyword, so no space before the first argument */
        puts_upper(&o, args[0].s);
        put(&o, '=');
        put_arg(&o, d.kind[1], &args[1]);
    } else {
        encode_args(&o, &d, args, nargs);
    }
    if (straight) {
        put(&o, ',');
        put(&o, 'S');
    }
    if (o.st != FBRL_OK) {
        buf[0] = '\0';
        return o.st;
    }
    buf[o.len] = '\0';
    *len = o.len;
    return FBRL_OK;
}
