/* SPDX-License-Identifier: MIT */
/* fuzz_fileio.c - fuzz target for the typed data file reader (src/fileio.c).
 *
 * Input: one flag byte, then the bytes of a data file. Flag bit 0 reseals the
 * file first (header length = file size, both CRC-32s recomputed), so the
 * mutations reach the record walk behind the checksums; bits 1-2 pick the
 * caller's buffer size (64 B .. 64 KiB). The file is written to a private
 * temporary directory and opened. A refused file gives one of the documented
 * errors. An accepted one must read back completely: every record with the
 * type peek reports (a wrong type is refused with the position unchanged),
 * reals finite, EEOF exactly after `count` records. Then it is changed
 * (record 0 replaced by a REAL, a CHR appended), committed, and must open
 * again with the records expected. */
#include "fuzz_util.h"

#include <math.h>
#include <string.h>

#include "fbrl/crc32.h"
#include "fbrl/fileio.h"

#define FUZZ_BUF_MAX 65536u
#define FUZZ_REAL    1.5
#define FUZZ_CHR     0x5a

static unsigned char file[FUZZ_BUF_MAX], buf[FUZZ_BUF_MAX], buf2[FUZZ_BUF_MAX], val[FUZZ_BUF_MAX];

static void put32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)v;
    p[1] = (unsigned char)(v >> 8);
    p[2] = (unsigned char)(v >> 16);
    p[3] = (unsigned char)(v >> 24);
}

static int refusal(fbrl_status st)
{
    return st == FBRL_EFORMAT || st == FBRL_EVERSION || st == FBRL_ECHECKSUM || st == FBRL_ETRUNCATED ||
           st == FBRL_ENOSPC;
}

/* A type other than t with a valid shape, to check that a wrong read is refused. */
static fbrl_ftype other_type(fbrl_ftype t)
{
    if (t.code == FBRL_FT_USER)
        return fbrl_ftype_user((uint16_t)(t.tag + 1), t.size);
    return t.code == FBRL_FT_CHR ? fbrl_ftype_integer : fbrl_ftype_chr;
}

static void walk(fbrl_file *f, size_t cap)
{
    uint32_t index, count, before, after, n = 0;
    fbrl_ftype t;
    fbrl_status st;
    if (fbrl_file_tell(f, &index, &count) != FBRL_OK || index != 0)
        fuzz_fail("tell after open");
    while ((st = fbrl_file_peek(f, &t)) == FBRL_OK) {
        if (t.size == 0 || t.size > cap)
            fuzz_fail("record %u: size %u in a %zu-byte buffer", n, (unsigned)t.size, cap);
        fbrl_file_tell(f, &before, NULL);
        if (fbrl_file_read(f, other_type(t), val) != FBRL_ETYPE)
            fuzz_fail("record %u read as another type", n);
        fbrl_file_tell(f, &after, NULL);
        if (after != before)
            fuzz_fail("a refused read moved the position");
        if ((st = fbrl_file_read(f, t, val)) != FBRL_OK)
            fuzz_fail("record %u: peeked type does not read (%d)", n, (int)st);
        if (t.code == FBRL_FT_REAL || t.code == FBRL_FT_LOCATION) {
            uint32_t k;
            for (k = 0; k < t.size; k += 8) {
                double d;
                memcpy(&d, val + k, sizeof d);
                if (!isfinite(d))
                    fuzz_fail("record %u: a non-finite real was accepted", n);
            }
        }
        n++;
    }
    if (st != FBRL_EEOF || n != count)
        fuzz_fail("%u records read, header says %u (status %d)", n, count, (int)st);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const size_t caps[4] = {64, 256, 4096, FUZZ_BUF_MAX};
    char path[512];
    size_t n, cap;
    int replaced;
    fbrl_file f, g;
    fbrl_status st;
    uint32_t count, count2;
    double r;

    if (size < 1 || size - 1 > sizeof file)
        return 0;
    cap = caps[(data[0] >> 1) & 3];
    n = size - 1;
    memcpy(file, data + 1, n);
    if ((data[0] & 1) && n >= FBRL_FILE_HEADER_SIZE) {
        put32(file + 12, (uint32_t)n);
        put32(file + 20, fbrl_crc32(0, file + FBRL_FILE_HEADER_SIZE, n - FBRL_FILE_HEADER_SIZE));
        put32(file + 28, fbrl_crc32(0, file, 28));
    }
    fuzz_path(path, sizeof path, "f.dat");
    fuzz_write_file(path, file, n);

    st = fbrl_file_open(&f, path, buf, cap);
    if (st != FBRL_OK) {
        if (!refusal(st))
            fuzz_fail("open: unexpected status %d", (int)st);
        return 0;
    }
    walk(&f, cap);
    fbrl_file_tell(&f, NULL, &count);

    /* change it: record 0 becomes a REAL, a CHR goes at the end */
    fbrl_file_reset(&f);
    st = fbrl_file_write_real(&f, FUZZ_REAL);
    replaced = st == FBRL_OK;
    if (st == FBRL_OK) {
        fbrl_file_append(&f);
        st = fbrl_file_write_chr(&f, FUZZ_CHR);
    }
    if (st != FBRL_OK && st != FBRL_ENOSPC)
        fuzz_fail("write: status %d", (int)st);
    fbrl_file_tell(&f, NULL, &count2);
    if ((st = fbrl_file_close(&f)) != FBRL_OK)
        fuzz_fail("close: status %d", (int)st);

    if ((st = fbrl_file_open(&g, path, buf2, sizeof buf2)) != FBRL_OK)
        fuzz_fail("a file this library wrote does not open: status %d", (int)st);
    walk(&g, sizeof buf2);
    fbrl_file_tell(&g, NULL, &count);
    if (count != count2)
        fuzz_fail("%u records written, %u read back", count2, count);
    fbrl_file_reset(&g);
    if (replaced && ((st = fbrl_file_read_real(&g, &r)) != FBRL_OK || r != FUZZ_REAL))
        fuzz_fail("record 0 does not read back as the REAL written (status %d)", (int)st);
    fbrl_file_discard(&g);
    return 0;
}
