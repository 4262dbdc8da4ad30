# SPDX-License-Identifier: MIT
"""The station's feature definitions and protobuf files against the standard's own files
(reference/: the schema, SiLAFramework.proto, the core features) and against Part B's mapping
written out by hand for one feature. No station runs here."""
import os
import shutil
import subprocess

import pytest
from google.protobuf import descriptor_pb2
from lxml import etree

from fbrl_station import fdl, protogen

HERE = os.path.dirname(os.path.abspath(__file__))
REF = os.path.join(HERE, "reference")
NS = "{http://www.sila-standard.org}"
PROTOC = shutil.which("protoc")


def test_every_feature_definition_validates_against_the_schema():
    schema = etree.XMLSchema(etree.parse(os.path.join(REF, "schema", "FeatureDefinition.xsd")))
    files = fdl.all_files()
    assert len(files) >= 9
    for path in files:
        doc = etree.parse(path)
        assert schema.validate(doc), (path, schema.error_log)


def _shape(node):
    """What a client depends on in a definition: everything but display names, descriptions
    and comments, as nested tuples (element order kept)."""
    tag = node.tag[len(NS):] if isinstance(node.tag, str) else None
    if tag is None or tag in ("DisplayName", "Description"):
        return None
    kids = [s for s in (_shape(k) for k in node) if s is not None]
    text = (node.text or "").strip() if not len(node) else ""
    attrs = tuple(sorted((k, v) for k, v in node.attrib.items() if not k.startswith("{")))
    return (tag, attrs, text, tuple(kids))


@pytest.mark.parametrize("name", ["SiLAService", "LockController", "CancelController", "PauseController",
                                  "SimulationController"])
def test_core_features_are_the_standard_s(name):
    ours = etree.parse(fdl.path(name)).getroot()
    theirs = etree.parse(os.path.join(REF, "core", name + ".sila.xml")).getroot()
    assert _shape(ours) == _shape(theirs)


def _descriptors(directory, *files):
    out = os.path.join(directory, "set.pb")
    subprocess.run([PROTOC, "-I", directory, "--descriptor_set_out=" + out] + list(files), check=True)
    fds = descriptor_pb2.FileDescriptorSet()
    with open(out, "rb") as f:
        fds.ParseFromString(f.read())
    return fds


def _messages(fd):
    """{message name: (fields, nested, enums, oneofs)} of a file, fields as (name, number,
    label, type, type name, oneof index)."""
    def one(m):
        fields = tuple((f.name, f.number, f.label, f.type, f.type_name,
                        f.oneof_index if f.HasField("oneof_index") else None) for f in m.field)
        enums = tuple((e.name, tuple((v.name, v.number) for v in e.value)) for e in m.enum_type)
        return fields, tuple(sorted((n.name, one(n)) for n in m.nested_type)), enums, \
            tuple(o.name for o in m.oneof_decl)
    return {m.name: one(m) for m in fd.message_type}


@pytest.mark.skipif(PROTOC is None, reason="protoc not installed")
def test_the_framework_messages_are_the_standard_s(tmp_path):
    a, b = tmp_path / "ours", tmp_path / "theirs"
    a.mkdir()
    b.mkdir()
    shutil.copy(os.path.join(os.path.dirname(fdl.__file__), "proto", "SiLAFramework.proto"), a)
    shutil.copy(os.path.join(REF, "protobuf", "SiLAFramework.proto"), b)
    ours = _descriptors(str(a), "SiLAFramework.proto").file[0]
    theirs = _descriptors(str(b), "SiLAFramework.proto").file[0]
    assert ours.package == theirs.package == "sila2.org.silastandard"
    assert _messages(ours) == _messages(theirs)


# LockController as SiLA 2 Part B maps it, written out by hand from the mapping's rules (the
# standard's examples name these messages so): the generator must give the same descriptors.
LOCK_PROTO = """syntax = "proto3";
import "SiLAFramework.proto";
package sila2.org.silastandard.core.lockcontroller.v1;
service LockController {
  rpc LockServer (LockServer_Parameters) returns (LockServer_Responses) {}
  rpc UnlockServer (UnlockServer_Parameters) returns (UnlockServer_Responses) {}
  rpc Get_IsLocked (Get_IsLocked_Parameters) returns (Get_IsLocked_Responses) {}
  rpc Get_FCPAffectedByMetadata_LockIdentifier (Get_FCPAffectedByMetadata_LockIdentifier_Parameters)
      returns (Get_FCPAffectedByMetadata_LockIdentifier_Responses) {}
}
message LockServer_Parameters {
  sila2.org.silastandard.String LockIdentifier = 1;
  sila2.org.silastandard.Integer Timeout = 2;
}
message LockServer_Responses {}
message UnlockServer_Parameters { sila2.org.silastandard.String LockIdentifier = 1; }
message UnlockServer_Responses {}
message Get_IsLocked_Parameters {}
message Get_IsLocked_Responses { sila2.org.silastandard.Boolean IsLocked = 1; }
message Metadata_LockIdentifier { sila2.org.silastandard.String LockIdentifier = 1; }
message Get_FCPAffectedByMetadata_LockIdentifier_Parameters {}
message Get_FCPAffectedByMetadata_LockIdentifier_Responses {
  repeated sila2.org.silastandard.String AffectedCalls = 1;
}
"""
# An observable command with intermediate responses and a structure, and a data type
# definition (the standard's ObservableCommandTest and RobotController shapes).
OBSERVABLE_FDL = """<?xml version="1.0" encoding="utf-8"?>
<Feature SiLA2Version="1.0" FeatureVersion="2.1" Originator="org.example" Category="test"
         xmlns="http://www.sila-standard.org">
  <Identifier>Mover</Identifier><DisplayName>Mover</DisplayName><Description>d</Description>
  <Command>
    <Identifier>Move</Identifier><DisplayName>Move</DisplayName><Description>d</Description>
    <Observable>Yes</Observable>
    <Parameter><Identifier>To</Identifier><DisplayName>To</DisplayName><Description>d</Description>
      <DataType><DataTypeIdentifier>Site</DataTypeIdentifier></DataType></Parameter>
    <Response><Identifier>Steps</Identifier><DisplayName>S</DisplayName><Description>d</Description>
      <DataType><List><DataType><Structure>
        <Element><Identifier>Name</Identifier><DisplayName>N</DisplayName><Description>d</Description>
          <DataType><Basic>String</Basic></DataType></Element>
      </Structure></DataType></List></DataType></Response>
    <IntermediateResponse><Identifier>Done</Identifier><DisplayName>D</DisplayName><Description>d</Description>
      <DataType><Constrained><DataType><Basic>Integer</Basic></DataType>
        <Constraints><MinimalInclusive>0</MinimalInclusive></Constraints></Constrained></DataType>
    </IntermediateResponse>
  </Command>
  <Property><Identifier>Where</Identifier><DisplayName>W</DisplayName><Description>d</Description>
    <Observable>Yes</Observable><DataType><Basic>Real</Basic></DataType></Property>
  <DataTypeDefinition><Identifier>Site</Identifier><DisplayName>S</DisplayName><Description>d</Description>
    <DataType><Structure>
      <Element><Identifier>Device</Identifier><DisplayName>D</DisplayName><Description>d</Description>
        <DataType><Basic>String</Basic></DataType></Element>
      <Element><Identifier>Index</Identifier><DisplayName>I</DisplayName><Description>d</Description>
        <DataType><Basic>Integer</Basic></DataType></Element>
    </Structure></DataType></DataTypeDefinition>
</Feature>
"""
OBSERVABLE_PROTO = """syntax = "proto3";
import "SiLAFramework.proto";
package sila2.org.example.test.mover.v2;
service Mover {
  rpc Move (Move_Parameters) returns (sila2.org.silastandard.CommandConfirmation) {}
  rpc Move_Info (sila2.org.silastandard.CommandExecutionUUID) returns (stream sila2.org.silastandard.ExecutionInfo) {}
  rpc Move_Intermediate (sila2.org.silastandard.CommandExecutionUUID) returns (stream Move_IntermediateResponses) {}
  rpc Move_Result (sila2.org.silastandard.CommandExecutionUUID) returns (Move_Responses) {}
  rpc Subscribe_Where (Subscribe_Where_Parameters) returns (stream Subscribe_Where_Responses) {}
}
message DataType_Site {
  message Site_Struct {
    sila2.org.silastandard.String Device = 1;
    sila2.org.silastandard.Integer Index = 2;
  }
  Site_Struct Site = 1;
}
message Move_Parameters { DataType_Site To = 1; }
message Move_Responses {
  message Steps_Struct { sila2.org.silastandard.String Name = 1; }
  repeated Steps_Struct Steps = 1;
}
message Move_IntermediateResponses { sila2.org.silastandard.Integer Done = 1; }
message Subscribe_Where_Parameters {}
message Subscribe_Where_Responses { sila2.org.silastandard.Real Where = 1; }
"""


@pytest.mark.skipif(PROTOC is None, reason="protoc not installed")
@pytest.mark.parametrize("fdl_text,expected", [(open(fdl.path("LockController")).read(), LOCK_PROTO),
                                               (OBSERVABLE_FDL, OBSERVABLE_PROTO)], ids=["LockController", "Mover"])
def test_generated_protobuf_is_part_b_s_mapping(tmp_path, fdl_text, expected):
    feature = fdl.Feature(fdl_text)
    framework = os.path.join(os.path.dirname(fdl.__file__), "proto", "SiLAFramework.proto")
    got, want = tmp_path / "got", tmp_path / "want"
    for d, text in ((got, protogen.proto(feature)), (want, expected)):
        d.mkdir()
        shutil.copy(framework, d)
        (d / "F.proto").write_text(text)
    a = [f for f in _descriptors(str(got), "F.proto").file if f.name == "F.proto"][0]
    b = [f for f in _descriptors(str(want), "F.proto").file if f.name == "F.proto"][0]
    assert a.package == b.package
    assert _messages(a) == _messages(b)
    services = lambda fd: [(s.name, [(m.name, m.input_type, m.output_type, m.server_streaming) for m in s.method])
                           for s in fd.service]
    assert services(a) == services(b)
