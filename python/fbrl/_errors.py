# SPDX-License-Identifier: MIT
"""fbrl.Error: a failed call, with everything the library knows about it."""
from ._ffi import ffi, lib

FBRL_OK = 0
FBRL_ECONTROLLER_NAME = "FBRL_ECONTROLLER"
# fbrl_link_fate (fbrl/link.h): did the command run?
FATES = {0: "ran", 1: "ran", 2: "refused", 3: "not run", 4: "may have run"}


def status_name(st):
    """"FBRL_ETIMEOUT" for a status code."""
    return ffi.string(lib.fbrl_status_name(st)).decode()


def status_text(st):
    """"deadline passed" for a status code."""
    return ffi.string(lib.fbrl_status_str(st)).decode()


_CODES = {}


def status_code(name):
    """A status code by its name ("FBRL_EMAYBE"), from the library's own table: no code is
    written twice."""
    if not _CODES:
        for st in range(0, -200, -1):
            n = ffi.string(lib.fbrl_status_name(st)).decode()
            if n.startswith("FBRL_") and n not in _CODES:
                _CODES[n] = st
    return _CODES[name]


class Error(Exception):
    """A libfbrl call failed.

    status: the fbrl_status code (negative int); name: its name ("FBRL_ETIMEOUT");
    text: its meaning; controller_code / controller_text: the controller's error
    (e.g. 29, "TRANSFORM ILLEGAL") when it refused a command, else None; fate: for link
    commands "ran", "refused", "not run" or "may have run", else None; what: the call or
    the command line."""

    def __init__(self, status, what="", controller_code=None, controller_text=None, fate=None, detail=None):
        self.status = status
        self.name = status_name(status)
        self.text = status_text(status)
        self.controller_code = controller_code
        self.controller_text = controller_text
        self.fate = fate
        self.what = what
        self.detail = detail
        msg = "%s: %s (%s)" % (what, self.text, self.name) if what else "%s (%s)" % (self.text, self.name)
        if controller_code is not None:
            msg += ": controller error %d %s" % (controller_code, controller_text or "")
        if detail:
            msg += ": " + detail
        if fate is not None:
            msg += " [%s]" % fate
        super().__init__(msg)


class ControllerError(Error):
    """The controller answered the command with an error: it was refused, not run."""


def check(st, what=""):
    """Raise Error for a failed status; return it otherwise."""
    if st < 0:
        raise Error(st, what)
    return st
