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

/* A word's parameters (its row's spec, vmx.h's fbrl_vmx_check), its ctx unused: every
 * data word begins with this. */
#define DATA_ARGS(v)                              \
    fbrl_status st = fbrl_vmx_check(vm, word, v); \
    (void)ctx;                                    \
    if (st != FBRL_OK)                            \
    return st

/* Takes ( q -- ) (its row's spec "A") and checks it is a queue. */
static fbrl_ring *pop_queue(fbrl_vm *vm, const void *word, fbrl_status *st)
{
    fbrl_vmx_val v[1];
    if ((*st = fbrl_vmx_check(vm, word, v)) != FBRL_OK)
        return NULL;
    return queue_at(vm, v[0].i, st);
}

static fbrl_status w_create_q(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_vmx_val v[1];
    void *p;
    DATA_ARGS(v);
    fbrl_cell n = v[0].i;
    if (n < 2 || n > (1 << 24))
        return fail(vm, FBRL_THROW_BAD_NUMBER, "queue size must be 2..16777216 bytes");
    if ((st = fbrl_vmx_create(vm, NULL, 0, &queue_type, sizeof(fbrl_ring) + (size_t)n, NULL, NULL,
                              FBRL_DOC_TEXT("( -- q-addr )"), FBRL_DOC_TEXT("queue"), NULL, &p)))
        return st;
    return fbrl_ring_init((fbrl_ring *)p, (fbrl_ring *)p + 1, (size_t)n);
}

static fbrl_status w_enq(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_vmx_val v[2];
    DATA_ARGS(v);
    fbrl_ring *r = queue_at(vm, v[1].i, &st);
    if (!r)
        return st;
    if (fbrl_ring_put(r, (uint8_t)v[0].i) != FBRL_OK)
        return fail(vm, FBRL_VM_THROW_OF_STATUS(FBRL_EFULL), "queue full");
    return FBRL_OK;
}

static fbrl_status w_deq(fbrl_vm *vm, void *ctx, const void *word)
{
    uint8_t b;
    fbrl_status st;
    (void)ctx;
    fbrl_ring *r = pop_queue(vm, word, &st);
    if (!r)
        return st;
    if (fbrl_ring_get(r, &b) != FBRL_OK)
        return fail(vm, FBRL_VM_THROW_OF_STATUS(FBRL_EEMPTY), "queue empty");
    return fbrl_vm_push(vm, b);
}

static fbrl_status w_q_test(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_status st;
    (void)ctx;
    fbrl_ring *r = pop_queue(vm, word, &st);
    if (!r)
        return st;
    int yes = ((const fbrl_vmx_reg *)word)->arg ? fbrl_ring_full(r) : fbrl_ring_empty(r);
    return fbrl_vm_push(vm, yes ? -1 : 0);
}

static fbrl_status w_q_count(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_status st;
    (void)ctx;
    fbrl_ring *r = pop_queue(vm, word, &st);
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
    fbrl_vmx_val v[2];
    fbrl_status st;
    void *cell;
    fbrl_array *a = array_at(vm, (fbrl_cell)body, &st);
    if (!a)
        return st;
    /* a word this set made runs without a row: its parameters by the same parser */
    if ((st = fbrl_vmx_args(vm, NULL, two ? "II" : "I", NULL, FBRL_VMX_STACKS, v)) != FBRL_OK)
        return st;
    fbrl_cell i = v[0].i, j = two ? v[1].i : 0;
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

static fbrl_status w_array(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_vmx_val v[2];
    DATA_ARGS(v);
    return make_array(vm, v[0].i, 1, v[1].i, 0);
}

static fbrl_status w_2array(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_vmx_val v[3];
    DATA_ARGS(v);
    return make_array(vm, v[0].i, v[1].i, v[2].i, 1);
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

/* Takes ( str -- ) (its row's spec "A") and checks it is a string: its characters, *s its
 * address. */
static unsigned char *pop_string(fbrl_vm *vm, const void *word, fbrl_cell *s, unsigned *size, unsigned *len,
                                 fbrl_status *st)
{
    fbrl_vmx_val v[1];
    if ((*st = fbrl_vmx_check(vm, word, v)) != FBRL_OK)
        return NULL;
    *s = v[0].i;
    return string_at(vm, *s, size, len, st);
}

static void set_len(fbrl_cell s, unsigned len)
{
    uint16_t v = (uint16_t)len;
    memcpy((unsigned char *)s + 2, &v, 2);
}

static fbrl_status w_string(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_vmx_val v[1];
    void *p;
    DATA_ARGS(v);
    fbrl_cell n = v[0].i;
    if (n < 1 || n > STR_MAX)
        return fail(vm, FBRL_THROW_BAD_NUMBER, "string length must be 1..65535");
    if ((st = fbrl_vmx_create(vm, NULL, 0, NULL, 4 + (size_t)n, NULL, NULL, FBRL_DOC_TEXT("( -- str )"),
                              FBRL_DOC_TEXT("string"), NULL, &p)))
        return st;
    uint16_t size = (uint16_t)n;
    memcpy(p, &size, 2);
    return FBRL_OK;
}

/* STRING-CNT, STRING-SIZE, TYPE-STRING, NULL-STRING: ( str -- ... ) */
enum { S_CNT, S_SIZE, S_TYPE, S_NULL, S_TEXT };
static fbrl_status w_str1(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_cell s;
    unsigned size, len;
    fbrl_status st;
    (void)ctx;
    unsigned char *c = pop_string(vm, word, &s, &size, &len, &st);
    if (!c)
        return st;
    switch ((int)((const fbrl_vmx_reg *)word)->arg) {
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

static fbrl_status w_append_chr(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_vmx_val v[2];
    unsigned size, len;
    DATA_ARGS(v);
    fbrl_cell ch = v[0].i, s = v[1].i;
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
static fbrl_status w_append_copy(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_vmx_val v[2];
    unsigned tsize, tlen, ssize, slen;
    DATA_ARGS(v);
    fbrl_cell t = v[0].i, s = v[1].i;
    unsigned char *tc = string_at(vm, t, &tsize, &tlen, &st);
    if (!tc)
        return st;
    unsigned char *sc = string_at(vm, s, &ssize, &slen, &st);
    if (!sc)
        return st;
    unsigned at = ((const fbrl_vmx_reg *)word)->arg ? tlen : 0;
    if (at + slen > tsize)
        return overflow(vm);
    memmove(tc + at, sc, slen);
    set_len(t, at + slen);
    return FBRL_OK;
}

/* SUB-STRING ( targ src m n -- ): characters m..n of src (counted from 1) into targ */
static fbrl_status w_sub_string(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_vmx_val v[4];
    unsigned tsize, tlen, ssize, slen;
    DATA_ARGS(v);
    fbrl_cell t = v[0].i, s = v[1].i, m = v[2].i, n = v[3].i;
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

static fbrl_status w_string_chr(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_vmx_val v[2];
    unsigned size, len;
    DATA_ARGS(v);
    fbrl_cell s = v[0].i, pos = v[1].i;
    unsigned char *c = string_at(vm, s, &size, &len, &st);
    if (!c)
        return st;
    if (pos < 1 || pos > (fbrl_cell)len)
        return fail(vm, FBRL_VM_THROW_OF_STATUS(FBRL_ERANGE), "position out of range");
    return fbrl_vm_push(vm, c[pos - 1]);
}

/* STRING-PUT ( str a u -- ): store text into the string */
static fbrl_status w_string_put(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_vmx_val v[2]; /* the text's address and length are checked by fbrl_vmx_check */
    unsigned size, len;
    DATA_ARGS(v);
    fbrl_cell s = v[0].i;
    unsigned char *c = string_at(vm, s, &size, &len, &st);
    if (!c)
        return st;
    if (v[1].n > size)
        return overflow(vm);
    if (v[1].n)
        memmove(c, v[1].s, v[1].n);
    set_len(s, (unsigned)v[1].n);
    return FBRL_OK;
}

/* STRING-LIT "text" (immediate): stores the quoted text into the string on the stack */
static fbrl_status w_string_lit(fbrl_vm *vm, void *ctx, const void *word)
{
    const char *p;
    size_t n;
    fbrl_cell put;
    (void)ctx;
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
    unsigned char *c = pop_string(vm, word, &s, &size, &len, &st);
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
static fbrl_status w_get_string(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_cell s;
    unsigned size, len, k = 0;
    unsigned long dropped = 0;
    fbrl_status st;
    (void)ctx;
    unsigned char *c = pop_string(vm, word, &s, &size, &len, &st);
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
static fbrl_status w_const(fbrl_vm *vm, void *ctx, const void *word)
{
    (void)ctx;
    return fbrl_vmx_push(vm, (fbrl_cell)((const fbrl_vmx_reg *)word)->arg);
}

/* The rows: name, function, parameters (fbrl_vmx_check), flags, -, the function's selector. */
static const fbrl_vmx_reg words[] = {
    {"CREATE-Q", w_create_q, "I", 0, 0, 0,
     FBRL_DOC("( n \"name\" -- )",
              "make a character queue named name; it holds n characters, rounded down to a power of two")},
    {"ENQ", w_enq, "IA", 0, 0, 0,
     FBRL_DOC("( c q-addr -- )", "add a character to the queue (throws when full)")},
    {"DEQ", w_deq, "A", 0, 0, 0,
     FBRL_DOC("( q-addr -- c )", "take the oldest character from the queue (throws when empty)")},
    {"EMPTY-Q?", w_q_test, "A", 0, 0, 0, FBRL_DOC("( q-addr -- flag )", "true if the queue is empty")},
    {"FULL-Q?", w_q_test, "A", 0, 0, 1, FBRL_DOC("( q-addr -- flag )", "true if the queue is full")},
    {"ENQ-L", w_enq, "IA", 0, 0, 0,
     FBRL_DOC("( c q-addr -- )", "ENQ (the thesis's low-level twin; same code here)")},
    {"DEQ-L", w_deq, "A", 0, 0, 0,
     FBRL_DOC("( q-addr -- c )", "DEQ (the thesis's low-level twin; same code here)")},
    {"EMPTY-Q?-L", w_q_test, "A", 0, 0, 0,
     FBRL_DOC("( q-addr -- flag )", "EMPTY-Q? (the thesis's low-level twin)")},
    {"FULL-Q?-L", w_q_test, "A", 0, 0, 1,
     FBRL_DOC("( q-addr -- flag )", "FULL-Q? (the thesis's low-level twin)")},
    {"Q-COUNT", w_q_count, "A", 0, 0, 0, FBRL_DOC("( q-addr -- n )", "number of characters in the queue")},
    {"ARRAY", w_array, "II", 0, 0, 0,
     FBRL_DOC("( n cell-size \"name\" -- ) ( run: index -- addr )",
              "make a one-dimensional array of n cells")},
    {"2ARRAY", w_2array, "III", 0, 0, 0,
     FBRL_DOC("( rows cols cell-size \"name\" -- ) ( run: row col -- addr )",
              "make a two-dimensional array")},
    {"STRING", w_string, "I", 0, 0, 0,
     FBRL_DOC("( length \"name\" -- ) ( run: -- str )", "make a string of up to length characters")},
    {"STRING-CNT", w_str1, "A", 0, 0, S_CNT,
     FBRL_DOC("( str -- cnt )", "number of characters in the string")},
    {"STRING-SIZE", w_str1, "A", 0, 0, S_SIZE,
     FBRL_DOC("( str -- size )", "number of characters reserved for the string")},
    {"TYPE-STRING", w_str1, "A", 0, 0, S_TYPE, FBRL_DOC("( str -- )", "print the string")},
    {"NULL-STRING", w_str1, "A", 0, 0, S_NULL, FBRL_DOC("( str -- )", "make the string empty")},
    {"STRING-TEXT", w_str1, "A", 0, 0, S_TEXT,
     FBRL_DOC("( str -- a u )", "address and length of the string's characters")},
    {"APPEND-CHR", w_append_chr, "IA", 0, 0, 0, FBRL_DOC("( c str -- )", "append a character to the string")},
    {"APPEND-STRING", w_append_copy, "AA", 0, 0, 1,
     FBRL_DOC("( targ src -- )", "append string src to string targ")},
    {"COPY-STRING", w_append_copy, "AA", 0, 0, 0,
     FBRL_DOC("( targ src -- )", "copy string src into string targ")},
    {"SUB-STRING", w_sub_string, "AAII", 0, 0, 0,
     FBRL_DOC("( targ src m n -- )", "copy characters m..n (from 1) of src into targ")},
    {"STRING->CHR", w_string_chr, "AI", 0, 0, 0,
     FBRL_DOC("( str n -- c )", "the n-th character of the string (from 1)")},
    {"STRING-PUT", w_string_put, "AS", 0, 0, 0,
     FBRL_DOC("( str a u -- )", "store the text a u into the string")},
    {"STRING-LIT", w_string_lit, "A", FBRL_VMX_IMMEDIATE | FBRL_VMX_STATE_SMART, 0, 0,
     FBRL_DOC("( str \"\"text\"\" -- )", "store the quoted text into the string")},
    {"GET-STRING", w_get_string, "A", 0, 0, 0,
     FBRL_DOC("( str -- )", "read a line from the console into the string")},
    {"CHR", w_const, "", 0, 0, 1, FBRL_DOC("( -- 1 )", "size in bytes of a character (for ARRAY)")},
    {"INTEGER", w_const, "", 0, 0, 2, FBRL_DOC("( -- 2 )", "size in bytes of an integer (for ARRAY)")},
    {"LONG-INTEGER", w_const, "", 0, 0, 4,
     FBRL_DOC("( -- 4 )", "size in bytes of a long integer (for ARRAY)")},
    {"REAL", w_const, "", 0, 0, 8, FBRL_DOC("( -- 8 )", "size in bytes of a real (a float, for ARRAY)")},
    {"LOCATION", w_const, "", 0, 0, 48,
     FBRL_DOC("( -- 48 )", "size in bytes of a location template (6 floats, for ARRAY)")},
};

fbrl_status fbrl_vmx_data_words(fbrl_vm *vm)
{
    return fbrl_vmx_define_table(vm, words, sizeof words / sizeof words[0], NULL);
}
