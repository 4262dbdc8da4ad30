/* SPDX-License-Identifier: MIT */
/* audit_store.h - what the audit chain and the users file need from the storage under them
 * (internal), in the idiom of fileio_store.h: audit_posix.c provides these at link time. */
#ifndef FBRL_AUDIT_STORE_H
#define FBRL_AUDIT_STORE_H

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"

/* Open path for appending (created owner read-write, group read, when missing), locked
 * against other writers until closed: FBRL_EBUSY while another holds it. */
fbrl_status fbrl__astore_open_append(const char *path, void **handle);
/* Append n bytes and make them durable (fdatasync) before returning. */
fbrl_status fbrl__astore_append(void *handle, const char *s, size_t n);
void fbrl__astore_close(void *handle);
/* Open path for reading (FBRL_ENOENT when missing); read up to n bytes (fewer only at the
 * end: *got 0 there). */
fbrl_status fbrl__astore_read_open(const char *path, void **handle);
fbrl_status fbrl__astore_read(void *handle, char *buf, size_t n, size_t *got);
/* Replace path atomically, written in pieces: begin makes a temporary beside it (owner_only:
 * 0600, else 0640, whatever the umask), write adds to it, commit syncs it, renames it over
 * path and syncs the directory (or, when ok is 0, removes it). */
fbrl_status fbrl__astore_put_begin(const char *path, int owner_only, void **handle);
fbrl_status fbrl__astore_put_write(void *handle, const char *s, size_t n);
fbrl_status fbrl__astore_put_commit(void *handle, const char *path, int ok);
/* A small file rewritten in place (the chain's head): open (created 0640), put n bytes at
 * its start and make them durable (fdatasync); every put has the same length. */
fbrl_status fbrl__astore_head_open(const char *path, void **handle);
fbrl_status fbrl__astore_head_put(void *handle, const char *s, size_t n);
/* FBRL_OK if path exists and neither its group nor others may write it; FBRL_EPERM if they
 * may, FBRL_ENOENT if there is none, FBRL_ENOTFILE if it is not a regular file. */
fbrl_status fbrl__astore_guarded(const char *path);
/* The system clock: UTC milliseconds since 1970. */
int64_t fbrl__astore_utc_ms(void);

#endif
