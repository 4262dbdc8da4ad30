# SPDX-License-Identifier: MIT
"""Many arms: four stations on this host, each with its own emulated controller, found by
discovery (mDNS, _sila._tcp) and driven at once from one client. Each emulator's command log
must hold its own run, and the runs must overlap in time."""
import json
import os
import shutil
import threading
import time

from client import Client, Failure, Station
from conftest import ROOT, SITES, Sim, launcher
from fbrl_station import pb
from fbrl_station.discovery import browse
from fbrl_station.sila import I, S

ARMS = 4
DISCOVERY_S = 20
ML = "MethodLibrary"
P = pb.messages(ML).RunMethod_Parameters.Parameters_Struct


def pinned_client(info):
    """A client of a discovered station: its address and port from the record, the certificate
    it announced (TXT ca0, ca1 ...) pinned."""
    props = {k.decode(): v.decode() for k, v in info.properties.items()}
    pem = "\n".join(props["ca%d" % i] for i in range(len([k for k in props if k.startswith("ca")]))) + "\n"
    return Client(info.port, host=info.parsed_addresses()[0], pem=pem.encode())


def test_four_arms_found_by_discovery_run_a_method_at_once(tmp_path):
    lib = tmp_path / "lib"
    (lib / "methods").mkdir(parents=True)
    for f in ("asps_cell.fbrl", "asps_cell_objects.fbrl"):
        shutil.copy(os.path.join(ROOT, "examples", f), lib)
    shutil.copy(os.path.join(ROOT, "tests", "station", "methods", "station_tests.fbrl"), lib / "methods")
    sims, stations, clients = [], [], []
    try:
        for k in range(ARMS):
            sims.append(Sim(str(tmp_path / ("sim%d" % k))))
        for k in range(ARMS):  # discovery on: each announces itself
            stations.append(Station(launcher(), tmp_path / ("data%d" % k), "--port", sims[k].port,
                                    "--methods", str(lib / "methods"), SITES))
        uuids = [json.load(open(os.path.join(st.data, "station.json")))["uuid"] for st in stations]
        found = {}
        deadline = time.monotonic() + DISCOVERY_S
        while time.monotonic() < deadline and not set(uuids) <= set(found):
            found.update(browse(2))
        assert set(uuids) <= set(found), "discovered %s of %s" % (sorted(set(found) & set(uuids)), uuids)
        for k, u in enumerate(uuids):
            assert found[u].port == stations[k].port
            clients.append(pinned_client(found[u]))
            assert clients[k].get("SiLAService", "ServerUUID").value == u
        # one client, four runs at once
        uuids_run = [c.start(ML, "RunMethod", Method=S("QUICK"), Parameters=[P(Name=S("#ITEMS"), Value=I(2)),
                                                                             P(Name=S("HOLD-DS"), Value=I(10))])
                     for c in clients]
        spans = [None] * ARMS

        def follow(k):
            t0 = time.monotonic()
            infos = list(clients[k].info(ML, "RunMethod", uuids_run[k]))
            spans[k] = (t0, time.monotonic(), infos)

        threads = [threading.Thread(target=follow, args=(k,)) for k in range(ARMS)]
        for t in threads:
            t.start()
        for t in threads:
            t.join(300)
        for k, c in enumerate(clients):
            r = c.result(ML, "RunMethod", uuids_run[k])
            assert r.Outcome.value == "completed", (k, r)
            log = sims[k].log()
            assert "HOME" in log and log.count("OUTPUT 1") == 2 and log.count("OUTPUT -1") == 2, (k, log)
        assert max(s[0] for s in spans) < min(s[1] for s in spans), "the four runs did not overlap"
    except Failure as f:
        raise AssertionError(str(f))
    finally:
        for c in clients:
            c.close()
        for st in stations:
            st.stop()
        for s in sims:
            s.stop()
