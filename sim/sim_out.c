/* SPDX-License-Identifier: MIT */
/* sim_out.c - the text of one reply, collected while a command runs and sent
 * by the terminal (sim_term.c) when it is done, so a reply is never interleaved. */
#include "sim_cmd.h"

#include <stdarg.h>
#include <stdlib.h>

void sim_out_printf(sim_out *o, const char *fmt, ...)
{
    va_list ap;
    int n;
    va_start(ap, fmt);
    n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0)
        return;
    if (o->len + (size_t)n + 1 > o->cap) {
        size_t cap = (o->cap ? o->cap * 2 : 1024) + (size_t)n;
        char *b = realloc(o->buf, cap);
        if (!b)
            return;
        o->buf = b;
        o->cap = cap;
    }
    va_start(ap, fmt);
    vsnprintf(o->buf + o->len, o->cap - o->len, fmt, ap);
    va_end(ap);
    o->len += (size_t)n;
}
