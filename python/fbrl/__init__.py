# SPDX-License-Identifier: MIT
"""fbrl - Python bindings for libfbrl (FBRL, the Forth Based Robotics Language, and the
RAPL link to a CRS robot controller). See docs/python.md.

    import fbrl
    with fbrl.Port("/dev/ttyUSB0", baud=9600) as port:
        link = fbrl.Link(port)
        link.command("HOME")
        print(link.where().world)
    with fbrl.Engine(link=link) as fb:
        fb.eval("READY")

Every failing call raises fbrl.Error (fbrl.ControllerError when the controller refused
the command), carrying the library's fbrl_status, its name and text, the controller's
error code and text, and whether the command ran.
"""
from ._ffi import ffi, lib, alloc
from ._errors import Error, ControllerError, check, status_name, status_text, FATES
from .loc import Location, Calibration
from .datafile import DataFile, CHR, INTEGER, LONG, REAL, LOCATION, user_type
from .link import Port, Link, Position, Status, PortInfo, list_ports
from .stop import Stop
from .engine import Engine
from .run import Run
from .users import Users
from .arm import Arm
from .release import method_version, method_release
from .audit import AuditTrail, RunLog

__all__ = [
    "Error", "ControllerError", "Location", "Calibration", "DataFile", "CHR", "INTEGER", "LONG",
    "REAL", "LOCATION", "user_type", "Port", "Link", "Position", "Status", "Engine", "version",
    "status_name", "status_text", "FATES", "PortInfo", "list_ports", "Stop", "Users", "Arm", "method_version",
    "method_release", "AuditTrail", "RunLog",
]

__version__ = ffi.string(lib.fbrl_version()).decode()


def version():
    """The running library's version, e.g. "0.1.0"."""
    return ffi.string(lib.fbrl_version()).decode()
