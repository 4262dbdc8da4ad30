# SPDX-License-Identifier: MIT
"""Fixtures: a real fbrlsim process on a pty, its command log (the truth for what ran)."""
import os
import subprocess
import sys
import time

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))  # python/: the package under test

SIM_START_SECONDS = 10
TIME_SCALE = "100"  # simulated time 100 times faster: motions take milliseconds
LOADED_HOST_ECHO_MS = 500  # a loaded test machine may stall us; the controller is not slow


def _fbrlsim():
    path = os.environ.get("FBRL_SIM") or os.path.join(os.path.dirname(os.path.dirname(HERE)), "build", "sim",
                                                      "fbrlsim")
    if not os.access(path, os.X_OK):
        pytest.fail("fbrlsim not found at %s (set FBRL_SIM)" % path)
    return path


class Sim:
    """An fbrlsim process: .port is its pty, .log() the command lines it executed."""

    def __init__(self, tmp_path, *args, time_scale=TIME_SCALE, status_extra=True):
        self.log_path = str(tmp_path / "sim.log")
        extra = ["--status-extra"] if status_extra else []  # without it STATUS is RAPL-II's: no OUTPUTS line
        self.proc = subprocess.Popen([_fbrlsim()] + extra + ["--log", self.log_path, "--time-scale", time_scale]
                                     + list(args), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        deadline = time.monotonic() + SIM_START_SECONDS
        self.port = self.proc.stdout.readline().strip()
        if not self.port.startswith("/dev/") or time.monotonic() > deadline:
            self.stop()
            pytest.fail("fbrlsim did not start: %r %s" % (self.port, self.proc.stderr.read()))

    def log(self):
        try:
            with open(self.log_path) as f:
                return [line.rstrip("\n") for line in f]
        except FileNotFoundError:
            return []

    def stop(self):
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=SIM_START_SECONDS)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self.proc.stdout.close()
        self.proc.stderr.close()


@pytest.fixture
def sim(tmp_path):
    s = Sim(tmp_path)
    yield s
    s.stop()


@pytest.fixture
def link(sim):
    import fbrl
    with fbrl.Port(sim.port) as port:
        yield fbrl.Link(port, echo_timeout_ms=LOADED_HOST_ECHO_MS)


@pytest.fixture
def realtime_sim(tmp_path):
    """fbrlsim in real time on a strict 9600-baud line, its log stamped (seconds since it
    started, the result, the line): for waits and stops whose timing is the point."""
    s = Sim(tmp_path, "--baud", "9600", "--log-format", "stamped", time_scale="1")
    yield s
    s.stop()


def fbrl_audit_path():
    """The build's fbrl-audit (FBRL_AUDIT), the C program the chain's truth is read with."""
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    path = os.environ.get("FBRL_AUDIT") or os.path.join(root, "build", "apps", "fbrl-audit")
    if not os.access(path, os.X_OK):
        pytest.skip("fbrl-audit not built (set FBRL_AUDIT)")
    return path
