/* SPDX-License-Identifier: MIT */
/* store.c - the data files' store (src/fileio_store.h) on the board's storage region:
 * the firmware's replacement for fileio_posix.c.
 *
 * The region is cut into STORE_SLOTS equal slots. A slot holds one version of one file:
 * a header (magic, sequence number, name, length) and the bytes. The newest sequence
 * number of a name is the file. A replace writes the new version into a slot that holds
 * no current file, header mark last, so the old version stays whole until the new one is
 * complete: the same guarantee as the POSIX rename, and what a flash port needs (it
 * writes a slot with erase/program through board_storage_write). */
#include <string.h>

#include "board.h"
#include "fbrl/fileio.h"
#include "fileio_store.h"

#define STORE_SLOTS    4u
#define STORE_NAME_MAX 32u         /* bytes of a name, with its NUL */
#define STORE_MARK     0x4C524246u /* "FBRL": a complete slot */
#define STORE_READERS  2u          /* files being read at once (fileio reads one at a time) */

typedef struct slot_header {
    uint32_t mark; /* STORE_MARK once the slot is complete; anything else: free */
    uint32_t seq;  /* higher is newer */
    uint32_t len;  /* bytes after the header */
    char name[STORE_NAME_MAX];
} slot_header;

typedef struct reader {
    const unsigned char *data;
    size_t len, pos;
    int busy;
} reader;

static reader readers[STORE_READERS];

static size_t slot_bytes(void)
{
    size_t size;
    (void)board_storage(&size);
    return size / STORE_SLOTS;
}

static const slot_header *slot_at(unsigned k)
{
    size_t size;
    unsigned char *base = board_storage(&size);
    return (const slot_header *)(void *)(base + (size_t)k * slot_bytes());
}

static int slot_valid(const slot_header *h)
{
    return h->mark == STORE_MARK && h->len <= slot_bytes() - sizeof *h &&
           memchr(h->name, '\0', sizeof h->name) != NULL;
}

/* The slot holding the current version of name, or -1. */
static int find(const char *name)
{
    int best = -1;
    for (unsigned k = 0; k < STORE_SLOTS; k++) {
        const slot_header *h = slot_at(k);
        if (slot_valid(h) && strcmp(h->name, name) == 0 &&
            (best < 0 || h->seq > slot_at((unsigned)best)->seq))
            best = (int)k;
    }
    return best;
}

/* A slot that holds no current file (free, or an older version), or -1; *n says how many
 * such slots there are. */
static int free_slot(unsigned *n)
{
    int first = -1;
    *n = 0;
    for (unsigned k = 0; k < STORE_SLOTS; k++) {
        const slot_header *h = slot_at(k);
        if (!slot_valid(h) || find(h->name) != (int)k) {
            if (first < 0)
                first = (int)k;
            ++*n;
        }
    }
    return first;
}

static uint32_t next_seq(void)
{
    uint32_t seq = 0;
    for (unsigned k = 0; k < STORE_SLOTS; k++)
        if (slot_valid(slot_at(k)) && slot_at(k)->seq >= seq)
            seq = slot_at(k)->seq + 1u;
    return seq;
}

fbrl_status fbrl__fstore_open(const char *path, void **handle, uint64_t *size, uint32_t *mode)
{
    int k;
    if (strlen(path) >= STORE_NAME_MAX)
        return FBRL_ENAME;
    if ((k = find(path)) < 0)
        return FBRL_ENOENT;
    for (unsigned r = 0; r < STORE_READERS; r++) {
        if (!readers[r].busy) {
            const slot_header *h = slot_at((unsigned)k);
            readers[r].data = (const unsigned char *)(h + 1);
            readers[r].len = h->len;
            readers[r].pos = 0;
            readers[r].busy = 1;
            *handle = &readers[r];
            *size = h->len;
            *mode = 0; /* no permission bits here */
            return FBRL_OK;
        }
    }
    return FBRL_EIO;
}

fbrl_status fbrl__fstore_read(void *handle, unsigned char *p, size_t n, size_t *got)
{
    reader *r = handle;
    size_t left = r->len - r->pos;
    if (n > left)
        n = left;
    memcpy(p, r->data + r->pos, n);
    r->pos += n;
    *got = n;
    return FBRL_OK;
}

void fbrl__fstore_close(void *handle) { ((reader *)handle)->busy = 0; }

long fbrl__fstore_mode(const char *path) { return strlen(path) < STORE_NAME_MAX && find(path) >= 0 ? 0 : -1; }

fbrl_status fbrl__fstore_replace(const char *path, long keep_mode, const unsigned char *hdr,
                                 const unsigned char *data, size_t len)
{
    slot_header h;
    size_t off;
    unsigned nfree;
    int k;
    (void)keep_mode;
    if (strlen(path) >= STORE_NAME_MAX)
        return FBRL_ENAME;
    if (FBRL_FILE_HEADER_SIZE + len > slot_bytes() - sizeof h)
        return FBRL_ENOSPC;
    /* A new name must leave a slot free: every existing file can then still be replaced. */
    if ((k = free_slot(&nfree)) < 0 || (find(path) < 0 && nfree < 2))
        return FBRL_ENOSPC;
    memset(&h, 0, sizeof h);
    h.seq = next_seq();
    h.len = (uint32_t)(FBRL_FILE_HEADER_SIZE + len);
    strcpy(h.name, path);
    off = (size_t)k * slot_bytes();
    /* The header without its mark, the bytes, then the mark: complete or not there. */
    if (board_storage_write(off, &h, sizeof h) != 0 ||
        board_storage_write(off + sizeof h, hdr, FBRL_FILE_HEADER_SIZE) != 0 ||
        (len && board_storage_write(off + sizeof h + FBRL_FILE_HEADER_SIZE, data, len) != 0))
        return FBRL_EIO;
    h.mark = STORE_MARK;
    return board_storage_write(off, &h.mark, sizeof h.mark) == 0 ? FBRL_OK : FBRL_EIO;
}

/* A replace leaves no temporaries behind here. */
fbrl_status fbrl__fstore_sweep(const char *path, unsigned *removed)
{
    (void)path;
    if (removed)
        *removed = 0;
    return FBRL_OK;
}
