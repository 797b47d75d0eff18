"""Closed rational intervals: the certified filter in front of exact decisions.

An :class:`Interval` ``[lo, hi]`` with Fraction ends encloses an exact value; sums,
differences, products, squares and quotients of intervals enclose the results (interval
arithmetic, no rounding: the ends are rationals).  A decision first asks the cheap
enclosure (:meth:`Interval.sign` is 1 or -1 when the interval excludes 0) and falls
back to exact arithmetic only when it contains 0: the filters of the A3.6 area
certificate (:mod:`~ddg_oracle.reference.minimal`) and of the harmonic-index decrease
(:mod:`~ddg_oracle.reference.delaunay`) are written with it.

>>> from ddg_oracle.reference.exact import sqrt
>>> x = Interval.enclosing(sqrt(2), 20)
>>> (x * x).sign(), (x * x - 2).sign()          # 2 > 0 decided; x^2 - 2 contains 0
(1, None)
>>> Interval(1, 2) / Interval(4, 8)
Interval(Fraction(1, 8), Fraction(1, 2))
"""

from __future__ import annotations

import math
from fractions import Fraction

__all__ = ["Interval", "dot", "scaled_bounds", "top_bit", "terms_top_bit"]


class Interval:
    """The closed interval [lo, hi] of rationals (lo <= hi), immutable.

    Arithmetic with Intervals and with exact rationals (ints, Fractions) encloses the
    exact results; unpacking gives ``(lo, hi)``."""

    __slots__ = ("lo", "hi")

    def __init__(self, lo, hi=None):
        lo = Fraction(lo)
        hi = lo if hi is None else Fraction(hi)
        if hi < lo:
            raise ValueError(f"an interval needs lo <= hi, got [{lo}, {hi}]")
        self.lo, self.hi = lo, hi

    @classmethod
    def _raw(cls, lo, hi):
        x = object.__new__(cls)
        x.lo, x.hi = lo, hi
        return x

    @classmethod
    def enclosing(cls, x, bits: int) -> "Interval":
        """An enclosure of the exact value ``x``: a rational encloses itself, anything with
        ``interval(bits)`` (Surd, Angle, AngleLength) to width 2**-bits."""
        if type(x) is not Fraction:
            if hasattr(x, "interval"):
                return cls._raw(*x.interval(bits))
            x = Fraction(x)
        return cls._raw(x, x)           # one object at both ends: a point (see __mul__)

    @classmethod
    def relative(cls, x, bits: int) -> "Interval":
        """:meth:`enclosing` ``x`` to about ``bits`` bits below its largest term
        (:func:`top_bit`): values of a mesh scaled by 2^-1200 are enclosed as finely,
        relative to their size, as those of a unit mesh.

        >>> from ddg_oracle.reference.exact import sqrt
        >>> Interval.relative(sqrt(2) / 2**3000, 64).sign()
        1
        """
        if type(x) is Fraction:
            return cls._raw(x, x)        # a rational encloses itself: no size needed
        return cls.enclosing(x, max(0, bits - top_bit(x)))

    @staticmethod
    def _of(x):
        return x if isinstance(x, Interval) else Interval(x)

    def __iter__(self):
        yield self.lo
        yield self.hi

    def __repr__(self):
        return f"Interval({self.lo!r}, {self.hi!r})"

    def __eq__(self, other):
        return isinstance(other, Interval) and (self.lo, self.hi) == (other.lo, other.hi)

    def __hash__(self):
        return hash((self.lo, self.hi))

    # -- arithmetic ------------------------------------------------------------------------

    def __add__(self, other):
        o = self._of(other)
        return Interval._raw(self.lo + o.lo, self.hi + o.hi)

    __radd__ = __add__

    def __neg__(self):
        return Interval._raw(-self.hi, -self.lo)

    def __sub__(self, other):
        o = self._of(other)
        return Interval._raw(self.lo - o.hi, self.hi - o.lo)

    def __rsub__(self, other):
        return self._of(other) - self

    def __mul__(self, other):
        o = self._of(other)
        a, b, c, d = self.lo, self.hi, o.lo, o.hi
        # the cases filters meet most, with fewer products than the general four
        if a is b and c is d:                           # two points (rationals)
            p = a * c
            return Interval._raw(p, p)
        if a >= 0 and c >= 0:
            return Interval._raw(a * c, b * d)
        ps = (a * c, a * d, b * c, b * d)
        return Interval._raw(min(ps), max(ps))

    __rmul__ = __mul__

    def __truediv__(self, other):
        o = self._of(other)
        c, d = o.lo, o.hi
        if c <= 0 <= d:
            raise ZeroDivisionError(f"division by an interval containing 0: {o!r}")
        a, b = self.lo, self.hi
        if a is b and c is d:                           # two points (rationals)
            q = a / c
            return Interval._raw(q, q)
        if a >= 0 and c > 0:
            return Interval._raw(a / d, b / c)
        return self * Interval._raw(1 / d, 1 / c)

    def square(self) -> "Interval":
        """The enclosure of x^2 for x in the interval (tighter than ``self * self``)."""
        lo, hi = self.lo, self.hi
        if lo >= 0:
            return Interval._raw(lo * lo, hi * hi)
        if hi <= 0:
            return Interval._raw(hi * hi, lo * lo)
        return Interval._raw(Fraction(0), max(lo * lo, hi * hi))

    def clamped_below(self, floor) -> "Interval":
        """The interval intersected with [floor, inf): for a value known to be >= floor."""
        return Interval._raw(max(self.lo, floor), max(self.hi, floor))

    # -- decisions -------------------------------------------------------------------------

    def sign(self) -> int | None:
        """1 or -1 when the interval excludes 0, None when it does not decide."""
        if self.lo > 0:
            return 1
        if self.hi < 0:
            return -1
        return None

    @property
    def width(self) -> Fraction:
        return self.hi - self.lo


def dot(u, v) -> Interval:
    """The enclosure of the inner product of two vectors of intervals (squares where the
    same interval meets itself)."""
    acc = Interval._raw(Fraction(0), Fraction(0))
    for a, b in zip(u, v):
        acc = acc + (a.square() if a is b else a * b)
    return acc


def top_bit(x) -> int:
    """t with every term of the exact number ``x`` below 2^t in absolute value (an int or
    Fraction: x itself; a Surd: its terms q sqrt(r); a number with its own ``top_bit()``,
    :class:`~.lazy.Lazy`: its enclosure's); read off bit lengths, no arithmetic.

    >>> top_bit(Fraction(3, 4)), top_bit(Fraction(1, 2**100))
    (0, -99)
    """
    if hasattr(x, "top_bit"):
        return x.top_bit()
    pairs = (x.terms() if hasattr(x, "terms")
             else ((1, x if type(x) is Fraction else Fraction(x)),))
    return terms_top_bit(pairs)


def terms_top_bit(pairs) -> int:
    """:func:`top_bit` of the sum of ``q sqrt(r)`` over the pairs ``(r, q)`` (0 for none):
    |q| < 2^(bits(num) - bits(den) + 1) and sqrt(r) <= 2^ceil(bits(r) / 2).

    >>> terms_top_bit([(2, Fraction(3))]), terms_top_bit([(1, Fraction(-1, 8)), (3, 1)])
    (3, 2)
    """
    return max((abs(q.numerator).bit_length() - q.denominator.bit_length() + 1
                + (r.bit_length() + 1) // 2 - (r == 1) for r, q in pairs), default=0)


def scaled_bounds(x, k: int) -> tuple[int, int]:
    """Integers ``lo <= x * 2**k <= hi``, ``hi - lo <= 2`` (equal when ``x * 2**k`` is an
    integer), for an exact number ``x``: an int, a Fraction, a float (taken exactly) or
    anything with ``scaled_bounds`` (:meth:`~ddg_oracle.reference.exact.Surd.scaled_bounds`).
    Interval arithmetic on integers at one absolute scale 2**-k starts here: sums of such
    bounds are bounds, products of two are bounds at the scale 2**-2k.

    >>> scaled_bounds(Fraction(1, 3), 4), scaled_bounds(0.75, 2), scaled_bounds(-1, 3)
    ((5, 6), (3, 3), (-8, -8))
    """
    if isinstance(x, int):
        return x << k, x << k
    if hasattr(x, "scaled_bounds"):
        return x.scaled_bounds(k)
    q = Fraction(x) * (1 << k)
    return math.floor(q), math.ceil(q)
