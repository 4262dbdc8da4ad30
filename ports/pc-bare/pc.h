/* SPDX-License-Identifier: MIT */
/* pc.h - the few PC facilities the image needs: port I/O, interrupts (IDT, 8259),
 * a 1 kHz PIT clock, the debug console and QEMU's isa-debug-exit. */
#ifndef PC_H
#define PC_H

#include <stdint.h>
#include "fbrl/uart_8250.h"

static inline uint8_t pc_inb(uint16_t port)
{
    uint8_t v;
    __asm__ volatile("inb %1, %0" : "=a"(v) : "Nd"(port));
    return v;
}

static inline void pc_outb(uint16_t port, uint8_t v)
{
    __asm__ volatile("outb %0, %1" : : "a"(v), "Nd"(port));
}

/* Set up the IDT (exceptions, IRQ0 timer, the COM IRQ, the rest), remap the 8259s to
 * vectors 0x20-0x2F with every line masked except the timer, and start the PIT at
 * 1 kHz. com_irq is the UART's line (4 for COM1). Interrupts stay disabled. */
void pc_init(unsigned com_irq, fbrl_uart_8250 *com);

/* The hooks for fbrl_uart_8250 (port I/O, cli/sti, hlt, the PIT clock). */
extern const fbrl_uart_8250_io pc_uart_io;

static inline void pc_sti(void) { __asm__ volatile("sti" ::: "memory"); }

uint64_t pc_now_us(void);

/* Text on QEMU's debug console (port 0xE9, -debugcon); ignored elsewhere. */
void pc_debug(const char *s);

/* End QEMU through isa-debug-exit (iobase 0xf4): exit status (code << 1) | 1. */
#define PC_EXIT_PASS  0x10u /* QEMU exit status 33 */
#define PC_EXIT_FAIL  0x11u /* 35 */
#define PC_EXIT_CRASH 0x12u /* 37: CPU exception */
void pc_exit(uint8_t code) __attribute__((noreturn));

#endif
