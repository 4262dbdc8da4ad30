# SPDX-License-Identifier: MIT
"""The protobuf description of a feature, generated from its FDL as SiLA 2 Part B maps it.

    python3 -m fbrl_station.protogen OUTDIR FEATURE.sila.xml...

writes OUTDIR/<Identifier>.proto for each feature; the build then runs protoc and
grpc_python_plugin on them (and on SiLAFramework.proto). The mapping:

- package sila2.<originator>.<category>.<identifier in lower case>.v<major>; one service named
  as the feature; every message in the package, types of the framework from
  sila2.org.silastandard (SiLAFramework.proto).
- a basic type is the framework message of its name; a constrained type its base type; a
  list a repeated field; a structure a message <Identifier>_Struct nested in the message that
  holds the field; a data type definition a message DataType_<Identifier> with one field
  <Identifier>, used by its name.
- an unobservable command: rpc C(C_Parameters) returns (C_Responses). An observable command:
  rpc C(C_Parameters) returns (CommandConfirmation), C_Info(CommandExecutionUUID) returns
  (stream ExecutionInfo), C_Intermediate(CommandExecutionUUID) returns (stream
  C_IntermediateResponses) when it has intermediate responses, C_Result(CommandExecutionUUID)
  returns (C_Responses).
- an unobservable property: rpc Get_P(Get_P_Parameters) returns (Get_P_Responses); an
  observable one: rpc Subscribe_P(Subscribe_P_Parameters) returns (stream
  Subscribe_P_Responses); the response holds one field named as the property.
- metadata M: message Metadata_M with one field M, and rpc Get_FCPAffectedByMetadata_M
  returning repeated sila2.org.silastandard.String AffectedCalls.
Fields are numbered from 1 in the order the FDL gives them."""
import os
import sys

from . import fdl

FW = "sila2.org.silastandard."


class _Writer:
    def __init__(self):
        self.lines = []

    def add(self, depth, text):
        self.lines.append("    " * depth + text)


def _field_type(dt, name, nested):
    """The protobuf type of data type dt for a field called name; structures append their
    message definition to nested (a list of line lists). Returns (type, repeated)."""
    if dt.kind == "basic":
        return FW + dt.name, False
    if dt.kind == "identifier":
        return "DataType_" + dt.name, False
    if dt.kind == "constrained":
        return _field_type(dt.of, name, nested)
    if dt.kind == "list":
        inner, repeated = _field_type(dt.of, name, nested)
        if repeated:
            raise ValueError("%s: a list of lists has no protobuf form (SiLA forbids it)" % name)
        return inner, True
    if dt.kind == "structure":
        nested.append(_message(name + "_Struct", dt.elements))
        return name + "_Struct", False
    raise ValueError("unknown data type kind %s" % dt.kind)


def _message(name, elements):
    """The lines of message name with one field per element (nested structures inside)."""
    nested, fields = [], []
    for i, e in enumerate(elements, 1):
        ptype, repeated = _field_type(e.data_type, e.identifier, nested)
        fields.append("%s%s %s = %d;" % ("repeated " if repeated else "", ptype, e.identifier, i))
    lines = ["message %s {" % name]
    for block in nested:
        lines += ["    " + line for line in block]
    lines += ["    " + f for f in fields]
    lines.append("}")
    return lines


def proto(feature):
    """The .proto text of a fdl.Feature."""
    w = _Writer()
    w.add(0, "// Generated from the feature definition %s.sila.xml by fbrl_station.protogen:" % feature.identifier)
    w.add(0, "// do not edit (docs/sila.md).")
    w.add(0, 'syntax = "proto3";')
    w.add(0, "")
    w.add(0, 'import "SiLAFramework.proto";')
    w.add(0, "")
    w.add(0, "package %s;" % feature.package)
    w.add(0, "")
    w.add(0, "service %s {" % feature.identifier)
    uuid, confirmation, info = FW + "CommandExecutionUUID", FW + "CommandConfirmation", FW + "ExecutionInfo"
    for c in feature.commands:
        n = c.identifier
        if not c.observable:
            w.add(1, "rpc %s (%s_Parameters) returns (%s_Responses) {}" % (n, n, n))
            continue
        w.add(1, "rpc %s (%s_Parameters) returns (%s) {}" % (n, n, confirmation))
        w.add(1, "rpc %s_Info (%s) returns (stream %s) {}" % (n, uuid, info))
        if c.intermediates:
            w.add(1, "rpc %s_Intermediate (%s) returns (stream %s_IntermediateResponses) {}" % (n, uuid, n))
        w.add(1, "rpc %s_Result (%s) returns (%s_Responses) {}" % (n, uuid, n))
    for p in feature.properties:
        verb, stream = ("Subscribe", "stream ") if p.observable else ("Get", "")
        w.add(1, "rpc %s_%s (%s_%s_Parameters) returns (%s%s_%s_Responses) {}" % (
            verb, p.identifier, verb, p.identifier, stream, verb, p.identifier))
    for m in feature.metadata:
        n = "Get_FCPAffectedByMetadata_" + m.identifier
        w.add(1, "rpc %s (%s_Parameters) returns (%s_Responses) {}" % (n, n, n))
    w.add(0, "}")
    messages = []
    for t in feature.types:
        messages.append(_message("DataType_" + t.identifier, [t]))
    for c in feature.commands:
        messages.append(_message(c.identifier + "_Parameters", c.parameters))
        messages.append(_message(c.identifier + "_Responses", c.responses))
        if c.observable and c.intermediates:
            messages.append(_message(c.identifier + "_IntermediateResponses", c.intermediates))
    for p in feature.properties:
        verb = "Subscribe" if p.observable else "Get"
        messages.append(_message("%s_%s_Parameters" % (verb, p.identifier), []))
        messages.append(_message("%s_%s_Responses" % (verb, p.identifier),
                                 [fdl.Element(p.identifier, "", "", p.data_type)]))
    for m in feature.metadata:
        messages.append(_message("Metadata_" + m.identifier, [m]))
        n = "Get_FCPAffectedByMetadata_" + m.identifier
        messages.append(_message(n + "_Parameters", []))
        affected = fdl.Element("AffectedCalls", "", "", fdl.DataType("list", of=fdl.DataType("basic", name="String")))
        messages.append(_message(n + "_Responses", [affected]))
    for lines in messages:
        w.add(0, "")
        w.lines += lines
    return "\n".join(w.lines) + "\n"


def main(argv):
    if len(argv) < 2:
        sys.stderr.write("usage: python3 -m fbrl_station.protogen OUTDIR FEATURE.sila.xml...\n")
        return 2
    out = argv[0]
    os.makedirs(out, exist_ok=True)
    for p in argv[1:]:
        with open(p, encoding="utf-8") as f:
            feature = fdl.Feature(f.read())
        text = proto(feature)
        target = os.path.join(out, feature.identifier + ".proto")
        with open(target, "w", encoding="utf-8") as f:
            f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
