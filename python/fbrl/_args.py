# SPDX-License-Identifier: MIT
"""Arguments on their way to C, checked where Python and C disagree: a C string ends at
its first NUL, so "OUTPUT 3\\0 junk" would run as "OUTPUT 3"; and str(None) is a name.
What the library itself checks (names, ranges, the line) stays the library's."""
import numbers
import os


def _nul(data, value, what):
    if b"\0" in data:
        raise ValueError("%s: %r holds a NUL character: C would stop there and take only what comes before it"
                         % (what, value))
    return data


def text(value, what):
    """A str (UTF-8) or bytes as the bytes of a C string."""
    if isinstance(value, str):
        try:
            data = value.encode("utf-8")
        except UnicodeEncodeError as e:
            raise ValueError("%s: %r cannot be written as UTF-8" % (what, value)) from e
    elif isinstance(value, (bytes, bytearray)):
        data = bytes(value)
    else:
        raise TypeError("%s: a str, not %s" % (what, type(value).__name__))
    return _nul(data, value, what)


def path(value, what):
    """A file name (str, bytes or os.PathLike) as the operating system's bytes: a name that
    is not UTF-8 (os.fsdecode's surrogates) keeps its bytes."""
    try:
        data = os.fsencode(value)
    except TypeError:
        raise TypeError("%s: a path (str, bytes or os.PathLike), not %s" % (what, type(value).__name__)) from None
    return _nul(data, value, what)


def integer(value, what):
    """An int (not a bool: True is no count)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError("%s: an int, not %s" % (what, type(value).__name__))
    return int(value)


def real(value, what):
    """A float (an int is taken as one; a bool is not)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError("%s: a number, not %s" % (what, type(value).__name__))
    return float(value)
