/* SPDX-License-Identifier: MIT */
/* cell_rig.h - shared by the guard's C tests (guard_link.c, guard_random.c): the real fbrlsim
 * with a work cell on a pty (rapl_harness.h), and a VM with the glossary, the robot words and
 * the work cell's words over its link, the same cell included. Static inline, like
 * rapl_harness.h. */
#ifndef CELL_RIG_H
#define CELL_RIG_H

#include "rapl_harness.h"
#include "fbrl/cell_words.h"
#include "fbrl/glossary.h"
#include "fbrl/robot.h"
#include "fbrl/vm.h"
#include "fbrl/vmx.h"
#include "support/vm_host.h"

typedef struct cell_rig {
    rig r;
    fbrl_vm *vm;
    fbrl_glossary g;
    fbrl_robot robot;
    fbrl_cell_words cw;
    vmh_text out; /* what the VM printed */
} cell_rig;

/* fbrlsim --cell CELL ARGS... (args NULL-terminated), the link at 38400 baud with XON/XOFF,
 * the VM in mem (size bytes, 16-byte aligned) with the host's clock (now_us and sleep_ms; NULL:
 * the real one) and stdio files, CELL included. 0 when all of it is up; else -1, said why. */
static inline int cell_rig_start(cell_rig *c, const char *sim, const char *cell, const char *const *args,
                                 unsigned char *mem, size_t size, uint64_t (*now_us)(void *),
                                 void (*sleep_ms)(void *, uint32_t))
{
    const char *argv[24];
    char inc[600];
    int n = 0;
    argv[n++] = "--cell";
    argv[n++] = cell;
    for (; args && *args && n < 23; args++)
        argv[n++] = *args;
    argv[n] = NULL;
    fbrl_link_config lc;
    fbrl_link_config_init(&lc);
    lc.echo_timeout_ms = 500; /* a loaded CI machine can stall this process */
    if (rig_start(&c->r, sim, argv, 38400, FBRL_FLOW_XONXOFF, &lc) != 0 || fbrl_link_connect(&c->r.link) != FBRL_OK) {
        fprintf(stderr, "FAIL: no fbrlsim\n");
        rig_stop(&c->r);
        return -1;
    }
    fbrl_vm_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.mem = mem;
    cfg.mem_size = size;
    cfg.host.user = &c->out;
    cfg.host.write = vmh_write;
    vmh_use_files(&cfg.host);
    vmh_use_clock(&cfg.host);
    if (now_us)
        cfg.host.now_us = now_us, cfg.host.sleep_ms = sleep_ms;
    snprintf(inc, sizeof inc, "INCLUDE %s", cell);
    if (fbrl_vm_create(&c->vm, &cfg) != FBRL_OK || fbrl_glossary_install(c->vm, &c->g) != FBRL_OK ||
        fbrl_robot_install(c->vm, &c->robot, &c->r.link, &c->g) != FBRL_OK ||
        fbrl_cell_install(c->vm, &c->cw, &c->robot, &c->g) != FBRL_OK ||
        fbrl_vm_eval(c->vm, inc, strlen(inc)) != FBRL_OK) {
        fprintf(stderr, "FAIL: the VM with the cell: %s\n", c->vm ? fbrl_vm_last_error(c->vm)->message : "");
        rig_stop(&c->r);
        return -1;
    }
    return 0;
}

static inline void cell_rig_stop(cell_rig *c)
{
    fbrl_glossary_finish(&c->g);
    rig_stop(&c->r);
}

#endif
