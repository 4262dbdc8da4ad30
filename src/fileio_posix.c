/* SPDX-License-Identifier: MIT */
/* fileio_posix.c - the data files' store in a POSIX file system (fileio_store.h): reads
 * through open/read, atomic replace as temporary, fsync, rename, fsync of the directory.
 * A path that is a symbolic link is written through: its target is replaced, the link
 * stays. Failures are named (permission, a full disk, a link loop, read-only). */
#include "fbrl/fileio.h"
#include "fileio_store.h"
#include "posix_io.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define TMP_TRIES 1000u
#define LINKS_MAX 40u /* links followed to a file before it counts as a loop (Linux's limit) */

fbrl_status fbrl_file_status_of_errno(int e)
{
    switch (e) {
    case 0: return FBRL_OK;
    case ENOENT:
    case ENOTDIR: return FBRL_ENOENT;
    case ENAMETOOLONG: return FBRL_ENAME;
    case EACCES:
    case EPERM: return FBRL_EPERM;
    case ENOSPC:
#ifdef EDQUOT
    case EDQUOT:
#endif
    case EFBIG: return FBRL_EDISKFULL;
    case ELOOP: return FBRL_ELOOP;
    case EROFS:
    case ETXTBSY: return FBRL_EREADONLY;
    case EISDIR: return FBRL_ENOTFILE;
    default: return FBRL_EIO;
    }
}

static fbrl_status from_errno(int e) { return fbrl_file_status_of_errno(e); }

/* Read up to n bytes (fewer only at end of file). */
static fbrl_status read_full(int fd, unsigned char *p, size_t n, size_t *got)
{
    size_t done = 0;
    while (done < n) {
        ssize_t r = read(fd, p + done, n - done);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0)
            return from_errno(errno);
        if (r == 0)
            break;
        done += (size_t)r;
    }
    *got = done;
    return FBRL_OK;
}

fbrl_status fbrl__posix_write_full(int fd, const void *data, size_t n)
{
    const unsigned char *p = data;
    while (n > 0) {
        ssize_t r = write(fd, p, n);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            return r < 0 ? from_errno(errno) : FBRL_EIO;
        p += r;
        n -= (size_t)r;
    }
    return FBRL_OK;
}

fbrl_status fbrl__posix_sync(int fd)
{
    while (fsync(fd) != 0)
        if (errno != EINTR)
            return from_errno(errno); /* a delayed allocation may find the disk full here */
    return FBRL_OK;
}

/* Decimal digits of v at out; returns the number written (at most 10). */
static size_t put_decimal(char *out, uint32_t v)
{
    char tmp[10];
    size_t n = 0;
    do {
        tmp[n++] = (char)('0' + v % 10u);
        v /= 10u;
    } while (v);
    for (size_t i = 0; i < n; i++)
        out[i] = tmp[n - 1 - i];
    return n;
}

/* The directory part of path ("." when there is none), into dir[FBRL_FILE_PATH_MAX]. */
static void dir_of(const char *path, char *dir)
{
    const char *slash = strrchr(path, '/');
    if (!slash) {
        strcpy(dir, ".");
    } else if (slash == path) {
        strcpy(dir, "/");
    } else {
        memcpy(dir, path, (size_t)(slash - path));
        dir[slash - path] = '\0';
    }
}

/* Temporary name in the same directory: DIR/.BASE.PID-N.tmp (a leading dot keeps it out of
 * listings; pid and N keep concurrent writers apart). */
#define TMP_PATH_MAX (FBRL_FILE_PATH_MAX + 32)

static void tmp_name(const char *path, uint32_t n, char *out)
{
    const char *slash = strrchr(path, '/');
    size_t dlen = slash ? (size_t)(slash - path) + 1 : 0;
    size_t k = 0;
    memcpy(out, path, dlen);
    k = dlen;
    out[k++] = '.';
    size_t blen = strlen(path + dlen);
    memcpy(out + k, path + dlen, blen);
    k += blen;
    out[k++] = '.';
    k += put_decimal(out + k, (uint32_t)getpid());
    out[k++] = '-';
    k += put_decimal(out + k, n);
    memcpy(out + k, ".tmp", 5);
}

/* The file path names, its symbolic links followed (the file need not exist: a link to a
 * file not yet made names where it goes), into out[FBRL_FILE_PATH_MAX]. */
static fbrl_status follow_links(const char *path, char *out)
{
    char link[FBRL_FILE_PATH_MAX], dir[FBRL_FILE_PATH_MAX];
    struct stat sb;
    if (strlen(path) >= FBRL_FILE_PATH_MAX)
        return FBRL_ENAME;
    strcpy(out, path);
    for (unsigned hops = 0;; hops++) {
        if (lstat(out, &sb) != 0)
            return errno == ENOENT ? FBRL_OK : from_errno(errno);
        if (!S_ISLNK(sb.st_mode))
            return FBRL_OK;
        if (hops == LINKS_MAX)
            return FBRL_ELOOP;
        ssize_t n = readlink(out, link, sizeof link - 1);
        if (n < 0)
            return from_errno(errno);
        if ((size_t)n >= sizeof link - 1)
            return FBRL_ENAME;
        link[n] = '\0';
        if (link[0] == '/') {
            strcpy(out, link);
            continue;
        }
        dir_of(out, dir); /* a relative target is relative to the link's directory */
        if (strlen(dir) + 1 + (size_t)n >= FBRL_FILE_PATH_MAX)
            return FBRL_ENAME;
        strcat(strcat(strcpy(out, dir), "/"), link);
    }
}

/* A file whose permission bits let nobody write it was made read-only on purpose: saving
 * does not replace it behind its owner's back (the directory alone would allow it). */
static fbrl_status writable(const char *path)
{
    struct stat sb;
    if (stat(path, &sb) != 0)
        return errno == ENOENT ? FBRL_OK : from_errno(errno);
    if (!S_ISREG(sb.st_mode))
        return FBRL_ENOTFILE;
    if ((sb.st_mode & 0222) == 0)
        return FBRL_EREADONLY;
    if (access(path, W_OK) != 0 && errno != ENOENT)
        return from_errno(errno);
    return FBRL_OK;
}

/* fileio_store.h. Replace path by header+data: temporary, fsync, rename, fsync directory. keep_mode >= 0 sets
 * the new file's permission bits (the old file's); otherwise open()'s 0666 & ~umask stands. */
fbrl_status fbrl__fstore_replace(const char *given, long keep_mode, const unsigned char *hdr,
                                 const unsigned char *data, size_t len)
{
    char tmp[TMP_PATH_MAX], path[FBRL_FILE_PATH_MAX];
    int fd = -1;
    fbrl_status st = follow_links(given, path);
    if (st == FBRL_OK)
        st = writable(path);
    if (st != FBRL_OK)
        return st;
    for (uint32_t n = 0; n < TMP_TRIES && fd < 0; n++) {
        tmp_name(path, n, tmp);
        fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0 && errno != EEXIST && errno != EINTR)
            return from_errno(errno);
    }
    if (fd < 0)
        return FBRL_EIO;

    if (keep_mode >= 0 && fchmod(fd, (mode_t)keep_mode) != 0)
        st = from_errno(errno);
    if (st == FBRL_OK)
        st = fbrl__posix_write_full(fd, hdr, FBRL_FILE_HEADER_SIZE);
    if (st == FBRL_OK)
        st = fbrl__posix_write_full(fd, data, len);
    if (st == FBRL_OK)
        st = fbrl__posix_sync(fd);
    if (close(fd) != 0 && st == FBRL_OK)
        st = from_errno(errno);
    if (st == FBRL_OK && rename(tmp, path) != 0)
        st = from_errno(errno);
    if (st != FBRL_OK) {
        unlink(tmp);
        return st;
    }

    /* Make the rename itself durable. Some file systems cannot fsync a directory (EINVAL):
     * the rename is then as durable as that file system makes it. */
    char dir[FBRL_FILE_PATH_MAX];
    dir_of(path, dir);
    int dfd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd < 0)
        return from_errno(errno);
    if (fsync(dfd) != 0 && errno != EINVAL)
        st = from_errno(errno);
    close(dfd);
    return st;
}

/* name is ".BASE.DIGITS-DIGITS.tmp" for this base: a temporary of ours, not a user file. */
static int is_temporary(const char *name, const char *base, size_t blen)
{
    if (name[0] != '.' || strncmp(name + 1, base, blen) != 0 || name[1 + blen] != '.')
        return 0;
    const char *p = name + 2 + blen;
    for (int part = 0; part < 2; part++) {
        const char *start = p;
        while (*p >= '0' && *p <= '9')
            p++;
        if (p == start || *p != (part == 0 ? '-' : '.'))
            return 0;
        p++;
    }
    return strcmp(p, "tmp") == 0;
}

fbrl_status fbrl__fstore_sweep(const char *given, unsigned *removed)
{
    char dir[FBRL_FILE_PATH_MAX], path[FBRL_FILE_PATH_MAX];
    fbrl_status st = follow_links(given, path); /* the temporaries are beside the target */
    if (st != FBRL_OK)
        return st;
    dir_of(path, dir);
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    size_t blen = strlen(base);
    DIR *dp = opendir(dir);
    if (!dp)
        return from_errno(errno);
    char victim[TMP_PATH_MAX];
    size_t dlen = (size_t)(base - path);
    struct dirent *e;
    while ((e = readdir(dp)) != NULL) {
        if (!is_temporary(e->d_name, base, blen) || dlen + strlen(e->d_name) >= sizeof victim)
            continue;
        memcpy(victim, path, dlen);
        strcpy(victim + dlen, e->d_name);
        if (unlink(victim) == 0) {
            if (removed)
                (*removed)++;
        } else if (errno != ENOENT) {
            st = from_errno(errno);
        }
    }
    closedir(dp);
    return st;
}

/* Permission bits of an existing file, or -1 if there is none. */
long fbrl__fstore_mode(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 ? (long)(sb.st_mode & 07777) : -1L;
}

/* O_NONBLOCK: a FIFO must not hang the open; it is refused as not a regular file. The
 * handle is the file descriptor, kept in the pointer's bits (no allocation). */
fbrl_status fbrl__fstore_open(const char *path, void **handle, uint64_t *size, uint32_t *mode)
{
    int fd;
    struct stat sb;
    fbrl_status st;
    do {
        fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    } while (fd < 0 && errno == EINTR);
    if (fd < 0)
        return from_errno(errno);
    if (fstat(fd, &sb) != 0) {
        st = from_errno(errno);
        close(fd);
        return st;
    }
    if (!S_ISREG(sb.st_mode)) {
        close(fd);
        return FBRL_EFORMAT;
    }
    *handle = (void *)(intptr_t)(fd + 1);
    *size = (uint64_t)sb.st_size;
    *mode = (uint32_t)(sb.st_mode & 07777);
    return FBRL_OK;
}

fbrl_status fbrl__fstore_read(void *handle, unsigned char *p, size_t n, size_t *got)
{
    return read_full((int)((intptr_t)handle - 1), p, n, got);
}

void fbrl__fstore_close(void *handle) { close((int)((intptr_t)handle - 1)); }
