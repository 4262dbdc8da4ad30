/* SPDX-License-Identifier: MIT */
/* users.c - users, roles, passwords (Argon2id), sealed signing keys (Ed25519 under
 * secretbox), lockout; the users file through the store (audit_store.h). */
#include "fbrl/users.h"
#include "audit_int.h"
#include "audit_store.h"

#include <sodium.h>
#include <stdio.h>
#include <string.h>

#define MAGIC "# fbrl users 1"
#define READ_CHUNK 1024

typedef char sizes_agree[(FBRL_USERS_PWHASH_MAX == crypto_pwhash_STRBYTES &&
                          sizeof(((fbrl_user *)0)->salt) == crypto_pwhash_SALTBYTES &&
                          sizeof(((fbrl_user *)0)->nonce) == crypto_secretbox_NONCEBYTES &&
                          FBRL_USERS_SEALED_SIZE == FBRL_AUDIT_SK_SIZE + crypto_secretbox_MACBYTES &&
                          FBRL_AUDIT_SK_SIZE == crypto_sign_SECRETKEYBYTES &&
                          FBRL_AUDIT_PK_SIZE == crypto_sign_PUBLICKEYBYTES)
                             ? 1
                             : -1];

static const char *const role_names[FBRL_ROLE_COUNT] = {"operator", "developer", "programmer", "reviewer",
                                                        "administrator"};

/* Each role's rights, one bit per fbrl_right. A reviewer and an administrator run no
 * methods: the one who approves or administers is not the one whose work is approved. */
#define R(x) (1u << FBRL_RIGHT_##x)
static const unsigned rights[FBRL_ROLE_COUNT] = {
    R(RUN),
    R(RUN) | R(RUN_DRAFT) | R(TEACH) | R(COMPOSE),
    R(RUN) | R(RUN_DRAFT) | R(TEACH) | R(COMPOSE) | R(FORTH),
    R(RELEASE) | R(REVIEW_RUN),
    R(USERS) | R(RECOVER),
};

int fbrl_users_may(fbrl_role role, fbrl_right right)
{
    if ((unsigned)role >= FBRL_ROLE_COUNT || (unsigned)right >= FBRL_RIGHT_COUNT)
        return 0;
    return (rights[role] >> right) & 1u;
}

const char *fbrl_users_role_name(fbrl_role role)
{
    return (unsigned)role < FBRL_ROLE_COUNT ? role_names[role] : NULL;
}

fbrl_status fbrl_users_role_parse(const char *text, fbrl_role *role)
{
    if (text == NULL || role == NULL)
        return FBRL_EINVAL;
    for (int i = 0; i < FBRL_ROLE_COUNT; i++)
        if (strcmp(text, role_names[i]) == 0) {
            *role = (fbrl_role)i;
            return FBRL_OK;
        }
    if (strcmp(text, "method-developer") == 0) {
        *role = FBRL_ROLE_DEVELOPER;
        return FBRL_OK;
    }
    return FBRL_ENOENT;
}

void fbrl_users_wipe(void *p, size_t n)
{
    if (p != NULL)
        sodium_memzero(p, n);
}

void fbrl_users_init(fbrl_users *u)
{
    if (u == NULL)
        return;
    memset(u, 0, sizeof *u);
    u->max_tries = 5;
    u->lock_s = 900;
    u->idle_s = 600;
    u->kdf_ops = crypto_pwhash_OPSLIMIT_INTERACTIVE;
    u->kdf_mem = crypto_pwhash_MEMLIMIT_INTERACTIVE;
}

static void copy_name(char *dst, const char *src)
{
    size_t n = strlen(src);
    n = n < FBRL_AUDIT_NAME_MAX ? n : FBRL_AUDIT_NAME_MAX - 1;
    memcpy(dst, src, n);
    dst[n] = '\0';
}

static fbrl_user *find(fbrl_users *u, const char *name)
{
    for (size_t i = 0; u && name && i < u->n; i++)
        if (strcmp(u->user[i].name, name) == 0)
            return &u->user[i];
    return NULL;
}

const fbrl_user *fbrl_users_find(const fbrl_users *u, const char *name)
{
    return find((fbrl_users *)(uintptr_t)u, name);
}

size_t fbrl_users_admins(const fbrl_users *u)
{
    size_t n = 0;
    for (size_t i = 0; u && i < u->n; i++)
        n += u->user[i].role == FBRL_ROLE_ADMINISTRATOR && !u->user[i].disabled;
    return n;
}

static fbrl_status password_ok(const char *pw)
{
    size_t n = pw ? strlen(pw) : 0;
    return n < FBRL_USERS_PASSWORD_MIN || n > FBRL_USERS_PASSWORD_MAX ? FBRL_ERANGE : FBRL_OK;
}

/* The password's hash, a new key pair, its secret half sealed by the password. */
static fbrl_status set_password(const fbrl_users *u, fbrl_user *x, const char *pw)
{
    unsigned char sk[FBRL_AUDIT_SK_SIZE], key[crypto_secretbox_KEYBYTES];
    fbrl_status st = FBRL_OK;
    if (sodium_init() < 0)
        return FBRL_EIO;
    if (crypto_pwhash_str(x->pwhash, pw, strlen(pw), u->kdf_ops, u->kdf_mem) != 0)
        return FBRL_ENOMEM; /* Argon2id could not have its memory */
    randombytes_buf(x->salt, sizeof x->salt);
    randombytes_buf(x->nonce, sizeof x->nonce);
    x->kdf_ops = u->kdf_ops;
    x->kdf_mem = u->kdf_mem;
    crypto_sign_keypair(x->pk, sk);
    if (crypto_pwhash(key, sizeof key, pw, strlen(pw), x->salt, x->kdf_ops, x->kdf_mem,
                      crypto_pwhash_ALG_ARGON2ID13) != 0)
        st = FBRL_ENOMEM;
    else
        crypto_secretbox_easy(x->sealed, sk, sizeof sk, x->nonce, key);
    sodium_memzero(sk, sizeof sk);
    sodium_memzero(key, sizeof key);
    x->failures = 0;
    x->locked_until = 0;
    return st;
}

fbrl_status fbrl_users_add(fbrl_users *u, const char *name, fbrl_role role, const char *password)
{
    fbrl_user *x;
    fbrl_status st;
    if (u == NULL || password == NULL)
        return FBRL_EINVAL;
    if (!fbrl__audit_name_ok(name))
        return FBRL_ENAME;
    if ((unsigned)role >= FBRL_ROLE_COUNT || password_ok(password) != FBRL_OK)
        return FBRL_ERANGE;
    if (find(u, name) != NULL)
        return FBRL_ESTATE;
    if (u->n >= FBRL_USERS_MAX)
        return FBRL_EFULL;
    x = &u->user[u->n];
    memset(x, 0, sizeof *x);
    snprintf(x->name, sizeof x->name, "%s", name);
    x->role = role;
    st = set_password(u, x, password);
    if (st == FBRL_OK)
        u->n++;
    return st;
}

/* The checks a sign-in and an unlock share: disabled and locked first, then the password
 * (by verify: its hash, or the sealed key), then the count. */
typedef int (*try_fn)(fbrl_user *x, const char *pw, void *ctx);

static fbrl_status attempt(fbrl_users *u, const char *name, const char *pw, int64_t now, try_fn try_pw, void *ctx)
{
    fbrl_user *x;
    if (u == NULL || pw == NULL)
        return FBRL_EINVAL;
    if (sodium_init() < 0)
        return FBRL_EIO;
    x = find(u, name);
    if (x == NULL)
        return FBRL_EAUTH;
    if (x->disabled || (x->locked_until != 0 && now < x->locked_until))
        return FBRL_ELOCKED;
    if (x->locked_until != 0) { /* the lock has run out: a fresh count */
        x->locked_until = 0;
        x->failures = 0;
    }
    if (try_pw(x, pw, ctx) != 0) {
        x->failures++;
        if (x->failures >= u->max_tries)
            x->locked_until = now + (int64_t)u->lock_s * 1000;
        return FBRL_EAUTH;
    }
    x->failures = 0;
    return FBRL_OK;
}

static int try_hash(fbrl_user *x, const char *pw, void *ctx)
{
    (void)ctx;
    return crypto_pwhash_str_verify(x->pwhash, pw, strlen(pw));
}

fbrl_status fbrl_users_login(fbrl_users *u, const char *name, const char *password, int64_t now)
{
    return attempt(u, name, password, now, try_hash, NULL);
}

typedef struct unlock_ctx {
    unsigned char *sk, *pk;
} unlock_ctx;

static int try_key(fbrl_user *x, const char *pw, void *ctx)
{
    unlock_ctx *c = ctx;
    unsigned char key[crypto_secretbox_KEYBYTES];
    int r = -1;
    if (crypto_pwhash(key, sizeof key, pw, strlen(pw), x->salt, x->kdf_ops, x->kdf_mem,
                      crypto_pwhash_ALG_ARGON2ID13) == 0)
        r = crypto_secretbox_open_easy(c->sk, x->sealed, sizeof x->sealed, x->nonce, key);
    sodium_memzero(key, sizeof key);
    if (r == 0)
        memcpy(c->pk, x->pk, FBRL_AUDIT_PK_SIZE);
    return r;
}

fbrl_status fbrl_users_unlock(fbrl_users *u, const char *name, const char *password, int64_t now,
                              unsigned char *sk, unsigned char *pk)
{
    unlock_ctx c = {sk, pk};
    if (sk == NULL || pk == NULL)
        return FBRL_EINVAL;
    return attempt(u, name, password, now, try_key, &c);
}

fbrl_status fbrl_users_disable(fbrl_users *u, const char *name, int disabled)
{
    fbrl_user *x = find(u, name);
    if (x == NULL)
        return u == NULL ? FBRL_EINVAL : FBRL_ENOENT;
    x->disabled = disabled != 0;
    return FBRL_OK;
}

fbrl_status fbrl_users_reset(fbrl_users *u, const char *name, const char *password)
{
    fbrl_user *x = find(u, name);
    fbrl_audit_key *k;
    if (x == NULL)
        return u == NULL ? FBRL_EINVAL : FBRL_ENOENT;
    if (password_ok(password) != FBRL_OK)
        return FBRL_ERANGE;
    if (u->nold >= FBRL_USERS_OLD_KEYS)
        return FBRL_EFULL;
    k = &u->old[u->nold++];
    memset(k, 0, sizeof *k);
    copy_name(k->name, x->name);
    snprintf(k->role, sizeof k->role, "%s", role_names[x->role]);
    memcpy(k->pk, x->pk, sizeof k->pk);
    return set_password(u, x, password);
}

fbrl_status fbrl_users_set_role(fbrl_users *u, const char *name, fbrl_role role)
{
    fbrl_user *x = find(u, name);
    if (x == NULL)
        return u == NULL ? FBRL_EINVAL : FBRL_ENOENT;
    if ((unsigned)role >= FBRL_ROLE_COUNT)
        return FBRL_ERANGE;
    x->role = role;
    return FBRL_OK;
}

fbrl_status fbrl_users_set(fbrl_users *u, const char *key, long long v)
{
    if (u == NULL || key == NULL)
        return FBRL_EINVAL;
    if (strcmp(key, "max_tries") == 0) {
        if (v < 1 || v > 100)
            return FBRL_ERANGE;
        u->max_tries = (unsigned)v;
    } else if (strcmp(key, "lock_s") == 0 || strcmp(key, "idle_s") == 0) {
        if (v < 1 || v > 7L * 24 * 3600)
            return FBRL_ERANGE;
        *(key[0] == 'l' ? &u->lock_s : &u->idle_s) = (long)v;
    } else if (strcmp(key, "allow_drafts") == 0) {
        if (v != 0 && v != 1)
            return FBRL_ERANGE;
        u->allow_drafts = (int)v;
    } else if (strcmp(key, "kdf_ops") == 0) {
        if (v < (long long)crypto_pwhash_OPSLIMIT_MIN || v > 64)
            return FBRL_ERANGE;
        u->kdf_ops = (unsigned long long)v;
    } else if (strcmp(key, "kdf_mem") == 0) {
        if (v < (long long)crypto_pwhash_MEMLIMIT_MIN || v > (1LL << 32))
            return FBRL_ERANGE;
        u->kdf_mem = (unsigned long)v;
    } else {
        return FBRL_ENOENT;
    }
    return FBRL_OK;
}

fbrl_status fbrl_users_keys(const fbrl_users *u, fbrl_audit_key *out, size_t cap, size_t *n)
{
    if (u == NULL || n == NULL || (cap && out == NULL))
        return FBRL_EINVAL;
    *n = 0;
    for (size_t i = 0; i < u->n; i++) {
        if (*n >= cap)
            return FBRL_ENOSPC;
        memset(&out[*n], 0, sizeof out[*n]);
        snprintf(out[*n].name, sizeof out[*n].name, "%s", u->user[i].name);
        snprintf(out[*n].role, sizeof out[*n].role, "%s", role_names[u->user[i].role]);
        memcpy(out[*n].pk, u->user[i].pk, FBRL_AUDIT_PK_SIZE);
        (*n)++;
    }
    for (size_t i = 0; i < u->nold; i++) {
        if (*n >= cap)
            return FBRL_ENOSPC;
        out[(*n)++] = u->old[i];
    }
    return FBRL_OK;
}

/* ---- the file ---- */

/* "user NAME ROLE STATE FAILURES LOCKED_UNTIL PWHASH PK SALT NONCE SEALED KDF_OPS KDF_MEM" */
static int put_user(fbrl_users *u, const fbrl_user *x)
{
    char pk[65], salt[33], nonce[49], sealed[2 * FBRL_USERS_SEALED_SIZE + 1];
    fbrl__audit_hex(x->pk, sizeof x->pk, pk);
    fbrl__audit_hex(x->salt, sizeof x->salt, salt);
    fbrl__audit_hex(x->nonce, sizeof x->nonce, nonce);
    fbrl__audit_hex(x->sealed, sizeof x->sealed, sealed);
    return snprintf(u->line, sizeof u->line, "user %s %s %s %u %lld %s %s %s %s %s %llu %lu\n", x->name,
                    role_names[x->role], x->disabled ? "disabled" : "active", x->failures,
                    (long long)x->locked_until, x->pwhash, pk, salt, nonce, sealed, x->kdf_ops, x->kdf_mem);
}

fbrl_status fbrl_users_save(fbrl_users *u, const char *path)
{
    void *h;
    fbrl_status st;
    int n;
    if (u == NULL || path == NULL)
        return FBRL_EINVAL;
    st = fbrl__astore_put_begin(path, 1, &h);
    if (st != FBRL_OK)
        return st;
    n = snprintf(u->line, sizeof u->line,
                 MAGIC " (owner-only; change it with fbrl-users)\nsetting max_tries %u\nsetting lock_s %ld\n"
                       "setting idle_s %ld\nsetting allow_drafts %d\nsetting kdf_ops %llu\nsetting kdf_mem %lu\n",
                 u->max_tries, u->lock_s, u->idle_s, u->allow_drafts, u->kdf_ops, u->kdf_mem);
    st = fbrl__astore_put_write(h, u->line, (size_t)n);
    for (size_t i = 0; st == FBRL_OK && i < u->n; i++) {
        n = put_user(u, &u->user[i]);
        st = n > 0 && (size_t)n < sizeof u->line ? fbrl__astore_put_write(h, u->line, (size_t)n) : FBRL_ENOSPC;
    }
    for (size_t i = 0; st == FBRL_OK && i < u->nold; i++) {
        char pk[2 * FBRL_AUDIT_PK_SIZE + 1];
        fbrl__audit_hex(u->old[i].pk, sizeof u->old[i].pk, pk);
        n = snprintf(u->line, sizeof u->line, "oldkey %s %s %s\n", u->old[i].name, u->old[i].role, pk);
        st = fbrl__astore_put_write(h, u->line, (size_t)n);
    }
    fbrl_status cst = fbrl__astore_put_commit(h, path, st == FBRL_OK);
    return st != FBRL_OK ? st : cst;
}

/* The next blank-separated word of s at *p, NUL-terminated in place. */
static char *word(char *s, size_t *p)
{
    char *w;
    while (s[*p] == ' ')
        (*p)++;
    if (s[*p] == '\0')
        return NULL;
    w = s + *p;
    while (s[*p] != ' ' && s[*p] != '\0')
        (*p)++;
    if (s[*p] == ' ')
        s[(*p)++] = '\0';
    return w;
}

static int number(const char *w, long long *v)
{
    long long x = 0;
    int neg = w && w[0] == '-';
    if (w == NULL || w[neg] == '\0' || strlen(w) > 18)
        return -1;
    for (const char *c = w + neg; *c; c++) {
        if (*c < '0' || *c > '9')
            return -1;
        x = x * 10 + (*c - '0');
    }
    *v = neg ? -x : x;
    return 0;
}

static int unhex(const char *w, unsigned char *out, size_t n)
{
    return w == NULL ? -1 : fbrl__audit_unhex(w, strlen(w), out, n);
}

static fbrl_status parse_line(fbrl_users *u, char *s, unsigned long lineno)
{
    size_t p = 0;
    char *kind, *w[12];
    long long a, b, c, d;
    if (lineno == 1)
        return strncmp(s, MAGIC, sizeof MAGIC - 1) == 0 ? FBRL_OK : FBRL_EFORMAT;
    kind = word(s, &p);
    if (kind == NULL || kind[0] == '#')
        return FBRL_OK;
    if (strcmp(kind, "setting") == 0) {
        char *key = word(s, &p);
        if (key == NULL || number(word(s, &p), &a) != 0 || word(s, &p) != NULL)
            return FBRL_EFORMAT;
        return fbrl_users_set(u, key, a) == FBRL_OK ? FBRL_OK : FBRL_EFORMAT;
    }
    if (strcmp(kind, "oldkey") == 0) {
        fbrl_audit_key *k = &u->old[u->nold];
        fbrl_role r;
        char *name = word(s, &p), *role = word(s, &p);
        if (u->nold >= FBRL_USERS_OLD_KEYS || !fbrl__audit_name_ok(name) || role == NULL ||
            fbrl_users_role_parse(role, &r) != FBRL_OK || unhex(word(s, &p), k->pk, sizeof k->pk) != 0 ||
            word(s, &p) != NULL)
            return FBRL_EFORMAT;
        copy_name(k->name, name);
        snprintf(k->role, sizeof k->role, "%s", role_names[r]);
        u->nold++;
        return FBRL_OK;
    }
    if (strcmp(kind, "user") != 0 || u->n >= FBRL_USERS_MAX)
        return FBRL_EFORMAT;
    for (int i = 0; i < 12; i++)
        if ((w[i] = word(s, &p)) == NULL)
            return FBRL_EFORMAT;
    fbrl_user *x = &u->user[u->n];
    memset(x, 0, sizeof *x);
    if (!fbrl__audit_name_ok(w[0]) || find(u, w[0]) != NULL || fbrl_users_role_parse(w[1], &x->role) != FBRL_OK ||
        (strcmp(w[2], "active") != 0 && strcmp(w[2], "disabled") != 0) || number(w[3], &a) != 0 || a < 0 ||
        number(w[4], &b) != 0 || strlen(w[5]) >= sizeof x->pwhash || unhex(w[6], x->pk, sizeof x->pk) != 0 ||
        unhex(w[7], x->salt, sizeof x->salt) != 0 || unhex(w[8], x->nonce, sizeof x->nonce) != 0 ||
        unhex(w[9], x->sealed, sizeof x->sealed) != 0 || number(w[10], &c) != 0 || c < 1 ||
        number(w[11], &d) != 0 || d < 1 || word(s, &p) != NULL)
        return FBRL_EFORMAT;
    snprintf(x->name, sizeof x->name, "%s", w[0]);
    x->disabled = w[2][0] == 'd';
    x->failures = (unsigned)a;
    x->locked_until = b;
    snprintf(x->pwhash, sizeof x->pwhash, "%s", w[5]);
    x->kdf_ops = (unsigned long long)c;
    x->kdf_mem = (unsigned long)d;
    u->n++;
    return FBRL_OK;
}

fbrl_status fbrl_users_load(fbrl_users *u, const char *path)
{
    char chunk[READ_CHUNK];
    size_t got, len = 0;
    unsigned long lineno = 0;
    void *h;
    fbrl_status st;
    if (u == NULL || path == NULL)
        return FBRL_EINVAL;
    st = fbrl__astore_guarded(path);
    if (st != FBRL_OK)
        return st;
    st = fbrl__astore_read_open(path, &h);
    if (st != FBRL_OK)
        return st;
    fbrl_users_init(u);
    do {
        st = fbrl__astore_read(h, chunk, sizeof chunk, &got);
        for (size_t i = 0; st == FBRL_OK && i < got; i++) {
            if (chunk[i] != '\n') {
                if (len + 1 >= sizeof u->line)
                    st = FBRL_EFORMAT;
                else
                    u->line[len++] = chunk[i];
                continue;
            }
            u->line[len] = '\0';
            len = 0;
            st = parse_line(u, u->line, ++lineno);
        }
    } while (st == FBRL_OK && got > 0);
    fbrl__astore_close(h);
    if (st == FBRL_OK && (len > 0 || lineno == 0))
        st = FBRL_EFORMAT; /* a cut last line, or an empty file */
    if (st == FBRL_EFORMAT)
        u->bad_line = lineno + (len > 0);
    fbrl_users_wipe(u->line, sizeof u->line);
    return st;
}
