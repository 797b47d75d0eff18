"""Values as JSON, read back without running any code: replay strings and resumed results.

A replay string (``ddg2:...``, in a snippet, a report, a CI artifact someone downloads) and
a report directory's ``results.jsonl`` (read by ``ddg-oracle check --resume``) come from
outside the process that reads them.  Unpickling either would run whatever code a crafted
file names.  This codec writes and reads only the types an example or a result is made of
(numbers, strings, tuples, lists, dicts, Fractions, and the named records below), each
rebuilt through its own validating constructor; anything else is refused on the way in
(:class:`UnsafeValue`) and on the way out (:class:`BadEncoding`).

    >>> from fractions import Fraction
    >>> decode(encode((1, Fraction(1, 3), [2.5, None], "x")))
    (1, Fraction(1, 3), [2.5, None], 'x')
"""

from __future__ import annotations

import base64
import json
import math
import numbers
import zlib
from fractions import Fraction

__all__ = ["encode", "decode", "to_text", "from_text", "UnsafeValue", "BadEncoding"]

#: the most a decoded text may inflate to (a compressed "bomb" is refused, not expanded)
MAX_BYTES = 64 << 20


class UnsafeValue(TypeError):
    """A value of a type the codec does not write (the replay is then left out)."""


class BadEncoding(ValueError):
    """A text that is not one this codec wrote: damaged, or crafted."""


def _records():
    """name -> (type, fields of the value, build from the fields): the records that may
    appear, each rebuilt by its own (validating) constructor."""
    from ..reference.combinatorics import Classification, Triangulation

    from .example import Example
    from .registry import PropertyFailure, TieDisagreement

    def triangulation(t):
        _, (faces, n, gluings) = t.__reduce__()          # its defining data, as it pickles
        return {"faces": [list(f) for f in faces], "n": n,
                "gluings": [[a, b, bool(r)] for a, b, r in gluings]}

    def example(x):
        fields = {f: getattr(x, f) for f in x.__dataclass_fields__ if f != "_cache"}
        return fields

    def build_example(d):
        d = dict(d)
        given = d.pop("_given", None)
        return Example(**d, _given=given)

    def failure(f):
        return {k: f.__dict__.get(k) for k in ("property_id", "implementation", "message", "mesh",
                                               "element", "expected", "observed", "bound")}

    def build_failure(cls):
        def build(d):
            f = cls.__new__(cls)
            f.__dict__.update(d)
            AssertionError.__init__(f, str(f))
            return f
        return build

    return {
        "Triangulation": (Triangulation, triangulation,
                          lambda d: Triangulation([tuple(f) for f in d["faces"]],
                                                  [tuple(g) for g in d["gluings"]], d["n"])),
        "Classification": (Classification,
                           lambda c: [c.orientable, c.genus, c.boundary_components,
                                      c.euler_characteristic],
                           lambda v: Classification(*v)),
        "Example": (Example, example, build_example),
        "TieDisagreement": (TieDisagreement, failure, build_failure(TieDisagreement)),
        "PropertyFailure": (PropertyFailure, failure, build_failure(PropertyFailure)),
    }


_RECORDS = None


def _table():
    global _RECORDS
    if _RECORDS is None:
        _RECORDS = _records()
    return _RECORDS


def encode(value, lenient: bool = False):
    """``value`` as a JSON-able structure (tags keep tuples, Fractions, floats and records
    apart from lists and dicts); ``lenient``: a value of another type becomes its ``repr``
    (for values shown, never decided on), else :class:`UnsafeValue`."""
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, numbers.Integral):
        return int(value)
    if isinstance(value, Fraction):
        return {"q": [value.numerator, value.denominator]}
    if isinstance(value, numbers.Real):
        return {"f": repr(float(value))}
    if isinstance(value, tuple):
        return {"t": [encode(v, lenient) for v in value]}
    if isinstance(value, list):
        return [encode(v, lenient) for v in value]
    if isinstance(value, dict):
        return {"d": [[encode(k, lenient), encode(v, lenient)] for k, v in value.items()]}
    for name, (cls, fields, _) in _table().items():
        if type(value) is cls:
            return {"r": name, "v": encode(fields(value), lenient)}
    if lenient:
        return repr(value)
    raise UnsafeValue(f"{type(value).__qualname__} is not a value the codec writes")


def decode(data):
    """The value :func:`encode` made; :class:`BadEncoding` for anything else."""
    if data is None or isinstance(data, (bool, str)):
        return data
    if isinstance(data, int):
        return data
    if isinstance(data, list):
        return [decode(v) for v in data]
    if not isinstance(data, dict) or len(data) not in (1, 2):
        raise BadEncoding(f"not an encoded value: {str(data)[:80]}")
    if set(data) == {"q"} and _ints(data["q"], 2) and data["q"][1] != 0:
        return Fraction(*data["q"])
    if set(data) == {"f"} and isinstance(data["f"], str):
        x = _float(data["f"])
        return x
    if set(data) == {"t"} and isinstance(data["t"], list):
        return tuple(decode(v) for v in data["t"])
    if set(data) == {"d"} and isinstance(data["d"], list) and \
            all(isinstance(p, list) and len(p) == 2 for p in data["d"]):
        return {_hashable(decode(k)): decode(v) for k, v in data["d"]}
    if set(data) == {"r", "v"} and data["r"] in _table():
        _, _, build = _table()[data["r"]]
        try:
            return build(decode(data["v"]))
        except (TypeError, ValueError, KeyError, IndexError) as e:
            raise BadEncoding(f"a {data['r']} that does not build: {e}") from None
    raise BadEncoding(f"not an encoded value: {str(data)[:80]}")


def _ints(v, n) -> bool:
    return isinstance(v, list) and len(v) == n and all(isinstance(x, int) and
                                                       not isinstance(x, bool) for x in v)


def _float(text: str) -> float:
    try:
        x = float(text)
    except ValueError:
        raise BadEncoding(f"not a float: {text[:40]!r}") from None
    if len(text) > 40 or (math.isfinite(x) and repr(x) != text and text not in ("-0.0",)):
        raise BadEncoding(f"not a float's repr: {text[:40]!r}")
    return x


def _hashable(k):
    try:
        hash(k)
    except TypeError:
        raise BadEncoding("a dict key that is not hashable") from None
    return k


def to_text(value, prefix: str) -> str:
    """``prefix`` + base64 of the zlib-compressed JSON of :func:`encode` (value)."""
    raw = json.dumps(encode(value), separators=(",", ":")).encode()
    return prefix + base64.b64encode(zlib.compress(raw, 9)).decode()


def from_text(text: str, prefix: str):
    """The value of a :func:`to_text` text with this ``prefix``; :class:`BadEncoding` for
    another prefix, bad base64, a compressed size past :data:`MAX_BYTES`, or JSON that is
    not an encoded value."""
    if not isinstance(text, str) or not text.startswith(prefix):
        raise BadEncoding(f"not a ddg-oracle value (expected text starting {prefix!r})")
    try:
        packed = base64.b64decode(text[len(prefix):], validate=True)
        inflate = zlib.decompressobj()
        raw = inflate.decompress(packed, MAX_BYTES)
        if inflate.unconsumed_tail:
            raise BadEncoding(f"the value inflates past {MAX_BYTES} bytes")
        data = json.loads(raw)
    except (ValueError, zlib.error) as e:
        raise BadEncoding(f"not a ddg-oracle value: {e}") from None
    return decode(data)
