#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""scheduler.py HOST:PORT CERT METHOD [NAME=VALUE...] - what a lab scheduler does with
fbrl-station, from a plain gRPC client (docs/sila.md, "A scheduler's view"): it pins the
station's certificate, lists the features, locks the station, homes the arm, moves a tube with
MovePlate, runs a method and follows it to its end, and unlocks.

It needs only grpcio, protobuf and the Python modules protoc makes from the station's .proto
files (the build puts them in build/station/gen):

    PYTHONPATH=build/station/gen python3 examples/station/scheduler.py 127.0.0.1:50052 \\
        ~/.local/share/fbrl-station/50052/cert.pem SAMPLE-PREP '#SAMPLES=2'
"""
import base64
import sys
import uuid

import grpc

import ArmController_pb2 as arm
import ArmController_pb2_grpc as arm_grpc
import LockController_pb2 as lock
import LockController_pb2_grpc as lock_grpc
import MethodLibrary_pb2 as ml
import MethodLibrary_pb2_grpc as ml_grpc
import RobotController_pb2 as robot
import RobotController_pb2_grpc as robot_grpc
import SiLAFramework_pb2 as fw
import SiLAService_pb2 as svc
import SiLAService_pb2_grpc as svc_grpc

LOCK_KEY = "sila-org.silastandard-core-lockcontroller-v1-metadata-lockidentifier-bin"


def sila_error(e):
    """The SiLA error a call ended with (status ABORTED, the base64 of a SiLAError)."""
    err = fw.SiLAError()
    err.ParseFromString(base64.b64decode(e.details()))
    kind = err.WhichOneof("error")
    return "%s: %s" % (kind, getattr(err, kind))


def follow(stub, command, confirmation, metadata):
    """An observable command to its end: progress as it goes, then its result."""
    cid = confirmation.commandExecutionUUID
    for info in getattr(stub, command + "_Info")(cid, metadata=metadata):
        left = info.estimatedRemainingTime.seconds if info.HasField("estimatedRemainingTime") else "?"
        status = fw.ExecutionInfo.CommandStatus.Name(info.commandStatus)
        print("  %-20s %3.0f%%  about %s s left" % (status, 100 * info.progressInfo.value, left), end="\r")
    print()
    return getattr(stub, command + "_Result")(cid, metadata=metadata)


def main(target, cert, method, values):
    with open(cert, "rb") as f:  # the station's own certificate: trust exactly it
        creds = grpc.ssl_channel_credentials(root_certificates=f.read())
    channel = grpc.secure_channel(target, creds, options=[("grpc.ssl_target_name_override", "localhost")])
    s = svc_grpc.SiLAServiceStub(channel)
    name = s.Get_ServerName(svc.Get_ServerName_Parameters()).ServerName.value
    features = s.Get_ImplementedFeatures(svc.Get_ImplementedFeatures_Parameters()).ImplementedFeatures
    print("%s: %s" % (name, ", ".join(f.value.split("/")[2] for f in features)))

    me = str(uuid.uuid4())  # the lock: from now on every call carries it
    lock_grpc.LockControllerStub(channel).LockServer(lock.LockServer_Parameters(
        LockIdentifier=fw.String(value=me), Timeout=fw.Integer(value=600)))
    md = [(LOCK_KEY, lock.Metadata_LockIdentifier(LockIdentifier=fw.String(value=me)).SerializeToString())]
    try:
        a = arm_grpc.ArmControllerStub(channel)
        print("Home")
        follow(a, "Home", a.Home(arm.Home_Parameters(), metadata=md), md)

        r = robot_grpc.RobotControllerStub(channel)
        site = lambda device, i: robot.DataType_Site(Site=robot.DataType_Site.Site_Struct(
            Device=fw.String(value=device), SiteIndex=fw.Integer(value=i)))
        print("MovePlate HEATING-BLOCK 0 -> SEPARATOR")
        follow(r, "MovePlate", r.MovePlate(robot.MovePlate_Parameters(
            OriginSite=site("HEATING-BLOCK", 0), DestinationSite=site("SEPARATOR", 0),
            PlateType=fw.String(value="TUBE")), metadata=md), md)
        print("MovePlate SEPARATOR -> HEATING-BLOCK 0")
        follow(r, "MovePlate", r.MovePlate(robot.MovePlate_Parameters(
            OriginSite=site("SEPARATOR", 0), DestinationSite=site("HEATING-BLOCK", 0),
            PlateType=fw.String(value="TUBE")), metadata=md), md)

        m = ml_grpc.MethodLibraryStub(channel)
        params = [ml.RunMethod_Parameters.Parameters_Struct(Name=fw.String(value=k), Value=fw.Integer(value=int(v)))
                  for k, v in (x.split("=", 1) for x in values)]
        print("RunMethod %s %s" % (method, " ".join(values)))
        result = follow(m, "RunMethod", m.RunMethod(ml.RunMethod_Parameters(
            Method=fw.String(value=method), Parameters=params), metadata=md), md)
        print(result.Summary.value)
        for x in result.Samples:
            print("  sample %d: %s %s" % (x.Sample.value, x.Outcome.value, x.Reason.value))
        return 0 if result.Outcome.value == "completed" else 4
    except grpc.RpcError as e:
        print(sila_error(e) if e.code() == grpc.StatusCode.ABORTED else e, file=sys.stderr)
        return 1
    finally:
        lock_grpc.LockControllerStub(channel).UnlockServer(lock.UnlockServer_Parameters(
            LockIdentifier=fw.String(value=me)))


if __name__ == "__main__":
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]))
