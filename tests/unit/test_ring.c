/* SPDX-License-Identifier: MIT */
/* test_ring.c - the SPSC byte ring: queue semantics against a reference model,
 * wrap-around at every offset, bad input, and a two-thread stress run that moves
 * at least 100 MB in random chunks and checks every byte's value and order.
 *
 * The stress size comes from FBRL_RING_STRESS_MB (default 100). Under
 * ThreadSanitizer the target stays 100 MB (about 10 s on this 2-core machine when
 * idle) but the run also stops at a 12 s deadline, because a loaded machine took 25 s:
 * the producer then publishes how far it got and the consumer checks exactly that
 * much (at least 10 MB are required). The test prints what it moved. */
/* ctest-labels: threads */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <stdio.h>
#include <pthread.h>
#include <sched.h>
#include <time.h>
#include <cmocka.h>

#include "fbrl/ring.h"

/* xorshift32: cheap deterministic stream for data and for chunk sizes. */
static uint32_t rnd(uint32_t *s)
{
    uint32_t x = *s;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    return *s = x;
}

static void bad_input_gives_errors(void **state)
{
    (void)state;
    fbrl_ring r;
    uint8_t mem[8], b = 0, out[4];
    size_t n = 99;

    assert_int_equal(fbrl_ring_init(NULL, mem, sizeof mem), FBRL_EINVAL);
    assert_int_equal(fbrl_ring_init(&r, NULL, sizeof mem), FBRL_EINVAL);
    assert_int_equal(fbrl_ring_init(&r, mem, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_ring_init(&r, mem, 1), FBRL_EINVAL);

    /* A zeroed (never initialised) ring and a NULL ring refuse everything. */
    fbrl_ring *rings[2] = {NULL, &r};
    memset(&r, 0, sizeof r);
    for (int i = 0; i < 2; i++) {
        fbrl_ring *q = rings[i];
        assert_int_equal(fbrl_ring_put(q, 1), FBRL_EINVAL);
        assert_int_equal(fbrl_ring_get(q, &b), FBRL_EINVAL);
        assert_int_equal(fbrl_ring_write(q, "ab", 2, &n), FBRL_EINVAL);
        assert_int_equal(fbrl_ring_read(q, out, 2, &n), FBRL_EINVAL);
        assert_int_equal(fbrl_ring_peek(q, out, 2, &n), FBRL_EINVAL);
        assert_int_equal(fbrl_ring_skip(q, 0), FBRL_EINVAL);
        assert_int_equal(fbrl_ring_reset(q), FBRL_EINVAL);
        assert_int_equal(fbrl_ring_count(q), 0);
        assert_int_equal(fbrl_ring_space(q), 0);
        assert_int_equal(fbrl_ring_capacity(q), 0);
        assert_true(fbrl_ring_empty(q));
        assert_true(fbrl_ring_full(q));
    }

    assert_int_equal(fbrl_ring_init(&r, mem, 2), FBRL_OK);
    assert_int_equal(fbrl_ring_get(&r, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_ring_write(&r, NULL, 1, &n), FBRL_EINVAL);
    assert_int_equal(fbrl_ring_write(&r, "a", 1, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_ring_read(&r, NULL, 1, &n), FBRL_EINVAL);
    assert_int_equal(fbrl_ring_read(&r, out, 1, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_ring_peek(&r, NULL, 1, &n), FBRL_EINVAL);
    assert_int_equal(fbrl_ring_peek(&r, out, 1, NULL), FBRL_EINVAL);
    /* Zero-length transfers with NULL buffers are fine and move nothing. */
    assert_int_equal(fbrl_ring_write(&r, NULL, 0, &n), FBRL_OK);
    assert_int_equal(n, 0);
    assert_int_equal(fbrl_ring_read(&r, NULL, 0, &n), FBRL_OK);
    assert_int_equal(n, 0);
    /* Errors leave the ring untouched. */
    assert_int_equal(fbrl_ring_count(&r), 0);
    assert_int_equal(fbrl_ring_skip(&r, 1), FBRL_ERANGE);
}

/* Any size >= 2 is accepted; the capacity is the largest power of two that fits. */
static void capacity_is_largest_power_of_two(void **state)
{
    (void)state;
    static uint8_t mem[5000];
    const size_t sizes[][2] = {{2, 2},      {3, 2},      {4, 4},       {5, 4},       {7, 4},      {8, 8},
                               {1000, 512}, {1023, 512}, {1024, 1024}, {4096, 4096}, {5000, 4096}};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        fbrl_ring r;
        assert_int_equal(fbrl_ring_init(&r, mem, sizes[i][0]), FBRL_OK);
        assert_int_equal(fbrl_ring_capacity(&r), sizes[i][1]);
        assert_int_equal(fbrl_ring_space(&r), sizes[i][1]);
    }
    /* The largest size does not overflow the computation (storage is never touched). */
    fbrl_ring r;
    assert_int_equal(fbrl_ring_init(&r, mem, SIZE_MAX), FBRL_OK);
    assert_int_equal(fbrl_ring_capacity(&r), (SIZE_MAX >> 1) + 1);
}

/* The thesis's five queue words; every byte of the capacity is usable. */
static void queue_words_and_full_capacity(void **state)
{
    (void)state;
    fbrl_ring r;
    uint8_t mem[5], b; /* capacity 4; the fifth byte is never written */
    mem[4] = 0x5A;
    assert_int_equal(fbrl_ring_init(&r, mem, sizeof mem), FBRL_OK);
    assert_true(fbrl_ring_empty(&r));
    assert_false(fbrl_ring_full(&r));
    assert_int_equal(fbrl_ring_get(&r, &b), FBRL_EEMPTY);
    for (int round = 0; round < 7; round++) { /* repeated so the offsets wrap */
        for (uint8_t i = 0; i < 4; i++) {
            assert_false(fbrl_ring_full(&r));
            assert_int_equal(fbrl_ring_put(&r, (uint8_t)(round * 10 + i)), FBRL_OK);
            assert_false(fbrl_ring_empty(&r));
        }
        assert_true(fbrl_ring_full(&r));
        assert_int_equal(fbrl_ring_count(&r), 4);
        assert_int_equal(fbrl_ring_space(&r), 0);
        assert_int_equal(fbrl_ring_put(&r, 0xEE), FBRL_EFULL);
        for (uint8_t i = 0; i < 4; i++) {
            assert_int_equal(fbrl_ring_get(&r, &b), FBRL_OK);
            assert_int_equal(b, round * 10 + i);
        }
        assert_true(fbrl_ring_empty(&r));
        assert_int_equal(fbrl_ring_get(&r, &b), FBRL_EEMPTY);
    }
    assert_int_equal(fbrl_ring_capacity(&r), 4);
    assert_int_equal(mem[4], 0x5A);
}

/* Bulk calls split at every possible offset, and report partial transfers. */
static void bulk_wraps_at_every_offset(void **state)
{
    (void)state;
    const size_t sizes[] = {2, 4, 8, 16, 64};
    for (size_t si = 0; si < sizeof sizes / sizeof sizes[0]; si++) {
        size_t size = sizes[si];
        uint8_t mem[100], in[200], out[200];
        for (size_t i = 0; i < sizeof in; i++)
            in[i] = (uint8_t)(i * 37 + 11);
        for (size_t off = 0; off < size; off++) {
            for (size_t len = 1; len <= size; len++) {
                fbrl_ring r;
                size_t n;
                assert_int_equal(fbrl_ring_init(&r, mem, size), FBRL_OK);
                /* Move the indices to off (via a full lap, to use the mirror half too). */
                for (size_t k = 0; k < size + off; k++) {
                    uint8_t b;
                    assert_int_equal(fbrl_ring_put(&r, 0), FBRL_OK);
                    assert_int_equal(fbrl_ring_get(&r, &b), FBRL_OK);
                }
                assert_int_equal(fbrl_ring_write(&r, in, len, &n), FBRL_OK);
                assert_int_equal(n, len);
                /* Asking for more than the room gives exactly the room. */
                assert_int_equal(fbrl_ring_write(&r, in + len, size, &n), len == size ? FBRL_EFULL : FBRL_OK);
                assert_int_equal(n, size - len);
                memset(out, 0, sizeof out);
                assert_int_equal(fbrl_ring_peek(&r, out, 2 * size, &n), FBRL_OK);
                assert_int_equal(n, size);
                assert_memory_equal(out, in, size);
                assert_int_equal(fbrl_ring_read(&r, out, 2 * size, &n), FBRL_OK);
                assert_int_equal(n, size);
                assert_memory_equal(out, in, size);
                assert_int_equal(fbrl_ring_read(&r, out, 1, &n), FBRL_EEMPTY);
                assert_int_equal(n, 0);
            }
        }
    }
}

/* Random mix of every operation against a plain array model. */
static void random_ops_match_model(void **state)
{
    (void)state;
    enum { SIZE = 64, MODEL = 1 << 16 };
    static uint8_t model[MODEL];
    size_t mh = 0, mt = 0; /* model head/tail, never wrap within the run */
    uint8_t mem[SIZE], buf[3 * SIZE];
    fbrl_ring r;
    uint32_t seed = 12345, val = 777;
    assert_int_equal(fbrl_ring_init(&r, mem, SIZE), FBRL_OK);
    for (int step = 0; step < 20000 && mh + 3 * SIZE < MODEL; step++) {
        size_t cnt = mh - mt, n, len = rnd(&seed) % (2 * SIZE);
        switch (rnd(&seed) % 6) {
        case 0: { /* put */
            uint8_t b = (uint8_t)rnd(&val);
            fbrl_status st = fbrl_ring_put(&r, b);
            assert_int_equal(st, cnt == SIZE ? FBRL_EFULL : FBRL_OK);
            if (st == FBRL_OK)
                model[mh++] = b;
            break;
        }
        case 1: { /* get */
            uint8_t b;
            fbrl_status st = fbrl_ring_get(&r, &b);
            assert_int_equal(st, cnt == 0 ? FBRL_EEMPTY : FBRL_OK);
            if (st == FBRL_OK)
                assert_int_equal(b, model[mt++]);
            break;
        }
        case 2: /* write */
            for (size_t i = 0; i < len; i++)
                buf[i] = (uint8_t)rnd(&val);
            fbrl_ring_write(&r, buf, len, &n);
            assert_int_equal(n, len < SIZE - cnt ? len : SIZE - cnt);
            memcpy(model + mh, buf, n);
            mh += n;
            break;
        case 3: /* read */
            fbrl_ring_read(&r, buf, len, &n);
            assert_int_equal(n, len < cnt ? len : cnt);
            assert_memory_equal(buf, model + mt, n);
            mt += n;
            break;
        case 4: /* peek then skip part of it */
            fbrl_ring_peek(&r, buf, len, &n);
            assert_int_equal(n, len < cnt ? len : cnt);
            assert_memory_equal(buf, model + mt, n);
            assert_int_equal(fbrl_ring_skip(&r, n / 2), FBRL_OK);
            mt += n / 2;
            break;
        default: assert_int_equal(fbrl_ring_skip(&r, cnt + 1), FBRL_ERANGE); break;
        }
        assert_int_equal(fbrl_ring_count(&r), mh - mt);
        assert_int_equal(fbrl_ring_space(&r), SIZE - (mh - mt));
    }
    assert_int_equal(fbrl_ring_reset(&r), FBRL_OK);
    assert_true(fbrl_ring_empty(&r));
}

/* Two threads: a producer and a consumer share one ring, as an interrupt handler
 * and the main line do. Both derive the byte stream from the same generator, so a
 * lost, duplicated or reordered byte shows as a mismatch at that position. */
#if defined(__SANITIZE_THREAD__)
#define UNDER_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define UNDER_TSAN 1
#endif
#endif
#ifdef UNDER_TSAN
#define STRESS_DEADLINE_NS 12000000000LL
#else
#define STRESS_DEADLINE_NS 0 /* none: always the full amount */
#endif

static int64_t mono_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000LL + ts.tv_nsec;
}

struct stress {
    fbrl_ring ring;
    uint64_t total; /* producer's target; lowered (atomically) at the deadline */
    uint32_t data_seed, chunk_seed;
    uint64_t mismatch_at; /* UINT64_MAX when none */
};

static void *producer(void *arg)
{
    struct stress *s = arg;
    uint32_t data = s->data_seed, chunk = s->chunk_seed;
    uint8_t buf[1024];
    uint64_t sent = 0;
    int64_t deadline = STRESS_DEADLINE_NS ? mono_ns() + STRESS_DEADLINE_NS : 0;
    while (sent < s->total) {
        if (deadline && (sent & 0xFFFF) < 1024 && mono_ns() > deadline) {
            __atomic_store_n(&s->total, sent, __ATOMIC_RELEASE);
            break;
        }
        uint32_t c = rnd(&chunk);
        size_t len = 1 + c % sizeof buf;
        if (len > s->total - sent)
            len = (size_t)(s->total - sent);
        for (size_t i = 0; i < len; i++)
            buf[i] = (uint8_t)(rnd(&data) >> 24);
        size_t done = 0;
        bool single = (c >> 28) == 0; /* one chunk in 16 goes byte by byte */
        while (done < len) {
            size_t n = 0;
            if (single)
                n = fbrl_ring_put(&s->ring, buf[done]) == FBRL_OK;
            else
                fbrl_ring_write(&s->ring, buf + done, len - done, &n);
            if (n == 0)
                sched_yield();
            done += n;
        }
        sent += len;
    }
    return NULL;
}

static void *consumer(void *arg)
{
    struct stress *s = arg;
    uint32_t data = s->data_seed, chunk = s->chunk_seed ^ 0x9e3779b9u;
    uint8_t buf[1500];
    uint64_t got = 0;
    while (got < __atomic_load_n(&s->total, __ATOMIC_ACQUIRE)) {
        uint32_t c = rnd(&chunk);
        size_t len = 1 + c % sizeof buf, n = 0;
        /* never beyond the end the producer published */
        uint64_t left = __atomic_load_n(&s->total, __ATOMIC_ACQUIRE) - got;
        if (len > left)
            len = (size_t)left;
        switch (c >> 29) {
        case 0: { /* single byte */
            uint8_t b;
            n = fbrl_ring_get(&s->ring, &b) == FBRL_OK;
            buf[0] = b;
            break;
        }
        case 1: /* peek then skip what was seen */
            fbrl_ring_peek(&s->ring, buf, len, &n);
            if (n > 0 && fbrl_ring_skip(&s->ring, n) != FBRL_OK)
                n = 0, s->mismatch_at = got; /* skip must accept what peek saw */
            break;
        default: fbrl_ring_read(&s->ring, buf, len, &n); break;
        }
        if (n == 0) {
            sched_yield();
            continue;
        }
        for (size_t i = 0; i < n; i++) {
            if (buf[i] != (uint8_t)(rnd(&data) >> 24)) {
                s->mismatch_at = got + i;
                return NULL;
            }
        }
        got += n;
    }
    return NULL;
}

static uint64_t stress_bytes(void)
{
    const char *e = getenv("FBRL_RING_STRESS_MB");
    uint64_t mb = 100;
    if (e != NULL && atoi(e) > 0)
        mb = (uint64_t)atoi(e);
    return mb * 1000000u;
}

/* Returns the bytes moved (total, or less if the TSan deadline cut the run). */
static uint64_t run_stress(size_t ring_size, uint64_t total)
{
    static uint8_t mem[4096];
    static struct stress s;
    pthread_t p, c;
    assert_true(ring_size <= sizeof mem);
    memset(&s, 0, sizeof s);
    assert_int_equal(fbrl_ring_init(&s.ring, mem, ring_size), FBRL_OK);
    s.total = total;
    s.data_seed = 0xC0FFEEu + (uint32_t)ring_size;
    s.chunk_seed = 0xBEEFu;
    s.mismatch_at = UINT64_MAX;
    assert_int_equal(pthread_create(&p, NULL, producer, &s), 0);
    assert_int_equal(pthread_create(&c, NULL, consumer, &s), 0);
    pthread_join(p, NULL);
    pthread_join(c, NULL);
    if (s.mismatch_at != UINT64_MAX)
        fail_msg("ring %zu: byte %llu lost, duplicated or out of order", ring_size,
                 (unsigned long long)s.mismatch_at);
    assert_true(fbrl_ring_empty(&s.ring));
    return s.total;
}

/* 100 MB (or FBRL_RING_STRESS_MB) through a 4 KiB ring. */
static void two_threads_move_100mb_intact(void **state)
{
    (void)state;
    uint64_t total = stress_bytes(), moved = run_stress(4096, total);
    printf("# two-thread stress: %llu of %llu bytes through a 4096-byte ring, all in order\n",
           (unsigned long long)moved, (unsigned long long)total);
    assert_true(moved == total || (STRESS_DEADLINE_NS && moved >= 10000000u));
}

/* A tiny ring keeps both sides at the full/empty edges all the time. */
static void two_threads_tiny_ring(void **state)
{
    (void)state;
    /* every byte a full/empty hand-over: dear under TSan, so less there */
    uint64_t total = STRESS_DEADLINE_NS ? 300000u : 2000000u;
    assert_int_equal(run_stress(2, total), total);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(bad_input_gives_errors),        cmocka_unit_test(capacity_is_largest_power_of_two),
        cmocka_unit_test(queue_words_and_full_capacity), cmocka_unit_test(bulk_wraps_at_every_offset),
        cmocka_unit_test(random_ops_match_model),        cmocka_unit_test(two_threads_move_100mb_intact),
        cmocka_unit_test(two_threads_tiny_ring),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
