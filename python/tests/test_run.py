# SPDX-License-Identifier: MIT
"""fbrl.Run: a method run from Python, its outcomes per sample and per run, requests from
another thread while it runs, and the sample-prep method against fbrlsim (its command log
the truth for what ran)."""
import os
import threading
import time

import pytest

import fbrl
from conftest import Sim, LOADED_HOST_ECHO_MS

SRC = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

METHOD = """VARIABLE BAD 0 BAD !
VARIABLE SAFE 0 SAFE !
: EACH ( i -- ) 1 OVER LSHIFT BAD @ AND IF S" no tube" SAMPLE-FAILED ELSE DROP THEN ;
: SLOW ( i -- ) DROP 40 MS ;
: TO-SAFE 1 SAFE ! ;
METHOD DEMO  a demonstration
1 12 3 SAMPLES-PARAM #TUBES tubes  the tubes
1 60 10 PARAM SOAK s  soaking
' EACH SAMPLE-STEP Each  each tube
' SLOW SAMPLE-STEP Slow  a little wait
' TO-SAFE ON-ABORT
END-METHOD
"""


def declare(fb, text):
    for line in text.splitlines():  # a declaration takes the rest of its line
        fb.eval(line)


def test_outcomes_per_sample_and_per_run():
    with fbrl.Engine() as fb:
        run = fbrl.Run(fb)
        declare(fb, METHOD)
        m = run.methods()[0]
        assert m["name"] == "DEMO" and [p["name"] for p in m["params"]] == ["#TUBES", "SOAK"]
        assert m["params"][0]["samples"] and (m["params"][1]["min"], m["params"][1]["max"]) == (1, 60)
        assert [s["per_sample"] for s in m["steps"]] == [True, True]
        r = run.start("DEMO", {"#tubes": 2})
        assert r["outcome"] == "completed" and r["state"] == "finished"
        assert r["samples"] == [{"sample": 1, "outcome": "succeeded", "reason": ""},
                                {"sample": 2, "outcome": "succeeded", "reason": ""}]
        fb.eval("2 BAD !")
        r = run.start("DEMO", [3, 10])
        assert r["outcome"] == "partial"
        assert r["samples"][1] == {"sample": 2, "outcome": "failed", "reason": "no tube"}
        fb.eval("7 BAD !")
        assert run.start("DEMO")["outcome"] == "failed"


def test_parameters_are_checked_before_anything_runs():
    with fbrl.Engine() as fb:
        run = fbrl.Run(fb)
        declare(fb, METHOD)
        with pytest.raises(ValueError, match="SOAK: 61 is outside 1..60 s"):
            run.start("DEMO", {"#TUBES": 2, "SOAK": 61})
        assert run.methods()[0]["params"][0]["value"] == 3  # nothing was set
        with pytest.raises(ValueError, match="no parameter"):
            run.start("DEMO", {"VOLUME": 2})
        with pytest.raises(TypeError):
            run.start("DEMO", {"SOAK": 2.5})
        with pytest.raises(fbrl.Error) as e:
            run.start("NO-SUCH", [])
        assert e.value.name == "FBRL_ENOENT"


def test_events_and_an_observer_that_raises():
    with fbrl.Engine() as fb:
        run = fbrl.Run(fb)
        declare(fb, METHOD)
        seen = []
        run.on_event(lambda e: seen.append((e["kind"], e.get("step_name"), e["sample"], e.get("outcome"))))
        run.start("DEMO", {"#TUBES": 1})
        assert seen == [("begin", None, None, None), ("step_begin", "Each", 1, None), ("step_end", "Each", 1, None),
                        ("step_begin", "Slow", 1, None), ("step_end", "Slow", 1, None),
                        ("sample", "Slow", 1, "succeeded"), ("end", "Slow", None, "completed")]

        def refuse(e):
            if e["kind"] == "begin":
                raise RuntimeError("no run log")
        run.on_event(refuse)
        with pytest.raises(RuntimeError, match="no run log"):
            run.start("DEMO")
        assert run.snapshot()["outcome"] is None  # it never began


def test_pause_resume_and_abort_from_another_thread():
    with fbrl.Engine() as fb:
        run = fbrl.Run(fb)
        declare(fb, METHOD)
        result = {}
        t = threading.Thread(target=lambda: result.update(run.start("DEMO", {"#TUBES": 12})))
        t.start()

        def until(state):
            for _ in range(500):
                s = run.snapshot()
                if s["state"] == state:
                    return s
                time.sleep(0.01)
            raise AssertionError("never %s: %s" % (state, run.snapshot()))
        until("running")
        run.pause("ann")
        s = until("paused")
        done = s["steps"][1]["done"]
        time.sleep(0.3)
        assert run.snapshot()["steps"][1]["done"] == done  # nothing ran while paused
        assert run.snapshot()["who"] == "ann"
        run.resume("bob")
        until("running")
        run.abort("cy")
        t.join(10)
        assert not t.is_alive()
        assert result["outcome"] == "aborted" and result["who"] == "cy"
        assert any(x["outcome"] == "skipped" for x in result["samples"])
        assert fb.eval("SAFE @ .").strip() == "1"  # ON-ABORT ran
        with pytest.raises(fbrl.Error):
            run.pause("late")  # no run goes


SEPARATION = """3 INPUT-DEVICE TUBE-ON-SEPARATOR
5 OUTPUT-DEVICE SEPARATOR-VACUUM
: SEPARATE ( n -- ) TUBE-ON-SEPARATOR TRUE 300 WAIT-INPUT IF 50 SEPARATOR-VACUUM PULSE DROP
   ELSE S" its tube never reached the separation unit's sensor" SAMPLE-FAILED THEN ;
METHOD SEP  the separation step of the sample preparation
1 12 2 SAMPLES-PARAM #SAMPLES tubes  the tubes
' SEPARATE SAMPLE-STEP Separation  vacuum when the tube is there
END-METHOD
"""


def run_separation(port):
    with fbrl.Port(port) as p:
        link = fbrl.Link(p, echo_timeout_ms=LOADED_HOST_ECHO_MS)
        with fbrl.Engine(link=link) as fb:
            run = fbrl.Run(fb)
            declare(fb, SEPARATION)
            return run.start("SEP", {"#SAMPLES": 2})


def test_a_method_on_fbrlsim_with_and_without_the_tube(sim, tmp_path):
    """The controller's log is the truth: the vacuum valve opened once per sample that
    succeeded; without the tube both samples failed, with why."""
    r = run_separation(sim.port)
    why = "its tube never reached the separation unit's sensor"
    assert r["outcome"] == "failed"
    assert r["samples"] == [{"sample": 1, "outcome": "failed", "reason": why},
                            {"sample": 2, "outcome": "failed", "reason": why}]
    assert "TYPEI SIG(3)" in sim.log() and "OUTPUT 5" not in sim.log()
    (tmp_path / "tube").mkdir()
    tube = Sim(tmp_path / "tube", "--inputs", os.path.join(SRC, "examples", "tube_present.inputs"))
    try:
        r = run_separation(tube.port)
        assert r["outcome"] == "completed" and [x["outcome"] for x in r["samples"]] == ["succeeded"] * 2
        assert tube.log().count("OUTPUT 5") == 2 and tube.log().count("OUTPUT -5") == 2
    finally:
        tube.stop()
