/* SPDX-License-Identifier: MIT */
/* board.c - TI Stellaris LM3S6965 (QEMU lm3s6965evb): vector table and reset, the PLL
 * at 50 MHz, SysTick at 1 kHz as the clock, UART0/UART1 (PL011) with their pins and
 * NVIC lines, a RAM storage region, reset. Register addresses: LM3S6965 data sheet. */
#include "board.h"

#include <string.h>

#define REG32(a) (*(volatile uint32_t *)(uintptr_t)(a))

/* System control */
#define SYSCTL_RIS       0x400FE050u
#define SYSCTL_RCC       0x400FE060u
#define SYSCTL_RCGC1     0x400FE104u
#define SYSCTL_RCGC2     0x400FE108u
#define RIS_PLLLRIS      (1u << 6)
#define RCC_SYSDIV_SHIFT 23u
#define RCC_USESYSDIV    (1u << 22)
#define RCC_PWRDN        (1u << 13)
#define RCC_BYPASS       (1u << 11)
#define RCC_XTAL_SHIFT   6u
#define RCC_XTAL_MASK    (0xFu << RCC_XTAL_SHIFT)
#define RCC_OSCSRC_MASK  (3u << 4)
#define RCC_XTAL_8MHZ    0xEu /* the EVB's crystal */
#define RCC_SYSDIV_50MHZ 3u   /* 200 MHz PLL output / (3 + 1) */
#define PLL_LOCK_POLLS   100000u
#define SYSCLK_HZ        50000000u
#define RCGC1_UART0      (1u << 0)
#define RCGC1_UART1      (1u << 1)
#define RCGC2_GPIOA      (1u << 0)
#define RCGC2_GPIOD      (1u << 3)

/* GPIO: UART0 on PA0/PA1, UART1 on PD2/PD3 */
#define GPIOA_BASE      0x40004000u
#define GPIOD_BASE      0x40007000u
#define GPIO_AFSEL      0x420u
#define GPIO_DEN        0x51Cu
#define UART0_PINS      0x03u
#define UART1_PINS      0x0Cu
#define UART0_BASE      0x4000C000u
#define UART1_BASE      0x4000D000u
#define UART0_IRQ       5u
#define UART1_IRQ       6u
#define CLOCK_GATE_WAIT 3u /* cycles to wait after a clock gate opens */

/* Cortex-M3 core peripherals */
#define SYST_CSR         0xE000E010u
#define SYST_RVR         0xE000E014u
#define SYST_CVR         0xE000E018u
#define SYST_CSR_ENABLE  (1u << 0)
#define SYST_CSR_TICKINT (1u << 1)
#define SYST_CSR_CORECLK (1u << 2)
#define SCB_ICSR         0xE000ED04u
#define ICSR_PENDSTSET   (1u << 26)
#define NVIC_ISER0       0xE000E100u
#define SCB_AIRCR        0xE000ED0Cu
#define AIRCR_RESET      ((0x05FAu << 16) | (1u << 2)) /* VECTKEY | SYSRESETREQ */

#define US_PER_TICK   (1000000u / BOARD_TICK_HZ)
#define CYCLES_PER_US (SYSCLK_HZ / 1000000u)
#define TICK_RELOAD   (SYSCLK_HZ / BOARD_TICK_HZ - 1u)

#define STORAGE_BYTES 2048u /* RAM region for the data files (store.c) */

/* ---- interrupts ---- */

static uint32_t irq_save(void)
{
    uint32_t primask;
    __asm volatile("mrs %0, primask\n cpsid i" : "=r"(primask)::"memory");
    return primask;
}

static void irq_restore(uint32_t primask) { __asm volatile("msr primask, %0" ::"r"(primask) : "memory"); }

void board_irq_on(void) { __asm volatile("cpsie i" ::: "memory"); }

/* ---- clock ---- */

static volatile uint32_t ticks_hi, ticks_lo; /* SysTick interrupts since reset (64 bits) */
static void (*volatile tick_hook)(void);

static void systick_handler(void)
{
    void (*fn)(void) = tick_hook;
    if (++ticks_lo == 0)
        ticks_hi++;
    if (fn)
        fn();
}

void board_on_tick(void (*fn)(void)) { tick_hook = fn; }

uint64_t board_now_us(void)
{
    uint32_t saved = irq_save(), cvr = REG32(SYST_CVR);
    uint64_t t = ((uint64_t)ticks_hi << 32) | ticks_lo;
    /* A tick whose handler is held off here: count it (once: it still runs later). */
    if (REG32(SCB_ICSR) & ICSR_PENDSTSET) {
        cvr = REG32(SYST_CVR);
        t++;
    }
    irq_restore(saved);
    return t * US_PER_TICK + (TICK_RELOAD - cvr) / CYCLES_PER_US;
}

/* Inside irq_save: WFI wakes for a pending interrupt even while PRIMASK holds it off;
 * opening PRIMASK then lets it run, and closing it again restores the caller's state. */
static void idle(void) { __asm volatile("wfi\n cpsie i\n isb\n cpsid i" ::: "memory"); }

void board_sleep_until(uint64_t us)
{
    uint32_t saved = irq_save();
    while (board_now_us() < us)
        idle();
    irq_restore(saved);
}

/* ---- UARTs ---- */

static const uint32_t uart_irq[BOARD_UARTS] = {UART0_IRQ, UART1_IRQ};
static fbrl_uart_pl011 *uart_state[BOARD_UARTS];

static uint32_t io_read(void *ctx, uint32_t off) { return REG32((uintptr_t)ctx + off); }
static void io_write(void *ctx, uint32_t off, uint32_t v) { REG32((uintptr_t)ctx + off) = v; }
static uint32_t io_irq_save(void *ctx)
{
    (void)ctx;
    return irq_save();
}
static void io_irq_restore(void *ctx, uint32_t saved)
{
    (void)ctx;
    irq_restore(saved);
}
static void io_idle(void *ctx)
{
    (void)ctx;
    idle();
}
static uint64_t io_now_us(void *ctx)
{
    (void)ctx;
    return board_now_us();
}

static const fbrl_uart_pl011_io uart_io[BOARD_UARTS] = {
    {io_read, io_write, io_irq_save, io_irq_restore, io_idle, io_now_us, (void *)(uintptr_t)UART0_BASE},
    {io_read, io_write, io_irq_save, io_irq_restore, io_idle, io_now_us, (void *)(uintptr_t)UART1_BASE},
};

const fbrl_uart_pl011_io *board_uart_io(unsigned n) { return n < BOARD_UARTS ? &uart_io[n] : NULL; }

uint32_t board_uart_clock_hz(void) { return SYSCLK_HZ; }

void board_uart_irq(unsigned n, fbrl_uart_pl011 *b)
{
    if (n >= BOARD_UARTS)
        return;
    uart_state[n] = b;
    REG32(NVIC_ISER0) = 1u << uart_irq[n];
}

static void uart0_handler(void) { fbrl_uart_pl011_isr(uart_state[0]); }
static void uart1_handler(void) { fbrl_uart_pl011_isr(uart_state[1]); }

/* ---- storage ---- */

static unsigned char storage[STORAGE_BYTES] __attribute__((aligned(8)));

void *board_storage(size_t *size)
{
    *size = sizeof storage;
    return storage;
}

int board_storage_write(size_t off, const void *src, size_t n)
{
    if (off > sizeof storage || n > sizeof storage - off)
        return -1;
    memcpy(storage + off, src, n);
    return 0;
}

/* ---- reset ---- */

void board_reset(void)
{
    REG32(SCB_AIRCR) = AIRCR_RESET;
    for (;;)
        __asm volatile("wfi");
}

static void pll_50mhz(void)
{
    uint32_t rcc = REG32(SYSCTL_RCC), n;
    /* Data sheet order: bypass the PLL, set the crystal and power the PLL, divide,
     * wait for lock (bounded), then take the PLL. */
    rcc = (rcc | RCC_BYPASS) & ~RCC_USESYSDIV;
    REG32(SYSCTL_RCC) = rcc;
    rcc = (rcc & ~(RCC_XTAL_MASK | RCC_OSCSRC_MASK | RCC_PWRDN)) | (RCC_XTAL_8MHZ << RCC_XTAL_SHIFT);
    REG32(SYSCTL_RCC) = rcc;
    rcc = (rcc & ~(0xFu << RCC_SYSDIV_SHIFT)) | (RCC_SYSDIV_50MHZ << RCC_SYSDIV_SHIFT) | RCC_USESYSDIV;
    REG32(SYSCTL_RCC) = rcc;
    for (n = 0; n < PLL_LOCK_POLLS && !(REG32(SYSCTL_RIS) & RIS_PLLLRIS); n++) {
    }
    REG32(SYSCTL_RCC) = rcc & ~RCC_BYPASS;
}

void board_init(void)
{
    volatile uint32_t settle;
    pll_50mhz();
    REG32(SYSCTL_RCGC1) |= RCGC1_UART0 | RCGC1_UART1;
    REG32(SYSCTL_RCGC2) |= RCGC2_GPIOA | RCGC2_GPIOD;
    for (settle = 0; settle < CLOCK_GATE_WAIT; settle++) {
    }
    REG32(GPIOA_BASE + GPIO_AFSEL) |= UART0_PINS;
    REG32(GPIOA_BASE + GPIO_DEN) |= UART0_PINS;
    REG32(GPIOD_BASE + GPIO_AFSEL) |= UART1_PINS;
    REG32(GPIOD_BASE + GPIO_DEN) |= UART1_PINS;
    REG32(SYST_RVR) = TICK_RELOAD;
    REG32(SYST_CVR) = 0;
    REG32(SYST_CSR) = SYST_CSR_ENABLE | SYST_CSR_TICKINT | SYST_CSR_CORECLK;
}

/* ---- reset and the vector table ---- */

extern uint32_t fw_data_start[], fw_data_end[], fw_data_load[], fw_tdata_start[], fw_tdata_end[],
    fw_tdata_load[], fw_bss_start[], fw_bss_end[], fw_stack_bottom[], fw_stack_top[];
extern void _set_tls(void *tls); /* picolibc: the thread pointer (errno lives there) */
int main(void);
void fw_reset(void) __attribute__((noreturn));

static void copy_words(uint32_t *dst, const uint32_t *end, const uint32_t *src)
{
    while (dst < end)
        *dst++ = *src++;
}

#define STACK_PAINT     0x5354414Bu /* "STAK": never written by the program, so far */
#define STACK_PAINT_GAP 64u         /* bytes left alone below fw_reset's own frame */

size_t board_stack_size(void)
{
    return (size_t)((unsigned char *)fw_stack_top - (unsigned char *)fw_stack_bottom);
}

size_t board_stack_used(void)
{
    const uint32_t *p = fw_stack_bottom;
    while (p < fw_stack_top && *p == STACK_PAINT)
        p++;
    return (size_t)((const unsigned char *)fw_stack_top - (const unsigned char *)p);
}

void fw_reset(void)
{
    uint32_t *p;
    unsigned char *sp;
    /* Paint the stack below this frame: board_stack_used() finds the high-water mark. */
    __asm volatile("mov %0, sp" : "=r"(sp));
    for (p = fw_stack_bottom; (unsigned char *)(p + 1) < sp - STACK_PAINT_GAP; p++)
        *p = STACK_PAINT;
    copy_words(fw_data_start, fw_data_end, fw_data_load);
    copy_words(fw_tdata_start, fw_tdata_end, fw_tdata_load);
    for (p = fw_bss_start; p < fw_bss_end; p++)
        *p = 0;
    _set_tls(fw_tdata_start);
    main();
    board_reset();
}

/* A fault resets the board: the controller's line and the prompt come back. */
static void fault_handler(void) { board_reset(); }

static void unused_handler(void) {}

#define VECTORS 64u /* 16 system exceptions + the part's 48 interrupt lines */
#define IRQ0    16u

/* Lines never enabled in the NVIC stay empty (reserved slots are 0 on every part). */
typedef void (*vector)(void);
__attribute__((section(".vectors"), used)) static const vector vectors[VECTORS] = {
    [0] = (vector)(uintptr_t)fw_stack_top,
    [1] = fw_reset,
    [2] = fault_handler,   /* NMI */
    [3] = fault_handler,   /* HardFault */
    [4] = fault_handler,   /* MemManage */
    [5] = fault_handler,   /* BusFault */
    [6] = fault_handler,   /* UsageFault */
    [11] = unused_handler, /* SVCall */
    [14] = unused_handler, /* PendSV */
    [15] = systick_handler,
    [IRQ0 + UART0_IRQ] = uart0_handler,
    [IRQ0 + UART1_IRQ] = uart1_handler,
};
