/* SPDX-License-Identifier: MIT */
/* words_io.c - number and float output, the console's words (KEY EMIT TYPE ...), WORDS,
 * DUMP, HELP and MS beside tasks: the engine's words that talk to its host. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fbrl/num.h"
#include "words_stack.h"

#define U(x) ((fbrl_ucell)(x))

/* ---- number and float output ---- */
static int get_base(fbrl_vm *vm, unsigned *b)
{
    fbrl_cell x = *vm->base;
    if (x < 2 || x > 36) {
        *vm->base = 10;
        return fbrl__throw_msg(vm, FBRL_THROW_BAD_NUMBER, "invalid BASE (reset to decimal)");
    }
    *b = (unsigned)x;
    return 0;
}

static char digit_char(fbrl_ucell d) { return (char)(d < 10 ? '0' + d : 'A' + d - 10); }

/* ud / base in place, returns the remainder */
static fbrl_ucell ud_divsmall(fbrl_ucell *lo, fbrl_ucell *hi, unsigned base)
{
    fbrl_ucell qh = *hi / base, r = *hi % base, ql;
    fbrl__udiv(r, *lo, base, &ql, &r);
    *hi = qh;
    *lo = ql;
    return r;
}

/* n spaces in chunks, so a huge count (`1E11 SPACES`, a wide `.R`) stays interruptible. */
int fbrl__spaces(fbrl_vm *vm, fbrl_cell n)
{
    static const char blanks[64] = "                                                                ";
    while (n > 0) {
        size_t k = n > (fbrl_cell)sizeof blanks ? sizeof blanks : (size_t)n;
        if (fbrl__take_interrupt(vm))
            return FBRL_THROW_INTERRUPT;
        fbrl__write(vm, blanks, k);
        n -= (fbrl_cell)k;
    }
    return 0;
}

static int print_d(fbrl_vm *vm, fbrl_cell lo, fbrl_cell hi, int is_signed, fbrl_cell width, int space)
{
    unsigned base = 10;
    int r = get_base(vm, &base);
    if (r)
        return r;
    char b[CELL_BITS * 2 + 4], *e = b + sizeof b, *p = e;
    fbrl_ucell l = U(lo), h = U(hi);
    int neg = is_signed && hi < 0;
    if (neg)
        fbrl__dneg(&l, &h);
    do
        *--p = digit_char(ud_divsmall(&l, &h, base));
    while (l || h);
    if (neg)
        *--p = '-';
    if ((r = fbrl__spaces(vm, width - (fbrl_cell)(e - p))))
        return r;
    fbrl__write(vm, p, (size_t)(e - p));
    if (space)
        fbrl__write(vm, " ", 1);
    return 0;
}

static int hold_char(fbrl_vm *vm, char c)
{
    if (vm->hld <= vm->hold || vm->hld > vm->hold + FBRL_HOLDSIZE)
        return FBRL_THROW_PICTURED_OVERFLOW;
    *--vm->hld = c;
    return 0;
}

/* REPRESENT: u significant digits of r; returns validity */
static int represent(double r, char *out, int u, int *exp, int *neg)
{
    char t[64];
    *neg = signbit(r) != 0;
    *exp = 0;
    if (!isfinite(r)) {
        for (int i = 0; i < u; i++)
            out[i] = isnan(r) ? 'n' : 'i';
        return 0;
    }
    int d = u < 1 ? 1 : u > 17 ? 17 : u, e10 = 0;
    fbrl_num_digits(r, d, t, &e10); /* locale-free "%.*e" */
    for (int i = 0; i < u; i++)
        out[i] = i < d ? t[i] : '0';
    *exp = r == 0 ? 1 : e10 + 1;
    return 1;
}

static int print_float(fbrl_vm *vm, double r, int mode)
{
    char dg[20], b[400];
    int exp, neg, prec = vm->precision, k = 0;
    if (!represent(r, dg, prec, &exp, &neg)) {
        fbrl__puts(vm, isnan(r) ? "NaN " : neg ? "-Inf " : "Inf ");
        return 0;
    }
    if (neg)
        b[k++] = '-';
    if (mode == 0) { /* F. fixed point, trailing zeros dropped */
        int last = prec;
        while (last > 0 && dg[last - 1] == '0')
            last--;
        if (exp <= 0) {
            b[k++] = '0';
            b[k++] = '.';
            for (int i = 0; i < -exp && k < 350; i++)
                b[k++] = '0';
            for (int i = 0; i < last; i++)
                b[k++] = dg[i];
        } else {
            for (int i = 0; i < exp && k < 350; i++)
                b[k++] = i < prec ? dg[i] : '0';
            b[k++] = '.';
            for (int i = exp; i < last; i++)
                b[k++] = dg[i];
        }
    } else { /* FS. scientific, FE. engineering */
        int lead = 1, e = exp - 1;
        if (mode == 2) {
            int m = ((e % 3) + 3) % 3;
            lead += m;
            e -= m;
            if (lead > prec) { /* not enough digits: pad */
                for (int i = prec; i < lead; i++)
                    dg[i] = '0';
                prec = lead;
            }
        }
        for (int i = 0; i < lead; i++)
            b[k++] = dg[i];
        b[k++] = '.';
        for (int i = lead; i < prec; i++)
            b[k++] = dg[i];
        k += snprintf(b + k, sizeof b - (size_t)k, "E%d", r == 0 ? 0 : e);
    }
    b[k++] = ' ';
    fbrl__write(vm, b, (size_t)k);
    return 0;
}

static int words_line(void *ctx, const char *name, size_t len)
{
    fbrl_vm *vm = ctx;
    fbrl__write(vm, name, len);
    fbrl__write(vm, " ", 1);
    return 0;
}

#define KEY_POLL_US 10000u /* KEY beside tasks: how often it looks for a key */

/* MS while other tasks exist: they run until the time has come; the argument stays on
 * the stack until then (a background task's MS runs again when it resumes). */
static int ms_beside_tasks(fbrl_vm *vm)
{
    int r;
    if ((r = need(vm, 1)))
        return r;
    if (!vm->host.sleep_ms || !vm->host.now_us)
        return fbrl__throw_msg(vm, FBRL_THROW_UNSUPPORTED, "no clock in this host");
    fbrl_cell v = vm->sp[-1];
    uint64_t due = fbrl__wait_begin(vm)->since_us + (v > 0 ? (uint64_t)v * 1000u : 0);
    for (;;) {
        if (vm->host.now_us(vm->host.user) >= due) {
            vm->sp--;
            return 0;
        }
        if ((r = vm->task_pause(vm, due, 0)))
            return r;
    }
}

int fbrl__w_io(fbrl_vm *vm, int op)
{
    fbrl_cell a, u, v, w;
    double f;
    int r;
    unsigned base = 10;
    switch (op) {
    case OP_KEY:
        if (!vm->host.key)
            return fbrl__throw_msg(vm, FBRL_THROW_UNSUPPORTED, "no console input in this host");
        if (vm->ntasks && vm->host.key_ready && vm->host.now_us) /* other tasks run until a key comes */
            for (fbrl__wait_begin(vm); !vm->host.key_ready(vm->host.user);)
                if ((r = vm->task_pause(vm, vm->host.now_us(vm->host.user) + KEY_POLL_US, 0)))
                    return r;
        r = vm->host.key(vm->host.user);
        if (r < 0)
            return FBRL_THROW_CHAR_IO;
        return push(vm, (unsigned char)r);
    case OP_KEYQ:
        if (!vm->host.key_ready)
            return fbrl__throw_msg(vm, FBRL_THROW_UNSUPPORTED, "no console input in this host");
        return push(vm, vm->host.key_ready(vm->host.user) ? -1 : 0);
    case OP_ACCEPT: {
        if ((r = need(vm, 2)))
            return r;
        u = *--vm->sp;
        a = *--vm->sp;
        if (u < 0)
            return FBRL_THROW_BAD_NUMBER;
        if (u && !fbrl__addr_ok(vm, a, u))
            return FBRL_THROW_BAD_ADDRESS;
        if (!vm->host.key)
            return fbrl__throw_msg(vm, FBRL_THROW_UNSUPPORTED, "no console input in this host");
        fbrl_cell k = 0;
        for (;;) {
            int c = vm->host.key(vm->host.user);
            if (c < 0 || c == '\n' || c == '\r')
                break;
            if (k < u)
                ((char *)a)[k++] = (char)c;
        }
        return push(vm, k);
    }
    case OP_DOT:
    case OP_UDOT:
        if ((r = pop(vm, &v)))
            return r;
        return print_d(vm, v, op == OP_DOT && v < 0 ? -1 : 0, op == OP_DOT, 0, 1);
    case OP_DOTR:
    case OP_UDOTR:
        if ((r = need(vm, 2)))
            return r;
        w = *--vm->sp;
        v = *--vm->sp;
        return print_d(vm, v, op == OP_DOTR && v < 0 ? -1 : 0, op == OP_DOTR, w, 0);
    case OP_DDOT:
    case OP_UDDOT:
        if ((r = need(vm, 2)))
            return r;
        vm->sp -= 2;
        return print_d(vm, vm->sp[0], vm->sp[1], op == OP_DDOT, 0, 1);
    case OP_DDOTR:
        if ((r = need(vm, 3)))
            return r;
        vm->sp -= 3;
        return print_d(vm, vm->sp[0], vm->sp[1], 1, vm->sp[2], 0);
    case OP_QUESTION:
        if ((r = pop(vm, &a)))
            return r;
        if (!fbrl__addr_ok(vm, a, CELL))
            return FBRL_THROW_BAD_ADDRESS;
        memcpy(&v, (void *)a, sizeof v);
        return print_d(vm, v, v < 0 ? -1 : 0, 1, 0, 1);
    case OP_LTNUM: vm->hld = vm->hold + FBRL_HOLDSIZE; return 0;
    case OP_NUM:
    case OP_NUMS: {
        if ((r = need(vm, 2)) || (r = get_base(vm, &base)))
            return r;
        fbrl_ucell lo = U(vm->sp[-2]), hi = U(vm->sp[-1]);
        do {
            if ((r = hold_char(vm, digit_char(ud_divsmall(&lo, &hi, base)))))
                return r;
        } while (op == OP_NUMS && (lo || hi));
        vm->sp[-2] = (fbrl_cell)lo;
        vm->sp[-1] = (fbrl_cell)hi;
        return 0;
    }
    case OP_NUMGT:
        if ((r = need(vm, 2)))
            return r;
        if (vm->hld < vm->hold || vm->hld > vm->hold + FBRL_HOLDSIZE)
            vm->hld = vm->hold + FBRL_HOLDSIZE;
        vm->sp[-2] = (fbrl_cell)vm->hld;
        vm->sp[-1] = (fbrl_cell)(vm->hold + FBRL_HOLDSIZE - vm->hld);
        return 0;
    case OP_HOLD:
        if ((r = pop(vm, &v)))
            return r;
        return hold_char(vm, (char)v);
    case OP_HOLDS: {
        const char *s;
        size_t n;
        if ((r = pop_str(vm, &s, &n)))
            return r;
        while (n > 0)
            if ((r = hold_char(vm, s[--n])))
                return r;
        return 0;
    }
    case OP_SIGN:
        if ((r = pop(vm, &v)))
            return r;
        return v < 0 ? hold_char(vm, '-') : 0;
    case OP_DOTS: {
        char b[24];
        int k = snprintf(b, sizeof b, "<%ld> ", (long)(vm->sp - vm->ds0));
        fbrl__write(vm, b, (size_t)k);
        for (fbrl_cell *p = vm->ds0; p < vm->sp; p++)
            if ((r = print_d(vm, *p, *p < 0 ? -1 : 0, 1, 0, 1)))
                return r;
        if (vm->fp > vm->fs0) {
            k = snprintf(b, sizeof b, "F: <%ld> ", (long)(vm->fp - vm->fs0));
            fbrl__write(vm, b, (size_t)k);
            for (double *p = vm->fs0; p < vm->fp; p++)
                print_float(vm, *p, 1);
        }
        fbrl__write(vm, "\n", 1);
        return 0;
    }
    case OP_DUMP: {
        if ((r = need(vm, 2)))
            return r;
        u = *--vm->sp;
        a = *--vm->sp;
        if (u < 0)
            return FBRL_THROW_BAD_NUMBER;
        if (u && !fbrl__addr_ok(vm, a, u))
            return FBRL_THROW_BAD_ADDRESS;
        for (fbrl_cell i = 0; i < u; i += 16) {
            char b[100];
            int k = snprintf(b, sizeof b, "%0*lx ", (int)(2 * sizeof(fbrl_cell)), (unsigned long)U(a + i));
            for (fbrl_cell j = 0; j < 16; j++) {
                if (i + j < u)
                    k += snprintf(b + k, sizeof b - (size_t)k, " %02x", ((unsigned char *)a)[i + j]);
                else
                    k += snprintf(b + k, sizeof b - (size_t)k, "   ");
            }
            b[k++] = ' ';
            b[k++] = ' ';
            for (fbrl_cell j = 0; j < 16 && i + j < u; j++) {
                unsigned char c = ((unsigned char *)a)[i + j];
                b[k++] = (char)(c >= 32 && c < 127 ? c : '.');
            }
            b[k++] = '\n';
            fbrl__write(vm, b, (size_t)k);
        }
        return 0;
    }
    case OP_WORDS:
        fbrl_vm_words(vm, words_line, vm);
        fbrl__write(vm, "\n", 1);
        return 0;
    case OP_MS:
        if (vm->ntasks) /* other tasks run while this one waits (task.c) */
            return ms_beside_tasks(vm);
        if ((r = pop(vm, &v)))
            return r;
        if (!vm->host.sleep_ms)
            return fbrl__throw_msg(vm, FBRL_THROW_UNSUPPORTED, "no clock in this host");
        if (v > 0)
            vm->host.sleep_ms(vm->host.user, (uint32_t)(v > 0x7fffffff ? 0x7fffffff : v));
        return fbrl__take_interrupt(vm) ? FBRL_THROW_INTERRUPT
                                        : 0; /* a host may cut the sleep short on Ctrl-C */
    case OP_TIMEDATE: {
        int t[6] = {0};
        if (!vm->host.time_date)
            return fbrl__throw_msg(vm, FBRL_THROW_UNSUPPORTED, "no clock in this host");
        if (vm->ds_end - vm->sp < 6)
            return FBRL_THROW_STACK_OVERFLOW;
        vm->host.time_date(vm->host.user, t);
        for (int i = 0; i < 6; i++)
            *vm->sp++ = t[i];
        return 0;
    }
    case OP_USECS: {
        if (!vm->host.now_us)
            return fbrl__throw_msg(vm, FBRL_THROW_UNSUPPORTED, "no clock in this host");
        uint64_t t = vm->host.now_us(vm->host.user);
        if ((r = push(vm, (fbrl_cell)t)))
            return r;
        return push(vm, sizeof(fbrl_cell) >= 8 ? 0 : (fbrl_cell)(t >> 31 >> 1));
    }
    case OP_FDOT:
    case OP_FSDOT:
    case OP_FEDOT:
        if ((r = fpop(vm, &f)))
            return r;
        return print_float(vm, f, op == OP_FDOT ? 0 : op == OP_FSDOT ? 1 : 2);
    case OP_REPRESENT: {
        int exp, neg, ok;
        char dg[64];
        if ((r = need(vm, 2)))
            return r;
        u = vm->sp[-1];
        a = vm->sp[-2];
        if (u < 0)
            return FBRL_THROW_BAD_NUMBER;
        if (u && !fbrl__addr_ok(vm, a, u))
            return FBRL_THROW_BAD_ADDRESS;
        if ((r = fpop(vm, &f)))
            return r;
        ok = represent(f, dg, u > 17 ? 17 : (int)u, &exp, &neg);
        if (u)
            memcpy((void *)a, dg, (size_t)(u > 17 ? 17 : u));
        if (u > 17)
            memset((char *)a + 17, '0', (size_t)(u - 17));
        vm->sp[-2] = exp;
        vm->sp[-1] = neg ? -1 : 0;
        return push(vm, ok ? -1 : 0);
    }
    case OP_TOFLOAT: {
        const char *s;
        size_t n, i = 0;
        if ((r = pop_str(vm, &s, &n)))
            return r;
        while (i < n && s[i] == ' ')
            i++;
        if (i == n) {
            if ((r = fpush(vm, 0.0)))
                return r;
            return push(vm, -1);
        }
        if (fbrl__parse_float(s, n, 0, &f)) {
            if ((r = fpush(vm, f)))
                return r;
            return push(vm, -1);
        }
        return push(vm, 0);
    }
    }
    return FBRL_THROW_UNSUPPORTED;
}
