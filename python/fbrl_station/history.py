# SPDX-License-Identifier: MIT
"""The station's history of method runs (docs/page.md): one JSON line per finished run in the
data folder's runs.jsonl, whoever started it (a SiLA client, a page): when, the method, its
version (its files' hash, fbrl.method_version) and its values, who, the outcome and each
sample's, and the run's events as its log."""
import json
import logging
import threading
import time

log = logging.getLogger("fbrl-station")

HISTORY_FILE = "runs.jsonl"
SHOWN = 200  # the newest runs a page lists


def _progress(p):
    return {"event": p.Event.value, "step": p.Step.value, "step_name": p.StepName.value,
            "sample": p.Sample.value, "samples": p.SampleCount.value, "message": p.Message.value}


class History:
    def __init__(self, data):
        self.path = data.file(HISTORY_FILE)
        self._lock = threading.Lock()

    def record(self, e, started):
        """Execution e of RunMethod has finished (any thread): append its record."""
        rs = e.run_state
        r = {"uuid": e.uuid, "start": started, "end": time.time(), "method": rs.method if rs else "",
             "values": rs.values if rs else [], "by": rs.who if rs else "", "version": rs.version if rs else None,
             "events": [_progress(x.Progress) for x in e.intermediates]}
        if e.result is not None:
            r.update(outcome=e.result.Outcome.value, summary=e.result.Summary.value,
                     samples=[{"sample": s.Sample.value, "outcome": s.Outcome.value, "reason": s.Reason.value}
                              for s in e.result.Samples])
        else:
            r.update(outcome="error", summary=str(e.error), samples=[])
        line = json.dumps(r) + "\n"
        with self._lock:
            try:
                with open(self.path, "a", encoding="utf-8") as f:
                    f.write(line)
            except OSError as err:  # the run's own result stands; the history says it lost one
                log.warning("%s: the run of %s was not recorded: %s", self.path, r["method"], err)

    def runs(self):
        """The newest runs first; a line that is not a record is named in the log and left out."""
        out = []
        with self._lock:
            try:
                with open(self.path, encoding="utf-8") as f:
                    lines = f.readlines()
            except FileNotFoundError:
                return []
        for n, line in enumerate(lines, 1):
            try:
                out.append(json.loads(line))
            except ValueError:
                log.warning("%s:%d: not a run record: left out", self.path, n)
        return out[::-1][:SHOWN]
