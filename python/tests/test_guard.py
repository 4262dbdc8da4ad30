# SPDX-License-Identifier: MIT
"""The work cell's guard from Python (docs/workcell.md "The guard", docs/python.md): the
Engine's robot words are checked against a cell it describes, and a motion sent on the same
Link directly is refused unless sent around the guard on purpose. fbrlsim knows the same
cell (--cell: a motion into it ends in 190 in its stamped log), so its log is the truth."""
import os

import pytest

import fbrl
from conftest import Sim, LOADED_HOST_ECHO_MS

HERE = os.path.dirname(os.path.abspath(__file__))
CELL = os.path.join(os.path.dirname(os.path.dirname(HERE)), "tests", "e2e", "cell", "cell.fbrl")


@pytest.fixture
def cell_sim(tmp_path):
    s = Sim(tmp_path, "--cell", CELL, "--log-format", "stamped")
    yield s
    s.stop()


def collisions(sim):
    return [line for line in sim.log() if line.split()[1:2] == ["190"]]


def test_engine_refuses_a_move_into_the_cell_before_a_byte_is_sent(cell_sim):
    with fbrl.Port(cell_sim.port) as port:
        link = fbrl.Link(port, echo_timeout_ms=LOADED_HOST_ECHO_MS)
        with fbrl.Engine(link=link) as fb:
            fb.include(CELL)
            fb.eval("HOME READY CREATE-LOC IN-POST 14E0 0E0 3E0 0E0 -90E0 0E0 IN-POST DEFINE-LOC")
            with pytest.raises(fbrl.Error) as e:
                fb.eval("IN-POST MOV")
            assert e.value.throw_code == -302 and "would hit POST" in e.value.message
    assert not [line for line in cell_sim.log() if "POINT FBRLT" in line and ",14,0,3," in line]
    assert not collisions(cell_sim)


def test_a_motion_on_a_guarded_link_needs_the_explicit_way_around(cell_sim):
    with fbrl.Port(cell_sim.port) as port:
        link = fbrl.Link(port, echo_timeout_ms=LOADED_HOST_ECHO_MS)
        with fbrl.Engine(link=link) as fb:
            fb.include(CELL)
            fb.eval("HOME READY")
            with pytest.raises(fbrl.Error) as e:
                link.command("JOG", 0.0, 0.0, -21.0)  # from READY straight down through the table
            assert e.value.name == "FBRL_EGUARD" and e.value.fate == "not run"
            with pytest.raises(fbrl.Error) as e:
                link.raw("JOG 0,0,-21")
            assert e.value.name == "FBRL_EGUARD"
            assert not [line for line in cell_sim.log() if "JOG" in line]
            link.command("JOG", 0.0, 0.0, -1.0, unguarded=True)  # said so: it goes
            assert [line for line in cell_sim.log() if line.endswith("JOG 0,0,-1")]
            fb.eval("0E0 0E0 -1E0 JOG")  # the guard reads where that left the arm
        link.command("JOG", 0.0, 0.0, 1.0)  # the engine is closed: a link alone knows no cell
    assert not collisions(cell_sim)
