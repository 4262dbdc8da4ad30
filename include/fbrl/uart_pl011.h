/* SPDX-License-Identifier: MIT */
/* uart_pl011.h - ARM PrimeCell PL011 backend for the UART driver core (uart.h): the
 * UART of most Cortex-M and Cortex-A parts (Stellaris/Tiva, STM32 "USART" excepted,
 * Raspberry Pi, QEMU's lm3s6965evb/virt/versatile machines). Interrupt driven: the board
 * calls fbrl_uart_pl011_isr() from the UART's vector; the handler fills the core's
 * receive ring and drains its transmit ring. XON/XOFF is the core's (as with the 8250).
 *
 * All register access goes through fbrl_uart_pl011_io (offsets from the UART's base), so
 * a unit test can stand in for the chip and a board maps it onto memory-mapped I/O.
 * No OS header, no hardware address: docs/firmware.md. */
#ifndef FBRL_UART_PL011_H
#define FBRL_UART_PL011_H

#include "fbrl/export.h"

#include <stdint.h>
#include "fbrl/status.h"
#include "fbrl/uart.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Register offsets (PL011 TRM, Stellaris data sheets). */
#define FBRL_PL011_DR   0x000u /* data; on read bits 11:8 = OE BE PE FE of that byte */
#define FBRL_PL011_RSR  0x004u /* receive status / error clear */
#define FBRL_PL011_FR   0x018u /* flags */
#define FBRL_PL011_IBRD 0x024u /* integer baud divisor */
#define FBRL_PL011_FBRD 0x028u /* fractional baud divisor (1/64) */
#define FBRL_PL011_LCRH 0x02Cu /* line control; writing it latches IBRD/FBRD */
#define FBRL_PL011_CR   0x030u /* control */
#define FBRL_PL011_IFLS 0x034u /* FIFO interrupt levels */
#define FBRL_PL011_IMSC 0x038u /* interrupt mask (1 = enabled) */
#define FBRL_PL011_RIS  0x03Cu /* raw interrupt status */
#define FBRL_PL011_MIS  0x040u /* masked interrupt status */
#define FBRL_PL011_ICR  0x044u /* interrupt clear */

#define FBRL_PL011_DR_OE 0x800u
#define FBRL_PL011_DR_BE 0x400u
#define FBRL_PL011_DR_PE 0x200u
#define FBRL_PL011_DR_FE 0x100u

#define FBRL_PL011_FR_TXFE 0x80u /* transmit FIFO empty */
#define FBRL_PL011_FR_RXFF 0x40u
#define FBRL_PL011_FR_TXFF 0x20u /* transmit FIFO full */
#define FBRL_PL011_FR_RXFE 0x10u /* receive FIFO empty */
#define FBRL_PL011_FR_BUSY 0x08u

#define FBRL_PL011_LCRH_SPS  0x80u /* stick parity */
#define FBRL_PL011_LCRH_WLEN 0x60u /* word length - 5, bits 6:5 */
#define FBRL_PL011_LCRH_FEN  0x10u /* FIFOs on */
#define FBRL_PL011_LCRH_STP2 0x08u
#define FBRL_PL011_LCRH_EPS  0x04u /* even parity */
#define FBRL_PL011_LCRH_PEN  0x02u /* parity on */

#define FBRL_PL011_CR_RXE    0x200u
#define FBRL_PL011_CR_TXE    0x100u
#define FBRL_PL011_CR_UARTEN 0x001u

/* Interrupt bits of IMSC, RIS, MIS and ICR. */
#define FBRL_PL011_INT_OE  0x400u
#define FBRL_PL011_INT_BE  0x200u
#define FBRL_PL011_INT_PE  0x100u
#define FBRL_PL011_INT_FE  0x080u
#define FBRL_PL011_INT_RT  0x040u /* receive timeout: bytes below the level wait */
#define FBRL_PL011_INT_TX  0x020u /* transmit FIFO at or below its level */
#define FBRL_PL011_INT_RX  0x010u /* receive FIFO at or above its level */
#define FBRL_PL011_INT_ERR (FBRL_PL011_INT_OE | FBRL_PL011_INT_BE | FBRL_PL011_INT_PE | FBRL_PL011_INT_FE)

/* IFLS: receive interrupt at 1/2 full (8 of 16), transmit at 1/8 (2 left): room for
 * interrupt latency on both sides, few interrupts per byte. */
#define FBRL_PL011_IFLS_DEFAULT 0x10u

#define FBRL_UART_PL011_FIFO        16u /* bytes in each FIFO */
#define FBRL_UART_PL011_RX_HEADROOM 16u /* receive pauses below this many free ring bytes */
#define FBRL_UART_PL011_RX_BURST    64u /* most bytes taken per handler call */

typedef struct fbrl_uart_pl011_io {
    uint32_t (*read)(void *io_ctx, uint32_t offset);              /* a register */
    void (*write)(void *io_ctx, uint32_t offset, uint32_t value); /* a register */
    /* Keep the UART's handler out (Cortex-M: PRIMASK set) and let it in again; must nest. */
    uint32_t (*irq_save)(void *io_ctx);
    void (*irq_restore)(void *io_ctx, uint32_t saved);
    /* Inside irq_save: sleep until an interrupt is pending, let it run, keep interrupts
     * out again (Cortex-M: wfi; cpsie i; cpsid i - WFI wakes on a pending interrupt even
     * while PRIMASK holds it off, so no wake-up is lost). */
    void (*idle)(void *io_ctx);
    uint64_t (*now_us)(void *io_ctx); /* monotonic microseconds */
    void *io_ctx;
} fbrl_uart_pl011_io;

typedef struct fbrl_uart_pl011_stats {
    uint32_t irqs;      /* handler calls */
    uint32_t spurious;  /* calls that found nothing to do */
    uint32_t throttles; /* times receive paused for lack of ring room */
    uint32_t max_burst; /* most bytes written to the transmit FIFO in one go */
} fbrl_uart_pl011_stats;

typedef struct fbrl_uart_pl011 {
    fbrl_uart_pl011_io io;
    struct fbrl_uart *uart;   /* fed by the handler; NULL until attached */
    uint32_t clock_hz;        /* UARTCLK: the divisors come from it */
    uint16_t headroom;        /* see FBRL_UART_PL011_RX_HEADROOM */
    volatile uint32_t imsc;   /* shadow of IMSC, written with the register */
    volatile uint32_t events; /* bumped by the handler whenever it moved a byte */
    uint32_t seen;            /* events as of the last service() return */
    fbrl_uart_pl011_stats stats;
} fbrl_uart_pl011;

/* Fill b (no register touched). clock_hz is the UART's reference clock (UARTCLK; on a
 * Stellaris part the system clock). */
FBRL_API fbrl_status fbrl_uart_pl011_init(fbrl_uart_pl011 *b, const fbrl_uart_pl011_io *io,
                                          uint32_t clock_hz);

/* The backend for fbrl_uart_init(u, &fbrl_uart_pl011_ops, b, ...). configure programs
 * IBRD/FBRD (nearest 1/64: within 0.8 %; refused where IBRD leaves 1..65535), LCRH
 * (5-8 bits, N/E/O, 1-2 stop bits, FIFOs on), IFLS, CR. */
extern FBRL_API const fbrl_uart_ops fbrl_uart_pl011_ops;

/* After fbrl_uart_init: connect the handler to the core and unmask receive and error
 * interrupts in IMSC. The board enables the UART's line in its interrupt controller. */
FBRL_API fbrl_status fbrl_uart_pl011_attach(fbrl_uart_pl011 *b, struct fbrl_uart *u);

/* The interrupt handler: call from the UART's vector. */
FBRL_API void fbrl_uart_pl011_isr(fbrl_uart_pl011 *b);

FBRL_API fbrl_status fbrl_uart_pl011_get_stats(const fbrl_uart_pl011 *b, fbrl_uart_pl011_stats *out);

#ifdef __cplusplus
}
#endif
#endif
