/* SPDX-License-Identifier: MIT */
/* main.c - the FBRL firmware: the whole language on the board, with the console on
 * UART0 (the Forth prompt) and the controller on UART1 (RAPL through the link).
 *
 * Everything is static: the engine's memory (dictionary, stacks), the glossary's data
 * file buffers, the link and the UART rings. Nothing is allocated. */
#include <stdio.h>
#include <string.h>

#include "board.h"
#include "fbrl/cell_words.h"
#include "fbrl/glossary.h"
#include "fbrl/link.h"
#include "fbrl/robot.h"
#include "fbrl/uart.h"
#include "fbrl/uart_pl011.h"
#include "fbrl/vm.h"
#include "fbrl/vmx.h"

#ifndef FW_VERSION
#define FW_VERSION "unknown"
#endif

/* Memory (docs/firmware.md has the budget). */
#define FW_DICT_BYTES     (16u * 1024u) /* dictionary free for programs, at least */
#define FW_DATA_STACK     128u          /* cells */
#define FW_RETURN_STACK   128u          /* cells */
#define FW_FLOAT_STACK    32u           /* floats */
#define FW_FILE_BUFFER    2048u         /* records of the open data files */
#define FW_CON_RX         256u
#define FW_CON_TX         256u
#define FW_ROBOT_RX       512u
#define FW_ROBOT_TX       256u
#define FW_LINE_MAX       256u /* longest console line */
#define FW_CONSOLE_BAUD   115200u
#define FW_CONNECT_TRIES  5u /* the controller may still be starting when we boot */
#define FW_WRITE_WAIT_MS  1000u
#define FW_KEY_POLL_MS    1000u
#define FW_SLEEP_SLICE_US 1000u /* one clock tick: MS checks for Ctrl-C this often */
#define FW_CHAR_CTRL_C    0x03
#define FW_CHAR_BS        0x08
#define FW_CHAR_DEL       0x7F

/* The VM's memory: its own structures, stacks and buffers, ALLOCATE's heap, the headers
 * of the C words (the primitives' are in flash: FBRL_ROM_PRIMS) and FW_DICT_BYTES for
 * programs (checked at boot against fbrl_vm_size_for()). All the RAM the rest leaves. */
#ifndef FW_VM_BYTES
#define FW_VM_BYTES (42u * 1024u + 512u)
#endif

static unsigned char vm_mem[FW_VM_BYTES] __attribute__((aligned(16)));
static unsigned char file_mem[FW_FILE_BUFFER] __attribute__((aligned(8)));
static uint8_t con_rx[FW_CON_RX], con_tx[FW_CON_TX], robot_rx[FW_ROBOT_RX], robot_tx[FW_ROBOT_TX];

static fbrl_uart_pl011 con_hw, robot_hw;
static fbrl_uart con, robot_line;
static fbrl_link link;
static fbrl_link_config link_cfg;
static fbrl_glossary glossary;
static fbrl_robot robot;
static fbrl_cell_words cell; /* the work cell and the guard on every motion (docs/workcell.md) */
static fbrl_vm *vm;
static char line[FW_LINE_MAX];

/* ---- the console ---- */

static void con_put(const char *s, size_t n)
{
    size_t w;
    while (n > 0) {
        if (fbrl_uart_write(&con, s, n, &w, FW_WRITE_WAIT_MS) != FBRL_OK && w == 0)
            return; /* nobody reads the console: drop rather than hang the robot */
        s += w;
        n -= w;
    }
}

/* Output as a terminal wants it: every LF as CR LF. */
static void con_write(void *user, const char *s, size_t n)
{
    size_t start = 0;
    (void)user;
    for (size_t k = 0; k < n; k++) {
        if (s[k] == '\n') {
            con_put(s + start, k - start);
            con_put("\r\n", 2);
            start = k + 1;
        }
    }
    con_put(s + start, n - start);
}

static void con_puts(const char *s) { con_write(NULL, s, strlen(s)); }

/* Next byte from the console; waits as long as it takes (a UART has no end of input). */
static int con_key(void *user)
{
    uint8_t c;
    size_t got = 0;
    (void)user;
    while (got == 0)
        (void)fbrl_uart_read(&con, &c, 1, &got, FW_KEY_POLL_MS);
    return c;
}

static int con_key_ready(void *user)
{
    (void)user;
    return fbrl_uart_rx_available(&con) > 0;
}

/* One line with echo and backspace; CR, LF or CR LF ends it. Ctrl-C drops it and asks
 * the engine to stop (FBRL_EEOF, as the host interface says). */
static int last_was_cr;
static fbrl_status con_read_line(void *user, const char *prompt, char *buf, size_t cap, size_t *len)
{
    size_t n = 0;
    (void)user;
    if (prompt)
        con_puts(prompt);
    for (;;) {
        int c = con_key(NULL);
        if (c == '\n' && last_was_cr) {
            last_was_cr = 0;
            continue;
        }
        last_was_cr = c == '\r';
        if (c == '\r' || c == '\n')
            break;
        if (c == FW_CHAR_CTRL_C) {
            con_puts("^C\n");
            fbrl_vm_interrupt(vm);
            return FBRL_EEOF;
        }
        if (c == FW_CHAR_BS || c == FW_CHAR_DEL) {
            if (n > 0) {
                n--;
                con_put("\b \b", 3);
            }
            continue;
        }
        if (n + 1 < cap && (unsigned char)c >= ' ') {
            buf[n++] = (char)c;
            con_put(&buf[n - 1], 1);
        }
    }
    con_put("\r\n", 2);
    buf[n] = '\0';
    *len = n;
    return FBRL_OK;
}

/* Ctrl-C while a word runs: every tick looks at the next console byte without taking it
 * (the line reader takes it later, and then the request is dropped at the next line).
 * A Ctrl-C typed behind other unread input is seen when that input has been read. */
static void on_tick(void)
{
    uint8_t c;
    size_t got = 0;
    if (vm && fbrl_ring_peek(&con.rx, &c, 1, &got) == FBRL_OK && got == 1 && c == FW_CHAR_CTRL_C)
        fbrl_vm_interrupt(vm);
}

/* ---- time ---- */

static uint64_t host_now_us(void *user)
{
    (void)user;
    return board_now_us();
}

/* MS and the timed waits: tick by tick, so that a Ctrl-C (on_tick) ends them early. */
static void host_sleep_ms(void *user, uint32_t ms)
{
    uint64_t end = board_now_us() + (uint64_t)ms * 1000u, now;
    (void)user;
    while ((now = board_now_us()) < end && !fbrl_vm_interrupt_pending(vm))
        board_sleep_until(end - now > FW_SLEEP_SLICE_US ? now + FW_SLEEP_SLICE_US : end);
}

/* The board has no calendar: TIME&DATE counts from 2000-01-01 00:00:00 at reset. */
static void host_time_date(void *user, int out[6])
{
    uint32_t s = (uint32_t)(board_now_us() / 1000000u);
    (void)user;
    out[0] = (int)(s % 60u);
    out[1] = (int)(s / 60u % 60u);
    out[2] = (int)(s / 3600u % 24u);
    out[3] = 1 + (int)(s / 86400u % 28u);
    out[4] = 1;
    out[5] = 2000;
}

/* ---- the controller ---- */

static fbrl_status open_uart(fbrl_uart_pl011 *hw, fbrl_uart *u, unsigned n, uint8_t *rx, size_t rxn,
                             uint8_t *tx, size_t txn, const fbrl_uart_config *cfg)
{
    fbrl_status st = fbrl_uart_pl011_init(hw, board_uart_io(n), board_uart_clock_hz());
    if (st == FBRL_OK)
        st = fbrl_uart_init(u, &fbrl_uart_pl011_ops, hw, rx, rxn, tx, txn, cfg);
    if (st == FBRL_OK)
        st = fbrl_uart_pl011_attach(hw, u);
    if (st == FBRL_OK)
        board_uart_irq(n, hw);
    return st;
}

static fbrl_status connect(void)
{
    fbrl_status st = FBRL_ETIMEOUT;
    for (unsigned k = 0; k < FW_CONNECT_TRIES && st != FBRL_OK; k++)
        st = fbrl_link_connect(&link);
    return st;
}

/* RECONNECT and the robot words after the controller went away: the line stays, the
 * link greets the controller again. */
static fbrl_status relink(void *ctx, fbrl_robot *r)
{
    fbrl_status st;
    (void)ctx;
    st = connect();
    return st == FBRL_OK ? fbrl_robot_set_link(r, &link) : st;
}

/* XONXOFF ( flag -- ): flow control on the controller's line, as fbrlmon's --flow: true
 * XON/XOFF (the default, the thesis's), false none (a line whose noise could fake an
 * XOFF and hold the output until an XON that never comes). The link learns the line's
 * setting when it starts (without flow control its probes carry an XON), so it starts
 * again and greets the controller, as RECONNECT does. */
static fbrl_status w_xonxoff(fbrl_vm *v, void *arg, const void *word)
{
    fbrl_vmx_val val[1];
    fbrl_uart_config c;
    fbrl_status st;
    (void)arg;
    if ((st = fbrl_vmx_check(v, word, val)) != FBRL_OK)
        return st;
    fbrl_cell flag = val[0].i;
    if ((st = fbrl_uart_get_config(&robot_line, &c)) != FBRL_OK)
        return st;
    c.flow = flag ? FBRL_FLOW_XONXOFF : FBRL_FLOW_NONE;
    if ((st = fbrl_uart_configure(&robot_line, &c)) != FBRL_OK ||
        (st = fbrl_link_init(&link, &robot_line, &link_cfg)) != FBRL_OK || (st = connect()) != FBRL_OK)
        return st;
    return fbrl_robot_set_link(&robot, &link);
}

/* FW-STATS ( -- ), defined in Forth over (FW-STATS): what the board's memory and lines have seen, for a person at the
 * console and for the tests: stack high-water mark, dictionary free, each UART's
 * counters. */
static void stats_line(const char *name, fbrl_uart *u)
{
    fbrl_uart_counters c;
    char msg[160];
    if (fbrl_uart_get_counters(u, &c) != FBRL_OK)
        return;
    snprintf(msg, sizeof msg,
             "%s: rx %lu tx %lu overruns %lu framing %lu parity %lu xoff-in %lu xoff-out %lu\n", name,
             (unsigned long)c.rx_bytes, (unsigned long)c.tx_bytes, (unsigned long)c.overruns,
             (unsigned long)c.framing_errors, (unsigned long)c.parity_errors, (unsigned long)c.xoff_received,
             (unsigned long)c.xoff_sent);
    con_puts(msg);
}

static fbrl_status w_fw_stats(fbrl_vm *v, void *arg, const void *word) /* (FW-STATS) ( unused -- ) */
{
    fbrl_vmx_val val[1];
    char msg[96];
    fbrl_status st;
    (void)arg;
    if ((st = fbrl_vmx_check(v, word, val)) != FBRL_OK)
        return st;
    fbrl_cell unused = val[0].i;
    snprintf(msg, sizeof msg, "stack: %lu of %lu bytes used; dictionary: %ld bytes free\n",
             (unsigned long)board_stack_used(), (unsigned long)board_stack_size(), (long)unused);
    con_puts(msg);
    stats_line("console", &con);
    stats_line("controller", &robot_line);
    return FBRL_OK;
}

static const fbrl_vmx_reg fw_words[] = {
    {"XONXOFF", w_xonxoff, "I", 0, 0, 0,
     FBRL_DOC("( flag -- )", "flow control on the controller's line: XON/XOFF (true, the default) or none")},
    {"(FW-STATS)", w_fw_stats, "I", 0, 0, 0, FBRL_DOC("( u -- )", "FW-STATS with UNUSED given")},
};

/* ---- errors, as fbrlmon prints them: "error: MESSAGE [in WORD]" ---- */

static void report(fbrl_status st)
{
    const fbrl_vm_error *e = fbrl_vm_last_error(vm);
    char num[16];
    con_puts("error: ");
    con_puts(e && e->message[0] ? e->message : fbrl_status_str(st));
    if (e && (e->throw_code > 0 || e->throw_code < -4095)) {
        snprintf(num, sizeof num, " %d", e->throw_code);
        con_puts(num);
    }
    if (e && e->word[0] && e->throw_code != -39) {
        con_puts(e->throw_code == -13 ? " " : " in ");
        con_puts(e->word);
    }
    con_puts("\n");
}

static void fail(const char *what, fbrl_status st)
{
    con_puts(what);
    con_puts(": ");
    con_puts(fbrl_status_str(st));
    con_puts("\n");
}

int main(void)
{
    fbrl_uart_config con_cfg = FBRL_UART_CONFIG_DEFAULT, robot_cfg = FBRL_UART_CONFIG_DEFAULT;
    fbrl_vm_config cfg;
    fbrl_status st;
    char msg[96];
    fbrl_cell unused = 0;

    board_init();
    con_cfg.baud = FW_CONSOLE_BAUD;
    if (open_uart(&con_hw, &con, BOARD_UART_CONSOLE, con_rx, sizeof con_rx, con_tx, sizeof con_tx,
                  &con_cfg) != FBRL_OK)
        board_reset();
    st = open_uart(&robot_hw, &robot_line, BOARD_UART_ROBOT, robot_rx, sizeof robot_rx, robot_tx,
                   sizeof robot_tx, &robot_cfg);
    board_irq_on();
    con_puts("FBRL firmware " FW_VERSION "\n");
    if (st != FBRL_OK)
        fail("controller line", st);

    memset(&cfg, 0, sizeof cfg);
    cfg.data_stack_cells = FW_DATA_STACK;
    cfg.return_stack_cells = FW_RETURN_STACK;
    cfg.float_stack_cells = FW_FLOAT_STACK;
    cfg.mem = vm_mem;
    cfg.mem_size = sizeof vm_mem;
    cfg.mem_zeroed = 1; /* .bss */
    cfg.host.write = con_write;
    cfg.host.key = con_key;
    cfg.host.key_ready = con_key_ready;
    cfg.host.now_us = host_now_us;
    cfg.host.sleep_ms = host_sleep_ms;
    cfg.host.time_date = host_time_date;
    cfg.host.read_line = con_read_line;
    /* The dictionary promised: FW_DICT_BYTES free after every built-in word. */
    if (fbrl_vm_size_for(&cfg, FW_DICT_BYTES) > sizeof vm_mem) {
        snprintf(msg, sizeof msg, "engine: needs %lu bytes, has %lu\n",
                 (unsigned long)fbrl_vm_size_for(&cfg, FW_DICT_BYTES), (unsigned long)sizeof vm_mem);
        con_puts(msg);
    }
    st = fbrl_vm_create(&vm, &cfg);
    if (st == FBRL_OK)
        st = fbrl_glossary_install(vm, &glossary);
    if (st == FBRL_OK)
        st = fbrl_glossary_set_file_storage(&glossary, file_mem, sizeof file_mem);
    if (st == FBRL_OK) {
        fbrl_link_config_init(&link_cfg);
        st = fbrl_link_init(&link, &robot_line, &link_cfg);
    }
    if (st == FBRL_OK)
        st = fbrl_robot_install(vm, &robot, &link, &glossary);
    if (st == FBRL_OK)
        st = fbrl_robot_set_relink(&robot, relink, NULL);
    if (st == FBRL_OK) /* CELL-BOX ...: every motion is checked against the cell before it is sent */
        st = fbrl_cell_install(vm, &cell, &robot, &glossary);
    if (st == FBRL_OK)
        st = fbrl_vmx_define_table(vm, fw_words, sizeof fw_words / sizeof fw_words[0], NULL);
    if (st == FBRL_OK) {
        static const char fw_stats[] = ": FW-STATS ( -- ) UNUSED (FW-STATS) ;";
        st = fbrl_vm_eval(vm, fw_stats, sizeof fw_stats - 1);
    }
    if (st != FBRL_OK) {
        fail("engine", st);
        board_reset();
    }
    board_on_tick(on_tick);
    st = connect();
    if (st != FBRL_OK)
        fail("controller (the robot words try again when used)", st);
    if (fbrl_vm_eval(vm, "UNUSED", 6) == FBRL_OK && fbrl_vm_pop(vm, &unused) == FBRL_OK) {
        snprintf(msg, sizeof msg, "dictionary: %ld bytes free; the controller on UART1\n", (long)unused);
        con_puts(msg);
    }

    for (;;) {
        size_t n;
        if (con_read_line(NULL, NULL, line, sizeof line, &n) != FBRL_OK) {
            (void)fbrl_vmx_take_interrupt(vm);
            continue;
        }
        st = fbrl_vm_eval(vm, line, n);
        if (st != FBRL_OK)
            report(st);
        else
            con_puts(fbrl_vm_compiling(vm) ? " compiled\n" : " ok\n");
        if (fbrl_vm_bye(vm)) {
            (void)fbrl_glossary_finish(&glossary);
            (void)fbrl_uart_drain(&con, FW_WRITE_WAIT_MS);
            board_reset();
        }
    }
}
