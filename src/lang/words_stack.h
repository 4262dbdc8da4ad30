/* SPDX-License-Identifier: MIT */
/* words_stack.h - the stacks as the engine's word groups (words.c, words_io.c) take them:
 * throw codes, 0 = ok; each group works on the VM's own stack pointers (run.c saved them).
 * Private. */
#ifndef FBRL_LANG_WORDS_STACK_H
#define FBRL_LANG_WORDS_STACK_H

#include "words.h"

static inline int pop(fbrl_vm *vm, fbrl_cell *v)
{
    if (vm->sp <= vm->ds0)
        return FBRL_THROW_STACK_UNDERFLOW;
    *v = *--vm->sp;
    return 0;
}
static inline int push(fbrl_vm *vm, fbrl_cell v)
{
    if (vm->sp >= vm->ds_end)
        return FBRL_THROW_STACK_OVERFLOW;
    *vm->sp++ = v;
    return 0;
}
static inline int need(fbrl_vm *vm, int n) { return vm->sp - vm->ds0 < n ? FBRL_THROW_STACK_UNDERFLOW : 0; }
static inline int fpop(fbrl_vm *vm, double *v)
{
    if (vm->fp <= vm->fs0)
        return FBRL_THROW_FSTACK_UNDERFLOW;
    *v = *--vm->fp;
    return 0;
}
static inline int fpush(fbrl_vm *vm, double v)
{
    if (vm->fp >= vm->fs_end)
        return FBRL_THROW_FSTACK_OVERFLOW;
    *vm->fp++ = v;
    return 0;
}
/* pop a string ( a u ) that must lie in data space */
static inline int pop_str(fbrl_vm *vm, const char **s, size_t *n)
{
    fbrl_cell a, u;
    if (need(vm, 2))
        return FBRL_THROW_STACK_UNDERFLOW;
    u = *--vm->sp;
    a = *--vm->sp;
    if (u < 0)
        return FBRL_THROW_BAD_NUMBER;
    if (u > 0 && !fbrl__addr_ok(vm, a, u))
        return FBRL_THROW_BAD_ADDRESS;
    *s = u ? (const char *)a : "";
    *n = (size_t)u;
    return 0;
}

#endif
