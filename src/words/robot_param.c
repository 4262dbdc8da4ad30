/* SPDX-License-Identifier: MIT */
/* robot_param.c - thesis 5.3 and I-6: a robot word's parameters, from the stacks or
 * from the input after the word (one rule, docs/robot.md), their checks, and the words
 * GETREAL GETINT GETSTRING. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "robot_internal.h"

/* ---- parameters: the robot's kinds on the engine's one parser (vmx.h) ---- */

/* The robot's parameter letters: those of vmx.h, and L (a location), X (a location, or a
 * controller location's name), A (a device); each with what an error message calls it. */
static char vmx_kind(char kind, const char **what)
{
    switch (kind) {
    case 'L': *what = "a location name"; return 'A';
    case 'X': *what = "a location or controller location name"; return 'N';
    case 'A': *what = "a device name"; return 'A';
    default: *what = NULL; return kind;
    }
}

fbrl_status rb_parse_param(fbrl_robot *r, const rb_word *w, char kind, rb_val *v)
{
    const char *what;
    char k = vmx_kind(kind, &what);
    return fbrl_vmx_arg_parse(r->vm, w->name, k, what, v);
}

/* The one rule (docs/robot.md): when the stacks hold enough values for every
 * parameter, they come from the stacks; otherwise all of them are read from the
 * input after the word, in the order of the stack effect. */
unsigned rb_naxes(const fbrl_robot *r)
{
    unsigned n = FBRL_RAPL_ARM_AXES_MIN;
    if (r->link && fbrl_link_get_naxes(r->link, &n) != FBRL_OK)
        n = FBRL_RAPL_ARM_AXES_MIN;
    return n;
}

fbrl_status rb_params(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    char spec[RB_MAXP + 1];
    const char *what[RB_MAXP];
    size_t np = 0;
    for (const char *p = w->spec; *p; p++) {
        size_t rep = *p == 'J' ? rb_naxes(r) : 1; /* J: the joint values, one per axis */
        for (size_t k = 0; k < rep; k++, np++) {
            if (np >= RB_MAXP)
                return FBRL_EINVAL;
            spec[np] = vmx_kind(*p == 'J' ? 'R' : *p, &what[np]);
        }
    }
    spec[np] = '\0';
    return fbrl_vmx_args(r->vm, w->name, spec, what, FBRL_VMX_LINE, v);
}

fbrl_status rb_fetch(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    memset(v, 0, RB_MAXP * sizeof *v);
    return rb_params(r, w, v);
}

/* Copy a name parameter into a C string (controller names are short). */
fbrl_status rb_name_arg(fbrl_robot *r, const rb_word *w, const rb_val *v, char *buf, size_t cap)
{
    if (v->n == 0 || v->n >= cap) {
        char msg[96];
        snprintf(msg, sizeof msg, "%s: controller name must be 1..%u characters", w->name,
                 (unsigned)(cap - 2));
        return rb_fail(r, FBRL_VM_THROW_OF_STATUS(FBRL_ENAME), msg);
    }
    memcpy(buf, v->s, v->n);
    buf[v->n] = '\0';
    return FBRL_OK;
}

fbrl_status rb_range(fbrl_robot *r, const rb_word *w, const char *what, fbrl_cell v, fbrl_cell lo,
                     fbrl_cell hi)
{
    if (v >= lo && v <= hi)
        return FBRL_OK;
    char msg[96];
    snprintf(msg, sizeof msg, "%s: %s %ld outside %ld..%ld", w->name, what, (long)v, (long)lo, (long)hi);
    return rb_fail(r, FBRL_THROW_BAD_NUMBER, msg);
}

fbrl_status rb_finite(fbrl_robot *r, const rb_word *w, const rb_val *v, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (!isfinite(v[k].f) || fabs(v[k].f) > FBRL_RAPL_REAL_MAX) {
            char msg[96];
            snprintf(msg, sizeof msg, "%s: number out of range (NaN, infinite or too large)", w->name);
            return rb_fail(r, FBRL_VM_THROW_OF_STATUS(FBRL_ERANGE), msg);
        }
    return FBRL_OK;
}

/* ---- I-6 words ---- */

static fbrl_status w_getreal(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_status st = rb_parse_param(r, w, 'R', v);
    if (st != FBRL_OK)
        return st;
    return fbrl_vm_fpush(r->vm, v[0].f) == FBRL_OK ? FBRL_OK : rb_fail(r, FBRL_THROW_FSTACK_OVERFLOW, NULL);
}

static fbrl_status w_getint(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_status st = rb_parse_param(r, w, 'I', v);
    if (st != FBRL_OK)
        return st;
    return fbrl_vm_push(r->vm, v[0].i) == FBRL_OK ? FBRL_OK : rb_fail(r, FBRL_THROW_STACK_OVERFLOW, NULL);
}

static fbrl_status w_getstring(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_status st = rb_parse_param(r, w, 'S', v);
    if (st != FBRL_OK)
        return st;
    if (fbrl_vm_push(r->vm, (fbrl_cell)v[0].s) || fbrl_vm_push(r->vm, (fbrl_cell)v[0].n))
        return rb_fail(r, FBRL_THROW_STACK_OVERFLOW, NULL);
    return FBRL_OK;
}

const rb_word rb_param_words[] = {
    {"GETREAL", w_getreal, "", 0, -1, 0,
     FBRL_DOC("( \"number\" -- ) ( F: -- r )", "read a real (literal or constant) from the input")},
    {"GETINT", w_getint, "", 0, -1, 0,
     FBRL_DOC("( \"number\" -- n )", "read an integer (literal or constant) from the input")},
    {"GETSTRING", w_getstring, "", 0, -1, 0,
     FBRL_DOC("( \"text\" -- c-addr u )", "read a word or a \"quoted text\" from the input")},
};
const size_t rb_param_nwords = sizeof rb_param_words / sizeof rb_param_words[0];
