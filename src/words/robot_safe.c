/* SPDX-License-Identifier: MIT */
/* robot_safe.c - the safe stop after an abort (Ctrl-C): the arm halted, the outputs this
 * context switched on switched off, and what was found reported (docs/robot.md,
 * "Stopping safely"). It never throws: the host calls it after the word was aborted. */
#include <string.h>

#include "robot_internal.h"

/* Slices in which a command still in the link is driven to its end. */
#define STOP_SLICE_MS 100u

/* Let a command the controller already has end: it cannot be taken back, and the
 * controller reads nothing else (not even HALT) until it answers. */
static fbrl_status drain(fbrl_link *l)
{
    for (uint32_t t = 0; t < FBRL_ROBOT_STOP_DRAIN_MS; t += STOP_SLICE_MS) {
        int done = 0;
        fbrl_status st = fbrl_link_poll(l, STOP_SLICE_MS, &done);
        if (st == FBRL_EDISCONNECTED)
            return st;
        if (done)
            return FBRL_OK; /* its own result was the interrupted word's business */
    }
    return FBRL_EBUSY;
}

/* HALT, the outputs off, STATUS and W2 for the report (out->result is the caller's). */
static fbrl_status stop_link(fbrl_link *l, uint32_t outputs, fbrl_robot_stop *out)
{
    fbrl_rapl_status_info si;
    fbrl_rapl_pos pos;
    fbrl_status st;
    uint32_t off;

    if (fbrl_link_busy(l) && (st = drain(l)) != FBRL_OK)
        return st;

    /* the arm first: it is what can hurt */
    st = fbrl_link_cmd(l, FBRL_RAPL_HALT, NULL, 0, 0);
    if (st != FBRL_OK && st != FBRL_ECONTROLLER)
        return st;
    out->halted = st == FBRL_OK;

    /* then the outputs: those STATUS shows on, or, without STATUS, every one we touched */
    st = fbrl_link_status(l, &si);
    if (st == FBRL_EDISCONNECTED)
        return st;
    out->have_status = st == FBRL_OK && (si.have & FBRL_RAPL_ST_OUTPUTS) != 0;
    out->homed = out->have_status && si.homed;
    off = outputs & (out->have_status ? si.outputs : 0xFFFFu);
    for (int n = 1; n <= FBRL_ROBOT_IO_MAX; n++) {
        uint32_t bit = 1u << (n - 1);
        if (!(off & bit))
            continue;
        fbrl_rapl_arg a = fbrl_rapl_int(-n);
        st = fbrl_link_cmd(l, FBRL_RAPL_OUTPUT, &a, 1, 0);
        if (st == FBRL_EDISCONNECTED)
            return st;
        if (st == FBRL_OK)
            out->switched_off |= bit;
    }
    if (out->have_status)
        out->left_on = si.outputs & ~out->switched_off & 0xFFFFu;

    /* where the arm stands now, for the report */
    st = fbrl_link_where(l, FBRL_RAPL_W2, &pos);
    if (st == FBRL_EDISCONNECTED)
        return st;
    if (st == FBRL_OK && pos.nworld >= 6) {
        out->have_where = 1;
        for (int k = 0; k < 6; k++)
            out->where[k] = pos.world[k];
    }
    return out->halted ? FBRL_OK : FBRL_ECONTROLLER;
}

fbrl_status fbrl_robot_safe_stop(fbrl_robot *r, fbrl_robot_stop *out)
{
    fbrl_status st;
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
    st = stop_link(r->link, r->outputs_on, out);
    if (out->halted)
        r->moving = 0;
    if (st == FBRL_EDISCONNECTED)
        r->lost = 1;
    return out->result = st;
}

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
    return out->result = stop_link(link, outputs, out);
}
