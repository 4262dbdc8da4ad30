/* SPDX-License-Identifier: MIT */
/* main.c - the bare-metal demo service: an interrupt-driven echo on COM1.
 *
 * The library's driver core (uart.c with its rings and XON/XOFF) runs over the
 * 8250/16550 backend; IRQ4 drives it. Protocol, for the host test:
 *   ENQ (0x05)  -> answers "READY\n"
 *   EOT (0x04)  -> drains the transmitter, prints one line
 *                  "STATS rx=N tx=N sum=N xoff_sent=N xoff_recv=N overruns=N errors=N
 *                   irqs=N throttles=N maxburst=N PASS|FAIL"
 *                  then waits for ACK (0x06, up to 5 s) and ends QEMU through
 *                  isa-debug-exit (PASS: status 33, FAIL: 35)
 *   any other byte -> echoed, a-z upper-cased.
 * Verdict FAIL: a received byte was lost (overrun) or a line error was seen. With no
 * byte at all for 60 s the image gives up with FAIL, so it never hangs a test run.
 *
 * Options on the Multiboot command line (qemu -append "..."):
 *   baud=N      line rate (default 115200; must divide 115200)
 *   fifo=N      16550 receive trigger 1, 4, 8 or 14 (default 14); fifo=0 runs the
 *               chip as a plain 8250/16450 (one byte per interrupt), as does a chip
 *               that fbrl_uart_8250_probe() finds has no usable FIFO
 *   stall=MS    after every 16 KiB received, stop reading for MS milliseconds (a
 *               slow consumer: the receive ring fills, XOFF goes out, the handler
 *               pauses reception) */
#include <stdint.h>
#include <stddef.h>
#include "pc.h"
#include "fbrl/uart.h"
#include "fbrl/uart_8250.h"

#define ENQ           0x05u
#define EOT           0x04u
#define ACK           0x06u
#define IDLE_LIMIT_US 60000000u

static fbrl_uart_8250 com;
static fbrl_uart uart;
/* A small receive ring on purpose: its high-water mark is crossed in normal use, so
 * the XOFF/XON path and the handler's headroom rule both run. */
static uint8_t rx_mem[256];
static uint8_t tx_mem[1024];

/* The value of "key=N" in the command line, or dflt. */
static uint32_t option(const char *cmdline, const char *key, uint32_t dflt)
{
    const char *p = cmdline;
    while (p && *p) {
        const char *k = key, *q = p;
        while (*k && *q == *k) {
            k++;
            q++;
        }
        if (*k == 0 && (p == cmdline || p[-1] == ' ') && *q >= '0' && *q <= '9') {
            uint32_t v = 0;
            while (*q >= '0' && *q <= '9')
                v = v * 10u + (uint32_t)(*q++ - '0');
            return v;
        }
        p++;
    }
    return dflt;
}

static void put_all(const void *buf, size_t len)
{
    const uint8_t *p = buf;
    while (len > 0) {
        size_t n = 0;
        fbrl_status st = fbrl_uart_write(&uart, p, len, &n, 1000u);
        if (st < 0 && st != FBRL_ETIMEOUT && st != FBRL_EFULL)
            pc_exit(PC_EXIT_FAIL);
        p += n;
        len -= n;
    }
}

static void put_str(const char *s)
{
    size_t n = 0;
    while (s[n])
        n++;
    put_all(s, n);
}

/* Decimal without division by a 64-bit value (no libgcc here): 32-bit is enough. */
static void put_num(const char *label, uint32_t v)
{
    char buf[16];
    int i = (int)sizeof buf;
    buf[--i] = 0;
    do {
        buf[--i] = (char)('0' + v % 10u);
        v /= 10u;
    } while (v);
    put_str(label);
    put_str(&buf[i]);
}

static void finish(uint32_t sum)
{
    fbrl_uart_counters c;
    fbrl_uart_8250_stats s;
    int pass;
    (void)fbrl_uart_get_counters(&uart, &c);
    (void)fbrl_uart_8250_get_stats(&com, &s);
    pass = c.overruns == 0 && c.framing_errors == 0 && c.parity_errors == 0;
    put_num("STATS rx=", (uint32_t)c.rx_bytes);
    put_num(" tx=", (uint32_t)c.tx_bytes);
    put_num(" sum=", sum);
    put_num(" xoff_sent=", (uint32_t)c.xoff_sent);
    put_num(" xoff_recv=", (uint32_t)c.xoff_received);
    put_num(" overruns=", (uint32_t)c.overruns);
    put_num(" errors=", (uint32_t)(c.framing_errors + c.parity_errors));
    put_num(" irqs=", s.irqs);
    put_num(" throttles=", s.throttles);
    put_num(" maxburst=", s.max_burst);
    put_str(pass ? " PASS\n" : " FAIL\n");
    /* QEMU drops what it has not yet handed to the host when it exits, so wait for
     * the host's ACK (it has the whole line) before leaving; give up after 5 s. */
    for (;;) {
        uint8_t c;
        size_t n = 0;
        if (fbrl_uart_read(&uart, &c, 1, &n, 5000u) != FBRL_OK || c == ACK)
            break;
    }
    pc_exit(pass ? PC_EXIT_PASS : PC_EXIT_FAIL);
}

void kmain(uint32_t magic, void *mbi);

void kmain(uint32_t magic, void *mbi)
{
    fbrl_uart_config cfg = FBRL_UART_CONFIG_DEFAULT;
    uint8_t in[64];
    uint32_t sum = 0;
    uint64_t last = 0;
    uint32_t fifo, stall_ms, since_stall = 0;
    const char *cmdline = NULL;
    fbrl_uart_8250_chip chip;
    if (magic != 0x2BADB002u)
        pc_exit(PC_EXIT_FAIL);
    /* Multiboot info: flags bit 2 says the command line's address is at offset 16. */
    if (((const uint32_t *)mbi)[0] & 4u)
        cmdline = (const char *)((const uint32_t *)mbi)[4];
    cfg.baud = option(cmdline, "baud=", 115200u);
    fifo = option(cmdline, "fifo=", 14u);
    stall_ms = option(cmdline, "stall=", 0u);
    pc_init(FBRL_UART_8250_COM1_IRQ, &com);
    if (fbrl_uart_8250_probe(&pc_uart_io, FBRL_UART_8250_COM1_BASE, &chip) != FBRL_OK) {
        pc_debug("pc-bare: no UART at COM1\n");
        pc_exit(PC_EXIT_FAIL);
    }
    pc_debug(chip == FBRL_UART_8250_16550 ? "pc-bare: COM1 is a 16550A\n" : "pc-bare: COM1 is an 8250\n");
    if (chip == FBRL_UART_8250_8250 || fifo == 0) {
        chip = FBRL_UART_8250_8250;
        fifo = 1;
    }
    if (fbrl_uart_8250_init(&com, &pc_uart_io, FBRL_UART_8250_COM1_BASE, FBRL_UART_8250_COM1_IRQ, chip,
                            (uint8_t)fifo) != FBRL_OK ||
        fbrl_uart_init(&uart, &fbrl_uart_8250_ops, &com, rx_mem, sizeof rx_mem, tx_mem, sizeof tx_mem,
                       &cfg) != FBRL_OK ||
        fbrl_uart_8250_attach(&com, &uart) != FBRL_OK) {
        pc_debug("pc-bare: uart setup failed\n");
        pc_exit(PC_EXIT_FAIL);
    }
    pc_sti();
    pc_debug("pc-bare: up\n");
    last = pc_now_us();
    for (;;) {
        size_t n = 0, i, out;
        fbrl_status st = fbrl_uart_read(&uart, in, sizeof in, &n, 1000u);
        if (st < 0 && st != FBRL_ETIMEOUT && st != FBRL_EEMPTY)
            pc_exit(PC_EXIT_FAIL);
        if (n == 0) {
            if (pc_now_us() - last > IDLE_LIMIT_US) {
                pc_debug("pc-bare: no input, giving up\n");
                pc_exit(PC_EXIT_FAIL);
            }
            continue;
        }
        last = pc_now_us();
        since_stall += (uint32_t)n;
        if (stall_ms && since_stall >= 16384u) {
            /* Interrupts stay on: the handler keeps filling the ring meanwhile. */
            uint64_t until = pc_now_us() + (uint64_t)stall_ms * 1000u;
            while (pc_now_us() < until)
                __asm__ volatile("hlt");
            since_stall = 0;
        }
        /* Transform in place; answer ENQ and EOT where they stand in the stream. */
        for (i = 0, out = 0; i < n; i++) {
            uint8_t c = in[i];
            if (c == ENQ || c == EOT) {
                put_all(in, out);
                out = 0;
                if (c == EOT)
                    finish(sum);
                put_str("READY\n");
                continue;
            }
            if (c >= 'a' && c <= 'z')
                c = (uint8_t)(c - 'a' + 'A');
            sum += c;
            in[out++] = c;
        }
        put_all(in, out);
    }
}
