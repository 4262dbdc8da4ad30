# SPDX-License-Identifier: MIT
"""The arm's features: ArmController (state, position, status, home, move to a place, grip,
release, teach) and RobotController (MovePlate between sites). Every motion is FBRL text of
robot words run by the owner thread, so the collision guard checks it."""
import logging

import fbrl

from . import sila
from .cell import KIND_LOC, forth_float
from .controller import RobotFailure
from .core import Feature
from .sila import B, I, R, S, rpc, stream_rpc, who

RELEASE_FORCE = 30  # percent: the gripper opens with a light force (the ASPS cell's OPEN-HAND)
WATCH_TICK_S = 1.0  # how often a subscription looks whether its client is still there
FIRST_READING_S = 2.0  # a new subscriber waits this long at most for a fresh reading
log = logging.getLogger("fbrl-station")


def location(m, loc):
    """ArmController's DataType_Location message of 6 values."""
    inches = [m.DataType_Inches(Inches=R(v)) for v in loc[:3]]
    degrees = [m.DataType_Degrees(Degrees=R(v)) for v in loc[3:6]]
    s = m.DataType_Location.Location_Struct(X=inches[0], Y=inches[1], Z=inches[2], Yaw=degrees[0],
                                              Pitch=degrees[1], Roll=degrees[2])
    return m.DataType_Location(Location=s)


def watch_stream(context, watched, message):
    """Yield message(value) for the value now and for every change, while the client listens
    (a value not read yet, None, is not sent)."""
    version = None
    while context.is_active():
        with watched.cond:
            value, v = watched.value, watched.version
        if v != version:
            version = v
            if value is not None:
                yield message(value)
        watched.wait(version, WATCH_TICK_S)


class Observable:
    """Running an observable command: an execution whose job the owner runs, its Info,
    Intermediate and Result calls."""

    def audit(self, context, command, text):
        """With --lab: the FBRL text a client's command runs, in the lab's audit trail before it
        runs; a command that cannot be recorded does not run."""
        trail = self.st.trail
        if trail is not None:
            try:
                trail.sila(text, "%s.%s" % (self.FEATURE, command), who(context))
            except fbrl.Error as e:
                raise sila.undefined("%s not run: the lab's audit trail cannot record it: %s"
                                     % (command, e.detail or e))

    def eval(self, c, context, command, text):
        """On the owner thread: run a client's FBRL text, recorded first (audit)."""
        self.audit(context, command, text)
        return c.eval(text)

    def launch(self, context, command, work):
        """work(controller) runs on the owner thread as a motion; returns the confirmation."""
        self.protected(context)
        st = self.st
        self.not_running()
        e = st.executions.new(self.f.command_fqi(command))

        def job(c):
            e.start()
            return work(c)

        fut = st.owner.motion(job)

        def done(f):
            try:
                e.finish(f.result())
            except RobotFailure as failure:
                e.fail(self.error(failure))
            except sila.SilaError as err:
                e.fail(err)
            except Exception as ex:  # the client must learn the command failed, and how
                e.fail(sila.undefined("%s: %s" % (type(ex).__name__, ex)))

        fut.add_done_callback(done)
        return st.executions.confirmation(e)

    def info(self, command, request, context):
        e = self.st.executions.get(request.value, self.f.command_fqi(command))
        yield from self.st.executions.info_stream(e, context)

    def result(self, command, request):
        return self.st.executions.result(self.st.executions.get(request.value, self.f.command_fqi(command)))


class ArmController(Observable, Feature):
    FEATURE = "ArmController"

    # ---------------------------------------------------------------- commands
    @rpc
    def Home(self, request, context):
        self.check("Home", request)

        def work(c):
            self.eval(c, context, "Home", "HOME FINISH")
            return self.m.Home_Responses()

        return self.launch(context, "Home", work)

    @stream_rpc
    def Home_Info(self, request, context):
        yield from self.info("Home", request, context)

    @rpc
    def Home_Result(self, request, context):
        return self.result("Home", request)

    @rpc
    def MoveToPlace(self, request, context):
        self.check("MoveToPlace", request)
        place, index = request.Place.PlaceName.value, request.Index.value

        def work(c):
            self.eval(c, context, "MoveToPlace", self.st.cell.site_loc(place, index) + " MOV FINISH")
            return self.m.MoveToPlace_Responses()

        return self.launch(context, "MoveToPlace", work)

    @stream_rpc
    def MoveToPlace_Info(self, request, context):
        yield from self.info("MoveToPlace", request, context)

    @rpc
    def MoveToPlace_Result(self, request, context):
        return self.result("MoveToPlace", request)

    def _now(self, context, command, text):
        """An unobservable command: run it and wait."""
        self.protected(context)
        self.not_running()
        try:
            self.st.owner.motion(lambda c: self.eval(c, context, command, text)).result()
        except RobotFailure as failure:
            raise self.error(failure)

    @rpc
    def Grip(self, request, context):
        self.check("Grip", request)
        self._now(context, "Grip",
                  "%d %s GRIP" % (request.Force.value, forth_float(request.Width.Opening.value)))
        return self.m.Grip_Responses()

    @rpc
    def Release(self, request, context):
        self.check("Release", request)
        self._now(context, "Release",
                  "%d %s GRIP" % (RELEASE_FORCE, forth_float(request.Width.Opening.value)))
        return self.m.Release_Responses()

    @rpc
    def TeachPlace(self, request, context):
        self.check("TeachPlace", request)
        self.protected(context)
        self.not_running()
        name = request.Place.PlaceName.value
        owner, cell = self.st.owner, self.st.cell

        def job(c):
            if owner.run is not None:
                raise RobotFailure("StationBusy", "a method run owns the arm (%s)" % owner.run.describe())
            if not c.connected:
                owner.reconnect(c)
            self.audit(context, "TeachPlace", "%s ARM-HERE" % name)
            return cell.teach(c, name)

        try:
            loc = owner.call(job)
        except RobotFailure as failure:
            raise self.error(failure)
        except ValueError as e:
            raise sila.validation(self.f.parameter_fqi("TeachPlace", "Place"), str(e))
        return self.m.TeachPlace_Responses(Location=location(self.m, loc))

    # ---------------------------------------------------------------- properties
    @stream_rpc
    def Subscribe_ArmState(self, request, context):
        yield from watch_stream(context, self.st.owner.arm_state,
                                lambda v: self.m.Subscribe_ArmState_Responses(ArmState=S(v)))

    def _subscribe(self, context, what, watched, message):
        owner = self.st.owner
        owner.watch(what, +1)

        def first_reading(c):  # a fresh value for the new subscriber, when the arm is free to be read
            if c.connected and owner.run is None:
                owner.refresh(position=what == "position", status=what == "status")

        try:
            if watched.value is None or (what == "status" and not owner.status_fresh):
                try:  # a fresh first value when the arm is free; the one there otherwise
                    owner.submit(first_reading).result(FIRST_READING_S)
                except Exception as e:  # the stream still starts; it tells what comes
                    log.debug("first reading for a %s subscriber: %s", what, e)
            yield from watch_stream(context, watched, message)
        finally:
            owner.watch(what, -1)

    @stream_rpc
    def Subscribe_Position(self, request, context):
        m = self.m

        def message(p):
            world = p["world"] or [0.0] * 6
            s = m.Subscribe_Position_Responses.Position_Struct(
                Location=location(m, world), Joints=[m.DataType_Degrees(Degrees=R(j)) for j in p["joints"]])
            return m.Subscribe_Position_Responses(Position=s)

        yield from self._subscribe(context, "position", self.st.owner.position, message)

    @stream_rpc
    def Subscribe_ControllerStatus(self, request, context):
        m = self.m

        def message(st):
            s = m.Subscribe_ControllerStatus_Responses.ControllerStatus_Struct(
                Connection=S(st["connection"]), Connected=B(st["connected"]), Homed=B(st.get("homed", False)),
                Speed=R(st.get("speed", 0.0)), LastError=I(st.get("last_error", 0)),
                LastErrorText=S(st.get("last_error_text", "")), Inputs=I(st.get("inputs", 0)),
                Outputs=I(st.get("outputs", 0)))
            return m.Subscribe_ControllerStatus_Responses(ControllerStatus=s)

        yield from self._subscribe(context, "status", self.st.owner.status, message)

    @rpc
    def Get_Places(self, request, context):
        struct = self.m.Get_Places_Responses.Places_Struct
        cell = self.st.cell
        return self.m.Get_Places_Responses(Places=[
            struct(Name=S(s.name), Positions=I(s.count), Taught=B(s.kind == KIND_LOC and cell.is_taught(s.name)))
            for s in cell.sites])


class RobotController(Observable, Feature):
    FEATURE = "RobotController"

    @rpc
    def MovePlate(self, request, context):
        self.check("MovePlate", request)
        o, t = request.OriginSite.Site, request.DestinationSite.Site
        plate = request.PlateType.value
        if self.st.cell.plate(plate) is None:
            raise sila.validation(self.f.parameter_fqi("MovePlate", "PlateType"),
                                  "no plate type %r: the cell has %s" % (
                                      plate, ", ".join(p[1] for p in self.st.cell.plates) or "none"))
        origin, target = (o.Device.value, o.SiteIndex.value), (t.Device.value, t.SiteIndex.value)

        def work(c):
            self.eval(c, context, "MovePlate", self.st.cell.transfer(origin, target, plate) + " FINISH")
            return self.m.MovePlate_Responses()

        return self.launch(context, "MovePlate", work)

    @stream_rpc
    def MovePlate_Info(self, request, context):
        yield from self.info("MovePlate", request, context)

    @rpc
    def MovePlate_Result(self, request, context):
        return self.result("MovePlate", request)

    @rpc
    def Get_Sites(self, request, context):
        struct = self.m.Get_Sites_Responses.Sites_Struct
        return self.m.Get_Sites_Responses(Sites=[struct(Device=S(s.name), SiteCount=I(s.count))
                                                 for s in self.st.cell.sites])

    @rpc
    def Get_PlateTypes(self, request, context):
        struct = self.m.Get_PlateTypes_Responses.PlateTypes_Struct
        return self.m.Get_PlateTypes_Responses(PlateTypes=[struct(Name=S(p[1]), Width=R(p[2]))
                                                           for p in self.st.cell.plates])
