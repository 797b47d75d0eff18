"""Exact angles: integer combinations of corner angles plus rational multiples of pi.

A corner angle of a triangle lies in (0, pi) and is determined exactly by its
cotangent, an element of the square-root field (:class:`~ddg_oracle.reference.exact.surds.Surd`).
An :class:`Angle` is a formal sum

    theta = m_1 arccot(c_1) + ... + m_n arccot(c_n) + r pi      (m_i integers, r rational)

which is what angle sums, angle defects (D2.2) and Gauss-Bonnet totals (T2.6) are.

How comparisons are decided, exactly:

* A rigorous enclosure: every ``arccot(c)`` is bounded by integer fixed-point
  evaluation of Euler's series for arctan, with an explicit error bound
  (see :func:`_atan_bounds`), and pi likewise.  If the enclosure of theta
  excludes 0, the sign is known.
* An exact zero test: the direction w = prod (c_i + i)^(m_i) * e^(i r pi) has
  argument theta modulo 2 pi.  theta == 0 iff w is a positive real *and* the
  enclosure already confines theta to (-2 pi, 2 pi).  The direction of r pi is
  exact when 24 r is an integer (tan(pi/24) = sqrt6 - sqrt3 + sqrt2 - 2), which
  covers every multiple of pi/24.
* A pi part with 24 r not an integer needs no zero test: the arccot part
  sum m_i arccot(c_i) is a rational multiple of pi only if it is a multiple of
  pi/24 (e^(2 i theta) = prod ((c_i + i) / (c_i - i))^(m_i) lies in a
  multiquadratic field Q(i, sqrt r_1, ...), whose roots of unity have orders
  dividing 24), so theta = 0 is impossible there.
* Otherwise theta != 0 and the enclosure is refined until it excludes 0; a
  nonzero theta within 2**-``PRECISION_LIMIT`` of 0 raises
  :class:`~ddg_oracle.reference.errors.Undecidable`, saying so.

No float is used anywhere in a decision.  ``float(angle)`` is correctly rounded.

>>> from fractions import Fraction
>>> from ddg_oracle.reference.exact import pi, corner_angle
>>> right = corner_angle(0)              # cot = 0: a right angle
>>> right == pi * Fraction(1, 2)
True
>>> 2 * pi - 3 * right == right          # angle defect of a cube vertex
True
"""

from __future__ import annotations

import math
from fractions import Fraction
from functools import lru_cache

from ..errors import InputError, Undecidable
from .rationals import rational
from .surds import Surd, sqrt

#: Refinement stops here (bits of absolute precision) and raises Undecidable.
PRECISION_LIMIT = 4096

_Number = (int, Fraction, float)


class Angle:
    """An exact real angle (radians): sum of m_i arccot(c_i) plus r pi.

    Immutable and hashable; ``==``, ``<``, ``sign()`` are exact.  Build angles
    with :func:`corner_angle`, :func:`direction_angle` and the constant ``pi``;
    add, subtract, multiply by integers (and by any rational when the angle is a
    rational multiple of pi).
    """

    __slots__ = ("_parts", "_pi", "_hash")

    def __init__(self, parts=None, pi_coefficient=0):
        """``parts``: {cotangent: integer multiplicity}; theta = sum m arccot(c) + r pi."""
        clean: dict[Surd, int] = {}
        for c, m in (parts or {}).items():
            if not isinstance(m, int) or isinstance(m, bool):
                raise InputError(f"multiplicity of arccot({c}) must be an int, got {m!r}")
            c = c if isinstance(c, Surd) else Surd(c)
            clean[c] = clean.get(c, 0) + m
        self._parts = {c: m for c, m in clean.items() if m}
        self._pi = rational(pi_coefficient)
        self._hash = None

    # -- construction helpers -------------------------------------------------

    @classmethod
    def _raw(cls, parts, r):
        a = object.__new__(cls)
        a._parts = parts
        a._pi = r
        a._hash = None
        return a

    # -- structure ------------------------------------------------------------

    @property
    def pi_coefficient(self) -> Fraction:
        """r in theta = sum m_i arccot(c_i) + r pi (not unique; see as_multiple_of_pi)."""
        return self._pi

    @property
    def parts(self) -> dict:
        """Copy of {cotangent: multiplicity} of the primitive corner angles."""
        return dict(self._parts)

    def as_multiple_of_pi(self) -> Fraction | None:
        """theta / pi when theta is a rational multiple of pi (exactly decided), else None.

        The arccot part is then a multiple of pi/24 (module docstring), so theta / pi =
        r + k / 24 for one integer k: the enclosure picks k, the exact zero test checks it.

        >>> from ddg_oracle.reference.exact import corner_angle, pi
        >>> (corner_angle(1) + pi * Fraction(1, 5)).as_multiple_of_pi()     # pi/4 + pi/5
        Fraction(9, 20)
        >>> corner_angle(2).as_multiple_of_pi() is None
        True
        """
        if not self._parts:
            return self._pi
        arccots = Angle._raw(self._parts, Fraction(0))
        lo, hi = arccots.interval(20)
        plo, phi = _pi_bounds(30)
        # the enclosure only picks the candidate k/24 nearest to the arccot part / pi;
        # the candidate is then checked exactly
        k = round(24 * (lo + hi) * (1 << 30) / (plo + phi))
        if (arccots - pi * Fraction(k, 24)).sign() == 0:
            return self._pi + Fraction(k, 24)
        return None

    # -- arithmetic -------------------------------------------------------------

    def __add__(self, other):
        if not isinstance(other, Angle):
            if other == 0 and isinstance(other, _Number):
                return self
            return NotImplemented
        parts = dict(self._parts)
        for c, m in other._parts.items():
            n = parts.get(c, 0) + m
            if n:
                parts[c] = n
            else:
                parts.pop(c, None)
        return Angle._raw(parts, self._pi + other._pi)

    __radd__ = __add__

    def __neg__(self):
        return Angle._raw({c: -m for c, m in self._parts.items()}, -self._pi)

    def __pos__(self):
        return self

    def __sub__(self, other):
        if not isinstance(other, Angle):
            if other == 0 and isinstance(other, _Number):
                return self
            return NotImplemented
        return self + (-other)

    def __rsub__(self, other):
        if other == 0 and isinstance(other, _Number):
            return -self
        return NotImplemented

    def __mul__(self, k):
        if isinstance(k, Angle) or not isinstance(k, (int, Fraction)) or isinstance(k, bool):
            return NotImplemented
        k = Fraction(k)
        if k.denominator == 1:
            n = int(k)
            if n == 0:
                return Angle._raw({}, Fraction(0))
            return Angle._raw({c: n * m for c, m in self._parts.items()}, self._pi * n)
        q = self.as_multiple_of_pi()
        if q is None:
            raise InputError(
                "an exact angle can be multiplied by a non-integer only when it is a "
                f"rational multiple of pi; got {self!r} * {k}")
        return Angle._raw({}, q * k)

    __rmul__ = __mul__

    def __truediv__(self, k):
        if not isinstance(k, (int, Fraction)) or isinstance(k, bool):
            return NotImplemented
        return self * (1 / Fraction(k))

    # -- exact decisions --------------------------------------------------------

    def sign(self) -> int:
        """-1, 0 or 1, decided exactly (see the module docstring)."""
        if not self._parts:
            return (self._pi > 0) - (self._pi < 0)
        bits = 64 + max(1, sum(abs(m) for m in self._parts.values())).bit_length()
        # a pi part off the multiples of pi/24 makes theta != 0 (module docstring)
        nonzero = (self._pi * 24).denominator != 1
        bits = min(bits, PRECISION_LIMIT)
        while True:
            lo, hi = self.interval_at(bits)
            if lo > 0:
                return 1
            if hi < 0:
                return -1
            if not nonzero:
                two_pi_lo = Fraction(2 * _pi_bounds(bits)[0], 1 << bits)
                if -two_pi_lo < lo and hi < two_pi_lo:
                    x, y = self._direction()
                    if y == 0 and x > 0:
                        return 0
                    nonzero = True          # theta != 0: refining will separate it
            if bits >= PRECISION_LIMIT:
                break
            bits = min(2 * bits, PRECISION_LIMIT)   # the last try at the limit itself
        why = ("it is not 0 (its pi part is off the multiples of pi/24)"
               if (self._pi * 24).denominator != 1 else
               "it is not 0 (exact zero test)" if nonzero else "the zero test was not reached")
        raise Undecidable(
            f"the sign of {self!r}: {why}, but its enclosure at {PRECISION_LIMIT} bits per "
            "term still contains 0; raise ddg_oracle.reference.exact.angles.PRECISION_LIMIT "
            "to decide it")

    def __eq__(self, other):
        if isinstance(other, Angle):
            return (self - other).sign() == 0
        if isinstance(other, _Number) and other == 0:
            return self.sign() == 0
        return NotImplemented

    def __ne__(self, other):
        r = self.__eq__(other)
        return r if r is NotImplemented else not r

    def _cmp(self, other):
        if isinstance(other, Angle):
            return (self - other).sign()
        if isinstance(other, _Number) and other == 0:
            return self.sign()
        return None

    def __lt__(self, other):
        s = self._cmp(other)
        return NotImplemented if s is None else s < 0

    def __le__(self, other):
        s = self._cmp(other)
        return NotImplemented if s is None else s <= 0

    def __gt__(self, other):
        s = self._cmp(other)
        return NotImplemented if s is None else s > 0

    def __ge__(self, other):
        s = self._cmp(other)
        return NotImplemented if s is None else s >= 0

    def __bool__(self):
        return self.sign() != 0

    def __hash__(self):
        # float() is correctly rounded, hence a function of the value alone:
        # equal angles hash equal whatever their representation.
        if self._hash is None:
            self._hash = hash(float(self))
        return self._hash

    # -- numerics -----------------------------------------------------------------

    def interval_at(self, bits: int) -> tuple[Fraction, Fraction]:
        """A rigorous enclosure (lo, hi) computed with ``bits`` bits per term."""
        lo = hi = 0
        for c, m in self._parts.items():
            a, b = _arccot_bounds(c, bits)
            if m > 0:
                lo += m * a
                hi += m * b
            else:
                lo += m * b
                hi += m * a
        if self._pi:
            a, b = _pi_bounds(bits)
            n, d = self._pi.numerator, self._pi.denominator
            if n > 0:
                lo += Fraction(n * a, d)
                hi += Fraction(n * b, d)
            else:
                lo += Fraction(n * b, d)
                hi += Fraction(n * a, d)
        scale = Fraction(1, 1 << bits)
        return Fraction(lo) * scale, Fraction(hi) * scale

    def interval(self, bits: int) -> tuple[Fraction, Fraction]:
        """A rigorous enclosure (lo, hi) of width at most 2**-bits."""
        n = 1 + sum(abs(m) for m in self._parts.values()) + abs(self._pi.numerator)
        b = bits + n.bit_length() + 3
        while True:
            lo, hi = self.interval_at(b)
            if hi - lo <= Fraction(1, 1 << bits):
                return lo, hi
            b += 16

    def enclosure(self, digits: int = 30) -> tuple[Fraction, Fraction]:
        """Certified (lo, hi) with lo <= theta <= hi and hi - lo <= 10**-digits."""
        bits = math.ceil(digits * 3.3219280948873626) + 1
        return self.interval(bits)

    def decimal(self, digits: int = 30) -> str:
        """theta as a decimal string with ``digits`` decimals, certified:

        the string is the midpoint of an enclosure of width 10**-(digits+2),
        rounded, so |s - theta| <= 0.51 * 10**-digits.
        """
        lo, hi = self.enclosure(digits + 2)
        mid = (lo + hi) / 2
        q = round(mid * 10 ** digits)
        sign = "-" if q < 0 else ""
        q = abs(q)
        s = str(q).rjust(digits + 1, "0")
        return f"{sign}{s[:-digits]}.{s[-digits:]}" if digits else f"{sign}{s}"

    def __float__(self):
        if self.sign() == 0:
            return 0.0
        bits = 60
        while True:
            lo, hi = self.interval_at(bits)
            if float(lo) == float(hi):
                return float(lo)
            bits *= 2
            if bits > PRECISION_LIMIT * 4:           # cannot happen for theta != 0
                raise Undecidable(f"float({self!r}) did not converge")

    def __repr__(self):
        terms = []
        for c, m in sorted(self._parts.items(), key=lambda cm: _sort_key(cm[0])):
            terms.append(f"{m:+d}*arccot({c})")
        if self._pi or not terms:
            terms.insert(0, f"{self._pi}*pi")
        return "Angle(" + " ".join(terms) + ")"

    def _direction(self) -> tuple[Surd, Surd]:
        """The exact direction prod (c+i)^m * dir(r pi), up to a positive factor.

        Factors with the same radicands are multiplied first so that the square
        roots of one face collapse before different faces meet.
        """
        groups: dict[tuple, tuple[Surd, Surd]] = {}
        for c, m in self._parts.items():
            z = (c, Surd(1)) if m > 0 else (c, Surd(-1))
            key = tuple(r for r, _ in c.terms())
            acc = groups.get(key, (Surd(1), Surd(0)))
            groups[key] = _cmul(acc, _cpow(z, abs(m)))
        x, y = Surd(1), Surd(0)
        for z in sorted(groups.values(), key=lambda z: z[0].n_terms + z[1].n_terms):
            x, y = _cmul((x, y), z)
        if self._pi:
            j = int(self._pi * 24) % 48
            x, y = _cmul((x, y), _pi24_direction(j))
        return x, y


def _cmul(z, w):
    (a, b), (c, d) = z, w
    return a * c - b * d, a * d + b * c


def _cpow(z, n: int):
    """z**n for a complex number z = (x, y) of Surds, n >= 0, by repeated squaring: about
    log2 n products instead of n (an angle sum of multiplicity 10,000 is one arccot)."""
    out = (Surd(1), Surd(0))
    while n:
        if n & 1:
            out = _cmul(out, z)
        n >>= 1
        if n:
            z = _cmul(z, z)
    return out


def _sort_key(c: Surd) -> float:
    """A float ordering cotangents for display: beyond the float range, +-inf (never an
    OverflowError: a repr inside an error message must not raise one)."""
    try:
        return float(c)
    except OverflowError:
        return math.inf if c > 0 else -math.inf


@lru_cache(maxsize=None)
def _pi24_direction(j: int) -> tuple[Surd, Surd]:
    """Direction of j*pi/24 (unnormalised): (1 + i tan(pi/24))**j, exact."""
    t = sqrt(6) - sqrt(3) + sqrt(2) - 2
    z = (Surd(1), Surd(0))
    for _ in range(j):
        z = _cmul(z, (Surd(1), t))
    return z


def corner_angle(cot) -> Angle:
    """The angle in (0, pi) whose cotangent is ``cot`` (int, Fraction, float or Surd).

    Multiples of pi/24 (right angles, 60 degrees, ...) are stored as such.
    """
    c = cot if isinstance(cot, Surd) else Surd(cot)
    q = _known_multiple(c)
    if q is not None:
        return Angle._raw({}, q)
    return Angle._raw({c: 1}, Fraction(0))


def direction_angle(x, y) -> Angle:
    """arg(x + i y) in [0, 2 pi) for a nonzero direction (x, y) with exact coordinates."""
    x = x if isinstance(x, Surd) else Surd(x)
    y = y if isinstance(y, Surd) else Surd(y)
    sy = y.sign()
    if sy == 0:
        sx = x.sign()
        if sx == 0:
            raise InputError("direction_angle of the zero vector")
        return Angle._raw({}, Fraction(0 if sx > 0 else 1))
    a = corner_angle(x / y)
    return a if sy > 0 else a + pi


def _known_multiple(c: Surd) -> Fraction | None:
    """j/24 if arccot(c) = j pi / 24, decided exactly (the enclosure only picks j)."""
    if c.is_rational():
        q = c.as_fraction()
        if q == 0:
            return Fraction(1, 2)
        if abs(q) != 1:
            return None                       # tan(j pi/24) rational only for 0, +-1
        return Fraction(1, 4) if q > 0 else Fraction(3, 4)
    if c.n_terms > 4:
        return None
    # Only radicands built from 2 and 3 can give a multiple of pi/24.
    for r, _ in c.terms():
        while r % 2 == 0:
            r //= 2
        while r % 3 == 0:
            r //= 3
        if r != 1:
            return None
    lo, hi = _arccot_bounds(c, 40)
    plo, phi = _pi_bounds(40)
    j = round(Fraction(24 * (lo + hi), plo + phi))
    if 0 < j < 24:
        x, y = _pi24_direction(j)
        if c * y == x:
            return Fraction(j, 24)
    return None


# -- rigorous fixed-point arctan and pi ---------------------------------------


def _atan_series(p: int, q: int, bits: int) -> tuple[int, int]:
    """Bounds (lo, hi) of atan(p/q) * 2**bits for 0 <= p <= q, q > 0.

    Euler's series atan(t) = sum_n 4^n (n!)^2/(2n+1)! t^(2n+1)/(1+t^2)^(n+1):
    terms are positive, each is the previous one times
    rho_n = 2n/(2n+1) * p^2/(p^2+q^2) < 1/2.  With floors, the error of each
    computed term is in [0, 2) units (e_n < e_(n-1)/2 + 1), and after the first
    zero term the tail is < 2 units; so the true value is in [S, S + 2N + 4].
    """
    if p == 0:
        return 0, 0
    den = p * p + q * q
    pp = p * p
    t = (p * q << bits) // den
    s = t
    n = 0
    while t:
        n += 1
        t = (t * 2 * n * pp) // ((2 * n + 1) * den)
        s += t
    return s, s + 2 * n + 4


@lru_cache(maxsize=64)
def _pi_bounds(bits: int) -> tuple[int, int]:
    """Bounds (lo, hi) of pi * 2**bits, from pi = 4 atan(1)."""
    lo, hi = _atan_series(1, 1, bits)
    return 4 * lo, 4 * hi


def _atan_bounds(s: Fraction, bits: int) -> tuple[int, int]:
    """Bounds (lo, hi) of atan(s) * 2**bits for any rational s."""
    if s < 0:
        lo, hi = _atan_bounds(-s, bits)
        return -hi, -lo
    if s > 1:
        # atan(s) = pi/2 - atan(1/s)
        plo, phi = _pi_bounds(bits)
        lo, hi = _atan_bounds(1 / s, bits)
        return plo // 2 - hi, -(-phi // 2) - lo
    return _atan_series(s.numerator, s.denominator, bits)


def _fixed_bounds(lo: Fraction, hi: Fraction, bits: int) -> tuple[Fraction, Fraction]:
    """Round an interval outward to multiples of 2**-bits (keeps integers small)."""
    scale = 1 << bits
    return (Fraction(math.floor(lo * scale), scale), Fraction(math.ceil(hi * scale), scale))


@lru_cache(maxsize=1 << 16)
def _arccot_bounds(c: Surd, bits: int) -> tuple[int, int]:
    """Bounds (lo, hi) of arccot(c) * 2**bits, arccot in (0, pi): pi/2 - atan(c)."""
    clo, chi = c.interval(bits + 2)
    clo, chi = _fixed_bounds(clo, chi, bits + 2)
    plo, phi = _pi_bounds(bits)
    alo, _ = _atan_bounds(clo, bits)
    _, ahi = _atan_bounds(chi, bits)
    # |atan(c) - atan(c')| <= |c - c'|, and the c-interval has width <= 2**-(bits+1):
    # the bounds at the interval ends already enclose atan(c).
    return plo // 2 - ahi, -(-phi // 2) - alo


#: The exact angle pi.
pi = Angle._raw({}, Fraction(1))
