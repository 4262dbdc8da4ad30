/* SPDX-License-Identifier: MIT */
/* fileio.h - typed binary data files (the thesis's CREATE-FILE, OPEN-FILE, RESET-FILE,
 * APPEND-FILE, CLOSE-FILE, READ-FILE, WRITE-FILE; appendix I-9, chapter 5.7-5.8).
 *
 * A data file is a sequence of typed records. Each record carries its type, so reading a
 * record as the wrong type is refused (FBRL_ETYPE) and the read position stays where it was.
 *
 * Safety model (docs/files.md has the byte-by-byte format):
 * - open reads and verifies the WHOLE file (magic, version, lengths, record count, two CRC-32s,
 *   every record's framing) into a buffer the caller provides; a file cut at any byte or with
 *   any single flipped bit is refused before a single record is returned.
 * - reads, writes, reset and append work on that buffer. Nothing touches the disk until
 *   fbrl_file_commit() (or fbrl_file_close()), which writes a temporary file in the same
 *   directory, fsyncs it, renames it over the target and fsyncs the directory. A crash at any
 *   moment leaves either the old or the new file complete, never a mix.
 * - other readers keep seeing the last committed file until the rename; a handle already open
 *   keeps its own snapshot.
 *
 * No allocation: the handle (struct fbrl_file) and the record buffer belong to the caller.
 * A handle is not thread-safe; distinct handles may be used from distinct threads. */
#ifndef FBRL_FILEIO_H
#define FBRL_FILEIO_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"
#include "fbrl/loc.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FBRL_FILE_VERSION       1u   /* format version this library writes and reads */
#define FBRL_FILE_HEADER_SIZE   32u  /* bytes of the file header */
#define FBRL_FILE_RECORD_HEADER 8u   /* bytes in front of each record's payload */
#define FBRL_FILE_PATH_MAX      256u /* longest path accepted, including the final NUL */

/* Buffer bytes one record of `payload` bytes takes (header + payload). The buffer given to
 * fbrl_file_open() must hold the sum of this over every record the file will ever hold. */
#define FBRL_FILE_RECORD_SIZE(payload) ((size_t)FBRL_FILE_RECORD_HEADER + (size_t)(payload))

/* Record type codes, as stored in the file. Never renumber. */
typedef enum fbrl_ftype_code {
    FBRL_FT_CHR = 1,      /* 1 byte, unsigned char */
    FBRL_FT_INTEGER = 2,  /* 2 bytes, int16_t, two's complement */
    FBRL_FT_LONG = 3,     /* 4 bytes, int32_t (the thesis's LONG-INTEGER) */
    FBRL_FT_REAL = 4,     /* 8 bytes, IEEE-754 binary64 double, finite */
    FBRL_FT_LOCATION = 5, /* 48 bytes, struct fbrl_loc: six doubles x y z o a t, finite */
    FBRL_FT_USER = 6      /* user-defined: `size` opaque bytes, told apart by `tag` */
} fbrl_ftype_code;

/* A data type. Built-in types have tag 0 and their fixed size; a user type is identified by
 * its tag AND its size (the thesis: "data types are constants holding the length"). */
typedef struct fbrl_ftype {
    fbrl_ftype_code code;
    uint16_t tag;  /* user types only; 0 for built-in types */
    uint32_t size; /* payload bytes: 1, 2, 4, 8, 48, or any size >= 1 for USER */
} fbrl_ftype;

extern FBRL_API const fbrl_ftype fbrl_ftype_chr, fbrl_ftype_integer, fbrl_ftype_long, fbrl_ftype_real,
    fbrl_ftype_location;

/* A user-defined type of `size` bytes and caller-chosen `tag` (size is checked when used). */
FBRL_API fbrl_ftype fbrl_ftype_user(uint16_t tag, uint32_t size);

/* The thesis's rule "a type is its length": 1 -> CHR, 2 -> INTEGER, 4 -> LONG, 8 -> REAL,
 * 48 -> LOCATION, any other size -> USER with tag 0. */
FBRL_API fbrl_ftype fbrl_ftype_of_size(size_t size);

/* An open data file. Caller-owned; treat the fields as private. */
typedef struct fbrl_file {
    unsigned char *buf; /* caller's buffer: the records, encoded as on disk */
    size_t cap;         /* its size */
    size_t len;         /* bytes of records in use */
    size_t pos;         /* byte offset of the current record */
    uint32_t count;     /* records in the file */
    uint32_t index;     /* number of the current record, 0-based */
    uint32_t mode;      /* permission bits of the file when opened (kept on commit) */
    uint32_t state;     /* open marker; anything else means closed */
    int dirty;          /* changed since the last commit */
    char path[FBRL_FILE_PATH_MAX];
} fbrl_file;

/* CREATE-FILE: make `path` an empty data file, atomically replacing any file of that name
 * (the thesis: "if the file exists, it is set to zero length"). */
FBRL_API fbrl_status fbrl_file_create(const char *path);

/* OPEN-FILE: read and verify the whole file into buf[0..cap) and position at record 0.
 * Errors: ENOENT (no such file or directory), EFORMAT (not a data file, or malformed),
 * EVERSION, ECHECKSUM, ETRUNCATED, ENOSPC (records do not fit in cap), ENAME (path longer
 * than FBRL_FILE_PATH_MAX-1), EIO. On error the handle is left closed. Opening over a handle
 * that is still open drops its unsaved changes: close it first. */
FBRL_API fbrl_status fbrl_file_open(fbrl_file *f, const char *path, void *buf, size_t cap);

/* RESET-FILE: position at the first record. */
FBRL_API fbrl_status fbrl_file_reset(fbrl_file *f);

/* APPEND-FILE: position after the last record. */
FBRL_API fbrl_status fbrl_file_append(fbrl_file *f);

/* Drop every record from the current position to the end (in the buffer; the disk changes on
 * commit). RESET + TRUNCATE + writes + CLOSE rewrites a file in one atomic step. */
FBRL_API fbrl_status fbrl_file_truncate(fbrl_file *f);

/* WRITE-FILE: write one value of `type` at the current position and move past it. At the
 * end this appends a record; on an existing record it replaces that record (whatever its
 * type), like F-PC overwriting at the file pointer, and keeps the records after it.
 * `value` points to the host object: unsigned char, int16_t, int32_t, double, fbrl_loc, or
 * type.size raw bytes for USER. Errors: EINVAL (bad type or NULL), ENONFINITE (NaN/inf in a
 * REAL or LOCATION), ENOSPC (buffer full), EFULL (2^32-1 records), ESTATE (closed handle).
 * On error nothing changes. The change reaches the disk on commit/close. */
FBRL_API fbrl_status fbrl_file_write(fbrl_file *f, fbrl_ftype type, const void *value);

/* READ-FILE: read the current record into `value` and move past it. ETYPE if the record is
 * not of `type` (position unchanged: read it again with the right type), EEOF at the end. */
FBRL_API fbrl_status fbrl_file_read(fbrl_file *f, fbrl_ftype type, void *value);

/* Type of the current record, without moving (EEOF at the end). */
FBRL_API fbrl_status fbrl_file_peek(const fbrl_file *f, fbrl_ftype *type);

/* Current record number (0-based; == count at the end) and number of records. Either
 * pointer may be NULL. */
FBRL_API fbrl_status fbrl_file_tell(const fbrl_file *f, uint32_t *index, uint32_t *count);

/* Write the records to disk atomically (temporary, fsync, rename, fsync directory). No-op if
 * nothing changed. On error the file on disk is untouched and the handle stays open. */
FBRL_API fbrl_status fbrl_file_commit(fbrl_file *f);

/* CLOSE-FILE: commit, then close the handle. If the commit fails the handle stays open and
 * the error is returned: retry, or fbrl_file_discard(). */
FBRL_API fbrl_status fbrl_file_close(fbrl_file *f);

/* Close the handle without writing its unsaved changes. */
FBRL_API fbrl_status fbrl_file_discard(fbrl_file *f);

/* Remove the temporaries a writer killed mid-commit left next to `path` (hidden files named
 * .BASE.PID-N.tmp; see docs/files.md). They are never read and never block a later commit;
 * this only reclaims their space. Call it when no other process is committing to `path`: a
 * live writer's temporary would be removed and its commit would fail (without harm to the
 * file). `removed` (may be NULL) receives the number removed. */
FBRL_API fbrl_status fbrl_file_remove_temporaries(const char *path, unsigned *removed);

/* The status an operating-system error number (POSIX errno) reads as, so a program's own
 * file errors say what the library's say: FBRL_EPERM (EACCES, EPERM), FBRL_EDISKFULL
 * (ENOSPC, EDQUOT, EFBIG), FBRL_ELOOP, FBRL_EREADONLY (EROFS, ETXTBSY), FBRL_ENOENT (ENOENT,
 * ENOTDIR), FBRL_ENAME (ENAMETOOLONG), FBRL_ENOTFILE (EISDIR), FBRL_OK for 0, else
 * FBRL_EIO. Where the library has a file system (not in the firmware). */
FBRL_API fbrl_status fbrl_file_status_of_errno(int err);

/* Typed shorthands for fbrl_file_write/read with the built-in types. */
FBRL_API fbrl_status fbrl_file_write_chr(fbrl_file *f, unsigned char v);
FBRL_API fbrl_status fbrl_file_write_integer(fbrl_file *f, int16_t v);
FBRL_API fbrl_status fbrl_file_write_long(fbrl_file *f, int32_t v);
FBRL_API fbrl_status fbrl_file_write_real(fbrl_file *f, double v);
FBRL_API fbrl_status fbrl_file_write_loc(fbrl_file *f, const fbrl_loc *v);
FBRL_API fbrl_status fbrl_file_write_user(fbrl_file *f, uint16_t tag, const void *data, size_t size);
FBRL_API fbrl_status fbrl_file_read_chr(fbrl_file *f, unsigned char *v);
FBRL_API fbrl_status fbrl_file_read_integer(fbrl_file *f, int16_t *v);
FBRL_API fbrl_status fbrl_file_read_long(fbrl_file *f, int32_t *v);
FBRL_API fbrl_status fbrl_file_read_real(fbrl_file *f, double *v);
FBRL_API fbrl_status fbrl_file_read_loc(fbrl_file *f, fbrl_loc *v);
FBRL_API fbrl_status fbrl_file_read_user(fbrl_file *f, uint16_t tag, void *data, size_t size);

#ifdef __cplusplus
}
#endif
#endif
