/* SPDX-License-Identifier: MIT */
/* test_audit.c - the audit chain: records as written, every kind of edit found at its
 * record, signatures checked against keys, the head file, a refused writer, recovery. The
 * truths are outside the code under test: SHA-256 and Ed25519 from libsodium directly,
 * and the chain's file read back with stdio. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include <sodium.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "support/tmpdir.h"

#include "fbrl/audit.h"

typedef struct sink {
    char buf[1 << 16];
    size_t len;
    int fail;
    int64_t now;
} sink;

static int sink_write(void *ctx, const char *s, size_t n)
{
    sink *k = ctx;
    if (k->fail)
        return -1;
    assert_true(n > 0 && s[n - 1] == '\n');
    assert_null(memchr(s, '\n', n - 1));
    assert_true(k->len + n < sizeof k->buf);
    memcpy(k->buf + k->len, s, n);
    k->len += n;
    k->buf[k->len] = '\0';
    return 0;
}

static int64_t sink_utc(void *ctx) { return ((sink *)ctx)->now; }

static size_t line_at(const char *buf, unsigned n, const char **start)
{
    const char *p = buf;
    while (n-- > 0)
        p = strchr(p, '\n') + 1;
    *start = p;
    return (size_t)(strchr(p, '\n') - p);
}

static void hex(const unsigned char *b, size_t n, char *out)
{
    for (size_t i = 0; i < n; i++)
        sprintf(out + 2 * i, "%02x", b[i]);
}

static sink k;

static void a_record_is_its_body_with_seq_time_user_prev_and_hash(void **state)
{
    (void)state;
    fbrl_audit a;
    const char *l;
    size_t n;
    unsigned char h[32];
    char want[65], line[512];
    memset(&k, 0, sizeof k);
    k.now = 1795580996123LL; /* 2026-11-25T04:29:56.123Z */
    assert_int_equal(fbrl_audit_init(&a, sink_write, &k, sink_utc, &k, 0, NULL), FBRL_OK);
    assert_int_equal(fbrl_audit_append(&a, "{}", 2), FBRL_ESTATE); /* nobody to attribute it to */
    assert_int_equal(fbrl_audit_set_user(&a, "ann smith"), FBRL_ENAME);
    assert_int_equal(fbrl_audit_set_user(&a, "ann"), FBRL_OK);
    assert_int_equal(fbrl_audit_append(&a, "{\"t\":0,\"type\":\"header\"}\n", 24), FBRL_OK);
    n = line_at(k.buf, 0, &l);
    memcpy(line, l, n);
    line[n] = '\0';
    /* the hash is SHA-256 of the bytes before ,"hash" */
    const char *cut = strstr(line, ",\"hash\":\"");
    assert_non_null(cut);
    crypto_hash_sha256(h, (const unsigned char *)line, (size_t)(cut - line));
    hex(h, 32, want);
    char expect[512];
    snprintf(expect, sizeof expect,
             "{\"seq\":1,\"utc\":\"2026-11-25T04:29:56.123Z\",\"user\":\"ann\",\"prev\":\"%064d\",\"t\":0,"
             "\"type\":\"header\",\"hash\":\"%s\"}",
             0, want);
    assert_string_equal(line, expect);
    /* the next record's prev is that hash */
    assert_int_equal(fbrl_audit_append(&a, "{\"type\":\"x\"}", 12), FBRL_OK);
    n = line_at(k.buf, 1, &l);
    assert_non_null(strstr(l, want));
    assert_memory_equal(l, "{\"seq\":2,", 9);
    /* not one object: refused, nothing written */
    size_t before = k.len;
    assert_int_equal(fbrl_audit_append(&a, "{\"a\":1} {", 9), FBRL_ESYNTAX);
    assert_int_equal(fbrl_audit_append(&a, "[1]", 3), FBRL_ESYNTAX);
    assert_int_equal(fbrl_audit_append(&a, "{\"a\":\"x}", 8), FBRL_ESYNTAX);
    assert_int_equal(k.len, before);
    /* a failed sink stops the writer for good */
    k.fail = 1;
    assert_int_equal(fbrl_audit_append(&a, "{}", 2), FBRL_EIO);
    k.fail = 0;
    assert_int_equal(fbrl_audit_append(&a, "{}", 2), FBRL_EIO);
}

static void utc_text_is_the_civil_date(void **state)
{
    (void)state;
    char b[32];
    fbrl_audit_utc_text(0, b);
    assert_string_equal(b, "1970-01-01T00:00:00.000Z");
    fbrl_audit_utc_text(951782400000LL + 86399999LL, b); /* the leap day of 2000 */
    assert_string_equal(b, "2000-02-29T23:59:59.999Z");
    fbrl_audit_utc_text(4102444800000LL, b);
    assert_string_equal(b, "2100-01-01T00:00:00.000Z");
}

static void fields_are_read_and_escapes_undone(void **state)
{
    (void)state;
    fbrl_audit a;
    char s[64];
    long long x;
    const char *l;
    size_t n;
    memset(&k, 0, sizeof k);
    fbrl_audit_init(&a, sink_write, &k, NULL, NULL, 0, NULL);
    fbrl_audit_set_user(&a, "ann");
    fbrl_audit_begin(&a, "teach");
    fbrl_audit_str(&a, "place", "A\"1\\\n");
    fbrl_audit_num(&a, "n", -42);
    fbrl_audit_raw(&a, "xyz", "[1,{\"a\":[2]},3]");
    assert_int_equal(fbrl_audit_end(&a), FBRL_OK);
    n = line_at(k.buf, 0, &l);
    assert_int_equal(fbrl_audit_field_str(l, n, "place", s, sizeof s), FBRL_OK);
    assert_string_equal(s, "A\"1\\\n");
    assert_int_equal(fbrl_audit_field_num(l, n, "n", &x), FBRL_OK);
    assert_int_equal(x, -42);
    assert_int_equal(fbrl_audit_field_str(l, n, "type", s, sizeof s), FBRL_OK);
    assert_string_equal(s, "teach");
    assert_int_equal(fbrl_audit_field_str(l, n, "nope", s, sizeof s), FBRL_ENOENT);
    assert_int_equal(fbrl_audit_field_str(l, n, "n", s, sizeof s), FBRL_ETYPE);
    assert_int_equal(fbrl_audit_field_str(l, n, "place", s, 3), FBRL_ENOSPC);
    /* a key inside the nested value is not a top-level field */
    assert_int_equal(fbrl_audit_field_str(l, n, "a", s, sizeof s), FBRL_ENOENT);
    /* an overflowing body is refused whole */
    fbrl_audit_begin(&a, "big");
    for (int i = 0; i < 400; i++)
        fbrl_audit_str(&a, "k", "0123456789");
    size_t before = k.len;
    assert_int_equal(fbrl_audit_end(&a), FBRL_ENOSPC);
    assert_int_equal(k.len, before);
}

/* A chain of n records with a user record, a signature and seals, in k. */
static unsigned char pk_rev[32], sk_rev[64], pk_adm[32], sk_adm[64];

static void make_chain(fbrl_audit *a, int n)
{
    char pkhex[65];
    unsigned char h[32];
    memset(&k, 0, sizeof k);
    k.now = 1795580996000LL;
    fbrl_audit_init(a, sink_write, &k, sink_utc, &k, 0, NULL);
    fbrl_audit_set_user(a, "admin");
    hex(pk_rev, 32, pkhex);
    fbrl_audit_begin(a, "user");
    fbrl_audit_str(a, "action", "add");
    fbrl_audit_str(a, "name", "rev");
    fbrl_audit_str(a, "role", "reviewer");
    fbrl_audit_str(a, "key", pkhex);
    assert_int_equal(fbrl_audit_end(a), FBRL_OK);
    hex(pk_adm, 32, pkhex);
    fbrl_audit_begin(a, "user");
    fbrl_audit_str(a, "action", "add");
    fbrl_audit_str(a, "name", "admin");
    fbrl_audit_str(a, "role", "administrator");
    fbrl_audit_str(a, "key", pkhex);
    assert_int_equal(fbrl_audit_end(a), FBRL_OK);
    fbrl_audit_set_user(a, "ann");
    for (int i = 0; i < n; i++) {
        char body[64];
        k.now += 7;
        snprintf(body, sizeof body, "{\"t\":%d,\"type\":\"command\",\"line\":\"W%d\"}", i, i % 6);
        assert_int_equal(fbrl_audit_append(a, body, strlen(body)), FBRL_OK);
    }
    assert_int_equal(fbrl_audit_seal(a), FBRL_OK);
    uint64_t sealed = fbrl_audit_head(a, h);
    fbrl_audit_set_user(a, "rev");
    assert_int_equal(fbrl_audit_sign(a, sealed, h, FBRL_AUDIT_MEANING_REVIEW, sk_rev, pk_rev), FBRL_OK);
    /* a wrong pair is refused */
    assert_int_equal(fbrl_audit_sign(a, sealed, h, FBRL_AUDIT_MEANING_REVIEW, sk_rev, pk_adm), FBRL_EINVAL);
    fbrl_audit_set_user(a, "ann");
    assert_int_equal(fbrl_audit_append(a, "{\"type\":\"login\"}", 16), FBRL_OK);
    assert_int_equal(fbrl_audit_seal(a), FBRL_OK);
}

static fbrl_audit_key keys[8];
static unsigned char hashes[4096][32];

static fbrl_status verify(const char *buf, size_t len, fbrl_audit_verifier *v, uint64_t head_seq,
                          const unsigned char *head)
{
    fbrl_audit_verify_init(v, keys, 0, 8, hashes, 4096);
    /* in odd pieces: a line may arrive in parts */
    for (size_t i = 0; i < len; i += 37)
        fbrl_audit_verify_bytes(v, buf + i, len - i < 37 ? len - i : 37);
    return fbrl_audit_verify_end(v, head_seq, head);
}

static void an_intact_chain_verifies_sealed_and_signed(void **state)
{
    (void)state;
    fbrl_audit a;
    static fbrl_audit_verifier v;
    unsigned char h[32];
    make_chain(&a, 20);
    uint64_t n = fbrl_audit_head(&a, h);
    assert_int_equal(n, 2 + 20 + 1 + 1 + 1 + 1);
    assert_int_equal(verify(k.buf, k.len, &v, n, h), FBRL_OK);
    assert_int_equal(v.records, n);
    assert_int_equal(v.signatures, 1);
    assert_true(v.sealed);
    assert_int_equal(v.last_seal, n);
    /* the seal covers what came since the last one */
    const char *l;
    size_t ln = line_at(k.buf, 22, &l);
    long long x;
    assert_int_equal(fbrl_audit_field_num(l, ln, "first", &x), FBRL_OK);
    assert_int_equal(x, 1);
    assert_int_equal(fbrl_audit_field_num(l, ln, "records", &x), FBRL_OK);
    assert_int_equal(x, 22);
    ln = line_at(k.buf, 25, &l);
    assert_int_equal(fbrl_audit_field_num(l, ln, "first", &x), FBRL_OK);
    assert_int_equal(x, 24);
}

static char work[1 << 16];

/* Copy k.buf with line `drop` removed, or line a and b swapped, or line `dup` repeated. */
static size_t edit(int kind, unsigned x, unsigned y)
{
    const char *lines[64];
    size_t lens[64], n = 0, o = 0;
    const char *p = k.buf;
    while (*p) {
        const char *e = strchr(p, '\n');
        lines[n] = p;
        lens[n++] = (size_t)(e - p) + 1;
        p = e + 1;
    }
    for (size_t i = 0; i < n; i++) {
        size_t j = i;
        if (kind == 'd' && i == x)
            continue;
        if (kind == 's' && i == x)
            j = y;
        if (kind == 's' && i == y)
            j = x;
        memcpy(work + o, lines[j], lens[j]);
        o += lens[j];
        if (kind == 'r' && i == x) {
            memcpy(work + o, lines[j], lens[j]);
            o += lens[j];
        }
    }
    work[o] = '\0';
    return o;
}

static void each_edit_is_found_at_its_record(void **state)
{
    (void)state;
    fbrl_audit a;
    static fbrl_audit_verifier v;
    unsigned char h[32];
    make_chain(&a, 20);
    uint64_t n = fbrl_audit_head(&a, h);
    size_t len;
    char *p;

    /* one character of record 10's content */
    memcpy(work, k.buf, k.len + 1);
    p = strstr(work, "\"line\":\"W1\"");
    p = strstr(p + 1, "\"line\":\"W1\""); /* the second: record 2 + 7 + 1 = 10 */
    p[9] = '2';
    assert_int_equal(verify(work, k.len, &v, n, h), FBRL_ECHECKSUM);
    assert_string_equal(v.where, "record 10 (line 10): changed after it was written: its content does not match "
                                 "its hash");
    /* deleted */
    len = edit('d', 4, 0);
    assert_int_equal(verify(work, len, &v, n, h), FBRL_ECHECKSUM);
    assert_non_null(strstr(v.where, "record 5 (line 5): out of order: record 6 stands here"));
    /* swapped */
    len = edit('s', 6, 7);
    assert_int_equal(verify(work, len, &v, n, h), FBRL_ECHECKSUM);
    assert_non_null(strstr(v.where, "record 7 (line 7): out of order: record 8"));
    /* repeated */
    len = edit('r', 11, 0);
    assert_int_equal(verify(work, len, &v, n, h), FBRL_ECHECKSUM);
    assert_string_equal(v.where, "record 13 (line 13): record 12 repeated");
    /* the tail cut: the head still says n */
    len = edit('d', (unsigned)n - 1, 0);
    assert_int_equal(verify(work, len, &v, n, h), FBRL_ECHECKSUM);
    assert_non_null(strstr(v.where, "record 26 (line 26): missing: the head file says 26 records"));
    /* the tail cut in the middle of a line */
    assert_int_equal(verify(k.buf, k.len - 5, &v, n, h), FBRL_ECHECKSUM);
    assert_non_null(strstr(v.where, "record 26 (line 26): incomplete"));
    /* the last record replaced by one made anew (same seq, a valid chain) */
    {
        fbrl_audit b = a;
        static sink k2;
        memcpy(&k2, &k, sizeof k);
        const char *l;
        line_at(k.buf, (unsigned)n - 1, &l);
        k2.len = (size_t)(l - k.buf);
        b.write_ctx = &k2;
        b.seq = n - 1;
        assert_int_equal(verify(k.buf, k2.len, &v, n - 1, NULL), FBRL_OK);
        memcpy(b.head, v.head, 32);
        assert_int_equal(fbrl_audit_append(&b, "{\"type\":\"other\"}", 16), FBRL_OK);
        assert_int_equal(verify(k2.buf, k2.len, &v, n, h), FBRL_ECHECKSUM);
        assert_non_null(strstr(v.where, "record 26 (line 26): its hash differs from the head file's"));
    }
}

/* Rewrite record i's field value old->new, then re-hash it and every record after (what a
 * forger with the tools but no private key could do) into work; returns the length. */
static size_t forge(unsigned i, const char *old, const char *new)
{
    const char *lines[64];
    size_t lens[64], n = 0, o = 0;
    const char *p = k.buf;
    unsigned char prev[32];
    while (*p) {
        const char *e = strchr(p, '\n');
        lines[n] = p;
        lens[n++] = (size_t)(e - p);
        p = e + 1;
    }
    for (size_t r = 0; r < n; r++) {
        char line[4200], *q;
        memcpy(line, lines[r], lens[r]);
        line[lens[r]] = '\0';
        if (r == i) {
            q = strstr(line, old);
            assert_non_null(q);
            memmove(q + strlen(new), q + strlen(old), strlen(q + strlen(old)) + 1);
            memcpy(q, new, strlen(new));
        }
        if (r >= i) {
            char hx[65];
            if (r > i) { /* prev */
                q = strstr(line, "\"prev\":\"") + 8;
                hex(prev, 32, hx);
                memcpy(q, hx, 64);
            }
            q = strstr(line, ",\"hash\":\"");
            crypto_hash_sha256(prev, (const unsigned char *)line, (size_t)(q - line));
            hex(prev, 32, hx);
            memcpy(q + 9, hx, 64);
        } else {
            char *q2 = strstr(line, ",\"hash\":\"") + 9;
            assert_int_equal(sodium_hex2bin(prev, 32, q2, 64, NULL, NULL, NULL), 0);
        }
        memcpy(work + o, line, strlen(line));
        o += strlen(line);
        work[o++] = '\n';
    }
    work[o] = '\0';
    return o;
}

static void a_forged_rewrite_fails_the_signature_and_the_head(void **state)
{
    (void)state;
    fbrl_audit a;
    static fbrl_audit_verifier v;
    unsigned char h[32], fh[32];
    make_chain(&a, 20);
    uint64_t n = fbrl_audit_head(&a, h);
    /* the signature (record 24) made to point at record 23 instead of the seal (23 is the
     * seal: point at 22), every hash after re-made: the chain is whole again, but the
     * signed hash is not record 22's */
    size_t len = forge(23, "\"signs\":23", "\"signs\":22");
    memcpy(fh, work + len - 67, 0);
    sodium_hex2bin(fh, 32, work + len - 67, 64, NULL, NULL, NULL); /* the forged last hash */
    assert_int_equal(verify(work, len, &v, n, fh), FBRL_ECHECKSUM);
    assert_string_equal(v.where, "record 24 (line 24): signature by rev is not for record 22: its hash differs "
                                 "(moved)");
    /* and the signed hash changed too: the signature no longer verifies */
    const char *l;
    line_at(k.buf, 21, &l); /* record 22's hash */
    char h22[65];
    memcpy(h22, strstr(l, ",\"hash\":\"") + 9, 64);
    h22[64] = '\0';
    char old[160], new[160];
    line_at(k.buf, 22, &l);
    snprintf(old, sizeof old, "\"signs\":23,\"signed_hash\":\"%.64s\"", strstr(l, ",\"hash\":\"") + 9);
    snprintf(new, sizeof new, "\"signs\":22,\"signed_hash\":\"%s\"", h22);
    len = forge(23, old, new);
    sodium_hex2bin(fh, 32, work + len - 67, 64, NULL, NULL, NULL);
    assert_int_equal(verify(work, len, &v, n, fh), FBRL_ECHECKSUM);
    assert_string_equal(v.where, "record 24 (line 24): signature by rev does not verify with rev's public key");
    /* a command edited early and everything re-hashed: only the head file tells */
    len = forge(5, "\"line\":\"W3\"", "\"line\":\"W4\"");
    assert_int_equal(verify(work, len, &v, n, h), FBRL_ECHECKSUM);
    assert_non_null(strstr(v.where, "(line 24): signature by rev is not for record 23"));
}

static void signatures_need_a_trusted_key(void **state)
{
    (void)state;
    fbrl_audit a;
    static fbrl_audit_verifier v;
    unsigned char h[32];
    make_chain(&a, 3);
    uint64_t n = fbrl_audit_head(&a, h);
    /* offline, with only the public keys given (not the chain's) */
    fbrl_audit_key mine[2];
    memset(mine, 0, sizeof mine);
    strcpy(mine[0].name, "rev");
    strcpy(mine[0].role, "reviewer");
    memcpy(mine[0].pk, pk_rev, 32);
    fbrl_audit_verify_init(&v, mine, 1, 2, hashes, 4096);
    fbrl_audit_verify_bytes(&v, k.buf, k.len);
    assert_int_equal(fbrl_audit_verify_end(&v, n, h), FBRL_OK);
    assert_int_equal(v.signatures, 1);
    /* a different key for rev: refused */
    memcpy(mine[0].pk, pk_adm, 32);
    fbrl_audit_verify_init(&v, mine, 1, 2, hashes, 4096);
    fbrl_audit_verify_bytes(&v, k.buf, k.len);
    assert_int_equal(fbrl_audit_verify_end(&v, n, h), FBRL_ECHECKSUM);
    assert_string_equal(v.where, "record 7 (line 7): signature by rev: no trusted public key of rev matches");
}

static char dir[256];

static void path_in(char *out, const char *name) { snprintf(out, 512, "%s/%s", dir, name); }

static void file_chain_refuses_to_append_when_broken_until_recovered(void **state)
{
    (void)state;
    static fbrl_audit_file f;
    static fbrl_audit_verifier v;
    char path[512], hpath[520];
    FILE *fp;
    path_in(path, "trail.jsonl");
    snprintf(hpath, sizeof hpath, "%s.head", path);
    unlink(path);
    unlink(hpath);
    fbrl_audit_verify_init(&v, keys, 0, 8, hashes, 4096);
    assert_int_equal(fbrl_audit_file_open(&f, path, &v), FBRL_OK);
    fbrl_audit_set_user(&f.a, "admin");
    {
        char pkhex[65];
        hex(pk_adm, 32, pkhex);
        fbrl_audit_begin(&f.a, "user");
        fbrl_audit_str(&f.a, "name", "admin");
        fbrl_audit_str(&f.a, "role", "administrator");
        fbrl_audit_str(&f.a, "key", pkhex);
        assert_int_equal(fbrl_audit_end(&f.a), FBRL_OK);
    }
    for (int i = 0; i < 5; i++)
        assert_int_equal(fbrl_audit_append(&f.a, "{\"type\":\"x\"}", 12), FBRL_OK);
    assert_int_equal(fbrl_audit_seal(&f.a), FBRL_OK);
    assert_int_equal(fbrl_audit_file_close(&f), FBRL_OK);
    /* the head file: the count and the last hash, readable by the owner's group only */
    struct stat sb;
    assert_int_equal(stat(hpath, &sb), 0);
    assert_int_equal(sb.st_mode & 0777, 0640);
    char head[200];
    fp = fopen(hpath, "r");
    assert_non_null(fgets(head, sizeof head, fp));
    fclose(fp);
    assert_memory_equal(head, "fbrl-audit-head 1 00000000000000000007 ", 39);

    /* reopened: continues at 8 */
    fbrl_audit_verify_init(&v, keys, 0, 8, hashes, 4096);
    assert_int_equal(fbrl_audit_file_open(&f, path, &v), FBRL_OK);
    fbrl_audit_set_user(&f.a, "ann");
    assert_int_equal(fbrl_audit_append(&f.a, "{\"type\":\"y\"}", 12), FBRL_OK);
    fbrl_audit_file_close(&f);
    fp = fopen(path, "r");
    char line[600];
    int lines = 0;
    while (fgets(line, sizeof line, fp))
        lines++;
    fclose(fp);
    assert_int_equal(lines, 8);
    assert_memory_equal(line, "{\"seq\":8,", 9);

    /* edit record 3 in place: the next writer refuses, naming it */
    fp = fopen(path, "r+");
    fseek(fp, 0, SEEK_SET);
    char all[8192];
    size_t n = fread(all, 1, sizeof all, fp);
    char *p = strstr(all, "{\"seq\":3,");
    p = strstr(p, "\"x\"");
    p[1] = 'z';
    fseek(fp, 0, SEEK_SET);
    fwrite(all, 1, n, fp);
    fclose(fp);
    fbrl_audit_verify_init(&v, keys, 0, 8, hashes, 4096);
    assert_int_equal(fbrl_audit_file_open(&f, path, &v), FBRL_ECHECKSUM);
    assert_string_equal(f.where, "record 3 (line 3): changed after it was written: its content does not match its "
                                 "hash");
    fp = fopen(path, "r");
    assert_int_equal(fread(line, 1, sizeof line, fp) > 0, 1);
    fclose(fp);

    /* a recovery signed by someone who is not an administrator does not count */
    fbrl_audit_verify_init(&v, keys, 0, 8, hashes, 4096);
    assert_int_equal(fbrl_audit_file_recover(&f, path, &v, "rev", "test", sk_rev, pk_rev), FBRL_OK);
    fbrl_audit_file_close(&f);
    fbrl_audit_verify_init(&v, keys, 0, 8, hashes, 4096);
    assert_int_equal(fbrl_audit_file_verify(path, &v), FBRL_ECHECKSUM);
    assert_string_equal(v.where, "record 10 (line 10): signature by rev: no trusted public key of rev matches");
    /* the administrator's: the chain goes on, the break stays on record */
    fbrl_audit_verify_init(&v, keys, 0, 8, hashes, 4096);
    assert_int_equal(fbrl_audit_file_recover(&f, path, &v, "admin", "edited by hand on 25 Nov, see deviation 12",
                                             sk_adm, pk_adm),
                     FBRL_OK);
    fbrl_audit_file_close(&f);
    fbrl_audit_verify_init(&v, keys, 0, 8, hashes, 4096);
    assert_int_equal(fbrl_audit_file_open(&f, path, &v), FBRL_OK);
    assert_int_equal(v.recoveries, 1);
    assert_non_null(strstr(v.recovered, "record 10 (line 10): signature by rev"));
    fbrl_audit_set_user(&f.a, "ann");
    assert_int_equal(fbrl_audit_append(&f.a, "{\"type\":\"after\"}", 16), FBRL_OK);
    assert_int_equal(fbrl_audit_file_close(&f), FBRL_OK);
    fbrl_audit_verify_init(&v, keys, 0, 8, hashes, 4096);
    assert_int_equal(fbrl_audit_file_verify(path, &v), FBRL_OK);
    /* an intact chain needs no recovery */
    fbrl_audit_verify_init(&v, keys, 0, 8, hashes, 4096);
    assert_int_equal(fbrl_audit_file_recover(&f, path, &v, "admin", "x", sk_adm, pk_adm), FBRL_ESTATE);
    /* a deleted head file is a break */
    unlink(hpath);
    fbrl_audit_verify_init(&v, keys, 0, 8, hashes, 4096);
    assert_int_equal(fbrl_audit_file_verify(path, &v), FBRL_ECHECKSUM);
    assert_non_null(strstr(v.where, ".head is missing"));
}

static int setup(void **state)
{
    (void)state;
    assert_true(sodium_init() >= 0);
    crypto_sign_keypair(pk_rev, sk_rev);
    crypto_sign_keypair(pk_adm, sk_adm);
    return test_tmpdir_make(dir, sizeof dir, "audit");
}

static int teardown(void **state)
{
    (void)state;
    return test_tmpdir_remove(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_record_is_its_body_with_seq_time_user_prev_and_hash),
        cmocka_unit_test(utc_text_is_the_civil_date),
        cmocka_unit_test(fields_are_read_and_escapes_undone),
        cmocka_unit_test(an_intact_chain_verifies_sealed_and_signed),
        cmocka_unit_test(each_edit_is_found_at_its_record),
        cmocka_unit_test(a_forged_rewrite_fails_the_signature_and_the_head),
        cmocka_unit_test(signatures_need_a_trusted_key),
        cmocka_unit_test(file_chain_refuses_to_append_when_broken_until_recovered),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
