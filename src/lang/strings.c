/* SPDX-License-Identifier: MIT */
/* strings.c - the STRING EXT words REPLACES SUBSTITUTE UNESCAPE.
 *
 * REPLACES keeps its name/text pairs in ALLOCATE's heap (heap.c), one block each, linked
 * from vm->subst: [next][name length][text length][name][text]. The heap is addressable,
 * so a program may have overwritten an entry: each is checked before it is read, and a
 * broken one ends the list. Names match without regard to case, as word names do. */
#include <string.h>
#include "words.h"

enum { E_NEXT, E_NLEN, E_TLEN, E_CELLS };

static fbrl_cell *entry(fbrl_vm *vm, fbrl_cell a)
{
    if (!a || !fbrl__addr_ok(vm, a, E_CELLS * CELL))
        return NULL;
    fbrl_cell *e = (fbrl_cell *)a;
    if (e[E_NLEN] < 0 || e[E_TLEN] < 0 || !fbrl__addr_ok(vm, a, E_CELLS * CELL + e[E_NLEN] + e[E_TLEN]))
        return NULL;
    return e;
}

/* The entry named s[0..n), and the link that points at it. */
static fbrl_cell *lookup(fbrl_vm *vm, const char *s, size_t n, fbrl_cell **link)
{
    fbrl_cell *prev = &vm->subst;
    int guard = 0;
    for (fbrl_cell *e; (e = entry(vm, *prev)) != NULL && guard < 100000; prev = &e[E_NEXT], guard++) {
        if ((size_t)e[E_NLEN] == n && fbrl__name_eq((const char *)(e + E_CELLS), s, n)) {
            if (link)
                *link = prev;
            return e;
        }
    }
    return NULL;
}

static int pop_str(fbrl_vm *vm, const char **s, size_t *n)
{
    fbrl_cell u = *--vm->sp, a = *--vm->sp;
    if (u < 0 || (u > 0 && !fbrl__addr_ok(vm, a, u)))
        return FBRL_THROW_BAD_ADDRESS;
    *s = u ? (const char *)a : ""; /* never NULL: memmove/memcmp of 0 bytes need a pointer too */
    *n = (size_t)u;
    return 0;
}

static fbrl_status w_replaces(fbrl_vm *vm, void *arg)
{
    const char *text, *name;
    size_t tn, nn;
    fbrl_cell *link, a;
    int r;
    (void)arg;
    if (fbrl__cneed(vm, 4))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    if ((r = pop_str(vm, &name, &nn)) || (r = pop_str(vm, &text, &tn)))
        return fbrl__cthrow(vm, r);
    fbrl_cell ior = fbrl__heap_alloc(vm, (fbrl_cell)(E_CELLS * CELL + nn + tn), &a);
    if (ior)
        return fbrl__cthrow(vm, fbrl__throw_msg(vm, (int)ior, "REPLACES: no room in the heap"));
    fbrl_cell *e = (fbrl_cell *)a;
    e[E_NLEN] = (fbrl_cell)nn;
    e[E_TLEN] = (fbrl_cell)tn;
    memmove(e + E_CELLS, name, nn);
    memmove((char *)(e + E_CELLS) + nn, text, tn);
    fbrl_cell *old = lookup(vm, name, nn, &link);
    if (old) { /* the new entry takes the old one's place */
        e[E_NEXT] = old[E_NEXT];
        *link = a;
        fbrl__heap_free(vm, (fbrl_cell)old);
    } else {
        e[E_NEXT] = vm->subst;
        vm->subst = a;
    }
    return FBRL_OK;
}

/* SUBSTITUTE into out[0..cap): the number of substitutions, or -1 if it does not fit. */
static fbrl_cell substitute(fbrl_vm *vm, const char *s, size_t n, char *out, size_t cap, size_t *len)
{
    size_t k = 0, i = 0;
    fbrl_cell count = 0;
#define PUT(p, m)                       \
    do {                                \
        if ((m) > cap - k)              \
            return -1;                  \
        if (m)                          \
            memmove(out + k, (p), (m)); \
        k += (m);                       \
    } while (0)
    while (i < n) {
        if (s[i] != '%') {
            PUT(s + i, 1);
            i++;
            continue;
        }
        if (i + 1 < n && s[i + 1] == '%') { /* %% is one % */
            PUT(s + i, 1);
            i += 2;
            continue;
        }
        const char *end = memchr(s + i + 1, '%', n - i - 1);
        fbrl_cell *e = end ? lookup(vm, s + i + 1, (size_t)(end - s - i - 1), NULL) : NULL;
        if (e) {
            PUT((const char *)(e + E_CELLS) + e[E_NLEN], (size_t)e[E_TLEN]);
            i = (size_t)(end - s) + 1;
            count++;
        } else { /* not a name: the % stays, the text after it is read on */
            PUT(s + i, 1);
            i++;
        }
    }
#undef PUT
    *len = k;
    return count;
}

static fbrl_status w_substitute(fbrl_vm *vm, void *arg)
{
    const char *s;
    size_t n, len = 0;
    int r;
    (void)arg;
    if (fbrl__cneed(vm, 4))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    fbrl_cell a2 = vm->sp[-2], u2 = vm->sp[-1];
    if (u2 < 0 || (u2 > 0 && !fbrl__addr_ok(vm, a2, u2)))
        return fbrl__cthrow(vm, FBRL_THROW_BAD_ADDRESS);
    vm->sp -= 2;
    if ((r = pop_str(vm, &s, &n)))
        return fbrl__cthrow(vm, r);
    /* the result is made in a heap block, so the two strings may overlap */
    fbrl_cell tmp = 0, count;
    if (u2 > 0 && fbrl__heap_alloc(vm, u2, &tmp))
        count = -1;
    else {
        count = substitute(vm, s, n, (char *)tmp, (size_t)u2, &len);
        if (count >= 0 && len)
            memmove((void *)a2, (void *)tmp, len);
    }
    if (tmp)
        fbrl__heap_free(vm, tmp);
    *vm->sp++ = a2;
    *vm->sp++ = count >= 0 ? (fbrl_cell)len : 0;
    *vm->sp++ = count >= 0 ? count : FBRL_THROW_PARSED_OVERFLOW;
    return FBRL_OK;
}

static fbrl_status w_unescape(fbrl_vm *vm, void *arg)
{
    const char *s;
    size_t n, m = 0;
    int r;
    (void)arg;
    if (fbrl__cneed(vm, 3))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    fbrl_cell a2 = *--vm->sp;
    if ((r = pop_str(vm, &s, &n)))
        return fbrl__cthrow(vm, r);
    for (size_t i = 0; i < n; i++)
        m += s[i] == '%' ? 2 : 1;
    if (m && !fbrl__addr_ok(vm, a2, (fbrl_cell)m))
        return fbrl__cthrow(vm, FBRL_THROW_BAD_ADDRESS);
    char *out = (char *)a2;
    for (size_t i = n, k = m; i-- > 0;) { /* from the end: out may start where s does */
        out[--k] = s[i];
        if (s[i] == '%')
            out[--k] = '%';
    }
    *vm->sp++ = a2;
    *vm->sp++ = (fbrl_cell)m;
    return FBRL_OK;
}

static const fbrl_cword words[] = {
    {"REPLACES", w_replaces, NULL, 0,
     FBRL_DOC("( c-addr1 u1 c-addr2 u2 -- )",
              "make %name% (c-addr2 u2) stand for the text c-addr1 u1 in SUBSTITUTE")},
    {"SUBSTITUTE", w_substitute, NULL, 0,
     FBRL_DOC("( c-addr1 u1 c-addr2 u2 -- c-addr2 u3 n )",
              "copy the text into the buffer replacing %name% and %% (n < 0: too long)")},
    {"UNESCAPE", w_unescape, NULL, 0,
     FBRL_DOC("( c-addr1 u1 c-addr2 -- c-addr2 u2 )",
              "copy the text doubling each %, so SUBSTITUTE gives it back")},
};

int fbrl__strings_init(fbrl_vm *vm) { return fbrl__define_words(vm, words, sizeof words / sizeof words[0]); }
