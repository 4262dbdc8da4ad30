/* SPDX-License-Identifier: MIT */
/* audit_file.c - a chain in a file with its head file beside it: verified before anything
 * is appended, every record made durable before the head moves on, an administrator's
 * recovery of a broken chain. The file system is the store's (audit_store.h). */
#include "fbrl/audit.h"
#include "audit_int.h"
#include "audit_store.h"

#include <sodium.h>
#include <stdio.h>
#include <string.h>

#define HEAD_MAGIC "fbrl-audit-head 1 "
#define HEAD_SUFFIX ".head"
#define READ_CHUNK 4096

static int head_path(const char *path, char *out, size_t cap)
{
    int k = snprintf(out, cap, "%s%s", path, HEAD_SUFFIX);
    return k < 0 || (size_t)k >= cap ? -1 : 0;
}

/* The head file: "fbrl-audit-head 1 SEQ HASH\n". FBRL_ENOENT when there is none,
 * FBRL_EFORMAT when it is not one. */
static fbrl_status read_head(const char *path, uint64_t *seq, unsigned char *hash)
{
    char hp[FBRL_AUDIT_PATH_MAX + 8], buf[160];
    size_t got = 0, k = sizeof HEAD_MAGIC - 1;
    unsigned long long n = 0;
    void *h;
    fbrl_status st;
    if (head_path(path, hp, sizeof hp) != 0)
        return FBRL_ENAME;
    st = fbrl__astore_read_open(hp, &h);
    if (st != FBRL_OK)
        return st;
    st = fbrl__astore_read(h, buf, sizeof buf - 1, &got);
    fbrl__astore_close(h);
    if (st != FBRL_OK)
        return st;
    if (got <= k || memcmp(buf, HEAD_MAGIC, k) != 0)
        return FBRL_EFORMAT;
    while (k < got && buf[k] >= '0' && buf[k] <= '9' && n < 1000000000000ull)
        n = n * 10 + (unsigned long long)(buf[k++] - '0');
    if (k >= got || buf[k] != ' ' || got < k + 1 + 2 * FBRL_AUDIT_HASH_SIZE + 1 ||
        fbrl__audit_unhex(buf + k + 1, 2 * FBRL_AUDIT_HASH_SIZE, hash, FBRL_AUDIT_HASH_SIZE) != 0 ||
        buf[k + 1 + 2 * FBRL_AUDIT_HASH_SIZE] != '\n')
        return FBRL_EFORMAT;
    *seq = n;
    return FBRL_OK;
}

/* The head, always the same length (seq in 20 digits), rewritten in place: one sync. */
static fbrl_status write_head(fbrl_audit_file *f, uint64_t seq, const unsigned char *hash)
{
    char hp[FBRL_AUDIT_PATH_MAX + 8], hex[2 * FBRL_AUDIT_HASH_SIZE + 1], buf[160];
    int n;
    if (f->head_handle == NULL) {
        fbrl_status st;
        if (head_path(f->path, hp, sizeof hp) != 0)
            return FBRL_ENAME;
        st = fbrl__astore_head_open(hp, &f->head_handle);
        if (st != FBRL_OK)
            return st;
    }
    fbrl__audit_hex(hash, FBRL_AUDIT_HASH_SIZE, hex);
    n = snprintf(buf, sizeof buf, "%s%020llu %s\n", HEAD_MAGIC, (unsigned long long)seq, hex);
    return fbrl__astore_head_put(f->head_handle, buf, (size_t)n);
}

fbrl_status fbrl_audit_file_verify(const char *path, fbrl_audit_verifier *v)
{
    char buf[READ_CHUNK];
    unsigned char head[FBRL_AUDIT_HASH_SIZE];
    uint64_t head_seq = 0;
    size_t got;
    void *h;
    fbrl_status st, hst;
    if (path == NULL || v == NULL)
        return FBRL_EINVAL;
    st = fbrl__astore_read_open(path, &h);
    if (st != FBRL_OK && st != FBRL_ENOENT)
        return st;
    if (st == FBRL_OK) {
        do {
            st = fbrl__astore_read(h, buf, sizeof buf, &got);
            if (st == FBRL_OK)
                fbrl_audit_verify_bytes(v, buf, got);
        } while (st == FBRL_OK && got > 0);
        fbrl__astore_close(h);
        if (st != FBRL_OK)
            return st;
    }
    hst = read_head(path, &head_seq, head);
    if (hst == FBRL_ENOENT && v->line == 0 && v->len == 0)
        return fbrl_audit_verify_end(v, 0, NULL); /* no chain yet */
    if (hst == FBRL_ENOENT || hst == FBRL_EFORMAT) {
        fbrl_audit_verify_end(v, 0, NULL);
        if (v->broken == FBRL_OK) {
            snprintf(v->where, sizeof v->where, "record %llu (line %lu): the head file %s%s is %s",
                     (unsigned long long)v->seq, v->line, path, HEAD_SUFFIX,
                     hst == FBRL_ENOENT ? "missing" : "not a head file");
            v->broken = FBRL_ECHECKSUM;
            v->broken_line = v->line;
        }
        return v->broken;
    }
    if (hst != FBRL_OK)
        return hst;
    return fbrl_audit_verify_end(v, head_seq, head);
}

/* The writer's sink: append and sync, then move the head. The record's seq and hash are
 * read back from the line the writer made. */
static int file_write(void *ctx, const char *s, size_t n)
{
    fbrl_audit_file *f = ctx;
    unsigned long long seq = 0;
    unsigned char h[FBRL_AUDIT_HASH_SIZE];
    size_t k = sizeof "{\"seq\":" - 1;
    if (n < FBRL__AUDIT_TAIL + k + 1 || fbrl__astore_append(f->handle, s, n) != FBRL_OK)
        return -1;
    while (k < n && s[k] >= '0' && s[k] <= '9')
        seq = seq * 10 + (unsigned long long)(s[k++] - '0');
    if (fbrl__audit_unhex(s + n - 3 - 2 * FBRL_AUDIT_HASH_SIZE, 2 * FBRL_AUDIT_HASH_SIZE, h, sizeof h) != 0 ||
        write_head(f, seq, h) != FBRL_OK)
        return -1;
    f->head_seq = seq;
    memcpy(f->head, h, sizeof h);
    return 0;
}

static int64_t store_utc(void *ctx)
{
    (void)ctx;
    return fbrl__astore_utc_ms();
}

int64_t fbrl_audit_utc_now(void *ctx) { return store_utc(ctx); }

static fbrl_status start(fbrl_audit_file *f, const char *path)
{
    if (f == NULL || path == NULL || path[0] == '\0')
        return FBRL_EINVAL;
    memset(f, 0, sizeof *f);
    if (strlen(path) >= sizeof f->path - sizeof HEAD_SUFFIX)
        return FBRL_ENAME;
    snprintf(f->path, sizeof f->path, "%s", path);
    return FBRL_OK;
}

fbrl_status fbrl_audit_file_open(fbrl_audit_file *f, const char *path, fbrl_audit_verifier *v)
{
    fbrl_status st = start(f, path);
    if (st != FBRL_OK || v == NULL)
        return st != FBRL_OK ? st : FBRL_EINVAL;
    /* locked first, then verified: nobody appends between the check and the writes */
    st = fbrl__astore_open_append(path, &f->handle);
    if (st != FBRL_OK)
        return st;
    st = fbrl_audit_file_verify(path, v);
    if (st == FBRL_ECHECKSUM)
        snprintf(f->where, sizeof f->where, "%s", v->where);
    if (st != FBRL_OK) {
        fbrl__astore_close(f->handle);
        f->handle = NULL;
        return st;
    }
    f->head_seq = v->seq;
    memcpy(f->head, v->head, sizeof f->head);
    st = fbrl_audit_init(&f->a, file_write, f, store_utc, NULL, v->seq, v->seq ? v->head : NULL);
    f->a.last_seal = v->last_seal;
    return st;
}

fbrl_status fbrl_audit_file_recover(fbrl_audit_file *f, const char *path, fbrl_audit_verifier *v,
                                    const char *admin, const char *reason, const unsigned char *sk,
                                    const unsigned char *pk)
{
    unsigned char before[FBRL_AUDIT_HASH_SIZE];
    crypto_hash_sha256_state hs;
    char utc[32];
    uint64_t seq;
    unsigned long line;
    fbrl_status st = start(f, path);
    if (st != FBRL_OK || v == NULL || admin == NULL || reason == NULL || sk == NULL || pk == NULL)
        return st != FBRL_OK ? st : FBRL_EINVAL;
    st = fbrl__astore_open_append(path, &f->handle);
    if (st != FBRL_OK)
        return st;
    st = fbrl_audit_file_verify(path, v);
    if (st != FBRL_ECHECKSUM) {
        fbrl__astore_close(f->handle);
        f->handle = NULL;
        return st == FBRL_OK ? FBRL_ESTATE : st;
    }
    snprintf(f->where, sizeof f->where, "%s", v->where);
    st = FBRL_OK;
    memcpy(&hs, v->file_hash, sizeof hs);
    line = v->line;
    if (v->len > 0 || v->overlong) { /* a cut last line: ended, so the recovery stands on its own line */
        st = fbrl__astore_append(f->handle, "\n", 1);
        crypto_hash_sha256_update(&hs, (const unsigned char *)"\n", 1);
        line++;
    }
    crypto_hash_sha256_final(&hs, before);
    seq = line + 1;
    if (st == FBRL_OK)
        st = fbrl_audit_init(&f->a, file_write, f, store_utc, NULL, 0, NULL);
    if (st == FBRL_OK)
        st = fbrl_audit_set_user(&f->a, admin);
    if (st == FBRL_OK) {
        fbrl_audit *a = &f->a;
        const char *inner;
        fbrl_audit_begin(a, "recovery");
        fbrl_audit_num(a, "broken_line", (long)v->broken_line);
        fbrl_audit_str(a, "break", v->where);
        fbrl_audit_str(a, "reason", reason);
        a->building = 0;
        if (a->overflow || a->blen < 2)
            st = FBRL_ENOSPC;
        inner = a->body + 1; /* the members after "{": the body is not closed yet */
        fbrl_audit_utc_text(store_utc(NULL), utc);
        if (st == FBRL_OK)
            st = fbrl__audit_write(a, utc, inner, a->blen - 1, seq, before);
    }
    if (st == FBRL_OK)
        st = fbrl_audit_sign(&f->a, f->a.seq, f->a.head, FBRL_AUDIT_MEANING_RECOVERY, sk, pk);
    if (st != FBRL_OK) {
        fbrl__astore_close(f->handle);
        fbrl__astore_close(f->head_handle);
        f->handle = f->head_handle = NULL;
    }
    return st;
}

fbrl_status fbrl_audit_file_close(fbrl_audit_file *f)
{
    fbrl_status st;
    if (f == NULL)
        return FBRL_EINVAL;
    st = f->a.failed;
    fbrl__astore_close(f->handle);
    fbrl__astore_close(f->head_handle);
    f->handle = f->head_handle = NULL;
    return st;
}
