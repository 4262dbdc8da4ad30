/* SPDX-License-Identifier: MIT */
/* run.c - the inner interpreter: token-threaded code.
 *
 * A code cell is either an opcode (< OP__END, see ops.def) or an execution token
 * (FBRL_XT_BASE + header index). Colon definitions are called with OP_CALL + body
 * address, so a call costs one validated jump. Any cell sequence is safe to run:
 * every operand that leaves the code (jumps, addresses, xts) is checked.
 *
 * Speed: with GCC or Clang each primitive ends in its own indirect jump through a
 * table of label addresses ("computed goto", a GNU extension, confined to this
 * function; define FBRL_NO_CGOTO or configure with -DFBRL_PORTABLE_DISPATCH=ON for
 * the portable switch). The top of the data stack and of the float stack live in
 * locals (tos, ftos) that the compiler keeps in registers; the stacks in memory hold
 * the rest. Each primitive checks the depth it needs; the compiler (dict.c) fuses
 * common pairs (a literal and an operator, a comparison and a branch) into one op.
 *
 * Stack representation inside fbrl__run: with depth d, the d-1 lower cells are at
 * ds0[0 .. d-2], the top is in tos, and sp = ds0 + d - 1 (the slot the top would be
 * stored in). With d = 0, sp = ds0 - 1: the layout keeps a spare cell there, so
 * SAVE (which stores tos at *sp) needs no special case. Outside fbrl__run,
 * vm->sp follows the usual convention (all cells in memory, next free slot). The
 * float stack works the same way with fp, ftos and fs0.
 *
 * Every case carries its stack comment, as pForth's do: the words' own from ops.def, and
 * for the compiler's internal ops what they take and leave ("lit", "target": cells inline). */
#include <math.h>
#include <string.h>
#include "atomic.h"
#include "vm_internal.h"
#include "words.h"

#if (defined(__GNUC__) || defined(__clang__)) && !defined(FBRL_NO_CGOTO)
#define FBRL_CGOTO 1
#else
#define FBRL_CGOTO 0
#endif

#define SAVE() (*sp = tos, vm->sp = sp + 1, *fp = ftos, vm->fp = fp + 1, vm->rp = rp)
#define LOAD() (sp = vm->sp - 1, tos = *sp, fp = vm->fp - 1, ftos = *fp, rp = vm->rp, SPANS())
/* the data region's end moved (a helper ran): the address checks' limits */
#define SPANS()                                                                                  \
    (lim.span[1] = (fbrl_ucell)(vm->data_hi - vm->data_lo) - 1, lim.span[2] = lim.span[1] - 1, \
     lim.span[4] = lim.span[1] - 3, lim.span[8] = lim.span[1] - 7, lim.span[16] = lim.span[1] - 15)
#define THROW(c)       \
    do {               \
        code = (c);    \
        goto do_throw; \
    } while (0)
/* What every check compares with, worked out once per fbrl__run (the stacks) or after each
 * helper (the data region's end, which only a helper moves): a check is one compare with a
 * value the compiler keeps at hand, not a sum worked out again in every primitive. */
typedef struct run_limits {
    fbrl_cell *need[7], *room[7];   /* data stack: the lowest sp holding n cells; sp must be below room[n] to push n */
    fbrl_cell *rneed[7], *rroom[7]; /* return stack: rp at least rneed[n] to pop n, at most rroom[n] to push n */
    double *fneed[4], *froom[4];    /* float stack, as the data stack */
    fbrl_ucell span[17];            /* span[n] (n = 1, 2, 4, 8, 16): the highest offset from data_lo an n-byte access may start at */
    fbrl_ucell code_cells;          /* cells from data_lo to the end of the block: where code may be */
} run_limits;
/* depth checks: NEED(n) at least n cells, ROOM(n) space for n more */
/* (each error has its own label, so the hot path does not set up a throw code) */
#define NEED(n)              \
    if (sp < lim.need[(n)]) \
    goto e_underflow
#define ROOM(n)               \
    if (sp >= lim.room[(n)]) \
    goto e_overflow
#define RNEED(n)               \
    if (rp < lim.rneed[(n)]) \
    goto e_r_underflow
#define RROOM(n)               \
    if (rp > lim.rroom[(n)]) \
    goto e_r_overflow
#define FNEED(n)               \
    if (fp < lim.fneed[(n)]) \
    goto e_f_underflow
#define FROOM(n)                \
    if (fp >= lim.froom[(n)]) \
    goto e_f_overflow
#define CHK(a, n)                     \
    if (!fbrl__addr_ok(vm, (a), (n))) \
    goto e_address
/* the same for a constant n of 1, 2, 4, 8 or 16 bytes */
#define CHKC(a, n)                                  \
    if ((fbrl_ucell)(a) - (fbrl_ucell)vm->data_lo > lim.span[(n)]) \
    goto e_address
/* A jump target: inside the block from data_lo, and cell-aligned. Rotated right by the
 * cell's bits, an unaligned offset is as large as an offset past the end: one compare. */
#define CELL_SHIFT (sizeof(fbrl_cell) == 8 ? 3 : 2)
#define ROTR(x) (((x) >> CELL_SHIFT) | ((x) << (CELL_BITS - CELL_SHIFT)))
#define CODE_OK(t) (ROTR((fbrl_ucell)(t) - (fbrl_ucell)vm->data_lo) < lim.code_cells)
#define JUMP(t)                     \
    do {                            \
        fbrl_cell t_ = (t);         \
        if (!CODE_OK(t_))           \
            goto e_address;         \
        ip = (const fbrl_cell *)t_; \
    } while (0)
#define CALLC(expr)        \
    do {                   \
        SAVE();            \
        code = (expr);     \
        LOAD();            \
        STEPWORDS();       \
        if (code)          \
            goto do_throw; \
    } while (0)
/* fbrl_vm_interrupt() is honoured wherever a program can loop or recurse */
#define POLL()                                                     \
    if (fbrl_load_rlx(&vm->interrupt) && fbrl__take_interrupt(vm)) \
        THROW(FBRL_THROW_INTERRUPT);
/* A colon definition starts: POLL, and a step hook (debug.c) may stop it there. */
#define ENTER(body)                             \
    if (fbrl_load_rlx(&vm->interrupt)) {        \
        if (fbrl__take_interrupt(vm))           \
            THROW(FBRL_THROW_INTERRUPT);        \
        if (vm->step_fn && !vm->in_step) {      \
            SAVE();                             \
            vm->ip = ip;                        \
            int stop_ = fbrl__step(vm, (body)); \
            LOAD();                             \
            STEPWORDS();                        \
            if (stop_)                          \
                THROW(stop_);                   \
        }                                       \
    }
/* T is the top cell, S the second, S3 the third ... */
#define T  tos
#define S  sp[-1]
#define S3 sp[-2]
#define S4 sp[-3]
#define S5 sp[-4]
#define S6 sp[-5]
#define PUSH(x)             \
    do {                    \
        fbrl_cell v_ = (x); \
        sp[0] = tos; sp += 1;        \
        tos = v_;           \
    } while (0)
#define DROP1() (tos = *--sp)
#define FPUSH(x)         \
    do {                 \
        double f_ = (x); \
        fp[0] = ftos; fp += 1;    \
        ftos = f_;       \
    } while (0)
#define FDROP1() (ftos = *--fp)
#define U(x)     ((fbrl_ucell)(x))
#define FLAG(c)  ((c) ? (fbrl_cell)-1 : 0)
#define FCELLS   ((sizeof(double) + sizeof(fbrl_cell) - 1) / sizeof(fbrl_cell))
/* float results follow IEEE 754 (infinities, NaN, signed zero): the safety check is at
 * the controller boundary instead (robot words refuse a value that is not finite) */
#define FRES(r, bad) \
    do {             \
        (void)(bad); \
        ftos = (r);  \
    } while (0)
/* binary float op: r1 = second, r2 = top; the result replaces both */
#define FBIN(expr, bad)                \
    do {                               \
        double r1 = fp[-1], r2 = ftos; \
        (void)r1;                      \
        (void)r2;                      \
        FRES(expr, bad);               \
        fp--;                          \
    } while (0)

/* The word hook (fbrl_vm_word_hook, a debugger's single steps) sees each word before it
 * runs. With computed goto the dispatch goes through tab: optab, or while the hook is set
 * steptab, whose every entry (xts too: entry OP__END) leads to the hook first; so the hot
 * path has no test of its own. The portable switch tests a flag. Looked at again after
 * each C call and step hook (which may set or clear the word hook). */
#if FBRL_CGOTO
#define CASE(id) L_##id:
#define DEFAULT
#define DISPATCH()               \
    do {                         \
        if (U(w) < OP__END)      \
            goto *tab[w];        \
        goto *tab[OP__END];      \
    } while (0)
#define DISPATCH_PLAIN()    \
    do {                    \
        if (U(w) < OP__END) \
            goto *optab[w]; \
        goto execute_xt;    \
    } while (0)
#define NEXT        \
    do {            \
        w = ip[0];  \
        ip += 1;    \
        DISPATCH(); \
    } while (0)
#if FBRL_WORD_HOOK
#define STEPWORDS() (tab = vm->word_fn && !vm->in_step ? steptab : optab)
#else
#define STEPWORDS() ((void)0)
#endif
#else
#define CASE(id)         case OP_##id:
#define DEFAULT          default:
#define DISPATCH()       goto dispatch
#define DISPATCH_PLAIN() goto dispatch
#define NEXT             continue
#define STEPWORDS()      (stepping = FBRL_WORD_HOOK && vm->word_fn && !vm->in_step)
#endif

static fbrl_cell ld(fbrl_cell a)
{
    fbrl_cell v;
    memcpy(&v, (const void *)a, sizeof v);
    return v;
}
static void st(fbrl_cell a, fbrl_cell v) { memcpy((void *)a, &v, sizeof v); }
static double ldf(fbrl_cell a)
{
    double v;
    memcpy(&v, (const void *)a, sizeof v);
    return v;
}
static void stf(fbrl_cell a, double v) { memcpy((void *)a, &v, sizeof v); }

static int floordiv(fbrl_cell a, fbrl_cell b, fbrl_cell *q, fbrl_cell *r)
{
    if (b == 0)
        return FBRL_THROW_DIV_ZERO;
    if (b == -1) {
        *q = (fbrl_cell)(0 - U(a));
        *r = 0;
        return 0;
    }
    fbrl_cell qq = a / b, rr = a % b;
    if (rr != 0 && ((rr < 0) != (b < 0))) {
        qq--;
        rr += b;
    }
    *q = qq;
    *r = rr;
    return 0;
}

#if FBRL_CGOTO
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpedantic"
#endif
int fbrl__run(fbrl_vm *vm, fbrl_cell xt)
{
    fbrl_cell *sp, *rp, tos;
    double *fp, ftos;
    fbrl_cell *const ds0 = vm->ds0, *const dse = vm->ds_end;
    fbrl_cell *const rs0 = vm->rs0, *const rse = vm->rs_end;
    double *const fs0 = vm->fs0, *const fse = vm->fs_end;
    run_limits lim;
    const fbrl_cell *ip = (const fbrl_cell *)vm->guard_addr; /* the HALT cell */
    fbrl_cell w = xt, entry, a, b;
    fbrl_ucell ua, ub;
    fbrl_cell o1, o2; /* out-parameters: a, b and ua, ub never have their address taken */
    fbrl_ucell uo1, uo2;
    double fa;
    int code = 0;
#if FBRL_CGOTO
    static const void *const optab[OP__END + 1] = {
#define OP(id, name, flags, stack, help) &&L_##id,
#include "ops.def"
#undef OP
        &&execute_xt};
#if FBRL_WORD_HOOK
    static const void *const steptab[OP__END + 1] = {[0 ... OP__END] = &&step_word};
#endif
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
    /* the table's address in a register of its own (GCC reloaded it from the stack on the
     * hot paths of some primitives); r15 is callee-saved, so C helpers leave it alone */
    register const void *const *tab __asm__("r15") = optab;
#else
    const void *const *tab = optab;
#endif
#else
    int stepping = 0;
#endif

    if (vm->nest >= 64)
        return FBRL_THROW_RSTACK_OVERFLOW;
    for (int n = 0; n < 7; n++) {
        lim.need[n] = ds0 + n - 1;
        lim.room[n] = dse - n;
        lim.rneed[n] = rs0 + n;
        lim.rroom[n] = rse - n;
    }
    for (int n = 0; n < 4; n++) {
        lim.fneed[n] = fs0 + n - 1;
        lim.froom[n] = fse - n;
    }
    lim.code_cells = (fbrl_ucell)(vm->mem_end - vm->data_lo) / (fbrl_ucell)CELL;
    LOAD();
    STEPWORDS();
    entry = rp - rs0;
    vm->nest++;
    if (vm->resume_ip) { /* task.c: a task's slice goes on where it stopped (xt: the word to run again) */
        ip = vm->resume_ip;
        vm->resume_ip = NULL;
        entry = 0;
        DISPATCH_PLAIN();
    }
    goto execute_xt;

    for (;;) {
        w = *ip++;
#if FBRL_CGOTO
        DISPATCH();
        {
#else
        if (stepping)
            goto step_word;
    dispatch:
        switch ((fbrl_ucell)w) {
#endif
            /* BAD ( -- ) an invalid cell: throws */
            CASE(BAD)
            THROW(fbrl__throw_msg(vm, FBRL_THROW_BAD_ADDRESS, "invalid instruction (corrupted code?)"));
            /* HALT ( -- ) ends the run */
            CASE(HALT) code = 0;
            goto out; /* (so code is dead in the hot path) */
            /* CATCHEND ( -- 0 ) CATCH returns normally */
            CASE(CATCHEND)
            if (vm->handler != rp - rs0 || rp - rs0 < 5)
                THROW(FBRL_THROW_RSTACK_IMBALANCE);
            rp -= 5;
            vm->handler = (rp[3] >= 0 && rp[3] <= rp - rs0) ? rp[3] : 0;
            JUMP(rp[0]);
            ROOM(1);
            PUSH(0);
            NEXT;
            /* LIT ( -- x ) x inline */
            CASE(LIT) ROOM(1);
            PUSH(*ip++);
            NEXT;
            /* FLIT ( F: -- r ) r inline */
            CASE(FLIT) FROOM(1);
            fp[0] = ftos;
            fp += 1;
            memcpy(&ftos, ip, sizeof(double));
            ip += FCELLS;
            NEXT;
            /* CALL ( -- ) R: ( -- ip ) body inline */
            CASE(CALL) ENTER(*ip);
            RROOM(1);
            a = *ip++;
            rp[0] = (fbrl_cell)ip; rp += 1;
            JUMP(a);
            NEXT;
            /* EXIT ( -- ) R: ( ip -- ), EXITBR ( -- ) R: ( ip -- ) a BRANCH that lands on ; */
            CASE(EXIT) CASE(EXITBR) RNEED(1);
            JUMP(*--rp);
            NEXT;
            /* BRANCH ( -- ) target inline */
            CASE(BRANCH) POLL();
            JUMP(*ip);
            NEXT;
            /* ZBRANCH ( flag -- ) target inline */
            CASE(ZBRANCH)
            NEED(1);
            a = tos;
            DROP1();
            if (a == 0) {
                POLL();
                JUMP(*ip);
            } else
                ip++;
            NEXT;
            /* PQDO ( limit start -- ) R: ( -- leave limit index | ) */
            CASE(PQDO)
            NEED(2);
            if (S == T) {
                sp -= 2;
                tos = *sp;
                JUMP(*ip);
                NEXT;
            }
            goto pdo;
            /* PDO ( limit start -- ) R: ( -- leave limit index ) */
            CASE(PDO)
            NEED(2);
        pdo:
            RROOM(3);
            rp[0] = *ip++;
            rp[1] = S;
            rp[2] = T;
            rp += 3;
            sp -= 2;
            tos = *sp;
            NEXT;
            /* PLOOP ( -- ) R: ( leave limit index -- leave limit index' | ) */
            CASE(PLOOP)
            RNEED(3);
            a = (fbrl_cell)(U(rp[-1]) + 1);
            if (a == rp[-2]) {
                rp -= 3;
                ip++;
            } else {
                POLL();
                rp[-1] = a;
                JUMP(*ip);
            }
            NEXT;
            /* LITPPLOOP ( -- ) n inline, as n +LOOP */
            CASE(LITPPLOOP)
            RNEED(3);
            ub = U(*ip++);
            goto pploop;
            /* DUPPPLOOP ( n -- n ) as DUP +LOOP */
            CASE(DUPPPLOOP)
            NEED(1);
            RNEED(3);
            ub = U(tos);
            goto pploop;
            /* PPLOOP ( n -- ) R: ( leave limit index -- leave limit index' | ) */
            CASE(PPLOOP)
            NEED(1);
            RNEED(3);
            ub = U(tos);
            DROP1();
        pploop: /* ub: the increment */
            ua = U(rp[-1]) - U(rp[-2]);
            if ((fbrl_cell)((ua ^ (ua + ub)) & (ua ^ ub)) < 0) {
                rp -= 3;
                ip++;
            } else {
                POLL();
                rp[-1] = (fbrl_cell)(U(rp[-1]) + ub);
                JUMP(*ip);
            }
            NEXT;
            /* I ( -- n ) */
            CASE(I) RNEED(1);
            ROOM(1);
            PUSH(rp[-1]);
            NEXT;
            /* J ( -- n ) */
            CASE(J) RNEED(4);
            ROOM(1);
            PUSH(rp[-4]);
            NEXT;
            /* LEAVE ( -- ) ( R: loop-sys -- ) */
            CASE(LEAVE) RNEED(3);
            a = rp[-3];
            rp -= 3;
            JUMP(a);
            NEXT;
            /* UNLOOP ( -- ) ( R: loop-sys -- ) */
            CASE(UNLOOP) RNEED(3);
            rp -= 3;
            NEXT;
            /* SLIT ( -- c-addr u ) string inline, CSLIT ( -- c-addr ) counted string inline,
             * PABORTQ ( i*x flag -- | i*x ) message inline */
            CASE(SLIT) CASE(CSLIT) CASE(PABORTQ)
            {
                fbrl_ucell n = U(*ip++), skip = (n / U(CELL) + 1) * U(CELL);
                fbrl_cell s = (fbrl_cell)ip;
                if (n > 65536)
                    THROW(FBRL_THROW_BAD_ADDRESS);
                JUMP((fbrl_cell)(U(s) + skip));
                if (w == OP_PABORTQ) {
                    NEED(1);
                    a = tos;
                    DROP1();
                    if (a) {
                        char m[sizeof vm->throw_msg];
                        size_t k = n < sizeof m - 1 ? (size_t)n : sizeof m - 1;
                        CHK(s, (fbrl_cell)k);
                        memcpy(m, (const void *)s, k);
                        m[k] = 0;
                        THROW(fbrl__throw_msg(vm, FBRL_THROW_ABORTQ, m));
                    }
                } else if (w == OP_CSLIT) {
                    ROOM(1);
                    PUSH(s);
                } else {
                    ROOM(2);
                    PUSH(s);
                    PUSH((fbrl_cell)n);
                }
                NEXT;
            }
            /* DOESSET ( -- ) the latest word runs the code after it */
            CASE(DOESSET)
            {
                fbrl_hdr *h = vm->nwords ? HDR(vm, vm->nwords - 1) : NULL;
                if (!h || h->kind != K_CREATE)
                    THROW(fbrl__throw_msg(vm, FBRL_THROW_TO_BODY, "DOES> needs a CREATEd word"));
                H_DOES(h) = (fbrl_cell)ip;
                RNEED(1);
                JUMP(*--rp);
                NEXT;
            }
            /* POF ( x1 x2 -- | x1 ) target inline */
            CASE(POF)
            NEED(2);
            if (S == T) {
                sp -= 2;
                tos = *sp;
                ip++;
            } else {
                DROP1();
                JUMP(*ip);
            }
            NEXT;
            /* COMPSEM ( i*x -- j*x ) a word's compilation semantics */
            CASE(COMPSEM)
            { /* run a state-smart word as if compiling */
                fbrl_cell saved = *vm->state;
                NEED(1);
                a = tos;
                DROP1();
                *vm->state = -1;
                SAVE();
                code = fbrl__run(vm, a);
                LOAD();
                if (*vm->state == -1)
                    *vm->state = saved;
                if (code)
                    goto do_throw;
                NEXT;
            }
            /* PTOVAL ( x -- ) value's body inline */
            CASE(PTOVAL) NEED(1);
            a = *ip++;
            CHKC(a, CELL);
            st(a, tos);
            DROP1();
            NEXT;
            /* PTO2VAL ( x1 x2 -- ) body inline */
            CASE(PTO2VAL) NEED(2);
            a = *ip++;
            CHKC(a, 2 * CELL);
            st(a, T);
            st(a + CELL, S);
            sp -= 2;
            tos = *sp;
            NEXT;
            /* PTOFVAL ( F: r -- ) body inline */
            CASE(PTOFVAL) FNEED(1);
            a = *ip++;
            CHKC(a, (fbrl_cell)sizeof(double));
            stf(a, ftos);
            FDROP1();
            NEXT;

            /* superinstructions (vm.c fuses them): a literal operand, or a branch target */
            /* LITPLUS ( n -- n+lit ) */
            CASE(LITPLUS) NEED(1);
            T = (fbrl_cell)(U(T) + U(*ip++));
            NEXT;
            /* LITMINUS ( n -- n-lit ) */
            CASE(LITMINUS) NEED(1);
            T = (fbrl_cell)(U(T) - U(*ip++));
            NEXT;
            /* LITSTAR ( n -- n*lit ) */
            CASE(LITSTAR) NEED(1);
            T = (fbrl_cell)(U(T) * U(*ip++));
            NEXT;
            /* LITAND ( x -- x&lit ) */
            CASE(LITAND) NEED(1);
            T &= *ip++;
            NEXT;
            /* LITEQ ( x -- flag ) */
            CASE(LITEQ) NEED(1);
            T = FLAG(T == *ip);
            ip++;
            NEXT;
            /* LITNE ( x -- flag ) */
            CASE(LITNE) NEED(1);
            T = FLAG(T != *ip);
            ip++;
            NEXT;
            /* LITLT ( n -- flag ) */
            CASE(LITLT) NEED(1);
            T = FLAG(T < *ip);
            ip++;
            NEXT;
            /* LITGT ( n -- flag ) */
            CASE(LITGT) NEED(1);
            T = FLAG(T > *ip);
            ip++;
            NEXT;
            /* LITFETCH ( -- x ) lit @ */
            CASE(LITFETCH) ROOM(1);
            a = *ip++;
            CHKC(a, CELL);
            PUSH(ld(a));
            NEXT;
            /* PICK2 ( x2 x1 x0 -- x2 x1 x0 x2 ) */
            CASE(PICK2) NEED(3);
            ROOM(1);
            PUSH(S3);
            NEXT;
            /* OVERPLUS ( n1 n2 -- n1 n1+n2 ) */
            CASE(OVERPLUS) NEED(2);
            T = (fbrl_cell)(U(T) + U(S));
            NEXT;
            /* IPLUS ( n -- n+i ) */
            CASE(IPLUS) RNEED(1);
            NEED(1);
            T = (fbrl_cell)(U(T) + U(rp[-1]));
            NEXT;
            /* CELLPLUSFETCH ( a-addr -- x ) CELL+ @ */
            CASE(CELLPLUSFETCH) NEED(1);
            a = (fbrl_cell)(U(T) + U(CELL));
            CHKC(a, CELL);
            T = ld(a);
            NEXT;
            /* DUPFETCH ( a-addr -- a-addr x ) */
            CASE(DUPFETCH) NEED(1);
            ROOM(1);
            CHKC(T, CELL);
            sp[0] = tos; sp += 1;
            T = ld(T);
            NEXT;
            /* EQZBR ( x1 x2 -- ) = 0BRANCH */
            CASE(EQZBR) NEED(2);
            a = S == T;
            sp--;
            tos = *--sp;
            goto zbr_a;
            /* NEZBR ( x1 x2 -- ) <> 0BRANCH */
            CASE(NEZBR) NEED(2);
            a = S != T;
            sp--;
            tos = *--sp;
            goto zbr_a;
            /* LTZBR ( n1 n2 -- ) < 0BRANCH */
            CASE(LTZBR) NEED(2);
            a = S < T;
            sp--;
            tos = *--sp;
            goto zbr_a;
            /* GTZBR ( n1 n2 -- ) > 0BRANCH */
            CASE(GTZBR) NEED(2);
            a = S > T;
            sp--;
            tos = *--sp;
            goto zbr_a;
            /* ZEQZBR ( x -- ) 0= 0BRANCH */
            CASE(ZEQZBR) NEED(1);
            a = T == 0;
            DROP1();
            goto zbr_a;
            /* LITEQZBR ( x -- ) lit = 0BRANCH */
            CASE(LITEQZBR) NEED(1);
            a = T == *ip++;
            DROP1();
            goto zbr_a;
            /* LITNEZBR ( x -- ) lit <> 0BRANCH */
            CASE(LITNEZBR) NEED(1);
            a = T != *ip++;
            DROP1();
            goto zbr_a;
            /* LITLTZBR ( n -- ) lit < 0BRANCH */
            CASE(LITLTZBR) NEED(1);
            a = T < *ip++;
            DROP1();
            goto zbr_a;
            /* LITGTZBR ( n -- ) lit > 0BRANCH */
            CASE(LITGTZBR) NEED(1);
            a = T > *ip++;
            DROP1();
            goto zbr_a;
            /* TWODUPEQZBR ( x1 x2 -- x1 x2 ) 2DUP = 0BRANCH */
            CASE(TWODUPEQZBR) NEED(2);
            a = S == T;
            goto zbr_a;
            /* TWODUPNEZBR ( x1 x2 -- x1 x2 ) 2DUP <> 0BRANCH */
            CASE(TWODUPNEZBR) NEED(2);
            a = S != T;
            goto zbr_a;
            /* TWODUPLTZBR ( n1 n2 -- n1 n2 ) 2DUP < 0BRANCH */
            CASE(TWODUPLTZBR) NEED(2);
            a = S < T;
            goto zbr_a;
            /* TWODUPGTZBR ( n1 n2 -- n1 n2 ) 2DUP > 0BRANCH */
            CASE(TWODUPGTZBR) NEED(2);
            a = S > T;
            goto zbr_a;
            /* DUPLITEQZBR ( x -- x ) DUP lit = 0BRANCH */
            CASE(DUPLITEQZBR) NEED(1);
            a = T == *ip++;
            goto zbr_a;
            /* DUPLITNEZBR ( x -- x ) DUP lit <> 0BRANCH */
            CASE(DUPLITNEZBR) NEED(1);
            a = T != *ip++;
            goto zbr_a;
            /* DUPLITLTZBR ( n -- n ) DUP lit < 0BRANCH */
            CASE(DUPLITLTZBR) NEED(1);
            a = T < *ip++;
            goto zbr_a;
            /* DUPLITGTZBR ( n -- n ) DUP lit > 0BRANCH */
            CASE(DUPLITGTZBR) NEED(1);
            a = T > *ip++;
        zbr_a:
            if (a == 0) {
                POLL();
                JUMP(*ip);
            } else
                ip++;
            NEXT;

            /* DROPLIT ( x -- lit ) */
            CASE(DROPLIT) NEED(1);
            T = *ip++;
            NEXT;
            /* IFETCH ( -- x ) I @ */
            CASE(IFETCH) RNEED(1);
            ROOM(1);
            a = rp[-1];
            CHKC(a, CELL);
            PUSH(ld(a));
            NEXT;
            /* ICFETCH ( -- char ) I C@ */
            CASE(ICFETCH) RNEED(1);
            ROOM(1);
            a = rp[-1];
            CHKC(a, 1);
            PUSH(*(unsigned char *)a);
            NEXT;
            /* ITWOFETCH ( -- x1 x2 ) I 2@ */
            CASE(ITWOFETCH) RNEED(1);
            ROOM(2);
            a = rp[-1];
            CHKC(a, 2 * CELL);
            sp[0] = tos;
            sp[1] = ld(a + CELL);
            sp += 2;
            T = ld(a);
            NEXT;
            /* ISTORE ( x -- ) I ! */
            CASE(ISTORE) NEED(1);
            RNEED(1);
            a = rp[-1];
            CHKC(a, CELL);
            st(a, T);
            DROP1();
            NEXT;
            /* ICSTORE ( char -- ) I C! */
            CASE(ICSTORE) NEED(1);
            RNEED(1);
            a = rp[-1];
            CHKC(a, 1);
            *(unsigned char *)a = (unsigned char)T;
            DROP1();
            NEXT;
            /* ITWOSTORE ( x1 x2 -- ) I 2! */
            CASE(ITWOSTORE) NEED(2);
            RNEED(1);
            a = rp[-1];
            CHKC(a, 2 * CELL);
            st(a, T);
            st(a + CELL, S);
            sp -= 2;
            tos = *sp;
            NEXT;
            /* LITPLUSFETCH ( addr -- x ) lit + @ */
            CASE(LITPLUSFETCH) NEED(1);
            a = (fbrl_cell)(U(T) + U(*ip++));
            CHKC(a, CELL);
            T = ld(a);
            NEXT;
            /* LITPLUSCFETCH ( addr -- char ) lit + C@ */
            CASE(LITPLUSCFETCH) NEED(1);
            a = (fbrl_cell)(U(T) + U(*ip++));
            CHKC(a, 1);
            T = *(unsigned char *)a;
            NEXT;
            /* LITPLUSSTORE ( x addr -- ) lit + ! */
            CASE(LITPLUSSTORE) NEED(2);
            a = (fbrl_cell)(U(T) + U(*ip++));
            CHKC(a, CELL);
            st(a, S);
            sp -= 2;
            tos = *sp;
            NEXT;
            /* LITPLUSCSTORE ( char addr -- ) lit + C! */
            CASE(LITPLUSCSTORE) NEED(2);
            a = (fbrl_cell)(U(T) + U(*ip++));
            CHKC(a, 1);
            *(unsigned char *)a = (unsigned char)S;
            sp -= 2;
            tos = *sp;
            NEXT;
            /* OVERFETCH ( a-addr x -- a-addr x y ) OVER @ */
            CASE(OVERFETCH) NEED(2);
            ROOM(1);
            a = S;
            CHKC(a, CELL);
            PUSH(ld(a));
            NEXT;
            /* PICK2FETCH ( a-addr x1 x2 -- a-addr x1 x2 y ) 2 PICK @ */
            CASE(PICK2FETCH) NEED(3);
            ROOM(1);
            a = S3;
            CHKC(a, CELL);
            PUSH(ld(a));
            NEXT;
            /* ISTOF ( -- ) ( F: -- r ) R: ( loop-sys -- loop-sys ) I S>F (the data stack's
             * room asked as I asks it, so an error is the same) */
            CASE(ISTOF) RNEED(1);
            ROOM(1);
            FROOM(1);
            FPUSH((double)rp[-1]);
            NEXT;
            /* FOVERFOVER ( F: r1 r2 -- r1 r2 r1 r2 ) FOVER FOVER */
            CASE(FOVERFOVER) FNEED(2);
            FROOM(2);
            fp[0] = ftos; /* r2 stays in ftos */
            fp[1] = fp[-1];
            fp += 2;
            NEXT;
            /* FDUPFSTAR ( F: r -- r*r ) FDUP F* */
            CASE(FDUPFSTAR) FNEED(1);
            FROOM(1);
            ftos = ftos * ftos;
            NEXT;
            /* IJ ( -- n1 n2 ) R: ( loop-sys1 loop-sys2 -- loop-sys1 loop-sys2 ) I J: I's checks,
             * its push, then J's, so that an error leaves what the two words leave */
            CASE(IJ) RNEED(1);
            ROOM(1);
            PUSH(rp[-1]);
            RNEED(4);
            ROOM(1);
            PUSH(rp[-4]);
            NEXT;
            /* STARPLUS ( n1 n2 n3 -- n1+n2*n3 ) */
            CASE(STARPLUS) NEED(3);
            T = (fbrl_cell)(U(S3) + U(S) * U(T));
            sp -= 2;
            NEXT;

            /* stack */
            /* DUP ( x -- x x ) */
            CASE(DUP) NEED(1);
            ROOM(1);
            sp[0] = tos; sp += 1;
            NEXT;
            /* DROP ( x -- ) */
            CASE(DROP) NEED(1);
            DROP1();
            NEXT;
            /* SWAP ( a b -- b a ) */
            CASE(SWAP) NEED(2);
            a = T;
            T = S;
            S = a;
            NEXT;
            /* OVER ( a b -- a b a ) */
            CASE(OVER) NEED(2);
            ROOM(1);
            PUSH(S);
            NEXT;
            /* ROT ( a b c -- b c a ) */
            CASE(ROT) NEED(3);
            a = S3;
            S3 = S;
            S = T;
            T = a;
            NEXT;
            /* -ROT ( a b c -- c a b ) */
            CASE(MROT) NEED(3);
            a = T;
            T = S;
            S = S3;
            S3 = a;
            NEXT;
            /* NIP ( a b -- b ) */
            CASE(NIP) NEED(2);
            sp--;
            NEXT;
            /* TUCK ( a b -- b a b ) */
            CASE(TUCK) NEED(2);
            ROOM(1);
            a = S;
            S = T;
            sp[0] = a; sp += 1;
            NEXT;
            /* PICK ( xu ... x0 u -- xu ... x0 xu ) */
            CASE(PICK)
            NEED(1);
            ua = U(T);
            if (ua >= U(sp - ds0))
                THROW(FBRL_THROW_STACK_UNDERFLOW);
            T = sp[-1 - (fbrl_cell)ua];
            NEXT;
            /* ROLL ( xu ... x0 u -- xu-1 ... x0 xu ) */
            CASE(ROLL)
            NEED(1);
            ua = U(T);
            if (ua >= U(sp - ds0))
                THROW(FBRL_THROW_STACK_UNDERFLOW);
            a = sp[-1 - (fbrl_cell)ua];
            memmove(sp - 1 - ua, sp - ua, (size_t)ua * sizeof(fbrl_cell));
            sp--;
            T = a;
            NEXT;
            /* ?DUP ( x -- 0 | x x ) */
            CASE(QDUP) NEED(1);
            if (T) {
                ROOM(1);
                sp[0] = tos; sp += 1;
            }
            NEXT;
            /* 2DUP ( a b -- a b a b ) */
            CASE(TWODUP) NEED(2);
            ROOM(2);
            a = S;
            sp[0] = T;
            sp[1] = a;
            sp += 2;
            NEXT;
            /* 2DROP ( a b -- ) */
            CASE(TWODROP) NEED(2);
            sp -= 2;
            tos = *sp;
            NEXT;
            /* 2SWAP ( a b c d -- c d a b ) */
            CASE(TWOSWAP) NEED(4);
            a = S4;
            b = S3;
            S4 = S;
            S3 = T;
            S = a;
            T = b;
            NEXT;
            /* 2OVER ( a b c d -- a b c d a b ) */
            CASE(TWOOVER) NEED(4);
            ROOM(2);
            a = S4;
            b = S3;
            sp[0] = T;
            sp[1] = a;
            sp += 2;
            T = b;
            NEXT;
            /* 2ROT ( a b c d e f -- c d e f a b ) */
            CASE(TWOROT)
            NEED(6);
            a = S6;
            b = S5;
            memmove(sp - 5, sp - 3, 3 * sizeof(fbrl_cell));
            sp[-2] = tos;
            S = a;
            T = b;
            NEXT;
            /* 2NIP ( a b c d -- c d ) */
            CASE(TWONIP) NEED(4);
            S4 = S;
            sp -= 2;
            NEXT;
            /* DEPTH ( -- n ) */
            CASE(DEPTH) ROOM(1);
            a = sp - ds0 + 1;
            PUSH(a);
            NEXT;
            /* >R ( x -- ) ( R: -- x ) */
            CASE(TOR) NEED(1);
            RROOM(1);
            rp[0] = tos; rp += 1;
            DROP1();
            NEXT;
            /* R> ( -- x ) ( R: x -- ) */
            CASE(RFROM) RNEED(1);
            ROOM(1);
            PUSH(*--rp);
            NEXT;
            /* R@ ( -- x ) ( R: x -- x ) */
            CASE(RFETCH) RNEED(1);
            ROOM(1);
            PUSH(rp[-1]);
            NEXT;
            /* 2>R ( a b -- ) ( R: -- a b ) */
            CASE(TWOTOR) NEED(2);
            RROOM(2);
            rp[0] = S;
            rp[1] = T;
            rp += 2;
            sp -= 2;
            tos = *sp;
            NEXT;
            /* 2R> ( -- a b ) ( R: a b -- ) */
            CASE(TWORFROM) RNEED(2);
            ROOM(2);
            PUSH(rp[-2]);
            PUSH(rp[-1]);
            rp -= 2;
            NEXT;
            /* 2R@ ( -- a b ) ( R: a b -- a b ) */
            CASE(TWORFETCH) RNEED(2);
            ROOM(2);
            PUSH(rp[-2]);
            PUSH(rp[-1]);
            NEXT;
            /* RDROP ( R: x -- ) */
            CASE(RDROP) RNEED(1);
            rp--;
            NEXT;

            /* arithmetic */
            /* + ( a b -- a+b ) */
            CASE(PLUS) NEED(2);
            T = (fbrl_cell)(U(S) + U(T));
            sp--;
            NEXT;
            /* - ( a b -- a-b ) */
            CASE(MINUS) NEED(2);
            T = (fbrl_cell)(U(S) - U(T));
            sp--;
            NEXT;
            /* * ( a b -- a*b ) */
            CASE(STAR) NEED(2);
            T = (fbrl_cell)(U(S) * U(T));
            sp--;
            NEXT;
            /* / ( a b -- q ) */
            CASE(SLASH) NEED(2);
            if ((code = floordiv(S, T, &o1, &o2)))
                goto do_throw;
            T = o1;
            sp--;
            NEXT;
            /* MOD ( a b -- r ) */
            CASE(MOD) NEED(2);
            if ((code = floordiv(S, T, &o1, &o2)))
                goto do_throw;
            T = o2;
            sp--;
            NEXT;
            /* /MOD ( a b -- r q ) */
            CASE(SLASHMOD) NEED(2);
            if ((code = floordiv(S, T, &o1, &o2)))
                goto do_throw;
            S = o2;
            T = o1;
            NEXT;
            /* STARSLASH ( a b c -- a*b/c ), STARSLASHMOD ( a b c -- r q ) */
            CASE(STARSLASH) CASE(STARSLASHMOD) NEED(3);
            if ((code = fbrl__starslash(S3, S, T, &o1, &o2)))
                goto do_throw;
            if (w == OP_STARSLASH) {
                sp -= 2;
                T = o1;
            } else {
                sp--;
                S = o2;
                T = o1;
            }
            NEXT;
            /* 1+ ( n -- n+1 ) */
            CASE(ONEPLUS) NEED(1);
            T = (fbrl_cell)(U(T) + 1);
            NEXT;
            /* 1- ( n -- n-1 ) */
            CASE(ONEMINUS) NEED(1);
            T = (fbrl_cell)(U(T) - 1);
            NEXT;
            /* 2* ( x -- x*2 ) */
            CASE(TWOSTAR) NEED(1);
            T = (fbrl_cell)(U(T) << 1);
            NEXT;
            /* 2/ ( x -- x/2 ) */
            CASE(TWOSLASH) NEED(1);
            T = T < 0 ? (fbrl_cell) ~(~U(T) >> 1) : (fbrl_cell)(U(T) >> 1);
            NEXT;
            /* NEGATE ( n -- -n ) */
            CASE(NEGATE) NEED(1);
            T = (fbrl_cell)(0 - U(T));
            NEXT;
            /* ABS ( n -- u ) */
            CASE(ABS) NEED(1);
            if (T < 0)
                T = (fbrl_cell)(0 - U(T));
            NEXT;
            /* MIN ( a b -- min ) */
            CASE(MIN) NEED(2);
            if (S < T)
                T = S;
            sp--;
            NEXT;
            /* MAX ( a b -- max ) */
            CASE(MAX) NEED(2);
            if (S > T)
                T = S;
            sp--;
            NEXT;
            /* AND ( a b -- a&b ) */
            CASE(AND) NEED(2);
            T &= S;
            sp--;
            NEXT;
            /* OR ( a b -- a|b ) */
            CASE(OR) NEED(2);
            T |= S;
            sp--;
            NEXT;
            /* XOR ( a b -- a^b ) */
            CASE(XOR) NEED(2);
            T ^= S;
            sp--;
            NEXT;
            /* INVERT ( x -- ~x ) */
            CASE(INVERT) NEED(1);
            T = ~T;
            NEXT;
            /* LSHIFT ( x u -- x<<u ) */
            CASE(LSHIFT) NEED(2);
            T = U(T) >= (fbrl_ucell)CELL_BITS ? 0 : (fbrl_cell)(U(S) << U(T));
            sp--;
            NEXT;
            /* RSHIFT ( x u -- x>>u ) */
            CASE(RSHIFT) NEED(2);
            T = U(T) >= (fbrl_ucell)CELL_BITS ? 0 : (fbrl_cell)(U(S) >> U(T));
            sp--;
            NEXT;
            /* M* ( n1 n2 -- d ) */
            CASE(MSTAR) NEED(2);
            fbrl__mstar(S, T, &o1, &o2);
            S = o1;
            T = o2;
            NEXT;
            /* UM* ( u1 u2 -- ud ) */
            CASE(UMSTAR) NEED(2);
            fbrl__umul(U(S), U(T), &uo1, &uo2);
            S = (fbrl_cell)uo2;
            T = (fbrl_cell)uo1;
            NEXT;
            /* UM/MOD ( ud u -- ur uq ) */
            CASE(UMSLASHMOD)
            NEED(3);
            if (T == 0)
                THROW(FBRL_THROW_DIV_ZERO);
            if (U(S) >= U(T))
                THROW(FBRL_THROW_RESULT_RANGE);
            fbrl__udiv(U(S), U(S3), U(T), &uo1, &uo2);
            sp--;
            S = (fbrl_cell)uo2;
            T = (fbrl_cell)uo1;
            NEXT;
            /* FM/MOD ( d n -- r q ), SM/REM ( d n -- r q ) */
            CASE(FMSLASHMOD) CASE(SMSLASHREM) NEED(3);
            if ((code = fbrl__dsdiv(S3, S, T, w == OP_FMSLASHMOD, &o1, &o2)))
                goto do_throw;
            sp--;
            S = o2;
            T = o1;
            NEXT;
            /* CELL+ ( a -- a' ) */
            CASE(CELLPLUS) NEED(1);
            T = (fbrl_cell)(U(T) + U(CELL));
            NEXT;
            /* CELLS ( n -- n*cell ) */
            CASE(CELLS) NEED(1);
            T = (fbrl_cell)(U(T) * U(CELL));
            NEXT;
            /* CHAR+ ( a -- a+1 ) */
            CASE(CHARPLUS) NEED(1);
            T = (fbrl_cell)(U(T) + 1);
            NEXT;
            /* CHARS ( n -- n ) */
            CASE(CHARS) NEED(1);
            NEXT;
            /* = ( a b -- flag ) */
            CASE(EQ) NEED(2);
            T = FLAG(S == T);
            sp--;
            NEXT;
            /* <> ( a b -- flag ) */
            CASE(NE) NEED(2);
            T = FLAG(S != T);
            sp--;
            NEXT;
            /* < ( a b -- flag ) */
            CASE(LT) NEED(2);
            T = FLAG(S < T);
            sp--;
            NEXT;
            /* > ( a b -- flag ) */
            CASE(GT) NEED(2);
            T = FLAG(S > T);
            sp--;
            NEXT;
            /* U< ( u1 u2 -- flag ) */
            CASE(ULT) NEED(2);
            T = FLAG(U(S) < U(T));
            sp--;
            NEXT;
            /* U> ( u1 u2 -- flag ) */
            CASE(UGT) NEED(2);
            T = FLAG(U(S) > U(T));
            sp--;
            NEXT;
            /* 0= ( x -- flag ) */
            CASE(ZEQ) NEED(1);
            T = FLAG(T == 0);
            NEXT;
            /* 0<> ( x -- flag ) */
            CASE(ZNE) NEED(1);
            T = FLAG(T != 0);
            NEXT;
            /* 0< ( n -- flag ) */
            CASE(ZLT) NEED(1);
            T = FLAG(T < 0);
            NEXT;
            /* 0> ( n -- flag ) */
            CASE(ZGT) NEED(1);
            T = FLAG(T > 0);
            NEXT;
            /* WITHIN ( x lo hi -- flag ) */
            CASE(WITHIN) NEED(3);
            a = FLAG(U(S3) - U(S) < U(T) - U(S));
            sp -= 2;
            T = a;
            NEXT;
            /* TRUE ( -- -1 ) */
            CASE(TRUE) ROOM(1);
            PUSH(-1);
            NEXT;
            /* FALSE ( -- 0 ) */
            CASE(FALSE) ROOM(1);
            PUSH(0);
            NEXT;
            /* BL ( -- 32 ) */
            CASE(BL) ROOM(1);
            PUSH(' ');
            NEXT;

            /* doubles: low cell below, high cell on top */
            /* S>D ( n -- d ) */
            CASE(STOD) NEED(1);
            ROOM(1);
            PUSH(T < 0 ? -1 : 0);
            NEXT;
            /* D>S ( d -- n ) */
            CASE(DTOS) NEED(2);
            DROP1();
            NEXT;
            /* D+ ( d1 d2 -- d ), D- ( d1 d2 -- d ) */
            CASE(DPLUS) CASE(DMINUS)
            {
                NEED(4);
                fbrl_ucell al = U(S4), ah = U(S3), bl = U(S), bh = U(T);
                if (w == OP_DMINUS) {
                    bl = ~bl + 1;
                    bh = ~bh + (bl == 0);
                }
                fbrl_ucell l = al + bl;
                S4 = (fbrl_cell)l;
                T = (fbrl_cell)(ah + bh + (l < al));
                sp -= 2;
                NEXT;
            }
            /* DNEGATE ( d -- -d ) */
            CASE(DNEGATE) NEED(2);
            S = (fbrl_cell)(~U(S) + 1);
            T = (fbrl_cell)(~U(T) + (S == 0));
            NEXT;
            /* DABS ( d -- ud ) */
            CASE(DABS) NEED(2);
            if (T < 0) {
                S = (fbrl_cell)(~U(S) + 1);
                T = (fbrl_cell)(~U(T) + (S == 0));
            }
            NEXT;
            /* D= ( d1 d2 -- flag ) */
            CASE(DEQ) NEED(4);
            a = FLAG(S4 == S && S3 == T);
            sp -= 3;
            T = a;
            NEXT;
            /* D< ( d1 d2 -- flag ) */
            CASE(DLT) NEED(4);
            a = FLAG(S3 < T || (S3 == T && U(S4) < U(S)));
            sp -= 3;
            T = a;
            NEXT;
            /* DU< ( ud1 ud2 -- flag ) */
            CASE(DULT) NEED(4);
            a = FLAG(U(S3) < U(T) || (S3 == T && U(S4) < U(S)));
            sp -= 3;
            T = a;
            NEXT;
            /* D0= ( d -- flag ) */
            CASE(DZEQ) NEED(2);
            a = FLAG(S == 0 && T == 0);
            sp--;
            T = a;
            NEXT;
            /* D0< ( d -- flag ) */
            CASE(DZLT) NEED(2);
            a = FLAG(T < 0);
            sp--;
            T = a;
            NEXT;
            /* D2* ( d -- d*2 ) */
            CASE(DTWOSTAR) NEED(2);
            T = (fbrl_cell)((U(T) << 1) | (U(S) >> (CELL_BITS - 1)));
            S = (fbrl_cell)(U(S) << 1);
            NEXT;
            /* D2/ ( d -- d/2 ) */
            CASE(DTWOSLASH) NEED(2);
            S = (fbrl_cell)((U(S) >> 1) | (U(T) << (CELL_BITS - 1)));
            T = T < 0 ? (fbrl_cell) ~(~U(T) >> 1) : (fbrl_cell)(U(T) >> 1);
            NEXT;
            /* DMAX ( d1 d2 -- d ), DMIN ( d1 d2 -- d ) */
            CASE(DMAX) CASE(DMIN)
            {
                NEED(4);
                int lt = S3 < T || (S3 == T && U(S4) < U(S));
                if ((w == OP_DMAX) == lt) {
                    S4 = S;
                    S3 = T;
                }
                sp -= 2;
                tos = *sp;
                NEXT;
            }
            /* M+ ( d n -- d' ) */
            CASE(MPLUS)
            {
                NEED(3);
                fbrl_ucell l = U(S3) + U(T);
                a = (fbrl_cell)(U(S) + (T < 0 ? ~(fbrl_ucell)0 : 0) + (l < U(S3)));
                S3 = (fbrl_cell)l;
                sp--;
                T = a;
                NEXT;
            }
            /* MSTARSLASH ( d n +n -- d' ) */
            CASE(MSTARSLASH)
            NEED(4);
            if ((code = fbrl__mstarslash(&S4, &S3, S, T)))
                goto do_throw;
            sp -= 2;
            tos = *sp;
            NEXT;

            /* memory */
            /* @ ( a -- x ) */
            CASE(FETCH) NEED(1);
            CHKC(T, CELL);
            T = ld(T);
            NEXT;
            /* ! ( x a -- ) */
            CASE(STORE) NEED(2);
            CHKC(T, CELL);
            st(T, S);
            sp -= 2;
            tos = *sp;
            NEXT;
            /* C@ ( a -- c ) */
            CASE(CFETCH) NEED(1);
            CHKC(T, 1);
            T = *(unsigned char *)T;
            NEXT;
            /* C! ( c a -- ) */
            CASE(CSTORE) NEED(2);
            CHKC(T, 1);
            *(unsigned char *)T = (unsigned char)S;
            sp -= 2;
            tos = *sp;
            NEXT;
            /* +! ( n a -- ) */
            CASE(PLUSSTORE) NEED(2);
            CHKC(T, CELL);
            st(T, (fbrl_cell)(U(ld(T)) + U(S)));
            sp -= 2;
            tos = *sp;
            NEXT;
            /* 2@ ( a -- x1 x2 ) */
            CASE(TWOFETCH) NEED(1);
            ROOM(1);
            CHKC(T, 2 * CELL);
            a = T;
            sp[0] = ld(a + CELL); sp += 1;
            T = ld(a);
            NEXT;
            /* 2! ( x1 x2 a -- ) */
            CASE(TWOSTORE) NEED(3);
            CHKC(T, 2 * CELL);
            st(T, S);
            st(T + CELL, S3);
            sp -= 3;
            tos = *sp;
            NEXT;
            /* W@ ( a -- u ) */
            CASE(WFETCH)
            {
                uint16_t v;
                NEED(1);
                CHKC(T, 2);
                memcpy(&v, (void *)T, 2);
                T = v;
                NEXT;
            }
            /* W! ( u a -- ) */
            CASE(WSTORE)
            {
                uint16_t v;
                NEED(2);
                CHKC(T, 2);
                v = (uint16_t)S;
                memcpy((void *)T, &v, 2);
                sp -= 2;
                tos = *sp;
                NEXT;
            }
            /* , ( x -- ) */
            CASE(COMMA) NEED(1);
            if ((code = fbrl__emit(vm, T)))
                goto do_throw;
            DROP1();
            NEXT;
            /* C, ( c -- ) */
            CASE(CCOMMA)
            NEED(1);
            if ((code = fbrl__allot(vm, 1)))
                goto do_throw;
            vm->here[-1] = (unsigned char)tos;
            DROP1();
            NEXT;
            /* ALLOT ( n -- ) */
            CASE(ALLOT) NEED(1);
            if ((code = fbrl__allot(vm, T)))
                goto do_throw;
            DROP1();
            NEXT;
            /* HERE ( -- a ) */
            CASE(HERE) ROOM(1);
            PUSH((fbrl_cell)vm->here);
            vm->peep_end = NULL;
            NEXT;
            /* ALIGN ( -- ) */
            CASE(ALIGN) if ((code = fbrl__align(vm))) goto do_throw;
            NEXT;
            /* ALIGNED ( a -- a' ) */
            CASE(ALIGNED) NEED(1);
            T = (fbrl_cell)((U(T) + U(CELL) - 1) & ~(U(CELL) - 1));
            NEXT;
            /* UNUSED ( -- u ) */
            CASE(UNUSED)
            ROOM(1);
            PUSH((fbrl_cell)((unsigned char *)HDR_LOW(vm) - vm->here));
            NEXT;
            /* PAD ( -- a ) */
            CASE(PAD) ROOM(1);
            PUSH((fbrl_cell)vm->pad);
            NEXT;
            /* FILL ( a u c -- ), ERASE ( a u -- ), BLANK ( a u -- ) */
            CASE(FILL) CASE(ERASE) CASE(BLANK) if (w == OP_FILL)
            {
                NEED(3);
                b = T;
                DROP1();
            }
            else
            {
                NEED(2);
                b = w == OP_BLANK ? ' ' : 0;
            }
            if (T > 0) {
                CHK(S, T);
                memset((void *)S, (int)(unsigned char)b, (size_t)T);
            }
            sp -= 2;
            tos = *sp;
            NEXT;
            /* MOVE ( src dst u -- ), CMOVE ( src dst u -- ), CMOVE> ( src dst u -- ) */
            CASE(MOVE) CASE(CMOVE) CASE(CMOVEUP) NEED(3);
            if (T > 0) {
                CHK(S3, T);
                CHK(S, T);
                if (w == OP_MOVE)
                    memmove((void *)S, (void *)S3, (size_t)T);
                else if (w == OP_CMOVE) {
                    unsigned char *d = (unsigned char *)S;
                    const unsigned char *s = (const unsigned char *)S3;
                    for (fbrl_cell i = 0; i < T; i++)
                        d[i] = s[i];
                } else {
                    unsigned char *d = (unsigned char *)S;
                    const unsigned char *s = (const unsigned char *)S3;
                    for (fbrl_cell i = T; i-- > 0;)
                        d[i] = s[i];
                }
            }
            sp -= 3;
            tos = *sp;
            NEXT;
            /* COUNT ( c-addr -- a u ) */
            CASE(COUNT) NEED(1);
            ROOM(1);
            CHKC(T, 1);
            a = T;
            sp[0] = a + 1; sp += 1;
            T = *(unsigned char *)a;
            NEXT;
            /* COMPARE ( a1 u1 a2 u2 -- n ), SEARCH ( a1 u1 a2 u2 -- a3 u3 flag ), /STRING ( a u n -- a+n u-n ),
             * -TRAILING ( a u -- a u' ) */
            CASE(COMPARE) CASE(SEARCH) CASE(SLASHSTRING) CASE(MTRAILING) CALLC(fbrl__w_string(vm, (int)w));
            NEXT;

            /* compiling words */
            /* IF ( C: -- orig ) ( x -- ) */
            CASE(IF)
            /* ELSE ( C: orig -- orig' ) */
            CASE(ELSE)
            /* THEN ( C: orig -- ) */
            CASE(THEN)
            /* BEGIN ( C: -- dest ) */
            CASE(BEGIN)
            /* UNTIL ( C: dest -- ) ( x -- ) */
            CASE(UNTIL)
            /* AGAIN ( C: dest -- ) */
            CASE(AGAIN)
            /* WHILE ( C: dest -- orig dest ) ( x -- ), REPEAT ( C: orig dest -- ), AHEAD ( C: -- orig ),
             * DO ( C: -- do-sys ) ( limit start -- ), ?DO ( C: -- do-sys ) ( limit start -- ),
             * LOOP ( C: do-sys -- ), +LOOP ( C: do-sys -- ) ( n -- ), RECURSE ( -- ) */
            CASE(WHILE) CASE(REPEAT) CASE(AHEAD) CASE(DO) CASE(QDO) CASE(LOOP) CASE(PLUSLOOP) CASE(RECURSE)
                /* CASE ( C: -- case-sys ), OF ( C: -- of-sys ) ( x1 x2 -- | x1 ), ENDOF ( C: of-sys -- ),
                 * ENDCASE ( C: case-sys -- ) ( x -- ), DOES> ( -- ) ( run: -- a ) */
                CASE(CASE) CASE(OF) CASE(ENDOF) CASE(ENDCASE) CASE(DOES) CALLC(fbrl__w_control(vm, (int)w));
            NEXT;
            /* : ( "name" -- colon-sys ) */
            CASE(COLON) CALLC(fbrl__colon(vm, 0, NULL));
            NEXT;
            /* :NONAME ( -- xt colon-sys ) */
            CASE(NONAME) ROOM(1);
            CALLC(fbrl__colon(vm, 1, &o1));
            PUSH(o1);
            NEXT;
            /* ; ( colon-sys -- ) */
            CASE(SEMI) CALLC(fbrl__semicolon(vm));
            NEXT;
            /* CREATE ( "name" -- ) */
            CASE(CREATE)
            /* VARIABLE ( "name" -- ) */
            CASE(VARIABLE)
            /* 2VARIABLE ( "name" -- ) */
            CASE(TWOVARIABLE)
            /* CONSTANT ( x "name" -- ) */
            CASE(CONSTANT)
            /* 2CONSTANT ( x1 x2 "name" -- ) */
            CASE(TWOCONSTANT)
            /* VALUE ( x "name" -- ) */
            CASE(VALUE)
            /* 2VALUE ( x1 x2 "name" -- ), DEFER ( "name" -- ), BUFFER: ( u "name" -- ), MARKER ( "name" -- ),
             * FVARIABLE ( "name" -- ), FCONSTANT ( "name" -- ) ( F: r -- ) */
            CASE(TWOVALUE) CASE(DEFER) CASE(BUFFERCOLON) CASE(MARKER) CASE(FVARIABLE) CASE(FCONSTANT)
                /* FVALUE ( "name" -- ) ( F: r -- ) */
                CASE(FVALUE) CALLC(fbrl__w_define(vm, (int)w));
            NEXT;
            /* TO ( x "name" -- ) */
            CASE(TO)
            /* IS ( xt "name" -- ) */
            CASE(IS)
            /* ACTION-OF ( "name" -- xt ) */
            CASE(ACTIONOF)
            /* POSTPONE ( "name" -- ) */
            CASE(POSTPONE)
            /* [COMPILE] ( "name" -- ) */
            CASE(BCOMPILE)
            /* ['] ( "name" -- ) */
            CASE(BTICK)
            /* [CHAR] ( "c" -- ), ' ( "name" -- xt ), CHAR ( "c" -- c ), ( ( "text)" -- ), \ ( "text" -- ),
             * #! ( "text" -- ), .( ( "text)" -- ) */
            CASE(BCHAR) CASE(TICK) CASE(CHAR) CASE(PAREN) CASE(BACKSLASH) CASE(SHEBANG) CASE(DOTPAREN)
                /* ." ( "text"" -- ), S" ( "text"" -- a u ), S\" ( "text"" -- a u ), C" ( "text"" -- c-addr ),
                 * ABORT" ( "text"" -- ) ( run: x -- ), PARSE ( c "text<c>" -- a u ) */
                CASE(DOTQUOTE) CASE(SQUOTE) CASE(SBQUOTE) CASE(CQUOTE) CASE(ABORTQ) CASE(PARSE)
                    /* PARSE-NAME ( "name" -- a u ), WORD ( c "text<c>" -- c-addr ),
                     * FIND ( c-addr -- c-addr 0 | xt 1 | xt -1 ), LITERAL ( x -- ), 2LITERAL ( x1 x2 -- ),
                     * SLITERAL ( a u -- ) */
                    CASE(PARSENAME) CASE(WORD) CASE(FIND) CASE(LITERAL) CASE(TWOLITERAL) CASE(SLITERAL)
                        /* FLITERAL ( F: r -- ), COMPILE, ( xt -- ), IMMEDIATE ( -- ),
                         * >NUMBER ( ud a u -- ud' a' u' ), SEE ( "name" -- ), HELP ( "name" -- ) */
                        CASE(FLITERAL) CASE(COMPILECOMMA) CASE(IMMEDIATE) CASE(TONUMBER) CASE(SEE) CASE(HELP)
                            /* INCLUDE ( "file" -- ), REQUIRE ( "file" -- ), REFILL ( -- flag ),
                             * ENVIRONMENT? ( a u -- false | i*x true ), LATESTXT ( -- xt ), >BODY ( xt -- a ) */
                            CASE(INCLUDE) CASE(REQUIRE) CASE(REFILL) CASE(ENVQ) CASE(LATESTXT) CASE(TOBODY)
                                /* DEFER@ ( xt1 -- xt2 ), DEFER! ( xt2 xt1 -- ), [IF] ( flag -- ), [ELSE] ( -- ),
                                 * [THEN] ( -- ) */
                                CASE(DEFERFETCH) CASE(DEFERSTORE) CASE(BIF) CASE(BELSE) CASE(BTHEN)
                                    /* [DEFINED] ( "name" -- flag ), [UNDEFINED] ( "name" -- flag ),
                                     * SAVE-INPUT ( -- x1 x2 x3 3 ), RESTORE-INPUT ( x1 x2 x3 3 -- flag ) */
                                    CASE(BDEFINED) CASE(BUNDEFINED) CASE(SAVEINPUT) CASE(RESTOREINPUT)
                                        CALLC(fbrl__w_parse(vm, (int)w));
            NEXT;
            /* [ ( -- ) */
            CASE(LBRACKET) *vm->state = 0;
            NEXT;
            /* ] ( -- ) */
            CASE(RBRACKET) *vm->state = -1;
            NEXT;
            /* EXECUTE ( i*x xt -- j*x ) */
            CASE(EXECUTE) NEED(1);
            w = tos;
            DROP1();
            goto execute_xt;
            /* STATE ( -- a ) */
            CASE(STATE) ROOM(1);
            PUSH((fbrl_cell)vm->state);
            NEXT;
            /* BASE ( -- a ) */
            CASE(BASE) ROOM(1);
            PUSH((fbrl_cell)vm->base);
            NEXT;
            /* >IN ( -- a ) */
            CASE(TOIN) ROOM(1);
            PUSH((fbrl_cell)vm->toin);
            NEXT;
            /* DECIMAL ( -- ) */
            CASE(DECIMAL) *vm->base = 10;
            NEXT;
            /* HEX ( -- ) */
            CASE(HEX) *vm->base = 16;
            NEXT;
            /* SOURCE ( -- a u ) */
            CASE(SOURCE)
            {
                ROOM(2);
                const fbrl_src *s = vm->nsrc ? &vm->src[vm->nsrc - 1] : NULL;
                PUSH(s ? (fbrl_cell)s->buf : (fbrl_cell)vm->wordbuf);
                PUSH(s ? (fbrl_cell)s->len : 0);
                NEXT;
            }
            /* SOURCE-ID ( -- n ) */
            CASE(SOURCEID) ROOM(1);
            PUSH(vm->nsrc ? vm->src[vm->nsrc - 1].id : 0);
            NEXT;
            /* EVALUATE ( i*x a u -- j*x ) */
            CASE(EVALUATE)
            NEED(2);
            a = S;
            b = T;
            sp -= 2;
            tos = *sp;
            if (b < 0)
                THROW(FBRL_THROW_BAD_NUMBER);
            CHK(a, b);
            CALLC(vm->nest_evaluate(vm, (char *)a, (size_t)b));
            NEXT;
            /* INCLUDED ( a u -- ), REQUIRED ( a u -- ) */
            CASE(INCLUDED) CASE(REQUIRED) NEED(2);
            a = S;
            b = T;
            sp -= 2;
            tos = *sp;
            if (b < 0)
                THROW(FBRL_THROW_BAD_NUMBER);
            CHK(a, b);
            CALLC(vm->nest_included(vm, (const char *)a, (size_t)b, w == OP_REQUIRED));
            NEXT;
            /* QUIT ( -- ) ( R: i*x -- ) */
            CASE(QUIT) THROW(THROW_QUIT);
            /* ABORT ( i*x -- ) */
            CASE(ABORT) THROW(FBRL_THROW_ABORT);
            /* BYE ( -- ) */
            CASE(BYE) vm->bye = 1;
            THROW(THROW_BYE);
            /* CATCH ( i*x xt -- j*x 0 | i*x n ) */
            CASE(CATCH)
            NEED(1);
            RROOM(6);
            w = tos;
            DROP1(); /* the cell below is in memory too (*sp) */
            *fp = ftos;
            rp[0] = (fbrl_cell)ip;
            rp[1] = sp + 1 - ds0;
            rp[2] = fp + 1 - fs0;
            rp[3] = vm->handler;
            rp[4] = vm->lp; /* the locals in use (locals.c) */
            rp += 5;
            vm->handler = rp - rs0;
            ip = (const fbrl_cell *)vm->guard_addr + 1; /* the CATCHEND cell */
            goto execute_xt;
            /* THROW ( k*x n -- k*x | i*x n ) */
            CASE(THROW)
            NEED(1);
            a = tos;
            DROP1();
            if (a == 0)
                NEXT;
            if (a == THROW_BYE)
                a = -1;
            THROW((int)(a < -2000000000 || a > 2000000000 ? FBRL_THROW_BAD_NUMBER : a));

            /* I/O, output, tools, facility: helpers */
            /* EMIT ( c -- ) */
            CASE(EMIT)
            {
                char ch;
                NEED(1);
                ch = (char)tos;
                DROP1();
                fbrl__write(vm, &ch, 1);
                NEXT;
            }
            /* TYPE ( a u -- ) */
            CASE(TYPE)
            NEED(2);
            if (T > 0) {
                CHK(S, T);
                fbrl__write(vm, (const char *)S, (size_t)T);
            }
            sp -= 2;
            tos = *sp;
            NEXT;
            /* CR ( -- ) */
            CASE(CR) fbrl__write(vm, "\n", 1);
            NEXT;
            /* SPACE ( -- ) */
            CASE(SPACE) fbrl__write(vm, " ", 1);
            NEXT;
            /* SPACES ( n -- ) */
            CASE(SPACES) NEED(1);
            a = tos;
            DROP1();
            CALLC(fbrl__spaces(vm, a));
            NEXT;
            /* KEY ( -- c ) */
            CASE(KEY)
            /* KEY? ( -- flag ) */
            CASE(KEYQ)
            /* ACCEPT ( a +n -- +n' ) */
            CASE(ACCEPT)
            /* . ( n -- ) */
            CASE(DOT)
            /* U. ( u -- ) */
            CASE(UDOT)
            /* .R ( n width -- ) */
            CASE(DOTR)
            /* U.R ( u width -- ), D. ( d -- ), D.R ( d width -- ), UD. ( ud -- ), ? ( a -- ), <# ( -- ),
             * # ( ud -- ud' ), #S ( ud -- 0 0 ) */
            CASE(UDOTR) CASE(DDOT) CASE(DDOTR) CASE(UDDOT) CASE(QUESTION) CASE(LTNUM) CASE(NUM) CASE(NUMS)
                /* #> ( xd -- a u ), HOLD ( c -- ), HOLDS ( a u -- ), SIGN ( n -- ), .S ( -- ), DUMP ( a u -- ),
                 * WORDS ( -- ), MS ( u -- ) */
                CASE(NUMGT) CASE(HOLD) CASE(HOLDS) CASE(SIGN) CASE(DOTS) CASE(DUMP) CASE(WORDS) CASE(MS)
                    /* TIME&DATE ( -- sec min hour day month year ), UTIME ( -- ud ), F. ( F: r -- ),
                     * FE. ( F: r -- ), FS. ( F: r -- ), REPRESENT ( a u -- n flag1 flag2 ) ( F: r -- ) */
                    CASE(TIMEDATE) CASE(USECS) CASE(FDOT) CASE(FEDOT) CASE(FSDOT) CASE(REPRESENT)
                        /* >FLOAT ( a u -- flag ) ( F: -- r | ) */
                        CASE(TOFLOAT) CALLC(fbrl__w_io(vm, (int)w));
            NEXT;

            /* floating point */
            /* F+ ( F: r1 r2 -- r ) */
            CASE(FPLUS) FNEED(2);
            FBIN(r1 + r2, 43);
            NEXT;
            /* F- ( F: r1 r2 -- r ) */
            CASE(FMINUS) FNEED(2);
            FBIN(r1 - r2, 43);
            NEXT;
            /* F* ( F: r1 r2 -- r ) */
            CASE(FSTAR) FNEED(2);
            FBIN(r1 * r2, 43);
            NEXT;
            /* F/ ( F: r1 r2 -- r ) */
            CASE(FSLASH) FNEED(2);
            FBIN(r1 / r2, 43);
            NEXT;
            /* FNEGATE ( F: r -- -r ) */
            CASE(FNEGATE) FNEED(1);
            ftos = -ftos;
            NEXT;
            /* FABS ( F: r -- |r| ) */
            CASE(FABS) FNEED(1);
            ftos = fabs(ftos);
            NEXT;
            /* FMIN ( F: r1 r2 -- r ) */
            CASE(FMIN) FNEED(2);
            if (fp[-1] < ftos)
                ftos = fp[-1];
            fp--;
            NEXT;
            /* FMAX ( F: r1 r2 -- r ) */
            CASE(FMAX) FNEED(2);
            if (fp[-1] > ftos)
                ftos = fp[-1];
            fp--;
            NEXT;
            /* FSQRT ( F: r -- sqrt ) */
            CASE(FSQRT) FNEED(1);
            FRES(sqrt(ftos), 46);
            NEXT;
            /* FSIN ( F: rad -- r ) */
            CASE(FSIN) FNEED(1);
            FRES(sin(ftos), 46);
            NEXT;
            /* FCOS ( F: rad -- r ) */
            CASE(FCOS) FNEED(1);
            FRES(cos(ftos), 46);
            NEXT;
#ifndef FBRL_NO_FTRANS
            /* FTAN ( F: rad -- r ) */
            CASE(FTAN) FNEED(1);
            FRES(tan(ftos), 46);
            NEXT;
#endif
            /* FSINCOS ( F: rad -- sin cos ) */
            CASE(FSINCOS) FNEED(1);
            FROOM(1);
            fa = ftos;
            fp[0] = sin(fa); fp += 1;
            ftos = cos(fa);
            NEXT;
#ifndef FBRL_NO_FTRANS
            /* FASIN ( F: r -- rad ) */
            CASE(FASIN) FNEED(1);
            FRES(asin(ftos), 46);
            NEXT;
#endif
            /* FACOS ( F: r -- rad ) */
            CASE(FACOS) FNEED(1);
            FRES(acos(ftos), 46);
            NEXT;
            /* FATAN ( F: r -- rad ) */
            CASE(FATAN) FNEED(1);
            FRES(atan(ftos), 46);
            NEXT;
            /* FATAN2 ( F: y x -- rad ) */
            CASE(FATAN2) FNEED(2);
            FBIN(atan2(r1, r2), 46);
            NEXT;
#ifndef FBRL_NO_FTRANS
            /* FSINH ( F: r -- r' ) */
            CASE(FSINH) FNEED(1);
            FRES(sinh(ftos), 43);
            NEXT;
            /* FCOSH ( F: r -- r' ) */
            CASE(FCOSH) FNEED(1);
            FRES(cosh(ftos), 43);
            NEXT;
            /* FTANH ( F: r -- r' ) */
            CASE(FTANH) FNEED(1);
            FRES(tanh(ftos), 46);
            NEXT;
            /* FASINH ( F: r -- r' ) */
            CASE(FASINH) FNEED(1);
            FRES(asinh(ftos), 46);
            NEXT;
            /* FACOSH ( F: r -- r' ) */
            CASE(FACOSH) FNEED(1);
            FRES(acosh(ftos), 46);
            NEXT;
            /* FATANH ( F: r -- r' ) */
            CASE(FATANH) FNEED(1);
            FRES(atanh(ftos), 46);
            NEXT;
            /* FEXP ( F: r -- e^r ) */
            CASE(FEXP) FNEED(1);
            FRES(exp(ftos), 43);
            NEXT;
            /* FEXPM1 ( F: r -- e^r-1 ) */
            CASE(FEXPM1) FNEED(1);
            FRES(expm1(ftos), 43);
            NEXT;
            /* FLN ( F: r -- ln ) */
            CASE(FLN) FNEED(1);
            FRES(log(ftos), 46);
            NEXT;
            /* FLNP1 ( F: r -- ln(1+r) ) */
            CASE(FLNP1) FNEED(1);
            FRES(log1p(ftos), 46);
            NEXT;
            /* FLOG ( F: r -- log10 ) */
            CASE(FLOG) FNEED(1);
            FRES(log10(ftos), 46);
            NEXT;
            /* FALOG ( F: r -- 10^r ) */
            CASE(FALOG) FNEED(1);
            FRES(pow(10.0, ftos), 43);
            NEXT;
            /* F** ( F: r1 r2 -- r1^r2 ) */
            CASE(FPOW) FNEED(2);
            FBIN(pow(r1, r2), 46);
            NEXT;
#endif
            /* FLOOR ( F: r -- r' ) */
            CASE(FLOOR) FNEED(1);
            ftos = floor(ftos);
            NEXT;
            /* FROUND ( F: r -- r' ) */
            CASE(FROUND) FNEED(1);
            ftos = nearbyint(ftos);
            NEXT;
            /* FTRUNC ( F: r -- r' ) */
            CASE(FTRUNC) FNEED(1);
            ftos = trunc(ftos);
            NEXT;
            /* F0= ( -- flag ) ( F: r -- ) */
            CASE(FZEQ) FNEED(1);
            ROOM(1);
            fa = ftos;
            FDROP1();
            PUSH(FLAG(fa == 0));
            NEXT;
            /* F0< ( -- flag ) ( F: r -- ) */
            CASE(FZLT) FNEED(1);
            ROOM(1);
            fa = ftos;
            FDROP1();
            PUSH(FLAG(fa < 0));
            NEXT;
            /* F0> ( -- flag ) ( F: r -- ) */
            CASE(FZGT) FNEED(1);
            ROOM(1);
            fa = ftos;
            FDROP1();
            PUSH(FLAG(fa > 0));
            NEXT;
            /* F< ( -- flag ) ( F: r1 r2 -- ) */
            CASE(FLT) FNEED(2);
            ROOM(1);
            a = FLAG(fp[-1] < ftos);
            fp -= 2;
            ftos = *fp;
            PUSH(a);
            NEXT;
            /* F> ( -- flag ) ( F: r1 r2 -- ) */
            CASE(FGT) FNEED(2);
            ROOM(1);
            a = FLAG(fp[-1] > ftos);
            fp -= 2;
            ftos = *fp;
            PUSH(a);
            NEXT;
            /* F= ( -- flag ) ( F: r1 r2 -- ) */
            CASE(FEQ) FNEED(2);
            ROOM(1);
            a = FLAG(fp[-1] == ftos);
            fp -= 2;
            ftos = *fp;
            PUSH(a);
            NEXT;
            /* F~ ( -- flag ) ( F: r1 r2 r3 -- ) */
            CASE(FPROX)
            {
                FNEED(3);
                ROOM(1);
                double x = fp[-2], y = fp[-1], e = ftos;
                int r;
                fp -= 3;
                ftos = *fp;
                if (e > 0)
                    r = fabs(x - y) < e;
                else if (e == 0)
                    r = memcmp(&x, &y, sizeof x) == 0;
                else
                    r = fabs(x - y) < -e * (fabs(x) + fabs(y));
                PUSH(FLAG(r));
                NEXT;
            }
            /* F@ ( a -- ) ( F: -- r ), DF@ ( a -- ) ( F: -- r ) */
            CASE(FFETCH) CASE(DFFETCH) NEED(1);
            FROOM(1);
            CHKC(T, (fbrl_cell)sizeof(double));
            FPUSH(ldf(T));
            DROP1();
            NEXT;
            /* F! ( a -- ) ( F: r -- ), DF! ( a -- ) ( F: r -- ) */
            CASE(FSTORE) CASE(DFSTORE) NEED(1);
            FNEED(1);
            CHKC(T, (fbrl_cell)sizeof(double));
            stf(T, ftos);
            DROP1();
            FDROP1();
            NEXT;
            /* SF@ ( a -- ) ( F: -- r ) */
            CASE(SFFETCH)
            {
                float f;
                NEED(1);
                FROOM(1);
                CHKC(T, 4);
                memcpy(&f, (void *)T, 4);
                DROP1();
                FPUSH(f);
                NEXT;
            }
            /* SF! ( a -- ) ( F: r -- ) */
            CASE(SFSTORE)
            {
                float f;
                NEED(1);
                FNEED(1);
                CHKC(T, 4);
                f = (float)ftos;
                memcpy((void *)T, &f, 4);
                DROP1();
                FDROP1();
                NEXT;
            }
            /* FDUP ( F: r -- r r ) */
            CASE(FDUP) FNEED(1);
            FROOM(1);
            fp[0] = ftos; fp += 1;
            NEXT;
            /* FDROP ( F: r -- ) */
            CASE(FDROP) FNEED(1);
            FDROP1();
            NEXT;
            /* FSWAP ( F: r1 r2 -- r2 r1 ) */
            CASE(FSWAP) FNEED(2);
            fa = ftos;
            ftos = fp[-1];
            fp[-1] = fa;
            NEXT;
            /* FOVER ( F: r1 r2 -- r1 r2 r1 ) */
            CASE(FOVER) FNEED(2);
            FROOM(1);
            FPUSH(fp[-1]);
            NEXT;
            /* FROT ( F: r1 r2 r3 -- r2 r3 r1 ) */
            CASE(FROT) FNEED(3);
            fa = fp[-2];
            fp[-2] = fp[-1];
            fp[-1] = ftos;
            ftos = fa;
            NEXT;
            /* FNIP ( F: r1 r2 -- r2 ) */
            CASE(FNIP) FNEED(2);
            fp--;
            NEXT;
            /* FTUCK ( F: r1 r2 -- r2 r1 r2 ) */
            CASE(FTUCK) FNEED(2);
            FROOM(1);
            fa = fp[-1];
            fp[-1] = ftos;
            fp[0] = fa; fp += 1;
            NEXT;
            /* FPICK ( u -- ) ( F: ru ... r0 -- ru ... r0 ru ) */
            CASE(FPICK)
            NEED(1);
            ua = U(tos);
            if (ua >= U(fp - fs0 + 1))
                THROW(FBRL_THROW_FSTACK_UNDERFLOW);
            FROOM(1);
            DROP1();
            FPUSH(ua == 0 ? ftos : fp[-(fbrl_cell)ua]);
            NEXT;
            /* FDEPTH ( -- n ) */
            CASE(FDEPTH) ROOM(1);
            PUSH(fp - fs0 + 1);
            NEXT;
            /* F>S ( -- n ) ( F: r -- ) */
            CASE(FTOS)
            FNEED(1);
            ROOM(1);
            fa = trunc(ftos);
            if (!(fa >= -9.2233720368547758e18 && fa < 9.2233720368547758e18))
                THROW(FBRL_THROW_RESULT_RANGE);
            FDROP1();
            PUSH((fbrl_cell)fa);
            NEXT;
            /* S>F ( n -- ) ( F: -- r ) */
            CASE(STOF) NEED(1);
            FROOM(1);
            FPUSH((double)tos);
            DROP1();
            NEXT;
            /* D>F ( d -- ) ( F: -- r ) */
            CASE(DTOF) NEED(2);
            FROOM(1);
            FPUSH(fbrl__d_to_f(S, T));
            sp -= 2;
            tos = *sp;
            NEXT;
            /* F>D ( -- d ) ( F: r -- ) */
            CASE(FTOD)
            FNEED(1);
            ROOM(2);
            if ((code = fbrl__f_to_d(ftos, &o1, &o2)))
                goto do_throw;
            FDROP1();
            PUSH(o1);
            PUSH(o2);
            NEXT;
            /* FLOATS ( n -- n*float ), DFLOATS ( n -- n*8 ) */
            CASE(FLOATS) CASE(DFLOATS) NEED(1);
            T = (fbrl_cell)(U(T) * sizeof(double));
            NEXT;
            /* FLOAT+ ( a -- a' ), DFLOAT+ ( a -- a+8 ) */
            CASE(FLOATPLUS) CASE(DFLOATPLUS) NEED(1);
            T = (fbrl_cell)(U(T) + sizeof(double));
            NEXT;
            /* SFLOATS ( n -- n*4 ) */
            CASE(SFLOATS) NEED(1);
            T = (fbrl_cell)(U(T) * 4);
            NEXT;
            /* SFLOAT+ ( a -- a+4 ) */
            CASE(SFLOATPLUS) NEED(1);
            T = (fbrl_cell)(U(T) + 4);
            NEXT;
            /* FALIGN ( -- ), DFALIGN ( -- ), SFALIGN ( -- ) */
            CASE(FALIGN) CASE(DFALIGN) CASE(SFALIGN) ua = w == OP_SFALIGN ? 4 : sizeof(double);
            ub = U(vm->here);
            if ((code = fbrl__allot(vm, (fbrl_cell)(((ub + ua - 1) & ~(ua - 1)) - ub))))
                goto do_throw;
            NEXT;
            /* FALIGNED ( a -- a' ), DFALIGNED ( a -- a' ), SFALIGNED ( a -- a' ) */
            CASE(FALIGNED) CASE(DFALIGNED) CASE(SFALIGNED) NEED(1);
            ua = w == OP_SFALIGNED ? 4 : sizeof(double);
            T = (fbrl_cell)((U(T) + ua - 1) & ~(ua - 1));
            NEXT;
            /* PRECISION ( -- u ) */
            CASE(PRECISION) ROOM(1);
            PUSH(vm->precision);
            NEXT;
            /* SET-PRECISION ( u -- ) */
            CASE(SETPRECISION)
            NEED(1);
            a = tos;
            DROP1();
            vm->precision = a < 1 ? 1 : a > 17 ? 17 : (int)a;
            NEXT;
            /* PI ( F: -- pi ) */
            CASE(FPI) FROOM(1);
            FPUSH(3.14159265358979323846);
            NEXT;

            DEFAULT
        execute_xt : {
            fbrl_hdr *h = fbrl__xt_hdr(vm, w);
            if (!h)
                THROW(fbrl__throw_msg(vm, FBRL_THROW_UNDEFINED, "invalid execution token"));
            switch (h->kind) {
            /* a primitive: as its op */
            case K_PRIM: w = H_OP(h); DISPATCH_PLAIN(); /* its step was the xt's */
            /* ( i*x -- j*x ) R: ( -- ip ) */
            case K_COLON:
                ENTER(h->body);
                RROOM(1);
                rp[0] = (fbrl_cell)ip; rp += 1;
                JUMP(h->body);
                NEXT;
            /* ( -- a-addr ) */
            case K_VAR:
                ROOM(1);
                PUSH(h->body);
                NEXT;
            /* ( -- a-addr ), then the DOES> code: R: ( -- ip ) */
            case K_CREATE:
                ROOM(1);
                PUSH(h->body);
                if (H_DOES(h)) {
                    RROOM(1);
                    rp[0] = (fbrl_cell)ip; rp += 1;
                    JUMP(H_DOES(h));
                }
                NEXT;
            /* ( -- x ) */
            case K_CONST:
            case K_VALUE:
                ROOM(1);
                CHKC(h->body, CELL);
                PUSH(ld(h->body));
                NEXT;
            /* ( -- x1 x2 ) */
            case K_2CONST:
            case K_2VALUE:
                ROOM(2);
                CHKC(h->body, 2 * CELL);
                PUSH(ld(h->body + CELL));
                PUSH(ld(h->body));
                NEXT;
            /* ( F: -- r ) */
            case K_FCONST:
            case K_FVALUE:
                FROOM(1);
                CHKC(h->body, (fbrl_cell)sizeof(double));
                FPUSH(ldf(h->body));
                NEXT;
            /* ( i*x -- j*x ) as the word it is set to */
            case K_DEFER: {
                int n = 0;
                for (;;) {
                    CHKC(h->body, CELL);
                    w = ld(h->body);
                    if (w == 0)
                        THROW(fbrl__throw_msg(vm, FBRL_THROW_UNSUPPORTED, "deferred word not set (use IS)"));
                    h = fbrl__xt_hdr(vm, w);
                    if (!h || h->kind != K_DEFER)
                        break;
                    if (++n > 1000)
                        THROW(fbrl__throw_msg(vm, FBRL_THROW_UNSUPPORTED, "deferred words loop"));
                }
                goto execute_xt;
            }
            /* ( i*x -- j*x ) as its C function (help text: its stack comment) */
            case K_CFUNC: {
                fbrl_status st;
                if (!H_FN(h) && !H_XFN(h))
                    THROW(FBRL_THROW_UNSUPPORTED);
                SAVE();
                vm->ip = ip;
                vm->pending_throw = 0;
                vm->cword = h;
                st = H_XFN(h) ? H_XFN(h)(vm, H_ARG(h), h->word) : H_FN(h)(vm, H_ARG(h));
                vm->resuming = 0; /* task.c: only the first C word after a resume runs again */
                if (st == FBRL_ETHROW && vm->pending_throw == THROW_YIELD) {
                    vm->sp = sp + 1; /* it runs again on resuming: its arguments back */
                    vm->fp = fp + 1;
                }
                if (vm->sp < ds0 || vm->sp > dse || vm->fp < fs0 || vm->fp > fse) {
                    vm->sp = ds0;
                    vm->fp = fs0;
                    LOAD();
                    THROW(FBRL_THROW_STACK_UNDERFLOW);
                }
                LOAD();
                STEPWORDS(); /* BREAK, UNBREAK ... set the word hook */
                if (st != FBRL_OK)
                    THROW(st == FBRL_ETHROW ? (vm->pending_throw ? vm->pending_throw : -1)
                                            : FBRL_THROW_STATUS(st));
                POLL(); /* a C word that waited (robot motion, I/O) may have been interrupted */
                NEXT;
            }
            /* ( -- ) the dictionary back to before the marker */
            case K_MARKER:
                if (vm->defining)
                    THROW(fbrl__throw_msg(vm, FBRL_THROW_COMPILER_NESTING,
                                          "a MARKER cannot run inside a definition"));
                fbrl__forget(vm, (unsigned char *)h->body, (uint32_t)H_END(h), (size_t)H_DOES(h));
                SPANS();
                NEXT;
            default: THROW(FBRL_THROW_UNSUPPORTED);
            }
        }
        }
        NEXT;

    /* The error exits store their code in memory: as plain assignments, the
     * compiler would load every exit's code into a register before each check. */
    e_underflow:
        vm->run_code = -4;
        goto e_stored;
    e_overflow:
        vm->run_code = -3;
        goto e_stored;
    e_r_underflow:
        vm->run_code = -6;
        goto e_stored;
    e_r_overflow:
        vm->run_code = -5;
        goto e_stored;
    e_f_underflow:
        vm->run_code = -45;
        goto e_stored;
    e_f_overflow:
        vm->run_code = -44;
        goto e_stored;
    e_address:
        vm->run_code = -9;
        goto e_stored;
    e_stored:
        code = vm->run_code;
        goto do_throw;
#if FBRL_WORD_HOOK || !FBRL_CGOTO
    step_word: /* the word hook, before the word w (ip: after it) */
        if (FBRL_WORD_HOOK && vm->word_fn && !vm->in_step) {
            SAVE();
            vm->ip = ip;
            code = fbrl__step_word(vm, w);
            LOAD();
            STEPWORDS();
            if (code)
                goto do_throw;
        }
        DISPATCH_PLAIN();
#endif
    do_throw:
        if (code == THROW_BYE || code == THROW_QUIT)
            goto out;
        if (code == THROW_YIELD || code == THROW_STOP) { /* task.c: the slice ends here */
            vm->resume_w = w;
            vm->resume_at = ip;
            goto out;
        }
        if (!vm->handler && !vm->bt_captured) { /* no CATCH will take it: keep where it happened */
            SAVE();
            fbrl__backtrace(vm, ip);
        }
        {
            fbrl_cell hd = vm->handler;
            if (hd > entry && hd >= 5 && hd <= rp - rs0) {
                fbrl_cell *f = rs0 + hd - 5;
                rp = f;
                vm->handler = (f[3] >= 0 && f[3] <= hd - 5) ? f[3] : 0;
                vm->lp = (f[4] >= 0 && f[4] <= vm->lp) ? f[4] : 0;
                sp = ds0 + (U(f[1]) < U(dse - ds0) ? f[1] : 0) - 1;
                tos = *sp;
                fp = fs0 + (U(f[2]) <= U(fse - fs0) ? f[2] : 0) - 1;
                ftos = *fp;
                vm->err_captured = 0;
                vm->bt_captured = 0;
                if (!CODE_OK(f[0])) {
                    code = FBRL_THROW_BAD_ADDRESS;
                    goto do_throw;
                }
                ip = (const fbrl_cell *)f[0];
                PUSH(code);
                code = 0;
                NEXT;
            }
        }
        goto out;
    }
out:
    SAVE();
    vm->nest--;
    if (code && vm->nest == 0)
        vm->lp = 0; /* no definition runs any more: no locals */
    return code;
}
#if FBRL_CGOTO
#pragma GCC diagnostic pop
#endif
#undef tab
