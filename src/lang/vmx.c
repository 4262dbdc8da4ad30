/* SPDX-License-Identifier: MIT */
/* vmx.c - the extension interface for word sets (include/fbrl/vmx.h): the one place
 * where word sets meet the engine's insides (headers, input sources, the number parser). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include "words.h"

/* Every C word of a word set is a K_CFUNC header whose xfn runs instead of fn; fn is only
 * there because fbrl_vm_define() needs one. */
static fbrl_status never_called(fbrl_vm *vm, void *arg)
{
    (void)arg;
    return fbrl_vm_throw(vm, FBRL_THROW_UNSUPPORTED, NULL);
}

static fbrl_hdr *latest(fbrl_vm *vm) { return HDR(vm, vm->nwords - 1); }

fbrl_status fbrl_vmx_define(fbrl_vm *vm, const char *name, fbrl_vmx_fn fn, void *ctx, const void *word,
                            unsigned flags, const char *stack_effect, const char *help)
{
    if (!vm || !name || !fn || (flags & ~(FBRL_VMX_IMMEDIATE | FBRL_VMX_COMPILE_ONLY | FBRL_VMX_STATE_SMART)))
        return FBRL_EINVAL;
    fbrl_status st = fbrl_vm_define(vm, name, never_called, ctx, stack_effect, help);
    if (st != FBRL_OK)
        return st;
    fbrl_hdr *h = latest(vm);
    H_XFN(h) = fn;
    h->word = word;
    h->flags =
        (uint8_t)(((flags & FBRL_VMX_IMMEDIATE) ? FI : 0u) | ((flags & FBRL_VMX_COMPILE_ONLY) ? FC : 0u) |
                  ((flags & FBRL_VMX_STATE_SMART) ? FS : 0u));
    return FBRL_OK;
}

fbrl_status fbrl_vmx_define_table(fbrl_vm *vm, const fbrl_vmx_reg *rows, size_t n, void *ctx)
{
    if (!vm || (!rows && n))
        return FBRL_EINVAL;
    for (size_t i = 0; i < n; i++) {
        fbrl_status st =
            fbrl_vmx_define(vm, rows[i].name, rows[i].fn, ctx, &rows[i], rows[i].flags & ~FBRL_VMX_PARSE,
                            FBRL_DOC_STACK(rows[i]), FBRL_DOC_HELP(rows[i]));
        if (st != FBRL_OK)
            return st;
    }
    return FBRL_OK;
}

fbrl_status fbrl_vmx_name(const fbrl_vm *vm, fbrl_cell xt, const char **name, size_t *len)
{
    if (!vm || !name || !len)
        return FBRL_EINVAL;
    const fbrl_hdr *h = fbrl__xt_hdr(vm, xt);
    if (!h)
        return FBRL_ENOENT;
    *name = h->name;
    *len = h->len;
    return FBRL_OK;
}

fbrl_status fbrl_vmx_find(const fbrl_vm *vm, const char *name, size_t len, fbrl_cell *xt)
{
    if (!vm || !name || !xt)
        return FBRL_EINVAL;
    int i = fbrl__find(vm, name, len);
    if (i < 0)
        return FBRL_ENOENT;
    *xt = FBRL_XT_BASE + i;
    return FBRL_OK;
}

/* ---- typed data ---- */

static fbrl_cell align16(fbrl_cell a) { return (fbrl_cell)(((fbrl_ucell)a + 15) & ~(fbrl_ucell)15); }

fbrl_status fbrl_vmx_create(fbrl_vm *vm, const char *name, size_t len, const fbrl_vmx_type *type,
                            size_t bytes, fbrl_vmx_fn run, void *ctx, const char *stack_effect,
                            const char *help, fbrl_cell *addr, void **payload)
{
    if (!vm)
        return FBRL_EINVAL;
    unsigned char *here0 = vm->here;
    uint32_t nwords0 = vm->nwords;
    size_t head = type ? FBRL_VMX_PAYLOAD : 0;
    fbrl_hdr *h = NULL;
    int r = 0;
    if (bytes > (size_t)INTPTR_MAX - head)
        r = FBRL_THROW_DICT_OVERFLOW;
    else if (name)
        r = fbrl__new_word(vm, name, len, run ? K_CFUNC : K_VAR, stack_effect ? stack_effect : "",
                           help ? help : "", &h);
    else
        r = fbrl__create(vm, run ? K_CFUNC : K_VAR, stack_effect ? stack_effect : "", help ? help : "", &h);
    if (!r)
        r = fbrl__allot(vm, align16((fbrl_cell)vm->here) - (fbrl_cell)vm->here);
    if (!r) {
        h->body = (fbrl_cell)vm->here;
        r = fbrl__allot(vm, (fbrl_cell)(head + bytes));
    }
    if (r) { /* all or nothing: no half-made word, no data space used */
        if (vm->nwords != nwords0 || vm->here != here0)
            fbrl__forget(vm, here0, nwords0, vm->req_used);
        return fbrl_vm_throw(vm, r, NULL);
    }
    memset((void *)h->body, 0, head + bytes);
    if (type)
        memcpy((void *)h->body, &type->magic, sizeof type->magic);
    if (!run) {
        h->word = ctx; /* the word set's tag (fbrl_vmx_tag) */
    } else {
        H_FN(h) = never_called;
        H_XFN(h) = run;
        H_ARG(h) = ctx;
        h->word = (const void *)h->body;
    }
    if (addr)
        *addr = h->body;
    if (payload)
        *payload = (void *)(h->body + (fbrl_cell)head);
    return FBRL_OK;
}

void *fbrl_vmx_data(fbrl_vm *vm, fbrl_cell addr, const fbrl_vmx_type *type, size_t bytes)
{
    fbrl_cell m;
    if (!vm || !type || (fbrl_ucell)addr % 16 || bytes > (size_t)INTPTR_MAX - FBRL_VMX_PAYLOAD ||
        !fbrl__addr_ok(vm, addr, (fbrl_cell)(FBRL_VMX_PAYLOAD + bytes)))
        return NULL;
    memcpy(&m, (const void *)addr, sizeof m);
    return m == type->magic ? (void *)(addr + FBRL_VMX_PAYLOAD) : NULL;
}

fbrl_status fbrl_vmx_created(const fbrl_vm *vm, fbrl_cell xt, fbrl_vmx_fn run, fbrl_cell *addr)
{
    if (!vm || !addr)
        return FBRL_EINVAL;
    const fbrl_hdr *h = fbrl__xt_hdr(vm, xt);
    if (!h || (run ? (h->kind != K_CFUNC || H_XFN(h) != run) : h->kind != K_VAR))
        return FBRL_ETYPE;
    *addr = h->body;
    return FBRL_OK;
}

fbrl_status fbrl_vmx_tag(const fbrl_vm *vm, fbrl_cell xt, const void **tag, fbrl_cell *addr)
{
    if (!vm || !tag || !addr)
        return FBRL_EINVAL;
    const fbrl_hdr *h = fbrl__xt_hdr(vm, xt);
    if (!h || h->kind != K_VAR)
        return FBRL_ETYPE;
    *tag = h->word;
    *addr = h->body;
    return FBRL_OK;
}

fbrl_status fbrl_vmx_mark_here(const fbrl_vm *vm, fbrl_vmx_mark *m)
{
    if (!vm || !m)
        return FBRL_EINVAL;
    m->here = (fbrl_cell)vm->here;
    m->nwords = vm->nwords;
    m->required = vm->req_used;
    return FBRL_OK;
}

fbrl_status fbrl_vmx_forget(fbrl_vm *vm, const fbrl_vmx_mark *m)
{
    if (!vm || !m)
        return FBRL_EINVAL;
    if (vm->defining || m->nwords > vm->nwords || m->here > (fbrl_cell)vm->here ||
        m->here < (fbrl_cell)vm->data_lo)
        return FBRL_ESTATE;
    fbrl__forget(vm, (unsigned char *)m->here, m->nwords, m->required);
    return FBRL_OK;
}

/* ---- arguments ---- */

static int is_blank(char c) { return (unsigned char)c <= ' '; }

static fbrl_src *cur_src(fbrl_vm *vm) { return vm->nsrc ? fbrl__src(vm) : NULL; }

static void skip_blanks(fbrl_vm *vm)
{
    fbrl_src *src = cur_src(vm);
    while (src && *vm->toin >= 0 && (size_t)*vm->toin < src->len && is_blank(src->buf[*vm->toin]))
        ++*vm->toin;
}

/* A dictionary word that holds data (never code with side effects). */
static const fbrl_hdr *data_word(fbrl_vm *vm, const char *s, size_t n)
{
    int i = fbrl__find(vm, s, n);
    if (i < 0)
        return NULL;
    const fbrl_hdr *h = HDR(vm, i);
    switch (h->kind) {
    case K_CREATE: return H_DOES(h) ? NULL : h; /* a DOES> part is code: never run for a parameter */
    case K_VAR:
    case K_CONST:
    case K_VALUE:
    case K_FCONST:
    case K_FVALUE: return h;
    default: return NULL;
    }
}

/* Run a data word and take the one cell or (want_float) one float it leaves. */
static int data_value(fbrl_vm *vm, const fbrl_hdr *h, int want_float, fbrl_cell *c, double *f)
{
    size_t d0 = fbrl_vm_depth(vm), f0 = fbrl_vm_fdepth(vm);
    if (fbrl__run(vm, (fbrl_cell)(FBRL_XT_BASE + fbrl__hdr_index(vm, h))) != 0)
        return 0;
    size_t d1 = fbrl_vm_depth(vm), f1 = fbrl_vm_fdepth(vm);
    if (d1 == d0 + 1 && f1 == f0) {
        fbrl_vm_pop(vm, c);
        if (want_float)
            *f = (double)*c;
        return 1;
    }
    if (want_float && f1 == f0 + 1 && d1 == d0) {
        fbrl_vm_fpop(vm, f);
        return 1;
    }
    /* leave the stacks as they were */
    while (fbrl_vm_depth(vm) > d0)
        fbrl_vm_pop(vm, c);
    while (fbrl_vm_fdepth(vm) > f0)
        fbrl_vm_fpop(vm, f);
    return 0;
}

static const char *kind_name(char kind)
{
    switch (kind) {
    case 'I': return "an integer";
    case 'R': return "a number";
    case 'C': return "a character";
    case 'A': return "a data word's name";
    case 'S':
    case 'T': return "a text";
    default: return "a name";
    }
}

fbrl_status fbrl_vmx_arg_parse(fbrl_vm *vm, const char *word, char kind, const char *what, fbrl_vmx_val *v)
{
    const char *s;
    size_t n;
    int found;
    if (!vm || !v)
        return FBRL_EINVAL;
    if (!word)
        word = "";
    if (!what)
        what = kind_name(kind);
    if (kind == 'T') { /* the rest of the line */
        skip_blanks(vm);
        fbrl__parse(vm, '\0', &s, &n, &found);
        while (n > 0 && is_blank(s[n - 1]))
            n--;
    } else if (kind == 'S') { /* a "quoted text" or one word */
        int q = fbrl_vmx_parse_quoted(vm, &s, &n);
        if (q == 0)
            return fbrl_vmx_throwf(vm, FBRL_THROW_UNEXPECTED_EOF, "%s: unterminated \"text\"", word);
        if (q > 0) {
            v->s = s;
            v->n = n;
            return FBRL_OK;
        }
        fbrl__parse_name(vm, &s, &n);
    } else {
        fbrl__parse_name(vm, &s, &n);
    }
    if (n == 0)
        return fbrl_vmx_throwf(vm, FBRL_THROW_NO_NAME,
                               "%s needs %s: on the stack before it, or after it on the line", word, what);
    const fbrl_hdr *h;
    fbrl_cell num[2];
    double f;
    int nk;
    switch (kind) {
    case 'T':
    case 'S':
        v->s = s;
        v->n = n;
        return FBRL_OK;
    case 'I':
        if (fbrl__parse_number(vm, s, n, num, &f) == 1) {
            v->i = num[0];
            return FBRL_OK;
        }
        if ((h = data_word(vm, s, n)) && (h->kind == K_CONST || h->kind == K_VALUE) &&
            data_value(vm, h, 0, &v->i, &v->f))
            return FBRL_OK;
        break;
    case 'C':
        if (n == 1) {
            v->i = (unsigned char)s[0];
            return FBRL_OK;
        }
        if (fbrl__parse_number(vm, s, n, num, &f) == 1) {
            v->i = num[0];
            return FBRL_OK;
        }
        break;
    case 'R':
        nk = fbrl__parse_number(vm, s, n, num, &f);
        if (nk == 1) {
            v->f = (double)num[0];
            return FBRL_OK;
        }
        if (nk == 2) {
            v->f = fbrl__d_to_f(num[0], num[1]);
            return FBRL_OK;
        }
        if (nk == 3) {
            v->f = f;
            return FBRL_OK;
        }
        if ((h = data_word(vm, s, n)) && h->kind != K_VAR && h->kind != K_CREATE &&
            data_value(vm, h, 1, &v->i, &v->f))
            return FBRL_OK;
        break;
    case 'A':
    case 'N':
        if ((h = data_word(vm, s, n)) &&
            (h->kind == K_VAR || h->kind == K_CREATE || h->kind == K_CONST || h->kind == K_VALUE) &&
            data_value(vm, h, 0, &v->i, &v->f)) {
            v->s = NULL;
            return FBRL_OK;
        }
        if (kind == 'N' && fbrl__find(vm, s, n) < 0) { /* a name that is no word */
            v->i = 0;
            v->s = s;
            v->n = n;
            return FBRL_OK;
        }
        break;
    default: return FBRL_EINVAL;
    }
    return fbrl_vmx_throwf(vm, FBRL_THROW_BAD_NUMBER, "%s: '%.*s' is not %s", word, (int)(n > 40 ? 40 : n), s,
                           what);
}

static size_t cells_of(char kind) { return kind == 'R' ? 0 : (kind == 'S' || kind == 'T') ? 2 : 1; }

/* The safety of real arithmetic (IEEE: infinities, NaN) is checked here, where a value
 * enters a word set: every real parameter of a word set's word (a location, a motion, a
 * speed, a calibration: anything that may be bound for the controller) must be finite. */
static fbrl_status refuse_nonfinite(fbrl_vm *vm, const char *word, double f)
{
    return fbrl_vmx_throwf(vm, FBRL_VM_THROW_OF_STATUS(FBRL_ENONFINITE),
                           "%s refuses %s: not a finite number (nothing was sent)",
                           word && *word ? word
                           : vm->cword   ? vm->cword->name
                                         : "?",
                           isnan(f) ? "NaN"
                           : f < 0  ? "-Inf"
                                    : "Inf");
}

fbrl_status fbrl_vmx_args(fbrl_vm *vm, const char *word, const char *spec, const char *const *what,
                          unsigned how, fbrl_vmx_val *v)
{
    size_t nc = 0, nf = 0, k, np;
    if (!vm || !spec || !v || how > FBRL_VMX_LINE)
        return FBRL_EINVAL;
    np = strlen(spec);
    if (np > FBRL_VMX_MAXARGS)
        return FBRL_EINVAL;
    for (k = 0; k < np; k++) {
        if (!strchr("IRCANST", spec[k]))
            return FBRL_EINVAL;
        nf += spec[k] == 'R';
        nc += cells_of(spec[k]);
    }
    memset(v, 0, np * sizeof *v);
    if (np == 0)
        return FBRL_OK;
    size_t d = fbrl_vm_depth(vm), fd = fbrl_vm_fdepth(vm);
    int ints = fd < nf; /* the reals come from the data stack, as integers */
    if (how == FBRL_VMX_LINE && d < nc + (ints ? nf : 0)) {
        for (k = 0; k < np; k++) {
            fbrl_status st = fbrl_vmx_arg_parse(vm, word, spec[k], what ? what[k] : NULL, &v[k]);
            if (st != FBRL_OK)
                return st;
            if (spec[k] == 'R' && !isfinite(v[k].f))
                return refuse_nonfinite(vm, word, v[k].f);
        }
        return FBRL_OK;
    }
    if (d < nc)
        return fbrl_vm_throw(vm, FBRL_THROW_STACK_UNDERFLOW, NULL);
    if (ints && d < nc + nf)
        return fbrl_vm_throw(vm, FBRL_THROW_FSTACK_UNDERFLOW, NULL);
    for (k = 0; !ints && k < nf; k++) /* before anything is taken: bad input loses nothing */
        if (!isfinite(vm->fp[-1 - (ptrdiff_t)k]))
            return refuse_nonfinite(vm, word, vm->fp[-1 - (ptrdiff_t)k]);
    /* the word's cell parameters are on top, in spec order; beneath them its reals given
     * as integers (or the reals are on the float stack) */
    fbrl_cell *top = (fbrl_cell *)vm->sp;
    for (k = np; k-- > 0;) {
        char c = spec[k];
        if (c == 'R')
            continue;
        if (c == 'S' || c == 'T') {
            fbrl_cell a = top[-2], u = top[-1];
            top -= 2;
            if (u < 0 || (u > 0 && !fbrl__addr_ok(vm, a, u)))
                return fbrl_vm_throw(vm, FBRL_THROW_BAD_ADDRESS, NULL);
            v[k].s = (const char *)a;
            v[k].n = (size_t)u;
        } else {
            v[k].i = *--top;
        }
    }
    for (k = np; k-- > 0;) {
        if (spec[k] != 'R')
            continue;
        if (ints)
            v[k].f = (double)*--top;
        else
            fbrl_vm_fpop(vm, &v[k].f);
    }
    vm->sp = top;
    return FBRL_OK;
}

fbrl_status fbrl_vmx_check(fbrl_vm *vm, const void *word, fbrl_vmx_val *v)
{
    const fbrl_vmx_reg *w = word;
    if (!w || !w->spec)
        return FBRL_EINVAL;
    return fbrl_vmx_args(vm, w->name, w->spec, NULL,
                         (w->flags & FBRL_VMX_PARSE) ? FBRL_VMX_LINE : FBRL_VMX_STACKS, v);
}

fbrl_status fbrl_vmx_push(fbrl_vm *vm, fbrl_cell v)
{
    return fbrl_vm_push(vm, v) == FBRL_OK ? FBRL_OK : fbrl_vm_throw(vm, FBRL_THROW_STACK_OVERFLOW, NULL);
}

fbrl_status fbrl_vmx_fpush(fbrl_vm *vm, double v)
{
    fbrl_status st = fbrl_vm_fpush(vm, v);
    if (st == FBRL_ENOMEM)
        return fbrl_vm_throw(vm, FBRL_THROW_FSTACK_OVERFLOW, NULL);
    return st;
}

/* ---- parsing, state, compiling, running ---- */

fbrl_status fbrl_vmx_parse(fbrl_vm *vm, char delim, const char **text, size_t *len, int *found)
{
    int f = 0;
    if (!vm || !text || !len)
        return FBRL_EINVAL;
    fbrl__parse(vm, delim, text, len, &f);
    if (found)
        *found = f;
    return FBRL_OK;
}

int fbrl_vmx_parse_quoted(fbrl_vm *vm, const char **text, size_t *len)
{
    fbrl_src *src = cur_src(vm);
    int found;
    *text = "";
    *len = 0;
    skip_blanks(vm);
    if (!src || *vm->toin < 0 || (size_t)*vm->toin >= src->len || src->buf[*vm->toin] != '"')
        return -1;
    ++*vm->toin;
    fbrl__parse(vm, '"', text, len, &found);
    return found;
}

fbrl_status fbrl_vmx_parse_line(fbrl_vm *vm, const char **text, size_t *len)
{
    int found;
    if (!vm || !text || !len)
        return FBRL_EINVAL;
    skip_blanks(vm);
    fbrl__parse(vm, '\0', text, len, &found);
    while (*len > 0 && is_blank((*text)[*len - 1]))
        --*len;
    return FBRL_OK;
}

fbrl_status fbrl_vmx_refill(fbrl_vm *vm, const char **line, size_t *len)
{
    if (!vm || !line || !len)
        return FBRL_EINVAL;
    fbrl_src *s = cur_src(vm);
    if (!s || s->kind == SRC_STRING)
        return FBRL_EEOF;
    int got = fbrl__refill(vm);
    if (got < 0)
        return fbrl_vm_throw(vm, got, NULL);
    if (got == 0)
        return FBRL_EEOF;
    *line = s->buf;
    *len = s->len;
    *vm->toin = (fbrl_cell)s->len;
    return FBRL_OK;
}

int fbrl_vmx_compiling(const fbrl_vm *vm) { return vm && *vm->state != 0; }

static fbrl_status thrown(fbrl_vm *vm, int code) { return code ? fbrl_vm_throw(vm, code, NULL) : FBRL_OK; }

fbrl_status fbrl_vmx_compile_lit(fbrl_vm *vm, fbrl_cell v) { return thrown(vm, fbrl__compile_lit(vm, v)); }
fbrl_status fbrl_vmx_compile_xt(fbrl_vm *vm, fbrl_cell xt) { return thrown(vm, fbrl__compile_xt(vm, xt)); }
fbrl_status fbrl_vmx_compile_string(fbrl_vm *vm, const char *s, size_t n)
{
    return thrown(vm, fbrl__compile_str(vm, OP_SLIT, s, n));
}

fbrl_status fbrl_vmx_execute(fbrl_vm *vm, fbrl_cell xt) { return thrown(vm, fbrl__run(vm, xt)); }
fbrl_status fbrl_vmx_evaluate(fbrl_vm *vm, const char *text, size_t len)
{
    return thrown(vm, fbrl__evaluate(vm, (char *)(uintptr_t)text, len));
}

fbrl_status fbrl_vmx_evaluate_catch(fbrl_vm *vm, const char *text, size_t len, int *code, char *msg,
                                    size_t cap)
{
    if (!vm || !code || !msg || cap == 0 || (!text && len))
        return FBRL_EINVAL;
    fbrl_cell *sp = vm->sp, *rp = vm->rp;
    double *fp = vm->fp;
    fbrl_cell handler = vm->handler, lp = vm->lp;
    int nest = vm->nest, nsrc = vm->nsrc, captured = vm->err_captured;
    int defining = vm->defining, compiling = *vm->state != 0;
    char word[sizeof vm->cur_word];
    memcpy(word, vm->cur_word, sizeof word);
    *code = 0;
    msg[0] = 0;
    int r = fbrl__evaluate(vm, (char *)(uintptr_t)text, len);
    if (r == 0) {
        memcpy(vm->cur_word, word, sizeof word); /* an error after this is the caller's */
        return FBRL_OK;
    }
    if (r == THROW_BYE || r == THROW_QUIT)
        return fbrl_vm_throw(vm, r, NULL);
    const char *m = (vm->pending_msg && vm->pending_code == r) ? vm->pending_msg : fbrl__throw_text(r);
    if (r == FBRL_THROW_UNDEFINED && vm->cur_word[0])
        snprintf(msg, cap, "%s %s", m, vm->cur_word);
    else
        snprintf(msg, cap, "%s", m);
    *code = r;
    /* put the VM back as CATCH does, and drop what the failed text left half made */
    vm->sp = sp;
    vm->rp = rp;
    vm->fp = fp;
    vm->handler = handler;
    vm->lp = lp;
    vm->nest = nest;
    while (vm->nsrc > nsrc)
        fbrl__pop_source(vm);
    if ((!defining && vm->defining) || (!compiling && *vm->state))
        fbrl__drop_definition(vm);
    vm->err_captured = captured;
    vm->pending_msg = NULL;
    vm->pending_throw = 0;
    memcpy(vm->cur_word, word, sizeof word);
    return FBRL_OK;
}

/* ---- host services ---- */

const fbrl_vm_host *fbrl_vmx_host(const fbrl_vm *vm) { return vm ? &vm->host : NULL; }
void fbrl_vmx_write(fbrl_vm *vm, const char *s, size_t n) { fbrl__write(vm, s, n); }
void fbrl_vmx_puts(fbrl_vm *vm, const char *s) { fbrl__puts(vm, s); }
int fbrl_vmx_take_interrupt(fbrl_vm *vm) { return fbrl__take_interrupt(vm); }

fbrl_status fbrl_vmx_throwf(fbrl_vm *vm, int code, const char *fmt, ...)
{
    char msg[128];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return fbrl_vm_throw(vm, code, msg);
}

fbrl_cell fbrl_vmx_forth2012_wid(const fbrl_vm *vm) { return vm ? (fbrl_cell)vm->wl_forth2012 + 1 : 0; }

fbrl_status fbrl_vmx_set_current(fbrl_vm *vm, fbrl_cell wid, fbrl_cell *previous)
{
    if (!vm || wid < 1 || wid > (fbrl_cell)vm->nwl)
        return FBRL_EINVAL;
    if (previous)
        *previous = (fbrl_cell)vm->current + 1;
    vm->current = (uint8_t)(wid - 1);
    return FBRL_OK;
}

/* ---- waiting words and tasks (task.c runs them) ---- */

int fbrl_vmx_tasking(const fbrl_vm *vm) { return vm && vm->ntasks > 0; }

fbrl_vmx_wait *fbrl_vmx_wait_state(fbrl_vm *vm) { return fbrl__wait_begin(vm); }

fbrl_status fbrl_vmx_pause(fbrl_vm *vm, uint64_t wake_us)
{
    int code = vm->task_pause(vm, wake_us, 0);
    if (!code)
        return FBRL_OK;
    vm->pending_throw = code;
    return FBRL_ETHROW;
}

int fbrl_vmx_yielded(const fbrl_vm *vm) { return vm->pending_throw == THROW_YIELD; }

fbrl_vmx_timer *fbrl_vmx_task_timer(fbrl_vm *vm) { return &vm->tasks[vm->cur_task].timer; }

fbrl_status fbrl_vmx_claim_wait(fbrl_vm *vm, fbrl_cell key)
{
    if (!vm->ntasks)
        return FBRL_OK;
    for (;;) {
        const fbrl_claim *c = NULL;
        for (int k = 0; k < FBRL_CLAIMS_MAX && !c; k++)
            if (vm->claims[k].key == key)
                c = &vm->claims[k];
        if (!c || c->owner < 0 || c->owner == vm->cur_task)
            return FBRL_OK;
        int code = vm->task_pause(vm, FBRL_TASK_NEVER, 1); /* until the holder releases it */
        if (code) {
            vm->pending_throw = code;
            return FBRL_ETHROW;
        }
    }
}
