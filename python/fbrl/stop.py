# SPDX-License-Identifier: MIT
"""fbrl.Stop: what a safe stop found and did (fbrl_robot_stop, docs/robot.md "Stopping safely")."""
from ._ffi import ffi
from ._errors import status_name, status_text
from .loc import Location

IO_MAX = 16  # FBRL_LINK_IO_MAX: outputs 1..16


def _outputs(bits):
    return [n for n in range(1, IO_MAX + 1) if bits >> (n - 1) & 1]


def _ranges(ns):
    """[1, 2, 3, 5] as "1-3 5", as fbrlmon's stop says it."""
    out, k = [], 0
    while k < len(ns):
        j = k
        while j + 1 < len(ns) and ns[j + 1] == ns[j] + 1:
            j += 1
        out.append("%d-%d" % (ns[k], ns[j]) if j > k else str(ns[k]))
        k = j + 1
    return " ".join(out)


class Stop:
    """The report of Link.safe_stop() (and of the stop Ctrl-C makes, KeyboardInterrupt.stop):
    the link's safe stop (fbrl_link_safe_stop, docs/link.md 1 "The safe stop") with the motion.

    ok: the arm was halted and the report is whole; status, name: the fbrl_status (FBRL_EBUSY:
    the controller was still running a command that waits, HALT could not be sent;
    FBRL_EDISCONNECTED ...); was_moving, motion: a motion had been sent and not seen to end,
    and its line; halted: HALT ran; switched_off: the outputs this stop switched off;
    off_failed: those it could not switch off (or may have); left_on: the outputs known to be
    on after it (None: the controller's STATUS does not show its outputs, or could not be
    read); unknown: the outputs whose state is not known, and unknown_why: why ("" none);
    homed (None: STATUS not read); where: the arm's Location after the stop (None: not read)."""

    def __init__(self, c):
        so = c.stop
        self.status = c.result
        self.name = status_name(c.result)
        self.ok = c.result == 0
        self.was_moving = bool(c.was_moving)
        self.motion = ffi.string(c.motion).decode("latin-1") or None
        self.halted = bool(so.halted)
        self.switched_off = _outputs(so.switched_off)
        self.off_failed = _outputs(so.off_failed)
        self.left_on = _outputs(so.left_on) if so.have_outputs else None
        self.unknown = _outputs(so.unknown & ~so.off_failed)
        if not self.unknown:
            self.unknown_why = ""
        elif so.have_status:
            self.unknown_why = ("this controller's STATUS does not show its outputs, and this program did not "
                                "switch them on: check them at the controller")
        else:
            self.unknown_why = ("STATUS could not be read after HALT: %s; check them at the controller"
                                % status_text(so.status_result))
        self.homed = bool(so.homed) if so.have_status else None
        self.where = Location(*[so.where[k] for k in range(6)]) if so.have_where else None

    def __str__(self):
        if self.name in ("FBRL_EDISCONNECTED", "FBRL_EOFFLINE"):
            return "the controller is not connected: the arm could not be halted%s" % (
                "; it was moving: " + (self.motion or "") if self.was_moving else "")
        if self.name == "FBRL_EBUSY":
            return ("the controller is still running a command that waits (WAIT or RUN) and reads nothing else: "
                    "HALT could not be sent; stop the arm at the controller")
        if self.halted:
            text = "arm halted " + ("(no motion was running)" if not self.was_moving else
                                    "while moving (%s)" % self.motion if self.motion else "while it may have moved")
        else:
            text = "HALT failed (%s)" % status_text(self.status)
        if self.where:
            w = self.where
            text += "; it stands at X %.4f Y %.4f Z %.4f pitch %.4f roll %.4f" % (w.x, w.y, w.z, w.a, w.t)
        text += "; outputs switched off: %s" % (" ".join(map(str, self.switched_off)) or "none")
        if self.left_on is not None:
            text += "; outputs still on: %s" % (" ".join(map(str, self.left_on)) or "none")
        if self.off_failed:
            text += "; switching off failed for %s (may still be on)" % " ".join(map(str, self.off_failed))
        if self.unknown:
            text += "; not known: %s (%s)" % (_ranges(self.unknown), self.unknown_why)
        return text

    def __repr__(self):
        return "Stop(%s, halted=%r, switched_off=%r, left_on=%r)" % (self.name, self.halted, self.switched_off,
                                                                     self.left_on)
