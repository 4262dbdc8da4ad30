/* SPDX-License-Identifier: MIT */
/* link_probe.c - the link's probe (docs/link.md 3.3): "? CAN ? CAN m m m" erases whatever
 * the controller's line holds and leaves exactly its three marker characters there; its
 * echo "? (k triples) ? BS SP BS m m m" proves the line's state, and k, the characters its
 * first CAN erased, what the line held when it arrived (3.2). The probe's own state: its
 * markers, the last bytes of its echo, and the parse of that echo. No link, no OS. */
#include "link_internal.h"

#define CAN 0x18
#define BS  0x08
#define XON 0x11

/* Marker characters: any two differ in at least two bits, so one flipped bit cannot turn
 * one into another. A probe ends with three of them, the probe's number in base 6, so the
 * echo of any of the 215 probes before it is never taken for its answer. */
static const char markers[] = "!$@^|'";
#define NMARK 6u

/* The parse of the echo (state): "?", k triples, "?", one triple, the three markers;
 * anything else makes it useless as evidence. */
enum { PE_START, PE_T1, PE_T2, PE_MARK, PE_DONE, PE_BAD = -1 };

size_t fbrli_probe_make(fbrl_link_probe *p, uint8_t out[FBRLI_PROBE_MAX], int xon)
{
    static const uint8_t head[] = {XON, '?', CAN, '?', CAN};
    unsigned v = p->next++ % (NMARK * NMARK * NMARK);
    size_t n = 0;
    for (size_t k = xon ? 0 : 1; k < sizeof head; k++)
        out[n++] = head[k];
    for (int k = 2; k >= 0; k--) {
        p->marker[k] = markers[v % NMARK];
        v /= NMARK;
    }
    for (int k = 0; k < 3; k++)
        out[n++] = (uint8_t)p->marker[k];
    for (int k = 0; k < 7; k++)
        p->tail[k] = 0;
    p->state = PE_START;
    return n;
}

static void parse(fbrl_link_probe *p, uint8_t b)
{
    static const char triple[] = "\b \b";
    switch (p->state) {
    case PE_START:
        p->state = b == '?' ? PE_T1 : PE_BAD;
        p->erased = p->sub = 0;
        break;
    case PE_T1:
        if (p->sub == 0 && b == '?') {
            p->state = PE_T2;
        } else if (b != (uint8_t)triple[p->sub]) {
            p->state = PE_BAD;
        } else if (++p->sub == 3) {
            p->sub = 0;
            p->erased++;
        }
        break;
    case PE_T2:
        if (b != (uint8_t)triple[p->sub])
            p->state = PE_BAD;
        else if (++p->sub == 3)
            p->state = PE_MARK, p->sub = 0;
        break;
    case PE_MARK:
        if (b != (uint8_t)p->marker[p->sub])
            p->state = PE_BAD;
        else if (++p->sub == 3)
            p->state = PE_DONE;
        break;
    default:
        p->state = PE_BAD; /* bytes after the answer */
        break;
    }
}

void fbrli_probe_echo(fbrl_link_probe *p, uint8_t b, int parse_it)
{
    for (int k = 0; k < 6; k++)
        p->tail[k] = p->tail[k + 1];
    p->tail[6] = b;
    if (parse_it)
        parse(p, b);
}

int fbrli_probe_ended(const fbrl_link_probe *p)
{
    return p->tail[4] == (uint8_t)p->marker[0] && p->tail[5] == (uint8_t)p->marker[1] &&
           p->tail[6] == (uint8_t)p->marker[2];
}

int fbrli_probe_answered(const fbrl_link_probe *p)
{
    return p->tail[0] == '?' && p->tail[1] == BS && p->tail[2] == ' ' && p->tail[3] == BS &&
           fbrli_probe_ended(p);
}

long fbrli_probe_erased(const fbrl_link_probe *p) { return p->state == PE_DONE ? (long)p->erased : -1; }

int fbrli_probe_may_echo(uint8_t b)
{
    if (b == '?' || b == BS || b == ' ')
        return 1;
    for (unsigned k = 0; k < NMARK; k++)
        if (b == (uint8_t)markers[k])
            return 1;
    return 0;
}
