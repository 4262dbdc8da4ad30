/* SPDX-License-Identifier: MIT */
/* fuzz_util.c - helpers the fuzz targets share (fuzz_util.h). */
#include "fuzz_util.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char tmpdir[256];

void fuzz_fail(const char *fmt, ...)
{
    va_list ap;
    fputs("fuzz: ", stderr);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    abort();
}

static void remove_tmpdir(void)
{
    DIR *d = opendir(tmpdir);
    struct dirent *e;
    char p[600];
    if (d) {
        while ((e = readdir(d)) != NULL) {
            if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
                continue;
            snprintf(p, sizeof p, "%s/%s", tmpdir, e->d_name);
            unlink(p);
        }
        closedir(d);
    }
    rmdir(tmpdir);
}

void fuzz_path(char *out, size_t cap, const char *name)
{
    if (!tmpdir[0]) {
        const char *base = getenv("FBRL_FUZZ_TMPDIR");
        if (!base || !*base)
            base = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : getenv("TMPDIR");
        if (!base || !*base)
            base = "/tmp";
        snprintf(tmpdir, sizeof tmpdir, "%s/fbrl-fuzz-XXXXXX", base);
        if (!mkdtemp(tmpdir))
            fuzz_fail("mkdtemp %s: %s", tmpdir, strerror(errno));
        atexit(remove_tmpdir);
    }
    if (snprintf(out, cap, "%s/%s", tmpdir, name) >= (int)cap)
        fuzz_fail("path too long");
}

void fuzz_write_file(const char *path, const void *data, size_t n)
{
    const char *p = data;
    int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (fd < 0)
        fuzz_fail("%s: %s", path, strerror(errno));
    while (n > 0) {
        ssize_t w = write(fd, p, n);
        if (w <= 0)
            fuzz_fail("write %s: %s", path, strerror(errno));
        p += w;
        n -= (size_t)w;
    }
    close(fd);
}

unsigned char *fuzz_read_file(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    unsigned char *b = NULL;
    size_t cap = 0, len = 0, r;
    if (!f)
        return NULL;
    do {
        if (len == cap) {
            unsigned char *nb = realloc(b, cap = cap ? cap * 2 : 4096);
            if (!nb)
                fuzz_fail("out of memory");
            b = nb;
        }
        r = fread(b + len, 1, cap - len, f);
        len += r;
    } while (r > 0);
    fclose(f);
    *n = len;
    return b;
}

void fuzz_split(const uint8_t *d, size_t n, size_t *head, const uint8_t **tail, size_t *tail_n)
{
    size_t i;
    for (i = 0; i + 2 <= n; i++) {
        if ((i == 0 || d[i - 1] == '\n') && d[i] == '%' && d[i + 1] == '%' &&
            (i + 2 == n || d[i + 2] == '\n')) {
            *head = i;
            *tail = d + (i + 2 < n ? i + 3 : n);
            *tail_n = n - (i + 2 < n ? i + 3 : n);
            return;
        }
    }
    *head = n;
    *tail = d + n;
    *tail_n = 0;
}
