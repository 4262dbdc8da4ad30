# SPDX-License-Identifier: MIT
"""What fbrl-station needs of the bindings (docs/python.md): the engine guards every motion
with the work cell, drives another link after set_link, stops on interrupt() from another
thread; the link knows the controller's units. fbrlsim's log is the truth of what ran."""
import os
import threading
import time

import pytest

import fbrl

HERE = os.path.dirname(os.path.abspath(__file__))
CELL = os.path.join(HERE, "..", "..", "examples", "asps_cell_objects.fbrl")
# a place inside the heating block's body (asps_cell_objects.fbrl), and one clear of everything
INSIDE = "CREATE-LOC IN-BLOCK 10E0 -2E0 0.5E0 0E0 -90E0 0E0 IN-BLOCK DEFINE-LOC"
CLEAR = "CREATE-LOC CLEAR 14E0 2E0 8E0 0E0 -90E0 0E0 CLEAR DEFINE-LOC"


def test_a_motion_into_the_cell_is_refused_and_nothing_is_sent(sim, link):
    with fbrl.Engine(link=link) as fb:
        fb.include(CELL)
        fb.eval("HOME " + INSIDE + " " + CLEAR + " CLEAR MOV FINISH")
        sent = len(sim.log())
        with pytest.raises(fbrl.Error) as e:
            fb.eval("IN-BLOCK MOV")
        assert "would hit" in e.value.message and "nothing was sent" in e.value.message
        assert fb.guard == (1, 1)  # the move to CLEAR checked and sent (HOME is not a path), one refused
        # the guard reads where the arm is before it checks (W1, docs/workcell.md); nothing else
        after = sim.log()[sent:]
        assert all(line in ("W1", "W2") for line in after), after  # not a POINT, not a MOVE
        assert any(line.startswith("MOVE") for line in sim.log())


def test_set_link_drives_another_controller(tmp_path, sim, link):
    from conftest import Sim
    (tmp_path / "b").mkdir()
    other = Sim(tmp_path / "b")
    try:
        with fbrl.Port(other.port) as port, fbrl.Engine(link=link) as fb:
            fb.eval("HOME")
            fb.set_link(None)
            with pytest.raises(fbrl.Error):
                fb.eval("READY")
            fb.set_link(fbrl.Link(port))
            fb.eval("HOME READY")
        assert "READY" not in sim.log() and "READY" in other.log()
    finally:
        other.stop()


def test_interrupt_from_another_thread_stops_a_wait(link):
    with fbrl.Engine(link=link) as fb:
        threading.Timer(0.3, fb.interrupt).start()
        t0 = time.monotonic()
        with pytest.raises(fbrl.Error) as e:
            fb.eval("20000 MS")
        assert e.value.throw_code == -28 and time.monotonic() - t0 < 5


def test_the_link_learns_the_controller_s_units(sim, link):
    assert sim.log()[:2] == ["NOHELP", "STATUS"]  # the connect read them (docs/link.md 1)
    assert link.units == "inch"
    link.raw("METRIC")
    assert link.units == "mm"
    link.status()
    assert link.units == "mm"
