/* SPDX-License-Identifier: MIT */
/* lab.h - the lab's users file and audit chain as the programs use them (fbrl-users,
 * fbrl-audit, the console): where they are, signing in with its record, passwords typed
 * without echo. docs/compliance.md describes the files. */
#ifndef FBRL_APPS_LAB_H
#define FBRL_APPS_LAB_H

#include <stddef.h>
#include <stdint.h>

#include "fbrl/audit.h"
#include "fbrl/release.h"
#include "fbrl/users.h"

#define LAB_PATH_MAX 1024
#define LAB_KEYS_MAX (FBRL_USERS_MAX + FBRL_USERS_OLD_KEYS)
#define LAB_USERS_FILE "users"
#define LAB_CHAIN_FILE "audit.jsonl"
#define LAB_BUSY_WAIT_S 10   /* how long a program waits while another writes the chain */
#define LAB_BUSY_POLL_MS 100

typedef struct lab {
    char users_path[LAB_PATH_MAX];
    char chain_path[LAB_PATH_MAX];
    fbrl_users users;
    fbrl_audit_file chain;
    int chain_open;
    uint64_t opened_at; /* records when opened: what was written since is sealed at close */
    fbrl_audit_verifier v;
    fbrl_audit_key keys[LAB_KEYS_MAX];
    size_t nkeys;
    char err[2 * LAB_PATH_MAX + FBRL_AUDIT_WHERE_MAX + 256];
} lab;

/* The lab's files: dir (or $FBRL_LAB) holds users and audit.jsonl; users_path and
 * chain_path (when not NULL) name them instead. -1 with L->err when there is no lab. */
int lab_init(lab *L, const char *dir, const char *users_path, const char *chain_path);
/* Read the users file (refused when others may write it). -1 with L->err. */
int lab_load_users(lab *L);
/* Verify the chain with the users' public keys and open it for appending, waiting up to
 * LAB_BUSY_WAIT_S while another program writes it. -1 with L->err: a broken chain names its
 * first broken record and is not written. */
int lab_open_chain(lab *L);
/* Seal what this program wrote (a session), close the chain, wipe the users table. */
void lab_close(lab *L);
/* Write the users file back (the counts of wrong passwords must outlive the program). */
int lab_save_users(lab *L);

/* A password: from the terminal without echo when there is one (prompt on stderr), else
 * one line of standard input. -1 at end of input. */
int lab_password(const char *prompt, char *buf, size_t cap);

/* Sign in (what = "sign-in", "signature" ...): checks the password, records the attempt
 * in the chain (with its outcome: a wrong password, the lock it caused, a locked or
 * disabled account) and saves the users file. The chain's user is name after a success.
 * FBRL_OK, FBRL_EAUTH, FBRL_ELOCKED; L->err says it in words. */
fbrl_status lab_sign_in(lab *L, const char *name, const char *password, const char *what);
/* The same for a signature: the key unlocked into sk/pk (wipe sk after use). */
fbrl_status lab_unlock(lab *L, const char *name, const char *password, unsigned char *sk, unsigned char *pk);
/* A "user" record of what was done to name, with its role and current public key. */
fbrl_status lab_record_user(lab *L, const char *action, const char *name);
/* UTC ms now. */
long long lab_now(void);

#endif
