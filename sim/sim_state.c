/* SPDX-License-Identifier: MIT */
/* sim_state.c - the controller's battery-backed memory: a text state file.
 *
 * Saving writes a uniquely named temporary created exclusively and without
 * following links (a planted symlink cannot redirect the write), flushes it to
 * disk and renames it into place, so a crash never leaves a half-written file.
 * Loading is strict: every field is a whole token of the right kind and range,
 * and a bad line stops the emulator with "file:line: what" instead of being
 * half-read (and later overwritten). What the emulator saves it can load. */
#include "sim_internal.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define MAGIC      "FBRLSIM-STATE 1"
#define TMP_TRIES  100          /* unique temporary names tried before giving up */
#define MAX_FIELDS 16           /* tokens on one state line */
#define PULSE_MAX  9999999999.0 /* a precision point's pulses: ten digits, as POINT takes them */
#define BAUD_MAX   10000000L    /* --baud's range; CONFIG keeps to the controller's list */

/* Opens a new, uniquely named file next to path: O_EXCL refuses anything that
 * exists (a planted file or symlink), O_NOFOLLOW any link in the last step. */
static int open_temp(const char *path, char *tmp, size_t cap)
{
    static unsigned counter;
    int i;
    for (i = 0; i < TMP_TRIES; i++) {
        int fd;
        struct timespec ts;
        unsigned long r;
        clock_gettime(CLOCK_MONOTONIC, &ts);
        r = (unsigned long)getpid() * 2654435761UL ^ (unsigned long)ts.tv_nsec ^
            ((unsigned long)__atomic_fetch_add(&counter, 1u, __ATOMIC_RELAXED) << 20);
        if (snprintf(tmp, cap, "%s.%lx.tmp", path, r & 0xffffffffUL) >= (int)cap) {
            errno = ENAMETOOLONG;
            return -1;
        }
        fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd >= 0 || errno != EEXIST)
            return fd;
    }
    errno = EEXIST;
    return -1;
}

/* fsync of the directory that holds path, so the rename itself is on disk. */
static void sync_dir(const char *path)
{
    char dir[4096];
    const char *slash = strrchr(path, '/');
    int fd;
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else if (slash == path)
        snprintf(dir, sizeof dir, "/");
    else
        snprintf(dir, sizeof dir, "%.*s", (int)(slash - path), path);
    fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) {
        fsync(fd);
        close(fd);
    }
}

static void write_state(fbrl_sim *s, FILE *f)
{
    int i, j;
    double q[FBRL_ARM_AXES_MAX];
    /* A motion in progress is saved at its end point: the arm is on its way there. */
    memcpy(q, s->arm.moving ? s->arm.qt : s->arm.q, sizeof q);
    fprintf(f, "%s\n", MAGIC);
    fprintf(f, "MODEL %s\n", s->arm.model->name);
    fprintf(f, "SPEED %.17g\n", s->arm.speed);
    fprintf(f, "JOINTS");
    for (i = 0; i < sim_naxes(s); i++)
        fprintf(f, " %.17g", q[i]);
    fputc('\n', f);
    fprintf(f, "EXTRA %.17g %.17g\n", s->arm.xmoving ? s->arm.xtarget : s->arm.xpos, s->arm.xhome);
    fprintf(f, "GRIPPER %.17g %.17g\n", s->dev.grip, s->dev.grip_force);
    fprintf(f, "OUTPUTS ");
    for (i = 0; i < SIM_IO; i++)
        fputc(s->dev.out_[i] ? '1' : '0', f);
    fputc('\n', f);
    if (s->mem.tool_set)
        fprintf(f, "TOOL %s %.17g %.17g %.17g %.17g %.17g %.17g\n", s->mem.tool_name, s->mem.tool[0],
                s->mem.tool[1], s->mem.tool[2], s->mem.tool[3], s->mem.tool[4], s->mem.tool[5]);
    fprintf(f, "FLASH %d\n", s->dev.flash);
    fprintf(f, "UNITS %s\n", s->dev.metric ? "METRIC" : "INCH");
    for (i = 0; i < 2; i++)
        fprintf(f, "CONFIG %d %ld %c %d %d %c %d\n", i, s->dev.chan[i].baud, s->dev.chan[i].parity,
                s->dev.chan[i].data, s->dev.chan[i].stop, s->dev.chan[i].handshake, s->dev.chan[i].echo);
    for (i = 1; i <= sim_naxes(s); i++)
        fprintf(f, "GAIN %d %.17g %.17g %.17g\n", i, s->dev.gain[i][0], s->dev.gain[i][1], s->dev.gain[i][2]);
    for (i = 0; i < s->mem.nvars; i++)
        fprintf(f, "VAR %s %.17g\n", s->mem.vars[i].name, s->mem.vars[i].v);
    for (i = 0; i < s->mem.nlocs; i++) {
        const sim_loc *l = &s->mem.locs[i];
        if (l->precision) {
            fprintf(f, "PLOC %s", l->name);
            for (j = 0; j < sim_naxes(s); j++)
                fprintf(f, " %ld", l->p[j]);
            fputc('\n', f);
        } else {
            fprintf(f, "LOC %s %.17g %.17g %.17g %.17g %.17g %.17g\n", l->name, l->v[0], l->v[1], l->v[2],
                    l->v[3], l->v[4], l->v[5]);
        }
    }
    for (i = 0; i < s->mem.nprogs; i++) {
        fprintf(f, "PROGRAM %s\n", s->mem.progs[i].name);
        for (j = 0; j < s->mem.progs[i].n; j++)
            fprintf(f, "  %s\n", s->mem.progs[i].lines[j]);
        fprintf(f, "END\n");
    }
}

int sim_state_save(fbrl_sim *s)
{
    char tmp[4096];
    FILE *f;
    int fd, ok, saved;

    if (!s->state_path)
        return 0;
    fd = open_temp(s->state_path, tmp, sizeof tmp);
    if (fd < 0)
        return -1;
    f = fdopen(fd, "w");
    if (!f) {
        saved = errno;
        close(fd);
        unlink(tmp);
        errno = saved;
        return -1;
    }
    write_state(s, f);
    ok = fflush(f) == 0 && fsync(fileno(f)) == 0;
    ok = (fclose(f) == 0) && ok;
    if (!ok || rename(tmp, s->state_path) != 0) {
        saved = errno;
        unlink(tmp);
        errno = saved;
        return -1;
    }
    sync_dir(s->state_path);
    return 0;
}

/* ---- loading --------------------------------------------------------- */

typedef struct loader {
    fbrl_sim *s;
    const char *path;
    int lineno;
    char *err;
    size_t errlen;
    char *tok[MAX_FIELDS];
    int ntok;
    int items; /* items read so far (MODEL must come first) */
} loader;

static int bad(loader *ld, const char *what, const char *tok)
{
    if (tok)
        sim_seterr(ld->err, ld->errlen, "%s:%d: %s '%s'", ld->path, ld->lineno, what, tok);
    else
        sim_seterr(ld->err, ld->errlen, "%s:%d: %s", ld->path, ld->lineno, what);
    return -1;
}

/* The n-th field as a finite number in lo..hi, the whole token. */
static int real_field(loader *ld, int n, double lo, double hi, double *out)
{
    char *end;
    double d;
    errno = 0;
    d = strtod(ld->tok[n], &end);
    /* decimal only: strtod would also take hex, "nan" and "inf" */
    if (end == ld->tok[n] || *end || strspn(ld->tok[n], "0123456789+-.eE") != strlen(ld->tok[n]) ||
        !isfinite(d) || errno == ERANGE)
        return bad(ld, "not a finite number:", ld->tok[n]);
    if (d < lo || d > hi) {
        sim_seterr(ld->err, ld->errlen, "%s:%d: %s out of range %g..%g", ld->path, ld->lineno, ld->tok[n], lo,
                   hi);
        return -1;
    }
    *out = d;
    return 0;
}

/* The n-th field as a whole number in lo..hi (decimal digits with an optional sign). */
static int int_field(loader *ld, int n, long lo, long hi, long *out)
{
    char *end;
    long v;
    const char *t = ld->tok[n];
    if (!(isdigit((unsigned char)t[0]) || ((t[0] == '-' || t[0] == '+') && isdigit((unsigned char)t[1]))))
        return bad(ld, "not a whole number:", t);
    errno = 0;
    v = strtol(t, &end, 10);
    if (*end || errno == ERANGE)
        return bad(ld, "not a whole number in range:", t);
    if (v < lo || v > hi) {
        sim_seterr(ld->err, ld->errlen, "%s:%d: %s out of range %ld..%ld", ld->path, ld->lineno, t, lo, hi);
        return -1;
    }
    *out = v;
    return 0;
}

/* One character out of a set ("NEO"). */
static int char_field(loader *ld, int n, const char *set, char *out)
{
    const char *t = ld->tok[n];
    if (strlen(t) != 1 || !strchr(set, toupper((unsigned char)t[0])))
        return bad(ld, "expected one of the letters", t);
    *out = (char)toupper((unsigned char)t[0]);
    return 0;
}

/* A controller name: upper-cased, as the command line upper-cases what is typed. */
static int name_field(loader *ld, int n, char out[SIM_NAME_MAX + 1])
{
    const char *t = ld->tok[n];
    size_t i, len = strlen(t);
    if (len == 0 || len > SIM_NAME_MAX || !isalpha((unsigned char)t[0]))
        return bad(ld, "bad name", t);
    for (i = 0; i < len; i++) {
        if (!isalnum((unsigned char)t[i]) && t[i] != '_')
            return bad(ld, "bad name", t);
        out[i] = (char)toupper((unsigned char)t[i]);
    }
    out[len] = 0;
    return 0;
}

static int want_fields(loader *ld, int n)
{
    if (ld->ntok != n) {
        sim_seterr(ld->err, ld->errlen, "%s:%d: %s takes %d value%s, found %d", ld->path, ld->lineno,
                   ld->tok[0], n - 1, n == 2 ? "" : "s", ld->ntok - 1);
        return -1;
    }
    return 0;
}

static int split(loader *ld, char *line)
{
    char *p = line;
    ld->ntok = 0;
    for (;;) {
        while (*p == ' ' || *p == '\t')
            p++;
        if (!*p)
            return 0;
        if (ld->ntok == MAX_FIELDS)
            return bad(ld, "too many fields", NULL);
        ld->tok[ld->ntok++] = p;
        while (*p && *p != ' ' && *p != '\t')
            p++;
        if (*p)
            *p++ = 0;
    }
}

static int add_prog_line(loader *ld, sim_prog *p, const char *text)
{
    char **l;
    char *d;
    size_t n = strlen(text), i;
    if (n > SIM_LINE_MAX)
        return bad(ld, "program line longer than the controller's line", NULL);
    l = realloc(p->lines, (size_t)(p->n + 1) * sizeof *l);
    if (!l)
        return bad(ld, "out of memory", NULL);
    p->lines = l;
    d = malloc(n + 1);
    if (!d)
        return bad(ld, "out of memory", NULL);
    /* Upper case, as if typed: names in it (HERE p1) then match what is saved. */
    for (i = 0; i <= n; i++) {
        unsigned char c = (unsigned char)text[i];
        if (c && (c < 0x20 || c > 0x7e)) {
            free(d);
            return bad(ld, "program line holds a control character", NULL);
        }
        d[i] = (char)toupper(c);
    }
    p->lines[p->n++] = d;
    return 0;
}

static int dup_loc(fbrl_sim *s, const char *name, int prec)
{
    int i;
    for (i = 0; i < s->mem.nlocs; i++)
        if (s->mem.locs[i].precision == prec && !strcmp(s->mem.locs[i].name, name))
            return 1;
    return 0;
}

static int dup_var(fbrl_sim *s, const char *name)
{
    int i;
    for (i = 0; i < s->mem.nvars; i++)
        if (!strcmp(s->mem.vars[i].name, name))
            return 1;
    return 0;
}

/* One line of the memory outside a program; 0 or -1 (message set). */
static int load_item(loader *ld, sim_prog **prog)
{
    fbrl_sim *s = ld->s;
    const char *k = ld->tok[0];
    char name[SIM_NAME_MAX + 1];
    double d[8];
    long v[FBRL_ARM_AXES_MAX + 1];
    int i;

    if (!strcmp(k, "MODEL")) {
        const fbrl_arm *m;
        if (want_fields(ld, 2))
            return -1;
        if (ld->items > 0)
            return bad(ld, "MODEL must be the first item", NULL);
        if (!(m = fbrl_arm_find(ld->tok[1])))
            return bad(ld, "unknown arm model", ld->tok[1]);
        if (s->model_given && m != s->arm.model) {
            sim_seterr(ld->err, ld->errlen, "%s:%d: this memory belongs to an %s, not the %s of --model",
                       ld->path, ld->lineno, m->name, s->arm.model->name);
            return -1;
        }
        s->arm.model = m;
        sim_defaults(s); /* READY and gains of this arm */
    } else if (ld->items == 0 && s->arm.model != fbrl_arm_model(0)) {
        /* files from before models were kept hold an A255's memory */
        sim_seterr(ld->err, ld->errlen,
                   "%s:%d: no MODEL line: this memory belongs to an A255, not the %s of --model", ld->path,
                   ld->lineno, s->arm.model->name);
        return -1;
    } else if (!strcmp(k, "SPEED")) {
        /* SPEED takes any percentage above 0 up to 100: so does the file (it once
         * refused below 1e-9, so SPEED 50/111111111111 saved a file that did not load) */
        if (want_fields(ld, 2) || real_field(ld, 1, 0.0, 100.0, &d[0]))
            return -1;
        if (!(d[0] > 0.0))
            return bad(ld, "SPEED must be above 0, not", ld->tok[1]);
        s->arm.speed = d[0];
    } else if (!strcmp(k, "JOINTS")) {
        if (want_fields(ld, sim_naxes(s) + 1))
            return -1;
        for (i = 0; i < sim_naxes(s); i++)
            if (real_field(ld, i + 1, -360.0, 360.0, &d[i]))
                return -1;
        if (fbrl_arm_check(s->arm.model, d, &i) != FBRL_OK) {
            sim_seterr(ld->err, ld->errlen, "%s:%d: joint %d outside its limits", ld->path, ld->lineno,
                       i + 1);
            return -1;
        }
        memcpy(s->arm.q, d, sizeof s->arm.q);
        memcpy(s->arm.qt, d, sizeof s->arm.qt);
    } else if (!strcmp(k, "EXTRA")) {
        if (want_fields(ld, 3) || real_field(ld, 1, -PULSE_MAX, PULSE_MAX, &s->arm.xpos) ||
            real_field(ld, 2, -PULSE_MAX, PULSE_MAX, &s->arm.xhome))
            return -1;
    } else if (!strcmp(k, "GRIPPER")) {
        if (want_fields(ld, 3) || real_field(ld, 1, 0.0, SIM_GRIP_MAX, &s->dev.grip) ||
            real_field(ld, 2, 1.0, 100.0, &s->dev.grip_force))
            return -1;
    } else if (!strcmp(k, "OUTPUTS")) {
        if (want_fields(ld, 2))
            return -1;
        if (strlen(ld->tok[1]) != SIM_IO || strspn(ld->tok[1], "01") != SIM_IO)
            return bad(ld, "OUTPUTS needs 16 digits 0 or 1, not", ld->tok[1]);
        for (i = 0; i < SIM_IO; i++)
            s->dev.out_[i] = ld->tok[1][i] == '1';
    } else if (!strcmp(k, "TOOL")) {
        if (want_fields(ld, 8) || name_field(ld, 1, name))
            return -1;
        for (i = 0; i < 6; i++)
            if (real_field(ld, i + 2, -HUGE_VAL, HUGE_VAL, &d[i]))
                return -1;
        s->mem.tool_set = 1;
        strcpy(s->mem.tool_name, name);
        memcpy(s->mem.tool, d, sizeof s->mem.tool);
    } else if (!strcmp(k, "FLASH")) {
        if (want_fields(ld, 2) || int_field(ld, 1, 0, 1, &v[0]))
            return -1;
        s->dev.flash = (int)v[0];
    } else if (!strcmp(k, "UNITS")) {
        if (want_fields(ld, 2))
            return -1;
        if (strcmp(ld->tok[1], "METRIC") && strcmp(ld->tok[1], "INCH"))
            return bad(ld, "expected METRIC or INCH", ld->tok[1]);
        s->dev.metric = !strcmp(ld->tok[1], "METRIC");
    } else if (!strcmp(k, "CONFIG")) {
        sim_chan c;
        if (want_fields(ld, 8) || int_field(ld, 1, 0, 1, &v[0]) || int_field(ld, 2, 1, BAUD_MAX, &c.baud) ||
            char_field(ld, 3, "NEO", &c.parity) || int_field(ld, 4, 7, 8, &v[1]) ||
            int_field(ld, 5, 1, 2, &v[2]) || char_field(ld, 6, "NX", &c.handshake) ||
            int_field(ld, 7, 0, 1, &v[3]))
            return -1;
        c.data = (int)v[1];
        c.stop = (int)v[2];
        c.echo = (int)v[3];
        s->dev.chan[v[0]] = c;
    } else if (!strcmp(k, "GAIN")) { /* GAIN m p i d; an older file's GAIN m p keeps i and d */
        int n = ld->ntok == 3 ? 1 : SIM_GAIN_PARAMS;
        if (want_fields(ld, 2 + n) || int_field(ld, 1, 1, sim_naxes(s), &v[0]))
            return -1;
        for (i = 0; i < n; i++)
            if (real_field(ld, 2 + i, 0.0, HUGE_VAL, &d[i]))
                return -1;
        memcpy(s->dev.gain[v[0]], d, (size_t)n * sizeof d[0]);
    } else if (!strcmp(k, "VAR")) {
        if (want_fields(ld, 3) || name_field(ld, 1, name) || real_field(ld, 2, -HUGE_VAL, HUGE_VAL, &d[0]))
            return -1;
        if (dup_var(s, name))
            return bad(ld, "variable defined twice:", name);
        if (s->mem.nvars == SIM_MAX_VARS)
            return bad(ld, "too many variables", NULL);
        strcpy(s->mem.vars[s->mem.nvars].name, name);
        s->mem.vars[s->mem.nvars++].v = d[0];
    } else if (!strcmp(k, "PLOC") || !strcmp(k, "LOC")) {
        int prec = k[0] == 'P', need = prec ? sim_naxes(s) : 6;
        sim_loc *l;
        if (want_fields(ld, need + 2) || name_field(ld, 1, name))
            return -1;
        for (i = 0; i < need; i++)
            if (prec ? int_field(ld, i + 2, -(long)PULSE_MAX, (long)PULSE_MAX, &v[i])
                     : real_field(ld, i + 2, -HUGE_VAL, HUGE_VAL, &d[i]))
                return -1;
        if (dup_loc(s, name, prec))
            return bad(ld, "location defined twice:", name);
        if (s->mem.nlocs == SIM_MAX_LOCS)
            return bad(ld, "too many locations", NULL);
        l = &s->mem.locs[s->mem.nlocs++];
        memset(l, 0, sizeof *l);
        strcpy(l->name, name);
        l->precision = prec;
        for (i = 0; i < need; i++) {
            if (prec)
                l->p[i] = v[i];
            else
                l->v[i] = d[i];
        }
    } else if (!strcmp(k, "PROGRAM")) {
        sim_prog *np;
        if (want_fields(ld, 2) || name_field(ld, 1, name))
            return -1;
        for (i = 0; i < s->mem.nprogs; i++)
            if (!strcmp(s->mem.progs[i].name, name))
                return bad(ld, "program defined twice:", name);
        if (s->mem.nprogs == SIM_MAX_PROGS)
            return bad(ld, "too many programs (the program table holds 16)", NULL);
        np = realloc(s->mem.progs, (size_t)(s->mem.nprogs + 1) * sizeof *np);
        if (!np)
            return bad(ld, "out of memory", NULL);
        s->mem.progs = np;
        *prog = &s->mem.progs[s->mem.nprogs++];
        memset(*prog, 0, sizeof **prog);
        strcpy((*prog)->name, name);
    } else {
        return bad(ld, "unknown item", k);
    }
    return 0;
}

/* The line fgets just read held a NUL byte (it read more bytes than the string
 * has); *at is where the next line starts. Only where the file can tell. */
static int has_nul(FILE *f, const char *line, long *at)
{
    long next = ftell(f);
    int nul = *at >= 0 && next >= 0 && (size_t)(next - *at) != strlen(line);
    *at = next;
    return nul;
}

/* A program's END: the keyword in either case (as every keyword), alone on its line.
 * Anything else is a program line, upper-cased: "end" must not be saved as "END". */
static int is_end(const char *t)
{
    if (toupper((unsigned char)t[0]) != 'E' || toupper((unsigned char)t[1]) != 'N' ||
        toupper((unsigned char)t[2]) != 'D')
        return 0;
    return t[3 + strspn(t + 3, " \t")] == 0;
}

int sim_state_load(fbrl_sim *s, char *err, size_t errlen)
{
    FILE *f = fopen(s->state_path, "r");
    char line[512];
    sim_prog *prog = NULL;
    loader ld;
    long at;

    if (!f) {
        if (errno == ENOENT)
            return 0; /* a new controller: empty memory */
        sim_seterr(err, errlen, "%s: %s", s->state_path, strerror(errno));
        return -1;
    }
    memset(&ld, 0, sizeof ld);
    ld.s = s;
    ld.path = s->state_path;
    ld.err = err;
    ld.errlen = errlen;
    ld.lineno = 1;
    at = ftell(f);
    if (fgets(line, sizeof line, f) && !has_nul(f, line, &at))
        line[strcspn(line, "\r\n")] = 0;
    else
        line[0] = 0;
    if (strcmp(line, MAGIC) != 0) {
        sim_seterr(err, errlen, "%s:1: not an fbrlsim state file (first line must be '%s')", s->state_path,
                   MAGIC);
        fclose(f);
        return -1;
    }
    while (fgets(line, sizeof line, f)) {
        size_t n = strlen(line);
        int e = 0;
        ld.lineno++;
        if (has_nul(f, line, &at)) {
            bad(&ld, "a NUL byte in the line", NULL);
            fclose(f);
            return -1;
        }
        if (n == sizeof line - 1 && line[n - 1] != '\n') {
            bad(&ld, "line too long", NULL);
            fclose(f);
            return -1;
        }
        line[strcspn(line, "\r\n")] = 0;
        if (prog) {
            char *t = line;
            while (*t == ' ' || *t == '\t')
                t++;
            if (is_end(t))
                prog = NULL;
            else
                e = add_prog_line(&ld, prog, t);
        } else if (line[0] == '#') {
            continue;
        } else if ((e = split(&ld, line)) == 0 && ld.ntok > 0) {
            char *t;
            for (t = ld.tok[0]; *t; t++) /* keywords in either case, as commands */
                *t = (char)toupper((unsigned char)*t);
            e = load_item(&ld, &prog);
            ld.items++;
        }
        if (e) {
            fclose(f);
            return -1;
        }
    }
    fclose(f);
    if (prog) {
        sim_seterr(err, errlen, "%s:%d: PROGRAM %s has no END", s->state_path, ld.lineno, prog->name);
        return -1;
    }
    return 0;
}
