# SPDX-License-Identifier: MIT
"""fbrl.method_version: the version fbrl-audit names for the same file (another program: its
"method status" line), another version after a one-character edit of an included file, and
one clear error for a missing file."""
import os
import re
import shutil
import subprocess

import pytest

import fbrl
from conftest import fbrl_audit_path

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


audit = fbrl_audit_path


def test_the_version_is_the_one_fbrl_audit_names(tmp_path):
    lab = tmp_path / "lab"
    lab.mkdir()
    shutil.copytree(os.path.join(ROOT, "examples"), str(tmp_path / "ex"))
    path = str(tmp_path / "ex" / "methods" / "sample_prep.fbrl")
    hexv, method = fbrl.method_version(path)
    out = subprocess.run([audit(), "method", "status", path, "--lab", str(lab)], capture_output=True, text=True,
                         timeout=30)
    m = re.match(r"(\S+) version ([0-9a-f]{64}): ", out.stdout)
    assert m, out.stdout + out.stderr
    assert (method, hexv) == (m.group(1), m.group(2))
    # an included file edited by one character: another version
    cell = tmp_path / "ex" / "asps_cell_objects.fbrl"
    cell.write_text(cell.read_text().replace("CELL-TABLE", "CELL-TABLE ", 1))
    assert fbrl.method_version(path)[0] != hexv


def test_a_missing_file_is_one_clear_error(tmp_path):
    with pytest.raises(fbrl.Error) as e:
        fbrl.method_version(str(tmp_path / "none.fbrl"))
    assert "none.fbrl" in str(e.value)
