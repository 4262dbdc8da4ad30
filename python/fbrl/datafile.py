# SPDX-License-Identifier: MIT
"""Typed data files (CREATE-FILE, OPEN-FILE, READ-FILE, WRITE-FILE ...; docs/files.md)."""
import os

from ._ffi import ffi, lib, alloc
from ._errors import Error, check
from .loc import Location

FBRL_EEOF_NAME = "FBRL_EEOF"


class FileType:
    """A record type: code (1 CHR, 2 INTEGER, 3 LONG, 4 REAL, 5 LOCATION, 6 user), tag, size."""

    def __init__(self, name, code, size, tag=0, ctype=None):
        self.name, self.code, self.size, self.tag, self.ctype = name, code, size, tag, ctype

    def _c(self):
        t = ffi.new("fbrl_ftype *")
        t.code, t.tag, t.size = self.code, self.tag, self.size
        return t[0]

    def __eq__(self, other):
        return isinstance(other, FileType) and (self.code, self.tag, self.size) == (other.code, other.tag, other.size)

    def __hash__(self):
        return hash((self.code, self.tag, self.size))

    def __repr__(self):
        return "fbrl." + self.name if self.code != 6 else "fbrl.user_type(%d, %d)" % (self.tag, self.size)


CHR = FileType("CHR", 1, 1, ctype="unsigned char")
INTEGER = FileType("INTEGER", 2, 2, ctype="int16_t")
LONG = FileType("LONG", 3, 4, ctype="int32_t")
REAL = FileType("REAL", 4, 8, ctype="double")
LOCATION = FileType("LOCATION", 5, 48, ctype="fbrl_loc")
_BUILTIN = {t.code: t for t in (CHR, INTEGER, LONG, REAL, LOCATION)}


def user_type(tag, size):
    """A user-defined record type: size raw bytes, told apart by tag."""
    return FileType("USER", 6, size, tag)


def _type_of(c):
    return _BUILTIN.get(c.code) or user_type(c.tag, c.size)


class DataFile:
    """An open typed data file. All of it is read and verified at open; changes reach the
    disk atomically at commit() or close() (leaving the with block commits; an exception
    inside it discards the changes).

        with fbrl.DataFile("results.dat", create=True) as f:
            f.append()
            f.write(fbrl.REAL, 7.25)
    """

    def __init__(self, path, capacity=1 << 20, create=False):
        self.path = os.fspath(path)
        if create or not os.path.exists(self.path):
            check(lib.fbrl_file_create(self.path.encode()), "create " + self.path)
        self._f = alloc("fbrl_file")
        self._buf = ffi.new("unsigned char[]", capacity)
        check(lib.fbrl_file_open(self._f.ptr, self.path.encode(), self._buf, capacity), "open " + self.path)
        self._open = True

    def __enter__(self):
        return self

    def __exit__(self, exc_type, exc, tb):
        if exc_type is None:
            self.close()
        else:
            self.discard()
        return False

    def __iter__(self):
        """(type, value) for every record from the current one to the end."""
        while True:
            t = self.peek()
            if t is None:
                return
            yield t, self.read(t)

    def _handle(self):
        if not self._open:
            raise ValueError("the data file is closed")
        return self._f.ptr

    def write(self, ftype, value):
        """Write one value at the current position (replacing a record there) and move past it."""
        if ftype.ctype == "fbrl_loc":
            if not isinstance(value, Location):
                value = Location(*value)
            p = value._c()
        elif ftype.ctype:
            p = ffi.new(ftype.ctype + " *", value)
        else:
            data = bytes(value)
            if len(data) != ftype.size:
                raise ValueError("a %r record holds %d bytes, not %d" % (ftype, ftype.size, len(data)))
            p = ffi.new("unsigned char[]", data)
        check(lib.fbrl_file_write(self._handle(), ftype._c(), p), "write " + self.path)

    def read(self, ftype):
        """Read the current record as ftype and move past it (fbrl.Error FBRL_ETYPE if it is
        of another type: the position stays)."""
        if ftype.ctype:
            p = ffi.new(ftype.ctype + " *")
        else:
            p = ffi.new("unsigned char[]", ftype.size)
        check(lib.fbrl_file_read(self._handle(), ftype._c(), p), "read " + self.path)
        if ftype.ctype == "fbrl_loc":
            return Location._from_c(p)
        if ftype.ctype:
            return p[0]
        return bytes(ffi.buffer(p, ftype.size))

    def peek(self):
        """The current record's type, or None at the end."""
        t = ffi.new("fbrl_ftype *")
        st = lib.fbrl_file_peek(self._handle(), t)
        if st < 0 and Error(st).name == FBRL_EEOF_NAME:
            return None
        check(st, "peek " + self.path)
        return _type_of(t)

    def tell(self):
        """(current record number, number of records)."""
        i, n = ffi.new("uint32_t *"), ffi.new("uint32_t *")
        check(lib.fbrl_file_tell(self._handle(), i, n), "tell " + self.path)
        return i[0], n[0]

    def __len__(self):
        return self.tell()[1]

    def reset(self):
        check(lib.fbrl_file_reset(self._handle()), "reset " + self.path)

    def append(self):
        check(lib.fbrl_file_append(self._handle()), "append " + self.path)

    def truncate(self):
        check(lib.fbrl_file_truncate(self._handle()), "truncate " + self.path)

    def commit(self):
        check(lib.fbrl_file_commit(self._handle()), "commit " + self.path)

    def close(self):
        if self._open:
            check(lib.fbrl_file_close(self._f.ptr), "close " + self.path)
            self._open = False

    def discard(self):
        if self._open:
            check(lib.fbrl_file_discard(self._f.ptr), "discard " + self.path)
            self._open = False
