# SPDX-License-Identifier: MIT
"""Stopping the arm from Python (issue 27 item 5), against fbrlsim in real time on a
9600-baud line: a 60 s move, halt(), and a real SIGINT sent to this process while it
waits. fbrlsim's stamped log (seconds on its clock, result, line) is the truth for when
HALT ran; W2 readings for where the arm stopped."""
import os
import signal
import statistics
import threading
import time

import pytest

import fbrl
from conftest import LOADED_HOST_ECHO_MS, Sim

TARGET = fbrl.Location(10.0, -12.0, 3.0, 0.0, -90.0, 0.0)
SLOW = 2  # SPEED 2: READY to TARGET takes about 60 s on fbrlsim
MOVING_S = 2.0  # into the move when it is stopped
SHORT_IN = 5.0  # the arm stopped at least this far from the target (inches)
STILL_IN = 0.01  # two readings of a standing arm agree within this
SIGNAL_TO_HALT_MAX_S = 1.0  # generous: a W5 round trip at 9600 baud is about 0.1 s, the move has 58 s left
OUTPUT = 3  # switched on by the program before the move: the stop switches it off


def stamped(sim):
    """fbrlsim's log as (seconds, result, line)."""
    out = []
    for line in sim.log():
        t, st, text = line.split(" ", 2)
        out.append((float(t), st, text))
    return out


def start_long_move(link):
    link.home()
    link.ready()
    link.finish()
    link.point("P1", TARGET)
    link.speed(SLOW)
    link.output(OUTPUT, True)
    link.move("P1")


def clock_offset(sim, link):
    """(lo, hi): this process's monotonic time minus fbrlsim's clock lies between them (a
    line both clocks saw: fbrlsim stamps when its CR came)."""
    a = time.monotonic()
    link.raw("V9=1")
    b = time.monotonic()
    t = [t for t, st, text in stamped(sim) if text == "V9=1"][-1]
    return a - t, b - t


@pytest.fixture
def slow_link(realtime_sim):
    with fbrl.Port(realtime_sim.port) as port:
        yield fbrl.Link(port, echo_timeout_ms=LOADED_HOST_ECHO_MS)


def test_halt_stops_a_move_short(realtime_sim, slow_link):
    link = slow_link
    start_long_move(link)
    time.sleep(MOVING_S)
    link.halt()
    first = link.where().world
    time.sleep(1.0)
    second = link.where().world
    link.finish()  # returns at once: nothing moves
    ready = fbrl.Location(12.0, 0.0, 20.0, 0.0, 0.0, 0.0)
    assert first.distance(ready) > 0.1, "the arm never moved"
    assert first.distance(TARGET) > SHORT_IN, "the arm was not stopped short: %s" % first
    assert second.distance(first) < STILL_IN, "the arm went on moving after HALT"
    assert not link.moving
    lines = [text for t, st, text in stamped(realtime_sim)]
    assert lines.index("HALT") > lines.index("MOVE P1")
    assert lines[-2:] == ["W2", "FINISH"]  # HALT ran: no W5 to wait for, FINISH at once


def interrupt_after(seconds, sent):
    def fire():  # the signal went between the two readings: the later one bounds what may follow it
        before = time.monotonic()
        os.kill(os.getpid(), signal.SIGINT)
        sent.append((before, time.monotonic()))
    timer = threading.Timer(seconds, fire)
    timer.start()
    return timer


def check_stopped_by_the_signal(sim, stop, sent, offset):
    """HALT is the first line fbrlsim took after the signal (only a line already on its way
    ended first) and came within a round trip; the outputs this program switched on are
    off; the arm stands far short of the target."""
    lo, hi = offset
    log = stamped(sim)
    earliest, latest = sent[0] - hi, sent[1] - lo  # the signal on fbrlsim's clock
    halt = [t for t, st, text in log if text == "HALT"]
    assert len(halt) == 1 and halt[0] > earliest
    # Python runs its handler between bytecodes: a W5 read the main thread had begun to call as
    # the signal came may still start; it ends within its round trip and HALT follows. Nothing
    # else may start (a motion, an output, a second read).
    started_after = [text for t, st, text in log if latest < t < halt[0]]
    assert started_after in ([], ["W5"]), "lines started between the signal and HALT: %s" % started_after
    w5 = [t for t, st, text in log if text == "W5"]
    period = statistics.median(b - a for a, b in zip(w5, w5[1:])) if len(w5) > 2 else float("nan")
    print("signal to HALT: at most %.3f s (clock sync +- %.3f s); W5 readings every %.3f s while waiting"
          % (halt[0] - earliest, (hi - lo) / 2, period))
    assert halt[0] - earliest < SIGNAL_TO_HALT_MAX_S
    after = [text for t, st, text in log if t >= halt[0]]
    assert "OUTPUT -%d" % OUTPUT in after
    assert stop.halted and stop.ok and stop.was_moving and stop.motion == "MOVE P1"
    assert stop.switched_off == [OUTPUT] and stop.left_on == []
    assert stop.where.distance(TARGET) > SHORT_IN


def test_ctrl_c_during_finish_halts_within_a_round_trip(realtime_sim, slow_link):
    link = slow_link
    start_long_move(link)
    offset = clock_offset(realtime_sim, link)
    sent = []
    timer = interrupt_after(MOVING_S, sent)
    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt) as e:
        link.finish()
    timer.join()
    assert time.monotonic() - t0 < MOVING_S + 5.0  # not the move's 60 s
    assert "arm halted while moving (MOVE P1)" in str(e.value)
    check_stopped_by_the_signal(realtime_sim, e.value.stop, sent[0], offset)
    first = link.where().world
    time.sleep(1.0)
    assert link.where().world.distance(first) < STILL_IN
    assert not link.status().output(OUTPUT)


def test_ctrl_c_during_an_fbrl_wait_halts(realtime_sim, slow_link):
    link = slow_link
    with fbrl.Engine(link=link) as fb:
        fb.eval("FINISH")  # its robot words now know the arm stands
        start_long_move(link)  # moved through the link: they must ask again (W5), not send FINISH
        offset = clock_offset(realtime_sim, link)
        sent = []
        timer = interrupt_after(MOVING_S, sent)
        with pytest.raises(KeyboardInterrupt) as e:
            fb.eval("FINISH")
        timer.join()
        check_stopped_by_the_signal(realtime_sim, e.value.stop, sent[0], offset)
        assert fb.eval("1 2 + .") == "3 "  # the engine goes on


def test_ctrl_c_in_the_program_s_own_code_stops_the_arm(realtime_sim, slow_link):
    link = slow_link
    sent = []
    with pytest.raises(KeyboardInterrupt) as e:
        with link:
            start_long_move(link)
            interrupt_after(MOVING_S, sent).join()
            time.sleep(5.0)  # the program's own wait: KeyboardInterrupt comes here
    stop = e.value.stop
    assert stop.halted and stop.motion == "MOVE P1" and stop.switched_off == [OUTPUT]
    assert stop.where.distance(TARGET) > SHORT_IN


def test_ctrl_c_while_the_controller_waits_says_halt_could_not_be_sent(sim, link):
    """A WAIT for an input that never comes: the controller reads nothing else, HALT cannot
    be typed; the stop says so (FBRL_EBUSY) instead of claiming the arm was halted."""
    sent = []
    interrupt_after(0.5, sent)
    with pytest.raises(KeyboardInterrupt) as e:
        link.raw("WAIT 5")
    stop = e.value.stop
    assert stop.name == "FBRL_EBUSY" and not stop.halted and not stop.ok
    assert "HALT could not be sent" in str(e.value)
    assert "HALT" not in sim.log()


def test_safe_stop_names_the_outputs_a_plain_status_does_not_show(tmp_path):
    """A controller whose STATUS has no OUTPUTS line (every RAPL-II one; fbrlsim without
    --status-extra): the stop switches off what this program switched on and names every
    other output as not known, with why, instead of "STATUS could not be read"."""
    sim = Sim(tmp_path, status_extra=False)
    try:
        with fbrl.Port(sim.port) as port:
            link = fbrl.Link(port, echo_timeout_ms=LOADED_HOST_ECHO_MS)
            link.connect()
            link.output(OUTPUT, True)
            stop = link.safe_stop()
        after = sim.log()[sim.log().index("HALT"):]
        assert after[:2] == ["HALT", "STATUS"] and "OUTPUT -%d" % OUTPUT in after
        assert stop.ok and stop.halted and stop.switched_off == [OUTPUT] and stop.left_on is None
        assert stop.unknown == [n for n in range(1, 17) if n != OUTPUT] and stop.homed is not None
        assert "STATUS could not be read" not in str(stop)
        assert "not known: 1-2 4-16 (this controller's STATUS does not show its outputs" in str(stop)
    finally:
        sim.stop()
