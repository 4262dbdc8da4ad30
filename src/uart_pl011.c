/* SPDX-License-Identifier: MIT */
/* uart_pl011.c - ARM PL011 backend: line programming, interrupt causes. The ring and
 * interrupt logic is uart_irq.c's, shared with the 8250 (the PL011 is asked before each
 * byte it is given, gives each byte's errors with it, and raises TX as a level). */
#include "fbrl/uart_pl011.h"
#include "uart_irq.h"

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

/* The chip's steps for uart_irq.c. */
static int chip_rx_ready(void *dev) { return !(rd(dev, FBRL_PL011_FR) & FBRL_PL011_FR_RXFE); }

static unsigned chip_rx_read(void *dev)
{
    uint32_t dr = rd(dev, FBRL_PL011_DR);
    unsigned flags = 0;
    if (dr & FBRL_PL011_DR_OE)
        flags |= FBRL_UART_LS_OVERRUN;
    if (dr & FBRL_PL011_DR_PE)
        flags |= FBRL_UART_LS_PARITY;
    if (dr & (FBRL_PL011_DR_FE | FBRL_PL011_DR_BE))
        flags |= FBRL_UART_LS_FRAMING;
    return (unsigned)(dr & 0xFFu) | flags << 8;
}

static int chip_tx_ready(void *dev) { return !(rd(dev, FBRL_PL011_FR) & FBRL_PL011_FR_TXFF); }

static void chip_tx_write(void *dev, uint8_t c) { wr(dev, FBRL_PL011_DR, c); }

static void chip_irq_on(void *dev, unsigned irqs, int on)
{
    fbrl_uart_pl011 *b = dev;
    uint32_t bits = ((irqs & FBRL__UART_IRQ_RX) ? FBRL_PL011_INT_RX | FBRL_PL011_INT_RT : 0u) |
                    ((irqs & FBRL__UART_IRQ_TX) ? FBRL_PL011_INT_TX : 0u);
    if (!on && (irqs & FBRL__UART_IRQ_TX))
        wr(b, FBRL_PL011_ICR, FBRL_PL011_INT_TX); /* TX is a level: it stays raised while the FIFO is low */
    set_imsc(b, on ? b->imsc | bits : b->imsc & ~bits);
}

static unsigned chip_irq_enabled(const void *dev)
{
    const fbrl_uart_pl011 *b = dev;
    return ((b->imsc & FBRL_PL011_INT_RX) ? FBRL__UART_IRQ_RX : 0u) |
           ((b->imsc & FBRL_PL011_INT_TX) ? FBRL__UART_IRQ_TX : 0u);
}

static const fbrl__uart_chip chip_pl011 = {0, chip_rx_ready, chip_rx_read, chip_tx_ready,
                                           chip_tx_write, chip_irq_on, chip_irq_enabled};

static fbrl__uart_port port(fbrl_uart_pl011 *b)
{
    fbrl__uart_port p = {&chip_pl011,         b,
                         b->uart,             b->headroom,
                         FBRL_UART_PL011_FIFO, FBRL_UART_PL011_RX_BURST,
                         &b->events,          &b->seen,
                         &b->stats.throttles, &b->stats.max_burst,
                         b->io.irq_save,      b->io.irq_restore,
                         b->io.idle,          b->io.now_us,
                         b->io.io_ctx};
    return p;
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
    fbrl__uart_port p = port(b);
    if (mis & (FBRL_PL011_INT_RX | FBRL_PL011_INT_RT)) {
        /* RX and RT clear as the FIFO empties; clear RT explicitly (it is a timeout). */
        wr(b, FBRL_PL011_ICR, FBRL_PL011_INT_RT);
        fbrl__uart_irq_rx_drain(&p);
    }
    if (mis & FBRL_PL011_INT_TX)
        fbrl__uart_irq_tx_fill(&p);
}

static void op_tx_kick(void *ctx)
{
    fbrl_uart_pl011 *b = ctx;
    if (b && b->uart) {
        fbrl__uart_port p = port(b);
        fbrl__uart_irq_tx_kick(&p);
    }
}

static fbrl_status op_service(void *ctx, uint32_t timeout_us)
{
    fbrl_uart_pl011 *b = ctx;
    fbrl__uart_port p;
    if (!b)
        return FBRL_EINVAL;
    p = port(b);
    return fbrl__uart_irq_service(&p, timeout_us);
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
    b->headroom = fbrl__uart_irq_headroom(u, FBRL_UART_PL011_RX_HEADROOM);
    set_imsc(b, FBRL_PL011_INT_RX | FBRL_PL011_INT_RT | FBRL_PL011_INT_ERR);
    fbrl__uart_port p = port(b);
    fbrl__uart_irq_rx_drain(&p); /* bytes that arrived before attach raise no interrupt of their own */
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
