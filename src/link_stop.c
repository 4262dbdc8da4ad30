/* SPDX-License-Identifier: MIT */
/* link_stop.c - the safe stop on a link (fbrl_link_safe_stop): the arm halted, the
 * outputs the caller switched on switched off, and what is known afterwards said truly
 * (docs/link.md 1, "The safe stop"). The robot words' stop after Ctrl-C is this one
 * (fbrl_robot_safe_stop); a program or a binding without the robot words calls it itself.
 * Blocking, bounded by the link's timeouts and drain_ms. No OS header. */
#include "link_internal.h"

#define IO_MASK  ((1u << FBRL_LINK_IO_MAX) - 1u)
#define SLICE_MS 100u /* a command still in the link is driven to its end in slices */

/* Let a command the controller already has end: it cannot be taken back, and the
 * controller reads nothing else (not even HALT) until it answers. */
static fbrl_status drain(fbrl_link *l, uint32_t drain_ms)
{
    for (uint32_t t = 0; t < drain_ms; t += SLICE_MS) {
        int done = 0;
        fbrl_status st = fbrl_link_poll(l, SLICE_MS, &done);
        if (st == FBRL_EDISCONNECTED)
            return st;
        if (done)
            return FBRL_OK; /* its own result was the interrupted caller's business */
    }
    return FBRL_EBUSY;
}

fbrl_status fbrl_link_safe_stop(fbrl_link *l, uint32_t outputs_on, uint32_t drain_ms, fbrl_link_stop *out)
{
    fbrl_rapl_status_info si;
    fbrl_rapl_pos pos;
    fbrl_status st;
    uint32_t off, maybe = 0;

    if (!out)
        return FBRL_EINVAL;
    *out = (fbrl_link_stop){0};
    out->unknown = IO_MASK; /* until STATUS or an OUTPUT says otherwise */
    out->status_result = FBRL_ESTATE;
    if (!l || !l->u)
        return out->result = FBRL_EINVAL;
    if (fbrl_link_busy(l) && (st = drain(l, drain_ms)) != FBRL_OK)
        return out->result = st;

    /* the arm first: it is what can hurt */
    st = fbrl_link_cmd(l, FBRL_RAPL_HALT, 0, 0, 0);
    if (st != FBRL_OK && st != FBRL_ECONTROLLER)
        return out->result = st;
    out->halted = st == FBRL_OK;

    /* then the outputs: those STATUS shows on, or, when it does not show them, every one
     * the caller switched on. A RAPL-II STATUS has no OUTPUTS line (fbrlsim prints one
     * with --status-extra): the others' state is then not known, and said so. */
    st = fbrl_link_status(l, &si);
    out->status_result = st;
    if (st == FBRL_EDISCONNECTED)
        return out->result = st;
    out->have_status = st == FBRL_OK;
    out->homed = out->have_status && si.homed;
    out->have_outputs = out->have_status && (si.have & FBRL_RAPL_ST_OUTPUTS) != 0;
    off = outputs_on & (out->have_outputs ? si.outputs : IO_MASK) & IO_MASK;
    for (int n = 1; n <= FBRL_LINK_IO_MAX; n++) {
        uint32_t bit = 1u << (n - 1);
        if (!(off & bit))
            continue;
        fbrl_rapl_arg a = fbrl_rapl_int(-n);
        st = fbrl_link_cmd(l, FBRL_RAPL_OUTPUT, &a, 1, 0);
        if (st == FBRL_EDISCONNECTED)
            return out->result = st;
        if (st == FBRL_OK)
            out->switched_off |= bit;
        else
            out->off_failed |= bit;
        if (st == FBRL_EMAYBE)
            maybe |= bit;
    }
    if (out->have_outputs) {
        out->left_on = si.outputs & IO_MASK & ~out->switched_off & ~maybe;
        out->unknown = maybe;
    } else {
        out->unknown = IO_MASK & ~out->switched_off;
    }

    /* where the arm stands now, for the report */
    st = fbrl_link_where(l, FBRL_RAPL_W2, &pos);
    if (st == FBRL_EDISCONNECTED)
        return out->result = st;
    if (st == FBRL_OK && pos.nworld >= 6) {
        out->have_where = 1;
        for (int k = 0; k < 6; k++)
            out->where[k] = pos.world[k];
    }
    return out->result = out->halted ? FBRL_OK : FBRL_ECONTROLLER;
}
