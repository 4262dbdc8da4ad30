# SPDX-License-Identifier: MIT
"""The SiLA 2 framework on gRPC (Part B): errors, client metadata, the lock, and observable
command executions with their Info, Intermediate and Result calls."""
import base64
import functools
import logging
import threading
import time
import uuid as uuidlib

import grpc

from .pb import fw

log = logging.getLogger("fbrl-station")

# How often an Info stream speaks while nothing changes (the remaining time counts down), and
# how long a finished execution stays answerable.
INFO_PERIOD_S = 0.25
EXECUTIONS_KEPT = 1000


# ------------------------------------------------------------------ values
def S(v):
    return fw.String(value=v)


def I(v):  # noqa: E743 - the SiLA type's name
    return fw.Integer(value=int(v))


def R(v):
    return fw.Real(value=float(v))


def B(v):
    return fw.Boolean(value=bool(v))


def duration(seconds):
    seconds = max(0.0, seconds)
    whole = int(seconds)
    return fw.Duration(seconds=whole, nanos=int((seconds - whole) * 1e9))


def timestamp(t=None):
    """A SiLA Timestamp of the UTC time t (seconds since the epoch; now by default)."""
    g = time.gmtime(t)
    return fw.Timestamp(second=g.tm_sec, minute=g.tm_min, hour=g.tm_hour, day=g.tm_mday, month=g.tm_mon,
                        year=g.tm_year, timezone=fw.Timezone(hours=0, minutes=0))


# ------------------------------------------------------------------ errors
class SilaError(Exception):
    """A SiLA error to send: .pb is the SiLAError message."""

    def __init__(self, pb, text):
        super().__init__(text)
        self.pb = pb


def validation(parameter_fqi, message):
    return SilaError(fw.SiLAError(validationError=fw.ValidationError(parameter=parameter_fqi, message=message)),
                     "%s: %s" % (parameter_fqi, message))


def defined(feature, error, message):
    """A defined execution error of feature (fdl.Feature) by its identifier."""
    fqi = feature.error_fqi(error)
    return SilaError(fw.SiLAError(definedExecutionError=fw.DefinedExecutionError(errorIdentifier=fqi,
                                                                                 message=message)),
                     "%s: %s" % (error, message))


def undefined(message):
    return SilaError(fw.SiLAError(undefinedExecutionError=fw.UndefinedExecutionError(message=message)), message)


def framework(kind, message):
    """kind: COMMAND_EXECUTION_NOT_ACCEPTED, INVALID_COMMAND_EXECUTION_UUID,
    COMMAND_EXECUTION_NOT_FINISHED, INVALID_METADATA or NO_METADATA_ALLOWED."""
    return SilaError(fw.SiLAError(frameworkError=fw.FrameworkError(
        errorType=fw.FrameworkError.ErrorType.Value(kind), message=message)), "%s: %s" % (kind, message))


def abort(context, err):
    """End the call with the error as Part B sends it: status ABORTED, the base64 of the
    serialized SiLAError as the status message."""
    context.abort(grpc.StatusCode.ABORTED, base64.b64encode(err.pb.SerializeToString()).decode("ascii"))


def decode_error(details):
    """The SiLAError a client received (for tests and the bench)."""
    e = fw.SiLAError()
    e.ParseFromString(base64.b64decode(details))
    return e


def who(context):
    """A SiLA client, as runs and records name it."""
    return "SiLA client %s" % context.peer()


def rpc(fn):
    """A servicer method: a SilaError it raises goes to the client as such; anything else
    is an undefined execution error with its text (and in the station's log)."""

    @functools.wraps(fn)
    def call(self, request, context):
        try:
            return fn(self, request, context)
        except SilaError as e:
            abort(context, e)
        except Exception as e:  # the client must get an answer; the log gets the details
            log.exception("%s failed", fn.__name__)
            abort(context, undefined("%s: %s" % (type(e).__name__, e)))

    return call


def stream_rpc(fn):
    """As rpc, for a method that yields a stream."""

    @functools.wraps(fn)
    def call(self, request, context):
        try:
            yield from fn(self, request, context)
        except SilaError as e:
            abort(context, e)
        except Exception as e:
            log.exception("%s failed", fn.__name__)
            abort(context, undefined("%s: %s" % (type(e).__name__, e)))

    return call


# ------------------------------------------------------------------ metadata
def metadata_key(metadata_fqi):
    """The gRPC metadata key of a SiLA metadata: sila-<FQI, lower case, / as ->-bin."""
    return "sila-" + metadata_fqi.lower().replace("/", "-") + "-bin"


def sila_metadata(context):
    """The SiLA client metadata of a call: {key: bytes}."""
    return {k: v for k, v in context.invocation_metadata() if k.startswith("sila-") and k.endswith("-bin")}


def refuse_metadata(context):
    """SiLAService calls take no SiLA metadata (Part B)."""
    if sila_metadata(context):
        raise framework("NO_METADATA_ALLOWED", "calls to the SiLA Service feature take no SiLA metadata")


class Lock:
    """LockController's lock: identifier, timeout, and the check every protected call makes."""

    def __init__(self, feature, metadata_message):
        self.feature = feature  # LockController's fdl.Feature
        self.key = metadata_key(feature.metadata_fqi("LockIdentifier"))
        self._message = metadata_message
        self._mutex = threading.Lock()
        self._id = None
        self._timeout = 0
        self._last = 0.0

    def _expired(self):
        return self._id is not None and self._timeout > 0 and time.monotonic() - self._last > self._timeout

    @property
    def locked(self):
        with self._mutex:
            if self._expired():
                self._id = None
            return self._id is not None

    def lock(self, ident, timeout):
        with self._mutex:
            if self._expired():
                self._id = None
            if self._id is not None:
                raise defined(self.feature, "ServerAlreadyLocked", "the station is locked by another identifier")
            self._id, self._timeout, self._last = ident, max(0, timeout), time.monotonic()

    def unlock(self, ident):
        with self._mutex:
            if self._expired():
                self._id = None
            if self._id is None:
                raise defined(self.feature, "ServerNotLocked", "the station is not locked")
            if ident != self._id:
                raise defined(self.feature, "InvalidLockIdentifier", "this is not the identifier the station is "
                              "locked with")
            self._id = None

    def check(self, context):
        """Raise unless the station is unlocked or the call carries the lock identifier."""
        with self._mutex:
            if self._expired():
                self._id = None
            if self._id is None:
                return
            raw = dict(context.invocation_metadata()).get(self.key)
            if raw is None:
                raise framework("INVALID_METADATA", "the station is locked: this call needs the lock identifier "
                                "(metadata %s)" % self.feature.metadata_fqi("LockIdentifier"))
            m = self._message()
            try:
                m.ParseFromString(raw)
            except Exception:
                raise framework("INVALID_METADATA", "the lock identifier metadata is not a Metadata_LockIdentifier")
            if m.LockIdentifier.value != self._id:
                raise defined(self.feature, "InvalidLockIdentifier", "the station is locked with another identifier")
            self._last = time.monotonic()


# ------------------------------------------------------------------ observable commands
WAITING, RUNNING, DONE, FAILED = (fw.ExecutionInfo.CommandStatus.Value(n) for n in (
    "waiting", "running", "finishedSuccessfully", "finishedWithError"))


class Execution:
    """One observable command execution. The thread doing the work calls start(), progress(),
    intermediate(), finish() or fail(); the Info, Intermediate and Result calls read it.
    Cancel/pause/resume hooks (callables, None: not supported) are set by the command."""

    def __init__(self, registry, command_fqi):
        self.uuid = str(uuidlib.uuid4())
        self.command_fqi = command_fqi
        self._cond = registry.cond
        self.status = WAITING
        self.fraction = 0.0
        self.end_at = None  # monotonic time the work should be done, None: unknown
        self.intermediates = []
        self.result = None
        self.error = None
        self.cancel = self.pause = self.resume = None  # hooks of a method run (runs.py)
        self.run_state = None

    def _set(self, **kw):
        with self._cond:
            for k, v in kw.items():
                setattr(self, k, v)
            self._cond.notify_all()

    def start(self, expected_s=None):
        self._set(status=RUNNING, end_at=None if expected_s is None else time.monotonic() + expected_s)

    def progress(self, fraction, remaining_s=None):
        self._set(fraction=min(1.0, max(0.0, fraction)),
                  end_at=None if remaining_s is None else time.monotonic() + max(0.0, remaining_s))

    def intermediate(self, message):
        with self._cond:
            self.intermediates.append(message)
            self._cond.notify_all()

    def finish(self, result):
        self._set(status=DONE, result=result, fraction=1.0, end_at=time.monotonic())

    def fail(self, error):
        self._set(status=FAILED, error=error, end_at=time.monotonic())

    @property
    def finished(self):
        return self.status in (DONE, FAILED)

    def info(self):
        now = time.monotonic()
        remaining = 0.0 if self.finished else (None if self.end_at is None else max(0.0, self.end_at - now))
        msg = fw.ExecutionInfo(commandStatus=self.status, progressInfo=R(self.fraction))
        if remaining is not None:
            msg.estimatedRemainingTime.CopyFrom(duration(remaining))
        return msg


class Executions:
    """The station's observable command executions by UUID."""

    def __init__(self):
        self.cond = threading.Condition()
        self._by_uuid = {}

    def new(self, command_fqi):
        e = Execution(self, command_fqi)
        with self.cond:
            self._by_uuid[e.uuid] = e
            if len(self._by_uuid) > EXECUTIONS_KEPT:  # forget the oldest finished one
                for k, old in list(self._by_uuid.items()):
                    if old.finished:
                        del self._by_uuid[k]
                        break
        return e

    def all(self):
        with self.cond:
            return list(self._by_uuid.values())

    def get(self, uuid, command_fqi=None):
        with self.cond:
            e = self._by_uuid.get(uuid)
        if e is None or (command_fqi is not None and e.command_fqi != command_fqi):
            raise framework("INVALID_COMMAND_EXECUTION_UUID", "no execution %r of this command" % uuid)
        return e

    @staticmethod
    def confirmation(e):
        return fw.CommandConfirmation(commandExecutionUUID=fw.CommandExecutionUUID(value=e.uuid))

    def info_stream(self, e, context):
        """ExecutionInfo now, on every change, and every INFO_PERIOD_S (the remaining time
        counting down) until the execution is finished."""
        seen = None
        while context.is_active():
            with self.cond:
                state = (e.status, e.fraction, e.end_at)
                if state == seen:
                    self.cond.wait(INFO_PERIOD_S)
                    state = (e.status, e.fraction, e.end_at)
                msg, finished = e.info(), e.finished
            seen = state
            yield msg
            if finished:
                return

    def intermediate_stream(self, e, context):
        """The intermediate responses from the latest one on, as they come, until finished."""
        i = max(0, len(e.intermediates) - 1)
        while context.is_active():
            with self.cond:
                if i >= len(e.intermediates) and not e.finished:
                    self.cond.wait(INFO_PERIOD_S)
                new, i, finished = e.intermediates[i:], len(e.intermediates), e.finished
            yield from new
            if finished and i >= len(e.intermediates):
                return

    @staticmethod
    def result(e):
        if not e.finished:
            raise framework("COMMAND_EXECUTION_NOT_FINISHED", "the command is still running")
        if e.error is not None:
            raise e.error
        return e.result
