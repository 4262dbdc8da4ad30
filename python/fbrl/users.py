# SPDX-License-Identifier: MIT
"""fbrl.Users: the lab's users file (docs/compliance.md) from Python, for a station or a
page that signs people in. Thin: the checks (Argon2id, the lockout, the file's mode) are the
library's (fbrl/users.h); failures raise fbrl.Error (FBRL_EAUTH, FBRL_ELOCKED, FBRL_EPERM ...).

    users = fbrl.Users("/lab/users")
    users.login("ann", password)          # raises fbrl.Error when refused; save() keeps the count
    users.save()
    if fbrl.Users.may(users.user("ann")["role"], "run"): ...
"""
import os
import time

from ._ffi import ffi, lib, alloc, declared_later
from ._errors import check

ffi.cdef("""
typedef struct fbrl_user {
    char name[32];
    int role;
    int disabled;
    unsigned failures;
    int64_t locked_until;
    char pwhash[128];
    unsigned char pk[32];
    unsigned char salt[16];
    unsigned char nonce[24];
    unsigned char sealed[80];
    unsigned long long kdf_ops;
    unsigned long kdf_mem;
} fbrl_user;
typedef struct fbrl_audit_key {
    char name[32];
    char role[16];
    unsigned char pk[32];
} fbrl_audit_key;
typedef struct fbrl_users {
    size_t n;
    fbrl_user user[64];
    unsigned max_tries;
    long lock_s;
    long idle_s;
    int allow_drafts;
    unsigned long long kdf_ops;
    unsigned long kdf_mem;
    size_t nold;
    fbrl_audit_key old[128];
    unsigned long bad_line;
    char line[1024];
} fbrl_users;
void fbrl_users_init(fbrl_users *u);
fbrl_status fbrl_users_load(fbrl_users *u, const char *path);
fbrl_status fbrl_users_save(fbrl_users *u, const char *path);
const fbrl_user *fbrl_users_find(const fbrl_users *u, const char *name);
fbrl_status fbrl_users_add(fbrl_users *u, const char *name, int role, const char *password);
fbrl_status fbrl_users_login(fbrl_users *u, const char *name, const char *password, int64_t now);
fbrl_status fbrl_users_disable(fbrl_users *u, const char *name, int disabled);
fbrl_status fbrl_users_reset(fbrl_users *u, const char *name, const char *password);
fbrl_status fbrl_users_set_role(fbrl_users *u, const char *name, int role);
fbrl_status fbrl_users_set(fbrl_users *u, const char *key, long long value);
size_t fbrl_users_admins(const fbrl_users *u);
int fbrl_users_may(int role, int right);
const char *fbrl_users_role_name(int role);
fbrl_status fbrl_users_role_parse(const char *text, int *role);
""", override=True)

declared_later("fbrl_users", "fbrl_user")  # read field by field (settings(), user()): the layouts must agree

# fbrl_right (fbrl/users.h), by name
RIGHTS = ("run", "run_draft", "teach", "compose", "forth", "release", "review_run", "users", "recover")


def _now_ms():
    return int(time.time() * 1000)


class Users:
    """The users of a lab: loaded from its file (refused when others may write it), changed,
    saved owner-only. Users() without a path is an empty table."""

    def __init__(self, path=None):
        self._u = alloc("fbrl_users")
        self.path = path
        lib.fbrl_users_init(self._u.ptr)
        if path is not None and os.path.exists(path):
            check(lib.fbrl_users_load(self._u.ptr, path.encode()), "users: load %s" % path)

    def save(self, path=None):
        """Write the file atomically, mode 0600."""
        path = path or self.path
        check(lib.fbrl_users_save(self._u.ptr, path.encode()), "users: save %s" % path)

    @staticmethod
    def role(text):
        """The role's number for "operator", "developer", "programmer", "reviewer", "administrator"."""
        r = ffi.new("int *")
        check(lib.fbrl_users_role_parse(text.encode(), r), "users: role %r" % text)
        return r[0]

    @staticmethod
    def may(role, right):
        """May a role (its name or number) do that ("run", "run_draft", "teach", ... "recover")?"""
        if isinstance(role, str):
            role = Users.role(role)
        return bool(lib.fbrl_users_may(role, RIGHTS.index(right)))

    def add(self, name, role, password):
        check(lib.fbrl_users_add(self._u.ptr, name.encode(), self.role(role), password.encode()),
              "users: add %s" % name)

    def login(self, name, password, now_ms=None):
        """Sign in; raises fbrl.Error (FBRL_EAUTH: unknown or wrong, counted; FBRL_ELOCKED: locked
        or disabled). Save afterwards so that the count outlives the program."""
        check(lib.fbrl_users_login(self._u.ptr, name.encode(), password.encode(),
                                   _now_ms() if now_ms is None else now_ms), "users: sign-in of %s" % name)

    def disable(self, name, disabled=True):
        check(lib.fbrl_users_disable(self._u.ptr, name.encode(), 1 if disabled else 0), "users: disable %s" % name)

    def reset(self, name, password):
        check(lib.fbrl_users_reset(self._u.ptr, name.encode(), password.encode()), "users: reset %s" % name)

    def set_role(self, name, role):
        check(lib.fbrl_users_set_role(self._u.ptr, name.encode(), self.role(role)), "users: role of %s" % name)

    def set(self, key, value):
        """A lab setting: max_tries, lock_s, idle_s, allow_drafts, kdf_ops, kdf_mem."""
        check(lib.fbrl_users_set(self._u.ptr, key.encode(), int(value)), "users: set %s" % key)

    def settings(self):
        """The lab's settings: {max_tries, lock_s, idle_s, allow_drafts}."""
        u = ffi.cast("fbrl_users *", self._u.ptr)
        return {"max_tries": u.max_tries, "lock_s": u.lock_s, "idle_s": u.idle_s, "allow_drafts": bool(u.allow_drafts)}

    def user(self, name):
        """{name, role, disabled, failures, locked_until (UTC ms, 0: not locked), public_key (hex)}, or None."""
        x = lib.fbrl_users_find(self._u.ptr, name.encode())
        if x == ffi.NULL:
            return None
        return {"name": ffi.string(x.name).decode(), "role": ffi.string(lib.fbrl_users_role_name(x.role)).decode(),
                "disabled": bool(x.disabled), "failures": x.failures, "locked_until": x.locked_until,
                "public_key": bytes(ffi.buffer(x.pk, 32)).hex()}

    def admins(self):
        return lib.fbrl_users_admins(self._u.ptr)
