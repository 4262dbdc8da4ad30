/* SPDX-License-Identifier: MIT */
/* test_uart_8250.c - the 8250/16550 backend against a register model.
 *
 * The model below is the hardware boundary (the only place the project allows a
 * stand-in): it behaves like a 16550 (DLAB, IER/IIR priorities, LSR, FIFOs, THRE) and
 * a master 8259 (mask register, EOI), and logs every port access so the tests can
 * check the exact register sequence. Everything above it is real: the backend and
 * the driver core with its rings and flow control. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>

#include "fbrl/uart_8250.h"
#include "fbrl/uart.h"

#define BASE 0x3F8u

/* ---------------------------------------------------------------- the model */

typedef struct access {
    char dir; /* 'r' or 'w' */
    uint16_t port;
    uint8_t val;
} access;

typedef struct model {
    unsigned depth;  /* 16 (16550) or 1 (8250) */
    int absent;      /* nothing at BASE: every read gives 0xFF */
    int early_16550; /* the first 16550: IIR bits 7:6 read 10 with FIFO on */
    /* chip */
    uint8_t ier, lcr, mcr, fcr, dll, dlm;
    uint8_t rx[256];
    unsigned rx_head, rx_n;
    uint8_t lsr_err;      /* OE/PE/FE/BI latched until LSR is read */
    unsigned tx_fifo;     /* bytes written since the transmitter was last empty */
    unsigned tx_overflow; /* THR writes while the FIFO was already full */
    int thre_pending;
    int msr_delta, msr_stuck;
    uint8_t tx[70000];
    size_t tx_n;
    /* 8259 */
    uint8_t pic_mask;
    unsigned eois;
    /* clock and hooks */
    uint64_t now;
    unsigned iir_reads;
    void (*on_iir)(struct model *m, unsigned nth);
    void (*on_idle)(struct model *m);
    unsigned saved_depth; /* irq_save nesting */
    unsigned ier_writes_while_open;
    /* log */
    access log[8192];
    size_t nlog;
} model;

static model M;
static fbrl_uart_8250 B;
static fbrl_uart U;
static uint8_t rx_mem[512], tx_mem[512];

static void model_reset(unsigned depth)
{
    memset(&M, 0, sizeof M);
    M.depth = depth;
    M.pic_mask = 0xFF;
}

static void model_rx(model *m, const char *s, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        assert_true(m->rx_n < sizeof m->rx);
        m->rx[(m->rx_head + m->rx_n++) % sizeof m->rx] = (uint8_t)s[i];
    }
}

/* The transmitter shifted everything out: THR empty, THRE interrupt latched. */
static void model_tx_done(model *m)
{
    m->tx_fifo = 0;
    m->thre_pending = 1;
}

static uint8_t model_iir(model *m)
{
    uint8_t fifo_bits = (m->fcr & 1u) ? (m->early_16550 ? 0x80u : 0xC0u) : 0u;
    if ((m->ier & FBRL_8250_IER_RLSI) && m->lsr_err)
        return (uint8_t)(fifo_bits | FBRL_8250_IIR_RLS);
    if ((m->ier & FBRL_8250_IER_RDI) && m->rx_n)
        return (uint8_t)(fifo_bits | FBRL_8250_IIR_RDA);
    if ((m->ier & FBRL_8250_IER_THRI) && m->thre_pending) {
        m->thre_pending = 0; /* reading IIR while it shows THRE clears it */
        return (uint8_t)(fifo_bits | FBRL_8250_IIR_THRE);
    }
    if ((m->ier & FBRL_8250_IER_MSI) && m->msr_delta)
        return (uint8_t)(fifo_bits | FBRL_8250_IIR_MSR);
    return (uint8_t)(fifo_bits | FBRL_8250_IIR_NONE);
}

static uint8_t io_inb(void *ctx, uint16_t port)
{
    model *m = ctx;
    uint8_t v = 0;
    int dlab = (m->lcr & FBRL_8250_LCR_DLAB) != 0;
    if (m->absent && port >= BASE && port <= BASE + 7) {
        assert_true(m->nlog < sizeof m->log / sizeof m->log[0]);
        m->log[m->nlog++] = (access){'r', port, 0xFF};
        return 0xFF;
    }
    switch (port) {
    case BASE + 0:
        if (dlab) {
            v = m->dll;
        } else if (m->rx_n) {
            v = m->rx[m->rx_head];
            m->rx_head = (m->rx_head + 1) % sizeof m->rx;
            m->rx_n--;
        }
        break;
    case BASE + 1: v = dlab ? m->dlm : m->ier; break;
    case BASE + 2:
        m->iir_reads++;
        if (m->on_iir)
            m->on_iir(m, m->iir_reads);
        v = model_iir(m);
        break;
    case BASE + 3: v = m->lcr; break;
    case BASE + 4: v = m->mcr; break;
    case BASE + 5:
        v = (uint8_t)(m->lsr_err | (m->rx_n ? FBRL_8250_LSR_DR : 0) |
                      (m->tx_fifo == 0 ? (FBRL_8250_LSR_THRE | 0x40u) : 0));
        m->lsr_err = 0;
        break;
    case BASE + 6:
        if (!m->msr_stuck)
            m->msr_delta = 0;
        v = 0xB0; /* DCD DSR CTS */
        break;
    case FBRL_8259_DATA: v = m->pic_mask; break;
    default: fail_msg("inb from unexpected port 0x%x", port);
    }
    assert_true(m->nlog < sizeof m->log / sizeof m->log[0]);
    m->log[m->nlog++] = (access){'r', port, v};
    return v;
}

static void io_outb(void *ctx, uint16_t port, uint8_t v)
{
    model *m = ctx;
    int dlab = (m->lcr & FBRL_8250_LCR_DLAB) != 0;
    assert_true(m->nlog < sizeof m->log / sizeof m->log[0]);
    m->log[m->nlog++] = (access){'w', port, v};
    if (m->absent && port >= BASE && port <= BASE + 7)
        return;
    switch (port) {
    case BASE + 0:
        if (dlab) {
            m->dll = v;
            break;
        }
        if (m->tx_fifo >= m->depth)
            m->tx_overflow++;
        m->tx_fifo++;
        m->thre_pending = 0;
        assert_true(m->tx_n < sizeof m->tx);
        m->tx[m->tx_n++] = v;
        break;
    case BASE + 1:
        if (dlab) {
            m->dlm = v;
        } else {
            /* THRI rising with the transmitter empty raises THRE (16550, QEMU). */
            if (!(m->ier & FBRL_8250_IER_THRI) && (v & FBRL_8250_IER_THRI) && m->tx_fifo == 0)
                m->thre_pending = 1;
            m->ier = v & 0x0Fu;
        }
        break;
    case BASE + 2:
        if (m->depth == 1)
            break; /* an 8250 has no FCR */
        m->fcr = v;
        if (v & FBRL_8250_FCR_CLEAR_RX)
            m->rx_n = 0;
        break;
    case BASE + 3: m->lcr = v; break;
    case BASE + 4: m->mcr = v; break;
    case FBRL_8259_DATA: m->pic_mask = v; break;
    case FBRL_8259_CMD:
        assert_int_equal(v, FBRL_8259_EOI);
        m->eois++;
        break;
    default: fail_msg("outb to unexpected port 0x%x", port);
    }
}

static uint32_t io_irq_save(void *ctx)
{
    model *m = ctx;
    return m->saved_depth++;
}

static void io_irq_restore(void *ctx, uint32_t saved)
{
    model *m = ctx;
    assert_int_equal(saved + 1, m->saved_depth);
    m->saved_depth = saved;
}

/* "sti; hlt; cli": time passes; the test may let an interrupt happen here. */
static void io_idle(void *ctx)
{
    model *m = ctx;
    m->now += 1000;
    if (m->on_idle)
        m->on_idle(m);
}

static uint64_t io_now(void *ctx) { return ((model *)ctx)->now; }

static const fbrl_uart_8250_io IO = {io_inb, io_outb, io_irq_save, io_irq_restore, io_idle, io_now, &M};

/* ------------------------------------------------------------ log helpers */

static size_t log_mark(void) { return M.nlog; }

/* The accesses since mark must be exactly the expected list. */
static void expect_log(size_t mark, const access *want, size_t n)
{
    size_t i;
    assert_int_equal(M.nlog - mark, n);
    for (i = 0; i < n; i++) {
        const access *got = &M.log[mark + i];
        if (got->dir != want[i].dir || got->port != want[i].port || got->val != want[i].val)
            fail_msg("access %zu: got %c 0x%x=0x%02x, want %c 0x%x=0x%02x", i, got->dir, got->port, got->val,
                     want[i].dir, want[i].port, want[i].val);
    }
}

static const access *last_access(void) { return &M.log[M.nlog - 1]; }

/* ---------------------------------------------------- the core, for real */

static fbrl_uart_config cfg_of(uint32_t baud, uint8_t bits, fbrl_parity par, uint8_t stop)
{
    fbrl_uart_config c = FBRL_UART_CONFIG_DEFAULT;
    c.baud = baud;
    c.data_bits = bits;
    c.parity = par;
    c.stop_bits = stop;
    return c;
}

/* A 16550 (or 8250) with the core on top, attached, 9600 8N1 XON/XOFF. */
static void open_port(fbrl_uart_8250_chip chip, uint8_t trigger, size_t rx_size)
{
    fbrl_uart_config c = FBRL_UART_CONFIG_DEFAULT;
    model_reset((unsigned)chip);
    assert_int_equal(fbrl_uart_8250_init(&B, &IO, BASE, 4, chip, trigger), FBRL_OK);
    assert_int_equal(fbrl_uart_init(&U, &fbrl_uart_8250_ops, &B, rx_mem, rx_size, tx_mem, sizeof tx_mem, &c),
                     FBRL_OK);
    assert_int_equal(fbrl_uart_8250_attach(&B, &U), FBRL_OK);
}

static size_t read_all(uint8_t *buf, size_t cap)
{
    size_t got = 0;
    assert_true(fbrl_uart_read(&U, buf, cap, &got, 0) >= FBRL_EEMPTY);
    return got;
}

static fbrl_uart_counters counters(void)
{
    fbrl_uart_counters c;
    assert_int_equal(fbrl_uart_get_counters(&U, &c), FBRL_OK);
    return c;
}

/* ------------------------------------------------------ line programming */

static const uint32_t standard_bauds[] = {50,   75,   150,  300,   600,   1200,  1800,  2400,  3600,
                                          4800, 7200, 9600, 14400, 19200, 38400, 57600, 115200};

/* LCR from the 16550 data sheet: bits 1:0 word length - 5, bit 2 two stop bits,
 * bit 3 parity enable, bit 4 even parity. */
static uint8_t sheet_lcr(uint8_t bits, fbrl_parity par, uint8_t stop)
{
    uint8_t lcr = (uint8_t)(bits - 5);
    if (stop == 2)
        lcr |= 0x04;
    if (par != FBRL_PARITY_NONE)
        lcr |= 0x08;
    if (par == FBRL_PARITY_EVEN)
        lcr |= 0x10;
    return lcr;
}

static void test_configure_every_setting(void **state)
{
    static const fbrl_parity pars[] = {FBRL_PARITY_NONE, FBRL_PARITY_EVEN, FBRL_PARITY_ODD};
    size_t bi, pi;
    unsigned bits, stop, checked = 0;
    (void)state;
    for (bi = 0; bi < sizeof standard_bauds / sizeof standard_bauds[0]; bi++)
        for (bits = 5; bits <= 8; bits++)
            for (pi = 0; pi < 3; pi++)
                for (stop = 1; stop <= 2; stop++) {
                    uint32_t baud = standard_bauds[bi];
                    fbrl_uart_config c = cfg_of(baud, (uint8_t)bits, pars[pi], (uint8_t)stop);
                    uint32_t div = 115200u / baud;
                    size_t mark;
                    model_reset(16);
                    assert_int_equal(fbrl_uart_8250_init(&B, &IO, BASE, 4, FBRL_UART_8250_16550, 14),
                                     FBRL_OK);
                    mark = log_mark();
                    if (bits == 5 && stop == 2) {
                        assert_int_equal(fbrl_uart_8250_ops.configure(&B, &c), FBRL_EUNSUPPORTED);
                        assert_int_equal(M.nlog, mark);
                        continue;
                    }
                    assert_int_equal(fbrl_uart_8250_ops.configure(&B, &c), FBRL_OK);
                    {
                        const access want[] = {
                            {'w', BASE + 1, 0x00},                  /* IER off */
                            {'w', BASE + 3, 0x80},                  /* DLAB */
                            {'w', BASE + 0, (uint8_t)(div & 0xFF)}, /* DLL */
                            {'w', BASE + 1, (uint8_t)(div >> 8)},   /* DLM */
                            {'w', BASE + 3, sheet_lcr((uint8_t)bits, pars[pi], (uint8_t)stop)},
                            {'w', BASE + 2, 0xC7}, /* FIFO on, clear, trigger 14 */
                            {'w', BASE + 4, 0x0B}, /* DTR RTS OUT2 */
                            {'r', BASE + 5, 0x60},
                            {'r', BASE + 6, 0xB0},
                            {'r', BASE + 2, 0xC1},
                        };
                        expect_log(mark, want, sizeof want / sizeof want[0]);
                    }
                    /* The divisor the chip holds gives back the baud rate exactly. */
                    assert_int_equal(115200u / ((unsigned)M.dlm << 8 | M.dll), baud);
                    assert_int_equal(M.lcr & 0x80, 0);
                    assert_int_equal(M.saved_depth, 0);
                    checked++;
                }
    assert_int_equal(checked, 17u * (4 * 3 * 2 - 3));
}

/* Values straight from the data sheet's tables, independent of any formula. */
static void test_configure_datasheet_values(void **state)
{
    static const struct {
        uint32_t baud;
        uint8_t bits, stop;
        fbrl_parity par;
        uint8_t dll, dlm, lcr;
    } t[] = {
        {9600, 8, 1, FBRL_PARITY_NONE, 0x0C, 0x00, 0x03}, {115200, 8, 1, FBRL_PARITY_NONE, 0x01, 0x00, 0x03},
        {2400, 7, 1, FBRL_PARITY_EVEN, 0x30, 0x00, 0x1A}, {1200, 7, 2, FBRL_PARITY_ODD, 0x60, 0x00, 0x0E},
        {300, 8, 2, FBRL_PARITY_EVEN, 0x80, 0x01, 0x1F},  {50, 5, 1, FBRL_PARITY_NONE, 0x00, 0x09, 0x00},
        {19200, 6, 1, FBRL_PARITY_ODD, 0x06, 0x00, 0x09},
    };
    size_t i;
    (void)state;
    for (i = 0; i < sizeof t / sizeof t[0]; i++) {
        fbrl_uart_config c = cfg_of(t[i].baud, t[i].bits, t[i].par, t[i].stop);
        model_reset(16);
        assert_int_equal(fbrl_uart_8250_init(&B, &IO, BASE, 4, FBRL_UART_8250_16550, 8), FBRL_OK);
        assert_int_equal(fbrl_uart_8250_ops.configure(&B, &c), FBRL_OK);
        assert_int_equal(M.dll, t[i].dll);
        assert_int_equal(M.dlm, t[i].dlm);
        assert_int_equal(M.lcr, t[i].lcr);
        assert_int_equal(M.fcr, 0x87); /* trigger 8 */
        assert_int_equal(M.mcr, 0x0B);
    }
}

static void test_configure_unsupported(void **state)
{
    static const uint32_t bad_bauds[] = {0, 110, 134, 7, 230400, 1, 56000, 921600};
    static const struct {
        uint8_t bits, stop;
    } bad_frames[] = {{4, 1}, {9, 1}, {8, 0}, {8, 3}, {5, 2}};
    size_t i;
    (void)state;
    model_reset(16);
    assert_int_equal(fbrl_uart_8250_init(&B, &IO, BASE, 4, FBRL_UART_8250_16550, 14), FBRL_OK);
    for (i = 0; i < sizeof bad_bauds / sizeof bad_bauds[0]; i++) {
        fbrl_uart_config c = cfg_of(bad_bauds[i], 8, FBRL_PARITY_NONE, 1);
        assert_int_equal(fbrl_uart_8250_ops.configure(&B, &c), FBRL_EUNSUPPORTED);
    }
    for (i = 0; i < sizeof bad_frames / sizeof bad_frames[0]; i++) {
        fbrl_uart_config c = cfg_of(9600, bad_frames[i].bits, FBRL_PARITY_NONE, bad_frames[i].stop);
        assert_int_equal(fbrl_uart_8250_ops.configure(&B, &c), FBRL_EUNSUPPORTED);
    }
    {
        fbrl_uart_config c = cfg_of(9600, 8, (fbrl_parity)'M', 1); /* mark parity */
        assert_int_equal(fbrl_uart_8250_ops.configure(&B, &c), FBRL_EUNSUPPORTED);
    }
    assert_int_equal(M.nlog, 0); /* a refused setting touches no register */
    assert_int_equal(fbrl_uart_8250_ops.configure(NULL, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_8250_ops.configure(&B, NULL), FBRL_EINVAL);
}

/* An 8250 has no FCR: the sequence skips it. */
static void test_configure_8250_no_fifo(void **state)
{
    fbrl_uart_config c = cfg_of(9600, 8, FBRL_PARITY_NONE, 1);
    size_t i;
    (void)state;
    model_reset(1);
    assert_int_equal(fbrl_uart_8250_init(&B, &IO, BASE, 4, FBRL_UART_8250_8250, 1), FBRL_OK);
    assert_int_equal(fbrl_uart_8250_ops.configure(&B, &c), FBRL_OK);
    for (i = 0; i < M.nlog; i++)
        assert_false(M.log[i].dir == 'w' && M.log[i].port == BASE + 2);
    assert_int_equal(M.fcr, 0);
}

/* probe: tells a 16550A from an 8250/16450 and from the early 16550 (broken FIFO),
 * finds an empty port, and leaves LCR as it was and the FIFOs off. */
static void test_probe(void **state)
{
    fbrl_uart_8250_chip chip = (fbrl_uart_8250_chip)0;
    (void)state;
    model_reset(16);
    M.lcr = 0x1A;
    assert_int_equal(fbrl_uart_8250_probe(&IO, BASE, &chip), FBRL_OK);
    assert_int_equal(chip, FBRL_UART_8250_16550);
    assert_int_equal(M.lcr, 0x1A);
    assert_int_equal(M.fcr & 1, 0);

    model_reset(1);
    assert_int_equal(fbrl_uart_8250_probe(&IO, BASE, &chip), FBRL_OK);
    assert_int_equal(chip, FBRL_UART_8250_8250);

    model_reset(16);
    M.early_16550 = 1;
    assert_int_equal(fbrl_uart_8250_probe(&IO, BASE, &chip), FBRL_OK);
    assert_int_equal(chip, FBRL_UART_8250_8250);

    model_reset(16);
    M.absent = 1;
    assert_int_equal(fbrl_uart_8250_probe(&IO, BASE, &chip), FBRL_ENOENT);

    assert_int_equal(fbrl_uart_8250_probe(NULL, BASE, &chip), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_8250_probe(&IO, BASE, NULL), FBRL_EINVAL);
}

static void test_init_arguments(void **state)
{
    fbrl_uart_8250_io io = IO;
    fbrl_uart_8250_stats st;
    (void)state;
    model_reset(16);
    assert_int_equal(fbrl_uart_8250_init(NULL, &IO, BASE, 4, FBRL_UART_8250_16550, 14), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_8250_init(&B, NULL, BASE, 4, FBRL_UART_8250_16550, 14), FBRL_EINVAL);
    io.idle = NULL;
    assert_int_equal(fbrl_uart_8250_init(&B, &io, BASE, 4, FBRL_UART_8250_16550, 14), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_8250_init(&B, &IO, BASE, 8, FBRL_UART_8250_16550, 14), FBRL_ERANGE);
    assert_int_equal(fbrl_uart_8250_init(&B, &IO, BASE, 4, FBRL_UART_8250_16550, 2), FBRL_ERANGE);
    assert_int_equal(fbrl_uart_8250_init(&B, &IO, BASE, 4, FBRL_UART_8250_8250, 14), FBRL_ERANGE);
    assert_int_equal(fbrl_uart_8250_init(&B, &IO, BASE, 4, (fbrl_uart_8250_chip)3, 1), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_8250_attach(NULL, &U), FBRL_EINVAL);
    assert_int_equal(fbrl_uart_8250_get_stats(NULL, &st), FBRL_EINVAL);
    assert_int_equal(M.nlog, 0);
}

/* attach: receive + line-status interrupts on, then IRQ4 unmasked at the 8259 (and
 * nothing else unmasked). COM2 on IRQ3 likewise. */
static void test_attach_and_close(void **state)
{
    fbrl_uart_config c = FBRL_UART_CONFIG_DEFAULT;
    size_t mark;
    (void)state;
    model_reset(16);
    M.pic_mask = 0xFE; /* timer already on */
    assert_int_equal(fbrl_uart_8250_init(&B, &IO, BASE, 4, FBRL_UART_8250_16550, 14), FBRL_OK);
    assert_int_equal(
        fbrl_uart_init(&U, &fbrl_uart_8250_ops, &B, rx_mem, sizeof rx_mem, tx_mem, sizeof tx_mem, &c),
        FBRL_OK);
    assert_int_equal(M.dll, 12); /* the core programmed the line through configure */
    mark = log_mark();
    assert_int_equal(fbrl_uart_8250_attach(&B, &U), FBRL_OK);
    {
        const access want[] = {
            {'w', BASE + 1, 0x05}, {'r', FBRL_8259_DATA, 0xFE}, {'w', FBRL_8259_DATA, 0xEE}};
        expect_log(mark, want, 3);
    }
    /* Reprogramming an attached port keeps its interrupts: IER comes back last. */
    mark = log_mark();
    assert_int_equal(fbrl_uart_8250_ops.configure(&B, &c), FBRL_OK);
    assert_int_equal(M.log[mark].port, BASE + 1);
    assert_int_equal(M.log[mark].val, 0);
    assert_int_equal(last_access()->port, BASE + 1);
    assert_int_equal(last_access()->val, 0x05);

    mark = log_mark();
    assert_int_equal(fbrl_uart_8250_ops.close(&B), FBRL_OK);
    {
        const access want[] = {{'r', FBRL_8259_DATA, 0xEE},
                               {'w', FBRL_8259_DATA, 0xFE},
                               {'w', BASE + 1, 0x00},
                               {'w', BASE + 4, 0x00}};
        expect_log(mark, want, 4);
    }

    model_reset(16);
    assert_int_equal(fbrl_uart_8250_init(&B, &IO, BASE, 3, FBRL_UART_8250_16550, 14), FBRL_OK);
    assert_int_equal(fbrl_uart_8250_attach(&B, &U), FBRL_OK);
    assert_int_equal(M.pic_mask, 0xF7);
}

/* ------------------------------------------------------- interrupt handler */

static void test_isr_receive(void **state)
{
    uint8_t buf[64];
    fbrl_uart_8250_stats st;
    (void)state;
    open_port(FBRL_UART_8250_16550, 14, sizeof rx_mem);
    model_rx(&M, "Hello, robot", 12);
    M.eois = 0;
    fbrl_uart_8250_isr(&B);
    assert_int_equal(M.rx_n, 0);
    assert_int_equal(M.eois, 1);
    /* The EOI is the very last access, after IIR read "none pending". */
    assert_int_equal(last_access()->port, FBRL_8259_CMD);
    assert_int_equal(M.log[M.nlog - 2].port, BASE + 2);
    assert_int_equal(M.log[M.nlog - 2].val & 1, 1);
    assert_int_equal(read_all(buf, sizeof buf), 12);
    assert_memory_equal(buf, "Hello, robot", 12);
    assert_int_equal(counters().rx_bytes, 12);
    assert_int_equal(fbrl_uart_8250_get_stats(&B, &st), FBRL_OK);
    assert_int_equal(st.irqs, 1);
    assert_int_equal(st.spurious, 0);
}

/* Transmit: tx_kick primes at most 16 bytes; each THRE interrupt refills at most 16;
 * when the core has nothing more, THRE interrupts go off. */
static void tx_run(fbrl_uart_8250_chip chip, uint8_t trigger)
{
    uint8_t msg[100];
    size_t i, written = 0;
    unsigned rounds = 0;
    for (i = 0; i < sizeof msg; i++)
        msg[i] = (uint8_t)('A' + i % 26);
    open_port(chip, trigger, sizeof rx_mem);
    assert_int_equal(fbrl_uart_write(&U, msg, sizeof msg, &written, 0), FBRL_OK);
    assert_int_equal(written, sizeof msg);
    assert_int_equal(M.tx_n, (unsigned)chip); /* primed by tx_kick, one FIFO-full */
    assert_true(M.ier & FBRL_8250_IER_THRI);
    while (M.tx_n < sizeof msg) {
        size_t before = M.tx_n;
        model_tx_done(&M);
        fbrl_uart_8250_isr(&B);
        assert_true(M.tx_n - before <= (unsigned)chip);
        assert_true(M.tx_n > before);
        assert_true(++rounds < 200);
    }
    assert_memory_equal(M.tx, msg, sizeof msg);
    assert_int_equal(M.tx_overflow, 0);
    assert_true(M.ier & FBRL_8250_IER_THRI);
    model_tx_done(&M);
    fbrl_uart_8250_isr(&B);
    assert_false(M.ier & FBRL_8250_IER_THRI); /* nothing left: THRE interrupts off */
    assert_int_equal(counters().tx_bytes, sizeof msg);
}

static void test_isr_transmit_16550(void **state)
{
    fbrl_uart_8250_stats st;
    (void)state;
    tx_run(FBRL_UART_8250_16550, 14);
    assert_int_equal(fbrl_uart_8250_get_stats(&B, &st), FBRL_OK);
    assert_int_equal(st.max_burst, 16);
}

static void test_isr_transmit_8250(void **state)
{
    (void)state;
    tx_run(FBRL_UART_8250_8250, 1);
}

/* LSR error bits reach the core's counters, per kind. */
static void test_isr_line_status(void **state)
{
    fbrl_uart_counters c;
    uint8_t buf[8];
    (void)state;
    open_port(FBRL_UART_8250_16550, 14, sizeof rx_mem);
    M.ier |= FBRL_8250_IER_RLSI;
    M.lsr_err = FBRL_8250_LSR_OE;
    fbrl_uart_8250_isr(&B);
    M.lsr_err = FBRL_8250_LSR_PE;
    fbrl_uart_8250_isr(&B);
    M.lsr_err = FBRL_8250_LSR_FE;
    fbrl_uart_8250_isr(&B);
    /* A break: FE|BI with a NUL in the FIFO; the byte is still delivered. */
    M.lsr_err = FBRL_8250_LSR_FE | FBRL_8250_LSR_BI;
    model_rx(&M, "\0", 1);
    fbrl_uart_8250_isr(&B);
    c = counters();
    assert_int_equal(c.overruns, 1);
    assert_int_equal(c.parity_errors, 1);
    assert_int_equal(c.framing_errors, 2);
    assert_int_equal(read_all(buf, sizeof buf), 1);
    assert_int_equal(buf[0], 0);
    assert_int_equal(M.eois, 4);
}

/* The handler reads IIR again after each cause and handles whatever is pending now:
 * here more data arrives while the first burst is handled, and then THRE. */
static void inject_on_second(model *m, unsigned nth)
{
    if (nth == 2) {
        model_rx(m, "def", 3);
        model_tx_done(m);
    }
}

static void test_isr_pending_again(void **state)
{
    uint8_t buf[16];
    size_t written = 0;
    fbrl_uart_8250_stats st;
    (void)state;
    open_port(FBRL_UART_8250_16550, 14, sizeof rx_mem);
    assert_int_equal(fbrl_uart_write(&U, "0123456789ABCDEFGHIJ", 20, &written, 0), FBRL_OK);
    assert_int_equal(M.tx_n, 16);
    model_rx(&M, "abc", 3);
    M.iir_reads = 0;
    M.eois = 0;
    M.on_iir = inject_on_second;
    fbrl_uart_8250_isr(&B);
    M.on_iir = NULL;
    assert_int_equal(M.eois, 1); /* one interrupt, one EOI */
    assert_true(M.iir_reads >= 3);
    assert_int_equal(read_all(buf, sizeof buf), 6);
    assert_memory_equal(buf, "abcdef", 6);
    assert_int_equal(M.tx_n, 20);
    assert_memory_equal(M.tx, "0123456789ABCDEFGHIJ", 20);
    assert_int_equal(fbrl_uart_8250_get_stats(&B, &st), FBRL_OK);
    assert_true(st.passes >= 3);
}

/* A cause that never clears: the handler gives up after the pass bound, pulses IER
 * so an edge-triggered 8259 sees a new edge, and still sends the EOI. */
static void test_isr_pass_limit(void **state)
{
    fbrl_uart_8250_stats st;
    size_t mark;
    (void)state;
    open_port(FBRL_UART_8250_16550, 14, sizeof rx_mem);
    M.ier |= FBRL_8250_IER_MSI;
    B.ier |= FBRL_8250_IER_MSI;
    M.msr_delta = M.msr_stuck = 1;
    mark = log_mark();
    fbrl_uart_8250_isr(&B);
    assert_int_equal(fbrl_uart_8250_get_stats(&B, &st), FBRL_OK);
    assert_int_equal(st.passes, FBRL_UART_8250_MAX_PASSES);
    assert_int_equal(st.pass_limit, 1);
    {
        const access want[] = {{'w', BASE + 1, 0x00}, {'w', BASE + 1, 0x0D}, {'w', FBRL_8259_CMD, 0x20}};
        expect_log(M.nlog - 3, want, 3);
    }
    assert_true(M.nlog - mark < 3 * FBRL_UART_8250_MAX_PASSES + 8);
}

static void test_isr_spurious(void **state)
{
    fbrl_uart_8250_stats st;
    size_t mark;
    (void)state;
    open_port(FBRL_UART_8250_16550, 14, sizeof rx_mem);
    mark = log_mark();
    fbrl_uart_8250_isr(&B);
    {
        const access want[] = {{'r', BASE + 2, 0xC1}, {'w', FBRL_8259_CMD, 0x20}};
        expect_log(mark, want, 2);
    }
    assert_int_equal(fbrl_uart_8250_get_stats(&B, &st), FBRL_OK);
    assert_int_equal(st.spurious, 1);
    fbrl_uart_8250_isr(NULL); /* harmless */
}

/* Headroom: with the core's ring nearly full the handler stops reading RBR and masks
 * receive interrupts; the bytes wait in the UART, none is lost, and the main line's
 * service() resumes reception once it has made room. */
static void test_isr_rx_headroom(void **state)
{
    char in[200];
    uint8_t out[256];
    size_t i, got = 0;
    fbrl_uart_8250_stats st;
    (void)state;
    for (i = 0; i < sizeof in; i++)
        in[i] = (char)('a' + i % 26);
    open_port(FBRL_UART_8250_16550, 14, 64);
    model_rx(&M, in, sizeof in);
    fbrl_uart_8250_isr(&B);
    assert_false(M.ier & FBRL_8250_IER_RDI);
    assert_true(M.rx_n > 0);
    assert_int_equal(M.rx_n + fbrl_uart_rx_available(&U), sizeof in);
    assert_true(fbrl_uart_rx_available(&U) > 64 - FBRL_UART_8250_RX_HEADROOM);
    while (got < sizeof in) {
        size_t n = read_all(out + got, sizeof out - got);
        got += n;
        if (n == 0)
            assert_int_equal(fbrl_uart_8250_ops.service(&B, 0), FBRL_OK);
        if (M.rx_n && (M.ier & FBRL_8250_IER_RDI))
            fbrl_uart_8250_isr(&B);
    }
    assert_memory_equal(out, in, sizeof in);
    assert_int_equal(counters().overruns, 0);
    assert_int_equal(fbrl_uart_8250_get_stats(&B, &st), FBRL_OK);
    assert_true(st.throttles >= 1);
    assert_true(M.ier & FBRL_8250_IER_RDI);
}

/* A ring smaller than the headroom still receives: the rule scales with the ring. */
static void test_isr_rx_tiny_ring(void **state)
{
    char in[40];
    uint8_t out[64];
    size_t i, got = 0;
    unsigned rounds = 0;
    (void)state;
    for (i = 0; i < sizeof in; i++)
        in[i] = (char)('A' + i % 26);
    open_port(FBRL_UART_8250_16550, 1, 8);
    model_rx(&M, in, sizeof in);
    while (got < sizeof in) {
        fbrl_uart_8250_isr(&B);
        got += read_all(out + got, sizeof out - got);
        assert_int_equal(fbrl_uart_8250_ops.service(&B, 0), FBRL_OK);
        assert_true(++rounds < 100);
    }
    assert_memory_equal(out, in, sizeof in);
    assert_int_equal(counters().overruns, 0);
}

/* service() sleeps (idle hook) until the handler moved something, or the timeout. */
static void irq_during_idle(model *m)
{
    if (m->now == 3000) {
        model_rx(m, "x", 1);
        fbrl_uart_8250_isr(&B);
    }
}

static void test_service_waits_for_interrupt(void **state)
{
    uint8_t c;
    (void)state;
    open_port(FBRL_UART_8250_16550, 14, sizeof rx_mem);
    M.now = 0;
    assert_int_equal(fbrl_uart_8250_ops.service(&B, 10000), FBRL_OK);
    assert_int_equal(M.now, 10000); /* nothing happened: slept to the deadline */
    M.now = 0;
    M.on_idle = irq_during_idle;
    assert_int_equal(fbrl_uart_8250_ops.service(&B, 100000), FBRL_OK);
    assert_int_equal(M.now, 3000); /* woke at the interrupt */
    M.on_idle = NULL;
    assert_int_equal(read_all(&c, 1), 1);
    assert_int_equal(c, 'x');
    /* Something happened before the call: no sleep at all. */
    model_rx(&M, "y", 1);
    fbrl_uart_8250_isr(&B);
    M.now = 0;
    assert_int_equal(fbrl_uart_8250_ops.service(&B, 100000), FBRL_OK);
    assert_int_equal(M.now, 0);
    assert_int_equal(fbrl_uart_8250_ops.now_us(&B), 0);
    assert_int_equal(M.saved_depth, 0);
}

/* The whole path with flow control: the core's XOFF goes out through the handler when
 * the receive ring fills, and a peer's XOFF/XON stops and restarts the transmitter. */
static void test_xon_xoff_through_isr(void **state)
{
    char in[48];
    uint8_t out[64];
    size_t i, written = 0;
    (void)state;
    for (i = 0; i < sizeof in; i++)
        in[i] = 'q';
    open_port(FBRL_UART_8250_16550, 14, 64);
    model_rx(&M, in, sizeof in);
    fbrl_uart_8250_isr(&B);
    assert_true(counters().xoff_sent >= 1);
    assert_true(M.tx_n >= 1);
    assert_int_equal(M.tx[M.tx_n - 1], FBRL_XOFF);
    (void)read_all(out, sizeof out);

    /* Peer says XOFF: data waits in the core, not in THR. */
    open_port(FBRL_UART_8250_16550, 14, sizeof rx_mem);
    model_rx(&M, "\x13", 1);
    fbrl_uart_8250_isr(&B);
    assert_int_equal(counters().xoff_received, 1);
    assert_int_equal(fbrl_uart_write(&U, "held", 4, &written, 0), FBRL_OK);
    model_tx_done(&M);
    fbrl_uart_8250_isr(&B);
    assert_int_equal(M.tx_n, 0);
    /* XON: the handler restarts the idle transmitter itself. */
    model_rx(&M, "\x11", 1);
    fbrl_uart_8250_isr(&B);
    assert_int_equal(M.tx_n, 4);
    assert_memory_equal(M.tx, "held", 4);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_configure_every_setting),
        cmocka_unit_test(test_configure_datasheet_values),
        cmocka_unit_test(test_configure_unsupported),
        cmocka_unit_test(test_configure_8250_no_fifo),
        cmocka_unit_test(test_probe),
        cmocka_unit_test(test_init_arguments),
        cmocka_unit_test(test_attach_and_close),
        cmocka_unit_test(test_isr_receive),
        cmocka_unit_test(test_isr_transmit_16550),
        cmocka_unit_test(test_isr_transmit_8250),
        cmocka_unit_test(test_isr_line_status),
        cmocka_unit_test(test_isr_pending_again),
        cmocka_unit_test(test_isr_pass_limit),
        cmocka_unit_test(test_isr_spurious),
        cmocka_unit_test(test_isr_rx_headroom),
        cmocka_unit_test(test_isr_rx_tiny_ring),
        cmocka_unit_test(test_service_waits_for_interrupt),
        cmocka_unit_test(test_xon_xoff_through_isr),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
