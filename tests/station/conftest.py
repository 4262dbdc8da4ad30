# SPDX-License-Identifier: MIT
"""Fixtures for fbrl-station's tests: a real fbrlsim (its command log is the truth of what the
controller ran) and a station on it, started by the build's launcher as a user starts it."""
import os
import shutil
import signal
import subprocess
import sys
import time

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "python"))

from client import Station, end  # noqa: E402

SITES = os.path.join(ROOT, "examples", "station", "asps_sites.fbrl")
SIM_TIME_SCALE = "20"  # motions 20 times faster than the arm's: a move takes tens of ms
# Places the tests need beyond the cell's: one inside the heating block's body (the guard
# refuses it), one out of the arm's reach (the guard cannot check it, so refuses it too).
TEST_PLACES = ("CREATE-LOC IN-BLOCK 10E0 -2E0 0.5E0 0E0 -90E0 0E0 IN-BLOCK DEFINE-LOC LOC-SITE IN-BLOCK "
               "CREATE-LOC FAR 50E0 0E0 5E0 0E0 -90E0 0E0 FAR DEFINE-LOC LOC-SITE FAR")


def launcher():
    path = os.environ.get("FBRL_STATION") or os.path.join(ROOT, "build", "apps", "fbrl-station")
    if not os.access(path, os.X_OK):
        pytest.fail("fbrl-station not found at %s (set FBRL_STATION)" % path)
    return path


def fbrlsim():
    path = os.environ.get("FBRL_SIM") or os.path.join(ROOT, "build", "sim", "fbrlsim")
    if not os.access(path, os.X_OK):
        pytest.fail("fbrlsim not found at %s (set FBRL_SIM)" % path)
    return path


class Sim:
    """fbrlsim on a pty: .port, .log() the lines it executed, .pause()/.resume() (SIGSTOP)."""

    def __init__(self, directory, *args):
        os.makedirs(directory, exist_ok=True)
        self.log_path = os.path.join(directory, "sim.log")
        self.control_path = os.path.join(directory, "control")  # the panel: POWER 0, IN n 1 ...
        os.mkfifo(self.control_path)
        self.proc = subprocess.Popen([fbrlsim(), "--status-extra", "--log", self.log_path, "--time-scale",
                                      SIM_TIME_SCALE, "--control", self.control_path] + list(args), stdin=subprocess.DEVNULL,
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.port = self.proc.stdout.readline().strip()
        if not self.port.startswith("/dev/"):
            self.proc.kill()
            pytest.fail("fbrlsim did not start: %r" % self.port)
        self.panel = open(self.control_path, "w")  # fbrlsim reads it as long as it runs

    def log(self):
        try:
            with open(self.log_path) as f:
                return [line.rstrip("\n") for line in f]
        except FileNotFoundError:
            return []

    def control(self, line):
        """A control line as the front panel or the cell would give it (fbrlsim --control)."""
        self.panel.write(line + "\n")
        self.panel.flush()

    def pause(self):
        self.proc.send_signal(signal.SIGSTOP)

    def resume(self):
        self.proc.send_signal(signal.SIGCONT)

    def stop(self):
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGCONT)
        end(self.proc, 10)
        self.proc.stdout.close()
        self.proc.stderr.close()
        self.panel.close()


def method_library(directory, sample_prep=True):
    """directory/lib/methods: the tests' methods (tests/station/methods) and the sample-prep
    method, beside the ASPS cell files they include; its path."""
    lib = os.path.join(directory, "lib", "methods")
    os.makedirs(lib)
    for f in ("asps_cell.fbrl", "asps_cell_objects.fbrl"):
        shutil.copy(os.path.join(ROOT, "examples", f), os.path.join(directory, "lib"))
    if sample_prep:
        shutil.copy(os.path.join(ROOT, "examples", "methods", "sample_prep.fbrl"), lib)
    for f in os.listdir(os.path.join(HERE, "methods")):
        shutil.copy(os.path.join(HERE, "methods", f), lib)
    return lib


def wait_for(predicate, seconds=20, what="the condition"):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if predicate():
            return
        time.sleep(0.05)
    pytest.fail("timed out waiting for %s" % what)


def start_station(data, sim, *args, **kw):
    return Station(launcher(), data, "--port", sim.port, "--no-discovery", SITES, "-e", TEST_PLACES, *args, **kw)


class Arm:
    """An fbrlsim, a station on it and a client: .sim, .station, .client."""

    def __init__(self, directory):
        self.sim = Sim(os.path.join(directory, "sim"))
        try:
            self.station = self.start(os.path.join(directory, "data"))
        except BaseException:
            self.sim.stop()
            raise
        self.client = self.station.client()

    def start(self, data):
        return start_station(data, self.sim)

    def stop(self):
        self.client.close()
        self.station.stop()
        self.sim.stop()


class MethodLab(Arm):
    """An Arm whose station has a method library (method_library) and station_args."""

    def __init__(self, directory, *station_args, sample_prep=True):
        self.lib = method_library(directory, sample_prep)
        self.station_args = station_args
        super().__init__(directory)

    def start(self, data):
        return Station(launcher(), data, "--port", self.sim.port, "--no-discovery", "--methods", self.lib,
                       *self.station_args, "-e", "200 CONSTANT TIME-SCALE", SITES)


def assert_aborted_safely(log):
    """fbrlsim's log of a run aborted while the pump ran for its first item: the arm halted,
    then the outputs off and ON-ABORT's safe place, and no second item."""
    on = log.index("OUTPUT 1")
    assert "HALT" in log[on:], log[on:]
    halt = log.index("HALT", on)
    assert "OUTPUT -1" in log[halt:] and "READY" in log[halt:]  # outputs off, then ON-ABORT's safe place
    assert log.count("OUTPUT 1") == 1  # it never got to the next item


@pytest.fixture(scope="module")
def arm(tmp_path_factory):
    """One station for the tests of a file that can share it (each test looks only at the log
    lines its own calls added): starting one costs about a second."""
    a = Arm(str(tmp_path_factory.mktemp("arm")))
    yield a
    a.stop()


@pytest.fixture(scope="module")
def fresh(tmp_path_factory):
    """A station whose arm has not been moved or homed (for tests that only read or are refused)."""
    a = Arm(str(tmp_path_factory.mktemp("fresh")))
    yield a
    a.stop()


@pytest.fixture
def own(tmp_path):
    """A station of the test's own (it stops the emulator, restarts the station ...)."""
    a = Arm(str(tmp_path))
    yield a
    a.stop()
