/* SPDX-License-Identifier: MIT */
/* sim_msg.c - error messages for whoever starts the emulator (option, file and
 * OS errors), shared by every part, so it depends on none of them. */
#include "sim_internal.h"

#include <stdarg.h>

void sim_seterr(char *err, size_t errlen, const char *fmt, ...)
{
    va_list ap;
    if (!err || !errlen)
        return;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
}
