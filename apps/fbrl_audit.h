/* SPDX-License-Identifier: MIT */
/* fbrl_audit.h - fbrl-audit's parts: verifying (fbrl_audit.c), the review report
 * (audit_report.c), the replay against fbrlsim (audit_replay.c). */
#ifndef FBRL_APPS_FBRL_AUDIT_H
#define FBRL_APPS_FBRL_AUDIT_H

#include <stddef.h>
#include <stdio.h>

#include "fbrl/audit.h"

enum { AUDIT_EXIT_OK = 0, AUDIT_EXIT_BROKEN = 1, AUDIT_EXIT_USAGE = 2, AUDIT_EXIT_OPEN = 3 };

/* Trusted public keys: from a keys file (name role hex per line), the lab's users file,
 * or (none given) the chain's own user records. */
typedef struct audit_keys {
    fbrl_audit_key *k;
    size_t n, cap;
    const char *source; /* said in the output */
} audit_keys;

/* The whole file in memory with its lines (the programs may allocate). NULL with errno. */
typedef struct audit_text {
    char *buf;
    size_t len, nlines;
    size_t *start; /* line i (0..) starts at buf + start[i]; start[nlines] = len */
} audit_text;

int audit_text_read(const char *path, audit_text *t);
void audit_text_free(audit_text *t);
/* Verify path into v with the keys, keeping every record's hash (hashes: freed by the
 * caller). The library's status. */
fbrl_status audit_verify(const char *path, const audit_keys *keys, fbrl_audit_verifier *v,
                         unsigned char (**hashes)[FBRL_AUDIT_HASH_SIZE]);

int audit_report(const char *path, const char *out, const audit_keys *keys);
int audit_replay(const char *path, long run, const char *fbrlsim, int home, int keep);

#endif
