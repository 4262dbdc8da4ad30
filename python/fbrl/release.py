# SPDX-License-Identifier: MIT
"""fbrl.method_version: a method's version as the compliance issue names it (docs/compliance.md,
"Released methods"): the SHA-256 of its file and of every file it includes, each under the name
it is included by. Thin: fbrl_release_identify (fbrl/release.h) reads and hashes the files.

    hex, method = fbrl.method_version("/lab/methods/sample_prep.fbrl")
"""
from ._ffi import ffi, lib, alloc, declared_later
from ._errors import check

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
