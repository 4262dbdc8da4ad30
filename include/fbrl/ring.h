/* SPDX-License-Identifier: MIT */
/* ring.h - single-producer/single-consumer byte ring (the thesis's queue).
 *
 * The thesis (5.1, appendix I-1) builds the serial buffers from a byte queue with
 * CREATE-Q, ENQ, DEQ, EMPTY-Q? and FULL-Q?. Here that queue is a lock-free ring in
 * caller-owned storage:
 *
 *     CREATE-Q   fbrl_ring_init(&r, storage, size)
 *     ENQ        fbrl_ring_put(&r, byte)          (fbrl_ring_write for many bytes)
 *     DEQ        fbrl_ring_get(&r, &byte)         (fbrl_ring_read for many bytes)
 *     EMPTY-Q?   fbrl_ring_empty(&r)
 *     FULL-Q?    fbrl_ring_full(&r)
 *
 * Rules:
 *  - Storage of any size >= 2 is accepted; the ring uses the largest power of two
 *    that fits (fbrl_ring_capacity() tells which): 4096 bytes hold 4096, 1000 bytes
 *    hold 512. Powers of two let the per-byte path mask instead of divide or compare,
 *    and let every byte of that capacity be used (free-running indices).
 *  - One producer (put/write) and one consumer (get/read/peek/skip) may run at the same
 *    time, each in its own thread or one of them in an interrupt handler, with no lock.
 *    Two producers, or two consumers, need a lock of the caller's.
 *  - count/space/empty/full may be called from either side; the answer is exact for
 *    the side that asks (the other side can only make it more favourable).
 *  - fbrl_ring_reset() is not concurrent-safe: call it while neither side runs.
 *
 * The struct is caller-owned storage; its fields are private. */
#ifndef FBRL_RING_H
#define FBRL_RING_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include <stdbool.h>
#include "fbrl/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Keeps the producer's and the consumer's index on separate cache lines. */
#define FBRL_RING_CACHE_LINE 64

typedef struct fbrl_ring {
    /* private: head and tail are free-running byte counters (count = head - tail,
     * offset = index & mask); head is written only by the producer, tail only by
     * the consumer. */
    uint8_t *buf;
    size_t mask;
    size_t head;
    unsigned char pad_[FBRL_RING_CACHE_LINE];
    size_t tail;
} fbrl_ring;

/* CREATE-Q: use storage (size bytes, of which the largest power of two is used) as
 * an empty ring. EINVAL: r or storage NULL, or size < 2. */
FBRL_API fbrl_status fbrl_ring_init(fbrl_ring *r, void *storage, size_t size);

/* Empty the ring. Only while neither producer nor consumer runs. */
FBRL_API fbrl_status fbrl_ring_reset(fbrl_ring *r);

/* ENQ: add one byte. FBRL_EFULL when there is no room (nothing changes). */
FBRL_API fbrl_status fbrl_ring_put(fbrl_ring *r, uint8_t byte);

/* DEQ: take the oldest byte. FBRL_EEMPTY when there is none. */
FBRL_API fbrl_status fbrl_ring_get(fbrl_ring *r, uint8_t *byte);

/* Add up to len bytes from src; *written = how many fit (may be fewer than len).
 * FBRL_EFULL when len > 0 and nothing fit. src may be NULL only when len is 0. */
FBRL_API fbrl_status fbrl_ring_write(fbrl_ring *r, const void *src, size_t len, size_t *written);

/* Take up to len bytes into dst; *got = how many. FBRL_EEMPTY when len > 0 and the
 * ring was empty. */
FBRL_API fbrl_status fbrl_ring_read(fbrl_ring *r, void *dst, size_t len, size_t *got);

/* Copy up to len of the oldest bytes into dst without taking them (consumer side). */
FBRL_API fbrl_status fbrl_ring_peek(const fbrl_ring *r, void *dst, size_t len, size_t *got);

/* Drop the n oldest bytes (consumer side). FBRL_ERANGE when fewer than n are stored. */
FBRL_API fbrl_status fbrl_ring_skip(fbrl_ring *r, size_t n);

/* Bytes stored / bytes of room / total capacity. A NULL or uninitialised ring
 * reads as capacity 0: count 0, space 0. */
FBRL_API size_t fbrl_ring_count(const fbrl_ring *r);
FBRL_API size_t fbrl_ring_space(const fbrl_ring *r);
FBRL_API size_t fbrl_ring_capacity(const fbrl_ring *r);

/* EMPTY-Q? and FULL-Q?. A NULL ring is both empty and full (nothing goes in or out). */
FBRL_API bool fbrl_ring_empty(const fbrl_ring *r);
FBRL_API bool fbrl_ring_full(const fbrl_ring *r);

#ifdef __cplusplus
}
#endif
#endif
