/* SPDX-License-Identifier: MIT */
/* tmpdir.h - a scratch folder under the build tree for a unit test's files, made in its
 * setup and removed with everything in it in its teardown (static inline: a test uses
 * only what it needs). */
#ifndef FBRL_TEST_TMPDIR_H
#define FBRL_TEST_TMPDIR_H

#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>

/* dir[cap] := FBRL_TEST_BINDIR/tests/unit/PREFIX-XXXXXX, made. 0, or -1. */
static inline int test_tmpdir_make(char *dir, size_t cap, const char *prefix)
{
    char base[300];
    snprintf(base, sizeof base, "%s/tests/unit", FBRL_TEST_BINDIR);
    mkdir(base, 0755);
    if ((size_t)snprintf(dir, cap, "%s/%s-XXXXXX", base, prefix) >= cap)
        return -1;
    return mkdtemp(dir) ? 0 : -1;
}

/* The folder and all in it gone. 0, or -1. */
static inline int test_tmpdir_remove(const char *dir)
{
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd) == 0 ? 0 : -1;
}

#endif
