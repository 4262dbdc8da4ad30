/* SPDX-License-Identifier: MIT */
/* uart_irq.h - the interrupt layer the bare-metal UART backends share (uart_8250.c,
 * uart_pl011.c), as Linux's serial core sits under its 8250 and amba-pl011 drivers: one
 * copy of the receive drain with its headroom throttle, the transmit fill, the kick, the
 * unthrottle and the interrupt-safe wait. A backend gives its register steps and quirk
 * bits (fbrl__uart_chip) and a view of its state (fbrl__uart_port). Not public: the
 * backends' headers and structs are unchanged.
 *
 * Concurrency: the handler (interrupt side) and the ops (main line) share the chip's
 * registers and its interrupt-mask shadow. The main line touches them only between the
 * board's irq_save and irq_restore, so on one CPU the two never interleave. */
#ifndef FBRL_UART_IRQ_H
#define FBRL_UART_IRQ_H

#include <stdint.h>
#include "fbrl/uart.h"

/* Interrupt sources, for fbrl__uart_chip.irq_on / irq_enabled. */
#define FBRL__UART_IRQ_RX 0x1u
#define FBRL__UART_IRQ_TX 0x2u

/* Quirks. */
/* The transmitter reports only "empty" (8250 LSR.THRE), then takes the whole FIFO
 * unasked: the fill writes up to burst bytes after one tx_ready; a kick fills only an
 * empty transmitter. Without it tx_ready is asked before every byte (PL011 TXFF). */
#define FBRL__UART_TX_EMPTY_ONLY 0x1u

typedef struct fbrl__uart_chip {
    unsigned quirks;
    /* A received byte waits in the chip (the 8250 reports the line errors LSR shows here,
     * as reading LSR clears them; the PL011 gives them with each byte, from rx_read). */
    int (*rx_ready)(void *dev);
    /* Take it: the byte in bits 7:0, its FBRL_UART_LS_* flags from bit 8. */
    unsigned (*rx_read)(void *dev);
    /* The transmitter takes a byte (FBRL__UART_TX_EMPTY_ONLY: it is empty). */
    int (*tx_ready)(void *dev);
    void (*tx_write)(void *dev, uint8_t c);
    /* Unmask (on) or mask the sources in irqs (and, masking a level-raised one, clear it). */
    void (*irq_on)(void *dev, unsigned irqs, int on);
    /* The sources unmasked now (from the shadow, not the chip). */
    unsigned (*irq_enabled)(const void *dev);
} fbrl__uart_chip;

/* What the shared code works on: the backend's own fields, by address. */
typedef struct fbrl__uart_port {
    const fbrl__uart_chip *chip;
    void *dev;
    struct fbrl_uart *uart;    /* NULL until attached */
    unsigned headroom;         /* receive pauses below this many free ring bytes */
    unsigned tx_max, rx_max;   /* most bytes per fill, per drain */
    volatile uint32_t *events; /* bumped whenever a byte moved */
    uint32_t *seen;            /* events as of the last service() return */
    uint32_t *throttles, *max_burst;
    uint32_t (*irq_save)(void *io_ctx);
    void (*irq_restore)(void *io_ctx, uint32_t saved);
    void (*idle)(void *io_ctx);
    uint64_t (*now_us)(void *io_ctx);
    void *io_ctx;
} fbrl__uart_port;

/* Fill the transmitter from the core; the TX interrupt on exactly while bytes are in flight. */
void fbrl__uart_irq_tx_fill(const fbrl__uart_port *p);
/* Move received bytes into the core while the chip has some and the ring has room;
 * without room, mask receive interrupts and leave the bytes in the chip. */
void fbrl__uart_irq_rx_drain(const fbrl__uart_port *p);
/* The ops' shared bodies (ctx checks are the backend's). */
void fbrl__uart_irq_tx_kick(const fbrl__uart_port *p);
fbrl_status fbrl__uart_irq_service(const fbrl__uart_port *p, uint32_t timeout_us);
/* The receive headroom for the core's ring: a quarter of it, at most max, at least 1. */
uint16_t fbrl__uart_irq_headroom(const struct fbrl_uart *u, unsigned max);

#endif
