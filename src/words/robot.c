/* SPDX-License-Identifier: MIT */
/* robot.c - binding the FBRL robot words into a VM: each word set's table (robot_motion.c
 * robot_rapl.c robot_teach.c robot_param.c robot_line.c robot_comm.c robot_io.c) is
 * defined by vmx.h's table call; each word fetches its parameters first (RB_WORD).
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

/* The word tables, in this order: HELP and WORDS list the words as they were defined. */
static const size_t one = 1;
static const struct {
    const rb_word *t;
    const size_t *n;
} tables[] = {
    {rb_motion_words, &rb_motion_nwords},
    {rb_rapl_words, &rb_rapl_nwords},
    {rb_teach_words, &rb_teach_nwords},
    {rb_param_words, &rb_param_nwords},
    {rb_line_words, &rb_line_nwords},
    {rb_comm_words, &rb_comm_nwords},
    {&rb_comm_asc, &one},
    {rb_io_words, &rb_io_nwords},
    {rb_import_words, &rb_import_nwords},
};
#define NTABLES (sizeof tables / sizeof tables[0])

const char *fbrl_robot_word(size_t i)
{
    for (size_t k = 0; k < NTABLES; k++) {
        if (i < *tables[k].n)
            return tables[k].t[i].name;
        i -= *tables[k].n;
    }
    return NULL;
}

/* Input handlers (docs/tasks.md): a word run as a task when an input device changes to a
 * state (ONSIG, every time) or once it is in that state (WHEN). */
/* (clang-format cannot lay out strings joined to a macro's string) */
/* clang-format off */
static const char rb_handlers[] =
    ": (ONSIG) " FBRL_DOC_SRC("( xt dev state -- )") " BEGIN 2DUP INPUT-EDGE 2 PICK EXECUTE AGAIN ;\n"
    ": ONSIG "
        FBRL_DOC_SRC("( xt dev state task -- ) \\ run xt as the task each time the input device "
                     "turns to state") "\n"
    "   >R 3 ['] (ONSIG) R> START-WITH ;\n"
    ": (WHEN) " FBRL_DOC_SRC("( xt dev state -- )") " BEGIN 2DUP 86400000 WAIT-INPUT UNTIL 2DROP EXECUTE ;\n"
    ": WHEN "
        FBRL_DOC_SRC("( xt dev state task -- ) \\ run xt as the task once the input device is in state") "\n"
    "   >R 3 ['] (WHEN) R> START-WITH ;\n";
/* clang-format on */

fbrl_status fbrl_robot_install(fbrl_vm *vm, fbrl_robot *r, fbrl_link *link, fbrl_glossary *g)
{
    fbrl_cell xt;
    if (!vm || !r)
        return FBRL_EINVAL;
    memset(r, 0, sizeof *r);
    r->vm = vm;
    r->g = g;
    r->last_error = -1;
    fbrl_uart_config def = FBRL_UART_CONFIG_DEFAULT;
    r->comm = def;
    if (fbrl_vm_compiling(vm))
        return FBRL_ESTATE;
    /* GET-CAL-POINTS' line buffer lives in the data space: the words it runs parse it */
    if (fbrl_vmx_create(vm, "(ROBOT-TIB)", 11, NULL, FBRL_ROBOT_TIB + FBRL_LINK_LINE_MAX, NULL, NULL, FBRL_DOC_TEXT("( -- a )"),
                        FBRL_DOC_TEXT("robot words' line buffer"), &r->tib, NULL) != FBRL_OK)
        return FBRL_ENOMEM;
    fbrl_status st = FBRL_OK;
    for (size_t k = 0; st == FBRL_OK && k < NTABLES; k++) {
        /* ASC is F-PC's: a VM that has one keeps it */
        if (tables[k].t == &rb_comm_asc && fbrl_vmx_find(vm, "ASC", 3, &xt) == FBRL_OK)
            continue;
        st = fbrl_vmx_define_table(vm, tables[k].t, *tables[k].n, r);
    }
    if (st == FBRL_OK)
        st = fbrl_vm_eval(vm, rb_handlers, strlen(rb_handlers));
    if (st == FBRL_OK)
        st = fbrl_robot_set_link(r, link);
    return st;
}

fbrl_status fbrl_robot_set_link(fbrl_robot *r, fbrl_link *link)
{
    if (!r)
        return FBRL_EINVAL;
    if (r->link && r->link != link && r->link->gate == rb_link_gate && r->link->gate_ctx == r)
        fbrl_link_set_gate(r->link, NULL, NULL); /* the link it leaves goes on without it */
    if (link)
        fbrl_link_set_gate(link, rb_link_gate, r); /* every line passes the motion guard */
    r->link = link;
    r->lost = 0;
    r->armed = NULL;
    /* a controller we did not watch may be moving: the next motion asks it first */
    r->moving = link != NULL;
    r->motion[0] = 0;
    rb_where_lost(r);
    if (link && link->u)
        fbrl_uart_get_config(link->u, &r->comm);
    rb_port_writer(r);
    return FBRL_OK;
}

fbrl_status fbrl_robot_set_relink(fbrl_robot *r, fbrl_status (*fn)(void *ctx, fbrl_robot *r), void *ctx)
{
    if (!r)
        return FBRL_EINVAL;
    r->relink = fn;
    r->relink_ctx = ctx;
    return FBRL_OK;
}

int fbrl_robot_lost(const fbrl_robot *r) { return r ? r->lost : 0; }

int fbrl_robot_last_error(const fbrl_robot *r) { return r ? r->last_error : -1; }

fbrl_status fbrl_robot_base_offset(const fbrl_robot *r, double base[4])
{
    if (!r || !base)
        return FBRL_EINVAL;
    memcpy(base, r->base, sizeof r->base);
    return FBRL_OK;
}

fbrl_status fbrl_robot_set_base_offset(fbrl_robot *r, const double base[4])
{
    if (!r || !base)
        return FBRL_EINVAL;
    for (int k = 0; k < 4; k++)
        if (!isfinite(base[k]))
            return FBRL_ENONFINITE;
    memcpy(r->base, base, sizeof r->base);
    return FBRL_OK;
}

void fbrl_robot_set_console(fbrl_robot *r, fbrl_robot_progress_fn progress, void *ctx, int tell)
{
    if (!r)
        return;
    r->progress = progress;
    r->progress_ctx = ctx;
    r->tell = tell != 0;
}

void fbrl_robot_set_watch(fbrl_robot *r, fbrl_robot_watch_fn fn, void *ctx)
{
    if (!r)
        return;
    r->watch = fn;
    r->watch_ctx = ctx;
}
