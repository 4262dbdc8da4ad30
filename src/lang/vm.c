/* SPDX-License-Identifier: MIT */
/* vm.c - the FBRL engine: memory layout, dictionary, text interpreter, C API.
 * The inner interpreter (the big switch) is in run.c. */
#include <string.h>
#include "atomic.h"
#include "words.h"

typedef struct opinfo {
    const char *name;
    uint8_t flags;
    const char *stack, *help;
} opinfo;
static const opinfo ops[OP__END] = {
#define OP(id, name, flags, stack, help) {name, flags, stack, help},
#include "ops.def"
#undef OP
};

const char *fbrl__op_name(int op) { return (op >= 0 && op < OP__END) ? ops[op].name : ""; }

/* ---- throw codes and their standard texts (Forth-2012 table 9.1) ---- */
static const char *const throw_texts[] = {
    "",
    "aborted",
    "aborted",
    "stack overflow",
    "stack underflow",
    "return stack overflow",
    "return stack underflow",
    "do-loops nested too deeply",
    "dictionary overflow",
    "invalid memory address",
    "division by zero",
    "result out of range",
    "argument type mismatch",
    "undefined word",
    "interpreting a compile-only word",
    "invalid FORGET",
    "attempt to use zero-length string as a name",
    "pictured numeric output string overflow",
    "parsed string overflow",
    "definition name too long",
    "write to a read-only location",
    "unsupported operation",
    "control structure mismatch",
    "address alignment exception",
    "invalid numeric argument",
    "return stack imbalance",
    "loop parameters unavailable",
    "invalid recursion",
    "user interrupt",
    "compiler nesting",
    "obsolescent feature",
    ">BODY used on non-CREATEd definition",
    "invalid name argument",
    "block read exception",
    "block write exception",
    "invalid block number",
    "invalid file position",
    "file I/O exception",
    "non-existent file",
    "unexpected end of file",
    "invalid BASE for floating point conversion",
    "loss of precision",
    "floating-point divide by zero",
    "floating-point result out of range",
    "floating-point stack overflow",
    "floating-point stack underflow",
    "floating-point invalid argument",
    "compilation word list deleted",
    "invalid POSTPONE",
    "search-order overflow",
    "search-order underflow",
    "compilation word list changed",
    "control-flow stack overflow",
    "exception stack overflow",
    "floating-point underflow",
    "floating-point unidentified fault",
    "QUIT",
    "exception in sending or receiving a character",
    "[IF], [ELSE], or [THEN] exception",
};

const char *fbrl__throw_text(int code)
{
    if (code < 0 && -code < (int)(sizeof throw_texts / sizeof throw_texts[0]))
        return throw_texts[-code];
    if (code <= FBRL_THROW_STATUS(0) && code >= FBRL_THROW_STATUS(FBRL_STATUS_MIN))
        return fbrl_status_str((fbrl_status)(code - FBRL_THROW_STATUS(0)));
    return "user exception";
}

/* Raise with a message other than the standard one (the message is copied). */
int fbrl__throw_msg(fbrl_vm *vm, int code, const char *msg)
{
    vm->pending_code = code;
    size_t n = strlen(msg);
    if (n >= sizeof vm->throw_msg)
        n = sizeof vm->throw_msg - 1;
    memcpy(vm->throw_msg, msg, n);
    vm->throw_msg[n] = 0;
    vm->pending_msg = vm->throw_msg;
    return code;
}

/* ---- output ---- */
void fbrl__write(fbrl_vm *vm, const char *s, size_t n)
{
    if (vm->host.write && n)
        vm->host.write(vm->host.user, s, n);
}
void fbrl__puts(fbrl_vm *vm, const char *s) { fbrl__write(vm, s, strlen(s)); }

/* ---- memory checks ---- */
void *fbrl_vm_addr(fbrl_vm *vm, fbrl_cell addr, size_t n)
{
    if (!vm || !fbrl__addr_ok(vm, addr, (fbrl_cell)n))
        return NULL;
    return (void *)addr;
}

/* ---- dictionary ---- */
static unsigned hash_name(const char *s, size_t n)
{
    uint32_t h = 2166136261u;
    for (size_t i = 0; i < n; i++) {
        unsigned char c = (unsigned char)s[i];
        if (c >= 'a' && c <= 'z')
            c = (unsigned char)(c - 32);
        h = (h ^ c) * 16777619u;
    }
    return (unsigned)(h ^ (h >> 15)) & (FBRL_HASH - 1);
}

static int name_eq(const char *a, const char *b, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        unsigned char x = (unsigned char)a[i], y = (unsigned char)b[i];
        if (x >= 'a' && x <= 'z')
            x = (unsigned char)(x - 32);
        if (y >= 'a' && y <= 'z')
            y = (unsigned char)(y - 32);
        if (x != y)
            return 0;
    }
    return 1;
}

int fbrl__find(const fbrl_vm *vm, const char *name, size_t len)
{
    if (len == 0 || len > FBRL_NAME_MAX)
        return -1;
    uint32_t i = vm->hash[hash_name(name, len)];
    while (i) {
        const fbrl_hdr *h = HDR(vm, i - 1);
        if (h->len == len && !(h->flags & FH) && name_eq(h->name, name, len))
            return (int)(i - 1);
        i = h->next;
    }
    return -1;
}

static void rebuild_hash(fbrl_vm *vm)
{
    vm->data_hi = (unsigned char *)(vm->hdr_top - vm->nwords);
    memset(vm->hash, 0, sizeof vm->hash);
    for (uint32_t i = 0; i < vm->nwords; i++) {
        fbrl_hdr *h = HDR(vm, i);
        unsigned b = hash_name(h->name, h->len);
        h->next = vm->hash[b];
        vm->hash[b] = i + 1;
    }
}

fbrl_hdr *fbrl__xt_hdr(const fbrl_vm *vm, fbrl_cell xt)
{
    fbrl_ucell i = (fbrl_ucell)xt - FBRL_XT_BASE;
    return i < vm->nwords ? HDR(vm, i) : NULL;
}

static fbrl_cell hdr_xt(const fbrl_vm *vm, const fbrl_hdr *h)
{
    return (fbrl_cell)(FBRL_XT_BASE + (vm->hdr_top - 1 - h));
}

/* A new header; the name must be 1..31 characters (0 allowed only for :NONAME). */
static int new_header(fbrl_vm *vm, const char *name, size_t len, int kind, unsigned flags, fbrl_hdr **out)
{
    if (len > FBRL_NAME_MAX)
        return FBRL_THROW_NAME_TOO_LONG;
    unsigned char *newlo = (unsigned char *)(vm->hdr_top - vm->nwords - 1);
    if (vm->here > newlo)
        return FBRL_THROW_DICT_OVERFLOW;
    fbrl_hdr *h = HDR(vm, vm->nwords);
    memset(h, 0, sizeof *h);
    memcpy(h->name, name, len);
    h->len = (uint8_t)len;
    h->kind = (uint8_t)kind;
    h->flags = (uint8_t)flags;
    h->stack = "";
    h->help = "";
    unsigned b = hash_name(name, len);
    h->next = vm->hash[b];
    vm->hash[b] = vm->nwords + 1;
    vm->nwords++;
    vm->data_hi = (unsigned char *)h;
    *out = h;
    return 0;
}

static fbrl_cell unused_bytes(const fbrl_vm *vm)
{
    return (fbrl_cell)((unsigned char *)(vm->hdr_top - vm->nwords) - vm->here);
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

/* ---- input parsing ---- */
fbrl_src *fbrl__src(fbrl_vm *vm) { return &vm->src[vm->nsrc - 1]; }

static size_t src_in(fbrl_vm *vm, const fbrl_src *s)
{
    fbrl_cell in = *vm->toin;
    if (in < 0)
        in = 0;
    if ((size_t)in > s->len)
        in = (fbrl_cell)s->len;
    return (size_t)in;
}

/* Blank-delimited name (any control character counts as blank). */
void fbrl__parse_name(fbrl_vm *vm, const char **p, size_t *n)
{
    *p = "";
    *n = 0;
    if (vm->nsrc == 0)
        return;
    fbrl_src *s = fbrl__src(vm);
    size_t i = src_in(vm, s);
    while (i < s->len && (unsigned char)s->buf[i] <= ' ')
        i++;
    size_t st = i;
    while (i < s->len && (unsigned char)s->buf[i] > ' ')
        i++;
    *p = s->buf + st;
    *n = i - st;
    *vm->toin = (fbrl_cell)(i < s->len ? i + 1 : i);
}

/* Text up to delimiter c (a blank delimiter matches any control character too). */
void fbrl__parse(fbrl_vm *vm, char c, const char **p, size_t *n, int *found)
{
    *p = "";
    *n = 0;
    *found = 0;
    if (vm->nsrc == 0)
        return;
    fbrl_src *s = fbrl__src(vm);
    size_t i = src_in(vm, s), st = i;
    while (i < s->len && !(s->buf[i] == c || (c == ' ' && (unsigned char)s->buf[i] < ' ')))
        i++;
    *p = s->buf + st;
    *n = i - st;
    *found = i < s->len;
    *vm->toin = (fbrl_cell)(i < s->len ? i + 1 : i);
}

/* Next line of the current source: 1 read, 0 end, <0 throw code. */
int fbrl__refill(fbrl_vm *vm)
{
    if (vm->nsrc == 0)
        return 0;
    fbrl_src *s = fbrl__src(vm);
    size_t len = 0;
    if (s->kind == SRC_STRING)
        return 0;
    if (s->kind == SRC_TEXT) {
        if (s->text >= s->text_end)
            return 0;
        const char *nl = memchr(s->text, '\n', (size_t)(s->text_end - s->text));
        const char *e = nl ? nl : s->text_end;
        len = (size_t)(e - s->text);
        if (len > 0 && s->text[len - 1] == '\r')
            len--;
        if (len > FBRL_LINE_MAX) {
            s->text = nl ? nl + 1 : s->text_end;
            s->line++;
            return fbrl__throw_msg(vm, FBRL_THROW_PARSED_OVERFLOW, "input line too long");
        }
        memcpy(s->linebuf, s->text, len);
        s->text = nl ? nl + 1 : s->text_end;
    } else {
        if (!vm->host.file_read_line)
            return fbrl__throw_msg(vm, FBRL_THROW_UNSUPPORTED, "no file support in this host");
        fbrl_status st = vm->host.file_read_line(vm->host.user, s->fh, s->linebuf, FBRL_LINE_MAX, &len);
        if (st == FBRL_EEOF)
            return 0;
        if (st == FBRL_ENOSPC) {
            s->line++;
            return fbrl__throw_msg(vm, FBRL_THROW_PARSED_OVERFLOW, "input line too long");
        }
        if (st != FBRL_OK || len > FBRL_LINE_MAX)
            return FBRL_THROW_FILE_IO;
        if (len > 0 && s->linebuf[len - 1] == '\r')
            len--;
    }
    s->buf = s->linebuf;
    s->len = len;
    s->line++;
    *vm->toin = 0;
    return 1;
}

/* ---- numbers ---- */
static int digit_of(unsigned char c, fbrl_cell base)
{
    int d;
    if (c >= '0' && c <= '9')
        d = c - '0';
    else if (c >= 'A' && c <= 'Z')
        d = c - 'A' + 10;
    else if (c >= 'a' && c <= 'z')
        d = c - 'a' + 10;
    else
        return -1;
    return d < base ? d : -1;
}

/* ud = ud*base + d, wrapping (cells hold the double as lo, hi). */
static void ud_mul_add(fbrl_ucell *lo, fbrl_ucell *hi, fbrl_ucell base, fbrl_ucell d)
{
    const int hb = CELL_BITS / 2;
    const fbrl_ucell mask = ((fbrl_ucell)1 << hb) - 1;
    fbrl_ucell l0 = *lo & mask, l1 = *lo >> hb;
    fbrl_ucell p0 = l0 * base + d; /* base <= 36 and halves keep these exact */
    fbrl_ucell p1 = l1 * base + (p0 >> hb);
    *lo = (p0 & mask) | (p1 << hb);
    *hi = *hi * base + (p1 >> hb);
}

/* >NUMBER on a C string: converts while digits remain; returns chars consumed. */
size_t fbrl__to_number(const char *s, size_t n, fbrl_cell base, fbrl_ucell *lo, fbrl_ucell *hi)
{
    size_t i = 0;
    for (; i < n; i++) {
        int d = digit_of((unsigned char)s[i], base);
        if (d < 0)
            break;
        ud_mul_add(lo, hi, (fbrl_ucell)base, (fbrl_ucell)d);
    }
    return i;
}

int fbrl__parse_float(const char *s, size_t n, double *out);

/* The text interpreter's number syntax. kind: 1 single, 2 double, 3 float; 0 not a number. */
int fbrl__parse_number(fbrl_vm *vm, const char *s, size_t n, fbrl_cell v[2], double *f)
{
    fbrl_cell base = *vm->base;
    if (n == 3 && s[0] == '\'' && s[2] == '\'') {
        v[0] = (unsigned char)s[1];
        return 1;
    }
    const char *p = s;
    size_t k = n;
    if (k > 1 && (*p == '#' || *p == '$' || *p == '%')) {
        base = *p == '#' ? 10 : *p == '$' ? 16 : 2;
        p++;
        k--;
    }
    if (base >= 2 && base <= 36) {
        int neg = 0, dbl = 0;
        const char *q = p;
        size_t m = k;
        if (m > 1 && *q == '-') {
            neg = 1;
            q++;
            m--;
        }
        if (m > 1 && q[m - 1] == '.') {
            dbl = 1;
            m--;
        }
        fbrl_ucell lo = 0, hi = 0;
        if (m > 0 && fbrl__to_number(q, m, base, &lo, &hi) == m) {
            if (neg) {
                lo = ~lo + 1;
                hi = ~hi + (lo == 0);
            }
            v[0] = (fbrl_cell)lo;
            v[1] = (fbrl_cell)hi;
            return dbl ? 2 : 1;
        }
    }
    if (p == s && *vm->base == 10 && fbrl__parse_float(s, n, f))
        return 3;
    return 0;
}

/* ---- compilation helpers ---- */
/* Peephole fusion: common pairs of ops become one superinstruction (ops.def), and
 * a literal followed by CELLS, 1+, ... is folded. vm->peep is the last instruction
 * that fbrl__compile_op/fbrl__compile_lit emitted; it may be rewritten only while
 * HERE still ends it (peep_end == here). Everything else that moves HERE clears
 * peep_end, and so do the control-flow words and HERE itself, because a branch
 * target (a label at HERE) must never end up inside a fused instruction. */
static void peep_set(fbrl_vm *vm, unsigned char *at)
{
    vm->peep = at;
    vm->peep_end = vm->here;
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
    };
    for (size_t i = 0; i < sizeof pairs / sizeof pairs[0]; i++)
        if (pairs[i].prev == prev && pairs[i].op == op)
            return pairs[i].fused;
    return 0;
}

/* Compile one op (a primitive, or OP_ZBRANCH whose target the caller emits next). */
int fbrl__compile_op(fbrl_vm *vm, int op)
{
    if (vm->peep_end && vm->peep_end == vm->here) {
        /* (HERE need not be aligned: , and C, can leave it anywhere, so memcpy) */
        unsigned char *p = vm->peep;
        fbrl_cell prev, v;
        int f;
        memcpy(&prev, p, sizeof prev);
        if (prev == OP_LIT) {
            memcpy(&v, p + CELL, sizeof v);
            if (fold_lit(op, &v)) {
                memcpy(p + CELL, &v, sizeof v);
                return 0;
            }
            if (op == OP_PICK && v >= 0 && v <= 2) { /* 0 PICK = DUP, 1 PICK = OVER */
                prev = v == 0 ? OP_DUP : v == 1 ? OP_OVER : OP_PICK2;
                memcpy(p, &prev, sizeof prev);
                vm->here -= CELL;
                vm->peep_end = vm->here;
                return 0;
            }
        }
        if ((f = fuse(prev, op))) {
            prev = f;
            memcpy(p, &prev, sizeof prev);
            return 0;
        }
    }
    unsigned char *at = vm->here;
    int r = fbrl__emit(vm, op);
    if (!r)
        peep_set(vm, at);
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
    case K_PRIM: return fbrl__compile_op(vm, h->op);
    case K_COLON:
        if ((r = fbrl__emit(vm, OP_CALL)))
            return r;
        return fbrl__emit(vm, h->body);
    case K_CREATE:
        /* Without DOES> a created word is a literal. DOES> can only change the
         * latest word, and a word compiled into a definition is no longer latest. */
        if (h->does)
            return fbrl__emit(vm, xt);
        /* fall through */
    case K_VAR: return fbrl__compile_lit(vm, h->body);
    case K_CONST: memcpy(&v, (void *)h->body, sizeof v); return fbrl__compile_lit(vm, v);
    default: return fbrl__emit(vm, xt);
    }
}

int fbrl__compile_lit(fbrl_vm *vm, fbrl_cell v)
{
    unsigned char *at = vm->here;
    int r = fbrl__emit(vm, OP_LIT);
    if (r || (r = fbrl__emit(vm, v)))
        return r;
    peep_set(vm, at);
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
    h->stack = dstack;
    h->help = dhelp;
    if (vm->nsrc == 0)
        return;
    fbrl_src *s = fbrl__src(vm);
    size_t i = src_in(vm, s), n = s->len;
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
    h->stack = stack;
    h->help = help;
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
    h->stack = h->stack[0] ? h->stack : "( i*x -- j*x )";
    h->help = h->help[0] ? h->help : "colon definition";
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

int fbrl__semicolon(fbrl_vm *vm)
{
    int r;
    if (!vm->defining || vm->ncf != 1 || vm->cf[0].tag != CF_COLON)
        return FBRL_THROW_CONTROL_MISMATCH;
    if ((r = fbrl__emit(vm, OP_EXIT)))
        return r;
    fbrl_hdr *h = HDR(vm, vm->def_word);
    h->end = (fbrl_cell)vm->here;
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
    if (vm->defining) {
        vm->here = vm->def_here;
        vm->nwords = vm->def_nwords;
        rebuild_hash(vm);
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
}

/* ---- the text interpreter ---- */
static void capture_error(fbrl_vm *vm)
{
    if (vm->err_captured)
        return;
    vm->err_captured = 1;
    memcpy(vm->err.word, vm->cur_word, sizeof vm->err.word);
    vm->err.file[0] = 0;
    vm->err.line = 0;
    for (int i = vm->nsrc - 1; i >= 0; i--) {
        const fbrl_src *s = &vm->src[i];
        if (s->kind == SRC_STRING)
            continue;
        if (s->kind == SRC_FILE) {
            size_t n = strlen(s->path);
            if (n >= sizeof vm->err.file)
                n = sizeof vm->err.file - 1;
            memcpy(vm->err.file, s->path, n);
            vm->err.file[n] = 0;
        }
        vm->err.line = s->line;
        break;
    }
}

static int interpret_word(fbrl_vm *vm, const char *name, size_t len)
{
    size_t n = len < sizeof vm->cur_word - 1 ? len : sizeof vm->cur_word - 1;
    memcpy(vm->cur_word, name, n);
    vm->cur_word[n] = 0;
    int idx = fbrl__find(vm, name, len);
    if (idx >= 0) {
        fbrl_hdr *h = HDR(vm, idx);
        fbrl_cell xt = FBRL_XT_BASE + idx;
        if (*vm->state == 0 && (h->flags & FC))
            return FBRL_THROW_COMPILE_ONLY;
        if (*vm->state != 0 && !(h->flags & FI))
            return fbrl__compile_xt(vm, xt);
        return fbrl__run(vm, xt);
    }
    fbrl_cell v[2];
    double f;
    int kind = fbrl__parse_number(vm, name, len, v, &f);
    if (kind == 0)
        return FBRL_THROW_UNDEFINED;
    if (*vm->state) {
        if (kind == 3)
            return fbrl__compile_flit(vm, f);
        int r = fbrl__compile_lit(vm, v[0]);
        return (r || kind == 1) ? r : fbrl__compile_lit(vm, v[1]);
    }
    if (kind == 3) {
        if (vm->fp >= vm->fs_end)
            return FBRL_THROW_FSTACK_OVERFLOW;
        *vm->fp++ = f;
        return 0;
    }
    if (vm->ds_end - vm->sp < kind)
        return FBRL_THROW_STACK_OVERFLOW;
    *vm->sp++ = v[0];
    if (kind == 2)
        *vm->sp++ = v[1];
    return 0;
}

/* Interpret the current source to its end. */
static int interpret(fbrl_vm *vm)
{
    for (;;) {
        const char *name;
        size_t len;
        int r;
        fbrl__parse_name(vm, &name, &len);
        if (len == 0) {
            r = fbrl__refill(vm);
            if (r > 0)
                continue;
        } else {
            r = interpret_word(vm, name, len);
            if (vm->bye && !r)
                r = THROW_BYE;
            if (!r)
                continue;
        }
        if (r)
            capture_error(vm);
        return r;
    }
}

static int push_source(fbrl_vm *vm, int kind, fbrl_src **out)
{
    if (vm->nsrc >= FBRL_SRC_MAX)
        return fbrl__throw_msg(vm, FBRL_THROW_FILE_IO, "input sources nested too deeply");
    fbrl_src *s = &vm->src[vm->nsrc];
    char *lb = s->linebuf;
    memset(s, 0, sizeof *s);
    s->linebuf = lb;
    s->kind = kind;
    s->buf = lb;
    s->saved_in = *vm->toin;
    vm->nsrc++;
    *vm->toin = 0;
    *out = s;
    return 0;
}

static void pop_source(fbrl_vm *vm)
{
    fbrl_src *s = fbrl__src(vm);
    if (s->kind == SRC_FILE && s->fh && vm->host.file_close)
        vm->host.file_close(vm->host.user, s->fh);
    *vm->toin = s->saved_in;
    vm->nsrc--;
}

void fbrl__pop_source(fbrl_vm *vm)
{
    if (vm->nsrc > 0)
        pop_source(vm);
}

int fbrl__evaluate(fbrl_vm *vm, char *text, size_t len)
{
    fbrl_src *s = NULL;
    int r = push_source(vm, SRC_STRING, &s);
    if (r)
        return r;
    s->buf = text;
    s->len = len;
    s->id = -1;
    r = interpret(vm);
    pop_source(vm);
    return r;
}

static int is_included(const fbrl_vm *vm, const char *path)
{
    for (size_t i = 0; i < vm->req_used; i += strlen(vm->req_pool + i) + 1)
        if (strcmp(vm->req_pool + i, path) == 0)
            return 1;
    return 0;
}

/* INCLUDED / REQUIRED. Relative paths are taken from the including file's directory. */
int fbrl__included(fbrl_vm *vm, const char *name, size_t n, int require)
{
    char path[FBRL_PATH_MAX];
    size_t dl = 0;
    if (n == 0)
        return FBRL_THROW_NO_FILE;
    if (name[0] != '/') {
        for (int i = vm->nsrc - 1; i >= 0; i--) {
            if (vm->src[i].kind != SRC_FILE)
                continue;
            const char *slash = strrchr(vm->src[i].path, '/');
            if (slash)
                dl = (size_t)(slash - vm->src[i].path) + 1;
            if (dl)
                memcpy(path, vm->src[i].path, dl);
            break;
        }
    }
    if (dl + n >= sizeof path)
        return fbrl__throw_msg(vm, FBRL_THROW_NO_FILE, "file name too long");
    memcpy(path + dl, name, n);
    path[dl + n] = 0;
    if (memchr(path, 0, dl + n))
        return FBRL_THROW_NO_FILE;
    if (require && is_included(vm, path))
        return 0;
    if (!vm->host.file_open || !vm->host.file_read_line)
        return fbrl__throw_msg(vm, FBRL_THROW_UNSUPPORTED, "no file support in this host");
    if (!is_included(vm, path)) {
        if (vm->req_used + dl + n + 1 > sizeof vm->req_pool)
            return fbrl__throw_msg(vm, FBRL_THROW_FILE_IO, "too many included files");
        memcpy(vm->req_pool + vm->req_used, path, dl + n + 1);
        vm->req_used += dl + n + 1;
    }
    fbrl_src *s = NULL;
    int r = push_source(vm, SRC_FILE, &s);
    if (r)
        return r;
    memcpy(s->path, path, dl + n + 1);
    s->id = vm->nsrc;
    fbrl_status ost = vm->host.file_open(vm->host.user, path, &s->fh);
    if (ost != FBRL_OK) {
        s->fh = NULL;
        vm->nsrc--;
        *vm->toin = s->saved_in;
        char msg[sizeof vm->throw_msg];
        size_t k = n < 80 ? n : 80;
        memcpy(msg, "cannot open ", 12);
        memcpy(msg + 12, name, k);
        msg[12 + k] = 0;
        if (ost != FBRL_ENOENT) { /* say why, e.g. a device or FIFO refused */
            const char *why = fbrl_status_str(ost);
            size_t at = 12 + k, w = strlen(why);
            if (at + 2 + w < sizeof msg) {
                memcpy(msg + at, ": ", 2);
                memcpy(msg + at + 2, why, w + 1);
            }
        }
        return fbrl__throw_msg(vm, FBRL_THROW_NO_FILE, msg);
    }
    fbrl_cell state0 = *vm->state;
    r = interpret(vm);
    if (r == 0 && *vm->state != 0 && state0 == 0) {
        r = fbrl__throw_msg(vm, FBRL_THROW_UNEXPECTED_EOF, "unterminated definition at end of file");
        capture_error(vm);
    }
    pop_source(vm);
    return r;
}

/* ---- the C API ---- */
static size_t align16(size_t n) { return (n + 15) & ~(size_t)15; }

typedef struct layout {
    size_t ds, rs, fs; /* cells */
    size_t o_ds, o_rs, o_fs, o_data, fixed;
} layout;

#define FBRL_SYSVARS 8
#define FBRL_BUFS                                                                     \
    (FBRL_SYSVARS * sizeof(fbrl_cell) + FBRL_WORDBUF + FBRL_PADSIZE + FBRL_HOLDSIZE + \
     FBRL_NSBUF * FBRL_SBUF + FBRL_SRC_MAX * (FBRL_LINE_MAX + 8))
#define FBRL_EXTRA_WORDS 64 /* headers beyond the primitives (data words) */

/* Primitives with a dictionary entry (internal ops and superinstructions have none). */
static size_t named_ops(void)
{
    size_t n = 0;
    for (int op = 0; op < OP__END; op++)
        n += ops[op].name[0] != 0;
    return n;
}

static void make_layout(const fbrl_vm_config *cfg, layout *l)
{
    l->ds = cfg->data_stack_cells ? cfg->data_stack_cells : 256;
    l->rs = cfg->return_stack_cells ? cfg->return_stack_cells : 256;
    l->fs = cfg->float_stack_cells ? cfg->float_stack_cells : 64;
    /* 16 spare bytes below the data and float stacks: run.c stores the cached top
     * of an empty stack there */
    l->o_ds = align16(sizeof(struct fbrl_vm)) + 16;
    l->o_rs = l->o_ds + align16(l->ds * sizeof(fbrl_cell));
    l->o_fs = l->o_rs + align16(l->rs * sizeof(fbrl_cell)) + 16;
    l->o_data = l->o_fs + align16(l->fs * sizeof(double));
    l->fixed = l->o_data + align16(FBRL_BUFS) + FBRL_GUARD_CELLS * sizeof(fbrl_cell) + 16 +
               (named_ops() + FBRL_EXTRA_WORDS) * sizeof(fbrl_hdr) + 2048;
}

size_t fbrl_vm_size_for(const fbrl_vm_config *cfg, size_t dict_bytes)
{
    layout l;
    if (!cfg)
        return 0;
    make_layout(cfg, &l);
    return l.fixed + dict_bytes;
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

    fbrl_cell *guard = (fbrl_cell *)(void *)(vm->mem_end - FBRL_GUARD_CELLS * sizeof(fbrl_cell));
    for (int i = 0; i < FBRL_GUARD_CELLS; i++)
        guard[i] = OP_BAD;
    guard[0] = OP_HALT;
    guard[1] = OP_CATCHEND;
    vm->guard_addr = (fbrl_cell)guard;
    vm->hdr_top = (fbrl_hdr *)(void *)guard;
    vm->data_hi = (unsigned char *)guard;
    *vm->base = 10;
    vm->precision = 6;

    for (int op = 0; op < OP__END; op++) {
        fbrl_hdr *h;
        if (!ops[op].name[0])
            continue;
        if (new_header(vm, ops[op].name, strlen(ops[op].name), K_PRIM, ops[op].flags, &h))
            return FBRL_ENOSPC;
        h->op = (uint16_t)op;
        h->stack = ops[op].stack;
        h->help = ops[op].help;
    }
    fbrl_status st = fbrl__fbrl_words(vm);
    if (st != FBRL_OK)
        return st == FBRL_ENOMEM ? FBRL_ENOSPC : st;
    st = fbrl_vm_eval(vm, fbrl__prelude, strlen(fbrl__prelude));
    if (st != FBRL_OK)
        return vm->err.throw_code == FBRL_THROW_DICT_OVERFLOW ? FBRL_ENOSPC : st;
    vm->dict_lo = vm->here;
    *out = vm;
    return FBRL_OK;
}

static void reset_after_error(fbrl_vm *vm)
{
    vm->sp = vm->ds0;
    vm->rp = vm->rs0;
    vm->fp = vm->fs0;
    vm->handler = 0;
    vm->nest = 0;
    while (vm->nsrc > 0)
        pop_source(vm);
    discard_definition(vm);
    vm->hld = vm->hold + FBRL_HOLDSIZE;
}

void fbrl_vm_interrupt(fbrl_vm *vm)
{
    if (vm)
        fbrl_store_rlx(&vm->interrupt, 1);
}

int fbrl_vm_interrupt_pending(const fbrl_vm *vm)
{
    return vm ? fbrl_load_rlx(&((fbrl_vm *)vm)->interrupt) != 0 : 0;
}

int fbrl__take_interrupt(fbrl_vm *vm)
{
    if (!fbrl_load_rlx(&vm->interrupt))
        return 0;
    fbrl_store_rlx(&vm->interrupt, 0);
    return 1;
}

static void begin_top(fbrl_vm *vm)
{
    fbrl_store_rlx(&vm->interrupt, 0);
    vm->running = 1;
    vm->err_captured = 0;
    vm->pending_msg = NULL;
    vm->cur_word[0] = 0;
    memset(&vm->err, 0, sizeof vm->err);
    vm->rp = vm->rs0;
    vm->handler = 0;
    vm->nest = 0;
}

static fbrl_status finish_top(fbrl_vm *vm, int code)
{
    vm->running = 0;
    if (code == 0 || code == THROW_BYE) {
        while (vm->nsrc > 0)
            pop_source(vm);
        return FBRL_OK;
    }
    if (code == THROW_QUIT) {
        vm->rp = vm->rs0;
        while (vm->nsrc > 0)
            pop_source(vm);
        discard_definition(vm);
        return FBRL_OK;
    }
    capture_error(vm);
    vm->err.throw_code = code;
    const char *msg =
        (vm->pending_msg && vm->pending_code == code) ? vm->pending_msg : fbrl__throw_text(code);
    size_t n = strlen(msg);
    if (n >= sizeof vm->err.message)
        n = sizeof vm->err.message - 1;
    memcpy(vm->err.message, msg, n);
    vm->err.message[n] = 0;
    reset_after_error(vm);
    if (code <= FBRL_THROW_STATUS(0) && code >= FBRL_THROW_STATUS(FBRL_STATUS_MIN) &&
        code != FBRL_THROW_STATUS(FBRL_ETHROW))
        return (fbrl_status)(code - FBRL_THROW_STATUS(0));
    return FBRL_ETHROW;
}

fbrl_status fbrl_vm_eval(fbrl_vm *vm, const char *text, size_t len)
{
    fbrl_src *s = NULL;
    if (!vm || (!text && len))
        return FBRL_EINVAL;
    if (vm->running)
        return FBRL_ESTATE;
    if (vm->bye)
        return FBRL_OK;
    begin_top(vm);
    int r = push_source(vm, SRC_TEXT, &s);
    if (!r) {
        s->text = text ? text : "";
        s->text_end = s->text + len;
        s->len = 0;
        r = interpret(vm);
    }
    return finish_top(vm, r);
}

fbrl_status fbrl_vm_include(fbrl_vm *vm, const char *path)
{
    if (!vm || !path)
        return FBRL_EINVAL;
    if (vm->running)
        return FBRL_ESTATE;
    if (vm->bye)
        return FBRL_OK;
    begin_top(vm);
    int r = fbrl__included(vm, path, strlen(path), 0);
    return finish_top(vm, r);
}

const fbrl_vm_error *fbrl_vm_last_error(const fbrl_vm *vm) { return vm ? &vm->err : NULL; }
int fbrl_vm_bye(const fbrl_vm *vm) { return vm ? vm->bye : 0; }
int fbrl_vm_compiling(const fbrl_vm *vm) { return vm ? (*vm->state != 0 || vm->defining) : 0; }

void fbrl_vm_reset(fbrl_vm *vm)
{
    if (!vm || vm->running)
        return;
    reset_after_error(vm);
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
    h->fn = fn;
    h->arg = arg;
    h->body = (fbrl_cell)vm->here;
    h->stack = stack_effect ? stack_effect : "";
    h->help = help ? help : "";
    return FBRL_OK;
}

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

fbrl_status fbrl_vm_help(const fbrl_vm *vm, const char *name, const char **stack_effect, const char **help)
{
    if (!vm || !name)
        return FBRL_EINVAL;
    int i = fbrl__find(vm, name, strlen(name));
    if (i < 0)
        return FBRL_ENOENT;
    const fbrl_hdr *h = HDR(vm, i);
    if (stack_effect)
        *stack_effect = h->stack;
    if (help)
        *help = h->help;
    return FBRL_OK;
}

void fbrl_vm_words(const fbrl_vm *vm, int (*fn)(void *ctx, const char *name, size_t len), void *ctx)
{
    if (!vm || !fn)
        return;
    for (uint32_t i = vm->nwords; i-- > 0;) {
        const fbrl_hdr *h = HDR(vm, i);
        if (!h->len || (h->flags & FH))
            continue;
        /* skip words shadowed by a newer one of the same name */
        if (fbrl__find(vm, h->name, h->len) != (int)i)
            continue;
        if (fn(ctx, h->name, h->len))
            return;
    }
}
