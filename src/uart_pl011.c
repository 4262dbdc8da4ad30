/* SPDX-License-Identifier: MIT */
/* uart_pl011.c - ARM PL011 backend: line programming, interrupt handler, headroom rule.
 *
 * Concurrency: the handler (interrupt side) and the ops (main line) share the UART's
 * registers and the IMSC shadow. The main line touches them only inside the board's
 * irq_save/irq_restore, so on one CPU the two never interleave (as in uart_8250.c). */
#include "fbrl/uart_pl011.h"

#define IBRD_MAX            0xFFFFu
#define DIV64_FRACTION_BITS 6u /* FBRD is in 1/64 */

static uint32_t rd(fbrl_uart_pl011 *b, uint32_t off) { return b->io.read(b->io.io_ctx, off); }

static void wr(fbrl_uart_pl011 *b, uint32_t off, uint32_t v) { b->io.write(b->io.io_ctx, off, v); }

static void set_imsc(fbrl_uart_pl011 *b, uint32_t imsc)
{
    if (imsc != b->imsc) {
        b->imsc = imsc;
        wr(b, FBRL_PL011_IMSC, imsc);
    }
}

fbrl_status fbrl_uart_pl011_init(fbrl_uart_pl011 *b, const fbrl_uart_pl011_io *io, uint32_t clock_hz)
{
    if (!b || !io || !io->read || !io->write || !io->irq_save || !io->irq_restore || !io->idle || !io->now_us)
        return FBRL_EINVAL;
    if (clock_hz == 0)
        return FBRL_ERANGE;
    b->io = *io;
    b->uart = NULL;
    b->clock_hz = clock_hz;
    b->headroom = FBRL_UART_PL011_RX_HEADROOM;
    b->imsc = 0;
    b->events = 0;
    b->seen = 0;
    b->stats = (fbrl_uart_pl011_stats){0, 0, 0, 0};
    return FBRL_OK;
}

/* LCRH for a line setting, or -1 when the PL011 cannot do it. */
static int32_t lcrh_for(const fbrl_uart_config *cfg)
{
    uint32_t lcrh = FBRL_PL011_LCRH_FEN;
    if (cfg->data_bits < 5 || cfg->data_bits > 8)
        return -1;
    lcrh |= (uint32_t)(cfg->data_bits - 5) << 5;
    if (cfg->stop_bits == 2)
        lcrh |= FBRL_PL011_LCRH_STP2;
    else if (cfg->stop_bits != 1)
        return -1;
    switch (cfg->parity) {
    case FBRL_PARITY_NONE: break;
    case FBRL_PARITY_ODD: lcrh |= FBRL_PL011_LCRH_PEN; break;
    case FBRL_PARITY_EVEN: lcrh |= FBRL_PL011_LCRH_PEN | FBRL_PL011_LCRH_EPS; break;
    default: return -1;
    }
    return (int32_t)lcrh;
}

static fbrl_status op_configure(void *ctx, const fbrl_uart_config *cfg)
{
    fbrl_uart_pl011 *b = ctx;
    uint64_t div64;
    uint32_t saved, ibrd;
    int32_t lcrh;
    if (!b || !cfg)
        return FBRL_EINVAL;
    if (cfg->flow != FBRL_FLOW_NONE && cfg->flow != FBRL_FLOW_XONXOFF)
        return FBRL_EUNSUPPORTED; /* XON/XOFF is the core's; RTS/CTS is not wired here */
    if (cfg->baud == 0)
        return FBRL_EUNSUPPORTED;
    /* Divisor = UARTCLK / (16 x baud), in 1/64: UARTCLK x 4 / baud, rounded. With IBRD at
     * least 1 the rounding is within 1/128 of the divisor (0.8 %), well inside what a
     * frame tolerates, so a rate is refused only when the divisor is out of range. */
    div64 = ((uint64_t)b->clock_hz * 4u + cfg->baud / 2u) / cfg->baud;
    ibrd = (uint32_t)(div64 >> DIV64_FRACTION_BITS);
    if (ibrd == 0 || ibrd > IBRD_MAX)
        return FBRL_EUNSUPPORTED;
    lcrh = lcrh_for(cfg);
    if (lcrh < 0)
        return FBRL_EUNSUPPORTED;

    saved = b->io.irq_save(b->io.io_ctx);
    /* The TRM's order: disable, wait for the last frame, flush by FEN off, program,
     * enable. Bytes already in the receive FIFO stay there. */
    wr(b, FBRL_PL011_CR, 0);
    while (rd(b, FBRL_PL011_FR) & FBRL_PL011_FR_BUSY) {
    }
    wr(b, FBRL_PL011_LCRH, 0);
    wr(b, FBRL_PL011_IBRD, ibrd);
    wr(b, FBRL_PL011_FBRD, (uint32_t)(div64 & ((1u << DIV64_FRACTION_BITS) - 1u)));
    wr(b, FBRL_PL011_LCRH, (uint32_t)lcrh); /* latches the divisors */
    wr(b, FBRL_PL011_IFLS, FBRL_PL011_IFLS_DEFAULT);
    wr(b, FBRL_PL011_ICR, FBRL_PL011_INT_ERR);
    wr(b, FBRL_PL011_RSR, 0);
    wr(b, FBRL_PL011_IMSC, b->imsc);
    wr(b, FBRL_PL011_CR, FBRL_PL011_CR_RXE | FBRL_PL011_CR_TXE | FBRL_PL011_CR_UARTEN);
    b->io.irq_restore(b->io.io_ctx, saved);
    return FBRL_OK;
}

/* Free bytes in the core's receive ring: exact for the producer, which the handler is. */
static size_t rx_room(const fbrl_uart_pl011 *b) { return fbrl_ring_space(&b->uart->rx); }

/* Fill the transmit FIFO from the core; keep the TX interrupt on exactly while bytes are
 * in flight. When the core has nothing (empty, or held by the peer's XOFF) it goes off:
 * TX is a level that stays raised while the FIFO is low, so it must be masked. */
static void tx_fill(fbrl_uart_pl011 *b)
{
    uint32_t n = 0;
    while (!(rd(b, FBRL_PL011_FR) & FBRL_PL011_FR_TXFF) && n < FBRL_UART_PL011_FIFO) {
        int c = fbrl_uart_isr_tx(b->uart);
        if (c < 0)
            break;
        wr(b, FBRL_PL011_DR, (uint32_t)c);
        n++;
    }
    if (n > b->stats.max_burst)
        b->stats.max_burst = n;
    if (n > 0) {
        b->events++;
        set_imsc(b, b->imsc | FBRL_PL011_INT_TX);
    } else {
        wr(b, FBRL_PL011_ICR, FBRL_PL011_INT_TX);
        set_imsc(b, b->imsc & ~FBRL_PL011_INT_TX);
    }
}

/* Move received bytes into the core while the FIFO has some and the ring has room;
 * without room, mask the receive interrupts and leave the bytes in the FIFO (the sender
 * then sees the core's XOFF, or, under QEMU, the host is held back). */
static void rx_drain(fbrl_uart_pl011 *b)
{
    uint32_t n;
    for (n = 0; n < FBRL_UART_PL011_RX_BURST; n++) {
        uint32_t dr;
        unsigned flags = 0;
        if (rd(b, FBRL_PL011_FR) & FBRL_PL011_FR_RXFE)
            return;
        if (rx_room(b) < b->headroom) {
            set_imsc(b, b->imsc & ~(FBRL_PL011_INT_RX | FBRL_PL011_INT_RT));
            b->stats.throttles++;
            return;
        }
        dr = rd(b, FBRL_PL011_DR);
        if (dr & FBRL_PL011_DR_OE)
            flags |= FBRL_UART_LS_OVERRUN;
        if (dr & FBRL_PL011_DR_PE)
            flags |= FBRL_UART_LS_PARITY;
        if (dr & (FBRL_PL011_DR_FE | FBRL_PL011_DR_BE))
            flags |= FBRL_UART_LS_FRAMING;
        if (flags)
            fbrl_uart_isr_line_status(b->uart, flags);
        /* As on the 8250: a byte with a parity or framing error is still delivered,
         * counted; the core's own rules decide (the link drops a damaged line). */
        fbrl_uart_isr_rx(b->uart, (uint8_t)(dr & 0xFFu));
        b->events++;
    }
}

void fbrl_uart_pl011_isr(fbrl_uart_pl011 *b)
{
    uint32_t mis;
    if (!b)
        return;
    b->stats.irqs++;
    mis = rd(b, FBRL_PL011_MIS);
    if (!b->uart || mis == 0) {
        b->stats.spurious++;
        if (mis)
            wr(b, FBRL_PL011_ICR, mis);
        return;
    }
    /* Errors are also flagged per byte in DR (read by rx_drain); clear the summary. */
    if (mis & FBRL_PL011_INT_ERR)
        wr(b, FBRL_PL011_ICR, mis & FBRL_PL011_INT_ERR);
    if (mis & (FBRL_PL011_INT_RX | FBRL_PL011_INT_RT)) {
        /* RX and RT clear as the FIFO empties; clear RT explicitly (it is a timeout). */
        wr(b, FBRL_PL011_ICR, FBRL_PL011_INT_RT);
        rx_drain(b);
    }
    if (mis & FBRL_PL011_INT_TX)
        tx_fill(b);
}

/* Called by the main line, and by the core from inside the handler (an XOFF to send,
 * or output released by the peer's XON): irq_save nests, so both are safe. */
static void op_tx_kick(void *ctx)
{
    fbrl_uart_pl011 *b = ctx;
    uint32_t saved;
    if (!b || !b->uart)
        return;
    saved = b->io.irq_save(b->io.io_ctx);
    /* With TX on, the handler refills as the FIFO drains. Otherwise prime the FIFO here:
     * the PL011 raises TX only when the level is crossed, never for an idle FIFO. */
    if (!(b->imsc & FBRL_PL011_INT_TX))
        tx_fill(b);
    b->io.irq_restore(b->io.io_ctx, saved);
}

/* Resume receiving once the main line made room (hysteresis: twice the headroom), and
 * take what waits in the FIFO at once: it raises no new interrupt for bytes already there. */
static void rx_unthrottle(fbrl_uart_pl011 *b)
{
    if (!(b->imsc & FBRL_PL011_INT_RX) && rx_room(b) >= 2u * b->headroom) {
        set_imsc(b, b->imsc | FBRL_PL011_INT_RX | FBRL_PL011_INT_RT);
        rx_drain(b);
    }
}

static fbrl_status op_service(void *ctx, uint32_t timeout_us)
{
    fbrl_uart_pl011 *b = ctx;
    uint64_t deadline;
    uint32_t saved;
    if (!b)
        return FBRL_EINVAL;
    if (!b->uart)
        return FBRL_ESTATE;
    deadline = b->io.now_us(b->io.io_ctx) + timeout_us;
    saved = b->io.irq_save(b->io.io_ctx);
    rx_unthrottle(b);
    /* Sleep only while the handler has done nothing since the core last looked; the
     * check and the sleep run with interrupts held off, so no wake-up is lost. */
    while (b->events == b->seen && b->io.now_us(b->io.io_ctx) < deadline)
        b->io.idle(b->io.io_ctx);
    b->seen = b->events;
    b->io.irq_restore(b->io.io_ctx, saved);
    return FBRL_OK;
}

static uint64_t op_now_us(void *ctx)
{
    fbrl_uart_pl011 *b = ctx;
    return b ? b->io.now_us(b->io.io_ctx) : 0;
}

static fbrl_status op_close(void *ctx)
{
    fbrl_uart_pl011 *b = ctx;
    uint32_t saved;
    if (!b)
        return FBRL_EINVAL;
    saved = b->io.irq_save(b->io.io_ctx);
    b->imsc = 0;
    wr(b, FBRL_PL011_IMSC, 0);
    wr(b, FBRL_PL011_CR, 0);
    b->uart = NULL;
    b->io.irq_restore(b->io.io_ctx, saved);
    return FBRL_OK;
}

const fbrl_uart_ops fbrl_uart_pl011_ops = {op_configure, op_tx_kick, op_service, op_now_us, op_close, 0, 0};

fbrl_status fbrl_uart_pl011_attach(fbrl_uart_pl011 *b, struct fbrl_uart *u)
{
    uint32_t saved;
    if (!b || !u)
        return FBRL_EINVAL;
    saved = b->io.irq_save(b->io.io_ctx);
    b->uart = u;
    /* A ring smaller than 4 x the headroom scales it down, so reception never stalls. */
    b->headroom = (uint16_t)(fbrl_ring_capacity(&u->rx) / 4u);
    if (b->headroom > FBRL_UART_PL011_RX_HEADROOM)
        b->headroom = FBRL_UART_PL011_RX_HEADROOM;
    if (b->headroom == 0)
        b->headroom = 1;
    set_imsc(b, FBRL_PL011_INT_RX | FBRL_PL011_INT_RT | FBRL_PL011_INT_ERR);
    rx_drain(b); /* bytes that arrived before attach raise no interrupt of their own */
    b->io.irq_restore(b->io.io_ctx, saved);
    return FBRL_OK;
}

fbrl_status fbrl_uart_pl011_get_stats(const fbrl_uart_pl011 *b, fbrl_uart_pl011_stats *out)
{
    if (!b || !out)
        return FBRL_EINVAL;
    *out = b->stats;
    return FBRL_OK;
}
