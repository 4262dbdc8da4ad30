# SPDX-License-Identifier: MIT
"""fbrl.AuditTrail and fbrl.RunLog: the lab's audit trail (docs/compliance.md) from Python, for
a station that keeps its records where fbrlmon, fbrl-users and fbrl-audit keep theirs. Thin:
the chain (verification when opened, the lock against other writers, SHA-256, the head file,
seals) is the library's fbrl_audit_file_* (fbrl/audit.h); a run's records are the library's
run log (fbrl/runlog.h: the header, fbrl_runlog_event for each event of the run, the commands).

    with fbrl.AuditTrail("/lab/audit.jsonl", fbrl.Users("/lab/users")) as trail:
        trail.record("login", "ann", purpose="page", name="ann", outcome="accepted")
        trail.set_user("ann")                    # who the run log's records are by
        log = fbrl.RunLog(trail, "QUICK", source=path, operator="ann", params=[("#ITEMS", 1, "")])
        run.record(log)                          # fbrl.Run: every event of the run
        ...
        trail.seal()
"""
import threading
import time

from . import run as _run, users as _users  # noqa: F401 (their declarations come first)
from ._ffi import ffi, lib, alloc, declared_later, opaque_later
from ._errors import Error, status_code

ffi.cdef("""
typedef int (*fbrl_audit_write_fn)(void *ctx, const char *s, size_t n);
typedef int64_t (*fbrl_audit_utc_fn)(void *ctx);
typedef struct fbrl_audit {
    fbrl_audit_write_fn write;
    void *write_ctx;
    fbrl_audit_utc_fn utc;
    void *utc_ctx;
    uint64_t seq;
    unsigned char head[32];
    uint64_t last_seal;
    char user[32];
    fbrl_status failed;
    size_t blen;
    int building, overflow;
    char body[3586];
    char line[4098];
} fbrl_audit;
typedef struct fbrl_audit_file {
    fbrl_audit a;
    void *handle, *head_handle;
    char path[1024];
    char where[256];
    uint64_t head_seq;
    unsigned char head[32];
} fbrl_audit_file;
typedef struct fbrl_audit_verifier fbrl_audit_verifier;
typedef struct fbrl_runlog fbrl_runlog;
typedef int (*fbrl_runlog_write_fn)(void *ctx, const char *s, size_t n);
typedef uint64_t (*fbrl_runlog_clock_fn)(void *ctx);
typedef struct fbrl_runlog_param {
    const char *name;
    long value;
    const char *unit;
} fbrl_runlog_param;
typedef struct fbrl_runlog_header {
    const char *method;
    const char *source;
    const char *operator_id;
    const char *started;
    const char *controller;
    const char *program;
    const char *calibration;
    const fbrl_runlog_param *params;
    size_t nparams;
} fbrl_runlog_header;
fbrl_status fbrl_audit_verify_init(fbrl_audit_verifier *v, fbrl_audit_key *keys, size_t nkeys, size_t key_cap,
                                   unsigned char (*hashes)[32], size_t hash_cap);
fbrl_status fbrl_audit_file_open(fbrl_audit_file *f, const char *path, fbrl_audit_verifier *v);
fbrl_status fbrl_audit_file_close(fbrl_audit_file *f);
fbrl_status fbrl_audit_set_user(fbrl_audit *a, const char *user);
fbrl_status fbrl_audit_append(fbrl_audit *a, const char *json, size_t len);
fbrl_status fbrl_audit_begin(fbrl_audit *a, const char *type);
void fbrl_audit_str(fbrl_audit *a, const char *key, const char *value);
void fbrl_audit_num(fbrl_audit *a, const char *key, long value);
fbrl_status fbrl_audit_end(fbrl_audit *a);
fbrl_status fbrl_audit_seal(fbrl_audit *a);
uint64_t fbrl_audit_head(const fbrl_audit *a, unsigned char *hash);
fbrl_status fbrl_users_keys(const fbrl_users *u, fbrl_audit_key *out, size_t cap, size_t *n);
fbrl_status fbrl_runlog_begin(fbrl_runlog *l, fbrl_runlog_write_fn write, void *write_ctx,
                              fbrl_runlog_clock_fn now_us, void *clock_ctx, const fbrl_runlog_header *h);
fbrl_status fbrl_runlog_command_run(fbrl_runlog *l, const char *line, size_t len, fbrl_status result, int code,
                                    unsigned run);
fbrl_status fbrl_runlog_event(fbrl_runlog *l, fbrl_run *run, const fbrl_run_event *ev, fbrl_run_snap *scratch);
""", override=True)

declared_later("fbrl_audit_file", "fbrl_runlog_param", "fbrl_runlog_header")
opaque_later("fbrl_audit_verifier", "fbrl_runlog")

_USERS = dict(ffi.typeof("fbrl_users").fields)
KEYS_MAX = _USERS["user"].type.length + _USERS["old"].type.length  # the users' keys and those resets replaced
BUSY_WAIT_S = 10.0  # how long a record waits while another program writes the chain


class AuditTrail:
    """The chain at path, verified and locked for this writer while open (FBRL_EBUSY while
    another program has it: open() waits up to BUSY_WAIT_S for it). users: an fbrl.Users whose
    keys the signatures are checked with (None: the chain's own user records). A broken chain
    is refused (fbrl.Error FBRL_ECHECKSUM, its detail where it broke) and nothing is written.
    Thread-safe: one record at a time."""

    def __init__(self, path, users=None):
        self.path = path
        self._users = users
        self._f = ffi.new("fbrl_audit_file *")
        self._v = alloc("fbrl_audit_verifier")
        self._keys = ffi.new("fbrl_audit_key[]", KEYS_MAX)
        self._lock = threading.RLock()
        self._open = False

    def open(self, wait_s=BUSY_WAIT_S):
        with self._lock:
            if self._open:
                return self
            n = ffi.new("size_t *")
            if self._users is not None:
                lib.fbrl_users_keys(self._users._u.ptr, self._keys, KEYS_MAX, n)
            deadline = time.monotonic() + wait_s
            while True:
                lib.fbrl_audit_verify_init(self._v.ptr, self._keys, n[0], KEYS_MAX, ffi.NULL, 0)
                st = lib.fbrl_audit_file_open(self._f, self.path.encode(), self._v.ptr)
                if st != status_code("FBRL_EBUSY") or time.monotonic() >= deadline:
                    break
                time.sleep(0.1)
            if st < 0:
                detail = {"FBRL_ECHECKSUM": "%s: the audit trail is broken: nothing is written to it until an "
                                            "administrator recovers it (fbrl-audit recover)"
                                            % ffi.string(self._f.where).decode(errors="replace"),
                          "FBRL_EBUSY": "another program is writing the audit trail"}.get(
                    Error(st).name)
                raise Error(st, "audit trail %s" % self.path, detail=detail)
            self._open = True
            return self

    def _a(self):
        if not self._open:
            raise Error(status_code("FBRL_ESTATE"), "audit trail %s: not open" % self.path)
        return ffi.addressof(self._f, "a")

    def record(self, type, user, **fields):
        """Append one record of type by user (the writer's user for other records, set_user(),
        stays as it was): each field a str, an int, or None (left out)."""
        with self._lock:
            a = self._a()
            was = ffi.string(a.user)
            self._user(a, user)
            try:
                st = lib.fbrl_audit_begin(a, type.encode())
                if st >= 0:
                    for k, v in fields.items():
                        if v is None:
                            continue
                        if isinstance(v, int):
                            lib.fbrl_audit_num(a, k.encode(), int(v))
                        else:
                            lib.fbrl_audit_str(a, k.encode(), str(v).encode())
                    st = lib.fbrl_audit_end(a)
            finally:
                lib.fbrl_audit_set_user(a, was or b"-")
            if st < 0:
                raise Error(st, "audit record %s" % type)

    def _user(self, a, user):
        if lib.fbrl_audit_set_user(a, (user or "-").encode()) < 0:
            lib.fbrl_audit_set_user(a, b"-")  # not a user's name: the record says nobody

    def append(self, line):
        """A record's body (a run log line, bytes) as the next record. 0, or -1 when it failed
        (the writer then stops: every later record fails too)."""
        with self._lock:
            return 0 if lib.fbrl_audit_append(self._a(), line, len(line)) >= 0 else -1

    def set_user(self, user):
        """Who the records appended from now on are by (a run log's)."""
        with self._lock:
            self._user(self._a(), user)

    def seal(self):
        """Close what was written since the last seal (nothing when nothing was)."""
        with self._lock:
            a = self._a()
            if lib.fbrl_audit_head(a, ffi.NULL) > a.last_seal:
                st = lib.fbrl_audit_seal(a)
                if st < 0:
                    raise Error(st, "audit trail %s: seal" % self.path)

    def close(self, seal=True):
        """Seal (unless told not to) and let other writers have the chain."""
        with self._lock:
            if not self._open:
                return
            try:
                if seal:
                    self.seal()
            finally:
                lib.fbrl_audit_file_close(self._f)
                self._open = False

    def __enter__(self):
        return self.open()

    def __exit__(self, *exc):
        self.close()
        return False


class RunLog:
    """One method run's records in an open AuditTrail, made by the library's run log
    (fbrl/runlog.h): the header now; each event of the run by fbrl.Run.record(log); each
    command the controller ran by command(); the summary at the run's end."""

    def __init__(self, trail, method, source=None, operator=None, started=None, controller=None, program=None,
                 params=()):
        self.trail = trail
        self.failed = None  # the first record that could not be written (the log then misses records)
        self._log = alloc("fbrl_runlog")
        self._snap = alloc("fbrl_run_snap")
        self._write = ffi.callback("int(void *, const char *, size_t)", self._sink)
        self._clock = ffi.callback("uint64_t(void *)", lambda ctx: time.monotonic_ns() // 1000)
        keep = []

        def c(text):
            if text is None:
                return ffi.NULL
            b = ffi.new("char[]", str(text).encode())
            keep.append(b)
            return b
        ps = ffi.new("fbrl_runlog_param[]", max(len(params), 1))
        for i, (name, value, unit) in enumerate(params):
            ps[i].name, ps[i].value, ps[i].unit = c(name), int(value), c(unit or None)
        h = ffi.new("fbrl_runlog_header *")
        h.method, h.source, h.operator_id, h.started = c(method), c(source), c(operator), c(started)
        h.controller, h.program, h.calibration = c(controller), c(program), ffi.NULL
        h.params, h.nparams = ps, len(params)
        st = lib.fbrl_runlog_begin(self._log.ptr, self._write, ffi.NULL, self._clock, ffi.NULL, h)
        if st < 0:
            raise Error(st, "run log of %s in %s" % (method, trail.path), detail=self.failed)

    def _sink(self, ctx, s, n):
        if self.trail.append(ffi.unpack(s, n)) == 0:
            return 0
        self.failed = self.failed or "a record was not written"
        return -1

    def event(self, run_ptr, ev_ptr):
        """An event of the run (an fbrl_run_event *): its records (fbrl_runlog_event)."""
        lib.fbrl_runlog_event(self._log.ptr, run_ptr, ev_ptr, self._snap.ptr)

    def command(self, line, result, code=-1, run=0):
        """A line the controller executed (or may have), with the link's result."""
        if isinstance(line, str):
            line = line.encode("latin-1")
        lib.fbrl_runlog_command_run(self._log.ptr, line, len(line), result, code, run)
