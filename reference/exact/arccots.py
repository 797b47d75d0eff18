"""The shared base of the exact transcendental numbers: sums of arccotangents and pi.

:class:`~ddg_oracle.reference.exact.angles.Angle` (integer multiplicities, a rational
multiple of pi: angle sums, angle defects) and
:class:`~ddg_oracle.reference.exact.measures.AngleLength` (square-root coefficients:
angle times length, mean curvature) are both finite sums

    x = s_1 arccot(c_1) + ... + s_n arccot(c_n) + s_pi pi

held as ``{c_k: s_k}`` and ``s_pi``.  What does not depend on the kind of coefficient is
written once here, as ``fractions.py`` writes its operators once: addition and
subtraction through one coercion hook, the comparisons and ``==`` through one exact
:meth:`ArccotSum.sign`, hashing through the correctly rounded ``float`` (so equal values
hash equal whatever their representation), and the certified enclosures and decimals
built on each class's :meth:`interval_at`.  Each class supplies its coefficients' zero,
its coercion (which numbers mix in), scalar multiplication, the sign and the enclosure.
"""

from __future__ import annotations

import math
import operator
from fractions import Fraction

__all__ = ["ArccotSum", "PRECISION_LIMIT"]

#: Refinement of an enclosure stops here (bits of absolute precision); past it a nonzero
#: value still not separated from 0 raises Undecidable (both classes, one setting).
PRECISION_LIMIT = 4096


class ArccotSum:
    """sum_k s_k arccot(c_k) + s_pi pi, exact; the common part of its two kinds.

    Subclasses define ``_coerce(other)`` (an instance of the class for what mixes in, or
    None), ``_raw(parts, pi_coefficient)``, ``_ZERO`` (the zero coefficient),
    :meth:`sign`, :meth:`interval_at`, ``_interval_bits(bits)`` (the first precision to
    try for an enclosure of width 2**-bits), ``__float__`` and ``__repr__``.
    """

    __slots__ = ()

    # -- structure -------------------------------------------------------------------------

    @property
    def parts(self) -> dict:
        """Copy of {cotangent c: coefficient} of the primitive angles arccot(c)."""
        return dict(self._parts)

    @property
    def pi_coefficient(self):
        """s_pi in x = sum s_k arccot(c_k) + s_pi pi (not unique for an Angle: see
        ``as_multiple_of_pi``)."""
        return self._pi

    # -- addition, once ------------------------------------------------------------------------

    def __add__(self, other):
        o = self._coerce(other)
        if o is None:
            return NotImplemented
        if not o._parts and not o._pi:
            return self
        parts = dict(self._parts)
        for c, s in o._parts.items():
            t = parts.get(c)
            t = s if t is None else t + s
            if t:
                parts[c] = t
            else:
                parts.pop(c, None)
        return self._raw(parts, self._pi + o._pi)

    __radd__ = __add__

    def __neg__(self):
        return self._raw({c: -s for c, s in self._parts.items()}, -self._pi)

    def __pos__(self):
        return self

    def __sub__(self, other):
        o = self._coerce(other)
        if o is None:
            return NotImplemented
        return self + (-o)

    def __rsub__(self, other):
        o = self._coerce(other)
        if o is None:
            return NotImplemented
        return o + (-self)

    # -- comparisons, once, through the exact sign ------------------------------------------------

    def _difference_sign(self, other):
        o = self._coerce(other)
        if o is None:
            return None
        return (self - o).sign() if (o._parts or o._pi) else self.sign()

    def _comparison(op):
        def compare(self, other):
            s = self._difference_sign(other)
            return NotImplemented if s is None else op(s, 0)
        compare.__name__ = f"__{op.__name__}__"
        compare.__doc__ = f"``{op.__name__}``, decided exactly (the sign of the difference)."
        return compare

    __eq__ = _comparison(operator.eq)
    __ne__ = _comparison(operator.ne)
    __lt__ = _comparison(operator.lt)
    __le__ = _comparison(operator.le)
    __gt__ = _comparison(operator.gt)
    __ge__ = _comparison(operator.ge)
    del _comparison

    def __bool__(self):
        return self.sign() != 0

    def __hash__(self):
        # float() is correctly rounded, hence a function of the value alone: equal numbers
        # (also an equal number of the other kind, or 0) hash equal.
        if self._hash is None:
            try:
                self._hash = hash(float(self))
            except OverflowError:
                # beyond the float range: a multiple of pi or a sum of arccots is never a
                # rational there, so one hash per sign keeps equal values hashing equal
                self._hash = hash(math.copysign(math.inf, self.sign()))
        return self._hash

    # -- enclosures, once ----------------------------------------------------------------

    def interval(self, bits: int) -> tuple[Fraction, Fraction]:
        """A rigorous enclosure (lo, hi) of width at most 2**-bits."""
        b = self._interval_bits(bits)
        while True:
            lo, hi = self.interval_at(b)
            if hi - lo <= Fraction(1, 1 << bits):
                return lo, hi
            b += 16

    def enclosure(self, digits: int = 30) -> tuple[Fraction, Fraction]:
        """Certified (lo, hi) with lo <= x <= hi and hi - lo <= 10**-digits."""
        return self.interval(math.ceil(digits * 3.3219280948873626) + 1)

    def decimal(self, digits: int = 30) -> str:
        """x as a decimal string with ``digits`` decimals, certified: the string is the
        midpoint of an enclosure of width 10**-(digits+2), rounded, so
        |s - x| <= 0.51 * 10**-digits."""
        lo, hi = self.enclosure(digits + 2)
        q = round((lo + hi) / 2 * 10 ** digits)
        sign = "-" if q < 0 else ""
        s = str(abs(q)).rjust(digits + 1, "0")
        return f"{sign}{s[:-digits]}.{s[-digits:]}" if digits else f"{sign}{s}"
