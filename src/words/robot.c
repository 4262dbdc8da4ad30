/* robot.c - binding the FBRL robot words into a VM: each word set's table (robot_motion.c
 * robot_rapl.c robot_teach.c robot_param.c robot_line.c robot_comm.c robot_io.c) is
 * defined with its parameters fetched by robot_param.c before the word runs.
 *
 * Every word that talks to the controller goes through the robot's fbrl_link, so each
 * command line is echo-verified before its CR is sent. Locations come from the host
 * side (6 floats in the VM's data space); a word that moves to one first defines a
 * scratch controller point with POINT, then moves to that point. docs/robot.md tells
 * the rules, docs/glossary.md lists every word with the text it sends. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "robot_internal.h"

static fbrl_status tramp(fbrl_vm *vm, void *arg)
{
    const fbrl_robot_bind *b = arg;
    const rb_word *w = b->word;
    rb_val v[RB_MAXP];
    (void)vm;
    memset(v, 0, sizeof v);
    fbrl_status st = rb_params(b->r, w, v);
    if (st != FBRL_OK) return st;
    return w->fn(b->r, w, v);
}

static fbrl_status rb_define(fbrl_robot *r, const rb_word *t, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        if (r->nbind >= FBRL_ROBOT_MAX_WORDS) return FBRL_ENOSPC;
        fbrl_robot_bind *b = &r->bind[r->nbind++];
        b->r = r;
        b->word = &t[i];
        fbrl_status st = fbrl_vm_define(r->vm, t[i].name, tramp, b, t[i].stack, t[i].help);
        if (st != FBRL_OK) return st;
    }
    return FBRL_OK;
}

fbrl_status fbrl_robot_install(fbrl_vm *vm, fbrl_robot *r, fbrl_link *link, fbrl_glossary *g)
{
    fbrl_hdr *h;
    if (!vm || !r) return FBRL_EINVAL;
    memset(r, 0, sizeof *r);
    r->vm = vm;
    r->g = g;
    r->last_error = -1;
    fbrl_uart_config def = FBRL_UART_CONFIG_DEFAULT;
    r->comm = def;
    if (vm->defining) return FBRL_ESTATE;
    /* GET-CAL-POINTS' line buffer lives in the data space: the words it runs parse it */
    if (fbrl__new_word(vm, "(ROBOT-TIB)", 11, K_VAR, "( -- a )", "robot words' line buffer", &h) ||
        fbrl__allot(vm, FBRL_ROBOT_TIB))
        return FBRL_ENOMEM;
    r->tib = h->body;
    memset((void *)h->body, 0, FBRL_ROBOT_TIB);
    /* in this order: HELP and WORDS list them as they were defined */
    static const struct { const rb_word *t; const size_t *n; } tables[] = {
        { rb_motion_words, &rb_motion_nwords }, { rb_rapl_words, &rb_rapl_nwords },
        { rb_teach_words, &rb_teach_nwords },   { rb_param_words, &rb_param_nwords },
        { rb_line_words, &rb_line_nwords },     { rb_comm_words, &rb_comm_nwords },
    };
    fbrl_status st = FBRL_OK;
    for (size_t k = 0; st == FBRL_OK && k < sizeof tables / sizeof tables[0]; k++)
        st = rb_define(r, tables[k].t, *tables[k].n);
    if (st == FBRL_OK && fbrl__find(r->vm, "ASC", 3) < 0) {
        st = rb_define(r, &rb_comm_asc, 1);
        if (st == FBRL_OK) HDR(r->vm, fbrl__find(r->vm, "ASC", 3))->flags |= FI;
    }
    if (st == FBRL_OK) st = rb_define(r, rb_io_words, rb_io_nwords);
    if (st == FBRL_OK) st = fbrl_robot_set_link(r, link);
    return st == FBRL_ENOSPC ? FBRL_ENOMEM : st;
}

fbrl_status fbrl_robot_set_link(fbrl_robot *r, fbrl_link *link)
{
    if (!r) return FBRL_EINVAL;
    r->link = link;
    r->lost = 0;
    /* a controller we did not watch may be moving: the next motion asks it first */
    r->moving = link != NULL;
    r->motion[0] = 0;
    if (link && link->u) fbrl_uart_get_config(link->u, &r->comm);
    rb_port_writer(r);
    return FBRL_OK;
}

fbrl_status fbrl_robot_set_relink(fbrl_robot *r, fbrl_status (*fn)(void *ctx, fbrl_robot *r), void *ctx)
{
    if (!r) return FBRL_EINVAL;
    r->relink = fn;
    r->relink_ctx = ctx;
    return FBRL_OK;
}

int fbrl_robot_lost(const fbrl_robot *r) { return r ? r->lost : 0; }

int fbrl_robot_last_error(const fbrl_robot *r) { return r ? r->last_error : -1; }
