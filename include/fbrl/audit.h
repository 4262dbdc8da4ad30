/* SPDX-License-Identifier: MIT */
/* audit.h - the audit trail: one append-only chain of JSON Lines records nobody can
 * quietly edit (docs/compliance.md).
 *
 * Every record is one JSON object on one line. The chain puts its own fields around the
 * body a caller gives it (a run log record, a console action, a user change ...):
 *
 *   {"seq":7,"utc":"2026-11-25T04:29:56.123Z","user":"ann","prev":"<64 hex>",BODY,"hash":"<64 hex>"}
 *
 * seq counts from 1; prev is the hash of the record before (64 zeros for the first); hash
 * is the SHA-256 (libsodium) of the line's bytes up to the comma before "hash". An edited
 * record no longer matches its own hash; a deleted, swapped or repeated one breaks the seq
 * and prev order; a cut tail disagrees with the head file kept beside the chain
 * (FILE.head: the count and the last hash). A run ends with a seal record.
 *
 * Signatures are records too: an Ed25519 signature (libsodium crypto_sign) by the
 * signer's key over the signed record's hash, the signer, the UTC time and the meaning
 * ("approved for use", "run reviewed"). Anyone holding the public keys checks them.
 *
 * The core builds and checks records in caller storage and never allocates; the chain
 * files (append, fsync, the head file) go through the store of src/audit_store.h. */
#ifndef FBRL_AUDIT_H
#define FBRL_AUDIT_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FBRL_AUDIT_LINE_MAX 4096 /* one record, the chain's fields included */
#define FBRL_AUDIT_BODY_MAX 3584 /* the body a caller gives (a run log line fits: 1024) */
#define FBRL_AUDIT_HASH_SIZE 32
#define FBRL_AUDIT_NAME_MAX 32 /* user names: 1..31 of A-Z a-z 0-9 . _ - */
#define FBRL_AUDIT_PK_SIZE 32  /* Ed25519 public key */
#define FBRL_AUDIT_SK_SIZE 64  /* Ed25519 secret key */
#define FBRL_AUDIT_SIG_SIZE 64
#define FBRL_AUDIT_WHERE_MAX 256 /* "record K (line L): what broke" */
#define FBRL_AUDIT_PATH_MAX 1024
#define FBRL_AUDIT_ROLE_MAX 16

/* The signature meanings the tools use; any other text is allowed. */
#define FBRL_AUDIT_MEANING_RELEASE "approved for use"
#define FBRL_AUDIT_MEANING_REVIEW "run reviewed"
#define FBRL_AUDIT_MEANING_RECOVERY "chain recovery"

/* The sink: append n bytes (one whole line) durably; 0 = written, -1 = failed. */
typedef int (*fbrl_audit_write_fn)(void *ctx, const char *s, size_t n);
/* UTC: milliseconds since 1970-01-01T00:00:00Z. */
typedef int64_t (*fbrl_audit_utc_fn)(void *ctx);

/* The writer. Caller-owned; fields private. */
typedef struct fbrl_audit {
    fbrl_audit_write_fn write;
    void *write_ctx;
    fbrl_audit_utc_fn utc;
    void *utc_ctx;
    uint64_t seq;                              /* records in the chain */
    unsigned char head[FBRL_AUDIT_HASH_SIZE];  /* the last record's hash */
    uint64_t last_seal;                        /* seq of the last seal (0: none) */
    char user[FBRL_AUDIT_NAME_MAX];            /* who the next records are by */
    fbrl_status failed;                        /* the first failed write: the writer then stops */
    size_t blen;                               /* the body being built */
    int building, overflow;
    char body[FBRL_AUDIT_BODY_MAX + 2];
    char line[FBRL_AUDIT_LINE_MAX + 2];
} fbrl_audit;

/* Start a writer that continues a chain of seq records whose last hash is head (seq 0 and
 * head NULL: a new chain). The caller has verified the chain (fbrl_audit_file_open does).
 * utc may be NULL (times then read 1970). FBRL_EINVAL for NULLs. */
FBRL_API fbrl_status fbrl_audit_init(fbrl_audit *a, fbrl_audit_write_fn write, void *write_ctx,
                                     fbrl_audit_utc_fn utc, void *utc_ctx, uint64_t seq,
                                     const unsigned char *head);

/* Who the following records are by (a signed-in user's name, or a program's: "fbrlmon").
 * FBRL_ENAME for an empty name, one too long or with other characters. */
FBRL_API fbrl_status fbrl_audit_set_user(fbrl_audit *a, const char *user);

/* Append one record whose body is the JSON object json (its braces, a trailing newline
 * allowed): a run log line goes in as it is. FBRL_ESYNTAX if json is not one object,
 * FBRL_ENOSPC if the record would pass FBRL_AUDIT_LINE_MAX, FBRL_EIO if the sink failed
 * (then every later append fails: a chain with a hole is not continued). */
FBRL_API fbrl_status fbrl_audit_append(fbrl_audit *a, const char *json, size_t len);

/* Build a record field by field (a sketch of lauxlib's buffer): begin with its "type",
 * add fields, end appends it. Texts are JSON-escaped; raw adds a JSON value as it is
 * (the caller's array or object). An overflow shows at end (FBRL_ENOSPC, nothing written). */
FBRL_API fbrl_status fbrl_audit_begin(fbrl_audit *a, const char *type);
FBRL_API void fbrl_audit_str(fbrl_audit *a, const char *key, const char *value);
FBRL_API void fbrl_audit_num(fbrl_audit *a, const char *key, long value);
FBRL_API void fbrl_audit_raw(fbrl_audit *a, const char *key, const char *json);
FBRL_API fbrl_status fbrl_audit_end(fbrl_audit *a);

/* Seal: {"type":"seal","first":F,"records":N} closes what was written since the last
 * seal (a run, a user's session). */
FBRL_API fbrl_status fbrl_audit_seal(fbrl_audit *a);

/* Sign record number seq, whose hash is hash, as the current user with the meaning given,
 * with the Ed25519 key pair sk/pk (fbrl_users_unlock gives it):
 * {"type":"signature","signs":SEQ,"signed_hash":"..","meaning":"..","key":"<pk>","sig":".."}.
 * The signature covers fbrl_audit_sig_message's text. */
FBRL_API fbrl_status fbrl_audit_sign(fbrl_audit *a, uint64_t seq, const unsigned char *hash,
                                     const char *meaning, const unsigned char *sk, const unsigned char *pk);

/* The last record's number and hash (what a signature of it needs). */
FBRL_API uint64_t fbrl_audit_head(const fbrl_audit *a, unsigned char *hash);

/* The text a signature covers: "fbrl-signature 1\n<signed hash hex>\n<seq>\n<signer>\n<utc>\n
 * <meaning>\n" into buf; its length, or 0 if cap is too small. */
FBRL_API size_t fbrl_audit_sig_message(char *buf, size_t cap, const unsigned char *hash, uint64_t seq,
                                       const char *signer, const char *utc, const char *meaning);

/* UTC milliseconds as "YYYY-MM-DDTHH:MM:SS.mmmZ" (25 bytes with the NUL). */
FBRL_API void fbrl_audit_utc_text(int64_t ms, char *buf /* [32] */);

/* ---- reading records ---- */

/* A top-level field of the record (or any flat JSON object) line[0..len): the value's
 * text as it stands (a string with its quotes, a number, an array ...). FBRL_ENOENT if
 * the object has no such key, FBRL_ESYNTAX if it is not an object. */
FBRL_API fbrl_status fbrl_audit_field(const char *line, size_t len, const char *key, const char **value,
                                      size_t *vlen);
/* A string field, unescaped into buf (cut to cap-1 bytes, then FBRL_ENOSPC); FBRL_ETYPE if
 * the value is not a string. */
FBRL_API fbrl_status fbrl_audit_field_str(const char *line, size_t len, const char *key, char *buf, size_t cap);
/* A whole-number field. */
FBRL_API fbrl_status fbrl_audit_field_num(const char *line, size_t len, const char *key, long long *value);

/* ---- verifying a chain ---- */

/* A public key the verifier trusts for a user (from a keys file, or from the chain's user
 * records): role is the user's role when the key was recorded. */
typedef struct fbrl_audit_key {
    char name[FBRL_AUDIT_NAME_MAX];
    char role[FBRL_AUDIT_ROLE_MAX];
    unsigned char pk[FBRL_AUDIT_PK_SIZE];
} fbrl_audit_key;

/* The verifier: feed it the file's bytes in any pieces; it checks every record as its line
 * ends. Caller-owned; fields private but for the results named below. */
typedef struct fbrl_audit_verifier {
    /* results */
    uint64_t records;       /* records checked and intact */
    unsigned long line;     /* lines seen */
    unsigned long signatures, recoveries;
    int sealed;             /* the last record is a seal */
    uint64_t last_seal;     /* the last seal's seq (0: none) */
    fbrl_status broken;     /* FBRL_OK, or FBRL_ECHECKSUM at the first break not recovered */
    char where[FBRL_AUDIT_WHERE_MAX]; /* "record K (line L): ..." */
    char recovered[FBRL_AUDIT_WHERE_MAX]; /* the last break an administrator recovered */
    /* state */
    uint64_t seq;
    unsigned char head[FBRL_AUDIT_HASH_SIZE];
    unsigned long broken_line, pending_recovery;
    uint64_t pending_seq;
    unsigned char pending_hash[FBRL_AUDIT_HASH_SIZE];
    uint64_t file_hash[16];  /* the running SHA-256 of every byte (a recovery's prev) */
    uint64_t line_hash[16];  /* the same at the start of the current line */
    fbrl_audit_key *keys;
    size_t nkeys, key_cap;
    int keys_from_chain;
    unsigned char (*hashes)[FBRL_AUDIT_HASH_SIZE];
    size_t hash_cap;
    unsigned long unchecked; /* signatures of records older than hash_cap could hold */
    size_t len;
    int overlong;
    char buf[FBRL_AUDIT_LINE_MAX + 2];
} fbrl_audit_verifier;

/* Start a verifier. keys[0..nkeys) are trusted public keys (a keys file); with nkeys 0 the
 * keys the chain's own "user" records name are used, up to key_cap. hashes[hash_cap]
 * holds each record's hash so a signature of an older record can be checked (NULL/0: only
 * the record just before a signature). FBRL_EINVAL for NULLs. */
FBRL_API fbrl_status fbrl_audit_verify_init(fbrl_audit_verifier *v, fbrl_audit_key *keys, size_t nkeys,
                                            size_t key_cap, unsigned char (*hashes)[FBRL_AUDIT_HASH_SIZE],
                                            size_t hash_cap);
/* The next n bytes of the chain. FBRL_OK while intact; FBRL_ECHECKSUM once broken (v->where
 * says where; later bytes are still read: an administrator's recovery may follow). */
FBRL_API fbrl_status fbrl_audit_verify_bytes(fbrl_audit_verifier *v, const char *s, size_t n);
/* The end of the chain, with the head file's count and hash (head NULL: no head file to
 * compare). A last line without its newline is a cut write. FBRL_OK: intact. */
FBRL_API fbrl_status fbrl_audit_verify_end(fbrl_audit_verifier *v, uint64_t head_seq, const unsigned char *head);
/* The hash of record seq (1..), if the verifier kept it. */
FBRL_API fbrl_status fbrl_audit_verify_hash(const fbrl_audit_verifier *v, uint64_t seq, unsigned char *hash);

/* ---- chain files (the store: src/audit_store.h) ---- */

/* A chain file open for appending: its writer, after a full verification. */
typedef struct fbrl_audit_file {
    fbrl_audit a;
    void *handle, *head_handle;
    char path[FBRL_AUDIT_PATH_MAX];
    char where[FBRL_AUDIT_WHERE_MAX]; /* why it was refused */
    uint64_t head_seq;
    unsigned char head[FBRL_AUDIT_HASH_SIZE];
} fbrl_audit_file;

/* Open (or create) the chain at path and its head file path".head", verify the chain
 * with v (initialised by the caller: the keys it trusts) and start a writer after its last
 * record. A broken
 * chain is refused: FBRL_ECHECKSUM, f->where says where it broke; nothing is written. The
 * file is locked against other writers until closed (FBRL_EBUSY while another has it).
 * Each record is appended and synced (fdatasync), then the head file is rewritten in place
 * and synced. */
FBRL_API fbrl_status fbrl_audit_file_open(fbrl_audit_file *f, const char *path, fbrl_audit_verifier *v);
/* Open a broken chain only to append an administrator's recovery: the recovery record
 * (what broke, the reason) signed by the administrator (sk/pk) with the meaning "chain
 * recovery"; the chain then continues after it. FBRL_ESTATE if the chain is not broken. */
FBRL_API fbrl_status fbrl_audit_file_recover(fbrl_audit_file *f, const char *path, fbrl_audit_verifier *v,
                                             const char *admin, const char *reason, const unsigned char *sk,
                                             const unsigned char *pk);
FBRL_API fbrl_status fbrl_audit_file_close(fbrl_audit_file *f);
/* Verify the chain at path and its head file with v (initialised by the caller, keys and
 * hash storage as it wants). FBRL_OK intact; FBRL_ECHECKSUM broken (v->where); FBRL_ENOENT,
 * FBRL_EIO as the store says. */
FBRL_API fbrl_status fbrl_audit_file_verify(const char *path, fbrl_audit_verifier *v);
/* The system clock's UTC (fbrl_audit_utc_fn). */
FBRL_API int64_t fbrl_audit_utc_now(void *ctx);

#ifdef __cplusplus
}
#endif
#endif
