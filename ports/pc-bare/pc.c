/* SPDX-License-Identifier: MIT */
/* pc.c - IDT, 8259 PIC, PIT clock, port-I/O hooks and exits for the bare PC image. */
#include "pc.h"

#define PIC1_CMD       0x20u
#define PIC1_DATA      0x21u
#define PIC2_CMD       0xA0u
#define PIC2_DATA      0xA1u
#define IRQ_BASE       0x20u /* vectors 0x20-0x2F: clear of the CPU's 0-31 */
#define PIT_HZ_DIVISOR 1193u /* 1193182 Hz / 1193 = 1000.15 Hz: one tick per ms */

struct idt_gate {
    uint16_t off_lo;
    uint16_t sel;
    uint8_t zero;
    uint8_t type;
    uint16_t off_hi;
} __attribute__((packed));

static struct idt_gate idt[IRQ_BASE + 16];
static volatile uint32_t ticks_ms;
static fbrl_uart_8250 *com_port;
static unsigned com_line;

extern const uint32_t pc_exception_stubs[32];
void pc_irq_timer_stub(void);
void pc_irq_com_stub(void);
void pc_irq_other_stub(void);
/* Called from boot.S. */
void pc_irq_timer(void);
void pc_irq_com(void);
void pc_irq_other(void);
void pc_exception(uint32_t vector);

static void set_gate(unsigned vec, uint32_t handler)
{
    idt[vec].off_lo = (uint16_t)(handler & 0xFFFFu);
    idt[vec].sel = 0x08;
    idt[vec].zero = 0;
    idt[vec].type = 0x8E; /* present, ring 0, 32-bit interrupt gate (clears IF) */
    idt[vec].off_hi = (uint16_t)(handler >> 16);
}

void pc_init(unsigned com_irq, fbrl_uart_8250 *com)
{
    struct {
        uint16_t limit;
        uint32_t base;
    } __attribute__((packed)) idtr;
    unsigned v;

    com_port = com;
    com_line = com_irq;
    for (v = 0; v < 32; v++)
        set_gate(v, pc_exception_stubs[v]);
    for (v = 0; v < 16; v++)
        set_gate(IRQ_BASE + v, (uint32_t)pc_irq_other_stub);
    set_gate(IRQ_BASE + 0, (uint32_t)pc_irq_timer_stub);
    set_gate(IRQ_BASE + com_irq, (uint32_t)pc_irq_com_stub);
    idtr.limit = sizeof idt - 1;
    idtr.base = (uint32_t)idt;
    __asm__ volatile("lidt %0" : : "m"(idtr));

    /* 8259 pair: ICW1 edge + ICW4, ICW2 vector bases, ICW3 cascade on IRQ2, ICW4 8086. */
    pc_outb(PIC1_CMD, 0x11);
    pc_outb(PIC2_CMD, 0x11);
    pc_outb(PIC1_DATA, IRQ_BASE);
    pc_outb(PIC2_DATA, IRQ_BASE + 8);
    pc_outb(PIC1_DATA, 0x04);
    pc_outb(PIC2_DATA, 0x02);
    pc_outb(PIC1_DATA, 0x01);
    pc_outb(PIC2_DATA, 0x01);
    pc_outb(PIC1_DATA, 0xFE); /* timer only; the UART backend unmasks its own line */
    pc_outb(PIC2_DATA, 0xFF);

    /* PIT channel 0, lobyte/hibyte, mode 2 (rate generator). */
    pc_outb(0x43, 0x34);
    pc_outb(0x40, (uint8_t)(PIT_HZ_DIVISOR & 0xFFu));
    pc_outb(0x40, (uint8_t)(PIT_HZ_DIVISOR >> 8));
}

void pc_irq_timer(void)
{
    ticks_ms++;
    pc_outb(PIC1_CMD, 0x20);
}

void pc_irq_com(void) { fbrl_uart_8250_isr(com_port); /* ends with the EOI */ }

void pc_irq_other(void)
{
    /* Masked lines and the 8259's spurious IRQ7 land here: an EOI with nothing in
     * service is harmless. */
    pc_outb(PIC2_CMD, 0x20);
    pc_outb(PIC1_CMD, 0x20);
}

static void put_hex(uint32_t v)
{
    char s[11];
    int i;
    s[0] = '0';
    s[1] = 'x';
    for (i = 0; i < 8; i++)
        s[2 + i] = "0123456789abcdef"[(v >> (28 - 4 * i)) & 0xFu];
    s[10] = 0;
    pc_debug(s);
}

void pc_exception(uint32_t vector)
{
    pc_debug("pc-bare: CPU exception ");
    put_hex(vector);
    pc_debug("\n");
    pc_exit(PC_EXIT_CRASH);
}

uint64_t pc_now_us(void) { return (uint64_t)ticks_ms * 1000u; }

void pc_debug(const char *s)
{
    while (*s)
        pc_outb(0xE9, (uint8_t)*s++);
}

void pc_exit(uint8_t code)
{
    pc_outb(0xF4, code);
    /* Not under QEMU (or no isa-debug-exit): stop here. */
    for (;;)
        __asm__ volatile("cli; hlt");
}

/* --- hooks for the 8250 backend --- */

static uint8_t io_inb(void *ctx, uint16_t port)
{
    (void)ctx;
    return pc_inb(port);
}

static void io_outb(void *ctx, uint16_t port, uint8_t v)
{
    (void)ctx;
    pc_outb(port, v);
}

static uint32_t io_irq_save(void *ctx)
{
    uint32_t flags;
    (void)ctx;
    __asm__ volatile("pushfl; popl %0; cli" : "=r"(flags) : : "memory");
    return flags;
}

static void io_irq_restore(void *ctx, uint32_t flags)
{
    (void)ctx;
    if (flags & 0x200u) /* IF was set */
        __asm__ volatile("sti" ::: "memory");
}

static void io_idle(void *ctx)
{
    (void)ctx;
    /* STI takes effect after the next instruction, so no interrupt can slip in
     * between the caller's check and the HLT. */
    __asm__ volatile("sti; hlt; cli" ::: "memory");
}

static uint64_t io_now_us(void *ctx)
{
    (void)ctx;
    return pc_now_us();
}

const fbrl_uart_8250_io pc_uart_io = {io_inb, io_outb, io_irq_save, io_irq_restore, io_idle, io_now_us, 0};
