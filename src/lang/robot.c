/* robot.c - FBRL robot words: the binding machinery, parameters on the stack or after
 * the word (thesis 5.3, I-6), robot commands (I-5) and RAPL line building (I-8).
 *
 * Every word that talks to the controller goes through the robot's fbrl_link, so each
 * command line is echo-verified before its CR is sent. Locations come from the host
 * side (6 floats in the VM's data space); a word that moves to one first defines a
 * scratch controller point with POINT, then moves to that point. docs/robot.md tells
 * the rules, docs/glossary.md lists every word with the text it sends. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fbrl/num.h"
#include "robot_internal.h"

static const char OFFLINE[] = "no controller connected: start fbrlmon with --sim or --port";

/* ---- binding ---- */

static fbrl_status rb_params(fbrl_robot *r, const rb_word *w, rb_val *v);

static fbrl_status tramp(fbrl_vm *vm, void *arg)
{
    const fbrl_robot_bind *b = arg;
    const rb_word *w = b->word;
    rb_val v[RB_MAXP];
    (void)vm;
    memset(v, 0, sizeof v);
    fbrl_status st = rb_params(b->r, w, v);
    if (st != FBRL_OK) return st;
    return w->fn(b->r, w, v);
}

fbrl_status rb_define(fbrl_robot *r, const rb_word *t, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        if (r->nbind >= FBRL_ROBOT_MAX_WORDS) return FBRL_ENOSPC;
        fbrl_robot_bind *b = &r->bind[r->nbind++];
        b->r = r;
        b->word = &t[i];
        fbrl_status st = fbrl_vm_define(r->vm, t[i].name, tramp, b, t[i].stack, t[i].help);
        if (st != FBRL_OK) return st;
    }
    return FBRL_OK;
}

/* ---- errors, output, clock ---- */

fbrl_status rb_fail(fbrl_robot *r, int code, const char *msg) { return fbrl_vm_throw(r->vm, code, msg); }

fbrl_status rb_fail_st(fbrl_robot *r, const rb_word *w, fbrl_status st, const char *what)
{
    char msg[128];
    snprintf(msg, sizeof msg, "%s: %s%s%s", w->name, what ? what : "", what ? ": " : "", fbrl_status_str(st));
    return rb_fail(r, FBRL_THROW_STATUS(st), msg);
}

/* Ctrl-C while a robot word waits on the controller: take the VM's interrupt request
 * here (the engine would deliver it only after the word returns) and throw -28 with
 * what it means for the controller. */
fbrl_status rb_interrupted(fbrl_robot *r)
{
    if (!fbrl__take_interrupt(r->vm)) return FBRL_OK;
    return rb_fail(r, -28, "user interrupt (a command the controller already has still runs;"
                           " the next robot word waits for it)");
}

/* Run the link's current command to its end in slices, looking for Ctrl-C between
 * them. Interrupted, the command stays in the link (the controller cannot take a
 * line back): rb_online() finishes it before the next command. */
static fbrl_status rb_drive(fbrl_robot *r, fbrl_status *result)
{
    for (;;) {
        int done = 0;
        fbrl_status st = fbrl_link_poll(r->link, 100, &done);
        if (done || st != FBRL_OK) {
            *result = st;
            return FBRL_OK;
        }
        if ((st = rb_interrupted(r)) != FBRL_OK) return st;
    }
}

fbrl_status rb_online(fbrl_robot *r)
{
    if (!r->link) return rb_fail(r, FBRL_THROW_STATUS(FBRL_EOFFLINE), OFFLINE);
    if (fbrl_link_busy(r->link)) { /* left running by an interrupted word: end it first */
        fbrl_status res = FBRL_OK, st = rb_drive(r, &res);
        if (st != FBRL_OK) return st;
        if (res == FBRL_ECONTROLLER) fbrl_link_error(r->link, &r->last_error, NULL);
    }
    return FBRL_OK;
}

void rb_puts(fbrl_robot *r, const char *s) { fbrl__write(r->vm, s, strlen(s)); }

fbrl_status rb_now_ms(fbrl_robot *r, uint64_t *ms)
{
    if (!r->vm->host.now_us) return rb_fail(r, -21, "no clock in this host");
    *ms = r->vm->host.now_us(r->vm->host.user) / 1000u;
    return FBRL_OK;
}

fbrl_status rb_sleep_ms(fbrl_robot *r, uint32_t ms)
{
    if (!r->vm->host.sleep_ms) return rb_fail(r, -21, "no clock in this host");
    if (ms) r->vm->host.sleep_ms(r->vm->host.user, ms);
    return FBRL_OK;
}

/* ---- the data glossary's side: locations, mapping, units ---- */

/* The location template at a VM address (48 aligned bytes inside the data space). */
static fbrl_loc *gl_loc(fbrl_robot *r, fbrl_cell addr)
{
    fbrl_loc *p = NULL;
    return fbrl_glossary_loc(r->vm, addr, &p) == FBRL_OK ? p : NULL;
}

static int gl_metric(const fbrl_robot *r)
{
    int on = 0;
    return r->g && fbrl_units_is_metric(fbrl_glossary_units(r->g), &on) == FBRL_OK && on;
}

/* MAP-ON mapping (identity without a glossary or with MAP-OFF). The waist turns about the
 * arm's base axis: where BASE-OFFSET puts it in the user's frame. */
static void gl_arm_axis(const fbrl_robot *r, double axis[2])
{
    double c = cos(FBRL_RAD(r->base[3])), s = sin(FBRL_RAD(r->base[3]));
    axis[0] = -(c * r->base[0] + s * r->base[1]);
    axis[1] = s * r->base[0] - c * r->base[1];
}

static fbrl_status gl_map_out(fbrl_robot *r, const fbrl_loc *in, fbrl_loc *out, double *off)
{
    double axis[2];
    *out = *in;
    *off = 0.0;
    gl_arm_axis(r, axis);
    return r->g ? fbrl_glossary_map_out(r->g, out, axis, off) : FBRL_OK;
}

static fbrl_status gl_map_in(fbrl_robot *r, const fbrl_loc *in, fbrl_loc *out)
{
    double axis[2];
    *out = *in;
    gl_arm_axis(r, axis);
    return r->g ? fbrl_glossary_map_in(r->g, out, axis) : FBRL_OK;
}

double rb_len_in(const fbrl_robot *r, double v) { return gl_metric(r) ? v / 2.54 : v; }

/* ---- talking to the controller ---- */

fbrl_status rb_link_result(fbrl_robot *r, const rb_word *w, fbrl_status st)
{
    char msg[128];
    if (st == FBRL_OK) return FBRL_OK;
    if (st == FBRL_ECONTROLLER) {
        int code = -1;
        const char *text = "";
        fbrl_link_error(r->link, &code, &text);
        r->last_error = code;
        snprintf(msg, sizeof msg, "%s: controller error %03d-%s", w->name, code, text);
        return rb_fail(r, FBRL_THROW_STATUS(st), msg);
    }
    if (st == FBRL_EINVAL || st == FBRL_ENAME || st == FBRL_ERANGE || st == FBRL_ENONFINITE)
        return rb_fail_st(r, w, st, "cannot encode the command");
    return rb_fail_st(r, w, st, "link");
}

fbrl_status rb_cmd(fbrl_robot *r, const rb_word *w, fbrl_rapl_cmd cmd, const fbrl_rapl_arg *a, size_t n,
                   int straight)
{
    fbrl_status st = rb_online(r);
    if (st != FBRL_OK) return st;
    const fbrl_rapl_cmdinfo *ci = fbrl_rapl_cmd_info(cmd);
    if (!ci || !((ci->flags & FBRL_RAPL_F_MOTION) || cmd == FBRL_RAPL_FINISH || cmd == FBRL_RAPL_WAIT ||
                 cmd == FBRL_RAPL_RUN))
        return rb_link_result(r, w, fbrl_link_cmd(r->link, cmd, a, n, straight));
    /* A command that may wait for the arm or an input (no reply but the prompt): run it
     * step by step so that Ctrl-C is noticed while it waits. */
    char text[FBRL_RAPL_LINE_MAX];
    size_t len;
    fbrl_rapl_form form = FBRL_RAPL_KEYWORD;
    (void)fbrl_link_get_form(r->link, &form);
    fbrl_status res = fbrl_rapl_encode(text, sizeof text, &len, form, cmd, a, n, straight);
    if (res == FBRL_OK && len > FBRL_LINK_LINE_MAX) res = FBRL_ERANGE;
    if (res == FBRL_OK) res = fbrl_link_start(r->link, text, FBRL_LINK_REPLY_NONE);
    if (res == FBRL_OK && (st = rb_drive(r, &res)) != FBRL_OK) return st;
    return rb_link_result(r, w, res);
}

static void print_line(void *ctx, const char *line, size_t len, int flawed)
{
    fbrl_robot *r = ctx;
    fbrl__write(r->vm, line, len);
    fbrl__write(r->vm, flawed ? " (damaged)\n" : "\n", flawed ? 12 : 1);
}

/* The robot borrows the link's line handler for one command (docs/robot.md) and puts
 * the owner's back. */
static void borrow_lines(fbrl_robot *r, void (**fn)(void *, const char *, size_t, int), void **ctx)
{
    (void)fbrl_link_set_line_handler(r->link, print_line, r, fn, ctx);
}

static void return_lines(fbrl_robot *r, void (*fn)(void *, const char *, size_t, int), void *ctx)
{
    (void)fbrl_link_set_line_handler(r->link, fn, ctx, NULL, NULL);
}

fbrl_status rb_raw(fbrl_robot *r, const rb_word *w, const char *line, int print)
{
    void (*fn)(void *, const char *, size_t, int);
    void *ctx;
    fbrl_status st = rb_online(r);
    if (st != FBRL_OK) return st;
    if (print) borrow_lines(r, &fn, &ctx);
    st = fbrl_link_raw(r->link, line);
    if (print) return_lines(r, fn, ctx);
    return rb_link_result(r, w, st);
}

static fbrl_status rb_stream(fbrl_robot *r, const rb_word *w, fbrl_rapl_cmd cmd)
{
    void (*fn)(void *, const char *, size_t, int);
    void *ctx;
    fbrl_status st = rb_online(r);
    if (st != FBRL_OK) return st;
    borrow_lines(r, &fn, &ctx);
    st = fbrl_link_stream(r->link, cmd, FBRL_ROBOT_STREAM_LINES);
    return_lines(r, fn, ctx);
    return rb_link_result(r, w, st);
}

/* ---- locations: host side, mapping, base offset ---- */

static fbrl_status loc_read(fbrl_robot *r, const rb_word *w, fbrl_cell addr, fbrl_loc *out)
{
    const fbrl_loc *p = gl_loc(r, addr);
    char msg[96];
    if (!p) {
        snprintf(msg, sizeof msg, "%s: not a location (use a CREATE-LOC name)", w->name);
        return rb_fail(r, -9, msg);
    }
    if (fbrl_loc_check(p) != FBRL_OK) {
        snprintf(msg, sizeof msg, "%s: location holds a NaN or infinity", w->name);
        return rb_fail(r, FBRL_THROW_STATUS(FBRL_ENONFINITE), msg);
    }
    *out = *p;
    return FBRL_OK;
}

static fbrl_status loc_write(fbrl_robot *r, const rb_word *w, fbrl_cell addr, const fbrl_loc *in)
{
    fbrl_loc *p = gl_loc(r, addr);
    if (!p) {
        char msg[96];
        snprintf(msg, sizeof msg, "%s: not a location (use a CREATE-LOC name)", w->name);
        return rb_fail(r, -9, msg);
    }
    if (in) *p = *in; /* in NULL: only check that addr is a location */
    return FBRL_OK;
}

static double wrap180(double a)
{
    a = fmod(a, 360.0);
    if (a > 180.0) a -= 360.0;
    if (a <= -180.0) a += 360.0;
    return a;
}

/* A location of the user's frame as the controller must see it: MAP-ON mapping (the
 * block's motion), then the BASE-OFFSET (where the user's world sits on the arm). */
static fbrl_status to_arm(fbrl_robot *r, const rb_word *w, const fbrl_loc *user, fbrl_loc *arm)
{
    fbrl_loc m;
    double off;
    fbrl_status st = gl_map_out(r, user, &m, &off);
    if (st == FBRL_ERANGE) {
        char msg[200], deg[32], lim[32];
        fbrl_num_fixed(deg, sizeof deg, off, 0, 2, 0, NULL);
        fbrl_num_fixed(lim, sizeof lim, FBRL_CALIB_AXIS_MAX, 0, 1, 0, NULL);
        snprintf(msg, sizeof msg, "%s: mapping: the block's tilt asks for the tool axis %s deg across the arm,"
                 " which a 5-axis arm cannot follow (limit %s deg)", w->name, deg, lim);
        return rb_fail(r, FBRL_THROW_STATUS(st), msg);
    }
    if (st != FBRL_OK) return rb_fail_st(r, w, st, "mapping");
    double c = cos(FBRL_RAD(r->base[3])), s = sin(FBRL_RAD(r->base[3]));
    arm->x = c * m.x - s * m.y + r->base[0];
    arm->y = s * m.x + c * m.y + r->base[1];
    arm->z = m.z + r->base[2];
    arm->o = r->base[3] != 0.0 ? wrap180(m.o + r->base[3]) : m.o;
    arm->a = m.a;
    arm->t = m.t;
    return FBRL_OK;
}

/* The inverse: a position the controller reported, in the user's (original block) frame. */
static fbrl_status from_arm(fbrl_robot *r, const rb_word *w, const fbrl_loc *arm, fbrl_loc *user, int map)
{
    fbrl_loc m;
    double c = cos(FBRL_RAD(r->base[3])), s = sin(FBRL_RAD(r->base[3]));
    double dx = arm->x - r->base[0], dy = arm->y - r->base[1];
    m.x = c * dx + s * dy;
    m.y = -s * dx + c * dy;
    m.z = arm->z - r->base[2];
    m.o = r->base[3] != 0.0 ? wrap180(arm->o - r->base[3]) : arm->o;
    m.a = arm->a;
    m.t = arm->t;
    if (!map) {
        *user = m;
        return FBRL_OK;
    }
    fbrl_status st = gl_map_in(r, &m, user);
    return st == FBRL_OK ? FBRL_OK : rb_fail_st(r, w, st, "unmapping");
}

/* POINT a scratch controller location at arm coordinates; its name goes to name[]. */
static fbrl_status scratch_point(fbrl_robot *r, const rb_word *w, const fbrl_loc *arm, const char **name)
{
    static const char *const names[2] = { "FBRLT1", "FBRLT2" };
    *name = names[r->scratch++ & 1u];
    fbrl_rapl_arg a[7] = { fbrl_rapl_str(*name), fbrl_rapl_real(arm->x), fbrl_rapl_real(arm->y),
                           fbrl_rapl_real(arm->z), fbrl_rapl_real(arm->o), fbrl_rapl_real(arm->a),
                           fbrl_rapl_real(arm->t) };
    return rb_cmd(r, w, FBRL_RAPL_POINT, a, 7, 0);
}

/* The arm's position (W2 WORLD line), waiting for the motion to end first when asked. */
static fbrl_status arm_where(fbrl_robot *r, const rb_word *w, int finish, fbrl_loc *arm)
{
    fbrl_rapl_pos p;
    fbrl_status st = rb_online(r);
    if (st != FBRL_OK) return st;
    if (finish && (st = rb_cmd(r, w, FBRL_RAPL_FINISH, NULL, 0, 0)) != FBRL_OK) return st;
    if ((st = rb_link_result(r, w, fbrl_link_where(r->link, FBRL_RAPL_W2, &p))) != FBRL_OK) return st;
    if (p.nworld < 6) return rb_fail_st(r, w, FBRL_EPROTOCOL, "W2 had no WORLD line");
    arm->x = p.world[0];
    arm->y = p.world[1];
    arm->z = p.world[2];
    arm->o = p.world[3];
    arm->a = p.world[4];
    arm->t = p.world[5];
    return FBRL_OK;
}

/* ---- I-6: parameters after the word ---- */

static int is_blank(char c) { return (unsigned char)c <= ' '; }

/* [+-]digits[.digits][(E|e)[+-]digits], exactly rounded for up to 15 significant digits
 * (an integer mantissa over an exact power of ten), locale-free. */
static int parse_real(const char *s, size_t n, double *out)
{
    size_t i = 0;
    int neg = 0, nd = 0, frac = 0, ex = 0, eneg = 0;
    double mant = 0.0;
    if (i < n && (s[i] == '+' || s[i] == '-')) neg = s[i++] == '-';
    for (; i < n && s[i] >= '0' && s[i] <= '9'; i++, nd++) mant = mant * 10.0 + (s[i] - '0');
    if (i < n && s[i] == '.')
        for (i++; i < n && s[i] >= '0' && s[i] <= '9'; i++, nd++, frac++) mant = mant * 10.0 + (s[i] - '0');
    if (nd == 0 || nd > 17) return 0;
    if (i < n && (s[i] == 'E' || s[i] == 'e')) {
        int ed = 0;
        i++;
        if (i < n && (s[i] == '+' || s[i] == '-')) eneg = s[i++] == '-';
        for (; i < n && s[i] >= '0' && s[i] <= '9' && ex < 1000; i++, ed++) ex = ex * 10 + (s[i] - '0');
        if (ed == 0 && i < n) return 0;
    }
    if (i != n) return 0;
    int e10 = (eneg ? -ex : ex) - frac;
    double v = mant;
    if (e10 < 0) {
        v = e10 >= -22 ? v / pow(10.0, -e10) : v * pow(10.0, e10);
    } else if (e10 > 0) {
        v = v * pow(10.0, e10);
    }
    if (!isfinite(v)) return 0;
    *out = neg ? -v : v;
    return 1;
}

static int parse_int(const fbrl_vm *vm, const char *s, size_t n, fbrl_cell *out)
{
    fbrl_cell base = *vm->base;
    int neg = 0;
    if (n > 1 && (*s == '#' || *s == '$' || *s == '%')) {
        base = *s == '#' ? 10 : *s == '$' ? 16 : 2;
        s++;
        n--;
    }
    if (n > 1 && *s == '-') {
        neg = 1;
        s++;
        n--;
    }
    if (base < 2 || base > 36 || n == 0) return 0;
    fbrl_ucell lo = 0, hi = 0;
    if (fbrl__to_number(s, n, base, &lo, &hi) != n || hi != 0 || lo > (fbrl_ucell)INTPTR_MAX) return 0;
    *out = neg ? -(fbrl_cell)lo : (fbrl_cell)lo;
    return 1;
}

/* A dictionary word that holds data (never code with side effects). */
static const fbrl_hdr *data_word(fbrl_vm *vm, const char *s, size_t n)
{
    int i = fbrl__find(vm, s, n);
    if (i < 0) return NULL;
    const fbrl_hdr *h = HDR(vm, i);
    switch (h->kind) {
    case K_CREATE: return h->does ? NULL : h; /* a DOES> part is code: never run for a parameter */
    case K_VAR: case K_CONST: case K_VALUE: case K_FCONST: case K_FVALUE: return h;
    default: return NULL;
    }
}

/* Run a data word and take the one cell (cells = 1) or one float it leaves. */
static int data_value(fbrl_vm *vm, const fbrl_hdr *h, int want_float, fbrl_cell *c, double *f)
{
    size_t d0 = fbrl_vm_depth(vm), f0 = fbrl_vm_fdepth(vm);
    int idx = (int)((vm->hdr_top - 1) - h); /* HDR(vm, i) = hdr_top - 1 - i */
    if (fbrl__run(vm, FBRL_XT_BASE + idx) != 0) return 0;
    size_t d1 = fbrl_vm_depth(vm), f1 = fbrl_vm_fdepth(vm);
    if (d1 == d0 + 1 && f1 == f0) {
        fbrl_vm_pop(vm, c);
        if (want_float) *f = (double)*c;
        return 1;
    }
    if (want_float && f1 == f0 + 1 && d1 == d0) {
        fbrl_vm_fpop(vm, f);
        return 1;
    }
    /* leave the stacks as they were */
    while (fbrl_vm_depth(vm) > d0) fbrl_vm_pop(vm, c);
    while (fbrl_vm_fdepth(vm) > f0) fbrl_vm_fpop(vm, f);
    return 0;
}

static const char *kind_name(char kind)
{
    switch (kind) {
    case 'I': return "an integer";
    case 'R': return "a number";
    case 'L': return "a location name";
    case 'C': return "a character";
    case 'X': return "a location or controller location name";
    case 'A': return "a device name";
    default: return "a name";
    }
}

fbrl_status rb_parse_param(fbrl_robot *r, const rb_word *w, char kind, rb_val *v)
{
    fbrl_vm *vm = r->vm;
    const char *s;
    size_t n;
    char msg[128];
    if (kind == 'T') { /* the rest of the line */
        int found;
        fbrl_src *src = vm->nsrc ? fbrl__src(vm) : NULL;
        while (src && *vm->toin >= 0 && (size_t)*vm->toin < src->len && is_blank(src->buf[*vm->toin]))
            ++*vm->toin;
        fbrl__parse(vm, '\0', &s, &n, &found);
        while (n > 0 && is_blank(s[n - 1])) n--;
    } else if (kind == 'S') { /* GETSTRING: a "quoted text" or one word */
        fbrl_src *src = vm->nsrc ? fbrl__src(vm) : NULL;
        while (src && *vm->toin >= 0 && (size_t)*vm->toin < src->len && is_blank(src->buf[*vm->toin]))
            ++*vm->toin;
        if (src && *vm->toin >= 0 && (size_t)*vm->toin < src->len && src->buf[*vm->toin] == '"') {
            int found;
            ++*vm->toin;
            fbrl__parse(vm, '"', &s, &n, &found);
            if (!found) {
                snprintf(msg, sizeof msg, "%s: unterminated \"text\"", w->name);
                return rb_fail(r, -39, msg);
            }
            v->s = s;
            v->n = n;
            return FBRL_OK;
        }
        fbrl__parse_name(vm, &s, &n);
    } else {
        fbrl__parse_name(vm, &s, &n);
    }
    if (n == 0) {
        snprintf(msg, sizeof msg, "%s needs %s: on the stack before it, or after it on the line", w->name,
                 kind_name(kind));
        return rb_fail(r, -16, msg);
    }
    const fbrl_hdr *h;
    switch (kind) {
    case 'T': case 'S':
        v->s = s;
        v->n = n;
        return FBRL_OK;
    case 'I':
        if (parse_int(vm, s, n, &v->i)) return FBRL_OK;
        if ((h = data_word(vm, s, n)) && (h->kind == K_CONST || h->kind == K_VALUE) && data_value(vm, h, 0, &v->i, &v->f))
            return FBRL_OK;
        break;
    case 'C':
        if (n == 1) { v->i = (unsigned char)s[0]; return FBRL_OK; }
        if (n == 3 && s[0] == '\'' && s[2] == '\'') { v->i = (unsigned char)s[1]; return FBRL_OK; }
        if (parse_int(vm, s, n, &v->i)) return FBRL_OK;
        break;
    case 'R':
        if (parse_real(s, n, &v->f)) return FBRL_OK;
        if ((h = data_word(vm, s, n)) && h->kind != K_VAR && h->kind != K_CREATE && data_value(vm, h, 1, &v->i, &v->f))
            return FBRL_OK;
        break;
    case 'L': case 'X': case 'A':
        if ((h = data_word(vm, s, n)) && (h->kind == K_VAR || h->kind == K_CREATE || h->kind == K_CONST || h->kind == K_VALUE)
            && data_value(vm, h, 0, &v->i, &v->f)) {
            v->s = NULL;
            return FBRL_OK;
        }
        if (kind == 'X' && fbrl__find(vm, s, n) < 0) { /* a controller location name */
            v->s = s;
            v->n = n;
            return FBRL_OK;
        }
        break;
    default:
        break;
    }
    snprintf(msg, sizeof msg, "%s: '%.*s' is not %s", w->name, (int)(n > 40 ? 40 : n), s, kind_name(kind));
    return rb_fail(r, -24, msg);
}

/* The one rule (docs/robot.md): when the stacks hold enough values for every
 * parameter, they come from the stacks; otherwise all of them are read from the
 * input after the word, in the order of the stack effect. */
static fbrl_status rb_params(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_vm *vm = r->vm;
    size_t nc = 0, nf = 0, k, np = strlen(w->spec);
    for (k = 0; k < np; k++) {
        char c = w->spec[k];
        if (c == 'R') nf++;
        else if (c == 'S' || c == 'T') nc += 2;
        else nc++;
    }
    if (np == 0) return FBRL_OK;
    if (fbrl_vm_depth(vm) >= nc && fbrl_vm_fdepth(vm) >= nf) {
        for (k = np; k-- > 0;) {
            char c = w->spec[k];
            if (c == 'R') {
                fbrl_vm_fpop(vm, &v[k].f);
            } else if (c == 'S' || c == 'T') {
                fbrl_cell a, u;
                fbrl_vm_pop(vm, &u);
                fbrl_vm_pop(vm, &a);
                if (u < 0 || (u > 0 && !fbrl__addr_ok(vm, a, u))) return rb_fail(r, -9, NULL);
                v[k].s = (const char *)a;
                v[k].n = (size_t)u;
            } else {
                fbrl_vm_pop(vm, &v[k].i);
            }
        }
        return FBRL_OK;
    }
    for (k = 0; k < np; k++) {
        fbrl_status st = rb_parse_param(r, w, w->spec[k], &v[k]);
        if (st != FBRL_OK) return st;
    }
    return FBRL_OK;
}

/* Copy a name parameter into a C string (controller names are short). */
static fbrl_status name_arg(fbrl_robot *r, const rb_word *w, const rb_val *v, char *buf, size_t cap)
{
    if (v->n == 0 || v->n >= cap) {
        char msg[96];
        snprintf(msg, sizeof msg, "%s: controller name must be 1..%u characters", w->name, (unsigned)(cap - 2));
        return rb_fail(r, FBRL_THROW_STATUS(FBRL_ENAME), msg);
    }
    memcpy(buf, v->s, v->n);
    buf[v->n] = '\0';
    return FBRL_OK;
}

static fbrl_status range(fbrl_robot *r, const rb_word *w, const char *what, fbrl_cell v, fbrl_cell lo, fbrl_cell hi)
{
    if (v >= lo && v <= hi) return FBRL_OK;
    char msg[96];
    snprintf(msg, sizeof msg, "%s: %s %ld outside %ld..%ld", w->name, what, (long)v, (long)lo, (long)hi);
    return rb_fail(r, -24, msg);
}

static fbrl_status finite(fbrl_robot *r, const rb_word *w, const rb_val *v, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (!isfinite(v[k].f) || fabs(v[k].f) > FBRL_RAPL_REAL_MAX) {
            char msg[96];
            snprintf(msg, sizeof msg, "%s: number out of range (NaN, infinite or too large)", w->name);
            return rb_fail(r, FBRL_THROW_STATUS(FBRL_ERANGE), msg);
        }
    return FBRL_OK;
}

/* ---- I-5 robot commands ---- */

/* Commands without parameters (HOME, READY, HALT, FINISH ...). */
static fbrl_status w_plain(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    (void)v;
    return rb_cmd(r, w, (fbrl_rapl_cmd)w->cmd, NULL, 0, 0);
}

/* One axis / number. arg: 0 plain; 1 axis 1..5 with 0 = all (no argument sent);
 * 2 axis 1..5; 3 extra axis 1..8; 4 SPEED 1..100; 5 FLASH interval >= 0. */
static fbrl_status w_int1(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_status st = FBRL_OK;
    switch (w->arg) {
    case 1: st = range(r, w, "axis", v[0].i, 0, 5); break;
    case 2: st = range(r, w, "axis", v[0].i, 1, 5); break;
    case 3: st = range(r, w, "axis", v[0].i, 1, 8); break;
    case 4: st = range(r, w, "speed", v[0].i, 1, 100); break;
    case 5: st = range(r, w, "interval", v[0].i, 0, 32767); break;
    default: break;
    }
    if (st != FBRL_OK) return st;
    fbrl_rapl_arg a = fbrl_rapl_int((long)v[0].i);
    return rb_cmd(r, w, (fbrl_rapl_cmd)w->cmd, &a, (w->arg == 1 && v[0].i == 0) ? 0 : 1, 0);
}

/* JOINT ( joint degrees -- ), MOTOR ( axis# #pulses -- ) */
static fbrl_status w_joint(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_status st = range(r, w, w->cmd == FBRL_RAPL_MOTOR ? "motor" : "joint", v[0].i, 1,
                           w->cmd == FBRL_RAPL_MOTOR ? 6 : 5);
    if (st == FBRL_OK) st = range(r, w, w->cmd == FBRL_RAPL_MOTOR ? "pulses" : "degrees", v[1].i, -2000000000L, 2000000000L);
    if (st != FBRL_OK) return st;
    fbrl_rapl_arg a[2] = { fbrl_rapl_int((long)v[0].i),
                           w->cmd == FBRL_RAPL_MOTOR ? fbrl_rapl_int((long)v[1].i) : fbrl_rapl_real((double)v[1].i) };
    return rb_cmd(r, w, (fbrl_rapl_cmd)w->cmd, a, 2, 0);
}

/* GAIN ( motor# -- | F: value ) */
static fbrl_status w_gain(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_status st = range(r, w, "motor", v[0].i, 0, 8);
    if (st == FBRL_OK) st = finite(r, w, &v[1], 1);
    if (st == FBRL_OK && v[1].f < 0) st = rb_fail(r, -24, "GAIN: value must not be negative");
    if (st != FBRL_OK) return st;
    fbrl_rapl_arg a[2] = { fbrl_rapl_int((long)v[0].i), fbrl_rapl_real(v[1].f) };
    return rb_cmd(r, w, FBRL_RAPL_GAIN, a, 2, 0);
}

/* GRIP ( torque -- | F: distance ): GRIP distance,torque */
static fbrl_status w_grip(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_status st = range(r, w, "torque (% of full)", v[0].i, 1, 100);
    if (st == FBRL_OK) st = finite(r, w, &v[1], 1);
    if (st != FBRL_OK) return st;
    double d = rb_len_in(r, v[1].f);
    if (d < 0) return rb_fail(r, -24, "GRIP: distance must not be negative");
    fbrl_rapl_arg a[2] = { fbrl_rapl_real(d), fbrl_rapl_int((long)v[0].i) };
    return rb_cmd(r, w, FBRL_RAPL_GRIP, a, 2, 0);
}

/* JOG ( F: dX dY dZ -- ), lengths in the user's units */
static fbrl_status w_jog(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_status st = finite(r, w, v, 3);
    if (st != FBRL_OK) return st;
    fbrl_rapl_arg a[3] = { fbrl_rapl_real(rb_len_in(r, v[0].f)), fbrl_rapl_real(rb_len_in(r, v[1].f)),
                           fbrl_rapl_real(rb_len_in(r, v[2].f)) };
    return rb_cmd(r, w, FBRL_RAPL_JOG, a, 3, 0);
}

/* MA / MI ( F: j1 j2 j3 j4 j5 -- ), radians; arg 1 = straight */
static fbrl_status w_joints(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_status st = finite(r, w, v, 5);
    if (st != FBRL_OK) return st;
    fbrl_rapl_arg a[5];
    for (int k = 0; k < 5; k++) a[k] = fbrl_rapl_real(v[k].f);
    return rb_cmd(r, w, (fbrl_rapl_cmd)w->cmd, a, 5, (int)w->arg);
}

/* DEPART / DEPART-STRT ( F: distance -- ) */
static fbrl_status w_depart(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_status st = finite(r, w, v, 1);
    if (st != FBRL_OK) return st;
    fbrl_rapl_arg a = fbrl_rapl_real(rb_len_in(r, v[0].f));
    return rb_cmd(r, w, FBRL_RAPL_DEPART, &a, 1, (int)w->arg);
}

/* MOV / MOV-STRT ( loc -- ): POINT scratch, then MOVE scratch[,S] */
static fbrl_status w_mov(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_loc user, arm;
    const char *name;
    fbrl_status st = loc_read(r, w, v[0].i, &user);
    if (st == FBRL_OK) st = rb_online(r);
    if (st == FBRL_OK) st = to_arm(r, w, &user, &arm);
    if (st == FBRL_OK) st = scratch_point(r, w, &arm, &name);
    if (st != FBRL_OK) return st;
    fbrl_rapl_arg a = fbrl_rapl_str(name);
    return rb_cmd(r, w, FBRL_RAPL_MOVE, &a, 1, (int)w->arg);
}

/* APPROACH / APPROACH-STRT ( loc -- | F: distance -- ) */
static fbrl_status w_approach(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_loc user, arm;
    const char *name;
    fbrl_status st = finite(r, w, &v[1], 1);
    if (st == FBRL_OK) st = loc_read(r, w, v[0].i, &user);
    if (st == FBRL_OK) st = rb_online(r);
    if (st == FBRL_OK) st = to_arm(r, w, &user, &arm);
    if (st == FBRL_OK) st = scratch_point(r, w, &arm, &name);
    if (st != FBRL_OK) return st;
    fbrl_rapl_arg a[2] = { fbrl_rapl_str(name), fbrl_rapl_real(rb_len_in(r, v[1].f)) };
    return rb_cmd(r, w, FBRL_RAPL_APPRO, a, 2, (int)w->arg);
}

/* ARM-HERE ( loc -- ): wait for the motion to end, read W2, store it unmapped */
static fbrl_status w_arm_here(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_loc arm, user;
    fbrl_status st = loc_write(r, w, v[0].i, NULL);
    if (st == FBRL_OK) st = rb_online(r);
    if (st == FBRL_OK) st = arm_where(r, w, 1, &arm);
    if (st == FBRL_OK) st = from_arm(r, w, &arm, &user, 1);
    if (st == FBRL_OK) st = loc_write(r, w, v[0].i, &user);
    return st;
}

/* ACTUAL ( loc -- ) or ( PAR: controller-name ): the actual position now, into a host
 * location (unmapped) or, for a name that is no FBRL word, into the controller's location. */
static fbrl_status w_actual(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    if (v[0].s) {
        char name[16];
        fbrl_status st = name_arg(r, w, &v[0], name, 10);
        if (st != FBRL_OK) return st;
        fbrl_rapl_arg a = fbrl_rapl_str(name);
        return rb_cmd(r, w, FBRL_RAPL_ACTUAL, &a, 1, 0);
    }
    fbrl_loc arm, user;
    fbrl_status st = loc_write(r, w, v[0].i, NULL);
    if (st == FBRL_OK) st = rb_online(r);
    if (st == FBRL_OK) st = arm_where(r, w, 0, &arm);
    if (st == FBRL_OK) st = from_arm(r, w, &arm, &user, 1);
    if (st == FBRL_OK) st = loc_write(r, w, v[0].i, &user);
    return st;
}

/* TOOL ( loc -- ): the tool transform is relative to the flange: never mapped */
static fbrl_status w_tool(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_loc t;
    const char *name;
    fbrl_status st = loc_read(r, w, v[0].i, &t);
    if (st == FBRL_OK) st = scratch_point(r, w, &t, &name);
    if (st != FBRL_OK) return st;
    fbrl_rapl_arg a = fbrl_rapl_str(name);
    return rb_cmd(r, w, FBRL_RAPL_TOOL, &a, 1, 0);
}

/* ARM ( flag -- ) */
static fbrl_status w_arm(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_rapl_arg a = fbrl_rapl_str(v[0].i ? "ON" : "OFF");
    return rb_cmd(r, w, FBRL_RAPL_ARM, &a, 1, 0);
}

/* CONFIG ( dev baud parity #data #stop handshake echo -- ) */
static fbrl_status w_config(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    static const long bauds[] = { 300, 600, 1200, 2400, 4800, 9600, 19200, 38400 };
    const char *par = NULL, *hs = NULL;
    size_t k;
    fbrl_status st = range(r, w, "device", v[0].i, 0, 1);
    for (k = 0; st == FBRL_OK && k < sizeof bauds / sizeof bauds[0] && bauds[k] != v[1].i; k++)
        ;
    if (st == FBRL_OK && k == sizeof bauds / sizeof bauds[0]) st = rb_fail(r, -24, "CONFIG: baud must be 300..38400 (a standard rate)");
    switch (v[2].i) {
    case 'N': case 'n': par = "N"; break;
    case 'E': case 'e': par = "E"; break;
    case 'O': case 'o': par = "O"; break;
    default: break;
    }
    switch (v[5].i) {
    case 'N': case 'n': case 0: hs = "N"; break;
    case 'X': case 'x': case 1: case -1: hs = "X"; break;
    default: break;
    }
    if (st == FBRL_OK && !par) st = rb_fail(r, -24, "CONFIG: parity must be the character N, E or O");
    if (st == FBRL_OK) st = range(r, w, "data bits", v[3].i, 7, 8);
    if (st == FBRL_OK) st = range(r, w, "stop bits", v[4].i, 1, 2);
    if (st == FBRL_OK && !hs) st = rb_fail(r, -24, "CONFIG: handshake must be N or X (or 0 / 1)");
    if (st == FBRL_OK) st = range(r, w, "echo", v[6].i, -1, 1);
    if (st != FBRL_OK) return st;
    fbrl_rapl_arg a[7] = { fbrl_rapl_int((long)v[0].i), fbrl_rapl_int((long)v[1].i), fbrl_rapl_str(par),
                           fbrl_rapl_int((long)v[3].i), fbrl_rapl_int((long)v[4].i), fbrl_rapl_str(hs),
                           fbrl_rapl_int(v[6].i ? 1 : 0) };
    return rb_cmd(r, w, FBRL_RAPL_CONFIG, a, 7, 0);
}

/* BASE-OFFSET ( F: dX dY dZ dO -- ): where the user's world frame sits on the arm */
static fbrl_status w_base_offset(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_status st = finite(r, w, v, 4);
    if (st != FBRL_OK) return st;
    r->base[0] = rb_len_in(r, v[0].f);
    r->base[1] = rb_len_in(r, v[1].f);
    r->base[2] = rb_len_in(r, v[2].f);
    r->base[3] = v[3].f;
    return FBRL_OK;
}

/* SHIFT-RIGHT ( n -- n' b ) */
static fbrl_status w_shift_right(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    (void)w;
    fbrl_ucell u = (fbrl_ucell)v[0].i;
    fbrl_status st = fbrl_vm_push(r->vm, (fbrl_cell)(u >> 1));
    if (st == FBRL_OK) st = fbrl_vm_push(r->vm, (fbrl_cell)(u & 1u));
    return st == FBRL_OK ? FBRL_OK : rb_fail(r, -3, NULL);
}

/* OUTPORT ( output# -- ): output n on, -n off */
static fbrl_status w_outport(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_cell n = v[0].i < 0 ? -v[0].i : v[0].i;
    fbrl_status st = range(r, w, "output", n, 1, FBRL_ROBOT_IO_MAX);
    if (st != FBRL_OK) return st;
    fbrl_rapl_arg a = fbrl_rapl_int((long)v[0].i);
    return rb_cmd(r, w, FBRL_RAPL_OUTPUT, &a, 1, 0);
}

/* OUT2BYTE ( n -- ): bit k of n sets output k+1 (16 outputs, two OUTPUT lines of 8) */
static fbrl_status w_out2byte(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_status st = range(r, w, "value", v[0].i, 0, 0xFFFF);
    for (int half = 0; st == FBRL_OK && half < 2; half++) {
        fbrl_rapl_arg a[8];
        for (int k = 0; k < 8; k++) {
            int out = half * 8 + k + 1;
            a[k] = fbrl_rapl_int(((v[0].i >> (out - 1)) & 1) ? out : -out);
        }
        st = rb_cmd(r, w, FBRL_RAPL_OUTPUT, a, 8, 0);
    }
    return st;
}

/* WAITPORT ( input# -- ): RAPL WAIT: input n on, -n off */
static fbrl_status w_waitport(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_cell n = v[0].i < 0 ? -v[0].i : v[0].i;
    fbrl_status st = range(r, w, "input", n, 1, FBRL_ROBOT_IO_MAX);
    if (st != FBRL_OK) return st;
    fbrl_rapl_arg a = fbrl_rapl_int((long)v[0].i);
    return rb_cmd(r, w, FBRL_RAPL_WAIT, &a, 1, 0);
}

/* W0 W2 W4: the link repeats a read-only query until query_reads replies agree and
 * hands over the lines of every reply; only the last block (the confirmed reading)
 * is kept for the console. A block starts at its title line. */
typedef struct rb_block {
    char text[2048];
    size_t n;
} rb_block;

static void keep_block(void *ctx, const char *line, size_t len, int flawed)
{
    rb_block *b = ctx;
    fbrl_rapl_pos title;
    fbrl_rapl_pos_init(&title);
    if (!flawed && fbrl_rapl_pos_line(&title, line, len) == FBRL_OK) b->n = 0; /* only a title fits an empty block */
    if (b->n + len + 1 > sizeof b->text) return;
    memcpy(b->text + b->n, line, len);
    b->n += len;
    b->text[b->n++] = '\n';
}

/* W0 W2 W4 ROBOT-STATUS SERIAL: the controller's text on the console */
static fbrl_status w_show(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    (void)v;
    fbrl_rapl_cmd cmd = (fbrl_rapl_cmd)w->cmd;
    if (cmd != FBRL_RAPL_W0 && cmd != FBRL_RAPL_W2 && cmd != FBRL_RAPL_W4)
        return rb_raw(r, w, fbrl_rapl_cmd_info(cmd)->keyword, 1);
    rb_block b;
    fbrl_link_line_fn fn = NULL;
    void *ctx = NULL;
    fbrl_status st = rb_online(r);
    if (st != FBRL_OK) return st;
    b.n = 0;
    (void)fbrl_link_set_line_handler(r->link, keep_block, &b, &fn, &ctx); /* for this command */
    st = fbrl_link_where(r->link, cmd, NULL);
    (void)fbrl_link_set_line_handler(r->link, fn, ctx, NULL, NULL);
    if (st == FBRL_OK) fbrl__write(r->vm, b.text, b.n);
    return rb_link_result(r, w, st);
}

/* W1 W3 W5 WE1 WE3 WE5: FBRL_ROBOT_STREAM_LINES readings, then the stream is stopped */
static fbrl_status w_stream(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    (void)v;
    return rb_stream(r, w, (fbrl_rapl_cmd)w->cmd);
}

/* TYPEINT / TYPEREAL ( string -- ): print a controller variable */
static fbrl_status w_typevar(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    char name[16], out[48];
    fbrl_status st = name_arg(r, w, &v[0], name, 10);
    if (st == FBRL_OK) st = rb_online(r);
    if (st != FBRL_OK) return st;
    if (w->arg) {
        double d;
        if ((st = rb_link_result(r, w, fbrl_link_typev(r->link, name, &d))) != FBRL_OK) return st;
        if (w->arg == 2) return fbrl_vm_fpush(r->vm, d) == FBRL_OK ? FBRL_OK : rb_fail(r, -44, NULL);
        fbrl_num_fixed(out, sizeof out - 1, d, 0, 6, 0, NULL); /* "%.6f", whatever the locale */
        strcat(out, " ");
    } else {
        long i;
        if ((st = rb_link_result(r, w, fbrl_link_typei(r->link, name, &i))) != FBRL_OK) return st;
        if (w->cmd == 1) return fbrl_vm_push(r->vm, (fbrl_cell)i) == FBRL_OK ? FBRL_OK : rb_fail(r, -3, NULL);
        snprintf(out, sizeof out, "%ld ", i);
    }
    rb_puts(r, out);
    return FBRL_OK;
}

/* WGRIP ( string -- ): the gripper opening into a controller variable */
static fbrl_status w_wgrip(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    char name[16], line[40];
    fbrl_status st = name_arg(r, w, &v[0], name, 10);
    if (st == FBRL_OK && fbrl_rapl_name_check(name, 0) != FBRL_OK) st = rb_fail_st(r, w, FBRL_ENAME, name);
    if (st != FBRL_OK) return st;
    snprintf(line, sizeof line, "%s=GRIPPER", name);
    return rb_raw(r, w, line, 0);
}

/* RAPL ( PAR: text ) or ( c-addr u -- ): a line straight to the controller */
static fbrl_status w_rapl(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    char line[FBRL_LINK_LINE_MAX + 1];
    if (v[0].n == 0 || v[0].n > FBRL_LINK_LINE_MAX)
        return rb_fail(r, -24, "RAPL: the line must be 1..80 characters");
    memcpy(line, v[0].s, v[0].n);
    line[v[0].n] = '\0';
    return rb_raw(r, w, line, 1);
}

/* SET-RAPL-REAL ( PAR: name value ), SET-RAPL-INT */
static fbrl_status w_set_var(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    char name[16];
    fbrl_status st = name_arg(r, w, &v[0], name, 10);
    if (st == FBRL_OK && w->arg) st = finite(r, w, &v[1], 1);
    if (st != FBRL_OK) return st;
    if (!w->arg) { /* the encoder writes every value as a real; an integer goes as typed */
        char line[40];
        if (fbrl_rapl_name_check(name, 0) != FBRL_OK) return rb_fail_st(r, w, FBRL_ENAME, name);
        snprintf(line, sizeof line, "%s=%ld", name, (long)v[1].i);
        return rb_raw(r, w, line, 0);
    }
    fbrl_rapl_arg a[2] = { fbrl_rapl_str(name), fbrl_rapl_real(v[1].f) };
    return rb_cmd(r, w, FBRL_RAPL_ASSIGN, a, 2, 0);
}

/* RAPL-ANALOG ( PAR: input# variable ): the controller reads A/D channel n into a
 * variable with `NAME=ADC(n)` (ADC is our decision; see docs/rapl-commands.md). */
static fbrl_status w_analog(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    char name[16], line[40];
    fbrl_status st = name_arg(r, w, &v[1], name, 10);
    if (st != FBRL_OK) return st;
    if (v[0].i < 1 || v[0].i > 8) return rb_fail(r, -24, "RAPL-ANALOG: the analog input must be 1..8");
    if (fbrl_rapl_name_check(name, 0) != FBRL_OK) return rb_fail_st(r, w, FBRL_ENAME, name);
    snprintf(line, sizeof line, "%s=ADC(%ld)", name, (long)v[0].i);
    return rb_raw(r, w, line, 0);
}

/* RAPL-HERE, RAPL-RUN ( PAR: name ) */
static fbrl_status w_name1(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    char name[16];
    fbrl_status st = name_arg(r, w, &v[0], name, 10);
    if (st != FBRL_OK) return st;
    fbrl_rapl_arg a = fbrl_rapl_str(name);
    return rb_cmd(r, w, (fbrl_rapl_cmd)w->cmd, &a, 1, 0);
}

/* RAPL-SET, RAPL-SHIFTA ( PAR: loc1 loc2 ) */
static fbrl_status w_name2(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    char a1[16], a2[16];
    fbrl_status st = name_arg(r, w, &v[0], a1, 10);
    if (st == FBRL_OK) st = name_arg(r, w, &v[1], a2, 10);
    if (st != FBRL_OK) return st;
    fbrl_rapl_arg a[2] = { fbrl_rapl_str(a1), fbrl_rapl_str(a2) };
    return rb_cmd(r, w, (fbrl_rapl_cmd)w->cmd, a, 2, 0);
}

/* RAPL-POINT ( PAR: rapl-loc fbrl-loc ): define a controller location from a host one */
static fbrl_status w_rapl_point(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    char name[16];
    fbrl_loc user, arm;
    fbrl_status st = name_arg(r, w, &v[0], name, 10);
    if (st == FBRL_OK && name[0] == '#') st = rb_fail(r, -24, "RAPL-POINT: a host location is cartesian: no '#' name");
    if (st == FBRL_OK) st = loc_read(r, w, v[1].i, &user);
    if (st == FBRL_OK) st = rb_online(r);
    if (st == FBRL_OK) st = to_arm(r, w, &user, &arm);
    if (st != FBRL_OK) return st;
    fbrl_rapl_arg a[7] = { fbrl_rapl_str(name), fbrl_rapl_real(arm.x), fbrl_rapl_real(arm.y), fbrl_rapl_real(arm.z),
                           fbrl_rapl_real(arm.o), fbrl_rapl_real(arm.a), fbrl_rapl_real(arm.t) };
    return rb_cmd(r, w, FBRL_RAPL_POINT, a, 7, 0);
}

/* RAPL-ERROR ( -- n ) */
static fbrl_status w_rapl_error(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    (void)w;
    (void)v;
    return fbrl_vm_push(r->vm, r->last_error) == FBRL_OK ? FBRL_OK : rb_fail(r, -3, NULL);
}

/* GET-CAL-POINTS ( cal -- ): teach slots 1..3 from the arm's position. For each slot
 * the lines that follow in the current input (a file, or evaluated text; at the end of
 * it, console lines) are run as FBRL until an empty line takes the point. The points
 * are physical arm positions (never mapped: they define the mapping); SET-CAL stores
 * them, all three only when all were taken. */
static fbrl_status next_line(fbrl_robot *r, const rb_word *w, int slot, size_t *len)
{
    fbrl_vm *vm = r->vm;
    char *buf = (char *)r->tib;
    fbrl_src *s = vm->nsrc ? fbrl__src(vm) : NULL;
    if (s && s->kind != SRC_STRING) {
        int got = fbrl__refill(vm);
        if (got < 0) return fbrl_vm_throw(vm, got, NULL);
        if (got > 0) {
            size_t n = s->len < FBRL_ROBOT_TIB ? s->len : FBRL_ROBOT_TIB;
            memcpy(buf, s->buf, n);
            *vm->toin = (fbrl_cell)s->len;
            *len = n;
            return FBRL_OK;
        }
    }
    if (!vm->host.key) {
        char msg[96];
        snprintf(msg, sizeof msg, "%s: input ended before point %d was taken", w->name, slot);
        return rb_fail(r, -24, msg);
    }
    size_t n = 0;
    for (;;) {
        int c = vm->host.key(vm->host.user);
        if (c < 0) {
            char msg[96];
            snprintf(msg, sizeof msg, "%s: input ended before point %d was taken", w->name, slot);
            return rb_fail(r, -24, msg);
        }
        if (c == '\n' || c == '\r') break;
        if (n < FBRL_ROBOT_TIB) buf[n++] = (char)c;
    }
    *len = n;
    return FBRL_OK;
}

static fbrl_status teach3(fbrl_robot *r, const rb_word *w, fbrl_loc pts[3]);

static fbrl_status w_get_cal_points(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_vm *vm = r->vm;
    fbrl_loc pts[3];
    fbrl_calpts *cal;
    char msg[128];
    fbrl_status st = fbrl_glossary_calpts(vm, v[0].i, &cal);
    if (st != FBRL_OK) {
        snprintf(msg, sizeof msg, "%s: not a calibration (use a CREATE-CAL name)", w->name);
        return rb_fail(r, st == FBRL_ETYPE ? -12 : -9, msg);
    }
    if ((st = rb_online(r)) != FBRL_OK) return st;
    if (r->teaching) return rb_fail(r, -24, "GET-CAL-POINTS: already teaching (not inside its own lines)");
    r->teaching = 1;
    st = teach3(r, w, pts);
    r->teaching = 0;
    if (st != FBRL_OK) return st;
    /* the lines run while teaching may have changed the dictionary: look the structure up again */
    if (fbrl_glossary_calpts(vm, v[0].i, &cal) != FBRL_OK) return rb_fail(r, -9, "GET-CAL-POINTS: calibration gone");
    for (int slot = 1; slot <= 3; slot++)
        if ((st = fbrl_calpts_set(cal, slot, &pts[slot - 1])) != FBRL_OK) return rb_fail_st(r, w, st, NULL);
    return FBRL_OK;
}

/* The three positions, each after the lines that bring the arm there. */
static fbrl_status teach3(fbrl_robot *r, const rb_word *w, fbrl_loc pts[3])
{
    fbrl_vm *vm = r->vm;
    fbrl_status st;
    char msg[128];
    for (int slot = 1; slot <= 3; slot++) {
        snprintf(msg, sizeof msg, "Calibration point %d: move the arm there (robot words), then an empty line takes it.\n", slot);
        rb_puts(r, msg);
        for (;;) {
            size_t n = 0;
            if ((st = next_line(r, w, slot, &n)) != FBRL_OK) return st;
            size_t k = 0;
            while (k < n && is_blank(((char *)r->tib)[k])) k++;
            if (k == n) break;
            int e = fbrl__evaluate(vm, (char *)r->tib, n);
            if (e) return fbrl_vm_throw(vm, e, NULL);
        }
        fbrl_loc arm;
        if ((st = arm_where(r, w, 1, &arm)) != FBRL_OK) return st;
        if ((st = from_arm(r, w, &arm, &pts[slot - 1], 0)) != FBRL_OK) return st;
    }
    return FBRL_OK;
}

/* ---- I-6 words ---- */

static fbrl_status w_getreal(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_status st = rb_parse_param(r, w, 'R', v);
    if (st != FBRL_OK) return st;
    return fbrl_vm_fpush(r->vm, v[0].f) == FBRL_OK ? FBRL_OK : rb_fail(r, -44, NULL);
}

static fbrl_status w_getint(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_status st = rb_parse_param(r, w, 'I', v);
    if (st != FBRL_OK) return st;
    return fbrl_vm_push(r->vm, v[0].i) == FBRL_OK ? FBRL_OK : rb_fail(r, -3, NULL);
}

static fbrl_status w_getstring(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_status st = rb_parse_param(r, w, 'S', v);
    if (st != FBRL_OK) return st;
    if (fbrl_vm_push(r->vm, (fbrl_cell)v[0].s) || fbrl_vm_push(r->vm, (fbrl_cell)v[0].n)) return rb_fail(r, -3, NULL);
    return FBRL_OK;
}

/* ---- I-8: building a command line piecewise ---- */

static fbrl_status put(fbrl_robot *r, const char *s, size_t n)
{
    if (r->len + n > FBRL_LINK_LINE_MAX) {
        r->line_bad = 1;
        return FBRL_OK; /* reported by SEND-CR, which refuses the whole line */
    }
    memcpy(r->line + r->len, s, n);
    r->len += n;
    r->line[r->len] = '\0';
    return FBRL_OK;
}

/* A parameter right after the command word is separated from it by a space. */
static void sep(fbrl_robot *r)
{
    if (r->len > 0 && r->line[r->len - 1] != ' ' && r->line[r->len - 1] != ',' && !memchr(r->line, ' ', r->len))
        put(r, " ", 1);
}

static fbrl_status w_send_com(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    char tok[8];
    const char *text = NULL;
    for (int c = 0; c < FBRL_RAPL_NCMDS; c++) {
        const fbrl_rapl_cmdinfo *ci = fbrl_rapl_cmd_info((fbrl_rapl_cmd)c);
        if (ci->token && ci->token == v[0].i) {
            fbrl_rapl_form form = FBRL_RAPL_KEYWORD;
            if (r->link)
                (void)fbrl_link_get_form(r->link, &form);
            if (form == FBRL_RAPL_TOKEN) {
                snprintf(tok, sizeof tok, "/%03u", (unsigned)ci->token);
                text = tok;
            } else {
                text = ci->keyword;
            }
            break;
        }
    }
    if (!text) {
        char msg[80];
        snprintf(msg, sizeof msg, "%s: no RAPL command has the number %ld", w->name, (long)v[0].i);
        return rb_fail(r, -24, msg);
    }
    r->len = 0;
    r->line[0] = '\0';
    r->line_bad = 0;
    return put(r, text, strlen(text));
}

static fbrl_status w_send_real(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    char buf[32];
    size_t n;
    fbrl_status st = fbrl_rapl_format_real(buf, sizeof buf, &n, v[0].f);
    if (st != FBRL_OK) return rb_fail_st(r, w, st, NULL);
    sep(r);
    return put(r, buf, n);
}

static fbrl_status w_send_int(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    char buf[32];
    (void)w;
    int n = snprintf(buf, sizeof buf, "%ld", (long)v[0].i);
    sep(r);
    return put(r, buf, (size_t)n);
}

static fbrl_status w_send_text(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    for (size_t k = 0; k < v[0].n; k++)
        if (v[0].s[k] < 0x20 || v[0].s[k] > 0x7e || v[0].s[k] == '?')
            return rb_fail(r, -24, "SEND-TEXT: only printable characters (no '?')");
    (void)w;
    sep(r);
    return put(r, v[0].s, v[0].n);
}

static fbrl_status w_send_const(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    (void)v;
    return put(r, (const char *)w->arg, strlen((const char *)w->arg));
}

/* SEND-LOC ( loc -- ): the six components, mapped like every outgoing location */
static fbrl_status w_send_loc(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_loc user, arm;
    fbrl_status st = loc_read(r, w, v[0].i, &user);
    if (st == FBRL_OK) st = to_arm(r, w, &user, &arm);
    if (st != FBRL_OK) return st;
    const double c[6] = { arm.x, arm.y, arm.z, arm.o, arm.a, arm.t };
    sep(r);
    for (int k = 0; k < 6; k++) {
        char buf[32];
        size_t n;
        if ((st = fbrl_rapl_format_real(buf, sizeof buf, &n, c[k])) != FBRL_OK) return rb_fail_st(r, w, st, NULL);
        if (k) put(r, ",", 1);
        put(r, buf, n);
    }
    return FBRL_OK;
}

static fbrl_status w_send_cr(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    char line[FBRL_LINK_LINE_MAX + 1];
    int bad = r->line_bad;
    (void)v;
    memcpy(line, r->line, r->len + 1);
    size_t n = r->len;
    r->len = 0;
    r->line[0] = '\0';
    r->line_bad = 0;
    if (bad) return rb_fail(r, FBRL_THROW_STATUS(FBRL_ERANGE), "SEND-CR: the line grew past 80 characters");
    if (n == 0) return rb_fail(r, -24, "SEND-CR: nothing to send (start with SEND-COM)");
    return rb_raw(r, w, line, 1);
}

/* ---- the table ---- */

#define CMD(x) FBRL_RAPL_##x
static const rb_word robot_words[] = {
    /* I-5 motion */
    { "APPROACH", w_approach, "LR", 0, -1, 0, "( loc -- ) ( F: distance -- )", "joint-interpolated move to distance back from loc along the tool axis (APPRO)" },
    { "APPROACH-STRT", w_approach, "LR", 0, -1, 1, "( loc -- ) ( F: distance -- )", "straight-line approach (APPRO ...,S)" },
    { "DEPART", w_depart, "R", 0, -1, 0, "( F: distance -- )", "joint-interpolated move back along the tool axis" },
    { "DEPART-STRT", w_depart, "R", 0, -1, 1, "( F: distance -- )", "straight-line depart (DEPART ...,S)" },
    { "MOV", w_mov, "L", 0, -1, 0, "( loc -- )", "joint-interpolated move to a location (POINT scratch, MOVE scratch)" },
    { "MOV-STRT", w_mov, "L", 0, -1, 1, "( loc -- )", "straight-line move to a location (MOVE scratch,S)" },
    { "JOG", w_jog, "RRR", 0, -1, 0, "( F: dX dY dZ -- )", "move the tool by the displacements (straight line)" },
    { "JOINT", w_joint, "II", 0, CMD(JOINT), 0, "( joint degrees -- )", "drive one joint by degrees" },
    { "MOTOR", w_joint, "II", 0, CMD(MOTOR), 0, "( axis# #pulses -- )", "drive one motor by encoder pulses" },
    { "MA", w_joints, "RRRRR", 0, CMD(MA), 0, "( F: j1 j2 j3 j4 j5 -- )", "joint-interpolated move to absolute joint angles (radians)" },
    { "MI", w_joints, "RRRRR", 0, CMD(MI), 0, "( F: j1 j2 j3 j4 j5 -- )", "joint-interpolated move by joint increments (radians)" },
    { "READY", w_plain, "", 0, CMD(READY), 0, "( -- )", "move the arm to the READY position" },
    { "HOME", w_plain, "", 0, CMD(HOME), 0, "( -- )", "initialise the robot position registers" },
    { "ALIGNTOOL", w_plain, "", 0, CMD(ALIGN), 0, "( -- )", "align the tool with the nearest major axis" },
    { "FINISH", w_plain, "", 0, CMD(FINISH), 0, "( -- )", "wait until the current motion is done" },
    { "HALT", w_plain, "", 0, CMD(HALT), 0, "( -- )", "stop the motion in progress" },
    /* I-5 positions */
    { "ARM-HERE", w_arm_here, "L", 0, -1, 0, "( loc -- )", "store the arm's position (after the motion ends) in loc, unmapped" },
    { "ACTUAL", w_actual, "X", 0, -1, 0, "( loc -- ) or ( PAR: name )", "actual position now into a host location, or into a controller location" },
    { "TOOL", w_tool, "L", 0, -1, 0, "( loc -- )", "set the tool transform from a location" },
    { "BASE-OFFSET", w_base_offset, "RRRR", 0, -1, 0, "( F: dX dY dZ dO -- )", "where the user's world frame sits on the arm's base" },
    /* I-5 arm state */
    { "ARM", w_arm, "I", 0, -1, 0, "( flag -- )", "arm power relay on (true) or off" },
    { "LIMP", w_int1, "I", 0, CMD(LIMP), 1, "( axis# -- )", "limp one axis (0 = all)" },
    { "NOLIMP", w_plain, "", 0, CMD(NOLIMP), 0, "( -- )", "servo control on again after LIMP" },
    { "LOCK", w_int1, "I", 0, CMD(LOCK), 2, "( axis# -- )", "lock one axis" },
    { "UNLOCK", w_int1, "I", 0, CMD(UNLOCK), 1, "( axis# -- )", "unlock one axis (0 = all)" },
    { "SPEED", w_int1, "I", 0, CMD(SPEED), 4, "( speed -- )", "speed of later moves, percent of full" },
    { "GAIN", w_gain, "IR", 0, -1, 0, "( motor# -- ) ( F: value -- )", "position gain of a motor (0 = all)" },
    { "MANUAL", w_plain, "", 0, CMD(MANUAL), 0, "( -- )", "teach-pendant manual mode on" },
    { "NOMANUAL", w_plain, "", 0, CMD(NOMANUAL), 0, "( -- )", "manual mode off" },
    { "NOTEACH", w_plain, "", 0, CMD(NOTEACH), 0, "( -- )", "teach mode off" },
    { "NOHELP", w_plain, "", 0, CMD(NOHELP), 0, "( -- )", "controller syntax help off" },
    { "FLASH", w_int1, "I", 0, CMD(FLASH), 5, "( interval -- )", "flash the teach-pendant lamp" },
    { "NOFLASH", w_plain, "", 0, CMD(NOFLASH), 0, "( -- )", "pendant lamp off" },
    { "XCAL", w_int1, "I", 0, CMD(XCAL), 3, "( axis# -- )", "store the home position of an extra axis" },
    { "XHOME", w_int1, "I", 0, CMD(XHOME), 3, "( axis# -- )", "home an extra axis" },
    { "XZERO", w_int1, "I", 0, CMD(XZERO), 3, "( axis# -- )", "zero an extra axis's position register" },
    /* I-5 gripper */
    { "GRIP", w_grip, "IR", 0, -1, 0, "( torque -- ) ( F: distance -- )", "servo gripper to an opening with a force" },
    { "CLOSE-GRIP", w_plain, "", 0, CMD(CLOSE), 0, "( -- )", "close the gripper" },
    { "WGRIP", w_wgrip, "S", 0, -1, 0, "( c-addr u -- ) or ( PAR: variable )", "gripper opening into a controller variable" },
    /* I-5 I/O */
    { "OUTPORT", w_outport, "I", 0, -1, 0, "( output# -- )", "set output n on (-n: off)" },
    { "OUT2BYTE", w_out2byte, "I", 0, -1, 0, "( n -- )", "set outputs 1..16 from the 16 bits of n" },
    { "SHIFT-RIGHT", w_shift_right, "I", 0, -1, 0, "( n -- n' b )", "n shifted right one bit, and the bit shifted out" },
    { "WAITPORT", w_waitport, "I", 0, -1, 0, "( input# -- )", "controller waits until input n is on (-n: off)" },
    /* I-5 display */
    { "W0", w_show, "", 0, CMD(W0), 0, "( -- )", "show the commanded position (pulses, joints, world)" },
    { "W1", w_stream, "", 0, CMD(W1), 0, "( -- )", "show the actual position in pulses, 10 readings" },
    { "W2", w_show, "", 0, CMD(W2), 0, "( -- )", "show the actual position (pulses, joints, world)" },
    { "W3", w_stream, "", 0, CMD(W3), 0, "( -- )", "show the commanded position in pulses, 10 readings" },
    { "W4", w_show, "", 0, CMD(W4), 0, "( -- )", "show the end point of the current path" },
    { "W5", w_stream, "", 0, CMD(W5), 0, "( -- )", "show the velocity, 10 readings" },
    { "WE1", w_stream, "", 0, CMD(WE1), 0, "( -- )", "show the extra axis's actual position, 10 readings" },
    { "WE3", w_stream, "", 0, CMD(WE3), 0, "( -- )", "show the extra axis's commanded position, 10 readings" },
    { "WE5", w_stream, "", 0, CMD(WE5), 0, "( -- )", "show the extra axis's velocity, 10 readings" },
    { "ROBOT-STATUS", w_show, "", 0, CMD(STATUS), 0, "( -- )", "show the controller's STATUS block" },
    { "SERIAL", w_show, "", 0, CMD(SERIAL), 0, "( -- )", "show the controller's serial settings" },
    { "CONFIG", w_config, "IICIICI", 0, -1, 0, "( dev baud parity #data #stop handshake echo -- )", "configure a controller serial channel" },
    /* I-5 controller variables and locations */
    { "TYPEINT", w_typevar, "S", 0, 0, 0, "( c-addr u -- ) or ( PAR: variable )", "print a controller variable as an integer" },
    { "TYPEREAL", w_typevar, "S", 0, 0, 1, "( c-addr u -- ) or ( PAR: variable )", "print a controller variable as a real" },
    { "RAPL-INT@", w_typevar, "S", 0, 1, 0, "( c-addr u -- n )", "a controller variable's value as an integer" },
    { "RAPL-REAL@", w_typevar, "S", 0, 0, 2, "( c-addr u -- ) ( F: -- r )", "a controller variable's value as a real" },
    { "RAPL", w_rapl, "T", 0, -1, 0, "( PAR: text ) or ( c-addr u -- )", "send a line to the controller as it is; show its output" },
    { "SET-RAPL-REAL", w_set_var, "SR", 0, -1, 1, "( PAR: variable value ) or ( c-addr u -- ) ( F: r -- )", "set a controller variable to a real" },
    { "SET-RAPL-INT", w_set_var, "SI", 0, -1, 0, "( PAR: variable value ) or ( c-addr u n -- )", "set a controller variable to an integer" },
    { "RAPL-ANALOG", w_analog, "IS", 0, -1, 0, "( PAR: input# variable ) or ( n c-addr u -- )", "read analog input n (1..8, volts) into a controller variable" },
    { "RAPL-HERE", w_name1, "S", 0, CMD(HERE), 0, "( PAR: name ) or ( c-addr u -- )", "store the arm's position in a controller location" },
    { "RAPL-RUN", w_name1, "S", 0, CMD(RUN), 0, "( PAR: program ) or ( c-addr u -- )", "run a RAPL program stored in the controller" },
    { "RAPL-SET", w_name2, "SS", 0, CMD(SET), 0, "( PAR: loc1 loc2 ) or ( c-addr1 u1 c-addr2 u2 -- )", "controller location loc1 := loc2" },
    { "RAPL-SHIFTA", w_name2, "SS", 0, CMD(SHIFTA), 0, "( PAR: loc1 loc2 ) or ( c-addr1 u1 c-addr2 u2 -- )", "shift controller location loc1 by loc2's components" },
    { "RAPL-POINT", w_rapl_point, "SL", 0, -1, 0, "( PAR: rapl-loc fbrl-loc ) or ( c-addr u loc -- )", "define a controller location from a host location (mapped)" },
    { "RAPL-ERROR", w_rapl_error, "", 0, -1, 0, "( -- n )", "code of the controller's last error seen by a robot word (-1 none)" },
    { "GET-CAL-POINTS", w_get_cal_points, "I", 0, -1, 0, "( cal -- )", "teach the 3 calibration points from the arm's positions" },
    /* I-6 */
    { "GETREAL", w_getreal, "", 0, -1, 0, "( \"number\" -- ) ( F: -- r )", "read a real (literal or constant) from the input" },
    { "GETINT", w_getint, "", 0, -1, 0, "( \"number\" -- n )", "read an integer (literal or constant) from the input" },
    { "GETSTRING", w_getstring, "", 0, -1, 0, "( \"text\" -- c-addr u )", "read a word or a \"quoted text\" from the input" },
    /* I-8 */
    { "SEND-COM", w_send_com, "I", 0, -1, 0, "( command# -- )", "start a command line with the RAPL command of that number" },
    { "SEND-REAL", w_send_real, "R", 0, -1, 0, "( F: r -- )", "add a real to the command line" },
    { "SEND-INT", w_send_int, "I", 0, -1, 0, "( n -- )", "add an integer to the command line" },
    { "SEND-TEXT", w_send_text, "S", 0, -1, 1, "( c-addr u -- )", "add a name or text to the command line" },
    { "SEND-COMMA", w_send_const, "", 0, -1, (intptr_t)",", "( -- )", "add a comma to the command line" },
    { "SEND-STRT", w_send_const, "", 0, -1, (intptr_t)",S", "( -- )", "add the straight-line suffix ,S" },
    { "SEND-LOC", w_send_loc, "L", 0, -1, 0, "( loc -- )", "add a location's six components (mapped)" },
    { "SEND-CR", w_send_cr, "", 0, -1, 0, "( -- )", "send the command line (echo-verified) and show its output" },
};

fbrl_status fbrl_robot_install(fbrl_vm *vm, fbrl_robot *r, fbrl_link *link, fbrl_glossary *g)
{
    fbrl_hdr *h;
    if (!vm || !r) return FBRL_EINVAL;
    memset(r, 0, sizeof *r);
    r->vm = vm;
    r->g = g;
    r->last_error = -1;
    fbrl_uart_config def = FBRL_UART_CONFIG_DEFAULT;
    r->comm = def;
    if (vm->defining) return FBRL_ESTATE;
    /* GET-CAL-POINTS' line buffer lives in the data space: the words it runs parse it */
    if (fbrl__new_word(vm, "(ROBOT-TIB)", 11, K_VAR, "( -- a )", "robot words' line buffer", &h) ||
        fbrl__allot(vm, FBRL_ROBOT_TIB))
        return FBRL_ENOMEM;
    r->tib = h->body;
    memset((void *)h->body, 0, FBRL_ROBOT_TIB);
    fbrl_status st = rb_define(r, robot_words, sizeof robot_words / sizeof robot_words[0]);
    if (st == FBRL_OK) st = rb_install_comm(r);
    if (st == FBRL_OK) st = rb_install_io(r);
    if (st == FBRL_OK) st = fbrl_robot_set_link(r, link);
    return st == FBRL_ENOSPC ? FBRL_ENOMEM : st;
}

fbrl_status fbrl_robot_set_link(fbrl_robot *r, fbrl_link *link)
{
    if (!r) return FBRL_EINVAL;
    r->link = link;
    if (link && link->u) fbrl_uart_get_config(link->u, &r->comm);
    rb_port_writer(r);
    return FBRL_OK;
}

int fbrl_robot_last_error(const fbrl_robot *r) { return r ? r->last_error : -1; }
