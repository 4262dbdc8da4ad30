/* SPDX-License-Identifier: MIT */
/* audit.c - the audit chain's writer: records built in the writer's buffers, hashed with
 * libsodium's SHA-256, signed with its Ed25519; reading a record's fields. */
#include "fbrl/audit.h"
#include "audit_int.h"

#include <sodium.h>
#include <stdio.h>
#include <string.h>

/* ---- small pieces shared with the verifier (audit_int.h) ---- */

void fbrl__audit_hex(const unsigned char *b, size_t n, char *out)
{
    static const char hex[] = "0123456789abcdef";
    for (size_t i = 0; i < n; i++) {
        out[2 * i] = hex[b[i] >> 4];
        out[2 * i + 1] = hex[b[i] & 15];
    }
    out[2 * n] = '\0';
}

static int hexval(char c)
{
    return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
}

int fbrl__audit_unhex(const char *s, size_t len, unsigned char *out, size_t n)
{
    if (len != 2 * n)
        return -1;
    for (size_t i = 0; i < n; i++) {
        int hi = hexval(s[2 * i]), lo = hexval(s[2 * i + 1]);
        if (hi < 0 || lo < 0)
            return -1;
        out[i] = (unsigned char)(hi << 4 | lo);
    }
    return 0;
}

int fbrl__audit_name_ok(const char *s)
{
    size_t n = s ? strlen(s) : 0;
    if (n == 0 || n >= FBRL_AUDIT_NAME_MAX)
        return 0;
    for (size_t i = 0; i < n; i++) {
        char c = s[i];
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
              c == '_' || c == '-'))
            return 0;
    }
    return 1;
}

/* Days from 1970-01-01 to y-m-d's civil date, inverted (H. Hinnant's algorithm): the core
 * has no gmtime. */
void fbrl_audit_utc_text(int64_t ms, char *buf)
{
    int64_t secs = ms >= 0 ? ms / 1000 : (ms - 999) / 1000;
    int msec = (int)(ms - secs * 1000);
    int64_t days = secs >= 0 ? secs / 86400 : (secs - 86399) / 86400;
    int64_t sod = secs - days * 86400;
    int64_t z = days + 719468;
    int64_t era = (z >= 0 ? z : z - 146096) / 146097;
    int64_t doe = z - era * 146097;
    int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    int64_t y = yoe + era * 400;
    int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    int64_t mp = (5 * doy + 2) / 153;
    int64_t d = doy - (153 * mp + 2) / 5 + 1;
    int64_t m = mp < 10 ? mp + 3 : mp - 9;
    if (m <= 2)
        y++;
    if (y < 0 || y > 9999) /* past what ISO 8601's four digits hold */
        y = y < 0 ? 0 : 9999;
    snprintf(buf, 32, "%04u-%02u-%02uT%02u:%02u:%02u.%03uZ", (unsigned)y % 10000u, (unsigned)m % 100u,
             (unsigned)d % 100u, (unsigned)(sod / 3600) % 100u, (unsigned)(sod / 60 % 60) % 100u,
             (unsigned)(sod % 60) % 100u, (unsigned)msec % 1000u);
}

size_t fbrl_audit_sig_message(char *buf, size_t cap, const unsigned char *hash, uint64_t seq, const char *signer,
                              const char *utc, const char *meaning)
{
    char hex[2 * FBRL_AUDIT_HASH_SIZE + 1];
    int n;
    if (buf == NULL || hash == NULL || signer == NULL || utc == NULL || meaning == NULL)
        return 0;
    fbrl__audit_hex(hash, FBRL_AUDIT_HASH_SIZE, hex);
    n = snprintf(buf, cap, "fbrl-signature 1\n%s\n%llu\n%s\n%s\n%s\n", hex, (unsigned long long)seq, signer, utc,
                 meaning);
    return n < 0 || (size_t)n >= cap ? 0 : (size_t)n;
}

/* ---- JSON: just enough to walk one flat object's members (audit_int.h) ---- */

static size_t ws(const char *s, size_t n, size_t i)
{
    while (i < n && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r' || s[i] == '\n'))
        i++;
    return i;
}

static int skip_string(const char *s, size_t n, size_t *i)
{
    size_t k = *i + 1;
    while (k < n && s[k] != '"') {
        if ((unsigned char)s[k] < 0x20)
            return -1;
        k += s[k] == '\\' ? 2 : 1;
    }
    if (k >= n)
        return -1;
    *i = k + 1;
    return 0;
}

#define JSON_DEPTH_MAX 32

static int skip_value(const char *s, size_t n, size_t *i, int depth)
{
    size_t k = *i;
    if (k >= n || depth > JSON_DEPTH_MAX)
        return -1;
    if (s[k] == '"')
        return skip_string(s, n, i);
    if (s[k] == '{' || s[k] == '[') {
        char close = s[k] == '{' ? '}' : ']';
        int obj = s[k] == '{';
        k = ws(s, n, k + 1);
        if (k < n && s[k] == close) {
            *i = k + 1;
            return 0;
        }
        for (;;) {
            if (obj) {
                if (k >= n || s[k] != '"' || skip_string(s, n, &k) != 0)
                    return -1;
                k = ws(s, n, k);
                if (k >= n || s[k] != ':')
                    return -1;
                k = ws(s, n, k + 1);
            }
            if (skip_value(s, n, &k, depth + 1) != 0)
                return -1;
            k = ws(s, n, k);
            if (k < n && s[k] == ',') {
                k = ws(s, n, k + 1);
                continue;
            }
            if (k < n && s[k] == close) {
                *i = k + 1;
                return 0;
            }
            return -1;
        }
    }
    /* a number or true/false/null */
    size_t start = k;
    while (k < n && ((s[k] >= '0' && s[k] <= '9') || s[k] == '-' || s[k] == '+' || s[k] == '.' || s[k] == 'e' ||
                     s[k] == 'E' || (s[k] >= 'a' && s[k] <= 'z')))
        k++;
    if (k == start)
        return -1;
    *i = k;
    return 0;
}

int fbrl__audit_json_skip(const char *s, size_t n, size_t *i)
{
    *i = ws(s, n, *i);
    return skip_value(s, n, i, 0);
}

int fbrl__audit_json_object(const char *s, size_t n)
{
    size_t i = ws(s, n, 0);
    if (i >= n || s[i] != '{' || skip_value(s, n, &i, 0) != 0)
        return -1;
    return ws(s, n, i) == n ? 0 : -1;
}

fbrl_status fbrl_audit_field(const char *s, size_t n, const char *key, const char **value, size_t *vlen)
{
    size_t klen, i;
    if (s == NULL || key == NULL || value == NULL || vlen == NULL)
        return FBRL_EINVAL;
    klen = strlen(key);
    i = ws(s, n, 0);
    if (i >= n || s[i] != '{')
        return FBRL_ESYNTAX;
    i = ws(s, n, i + 1);
    if (i < n && s[i] == '}')
        return FBRL_ENOENT;
    for (;;) {
        size_t k0 = i, v0;
        if (i >= n || s[i] != '"' || skip_string(s, n, &i) != 0)
            return FBRL_ESYNTAX;
        int match = i - k0 == klen + 2 && memcmp(s + k0 + 1, key, klen) == 0;
        i = ws(s, n, i);
        if (i >= n || s[i] != ':')
            return FBRL_ESYNTAX;
        i = ws(s, n, i + 1);
        v0 = i;
        if (skip_value(s, n, &i, 1) != 0)
            return FBRL_ESYNTAX;
        if (match) {
            *value = s + v0;
            *vlen = i - v0;
            return FBRL_OK;
        }
        i = ws(s, n, i);
        if (i < n && s[i] == ',') {
            i = ws(s, n, i + 1);
            continue;
        }
        return i < n && s[i] == '}' ? FBRL_ENOENT : FBRL_ESYNTAX;
    }
}

fbrl_status fbrl_audit_field_str(const char *line, size_t len, const char *key, char *buf, size_t cap)
{
    const char *v;
    size_t vl, o = 0;
    fbrl_status st;
    if (buf == NULL || cap == 0)
        return FBRL_EINVAL;
    buf[0] = '\0';
    st = fbrl_audit_field(line, len, key, &v, &vl);
    if (st != FBRL_OK)
        return st;
    if (vl < 2 || v[0] != '"')
        return FBRL_ETYPE;
    for (size_t i = 1; i + 1 < vl; i++) {
        char c = v[i];
        if (c == '\\' && i + 2 < vl) {
            char e = v[++i];
            c = e == 'n' ? '\n' : e == 't' ? '\t' : e == 'r' ? '\r' : e;
            if (e == 'u' && i + 4 < vl) { /* \u00XX: the run log escapes control bytes so */
                unsigned char b[2];
                c = fbrl__audit_unhex(v + i + 1, 4, b, 2) == 0 && b[0] == 0 ? (char)b[1] : '?';
                i += 4;
            }
        }
        if (o + 1 >= cap) {
            buf[o] = '\0';
            return FBRL_ENOSPC;
        }
        buf[o++] = c;
    }
    buf[o] = '\0';
    return FBRL_OK;
}

fbrl_status fbrl_audit_field_num(const char *line, size_t len, const char *key, long long *value)
{
    const char *v;
    size_t vl;
    long long x = 0;
    int neg = 0;
    fbrl_status st = fbrl_audit_field(line, len, key, &v, &vl);
    if (st != FBRL_OK || value == NULL)
        return st != FBRL_OK ? st : FBRL_EINVAL;
    if (vl > 0 && v[0] == '-')
        neg = 1, v++, vl--;
    if (vl == 0 || vl > 18)
        return FBRL_ETYPE;
    for (size_t i = 0; i < vl; i++) {
        if (v[i] < '0' || v[i] > '9')
            return FBRL_ETYPE;
        x = x * 10 + (v[i] - '0');
    }
    *value = neg ? -x : x;
    return FBRL_OK;
}

/* ---- the writer ---- */

fbrl_status fbrl_audit_init(fbrl_audit *a, fbrl_audit_write_fn write, void *write_ctx, fbrl_audit_utc_fn utc,
                            void *utc_ctx, uint64_t seq, const unsigned char *head)
{
    if (a == NULL || write == NULL || (seq > 0 && head == NULL))
        return FBRL_EINVAL;
    if (sodium_init() < 0)
        return FBRL_EIO;
    memset(a, 0, sizeof *a);
    a->write = write;
    a->write_ctx = write_ctx;
    a->utc = utc;
    a->utc_ctx = utc_ctx;
    a->seq = seq;
    if (head != NULL)
        memcpy(a->head, head, FBRL_AUDIT_HASH_SIZE);
    return FBRL_OK;
}

fbrl_status fbrl_audit_set_user(fbrl_audit *a, const char *user)
{
    if (a == NULL)
        return FBRL_EINVAL;
    if (!fbrl__audit_name_ok(user))
        return FBRL_ENAME;
    snprintf(a->user, sizeof a->user, "%s", user);
    return FBRL_OK;
}

uint64_t fbrl_audit_head(const fbrl_audit *a, unsigned char *hash)
{
    if (a == NULL)
        return 0;
    if (hash != NULL)
        memcpy(hash, a->head, FBRL_AUDIT_HASH_SIZE);
    return a->seq;
}

/* The record: the chain's fields, the body's members, its hash; written in one piece. The
 * body is inner[0..n): the members between the object's braces. prev_override: a recovery's
 * prev (the hash of the file's bytes before it) instead of the last record's. */
fbrl_status fbrl__audit_write(fbrl_audit *a, const char *utc, const char *inner, size_t n, uint64_t seq,
                              const unsigned char *prev)
{
    char hex[2 * FBRL_AUDIT_HASH_SIZE + 1];
    unsigned char h[FBRL_AUDIT_HASH_SIZE];
    int k;
    size_t len;
    if (a->failed != FBRL_OK)
        return a->failed;
    if (a->user[0] == '\0')
        return FBRL_ESTATE;
    fbrl__audit_hex(prev, FBRL_AUDIT_HASH_SIZE, hex);
    k = snprintf(a->line, sizeof a->line, "{\"seq\":%llu,\"utc\":\"%s\",\"user\":\"%s\",\"prev\":\"%s\"",
                 (unsigned long long)seq, utc, a->user, hex);
    len = (size_t)k;
    if (len + (n ? n + 1 : 0) + FBRL__AUDIT_TAIL > FBRL_AUDIT_LINE_MAX)
        return FBRL_ENOSPC;
    if (n) {
        a->line[len++] = ',';
        memcpy(a->line + len, inner, n);
        len += n;
    }
    crypto_hash_sha256(h, (const unsigned char *)a->line, len);
    fbrl__audit_hex(h, sizeof h, hex);
    len += (size_t)snprintf(a->line + len, sizeof a->line - len, ",\"hash\":\"%s\"}\n", hex);
    if (a->write(a->write_ctx, a->line, len) != 0) {
        a->failed = FBRL_EIO;
        return FBRL_EIO;
    }
    a->seq = seq;
    memcpy(a->head, h, sizeof h);
    return FBRL_OK;
}

static void now_text(const fbrl_audit *a, char *utc)
{
    fbrl_audit_utc_text(a->utc ? a->utc(a->utc_ctx) : 0, utc);
}

/* The members of the object json[0..len): between its braces, blanks trimmed. */
static fbrl_status inner_of(const char *json, size_t len, const char **inner, size_t *n)
{
    size_t b = 0, e = len;
    if (json == NULL || fbrl__audit_json_object(json, len) != 0)
        return FBRL_ESYNTAX;
    while (json[b] != '{')
        b++;
    while (json[e - 1] != '}')
        e--;
    b++, e--;
    while (b < e && (json[b] == ' ' || json[b] == '\n' || json[b] == '\r' || json[b] == '\t'))
        b++;
    while (e > b && (json[e - 1] == ' ' || json[e - 1] == '\n' || json[e - 1] == '\r' || json[e - 1] == '\t'))
        e--;
    *inner = json + b;
    *n = e - b;
    return FBRL_OK;
}

fbrl_status fbrl_audit_append(fbrl_audit *a, const char *json, size_t len)
{
    char utc[32];
    const char *inner;
    size_t n;
    fbrl_status st;
    if (a == NULL || json == NULL)
        return FBRL_EINVAL;
    st = inner_of(json, len, &inner, &n);
    if (st != FBRL_OK)
        return st;
    now_text(a, utc);
    return fbrl__audit_write(a, utc, inner, n, a->seq + 1, a->head);
}

/* ---- building a body field by field ---- */

static void body_put(fbrl_audit *a, const char *s, size_t n)
{
    if (a->blen + n > FBRL_AUDIT_BODY_MAX) {
        a->overflow = 1;
        return;
    }
    memcpy(a->body + a->blen, s, n);
    a->blen += n;
}

void fbrl__audit_json_str(fbrl_audit *a, const char *s)
{
    static const char hex[] = "0123456789abcdef";
    body_put(a, "\"", 1);
    for (; s && *s; s++) {
        unsigned char c = (unsigned char)*s;
        char esc[6] = {'\\', 'u', '0', '0', hex[c >> 4], hex[c & 15]};
        if (c == '"' || c == '\\') {
            esc[1] = (char)c;
            body_put(a, esc, 2);
        } else if (c == '\n') {
            body_put(a, "\\n", 2);
        } else if (c < 0x20 || c == 0x7f) {
            body_put(a, esc, 6);
        } else {
            body_put(a, s, 1);
        }
    }
    body_put(a, "\"", 1);
}

static void body_key(fbrl_audit *a, const char *key)
{
    body_put(a, a->blen > 1 ? ",\"" : "\"", a->blen > 1 ? 2 : 1);
    body_put(a, key, strlen(key));
    body_put(a, "\":", 2);
}

fbrl_status fbrl_audit_begin(fbrl_audit *a, const char *type)
{
    if (a == NULL || type == NULL)
        return FBRL_EINVAL;
    a->blen = 0;
    a->overflow = 0;
    a->building = 1;
    body_put(a, "{", 1);
    fbrl_audit_str(a, "type", type);
    return FBRL_OK;
}

void fbrl_audit_str(fbrl_audit *a, const char *key, const char *value)
{
    if (a == NULL || !a->building || key == NULL)
        return;
    body_key(a, key);
    if (value == NULL)
        body_put(a, "null", 4);
    else
        fbrl__audit_json_str(a, value);
}

void fbrl_audit_num(fbrl_audit *a, const char *key, long value)
{
    char num[32];
    if (a == NULL || !a->building || key == NULL)
        return;
    body_key(a, key);
    body_put(a, num, (size_t)snprintf(num, sizeof num, "%ld", value));
}

void fbrl_audit_raw(fbrl_audit *a, const char *key, const char *json)
{
    if (a == NULL || !a->building || key == NULL)
        return;
    body_key(a, key);
    body_put(a, json ? json : "null", json ? strlen(json) : 4);
}

fbrl_status fbrl_audit_end(fbrl_audit *a)
{
    if (a == NULL || !a->building)
        return a == NULL ? FBRL_EINVAL : FBRL_ESTATE;
    a->building = 0;
    body_put(a, "}", 1);
    if (a->overflow)
        return FBRL_ENOSPC;
    return fbrl_audit_append(a, a->body, a->blen);
}

fbrl_status fbrl_audit_seal(fbrl_audit *a)
{
    fbrl_status st;
    uint64_t first;
    if (a == NULL)
        return FBRL_EINVAL;
    first = a->last_seal + 1;
    fbrl_audit_begin(a, "seal");
    fbrl_audit_num(a, "first", (long)first);
    fbrl_audit_num(a, "records", (long)(a->seq + 1 - first));
    st = fbrl_audit_end(a);
    if (st == FBRL_OK)
        a->last_seal = a->seq;
    return st;
}

fbrl_status fbrl_audit_sign(fbrl_audit *a, uint64_t seq, const unsigned char *hash, const char *meaning,
                            const unsigned char *sk, const unsigned char *pk)
{
    char utc[32], msg[FBRL_AUDIT_BODY_MAX / 2], hex[2 * FBRL_AUDIT_SIG_SIZE + 1];
    unsigned char sig[FBRL_AUDIT_SIG_SIZE];
    size_t mlen;
    const char *inner;
    size_t n;
    fbrl_status st;
    if (a == NULL || hash == NULL || meaning == NULL || sk == NULL || pk == NULL || seq == 0 || seq > a->seq)
        return FBRL_EINVAL;
    if (a->user[0] == '\0')
        return FBRL_ESTATE;
    now_text(a, utc);
    mlen = fbrl_audit_sig_message(msg, sizeof msg, hash, seq, a->user, utc, meaning);
    if (mlen == 0)
        return FBRL_ENOSPC;
    crypto_sign_detached(sig, NULL, (const unsigned char *)msg, mlen, sk);
    if (crypto_sign_verify_detached(sig, (const unsigned char *)msg, mlen, pk) != 0)
        return FBRL_EINVAL; /* sk and pk are not one pair */
    fbrl_audit_begin(a, "signature");
    fbrl_audit_num(a, "signs", (long)seq);
    fbrl__audit_hex(hash, FBRL_AUDIT_HASH_SIZE, hex);
    fbrl_audit_str(a, "signed_hash", hex);
    fbrl_audit_str(a, "meaning", meaning);
    fbrl__audit_hex(pk, FBRL_AUDIT_PK_SIZE, hex);
    fbrl_audit_str(a, "key", hex);
    fbrl__audit_hex(sig, sizeof sig, hex);
    fbrl_audit_str(a, "sig", hex);
    a->building = 0;
    body_put(a, "}", 1);
    if (a->overflow)
        return FBRL_ENOSPC;
    st = inner_of(a->body, a->blen, &inner, &n);
    return st != FBRL_OK ? st : fbrl__audit_write(a, utc, inner, n, a->seq + 1, a->head);
}
