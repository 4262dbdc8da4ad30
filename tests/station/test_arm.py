# SPDX-License-Identifier: MIT
"""ArmController and RobotController against fbrlsim: every command, property and defined
error, judged by the emulator's command log and the positions it reports."""
import threading
import time

import pytest

from client import Failure
from conftest import Sim, start_station, wait_for
from fbrl_station import pb
from fbrl_station.sila import I, R, S

ARM, ROBOT = "ArmController", "RobotController"
am, rm = pb.messages(ARM), pb.messages(ROBOT)
DONE = pb.fw.ExecutionInfo.CommandStatus.Value("finishedSuccessfully")
FAILED = pb.fw.ExecutionInfo.CommandStatus.Value("finishedWithError")


def place(name, index=0):
    return {"Place": am.DataType_PlaceName(PlaceName=S(name)), "Index": I(index)}


def site(device, index):
    return rm.DataType_Site(Site=rm.DataType_Site.Site_Struct(Device=S(device), SiteIndex=I(index)))


def location(loc):
    s = loc.Location
    return [s.X.Inches.value, s.Y.Inches.value, s.Z.Inches.value, s.Yaw.Degrees.value, s.Pitch.Degrees.value,
            s.Roll.Degrees.value]


def first(stream, predicate=lambda m: True, seconds=20):
    """The first message of a stream that satisfies predicate (the stream is cancelled)."""
    box = []

    def read():
        for m in stream:
            if predicate(m):
                box.append(m)
                break

    t = threading.Thread(target=read, daemon=True)
    t.start()
    t.join(seconds)
    stream.cancel()
    assert box, "no such message in %s s" % seconds
    return box[0]


def home(client):
    result, infos = client.run(ARM, "Home")
    assert not isinstance(result, Failure), result
    return infos


def position(client):
    return first(client.subscribe(ARM, "Position")).Position


def new_lines(sim, before):
    return sim.log()[before:]


def points(lines):
    """The coordinates of the POINT lines (the robot words' scratch names vary)."""
    return [l.split(",", 1)[1] for l in lines if l.startswith("POINT ")]


# ------------------------------------------------------------------ Home, MoveToPlace
def test_home_runs_home_on_the_controller_and_reports_progress(arm):
    sim, client = arm.sim, arm.client
    infos = home(client)
    assert "HOME" in sim.log()
    assert infos[-1].commandStatus == DONE and infos[-1].progressInfo.value == 1.0
    assert first(client.subscribe(ARM, "ControllerStatus")).ControllerStatus.Homed.value


def test_move_to_place_ends_at_the_place(arm):
    sim, client = arm.sim, arm.client
    home(client)
    before = len(sim.log())
    result, infos = client.run(ARM, "MoveToPlace", **place("SEPARATOR"))
    assert not isinstance(result, Failure), result
    assert points(new_lines(sim, before)) == ["15,5,4,0,-90,0"]
    assert [l for l in new_lines(sim, before) if l.startswith("MOVE")] == ["MOVE " + l.split()[1].split(",")[0]
                                                                           for l in new_lines(sim, before)
                                                                           if l.startswith("POINT")]
    world = location(position(client).Location)
    assert [round(v, 3) for v in world[:3]] == [15.0, 5.0, 4.0] and round(world[4]) == -90


def test_move_to_a_site_of_a_device_by_index(arm):
    sim, client = arm.sim, arm.client
    home(client)
    before = len(sim.log())
    result, _ = client.run(ARM, "MoveToPlace", **place("heating-block", 3))  # names without regard to case
    assert not isinstance(result, Failure), result
    assert points(new_lines(sim, before)) == ["10,0.25,3,0,-90,0"]  # tube A4: A1 + 3 columns of 0.75 in


def test_unknown_place_and_index_are_refused_before_anything_is_sent(arm):
    sim, client = arm.sim, arm.client
    home(client)
    before = len(sim.log())
    for params, says in ((place("NOWHERE"), "no site 'NOWHERE'"), (place("SEPARATOR", 1), "SEPARATOR has 1 site"),
                         (place("HEATING-BLOCK", 24), "not 24")):
        result, infos = client.run(ARM, "MoveToPlace", **params)
        assert isinstance(result, Failure) and result.identifier == "UnknownPlace", result
        assert says in result.message and infos[-1].commandStatus == FAILED
    assert [l for l in new_lines(sim, before) if not l.startswith(("W2", "W5", "STATUS"))] == []


def test_parameters_outside_their_constraints_are_validation_errors(arm):
    sim, client = arm.sim, arm.client
    before = len(sim.log())
    for params, parameter in ((place("A B"), "Place"), (place("1ST"), "Place"), (place("X\\"), "Place"),
                              (place("SEPARATOR", -1), "Index")):
        with pytest.raises(Failure) as e:
            client.start(ARM, "MoveToPlace", **params)
        assert e.value.kind == "validationError"
        assert e.value.identifier == "org.libfbrl/robot/ArmController/v1/Command/MoveToPlace/Parameter/" + parameter
    with pytest.raises(Failure) as e:
        client.start(ARM, "MoveToPlace", Place=am.DataType_PlaceName(PlaceName=S("SEPARATOR")))
    assert e.value.kind == "validationError" and "missing" in e.value.message
    assert new_lines(sim, before) == []


def test_a_motion_into_the_cell_is_refused_by_the_guard(arm):
    sim, client = arm.sim, arm.client
    home(client)
    before = len(sim.log())
    result, _ = client.run(ARM, "MoveToPlace", **place("IN-BLOCK"))
    assert isinstance(result, Failure) and result.identifier == "CollisionRefused", result
    assert "HEATING-BLOCK" in result.message and "nothing was sent" in result.message
    assert [l for l in new_lines(sim, before) if l.startswith(("POINT", "MOVE"))] == []


def test_a_place_beyond_reach_is_refused_before_a_byte_is_sent(arm):
    sim, client = arm.sim, arm.client
    home(client)
    before = len(sim.log())
    result, _ = client.run(ARM, "MoveToPlace", **place("FAR"))
    assert isinstance(result, Failure) and result.identifier == "CollisionRefused", result
    assert "beyond the arm's reach" in result.message and "nothing was sent" in result.message
    assert [l for l in new_lines(sim, before) if l.startswith(("POINT", "MOVE"))] == []


def test_the_controller_s_refusal_carries_its_code(own):
    sim, client = own.sim, own.client
    home(client)
    sim.control("POWER 0")  # the arm's power switched off at the panel: the controller refuses (040)
    result, _ = client.run(ARM, "MoveToPlace", **place("SEPARATOR"))
    assert isinstance(result, Failure) and result.identifier == "ControllerRefused", result
    assert result.message.startswith("040 ARM POWER HAS BEEN SWITCHED OFF"), result.message
    assert first(client.subscribe(ARM, "ControllerStatus")).ControllerStatus.LastError.value == 40


def test_a_motion_before_home_is_not_homed(fresh):
    sim, client = fresh.sim, fresh.client
    result, _ = client.run(ARM, "MoveToPlace", **place("SEPARATOR"))
    assert isinstance(result, Failure) and result.identifier == "NotHomed", result
    assert "041" in result.message
    result, _ = client.run(ROBOT, "MovePlate", OriginSite=site("SEPARATOR", 0), DestinationSite=site("RINSE-REST", 0),
                           PlateType=S("TUBE"))
    assert isinstance(result, Failure) and result.identifier == "NotHomed", result


def test_a_controller_in_millimetres_is_a_units_mismatch(tmp_path):
    sim = Sim(str(tmp_path / "sim"))
    st = start_station(tmp_path / "mm", sim, "-e", "RAPL METRIC")  # the station reads STATUS at start
    try:
        c = st.client()
        before = len(sim.log())
        result, _ = c.run(ARM, "MoveToPlace", **place("SEPARATOR"))
        assert isinstance(result, Failure) and result.identifier == "UnitsMismatch", result
        assert [l for l in new_lines(sim, before) if l.startswith(("POINT", "MOVE"))] == []
    finally:
        st.stop()
        sim.stop()


def test_a_reply_lost_after_the_command_started_is_may_have_run(tmp_path):
    sim = Sim(str(tmp_path / "slow"), "--cmd-time", "10000")  # 0.5 s real before it acts
    st = start_station(tmp_path / "d", sim)
    try:
        c = st.client()
        uuid = c.start(ARM, "Home")
        wait_for(lambda: sim.log()[-1:] == ["W5"], what="the station's HOME to start")  # the robot word's check
        time.sleep(0.25)  # HOME typed, echoed, its line ended: the controller has it
        sim.pause()
        try:
            with pytest.raises(Failure) as e:
                for _ in c.info(ARM, "Home", uuid):
                    pass
                c.result(ARM, "Home", uuid)
            assert e.value.identifier == "MayHaveRun" and "may have run" in e.value.message
        finally:
            sim.resume()
    finally:
        st.stop()
        sim.stop()


def test_a_controller_that_is_gone_is_controller_lost(own):
    sim, client = own.sim, own.client
    home(client)
    sim.stop()
    result, _ = client.run(ARM, "Home")
    assert isinstance(result, Failure) and result.identifier == "ControllerLost", result
    state = first(client.subscribe(ARM, "ArmState")).ArmState.value
    assert state == "Disconnected"


# ------------------------------------------------------------------ Grip, Release, TeachPlace
def test_grip_and_release_send_the_grip_commands(arm):
    sim, client = arm.sim, arm.client
    before = len(sim.log())
    client.call(ARM, "Grip", Width=am.DataType_Opening(Opening=R(0.5)), Force=I(40))
    client.call(ARM, "Release", Width=am.DataType_Opening(Opening=R(1.5)))
    assert [l for l in new_lines(sim, before) if l.startswith("GRIP")] == ["GRIP 0.5,40", "GRIP 1.5,30"]


def test_grip_outside_its_ranges(arm):
    sim, client = arm.sim, arm.client
    for width, force, parameter in ((0.5, 0, "Force"), (0.5, 101, "Force"), (-0.1, 40, "Width")):
        with pytest.raises(Failure) as e:
            client.call(ARM, "Grip", Width=am.DataType_Opening(Opening=R(width)), Force=I(force))
        assert e.value.kind == "validationError" and e.value.identifier.endswith("/" + parameter)
    with pytest.raises(Failure) as e:  # wider than the gripper opens: the controller says no
        client.call(ARM, "Release", Width=am.DataType_Opening(Opening=R(3.0)))
    assert e.value.identifier == "ControllerRefused"
    assert not [l for l in sim.log() if l.startswith("GRIP 3")] or e.value.message[:3].isdigit()


def test_teach_place_stores_where_the_arm_is_and_keeps_it(own):
    sim, station, client = own.sim, own.station, own.client
    home(client)
    client.run(ARM, "MoveToPlace", **place("RINSE-REST"))
    loc = location(client.call(ARM, "TeachPlace", Place=am.DataType_PlaceName(PlaceName=S("SPARE-1"))).Location)
    assert [round(v, 3) for v in loc[:3]] == [14.0, -6.0, 5.0]
    places = {p.Name.value: (p.Positions.value, p.Taught.value) for p in client.get(ARM, "Places")}
    assert places["SPARE-1"] == (1, True) and places["HEATING-BLOCK"] == (24, False)
    station.stop()  # a new station on the same data folder knows the place
    st2 = start_station(station.data, sim)
    try:
        c2 = st2.client()
        assert "SPARE-1" in [p.Name.value for p in c2.get(ARM, "Places")]
        client_home = c2.run(ARM, "MoveToPlace", **place("SEPARATOR"))[0]
        assert not isinstance(client_home, Failure)
        assert not isinstance(c2.run(ARM, "MoveToPlace", **place("SPARE-1"))[0], Failure)
        world = location(position(c2).Location)
        assert [round(v, 3) for v in world[:3]] == [14.0, -6.0, 5.0]
    finally:
        st2.stop()


def test_teach_place_refuses_names_that_are_not_places(arm):
    sim, client = arm.sim, arm.client
    before = len(sim.log())
    for name in ("HOME", "HEATING-BLOCK"):
        with pytest.raises(Failure) as e:
            client.call(ARM, "TeachPlace", Place=am.DataType_PlaceName(PlaceName=S(name)))
        assert e.value.kind == "validationError"
    assert new_lines(sim, before) == []


# ------------------------------------------------------------------ properties
def test_arm_state_goes_busy_while_a_command_runs(arm):
    sim, client = arm.sim, arm.client
    seen = []
    stream = client.subscribe(ARM, "ArmState")
    t = threading.Thread(target=lambda: [seen.append(m.ArmState.value) for m in stream], daemon=True)
    t.start()
    wait_for(lambda: seen == ["Idle"], what="the first state")
    home(client)
    wait_for(lambda: seen[-1:] == ["Idle"] and "Busy" in seen, what="Busy, then Idle")
    stream.cancel()
    assert seen[:3] == ["Idle", "Busy", "Idle"]


def test_position_is_the_controller_s(fresh):
    sim, client = fresh.sim, fresh.client
    p = position(client)
    assert [round(v, 3) for v in location(p.Location)[:3]] == [12.0, 0.0, 20.0]  # READY: fbrlsim's start
    assert [round(j.Degrees.value) for j in p.Joints] == [0, 90, -90, 0, 0]
    assert "W2" in sim.log()


def test_controller_status_reports_connection_and_io(fresh):
    sim, client = fresh.sim, fresh.client
    st = first(client.subscribe(ARM, "ControllerStatus")).ControllerStatus
    assert st.Connected.value and sim.port in st.Connection.value and not st.Homed.value
    assert st.Speed.value > 0 and st.Outputs.value == 0


# ------------------------------------------------------------------ RobotController
def test_move_plate_picks_at_the_origin_and_places_at_the_destination(arm):
    sim, client = arm.sim, arm.client
    home(client)
    before = len(sim.log())
    result, infos = client.run(ROBOT, "MovePlate", OriginSite=site("HEATING-BLOCK", 3),
                               DestinationSite=site("SEPARATOR", 0), PlateType=S("TUBE"))
    assert not isinstance(result, Failure), result
    pts = points(new_lines(sim, before))
    assert pts[0] == "10,0.25,3,0,-90,0" and pts[-1] == "15,5,4,0,-90,0"
    grips = [l for l in new_lines(sim, before) if l.startswith("GRIP")]
    assert grips == ["GRIP 1.5,30", "GRIP 0.5,40", "GRIP 1.5,30"]  # open, close on the tube, open


def test_move_plate_errors(arm):
    sim, client = arm.sim, arm.client
    home(client)
    with pytest.raises(Failure) as e:
        client.start(ROBOT, "MovePlate", OriginSite=site("SEPARATOR", 0), DestinationSite=site("RINSE-REST", 0),
                     PlateType=S("PLATE96"))
    assert e.value.kind == "validationError" and e.value.identifier.endswith("/PlateType")
    for origin, target, kind in ((site("NOWHERE", 0), site("SEPARATOR", 0), "SiteNotFound"),
                                 (site("SYRINGE-REST", 4), site("SEPARATOR", 0), "SiteNotFound"),
                                 (site("SEPARATOR", 0), site("IN-BLOCK", 0), "CollisionRefused")):
        result, _ = client.run(ROBOT, "MovePlate", OriginSite=origin, DestinationSite=target, PlateType=S("TUBE"))
        assert isinstance(result, Failure) and result.identifier == kind, result


def test_sites_and_plate_types(arm):
    client = arm.client
    sites = {s.Device.value: s.SiteCount.value for s in client.get(ROBOT, "Sites")}
    assert sites["HEATING-BLOCK"] == 24 and sites["SEPARATOR"] == 1 and sites["DISPENSER-REST"] == 7
    plates = {p.Name.value: p.Width.value for p in client.get(ROBOT, "PlateTypes")}
    assert plates == {"TUBE": 0.5, "RINSE-NOZZLE": 0.75}
