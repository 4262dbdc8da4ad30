# SPDX-License-Identifier: MIT
"""Locations (x y z in inches, yaw pitch roll in degrees) and calibrations."""
from ._ffi import ffi, lib
from ._errors import check

_AXES = ("x", "y", "z", "o", "a", "t")


class Location:
    """A location: x, y, z (inches), o (yaw), a (pitch, -90 = tool down), t (roll) in degrees."""

    __slots__ = _AXES

    def __init__(self, x=0.0, y=0.0, z=0.0, o=0.0, a=0.0, t=0.0):
        self.x, self.y, self.z, self.o, self.a, self.t = (float(v) for v in (x, y, z, o, a, t))
        check(lib.fbrl_loc_check(self._c()), "Location")

    def _c(self):
        c = ffi.new("fbrl_loc *")
        c.x, c.y, c.z, c.o, c.a, c.t = self.x, self.y, self.z, self.o, self.a, self.t
        return c

    @classmethod
    def _from_c(cls, c):
        return cls(c.x, c.y, c.z, c.o, c.a, c.t)

    def __iter__(self):
        return iter((self.x, self.y, self.z, self.o, self.a, self.t))

    def __eq__(self, other):
        return isinstance(other, Location) and tuple(self) == tuple(other)

    def __repr__(self):
        return "Location(%r, %r, %r, %r, %r, %r)" % tuple(self)

    def __str__(self):
        return self.format()

    def format(self, metric=False):
        """The text DISPLAY-LOC prints (inches, or cm with metric=True)."""
        buf = ffi.new("char[]", 256)
        check(lib.fbrl_loc_format(self._c(), 1 if metric else 0, buf, 256), "Location.format")
        return ffi.string(buf).decode()

    def distance(self, other):
        """Straight-line distance between the two positions, in inches."""
        d = ffi.new("double *")
        check(lib.fbrl_loc_distance(self._c(), other._c(), d), "Location.distance")
        return d[0]


def _pts(locs):
    if len(locs) != 3:
        raise ValueError("three points are needed")
    p = ffi.new("fbrl_calpts *")
    for i, loc in enumerate(locs):
        c = loc._c()
        p.p[i] = c[0]
    return p


class Calibration:
    """A rigid transform from a block's taught positions to where the block is now
    (docs/calibration.md): map() takes a location taught on the block to the moved
    block, unmap() back."""

    def __init__(self):
        self._c = ffi.new("fbrl_calib *")
        check(lib.fbrl_calib_identity(self._c), "Calibration")
        self.rms = 0.0

    @classmethod
    def three_point(cls, cal, recal):
        """From three points taught before (cal) and the same three found again (recal)."""
        c = cls()
        check(lib.fbrl_calib_3point(c._c, _pts(cal), _pts(recal)), "Calibration.three_point")
        return c

    @classmethod
    def n_point(cls, cal, recal):
        """Least squares over n >= 3 point pairs; .rms is the fit's root-mean-square residual."""
        if len(cal) != len(recal):
            raise ValueError("cal and recal need the same number of points")
        n = len(cal)
        a = ffi.new("fbrl_loc[]", max(n, 1))
        b = ffi.new("fbrl_loc[]", max(n, 1))
        for i in range(n):
            a[i] = cal[i]._c()[0]
            b[i] = recal[i]._c()[0]
        c = cls()
        rms = ffi.new("double *")
        check(lib.fbrl_calib_npoint(c._c, a, b, n, ffi.NULL, rms, ffi.NULL), "Calibration.n_point")
        c.rms = rms[0]
        return c

    def map(self, loc):
        out = ffi.new("fbrl_loc *")
        check(lib.fbrl_calib_map(self._c, loc._c(), out), "Calibration.map")
        return Location._from_c(out)

    def unmap(self, loc):
        out = ffi.new("fbrl_loc *")
        check(lib.fbrl_calib_unmap(self._c, loc._c(), out), "Calibration.unmap")
        return Location._from_c(out)

    @property
    def rotation(self):
        return [[self._c.r[i][j] for j in range(3)] for i in range(3)]

    @property
    def translation(self):
        return [self._c.t[i] for i in range(3)]
