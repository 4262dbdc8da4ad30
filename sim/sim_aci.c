/* SPDX-License-Identifier: MIT */
/* sim_aci.c - ACI mode: the binary host protocol some RAPL-II controllers power
 * up in (fbrlsim --aci). Only what clients use is emulated: the switch to
 * terminal mode (research notes 2.5, S2's ACI_to_Term with the S5 and S6
 * variants), with its handshake and checksum. Any other packet is refused with
 * NAK; bytes outside a handshake are ignored and never echoed. Ctrl-Z Ctrl-Z in
 * terminal mode comes back here (sim_term.c). */
#include "sim_internal.h"

#include <string.h>

#define ACI_START    'R'  /* selects a slave: 'R', its id, ENQ */
#define ACI_SLAVE_ID 0x21 /* slave 1 + 0x20, as every client sends */
#define ACI_WRITE    0x00
#define ACI_TO_TERM  0x48
#define SOH          0x01
#define STX          0x02
#define ETX          0x03
#define EOT          0x04
#define ENQ          0x05
#define ACK          0x06
#define NAK          0x15
/* dst src op cmd, six data bytes, ETX, checksum (the SOH is not stored) */
#define PKT_LEN    12
#define PKT_SUMMED 10 /* the bytes between SOH and ETX: their sum mod 256 is the checksum */
#define PKT_ETX    10
#define PKT_SUM    11
/* The controller's last byte of the switch, after the host's EOT. S2 reads and
 * discards one byte there; nothing says which, so it is ACK [D]. */
#define SWITCH_LAST ACK

enum { A_IDLE, A_GOT_R, A_GOT_ID, A_SELECTED, A_PKT, A_CLOSE_ACK, A_CLOSE_EOT };

static void say(fbrl_sim *s, const unsigned char *b, size_t n) { sim_emit(s, (const char *)b, n); }

static void note(fbrl_sim *s, const char *what)
{
    if (s->log) {
        fprintf(s->log, "# %s\n", what); /* not a command: the line starts with '#' */
        fflush(s->log);
    }
}

/* The switch is done: terminal mode, HELP on as after power-up, an empty line. */
static void to_terminal(fbrl_sim *s)
{
    s->term.aci = 0;
    s->term.aci_st = A_IDLE;
    s->term.len = 0;
    s->term.overlong = 0;
    s->term.ctrl_z = 0;
    note(s, "ACI: TERMINAL MODE");
}

void sim_aci_enter(fbrl_sim *s)
{
    s->term.aci = 1;
    s->term.aci_st = A_IDLE;
    s->term.len = 0;
    s->term.overlong = 0;
    s->term.ctrl_z = 0;
    note(s, "ACI MODE");
}

static void packet(fbrl_sim *s)
{
    const unsigned char *p = s->term.aci_pkt;
    unsigned sum = 0;
    int i;
    for (i = 0; i < PKT_SUMMED; i++)
        sum += p[i];
    if (p[0] != ACI_SLAVE_ID || p[PKT_ETX] != ETX || (sum & 0xFFu) != p[PKT_SUM] || p[2] != ACI_WRITE ||
        p[3] != ACI_TO_TERM) {
        static const unsigned char nak[] = {NAK};
        say(s, nak, sizeof nak);
        note(s, "ACI: PACKET REFUSED");
        s->term.aci_st = A_SELECTED; /* the host may send it again */
        return;
    }
    {
        static const unsigned char ok[] = {ACK, STX, ETX, 0x00};
        say(s, ok, sizeof ok);
    }
    s->term.aci_st = A_CLOSE_ACK;
}

/* Closing the switch: ACK -> EOT, EOT -> the last byte. A printable byte or a line end
 * means the host (S5, S6) goes on without reading: terminal mode takes it. */
static int closing(fbrl_sim *s, unsigned char b)
{
    if (b == ACK && s->term.aci_st == A_CLOSE_ACK) {
        static const unsigned char eot[] = {EOT};
        say(s, eot, sizeof eot);
        s->term.aci_st = A_CLOSE_EOT;
        return 0;
    }
    if (b == EOT && s->term.aci_st == A_CLOSE_EOT) {
        static const unsigned char last[] = {SWITCH_LAST};
        say(s, last, sizeof last);
        to_terminal(s);
        return 0;
    }
    if ((b >= 0x20 && b <= 0x7e) || b == '\r' || b == '\n') {
        to_terminal(s);
        return 1;
    }
    return 0; /* S6's second ACK and its ETX bytes */
}

int sim_aci_byte(fbrl_sim *s, unsigned char b)
{
    sim_term *t = &s->term;
    switch (t->aci_st) {
    case A_CLOSE_ACK:
    case A_CLOSE_EOT: return closing(s, b); /* 1: the byte starts the first terminal-mode line */
    case A_PKT:
        t->aci_pkt[t->aci_n++] = b;
        if (t->aci_n == PKT_LEN)
            packet(s);
        return 0;
    case A_GOT_R: t->aci_st = b == ACI_SLAVE_ID ? A_GOT_ID : b == ACI_START ? A_GOT_R : A_IDLE; return 0;
    case A_GOT_ID:
        if (b == ENQ) {
            static const unsigned char sel[] = {ACI_START, ACI_SLAVE_ID, ACK};
            say(s, sel, sizeof sel);
            t->aci_st = A_SELECTED;
        } else {
            t->aci_st = b == ACI_START ? A_GOT_R : A_IDLE;
        }
        return 0;
    case A_SELECTED:
        if (b == SOH) {
            t->aci_st = A_PKT;
            t->aci_n = 0;
            return 0;
        }
        t->aci_st = b == ACI_START ? A_GOT_R : A_IDLE; /* a new selection or noise */
        return 0;
    default: t->aci_st = b == ACI_START ? A_GOT_R : A_IDLE; return 0;
    }
}
