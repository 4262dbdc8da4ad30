/* SPDX-License-Identifier: MIT */
/* vm.c - one VM in the caller's memory block: its layout, creation, the interrupt
 * flag and the C API to its stacks. The text interpreter is interp.c, the inner
 * interpreter run.c, the dictionary dict.c. */
#include <string.h>
#include "atomic.h"
#include "words.h"

static size_t align16(size_t n) { return (n + 15) & ~(size_t)15; }

typedef struct layout {
    size_t ds, rs, fs; /* cells */
    size_t o_ds, o_rs, o_fs, o_data, fixed;
} layout;

#define FBRL_SYSVARS 8
#define FBRL_BUFS                                                                     \
    (FBRL_SYSVARS * sizeof(fbrl_cell) + FBRL_WORDBUF + FBRL_PADSIZE + FBRL_HOLDSIZE + \
     FBRL_NSBUF * FBRL_SBUF + FBRL_SRC_MAX * (FBRL_LINE_MAX + 8))
/* A small target (the Cortex-M3 firmware) sets these lower on the command line. */
#ifndef FBRL_STACK_ALIGN
#define FBRL_STACK_ALIGN 4096 /* see make_layout */
#endif
#define FBRL_HEAP_PART 8 /* the heap takes an eighth of the free data region, */
#ifndef FBRL_HEAP_MAX
#define FBRL_HEAP_MAX (512u << 10) /* at most this much (the dictionary keeps the rest) */
#endif
#ifndef FBRL_EXTRA_WORDS
#define FBRL_EXTRA_WORDS 192 /* headers beyond the primitives (data words, C words of src/lang) */
#endif

static size_t heap_for(size_t free_bytes)
{
    size_t h = free_bytes / FBRL_HEAP_PART;
    return (h < FBRL_HEAP_MAX ? h : FBRL_HEAP_MAX) & ~(size_t)15;
}

/* Primitives whose headers take RAM (none with FBRL_ROM_PRIMS: theirs are in flash). */
static size_t ram_prims(void)
{
#ifdef FBRL_ROM_PRIMS
    return 0;
#else
    return fbrl__named_ops();
#endif
}

static void make_layout(const fbrl_vm_config *cfg, layout *l)
{
    l->ds = cfg->data_stack_cells ? cfg->data_stack_cells : 256;
    l->rs = cfg->return_stack_cells ? cfg->return_stack_cells : 256;
    l->fs = cfg->float_stack_cells ? cfg->float_stack_cells : 64;
    /* 16 spare bytes below the data and float stacks: run.c stores the cached top
     * of an empty stack there */
    /* the data stack starts on a 4 KiB boundary past the VM struct (16 spare bytes below
     * it): where it fell by the struct's size, its cells could share their low 12 address
     * bits with the struct's hot fields and the CPU's memory disambiguation stalled (the
     * matrix benchmark ran 2.7 times slower for one struct size) */
    l->o_ds = (sizeof(struct fbrl_vm) + 16 + FBRL_STACK_ALIGN - 1) & ~(size_t)(FBRL_STACK_ALIGN - 1);
    l->o_rs = l->o_ds + align16(l->ds * sizeof(fbrl_cell));
    l->o_fs = l->o_rs + align16(l->rs * sizeof(fbrl_cell)) + 16;
    l->o_data = l->o_fs + align16(l->fs * sizeof(double));
    l->fixed = l->o_data + align16(FBRL_BUFS) + FBRL_GUARD_CELLS * sizeof(fbrl_cell) + 16 +
               (ram_prims() + FBRL_EXTRA_WORDS) * sizeof(fbrl_hdr) + 2048;
}

size_t fbrl_vm_size_for(const fbrl_vm_config *cfg, size_t dict_bytes)
{
    layout l;
    if (!cfg)
        return 0;
    make_layout(cfg, &l);
    return l.fixed + dict_bytes + heap_for(dict_bytes + dict_bytes / (FBRL_HEAP_PART - 1)) + 16;
}

fbrl_status fbrl_vm_create(fbrl_vm **out, const fbrl_vm_config *cfg)
{
    layout l;
    if (!out || !cfg || !cfg->mem)
        return FBRL_EINVAL;
    *out = NULL;
    if (cfg->data_stack_cells > (1u << 20) || cfg->return_stack_cells > (1u << 20) ||
        cfg->float_stack_cells > (1u << 20))
        return FBRL_ERANGE;
    make_layout(cfg, &l);
    unsigned char *m = cfg->mem;
    size_t size = cfg->mem_size;
    size_t mis = (size_t)((uintptr_t)m & 15);
    if (mis) {
        if (size < 16 - mis)
            return FBRL_ENOSPC;
        m += 16 - mis;
        size -= 16 - mis;
    }
    size &= ~(size_t)15;
    if (size < l.fixed)
        return FBRL_ENOSPC;

    fbrl_vm *vm = (fbrl_vm *)(void *)m;
    memset(vm, 0, sizeof *vm);
    vm->host = cfg->host;
    vm->mem_end = m + size;
    vm->ds0 = vm->sp = (fbrl_cell *)(void *)(m + l.o_ds);
    vm->ds_end = vm->ds0 + l.ds;
    vm->rs0 = vm->rp = (fbrl_cell *)(void *)(m + l.o_rs);
    vm->rs_end = vm->rs0 + l.rs;
    vm->fs0 = vm->fp = (double *)(void *)(m + l.o_fs);
    vm->fs_end = vm->fs0 + l.fs;

    unsigned char *d = m + l.o_data;
    vm->data_lo = d;
    /* Unused dictionary reads as OP_BAD (0), so a stray jump stops at once; a
     * caller that passes zeroed memory saves touching (and so backing) every page. */
    if (cfg->mem_zeroed)
        memset(d, 0, align16(FBRL_BUFS));
    else
        memset(d, 0, (size_t)(vm->mem_end - d));
    vm->base = (fbrl_cell *)(void *)d;
    vm->state = vm->base + 1;
    vm->toin = vm->base + 2;
    d += FBRL_SYSVARS * sizeof(fbrl_cell);
    vm->wordbuf = (char *)d;
    d += FBRL_WORDBUF;
    vm->pad = (char *)d;
    d += FBRL_PADSIZE;
    vm->hold = (char *)d;
    d += FBRL_HOLDSIZE;
    vm->hld = vm->hold + FBRL_HOLDSIZE;
    vm->sbuf = (char *)d;
    d += FBRL_NSBUF * FBRL_SBUF;
    for (int i = 0; i < FBRL_SRC_MAX; i++) {
        vm->src[i].linebuf = (char *)d;
        d += FBRL_LINE_MAX + 8;
    }
    vm->dict_lo = vm->here = vm->data_lo + align16(FBRL_BUFS);
    /* ALLOCATE's heap: a part of the free data region, below the dictionary (heap.c) */
    size_t heap = heap_for(size - l.fixed); /* size >= l.fixed */
    fbrl__heap_init(vm, vm->here, heap);
    vm->dict_lo = vm->here = vm->here + heap;

    fbrl_cell *guard = (fbrl_cell *)(void *)(vm->mem_end - FBRL_GUARD_CELLS * sizeof(fbrl_cell));
    for (int i = 0; i < FBRL_GUARD_CELLS; i++)
        guard[i] = OP_BAD;
    guard[0] = OP_HALT;
    guard[1] = OP_CATCHEND;
    vm->guard_addr = (fbrl_cell)guard;
    vm->hdr_top = (fbrl_hdr *)(void *)guard;
    vm->nwords = HDR_ROM; /* FBRL_ROM_PRIMS: the primitives' headers come first, in flash */
    vm->data_hi = (unsigned char *)guard;
    *vm->base = 10;
    vm->precision = 6;

    vm->nest_evaluate = fbrl__evaluate;
    vm->nest_included = fbrl__included;
    if (fbrl__wordlist_init(vm) || fbrl__install_prims(vm) || fbrl__heap_words(vm) ||
        fbrl__strings_init(vm) || fbrl__locals_init(vm) || fbrl__facility_words(vm))
        return FBRL_ENOSPC;
    if (fbrl__task_words(vm))
        return FBRL_ENOSPC;
    /* no word set: they are the host's to install (fbrl_glossary_install, fbrl_vmx_data_words ...) */
    fbrl_status st = FBRL_OK;
#ifndef FBRL_NO_FILE_WORDS /* a port without a file system (the firmware) leaves them out */
    if (st == FBRL_OK && vm->host.files)
        st = fbrl__file_words(vm) ? FBRL_ENOSPC : FBRL_OK;
#endif
    if (st != FBRL_OK)
        return st == FBRL_ENOMEM ? FBRL_ENOSPC : st;
    st = fbrl_vm_eval(vm, fbrl__prelude, strlen(fbrl__prelude));
    if (st != FBRL_OK)
        return vm->err.throw_code == FBRL_THROW_DICT_OVERFLOW ? FBRL_ENOSPC : st;
    vm->dict_lo = vm->here;
    *out = vm;
    return FBRL_OK;
}

void fbrl_vm_interrupt(fbrl_vm *vm)
{
    if (vm)
        fbrl_store_rlx(&vm->interrupt, fbrl_load_rlx(&vm->interrupt) | FBRL_ATTN_INTERRUPT);
}

int fbrl_vm_interrupt_pending(const fbrl_vm *vm)
{
    return vm ? (fbrl_load_rlx(&((fbrl_vm *)vm)->interrupt) & FBRL_ATTN_INTERRUPT) != 0 : 0;
}

const fbrl_vm_error *fbrl_vm_last_error(const fbrl_vm *vm) { return vm ? &vm->err : NULL; }
int fbrl_vm_bye(const fbrl_vm *vm) { return vm ? vm->bye : 0; }
int fbrl_vm_compiling(const fbrl_vm *vm) { return vm ? (*vm->state != 0 || vm->defining) : 0; }

fbrl_status fbrl_vm_push(fbrl_vm *vm, fbrl_cell v)
{
    if (!vm)
        return FBRL_EINVAL;
    if (vm->sp >= vm->ds_end)
        return FBRL_ENOMEM;
    *vm->sp++ = v;
    return FBRL_OK;
}

fbrl_status fbrl_vm_pop(fbrl_vm *vm, fbrl_cell *v)
{
    if (!vm || !v)
        return FBRL_EINVAL;
    if (vm->sp <= vm->ds0)
        return FBRL_EEMPTY;
    *v = *--vm->sp;
    return FBRL_OK;
}

fbrl_status fbrl_vm_fpush(fbrl_vm *vm, double v)
{
    if (!vm)
        return FBRL_EINVAL;
    if (v != v || v - v != 0)
        return FBRL_ENONFINITE;
    if (vm->fp >= vm->fs_end)
        return FBRL_ENOMEM;
    *vm->fp++ = v;
    return FBRL_OK;
}

fbrl_status fbrl_vm_fpop(fbrl_vm *vm, double *v)
{
    if (!vm || !v)
        return FBRL_EINVAL;
    if (vm->fp <= vm->fs0)
        return FBRL_EEMPTY;
    *v = *--vm->fp;
    return FBRL_OK;
}

size_t fbrl_vm_depth(const fbrl_vm *vm) { return vm ? (size_t)(vm->sp - vm->ds0) : 0; }
size_t fbrl_vm_fdepth(const fbrl_vm *vm) { return vm ? (size_t)(vm->fp - vm->fs0) : 0; }

fbrl_status fbrl_vm_throw(fbrl_vm *vm, int code, const char *msg)
{
    if (!vm || code == 0)
        return FBRL_EINVAL;
    vm->pending_throw = code;
    if (msg)
        fbrl__throw_msg(vm, code, msg);
    return FBRL_ETHROW;
}

fbrl_status fbrl_vm_parse_name(fbrl_vm *vm, const char **name, size_t *len)
{
    if (!vm || !name || !len)
        return FBRL_EINVAL;
    fbrl__parse_name(vm, name, len);
    return FBRL_OK;
}
