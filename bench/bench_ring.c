/* SPDX-License-Identifier: MIT */
/* bench_ring.c - throughput of the SPSC ring beside a naive mutex ring.
 *
 * Cases: single-byte put/get and 64-byte bulk write/read; one thread (put a chunk,
 * then get it back, in a loop: the cost of the calls) and two threads (a producer
 * and a consumer spinning on full/empty). The naive ring is what one writes first:
 * modulo indexing and a pthread mutex around every call. Prints bytes/s, the best
 * of three runs per case (the machine is shared; the best run is the least disturbed).
 * Usage: bench_ring [MB per case, default 64] */
#include <pthread.h>
#include <sched.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "fbrl/ring.h"

#define RING_SIZE 4096

/* ---- naive ring: modulo-indexed, one mutex ---- */
typedef struct naive {
    pthread_mutex_t mu;
    uint8_t buf[RING_SIZE];
    size_t head, count;
} naive;

static int naive_put(naive *q, uint8_t b)
{
    int ok = 0;
    pthread_mutex_lock(&q->mu);
    if (q->count < RING_SIZE) {
        q->buf[(q->head + q->count) % RING_SIZE] = b;
        q->count++;
        ok = 1;
    }
    pthread_mutex_unlock(&q->mu);
    return ok;
}

static int naive_get(naive *q, uint8_t *b)
{
    int ok = 0;
    pthread_mutex_lock(&q->mu);
    if (q->count > 0) {
        *b = q->buf[q->head];
        q->head = (q->head + 1) % RING_SIZE;
        q->count--;
        ok = 1;
    }
    pthread_mutex_unlock(&q->mu);
    return ok;
}

static size_t naive_write(naive *q, const uint8_t *src, size_t len)
{
    size_t n = 0;
    pthread_mutex_lock(&q->mu);
    while (n < len && q->count < RING_SIZE) {
        q->buf[(q->head + q->count) % RING_SIZE] = src[n++];
        q->count++;
    }
    pthread_mutex_unlock(&q->mu);
    return n;
}

static size_t naive_read(naive *q, uint8_t *dst, size_t len)
{
    size_t n = 0;
    pthread_mutex_lock(&q->mu);
    while (n < len && q->count > 0) {
        dst[n++] = q->buf[q->head];
        q->head = (q->head + 1) % RING_SIZE;
        q->count--;
    }
    pthread_mutex_unlock(&q->mu);
    return n;
}

/* ---- one interface over both rings, for the two-thread runs ---- */
static fbrl_ring fring;
static uint8_t fmem[RING_SIZE];
static naive nring = {PTHREAD_MUTEX_INITIALIZER, {0}, 0, 0};

static size_t put_bytes(int which, const uint8_t *src, size_t len, int bulk)
{
    size_t n = 0;
    if (bulk) {
        if (which)
            return naive_write(&nring, src, len);
        fbrl_ring_write(&fring, src, len, &n);
        return n;
    }
    while (n < len && (which ? naive_put(&nring, src[n]) : fbrl_ring_put(&fring, src[n]) == FBRL_OK))
        n++;
    return n;
}

static size_t get_bytes(int which, uint8_t *dst, size_t len, int bulk)
{
    size_t n = 0;
    if (bulk) {
        if (which)
            return naive_read(&nring, dst, len);
        fbrl_ring_read(&fring, dst, len, &n);
        return n;
    }
    while (n < len && (which ? naive_get(&nring, &dst[n]) : fbrl_ring_get(&fring, &dst[n]) == FBRL_OK))
        n++;
    return n;
}

/* One-thread cases are timed in the thread's CPU time, so that time this shared
 * machine gives to other processes does not count; two-thread cases in wall time. */
static double now_s(int threads)
{
    struct timespec ts;
    clock_gettime(threads ? CLOCK_MONOTONIC : CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

struct job {
    int which, bulk;
    uint64_t total, sum;
};

static void *produce(void *arg)
{
    struct job *j = arg;
    uint8_t chunk[64];
    uint64_t done = 0;
    for (int i = 0; i < 64; i++)
        chunk[i] = (uint8_t)i;
    while (done < j->total) {
        size_t n = put_bytes(j->which, chunk, 64, j->bulk);
        if (n == 0)
            sched_yield();
        done += n;
    }
    return NULL;
}

static void *consume(void *arg)
{
    struct job *j = arg;
    uint8_t chunk[64];
    uint64_t done = 0, sum = 0;
    while (done < j->total) {
        size_t n = get_bytes(j->which, chunk, 64, j->bulk);
        if (n == 0)
            sched_yield();
        for (size_t i = 0; i < n; i++)
            sum += chunk[i];
        done += n;
    }
    j->sum = sum;
    return NULL;
}

/* One thread: put 64 bytes, then get them back. Written out per ring and per mode
 * so the loop measures the calls, not a dispatch. */
static uint64_t one_thread_fbrl_byte(uint64_t total)
{
    uint8_t in[64], out[64];
    uint64_t sum = 0;
    for (int i = 0; i < 64; i++)
        in[i] = (uint8_t)(i + 1);
    for (uint64_t done = 0; done < total; done += 64) {
        size_t n = 0, m = 0;
        while (n < 64 && fbrl_ring_put(&fring, in[n]) == FBRL_OK)
            n++;
        while (m < n && fbrl_ring_get(&fring, &out[m]) == FBRL_OK)
            m++;
        sum += out[m - 1];
    }
    return sum;
}

static uint64_t one_thread_fbrl_bulk(uint64_t total)
{
    uint8_t in[64], out[64];
    uint64_t sum = 0;
    for (int i = 0; i < 64; i++)
        in[i] = (uint8_t)(i + 1);
    for (uint64_t done = 0; done < total; done += 64) {
        size_t n = 0, m = 0;
        fbrl_ring_write(&fring, in, 64, &n);
        fbrl_ring_read(&fring, out, n, &m);
        sum += out[m - 1];
    }
    return sum;
}

static uint64_t one_thread_naive(int bulk, uint64_t total)
{
    uint8_t in[64], out[64];
    uint64_t sum = 0;
    for (int i = 0; i < 64; i++)
        in[i] = (uint8_t)(i + 1);
    for (uint64_t done = 0; done < total; done += 64) {
        size_t n = 0, m = 0;
        if (bulk) {
            n = naive_write(&nring, in, 64);
            m = naive_read(&nring, out, n);
        } else {
            while (n < 64 && naive_put(&nring, in[n]))
                n++;
            while (m < n && naive_get(&nring, &out[m]))
                m++;
        }
        sum += out[m - 1];
    }
    return sum;
}

static double run(int which, int bulk, int threads, uint64_t total)
{
    struct job j = {which, bulk, total, 0};
    fbrl_ring_init(&fring, fmem, sizeof fmem);
    nring.head = nring.count = 0;
    double t0 = now_s(threads);
    if (threads) {
        pthread_t p, c;
        pthread_create(&p, NULL, produce, &j);
        pthread_create(&c, NULL, consume, &j);
        pthread_join(p, NULL);
        pthread_join(c, NULL);
    } else {
        j.sum = which  ? one_thread_naive(bulk, total)
                : bulk ? one_thread_fbrl_bulk(total)
                       : one_thread_fbrl_byte(total);
    }
    double dt = now_s(threads) - t0;
    if (j.sum == 0)
        fprintf(stderr, "checksum zero?\n");
    return (double)total / dt;
}

int main(int argc, char **argv)
{
    uint64_t total = (uint64_t)(argc > 1 ? atoi(argv[1]) : 64) * 1000000u;
    total -= total % 64;
    printf("ring %d bytes, %llu bytes per case, bytes/s (MB = 1e6 B); 1 thread: per CPU second, "
           "2 threads: wall time\n",
           RING_SIZE, (unsigned long long)total);
    printf("%-22s %16s %16s %8s\n", "case", "fbrl_ring", "naive+mutex", "ratio");
    const char *names[2][2] = {{"1 thread, 1 byte", "1 thread, 64 B bulk"},
                               {"2 threads, 1 byte", "2 threads, 64 B bulk"}};
    for (int threads = 0; threads < 2; threads++) {
        for (int bulk = 0; bulk < 2; bulk++) {
            double f = 0, n = 0;
            for (int rep = 0; rep < 3; rep++) {
                double a = run(0, bulk, threads, total), b = run(1, bulk, threads, total);
                f = a > f ? a : f;
                n = b > n ? b : n;
            }
            printf("%-22s %10.1f MB/s %10.1f MB/s %7.1fx\n", names[threads][bulk], f / 1e6, n / 1e6, f / n);
        }
    }
    return 0;
}
