/* SPDX-License-Identifier: MIT */
/* sim_line.c - the serial line between the host and the controller: what each
 * side's UART does to the bytes, apart from where they come from (pty or TCP,
 * sim_io.c) and what the controller makes of them (sim_term.c).
 *
 * With --baud N each direction is a UART shift register: a character takes ten
 * bit times (8N1) and cannot start before the previous one has finished, so no
 * direction ever carries more than N/10 characters per second over any window,
 * and no character is handed over before its start plus ten bit times. The
 * emulator only ever hands bytes over late (when the OS wakes it late), never
 * early. Idle time earns no credit: a character that finds the line idle starts
 * when it is queued, not in the past. What the controller sends in answer to a
 * character (its echo, and a command's reply to its CR) is queued at the time that
 * character arrived, as a UART interrupt would see it, not when the OS got round to
 * waking the emulator: the emulator's lateness does not lengthen the line's turnaround.
 *
 * Faults (drop, corrupt, noise, stall), parity and XON/XOFF are modelled here
 * too, because they happen on the line, not in the controller. */
#include "sim_internal.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>

#define XON            0x11
#define XOFF           0x13
#define WIRE_AHEAD_MIN 0.001 /* s: how far ahead the host's bytes are taken off the OS (at least one) */
#define TX_FIRST_CAP   4096
#define BURST_MIN      2 /* characters handed over at once at least (see pace_cap) */
/* A host that honours XOFF stops within this time after it has our XOFF (what it sent
 * by then was already on its way, as in a real UART's FIFO); more bytes after it mean
 * it ignores XOFF. Generous, because a host on a loaded machine reacts late. */
#define HOLD_GRACE 0.05
#define HOLD_POLL  0.002 /* s: how often the bytes a holding host has queued are counted */

/* The OS may wake the emulator late; characters whose time has come are then handed
 * over together. So that lateness never turns into a burst faster than the line,
 * handing over is paced too: a bucket that refills one character per character time
 * and holds at most about a millisecond of characters (pace_cap). A late emulator
 * thus delays characters (the line seems to have paused), it never compresses them. */
static double pace_cap(double byte_time)
{
    double c = ceil(WIRE_AHEAD_MIN / byte_time);
    return c > BURST_MIN ? c : BURST_MIN;
}

static double pace_tokens(const sim_pace *p, double byte_time, double now)
{
    double t = p->tokens + (now - p->t) / byte_time, cap = pace_cap(byte_time);
    return t > cap ? cap : t;
}

static void pace_take(sim_pace *p, double byte_time, double now, double n)
{
    p->tokens = pace_tokens(p, byte_time, now) - n;
    p->t = now;
}

/* When the next character may be handed over, given the bucket. */
static double pace_ready_at(const sim_pace *p, double byte_time, double now)
{
    double t = pace_tokens(p, byte_time, now);
    return t >= 1.0 ? now : now + (1.0 - t) * byte_time;
}

int sim_line_init(sim_line *l, long baud, int rx_buffer)
{
    memset(l, 0, sizeof *l);
    l->byte_time = baud > 0 ? 10.0 / (double)baud : 0.0;
    if (baud > 0)
        l->tx_pace.tokens = l->rx_pace.tokens = pace_cap(l->byte_time);
    l->urgent = -1;
    l->rng = 1;
    /* Without a line model the buffer stands in for the kernel's: large, so that XON
     * from the host is still read while the controller waits for output to drain. */
    l->rxcap = baud > 0 ? (rx_buffer > 0 ? rx_buffer : SIM_RX_DEFAULT) : SIM_RX_UNPACED;
    l->rx = malloc((size_t)l->rxcap);
    l->rx_t = malloc((size_t)l->rxcap * sizeof *l->rx_t);
    return l->rx && l->rx_t ? 0 : -1;
}

void sim_line_free(sim_line *l)
{
    free(l->rx);
    free(l->rx_t);
    l->rx_t = NULL;
    free(l->tx);
    free(l->txq);
    l->rx = l->tx = NULL;
    l->txq = NULL;
}

/* ---- faults ---------------------------------------------------------- */

/* xorshift64*: reproducible faults from a seed. */
static double rnd(sim_line *l)
{
    unsigned long long x = l->rng;
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    l->rng = x;
    return (double)((x * 2685821657736338717ULL) >> 11) / 9007199254740992.0;
}

static unsigned char rnd_byte(sim_line *l) { return (unsigned char)(rnd(l) * 256.0); }

int sim_line_faults(sim_line *l, const char *spec, char *err, size_t errlen)
{
    char buf[256], *tok, *save = NULL;
    unsigned long long seed = 1;
    if (strlen(spec) >= sizeof buf) {
        sim_seterr(err, errlen, "fault spec too long");
        return -1;
    }
    strcpy(buf, spec);
    for (tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        char *eq = strchr(tok, '='), *end;
        double v;
        if (!eq) {
            sim_seterr(err, errlen, "fault '%s': expected name=value", tok);
            return -1;
        }
        *eq = 0;
        v = strtod(eq + 1, &end);
        if (*end || end == eq + 1 || !isfinite(v) || v < 0) {
            sim_seterr(err, errlen, "fault '%s': bad value", tok);
            return -1;
        }
        if (!strcmp(tok, "drop") && v <= 1)
            l->f_drop = v;
        else if (!strcmp(tok, "corrupt") && v <= 1)
            l->f_corrupt = v;
        else if (!strcmp(tok, "noise") && v <= 1)
            l->f_noise = v;
        else if (!strcmp(tok, "stall") && v <= SIM_STALL_MAX_MS)
            l->f_stall = (int)v;
        else if (!strcmp(tok, "seed") && v <= 1e18)
            seed = (unsigned long long)v;
        else {
            sim_seterr(err, errlen, "fault '%s': unknown name or value out of range", tok);
            return -1;
        }
    }
    l->rng = seed * 0x9E3779B97F4A7C15ULL + 0x2545F4914F6CDD1DULL;
    if (!l->rng)
        l->rng = 1;
    return 0;
}

/* The host channel checks parity (CONFIG 0 / --parity E or O). */
static int parity_on(const fbrl_sim *s)
{
    return s->dev.chan[0].parity == 'E' || s->dev.chan[0].parity == 'O';
}

static int flow_on(const fbrl_sim *s) { return s->dev.chan[0].handshake == 'X'; }

/* The receive buffer's fill at which the controller sends XOFF (three quarters). */
static int xoff_mark(const sim_line *l) { return l->rxcap * 3 / 4; }

/* Applies the line faults to one byte; returns how many bytes went to out (0..2).
 * bad[k] = the receiving UART sees a parity error on out[k] (only with parity on): a
 * corrupted byte always (one bit flipped: an odd number), a noise byte half the time
 * (its parity bit is as random as its data). */
static int fault_byte(fbrl_sim *s, unsigned char b, unsigned char out[2], int bad[2])
{
    sim_line *l = &s->line;
    int n = 0;
    bad[0] = bad[1] = 0;
    if (l->f_drop > 0 && rnd(l) < l->f_drop)
        return 0;
    if (l->f_corrupt > 0 && rnd(l) < l->f_corrupt) {
        b ^= (unsigned char)(1u << (int)(rnd(l) * 8.0)); /* one bit flipped: always a different byte */
        bad[0] = parity_on(s);
    }
    out[n++] = b;
    if (l->f_noise > 0 && rnd(l) < l->f_noise) {
        bad[n] = parity_on(s) && rnd(l) < 0.5;
        out[n++] = rnd_byte(l);
    }
    return n;
}

/* A parity error, noted in the log (not a command: the line starts with '#'). */
static void log_parity(fbrl_sim *s, const char *dir)
{
    if (s->log) {
        fprintf(s->log, "# PARITY ERROR %s\n", dir);
        fflush(s->log);
    }
}

/* ---- controller -> host ---------------------------------------------- */

static void tx_push(sim_line *l, unsigned char b, double queued)
{
    if (l->txlen == l->txcap) {
        if (l->txoff > 0) { /* compact first */
            memmove(l->tx, l->tx + l->txoff, l->txlen - l->txoff);
            memmove(l->txq, l->txq + l->txoff, (l->txlen - l->txoff) * sizeof *l->txq);
            l->txlen -= l->txoff;
            l->txoff = 0;
        }
        if (l->txlen == l->txcap) {
            size_t cap = l->txcap ? l->txcap * 2 : TX_FIRST_CAP;
            unsigned char *t = realloc(l->tx, cap);
            double *q;
            if (!t)
                return; /* out of memory: the byte is lost, as on an overrun */
            l->tx = t;
            q = realloc(l->txq, cap * sizeof *q);
            if (!q)
                return;
            l->txq = q;
            l->txcap = cap;
        }
    }
    l->txq[l->txlen] = queued;
    l->tx[l->txlen++] = b;
}

/* What the host reads is what its UART delivers. With parity on, that is the format of
 * a Linux serial port opened with INPCK|PARMRK: a byte with a parity error comes as
 * 0xFF 0x00 byte, a data byte 0xFF as 0xFF 0xFF. (The marks are the host driver's,
 * not characters on the wire: they cost no line time.) */
void sim_emit(fbrl_sim *s, const char *bytes, size_t n)
{
    double now = sim_real_now(s);
    if (s->line.pop_valid && s->line.pop_t < now)
        now = s->line.pop_t; /* an answer to the character taken: queued when it arrived */
    size_t i;
    for (i = 0; i < n; i++) {
        unsigned char o[2];
        int bad[2];
        int k = fault_byte(s, (unsigned char)bytes[i], o, bad), j;
        for (j = 0; j < k; j++) {
            if (bad[j]) {
                s->line.parity_out++;
                log_parity(s, "OUT");
                tx_push(&s->line, 0xFF, SIM_MARK);
                tx_push(&s->line, 0x00, SIM_MARK);
            } else if (parity_on(s) && o[j] == 0xFF) {
                tx_push(&s->line, 0xFF, SIM_MARK);
            }
            tx_push(&s->line, o[j], now);
        }
    }
}

int sim_line_tx_pending(const sim_line *l) { return (int)(l->txlen - l->txoff); }

void sim_line_hold(sim_line *l, double until)
{
    if (until > l->tx_hold_until)
        l->tx_hold_until = until;
}

/* Output is held: the host sent XOFF, or a stall fault holds the reply. */
static int tx_blocked(const sim_line *l, double now) { return l->peer_xoff || now < l->tx_hold_until; }

/* When the next character on the line (urgent first) would be complete, or HUGE_VAL. */
static double tx_line_end(const sim_line *l, double now)
{
    double start;
    if (l->urgent >= 0) {
        start = l->urgent_q > l->tx_free ? l->urgent_q : l->tx_free;
        return start + l->byte_time;
    }
    if (!sim_line_tx_pending(l) || tx_blocked(l, now))
        return HUGE_VAL;
    {
        size_t k = l->txoff;
        while (k < l->txlen && l->txq[k] == SIM_MARK) /* a mark travels with the character after it */
            k++;
        start = k < l->txlen ? l->txq[k] : now;
    }
    if (start < l->tx_free)
        start = l->tx_free;
    if (start < l->tx_resume)
        start = l->tx_resume;
    if (start < l->tx_hold_until)
        start = l->tx_hold_until;
    return start + l->byte_time;
}

/* When the next character can be handed to the host: complete on the line, and paced. */
static double tx_next_end(const sim_line *l, double now)
{
    double end = tx_line_end(l, now), ready;
    if (end == HUGE_VAL)
        return end;
    ready = pace_ready_at(&l->tx_pace, l->byte_time, now);
    return end > ready ? end : ready;
}

/* Writes what the line has carried by now; -1 when the connection broke. */
int sim_line_write(fbrl_sim *s, int fd, double now)
{
    sim_line *l = &s->line;
    size_t n = 0;
    ssize_t w;
    l->pop_valid = 0; /* the controller's answers to this round's characters are queued */
    if (fd < 0) {
        l->txoff = l->txlen = 0; /* nobody listening: the bytes fall off the line */
        l->urgent = -1;
        return 0;
    }
    if (l->urgent >= 0) {
        double end = l->byte_time > 0 ? tx_line_end(l, now) : now;
        unsigned char b = (unsigned char)l->urgent;
        if (l->byte_time > 0 && tx_next_end(l, now) > now)
            return 0; /* the flow-control character goes first */
        if (write(fd, &b, 1) != 1)
            return errno == EAGAIN || errno == EINTR ? 0 : -1;
        l->urgent = -1;
        if (b == XOFF) {
            /* from when the host has it, its bytes stay with it (sim_line_rx_allow) */
            l->holding = 1;
            l->hold_from = l->byte_time > 0 ? end : now;
            l->hold_base = -1;
            l->host_ignores = 0;
        } else {
            /* the host's UART starts again when it has our XON, not in the past */
            double resume = l->byte_time > 0 ? end : now;
            if (l->holding && l->rx_free < resume)
                l->rx_free = resume;
            l->holding = l->host_ignores = 0;
        }
        if (l->byte_time > 0) {
            l->tx_free = end;
            pace_take(&l->tx_pace, l->byte_time, now, 1.0);
        }
    }
    if (!sim_line_tx_pending(l) || tx_blocked(l, now))
        return 0;
    if (l->byte_time <= 0) {
        n = (size_t)sim_line_tx_pending(l);
    } else {
        /* every character whose ten bit times have passed, one after another, as
         * many as the hand-over pace allows */
        double free_at = l->tx_free, allow = floor(pace_tokens(&l->tx_pace, l->byte_time, now));
        size_t i = l->txoff, count = 0;
        while (i < l->txlen && (double)count < allow) {
            double start, end;
            size_t k = i;
            while (k < l->txlen && l->txq[k] == SIM_MARK)
                k++;
            if (k == l->txlen)
                break;
            start = l->txq[k];
            if (start < free_at)
                start = free_at;
            if (start < l->tx_resume)
                start = l->tx_resume;
            if (start < l->tx_hold_until)
                start = l->tx_hold_until;
            end = start + l->byte_time;
            if (end > now)
                break;
            free_at = end;
            i = k + 1;
            count++;
        }
        n = i - l->txoff;
        if (!n)
            return 0;
        w = write(fd, l->tx + l->txoff, n);
        if (w > 0 && (size_t)w == n) {
            l->tx_free = free_at;
            pace_take(&l->tx_pace, l->byte_time, now, (double)count);
        } else if (w > 0) {
            l->tx_free = now; /* a partial write: the rest goes when the OS takes it */
            pace_take(&l->tx_pace, l->byte_time, now, (double)w);
        }
        goto wrote;
    }
    w = write(fd, l->tx + l->txoff, n);
wrote:
    if (w > 0) {
        l->txoff += (size_t)w;
        if (l->txoff == l->txlen)
            l->txoff = l->txlen = 0;
    } else if (w < 0 && errno != EAGAIN && errno != EINTR) {
        return -1;
    }
    return 0;
}

/* ---- host -> controller ---------------------------------------------- */

static void rx_byte(fbrl_sim *s, unsigned char b, double now)
{
    sim_line *l = &s->line;
    if (flow_on(s) && b == XON) {
        if (l->peer_xoff)
            l->tx_resume = now; /* the transmitter starts again from here, not in the past */
        l->peer_xoff = 0;
        return;
    }
    if (flow_on(s) && b == XOFF) {
        l->peer_xoff = 1;
        return;
    }
    if (l->rxcount == l->rxcap) {
        l->overruns++;
        return;
    }
    l->rx[(l->rxhead + l->rxcount) % l->rxcap] = b;
    l->rx_t[(l->rxhead + l->rxcount) % l->rxcap] = now;
    l->rxcount++;
    if (l->byte_time > 0 && flow_on(s) && !l->xoff_sent && l->rxcount >= xoff_mark(l)) {
        l->urgent = XOFF;
        l->urgent_q = now;
        l->xoff_sent = 1;
    }
}

int sim_line_rx_pop(fbrl_sim *s)
{
    sim_line *l = &s->line;
    int b;
    if (!l->rxcount)
        return -1;
    b = l->rx[l->rxhead];
    /* A character that arrived this round is taken at its arrival; one that waited in the
     * buffer (the controller was busy) when the controller takes it, now. */
    l->pop_t = l->rx_t[l->rxhead];
    if (l->rx_stale > 0) {
        l->rx_stale--;
        l->pop_t = sim_real_now(s);
    }
    l->pop_valid = l->byte_time > 0;
    l->rxhead = (l->rxhead + 1) % l->rxcap;
    l->rxcount--;
    if (l->xoff_sent && l->rxcount <= l->rxcap / 4) {
        l->urgent = XON;
        l->urgent_q = sim_real_now(s);
        l->xoff_sent = 0;
    }
    return b;
}

/* A byte reaches the controller's UART: faults, parity check, then the buffer. */
static void arrive(fbrl_sim *s, unsigned char b, double now)
{
    unsigned char o[2];
    int bad[2];
    int k = fault_byte(s, b, o, bad), j;
    for (j = 0; j < k; j++) {
        if (bad[j]) {
            /* the controller's UART flags it; its firmware drops the character */
            s->line.parity_in++;
            log_parity(s, "IN");
            continue;
        }
        rx_byte(s, o[j], now);
    }
}

/* Characters whose last bit has arrived by now go into the receive buffer. */
void sim_line_deliver(fbrl_sim *s, double now)
{
    sim_line *l = &s->line;
    double allow = l->byte_time > 0 ? floor(pace_tokens(&l->rx_pace, l->byte_time, now)) : HUGE_VAL;
    double count = 0;
    l->pop_valid = 0;
    l->rx_stale = l->rxcount;
    while (l->wn > 0 && l->wire_end[l->whead] <= now && count < allow) {
        unsigned char b = l->wire[l->whead];
        double at = l->wire_end[l->whead];
        l->whead = (l->whead + 1) % SIM_WIRE_MAX;
        l->wn--;
        arrive(s, b, l->byte_time > 0 ? at : now);
        count++;
    }
    if (l->byte_time > 0 && count > 0)
        pace_take(&l->rx_pace, l->byte_time, now, count);
}

/* How many bytes may be taken off the OS now. Paced: those that will be complete
 * within a short look-ahead (at least one when the wire is empty), so that bytes a
 * host still holds after our XOFF stay with it, as they would in its UART. */
/* Whether the host's port stops sending on our XOFF: its tty has IXON (a pty), or, over
 * TCP, it has not been seen sending on after our XOFF. */
static int host_honours(const sim_line *l)
{
    return l->host_ixon == 1 || (l->host_ixon < 0 && !l->host_ignores);
}

int sim_line_rx_allow(const sim_line *l, double now)
{
    if (l->flow && l->holding && host_honours(l))
        return 0; /* our XOFF is out: what the host queued stays with it */
    if (l->byte_time > 0) {
        double start = l->backlog > 0 || l->rx_free > now ? l->rx_free : now;
        double ahead = l->byte_time > WIRE_AHEAD_MIN ? l->byte_time : WIRE_AHEAD_MIN;
        int k = (int)floor((now + ahead - start) / l->byte_time);
        if (k < 1 && l->wn == 0)
            k = 1;
        if (k > SIM_WIRE_MAX - l->wn)
            k = SIM_WIRE_MAX - l->wn;
        if (l->flow && host_honours(l)) {
            /* A real controller's XOFF leaves the moment its buffer reaches the mark, even
             * when this process runs late: so a host that honours it never sends more than
             * fills the buffer to the mark (plus what it still had on the wire). */
            int room = xoff_mark(l) - l->rxcount - l->wn;
            if (k > room)
                k = room;
        }
        return k < 0 ? 0 : k;
    }
    return l->rxcap - l->rxcount; /* no line model: the kernel buffer holds the rest */
}

/* Does the host honour our XOFF? On a pty its tty's IXON says (host_ixon 0 or 1: the
 * kernel then stops its writes, as a real port's driver would stop its UART). Over TCP
 * (host_ixon -1) its behaviour says: after the grace, count what it has queued; if
 * that grows, it ignores XOFF and its bytes flow again (into an overrun). */
void sim_line_hold_check(sim_line *l, int fd, double now, int flow, int host_ixon)
{
    int waiting = 0;
    l->flow = flow;
    l->host_ixon = host_ixon;
    if (host_ixon >= 0)
        return; /* the host's own port says whether it honours XOFF */
    if (!l->holding || l->host_ignores || fd < 0 || now < l->hold_from + HOLD_GRACE)
        return;
    if (ioctl(fd, FIONREAD, &waiting) != 0 || waiting < 0)
        return;
    if (l->hold_base < 0) {
        l->hold_base = waiting;
    } else if (waiting > l->hold_base) {
        l->host_ignores = 1; /* counted in ignored_xoff below */
        l->ignored_xoff++;
        l->backlog = 0; /* what it sends now starts now */
        if (l->rx_free < now)
            l->rx_free = now;
    }
}

/* Reads from the host; 1 at end of file, -1 on a broken connection, else 0. */
int sim_line_read(fbrl_sim *s, int fd, double now)
{
    sim_line *l = &s->line;
    unsigned char buf[SIM_WIRE_MAX > 512 ? SIM_WIRE_MAX : 512];
    int allow = sim_line_rx_allow(l, now), i;
    ssize_t n;
    if (allow <= 0)
        return 0;
    if (allow > (int)sizeof buf)
        allow = (int)sizeof buf;
    n = read(fd, buf, (size_t)allow);
    if (n == 0)
        return 1;
    if (n < 0)
        return errno == EAGAIN || errno == EINTR ? 0 : -1;
    if (l->byte_time <= 0) {
        for (i = 0; i < n; i++)
            arrive(s, buf[i], now);
        return 0;
    }
    {
        /* Bytes seen waiting at the last read were in the host's UART then: they follow
         * the previous character at once. Any other byte was sent no earlier than now. */
        double t = l->rx_free;
        int waiting = 0;
        for (i = 0; i < n; i++) {
            int at = (l->whead + l->wn) % SIM_WIRE_MAX;
            if (i >= l->backlog && t < now)
                t = now;
            t += l->byte_time;
            l->wire[at] = buf[i];
            l->wire_end[at] = t;
            l->wn++;
        }
        l->rx_free = t;
        if (ioctl(fd, FIONREAD, &waiting) != 0 || waiting < 0)
            waiting = 0;
        l->backlog = waiting;
    }
    return 0;
}

/* Real seconds until the line has something to do, capped by limit. */
double sim_line_due(const sim_line *l, double now, double limit)
{
    double r = limit, t;
    if (l->byte_time > 0) {
        if (l->wn > 0) {
            double at = l->wire_end[l->whead], ready = pace_ready_at(&l->rx_pace, l->byte_time, now);
            if (ready > at)
                at = ready;
            if (at - now < r)
                r = at - now;
        }
        t = tx_next_end(l, now);
        if (t != HUGE_VAL && t - now < r)
            r = t - now;
    } else if (l->urgent >= 0) {
        r = 0;
    }
    if (l->holding && l->host_ixon < 0 && !l->host_ignores) { /* TCP: watch what the host queues */
        t = l->hold_from + HOLD_GRACE - now;
        if (t < HOLD_POLL)
            t = HOLD_POLL;
        if (t < r)
            r = t;
    }
    if (sim_line_tx_pending(l) && !l->peer_xoff && l->tx_hold_until > now && l->tx_hold_until - now < r)
        r = l->tx_hold_until - now;
    return r;
}

/* Whether the line wants to write now (POLLOUT). */
int sim_line_wants_write(const sim_line *l, double now)
{
    if (l->urgent < 0 && (!sim_line_tx_pending(l) || tx_blocked(l, now)))
        return 0;
    return l->byte_time <= 0 || tx_next_end(l, now) <= now;
}

/* The connection ended: what was on the line is lost with it. */
void sim_line_reset(sim_line *l)
{
    l->rxcount = 0;
    l->wn = 0;
    l->backlog = 0;
    l->txoff = l->txlen = 0;
    l->peer_xoff = l->xoff_sent = 0;
    l->holding = l->host_ignores = 0;
    l->urgent = -1;
}
