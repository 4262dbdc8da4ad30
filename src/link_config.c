/* SPDX-License-Identifier: MIT */
/* link_config.c - the link's settings: the defaults (fbrl_link_config_init) and those a
 * caller changes after init (the line and run-log handlers, the gate), and what it may ask
 * of them. No OS header. */
#include "link_internal.h"

void fbrl_link_config_init(fbrl_link_config *c)
{
    if (!c)
        return;
    c->form = FBRL_RAPL_KEYWORD;
    c->lower_case = 1;
    c->echo_timeout_ms = 100;
    c->reply_timeout_ms = 5000;
    c->wait_timeout_ms = 120000;
    c->max_attempts = 12;
    c->query_reads = 2;
    c->naxes = 5;
    c->arm = 0;
    c->now_us = 0;
    c->clock_ctx = 0;
    c->on_exec = 0;
    c->exec_ctx = 0;
    c->on_line = 0;
    c->line_ctx = 0;
    c->aci = 0;
    c->check_units = 1;
    c->modes = 0;
}

fbrl_status fbrl_link_set_line_handler(fbrl_link *l, fbrl_link_line_fn fn, void *ctx,
                                       fbrl_link_line_fn *old_fn, void **old_ctx)
{
    if (!l)
        return FBRL_EINVAL;
    if (old_fn)
        *old_fn = l->cfg.on_line;
    if (old_ctx)
        *old_ctx = l->cfg.line_ctx;
    l->cfg.on_line = fn;
    l->cfg.line_ctx = ctx;
    return FBRL_OK;
}

fbrl_status fbrl_link_set_gate(fbrl_link *l, fbrl_link_gate_fn fn, void *ctx)
{
    if (!l)
        return FBRL_EINVAL;
    l->gate = fn;
    l->gate_ctx = ctx;
    return FBRL_OK;
}

fbrl_status fbrl_link_unguarded(fbrl_link *l)
{
    if (!l)
        return FBRL_EINVAL;
    l->unguarded = 1;
    return FBRL_OK;
}

fbrl_status fbrl_link_set_exec_handler(fbrl_link *l, fbrl_link_exec_fn fn, void *ctx,
                                       fbrl_link_exec_fn *old_fn, void **old_ctx)
{
    if (!l)
        return FBRL_EINVAL;
    if (old_fn)
        *old_fn = l->cfg.on_exec;
    if (old_ctx)
        *old_ctx = l->cfg.exec_ctx;
    l->cfg.on_exec = fn;
    l->cfg.exec_ctx = ctx;
    return FBRL_OK;
}

fbrl_status fbrl_link_get_form(const fbrl_link *l, fbrl_rapl_form *form)
{
    if (!l || !form)
        return FBRL_EINVAL;
    *form = l->cfg.form;
    return FBRL_OK;
}

fbrl_status fbrl_link_get_naxes(const fbrl_link *l, unsigned *naxes)
{
    if (!l || !naxes)
        return FBRL_EINVAL;
    *naxes = l->cfg.naxes;
    return FBRL_OK;
}
