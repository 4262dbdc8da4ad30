/* SPDX-License-Identifier: MIT */
/* words.c - the words that are not worth inlining in the inner interpreter:
 * control-structure compilers, defining and parsing words, SEE (number and float
 * output and the console's words are in words_io.c).
 * Each group works on the VM's own stack pointers (run.c saved them). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fbrl/num.h"
#include "words_stack.h"

#define U(x) ((fbrl_ucell)(x))

/* ---- strings ---- */
int fbrl__w_string(fbrl_vm *vm, int op)
{
    fbrl_cell a, u, n;
    const char *s1, *s2;
    size_t n1, n2;
    int r;
    switch (op) {
    case OP_COMPARE:
        if ((r = need(vm, 4)) || (r = pop_str(vm, &s2, &n2)) || (r = pop_str(vm, &s1, &n1)))
            return r;
        {
            size_t m = n1 < n2 ? n1 : n2;
            int c = m ? memcmp(s1, s2, m) : 0;
            if (c == 0)
                c = n1 < n2 ? -1 : n1 > n2;
            return push(vm, c < 0 ? -1 : c > 0);
        }
    case OP_SEARCH:
        if ((r = need(vm, 4)) || (r = pop_str(vm, &s2, &n2)) || (r = pop_str(vm, &s1, &n1)))
            return r;
        for (size_t i = 0; n2 <= n1 && i <= n1 - n2; i++) {
            if (n2 == 0 || memcmp(s1 + i, s2, n2) == 0) {
                vm->sp += 2; /* a1 stays as given (an empty string's too) */
                vm->sp[-2] = (fbrl_cell)(U(vm->sp[-2]) + i);
                vm->sp[-1] = (fbrl_cell)(n1 - i);
                return push(vm, -1);
            }
        }
        vm->sp += 2; /* the original a1 u1 are still in place below */
        return push(vm, 0);
    case OP_SLASHSTRING:
        if ((r = need(vm, 3)) || (r = pop(vm, &n)))
            return r;
        vm->sp[-2] = (fbrl_cell)(U(vm->sp[-2]) + U(n));
        vm->sp[-1] = (fbrl_cell)(U(vm->sp[-1]) - U(n));
        return 0;
    case OP_MTRAILING:
        if ((r = need(vm, 2)))
            return r;
        a = vm->sp[-2];
        u = vm->sp[-1];
        if (u < 0)
            return FBRL_THROW_BAD_NUMBER;
        if (u && !fbrl__addr_ok(vm, a, u))
            return FBRL_THROW_BAD_ADDRESS;
        while (u > 0 && ((const char *)a)[u - 1] == ' ')
            u--;
        vm->sp[-1] = u;
        return 0;
    }
    return FBRL_THROW_UNSUPPORTED;
}

/* ---- control structures ---- */
static int cf_push(fbrl_vm *vm, int tag, fbrl_cell a)
{
    if (vm->ncf >= FBRL_CF_MAX)
        return FBRL_THROW_CF_OVERFLOW;
    vm->cf[vm->ncf].tag = tag;
    vm->cf[vm->ncf].a = a;
    vm->ncf++;
    return 0;
}

static int cf_pop(fbrl_vm *vm, int tag, fbrl_cell *a)
{
    if (vm->ncf == 0 || vm->cf[vm->ncf - 1].tag != tag)
        return fbrl__throw_msg(vm, FBRL_THROW_CONTROL_MISMATCH,
                               "control structure mismatch (unbalanced IF/DO/BEGIN/CASE?)");
    *a = vm->cf[--vm->ncf].a;
    return 0;
}

/* A branch op and its target; 0BRANCH may fuse with the comparison before it, +LOOP with
 * the literal or DUP that gives its increment. */
static int branch_op(fbrl_vm *vm, int op)
{
    return op == OP_ZBRANCH || op == OP_PPLOOP ? fbrl__compile_op(vm, op) : fbrl__emit(vm, op);
}

#define NBR ((unsigned)(sizeof vm->br_orig / sizeof vm->br_orig[0]))

static int forward(fbrl_vm *vm, int op, fbrl_cell *orig)
{
    int r = branch_op(vm, op);
    if (r)
        return r;
    *orig = (fbrl_cell)vm->here;
    if (op == OP_BRANCH)
        vm->br_orig[vm->nbr_orig++ % NBR] = *orig;
    return fbrl__emit(vm, 0);
}

static int resolve(fbrl_vm *vm, fbrl_cell orig)
{
    fbrl_cell t = (fbrl_cell)vm->here;
    if (!fbrl__addr_ok(vm, orig, CELL))
        return FBRL_THROW_BAD_ADDRESS;
    memcpy((void *)orig, &t, sizeof t);
    for (unsigned i = 0; i < NBR && i < vm->nbr_orig; i++) {
        if (vm->br_orig[(vm->nbr_orig - 1 - i) % NBR] != orig)
            continue;
        if (vm->exit_here != vm->here) { /* a forward BRANCH to HERE: an exit if ; follows */
            vm->exit_here = vm->here;
            vm->nexit_orig = 0;
        }
        if (vm->nexit_orig < NBR)
            vm->exit_orig[vm->nexit_orig++] = orig;
        break;
    }
    return 0;
}

static int back(fbrl_vm *vm, int op, fbrl_cell dest)
{
    int r = branch_op(vm, op);
    return r ? r : fbrl__emit(vm, dest);
}

static int control(fbrl_vm *vm, int op)
{
    fbrl_cell o = 0, d = 0;
    int r = 0;
    /* also valid between [ ] inside a definition (a POSTPONEd IF run there) */
    if (*vm->state == 0 && !vm->defining)
        return FBRL_THROW_COMPILE_ONLY;
    switch (op) {
    case OP_IF: return (r = forward(vm, OP_ZBRANCH, &o)) ? r : cf_push(vm, CF_ORIG, o);
    case OP_AHEAD: return (r = forward(vm, OP_BRANCH, &o)) ? r : cf_push(vm, CF_ORIG, o);
    case OP_ELSE:
        if ((r = cf_pop(vm, CF_ORIG, &o)) || (r = forward(vm, OP_BRANCH, &d)) || (r = resolve(vm, o)))
            return r;
        return cf_push(vm, CF_ORIG, d);
    case OP_THEN: return (r = cf_pop(vm, CF_ORIG, &o)) ? r : resolve(vm, o);
    case OP_BEGIN: return cf_push(vm, CF_DEST, (fbrl_cell)vm->here);
    case OP_UNTIL: return (r = cf_pop(vm, CF_DEST, &d)) ? r : back(vm, OP_ZBRANCH, d);
    case OP_AGAIN: return (r = cf_pop(vm, CF_DEST, &d)) ? r : back(vm, OP_BRANCH, d);
    case OP_WHILE:
        if ((r = cf_pop(vm, CF_DEST, &d)) || (r = forward(vm, OP_ZBRANCH, &o)) ||
            (r = cf_push(vm, CF_ORIG, o)))
            return r;
        return cf_push(vm, CF_DEST, d);
    case OP_REPEAT:
        if ((r = cf_pop(vm, CF_DEST, &d)) || (r = back(vm, OP_BRANCH, d)) || (r = cf_pop(vm, CF_ORIG, &o)))
            return r;
        return resolve(vm, o);
    case OP_DO:
    case OP_QDO:
        if ((r = forward(vm, op == OP_DO ? OP_PDO : OP_PQDO, &o)) || (r = cf_push(vm, CF_DO, o)))
            return r;
        return cf_push(vm, CF_DEST, (fbrl_cell)vm->here);
    case OP_LOOP:
    case OP_PLUSLOOP:
        if ((r = cf_pop(vm, CF_DEST, &d)) || (r = cf_pop(vm, CF_DO, &o)))
            return r;
        if ((r = back(vm, op == OP_LOOP ? OP_PLOOP : OP_PPLOOP, d)))
            return r;
        return resolve(vm, o);
    case OP_CASE: return cf_push(vm, CF_CASE, 0);
    case OP_OF: return (r = forward(vm, OP_POF, &o)) ? r : cf_push(vm, CF_OF, o);
    case OP_ENDOF:
        if ((r = cf_pop(vm, CF_OF, &o)) || (r = forward(vm, OP_BRANCH, &d)) || (r = resolve(vm, o)))
            return r;
        return cf_push(vm, CF_ENDOF, d);
    case OP_ENDCASE: /* the default path drops the selector; ENDOFs jump past that */
        if ((r = fbrl__emit(vm, OP_DROP)))
            return r;
        while (vm->ncf > 0 && vm->cf[vm->ncf - 1].tag == CF_ENDOF) {
            if ((r = cf_pop(vm, CF_ENDOF, &o)) || (r = resolve(vm, o)))
                return r;
        }
        return cf_pop(vm, CF_CASE, &o);
    case OP_RECURSE:
        if (!vm->defining)
            return FBRL_THROW_CONTROL_MISMATCH;
        return back(vm, OP_CALL, HDR(vm, vm->def_word)->body);
    case OP_DOES:
        if (!vm->defining)
            return FBRL_THROW_CONTROL_MISMATCH;
        if (vm->nlocals) { /* the creating part's locals end here; DOES> code may have its own */
            int r = fbrl__compile_xt(vm, vm->lexit_xt);
            vm->nlocals = 0;
            if (r)
                return r;
        }
        return fbrl__emit(vm, OP_DOESSET);
    }
    return FBRL_THROW_UNSUPPORTED;
}

int fbrl__w_control(fbrl_vm *vm, int op)
{
    int r = control(vm, op);
    fbrl__peep_reset(vm); /* HERE may now be a branch target: fuse nothing across it */
    return r;
}

/* ---- defining words ---- */
static int falign_body(fbrl_vm *vm, fbrl_hdr *h)
{
    fbrl_ucell a = U(vm->here), m = sizeof(double) - 1;
    int r = fbrl__allot(vm, (fbrl_cell)(((a + m) & ~m) - a));
    h->body = (fbrl_cell)vm->here;
    return r;
}

int fbrl__w_define(fbrl_vm *vm, int op)
{
    fbrl_hdr *h;
    fbrl_cell v = 0, v2 = 0;
    double f = 0;
    int r;
    switch (op) {
    case OP_CREATE:
        return fbrl__create(vm, K_CREATE, "( -- a )", "created word: pushes its data address", &h);
    case OP_VARIABLE:
        if ((r = fbrl__create(vm, K_VAR, "( -- a )", "variable", &h)))
            return r;
        return fbrl__emit(vm, 0);
    case OP_TWOVARIABLE:
        if ((r = fbrl__create(vm, K_VAR, "( -- a )", "double variable", &h)) || (r = fbrl__emit(vm, 0)))
            return r;
        return fbrl__emit(vm, 0);
    case OP_CONSTANT:
    case OP_VALUE:
        if ((r = pop(vm, &v)))
            return r;
        if ((r = fbrl__create(vm, op == OP_CONSTANT ? K_CONST : K_VALUE, "( -- x )",
                              op == OP_CONSTANT ? "constant" : "value (set with TO)", &h)))
            return r;
        return fbrl__emit(vm, v);
    case OP_TWOCONSTANT:
    case OP_TWOVALUE:
        if ((r = need(vm, 2)))
            return r;
        pop(vm, &v2);
        pop(vm, &v);
        if ((r = fbrl__create(vm, op == OP_TWOCONSTANT ? K_2CONST : K_2VALUE, "( -- x1 x2 )",
                              op == OP_TWOCONSTANT ? "double constant" : "double value (set with TO)", &h)) ||
            (r = fbrl__emit(vm, v2)))
            return r;
        return fbrl__emit(vm, v);
    case OP_DEFER:
        if ((r = fbrl__create(vm, K_DEFER, "( i*x -- j*x )", "deferred word (set with IS)", &h)))
            return r;
        return fbrl__emit(vm, 0);
    case OP_BUFFERCOLON:
        if ((r = pop(vm, &v)))
            return r;
        if (v < 0)
            return FBRL_THROW_BAD_NUMBER;
        if ((r = fbrl__create(vm, K_VAR, "( -- a )", "buffer", &h)))
            return r;
        return fbrl__allot(vm, v);
    case OP_MARKER: {
        unsigned char *here = vm->here;
        uint32_t n = vm->nwords;
        if ((r = fbrl__create(vm, K_MARKER, "( -- )", "forget this marker and everything after it", &h)))
            return r;
        h->body = (fbrl_cell)here;
        H_END(h) = (fbrl_cell)n;
        H_DOES(h) = (fbrl_cell)vm->req_used;
        return 0;
    }
    case OP_FVARIABLE:
        if ((r = fbrl__create(vm, K_VAR, "( -- a )", "float variable", &h)) || (r = falign_body(vm, h)))
            return r;
        if ((r = fbrl__allot(vm, (fbrl_cell)sizeof(double))))
            return r;
        memset(vm->here - sizeof(double), 0, sizeof(double));
        return 0;
    case OP_FCONSTANT:
    case OP_FVALUE:
        if ((r = fpop(vm, &f)))
            return r;
        if ((r = fbrl__create(vm, op == OP_FCONSTANT ? K_FCONST : K_FVALUE, "( F: -- r )",
                              op == OP_FCONSTANT ? "float constant" : "float value (set with TO)", &h)) ||
            (r = falign_body(vm, h)) || (r = fbrl__allot(vm, (fbrl_cell)sizeof(double))))
            return r;
        memcpy(vm->here - sizeof(double), &f, sizeof f);
        return 0;
    }
    return FBRL_THROW_UNSUPPORTED;
}

/* ---- parsing words ---- */
static int parse_word_xt(fbrl_vm *vm, fbrl_cell *xt, fbrl_hdr **h)
{
    const char *name;
    size_t len;
    fbrl__parse_name(vm, &name, &len);
    if (len == 0)
        return FBRL_THROW_NO_NAME;
    int i = fbrl__find(vm, name, len);
    if (i < 0) {
        size_t n = len < 60 ? len : 60;
        memcpy(vm->cur_word, name, n);
        vm->cur_word[n] = 0;
        return FBRL_THROW_UNDEFINED;
    }
    *xt = FBRL_XT_BASE + i;
    *h = HDR(vm, i);
    return 0;
}

/* S\" escapes; parses up to the closing quote into out */
static int parse_escaped(fbrl_vm *vm, char *out, size_t cap, size_t *n)
{
    fbrl_src *s = fbrl__src(vm);
    size_t i = (size_t)(*vm->toin < 0 ? 0 : *vm->toin), k = 0;
    if (i > s->len)
        i = s->len;
    for (;;) {
        if (i >= s->len)
            return fbrl__throw_msg(vm, FBRL_THROW_UNEXPECTED_EOF, "unterminated string");
        char c = s->buf[i++];
        if (c == '"')
            break;
        if (c == '\\' && i < s->len) {
            c = s->buf[i++];
            switch (c) {
            case 'a': c = 7; break;
            case 'b': c = 8; break;
            case 'e': c = 27; break;
            case 'f': c = 12; break;
            case 'l':
            case 'n': c = 10; break;
            case 'q': c = '"'; break;
            case 'r': c = 13; break;
            case 't': c = 9; break;
            case 'v': c = 11; break;
            case 'z': c = 0; break;
            case 'm':
                if (k >= cap)
                    return FBRL_THROW_PARSED_OVERFLOW;
                out[k++] = 13;
                c = 10;
                break;
            case 'x': {
                int v = 0;
                for (int j = 0; j < 2; j++) {
                    int d = -1;
                    if (i < s->len) {
                        char h = s->buf[i];
                        d = h >= '0' && h <= '9'   ? h - '0'
                            : h >= 'a' && h <= 'f' ? h - 'a' + 10
                            : h >= 'A' && h <= 'F' ? h - 'A' + 10
                                                   : -1;
                    }
                    if (d < 0)
                        return fbrl__throw_msg(vm, FBRL_THROW_BAD_NUMBER, "bad \\x escape");
                    v = v * 16 + d;
                    i++;
                }
                c = (char)v;
                break;
            }
            default: break; /* \" \\ and anything else: the character itself */
            }
        }
        if (k >= cap)
            return FBRL_THROW_PARSED_OVERFLOW;
        out[k++] = c;
    }
    *vm->toin = (fbrl_cell)i;
    *n = k;
    return 0;
}

static int string_literal(fbrl_vm *vm, const char *s, size_t n)
{
    if (*vm->state)
        return fbrl__compile_str(vm, OP_SLIT, s, n);
    if (n > FBRL_SBUF)
        return FBRL_THROW_PARSED_OVERFLOW;
    char *b = vm->sbuf + FBRL_SBUF * vm->sbuf_next;
    vm->sbuf_next = (vm->sbuf_next + 1) % FBRL_NSBUF;
    memmove(b, s, n);
    int r = push(vm, (fbrl_cell)b);
    return r ? r : push(vm, (fbrl_cell)n);
}

static int parse_quoted(fbrl_vm *vm, char delim, const char **p, size_t *n)
{
    int found;
    fbrl__parse(vm, delim, p, n, &found);
    if (!found)
        return fbrl__throw_msg(vm, FBRL_THROW_UNEXPECTED_EOF,
                               delim == ')' ? "unterminated comment" : "unterminated string");
    return 0;
}

static int paren_comment(fbrl_vm *vm)
{
    for (;;) {
        const char *p;
        size_t n;
        int found, r;
        fbrl__parse(vm, ')', &p, &n, &found);
        if (found)
            return 0;
        if (fbrl__src(vm)->kind == SRC_STRING)
            return fbrl__throw_msg(vm, FBRL_THROW_UNEXPECTED_EOF, "unterminated comment");
        if ((r = fbrl__refill(vm)) < 0)
            return r;
        if (r == 0)
            return fbrl__throw_msg(vm, FBRL_THROW_UNEXPECTED_EOF, "unterminated comment");
    }
}

static void put_num(fbrl_vm *vm, fbrl_cell n)
{
    char b[32];
    int k = snprintf(b, sizeof b, "%ld", (long)n);
    fbrl__write(vm, b, (size_t)k);
}

static fbrl_hdr *hdr_by_body(fbrl_vm *vm, fbrl_cell body)
{
    for (uint32_t i = vm->nwords; i-- > 0;)
        if (HDR(vm, i)->body == body && HDR(vm, i)->kind != K_PRIM && HDR(vm, i)->kind != K_CFUNC)
            return HDR(vm, i);
    return NULL;
}

static void put_name(fbrl_vm *vm, const fbrl_hdr *h)
{
    if (h && h->len)
        fbrl__write(vm, h->name, h->len);
    else
        fbrl__puts(vm, ":NONAME");
}

/* A superinstruction shows as the words it was compiled from (fbrl__fused_words). */
static int see_fused(fbrl_vm *vm, fbrl_cell w, fbrl_cell *pc)
{
    int lit, br;
    fbrl_cell a = 0;
    const char *words = fbrl__fused_words((int)w, &lit, &br), *at;
    if (!words)
        return 0;
    at = strchr(words, '#');
    if (lit) {
        if (!fbrl__addr_ok(vm, *pc, CELL))
            return 1;
        memcpy(&a, (void *)*pc, sizeof a);
        *pc += CELL;
    }
    if (lit && !at) {
        put_num(vm, a);
        fbrl__puts(vm, " ");
    }
    if (at) {
        fbrl__write(vm, words, (size_t)(at - words));
        put_num(vm, a);
        words = at + 1;
    }
    fbrl__puts(vm, words);
    if (br) {
        if (!fbrl__addr_ok(vm, *pc, CELL))
            return 1;
        memcpy(&a, (void *)*pc, sizeof a);
        *pc += CELL;
        if (br == 1) { /* a loop's target (br 2) is shown by nothing, as after +LOOP */
            fbrl__puts(vm, " 0BRANCH(");
            put_num(vm, (fbrl_cell)(U(a) - U(*pc)) / CELL);
            fbrl__puts(vm, ")");
        }
    }
    return 1;
}

static void see_colon(fbrl_vm *vm, fbrl_hdr *h)
{
    fbrl_cell pc = h->body, end = H_END(h);
    fbrl__puts(vm, ": ");
    put_name(vm, h);
    while (pc < end && fbrl__addr_ok(vm, pc, CELL)) {
        fbrl_cell w, a;
        memcpy(&w, (void *)pc, sizeof w);
        pc += CELL;
        if (w == OP_EXIT && pc == end)
            break; /* the EXIT that ; compiled */
        fbrl__puts(vm, " ");
        if (w >= FBRL_XT_BASE) {
            put_name(vm, fbrl__xt_hdr(vm, w));
            continue;
        }
        if (w < 0 || w >= OP__END) {
            fbrl__puts(vm, "?");
            continue;
        }
        if (see_fused(vm, w, &pc))
            continue;
        const char *nm = fbrl__op_name((int)w);
        if (nm[0]) {
            fbrl__puts(vm, nm);
            continue;
        }
        if (!fbrl__addr_ok(vm, pc, CELL))
            break;
        memcpy(&a, (void *)pc, sizeof a);
        switch (w) {
        case OP_LIT:
            put_num(vm, a);
            pc += CELL;
            break;
        case OP_FLIT: {
            double d;
            char b[40];
            memcpy(&d, (void *)pc, sizeof d);
            fbrl_num_general(b, sizeof b - 1, d, 17, NULL); /* locale-free %.17g */
            strcat(b, "E");
            fbrl__puts(vm, b);
            pc += (fbrl_cell)((sizeof(double) + sizeof(fbrl_cell) - 1) / sizeof(fbrl_cell)) * CELL;
            break;
        }
        case OP_CALL:
            put_name(vm, hdr_by_body(vm, a));
            pc += CELL;
            break;
        case OP_BRANCH:
        case OP_EXITBR: /* a BRANCH to the end (dict.c exit_branches) */
        case OP_ZBRANCH:
            fbrl__puts(vm, w == OP_ZBRANCH ? "0BRANCH(" : "BRANCH(");
            put_num(vm, (fbrl_cell)(U(a) - U(pc) - U(CELL)) / CELL);
            fbrl__puts(vm, ")");
            pc += CELL;
            break;
        case OP_PDO:
            fbrl__puts(vm, "DO");
            pc += CELL;
            break;
        case OP_PQDO:
            fbrl__puts(vm, "?DO");
            pc += CELL;
            break;
        case OP_PLOOP:
            fbrl__puts(vm, "LOOP");
            pc += CELL;
            break;
        case OP_PPLOOP:
            fbrl__puts(vm, "+LOOP");
            pc += CELL;
            break;
        case OP_POF:
            fbrl__puts(vm, "OF");
            pc += CELL;
            break;
        case OP_DOESSET: fbrl__puts(vm, "DOES>"); break;
        case OP_COMPSEM: fbrl__puts(vm, "(COMPILING-EXECUTE)"); break;
        case OP_PTOVAL:
        case OP_PTO2VAL:
        case OP_PTOFVAL:
            fbrl__puts(vm, "TO ");
            put_name(vm, hdr_by_body(vm, a));
            pc += CELL;
            break;
        case OP_SLIT:
        case OP_CSLIT:
        case OP_PABORTQ: {
            fbrl_cell s = pc + CELL;
            fbrl__puts(vm, w == OP_SLIT ? "S\" " : w == OP_CSLIT ? "C\" " : "ABORT\" ");
            if (a >= 0 && a <= 65536 && fbrl__addr_ok(vm, s, a)) {
                fbrl_cell t = w == OP_CSLIT ? 1 : 0;
                fbrl__write(vm, (const char *)s + t, (size_t)(a - t));
            }
            fbrl__puts(vm, "\"");
            pc = s + (a / CELL + 1) * CELL;
            break;
        }
        default: fbrl__puts(vm, "?"); break;
        }
    }
    fbrl__puts(vm, " ;");
    if (h->flags & FI)
        fbrl__puts(vm, " IMMEDIATE");
    fbrl__puts(vm, "\n");
}

static void see(fbrl_vm *vm, fbrl_hdr *h)
{
    static const char *const kinds[] = {
        "primitive",      "",      "variable",     "created",     "constant", "double constant",
        "float constant", "value", "double value", "float value", "deferred", "C word",
        "marker"};
    if (h->kind == K_COLON) {
        see_colon(vm, h);
        return;
    }
    put_name(vm, h);
    fbrl__puts(vm, " is a ");
    fbrl__puts(vm, kinds[h->kind]);
    if (h->kind == K_DEFER && fbrl__addr_ok(vm, h->body, CELL)) {
        fbrl_cell x;
        memcpy(&x, (void *)h->body, sizeof x);
        fbrl__puts(vm, " -> ");
        if (fbrl__xt_hdr(vm, x))
            put_name(vm, fbrl__xt_hdr(vm, x));
        else
            fbrl__puts(vm, "(not set)");
    } else if ((h->kind == K_CONST || h->kind == K_VALUE) && fbrl__addr_ok(vm, h->body, CELL)) {
        fbrl_cell x;
        memcpy(&x, (void *)h->body, sizeof x);
        fbrl__puts(vm, " = ");
        put_num(vm, x);
    }
    if (h->flags & FI)
        fbrl__puts(vm, " (immediate)");
    fbrl__puts(vm, "\n");
}

static int env_query(fbrl_vm *vm, const char *s, size_t n)
{
    static const struct {
        const char *name;
        int kind;
    } q[] = {
        {"/COUNTED-STRING", 1},
        {"/HOLD", 2},
        {"/PAD", 3},
        {"ADDRESS-UNIT-BITS", 4},
        {"FLOORED", 5},
        {"MAX-CHAR", 6},
        {"MAX-N", 7},
        {"MAX-U", 8},
        {"MAX-D", 9},
        {"MAX-UD", 10},
        {"RETURN-STACK-CELLS", 11},
        {"STACK-CELLS", 12},
        {"FLOATING-STACK", 13},
        {"MAX-FLOAT", 14},
        {"#LOCALS", 16},
        {"WORDLISTS", 17},
        /* Forth-94 word-set queries (obsolescent, still asked by test suites) */
        {"CORE", 15},
        {"CORE-EXT", 15},
        {"DOUBLE", 15},
        {"EXCEPTION", 15},
        {"EXCEPTION-EXT", 15},
        {"FACILITY", 15},
        {"FLOATING", 15},
        {"FLOATING-EXT", 15},
        {"STRING", 15},
        {"TOOLS", 15},
    };
    const fbrl_ucell umax = ~(fbrl_ucell)0;
    for (size_t i = 0; i < sizeof q / sizeof q[0]; i++) {
        if (strlen(q[i].name) != n)
            continue;
        size_t j = 0;
        while (j < n && (s[j] == q[i].name[j] || (s[j] >= 'a' && s[j] <= 'z' && s[j] - 32 == q[i].name[j])))
            j++;
        if (j != n)
            continue;
        int r = 0;
        switch (q[i].kind) {
        case 1: r = push(vm, 255); break;
        case 2: r = push(vm, FBRL_HOLDSIZE); break;
        case 3: r = push(vm, FBRL_PADSIZE); break;
        case 4: r = push(vm, 8); break;
        case 5: r = push(vm, -1); break;
        case 6: r = push(vm, 255); break;
        case 7: r = push(vm, (fbrl_cell)(umax >> 1)); break;
        case 8: r = push(vm, (fbrl_cell)umax); break;
        case 9:
            r = push(vm, -1);
            if (!r)
                r = push(vm, (fbrl_cell)(umax >> 1));
            break;
        case 10:
            r = push(vm, -1);
            if (!r)
                r = push(vm, -1);
            break;
        case 11: r = push(vm, vm->rs_end - vm->rs0); break;
        case 12: r = push(vm, vm->ds_end - vm->ds0); break;
        case 13: r = push(vm, vm->fs_end - vm->fs0); break;
        case 14: r = fpush(vm, 1.7976931348623157e308); break;
        case 15: r = push(vm, -1); break;
        case 16: r = push(vm, FBRL_NLOCALS); break;
        case 17: r = push(vm, FBRL_WL_MAX); break;
        }
        return r ? r : push(vm, -1);
    }
    return push(vm, 0);
}

static int name_is(const char *p, size_t n, const char *w)
{
    size_t k = strlen(w);
    if (n != k)
        return 0;
    for (size_t i = 0; i < n; i++) {
        char c = p[i];
        if (c >= 'a' && c <= 'z')
            c = (char)(c - 32);
        if (c != w[i])
            return 0;
    }
    return 1;
}

/* Skip words up to the [ELSE] (if else_ok) or [THEN] matching this level, across lines. */
static int skip_conditional(fbrl_vm *vm, int else_ok)
{
    int level = 0;
    for (;;) {
        const char *p;
        size_t n;
        fbrl__parse_name(vm, &p, &n);
        if (n == 0) {
            int r = fbrl__refill(vm);
            if (r < 0)
                return r;
            if (r == 0)
                return fbrl__throw_msg(vm, FBRL_THROW_BRACKET_IF, "[IF] without [THEN]");
            continue;
        }
        if (name_is(p, n, "[IF]"))
            level++;
        else if (name_is(p, n, "[THEN]")) {
            if (level-- == 0)
                return 0;
        } else if (name_is(p, n, "[ELSE]") && level == 0 && else_ok)
            return 0;
    }
}

int fbrl__w_parse(fbrl_vm *vm, int op)
{
    const char *p;
    size_t n;
    fbrl_cell xt, v;
    fbrl_hdr *h;
    double f;
    int r, found;
    switch (op) {
    case OP_TO:
    case OP_IS:
    case OP_ACTIONOF:
        if (op == OP_TO && vm->nlocals && *vm->state) { /* TO a local (locals.c) */
            fbrl_cell in = *vm->toin;
            fbrl__parse_name(vm, &p, &n);
            int k = fbrl__local_index(vm, p, n);
            if (k >= 0)
                return fbrl__compile_local(vm, k, 1);
            *vm->toin = in;
        }
        if ((r = parse_word_xt(vm, &xt, &h)))
            return r;
        if (op == OP_TO) {
            int k = h->kind;
            if (k != K_VALUE && k != K_2VALUE && k != K_FVALUE)
                return fbrl__throw_msg(vm, FBRL_THROW_BAD_NAME_ARG, "TO needs a VALUE, 2VALUE or FVALUE");
            if (*vm->state)
                return back(vm, k == K_VALUE ? OP_PTOVAL : k == K_2VALUE ? OP_PTO2VAL : OP_PTOFVAL, h->body);
            if (!fbrl__addr_ok(vm, h->body, 2 * CELL))
                return FBRL_THROW_BAD_ADDRESS;
            if (k == K_FVALUE) {
                if ((r = fpop(vm, &f)))
                    return r;
                memcpy((void *)h->body, &f, sizeof f);
            } else if (k == K_VALUE) {
                if ((r = pop(vm, &v)))
                    return r;
                memcpy((void *)h->body, &v, sizeof v);
            } else {
                if ((r = need(vm, 2)))
                    return r;
                memcpy((void *)h->body, vm->sp - 1, sizeof v);
                memcpy((void *)(h->body + CELL), vm->sp - 2, sizeof v);
                vm->sp -= 2;
            }
            return 0;
        }
        if (h->kind != K_DEFER)
            return fbrl__throw_msg(vm, FBRL_THROW_BAD_NAME_ARG, "IS and ACTION-OF need a DEFERred word");
        if (*vm->state) {
            if ((r = fbrl__compile_lit(vm, xt)))
                return r;
            return fbrl__emit(vm, op == OP_IS ? OP_DEFERSTORE : OP_DEFERFETCH);
        }
        if (!fbrl__addr_ok(vm, h->body, CELL))
            return FBRL_THROW_BAD_ADDRESS;
        if (op == OP_IS) {
            if ((r = pop(vm, &v)))
                return r;
            memcpy((void *)h->body, &v, sizeof v);
            return 0;
        }
        memcpy(&v, (void *)h->body, sizeof v);
        return push(vm, v);
    case OP_DEFERFETCH:
    case OP_DEFERSTORE:
        if ((r = pop(vm, &xt)))
            return r;
        h = fbrl__xt_hdr(vm, xt);
        if (!h || h->kind != K_DEFER)
            return fbrl__throw_msg(vm, FBRL_THROW_UNSUPPORTED, "not a DEFERred word");
        if (!fbrl__addr_ok(vm, h->body, CELL))
            return FBRL_THROW_BAD_ADDRESS;
        if (op == OP_DEFERSTORE) {
            if ((r = pop(vm, &v)))
                return r;
            memcpy((void *)h->body, &v, sizeof v);
            return 0;
        }
        memcpy(&v, (void *)h->body, sizeof v);
        return push(vm, v);
    case OP_POSTPONE:
        if ((r = parse_word_xt(vm, &xt, &h)))
            return r;
        if (h->flags & FS) { /* its compilation semantics, even if run between [ ] */
            if ((r = fbrl__compile_lit(vm, xt)))
                return r;
            return fbrl__emit(vm, OP_COMPSEM);
        }
        if (h->flags & FI)
            return fbrl__compile_xt(vm, xt);
        if ((r = fbrl__compile_lit(vm, xt)))
            return r;
        return fbrl__emit(vm, OP_COMPILECOMMA);
    case OP_BCOMPILE:
        if ((r = parse_word_xt(vm, &xt, &h)))
            return r;
        return fbrl__compile_xt(vm, xt);
    case OP_BTICK:
        if ((r = parse_word_xt(vm, &xt, &h)))
            return r;
        return fbrl__compile_lit(vm, xt);
    case OP_TICK:
        if ((r = parse_word_xt(vm, &xt, &h)))
            return r;
        return push(vm, xt);
    case OP_BCHAR:
    case OP_CHAR:
        fbrl__parse_name(vm, &p, &n);
        if (n == 0)
            return FBRL_THROW_NO_NAME;
        return op == OP_CHAR ? push(vm, (unsigned char)p[0]) : fbrl__compile_lit(vm, (unsigned char)p[0]);
    case OP_PAREN: return paren_comment(vm);
    case OP_BACKSLASH:
    case OP_SHEBANG:
        if (vm->nsrc)
            *vm->toin = (fbrl_cell)fbrl__src(vm)->len;
        return 0;
    case OP_DOTPAREN:
        if ((r = parse_quoted(vm, ')', &p, &n)))
            return r;
        fbrl__write(vm, p, n);
        return 0;
    case OP_DOTQUOTE:
        if ((r = parse_quoted(vm, '"', &p, &n)))
            return r;
        if (*vm->state == 0) {
            fbrl__write(vm, p, n);
            return 0;
        }
        if ((r = fbrl__compile_str(vm, OP_SLIT, p, n)))
            return r;
        return fbrl__emit(vm, OP_TYPE);
    case OP_SQUOTE:
        if ((r = parse_quoted(vm, '"', &p, &n)))
            return r;
        return string_literal(vm, p, n);
    case OP_SBQUOTE: {
        char b[FBRL_LINE_MAX];
        if ((r = parse_escaped(vm, b, sizeof b, &n)))
            return r;
        return string_literal(vm, b, n);
    }
    case OP_CQUOTE: {
        char b[256];
        if ((r = parse_quoted(vm, '"', &p, &n)))
            return r;
        if (n > 255)
            return FBRL_THROW_PARSED_OVERFLOW;
        b[0] = (char)n;
        memcpy(b + 1, p, n);
        return fbrl__compile_str(vm, OP_CSLIT, b, n + 1);
    }
    case OP_ABORTQ:
        if ((r = parse_quoted(vm, '"', &p, &n)))
            return r;
        return fbrl__compile_str(vm, OP_PABORTQ, p, n);
    case OP_PARSE:
        if ((r = pop(vm, &v)))
            return r;
        fbrl__parse(vm, (char)v, &p, &n, &found);
        if ((r = push(vm, (fbrl_cell)p)))
            return r;
        return push(vm, (fbrl_cell)n);
    case OP_PARSENAME:
        fbrl__parse_name(vm, &p, &n);
        if ((r = push(vm, (fbrl_cell)p)))
            return r;
        return push(vm, (fbrl_cell)n);
    case OP_WORD: {
        if ((r = pop(vm, &v)))
            return r;
        char c = (char)v;
        if (vm->nsrc) {
            fbrl_src *s = fbrl__src(vm);
            size_t i = (size_t)(*vm->toin < 0 ? 0 : *vm->toin);
            if (i > s->len)
                i = s->len;
            while (i < s->len && (s->buf[i] == c || (c == ' ' && (unsigned char)s->buf[i] < ' ')))
                i++;
            *vm->toin = (fbrl_cell)i;
        }
        fbrl__parse(vm, c, &p, &n, &found);
        if (n > 255)
            return FBRL_THROW_PARSED_OVERFLOW;
        vm->wordbuf[0] = (char)n;
        memmove(vm->wordbuf + 1, p, n);
        vm->wordbuf[n + 1] = ' ';
        return push(vm, (fbrl_cell)vm->wordbuf);
    }
    case OP_FIND: {
        if ((r = need(vm, 1)))
            return r;
        v = vm->sp[-1];
        if (!fbrl__addr_ok(vm, v, 1))
            return FBRL_THROW_BAD_ADDRESS;
        n = *(unsigned char *)v;
        if (!fbrl__addr_ok(vm, v, (fbrl_cell)n + 1))
            return FBRL_THROW_BAD_ADDRESS;
        int i = fbrl__find(vm, (const char *)v + 1, n);
        if (i < 0)
            return push(vm, 0);
        vm->sp[-1] = FBRL_XT_BASE + i;
        return push(vm, (HDR(vm, i)->flags & FI) ? 1 : -1);
    }
    case OP_LITERAL:
        if ((r = pop(vm, &v)))
            return r;
        return fbrl__compile_lit(vm, v);
    case OP_TWOLITERAL:
        if ((r = need(vm, 2)))
            return r;
        vm->sp -= 2;
        if ((r = fbrl__compile_lit(vm, vm->sp[0])))
            return r;
        return fbrl__compile_lit(vm, vm->sp[1]);
    case OP_SLITERAL:
        if ((r = pop_str(vm, &p, &n)))
            return r;
        return fbrl__compile_str(vm, OP_SLIT, p, n);
    case OP_FLITERAL:
        if ((r = fpop(vm, &f)))
            return r;
        return fbrl__compile_flit(vm, f);
    case OP_COMPILECOMMA:
        if ((r = pop(vm, &xt)))
            return r;
        return fbrl__compile_xt(vm, xt);
    case OP_IMMEDIATE:
        if (vm->nwords == HDR_ROM) /* no word in RAM (a primitive's header is in flash) */
            return FBRL_THROW_UNSUPPORTED;
        HDR(vm, vm->nwords - 1)->flags |= FI;
        return 0;
    case OP_TONUMBER: {
        if ((r = need(vm, 4)))
            return r;
        fbrl_cell a = vm->sp[-2], u = vm->sp[-1];
        fbrl_ucell lo = U(vm->sp[-4]), hi = U(vm->sp[-3]);
        if (u < 0)
            return FBRL_THROW_BAD_NUMBER;
        if (u && !fbrl__addr_ok(vm, a, u))
            return FBRL_THROW_BAD_ADDRESS;
        if (*vm->base < 2 || *vm->base > 36)
            return FBRL_THROW_BAD_NUMBER;
        size_t k = u ? fbrl__to_number((const char *)a, (size_t)u, *vm->base, &lo, &hi) : 0;
        vm->sp[-4] = (fbrl_cell)lo;
        vm->sp[-3] = (fbrl_cell)hi;
        vm->sp[-2] = a + (fbrl_cell)k;
        vm->sp[-1] = u - (fbrl_cell)k;
        return 0;
    }
    case OP_SEE:
        if ((r = parse_word_xt(vm, &xt, &h)))
            return r;
        see(vm, h);
        return 0;
    case OP_HELP:
        if ((r = parse_word_xt(vm, &xt, &h)) == FBRL_THROW_NO_NAME) { /* no name after HELP: say how */
            fbrl__puts(vm, "HELP name shows what a word does and its stack effect, e.g. HELP MOV;\n"
                           "WORDS lists every word (TAB at the prompt completes a name).\n");
            return 0;
        }
        if (r)
            return r;
        put_name(vm, h);
#ifdef FBRL_NO_HELP
        fbrl__puts(vm, ": this build has no HELP texts (docs/glossary.md has them)\n");
#else
        fbrl__puts(vm, " ");
        fbrl__puts(vm, h->stack);
        fbrl__puts(vm, h->stack[0] ? " " : "");
        fbrl__puts(vm, h->help);
        fbrl__puts(vm, "\n");
#endif
        return 0;
    case OP_INCLUDE:
    case OP_REQUIRE:
        fbrl__parse_name(vm, &p, &n);
        if (n == 0)
            return fbrl__throw_msg(vm, FBRL_THROW_NO_FILE, "file name expected");
        {
            char name[FBRL_PATH_MAX];
            if (n >= sizeof name)
                return FBRL_THROW_NO_FILE;
            memcpy(name, p, n); /* the line buffer is reused by the nested source */
            return vm->nest_included(vm, name, n, op == OP_REQUIRE);
        }
    case OP_REFILL:
        r = fbrl__refill(vm);
        if (r < 0)
            return r;
        return push(vm, r ? -1 : 0);
    case OP_ENVQ:
        if ((r = pop_str(vm, &p, &n)))
            return r;
        return env_query(vm, p, n);
    case OP_BIF:
        if ((r = pop(vm, &v)))
            return r;
        return v ? 0 : skip_conditional(vm, 1);
    case OP_BELSE: return skip_conditional(vm, 0);
    case OP_BTHEN: return 0;
    case OP_BDEFINED:
    case OP_BUNDEFINED:
        fbrl__parse_name(vm, &p, &n);
        found = fbrl__find(vm, p, n) >= 0;
        return push(vm, (op == OP_BDEFINED) == found ? -1 : 0);
    case OP_SAVEINPUT: {
        const fbrl_src *s = vm->nsrc ? fbrl__src(vm) : NULL;
        if (vm->ds_end - vm->sp < 4)
            return FBRL_THROW_STACK_OVERFLOW;
        *vm->sp++ = *vm->toin;
        *vm->sp++ = s ? (fbrl_cell)s->line : 0;
        *vm->sp++ = s ? s->id : 0;
        *vm->sp++ = 3;
        return 0;
    }
    case OP_RESTOREINPUT: {
        const fbrl_src *s = vm->nsrc ? fbrl__src(vm) : NULL;
        if ((r = pop(vm, &v)))
            return r;
        if (v < 0 || vm->sp - vm->ds0 < v)
            return FBRL_THROW_STACK_UNDERFLOW;
        vm->sp -= v;
        if (v == 3 && s && vm->sp[2] == s->id && vm->sp[1] != (fbrl_cell)s->line && s->kind == SRC_FILE &&
            vm->sp[1] > 0 && fbrl__src_goto_line(vm, (unsigned long)vm->sp[1]) != 0)
            return push(vm, -1); /* a file source goes back to the saved line */
        if (v != 3 || !s || vm->sp[2] != s->id || vm->sp[1] != (fbrl_cell)s->line || vm->sp[0] < 0 ||
            (size_t)vm->sp[0] > s->len)
            return push(vm, -1);
        *vm->toin = vm->sp[0];
        return push(vm, 0);
    }
    case OP_LATESTXT:
        if (vm->nwords == 0)
            return FBRL_THROW_UNSUPPORTED;
        return push(vm, (fbrl_cell)(FBRL_XT_BASE + vm->nwords - 1));
    case OP_TOBODY:
        if ((r = pop(vm, &xt)))
            return r;
        h = fbrl__xt_hdr(vm, xt);
        if (!h || h->kind == K_PRIM || h->kind == K_COLON || h->kind == K_CFUNC || h->kind == K_MARKER)
            return FBRL_THROW_TO_BODY;
        return push(vm, h->body);
    }
    return FBRL_THROW_UNSUPPORTED;
}
