# SPDX-License-Identifier: MIT
"""The FBRL language engine: evaluate text, read and set the stacks (docs/language.md)."""
import os
import time

from ._ffi import ffi, lib, alloc
from ._errors import Error, ControllerError, check, status_name

DICT_BYTES_DEFAULT = 1 << 20
FILE_STORAGE_BYTES = 1 << 20  # the glossary's data-file buffers (OPEN-FILE)
SLEEP_SLICE_S = 0.05  # a timed wait looks for an interrupt this often


class Engine:
    """One FBRL system (a Forth VM with FBRL's data, location, calibration and file words,
    and the robot words bound to link, or offline when link is None).

        with fbrl.Engine() as fb:
            fb.eval("CREATE-LOC P 1.0 2.0 3.0 0.0 -90.0 0.0 P DEFINE-LOC P GETY")
            fb.fstack()      # [2.0]

    eval() returns what the text printed; an error raises fbrl.Error with the Forth
    THROW code, message, word, file and line (and the controller's error code and text
    when the controller refused a robot command)."""

    def __init__(self, link=None, dict_bytes=DICT_BYTES_DEFAULT):
        self.link = link
        self._out = []
        self._files = {}
        cfg = ffi.new("fbrl_vm_config *")
        cb = self._callbacks = [
            ffi.callback("void(void *, const char *, size_t)", self._write),
            ffi.callback("fbrl_status(void *, const char *, void **)", self._file_open),
            ffi.callback("fbrl_status(void *, void *, char *, size_t, size_t *)", self._file_read_line),
            ffi.callback("void(void *, void *)", self._file_close),
            ffi.callback("uint64_t(void *)", lambda user: lib.fbrl_clock_now_us()),
            ffi.callback("void(void *, uint32_t)", self._sleep_ms),
        ]
        cfg.host.write, cfg.host.file_open, cfg.host.file_read_line, cfg.host.file_close = cb[:4]
        cfg.host.now_us, cfg.host.sleep_ms = cb[4], cb[5]
        size = lib.fbrl_vm_size_for(cfg, dict_bytes)
        self._mem = ffi.new("char[]", size + 16)  # zeroed
        addr = int(ffi.cast("uintptr_t", self._mem))
        cfg.mem = ffi.cast("void *", addr + (-addr) % 16)  # the VM wants 16-byte alignment
        cfg.mem_size = size
        cfg.mem_zeroed = 1
        vm = ffi.new("fbrl_vm **")
        check(lib.fbrl_vm_create(vm, cfg), "Engine")
        self._vm = vm[0]
        self._glossary = alloc("fbrl_glossary")
        self._robot = alloc("fbrl_robot")
        self._file_mem = ffi.new("char[]", FILE_STORAGE_BYTES)
        check(lib.fbrl_glossary_install(self._vm, self._glossary.ptr), "Engine glossary")
        check(lib.fbrl_glossary_set_file_storage(self._glossary.ptr, self._file_mem, FILE_STORAGE_BYTES),
              "Engine glossary")
        check(lib.fbrl_robot_install(self._vm, self._robot.ptr, link.ptr if link else ffi.NULL,
                                     self._glossary.ptr), "Engine robot words")
        # the work cell (CELL-BOX ...) and its guard over every robot motion, as in fbrlmon
        self._cell = alloc("fbrl_cell_words")
        check(lib.fbrl_cell_install(self._vm, self._cell.ptr, self._robot.ptr, self._glossary.ptr),
              "Engine cell words")

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def close(self):
        """Closes the source files an interrupted INCLUDED left open."""
        for f in self._files.values():
            f.close()
        self._files.clear()

    # host callbacks
    def _write(self, user, s, n):
        self._out.append(ffi.unpack(s, n).decode("latin-1"))

    def _sleep_ms(self, user, ms):
        # in slices, so interrupt() from another thread ends a timed wait within one
        end = time.monotonic() + ms / 1000.0
        while not lib.fbrl_vm_interrupt_pending(self._vm):
            left = end - time.monotonic()
            if left <= 0:
                break
            time.sleep(min(left, SLEEP_SLICE_S))

    def _file_open(self, user, path, handle):
        try:
            f = open(ffi.string(path).decode(), "rb")
        except OSError:
            return _status("FBRL_ENOENT")
        key = len(self._files) + 1
        while key in self._files:
            key += 1
        self._files[key] = f
        handle[0] = ffi.cast("void *", key)
        return 0

    def _file_read_line(self, user, handle, buf, cap, n):
        f = self._files[int(ffi.cast("uintptr_t", handle))]
        line = f.readline()
        if not line:
            return _status("FBRL_EEOF")
        line = line.rstrip(b"\r\n")
        if len(line) > cap:
            return _status("FBRL_ENOSPC")
        ffi.memmove(buf, line, len(line))
        n[0] = len(line)
        return 0

    def _file_close(self, user, handle):
        f = self._files.pop(int(ffi.cast("uintptr_t", handle)), None)
        if f:
            f.close()

    def _fail(self, st, what):
        err = lib.fbrl_vm_last_error(self._vm)
        msg = ffi.string(err.message).decode("latin-1")
        word = ffi.string(err.word).decode("latin-1")
        where = ffi.string(err.file).decode("latin-1")
        detail = "%s (THROW %d%s%s)" % (msg, err.throw_code, ", in " + word if word else "",
                                       ", %s:%d" % (where, err.line) if where else "")
        code = lib.fbrl_robot_last_error(self._robot.ptr)
        cls = Error
        ccode = ctext = None
        # a robot word the controller refused ends the text with FBRL_ECONTROLLER
        if code >= 0 and status_name(st) == "FBRL_ECONTROLLER":
            cls, ccode = ControllerError, code
            t = lib.fbrl_rapl_error_text(code)
            ctext = ffi.string(t).decode() if t else None
        e = cls(st, what, ccode, ctext, detail=detail)
        e.throw_code = err.throw_code
        e.message = msg
        e.word = word
        e.file = where
        e.line = err.line
        e.output = "".join(self._out)
        raise e

    def eval(self, text):
        """Interpret text as if typed; returns what it printed."""
        self._out = []
        data = text.encode()
        st = lib.fbrl_vm_eval(self._vm, data, len(data))
        if st < 0:
            self._fail(st, text if len(text) < 60 else text[:57] + "...")
        return "".join(self._out)

    def include(self, path):
        """INCLUDED: interpret a source file; returns what it printed."""
        self._out = []
        st = lib.fbrl_vm_include(self._vm, os.fspath(path).encode())
        if st < 0:
            self._fail(st, "include " + os.fspath(path))
        return "".join(self._out)

    def set_link(self, link):
        """Drive another controller (or none: None) from now on, e.g. after the port was
        reopened; the dictionary, the cell and the places stay as they are."""
        check(lib.fbrl_robot_set_link(self._robot.ptr, link.ptr if link else ffi.NULL), "set_link")
        self.link = link

    def interrupt(self):
        """Ask a running eval()/include() to stop (THROW -28 at its next word; a wait for the
        arm returns early). The one call that is safe from another thread."""
        lib.fbrl_vm_interrupt(self._vm)

    @property
    def guard(self):
        """The collision guard's record: (motions checked and sent, motions refused)."""
        st = lib.fbrl_cell_stats_get(self._cell.ptr)
        return st.moves, st.refused

    @property
    def bye(self):
        """True once the text ran BYE."""
        return bool(lib.fbrl_vm_bye(self._vm))

    def reset(self):
        """Back to a clean prompt: stacks emptied, an unfinished definition dropped."""
        lib.fbrl_vm_reset(self._vm)

    # the stacks
    def stack(self):
        """The data stack, bottom first (left as it is)."""
        vals = []
        v = ffi.new("fbrl_cell *")
        while lib.fbrl_vm_depth(self._vm):
            check(lib.fbrl_vm_pop(self._vm, v), "stack")
            vals.append(v[0])
        vals.reverse()
        for x in vals:
            check(lib.fbrl_vm_push(self._vm, x), "stack")
        return vals

    def fstack(self):
        """The floating-point stack, bottom first (left as it is)."""
        vals = []
        v = ffi.new("double *")
        while lib.fbrl_vm_fdepth(self._vm):
            check(lib.fbrl_vm_fpop(self._vm, v), "fstack")
            vals.append(v[0])
        vals.reverse()
        for x in vals:
            check(lib.fbrl_vm_fpush(self._vm, x), "fstack")
        return vals

    def push(self, *values):
        for x in values:
            if isinstance(x, float):
                check(lib.fbrl_vm_fpush(self._vm, x), "push")
            else:
                check(lib.fbrl_vm_push(self._vm, int(x)), "push")

    def pop(self):
        v = ffi.new("fbrl_cell *")
        check(lib.fbrl_vm_pop(self._vm, v), "pop")
        return v[0]

    def fpop(self):
        v = ffi.new("double *")
        check(lib.fbrl_vm_fpop(self._vm, v), "fpop")
        return v[0]


_STATUS = {}


def _status(name):
    """A status code by name (the library's own table: codes are never hard-coded twice)."""
    if not _STATUS:
        for st in range(0, -200, -1):
            n = ffi.string(lib.fbrl_status_name(st)).decode()
            if n.startswith("FBRL_") and n not in _STATUS:
                _STATUS[n] = st
    return _STATUS[name]
