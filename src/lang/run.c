/* run.c - the inner interpreter: token-threaded code, one switch.
 *
 * A code cell is either an opcode (< OP__END, see ops.def) or an execution token
 * (FBRL_XT_BASE + header index). Colon definitions are called with OP_CALL + body
 * address, so a call costs one validated jump. Stack pointers live in locals and are
 * written back (SAVE) before any helper that works on the VM's stacks. */
#include <math.h>
#include <string.h>
#include "atomic.h"
#include "vm_internal.h"
#include "words.h"

#define SAVE() (vm->sp = sp, vm->rp = rp, vm->fp = fp)
#define LOAD() (sp = vm->sp, rp = vm->rp, fp = vm->fp)
#define THROW(c) do { code = (c); goto do_throw; } while (0)
#define NEED(n) if (sp - ds0 < (n)) THROW(FBRL_THROW_STACK_UNDERFLOW)
#define ROOM(n) if (dse - sp < (n)) THROW(FBRL_THROW_STACK_OVERFLOW)
#define RNEED(n) if (rp - rs0 < (n)) THROW(FBRL_THROW_RSTACK_UNDERFLOW)
#define RROOM(n) if (rse - rp < (n)) THROW(FBRL_THROW_RSTACK_OVERFLOW)
#define FNEED(n) if (fp - fs0 < (n)) THROW(FBRL_THROW_FSTACK_UNDERFLOW)
#define FROOM(n) if (fse - fp < (n)) THROW(FBRL_THROW_FSTACK_OVERFLOW)
#define CHK(a, n) if (!fbrl__addr_ok(vm, (a), (n))) THROW(FBRL_THROW_BAD_ADDRESS)
#define CODE_OK(t) ((fbrl_ucell)(t) - code_lo < code_span && !((fbrl_ucell)(t) & ((fbrl_ucell)CELL - 1)))
#define JUMP(t) do { fbrl_cell t_ = (t); if (!CODE_OK(t_)) THROW(FBRL_THROW_BAD_ADDRESS); ip = (const fbrl_cell *)t_; } while (0)
#define CALLC(expr) do { SAVE(); code = (expr); LOAD(); if (code) goto do_throw; } while (0)
/* fbrl_vm_interrupt() is honoured wherever a program can loop or recurse */
#define POLL() if (fbrl_load_rlx(&vm->interrupt)) { fbrl_store_rlx(&vm->interrupt, 0); THROW(FBRL_THROW_INTERRUPT); }
#define T sp[-1]
#define S sp[-2]
#define U(x) ((fbrl_ucell)(x))
#define FLAG(c) ((c) ? (fbrl_cell)-1 : 0)
#define FCELLS ((sizeof(double) + sizeof(fbrl_cell) - 1) / sizeof(fbrl_cell))
/* a float result must be finite when its inputs were (else -43 / -46) */
#define FRES(r, bad) do { double r_ = (r); if (!isfinite(r_)) THROW(bad); fp[-1] = r_; } while (0)

static fbrl_cell ld(fbrl_cell a) { fbrl_cell v; memcpy(&v, (const void *)a, sizeof v); return v; }
static void st(fbrl_cell a, fbrl_cell v) { memcpy((void *)a, &v, sizeof v); }
static double ldf(fbrl_cell a) { double v; memcpy(&v, (const void *)a, sizeof v); return v; }
static void stf(fbrl_cell a, double v) { memcpy((void *)a, &v, sizeof v); }

static int floordiv(fbrl_cell a, fbrl_cell b, fbrl_cell *q, fbrl_cell *r)
{
    if (b == 0) return FBRL_THROW_DIV_ZERO;
    if (b == -1) { *q = (fbrl_cell)(0 - U(a)); *r = 0; return 0; }
    fbrl_cell qq = a / b, rr = a % b;
    if (rr != 0 && ((rr < 0) != (b < 0))) { qq--; rr += b; }
    *q = qq;
    *r = rr;
    return 0;
}

int fbrl__run(fbrl_vm *vm, fbrl_cell xt)
{
    fbrl_cell *sp, *rp;
    double *fp;
    fbrl_cell *const ds0 = vm->ds0, *const dse = vm->ds_end;
    fbrl_cell *const rs0 = vm->rs0, *const rse = vm->rs_end;
    double *const fs0 = vm->fs0, *const fse = vm->fs_end;
    const fbrl_ucell code_lo = (fbrl_ucell)vm->data_lo;
    const fbrl_ucell code_span = (fbrl_ucell)(vm->mem_end - vm->data_lo);
    const fbrl_cell *ip = (const fbrl_cell *)vm->guard_addr; /* the HALT cell */
    fbrl_cell w = xt, entry, a, b, c = 0;
    fbrl_ucell ua, ub;
    double fa;
    int code = 0, defers = 0;

    LOAD();
    entry = rp - rs0;
    if (vm->nest >= 64) return FBRL_THROW_RSTACK_OVERFLOW;
    vm->nest++;
    goto execute_xt;

    for (;;) {
        w = *ip++;
    dispatch:
        switch ((fbrl_ucell)w) {
        case OP_BAD: THROW(fbrl__throw_msg(vm, FBRL_THROW_BAD_ADDRESS, "invalid instruction (corrupted code?)"));
        case OP_HALT: goto out;
        case OP_CATCHEND:
            if (vm->handler != rp - rs0 || rp - rs0 < 5) THROW(FBRL_THROW_RSTACK_IMBALANCE);
            rp -= 5;
            vm->handler = (rp[3] >= 0 && rp[3] <= rp - rs0) ? rp[3] : 0;
            JUMP(rp[0]);
            ROOM(1);
            *sp++ = 0;
            continue;
        case OP_LIT: ROOM(1); *sp++ = *ip++; continue;
        case OP_FLIT: FROOM(1); memcpy(fp, ip, sizeof(double)); fp++; ip += FCELLS; continue;
        case OP_CALL: POLL(); RROOM(1); a = *ip++; *rp++ = (fbrl_cell)ip; JUMP(a); continue;
        case OP_EXIT: RNEED(1); JUMP(*--rp); continue;
        case OP_BRANCH: POLL(); JUMP(*ip); continue;
        case OP_ZBRANCH: NEED(1); if (*--sp == 0) { POLL(); JUMP(*ip); } else ip++; continue;
        case OP_PQDO:
            NEED(2);
            if (S == T) { sp -= 2; JUMP(*ip); continue; }
            /* fall through */
        case OP_PDO:
            NEED(2); RROOM(3);
            rp[0] = *ip++; rp[1] = S; rp[2] = T;
            rp += 3; sp -= 2;
            continue;
        case OP_PLOOP:
            RNEED(3);
            a = (fbrl_cell)(U(rp[-1]) + 1);
            if (a == rp[-2]) { rp -= 3; ip++; } else { POLL(); rp[-1] = a; JUMP(*ip); }
            continue;
        case OP_PPLOOP: {
            NEED(1); RNEED(3);
            fbrl_ucell d = U(rp[-1]) - U(rp[-2]), n = U(*--sp), nd = d + n;
            if ((fbrl_cell)((d ^ nd) & (d ^ n)) < 0) { rp -= 3; ip++; }
            else { POLL(); rp[-1] = (fbrl_cell)(U(rp[-1]) + n); JUMP(*ip); }
            continue;
        }
        case OP_I: RNEED(1); ROOM(1); *sp++ = rp[-1]; continue;
        case OP_J: RNEED(4); ROOM(1); *sp++ = rp[-4]; continue;
        case OP_LEAVE: RNEED(3); a = rp[-3]; rp -= 3; JUMP(a); continue;
        case OP_UNLOOP: RNEED(3); rp -= 3; continue;
        case OP_SLIT: case OP_CSLIT: case OP_PABORTQ: {
            fbrl_ucell n = U(*ip++), skip = (n / U(CELL) + 1) * U(CELL);
            fbrl_cell s = (fbrl_cell)ip;
            if (n > 65536) THROW(FBRL_THROW_BAD_ADDRESS);
            JUMP((fbrl_cell)(U(s) + skip));
            if (w == OP_PABORTQ) {
                NEED(1);
                if (*--sp) {
                    char m[sizeof vm->throw_msg];
                    size_t k = n < sizeof m - 1 ? (size_t)n : sizeof m - 1;
                    CHK(s, (fbrl_cell)k);
                    memcpy(m, (const void *)s, k);
                    m[k] = 0;
                    THROW(fbrl__throw_msg(vm, FBRL_THROW_ABORTQ, m));
                }
            } else if (w == OP_CSLIT) {
                ROOM(1); *sp++ = s;
            } else {
                ROOM(2); *sp++ = s; *sp++ = (fbrl_cell)n;
            }
            continue;
        }
        case OP_DOESSET: {
            fbrl_hdr *h = vm->nwords ? HDR(vm, vm->nwords - 1) : NULL;
            if (!h || h->kind != K_CREATE) THROW(fbrl__throw_msg(vm, FBRL_THROW_TO_BODY, "DOES> needs a CREATEd word"));
            h->does = (fbrl_cell)ip;
            RNEED(1);
            JUMP(*--rp);
            continue;
        }
        case OP_POF:
            NEED(2);
            if (S == T) { sp -= 2; ip++; } else { sp--; JUMP(*ip); }
            continue;
        case OP_COMPSEM: { /* run a state-smart word as if compiling */
            fbrl_cell saved = *vm->state;
            NEED(1);
            a = *--sp;
            *vm->state = -1;
            SAVE();
            code = fbrl__run(vm, a);
            LOAD();
            if (*vm->state == -1) *vm->state = saved;
            if (code) goto do_throw;
            continue;
        }
        case OP_PTOVAL: NEED(1); a = *ip++; CHK(a, CELL); st(a, *--sp); continue;
        case OP_PTO2VAL: NEED(2); a = *ip++; CHK(a, 2 * CELL); st(a, T); st(a + CELL, S); sp -= 2; continue;
        case OP_PTOFVAL: FNEED(1); a = *ip++; CHK(a, (fbrl_cell)sizeof(double)); stf(a, *--fp); continue;

        /* stack */
        case OP_DUP: NEED(1); ROOM(1); sp[0] = T; sp++; continue;
        case OP_DROP: NEED(1); sp--; continue;
        case OP_SWAP: NEED(2); a = T; T = S; S = a; continue;
        case OP_OVER: NEED(2); ROOM(1); sp[0] = S; sp++; continue;
        case OP_ROT: NEED(3); a = sp[-3]; sp[-3] = S; S = T; T = a; continue;
        case OP_MROT: NEED(3); a = T; T = S; S = sp[-3]; sp[-3] = a; continue;
        case OP_NIP: NEED(2); S = T; sp--; continue;
        case OP_TUCK: NEED(2); ROOM(1); a = T; sp[0] = a; T = S; S = a; sp++; continue;
        case OP_PICK:
            NEED(1); ua = U(T);
            if (ua >= U(sp - ds0 - 1)) THROW(FBRL_THROW_STACK_UNDERFLOW);
            T = sp[-2 - (fbrl_cell)ua];
            continue;
        case OP_ROLL:
            NEED(1); ua = U(T);
            if (ua >= U(sp - ds0 - 1)) THROW(FBRL_THROW_STACK_UNDERFLOW);
            sp--;
            a = sp[-1 - (fbrl_cell)ua];
            memmove(sp - 1 - ua, sp - ua, (size_t)ua * sizeof(fbrl_cell));
            T = a;
            continue;
        case OP_QDUP: NEED(1); if (T) { ROOM(1); sp[0] = T; sp++; } continue;
        case OP_TWODUP: NEED(2); ROOM(2); sp[0] = S; sp[1] = T; sp += 2; continue;
        case OP_TWODROP: NEED(2); sp -= 2; continue;
        case OP_TWOSWAP: NEED(4); a = sp[-4]; b = sp[-3]; sp[-4] = S; sp[-3] = T; S = a; T = b; continue;
        case OP_TWOOVER: NEED(4); ROOM(2); sp[0] = sp[-4]; sp[1] = sp[-3]; sp += 2; continue;
        case OP_TWOROT:
            NEED(6); a = sp[-6]; b = sp[-5];
            memmove(sp - 6, sp - 4, 4 * sizeof(fbrl_cell));
            S = a; T = b;
            continue;
        case OP_TWONIP: NEED(4); sp[-4] = S; sp[-3] = T; sp -= 2; continue;
        case OP_DEPTH: ROOM(1); a = sp - ds0; *sp++ = a; continue;
        case OP_TOR: NEED(1); RROOM(1); *rp++ = *--sp; continue;
        case OP_RFROM: RNEED(1); ROOM(1); *sp++ = *--rp; continue;
        case OP_RFETCH: RNEED(1); ROOM(1); *sp++ = rp[-1]; continue;
        case OP_TWOTOR: NEED(2); RROOM(2); rp[0] = S; rp[1] = T; rp += 2; sp -= 2; continue;
        case OP_TWORFROM: RNEED(2); ROOM(2); sp[0] = rp[-2]; sp[1] = rp[-1]; sp += 2; rp -= 2; continue;
        case OP_TWORFETCH: RNEED(2); ROOM(2); sp[0] = rp[-2]; sp[1] = rp[-1]; sp += 2; continue;
        case OP_RDROP: RNEED(1); rp--; continue;

        /* arithmetic */
        case OP_PLUS: NEED(2); S = (fbrl_cell)(U(S) + U(T)); sp--; continue;
        case OP_MINUS: NEED(2); S = (fbrl_cell)(U(S) - U(T)); sp--; continue;
        case OP_STAR: NEED(2); S = (fbrl_cell)(U(S) * U(T)); sp--; continue;
        case OP_SLASH: NEED(2); if ((code = floordiv(S, T, &a, &b))) goto do_throw; S = a; sp--; continue;
        case OP_MOD: NEED(2); if ((code = floordiv(S, T, &a, &b))) goto do_throw; S = b; sp--; continue;
        case OP_SLASHMOD: NEED(2); if ((code = floordiv(S, T, &a, &b))) goto do_throw; S = b; T = a; continue;
        case OP_STARSLASH: case OP_STARSLASHMOD:
            NEED(3);
            if ((code = fbrl__starslash(sp[-3], S, T, &a, &b))) goto do_throw;
            if (w == OP_STARSLASH) { sp -= 2; T = a; } else { sp--; S = b; T = a; }
            continue;
        case OP_ONEPLUS: NEED(1); T = (fbrl_cell)(U(T) + 1); continue;
        case OP_ONEMINUS: NEED(1); T = (fbrl_cell)(U(T) - 1); continue;
        case OP_TWOSTAR: NEED(1); T = (fbrl_cell)(U(T) << 1); continue;
        case OP_TWOSLASH: NEED(1); T = T < 0 ? (fbrl_cell)~(~U(T) >> 1) : (fbrl_cell)(U(T) >> 1); continue;
        case OP_NEGATE: NEED(1); T = (fbrl_cell)(0 - U(T)); continue;
        case OP_ABS: NEED(1); if (T < 0) T = (fbrl_cell)(0 - U(T)); continue;
        case OP_MIN: NEED(2); if (T < S) S = T; sp--; continue;
        case OP_MAX: NEED(2); if (T > S) S = T; sp--; continue;
        case OP_AND: NEED(2); S &= T; sp--; continue;
        case OP_OR: NEED(2); S |= T; sp--; continue;
        case OP_XOR: NEED(2); S ^= T; sp--; continue;
        case OP_INVERT: NEED(1); T = ~T; continue;
        case OP_LSHIFT: NEED(2); S = U(T) >= (fbrl_ucell)CELL_BITS ? 0 : (fbrl_cell)(U(S) << U(T)); sp--; continue;
        case OP_RSHIFT: NEED(2); S = U(T) >= (fbrl_ucell)CELL_BITS ? 0 : (fbrl_cell)(U(S) >> U(T)); sp--; continue;
        case OP_MSTAR: NEED(2); fbrl__mstar(S, T, &sp[-2], &sp[-1]); continue;
        case OP_UMSTAR: NEED(2); fbrl__umul(U(S), U(T), &ua, &ub); S = (fbrl_cell)ub; T = (fbrl_cell)ua; continue;
        case OP_UMSLASHMOD:
            NEED(3);
            if (T == 0) THROW(FBRL_THROW_DIV_ZERO);
            if (U(S) >= U(T)) THROW(FBRL_THROW_RESULT_RANGE);
            fbrl__udiv(U(S), U(sp[-3]), U(T), &ua, &ub);
            sp--; S = (fbrl_cell)ub; T = (fbrl_cell)ua;
            continue;
        case OP_FMSLASHMOD: case OP_SMSLASHREM:
            NEED(3);
            if ((code = fbrl__dsdiv(sp[-3], S, T, w == OP_FMSLASHMOD, &a, &b))) goto do_throw;
            sp--; S = b; T = a;
            continue;
        case OP_CELLPLUS: NEED(1); T = (fbrl_cell)(U(T) + U(CELL)); continue;
        case OP_CELLS: NEED(1); T = (fbrl_cell)(U(T) * U(CELL)); continue;
        case OP_CHARPLUS: NEED(1); T = (fbrl_cell)(U(T) + 1); continue;
        case OP_CHARS: NEED(1); continue;
        case OP_EQ: NEED(2); S = FLAG(S == T); sp--; continue;
        case OP_NE: NEED(2); S = FLAG(S != T); sp--; continue;
        case OP_LT: NEED(2); S = FLAG(S < T); sp--; continue;
        case OP_GT: NEED(2); S = FLAG(S > T); sp--; continue;
        case OP_ULT: NEED(2); S = FLAG(U(S) < U(T)); sp--; continue;
        case OP_UGT: NEED(2); S = FLAG(U(S) > U(T)); sp--; continue;
        case OP_ZEQ: NEED(1); T = FLAG(T == 0); continue;
        case OP_ZNE: NEED(1); T = FLAG(T != 0); continue;
        case OP_ZLT: NEED(1); T = FLAG(T < 0); continue;
        case OP_ZGT: NEED(1); T = FLAG(T > 0); continue;
        case OP_WITHIN: NEED(3); sp[-3] = FLAG(U(sp[-3]) - U(S) < U(T) - U(S)); sp -= 2; continue;
        case OP_TRUE: ROOM(1); *sp++ = -1; continue;
        case OP_FALSE: ROOM(1); *sp++ = 0; continue;
        case OP_BL: ROOM(1); *sp++ = ' '; continue;

        /* doubles: low cell below, high cell on top */
        case OP_STOD: NEED(1); ROOM(1); sp[0] = T < 0 ? -1 : 0; sp++; continue;
        case OP_DTOS: NEED(2); sp--; continue;
        case OP_DPLUS: case OP_DMINUS: {
            NEED(4);
            fbrl_ucell al = U(sp[-4]), ah = U(sp[-3]), bl = U(S), bh = U(T);
            if (w == OP_DMINUS) { bl = ~bl + 1; bh = ~bh + (bl == 0); }
            fbrl_ucell l = al + bl;
            sp[-4] = (fbrl_cell)l;
            sp[-3] = (fbrl_cell)(ah + bh + (l < al));
            sp -= 2;
            continue;
        }
        case OP_DNEGATE: NEED(2); S = (fbrl_cell)(~U(S) + 1); T = (fbrl_cell)(~U(T) + (S == 0)); continue;
        case OP_DABS: NEED(2); if (T < 0) { S = (fbrl_cell)(~U(S) + 1); T = (fbrl_cell)(~U(T) + (S == 0)); } continue;
        case OP_DEQ: NEED(4); sp[-4] = FLAG(sp[-4] == S && sp[-3] == T); sp -= 3; continue;
        case OP_DLT: NEED(4);
            sp[-4] = FLAG(sp[-3] < T || (sp[-3] == T && U(sp[-4]) < U(S))); sp -= 3; continue;
        case OP_DULT: NEED(4);
            sp[-4] = FLAG(U(sp[-3]) < U(T) || (sp[-3] == T && U(sp[-4]) < U(S))); sp -= 3; continue;
        case OP_DZEQ: NEED(2); S = FLAG(S == 0 && T == 0); sp--; continue;
        case OP_DZLT: NEED(2); S = FLAG(T < 0); sp--; continue;
        case OP_DTWOSTAR: NEED(2);
            T = (fbrl_cell)((U(T) << 1) | (U(S) >> (CELL_BITS - 1))); S = (fbrl_cell)(U(S) << 1); continue;
        case OP_DTWOSLASH: NEED(2);
            S = (fbrl_cell)((U(S) >> 1) | (U(T) << (CELL_BITS - 1)));
            T = T < 0 ? (fbrl_cell)~(~U(T) >> 1) : (fbrl_cell)(U(T) >> 1);
            continue;
        case OP_DMAX: case OP_DMIN: {
            NEED(4);
            int lt = sp[-3] < T || (sp[-3] == T && U(sp[-4]) < U(S));
            if ((w == OP_DMAX) == lt) { sp[-4] = S; sp[-3] = T; }
            sp -= 2;
            continue;
        }
        case OP_MPLUS: {
            NEED(3);
            fbrl_ucell l = U(sp[-3]) + U(T);
            sp[-2] = (fbrl_cell)(U(sp[-2]) + (T < 0 ? ~(fbrl_ucell)0 : 0) + (l < U(sp[-3])));
            sp[-3] = (fbrl_cell)l;
            sp--;
            continue;
        }
        case OP_MSTARSLASH:
            NEED(4);
            if ((code = fbrl__mstarslash(&sp[-4], &sp[-3], S, T))) goto do_throw;
            sp -= 2;
            continue;

        /* memory */
        case OP_FETCH: NEED(1); CHK(T, CELL); T = ld(T); continue;
        case OP_STORE: NEED(2); CHK(T, CELL); st(T, S); sp -= 2; continue;
        case OP_CFETCH: NEED(1); CHK(T, 1); T = *(unsigned char *)T; continue;
        case OP_CSTORE: NEED(2); CHK(T, 1); *(unsigned char *)T = (unsigned char)S; sp -= 2; continue;
        case OP_PLUSSTORE: NEED(2); CHK(T, CELL); st(T, (fbrl_cell)(U(ld(T)) + U(S))); sp -= 2; continue;
        case OP_TWOFETCH: NEED(1); ROOM(1); CHK(T, 2 * CELL); a = T; T = ld(a + CELL); *sp++ = ld(a); continue;
        case OP_TWOSTORE: NEED(3); CHK(T, 2 * CELL); st(T, S); st(T + CELL, sp[-3]); sp -= 3; continue;
        case OP_WFETCH: { uint16_t v; NEED(1); CHK(T, 2); memcpy(&v, (void *)T, 2); T = v; continue; }
        case OP_WSTORE: { uint16_t v; NEED(2); CHK(T, 2); v = (uint16_t)S; memcpy((void *)T, &v, 2); sp -= 2; continue; }
        case OP_COMMA: NEED(1); SAVE(); if ((code = fbrl__emit(vm, T))) goto do_throw; sp--; continue;
        case OP_CCOMMA:
            NEED(1); if ((code = fbrl__allot(vm, 1))) goto do_throw;
            vm->here[-1] = (unsigned char)*--sp;
            continue;
        case OP_ALLOT: NEED(1); if ((code = fbrl__allot(vm, T))) goto do_throw; sp--; continue;
        case OP_HERE: ROOM(1); *sp++ = (fbrl_cell)vm->here; continue;
        case OP_ALIGN: if ((code = fbrl__align(vm))) goto do_throw; continue;
        case OP_ALIGNED: NEED(1); T = (fbrl_cell)((U(T) + U(CELL) - 1) & ~(U(CELL) - 1)); continue;
        case OP_UNUSED:
            ROOM(1); *sp++ = (fbrl_cell)((unsigned char *)(vm->hdr_top - vm->nwords) - vm->here); continue;
        case OP_PAD: ROOM(1); *sp++ = (fbrl_cell)vm->pad; continue;
        case OP_FILL: NEED(3); c = T; sp--; /* fall through */
        case OP_ERASE: case OP_BLANK:
            if (w != OP_FILL) { NEED(2); c = w == OP_BLANK ? ' ' : 0; }
            if (T > 0) { CHK(S, T); memset((void *)S, (int)(unsigned char)c, (size_t)T); }
            sp -= 2;
            continue;
        case OP_MOVE: case OP_CMOVE: case OP_CMOVEUP:
            NEED(3);
            if (T > 0) {
                CHK(sp[-3], T); CHK(S, T);
                if (w == OP_MOVE) memmove((void *)S, (void *)sp[-3], (size_t)T);
                else if (w == OP_CMOVE) {
                    unsigned char *d = (unsigned char *)S; const unsigned char *s = (const unsigned char *)sp[-3];
                    for (fbrl_cell i = 0; i < T; i++) d[i] = s[i];
                } else {
                    unsigned char *d = (unsigned char *)S; const unsigned char *s = (const unsigned char *)sp[-3];
                    for (fbrl_cell i = T; i-- > 0;) d[i] = s[i];
                }
            }
            sp -= 3;
            continue;
        case OP_COUNT: NEED(1); ROOM(1); CHK(T, 1); a = T; T = a + 1; *sp++ = *(unsigned char *)a; continue;
        case OP_COMPARE: case OP_SEARCH: case OP_SLASHSTRING: case OP_MTRAILING:
            CALLC(fbrl__w_string(vm, (int)w));
            continue;

        /* compiling words */
        case OP_IF: case OP_ELSE: case OP_THEN: case OP_BEGIN: case OP_UNTIL: case OP_AGAIN:
        case OP_WHILE: case OP_REPEAT: case OP_AHEAD: case OP_DO: case OP_QDO: case OP_LOOP:
        case OP_PLUSLOOP: case OP_RECURSE: case OP_CASE: case OP_OF: case OP_ENDOF: case OP_ENDCASE:
        case OP_DOES:
            CALLC(fbrl__w_control(vm, (int)w));
            continue;
        case OP_COLON: CALLC(fbrl__colon(vm, 0, NULL)); continue;
        case OP_NONAME: ROOM(1); CALLC(fbrl__colon(vm, 1, &a)); *sp++ = a; continue;
        case OP_SEMI: CALLC(fbrl__semicolon(vm)); continue;
        case OP_CREATE: case OP_VARIABLE: case OP_TWOVARIABLE: case OP_CONSTANT: case OP_TWOCONSTANT:
        case OP_VALUE: case OP_TWOVALUE: case OP_DEFER: case OP_BUFFERCOLON: case OP_MARKER:
        case OP_FVARIABLE: case OP_FCONSTANT: case OP_FVALUE:
            CALLC(fbrl__w_define(vm, (int)w));
            continue;
        case OP_TO: case OP_IS: case OP_ACTIONOF: case OP_POSTPONE: case OP_BCOMPILE: case OP_BTICK:
        case OP_BCHAR: case OP_TICK: case OP_CHAR: case OP_PAREN: case OP_BACKSLASH: case OP_SHEBANG: case OP_DOTPAREN:
        case OP_DOTQUOTE: case OP_SQUOTE: case OP_SBQUOTE: case OP_CQUOTE: case OP_ABORTQ:
        case OP_PARSE: case OP_PARSENAME: case OP_WORD: case OP_FIND: case OP_LITERAL: case OP_TWOLITERAL:
        case OP_SLITERAL: case OP_FLITERAL: case OP_COMPILECOMMA: case OP_IMMEDIATE: case OP_TONUMBER:
        case OP_SEE: case OP_HELP: case OP_INCLUDE: case OP_REQUIRE: case OP_REFILL: case OP_ENVQ:
        case OP_LATESTXT: case OP_TOBODY: case OP_DEFERFETCH: case OP_DEFERSTORE:
        case OP_BIF: case OP_BELSE: case OP_BTHEN: case OP_BDEFINED: case OP_BUNDEFINED:
        case OP_SAVEINPUT: case OP_RESTOREINPUT:
            CALLC(fbrl__w_parse(vm, (int)w));
            continue;
        case OP_LBRACKET: *vm->state = 0; continue;
        case OP_RBRACKET: *vm->state = -1; continue;
        case OP_EXECUTE: NEED(1); w = *--sp; goto execute_xt;
        case OP_STATE: ROOM(1); *sp++ = (fbrl_cell)vm->state; continue;
        case OP_BASE: ROOM(1); *sp++ = (fbrl_cell)vm->base; continue;
        case OP_TOIN: ROOM(1); *sp++ = (fbrl_cell)vm->toin; continue;
        case OP_DECIMAL: *vm->base = 10; continue;
        case OP_HEX: *vm->base = 16; continue;
        case OP_SOURCE: {
            ROOM(2);
            const fbrl_src *s = vm->nsrc ? &vm->src[vm->nsrc - 1] : NULL;
            *sp++ = s ? (fbrl_cell)s->buf : (fbrl_cell)vm->wordbuf;
            *sp++ = s ? (fbrl_cell)s->len : 0;
            continue;
        }
        case OP_SOURCEID: ROOM(1); *sp++ = vm->nsrc ? vm->src[vm->nsrc - 1].id : 0; continue;
        case OP_EVALUATE:
            NEED(2);
            a = sp[-2]; b = T; sp -= 2;
            if (b < 0) THROW(FBRL_THROW_BAD_NUMBER);
            CHK(a, b);
            CALLC(fbrl__evaluate(vm, (char *)a, (size_t)b));
            continue;
        case OP_INCLUDED: case OP_REQUIRED:
            NEED(2);
            a = sp[-2]; b = T; sp -= 2;
            if (b < 0) THROW(FBRL_THROW_BAD_NUMBER);
            CHK(a, b);
            CALLC(fbrl__included(vm, (const char *)a, (size_t)b, w == OP_REQUIRED));
            continue;
        case OP_QUIT: THROW(THROW_QUIT);
        case OP_ABORT: THROW(FBRL_THROW_ABORT);
        case OP_BYE: vm->bye = 1; THROW(THROW_BYE);
        case OP_CATCH:
            NEED(1); RROOM(6);
            w = *--sp;
            rp[0] = (fbrl_cell)ip; rp[1] = sp - ds0; rp[2] = fp - fs0; rp[3] = vm->handler; rp[4] = 0;
            rp += 5;
            vm->handler = rp - rs0;
            ip = (const fbrl_cell *)vm->guard_addr + 1; /* the CATCHEND cell */
            goto execute_xt;
        case OP_THROW:
            NEED(1);
            a = *--sp;
            if (a == 0) continue;
            if (a == THROW_BYE) a = -1;
            THROW((int)(a < -2000000000 || a > 2000000000 ? FBRL_THROW_BAD_NUMBER : a));

        /* I/O, output, tools, facility: helpers */
        case OP_EMIT: { char ch; NEED(1); ch = (char)*--sp; fbrl__write(vm, &ch, 1); continue; }
        case OP_TYPE:
            NEED(2);
            if (T > 0) { CHK(S, T); fbrl__write(vm, (const char *)S, (size_t)T); }
            sp -= 2;
            continue;
        case OP_CR: fbrl__write(vm, "\n", 1); continue;
        case OP_SPACE: fbrl__write(vm, " ", 1); continue;
        case OP_SPACES: NEED(1); a = *--sp; CALLC(fbrl__spaces(vm, a)); continue;
        case OP_KEY: case OP_KEYQ: case OP_ACCEPT: case OP_DOT: case OP_UDOT: case OP_DOTR: case OP_UDOTR:
        case OP_DDOT: case OP_DDOTR: case OP_UDDOT: case OP_QUESTION: case OP_LTNUM: case OP_NUM:
        case OP_NUMS: case OP_NUMGT: case OP_HOLD: case OP_HOLDS: case OP_SIGN: case OP_DOTS:
        case OP_DUMP: case OP_WORDS: case OP_MS: case OP_TIMEDATE: case OP_USECS:
        case OP_FDOT: case OP_FEDOT: case OP_FSDOT: case OP_REPRESENT: case OP_TOFLOAT:
            CALLC(fbrl__w_io(vm, (int)w));
            continue;

        /* floating point */
        case OP_FPLUS: FNEED(2); fp--; FRES(fp[-1] + fp[0], FBRL_THROW_FRESULT_RANGE); continue;
        case OP_FMINUS: FNEED(2); fp--; FRES(fp[-1] - fp[0], FBRL_THROW_FRESULT_RANGE); continue;
        case OP_FSTAR: FNEED(2); fp--; FRES(fp[-1] * fp[0], FBRL_THROW_FRESULT_RANGE); continue;
        case OP_FSLASH: FNEED(2); fp--; if (fp[0] == 0) THROW(FBRL_THROW_FDIV_ZERO); FRES(fp[-1] / fp[0], FBRL_THROW_FRESULT_RANGE); continue;
        case OP_FNEGATE: FNEED(1); fp[-1] = -fp[-1]; continue;
        case OP_FABS: FNEED(1); fp[-1] = fabs(fp[-1]); continue;
        case OP_FMIN: FNEED(2); fp--; if (fp[0] < fp[-1]) fp[-1] = fp[0]; continue;
        case OP_FMAX: FNEED(2); fp--; if (fp[0] > fp[-1]) fp[-1] = fp[0]; continue;
        case OP_FSQRT: FNEED(1); FRES(sqrt(fp[-1]), FBRL_THROW_FBAD_ARG); continue;
        case OP_FSIN: FNEED(1); FRES(sin(fp[-1]), FBRL_THROW_FBAD_ARG); continue;
        case OP_FCOS: FNEED(1); FRES(cos(fp[-1]), FBRL_THROW_FBAD_ARG); continue;
        case OP_FTAN: FNEED(1); FRES(tan(fp[-1]), FBRL_THROW_FBAD_ARG); continue;
        case OP_FSINCOS: FNEED(1); FROOM(1); fa = fp[-1]; fp[-1] = sin(fa); fp[0] = cos(fa); fp++; continue;
        case OP_FASIN: FNEED(1); FRES(asin(fp[-1]), FBRL_THROW_FBAD_ARG); continue;
        case OP_FACOS: FNEED(1); FRES(acos(fp[-1]), FBRL_THROW_FBAD_ARG); continue;
        case OP_FATAN: FNEED(1); FRES(atan(fp[-1]), FBRL_THROW_FBAD_ARG); continue;
        case OP_FATAN2: FNEED(2); fp--; FRES(atan2(fp[-1], fp[0]), FBRL_THROW_FBAD_ARG); continue;
        case OP_FSINH: FNEED(1); FRES(sinh(fp[-1]), FBRL_THROW_FRESULT_RANGE); continue;
        case OP_FCOSH: FNEED(1); FRES(cosh(fp[-1]), FBRL_THROW_FRESULT_RANGE); continue;
        case OP_FTANH: FNEED(1); FRES(tanh(fp[-1]), FBRL_THROW_FBAD_ARG); continue;
        case OP_FASINH: FNEED(1); FRES(asinh(fp[-1]), FBRL_THROW_FBAD_ARG); continue;
        case OP_FACOSH: FNEED(1); FRES(acosh(fp[-1]), FBRL_THROW_FBAD_ARG); continue;
        case OP_FATANH: FNEED(1); FRES(atanh(fp[-1]), FBRL_THROW_FBAD_ARG); continue;
        case OP_FEXP: FNEED(1); FRES(exp(fp[-1]), FBRL_THROW_FRESULT_RANGE); continue;
        case OP_FEXPM1: FNEED(1); FRES(expm1(fp[-1]), FBRL_THROW_FRESULT_RANGE); continue;
        case OP_FLN: FNEED(1); FRES(log(fp[-1]), FBRL_THROW_FBAD_ARG); continue;
        case OP_FLNP1: FNEED(1); FRES(log1p(fp[-1]), FBRL_THROW_FBAD_ARG); continue;
        case OP_FLOG: FNEED(1); FRES(log10(fp[-1]), FBRL_THROW_FBAD_ARG); continue;
        case OP_FALOG: FNEED(1); FRES(pow(10.0, fp[-1]), FBRL_THROW_FRESULT_RANGE); continue;
        case OP_FPOW: FNEED(2); fp--; FRES(pow(fp[-1], fp[0]), FBRL_THROW_FBAD_ARG); continue;
        case OP_FLOOR: FNEED(1); fp[-1] = floor(fp[-1]); continue;
        case OP_FROUND: FNEED(1); fp[-1] = nearbyint(fp[-1]); continue;
        case OP_FTRUNC: FNEED(1); fp[-1] = trunc(fp[-1]); continue;
        case OP_FZEQ: FNEED(1); ROOM(1); *sp++ = FLAG(*--fp == 0); continue;
        case OP_FZLT: FNEED(1); ROOM(1); *sp++ = FLAG(*--fp < 0); continue;
        case OP_FZGT: FNEED(1); ROOM(1); *sp++ = FLAG(*--fp > 0); continue;
        case OP_FLT: FNEED(2); ROOM(1); fp -= 2; *sp++ = FLAG(fp[0] < fp[1]); continue;
        case OP_FGT: FNEED(2); ROOM(1); fp -= 2; *sp++ = FLAG(fp[0] > fp[1]); continue;
        case OP_FEQ: FNEED(2); ROOM(1); fp -= 2; *sp++ = FLAG(fp[0] == fp[1]); continue;
        case OP_FPROX: {
            FNEED(3); ROOM(1);
            fp -= 3;
            double x = fp[0], y = fp[1], e = fp[2];
            int r;
            if (e > 0) r = fabs(x - y) < e;
            else if (e == 0) r = memcmp(&x, &y, sizeof x) == 0;
            else r = fabs(x - y) < -e * (fabs(x) + fabs(y));
            *sp++ = FLAG(r);
            continue;
        }
        case OP_FFETCH: case OP_DFFETCH:
            NEED(1); FROOM(1); CHK(T, (fbrl_cell)sizeof(double)); *fp++ = ldf(*--sp); continue;
        case OP_FSTORE: case OP_DFSTORE:
            NEED(1); FNEED(1); CHK(T, (fbrl_cell)sizeof(double)); stf(*--sp, *--fp); continue;
        case OP_SFFETCH: { float f; NEED(1); FROOM(1); CHK(T, 4); memcpy(&f, (void *)*--sp, 4); *fp++ = f; continue; }
        case OP_SFSTORE: {
            float f; NEED(1); FNEED(1); CHK(T, 4);
            fa = *--fp;
            if (fabs(fa) > 3.4028234663852886e38) THROW(FBRL_THROW_FRESULT_RANGE);
            f = (float)fa; memcpy((void *)*--sp, &f, 4); continue;
        }
        case OP_FDUP: FNEED(1); FROOM(1); fp[0] = fp[-1]; fp++; continue;
        case OP_FDROP: FNEED(1); fp--; continue;
        case OP_FSWAP: FNEED(2); fa = fp[-1]; fp[-1] = fp[-2]; fp[-2] = fa; continue;
        case OP_FOVER: FNEED(2); FROOM(1); fp[0] = fp[-2]; fp++; continue;
        case OP_FROT: FNEED(3); fa = fp[-3]; fp[-3] = fp[-2]; fp[-2] = fp[-1]; fp[-1] = fa; continue;
        case OP_FNIP: FNEED(2); fp[-2] = fp[-1]; fp--; continue;
        case OP_FTUCK: FNEED(2); FROOM(1); fa = fp[-1]; fp[0] = fa; fp[-1] = fp[-2]; fp[-2] = fa; fp++; continue;
        case OP_FPICK:
            NEED(1); ua = U(*--sp);
            if (ua >= U(fp - fs0)) THROW(FBRL_THROW_FSTACK_UNDERFLOW);
            FROOM(1); fp[0] = fp[-1 - (fbrl_cell)ua]; fp++;
            continue;
        case OP_FDEPTH: ROOM(1); *sp++ = fp - fs0; continue;
        case OP_FTOS:
            FNEED(1); ROOM(1);
            fa = trunc(*--fp);
            if (!(fa >= -9.2233720368547758e18 && fa < 9.2233720368547758e18)) THROW(FBRL_THROW_RESULT_RANGE);
            *sp++ = (fbrl_cell)fa;
            continue;
        case OP_STOF: NEED(1); FROOM(1); *fp++ = (double)*--sp; continue;
        case OP_DTOF: NEED(2); FROOM(1); *fp++ = fbrl__d_to_f(S, T); sp -= 2; continue;
        case OP_FTOD:
            FNEED(1); ROOM(2);
            if ((code = fbrl__f_to_d(fp[-1], &sp[0], &sp[1]))) goto do_throw;
            fp--; sp += 2;
            continue;
        case OP_FLOATS: case OP_DFLOATS: NEED(1); T = (fbrl_cell)(U(T) * sizeof(double)); continue;
        case OP_FLOATPLUS: case OP_DFLOATPLUS: NEED(1); T = (fbrl_cell)(U(T) + sizeof(double)); continue;
        case OP_SFLOATS: NEED(1); T = (fbrl_cell)(U(T) * 4); continue;
        case OP_SFLOATPLUS: NEED(1); T = (fbrl_cell)(U(T) + 4); continue;
        case OP_FALIGN: case OP_DFALIGN: case OP_SFALIGN:
            ua = w == OP_SFALIGN ? 4 : sizeof(double);
            ub = U(vm->here);
            if ((code = fbrl__allot(vm, (fbrl_cell)(((ub + ua - 1) & ~(ua - 1)) - ub)))) goto do_throw;
            continue;
        case OP_FALIGNED: case OP_DFALIGNED: case OP_SFALIGNED:
            NEED(1);
            ua = w == OP_SFALIGNED ? 4 : sizeof(double);
            T = (fbrl_cell)((U(T) + ua - 1) & ~(ua - 1));
            continue;
        case OP_PRECISION: ROOM(1); *sp++ = vm->precision; continue;
        case OP_SETPRECISION:
            NEED(1); a = *--sp;
            vm->precision = a < 1 ? 1 : a > 17 ? 17 : (int)a;
            continue;
        case OP_FPI: FROOM(1); *fp++ = 3.14159265358979323846; continue;

        default:
        execute_xt: {
            fbrl_hdr *h = fbrl__xt_hdr(vm, w);
            if (!h) THROW(fbrl__throw_msg(vm, FBRL_THROW_UNDEFINED, "invalid execution token"));
            switch (h->kind) {
            case K_PRIM: defers = 0; w = h->op; goto dispatch;
            case K_COLON: defers = 0; POLL(); RROOM(1); *rp++ = (fbrl_cell)ip; JUMP(h->body); continue;
            case K_VAR: ROOM(1); *sp++ = h->body; continue;
            case K_CREATE:
                ROOM(1); *sp++ = h->body;
                if (h->does) { RROOM(1); *rp++ = (fbrl_cell)ip; JUMP(h->does); }
                continue;
            case K_CONST: case K_VALUE: ROOM(1); CHK(h->body, CELL); *sp++ = ld(h->body); continue;
            case K_2CONST: case K_2VALUE:
                ROOM(2); CHK(h->body, 2 * CELL);
                sp[0] = ld(h->body + CELL); sp[1] = ld(h->body); sp += 2;
                continue;
            case K_FCONST: case K_FVALUE:
                FROOM(1); CHK(h->body, (fbrl_cell)sizeof(double)); *fp++ = ldf(h->body); continue;
            case K_DEFER:
                CHK(h->body, CELL);
                w = ld(h->body);
                if (w == 0) THROW(fbrl__throw_msg(vm, FBRL_THROW_UNSUPPORTED, "deferred word not set (use IS)"));
                if (++defers > 1000) THROW(fbrl__throw_msg(vm, FBRL_THROW_UNSUPPORTED, "deferred words loop"));
                goto execute_xt;
            case K_CFUNC: {
                if (!h->fn && !h->xfn) THROW(FBRL_THROW_UNSUPPORTED);
                SAVE();
                vm->pending_throw = 0;
                fbrl_status st = h->xfn ? h->xfn(vm, h->arg, h->word) : h->fn(vm, h->arg);
                LOAD();
                if (sp < ds0 || sp > dse || fp < fs0 || fp > fse) { sp = ds0; fp = fs0; THROW(FBRL_THROW_STACK_UNDERFLOW); }
                if (st != FBRL_OK)
                    THROW(st == FBRL_ETHROW ? (vm->pending_throw ? vm->pending_throw : -1)
                                            : FBRL_THROW_STATUS(st));
                POLL(); /* a C word that waited (robot motion, I/O) may have been interrupted */
                continue;
            }
            case K_MARKER:
                if (vm->defining) THROW(fbrl__throw_msg(vm, FBRL_THROW_COMPILER_NESTING, "a MARKER cannot run inside a definition"));
                fbrl__forget(vm, (unsigned char *)h->body, (uint32_t)h->end, (size_t)h->does);
                continue;
            default: THROW(FBRL_THROW_UNSUPPORTED);
            }
        }
        }
        continue;

    do_throw:
        if (code == THROW_BYE || code == THROW_QUIT) goto out;
        {
            fbrl_cell hd = vm->handler;
            if (hd > entry && hd >= 5 && hd <= rp - rs0) {
                fbrl_cell *f = rs0 + hd - 5;
                rp = f;
                vm->handler = (f[3] >= 0 && f[3] <= hd - 5) ? f[3] : 0;
                sp = ds0 + (U(f[1]) < U(dse - ds0) ? f[1] : 0);
                fp = fs0 + (U(f[2]) <= U(fse - fs0) ? f[2] : 0);
                vm->err_captured = 0;
                if (!CODE_OK(f[0])) { code = FBRL_THROW_BAD_ADDRESS; goto do_throw; }
                ip = (const fbrl_cell *)f[0];
                *sp++ = code;
                code = 0;
                continue;
            }
        }
        goto out;
    }
out:
    SAVE();
    vm->nest--;
    return code;
}
