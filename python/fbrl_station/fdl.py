# SPDX-License-Identifier: MIT
"""Feature definitions (SiLA 2 FDL XML) read into what the server and the proto generator need.

The .sila.xml files in features/ are the one description of what the station serves: the
protobuf files are generated from them (protogen.py, at build time), GetFeatureDefinition
returns their text, and the server takes from them which commands are observable and the
fully qualified identifiers of everything. Only the standard library's ElementTree is used, so
the build needs nothing beyond Python 3."""
import os
import xml.etree.ElementTree as ET

NS = "{http://www.sila-standard.org}"
HERE = os.path.dirname(os.path.abspath(__file__))
FEATURE_DIR = os.path.join(HERE, "features")


class DataType:
    """kind: "basic" (name), "list" (of), "structure" (elements), "constrained" (of, constraints
    element), "identifier" (name of a DataTypeDefinition)."""

    def __init__(self, kind, name=None, of=None, elements=None, constraints=None):
        self.kind, self.name, self.of, self.elements, self.constraints = kind, name, of, elements, constraints


class Element:
    """A parameter, response, intermediate response, structure element, property type, metadata
    or data type definition: identifier, display name, description, data type."""

    def __init__(self, identifier, display, description, data_type):
        self.identifier, self.display, self.description, self.data_type = identifier, display, description, data_type


class Command:
    def __init__(self, identifier, observable, parameters, responses, intermediates, errors):
        self.identifier = identifier
        self.observable = observable
        self.parameters, self.responses, self.intermediates = parameters, responses, intermediates
        self.errors = errors


class Property:
    def __init__(self, identifier, observable, data_type, errors):
        self.identifier, self.observable, self.data_type, self.errors = identifier, observable, data_type, errors


class Feature:
    """One feature definition: .identifier, .originator, .category, .version ("1.0"), .major,
    .fqi ("org.silastandard/core/SiLAService/v1"), .package (the protobuf package), .commands,
    .properties, .metadata, .errors (identifier -> display name), .types (DataTypeDefinitions),
    .text (the XML as read)."""

    def __init__(self, text):
        self.text = text
        root = ET.fromstring(text)
        if root.tag != NS + "Feature":
            raise ValueError("not a SiLA feature definition (root element %s)" % root.tag)
        self.identifier = _text(root, "Identifier")
        self.originator = root.get("Originator")
        self.category = root.get("Category", "none")
        self.version = root.get("FeatureVersion")
        self.major = int(self.version.split(".")[0])
        self.fqi = "%s/%s/%s/v%d" % (self.originator, self.category, self.identifier, self.major)
        self.package = "sila2.%s.%s.%s.v%d" % (self.originator, self.category, self.identifier.lower(), self.major)
        self.commands, self.properties, self.metadata, self.types, self.errors = [], [], [], [], {}
        for node in root:
            tag = node.tag[len(NS):]
            if tag == "Command":
                self.commands.append(Command(
                    _text(node, "Identifier"), _text(node, "Observable") == "Yes",
                    [_element(n) for n in node.findall(NS + "Parameter")],
                    [_element(n) for n in node.findall(NS + "Response")],
                    [_element(n) for n in node.findall(NS + "IntermediateResponse")], _errors(node)))
            elif tag == "Property":
                self.properties.append(Property(_text(node, "Identifier"), _text(node, "Observable") == "Yes",
                                                _data_type(node.find(NS + "DataType")), _errors(node)))
            elif tag == "Metadata":
                self.metadata.append(_element(node))
            elif tag == "DataTypeDefinition":
                self.types.append(_element(node))
            elif tag == "DefinedExecutionError":
                self.errors[_text(node, "Identifier")] = _text(node, "DisplayName")

    def command(self, identifier):
        for c in self.commands:
            if c.identifier == identifier:
                return c
        raise KeyError("%s has no command %s" % (self.identifier, identifier))

    # fully qualified identifiers (SiLA 2 Part A)
    def command_fqi(self, command):
        return "%s/Command/%s" % (self.fqi, command)

    def parameter_fqi(self, command, parameter):
        return "%s/Command/%s/Parameter/%s" % (self.fqi, command, parameter)

    def property_fqi(self, prop):
        return "%s/Property/%s" % (self.fqi, prop)

    def error_fqi(self, error):
        if error not in self.errors:
            raise KeyError("%s defines no execution error %s" % (self.identifier, error))
        return "%s/DefinedExecutionError/%s" % (self.fqi, error)

    def metadata_fqi(self, metadata):
        return "%s/Metadata/%s" % (self.fqi, metadata)


def _text(node, tag):
    child = node.find(NS + tag)
    return child.text.strip() if child is not None and child.text else ""


def _errors(node):
    lst = node.find(NS + "DefinedExecutionErrors")
    return [] if lst is None else [e.text.strip() for e in lst.findall(NS + "Identifier")]


def _element(node):
    return Element(_text(node, "Identifier"), _text(node, "DisplayName"), _text(node, "Description"),
                   _data_type(node.find(NS + "DataType")))


def _data_type(node):
    (child,) = list(node)
    tag = child.tag[len(NS):]
    if tag == "Basic":
        return DataType("basic", name=child.text.strip())
    if tag == "DataTypeIdentifier":
        return DataType("identifier", name=child.text.strip())
    if tag == "List":
        return DataType("list", of=_data_type(child.find(NS + "DataType")))
    if tag == "Structure":
        return DataType("structure", elements=[_element(e) for e in child.findall(NS + "Element")])
    if tag == "Constrained":
        return DataType("constrained", of=_data_type(child.find(NS + "DataType")),
                        constraints=child.find(NS + "Constraints"))
    raise ValueError("unknown data type element %s" % tag)


def path(identifier, directory=FEATURE_DIR):
    return os.path.join(directory, identifier + ".sila.xml")


def load(identifier, directory=FEATURE_DIR):
    with open(path(identifier, directory), encoding="utf-8") as f:
        return Feature(f.read())


def all_files(directory=FEATURE_DIR):
    """Every feature definition file of the station."""
    return sorted(os.path.join(directory, f) for f in os.listdir(directory) if f.endswith(".sila.xml"))
