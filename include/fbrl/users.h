/* SPDX-License-Identifier: MIT */
/* users.h - named users with roles, their passwords and signing keys (docs/compliance.md).
 *
 * A lab's users live in one file, readable and writable by its owner alone (created 0600,
 * refused when its group or others may write it). A password is kept only as an Argon2id
 * hash (libsodium crypto_pwhash_str). Each user has an Ed25519 key pair for electronic
 * signatures; its secret half is sealed (crypto_secretbox) with a key derived from the
 * password by Argon2id, so only the password unlocks it. Wrong passwords are counted: the
 * lab's limit of tries (five unless set) locks the account for a time. The same file
 * holds the lab's settings (tries, lock time, idle sign-out, whether Drafts may run).
 *
 * The table is caller storage; nothing is allocated by this module (libsodium's Argon2id
 * takes its working memory itself, as it must). The file goes through the store of
 * src/audit_store.h. */
#ifndef FBRL_USERS_H
#define FBRL_USERS_H

#include "fbrl/export.h"

#include <stddef.h>
#include <stdint.h>
#include "fbrl/audit.h"
#include "fbrl/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FBRL_USERS_MAX 64
#define FBRL_USERS_PWHASH_MAX 128 /* crypto_pwhash_STRBYTES */
#define FBRL_USERS_PASSWORD_MIN 8
#define FBRL_USERS_PASSWORD_MAX 128
#define FBRL_USERS_OLD_KEYS 128 /* public keys replaced by resets, kept to check old signatures */
#define FBRL_USERS_SEALED_SIZE (FBRL_AUDIT_SK_SIZE + 16) /* the secret key and its MAC */

typedef enum fbrl_role {
    FBRL_ROLE_OPERATOR = 0,  /* runs Released methods */
    FBRL_ROLE_DEVELOPER,     /* method developer: also teaches, composes, runs Drafts, submits for review */
    FBRL_ROLE_PROGRAMMER,    /* also the Forth line */
    FBRL_ROLE_REVIEWER,      /* signs releases and run reviews */
    FBRL_ROLE_ADMINISTRATOR, /* users, settings, the chain's recovery */
    FBRL_ROLE_COUNT
} fbrl_role;

typedef enum fbrl_right {
    FBRL_RIGHT_RUN = 0,     /* run a Released method */
    FBRL_RIGHT_RUN_DRAFT,   /* run a Draft (when the lab allows Drafts) */
    FBRL_RIGHT_TEACH,       /* teach places, change the work cell */
    FBRL_RIGHT_COMPOSE,     /* compose and submit methods for review */
    FBRL_RIGHT_FORTH,       /* the Forth line */
    FBRL_RIGHT_RELEASE,     /* sign a release ("approved for use"), retire */
    FBRL_RIGHT_REVIEW_RUN,  /* sign a run ("run reviewed") */
    FBRL_RIGHT_USERS,       /* add, disable, reset users; change settings */
    FBRL_RIGHT_RECOVER,     /* recover a broken chain */
    FBRL_RIGHT_COUNT
} fbrl_right;

typedef struct fbrl_user {
    char name[FBRL_AUDIT_NAME_MAX];
    fbrl_role role;
    int disabled;
    unsigned failures;      /* wrong passwords since the last right one */
    int64_t locked_until;   /* UTC ms; 0: not locked */
    char pwhash[FBRL_USERS_PWHASH_MAX];
    unsigned char pk[FBRL_AUDIT_PK_SIZE];
    unsigned char salt[16]; /* crypto_pwhash_SALTBYTES */
    unsigned char nonce[24]; /* crypto_secretbox_NONCEBYTES */
    unsigned char sealed[FBRL_USERS_SEALED_SIZE];
    unsigned long long kdf_ops; /* the sealing key's Argon2id cost */
    unsigned long kdf_mem;
} fbrl_user;

typedef struct fbrl_users {
    size_t n;
    fbrl_user user[FBRL_USERS_MAX];
    /* the lab's settings */
    unsigned max_tries;       /* wrong passwords that lock an account (5) */
    long lock_s;              /* how long it stays locked (900 s) */
    long idle_s;              /* a session idle this long signs out (600 s) */
    int allow_drafts;         /* developers may run Drafts (0) */
    unsigned long long kdf_ops; /* Argon2id cost for new passwords (libsodium's interactive) */
    unsigned long kdf_mem;
    size_t nold;              /* public keys a reset replaced: old signatures stay checkable */
    fbrl_audit_key old[FBRL_USERS_OLD_KEYS];
    unsigned long bad_line;   /* the file's line a load refused (0: none) */
    char line[1024];
} fbrl_users;

/* An empty table with the default settings. */
FBRL_API void fbrl_users_init(fbrl_users *u);
/* Read the users file. FBRL_EPERM if its group or others may write it (nothing is read),
 * FBRL_ENOENT if there is none, FBRL_EFORMAT for a line that is not one (u->bad_line). */
FBRL_API fbrl_status fbrl_users_load(fbrl_users *u, const char *path);
/* Write it atomically, owner-only (0600). */
FBRL_API fbrl_status fbrl_users_save(fbrl_users *u, const char *path);

/* The user of that name, or NULL. */
FBRL_API const fbrl_user *fbrl_users_find(const fbrl_users *u, const char *name);
/* Add a user: FBRL_ENAME (name), FBRL_ERANGE (password shorter than
 * FBRL_USERS_PASSWORD_MIN or longer than _MAX, or the role), FBRL_ESTATE (the name
 * exists), FBRL_EFULL. Makes the password's hash and a new key pair sealed by it. */
FBRL_API fbrl_status fbrl_users_add(fbrl_users *u, const char *name, fbrl_role role, const char *password);
/* Sign in: FBRL_OK; FBRL_EAUTH for an unknown name or a wrong password (counted: the
 * lab's max_tries-th locks the account for lock_s); FBRL_ELOCKED while locked or when
 * disabled (the password is not even tried). now: UTC ms. Save the table afterwards: the
 * count must outlive the program. */
FBRL_API fbrl_status fbrl_users_login(fbrl_users *u, const char *name, const char *password, int64_t now);
/* The user's signing key, unlocked by the password (counted and locked as a sign-in):
 * sk[FBRL_AUDIT_SK_SIZE], pk[FBRL_AUDIT_PK_SIZE]. Wipe sk after use (fbrl_users_wipe). */
FBRL_API fbrl_status fbrl_users_unlock(fbrl_users *u, const char *name, const char *password, int64_t now,
                                       unsigned char *sk, unsigned char *pk);
/* Disable (1) or enable (0) a user; FBRL_ENOENT. A disabled user cannot sign in or sign. */
FBRL_API fbrl_status fbrl_users_disable(fbrl_users *u, const char *name, int disabled);
/* A new password (and so a new key pair; the old public key is kept for old signatures);
 * clears the count and the lock. FBRL_EFULL when no more old keys can be kept. */
FBRL_API fbrl_status fbrl_users_reset(fbrl_users *u, const char *name, const char *password);
FBRL_API fbrl_status fbrl_users_set_role(fbrl_users *u, const char *name, fbrl_role role);
/* Change a setting: "max_tries", "lock_s", "idle_s", "allow_drafts", "kdf_ops",
 * "kdf_mem". FBRL_ENOENT (no such setting), FBRL_ERANGE. */
FBRL_API fbrl_status fbrl_users_set(fbrl_users *u, const char *key, long long value);
/* Active administrators (set-up makes the first). */
FBRL_API size_t fbrl_users_admins(const fbrl_users *u);

/* May a role do that? */
FBRL_API int fbrl_users_may(fbrl_role role, fbrl_right right);
/* "operator", "developer", "programmer", "reviewer", "administrator"; NULL if none. */
FBRL_API const char *fbrl_users_role_name(fbrl_role role);
/* The role named (those names; "method-developer" too); FBRL_ENOENT. */
FBRL_API fbrl_status fbrl_users_role_parse(const char *text, fbrl_role *role);
/* The users' public keys for a verifier (fbrl_audit_verify_init), the current ones and
 * those resets replaced: up to cap, *n of them. */
FBRL_API fbrl_status fbrl_users_keys(const fbrl_users *u, fbrl_audit_key *out, size_t cap, size_t *n);
/* Overwrite n bytes (a password, a secret key) so the compiler keeps the writes. */
FBRL_API void fbrl_users_wipe(void *p, size_t n);

#ifdef __cplusplus
}
#endif
#endif
