/* SPDX-License-Identifier: MIT */
/* method.c - the method words: METHOD PARAM SAMPLES-PARAM STEP SAMPLE-STEP ON-ABORT
 * USE-PARAMS END-METHOD declare a method; METHODS .METHOD PARAM! show and set it at the
 * prompt (include/fbrl/method.h). A run of one is src/method_run.c's. */
#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include "fbrl/method.h"
#include "fbrl/vmx.h"

static const fbrl_vmx_type method_type = {"method", (fbrl_cell)0x4d455448}; /* "METH" */
static const fbrl_vmx_type param_type = {"method parameter", (fbrl_cell)0x50415241};

static fbrl_status fail(fbrl_vm *vm, int code, const char *fmt, const char *a, const char *b)
{
    return fbrl_vmx_throwf(vm, code, fmt, a, b);
}

static int same_name(const char *a, const char *b, size_t n)
{
    size_t i;
    for (i = 0; i < n && a[i]; i++)
        if (toupper((unsigned char)a[i]) != toupper((unsigned char)b[i]))
            return 0;
    return i == n && a[i] == '\0';
}

static void copy_text(char *dst, size_t cap, const char *s, size_t n)
{
    if (n >= cap)
        n = cap - 1;
    memcpy(dst, s, n);
    dst[n] = '\0';
}

/* The next name after the word, copied; throws if there is none or it is too long. */
static fbrl_status parse_name(fbrl_vm *vm, const char *word, const char *what, char *out, size_t cap,
                              size_t *len)
{
    const char *s;
    size_t n;
    fbrl_status st = fbrl_vm_parse_name(vm, &s, &n);
    if (st != FBRL_OK)
        return st;
    if (n == 0)
        return fail(vm, FBRL_THROW_NO_NAME, "%s: %s missing", word, what);
    if (n >= cap)
        return fail(vm, FBRL_THROW_NAME_TOO_LONG, "%s: %s too long", word, what);
    memcpy(out, s, n);
    out[n] = '\0';
    *len = n;
    return FBRL_OK;
}

static fbrl_status rest_of_line(fbrl_vm *vm, char *out, size_t cap)
{
    const char *s;
    size_t n;
    fbrl_status st = fbrl_vmx_parse_line(vm, &s, &n);
    if (st == FBRL_OK)
        copy_text(out, cap, s, n);
    return st;
}

static fbrl_status declaring(fbrl_method_set *s, const char *word, fbrl_method **m)
{
    *m = s->current;
    if (s->current == NULL)
        return fail(s->vm, FBRL_THROW_BAD_NAME_ARG, "%s: no method is being declared (METHOD name first)%s",
                    word, "");
    return FBRL_OK;
}

static fbrl_method *method_of(fbrl_method_set *s, fbrl_cell addr)
{
    fbrl_cell *p = fbrl_vmx_data(s->vm, addr, &method_type, sizeof(fbrl_cell));
    fbrl_cell i;
    if (p == NULL)
        return NULL;
    memcpy(&i, p, sizeof i);
    return i >= 0 && (size_t)i < s->count && s->methods[i].addr == addr ? &s->methods[i] : NULL;
}

/* METHOD ( "name" "text" -- ): a method of that name declared again (a method file
 * loaded again) is replaced. */
static fbrl_status w_method(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_method_set *s = ctx;
    char name[FBRL_METHOD_NAME_MAX + 1];
    size_t len, i;
    fbrl_cell addr, index;
    void *payload;
    (void)word;
    if (s->running)
        return fail(vm, FBRL_THROW_BAD_NAME_ARG, "METHOD: %s is running%s", s->running->name, "");
    fbrl_status st = parse_name(vm, "METHOD", "the method's name", name, sizeof name, &len);
    if (st != FBRL_OK)
        return st;
    for (i = 0; i < s->count && !same_name(s->methods[i].name, name, len); i++)
        ;
    if (i == FBRL_METHOD_MAX)
        return fail(vm, FBRL_VM_THROW_OF_STATUS(FBRL_EFULL), "METHOD: %s: too many methods%s", name, "");
    index = (fbrl_cell)i;
    st = fbrl_vmx_create(vm, name, len, &method_type, sizeof(fbrl_cell), NULL, s, "( -- method )",
                         "a method: RUN-METHOD runs it, .METHOD shows it", &addr, &payload);
    if (st != FBRL_OK)
        return st;
    memcpy(payload, &index, sizeof index);
    fbrl_method *m = &s->methods[i];
    memset(m, 0, sizeof *m);
    memcpy(m->name, name, len + 1);
    m->samples = -1;
    m->addr = addr;
    if (i == s->count)
        s->count++;
    s->current = m;
    return rest_of_line(vm, m->text, sizeof m->text);
}

static fbrl_status w_param_run(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_cell v;
    (void)ctx;
    memcpy(&v, (const unsigned char *)word + FBRL_VMX_PAYLOAD, sizeof v);
    return fbrl_vmx_push(vm, v);
}

/* PARAM / SAMPLES-PARAM ( min max default "name" "unit" "text" -- ) */
static fbrl_status w_param(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_method_set *s = ctx;
    const fbrl_vmx_reg *w = word;
    const char *wname = w->name;
    fbrl_vmx_val v[3];
    char name[FBRL_METHOD_NAME_MAX + 1], unit[FBRL_METHOD_UNIT_MAX + 1];
    size_t len, ulen;
    void *payload;
    fbrl_method *m;
    fbrl_status dst = declaring(s, wname, &m);
    if (dst != FBRL_OK)
        return dst;
    fbrl_status st = fbrl_vmx_check(vm, w, v);
    if (st == FBRL_OK)
        st = parse_name(vm, wname, "the parameter's name", name, sizeof name, &len);
    if (st == FBRL_OK)
        st = parse_name(vm, wname, "the parameter's unit", unit, sizeof unit, &ulen);
    if (st != FBRL_OK)
        return st;
    if (m->nparams == FBRL_METHOD_MAX_PARAMS)
        return fail(vm, FBRL_VM_THROW_OF_STATUS(FBRL_EFULL), "%s: %s: too many parameters", wname, name);
    if (v[0].i > v[1].i || v[2].i < v[0].i || v[2].i > v[1].i)
        return fbrl_vmx_throwf(vm, FBRL_THROW_BAD_NUMBER, "%s: %s: default %ld outside %ld..%ld", wname, name,
                               (long)v[2].i, (long)v[0].i, (long)v[1].i);
    if (w->arg && m->samples >= 0)
        return fail(vm, FBRL_THROW_BAD_NAME_ARG, "%s: %s: the method has a sample count already", wname,
                    name);
    fbrl_method_param *p = &m->params[m->nparams];
    memset(p, 0, sizeof *p);
    memcpy(p->name, name, len + 1);
    memcpy(p->unit, unit, ulen + 1);
    p->min = (long)v[0].i;
    p->max = (long)v[1].i;
    p->def = (long)v[2].i;
    st = rest_of_line(vm, p->text, sizeof p->text);
    if (st == FBRL_OK)
        st = fbrl_vmx_create(vm, name, len, &param_type, sizeof(fbrl_cell), w_param_run, s, "( -- n )",
                             p->text, &p->addr, &payload);
    if (st != FBRL_OK)
        return st;
    memcpy(payload, &v[2].i, sizeof v[2].i);
    if (w->arg)
        m->samples = (int)m->nparams;
    m->nparams++;
    return FBRL_OK;
}

/* STEP / SAMPLE-STEP ( xt "name" "text" -- ) */
static fbrl_status w_step(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_method_set *s = ctx;
    const fbrl_vmx_reg *w = word;
    const char *wname = w->name;
    fbrl_vmx_val v[1];
    char name[FBRL_METHOD_NAME_MAX + 1];
    size_t len;
    fbrl_method *m;
    fbrl_status dst = declaring(s, wname, &m);
    if (dst != FBRL_OK)
        return dst;
    fbrl_status st = fbrl_vmx_check(vm, w, v);
    if (st == FBRL_OK)
        st = parse_name(vm, wname, "the step's name", name, sizeof name, &len);
    if (st != FBRL_OK)
        return st;
    if (m->nsteps == FBRL_METHOD_MAX_STEPS)
        return fail(vm, FBRL_VM_THROW_OF_STATUS(FBRL_EFULL), "%s: %s: too many steps", wname, name);
    if (w->arg && m->samples < 0)
        return fail(vm, FBRL_THROW_BAD_NAME_ARG, "%s: %s: the method has no SAMPLES-PARAM", wname, name);
    if (v[0].i == 0)
        return fail(vm, FBRL_THROW_BAD_NUMBER, "%s: %s: no word given (' WORD STEP name)", wname, name);
    fbrl_method_step *p = &m->steps[m->nsteps];
    memset(p, 0, sizeof *p);
    memcpy(p->name, name, len + 1);
    p->xt = v[0].i;
    p->per_sample = w->arg != 0;
    st = rest_of_line(vm, p->text, sizeof p->text);
    if (st == FBRL_OK)
        m->nsteps++;
    return st;
}

/* ON-ABORT ( xt -- ) */
static fbrl_status w_on_abort(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_method_set *s = ctx;
    fbrl_vmx_val v[1];
    fbrl_method *m;
    fbrl_status dst = declaring(s, "ON-ABORT", &m);
    if (dst != FBRL_OK)
        return dst;
    fbrl_status st = fbrl_vmx_check(vm, word, v);
    if (st == FBRL_OK)
        m->abort_xt = v[0].i;
    return st;
}

static fbrl_status method_arg(fbrl_method_set *s, const void *word, fbrl_method **out);

/* USE-PARAMS ( method -- ): the parameters of another method, shared (the same words,
 * so the steps of that method see the values set here); for a method composed of its steps */
static fbrl_status w_use_params(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_method_set *s = ctx;
    fbrl_method *m, *from = NULL;
    fbrl_status st = declaring(s, "USE-PARAMS", &m);
    if (st == FBRL_OK)
        st = method_arg(s, word, &from);
    if (st != FBRL_OK)
        return st;
    if (from == m)
        return fail(vm, FBRL_THROW_BAD_NAME_ARG, "USE-PARAMS: %s is the method being declared%s", m->name,
                    "");
    if (m->nparams + from->nparams > FBRL_METHOD_MAX_PARAMS)
        return fail(vm, FBRL_VM_THROW_OF_STATUS(FBRL_EFULL), "USE-PARAMS: %s: too many parameters%s", m->name,
                    "");
    if (from->samples >= 0 && m->samples >= 0)
        return fail(vm, FBRL_THROW_BAD_NAME_ARG, "USE-PARAMS: %s has a sample count already%s", m->name, "");
    if (from->samples >= 0)
        m->samples = (int)m->nparams + from->samples;
    memcpy(&m->params[m->nparams], from->params, from->nparams * sizeof from->params[0]);
    m->nparams += from->nparams;
    return FBRL_OK;
}

/* END-METHOD ( -- ) */
static fbrl_status w_end_method(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_method_set *s = ctx;
    fbrl_method *m;
    (void)word;
    fbrl_status dst = declaring(s, "END-METHOD", &m);
    if (dst != FBRL_OK)
        return dst;
    if (m->nsteps == 0)
        return fail(vm, FBRL_THROW_BAD_NAME_ARG, "END-METHOD: %s has no steps%s", m->name, "");
    m->complete = 1;
    s->current = NULL;
    return FBRL_OK;
}

/* The word's method parameter (its row's spec "A", given or typed after it). */
static fbrl_status method_arg(fbrl_method_set *s, const void *word, fbrl_method **out)
{
    fbrl_vmx_val v[1];
    fbrl_status st = fbrl_vmx_check(s->vm, word, v);
    if (st != FBRL_OK)
        return st;
    *out = method_of(s, v[0].i);
    if (*out == NULL)
        return fail(s->vm, FBRL_THROW_TYPE_MISMATCH, "%s: not a method%s", ((const fbrl_vmx_reg *)word)->name,
                    "");
    return FBRL_OK;
}

long fbrl_method_step_runs(const fbrl_method_set *s, const fbrl_method *m, size_t k)
{
    long n = 0;
    if (s == NULL || m == NULL || k >= m->nsteps)
        return 0;
    if (!m->steps[k].per_sample)
        return 1;
    return fbrl_method_param_get(s, m, (size_t)m->samples, &n) == FBRL_OK ? n : 0;
}

static void say(fbrl_vm *vm, const char *s) { fbrl_vmx_puts(vm, s); }

/* METHODS ( -- ) */
static fbrl_status w_methods(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_method_set *s = ctx;
    char line[FBRL_METHOD_NAME_MAX + FBRL_METHOD_TEXT_MAX + 16];
    (void)word;
    if (s->count == 0)
        say(vm, "no methods declared\n");
    for (size_t i = 0; i < s->count; i++) {
        snprintf(line, sizeof line, "%-16s %s%s\n", s->methods[i].name, s->methods[i].text,
                 s->methods[i].complete ? "" : " (incomplete)");
        say(vm, line);
    }
    return FBRL_OK;
}

/* .METHOD ( method -- ) */
static fbrl_status w_dot_method(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_method_set *s = ctx;
    fbrl_method *m = NULL;
    char line[256];
    fbrl_status st = method_arg(s, word, &m);
    if (st != FBRL_OK)
        return st;
    snprintf(line, sizeof line, "%s - %s\n", m->name, m->text);
    say(vm, line);
    for (size_t k = 0; k < m->nparams; k++) {
        const fbrl_method_param *p = &m->params[k];
        long v = 0;
        fbrl_method_param_get(s, m, k, &v);
        snprintf(line, sizeof line, "  %-14s %6ld %-8s (%ld..%ld, default %ld) %s\n", p->name, v, p->unit,
                 p->min, p->max, p->def, p->text);
        say(vm, line);
    }
    for (size_t k = 0; k < m->nsteps; k++) {
        snprintf(line, sizeof line, "  %2zu. %-14s %s%s\n", k + 1, m->steps[k].name,
                 m->steps[k].per_sample ? "[each sample] " : "", m->steps[k].text);
        say(vm, line);
    }
    return FBRL_OK;
}

/* PARAM! ( n "name" -- ): set a parameter with its range checked */
static fbrl_status w_param_store(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_method_set *s = ctx;
    fbrl_vmx_val v[1];
    char name[FBRL_METHOD_NAME_MAX + 1];
    size_t len;
    fbrl_status st = fbrl_vmx_check(vm, word, v);
    if (st == FBRL_OK)
        st = parse_name(vm, "PARAM!", "a parameter's name", name, sizeof name, &len);
    if (st != FBRL_OK)
        return st;
    for (size_t i = s->count; i-- > 0;)
        for (size_t k = 0; k < s->methods[i].nparams; k++) {
            const fbrl_method_param *p = &s->methods[i].params[k];
            if (!same_name(p->name, name, len))
                continue;
            st = fbrl_method_param_set(s, &s->methods[i], k, (long)v[0].i);
            if (st == FBRL_ERANGE)
                return fbrl_vmx_throwf(vm, FBRL_THROW_BAD_NUMBER, "PARAM!: %s: %ld outside %ld..%ld %s",
                                       p->name, (long)v[0].i, p->min, p->max, p->unit);
            if (st == FBRL_ESTATE)
                return fail(vm, FBRL_THROW_BAD_NAME_ARG, "PARAM!: %s: %s is running", p->name,
                            s->methods[i].name);
            return st;
        }
    return fail(vm, FBRL_THROW_UNDEFINED, "PARAM!: %s: no such method parameter%s", name, "");
}

/* The rows (vmx.h): arg 1 is the SAMPLE- variant. */
static const fbrl_vmx_reg words[] = {
    {"METHOD", w_method, "", 0, 0, 0,
     FBRL_DOC("( \"name\" \"text\" -- )", "declare a method: its name, then a description")},
    {"PARAM", w_param, "III", 0, 0, 0,
     FBRL_DOC("( min max default \"name\" \"unit\" \"text\" -- )",
              "declare a parameter of the method being declared (name pushes its value)")},
    {"SAMPLES-PARAM", w_param, "III", 0, 0, 1,
     FBRL_DOC("( min max default \"name\" \"unit\" \"text\" -- )",
              "declare the parameter that counts the samples (SAMPLE-STEP runs once per sample)")},
    {"STEP", w_step, "I", 0, 0, 0,
     FBRL_DOC("( xt \"name\" \"text\" -- )", "declare a named step: the word runs once per run")},
    {"SAMPLE-STEP", w_step, "I", 0, 0, 1,
     FBRL_DOC("( xt \"name\" \"text\" -- )",
              "declare a named step run once per sample with ( index -- ), index 0..")},
    {"ON-ABORT", w_on_abort, "I", 0, 0, 0,
     FBRL_DOC("( xt -- )", "the word that takes the arm to a safe place after an abort")},
    {"USE-PARAMS", w_use_params, "A", FBRL_VMX_PARSE, 0, 0,
     FBRL_DOC("( method -- )", "share another method's parameters (a method composed of its steps)")},
    {"END-METHOD", w_end_method, "", 0, 0, 0, FBRL_DOC("( -- )", "end the method's declaration")},
    {"METHODS", w_methods, "", 0, 0, 0, FBRL_DOC("( -- )", "list the declared methods")},
    {".METHOD", w_dot_method, "A", FBRL_VMX_PARSE, 0, 0,
     FBRL_DOC("( method -- )", "show a method's parameters and steps")},
    {"PARAM!", w_param_store, "I", 0, 0, 0,
     FBRL_DOC("( n \"name\" -- )", "set a method parameter, its range checked")},
};

fbrl_status fbrl_method_install(fbrl_vm *vm, fbrl_method_set *s)
{
    if (vm == NULL || s == NULL)
        return FBRL_EINVAL;
    /* Not the methods themselves: METHOD clears each as it is declared, and clearing all of
     * them here would make a static set's 92 KB resident for nothing. */
    s->vm = vm;
    s->count = 0;
    s->current = NULL;
    s->running = NULL;
    return fbrl_vmx_define_table(vm, words, sizeof words / sizeof words[0], s);
}

const fbrl_method *fbrl_method_at(const fbrl_method_set *s, size_t i)
{
    return s != NULL && i < s->count ? &s->methods[i] : NULL;
}

const fbrl_method *fbrl_method_find(const fbrl_method_set *s, const char *name)
{
    for (size_t i = 0; s != NULL && name != NULL && i < s->count; i++)
        if (same_name(s->methods[i].name, name, strlen(name)))
            return &s->methods[i];
    return NULL;
}

static fbrl_cell *param_cell(const fbrl_method_set *s, const fbrl_method *m, size_t k)
{
    if (s == NULL || m == NULL || k >= m->nparams)
        return NULL;
    return fbrl_vmx_data(s->vm, m->params[k].addr, &param_type, sizeof(fbrl_cell));
}

fbrl_status fbrl_method_param_get(const fbrl_method_set *s, const fbrl_method *m, size_t k, long *v)
{
    fbrl_cell *p = param_cell(s, m, k), c;
    if (p == NULL || v == NULL)
        return FBRL_EINVAL;
    memcpy(&c, p, sizeof c);
    *v = (long)c;
    return FBRL_OK;
}

fbrl_status fbrl_method_param_set(fbrl_method_set *s, const fbrl_method *m, size_t k, long v)
{
    fbrl_cell *p = param_cell(s, m, k), c = v;
    if (p == NULL)
        return FBRL_EINVAL;
    if (s->running == m)
        return FBRL_ESTATE;
    if (v < m->params[k].min || v > m->params[k].max)
        return FBRL_ERANGE;
    memcpy(p, &c, sizeof c);
    return FBRL_OK;
}
