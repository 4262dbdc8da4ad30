/* SPDX-License-Identifier: MIT */
/* test_uart_pl011.c - the PL011 backend against a register model.
 *
 * The model below is the hardware boundary (the only place the project allows a
 * stand-in): a PL011 as the ARM TRM describes it - 16-byte FIFOs, the divisors latched
 * by the LCRH write, DR's error bits, raw and masked interrupt status, TX raised while
 * the transmit FIFO is at or below its level - with every register write logged.
 * Everything above it is real: the backend and the driver core with its rings and flow
 * control. The firmware's QEMU tests (tests/qemu/cm3_*.sh) run the same code on QEMU's
 * PL011; this test checks what QEMU cannot show (divisors, line settings, refusals,
 * errors, the exact interrupt masks). */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/uart.h"
#include "fbrl/uart_pl011.h"

#define CLOCK_50MHZ 50000000u
#define FIFO        16u
#define TX_LEVEL    2u /* IFLS_DEFAULT: TX at or below 1/8 full */

/* ---------------------------------------------------------------- the model */

typedef struct wlog {
    uint32_t off, val;
} wlog;

typedef struct model {
    uint32_t ibrd, fbrd, lcrh, cr, ifls, imsc, ris;
    uint32_t ibrd_latched, fbrd_latched; /* what the LCRH write took */
    uint16_t rx[512];                    /* data | error bits, as DR reads them */
    unsigned rx_head, rx_n;
    unsigned tx_fifo; /* bytes waiting in the transmit FIFO */
    unsigned tx_overflow;
    uint8_t tx[4096]; /* every byte written to DR, in order */
    size_t tx_n;
    uint64_t now;
    unsigned saved_depth;
    wlog log[256];
    size_t nlog;
} model;

static model M;
static fbrl_uart_pl011 B;
static fbrl_uart U;
static uint8_t rx_mem[256], tx_mem[256];

static void model_reset(void)
{
    memset(&M, 0, sizeof M);
    /* TX is raised at reset: the FIFO is empty, below every level */
    M.ris = FBRL_PL011_INT_TX;
}

static void update_tx_level(model *m)
{
    if (m->tx_fifo <= TX_LEVEL)
        m->ris |= FBRL_PL011_INT_TX;
}

static void model_rx_err(model *m, uint8_t byte, uint16_t err)
{
    if (m->rx_n < FIFO) {
        m->rx[(m->rx_head + m->rx_n++) % FIFO] = (uint16_t)(byte | err);
        m->ris |= FBRL_PL011_INT_RX;
        if (err & FBRL_PL011_DR_FE)
            m->ris |= FBRL_PL011_INT_FE;
        if (err & FBRL_PL011_DR_PE)
            m->ris |= FBRL_PL011_INT_PE;
    }
}

/* Feed up to what the FIFO takes; returns how many were taken. */
static size_t model_rx(model *m, const char *s, size_t n)
{
    size_t k = 0;
    while (k < n && m->rx_n < FIFO)
        model_rx_err(m, (uint8_t)s[k++], 0);
    return k;
}

/* The transmitter sends everything in its FIFO. */
static void model_tx_done(model *m)
{
    m->tx_fifo = 0;
    update_tx_level(m);
}

static uint32_t io_read(void *ctx, uint32_t off)
{
    model *m = ctx;
    switch (off) {
    case FBRL_PL011_DR: {
        uint32_t v = 0;
        if (m->rx_n) {
            v = m->rx[m->rx_head];
            m->rx_head = (m->rx_head + 1) % FIFO;
            m->rx_n--;
        }
        if (m->rx_n == 0)
            m->ris &= ~(FBRL_PL011_INT_RX | FBRL_PL011_INT_RT);
        return v;
    }
    case FBRL_PL011_FR:
        return (m->rx_n == 0 ? FBRL_PL011_FR_RXFE : 0) | (m->rx_n == FIFO ? FBRL_PL011_FR_RXFF : 0) |
               (m->tx_fifo == 0 ? FBRL_PL011_FR_TXFE : 0) | (m->tx_fifo == FIFO ? FBRL_PL011_FR_TXFF : 0);
    case FBRL_PL011_IBRD: return m->ibrd;
    case FBRL_PL011_FBRD: return m->fbrd;
    case FBRL_PL011_LCRH: return m->lcrh;
    case FBRL_PL011_CR: return m->cr;
    case FBRL_PL011_IFLS: return m->ifls;
    case FBRL_PL011_IMSC: return m->imsc;
    case FBRL_PL011_RIS: return m->ris;
    case FBRL_PL011_MIS: return m->ris & m->imsc;
    default: fail_msg("read of register 0x%03x", (unsigned)off); return 0;
    }
}

static void io_write(void *ctx, uint32_t off, uint32_t v)
{
    model *m = ctx;
    if (m->nlog < sizeof m->log / sizeof m->log[0])
        m->log[m->nlog++] = (wlog){off, v};
    switch (off) {
    case FBRL_PL011_DR:
        if (m->tx_fifo == FIFO) {
            m->tx_overflow++;
            return;
        }
        m->tx_fifo++;
        if (m->tx_n < sizeof m->tx)
            m->tx[m->tx_n++] = (uint8_t)v;
        if (m->tx_fifo > TX_LEVEL)
            m->ris &= ~FBRL_PL011_INT_TX;
        break;
    case FBRL_PL011_RSR: break;
    case FBRL_PL011_IBRD: m->ibrd = v; break;
    case FBRL_PL011_FBRD: m->fbrd = v; break;
    case FBRL_PL011_LCRH:
        m->lcrh = v;
        m->ibrd_latched = m->ibrd;
        m->fbrd_latched = m->fbrd;
        break;
    case FBRL_PL011_CR: m->cr = v; break;
    case FBRL_PL011_IFLS: m->ifls = v; break;
    case FBRL_PL011_IMSC: m->imsc = v; break;
    case FBRL_PL011_ICR: m->ris &= ~v; break;
    default: fail_msg("write of register 0x%03x", (unsigned)off);
    }
}

static uint32_t io_irq_save(void *ctx)
{
    model *m = ctx;
    return m->saved_depth++;
}

static void io_irq_restore(void *ctx, uint32_t saved)
{
    model *m = ctx;
    assert_int_equal(m->saved_depth, saved + 1);
    m->saved_depth = saved;
}

/* Sleeping: a millisecond passes, the transmitter empties, and a pending, unmasked
 * interrupt runs the handler (as the NVIC would). */
static void io_idle(void *ctx)
{
    model *m = ctx;
    m->now += 1000;
    model_tx_done(m);
    if (m->ris & m->imsc)
        fbrl_uart_pl011_isr(&B);
}

static uint64_t io_now_us(void *ctx) { return ((model *)ctx)->now; }

static const fbrl_uart_pl011_io IO = {io_read, io_write, io_irq_save, io_irq_restore, io_idle, io_now_us, &M};

static void open_port(size_t rx_size, const fbrl_uart_config *cfg)
{
    fbrl_uart_config def = FBRL_UART_CONFIG_DEFAULT;
    model_reset();
    assert_int_equal(fbrl_uart_pl011_init(&B, &IO, CLOCK_50MHZ), FBRL_OK);
    assert_int_equal(fbrl_uart_init(&U, &fbrl_uart_pl011_ops, &B, rx_mem, rx_size, tx_mem, sizeof tx_mem,
                                    cfg ? cfg : &def),
                     FBRL_OK);
    assert_int_equal(fbrl_uart_pl011_attach(&B, &U), FBRL_OK);
}

static size_t read_all(uint8_t *out, size_t cap)
{
    size_t got = 0;
    assert_int_equal(fbrl_uart_read(&U, out, cap, &got, 0), FBRL_OK);
    return got;
}

static fbrl_uart_counters counters(void)
{
    fbrl_uart_counters c;
    assert_int_equal(fbrl_uart_get_counters(&U, &c), FBRL_OK);
    return c;
}

/* ---------------------------------------------------------------- line settings */

/* Divisors worked out by hand from the TRM's formula, UARTCLK / (16 x baud) with the
 * fraction in 1/64 rounded: 50 MHz / (16 x 115200) = 27.127 -> 27 + 8/64, and so on. */
static void test_configure_divisors(void **state)
{
    static const struct {
        uint32_t baud, ibrd, fbrd;
    } want[] = {{115200, 27, 8}, {57600, 54, 16}, {38400, 81, 24},  {19200, 162, 49},
                {9600, 325, 33}, {2400, 1302, 5}, {300, 10416, 43}, {50, 62500, 0}};
    (void)state;
    for (size_t k = 0; k < sizeof want / sizeof want[0]; k++) {
        fbrl_uart_config c = FBRL_UART_CONFIG_DEFAULT;
        c.baud = want[k].baud;
        open_port(sizeof rx_mem, &c);
        assert_int_equal(M.ibrd_latched, want[k].ibrd);
        assert_int_equal(M.fbrd_latched, want[k].fbrd);
        assert_int_equal(M.cr, FBRL_PL011_CR_RXE | FBRL_PL011_CR_TXE | FBRL_PL011_CR_UARTEN);
        assert_int_equal(M.ifls, FBRL_PL011_IFLS_DEFAULT);
    }
}

/* LCRH for data bits, parity and stop bits (TRM bit layout), FIFOs always on; and the
 * TRM's order: UART off, divisors, LCRH (which latches them), UART on last. */
static void test_configure_line(void **state)
{
    static const struct {
        uint8_t bits;
        fbrl_parity parity;
        uint8_t stop;
        uint32_t lcrh;
    } want[] = {{8, FBRL_PARITY_NONE, 1, 0x70},
                {7, FBRL_PARITY_EVEN, 1, 0x56},
                {8, FBRL_PARITY_NONE, 2, 0x78},
                {5, FBRL_PARITY_ODD, 1, 0x12},
                {6, FBRL_PARITY_ODD, 2, 0x3A}};
    (void)state;
    for (size_t k = 0; k < sizeof want / sizeof want[0]; k++) {
        fbrl_uart_config c = {9600, want[k].bits, want[k].parity, want[k].stop, FBRL_FLOW_NONE};
        open_port(sizeof rx_mem, &c);
        assert_int_equal(M.lcrh, want[k].lcrh);
    }
    open_port(sizeof rx_mem, NULL);
    M.nlog = 0;
    fbrl_uart_config c = FBRL_UART_CONFIG_DEFAULT;
    assert_int_equal(fbrl_uart_configure(&U, &c), FBRL_OK);
    assert_true(M.nlog >= 4);
    assert_int_equal(M.log[0].off, FBRL_PL011_CR);
    assert_int_equal(M.log[0].val, 0);
    size_t at_lcrh = 0, at_ibrd = 0, at_cr = 0;
    for (size_t k = 0; k < M.nlog; k++) {
        if (M.log[k].off == FBRL_PL011_LCRH)
            at_lcrh = k;
        if (M.log[k].off == FBRL_PL011_IBRD)
            at_ibrd = k;
        if (M.log[k].off == FBRL_PL011_CR)
            at_cr = k;
    }
    assert_true(at_ibrd > 0 && at_lcrh > at_ibrd && at_cr > at_lcrh);
    assert_int_equal(M.log[at_cr].val, FBRL_PL011_CR_RXE | FBRL_PL011_CR_TXE | FBRL_PL011_CR_UARTEN);
    /* the interrupt mask survives a new setting */
    assert_int_equal(M.imsc, FBRL_PL011_INT_RX | FBRL_PL011_INT_RT | FBRL_PL011_INT_ERR);
}

/* What the chip cannot do is refused and touches no register. */
static void test_configure_unsupported(void **state)
{
    static const fbrl_uart_config bad[] = {
        {0, 8, FBRL_PARITY_NONE, 1, FBRL_FLOW_NONE},       /* no rate */
        {4000000, 8, FBRL_PARITY_NONE, 1, FBRL_FLOW_NONE}, /* above UARTCLK / 16 */
        {45, 8, FBRL_PARITY_NONE, 1, FBRL_FLOW_NONE},      /* IBRD past 16 bits */
        {9600, 9, FBRL_PARITY_NONE, 1, FBRL_FLOW_NONE},    {9600, 4, FBRL_PARITY_NONE, 1, FBRL_FLOW_NONE},
        {9600, 8, FBRL_PARITY_NONE, 3, FBRL_FLOW_NONE},    {9600, 8, FBRL_PARITY_NONE, 1, (fbrl_flow)2},
        {9600, 8, (fbrl_parity)7, 1, FBRL_FLOW_NONE},
    };
    (void)state;
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        open_port(sizeof rx_mem, NULL);
        M.nlog = 0;
        /* the backend itself (the core refuses some of these before it) */
        assert_int_equal(fbrl_uart_pl011_ops.configure(&B, &bad[k]), FBRL_EUNSUPPORTED);
        assert_int_equal(M.nlog, 0);
    }
    /* the fastest rate, UARTCLK / 16 (IBRD 1), is still taken */
    open_port(sizeof rx_mem, NULL);
    fbrl_uart_config c = FBRL_UART_CONFIG_DEFAULT;
    c.baud = CLOCK_50MHZ / 16u;
    assert_int_equal(fbrl_uart_configure(&U, &c), FBRL_OK);
    assert_int_equal(M.ibrd_latched, 1);
    assert_int_equal(M.fbrd_latched, 0);
}

static void test_init_arguments(void **state)
{
    fbrl_uart_pl011_io io = IO;
    (void)state;
    assert_int_equal(fbrl_uart_pl011_init(NULL, &IO, CLOCK_50MHZ), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_pl011_init(&B, NULL, CLOCK_50MHZ), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_pl011_init(&B, &IO, 0), FBRL_ERANGE);
    io.idle = NULL;
    assert_int_equal(fbrl_uart_pl011_init(&B, &io, CLOCK_50MHZ), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_pl011_attach(NULL, &U), FBRL_EINVAL);
}

/* ---------------------------------------------------------------- the handler */

static void test_isr_receive(void **state)
{
    uint8_t out[32];
    (void)state;
    open_port(sizeof rx_mem, NULL);
    assert_int_equal(model_rx(&M, "hello", 5), 5);
    fbrl_uart_pl011_isr(&B);
    assert_int_equal(read_all(out, sizeof out), 5);
    assert_memory_equal(out, "hello", 5);
    assert_int_equal(M.rx_n, 0);
    assert_int_equal(M.ris & M.imsc, 0); /* nothing left pending */
}

/* Bytes that arrived before attach raise no interrupt of their own: attach takes them. */
static void test_attach_takes_waiting_bytes(void **state)
{
    fbrl_uart_config c = FBRL_UART_CONFIG_DEFAULT;
    uint8_t out[8];
    (void)state;
    model_reset();
    assert_int_equal(model_rx(&M, "ab", 2), 2);
    assert_int_equal(fbrl_uart_pl011_init(&B, &IO, CLOCK_50MHZ), FBRL_OK);
    assert_int_equal(
        fbrl_uart_init(&U, &fbrl_uart_pl011_ops, &B, rx_mem, sizeof rx_mem, tx_mem, sizeof tx_mem, &c),
        FBRL_OK);
    assert_int_equal(fbrl_uart_pl011_attach(&B, &U), FBRL_OK);
    assert_int_equal(read_all(out, sizeof out), 2);
    assert_memory_equal(out, "ab", 2);
}

/* DR's per-byte error bits reach the core's counters; the byte is still delivered. */
static void test_isr_errors(void **state)
{
    uint8_t out[8];
    (void)state;
    open_port(sizeof rx_mem, NULL);
    model_rx_err(&M, 'p', FBRL_PL011_DR_PE);
    model_rx_err(&M, 'f', FBRL_PL011_DR_FE);
    model_rx_err(&M, 'b', FBRL_PL011_DR_BE | FBRL_PL011_DR_FE);
    model_rx_err(&M, 'o', FBRL_PL011_DR_OE);
    fbrl_uart_pl011_isr(&B);
    fbrl_uart_counters c = counters();
    assert_int_equal(c.parity_errors, 1);
    assert_int_equal(c.framing_errors, 2);
    assert_int_equal(c.overruns, 1);
    assert_int_equal(read_all(out, sizeof out), 4);
    assert_memory_equal(out, "pfbo", 4);
    assert_int_equal(M.ris & FBRL_PL011_INT_ERR, 0); /* the summary bits were cleared */
}

/* Transmit: the main line primes the FIFO (no TX edge comes for an idle FIFO), the
 * handler refills it at the level, and TX is masked again once the core is empty. The
 * FIFO never overflows. */
static void test_isr_transmit(void **state)
{
    char msg[100];
    size_t written = 0;
    (void)state;
    for (size_t k = 0; k < sizeof msg; k++)
        msg[k] = (char)('A' + k % 26);
    open_port(sizeof rx_mem, NULL);
    assert_int_equal(fbrl_uart_write(&U, msg, sizeof msg, &written, 0), FBRL_OK);
    assert_int_equal(written, sizeof msg);
    assert_int_equal(M.tx_n, FIFO); /* primed: one FIFO's worth */
    assert_true(M.imsc & FBRL_PL011_INT_TX);
    while (M.tx_n < sizeof msg) {
        size_t before = M.tx_n;
        model_tx_done(&M);
        fbrl_uart_pl011_isr(&B);
        assert_true(M.tx_n > before);
    }
    assert_memory_equal(M.tx, msg, sizeof msg);
    assert_int_equal(M.tx_overflow, 0);
    model_tx_done(&M);
    fbrl_uart_pl011_isr(&B); /* nothing left: TX off, or it would fire forever */
    assert_false(M.imsc & FBRL_PL011_INT_TX);
    assert_int_equal(M.ris & M.imsc, 0);
    assert_int_equal(counters().tx_bytes, sizeof msg);
}

/* Headroom: with the ring nearly full the handler masks RX/RT and leaves the bytes in
 * the FIFO; service() takes them once the reader made room. Nothing is lost. */
static void test_isr_rx_headroom(void **state)
{
    char in[300];
    uint8_t out[300];
    size_t fed = 0, got = 0;
    fbrl_uart_config c = {9600, 8, FBRL_PARITY_NONE, 1, FBRL_FLOW_NONE};
    fbrl_uart_pl011_stats st;
    int paused = 0;
    (void)state;
    for (size_t k = 0; k < sizeof in; k++)
        in[k] = (char)('a' + k % 26);
    open_port(64, &c);
    /* nobody reads: the ring fills to its headroom, then the FIFO holds the rest */
    for (int k = 0; k < 8 && (M.imsc & FBRL_PL011_INT_RX); k++) {
        fed += model_rx(&M, in + fed, sizeof in - fed);
        fbrl_uart_pl011_isr(&B);
    }
    paused = !(M.imsc & FBRL_PL011_INT_RX);
    assert_true(M.rx_n > 0); /* held in the FIFO, not dropped */
    assert_int_equal(fed, fbrl_uart_rx_available(&U) + M.rx_n);
    while (got < sizeof in) {
        fed += model_rx(&M, in + fed, sizeof in - fed);
        if (M.ris & M.imsc)
            fbrl_uart_pl011_isr(&B);
        size_t n = read_all(out + got, sizeof out - got);
        got += n;
        if (n == 0)
            assert_int_equal(fbrl_uart_pl011_ops.service(&B, 0), FBRL_OK);
    }
    assert_memory_equal(out, in, sizeof in);
    assert_int_equal(counters().overruns, 0);
    assert_true(paused);
    assert_int_equal(fbrl_uart_pl011_get_stats(&B, &st), FBRL_OK);
    assert_true(st.throttles >= 1);
    assert_true(M.imsc & FBRL_PL011_INT_RX);
}

/* XON/XOFF through the handler: the core's XOFF goes out when its ring fills; the
 * peer's XOFF holds output in the core, its XON restarts the idle transmitter. */
static void test_xon_xoff_through_isr(void **state)
{
    uint8_t out[64];
    size_t written = 0, k;
    (void)state;
    open_port(64, NULL);
    for (k = 0; k < 3; k++) {
        model_rx(&M, "qqqqqqqqqqqqqqqq", 16);
        fbrl_uart_pl011_isr(&B);
    }
    assert_true(counters().xoff_sent >= 1);
    assert_true(M.tx_n >= 1);
    assert_int_equal(M.tx[M.tx_n - 1], FBRL_XOFF);
    (void)read_all(out, sizeof out);

    open_port(sizeof rx_mem, NULL);
    model_rx(&M, "\x13", 1);
    fbrl_uart_pl011_isr(&B);
    assert_int_equal(counters().xoff_received, 1);
    assert_int_equal(fbrl_uart_write(&U, "held", 4, &written, 0), FBRL_OK);
    model_tx_done(&M);
    if (M.ris & M.imsc)
        fbrl_uart_pl011_isr(&B);
    assert_int_equal(M.tx_n, 0);
    model_rx(&M, "\x11", 1);
    fbrl_uart_pl011_isr(&B);
    assert_int_equal(M.tx_n, 4);
    assert_memory_equal(M.tx, "held", 4);
}

/* service() sleeps until the handler moved a byte, or until the deadline. */
static void test_service_waits(void **state)
{
    (void)state;
    open_port(sizeof rx_mem, NULL);
    uint64_t t0 = M.now;
    assert_int_equal(fbrl_uart_pl011_ops.service(&B, 5000), FBRL_OK);
    assert_true(M.now - t0 >= 5000);
    model_rx(&M, "x", 1);
    t0 = M.now;
    assert_int_equal(fbrl_uart_pl011_ops.service(&B, 50000), FBRL_OK);
    assert_true(M.now - t0 <= 1000); /* woke at the first interrupt */
    assert_int_equal(fbrl_uart_rx_available(&U), 1);
}

static void test_close(void **state)
{
    (void)state;
    open_port(sizeof rx_mem, NULL);
    assert_int_equal(fbrl_uart_close(&U), FBRL_OK);
    assert_int_equal(M.imsc, 0);
    assert_int_equal(M.cr, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_configure_divisors),
        cmocka_unit_test(test_configure_line),
        cmocka_unit_test(test_configure_unsupported),
        cmocka_unit_test(test_init_arguments),
        cmocka_unit_test(test_isr_receive),
        cmocka_unit_test(test_attach_takes_waiting_bytes),
        cmocka_unit_test(test_isr_errors),
        cmocka_unit_test(test_isr_transmit),
        cmocka_unit_test(test_isr_rx_headroom),
        cmocka_unit_test(test_xon_xoff_through_isr),
        cmocka_unit_test(test_service_waits),
        cmocka_unit_test(test_close),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
