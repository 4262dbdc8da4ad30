# SPDX-License-Identifier: MIT
"""The standard core features: SiLAService, LockController and SimulationController."""
import fbrl

from . import pb, sila, validate
from .controller import RobotFailure
from .sila import B, S, rpc

SERVER_TYPE = "FbrlStation"
VENDOR_URL = "https://example.invalid/libfbrl"  # the project's homepage (debian/control)
DESCRIPTION = ("A CRS Plus robot arm on a RAPL controller, driven by libfbrl (FBRL): moves between the named "
               "places of its work cell, every motion checked by the collision guard, and the lab's methods.")


class Feature:
    """What every servicer has: the station, its feature definition and messages."""

    FEATURE = None

    def __init__(self, station):
        self.st = station
        self.f = station.features[self.FEATURE]
        self.m = pb.messages(self.FEATURE)

    def add_to(self, server):
        getattr(pb.grpc_module(self.FEATURE), "add_%sServicer_to_server" % self.FEATURE)(self, server)

    def protected(self, context):
        """A call that moves the arm or changes the station: the lock's check."""
        self.st.lock.check(context)

    def check(self, command, request):
        validate.check(self.f, command, request)

    def not_running(self):
        """A command that needs the arm is refused at once while a method run owns it."""
        rs = self.st.owner.run
        if rs is not None:
            raise sila.defined(self.f, "StationBusy", "a method run owns the arm (%s): cancel it or let it end "
                               "first" % rs.describe())

    def error(self, failure):
        """A RobotFailure as this feature's defined execution error (or an undefined one)."""
        kind = failure.kind
        if kind == "SiteNotFound" and kind not in self.f.errors:
            kind = "UnknownPlace"
        if kind in self.f.errors:
            return sila.defined(self.f, kind, failure.message)
        return sila.undefined(failure.message)


class SiLAService(Feature):
    FEATURE = "SiLAService"

    @rpc
    def GetFeatureDefinition(self, request, context):
        sila.refuse_metadata(context)
        self.check("GetFeatureDefinition", request)
        ident = request.FeatureIdentifier.value
        for f in self.st.features.values():
            if f.fqi == ident:
                return self.m.GetFeatureDefinition_Responses(FeatureDefinition=S(f.text))
        raise sila.defined(self.f, "UnimplementedFeature", "this server does not implement %s" % ident)

    @rpc
    def SetServerName(self, request, context):
        sila.refuse_metadata(context)
        self.check("SetServerName", request)
        self.st.set_name(request.ServerName.value)
        return self.m.SetServerName_Responses()

    def _get(self, context, name, value):
        sila.refuse_metadata(context)
        return getattr(self.m, "Get_%s_Responses" % name)(**{name: value})

    @rpc
    def Get_ServerName(self, request, context):
        return self._get(context, "ServerName", S(self.st.identity["name"]))

    @rpc
    def Get_ServerType(self, request, context):
        return self._get(context, "ServerType", S(SERVER_TYPE))

    @rpc
    def Get_ServerUUID(self, request, context):
        return self._get(context, "ServerUUID", S(self.st.identity["uuid"]))

    @rpc
    def Get_ServerDescription(self, request, context):
        return self._get(context, "ServerDescription", S(DESCRIPTION))

    @rpc
    def Get_ServerVersion(self, request, context):
        return self._get(context, "ServerVersion", S(fbrl.version()))

    @rpc
    def Get_ServerVendorURL(self, request, context):
        return self._get(context, "ServerVendorURL", S(VENDOR_URL))

    @rpc
    def Get_ImplementedFeatures(self, request, context):
        return self._get(context, "ImplementedFeatures", [S(f.fqi) for f in self.st.features.values()])


class LockController(Feature):
    FEATURE = "LockController"

    @rpc
    def LockServer(self, request, context):
        self.check("LockServer", request)
        self.st.lock.lock(request.LockIdentifier.value, request.Timeout.value)
        return self.m.LockServer_Responses()

    @rpc
    def UnlockServer(self, request, context):
        self.check("UnlockServer", request)
        self.st.lock.unlock(request.LockIdentifier.value)
        return self.m.UnlockServer_Responses()

    @rpc
    def Get_IsLocked(self, request, context):
        return self.m.Get_IsLocked_Responses(IsLocked=B(self.st.lock.locked))

    @rpc
    def Get_FCPAffectedByMetadata_LockIdentifier(self, request, context):
        return self.m.Get_FCPAffectedByMetadata_LockIdentifier_Responses(
            AffectedCalls=[S(x) for x in self.st.lock_protected()])


class SimulationController(Feature):
    """Emulator or real port; a switch only while nothing runs (the job queue is empty and
    no method run owns the arm: the switch is itself a job, after whatever was queued)."""

    FEATURE = "SimulationController"

    def _switch(self, context, simulation, error):
        self.protected(context)
        owner = self.st.owner

        def job(c):
            if owner.run is not None:
                raise RobotFailure(error, "a method run owns the arm (%s): cancel it or let it end first"
                                   % owner.run.describe())
            if c.simulation == simulation and c.connected:
                return
            before, was_connected = c.simulation, c.connected
            try:
                c.connect(simulation)
            except (fbrl.Error, OSError) as e:
                why = "%s: %s" % ("the emulator did not start" if simulation else
                                  "the real controller did not answer", e)
                if was_connected:  # back to the controller it had, so a failed switch changes nothing
                    try:
                        c.connect(before)
                    except (fbrl.Error, OSError) as e2:
                        why += "; and the %s did not answer again: %s" % (
                            "emulator" if before else "real controller", e2)
                if c.connected:
                    owner.refresh(status=True)
                owner.publish_connection()
                raise RobotFailure(error, why)
            owner.refresh(status=True)

        try:
            owner.call(job)
        except RobotFailure as e:
            raise sila.defined(self.f, error, e.message)

    @rpc
    def StartSimulationMode(self, request, context):
        self._switch(context, True, "StartSimulationModeFailed")
        return self.m.StartSimulationMode_Responses()

    @rpc
    def StartRealMode(self, request, context):
        self._switch(context, False, "StartRealModeFailed")
        return self.m.StartRealMode_Responses()

    @rpc
    def Get_SimulationMode(self, request, context):
        return self.m.Get_SimulationMode_Responses(SimulationMode=B(self.st.controller.simulation))
