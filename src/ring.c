/* SPDX-License-Identifier: MIT */
/* ring.c - lock-free SPSC byte ring; see fbrl/ring.h for the rules.
 *
 * The capacity is a power of two and head/tail are free-running counters: the
 * stored count is head - tail (unsigned arithmetic wraps correctly), the storage
 * offset is index & mask, so no byte is wasted and no division or compare-wrap is
 * needed on the per-byte path. The producer publishes data with a store-release of
 * head after copying in; the consumer publishes freed room with a store-release of
 * tail after copying out; each loads the other's index with acquire. */
#include <string.h>
#include "fbrl/ring.h"
#include "atomic.h"

static bool valid(const fbrl_ring *r) { return r != NULL && r->buf != NULL; }

fbrl_status fbrl_ring_init(fbrl_ring *r, void *storage, size_t size)
{
    if (r == NULL || storage == NULL || size < 2)
        return FBRL_EINVAL;
    size_t cap = 2;
    while (cap <= size / 2) /* largest power of two <= size */
        cap *= 2;
    r->buf = storage;
    r->mask = cap - 1;
    r->head = 0;
    r->tail = 0;
    return FBRL_OK;
}

fbrl_status fbrl_ring_reset(fbrl_ring *r)
{
    if (!valid(r))
        return FBRL_EINVAL;
    fbrl_store_rel(&r->head, 0);
    fbrl_store_rel(&r->tail, 0);
    return FBRL_OK;
}

/* put and get are the per-byte paths of an interrupt handler: kept minimal. */
fbrl_status fbrl_ring_put(fbrl_ring *r, uint8_t byte)
{
    if (!valid(r))
        return FBRL_EINVAL;
    size_t h = fbrl_load_rlx(&r->head);
    if (h - fbrl_load_acq(&r->tail) > r->mask)
        return FBRL_EFULL;
    r->buf[h & r->mask] = byte;
    fbrl_store_rel(&r->head, h + 1);
    return FBRL_OK;
}

fbrl_status fbrl_ring_get(fbrl_ring *r, uint8_t *byte)
{
    if (!valid(r) || byte == NULL)
        return FBRL_EINVAL;
    size_t t = fbrl_load_rlx(&r->tail);
    if (fbrl_load_acq(&r->head) == t)
        return FBRL_EEMPTY;
    *byte = r->buf[t & r->mask];
    fbrl_store_rel(&r->tail, t + 1);
    return FBRL_OK;
}

fbrl_status fbrl_ring_write(fbrl_ring *r, const void *src, size_t len, size_t *written)
{
    if (!valid(r) || written == NULL || (src == NULL && len > 0))
        return FBRL_EINVAL;
    *written = 0;
    if (len == 0)
        return FBRL_OK;
    size_t h = fbrl_load_rlx(&r->head);
    size_t room = r->mask + 1 - (h - fbrl_load_acq(&r->tail));
    if (room == 0)
        return FBRL_EFULL;
    size_t n = len < room ? len : room;
    size_t at = h & r->mask;
    size_t first = r->mask + 1 - at < n ? r->mask + 1 - at : n;
    memcpy(r->buf + at, src, first);
    if (n > first) /* wrapped: the rest goes to the start */
        memcpy(r->buf, (const uint8_t *)src + first, n - first);
    fbrl_store_rel(&r->head, h + n);
    *written = n;
    return FBRL_OK;
}

/* Copy up to len stored bytes starting at index t into dst; returns how many. */
static size_t copy_out(const fbrl_ring *r, size_t t, void *dst, size_t len)
{
    size_t have = fbrl_load_acq(&r->head) - t;
    size_t n = len < have ? len : have;
    size_t at = t & r->mask;
    size_t first = r->mask + 1 - at < n ? r->mask + 1 - at : n;
    memcpy(dst, r->buf + at, first);
    if (n > first)
        memcpy((uint8_t *)dst + first, r->buf, n - first);
    return n;
}

fbrl_status fbrl_ring_read(fbrl_ring *r, void *dst, size_t len, size_t *got)
{
    if (!valid(r) || got == NULL || (dst == NULL && len > 0))
        return FBRL_EINVAL;
    *got = 0;
    if (len == 0)
        return FBRL_OK;
    size_t t = fbrl_load_rlx(&r->tail);
    size_t n = copy_out(r, t, dst, len);
    if (n == 0)
        return FBRL_EEMPTY;
    fbrl_store_rel(&r->tail, t + n);
    *got = n;
    return FBRL_OK;
}

fbrl_status fbrl_ring_peek(const fbrl_ring *r, void *dst, size_t len, size_t *got)
{
    if (!valid(r) || got == NULL || (dst == NULL && len > 0))
        return FBRL_EINVAL;
    *got = 0;
    if (len == 0)
        return FBRL_OK;
    *got = copy_out(r, fbrl_load_rlx(&r->tail), dst, len);
    return *got == 0 ? FBRL_EEMPTY : FBRL_OK;
}

fbrl_status fbrl_ring_skip(fbrl_ring *r, size_t n)
{
    if (!valid(r))
        return FBRL_EINVAL;
    size_t t = fbrl_load_rlx(&r->tail);
    if (n > fbrl_load_acq(&r->head) - t)
        return FBRL_ERANGE;
    fbrl_store_rel(&r->tail, t + n);
    return FBRL_OK;
}

size_t fbrl_ring_count(const fbrl_ring *r)
{
    if (!valid(r))
        return 0;
    size_t t = fbrl_load_acq(&r->tail);
    size_t n = fbrl_load_acq(&r->head) - t;
    /* Only a third party (neither side) can see the indices this far apart. */
    return n > r->mask + 1 ? r->mask + 1 : n;
}

size_t fbrl_ring_space(const fbrl_ring *r) { return valid(r) ? r->mask + 1 - fbrl_ring_count(r) : 0; }

size_t fbrl_ring_capacity(const fbrl_ring *r) { return valid(r) ? r->mask + 1 : 0; }

bool fbrl_ring_empty(const fbrl_ring *r) { return fbrl_ring_count(r) == 0; }

bool fbrl_ring_full(const fbrl_ring *r) { return fbrl_ring_space(r) == 0; }
