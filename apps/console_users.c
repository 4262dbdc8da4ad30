/* SPDX-License-Identifier: MIT */
/* console_users.c - sign-in, the role's level, idle sign-out and recorded actions for the
 * operator console. */
#include "console_users.h"

#include <stdio.h>
#include <string.h>

static struct {
    mon_runlog *log;
    int signed_in;
    fbrl_role role;
    uint64_t last_key_us;
} cu;

void cu_start(mon_runlog *log)
{
    memset(&cu, 0, sizeof cu);
    cu.log = log;
    cu.last_key_us = mon_runlog_now_us(NULL);
}

int cu_lab(void) { return cu.log != NULL && cu.log->audit.lab != NULL; }

int cu_signed_in(void) { return cu.signed_in; }

void cu_touch(void) { cu.last_key_us = mon_runlog_now_us(NULL); }

const char *cu_role(void) { return cu.signed_in ? fbrl_users_role_name(cu.role) : "-"; }

int cu_level_max(void)
{
    if (!cu.signed_in)
        return 0;
    return cu.role == FBRL_ROLE_PROGRAMMER ? 2 : cu.role == FBRL_ROLE_DEVELOPER ? 1 : 0;
}

/* The sign-in goes into the chain the runs go to: no record, no sign-in. */
int cu_sign_in(const char *name, char *password, char *msg, size_t cap)
{
    lab *L = cu.log->audit.lab;
    mon_audit *A = &cu.log->audit;
    const fbrl_user *x;
    char until[32] = "";
    fbrl_status st;
    if (A->path[0] == '\0')
        snprintf(A->path, sizeof A->path, "%s", cu.log->path);
    if (mon_audit_open(A) != 0) {
        fbrl_users_wipe(password, strlen(password));
        snprintf(msg, cap, "%s", A->err);
        return -1;
    }
    st = fbrl_users_login(&L->users, name, password, lab_now());
    fbrl_users_wipe(password, strlen(password));
    x = fbrl_users_find(&L->users, name);
    if (x && x->locked_until > lab_now())
        fbrl_audit_utc_text(x->locked_until, until);
    if (fbrl_audit_set_user(&A->f.a, name) != FBRL_OK)
        fbrl_audit_set_user(&A->f.a, "-");
    fbrl_audit_begin(&A->f.a, "login");
    fbrl_audit_str(&A->f.a, "purpose", "console");
    fbrl_audit_str(&A->f.a, "name", name);
    fbrl_audit_str(&A->f.a, "outcome", st == FBRL_OK       ? "accepted"
                                       : x == NULL         ? "unknown user"
                                       : x->disabled       ? "disabled"
                                       : st == FBRL_ELOCKED ? "locked"
                                                            : "wrong password");
    if (x)
        fbrl_audit_num(&A->f.a, "failures", (long)x->failures);
    if (until[0])
        fbrl_audit_str(&A->f.a, "locked_until", until);
    if (fbrl_audit_end(&A->f.a) != FBRL_OK && st == FBRL_OK)
        st = FBRL_EIO;
    mon_audit_close(A, 0);
    if (lab_save_users(L) != 0 && st == FBRL_OK)
        st = FBRL_EIO;
    if (st == FBRL_EIO) {
        snprintf(msg, cap, "the sign-in could not be recorded: %s", L->err);
        return -1;
    }
    if (st != FBRL_OK) {
        if (x && !x->disabled && until[0])
            snprintf(msg, cap, "%s is locked until %s (too many wrong passwords)", name, until);
        else if (x && x->disabled)
            snprintf(msg, cap, "%s is disabled", name);
        else
            snprintf(msg, cap, "name or password not accepted");
        return -1;
    }
    cu.signed_in = 1;
    cu.role = x->role;
    snprintf(cu.log->operator_id, sizeof cu.log->operator_id, "%s", name);
    mon_audit_set_user(A, name, 1, x->role);
    cu_touch();
    snprintf(msg, cap, "signed in: %s (%s)", name, fbrl_users_role_name(x->role));
    return 0;
}

void cu_sign_out(const char *reason)
{
    if (!cu.signed_in)
        return;
    cu_action("logout", cu.log->operator_id, reason);
    cu.signed_in = 0;
    cu.log->operator_id[0] = '\0';
    mon_audit_set_user(&cu.log->audit, "-", 0, FBRL_ROLE_OPERATOR);
}

int cu_idle(int running)
{
    char why[64];
    long idle_s;
    if (!cu_lab() || !cu.signed_in || running)
        return 0;
    idle_s = cu.log->audit.lab->users.idle_s;
    if (mon_runlog_now_us(NULL) - cu.last_key_us < (uint64_t)idle_s * 1000000u)
        return 0;
    snprintf(why, sizeof why, "idle for %ld s", idle_s);
    cu_sign_out(why);
    return 1;
}

void cu_action(const char *action, const char *what, const char *detail)
{
    mon_audit *A = &cu.log->audit;
    if (A->path[0] == '\0')
        snprintf(A->path, sizeof A->path, "%s", cu.log->path);
    if (A->path[0] == '\0')
        return; /* no audit trail kept */
    if (!A->user[0] || (!cu.signed_in && !cu_lab()))
        mon_audit_set_user(A, cu.log->operator_id, 0, FBRL_ROLE_OPERATOR);
    mon_audit_action(A, action, what, detail);
}

void cu_end(void)
{
    mon_audit *A = &cu.log->audit;
    cu_sign_out("the console closed");
    mon_audit_set_user(A, "fbrlmon", 0, FBRL_ROLE_OPERATOR); /* the program closes the session */
    if (A->path[0] && mon_audit_open(A) == 0)
        mon_audit_close(A, 1); /* the session's seal */
}
