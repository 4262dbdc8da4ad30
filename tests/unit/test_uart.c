/* SPDX-License-Identifier: MIT */
/* test_uart.c - the driver core over an in-test loopback "wire": two ports whose
 * backends hand each other's bytes across when serviced, under a simulated clock.
 * This is the hardware boundary (the only fake allowed); everything above it is the
 * real core: rings, XON/XOFF both ways, counters, timeouts. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/uart.h"

typedef struct end end;
typedef struct line {
    uint64_t now;         /* simulated monotonic clock, microseconds */
    size_t per_service;   /* bytes each direction may move per service call */
    uint64_t us_per_byte; /* simulated line time per byte */
} line;

struct end {
    fbrl_uart u;
    uint8_t rxm[64], txm[64];
    end *peer;
    line *ln;
    int kicks, services, closed, flushes;
    fbrl_status configure_result, service_result;
    fbrl_uart_config applied;
};

/* Move up to ln->per_service bytes from a's transmitter into b's receiver. */
static size_t pump(end *a)
{
    size_t n = 0;
    int c;
    while (n < a->ln->per_service && (c = fbrl_uart_isr_tx(&a->u)) >= 0) {
        fbrl_uart_isr_rx(&a->peer->u, (uint8_t)c);
        n++;
    }
    return n;
}

static fbrl_status lb_configure(void *ctx, const fbrl_uart_config *cfg)
{
    end *e = ctx;
    if (e->configure_result == FBRL_OK)
        e->applied = *cfg;
    return e->configure_result;
}

static void lb_kick(void *ctx) { ((end *)ctx)->kicks++; }

static fbrl_status lb_service(void *ctx, uint32_t timeout_us)
{
    end *e = ctx;
    e->services++;
    size_t moved = pump(e) + pump(e->peer);
    /* Idle: the wait lasts its whole timeout; busy: the bytes take line time. */
    e->ln->now += moved ? moved * e->ln->us_per_byte : timeout_us;
    return e->service_result;
}

static uint64_t lb_now(void *ctx) { return ((end *)ctx)->ln->now; }

static fbrl_status lb_close(void *ctx)
{
    ((end *)ctx)->closed++;
    return FBRL_OK;
}

static const fbrl_uart_ops lb_ops = {lb_configure, lb_kick, lb_service, lb_now, lb_close, 0, 0};

/* A polled backend's flush: the transmitter's bytes go onto the wire now, no waiting. */
static fbrl_status lb_flush(void *ctx)
{
    end *e = ctx;
    e->flushes++;
    while (pump(e) > 0)
        ;
    return e->service_result;
}

static const fbrl_uart_ops lb_flush_ops = {lb_configure, lb_kick, lb_service, lb_now, lb_close, lb_flush, 0};

static line the_line;
static end A, B;

static void open_pair_ops(fbrl_flow flow, const fbrl_uart_ops *ops)
{
    fbrl_uart_config cfg = FBRL_UART_CONFIG_DEFAULT;
    cfg.flow = flow;
    memset(&A, 0, sizeof A);
    memset(&B, 0, sizeof B);
    the_line.now = 1000;
    the_line.per_service = 8;
    the_line.us_per_byte = 1000; /* about 9600 baud */
    A.peer = &B, B.peer = &A;
    A.ln = B.ln = &the_line;
    assert_int_equal(fbrl_uart_init(&A.u, ops, &A, A.rxm, sizeof A.rxm, A.txm, sizeof A.txm, &cfg), FBRL_OK);
    assert_int_equal(fbrl_uart_init(&B.u, ops, &B, B.rxm, sizeof B.rxm, B.txm, sizeof B.txm, &cfg), FBRL_OK);
}

static void open_pair(fbrl_flow flow) { open_pair_ops(flow, &lb_ops); }

static int setup_flush(void **state)
{
    (void)state;
    open_pair_ops(FBRL_FLOW_XONXOFF, &lb_flush_ops);
    return 0;
}

static int setup_xon(void **state)
{
    (void)state;
    open_pair(FBRL_FLOW_XONXOFF);
    return 0;
}

static int setup_none(void **state)
{
    (void)state;
    open_pair(FBRL_FLOW_NONE);
    return 0;
}

static void bad_input_gives_errors(void **state)
{
    (void)state;
    fbrl_uart u;
    uint8_t rx[16], tx[16], buf[4];
    size_t n;
    end e = {0};
    e.ln = &the_line;
    fbrl_uart_config good = FBRL_UART_CONFIG_DEFAULT, bad;
    fbrl_uart_ops ops;

    assert_int_equal(fbrl_uart_init(NULL, &lb_ops, &e, rx, 16, tx, 16, &good), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_init(&u, NULL, &e, rx, 16, tx, 16, &good), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_init(&u, &lb_ops, &e, rx, 16, tx, 16, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_init(&u, &lb_ops, &e, NULL, 16, tx, 16, &good), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_init(&u, &lb_ops, &e, rx, 1, tx, 16, &good), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_init(&u, &lb_ops, &e, rx, 16, tx, 0, &good), FBRL_EINVAL);
    for (int member = 0; member < 4; member++) { /* every op but close is required */
        ops = lb_ops;
        if (member == 0)
            ops.configure = NULL;
        if (member == 1)
            ops.tx_kick = NULL;
        if (member == 2)
            ops.service = NULL;
        if (member == 3)
            ops.now_us = NULL;
        assert_int_equal(fbrl_uart_init(&u, &ops, &e, rx, 16, tx, 16, &good), FBRL_EINVAL);
    }
    for (int field = 0; field < 7; field++) {
        bad = good;
        if (field == 0)
            bad.baud = 0;
        if (field == 1)
            bad.data_bits = 4;
        if (field == 2)
            bad.data_bits = 9;
        if (field == 3)
            bad.parity = (fbrl_parity)'X';
        if (field == 4)
            bad.stop_bits = 0;
        if (field == 5)
            bad.stop_bits = 3;
        if (field == 6)
            bad.flow = (fbrl_flow)7;
        assert_int_equal(fbrl_uart_init(&u, &lb_ops, &e, rx, 16, tx, 16, &bad), FBRL_EINVAL);
    }
    /* The backend refuses a setting: the error comes back and the port stays closed. */
    e.configure_result = FBRL_EUNSUPPORTED;
    assert_int_equal(fbrl_uart_init(&u, &lb_ops, &e, rx, 16, tx, 16, &good), FBRL_EUNSUPPORTED);
    assert_int_equal(fbrl_uart_write(&u, "x", 1, &n, 0), FBRL_ESTATE);
    assert_int_equal(fbrl_uart_read(&u, buf, 1, &n, 0), FBRL_ESTATE);

    /* A zeroed handle and NULL handles are refused everywhere, never dereferenced. */
    memset(&u, 0, sizeof u);
    fbrl_uart_counters c;
    assert_int_equal(fbrl_uart_write(NULL, "x", 1, &n, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_read(NULL, buf, 1, &n, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_drain(NULL, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_close(NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_get_counters(NULL, &c), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_configure(NULL, &good), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_drain(&u, 0), FBRL_ESTATE);
    assert_int_equal(fbrl_uart_close(&u), FBRL_ESTATE);
    assert_int_equal(fbrl_uart_rx_available(NULL), 0);
    assert_int_equal(fbrl_uart_tx_pending(&u), 0);
    assert_int_equal(fbrl_uart_peer_stopped(NULL), 0);
    fbrl_uart_isr_rx(NULL, 'a');
    fbrl_uart_isr_rx(&u, 'a');
    fbrl_uart_isr_line_status(NULL, FBRL_UART_LS_PARITY);
    assert_int_equal(fbrl_uart_isr_tx(NULL), -1);
    assert_int_equal(fbrl_uart_isr_tx(&u), -1);

    /* An open port checks its arguments too. */
    e.configure_result = FBRL_OK;
    assert_int_equal(fbrl_uart_init(&u, &lb_ops, &e, rx, 16, tx, 16, &good), FBRL_OK);
    assert_int_equal(fbrl_uart_write(&u, NULL, 1, &n, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_read(&u, NULL, 1, &n, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_read(&u, buf, 1, NULL, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_get_counters(&u, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_get_config(&u, NULL), FBRL_EINVAL);
    bad = good;
    bad.data_bits = 10;
    assert_int_equal(fbrl_uart_configure(&u, &bad), FBRL_EINVAL);
    e.configure_result = FBRL_EUNSUPPORTED;
    bad = good;
    bad.baud = 12345;
    assert_int_equal(fbrl_uart_configure(&u, &bad), FBRL_EUNSUPPORTED);
    fbrl_uart_config now;
    assert_int_equal(fbrl_uart_get_config(&u, &now), FBRL_OK);
    assert_int_equal(now.baud, 9600); /* a refused change leaves the old settings */
    assert_int_equal(fbrl_uart_close(&u), FBRL_OK);
    assert_int_equal(e.closed, 1);
    assert_int_equal(fbrl_uart_close(&u), FBRL_ESTATE);
    assert_int_equal(fbrl_uart_write(&u, "x", 1, &n, 0), FBRL_ESTATE);
    assert_int_equal(fbrl_uart_isr_tx(&u), -1);
}

static void settings_reach_the_backend(void **state)
{
    (void)state;
    fbrl_uart_config cfg = {2400, 7, FBRL_PARITY_EVEN, 2, FBRL_FLOW_NONE}, got;
    assert_int_equal(fbrl_uart_configure(&A.u, &cfg), FBRL_OK);
    assert_int_equal(A.applied.baud, 2400);
    assert_int_equal(A.applied.data_bits, 7);
    assert_int_equal(A.applied.parity, FBRL_PARITY_EVEN);
    assert_int_equal(A.applied.stop_bits, 2);
    assert_int_equal(fbrl_uart_get_config(&A.u, &got), FBRL_OK);
    assert_memory_equal(&got, &cfg, sizeof cfg);
}

/* Read everything B can get until n bytes or a timeout. */
static size_t read_all(end *e, uint8_t *dst, size_t n, uint32_t timeout_ms)
{
    size_t have = 0, got;
    while (have < n && fbrl_uart_read(&e->u, dst + have, n - have, &got, timeout_ms) == FBRL_OK)
        have += got;
    return have;
}

static void bytes_cross_in_order(void **state)
{
    (void)state;
    const char msg[] = "HERE #P1\r"; /* a RAPL line */
    size_t n;
    uint8_t buf[32];
    assert_int_equal(fbrl_uart_write(&A.u, msg, sizeof msg - 1, &n, 100), FBRL_OK);
    assert_int_equal(n, sizeof msg - 1);
    assert_true(A.kicks > 0);
    assert_int_equal(read_all(&B, buf, sizeof msg - 1, 100), sizeof msg - 1);
    assert_memory_equal(buf, msg, sizeof msg - 1);
    fbrl_uart_counters ca, cb;
    assert_int_equal(fbrl_uart_get_counters(&A.u, &ca), FBRL_OK);
    assert_int_equal(fbrl_uart_get_counters(&B.u, &cb), FBRL_OK);
    assert_int_equal(ca.tx_bytes, sizeof msg - 1);
    assert_int_equal(cb.rx_bytes, sizeof msg - 1);
    assert_int_equal(cb.overruns + ca.xoff_received + cb.xoff_sent, 0);
}

static void timeouts_are_kept(void **state)
{
    (void)state;
    uint8_t buf[4];
    size_t n = 7;
    uint64_t t0 = the_line.now;
    /* 0 = do not block: one service pass, then ETIMEOUT without the clock moving. */
    assert_int_equal(fbrl_uart_read(&B.u, buf, sizeof buf, &n, 0), FBRL_ETIMEOUT);
    assert_int_equal(n, 0);
    assert_int_equal(the_line.now, t0);
    assert_int_equal(B.services, 1);
    /* 250 ms: the wait ends at the deadline, not before and not much after. */
    assert_int_equal(fbrl_uart_read(&B.u, buf, sizeof buf, &n, 250), FBRL_ETIMEOUT);
    assert_true(the_line.now - t0 >= 250000u);
    assert_true(the_line.now - t0 <= 251000u);
    /* Zero-length read and write succeed at once. */
    assert_int_equal(fbrl_uart_read(&B.u, buf, 0, &n, 1000), FBRL_OK);
    assert_int_equal(fbrl_uart_write(&B.u, buf, 0, &n, 1000), FBRL_OK);
    assert_int_equal(fbrl_uart_drain(&B.u, 0), FBRL_OK);
}

/* The main loop of a flow-control scenario: A sends total bytes while B reads only
 * when told, everything through the simulated line. */
static void pattern(uint8_t *p, size_t n, unsigned seed)
{
    for (size_t i = 0; i < n; i++) {
        uint8_t b = (uint8_t)(seed + i * 7 + (i >> 5));
        p[i] = (b == FBRL_XON || b == FBRL_XOFF) ? (uint8_t)(b + 1) : b; /* not sendable as data */
    }
}

static void xoff_holds_the_sender_and_xon_releases_it(void **state)
{
    (void)state;
    enum { TOTAL = 600 };
    uint8_t out[TOTAL], in[TOTAL];
    size_t n, have = 0;
    pattern(out, TOTAL, 3);

    /* B does not read: its 64-byte ring passes 3/4 (48) and it sends XOFF; A stops.
     * A's write then times out once its own tx ring is full too. */
    fbrl_status st = fbrl_uart_write(&A.u, out, TOTAL, &n, 500);
    assert_int_equal(st, FBRL_ETIMEOUT);
    assert_true(n < TOTAL);
    assert_int_equal(fbrl_uart_peer_stopped(&A.u), 1);
    assert_int_equal(fbrl_uart_peer_stopped(&B.u), 0);
    size_t queued = n;
    /* XOFF came while under the ring size: nothing was lost. */
    size_t held_rx = fbrl_uart_rx_available(&B.u);
    assert_true(held_rx >= 48 && held_rx <= 64);
    fbrl_uart_counters ca, cb;
    fbrl_uart_get_counters(&A.u, &ca);
    fbrl_uart_get_counters(&B.u, &cb);
    assert_int_equal(cb.xoff_sent, 1);
    assert_int_equal(ca.xoff_received, 1);
    assert_int_equal(cb.overruns, 0);
    assert_true(ca.held_off_us > 400000u); /* held for most of the 500 ms wait, still running */
    assert_int_equal(fbrl_uart_drain(&A.u, 100), FBRL_ETIMEOUT); /* held: cannot drain */

    /* Now B reads everything; XON goes out when B is down to 1/4, and A resumes. */
    for (int rounds = 0; rounds < 10000 && have < TOTAL; rounds++) {
        size_t got = 0;
        if (fbrl_uart_read(&B.u, in + have, TOTAL - have, &got, 10) == FBRL_OK)
            have += got;
        if (queued < TOTAL && fbrl_uart_write(&A.u, out + queued, TOTAL - queued, &n, 0) != FBRL_EINVAL)
            queued += n;
    }
    assert_int_equal(have, TOTAL);
    assert_memory_equal(in, out, TOTAL);
    assert_int_equal(fbrl_uart_peer_stopped(&A.u), 0);
    fbrl_uart_get_counters(&A.u, &ca);
    fbrl_uart_get_counters(&B.u, &cb);
    assert_true(cb.xoff_sent >= 1);
    assert_int_equal(ca.xoff_received, cb.xoff_sent);
    assert_int_equal(cb.overruns, 0);
    assert_int_equal(cb.rx_bytes, TOTAL); /* flow-control bytes are not counted as data */
    assert_int_equal(ca.tx_bytes, TOTAL);
    uint64_t held = ca.held_off_us;
    fbrl_uart_get_counters(&A.u, &ca);
    assert_int_equal(ca.held_off_us, held); /* released: the hold time stopped growing */
}

/* Flow-control bytes jump the queue: with data waiting in B's tx ring, the first byte
 * B sends after passing its high-water mark is XOFF, and XON also comes first. */
static void flow_control_bytes_go_first(void **state)
{
    (void)state;
    uint8_t data[40];
    size_t n;
    pattern(data, sizeof data, 9);
    assert_int_equal(fbrl_uart_write(&B.u, data, sizeof data, &n, 0), FBRL_OK);
    for (int i = 0; i < 48; i++) /* straight into B's receiver, as its interrupt would */
        fbrl_uart_isr_rx(&B.u, 'a');
    assert_true(B.kicks > 0);
    assert_int_equal(fbrl_uart_isr_tx(&B.u), FBRL_XOFF);
    assert_int_equal(fbrl_uart_isr_tx(&B.u), data[0]); /* then the queued data */
    uint8_t buf[64];
    size_t got;
    int kicks = B.kicks;
    assert_int_equal(fbrl_uart_read(&B.u, buf, 32, &got, 0), FBRL_OK); /* 16 left: at 1/4 */
    assert_int_equal(got, 32);
    assert_true(B.kicks > kicks); /* the reader woke the transmitter for XON */
    assert_int_equal(fbrl_uart_isr_tx(&B.u), FBRL_XON);
    assert_int_equal(fbrl_uart_isr_tx(&B.u), data[1]);
}

/* The peer's XOFF stops data but not our own flow-control bytes. */
static void held_transmitter_still_sends_xoff(void **state)
{
    (void)state;
    size_t n;
    assert_int_equal(fbrl_uart_write(&B.u, "abc", 3, &n, 0), FBRL_OK);
    fbrl_uart_isr_rx(&B.u, FBRL_XOFF);
    assert_int_equal(fbrl_uart_isr_tx(&B.u), -1);
    for (int i = 0; i < 48; i++)
        fbrl_uart_isr_rx(&B.u, 'z');
    assert_int_equal(fbrl_uart_isr_tx(&B.u), FBRL_XOFF);
    assert_int_equal(fbrl_uart_isr_tx(&B.u), -1);
    /* A second XOFF from the peer while held changes nothing but the count. */
    fbrl_uart_isr_rx(&B.u, FBRL_XOFF);
    fbrl_uart_isr_rx(&B.u, FBRL_XON);
    assert_int_equal(fbrl_uart_isr_tx(&B.u), 'a');
    fbrl_uart_counters c;
    fbrl_uart_get_counters(&B.u, &c);
    assert_int_equal(c.xoff_received, 2);
    /* A stray XON (not held) is swallowed and ignored. */
    fbrl_uart_isr_rx(&B.u, FBRL_XON);
    assert_int_equal(fbrl_uart_rx_available(&B.u), 48);
}

/* A full ring counts an overrun and sends XOFF again, as the thesis's READ-COM does. */
static void overrun_is_counted_and_xoff_resent(void **state)
{
    (void)state;
    for (int i = 0; i < 64; i++)
        fbrl_uart_isr_rx(&B.u, 'q');
    assert_int_equal(fbrl_uart_isr_tx(&B.u), FBRL_XOFF);
    fbrl_uart_isr_rx(&B.u, 'r'); /* the peer did not stop: lost */
    fbrl_uart_isr_rx(&B.u, 's');
    assert_int_equal(fbrl_uart_isr_tx(&B.u), FBRL_XOFF);
    assert_int_equal(fbrl_uart_isr_tx(&B.u), -1);
    fbrl_uart_counters c;
    fbrl_uart_get_counters(&B.u, &c);
    assert_int_equal(c.overruns, 2);
    assert_int_equal(c.xoff_sent, 2);
    assert_int_equal(c.rx_bytes, 64);
}

/* Without flow control 0x11/0x13 are ordinary data and nothing is ever held. */
static void no_flow_control_passes_everything(void **state)
{
    (void)state;
    uint8_t all[256], in[256];
    size_t n, have = 0;
    for (int i = 0; i < 256; i++)
        all[i] = (uint8_t)i;
    size_t sent = 0;
    for (int rounds = 0; rounds < 1000 && have < 256; rounds++) {
        if (sent < 256 && fbrl_uart_write(&A.u, all + sent, 256 - sent, &n, 0) != FBRL_EINVAL)
            sent += n;
        size_t got;
        if (fbrl_uart_read(&B.u, in + have, 256 - have, &got, 5) == FBRL_OK)
            have += got;
    }
    assert_int_equal(have, 256);
    assert_memory_equal(in, all, 256);
    for (int i = 0; i < 70; i++) /* overflow: counted, no XOFF */
        fbrl_uart_isr_rx(&B.u, 'x');
    assert_int_equal(fbrl_uart_isr_tx(&B.u), -1);
    fbrl_uart_counters c;
    fbrl_uart_get_counters(&B.u, &c);
    assert_int_equal(c.overruns, 6);
    assert_int_equal(c.xoff_sent, 0);
}

/* Taking bytes from a full ring wakes the backend (it may have stopped receiving). */
static void reading_a_full_ring_kicks_the_backend(void **state)
{
    (void)state;
    uint8_t buf[8];
    size_t n;
    for (int i = 0; i < 64; i++)
        fbrl_uart_isr_rx(&B.u, 'f');
    assert_int_equal(fbrl_uart_rx_room(&B.u), 0);
    int kicks = B.kicks;
    assert_int_equal(fbrl_uart_read(&B.u, buf, sizeof buf, &n, 0), FBRL_OK);
    assert_int_equal(B.kicks, kicks + 1);
    assert_int_equal(fbrl_uart_rx_room(&B.u), 8);
    assert_int_equal(fbrl_uart_read(&B.u, buf, sizeof buf, &n, 0), FBRL_OK);
    assert_int_equal(B.kicks, kicks + 1); /* not full before this read: no kick */
    assert_int_equal(fbrl_uart_rx_room(NULL), 0);
}

/* A polled backend gets the bytes within the write call (ops->flush): no service call,
 * no read needed, the peer has them when write returns; and the XON a read makes due
 * leaves within that read, even when the read found its bytes in the ring. */
static void write_hands_bytes_over_at_once(void **state)
{
    (void)state;
    const char msg[] = "SPEED 50\r";
    uint8_t buf[64];
    size_t n;
    assert_int_equal(fbrl_uart_write(&A.u, msg, sizeof msg - 1, &n, 0), FBRL_OK);
    assert_int_equal(A.services, 0);
    assert_int_equal(A.flushes, 1);
    assert_int_equal(fbrl_uart_tx_pending(&A.u), 0);
    assert_int_equal(fbrl_ring_read(&B.u.rx, buf, sizeof buf, &n), FBRL_OK);
    assert_int_equal(n, sizeof msg - 1);
    assert_memory_equal(buf, msg, n);
    assert_int_equal(fbrl_uart_write(&A.u, msg, 0, &n, 0), FBRL_OK); /* nothing queued: no flush */
    assert_int_equal(A.flushes, 1);
    for (int i = 0; i < 48; i++) /* B passes its high-water mark: XOFF goes out */
        fbrl_uart_isr_rx(&B.u, 'a');
    assert_int_equal(fbrl_uart_isr_tx(&B.u), FBRL_XOFF);
    assert_int_equal(fbrl_uart_read(&B.u, buf, 32, &n, 0), FBRL_OK); /* down to 1/4 */
    assert_int_equal(n, 32);
    assert_int_equal(B.services, 0);
    assert_true(B.flushes >= 1);
    assert_int_equal(fbrl_ring_get(&A.u.rx, buf), FBRL_EEMPTY); /* the XON was obeyed, not stored */
    fbrl_uart_counters c;
    assert_int_equal(fbrl_uart_get_counters(&B.u, &c), FBRL_OK);
    assert_int_equal(c.xoff_sent, 1);
    assert_int_equal(fbrl_uart_isr_tx(&B.u), -1); /* the XON is no longer due: it left */
    A.service_result = FBRL_EDISCONNECTED;        /* the line is gone: the write says so */
    assert_int_equal(fbrl_uart_write(&A.u, msg, sizeof msg - 1, &n, 0), FBRL_EDISCONNECTED);
    assert_int_equal(n, sizeof msg - 1);
}

/* Turning flow control off while we hold the peer off sends the XON it waits for. */
static void flow_off_releases_the_peer(void **state)
{
    (void)state;
    for (int i = 0; i < 50; i++)
        fbrl_uart_isr_rx(&B.u, 'k');
    assert_int_equal(fbrl_uart_isr_tx(&B.u), FBRL_XOFF);
    assert_int_equal(fbrl_uart_isr_tx(&B.u), -1);
    fbrl_uart_config cfg = FBRL_UART_CONFIG_DEFAULT;
    cfg.flow = FBRL_FLOW_NONE;
    assert_int_equal(fbrl_uart_configure(&B.u, &cfg), FBRL_OK);
    assert_int_equal(fbrl_uart_isr_tx(&B.u), FBRL_XON);
    fbrl_uart_isr_rx(&B.u, FBRL_XOFF); /* now plain data */
    assert_int_equal(fbrl_uart_rx_available(&B.u), 51);
}

static void line_status_counts(void **state)
{
    (void)state;
    fbrl_uart_isr_line_status(&A.u, FBRL_UART_LS_PARITY);
    fbrl_uart_isr_line_status(&A.u, FBRL_UART_LS_FRAMING | FBRL_UART_LS_PARITY);
    fbrl_uart_isr_line_status(&A.u, FBRL_UART_LS_OVERRUN);
    fbrl_uart_isr_line_status(&A.u, 0);
    fbrl_uart_counters c;
    fbrl_uart_get_counters(&A.u, &c);
    assert_int_equal(c.parity_errors, 2);
    assert_int_equal(c.framing_errors, 1);
    assert_int_equal(c.overruns, 1);
}

/* A backend error (the peer hung up) comes after the bytes that arrived first. */
static void disconnect_after_buffered_bytes(void **state)
{
    (void)state;
    uint8_t buf[8];
    size_t n;
    fbrl_uart_isr_rx(&B.u, 'o');
    fbrl_uart_isr_rx(&B.u, 'k');
    B.service_result = FBRL_EDISCONNECTED;
    assert_int_equal(fbrl_uart_read(&B.u, buf, sizeof buf, &n, 100), FBRL_OK);
    assert_int_equal(n, 2);
    assert_memory_equal(buf, "ok", 2);
    assert_int_equal(fbrl_uart_read(&B.u, buf, sizeof buf, &n, 100), FBRL_EDISCONNECTED);
    assert_int_equal(n, 0);
    /* write and drain report it too once they have to wait */
    uint8_t big[200] = {0};
    assert_int_equal(fbrl_uart_write(&B.u, big, sizeof big, &n, 100), FBRL_EDISCONNECTED);
    assert_int_equal(n, 64);
    assert_int_equal(fbrl_uart_drain(&B.u, 100), FBRL_EDISCONNECTED);
}

/* On a 32-bit target the interrupt side's counters are 32 bits wide; the totals the
 * main line keeps stay exact across a wrap. (White box: start the raw counter just
 * below the wrap, as it would be after 4 GB.) */
static void counters_survive_a_wrap(void **state)
{
    (void)state;
    fbrl_uart_counters c;
    B.u.raw[0] = B.u.seen[0] = SIZE_MAX - 1; /* slot 0 = rx_bytes */
    for (int i = 0; i < 5; i++)
        fbrl_uart_isr_rx(&B.u, 'w');
    assert_int_equal(fbrl_uart_get_counters(&B.u, &c), FBRL_OK);
    assert_int_equal(c.rx_bytes, 5);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(bad_input_gives_errors),
        cmocka_unit_test_setup(settings_reach_the_backend, setup_xon),
        cmocka_unit_test_setup(bytes_cross_in_order, setup_xon),
        cmocka_unit_test_setup(timeouts_are_kept, setup_xon),
        cmocka_unit_test_setup(xoff_holds_the_sender_and_xon_releases_it, setup_xon),
        cmocka_unit_test_setup(flow_control_bytes_go_first, setup_xon),
        cmocka_unit_test_setup(held_transmitter_still_sends_xoff, setup_xon),
        cmocka_unit_test_setup(overrun_is_counted_and_xoff_resent, setup_xon),
        cmocka_unit_test_setup(no_flow_control_passes_everything, setup_none),
        cmocka_unit_test_setup(flow_off_releases_the_peer, setup_xon),
        cmocka_unit_test_setup(write_hands_bytes_over_at_once, setup_flush),
        cmocka_unit_test_setup(reading_a_full_ring_kicks_the_backend, setup_none),
        cmocka_unit_test_setup(line_status_counts, setup_xon),
        cmocka_unit_test_setup(disconnect_after_buffered_bytes, setup_xon),
        cmocka_unit_test_setup(counters_survive_a_wrap, setup_xon),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
