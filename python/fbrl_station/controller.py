# SPDX-License-Identifier: MIT
"""The controller connection and the FBRL engine, as the library gives them (python/fbrl):
the emulator or the serial port, the link, the engine whose robot words drive the arm, and
what a failed robot command was in SiLA's terms. Only the owner thread (owner.py) calls it."""
import subprocess

import fbrl

from . import programs

SIM_START_S = 10
SIM_STOP_S = 5
ENGINE_DICT_BYTES = 4 << 20  # the ASPS cell and its methods take about 0.5 MB

# THROW codes of library statuses (fbrl/vm.h: FBRL_VM_THROW_OF_STATUS(st) = -300 + st)
THROW_STATUS_BASE = -300
THROW_STATUS_LOW = -400


class SimProcess:
    """fbrlsim on a pseudo-terminal: the station's emulated controller. FBRL_SIM names the
    program (the launcher sets it), else fbrlsim on PATH."""

    def __init__(self, opts):
        prog = programs.find("fbrlsim", "FBRL_SIM", "the emulator fbrlsim was not found")
        args = [prog, "--status-extra"]  # the robot words read outputs from fbrlsim's STATUS lines
        for opt, value in (("--state", opts.sim_state), ("--model", opts.sim_model),
                           ("--inputs", opts.sim_inputs), ("--log", opts.sim_log),
                           ("--time-scale", opts.sim_time_scale)):
            if value is not None:
                args += [opt, str(value)]
        self.proc = subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True)
        self.port = self.proc.stdout.readline().strip()
        if not self.port.startswith("/dev/"):
            err = self.proc.stderr.read() if self.proc.poll() is not None else ""
            self.stop()
            raise OSError("fbrlsim did not start: %s" % (err.strip() or self.port or "no output"))

    def stop(self):
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=SIM_STOP_S)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self.proc.stdout.close()
        self.proc.stderr.close()


class Controller:
    """The engine, and the controller it drives (emulator or port). .simulation says which."""

    def __init__(self, opts):
        self.opts = opts
        self.engine = fbrl.Engine(dict_bytes=ENGINE_DICT_BYTES)
        self.run = fbrl.Run(self.engine)  # the method, corrective-action and run words, before any file
        self.sim = self.port = self.link = None
        self.simulation = opts.port is None
        self.lost = False

    @property
    def connected(self):
        return self.link is not None and not self.lost

    def connect(self, simulation):
        """Open the emulator (simulation) or the real port, connect the link, give it to the
        engine's robot words. On failure nothing stays open and the engine has no controller."""
        self.disconnect()
        sim = port = None
        try:
            if simulation:
                sim = SimProcess(self.opts)
                url = sim.port
            elif self.opts.port is None:
                raise OSError("no real controller: the station was started without --port")
            else:
                url = self.opts.port
            port = fbrl.Port(url, **self.opts.line)
            link = fbrl.Link(port, **self.opts.link)
        except BaseException:
            if port is not None:
                port.close()
            if sim is not None:
                sim.stop()
            raise
        self.sim, self.port, self.link = sim, port, link
        self.engine.set_link(link)
        self.simulation = simulation
        self.lost = False

    def disconnect(self):
        self.engine.set_link(None)
        if self.port is not None:
            try:
                self.port.close()
            except fbrl.Error:
                pass  # closing a port whose device vanished: nothing left to do
        if self.sim is not None:
            self.sim.stop()
        self.sim = self.port = self.link = None

    def describe(self):
        if self.port is None:
            return "not connected"
        what = self.port.describe()
        return ("emulator (fbrlsim) on " if self.simulation else "") + what

    # ---------------------------------------------------------------- reading the arm
    def where(self):
        """The arm's position (W2): {"world": [x y z yaw pitch roll], "joints": [...]}."""
        pos = self._guarded(self.link.where)
        return {"world": list(pos.world) if pos.world else [], "joints": list(pos.joints)}

    def status(self):
        """The controller's STATUS, with the connection."""
        st = self._guarded(self.link.status)
        code = st.last_error or 0
        text = ""
        if code:
            t = fbrl.lib.fbrl_rapl_error_text(code)
            text = fbrl.ffi.string(t).decode() if t else ""
        return {"connection": self.describe(), "connected": True, "homed": st.homed, "speed": st.speed,
                "last_error": code, "last_error_text": text, "inputs": st.inputs, "outputs": st.outputs}

    def _guarded(self, fn):
        try:
            return fn()
        except fbrl.Error as e:
            if e.name in LOST:
                self.lost = True
            raise

    # ---------------------------------------------------------------- running FBRL
    def eval(self, text, floats=False):
        """Evaluate FBRL text (robot words: every motion passes the guard). Returns what it
        printed (and with floats=True also the float stack it left); raises RobotFailure
        (kind, message) when it failed. The stacks are empty afterwards."""
        before = self.engine.guard[1]
        try:
            out = self.engine.eval(text)
            return (out, self.engine.fstack()) if floats else out
        except fbrl.Error as e:
            kind = classify(e, self.engine.guard[1] > before, self.link)
            if kind == "ControllerLost":
                self.lost = True
            raise RobotFailure(kind, describe(e), e)
        finally:
            self.engine.reset()  # no stack or half definition left from a failed text


LOST = ("FBRL_EDISCONNECTED", "FBRL_ETIMEOUT", "FBRL_EOFFLINE", "FBRL_EIO", "FBRL_EECHO", "FBRL_EPROTOCOL")


class RobotFailure(Exception):
    """A robot command that failed: kind is a defined execution error of the arm features
    (CollisionRefused, ControllerRefused, NotHomed, UnitsMismatch, MayHaveRun, ControllerLost)
    or None for any other failure; message is the library's."""

    def __init__(self, kind, message, error=None):
        super().__init__(message)
        self.kind, self.message, self.error = kind, message, error


def report(e, where):
    """An FBRL error as fbrlmon reports it: "FILE:LINE: error: MESSAGE [in WORD]"."""
    if getattr(e, "file", ""):
        where = "%s:%d" % (e.file, e.line) if e.line else e.file
    text = "%s: error: %s" % (where, getattr(e, "message", None) or e.text)
    word, code = getattr(e, "word", ""), getattr(e, "throw_code", 0)
    if word and code != -39:  # -39, end of file: between words
        text += (" " if code == -13 else " in ") + word  # -13: the undefined word itself
    return text


def throw_status(throw_code):
    """The library status a THROW code stands for (its name), or None."""
    if throw_code is None or not THROW_STATUS_LOW < throw_code <= THROW_STATUS_BASE:
        return None
    return fbrl.status_name(throw_code - THROW_STATUS_BASE)


def classify(e, guard_refused, link):
    """Which defined execution error a failed robot word is, from the library's own record of
    it: the controller's error code, the guard's count of refusals, the link's fate and units."""
    if e.controller_code == 41:
        return "NotHomed"
    if e.controller_code is not None:
        return "ControllerRefused"
    if guard_refused:
        return "CollisionRefused"
    status = throw_status(getattr(e, "throw_code", None)) or e.name
    # ESTATE: the robot words' refusal; EUNITS: the link's own, where it checks units itself
    if status in ("FBRL_ESTATE", "FBRL_EUNITS") and link is not None and link.units == "mm":
        return "UnitsMismatch"
    if status == "FBRL_EMAYBE" or e.fate == "may have run":
        return "MayHaveRun"
    if status in LOST:
        return "ControllerLost"
    return None


def describe(e):
    """The words a client reads: the controller's code and text first when it refused."""
    msg = getattr(e, "message", None) or str(e)
    if e.controller_code is not None:
        return "%03d %s: %s" % (e.controller_code, e.controller_text or "", msg)
    return msg
