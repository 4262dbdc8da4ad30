/* SPDX-License-Identifier: MIT */
/* mon_tasks.c - fbrlmon's side of the engine's tasks: run them from the prompt's key
 * wait (fbrl_vm_run_tasks, the host event loop API) and let them end before exit. */
#include <poll.h>
#include <stdio.h>
#include <time.h>

#include "mon_safe.h"
#include "mon_tasks.h"

#define US_PER_MS      1000u
#define FINISH_POLL_MS 100 /* longest sleep while waiting for the tasks at exit */

static uint64_t now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

int mon_tasks_poll_ms(mon *m, int max_ms)
{
    uint64_t wake = 0, now;
    int live = 0;
    if (fbrl_vm_run_tasks(m->vm, &wake, &live) != FBRL_OK || !live)
        return max_ms;
    now = now_us();
    if (wake <= now)
        return 0;
    return wake - now >= (uint64_t)max_ms * US_PER_MS ? max_ms
                                                      : (int)((wake - now + US_PER_MS - 1) / US_PER_MS);
}

void mon_tasks_finish(mon *m)
{
    int said = 0;
    for (;;) {
        uint64_t wake = 0;
        int live = 0;
        if (mon_safe_pending()) /* Ctrl-C: the engine stops every task at its next run */
            fbrl_vm_interrupt(m->vm);
        if (fbrl_vm_run_tasks(m->vm, &wake, &live) != FBRL_OK || !live)
            return;
        if (!said) {
            fprintf(stderr, "fbrlmon: waiting for %d task%s to end (Ctrl-C stops them)\n", live,
                    live == 1 ? "" : "s");
            said = 1;
        }
        uint64_t now = now_us();
        int ms = wake <= now ? 0
                 : wake - now >= (uint64_t)FINISH_POLL_MS * US_PER_MS
                     ? FINISH_POLL_MS
                     : (int)((wake - now + US_PER_MS - 1) / US_PER_MS);
        if (ms > 0)
            poll(NULL, 0, ms);
    }
}
