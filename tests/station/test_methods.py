# SPDX-License-Identifier: MIT
"""MethodLibrary, PauseController, CancelController and ErrorRecoveryService: method runs on
the library's run, against fbrlsim (its log is the truth of what the controller did)."""
import os
import threading
import time

import pytest
from lxml import etree

from client import Failure
from conftest import ROOT, MethodLab, assert_aborted_safely, wait_for
from fbrl_station import pb
from fbrl_station.sila import I, R, S

ML, ARM, PAUSE, CANCEL, ERR = "MethodLibrary", "ArmController", "PauseController", "CancelController", \
    "ErrorRecoveryService"
mm, am = pb.messages(ML), pb.messages(ARM)
HERE = os.path.dirname(os.path.abspath(__file__))
P = mm.RunMethod_Parameters.Parameters_Struct
DONE = pb.fw.ExecutionInfo.CommandStatus.Value("finishedSuccessfully")


class Lab(MethodLab):
    """A method library (sample prep and the tests' methods), an fbrlsim whose inputs the test
    sets (--control), a station on it."""

    def set_input(self, n, on):
        self.sim.control("IN %d %d" % (n, 1 if on else 0))


@pytest.fixture(scope="module")
def lab(tmp_path_factory):
    lab = Lab(str(tmp_path_factory.mktemp("lab")))
    yield lab
    lab.stop()


def params(**kw):
    """Parameter values by name: N_SAMPLES=2 is #SAMPLES, REACTION_MIN is REACTION-MIN."""
    return [P(Name=S(("#" + k[2:] if k.startswith("N_") else k).replace("_", "-")), Value=I(v)) for k, v in kw.items()]


def start(lab, method, *ps):
    return lab.client.start(ML, "RunMethod", Method=S(method), Parameters=list(ps))


def follow(lab, uuid):
    """(result or Failure, the intermediate Progress messages, the ExecutionInfo messages)."""
    inter = []
    t = threading.Thread(target=lambda: inter.extend(m.Progress for m in lab.client.intermediate(ML, "RunMethod",
                                                                                                    uuid)),
                         daemon=True)
    t.start()
    infos = list(lab.client.info(ML, "RunMethod", uuid))
    t.join(30)
    try:
        return lab.client.result(ML, "RunMethod", uuid), inter, infos
    except Failure as f:
        return f, inter, infos


def collect(lab, uuid):
    """The intermediate responses of execution uuid from now on, gathered by a thread (join
    it once the execution has ended)."""
    got = []
    t = threading.Thread(target=lambda: got.extend(m.Progress for m in lab.client.intermediate(ML, "RunMethod",
                                                                                                  uuid)),
                         daemon=True)
    t.start()
    return got, t


def events(inter):
    return [(p.Event.value, p.StepName.value, p.Sample.value) for p in inter]


def wait_for_event(lab, uuid, event, step=None):
    """Read the intermediate stream until event (of step) comes; the stream is cancelled."""
    stream = lab.client.intermediate(ML, "RunMethod", uuid)
    for m in stream:
        if m.Progress.Event.value == event and (step is None or m.Progress.StepName.value == step):
            return m.Progress
    pytest.fail("no %s %s" % (event, step or ""))


# ------------------------------------------------------------------ the library
def test_methods_list_parameters_with_their_ranges_as_sila_constraints(lab):
    methods = {m.Name.value: m for m in lab.client.get(ML, "Methods")}
    assert {"SAMPLE-PREP", "QUICK", "VIAL-CHECK", "BUMP", "FAR-AWAY"} <= set(methods)
    sp = methods["SAMPLE-PREP"]
    assert sp.File.value.endswith("sample_prep.fbrl")
    ps = {p.Name.value: p for p in sp.Parameters}
    assert ps["#SAMPLES"].Unit.value == "tubes" and ps["#SAMPLES"].Default.value == 3
    assert [(s.Name.value, s.PerSample.value) for s in sp.Steps][:2] == [("Recalibrate", False), ("Buffer", True)]
    xsd = os.path.join(HERE, "reference", "schema", "Constraints.xsd")
    wrapper = ('<xs:schema xmlns:xs="http://www.w3.org/2001/XMLSchema" xmlns:tns="http://www.sila-standard.org" '
               'targetNamespace="http://www.sila-standard.org" elementFormDefault="qualified">'
               '<xs:include schemaLocation="%s"/><xs:element name="Constraints" type="tns:Constraints"/></xs:schema>'
               % xsd)
    schema = etree.XMLSchema(etree.fromstring(wrapper.encode()))
    ns = "{http://www.sila-standard.org}"
    for p in sp.Parameters:
        doc = etree.fromstring(p.Constraints.value.encode())
        assert schema.validate(doc), (p.Name.value, schema.error_log)
    reaction = etree.fromstring(ps["REACTION-MIN"].Constraints.value.encode())
    assert reaction.findtext(ns + "MinimalInclusive") == "1" and reaction.findtext(ns + "MaximalInclusive") == "120"
    assert reaction.find(ns + "Unit").findtext(ns + "Factor") == "60.0"  # min: 60 s
    assert reaction.find(ns + "Unit").find(ns + "UnitComponent").findtext(ns + "SIUnit") == "Second"


def test_parameters_out_of_range_or_unknown_are_refused_before_anything_runs(lab):
    before = len(lab.sim.log())
    for ps, says in ((params(N_SAMPLES=99), "99 is outside 1..24 tubes"), (params(SPEED=3), "no parameter SPEED")):
        with pytest.raises(Failure) as e:
            start(lab, "SAMPLE-PREP", *ps)
        assert e.value.kind == "validationError" and says in e.value.message
        assert e.value.identifier.endswith("/RunMethod/Parameter/Parameters")
    result, _, _ = follow(lab, start(lab, "NO-SUCH-METHOD"))
    assert isinstance(result, Failure) and result.identifier == "UnknownMethod"
    assert lab.sim.log()[before:] == []


# ------------------------------------------------------------------ runs
def test_a_run_reports_each_step_and_sample_and_its_outcomes(lab):
    before = len(lab.sim.log())
    result, inter, infos = follow(lab, start(lab, "QUICK", *params(N_ITEMS=2, HOLD_DS=1)))
    assert not isinstance(result, Failure), result
    assert result.Outcome.value == "completed"
    assert [(s.Sample.value, s.Outcome.value) for s in result.Samples] == [(1, "succeeded"), (2, "succeeded")]
    assert events(inter) == [("StepStarted", "Home", 0), ("StepEnded", "Home", 0), ("StepStarted", "Item", 1),
                             ("StepEnded", "Item", 1), ("StepStarted", "Item", 2), ("StepEnded", "Item", 2)]
    assert infos[-1].commandStatus == DONE and infos[-1].progressInfo.value == 1.0
    log = lab.sim.log()[before:]
    assert log.count("OUTPUT 1") == 2 and log.count("OUTPUT -1") == 2 and "HOME" in log


def test_samples_that_fail_make_the_outcome(lab):
    """No tube ever reaches the separator's sensor: the method marks each sample failed."""
    lab.set_input(3, False)
    result, _, _ = follow(lab, start(lab, "SAMPLE-PREP", *params(N_SAMPLES=1, REACTION_MIN=1)))
    assert not isinstance(result, Failure), result
    assert result.Outcome.value == "failed"
    assert [(s.Outcome.value, bool(s.Reason.value)) for s in result.Samples] == [("failed", True)]


def test_a_run_beyond_reach_is_refused_before_a_byte_is_sent(lab):
    before = len(lab.sim.log())
    result, inter, _ = follow(lab, start(lab, "FAR-AWAY"))
    assert isinstance(result, Failure) and result.identifier == "CollisionRefused", result
    assert "beyond the arm's reach" in result.message and ("StepFailed", "Reach", 0) in events(inter)
    assert not [l for l in lab.sim.log()[before:] if l.startswith(("POINT SPOT", "MOVE SPOT"))]


def test_a_run_the_controller_refuses_carries_its_code(lab):
    lab.sim.control("POWER 0")  # the arm's power off at the panel: HOME is refused (040)
    try:
        result, inter, _ = follow(lab, start(lab, "FAR-AWAY"))
    finally:
        lab.sim.control("POWER 1")
    assert isinstance(result, Failure) and result.identifier == "ControllerRefused", result
    assert "040" in result.message and ("StepFailed", "Reach", 0) in events(inter)


def test_a_run_stopped_by_the_guard_is_collision_refused(lab):
    before = len(lab.sim.log())
    result, inter, _ = follow(lab, start(lab, "BUMP"))
    assert isinstance(result, Failure) and result.identifier == "CollisionRefused", result
    assert "HEATING-BLOCK" in result.message and ("StepFailed", "Into", 0) in events(inter)
    assert not [l for l in lab.sim.log()[before:] if l.startswith("MOVE")]


# ------------------------------------------------------------------ pause, busy, cancel
def test_pause_resume_and_the_arm_is_busy_meanwhile(lab):
    uuid = start(lab, "QUICK", *params(N_ITEMS=2, HOLD_DS=5))
    wait_for_event(lab, uuid, "StepStarted", "Item")
    lab.client.call(PAUSE, "Pause", CommandExecutionUUID=pb.messages(PAUSE).DataType_UUID(UUID=S(uuid)))
    assert lab.client.get(PAUSE, "Paused").value
    wait_for_event(lab, uuid, "Paused")
    with pytest.raises(Failure) as e:  # paused already
        lab.client.call(PAUSE, "Pause", CommandExecutionUUID=pb.messages(PAUSE).DataType_UUID(UUID=S(uuid)))
    assert e.value.identifier == "InvalidCommandState"
    site = pb.messages("RobotController").DataType_Site
    for call in (lambda: lab.client.start(ARM, "Home"),
                 lambda: lab.client.start("RobotController", "MovePlate", OriginSite=site(
                     Site=site.Site_Struct(Device=S("SEPARATOR"), SiteIndex=I(0))), DestinationSite=site(
                     Site=site.Site_Struct(Device=S("RINSE-REST"), SiteIndex=I(0))), PlateType=S("TUBE")),
                 lambda: lab.client.call(ARM, "Grip", Width=am.DataType_Opening(Opening=R(1.0)), Force=I(40))):
        with pytest.raises(Failure) as e:
            call()
        assert e.value.identifier == "StationBusy" and "QUICK" in e.value.message
    n = len(lab.sim.log())
    time.sleep(1.0)
    assert len(lab.sim.log()) == n  # nothing is sent while it is paused
    lab.client.call(PAUSE, "Resume", CommandExecutionUUID=pb.messages(PAUSE).DataType_UUID(UUID=S(uuid)))
    result, inter, _ = follow(lab, uuid)
    assert not isinstance(result, Failure) and result.Outcome.value == "completed"
    with pytest.raises(Failure) as e:
        lab.client.call(PAUSE, "Resume", CommandExecutionUUID=pb.messages(PAUSE).DataType_UUID(UUID=S(uuid)))
    assert e.value.identifier == "InvalidCommandState"


def test_cancel_is_the_console_s_abort(lab):
    before = len(lab.sim.log())
    uuid = start(lab, "QUICK", *params(N_ITEMS=3, HOLD_DS=50))
    wait_for(lambda: "OUTPUT 1" in lab.sim.log()[before:], what="the pump to run")
    lab.client.call(CANCEL, "CancelCommand", CommandExecutionUUID=pb.messages(CANCEL).DataType_UUID(UUID=S(uuid)))
    result, inter, infos = follow(lab, uuid)
    assert isinstance(result, Failure) and result.identifier == "MethodCancelled", result
    assert "sample 1" in result.message
    assert_aborted_safely(lab.sim.log()[before:])


def test_cancel_and_pause_know_what_they_can_act_on(lab):
    u = lab.client.start(ARM, "Home")
    list(lab.client.info(ARM, "Home", u))
    U = pb.messages(CANCEL).DataType_UUID
    with pytest.raises(Failure) as e:
        lab.client.call(CANCEL, "CancelCommand", CommandExecutionUUID=U(UUID=S(u)))
    assert e.value.identifier == "OperationNotSupported"
    with pytest.raises(Failure) as e:
        lab.client.call(PAUSE, "Pause", CommandExecutionUUID=pb.messages(PAUSE).DataType_UUID(UUID=S(u)))
    assert e.value.identifier == "OperationNotSupported"
    for feature, command in ((CANCEL, "CancelCommand"), (PAUSE, "Pause"), (PAUSE, "Resume")):
        with pytest.raises(Failure) as e:
            lab.client.call(feature, command, CommandExecutionUUID=pb.messages(feature).DataType_UUID(
                UUID=S("12345678-1234-1234-1234-123456789abc")))
        assert e.value.identifier == "InvalidCommandExecutionUUID"
    with pytest.raises(Failure) as e:
        lab.client.call(CANCEL, "CancelCommand", CommandExecutionUUID=U(UUID=S("not-a-uuid")))
    assert e.value.kind == "validationError"


def test_cancel_all_ends_the_run_and_the_one_waiting(lab):
    before = len(lab.sim.log())
    first = start(lab, "QUICK", *params(N_ITEMS=3, HOLD_DS=50))
    second = start(lab, "QUICK", *params(N_ITEMS=1, HOLD_DS=1))
    wait_for(lambda: "OUTPUT 1" in lab.sim.log()[before:], what="the first run's pump")
    lab.client.call(CANCEL, "CancelAll")
    r1, _, _ = follow(lab, first)
    r2, inter2, _ = follow(lab, second)
    assert r1.identifier == "MethodCancelled" and r2.identifier == "MethodCancelled"
    assert "before it started" in r2.message and inter2 == []
    assert lab.sim.log()[before:].count("OUTPUT 1") == 1


# ------------------------------------------------------------------ recoverable errors
def recoverable(lab):
    stream = lab.client.subscribe(ERR, "RecoverableErrors")
    for m in stream:
        if m.RecoverableErrors:
            stream.cancel()
            return [e.RecoverableError for e in m.RecoverableErrors]
    return []


def test_a_question_is_a_recoverable_error_and_retry_answers_it(lab):
    lab.set_input(4, False)
    uuid = start(lab, "VIAL-CHECK", *params(N_VIALS=1))
    inter, collector = collect(lab, uuid)
    errors = recoverable(lab)
    assert len(errors) == 1 and "sample 1" in errors[0].ErrorMessage.value
    e = errors[0]
    assert e.CommandExecutionUUID.value == uuid and e.CommandIdentifier.value.endswith("/Command/RunMethod")
    assert e.ErrorIdentifier.value == "org.libfbrl/robot/MethodLibrary/v1/DefinedExecutionError/StepFailed"
    assert e.ErrorMessage.value and e.ErrorTime.year >= 2020
    assert [o.ContinuationOption.Identifier.value for o in e.ContinuationOptions] == ["Retry", "SkipSample", "Abort"]
    assert e.DefaultOption.value == "Abort"
    assert first_state(lab) == "Recovering"
    with pytest.raises(Failure) as err:
        lab.client.call(ERR, "ExecuteContinuationOption", CommandExecutionUUID=S(uuid), ContinuationOption=S("Later"),
                        InputData=S(""))
    assert err.value.identifier == "UnknownContinuationOption"
    reads = lab.sim.log().count("TYPEI SIG(4)")
    lab.set_input(4, True)  # the vial is put on its sensor; then the client says: again
    lab.client.call(ERR, "ExecuteContinuationOption", CommandExecutionUUID=S(uuid), ContinuationOption=S("Retry"),
                    InputData=S(""))
    result, _, _ = follow(lab, uuid)
    collector.join(30)
    assert not isinstance(result, Failure) and result.Outcome.value == "completed", result
    assert events(inter)[-3:] == [("WaitingForRecovery", "Take", 1), ("Recovered", "Take", 1), ("StepEnded", "Take", 1)]
    assert lab.sim.log().count("TYPEI SIG(4)") > reads  # the step ran again and read the sensor again
    with pytest.raises(Failure) as err:  # nothing waits any more
        lab.client.call(ERR, "ExecuteContinuationOption", CommandExecutionUUID=S(uuid), ContinuationOption=S("Retry"),
                        InputData=S(""))
    assert err.value.identifier == "InvalidCommandExecutionUUID"


def first_state(lab):
    stream = lab.client.subscribe(ARM, "ArmState")
    for m in stream:
        stream.cancel()
        return m.ArmState.value


def test_skip_abort_and_unhandled_errors(lab):
    lab.set_input(4, False)
    uuid = start(lab, "VIAL-CHECK", *params(N_VIALS=2))
    recoverable(lab)
    lab.client.call(ERR, "ExecuteContinuationOption", CommandExecutionUUID=S(uuid), ContinuationOption=S("SkipSample"),
                    InputData=S(""))
    wait_for(lambda: any("sample 2" in e.ErrorMessage.value for e in recoverable(lab)),
             what="the second vial's question")
    lab.client.call(ERR, "AbortErrorHandling", CommandExecutionUUID=S(uuid))
    result, _, _ = follow(lab, uuid)
    assert isinstance(result, Failure) and result.identifier == "StepFailed", result
    assert "not handled" in result.message and "1 skipped" in result.message

    uuid = start(lab, "VIAL-CHECK", *params(N_VIALS=1))
    recoverable(lab)
    with pytest.raises(Failure) as err:
        lab.client.call(ERR, "ExecuteContinuationOption", CommandExecutionUUID=S(uuid), ContinuationOption=S("Abort"),
                        InputData=S("x"))
    assert err.value.kind == "validationError"
    lab.client.call(ERR, "ExecuteContinuationOption", CommandExecutionUUID=S(uuid), ContinuationOption=S("Abort"),
                    InputData=S(""))
    assert follow(lab, uuid)[0].identifier == "MethodCancelled"

    lab.client.call(ERR, "SetErrorHandlingTimeout", ErrorHandlingTimeout=I(1))
    try:
        uuid = start(lab, "VIAL-CHECK", *params(N_VIALS=1))
        t0 = time.monotonic()
        result, _, _ = follow(lab, uuid)
        assert isinstance(result, Failure) and result.identifier == "StepFailed" and "timeout" in result.message
        assert time.monotonic() - t0 < 10
    finally:
        lab.client.call(ERR, "SetErrorHandlingTimeout", ErrorHandlingTimeout=I(0))


# ------------------------------------------------------------------ the docs' scheduler
def test_the_scheduler_example_of_the_docs(lab):
    """examples/station/scheduler.py, a plain gRPC client with only the generated modules."""
    import subprocess
    env = dict(os.environ, PYTHONPATH=os.environ["FBRL_STATION_GEN"])
    p = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "examples", "station", "scheduler.py"),
                        "127.0.0.1:%d" % lab.station.port, lab.station.cert, "QUICK", "#ITEMS=2", "HOLD-DS=1"],
                       env=env, capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "QUICK: completed" in p.stdout and "sample 2: succeeded" in p.stdout
    assert "ArmController, RobotController, MethodLibrary" in p.stdout
    assert not lab.client.get("LockController", "IsLocked").value  # it unlocked


def test_sigterm_during_a_run_stops_it_safely(tmp_path):
    """A service manager stops the station while a method runs: the run is cancelled as the
    console's abort (halt, outputs off, ON-ABORT), then the station exits 0."""
    lab = Lab(str(tmp_path))
    try:
        before = len(lab.sim.log())
        uuid = start(lab, "QUICK", *params(N_ITEMS=3, HOLD_DS=50))
        wait_for(lambda: "OUTPUT 1" in lab.sim.log()[before:], what="the pump to run")
        t0 = time.monotonic()
        assert lab.station.stop() == 0
        assert time.monotonic() - t0 < 20
        log = lab.sim.log()[before:]
        on = log.index("OUTPUT 1")
        assert "HALT" in log[on:] and "OUTPUT -1" in log[on:] and "READY" in log[on:], log[on:]
        assert uuid and log.count("OUTPUT 1") == 1
    finally:
        lab.stop()
