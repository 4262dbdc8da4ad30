# SPDX-License-Identifier: MIT
"""fbrl.method_version: a method's version as the compliance issue names it (docs/compliance.md,
"Released methods"): the SHA-256 of its file and of every file it includes, each under the name
it is included by. Thin: fbrl_release_identify (fbrl/release.h) reads and hashes the files.
fbrl.method_release: may a role run it, by the lab's audit trail (fbrl_release_status and
fbrl_release_check, as fbrlmon checks a run in a lab).

    hex, method = fbrl.method_version("/lab/methods/sample_prep.fbrl")
    hex, state = fbrl.method_release(path, "/lab/audit.jsonl", "operator", allow_drafts=False)
"""
from ._ffi import ffi, lib, alloc, declared_later
from ._errors import check, Error

ffi.cdef("""
typedef struct fbrl_release_file {
    char name[256];
    char path[256];
    unsigned char sha256[32];
} fbrl_release_file;
typedef struct fbrl_method_version {
    char method[64];
    size_t nfiles;
    fbrl_release_file file[32];
    unsigned char version[32];
    char hex[65];
    int state;
    char state_by[32];
    char state_utc[32];
    int has_released;
    char released_hex[65];
    char changed[256];
    char why[320];
} fbrl_method_version;
fbrl_status fbrl_release_identify(fbrl_method_version *mv, const char *path);
fbrl_status fbrl_release_status(fbrl_method_version *mv, const char *chain_path);
fbrl_status fbrl_release_check(fbrl_method_version *mv, int role, int allow_drafts);
const char *fbrl_release_state_name(int s);
""", override=True)

declared_later("fbrl_method_version")


def method_version(path):
    """(the version as 64 hex digits, the name on the file's METHOD line or ""); fbrl.Error
    naming the file that could not be read (a missing include too)."""
    mv = alloc("fbrl_method_version")
    p = mv.ptr
    st = lib.fbrl_release_identify(p, path.encode())
    check(st, "method version of %s: %s" % (path, ffi.string(p.why).decode(errors="replace")))
    return ffi.string(p.hex).decode(), ffi.string(p.method).decode()


def method_release(path, chain_path, role, allow_drafts=False):
    """(the version as 64 hex digits, its state: "Released", "Draft" ...) when role (a role's
    name or number, fbrl.Users.role) may run the method file at path by the chain at chain_path (a
    missing chain: every version is a Draft). fbrl.Error otherwise, its detail the library's
    words: FBRL_EPERM (a Draft or a version in review for an operator, a Released method whose
    files changed and which, a Retired version), FBRL_ECHECKSUM (the chain is broken, and
    where), FBRL_ENOENT (a file that cannot be read)."""
    from .users import Users
    mv = alloc("fbrl_method_version")
    p = mv.ptr

    def why():
        return ffi.string(p.why).decode(errors="replace")
    st = lib.fbrl_release_identify(p, path.encode())
    if st == 0:
        st = lib.fbrl_release_status(p, chain_path.encode())
    if st == 0:
        st = lib.fbrl_release_check(p, role if isinstance(role, int) else Users.role(role), 1 if allow_drafts else 0)
    if st < 0:
        raise Error(st, "method %s" % path, detail=why())
    return ffi.string(p.hex).decode(), ffi.string(lib.fbrl_release_state_name(p.state)).decode()
