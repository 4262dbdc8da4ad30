/* SPDX-License-Identifier: MIT */
/* release.c - a method's version (the hash of its files, includes followed) and its state
 * as the audit chain's "method" records and their signatures give it. */
#include "fbrl/release.h"
#include "audit_int.h"
#include "audit_store.h"

#include <sodium.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#define READ_CHUNK 4096
#define TOKEN_MAX 256
#define ROLES_MAX 64

static const char *const state_names[] = {"Draft", "In review", "Released", "Retired"};

/* src into dst[cap], cut to fit. */
static void copy(char *dst, size_t cap, const char *src)
{
    size_t n = strlen(src);
    if (n >= cap)
        n = cap - 1;
    memmove(dst, src, n);
    dst[n] = '\0';
}

/* The refusal or note in words, into mv->why (cut to fit). */
static void say(fbrl_method_version *mv, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(mv->why, sizeof mv->why, fmt, ap);
    va_end(ap);
}

/* The method's name: its METHOD line's, else its file's. */
static const char *method_name(const fbrl_method_version *mv)
{
    return mv->method[0] ? mv->method : mv->file[0].name;
}

const char *fbrl_release_state_name(fbrl_release_state s)
{
    return (unsigned)s <= FBRL_RELEASE_RETIRED ? state_names[s] : "?";
}

/* ---- the files: a Forth source's includes, read as the interpreter would see them ---- */

enum { M_CODE, M_LINE_COMMENT, M_PAREN_COMMENT, M_STRING };

typedef struct scan {
    fbrl_method_version *mv;
    size_t from;           /* the including file's index */
    int mode, expect_name; /* after INCLUDE / REQUIRE */
    int have_str, want_method;
    char tok[TOKEN_MAX];
    size_t tlen;
    char str[TOKEN_MAX];
    size_t slen;
    fbrl_status st;
} scan;

static int word_is(const char *t, const char *w)
{
    for (; *t && *w; t++, w++)
        if ((*t >= 'a' && *t <= 'z' ? *t - 32 : *t) != *w)
            return 0;
    return *t == '\0' && *w == '\0';
}

/* Add the file included as name by file `from`: its path is taken from the includer's
 * directory, as INCLUDED does. Once per name. */
static void add_file(scan *s, const char *name)
{
    fbrl_method_version *mv = s->mv;
    const char *inc = mv->file[s->from].path, *slash = strrchr(inc, '/');
    fbrl_release_file *f;
    char where[FBRL_RELEASE_PATH_MAX];
    int dl = name[0] != '/' && slash ? (int)(slash - inc) + 1 : 0;
    if ((size_t)snprintf(where, sizeof where, "%.*s%s", dl, inc, name) >= sizeof where) {
        s->st = FBRL_ENAME;
        return;
    }
    for (size_t i = 0; i < mv->nfiles; i++)
        if (strcmp(mv->file[i].name, name) == 0)
            return;
    if (mv->nfiles >= FBRL_RELEASE_MAX_FILES) {
        s->st = FBRL_EFULL;
        return;
    }
    f = &mv->file[mv->nfiles];
    memset(f, 0, sizeof *f);
    if (strlen(name) >= sizeof f->name) {
        s->st = FBRL_ENAME;
        return;
    }
    copy(f->name, sizeof f->name, name);
    copy(f->path, sizeof f->path, where);
    mv->nfiles++;
}

static void token(scan *s)
{
    const char *t = s->tok;
    s->tok[s->tlen] = '\0';
    s->tlen = 0;
    if (s->want_method) {
        copy(s->mv->method, sizeof s->mv->method, t);
        s->want_method = 0;
    } else if (s->expect_name) {
        s->expect_name = 0;
        add_file(s, t);
    } else if (strcmp(t, "\\") == 0) {
        s->mode = M_LINE_COMMENT;
    } else if (strcmp(t, "(") == 0 || strcmp(t, ".(") == 0) {
        s->mode = M_PAREN_COMMENT;
    } else if (word_is(t, "S\"")) {
        s->mode = M_STRING;
        s->slen = 0;
    } else if (word_is(t, "INCLUDE") || word_is(t, "REQUIRE")) {
        s->expect_name = 1;
    } else if (word_is(t, "INCLUDED") || word_is(t, "REQUIRED")) {
        if (s->have_str)
            add_file(s, s->str);
        s->have_str = 0;
    } else if (word_is(t, "METHOD") && s->from == 0 && s->mv->method[0] == '\0') {
        s->want_method = 1;
    } else {
        s->have_str = 0;
    }
}

static void feed(scan *s, const char *p, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        char c = p[i];
        switch (s->mode) {
        case M_LINE_COMMENT:
            if (c == '\n')
                s->mode = M_CODE;
            continue;
        case M_PAREN_COMMENT:
            if (c == ')')
                s->mode = M_CODE;
            continue;
        case M_STRING:
            if (c == '"') {
                s->str[s->slen] = '\0';
                s->have_str = 1;
                s->mode = M_CODE;
            } else if (s->slen + 1 < sizeof s->str) {
                s->str[s->slen++] = c;
            }
            continue;
        default:
            break;
        }
        if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
            if (s->tlen)
                token(s);
        } else if (s->tlen + 1 < sizeof s->tok) {
            s->tok[s->tlen++] = c;
        }
    }
}

fbrl_status fbrl_release_identify(fbrl_method_version *mv, const char *path)
{
    crypto_hash_sha256_state all;
    char chunk[READ_CHUNK], hex[2 * FBRL_AUDIT_HASH_SIZE + 1];
    const char *base;
    scan s;
    if (mv == NULL || path == NULL || path[0] == '\0')
        return FBRL_EINVAL;
    if (sodium_init() < 0)
        return FBRL_EIO;
    memset(mv, 0, sizeof *mv);
    memset(&s, 0, sizeof s);
    s.mv = mv;
    base = strrchr(path, '/');
    copy(mv->file[0].name, sizeof mv->file[0].name, base ? base + 1 : path);
    if ((size_t)snprintf(mv->file[0].path, sizeof mv->file[0].path, "%s", path) >= sizeof mv->file[0].path)
        return FBRL_ENAME;
    mv->nfiles = 1;
    crypto_hash_sha256_init(&all);
    crypto_hash_sha256_update(&all, (const unsigned char *)"fbrl-method 1\n", 14);
    for (size_t i = 0; i < mv->nfiles && s.st == FBRL_OK; i++) {
        crypto_hash_sha256_state one;
        fbrl_release_file *f = &mv->file[i];
        size_t got;
        void *h;
        fbrl_status st = fbrl__astore_read_open(f->path, &h);
        if (st != FBRL_OK) {
            say(mv, "%s: %s", f->path, fbrl_status_str(st));
            return st;
        }
        crypto_hash_sha256_init(&one);
        s.from = i;
        s.mode = M_CODE;
        s.tlen = 0;
        s.expect_name = s.have_str = s.want_method = 0;
        do {
            st = fbrl__astore_read(h, chunk, sizeof chunk, &got);
            if (st == FBRL_OK) {
                crypto_hash_sha256_update(&one, (const unsigned char *)chunk, got);
                feed(&s, chunk, got);
            }
        } while (st == FBRL_OK && got > 0);
        fbrl__astore_close(h);
        if (st != FBRL_OK) {
            say(mv, "%s: %s", f->path, fbrl_status_str(st));
            return st;
        }
        if (s.tlen && s.mode == M_CODE)
            token(&s);
        crypto_hash_sha256_final(&one, f->sha256);
        /* the version: each file under its name, in the order they are included */
        fbrl__audit_hex(f->sha256, sizeof f->sha256, hex);
        crypto_hash_sha256_update(&all, (const unsigned char *)f->name, strlen(f->name));
        crypto_hash_sha256_update(&all, (const unsigned char *)"\n", 1);
        crypto_hash_sha256_update(&all, (const unsigned char *)hex, strlen(hex));
        crypto_hash_sha256_update(&all, (const unsigned char *)"\n", 1);
    }
    if (s.st != FBRL_OK) {
        say(mv, "%s: %s", path,
                 s.st == FBRL_EFULL ? "includes more files than a version can name" : "an include's name is too long");
        return s.st;
    }
    crypto_hash_sha256_final(&all, mv->version);
    fbrl__audit_hex(mv->version, sizeof mv->version, mv->hex);
    return FBRL_OK;
}

/* ---- the state, from the chain ---- */

typedef struct role_of {
    char name[FBRL_AUDIT_NAME_MAX];
    char role[FBRL_AUDIT_ROLE_MAX];
} role_of;

typedef struct status_scan {
    fbrl_method_version *mv;
    role_of roles[ROLES_MAX];
    size_t nroles;
    char submitter[FBRL_AUDIT_NAME_MAX]; /* who submitted this version */
    long long release_seq;               /* a release waiting for its signature */
    char release_by[FBRL_AUDIT_NAME_MAX], release_utc[32], release_version[2 * FBRL_AUDIT_HASH_SIZE + 1];
    char release_changed[FBRL_RELEASE_PATH_MAX];
} status_scan;

static const char *role_for(const status_scan *c, const char *name)
{
    for (size_t i = 0; i < c->nroles; i++)
        if (strcmp(c->roles[i].name, name) == 0)
            return c->roles[i].role;
    return "";
}

static void note_role(status_scan *c, const char *s, size_t n)
{
    char name[FBRL_AUDIT_NAME_MAX], role[FBRL_AUDIT_ROLE_MAX];
    size_t i;
    if (fbrl_audit_field_str(s, n, "name", name, sizeof name) != FBRL_OK ||
        fbrl_audit_field_str(s, n, "role", role, sizeof role) != FBRL_OK)
        return;
    for (i = 0; i < c->nroles && strcmp(c->roles[i].name, name) != 0; i++)
        ;
    if (i == c->nroles) {
        if (c->nroles >= ROLES_MAX)
            return;
        c->nroles++;
    }
    copy(c->roles[i].name, sizeof c->roles[i].name, name);
    copy(c->roles[i].role, sizeof c->roles[i].role, role);
}

/* The first of mv's files that the record's "files" list does not name with the same
 * hash (or the first name the list has and mv has not), into out; "" if they agree. */
static void first_change(const fbrl_method_version *mv, const char *s, size_t n, char *out, size_t cap)
{
    const char *arr;
    size_t an, i = 1, seen = 0;
    out[0] = '\0';
    if (fbrl_audit_field(s, n, "files", &arr, &an) != FBRL_OK || an < 2 || arr[0] != '[')
        return;
    while (i < an) {
        size_t start;
        char name[FBRL_RELEASE_PATH_MAX], hex[2 * FBRL_AUDIT_HASH_SIZE + 2];
        unsigned char h[FBRL_AUDIT_HASH_SIZE];
        while (i < an && (arr[i] == ',' || arr[i] == ' '))
            i++;
        if (i >= an || arr[i] == ']')
            break;
        start = i;
        if (fbrl__audit_json_skip(arr, an, &i) != 0)
            return;
        if (fbrl_audit_field_str(arr + start, i - start, "name", name, sizeof name) != FBRL_OK ||
            fbrl_audit_field_str(arr + start, i - start, "sha256", hex, sizeof hex) != FBRL_OK ||
            fbrl__audit_unhex(hex, strlen(hex), h, sizeof h) != 0)
            return;
        seen++;
        size_t k;
        for (k = 0; k < mv->nfiles && strcmp(mv->file[k].name, name) != 0; k++)
            ;
        if (k == mv->nfiles || memcmp(mv->file[k].sha256, h, sizeof h) != 0) {
            copy(out, cap, k == mv->nfiles ? name : mv->file[k].name);
            return;
        }
    }
    if (seen < mv->nfiles) /* mv includes a file the release did not */
        copy(out, cap, mv->file[mv->nfiles - 1].name);
}

static void record(status_scan *c, const char *s, size_t n)
{
    fbrl_method_version *mv = c->mv;
    char type[16], method[FBRL_RELEASE_NAME_MAX], action[16], version[2 * FBRL_AUDIT_HASH_SIZE + 2];
    char user[FBRL_AUDIT_NAME_MAX], utc[32];
    long long seq;
    int ours;
    if (fbrl_audit_field_str(s, n, "type", type, sizeof type) != FBRL_OK ||
        fbrl_audit_field_num(s, n, "seq", &seq) != FBRL_OK ||
        fbrl_audit_field_str(s, n, "user", user, sizeof user) != FBRL_OK ||
        fbrl_audit_field_str(s, n, "utc", utc, sizeof utc) != FBRL_OK)
        return;
    if (c->release_seq) {
        /* a release counts when its next record is its signature by the same reviewer */
        long long signs = 0;
        char meaning[32];
        if (strcmp(type, "signature") == 0 && fbrl_audit_field_num(s, n, "signs", &signs) == FBRL_OK &&
            signs == c->release_seq && strcmp(user, c->release_by) == 0 &&
            fbrl_audit_field_str(s, n, "meaning", meaning, sizeof meaning) == FBRL_OK &&
            strcmp(meaning, FBRL_AUDIT_MEANING_RELEASE) == 0 && strcmp(role_for(c, user), "reviewer") == 0) {
            if (strcmp(c->release_version, mv->hex) == 0) {
                mv->state = FBRL_RELEASE_RELEASED;
                copy(mv->state_by, sizeof mv->state_by, c->release_by);
                copy(mv->state_utc, sizeof mv->state_utc, c->release_utc);
            } else {
                mv->has_released = 1;
                copy(mv->released_hex, sizeof mv->released_hex, c->release_version);
                copy(mv->changed, sizeof mv->changed, c->release_changed);
            }
        }
        c->release_seq = 0;
    }
    if (strcmp(type, "user") == 0) {
        note_role(c, s, n);
        return;
    }
    if (strcmp(type, "method") != 0 || fbrl_audit_field_str(s, n, "method", method, sizeof method) != FBRL_OK ||
        strcmp(method, method_name(mv)) != 0 || fbrl_audit_field_str(s, n, "action", action, sizeof action) != FBRL_OK ||
        fbrl_audit_field_str(s, n, "version", version, sizeof version) != FBRL_OK)
        return;
    ours = strcmp(version, mv->hex) == 0;
    if (strcmp(action, "release") == 0) {
        const char *role = role_for(c, user);
        if (strcmp(role, "reviewer") != 0 || (ours && strcmp(c->submitter, user) == 0))
            return; /* not a reviewer's, or the submitter approving their own work */
        c->release_seq = seq;
        copy(c->release_by, sizeof c->release_by, user);
        copy(c->release_utc, sizeof c->release_utc, utc);
        copy(c->release_version, sizeof c->release_version, version);
        first_change(mv, s, n, c->release_changed, sizeof c->release_changed);
        return;
    }
    if (strcmp(action, "retire") == 0 && strcmp(role_for(c, user), "reviewer") == 0) {
        if (!ours && strcmp(version, mv->released_hex) == 0)
            mv->has_released = 0;
        if (!ours)
            return;
        mv->state = FBRL_RELEASE_RETIRED;
    } else if (ours && strcmp(action, "submit") == 0 && mv->state <= FBRL_RELEASE_IN_REVIEW) {
        mv->state = FBRL_RELEASE_IN_REVIEW;
        copy(c->submitter, sizeof c->submitter, user);
    } else if (ours && strcmp(action, "draft") == 0 && mv->state <= FBRL_RELEASE_IN_REVIEW) {
        mv->state = FBRL_RELEASE_DRAFT;
    } else {
        return;
    }
    copy(mv->state_by, sizeof mv->state_by, user);
    copy(mv->state_utc, sizeof mv->state_utc, utc);
}

fbrl_status fbrl_release_status(fbrl_method_version *mv, const char *chain_path)
{
    fbrl_audit_verifier v;
    fbrl_audit_key keys[ROLES_MAX];
    status_scan c;
    char chunk[READ_CHUNK];
    size_t got, len = 0;
    void *h;
    fbrl_status st;
    if (mv == NULL || chain_path == NULL)
        return FBRL_EINVAL;
    mv->state = FBRL_RELEASE_DRAFT;
    mv->state_by[0] = mv->state_utc[0] = '\0';
    mv->has_released = 0;
    mv->released_hex[0] = mv->changed[0] = mv->why[0] = '\0';
    fbrl_audit_verify_init(&v, keys, 0, ROLES_MAX, NULL, 0);
    st = fbrl_audit_file_verify(chain_path, &v);
    if (st == FBRL_ECHECKSUM) {
        say(mv, "%s: %s", chain_path, v.where);
        return st;
    }
    if (st != FBRL_OK)
        return st;
    st = fbrl__astore_read_open(chain_path, &h);
    if (st == FBRL_ENOENT)
        return FBRL_OK; /* no chain yet: nothing released */
    if (st != FBRL_OK)
        return st;
    memset(&c, 0, sizeof c);
    c.mv = mv;
    do {
        st = fbrl__astore_read(h, chunk, sizeof chunk, &got);
        for (size_t i = 0; st == FBRL_OK && i < got; i++) {
            if (chunk[i] != '\n') {
                if (len < sizeof v.buf - 1)
                    v.buf[len++] = chunk[i];
                continue;
            }
            record(&c, v.buf, len);
            len = 0;
        }
    } while (st == FBRL_OK && got > 0);
    fbrl__astore_close(h);
    return st;
}

fbrl_status fbrl_release_check(fbrl_method_version *mv, fbrl_role role, int allow_drafts)
{
    const char *name;
    if (mv == NULL)
        return FBRL_EINVAL;
    name = method_name(mv);
    if (mv->state == FBRL_RELEASE_RELEASED)
        return fbrl_users_may(role, FBRL_RIGHT_RUN) ? FBRL_OK : FBRL_EPERM;
    if (mv->state == FBRL_RELEASE_RETIRED) {
        say(mv, "%s version %.12s is Retired (by %s at %s): it does not run", name, mv->hex,
                 mv->state_by, mv->state_utc);
        return FBRL_EPERM;
    }
    if (allow_drafts && fbrl_users_may(role, FBRL_RIGHT_RUN_DRAFT)) {
        if (mv->has_released)
            say(mv, "%s: runs as a Draft: %s changed since release %.12s", name,
                     mv->changed[0] ? mv->changed : mv->file[0].name, mv->released_hex);
        else
            say(mv, "%s: runs as a Draft (version %.12s, %s)", name, mv->hex,
                     fbrl_release_state_name(mv->state));
        return FBRL_OK;
    }
    if (mv->has_released)
        say(mv,
                 "%s: refused: %s changed since its release (released version %.12s, these files make %.12s): a "
                 "changed method needs a new review and release",
                 name, mv->changed[0] ? mv->changed : mv->file[0].name, mv->released_hex, mv->hex);
    else
        say(mv, "%s: refused: version %.12s is %s, not Released: %s", name, mv->hex,
                 fbrl_release_state_name(mv->state),
                 fbrl_users_may(role, FBRL_RIGHT_RUN_DRAFT) ? "the lab does not allow Drafts to run"
                                                           : "an operator runs only Released methods");
    return FBRL_EPERM;
}

fbrl_status fbrl_release_record(fbrl_audit *a, const fbrl_method_version *mv, const char *action)
{
    char files[FBRL_AUDIT_BODY_MAX], hex[2 * FBRL_AUDIT_HASH_SIZE + 1];
    size_t o = 0;
    if (a == NULL || mv == NULL || action == NULL || mv->nfiles == 0)
        return FBRL_EINVAL;
    if (strcmp(action, "draft") && strcmp(action, "submit") && strcmp(action, "release") && strcmp(action, "retire"))
        return FBRL_EINVAL;
    files[o++] = '[';
    for (size_t i = 0; i < mv->nfiles; i++) {
        int k;
        fbrl__audit_hex(mv->file[i].sha256, FBRL_AUDIT_HASH_SIZE, hex);
        /* names are file names: no quote or backslash can be in one the scan accepted */
        if (strchr(mv->file[i].name, '"') || strchr(mv->file[i].name, '\\'))
            return FBRL_ENAME;
        k = snprintf(files + o, sizeof files - o, "%s{\"name\":\"%s\",\"sha256\":\"%s\"}", i ? "," : "",
                     mv->file[i].name, hex);
        if (k < 0 || (size_t)k >= sizeof files - o - 1)
            return FBRL_ENOSPC;
        o += (size_t)k;
    }
    files[o++] = ']';
    files[o] = '\0';
    fbrl_audit_begin(a, "method");
    fbrl_audit_str(a, "action", action);
    fbrl_audit_str(a, "method", method_name(mv));
    fbrl_audit_str(a, "version", mv->hex);
    fbrl_audit_raw(a, "files", files);
    return fbrl_audit_end(a);
}
