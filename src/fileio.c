/* SPDX-License-Identifier: MIT */
/* fileio.c - typed binary data files: verified whole on open, replaced atomically on commit.
 * The on-disk format is in docs/files.md; every field is little-endian and encoded byte by
 * byte, so the files move unchanged between hosts of any endianness. */
#include "fbrl/fileio.h"
#include "fbrl/crc32.h"
#include "fileio_store.h"
#include "le.h"

#include <math.h>
#include <string.h>

/* REAL is stored as the bit pattern of an IEEE-754 binary64 double. */
typedef char fbrl_fileio_double_is_8_bytes[sizeof(double) == 8 ? 1 : -1];

#define OPEN_MARK 0x46424c46u /* "FBLF": a handle between open and close */
#define LOC_BYTES 48u

static const unsigned char magic[8] = {0x89, 'F', 'B', 'R', 'L', 'D', '\r', '\n'};

const fbrl_ftype fbrl_ftype_chr = {FBRL_FT_CHR, 0, 1};
const fbrl_ftype fbrl_ftype_integer = {FBRL_FT_INTEGER, 0, 2};
const fbrl_ftype fbrl_ftype_long = {FBRL_FT_LONG, 0, 4};
const fbrl_ftype fbrl_ftype_real = {FBRL_FT_REAL, 0, 8};
const fbrl_ftype fbrl_ftype_location = {FBRL_FT_LOCATION, 0, LOC_BYTES};

fbrl_ftype fbrl_ftype_user(uint16_t tag, uint32_t size)
{
    fbrl_ftype t;
    t.code = FBRL_FT_USER;
    t.tag = tag;
    t.size = size;
    return t;
}

fbrl_ftype fbrl_ftype_of_size(size_t size)
{
    switch (size) {
    case 1: return fbrl_ftype_chr;
    case 2: return fbrl_ftype_integer;
    case 4: return fbrl_ftype_long;
    case 8: return fbrl_ftype_real;
    case LOC_BYTES: return fbrl_ftype_location;
    default: return fbrl_ftype_user(0, size > UINT32_MAX ? 0 : (uint32_t)size);
    }
}

/* ---- types and records ---- */

static uint32_t builtin_size(unsigned code)
{
    switch (code) {
    case FBRL_FT_CHR: return 1;
    case FBRL_FT_INTEGER: return 2;
    case FBRL_FT_LONG: return 4;
    case FBRL_FT_REAL: return 8;
    case FBRL_FT_LOCATION: return LOC_BYTES;
    default: return 0;
    }
}

/* A (code, tag, size) triple describes a type this format can hold. */
static int type_ok(unsigned code, unsigned tag, uint32_t size)
{
    if (code == FBRL_FT_USER)
        return size >= 1 && size <= UINT32_MAX - FBRL_FILE_HEADER_SIZE - FBRL_FILE_RECORD_HEADER;
    return builtin_size(code) != 0 && tag == 0 && size == builtin_size(code);
}

static int same_type(fbrl_ftype a, fbrl_ftype b)
{
    return a.code == b.code && a.tag == b.tag && a.size == b.size;
}

/* Type of the record at buf[pos]; the buffer always holds well-formed records. */
static fbrl_ftype record_type(const unsigned char *rec)
{
    fbrl_ftype t;
    t.code = (fbrl_ftype_code)rec[0];
    t.tag = fbrl_le_get16(rec + 2);
    t.size = fbrl_le_get32(rec + 4);
    return t;
}

/* REAL and LOCATION values must be finite: a file never holds NaN or infinity. */
static int value_finite(fbrl_ftype t, const void *value)
{
    if (t.code == FBRL_FT_REAL) {
        double v;
        memcpy(&v, value, sizeof v);
        return isfinite(v);
    }
    if (t.code == FBRL_FT_LOCATION) {
        fbrl_loc l;
        memcpy(&l, value, sizeof l);
        return isfinite(l.x) && isfinite(l.y) && isfinite(l.z) && isfinite(l.o) && isfinite(l.a) &&
               isfinite(l.t);
    }
    return 1;
}

/* The host value as payload bytes: fixed little-endian fields, never a struct dump. */
static void encode_value(fbrl_ftype t, const void *value, unsigned char *out)
{
    switch (t.code) {
    case FBRL_FT_CHR: out[0] = *(const unsigned char *)value; break;
    case FBRL_FT_INTEGER: {
        int16_t v;
        memcpy(&v, value, sizeof v);
        fbrl_le_put16(out, (uint16_t)v);
        break;
    }
    case FBRL_FT_LONG: {
        int32_t v;
        memcpy(&v, value, sizeof v);
        fbrl_le_put32(out, (uint32_t)v);
        break;
    }
    case FBRL_FT_REAL: {
        double v;
        memcpy(&v, value, sizeof v);
        fbrl_le_put_double(out, v);
        break;
    }
    case FBRL_FT_LOCATION: {
        fbrl_loc l;
        memcpy(&l, value, sizeof l);
        fbrl_le_put_double(out, l.x);
        fbrl_le_put_double(out + 8, l.y);
        fbrl_le_put_double(out + 16, l.z);
        fbrl_le_put_double(out + 24, l.o);
        fbrl_le_put_double(out + 32, l.a);
        fbrl_le_put_double(out + 40, l.t);
        break;
    }
    case FBRL_FT_USER: memcpy(out, value, t.size); break;
    }
}

/* Two's complement from the unsigned field without implementation-defined conversions. */
static int16_t to_i16(uint16_t u) { return u < 0x8000u ? (int16_t)u : (int16_t)((int32_t)u - 0x10000); }

static int32_t to_i32(uint32_t u)
{
    return u < 0x80000000u ? (int32_t)u : (int32_t)(u - 0x80000000u) - INT32_MAX - 1;
}

static void decode_value(fbrl_ftype t, const unsigned char *in, void *value)
{
    switch (t.code) {
    case FBRL_FT_CHR: *(unsigned char *)value = in[0]; break;
    case FBRL_FT_INTEGER: {
        int16_t v = to_i16(fbrl_le_get16(in));
        memcpy(value, &v, sizeof v);
        break;
    }
    case FBRL_FT_LONG: {
        int32_t v = to_i32(fbrl_le_get32(in));
        memcpy(value, &v, sizeof v);
        break;
    }
    case FBRL_FT_REAL: {
        double v = fbrl_le_get_double(in);
        memcpy(value, &v, sizeof v);
        break;
    }
    case FBRL_FT_LOCATION: {
        fbrl_loc l;
        l.x = fbrl_le_get_double(in);
        l.y = fbrl_le_get_double(in + 8);
        l.z = fbrl_le_get_double(in + 16);
        l.o = fbrl_le_get_double(in + 24);
        l.a = fbrl_le_get_double(in + 32);
        l.t = fbrl_le_get_double(in + 40);
        memcpy(value, &l, sizeof l);
        break;
    }
    case FBRL_FT_USER: memcpy(value, in, t.size); break;
    }
}

/* Every record well formed, reals finite, exactly `count` records filling `len` bytes. */
static fbrl_status check_records(const unsigned char *buf, size_t len, uint32_t count)
{
    size_t pos = 0;
    uint32_t n = 0;
    while (pos < len) {
        if (len - pos < FBRL_FILE_RECORD_HEADER)
            return FBRL_EFORMAT;
        const unsigned char *rec = buf + pos;
        fbrl_ftype t = record_type(rec);
        if (rec[1] != 0 || !type_ok(rec[0], t.tag, t.size))
            return FBRL_EFORMAT;
        if (len - pos - FBRL_FILE_RECORD_HEADER < t.size)
            return FBRL_EFORMAT;
        const unsigned char *p = rec + FBRL_FILE_RECORD_HEADER;
        if (t.code == FBRL_FT_REAL || t.code == FBRL_FT_LOCATION)
            for (uint32_t i = 0; i < t.size; i += 8)
                if (!isfinite(fbrl_le_get_double(p + i)))
                    return FBRL_EFORMAT;
        pos += FBRL_FILE_RECORD_SIZE(t.size);
        if (++n == 0)
            return FBRL_EFORMAT;
    }
    return n == count ? FBRL_OK : FBRL_EFORMAT;
}

static fbrl_status check_path(const char *path)
{
    if (!path || !path[0])
        return FBRL_EINVAL;
    size_t n = strlen(path);
    return n >= FBRL_FILE_PATH_MAX || path[n - 1] == '/' ? FBRL_ENAME : FBRL_OK;
}

fbrl_status fbrl_file_remove_temporaries(const char *path, unsigned *removed)
{
    fbrl_status st = check_path(path);
    if (removed)
        *removed = 0;
    return st != FBRL_OK ? st : fbrl__fstore_sweep(path, removed);
}

static void make_header(unsigned char *h, const unsigned char *data, size_t len, uint32_t count)
{
    memcpy(h, magic, sizeof magic);
    fbrl_le_put16(h + 8, (uint16_t)FBRL_FILE_VERSION);
    fbrl_le_put16(h + 10, (uint16_t)FBRL_FILE_HEADER_SIZE);
    fbrl_le_put32(h + 12, (uint32_t)(FBRL_FILE_HEADER_SIZE + len));
    fbrl_le_put32(h + 16, count);
    fbrl_le_put32(h + 20, fbrl_crc32(0, data, len));
    fbrl_le_put32(h + 24, 0);
    fbrl_le_put32(h + 28, fbrl_crc32(0, h, 28));
}

/* ---- the words ---- */

fbrl_status fbrl_file_create(const char *path)
{
    fbrl_status st = check_path(path);
    if (st != FBRL_OK)
        return st;
    unsigned char h[FBRL_FILE_HEADER_SIZE];
    make_header(h, NULL, 0, 0);
    return fbrl__fstore_replace(path, fbrl__fstore_mode(path), h, NULL, 0);
}

/* Verify the header (as much of it as `got` bytes hold) and the file size. */
static fbrl_status check_header(const unsigned char *h, size_t got, uint64_t file_size, uint32_t *len,
                                uint32_t *count)
{
    size_t m = got < sizeof magic ? got : sizeof magic;
    if (memcmp(h, magic, m) != 0)
        return FBRL_EFORMAT;
    if (got < 10)
        return FBRL_ETRUNCATED;
    if (fbrl_le_get16(h + 8) != FBRL_FILE_VERSION)
        return FBRL_EVERSION;
    if (got < FBRL_FILE_HEADER_SIZE)
        return FBRL_ETRUNCATED;
    if (fbrl_le_get32(h + 28) != fbrl_crc32(0, h, 28))
        return FBRL_ECHECKSUM;
    uint32_t total = fbrl_le_get32(h + 12);
    if (fbrl_le_get16(h + 10) != FBRL_FILE_HEADER_SIZE || fbrl_le_get32(h + 24) != 0 ||
        total < FBRL_FILE_HEADER_SIZE)
        return FBRL_EFORMAT;
    if ((uint64_t)file_size < total)
        return FBRL_ETRUNCATED;
    if ((uint64_t)file_size > total)
        return FBRL_EFORMAT; /* bytes after the end: not what was written */
    *len = total - FBRL_FILE_HEADER_SIZE;
    *count = fbrl_le_get32(h + 16);
    return FBRL_OK;
}

static fbrl_status load(fbrl_file *f, void *fh, uint64_t size, uint32_t mode, unsigned char *buf, size_t cap)
{
    unsigned char h[FBRL_FILE_HEADER_SIZE];
    size_t got;
    uint32_t len = 0, count = 0;
    fbrl_status st = fbrl__fstore_read(fh, h, sizeof h, &got);
    if (st == FBRL_OK)
        st = check_header(h, got, size, &len, &count);
    if (st != FBRL_OK)
        return st;
    if (len > cap)
        return FBRL_ENOSPC;
    if ((st = fbrl__fstore_read(fh, buf, len, &got)) != FBRL_OK)
        return st;
    if (got < len)
        return FBRL_ETRUNCATED; /* shrank since it was opened: not written by this library */
    unsigned char extra;
    if ((st = fbrl__fstore_read(fh, &extra, 1, &got)) != FBRL_OK)
        return st;
    if (got != 0)
        return FBRL_EFORMAT;
    if (fbrl_crc32(0, buf, len) != fbrl_le_get32(h + 20))
        return FBRL_ECHECKSUM;
    if ((st = check_records(buf, len, count)) != FBRL_OK)
        return st;
    f->buf = buf;
    f->cap = cap;
    f->len = len;
    f->pos = 0;
    f->count = count;
    f->index = 0;
    f->mode = mode;
    f->dirty = 0;
    return FBRL_OK;
}

fbrl_status fbrl_file_open(fbrl_file *f, const char *path, void *buf, size_t cap)
{
    if (!f)
        return FBRL_EINVAL;
    f->state = 0;
    fbrl_status st = check_path(path);
    if (st != FBRL_OK)
        return st;
    if (!buf || cap == 0)
        return FBRL_EINVAL;
    void *fh;
    uint64_t size;
    uint32_t mode;
    if ((st = fbrl__fstore_open(path, &fh, &size, &mode)) != FBRL_OK)
        return st;
    st = load(f, fh, size, mode, buf, cap);
    fbrl__fstore_close(fh);
    if (st != FBRL_OK)
        return st;
    memcpy(f->path, path, strlen(path) + 1);
    f->state = OPEN_MARK;
    return FBRL_OK;
}

static int is_open(const fbrl_file *f) { return f && f->state == OPEN_MARK; }

static fbrl_status check_handle(const fbrl_file *f)
{
    if (!f)
        return FBRL_EINVAL;
    return is_open(f) ? FBRL_OK : FBRL_ESTATE;
}

fbrl_status fbrl_file_reset(fbrl_file *f)
{
    fbrl_status st = check_handle(f);
    if (st != FBRL_OK)
        return st;
    f->pos = 0;
    f->index = 0;
    return FBRL_OK;
}

fbrl_status fbrl_file_append(fbrl_file *f)
{
    fbrl_status st = check_handle(f);
    if (st != FBRL_OK)
        return st;
    f->pos = f->len;
    f->index = f->count;
    return FBRL_OK;
}

fbrl_status fbrl_file_truncate(fbrl_file *f)
{
    fbrl_status st = check_handle(f);
    if (st != FBRL_OK)
        return st;
    if (f->pos != f->len) {
        f->len = f->pos;
        f->count = f->index;
        f->dirty = 1;
    }
    return FBRL_OK;
}

fbrl_status fbrl_file_write(fbrl_file *f, fbrl_ftype type, const void *value)
{
    fbrl_status st = check_handle(f);
    if (st != FBRL_OK)
        return st;
    if (!value || !type_ok(type.code, type.tag, type.size))
        return FBRL_EINVAL;
    if (!value_finite(type, value))
        return FBRL_ENONFINITE;

    /* Bytes freed by the record being replaced (none when appending). */
    int at_end = f->pos == f->len;
    size_t old = at_end ? 0 : FBRL_FILE_RECORD_SIZE(record_type(f->buf + f->pos).size);
    size_t rec = FBRL_FILE_RECORD_SIZE(type.size);
    if (at_end && f->count == UINT32_MAX)
        return FBRL_EFULL;
    if (f->len - old > UINT32_MAX - FBRL_FILE_HEADER_SIZE - rec)
        return FBRL_EFULL; /* the file length field is 32 bits */
    if (rec > f->cap - (f->len - old))
        return FBRL_ENOSPC;

    unsigned char *r = f->buf + f->pos;
    memmove(r + rec, r + old, f->len - f->pos - old);
    f->len = f->len - old + rec;
    r[0] = (unsigned char)type.code;
    r[1] = 0;
    fbrl_le_put16(r + 2, type.tag);
    fbrl_le_put32(r + 4, type.size);
    encode_value(type, value, r + FBRL_FILE_RECORD_HEADER);
    f->pos += rec;
    f->index++;
    if (at_end)
        f->count++;
    f->dirty = 1;
    return FBRL_OK;
}

fbrl_status fbrl_file_peek(const fbrl_file *f, fbrl_ftype *type)
{
    fbrl_status st = check_handle(f);
    if (st != FBRL_OK)
        return st;
    if (!type)
        return FBRL_EINVAL;
    if (f->pos == f->len)
        return FBRL_EEOF;
    *type = record_type(f->buf + f->pos);
    return FBRL_OK;
}

fbrl_status fbrl_file_read(fbrl_file *f, fbrl_ftype type, void *value)
{
    fbrl_status st = check_handle(f);
    if (st != FBRL_OK)
        return st;
    if (!value || !type_ok(type.code, type.tag, type.size))
        return FBRL_EINVAL;
    if (f->pos == f->len)
        return FBRL_EEOF;
    const unsigned char *r = f->buf + f->pos;
    if (!same_type(record_type(r), type))
        return FBRL_ETYPE;
    decode_value(type, r + FBRL_FILE_RECORD_HEADER, value);
    f->pos += FBRL_FILE_RECORD_SIZE(type.size);
    f->index++;
    return FBRL_OK;
}

fbrl_status fbrl_file_tell(const fbrl_file *f, uint32_t *index, uint32_t *count)
{
    fbrl_status st = check_handle(f);
    if (st != FBRL_OK)
        return st;
    if (index)
        *index = f->index;
    if (count)
        *count = f->count;
    return FBRL_OK;
}

fbrl_status fbrl_file_commit(fbrl_file *f)
{
    fbrl_status st = check_handle(f);
    if (st != FBRL_OK || !f->dirty)
        return st;
    unsigned char h[FBRL_FILE_HEADER_SIZE];
    make_header(h, f->buf, f->len, f->count);
    st = fbrl__fstore_replace(f->path, (long)f->mode, h, f->buf, f->len);
    if (st == FBRL_OK)
        f->dirty = 0;
    return st;
}

fbrl_status fbrl_file_close(fbrl_file *f)
{
    fbrl_status st = fbrl_file_commit(f);
    if (st == FBRL_OK)
        f->state = 0;
    return st;
}

fbrl_status fbrl_file_discard(fbrl_file *f)
{
    fbrl_status st = check_handle(f);
    if (st == FBRL_OK)
        f->state = 0;
    return st;
}

/* ---- typed shorthands ---- */

fbrl_status fbrl_file_write_chr(fbrl_file *f, unsigned char v)
{
    return fbrl_file_write(f, fbrl_ftype_chr, &v);
}

fbrl_status fbrl_file_write_integer(fbrl_file *f, int16_t v)
{
    return fbrl_file_write(f, fbrl_ftype_integer, &v);
}

fbrl_status fbrl_file_write_long(fbrl_file *f, int32_t v) { return fbrl_file_write(f, fbrl_ftype_long, &v); }

fbrl_status fbrl_file_write_real(fbrl_file *f, double v) { return fbrl_file_write(f, fbrl_ftype_real, &v); }

fbrl_status fbrl_file_write_loc(fbrl_file *f, const fbrl_loc *v)
{
    return fbrl_file_write(f, fbrl_ftype_location, v);
}

fbrl_status fbrl_file_write_user(fbrl_file *f, uint16_t tag, const void *data, size_t size)
{
    if (size > UINT32_MAX)
        return FBRL_EINVAL;
    return fbrl_file_write(f, fbrl_ftype_user(tag, (uint32_t)size), data);
}

fbrl_status fbrl_file_read_chr(fbrl_file *f, unsigned char *v)
{
    return fbrl_file_read(f, fbrl_ftype_chr, v);
}

fbrl_status fbrl_file_read_integer(fbrl_file *f, int16_t *v)
{
    return fbrl_file_read(f, fbrl_ftype_integer, v);
}

fbrl_status fbrl_file_read_long(fbrl_file *f, int32_t *v) { return fbrl_file_read(f, fbrl_ftype_long, v); }

fbrl_status fbrl_file_read_real(fbrl_file *f, double *v) { return fbrl_file_read(f, fbrl_ftype_real, v); }

fbrl_status fbrl_file_read_loc(fbrl_file *f, fbrl_loc *v)
{
    return fbrl_file_read(f, fbrl_ftype_location, v);
}

fbrl_status fbrl_file_read_user(fbrl_file *f, uint16_t tag, void *data, size_t size)
{
    if (size > UINT32_MAX)
        return FBRL_EINVAL;
    return fbrl_file_read(f, fbrl_ftype_user(tag, (uint32_t)size), data);
}
