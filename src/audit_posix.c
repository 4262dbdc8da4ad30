/* SPDX-License-Identifier: MIT */
/* audit_posix.c - the audit chain's and users file's store in a POSIX file system
 * (audit_store.h): appends made durable with fdatasync, whole files replaced atomically. */
#ifndef _DEFAULT_SOURCE
#define _DEFAULT_SOURCE /* flock: a whole-file lock a second descriptor's close does not drop */
#endif
#include "audit_store.h"
#include "posix_io.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define PATH_CAP 4096

static fbrl_status from_errno(int e)
{
    switch (e) {
    case ENOENT:
    case ENOTDIR: return FBRL_ENOENT;
    case ENAMETOOLONG: return FBRL_ENAME;
    case EACCES:
    case EPERM: return FBRL_EPERM;
    default: return FBRL_EIO;
    }
}

/* A handle is the descriptor + 1 kept in the pointer: nothing to allocate. */
static void *to_handle(int fd) { return (void *)(intptr_t)(fd + 1); }
static int fd_of(void *h) { return (int)(intptr_t)h - 1; }

fbrl_status fbrl__astore_open_append(const char *path, void **handle)
{
    int fd = open(path, O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0640);
    if (fd < 0)
        return from_errno(errno);
    /* one writer at a time: another would continue from a head this one moved */
    while (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        if (errno == EINTR)
            continue;
        close(fd);
        return errno == EWOULDBLOCK ? FBRL_EBUSY : FBRL_EIO;
    }
    *handle = to_handle(fd);
    return FBRL_OK;
}

fbrl_status fbrl__astore_append(void *handle, const char *s, size_t n)
{
    int fd = fd_of(handle);
    struct stat sb;
    off_t at = fstat(fd, &sb) == 0 ? sb.st_size : -1;
    fbrl_status st = fbrl__posix_write_full(fd, s, n);
    if (st != FBRL_OK && at >= 0 && S_ISREG(sb.st_mode)) { /* a cut record taken back: the file ends whole */
        int e = errno; /* the caller tells why (ENOSPC ...) */
        (void)!ftruncate(fd, at);
        errno = e;
    }
    while (st == FBRL_OK && fdatasync(fd) != 0)
        if (errno != EINTR)
            st = FBRL_EIO;
    return st;
}

void fbrl__astore_close(void *handle)
{
    if (handle != NULL)
        close(fd_of(handle));
}

fbrl_status fbrl__astore_read_open(const char *path, void **handle)
{
    struct stat sb;
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return from_errno(errno);
    if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
        close(fd);
        return FBRL_ENOTFILE;
    }
    *handle = to_handle(fd);
    return FBRL_OK;
}

fbrl_status fbrl__astore_read(void *handle, char *buf, size_t n, size_t *got)
{
    for (;;) {
        ssize_t r = read(fd_of(handle), buf, n);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0)
            return FBRL_EIO;
        *got = (size_t)r;
        return FBRL_OK;
    }
}

/* The temporary beside path: path.PID.tmp (one writer per file in a process). */
static int tmp_of(const char *path, char *tmp, size_t cap)
{
    int k = snprintf(tmp, cap, "%s.%ld.tmp", path, (long)getpid());
    return k < 0 || (size_t)k >= cap ? -1 : 0;
}

fbrl_status fbrl__astore_put_begin(const char *path, int owner_only, void **handle)
{
    char tmp[PATH_CAP];
    int fd;
    if (tmp_of(path, tmp, sizeof tmp) != 0)
        return FBRL_ENAME;
    unlink(tmp); /* one a killed writer of this pid left */
    fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, owner_only ? 0600 : 0640);
    if (fd < 0)
        return from_errno(errno);
    /* the umask may have taken bits asked for: set them */
    if (fchmod(fd, owner_only ? 0600 : 0640) != 0) {
        close(fd);
        unlink(tmp);
        return FBRL_EIO;
    }
    *handle = to_handle(fd);
    return FBRL_OK;
}

fbrl_status fbrl__astore_put_write(void *handle, const char *s, size_t n)
{
    return fbrl__posix_write_full(fd_of(handle), s, n);
}

fbrl_status fbrl__astore_put_commit(void *handle, const char *path, int ok)
{
    char tmp[PATH_CAP], dir[PATH_CAP];
    const char *slash = strrchr(path, '/');
    int fd = fd_of(handle);
    fbrl_status st = ok ? FBRL_OK : FBRL_EIO;
    if (st == FBRL_OK)
        st = fbrl__posix_sync(fd);
    if (close(fd) != 0 && st == FBRL_OK)
        st = FBRL_EIO;
    if (tmp_of(path, tmp, sizeof tmp) != 0)
        return FBRL_ENAME;
    if (st == FBRL_OK && rename(tmp, path) != 0)
        st = from_errno(errno);
    if (st != FBRL_OK) {
        unlink(tmp);
        return ok ? st : FBRL_OK;
    }
    if (slash == NULL)
        snprintf(dir, sizeof dir, ".");
    else
        snprintf(dir, sizeof dir, "%.*s", slash == path ? 1 : (int)(slash - path), path);
    fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
        return FBRL_EIO;
    if (fsync(fd) != 0 && errno != EINVAL) /* some file systems cannot sync a directory */
        st = FBRL_EIO;
    close(fd);
    return st;
}

fbrl_status fbrl__astore_head_open(const char *path, void **handle)
{
    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0640);
    if (fd < 0)
        return from_errno(errno);
    *handle = to_handle(fd);
    return FBRL_OK;
}

fbrl_status fbrl__astore_head_put(void *handle, const char *s, size_t n)
{
    int fd = fd_of(handle);
    size_t done = 0;
    while (done < n) {
        ssize_t r = pwrite(fd, s + done, n - done, (off_t)done);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            return FBRL_EIO;
        done += (size_t)r;
    }
    while (fdatasync(fd) != 0)
        if (errno != EINTR)
            return FBRL_EIO;
    return FBRL_OK;
}

fbrl_status fbrl__astore_guarded(const char *path)
{
    struct stat sb;
    if (stat(path, &sb) != 0)
        return from_errno(errno);
    if (!S_ISREG(sb.st_mode))
        return FBRL_ENOTFILE;
    return (sb.st_mode & (S_IWGRP | S_IWOTH)) ? FBRL_EPERM : FBRL_OK;
}

int64_t fbrl__astore_utc_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}
