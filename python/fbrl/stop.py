# SPDX-License-Identifier: MIT
"""fbrl.Stop: what a safe stop found and did (fbrl_robot_stop, docs/robot.md "Stopping safely")."""
from ._ffi import ffi
from ._errors import status_name, status_text
from .loc import Location

IO_MAX = 16  # FBRL_ROBOT_IO_MAX: outputs 1..16


def _outputs(bits):
    return [n for n in range(1, IO_MAX + 1) if bits >> (n - 1) & 1]


class Stop:
    """The report of Link.safe_stop() (and of the stop Ctrl-C makes, KeyboardInterrupt.stop).

    ok: the arm was halted and the report is whole; status, name: the fbrl_status (FBRL_EBUSY:
    the controller was still running a command that waits, HALT could not be sent;
    FBRL_EDISCONNECTED ...); was_moving, motion: a motion had been sent and not seen to end,
    and its line; halted: HALT ran; switched_off: the outputs this stop switched off;
    left_on: the outputs still on after it (None: STATUS could not be read, unknown);
    homed (None: unknown); where: the arm's Location after the stop (None: not read)."""

    def __init__(self, c):
        self.status = c.result
        self.name = status_name(c.result)
        self.ok = c.result == 0
        self.was_moving = bool(c.was_moving)
        self.motion = ffi.string(c.motion).decode("latin-1") or None
        self.halted = bool(c.halted)
        self.switched_off = _outputs(c.switched_off)
        self.left_on = _outputs(c.left_on) if c.have_status else None
        self.homed = bool(c.homed) if c.have_status else None
        self.where = Location(*[c.where[k] for k in range(6)]) if c.have_where else None

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
        if self.left_on is None:
            text += "; STATUS could not be read: the outputs' state is unknown"
        else:
            text += "; outputs still on: %s" % (" ".join(map(str, self.left_on)) or "none")
        return text

    def __repr__(self):
        return "Stop(%s, halted=%r, switched_off=%r, left_on=%r)" % (self.name, self.halted, self.switched_off,
                                                                     self.left_on)
