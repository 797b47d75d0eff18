"""JSON Schemas (draft 2020-12) of the executable protocol, version 1 (docs/protocol.md):
the handshake, each method's request and each method's answer.

``docs/protocol.schema.json`` is :func:`schema` written by ``python -m
ddg_oracle.protocol.schema docs/protocol.schema.json``; a test keeps the two
equal and validates real traffic (every request ddg-oracle sends, every answer of the
reference served through the protocol) against it.  ``"$defs"`` holds, per method
``M``, ``request.M`` and ``answer.M``; ``hello.request``, ``hello.answer`` and
``error.answer`` are the others, and ``manifest`` the file that may stand for the
handshake (``exec:driver.json``).  Numbers are JSON numbers; a program may write NaN
and Infinity as Python's json module reads them (outside strict JSON: they are then
compared as wrong values, not rejected as garbage).
"""

from __future__ import annotations

import json
import sys

from .methods import METHODS

VERSION = 1

_NUMBER = {"type": "number"}
_INDEX = {"type": "integer", "minimum": 0}


def _array(items: dict, length: int | None = None) -> dict:
    out = {"type": "array", "items": items}
    if length is not None:
        out.update(minItems=length, maxItems=length)
    return out


_EDGE_VALUE = {"type": "array", "prefixItems": [_INDEX, _INDEX, _NUMBER], "minItems": 3,
               "maxItems": 3}

#: the ``value`` of an answer, by the method's kind (and element: protocol.methods.Method)
_VALUE_OF_KIND = {
    "integer": {"type": "integer"},
    "boolean": {"type": "boolean"},
    "loops": _array(_array(_INDEX)),
    "edges": _array(_EDGE_VALUE),
    "matrix": {"$ref": "#/$defs/sparse"},
    "flags": _array(_array({"type": "boolean"}, 3)),
    "intrinsic triangulation": {
        "type": "object", "required": ["F", "l2"], "additionalProperties": False,
        "properties": {"F": _array(_array(_INDEX, 3)), "l2": _array(_array(_NUMBER, 3))}},
    "planar triangulation": _array(_array(_INDEX, 3)),
}
_VALUE_OF_ELEMENT = {"corner": _array(_array(_NUMBER, 3)), "vertex": _array(_NUMBER),
                     "vertex coordinate": _array(_array(_NUMBER, 3)), "total": _NUMBER}

#: a preset of the conventions vocabulary (properties.conventions.PRESETS), by name
_PRESET = {"type": "string"}

#: each argument of a request (the method's ``arguments``)
_ARGUMENT = {"V": _array(_array(_NUMBER, 3)), "F": _array(_array(_INDEX, 3)),
             "P": _array(_array(_NUMBER, 2)), "boundary": _array(_INDEX),
             "values": _array(_NUMBER)}


def value_schema(method: str) -> dict:
    """The schema of ``method``'s answer value, from its kind and element."""
    m = METHODS[method]
    return _VALUE_OF_ELEMENT[m.element] if m.kind == "numbers" else _VALUE_OF_KIND[m.kind]


def _declaration(counterpart: str, counterpart_schema: dict) -> dict:
    """What a program declares of itself, in its handshake answer or in a manifest: a name,
    its methods, its machine epsilon and its conventions (a preset, or what it follows and
    how its counterpart is started: ``counterpart`` names that field, which differs)."""
    return {
        "name": {"type": "string"},
        "methods": {"type": "array", "minItems": 1, "uniqueItems": True,
                    "items": {"enum": list(METHODS)}},
        "machine_epsilon": {"type": "number", "exclusiveMinimum": 0},
        "conventions": {"anyOf": [
            _PRESET,
            {"type": "object",
             "properties": {
                 "follows": {"type": "object", "additionalProperties": {"type": "string"}},
                 counterpart: counterpart_schema}}]}}


def schema() -> dict:
    """The protocol's schemas, one JSON document."""
    defs: dict[str, dict] = {
        "sparse": {"type": "object", "required": ["shape", "rows", "cols", "values"],
                   "additionalProperties": False,
                   "properties": {"shape": _array(_INDEX, 2), "rows": _array(_INDEX),
                                  "cols": _array(_INDEX), "values": _array(_NUMBER)}},
        "hello.request": {"type": "object", "required": ["protocol", "version", "method"],
                          "properties": {"protocol": {"const": "ddg-oracle"},
                                         "version": {"const": VERSION},
                                         "method": {"const": "hello"}}},
        "hello.answer": {
            "type": "object", "required": ["methods"],
            "properties": _declaration("counterpart_arguments", _array({"type": "string"}))},
        "manifest": {
            "type": "object", "required": ["command", "methods"],
            "properties": {
                "command": {"type": "array", "minItems": 1, "items": {"type": "string"}},
                **_declaration("counterpart", {"type": "string"})}},
        "error.answer": {
            "type": "object", "required": ["id", "error"], "additionalProperties": False,
            "properties": {"id": {"type": "integer"},
                           "error": {"type": "object", "required": ["kind", "message"],
                                     "properties": {"kind": {"enum": ["outside_domain", "failed"]},
                                                    "message": {"type": "string"}}}}},
    }
    for method, spec in METHODS.items():
        value = value_schema(method)
        inputs = {a: _ARGUMENT[a] for a in spec.arguments}
        defs[f"request.{method}"] = {
            "type": "object", "required": ["id", "method", *inputs], "additionalProperties": False,
            "properties": {"id": {"type": "integer"}, "method": {"const": method}, **inputs}}
        defs[f"answer.{method}"] = {
            "type": "object", "required": ["id", "value"], "additionalProperties": False,
            "properties": {"id": {"type": "integer"}, "value": value}}
    return {"$schema": "https://json-schema.org/draft/2020-12/schema",
            "title": f"ddg-oracle executable protocol, version {VERSION}",
            "description": "One JSON object per line: requests on the program's stdin, "
                           "answers on its stdout (docs/protocol.md). Validate a message "
                           "against #/$defs/<kind>.",
            "version": VERSION, "$defs": defs}


def text() -> str:
    """:func:`schema` as the committed file's text (sorted keys, 2-space indent)."""
    return json.dumps(schema(), indent=2, sort_keys=True) + "\n"


#: an answer's ``value`` in words, by the method's kind (and element), for the method table
_VALUE_IN_WORDS = {
    "integer": "integer", "boolean": "`true` / `false`",
    "loops": "list of lists of vertex indices",
    "edges": "list of `[i, j, x]`, i < j",
    "matrix": 'sparse n x n: `{"shape": [n, n], "rows": [...], "cols": [...], '
              '"values": [...]}` (duplicates are summed)',
    "flags": "m x 3 booleans",
    "intrinsic triangulation": '`{"F": m x 3 integers, "l2": m x 3 numbers}`',
    "planar triangulation": "m x 3 integers",
    "corner": "m x 3 numbers", "vertex": "n numbers", "vertex coordinate": "n x 3 numbers",
    "total": "number"}

#: the lines around the method table in docs/protocol.md (:func:`with_method_table`)
TABLE_START = ("<!-- the method table: generated from protocol/methods.py by "
               "`python -m ddg_oracle.protocol.schema --table docs/protocol.md` -->")
TABLE_END = "<!-- end of the method table -->"


def method_table() -> str:
    """The protocol's methods as a Markdown table: arguments, the answer's ``value`` (its
    kind and element) and the contract, one row per method of :data:`.methods.METHODS`."""
    rows = ["| method | request fields | `value` | answer |", "|---|---|---|---|"]
    for name, m in METHODS.items():
        words = _VALUE_IN_WORDS[m.element if m.kind == "numbers" else m.kind]
        fields = ", ".join(f"`{a}`" for a in m.arguments)
        rows.append(f"| `{name}` | {fields} | {words} | {m.contract.replace('|', '/')} |")
    return "\n".join(rows) + "\n"


def with_method_table(markdown: str) -> str:
    """``markdown`` with the text between :data:`TABLE_START` and :data:`TABLE_END` replaced
    by :func:`method_table`."""
    head, found, rest = markdown.partition(TABLE_START + "\n")
    _, found_end, tail = rest.partition(TABLE_END)
    if not (found and found_end):
        raise ValueError("no method table markers in the document")
    return head + TABLE_START + "\n" + method_table() + TABLE_END + tail


if __name__ == "__main__":
    if sys.argv[1:2] == ["--table"]:
        with open(sys.argv[2], encoding="utf-8") as f:
            doc = with_method_table(f.read())
        with open(sys.argv[2], "w", encoding="utf-8") as out:
            out.write(doc)
    else:
        with open(sys.argv[1], "w", encoding="utf-8") as out:
            out.write(text())
