"""The floats an implementation receives: representable at the precision it declares.

A float32 implementation (``machine_epsilon = 2**-23``) reads its input as float32.  Drawn
coordinates that float32 cannot hold (2**-60-scaled meshes, float64 jitter) would be
rounded by the implementation itself, and the exact reference, computed on the float64
values, would fail it for errors that come only from that rounding.  So the strategies
round every coordinate they draw to the *input format* of the implementation being
checked (:func:`representable`), and keep their scales and offsets inside that format's
range (:func:`input_format`): the implementation receives exactly the numbers the
reference computes with, whatever its precision.

The runner sets the format per task (:func:`inputs_at`, from the implementation's
declared epsilon); outside it, float64.  IEEE binary64, binary32 and binary16 are
known; any other declared epsilon gets float64 inputs.
"""

from __future__ import annotations

import contextlib
import contextvars
import math
import struct
from dataclasses import dataclass
from fractions import Fraction

__all__ = ["InputFormat", "FORMATS", "inputs_at", "input_format", "representable", "rounded_to"]


@dataclass(frozen=True)
class InputFormat:
    """An IEEE binary format: ``bits`` of significand, the struct code that rounds to it,
    and how far the strategies may scale and move a mesh in it: ``scale`` (binary
    exponents of scaled meshes, |k| <= scale), ``offset`` (a move by 2**e times the
    mesh's size, e <= offset, keeps >= 12 bits of its edges), ``sliver`` (needles and
    caps down to 2**-sliver keep >= 12 bits)."""

    name: str
    bits: int
    code: str
    scale: int
    offset: int
    sliver: int


FORMATS = {
    53: InputFormat("float64", 53, "d", 60, 30, 30),
    24: InputFormat("float32", 24, "f", 20, 10, 12),
    11: InputFormat("float16", 11, "e", 4, 0, 0),
}

_format: contextvars.ContextVar[InputFormat] = contextvars.ContextVar(
    "ddg_input_format", default=FORMATS[53])


def format_of(epsilon: float) -> InputFormat:
    """The input format of an implementation declaring machine epsilon ``epsilon``
    (2**-(bits - 1)); float64 for an epsilon of no IEEE format.

    >>> format_of(2.0 ** -23).name, format_of(2.0 ** -52).name, format_of(1e-10).name
    ('float32', 'float64', 'float64')
    """
    bits = 1 - math.log2(epsilon) if epsilon > 0 else 53
    return FORMATS.get(int(bits), FORMATS[53]) if bits == int(bits) else FORMATS[53]


@contextlib.contextmanager
def inputs_at(epsilon: float):
    """Draw inputs for an implementation of machine epsilon ``epsilon`` inside this block."""
    token = _format.set(format_of(epsilon))
    try:
        yield
    finally:
        _format.reset(token)


def input_format() -> InputFormat:
    """The format of the implementation whose examples are being drawn now."""
    return _format.get()


def rounded_to(fmt: InputFormat, x: float) -> float:
    """The float ``x`` rounded to the nearest number of ``fmt`` (as a float64); an infinity
    beyond its range (IEEE rounding, as a cast in the implementation would give).

    >>> rounded_to(FORMATS[24], 0.1) == 0.10000000149011612
    True
    >>> rounded_to(FORMATS[24], 1e39), rounded_to(FORMATS[11], -70000.0)
    (inf, -inf)
    """
    try:
        return struct.unpack(fmt.code, struct.pack(fmt.code, x))[0]
    except OverflowError:        # struct rounds to inf for "f" but refuses for "e": one rule
        return math.copysign(math.inf, x)


def representable(x) -> Fraction:
    """``x`` (a rational) rounded to the nearest number of the current input format, taken
    exactly; OverflowError beyond its range (the strategies then draw another example).

    >>> representable(Fraction(1, 3)) == Fraction(1 / 3)
    True
    >>> with inputs_at(2.0 ** -23):
    ...     representable(Fraction(1, 3)) == Fraction(11184811, 33554432)
    True
    """
    f = float(x)
    fmt = _format.get()
    if fmt.bits == 53:
        if math.isinf(f):
            raise OverflowError(f"{x} is beyond the float64 range")
        return Fraction(f)
    # float64 first, then the format: double rounding may differ from rounding once in a
    # halfway case, and the result is representable either way (what the implementation
    # receives is what the reference computes with)
    return Fraction(rounded_to(fmt, f))
