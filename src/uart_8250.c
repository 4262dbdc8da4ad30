/* SPDX-License-Identifier: MIT */
/* uart_8250.c - PC 8250/16550 backend: registers, interrupt causes, 8259. The ring and
 * interrupt logic is uart_irq.c's, shared with the PL011 (quirk: the transmitter reports
 * only "empty", then takes the whole FIFO). */
#include "fbrl/uart_8250.h"
#include "uart_irq.h"

#define REG(b, r) ((uint16_t)((b)->base + (r)))
#define RX_BURST  64u /* most bytes taken from RBR per handler pass */

static uint8_t rd(fbrl_uart_8250 *b, unsigned reg) { return b->io.inb(b->io.io_ctx, REG(b, reg)); }

static void wr(fbrl_uart_8250 *b, unsigned reg, uint8_t v) { b->io.outb(b->io.io_ctx, REG(b, reg), v); }

static void set_ier(fbrl_uart_8250 *b, uint8_t ier)
{
    if (ier != b->ier) {
        b->ier = ier;
        wr(b, FBRL_8250_IER, ier);
    }
}

fbrl_status fbrl_uart_8250_init(fbrl_uart_8250 *b, const fbrl_uart_8250_io *io, uint16_t base, uint8_t irq,
                                fbrl_uart_8250_chip chip, uint8_t rx_trigger)
{
    uint8_t fcr;
    if (!b || !io || !io->inb || !io->outb || !io->irq_save || !io->irq_restore || !io->idle || !io->now_us)
        return FBRL_EINVAL;
    if (irq > 7)
        return FBRL_ERANGE;
    switch (chip) {
    case FBRL_UART_8250_8250:
        if (rx_trigger != 1)
            return FBRL_ERANGE;
        fcr = 0;
        break;
    case FBRL_UART_8250_16550:
        /* FCR bits 7:6 select the receive trigger: 00=1, 01=4, 10=8, 11=14 bytes. */
        switch (rx_trigger) {
        case 1: fcr = 0x00; break;
        case 4: fcr = 0x40; break;
        case 8: fcr = 0x80; break;
        case 14: fcr = 0xC0; break;
        default: return FBRL_ERANGE;
        }
        fcr |= FBRL_8250_FCR_ENABLE | FBRL_8250_FCR_CLEAR_RX | FBRL_8250_FCR_CLEAR_TX;
        break;
    default: return FBRL_EINVAL;
    }
    b->io = *io;
    b->uart = NULL;
    b->base = base;
    b->irq = irq;
    b->depth = (uint8_t)chip;
    b->headroom = FBRL_UART_8250_RX_HEADROOM;
    b->fcr = fcr;
    b->ier = 0;
    b->events = 0;
    b->seen = 0;
    b->stats = (fbrl_uart_8250_stats){0, 0, 0, 0, 0, 0};
    return FBRL_OK;
}

/* The LCR value for a line setting, or -1 when the 8250 cannot do it. */
static int lcr_for(const fbrl_uart_config *cfg)
{
    int lcr;
    if (cfg->data_bits < 5 || cfg->data_bits > 8)
        return -1;
    lcr = cfg->data_bits - 5;
    if (cfg->stop_bits == 2) {
        if (cfg->data_bits == 5)
            return -1; /* the chip sends 1.5 stop bits there, not 2 */
        lcr |= FBRL_8250_LCR_STOP2;
    } else if (cfg->stop_bits != 1) {
        return -1;
    }
    switch (cfg->parity) {
    case FBRL_PARITY_NONE: break;
    case FBRL_PARITY_ODD: lcr |= FBRL_8250_LCR_PARITY; break;
    case FBRL_PARITY_EVEN: lcr |= FBRL_8250_LCR_PARITY | FBRL_8250_LCR_EVEN; break;
    default: return -1;
    }
    return lcr;
}

static fbrl_status op_configure(void *ctx, const fbrl_uart_config *cfg)
{
    fbrl_uart_8250 *b = ctx;
    uint32_t divisor, saved;
    uint8_t ier;
    int lcr;
    if (!b || !cfg)
        return FBRL_EINVAL;
    if (cfg->baud == 0 || cfg->baud > FBRL_UART_8250_BAUD_BASE || FBRL_UART_8250_BAUD_BASE % cfg->baud != 0)
        return FBRL_EUNSUPPORTED;
    divisor = FBRL_UART_8250_BAUD_BASE / cfg->baud;
    if (divisor > 0xFFFFu)
        return FBRL_EUNSUPPORTED;
    if (cfg->flow != FBRL_FLOW_NONE && cfg->flow != FBRL_FLOW_XONXOFF)
        return FBRL_EUNSUPPORTED; /* XON/XOFF is the core's; the chip has no other */
    lcr = lcr_for(cfg);
    if (lcr < 0)
        return FBRL_EUNSUPPORTED;

    saved = b->io.irq_save(b->io.io_ctx);
    ier = b->ier;
    wr(b, FBRL_8250_IER, 0); /* quiet while the divisor latch hides RBR/THR/IER */
    wr(b, FBRL_8250_LCR, FBRL_8250_LCR_DLAB);
    wr(b, FBRL_8250_DLL, (uint8_t)(divisor & 0xFFu));
    wr(b, FBRL_8250_DLM, (uint8_t)(divisor >> 8));
    wr(b, FBRL_8250_LCR, (uint8_t)lcr);
    if (b->depth > 1)
        wr(b, FBRL_8250_FCR, b->fcr);
    wr(b, FBRL_8250_MCR, FBRL_8250_MCR_DTR | FBRL_8250_MCR_RTS | FBRL_8250_MCR_OUT2);
    /* Clear what the old setting left latched: line errors, modem deltas, THRE. */
    (void)rd(b, FBRL_8250_LSR);
    (void)rd(b, FBRL_8250_MSR);
    (void)rd(b, FBRL_8250_IIR);
    if (ier != 0)
        wr(b, FBRL_8250_IER, ier);
    b->io.irq_restore(b->io.io_ctx, saved);
    return FBRL_OK;
}

/* Report LSR error bits to the core. Reading LSR cleared them in the chip. */
static void line_status(fbrl_uart_8250 *b, uint8_t lsr)
{
    unsigned flags = 0;
    if (lsr & FBRL_8250_LSR_OE)
        flags |= FBRL_UART_LS_OVERRUN;
    if (lsr & FBRL_8250_LSR_PE)
        flags |= FBRL_UART_LS_PARITY;
    if (lsr & (FBRL_8250_LSR_FE | FBRL_8250_LSR_BI))
        flags |= FBRL_UART_LS_FRAMING;
    if (flags)
        fbrl_uart_isr_line_status(b->uart, flags);
}

/* The chip's steps for uart_irq.c. */
static int chip_rx_ready(void *dev)
{
    fbrl_uart_8250 *b = dev;
    uint8_t lsr = rd(b, FBRL_8250_LSR);
    line_status(b, lsr);
    return (lsr & FBRL_8250_LSR_DR) != 0;
}

static unsigned chip_rx_read(void *dev) { return rd(dev, FBRL_8250_RBR); }

static int chip_tx_ready(void *dev) { return (rd(dev, FBRL_8250_LSR) & FBRL_8250_LSR_THRE) != 0; }

static void chip_tx_write(void *dev, uint8_t c) { wr(dev, FBRL_8250_THR, c); }

static void chip_irq_on(void *dev, unsigned irqs, int on)
{
    fbrl_uart_8250 *b = dev;
    uint8_t bits = (uint8_t)(((irqs & FBRL__UART_IRQ_RX) ? FBRL_8250_IER_RDI : 0) |
                             ((irqs & FBRL__UART_IRQ_TX) ? FBRL_8250_IER_THRI : 0));
    set_ier(b, (uint8_t)(on ? b->ier | bits : b->ier & ~bits));
}

static unsigned chip_irq_enabled(const void *dev)
{
    const fbrl_uart_8250 *b = dev;
    return ((b->ier & FBRL_8250_IER_RDI) ? FBRL__UART_IRQ_RX : 0u) |
           ((b->ier & FBRL_8250_IER_THRI) ? FBRL__UART_IRQ_TX : 0u);
}

static const fbrl__uart_chip chip_8250 = {FBRL__UART_TX_EMPTY_ONLY, chip_rx_ready,   chip_rx_read,    chip_tx_ready,
                                          chip_tx_write,            chip_irq_on,     chip_irq_enabled};

static fbrl__uart_port port(fbrl_uart_8250 *b)
{
    fbrl__uart_port p = {&chip_8250,          b,           b->uart,           b->headroom,
                         b->depth,            RX_BURST,    &b->events,        &b->seen,
                         &b->stats.throttles, &b->stats.max_burst, b->io.irq_save, b->io.irq_restore,
                         b->io.idle,          b->io.now_us, b->io.io_ctx};
    return p;
}

void fbrl_uart_8250_isr(fbrl_uart_8250 *b)
{
    unsigned pass;
    if (!b)
        return;
    b->stats.irqs++;
    if (b->uart) {
        for (pass = 0;; pass++) {
            uint8_t iir = rd(b, FBRL_8250_IIR);
            if (iir & FBRL_8250_IIR_NONE) {
                if (pass == 0)
                    b->stats.spurious++;
                break;
            }
            if (pass == FBRL_UART_8250_MAX_PASSES) {
                /* Still pending: drop and raise the line so the 8259 sees a new edge. */
                uint8_t ier = b->ier;
                wr(b, FBRL_8250_IER, 0);
                wr(b, FBRL_8250_IER, ier);
                b->stats.pass_limit++;
                break;
            }
            b->stats.passes++;
            switch (iir & FBRL_8250_IIR_ID) {
            case FBRL_8250_IIR_RLS: line_status(b, rd(b, FBRL_8250_LSR)); break;
            case FBRL_8250_IIR_RDA:
            case FBRL_8250_IIR_CTI: {
                /* A received XON, or an XOFF the core must send, reaches the
                 * transmitter through the core's tx_kick. */
                fbrl__uart_port p = port(b);
                fbrl__uart_irq_rx_drain(&p);
                break;
            }
            case FBRL_8250_IIR_THRE: {
                fbrl__uart_port p = port(b);
                fbrl__uart_irq_tx_fill(&p);
                break;
            }
            default: /* modem status: reading MSR clears it */ (void)rd(b, FBRL_8250_MSR); break;
            }
        }
    }
    b->io.outb(b->io.io_ctx, FBRL_8259_CMD, FBRL_8259_EOI);
}

static void op_tx_kick(void *ctx)
{
    fbrl_uart_8250 *b = ctx;
    if (b && b->uart) {
        fbrl__uart_port p = port(b);
        fbrl__uart_irq_tx_kick(&p);
    }
}

static fbrl_status op_service(void *ctx, uint32_t timeout_us)
{
    fbrl_uart_8250 *b = ctx;
    fbrl__uart_port p;
    if (!b)
        return FBRL_EINVAL;
    p = port(b);
    return fbrl__uart_irq_service(&p, timeout_us);
}

static uint64_t op_now_us(void *ctx)
{
    fbrl_uart_8250 *b = ctx;
    return b ? b->io.now_us(b->io.io_ctx) : 0;
}

static fbrl_status op_close(void *ctx)
{
    fbrl_uart_8250 *b = ctx;
    uint32_t saved;
    if (!b)
        return FBRL_EINVAL;
    saved = b->io.irq_save(b->io.io_ctx);
    b->io.outb(b->io.io_ctx, FBRL_8259_DATA,
               (uint8_t)(b->io.inb(b->io.io_ctx, FBRL_8259_DATA) | (1u << b->irq)));
    b->ier = 0;
    wr(b, FBRL_8250_IER, 0);
    wr(b, FBRL_8250_MCR, 0);
    b->uart = NULL;
    b->io.irq_restore(b->io.io_ctx, saved);
    return FBRL_OK;
}

const fbrl_uart_ops fbrl_uart_8250_ops = {op_configure, op_tx_kick, op_service, op_now_us, op_close, 0, 0};

fbrl_status fbrl_uart_8250_attach(fbrl_uart_8250 *b, struct fbrl_uart *u)
{
    uint32_t saved;
    if (!b || !u)
        return FBRL_EINVAL;
    saved = b->io.irq_save(b->io.io_ctx);
    b->uart = u;
    b->headroom = fbrl__uart_irq_headroom(u, FBRL_UART_8250_RX_HEADROOM);
    set_ier(b, FBRL_8250_IER_RDI | FBRL_8250_IER_RLSI);
    b->io.outb(b->io.io_ctx, FBRL_8259_DATA,
               (uint8_t)(b->io.inb(b->io.io_ctx, FBRL_8259_DATA) & ~(1u << b->irq)));
    b->io.irq_restore(b->io.io_ctx, saved);
    return FBRL_OK;
}

fbrl_status fbrl_uart_8250_probe(const fbrl_uart_8250_io *io, uint16_t base, fbrl_uart_8250_chip *chip)
{
    uint8_t lcr, iir;
    if (!io || !io->inb || !io->outb || !chip)
        return FBRL_EINVAL;
    /* Presence: LCR is read/write on every 8250 family member; an empty port is not. */
    lcr = io->inb(io->io_ctx, (uint16_t)(base + FBRL_8250_LCR));
    io->outb(io->io_ctx, (uint16_t)(base + FBRL_8250_LCR), 0x1B);
    if (io->inb(io->io_ctx, (uint16_t)(base + FBRL_8250_LCR)) != 0x1B)
        return FBRL_ENOENT;
    io->outb(io->io_ctx, (uint16_t)(base + FBRL_8250_LCR), 0x03);
    if (io->inb(io->io_ctx, (uint16_t)(base + FBRL_8250_LCR)) != 0x03)
        return FBRL_ENOENT;
    /* FIFOs (with LCR at 0x03, so no later chip's extended registers get in the way):
     * after FCR enable, IIR bits 7:6 read 11 on a 16550A, 10 on the early 16550
     * (unusable FIFO), 00 on chips without one. */
    io->outb(io->io_ctx, (uint16_t)(base + FBRL_8250_FCR), FBRL_8250_FCR_ENABLE);
    iir = io->inb(io->io_ctx, (uint16_t)(base + FBRL_8250_IIR));
    io->outb(io->io_ctx, (uint16_t)(base + FBRL_8250_FCR), 0);
    io->outb(io->io_ctx, (uint16_t)(base + FBRL_8250_LCR), lcr);
    *chip = (iir & 0xC0u) == 0xC0u ? FBRL_UART_8250_16550 : FBRL_UART_8250_8250;
    return FBRL_OK;
}

fbrl_status fbrl_uart_8250_get_stats(const fbrl_uart_8250 *b, fbrl_uart_8250_stats *out)
{
    if (!b || !out)
        return FBRL_EINVAL;
    *out = b->stats;
    return FBRL_OK;
}
