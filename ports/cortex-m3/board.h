/* SPDX-License-Identifier: MIT */
/* board.h - the hooks the FBRL firmware needs from its board (board.c: TI LM3S6965, as
 * QEMU's lm3s6965evb models it). A port to another Cortex-M3 with a PL011 replaces
 * board.c and keeps main.c and store.c (docs/firmware.md, "Porting"). */
#ifndef FW_BOARD_H
#define FW_BOARD_H

#include <stddef.h>
#include <stdint.h>
#include "fbrl/uart_pl011.h"

#define BOARD_TICK_HZ 1000u /* SysTick rate: the clock's resolution */

/* The two serial lines: the console (the Forth prompt) and the controller (RAPL). */
enum { BOARD_UART_CONSOLE = 0, BOARD_UART_ROBOT = 1, BOARD_UARTS = 2 };

/* Clocks, pins, SysTick; interrupts stay off until board_irq_on(). */
void board_init(void);
/* The register hooks and reference clock of UART n, for fbrl_uart_pl011_init(). */
const fbrl_uart_pl011_io *board_uart_io(unsigned n);
uint32_t board_uart_clock_hz(void);
/* Connect UART n's interrupt to its backend state (its vector then calls
 * fbrl_uart_pl011_isr(b)) and enable the line in the NVIC. */
void board_uart_irq(unsigned n, fbrl_uart_pl011 *b);
void board_irq_on(void);

uint64_t board_now_us(void); /* since reset, monotonic */
/* fn runs in the clock's interrupt, every tick (NULL: none). */
void board_on_tick(void (*fn)(void));
void board_sleep_until(uint64_t us);

/* The storage region the data files live in (store.c): RAM here; a flash port returns
 * its sector and implements board_storage_write() with erase/program. */
void *board_storage(size_t *size);
/* Copy n bytes to offset off of the region (flash: program); 0 on success. */
int board_storage_write(size_t off, const void *src, size_t n);

/* Bytes of the main stack used so far (its high-water mark, from a painted stack). */
size_t board_stack_used(void);
size_t board_stack_size(void);

/* BYE: a system reset (QEMU run with -no-reboot exits instead). */
void board_reset(void) __attribute__((noreturn));

#endif
