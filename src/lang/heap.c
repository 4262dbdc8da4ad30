/* SPDX-License-Identifier: MIT */
/* heap.c - the MEMORY word set (ALLOCATE FREE RESIZE) on a heap inside the VM's own
 * block (the core never calls malloc).
 *
 * The heap is a fixed part of the data region, below the dictionary (vm.c sizes it), so
 * its blocks are ordinary addressable memory. Blocks lie end to end, each after a
 * header of two cells: its size in bytes (header included, a multiple of 16) and a tag,
 * HEAP_USED or HEAP_FREE. A program can overwrite a header like any memory, so every
 * walk checks each header against the heap's bounds and tags, and a broken heap gives
 * an ior, never a write outside it. FREE and RESIZE accept only the address of a block
 * in use. Adjacent free blocks merge as ALLOCATE walks over them (first fit). */
#include <string.h>
#include "words.h"

#define HEAP_ALIGN 16
#define HEAP_HDR   16                      /* two cells (padded to HEAP_ALIGN) */
#define HEAP_USED  ((fbrl_cell)0x55534544) /* "USED" */
#define HEAP_FREE  ((fbrl_cell)0x46524545) /* "FREE" */

/* iors: the THROW codes a program would see for the same failure */
#define IOR_NOMEM  FBRL_THROW_DICT_OVERFLOW /* -8: no room */
#define IOR_BADPTR FBRL_THROW_BAD_ADDRESS   /* -9: not an allocated block */

typedef struct blk {
    fbrl_cell size, tag;
} blk;

static blk *at(const fbrl_vm *vm, const unsigned char *p)
{
    (void)vm;
    return (blk *)(void *)p;
}

/* The block at p is sound: inside the heap, tagged, sized in whole units. */
static int sound(const fbrl_vm *vm, const unsigned char *p)
{
    if (p < vm->heap_lo || vm->heap_hi - p < HEAP_HDR)
        return 0;
    const blk *b = at(vm, p);
    return (b->tag == HEAP_USED || b->tag == HEAP_FREE) && b->size >= HEAP_HDR && b->size % HEAP_ALIGN == 0 &&
           b->size <= vm->heap_hi - p;
}

int fbrl__heap_init(fbrl_vm *vm, unsigned char *lo, size_t size)
{
    size &= ~(size_t)(HEAP_ALIGN - 1);
    vm->heap_lo = lo;
    vm->heap_hi = lo + size;
    if (size >= HEAP_HDR) {
        blk *b = at(vm, lo);
        b->size = (fbrl_cell)size;
        b->tag = HEAP_FREE;
    }
    return 0;
}

/* The block in use whose data starts at addr, or NULL. */
static unsigned char *find_used(const fbrl_vm *vm, fbrl_cell addr)
{
    unsigned char *p = vm->heap_lo;
    while (p < vm->heap_hi && sound(vm, p)) {
        unsigned char *data = p + HEAP_HDR;
        if ((fbrl_cell)data == addr)
            return at(vm, p)->tag == HEAP_USED ? p : NULL;
        if ((fbrl_cell)data > addr)
            return NULL;
        p += at(vm, p)->size;
    }
    return NULL;
}

static fbrl_cell rounded(fbrl_cell n)
{
    return (fbrl_cell)(((fbrl_ucell)n + HEAP_HDR + HEAP_ALIGN - 1) & ~(fbrl_ucell)(HEAP_ALIGN - 1));
}

/* Split block p (in use, size >= need) to need bytes when the rest can be a block. */
static void split(fbrl_vm *vm, unsigned char *p, fbrl_cell need)
{
    blk *b = at(vm, p);
    if (b->size - need >= HEAP_HDR) {
        blk *r = at(vm, p + need);
        r->size = b->size - need;
        r->tag = HEAP_FREE;
        b->size = need;
    }
}

fbrl_cell fbrl__heap_alloc(fbrl_vm *vm, fbrl_cell size, fbrl_cell *addr)
{
    *addr = 0;
    if (size < 0 || (fbrl_ucell)size > (fbrl_ucell)(vm->heap_hi - vm->heap_lo))
        return IOR_NOMEM;
    fbrl_cell need = rounded(size);
    unsigned char *p = vm->heap_lo;
    while (p < vm->heap_hi) {
        if (!sound(vm, p))
            return IOR_BADPTR; /* overwritten: refuse rather than guess */
        blk *b = at(vm, p);
        if (b->tag == HEAP_FREE) {
            unsigned char *q = p + b->size; /* merge the free blocks after it */
            while (q < vm->heap_hi && sound(vm, q) && at(vm, q)->tag == HEAP_FREE) {
                b->size += at(vm, q)->size;
                q = p + b->size;
            }
            if (b->size >= need) {
                b->tag = HEAP_USED;
                split(vm, p, need);
                *addr = (fbrl_cell)(p + HEAP_HDR);
                return 0;
            }
        }
        p += b->size;
    }
    return IOR_NOMEM;
}

fbrl_cell fbrl__heap_free(fbrl_vm *vm, fbrl_cell addr)
{
    unsigned char *p = find_used(vm, addr);
    if (!p)
        return IOR_BADPTR;
    at(vm, p)->tag = HEAP_FREE;
    return 0;
}

/* RESIZE: in place when the block or the free blocks after it suffice, else move. */
static fbrl_cell heap_resize(fbrl_vm *vm, fbrl_cell addr, fbrl_cell size, fbrl_cell *out)
{
    *out = addr;
    unsigned char *p = find_used(vm, addr);
    if (!p)
        return IOR_BADPTR;
    if (size < 0 || (fbrl_ucell)size > (fbrl_ucell)(vm->heap_hi - vm->heap_lo))
        return IOR_NOMEM;
    fbrl_cell need = rounded(size);
    blk *b = at(vm, p);
    fbrl_cell have = b->size;
    unsigned char *q = p + have;
    while (have < need && q < vm->heap_hi && sound(vm, q) && at(vm, q)->tag == HEAP_FREE) {
        have += at(vm, q)->size;
        q = p + have;
    }
    if (have >= need) {
        b->size = have;
        split(vm, p, need);
        return 0;
    }
    fbrl_cell n;
    fbrl_cell ior = fbrl__heap_alloc(vm, size, &n);
    if (ior)
        return ior; /* the old block stays as it was */
    memcpy((void *)n, p + HEAP_HDR, (size_t)(b->size - HEAP_HDR));
    b->tag = HEAP_FREE;
    *out = n;
    return 0;
}

static fbrl_status w_allocate(fbrl_vm *vm, void *arg)
{
    fbrl_cell a;
    (void)arg;
    if (fbrl__cneed(vm, 1))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    fbrl_cell ior = fbrl__heap_alloc(vm, vm->sp[-1], &a);
    vm->sp[-1] = a;
    return fbrl__cthrow(vm, fbrl__cpush(vm, ior));
}

static fbrl_status w_free(fbrl_vm *vm, void *arg)
{
    (void)arg;
    if (fbrl__cneed(vm, 1))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    vm->sp[-1] = fbrl__heap_free(vm, vm->sp[-1]);
    return FBRL_OK;
}

static fbrl_status w_resize(fbrl_vm *vm, void *arg)
{
    fbrl_cell a;
    (void)arg;
    if (fbrl__cneed(vm, 2))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    fbrl_cell ior = heap_resize(vm, vm->sp[-2], vm->sp[-1], &a);
    vm->sp[-2] = a;
    vm->sp[-1] = ior;
    return FBRL_OK;
}

static fbrl_status w_unused_heap(fbrl_vm *vm, void *arg)
{
    fbrl_cell total = 0;
    (void)arg;
    for (unsigned char *p = vm->heap_lo; p < vm->heap_hi && sound(vm, p); p += at(vm, p)->size)
        if (at(vm, p)->tag == HEAP_FREE)
            total += at(vm, p)->size - HEAP_HDR;
    return fbrl__cthrow(vm, fbrl__cpush(vm, total));
}

static const fbrl_cword words[] = {
    {"ALLOCATE", w_allocate, NULL, 0,
     FBRL_DOC("( u -- a-addr ior )", "take u bytes from the heap (ior 0: done; -8: no room)")},
    {"FREE", w_free, NULL, 0,
     FBRL_DOC("( a-addr -- ior )", "give back a block ALLOCATE gave (ior -9: not one)")},
    {"RESIZE", w_resize, NULL, 0,
     FBRL_DOC("( a-addr1 u -- a-addr2 ior )", "change a block's size, keeping its contents (it may move)")},
    {"UNUSED-HEAP", w_unused_heap, NULL, 0, FBRL_DOC("( -- u )", "free bytes in the heap (in pieces)")},
};

int fbrl__heap_words(fbrl_vm *vm) { return fbrl__define_words(vm, words, sizeof words / sizeof words[0]); }
