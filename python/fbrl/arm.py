# SPDX-License-Identifier: MIT
"""The arm models (fbrl/arm.h): forward kinematics and the chain of joint points, as the
library computes them for the guard, the emulator and the monitor (docs/robot.md)."""
from ._ffi import ffi, lib
from ._errors import check

AXES_MAX = 6  # FBRL_ARM_AXES_MAX
CHAIN = ("shoulder", "elbow", "wrist", "tool")  # the points of fbrl_arm_chain, in order


def names():
    """The models' names, lower case: ["a255", "a465"]."""
    n = lib.fbrl_arm_names(ffi.NULL, 0, b"|")
    buf = ffi.new("char[]", n + 1)
    lib.fbrl_arm_names(buf, n + 1, b"|")
    return ffi.string(buf).decode().split("|")


class Arm:
    """One row of the library's arm model table, by name (any case)."""

    def __init__(self, name="a255"):
        self._m = lib.fbrl_arm_find(name.encode())
        if self._m == ffi.NULL:
            raise ValueError("no arm model %r (the library knows %s)" % (name, ", ".join(names())))
        self.name = name.upper()

    def _q(self, joints):
        if len(joints) > AXES_MAX:
            raise ValueError("%d joints: an arm has at most %d" % (len(joints), AXES_MAX))
        return ffi.new("double[%d]" % AXES_MAX, [float(j) for j in joints] + [0.0] * (AXES_MAX - len(joints)))

    def fk(self, joints, tool=0.0):
        """The pose [x y z yaw pitch roll] of the tool point tool inches past the flange."""
        pose = ffi.new("double[6]")
        check(lib.fbrl_arm_fk(self._m, self._q(joints), float(tool), pose), "Arm.fk")
        return list(pose)

    def chain(self, joints, tool=0.0):
        """[shoulder, elbow, wrist centre, tool point], each [x y z] in inches."""
        p = ffi.new("double[4][3]")
        check(lib.fbrl_arm_chain(self._m, self._q(joints), float(tool), p), "Arm.chain")
        return [list(p[i]) for i in range(4)]
