/* SPDX-License-Identifier: MIT */
/* link_query.c - believing a read-only query's reply (docs/link.md 3.5): a position block
 * that agrees with itself through the arm's kinematics, or query_reads replies alike in value,
 * length and value line, none shorter than a value line the query already read. The link
 * reads and asks again. No OS. */
#include "link_internal.h"
#include "fbrl/arm.h"
#include "fbrl/crc32.h"

#include <math.h>

/* A TYPEI/TYPEV value line, parsed as a number or not: the read is damaged unless it parsed
 * and came whole; its CRC and length for fbrli_query_confirmed(); and the longest one of the query that
 * parsed, damaged framing or not (a byte the reader refused is left out, so a damaged line is
 * never longer than the one printed). */
void fbrli_query_value(fbrl_link *l, const char *s, size_t n, int flawed, int parsed)
{
    if (!parsed || flawed)
        l->out_bad = 1;
    if (parsed && n > l->val_longest)
        l->val_longest = n;
    l->val_sum = fbrl_crc32(0, s, n);
    l->val_len = n;
    l->nvalues++;
}

static int same_pos(const fbrl_rapl_pos *a, const fbrl_rapl_pos *b)
{
    if (a->kind != b->kind || a->npulses != b->npulses || a->njoints != b->njoints || a->nworld != b->nworld)
        return 0;
    for (unsigned k = 0; k < a->npulses; k++)
        if (a->pulses[k] != b->pulses[k])
            return 0;
    for (unsigned k = 0; k < a->njoints; k++)
        if (a->joints[k] != b->joints[k])
            return 0;
    for (unsigned k = 0; k < a->nworld; k++)
        if (a->world[k] != b->world[k])
            return 0;
    return 1;
}

static int same_status(const fbrl_rapl_status_info *a, const fbrl_rapl_status_info *b, int error_only)
{
    if (a->last_error != b->last_error)
        return 0;
    if (error_only)
        return 1;
    if (a->have != b->have || a->speed != b->speed || a->homed != b->homed || a->naxes != b->naxes ||
        a->inputs != b->inputs || a->outputs != b->outputs || a->metric != b->metric)
        return 0;
    for (unsigned k = 0; k < a->naxes; k++)
        if (a->lock[k] != b->lock[k] || a->done[k] != b->done[k] || a->limp[k] != b->limp[k] ||
            a->axis_homed[k] != b->axis_homed[k])
            return 0;
    return 1;
}

#define DEG_TO_RAD  0.017453292519943295
#define POS_TOL_IN  0.002 /* world x y z against the joints: print rounding is ~1e-4 */
#define POS_TOL_JNT 5e-5  /* an angle printed to 4 decimals: each joint, and each world angle */
#define TOOL_MAX_IN 100.0 /* a longer tool along the tool axis is not believed */

/* A position block is self-checking (docs/link.md 3.5): its pulses, joint angles and
 * world coordinates are printed from one sample of the arm, so they agree through the
 * pulses per degree and the arm's kinematics (fbrl/arm.h). A damaged digit breaks that
 * agreement (beyond the print resolution), so such a block is believed at once, even while
 * the arm moves and no two reads are alike. The tool point may lie any distance along the
 * tool axis (TOOL), so only the part of x y z across that axis is checked; a world angle
 * sums the joints' rounding, one per joint at most. */
static int pos_consistent(const fbrl_link *l)
{
    const fbrl_arm *m = l->cfg.arm ? l->cfg.arm : fbrl_arm_model(0);
    const fbrl_rapl_pos *p = &l->pos;
    unsigned n = m->naxes;
    double pose[6], tol = (n + 1) * POS_TOL_JNT;
    if (l->cfg.naxes != n || p->npulses < n || p->njoints < n || p->nworld < 6)
        return 0;
    for (unsigned k = 0; k < n; k++) {
        double want = p->joints[k] * m->ppd[k];
        if (fabs((double)p->pulses[k] - want) > 0.5 + POS_TOL_JNT * m->ppd[k] + 1e-6)
            return 0;
    }
    if (fbrl_arm_fk(m, p->joints, 0.0, pose) != FBRL_OK)
        return 0;
    const double *w = p->world;
    double yaw = pose[3] * DEG_TO_RAD, pr = pose[4] * DEG_TO_RAD;
    double d[3] = {w[0] - pose[0], w[1] - pose[1], w[2] - pose[2]};
    double axis[3] = {cos(pr) * cos(yaw), cos(pr) * sin(yaw), sin(pr)};
    double t = d[0] * axis[0] + d[1] * axis[1] + d[2] * axis[2], across = 0.0;
    for (int k = 0; k < 3; k++)
        across += (d[k] - t * axis[k]) * (d[k] - t * axis[k]);
    return sqrt(across) <= POS_TOL_IN && t >= -POS_TOL_IN && t <= TOOL_MAX_IN &&
           fabs(fbrl_arm_wrap(w[3] - pose[3])) <= tol && fabs(fbrl_arm_wrap(w[4] - pose[4])) <= tol &&
           fabs(fbrl_arm_wrap(w[5] - pose[5])) <= tol;
}

/* Count agreeing reads: same values and the same number of reply bytes (a dropped
 * digit can leave a well-formed number; it cannot keep the length), and for TYPEI and
 * TYPEV the same value line, byte for byte: on 8N1 "-72.330000" (an '8' dropped) and
 * "-072.33000" (the '8' flipped to '0', a '0' dropped) are the same number of the same
 * length, and two such reads once agreed on a value the controller never held. A read
 * that disagrees becomes the new reference. True once query_reads reads agree. */
int fbrli_query_confirmed(fbrl_link *l)
{
    int same = 0;
    if (l->kind == FBRL_LINK_REPLY_POS && pos_consistent(l)) {
        l->stats.self_checked++;
        return 1;
    }
    /* Noise drops bytes or changes them; it does not add them. A value line shorter than one
     * this query has already read lost bytes, however many reads agree on it (8N1, seed 7:
     * three reads lost the same '1' of +659.180000, after one read whole but for its LF). */
    if ((l->kind == FBRL_LINK_REPLY_INT || l->kind == FBRL_LINK_REPLY_REAL) && l->val_len < l->val_longest)
        return 0;
    if (l->have_prev && l->rd.bytes == l->prev_len) {
        switch (l->kind) {
        case FBRL_LINK_REPLY_POS: same = same_pos(&l->pos, &l->prev_pos); break;
        case FBRL_LINK_REPLY_STATUS: same = same_status(&l->st, &l->prev_st, l->stage == ST_ERRQ); break;
        case FBRL_LINK_REPLY_INT: same = l->ival == l->prev_i && l->val_sum == l->prev_sum; break;
        case FBRL_LINK_REPLY_REAL: same = l->rval == l->prev_r && l->val_sum == l->prev_sum; break;
        default: break;
        }
    }
    if (!same) {
        l->prev_pos = l->pos;
        l->prev_st = l->st;
        l->prev_i = l->ival;
        l->prev_r = l->rval;
        l->prev_sum = l->val_sum;
        l->prev_len = l->rd.bytes;
        l->have_prev = 1;
        return l->cfg.query_reads <= 1;
    }
    return (unsigned)++l->have_prev >= l->cfg.query_reads;
}
