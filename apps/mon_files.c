/* SPDX-License-Identifier: MIT */
/* mon_files.c - the file system behind the standard FILE words in fbrlmon (stdio and
 * POSIX; the engine reaches it only through fbrl_vm_host.files). A handle is a mon_fh:
 * C streams need a seek between a read and a write, so every operation seeks first. */
#include "mon_files.h"
#include "fbrl/fileio.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

typedef struct mon_fh {
    FILE *f;
} mon_fh;

/* what the OS said, named as the library names it (permission, a full disk, a link loop ...) */
static fbrl_status st_of_errno(void) { return errno ? fbrl_file_status_of_errno(errno) : FBRL_EIO; }

static fbrl_status fs_open(void *user, const char *path, unsigned fam, int create, void **handle)
{
    (void)user;
    const char *mode;
    if (create)
        mode = (fam & FBRL_FAM_READ) ? "w+b" : "wb";
    else
        mode = (fam & FBRL_FAM_WRITE) ? "r+b" : "rb"; /* W/O must not empty an existing file */
    struct stat sb;
    if (!create && stat(path, &sb) == 0 && !S_ISREG(sb.st_mode))
        return FBRL_ENOTFILE; /* a directory or a device is no file to read lines from */
    mon_fh *h = malloc(sizeof *h);
    if (!h)
        return FBRL_ENOSPC;
    h->f = fopen(path, mode);
    if (!h->f) {
        fbrl_status st = st_of_errno();
        free(h);
        return st;
    }
    *handle = h;
    return FBRL_OK;
}

static fbrl_status fs_close(void *user, void *handle)
{
    mon_fh *h = handle;
    (void)user;
    errno = 0;
    int bad = fclose(h->f) != 0; /* a buffered write's full disk shows here */
    fbrl_status st = bad ? st_of_errno() : FBRL_OK;
    free(h);
    return st;
}

static int here(mon_fh *h) { return fseeko(h->f, 0, SEEK_CUR) == 0; }

static fbrl_status fs_read(void *user, void *handle, void *buf, size_t n, size_t *got)
{
    mon_fh *h = handle;
    (void)user;
    if (!here(h))
        return FBRL_EIO;
    *got = fread(buf, 1, n, h->f);
    return ferror(h->f) ? (clearerr(h->f), FBRL_EIO) : FBRL_OK;
}

static fbrl_status fs_write(void *user, void *handle, const void *buf, size_t n)
{
    mon_fh *h = handle;
    (void)user;
    if (!here(h))
        return FBRL_EIO;
    errno = 0;
    if (fwrite(buf, 1, n, h->f) == n)
        return FBRL_OK;
    fbrl_status st = st_of_errno();
    clearerr(h->f);
    return st;
}

static fbrl_status fs_seek(void *user, void *handle, uint64_t pos)
{
    mon_fh *h = handle;
    (void)user;
    return pos <= (uint64_t)INT64_MAX && fseeko(h->f, (off_t)pos, SEEK_SET) == 0 ? FBRL_OK : FBRL_EIO;
}

static fbrl_status fs_tell(void *user, void *handle, uint64_t *pos)
{
    mon_fh *h = handle;
    (void)user;
    off_t p = ftello(h->f);
    if (p < 0)
        return FBRL_EIO;
    *pos = (uint64_t)p;
    return FBRL_OK;
}

static fbrl_status fs_size(void *user, void *handle, uint64_t *size)
{
    mon_fh *h = handle;
    struct stat sb;
    (void)user;
    errno = 0;
    if (fflush(h->f) != 0 || fstat(fileno(h->f), &sb) != 0)
        return st_of_errno();
    *size = (uint64_t)sb.st_size;
    return FBRL_OK;
}

static fbrl_status fs_resize(void *user, void *handle, uint64_t size)
{
    mon_fh *h = handle;
    (void)user;
    if (size > (uint64_t)INT64_MAX || fflush(h->f) != 0 || ftruncate(fileno(h->f), (off_t)size) != 0)
        return FBRL_EIO;
    return FBRL_OK;
}

static fbrl_status fs_flush(void *user, void *handle)
{
    mon_fh *h = handle;
    (void)user;
    return fflush(h->f) == 0 ? FBRL_OK : FBRL_EIO;
}

static fbrl_status fs_remove(void *user, const char *path)
{
    (void)user;
    return remove(path) == 0 ? FBRL_OK : st_of_errno();
}

static fbrl_status fs_rename(void *user, const char *from, const char *to)
{
    (void)user;
    return rename(from, to) == 0 ? FBRL_OK : st_of_errno();
}

static fbrl_status fs_status(void *user, const char *path, unsigned *mode)
{
    struct stat sb;
    (void)user;
    if (stat(path, &sb) != 0)
        return st_of_errno();
    *mode = (access(path, R_OK) == 0 ? FBRL_FAM_READ : 0) | (access(path, W_OK) == 0 ? FBRL_FAM_WRITE : 0);
    return FBRL_OK;
}

static const fbrl_vm_files files = {fs_open, fs_close,  fs_read,  fs_write,  fs_seek,   fs_tell,
                                    fs_size, fs_resize, fs_flush, fs_remove, fs_rename, fs_status};

const fbrl_vm_files *mon_files(void) { return &files; }
