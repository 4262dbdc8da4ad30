# SPDX-License-Identifier: MIT
"""The FBRL language engine: evaluate text, read and set the stacks (docs/language.md)."""
import os
import stat
import time

from . import _args, _interrupt
from ._ffi import ffi, lib, alloc
from ._errors import Error, ControllerError, check, status_name, status_code
from .link import Link

FBRL_OK = 0

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
    when the controller refused a robot command). Ctrl-C while it runs ends the text
    (THROW -28), makes the link's safe stop and raises KeyboardInterrupt (.stop: the
    report). After BYE the engine is over: eval() and include() raise."""

    def __init__(self, link=None, dict_bytes=DICT_BYTES_DEFAULT):
        if link is not None and not isinstance(link, Link):
            raise TypeError("Engine: link is an fbrl.Link or None, not %s" % type(link).__name__)
        dict_bytes = _args.integer(dict_bytes, "Engine dict_bytes")
        self.link = link
        self._out = []
        self._files = {}
        self._errors = []  # exceptions raised inside a callback, for the caller
        self.moving_error = None  # the last exception of the on_moving() watcher
        self._sig = None  # the Ctrl-C deferral of the evaluation in progress
        self._link_motions = link._motions if link else 0  # the link's motions this engine knows of
        cfg = ffi.new("fbrl_vm_config *")
        st_io = status_code("FBRL_EIO")
        kept = self._callback_failed
        cb = self._callbacks = [
            ffi.callback("void(void *, const char *, size_t)", self._write, onerror=kept),
            ffi.callback("fbrl_status(void *, const char *, void **)", self._file_open, error=st_io, onerror=kept),
            ffi.callback("fbrl_status(void *, void *, char *, size_t, size_t *)", self._file_read_line, error=st_io,
                         onerror=kept),
            ffi.callback("void(void *, void *)", self._file_close, onerror=kept),
            ffi.callback("uint64_t(void *)", lambda user: lib.fbrl_clock_now_us(), onerror=self._clock_failed),
            ffi.callback("void(void *, uint32_t)", self._sleep_ms, onerror=kept),
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
        # the work cell's words and the guard on every motion (docs/workcell.md)
        self._cell = alloc("fbrl_cell_words")
        check(lib.fbrl_cell_install(self._vm, self._cell.ptr, self._robot.ptr, self._glossary.ptr),
              "Engine cell words")

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def close(self):
        """Closes the source files an interrupted INCLUDED left open, and takes the robot
        words' gate off the link (the link goes on without this engine)."""
        for f in self._files.values():
            f.close()
        self._files.clear()
        if getattr(self, "link", None) is not None and hasattr(self, "_robot"):
            lib.fbrl_robot_set_link(self._robot.ptr, ffi.NULL)
            self.link = None

    def __del__(self):
        try:
            self.close()
        except Exception:  # at interpreter exit the module's globals may be gone already
            pass

    # host callbacks: an exception in one is an error status for the engine and is kept
    # for the caller (raised, or the cause of the error eval() raises), never lost
    def _callback_failed(self, kind, value, tb):
        self._errors.append(value)
        if isinstance(value, KeyboardInterrupt):
            lib.fbrl_vm_interrupt(self._vm)  # as the deferral does: the text ends

    def _clock_failed(self, kind, value, tb):
        self._callback_failed(kind, value, tb)
        return lib.fbrl_clock_now_us()

    def _write(self, user, s, n):
        self._out.append(ffi.unpack(s, n).decode("latin-1"))

    def _sleep_ms(self, user, ms):
        # in slices, so interrupt() from another thread ends a timed wait within one; Ctrl-C
        # ends it at once
        end = time.monotonic() + ms / 1000.0
        while not lib.fbrl_vm_interrupt_pending(self._vm):
            left = end - time.monotonic()
            if left <= 0:
                break
            if self._sig is not None:
                self._sig.sleep(min(left, SLEEP_SLICE_S))
                if self._sig.fired:
                    break
            else:
                time.sleep(min(left, SLEEP_SLICE_S))

    def _file_open(self, user, path, handle):
        """Only a regular file, as fbrlmon (a device never ends, a FIFO blocks); the name's
        bytes as they are (a name that is not UTF-8 is still a name)."""
        try:
            fd = os.open(ffi.string(path), os.O_RDONLY | os.O_NONBLOCK)  # a FIFO's open would block
        except (FileNotFoundError, NotADirectoryError):
            return status_code("FBRL_ENOENT")
        except PermissionError:
            return status_code("FBRL_EPERM")
        except OSError:
            return status_code("FBRL_EIO")
        try:
            if not stat.S_ISREG(os.fstat(fd).st_mode):
                os.close(fd)
                return status_code("FBRL_ENOTFILE")
            os.set_blocking(fd, True)
            f = os.fdopen(fd, "rb")
        except BaseException:
            os.close(fd)
            raise
        key = len(self._files) + 1
        while key in self._files:
            key += 1
        self._files[key] = f
        handle[0] = ffi.cast("void *", key)
        return FBRL_OK

    def _file_read_line(self, user, handle, buf, cap, n):
        """One line without its end; longer than cap is FBRL_ENOSPC as soon as cap is passed
        (fbrlmon's rule: a file without line ends is never read whole)."""
        f = self._files[int(ffi.cast("uintptr_t", handle))]
        line = f.readline(cap + 2)  # cap bytes, a CR and the LF
        if not line:
            return status_code("FBRL_EEOF")
        body = line[:-1] if line.endswith(b"\n") else line
        if body.endswith(b"\r"):
            body = body[:-1]
        if len(body) > cap:
            return status_code("FBRL_ENOSPC")
        ffi.memmove(buf, body, len(body))
        n[0] = len(body)
        return FBRL_OK

    def _file_close(self, user, handle):
        f = self._files.pop(int(ffi.cast("uintptr_t", handle)), None)
        if f:
            f.close()

    def _fail(self, st, what, cause):
        err = lib.fbrl_vm_last_error(self._vm)
        msg = ffi.string(err.message).decode("latin-1")
        word = ffi.string(err.word).decode("latin-1")
        where = ffi.string(err.file).decode("latin-1")
        detail = "%s (THROW %d%s%s)" % (msg, err.throw_code, ", in " + word if word else "",
                                       ", %s:%d" % (where, err.line) if where else "")
        if cause is not None:
            detail += "; in the Python host: %s: %s" % (type(cause).__name__, cause)
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
        raise e from cause

    def _stopped(self, e):
        """Ctrl-C ended the text: the link's safe stop (everything this program switched on
        through it); the robot words then take nothing for granted about the arm."""
        e.output = "".join(self._out)
        if self.link is None:
            return  # offline: nothing to stop
        self.link._stopped(e)
        lib.fbrl_robot_set_link(self._robot.ptr, self.link.ptr)

    def _evaluate(self, what, call):
        if lib.fbrl_vm_bye(self._vm):
            raise Error(status_code("FBRL_ESTATE"), what, detail="the engine ran BYE: start a new Engine")
        if self.link is not None and self.link._motions != self._link_motions:
            # the arm was moved through the link outside this engine: its robot words ask
            # the controller first (a motion may still run) and the guard reads the arm
            lib.fbrl_robot_set_link(self._robot.ptr, self.link.ptr)
        self._out = []
        self._errors = []
        with _interrupt.stopping(self._stopped, wake=lambda: lib.fbrl_vm_interrupt(self._vm)) as sig:
            self._sig = sig
            try:
                st = call()
                for e in self._errors:
                    if isinstance(e, KeyboardInterrupt):
                        raise e
            finally:
                self._sig = None
                if self.link is not None:
                    self._link_motions = self.link._motions
        cause = self._errors[0] if self._errors else None
        if st < 0:
            self._fail(st, what, cause)
        if cause is not None:
            raise cause  # a callback with no status to give failed: the text ran without it
        return "".join(self._out)

    def eval(self, text):
        """Interpret text as if typed; returns what it printed."""
        if not isinstance(text, str):
            raise TypeError("eval: a str, not %s" % type(text).__name__)
        data = text.encode()
        return self._evaluate(text if len(text) < 60 else text[:57] + "...",
                              lambda: lib.fbrl_vm_eval(self._vm, data, len(data)))

    def include(self, path):
        """INCLUDED: interpret a source file; returns what it printed. Only a regular file
        is read (not a device or a FIFO), a line at a time, each at most the engine's line."""
        name = _args.path(path, "include")
        return self._evaluate("include " + os.fsdecode(name), lambda: lib.fbrl_vm_include(self._vm, name))

    def set_link(self, link):
        """Drive another controller (or none: None) from now on, e.g. after the port was
        reopened; the dictionary, the cell and the places stay as they are."""
        check(lib.fbrl_robot_set_link(self._robot.ptr, link.ptr if link else ffi.NULL), "set_link")
        self.link = link
        self._link_motions = link._motions if link else 0

    def on_moving(self, fn):
        """fn() while a robot word waits for the arm to stop, about once a second, with the
        link free for a reading (link.where() reads the arm as it moves); it must not move
        the arm. None: nobody. An exception in fn is kept in .moving_error and the wait goes
        on: a live view that cannot read is not an error of the method."""
        if fn is None:
            lib.fbrl_robot_set_watch(self._robot.ptr, ffi.NULL, ffi.NULL)
            self._moving_cb = None
            return

        def failed(kind, value, tb):
            self.moving_error = value

        self._moving_cb = ffi.callback("void(void *, fbrl_robot *)", lambda ctx, r: fn(), onerror=failed)
        lib.fbrl_robot_set_watch(self._robot.ptr, self._moving_cb, ffi.NULL)

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
        """Push each value: a float on the floating-point stack, an int on the data stack."""
        for x in values:
            if isinstance(x, float):
                check(lib.fbrl_vm_fpush(self._vm, x), "push")
            else:
                try:
                    check(lib.fbrl_vm_push(self._vm, _args.integer(x, "push")), "push")
                except OverflowError:
                    raise ValueError("push: %r does not fit a cell" % (x,)) from None

    def pop(self):
        v = ffi.new("fbrl_cell *")
        check(lib.fbrl_vm_pop(self._vm, v), "pop")
        return v[0]

    def fpop(self):
        v = ffi.new("double *")
        check(lib.fbrl_vm_fpop(self._vm, v), "fpop")
        return v[0]
