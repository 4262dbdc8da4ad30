/* SPDX-License-Identifier: MIT */
/* clock.h - monotonic time and sleeping for hosted builds (POSIX: clock_posix.c).
 *
 * The driver core never reads a clock itself: backends hand it their now_us. These
 * are what the POSIX backends, the link layer and the apps use. */
#ifndef FBRL_CLOCK_H
#define FBRL_CLOCK_H

#include "fbrl/export.h"

#include <stdint.h>
#include "fbrl/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Microseconds from an arbitrary fixed point; never goes backwards (CLOCK_MONOTONIC). */
FBRL_API uint64_t fbrl_clock_now_us(void);

/* Sleep at least us microseconds (resumed after signals). FBRL_EIO if the OS refuses. */
FBRL_API fbrl_status fbrl_clock_sleep_us(uint64_t us);

#ifdef __cplusplus
}
#endif
#endif
