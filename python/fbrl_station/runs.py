# SPDX-License-Identifier: MIT
"""Method runs on the library's run (fbrl.Run, fbrl/run.h): the method library, a RunMethod
execution fed by the run's events and snapshots, and the requests other threads make (pause,
resume, abort, the answer to a corrective action's question), which go to the run's own
thread-safe calls. The run itself executes on the owner thread."""
import glob
import logging
import os
import re
import threading
import time

import fbrl

from . import dryrun, login, pb, sila, trail
from .cell import SITES_FBRL
from .sila import I, S
from .controller import RobotFailure, report
from .owner import Watched

log = logging.getLogger("fbrl-station")

TICK_S = 0.5  # how often a running execution's progress and remaining time are refreshed
METHOD_LINE = re.compile(r"^\s*METHOD\s+(\S+)", re.I | re.M)
CONTROLLER_CODE = re.compile(r"controller error (\d{3})")
# The continuation options of a question, and what each answers the run.
OPTIONS = (("Retry", "retry", "run the step again (put right what failed first)"),
           ("SkipSample", "skip", "give this sample up (it is recorded as skipped) and go on with the next"),
           ("Abort", "stop", "stop the run: the arm halts, the outputs go off, the method's ON-ABORT word "
                             "takes the arm to its safe place"))
# A corrective action's failure kind (fbrl/recover.h) as a defined execution error.
KIND_ERRORS = {"COLLISION": "CollisionRefused", "REACH": "ControllerRefused", "JOINT-LIMIT": "ControllerRefused",
               "CONTROLLER": "ControllerRefused", "COMM-LOST": "ControllerLost"}


class Library:
    """The methods the engine loaded from --methods DIR: {name: file}, and their description
    from the run (read on the owner thread, kept for any thread)."""

    def __init__(self, directory):
        self.directory = directory
        self.files = {}
        self.versions = {}  # file -> its version as included (fbrl.method_version), None: unknown
        self._methods = []
        self._mutex = threading.Lock()

    def load(self, c, warn):
        """Include every method file of the library (a file with a METHOD line); one that
        fails is left out with its error in the log."""
        if not os.path.isdir(self.directory):
            warn("no method library at %s (--methods DIR): no methods" % self.directory)
            return
        for path in sorted(glob.glob(os.path.join(self.directory, "*.fbrl"))):
            if not os.path.isfile(path):
                continue
            with open(path, encoding="utf-8", errors="replace") as f:
                names = METHOD_LINE.findall(f.read())
            if not names:
                continue
            try:
                c.engine.include(path)
            except fbrl.Error as e:
                warn("method library: %s (left out)" % report(e, path))
                continue
            finally:
                c.engine.reset()
            try:  # the files as the engine just read them: what every run of its methods runs
                self.versions[path] = fbrl.method_version(path)[0]
            except fbrl.Error as e:
                warn("method library: %s: no version: %s" % (path, e))
                self.versions[path] = None
            for n in names:
                self.files[n.upper()] = path
        self.refresh(c)

    def refresh(self, c):
        methods = [m for m in c.run.methods() if m["complete"] and m["name"].upper() in self.files]
        with self._mutex:
            self._methods = methods

    @property
    def methods(self):
        with self._mutex:
            return list(self._methods)

    def find(self, name):
        for m in self.methods:
            if m["name"].upper() == name.upper():
                return m
        return None


class RunState:
    """The run a RunMethod execution drives (owner.run while it goes)."""

    def __init__(self, execution, method, values):
        self.e = execution
        self.method = method
        self.values = values
        self.future = None  # the owner's job
        self.ticking = False
        self.cancelled_by = ""  # who cancelled it, or why the error was left unhandled
        self.run = None  # fbrl.Run once started
        self.question = None  # the recoverable error waiting for a choice (a dict)
        self.ending = None  # why it was stopped: "cancel", "error-handling" (a failure left unhandled)
        self.failure_kind = None  # the last corrective action's failure kind
        self.guard_before = 0
        self.samples = 0
        self.who = ""  # who started it (a SiLA client, a page)
        self.role = None  # with --lab: the role of the page's signed-in user (None: a SiLA client)
        self.user = None  # with --lab: the page's signed-in user's name (None: a SiLA client)
        self.path = None  # the method's file
        self.state = None  # with --lab: the version's state by the lab's audit trail ("Released" ...)
        self.version = None  # the method's version (its files' hash as the library loaded them)

    def describe(self):
        s = self.run.snapshot() if self.run else None
        if not s or s["step"] is None:
            return "%s, starting" % self.method
        step = s["steps"][s["step"]]["name"]
        return "%s, step %d %s%s" % (self.method, s["step"] + 1, step,
                                     ", sample %d" % s["sample"] if s["sample"] else "")


class Runs:
    """RunMethod and what the Cancel, Pause and Error Recovery features ask of it."""

    def __init__(self, station):
        self.st = station
        self.library = Library(station.opts.methods)
        self.recoverable = Watched(())  # ErrorRecoveryService's list
        self.error_timeout = 0  # s, 0: wait for a choice without end
        self.current = None  # the RunState whose run goes (its events come to it)
        # (method, file, its mtime, values): step ms from the dry run; (method, file, mtime): False
        # when the method's dry run failed
        self._predictions = {}
        self._lock = threading.Lock()
        self._m = pb.messages("MethodLibrary")

    def install(self, c):
        """Owner thread, once: the run's events reach the execution of the run that goes."""
        c.run.on_event(lambda ev: self._event(self.current, ev) if self.current is not None else None)

    # ---------------------------------------------------------------- starting
    def check_values(self, method, given):
        """[(name, value)] for every parameter, given ones replacing the current values;
        ValueError naming the first unknown or out of range."""
        m = self.library.find(method)
        by_name = {p["name"].upper(): p for p in m["params"]}
        values = {p["name"]: p["value"] for p in m["params"]}
        for name, v in given:
            p = by_name.get(name.upper())
            if p is None:
                raise ValueError("%s has no parameter %s (it has %s)" % (m["name"], name,
                                                                         ", ".join(values) or "none"))
            if not p["min"] <= v <= p["max"]:
                raise ValueError("%s: %d is outside %d..%d %s" % (p["name"], v, p["min"], p["max"], p["unit"]))
            values[p["name"]] = v
        return [(p["name"], values[p["name"]]) for p in m["params"]]

    def launch(self, e, method, values, who, role=None, user=None):
        """Queue the run of execution e started by who (a page's signed-in user of that role
        and name, else None); returns the owner's Future."""
        rs = RunState(e, method, values)
        rs.who = who
        rs.role, rs.user = role, user
        path = rs.path = self.library.files.get(method.upper())
        rs.version = self.library.versions.get(path) if path else None
        e.cancel = lambda w: self.cancel(rs, w)
        e.pause = lambda w: self._request(rs, "pause", w)
        e.resume = lambda w: self._request(rs, "resume", w)
        e.run_state = rs
        rs.future = self.st.owner.submit(self._job, rs, who)
        return rs.future

    def _job(self, c, rs, who):
        owner = self.st.owner
        m = self.library.find(rs.method)
        if m is None:
            raise RobotFailure("UnknownMethod", "the method library has no method %s" % rs.method)
        if rs.ending == "cancel":
            raise RobotFailure("MethodCancelled", "cancelled by %s before it started" % rs.cancelled_by)
        recorder, allow = None, False
        if self.st.opts.lab is not None:
            rs.state, allow = self._released(m, rs)
        if not c.connected:
            owner.reconnect(c)
        rs.run = c.run
        owner.run = self.current = rs
        owner.arm_state.set("Running")
        try:
            self._predict(c, rs, m)
            if rs.ending == "cancel":  # while the dry run ran
                raise RobotFailure("MethodCancelled", "cancelled by %s before it started" % rs.cancelled_by)
            if self.st.trail is not None:  # from here to its end the run holds the lab's audit trail
                try:
                    recorder = self.st.trail.run(c, rs, m, allow)
                except fbrl.Error as e:
                    raise RobotFailure("AuditTrailUnavailable", "%s: the run cannot be recorded in the lab's audit "
                                       "trail: %s" % (m["name"], e.detail or e))
            log.info("%s: run started by %s", m["name"], who)
            rs.guard_before = c.engine.guard[1]
            ticker = threading.Thread(target=self._tick, args=(rs,), name="fbrl-run-ticker", daemon=True)
            rs.ticking = True
            ticker.start()  # it reports once the run has begun (the begin event starts the execution)
            try:
                snap = c.run.start(m["name"], [v for _, v in rs.values])
            finally:
                rs.ticking = False
                ticker.join()
        finally:
            owner.run = self.current = None
            if recorder is not None:
                recorder.end()
            self._clear_question(rs)
            if c.connected:
                owner.refresh()
            owner.publish_connection()
        return self._outcome(c, rs, m, snap)

    def _released(self, m, rs):
        """With --lab: may rs's starter run the method, by the lab's audit trail? As fbrlmon
        checks a run in the lab (fbrl.method_release): an operator runs only a Released
        version whose files are unchanged, a developer a Draft too where the lab allows it. A
        SiLA client has no user of the lab and counts as an operator. The file must also be the
        one the station loaded (what the engine runs). (The version's state, whether the lab
        allows Drafts), or RobotFailure("MethodNotReleased", why)."""
        lab, path = self.st.opts.lab, rs.path
        role = rs.role or "operator"
        try:
            allow = fbrl.Users(os.path.join(lab, login.USERS_FILE)).settings()["allow_drafts"]
            hex_now, state = fbrl.method_release(path, os.path.join(lab, trail.CHAIN_FILE), role, allow)
        except fbrl.Error as e:
            log.warning("%s: not run for %s (%s): %s", m["name"], rs.who, role, e.detail or e)
            self._refused(m, rs, e.detail or str(e))
            raise RobotFailure("MethodNotReleased", "%s, %s: %s (%s): %s" % (
                rs.who, role, m["name"], os.path.basename(path), e.detail or e))
        if rs.version is not None and hex_now != rs.version:
            why = "%s: %s changed since the station loaded it (version %.12s, now %.12s): restart the station to " \
                  "run what the file holds now" % (m["name"], path, rs.version, hex_now)
            self._refused(m, rs, why)
            raise RobotFailure("MethodNotReleased", why)
        return state, allow

    def _refused(self, m, rs, why):
        """A run refused by the release check, in the lab's audit trail as fbrlmon records one."""
        try:
            self.st.trail.record("method_refused", rs.user, method=m["name"], version=rs.version, reason=why,
                                 by=rs.who)
        except fbrl.Error as e:
            log.error("%s: the refusal could not be recorded in the lab's audit trail: %s", m["name"], e)

    def _predict(self, c, rs, m):
        """The dry run's step times for the run (without them the run's own measurements count).
        Kept per method file (as it is now) and values; a dry run that failed is not tried again."""
        path = self.library.files[m["name"].upper()]
        method_key = (m["name"], path, os.stat(path).st_mtime_ns)
        key = method_key + (tuple(rs.values),)
        if key not in self._predictions and self._predictions.get(method_key, True):
            try:
                self._predictions[key] = dryrun.predict(self.st.opts, SITES_FBRL, path, m["name"], rs.values,
                                                        self.st.data.path)
            except (OSError, ValueError) as e:
                self._predictions[method_key] = False  # the method's dry run fails: not again
                log.warning("%s: no dry-run prediction, the remaining time is measured as the run goes: %s",
                            m["name"], e)
        ms = self._predictions.get(key)
        if ms:
            c.run.predict(m["name"], ms[:len(m["steps"])])

    # ---------------------------------------------------------------- while it runs
    def _tick(self, rs):
        """Progress and remaining time from the run's snapshot, and the arm's state."""
        while rs.ticking:
            if not rs.e.status == sila.RUNNING:
                time.sleep(TICK_S / 5)
                continue
            try:
                s = rs.run.snapshot()
            except fbrl.Error:  # the engine was changing it: the next tick reads it
                time.sleep(TICK_S / 5)
                continue
            remaining = None if s["remaining_ms"] is None else s["remaining_ms"] / 1000.0
            elapsed = s["elapsed_ms"] / 1000.0
            if remaining is not None:
                fraction = elapsed / (elapsed + remaining) if elapsed + remaining > 0 else 0.0
            else:
                runs = sum(x["runs"] for x in s["steps"]) or 1
                fraction = sum(x["done"] for x in s["steps"]) / runs
            rs.e.progress(fraction, remaining)
            state = {"paused": "Paused"}.get(s["state"], "Running")
            if s["question"]:
                state = "Recovering"
                q = rs.question
                if q and self.error_timeout and time.monotonic() - q["since"] > self.error_timeout:
                    self.abort_error_handling(rs.e.uuid, "the error handling timeout (%d s)" % self.error_timeout)
            self.st.owner.arm_state.set(state)
            time.sleep(TICK_S)

    def _event(self, rs, ev):
        """The run's events (owner thread) as the execution's intermediate responses."""
        kind = ev["kind"]
        if kind == "begin":
            if rs.ending == "cancel":  # cancelled between the check above and now: it ends at once
                rs.run.abort(rs.cancelled_by)
            snap = rs.run.snapshot()
            rs.samples = len(snap["samples"])
            rs.e.start(None if snap["remaining_ms"] is None else snap["remaining_ms"] / 1000.0)
            return
        if kind == "recovery":
            rs.failure_kind = ev.get("failure")
            return
        names = {"step_begin": "StepStarted", "pause": "Paused", "resume": "Resumed",
                 "question": "WaitingForRecovery", "answer": "Recovered"}
        if kind == "step_end":
            event = "StepFailed" if ev["text"] else "StepEnded"
        elif kind in names:
            event = names[kind]
        else:
            return
        if kind == "question":
            self._ask(rs, ev["text"])
        elif kind == "answer":
            self._clear_question(rs)
        message = ev["text"] or ""
        if kind in ("pause", "resume"):
            message = "by %s" % (ev.get("who") or "someone")
        elif kind == "answer":
            message = "%s, by %s" % (ev.get("choice"), ev.get("who") or "someone")
        p = self._m.RunMethod_IntermediateResponses.Progress_Struct(
            Event=S(event), Step=I(ev["step"] + 1 if ev.get("step") is not None else 0),
            StepName=S(ev.get("step_name") or ""), Sample=I(ev.get("sample") or 0), SampleCount=I(rs.samples),
            Message=S(message))
        rs.e.intermediate(self._m.RunMethod_IntermediateResponses(Progress=p))

    def _ask(self, rs, question):
        kind = KIND_ERRORS.get(rs.failure_kind or "", "StepFailed")
        rs.question = {"uuid": rs.e.uuid, "command": rs.e.command_fqi, "error": kind, "message": question,
                       "time": time.time(), "since": time.monotonic()}
        with self._lock:
            self.recoverable.set(tuple(q for q in self.recoverable.value if q["uuid"] != rs.e.uuid)
                                 + (rs.question,))
        self.st.owner.arm_state.set("Recovering")

    def _clear_question(self, rs):
        rs.question = None
        with self._lock:
            self.recoverable.set(tuple(q for q in self.recoverable.value if q["uuid"] != rs.e.uuid))

    # ---------------------------------------------------------------- requests (any thread)
    def _request(self, rs, what, who):
        """pause or resume: False when the run is not in a state for it."""
        if rs.run is None or rs.e.finished:
            return False
        s = rs.run.snapshot()
        if what == "pause" and s["state"] not in ("running",):
            return False
        if what == "resume" and s["state"] not in ("pausing", "paused"):
            return False
        try:
            getattr(rs.run, what)(who)
        except fbrl.Error:
            return False
        return True

    def cancel(self, rs, who):
        """The console's abort (or, not started yet, the run never starts)."""
        rs.ending = rs.ending or "cancel"
        rs.cancelled_by = who
        fut = getattr(rs, "future", None)
        if fut is not None and fut.cancel():  # still queued: it never runs (MethodCancelled)
            return
        if rs.run is not None and not rs.e.finished:
            try:
                rs.run.abort(who)
            except fbrl.Error:
                pass  # it ended meanwhile: its own outcome stands

    def answer(self, uuid, option, who):
        """A continuation option for the question of execution uuid: False when none waits,
        KeyError for an unknown option."""
        rs = self._waiting(uuid)
        if rs is None:
            return False
        choice = {o[0]: o[1] for o in OPTIONS}[option]
        if choice == "stop":
            rs.ending = "cancel"
            rs.cancelled_by = who
        try:
            rs.run.answer(choice, who)
        except fbrl.Error:
            return False
        return True

    def abort_error_handling(self, uuid, who):
        """The failure is not handled: the run stops with it as its error."""
        rs = self._waiting(uuid)
        if rs is None:
            return False
        rs.ending = "error-handling"
        rs.cancelled_by = who
        try:
            rs.run.answer("stop", who)
        except fbrl.Error:
            return False
        return True

    def _waiting(self, uuid):
        with self._lock:
            qs = [q for q in self.recoverable.value if q["uuid"] == uuid]
        if not qs:
            return None
        for e in self.st.executions.all():
            if e.uuid == uuid:
                return getattr(e, "run_state", None)
        return None

    # ---------------------------------------------------------------- the end
    def _outcome(self, c, rs, m, s):
        """The run's result, or the failure that stopped it as a RobotFailure."""
        done = ", ".join("%d %s" % (n, o) for o, n in _counts(s["samples"]).items()) or "no samples"
        where = _where(s)
        if s["outcome"] == "aborted":
            if rs.ending == "error-handling":
                raise RobotFailure(KIND_ERRORS.get(rs.failure_kind or "", "StepFailed"),
                                   "%s: %s (the error was not handled: %s; samples: %s)" % (
                                       where, s["error"] or "failed", rs.cancelled_by, done))
            raise RobotFailure("MethodCancelled", "%s by %s at %s; samples: %s; the arm was halted, the outputs "
                                                  "switched off and ON-ABORT run" % (
                                                      "cancelled", s["who"] or "a client", where, done))
        if s["error"] and any(x["failed"] for x in s["steps"]):
            raise RobotFailure(self._failure_kind(c, rs, s["error"]), "%s: %s (samples: %s; the arm was halted, "
                                                                      "the outputs switched off)" % (
                                                                          where, s["error"], done))
        return s

    def _failure_kind(self, c, rs, text):
        """What stopped the run, from the library's record: the guard's refusals, the link's
        units and state, the controller's error code in the run's error."""
        if c.engine.guard[1] > rs.guard_before:
            return "CollisionRefused"
        if c.link is not None and c.link.units == "mm" and "millimetres" in text:
            return "UnitsMismatch"
        code = CONTROLLER_CODE.search(text)
        if code:
            return "NotHomed" if int(code.group(1)) == 41 else "ControllerRefused"
        if "may have run" in text:
            return "MayHaveRun"
        if c.lost:
            return "ControllerLost"
        return "StepFailed"


def _counts(samples):
    out = {}
    for x in samples:
        out[x["outcome"]] = out.get(x["outcome"], 0) + 1
    return out


def _where(s):
    if s["step"] is None:
        return s["method"]
    return "%s step %d (%s)%s" % (s["method"], s["step"] + 1, s["steps"][s["step"]]["name"],
                                  ", sample %d" % s["sample"] if s["sample"] else "")
