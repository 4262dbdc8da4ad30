/* SPDX-License-Identifier: MIT */
/* test_users.c - users and roles: Argon2id hashes (checked with libsodium directly), the
 * lockout and its end, keys only the password unlocks, the owner-only file. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include <sodium.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "support/tmpdir.h"

#include "fbrl/users.h"

static char dir[320];
static fbrl_users u, u2;

static void path_in(char *out, const char *name) { snprintf(out, 512, "%s/%s", dir, name); }

static int contains(const void *hay, size_t n, const char *needle)
{
    size_t k = strlen(needle);
    for (size_t i = 0; i + k <= n; i++)
        if (memcmp((const char *)hay + i, needle, k) == 0)
            return 1;
    return 0;
}

static void a_password_is_kept_only_as_an_argon2id_hash(void **state)
{
    (void)state;
    fbrl_users_init(&u);
    assert_int_equal(fbrl_users_add(&u, "ann", FBRL_ROLE_OPERATOR, "correct horse"), FBRL_OK);
    const fbrl_user *x = fbrl_users_find(&u, "ann");
    assert_non_null(x);
    assert_memory_equal(x->pwhash, "$argon2id$", 10);
    assert_false(contains(&u, sizeof u, "correct horse"));
    assert_int_equal(crypto_pwhash_str_verify(x->pwhash, "correct horse", 13), 0);
    assert_int_equal(fbrl_users_login(&u, "ann", "correct horse", 1000), FBRL_OK);
    assert_int_equal(fbrl_users_login(&u, "ann", "correct hors", 1000), FBRL_EAUTH);
    assert_int_equal(fbrl_users_login(&u, "bob", "correct horse", 1000), FBRL_EAUTH);
    /* names, passwords and duplicates */
    assert_int_equal(fbrl_users_add(&u, "ann", FBRL_ROLE_OPERATOR, "another one"), FBRL_ESTATE);
    assert_int_equal(fbrl_users_add(&u, "a b", FBRL_ROLE_OPERATOR, "another one"), FBRL_ENAME);
    assert_int_equal(fbrl_users_add(&u, "bob", FBRL_ROLE_OPERATOR, "short"), FBRL_ERANGE);
    assert_int_equal(fbrl_users_add(&u, "bob", FBRL_ROLE_COUNT, "long enough"), FBRL_ERANGE);
}

static void five_wrong_tries_lock_the_account_for_a_time(void **state)
{
    (void)state;
    int64_t t = 1000000;
    fbrl_users_init(&u);
    assert_int_equal(fbrl_users_add(&u, "ann", FBRL_ROLE_OPERATOR, "correct horse"), FBRL_OK);
    for (int i = 0; i < 4; i++)
        assert_int_equal(fbrl_users_login(&u, "ann", "wrong", t), FBRL_EAUTH);
    assert_int_equal(fbrl_users_find(&u, "ann")->failures, 4);
    assert_int_equal(fbrl_users_find(&u, "ann")->locked_until, 0);
    assert_int_equal(fbrl_users_login(&u, "ann", "wrong", t), FBRL_EAUTH);
    assert_int_equal(fbrl_users_find(&u, "ann")->locked_until, t + 900 * 1000);
    /* now even the right password is refused, untried */
    assert_int_equal(fbrl_users_login(&u, "ann", "correct horse", t + 899 * 1000), FBRL_ELOCKED);
    /* after the lock time: a fresh start */
    assert_int_equal(fbrl_users_login(&u, "ann", "correct horse", t + 900 * 1000), FBRL_OK);
    assert_int_equal(fbrl_users_find(&u, "ann")->failures, 0);
    /* a right password resets the count */
    assert_int_equal(fbrl_users_login(&u, "ann", "wrong", t), FBRL_EAUTH);
    assert_int_equal(fbrl_users_login(&u, "ann", "correct horse", t), FBRL_OK);
    assert_int_equal(fbrl_users_find(&u, "ann")->failures, 0);
    /* the lab's own limit */
    assert_int_equal(fbrl_users_set(&u, "max_tries", 2), FBRL_OK);
    assert_int_equal(fbrl_users_set(&u, "lock_s", 60), FBRL_OK);
    fbrl_users_login(&u, "ann", "wrong", t);
    fbrl_users_login(&u, "ann", "wrong", t);
    assert_int_equal(fbrl_users_login(&u, "ann", "correct horse", t + 59999), FBRL_ELOCKED);
    assert_int_equal(fbrl_users_set(&u, "max_tries", 0), FBRL_ERANGE);
    assert_int_equal(fbrl_users_set(&u, "colour", 1), FBRL_ENOENT);
    /* disabled: refused without trying the password */
    assert_int_equal(fbrl_users_disable(&u, "ann", 1), FBRL_OK);
    assert_int_equal(fbrl_users_login(&u, "ann", "correct horse", t + 120000), FBRL_ELOCKED);
    assert_int_equal(fbrl_users_disable(&u, "ann", 0), FBRL_OK);
    assert_int_equal(fbrl_users_login(&u, "ann", "correct horse", t + 120000), FBRL_OK);
}

static void only_the_password_unlocks_the_signing_key(void **state)
{
    (void)state;
    unsigned char sk[64], pk[32], sig[64];
    const unsigned char msg[] = "approved for use";
    fbrl_users_init(&u);
    assert_int_equal(fbrl_users_add(&u, "rev", FBRL_ROLE_REVIEWER, "review pass"), FBRL_OK);
    const fbrl_user *x = fbrl_users_find(&u, "rev");
    assert_int_equal(fbrl_users_unlock(&u, "rev", "review pas", 0, sk, pk), FBRL_EAUTH);
    assert_int_equal(x->failures, 1);
    assert_int_equal(fbrl_users_unlock(&u, "rev", "review pass", 0, sk, pk), FBRL_OK);
    assert_memory_equal(pk, x->pk, 32);
    /* the key signs what its public half verifies (libsodium, not the module) */
    crypto_sign_detached(sig, NULL, msg, sizeof msg, sk);
    assert_int_equal(crypto_sign_verify_detached(sig, msg, sizeof msg, x->pk), 0);
    fbrl_users_wipe(sk, sizeof sk);
    /* a locked-out user cannot sign: the key stays sealed even with the right password */
    for (int i = 0; i < 5; i++)
        assert_int_equal(fbrl_users_login(&u, "rev", "nope nope", 5000), FBRL_EAUTH);
    memset(sk, 0, sizeof sk);
    assert_int_equal(fbrl_users_unlock(&u, "rev", "review pass", 6000, sk, pk), FBRL_ELOCKED);
    for (size_t i = 0; i < sizeof sk; i++)
        assert_int_equal(sk[i], 0);
    /* a reset makes a new key pair: the old signature no longer belongs to rev's key */
    unsigned char old_pk[32];
    memcpy(old_pk, x->pk, 32);
    assert_int_equal(fbrl_users_reset(&u, "rev", "new review pass"), FBRL_OK);
    assert_memory_not_equal(old_pk, x->pk, 32);
    assert_int_equal(x->locked_until, 0);
    assert_int_equal(fbrl_users_unlock(&u, "rev", "new review pass", 6000, sk, pk), FBRL_OK);
    assert_memory_equal(pk, x->pk, 32);
    fbrl_users_wipe(sk, sizeof sk);
}

static void roles_have_their_rights(void **state)
{
    (void)state;
    fbrl_role r;
    assert_true(fbrl_users_may(FBRL_ROLE_OPERATOR, FBRL_RIGHT_RUN));
    assert_false(fbrl_users_may(FBRL_ROLE_OPERATOR, FBRL_RIGHT_RUN_DRAFT));
    assert_false(fbrl_users_may(FBRL_ROLE_OPERATOR, FBRL_RIGHT_TEACH));
    assert_true(fbrl_users_may(FBRL_ROLE_DEVELOPER, FBRL_RIGHT_RUN_DRAFT));
    assert_false(fbrl_users_may(FBRL_ROLE_DEVELOPER, FBRL_RIGHT_FORTH));
    assert_true(fbrl_users_may(FBRL_ROLE_PROGRAMMER, FBRL_RIGHT_FORTH));
    assert_false(fbrl_users_may(FBRL_ROLE_PROGRAMMER, FBRL_RIGHT_RELEASE));
    assert_true(fbrl_users_may(FBRL_ROLE_REVIEWER, FBRL_RIGHT_RELEASE));
    assert_false(fbrl_users_may(FBRL_ROLE_REVIEWER, FBRL_RIGHT_RUN));
    assert_true(fbrl_users_may(FBRL_ROLE_ADMINISTRATOR, FBRL_RIGHT_USERS));
    assert_false(fbrl_users_may(FBRL_ROLE_ADMINISTRATOR, FBRL_RIGHT_RELEASE));
    assert_false(fbrl_users_may(FBRL_ROLE_COUNT, FBRL_RIGHT_RUN));
    assert_int_equal(fbrl_users_role_parse("method-developer", &r), FBRL_OK);
    assert_int_equal(r, FBRL_ROLE_DEVELOPER);
    assert_int_equal(fbrl_users_role_parse("boss", &r), FBRL_ENOENT);
    assert_string_equal(fbrl_users_role_name(FBRL_ROLE_ADMINISTRATOR), "administrator");
}

static void the_file_is_owner_only_and_refused_when_others_may_write(void **state)
{
    (void)state;
    char path[512];
    struct stat sb;
    FILE *f;
    path_in(path, "users");
    unlink(path);
    fbrl_users_init(&u);
    assert_int_equal(fbrl_users_load(&u, path), FBRL_ENOENT);
    assert_int_equal(fbrl_users_add(&u, "admin", FBRL_ROLE_ADMINISTRATOR, "admin pass"), FBRL_OK);
    assert_int_equal(fbrl_users_add(&u, "ann", FBRL_ROLE_OPERATOR, "ann's pass"), FBRL_OK);
    assert_int_equal(fbrl_users_set(&u, "allow_drafts", 1), FBRL_OK);
    fbrl_users_login(&u, "ann", "wrong", 10);
    umask(0); /* the file is owner-only whatever the umask */
    assert_int_equal(fbrl_users_save(&u, path), FBRL_OK);
    umask(022);
    assert_int_equal(stat(path, &sb), 0);
    assert_int_equal(sb.st_mode & 0777, 0600);
    assert_int_equal(fbrl_users_load(&u2, path), FBRL_OK);
    assert_int_equal(u2.n, 2);
    assert_int_equal(u2.allow_drafts, 1);
    assert_int_equal(fbrl_users_find(&u2, "ann")->failures, 1);
    assert_memory_equal(&u2.user[0], &u.user[0], sizeof u.user[0]);
    assert_memory_equal(&u2.user[1], &u.user[1], sizeof u.user[1]);
    assert_int_equal(fbrl_users_admins(&u2), 1);
    assert_int_equal(fbrl_users_login(&u2, "ann", "ann's pass", 10), FBRL_OK);
    /* others may write it: refused, nothing read */
    chmod(path, 0620);
    assert_int_equal(fbrl_users_load(&u2, path), FBRL_EPERM);
    chmod(path, 0602);
    assert_int_equal(fbrl_users_load(&u2, path), FBRL_EPERM);
    chmod(path, 0600);
    /* a damaged line is named */
    f = fopen(path, "a");
    fputs("user bob operator active 0 0 $argon2id$x zz\n", f);
    fclose(f);
    assert_int_equal(fbrl_users_load(&u2, path), FBRL_EFORMAT);
    assert_int_equal(u2.bad_line, 10);
    f = fopen(path, "w");
    fputs("user admin\n", f);
    fclose(f);
    assert_int_equal(fbrl_users_load(&u2, path), FBRL_EFORMAT);
    assert_int_equal(u2.bad_line, 1);
}

static void public_keys_go_to_a_verifier(void **state)
{
    (void)state;
    fbrl_audit_key k[4];
    size_t n;
    fbrl_users_init(&u);
    fbrl_users_add(&u, "rev", FBRL_ROLE_REVIEWER, "review pass");
    fbrl_users_add(&u, "ann", FBRL_ROLE_OPERATOR, "ann's pass");
    assert_int_equal(fbrl_users_keys(&u, k, 4, &n), FBRL_OK);
    assert_int_equal(n, 2);
    assert_string_equal(k[0].name, "rev");
    assert_string_equal(k[0].role, "reviewer");
    assert_memory_equal(k[0].pk, u.user[0].pk, 32);
    assert_int_equal(fbrl_users_keys(&u, k, 1, &n), FBRL_ENOSPC);
    /* a reset keeps the old public key, through the file too: old signatures stay checkable */
    unsigned char old[32];
    char path[512];
    memcpy(old, u.user[0].pk, 32);
    assert_int_equal(fbrl_users_reset(&u, "rev", "another review pass"), FBRL_OK);
    path_in(path, "users-keys");
    assert_int_equal(fbrl_users_save(&u, path), FBRL_OK);
    assert_int_equal(fbrl_users_load(&u2, path), FBRL_OK);
    assert_int_equal(fbrl_users_keys(&u2, k, 4, &n), FBRL_OK);
    assert_int_equal(n, 3);
    assert_string_equal(k[2].name, "rev");
    assert_memory_equal(k[2].pk, old, 32);
    assert_memory_not_equal(k[0].pk, old, 32);
}

static int setup(void **state)
{
    (void)state;
    assert_true(sodium_init() >= 0);
    return test_tmpdir_make(dir, sizeof dir, "users");
}

static int teardown(void **state)
{
    (void)state;
    return test_tmpdir_remove(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_password_is_kept_only_as_an_argon2id_hash),
        cmocka_unit_test(five_wrong_tries_lock_the_account_for_a_time),
        cmocka_unit_test(only_the_password_unlocks_the_signing_key),
        cmocka_unit_test(roles_have_their_rights),
        cmocka_unit_test(the_file_is_owner_only_and_refused_when_others_may_write),
        cmocka_unit_test(public_keys_go_to_a_verifier),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
