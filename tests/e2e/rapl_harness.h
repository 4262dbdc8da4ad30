/* SPDX-License-Identifier: MIT */
/* rapl_harness.h - shared by the RAPL e2e tests and bench_rapl: start the real fbrlsim
 * binary on a pseudo-terminal, open it with the POSIX uart backend and bind a link. */
#ifndef RAPL_HARNESS_H
#define RAPL_HARNESS_H

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "fbrl/clock.h"
#include "fbrl/link.h"
#include "fbrl/uart_posix.h"

typedef struct rig {
    pid_t pid;
    char path[256];
    fbrl_uart_posix port;
    fbrl_uart uart;
    uint8_t rx[4096], tx[1024];
    fbrl_link link;
} rig;

/* Start fbrlsim with the given extra arguments (NULL-terminated), read the device path
 * it prints first, and open it: 8 data bits, the parity given, at baud, flow control as
 * asked. 0 on success. */
static inline int rig_start_parity(rig *r, const char *sim, const char *const *args, uint32_t baud,
                                   fbrl_flow flow, fbrl_parity parity, const fbrl_link_config *cfg)
{
    int pipefd[2];
    memset(r, 0, sizeof *r);
    if (pipe(pipefd) != 0)
        return -1;
    const char *argv[32];
    int n = 0;
    argv[n++] = sim;
    argv[n++] = "--status-extra"; /* libfbrl reads the outputs from fbrlsim's own STATUS lines */
    for (; args && *args && n < 31; args++)
        argv[n++] = *args;
    argv[n] = NULL;
    r->pid = fork();
    if (r->pid < 0)
        return -1;
    if (r->pid == 0) {
        dup2(pipefd[1], 1);
        close(pipefd[0]);
        close(pipefd[1]);
        execv(sim, (char *const *)argv);
        _exit(127);
    }
    close(pipefd[1]);
    size_t k = 0;
    char c;
    while (k + 1 < sizeof r->path && read(pipefd[0], &c, 1) == 1 && c != '\n')
        r->path[k++] = c;
    r->path[k] = '\0';
    close(pipefd[0]);
    if (k == 0) {
        fprintf(stderr, "fbrlsim printed no path\n");
        return -1;
    }
    fbrl_uart_config uc = FBRL_UART_CONFIG_DEFAULT;
    uc.baud = baud;
    uc.flow = flow;
    uc.parity = parity;
    fbrl_status st = fbrl_uart_posix_open(&r->port, &r->uart, r->path, &uc, r->rx, sizeof r->rx, r->tx,
                                          sizeof r->tx, NULL);
    if (st != FBRL_OK) {
        fprintf(stderr, "open %s: %s\n", r->path, fbrl_status_str(st));
        return -1;
    }
    st = fbrl_link_init(&r->link, &r->uart, cfg);
    if (st != FBRL_OK) {
        fprintf(stderr, "link init: %s\n", fbrl_status_str(st));
        return -1;
    }
    return 0;
}

/* The same with 8N1. */
static inline int rig_start(rig *r, const char *sim, const char *const *args, uint32_t baud, fbrl_flow flow,
                            const fbrl_link_config *cfg)
{
    return rig_start_parity(r, sim, args, baud, flow, FBRL_PARITY_NONE, cfg);
}

static inline void rig_stop(rig *r)
{
    if (r->uart.open)
        fbrl_uart_close(&r->uart);
    if (r->pid > 0) {
        kill(r->pid, SIGTERM);
        waitpid(r->pid, NULL, 0);
        r->pid = 0;
    }
}

/* A private scratch directory for state and log files. */
static inline void rig_tmpdir(char *dir, size_t cap, const char *tag)
{
    snprintf(dir, cap, "/tmp/fbrl-%s-XXXXXX", tag);
    if (!mkdtemp(dir))
        dir[0] = '\0';
}

#endif
