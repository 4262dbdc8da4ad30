/* SPDX-License-Identifier: MIT */
/* robot_guard.c - what a motion guard (fbrl_robot_set_guard; the work cell's, fbrl/cell.h)
 * may ask the robot: the arm's joints (W2) once it stands. The hook itself is robot_svc.c's. */
#include <string.h>

#include "robot_internal.h"

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
