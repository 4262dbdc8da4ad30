/* SPDX-License-Identifier: MIT */
/* fbrl_users.c - fbrl-users: the lab's users (docs/compliance.md "Users").
 *
 *   fbrl-users [--lab DIR] setup NAME              the users file and its first administrator
 *   fbrl-users [--lab DIR] --as ADMIN add NAME ROLE
 *   fbrl-users [--lab DIR] --as ADMIN disable|enable|reset NAME
 *   fbrl-users [--lab DIR] --as ADMIN role NAME ROLE
 *   fbrl-users [--lab DIR] --as ADMIN set SETTING VALUE
 *   fbrl-users [--lab DIR] list | keys
 *
 * Passwords are typed without echo (or read one a line from standard input when it is not
 * a terminal: the administrator's first, then the user's). Every change, and every
 * sign-in attempt, is a record in the lab's audit trail. */
#include <errno.h>
#include <getopt.h>
#include <sys/stat.h>
#include <unistd.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fbrl/version.h"
#include "lab.h"

enum { EXIT_REFUSED = 1, EXIT_USAGE = 2 };

static lab L;

static void usage(FILE *f)
{
    fprintf(f, "usage: fbrl-users [--lab DIR] [--users FILE] [--chain FILE] [--as ADMIN] COMMAND ...\n"
               "  setup NAME            make the users file and its first administrator\n"
               "  add NAME ROLE         a user (roles: operator developer programmer reviewer administrator)\n"
               "  disable NAME | enable NAME | reset NAME | role NAME ROLE\n"
               "  set SETTING VALUE     max_tries lock_s idle_s allow_drafts kdf_ops kdf_mem\n"
               "  list                  the users, their roles and states\n"
               "  keys                  the public keys (name role key), for fbrl-audit verify --keys\n");
}

static int fail(const char *msg)
{
    fprintf(stderr, "fbrl-users: %s\n", msg);
    return EXIT_REFUSED;
}

/* A new password, twice on a terminal. */
static int new_password(const char *name, char *pw, size_t cap)
{
    char again[FBRL_USERS_PASSWORD_MAX + 2], prompt[96];
    snprintf(prompt, sizeof prompt, "new password for %s: ", name);
    if (lab_password(prompt, pw, cap) != 0)
        return -1;
    if (isatty(0)) {
        snprintf(prompt, sizeof prompt, "again: ");
        if (lab_password(prompt, again, sizeof again) != 0 || strcmp(again, pw) != 0) {
            fbrl_users_wipe(again, sizeof again);
            fprintf(stderr, "fbrl-users: the two passwords differ\n");
            return -1;
        }
        fbrl_users_wipe(again, sizeof again);
    }
    if (strlen(pw) < FBRL_USERS_PASSWORD_MIN || strlen(pw) > FBRL_USERS_PASSWORD_MAX) {
        fprintf(stderr, "fbrl-users: a password has %d to %d characters\n", FBRL_USERS_PASSWORD_MIN,
                FBRL_USERS_PASSWORD_MAX);
        return -1;
    }
    return 0;
}

static int setup(const char *name)
{
    char pw[FBRL_USERS_PASSWORD_MAX + 2];
    fbrl_status st;
    if (lab_load_users(&L) == 0 || fbrl_users_load(&L.users, L.users_path) != FBRL_ENOENT)
        return fail("the lab has a users file already: set-up is done once");
    fbrl_users_init(&L.users);
    {   /* the lab's folder, made when missing: its owner and group only */
        char dir[LAB_PATH_MAX];
        char *slash;
        snprintf(dir, sizeof dir, "%s", L.users_path);
        slash = strrchr(dir, '/');
        if (slash && slash != dir) {
            *slash = '\0';
            if (mkdir(dir, 0750) != 0 && errno != EEXIST) {
                fprintf(stderr, "fbrl-users: %s: %s\n", dir, strerror(errno));
                return EXIT_REFUSED;
            }
        }
    }
    if (new_password(name, pw, sizeof pw) != 0)
        return EXIT_REFUSED;
    st = fbrl_users_add(&L.users, name, FBRL_ROLE_ADMINISTRATOR, pw);
    fbrl_users_wipe(pw, sizeof pw);
    if (st != FBRL_OK)
        return fail(st == FBRL_ENAME ? "a name has 1 to 31 of A-Z a-z 0-9 . _ -" : fbrl_status_str(st));
    if (lab_save_users(&L) != 0 || lab_open_chain(&L) != 0)
        return fail(L.err);
    fbrl_audit_set_user(&L.chain.a, name);
    if (lab_record_user(&L, "setup", name) != FBRL_OK)
        return fail("the set-up could not be recorded");
    printf("%s: the first administrator is %s\n", L.users_path, name);
    return 0;
}

static int list(void)
{
    char until[32];
    printf("%-20s %-14s %-9s %s\n", "name", "role", "state", "wrong passwords");
    for (size_t i = 0; i < L.users.n; i++) {
        const fbrl_user *x = &L.users.user[i];
        until[0] = '\0';
        if (x->locked_until > lab_now())
            fbrl_audit_utc_text(x->locked_until, until);
        printf("%-20s %-14s %-9s %u%s%s\n", x->name, fbrl_users_role_name(x->role),
               x->disabled ? "disabled" : until[0] ? "locked" : "active", x->failures, until[0] ? " until " : "",
               until);
    }
    printf("settings: max_tries %u, lock_s %ld, idle_s %ld, allow_drafts %d\n", L.users.max_tries, L.users.lock_s,
           L.users.idle_s, L.users.allow_drafts);
    return 0;
}

static int keys(void)
{
    size_t n;
    fbrl_users_keys(&L.users, L.keys, LAB_KEYS_MAX, &n);
    for (size_t i = 0; i < n; i++) {
        printf("%s %s ", L.keys[i].name, L.keys[i].role);
        for (int b = 0; b < FBRL_AUDIT_PK_SIZE; b++)
            printf("%02x", L.keys[i].pk[b]);
        printf("\n");
    }
    return 0;
}

/* The administrator's commands: signed in first (recorded), then the change (recorded). */
static int admin(const char *as, int argc, char **argv)
{
    const char *cmd = argv[0];
    char pw[FBRL_USERS_PASSWORD_MAX + 2], prompt[96];
    fbrl_role role;
    fbrl_status st;
    int need = strcmp(cmd, "add") == 0 || strcmp(cmd, "role") == 0 || strcmp(cmd, "set") == 0 ? 3 : 2;
    if (argc != need)
        return usage(stderr), EXIT_USAGE;
    if (as == NULL)
        return fail("an administrator signs in for that: --as NAME");
    if (lab_open_chain(&L) != 0)
        return fail(L.err);
    snprintf(prompt, sizeof prompt, "password for %s: ", as);
    if (lab_password(prompt, pw, sizeof pw) != 0)
        return fail("no password");
    st = lab_sign_in(&L, as, pw, "fbrl-users");
    fbrl_users_wipe(pw, sizeof pw);
    if (st != FBRL_OK)
        return fail(L.err);
    if (!fbrl_users_may(fbrl_users_find(&L.users, as)->role, FBRL_RIGHT_USERS))
        return fail("only an administrator changes users and settings");
    if (strcmp(cmd, "add") == 0) {
        if (fbrl_users_role_parse(argv[2], &role) != FBRL_OK)
            return fail("roles: operator developer programmer reviewer administrator");
        if (new_password(argv[1], pw, sizeof pw) != 0)
            return EXIT_REFUSED;
        st = fbrl_users_add(&L.users, argv[1], role, pw);
    } else if (strcmp(cmd, "reset") == 0) {
        if (new_password(argv[1], pw, sizeof pw) != 0)
            return EXIT_REFUSED;
        st = fbrl_users_reset(&L.users, argv[1], pw);
    } else if (strcmp(cmd, "disable") == 0 || strcmp(cmd, "enable") == 0) {
        const fbrl_user *x = fbrl_users_find(&L.users, argv[1]);
        if (x && cmd[0] == 'd' && x->role == FBRL_ROLE_ADMINISTRATOR && fbrl_users_admins(&L.users) == 1)
            return fail("that is the last active administrator");
        st = fbrl_users_disable(&L.users, argv[1], cmd[0] == 'd');
    } else if (strcmp(cmd, "role") == 0) {
        const fbrl_user *x = fbrl_users_find(&L.users, argv[1]);
        if (fbrl_users_role_parse(argv[2], &role) != FBRL_OK)
            return fail("roles: operator developer programmer reviewer administrator");
        if (x && x->role == FBRL_ROLE_ADMINISTRATOR && role != x->role && fbrl_users_admins(&L.users) == 1)
            return fail("that is the last active administrator");
        st = fbrl_users_set_role(&L.users, argv[1], role);
    } else if (strcmp(cmd, "set") == 0) {
        char *end;
        long long v = strtoll(argv[2], &end, 10);
        st = *end ? FBRL_ERANGE : fbrl_users_set(&L.users, argv[1], v);
        if (st == FBRL_OK) {
            fbrl_audit_begin(&L.chain.a, "config");
            fbrl_audit_str(&L.chain.a, "setting", argv[1]);
            fbrl_audit_str(&L.chain.a, "value", argv[2]);
            if (lab_save_users(&L) != 0)
                return fail(L.err);
            if (fbrl_audit_end(&L.chain.a) != FBRL_OK)
                return fail("the change could not be recorded");
            printf("%s: %s is %s\n", L.users_path, argv[1], argv[2]);
            return 0;
        }
    } else {
        return usage(stderr), EXIT_USAGE;
    }
    fbrl_users_wipe(pw, sizeof pw);
    if (st != FBRL_OK)
        return fail(st == FBRL_ENOENT   ? "no such user"
                    : st == FBRL_ESTATE ? "that name is taken"
                    : st == FBRL_ENAME  ? "a name has 1 to 31 of A-Z a-z 0-9 . _ -"
                    : st == FBRL_ERANGE ? "not a value that setting takes"
                                        : fbrl_status_str(st));
    if (lab_save_users(&L) != 0)
        return fail(L.err);
    if (lab_record_user(&L, cmd, argv[1]) != FBRL_OK)
        return fail("the change could not be recorded");
    printf("%s: %s %s\n", L.users_path, cmd, argv[1]);
    return 0;
}

int main(int argc, char **argv)
{
    static const struct option opts[] = {{"lab", required_argument, NULL, 'l'},
                                         {"users", required_argument, NULL, 'u'},
                                         {"chain", required_argument, NULL, 'c'},
                                         {"as", required_argument, NULL, 'a'},
                                         {"help", no_argument, NULL, 'h'},
                                         {"version", no_argument, NULL, 'V'},
                                         {NULL, 0, NULL, 0}};
    const char *dir = NULL, *users = NULL, *chain = NULL, *as = NULL;
    int c, rc;
    while ((c = getopt_long(argc, argv, "hV", opts, NULL)) != -1) {
        switch (c) {
        case 'l': dir = optarg; break;
        case 'u': users = optarg; break;
        case 'c': chain = optarg; break;
        case 'a': as = optarg; break;
        case 'h': usage(stdout); return 0;
        case 'V': printf("fbrl-users (libfbrl) %s\n", FBRL_VERSION_STRING); return 0;
        default: usage(stderr); return EXIT_USAGE;
        }
    }
    argc -= optind;
    argv += optind;
    if (argc < 1)
        return usage(stderr), EXIT_USAGE;
    if (lab_init(&L, dir, users, chain) != 0)
        return fail(L.err);
    if (strcmp(argv[0], "setup") == 0) {
        if (argc != 2)
            return usage(stderr), EXIT_USAGE;
        rc = setup(argv[1]);
    } else if (lab_load_users(&L) != 0) {
        rc = fail(L.err);
    } else if (strcmp(argv[0], "list") == 0) {
        rc = list();
    } else if (strcmp(argv[0], "keys") == 0) {
        rc = keys();
    } else {
        rc = admin(as, argc, argv);
    }
    lab_close(&L);
    return rc;
}
