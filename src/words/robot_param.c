/* robot_param.c - thesis 5.3 and I-6: a robot word's parameters, from the stacks or
 * from the input after the word (one rule, docs/robot.md), their checks, and the words
 * GETREAL GETINT GETSTRING. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "robot_internal.h"

/* ---- I-6: parameters after the word ---- */

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
        while (src && *vm->toin >= 0 && (size_t)*vm->toin < src->len && rb_blank(src->buf[*vm->toin]))
            ++*vm->toin;
        fbrl__parse(vm, '\0', &s, &n, &found);
        while (n > 0 && rb_blank(s[n - 1])) n--;
    } else if (kind == 'S') { /* GETSTRING: a "quoted text" or one word */
        fbrl_src *src = vm->nsrc ? fbrl__src(vm) : NULL;
        while (src && *vm->toin >= 0 && (size_t)*vm->toin < src->len && rb_blank(src->buf[*vm->toin]))
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
fbrl_status rb_params(fbrl_robot *r, const rb_word *w, rb_val *v)
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
fbrl_status rb_name_arg(fbrl_robot *r, const rb_word *w, const rb_val *v, char *buf, size_t cap)
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

fbrl_status rb_range(fbrl_robot *r, const rb_word *w, const char *what, fbrl_cell v, fbrl_cell lo, fbrl_cell hi)
{
    if (v >= lo && v <= hi) return FBRL_OK;
    char msg[96];
    snprintf(msg, sizeof msg, "%s: %s %ld outside %ld..%ld", w->name, what, (long)v, (long)lo, (long)hi);
    return rb_fail(r, -24, msg);
}

fbrl_status rb_finite(fbrl_robot *r, const rb_word *w, const rb_val *v, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (!isfinite(v[k].f) || fabs(v[k].f) > FBRL_RAPL_REAL_MAX) {
            char msg[96];
            snprintf(msg, sizeof msg, "%s: number out of range (NaN, infinite or too large)", w->name);
            return rb_fail(r, FBRL_THROW_STATUS(FBRL_ERANGE), msg);
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

const rb_word rb_param_words[] = {
    { "GETREAL", w_getreal, "", 0, -1, 0, "( \"number\" -- ) ( F: -- r )", "read a real (literal or constant) from the input" },
    { "GETINT", w_getint, "", 0, -1, 0, "( \"number\" -- n )", "read an integer (literal or constant) from the input" },
    { "GETSTRING", w_getstring, "", 0, -1, 0, "( \"text\" -- c-addr u )", "read a word or a \"quoted text\" from the input" },
};
const size_t rb_param_nwords = sizeof rb_param_words / sizeof rb_param_words[0];
