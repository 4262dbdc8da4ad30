# SPDX-License-Identifier: MIT
"""A small SiLA 2 client for the station's tests and benchmark: stubs by feature, values,
errors decoded, the lock identifier as metadata, observable commands followed to the end."""
import base64
import os
import re
import subprocess
import threading
import time

import grpc

from fbrl_station import pb, sila

STATION_START_S = 60


def value(msg):
    """The Python value of a SiLA basic message (String, Integer, Real, Boolean)."""
    return msg.value


class Failure(Exception):
    """A call answered with a SiLA error: .kind (validation, defined, undefined, framework),
    .identifier (the defined error's last part, the framework error's type, the parameter),
    .message, .pb (the SiLAError)."""

    def __init__(self, details):
        self.pb = sila.decode_error(details)
        self.kind = self.pb.WhichOneof("error")
        e = getattr(self.pb, self.kind)
        if self.kind == "definedExecutionError":
            self.identifier = e.errorIdentifier.rsplit("/", 1)[-1]
        elif self.kind == "frameworkError":
            self.identifier = pb.fw.FrameworkError.ErrorType.Name(e.errorType)
        elif self.kind == "validationError":
            self.identifier = e.parameter
        else:
            self.identifier = None
        self.message = e.message
        super().__init__("%s %s: %s" % (self.kind, self.identifier, self.message))


def _stream(call):
    try:
        yield from call
    except grpc.RpcError as e:
        if e.code() == grpc.StatusCode.ABORTED:
            raise Failure(e.details()) from None
        raise


class Client:
    def __init__(self, port, cert=None, host="127.0.0.1", pem=None):
        """cert: the station's certificate file to pin, or pem: its text; neither: plain gRPC."""
        target = "%s:%d" % (host, port)
        if cert is not None:
            with open(cert, "rb") as f:
                pem = f.read()
        if pem is None:
            self.channel = grpc.insecure_channel(target)
        else:  # the certificate names localhost and 127.0.0.1; TLS's server name may not be an address
            self.channel = grpc.secure_channel(target, grpc.ssl_channel_credentials(root_certificates=pem),
                                               options=[("grpc.ssl_target_name_override", "localhost")])
        self.lock_id = None
        self._stubs = {}

    def close(self):
        self.channel.close()

    def stub(self, feature):
        if feature not in self._stubs:
            self._stubs[feature] = getattr(pb.grpc_module(feature), feature + "Stub")(self.channel)
        return self._stubs[feature]

    def metadata(self):
        if self.lock_id is None:
            return None
        m = pb.messages("LockController").Metadata_LockIdentifier(LockIdentifier=sila.S(self.lock_id))
        fqi = "org.silastandard/core/LockController/v1/Metadata/LockIdentifier"
        return [(sila.metadata_key(fqi), m.SerializeToString())]

    def call(self, feature, rpc, request=None, metadata=None, **fields):
        """rpc of feature with a request message (or its fields); the response, or Failure."""
        m = pb.messages(feature)
        if request is None:
            name = rpc[4:] if rpc.startswith("Get_") else rpc
            cls = getattr(m, ("Get_%s_Parameters" % name) if rpc.startswith("Get_") else rpc + "_Parameters")
            request = cls(**fields)
        try:
            return getattr(self.stub(feature), rpc)(request, metadata=metadata or self.metadata(), timeout=120)
        except grpc.RpcError as e:
            if e.code() == grpc.StatusCode.ABORTED:
                raise Failure(e.details()) from None
            raise

    def get(self, feature, prop):
        return getattr(self.call(feature, "Get_" + prop), prop)

    def subscribe(self, feature, prop):
        m = pb.messages(feature)
        return getattr(self.stub(feature), "Subscribe_" + prop)(getattr(m, "Subscribe_%s_Parameters" % prop)(),
                                                                 metadata=self.metadata())

    def start(self, feature, command, **fields):
        """An observable command: its execution UUID."""
        conf = self.call(feature, command, **fields)
        return conf.commandExecutionUUID.value

    def info(self, feature, command, uuid):
        """The ExecutionInfo stream (a generator; a SiLA error raises Failure)."""
        return _stream(getattr(self.stub(feature), command + "_Info")(pb.fw.CommandExecutionUUID(value=uuid),
                                                                       metadata=self.metadata()))

    def intermediate(self, feature, command, uuid):
        return _stream(getattr(self.stub(feature), command + "_Intermediate")(
            pb.fw.CommandExecutionUUID(value=uuid), metadata=self.metadata()))

    def result(self, feature, command, uuid):
        try:
            return getattr(self.stub(feature), command + "_Result")(pb.fw.CommandExecutionUUID(value=uuid),
                                                                     metadata=self.metadata(), timeout=120)
        except grpc.RpcError as e:
            if e.code() == grpc.StatusCode.ABORTED:
                raise Failure(e.details()) from None
            raise

    def run(self, feature, command, **fields):
        """An observable command to its end: (result or Failure, the ExecutionInfo messages)."""
        uuid = self.start(feature, command, **fields)
        infos = list(self.info(feature, command, uuid))
        try:
            return self.result(feature, command, uuid), infos
        except Failure as f:
            return f, infos


def end(proc, seconds):
    """SIGTERM to a process a test started, SIGKILL if it has not ended within seconds; its
    exit status."""
    if proc.poll() is None:
        proc.terminate()
        try:
            proc.wait(timeout=seconds)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
    return proc.returncode


class Station:
    """An fbrl-station process (the build's launcher) on a free port; .port, .cert, .lines
    (what it printed on stderr), .client()."""

    def __init__(self, launcher, data, *args, insecure=False, env=None):
        self.data = str(data)
        argv = [launcher, "--sila", "127.0.0.1:0", "--data", self.data] + list(args)
        if "--http" not in args:  # the page's default port is one for all: only its own tests serve it
            argv += ["--http", "off"]
        if insecure:
            argv.append("--insecure")
        self.proc = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True, env=env)
        self.lines = []
        self.cert = None if insecure else os.path.join(self.data, "cert.pem")
        self.port = None
        deadline = time.monotonic() + STATION_START_S
        while time.monotonic() < deadline:
            line = self.proc.stderr.readline()
            if not line:
                break
            self.lines.append(line.rstrip("\n"))
            found = re.search(r"SiLA 2 on [^ ]+:(\d+) ", line)
            if found:
                self.port = int(found.group(1))
                break
        if self.port is None:
            self.stop()
            raise RuntimeError("fbrl-station did not start:\n" + "\n".join(self.lines))
        self._drain = threading.Thread(target=self._read, daemon=True)
        self._drain.start()

    def _read(self):
        for line in self.proc.stderr:
            self.lines.append(line.rstrip("\n"))

    def client(self):
        return Client(self.port, self.cert)

    def stop(self):
        """SIGTERM, as a service manager stops it; its exit status."""
        return end(self.proc, 30)
