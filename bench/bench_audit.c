/* SPDX-License-Identifier: MIT */
/* bench_audit.c - what the audit trail costs: the bytes the chain adds to a run log record,
 * the time to make a record (hash, format) and to write one durably (append + fdatasync +
 * the head file) beside the plain run log's buffered write, fbrl-audit verify's time for
 * 100,000 records (with signatures), and a sign-in (Argon2id, libsodium's interactive cost).
 * Usage: bench_audit [DIR]   (default: $TMPDIR or /tmp) */
#include <sodium.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench_util.h"
#include "fbrl/audit.h"
#include "fbrl/users.h"

#define RECORDS 100000
#define SIGNED_EVERY 1000 /* a run reviewed every 1000 records */
#define DURABLE 300

typedef struct mem {
    char *buf;
    size_t len, cap;
} mem;

static int mem_write(void *ctx, const char *s, size_t n)
{
    mem *m = ctx;
    if (m->len + n > m->cap)
        return -1;
    memcpy(m->buf + m->len, s, n);
    m->len += n;
    return 0;
}

static int64_t fixed_utc(void *ctx)
{
    (void)ctx;
    return 1795580996123LL;
}

static void check(fbrl_status st, const char *what)
{
    if (st != FBRL_OK) {
        fprintf(stderr, "bench_audit: %s: %s\n", what, fbrl_status_str(st));
        exit(1);
    }
}

/* A typical run log record: a command the controller executed. */
static const char *body(unsigned i, char *out, size_t cap)
{
    snprintf(out, cap, "{\"t\":%u,\"type\":\"command\",\"line\":\"MOVE A%u\",\"status\":\"ran\"}", i * 37, i % 24);
    return out;
}

int main(int argc, char **argv)
{
    static fbrl_audit a;
    static fbrl_audit_verifier v;
    static fbrl_audit_file f;
    static fbrl_users u;
    const char *base = argc > 1 ? argv[1] : getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp";
    char dir[256], path[300], plain[300], line[256];
    unsigned char pk[32], sk[64], h[32];
    mem m = {NULL, 0, (size_t)RECORDS * 400};
    size_t body_bytes = 0;
    double t0, t;
    if (sodium_init() < 0)
        return 1;
    snprintf(dir, sizeof dir, "%s/bench-audit-XXXXXX", base);
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    snprintf(path, sizeof path, "%s/trail.jsonl", dir);
    snprintf(plain, sizeof plain, "%s/plain.jsonl", dir);
    m.buf = malloc(m.cap);
    crypto_sign_keypair(pk, sk);

    /* records in memory: the chain's own work, hash and format */
    check(fbrl_audit_init(&a, mem_write, &m, fixed_utc, NULL, 0, NULL), "init");
    fbrl_audit_set_user(&a, "rev");
    {
        char hex[65], rec[200];
        for (int i = 0; i < 32; i++)
            sprintf(hex + 2 * i, "%02x", pk[i]);
        snprintf(rec, sizeof rec, "{\"type\":\"user\",\"action\":\"add\",\"name\":\"rev\",\"role\":\"reviewer\",\"key\":\"%s\"}",
                 hex);
        check(fbrl_audit_append(&a, rec, strlen(rec)), "user");
    }
    fbrl_audit_set_user(&a, "ann");
    t0 = bench_now();
    for (unsigned i = 1; a.seq < RECORDS; i++) {
        body(i, line, sizeof line);
        body_bytes += strlen(line) + 1;
        check(fbrl_audit_append(&a, line, strlen(line)), "append");
        if (i % SIGNED_EVERY == 0 && a.seq < RECORDS - 2) {
            check(fbrl_audit_seal(&a), "seal");
            uint64_t n = fbrl_audit_head(&a, h);
            fbrl_audit_set_user(&a, "rev");
            check(fbrl_audit_sign(&a, n, h, FBRL_AUDIT_MEANING_REVIEW, sk, pk), "sign");
            fbrl_audit_set_user(&a, "ann");
        }
    }
    t = bench_now() - t0;
    printf("chain records made in memory: %u in %.3f s, %.2f us each (SHA-256, format; seals and Ed25519 "
           "signatures every %d)\n",
           RECORDS, t, t * 1e6 / RECORDS, SIGNED_EVERY);
    {
        char one[FBRL_AUDIT_LINE_MAX + 2];
        mem m1 = {one, 0, sizeof one};
        fbrl_audit b;
        fbrl_audit_init(&b, mem_write, &m1, fixed_utc, NULL, 41999, h);
        fbrl_audit_set_user(&b, "ann");
        body(42000, line, sizeof line);
        fbrl_audit_append(&b, line, strlen(line));
        printf("| audit chain: bytes added to a run log record (seq 42000, user ann) | %zu bytes on a %zu-byte record "
               "| seq, utc, user, prev, hash |\n",
               m1.len - strlen(line) - 1, strlen(line) + 1);
    }
    /* the file and its head, for the verifier */
    {
        FILE *fp = fopen(path, "wb");
        char hp[320], hex[65];
        uint64_t n = fbrl_audit_head(&a, h);
        fwrite(m.buf, 1, m.len, fp);
        fclose(fp);
        snprintf(hp, sizeof hp, "%s.head", path);
        for (int i = 0; i < 32; i++)
            sprintf(hex + 2 * i, "%02x", h[i]);
        fp = fopen(hp, "w");
        fprintf(fp, "fbrl-audit-head 1 %llu %s\n", (unsigned long long)n, hex);
        fclose(fp);
        printf("chain file: %llu records, %.1f MB (the same records without the chain: %.1f MB)\n",
               (unsigned long long)n, m.len / 1e6, body_bytes / 1e6);
    }
    {
        static fbrl_audit_key keys[8];
        unsigned char (*hashes)[32] = calloc(RECORDS + 1, 32);
        fbrl_audit_verify_init(&v, keys, 0, 8, hashes, RECORDS + 1);
        t0 = bench_now();
        check(fbrl_audit_file_verify(path, &v), "verify");
        t = bench_now() - t0;
        printf("| fbrl-audit verify: 100,000 records (%lu signatures) | %.3f s | %.1f us a record |\n", v.signatures,
               t, t * 1e6 / (double)v.records);
        free(hashes);
    }
    /* durable writes: append + fdatasync + head file, against the plain run log's write */
    unlink(path);
    {
        char hp[320];
        snprintf(hp, sizeof hp, "%s.head", path);
        unlink(hp);
    }
    fbrl_audit_verify_init(&v, NULL, 0, 0, NULL, 0);
    check(fbrl_audit_file_open(&f, path, &v), "open");
    fbrl_audit_set_user(&f.a, "ann");
    t0 = bench_now();
    for (unsigned i = 0; i < DURABLE; i++) {
        body(i, line, sizeof line);
        check(fbrl_audit_append(&f.a, line, strlen(line)), "durable append");
    }
    t = bench_now() - t0;
    fbrl_audit_file_close(&f);
    {
        FILE *fp = fopen(plain, "a");
        double t1 = bench_now();
        for (unsigned i = 0; i < DURABLE; i++) {
            body(i, line, sizeof line);
            fprintf(fp, "%s\n", line);
            fflush(fp);
        }
        double tp = bench_now() - t1;
        fclose(fp);
        printf("| audit chain: a record written durably (append, fdatasync, head rewritten in place, fdatasync) | %.3f ms | plain "
               "run log line (fwrite+fflush, no sync): %.4f ms |\n",
               t * 1e3 / DURABLE, tp * 1e3 / DURABLE);
    }
    /* a sign-in: Argon2id at libsodium's interactive cost */
    fbrl_users_init(&u);
    check(fbrl_users_add(&u, "ann", FBRL_ROLE_OPERATOR, "a password"), "add");
    t0 = bench_now();
    for (int i = 0; i < 5; i++)
        check(fbrl_users_login(&u, "ann", "a password", 0), "login");
    t = (bench_now() - t0) / 5;
    printf("| sign-in (Argon2id, %llu passes, %lu MiB) | %.0f ms | unlocking a signing key costs the same |\n",
           u.kdf_ops, u.kdf_mem >> 20, t * 1e3);
    {
        char cmd[300];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
        if (system(cmd) != 0)
            return 1;
    }
    free(m.buf);
    return 0;
}
