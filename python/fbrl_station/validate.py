# SPDX-License-Identifier: MIT
"""Parameters checked against their feature definition before a command runs: every
parameter present, and every constraint the FDL states (length, pattern, set, range) kept.
A failure is the standard's validation error naming the parameter."""
import re

from . import sila
from .fdl import NS

_NUMERIC = {"MinimalInclusive": lambda v, b: v >= b, "MaximalInclusive": lambda v, b: v <= b,
            "MinimalExclusive": lambda v, b: v > b, "MaximalExclusive": lambda v, b: v < b}
_WORDS = {"MinimalInclusive": "at least", "MaximalInclusive": "at most", "MinimalExclusive": "more than",
          "MaximalExclusive": "less than"}


def check(feature, command, request):
    """Raise a validation error for the first parameter of request (the command's
    _Parameters message) that is missing or breaks a constraint."""
    cmd = feature.command(command)
    types = {t.identifier: t.data_type for t in feature.types}
    for p in cmd.parameters:
        fqi = feature.parameter_fqi(command, p.identifier)
        if p.data_type.kind != "list" and not request.HasField(p.identifier):  # a list may be empty
            raise sila.validation(fqi, "the parameter %s is missing" % p.identifier)
        _value(getattr(request, p.identifier), p.data_type, types, fqi, p.identifier)


def _value(msg, dt, types, fqi, where):
    if dt.kind == "identifier":
        inner = getattr(msg, dt.name)
        if not msg.HasField(dt.name) and types[dt.name].kind not in ("list",):
            raise sila.validation(fqi, "%s is missing" % where)
        return _value(inner, types[dt.name], types, fqi, where)
    if dt.kind == "basic":
        return
    if dt.kind == "list":
        for i, item in enumerate(msg):
            _value(item, dt.of, types, fqi, "%s[%d]" % (where, i))
        return
    if dt.kind == "structure":
        for e in dt.elements:
            if e.data_type.kind != "list" and not msg.HasField(e.identifier):
                raise sila.validation(fqi, "%s.%s is missing" % (where, e.identifier))
            _value(getattr(msg, e.identifier), e.data_type, types, fqi, "%s.%s" % (where, e.identifier))
        return
    if dt.kind == "constrained":
        _value(msg, dt.of, types, fqi, where)
        _constraints(msg, dt.constraints, fqi, where)


def _constraints(msg, node, fqi, where):
    value = getattr(msg, "value", None)
    for c in node:
        tag, text = c.tag[len(NS):], (c.text or "").strip()
        if tag == "Length" and len(value) != int(text):
            raise sila.validation(fqi, "%s must be %s characters long" % (where, text))
        if tag == "MaximalLength" and len(value) > int(text):
            raise sila.validation(fqi, "%s is longer than %s characters" % (where, text))
        if tag == "MinimalLength" and len(value) < int(text):
            raise sila.validation(fqi, "%s is shorter than %s characters" % (where, text))
        if tag == "Pattern" and not re.fullmatch(text, value):
            raise sila.validation(fqi, "%s %r does not match the pattern %s" % (where, value, text))
        if tag == "Set":
            allowed = [v.text for v in c.findall(NS + "Value")]
            if str(value) not in allowed:
                raise sila.validation(fqi, "%s %r is not one of %s" % (where, value, ", ".join(allowed)))
        if tag in _NUMERIC and not _NUMERIC[tag](value, float(text)):
            raise sila.validation(fqi, "%s %s must be %s %s" % (where, value, _WORDS[tag], text))
