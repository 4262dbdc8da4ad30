/* SPDX-License-Identifier: MIT */
/* atomic.h - the acquire/release loads and stores that the SPSC rings and the UART
 * core need, and the compare-and-swap of the run's request lock (src/method_run.c), in one
 * place (internal header, not installed).
 *
 * Every shared value is a size_t with a single writer, so a load-acquire paired with
 * a store-release is all the ordering required:
 *  - GCC and Clang (any -std, hosted or freestanding -m32): the __atomic builtins,
 *    which compile to plain moves on x86 and are understood by ThreadSanitizer;
 *  - another C11 compiler with <stdatomic.h>: a volatile access plus a thread fence;
 *  - anything else: a volatile access and nothing more, which is correct only for an
 *    interrupt handler and the main line sharing one CPU (the thesis's PC). */
#ifndef FBRL_ATOMIC_H
#define FBRL_ATOMIC_H

#include <stddef.h>

#if defined(__GNUC__) || defined(__clang__)

static inline size_t fbrl_load_acq(const size_t *p) { return __atomic_load_n(p, __ATOMIC_ACQUIRE); }
static inline size_t fbrl_load_rlx(const size_t *p) { return __atomic_load_n(p, __ATOMIC_RELAXED); }
static inline void fbrl_store_rel(size_t *p, size_t v) { __atomic_store_n(p, v, __ATOMIC_RELEASE); }
static inline void fbrl_store_rlx(size_t *p, size_t v) { __atomic_store_n(p, v, __ATOMIC_RELAXED); }
/* *p from expect to v if it is expect (acquire): 1 if it was */
static inline int fbrl_cas_acq(size_t *p, size_t expect, size_t v)
{
    return __atomic_compare_exchange_n(p, &expect, v, 0, __ATOMIC_ACQUIRE, __ATOMIC_RELAXED);
}

#else

#if defined(__STDC_VERSION__) && __STDC_VERSION__ >= 201112L && !defined(__STDC_NO_ATOMICS__)
#include <stdatomic.h>
#define FBRL_FENCE_ACQ_() atomic_thread_fence(memory_order_acquire)
#define FBRL_FENCE_REL_() atomic_thread_fence(memory_order_release)
#else
#define FBRL_FENCE_ACQ_() ((void)0)
#define FBRL_FENCE_REL_() ((void)0)
#endif

static inline size_t fbrl_load_acq(const size_t *p)
{
    size_t v = *(const volatile size_t *)p;
    FBRL_FENCE_ACQ_();
    return v;
}
static inline size_t fbrl_load_rlx(const size_t *p) { return *(const volatile size_t *)p; }
static inline void fbrl_store_rel(size_t *p, size_t v)
{
    FBRL_FENCE_REL_();
    *(volatile size_t *)p = v;
}
static inline void fbrl_store_rlx(size_t *p, size_t v) { *(volatile size_t *)p = v; }
/* without the builtins: one CPU only (an interrupt handler never takes the run's lock) */
static inline int fbrl_cas_acq(size_t *p, size_t expect, size_t v)
{
    if (*(volatile size_t *)p != expect)
        return 0;
    *(volatile size_t *)p = v;
    FBRL_FENCE_ACQ_();
    return 1;
}

#endif
#endif
