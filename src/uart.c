/* SPDX-License-Identifier: MIT */
/* uart.c - the serial driver core: rings, XON/XOFF both ways, counters, waiting.
 *
 * The thesis's COM routine (5.2, appendix I-4) split in two: the backend's
 * interrupt (or poll loop) calls fbrl_uart_isr_rx/tx/line_status, which fill the
 * receive queue, empty the transmit queue and run the XON/XOFF protocol; the main
 * line queues and takes bytes and waits through ops->service. Every variable shared
 * between the two sides is a size_t with a single writer, accessed through atomic.h,
 * so no lock is needed and nothing here can block the interrupt side. */
#include <string.h>
#include "fbrl/uart.h"
#include "atomic.h"

/* Slots of fbrl_uart.raw / .total, in fbrl_uart_counters order. */
enum { C_RX, C_TX, C_OVERRUN, C_FRAMING, C_PARITY, C_XOFF_RX, C_XOFF_TX, C_HELD_US };

/* A counter written only by the interrupt side: no read-modify-write race. */
static void bump(size_t *c, size_t n) { fbrl_store_rel(c, fbrl_load_rlx(c) + n); }

static bool is_open(const fbrl_uart *u)
{
    return u != NULL && u->ops != NULL && fbrl_load_acq(&u->open) == 1;
}

static fbrl_status check_config(const fbrl_uart_config *cfg)
{
    if (cfg == NULL || cfg->baud == 0 || cfg->data_bits < 5 || cfg->data_bits > 8)
        return FBRL_EINVAL;
    if (cfg->parity != FBRL_PARITY_NONE && cfg->parity != FBRL_PARITY_EVEN && cfg->parity != FBRL_PARITY_ODD)
        return FBRL_EINVAL;
    if (cfg->stop_bits < 1 || cfg->stop_bits > 2)
        return FBRL_EINVAL;
    if (cfg->flow != FBRL_FLOW_NONE && cfg->flow != FBRL_FLOW_XONXOFF)
        return FBRL_EINVAL;
    return FBRL_OK;
}

fbrl_status fbrl_uart_init(fbrl_uart *u, const fbrl_uart_ops *ops, void *ctx, void *rx_storage,
                           size_t rx_size, void *tx_storage, size_t tx_size, const fbrl_uart_config *cfg)
{
    if (u == NULL || ops == NULL || ops->configure == NULL || ops->tx_kick == NULL || ops->service == NULL ||
        ops->now_us == NULL)
        return FBRL_EINVAL;
    fbrl_status st = check_config(cfg);
    if (st != FBRL_OK)
        return st;
    memset(u, 0, sizeof *u);
    if ((st = fbrl_ring_init(&u->rx, rx_storage, rx_size)) != FBRL_OK ||
        (st = fbrl_ring_init(&u->tx, tx_storage, tx_size)) != FBRL_OK)
        return st;
    size_t cap = fbrl_ring_capacity(&u->rx);
    u->rx_high = cap - cap / 4; /* XOFF at 3/4 full: a quarter is left for bytes in flight */
    u->rx_low = cap / 4;        /* XON once drained to 1/4 */
    u->ops = ops;
    u->ctx = ctx;
    u->cfg = *cfg;
    fbrl_store_rel(&u->flow, cfg->flow == FBRL_FLOW_XONXOFF);
    if ((st = ops->configure(ctx, cfg)) != FBRL_OK)
        return st;
    fbrl_store_rel(&u->open, 1);
    return FBRL_OK;
}

fbrl_status fbrl_uart_configure(fbrl_uart *u, const fbrl_uart_config *cfg)
{
    if (!is_open(u))
        return u == NULL ? FBRL_EINVAL : FBRL_ESTATE;
    fbrl_status st = check_config(cfg);
    if (st != FBRL_OK)
        return st;
    if ((st = u->ops->configure(u->ctx, cfg)) != FBRL_OK)
        return st;
    u->cfg = *cfg;
    fbrl_store_rel(&u->flow, cfg->flow == FBRL_FLOW_XONXOFF);
    u->ops->tx_kick(u->ctx); /* turning flow control off may release a held XON */
    return FBRL_OK;
}

fbrl_status fbrl_uart_get_config(const fbrl_uart *u, fbrl_uart_config *cfg)
{
    if (cfg == NULL || u == NULL)
        return FBRL_EINVAL;
    if (!is_open(u))
        return FBRL_ESTATE;
    *cfg = u->cfg;
    return FBRL_OK;
}

/* Main-line deadline bookkeeping shared by write, read and drain. */
typedef struct wait {
    uint64_t deadline;
    bool serviced; /* the backend got at least one chance to move bytes */
} wait;

static wait wait_start(const fbrl_uart *u, uint32_t timeout_ms)
{
    wait w = {u->ops->now_us(u->ctx) + (uint64_t)timeout_ms * 1000u, false};
    return w;
}

/* Let the backend make progress until something may have changed or the deadline
 * passes. FBRL_ETIMEOUT when the deadline had passed (after one service call, so
 * that timeout 0 still moves bytes through a polled backend). */
static fbrl_status wait_step(fbrl_uart *u, wait *w)
{
    uint64_t now = u->ops->now_us(u->ctx);
    if (w->serviced && now >= w->deadline)
        return FBRL_ETIMEOUT;
    uint64_t left = now >= w->deadline ? 0 : w->deadline - now;
    w->serviced = true;
    fbrl_status st = u->ops->service(u->ctx, left > UINT32_MAX ? UINT32_MAX : (uint32_t)left);
    return st == FBRL_ETIMEOUT ? FBRL_OK : st;
}

/* A polled backend writes what is queued now. */
static fbrl_status flush(fbrl_uart *u) { return u->ops->flush != NULL ? u->ops->flush(u->ctx) : FBRL_OK; }

fbrl_status fbrl_uart_write(fbrl_uart *u, const void *data, size_t len, size_t *written, uint32_t timeout_ms)
{
    size_t done = 0;
    if (written != NULL)
        *written = 0;
    if (u == NULL || (data == NULL && len > 0))
        return FBRL_EINVAL;
    if (!is_open(u))
        return FBRL_ESTATE;
    wait w = wait_start(u, timeout_ms);
    fbrl_status st = FBRL_OK;
    for (;;) {
        size_t n = 0;
        fbrl_ring_write(&u->tx, (const uint8_t *)data + done, len - done, &n);
        if (n > 0) {
            done += n;
            u->ops->tx_kick(u->ctx);
        }
        if (done == len || (st = wait_step(u, &w)) != FBRL_OK)
            break;
    }
    fbrl_status fst = done > 0 ? flush(u) : FBRL_OK;
    if (written != NULL)
        *written = done;
    if (fst != FBRL_OK)
        return fst; /* queued, but the line is gone: say so now */
    return done == len ? FBRL_OK : st;
}

/* After the main line took bytes from the rx ring: wake the transmitter side when we
 * hold the peer off and the ring is down to the low-water mark (isr_tx then sends
 * XON), or when the ring had been full (a backend that stopped reading resumes). */
static void after_rx_drain(fbrl_uart *u, bool was_full)
{
    if (was_full || (fbrl_load_acq(&u->rx_stopped) &&
                     (!fbrl_load_acq(&u->flow) || fbrl_ring_count(&u->rx) <= u->rx_low))) {
        u->ops->tx_kick(u->ctx);
        (void)flush(u); /* the XON the peer waits for leaves now; an error recurs at the next call */
    }
}

fbrl_status fbrl_uart_read(fbrl_uart *u, void *buf, size_t len, size_t *got, uint32_t timeout_ms)
{
    if (got != NULL)
        *got = 0;
    if (u == NULL || got == NULL || (buf == NULL && len > 0))
        return FBRL_EINVAL;
    if (!is_open(u))
        return FBRL_ESTATE;
    if (len == 0)
        return FBRL_OK;
    wait w = wait_start(u, timeout_ms);
    for (;;) {
        size_t n = 0;
        bool was_full = fbrl_ring_full(&u->rx);
        fbrl_ring_read(&u->rx, buf, len, &n);
        after_rx_drain(u, was_full && n > 0);
        if (n > 0) {
            *got = n;
            return FBRL_OK;
        }
        fbrl_status st = wait_step(u, &w);
        if (st != FBRL_OK) {
            /* Bytes that arrived with the error (e.g. just before a hang-up) come first. */
            bool was_full = fbrl_ring_full(&u->rx);
            fbrl_ring_read(&u->rx, buf, len, &n);
            after_rx_drain(u, was_full && n > 0);
            *got = n;
            return n > 0 ? FBRL_OK : st;
        }
    }
}

fbrl_status fbrl_uart_drain(fbrl_uart *u, uint32_t timeout_ms)
{
    if (u == NULL)
        return FBRL_EINVAL;
    if (!is_open(u))
        return FBRL_ESTATE;
    wait w = wait_start(u, timeout_ms);
    fbrl_status st = FBRL_OK;
    while (!fbrl_ring_empty(&u->tx) && (st = wait_step(u, &w)) == FBRL_OK)
        ;
    return fbrl_ring_empty(&u->tx) ? FBRL_OK : st;
}

size_t fbrl_uart_rx_available(const fbrl_uart *u) { return is_open(u) ? fbrl_ring_count(&u->rx) : 0; }

size_t fbrl_uart_tx_pending(const fbrl_uart *u) { return is_open(u) ? fbrl_ring_count(&u->tx) : 0; }

size_t fbrl_uart_rx_room(const fbrl_uart *u) { return is_open(u) ? fbrl_ring_space(&u->rx) : 0; }

int fbrl_uart_peer_stopped(const fbrl_uart *u) { return is_open(u) && fbrl_load_acq(&u->peer_xoff) ? 1 : 0; }

fbrl_status fbrl_uart_get_counters(fbrl_uart *u, fbrl_uart_counters *out)
{
    if (u == NULL || out == NULL)
        return FBRL_EINVAL;
    if (!is_open(u))
        return FBRL_ESTATE;
    for (int i = 0; i < FBRL_UART_NCOUNTERS; i++) {
        size_t cur = fbrl_load_acq(&u->raw[i]);
        u->total[i] += (size_t)(cur - u->seen[i]); /* modular: exact across one wrap */
        u->seen[i] = cur;
    }
    uint64_t held = u->total[C_HELD_US];
    if (fbrl_load_acq(&u->peer_xoff)) /* a hold still in progress counts so far */
        held += (size_t)((size_t)u->ops->now_us(u->ctx) - fbrl_load_acq(&u->held_since));
    memset(out, 0, sizeof *out);
    out->rx_bytes = u->total[C_RX];
    out->tx_bytes = u->total[C_TX];
    out->overruns = u->total[C_OVERRUN];
    out->framing_errors = u->total[C_FRAMING];
    out->parity_errors = u->total[C_PARITY];
    out->xoff_received = u->total[C_XOFF_RX];
    out->xoff_sent = u->total[C_XOFF_TX];
    out->held_off_us = held;
    return FBRL_OK;
}

/* Without a common wait_many: service each port without blocking, and if none has
 * anything, nap on the first port for at most a slice (1 ms). */
#define WAIT_SLICE_US 1000u

static fbrl_status wait_one_by_one(fbrl_uart *const *ports, size_t n, uint32_t timeout_us,
                                   unsigned char *flags)
{
    int any = 0;
    for (size_t k = 0; k < n; k++) {
        fbrl_status st = ports[k]->ops->service(ports[k]->ctx, 0);
        if ((st != FBRL_OK && st != FBRL_ETIMEOUT) || fbrl_ring_count(&ports[k]->rx) > 0) {
            flags[k] |= FBRL_UART_WAIT_READY;
            any |= flags[k] & FBRL_UART_WAIT_RX;
        }
    }
    if (any || timeout_us == 0)
        return FBRL_OK;
    fbrl_status st =
        ports[0]->ops->service(ports[0]->ctx, timeout_us < WAIT_SLICE_US ? timeout_us : WAIT_SLICE_US);
    if ((st != FBRL_OK && st != FBRL_ETIMEOUT) || fbrl_ring_count(&ports[0]->rx) > 0)
        flags[0] |= FBRL_UART_WAIT_READY;
    return FBRL_OK;
}

fbrl_status fbrl_uart_wait_any(fbrl_uart *const *ports, size_t n, uint32_t timeout_us, unsigned char *flags)
{
    if (ports == NULL || flags == NULL || n == 0)
        return FBRL_EINVAL;
    int same = 1;
    for (size_t k = 0; k < n; k++) {
        if (!is_open(ports[k]))
            return FBRL_EINVAL;
        flags[k] &= (unsigned char)FBRL_UART_WAIT_RX;
        same =
            same && ports[k]->ops->wait_many != NULL && ports[k]->ops->wait_many == ports[0]->ops->wait_many;
    }
    if (same && n <= FBRL_UART_WAIT_MAX) {
        fbrl_status st = ports[0]->ops->wait_many(ports, n, timeout_us, flags);
        if (st != FBRL_EUNSUPPORTED)
            return st;
    }
    return wait_one_by_one(ports, n, timeout_us, flags);
}

fbrl_status fbrl_uart_close(fbrl_uart *u)
{
    if (u == NULL)
        return FBRL_EINVAL;
    if (!is_open(u))
        return FBRL_ESTATE;
    fbrl_store_rel(&u->open, 0);
    return u->ops->close != NULL ? u->ops->close(u->ctx) : FBRL_OK;
}

/* ---- interrupt side ---- */

/* Ask for XOFF ahead of the queue and wake the transmitter. */
static void request_xoff(fbrl_uart *u)
{
    fbrl_store_rel(&u->ctl_pending, FBRL_XOFF);
    u->ops->tx_kick(u->ctx);
}

void fbrl_uart_isr_rx(fbrl_uart *u, uint8_t byte)
{
    if (!is_open(u))
        return;
    bool flow = fbrl_load_rlx(&u->flow) != 0;
    if (flow && byte == FBRL_XOFF) {
        bump(&u->raw[C_XOFF_RX], 1);
        if (!fbrl_load_rlx(&u->peer_xoff)) {
            fbrl_store_rel(&u->held_since, (size_t)u->ops->now_us(u->ctx));
            fbrl_store_rel(&u->peer_xoff, 1);
        }
        return;
    }
    if (flow && byte == FBRL_XON) {
        if (fbrl_load_rlx(&u->peer_xoff)) {
            size_t since = fbrl_load_rlx(&u->held_since);
            bump(&u->raw[C_HELD_US], (size_t)u->ops->now_us(u->ctx) - since);
            fbrl_store_rel(&u->peer_xoff, 0);
            u->ops->tx_kick(u->ctx);
        }
        return;
    }
    if (fbrl_ring_put(&u->rx, byte) != FBRL_OK) {
        bump(&u->raw[C_OVERRUN], 1);
        if (flow) /* the thesis: a full buffer sends XOFF at once (again, if it was lost) */
            request_xoff(u);
        return;
    }
    bump(&u->raw[C_RX], 1);
    if (flow && !fbrl_load_rlx(&u->rx_stopped) && fbrl_load_rlx(&u->ctl_pending) != FBRL_XOFF &&
        fbrl_ring_count(&u->rx) >= u->rx_high)
        request_xoff(u);
}

int fbrl_uart_isr_tx(fbrl_uart *u)
{
    if (!is_open(u))
        return -1;
    bool flow = fbrl_load_rlx(&u->flow) != 0;
    if (fbrl_load_rlx(&u->ctl_pending) == FBRL_XOFF) {
        fbrl_store_rel(&u->ctl_pending, 0);
        fbrl_store_rel(&u->rx_stopped, 1);
        bump(&u->raw[C_XOFF_TX], 1);
        return FBRL_XOFF;
    }
    if (fbrl_load_rlx(&u->rx_stopped) && (!flow || fbrl_ring_count(&u->rx) <= u->rx_low)) {
        fbrl_store_rel(&u->rx_stopped, 0);
        return FBRL_XON;
    }
    if (flow && fbrl_load_rlx(&u->peer_xoff))
        return -1;
    uint8_t b;
    if (fbrl_ring_get(&u->tx, &b) != FBRL_OK)
        return -1;
    bump(&u->raw[C_TX], 1);
    return b;
}

void fbrl_uart_isr_line_status(fbrl_uart *u, unsigned flags)
{
    if (!is_open(u))
        return;
    if (flags & FBRL_UART_LS_OVERRUN)
        bump(&u->raw[C_OVERRUN], 1);
    if (flags & FBRL_UART_LS_PARITY)
        bump(&u->raw[C_PARITY], 1);
    if (flags & FBRL_UART_LS_FRAMING)
        bump(&u->raw[C_FRAMING], 1);
}
