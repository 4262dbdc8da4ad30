# SPDX-License-Identifier: MIT
"""Ports and the echo-verified RAPL link to the controller (docs/serial.md, docs/link.md)."""
import contextlib
import numbers
import os
import weakref

from . import _args, _interrupt
from ._ffi import ffi, lib, alloc
from ._errors import Error, ControllerError, FATES, check, status_name, status_code
from .loc import Location
from .stop import Stop

FBRL_OK = 0
FBRL_RAPL_STATUS, FBRL_RAPL_W2, FBRL_RAPL_W5 = 37, 45, 48  # fbrl_rapl_cmd codes (stable)
_ARG_INT, _ARG_REAL, _ARG_STR = 0, 1, 2
_UNITS = {0: "inch", 1: "mm"}  # FBRL_LINK_UNITS_INCH, _MM (fbrl/link.h); -1: not known
_LINE_MOTION, _LINE_FINISH, _LINE_HALT = 0x1, 0x2, 0x4  # FBRL_ROBOT_LINE_* (fbrl/robot.h)
RAPL_LINE_MAX = 96  # FBRL_RAPL_LINE_MAX: the encoder's longest line and its NUL fit
POLL_SLICE_MS = 50  # the longest C waits before Python looks for Ctrl-C again
STILL_POLL_S = 0.05  # between two W5 readings of a moving arm, as the robot words (RB_STILL_POLL_MS)


PORTS_MAX = 64


class PortInfo:
    """A serial port as fbrl.list_ports() finds it: device, by_id (the stable
    /dev/serial/by-id name or None), description, manufacturer, serial, usb, vid, pid,
    driver, latency_timer_ms. name is what to open: the by-id name when there is one."""

    def __init__(self, c):
        text = lambda a: ffi.string(a).decode("utf-8", "replace") or None
        self.device = text(c.device)
        self.by_id = text(c.by_id)
        self.description = text(c.description)
        self.manufacturer = text(c.manufacturer)
        self.serial = text(c.serial)
        self.usb = bool(c.usb)
        self.vid = c.vid if c.usb else None
        self.pid = c.pid if c.usb else None
        self.driver = text(c.driver)
        self.latency_timer_ms = c.latency_timer_ms if c.latency_timer_ms >= 0 else None
        self.name = self.by_id or self.device

    def __repr__(self):
        usb = " [USB %04x:%04x]" % (self.vid, self.pid) if self.usb else ""
        return "PortInfo(%s%s%s)" % (self.name, usb, " serial " + self.serial if self.serial else "")


def list_ports(sysfs_root=None, dev_root=None):
    """The serial ports this machine has (Linux sysfs; nothing is opened)."""
    out = ffi.new("fbrl_port_entry[]", PORTS_MAX)
    n = ffi.new("size_t *")
    check(lib.fbrl_port_list(sysfs_root.encode() if sysfs_root else ffi.NULL,
                             dev_root.encode() if dev_root else ffi.NULL, out, PORTS_MAX, n), "list_ports")
    return [PortInfo(out[i]) for i in range(min(n[0], PORTS_MAX))]


def _option(key, value):
    """A line option as fbrlmon writes it: flow="xonxoff", low_latency=True ("on")."""
    if not isinstance(key, str):
        raise TypeError("port option name: a str, not %s" % type(key).__name__)
    if isinstance(value, bool):
        value = "on" if value else "off"
    elif isinstance(value, numbers.Real):
        value = str(value)
    return key.replace("_", "-"), _args.text(value, "port option " + key)


def _close_port(owned):
    return lib.fbrl_port_close(owned.ptr)


class Port:
    """A serial device, pty or tcp:HOST:PORT, opened with line options (baud=9600,
    parity="even", flow="xonxoff" ...: the names fbrlmon's options use). A context
    manager: leaving the with block closes it; so does dropping it (the device's lock
    goes with it)."""

    def __init__(self, url, **options):
        name = _args.path(url, "Port")
        self.url = os.fsdecode(name)
        self._opt = alloc("fbrl_port_options")
        lib.fbrl_port_options_init(self._opt.ptr)
        for key, value in options.items():
            key, data = _option(key, value)
            check(lib.fbrl_port_set_option(self._opt.ptr, key.encode(), data), "port option %s=%s" % (key, value))
        self._port = alloc("fbrl_port")
        check(lib.fbrl_port_open(self._port.ptr, name, self._opt.ptr), "open " + self.url)
        self._closer = weakref.finalize(self, _close_port, self._port)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    @property
    def _open(self):
        return self._closer.alive

    @property
    def uart(self):
        if not self._open:
            raise ValueError("the port is closed")
        return lib.fbrl_port_uart(self._port.ptr)

    def describe(self):
        """What is open and how: device, line settings."""
        buf = ffi.new("char[]", 512)
        check(lib.fbrl_port_describe(self._port.ptr, buf, 512), "describe " + self.url)
        return ffi.string(buf).decode()

    def close(self):
        if self._open:
            check(self._closer(), "close " + self.url)


class Position:
    """A position read back (W2): kind 'A' actual, pulses, joints (degrees), world Location."""

    def __init__(self, c):
        self.kind = c.kind.decode()
        self.pulses = [c.pulses[i] for i in range(c.npulses)]
        self.joints = [c.joints[i] for i in range(c.njoints)]
        self.world = Location(*[c.world[i] for i in range(6)]) if c.nworld == 6 else None

    def __repr__(self):
        return "Position(kind=%r, pulses=%r, joints=%r, world=%r)" % (self.kind, self.pulses, self.joints, self.world)


class Status:
    """The controller's STATUS block."""

    def __init__(self, c):
        self.last_error = None if c.last_error < 0 else c.last_error
        self.speed = c.speed
        self.homed = bool(c.homed)
        self.naxes = c.naxes
        self.inputs = c.inputs
        self.outputs = c.outputs

    def input(self, n):
        return bool(self.inputs >> (n - 1) & 1)

    def output(self, n):
        return bool(self.outputs >> (n - 1) & 1)

    def __repr__(self):
        return "Status(last_error=%r, speed=%r, homed=%r, inputs=%#x, outputs=%#x)" % (
            self.last_error, self.speed, self.homed, self.inputs, self.outputs)


class Link:
    """The echo-verified command link to a RAPL controller on an open Port. Every command
    runs, or raises fbrl.Error saying whether it ran (.fate); .runs says how many times the
    last one ran (a command safe to repeat whose reply came damaged may run twice).

    Settings (fbrl_link_config, docs/link.md): echo_timeout_ms, reply_timeout_ms,
    wait_timeout_ms, max_attempts, query_reads, naxes, lower_case; None keeps the default.

    Stopping (docs/python.md): a motion or FINISH first waits, reading W5, until the last
    motion has ended, so the controller never waits inside a command, deaf to HALT; Ctrl-C
    during any wait makes the safe stop (safe_stop(): HALT, the outputs this program
    switched on switched off) and then raises KeyboardInterrupt, whose .stop is the report.
    A context manager: Ctrl-C anywhere in the with block stops the arm the same way."""

    SETTINGS = ("lower_case", "echo_timeout_ms", "reply_timeout_ms", "wait_timeout_ms", "max_attempts",
                "query_reads", "naxes")

    def __init__(self, port, connect=True, **settings):
        if not isinstance(port, Port):
            raise TypeError("Link: an fbrl.Port, not %s" % type(port).__name__)
        self.port = port
        self._cfg = alloc("fbrl_link_config")
        lib.fbrl_link_config_init(self._cfg.ptr)
        head = ffi.cast("fbrl_link_config_head *", self._cfg.ptr)
        for key, value in settings.items():
            if key not in self.SETTINGS:
                raise TypeError("Link: no setting %r" % key)
            if value is not None:
                try:
                    setattr(head, key, _args.integer(value, "Link setting " + key))
                except OverflowError:
                    raise ValueError("Link setting %s=%r: out of range" % (key, value)) from None
        self._link = alloc("fbrl_link")
        self._lines = []  # (bytes, flawed) of the command running
        self._exec_observers = []  # on_exec's
        self._errors = []  # exceptions raised inside a callback, for the caller
        self._sig = None  # the Ctrl-C deferral of the call in progress
        # what this program did through the link, as the controller ran it (every line,
        # the Engine's robot words' too): the safe stop's knowledge
        self._outputs_on = 0  # bit n-1: output n switched on
        # the last motion line, until it is seen to end; "": a controller nobody watched may
        # be moving, so the first motion asks first (as fbrl_robot_set_link)
        self._motion = ""
        self._motions = 0  # motion lines run so far
        self.last_stop = None  # the report of the last safe stop
        self._on_line = ffi.callback("void(void *, const char *, size_t, int)", self._line,
                                     onerror=self._callback_failed)
        self._on_exec = ffi.callback("void(void *, const char *, size_t, fbrl_status)", self._exec,
                                     onerror=self._callback_failed)
        check(lib.fbrl_link_init(self._link.ptr, port.uart, self._cfg.ptr), "link")
        check(lib.fbrl_link_set_line_handler(self._link.ptr, self._on_line, ffi.NULL, ffi.NULL, ffi.NULL), "link")
        check(lib.fbrl_link_set_exec_handler(self._link.ptr, self._on_exec, ffi.NULL, ffi.NULL, ffi.NULL), "link")
        if connect:
            self.connect()

    @property
    def ptr(self):
        return self._link.ptr

    @property
    def moving(self):
        """A motion was sent and is not yet seen to end."""
        return self._motion is not None

    def __enter__(self):
        return self

    def __exit__(self, kind, value, tb):
        if isinstance(value, KeyboardInterrupt) and getattr(value, "stop", None) is None:
            self._stopped(value)  # Ctrl-C in the program's own code: the arm too
        return False

    # callbacks: an exception in one is kept for the caller, never lost in C
    def _callback_failed(self, kind, value, tb):
        self._errors.append(value)

    def _raise_kept(self):
        if self._errors:
            e, self._errors = self._errors[0], []
            raise e

    def _line(self, ctx, line, n, flawed):
        self._lines.append((ffi.unpack(line, n), bool(flawed)))

    def on_exec(self, fn):
        """fn(line, result, code, run) for every line the controller executed (or may have),
        on the thread that sent it: the line (bytes), the link's result (an fbrl_status), the
        controller's error code when it refused the line (else -1), and which run of the line
        it was (2: the link typed it again; 0: unknown). Returns fn, for remove_exec(fn)."""
        self._exec_observers = self._exec_observers + [fn]
        return fn

    def remove_exec(self, fn):
        self._exec_observers = [f for f in self._exec_observers if f is not fn]

    def _exec(self, ctx, line, n, result):
        text = ffi.unpack(line, n)
        observers = self._exec_observers
        if observers:
            code, msg = ffi.new("int *", -1), ffi.new("const char **")
            runs, maybe = ffi.new("unsigned *"), ffi.new("unsigned *")
            if status_name(result) == "FBRL_ECONTROLLER":
                lib.fbrl_link_error(self._link.ptr, code, msg)
            lib.fbrl_link_get_runs(self._link.ptr, runs, maybe)
            for fn in observers:
                fn(text, result, code[0], runs[0] + maybe[0])
        effect, on = ffi.new("unsigned *"), ffi.new("uint32_t *")
        lib.fbrl_robot_line_effect(text, effect, on)  # the robot words' own rules
        if result not in (FBRL_OK, status_code("FBRL_EMAYBE")):
            return  # refused: nothing started
        self._outputs_on |= on[0]
        if effect[0] & _LINE_MOTION:
            self._motion = text.decode("latin-1")
            self._motions += 1
        elif effect[0] & (_LINE_FINISH | _LINE_HALT) and result == FBRL_OK:
            self._motion = None

    def _check(self, st, what):
        if st >= 0:
            return st
        fate = FATES.get(lib.fbrl_link_fate_of(st))
        if status_name(st) == "FBRL_ECONTROLLER":
            code, text = ffi.new("int *"), ffi.new("const char **")
            lib.fbrl_link_error(self._link.ptr, code, text)
            raise ControllerError(st, what, code[0], ffi.string(text[0]).decode() if text[0] else None, fate)
        raise Error(st, what, fate=fate)

    @property
    def runs(self):
        """How many times the last command ran on the controller: (proven, may have). More
        than one when the link had to type it again (a damaged reply of a command safe to
        repeat), or a query read until its replies agreed (docs/link.md 3.9)."""
        runs, maybe = ffi.new("unsigned *"), ffi.new("unsigned *")
        lib.fbrl_link_get_runs(self._link.ptr, runs, maybe)
        return (runs[0], maybe[0])

    @property
    def units(self):
        """The controller's units of length as the link last learned them (a STATUS, or METRIC
        sent): "inch", "mm", or None when not known yet (fbrl_link_units)."""
        return _UNITS.get(lib.fbrl_link_units(self._link.ptr))

    # waiting where Ctrl-C can stop the arm
    @contextlib.contextmanager
    def _stopping(self):
        """Ctrl-C in the block: the safe stop, then KeyboardInterrupt carrying its report."""
        if self._sig is not None:
            yield self._sig
            return
        with _interrupt.stopping(self._stopped) as sig:
            self._sig = sig
            try:
                yield sig
            finally:
                self._sig = None

    def _stopped(self, e):
        stop = self.safe_stop()
        e.stop = stop
        e.args = ("stopped: " + str(stop),)

    def _drive(self):
        """Run the started command to its end in slices; Ctrl-C between two ends the wait."""
        done = ffi.new("int *")
        while True:
            st = lib.fbrl_link_poll(self._link.ptr, POLL_SLICE_MS, done)
            self._raise_kept()
            if done[0]:
                return st
            self._sig.check()

    def _run(self, what, start):
        """Start a command (start() returns the status) and run it; its status."""
        if lib.fbrl_link_busy(self._link.ptr):
            self._drive()  # left by a call that was interrupted: the controller has it
        self._lines = []
        st = start()
        self._raise_kept()
        return self._drive() if st == FBRL_OK else st

    def _await_still(self):
        """Until the last motion has ended (a W5 reading all zero): what the robot words do
        before a motion or FINISH (docs/robot.md, "Stopping safely")."""
        while self._motion is not None:
            st = self._run("W5", lambda: lib.fbrl_link_start_stream(self._link.ptr, FBRL_RAPL_W5, 1))
            if status_name(st) == "FBRL_ECONTROLLER":
                self._motion = None  # a controller without W5: its own queue decides
                break
            self._check(st, "W5")
            if any(lib.fbrl_robot_still_line(t, len(t), f) for t, f in self._lines):
                self._motion = None
                break
            self._sig.sleep(STILL_POLL_S)
            self._sig.check()

    def _send(self, line, what, start, unguarded=False):
        """A command line: first, if it moves the arm or waits for it, the wait for rest.
        unguarded: the line goes around the work cell's guard (fbrl_link_unguarded), set
        just before it starts so that the wait's own W5 readings do not take it."""
        effect = ffi.new("unsigned *")
        lib.fbrl_robot_line_effect(line, effect, ffi.NULL)

        def go():
            if unguarded:
                lib.fbrl_link_unguarded(self._link.ptr)
            return start()
        with self._stopping():
            if effect[0] & (_LINE_MOTION | _LINE_FINISH):
                self._await_still()
            return self._check(self._run(what, go), what)

    def connect(self):
        """The start-up handshake: a known, empty command line; NOHELP; STATUS, whose units
        must be inches (FBRL_EUNITS for a controller left in millimetres)."""
        with self._stopping():
            self._check(lib.fbrl_link_connect(self._link.ptr), "connect")

    def command(self, keyword, *args, straight=False, unguarded=False):
        """Run one RAPL command from the library's table, e.g. command("MOVE", "P1"),
        command("SPEED", 50), command("APPRO", "P1", 2.0). Ints, floats and names (str);
        anything else is a TypeError. On a link an Engine with a described work cell shares,
        a motion is refused (FBRL_EGUARD, nothing sent) unless unguarded=True sends it around
        the guard, which the engine's robot is told (docs/workcell.md "The guard")."""
        cmd = ffi.new("int *")
        st = lib.fbrl_rapl_cmd_find(_args.text(keyword, "RAPL command"), cmd)
        if st < 0:
            raise Error(st, "unknown RAPL command %s" % keyword)
        cargs = ffi.new("fbrl_rapl_arg[]", max(len(args), 1))
        keep = []
        for i, a in enumerate(args):
            what = "%s: argument %d" % (keyword, i + 1)
            if isinstance(a, numbers.Integral) and not isinstance(a, bool):
                cargs[i].kind, cargs[i].i = _ARG_INT, int(a)
            elif isinstance(a, numbers.Real) and not isinstance(a, bool):
                cargs[i].kind, cargs[i].r = _ARG_REAL, float(a)
            elif isinstance(a, (str, bytes)):
                s = ffi.new("char[]", _args.text(a, what))
                keep.append(s)
                cargs[i].kind, cargs[i].s = _ARG_STR, s
            else:
                raise TypeError("%s is %r: a RAPL argument is an int, a float or a name (str)" % (what, a))
        straight = 1 if straight else 0
        form, buf, n = ffi.new("int *"), ffi.new("char[]", RAPL_LINE_MAX), ffi.new("size_t *")
        lib.fbrl_link_get_form(self._link.ptr, form)
        st = lib.fbrl_rapl_encode(buf, RAPL_LINE_MAX, n, form[0], cmd[0], cargs, len(args), straight)
        line = ffi.string(buf)
        what = line.decode() if st == FBRL_OK else " ".join([keyword] + [str(a) for a in args])
        if st < 0:
            self._check(st, what)  # refused before anything was sent
        self._send(line, what, lambda: lib.fbrl_link_start_cmd(self._link.ptr, cmd[0], cargs, len(args), straight),
                   unguarded)

    def raw(self, line, unguarded=False):
        """Run a raw command line; returns the lines it printed. A line the link would not
        send (a NUL, a control character, '?', over 80 characters) is a ValueError.
        unguarded: as command()."""
        data = _args.text(line, "raw line")
        if lib.fbrl_link_line_check(data, len(data)) != FBRL_OK:
            raise ValueError("raw line %r: not a line the link sends (printable ASCII, 1 to 80 characters, no '?';"
                             " docs/link.md)" % (line,))
        what = data.decode()
        self._send(data, what, lambda: lib.fbrl_link_start_raw(self._link.ptr, data), unguarded)
        return [t.decode("latin-1") for t, flawed in self._lines]

    # robot commands
    def home(self):
        self.command("HOME")

    def ready(self):
        self.command("READY")

    def speed(self, percent):
        self.command("SPEED", _args.integer(percent, "speed"))

    def move(self, name, straight=False):
        self.command("MOVE", name, straight=straight)

    def appro(self, name, distance):
        self.command("APPRO", name, _args.real(distance, "appro distance"))

    def depart(self, distance):
        self.command("DEPART", _args.real(distance, "depart distance"))

    def point(self, name, loc):
        """Define the controller's location name (POINT name, x, y, z, yaw, pitch, roll)."""
        self.command("POINT", name, *[_args.real(v, "point " + str(name)) for v in loc])

    def finish(self):
        """Wait until the current motion is done (reading W5, where Ctrl-C can stop the arm;
        then FINISH, which returns at once)."""
        self.command("FINISH")

    def halt(self):
        """HALT: the arm stops where it is."""
        self.command("HALT")

    def safe_stop(self):
        """Make the cell safe (fbrl_robot_safe_stop_link, docs/robot.md "Stopping safely"): a
        command the controller already has is let end, HALT, every output this program
        switched on through the link (and its Engines) that is on is switched off, STATUS
        and W2 are read. Never raises for the controller's state: returns the report (Stop)."""
        out = ffi.new("fbrl_robot_stop *")
        motion = self._motion.encode("latin-1") if self._motion is not None else ffi.NULL
        with _interrupt.deferred():  # a second Ctrl-C does not cut the stop short
            lib.fbrl_robot_safe_stop_link(self._link.ptr, self._outputs_on, motion, out)
        self._errors = []  # a callback's failure during the stop: the report says what happened
        self.last_stop = Stop(out)
        return self.last_stop

    def where(self):
        """The arm's actual position (W2)."""
        self._send(b"W2", "W2", lambda: lib.fbrl_link_start_cmd(self._link.ptr, FBRL_RAPL_W2, ffi.NULL, 0, 0))
        return Position(lib.fbrl_link_last_pos(self._link.ptr))

    def status(self):
        self._send(b"STATUS", "STATUS",
                   lambda: lib.fbrl_link_start_cmd(self._link.ptr, FBRL_RAPL_STATUS, ffi.NULL, 0, 0))
        return Status(lib.fbrl_link_last_status(self._link.ptr))

    def _type(self, keyword, expr, kind, call):
        data = _args.text(expr, keyword)
        line = keyword.encode() + b" " + data
        if lib.fbrl_link_line_check(line, len(line)) != FBRL_OK:
            raise ValueError("%s %r: not a line the link sends (printable ASCII, 1 to 80 characters, no '?')"
                             % (keyword, expr))
        v = ffi.new(kind)
        with self._stopping():
            if lib.fbrl_link_busy(self._link.ptr):
                self._drive()
            self._check(call(self._link.ptr, data, v), line.decode())
        return v[0]

    def typei(self, expr):
        return self._type("TYPEI", expr, "long *", lib.fbrl_link_typei)

    def typev(self, expr):
        return self._type("TYPEV", expr, "double *", lib.fbrl_link_typev)

    def input(self, n):
        on = ffi.new("int *")
        n = _args.integer(n, "input")
        with self._stopping():
            if lib.fbrl_link_busy(self._link.ptr):
                self._drive()
            self._check(lib.fbrl_link_input(self._link.ptr, n, on), "input %d" % n)
        return bool(on[0])

    def output(self, n, on):
        """Digital output n on (True) or off."""
        n = _args.integer(n, "output")
        self.command("OUTPUT", n if on else -n)
