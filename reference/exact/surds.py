"""Exact square-root numbers: finite sums ``q1*sqrt(r1) + q2*sqrt(r2) + ...``.

A :class:`Surd` is an exact real number of the form ``sum q_i * sqrt(r_i)``
with rational ``q_i`` and positive integer ``r_i``; these numbers form a field
(closed under ``+ - * /``), comparisons and signs are decided exactly, and
``float()`` is correctly rounded.  The design follows ``fractions.Fraction``:
one canonical form set when a value is built, operators written once and
turned into forward and reverse methods by a helper.

>>> x = sqrt(2) + sqrt(3)
>>> x * x
Surd('5 + 2*sqrt(6)')
>>> x * x - 5 - 2 * sqrt(6) == 0
True
>>> 1 / x
Surd('-sqrt(2) + sqrt(3)')
>>> sqrt(2) + sqrt(3) < sqrt(10)      # 5 + 2*sqrt(6) = 9.899 < 10
True
>>> float(sqrt(2))
1.4142135623730951

Canonical form
--------------
Integers are never factored.  Every value carries a *base*: a sorted tuple of
pairwise coprime integers > 1, none of them a perfect square.  Its terms map
a *radicand* -- the product of a subset of the base, 1 for the rational
part -- to a nonzero ``Fraction``.  Pairwise coprime non-squares are
independent modulo squares, so the square roots of distinct subset products
are linearly independent over Q (Besicovitch).  Hence, over a common base, a
value is zero iff it has no terms, and two values are equal iff their term
dicts are equal.  Values over different bases are brought to the common
coprime refinement of both bases (gcd splitting, no factoring) before any
operation.  ``sqrt(m)`` strips squares of the primes below 100 at once
(``sqrt(12)`` is ``2*sqrt(3)``), and every result keeps only the base
elements its radicands use, so equal numbers usually end up with identical
representations; see :class:`Surd` for the exception.

Exactness guards
----------------
A product of sums can have as many terms as the product of the term counts.
``settings.term_limit`` (default 4096) bounds the number of terms of every
result; exceeding it raises :class:`~ddg_oracle.reference.errors.TermLimitExceeded`.
Use ``with limits(term_limit=N):`` to change it temporarily.  The setting is
process-wide (not thread-local).
"""

from __future__ import annotations

import math
import numbers
import operator
import re
from contextlib import contextmanager
from fractions import Fraction
from math import isqrt

from ..errors import InputError, TermLimitExceeded
from .terms import (pruned_base, reexpress, refine, strip_small_squares, t_add, t_bounds,
                    t_mul, t_scale, t_sign, t_split)
from .rationals import float_view, rational

__all__ = ["Surd", "Quotient", "sqrt", "simplest", "exact_sum", "rounded_sum", "sum_is_zero",
           "rounded_root_sum", "settings", "limits"]


# --- settings ----------------------------------------------------------------


class _Settings:
    """Guards of the exact arithmetic (process-wide).

    ``term_limit``: the largest number of terms a :class:`Surd` may have.
    """

    __slots__ = ("term_limit",)

    def __init__(self):
        self.term_limit = 4096

    def __repr__(self):
        return f"settings(term_limit={self.term_limit})"


settings = _Settings()


def _check_limit(value, name):
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < 1:
        raise InputError(f"{name} must be a positive integer, got {value!r}")
    return int(value)


@contextmanager
def limits(term_limit=None):
    """Temporarily change the guards; ``None`` keeps the current value.

    >>> with limits(term_limit=8):
    ...     settings.term_limit
    8
    >>> settings.term_limit
    4096
    """
    old = settings.term_limit
    if term_limit is not None:
        settings.term_limit = _check_limit(term_limit, "term_limit")
    try:
        yield settings
    finally:
        settings.term_limit = old


# --- the number type ---------------------------------------------------------

_ZERO = Fraction(0)
_ONE = Fraction(1)


def from_terms(base, terms, prune=True):
    """A Surd from canonical parts: ``terms`` (no zero coefficient) over ``base``, every
    radicand a product of base elements; ``prune``: keep only the base elements the
    radicands use.  Checks the term limit.  For exact kernels that build the terms of
    many numbers themselves (:mod:`ddg_oracle.reference.cotangents`)."""
    n = len(terms)
    if n > 1 and n > settings.term_limit:
        raise TermLimitExceeded(
            f"a square-root number would have {n} terms, more than the term limit "
            f"{settings.term_limit}; raise it with "
            f"`with ddg_oracle.reference.exact.limits(term_limit=...)`")
    self = object.__new__(Surd)
    self._base = pruned_base(base, terms) if prune else base
    self._terms = terms
    self._hash = None
    return self


def _from_fraction(q):
    self = object.__new__(Surd)
    self._base = ()
    self._terms = {1: q} if q else {}
    self._hash = None
    return self


def _common(a, b):
    """``(base, terms_a, terms_b, refined)`` with both term dicts over ``base``."""
    ba, bb = a._base, b._base
    if ba == bb or not bb:
        return ba, a._terms, b._terms, False
    if not ba:
        return bb, a._terms, b._terms, False
    if len(ba) <= len(bb):
        if all(x in bb for x in ba):
            return bb, a._terms, b._terms, False
    elif all(x in ba for x in bb):
        return ba, a._terms, b._terms, False
    base = refine(bb, coprime=ba) if len(ba) >= len(bb) else refine(ba, coprime=bb)
    ta, tb = a._terms, b._terms
    if not all(x in base for x in ba):
        ta = reexpress(ta, base)
    if not all(x in base for x in bb):
        tb = reexpress(tb, base)
    return base, ta, tb, True


_TERM = re.compile(r"""
    \s*(?P<sign>[-+])?\s*
    (?:
        (?P<coef>\d+(?:/\d+)?)(?:\s*\*\s*sqrt\(\s*(?P<rad1>\d+)\s*\))?
      | sqrt\(\s*(?P<rad2>\d+)\s*\)
    )\s*
""", re.VERBOSE)


def _parse(text):
    total = Surd()
    pos, first = 0, True
    while pos < len(text) or first:
        m = _TERM.match(text, pos)
        if m is None or m.end() == pos or (not first and m["sign"] is None):
            raise InputError(f"invalid Surd literal {text!r}")
        coef = Fraction(m["coef"]) if m["coef"] else _ONE
        rad = m["rad1"] or m["rad2"]
        term = sqrt(int(rad)) * coef if rad else Surd(coef)
        total = total - term if m["sign"] == "-" else total + term
        pos, first = m.end(), False
    return total


def _short(x, width=60):
    """``str(x)`` cut to ``width`` characters, for error messages."""
    s = str(x)
    return s if len(s) <= width else s[:width - 3] + "..."


def _rebuild(base, items):
    return from_terms(tuple(base), dict(items), prune=False)


#: :meth:`Surd.quotients` keeps n / d as the pair only for a denominator of more terms
QUOTIENT_TERMS = 4


class Surd:
    """An exact real number ``q1*sqrt(r1) + q2*sqrt(r2) + ...``.

    Build one from an int, Fraction, float (taken exactly), another Surd, or
    a string as printed by ``str``; square roots come from :func:`sqrt`.

    >>> Surd(Fraction(3, 2)) + 2 * sqrt(6)
    Surd('3/2 + 2*sqrt(6)')
    >>> Surd('3/2 + 2*sqrt(6)').terms()
    ((1, Fraction(3, 2)), (6, Fraction(2, 1)))
    >>> Surd(0.5) == Fraction(1, 2), hash(Surd(0.5)) == hash(0.5)
    (True, True)

    Representations are canonical *relative to the base* (see the module
    docstring).  Integers are not factored, so ``sqrt(p*p*q)`` for a prime
    ``p`` above 100 is stored as the square root of ``p*p*q`` and ``p*sqrt(q)``
    as a multiple of ``sqrt(q)``: the two have different bases (and reprs)
    until they meet in one operation, where the common refinement finds ``p``
    and they compare equal.  ``==``, ``<`` and ``hash`` are always exact and
    consistent with each other and with int, Fraction and float.
    """

    __slots__ = ("_base", "_terms", "_hash")

    def __new__(cls, x=0):
        if isinstance(x, Surd):
            if type(x) is cls:
                return x
            self = object.__new__(cls)
            self._base, self._terms, self._hash = x._base, x._terms, x._hash
            return self
        if isinstance(x, str):
            x = _parse(x)
            return x if cls is Surd else cls(x)
        q = rational(x)
        self = object.__new__(cls)
        self._base = ()
        self._terms = {1: q} if q else {}
        self._hash = None
        return self

    # --- inspection ---------------------------------------------------------

    @classmethod
    def quotients(cls, numerators, d) -> list:
        """``[n / d for n in numerators]``, exact (``d`` nonzero).  An irrational quotient of
        an irrational ``d`` is a :class:`SurdQuotient`: a Surd that keeps the pair and
        divides only if its canonical form is asked for.  After intrinsic flips a cotangent
        n / (4 A) has coefficients of tens of thousands of bits where n and A have hundreds
        (the division took most of T2.5's time); its sign, enclosures, float, hash and the
        exact zero test of angles (:mod:`.angles`, :attr:`ratio`) work from the pair.

        A ``d`` of at most :data:`QUOTIENT_TERMS` terms (a face area of a float mesh: one)
        is inverted at once, as before, and its quotients are plain Surds: their division is
        cheap, and a pair would only cost the angles' exact tests a division per corner.

        >>> d = 1 + sqrt(2) + sqrt(3) + sqrt(5) + sqrt(7)
        >>> q = Surd.quotients([1, 2 * d], d)
        >>> q[0] * d == 1, q[0].ratio == (1, d), q[1]
        (True, True, Surd('2'))
        >>> Surd.quotients([1], 1 + sqrt(2))[0].ratio is None       # a small d: divided
        True
        """
        if not (isinstance(d, Surd) and d._base and len(d._terms) > QUOTIENT_TERMS):
            inv = 1 / d
            return [n * inv for n in numerators]
        d = Surd(d)
        sign = d.sign()
        out = []
        for n in numerators:
            n = Surd(n)
            k = _proportion(n, d)
            out.append(Surd(k) if k is not None else SurdQuotient(sign * n, sign * d))
        return out

    @property
    def ratio(self):
        """``(n, d)`` (Surds, d > 0) with this number == n / d exactly, when it is kept as
        that quotient (:class:`SurdQuotient`); else None."""
        return None

    def terms(self):
        """``((radicand, coefficient), ...)`` sorted by radicand; 1 is the rational part.

        >>> (1 + sqrt(8)).terms()
        ((1, Fraction(1, 1)), (2, Fraction(2, 1)))
        """
        return tuple(sorted(self._terms.items()))

    @property
    def n_terms(self):
        """Number of nonzero terms (0 for zero)."""
        return len(self._terms)

    @property
    def base(self):
        """The pairwise coprime non-square integers the radicands are built from."""
        return self._base

    def is_rational(self):
        """True iff the value is rational.

        >>> sqrt(8).is_rational(), (sqrt(2) * sqrt(8)).is_rational()
        (False, True)
        """
        return not self._base

    def as_fraction(self):
        """The value as a Fraction; ValueError if it is irrational.

        >>> (sqrt(3) * sqrt(12)).as_fraction()
        Fraction(6, 1)
        """
        if self._base:
            raise ValueError(f"{_short(self)} is irrational, it has no Fraction value")
        return self._terms.get(1, _ZERO)

    def __repr__(self):
        return f"Surd('{self}')"

    def __str__(self):
        parts = []
        for r, q in sorted(self._terms.items()):
            if r == 1:
                s = str(q)
            elif q == 1:
                s = f"sqrt({r})"
            elif q == -1:
                s = f"-sqrt({r})"
            else:
                s = f"{q}*sqrt({r})"
            if parts:
                parts.append(f" - {s[1:]}" if s[0] == "-" else f" + {s}")
            else:
                parts.append(s)
        return "".join(parts) or "0"

    def __reduce__(self):
        return (_rebuild, (self._base, tuple(self._terms.items())))

    def __copy__(self):
        return self

    def __deepcopy__(self, memo):
        return self

    # --- arithmetic ---------------------------------------------------------

    def _operator_fallbacks(monomorphic_operator, name):
        """Forward and reverse operators from one Surd-by-Surd operator.

        int, Fraction and other ``numbers.Rational`` and float operands are
        converted exactly; anything else gives ``NotImplemented``.
        """

        def forward(a, b):
            if isinstance(b, Surd):
                return monomorphic_operator(a, b)
            if isinstance(b, (int, Fraction, float, numbers.Rational)):
                return monomorphic_operator(a, _from_fraction(rational(b)))
            return NotImplemented

        def reverse(b, a):
            if isinstance(a, (int, Fraction, float, numbers.Rational)):
                return monomorphic_operator(_from_fraction(rational(a)), b)
            if isinstance(a, Surd):
                return monomorphic_operator(a, b)
            return NotImplemented

        forward.__name__ = f"__{name}__"
        forward.__doc__ = monomorphic_operator.__doc__
        reverse.__name__ = f"__r{name}__"
        reverse.__doc__ = monomorphic_operator.__doc__
        return forward, reverse

    def _add(a, b):
        """a + b"""
        if not b._terms:
            return a
        if not a._terms:
            return b
        base, ta, tb, refined = _common(a, b)
        out, cancelled = t_add(ta, tb)
        return from_terms(base, out, cancelled or refined)

    __add__, __radd__ = _operator_fallbacks(_add, "add")

    def _sub(a, b):
        """a - b"""
        if not b._terms:
            return a
        if not a._terms:
            return -b
        base, ta, tb, refined = _common(a, b)
        out, cancelled = t_add(ta, tb, negate=True)
        return from_terms(base, out, cancelled or refined)

    __sub__, __rsub__ = _operator_fallbacks(_sub, "sub")

    def _mul(a, b):
        """a * b"""
        ta, tb = a._terms, b._terms
        if not ta:
            return a
        if not tb:
            return b
        if not b._base:
            return a._scale(tb[1])
        if not a._base:
            return b._scale(ta[1])
        base, ta, tb, _ = _common(a, b)
        return from_terms(base, t_mul(ta, tb))

    __mul__, __rmul__ = _operator_fallbacks(_mul, "mul")

    def _div(a, b):
        """a / b (exact; ZeroDivisionError if b == 0)"""
        if not b._base:
            if not b._terms:
                raise ZeroDivisionError(f"Surd division by zero: {_short(a)} / 0")
            return a._scale(1 / b._terms[1])
        return a * b._inverse()

    __truediv__, __rtruediv__ = _operator_fallbacks(_div, "truediv")

    def _scale(self, k):
        """self * k for a nonzero Fraction k (same base, no pruning)."""
        if k == 1:
            return self
        return from_terms(self._base, {r: q * k for r, q in self._terms.items()}, False)

    def _inverse(self):
        """1/self by conjugates.

        With ``den = a + b*sqrt(p)`` (p the largest base element in use),
        multiply numerator and denominator by ``a - b*sqrt(p)``: the
        denominator becomes ``a*a - p*b*b``, free of p.  Repeat until it is
        rational.
        """
        t = self._terms
        if not t:
            raise ZeroDivisionError("Surd division by zero")
        base = self._base
        if not base:
            return _from_fraction(1 / t[1])
        if len(t) == 1:
            (r, q), = t.items()
            return from_terms(base, {r: 1 / (q * r)}, False)
        num, den = None, t
        for i in range(len(base) - 1, -1, -1):
            p = base[i]
            a, b = t_split(den, p)
            if not b:
                continue
            conj = dict(a)
            for r, q in b.items():
                conj[r * p] = -q
            num = conj if num is None else t_mul(num, conj)
            if len(num) > settings.term_limit:
                from_terms(base, num, False)  # raises TermLimitExceeded
            den, _ = t_add(t_mul(a, a), t_scale(t_mul(b, b), p), negate=True)
        return from_terms(base, t_scale(num, 1 / den[1]))

    def __pow__(a, b, modulo=None):
        """a ** b for an integer b (negative: a power of the inverse).

        >>> (1 + sqrt(2)) ** 3
        Surd('7 + 5*sqrt(2)')
        >>> (1 + sqrt(2)) ** -1
        Surd('-1 + sqrt(2)')
        """
        if modulo is not None:
            return NotImplemented
        if isinstance(b, Surd):
            if b._base:
                return NotImplemented
            b = b._terms.get(1, _ZERO)
        if isinstance(b, numbers.Rational) and not isinstance(b, bool):
            if b.denominator != 1:
                return NotImplemented
            n = int(b.numerator)
        else:
            return NotImplemented
        if n < 0:
            a = a._inverse()
            n = -n
        result = None
        while n:
            if n & 1:
                result = a if result is None else result * a
            n >>= 1
            if n:
                a = a * a
        return _from_fraction(_ONE) if result is None else result

    def __rpow__(b, a, modulo=None):
        """a ** b for a rational-integer Surd b."""
        if modulo is not None or b._base:
            return NotImplemented
        if not isinstance(a, (int, Fraction, float, numbers.Rational)):
            return NotImplemented
        return Surd(a) ** b

    def __neg__(a):
        """-a"""
        return from_terms(a._base, {r: -q for r, q in a._terms.items()}, False)

    def __pos__(a):
        """+a"""
        return a

    def __abs__(a):
        """abs(a)"""
        return -a if a.sign() < 0 else a

    # --- enclosures and float -----------------------------------------------

    def interval(self, bits):
        """Rigorous rational enclosure ``(lo, hi)``, ``lo <= self <= hi``,
        ``hi - lo <= 2**-bits``; both ends are dyadic (exact if rational).

        >>> lo, hi = sqrt(2).interval(10)
        >>> lo * lo < 2 < hi * hi and hi - lo <= Fraction(1, 2**10)
        True
        """
        if isinstance(bits, bool) or not isinstance(bits, numbers.Integral):
            raise InputError(f"bits must be an integer, got {bits!r}")
        if self.is_rational():
            q = self._terms.get(1, _ZERO)
            return q, q
        k = max(0, int(bits) + (2 * self._bound_count() + 1).bit_length())
        lo, hi = self._bounds(k)
        return Fraction(lo, 1 << k), Fraction(hi, 1 << k)

    def scaled_bounds(self, k: int) -> tuple[int, int]:
        """Integers ``lo <= self * 2**k <= hi`` with ``hi - lo <= 2`` (``k >= 0``): the
        enclosure at the absolute scale 2**-k that interval arithmetic on integers starts
        from (:func:`ddg_oracle.reference.exact.intervals.scaled_bounds`).

        >>> sqrt(2).scaled_bounds(10)                   # 1448 / 1024 < sqrt 2 < 1449 / 1024
        (1448, 1449)
        """
        if self.is_rational():
            q = self._terms.get(1, _ZERO) * (1 << k)
            return math.floor(q), math.ceil(q)
        extra = (2 * self._bound_count() + 1).bit_length()
        lo, hi = self._bounds(k + extra)
        return lo >> extra, -(-hi >> extra)

    def _bound_count(self):
        """How many terms :meth:`_bounds` adds up (its enclosures are that many units wide)."""
        return len(self._terms)

    def _bounds(self, k):
        """Integers ``lo <= self * 2**k <= hi``, ``hi - lo <= 2 * self._bound_count() + 1``.

        What :meth:`interval`, ``float()`` and ``hash()`` use: a subclass that knows
        its value in another form (``ddg_oracle.reference.cotangents.CotanSum``) overrides this
        and :meth:`_bound_count` to skip the canonical form.
        """
        return t_bounds(self._terms, k)

    def __float__(self):
        """The correctly rounded float (round half to even), like ``float(Fraction)``.

        Enclosures are refined until both ends round to the same float; an
        irrational value is never a rounding midpoint, so this terminates.
        OverflowError if the value rounds beyond the float range.

        >>> float(sqrt(2) + sqrt(3)) == 3.1462643699419726
        True
        """
        if self.is_rational():
            return float(self._terms.get(1, _ZERO))
        extra = (2 * self._bound_count() + 1).bit_length()
        bits = 64
        while True:
            k = bits + extra
            lo, hi = self._bounds(k)
            if lo > 0 or hi < 0:
                den = 1 << k
                try:
                    flo = lo / den
                except OverflowError:
                    flo = math.inf if lo > 0 else -math.inf
                try:
                    fhi = hi / den
                except OverflowError:
                    fhi = math.inf if hi > 0 else -math.inf
                if flo == fhi:
                    if math.isinf(flo):
                        raise OverflowError("Surd too large to convert to float")
                    return flo
                # relative precision: aim at ~64 bits below the magnitude
                m = min(abs(lo), abs(hi))
                bits = max(2 * bits, k - m.bit_length() + 72)
            else:
                bits *= 2

    def __floor__(self):
        """math.floor(self), exact (without it math.floor would round via float).

        >>> math.floor(sqrt(10**40 - 1)), math.ceil(-sqrt(2)), int(-sqrt(2))
        (99999999999999999999, -1, -1)
        """
        if not self._base:
            return math.floor(self._terms.get(1, _ZERO))
        bits = 16
        while True:
            lo, hi = self.interval(bits)
            f = math.floor(lo)
            if f == math.floor(hi):   # an irrational number is never an integer
                return f
            bits *= 2

    def __ceil__(self):
        """math.ceil(self), exact."""
        return -(-self).__floor__()

    def __trunc__(self):
        """math.trunc(self), exact."""
        return self.__floor__() if self.sign() >= 0 else self.__ceil__()

    __int__ = __trunc__

    # --- sign and comparisons -----------------------------------------------

    def sign(self):
        """-1, 0 or 1, decided exactly.

        Up to two terms by squaring; otherwise enclosures at 64 and 256 bits,
        then exact recursion: ``x = a + b*sqrt(p)`` on the largest base
        element ``p``; if ``a`` and ``b*sqrt(p)`` have opposite signs, the sign
        is ``sign(a) * sign(a*a - p*b*b)`` (a number without ``p``).

        >>> (sqrt(10**12 + 1) - 10**6).sign()
        1
        >>> (sqrt(2) + sqrt(3) - sqrt(10)).sign()
        -1
        >>> (sqrt(5) + sqrt(6) + sqrt(7) - sqrt(54)).sign()
        -1
        """
        return t_sign(self._terms, self._base)

    def __bool__(a):
        """a != 0"""
        return bool(a._terms)

    def __eq__(a, b):
        """a == b (exact)"""
        if isinstance(b, Surd):
            if a is b:
                return True
            if a._base == b._base:
                return a._terms == b._terms
            if not a._base or not b._base:
                return False
            _, ta, tb, _ = _common(a, b)
            return ta == tb
        if isinstance(b, float):
            if not math.isfinite(b):
                return False
            b = Fraction(b)
        elif not isinstance(b, (int, Fraction, numbers.Rational)):
            return NotImplemented
        if not a.is_rational():
            return False
        return a._terms.get(1, 0) == b

    def _richcmp(a, b, op):
        if isinstance(b, Surd):
            return op((a - b).sign(), 0)
        if isinstance(b, float):
            if not math.isfinite(b):
                return op(0.0, b)
            b = Fraction(b)
        elif not isinstance(b, (int, Fraction, numbers.Rational)):
            return NotImplemented
        if a.is_rational():
            return op(a._terms.get(1, 0), b)
        if not b:
            return op(a.sign(), 0)
        return op((a - _from_fraction(rational(b))).sign(), 0)

    def __lt__(a, b):
        """a < b"""
        return a._richcmp(b, operator.lt)

    def __gt__(a, b):
        """a > b"""
        return a._richcmp(b, operator.gt)

    def __le__(a, b):
        """a <= b"""
        return a._richcmp(b, operator.le)

    def __ge__(a, b):
        """a >= b"""
        return a._richcmp(b, operator.ge)

    def __hash__(self):
        """hash(self): ``hash(Fraction)`` if rational, else hash of the correctly
        rounded float (a function of the value, whatever the base)."""
        h = self._hash
        if h is None:
            if self.is_rational():
                h = hash(self._terms.get(1, _ZERO))
            else:
                h = hash(float_view(self))
            self._hash = h
        return h


def sqrt(q):
    """The exact square root of a rational ``q >= 0`` as a :class:`Surd`.

    ints, Fractions, floats (taken exactly) and rational Surds are accepted;
    a negative value raises :class:`~ddg_oracle.reference.errors.InputError`.

    >>> sqrt(8), sqrt(Fraction(9, 4)), sqrt(Fraction(1, 2))
    (Surd('2*sqrt(2)'), Surd('3/2'), Surd('1/2*sqrt(2)'))
    """
    if isinstance(q, Surd):
        if q._base:
            raise InputError(f"sqrt of the irrational number {_short(q)} is not supported")
        q = q._terms.get(1, _ZERO)
    else:
        q = rational(q, "sqrt argument")
    if q < 0:
        raise InputError(f"sqrt of the negative number {q}")
    n, d = q.numerator, q.denominator
    m = n * d
    s = isqrt(m)
    if s * s == m:
        return _from_fraction(Fraction(s, d))
    c, m = strip_small_squares(m)
    return from_terms((m,), {m: Fraction(c, d)}, False)


def simplest(x):
    """``x`` in its simplest exact type: a rational :class:`Surd` as its ``Fraction`` (so
    rational data stay on fast Fraction arithmetic), anything else unchanged.

    >>> simplest(sqrt(2) * sqrt(8)), simplest(sqrt(2)), simplest(3)
    (Fraction(4, 1), Surd('sqrt(2)'), 3)
    """
    # is_rational, not _base: a lazily canonical Surd (cotangents.CotanSum) knows it is
    # irrational without computing its canonical form
    if isinstance(x, Surd) and x.is_rational():
        return x._terms.get(1, _ZERO)
    return x


def sign(x) -> int:
    """-1, 0 or 1: the exact sign of an int, Fraction or anything with ``sign()`` (Surd,
    Angle, ...), each decided the cheapest way its type knows.

    >>> sign(Fraction(-1, 3)), sign(0), sign(sqrt(2) - 1)
    (-1, 0, 1)
    """
    s = getattr(x, "sign", None)
    if s is not None:
        return s()
    return (x > 0) - (x < 0)


def exact_sum(values):
    """The exact sum of ints, Fractions and Surds, in its simplest type (:func:`simplest`).

    Adding Surds one by one refines the growing base at every step (cubic in the number of
    distinct radicands: a 400-face mesh with float coordinates takes ~25 s); here the
    coprime refinement of every base is computed once and each value re-expressed over it.

    >>> exact_sum([sqrt(2), sqrt(8), sqrt(3), 1]) == 1 + 3 * sqrt(2) + sqrt(3)
    True
    >>> exact_sum([sqrt(2), -sqrt(2), Fraction(1, 2)]), exact_sum([])
    (Fraction(1, 2), Fraction(0, 1))
    """
    values = list(values)
    for v in values:
        if hasattr(v, "_lazy_sum"):         # a lazy exact number (.lazy): the sum stays lazy
            return v._lazy_sum(values)
    rational_part = _ZERO
    surds = []
    for v in values:
        if isinstance(v, Surd):
            if v._base:
                surds.append(v)
            else:
                rational_part += v._terms.get(1, _ZERO)
        else:
            rational_part += rational(v)
    if not surds:
        return rational_part
    base = refine([b for v in surds for b in v.base])
    terms: dict[int, Fraction] = {1: rational_part} if rational_part else {}
    for v in surds:
        for r, q in reexpress(v._terms, base).items():
            t = terms.get(r, _ZERO) + q
            if t:
                terms[r] = t
            else:
                terms.pop(r, None)
    return simplest(from_terms(base, terms))


class Quotient:
    """The exact number ``n / d`` kept as the pair (``n``, ``d`` exact: ints, Fractions,
    Surds; ``d > 0``): its enclosures, ``float()`` and the exact zero test of sums of such
    (:func:`rounded_sum`, :func:`sum_is_zero`) need no division.  ``1 / d`` of a Surd with
    many square roots (a face area after dozens of intrinsic flips: 256 terms) takes
    seconds, its enclosure microseconds.  :meth:`exact` divides.

    >>> q = Quotient(1, sqrt(2) + sqrt(3) + sqrt(5))
    >>> float(q) == float(1 / (sqrt(2) + sqrt(3) + sqrt(5))), q.exact() * (sqrt(2) + sqrt(3) + sqrt(5)) == 1
    (True, True)
    """

    __slots__ = ("n", "d", "_k", "_kept")

    def __init__(self, n, d):
        # Surds and lazy exact numbers (.lazy) enclose themselves (scaled_bounds)
        self.n = n if hasattr(n, "scaled_bounds") else rational(n, "numerator")
        self.d = d if hasattr(d, "scaled_bounds") else rational(d, "denominator")
        if not self.d > 0:
            raise InputError(f"a quotient needs a positive denominator, got {_short(self.d)}")
        self._k = None

    def __repr__(self):
        return f"Quotient({self.n!r}, {self.d!r})"

    def scaled_bounds(self, k: int) -> tuple[int, int]:
        """Integers ``lo <= n / d * 2**k <= hi``, ``hi - lo <= 2`` (as
        :meth:`Surd.scaled_bounds`), from enclosures of ``n`` and ``d`` at a finer scale
        2**-j, j raised until the quotient of the enclosures is that narrow (it shrinks to
        a point: d > 0).  The last k's bounds are kept: the entries of a matrix share their
        terms."""
        if self._k == k:
            return self._kept
        n, d = self.n, self.d
        if not n:
            lo = hi = 0
        else:
            j = k + 16
            while True:
                da, db = d.scaled_bounds(j) if hasattr(d, "scaled_bounds") else _floor_ceil(d, j)
                if da <= 0:                     # d > 0, not yet told apart from 0 at 2**-j
                    j = 2 * j
                    continue
                na, nb = n.scaled_bounds(j) if hasattr(n, "scaled_bounds") else _floor_ceil(n, j)
                lo = min((na << k) // da, (na << k) // db)
                hi = max(-((-nb << k) // da), -((-nb << k) // db))
                if hi - lo <= 2:
                    break
                j += (hi - lo).bit_length() + 2
        self._k, self._kept = k, (lo, hi)
        return lo, hi

    def exact(self):
        """``n / d``, exact (a Fraction where rational): the division the enclosures avoid."""
        return simplest(self.n / self.d)

    def __float__(self):
        return rounded_sum((self,))


def _proportion(n: Surd, d: Surd) -> Fraction | None:
    """The rational k with n == k d (d irrational, nonzero), or None: exact, no division
    (the two term dicts over one base are proportional)."""
    if not n:
        return Fraction(0)
    _, tn, td, _ = _common(n, d)
    if tn.keys() != td.keys():
        return None
    r = next(iter(td))
    k = Fraction(tn[r]) / td[r]
    return k if all(tn[x] == k * td[x] for x in td) else None


class SurdQuotient(Surd):
    """An irrational :class:`Surd` known as n / d (Surds, d > 0): made by
    :meth:`Surd.quotients`.  It *is* a Surd (equal values compare and hash equal); its
    canonical form (``_base``, ``_terms``) is the division n * (1 / d), computed on first
    use (``__getattr__``: those slots stay unset until then, as in
    ``ddg_oracle.reference.cotangents.CotanSum``); the sign, negation, enclosures, float,
    hash and the exact zero test of angles work from the pair."""

    __slots__ = ("_n", "_d")

    def __new__(cls, n: Surd, d: Surd):
        self = object.__new__(cls)
        self._n, self._d, self._hash = n, d, None
        return self

    def __getattr__(self, name):
        if name != "_base" and name != "_terms":
            raise AttributeError(f"'SurdQuotient' object has no attribute {name!r}")
        v = self._n * (1 / self._d)
        self._base, self._terms = v._base, v._terms
        return v._base if name == "_base" else v._terms

    @property
    def ratio(self):
        return self._n, self._d

    def is_rational(self):
        return False                    # made so (Surd.quotients)

    def __bool__(self):
        return True

    def sign(self):
        return self._n.sign()

    def __neg__(self):
        return SurdQuotient(-self._n, self._d)

    def _bound_count(self):
        return 1

    def _bounds(self, k):
        return Quotient(self._n, self._d).scaled_bounds(k)       # 2 units wide at most


def _floor_ceil(q: Fraction, k: int) -> tuple[int, int]:
    x = q * (1 << k)
    return math.floor(x), math.ceil(x)


def rounded_sum(values) -> float:
    """``float(exact_sum(values))``, correctly rounded, without the exact sum's canonical form
    (one square root per face of a float mesh: minutes at 10,000 faces) and without dividing
    (``values`` may hold :class:`Quotient` objects): each value enclosed in integers at the
    scale 2^-k (:meth:`Surd.scaled_bounds`), the enclosures added; when both ends round to one
    float (and 0 lies outside), so does the sum (rounding is monotonic); else k grows (to
    ~64 bits below the sum's magnitude when 0 lies outside, else doubling) up to 4096 bits.
    A sum within 2^-250 of 0 is tested for an exact 0 (:func:`sum_is_zero`, cheap for up to
    two quotients); a sum still undecided at 4096 bits (a rounding tie) is computed exactly.

    >>> rounded_sum([sqrt(2), sqrt(3), Fraction(1, 3)]) == float(sqrt(2) + sqrt(3) + Fraction(1, 3))
    True
    >>> rounded_sum([sqrt(2), -sqrt(2)]), rounded_sum([])
    (0.0, 0.0)
    >>> rounded_sum([Quotient(sqrt(3), sqrt(2) + 1), Quotient(-sqrt(12), sqrt(8) + 2)])
    0.0
    """
    values = [v if hasattr(v, "scaled_bounds") else Surd(rational(v)) for v in values]
    k = 64 + len(values).bit_length()
    zero_tested = False
    while k <= 4096:
        lo = hi = 0
        for v in values:
            a, b = v.scaled_bounds(k)
            lo += a
            hi += b
        if lo > 0 or hi < 0:
            low, high = float(Fraction(lo, 1 << k)), float(Fraction(hi, 1 << k))
            if low == high:
                return low
            # relative precision: ~64 bits below the magnitude (the values of tiny meshes)
            k = max(2 * k, k - min(abs(lo), abs(hi)).bit_length() + 72)
            continue
        if k >= 256 and not zero_tested:
            zero_tested = True
            if sum_is_zero(values, cheap=True):
                return 0.0
        k *= 2
    return float(exact_sum(v.exact() if isinstance(v, Quotient) else v for v in values))


def sum_is_zero(values, cheap: bool = False) -> bool | None:
    """Whether the exact sum of ``values`` (exact numbers and :class:`Quotient` objects) is 0,
    decided exactly without dividing where there are at most two denominators (quotients
    over one denominator object share it): ``S + n1 / d1 + n2 / d2 = 0`` iff
    ``S d1 d2 + n1 d2 + n2 d1 = 0`` (``d > 0``).  More denominators: the exact sum (its
    divisions), or None with ``cheap`` (also where the products outgrow the term limit).

    >>> sum_is_zero([Quotient(1, sqrt(2)), Quotient(-1, sqrt(8) / 2)]), sum_is_zero([1, Quotient(1, 3)])
    (True, False)
    """
    plain, over = [], {}
    for v in values:
        if isinstance(v, Quotient):
            n, d = over.get(id(v.d), (None, v.d))
            over[id(v.d)] = (v.n if n is None else n + v.n, d)
        else:
            plain.append(v)
    groups = [(n, d) for n, d in over.values() if n]
    if len(groups) > 2:
        if cheap:
            return None
        return not exact_sum(plain + [n / d for n, d in groups])
    S = exact_sum(plain)
    try:
        if not groups:
            return not S
        if len(groups) == 1:
            (n, d), = groups
            return not (S * d + n)
        (n1, d1), (n2, d2) = groups
        return not (S * d1 * d2 + n1 * d2 + n2 * d1)
    except TermLimitExceeded:
        if cheap:                       # products of many square roots: let the caller go on
            return None
        raise


def rounded_root_sum(terms, den: int = 1) -> float:
    """``float(sum n / sqrt(G) / den)`` over ``terms`` [(n, G)] (ints, G > 0), correctly
    rounded, from integers: each term times 2^p lies in [s, s + 1) for
    ``s = isqrt(n^2 4^p // G)`` (signed), so the sum lies in an interval of width
    (number of terms) 2^-p; when both ends round to one float, so does the sum (rounding is
    monotonic), else p doubles up to 2048 bits, and then the exact Surd sum decides (a sum
    that is exactly 0).  The float views of the area gradient and of the vertex areas.

    >>> rounded_root_sum([(1, 2), (1, 2)]) == math.sqrt(2)      # 2 / sqrt(2)
    True
    >>> rounded_root_sum([(1, 8), (-2, 32)])                    # exactly 0
    0.0
    """
    if not terms:
        return 0.0
    k = len(terms)
    p = 64 + k.bit_length()
    while p <= 2048:
        four = 1 << (2 * p)
        lo = 0
        for n, G in terms:
            r = isqrt(n * n * four // G)
            lo += r if n > 0 else -r - 1
        scale = den << p
        a, b = float_view(Fraction(lo, scale)), float_view(Fraction(lo + k, scale))
        if a == b and (a != 0.0 or lo > 0 or lo + k < 0):
            return a
        p *= 2
    exact = Fraction(0)
    for n, G in terms:
        exact = exact + Fraction(n, den) / sqrt(G)
    return float_view(exact)
