/* SPDX-License-Identifier: MIT */
/* fbrl_audit.c - fbrl-audit: check, report, replay and sign the audit trail
 * (docs/compliance.md).
 *
 *   fbrl-audit verify FILE [--keys KEYS | --lab DIR]
 *   fbrl-audit report FILE [-o OUT.html]
 *   fbrl-audit replay FILE [--run N] [--fbrlsim PATH] [--no-home]
 *   fbrl-audit sign FILE --as NAME --record K [--meaning TEXT]     (--lab DIR: the users)
 *   fbrl-audit method status|draft|submit|release|retire METHOD-FILE [--as NAME]
 *   fbrl-audit recover FILE --as ADMIN --reason TEXT
 *
 * verify prints "FILE: N records, intact, sealed" and exits 0, or names the first broken
 * record ("FILE: record K (line L): ...") and exits 1; an intact chain whose last record is
 * no seal exits 3. */
#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fbrl/version.h"
#include "fbrl_audit.h"
#include "lab.h"

static lab L;

int audit_text_read(const char *path, audit_text *t)
{
    FILE *f = fopen(path, "rb");
    size_t cap = 1 << 16, k = 0;
    memset(t, 0, sizeof *t);
    if (f == NULL)
        return -1;
    t->buf = malloc(cap + 1);
    for (size_t got; t->buf && (got = fread(t->buf + t->len, 1, cap - t->len, f)) > 0;) {
        t->len += got;
        if (t->len == cap) {
            char *b = realloc(t->buf, 2 * cap + 1);
            if (b == NULL)
                free(t->buf);
            t->buf = b;
            cap *= 2;
        }
    }
    fclose(f);
    if (t->buf == NULL)
        return -1;
    t->buf[t->len] = '\0';
    for (size_t i = 0; i < t->len; i++)
        t->nlines += t->buf[i] == '\n';
    t->nlines += t->len > 0 && t->buf[t->len - 1] != '\n';
    t->start = malloc((t->nlines + 1) * sizeof *t->start);
    if (t->start == NULL)
        return -1;
    t->start[k++] = 0;
    for (size_t i = 0; i < t->len && k <= t->nlines; i++)
        if (t->buf[i] == '\n')
            t->start[k++] = i + 1;
    t->start[t->nlines] = t->len;
    return 0;
}

void audit_text_free(audit_text *t)
{
    free(t->buf);
    free(t->start);
    memset(t, 0, sizeof *t);
}

fbrl_status audit_verify(const char *path, const audit_keys *keys, fbrl_audit_verifier *v,
                         unsigned char (**hashes)[FBRL_AUDIT_HASH_SIZE])
{
    size_t lines = 1;
    int c;
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return errno == ENOENT ? FBRL_ENOENT : FBRL_EIO;
    while ((c = getc(f)) != EOF)
        lines += c == '\n';
    fclose(f);
    *hashes = calloc(lines, FBRL_AUDIT_HASH_SIZE);
    if (*hashes == NULL)
        return FBRL_ENOMEM;
    fbrl_audit_verify_init(v, keys->k, keys->n, keys->cap, *hashes, lines);
    return fbrl_audit_file_verify(path, v);
}

/* KEYS: "name role hex" per line, '#' comments. */
static int read_keys(const char *path, audit_keys *keys)
{
    FILE *f = fopen(path, "r");
    char line[256], name[64], role[32], hex[80];
    unsigned long n = 0;
    if (f == NULL) {
        fprintf(stderr, "fbrl-audit: %s: %s\n", path, strerror(errno));
        return -1;
    }
    while (fgets(line, sizeof line, f)) {
        n++;
        if (line[0] == '#' || line[strspn(line, " \t\r\n")] == '\0')
            continue;
        if (keys->n >= keys->cap || sscanf(line, "%63s %31s %79s", name, role, hex) != 3 ||
            strlen(name) >= FBRL_AUDIT_NAME_MAX || strlen(role) >= FBRL_AUDIT_ROLE_MAX || strlen(hex) != 64) {
            fprintf(stderr, "fbrl-audit: %s:%lu: not a key line (name role key)\n", path, n);
            fclose(f);
            return -1;
        }
        fbrl_audit_key *k = &keys->k[keys->n];
        memset(k, 0, sizeof *k);
        memcpy(k->name, name, strlen(name));
        memcpy(k->role, role, strlen(role));
        for (int i = 0; i < 32; i++) {
            unsigned b;
            if (sscanf(hex + 2 * i, "%2x", &b) != 1) {
                fclose(f);
                fprintf(stderr, "fbrl-audit: %s:%lu: the key is not hex\n", path, n);
                return -1;
            }
            k->pk[i] = (unsigned char)b;
        }
        keys->n++;
    }
    fclose(f);
    return 0;
}

static int verify(const char *path, const audit_keys *keys)
{
    static fbrl_audit_verifier v;
    unsigned char (*hashes)[FBRL_AUDIT_HASH_SIZE] = NULL;
    fbrl_status st = audit_verify(path, keys, &v, &hashes);
    int rc;
    free(hashes);
    if (st == FBRL_ECHECKSUM) {
        printf("%s: %s\n", path, v.where);
        return AUDIT_EXIT_BROKEN;
    }
    if (st != FBRL_OK) {
        printf("%s: %s\n", path, st == FBRL_ENOENT ? "no such file" : fbrl_status_str(st));
        return AUDIT_EXIT_BROKEN;
    }
    if (v.sealed) {
        printf("%s: %llu records, intact, sealed\n", path, (unsigned long long)v.records);
        rc = AUDIT_EXIT_OK;
    } else {
        printf("%s: %llu records, intact, not sealed: record %llu is no seal (a run still open, or its end lost)\n",
               path, (unsigned long long)v.records, (unsigned long long)v.seq);
        rc = AUDIT_EXIT_OPEN;
    }
    printf("  %lu signature%s verified with the public keys of %s%s\n", v.signatures, v.signatures == 1 ? "" : "s",
           keys->n ? keys->source : "the chain's user records", v.unchecked ? " (some only on their own hash)" : "");
    if (v.recoveries)
        printf("  %lu recorded recover%s; the last: %s\n", v.recoveries, v.recoveries == 1 ? "y" : "ies", v.recovered);
    return rc;
}

/* The hash of record k: a verification that keeps them all. */
static int record_hash(const char *path, uint64_t k, unsigned char *h)
{
    static fbrl_audit_verifier v;
    unsigned char (*hashes)[FBRL_AUDIT_HASH_SIZE] = NULL;
    audit_keys none = {L.keys, 0, LAB_KEYS_MAX, ""};
    fbrl_users_keys(&L.users, L.keys, LAB_KEYS_MAX, &none.n);
    fbrl_status st = audit_verify(path, &none, &v, &hashes);
    if (st == FBRL_OK)
        st = fbrl_audit_verify_hash(&v, k, h);
    free(hashes);
    return st == FBRL_OK ? 0 : -1;
}

static int refuse(const char *msg)
{
    fprintf(stderr, "fbrl-audit: %s\n", msg);
    return AUDIT_EXIT_BROKEN;
}

static int ask_password(const char *who, char *pw, size_t cap)
{
    char prompt[80];
    snprintf(prompt, sizeof prompt, "password for %s: ", who);
    return lab_password(prompt, pw, cap);
}

static int sign(const char *as, long long record, const char *meaning)
{
    unsigned char sk[FBRL_AUDIT_SK_SIZE], pk[FBRL_AUDIT_PK_SIZE], h[FBRL_AUDIT_HASH_SIZE];
    char pw[FBRL_USERS_PASSWORD_MAX + 2];
    fbrl_status st;
    fbrl_right right = strcmp(meaning, FBRL_AUDIT_MEANING_RELEASE) == 0 ? FBRL_RIGHT_RELEASE : FBRL_RIGHT_REVIEW_RUN;
    if (as == NULL || record < 1)
        return refuse("sign needs --as NAME and --record K");
    if (lab_load_users(&L) != 0 || lab_open_chain(&L) != 0)
        return refuse(L.err);
    if ((uint64_t)record > fbrl_audit_head(&L.chain.a, NULL) || record_hash(L.chain_path, (uint64_t)record, h) != 0)
        return refuse("no such record in the chain");
    if (ask_password(as, pw, sizeof pw) != 0)
        return refuse("no password");
    st = lab_unlock(&L, as, pw, sk, pk);
    fbrl_users_wipe(pw, sizeof pw);
    if (st != FBRL_OK)
        return refuse(L.err);
    if (!fbrl_users_may(fbrl_users_find(&L.users, as)->role, right)) {
        fbrl_users_wipe(sk, sizeof sk);
        return refuse("that signature needs a reviewer");
    }
    st = fbrl_audit_sign(&L.chain.a, (uint64_t)record, h, meaning, sk, pk);
    fbrl_users_wipe(sk, sizeof sk);
    if (st != FBRL_OK)
        return refuse(fbrl_status_str(st));
    printf("%s: record %lld signed by %s (%s) in record %llu\n", L.chain_path, record, as, meaning,
           (unsigned long long)fbrl_audit_head(&L.chain.a, NULL));
    return 0;
}

static int method(const char *action, const char *file, const char *as)
{
    static fbrl_method_version mv;
    char pw[FBRL_USERS_PASSWORD_MAX + 2];
    unsigned char sk[FBRL_AUDIT_SK_SIZE], pk[FBRL_AUDIT_PK_SIZE], h[FBRL_AUDIT_HASH_SIZE];
    int release = strcmp(action, "release") == 0;
    fbrl_status st = fbrl_release_identify(&mv, file);
    if (st != FBRL_OK)
        return refuse(mv.why);
    st = fbrl_release_status(&mv, L.chain_path);
    if (st != FBRL_OK)
        return refuse(mv.why[0] ? mv.why : fbrl_status_str(st));
    if (strcmp(action, "status") == 0) {
        printf("%s version %s: %s", mv.method[0] ? mv.method : mv.file[0].name, mv.hex,
               fbrl_release_state_name(mv.state));
        if (mv.state_by[0])
            printf(" (%s at %s)", mv.state_by, mv.state_utc);
        printf("\n");
        if (mv.has_released)
            printf("  released version %s differs: %s changed\n", mv.released_hex, mv.changed);
        for (size_t i = 0; i < mv.nfiles; i++) {
            printf("  ");
            for (int b = 0; b < FBRL_AUDIT_HASH_SIZE; b++)
                printf("%02x", mv.file[i].sha256[b]);
            printf("  %s\n", mv.file[i].path);
        }
        return 0;
    }
    if (strcmp(action, "draft") && strcmp(action, "submit") && !release && strcmp(action, "retire"))
        return refuse("method actions: status draft submit release retire");
    if (as == NULL)
        return refuse("sign in for that: --as NAME");
    if (lab_load_users(&L) != 0 || lab_open_chain(&L) != 0)
        return refuse(L.err);
    if (ask_password(as, pw, sizeof pw) != 0)
        return refuse("no password");
    st = release ? lab_unlock(&L, as, pw, sk, pk) : lab_sign_in(&L, as, pw, "method");
    fbrl_users_wipe(pw, sizeof pw);
    if (st != FBRL_OK)
        return refuse(L.err);
    fbrl_role role = fbrl_users_find(&L.users, as)->role;
    if (!fbrl_users_may(role, release || action[1] == 'e' ? FBRL_RIGHT_RELEASE : FBRL_RIGHT_COMPOSE)) {
        fbrl_users_wipe(sk, sizeof sk);
        return refuse(release || action[1] == 'e' ? "releasing and retiring need a reviewer"
                                                  : "drafts and submissions are a method developer's");
    }
    if (release && mv.state != FBRL_RELEASE_IN_REVIEW) {
        fbrl_users_wipe(sk, sizeof sk);
        return refuse("only a version In review is released (fbrl-audit method submit first)");
    }
    if (release && strcmp(mv.state_by, as) == 0) {
        fbrl_users_wipe(sk, sizeof sk);
        return refuse("the one who submitted a version does not release it");
    }
    st = fbrl_release_record(&L.chain.a, &mv, action);
    if (st == FBRL_OK && release) {
        uint64_t n = fbrl_audit_head(&L.chain.a, h);
        st = fbrl_audit_sign(&L.chain.a, n, h, FBRL_AUDIT_MEANING_RELEASE, sk, pk);
    }
    fbrl_users_wipe(sk, sizeof sk);
    if (st != FBRL_OK)
        return refuse(fbrl_status_str(st));
    printf("%s version %.12s: %s by %s\n", mv.method[0] ? mv.method : mv.file[0].name, mv.hex, action, as);
    return 0;
}

static int recover(const char *as, const char *reason)
{
    static fbrl_audit_verifier v;
    unsigned char sk[FBRL_AUDIT_SK_SIZE], pk[FBRL_AUDIT_PK_SIZE];
    char pw[FBRL_USERS_PASSWORD_MAX + 2];
    size_t n;
    fbrl_status st;
    if (as == NULL || reason == NULL || reason[0] == '\0')
        return refuse("recover needs --as ADMIN and --reason TEXT");
    if (lab_load_users(&L) != 0)
        return refuse(L.err);
    if (ask_password(as, pw, sizeof pw) != 0)
        return refuse("no password");
    st = lab_unlock(&L, as, pw, sk, pk); /* the broken chain takes no record: the users file counts */
    fbrl_users_wipe(pw, sizeof pw);
    if (st != FBRL_OK)
        return refuse(L.err);
    if (!fbrl_users_may(fbrl_users_find(&L.users, as)->role, FBRL_RIGHT_RECOVER)) {
        fbrl_users_wipe(sk, sizeof sk);
        return refuse("only an administrator recovers the chain");
    }
    fbrl_users_keys(&L.users, L.keys, LAB_KEYS_MAX, &n);
    fbrl_audit_verify_init(&v, L.keys, n, LAB_KEYS_MAX, NULL, 0);
    st = fbrl_audit_file_recover(&L.chain, L.chain_path, &v, as, reason, sk, pk);
    fbrl_users_wipe(sk, sizeof sk);
    if (st == FBRL_ESTATE)
        return refuse("the chain is intact: there is nothing to recover");
    if (st != FBRL_OK)
        return refuse(fbrl_status_str(st));
    printf("%s: %s: recovered by %s in record %llu; the chain goes on after it\n", L.chain_path, L.chain.where, as,
           (unsigned long long)(fbrl_audit_head(&L.chain.a, NULL) - 1));
    fbrl_audit_file_close(&L.chain);
    return 0;
}

static void usage(FILE *f)
{
    fprintf(f, "usage: fbrl-audit verify FILE [--keys KEYS | --lab DIR]\n"
               "       fbrl-audit report FILE [-o OUT.html]\n"
               "       fbrl-audit replay FILE [--run N] [--fbrlsim PATH] [--no-home] [--keep]\n"
               "       fbrl-audit sign FILE --as NAME --record K [--meaning TEXT]\n"
               "       fbrl-audit method status|draft|submit|release|retire METHOD-FILE [--as NAME]\n"
               "       fbrl-audit recover FILE --as ADMIN --reason TEXT\n"
               "The lab (its users, and its chain for 'method'): --lab DIR or FBRL_LAB.\n");
}

int main(int argc, char **argv)
{
    enum { O_KEYS = 256, O_LAB, O_AS, O_RECORD, O_MEANING, O_REASON, O_RUN, O_SIM, O_NOHOME, O_KEEP, O_USERS };
    static const struct option opts[] = {
        {"keys", required_argument, NULL, O_KEYS},       {"lab", required_argument, NULL, O_LAB},
        {"users", required_argument, NULL, O_USERS},     {"as", required_argument, NULL, O_AS},
        {"record", required_argument, NULL, O_RECORD},   {"meaning", required_argument, NULL, O_MEANING},
        {"reason", required_argument, NULL, O_REASON},   {"run", required_argument, NULL, O_RUN},
        {"fbrlsim", required_argument, NULL, O_SIM},     {"no-home", no_argument, NULL, O_NOHOME},
        {"keep", no_argument, NULL, O_KEEP},             {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, 'V'},             {NULL, 0, NULL, 0}};
    static fbrl_audit_key keybuf[LAB_KEYS_MAX];
    audit_keys keys = {keybuf, 0, LAB_KEYS_MAX, NULL};
    const char *keys_path = NULL, *dir = NULL, *users = NULL, *as = NULL, *meaning = FBRL_AUDIT_MEANING_REVIEW;
    const char *reason = NULL, *sim = NULL, *out = NULL;
    long long record = 0;
    long run = 0;
    int c, home = 1, keep = 0, rc;
    while ((c = getopt_long(argc, argv, "o:hV", opts, NULL)) != -1) {
        switch (c) {
        case O_KEYS: keys_path = optarg; break;
        case O_LAB: dir = optarg; break;
        case O_USERS: users = optarg; break;
        case O_AS: as = optarg; break;
        case O_RECORD: record = atoll(optarg); break;
        case O_MEANING: meaning = optarg; break;
        case O_REASON: reason = optarg; break;
        case O_RUN: run = atol(optarg); break;
        case O_SIM: sim = optarg; break;
        case O_NOHOME: home = 0; break;
        case O_KEEP: keep = 1; break;
        case 'o': out = optarg; break;
        case 'h': usage(stdout); return 0;
        case 'V': printf("fbrl-audit (libfbrl) %s\n", FBRL_VERSION_STRING); return 0;
        default: usage(stderr); return AUDIT_EXIT_USAGE;
        }
    }
    argc -= optind;
    argv += optind;
    if (argc < 2)
        return usage(stderr), AUDIT_EXIT_USAGE;
    if (keys_path != NULL) {
        if (read_keys(keys_path, &keys) != 0)
            return AUDIT_EXIT_USAGE;
        keys.source = keys_path;
    } else if (strcmp(argv[0], "verify") == 0 && (dir != NULL || users != NULL)) {
        if (lab_init(&L, dir, users, argv[1]) != 0 || lab_load_users(&L) != 0)
            return refuse(L.err);
        fbrl_users_keys(&L.users, keybuf, LAB_KEYS_MAX, &keys.n);
        keys.source = L.users_path;
    }
    if (strcmp(argv[0], "verify") == 0 && argc == 2)
        return verify(argv[1], &keys);
    if (strcmp(argv[0], "report") == 0 && argc == 2)
        return audit_report(argv[1], out, &keys);
    if (strcmp(argv[0], "replay") == 0 && argc == 2)
        return audit_replay(argv[1], run, sim, home, keep);
    if (strcmp(argv[0], "sign") == 0 && argc == 2) {
        if (lab_init(&L, dir, users, argv[1]) != 0)
            return refuse(L.err);
        rc = sign(as, record, meaning);
    } else if (strcmp(argv[0], "recover") == 0 && argc == 2) {
        if (lab_init(&L, dir, users, argv[1]) != 0)
            return refuse(L.err);
        rc = recover(as, reason);
    } else if (strcmp(argv[0], "method") == 0 && argc == 3) {
        if (lab_init(&L, dir, users, NULL) != 0)
            return refuse(L.err);
        rc = method(argv[1], argv[2], as);
    } else {
        usage(stderr);
        return AUDIT_EXIT_USAGE;
    }
    lab_close(&L);
    return rc;
}
