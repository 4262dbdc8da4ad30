/* SPDX-License-Identifier: MIT */
/* dict.c - the dictionary: word headers and their lookup, data space (ALLOT), the
 * compiler (compiling ops, literals and calls with peephole fusion), defining words
 * and FORGET. Nothing here executes code: the inner interpreter is run.c. */
#include <string.h>
#include "words.h"

/* FBRL_NO_HELP (a build option for small targets): no HELP texts in the image or the
 * headers; HELP then has only the word's name to go by. */
#ifdef FBRL_ROM_PRIMS
/* The primitives' names, one block: a member per op, so offsetof gives each name's place
 * (names keep their NUL: fbrl__op_name gives them as C strings). */
static const struct rom_names {
#define OP(id, nm, fl, st, hl) char n_##id[sizeof(nm)];
#include "ops.def"
#undef OP
} rom_names = {
#define OP(id, nm, fl, st, hl) nm,
#include "ops.def"
#undef OP
};
/* One primitive's header in flash (vm_internal.h, HDR): a nameless op's is hidden. */
typedef struct rom_prim {
    uint16_t name; /* offset in rom_names */
    uint8_t flags, len;
} rom_prim;
static const rom_prim rom_prims[OP__END] = {
#define OP(id, nm, fl, st, hl)                            \
    {(uint16_t)offsetof(struct rom_names, n_##id),       \
     (uint8_t)(sizeof(nm) > 1 ? (fl) : FH), (uint8_t)(sizeof(nm) - 1)},
#include "ops.def"
#undef OP
};
typedef char rom_names_fit[sizeof rom_names <= UINT16_MAX ? 1 : -1];
#define ROM_NAME(k) ((const char *)&rom_names + rom_prims[k].name)

/* The ring of primitives' headers made on demand (one image runs one engine thread; the
 * headers are the same for every VM). */
static fbrl_hdr rom_views[FBRL_ROM_VIEWS];
static unsigned rom_next;

fbrl_hdr *fbrl__rom_hdr(uint32_t op)
{
    fbrl_hdr *h = &rom_views[rom_next];
    rom_next = (rom_next + 1) % FBRL_ROM_VIEWS;
    memset(h, 0, sizeof *h);
    h->kind = K_PRIM;
    H_OP(h) = (uint16_t)op;
    h->flags = rom_prims[op].flags;
    h->len = rom_prims[op].len;
    h->name = ROM_NAME(op);
    return h;
}

const char *fbrl__op_name(int op) { return (op >= 0 && op < OP__END) ? ROM_NAME(op) : ""; }
#else
typedef struct opinfo {
    const char *name;
    uint8_t flags;
#ifndef FBRL_NO_HELP
    const char *stack, *help;
#endif
} opinfo;
static const opinfo ops[OP__END] = {
#ifdef FBRL_NO_HELP
#define OP(id, name, flags, stack, help) {name, flags},
#else
#define OP(id, name, flags, stack, help) {name, flags, stack, help},
#endif
#include "ops.def"
#undef OP
};
const char *fbrl__op_name(int op) { return (op >= 0 && op < OP__END) ? ops[op].name : ""; }
#endif

/* ---- memory checks ---- */
void *fbrl_vm_addr(fbrl_vm *vm, fbrl_cell addr, size_t n)
{
    if (!vm || !fbrl__addr_ok(vm, addr, (fbrl_cell)n))
        return NULL;
    return (void *)addr;
}

/* ---- dictionary ---- */
/* Upper case of each byte (names match regardless of case): a table, one load a byte. */
static const unsigned char upcase[256] = {
    0,   1,   2,   3,   4,   5,   6,   7,   8,   9,   10,  11,  12,  13,  14,  15,  16,  17,  18,  19,
    20,  21,  22,  23,  24,  25,  26,  27,  28,  29,  30,  31,  32,  33,  34,  35,  36,  37,  38,  39,
    40,  41,  42,  43,  44,  45,  46,  47,  48,  49,  50,  51,  52,  53,  54,  55,  56,  57,  58,  59,
    60,  61,  62,  63,  64,  65,  66,  67,  68,  69,  70,  71,  72,  73,  74,  75,  76,  77,  78,  79,
    80,  81,  82,  83,  84,  85,  86,  87,  88,  89,  90,  91,  92,  93,  94,  95,  96,  65,  66,  67,
    68,  69,  70,  71,  72,  73,  74,  75,  76,  77,  78,  79,  80,  81,  82,  83,  84,  85,  86,  87,
    88,  89,  90,  123, 124, 125, 126, 127, 128, 129, 130, 131, 132, 133, 134, 135, 136, 137, 138, 139,
    140, 141, 142, 143, 144, 145, 146, 147, 148, 149, 150, 151, 152, 153, 154, 155, 156, 157, 158, 159,
    160, 161, 162, 163, 164, 165, 166, 167, 168, 169, 170, 171, 172, 173, 174, 175, 176, 177, 178, 179,
    180, 181, 182, 183, 184, 185, 186, 187, 188, 189, 190, 191, 192, 193, 194, 195, 196, 197, 198, 199,
    200, 201, 202, 203, 204, 205, 206, 207, 208, 209, 210, 211, 212, 213, 214, 215, 216, 217, 218, 219,
    220, 221, 222, 223, 224, 225, 226, 227, 228, 229, 230, 231, 232, 233, 234, 235, 236, 237, 238, 239,
    240, 241, 242, 243, 244, 245, 246, 247, 248, 249, 250, 251, 252, 253, 254, 255,
};
#define upc(c) upcase[(unsigned char)(c)]

/* The full 32-bit hash of a name (kept in its header); its low bits pick the bucket. */
static uint32_t hash_name(const char *s, size_t n)
{
    uint32_t h = 2166136261u;
    for (size_t i = 0; i < n; i++)
        h = (h ^ upc(s[i])) * 16777619u;
    return h ^ (h >> 15);
}
/* The index of the RAM headers' names: a hash whose buckets live in the headers themselves,
 * bucket b's first header in the head field of the b-th RAM header. The number of buckets
 * is the largest power of two not above the number of RAM headers, so chains stay one or
 * two headers long on average however large the dictionary grows; when the headers reach
 * twice the buckets, the index doubles (rebuilt in one pass over the headers, so each
 * word costs O(1) on average). The index takes no memory of its own: the headers grow
 * down in the VM's block, out of reach of Forth code, and carry it. */
#define NRAM(vm) ((vm)->nwords - HDR_ROM)
static fbrl_hlink *bucket(const fbrl_vm *vm, uint32_t hn)
{
    return &HDR(vm, HDR_ROM + (hn & (vm->nbuckets - 1)))->head;
}
/* The first header (index+1) of hn's chain, 0: none. */
#define CHAIN(vm, hn) ((vm)->nbuckets ? *bucket((vm), (hn)) : 0u)
/* A header's hash, and whether it can be that of hash hn (FBRL_SMALL_HEADERS keeps none:
 * the name comparison decides). */
#ifdef FBRL_SMALL_HEADERS
#define HASH_OF(h)      hash_name((h)->name, (h)->len)
#define HASH_MAY(h, hn) ((void)(hn), 1)
#else
#define HASH_OF(h)      ((h)->hash)
#define HASH_MAY(h, hn) ((h)->hash == (hn))
#endif

static int name_eq(const char *a, const char *b, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (upc(a[i]) != upc(b[i]))
            return 0;
    return 1;
}

/* Position of word list wl in the search order (norder: not in it). */
static int order_rank(const fbrl_vm *vm, unsigned wl)
{
    int k = 0;
    while (k < vm->norder && vm->order[k] != wl)
        k++;
    return k;
}

#ifdef FBRL_ROM_PRIMS
/* The newest primitive of that name (all are in FORTH, word list 0), or -1. */
static int rom_find(const char *name, size_t len)
{
    for (uint32_t k = HDR_ROM; k-- > 0;) {
        if (rom_prims[k].len == len && !(rom_prims[k].flags & FH) && name_eq(ROM_NAME(k), name, len))
            return (int)k;
    }
    return -1;
}
#endif

/* The newest word of that name in the earliest word list of the search order. The hash
 * chain runs newest first, so a match in the first word list (the usual FORTH) ends the
 * walk at once: one list is as fast as before word lists. */
int fbrl__find(const fbrl_vm *vm, const char *name, size_t len)
{
    if (len == 0 || len > FBRL_NAME_MAX || vm->norder == 0)
        return -1;
    int best = -1, brank = vm->norder;
    uint32_t hn = hash_name(name, len), i = CHAIN(vm, hn);
    while (i) {
        const fbrl_hdr *h = HDR(vm, i - 1);
        if (HASH_MAY(h, hn) && h->len == len && !(h->flags & FH) && name_eq(h->name, name, len)) {
            int r = order_rank(vm, h->wl);
            if (r == 0)
                return (int)(i - 1);
            if (r < brank) {
                brank = r;
                best = (int)(i - 1);
            }
        }
        i = h->next;
    }
#ifdef FBRL_ROM_PRIMS
    if (order_rank(vm, 0) < brank) { /* the primitives: older than any RAM word */
        int k = rom_find(name, len);
        if (k >= 0)
            return k;
    }
#endif
    return best;
}

/* The newest word of that name in word list wl alone (SEARCH-WORDLIST). */
int fbrl__find_in(const fbrl_vm *vm, unsigned wl, const char *name, size_t len)
{
    if (len == 0 || len > FBRL_NAME_MAX)
        return -1;
    uint32_t hn = hash_name(name, len), i = CHAIN(vm, hn);
    while (i) {
        const fbrl_hdr *h = HDR(vm, i - 1);
        if (HASH_MAY(h, hn) && h->wl == wl && h->len == len && !(h->flags & FH) &&
            name_eq(h->name, name, len))
            return (int)(i - 1);
        i = h->next;
    }
#ifdef FBRL_ROM_PRIMS
    if (wl == 0)
        return rom_find(name, len);
#endif
    return -1;
}

int fbrl__name_eq(const char *a, const char *b, size_t n) { return name_eq(a, b, n); }

/* The index for the headers there are now (new_header_at when they reach twice the buckets,
 * and whenever words are forgotten). */
static void rebuild_hash(fbrl_vm *vm)
{
    uint32_t n = NRAM(vm), nb = n ? 1 : 0;
    while (nb && nb <= n / 2)
        nb *= 2;
    vm->data_hi = (unsigned char *)HDR_LOW(vm);
    vm->nbuckets = nb;
    for (uint32_t b = 0; b < nb; b++)
        HDR(vm, HDR_ROM + b)->head = 0;
    for (uint32_t i = HDR_ROM; i < vm->nwords; i++) { /* oldest first: chains run newest first */
        fbrl_hdr *h = HDR(vm, i);
        fbrl_hlink *b = bucket(vm, HASH_OF(h));
        h->next = *b;
        *b = (fbrl_hlink)(i + 1);
    }
}

fbrl_hdr *fbrl__xt_hdr(const fbrl_vm *vm, fbrl_cell xt)
{
    fbrl_ucell i = (fbrl_ucell)xt - FBRL_XT_BASE;
    return i < vm->nwords ? HDR(vm, i) : NULL;
}

uint32_t fbrl__hdr_index(const fbrl_vm *vm, const fbrl_hdr *h)
{
#ifdef FBRL_ROM_PRIMS
    if (h >= rom_views && h < rom_views + FBRL_ROM_VIEWS)
        return H_OP(h); /* a primitive's index is its op */
#endif
    return (uint32_t)(vm->hdr_top - 1 - h) + HDR_ROM;
}

static fbrl_cell hdr_xt(const fbrl_vm *vm, const fbrl_hdr *h)
{
    return (fbrl_cell)(FBRL_XT_BASE + fbrl__hdr_index(vm, h));
}

/* A new header; the name must be 1..31 characters (0 allowed only for :NONAME).
 * FBRL_SMALL_HEADERS (small targets): the header points at its name; a name that is not
 * `fixed` (a string that lives as long as the program) is copied to HERE first, so it
 * goes with the word when FORGET, MARKER or a failed definition drop it. */
static int new_header_at(fbrl_vm *vm, const char *name, size_t len, int kind, unsigned flags, int fixed,
                         fbrl_hdr **out)
{
    if (len > FBRL_NAME_MAX)
        return FBRL_THROW_NAME_TOO_LONG;
    if (vm->nwords >= FBRL_WORDS_MAX) /* its index + 1 must fit a chain link */
        return FBRL_THROW_DICT_OVERFLOW;
    unsigned char *newlo = (unsigned char *)(HDR_LOW(vm) - 1);
#ifdef FBRL_SMALL_HEADERS
    size_t copy = fixed || len == 0 ? 0 : len;
    if (vm->here > newlo || (size_t)(newlo - vm->here) < copy)
        return FBRL_THROW_DICT_OVERFLOW;
    if (copy) {
        memmove(vm->here, name, len);
        name = (const char *)vm->here;
        vm->here += len;
        vm->peep_end = NULL;
    }
#else
    (void)fixed;
    if (vm->here > newlo)
        return FBRL_THROW_DICT_OVERFLOW;
#endif
    fbrl_hdr *h = HDR(vm, vm->nwords);
    memset(h, 0, sizeof *h);
#ifdef FBRL_SMALL_HEADERS
    h->name = name;
#else
    memcpy(h->name, name, len);
#endif
    h->len = (uint8_t)len;
    h->kind = (uint8_t)kind;
    h->flags = (uint8_t)flags;
    h->wl = vm->current;
#ifndef FBRL_NO_HELP
    h->stack = "";
    h->help = "";
#endif
    uint32_t hn = hash_name(name, len);
#ifndef FBRL_SMALL_HEADERS
    h->hash = hn;
#endif
    fbrl__note_header(vm, h);
    vm->nwords++;
    if (NRAM(vm) >= 2 * vm->nbuckets) { /* the index doubles (and takes h in) */
        rebuild_hash(vm);
    } else {
        fbrl_hlink *b = bucket(vm, hn);
        h->next = *b;
        *b = (fbrl_hlink)vm->nwords;
        vm->data_hi = (unsigned char *)h;
    }
    *out = h;
    return 0;
}

static int new_header(fbrl_vm *vm, const char *name, size_t len, int kind, unsigned flags, fbrl_hdr **out)
{
    return new_header_at(vm, name, len, kind, flags, 0, out);
}

static fbrl_cell unused_bytes(const fbrl_vm *vm)
{
    return (fbrl_cell)((unsigned char *)HDR_LOW(vm) - vm->here);
}

int fbrl__allot(fbrl_vm *vm, fbrl_cell n)
{
    if (n >= 0) {
        if (n > unused_bytes(vm))
            return FBRL_THROW_DICT_OVERFLOW;
    } else if ((fbrl_ucell)(-(n + 1)) >= (fbrl_ucell)(vm->here - vm->dict_lo)) {
        return FBRL_THROW_BAD_ADDRESS;
    }
    vm->here += n;
    vm->peep_end = NULL;
    return 0;
}

int fbrl__align(fbrl_vm *vm)
{
    fbrl_ucell a = (fbrl_ucell)vm->here, m = (fbrl_ucell)CELL - 1;
    return fbrl__allot(vm, (fbrl_cell)(((a + m) & ~m) - a));
}

int fbrl__emit(fbrl_vm *vm, fbrl_cell v)
{
    if (unused_bytes(vm) < CELL)
        return FBRL_THROW_DICT_OVERFLOW;
    memcpy(vm->here, &v, sizeof v);
    vm->here += CELL;
    vm->peep_end = NULL;
    return 0;
}

/* ---- compilation helpers ---- */
/* Peephole fusion: common pairs of ops become one superinstruction (ops.def), and
 * a literal followed by CELLS, 1+, ... is folded. vm->peep is the last instruction
 * that fbrl__compile_op/fbrl__compile_lit emitted; it may be rewritten only while
 * HERE still ends it (peep_end == here). Everything else that moves HERE clears
 * peep_end, and so do the control-flow words and HERE itself, because a branch
 * target (a label at HERE) must never end up inside a fused instruction. */
static void peep_set(fbrl_vm *vm, unsigned char *at, unsigned char *prev)
{
    vm->peep_prev = prev;
    vm->peep = at;
    vm->peep_end = vm->here;
}
/* The instruction that ends at HERE and may be fused with, or NULL (asked before emitting). */
static unsigned char *peep_last(const fbrl_vm *vm) { return vm->peep_end == vm->here ? vm->peep : NULL; }

/* A comparison and its branch after DUP (DUP 2 < IF) or 2DUP (2DUP < IF): the op that
 * keeps what it compares, or 0. */
static int fuse_keep(fbrl_cell before, int op)
{
    static const struct {
        uint16_t before, op, fused;
    } triples[] = {
        {OP_DUP, OP_LITEQZBR, OP_DUPLITEQZBR},   {OP_DUP, OP_LITNEZBR, OP_DUPLITNEZBR},
        {OP_DUP, OP_LITLTZBR, OP_DUPLITLTZBR},   {OP_DUP, OP_LITGTZBR, OP_DUPLITGTZBR},
        {OP_TWODUP, OP_EQZBR, OP_TWODUPEQZBR},   {OP_TWODUP, OP_NEZBR, OP_TWODUPNEZBR},
        {OP_TWODUP, OP_LTZBR, OP_TWODUPLTZBR},   {OP_TWODUP, OP_GTZBR, OP_TWODUPGTZBR},
    };
    for (size_t i = 0; i < sizeof triples / sizeof triples[0]; i++)
        if (triples[i].before == before && triples[i].op == op)
            return triples[i].fused;
    return 0;
}

void fbrl__peep_reset(fbrl_vm *vm) { vm->peep_end = NULL; }

/* What `LIT v op` folds to: 1 and *v updated, or 0. */
static int fold_lit(int op, fbrl_cell *v)
{
    fbrl_ucell u = (fbrl_ucell)*v;
    switch (op) {
    case OP_CELLS: u *= (fbrl_ucell)CELL; break;
    case OP_CELLPLUS: u += (fbrl_ucell)CELL; break;
    case OP_FLOATS:
    case OP_DFLOATS: u *= sizeof(double); break;
    case OP_ONEPLUS:
    case OP_CHARPLUS: u += 1; break;
    case OP_ONEMINUS: u -= 1; break;
    case OP_TWOSTAR: u <<= 1; break;
    case OP_NEGATE: u = 0 - u; break;
    case OP_INVERT: u = ~u; break;
    case OP_CHARS: break;
    default: return 0;
    }
    *v = (fbrl_cell)u;
    return 1;
}

/* The superinstruction for `prev op`, or 0. */
static int fuse(fbrl_cell prev, int op)
{
    static const struct {
        uint16_t prev, op, fused;
    } pairs[] = {
        {OP_LIT, OP_PLUS, OP_LITPLUS},       {OP_LIT, OP_MINUS, OP_LITMINUS},
        {OP_LIT, OP_STAR, OP_LITSTAR},       {OP_LIT, OP_AND, OP_LITAND},
        {OP_LIT, OP_EQ, OP_LITEQ},           {OP_LIT, OP_NE, OP_LITNE},
        {OP_LIT, OP_LT, OP_LITLT},           {OP_LIT, OP_GT, OP_LITGT},
        {OP_LIT, OP_FETCH, OP_LITFETCH},     {OP_OVER, OP_PLUS, OP_OVERPLUS},
        {OP_I, OP_PLUS, OP_IPLUS},           {OP_CELLPLUS, OP_FETCH, OP_CELLPLUSFETCH},
        {OP_DUP, OP_FETCH, OP_DUPFETCH},     {OP_EQ, OP_ZBRANCH, OP_EQZBR},
        {OP_NE, OP_ZBRANCH, OP_NEZBR},       {OP_LT, OP_ZBRANCH, OP_LTZBR},
        {OP_GT, OP_ZBRANCH, OP_GTZBR},       {OP_ZEQ, OP_ZBRANCH, OP_ZEQZBR},
        {OP_LITEQ, OP_ZBRANCH, OP_LITEQZBR}, {OP_LITNE, OP_ZBRANCH, OP_LITNEZBR},
        {OP_LITLT, OP_ZBRANCH, OP_LITLTZBR}, {OP_LITGT, OP_ZBRANCH, OP_LITGTZBR},
        {OP_I, OP_FETCH, OP_IFETCH},         {OP_I, OP_CFETCH, OP_ICFETCH},
        {OP_I, OP_TWOFETCH, OP_ITWOFETCH},   {OP_I, OP_STORE, OP_ISTORE},
        {OP_I, OP_CSTORE, OP_ICSTORE},       {OP_I, OP_TWOSTORE, OP_ITWOSTORE},
        {OP_LIT, OP_PPLOOP, OP_LITPPLOOP},   {OP_DUP, OP_PPLOOP, OP_DUPPPLOOP},
        {OP_OVER, OP_FETCH, OP_OVERFETCH},   {OP_PICK2, OP_FETCH, OP_PICK2FETCH},
        {OP_STAR, OP_PLUS, OP_STARPLUS},
        {OP_LITPLUS, OP_FETCH, OP_LITPLUSFETCH}, {OP_LITPLUS, OP_CFETCH, OP_LITPLUSCFETCH},
        {OP_LITPLUS, OP_STORE, OP_LITPLUSSTORE}, {OP_LITPLUS, OP_CSTORE, OP_LITPLUSCSTORE},
        {OP_I, OP_STOF, OP_ISTOF},           {OP_FOVER, OP_FOVER, OP_FOVERFOVER},
        {OP_FDUP, OP_FSTAR, OP_FDUPFSTAR},   {OP_I, OP_J, OP_IJ},
    };
    for (size_t i = 0; i < sizeof pairs / sizeof pairs[0]; i++)
        if (pairs[i].prev == prev && pairs[i].op == op)
            return pairs[i].fused;
    return 0;
}

/* Compile one op (a primitive, or OP_ZBRANCH or OP_PPLOOP, whose target the caller emits
 * next). */
int fbrl__compile_op(fbrl_vm *vm, int op)
{
    if (vm->peep_end && vm->peep_end == vm->here) {
        /* (HERE need not be aligned: , and C, can leave it anywhere, so memcpy) */
        unsigned char *p = vm->peep;
        fbrl_cell prev, v;
        int f;
        memcpy(&prev, p, sizeof prev);
        if (prev == OP_LIT || prev == OP_DROPLIT) {
            memcpy(&v, p + CELL, sizeof v);
            if (fold_lit(op, &v)) {
                memcpy(p + CELL, &v, sizeof v);
                return 0;
            }
            if (op == OP_PICK && prev == OP_LIT && v >= 0 && v <= 2) { /* 0 PICK = DUP, 1 PICK = OVER */
                prev = v == 0 ? OP_DUP : v == 1 ? OP_OVER : OP_PICK2;
                memcpy(p, &prev, sizeof prev);
                vm->here -= CELL;
                vm->peep_end = vm->here;
                return 0;
            }
            if (prev == OP_DROPLIT && fuse(OP_LIT, op)) {
                /* DROPLIT v | op  ->  DROP | LIT v | op: the literal's own pair (V @, 1 +)
                 * saves as much, and a debugger steps over DROP and V @ as written */
                int r = fbrl__emit(vm, v);
                if (r)
                    return r;
                prev = OP_DROP;
                memcpy(p, &prev, sizeof prev);
                prev = OP_LIT;
                memcpy(p + CELL, &prev, sizeof prev);
                vm->peep_prev = p;
                vm->peep = p += CELL;
                vm->peep_end = vm->here;
            }
        }
        if ((f = fuse(prev, op))) {
            prev = f;
            memcpy(p, &prev, sizeof prev);
            unsigned char *q = vm->peep_prev;
            fbrl_cell before = 0;
            if (q)
                memcpy(&before, q, sizeof before);
            if ((f = fuse_keep(before, (int)prev))) {
                /* DUP | LITxZBR lit  ->  DUPLITxZBR lit;  2DUP | xZBR  ->  2DUPxZBR (the
                 * caller emits the target next): the fused op and its literal move down */
                prev = f;
                memcpy(q, &prev, sizeof prev);
                memmove(q + CELL, p + CELL, (size_t)(vm->here - (p + CELL)));
                vm->here -= CELL;
                vm->peep = q;
                vm->peep_prev = NULL;
                vm->peep_end = vm->here;
            }
            return 0;
        }
    }
    unsigned char *at = vm->here, *prev = peep_last(vm);
    int r = fbrl__emit(vm, op);
    if (!r)
        peep_set(vm, at, prev);
    return r;
}

int fbrl__compile_xt(fbrl_vm *vm, fbrl_cell xt)
{
    fbrl_hdr *h = fbrl__xt_hdr(vm, xt);
    fbrl_cell v;
    int r;
    if (!h)
        return fbrl__throw_msg(vm, FBRL_THROW_UNDEFINED, "invalid execution token");
    switch (h->kind) {
    case K_PRIM:
        if (H_OP(h) == OP_EXIT && vm->nlocals && (r = fbrl__compile_xt(vm, vm->lexit_xt)))
            return r; /* EXIT from a definition with locals drops their frame first */
        return fbrl__compile_op(vm, H_OP(h));
    case K_COLON:
        if ((r = fbrl__emit(vm, OP_CALL)))
            return r;
        return fbrl__emit(vm, h->body);
    case K_CREATE:
        /* Without DOES> a created word is a literal. DOES> can only change the
         * latest word, and a word compiled into a definition is no longer latest. */
        if (H_DOES(h))
            return fbrl__emit(vm, xt);
        /* fall through */
    case K_VAR: return fbrl__compile_lit(vm, h->body);
    case K_CONST: memcpy(&v, (void *)h->body, sizeof v); return fbrl__compile_lit(vm, v);
    default: return fbrl__emit(vm, xt);
    }
}

int fbrl__compile_lit(fbrl_vm *vm, fbrl_cell v)
{
    if (vm->peep_end && vm->peep_end == vm->here) { /* DROP 1  ->  DROPLIT 1 */
        fbrl_cell prev;
        memcpy(&prev, vm->peep, sizeof prev);
        if (prev == OP_DROP) {
            prev = OP_DROPLIT;
            memcpy(vm->peep, &prev, sizeof prev);
            int r = fbrl__emit(vm, v);
            if (!r)
                vm->peep_end = vm->here;
            return r;
        }
    }
    unsigned char *at = vm->here, *prev = peep_last(vm);
    int r = fbrl__emit(vm, OP_LIT);
    if (r || (r = fbrl__emit(vm, v)))
        return r;
    peep_set(vm, at, prev);
    return 0;
}

int fbrl__compile_flit(fbrl_vm *vm, double d)
{
    int r = fbrl__emit(vm, OP_FLIT);
    fbrl_cell c[(sizeof(double) + sizeof(fbrl_cell) - 1) / sizeof(fbrl_cell)] = {0};
    memcpy(c, &d, sizeof d);
    for (size_t i = 0; !r && i < sizeof c / sizeof c[0]; i++)
        r = fbrl__emit(vm, c[i]);
    return r;
}

/* Compiled string: op, length, bytes (padded to a cell). */
int fbrl__compile_str(fbrl_vm *vm, int op, const char *s, size_t n)
{
    int r;
    if (n > 65535)
        return FBRL_THROW_PARSED_OVERFLOW;
    if ((r = fbrl__emit(vm, op)) || (r = fbrl__emit(vm, (fbrl_cell)n)))
        return r;
    fbrl_cell need = (fbrl_cell)((n + 1 + (size_t)CELL - 1) / (size_t)CELL * (size_t)CELL);
    if (unused_bytes(vm) < need)
        return FBRL_THROW_DICT_OVERFLOW;
    memmove(vm->here, s, n);
    memset(vm->here + n, 0, (size_t)need - n);
    vm->here += need;
    vm->peep_end = NULL;
    return 0;
}

/* Capture "( stack )" and "\ help" following a new word's name on its line. */
static void capture_help(fbrl_vm *vm, fbrl_hdr *h, const char *dstack, const char *dhelp)
{
#ifdef FBRL_NO_HELP
    (void)vm, (void)h, (void)dstack, (void)dhelp;
#else
    h->stack = dstack;
    h->help = dhelp;
    if (vm->nsrc == 0)
        return;
    fbrl_src *s = fbrl__src(vm);
    size_t i = fbrl__src_in(vm, s), n = s->len;
    const char *b = s->buf;
    const char *st = NULL, *hp = NULL;
    size_t stn = 0, hpn = 0;
    while (i < n && (unsigned char)b[i] <= ' ')
        i++;
    if (i + 1 < n && b[i] == '(' && (unsigned char)b[i + 1] <= ' ') {
        const char *e = memchr(b + i, ')', n - i);
        if (e) {
            st = b + i;
            stn = (size_t)(e - st) + 1;
            i = (size_t)(e - b) + 1;
            while (i < n && (unsigned char)b[i] <= ' ')
                i++;
        }
    }
    if (i < n && b[i] == '\\' && (i + 1 == n || (unsigned char)b[i + 1] <= ' ')) {
        i++;
        while (i < n && (unsigned char)b[i] <= ' ')
            i++;
        hp = b + i;
        hpn = n - i;
        while (hpn && (unsigned char)hp[hpn - 1] <= ' ')
            hpn--;
    }
    if (!st && !hp)
        return;
    vm->peep_end = NULL;
    if (unused_bytes(vm) < (fbrl_cell)(stn + hpn + 2 + 64))
        return;
    if (st) {
        memmove(vm->here, st, stn);
        vm->here[stn] = 0;
        h->stack = (const char *)vm->here;
        vm->here += stn + 1;
    }
    if (hp) {
        memmove(vm->here, hp, hpn);
        vm->here[hpn] = 0;
        h->help = (const char *)vm->here;
        vm->here += hpn + 1;
    }
#endif
}

/* Make a word of the given kind with its data field aligned at HERE. */
int fbrl__new_word(fbrl_vm *vm, const char *name, size_t len, int kind, const char *stack, const char *help,
                   fbrl_hdr **out)
{
    fbrl_hdr *h;
    int r;
    if (len == 0)
        return FBRL_THROW_NO_NAME;
    if (unused_bytes(vm) < 256 + (fbrl_cell)sizeof(fbrl_hdr))
        return FBRL_THROW_DICT_OVERFLOW;
    if ((r = new_header(vm, name, len, kind, 0, &h)))
        return r;
#ifdef FBRL_NO_HELP
    (void)stack, (void)help;
#else
    h->stack = stack;
    h->help = help;
#endif
    h->body = (fbrl_cell)vm->here;
    if ((r = fbrl__align(vm)))
        return r;
    h->body = (fbrl_cell)vm->here;
    *out = h;
    return 0;
}

/* Parse a name and make a word of the given kind; a "( stack )" and "\ help" comment
 * after the name on its line become the word's HELP text. */
int fbrl__create(fbrl_vm *vm, int kind, const char *dstack, const char *dhelp, fbrl_hdr **out)
{
    const char *name;
    size_t len;
    fbrl_hdr *h;
    int r;
    fbrl__parse_name(vm, &name, &len);
    if ((r = fbrl__new_word(vm, name, len, kind, dstack, dhelp, &h)))
        return r;
    capture_help(vm, h, dstack, dhelp);
    if ((r = fbrl__align(vm)))
        return r;
    h->body = (fbrl_cell)vm->here;
    *out = h;
    return 0;
}

/* ---- colon definitions ---- */
static void discard_definition(fbrl_vm *vm);

int fbrl__colon(fbrl_vm *vm, int noname, fbrl_cell *xt)
{
    fbrl_hdr *h;
    int r;
    if (*vm->state)
        return FBRL_THROW_COMPILER_NESTING;
    /* A definition left open in interpretation state (": A 1 [" and never closed)
     * is abandoned: it was never finished, so it was never findable either. */
    if (vm->defining)
        discard_definition(vm);
    vm->def_here = vm->here;
    vm->def_nwords = vm->nwords;
    vm->nbr_orig = vm->nexit_orig = 0; /* words.c: no BRANCH of this definition yet */
    if (noname) {
        if (unused_bytes(vm) < 256 + (fbrl_cell)sizeof(fbrl_hdr))
            return FBRL_THROW_DICT_OVERFLOW;
        if ((r = new_header(vm, "", 0, K_COLON, FH, &h)) || (r = fbrl__align(vm)))
            goto fail;
        h->body = (fbrl_cell)vm->here;
    } else {
        if ((r = fbrl__create(vm, K_COLON, "", "", &h)))
            goto fail;
        h->flags |= FH;
    }
#ifndef FBRL_NO_HELP
    h->stack = h->stack[0] ? h->stack : "( i*x -- j*x )";
    h->help = h->help[0] ? h->help : "colon definition";
#endif
    vm->defining = 1;
    vm->def_word = vm->nwords - 1;
    vm->ncf = 1;
    vm->cf[0].tag = CF_COLON;
    vm->cf[0].a = 0;
    *vm->state = -1;
    if (xt)
        *xt = hdr_xt(vm, h);
    return 0;
fail:
    vm->here = vm->def_here;
    vm->peep_end = NULL;
    vm->nwords = vm->def_nwords;
    rebuild_hash(vm);
    return r;
}

/* ; is about to compile its EXIT at HERE (words.c resolve() noted the forward BRANCHes
 * that land there): a BRANCH that jumps there (ELSE ... THEN ;)
 * becomes EXITBR, an EXIT that keeps the branch's target for SEE. */
static void exit_branches(fbrl_vm *vm)
{
    if (vm->exit_here == vm->here) {
        for (unsigned i = 0; i < vm->nexit_orig; i++) {
            fbrl_cell at = vm->exit_orig[i] - CELL, op;
            if (!fbrl__addr_ok(vm, at, CELL))
                continue;
            memcpy(&op, (void *)at, sizeof op);
            if (op == OP_BRANCH) {
                op = OP_EXITBR;
                memcpy((void *)at, &op, sizeof op);
            }
        }
    }
    vm->nbr_orig = vm->nexit_orig = 0;
    vm->exit_here = NULL;
}

int fbrl__semicolon(fbrl_vm *vm)
{
    int r;
    if (!vm->defining || vm->ncf != 1 || vm->cf[0].tag != CF_COLON)
        return FBRL_THROW_CONTROL_MISMATCH;
    if (vm->nlocals && (r = fbrl__compile_xt(vm, vm->lexit_xt)))
        return r;
    vm->nlocals = vm->lpend = 0;
    exit_branches(vm);
    if ((r = fbrl__emit(vm, OP_EXIT)))
        return r;
    fbrl_hdr *h = HDR(vm, vm->def_word);
    H_END(h) = (fbrl_cell)vm->here;
    if (h->len)
        h->flags &= (uint8_t)~FH;
    vm->defining = 0;
    vm->ncf = 0;
    *vm->state = 0;
    return 0;
}

/* After an error: drop a half-made definition, back to interpretation. */
static void discard_definition(fbrl_vm *vm)
{
    vm->nlocals = vm->lpend = 0;
    if (vm->defining) {
        vm->here = vm->def_here;
        vm->nwords = vm->def_nwords;
        rebuild_hash(vm);
        fbrl__lines_forget(vm);
        vm->defining = 0;
        vm->peep_end = NULL;
    }
    vm->ncf = 0;
    *vm->state = 0;
}

void fbrl__drop_definition(fbrl_vm *vm) { discard_definition(vm); }

void fbrl__forget(fbrl_vm *vm, unsigned char *here, uint32_t nwords, size_t req_used)
{
    vm->here = here;
    vm->peep_end = NULL;
    vm->nwords = nwords;
    if (req_used <= vm->req_used)
        vm->req_used = req_used;
    rebuild_hash(vm);
    fbrl__lines_forget(vm);
}

/* Primitives with a dictionary entry (internal ops and superinstructions have none). */
size_t fbrl__named_ops(void)
{
    size_t n = 0;
    for (int op = 0; op < OP__END; op++)
        n += fbrl__op_name(op)[0] != 0;
    return n;
}

static int valid_name(const char *name, size_t n)
{
    if (n == 0 || n > FBRL_NAME_MAX)
        return 0;
    for (size_t i = 0; i < n; i++)
        if ((unsigned char)name[i] <= ' ')
            return 0;
    return 1;
}

fbrl_status fbrl_vm_define(fbrl_vm *vm, const char *name, fbrl_vm_prim fn, void *arg,
                           const char *stack_effect, const char *help)
{
    fbrl_hdr *h;
    if (!vm || !name || !fn)
        return FBRL_EINVAL;
    if (vm->defining)
        return FBRL_ESTATE;
    size_t n = strlen(name);
    if (!valid_name(name, n))
        return FBRL_ENAME;
    if (new_header(vm, name, n, K_CFUNC, 0, &h))
        return FBRL_ENOMEM;
    H_FN(h) = fn;
    H_ARG(h) = arg;
    h->body = (fbrl_cell)vm->here;
#ifdef FBRL_NO_HELP
    (void)stack_effect, (void)help;
#else
    h->stack = stack_effect ? stack_effect : "";
    h->help = help ? help : "";
#endif
    return FBRL_OK;
}

/* The engine's own C words (word lists, locals, memory, files ...) into the current word list. */
int fbrl__define_words(fbrl_vm *vm, const fbrl_cword *w, size_t n)
{
    for (size_t k = 0; k < n; k++) {
        fbrl_hdr *h;
        if (new_header(vm, w[k].name, strlen(w[k].name), K_CFUNC, w[k].flags, &h))
            return FBRL_THROW_DICT_OVERFLOW;
        H_FN(h) = w[k].fn;
        H_ARG(h) = w[k].arg;
        h->body = (fbrl_cell)vm->here;
#ifndef FBRL_NO_HELP
        h->stack = w[k].stack;
        h->help = w[k].help;
#endif
    }
    return 0;
}

/* SYNONYM: a new header that is a copy of old (its behaviour, flags and data), named name. */
int fbrl__synonym(fbrl_vm *vm, const char *name, size_t len, const fbrl_hdr *old)
{
    fbrl_hdr *h, copy = *old;
    int r = new_header(vm, name, len, old->kind, old->flags & (FI | FC | FS), &h);
    if (r)
        return r;
    fbrl_hlink next = h->next, head = h->head; /* its place in the index stays */
    uint8_t wl = h->wl;
#ifdef FBRL_SMALL_HEADERS
    const char *own = h->name; /* new_header copied the name to HERE */
    *h = copy;
    h->name = own;
#else
    uint32_t hash = h->hash;
    *h = copy;
    memset(h->name, 0, sizeof h->name);
    memcpy(h->name, name, len);
    h->hash = hash;
#endif
    h->len = (uint8_t)len;
    h->next = next;
    h->head = head;
    h->wl = wl;
    h->flags = (uint8_t)(old->flags & (FI | FC | FS));
    return 0;
}

fbrl_status fbrl_vm_help(const fbrl_vm *vm, const char *name, const char **stack_effect, const char **help)
{
    if (!vm || !name)
        return FBRL_EINVAL;
    int i = fbrl__find(vm, name, strlen(name));
    if (i < 0)
        return FBRL_ENOENT;
#ifdef FBRL_NO_HELP
    if (stack_effect)
        *stack_effect = "";
    if (help)
        *help = "";
#else
    const fbrl_hdr *h = HDR(vm, i);
    if (stack_effect)
        *stack_effect = h->stack;
    if (help)
        *help = h->help;
#endif
    return FBRL_OK;
}

/* True if find(name of word i) gives word i: what fbrl__find does, from the stored hash. */
static int found_as_itself(const fbrl_vm *vm, uint32_t i)
{
    const fbrl_hdr *w = HDR(vm, i);
    int rw = order_rank(vm, w->wl);
    if (rw >= vm->norder)
        return 0;
    uint32_t wh = HASH_OF(w);
#ifdef FBRL_ROM_PRIMS
    int k = rom_find(w->name, w->len); /* a primitive of that name: older than any RAM word */
    if (k >= 0 && (i < HDR_ROM ? (uint32_t)k != i : order_rank(vm, 0) < rw))
        return 0;
#endif
    for (uint32_t j = CHAIN(vm, wh); j; j = HDR(vm, j - 1)->next) {
        const fbrl_hdr *h = HDR(vm, j - 1);
        if (j - 1 == i || !HASH_MAY(h, wh) || h->len != w->len || (h->flags & FH) ||
            !name_eq(h->name, w->name, w->len))
            continue;
        int r = order_rank(vm, h->wl);
        if (r < rw || (r == rw && j - 1 > i)) /* an earlier list, or newer in the same */
            return 0;
    }
    return 1;
}

void fbrl_vm_words(const fbrl_vm *vm, int (*fn)(void *ctx, const char *name, size_t len), void *ctx)
{
    if (!vm || !fn)
        return;
    for (uint32_t i = vm->nwords; i-- > 0;) {
        const fbrl_hdr *h = HDR(vm, i);
        if (!h->len || (h->flags & FH))
            continue;
        /* skip words find would not give (shadowed, or out of the search order) */
        if (!found_as_itself(vm, i))
            continue;
        if (fn(ctx, h->name, h->len))
            return;
    }
}

/* One header per named primitive, in ops.def order (fbrl_vm_create calls this first). */
int fbrl__install_prims(fbrl_vm *vm)
{
#ifdef FBRL_ROM_PRIMS
    (void)vm; /* their headers are rom_prims */
#else
    for (int op = 0; op < OP__END; op++) {
        fbrl_hdr *h;
        if (!ops[op].name[0])
            continue;
        if (new_header_at(vm, ops[op].name, strlen(ops[op].name), K_PRIM, ops[op].flags, 1, &h))
            return FBRL_THROW_DICT_OVERFLOW;
        H_OP(h) = (uint16_t)op;
#ifndef FBRL_NO_HELP
        h->stack = ops[op].stack;
        h->help = ops[op].help;
#endif
    }
#endif
    return 0;
}

fbrl_status fbrl_vm_locate(const fbrl_vm *vm, const char *name, const char **file, unsigned long *line)
{
    if (!vm || !name || !file || !line)
        return FBRL_EINVAL;
    int i = fbrl__find(vm, name, strlen(name));
    if (i < 0)
        return FBRL_ENOENT;
    const fbrl_hdr *h = HDR(vm, i);
    int built_in =
        h->kind == K_PRIM || HDR_LINE(h) == 0 || (h->kind == K_COLON && h->body < (fbrl_cell)vm->dict_lo);
    *file = built_in ? "" : fbrl__file_name(vm, HDR_FILE(h));
    *line = built_in ? 0 : HDR_LINE(h);
    return FBRL_OK;
}

size_t fbrl_vm_word_count(const fbrl_vm *vm) { return vm ? vm->nwords : 0; }
