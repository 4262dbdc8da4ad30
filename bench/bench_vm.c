/* SPDX-License-Identifier: MIT */
/* bench_vm.c - speed of the FBRL language engine on classic Forth loads.
 * Usage: bench_vm            print the time of each load
 *        bench_vm --dump DIR write each load as DIR/<name>.fs (plain Forth-2012,
 *                            to run the same text in pforth or gforth) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "fbrl/vm.h"
#include "bench_util.h"

typedef struct load {
    const char *name, *setup, *run;
} load;

static const load loads[] = {
    {"fib", ": FIB ( n -- f ) DUP 2 < IF EXIT THEN DUP 1- RECURSE SWAP 2 - RECURSE + ;\n", "32 FIB DROP\n"},
    {"sieve",
     "8190 CONSTANT SIZE  CREATE FLAGS SIZE ALLOT\n"
     ": SIEVE ( -- n ) FLAGS SIZE 1 FILL 0 SIZE 0 DO FLAGS I + C@ IF I DUP + 3 + DUP I +\n"
     "  BEGIN DUP SIZE < WHILE 0 OVER FLAGS + C! OVER + REPEAT DROP DROP 1+ THEN LOOP ;\n"
     ": SIEVES 1000 0 DO SIEVE DROP LOOP ;\n",
     "SIEVES\n"},
    {"nested-loops", ": NEST ( -- n ) 0 10000 0 DO 1000 0 DO I J + + LOOP LOOP ;\n", "NEST DROP\n"},
    {"float-loop", ": FLOOP 0E0 5000000 0 DO I S>F 0.5E0 F* FSQRT F+ LOOP FDROP ;\n", "FLOOP\n"},
};

/* a large source text: 250 definitions (pforth's default dictionary holds no more),
 * each followed by 50 lines that interpret it and a few numbers */
static char *big_source(size_t *len)
{
    size_t cap = 4 << 20, n = 0;
    char *s = malloc(cap);
    if (!s)
        return NULL;
    for (int i = 0; i < 250; i++) {
        n += (size_t)snprintf(s + n, cap - n, ": W%d ( a -- b ) %d DUP + SWAP DROP 3 0 DO I DROP LOOP ;\n", i,
                              i);
        for (int j = 0; j < 50 && n + 200 < cap; j++)
            n += (size_t)snprintf(s + n, cap - n, "%d W%d DROP %d %d + 2 * DROP \\ comment %d\n", j, i, i, j,
                                  j);
    }
    *len = n;
    return s;
}

static void out(void *user, const char *s, size_t n)
{
    (void)user;
    fwrite(s, 1, n, stdout);
}

int main(int argc, char **argv)
{
    size_t blen;
    char *big = big_source(&blen);
    if (!big)
        return 1;
    if (argc == 3 && strcmp(argv[1], "--dump") == 0) {
        for (size_t i = 0; i <= sizeof loads / sizeof loads[0]; i++) {
            char path[512];
            snprintf(path, sizeof path, "%s/%s.fs", argv[2],
                     i < sizeof loads / sizeof loads[0] ? loads[i].name : "big-source");
            FILE *f = fopen(path, "w");
            if (!f)
                return 1;
            if (i < sizeof loads / sizeof loads[0])
                fprintf(f, "%s%s", loads[i].setup, loads[i].run);
            else
                fwrite(big, 1, blen, f);
            fprintf(f, "BYE\n");
            fclose(f);
        }
        free(big);
        return 0;
    }
    size_t size = 8u << 20;
    void *mem = malloc(size);
    if (!mem)
        return 1;
    printf("%-14s %10s\n", "load", "seconds");
    for (size_t i = 0; i <= sizeof loads / sizeof loads[0]; i++) {
        fbrl_vm_config cfg;
        fbrl_vm *vm;
        memset(&cfg, 0, sizeof cfg);
        cfg.mem = mem;
        cfg.mem_size = size;
        cfg.host.write = out;
        if (fbrl_vm_create(&vm, &cfg) != FBRL_OK)
            return 1;
        const char *name = i < sizeof loads / sizeof loads[0] ? loads[i].name : "big-source";
        double t0;
        fbrl_status st;
        if (i < sizeof loads / sizeof loads[0]) {
            if (fbrl_vm_eval(vm, loads[i].setup, strlen(loads[i].setup)) != FBRL_OK)
                return 1;
            t0 = bench_now();
            st = fbrl_vm_eval(vm, loads[i].run, strlen(loads[i].run));
        } else {
            t0 = bench_now();
            st = fbrl_vm_eval(vm, big, blen);
        }
        double t = bench_now() - t0;
        if (st != FBRL_OK) {
            printf("%s failed: %s\n", name, fbrl_vm_last_error(vm)->message);
            return 1;
        }
        printf("%-14s %10.4f\n", name, t);
    }
    free(mem);
    free(big);
    return 0;
}
