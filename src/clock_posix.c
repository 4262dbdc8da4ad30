/* SPDX-License-Identifier: MIT */
/* clock_posix.c - fbrl/clock.h on POSIX: CLOCK_MONOTONIC and clock_nanosleep. */
#include <errno.h>
#include <time.h>
#include "fbrl/clock.h"

uint64_t fbrl_clock_now_us(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0)
        return 0; /* cannot happen with CLOCK_MONOTONIC on POSIX systems */
    return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

fbrl_status fbrl_clock_sleep_us(uint64_t us)
{
    /* An absolute deadline, so that a signal does not stretch the total sleep. */
    struct timespec until;
    if (clock_gettime(CLOCK_MONOTONIC, &until) != 0)
        return FBRL_EIO;
    uint64_t ns = (uint64_t)until.tv_nsec + (us % 1000000u) * 1000u;
    until.tv_sec += (time_t)(us / 1000000u + ns / 1000000000u);
    until.tv_nsec = (long)(ns % 1000000000u);
    int rc;
    while ((rc = clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &until, NULL)) == EINTR)
        ;
    return rc == 0 ? FBRL_OK : FBRL_EIO;
}
