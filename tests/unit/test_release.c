/* SPDX-License-Identifier: MIT */
/* test_release.c - method versions (hashes checked with libsodium over the files as
 * written here) and their states from a real chain file: Released runs, a one-character
 * edit of an included file is named, Drafts only for developers when the lab allows. */
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

#include "fbrl/release.h"

static char dir[320], chain[400];
static unsigned char pk_dev[32], sk_dev[64], pk_rev[32], sk_rev[64], pk_op[32], sk_op[64];
static fbrl_method_version mv;

static void put(const char *name, const char *text)
{
    char p[512];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static const char *TOP = "\\ top.fbrl: a method\nINCLUDE lib/cell.fbrl  \\ INCLUDE not-this.fbrl\n"
                         "( INCLUDE nor-this.fbrl ) METHOD MINI  a small one\n' NOOP STEP Nothing  does nothing\n"
                         "END-METHOD\n";
static const char *CELL = ": PLACE ;\nS\" more.fbrl\" INCLUDED\n.( INCLUDE no.fbrl )\n";
static const char *MORE = ": MORE 1 ;\nrequire more.fbrl\n";

static void setup_files(void)
{
    char p[512];
    snprintf(p, sizeof p, "%s/lib", dir);
    mkdir(p, 0755);
    put("top.fbrl", TOP);
    put("lib/cell.fbrl", CELL);
    put("lib/more.fbrl", MORE);
}

static void a_version_is_the_hash_of_its_files_and_includes(void **state)
{
    (void)state;
    char p[512];
    unsigned char h[32];
    setup_files();
    snprintf(p, sizeof p, "%s/top.fbrl", dir);
    assert_int_equal(fbrl_release_identify(&mv, p), FBRL_OK);
    assert_string_equal(mv.method, "MINI");
    assert_int_equal(mv.nfiles, 3);
    assert_string_equal(mv.file[0].name, "top.fbrl");
    assert_string_equal(mv.file[1].name, "lib/cell.fbrl");
    assert_string_equal(mv.file[2].name, "more.fbrl");
    crypto_hash_sha256(h, (const unsigned char *)CELL, strlen(CELL));
    assert_memory_equal(mv.file[1].sha256, h, 32);
    crypto_hash_sha256(h, (const unsigned char *)MORE, strlen(MORE));
    assert_memory_equal(mv.file[2].sha256, h, 32);
    char v1[65];
    strcpy(v1, mv.hex);
    /* one character of the file included from the included file: another version */
    put("lib/more.fbrl", ": MORE 2 ;\nrequire more.fbrl\n");
    assert_int_equal(fbrl_release_identify(&mv, p), FBRL_OK);
    assert_string_not_equal(mv.hex, v1);
    put("lib/more.fbrl", MORE);
    assert_int_equal(fbrl_release_identify(&mv, p), FBRL_OK);
    assert_string_equal(mv.hex, v1);
    /* a missing include is named */
    put("lib/cell.fbrl", "INCLUDE gone.fbrl\n");
    assert_int_equal(fbrl_release_identify(&mv, p), FBRL_ENOENT);
    assert_non_null(strstr(mv.why, "lib/gone.fbrl"));
    put("lib/cell.fbrl", CELL);
}

static void add_user(fbrl_audit *a, const char *name, const char *role, const unsigned char *pk)
{
    char hex[65];
    for (int i = 0; i < 32; i++)
        sprintf(hex + 2 * i, "%02x", pk[i]);
    fbrl_audit_set_user(a, "admin");
    fbrl_audit_begin(a, "user");
    fbrl_audit_str(a, "action", "add");
    fbrl_audit_str(a, "name", name);
    fbrl_audit_str(a, "role", role);
    fbrl_audit_str(a, "key", hex);
    assert_int_equal(fbrl_audit_end(a), FBRL_OK);
}

static fbrl_audit_file f;
static fbrl_audit_verifier v;
static fbrl_audit_key keys[8];

static void open_chain(void)
{
    fbrl_audit_verify_init(&v, keys, 0, 8, NULL, 0);
    assert_int_equal(fbrl_audit_file_open(&f, chain, &v), FBRL_OK);
}

static void release(const char *who, const unsigned char *sk, const unsigned char *pk, const char *meaning)
{
    unsigned char h[32];
    fbrl_audit_set_user(&f.a, who);
    assert_int_equal(fbrl_release_record(&f.a, &mv, "release"), FBRL_OK);
    uint64_t n = fbrl_audit_head(&f.a, h);
    if (meaning)
        assert_int_equal(fbrl_audit_sign(&f.a, n, h, meaning, sk, pk), FBRL_OK);
}

static void status(const char *top)
{
    char p[512];
    snprintf(p, sizeof p, "%s/%s", dir, top);
    assert_int_equal(fbrl_release_identify(&mv, p), FBRL_OK);
    assert_int_equal(fbrl_release_status(&mv, chain), FBRL_OK);
}

static void only_a_reviewers_signed_release_releases(void **state)
{
    (void)state;
    setup_files();
    snprintf(chain, sizeof chain, "%s/trail.jsonl", dir);
    status("top.fbrl"); /* no chain: a Draft */
    assert_int_equal(mv.state, FBRL_RELEASE_DRAFT);
    assert_int_equal(fbrl_release_check(&mv, FBRL_ROLE_OPERATOR, 1), FBRL_EPERM);
    assert_non_null(strstr(mv.why, "is Draft, not Released: an operator runs only Released methods"));
    assert_int_equal(fbrl_release_check(&mv, FBRL_ROLE_DEVELOPER, 0), FBRL_EPERM);
    assert_non_null(strstr(mv.why, "the lab does not allow Drafts"));
    assert_int_equal(fbrl_release_check(&mv, FBRL_ROLE_DEVELOPER, 1), FBRL_OK);

    open_chain();
    add_user(&f.a, "dev", "developer", pk_dev);
    add_user(&f.a, "rev", "reviewer", pk_rev);
    add_user(&f.a, "op", "operator", pk_op);
    fbrl_audit_set_user(&f.a, "dev");
    assert_int_equal(fbrl_release_record(&f.a, &mv, "submit"), FBRL_OK);
    /* a release nobody signed */
    release("rev", NULL, NULL, NULL);
    /* signed, but by an operator with a review's meaning */
    release("op", sk_op, pk_op, FBRL_AUDIT_MEANING_RELEASE);
    release("rev", sk_rev, pk_rev, FBRL_AUDIT_MEANING_REVIEW);
    fbrl_audit_file_close(&f);
    status("top.fbrl");
    assert_int_equal(mv.state, FBRL_RELEASE_IN_REVIEW);
    assert_string_equal(mv.state_by, "dev");
    assert_int_equal(fbrl_release_check(&mv, FBRL_ROLE_OPERATOR, 0), FBRL_EPERM);

    open_chain();
    release("rev", sk_rev, pk_rev, FBRL_AUDIT_MEANING_RELEASE);
    fbrl_audit_file_close(&f);
    status("top.fbrl");
    assert_int_equal(mv.state, FBRL_RELEASE_RELEASED);
    assert_string_equal(mv.state_by, "rev");
    assert_int_equal(fbrl_release_check(&mv, FBRL_ROLE_OPERATOR, 0), FBRL_OK);
    /* a reviewer runs nothing */
    assert_int_equal(fbrl_release_check(&mv, FBRL_ROLE_REVIEWER, 0), FBRL_EPERM);

    /* a one-character edit of the file the include includes: refused, naming it */
    put("lib/more.fbrl", ": MORE 1 ;\nrequire more.fbrl \n");
    status("top.fbrl");
    assert_int_equal(mv.state, FBRL_RELEASE_DRAFT);
    assert_true(mv.has_released);
    assert_int_equal(fbrl_release_check(&mv, FBRL_ROLE_OPERATOR, 1), FBRL_EPERM);
    char want[600];
    snprintf(want, sizeof want, "MINI: refused: more.fbrl changed since its release");
    assert_memory_equal(mv.why, want, strlen(want));
    /* a developer may try it as a Draft where the lab allows, and is told what changed */
    assert_int_equal(fbrl_release_check(&mv, FBRL_ROLE_DEVELOPER, 1), FBRL_OK);
    assert_non_null(strstr(mv.why, "runs as a Draft"));
    assert_int_equal(fbrl_release_check(&mv, FBRL_ROLE_DEVELOPER, 0), FBRL_EPERM);
    put("lib/more.fbrl", MORE);
    status("top.fbrl");
    assert_int_equal(mv.state, FBRL_RELEASE_RELEASED);

    /* retired */
    open_chain();
    fbrl_audit_set_user(&f.a, "rev");
    assert_int_equal(fbrl_release_record(&f.a, &mv, "retire"), FBRL_OK);
    fbrl_audit_file_close(&f);
    status("top.fbrl");
    assert_int_equal(mv.state, FBRL_RELEASE_RETIRED);
    assert_int_equal(fbrl_release_check(&mv, FBRL_ROLE_DEVELOPER, 1), FBRL_EPERM);
    assert_non_null(strstr(mv.why, "is Retired (by rev"));

    /* a broken chain: no state is read from it */
    FILE *fp = fopen(chain, "r+");
    fseek(fp, 20, SEEK_SET);
    fputc('x', fp);
    fclose(fp);
    char p[512];
    snprintf(p, sizeof p, "%s/top.fbrl", dir);
    fbrl_release_identify(&mv, p);
    assert_int_equal(fbrl_release_status(&mv, chain), FBRL_ECHECKSUM);
    assert_non_null(strstr(mv.why, "record 1 (line 1): changed after it was written"));
}

static int setup(void **state)
{
    (void)state;
    assert_true(sodium_init() >= 0);
    crypto_sign_keypair(pk_dev, sk_dev);
    crypto_sign_keypair(pk_rev, sk_rev);
    crypto_sign_keypair(pk_op, sk_op);
    return test_tmpdir_make(dir, sizeof dir, "release");
}

static int teardown(void **state)
{
    (void)state;
    return test_tmpdir_remove(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_version_is_the_hash_of_its_files_and_includes),
        cmocka_unit_test(only_a_reviewers_signed_release_releases),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
