/* SPDX-License-Identifier: MIT */
/* link_outcome.c - what a command ended with (docs/link.md 3.9): its fate, what the
 * controller was last seen doing, how many times it ran, the controller's error, the
 * values of a query, the link's counters. Reads only. No OS header. */
#include "link_internal.h"

fbrl_status fbrl_link_error(const fbrl_link *l, int *code, const char **text)
{
    if (!l)
        return FBRL_EINVAL;
    int have = l->result == FBRL_ECONTROLLER;
    if (code)
        *code = have ? l->err_code : -1;
    if (text)
        *text = !have ? "" : l->err_code >= 0 ? l->err_text : "code unknown";
    return FBRL_OK;
}

fbrl_link_fate fbrl_link_fate_of(fbrl_status result)
{
    switch (result) {
    case FBRL_OK: return FBRL_LINK_RAN;
    case FBRL_ECONTROLLER: return FBRL_LINK_REFUSED;
    case FBRL_EMAYBE: return FBRL_LINK_MAY_HAVE_RUN;
    default: return FBRL_LINK_NOT_RUN;
    }
}

/* Short: fbrlmon puts it in a one-line message. */
static const char *seen_text(int seen)
{
    switch (seen) {
    case SEEN_SILENT: return "nothing came back after its CR";
    case SEEN_AMBIGUOUS: return "its CR may not have arrived (reply and probe damaged)";
    case SEEN_STARTED: return "it started; its reply stopped before the prompt";
    case SEEN_BUSY: return "it started and was still busy";
    case SEEN_UNREADABLE: return "it ran; no reply could be believed (damaged, or never twice the same)";
    case SEEN_UNSETTLED: return "it ran; reply damaged, STATUS unreadable";
    case SEEN_SAME_ERROR: return "it ran; reply damaged, STATUS shows the earlier error";
    default: return "it was not sent";
    }
}

fbrl_status fbrl_link_outcome_get(const fbrl_link *l, fbrl_link_outcome *out)
{
    if (!l || !out)
        return FBRL_EINVAL;
    if (l->busy)
        return FBRL_ESTATE;
    out->fate = l->stats.commands ? fbrl_link_fate_of(l->result) : FBRL_LINK_FATE_NONE;
    out->status = l->result;
    out->cause = l->cause;
    out->code = l->result == FBRL_ECONTROLLER ? l->err_code : -1;
    out->seen = seen_text(l->seen);
    out->runs = l->runs;
    out->maybe_runs = l->maybe_runs;
    return FBRL_OK;
}

fbrl_status fbrl_link_get_runs(const fbrl_link *l, unsigned *runs, unsigned *maybe_runs)
{
    if (!l)
        return FBRL_EINVAL;
    if (runs)
        *runs = l->own_report ? 0 : l->runs;
    if (maybe_runs)
        *maybe_runs = l->own_report ? 0 : l->maybe_runs;
    return FBRL_OK;
}

const fbrl_rapl_pos *fbrl_link_last_pos(const fbrl_link *l) { return l ? &l->pos : 0; }
const fbrl_rapl_status_info *fbrl_link_last_status(const fbrl_link *l) { return l ? &l->st : 0; }

/* The last command has finished, succeeded and gave a reply of this kind. */
static int reply_is(const fbrl_link *l, fbrl_link_reply kind)
{
    return !l->busy && l->result == FBRL_OK && l->kind == kind;
}

fbrl_status fbrl_link_last_int(const fbrl_link *l, long *v)
{
    if (!l || !v)
        return FBRL_EINVAL;
    if (!reply_is(l, FBRL_LINK_REPLY_INT))
        return FBRL_ESTATE;
    *v = l->ival;
    return FBRL_OK;
}

fbrl_status fbrl_link_last_real(const fbrl_link *l, double *v)
{
    if (!l || !v)
        return FBRL_EINVAL;
    if (!reply_is(l, FBRL_LINK_REPLY_REAL))
        return FBRL_ESTATE;
    *v = l->rval;
    return FBRL_OK;
}

fbrl_status fbrl_link_get_stats(const fbrl_link *l, fbrl_link_stats *out)
{
    if (!l || !out)
        return FBRL_EINVAL;
    *out = l->stats;
    return FBRL_OK;
}
