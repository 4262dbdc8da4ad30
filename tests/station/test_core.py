# SPDX-License-Identifier: MIT
"""The standard core features, the framework's errors and TLS, against a station on fbrlsim."""
import os
import re
import subprocess
import time

import grpc
import pytest
from lxml import etree

from client import Client, Failure
from conftest import ROOT, Sim, launcher, start_station, wait_for
from fbrl_station import pb, tls
from fbrl_station.sila import I, S, metadata_key

SCHEMA = os.path.join(ROOT, "tests", "station", "reference", "schema", "FeatureDefinition.xsd")
SVC, LOCK, SIM, ARM = "SiLAService", "LockController", "SimulationController", "ArmController"
am = pb.messages(ARM)
LOCK_FQI = "org.silastandard/core/LockController/v1/Metadata/LockIdentifier"


def home_uuid(client):
    return client.start(ARM, "Home")


# ------------------------------------------------------------------ SiLAService
def test_identity(arm):
    c = arm.client
    uuid = c.get(SVC, "ServerUUID").value
    assert re.fullmatch(r"[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}", uuid)
    with open(arm.station.cert, "rb") as f:
        assert tls.uuid_of(f.read()) == uuid  # the certificate carries it (SiLA's OID)
    assert c.get(SVC, "ServerType").value == "FbrlStation"
    assert re.fullmatch(r"\d+\.\d+\.\d+", c.get(SVC, "ServerVersion").value)
    assert c.get(SVC, "ServerVendorURL").value.startswith("https://")
    assert "robot arm" in c.get(SVC, "ServerDescription").value
    assert [f.value for f in c.get(SVC, "ImplementedFeatures")][0] == "org.silastandard/core/SiLAService/v1"


def test_every_feature_definition_served_validates_against_the_schema(arm):
    schema = etree.XMLSchema(etree.parse(SCHEMA))
    for fqi in arm.client.get(SVC, "ImplementedFeatures"):
        text = arm.client.call(SVC, "GetFeatureDefinition", FeatureIdentifier=fqi).FeatureDefinition.value
        doc = etree.fromstring(text.encode("utf-8"))
        assert schema.validate(doc), (fqi.value, schema.error_log)
        originator, category, ident, version = fqi.value.split("/")
        assert doc.get("Originator") == originator and doc.get("Category") == category
        assert doc.findtext("{http://www.sila-standard.org}Identifier") == ident and version == "v1"


def test_an_unknown_feature_is_the_standard_s_error(arm):
    with pytest.raises(Failure) as e:
        arm.client.call(SVC, "GetFeatureDefinition", FeatureIdentifier=S("org.example/none/Nothing/v1"))
    assert e.value.kind == "definedExecutionError"
    assert e.value.pb.definedExecutionError.errorIdentifier == \
        "org.silastandard/core/SiLAService/v1/DefinedExecutionError/UnimplementedFeature"


def test_silaservice_takes_no_metadata(arm):
    m = pb.messages(LOCK).Metadata_LockIdentifier(LockIdentifier=S("x"))
    with pytest.raises(Failure) as e:
        arm.client.call(SVC, "Get_ServerName", metadata=[(metadata_key(LOCK_FQI), m.SerializeToString())])
    assert e.value.identifier == "NO_METADATA_ALLOWED"


def test_server_name_is_set_and_kept(own):
    c = own.client
    c.call(SVC, "SetServerName", ServerName=S("Arm 2, room 114"))
    assert c.get(SVC, "ServerName").value == "Arm 2, room 114"
    with pytest.raises(Failure) as e:
        c.call(SVC, "SetServerName", ServerName=S("x" * 256))
    assert e.value.kind == "validationError"
    uuid = c.get(SVC, "ServerUUID").value
    own.station.stop()
    st = start_station(own.station.data, own.sim)
    try:
        c2 = st.client()
        assert c2.get(SVC, "ServerName").value == "Arm 2, room 114" and c2.get(SVC, "ServerUUID").value == uuid
    finally:
        st.stop()


# ------------------------------------------------------------------ LockController
def test_a_second_client_is_refused_while_locked(arm):
    owner, other = arm.client, arm.station.client()
    sim = arm.sim
    assert not owner.get(LOCK, "IsLocked").value
    owner.call(LOCK, "LockServer", LockIdentifier=S("scheduler-1"), Timeout=I(0))
    try:
        assert other.get(LOCK, "IsLocked").value  # reading needs no identifier
        before = len(sim.log())
        with pytest.raises(Failure) as e:  # no identifier: the framework's invalid metadata
            other.start(ARM, "Home")
        assert e.value.identifier == "INVALID_METADATA"
        other.lock_id = "guess"
        with pytest.raises(Failure) as e:
            other.start(ARM, "Home")
        assert e.value.identifier == "InvalidLockIdentifier"
        with pytest.raises(Failure) as e:
            other.call(LOCK, "LockServer", LockIdentifier=S("mine"), Timeout=I(0))
        assert e.value.identifier == "ServerAlreadyLocked"
        with pytest.raises(Failure) as e:
            other.call(LOCK, "UnlockServer", LockIdentifier=S("guess"))
        assert e.value.identifier == "InvalidLockIdentifier"
        assert "HOME" not in sim.log()[before:]
        owner.lock_id = "scheduler-1"
        result, _ = owner.run(ARM, "Home")
        assert not isinstance(result, Failure) and "HOME" in sim.log()[before:]
    finally:
        owner.lock_id = None
        owner.call(LOCK, "UnlockServer", LockIdentifier=S("scheduler-1"))
    with pytest.raises(Failure) as e:
        owner.call(LOCK, "UnlockServer", LockIdentifier=S("scheduler-1"))
    assert e.value.identifier == "ServerNotLocked"
    other.lock_id = None
    assert not isinstance(other.run(ARM, "Home")[0], Failure)
    other.close()


def test_a_lock_ends_after_its_timeout(arm):
    c = arm.client
    c.call(LOCK, "LockServer", LockIdentifier=S("brief"), Timeout=I(1))
    assert c.get(LOCK, "IsLocked").value
    time.sleep(1.3)
    assert not c.get(LOCK, "IsLocked").value


def test_the_lock_names_the_calls_it_protects(arm):
    calls = [x.value for x in arm.client.call(LOCK, "Get_FCPAffectedByMetadata_LockIdentifier").AffectedCalls]
    for cmd in ("ArmController/v1/Command/Home", "ArmController/v1/Command/MoveToPlace",
                "ArmController/v1/Command/TeachPlace", "RobotController/v1/Command/MovePlate",
                "SimulationController/v1/Command/StartRealMode"):
        assert any(x.endswith(cmd) for x in calls), cmd
    assert not any("SiLAService" in x or "LockController" in x for x in calls)


# ------------------------------------------------------------------ SimulationController
def test_switching_to_the_emulator_and_back(own, tmp_path):
    c, sim = own.client, own.sim
    assert not c.get(SIM, "SimulationMode").value
    c.call(SIM, "StartRealMode")  # already: nothing changes
    own.station.stop()
    emu_log = str(tmp_path / "emulator.log")
    st = start_station(own.station.data, sim, "--sim-log", emu_log)
    try:
        c2 = st.client()
        c2.call(SIM, "StartSimulationMode")
        assert c2.get(SIM, "SimulationMode").value
        before = len(sim.log())
        assert not isinstance(c2.run(ARM, "Home")[0], Failure)
        assert "HOME" in open(emu_log).read().split() and "HOME" not in sim.log()[before:]
        c2.call(SIM, "StartRealMode")
        assert not c2.get(SIM, "SimulationMode").value
        assert not isinstance(c2.run(ARM, "Home")[0], Failure) and "HOME" in sim.log()[before:]
    finally:
        st.stop()


def test_a_switch_that_cannot_be_made_changes_nothing(tmp_path):
    sim = Sim(str(tmp_path / "sim"))
    env = dict(os.environ, FBRL_SIM=str(tmp_path / "no-fbrlsim"))
    st = None
    try:
        from client import Station
        from conftest import SITES
        st = Station(launcher(), tmp_path / "d", "--port", sim.port, "--no-discovery", SITES, env=env)
        c = st.client()
        with pytest.raises(Failure) as e:
            c.call(SIM, "StartSimulationMode")
        assert e.value.identifier == "StartSimulationModeFailed" and "fbrlsim" in e.value.message
        assert not c.get(SIM, "SimulationMode").value
        assert not isinstance(c.run(ARM, "Home")[0], Failure) and "HOME" in sim.log()
    finally:
        if st:
            st.stop()
        sim.stop()


def test_real_mode_without_a_port_fails(tmp_path):
    from client import Station
    st = Station(launcher(), tmp_path / "d", "--sim", "--no-discovery", "--sim-time-scale", "20")
    try:
        c = st.client()
        assert c.get(SIM, "SimulationMode").value
        with pytest.raises(Failure) as e:
            c.call(SIM, "StartRealMode")
        assert e.value.identifier == "StartRealModeFailed" and "--port" in e.value.message
        assert c.get(SIM, "SimulationMode").value and not isinstance(c.run(ARM, "Home")[0], Failure)
    finally:
        st.stop()


# ------------------------------------------------------------------ observable commands
def test_unknown_and_unfinished_executions(own):
    c = own.client
    own.sim.pause()  # the command cannot end while the controller stands still
    try:
        uuid = home_uuid(c)
        with pytest.raises(Failure) as e:
            c.result(ARM, "Home", uuid)
        assert e.value.identifier == "COMMAND_EXECUTION_NOT_FINISHED"
    finally:
        own.sim.resume()
    with pytest.raises(Failure) as e:
        c.result(ARM, "MoveToPlace", uuid)  # another command's execution
    assert e.value.identifier == "INVALID_COMMAND_EXECUTION_UUID"
    with pytest.raises(Failure) as e:
        list(c.info(ARM, "Home", "00000000-0000-0000-0000-000000000000"))
    assert e.value.identifier == "INVALID_COMMAND_EXECUTION_UUID"


# ------------------------------------------------------------------ TLS and the command line
def test_tls_is_pinned_to_the_station_s_certificate(arm):
    channel = grpc.secure_channel("127.0.0.1:%d" % arm.station.port, grpc.ssl_channel_credentials())
    stub = pb.grpc_module(SVC).SiLAServiceStub(channel)
    with pytest.raises(grpc.RpcError) as e:  # the system's roots do not know the self-signed station
        stub.Get_ServerName(pb.messages(SVC).Get_ServerName_Parameters(), timeout=10)
    assert e.value.code() == grpc.StatusCode.UNAVAILABLE
    channel.close()
    plain = grpc.insecure_channel("127.0.0.1:%d" % arm.station.port)
    with pytest.raises(grpc.RpcError):
        pb.grpc_module(SVC).SiLAServiceStub(plain).Get_ServerName(
            pb.messages(SVC).Get_ServerName_Parameters(), timeout=10)
    plain.close()


def test_insecure_warns_on_every_start(tmp_path):
    sim = Sim(str(tmp_path / "sim"))
    st = start_station(tmp_path / "d", sim, insecure=True)
    try:
        assert any("warning: --insecure" in l for l in st.lines)
        c = Client(st.port)
        assert c.get(SVC, "ServerType").value == "FbrlStation"
    finally:
        st.stop()
        sim.stop()


def test_command_line_errors(tmp_path):
    def run(*args):
        p = subprocess.run([launcher()] + list(args), capture_output=True, text=True, timeout=60)
        return p.returncode, p.stdout + p.stderr

    code, out = run("--help")
    assert code == 0 and "--sila HOST:PORT|off" in out and "--http" in out
    code, out = run("--version")
    assert code == 0 and re.fullmatch(r"fbrl-station \(libfbrl\) \d+\.\d+\.\d+\n", out)
    code, out = run("--http", "0.0.0.0:8080")  # beyond loopback the page needs TLS and a login
    assert code == 2 and "loopback" in out
    assert run("--sila", "off", "--http", "off")[0] == 2  # nothing to serve
    assert run("--bogus")[0] == 2
    assert run("--sila", "nowhere")[0] == 2
    code, out = run("--port", str(tmp_path / "no-tty"), "--data", str(tmp_path / "d"), "--no-discovery")
    assert code == 3 and "no-tty" in out
    bad = tmp_path / "bad.fbrl"
    bad.write_text("1 2 +\nNO-SUCH-WORD\n")
    code, out = run("--sim", "--data", str(tmp_path / "d"), "--no-discovery", "--sila", "127.0.0.1:0", str(bad))
    assert code == 1 and "bad.fbrl:2: error: undefined word NO-SUCH-WORD" in out
