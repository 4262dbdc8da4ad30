# SPDX-License-Identifier: MIT
"""The station: the owner thread with the controller and the engine, the features, the gRPC
server (TLS unless --insecure) and the discovery record; run() is fbrl-station's life."""
import concurrent.futures
import logging
import signal
import socket
import sys
import threading

import grpc

import fbrl

from . import fdl, pb, sila, tls
from .arm import ArmController, RobotController
from .cell import Cell
from .commands import CancelController, ErrorRecoveryService, MethodLibrary, PauseController
from .controller import Controller, RobotFailure, report
from .core import DESCRIPTION, LockController, SiLAService, SimulationController
from .datadir import DataDir
from .history import History
from .owner import Owner
from .runs import Runs

log = logging.getLogger("fbrl-station")

GRPC_WORKERS = 64  # every open stream (Info, Intermediate, property subscriptions) holds one
STOP_GRACE_S = 2.0
FEATURE_CLASSES = (SiLAService, LockController, CancelController, PauseController, SimulationController,
                   ErrorRecoveryService, ArmController, RobotController, MethodLibrary)


class StartError(Exception):
    """The station could not start (exit status 3); .status 1 when a file or -e text failed."""

    def __init__(self, message, status=3):
        super().__init__(message)
        self.status = status


class Station:
    def __init__(self, opts):
        self.opts = opts
        # in the order ImplementedFeatures lists them (SiLAService first)
        self.features = {cls.FEATURE: fdl.load(cls.FEATURE) for cls in FEATURE_CLASSES}
        self.data = DataDir(opts.data)
        self.identity = self.data.identity("fbrl-station on %s" % socket.gethostname())
        self.executions = sila.Executions()
        self.lock = sila.Lock(self.features["LockController"], pb.messages("LockController").Metadata_LockIdentifier)
        self.controller = Controller(opts)
        self.owner = Owner(self.controller)
        self.cell = Cell(self.data)
        self.runs = Runs(self)
        self.history = History(self.data)
        self.servicers = [cls(self) for cls in FEATURE_CLASSES]
        self.server = None
        self.port = None
        self.cert_pem = None
        self.announcer = None
        self.page = None
        self.sign_in = None  # the page's sign-in (--lab): the users file is checked before the controller
        self.trail = None  # the lab's audit trail (--lab): sign-ins and runs recorded
        if opts.lab is not None:
            from .trail import LabTrail
            self.trail = LabTrail(opts.lab, "fbrl-station %s" % fbrl.version())
        if opts.http is not None and opts.lab is not None:
            from .login import SignIn
            self.sign_in = SignIn(opts.lab, self.trail)
        self._name_lock = threading.Lock()

    # ---------------------------------------------------------------- identity
    def set_name(self, name):
        with self._name_lock:
            self.data.set_name(name)
            self.identity = dict(self.identity, name=name)
            if self.announcer is not None:
                self.announcer.update(self._txt())

    def _txt(self):
        from .discovery import txt_record
        return txt_record(fbrl.version(), self.identity["name"], DESCRIPTION, self.cert_pem)

    def lock_protected(self):
        """The calls the lock protects: every command that moves the arm or changes the
        station (Get_FCPAffectedByMetadata_LockIdentifier)."""
        calls = []
        for f in self.features.values():
            if f.identifier not in ("SiLAService", "LockController"):
                calls += [f.command_fqi(c.identifier) for c in f.commands]
        return calls

    # ---------------------------------------------------------------- start and stop
    def start(self):
        self.owner.start()
        self.owner.call(self._setup)
        if self.opts.sila is not None:
            self._serve()
        if self.opts.http is not None:
            try:  # aiohttp is loaded only when the page is served
                from .web import Page
            except ImportError as e:
                raise StartError("--http: %s (Debian: python3-aiohttp), or --http off" % e)
            self.page = Page(self, *self.opts.http, sign_in=self.sign_in)
            self.page.start()

    def _setup(self, c):
        """On the owner thread: the controller, the site words, the FILEs and -e texts in
        order, the taught places; then the arm is read once."""
        try:
            c.connect(c.simulation)
        except (fbrl.Error, OSError) as e:
            raise StartError("cannot connect to the controller%s: %s" % (
                "" if c.simulation else " on " + self.opts.port, e))
        self.cell.install(c)
        for kind, what in self.opts.actions:
            try:
                out = c.engine.eval(what) if kind == "eval" else c.engine.include(what)
            except fbrl.Error as e:
                raise StartError(report(e, "-e" if kind == "eval" else what), status=1)
            finally:
                c.engine.reset()
            if out.strip():
                sys.stdout.write(out if out.endswith("\n") else out + "\n")
        self.runs.install(c)
        self.runs.library.load(c, log.warning)
        self.cell.restore(c, log.warning)
        self.owner.refresh(status=True)

    def tls_identity(self):
        """(key PEM, certificate PEM): one pair for the SiLA side and the page, covering both
        their addresses (each a new pair otherwise, and a client's pin would break)."""
        hosts = [a[0] for a in (self.opts.sila, self.opts.http) if a is not None]
        return tls.identity(self.data, self.identity["uuid"], *hosts)

    def _serve(self):
        host, port = self.opts.sila
        self.server = grpc.server(concurrent.futures.ThreadPoolExecutor(max_workers=GRPC_WORKERS,
                                                                        thread_name_prefix="sila"))
        for s in self.servicers:
            s.add_to(self.server)
        address = "%s:%d" % ("[%s]" % host if ":" in host else host, port)
        if self.opts.insecure:
            self.port = self.server.add_insecure_port(address)
        else:
            key, self.cert_pem = self.tls_identity()
            self.port = self.server.add_secure_port(address, grpc.ssl_server_credentials([(key, self.cert_pem)]))
        if not self.port:
            raise StartError("cannot listen on %s (in use, or not an address of this host)" % address)
        self.server.start()
        if self.opts.discovery:  # zeroconf is loaded only when it is used
            from .discovery import Announcer
            self.announcer = Announcer(self.identity["uuid"], host, self.port, self._txt())

    def stop(self):
        """Withdraw the record, end the calls, stop a method run as a cancel does (the arm
        halted, the outputs off, ON-ABORT), drop what waits, let the controller go."""
        if self.announcer is not None:
            self.announcer.close()
        if self.page is not None:
            self.page.stop()
        if self.server is not None:
            self.server.stop(STOP_GRACE_S).wait()
        for e in self.executions.all():
            if e.cancel is not None and not e.finished:
                e.cancel("fbrl-station stopping")
        self.owner.stop(lambda c: c.disconnect())


def run(opts):
    logging.basicConfig(format="fbrl-station: %(message)s", level=logging.INFO, stream=sys.stderr)
    if opts.insecure and opts.sila is not None:
        log.warning("warning: --insecure: SiLA 2 without TLS; anyone who reaches %s:%d can read and move the arm",
                    *opts.sila)
    try:
        station = Station(opts)
    except (OSError, ValueError) as e:
        log.error("%s", e)
        return 3
    stopping = threading.Event()
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_: stopping.set())
    try:
        station.start()
    except StartError as e:
        log.error("%s", e)
        _stop_quietly(station)
        return e.status
    except (OSError, RobotFailure) as e:
        log.error("%s", e)
        _stop_quietly(station)
        return 3
    c = station.controller
    log.info("%s %s: UUID %s, controller: %s", station.identity["name"], fbrl.version(), station.identity["uuid"],
             c.describe())
    if station.port:
        log.info("SiLA 2 on %s:%d (%s)%s", opts.sila[0], station.port,
                 "plain gRPC" if opts.insecure else "TLS, certificate " + station.data.file(tls.CERT_FILE),
                 ", announced as _sila._tcp" if opts.discovery else "")
    if station.page is not None:
        host = opts.http[0]
        log.info("the page on %s://%s:%d/%s", "https" if opts.lab else "http", "[%s]" % host if ":" in host else host,
                 station.page.port, " (TLS, certificate %s; the users of %s sign in)" % (
                     station.data.file(tls.CERT_FILE), opts.lab) if opts.lab else "")
    sys.stderr.flush()
    while not stopping.wait(1.0):  # a timed wait, so the signal handler runs promptly
        pass
    log.info("stopping")
    station.stop()
    return 0


def _stop_quietly(station):
    try:
        station.stop()
    except Exception as e:  # already failing: the first error is the one to report
        log.debug("stop after a failed start: %s", e)
