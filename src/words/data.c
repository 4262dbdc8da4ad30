/* SPDX-License-Identifier: MIT */
/* words_fbrl.c - FBRL's data-structure words (thesis appendix I-1 .. I-3):
 * queues (bound to the ring module), one- and two-dimensional arrays (bound to the
 * matrix module's fbrl_array), counted strings, and the data type sizes.
 *
 * Every structure lives in the VM's data space, where a program can overwrite it.
 * Each use therefore re-checks the structure before trusting it: a magic cell, the
 * storage pointer the C module keeps (it must point just behind the structure) and
 * the extent of the storage (inside the data space). A corrupted structure throws
 * instead of letting the C module touch memory outside the VM. */
#include <stdio.h>
#include <string.h>
#include "fbrl/matrix.h"
#include "fbrl/ring.h"
#include "fbrl/vmx.h"

static const fbrl_vmx_type queue_type = {"queue", (fbrl_cell)0x51554555 /* "QUEU" */};
static const fbrl_vmx_type array_type = {"array", (fbrl_cell)0x41525259 /* "ARRY" */};
#define STR_MAX 65535

static fbrl_cell align16(fbrl_cell a) { return (fbrl_cell)(((fbrl_ucell)a + 15) & ~(fbrl_ucell)15); }

static fbrl_status fail(fbrl_vm *vm, int code, const char *msg) { return fbrl_vm_throw(vm, code, msg); }
static fbrl_status need(fbrl_vm *vm, size_t n)
{
    return fbrl_vm_depth(vm) < n ? fbrl_vm_throw(vm, FBRL_THROW_STACK_UNDERFLOW, NULL) : FBRL_OK;
}

/* ---- I-1 queues ---- */
static fbrl_ring *queue_at(fbrl_vm *vm, fbrl_cell q, fbrl_status *st)
{
    fbrl_cell magic;
    *st = FBRL_OK;
    if (!fbrl_vm_addr(vm, q, sizeof(fbrl_cell))) {
        *st = fail(vm, FBRL_THROW_BAD_ADDRESS, NULL);
        return NULL;
    }
    memcpy(&magic, (void *)q, sizeof magic);
    if (magic != queue_type.magic) {
        *st = fail(vm, FBRL_THROW_TYPE_MISMATCH, "not a queue (use a CREATE-Q name)");
        return NULL;
    }
    fbrl_ring *r = fbrl_vmx_data(vm, q, &queue_type, sizeof(fbrl_ring));
    if (!r) {
        *st = fail(vm, FBRL_THROW_BAD_ADDRESS, NULL);
        return NULL;
    }
    size_t cap = r->mask + 1;
    if (r->buf != (uint8_t *)(r + 1) || cap == 0 || (cap & r->mask) ||
        !fbrl_vm_addr(vm, (fbrl_cell)r->buf, cap)) {
        *st = fail(vm, FBRL_THROW_BAD_ADDRESS, "queue structure overwritten");
        return NULL;
    }
    return r;
}

/* Pops ( q -- ) and checks it is a queue. */
static fbrl_ring *pop_queue(fbrl_vm *vm, fbrl_status *st)
{
    fbrl_cell q;
    if ((*st = need(vm, 1)))
        return NULL;
    fbrl_vm_pop(vm, &q);
    return queue_at(vm, q, st);
}

static fbrl_status w_create_q(fbrl_vm *vm, void *arg)
{
    fbrl_cell n;
    void *p;
    fbrl_status st;
    (void)arg;
    if ((st = need(vm, 1)))
        return st;
    fbrl_vm_pop(vm, &n);
    if (n < 2 || n > (1 << 24))
        return fail(vm, FBRL_THROW_BAD_NUMBER, "queue size must be 2..16777216 bytes");
    if ((st = fbrl_vmx_create(vm, NULL, 0, &queue_type, sizeof(fbrl_ring) + (size_t)n, NULL, NULL,
                              FBRL_DOC_TEXT("( -- q-addr )"), FBRL_DOC_TEXT("queue"), NULL, &p)))
        return st;
    return fbrl_ring_init((fbrl_ring *)p, (fbrl_ring *)p + 1, (size_t)n);
}

static fbrl_status w_enq(fbrl_vm *vm, void *arg)
{
    fbrl_cell q, c;
    fbrl_status st;
    (void)arg;
    if ((st = need(vm, 2)))
        return st;
    fbrl_vm_pop(vm, &q);
    fbrl_vm_pop(vm, &c);
    fbrl_ring *r = queue_at(vm, q, &st);
    if (!r)
        return st;
    if (fbrl_ring_put(r, (uint8_t)c) != FBRL_OK)
        return fail(vm, FBRL_VM_THROW_OF_STATUS(FBRL_EFULL), "queue full");
    return FBRL_OK;
}

static fbrl_status w_deq(fbrl_vm *vm, void *arg)
{
    uint8_t b;
    fbrl_status st;
    (void)arg;
    fbrl_ring *r = pop_queue(vm, &st);
    if (!r)
        return st;
    if (fbrl_ring_get(r, &b) != FBRL_OK)
        return fail(vm, FBRL_VM_THROW_OF_STATUS(FBRL_EEMPTY), "queue empty");
    return fbrl_vm_push(vm, b);
}

static fbrl_status w_q_test(fbrl_vm *vm, void *arg)
{
    fbrl_status st;
    fbrl_ring *r = pop_queue(vm, &st);
    if (!r)
        return st;
    int yes = arg ? fbrl_ring_full(r) : fbrl_ring_empty(r);
    return fbrl_vm_push(vm, yes ? -1 : 0);
}

static fbrl_status w_q_count(fbrl_vm *vm, void *arg)
{
    fbrl_status st;
    (void)arg;
    fbrl_ring *r = pop_queue(vm, &st);
    if (!r)
        return st;
    return fbrl_vm_push(vm, (fbrl_cell)fbrl_ring_count(r));
}

/* ---- I-2 arrays ---- */
static fbrl_array *array_at(fbrl_vm *vm, fbrl_cell body, fbrl_status *st)
{
    size_t bytes;
    *st = FBRL_OK;
    if (!fbrl_vm_addr(vm, body, FBRL_VMX_PAYLOAD + sizeof(fbrl_array))) {
        *st = fail(vm, FBRL_THROW_BAD_ADDRESS, NULL);
        return NULL;
    }
    fbrl_array *a = fbrl_vmx_data(vm, body, &array_type, sizeof(fbrl_array));
    if (!a || a->data != (unsigned char *)align16((fbrl_cell)a + (fbrl_cell)sizeof(fbrl_array)) ||
        fbrl_array_bytes(a->cell_size, a->rows, a->cols, &bytes) != FBRL_OK ||
        !fbrl_vm_addr(vm, (fbrl_cell)a->data, bytes)) {
        *st = fail(vm, FBRL_THROW_BAD_ADDRESS, "array structure overwritten");
        return NULL;
    }
    return a;
}

static fbrl_status array_run(fbrl_vm *vm, const void *body, int two)
{
    fbrl_cell i, j = 0;
    fbrl_status st;
    void *cell;
    fbrl_array *a = array_at(vm, (fbrl_cell)body, &st);
    if (!a)
        return st;
    if ((st = need(vm, two ? 2 : 1)))
        return st;
    if (two)
        fbrl_vm_pop(vm, &j);
    fbrl_vm_pop(vm, &i);
    if (i < 0 || j < 0)
        return fail(vm, FBRL_VM_THROW_OF_STATUS(FBRL_ERANGE), "array index out of range");
    st = two ? fbrl_array2_cell(a, (size_t)i, (size_t)j, &cell) : fbrl_array_cell(a, (size_t)i, &cell);
    if (st != FBRL_OK)
        return fail(vm, FBRL_VM_THROW_OF_STATUS(st), "array index out of range");
    return fbrl_vm_push(vm, (fbrl_cell)cell);
}
static fbrl_status w_array1_run(fbrl_vm *vm, void *ctx, const void *body)
{
    (void)ctx;
    return array_run(vm, body, 0);
}
static fbrl_status w_array2_run(fbrl_vm *vm, void *ctx, const void *body)
{
    (void)ctx;
    return array_run(vm, body, 1);
}

static fbrl_status make_array(fbrl_vm *vm, fbrl_cell rows, fbrl_cell cols, fbrl_cell size, int two)
{
    size_t bytes;
    void *p;
    fbrl_status st;
    if (rows < 1 || cols < 1 || size < 1 || rows > 65535 || cols > 65535 || size > 65535)
        return fail(vm, FBRL_THROW_BAD_NUMBER, "array sizes must be 1..65535");
    if (fbrl_array_bytes((size_t)size, (size_t)rows, (size_t)cols, &bytes) != FBRL_OK)
        return fail(vm, FBRL_THROW_BAD_NUMBER, NULL);
    if ((st = fbrl_vmx_create(vm, NULL, 0, &array_type, sizeof(fbrl_array) + 16 + bytes,
                              two ? w_array2_run : w_array1_run, NULL,
                              FBRL_DOC_TEXT(two ? "( row col -- addr )" : "( index -- addr )"),
                              FBRL_DOC_TEXT(two ? "address of cell (row, col) of this 2ARRAY"
                                                : "address of a cell of this ARRAY"),
                              NULL, &p)))
        return st;
    fbrl_cell aa = (fbrl_cell)p;
    fbrl_cell data = align16(aa + (fbrl_cell)sizeof(fbrl_array));
    if (two)
        st =
            fbrl_array2_init((fbrl_array *)aa, (void *)data, bytes, (size_t)size, (size_t)rows, (size_t)cols);
    else
        st = fbrl_array_init((fbrl_array *)aa, (void *)data, bytes, (size_t)size, (size_t)rows);
    return st == FBRL_OK ? st : fail(vm, FBRL_VM_THROW_OF_STATUS(st), NULL);
}

static fbrl_status w_array(fbrl_vm *vm, void *arg)
{
    fbrl_cell n, size;
    fbrl_status st;
    (void)arg;
    if ((st = need(vm, 2)))
        return st;
    fbrl_vm_pop(vm, &size);
    fbrl_vm_pop(vm, &n);
    return make_array(vm, n, 1, size, 0);
}

static fbrl_status w_2array(fbrl_vm *vm, void *arg)
{
    fbrl_cell rows, cols, size;
    fbrl_status st;
    (void)arg;
    if ((st = need(vm, 3)))
        return st;
    fbrl_vm_pop(vm, &size);
    fbrl_vm_pop(vm, &cols);
    fbrl_vm_pop(vm, &rows);
    return make_array(vm, rows, cols, size, 1);
}

/* ---- I-3 strings: [size u16][length u16][characters], as thesis figure 5.5 ---- */
static unsigned char *string_at(fbrl_vm *vm, fbrl_cell s, unsigned *size, unsigned *len, fbrl_status *st)
{
    uint16_t v[2];
    *st = FBRL_OK;
    if (!fbrl_vm_addr(vm, s, 4)) {
        *st = fail(vm, FBRL_THROW_BAD_ADDRESS, NULL);
        return NULL;
    }
    memcpy(v, (void *)s, 4);
    if (v[0] == 0 || v[1] > v[0] || !fbrl_vm_addr(vm, s + 4, v[0])) {
        *st = fail(vm, FBRL_THROW_TYPE_MISMATCH, "not a string (use a STRING name)");
        return NULL;
    }
    *size = v[0];
    *len = v[1];
    return (unsigned char *)s + 4;
}

/* Pops ( str -- ) and checks it is a string: its characters, *s its address. */
static unsigned char *pop_string(fbrl_vm *vm, fbrl_cell *s, unsigned *size, unsigned *len, fbrl_status *st)
{
    if ((*st = need(vm, 1)))
        return NULL;
    fbrl_vm_pop(vm, s);
    return string_at(vm, *s, size, len, st);
}

static void set_len(fbrl_cell s, unsigned len)
{
    uint16_t v = (uint16_t)len;
    memcpy((unsigned char *)s + 2, &v, 2);
}

static fbrl_status w_string(fbrl_vm *vm, void *arg)
{
    fbrl_cell n;
    void *p;
    fbrl_status st;
    (void)arg;
    if ((st = need(vm, 1)))
        return st;
    fbrl_vm_pop(vm, &n);
    if (n < 1 || n > STR_MAX)
        return fail(vm, FBRL_THROW_BAD_NUMBER, "string length must be 1..65535");
    if ((st = fbrl_vmx_create(vm, NULL, 0, NULL, 4 + (size_t)n, NULL, NULL, FBRL_DOC_TEXT("( -- str )"),
                              FBRL_DOC_TEXT("string"), NULL, &p)))
        return st;
    uint16_t v = (uint16_t)n;
    memcpy(p, &v, 2);
    return FBRL_OK;
}

/* STRING-CNT, STRING-SIZE, TYPE-STRING, NULL-STRING: ( str -- ... ) */
enum { S_CNT, S_SIZE, S_TYPE, S_NULL, S_TEXT };
static fbrl_status w_str1(fbrl_vm *vm, void *arg)
{
    fbrl_cell s;
    unsigned size, len;
    fbrl_status st;
    unsigned char *c = pop_string(vm, &s, &size, &len, &st);
    if (!c)
        return st;
    switch ((int)(intptr_t)arg) {
    case S_CNT: return fbrl_vm_push(vm, len);
    case S_SIZE: return fbrl_vm_push(vm, size);
    case S_TYPE: fbrl_vmx_write(vm, (const char *)c, len); return FBRL_OK;
    case S_NULL: set_len(s, 0); return FBRL_OK;
    default:
        if ((st = fbrl_vm_push(vm, (fbrl_cell)c)))
            return st;
        return fbrl_vm_push(vm, len);
    }
}

static fbrl_status overflow(fbrl_vm *vm)
{
    return fail(vm, FBRL_VM_THROW_OF_STATUS(FBRL_ERANGE), "string overflow");
}

static fbrl_status w_append_chr(fbrl_vm *vm, void *arg)
{
    fbrl_cell s, ch;
    unsigned size, len;
    fbrl_status st;
    (void)arg;
    if ((st = need(vm, 2)))
        return st;
    fbrl_vm_pop(vm, &s);
    fbrl_vm_pop(vm, &ch);
    unsigned char *c = string_at(vm, s, &size, &len, &st);
    if (!c)
        return st;
    if (len >= size)
        return overflow(vm);
    c[len] = (unsigned char)ch;
    set_len(s, len + 1);
    return FBRL_OK;
}

/* APPEND-STRING (append != 0) and COPY-STRING ( targ src -- ) */
static fbrl_status w_append_copy(fbrl_vm *vm, void *arg)
{
    fbrl_cell t, s;
    unsigned tsize, tlen, ssize, slen;
    fbrl_status st;
    if ((st = need(vm, 2)))
        return st;
    fbrl_vm_pop(vm, &s);
    fbrl_vm_pop(vm, &t);
    unsigned char *tc = string_at(vm, t, &tsize, &tlen, &st);
    if (!tc)
        return st;
    unsigned char *sc = string_at(vm, s, &ssize, &slen, &st);
    if (!sc)
        return st;
    unsigned at = arg ? tlen : 0;
    if (at + slen > tsize)
        return overflow(vm);
    memmove(tc + at, sc, slen);
    set_len(t, at + slen);
    return FBRL_OK;
}

/* SUB-STRING ( targ src m n -- ): characters m..n of src (counted from 1) into targ */
static fbrl_status w_sub_string(fbrl_vm *vm, void *arg)
{
    fbrl_cell t, s, m, n;
    unsigned tsize, tlen, ssize, slen;
    fbrl_status st;
    (void)arg;
    if ((st = need(vm, 4)))
        return st;
    fbrl_vm_pop(vm, &n);
    fbrl_vm_pop(vm, &m);
    fbrl_vm_pop(vm, &s);
    fbrl_vm_pop(vm, &t);
    unsigned char *tc = string_at(vm, t, &tsize, &tlen, &st);
    if (!tc)
        return st;
    unsigned char *sc = string_at(vm, s, &ssize, &slen, &st);
    if (!sc)
        return st;
    if (m < 1 || n < m - 1 || n > (fbrl_cell)slen)
        return fail(vm, FBRL_VM_THROW_OF_STATUS(FBRL_ERANGE), "SUB-STRING positions out of range");
    if (n - m + 1 > (fbrl_cell)tsize)
        return overflow(vm);
    memmove(tc, sc + m - 1, (size_t)(n - m + 1));
    set_len(t, (unsigned)(n - m + 1));
    return FBRL_OK;
}

static fbrl_status w_string_chr(fbrl_vm *vm, void *arg)
{
    fbrl_cell s, pos;
    unsigned size, len;
    fbrl_status st;
    (void)arg;
    if ((st = need(vm, 2)))
        return st;
    fbrl_vm_pop(vm, &pos);
    fbrl_vm_pop(vm, &s);
    unsigned char *c = string_at(vm, s, &size, &len, &st);
    if (!c)
        return st;
    if (pos < 1 || pos > (fbrl_cell)len)
        return fail(vm, FBRL_VM_THROW_OF_STATUS(FBRL_ERANGE), "position out of range");
    return fbrl_vm_push(vm, c[pos - 1]);
}

/* STRING-PUT ( str a u -- ): store text into the string */
static fbrl_status w_string_put(fbrl_vm *vm, void *arg)
{
    fbrl_cell s, a, u;
    unsigned size, len;
    fbrl_status st;
    (void)arg;
    if ((st = need(vm, 3)))
        return st;
    fbrl_vm_pop(vm, &u);
    fbrl_vm_pop(vm, &a);
    fbrl_vm_pop(vm, &s);
    unsigned char *c = string_at(vm, s, &size, &len, &st);
    if (!c)
        return st;
    if (u < 0 || (u && !fbrl_vm_addr(vm, a, (size_t)u)))
        return fail(vm, FBRL_THROW_BAD_ADDRESS, NULL);
    if (u > (fbrl_cell)size)
        return overflow(vm);
    if (u)
        memmove(c, (void *)a, (size_t)u);
    set_len(s, (unsigned)u);
    return FBRL_OK;
}

/* STRING-LIT "text" (immediate): stores the quoted text into the string on the stack */
static fbrl_status w_string_lit(fbrl_vm *vm, void *ctx, const void *word)
{
    const char *p;
    size_t n;
    fbrl_cell put;
    (void)ctx;
    (void)word;
    int found = fbrl_vmx_parse_quoted(vm, &p, &n);
    if (found < 0)
        return fail(vm, FBRL_THROW_BAD_NUMBER, "STRING-LIT needs a \"quoted\" text");
    if (!found)
        return fail(vm, FBRL_THROW_UNEXPECTED_EOF, "unterminated string");
    if (fbrl_vmx_compiling(vm)) {
        fbrl_status st = fbrl_vmx_find(vm, "STRING-PUT", 10, &put);
        if (st == FBRL_OK)
            st = fbrl_vmx_compile_string(vm, p, n);
        if (st == FBRL_OK)
            st = fbrl_vmx_compile_xt(vm, put);
        return st;
    }
    fbrl_cell s;
    unsigned size, len;
    fbrl_status st;
    unsigned char *c = pop_string(vm, &s, &size, &len, &st);
    if (!c)
        return st;
    if (n > size)
        return overflow(vm);
    memmove(c, p, n);
    set_len(s, (unsigned)n);
    return FBRL_OK;
}

/* GET-STRING ( str -- ): a line from the console. Characters beyond the string's size
 * are dropped, and the user is told how many were kept (a cut name or path must not
 * pass unseen). */
static fbrl_status w_get_string(fbrl_vm *vm, void *arg)
{
    fbrl_cell s;
    unsigned size, len, k = 0;
    unsigned long dropped = 0;
    fbrl_status st;
    (void)arg;
    unsigned char *c = pop_string(vm, &s, &size, &len, &st);
    if (!c)
        return st;
    const fbrl_vm_host *host = fbrl_vmx_host(vm);
    if (!host->key)
        return fail(vm, FBRL_THROW_UNSUPPORTED, "no console input in this host");
    for (;;) {
        int ch = host->key(host->user);
        if (ch < 0 || ch == '\n' || ch == '\r')
            break;
        if (k < size)
            c[k++] = (unsigned char)ch;
        else
            dropped++;
    }
    set_len(s, k);
    if (dropped) {
        char msg[128];
        snprintf(msg, sizeof msg,
                 "GET-STRING: the string holds %u characters: kept the first %u, dropped %lu\n", size, k,
                 dropped);
        fbrl_vmx_puts(vm, msg);
    }
    return FBRL_OK;
}

/* ---- data type sizes ---- */
static fbrl_status w_const(fbrl_vm *vm, void *arg) { return fbrl_vm_push(vm, (fbrl_cell)(intptr_t)arg); }

/* A word: fn(vm, arg), or (fn NULL) xfn with flags. */
typedef struct word {
    const char *name;
    fbrl_vm_prim fn;
    intptr_t arg;
    fbrl_vmx_fn xfn;
    unsigned flags;
    FBRL_DOC_FIELDS
} word;
static const word words[] = {
    {"CREATE-Q", w_create_q, 0, NULL, 0,
     FBRL_DOC("( n \"name\" -- )",
              "make a character queue named name; it holds n characters, rounded down to a power of two")},
    {"ENQ", w_enq, 0, NULL, 0,
     FBRL_DOC("( c q-addr -- )", "add a character to the queue (throws when full)")},
    {"DEQ", w_deq, 0, NULL, 0,
     FBRL_DOC("( q-addr -- c )", "take the oldest character from the queue (throws when empty)")},
    {"EMPTY-Q?", w_q_test, 0, NULL, 0, FBRL_DOC("( q-addr -- flag )", "true if the queue is empty")},
    {"FULL-Q?", w_q_test, 1, NULL, 0, FBRL_DOC("( q-addr -- flag )", "true if the queue is full")},
    {"ENQ-L", w_enq, 0, NULL, 0,
     FBRL_DOC("( c q-addr -- )", "ENQ (the thesis's low-level twin; same code here)")},
    {"DEQ-L", w_deq, 0, NULL, 0,
     FBRL_DOC("( q-addr -- c )", "DEQ (the thesis's low-level twin; same code here)")},
    {"EMPTY-Q?-L", w_q_test, 0, NULL, 0,
     FBRL_DOC("( q-addr -- flag )", "EMPTY-Q? (the thesis's low-level twin)")},
    {"FULL-Q?-L", w_q_test, 1, NULL, 0,
     FBRL_DOC("( q-addr -- flag )", "FULL-Q? (the thesis's low-level twin)")},
    {"Q-COUNT", w_q_count, 0, NULL, 0, FBRL_DOC("( q-addr -- n )", "number of characters in the queue")},
    {"ARRAY", w_array, 0, NULL, 0,
     FBRL_DOC("( n cell-size \"name\" -- ) ( run: index -- addr )",
              "make a one-dimensional array of n cells")},
    {"2ARRAY", w_2array, 0, NULL, 0,
     FBRL_DOC("( rows cols cell-size \"name\" -- ) ( run: row col -- addr )",
              "make a two-dimensional array")},
    {"STRING", w_string, 0, NULL, 0,
     FBRL_DOC("( length \"name\" -- ) ( run: -- str )", "make a string of up to length characters")},
    {"STRING-CNT", w_str1, S_CNT, NULL, 0, FBRL_DOC("( str -- cnt )", "number of characters in the string")},
    {"STRING-SIZE", w_str1, S_SIZE, NULL, 0,
     FBRL_DOC("( str -- size )", "number of characters reserved for the string")},
    {"TYPE-STRING", w_str1, S_TYPE, NULL, 0, FBRL_DOC("( str -- )", "print the string")},
    {"NULL-STRING", w_str1, S_NULL, NULL, 0, FBRL_DOC("( str -- )", "make the string empty")},
    {"STRING-TEXT", w_str1, S_TEXT, NULL, 0,
     FBRL_DOC("( str -- a u )", "address and length of the string's characters")},
    {"APPEND-CHR", w_append_chr, 0, NULL, 0, FBRL_DOC("( c str -- )", "append a character to the string")},
    {"APPEND-STRING", w_append_copy, 1, NULL, 0,
     FBRL_DOC("( targ src -- )", "append string src to string targ")},
    {"COPY-STRING", w_append_copy, 0, NULL, 0,
     FBRL_DOC("( targ src -- )", "copy string src into string targ")},
    {"SUB-STRING", w_sub_string, 0, NULL, 0,
     FBRL_DOC("( targ src m n -- )", "copy characters m..n (from 1) of src into targ")},
    {"STRING->CHR", w_string_chr, 0, NULL, 0,
     FBRL_DOC("( str n -- c )", "the n-th character of the string (from 1)")},
    {"STRING-PUT", w_string_put, 0, NULL, 0,
     FBRL_DOC("( str a u -- )", "store the text a u into the string")},
    {"STRING-LIT", NULL, 0, w_string_lit, FBRL_VMX_IMMEDIATE | FBRL_VMX_STATE_SMART,
     FBRL_DOC("( str \"\"text\"\" -- )", "store the quoted text into the string")},
    {"GET-STRING", w_get_string, 0, NULL, 0,
     FBRL_DOC("( str -- )", "read a line from the console into the string")},
    {"CHR", w_const, 1, NULL, 0, FBRL_DOC("( -- 1 )", "size in bytes of a character (for ARRAY)")},
    {"INTEGER", w_const, 2, NULL, 0, FBRL_DOC("( -- 2 )", "size in bytes of an integer (for ARRAY)")},
    {"LONG-INTEGER", w_const, 4, NULL, 0,
     FBRL_DOC("( -- 4 )", "size in bytes of a long integer (for ARRAY)")},
    {"REAL", w_const, 8, NULL, 0, FBRL_DOC("( -- 8 )", "size in bytes of a real (a float, for ARRAY)")},
    {"LOCATION", w_const, 48, NULL, 0,
     FBRL_DOC("( -- 48 )", "size in bytes of a location template (6 floats, for ARRAY)")},
};

fbrl_status fbrl_vmx_data_words(fbrl_vm *vm)
{
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++) {
        fbrl_status st =
            words[i].fn ? fbrl_vm_define(vm, words[i].name, words[i].fn, (void *)words[i].arg,
                                         FBRL_DOC_STACK(words[i]), FBRL_DOC_HELP(words[i]))
                        : fbrl_vmx_define(vm, words[i].name, words[i].xfn, NULL, &words[i], words[i].flags,
                                          FBRL_DOC_STACK(words[i]), FBRL_DOC_HELP(words[i]));
        if (st != FBRL_OK)
            return st;
    }
    return FBRL_OK;
}
