/* SPDX-License-Identifier: MIT */
/* words.h - helpers shared by the engine's source files (private). */
#ifndef FBRL_LANG_WORDS_H
#define FBRL_LANG_WORDS_H

#include "vm_internal.h"

/* dict.c: the dictionary and the compiler */
const char *fbrl__op_name(int op);
size_t fbrl__named_ops(void);
int fbrl__install_prims(fbrl_vm *vm);
int fbrl__emit(fbrl_vm *vm, fbrl_cell v);
int fbrl__allot(fbrl_vm *vm, fbrl_cell n);
int fbrl__align(fbrl_vm *vm);
int fbrl__colon(fbrl_vm *vm, int noname, fbrl_cell *xt);
int fbrl__semicolon(fbrl_vm *vm);
void fbrl__forget(fbrl_vm *vm, unsigned char *here, uint32_t nwords, size_t req_used);
/* drop an open definition (STATE 0), as after an error */
void fbrl__drop_definition(fbrl_vm *vm);
int fbrl__compile_xt(fbrl_vm *vm, fbrl_cell xt);
int fbrl__compile_lit(fbrl_vm *vm, fbrl_cell v);
int fbrl__compile_op(fbrl_vm *vm, int op);
void fbrl__peep_reset(fbrl_vm *vm);
int fbrl__compile_flit(fbrl_vm *vm, double d);
int fbrl__compile_str(fbrl_vm *vm, int op, const char *s, size_t n);
int fbrl__new_word(fbrl_vm *vm, const char *name, size_t len, int kind, const char *stack, const char *help,
                   fbrl_hdr **out);
int fbrl__create(fbrl_vm *vm, int kind, const char *dstack, const char *dhelp, fbrl_hdr **out);

/* A C word of the engine's own word sets (wordlist.c, locals.c, heap.c, ...). */
typedef struct fbrl_cword {
    const char *name;
    fbrl_vm_prim fn;
    void *arg;
    uint8_t flags; /* FI FC FS */
    FBRL_DOC_FIELDS
} fbrl_cword;
int fbrl__define_words(fbrl_vm *vm, const fbrl_cword *w, size_t n);
int fbrl__synonym(fbrl_vm *vm, const char *name, size_t len, const fbrl_hdr *old);
int fbrl__find_in(const fbrl_vm *vm, unsigned wl, const char *name, size_t len);
int fbrl__name_eq(const char *a, const char *b, size_t n);

/* The stacks from a C word (the inner interpreter has saved them): throw codes, 0 = ok. */
static inline int fbrl__cneed(const fbrl_vm *vm, ptrdiff_t n)
{
    return vm->sp - vm->ds0 < n ? FBRL_THROW_STACK_UNDERFLOW : 0;
}
static inline int fbrl__cpush(fbrl_vm *vm, fbrl_cell v)
{
    if (vm->sp >= vm->ds_end)
        return FBRL_THROW_STACK_OVERFLOW;
    *vm->sp++ = v;
    return 0;
}
/* A throw code as a C word's result. */
static inline fbrl_status fbrl__cthrow(fbrl_vm *vm, int code)
{
    if (!code)
        return FBRL_OK;
    vm->pending_throw = code; /* as fbrl_vm_throw (vm.c), which calls into these files */
    return FBRL_ETHROW;
}

/* wordlist.c, locals.c, heap.c, strings.c, file.c: install their words (vm.c) */
int fbrl__wordlist_init(fbrl_vm *vm);
int fbrl__new_wordlist(fbrl_vm *vm, const char *name, unsigned *wl);
int fbrl__locals_init(fbrl_vm *vm);
int fbrl__heap_init(fbrl_vm *vm, unsigned char *lo, size_t size);
int fbrl__heap_words(fbrl_vm *vm);
int fbrl__strings_init(fbrl_vm *vm);
int fbrl__facility_words(fbrl_vm *vm);
int fbrl__file_words(fbrl_vm *vm); /* only with host.files */
/* locals.c: the index of a local of the open definition, or -1 */
int fbrl__local_index(const fbrl_vm *vm, const char *name, size_t len);
/* locals.c: compile a local's value (read) or TO local (write) */
int fbrl__compile_local(fbrl_vm *vm, int index, int store);
/* heap.c: ALLOCATE / FREE for the engine's own users (REPLACES): 0 or an ior */
fbrl_cell fbrl__heap_alloc(fbrl_vm *vm, fbrl_cell size, fbrl_cell *addr);
fbrl_cell fbrl__heap_free(fbrl_vm *vm, fbrl_cell addr);

/* io.c: input sources and parsing */
fbrl_src *fbrl__src(fbrl_vm *vm);
size_t fbrl__src_in(fbrl_vm *vm, const fbrl_src *s); /* >IN clamped to the source */
int fbrl__push_source(fbrl_vm *vm, int kind, fbrl_src **out);
void fbrl__pop_source(fbrl_vm *vm); /* the newest input source, if any */
void fbrl__parse_name(fbrl_vm *vm, const char **p, size_t *n);
void fbrl__parse(fbrl_vm *vm, char c, const char **p, size_t *n, int *found);
int fbrl__refill(fbrl_vm *vm);
int fbrl__src_goto_line(fbrl_vm *vm, unsigned long n); /* 0, or -1: not possible */

/* number.c */
size_t fbrl__to_number(const char *s, size_t n, fbrl_cell base, fbrl_ucell *lo, fbrl_ucell *hi);
/* a float in the standard's form; need_e: the exponent is required (text interpreter) */
int fbrl__parse_float(const char *s, size_t n, int need_e, double *out);

/* interp.c: the text interpreter (from below only through vm->nest_*) */
int fbrl__evaluate(fbrl_vm *vm, char *text, size_t len);
int fbrl__included(fbrl_vm *vm, const char *name, size_t n, int require);

/* words.c: output */
int fbrl__spaces(fbrl_vm *vm, fbrl_cell n);

/* arith.c */
void fbrl__dneg(fbrl_ucell *lo, fbrl_ucell *hi);
void fbrl__umul(fbrl_ucell a, fbrl_ucell b, fbrl_ucell *hi, fbrl_ucell *lo);
void fbrl__udiv(fbrl_ucell hi, fbrl_ucell lo, fbrl_ucell d, fbrl_ucell *q, fbrl_ucell *r);
void fbrl__mstar(fbrl_cell a, fbrl_cell b, fbrl_cell *lo, fbrl_cell *hi);
int fbrl__dsdiv(fbrl_cell lo, fbrl_cell hi, fbrl_cell n, int floored, fbrl_cell *q, fbrl_cell *r);
int fbrl__starslash(fbrl_cell a, fbrl_cell b, fbrl_cell c, fbrl_cell *q, fbrl_cell *r);
int fbrl__mstarslash(fbrl_cell *lo, fbrl_cell *hi, fbrl_cell n, fbrl_cell div);
double fbrl__d_to_f(fbrl_cell lo, fbrl_cell hi);
int fbrl__f_to_d(double r, fbrl_cell *lo, fbrl_cell *hi);

/* words.c: word groups run on the VM's stacks (after SAVE) */
int fbrl__w_string(fbrl_vm *vm, int op);
int fbrl__w_control(fbrl_vm *vm, int op);
int fbrl__w_define(fbrl_vm *vm, int op);
int fbrl__w_parse(fbrl_vm *vm, int op);
int fbrl__w_io(fbrl_vm *vm, int op);

#endif
