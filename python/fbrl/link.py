# SPDX-License-Identifier: MIT
"""Ports and the echo-verified RAPL link to the controller (docs/serial.md, docs/link.md)."""
import os

from ._ffi import ffi, lib, alloc
from ._errors import Error, ControllerError, FATES, check, status_name
from .loc import Location

FBRL_RAPL_W2 = 45  # fbrl_rapl_cmd codes (stable): the actual position
_ARG_INT, _ARG_REAL, _ARG_STR = 0, 1, 2


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


class Port:
    """A serial device, pty or tcp:HOST:PORT, opened with line options (baud=9600,
    parity="even", flow="xonxoff" ...: the names fbrlmon's options use). A context
    manager: leaving the with block closes it."""

    def __init__(self, url, **options):
        self.url = os.fspath(url)
        self._opt = alloc("fbrl_port_options")
        lib.fbrl_port_options_init(self._opt.ptr)
        for key, value in options.items():
            key = key.replace("_", "-")
            check(lib.fbrl_port_set_option(self._opt.ptr, key.encode(), str(value).encode()),
                  "port option %s=%s" % (key, value))
        self._port = alloc("fbrl_port")
        check(lib.fbrl_port_open(self._port.ptr, self.url.encode(), self._opt.ptr), "open " + self.url)
        self._open = True

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

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
            self._open = False
            check(lib.fbrl_port_close(self._port.ptr), "close " + self.url)


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
    wait_timeout_ms, max_attempts, query_reads, naxes, lower_case; None keeps the default."""

    SETTINGS = ("lower_case", "echo_timeout_ms", "reply_timeout_ms", "wait_timeout_ms", "max_attempts",
                "query_reads", "naxes")

    def __init__(self, port, connect=True, **settings):
        self.port = port
        self._cfg = alloc("fbrl_link_config")
        lib.fbrl_link_config_init(self._cfg.ptr)
        head = ffi.cast("fbrl_link_config_head *", self._cfg.ptr)
        for key, value in settings.items():
            if key not in self.SETTINGS:
                raise TypeError("Link: no setting %r" % key)
            if value is not None:
                setattr(head, key, int(value))
        self._link = alloc("fbrl_link")
        self._lines = []
        self._on_line = ffi.callback("void(void *, const char *, size_t, int)", self._line)
        check(lib.fbrl_link_init(self._link.ptr, port.uart, self._cfg.ptr), "link")
        check(lib.fbrl_link_set_line_handler(self._link.ptr, self._on_line, ffi.NULL, ffi.NULL, ffi.NULL), "link")
        if connect:
            self.connect()

    @property
    def ptr(self):
        return self._link.ptr

    def _line(self, ctx, line, n, flawed):
        self._lines.append(ffi.unpack(line, n).decode("latin-1"))

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

    def connect(self):
        """The start-up handshake: a known, empty command line; NOHELP; STATUS, whose units
        must be inches (FBRL_EUNITS for a controller left in millimetres)."""
        self._check(lib.fbrl_link_connect(self._link.ptr), "connect")

    def command(self, keyword, *args, straight=False):
        """Run one RAPL command from the library's table, e.g. command("MOVE", "P1"),
        command("SPEED", 50), command("APPRO", "P1", 2.0). Ints, floats and names."""
        cmd = ffi.new("int *")
        st = lib.fbrl_rapl_cmd_find(keyword.encode(), cmd)
        if st < 0:
            raise Error(st, "unknown RAPL command " + keyword)
        cargs = ffi.new("fbrl_rapl_arg[]", max(len(args), 1))
        keep = []
        for i, a in enumerate(args):
            if isinstance(a, bool) or isinstance(a, int):
                cargs[i].kind, cargs[i].i = _ARG_INT, int(a)
            elif isinstance(a, float):
                cargs[i].kind, cargs[i].r = _ARG_REAL, a
            else:
                s = ffi.new("char[]", str(a).encode())
                keep.append(s)
                cargs[i].kind, cargs[i].s = _ARG_STR, s
        what = " ".join([keyword] + [str(a) for a in args])
        self._check(lib.fbrl_link_cmd(self._link.ptr, cmd[0], cargs, len(args), 1 if straight else 0), what)

    def raw(self, line):
        """Run a raw command line; returns the lines it printed."""
        self._lines = []
        self._check(lib.fbrl_link_raw(self._link.ptr, line.encode()), line)
        return list(self._lines)

    # robot commands
    def home(self):
        self.command("HOME")

    def ready(self):
        self.command("READY")

    def speed(self, percent):
        self.command("SPEED", int(percent))

    def move(self, name, straight=False):
        self.command("MOVE", name, straight=straight)

    def appro(self, name, distance):
        self.command("APPRO", name, float(distance))

    def depart(self, distance):
        self.command("DEPART", float(distance))

    def point(self, name, loc):
        """Define the controller's location name (POINT name, x, y, z, yaw, pitch, roll)."""
        self.command("POINT", name, *[float(v) for v in loc])

    def finish(self):
        """Wait until the current motion is done."""
        self._check(lib.fbrl_link_finish(self._link.ptr), "FINISH")

    def where(self):
        """The arm's actual position (W2)."""
        pos = ffi.new("fbrl_rapl_pos *")
        self._check(lib.fbrl_link_where(self._link.ptr, FBRL_RAPL_W2, pos), "W2")
        return Position(pos)

    def status(self):
        out = ffi.new("fbrl_rapl_status_info *")
        self._check(lib.fbrl_link_status(self._link.ptr, out), "STATUS")
        return Status(out)

    def typei(self, expr):
        v = ffi.new("long *")
        self._check(lib.fbrl_link_typei(self._link.ptr, expr.encode(), v), "TYPEI " + expr)
        return v[0]

    def typev(self, expr):
        v = ffi.new("double *")
        self._check(lib.fbrl_link_typev(self._link.ptr, expr.encode(), v), "TYPEV " + expr)
        return v[0]

    def input(self, n):
        on = ffi.new("int *")
        self._check(lib.fbrl_link_input(self._link.ptr, n, on), "input %d" % n)
        return bool(on[0])

    def output(self, n, on):
        """Digital output n on (True) or off."""
        self.command("OUTPUT", n if on else -n)
