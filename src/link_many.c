/* SPDX-License-Identifier: MIT */
/* link_many.c - several links from one thread (fbrl_link_poll_many; docs/link.md 2): each
 * pass serves every link that has bytes or a timer due, the one idle longest first, and
 * the thread sleeps on all ports at once, looking at a port only once what its link awaits
 * can have crossed the line. No OS header. */
#include "link_internal.h"

/* When fbrl_link_poll() acts on l with no byte arriving: the silence and deadline checks
 * at its top. */
static uint64_t due_at(const fbrl_link *l)
{
    uint64_t t = l->t_last + fbrli_ms(l->cfg.echo_timeout_ms);
    if ((l->phase == PH_REPLY || l->phase == PH_VERIFY) && l->t_deadline < t)
        t = l->t_deadline;
    return t;
}

/* Byte times that must pass, counted from t_last, before all l waits for can be in on
 * a line that carries one character per byte time:
 *  - typing, nothing back yet (t_last = the send): the first character must reach the
 *    controller before its echo starts, then the whole echo crosses: expect + 1 (expect
 *    when it starts with an owed '>', already on its way);
 *  - after the CR, nothing back yet: the CR, then the shortest reply the link can finish
 *    on ("CR LF >", 3.10);
 *  - part of either in: the rest, less one (the next byte may be on its way already).
 * 0 otherwise: any byte may be the one l waits for. */
#define MIN_REPLY_BYTES 3u
static size_t awaited(const fbrl_link *l)
{
    if (l->phase == PH_TYPE && l->expect > l->match)
        return l->match == 0 ? l->expect + 1 - (size_t)l->lead : l->expect - l->match - 1;
    if (l->phase == PH_REPLY && l->probe_out == PR_NONE && l->kind != FBRL_LINK_REPLY_STREAM &&
        l->rd.bytes < MIN_REPLY_BYTES)
        return l->rd.bytes == 0 ? 1 + MIN_REPLY_BYTES : MIN_REPLY_BYTES - l->rd.bytes - 1;
    return 0;
}

/* Microseconds one character takes on l's line (start, data, parity and stop bits). */
static uint64_t byte_us(const fbrl_link *l)
{
    fbrl_uart_config c;
    if (fbrl_uart_get_config(l->u, &c) != FBRL_OK || c.baud == 0)
        return 0;
    unsigned bits = 1u + c.data_bits + (c.parity != FBRL_PARITY_NONE) + c.stop_bits;
    return (uint64_t)bits * 1000000u / c.baud;
}

/* Nothing l waits for can be complete before this: the line carries one character per
 * byte time. Until then l's port is not watched (no wake-up per byte). Half a byte time
 * more: characters arrive a little after their line time (the sender is scheduled too),
 * and a look just before the last one only costs a second wake-up for it. */
static uint64_t not_before(const fbrl_link *l)
{
    size_t r = awaited(l);
    uint64_t bt = byte_us(l);
    return r > 0 ? l->t_last + (uint64_t)r * bt + bt / 2 : 0;
}

fbrl_status fbrl_link_poll_many(fbrl_link *const *links, size_t n, uint32_t timeout_ms, size_t *index)
{
    if (!links || !index)
        return FBRL_EINVAL;
    *index = n;
    if (n > FBRL_LINK_POLL_MANY_MAX)
        return FBRL_EINVAL;
    const fbrl_link *first = 0;
    for (size_t k = 0; k < n && !first; k++)
        if (links[k] && links[k]->busy)
            first = links[k];
    if (!first)
        return FBRL_EEMPTY;
    fbrl_uart *ports[FBRL_LINK_POLL_MANY_MAX];
    unsigned char flags[FBRL_LINK_POLL_MANY_MAX];
    size_t which[FBRL_LINK_POLL_MANY_MAX], order[FBRL_LINK_POLL_MANY_MAX];
    uint64_t end = fbrli_link_now_us(first) + fbrli_ms(timeout_ms);
    int waited = 0;
    for (;;) {
        /* Serve every link that has bytes or a timer due, the one idle longest first (its
         * last activity, t_last, is the oldest): no link waits behind the same others
         * twice, whatever its place in the array. */
        uint64_t t = fbrli_link_now_us(first);
        size_t nw = 0;
        for (size_t k = 0; k < n; k++) {
            const fbrl_link *l = links[k];
            if (!l || !l->busy || (fbrl_uart_rx_available(l->u) == 0 && due_at(l) > t))
                continue;
            size_t j = nw++;
            for (; j > 0 && links[order[j - 1]]->t_last > l->t_last; j--)
                order[j] = order[j - 1];
            order[j] = k;
        }
        for (size_t j = 0; j < nw; j++) {
            int done = 0;
            fbrl_status st = fbrl_link_poll(links[order[j]], 0, &done);
            if (done) {
                *index = order[j];
                return st;
            }
        }
        if (waited && t >= end)
            return FBRL_ETIMEOUT;
        /* Wait on all ports at once until the first one can have what its link awaits,
         * or the first timer; ports whose replies cannot be complete yet only move
         * output. After serving some links, only collect what arrived meanwhile. */
        uint64_t wake = end;
        size_t np = 0;
        for (size_t k = 0; k < n; k++) {
            const fbrl_link *l = links[k];
            if (!l || !l->busy)
                continue;
            uint64_t due = due_at(l), nb = not_before(l);
            if (due < wake)
                wake = due;
            if (nb > t && nb < wake)
                wake = nb;
            ports[np] = l->u;
            flags[np] = nb <= t ? FBRL_UART_WAIT_RX : 0;
            which[np++] = k;
        }
        uint64_t left = nw > 0 || wake <= t ? 0 : wake - t;
        fbrl_status st =
            fbrl_uart_wait_any(ports, np, left > UINT32_MAX ? UINT32_MAX : (uint32_t)left, flags);
        waited = 1;
        if (st != FBRL_OK) {
            /* the ports cannot be waited on together: let each link meet the error */
            for (size_t j = 0; j < np; j++) {
                int done = 0;
                fbrl_status s2 = fbrl_link_poll(links[which[j]], 0, &done);
                if (done) {
                    *index = which[j];
                    return s2;
                }
            }
        }
    }
}
