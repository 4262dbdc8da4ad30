# SPDX-License-Identifier: MIT
"""The Python bindings against the library and a real fbrlsim (its log is the truth)."""
import math
import os
import re
import subprocess

import pytest

import fbrl
from fbrl import _ffi
from conftest import LOADED_HOST_ECHO_MS, Sim

HERE = os.path.dirname(os.path.abspath(__file__))


def test_version_is_the_library_s():
    assert re.fullmatch(r"\d+\.\d+\.\d+", fbrl.version())
    assert fbrl.__version__ == fbrl.version()


def test_declared_structs_match_the_library():
    for name in _ffi.DECLARED:
        assert _ffi.ffi.sizeof(name) == _ffi.lib.fbrl_abi_size(_ffi.ABI[name])
    for name, code in _ffi.ABI.items():  # the code table agrees with the library's names
        assert _ffi.ffi.string(_ffi.lib.fbrl_abi_name(code)).decode() == name


def test_a_port_that_does_not_exist_raises_with_the_status(tmp_path):
    with pytest.raises(fbrl.Error) as e:
        fbrl.Port(str(tmp_path / "no-such-tty"))
    assert e.value.name == "FBRL_ENOENT" and e.value.status < 0
    assert "no-such-tty" in str(e.value)


def test_a_bad_line_option_raises():
    with pytest.raises(fbrl.Error) as e:
        fbrl.Port("/dev/null", parity="sideways")
    assert "parity" in str(e.value)


def test_link_commands_run_once_each(sim, link):
    link.speed(50)
    link.home()
    link.finish()
    assert link.status().homed
    pos = link.where()
    assert pos.kind == "A" and len(pos.pulses) == 5 and pos.world is not None
    log = sim.log()
    # exactly once each, in order (the log is what the controller executed)
    assert [l for l in log if l in ("SPEED 50", "HOME")] == ["SPEED 50", "HOME"]


def test_point_move_and_read_back(sim, link):
    link.home()
    target = fbrl.Location(12.0, 3.0, 8.0, 0.0, -90.0, 0.0)
    link.point("P1", target)
    link.move("P1")
    link.finish()
    world = link.where().world
    assert world.distance(target) < 0.01
    assert any(l.startswith("POINT P1,12") for l in sim.log())
    assert "MOVE P1" in sim.log()


def test_controller_error_carries_code_text_and_fate(sim, link):
    with pytest.raises(fbrl.ControllerError) as e:
        link.move("NOWHERE")
    err = e.value
    assert err.name == "FBRL_ECONTROLLER"
    assert isinstance(err.controller_code, int) and err.controller_code > 0
    assert err.controller_text
    assert err.fate == "refused"
    assert "MOVE NOWHERE" in str(err)


def test_variables_and_inputs(sim, link):
    link.raw("V1=41+1")
    assert link.typei("V1") == 42
    assert link.typev("V1/4") == pytest.approx(10.5)
    assert link.input(3) is False
    link.output(2, True)
    assert link.status().output(2)


def test_engine_evaluates_and_reads_stacks():
    with fbrl.Engine() as fb:
        assert fb.eval("1 2 + .") == "3 "
        fb.eval("CREATE-LOC P  1.0 2.0 3.0 4.0 5.0 6.0 P DEFINE-LOC  P GETY 7 8")
        assert fb.stack() == [7, 8]
        assert fb.fstack() == [2.0]
        assert fb.pop() == 8 and fb.fpop() == 2.0
        fb.push(5, 2.5)
        assert fb.eval(". F.") == "5 2.5 "


def test_engine_errors_say_what_and_where(tmp_path):
    src = tmp_path / "prog.fbrl"
    src.write_text(": ok 1 ;\nok nosuch\n")
    with fbrl.Engine() as fb:
        with pytest.raises(fbrl.Error) as e:
            fb.include(src)
        assert e.value.throw_code == -13 and e.value.line == 2 and e.value.file.endswith("prog.fbrl")
        assert e.value.name == "FBRL_ETHROW"
        assert fb.eval("2 .") == "2 "  # the engine goes on


def test_engine_robot_words_reach_the_controller(sim, link):
    with fbrl.Engine(link=link) as fb:
        fb.eval("HOME")
        fb.eval("CREATE-LOC NOW  NOW ARM-HERE  NOW GETZ")
        assert fb.fstack()[0] == pytest.approx(link.where().world.z, abs=1e-3)
    assert "HOME" in sim.log()


def test_engine_controller_errors_carry_its_code_twice_in_a_row(sim, link):
    with fbrl.Engine(link=link) as fb:
        for _ in range(2):
            with pytest.raises(fbrl.ControllerError) as e:
                fb.eval("RAPL MOVE NOWHERE")  # not homed yet: error 41
            assert e.value.controller_code == 41 and "HOMED" in e.value.controller_text
            assert e.value.name == "FBRL_ECONTROLLER" and e.value.word == "RAPL"


def test_engine_robot_words_offline_fail_clearly():
    with fbrl.Engine() as fb:
        with pytest.raises(fbrl.Error) as e:
            fb.eval("HOME")
        assert "controller" in str(e.value).lower()


def test_data_file_round_trip_and_types(tmp_path):
    path = tmp_path / "d.dat"
    loc = fbrl.Location(1.5, -2.25, 3.0, 90.0, -45.0, 10.0)
    with fbrl.DataFile(path, create=True) as f:
        f.write(fbrl.REAL, 7.25)
        f.write(fbrl.LONG, -123456)
        f.write(fbrl.LOCATION, loc)
        f.write(fbrl.user_type(9, 3), b"abc")
    with fbrl.DataFile(path) as f:
        assert len(f) == 4
        with pytest.raises(fbrl.Error) as e:
            f.read(fbrl.INTEGER)  # a REAL is there: refused, position kept
        assert e.value.name == "FBRL_ETYPE"
        assert list(f) == [(fbrl.REAL, 7.25), (fbrl.LONG, -123456), (fbrl.LOCATION, loc),
                           (fbrl.user_type(9, 3), b"abc")]


def test_a_file_written_in_python_reads_in_fbrl(tmp_path):
    path = tmp_path / "r.dat"
    with fbrl.DataFile(path, create=True) as f:
        f.write(fbrl.REAL, 2.5)
    with fbrl.Engine() as fb:
        out = fb.eval("FVARIABLE R  OPEN-FILE H %s  R REAL H READ-FILE R F@ F.  H CLOSE-FILE ." % path)
        assert out == "2.5 0 "


def test_an_exception_in_the_with_block_discards_changes(tmp_path):
    path = tmp_path / "k.dat"
    with fbrl.DataFile(path, create=True) as f:
        f.write(fbrl.CHR, 1)
    with pytest.raises(RuntimeError):
        with fbrl.DataFile(path) as f:
            f.append()
            f.write(fbrl.CHR, 2)
            raise RuntimeError("stop")
    with fbrl.DataFile(path) as f:
        assert list(f) == [(fbrl.CHR, 1)]


def test_three_point_calibration_maps_a_moved_block():
    # the block turned 30 degrees about z and moved by (2, 1, 0)
    ang = math.radians(30.0)

    def moved(p):
        return fbrl.Location(p.x * math.cos(ang) - p.y * math.sin(ang) + 2.0,
                             p.x * math.sin(ang) + p.y * math.cos(ang) + 1.0, p.z, 0.0, -90.0, 0.0)

    cal = [fbrl.Location(10, 0, 1, 0, -90, 0), fbrl.Location(14, 0, 1, 0, -90, 0), fbrl.Location(10, 3, 1, 0, -90, 0)]
    recal = [moved(p) for p in cal]
    c = fbrl.Calibration.three_point(cal, recal)
    probe = fbrl.Location(12, 2, 1, 0, -90, 0)
    got = c.map(probe)
    want = moved(probe)
    assert (got.x, got.y, got.z) == pytest.approx((want.x, want.y, want.z), abs=1e-9)
    back = c.unmap(got)
    assert (back.x, back.y, back.z) == pytest.approx((12, 2, 1), abs=1e-9)
    n = fbrl.Calibration.n_point(cal + [probe], recal + [want])
    assert n.rms == pytest.approx(0.0, abs=1e-9)


def test_collinear_points_raise_degenerate():
    cal = [fbrl.Location(0, 0, 0), fbrl.Location(1, 0, 0), fbrl.Location(2, 0, 0)]
    with pytest.raises(fbrl.Error) as e:
        fbrl.Calibration.three_point(cal, cal)
    assert e.value.name == "FBRL_EDEGENERATE"


def test_list_ports_reads_usb_details_and_by_id_names(tmp_path):
    sysfs, dev = tmp_path / "sys", tmp_path / "dev"
    usb = sysfs / "devices/usb1/1-1"
    (usb / "1-1:1.0/ttyUSB0").mkdir(parents=True)
    for name, text in (("idVendor", "0403"), ("idProduct", "6015"), ("product", "FT230X Basic UART"),
                       ("serial", "DN0ABC")):
        (usb / name).write_text(text + "\n")
    (sysfs / "class/tty/ttyUSB0").mkdir(parents=True)
    (sysfs / "class/tty/ttyUSB0/device").symlink_to(usb / "1-1:1.0/ttyUSB0")
    (dev / "serial/by-id").mkdir(parents=True)
    (dev / "ttyUSB0").write_text("")
    (dev / "serial/by-id/usb-FTDI_FT230X_DN0ABC-if00-port0").symlink_to(dev / "ttyUSB0")
    ports = fbrl.list_ports(str(sysfs), str(dev))
    assert len(ports) == 1
    p = ports[0]
    assert (p.vid, p.pid, p.serial, p.description) == (0x0403, 0x6015, "DN0ABC", "FT230X Basic UART")
    assert p.device == str(dev / "ttyUSB0")
    assert p.name == p.by_id == str(dev / "serial/by-id/usb-FTDI_FT230X_DN0ABC-if00-port0")


def test_a_port_opens_by_its_by_id_name(sim, tmp_path):
    by_id = tmp_path / "usb-FTDI_FT232R_USB_UART_A12345-if00-port0"
    by_id.symlink_to(sim.port)
    with fbrl.Port(str(by_id)) as port:
        fbrl.Link(port, echo_timeout_ms=500).home()
    assert "HOME" in sim.log()


def test_engine_on_moving_reads_the_arm_while_it_moves(tmp_path):
    """on_moving (fbrl_robot_set_watch): while a slow move waits for the arm, the watcher reads
    it (W2 in fbrlsim's log) at places on the way; an exception in it is kept and the motion goes
    on; None stops it."""
    s = Sim(tmp_path, time_scale="20")
    try:
        with fbrl.Port(s.port) as port:
            link = fbrl.Link(port, echo_timeout_ms=LOADED_HOST_ECHO_MS)
            with fbrl.Engine(link=link) as fb:
                fb.eval("HOME READY FINISH  CREATE-LOC SPOT 15.0 4.0 6.0 0.0 -90.0 0.0 SPOT DEFINE-LOC")
                seen = []
                fb.on_moving(lambda: seen.append(tuple(round(v, 3) for v in list(link.where().world)[:3])))
                n = len(s.log())
                fb.eval("1 SPEED SPOT MOV FINISH")
                assert s.log()[n:].count("W2") == len(seen) >= 3, (s.log()[n:], seen)
                assert len(set(seen)) == len(seen)  # each reading a different place on the way

                def broken():
                    raise RuntimeError("the view is gone")

                fb.on_moving(broken)
                fb.eval("3 SPEED READY FINISH")
                assert isinstance(fb.moving_error, RuntimeError)
                fb.on_moving(None)
                n = len(s.log())
                fb.eval("SPOT MOV FINISH 50 SPEED")
                assert "W2" not in s.log()[n:] and any(l.startswith("MOVE ") for l in s.log()[n:])
    finally:
        s.stop()
