# SPDX-License-Identifier: MIT
"""The protobuf and gRPC modules generated at build time (protoc, grpc_python_plugin) from the
feature definitions (protogen.py) and SiLAFramework.proto.

They are top-level modules (protoc names them after the .proto files and imports them so), kept
in a folder of their own: FBRL_STATION_GEN names it (the build tree's launcher sets it),
otherwise _gen/ beside this package (where the install puts them)."""
import importlib
import os
import sys

GEN = os.environ.get("FBRL_STATION_GEN") or os.path.join(os.path.dirname(os.path.abspath(__file__)), "_gen")
if not os.path.isfile(os.path.join(GEN, "SiLAFramework_pb2.py")):
    raise ImportError("fbrl_station: the generated protobuf modules are not in %s (build the target station, "
                      "or set FBRL_STATION_GEN)" % GEN)
if GEN not in sys.path:
    sys.path.insert(0, GEN)

fw = importlib.import_module("SiLAFramework_pb2")


def messages(feature_id):
    """The message module of a feature (e.g. ArmController_pb2)."""
    return importlib.import_module(feature_id + "_pb2")


def grpc_module(feature_id):
    """The service module of a feature (e.g. ArmController_pb2_grpc)."""
    return importlib.import_module(feature_id + "_pb2_grpc")
