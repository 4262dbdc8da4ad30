# SPDX-License-Identifier: MIT
"""fbrl-station's command line, in fbrlmon's style (docs/sila.md, fbrl-station(1))."""
import ipaddress
import os
import sys

USAGE = """usage: fbrl-station [options] [FILE...]
Serve one robot arm to lab schedulers over SiLA 2 (gRPC, TLS): the station owns the
controller's link and the FBRL engine; the FILEs and -e texts (the work cell, its sites)
run first, in order, then it serves until Ctrl-C or SIGTERM.

options:
  -e TEXT          evaluate TEXT (in order with the FILEs; also -eTEXT)
  --port PATH      controller on a serial device, pty or tcp:HOST:PORT
  --baud N         line speed (default 9600)
  --data-bits N    5, 6, 7 or 8 (default 8)
  --parity P       none, even or odd (default none)
  --stop-bits N    1 or 2 (default 1)
  --flow F         none or xonxoff (default xonxoff)
  --low-latency on|off  USB-serial low-latency mode (default on)
  --axes N         the arm's axes (default 5; the emulator's own with --sim)
  --sim            the emulated controller, fbrlsim (the default without --port)
  --sim-state FILE the emulator's persistent memory (default: none kept)
  --sim-model M    the emulated arm: a255 (default) or a465 (6 axes)
  --sim-inputs FILE the emulator's inputs over time, lines "T IN n v"
  --sim-log FILE   the emulator's log of the commands it executed (fbrlsim --log)
  --sim-time-scale N  the emulator's time runs N times faster (fbrlsim --time-scale)
  --sila HOST:PORT|off  serve SiLA 2 there (default 127.0.0.1:50052; port 0: any free
                   port, printed at start)
  --insecure       plain gRPC without TLS (a warning on every start)
  --data DIR       the station's UUID, name, TLS key and certificate, taught places
                   (default $XDG_DATA_HOME/fbrl-station/PORT, ~/.local/share/...)
  --methods DIR    the method library (default: methods)
  --http HOST:PORT|off  the page in a browser (default 127.0.0.1:8080; port 0: any free port,
                   printed at start); beyond loopback only with --lab
  --lab DIR        the lab's users sign in to the page, served over HTTPS/WSS with the
                   station's certificate; runs are checked (Released methods) and recorded
                   in the lab's audit trail (default $FBRL_LAB; as fbrlmon --lab)
  --no-discovery   do not announce the station over mDNS (_sila._tcp)
  -h, --help       show this help and exit
  -V, --version    show the version and exit
  (a long option's value may follow '=': --sila=0.0.0.0:50052; an unambiguous prefix
  of a long option's name is enough: --no-d)

exit status: 0 stopped by a signal, 1 an error aborted a file or -e text, 2 bad command
             line, 3 could not start
"""

DEFAULT_SILA = ("127.0.0.1", 50052)
DEFAULT_HTTP = ("127.0.0.1", 8080)
# long options: name -> (takes a value, attribute)
OPTIONS = {
    "port": True, "baud": True, "data-bits": True, "parity": True, "stop-bits": True, "flow": True,
    "low-latency": True, "axes": True, "sim": False, "sim-state": True, "sim-model": True, "sim-inputs": True,
    "sim-log": True, "sim-time-scale": True, "sila": True, "insecure": False, "data": True, "methods": True,
    "http": True, "lab": True, "no-discovery": False, "help": False, "version": False,
}
LINE_OPTIONS = ("baud", "data-bits", "parity", "stop-bits", "flow", "low-latency")


class UsageError(Exception):
    pass


class Options:
    def __init__(self):
        self.port = None
        self.line = {}  # fbrl.Port options
        self.link = {}  # fbrl.Link settings
        self.sim = False
        self.sim_state = self.sim_model = self.sim_inputs = self.sim_log = self.sim_time_scale = None
        self.sila = DEFAULT_SILA
        self.insecure = False
        self.data = None
        self.methods = "methods"
        self.http = DEFAULT_HTTP
        self.lab = None  # the lab folder whose users sign in to the page (TLS then)
        self.discovery = True
        self.actions = []  # ("eval", text) and ("file", path), in command-line order
        self.help = self.version = False


def is_loopback(host):
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def host_port(opt, value):
    """HOST:PORT (IPv6 in brackets) or off (None)."""
    if value == "off":
        return None
    host, sep, port = value.rpartition(":")
    host = host[1:-1] if host.startswith("[") and host.endswith("]") else host
    if not sep or not host or not port.isdigit() or int(port) > 65535:
        raise UsageError("--%s needs HOST:PORT or off, not %r" % (opt, value))
    return host, int(port)


def _number(opt, value, lo, hi, kind=int):
    try:
        v = kind(value)
    except ValueError:
        v = None
    if v is None or not lo <= v <= hi:
        raise UsageError("--%s needs a number in %s..%s, not %r" % (opt, lo, hi, value))
    return v


def _long(arg):
    """(name, value or None) of a --name[=value] argument, the name completed from a prefix."""
    name, eq, value = arg[2:].partition("=")
    if name not in OPTIONS:
        matches = [o for o in OPTIONS if o.startswith(name)]
        if len(matches) != 1:
            raise UsageError("unknown option --%s%s" % (name, "" if not matches else
                                                           " (could be --%s)" % ", --".join(matches)))
        name = matches[0]
    return name, (value if eq else None)


def parse(argv):
    o = Options()
    i = 0
    while i < len(argv):
        arg = argv[i]
        i += 1
        if arg == "-e" or (arg.startswith("-e") and not arg.startswith("--")):
            if arg == "-e":
                if i >= len(argv):
                    raise UsageError("-e needs a text")
                arg, i = "-e" + argv[i], i + 1
            o.actions.append(("eval", arg[2:]))
            continue
        if arg in ("-h",):
            o.help = True
            continue
        if arg in ("-V",):
            o.version = True
            continue
        if arg == "--":
            o.actions += [("file", a) for a in argv[i:]]
            break
        if not arg.startswith("--") or arg == "-":
            if arg.startswith("-") and arg != "-":
                raise UsageError("unknown option %s" % arg)
            o.actions.append(("file", arg))
            continue
        name, value = _long(arg)
        if OPTIONS[name]:
            if value is None:
                if i >= len(argv):
                    raise UsageError("--%s needs a value" % name)
                value, i = argv[i], i + 1
        elif value is not None:
            raise UsageError("--%s takes no value" % name)
        _apply(o, name, value)
    if o.sim and o.port is not None:
        raise UsageError("--sim and --port: choose one controller")
    if o.sila is None and o.http is None and not (o.help or o.version):
        raise UsageError("--sila off and --http off: nothing to serve")
    return o


def _apply(o, name, value):
    if name in LINE_OPTIONS:
        o.line[name.replace("-", "_")] = value
    elif name == "axes":
        o.link["naxes"] = _number(name, value, 1, 8)
    elif name == "sim-time-scale":
        o.sim_time_scale = _number(name, value, 0.001, 1e6, float)
    elif name == "sila":
        o.sila = host_port(name, value)
    elif name == "http":
        o.http = host_port(name, value)
    elif name == "no-discovery":
        o.discovery = False
    elif name in ("sim", "insecure", "help", "version"):
        setattr(o, name, True)
    else:
        setattr(o, name.replace("-", "_"), value)


def check_page(o):
    """Beyond loopback the page needs the lab's users (a sign-in) and TLS: --lab, and not
    --insecure (the station's certificate is its TLS; --insecure says there is none)."""
    if o.http is None or is_loopback(o.http[0]):
        return
    where = "%s:%d" % o.http
    if o.lab is None:
        raise UsageError("--http %s: beyond loopback the page needs the lab's users to sign in: give --lab DIR "
                         "(or FBRL_LAB), or serve it on 127.0.0.1 or ::1" % where)
    if o.insecure:
        raise UsageError("--http %s: beyond loopback the page is served over TLS with the station's certificate, "
                         "and --insecure turns TLS off: leave --insecure out, or serve the page on 127.0.0.1 or ::1"
                         % where)


def default_data(sila):
    """$XDG_DATA_HOME/fbrl-station/PORT: stations on one host keep apart by their port."""
    base = os.environ.get("XDG_DATA_HOME") or os.path.join(os.path.expanduser("~"), ".local", "share")
    return os.path.join(base, "fbrl-station", str(sila[1] if sila else "http"))


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    try:
        opts = parse(argv)
    except UsageError as e:
        sys.stderr.write("fbrl-station: %s\n(fbrl-station --help lists the options)\n" % e)
        return 2
    if opts.help:
        sys.stdout.write(USAGE)
        return 0
    if opts.version:
        import fbrl
        sys.stdout.write("fbrl-station (libfbrl) %s\n" % fbrl.version())
        return 0
    if opts.lab is None and os.environ.get("FBRL_LAB"):
        opts.lab = os.environ["FBRL_LAB"]
    try:
        check_page(opts)
    except UsageError as e:
        sys.stderr.write("fbrl-station: %s\n" % e)
        return 2
    if opts.data is None:
        opts.data = default_data(opts.sila)
    from .server import run
    return run(opts)
