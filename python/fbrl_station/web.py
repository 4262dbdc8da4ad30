# SPDX-License-Identifier: MIT
"""fbrl-station's page in the browser (--http, docs/page.md): one page, its three.js from
Debian's libjs-three, the scene (the cell, the places, the arm's chain) as JSON and a
WebSocket carrying the arm's readings, the runs' progress and the page's requests. It runs in
its own thread with its own asyncio loop; like the SiLA side it hands every job to the owner
thread and reads only what the owner publishes. With --lab the lab's users sign in
(login.py) and it serves HTTPS and WSS with the station's certificate."""
import asyncio
import html
import json
import logging
import os
import ssl
import subprocess
import tempfile
import threading
import time

from aiohttp import web, WSMsgType

import fbrl

from . import dryrun, login, tls
from .cell import SITES_FBRL
from .controller import RobotFailure
from .history import _progress as progress

log = logging.getLogger("fbrl-station")

PAGE_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "page")
# Debian's libjs-three (the .deb depends on it); FBRL_THREE_DIR for another copy of the same tree
THREE_DIR = os.environ.get("FBRL_THREE_DIR") or "/usr/share/javascript/three"
THREE_FILES = ("build/three.min.js", "examples/js/controls/OrbitControls.js")
WATCH_S = 0.05  # how often the watcher looks at what the owner published (the delay it adds)
RUN_FQI_SUFFIX = "/MethodLibrary/v1/Command/RunMethod"
START_S = 10
IDLE_CHECK_S = 1.0  # how often idle sessions are looked for (the lateness of an idle sign-out)
# what a page's WebSocket request needs: any signed-in user may view and plan (dryrun)
RIGHTS = {"control": "run", "release": "run", "run": "run", "pause": "run", "resume": "run", "abort": "run",
          "answer": "run"}


def scene(c, cell, arm_name):
    """On the owner thread: the cell as .CELL lists it, every site's positions (taught
    places, each position of a rack or matrix) and the arm model's name."""
    table, tool, obstacles = None, None, []
    for line in c.eval(".CELL").splitlines():
        w = line.replace(",", "").split()
        if line.startswith("cell:"):  # cell: guard on, table Z|none, tool length L radius R in, N obstacles
            table = None if w[w.index("table") + 1] == "none" else float(w[w.index("table") + 1])
            tool = {"length": float(w[w.index("length") + 1]), "radius": float(w[w.index("radius") + 1])}
        elif len(w) >= 10 and w[1] == "cylinder":  # NAME cylinder x X y Y z LO..HI radius R [on CAL]
            x, y, r = float(w[3]), float(w[5]), float(w[9])
            lo, hi = (float(v) for v in w[7].split(".."))
            obstacles.append({"name": w[0], "kind": "cylinder", "c": [x, y], "r": r, "lo": [x - r, y - r, lo],
                              "hi": [x + r, y + r, hi], "block": w[11] if len(w) > 11 else None})
        elif len(w) >= 9 and w[1] in ("box", "keep-out"):  # NAME box|keep-out X Y Z .. X Y Z [on CAL]
            obstacles.append({"name": w[0], "kind": "keepout" if w[1] == "keep-out" else "box",
                              "lo": [float(x) for x in w[2:5]], "hi": [float(x) for x in w[6:9]],
                              "block": w[10] if len(w) > 10 else None})
    for o in obstacles:  # a block's obstacles where its calibration puts them now, as the guard does
        o["placed"] = placement(c, o["block"]) if o["block"] else None
    places = []
    for s in cell.sites:
        for i in range(s.count):
            try:
                _, xyz = c.eval("%d %d SITE-LOC DUP GETX DUP GETY GETZ" % (i, s.index), floats=True)
            except RobotFailure:
                continue  # a site whose word fails now (a matrix not mapped yet): not drawn
            places.append({"site": s.name, "index": i, "count": s.count, "at": xyz[:3],
                           "taught": cell.is_taught(s.name)})
    return {"arm": arm_name, "table": table, "tool": tool, "obstacles": obstacles, "places": places}


def placement(c, name):
    """Where the guard puts a block's obstacles (src/words/robot_cell.c place_blocks): before
    each motion it looks up the word of the block's name and, when that is a calibration
    structure (CREATE-CAL-STRU), carries the block by it: p = r p_taught + t. The same 3x4
    [r | t] read here with CAL-STRU@, row by row; None when the word is not a calibration
    structure (the guard then leaves the block where it was taught). HELP tells the word's kind
    without running it (a block named after a word that moves the arm is not run here)."""
    try:
        if "( -- cal-stru )" not in c.eval("HELP %s" % name):
            return None
        _, v = c.eval(" ".join("%s %d CAL-STRU@" % (name, i) for i in range(1, 13)), floats=True)
    except RobotFailure:
        return None
    return {"r": [v[0:3], v[4:7], v[8:11]], "t": [v[3], v[7], v[11]]}


class Page:
    def __init__(self, station, host, port, sign_in=None):
        self.st = station
        self.host, self.port = host, port
        self.sign_in = sign_in  # login.SignIn with --lab (then TLS too), None: loopback without sign-in
        self.sessions = {}  # ws -> its session's token (signed in)
        self.arm = fbrl.Arm(station.opts.sim_model or "a255")
        self.scene = None
        self.clients = {}  # ws -> its name
        self.controller = None  # the ws that controls runs from the page, None: none
        self.runs = {}  # uuid -> [intermediates sent, end sent]
        self.last = {}  # the latest message of each kind, for a page that comes later
        self.run_log = []  # the current (or last) run's messages, likewise
        self.loop = None
        self.watcher = None  # the thread that sends the owner's news, once the page is served
        self._stop = threading.Event()
        self._ready = threading.Event()
        self._error = None
        self._n = 0

    # ---------------------------------------------------------------- life
    def start(self):
        self.scene = self.st.owner.call(lambda c: scene(c, self.st.cell, self.arm.name))
        self.thread = threading.Thread(target=self._serve, name="fbrl-page", daemon=True)
        self.thread.start()
        if not self._ready.wait(START_S) or self._error is not None:
            raise OSError("cannot serve the page on %s:%d: %s" % (self.host, self.port, self._error or "timed out"))
        self.st.owner.watch("position", +1)  # the page shows the arm: read it once a second while idle
        self.watcher = threading.Thread(target=self._watch, name="fbrl-page-watch", daemon=True)
        self.watcher.start()

    def stop(self):
        self._stop.set()
        if self.watcher is None:  # it never served (start failed): its loop has ended already
            return
        self.loop.call_soon_threadsafe(self._quit.set)
        self.thread.join(START_S)
        self.watcher.join(START_S)
        self.st.owner.watch("position", -1)

    def _serve(self):
        self.loop = asyncio.new_event_loop()
        asyncio.set_event_loop(self.loop)
        try:
            self.loop.run_until_complete(self._main())
        except Exception as e:  # told to start(), which reports it
            self._error = e
            self._ready.set()
        finally:
            self.loop.close()

    async def _main(self):
        self._quit = asyncio.Event()
        app = web.Application(middlewares=[self._same_origin, self._signed_in])
        app.router.add_get("/", self._index)
        if self.sign_in is not None:
            app.router.add_get("/login", self._login_page)
            app.router.add_post("/login", self._login)
            app.router.add_post("/logout", self._logout)
        app.router.add_get("/page/{name}", self._page_file)
        app.router.add_get("/three/{name:.+}", self._three)
        app.router.add_get("/api/scene", self._scene)
        app.router.add_get("/api/methods", self._methods)
        app.router.add_get("/api/history", self._history)
        app.router.add_get("/history/{uuid}", self._run_log)
        if self.st.trail is not None:
            app.router.add_get("/audit", self._audit_report)
        app.router.add_get("/ws", self._ws)
        runner = web.AppRunner(app, access_log=None)
        await runner.setup()
        site = web.TCPSite(runner, self.host, self.port, ssl_context=self._tls())
        await site.start()
        self.port = site._server.sockets[0].getsockname()[1]
        self._ready.set()
        idle = asyncio.ensure_future(self._sign_out_idle()) if self.sign_in is not None else None
        await self._quit.wait()
        if idle is not None:
            idle.cancel()
        for ws in list(self.clients):
            await ws.close()
        await runner.cleanup()

    def _tls(self):
        """With --lab: the station's own key and certificate (the SiLA side's, in --data)."""
        if self.sign_in is None:
            return None
        self.st.tls_identity()  # made or kept, covering this address
        ctx = ssl.create_default_context(ssl.Purpose.CLIENT_AUTH)
        ctx.minimum_version = ssl.TLSVersion.TLSv1_2
        ctx.load_cert_chain(self.st.data.file(tls.CERT_FILE), self.st.data.file(tls.KEY_FILE))
        return ctx

    # ---------------------------------------------------------------- who may ask
    def _hosts(self):
        """The Host headers a request to this page carries: its address by number or, on
        loopback, as localhost; with TLS the names its certificate covers. Another name is a
        DNS rebinding (a web site whose name now points here)."""
        names = {"localhost", "[::1]" if ":" in self.host else "127.0.0.1",
                 "[%s]" % self.host if ":" in self.host else self.host}
        if self.sign_in is not None:
            dns, ips = tls.names_for(self.host)
            names |= set(dns) | {"[%s]" % a if ":" in a else a for a in ips}
        return {"%s:%d" % (n, self.port) for n in names}

    def _scheme(self):
        return "https" if self.sign_in is not None else "http"

    @web.middleware
    async def _same_origin(self, request, handler):
        """Only the page itself: a request must name this host, and a WebSocket must come from a
        page this station served (browsers let any web site open a WebSocket to 127.0.0.1)."""
        if request.host not in self._hosts():
            raise web.HTTPForbidden(text="fbrl-station: not this station's address: %s\n" % request.host)
        origin = request.headers.get("Origin")
        if request.path == "/ws" and origin != "%s://%s" % (self._scheme(), request.host):
            raise web.HTTPForbidden(text="fbrl-station: a WebSocket from another site (%s)\n" % origin)
        if request.method == "POST" and origin is not None and origin != "%s://%s" % (self._scheme(), request.host):
            raise web.HTTPForbidden(text="fbrl-station: a form from another site (%s)\n" % origin)
        return await handler(request)

    # ---------------------------------------------------------------- signing in (--lab)
    @web.middleware
    async def _signed_in(self, request, handler):
        """With --lab everything but the sign-in needs a session: the page itself goes to the
        sign-in, the rest is refused (401)."""
        if self.sign_in is None or request.path == "/login":
            return await handler(request)
        # the history is fetched when a run ends, not by the user: it does not keep a session alive
        s = self.sign_in.session(request.cookies.get(login.COOKIE), touch=request.path != "/api/history")
        if s is None:
            if request.path == "/":
                raise web.HTTPSeeOther("/login")
            raise web.HTTPUnauthorized(text="fbrl-station: sign in first (/login)\n")
        request["session"] = s
        return await handler(request)

    def _login_form(self, message="", status=200):
        with open(os.path.join(PAGE_DIR, "login.html"), encoding="utf-8") as f:
            text = f.read().replace("MESSAGE", html.escape(message))
        return web.Response(text=text, content_type="text/html", status=status,
                            headers={"Cache-Control": "no-store"})

    async def _login_page(self, request):
        return self._login_form()

    async def _login(self, request):
        form = await request.post()
        name, password = form.get("name", ""), form.get("password", "")
        try:  # Argon2id takes its time: not on the loop
            user = await asyncio.get_running_loop().run_in_executor(None, self.sign_in.check, name, password)
        except login.Refused as e:
            log.warning("the page: sign-in of %r from %s refused: %s", name, request.remote, e)
            return self._login_form(str(e), status=401)
        except (fbrl.Error, login.LabError) as e:
            log.error("the page: sign-in of %r: %s", name, e)
            return self._login_form("the station cannot check it: %s" % e, status=500)
        log.info("the page: %s signed in from %s", name, request.remote)
        response = web.HTTPSeeOther("/")
        response.set_cookie(login.COOKIE, self.sign_in.open(user), secure=True, httponly=True, samesite="Strict", path="/")
        raise response

    async def _logout(self, request):
        token = request.cookies.get(login.COOKIE)
        s = self.sign_in.sign_out(token)
        if s is not None:
            await asyncio.get_running_loop().run_in_executor(None, self.sign_in.record_sign_out, s.name, "signed out")
        await self._close_sessions({token}, "signed out")
        response = web.HTTPSeeOther("/login")
        response.del_cookie(login.COOKIE, path="/")
        raise response

    async def _sign_out_idle(self):
        while True:
            await asyncio.sleep(IDLE_CHECK_S)
            gone = self.sign_in.expired()
            if gone:
                why = "idle for %d s" % self.sign_in.idle_s
                for _, s in gone:  # recorded before the page is told, as /logout does
                    await asyncio.get_running_loop().run_in_executor(None, self.sign_in.record_sign_out, s.name, why)
                await self._close_sessions({t for t, _ in gone}, "signed out: " + why)

    async def _close_sessions(self, tokens, why):
        for ws, token in list(self.sessions.items()):
            if token in tokens:
                try:
                    await ws.send_json({"t": "signedout", "message": why})
                except (ConnectionError, RuntimeError):
                    pass
                await ws.close()

    # ---------------------------------------------------------------- files and JSON
    async def _index(self, request):
        return web.FileResponse(os.path.join(PAGE_DIR, "index.html"))

    async def _page_file(self, request):
        name = request.match_info["name"]
        if name not in os.listdir(PAGE_DIR):
            raise web.HTTPNotFound()
        return web.FileResponse(os.path.join(PAGE_DIR, name))

    async def _three(self, request):
        name = request.match_info["name"]
        if name not in THREE_FILES:
            raise web.HTTPNotFound()
        path = os.path.join(THREE_DIR, name)
        if not os.path.isfile(path):
            raise web.HTTPNotFound(text="%s is missing (Debian: libjs-three)" % path)
        return web.FileResponse(path)

    async def _scene(self, request):
        return web.json_response(self.scene)

    async def _methods(self, request):
        return web.json_response(self._method_list())

    async def _history(self, request):
        runs = await asyncio.get_running_loop().run_in_executor(None, self.st.history.runs)
        return web.json_response([{k: r.get(k) for k in ("uuid", "start", "end", "method", "version", "values", "by",
                                                          "outcome", "summary")} for r in runs])

    async def _run_log(self, request):
        """One past run as text: what it was, each event, each sample's outcome."""
        uuid = request.match_info["uuid"]
        runs = await asyncio.get_running_loop().run_in_executor(None, self.st.history.runs)
        r = next((x for x in runs if x["uuid"] == uuid), None)
        if r is None:
            raise web.HTTPNotFound(text="no run %s in the station's history\n" % uuid)
        at = lambda t: time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(t))  # noqa: E731
        lines = ["%s %s, started by %s at %s, ended %s" % (r["method"], " ".join("%s=%s" % tuple(v) for v in r["values"]),
                                                            r["by"], at(r["start"]), at(r["end"])),
                 "method version: %s" % (r.get("version") or "not known"),
                 "outcome: %s: %s" % (r["outcome"], r["summary"]), ""]
        for ev in r["events"]:
            lines.append("%-18s %s%s%s" % (ev["event"], ev["step_name"], ", sample %d" % ev["sample"] if ev["sample"]
                                           else "", ": " + ev["message"] if ev["message"] else ""))
        lines += [""] + ["sample %d: %s%s" % (x["sample"], x["outcome"], " (%s)" % x["reason"] if x["reason"] else "")
                         for x in r["samples"]]
        return web.Response(text="\n".join(lines) + "\n")

    async def _audit_report(self, request):
        """With --lab: the lab's review report (fbrl-audit report), the station's runs in it."""
        try:
            text, intact = await asyncio.get_running_loop().run_in_executor(None, self.st.trail.report)
        except (OSError, subprocess.SubprocessError) as e:
            log.error("the page: the audit report: %s", e)
            raise web.HTTPInternalServerError(text="the lab's audit report cannot be made: %s\n" % e)
        if not intact:
            log.warning("the page: the lab's audit trail is not intact (the report says where)")
        return web.Response(text=text, content_type="text/html")

    def _method_list(self):
        lib = self.st.runs.library
        return [{"name": m["name"], "text": m["text"], "file": os.path.basename(lib.files[m["name"].upper()]),
                 "params": [{k: p[k] for k in ("name", "unit", "text", "min", "max", "value")} for p in m["params"]],
                 "steps": [{"name": x["name"], "text": x["text"], "per_sample": x["per_sample"]} for x in m["steps"]]}
                for m in lib.methods]

    # ---------------------------------------------------------------- the WebSocket
    async def _ws(self, request):
        ws = web.WebSocketResponse(heartbeat=20)
        await ws.prepare(request)
        self._n += 1
        session = request.get("session")
        name = ("%s (page %d, %s)" % (session.name, self._n, request.remote) if session is not None
                else "page %d (%s)" % (self._n, request.remote))
        self.clients[ws] = name
        if session is not None:
            self.sessions[ws] = request.cookies.get(login.COOKIE)
        await ws.send_json({"t": "hello", "you": name, "control": self._control_name(),
                            "user": {"name": session.name, "role": session.role} if session is not None else None,
                            "lab": self.st.trail is not None})
        for m in list(self.last.values()) + list(self.run_log):
            await ws.send_json(m)
        try:
            async for msg in ws:
                if msg.type != WSMsgType.TEXT:
                    continue
                try:
                    req = json.loads(msg.data)
                    if ws in self.sessions:
                        s = self.sign_in.session(self.sessions[ws])  # the user's action keeps it alive
                        if s is None:
                            break  # signed out meanwhile (idle): the idle check closes it too
                        if req["op"] in RIGHTS and not self.sign_in.may(s, RIGHTS[req["op"]]):
                            await ws.send_json({"t": "error", "message": "%s (%s) may not %s: the %s role has no "
                                                "right to run methods" % (s.name, s.role, req["op"], s.role)})
                            continue
                    reply = await self._dry_run(req) if req["op"] == "dryrun" else self._request(ws, req)
                except (ValueError, KeyError, TypeError, OSError) as e:
                    reply = {"t": "error", "message": str(e)}
                if reply is not None:
                    await ws.send_json(reply)
        finally:
            del self.clients[ws]
            self.sessions.pop(ws, None)
            if self.controller is ws:
                self.controller = None
                await self._broadcast({"t": "control", "by": None})
        return ws

    def _control_name(self):
        return self.clients.get(self.controller) if self.controller is not None else None

    async def _broadcast(self, m):
        for ws in list(self.clients):
            try:
                await ws.send_json(m)
            except (ConnectionError, RuntimeError):
                pass  # a page that went away: its handler ends it

    def _request(self, ws, req):
        """A page's request; the reply to it (None: the broadcast says it)."""
        op = req["op"]
        who = self.clients[ws]
        if op == "control":
            if self.controller is not None and self.controller is not ws:
                return {"t": "error", "message": "%s controls the runs; it must let go first" % self._control_name()}
            if self.st.lock.locked:
                return {"t": "error", "message": "a SiLA client has locked the station (LockController)"}
            self.controller = ws
            asyncio.ensure_future(self._broadcast({"t": "control", "by": who}))
            return None
        if op == "release":
            if self.controller is ws:
                self.controller = None
                asyncio.ensure_future(self._broadcast({"t": "control", "by": None}))
            return None
        if self.controller is not ws:
            return {"t": "error", "message": "take control first (%s)" % (
                "%s controls the runs" % self._control_name() if self.controller else "no one controls them")}
        if self.st.lock.locked:
            return {"t": "error", "message": "a SiLA client has locked the station (LockController)"}
        if op == "run":
            s = self.sign_in.session(self.sessions[ws]) if ws in self.sessions else None
            return self._run(req["method"], [(k, int(v)) for k, v in req.get("params", {}).items()], who,
                             s.role if s is not None else None, s.name if s is not None else None)
        e = self._current()
        if e is None:
            return {"t": "error", "message": "no method run goes"}
        if op in ("pause", "resume"):
            hook = e.pause if op == "pause" else e.resume
            if not hook(who):
                return {"t": "error", "message": "the run cannot %s now" % op}
            return None
        if op == "abort":
            e.cancel(who)
            return None
        if op == "answer":
            if not self.st.runs.answer(e.uuid, req["option"], who):
                return {"t": "error", "message": "no question waits for an answer"}
            return None
        return {"t": "error", "message": "unknown request %r" % op}

    def _run(self, method, given, who, role=None, user=None):
        runs = self.st.runs
        if runs.library.find(method) is None:
            return {"t": "error", "message": "the method library has no method %s" % method}
        if self.st.owner.run is not None or self._current() is not None:
            return {"t": "error", "message": "a method run owns the arm: let it end or abort it first"}
        try:
            values = runs.check_values(method, given)
        except ValueError as e:
            return {"t": "error", "message": str(e)}
        ml = next(s for s in self.st.servicers if s.FEATURE == "MethodLibrary")
        e = ml.launch_run(method, values, who, role, user)
        return {"t": "started", "uuid": e.uuid, "method": method}

    async def _dry_run(self, req):
        """The method's plan against fbrlmon's emulator (nothing moves: any page may ask)."""
        method = req["method"]
        m = self.st.runs.library.find(method)
        if m is None:
            return {"t": "error", "message": "the method library has no method %s" % method}
        values = self.st.runs.check_values(method, [(k, int(v)) for k, v in req.get("params", {}).items()])
        path = self.st.runs.library.files[m["name"].upper()]

        def work():
            with tempfile.TemporaryDirectory(prefix="fbrl-page-dry-") as d:
                return dryrun.plan(self.st.opts, SITES_FBRL, path, m["name"], values, d)

        r = await asyncio.get_running_loop().run_in_executor(None, work)
        return dict(r, t="plan", method=m["name"], values=values)

    def _current(self):
        """The method run's execution that has not finished (started by a page or a SiLA client)."""
        for e in self.st.executions.all():
            if e.command_fqi.endswith(RUN_FQI_SUFFIX) and not e.finished:
                return e
        return None

    # ---------------------------------------------------------------- what the owner published
    def _publish(self, m, keep=None):
        if keep == "last":
            self.last[m["t"]] = m
        elif keep == "run":
            self.run_log.append(m)
        if self.loop is not None and not self._stop.is_set():
            self.loop.call_soon_threadsafe(lambda: asyncio.ensure_future(self._broadcast(m)))

    def _watch(self):
        """Looks at the owner's readings, the arm's state, the questions and the runs'
        progress, and sends each change to every page."""
        owner = self.st.owner
        pos_seen = state_seen = questions_seen = None
        while not self._stop.is_set():
            owner.position.wait(owner.position.version if pos_seen is None else pos_seen[0], WATCH_S)
            pos = (owner.position.version, owner.position_at)
            if pos != pos_seen and owner.position.value is not None:
                pos_seen = pos
                p = owner.position.value
                m = {"t": "pose", "world": p["world"], "joints": p["joints"], "read_at": owner.position_at,
                     "sent_at": time.time()}
                try:
                    m["chain"] = self.arm.chain(p["joints"])
                except (fbrl.Error, ValueError) as e:
                    m["chain"], m["chain_error"] = None, str(e)
                self._publish(m, "last")
            if owner.arm_state.value != state_seen:
                state_seen = owner.arm_state.value
                self._publish({"t": "state", "state": state_seen}, "last")
            qs = self.st.runs.recoverable.value
            if qs != questions_seen:
                questions_seen = qs
                self._publish({"t": "questions", "questions": [
                    {"uuid": q["uuid"], "error": q["error"], "message": q["message"]} for q in qs]}, "last")
            self._follow_runs()

    def _follow_runs(self):
        for e in self.st.executions.all():
            if not e.command_fqi.endswith(RUN_FQI_SUFFIX):
                continue
            seen = self.runs.get(e.uuid)
            if seen is None:
                seen = self.runs[e.uuid] = [0, False]
                rs = e.run_state
                self.run_log = []
                self._publish({"t": "run", "uuid": e.uuid, "method": rs.method if rs else "",
                               "values": rs.values if rs else [], "by": rs.who if rs else ""}, "run")
            new = e.intermediates[seen[0]:]
            seen[0] += len(new)
            for x in new:
                self._publish(dict(progress(x.Progress), t="progress", uuid=e.uuid), "run")
            if e.finished and not seen[1]:
                seen[1] = True
                m = {"t": "end", "uuid": e.uuid}
                if e.result is not None:
                    r = e.result
                    m.update(outcome=r.Outcome.value, summary=r.Summary.value,
                             samples=[{"sample": s.Sample.value, "outcome": s.Outcome.value,
                                       "reason": s.Reason.value} for s in r.Samples])
                else:
                    m.update(outcome="error", summary=str(e.error), samples=[])
                self._publish(m, "run")
