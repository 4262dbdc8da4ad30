#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""station_bench.py [BUILD_DIR] - what fbrl-station costs a scheduler on loopback (docs/sila.md):
median and p99 of a property read and of an observable command's overhead beyond the robot's
own time, with TLS and with plain gRPC, and with four arms (four stations, four emulators)
driven at once from one client. Prints figures; asserts nothing.

The robot's own time of the command (MoveToPlace between two places, with FINISH, and the W2
the station reads after it) is the same FBRL text run straight through the Python bindings
against an emulator like the station's, timed just before each call to the station, so both
see the same load; a call's overhead is its time at the client (the command, its Info stream
to the end, its Result) less that direct run's. The emulators run 1000 times faster than the
arm (fbrlsim --time-scale 1000), so the robot's time is the link's.

    ./scripts/build.sh build && /usr/bin/python3 bench/station_bench.py build
"""
import os
import statistics
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
BUILD = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build"))
os.environ.setdefault("FBRL_LIBRARY", os.path.join(BUILD, "libfbrl.so"))
os.environ.setdefault("FBRL_STATION_GEN", os.path.join(BUILD, "station", "gen"))
os.environ.setdefault("FBRL_SIM", os.path.join(BUILD, "sim", "fbrlsim"))
sys.path[:0] = [os.path.join(ROOT, "python"), os.path.join(ROOT, "tests", "station")]

import fbrl  # noqa: E402
from client import Station  # noqa: E402  (the tests' small SiLA client)
from fbrl_station import pb  # noqa: E402
from fbrl_station.sila import I, S  # noqa: E402

READS = 2000
MOVES = 200
SCALE = "1000"
SITES = os.path.join(ROOT, "examples", "station", "asps_sites.fbrl")
PLACES = ("SEPARATOR", "RINSE-REST")
am = pb.messages("ArmController")


def pct(values, p):
    v = sorted(values)
    return v[min(len(v) - 1, int(round(p / 100.0 * (len(v) - 1))))]


def ms(values):
    return "median %.2f ms, p99 %.2f ms" % (statistics.median(values) * 1e3, pct(values, 99) * 1e3)


class Sim:
    def __init__(self, log):
        self.proc = subprocess.Popen([os.environ["FBRL_SIM"], "--status-extra", "--time-scale", SCALE, "--log", log],
                                     stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, text=True)
        self.port = self.proc.stdout.readline().strip()

    def stop(self):
        self.proc.terminate()
        self.proc.wait()
        self.proc.stdout.close()


class Direct:
    """The robot's own time of the motion: the same FBRL text through the bindings."""

    def __init__(self, tmp):
        self.sim = Sim(os.path.join(tmp, "direct.log"))
        self.port = fbrl.Port(self.sim.port)
        self.fb = fbrl.Engine(link=fbrl.Link(self.port), dict_bytes=4 << 20)
        self.fb.include(os.path.join(ROOT, "python", "fbrl_station", "sites.fbrl"))
        self.fb.include(SITES)
        self.fb.eval("HOME")
        names = self.fb.eval(".SITES").split()
        self.index = {names[i]: i // 3 for i in range(0, len(names), 3)}

    def move(self, k):
        t = time.perf_counter()
        self.fb.eval("0 %d SITE-LOC MOV FINISH" % self.index[PLACES[k % 2]])
        self.fb.link.where()  # the station reads the arm after each command too
        return time.perf_counter() - t

    def close(self):
        self.port.close()
        self.sim.stop()


def station(tmp, name, insecure):
    sim = Sim(os.path.join(tmp, name + ".log"))
    st = Station(os.path.join(BUILD, "apps", "fbrl-station"), os.path.join(tmp, name), "--port", sim.port,
                 "--no-discovery", SITES, insecure=insecure)
    return sim, st


def reads(c):
    times = []
    for _ in range(READS):
        t = time.perf_counter()
        c.get("SiLAService", "ServerUUID")
        times.append(time.perf_counter() - t)
    return times


def moves(c, direct, n=MOVES, lock=None):
    """n MoveToPlace calls, each after the same motion run directly: [(station s, direct s)]."""
    c.run("ArmController", "Home")
    out = []
    for k in range(n):
        if lock:
            with lock:
                d = direct.move(k)
        else:
            d = direct.move(k)
        t = time.perf_counter()
        result, _ = c.run("ArmController", "MoveToPlace", Place=am.DataType_PlaceName(PlaceName=S(PLACES[k % 2])),
                          Index=I(0))
        out.append((time.perf_counter() - t, d))
        assert result is not None and not hasattr(result, "kind"), result
    return out


def overhead(pairs):
    return [st - d for st, d in pairs]


def main():
    print("machine: %d cores, load %s" % (os.cpu_count(), open("/proc/loadavg").read().split()[:3]))
    with tempfile.TemporaryDirectory() as tmp:
        direct = Direct(tmp)
        try:
            for insecure in (False, True):
                sim, st = station(tmp, "plain" if insecure else "tls", insecure)
                c = st.client()
                try:
                    label = "plain gRPC" if insecure else "TLS"
                    print("| property read (Get_ServerUUID), %s | %s |" % (label, ms(reads(c))))
                    pairs = moves(c, direct)
                    print("| observable command overhead (MoveToPlace), %s | %s (the robot's own time: %s) |"
                          % (label, ms(overhead(pairs)), ms([d for _, d in pairs])))
                finally:
                    c.close()
                    st.stop()
                    sim.stop()
            arms = [station(tmp, "arm%d" % k, False) for k in range(4)]
            try:
                clients = [st.client() for _, st in arms]
                results = [None] * 4
                lock = threading.Lock()  # the one direct emulator serves the four in turn
                threads = [threading.Thread(target=lambda k=k: results.__setitem__(
                    k, moves(clients[k], direct, MOVES // 2, lock))) for k in range(4)]
                t0 = time.perf_counter()
                for t in threads:
                    t.start()
                for t in threads:
                    t.join()
                wall = time.perf_counter() - t0
                allm = [x for r in results for x in overhead(r)]
                print("| observable command overhead, 4 arms at once, TLS | %s (%d commands in %.1f s) |"
                      % (ms(allm), len(allm), wall))
                for c in clients:
                    c.close()
            finally:
                for sim, st in arms:
                    st.stop()
                    sim.stop()
        finally:
            direct.close()

if __name__ == "__main__":
    main()
