/* SPDX-License-Identifier: MIT */
/* mon_audit.h - fbrlmon's audit trail: the run log written as a hash-chained audit trail
 * (the chain is the run log's sink: each JSON line the run log makes gets seq, utc, user,
 * prev and hash), a run refused when the chain is broken or its method version may not run
 * for the user, a seal at each run's end, and the console's actions recorded in the same
 * chain. docs/console.md "The run log", docs/compliance.md. */
#ifndef FBRLMON_AUDIT_H
#define FBRLMON_AUDIT_H

#include <stddef.h>

#include "fbrl/audit.h"
#include "fbrl/method.h"
#include "fbrl/release.h"
#include "fbrl/users.h"
#include "lab.h"

typedef struct mon_audit {
    char path[LAB_PATH_MAX];    /* the chain ("" = none) */
    fbrl_audit_file f;
    fbrl_audit_verifier v;
    int open, in_run;
    char user[FBRL_AUDIT_NAME_MAX]; /* who the records are by */
    lab *lab;                   /* the lab's users and settings (NULL: no lab) */
    int signed_in;              /* the user signed in with a password (the console) */
    fbrl_role role;
    fbrl_method_version mv;
    char err[2 * LAB_PATH_MAX + FBRL_AUDIT_WHERE_MAX + FBRL_RELEASE_WHY_MAX];
} mon_audit;

/* Who the records are by: a signed-in user (signed_in 1, role given) or a name only. */
void mon_audit_set_user(mon_audit *A, const char *name, int signed_in, fbrl_role role);
/* Open the chain (verified, locked against other writers). -1 with A->err. */
int mon_audit_open(mon_audit *A);
/* Seal what was written (seal 1) and close. */
void mon_audit_close(mon_audit *A, int seal);
/* A run begins: the chain opened, the method's version checked against the lab's releases
 * (source: the method file, "" unknown), a "method_run" record. -1: the trail cannot be
 * kept (broken, not a file ...), -2: the lab does not let this user run this version
 * ("method_refused" recorded); either refuses the run, A->err says why. */
int mon_audit_run_begin(mon_audit *A, const fbrl_method *m, const char *source);
/* The run ended: sealed and closed. */
void mon_audit_run_end(mon_audit *A);
/* The run log's sink (fbrl_runlog_write_fn). */
int mon_audit_sink(void *ctx, const char *s, size_t n);
/* An action that changed something ("teach", "parameter", "pause" ...): what, and the
 * detail in words (may be NULL). Written at once (the chain opened and closed around it
 * when no run holds it). -1 with A->err. */
int mon_audit_action(mon_audit *A, const char *action, const char *what, const char *detail);

#endif
