# SPDX-License-Identifier: MIT
"""Ctrl-C while the bindings wait on the controller (docs/python.md, "Stopping the arm").

Python runs its SIGINT handler only between two bytecodes of the main thread: while C runs
(the engine evaluating FBRL, a command in the link) a KeyboardInterrupt would come only
when the wait is over, after the arm finished its move. Inside deferred():

- SIGINT is recorded (state.fired) instead of raising KeyboardInterrupt at whatever line
  runs, so the caller stops the arm first and then raises KeyboardInterrupt itself;
- the wake functions (fbrl_vm_interrupt for the engine) are called at once, from a thread
  woken by the signal's byte on a pipe (signal.set_wakeup_fd), so C code that looks for
  them sees them while Python's own handler still waits for the main thread;
- state.sleep() returns at once.

Only the main thread with Python's own SIGINT handler is changed: elsewhere (another
thread, a program's own handler) KeyboardInterrupt comes as usual and the callers' except
clauses stop the arm all the same. A wakeup fd another library set (asyncio) gets the
signal bytes passed on, and is put back afterwards."""
import contextlib
import os
import signal
import threading


class State:
    """One deferral: fired once Ctrl-C came."""

    def __init__(self, wake=None):
        self.fired = False
        self._wakes = [wake] if wake else []
        self._event = threading.Event()

    def fire(self):
        self.fired = True
        self._event.set()
        for wake in list(self._wakes):
            wake()

    def check(self):
        """KeyboardInterrupt if Ctrl-C came."""
        if self.fired:
            raise KeyboardInterrupt

    def sleep(self, seconds):
        """Sleep, ending early on Ctrl-C."""
        self._event.wait(seconds)


_active = None  # the main thread's deferral in effect


def _watch(rfd, state, old_fd):
    while True:
        try:
            data = os.read(rfd, 64)
        except InterruptedError:
            continue
        if not data:
            return  # the write end was closed: the deferral is over
        if signal.SIGINT in data:
            state.fire()
        if old_fd >= 0:
            try:
                os.write(old_fd, data)
            except OSError:
                pass  # its reader is gone or full: a wakeup is a hint, nothing is lost


@contextlib.contextmanager
def deferred(wake=None):
    """Defer Ctrl-C for the block (see the module's text); yields the State."""
    global _active
    main = threading.current_thread() is threading.main_thread()
    if main and _active is not None:  # nested: the outer deferral serves, with this wake too
        if wake:
            _active._wakes.append(wake)
        try:
            yield _active
        finally:
            if wake:
                _active._wakes.remove(wake)
        return
    if not main or signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        yield State(wake)
        return
    state = State(wake)
    signal.signal(signal.SIGINT, lambda signum, frame: state.fire())  # first: no Ctrl-C raises from here
    _active = state
    rfd, wfd = os.pipe()
    installed = False
    watcher = None
    try:
        os.set_blocking(wfd, False)
        old_fd = signal.set_wakeup_fd(wfd, warn_on_full_buffer=False)
        installed = True
        watcher = threading.Thread(target=_watch, args=(rfd, state, old_fd), name="fbrl-sigint", daemon=True)
        watcher.start()
        yield state
    finally:
        _active = None
        if installed:
            signal.set_wakeup_fd(old_fd)
        signal.signal(signal.SIGINT, signal.default_int_handler)
        os.close(wfd)  # the watcher reads the end and returns
        if watcher is not None:
            watcher.join()
        os.close(rfd)


@contextlib.contextmanager
def stopping(stop, wake=None):
    """deferred(), and when Ctrl-C came in the block (recorded, or a KeyboardInterrupt raised
    in it): stop(e) makes the arm safe and sets e.stop, then the KeyboardInterrupt e is
    raised, also when the block ended otherwise (an error the interrupted wait caused is its
    __cause__)."""
    def stopped(e):
        if getattr(e, "stop", None) is None:  # a nested block stopped already
            stop(e)
        return e

    with deferred(wake) as state:
        try:
            yield state
        except KeyboardInterrupt as e:
            raise stopped(e)
        except BaseException as e:
            if not state.fired:
                raise
            raise stopped(KeyboardInterrupt()) from e
        if state.fired:
            raise stopped(KeyboardInterrupt())
