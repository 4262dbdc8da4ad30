/* SPDX-License-Identifier: MIT */
/* locals.c - the LOCALS word set: {: args | vals -- outs :} and TO for locals.
 *
 * A definition's locals live in a frame on the VM's locals stack (vm->locals, not
 * addressable by the program, so a local has no address and cannot be corrupted). The
 * frame is made at run time by (LOCALS), which moves the arguments in; a local is read
 * by `k (LOCAL@)` and written by `k (LOCAL!)`; (LOCALS-EXIT) drops the frame and is
 * compiled before every EXIT, before DOES> and at ; (dict.c, words.c). The frame's
 * size is its top cell. A CATCH frame keeps the locals stack's depth (run.c), so THROW
 * drops the frames of the definitions it leaves. Separate from the return stack, the
 * locals stay usable inside DO loops and between >R and R>. */
#include <string.h>
#include "words.h"

/* ---- run time ---- */

static fbrl_status w_locals(fbrl_vm *vm, void *arg)
{
    (void)arg;
    if (fbrl__cneed(vm, 2))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    fbrl_cell m = vm->sp[-1], n = vm->sp[-2];
    if (n < 0 || m < 0 || n + m > FBRL_NLOCALS)
        return fbrl__cthrow(vm, FBRL_THROW_BAD_NUMBER);
    if (fbrl__cneed(vm, n + 2))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    if (vm->lp < 0 || FBRL_LOCALS_MAX - vm->lp < n + m + 1)
        return fbrl__cthrow(vm, fbrl__throw_msg(vm, FBRL_THROW_RSTACK_OVERFLOW, "locals stack overflow"));
    vm->sp -= 2 + n;
    fbrl_cell *f = vm->locals + vm->lp;
    memcpy(f, vm->sp, (size_t)n * sizeof *f);
    memset(f + n, 0, (size_t)m * sizeof *f);
    f[n + m] = n + m;
    vm->lp += n + m + 1;
    return FBRL_OK;
}

/* The frame of the running definition: its cells, or NULL if the stack is broken. */
static fbrl_cell *frame(fbrl_vm *vm, fbrl_cell *size)
{
    if (vm->lp < 1 || vm->lp > FBRL_LOCALS_MAX)
        return NULL;
    *size = vm->locals[vm->lp - 1];
    if (*size < 0 || *size > vm->lp - 1)
        return NULL;
    return vm->locals + vm->lp - 1 - *size;
}

static fbrl_status w_local_fetch(fbrl_vm *vm, void *arg)
{
    fbrl_cell size;
    (void)arg;
    fbrl_cell *f = frame(vm, &size);
    if (fbrl__cneed(vm, 1))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    fbrl_cell k = vm->sp[-1];
    if (!f || k < 0 || k >= size)
        return fbrl__cthrow(vm, fbrl__throw_msg(vm, FBRL_THROW_BAD_ADDRESS, "no such local"));
    vm->sp[-1] = f[k];
    return FBRL_OK;
}

static fbrl_status w_local_store(fbrl_vm *vm, void *arg)
{
    fbrl_cell size;
    (void)arg;
    fbrl_cell *f = frame(vm, &size);
    if (fbrl__cneed(vm, 2))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    fbrl_cell k = vm->sp[-1];
    if (!f || k < 0 || k >= size)
        return fbrl__cthrow(vm, fbrl__throw_msg(vm, FBRL_THROW_BAD_ADDRESS, "no such local"));
    f[k] = vm->sp[-2];
    vm->sp -= 2;
    return FBRL_OK;
}

static fbrl_status w_locals_exit(fbrl_vm *vm, void *arg)
{
    fbrl_cell size;
    (void)arg;
    if (!frame(vm, &size))
        return fbrl__cthrow(vm, fbrl__throw_msg(vm, FBRL_THROW_BAD_ADDRESS, "no locals frame"));
    vm->lp -= size + 1;
    return FBRL_OK;
}

/* ---- compile time ---- */

int fbrl__local_index(const fbrl_vm *vm, const char *name, size_t len)
{
    for (int k = vm->nlocals; k-- > 0;) /* the later of two equal names wins */
        if (vm->llen[k] == len && fbrl__name_eq(vm->lname[k], name, len))
            return k;
    return -1;
}

static fbrl_cell xt_of(const fbrl_vm *vm, const char *name)
{
    int i = fbrl__find_in(vm, 0, name, strlen(name));
    return i < 0 ? 0 : FBRL_XT_BASE + i;
}

int fbrl__compile_local(fbrl_vm *vm, int index, int store)
{
    fbrl_cell xt = xt_of(vm, store ? "(LOCAL!)" : "(LOCAL@)");
    int r = fbrl__compile_lit(vm, index);
    return r ? r : fbrl__compile_xt(vm, xt);
}

static int is(const char *p, size_t n, const char *w) { return strlen(w) == n && fbrl__name_eq(p, w, n); }

/* {: a b | c d -- outs :} */
static fbrl_status w_brace_colon(fbrl_vm *vm, void *arg)
{
    int part = 0, nargs = 0, nvals = 0, r;
    char names[FBRL_NLOCALS][FBRL_NAME_MAX + 1];
    uint8_t lens[FBRL_NLOCALS];
    (void)arg;
    if (!vm->defining || !*vm->state)
        return fbrl__cthrow(vm, FBRL_THROW_COMPILE_ONLY);
    if (vm->nlocals)
        return fbrl__cthrow(vm,
                            fbrl__throw_msg(vm, FBRL_THROW_CONTROL_MISMATCH, "one {: ... :} per definition"));
    for (;;) {
        const char *p;
        size_t n;
        fbrl__parse_name(vm, &p, &n);
        if (n == 0) {
            if ((r = fbrl__refill(vm)) <= 0)
                return fbrl__cthrow(
                    vm, r < 0 ? r : fbrl__throw_msg(vm, FBRL_THROW_UNEXPECTED_EOF, "{: without :}"));
            continue;
        }
        if (is(p, n, ":}"))
            break;
        if (part == 2) /* the outputs are a comment */
            continue;
        if (is(p, n, "--")) {
            part = 2;
            continue;
        }
        if (is(p, n, "|") && part == 0) {
            part = 1;
            continue;
        }
        if (nargs + nvals >= FBRL_NLOCALS)
            return fbrl__cthrow(vm,
                                fbrl__throw_msg(vm, FBRL_THROW_BAD_NUMBER, "too many locals (32 at most)"));
        if (n > FBRL_NAME_MAX)
            return fbrl__cthrow(vm, FBRL_THROW_NAME_TOO_LONG);
        int k = nargs + nvals;
        memcpy(names[k], p, n);
        lens[k] = (uint8_t)n;
        if (part == 0)
            nargs++;
        else
            nvals++;
    }
    if (nargs + nvals == 0)
        return FBRL_OK;
    if ((r = fbrl__compile_lit(vm, nargs)) || (r = fbrl__compile_lit(vm, nvals)) ||
        (r = fbrl__compile_xt(vm, xt_of(vm, "(LOCALS)"))))
        return fbrl__cthrow(vm, r);
    memcpy(vm->lname, names, sizeof names);
    memcpy(vm->llen, lens, sizeof lens);
    vm->nlocals = nargs + nvals;
    return FBRL_OK;
}

/* (LOCAL) and LOCALS|: the first name declared takes the top of the stack. */
static int declare(fbrl_vm *vm, const char *p, size_t n)
{
    if (!vm->defining || !*vm->state)
        return FBRL_THROW_COMPILE_ONLY;
    if (vm->nlocals)
        return fbrl__throw_msg(vm, FBRL_THROW_CONTROL_MISMATCH, "one locals declaration per definition");
    if (n == 0) { /* the end: the frame is in stack order, the reverse of the declarations */
        int m = vm->lpend, r;
        vm->lpend = 0;
        if (m == 0)
            return 0;
        for (int k = 0; k < m / 2; k++) {
            char t[FBRL_NAME_MAX + 1];
            uint8_t l = vm->llen[k];
            memcpy(t, vm->lname[k], sizeof t);
            memcpy(vm->lname[k], vm->lname[m - 1 - k], sizeof t);
            memcpy(vm->lname[m - 1 - k], t, sizeof t);
            vm->llen[k] = vm->llen[m - 1 - k];
            vm->llen[m - 1 - k] = l;
        }
        if ((r = fbrl__compile_lit(vm, m)) || (r = fbrl__compile_lit(vm, 0)) ||
            (r = fbrl__compile_xt(vm, xt_of(vm, "(LOCALS)"))))
            return r;
        vm->nlocals = m;
        return 0;
    }
    if (vm->lpend >= FBRL_NLOCALS)
        return fbrl__throw_msg(vm, FBRL_THROW_BAD_NUMBER, "too many locals (32 at most)");
    if (n > FBRL_NAME_MAX)
        return FBRL_THROW_NAME_TOO_LONG;
    memcpy(vm->lname[vm->lpend], p, n);
    vm->llen[vm->lpend++] = (uint8_t)n;
    return 0;
}

static fbrl_status w_paren_local(fbrl_vm *vm, void *arg)
{
    (void)arg;
    if (fbrl__cneed(vm, 2))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    fbrl_cell u = vm->sp[-1], a = vm->sp[-2];
    if (u < 0 || (u > 0 && !fbrl__addr_ok(vm, a, u)))
        return fbrl__cthrow(vm, FBRL_THROW_BAD_ADDRESS);
    vm->sp -= 2;
    return fbrl__cthrow(vm, declare(vm, (const char *)a, (size_t)u));
}

static fbrl_status w_locals_bar(fbrl_vm *vm, void *arg)
{
    int r;
    (void)arg;
    for (;;) {
        const char *p;
        size_t n;
        fbrl__parse_name(vm, &p, &n);
        if (n == 0)
            return fbrl__cthrow(vm, fbrl__throw_msg(vm, FBRL_THROW_UNEXPECTED_EOF, "LOCALS| without |"));
        if (is(p, n, "|"))
            return fbrl__cthrow(vm, declare(vm, p, 0));
        if ((r = declare(vm, p, n)))
            return fbrl__cthrow(vm, r);
    }
}

static const fbrl_cword words[] = {
    {"(LOCAL)", w_paren_local, NULL, FC,
     FBRL_DOC("( c-addr u -- )",
              "declare a local (u = 0 ends); the first declared takes the top of the stack")},
    {"LOCALS|", w_locals_bar, NULL, FI | FC,
     FBRL_DOC("( \"name ... |\" -- )", "declare locals; the first name takes the top of the stack")},
    {"{:", w_brace_colon, NULL, FI | FC,
     FBRL_DOC("( \"args | vals -- outs :}\" -- )",
              "declare locals: args taken from the stack, vals set to 0; TO name sets one")},
    {"(LOCALS)", w_locals, NULL, 0, FBRL_DOC("( x1 .. xn n m -- )", "make a locals frame (compiled by {:)")},
    {"(LOCAL@)", w_local_fetch, NULL, 0, FBRL_DOC("( k -- x )", "the k-th local (compiled)")},
    {"(LOCAL!)", w_local_store, NULL, 0, FBRL_DOC("( x k -- )", "set the k-th local (compiled by TO)")},
    {"(LOCALS-EXIT)", w_locals_exit, NULL, 0,
     FBRL_DOC("( -- )", "drop the locals frame (compiled before EXIT)")},
};

int fbrl__locals_init(fbrl_vm *vm)
{
    int r = fbrl__define_words(vm, words, sizeof words / sizeof words[0]);
    vm->lexit_xt = xt_of(vm, "(LOCALS-EXIT)");
    return r;
}
