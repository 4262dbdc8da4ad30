/* robot_guard.c - the hook every motion word passes before it sends a byte (the work cell's
 * collision guard, fbrl/cell.h, sits on it), and what a guard may ask the robot: the arm's
 * joints (W2) and whether the arm may have gone where the host cannot follow. */
#include <string.h>

#include "robot_internal.h"

fbrl_status fbrl_robot_set_guard(fbrl_robot *r, const fbrl_robot_guard *g)
{
    if (!r)
        return FBRL_EINVAL;
    if (g)
        r->guard = *g;
    else
        memset(&r->guard, 0, sizeof r->guard);
    return FBRL_OK;
}

unsigned long fbrl_robot_where_epoch(const fbrl_robot *r) { return r ? r->where_epoch : 0; }

void rb_where_lost(fbrl_robot *r) { r->where_epoch++; }

fbrl_status rb_guard(fbrl_robot *r, const rb_word *w, fbrl_robot_move *m)
{
    m->word = w->name;
    return r->guard.check ? r->guard.check(r->guard.ctx, r, m) : FBRL_OK;
}

fbrl_status rb_guard_done(fbrl_robot *r, const fbrl_robot_move *m, fbrl_status result)
{
    if (r->guard.done)
        r->guard.done(r->guard.ctx, r, m, result);
    return result;
}

fbrl_status fbrl_robot_joints(fbrl_robot *r, const char *word, double *q, unsigned *n)
{
    rb_word w;
    fbrl_rapl_pos p;
    fbrl_status st;
    if (!r || !q || !n)
        return FBRL_EINVAL;
    memset(&w, 0, sizeof w);
    w.name = word ? word : "GUARD";
    if ((st = rb_online(r)) != FBRL_OK || (st = rb_still(r, &w)) != FBRL_OK)
        return st;
    if ((st = rb_link_result(r, &w, fbrl_link_where(r->link, FBRL_RAPL_W2, &p))) != FBRL_OK)
        return st;
    if (p.njoints == 0)
        return rb_fail_st(r, &w, FBRL_EPROTOCOL, "W2 had no JOINTS line");
    for (unsigned k = 0; k < p.njoints; k++)
        q[k] = p.joints[k];
    *n = p.njoints;
    return FBRL_OK;
}
