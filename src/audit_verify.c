/* SPDX-License-Identifier: MIT */
/* audit_verify.c - checking a chain record by record: each record's own hash, the order
 * of seq and prev, signatures against the public keys, the head file at the end, and an
 * administrator's recovery of a break. */
#include "fbrl/audit.h"
#include "audit_int.h"

#include <sodium.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

typedef char state_fits[sizeof(crypto_hash_sha256_state) <= sizeof(((fbrl_audit_verifier *)0)->file_hash) ? 1
                                                                                                          : -1];

#define ADMIN_ROLE "administrator"

fbrl_status fbrl_audit_verify_init(fbrl_audit_verifier *v, fbrl_audit_key *keys, size_t nkeys, size_t key_cap,
                                   unsigned char (*hashes)[FBRL_AUDIT_HASH_SIZE], size_t hash_cap)
{
    if (v == NULL || (key_cap && keys == NULL) || nkeys > key_cap || (hash_cap && hashes == NULL))
        return FBRL_EINVAL;
    if (sodium_init() < 0)
        return FBRL_EIO;
    memset(v, 0, sizeof *v);
    v->keys = keys;
    v->nkeys = nkeys;
    v->key_cap = key_cap;
    v->keys_from_chain = nkeys == 0;
    v->hashes = hashes;
    v->hash_cap = hash_cap;
    crypto_hash_sha256_init((crypto_hash_sha256_state *)(void *)v->file_hash);
    memcpy(v->line_hash, v->file_hash, sizeof v->line_hash);
    return FBRL_OK;
}

/* The first break wins: later ones follow from it. */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static fbrl_status breaks(fbrl_audit_verifier *v, uint64_t rec, unsigned long line, const char *fmt, ...)
{
    char what[FBRL_AUDIT_WHERE_MAX - 40];
    va_list ap;
    if (v->broken != FBRL_OK)
        return FBRL_ECHECKSUM;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    snprintf(v->where, sizeof v->where, "record %llu (line %lu): %s", (unsigned long long)rec, line, what);
    v->broken = FBRL_ECHECKSUM;
    v->broken_line = line;
    return FBRL_ECHECKSUM;
}

static const fbrl_audit_key *find_key(const fbrl_audit_verifier *v, const char *name, const unsigned char *pk)
{
    for (size_t i = 0; i < v->nkeys; i++)
        if (strcmp(v->keys[i].name, name) == 0 && sodium_memcmp(v->keys[i].pk, pk, FBRL_AUDIT_PK_SIZE) == 0)
            return &v->keys[i];
    return NULL;
}

/* A "user" record that names a key: learnt when the keys come from the chain. */
static void learn_key(fbrl_audit_verifier *v, const char *s, size_t n)
{
    char name[FBRL_AUDIT_NAME_MAX], role[FBRL_AUDIT_ROLE_MAX], hex[2 * FBRL_AUDIT_PK_SIZE + 2];
    unsigned char pk[FBRL_AUDIT_PK_SIZE];
    fbrl_audit_key *known;
    if (!v->keys_from_chain || fbrl_audit_field_str(s, n, "name", name, sizeof name) != FBRL_OK ||
        fbrl_audit_field_str(s, n, "role", role, sizeof role) != FBRL_OK ||
        fbrl_audit_field_str(s, n, "key", hex, sizeof hex) != FBRL_OK ||
        fbrl__audit_unhex(hex, strlen(hex), pk, sizeof pk) != 0)
        return;
    known = (fbrl_audit_key *)(uintptr_t)find_key(v, name, pk);
    if (known != NULL) { /* a role change: the key is the same */
        snprintf(known->role, FBRL_AUDIT_ROLE_MAX, "%s", role);
        return;
    }
    if (v->nkeys >= v->key_cap)
        return;
    snprintf(v->keys[v->nkeys].name, FBRL_AUDIT_NAME_MAX, "%s", name);
    snprintf(v->keys[v->nkeys].role, FBRL_AUDIT_ROLE_MAX, "%s", role);
    memcpy(v->keys[v->nkeys].pk, pk, sizeof pk);
    v->nkeys++;
}

static int hash_of(const fbrl_audit_verifier *v, uint64_t seq, unsigned char *out)
{
    if (seq == v->seq) {
        memcpy(out, v->head, FBRL_AUDIT_HASH_SIZE);
        return 0;
    }
    if (seq >= 1 && seq <= v->hash_cap && seq < v->seq) {
        memcpy(out, v->hashes[seq - 1], FBRL_AUDIT_HASH_SIZE);
        return 0;
    }
    return -1;
}

/* A signature record: bound to the hash of the record it signs, made by a key the
 * verifier trusts for the user named, over the signer, time and meaning. 0 or a break. */
static fbrl_status check_signature(fbrl_audit_verifier *v, const char *s, size_t n, uint64_t rec,
                                   const char *user, const char *utc, const fbrl_audit_key **signer)
{
    char hex[2 * FBRL_AUDIT_SIG_SIZE + 2], meaning[256], msg[1024];
    unsigned char want[FBRL_AUDIT_HASH_SIZE], have[FBRL_AUDIT_HASH_SIZE], pk[FBRL_AUDIT_PK_SIZE];
    unsigned char sig[FBRL_AUDIT_SIG_SIZE];
    long long signs;
    size_t mlen;
    unsigned long line = v->line;
    *signer = NULL;
    if (fbrl_audit_field_num(s, n, "signs", &signs) != FBRL_OK || signs < 1 || (uint64_t)signs >= rec ||
        fbrl_audit_field_str(s, n, "signed_hash", hex, sizeof hex) != FBRL_OK ||
        fbrl__audit_unhex(hex, strlen(hex), want, sizeof want) != 0 ||
        fbrl_audit_field_str(s, n, "meaning", meaning, sizeof meaning) != FBRL_OK)
        return breaks(v, rec, line, "a signature without its record, hash or meaning");
    if (hash_of(v, (uint64_t)signs, have) == 0) {
        if (sodium_memcmp(have, want, sizeof have) != 0)
            return breaks(v, rec, line, "signature by %s is not for record %lld: its hash differs (moved)", user, signs);
    } else {
        v->unchecked++; /* older than the verifier kept: the signature is checked on its own hash */
    }
    if (fbrl_audit_field_str(s, n, "key", hex, sizeof hex) != FBRL_OK ||
        fbrl__audit_unhex(hex, strlen(hex), pk, sizeof pk) != 0)
        return breaks(v, rec, line, "signature by %s names no key", user);
    *signer = find_key(v, user, pk);
    if (*signer == NULL)
        return breaks(v, rec, line, "signature by %s: no trusted public key of %s matches", user, user);
    if (fbrl_audit_field_str(s, n, "sig", hex, sizeof hex) != FBRL_OK ||
        fbrl__audit_unhex(hex, strlen(hex), sig, sizeof sig) != 0)
        return breaks(v, rec, line, "signature by %s has no signature value", user);
    mlen = fbrl_audit_sig_message(msg, sizeof msg, want, (uint64_t)signs, user, utc, meaning);
    if (mlen == 0 || crypto_sign_verify_detached(sig, (const unsigned char *)msg, mlen, pk) != 0)
        return breaks(v, rec, line, "signature by %s does not verify with %s's public key", user, user);
    v->signatures++;
    return FBRL_OK;
}

/* One whole line: s[0..n), no newline. */
static fbrl_status check_line(fbrl_audit_verifier *v, const char *s, size_t n)
{
    unsigned char h[FBRL_AUDIT_HASH_SIZE], want[FBRL_AUDIT_HASH_SIZE], prev[FBRL_AUDIT_HASH_SIZE];
    char hex[2 * FBRL_AUDIT_HASH_SIZE + 2], type[32], user[FBRL_AUDIT_NAME_MAX], utc[40];
    long long seq;
    uint64_t expect = v->seq + 1;
    unsigned long line = v->line;
    const fbrl_audit_key *signer;
    size_t body = n >= FBRL__AUDIT_TAIL ? n - FBRL__AUDIT_TAIL : 0;
    int recovery;

    if (n == 0)
        return breaks(v, expect, line, "an empty line");
    if (v->overlong)
        return breaks(v, expect, line, "longer than any record can be");
    if (n < FBRL__AUDIT_TAIL || memcmp(s + body, FBRL__AUDIT_HASH_KEY, sizeof FBRL__AUDIT_HASH_KEY - 1) != 0 ||
        s[n - 2] != '"' || s[n - 1] != '}' ||
        fbrl__audit_unhex(s + body + sizeof FBRL__AUDIT_HASH_KEY - 1, 2 * FBRL_AUDIT_HASH_SIZE, want, sizeof want))
        return breaks(v, expect, line, "no hash at its end: not a whole record");
    crypto_hash_sha256(h, (const unsigned char *)s, body);
    if (sodium_memcmp(h, want, sizeof h) != 0)
        return breaks(v, expect, line, "changed after it was written: its content does not match its hash");
    if (fbrl__audit_json_object(s, n) != 0 || fbrl_audit_field_num(s, n, "seq", &seq) != FBRL_OK || seq < 1 ||
        fbrl_audit_field_str(s, n, "utc", utc, sizeof utc) != FBRL_OK ||
        fbrl_audit_field_str(s, n, "user", user, sizeof user) != FBRL_OK ||
        fbrl_audit_field_str(s, n, "prev", hex, sizeof hex) != FBRL_OK ||
        fbrl__audit_unhex(hex, strlen(hex), prev, sizeof prev) != 0)
        return breaks(v, expect, line, "not a chain record (seq, utc, user or prev missing)");
    if (fbrl_audit_field_str(s, n, "type", type, sizeof type) != FBRL_OK)
        type[0] = '\0';
    recovery = strcmp(type, "recovery") == 0;

    if (recovery) {
        /* An administrator's recovery: bound to every byte of the file before it, so the
         * break it acknowledges stays as it was found. Its signature is the next record. */
        crypto_hash_sha256_state st;
        unsigned char before[FBRL_AUDIT_HASH_SIZE];
        long long bl;
        memcpy(&st, v->line_hash, sizeof st);
        crypto_hash_sha256_final(&st, before);
        if ((unsigned long)seq != line || sodium_memcmp(before, prev, sizeof prev) != 0)
            return breaks(v, expect, line, "a recovery record not made for the file as it stands");
        if (v->broken != FBRL_OK && (fbrl_audit_field_num(s, n, "broken_line", &bl) != FBRL_OK ||
                                     (unsigned long)bl != v->broken_line))
            return FBRL_ECHECKSUM; /* it recovers another break than this one */
        v->pending_recovery = line;
        v->pending_seq = (uint64_t)seq;
        memcpy(v->pending_hash, h, sizeof h);
        v->seq = (uint64_t)seq;
        memcpy(v->head, h, sizeof h);
        return FBRL_OK;
    }
    if (v->pending_recovery) {
        unsigned long rline = v->pending_recovery;
        char meaning[64], found[FBRL_AUDIT_WHERE_MAX];
        int was_broken = v->broken != FBRL_OK;
        memcpy(found, v->where, sizeof found);
        v->pending_recovery = 0;
        v->broken = FBRL_OK; /* a recovery not validly signed is itself the break */
        if (strcmp(type, "signature") != 0 || (uint64_t)seq != expect || sodium_memcmp(prev, v->head, sizeof prev))
            return breaks(v, expect, line, "the recovery on line %lu is not signed", rline);
        if (check_signature(v, s, n, expect, user, utc, &signer) != FBRL_OK)
            return FBRL_ECHECKSUM;
        fbrl_audit_field_str(s, n, "meaning", meaning, sizeof meaning);
        if (strcmp(signer->role, ADMIN_ROLE) != 0 || strcmp(meaning, FBRL_AUDIT_MEANING_RECOVERY) != 0)
            return breaks(v, expect, line, "the recovery is signed by %s, not an administrator's recovery", user);
        snprintf(v->recovered, sizeof v->recovered, "%.120s (recovered by %s at %s, record %llu)",
                 was_broken ? found : "a cut tail or a replaced head file", user, utc,
                 (unsigned long long)v->pending_seq);
        v->where[0] = '\0';
        v->recoveries++;
        v->records += 2;
        v->seq = expect;
        memcpy(v->head, h, sizeof h);
        v->sealed = 0;
        return FBRL_OK;
    }
    if (v->broken != FBRL_OK)
        return FBRL_ECHECKSUM; /* lines after a break wait for a recovery */
    if ((uint64_t)seq != expect) {
        if ((uint64_t)seq + 1 == expect)
            return breaks(v, expect, line, "record %lld repeated", seq);
        return breaks(v, expect, line, "out of order: record %lld stands here (a record deleted, moved or repeated)",
                      seq);
    }
    if (sodium_memcmp(prev, v->head, sizeof prev) != 0)
        return breaks(v, expect, line, "prev is not the hash of the record before it (the chain was rewritten "
                      "from here)");
    if (strcmp(type, "signature") == 0 && check_signature(v, s, n, expect, user, utc, &signer) != FBRL_OK)
        return FBRL_ECHECKSUM;
    if (strcmp(type, "user") == 0)
        learn_key(v, s, n);
    if (v->seq >= 1 && v->seq <= v->hash_cap)
        memcpy(v->hashes[v->seq - 1], v->head, FBRL_AUDIT_HASH_SIZE);
    v->seq = expect;
    memcpy(v->head, h, sizeof h);
    v->records++;
    v->sealed = strcmp(type, "seal") == 0;
    if (v->sealed)
        v->last_seal = v->seq;
    return FBRL_OK;
}

fbrl_status fbrl_audit_verify_bytes(fbrl_audit_verifier *v, const char *s, size_t n)
{
    crypto_hash_sha256_state *fh;
    if (v == NULL || (n && s == NULL))
        return FBRL_EINVAL;
    fh = (crypto_hash_sha256_state *)(void *)v->file_hash;
    for (size_t i = 0; i < n;) {
        const char *nl = memchr(s + i, '\n', n - i);
        size_t take = nl ? (size_t)(nl - (s + i)) : n - i;
        if (v->len + take > FBRL_AUDIT_LINE_MAX)
            v->overlong = 1;
        else
            memcpy(v->buf + v->len, s + i, take);
        if (!v->overlong)
            v->len += take;
        crypto_hash_sha256_update(fh, (const unsigned char *)s + i, take + (nl != NULL));
        i += take;
        if (nl == NULL)
            break;
        i++;
        v->line++;
        check_line(v, v->buf, v->len);
        v->len = 0;
        v->overlong = 0;
        memcpy(v->line_hash, v->file_hash, sizeof v->line_hash);
    }
    return v->broken;
}

fbrl_status fbrl_audit_verify_end(fbrl_audit_verifier *v, uint64_t head_seq, const unsigned char *head)
{
    if (v == NULL)
        return FBRL_EINVAL;
    if (v->len > 0 || v->overlong)
        return breaks(v, v->seq + 1, v->line + 1, "incomplete: the file ends inside it (a write was cut)");
    if (v->pending_recovery)
        return breaks(v, v->seq + 1, v->line + 1, "missing: the recovery on line %lu is not signed",
                      v->pending_recovery);
    if (v->broken != FBRL_OK || head == NULL)
        return v->broken;
    if (head_seq > v->seq)
        return breaks(v, v->seq + 1, v->line + 1,
                      "missing: the head file says %llu records, the file ends before (tail cut)",
                      (unsigned long long)head_seq);
    if (head_seq < v->seq)
        return breaks(v, head_seq + 1, v->line - (unsigned long)(v->seq - head_seq) + 1,
                      "not in the head file, which ends at record %llu (records added behind the writer, or the "
                      "head was replaced)", (unsigned long long)head_seq);
    if (sodium_memcmp(v->head, head, FBRL_AUDIT_HASH_SIZE) != 0)
        return breaks(v, v->seq, v->line, "its hash differs from the head file's (the last record was replaced)");
    return FBRL_OK;
}

fbrl_status fbrl_audit_verify_hash(const fbrl_audit_verifier *v, uint64_t seq, unsigned char *hash)
{
    if (v == NULL || hash == NULL)
        return FBRL_EINVAL;
    return hash_of(v, seq, hash) == 0 ? FBRL_OK : FBRL_ERANGE;
}
