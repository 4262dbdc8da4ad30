/* sim_cmd.c - fbrlsim's command processor: the RAPL-II commands of
 * docs/rapl-commands.md, expressions, locations, the motion model, readouts
 * and the control lines. */
#include "sim_internal.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define NAXES FBRL_SIM_ARM_AXES
#define MAXARGS 12

/* ---- errors ---------------------------------------------------------- */

const char *sim_error_text(int code)
{
    static const struct { int code; const char *text; } t[] = {
        { 8, "ILLEGAL OPERAND" }, { 9, "END OF LINE NOT FOUND" }, { 10, "SYMBOL UNDEFINED" },
        { 11, "LOCATION UNDEFINED" }, { 12, "COMMAND ERROR" }, { 13, "ARGUMENT MISSING" },
        { 14, "BAD SYNTAX" }, { 15, "PRECISION POINT NOT LEGAL" }, { 16, "I/O ADDRESS ERROR" },
        { 17, "PROGRAM NOT FOUND" }, { 18, "ILLEGAL ARGUMENT" }, { 20, "ARGUMENT TOO BIG" },
        { 21, "NO ROOM LEFT" }, { 22, "TABLE FULL" }, { 24, "ILLEGAL A/D CHANNEL" },
        { 25, "LINE TOO LONG" },
        { 29, "TRANSFORM ILLEGAL" }, { 40, "ARM POWER HAS BEEN SWITCHED OFF" },
        { 41, "ROBOT HAS NOT BEEN HOMED" }, { 42, "JOINT #1 OUT OF RANGE" },
        { 43, "JOINT #2 OUT OF RANGE" }, { 44, "JOINT #3 OUT OF RANGE" },
        { 45, "JOINT #4 OUT OF RANGE" }, { 46, "JOINT #5 OUT OF RANGE" },
        { 47, "CHECKSUM FAILURE" }, { 50, "AMBIGUOUS COMMAND" }, { 61, "ILLEGAL CHANNEL" },
        { 65, "BAD AXIS NUMBER" }, { 66, "NOT AVAILABLE" }, { 68, "STRAIGHT LINE ERROR" },
    };
    size_t i;
    for (i = 0; i < sizeof t / sizeof t[0]; i++)
        if (t[i].code == code)
            return t[i].text;
    return "ERROR";
}

/* ---- output ---------------------------------------------------------- */

void sim_out_printf(sim_out *o, const char *fmt, ...)
{
    va_list ap;
    int n;
    va_start(ap, fmt);
    n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0)
        return;
    if (o->len + (size_t)n + 1 > o->cap) {
        size_t cap = (o->cap ? o->cap * 2 : 1024) + (size_t)n;
        char *b = realloc(o->buf, cap);
        if (!b)
            return;
        o->buf = b;
        o->cap = cap;
    }
    va_start(ap, fmt);
    vsnprintf(o->buf + o->len, o->cap - o->len, fmt, ap);
    va_end(ap);
    o->len += (size_t)n;
}

/* ---- arguments ------------------------------------------------------- */

typedef struct args {
    int n;
    char *v[MAXARGS];
    char buf[SIM_LINE_MAX + 1];
    const char *rest; /* raw text after the command word */
} args;

/* Splits rest on commas and spaces; 0 or 14 (empty or too many arguments). */
static int split_args(const char *rest, args *a)
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
            return 14;
        if (a->n == MAXARGS)
            return 14;
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
                return 14;
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
                return 14;
        }
    }
}

/* Removes a trailing ",S" argument; returns 1 if it was there. */
static int take_s(args *a, int need)
{
    if (a->n == need + 1 && !strcmp(a->v[a->n - 1], "S")) {
        a->n--;
        return 1;
    }
    return 0;
}

/* ---- names, variables, locations ------------------------------------- */

/* Checks a location or variable name; *prec gets the '#' flag (if prec). */
static int parse_name(const char *tok, int *prec, char name[SIM_NAME_MAX + 1])
{
    size_t i, n;
    int p = tok[0] == '#';
    if (p && !prec)
        return 18;
    tok += p;
    n = strlen(tok);
    if (n == 0 || n > SIM_NAME_MAX || !isalpha((unsigned char)tok[0]))
        return 18;
    for (i = 0; i < n; i++) {
        if (!isalnum((unsigned char)tok[i]) && tok[i] != '_')
            return 18;
        /* upper case wherever a name enters memory (a program line is not typed) */
        name[i] = (char)toupper((unsigned char)tok[i]);
    }
    name[n] = 0;
    if (prec)
        *prec = p;
    return 0;
}

static sim_var *find_var(fbrl_sim *s, const char *name)
{
    int i;
    for (i = 0; i < s->nvars; i++)
        if (!strcmp(s->vars[i].name, name))
            return &s->vars[i];
    return NULL;
}

static sim_loc *find_loc(fbrl_sim *s, const char *name, int prec)
{
    int i;
    for (i = 0; i < s->nlocs; i++)
        if (s->locs[i].precision == prec && !strcmp(s->locs[i].name, name))
            return &s->locs[i];
    return NULL;
}

static int new_loc(fbrl_sim *s, const char *name, int prec, sim_loc **out)
{
    sim_loc *l = find_loc(s, name, prec);
    if (!l) {
        if (s->nlocs == SIM_MAX_LOCS)
            return 22;
        l = &s->locs[s->nlocs++];
        memset(l, 0, sizeof *l);
        strcpy(l->name, name);
        l->precision = prec;
    }
    *out = l;
    s->dirty = 1;
    return 0;
}

static double tool_len(fbrl_sim *s)
{
    return s->tool_set ? s->tool[2] : 0.0;
}

static void pulses_to_joints(const long p[NAXES], double q[NAXES])
{
    int i;
    for (i = 0; i < NAXES; i++)
        q[i] = fbrl_sim_arm_degrees(i, p[i]);
}

/* Location by token: pose always; joints too for a precision point (*is_prec). */
static int loc_value(fbrl_sim *s, const char *tok, double pose[6], double q[NAXES], int *is_prec)
{
    char name[SIM_NAME_MAX + 1];
    int prec, e = parse_name(tok, &prec, name);
    sim_loc *l;
    if (e)
        return e;
    l = find_loc(s, name, prec);
    if (!l)
        return 11;
    *is_prec = prec;
    if (prec) {
        pulses_to_joints(l->p, q);
        fbrl_sim_arm_fk(q, tool_len(s), pose);
    } else {
        memcpy(pose, l->v, sizeof l->v);
    }
    return 0;
}

/* ---- expressions ----------------------------------------------------- */

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
        e->err = 16;
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
        e->err = 24;
        return 0;
    }
    return e->s->ain[i - 1];
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
            e->err = 14;
            return 0;
        }
        if (*q == 'E' && (isdigit((unsigned char)q[1])
                          || ((q[1] == '+' || q[1] == '-') && isdigit((unsigned char)q[2])))) {
            q += 2;
            while (isdigit((unsigned char)*q))
                q++;
        }
        n = (size_t)(q - e->p);
        if (n >= sizeof num) {
            e->err = 14;
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
                e->err = 14;
            return 0;
        }
        e->p++;
        return v;
    }
    if (isalpha((unsigned char)*e->p)) {
        char id[32];
        size_t n = 0;
        static const char *fn[] = { "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN",
                                    "ABS", "SQRT", "INT", "SIG", "OSIG", "ADC" };
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
                e->err = 14;
                return 0;
            }
            e->p++;
            x = e_sum(e);
            e_space(e);
            if (*e->p != ')') {
                if (!e->err)
                    e->err = 14;
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
            case 9: return e_io(e, e->s->in, x);
            case 10: return e_io(e, e->s->out_, x);
            default: return e_adc(e, x);
            }
            if (!isfinite(r) && !e->err)
                e->err = 18;
            return r;
        }
        if (!strcmp(id, "GRIPPER"))
            return e->s->grip;
        {
            sim_var *v = strlen(id) <= SIM_NAME_MAX ? find_var(e->s, id) : NULL;
            if (!v) {
                if (!e->err)
                    e->err = 10;
                return 0;
            }
            return v->v;
        }
    }
    if (!e->err)
        e->err = 14;
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
                    e->err = 18;
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
static int eval(fbrl_sim *s, const char *text, double *v)
{
    expr e;
    e.s = s;
    e.p = text;
    e.err = 0;
    *v = e_sum(&e);
    e_space(&e);
    if (!e.err && *e.p)
        e.err = 14;
    if (!e.err && !isfinite(*v))
        e.err = 18;
    return e.err;
}

static int num(fbrl_sim *s, args *a, int i, double *v)
{
    if (i >= a->n)
        return 13;
    return eval(s, a->v[i], v);
}

static int inum(fbrl_sim *s, args *a, int i, long *v)
{
    double d;
    int e = num(s, a, i, &d);
    if (!e && fabs(d) > 1e12)
        e = 20;
    if (!e)
        *v = lround(d);
    return e;
}

/* ---- the arm --------------------------------------------------------- */

void sim_joints_now(fbrl_sim *s, double q[NAXES])
{
    double f, pose[6];
    if (!s->moving) {
        memcpy(q, s->q, sizeof s->q);
        return;
    }
    f = (sim_now(s) - s->mt0) / (s->mt1 - s->mt0);
    if (f >= 1.0) {
        memcpy(q, s->qt, sizeof s->qt);
        return;
    }
    if (f < 0)
        f = 0;
    if (s->straight) {
        fbrl_sim_arm_lerp(s->pa, s->pb, f, pose);
        if (fbrl_sim_arm_ik(pose, tool_len(s), s->q[0], q) == 0)
            return;
    }
    {
        int i;
        for (i = 0; i < NAXES; i++)
            q[i] = s->q[i] + (s->qt[i] - s->q[i]) * f;
    }
}

static double extra_now(fbrl_sim *s)
{
    double f;
    if (!s->xmoving)
        return s->xpos;
    f = (sim_now(s) - s->xt0) / (s->xt1 - s->xt0);
    if (f >= 1.0)
        return s->xtarget;
    return s->xpos + (s->xtarget - s->xpos) * (f < 0 ? 0 : f);
}

void sim_arm_update(fbrl_sim *s)
{
    double now = sim_now(s);
    if (s->moving && now >= s->mt1) {
        memcpy(s->q, s->qt, sizeof s->q);
        s->moving = 0;
    }
    if (s->xmoving && now >= s->xt1) {
        s->xpos = s->xtarget;
        s->xmoving = 0;
    }
}

static void halt(fbrl_sim *s)
{
    double q[NAXES];
    sim_joints_now(s, q);
    memcpy(s->q, q, sizeof q);
    s->moving = 0;
    s->xpos = extra_now(s);
    s->xmoving = 0;
    s->dirty = 1;
}

static double joint_time(fbrl_sim *s, const double a[NAXES], const double b[NAXES])
{
    double t = 0;
    int i;
    for (i = 0; i < NAXES; i++) {
        double ti = fabs(b[i] - a[i]) / (fbrl_sim_arm_speed[i] * s->speed / 100.0);
        if (ti > t)
            t = ti;
    }
    return t;
}

static void begin(fbrl_sim *s, const double qt[NAXES], double t, int straight)
{
    memcpy(s->qt, qt, sizeof s->qt);
    s->straight = straight;
    s->mt0 = sim_now(s);
    s->mt1 = s->mt0 + t;
    s->moving = t > 0;
    if (!s->moving)
        memcpy(s->q, qt, sizeof s->q);
    s->dirty = 1;
}

/* Joint-interpolated move to joint angles; locked joints stay. */
static int move_joints(fbrl_sim *s, const double target[NAXES])
{
    double qt[NAXES];
    int i, e;
    for (i = 0; i < NAXES; i++)
        qt[i] = s->locked[i] ? s->q[i] : target[i];
    e = fbrl_sim_arm_check(qt);
    if (e)
        return e;
    begin(s, qt, joint_time(s, s->q, qt), 0);
    return 0;
}

static int pose_joints(fbrl_sim *s, const double pose[6], double q[NAXES])
{
    int e = fbrl_sim_arm_ik(pose, tool_len(s), s->q[0], q);
    return e ? e : fbrl_sim_arm_check(q);
}

/* Joint-interpolated move to a cartesian pose. */
static int move_pose(fbrl_sim *s, const double pose[6])
{
    double q[NAXES];
    int e = pose_joints(s, pose, q);
    return e ? e : move_joints(s, q);
}

/* Straight-line move to a pose (target joints qt if known, else from IK). */
static int move_line(fbrl_sim *s, const double pose[6], const double *qknown)
{
    double qt[NAXES], from[6], t, d;
    int e, i;
    if (qknown) {
        memcpy(qt, qknown, sizeof qt);
        e = fbrl_sim_arm_check(qt);
    } else {
        e = pose_joints(s, pose, qt);
    }
    if (e)
        return e;
    for (i = 0; i < NAXES; i++)
        if (s->locked[i] && fabs(qt[i] - s->q[i]) > 1e-9)
            return 68;
    fbrl_sim_arm_fk(s->q, tool_len(s), from);
    fbrl_sim_arm_fk(qt, tool_len(s), s->pb);
    if (fbrl_sim_arm_check_line(from, s->pb, tool_len(s), s->q[0]) != 0)
        return 68;
    {
        /* the line must end in the target's own configuration (a precision point may
         * hold the other reach) */
        double qe[NAXES];
        if (fbrl_sim_arm_ik(s->pb, tool_len(s), s->q[0], qe) != 0
            || fabs(fbrl_sim_arm_wrap(qe[0] - qt[0])) > 1e-6)
            return 68;
    }
    memcpy(s->pa, from, sizeof from);
    d = sqrt((s->pb[0] - from[0]) * (s->pb[0] - from[0]) + (s->pb[1] - from[1]) * (s->pb[1] - from[1])
             + (s->pb[2] - from[2]) * (s->pb[2] - from[2]));
    t = d / (FBRL_SIM_ARM_LINEAR * s->speed / 100.0);
    if (joint_time(s, s->q, qt) > t)
        t = joint_time(s, s->q, qt);
    begin(s, qt, t, 1);
    return 0;
}

static void current_pose(fbrl_sim *s, double pose[6])
{
    double q[NAXES];
    sim_joints_now(s, q);
    fbrl_sim_arm_fk(q, tool_len(s), pose);
}

/* The point dist back along a pose's tool axis. */
static void back_off(const double pose[6], double waist, double dist, double out[6])
{
    double w = (hypot(pose[0], pose[1]) > 1e-9 ? atan2(pose[1], pose[0]) : waist * PI / 180.0);
    double p = pose[4] * PI / 180.0;
    memcpy(out, pose, 6 * sizeof *out);
    out[0] -= dist * cos(p) * cos(w);
    out[1] -= dist * cos(p) * sin(w);
    out[2] -= dist * sin(p);
}

/* ---- command handlers ------------------------------------------------ */

typedef int (*handler)(fbrl_sim *s, args *a, int *block);

#define F_MOTION 1 /* waits for the previous motion; needs power, HOME, no LIMP */
#define F_RAW 2    /* takes the raw rest of the line */
#define F_TOP 4    /* only typed, not inside RUN */

static int want(args *a, int lo, int hi)
{
    if (a->n < lo)
        return 13;
    if (a->n > hi)
        return 14;
    return 0;
}

/* A command without arguments that sets a mode flag (TEACH off, MANUAL off, HELP). */
static int set_mode(args *a, int *flag, int on)
{
    int e = want(a, 0, 0);
    if (!e)
        *flag = on;
    return e;
}

static int h_align(fbrl_sim *s, args *a, int *b)
{
    double pose[6];
    int e = want(a, 0, 0);
    (void)b;
    if (e)
        return e;
    current_pose(s, pose);
    pose[4] = pose[4] < -45.0 ? -90.0 : pose[4] > 45.0 ? 90.0 : 0.0;
    return move_pose(s, pose);
}

static int h_appro(fbrl_sim *s, args *a, int *b)
{
    double pose[6], q[NAXES], t[6], d;
    int S = take_s(a, 2), prec, e = want(a, 2, 2);
    (void)b;
    if (e || (e = loc_value(s, a->v[0], pose, q, &prec)) || (e = num(s, a, 1, &d)))
        return e;
    back_off(pose, prec ? q[0] : s->q[0], d, t);
    return S ? move_line(s, t, NULL) : move_pose(s, t);
}

static int h_depart(fbrl_sim *s, args *a, int *b)
{
    double pose[6], t[6], d;
    int S = take_s(a, 1), e = want(a, 1, 1);
    (void)b;
    if (e || (e = num(s, a, 0, &d)))
        return e;
    current_pose(s, pose);
    back_off(pose, s->q[0], d, t);
    return S ? move_line(s, t, NULL) : move_pose(s, t);
}

static int h_move(fbrl_sim *s, args *a, int *b)
{
    double pose[6], q[NAXES];
    int S = take_s(a, 1), prec, e = want(a, 1, 1);
    (void)b;
    if (e || (e = loc_value(s, a->v[0], pose, q, &prec)))
        return e;
    if (S)
        return move_line(s, pose, prec ? q : NULL);
    return prec ? move_joints(s, q) : move_pose(s, pose);
}

static int h_jog(fbrl_sim *s, args *a, int *b)
{
    double pose[6], d[3];
    int i, e = want(a, 3, 3);
    (void)b;
    for (i = 0; !e && i < 3; i++)
        e = num(s, a, i, &d[i]);
    if (e)
        return e;
    current_pose(s, pose);
    for (i = 0; i < 3; i++)
        pose[i] += d[i];
    return move_line(s, pose, NULL);
}

static int axis_arg(fbrl_sim *s, args *a, int i, int hi, long *ax)
{
    int e = inum(s, a, i, ax);
    if (!e && (*ax < 1 || *ax > hi))
        e = 65;
    return e;
}

static int h_joint(fbrl_sim *s, args *a, int *b)
{
    double q[NAXES], d;
    long j;
    int e = want(a, 2, 2);
    (void)b;
    if (e || (e = axis_arg(s, a, 0, NAXES, &j)) || (e = num(s, a, 1, &d)))
        return e;
    memcpy(q, s->q, sizeof q);
    q[j - 1] += d;
    return move_joints(s, q);
}

static int h_motor(fbrl_sim *s, args *a, int *b)
{
    long m, p;
    int e;
    (void)b;
    if (a->n > 2)
        return 66;
    if ((e = want(a, 2, 2)) || (e = axis_arg(s, a, 0, NAXES + 1, &m)) || (e = inum(s, a, 1, &p)))
        return e;
    if (m == NAXES + 1) {
        s->xtarget = s->xpos + (double)p;
        s->xt0 = sim_now(s);
        s->xt1 = s->xt0 + fabs((double)p) / (SIM_EXTRA_RATE * s->speed / 100.0);
        s->xmoving = p != 0;
        s->dirty = 1;
        return 0;
    } else {
        double q[NAXES];
        memcpy(q, s->q, sizeof q);
        q[m - 1] += fbrl_sim_arm_degrees((int)m - 1, p);
        return move_joints(s, q);
    }
}

static int h_mi_ma(fbrl_sim *s, args *a, int rel)
{
    double q[NAXES], pose[6];
    int S = take_s(a, NAXES), e = want(a, NAXES, NAXES), i;
    for (i = 0; !e && i < NAXES; i++) {
        double r;
        e = num(s, a, i, &r);
        q[i] = (rel ? s->q[i] : 0.0) + r * 180.0 / PI;
    }
    if (e)
        return e;
    if (!S)
        return move_joints(s, q);
    if ((e = fbrl_sim_arm_check(q)))
        return e;
    fbrl_sim_arm_fk(q, tool_len(s), pose);
    return move_line(s, pose, q);
}

static int h_mi(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return h_mi_ma(s, a, 1);
}

static int h_ma(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return h_mi_ma(s, a, 0);
}

static int h_ready(fbrl_sim *s, args *a, int *b)
{
    int e = want(a, 0, 0);
    (void)b;
    if (e)
        return e;
    memset(s->locked, 0, sizeof s->locked);
    return move_joints(s, fbrl_sim_arm_ready);
}

static int h_finish(fbrl_sim *s, args *a, int *b)
{
    int e = want(a, 0, 0);
    if (!e && (s->moving || s->xmoving))
        *b = 1;
    return e;
}

static int h_halt(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    if (a->n)
        return 66;
    halt(s);
    return 0;
}

static int h_speed(fbrl_sim *s, args *a, int *b)
{
    double v;
    int e = want(a, 1, 1);
    (void)b;
    if (e || (e = num(s, a, 0, &v)))
        return e;
    if (v > 100.0)
        return 20;
    if (v <= 0.0)
        return 18;
    s->speed = v;
    s->dirty = 1;
    return 0;
}

static int h_home(fbrl_sim *s, args *a, int *b)
{
    int e = want(a, 0, 0);
    (void)b;
    if (e)
        return e;
    if (!s->power)
        return 40;
    s->homed = 1;
    return 0;
}

/* HERE and ACTUAL: the emulated servo has no following error, so both are the same. */
static int h_here(fbrl_sim *s, args *a, int *b)
{
    char name[SIM_NAME_MAX + 1];
    double q[NAXES];
    int prec, e = want(a, 1, 1), i;
    sim_loc *l;
    (void)b;
    if (e || (e = parse_name(a->v[0], &prec, name)) || (e = new_loc(s, name, prec, &l)))
        return e;
    sim_joints_now(s, q);
    if (prec)
        for (i = 0; i < NAXES; i++)
            l->p[i] = fbrl_sim_arm_pulses(i, q[i]);
    else
        fbrl_sim_arm_fk(q, tool_len(s), l->v);
    return 0;
}

/* Lists of axis numbers for LIMP, LOCK, UNLOCK: flags[i] = on. */
static int axis_list(fbrl_sim *s, args *a, int *flags, int on, int empty_all)
{
    int i, sel[NAXES] = { 0 };
    if (a->n == 0) {
        if (!empty_all)
            return 13;
        for (i = 0; i < NAXES; i++)
            sel[i] = 1;
    }
    for (i = 0; i < a->n; i++) {
        long ax;
        int e = axis_arg(s, a, i, NAXES, &ax);
        if (e)
            return e;
        sel[ax - 1] = 1;
    }
    for (i = 0; i < NAXES; i++)
        if (sel[i])
            flags[i] = on;
    return 0;
}

static int h_limp(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    if (s->moving)
        halt(s);
    return axis_list(s, a, s->limp, 1, 1);
}

static int h_nolimp(fbrl_sim *s, args *a, int *b)
{
    int e = want(a, 0, 0);
    (void)b;
    if (!e)
        memset(s->limp, 0, sizeof s->limp);
    return e;
}

static int h_lock(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return axis_list(s, a, s->locked, 1, 0);
}

static int h_unlock(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return axis_list(s, a, s->locked, 0, 1);
}

static int force_arg(fbrl_sim *s, args *a, int i)
{
    double f;
    int e;
    if (i >= a->n)
        return 0;
    if ((e = num(s, a, i, &f)))
        return e;
    if (f > 100.0)
        return 20;
    if (f < 1.0)
        return 18;
    s->grip_force = f;
    return 0;
}

/* Moves the gripper towards d; an object between the fingers stops it. */
static void grip_to(fbrl_sim *s, double d)
{
    if (s->object > 0 && d < s->object && s->grip >= s->object)
        d = s->object;
    s->grip = d;
    s->dirty = 1;
}

/* OPEN and CLOSE [force]: the gripper fully open or closed. */
static int open_close(fbrl_sim *s, args *a, double d)
{
    int e = want(a, 0, 1);
    if (e || (e = force_arg(s, a, 0)))
        return e;
    grip_to(s, d);
    return 0;
}

static int h_open(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return open_close(s, a, SIM_GRIP_MAX);
}

static int h_close(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return open_close(s, a, 0.0);
}

static int h_grip(fbrl_sim *s, args *a, int *b)
{
    double d;
    int e = want(a, 1, 2);
    (void)b;
    if (e || (e = num(s, a, 0, &d)))
        return e;
    if (d > SIM_GRIP_MAX)
        return 20;
    if (d < 0)
        return 18;
    if ((e = force_arg(s, a, 1)))
        return e;
    grip_to(s, d);
    return 0;
}

static int h_teach(fbrl_sim *s, args *a, int *b)
{
    char name[SIM_NAME_MAX + 1];
    int prec, e = want(a, 1, 1);
    (void)b;
    if (e || (e = parse_name(a->v[0], &prec, name)))
        return e;
    if (strlen(name) > SIM_NAME_MAX - 3)
        return 18;
    s->teach = 1 + prec; /* 2: precision points */
    strcpy(s->teach_name, name);
    s->teach_next = 1;
    return 0;
}

static int h_noteach(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return set_mode(a, &s->teach, 0);
}

static int h_manual(fbrl_sim *s, args *a, int *b)
{
    int e = want(a, 0, 1);
    (void)b;
    if (e)
        return e;
    if (a->n && strcmp(a->v[0], "JOI") && strcmp(a->v[0], "CYL"))
        return 18;
    s->manual = 1;
    return 0;
}

static int h_nomanual(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return set_mode(a, &s->manual, 0);
}

static int h_flash(fbrl_sim *s, args *a, int *b)
{
    double v;
    int e = want(a, 0, 1);
    (void)b;
    if (e || (a->n && (e = num(s, a, 0, &v))))
        return e;
    if (a->n && v < 0)
        return 18;
    s->flash = 1;
    s->dirty = 1;
    return 0;
}

static int h_noflash(fbrl_sim *s, args *a, int *b)
{
    int e = want(a, 0, 0);
    (void)b;
    if (!e) {
        s->flash = 0;
        s->dirty = 1;
    }
    return e;
}

static int h_nohelp(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return set_mode(a, &s->term.help, 0);
}

static int h_help(fbrl_sim *s, args *a, int *b)
{
    (void)b;
    return set_mode(a, &s->term.help, 1);
}

static int h_point(fbrl_sim *s, args *a, int *b)
{
    char name[SIM_NAME_MAX + 1];
    int prec, e, i, need;
    double v[6];
    sim_loc *l;
    (void)b;
    if (a->n < 1)
        return 13;
    if ((e = parse_name(a->v[0], &prec, name)))
        return e;
    need = prec ? NAXES : 6;
    if ((e = want(a, need + 1, need + 1)))
        return e;
    for (i = 0; i < need; i++) {
        if ((e = num(s, a, i + 1, &v[i])))
            return e;
        if (prec && fabs(v[i]) > 9999999999.0)
            return 20;
    }
    if ((e = new_loc(s, name, prec, &l)))
        return e;
    for (i = 0; i < need; i++) {
        if (prec)
            l->p[i] = lround(v[i]);
        else
            l->v[i] = v[i];
    }
    return 0;
}

/* SET A=B and SHIFTA A,B take two names separated by '=' or ','. */
static int two_names(args *a, char *x, char *y)
{
    const char *r = a->rest, *sep;
    size_t n;
    while (*r == ' ')
        r++;
    sep = strpbrk(r, "=,");
    if (!*r)
        return 13;
    if (!sep)
        return a->n < 2 ? 13 : a->n > 2 ? 14 : (strcpy(x, a->v[0]), strcpy(y, a->v[1]), 0);
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
        return 13;
    if (strpbrk(x, " =,") || strpbrk(y, " =,"))
        return 14;
    return 0;
}

static int h_set(fbrl_sim *s, args *a, int *b)
{
    char x[SIM_LINE_MAX + 1], y[SIM_LINE_MAX + 1], name[SIM_NAME_MAX + 1];
    double pose[6], q[NAXES];
    int prec, sprec, e, i;
    sim_loc *l;
    (void)b;
    if ((e = two_names(a, x, y)) || (e = parse_name(x, &prec, name))
        || (e = loc_value(s, y, pose, q, &sprec)))
        return e;
    if (prec && !sprec) {
        if ((e = fbrl_sim_arm_ik(pose, tool_len(s), s->q[0], q)) || (e = fbrl_sim_arm_check(q)))
            return e;
    }
    if ((e = new_loc(s, name, prec, &l)))
        return e;
    if (prec)
        for (i = 0; i < NAXES; i++)
            l->p[i] = fbrl_sim_arm_pulses(i, q[i]);
    else
        memcpy(l->v, pose, sizeof pose);
    return 0;
}

static int cart_loc(fbrl_sim *s, const char *tok, sim_loc **out)
{
    char name[SIM_NAME_MAX + 1];
    int prec, e = parse_name(tok, &prec, name);
    if (e)
        return e;
    if (prec)
        return 15;
    if (!(*out = find_loc(s, name, 0)))
        return 11;
    return 0;
}

static int h_shift(fbrl_sim *s, args *a, int *b)
{
    sim_loc *l;
    double d[3];
    int e = want(a, 4, 4), i;
    (void)b;
    if (e || (e = cart_loc(s, a->v[0], &l)))
        return e;
    for (i = 0; i < 3; i++)
        if ((e = num(s, a, i + 1, &d[i])))
            return e;
    for (i = 0; i < 3; i++)
        l->v[i] += d[i];
    s->dirty = 1;
    return 0;
}

static int h_shifta(fbrl_sim *s, args *a, int *b)
{
    char x[SIM_LINE_MAX + 1], y[SIM_LINE_MAX + 1];
    sim_loc *l, *m;
    int e, i;
    (void)b;
    if ((e = two_names(a, x, y)) || (e = cart_loc(s, x, &l)) || (e = cart_loc(s, y, &m)))
        return e;
    for (i = 0; i < 6; i++)
        l->v[i] += m->v[i];
    s->dirty = 1;
    return 0;
}

static int h_tool(fbrl_sim *s, args *a, int *b)
{
    sim_loc *l;
    int e = want(a, 0, 1), i;
    (void)b;
    if (e)
        return e;
    if (!a->n) {
        s->tool_set = 0;
        memset(s->tool, 0, sizeof s->tool);
        s->dirty = 1;
        return 0;
    }
    if ((e = cart_loc(s, a->v[0], &l)))
        return e;
    for (i = 0; i < 6; i++)
        if (i != 2 && l->v[i] != 0.0)
            return 18;
    if (s->moving)
        halt(s); /* the joints stay; the tool point moves with the new tool */
    s->tool_set = 1;
    strcpy(s->tool_name, l->name);
    memcpy(s->tool, l->v, sizeof s->tool);
    s->dirty = 1;
    return 0;
}

static int cmp_loc(const void *x, const void *y)
{
    const sim_loc *a = x, *b = y;
    int c = strcmp(a->name, b->name);
    return c ? c : a->precision - b->precision;
}

static void print_loc(sim_out *o, const sim_loc *l)
{
    int i;
    if (l->precision) {
        char n[SIM_NAME_MAX + 2];
        snprintf(n, sizeof n, "#%s", l->name);
        sim_out_printf(o, "%-9s", n);
        for (i = 0; i < NAXES; i++)
            sim_out_printf(o, " %+011ld", l->p[i]);
    } else {
        sim_out_printf(o, "%-9s", l->name);
        for (i = 0; i < 6; i++)
            sim_out_printf(o, " %+09.4f", l->v[i] + 0.0);
    }
    sim_out_printf(o, "\r\n");
}

static int h_listl(fbrl_sim *s, args *a, int *b)
{
    int e = want(a, 0, 1), i;
    (void)b;
    if (e)
        return e;
    if (a->n) {
        char name[SIM_NAME_MAX + 1];
        int prec;
        sim_loc *l;
        if ((e = parse_name(a->v[0], &prec, name)))
            return e;
        if (!(l = find_loc(s, name, prec)))
            return 11;
        print_loc(&s->term.out, l);
        return 0;
    }
    qsort(s->locs, (size_t)s->nlocs, sizeof s->locs[0], cmp_loc);
    for (i = 0; i < s->nlocs; i++)
        print_loc(&s->term.out, &s->locs[i]);
    return 0;
}

static int cmp_var(const void *x, const void *y)
{
    return strcmp(((const sim_var *)x)->name, ((const sim_var *)y)->name);
}

static int h_listv(fbrl_sim *s, args *a, int *b)
{
    int e = want(a, 0, 1), i;
    (void)b;
    if (e)
        return e;
    if (a->n) {
        char name[SIM_NAME_MAX + 1];
        sim_var *v;
        if ((e = parse_name(a->v[0], NULL, name)))
            return e;
        if (!(v = find_var(s, name)))
            return 10;
        sim_out_printf(&s->term.out, "%-8s = %+.6f\r\n", v->name, v->v);
        return 0;
    }
    qsort(s->vars, (size_t)s->nvars, sizeof s->vars[0], cmp_var);
    for (i = 0; i < s->nvars; i++)
        sim_out_printf(&s->term.out, "%-8s = %+.6f\r\n", s->vars[i].name, s->vars[i].v);
    return 0;
}

static int h_dlocn(fbrl_sim *s, args *a, int *b)
{
    char name[SIM_NAME_MAX + 1];
    int prec, e = want(a, 1, 1);
    sim_loc *l;
    (void)b;
    if (e || (e = parse_name(a->v[0], &prec, name)))
        return e;
    if (!(l = find_loc(s, name, prec)))
        return 11;
    *l = s->locs[--s->nlocs];
    s->dirty = 1;
    return 0;
}

static int h_dvar(fbrl_sim *s, args *a, int *b)
{
    char name[SIM_NAME_MAX + 1];
    int e = want(a, 1, 1);
    sim_var *v;
    (void)b;
    if (e || (e = parse_name(a->v[0], NULL, name)))
        return e;
    if (!(v = find_var(s, name)))
        return 10;
    *v = s->vars[--s->nvars];
    s->dirty = 1;
    return 0;
}

static int h_type(fbrl_sim *s, args *a, int *b)
{
    const char *r = a->rest;
    size_t n;
    (void)b;
    while (*r == ' ')
        r++;
    n = strlen(r);
    while (n && r[n - 1] == ' ')
        n--;
    if (n >= 2 && r[0] == '"' && r[n - 1] == '"') {
        r++;
        n -= 2;
    }
    sim_out_printf(&s->term.out, "%.*s\r\n", (int)n, r);
    return 0;
}

static int h_typei(fbrl_sim *s, args *a, int *b)
{
    double v;
    int e;
    (void)b;
    if (!a->n)
        return 13;
    if ((e = eval(s, a->rest, &v)))
        return e;
    if (fabs(v) > 9.2e18)
        return 20;
    sim_out_printf(&s->term.out, "%ld\r\n", lround(v));
    return 0;
}

static int h_typev(fbrl_sim *s, args *a, int *b)
{
    double v;
    int e;
    (void)b;
    if (!a->n)
        return 13;
    if ((e = eval(s, a->rest, &v)))
        return e;
    sim_out_printf(&s->term.out, "%+.6f\r\n", v);
    return 0;
}

/* OUTPUT and WAIT: "[-]n,..." -> n (1..16) and on/off. */
static int io_item(fbrl_sim *s, const char *tok, int *n, int *on)
{
    double v;
    int e;
    *on = *tok != '-';
    if (*tok == '-' || *tok == '+')
        tok++;
    if ((e = eval(s, tok, &v)))
        return e;
    if (lround(v) < 1 || lround(v) > SIM_IO)
        return 16;
    *n = (int)lround(v);
    return 0;
}

static int h_output(fbrl_sim *s, args *a, int *b)
{
    int i, n, on, e;
    (void)b;
    if (!a->n)
        return 13;
    for (i = 0; i < a->n; i++)
        if ((e = io_item(s, a->v[i], &n, &on)))
            return e;
    for (i = 0; i < a->n; i++) {
        io_item(s, a->v[i], &n, &on);
        s->out_[n - 1] = on;
    }
    s->dirty = 1;
    return 0;
}

static int h_wait(fbrl_sim *s, args *a, int *b)
{
    int i, n, on, e;
    if (!a->n)
        return 13;
    for (i = 0; i < a->n; i++) {
        if ((e = io_item(s, a->v[i], &n, &on)))
            return e;
        if (s->in[n - 1] != on)
            *b = 1;
    }
    return 0;
}

static int word_is(const char *w, const char *a, const char *b)
{
    return !strcmp(w, a) || !strcmp(w, b);
}

static int h_config(fbrl_sim *s, args *a, int *b)
{
    static const long bauds[] = { 300, 600, 1200, 2400, 4800, 9600, 19200, 38400 };
    sim_chan c;
    long dev, baud, data, stop;
    const char *w;
    int e = want(a, 7, 7), ok = 0;
    size_t i;
    (void)b;
    if (e || (e = inum(s, a, 0, &dev)))
        return e;
    if (dev != 0 && dev != 1)
        return 61;
    if ((e = inum(s, a, 1, &baud)) || (e = inum(s, a, 3, &data)) || (e = inum(s, a, 4, &stop)))
        return e;
    for (i = 0; i < sizeof bauds / sizeof bauds[0]; i++)
        ok |= bauds[i] == baud;
    if (!ok || (data != 7 && data != 8) || (stop != 1 && stop != 2))
        return 18;
    c.baud = baud;
    c.data = (int)data;
    c.stop = (int)stop;
    w = a->v[2];
    if (word_is(w, "N", "NONE"))
        c.parity = 'N';
    else if (word_is(w, "E", "EVEN"))
        c.parity = 'E';
    else if (word_is(w, "O", "ODD"))
        c.parity = 'O';
    else
        return 18;
    w = a->v[5];
    if (word_is(w, "N", "NONE"))
        c.handshake = 'N';
    else if (word_is(w, "X", "XON"))
        c.handshake = 'X';
    else
        return 18;
    w = a->v[6];
    if (word_is(w, "1", "ON"))
        c.echo = 1;
    else if (word_is(w, "0", "OFF"))
        c.echo = 0;
    else
        return 18;
    s->chan[dev] = c;
    s->dirty = 1;
    return 0;
}

static int h_serial(fbrl_sim *s, args *a, int *b)
{
    int e = want(a, 0, 0), i;
    (void)b;
    if (e)
        return e;
    for (i = 0; i < 2; i++) {
        const sim_chan *c = &s->chan[i];
        sim_out_printf(&s->term.out, "CHANNEL %d: BAUD %ld PARITY %c DATA %d STOP %d HANDSHAKE %c ECHO %d\r\n",
                       i, c->baud, c->parity, c->data, c->stop, c->handshake, c->echo);
    }
    return 0;
}

static int h_gain(fbrl_sim *s, args *a, int *b)
{
    long m;
    double v;
    int e = want(a, 1, 2), i;
    (void)b;
    if (e || (e = inum(s, a, 0, &m)))
        return e;
    if (m < 0 || m > NAXES)
        return 65;
    if (a->n == 1) {
        if (m == 0)
            return 65;
        sim_out_printf(&s->term.out, "GAIN MOTOR %ld: %+.4f\r\n", m, s->gain[m]);
        return 0;
    }
    if ((e = num(s, a, 1, &v)))
        return e;
    if (v < 0)
        return 18;
    for (i = 1; i <= NAXES; i++)
        if (m == 0 || m == i)
            s->gain[i] = v;
    s->dirty = 1;
    return 0;
}

static int h_arm(fbrl_sim *s, args *a, int *b)
{
    int e = want(a, 1, 1);
    (void)b;
    if (e)
        return e;
    if (!strcmp(a->v[0], "OFF")) {
        halt(s);
        s->power = 0;
    } else if (!strcmp(a->v[0], "ON")) {
        s->power = 1;
    } else {
        return 18;
    }
    return 0;
}

static int h_xaxis(fbrl_sim *s, args *a, int which, int *b)
{
    long ax;
    int e = want(a, 1, 1);
    (void)b;
    if (e || (e = axis_arg(s, a, 0, NAXES + 1, &ax)))
        return e;
    if (ax != NAXES + 1)
        return 65;
    if (which == 0) { /* XCAL */
        s->xhome = extra_now(s);
    } else if (which == 1) { /* XHOME */
        if (s->xmoving) {
            *b = 1;
            return 0;
        }
        if (!s->power)
            return 40;
        s->xtarget = s->xhome;
        s->xt0 = sim_now(s);
        s->xt1 = s->xt0 + fabs(s->xhome - s->xpos) / (SIM_EXTRA_RATE * s->speed / 100.0);
        s->xmoving = s->xhome != s->xpos;
        s->xhomed = 1;
    } else { /* XZERO */
        if (s->xmoving)
            halt(s);
        s->xpos = 0;
    }
    s->dirty = 1;
    return 0;
}

static int h_xcal(fbrl_sim *s, args *a, int *b) { return h_xaxis(s, a, 0, b); }
static int h_xhome(fbrl_sim *s, args *a, int *b) { return h_xaxis(s, a, 1, b); }
static int h_xzero(fbrl_sim *s, args *a, int *b) { return h_xaxis(s, a, 2, b); }

/* ---- readouts -------------------------------------------------------- */

static void print_position(fbrl_sim *s, const char *title, const double q[NAXES])
{
    sim_out *o = &s->term.out;
    double pose[6];
    int i;
    fbrl_sim_arm_fk(q, tool_len(s), pose);
    sim_out_printf(o, "\r\n%s\r\nNAME       ", title);
    for (i = 0; i < NAXES; i++)
        sim_out_printf(o, i < NAXES - 1 ? "AX#%d        " : "AX#%d", i + 1);
    sim_out_printf(o, "\r\nPULSES   ");
    for (i = 0; i < NAXES; i++)
        sim_out_printf(o, i ? " %+011ld" : "%+011ld", fbrl_sim_arm_pulses(i, q[i]));
    sim_out_printf(o, "\r\nNAME       ");
    for (i = 0; i < NAXES; i++)
        sim_out_printf(o, i < NAXES - 1 ? "JT#%d      " : "JT#%d", i + 1);
    sim_out_printf(o, "\r\nJOINTS   ");
    for (i = 0; i < NAXES; i++)
        sim_out_printf(o, i ? " %+09.4f" : "%+09.4f", q[i] + 0.0); /* no "-000.0000" */
    sim_out_printf(o, "\r\nWORLD     ");
    for (i = 0; i < 6; i++)
        sim_out_printf(o, i ? " %+09.4f" : "%+09.4f", pose[i] + 0.0);
    sim_out_printf(o, "\r\n");
}

static int h_wonce(fbrl_sim *s, args *a, int which)
{
    double q[NAXES];
    int e = want(a, 0, 0);
    if (e)
        return e;
    if (which == 4 && s->moving)
        memcpy(q, s->qt, sizeof q);
    else
        sim_joints_now(s, q);
    print_position(s, which == 0 ? "CURRENT COMMAND POSITION :"
                      : which == 2 ? "CURRENT ACTUAL POSITION :" : "END OF PATH POSITION :", q);
    return 0;
}

static int h_w0(fbrl_sim *s, args *a, int *b) { (void)b; return h_wonce(s, a, 0); }
static int h_w2(fbrl_sim *s, args *a, int *b) { (void)b; return h_wonce(s, a, 2); }
static int h_w4(fbrl_sim *s, args *a, int *b) { (void)b; return h_wonce(s, a, 4); }

static int h_stream(fbrl_sim *s, args *a, int kind)
{
    static const char *titles[] = {
        "ACTUAL POSITION (MOTOR PULSES):", "COMMAND POSITION (MOTOR PULSES):", "VELOCITY (PULSES/SEC):",
        "EXTRA AXIS ACTUAL (MOTOR PULSES):", "EXTRA AXIS COMMAND (MOTOR PULSES):",
        "EXTRA AXIS VELOCITY (PULSES/SEC):"
    };
    int e = want(a, 0, 0);
    if (e)
        return e;
    s->term.stream_kind = kind;
    s->term.ps = PS_STREAM;
    sim_out_printf(&s->term.out, "%s\r\n", titles[(kind % 10) / 2 + (kind > 10 ? 3 : 0)]);
    return 0;
}

static int h_w1(fbrl_sim *s, args *a, int *b) { (void)b; return h_stream(s, a, 1); }
static int h_w3(fbrl_sim *s, args *a, int *b) { (void)b; return h_stream(s, a, 3); }
static int h_w5(fbrl_sim *s, args *a, int *b) { (void)b; return h_stream(s, a, 5); }
static int h_we1(fbrl_sim *s, args *a, int *b) { (void)b; return h_stream(s, a, 11); }
static int h_we3(fbrl_sim *s, args *a, int *b) { (void)b; return h_stream(s, a, 13); }
static int h_we5(fbrl_sim *s, args *a, int *b) { (void)b; return h_stream(s, a, 15); }

void sim_stream_line(fbrl_sim *s, sim_out *o)
{
    const double dt = 0.01; /* simulated seconds for the velocity difference */
    int i;
    if (s->term.stream_kind < 10) {
        double q[NAXES], q2[NAXES];
        sim_joints_now(s, q);
        if (s->term.stream_kind == 5) {
            /* the difference over the last dt of simulated time, from the segment's own formula */
            double save = s->t0;
            s->t0 += dt / s->opt.time_scale;
            sim_joints_now(s, q2);
            s->t0 = save;
            for (i = 0; i < NAXES; i++)
                sim_out_printf(o, i ? " %+011ld" : "%+011ld",
                               lround((q[i] - q2[i]) * fbrl_sim_arm_ppd[i] / dt));
        } else {
            for (i = 0; i < NAXES; i++)
                sim_out_printf(o, i ? " %+011ld" : "%+011ld", fbrl_sim_arm_pulses(i, q[i]));
        }
    } else if (s->term.stream_kind == 15) {
        double v = s->xmoving && sim_now(s) < s->xt1 ? (s->xtarget - s->xpos) / (s->xt1 - s->xt0) : 0.0;
        sim_out_printf(o, "%+011ld", lround(v));
    } else {
        sim_out_printf(o, "%+011ld", lround(extra_now(s)));
    }
    sim_out_printf(o, "\r");
}

static int h_status(fbrl_sim *s, args *a, int *b)
{
    sim_out *o = &s->term.out;
    double q[NAXES];
    int e = want(a, 0, 0), i, moving[NAXES];
    (void)b;
    if (e)
        return e;
    sim_joints_now(s, q);
    for (i = 0; i < NAXES; i++)
        moving[i] = s->moving && fabs(s->qt[i] - s->q[i]) > 0 && sim_now(s) < s->mt1;
    sim_out_printf(o, "RAPL-II Version 2.60     A255 Robot (fbrlsim)\r\n");
    if (s->last_error < 0)
        sim_out_printf(o, "LAST ERROR CODE: NONE\r\n");
    else
        sim_out_printf(o, "LAST ERROR CODE: %03d-%s.\r\n", s->last_error, sim_error_text(s->last_error));
    sim_out_printf(o, "SPEED (%% OF FULL) : %+6ld\r\n", lround(s->speed));
    sim_out_printf(o, "MAX LINEAR SPEED: %+09.4f\r\n", FBRL_SIM_ARM_LINEAR);
    sim_out_printf(o, "CURRENT PROGRAM EXECUTING:%s%s\r\n", s->run_prog ? " " : "",
                   s->run_prog ? s->run_prog->name : "");
    sim_out_printf(o, "JOINT LIMIT CHECK IS ON\r\n");
    sim_out_printf(o, "CONTROLLER IS %sHOMED\r\n", s->homed ? "" : "NOT ");
    sim_out_printf(o, "TOOL TRANSFORM\r\n%-10s", s->tool_set ? "TOOL" : "NULL");
    for (i = 0; i < 6; i++)
        sim_out_printf(o, i ? " %+09.4f" : "%+09.4f", s->tool[i]);
    sim_out_printf(o, "\r\nGRIPPER TYPE:  SERVO\r\n%-13s", "AXIS#");
    for (i = 0; i < NAXES; i++)
        sim_out_printf(o, i ? " %d" : "%d", i + 1);
    sim_out_printf(o, "\r\n%-13s", "LOCK");
    for (i = 0; i < NAXES; i++)
        sim_out_printf(o, i ? " %c" : "%c", s->locked[i] ? 'Y' : 'N');
    sim_out_printf(o, "\r\n%-13s", "DONE");
    for (i = 0; i < NAXES; i++)
        sim_out_printf(o, i ? " %c" : "%c", moving[i] ? 'N' : 'Y');
    sim_out_printf(o, "\r\n%-13s", "LIMP");
    for (i = 0; i < NAXES; i++)
        sim_out_printf(o, i ? " %c" : "%c", s->limp[i] ? 'Y' : 'N');
    sim_out_printf(o, "\r\n%-13s", "HOMED");
    for (i = 0; i < NAXES; i++)
        sim_out_printf(o, i ? " %c" : "%c", s->homed ? 'Y' : 'N');
    sim_out_printf(o, "\r\nREQUESTED ROBOT CONFIG : UPRIGHT/REACH FORWARD/ELBOW UP/WRIST FREE\r\n");
    {
        /* backward when the tool point lies behind the base axis, seen along the waist */
        double pose[6], w = q[0] * 3.14159265358979323846 / 180.0;
        fbrl_sim_arm_fk(q, tool_len(s), pose);
        sim_out_printf(o, "CURRENT ROBOT CONFIG : UPRIGHT/REACH %s/ELBOW UP/WRIST FREE\r\n",
                       pose[0] * cos(w) + pose[1] * sin(w) < -1e-9 ? "BACKWARD" : "FORWARD");
    }
    sim_out_printf(o, "MANUAL MODE STATUS IS %s\r\n", s->manual ? "ON" : "OFF");
    sim_out_printf(o, "ARM POWER IS %s\r\n", s->power ? "ON" : "OFF");
    sim_out_printf(o, "PENDANT LAMP IS %s\r\n", s->flash ? "FLASHING" : "OFF");
    if (s->teach)
        sim_out_printf(o, "TEACH MODE IS ON: %s%s, NEXT %03d\r\n", s->teach == 2 ? "#" : "",
                       s->teach_name, s->teach_next);
    else
        sim_out_printf(o, "TEACH MODE IS OFF\r\n");
    sim_out_printf(o, "GRIPPER OPENING: %+09.4f FORCE (%% OF FULL): %+6ld\r\n", s->grip,
                   lround(s->grip_force));
    sim_out_printf(o, "INPUTS  1-16: ");
    for (i = 0; i < SIM_IO; i++)
        sim_out_printf(o, "%d", s->in[i]);
    sim_out_printf(o, "\r\nOUTPUTS 1-16: ");
    for (i = 0; i < SIM_IO; i++)
        sim_out_printf(o, "%d", s->out_[i]);
    sim_out_printf(o, "\r\nINCH UNITS.\r\n");
    return 0;
}

/* ---- programs -------------------------------------------------------- */

static int exec_line(fbrl_sim *s, const char *text, int top, int *block);

static int run_continue(fbrl_sim *s, int *block)
{
    while (s->run_left > 0) {
        while (s->run_pc < s->run_prog->n) {
            int b = 0, e = exec_line(s, s->run_prog->lines[s->run_pc], 0, &b);
            if (b) {
                *block = 1;
                return 0;
            }
            s->run_pc++;
            if (e) {
                s->run_prog = NULL;
                return e;
            }
        }
        s->run_pc = 0;
        s->run_left--;
    }
    s->run_prog = NULL;
    return 0;
}

static int h_run(fbrl_sim *s, args *a, int *b)
{
    char name[SIM_NAME_MAX + 1];
    long count = 1;
    int e = want(a, 1, 2), i;
    if (e || (e = parse_name(a->v[0], NULL, name)) || (a->n == 2 && (e = inum(s, a, 1, &count))))
        return e;
    if (count < 1)
        return 18;
    for (i = 0; i < s->nprogs; i++)
        if (!strcmp(s->progs[i].name, name))
            break;
    if (i == s->nprogs)
        return 17;
    s->run_prog = &s->progs[i];
    s->run_pc = 0;
    s->run_left = count;
    return run_continue(s, b);
}

/* ---- the command table ----------------------------------------------- */

typedef struct cmd {
    const char *name;
    int token; /* /NNN, or 0 */
    int flags;
    const char *hint;
    handler fn;
} cmd;

static const cmd cmds[] = {
    { "ACTUAL", 152, 0, "<LOC>", h_here },
    { "ALIGN", 1, F_MOTION, "", h_align },
    { "APPRO", 2, F_MOTION, "<LOC>,<DIST>[,S]", h_appro },
    { "ARM", 142, 0, "<ON|OFF>", h_arm },
    { "CLOSE", 38, 0, "[FORCE]", h_close },
    { "CONFIG", 110, 0, "<DEV#>,<BAUD>,<PARITY>,<#DATA>,<#STOP>,<HANDSHAKE>,<ECHO>", h_config },
    { "DEPART", 4, F_MOTION, "<DIST>[,S]", h_depart },
    { "DLOCN", 48, 0, "<LOC>", h_dlocn },
    { "DVAR", 67, 0, "<VAR>", h_dvar },
    { "FINISH", 10, 0, "", h_finish },
    { "FLASH", 84, 0, "[INTERVAL]", h_flash },
    { "GAIN", 150, 0, "<MOTOR#>[,<VALUE>]", h_gain },
    { "GRIP", 39, 0, "<DIST>[,FORCE]", h_grip },
    { "HALT", 154, 0, "", h_halt },
    { "HELP", 95, 0, "", h_help },
    { "HERE", 24, 0, "<LOC>", h_here },
    { "HOME", 20, 0, "", h_home },
    { "JOG", 5, F_MOTION, "<DX>,<DY>,<DZ>", h_jog },
    { "JOINT", 6, F_MOTION, "<JOINT#>,<DEGREES>", h_joint },
    { "LIMP", 7, 0, "[AXIS#,...]", h_limp },
    { "LISTL", 49, 0, "[LOC]", h_listl },
    { "LISTV", 69, 0, "[VAR]", h_listv },
    { "LOCK", 9, 0, "<JOINT#,...>", h_lock },
    { "MA", 132, F_MOTION, "<J1>,<J2>,<J3>,<J4>,<J5>[,S]", h_ma },
    { "MANUAL", 45, 0, "[JOI|CYL]", h_manual },
    { "MI", 131, F_MOTION, "<J1>,<J2>,<J3>,<J4>,<J5>[,S]", h_mi },
    { "MOTOR", 11, F_MOTION, "<MOTOR#>,<PULSES>", h_motor },
    { "MOVE", 0, F_MOTION, "<LOC>[,S]", h_move },
    { "NOFLASH", 0, 0, "", h_noflash },
    { "NOHELP", 0, 0, "", h_nohelp },
    { "NOLIMP", 0, 0, "", h_nolimp },
    { "NOMANUAL", 0, 0, "", h_nomanual },
    { "NOTEACH", 0, 0, "", h_noteach },
    { "OPEN", 40, 0, "[FORCE]", h_open },
    { "OUTPUT", 89, 0, "<[-]OUT#,...>", h_output },
    { "POINT", 50, 0, "<LOC>,<X>,<Y>,<Z>,<YAW>,<PITCH>,<ROLL>", h_point },
    { "READY", 15, F_MOTION, "", h_ready },
    { "RUN", 109, F_TOP, "<PROG>[,<COUNT>]", h_run },
    { "SERIAL", 111, 0, "", h_serial },
    { "SET", 51, F_RAW, "<LOC1>=<LOC2>", h_set },
    { "SHIFT", 52, 0, "<LOC>,<DX>,<DY>,<DZ>", h_shift },
    { "SHIFTA", 53, F_RAW, "<LOC1>,<LOC2>", h_shifta },
    { "SPEED", 16, 0, "<PERCENT>", h_speed },
    { "STATUS", 25, 0, "", h_status },
    { "TEACH", 44, 0, "<NAME>", h_teach },
    { "TOOL", 54, 0, "[LOC]", h_tool },
    { "TYPE", 58, F_RAW, "<TEXT>", h_type },
    { "TYPEI", 59, F_RAW, "<EXPR>", h_typei },
    { "TYPEV", 60, F_RAW, "<EXPR>", h_typev },
    { "UNLOCK", 17, 0, "[JOINT#,...]", h_unlock },
    { "W0", 27, 0, "", h_w0 },
    { "W1", 29, F_TOP, "", h_w1 },
    { "W2", 31, 0, "", h_w2 },
    { "W3", 33, F_TOP, "", h_w3 },
    { "W4", 35, 0, "", h_w4 },
    { "W5", 37, F_TOP, "", h_w5 },
    { "WAIT", 94, 0, "<[-]IN#,...>", h_wait },
    { "WE1", 28, F_TOP, "", h_we1 },
    { "WE3", 32, F_TOP, "", h_we3 },
    { "WE5", 36, F_TOP, "", h_we5 },
    { "XCAL", 157, 0, "<AXIS#>", h_xcal },
    { "XHOME", 158, 0, "<AXIS#>", h_xhome },
    { "XZERO", 159, 0, "<AXIS#>", h_xzero },
};

#define NCMDS ((int)(sizeof cmds / sizeof cmds[0]))

/* Finds a command by keyword, unique prefix or /NNN token; 0 or 12/50. */
static int lookup(const char *word, const cmd **out)
{
    int i, found = -1, count = 0;
    size_t n = strlen(word);
    if (word[0] == '/') {
        int t;
        if (n != 4 || !isdigit((unsigned char)word[1]) || !isdigit((unsigned char)word[2])
            || !isdigit((unsigned char)word[3]))
            return 12;
        t = atoi(word + 1);
        for (i = 0; i < NCMDS; i++)
            if (cmds[i].token == t) {
                *out = &cmds[i];
                return 0;
            }
        return 12;
    }
    if (!n)
        return 12;
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
    return count ? 50 : 12;
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
    if ((e = parse_name(tok, NULL, name)) || (e = eval(s, eq + 1, &v)))
        return e;
    var = find_var(s, name);
    if (!var) {
        if (s->nvars == SIM_MAX_VARS)
            return 22;
        var = &s->vars[s->nvars++];
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
        return 18;
    if ((e = split_args(p, &a)) && !(c->flags & F_RAW))
        return e;
    a.rest = p;
    if (*a.rest == ',')
        a.rest++;
    if (c->flags & F_MOTION) {
        if (s->moving || s->xmoving) {
            *block = 1;
            return 0;
        }
        if (!s->power)
            return 40;
        if (!s->homed)
            return 41;
        for (n = 0; n < NAXES; n++)
            if (s->limp[n])
                return 18;
    }
    return c->fn(s, &a, block);
}

int sim_exec(fbrl_sim *s, const char *line, int *err)
{
    if (line != s->term.cur)
        snprintf(s->term.cur, sizeof s->term.cur, "%s", line);
    s->run_prog = NULL;
    return sim_exec_step(s, err);
}

int sim_exec_step(fbrl_sim *s, int *err)
{
    int block = 0, e;
    sim_arm_update(s);
    e = s->run_prog ? run_continue(s, &block) : exec_line(s, s->term.cur, 1, &block);
    if (block)
        return EXEC_BLOCK;
    *err = e ? e : -1;
    return EXEC_DONE;
}

/* ---- control lines --------------------------------------------------- */

int sim_control(fbrl_sim *s, const char *line)
{
    char w[16];
    double a = 0, b = 0;
    int n = sscanf(line, "%15s %lf %lf", w, &a, &b);
    if (n < 1)
        return -1;
    if (!strcmp(w, "IN") && n == 3 && a >= 1 && a <= SIM_IO && (b == 0 || b == 1)) {
        if (s)
            s->in[(int)a - 1] = (int)b;
        return 0;
    }
    if (!strcmp(w, "AIN") && n == 3 && a >= 1 && a <= SIM_AIN && a == (int)a && b >= -10 && b <= 10) {
        if (s)
            s->ain[(int)a - 1] = b;
        return 0;
    }
    if (!strcmp(w, "POWER") && n == 2 && (a == 0 || a == 1)) {
        if (s) {
            if (!a)
                halt(s);
            s->power = (int)a;
        }
        return 0;
    }
    if (!strcmp(w, "OBJECT") && n == 2 && a >= 0 && a <= SIM_GRIP_MAX) {
        if (s)
            s->object = a;
        return 0;
    }
    if (!strcmp(w, "TEACH") && n == 1) {
        if (s && s->teach && s->teach_next <= 999) {
            char name[32];
            double q[NAXES];
            sim_loc *l;
            int i;
            snprintf(name, sizeof name, "%.5s%03d", s->teach_name, s->teach_next);
            if (new_loc(s, name, s->teach == 2, &l) == 0) {
                sim_joints_now(s, q);
                if (s->teach == 2)
                    for (i = 0; i < NAXES; i++)
                        l->p[i] = fbrl_sim_arm_pulses(i, q[i]);
                else
                    fbrl_sim_arm_fk(q, tool_len(s), l->v);
                s->teach_next++;
                if (s->state_path)
                    sim_state_save(s);
                s->dirty = 0;
            }
        }
        return 0;
    }
    return -1;
}

/* ---- memory ---------------------------------------------------------- */

void sim_state_defaults(fbrl_sim *s)
{
    int i;
    s->last_error = -1;
    s->speed = 50.0;
    s->power = 1;
    s->term.help = 1;
    s->grip = SIM_GRIP_MAX;
    s->grip_force = 50.0;
    for (i = 0; i <= NAXES; i++)
        s->gain[i] = 1.0;
    memcpy(s->q, fbrl_sim_arm_ready, sizeof s->q);
    memcpy(s->qt, s->q, sizeof s->q);
    for (i = 0; i < 2; i++) {
        s->chan[i].baud = 9600;
        s->chan[i].parity = 'N';
        s->chan[i].data = 8;
        s->chan[i].stop = 1;
        s->chan[i].handshake = i == 0 ? 'X' : 'N';
        s->chan[i].echo = 1;
    }
}

void sim_free_memory(fbrl_sim *s)
{
    int i, j;
    for (i = 0; i < s->nprogs; i++) {
        for (j = 0; j < s->progs[i].n; j++)
            free(s->progs[i].lines[j]);
        free(s->progs[i].lines);
    }
    free(s->progs);
    s->progs = NULL;
    s->nprogs = 0;
}
