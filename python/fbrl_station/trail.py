# SPDX-License-Identifier: MIT
"""With --lab: the station's records in the lab's audit trail (docs/compliance.md), the one chain
fbrlmon, fbrl-users and fbrl-audit keep. In fbrlmon's words: the page's sign-ins ("login") and
sign-outs ("action" logout), each SiLA client's motion and teach outside a run (the FBRL text
it runs, "action" forth, as fbrlmon records a line typed at its prompt), and every method run:
its "method_run" record (version, state, role), then the library's run log (fbrl.RunLog: the
header, each step, every line the controller ran, pauses, resumes, aborts and answers with who
asked, each sample, the summary), sealed at its end. Outside a run the chain is opened for each
record and closed after it, so the lab's other programs write it in between; while one of them
holds it, a record waits up to fbrl.audit.BUSY_WAIT_S and is then refused: a sign-in or a run
that cannot be recorded does not happen. During a run the run holds it, and other records (a
sign-in) join it."""
import os
import subprocess
import tempfile
import threading
import time

import fbrl
from fbrl.audit import BUSY_WAIT_S

from . import login, programs

CHAIN_FILE = "audit.jsonl"  # the lab folder's audit trail (apps/lab.h LAB_CHAIN_FILE)


class LabTrail:
    def __init__(self, lab, program):
        self.lab = lab
        self.path = os.path.join(lab, CHAIN_FILE)
        self.program = program  # "fbrl-station VERSION", the run log header's program
        self._lock = threading.Lock()
        self._run = None  # the running method's open AuditTrail

    def _open(self):
        """The chain, verified against the users' keys, opened for this station's writer."""
        users = fbrl.Users(os.path.join(self.lab, login.USERS_FILE))
        return fbrl.AuditTrail(self.path, users).open(BUSY_WAIT_S)

    def record(self, type, user, **fields):
        """One record by user (a lab user's name; None or any other text: "-", as the library
        takes it); fbrl.Error when it cannot be written."""
        with self._lock:
            if self._run is not None:
                self._run.record(type, user, **fields)  # sealed with the run
                return
            trail = self._open()
            try:
                trail.record(type, user, **fields)
            finally:
                trail.close()

    def login(self, name, outcome, user):
        """A page's sign-in attempt, as fbrlmon records one (apps/lab.c): the name typed, the
        outcome, the count of wrong passwords and the lock (user: the users file's entry after
        the attempt, None when there is no such user)."""
        locked = user and user["locked_until"] > time.time() * 1000
        self.record("login", name, purpose="page", name=name, outcome=outcome,
                    failures=user["failures"] if user and outcome != "accepted" else None,
                    locked_until=time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime(user["locked_until"] / 1000))
                    if locked else None)

    def report(self):
        """The lab's review report (fbrl-audit report: every run, action and signature, the
        chain verified with the users' keys) as HTML, and whether the chain is intact. Blocks."""
        with tempfile.TemporaryDirectory(prefix="fbrl-audit-report-") as d:
            out = os.path.join(d, "report.html")
            r = subprocess.run([programs.find("fbrl-audit", "FBRL_AUDIT", "fbrl-audit was not found for the report"), "report", self.path, "-o", out], capture_output=True, text=True,
                               timeout=600, env=dict(os.environ, FBRL_LAB=self.lab))
            if not os.path.exists(out):
                raise OSError("fbrl-audit report: %s" % (r.stderr.strip() or "exit status %d" % r.returncode))
            with open(out, encoding="utf-8") as f:
                return f.read(), r.returncode == 0

    def sila(self, text, command, by):
        """A SiLA client's motion or teach, as fbrlmon records a line typed at its prompt: the
        FBRL text (action "forth"), which command of whom in detail. No lab user: "-"."""
        self.record("action", None, action="forth", what=text, detail="SiLA %s by %s" % (command, by))

    def logout(self, name, why):
        self.record("action", name, action="logout", what=name, detail=why)

    def run(self, c, rs, m, allow):
        """Open the chain for a run (the owner thread): its method_run record and its run log's
        header, then every event of the run and line the controller runs. end() on the
        recorder seals and closes it."""
        return RunRecorder(self, c, rs, m, allow)


class RunRecorder:
    def __init__(self, lab, c, rs, m, allow):
        self._lab = lab
        self._run, self._link = c.run, c.engine.link
        with lab._lock:
            trail = lab._open()
            try:
                trail.record("method_run", rs.user, method=m["name"], version=rs.version, state=rs.state,
                             drafts_allowed=int(bool(allow)), role=rs.role or "operator", by=rs.who)
                trail.set_user(rs.user)
                units = {p["name"]: p["unit"] for p in m["params"]}
                self.log = fbrl.RunLog(trail, m["name"], source=rs.path, operator=rs.who,
                                       started=time.strftime("%Y-%m-%dT%H:%M:%S%z"), program=lab.program,
                                       params=[(n, v, units.get(n, "")) for n, v in rs.values])
            except BaseException:
                trail.close()
                raise
            lab._run = self.trail = trail
        self._command = self.log.command
        self._run.record(self.log)
        if self._link is not None:
            self._link.on_exec(self._command)

    def end(self):
        """The run is over (its end event wrote the summary): sealed and closed."""
        self._run.unrecord(self.log)
        if self._link is not None:
            self._link.remove_exec(self._command)
        with self._lab._lock:
            self._lab._run = None
            self.trail.close()
