"""Exact rationals: conversion of user input to ``fractions.Fraction``.

Every float is a dyadic rational, so ``Fraction(x)`` takes it exactly; what is
not a finite real number is rejected with an error naming the value and where.
"""

from __future__ import annotations

import math
import numbers
from decimal import Decimal
from fractions import Fraction

from ..errors import NonFiniteValue, NotANumber


def rational(x, where: str = "") -> Fraction:
    """``x`` as an exact ``Fraction``; ints, Fractions, floats, Decimals, numpy scalars.

    Floats are converted exactly (``rational(0.1)`` is 3602879701896397/36028797018963968).
    NaN and infinities raise :class:`NonFiniteValue`; bools, strings, None and
    complex numbers raise :class:`NotANumber`.  ``where`` (e.g. "vertex 3,
    coordinate 1") is put in the message.

    >>> rational(0.5), rational(3), rational(Fraction(2, 6))
    (Fraction(1, 2), Fraction(3, 1), Fraction(1, 3))
    """
    at = f" at {where}" if where else ""
    if isinstance(x, Fraction):
        return x
    if isinstance(x, bool) or not isinstance(x, (numbers.Real, Decimal)):
        raise NotANumber(f"expected a real number{at}, got {x!r} ({type(x).__name__})")
    if isinstance(x, numbers.Integral):
        return Fraction(int(x))
    if isinstance(x, numbers.Rational):
        return Fraction(int(x.numerator), int(x.denominator))
    if isinstance(x, Decimal):
        if not x.is_finite():
            raise NonFiniteValue(f"non-finite value {x}{at}")
        return Fraction(x)
    # floats, numpy floating types (float32, longdouble): as_integer_ratio is
    # exact for all of them, where float(x) would round a longdouble.
    try:
        n, d = x.as_integer_ratio()
    except (ValueError, OverflowError):
        raise NonFiniteValue(f"non-finite value {x}{at}") from None
    except AttributeError:
        f = float(x)
        if not math.isfinite(f):
            raise NonFiniteValue(f"non-finite value {f}{at}") from None
        return Fraction(f)
    return Fraction(int(n), int(d))


def float_view(x) -> float:
    """The correctly rounded float of an exact number (int, Fraction, Surd, angle): its
    ``float()``, or +-inf beyond the float range (IEEE round to nearest), where Python's
    ``float()`` raises OverflowError.  Exact: decided by the number's own rounding and sign.

    >>> float_view(Fraction(1, 3)) == 1 / 3
    True
    >>> float_view(-10 ** 400), float_view(Fraction(10 ** 400, 3))
    (-inf, inf)
    """
    try:
        return float(x)
    except OverflowError:
        return math.inf if x > 0 else -math.inf


def on_common_denominator(values) -> tuple[list[int], int]:
    """(integers X, D): rationals x = X / D over their least common denominator D > 0, so
    that sums and products of them are integer arithmetic (floats: D a power of two).

    >>> on_common_denominator([Fraction(1, 2), Fraction(3, 4), 2])
    ([2, 3, 8], 4)
    """
    values = [x if type(x) is Fraction else Fraction(x) for x in values]
    D = 1
    for x in values:
        d = x.denominator
        if D % d:
            D = D // math.gcd(D, d) * d
    return [x.numerator * (D // x.denominator) for x in values], D


#: positions whose least common denominator has at most this many bits are put over it once
#: (a float mesh: the spread of its binary exponents); beyond, one denominator per element
#: (per edge, per face) keeps the integers small
SHARED_DENOMINATOR_BITS = 128


def shared_denominator(points, max_bits: int = SHARED_DENOMINATOR_BITS
                       ) -> tuple[list[tuple[int, ...]], int] | None:
    """(integer points, D): every point of ``points`` (tuples of Fractions) over their
    least common denominator D, or None when D has more than ``max_bits`` bits (then one
    denominator per element keeps the integers small: :func:`points_on_common_denominator`).

    >>> shared_denominator([(Fraction(1, 2), 1), (0, Fraction(1, 4))], 8)
    ([(2, 4), (0, 1)], 4)
    >>> shared_denominator([(Fraction(1, 2**9),)], 8) is None
    True
    """
    # Fraction(x) of a Fraction goes through an abstract-base-class check: it was a third
    # of the cotan weights' time on a float mesh, whose coordinates all are Fractions
    if not {type(x) for p in points for x in p} <= {Fraction, int}:
        points = [tuple(map(Fraction, p)) for p in points]
    return shared_denominator_of_fractions(points, {len(p) for p in points} == {3}, max_bits)


def shared_denominator_of_fractions(points, in_r3: bool,
                                    max_bits: int = SHARED_DENOMINATOR_BITS
                                    ) -> tuple[list[tuple[int, ...]], int] | None:
    """:func:`shared_denominator` of points whose coordinates are known to be Fractions
    or ints (a :class:`~ddg_oracle.reference.polyhedral.PolyhedralSurface`'s positions),
    ``in_r3`` whether each has three: the same result without checking them (two passes
    over every coordinate, 7% of the Gauss-Bonnet decision on a float mesh).

    >>> shared_denominator_of_fractions([(Fraction(1, 2), 1, 0)], True)
    ([(1, 2, 0)], 2)
    """
    D = math.lcm(*{x.denominator for p in points for x in p})
    if D.bit_length() > max_bits:
        return None
    if in_r3:                                       # points in R^3, written out (2x faster)
        return [(x.numerator * (D // x.denominator), y.numerator * (D // y.denominator),
                 z.numerator * (D // z.denominator)) for x, y, z in points], D
    return [tuple(x.numerator * (D // x.denominator) for x in p) for p in points], D


def points_on_common_denominator(*points) -> tuple[list[list[int]], int]:
    """(integer points, D): rational points over one positive common denominator D.

    >>> points_on_common_denominator((Fraction(1, 2), 1), (0, Fraction(1, 4)))
    ([[2, 4], [0, 1]], 4)
    """
    flat, D = on_common_denominator([x for p in points for x in p])
    n = len(points[0])
    return [flat[k:k + n] for k in range(0, len(flat), n)], D
