/* SPDX-License-Identifier: MIT */
/* uart_irq.c - the interrupt layer of the bare-metal UART backends (uart_irq.h). */
#include "uart_irq.h"

/* Free bytes in the core's receive ring. The core has no call for this (only the count),
 * so ask its ring directly: fbrl_ring_space() is exact for the producer, which the
 * handler is. */
static size_t rx_room(const fbrl__uart_port *p) { return fbrl_ring_space(&p->uart->rx); }

void fbrl__uart_irq_tx_fill(const fbrl__uart_port *p)
{
    const fbrl__uart_chip *c = p->chip;
    int burst = (c->quirks & FBRL__UART_TX_EMPTY_ONLY) != 0;
    unsigned n = 0;
    while (n < p->tx_max && (burst || c->tx_ready(p->dev))) {
        int b = fbrl_uart_isr_tx(p->uart);
        if (b < 0)
            break;
        c->tx_write(p->dev, (uint8_t)b);
        n++;
    }
    if (n > *p->max_burst)
        *p->max_burst = n;
    if (n > 0) {
        (*p->events)++;
        c->irq_on(p->dev, FBRL__UART_IRQ_TX, 1);
    } else {
        /* Nothing (empty, or held by the peer's XOFF): a raised TX would stay raised. */
        c->irq_on(p->dev, FBRL__UART_IRQ_TX, 0);
    }
}

void fbrl__uart_irq_rx_drain(const fbrl__uart_port *p)
{
    const fbrl__uart_chip *c = p->chip;
    unsigned n;
    /* Bounded: the FIFO holds 16 bytes, but a fast source can refill it meanwhile. */
    for (n = 0; n < p->rx_max; n++) {
        unsigned v, flags;
        if (!c->rx_ready(p->dev))
            return;
        if (rx_room(p) < p->headroom) {
            c->irq_on(p->dev, FBRL__UART_IRQ_RX, 0);
            (*p->throttles)++;
            return;
        }
        v = c->rx_read(p->dev);
        flags = v >> 8;
        /* A byte with a parity or framing error is still delivered, counted; the core's
         * own rules decide (the link drops a damaged line). */
        if (flags)
            fbrl_uart_isr_line_status(p->uart, flags);
        fbrl_uart_isr_rx(p->uart, (uint8_t)(v & 0xFFu));
        (*p->events)++;
    }
}

/* Called by the main line, and by the core from inside the handler (XOFF to send, or
 * output released by the peer's XON): irq_save nests, so both are safe. */
void fbrl__uart_irq_tx_kick(const fbrl__uart_port *p)
{
    const fbrl__uart_chip *c = p->chip;
    uint32_t saved = p->irq_save(p->io_ctx);
    /* With TX on, the handler refills as the transmitter drains. Otherwise prime it here:
     * not every chip raises TX when it is unmasked over an idle transmitter. */
    if (!(c->irq_enabled(p->dev) & FBRL__UART_IRQ_TX) &&
        (!(c->quirks & FBRL__UART_TX_EMPTY_ONLY) || c->tx_ready(p->dev)))
        fbrl__uart_irq_tx_fill(p);
    p->irq_restore(p->io_ctx, saved);
}

/* Resume receiving once the main line made room (hysteresis: twice the headroom), and
 * take what waits at once: a chip raises no new interrupt for bytes already there. */
static void rx_unthrottle(const fbrl__uart_port *p)
{
    if (!(p->chip->irq_enabled(p->dev) & FBRL__UART_IRQ_RX) && rx_room(p) >= 2u * p->headroom) {
        p->chip->irq_on(p->dev, FBRL__UART_IRQ_RX, 1);
        fbrl__uart_irq_rx_drain(p);
    }
}

fbrl_status fbrl__uart_irq_service(const fbrl__uart_port *p, uint32_t timeout_us)
{
    uint64_t deadline;
    uint32_t saved;
    if (!p->uart)
        return FBRL_ESTATE;
    deadline = p->now_us(p->io_ctx) + timeout_us;
    saved = p->irq_save(p->io_ctx);
    rx_unthrottle(p);
    /* Sleep only while the handler has done nothing since the core last looked; the check
     * and the sleep run with interrupts held off, so no wake-up is lost. */
    while (*p->events == *p->seen && p->now_us(p->io_ctx) < deadline)
        p->idle(p->io_ctx);
    *p->seen = *p->events;
    p->irq_restore(p->io_ctx, saved);
    return FBRL_OK;
}

uint16_t fbrl__uart_irq_headroom(const struct fbrl_uart *u, unsigned max)
{
    /* A ring smaller than 4 x the headroom scales it down, so reception never stalls. */
    size_t h = fbrl_ring_capacity(&u->rx) / 4u;
    if (h > max)
        h = max;
    return (uint16_t)(h ? h : 1);
}
