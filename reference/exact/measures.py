"""Exact "angle times length" numbers: mean curvature (D2.3) and Steiner coefficients (T2.7).

An :class:`AngleLength` is a finite sum

    x = s_1 arccot(c_1) + ... + s_n arccot(c_n) + s_pi pi

with square-root numbers (:class:`~ddg_oracle.reference.exact.surds.Surd`) ``s_k``,
``s_pi`` and ``c_k``: an exact angle (:class:`~ddg_oracle.reference.exact.angles.Angle`)
multiplied by an exact length, and sums of such products.  The discrete mean
curvature H(e) = 1/2 theta(e) l(e) of an edge and the total mean curvature
H(S) are of this form.

How ``==`` and the sign are decided, exactly:

* A rigorous enclosure (each ``s_k`` and each ``arccot(c_k)`` enclosed, the
  products bounded by interval arithmetic).  If it excludes 0, the sign is known.
* An exact zero test.  Write every coefficient over one basis of square roots
  sqrt(r_1), sqrt(r_2), ... (pairwise coprime radicands, so the square roots
  are linearly independent over Q): x = sum_j sqrt(r_j) A_j, where each
  A_j = sum_k q_kj arccot(c_k) + q_pi,j pi has *rational* coefficients.  Each
  angle i arccot(c) = log((c + i)/|c + i|) and i pi = log(-1) is a logarithm of
  an algebraic number, so by Baker's theorem on linear forms in logarithms
  (1966: Q-linearly independent logarithms of algebraic numbers are linearly
  independent over the algebraic numbers) x = 0 if and only if every A_j = 0.
  A denominator-cleared A_j is an :class:`Angle` with integer multiplicities,
  and ``Angle.sign`` decides it exactly.
* Otherwise x != 0, and the enclosure is refined until it excludes 0; past
  ``arccots.PRECISION_LIMIT`` bits :class:`~ddg_oracle.reference.errors.Undecidable` is raised
  (this only happens for nonzero values closer to 0 than 2**-4096).

No float is used in a decision.  ``float(x)`` is correctly rounded: a nonzero
x is transcendental (Baker), so it is never a rounding midpoint and the
refinement terminates.

>>> from fractions import Fraction
>>> from ddg_oracle.reference.exact import corner_angle, pi, sqrt
>>> right = corner_angle(0)                     # dihedral angle of a cube edge
>>> H = AngleLength.of(right, Fraction(1, 2))   # H(e) = 1/2 theta l, l = 1
>>> 12 * H == 3 * pi                            # total mean curvature of the unit cube
True
>>> x = AngleLength.of(corner_angle(2), sqrt(2)) + AngleLength.of(corner_angle(3), sqrt(2))
>>> x == AngleLength.of(pi, sqrt(2) / 4)        # arccot 2 + arccot 3 = pi/4
True
>>> float(x) == float(sqrt(2)) * 0.7853981633974483
True
"""

from __future__ import annotations

import math
import numbers
from fractions import Fraction

from ..errors import InputError, Undecidable
from . import arccots
from .angles import Angle, arccot_bounds, pi_bounds
from .arccots import ArccotSum
from .rationals import rational
from .surds import Surd
from .terms import reexpress, refine

__all__ = ["AngleLength"]

_SCALARS = (int, Fraction, Surd, numbers.Rational)
_ZERO_SURD = Surd(0)


def _surd(k) -> Surd:
    if isinstance(k, Surd):
        return k
    if isinstance(k, bool) or not isinstance(k, (int, Fraction, numbers.Rational)):
        raise InputError(f"a coefficient must be an int, Fraction or Surd, got {k!r}")
    return Surd(rational(k))


class AngleLength(ArccotSum):
    """An exact real sum_k s_k arccot(c_k) + s_pi pi with Surd coefficients.

    Immutable and hashable.  Build with :meth:`of` (an Angle times a Surd) and
    add, subtract, negate, multiply or divide by ints, Fractions and Surds;
    Angles and the number 0 mix in sums and comparisons.  ``==``, ``<`` and
    :meth:`sign` are exact (see the module docstring).

    >>> from ddg_oracle.reference.exact import pi, sqrt
    >>> x = AngleLength.of(pi, sqrt(2))
    >>> x - x == 0, x > 0, x.pi_coefficient
    (True, True, Surd('sqrt(2)'))
    """

    __slots__ = ("_parts", "_pi", "_hash")

    def __init__(self, parts=None, pi_coefficient=0):
        """``parts``: {cotangent c: coefficient s}; the value is sum s arccot(c) + pi_coefficient pi."""
        clean: dict[Surd, Surd] = {}
        for c, s in (parts or {}).items():
            c = c if isinstance(c, Surd) else Surd(rational(c))
            s = _surd(s)
            clean[c] = clean.get(c, Surd(0)) + s
        self._parts = {c: s for c, s in clean.items() if s}
        self._pi = _surd(pi_coefficient)
        self._hash = None

    @classmethod
    def _raw(cls, parts, p):
        x = object.__new__(cls)
        x._parts = parts
        x._pi = p
        x._hash = None
        return x

    @classmethod
    def of(cls, angle: Angle, factor=1) -> "AngleLength":
        """The product ``factor * angle`` (factor: int, Fraction or Surd).

        >>> from ddg_oracle.reference.exact import corner_angle, sqrt
        >>> AngleLength.of(corner_angle(0), sqrt(8))
        AngleLength(sqrt(2)*pi)
        """
        if not isinstance(angle, Angle):
            raise InputError(f"AngleLength.of needs an Angle, got {angle!r}")
        s = _surd(factor)
        if not s:
            return cls._raw({}, Surd(0))
        r = angle.pi_coefficient
        return cls._raw({c: s if m == 1 else s * m for c, m in angle.parts.items()},
                        s * r if r else _ZERO_SURD)

    # -- arithmetic (addition and subtraction: ArccotSum) ---------------------------------

    @staticmethod
    def _coerce(other):
        """What mixes with an AngleLength: AngleLengths, Angles, and the number 0."""
        if isinstance(other, AngleLength):
            return other
        if isinstance(other, Angle):
            return AngleLength.of(other)
        if isinstance(other, (int, Fraction, float, Surd)) and not isinstance(other, bool) \
                and other == 0:
            return _ZERO_LENGTH
        return None

    def __mul__(self, k):
        if isinstance(k, bool) or not isinstance(k, _SCALARS):
            return NotImplemented
        k = _surd(k)
        if not k:
            return AngleLength._raw({}, Surd(0))
        return AngleLength._raw({c: s * k for c, s in self._parts.items()}, self._pi * k)

    __rmul__ = __mul__

    def __truediv__(self, k):
        if isinstance(k, bool) or not isinstance(k, _SCALARS):
            return NotImplemented
        k = _surd(k)
        if not k:
            raise ZeroDivisionError("AngleLength division by zero")
        return self * (1 / k)

    # -- exact decisions ------------------------------------------------------------

    def is_zero(self) -> bool:
        """x == 0, decided exactly by the per-square-root decomposition (Baker's theorem)."""
        if not self._parts:
            return not self._pi
        coefficients = list(self._parts.values()) + [self._pi]
        base = refine([b for s in coefficients for b in s.base])
        by_radicand: dict[int, tuple[dict, Fraction]] = {}
        items = list(self._parts.items()) + [(None, self._pi)]
        for c, s in items:
            for r, q in reexpress(s._terms, base).items():
                parts, p = by_radicand.get(r, ({}, Fraction(0)))
                if c is None:
                    p += q
                else:
                    parts[c] = parts.get(c, Fraction(0)) + q
                by_radicand[r] = (parts, p)
        for parts, p in by_radicand.values():
            den = math.lcm(p.denominator, *(q.denominator for q in parts.values()))
            angle = Angle({c: int(q * den) for c, q in parts.items()}, p * den)
            if angle.sign() != 0:
                return False
        return True

    def sign(self) -> int:
        """-1, 0 or 1, decided exactly (see the module docstring)."""
        if not self._parts:
            return self._pi.sign()
        bits = 64 + len(self._parts).bit_length()
        lo, hi = self._scaled_at(bits)
        if lo > 0:
            return 1
        if hi < 0:
            return -1
        if self.is_zero():
            return 0
        while bits <= arccots.PRECISION_LIMIT:
            bits *= 2
            lo, hi = self._scaled_at(bits)
            if lo > 0:
                return 1
            if hi < 0:
                return -1
        raise Undecidable(f"could not separate the nonzero value {self!r} from 0 with "
                          f"{arccots.PRECISION_LIMIT} bits; raise "
                          "ddg_oracle.reference.exact.arccots.PRECISION_LIMIT to decide it")

    # -- numerics ---------------------------------------------------------------------

    def interval_at(self, bits: int) -> tuple[Fraction, Fraction]:
        """A rigorous enclosure (lo, hi), every factor enclosed to ``bits`` bits."""
        lo, hi = self._scaled_at(bits)
        return Fraction(lo, 1 << 2 * bits), Fraction(hi, 1 << 2 * bits)

    def _scaled_at(self, bits: int) -> tuple[int, int]:
        """Integers lo <= x * 2**(2 bits) <= hi: every coefficient and every arccot (or pi)
        bounded at the scale 2**bits, the products by interval arithmetic on integers."""
        lo = hi = 0
        terms = [(s, arccot_bounds(c, bits)) for c, s in self._parts.items()]
        if self._pi:
            terms.append((self._pi, pi_bounds(bits)))
        for s, (alo, ahi) in terms:
            slo, shi = s.scaled_bounds(bits)
            if alo >= 0:                    # an angle's lower bound; 0 <= floor always
                lo += slo * (alo if slo >= 0 else ahi)
                hi += shi * (ahi if shi >= 0 else alo)
            else:                           # arccot(c) near 0 (c huge): a bound below 0
                ps = (slo * alo, slo * ahi, shi * alo, shi * ahi)
                lo, hi = lo + min(ps), hi + max(ps)
        return lo, hi

    def _interval_bits(self, bits: int) -> int:
        size = 1                       # an integer bound on sum |s_k| + |s_pi|
        for s in list(self._parts.values()) + [self._pi]:
            lo, hi = s.interval(1)
            size += math.ceil(max(abs(lo), abs(hi)))
        return bits + 4 + size.bit_length() + len(self._parts).bit_length()

    def __float__(self):
        """The correctly rounded float (see the module docstring)."""
        # the enclosure is absolute: 128 bits round values down to about 2^-70 in one
        # step (60 bits needed a second enclosure for most edges of a real mesh, |H| ~ 2^-13)
        bits = 128
        while True:
            lo, hi = self._scaled_at(bits)
            if lo <= 0 <= hi and self.sign() == 0:
                return 0.0
            # the int quotients are correctly rounded (Python's int division): when the
            # two ends agree, every number between them rounds to that float
            x = lo / (1 << 2 * bits)
            if x == hi / (1 << 2 * bits):
                # both ends round to a zero (maybe -0.0 from an end below 0): the correctly
                # rounded float has the value's own sign (exact)
                return x if x else math.copysign(0.0, self.sign())
            bits *= 2
            if bits > 4 * arccots.PRECISION_LIMIT:
                raise Undecidable(f"float({self!r}) did not converge")

    def __repr__(self):
        terms = [f"({s})*arccot({c})"
                 for c, s in sorted(self._parts.items(), key=lambda cs: float(cs[0]))]
        if self._pi or not terms:
            p = str(self._pi)
            terms.insert(0, f"{p}*pi" if self._pi.n_terms <= 1 else f"({p})*pi")
        return "AngleLength(" + " + ".join(terms) + ")"


_ZERO_LENGTH = AngleLength._raw({}, Surd(0))
