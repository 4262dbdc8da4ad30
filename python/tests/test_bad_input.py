# SPDX-License-Identifier: MIT
"""Bad input gets one clear error before anything reaches C or the controller (issue 28
item 2): fbrlsim's log is the truth for what ran. The cases that used to hang or loop
(/dev/zero, a FIFO, a name that is not UTF-8) run in a child Python with a deadline, so a
relapse fails here instead of hanging the suite."""
import gc
import os
import subprocess
import sys
import textwrap

import pytest

import fbrl

HERE = os.path.dirname(os.path.abspath(__file__))
CHILD_SECONDS = 30  # a child that takes longer hangs: the bug is back


def child(code, tmp_path):
    """Run code in a fresh Python (the package under test); its (status, stdout, stderr)."""
    env = dict(os.environ, PYTHONPATH=os.path.dirname(HERE))
    p = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], cwd=str(tmp_path), env=env,
                       capture_output=True, text=True, timeout=CHILD_SECONDS)
    return p.returncode, p.stdout, p.stderr


# ---- the link: C would stop at a NUL and run the rest's start ----

def test_a_nul_in_a_raw_line_is_refused_before_anything_runs(sim, link):
    with pytest.raises(ValueError) as e:
        link.raw("OUTPUT 3\x00 junk")
    assert "NUL" in str(e.value)
    assert not any(l.startswith("OUTPUT") for l in sim.log())
    assert not link.status().output(3)


def test_a_nul_in_a_typev_expression_is_refused(sim, link):
    with pytest.raises(ValueError):
        link.typev("V1\x00+1")
    with pytest.raises(ValueError):
        link.typei("SIG(3)\x00")
    assert not any(l.startswith("TYPE") for l in sim.log())


@pytest.mark.parametrize("line", ["W2?", "A" * 81, "OUTPUT 3\r", "HOME\n", "", "MOVE P\u00e9"])
def test_what_the_line_check_refuses_is_a_value_error(sim, link, line):
    before = sim.log()
    with pytest.raises(ValueError):
        link.raw(line)
    with pytest.raises(ValueError):
        link.typev(line or "?")
    assert sim.log() == before  # nothing was sent


def test_wrong_types_are_type_errors(sim, link):
    for bad in ((None,), (1.5j,), (True,), ([1],), (b"P1", None)):
        with pytest.raises(TypeError):
            link.command("MOVE", *bad)
    with pytest.raises(TypeError):
        link.command(None)
    with pytest.raises(TypeError):
        link.raw(3)
    with pytest.raises(TypeError):
        link.speed("50")
    with pytest.raises(TypeError):
        link.output(None, True)
    with pytest.raises(ValueError):
        link.command("MOVE", "P1\x00X")
    assert not any(l.startswith(("MOVE", "SPEED", "OUTPUT")) for l in sim.log())


def test_bad_port_and_link_arguments(sim, tmp_path):
    with pytest.raises(ValueError):
        fbrl.Port(sim.port + "\x00junk")
    with pytest.raises(TypeError):
        fbrl.Port(None)
    with pytest.raises(TypeError):
        fbrl.Port(sim.port, baud=None)
    with pytest.raises(ValueError):
        fbrl.Port(sim.port, parity="none\x00")
    with pytest.raises(TypeError):
        fbrl.Link("not a port")
    with fbrl.Port(sim.port) as port:
        with pytest.raises(TypeError):
            fbrl.Link(port, echo_timeout_ms="500")
        with pytest.raises(ValueError):
            fbrl.Link(port, echo_timeout_ms=-1)
        fbrl.Link(port, echo_timeout_ms=500, max_attempts=None).home()  # None keeps the default


def test_a_dropped_port_is_closed(sim):
    port = fbrl.Port(sim.port)
    fbrl.Link(port, echo_timeout_ms=500).home()
    with pytest.raises(fbrl.Error) as e:
        fbrl.Port(sim.port)  # the device is locked while it is open
    assert e.value.name == "FBRL_EBUSY"
    del port
    gc.collect()
    with fbrl.Port(sim.port) as again:  # the lock went with it
        fbrl.Link(again, echo_timeout_ms=500).home()
    assert sim.log().count("HOME") == 2


# ---- the engine's host: regular files only, a bounded line, no exception lost ----

def test_a_device_a_fifo_and_an_endless_line_are_refused(tmp_path):
    fifo = tmp_path / "fifo.fbrl"
    os.mkfifo(str(fifo))
    endless = tmp_path / "endless.fbrl"
    endless.write_bytes(b"1 " * (4 << 20))  # 8 MB without a line end
    status, out, err = child('''
        import fbrl
        with fbrl.Engine() as fb:
            for path in ("/dev/zero", "fifo.fbrl", "endless.fbrl"):
                try:
                    fb.include(path)
                    print(path, "ran")
                except fbrl.Error as e:
                    print(path, e.throw_code, e.message)
            print(fb.eval("2 3 + ."))
        ''', tmp_path)
    assert status == 0, err
    assert out.split("\n") == [
        "/dev/zero -38 cannot open /dev/zero: not a regular file (a device, FIFO or directory)",
        "fifo.fbrl -38 cannot open fifo.fbrl: not a regular file (a device, FIFO or directory)",
        "endless.fbrl -18 input line too long", "5 ", ""]
    assert err == ""


def test_a_name_that_is_not_utf8_is_read_and_nothing_loops(tmp_path):
    name = b"prog-\xff.fbrl"
    with open(os.path.join(os.fsencode(str(tmp_path)), name), "wb") as f:
        f.write(b": ANSWER 42 ;\n")
    status, out, err = child(r'''
        import os, fbrl
        with fbrl.Engine() as fb:
            fb.include(b"prog-\xff.fbrl")
            fb.include(os.fsdecode(b"prog-\xff.fbrl"))
            print(fb.eval("ANSWER ."))
            try:
                fb.eval('S" prog-\xff.fbrl" INCLUDED')  # the text is UTF-8: another name
            except fbrl.Error as e:
                print(e.name)
        ''', tmp_path)
    assert status == 0, err
    assert out == "42 \nFBRL_ETHROW\n"
    assert err == ""  # no traceback from a callback


class Failing(fbrl.Engine):
    """An engine whose host callbacks fail, as a full disk or a bug would make them."""

    fail = None

    def _file_read_line(self, user, handle, buf, cap, n):
        if self.fail == "read":
            raise RuntimeError("the disk went away")
        return super()._file_read_line(user, handle, buf, cap, n)

    def _write(self, user, s, n):
        if self.fail == "write":
            raise MemoryError("no room for the output")
        return super()._write(user, s, n)


def test_an_exception_in_a_callback_is_an_error_and_is_not_lost(tmp_path):
    src = tmp_path / "p.fbrl"
    src.write_text("1 2 +\n")
    with Failing() as fb:
        fb.fail = "read"
        with pytest.raises(fbrl.Error) as e:
            fb.include(src)
        assert isinstance(e.value.__cause__, RuntimeError)
        assert "the disk went away" in str(e.value)
        fb.fail = "write"
        with pytest.raises(MemoryError):
            fb.eval("7 .")
        fb.fail = None
        assert fb.eval("8 .") == "8 "


def test_use_after_bye_raises():
    with fbrl.Engine() as fb:
        fb.eval("BYE")
        assert fb.bye
        with pytest.raises(fbrl.Error) as e:
            fb.eval("1 .")
        assert e.value.name == "FBRL_ESTATE" and "BYE" in str(e.value)
        with pytest.raises(fbrl.Error):
            fb.include("/dev/null")


def test_engine_arguments_have_their_types():
    with pytest.raises(TypeError):
        fbrl.Engine(link="not a link")
    with fbrl.Engine() as fb:
        with pytest.raises(TypeError):
            fb.eval(b"1 .")
        with pytest.raises(TypeError):
            fb.push("5")
        with pytest.raises(ValueError):
            fb.include("p.fbrl\x00.txt")
