# SPDX-License-Identifier: MIT
"""fbrl-urdf: each arm model's URDF is accepted by check_urdf (Debian's liburdfdom-tools, a
parser the project did not write), and its chain, worked out here from the URDF's own joints
with plain 4x4 matrices (URDF's conventions: origin xyz, then rpy as Rz Ry Rx, then a turn
about the axis), puts tool0 where the library's forward kinematics puts the tool point,
within 0.1 mm, over many joint sets inside the limits."""
import math
import os
import random
import shutil
import subprocess
import xml.etree.ElementTree as ET

import pytest

import fbrl

URDF = os.environ.get("FBRL_URDF") or os.path.join(os.path.dirname(__file__), "..", "..", "build", "apps",
                                                   "fbrl-urdf")
M_PER_IN = 0.0254
TOLERANCE_M = 0.0001  # 0.1 mm
JOINT_SETS = 500


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def translation(x, y, z):
    return [[1, 0, 0, x], [0, 1, 0, y], [0, 0, 1, z], [0, 0, 0, 1]]


def rotation(axis, angle):
    """Rotation by angle about the unit axis (Rodrigues), as a 4x4 matrix."""
    x, y, z = axis
    n = math.sqrt(x * x + y * y + z * z)
    x, y, z = x / n, y / n, z / n
    c, s, t = math.cos(angle), math.sin(angle), 1 - math.cos(angle)
    return [[t * x * x + c, t * x * y - s * z, t * x * z + s * y, 0],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x, 0],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c, 0], [0, 0, 0, 1]]


def origin(joint):
    o = joint.find("origin")
    xyz = [float(v) for v in (o.get("xyz", "0 0 0") if o is not None else "0 0 0").split()]
    r, p, y = [float(v) for v in (o.get("rpy", "0 0 0") if o is not None else "0 0 0").split()]
    m = translation(*xyz)
    for axis, a in (((0, 0, 1), y), ((0, 1, 0), p), ((1, 0, 0), r)):  # Rz(yaw) Ry(pitch) Rx(roll)
        m = matmul(m, rotation(axis, a))
    return m


def chain(root):
    """The joints from base_link to tool0, in order."""
    by_child = {j.find("child").get("link"): j for j in root.findall("joint")}
    out, link = [], "tool0"
    while link != "base_link":
        j = by_child[link]
        out.append(j)
        link = j.find("parent").get("link")
    return out[::-1]


def tool0(joints, q):
    m, i = translation(0, 0, 0), 0
    for j in joints:
        m = matmul(m, origin(j))
        if j.get("type") == "revolute":
            m = matmul(m, rotation([float(v) for v in j.find("axis").get("xyz").split()], q[i]))
            i += 1
    return [m[0][3], m[1][3], m[2][3]]


def urdf(model):
    p = subprocess.run([URDF, model], capture_output=True, text=True, timeout=30)
    assert p.returncode == 0, p.stderr
    return p.stdout


@pytest.mark.parametrize("model", fbrl.arm.names())
def test_check_urdf_accepts_it(model, tmp_path):
    check = shutil.which("check_urdf")
    if check is None:
        pytest.fail("check_urdf not found (Debian: liburdfdom-tools)")
    f = tmp_path / (model + ".urdf")
    f.write_text(urdf(model))
    p = subprocess.run([check, str(f)], capture_output=True, text=True, timeout=30)
    assert p.returncode == 0 and "Successfully Parsed XML" in p.stdout, p.stdout + p.stderr
    assert "tool0" in p.stdout


@pytest.mark.parametrize("model", fbrl.arm.names())
def test_its_chain_puts_the_tool_where_the_library_does(model):
    root = ET.fromstring(urdf(model))
    joints = chain(root)
    revolute = [j for j in joints if j.get("type") == "revolute"]
    arm = fbrl.Arm(model)
    rng = random.Random(32)
    worst = 0.0
    for _ in range(JOINT_SETS):
        q = [rng.uniform(float(j.find("limit").get("lower")), float(j.find("limit").get("upper"))) for j in revolute]
        want = [v * M_PER_IN for v in arm.fk([math.degrees(a) for a in q])[:3]]
        got = tool0(joints, q)
        worst = max(worst, max(abs(a - b) for a, b in zip(got, want)))
    assert worst <= TOLERANCE_M, "%s: %.6f m off" % (model, worst)


def test_an_unknown_model_is_refused():
    p = subprocess.run([URDF, "a999"], capture_output=True, text=True, timeout=30)
    assert p.returncode == 2 and "no arm model a999" in p.stderr and p.stdout == ""
