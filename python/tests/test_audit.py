# SPDX-License-Identifier: MIT
"""fbrl.AuditTrail and fbrl.RunLog: records a Python program keeps in a lab's audit trail. The
truth is outside the bindings: fbrl-audit (C) verifies the chain, and fbrlsim's log is what
the controller ran."""
import json
import os
import subprocess

import pytest

import fbrl
from conftest import Sim, LOADED_HOST_ECHO_MS, fbrl_audit_path
from test_run import SEPARATION, SRC, declare

fbrl_audit = fbrl_audit_path


def records(path):
    with open(path) as f:
        return [json.loads(line) for line in f]


def test_a_run_on_fbrlsim_is_in_the_chain_as_the_controller_ran_it(tmp_path):
    tube = Sim(tmp_path, "--inputs", os.path.join(SRC, "examples", "tube_present.inputs"))
    chain = str(tmp_path / "audit.jsonl")
    try:
        with fbrl.Port(tube.port) as p:
            link = fbrl.Link(p, echo_timeout_ms=LOADED_HOST_ECHO_MS)
            with fbrl.Engine(link=link) as fb, fbrl.AuditTrail(chain) as trail:
                run = fbrl.Run(fb)
                declare(fb, SEPARATION)
                trail.record("method_run", "ann", method="SEP", state="Draft")
                trail.set_user("ann")  # the run log's records are hers
                before = len(tube.log())
                log = run.record(fbrl.RunLog(trail, "SEP", operator="ann", program="test_audit",
                                             params=[("#SAMPLES", 2, "tubes")]))
                link.on_exec(log.command)
                r = run.start("SEP", {"#SAMPLES": 2})
        ran = tube.log()[before:]
    finally:
        tube.stop()
    assert r["outcome"] == "completed"
    out = subprocess.run([fbrl_audit(), "verify", chain], capture_output=True, text=True)
    assert out.returncode == 0 and "intact, sealed" in out.stdout, out.stdout + out.stderr
    recs = records(chain)
    assert [x["type"] for x in recs[:2]] == ["method_run", "header"] and recs[-1]["type"] == "seal"
    assert recs[1]["method"] == "SEP" and recs[1]["operator"] == "ann"
    summary = next(x for x in recs if x["type"] == "summary")
    assert summary["outcome"] == "completed" and [s["outcome"] for s in summary["samples"]] == ["succeeded"] * 2
    # every line the controller ran during the run, in its order, and nothing else
    commands = []
    for x in recs:
        if x["type"] == "command":
            commands += [x["line"]] * x.get("count", 1)
    assert commands == ran and len(ran) > 5, (commands, ran)
    assert ran.count("OUTPUT 5") == 2
    assert all(x["user"] == "ann" for x in recs if x["type"] != "seal")


def test_a_broken_chain_is_refused_and_nothing_is_written(tmp_path):
    chain = str(tmp_path / "audit.jsonl")
    with fbrl.AuditTrail(chain) as trail:
        trail.record("login", "ann", purpose="page", name="ann", outcome="accepted")
    text = open(chain).read()
    with open(chain, "w") as f:
        f.write(text.replace('"accepted"', '"accepteD"', 1))
    with pytest.raises(fbrl.Error) as e:
        fbrl.AuditTrail(chain).open()
    assert e.value.name == "FBRL_ECHECKSUM" and "record 1 (line 1)" in str(e.value), str(e.value)
    assert open(chain).read() == text.replace('"accepted"', '"accepteD"', 1)


def test_one_writer_at_a_time(tmp_path):
    chain = str(tmp_path / "audit.jsonl")
    first = fbrl.AuditTrail(chain).open()
    try:
        with pytest.raises(fbrl.Error) as e:
            fbrl.AuditTrail(chain).open(wait_s=0.3)
        assert e.value.name == "FBRL_EBUSY" and "another program" in str(e.value)
    finally:
        first.close()
    with fbrl.AuditTrail(chain) as second:  # free again
        second.record("action", "bob", action="test")
    out = subprocess.run([fbrl_audit(), "verify", chain], capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr
