/* SPDX-License-Identifier: MIT */
/* fileio_store.h - what the typed data files (fileio.c) need from the storage under them
 * (internal). fileio.c owns the format and never touches storage itself; a store provides
 * these functions at link time: fileio_posix.c keeps files in a POSIX file system, a board
 * port its own (ports/cortex-m3/store.c: a RAM or flash region). Paths are checked by
 * fileio.c (non-empty, shorter than FBRL_FILE_PATH_MAX, not ending in '/'). */
#ifndef FBRL_FILEIO_STORE_H
#define FBRL_FILEIO_STORE_H

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"

/* Open path for reading: a handle, its size in bytes and its permission bits (0 where the
 * store has none). ENOENT (no such file), ENAME, EFORMAT (not a regular file), EIO. */
fbrl_status fbrl__fstore_open(const char *path, void **handle, uint64_t *size, uint32_t *mode);
/* Up to n bytes (fewer only at the end of the file) into p; *got says how many. */
fbrl_status fbrl__fstore_read(void *handle, unsigned char *p, size_t n, size_t *got);
void fbrl__fstore_close(void *handle);
/* Permission bits of an existing file, or -1 if there is none. */
long fbrl__fstore_mode(const char *path);
/* Make path hold the FBRL_FILE_HEADER_SIZE bytes of hdr, then len bytes of data, as one
 * atomic step: afterwards, and after a crash at any moment, the file is either the old one
 * or the new one complete. keep_mode >= 0: the new file's permission bits. */
fbrl_status fbrl__fstore_replace(const char *path, long keep_mode, const unsigned char *hdr,
                                 const unsigned char *data, size_t len);
/* Remove the temporaries a writer killed mid-replace left next to path (the store's own
 * names; fbrl_file_remove_temporaries); *removed counts them. FBRL_OK with 0 where the
 * store leaves none. */
fbrl_status fbrl__fstore_sweep(const char *path, unsigned *removed);

#endif
