/* SPDX-License-Identifier: MIT */
/* bench_fileio.c - figures for typed data files: CRC-32 speed, open+verify time of a file of
 * locations, and the cost of an atomic commit (two fsyncs and a rename) on this disk.
 * Usage: bench_fileio [DIR]   (default: $TMPDIR or /tmp) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "fbrl/fileio.h"
#include "bench_util.h"
#include "fbrl/crc32.h"

#define NLOCS   1000
#define COMMITS 50

static int check(fbrl_status st, const char *what)
{
    if (st != FBRL_OK) {
        fprintf(stderr, "bench_fileio: %s: %s\n", what, fbrl_status_str(st));
        exit(1);
    }
    return 0;
}

int main(int argc, char **argv)
{
    static unsigned char buf[NLOCS * FBRL_FILE_RECORD_SIZE(48)];
    const char *base = argc > 1 ? argv[1] : getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp";
    char dir[200], path[240];
    snprintf(dir, sizeof dir, "%s/bench-fileio-XXXXXX", base);
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    snprintf(path, sizeof path, "%s/locs.fbd", dir);

    /* CRC-32 throughput over the buffer, repeated. */
    memset(buf, 0x5a, sizeof buf);
    double t0 = bench_now();
    uint32_t crc = 0;
    int reps = 200;
    for (int i = 0; i < reps; i++)
        crc = fbrl_crc32(crc, buf, sizeof buf);
    double t = bench_now() - t0;
    printf("crc32:          %.1f MB/s (%08x)\n", reps * (double)sizeof buf / t / 1e6, (unsigned)crc);

    /* A file of NLOCS locations. */
    fbrl_file f;
    check(fbrl_file_create(path), "create");
    check(fbrl_file_open(&f, path, buf, sizeof buf), "open");
    for (int i = 0; i < NLOCS; i++) {
        fbrl_loc l = {i * 0.1, -i * 0.2, 3.0, 45.0, -90.0, i % 360};
        check(fbrl_file_write_loc(&f, &l), "write");
    }
    t0 = bench_now();
    check(fbrl_file_close(&f), "close");
    printf("commit %d locations (%zu bytes): %.3f ms\n", NLOCS, FBRL_FILE_HEADER_SIZE + sizeof buf,
           (bench_now() - t0) * 1e3);

    /* Open verifies everything: header, both CRCs, every record. */
    int opens = 200;
    t0 = bench_now();
    for (int i = 0; i < opens; i++) {
        check(fbrl_file_open(&f, path, buf, sizeof buf), "open");
        check(fbrl_file_discard(&f), "discard");
    }
    t = (bench_now() - t0) / opens;
    printf("open+verify:    %.3f ms per open, %.1f MB/s\n", t * 1e3, sizeof buf / t / 1e6);

    /* Read them all back. */
    check(fbrl_file_open(&f, path, buf, sizeof buf), "open");
    t0 = bench_now();
    fbrl_loc l;
    for (int i = 0; i < NLOCS; i++)
        check(fbrl_file_read_loc(&f, &l), "read");
    printf("read location:  %.1f ns each\n", (bench_now() - t0) / NLOCS * 1e9);

    /* Small commits: the price of durability (fsync file, rename, fsync directory). */
    t0 = bench_now();
    for (int i = 0; i < COMMITS; i++) {
        check(fbrl_file_reset(&f), "reset");
        check(fbrl_file_write_long(&f, i), "write");
        check(fbrl_file_commit(&f), "commit");
    }
    printf("commit (small change, %zu-byte file): %.3f ms each\n", FBRL_FILE_HEADER_SIZE + sizeof buf - 44,
           (bench_now() - t0) / COMMITS * 1e3);
    check(fbrl_file_close(&f), "close");

    unlink(path);
    rmdir(dir);
    return 0;
}
