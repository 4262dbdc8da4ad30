/* SPDX-License-Identifier: MIT */
/* vm_host.h - the VM host callbacks the test programs share: console output into a
 * buffer, source files through stdio, the POSIX clock and local time. Static inline, like
 * tests/e2e/rapl_harness.h, so that a test includes it with no object of its own and no
 * warning for the callbacks it does not use. */
#ifndef FBRL_TEST_VM_HOST_H
#define FBRL_TEST_VM_HOST_H

#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "fbrl/clock.h"
#include "fbrl/vm.h"

/* A NUL-terminated text that keeps what fits and drops the rest. */
typedef struct vmh_text {
    char s[1 << 16];
    size_t n;
} vmh_text;

static inline void vmh_put(vmh_text *t, const char *s, size_t n)
{
    size_t room = sizeof t->s - 1 - t->n;
    if (n > room)
        n = room;
    memcpy(t->s + t->n, s, n);
    t->n += n;
    t->s[t->n] = 0;
}

/* host.write when host.user is a vmh_text. */
static inline void vmh_write(void *user, const char *s, size_t n) { vmh_put(user, s, n); }

/* ---- source files (INCLUDED) through stdio ---- */
static inline fbrl_status vmh_file_open(void *user, const char *path, void **handle)
{
    (void)user;
    FILE *f = fopen(path, "r");
    if (!f)
        return FBRL_ENOENT;
    *handle = f;
    return FBRL_OK;
}

static inline fbrl_status vmh_file_read_line(void *user, void *handle, char *buf, size_t cap, size_t *len)
{
    (void)user;
    size_t n = 0;
    int c;
    while ((c = fgetc((FILE *)handle)) != EOF && c != '\n') {
        if (n >= cap)
            return FBRL_ENOSPC;
        buf[n++] = (char)c;
    }
    if (c == EOF && n == 0)
        return FBRL_EEOF;
    *len = n;
    return FBRL_OK;
}

static inline void vmh_file_close(void *user, void *handle)
{
    (void)user;
    fclose(handle);
}

static inline void vmh_use_files(fbrl_vm_host *host)
{
    host->file_open = vmh_file_open;
    host->file_read_line = vmh_file_read_line;
    host->file_close = vmh_file_close;
}

/* ---- time: the library's POSIX clock, local time for TIME&DATE ---- */
static inline uint64_t vmh_now_us(void *user)
{
    (void)user;
    return fbrl_clock_now_us();
}

static inline void vmh_sleep_ms(void *user, uint32_t ms)
{
    (void)user;
    fbrl_clock_sleep_us((uint64_t)ms * 1000u);
}

static inline void vmh_time_date(void *user, int out[6])
{
    time_t now = time(NULL);
    struct tm tm;
    (void)user;
    localtime_r(&now, &tm);
    out[0] = tm.tm_sec;
    out[1] = tm.tm_min;
    out[2] = tm.tm_hour;
    out[3] = tm.tm_mday;
    out[4] = tm.tm_mon + 1;
    out[5] = tm.tm_year + 1900;
}

static inline void vmh_use_clock(fbrl_vm_host *host)
{
    host->now_us = vmh_now_us;
    host->sleep_ms = vmh_sleep_ms;
    host->time_date = vmh_time_date;
}

#endif
