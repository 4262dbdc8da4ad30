/* SPDX-License-Identifier: MIT */
/* link_aci.c - the switch from ACI mode to terminal mode (research notes 2.5, S2's
 * ACI_to_Term; docs/link.md 1): a controller that powers up in ACI mode ignores typed
 * text until a host sends it. Connect only (cfg.aci). No OS header. */
#include "link_internal.h"

#define ACI_SLAVE   0x21 /* slave 1 + 0x20 */
#define ACI_TO_TERM 0x48
#define ACI_PKT_LEN 13 /* SOH dst src op cmd, 6 data, ETX, checksum */

/* Reads exactly n bytes within timeout_ms; how many came. */
static size_t aci_read(fbrl_link *l, uint8_t *buf, size_t n, uint32_t timeout_ms)
{
    uint64_t end = fbrli_link_now_us(l) + (uint64_t)timeout_ms * 1000u;
    size_t got = 0;
    while (got < n) {
        uint64_t t = fbrli_link_now_us(l);
        size_t k = 0;
        if (t >= end)
            break;
        if (fbrl_uart_read(l->u, buf + got, n - got, &k, (uint32_t)((end - t + 999) / 1000)) != FBRL_OK && !k)
            break;
        got += k;
    }
    return got;
}

static int aci_step(fbrl_link *l, const uint8_t *out, size_t n, const uint8_t *want, size_t wn)
{
    uint8_t got[8];
    if (fbrli_link_send(l, out, n) != FBRL_OK)
        return 0;
    if (aci_read(l, got, wn, l->cfg.reply_timeout_ms) != wn)
        return 0;
    for (size_t i = 0; i < wn; i++)
        if (got[i] != want[i])
            return 0;
    return 1;
}

/* Switches a controller in ACI mode to terminal mode. One in terminal mode echoes the
 * selection 'R' '!' (not its ENQ) instead of acknowledging it: the two are erased. */
fbrl_status fbrli_link_aci_switch(fbrl_link *l)
{
    static const uint8_t sel[] = {'R', ACI_SLAVE, 0x05};
    static const uint8_t pkt_ack[] = {0x06, 0x02, 0x03, 0x00}, ack[] = {0x06}, eot[] = {0x04};
    static const uint8_t erase[] = {0x08, 0x08};
    uint8_t pkt[ACI_PKT_LEN] = {0x01, ACI_SLAVE, ACI_SLAVE, 0x00, ACI_TO_TERM, 0, 0, 0, 0, 0, 0, 0x03, 0};
    uint8_t junk[16], b, last;
    unsigned sum = 0;
    int seen = 0, heard = 0, acked = 0; /* seen: 1 after 'R', 2 after 'R' '!' */
    size_t k;
    while (fbrl_uart_read(l->u, junk, sizeof junk, &k, 0) == FBRL_OK && k)
        ; /* what came before (a greeting, old output) is not the answer */
    if (fbrli_link_send(l, sel, sizeof sel) != FBRL_OK)
        return FBRL_EIO;
    uint64_t end = fbrli_link_now_us(l) + (uint64_t)l->cfg.reply_timeout_ms * 1000u;
    for (;;) {
        uint64_t t = fbrli_link_now_us(l);
        /* after "R!" the ACK comes at once or never (a terminal-mode echo) */
        uint32_t wait = seen == 2 ? l->cfg.echo_timeout_ms : t < end ? (uint32_t)((end - t + 999) / 1000) : 0;
        if (!wait || aci_read(l, &b, 1, wait) != 1)
            break;
        heard = 1;
        if (seen == 2 && b == 0x06) {
            acked = 1;
            break;
        }
        seen = b == 'R' ? 1 : seen == 1 && b == ACI_SLAVE ? 2 : 0;
    }
    if (!acked) {
        if (!heard)
            return FBRL_ETIMEOUT; /* nothing answers */
        /* terminal mode: "R!" was typed; erase it and let its echo pass */
        if (fbrli_link_send(l, erase, sizeof erase) != FBRL_OK)
            return FBRL_EIO;
        while (fbrl_uart_read(l->u, junk, sizeof junk, &k, l->cfg.echo_timeout_ms) == FBRL_OK && k)
            ;
        return FBRL_OK;
    }
    for (size_t i = 1; i < ACI_PKT_LEN - 2; i++) /* the bytes between SOH and ETX, mod 256 */
        sum += pkt[i];
    pkt[ACI_PKT_LEN - 1] = (uint8_t)(sum & 0xFFu);
    if (!aci_step(l, pkt, sizeof pkt, pkt_ack, sizeof pkt_ack) ||
        !aci_step(l, ack, sizeof ack, eot, sizeof eot))
        return FBRL_EPROTOCOL;
    if (fbrli_link_send(l, eot, sizeof eot) != FBRL_OK || aci_read(l, &last, 1, l->cfg.reply_timeout_ms) != 1)
        return FBRL_EPROTOCOL; /* the controller's last byte of the switch, discarded */
    return FBRL_OK;
}
