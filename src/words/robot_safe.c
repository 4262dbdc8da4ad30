/* SPDX-License-Identifier: MIT */
/* robot_safe.c - the safe stop after an abort (Ctrl-C): the link's safe stop
 * (fbrl_link_safe_stop: the arm halted, the outputs this context switched on switched off,
 * what is known afterwards) with what the robot words know besides: the motion that was
 * running (docs/robot.md, "Stopping safely"). It never throws: the host calls it after
 * the word was aborted. */
#include <string.h>

#include "robot_internal.h"

fbrl_status fbrl_robot_safe_stop(fbrl_robot *r, fbrl_robot_stop *out)
{
    if (!out)
        return FBRL_EINVAL;
    memset(out, 0, sizeof *out);
    if (!r)
        return out->result = FBRL_EINVAL;
    out->was_moving = r->moving;
    rb_where_lost(r); /* wherever the arm stops, the host did not choose it */
    memcpy(out->motion, r->motion, sizeof out->motion);
    if (!r->link)
        return out->result = FBRL_EOFFLINE;
    if (r->lost)
        return out->result = FBRL_EDISCONNECTED;
    out->result = fbrl_link_safe_stop(r->link, r->outputs_on, FBRL_ROBOT_STOP_DRAIN_MS, &out->stop);
    if (out->stop.halted)
        r->moving = 0;
    if (out->result == FBRL_EDISCONNECTED)
        r->lost = 1;
    return out->result;
}

/* The same report for a host that keeps the motion and the outputs itself (the Python
 * bindings): the link's stop, with the motion it names. */
fbrl_status fbrl_robot_safe_stop_link(fbrl_link *link, uint32_t outputs, const char *motion, fbrl_robot_stop *out)
{
    if (!out)
        return FBRL_EINVAL;
    memset(out, 0, sizeof *out);
    if (motion) {
        size_t n = strlen(motion);
        n = n < sizeof out->motion ? n : sizeof out->motion - 1;
        out->was_moving = 1;
        memcpy(out->motion, motion, n);
    }
    if (!link)
        return out->result = FBRL_EOFFLINE;
    return out->result = fbrl_link_safe_stop(link, outputs, FBRL_ROBOT_STOP_DRAIN_MS, &out->stop);
}
