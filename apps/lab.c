/* SPDX-License-Identifier: MIT */
/* lab.c - the lab's users file and chain for the programs: paths, sign-in with its record,
 * passwords without echo. */
#include "lab.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

long long lab_now(void) { return (long long)fbrl_audit_utc_now(NULL); }

static int set_path(char *out, const char *given, const char *dir, const char *name)
{
    int k = given ? snprintf(out, LAB_PATH_MAX, "%s", given) : snprintf(out, LAB_PATH_MAX, "%s/%s", dir, name);
    return k < 0 || k >= LAB_PATH_MAX ? -1 : 0;
}

int lab_init(lab *L, const char *dir, const char *users_path, const char *chain_path)
{
    memset(L, 0, sizeof *L);
    if (dir == NULL)
        dir = getenv("FBRL_LAB");
    if ((dir == NULL || dir[0] == '\0') && (users_path == NULL || chain_path == NULL)) {
        snprintf(L->err, sizeof L->err, "no lab: give --lab DIR (or set FBRL_LAB) for its users and audit trail");
        return -1;
    }
    if (set_path(L->users_path, users_path, dir, LAB_USERS_FILE) != 0 ||
        set_path(L->chain_path, chain_path, dir, LAB_CHAIN_FILE) != 0) {
        snprintf(L->err, sizeof L->err, "the lab's path is too long");
        return -1;
    }
    fbrl_users_init(&L->users);
    return 0;
}

int lab_load_users(lab *L)
{
    fbrl_status st = fbrl_users_load(&L->users, L->users_path);
    if (st == FBRL_EPERM)
        snprintf(L->err, sizeof L->err, "%s: its group or others may write it: refused (chmod 600 %s)", L->users_path,
                 L->users_path);
    else if (st == FBRL_ENOENT)
        snprintf(L->err, sizeof L->err, "%s: no users file: make the first administrator with 'fbrl-users setup NAME'",
                 L->users_path);
    else if (st == FBRL_EFORMAT)
        snprintf(L->err, sizeof L->err, "%s:%lu: not a users file line", L->users_path, L->users.bad_line);
    else if (st != FBRL_OK)
        snprintf(L->err, sizeof L->err, "%s: %s", L->users_path, fbrl_status_str(st));
    return st == FBRL_OK ? 0 : -1;
}

int lab_save_users(lab *L)
{
    fbrl_status st = fbrl_users_save(&L->users, L->users_path);
    if (st != FBRL_OK)
        snprintf(L->err, sizeof L->err, "%s: not saved: %s", L->users_path, fbrl_status_str(st));
    return st == FBRL_OK ? 0 : -1;
}

/* Another program (fbrlmon, the station) holds the chain for one record, or for a run: wait
 * for it a while, as the station does (fbrl.audit.BUSY_WAIT_S), saying so once. The lock is
 * taken before the chain is verified, so a refused attempt leaves the verifier untouched. */
static fbrl_status open_waiting(fbrl_audit_file *f, const char *path, fbrl_audit_verifier *v)
{
    const struct timespec poll = {0, LAB_BUSY_POLL_MS * 1000000L};
    fbrl_status st;
    for (int waited_ms = 0; (st = fbrl_audit_file_open(f, path, v)) == FBRL_EBUSY && waited_ms < LAB_BUSY_WAIT_S * 1000;
         waited_ms += LAB_BUSY_POLL_MS) {
        if (waited_ms == 0)
            fprintf(stderr, "%s: another program is writing the audit trail; waiting up to %d s\n", path,
                    LAB_BUSY_WAIT_S);
        nanosleep(&poll, NULL);
    }
    return st;
}

int lab_open_chain(lab *L)
{
    fbrl_status st;
    if (L->chain_open)
        return 0;
    fbrl_users_keys(&L->users, L->keys, LAB_KEYS_MAX, &L->nkeys);
    /* no users yet (set-up): the chain's own user records */
    fbrl_audit_verify_init(&L->v, L->keys, L->nkeys, LAB_KEYS_MAX, NULL, 0);
    st = open_waiting(&L->chain, L->chain_path, &L->v);
    if (st == FBRL_ECHECKSUM)
        snprintf(L->err, sizeof L->err,
                 "%s: %s: the audit trail is broken; nothing is written to it until an administrator "
                 "recovers it (fbrl-audit recover)",
                 L->chain_path, L->chain.where);
    else if (st == FBRL_EBUSY)
        snprintf(L->err, sizeof L->err, "%s: another program is still writing the audit trail after %d s",
                 L->chain_path, LAB_BUSY_WAIT_S);
    else if (st != FBRL_OK)
        snprintf(L->err, sizeof L->err, "%s: %s", L->chain_path, fbrl_status_str(st));
    L->chain_open = st == FBRL_OK;
    L->opened_at = st == FBRL_OK ? fbrl_audit_head(&L->chain.a, NULL) : 0;
    return st == FBRL_OK ? 0 : -1;
}

void lab_close(lab *L)
{
    if (L->chain_open) {
        if (fbrl_audit_head(&L->chain.a, NULL) > L->opened_at && L->chain.a.user[0])
            fbrl_audit_seal(&L->chain.a);
        fbrl_audit_file_close(&L->chain);
    }
    L->chain_open = 0;
    fbrl_users_wipe(&L->users, sizeof L->users);
}

int lab_password(const char *prompt, char *buf, size_t cap)
{
    struct termios old, quiet;
    int tty = open("/dev/tty", O_RDWR | O_CLOEXEC), n = -1;
    FILE *in = stdin;
    if (tty >= 0 && isatty(STDIN_FILENO) && tcgetattr(tty, &old) == 0) {
        quiet = old;
        quiet.c_lflag &= ~(tcflag_t)ECHO;
        fprintf(stderr, "%s", prompt);
        fflush(stderr);
        tcsetattr(tty, TCSAFLUSH, &quiet);
        if (fgets(buf, (int)cap, in) != NULL)
            n = 0;
        tcsetattr(tty, TCSAFLUSH, &old);
        fprintf(stderr, "\n");
    } else if (fgets(buf, (int)cap, in) != NULL) {
        n = 0;
    }
    if (tty >= 0)
        close(tty);
    if (n == 0)
        buf[strcspn(buf, "\r\n")] = '\0';
    return n;
}

/* The chain's user for a record about an attempt: the name typed, when it is one. */
static void attempt_user(lab *L, const char *name)
{
    if (fbrl_audit_set_user(&L->chain.a, name) != FBRL_OK)
        fbrl_audit_set_user(&L->chain.a, "-");
}

static fbrl_status record_attempt(lab *L, const char *name, const char *what, fbrl_status st)
{
    const fbrl_user *x = fbrl_users_find(&L->users, name);
    char until[32] = "";
    const char *outcome = st == FBRL_OK ? "accepted"
                          : x == NULL   ? "unknown user"
                          : x->disabled ? "disabled"
                          : st == FBRL_ELOCKED ? "locked"
                                               : "wrong password";
    if (x != NULL && x->locked_until > lab_now())
        fbrl_audit_utc_text(x->locked_until, until);
    if (st == FBRL_OK)
        snprintf(L->err, sizeof L->err, "%s: %s", name, what);
    else if (st == FBRL_ELOCKED && x && !x->disabled)
        snprintf(L->err, sizeof L->err, "%s is locked until %s (too many wrong passwords)", name, until);
    else if (st == FBRL_ELOCKED)
        snprintf(L->err, sizeof L->err, "%s is disabled", name);
    else if (x && until[0])
        snprintf(L->err, sizeof L->err, "wrong password: %s is now locked until %s", name, until);
    else
        snprintf(L->err, sizeof L->err, "name or password not accepted");
    if (L->chain_open) {
        attempt_user(L, name);
        fbrl_audit_begin(&L->chain.a, "login");
        fbrl_audit_str(&L->chain.a, "purpose", what);
        fbrl_audit_str(&L->chain.a, "name", name);
        fbrl_audit_str(&L->chain.a, "outcome", outcome);
        if (x != NULL)
            fbrl_audit_num(&L->chain.a, "failures", (long)x->failures);
        if (until[0])
            fbrl_audit_str(&L->chain.a, "locked_until", until);
        if (fbrl_audit_end(&L->chain.a) != FBRL_OK) {
            snprintf(L->err, sizeof L->err, "%s: the attempt could not be recorded", L->chain_path);
            st = FBRL_EIO;
        }
    }
    if (lab_save_users(L) != 0 && st == FBRL_OK)
        st = FBRL_EIO;
    return st;
}

fbrl_status lab_sign_in(lab *L, const char *name, const char *password, const char *what)
{
    fbrl_status st = fbrl_users_login(&L->users, name, password, lab_now());
    st = record_attempt(L, name, what, st);
    if (st == FBRL_OK && L->chain_open)
        fbrl_audit_set_user(&L->chain.a, name);
    return st;
}

fbrl_status lab_unlock(lab *L, const char *name, const char *password, unsigned char *sk, unsigned char *pk)
{
    fbrl_status st = fbrl_users_unlock(&L->users, name, password, lab_now(), sk, pk);
    st = record_attempt(L, name, "signature", st);
    if (st == FBRL_OK && L->chain_open)
        fbrl_audit_set_user(&L->chain.a, name);
    return st;
}

fbrl_status lab_record_user(lab *L, const char *action, const char *name)
{
    const fbrl_user *x = fbrl_users_find(&L->users, name);
    char pk[2 * FBRL_AUDIT_PK_SIZE + 1];
    if (x == NULL || !L->chain_open)
        return FBRL_ENOENT;
    for (size_t i = 0; i < FBRL_AUDIT_PK_SIZE; i++)
        snprintf(pk + 2 * i, 3, "%02x", x->pk[i]);
    fbrl_audit_begin(&L->chain.a, "user");
    fbrl_audit_str(&L->chain.a, "action", action);
    fbrl_audit_str(&L->chain.a, "name", name);
    fbrl_audit_str(&L->chain.a, "role", fbrl_users_role_name(x->role));
    fbrl_audit_str(&L->chain.a, "state", x->disabled ? "disabled" : "active");
    fbrl_audit_str(&L->chain.a, "key", pk);
    return fbrl_audit_end(&L->chain.a);
}
