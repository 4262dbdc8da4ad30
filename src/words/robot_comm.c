/* SPDX-License-Identifier: MIT */
/* robot_comm.c - thesis I-4: the communications words on the uart API.
 *
 * The thesis programmed a PC's 8250 through BIOS INT 14h and revectored its
 * interrupts. Here the port is the link's fbrl_uart (a termios tty or pty, TCP, or the
 * 8250 backend), which already runs in the background with XON/XOFF; the setup words
 * collect settings and SETUPUART applies them with fbrl_uart_configure(). EMIT-COM and
 * friends write raw bytes past the link (no echo check); RESET-COMM discards what came
 * in and brings the controller's line back to a known state. The DOS-only words are not
 * bound (docs/glossary.md says why). */
#include <stdio.h>
#include <string.h>

#include "robot_internal.h"

/* How long the raw words wait for room to send, or for a byte to arrive. */
#define COMM_TIMEOUT_MS 1000u

static fbrl_status uart_of(fbrl_robot *r, fbrl_uart **u)
{
    fbrl_status st = rb_online(r);
    if (st != FBRL_OK)
        return st;
    *u = r->link->u;
    return FBRL_OK;
}

static fbrl_status check_port(fbrl_robot *r, const rb_word *w, fbrl_cell port)
{
    if (port == 1)
        return FBRL_OK;
    char msg[96];
    snprintf(msg, sizeof msg, "%s: port %ld: only port 1 (the controller's line) exists here", w->name,
             (long)port);
    return rb_fail(r, FBRL_THROW_BAD_NUMBER, msg);
}

static fbrl_status bad_setting(fbrl_robot *r, const rb_word *w, const char *what)
{
    char msg[96];
    snprintf(msg, sizeof msg, "%s: %s", w->name, what);
    return rb_fail(r, FBRL_THROW_BAD_NUMBER, msg);
}

static fbrl_status set_word_length(fbrl_robot *r, const rb_word *w, fbrl_cell n)
{
    if (n < 5 || n > 8)
        return bad_setting(r, w, "word length 5..8 bits");
    r->comm.data_bits = (uint8_t)n;
    return FBRL_OK;
}

static fbrl_status set_stop_bits(fbrl_robot *r, const rb_word *w, fbrl_cell n)
{
    if (n < 1 || n > 2)
        return bad_setting(r, w, "1 or 2 stop bits");
    r->comm.stop_bits = (uint8_t)n;
    return FBRL_OK;
}

static fbrl_status set_parity(fbrl_robot *r, const rb_word *w, fbrl_cell c)
{
    switch (c) {
    case 'N':
    case 'n': r->comm.parity = FBRL_PARITY_NONE; return FBRL_OK;
    case 'E':
    case 'e': r->comm.parity = FBRL_PARITY_EVEN; return FBRL_OK;
    case 'O':
    case 'o': r->comm.parity = FBRL_PARITY_ODD; return FBRL_OK;
    default: return bad_setting(r, w, "parity is the character N, E or O (ASC E)");
    }
}

static fbrl_status set_baud(fbrl_robot *r, const rb_word *w, fbrl_cell b)
{
    if (b < 50 || b > 4000000)
        return bad_setting(r, w, "baud rate 50..4000000");
    r->comm.baud = (uint32_t)b;
    return FBRL_OK;
}

static fbrl_status w_setting(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    switch (w->arg) {
    case 0: return set_word_length(r, w, v[0].i);
    case 1: return set_stop_bits(r, w, v[0].i);
    case 2: return set_parity(r, w, v[0].i);
    default: return set_baud(r, w, v[0].i);
    }
}

/* COMMSET ( baud parity stopbits wordlen -- ): all four; nothing changes on an error */
static fbrl_status commset(fbrl_robot *r, const rb_word *w, rb_val *v)
{
    fbrl_uart_config keep = r->comm;
    fbrl_status st = set_baud(r, w, v[0].i);
    if (st == FBRL_OK)
        st = set_parity(r, w, v[1].i);
    if (st == FBRL_OK)
        st = set_stop_bits(r, w, v[2].i);
    if (st == FBRL_OK)
        st = set_word_length(r, w, v[3].i);
    if (st != FBRL_OK)
        r->comm = keep;
    return st;
}

static fbrl_status apply(fbrl_robot *r, const rb_word *w)
{
    fbrl_uart *u;
    fbrl_status st = uart_of(r, &u);
    if (st != FBRL_OK)
        return st;
    /* bytes already queued leave at the old settings */
    fbrl_uart_drain(u, COMM_TIMEOUT_MS);
    st = fbrl_uart_configure(u, &r->comm);
    if (st != FBRL_OK) {
        fbrl_uart_get_config(u, &r->comm);
        return rb_fail_st(r, w, st, "port settings");
    }
    return FBRL_OK;
}

/* SETUPUART ( comm-port -- ) */
static fbrl_status w_setupuart(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_status st = check_port(r, w, v[0].i);
    return st == FBRL_OK ? apply(r, w) : st;
}

static fbrl_status w_commset(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    return commset(r, w, v);
}

/* COMM-SETUP ( pt# bd prty stop-bit wrdlen -- ) */
static fbrl_status w_comm_setup(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_status st = check_port(r, w, v[0].i);
    if (st == FBRL_OK)
        st = commset(r, w, v + 1);
    return st == FBRL_OK ? apply(r, w) : st;
}

/* Everything the link has typed so far: if it changed, the link used the line. */
static uint64_t link_mark(const fbrl_link *l) { return l->stats.attempts + l->stats.probes; }

/* Before raw bytes: unless they continue our own unfinished raw line, erase what the link
 * may have left on the controller's line (a probe leaves marker characters there), so a
 * CR in the raw text runs only the raw text. */
static fbrl_status raw_begin(fbrl_robot *r)
{
    if (!r->link || (r->raw_open && r->raw_link_mark == link_mark(r->link)))
        return FBRL_OK;
    r->raw_len = 0;
    return fbrl_link_clear_line(r->link);
}

/* The raw bytes as the controller's line editor takes them (BS and DEL erase): each line
 * they end (CR or LF) runs, and passes the motion guard's gate first (rb_link_gate): while
 * the guard is on, one that can move the arm is refused, and none of the bytes is sent (the
 * guard cannot follow a motion typed byte by byte). *len gets the unfinished line's length
 * (in line[]) once they are sent. */
static fbrl_status raw_gate(fbrl_robot *r, const rb_word *w, const uint8_t *p, size_t n, char *line, size_t *len)
{
    size_t k = r->raw_open ? r->raw_len : 0;
    memcpy(line, (const char *)r->tib + FBRL_ROBOT_TIB, k);
    for (size_t i = 0; i < n; i++) {
        if (p[i] == '\r' || p[i] == '\n') {
            if (k > 0 && rb_link_gate(r, line, k, 0) != FBRL_OK) {
                char msg[220];
                /* what of it the controller has on its line never runs: erased */
                r->raw_open = 0;
                r->raw_len = 0;
                (void)fbrl_link_clear_line(r->link);
                snprintf(msg, sizeof msg,
                         "%s: %.*s would move the arm unchecked by the guard (RAPL checks it); erased, "
                         "nothing ran",
                         w->name, (int)k, line);
                return rb_fail(r, FBRL_ROBOT_THROW_REFUSED, msg);
            }
            k = 0;
        } else if (p[i] == 0x08 || p[i] == 0x7f) {
            k -= k > 0;
        } else if (k < FBRL_LINK_LINE_MAX) {
            line[k++] = (char)p[i];
        }
    }
    *len = k;
    return FBRL_OK;
}

/* After raw bytes: a CR or LF ends the raw line (the controller ran it). */
static void raw_end(fbrl_robot *r, const void *p, size_t n)
{
    if (!r->link || n == 0)
        return;
    uint8_t last = ((const uint8_t *)p)[n - 1];
    r->raw_open = last != '\r' && last != '\n';
    r->raw_link_mark = link_mark(r->link);
}

/* Raw bytes to the port (no echo verification). */
static fbrl_status send_raw(fbrl_robot *r, const rb_word *w, const void *p, size_t n)
{
    fbrl_uart *u;
    fbrl_status st = uart_of(r, &u);
    if (st != FBRL_OK)
        return st;
    fbrl_uart_config c;
    if (fbrl_uart_get_config(u, &c) == FBRL_OK && c.flow == FBRL_FLOW_XONXOFF)
        for (size_t k = 0; k < n; k++)
            if (((const uint8_t *)p)[k] == FBRL_XON || ((const uint8_t *)p)[k] == FBRL_XOFF)
                return rb_fail(r, FBRL_THROW_BAD_NUMBER,
                               "XON/XOFF bytes cannot be sent as data while XON/XOFF flow control is on");
    if ((st = raw_begin(r)) != FBRL_OK)
        return rb_fail_st(r, w, st, "port");
    char line[FBRL_LINK_LINE_MAX + 1];
    size_t len = 0;
    if ((st = raw_gate(r, w, p, n, line, &len)) != FBRL_OK)
        return st;
    st = fbrl_uart_write(u, p, n, NULL, COMM_TIMEOUT_MS);
    if (st == FBRL_OK) {
        raw_end(r, p, n);
        memcpy((char *)r->tib + FBRL_ROBOT_TIB, line, len);
        r->raw_len = len;
    }
    if (st == FBRL_OK && w->arg)
        st = fbrl_uart_drain(u, COMM_TIMEOUT_MS);
    return st == FBRL_OK ? FBRL_OK : rb_fail_st(r, w, st, "port");
}

/* EMIT-COM ( char -- ), DIRECT-WRITE-COM ( c -- ) */
static fbrl_status w_emit_com(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    if (v[0].i < 0 || v[0].i > 255)
        return rb_fail(r, FBRL_THROW_BAD_NUMBER, "EMIT-COM: a byte 0..255");
    uint8_t b = (uint8_t)v[0].i;
    return send_raw(r, w, &b, 1);
}

/* TYPE-COM ( chrs addr -- ) - the thesis's order: count first */
static fbrl_status w_type_com(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    if (v[0].i < 0 || (v[0].i > 0 && !fbrl_vm_addr(r->vm, v[1].i, (size_t)v[0].i)))
        return rb_fail(r, FBRL_THROW_BAD_ADDRESS, NULL);
    return send_raw(r, w, (const void *)v[1].i, (size_t)v[0].i);
}

/* .-COM ( n -- ) */
static fbrl_status w_dot_com(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    char buf[32];
    int n = snprintf(buf, sizeof buf, "%ld", (long)v[0].i);
    return send_raw(r, w, buf, (size_t)n);
}

/* F.-COM ( F: r -- ): as RAPL reads reals (four decimals) */
static fbrl_status w_fdot_com(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    char buf[32];
    size_t n;
    fbrl_status st = fbrl_rapl_format_real(buf, sizeof buf, &n, v[0].f);
    if (st != FBRL_OK)
        return rb_fail_st(r, w, st, NULL);
    return send_raw(r, w, buf, n);
}

/* GET-COM ( -- char ): the next received byte, -1 if none came within a second */
static fbrl_status w_get_com(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_uart *u;
    uint8_t b;
    size_t got = 0;
    (void)v;
    fbrl_status st = uart_of(r, &u);
    if (st != FBRL_OK)
        return st;
    st = fbrl_uart_read(u, &b, 1, &got, COMM_TIMEOUT_MS);
    if (st != FBRL_OK && st != FBRL_ETIMEOUT)
        return rb_fail_st(r, w, st, "port");
    return fbrl_vm_push(r->vm, got ? (fbrl_cell)b : -1) == FBRL_OK
               ? FBRL_OK
               : rb_fail(r, FBRL_THROW_STACK_OVERFLOW, NULL);
}

/* Bring the link back in step after raw output: let the controller finish answering,
 * discard it all (at most 2 s: a stream started raw never goes quiet, the connect step's
 * probe ends it), then erase the controller's line and send NOHELP. */
static fbrl_status resync_keep(fbrl_robot *r, char *keep, size_t cap, size_t *kept)
{
    uint8_t buf[64];
    for (int quiet = 0, rounds = 0; quiet < 3 && rounds < 40; rounds++) {
        size_t got = 0;
        fbrl_status st = fbrl_uart_read(r->link->u, buf, sizeof buf, &got, 50);
        if (st != FBRL_OK && st != FBRL_ETIMEOUT)
            return st;
        quiet = got ? 0 : quiet + 1;
        for (size_t k = 0; keep && k < got && *kept + 1 < cap; k++)
            keep[(*kept)++] = (char)buf[k];
    }
    if (keep)
        keep[*kept] = '\0';
    return fbrl_link_connect(r->link);
}

fbrl_status rb_resync(fbrl_robot *r) { return resync_keep(r, NULL, 0, NULL); }

/* RESET-COMM ( port -- ): drop what was received and not read, and resynchronise. */
static fbrl_status w_reset_comm(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_uart *u;
    fbrl_status st = check_port(r, w, v[0].i);
    if (st == FBRL_OK)
        st = uart_of(r, &u);
    if (st != FBRL_OK)
        return st;
    return rb_link_result(r, w, rb_resync(r));
}

/* PRINT-LOC's destination unless the host gave it a printer (fbrlmon --printer): the
 * text goes out on the controller's line as it is, as the thesis's PRINT-LOC did. A
 * controller reads the line as a command and rejects it (050-AMBIGUOUS COMMAND: an "X"
 * starts several commands), which it records as its last error: the user is told what
 * it answered, then the link is resynchronised. */
static void print_to_port(void *ctx, const char *s, size_t n)
{
    fbrl_robot *r = ctx;
    char answer[512], msg[256];
    size_t kept = 0;
    if (!r->link || raw_begin(r) != FBRL_OK) {
        rb_puts(r, "PRINT-LOC: the controller's line is busy: nothing printed\n");
        return;
    }
    if (fbrl_uart_write(r->link->u, s, n, NULL, COMM_TIMEOUT_MS) != FBRL_OK) {
        rb_puts(r, "PRINT-LOC: could not write to the controller's line: nothing printed\n");
        return;
    }
    raw_end(r, s, n);
    if (!n || s[n - 1] != '\n')
        return;
    fbrl_status st = resync_keep(r, answer, sizeof answer, &kept);
    if (st != FBRL_OK && st != FBRL_EUNITS) { /* in millimetres: in step, the words refuse lengths */
        rb_puts(r,
                "PRINT-LOC: printed on the controller's line; the controller did not answer in step again\n");
        return;
    }
    /* the controller's answer: an error line "NNN-TEXT." somewhere after its echo */
    for (size_t i = 0; i + 4 < kept; i++) {
        int code;
        char text[64];
        size_t e = i;
        while (e < kept && answer[e] != '\r' && answer[e] != '\n')
            e++;
        if (fbrl_rapl_parse_error(answer + i, e - i, &code, text, sizeof text) == FBRL_OK) {
            r->last_error = code;
            snprintf(msg, sizeof msg,
                     "PRINT-LOC: printed on the controller's line, which read it as a command and answered "
                     "%03d-%s (nothing ran; fbrlmon --printer PATH prints elsewhere)\n",
                     code, text);
            rb_puts(r, msg);
            return;
        }
        i = e;
    }
    rb_puts(r, "PRINT-LOC: printed on the controller's line (the controller answered no error)\n");
}

void rb_port_writer(fbrl_robot *r)
{
    if (r->g)
        fbrl_glossary_set_port_writer(r->g, r->link ? print_to_port : NULL, r);
}

/* .COMM ( -- ): the port's settings as the uart has them now */
static fbrl_status w_dot_comm(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    fbrl_uart *u;
    fbrl_uart_config c;
    char buf[96];
    (void)w;
    (void)v;
    fbrl_status st = uart_of(r, &u);
    if (st != FBRL_OK)
        return st;
    fbrl_uart_get_config(u, &c);
    snprintf(buf, sizeof buf, "%lu baud, %u data bits, parity %c, %u stop bit%s, %s\n", (unsigned long)c.baud,
             (unsigned)c.data_bits, (char)c.parity, (unsigned)c.stop_bits, c.stop_bits > 1 ? "s" : "",
             c.flow == FBRL_FLOW_XONXOFF ? "XON/XOFF" : "no flow control");
    rb_puts(r, buf);
    return FBRL_OK;
}

/* ASC ( "c" -- char ): F-PC's character literal, used by the thesis's examples
 * (ASC E SETPARITY); compiles a literal inside definitions. */
static fbrl_status w_asc(fbrl_vm *vm, void *ctx, const void *word)
{
    RB_WORD(vm, ctx, word);
    const char *s;
    size_t n;
    (void)w;
    (void)v;
    fbrl_vm_parse_name(r->vm, &s, &n);
    if (n == 0)
        return rb_fail(r, FBRL_THROW_NO_NAME, "ASC needs a character after it");
    if (fbrl_vmx_compiling(r->vm))
        return fbrl_vmx_compile_lit(r->vm, (unsigned char)s[0]);
    return fbrl_vm_push(r->vm, (unsigned char)s[0]) == FBRL_OK ? FBRL_OK
                                                               : rb_fail(r, FBRL_THROW_STACK_OVERFLOW, NULL);
}

const rb_word rb_comm_words[] = {
    {"SETWORDLENGTH", w_setting, "I", 0, -1, 0,
     FBRL_DOC("( num-bits -- )", "word length for the next SETUPUART (5..8)")},
    {"SETSTOPBITS", w_setting, "I", 0, -1, 1,
     FBRL_DOC("( numbits -- )", "stop bits for the next SETUPUART (1..2)")},
    {"SETPARITY", w_setting, "C", 0, -1, 2,
     FBRL_DOC("( parity-char -- )", "parity for the next SETUPUART: ASC N, ASC E or ASC O")},
    {"SETBAUDRATE", w_setting, "I", 0, -1, 3,
     FBRL_DOC("( baud-rate -- )", "baud rate for the next SETUPUART")},
    {"COMMSET", w_commset, "ICII", 0, -1, 0,
     FBRL_DOC("( baud parity stopbits wordlen -- )", "all four settings for the next SETUPUART")},
    {"SETUPUART", w_setupuart, "I", 0, -1, 0,
     FBRL_DOC("( comm-port -- )", "apply the settings to the port (1 = the controller's line)")},
    {"COMM-SETUP", w_comm_setup, "IICII", 0, -1, 0,
     FBRL_DOC("( pt# bd prty stop-bit wrdlen -- )", "set and apply all port settings")},
    {"EMIT-COM", w_emit_com, "I", 0, -1, 0,
     FBRL_DOC("( char -- )", "send a byte to the port (raw, no echo check)")},
    {"DIRECT-WRITE-COM", w_emit_com, "I", 0, -1, 1,
     FBRL_DOC("( c -- )", "send a byte and wait until it has left the queue")},
    {"TYPE-COM", w_type_com, "II", 0, -1, 0, FBRL_DOC("( chrs addr -- )", "send a string to the port (raw)")},
    {".-COM", w_dot_com, "I", 0, -1, 0, FBRL_DOC("( n -- )", "send a number as decimal text (raw)")},
    {"F.-COM", w_fdot_com, "R", 0, -1, 0,
     FBRL_DOC("( F: r -- )", "send a real as RAPL text, four decimals (raw)")},
    {"GET-COM", w_get_com, "", 0, -1, 0,
     FBRL_DOC("( -- char )", "next received byte; -1 if none came within a second")},
    {".COMM", w_dot_comm, "", 0, -1, 0, FBRL_DOC("( -- )", "show the port's settings in use")},
    {"RESET-COMM", w_reset_comm, "I", 0, -1, 0,
     FBRL_DOC("( port -- )", "discard received bytes and resynchronise the controller line")},
};

const size_t rb_comm_nwords = sizeof rb_comm_words / sizeof rb_comm_words[0];

/* ASC is F-PC's; a VM that has one keeps it. Immediate. */
const rb_word rb_comm_asc = {
    "ASC",
    w_asc,
    "",
    FBRL_VMX_IMMEDIATE,
    -1,
    0,
    FBRL_DOC("( \"c\" -- char )", "the character code of the next word's first character")};
