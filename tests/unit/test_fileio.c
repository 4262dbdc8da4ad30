/* SPDX-License-Identifier: MIT */
/* test_fileio.c - typed data files on real files in a temporary directory: round trips,
 * the byte-exact format, type checks, every truncation, every bit flip, and writers killed
 * with SIGKILL mid-commit. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include "fbrl/crc32.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <float.h>
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "fbrl/fileio.h"

/* ---- scratch directory and raw file helpers ---- */

static char dir[512];

#define PATH_LEN 800

/* A path in the scratch directory, into the caller's storage. */
static void path_in(char *out, const char *name) { snprintf(out, PATH_LEN, "%s/%s", dir, name); }

/* The same, for use within one expression (a few rotating buffers). */
static const char *in_dir(const char *name)
{
    static char p[4][768];
    static int k;
    k = (k + 1) % 4;
    snprintf(p[k], sizeof p[k], "%s/%s", dir, name);
    return p[k];
}

static void remove_tree(const char *d)
{
    DIR *dp = opendir(d);
    if (!dp)
        return;
    struct dirent *e;
    char p[1024];
    while ((e = readdir(dp)) != NULL) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        snprintf(p, sizeof p, "%s/%s", d, e->d_name);
        struct stat sb;
        if (lstat(p, &sb) == 0 && S_ISDIR(sb.st_mode))
            remove_tree(p);
        else
            unlink(p);
    }
    closedir(dp);
    rmdir(d);
}

static int make_dir(void **state)
{
    (void)state;
    snprintf(dir, sizeof dir, "%s/fileio-test-XXXXXX", FBRL_TEST_BINDIR);
    return mkdtemp(dir) ? 0 : -1;
}

static int drop_dir(void **state)
{
    (void)state;
    remove_tree(dir);
    return 0;
}

static void put_raw(const char *path, const unsigned char *b, size_t n)
{
    int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, b, n), (ssize_t)n);
    assert_int_equal(close(fd), 0);
}

static size_t get_raw(const char *path, unsigned char *b, size_t cap)
{
    int fd = open(path, O_RDONLY);
    assert_true(fd >= 0);
    ssize_t n = read(fd, b, cap);
    assert_true(n >= 0 && (size_t)n < cap); /* whole file fits */
    close(fd);
    return (size_t)n;
}

static int count_temporaries(void)
{
    DIR *dp = opendir(dir);
    assert_non_null(dp);
    int n = 0;
    struct dirent *e;
    while ((e = readdir(dp)) != NULL) {
        size_t l = strlen(e->d_name);
        if (e->d_name[0] == '.' && l > 4 && !strcmp(e->d_name + l - 4, ".tmp"))
            n++;
    }
    closedir(dp);
    return n;
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* ---- a sample file holding every type ---- */

static const unsigned char chrs[] = {0, 'A', 255};
static const int16_t ints[] = {INT16_MIN, -1, 0, 1, 0x1234, INT16_MAX};
static const int32_t longs[] = {INT32_MIN, -123456789, -1, 0, 0x12345678, INT32_MAX};
static double reals[] = {0.0, -0.0, 1.0, -3.141592653589793, 1e-300, 4.9e-324, DBL_MAX, -DBL_MAX};
static const fbrl_loc locs[] = {
    {10.5, -3.25, 7.0, 45.0, -90.0, 180.0}, {0, 0, 0, 0, 0, 0}, {-22.0, 22.0, 1e-9, -175.0, 110.0, -180.0}};

/* User types: told apart by tag and size, including one sized like a REAL. */
static void user_bytes(unsigned char *b, size_t n, unsigned seed)
{
    for (size_t i = 0; i < n; i++)
        b[i] = (unsigned char)(seed * 31u + i * 7u);
}

static const struct {
    uint16_t tag;
    uint32_t size;
} users[] = {{0, 1}, {7, 3}, {7, 100}, {65535, 8}, {42, 300}};

#define N_ALL (3 + 6 + 6 + 8 + 3 + 5)

static void write_all(fbrl_file *f)
{
    unsigned char ub[300];
    for (size_t i = 0; i < sizeof chrs; i++)
        assert_int_equal(fbrl_file_write_chr(f, chrs[i]), FBRL_OK);
    for (size_t i = 0; i < 6; i++)
        assert_int_equal(fbrl_file_write_integer(f, ints[i]), FBRL_OK);
    for (size_t i = 0; i < 6; i++)
        assert_int_equal(fbrl_file_write_long(f, longs[i]), FBRL_OK);
    for (size_t i = 0; i < 8; i++)
        assert_int_equal(fbrl_file_write_real(f, reals[i]), FBRL_OK);
    for (size_t i = 0; i < 3; i++)
        assert_int_equal(fbrl_file_write_loc(f, &locs[i]), FBRL_OK);
    for (size_t i = 0; i < 5; i++) {
        user_bytes(ub, users[i].size, (unsigned)i);
        assert_int_equal(fbrl_file_write(f, fbrl_ftype_user(users[i].tag, users[i].size), ub), FBRL_OK);
    }
}

static void read_all(fbrl_file *f)
{
    unsigned char c, ub[300], want[300];
    int16_t s;
    int32_t l;
    double d;
    fbrl_loc loc;
    fbrl_ftype t;
    for (size_t i = 0; i < sizeof chrs; i++) {
        assert_int_equal(fbrl_file_peek(f, &t), FBRL_OK);
        assert_int_equal(t.code, FBRL_FT_CHR);
        assert_int_equal(fbrl_file_read_chr(f, &c), FBRL_OK);
        assert_int_equal(c, chrs[i]);
    }
    for (size_t i = 0; i < 6; i++) {
        assert_int_equal(fbrl_file_read_integer(f, &s), FBRL_OK);
        assert_int_equal(s, ints[i]);
    }
    for (size_t i = 0; i < 6; i++) {
        assert_int_equal(fbrl_file_read_long(f, &l), FBRL_OK);
        assert_int_equal(l, longs[i]);
    }
    for (size_t i = 0; i < 8; i++) {
        assert_int_equal(fbrl_file_read_real(f, &d), FBRL_OK);
        assert_true(same_bits(d, reals[i])); /* bit-exact, -0.0 and subnormals too */
    }
    for (size_t i = 0; i < 3; i++) {
        assert_int_equal(fbrl_file_read_loc(f, &loc), FBRL_OK);
        assert_memory_equal(&loc, &locs[i], sizeof loc);
    }
    for (size_t i = 0; i < 5; i++) {
        assert_int_equal(fbrl_file_peek(f, &t), FBRL_OK);
        assert_int_equal(t.code, FBRL_FT_USER);
        assert_int_equal(t.tag, users[i].tag);
        assert_int_equal(t.size, users[i].size);
        assert_int_equal(fbrl_file_read_user(f, users[i].tag, ub, users[i].size), FBRL_OK);
        user_bytes(want, users[i].size, (unsigned)i);
        assert_memory_equal(ub, want, users[i].size);
    }
}

/* Bytes of the sample file, as written by the library. */
static size_t sample_file(const char *name, unsigned char *out, size_t cap)
{
    static unsigned char buf[4096];
    fbrl_file f;
    assert_int_equal(fbrl_file_create(in_dir(name)), FBRL_OK);
    assert_int_equal(fbrl_file_open(&f, in_dir(name), buf, sizeof buf), FBRL_OK);
    write_all(&f);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
    return get_raw(in_dir(name), out, cap);
}

/* ---- tests ---- */

static void round_trip_every_type(void **state)
{
    (void)state;
    static unsigned char buf[4096], buf2[4096];
    fbrl_file f;
    char p[PATH_LEN];
    path_in(p, "all.fbd");
    assert_int_equal(fbrl_file_create(p), FBRL_OK);
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    write_all(&f);
    uint32_t idx, cnt;
    assert_int_equal(fbrl_file_tell(&f, &idx, &cnt), FBRL_OK);
    assert_int_equal(idx, N_ALL);
    assert_int_equal(cnt, N_ALL);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);

    /* A fresh handle and buffer: everything comes from the disk. */
    memset(buf, 0xAA, sizeof buf);
    assert_int_equal(fbrl_file_open(&f, p, buf2, sizeof buf2), FBRL_OK);
    assert_int_equal(fbrl_file_tell(&f, &idx, &cnt), FBRL_OK);
    assert_int_equal(idx, 0);
    assert_int_equal(cnt, N_ALL);
    read_all(&f);
    unsigned char c;
    fbrl_ftype t;
    assert_int_equal(fbrl_file_read_chr(&f, &c), FBRL_EEOF);
    assert_int_equal(fbrl_file_peek(&f, &t), FBRL_EEOF);

    /* RESET-FILE reads it all again. */
    assert_int_equal(fbrl_file_reset(&f), FBRL_OK);
    read_all(&f);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);

    /* The buffer holds exactly the records: header + records == file size. */
    size_t records = 3 * FBRL_FILE_RECORD_SIZE(1) + 6 * FBRL_FILE_RECORD_SIZE(2) +
                     6 * FBRL_FILE_RECORD_SIZE(4) + 8 * FBRL_FILE_RECORD_SIZE(8) +
                     3 * FBRL_FILE_RECORD_SIZE(48);
    for (size_t i = 0; i < 5; i++)
        records += FBRL_FILE_RECORD_SIZE(users[i].size);
    struct stat sb;
    assert_int_equal(stat(p, &sb), 0);
    assert_int_equal((size_t)sb.st_size, FBRL_FILE_HEADER_SIZE + records);
    /* ...so a buffer of exactly that size is enough, one byte less is not. */
    assert_int_equal(fbrl_file_open(&f, p, buf, records), FBRL_OK);
    assert_int_equal(fbrl_file_discard(&f), FBRL_OK);
    assert_int_equal(fbrl_file_open(&f, p, buf, records - 1), FBRL_ENOSPC);
}

/* The documented format, byte for byte (docs/files.md), independent of host endianness. */
static void format_is_little_endian_byte_by_byte(void **state)
{
    (void)state;
    static unsigned char buf[256];
    fbrl_file f;
    char p[PATH_LEN];
    path_in(p, "golden.fbd");
    assert_int_equal(fbrl_file_create(p), FBRL_OK);
    unsigned char got[256];
    static const unsigned char empty_hdr[12] = {0x89, 'F', 'B', 'R', 'L', 'D', '\r', '\n', 1, 0, 32, 0};
    assert_int_equal(get_raw(p, got, sizeof got), 32);
    assert_memory_equal(got, empty_hdr, 12);

    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_write_integer(&f, 0x1234), FBRL_OK);
    assert_int_equal(fbrl_file_write_long(&f, -2), FBRL_OK);
    assert_int_equal(fbrl_file_write_real(&f, 1.0), FBRL_OK);
    assert_int_equal(fbrl_file_write_user(&f, 0x0102, "xyz", 3), FBRL_OK);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);

    static const unsigned char body[] = {2, 0, 0,    0,    2, 0, 0, 0, 0x34, 0x12,             /* INTEGER */
                                         3, 0, 0,    0,    4, 0, 0, 0, 0xfe, 0xff, 0xff, 0xff, /* LONG -2 */
                                         4, 0, 0,    0,    8, 0, 0, 0, 0,    0,    0,    0,
                                         0, 0, 0xf0, 0x3f,                               /* REAL 1.0 */
                                         6, 0, 0x02, 0x01, 3, 0, 0, 0, 'x',  'y',  'z'}; /* USER */
    size_t n = get_raw(p, got, sizeof got);
    assert_int_equal(n, 32 + sizeof body);
    assert_memory_equal(got, empty_hdr, 12);
    assert_int_equal(got[12] | got[13] << 8 | got[14] << 16 | (uint32_t)got[15] << 24, n);
    assert_int_equal(got[16], 4); /* record count */
    assert_int_equal(got[17] | got[18] | got[19], 0);
    uint32_t dcrc = fbrl_crc32(0, body, sizeof body);
    uint32_t hcrc = fbrl_crc32(0, got, 28);
    for (int i = 0; i < 4; i++) {
        assert_int_equal(got[20 + i], (dcrc >> (8 * i)) & 0xff);
        assert_int_equal(got[24 + i], 0);
        assert_int_equal(got[28 + i], (hcrc >> (8 * i)) & 0xff);
    }
    assert_memory_equal(got + 32, body, sizeof body);
}

static void reset_append_replace_truncate(void **state)
{
    (void)state;
    static unsigned char buf[1024];
    fbrl_file f;
    char p[PATH_LEN];
    path_in(p, "seq.fbd");
    int32_t l;
    int16_t s;
    double d;
    uint32_t idx, cnt;

    assert_int_equal(fbrl_file_create(p), FBRL_OK);
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    for (int32_t i = 0; i < 3; i++)
        assert_int_equal(fbrl_file_write_long(&f, i), FBRL_OK);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);

    /* APPEND-FILE adds after the last record. */
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_append(&f), FBRL_OK);
    assert_int_equal(fbrl_file_tell(&f, &idx, &cnt), FBRL_OK);
    assert_int_equal(idx, 3);
    assert_int_equal(fbrl_file_write_long(&f, 3), FBRL_OK);
    assert_int_equal(fbrl_file_write_long(&f, 4), FBRL_OK);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);

    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    for (int32_t i = 0; i < 5; i++) {
        assert_int_equal(fbrl_file_read_long(&f, &l), FBRL_OK);
        assert_int_equal(l, i);
    }
    assert_int_equal(fbrl_file_read_long(&f, &l), FBRL_EEOF);

    /* RESET then WRITE replaces record 0 (here by a smaller and then a larger type) and
     * keeps the records after it. */
    assert_int_equal(fbrl_file_reset(&f), FBRL_OK);
    assert_int_equal(fbrl_file_write_integer(&f, -7), FBRL_OK);
    assert_int_equal(fbrl_file_read_long(&f, &l), FBRL_OK);
    assert_int_equal(l, 1);
    assert_int_equal(fbrl_file_write_real(&f, 2.5), FBRL_OK); /* replaces long 2 */
    assert_int_equal(fbrl_file_tell(&f, &idx, &cnt), FBRL_OK);
    assert_int_equal(idx, 3);
    assert_int_equal(cnt, 5);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);

    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_read_integer(&f, &s), FBRL_OK);
    assert_int_equal(s, -7);
    assert_int_equal(fbrl_file_read_long(&f, &l), FBRL_OK);
    assert_int_equal(l, 1);
    assert_int_equal(fbrl_file_read_real(&f, &d), FBRL_OK);
    assert_true(d == 2.5);
    assert_int_equal(fbrl_file_read_long(&f, &l), FBRL_OK);
    assert_int_equal(l, 3);

    /* TRUNCATE drops the rest: here record 4 on. */
    assert_int_equal(fbrl_file_truncate(&f), FBRL_OK);
    assert_int_equal(fbrl_file_tell(&f, &idx, &cnt), FBRL_OK);
    assert_int_equal(cnt, 4);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_tell(&f, &idx, &cnt), FBRL_OK);
    assert_int_equal(cnt, 4);

    /* RESET + TRUNCATE + WRITE rewrites the file in one commit. */
    assert_int_equal(fbrl_file_truncate(&f), FBRL_OK);
    assert_int_equal(fbrl_file_write_long(&f, 99), FBRL_OK);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_read_long(&f, &l), FBRL_OK);
    assert_int_equal(l, 99);
    assert_int_equal(fbrl_file_read_long(&f, &l), FBRL_EEOF);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);

    /* CREATE-FILE on an existing file empties it. */
    assert_int_equal(fbrl_file_create(p), FBRL_OK);
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_tell(&f, &idx, &cnt), FBRL_OK);
    assert_int_equal(cnt, 0);
    assert_int_equal(fbrl_file_read_long(&f, &l), FBRL_EEOF);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
}

static void wrong_type_is_refused_and_nothing_lost(void **state)
{
    (void)state;
    static unsigned char buf[1024];
    fbrl_file f;
    char p[PATH_LEN];
    path_in(p, "types.fbd");
    unsigned char c, ub[8];
    int16_t s;
    int32_t l;
    double d = 0;
    fbrl_loc loc;
    uint32_t idx;
    static const unsigned char u5[5] = {1, 2, 3, 4, 5};

    assert_int_equal(fbrl_file_create(p), FBRL_OK);
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_write_real(&f, 6.25), FBRL_OK);
    assert_int_equal(fbrl_file_write_user(&f, 9, u5, 5), FBRL_OK);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);

    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_read_chr(&f, &c), FBRL_ETYPE);
    assert_int_equal(fbrl_file_read_integer(&f, &s), FBRL_ETYPE);
    assert_int_equal(fbrl_file_read_long(&f, &l), FBRL_ETYPE);
    assert_int_equal(fbrl_file_read_loc(&f, &loc), FBRL_ETYPE);
    /* Same size, different type: still refused (the tag in the file decides). */
    assert_int_equal(fbrl_file_read_user(&f, 0, ub, 8), FBRL_ETYPE);
    assert_int_equal(fbrl_file_tell(&f, &idx, NULL), FBRL_OK);
    assert_int_equal(idx, 0);
    assert_int_equal(fbrl_file_read_real(&f, &d), FBRL_OK);
    assert_true(d == 6.25);

    /* A user type needs both its tag and its size. */
    assert_int_equal(fbrl_file_read_user(&f, 8, ub, 5), FBRL_ETYPE);
    assert_int_equal(fbrl_file_read_user(&f, 9, ub, 4), FBRL_ETYPE);
    assert_int_equal(fbrl_file_read_user(&f, 9, ub, 6), FBRL_ETYPE);
    assert_int_equal(fbrl_file_read_long(&f, &l), FBRL_ETYPE);
    assert_int_equal(fbrl_file_tell(&f, &idx, NULL), FBRL_OK);
    assert_int_equal(idx, 1);
    assert_int_equal(fbrl_file_read_user(&f, 9, ub, 5), FBRL_OK);
    assert_memory_equal(ub, u5, 5);
    assert_int_equal(fbrl_file_read_user(&f, 9, ub, 5), FBRL_EEOF);
    /* A refused read never marks the file changed: discarding loses nothing. */
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
}

/* The thesis's "a type is its length" mapping, for the language layer. */
static void type_of_size_follows_the_thesis(void **state)
{
    (void)state;
    assert_int_equal(fbrl_ftype_of_size(1).code, FBRL_FT_CHR);
    assert_int_equal(fbrl_ftype_of_size(2).code, FBRL_FT_INTEGER);
    assert_int_equal(fbrl_ftype_of_size(4).code, FBRL_FT_LONG);
    assert_int_equal(fbrl_ftype_of_size(8).code, FBRL_FT_REAL);
    assert_int_equal(fbrl_ftype_of_size(48).code, FBRL_FT_LOCATION);
    fbrl_ftype t = fbrl_ftype_of_size(12);
    assert_int_equal(t.code, FBRL_FT_USER);
    assert_int_equal(t.tag, 0);
    assert_int_equal(t.size, 12);
    assert_int_equal(fbrl_ftype_location.size, sizeof(fbrl_loc));
}

/* Readers see the last committed file; a handle keeps its snapshot. */
static void changes_are_invisible_until_commit(void **state)
{
    (void)state;
    static unsigned char wb[512], rb[512], rb2[512];
    fbrl_file w, r, r2;
    char p[PATH_LEN];
    path_in(p, "snap.fbd");
    uint32_t cnt;
    assert_int_equal(fbrl_file_create(p), FBRL_OK);
    assert_int_equal(fbrl_file_open(&w, p, wb, sizeof wb), FBRL_OK);
    assert_int_equal(fbrl_file_write_long(&w, 1), FBRL_OK);
    assert_int_equal(fbrl_file_open(&r, p, rb, sizeof rb), FBRL_OK);
    assert_int_equal(fbrl_file_tell(&r, NULL, &cnt), FBRL_OK);
    assert_int_equal(cnt, 0);
    assert_int_equal(fbrl_file_commit(&w), FBRL_OK);
    assert_int_equal(count_temporaries(), 0);
    assert_int_equal(fbrl_file_open(&r2, p, rb2, sizeof rb2), FBRL_OK);
    assert_int_equal(fbrl_file_tell(&r2, NULL, &cnt), FBRL_OK);
    assert_int_equal(cnt, 1);
    assert_int_equal(fbrl_file_tell(&r, NULL, &cnt), FBRL_OK);
    assert_int_equal(cnt, 0);

    /* Discard drops unsaved changes. */
    assert_int_equal(fbrl_file_write_long(&w, 2), FBRL_OK);
    assert_int_equal(fbrl_file_discard(&w), FBRL_OK);
    assert_int_equal(fbrl_file_open(&w, p, wb, sizeof wb), FBRL_OK);
    assert_int_equal(fbrl_file_tell(&w, NULL, &cnt), FBRL_OK);
    assert_int_equal(cnt, 1);
    assert_int_equal(fbrl_file_close(&w), FBRL_OK);
    assert_int_equal(fbrl_file_close(&r), FBRL_OK);
    assert_int_equal(fbrl_file_close(&r2), FBRL_OK);
}

static void commit_keeps_permissions(void **state)
{
    (void)state;
    static unsigned char buf[256];
    fbrl_file f;
    char p[PATH_LEN];
    path_in(p, "mode.fbd");
    struct stat sb;
    assert_int_equal(fbrl_file_create(p), FBRL_OK);
    assert_int_equal(chmod(p, 0640), 0);
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_write_chr(&f, 'm'), FBRL_OK);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
    assert_int_equal(stat(p, &sb), 0);
    assert_int_equal(sb.st_mode & 07777, 0640);
    assert_int_equal(fbrl_file_create(p), FBRL_OK);
    assert_int_equal(stat(p, &sb), 0);
    assert_int_equal(sb.st_mode & 07777, 0640);
}

/* Cut at every byte offset, including every record boundary: always ETRUNCATED. */
static void every_truncation_is_refused(void **state)
{
    (void)state;
    static unsigned char whole[4096], buf[4096];
    size_t n = sample_file("cut-src.fbd", whole, sizeof whole);
    assert_true(n > 900);
    char p[PATH_LEN];
    path_in(p, "cut.fbd");
    fbrl_file f;
    for (size_t cut = 0; cut < n; cut++) {
        put_raw(p, whole, cut);
        fbrl_status st = fbrl_file_open(&f, p, buf, sizeof buf);
        if (st != FBRL_ETRUNCATED)
            fail_msg("cut at %zu of %zu: %s", cut, n, fbrl_status_name(st));
        assert_int_equal(fbrl_file_read_chr(&f, buf), FBRL_ESTATE); /* handle stays closed */
    }
    /* A byte too many is refused as well, and the whole file is fine. */
    whole[n] = 0;
    put_raw(p, whole, n + 1);
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_EFORMAT);
    put_raw(p, whole, n);
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    read_all(&f);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
}

/* Every single flipped bit of a file holding every type is refused. */
static void every_bit_flip_is_refused(void **state)
{
    (void)state;
    static unsigned char whole[4096], buf[4096];
    fbrl_file f;
    char p[PATH_LEN];
    path_in(p, "flip.fbd");
    assert_int_equal(fbrl_file_create(p), FBRL_OK);
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_write_chr(&f, 'c'), FBRL_OK);
    assert_int_equal(fbrl_file_write_integer(&f, -300), FBRL_OK);
    assert_int_equal(fbrl_file_write_long(&f, 70000), FBRL_OK);
    assert_int_equal(fbrl_file_write_real(&f, 2.75), FBRL_OK);
    assert_int_equal(fbrl_file_write_loc(&f, &locs[0]), FBRL_OK);
    assert_int_equal(fbrl_file_write_user(&f, 3, "abcd", 4), FBRL_OK);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
    size_t n = get_raw(p, whole, sizeof whole);
    int flips = 0;
    for (size_t byte = 0; byte < n; byte++) {
        for (int bit = 0; bit < 8; bit++) {
            whole[byte] ^= (unsigned char)(1u << bit);
            put_raw(p, whole, n);
            fbrl_status want = byte < 8 ? FBRL_EFORMAT : byte < 10 ? FBRL_EVERSION : FBRL_ECHECKSUM;
            fbrl_status st = fbrl_file_open(&f, p, buf, sizeof buf);
            if (st != want)
                fail_msg("bit %d of byte %zu: %s, expected %s", bit, byte, fbrl_status_name(st),
                         fbrl_status_name(want));
            whole[byte] ^= (unsigned char)(1u << bit);
            flips++;
        }
    }
    assert_int_equal(flips, (int)(8 * n));
    put_raw(p, whole, n);
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
}

/* Recompute both CRCs after editing a file's bytes, to reach the checks behind them. */
static void reseal(unsigned char *b, size_t n)
{
    uint32_t d = fbrl_crc32(0, b + 32, n - 32);
    for (int i = 0; i < 4; i++)
        b[20 + i] = (unsigned char)(d >> (8 * i));
    uint32_t h = fbrl_crc32(0, b, 28);
    for (int i = 0; i < 4; i++)
        b[28 + i] = (unsigned char)(h >> (8 * i));
}

/* Open a copy of orig with bytes changed ({offset, value} pairs) and both CRCs recomputed. */
struct edit {
    size_t at;
    unsigned char v;
};

static fbrl_status open_edited(const unsigned char *orig, size_t n, const struct edit *e, int k)
{
    static unsigned char b[512], buf[512];
    fbrl_file f;
    memcpy(b, orig, n);
    for (int i = 0; i < k; i++)
        b[e[i].at] = e[i].v;
    reseal(b, n);
    put_raw(in_dir("edit.fbd"), b, n);
    fbrl_status st = fbrl_file_open(&f, in_dir("edit.fbd"), buf, sizeof buf);
    if (st == FBRL_OK)
        assert_int_equal(fbrl_file_discard(&f), FBRL_OK);
    return st;
}

#define EDIT(...)                                         \
    open_edited(b, n, (const struct edit[]){__VA_ARGS__}, \
                (int)(sizeof((const struct edit[]){__VA_ARGS__}) / sizeof(struct edit)))

/* Files with valid checksums but impossible contents are refused too. */
static void well_sealed_nonsense_is_refused(void **state)
{
    (void)state;
    static unsigned char buf[512], b[512];
    fbrl_file f;
    char p[PATH_LEN];
    path_in(p, "seal.fbd");
    assert_int_equal(fbrl_file_create(p), FBRL_OK);
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_write_real(&f, 1.5), FBRL_OK); /* record at 32 */
    assert_int_equal(fbrl_file_write_chr(&f, 'z'), FBRL_OK);  /* record at 48 */
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
    size_t n = get_raw(p, b, sizeof b);
    assert_int_equal(n, 32 + 16 + 9);
    assert_int_equal(EDIT({8, 1}), FBRL_OK);                      /* unchanged, resealed */
    assert_int_equal(EDIT({48, 6}), FBRL_OK);                     /* CHR -> USER tag 0 size 1 */
    assert_int_equal(EDIT({8, 2}), FBRL_EVERSION);                /* a future version */
    assert_int_equal(EDIT({10, 33}), FBRL_EFORMAT);               /* header size */
    assert_int_equal(EDIT({12, 58}), FBRL_ETRUNCATED);            /* file length one more */
    assert_int_equal(EDIT({12, 56}), FBRL_EFORMAT);               /* file length one less */
    assert_int_equal(EDIT({12, 0}, {13, 0}), FBRL_EFORMAT);       /* file length 0 */
    assert_int_equal(EDIT({16, 3}), FBRL_EFORMAT);                /* count says 3 records */
    assert_int_equal(EDIT({16, 1}), FBRL_EFORMAT);                /* count says 1 */
    assert_int_equal(EDIT({24, 1}), FBRL_EFORMAT);                /* reserved field */
    assert_int_equal(EDIT({32, 0}), FBRL_EFORMAT);                /* type code 0 */
    assert_int_equal(EDIT({32, 7}), FBRL_EFORMAT);                /* type code 7 */
    assert_int_equal(EDIT({33, 1}), FBRL_EFORMAT);                /* reserved byte */
    assert_int_equal(EDIT({34, 1}), FBRL_EFORMAT);                /* tag on a built-in type */
    assert_int_equal(EDIT({36, 4}), FBRL_EFORMAT);                /* REAL of 4 bytes */
    assert_int_equal(EDIT({47, 0x7f}), FBRL_EFORMAT);             /* REAL is now NaN */
    assert_int_equal(EDIT({46, 0xf0}, {47, 0x7f}), FBRL_EFORMAT); /* REAL is +inf */
    assert_int_equal(EDIT({48, 6}, {52, 2}), FBRL_EFORMAT);       /* USER runs past the end */
    assert_int_equal(EDIT({48, 6}, {52, 0}), FBRL_EFORMAT);       /* USER of 0 bytes */
}

/* Any file open accepts reads completely, record by record, with the types peek reports. */
static void read_through(fbrl_file *f)
{
    static unsigned char v[4096];
    fbrl_ftype t;
    uint32_t n = 0, cnt;
    fbrl_status st;
    while ((st = fbrl_file_peek(f, &t)) == FBRL_OK) {
        assert_int_equal(fbrl_file_read(f, t, v), FBRL_OK);
        n++;
    }
    assert_int_equal(st, FBRL_EEOF);
    assert_int_equal(fbrl_file_tell(f, NULL, &cnt), FBRL_OK);
    assert_int_equal(n, cnt);
}

static uint32_t rng(void);

/* Random damage (bytes overwritten, inserted, removed), raw or resealed with correct CRCs:
 * raw damage is always refused; resealed damage is refused or reads completely. Under
 * ASan this is a small fuzzer of the record walk. */
static void random_damage_is_refused(void **state)
{
    (void)state;
    static unsigned char whole[4096], b[4200], buf[4096];
    size_t n = sample_file("dmg-src.fbd", whole, sizeof whole);
    char p[PATH_LEN];
    path_in(p, "dmg.fbd");
    fbrl_file f;
    int refused = 0, accepted = 0;
    for (int run = 0; run < 3000; run++) {
        size_t m = n;
        memcpy(b, whole, n);
        int edits = 1 + (int)(rng() % 4);
        for (int e = 0; e < edits; e++) {
            size_t at = 32 + rng() % (m - 32);
            switch (rng() % 3) {
            case 0: b[at] = (unsigned char)rng(); break;
            case 1:
                memmove(b + at + 1, b + at, m - at);
                b[at] = (unsigned char)rng();
                m++;
                break;
            default:
                memmove(b + at, b + at + 1, m - at - 1);
                m--;
                break;
            }
        }
        int same = m == n && memcmp(b, whole, n) == 0;
        int sealed = run % 2;
        if (sealed) {
            for (int i = 0; i < 4; i++)
                b[12 + i] = (unsigned char)(m >> (8 * i)); /* the length it now has */
            reseal(b, m);
        }
        put_raw(p, b, m);
        fbrl_status st = fbrl_file_open(&f, p, buf, sizeof buf);
        if (st == FBRL_OK) {
            if (!sealed && !same)
                fail_msg("run %d: damaged file opened", run);
            read_through(&f);
            assert_int_equal(fbrl_file_discard(&f), FBRL_OK);
            accepted++;
        } else {
            assert_true(st == FBRL_EFORMAT || st == FBRL_ECHECKSUM || st == FBRL_ETRUNCATED);
            refused++;
        }
    }
    print_message("random damage: %d refused, %d accepted (resealed or unchanged)\n", refused, accepted);
}

/* ---- writers killed with SIGKILL in the middle of commits ---- */

#define KILL_RUNS 200

static uint32_t rng_state = 1;

static uint32_t rng(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return rng_state;
}

/* Generation g: LONG g, then 1 + g % 37 records of every type derived from g, so files of
 * different generations differ in length, types and contents. */
static uint32_t gen_records(uint32_t g) { return 1 + g % 37; }

static void gen_user(unsigned char *b, uint32_t g, uint32_t i, uint16_t *tag, uint32_t *size)
{
    *tag = (uint16_t)((g + i) % 7);
    *size = 1 + (g + i) % 23;
    for (uint32_t k = 0; k < *size; k++)
        b[k] = (unsigned char)(g * 13 + i * 5 + k);
}

static fbrl_loc gen_loc(uint32_t g, uint32_t i)
{
    fbrl_loc l = {g, i, -(double)g, g * 0.5, -(double)i, g + i + 0.25};
    return l;
}

static fbrl_status gen_write(fbrl_file *f, uint32_t g)
{
    fbrl_status st = fbrl_file_write_long(f, (int32_t)g);
    unsigned char ub[32];
    uint16_t tag;
    uint32_t size;
    for (uint32_t i = 0; st == FBRL_OK && i < gen_records(g); i++) {
        fbrl_loc l = gen_loc(g, i);
        switch (i % 5) {
        case 0: st = fbrl_file_write_chr(f, (unsigned char)(g + i)); break;
        case 1: st = fbrl_file_write_integer(f, (int16_t)(g * 3 + i)); break;
        case 2: st = fbrl_file_write_real(f, g + i / 4.0); break;
        case 3: st = fbrl_file_write_loc(f, &l); break;
        default: gen_user(ub, g, i, &tag, &size); st = fbrl_file_write_user(f, tag, ub, size);
        }
    }
    return st;
}

/* The file at path is one complete generation; returns it. */
static uint32_t gen_check(const char *path)
{
    static unsigned char buf[8192];
    fbrl_file f;
    int32_t g;
    uint32_t cnt;
    assert_int_equal(fbrl_file_open(&f, path, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_read_long(&f, &g), FBRL_OK);
    assert_int_equal(fbrl_file_tell(&f, NULL, &cnt), FBRL_OK);
    assert_int_equal(cnt, 1 + gen_records((uint32_t)g));
    for (uint32_t i = 0; i < gen_records((uint32_t)g); i++) {
        unsigned char c, ub[32], want[32];
        int16_t s;
        double d;
        fbrl_loc l, lw = gen_loc((uint32_t)g, i);
        uint16_t tag;
        uint32_t size;
        switch (i % 5) {
        case 0:
            assert_int_equal(fbrl_file_read_chr(&f, &c), FBRL_OK);
            assert_int_equal(c, (unsigned char)((uint32_t)g + i));
            break;
        case 1:
            assert_int_equal(fbrl_file_read_integer(&f, &s), FBRL_OK);
            assert_int_equal(s, (int16_t)((uint32_t)g * 3 + i));
            break;
        case 2:
            assert_int_equal(fbrl_file_read_real(&f, &d), FBRL_OK);
            assert_true(d == (uint32_t)g + i / 4.0);
            break;
        case 3:
            assert_int_equal(fbrl_file_read_loc(&f, &l), FBRL_OK);
            assert_memory_equal(&l, &lw, sizeof l);
            break;
        default:
            gen_user(want, (uint32_t)g, i, &tag, &size);
            assert_int_equal(fbrl_file_read_user(&f, tag, ub, size), FBRL_OK);
            assert_memory_equal(ub, want, size);
        }
    }
    assert_int_equal(fbrl_file_read_chr(&f, buf), FBRL_EEOF);
    assert_int_equal(fbrl_file_discard(&f), FBRL_OK);
    return (uint32_t)g;
}

/* Rewrite path with generations g+1, g+2, ... until killed, telling `done` of each commit;
 * any error exits. */
static void writer_child(const char *path, uint32_t g, int done)
{
    static unsigned char buf[8192];
    fbrl_file f;
    for (;;) {
        g++;
        if (fbrl_file_open(&f, path, buf, sizeof buf) != FBRL_OK || fbrl_file_truncate(&f) != FBRL_OK ||
            gen_write(&f, g) != FBRL_OK || fbrl_file_close(&f) != FBRL_OK || write(done, "c", 1) != 1)
            _exit(3);
    }
}

static void killed_writers_leave_old_or_new_file(void **state)
{
    (void)state;
    static unsigned char buf[8192];
    char p[PATH_LEN];
    path_in(p, "kill.fbd");
    fbrl_file f;
    rng_state = (uint32_t)time(NULL) | 1u;
    uint32_t seed = rng_state;

    assert_int_equal(fbrl_file_create(p), FBRL_OK);
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(gen_write(&f, 0), FBRL_OK);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);

    uint32_t g = gen_check(p), first = g;
    int advanced = 0, unchanged = 0;
    for (int run = 0; run < KILL_RUNS; run++) {
        /* Delay 1 us .. 32 ms, spread evenly over the powers of two. */
        uint32_t base = 1u << (rng() % 15);
        uint32_t us = base + rng() % base;
        int done[2];
        assert_int_equal(pipe(done), 0);
        pid_t pid = fork();
        assert_true(pid >= 0);
        if (pid == 0) {
            close(done[0]);
            writer_child(p, g, done[1]);
        }
        close(done[1]);
        /* Every tenth run first waits for one commit, so even a machine too loaded to commit
         * within the random delay shows kills after commits too. */
        char c;
        if (run % 10 == 9)
            assert_int_equal(read(done[0], &c, 1), 1);
        struct timespec ts = {us / 1000000u, (long)(us % 1000000u) * 1000L};
        nanosleep(&ts, NULL);
        assert_int_equal(kill(pid, SIGKILL), 0);
        int ws;
        assert_int_equal(waitpid(pid, &ws, 0), pid);
        close(done[0]);
        if (!WIFSIGNALED(ws) || WTERMSIG(ws) != SIGKILL)
            fail_msg("run %d (seed %u): writer ended by itself, status %d", run, seed, ws);
        uint32_t now = gen_check(p); /* complete, one generation, never a mix */
        assert_true(now >= g);
        if (now > g)
            advanced++;
        else
            unchanged++;
        g = now;
    }
    int left = count_temporaries();
    print_message("kill test: %d runs (seed %u), %u generations committed, %d runs advanced the "
                  "file, %d left it unchanged, %d temporaries left behind\n",
                  KILL_RUNS, seed, g - first, advanced, unchanged, left);
    /* The kills landed both before and after commits: the test saw both outcomes. */
    assert_true(advanced > 0);
    assert_true(unchanged > 0);

    /* Leftover temporaries do not get in the way of later writes. */
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_truncate(&f), FBRL_OK);
    assert_int_equal(gen_write(&f, g + 1), FBRL_OK);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
    assert_int_equal(gen_check(p), g + 1);
    unsigned removed;
    assert_int_equal(fbrl_file_remove_temporaries(p, &removed), FBRL_OK);
    assert_int_equal(removed, left);
    assert_int_equal(count_temporaries(), 0);
    assert_int_equal(gen_check(p), g + 1);
}

/* Temporaries left with exactly the names this process would use first are skipped. */
static void leftover_temporaries_do_not_block_writes(void **state)
{
    (void)state;
    static unsigned char buf[256], raw[256];
    fbrl_file f;
    char p[PATH_LEN];
    path_in(p, "left.fbd");
    char name[128];
    static const unsigned char junk[] = "half-written junk";
    assert_int_equal(fbrl_file_create(p), FBRL_OK);
    for (int n = 0; n < 5; n++) {
        snprintf(name, sizeof name, ".left.fbd.%ld-%d.tmp", (long)getpid(), n);
        put_raw(in_dir(name), junk, sizeof junk);
    }
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_write_integer(&f, 321), FBRL_OK);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
    int16_t s;
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_read_integer(&f, &s), FBRL_OK);
    assert_int_equal(s, 321);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
    for (int n = 0; n < 5; n++) {
        snprintf(name, sizeof name, ".left.fbd.%ld-%d.tmp", (long)getpid(), n);
        assert_int_equal(get_raw(in_dir(name), raw, sizeof raw), sizeof junk);
        assert_memory_equal(raw, junk, sizeof junk);
    }

    /* Removing them takes exactly the temporaries of this file, nothing that only looks
     * like one. */
    static const char *const keep[] = {".left.fbd.12-3.tmpx", ".left.fbd.12.tmp",    ".left.fbd.-3.tmp",
                                       "left.fbd.12-3.tmp",   ".left.fbdx.12-3.tmp", ".other.fbd.12-3.tmp",
                                       ".left.fbd.12-3x.tmp"};
    for (size_t i = 0; i < sizeof keep / sizeof keep[0]; i++)
        put_raw(in_dir(keep[i]), junk, sizeof junk);
    unsigned removed;
    assert_int_equal(fbrl_file_remove_temporaries(p, &removed), FBRL_OK);
    assert_int_equal(removed, 5);
    for (size_t i = 0; i < sizeof keep / sizeof keep[0]; i++) {
        assert_int_equal(get_raw(in_dir(keep[i]), raw, sizeof raw), sizeof junk);
        unlink(in_dir(keep[i]));
    }
    assert_int_equal(fbrl_file_remove_temporaries(p, &removed), FBRL_OK);
    assert_int_equal(removed, 0);
    assert_int_equal(fbrl_file_remove_temporaries(p, NULL), FBRL_OK);
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
    assert_int_equal(fbrl_file_remove_temporaries(NULL, &removed), FBRL_EINVAL);
    assert_int_equal(fbrl_file_remove_temporaries(in_dir("nodir/x"), &removed), FBRL_ENOENT);
}

/* A failed commit leaves the old file and an open handle; discard then closes it. */
static void failed_commit_keeps_handle_open(void **state)
{
    (void)state;
    static unsigned char buf[256];
    fbrl_file f;
    char sub[PATH_LEN];
    path_in(sub, "gone");
    char p[PATH_LEN + 16];
    snprintf(p, sizeof p, "%s/x.fbd", sub);
    assert_int_equal(mkdir(sub, 0755), 0);
    assert_int_equal(fbrl_file_create(p), FBRL_OK);
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_write_chr(&f, 1), FBRL_OK);
    assert_int_equal(unlink(p), 0);
    assert_int_equal(rmdir(sub), 0);
    assert_int_equal(fbrl_file_commit(&f), FBRL_ENOENT);
    assert_int_equal(fbrl_file_close(&f), FBRL_ENOENT);
    uint32_t cnt;
    assert_int_equal(fbrl_file_tell(&f, NULL, &cnt), FBRL_OK); /* still open */
    assert_int_equal(cnt, 1);
    assert_int_equal(mkdir(sub, 0755), 0); /* the directory is back: the retry works */
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_write_chr(&f, 2), FBRL_OK);
    assert_int_equal(fbrl_file_discard(&f), FBRL_OK);
    assert_int_equal(fbrl_file_tell(&f, NULL, &cnt), FBRL_ESTATE);
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_tell(&f, NULL, &cnt), FBRL_OK);
    assert_int_equal(cnt, 1);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
}

/* What the OS said is named, not "input/output error": the errno table; a symbolic link
 * is written through (the link stays, its target changes, a chain and a link to a file not
 * made yet included); a link loop, a read-only file and a file size limit (EFBIG: the
 * disk-full status) are refused with nothing changed. */
static void os_errors_are_named_and_links_followed(void **state)
{
    (void)state;
    static unsigned char buf[256];
    fbrl_file f;
    char real[PATH_LEN], link1[PATH_LEN], link2[PATH_LEN], loop1[PATH_LEN], loop2[PATH_LEN];
    struct stat sb;
    assert_int_equal(fbrl_file_status_of_errno(0), FBRL_OK);
    assert_int_equal(fbrl_file_status_of_errno(EACCES), FBRL_EPERM);
    assert_int_equal(fbrl_file_status_of_errno(EPERM), FBRL_EPERM);
    assert_int_equal(fbrl_file_status_of_errno(ENOSPC), FBRL_EDISKFULL);
    assert_int_equal(fbrl_file_status_of_errno(EFBIG), FBRL_EDISKFULL);
    assert_int_equal(fbrl_file_status_of_errno(ELOOP), FBRL_ELOOP);
    assert_int_equal(fbrl_file_status_of_errno(EROFS), FBRL_EREADONLY);
    assert_int_equal(fbrl_file_status_of_errno(ENOENT), FBRL_ENOENT);
    assert_int_equal(fbrl_file_status_of_errno(EIO), FBRL_EIO);

    path_in(real, "real.fbd");
    path_in(link1, "link1.fbd");
    path_in(link2, "link2.fbd");
    assert_int_equal(symlink("real.fbd", link1), 0);  /* a link to a file not made yet */
    assert_int_equal(symlink("link1.fbd", link2), 0); /* and a chain of two */
    assert_int_equal(fbrl_file_create(link2), FBRL_OK);
    assert_int_equal(fbrl_file_open(&f, link2, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_write_chr(&f, 'L'), FBRL_OK);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
    assert_int_equal(lstat(link1, &sb), 0);
    assert_true(S_ISLNK(sb.st_mode));
    assert_int_equal(lstat(link2, &sb), 0);
    assert_true(S_ISLNK(sb.st_mode));
    assert_int_equal(fbrl_file_open(&f, real, buf, sizeof buf), FBRL_OK);
    unsigned char c = 0;
    assert_int_equal(fbrl_file_read_chr(&f, &c), FBRL_OK);
    assert_int_equal(c, 'L');
    assert_int_equal(fbrl_file_discard(&f), FBRL_OK);

    path_in(loop1, "loop1.fbd");
    path_in(loop2, "loop2.fbd");
    assert_int_equal(symlink("loop2.fbd", loop1), 0);
    assert_int_equal(symlink("loop1.fbd", loop2), 0);
    assert_int_equal(fbrl_file_create(loop1), FBRL_ELOOP);
    assert_int_equal(fbrl_file_open(&f, loop1, buf, sizeof buf), FBRL_ELOOP);

    assert_int_equal(chmod(real, 0444), 0); /* read-only: refused, even for root */
    assert_int_equal(fbrl_file_open(&f, link2, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_write_chr(&f, 'X'), FBRL_OK);
    assert_int_equal(fbrl_file_commit(&f), FBRL_EREADONLY);
    assert_int_equal(fbrl_file_discard(&f), FBRL_OK);
    assert_int_equal(fbrl_file_create(real), FBRL_EREADONLY);
    assert_int_equal(chmod(real, 0644), 0);

    /* a file size limit in a child (it must not end this test): EFBIG, named as no room */
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        struct rlimit rl = {0, 0};
        signal(SIGXFSZ, SIG_IGN);
        if (setrlimit(RLIMIT_FSIZE, &rl) != 0)
            _exit(2);
        fbrl_status st = fbrl_file_create(in_dir("big.fbd"));
        _exit(st == FBRL_EDISKFULL ? 0 : 1);
    }
    int wst = 0;
    assert_int_equal(waitpid(pid, &wst, 0), pid);
    assert_true(WIFEXITED(wst));
    assert_int_equal(WEXITSTATUS(wst), 0);
    assert_int_equal(stat(in_dir("big.fbd"), &sb), -1); /* nothing left behind */
}

static void bad_input_is_refused(void **state)
{
    (void)state;
    static unsigned char buf[64];
    fbrl_file f, zero;
    memset(&zero, 0, sizeof zero);
    char p[PATH_LEN];
    path_in(p, "bad.fbd");
    unsigned char c = 0;
    double d = 0;
    fbrl_ftype t;
    char longpath[FBRL_FILE_PATH_MAX + 8];
    int temps = count_temporaries();
    uint32_t idx, cnt;

    /* Paths. */
    assert_int_equal(fbrl_file_create(NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_file_create(""), FBRL_EINVAL);
    assert_int_equal(fbrl_file_create(in_dir("no-such-dir/x.fbd")), FBRL_ENOENT);
    memset(longpath, 'a', sizeof longpath - 1);
    longpath[sizeof longpath - 1] = '\0';
    assert_int_equal(fbrl_file_create(longpath), FBRL_ENAME);
    assert_int_equal(fbrl_file_open(&f, longpath, buf, sizeof buf), FBRL_ENAME);
    assert_int_equal(fbrl_file_open(&f, in_dir("no-such-dir/x.fbd"), buf, sizeof buf), FBRL_ENOENT);
    assert_int_equal(fbrl_file_open(&f, in_dir("missing.fbd"), buf, sizeof buf), FBRL_ENOENT);
    assert_int_equal(count_temporaries(), temps); /* failed creates leave nothing behind */

    /* Arguments of open. */
    assert_int_equal(fbrl_file_create(p), FBRL_OK);
    assert_int_equal(fbrl_file_open(NULL, p, buf, sizeof buf), FBRL_EINVAL);
    assert_int_equal(fbrl_file_open(&f, NULL, buf, sizeof buf), FBRL_EINVAL);
    assert_int_equal(fbrl_file_open(&f, p, NULL, sizeof buf), FBRL_EINVAL);
    assert_int_equal(fbrl_file_open(&f, p, buf, 0), FBRL_EINVAL);

    /* Things that are not data files. */
    static const unsigned char text[] = "X Y Z O A T\n1 2 3 4 5 6\n and more text than a header";
    put_raw(in_dir("text.txt"), text, sizeof text - 1);
    assert_int_equal(fbrl_file_open(&f, in_dir("text.txt"), buf, sizeof buf), FBRL_EFORMAT);
    put_raw(in_dir("hi.txt"), (const unsigned char *)"hi", 2);
    assert_int_equal(fbrl_file_open(&f, in_dir("hi.txt"), buf, sizeof buf), FBRL_EFORMAT);
    put_raw(in_dir("empty"), text, 0);
    assert_int_equal(fbrl_file_open(&f, in_dir("empty"), buf, sizeof buf), FBRL_ETRUNCATED);
    assert_int_equal(fbrl_file_open(&f, dir, buf, sizeof buf), FBRL_EFORMAT);
    assert_int_equal(fbrl_file_open(&f, "/dev/zero", buf, sizeof buf), FBRL_EFORMAT);
    assert_int_equal(mkfifo(in_dir("fifo"), 0600), 0);
    assert_int_equal(fbrl_file_open(&f, in_dir("fifo"), buf, sizeof buf), FBRL_EFORMAT);
    assert_int_equal(fbrl_file_open(&f, in_dir("trailing/"), buf, sizeof buf), FBRL_ENAME);

    /* Closed, never-opened and NULL handles. */
    assert_int_equal(fbrl_file_open(&f, p, buf, sizeof buf), FBRL_OK);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
    fbrl_file *hs[2] = {&f, &zero};
    for (int i = 0; i < 2; i++) {
        fbrl_file *h = hs[i];
        assert_int_equal(fbrl_file_reset(h), FBRL_ESTATE);
        assert_int_equal(fbrl_file_append(h), FBRL_ESTATE);
        assert_int_equal(fbrl_file_truncate(h), FBRL_ESTATE);
        assert_int_equal(fbrl_file_write_chr(h, 1), FBRL_ESTATE);
        assert_int_equal(fbrl_file_read_chr(h, &c), FBRL_ESTATE);
        assert_int_equal(fbrl_file_peek(h, &t), FBRL_ESTATE);
        assert_int_equal(fbrl_file_tell(h, NULL, NULL), FBRL_ESTATE);
        assert_int_equal(fbrl_file_commit(h), FBRL_ESTATE);
        assert_int_equal(fbrl_file_close(h), FBRL_ESTATE);
        assert_int_equal(fbrl_file_discard(h), FBRL_ESTATE);
    }
    assert_int_equal(fbrl_file_reset(NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_file_append(NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_file_truncate(NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_file_write_chr(NULL, 1), FBRL_EINVAL);
    assert_int_equal(fbrl_file_read_chr(NULL, &c), FBRL_EINVAL);
    assert_int_equal(fbrl_file_peek(NULL, &t), FBRL_EINVAL);
    assert_int_equal(fbrl_file_tell(NULL, NULL, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_file_commit(NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_file_close(NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_file_discard(NULL), FBRL_EINVAL);

    /* Bad types, NULL values, zero sizes, non-finite numbers, full buffer. */
    assert_int_equal(fbrl_file_open(&f, p, buf, 40), FBRL_OK);
    const fbrl_ftype bad[] = {{(fbrl_ftype_code)0, 0, 1}, {(fbrl_ftype_code)99, 0, 4}, {FBRL_FT_REAL, 0, 4},
                              {FBRL_FT_CHR, 1, 1},        {FBRL_FT_LOCATION, 0, 47},   {FBRL_FT_USER, 5, 0}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(fbrl_file_write(&f, bad[i], buf), FBRL_EINVAL);
        assert_int_equal(fbrl_file_read(&f, bad[i], buf), FBRL_EINVAL);
    }
    assert_int_equal(fbrl_file_write(&f, fbrl_ftype_of_size(0), buf), FBRL_EINVAL);
    assert_int_equal(fbrl_file_write(&f, fbrl_ftype_real, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_file_read(&f, fbrl_ftype_real, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_file_write_user(&f, 1, NULL, 4), FBRL_EINVAL);
    assert_int_equal(fbrl_file_write_user(&f, 1, buf, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_file_read_user(&f, 1, buf, 0), FBRL_EINVAL);
    assert_int_equal(fbrl_file_read_loc(&f, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_file_peek(&f, NULL), FBRL_EINVAL);
    assert_int_equal(fbrl_file_write_real(&f, NAN), FBRL_ENONFINITE);
    assert_int_equal(fbrl_file_write_real(&f, -INFINITY), FBRL_ENONFINITE);
    fbrl_loc l = locs[0];
    l.t = INFINITY;
    assert_int_equal(fbrl_file_write_loc(&f, &l), FBRL_ENONFINITE);
    l.t = 0;
    l.y = NAN;
    assert_int_equal(fbrl_file_write_loc(&f, &l), FBRL_ENONFINITE);
    /* 40 bytes of buffer: no LOCATION (56), three LONGs (36), not a fourth. */
    assert_int_equal(fbrl_file_write_loc(&f, &locs[0]), FBRL_ENOSPC);
    for (int32_t i = 0; i < 3; i++)
        assert_int_equal(fbrl_file_write_long(&f, i), FBRL_OK);
    assert_int_equal(fbrl_file_write_long(&f, 3), FBRL_ENOSPC);
    /* Replacing record 1 (12 bytes) by 17 does not fit (36 - 12 + 17 > 40), 13 do. */
    assert_int_equal(fbrl_file_reset(&f), FBRL_OK);
    assert_int_equal(fbrl_file_read_chr(&f, &c), FBRL_ETYPE);
    int32_t v;
    assert_int_equal(fbrl_file_read_long(&f, &v), FBRL_OK);
    assert_int_equal(fbrl_file_write_user(&f, 0, buf, 9), FBRL_ENOSPC);
    assert_int_equal(fbrl_file_tell(&f, &idx, &cnt), FBRL_OK);
    assert_int_equal(idx, 1);                                       /* nothing moved */
    assert_int_equal(fbrl_file_write_user(&f, 0, buf, 5), FBRL_OK); /* 13 bytes: fits */
    assert_int_equal(fbrl_file_tell(&f, &idx, &cnt), FBRL_OK);
    assert_int_equal(idx, 2);
    assert_int_equal(cnt, 3);
    assert_int_equal(fbrl_file_read_long(&f, &v), FBRL_OK);
    assert_int_equal(v, 2);
    assert_int_equal(fbrl_file_read_real(&f, &d), FBRL_EEOF);
    assert_int_equal(fbrl_file_close(&f), FBRL_OK);
    /* The file now needs 37 bytes of buffer. */
    assert_int_equal(fbrl_file_open(&f, p, buf, 36), FBRL_ENOSPC);
    assert_int_equal(fbrl_file_open(&f, p, buf, 37), FBRL_OK);
    assert_int_equal(fbrl_file_discard(&f), FBRL_OK);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(round_trip_every_type),
        cmocka_unit_test(format_is_little_endian_byte_by_byte),
        cmocka_unit_test(reset_append_replace_truncate),
        cmocka_unit_test(wrong_type_is_refused_and_nothing_lost),
        cmocka_unit_test(type_of_size_follows_the_thesis),
        cmocka_unit_test(changes_are_invisible_until_commit),
        cmocka_unit_test(commit_keeps_permissions),
        cmocka_unit_test(every_truncation_is_refused),
        cmocka_unit_test(every_bit_flip_is_refused),
        cmocka_unit_test(well_sealed_nonsense_is_refused),
        cmocka_unit_test(random_damage_is_refused),
        cmocka_unit_test(killed_writers_leave_old_or_new_file),
        cmocka_unit_test(leftover_temporaries_do_not_block_writes),
        cmocka_unit_test(failed_commit_keeps_handle_open),
        cmocka_unit_test(bad_input_is_refused),
        cmocka_unit_test(os_errors_are_named_and_links_followed),
    };
    return cmocka_run_group_tests(tests, make_dir, drop_dir);
}
