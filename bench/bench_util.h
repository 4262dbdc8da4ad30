/* SPDX-License-Identifier: MIT */
/* bench_util.h - what the bench programs share: a monotonic clock in seconds and a timed
 * Forth evaluation that ends the program on a Forth error (a bench figure of a failed
 * run would mean nothing). Static inline, so a bench uses only what it needs. */
#ifndef BENCH_UTIL_H
#define BENCH_UTIL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fbrl/vm.h"

static inline double bench_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* Evaluate src in vm; the seconds it took. */
static inline double bench_eval(fbrl_vm *vm, const char *src)
{
    double t0 = bench_now();
    if (fbrl_vm_eval(vm, src, strlen(src)) != FBRL_OK) {
        fprintf(stderr, "'%s': %s\n", src, fbrl_vm_last_error(vm)->message);
        exit(1);
    }
    return bench_now() - t0;
}

#endif
