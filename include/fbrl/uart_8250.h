/* SPDX-License-Identifier: MIT */
/* uart_8250.h - PC 8250/16550 UART backend for the serial driver core (uart.h).
 *
 * The thesis's COM routine (section 5.2) at register level: divisor latch = 115200 /
 * baud, LCR word length/parity/stop bits, FCR (16550 FIFO), MCR with DTR, RTS and
 * OUT2 (OUT2 gates the UART's interrupt line on a PC), IER, an interrupt handler that
 * loops on IIR until no interrupt is pending, and the 8259 mask and EOI.
 *
 * Nothing here touches the hardware directly: every port access goes through the
 * board's hooks in fbrl_uart_8250_io, so the same code runs on a bare PC (inb/outb
 * instructions), under a host unit test (a register model), or on any board that
 * maps a 16550 somewhere. The backend includes no OS header.
 *
 * Use (bare metal):
 *     fbrl_uart_8250 com;  fbrl_uart u;
 *     fbrl_uart_8250_init(&com, &board_io, FBRL_UART_8250_COM1_BASE, FBRL_UART_8250_COM1_IRQ,
 *                         FBRL_UART_8250_16550, 14);
 *     fbrl_uart_init(&u, &fbrl_uart_8250_ops, &com, ...);   (the core programs the line)
 *     fbrl_uart_8250_attach(&com, &u);                       (IER + 8259 unmask)
 *     IRQ4 handler: fbrl_uart_8250_isr(&com);                 (ends with the EOI)
 */
#ifndef FBRL_UART_8250_H
#define FBRL_UART_8250_H

#include "fbrl/export.h"

#include <stdint.h>
#include "fbrl/status.h"
#include "fbrl/uart.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The PC's standard ports. */
#define FBRL_UART_8250_COM1_BASE 0x3F8u
#define FBRL_UART_8250_COM1_IRQ  4u
#define FBRL_UART_8250_COM2_BASE 0x2F8u
#define FBRL_UART_8250_COM2_IRQ  3u
/* The UART's clock divided by 16: the rate at divisor 1. */
#define FBRL_UART_8250_BAUD_BASE 115200u

/* Register offsets from the base port and their bits (16550 data sheet names). */
#define FBRL_8250_RBR 0u /* receive buffer (read, DLAB=0) */
#define FBRL_8250_THR 0u /* transmit holding (write, DLAB=0) */
#define FBRL_8250_DLL 0u /* divisor latch low (DLAB=1) */
#define FBRL_8250_IER 1u /* interrupt enable (DLAB=0) */
#define FBRL_8250_DLM 1u /* divisor latch high (DLAB=1) */
#define FBRL_8250_IIR 2u /* interrupt identification (read) */
#define FBRL_8250_FCR 2u /* FIFO control (write, 16550 only) */
#define FBRL_8250_LCR 3u
#define FBRL_8250_MCR 4u
#define FBRL_8250_LSR 5u
#define FBRL_8250_MSR 6u

#define FBRL_8250_IER_RDI  0x01u /* receive data available (and the 16550's timeout) */
#define FBRL_8250_IER_THRI 0x02u /* transmit holding register empty */
#define FBRL_8250_IER_RLSI 0x04u /* receiver line status */
#define FBRL_8250_IER_MSI  0x08u /* modem status */

#define FBRL_8250_IIR_NONE 0x01u /* bit 0 set: no interrupt pending */
#define FBRL_8250_IIR_ID   0x0Eu /* cause, highest priority first: */
#define FBRL_8250_IIR_RLS  0x06u /*   line status (OE/PE/FE/BI) */
#define FBRL_8250_IIR_RDA  0x04u /*   received data at the trigger level */
#define FBRL_8250_IIR_CTI  0x0Cu /*   character timeout (16550) */
#define FBRL_8250_IIR_THRE 0x02u /*   transmitter empty */
#define FBRL_8250_IIR_MSR  0x00u /*   modem status */

#define FBRL_8250_FCR_ENABLE   0x01u
#define FBRL_8250_FCR_CLEAR_RX 0x02u
#define FBRL_8250_FCR_CLEAR_TX 0x04u

#define FBRL_8250_LCR_PARITY 0x08u /* parity enable */
#define FBRL_8250_LCR_EVEN   0x10u /* even parity select */
#define FBRL_8250_LCR_STOP2  0x04u /* 2 stop bits (1.5 with 5 data bits) */
#define FBRL_8250_LCR_DLAB   0x80u /* divisor latch access */

#define FBRL_8250_MCR_DTR  0x01u
#define FBRL_8250_MCR_RTS  0x02u
#define FBRL_8250_MCR_OUT2 0x08u

#define FBRL_8250_LSR_DR   0x01u /* data ready */
#define FBRL_8250_LSR_OE   0x02u /* overrun: a byte was lost */
#define FBRL_8250_LSR_PE   0x04u /* parity error (byte at the FIFO head) */
#define FBRL_8250_LSR_FE   0x08u /* framing error */
#define FBRL_8250_LSR_BI   0x10u /* break */
#define FBRL_8250_LSR_THRE 0x20u /* transmit holding register (16550: FIFO) empty */

/* 8259 interrupt controller (master): command port, data (mask) port, EOI. */
#define FBRL_8259_CMD  0x20u
#define FBRL_8259_DATA 0x21u
#define FBRL_8259_EOI  0x20u

/* Interrupt-handler bounds. An edge-triggered 8259 needs IIR to read "none pending"
 * before the EOI, but a cause that never clears must not hang the CPU: after
 * FBRL_UART_8250_MAX_PASSES passes the handler stops and re-arms the line. */
#define FBRL_UART_8250_MAX_PASSES 16u
/* Stop reading RBR when the core's receive ring has fewer free bytes than this (a
 * quarter of the ring, if that is less); read again (unmask receive interrupts) once
 * it has at least twice as many. The bytes then wait in the UART (and under QEMU, in
 * the host), not in a full ring. */
#define FBRL_UART_8250_RX_HEADROOM 16u

typedef enum fbrl_uart_8250_chip {
    FBRL_UART_8250_8250 = 1,  /* 8250/16450: one-byte holding registers, no FCR */
    FBRL_UART_8250_16550 = 16 /* 16550A: 16-byte FIFOs */
} fbrl_uart_8250_chip;

/* The board's side. io_ctx is passed back to every hook. All hooks are required. */
typedef struct fbrl_uart_8250_io {
    uint8_t (*inb)(void *io_ctx, uint16_t port);
    void (*outb)(void *io_ctx, uint16_t port, uint8_t value);
    /* Keep the UART's interrupt handler out (x86: pushf; cli) and let it in again
     * (popf). Must nest. */
    uint32_t (*irq_save)(void *io_ctx);
    void (*irq_restore)(void *io_ctx, uint32_t saved);
    /* Called inside irq_save: let interrupts in and sleep until one has run, then
     * keep them out again (x86: sti; hlt; cli - the STI shadow makes it race-free). */
    void (*idle)(void *io_ctx);
    /* Monotonic microseconds. */
    uint64_t (*now_us)(void *io_ctx);
    void *io_ctx;
} fbrl_uart_8250_io;

typedef struct fbrl_uart_8250_stats {
    uint32_t irqs;       /* calls of fbrl_uart_8250_isr */
    uint32_t spurious;   /* calls that found nothing pending */
    uint32_t passes;     /* IIR causes handled */
    uint32_t pass_limit; /* times the pass bound was hit */
    uint32_t throttles;  /* times receive was paused for lack of room */
    uint32_t max_burst;  /* most bytes written to THR after one THRE */
} fbrl_uart_8250_stats;

/* Caller-owned state; fields are private. */
typedef struct fbrl_uart_8250 {
    fbrl_uart_8250_io io;
    struct fbrl_uart *uart; /* core fed by the handler; NULL until attached */
    uint16_t base;
    uint8_t irq;              /* 0..7, on the master 8259 */
    uint8_t depth;            /* transmit bytes per THRE: 16 or 1 */
    uint8_t fcr;              /* FIFO control value (0 on an 8250) */
    uint16_t headroom;        /* receive pauses below this many free ring bytes */
    volatile uint8_t ier;     /* shadow of IER, written with the register */
    volatile uint32_t events; /* bumped by the handler whenever it moved a byte */
    uint32_t seen;            /* events as of the last service() return */
    fbrl_uart_8250_stats stats;
} fbrl_uart_8250;

/* Set up the state; touches no register. rx_trigger is the 16550's receive FIFO
 * trigger level (1, 4, 8 or 14) and must be 1 on an 8250. EINVAL: b or io NULL or a
 * hook missing; ERANGE: irq > 7 (COM ports live on the master 8259), bad trigger. */
FBRL_API fbrl_status fbrl_uart_8250_init(fbrl_uart_8250 *b, const fbrl_uart_8250_io *io, uint16_t base,
                                         uint8_t irq, fbrl_uart_8250_chip chip, uint8_t rx_trigger);

/* The ops for fbrl_uart_init(); ctx is the fbrl_uart_8250. configure programs the
 * line (FBRL_EUNSUPPORTED when 115200 is not a whole multiple of the baud rate, or for
 * 5 data bits with 2 stop bits, which an 8250 sends as 1.5); tx_kick primes the
 * transmitter; service sleeps until the handler has moved something (or the
 * timeout); close masks everything and drops DTR/RTS/OUT2. */
extern FBRL_API const fbrl_uart_ops fbrl_uart_8250_ops;

/* Connect the handler to the core and enable interrupts: IER = receive data + line
 * status, then unmask the IRQ at the 8259. Call after the core configured the line. */
FBRL_API fbrl_status fbrl_uart_8250_attach(fbrl_uart_8250 *b, struct fbrl_uart *u);

/* The interrupt handler: call it from the IRQ's vector. Loops on IIR until nothing is
 * pending, then sends the 8259 its EOI. */
FBRL_API void fbrl_uart_8250_isr(fbrl_uart_8250 *b);

/* Find out what sits at base (before init; only inb/outb are used, and the chip is
 * left with its FIFOs off and LCR as found): FBRL_UART_8250_16550 for a 16550A with
 * working FIFOs, FBRL_UART_8250_8250 for an 8250/16450 - or for an early 16550, whose
 * FIFO is broken. FBRL_ENOENT when no UART answers there (LCR does not read back what
 * was written, as on an empty ISA port that reads 0xFF). EINVAL on NULL arguments. */
FBRL_API fbrl_status fbrl_uart_8250_probe(const fbrl_uart_8250_io *io, uint16_t base,
                                          fbrl_uart_8250_chip *chip);

/* Copy of the handler's counters. EINVAL on NULL. */
FBRL_API fbrl_status fbrl_uart_8250_get_stats(const fbrl_uart_8250 *b, fbrl_uart_8250_stats *out);

#ifdef __cplusplus
}
#endif
#endif
