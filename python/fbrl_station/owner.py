# SPDX-License-Identifier: MIT
"""The one thread that owns the link and the engine (DESIGN 10: the engine stays
single-threaded). gRPC's threads hand it jobs (submit/call) and read what it publishes (the
arm's state, position and controller status, as Watched values); nothing else touches the
library's objects, except the requests the library documents as safe from any thread (an
engine interrupt, the run's pause, abort and recovery answer)."""
import concurrent.futures
import logging
import queue
import threading
import time

import fbrl

from .controller import RobotFailure

log = logging.getLogger("fbrl-station")

IDLE_READ_S = 1.0  # while idle with a position subscriber: one W2 this often (docs/sila.md)


class Watched:
    """A value other threads wait on: each change bumps .version and wakes them."""

    def __init__(self, value):
        self.value = value
        self.version = 0
        self.cond = threading.Condition()

    def set(self, value):
        with self.cond:
            if value != self.value:
                self.value = value
                self.version += 1
                self.cond.notify_all()

    def wait(self, version, timeout):
        """(value, version) once the version differs from version, or after timeout."""
        with self.cond:
            if self.version == version:
                self.cond.wait(timeout)
            return self.value, self.version


class Owner:
    """Jobs run one after the other on the owner thread with the Controller; while there is
    none and someone watches the position, the arm is read once a second."""

    def __init__(self, controller):
        self.controller = controller
        self.jobs = queue.Queue()
        self.arm_state = Watched("Disconnected")
        self.position = Watched(None)
        self.position_at = None  # time.time() of the last reading (the page tells its age)
        self.status = Watched(None)
        self.run = None  # the method run that owns the arm (methods.py), None: none
        self.status_fresh = False  # the published STATUS was read after the last command
        self._watchers = {"position": 0, "status": 0}
        self._wlock = threading.Lock()
        self._stop = False
        self.thread = threading.Thread(target=self._loop, name="fbrl-engine", daemon=True)
        controller.engine.on_moving(self._moving)

    def start(self):
        self.thread.start()

    def stop(self, last=None):
        """Drop the jobs that wait (their Futures cancelled), run last(controller), end the
        thread. A job that runs now finishes first."""
        self._stop = True
        while True:
            try:
                job = self.jobs.get_nowait()
            except queue.Empty:
                break
            if job is not None:
                job[0].cancel()
        if last is not None:
            self.jobs.put((concurrent.futures.Future(), last, ()))
        self.jobs.put(None)
        self.thread.join()

    def submit(self, fn, *args):
        """Run fn(controller, *args) on the owner thread; a Future of its result."""
        fut = concurrent.futures.Future()
        if self._stop:  # the station is stopping: nothing new starts
            fut.cancel()
        else:
            self.jobs.put((fut, fn, args))
        return fut

    def call(self, fn, *args):
        return self.submit(fn, *args).result()

    def watch(self, what, delta):
        """A subscriber of "position" or "status" came (+1) or went (-1)."""
        with self._wlock:
            self._watchers[what] += delta

    def watching(self, what):
        with self._wlock:
            return self._watchers[what] > 0

    def _loop(self):
        while True:
            try:
                job = self.jobs.get(timeout=IDLE_READ_S)
            except queue.Empty:
                if self.watching("position") and self.controller.connected and self.run is None:
                    self.refresh(position=True, status=False)
                continue
            if job is None:
                break
            fut, fn, args = job
            if not fut.set_running_or_notify_cancel():
                continue
            try:
                fut.set_result(fn(self.controller, *args))
            except BaseException as e:  # handed to the caller's thread
                fut.set_exception(e)

    # ---------------------------------------------------------------- on the owner thread
    def refresh(self, position=True, status=None):
        """Read the arm (W2) and, when someone watches it (or status=True), the controller's
        STATUS; publish them. A controller that does not answer makes the state Disconnected."""
        c = self.controller
        if status is None:
            status = self.watching("status") or self.status.value is None
        self.status_fresh = self.status_fresh and not position  # a command ran since the last STATUS
        try:
            if position:
                where = c.where()
                self.position_at = time.time()
                self.position.set(where)
            if status:
                self.status.set(c.status())
                self.status_fresh = True
        except fbrl.Error as e:
            log.warning("reading the arm: %s", e)
        self.publish_connection()

    def _moving(self):
        """A robot word waits for the arm to stop (a run's motion or a client's): read it, about
        once a second, for whoever watches the position, so the page draws the arm as it moves.
        A reading that fails is kept in engine.moving_error; the motion goes on."""
        if self.watching("position") and self.controller.connected:
            where = self.controller.where()
            self.position_at = time.time()
            self.position.set(where)

    def publish_connection(self):
        c = self.controller
        if not c.connected:
            self.arm_state.set("Disconnected")
            st = dict(self.status.value or {})
            st.update(connected=False, connection=c.describe())
            self.status.set(st)
        elif self.run is None and self.arm_state.value != "Idle":  # a motion's or a run's state is over
            self.arm_state.set("Idle")

    def motion(self, fn, *args):
        """Run a job that drives the arm: the state is Busy meanwhile, and the arm is read
        afterwards (also after a failure: it may have moved part of the way)."""

        def job(c):
            if self.run is not None:
                raise RobotFailure("StationBusy", "a method run owns the arm (%s)" % self.run.describe())
            if not c.connected:
                self.reconnect(c)
            self.arm_state.set("Busy")
            try:
                return fn(c, *args)
            finally:
                if c.connected:
                    self.refresh()
                self.publish_connection()

        return self.submit(job)

    def reconnect(self, c):
        """Try the controller once more (it may be back); RobotFailure ControllerLost if not."""
        try:
            c.connect(c.simulation)
        except (fbrl.Error, OSError) as e:
            raise RobotFailure("ControllerLost", "the controller does not answer: %s" % e)
        log.info("connected again: %s", c.describe())
