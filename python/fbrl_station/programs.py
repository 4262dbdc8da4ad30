# SPDX-License-Identifier: MIT
"""The project's programs the station starts (fbrlsim, fbrlmon, fbrl-audit): the one its
environment variable names (the launcher sets it), else the one on PATH."""
import os
import shutil


def find(name, env, missing):
    """The path of program name; OSError "MISSING (install it, or set ENV)" when there is none."""
    prog = os.environ.get(env) or shutil.which(name)
    if not prog or not os.access(prog, os.X_OK):
        raise OSError("%s (install it, or set %s)" % (missing, env))
    return prog
