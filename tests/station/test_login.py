# SPDX-License-Identifier: MIT
"""fbrl-station's page beyond loopback (--http on this machine's own address, --lab): HTTPS and
WSS with the station's certificate, pinned as the SiLA tests pin it, and the lab's users signing
in. The lab is made by fbrl-users as an administrator makes it; the truth of the count of wrong
passwords and of a lock is the program's own list of the users file, of a run fbrlsim's log."""
import http.client
import json
import os
import re
import ssl
import subprocess
import threading
import time
import urllib.parse

import pytest
from cryptography import x509
from cryptography.hazmat.primitives import hashes, serialization

from conftest import ROOT, MethodLab, launcher, wait_for

websocket = pytest.importorskip("websocket", reason="python3-websocket is the WebSocket client")

PASSWORDS = {"admin": "admin-pass-1", "ann": "ann-pass-12", "bob": "bob-pass-123", "dev": "dev-pass-1234",
             "rev": "rev-pass-1234"}


def own_address():
    """An address of this machine beyond loopback (hostname -I's first IPv4 one)."""
    out = subprocess.run(["hostname", "-I"], capture_output=True, text=True).stdout.split()
    for a in out:
        if "." in a and not a.startswith("127."):
            return a
    pytest.skip("this machine has no IPv4 address beyond loopback to bind the page to")


def fbrl_users(lab, *args, stdin=""):
    path = os.environ.get("FBRL_USERS") or os.path.join(ROOT, "build", "apps", "fbrl-users")
    r = subprocess.run([path, "--lab", lab] + list(args), input=stdin, capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, (args, r.stdout, r.stderr)
    return r.stdout


def fbrl_audit(lab, *args, stdin=""):
    path = os.environ.get("FBRL_AUDIT") or os.path.join(ROOT, "build", "apps", "fbrl-audit")
    r = subprocess.run([path, "--lab", lab] + list(args), input=stdin, capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, (args, r.stdout, r.stderr)
    return r.stdout


def listed(lab, name):
    """fbrl-users list's line of a user: [name, role, state, wrong passwords, ...]."""
    return next(l.split() for l in fbrl_users(lab, "list").splitlines() if l.split()[:1] == [name])


def make_lab(directory):
    lab = os.path.join(directory, "lab")
    os.makedirs(lab)
    fbrl_users(lab, "setup", "admin", stdin=PASSWORDS["admin"] + "\n")
    for name, role in (("ann", "operator"), ("bob", "operator"), ("dev", "developer"), ("rev", "reviewer")):
        fbrl_users(lab, "--as", "admin", "add", name, role, stdin="%s\n%s\n" % (PASSWORDS["admin"], PASSWORDS[name]))
    return lab


class Page(MethodLab):
    """fbrlsim, the lab, a station serving the page on this machine's address with --lab."""

    def __init__(self, directory):
        self.host = own_address()
        self.labdir = make_lab(directory)
        super().__init__(directory, "--http", "%s:0" % self.host, "--lab", self.labdir, sample_prep=False)
        try:
            wait_for(lambda: any("the page on https://" in l for l in self.station.lines), what="the page's address")
            line = next(l for l in self.station.lines if "the page on https://" in l)
            self.port = int(re.search(r"https://[^/]+:(\d+)/", line).group(1))
            self.cert = self.station.cert
        except BaseException:
            super().stop()
            raise

    def origin(self):
        return "https://%s:%d" % (self.host, self.port)

    def tls(self):
        """The station's certificate is the only one trusted (the pin), checked against the address."""
        return ssl.create_default_context(cafile=self.cert)

    def request(self, method, path, body=None, cookie=None, origin=True):
        conn = http.client.HTTPSConnection(self.host, self.port, context=self.tls(), timeout=60)
        headers = {"Origin": self.origin()} if origin else {}
        if cookie:
            headers["Cookie"] = cookie
        if body is not None:
            body = urllib.parse.urlencode(body)
            headers["Content-Type"] = "application/x-www-form-urlencoded"
        try:
            conn.request(method, path, body=body, headers=headers)
            r = conn.getresponse()
            return r.status, r.getheader("Location"), r.getheader("Set-Cookie"), r.read().decode(), \
                conn.sock.getpeercert(binary_form=True)
        finally:
            conn.close()

    def sign_in(self, name, password=None):
        """(status, cookie or None, the page's text)."""
        status, where, cookie, text, _ = self.request("POST", "/login", {"name": name,
                                                                         "password": password or PASSWORDS[name]})
        return status, cookie, text

    def ws(self, cookie=None, origin=None):
        ws = websocket.create_connection("wss://%s:%d/ws" % (self.host, self.port), timeout=60,
                                         sslopt={"ca_certs": self.cert}, origin=origin or self.origin(),
                                         header=["Cookie: " + cookie.split(";")[0]] if cookie else [])
        return ws


def receive(ws, kind, seconds=60):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        m = json.loads(ws.recv())
        if m["t"] in kind:
            return m
    pytest.fail("no %s message in %d s" % (kind, seconds))


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    p = Page(str(tmp_path_factory.mktemp("login")))
    yield p
    p.stop()


def refused(*args, env=None):
    r = subprocess.run([launcher(), "--no-discovery", "--sila", "off"] + list(args), capture_output=True, text=True,
                       timeout=60, env=env)
    return r.returncode, r.stderr


def test_beyond_loopback_needs_the_lab_and_tls(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "FBRL_LAB"}
    host = own_address()
    rc, err = refused("--http", "%s:0" % host, env=env)
    assert rc == 2 and "needs the lab's users to sign in: give --lab DIR" in err, err
    rc, err = refused("--http", "0.0.0.0:0", env=env)
    assert rc == 2 and "--lab" in err, err
    rc, err = refused("--http", "%s:0" % host, "--lab", str(tmp_path), "--insecure", env=env)
    assert rc == 2 and "served over TLS" in err and "--insecure turns TLS off" in err, err
    # a lab without users: refused before the controller is touched
    rc, err = refused("--http", "%s:0" % host, "--lab", str(tmp_path), "--data", str(tmp_path / "data"), env=env)
    assert rc == 3 and "no users file: make the first administrator with 'fbrl-users" in err, err


def test_plain_http_is_not_served(page):
    conn = http.client.HTTPConnection(page.host, page.port, timeout=30)
    with pytest.raises((http.client.HTTPException, OSError)):
        conn.request("GET", "/")
        conn.getresponse().read()
    conn.close()


def test_the_page_needs_a_sign_in_over_tls_with_the_stations_certificate(page):
    status, where, _, _, peer = page.request("GET", "/")
    assert (status, where) == (303, "/login")
    with open(page.cert, "rb") as f:
        assert peer == ssl.PEM_cert_to_DER_cert(f.read().decode())  # the station's own, the SiLA side's
    for path in ("/api/scene", "/api/methods", "/api/history", "/page/page.js"):
        assert page.request("GET", path)[0] == 401, path
    status, _, _, text, _ = page.request("GET", "/login")
    assert status == 200 and 'type="password"' in text
    with pytest.raises(websocket.WebSocketBadStatusException) as e:
        page.ws()
    assert e.value.status_code == 401


def test_a_wrong_password_is_refused_and_counted(page):
    status, cookie, text = page.sign_in("ann", "not-anns-password")
    assert status == 401 and cookie is None and "name or password not accepted" in text
    assert listed(page.labdir, "ann")[2:4] == ["active", "1"]
    status, cookie, text = page.sign_in("nobody", "whatever-it-is")
    assert status == 401 and cookie is None and "name or password not accepted" in text


def test_five_wrong_passwords_lock_the_account(page):
    for i in range(4):
        assert page.sign_in("bob", "wrong-%d-password" % i)[0] == 401
    assert listed(page.labdir, "bob")[2:4] == ["active", "4"]
    status, cookie, text = page.sign_in("bob", "wrong-4-password")
    assert status == 401 and cookie is None and "wrong password: bob is now locked until" in text, text
    assert listed(page.labdir, "bob")[2:4] == ["locked", "5"]
    status, cookie, text = page.sign_in("bob")  # the right one: not even tried while locked
    assert status == 401 and cookie is None and "bob is locked until" in text, text


def test_a_signed_in_operator_gets_the_page_and_the_websocket(page):
    status, cookie, _ = page.sign_in("ann")
    assert status == 303 and cookie is not None
    flags = [f.strip().lower() for f in cookie.split(";")]
    assert "secure" in flags and "httponly" in flags and "samesite=strict" in flags, cookie
    assert listed(page.labdir, "ann")[2:4] == ["active", "0"]  # a right password clears the count
    status, _, _, text, _ = page.request("GET", "/", cookie=cookie.split(";")[0])
    assert status == 200 and "/three/build/three.min.js" in text
    assert page.request("GET", "/api/scene", cookie=cookie.split(";")[0])[0] == 200
    ws = page.ws(cookie)
    try:
        hello = receive(ws, ("hello",))
        assert hello["you"].startswith("ann (page ")
        assert hello["user"] == {"name": "ann", "role": "operator"}
        receive(ws, ("pose",))
    finally:
        ws.close()
    with pytest.raises(websocket.WebSocketBadStatusException) as e:  # another site's page, with ann's cookie
        page.ws(cookie, origin="https://elsewhere.example")
    assert e.value.status_code == 403
    with pytest.raises(websocket.WebSocketBadStatusException) as e:  # a made-up session
        page.ws("fbrl_session=" + "A" * 43)
    assert e.value.status_code == 401


def run_from_page(page, cookie, method, params):
    """Take control and run method from a page signed in with cookie; its end message."""
    ws = page.ws(cookie)
    try:
        receive(ws, ("hello",))
        ws.send(json.dumps({"op": "control"}))
        assert receive(ws, ("control", "error"))["t"] == "control"
        ws.send(json.dumps({"op": "run", "method": method, "params": params}))
        assert receive(ws, ("started", "error"))["t"] == "started"
        return receive(ws, ("end",), seconds=120)
    finally:
        ws.close()


MOTION = ("OUTPUT", "MOVE", "APPRO", "DEPART", "JOINT", "SPEED")


def test_a_sila_client_in_the_lab_counts_as_an_operator(page):
    """A SiLA client is no user of the lab: a Draft is refused it as an operator's run would be
    (before the next test releases the tests' methods)."""
    from client import Failure
    from fbrl_station.sila import S
    before = len(page.sim.log())
    uuid = page.client.start("MethodLibrary", "RunMethod", Method=S("CROSS"), Parameters=[])
    list(page.client.info("MethodLibrary", "RunMethod", uuid))
    with pytest.raises(Failure) as e:
        page.client.result("MethodLibrary", "RunMethod", uuid)
    assert e.value.identifier == "MethodNotReleased", e.value.message
    assert re.search(r", operator: CROSS \(station_tests.fbrl\): \w+: refused: version \w+ is Draft", e.value.message), e.value.message
    assert not [l for l in page.sim.log()[before:] if l.startswith(MOTION)]


def test_a_sila_clients_motions_are_in_the_lab_audit_trail(page):
    """Outside a run, each SiLA motion and teach is recorded before it runs, as fbrlmon records a
    line typed at its prompt (the FBRL text, "action" forth, by "-": a SiLA client is no lab
    user); while the chain cannot be written, the command is refused and nothing moves."""
    import fbrl
    from client import Failure
    from fbrl_station import pb
    from fbrl_station.sila import I, R, S
    am = pb.messages("ArmController")
    chain = os.path.join(page.labdir, "audit.jsonl")
    start = sum(1 for _ in open(chain))
    before = len(page.sim.log())
    result, _ = page.client.run("ArmController", "Home")
    assert not isinstance(result, Failure), result
    page.client.call("ArmController", "Grip", Width=am.DataType_Opening(Opening=R(0.5)), Force=I(40))
    page.client.call("ArmController", "TeachPlace", Place=am.DataType_PlaceName(PlaceName=S("AUDITED")))
    ran = page.sim.log()[before:]
    assert any(l.startswith("HOME") for l in ran) and any(l.startswith("GRIP") for l in ran), ran
    recs = [json.loads(line) for line in open(chain)][start:]
    sila = [(x["what"], x["detail"].split(" by ")[0], x["user"]) for x in recs
            if x["type"] == "action" and x["action"] == "forth"]
    assert sila == [("HOME FINISH", "SiLA ArmController.Home", "-"), ("40 5.00000000000000000E-01 GRIP", "SiLA ArmController.Grip", "-"),
                    ("AUDITED ARM-HERE", "SiLA ArmController.TeachPlace", "-")], sila
    assert all(re.match(r"SiLA ArmController\.\w+ by SiLA client ipv[46]:", x["detail"]) for x in recs
               if x["type"] == "action" and x["action"] == "forth"), recs
    assert "intact" in fbrl_audit(page.labdir, "verify", chain)
    # another program holds the chain past the station's wait: refused, nothing sent
    holder = fbrl.AuditTrail(chain).open()
    try:
        before = len(page.sim.log())
        with pytest.raises(Failure) as e:
            page.client.call("ArmController", "Grip", Width=am.DataType_Opening(Opening=R(0.5)), Force=I(40))
    finally:
        holder.close(seal=False)
    assert "Grip not run: the lab's audit trail cannot record it" in e.value.message, e.value.message
    assert not [l for l in page.sim.log()[before:] if l.startswith(MOTION + ("GRIP",))]


def test_an_operator_runs_a_released_method_and_not_a_draft(page):
    """As fbrlmon in a lab (tests/e2e/console_audit.sh): an operator runs only a Released version,
    by the lab's audit trail; a developer may run the Draft only where the lab allows Drafts."""
    quick = os.path.join(page.lib, "station_tests.fbrl")
    _, cookie, _ = page.sign_in("ann")
    before = len(page.sim.log())
    end = run_from_page(page, cookie, "QUICK", {"#ITEMS": 1, "HOLD-DS": 1})
    assert end["outcome"] == "error" and "MethodNotReleased" in end["summary"], end
    assert re.search(r"ann \(.*\), operator: QUICK \(station_tests.fbrl\): QUICK: refused: version \w+ is Draft", end["summary"]), end
    _, dcookie, _ = page.sign_in("dev")
    end = run_from_page(page, dcookie, "QUICK", {"#ITEMS": 1, "HOLD-DS": 1})  # the lab allows no Drafts
    assert re.search(r"dev \(.*\), developer: QUICK \(station_tests.fbrl\): QUICK: refused: .*Draft", end["summary"]), end
    assert not [l for l in page.sim.log()[before:] if l.startswith(MOTION)]  # nothing moved
    fbrl_audit(page.labdir, "method", "submit", quick, "--as", "dev", stdin=PASSWORDS["dev"] + "\n")
    fbrl_audit(page.labdir, "method", "release", quick, "--as", "rev", stdin=PASSWORDS["rev"] + "\n")
    at = len(page.sim.log())
    end = run_from_page(page, cookie, "QUICK", {"#ITEMS": 1, "HOLD-DS": 1})
    assert end["outcome"] == "completed", end
    ran = page.sim.log()[at:]
    assert "OUTPUT 1" in ran  # the pump ran on the controller
    status, _, _, text, _ = page.request("GET", "/api/history", cookie=cookie.split(";")[0])
    assert status == 200 and json.loads(text)[0]["by"].startswith("ann ("), text  # the run's record names her
    # the lab's audit trail, as fbrl-audit (C) reads it: the refusals, the run, every line fbrlsim ran
    chain = os.path.join(page.labdir, "audit.jsonl")
    out = fbrl_audit(page.labdir, "verify", chain)
    assert "intact, sealed" in out, out
    recs = [json.loads(line) for line in open(chain)]
    refused = [(x["user"], x["method"]) for x in recs if x["type"] == "method_refused"]
    assert ("ann", "QUICK") in refused and ("dev", "QUICK") in refused and ("-", "CROSS") in refused, refused
    start = max(i for i, x in enumerate(recs) if x["type"] == "method_run")
    run = recs[start:next(i for i in range(start, len(recs)) if recs[i]["type"] == "seal") + 1]
    assert run[0]["method"] == "QUICK" and run[0]["state"] == "Released" and run[0]["user"] == "ann", run[0]
    assert run[1]["type"] == "header" and run[1]["operator"].startswith("ann ("), run[1]
    commands = []
    for x in run:
        if x["type"] == "command":
            commands += [x["line"]] * x.get("count", 1)
    # every line the run sent, in order; after its end the station reads the arm's place once more
    assert commands == ran[:len(commands)] and set(ran[len(commands):]) <= {"W2"}, (commands, ran)
    summary = next(x for x in run if x["type"] == "summary")
    assert summary["outcome"] == "completed" and all(x["user"] == "ann" for x in run[:-1]), summary
    logins = [(x["name"], x["outcome"]) for x in recs if x["type"] == "login"]
    assert ("ann", "accepted") in logins and ("dev", "accepted") in logins and ("ann", "wrong password") in logins
    status, _, _, report, _ = page.request("GET", "/audit", cookie=cookie.split(";")[0])  # the page's link
    assert status == 200 and "Intact and sealed" in report and "QUICK" in report and ">completed<" in report, report[:2000]
    status, where, _, _, _ = page.request("GET", "/audit")  # signed in only
    assert status in (302, 303, 401) and (status == 401 or where.endswith("/login")), (status, where)


def test_a_run_the_audit_trail_cannot_record_does_not_start(page):
    """Another program holds the lab's audit trail (as fbrlmon does through a console session):
    the station waits for it, then refuses the run; nothing moves, and the chain stays whole."""
    import fbrl
    chain = os.path.join(page.labdir, "audit.jsonl")
    _, cookie, _ = page.sign_in("ann")
    before = len(page.sim.log())
    holder = fbrl.AuditTrail(chain).open()
    try:
        end = run_from_page(page, cookie, "QUICK", {"#ITEMS": 1, "HOLD-DS": 1})
    finally:
        holder.close(seal=False)
    assert end["outcome"] == "error" and "AuditTrailUnavailable" in end["summary"], end
    assert "another program is writing the audit trail" in end["summary"], end
    assert not [l for l in page.sim.log()[before:] if l.startswith(MOTION)]
    assert "intact" in fbrl_audit(page.labdir, "verify", chain)


def test_a_role_without_the_right_to_run_is_refused(page):
    _, cookie, _ = page.sign_in("admin")  # an administrator "signs nothing else, runs nothing"
    ws = page.ws(cookie)
    try:
        assert receive(ws, ("hello",))["you"].startswith("admin (")
        before = len(page.sim.log())
        for op in ({"op": "control"}, {"op": "run", "method": "QUICK", "params": {}}, {"op": "abort"}):
            ws.send(json.dumps(op))
            m = receive(ws, ("error", "control", "started"))
            assert m["t"] == "error" and "admin (administrator) may not %s" % op["op"] in m["message"], m
        receive(ws, ("pose",))  # viewing it is allowed
    finally:
        ws.close()
    assert not [l for l in page.sim.log()[before:] if l.startswith(("OUTPUT", "MOVE", "APPRO", "DEPART"))]


def test_an_idle_session_is_signed_out(page):
    fbrl_users(page.labdir, "--as", "admin", "set", "idle_s", "3", stdin=PASSWORDS["admin"] + "\n")
    try:
        _, cookie, _ = page.sign_in("ann")  # the sign-in reads the lab's setting
        ws = page.ws(cookie)
        try:
            receive(ws, ("hello",))
            m = receive(ws, ("signedout",), seconds=20)
            assert m["message"] == "signed out: idle for 3 s"
            # recorded before the page was told (and the chain free again for fbrl-users)
            recs = [json.loads(line) for line in open(os.path.join(page.labdir, "audit.jsonl"))]
            out = [x for x in recs if x["type"] == "action" and x.get("action") == "logout"]
            assert out and (out[-1]["what"], out[-1]["detail"]) == ("ann", "idle for 3 s"), out[-3:]
        finally:
            ws.close()
        assert page.request("GET", "/api/scene", cookie=cookie.split(";")[0])[0] == 401
    finally:
        fbrl_users(page.labdir, "--as", "admin", "set", "idle_s", "600", stdin=PASSWORDS["admin"] + "\n")
        page.sign_in("ann")


def test_fbrl_users_waits_while_another_program_writes_the_chain(page):
    """The station holds the chain for each record (and a run for its length): fbrl-users,
    typed meanwhile, waits for it and says so rather than failing at once."""
    import fbrl
    holder = fbrl.AuditTrail(os.path.join(page.labdir, "audit.jsonl")).open()
    threading.Timer(1.5, holder.close, kwargs={"seal": False}).start()
    path = os.environ.get("FBRL_USERS") or os.path.join(ROOT, "build", "apps", "fbrl-users")
    r = subprocess.run([path, "--lab", page.labdir, "--as", "admin", "set", "idle_s", "600"],
                       input=PASSWORDS["admin"] + "\n", capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and "another program is writing the audit trail; waiting up to 10 s" in r.stderr, r


def test_signing_out_ends_the_session(page):
    _, cookie, _ = page.sign_in("ann")
    cookie = cookie.split(";")[0]
    assert page.request("GET", "/api/scene", cookie=cookie)[0] == 200
    status, where, _, _, _ = page.request("POST", "/logout", {}, cookie=cookie)
    assert (status, where) == (303, "/login")
    assert page.request("GET", "/api/scene", cookie=cookie)[0] == 401


def spki_pin(cert_path):
    """chromium's pin of a certificate's key: base64 of the SHA-256 of its SubjectPublicKeyInfo."""
    import base64
    with open(cert_path, "rb") as f:
        key = x509.load_pem_x509_certificate(f.read()).public_key()
    h = hashes.Hash(hashes.SHA256())
    h.update(key.public_bytes(serialization.Encoding.DER, serialization.PublicFormat.SubjectPublicKeyInfo))
    return base64.b64encode(h.finalize()).decode()


def test_in_a_browser_the_sign_in_leads_to_the_page(page):
    cdp = pytest.importorskip("cdp", reason="python3-websocket drives chromium")
    if cdp.chromium() is None:
        pytest.skip("no chromium (Debian: chromium)")
    b = cdp.Browser(flags=["--ignore-certificate-errors-spki-list=" + spki_pin(page.cert)])  # the station's key only

    def until(js, what, seconds=60):
        """b.wait_for across a navigation (an evaluation the navigation cut off is asked again)."""
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            try:
                if b.eval(js):
                    return
            except RuntimeError:
                pass
            time.sleep(0.1)
        pytest.fail("timed out waiting for " + what)

    try:
        b.goto(page.origin() + "/")
        until("location.pathname === '/login' && !!document.querySelector('input[name=password]')", "the sign-in")
        b.eval("document.querySelector('input[name=name]').value = 'ann'; "
               "document.querySelector('input[name=password]').value = %s; "
               "setTimeout(() => document.querySelector('form').submit(), 0); true" % json.dumps(PASSWORDS["ann"]))
        until("window.fbrlPage && window.fbrlPage.connected === true", "the page over WSS")
        assert b.eval("location.protocol") == "https:"
        until("document.getElementById('user').textContent === 'ann (operator)'", "the user named")
        assert b.eval("document.cookie") == ""  # HttpOnly: the page's script cannot read the token
        b.eval("setTimeout(() => document.querySelector('#signed-in button').click(), 0); true")
        until("location.pathname === '/login'", "the sign-in after signing out")
    finally:
        b.close()
