/* SPDX-License-Identifier: MIT */
/* mon_audit.c - fbrlmon's audit trail: the run log's sink, the release check at a run's
 * start, seals, the console's actions. */
#include "mon_audit.h"

#include <stdio.h>
#include <string.h>

void mon_audit_set_user(mon_audit *A, const char *name, int signed_in, fbrl_role role)
{
    snprintf(A->user, sizeof A->user, "%s", name && name[0] ? name : "-");
    A->signed_in = signed_in;
    A->role = role;
    if (A->open && fbrl_audit_set_user(&A->f.a, A->user) != FBRL_OK)
        fbrl_audit_set_user(&A->f.a, "-");
}

int mon_audit_open(mon_audit *A)
{
    fbrl_status st;
    size_t n = 0;
    if (A->open)
        return 0;
    if (A->path[0] == '\0') {
        snprintf(A->err, sizeof A->err, "no audit trail");
        return -1;
    }
    if (A->lab != NULL) /* the users' keys: the chain is checked against the users file */
        fbrl_users_keys(&A->lab->users, A->lab->keys, LAB_KEYS_MAX, &n);
    fbrl_audit_verify_init(&A->v, A->lab ? A->lab->keys : NULL, n, A->lab ? LAB_KEYS_MAX : 0, NULL, 0);
    st = fbrl_audit_file_open(&A->f, A->path, &A->v);
    if (st == FBRL_ECHECKSUM)
        snprintf(A->err, sizeof A->err,
                 "%s: %s: the audit trail is broken: nothing is written to it (and no run starts) until an "
                 "administrator recovers it (fbrl-audit recover)",
                 A->path, A->f.where);
    else if (st == FBRL_EBUSY)
        snprintf(A->err, sizeof A->err, "%s: another program is writing the audit trail", A->path);
    else if (st != FBRL_OK)
        snprintf(A->err, sizeof A->err, "%s: the audit trail cannot be opened: %s", A->path, fbrl_status_str(st));
    if (st != FBRL_OK)
        return -1;
    A->open = 1;
    if (fbrl_audit_set_user(&A->f.a, A->user[0] ? A->user : "-") != FBRL_OK)
        fbrl_audit_set_user(&A->f.a, "-");
    return 0;
}

void mon_audit_close(mon_audit *A, int seal)
{
    if (!A->open)
        return;
    if (seal && fbrl_audit_head(&A->f.a, NULL) > A->f.a.last_seal)
        fbrl_audit_seal(&A->f.a);
    fbrl_audit_file_close(&A->f);
    A->open = 0;
}

int mon_audit_sink(void *ctx, const char *s, size_t n)
{
    mon_audit *A = ctx;
    return A->open && fbrl_audit_append(&A->f.a, s, n) == FBRL_OK ? 0 : -1;
}

int mon_audit_run_begin(mon_audit *A, const fbrl_method *m, const char *source)
{
    const char *state = "unchecked (no lab)";
    int allow = A->lab ? A->lab->users.allow_drafts : 0;
    A->err[0] = '\0';
    if (mon_audit_open(A) != 0)
        return -1; /* the trail cannot be kept: an error */
    memset(&A->mv, 0, sizeof A->mv);
    if (source && source[0] && fbrl_release_identify(&A->mv, source) != FBRL_OK) {
        snprintf(A->err, sizeof A->err, "%s", A->mv.why);
        goto refuse;
    }
    if (A->lab != NULL) {
        if (!source || !source[0]) {
            snprintf(A->err, sizeof A->err, "%s: a method run in the lab comes from a method file (the console's "
                     "library): its version is checked before it runs", m->name);
            goto refuse;
        }
        if (!A->signed_in) {
            snprintf(A->err, sizeof A->err, "%s: sign in first: in the lab only a signed-in user runs methods",
                     m->name);
            goto refuse;
        }
        if (fbrl_release_status(&A->mv, A->path) != FBRL_OK) {
            snprintf(A->err, sizeof A->err, "%s", A->mv.why);
            goto refuse;
        }
        if (fbrl_release_check(&A->mv, A->role, allow) != FBRL_OK) {
            snprintf(A->err, sizeof A->err, "%s", A->mv.why);
            goto refuse;
        }
        state = fbrl_release_state_name(A->mv.state);
    } else if (!source || !source[0]) {
        state = "unknown (no method file)";
    }
    fbrl_audit_begin(&A->f.a, "method_run");
    fbrl_audit_str(&A->f.a, "method", m->name);
    fbrl_audit_str(&A->f.a, "version", A->mv.nfiles ? A->mv.hex : NULL);
    fbrl_audit_str(&A->f.a, "state", state);
    fbrl_audit_num(&A->f.a, "drafts_allowed", allow);
    if (A->lab != NULL)
        fbrl_audit_str(&A->f.a, "role", fbrl_users_role_name(A->role));
    if (A->mv.why[0])
        fbrl_audit_str(&A->f.a, "note", A->mv.why);
    if (fbrl_audit_end(&A->f.a) != FBRL_OK) {
        snprintf(A->err, sizeof A->err, "%s: the run cannot be recorded", A->path);
        mon_audit_close(A, 0);
        return -1;
    }
    A->in_run = 1;
    return 0;
refuse:
    /* the refusal is a record too: who tried to run what */
    fbrl_audit_begin(&A->f.a, "method_refused");
    fbrl_audit_str(&A->f.a, "method", m->name);
    fbrl_audit_str(&A->f.a, "version", A->mv.nfiles ? A->mv.hex : NULL);
    fbrl_audit_str(&A->f.a, "reason", A->err);
    fbrl_audit_end(&A->f.a);
    mon_audit_close(A, 1);
    return -2; /* what the lab allows: a refusal, not an error */
}

void mon_audit_run_end(mon_audit *A)
{
    A->in_run = 0;
    mon_audit_close(A, 1);
}

int mon_audit_action(mon_audit *A, const char *action, const char *what, const char *detail)
{
    int was_open = A->open, rc = 0;
    if (A->path[0] == '\0')
        return 0; /* no audit trail kept */
    if (mon_audit_open(A) != 0)
        return -1;
    fbrl_audit_begin(&A->f.a, "action");
    fbrl_audit_str(&A->f.a, "action", action);
    fbrl_audit_str(&A->f.a, "what", what);
    if (detail != NULL)
        fbrl_audit_str(&A->f.a, "detail", detail);
    if (fbrl_audit_end(&A->f.a) != FBRL_OK) {
        snprintf(A->err, sizeof A->err, "%s: the %s could not be recorded", A->path, action);
        rc = -1;
    }
    if (!was_open && !A->in_run)
        mon_audit_close(A, 0); /* the session's seal comes at its end */
    return rc;
}
