/* SPDX-License-Identifier: MIT */
/* robot_guard.c - what a motion guard (fbrl_robot_set_guard; the work cell's, fbrl/cell.h)
 * may ask the robot: where the arm stands, once it stands: its whole position block (W2),
 * or, shorter on the wire, its motor pulses (one line of W1). The hook itself is
 * robot_gate.c's. */
#include <string.h>

#include "fbrl/rapl_reply.h"
#include "robot_internal.h"

fbrl_status fbrl_robot_position(fbrl_robot *r, const char *word, fbrl_rapl_pos *p)
{
    rb_word w;
    fbrl_status st;
    if (!r || !p)
        return FBRL_EINVAL;
    memset(&w, 0, sizeof w);
    w.name = word ? word : "GUARD";
    if ((st = rb_online(r)) != FBRL_OK || (st = rb_still(r, &w)) != FBRL_OK)
        return st;
    if ((st = rb_link_result(r, &w, fbrl_link_where(r->link, FBRL_RAPL_W2, p))) != FBRL_OK)
        return st;
    if (p->njoints == 0)
        return rb_fail_st(r, &w, FBRL_EPROTOCOL, "W2 had no JOINTS line");
    return FBRL_OK;
}

fbrl_status fbrl_robot_joints(fbrl_robot *r, const char *word, double *q, unsigned *n)
{
    fbrl_rapl_pos p;
    fbrl_status st;
    if (!q || !n)
        return FBRL_EINVAL;
    if ((st = fbrl_robot_position(r, word, &p)) != FBRL_OK)
        return st;
    for (unsigned k = 0; k < p.njoints; k++)
        q[k] = p.joints[k];
    *n = p.njoints;
    return FBRL_OK;
}

/* The value lines of one W1 reading (more may come before the stream stops: the arm
 * stands, so they must all agree), and whether any line was damaged. */
typedef struct pulse_read {
    long v[FBRL_RAPL_MAX_AXES];
    size_t n;
    int lines, bad;
} pulse_read;

static void pulse_line(void *ctx, const char *line, size_t len, int flawed)
{
    pulse_read *pr = ctx;
    long v[FBRL_RAPL_MAX_AXES];
    size_t n = 0;
    if (fbrl_rapl_parse_ints(line, len, v, FBRL_RAPL_MAX_AXES, &n) != FBRL_OK || n == 0) {
        pr->bad |= flawed; /* the title, or a value line damaged past reading */
        return;
    }
    if (flawed || (pr->lines && (n != pr->n || memcmp(v, pr->v, n * sizeof v[0]) != 0)))
        pr->bad = 1;
    memcpy(pr->v, v, n * sizeof v[0]);
    pr->n = n;
    pr->lines++;
}

fbrl_status fbrl_robot_pulses(fbrl_robot *r, const char *word, long *pulses, unsigned *n)
{
    rb_word w;
    pulse_read pr;
    fbrl_link_line_fn fn;
    void *ctx;
    fbrl_status st;
    if (!r || !pulses || !n)
        return FBRL_EINVAL;
    memset(&w, 0, sizeof w);
    w.name = word ? word : "GUARD";
    if ((st = rb_online(r)) != FBRL_OK || (st = rb_still(r, &w)) != FBRL_OK)
        return st;
    memset(&pr, 0, sizeof pr);
    (void)fbrl_link_set_line_handler(r->link, pulse_line, &pr, &fn, &ctx);
    st = fbrl_link_stream(r->link, FBRL_RAPL_W1, 1);
    (void)fbrl_link_set_line_handler(r->link, fn, ctx, NULL, NULL);
    if ((st = rb_link_result(r, &w, st)) != FBRL_OK)
        return st;
    if (pr.lines == 0 || pr.bad) /* no clean reading: no proof of where the arm is */
        return FBRL_EPROTOCOL;
    for (size_t k = 0; k < pr.n; k++)
        pulses[k] = pr.v[k];
    *n = (unsigned)pr.n;
    return FBRL_OK;
}
