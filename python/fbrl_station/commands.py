# SPDX-License-Identifier: MIT
"""The method library and what a client does to a running command: MethodLibrary (Methods,
RunMethod), CancelController, PauseController and ErrorRecoveryService, on runs.py."""
import concurrent.futures
import decimal
import time
from xml.sax.saxutils import escape

from . import sila
from .arm import watch_stream
from .controller import RobotFailure
from .core import Feature
from .runs import OPTIONS
from .sila import B, I, R, S, rpc, stream_rpc, who

# Units a method's parameter may name, as SiLA unit constraints: (label, factor to SI, SI
# unit, exponent). A unit not here is given as the range alone.
UNITS = {"s": (1, "Second", 1), "min": (60, "Second", 1), "h": (3600, "Second", 1), "ms": (0.001, "Second", 1),
         "ml": (1e-6, "Meter", 3), "ul": (1e-9, "Meter", 3), "l": (1e-3, "Meter", 3), "mm": (0.001, "Meter", 1),
         "cm": (0.01, "Meter", 1), "in": (0.0254, "Meter", 1), "tubes": (1, "Dimensionless", 1),
         "samples": (1, "Dimensionless", 1), "vials": (1, "Dimensionless", 1)}


def constraints_xml(p):
    """A parameter's range (and unit) as a Constraints element of the standard's Constraints.xsd."""
    parts = ["<MinimalInclusive>%d</MinimalInclusive>" % p["min"], "<MaximalInclusive>%d</MaximalInclusive>" % p["max"]]
    unit = UNITS.get(p["unit"].lower())
    if unit:
        parts.append("<Unit><Label>%s</Label><Factor>%s</Factor><Offset>0</Offset><UnitComponent><SIUnit>%s</SIUnit>"
                     "<Exponent>%d</Exponent></UnitComponent></Unit>" % (
                         escape(p["unit"]), format(decimal.Decimal(repr(float(unit[0]))), "f"), unit[1], unit[2]))
    return '<Constraints xmlns="http://www.sila-standard.org">%s</Constraints>' % "".join(parts)


class MethodLibrary(Feature):
    FEATURE = "MethodLibrary"

    @rpc
    def Get_Methods(self, request, context):
        lib = self.st.runs.library
        M = self.m.Get_Methods_Responses.Methods_Struct
        out = []
        for m in lib.methods:
            params = [M.Parameters_Struct(Name=S(p["name"]), Unit=S(p["unit"]), Description=S(p["text"]),
                                          Default=I(p["value"]), Constraints=S(constraints_xml(p)))
                      for p in m["params"]]
            steps = [M.Steps_Struct(Name=S(x["name"]), Description=S(x["text"]), PerSample=B(x["per_sample"]))
                     for x in m["steps"]]
            out.append(M(Name=S(m["name"]), Description=S(m["text"]), File=S(lib.files[m["name"].upper()]),
                         Parameters=params, Steps=steps))
        return self.m.Get_Methods_Responses(Methods=out)

    @rpc
    def RunMethod(self, request, context):
        self.check("RunMethod", request)
        self.protected(context)
        st = self.st
        name = request.Method.value
        given = [(p.Name.value, p.Value.value) for p in request.Parameters]
        values = []
        if st.runs.library.find(name) is not None:
            try:
                values = st.runs.check_values(name, given)
            except ValueError as e:
                raise sila.validation(self.f.parameter_fqi("RunMethod", "Parameters"), str(e))
        return st.executions.confirmation(self.launch_run(name, values, who(context)))

    def launch_run(self, name, values, by, role=None, user=None):
        """A RunMethod execution of method name with checked values [(name, value)], started by
        by (a SiLA client, a page; role and user: the page's signed-in user's); the execution."""
        st = self.st
        e = st.executions.new(self.f.command_fqi("RunMethod"))
        fut = st.runs.launch(e, name, values, by, role, user)
        started = time.time()

        def done(f):
            finish(f)
            st.history.record(e, started)

        def finish(f):
            try:
                s = f.result()
            except concurrent.futures.CancelledError:
                e.fail(sila.defined(self.f, "MethodCancelled", "cancelled by %s before it started" % getattr(
                    e.run_state, "cancelled_by", "a client")))
                return
            except RobotFailure as failure:
                e.fail(self.error(failure))
                return
            except Exception as ex:  # the client must learn the run failed, and how
                e.fail(sila.undefined("%s: %s" % (type(ex).__name__, ex)))
                return
            e.finish(self._result(s))

        fut.add_done_callback(done)
        return e

    def _result(self, s):
        R_ = self.m.RunMethod_Responses
        samples = [R_.Samples_Struct(Sample=I(x["sample"]), Outcome=S(x["outcome"]), Reason=S(
            x["reason"] if x["outcome"] != "succeeded" else "")) for x in s["samples"]]
        counts = {}
        for x in s["samples"]:
            counts[x["outcome"]] = counts.get(x["outcome"], 0) + 1
        summary = "%s: %s after %.1f s; samples: %s" % (s["method"], s["outcome"], s["elapsed_ms"] / 1000.0,
                                                         ", ".join("%d %s" % (n, o) for o, n in counts.items())
                                                         or "none")
        return R_(Outcome=S(s["outcome"]), Samples=samples, Summary=S(summary),
                  Elapsed=self.m.DataType_Seconds(Seconds=R(s["elapsed_ms"] / 1000.0)))

    def _execution(self, request):
        return self.st.executions.get(request.value, self.f.command_fqi("RunMethod"))

    @stream_rpc
    def RunMethod_Info(self, request, context):
        yield from self.st.executions.info_stream(self._execution(request), context)

    @stream_rpc
    def RunMethod_Intermediate(self, request, context):
        yield from self.st.executions.intermediate_stream(self._execution(request), context)

    @rpc
    def RunMethod_Result(self, request, context):
        return self.st.executions.result(self._execution(request))


class _OnExecutions(Feature):
    """Cancel and Pause work on an execution named by its UUID."""

    def _target(self, command, request):
        uuid = request.CommandExecutionUUID.UUID.value
        try:
            return self.st.executions.get(uuid)
        except sila.SilaError:
            raise sila.defined(self.f, "InvalidCommandExecutionUUID", "no command execution %s" % uuid)


class CancelController(_OnExecutions):
    FEATURE = "CancelController"

    @rpc
    def CancelCommand(self, request, context):
        self.check("CancelCommand", request)
        self.protected(context)
        e = self._target("CancelCommand", request)
        if e.cancel is None:
            raise sila.defined(self.f, "OperationNotSupported", "only method runs can be cancelled; %s is not one"
                               % e.command_fqi)
        if e.finished:
            raise sila.defined(self.f, "InvalidCommandExecutionUUID", "the execution has ended already")
        e.cancel(who(context))
        return self.m.CancelCommand_Responses()

    @rpc
    def CancelAll(self, request, context):
        self.protected(context)
        for e in self.st.executions.all():
            if e.cancel is not None and not e.finished:
                e.cancel(who(context))
        return self.m.CancelAll_Responses()


class PauseController(_OnExecutions):
    FEATURE = "PauseController"

    def _do(self, command, request, context, what):
        self.check(command, request)
        self.protected(context)
        e = self._target(command, request)
        hook = getattr(e, what)
        if hook is None:
            raise sila.defined(self.f, "OperationNotSupported", "only method runs can be paused; %s is not one"
                               % e.command_fqi)
        if e.finished or not hook(who(context)):
            raise sila.defined(self.f, "InvalidCommandState", "the run is not in a state to %s (%s)" % (
                what, "ended" if e.finished else "see Paused and the run's progress"))
        return getattr(self.m, command + "_Responses")()

    @rpc
    def Pause(self, request, context):
        return self._do("Pause", request, context, "pause")

    @rpc
    def Resume(self, request, context):
        return self._do("Resume", request, context, "resume")

    @rpc
    def Get_Paused(self, request, context):
        rs = self.st.owner.run
        paused = rs is not None and rs.run is not None and rs.run.snapshot()["state"] in ("pausing", "paused")
        return self.m.Get_Paused_Responses(Paused=B(paused))


class ErrorRecoveryService(Feature):
    FEATURE = "ErrorRecoveryService"

    @rpc
    def ExecuteContinuationOption(self, request, context):
        self.check("ExecuteContinuationOption", request)
        self.protected(context)
        option = request.ContinuationOption.value
        if option not in [o[0] for o in OPTIONS]:
            raise sila.defined(self.f, "UnknownContinuationOption", "%r is not one of %s" % (
                option, ", ".join(o[0] for o in OPTIONS)))
        if request.InputData.value:
            raise sila.validation(self.f.parameter_fqi("ExecuteContinuationOption", "InputData"),
                                  "no continuation option of the station takes input data")
        if not self.st.runs.answer(request.CommandExecutionUUID.value, option, who(context)):
            raise sila.defined(self.f, "InvalidCommandExecutionUUID", "no recoverable error of execution %s waits"
                               % request.CommandExecutionUUID.value)
        return self.m.ExecuteContinuationOption_Responses()

    @rpc
    def AbortErrorHandling(self, request, context):
        self.check("AbortErrorHandling", request)
        self.protected(context)
        if not self.st.runs.abort_error_handling(request.CommandExecutionUUID.value, who(context)):
            raise sila.defined(self.f, "InvalidCommandExecutionUUID", "no recoverable error of execution %s waits"
                               % request.CommandExecutionUUID.value)
        return self.m.AbortErrorHandling_Responses()

    @rpc
    def SetErrorHandlingTimeout(self, request, context):
        self.check("SetErrorHandlingTimeout", request)
        self.protected(context)
        self.st.runs.error_timeout = request.ErrorHandlingTimeout.value
        return self.m.SetErrorHandlingTimeout_Responses()

    @stream_rpc
    def Subscribe_RecoverableErrors(self, request, context):
        m = self.m
        mlib = self.st.features["MethodLibrary"]

        def message(questions):
            errors = []
            for q in questions:
                options = [m.DataType_ContinuationOption(ContinuationOption=m.DataType_ContinuationOption.
                                                         ContinuationOption_Struct(Identifier=S(o[0]),
                                                                                   Description=S(o[2]),
                                                                                   RequiredInputData=S("")))
                           for o in OPTIONS]
                errors.append(m.DataType_RecoverableError(RecoverableError=m.DataType_RecoverableError.
                                                          RecoverableError_Struct(
                                                              ErrorIdentifier=S(mlib.error_fqi(q["error"])),
                                                              CommandIdentifier=S(q["command"]),
                                                              CommandExecutionUUID=S(q["uuid"]),
                                                              ErrorTime=sila.timestamp(q["time"]),
                                                              ErrorMessage=S(q["message"]),
                                                              ContinuationOptions=options, DefaultOption=S("Abort"),
                                                              AutomaticSelectionTimeout=I(0))))
            return m.Subscribe_RecoverableErrors_Responses(RecoverableErrors=errors)

        yield from watch_stream(context, self.st.runs.recoverable, message)
