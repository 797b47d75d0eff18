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
* An exact test whether the arccot part A = sum m_i arccot(c_i) is a rational
  multiple of pi: it is one iff e^(2iA) = prod ((c_i + i)/(c_i - i))^(m_i) is a root
  of unity.  That number lies in a multiquadratic field Q(i, sqrt r_1, ...), whose
  roots of unity have orders dividing 24, so A is then a multiple of pi/24 and the
  enclosure picks which: theta = (k/24 + r) pi is decided.  The test splits the
  product by the characters of the Galois group (:func:`_pi24_multiple`), so its
  cost grows with the number of square roots of single cotangents, not with the
  number of square roots of the whole sum: a sum over 128 faces with 128
  independent radicands costs 128 small products, not 2^128 terms.
* A pi part with 24 r not an integer makes theta != 0 at once (the arccot part
  is a multiple of pi/24 or irrational over pi).
* Otherwise theta != 0 and the enclosure is refined until it excludes 0.
* The turning count (:func:`_sign_by_turning`): with r a multiple of 1/2, the sign of
  theta follows from the exact signs of the partial products of the c + i (each turns
  by an arccot in (0, pi)), with no enclosure.  It decides at once where the arccots
  have at most 4 square roots in all, and, where the enclosure reaches
  2**-``arccots.PRECISION_LIMIT`` without excluding 0, wherever they have at most
  TURNING_ROOTS (12) square roots (a coprime base of all their radicands) and at most
  TURNING_STEPS (64) arccots counted with multiplicity: such an angle is always decided,
  whatever the size of its numbers (a float mesh's vertex of valence k has one radicand
  per face, k in all, often pairwise coprime).  Beyond those, a nonzero theta within 2**-``arccots.PRECISION_LIMIT`` of 0 raises
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
from . import arccots
from .arccots import ArccotSum
from .rationals import float_view, rational
from .surds import Surd
from .terms import reexpress, refine, t_add, t_scale, t_sign

_Number = (int, Fraction, float)
_ZERO = Fraction(0)


class Angle(ArccotSum):
    """An exact real angle (radians): sum of m_i arccot(c_i) plus r pi.

    Immutable and hashable; ``==``, ``<``, ``sign()`` are exact.  Build angles
    with :func:`corner_angle`, :func:`direction_angle` and the constant ``pi``;
    add, subtract, multiply by integers (and by any rational when the angle is a
    rational multiple of pi).
    """

    # _enc: the narrowest enclosure computed so far, (bits, lo, hi): sign() leaves the one
    # that decided it, float() starts from it
    __slots__ = ("_parts", "_pi", "_hash", "_enc")

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
        self._enc = None

    # -- construction helpers -------------------------------------------------

    @classmethod
    def _raw(cls, parts, r):
        a = object.__new__(cls)
        a._parts = parts
        a._pi = r
        a._hash = None
        a._enc = None
        return a

    # -- structure ------------------------------------------------------------

    @staticmethod
    def _coerce(other):
        """What mixes with an Angle: Angles, and the number 0."""
        if isinstance(other, Angle):
            return other
        if isinstance(other, _Number) and not isinstance(other, bool) and other == 0:
            return _ZERO_ANGLE
        return None

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
        k = _pi24_multiple(self._parts)
        return None if k is None else self._pi + Fraction(k, 24)

    # -- arithmetic (addition and subtraction: ArccotSum) ---------------------------------

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
        weight = self._weight()
        if not weight:
            return (self._pi > 0) - (self._pi < 0)
        # every arccot lies in (0, pi): terms of one sign (a corner angle, a sum of corner
        # angles) have that sign, no enclosure needed
        one = self._one_signed()
        if one > 0 and self._pi >= 0:
            return 1
        if one < 0 and self._pi <= 0:
            return -1
        limit = arccots.PRECISION_LIMIT
        terms = weight.bit_length()
        bits = min(64 + terms, limit)
        # the exact zero test costs far more than an enclosure: it waits until one of
        # 128 bits (and the terms' widths) has failed too
        zero_test_bits = min(128 + terms, limit)
        # a pi part off the multiples of pi/24 makes theta != 0 (module docstring)
        nonzero = (self._pi * 24).denominator != 1
        while True:
            lo, hi = self._scaled(bits)
            if lo > 0:
                return 1
            if hi < 0:
                return -1
            if not nonzero and bits >= zero_test_bits:
                # a few square roots in all: the turning count decides outright (exact
                # products of at most 16 terms, milliseconds)
                turned = _sign_by_turning(self._parts, self._pi, roots=4)
                if turned is not None:
                    return turned
                # the test builds nothing larger than the products of one cotangent's
                # conjugates, so it always finishes
                k = _pi24_multiple(self._parts)
                if k is not None:               # theta = (r + k/24) pi exactly
                    q = self._pi + Fraction(k, 24)
                    return (q > 0) - (q < 0)
                nonzero = True                  # theta != 0: refining will separate it
            if bits >= limit:
                break
            # the zero test's precision next (never above twice this one), then doubling;
            # the last try at the limit itself
            bits = min(zero_test_bits if not nonzero and bits < zero_test_bits else 2 * bits,
                       limit)
        # beyond the enclosures' limit, few square roots: the turning of exact products
        turned = _sign_by_turning(self._parts, self._pi)
        if turned is not None:
            return turned
        why = ("its pi part is off the multiples of pi/24" if (self._pi * 24).denominator != 1
               else "exact zero test")
        raise Undecidable(
            f"the sign of {self!r}: it is not 0 ({why}), but its enclosure at "
            f"{limit} bits per term still contains 0; raise "
            "ddg_oracle.reference.exact.arccots.PRECISION_LIMIT to decide it")

    def interval_at(self, bits: int) -> tuple[Fraction, Fraction]:
        """A rigorous enclosure (lo, hi) computed with ``bits`` bits per term."""
        lo, hi = self._scaled(bits)
        return Fraction(lo, 1 << bits), Fraction(hi, 1 << bits)

    # -- what the decisions read of the arccot part (a lazy subclass answers from its own data)

    def _weight(self) -> int:
        """``sum |m_i|``: how many arccots the enclosures add up."""
        return sum(abs(m) for m in self._parts.values())

    def _one_signed(self) -> int:
        """1 if every multiplicity is positive, -1 if every one is negative, else 0."""
        ms = self._parts.values()
        return 1 if all(m > 0 for m in ms) else -1 if all(m < 0 for m in ms) else 0

    def _arccots_scaled(self, bits: int) -> tuple[int, int]:
        """Integers lo <= (sum m_i arccot(c_i)) * 2**bits <= hi, each arccot bounded with
        ``bits`` bits."""
        lo = hi = 0
        for c, m in self._parts.items():
            a, b = arccot_bounds(c, bits)
            if m > 0:
                lo += m * a
                hi += m * b
            else:
                lo += m * b
                hi += m * a
        return lo, hi

    def _scaled_at(self, bits: int) -> tuple[int, int]:
        """Integers lo <= theta * 2**bits <= hi, every term bounded with ``bits`` bits (on
        integers: a float view costs one such enclosure, no Fraction)."""
        lo, hi = self._arccots_scaled(bits)
        if self._pi:
            a, b = pi_bounds(bits)
            n, d = self._pi.numerator, self._pi.denominator
            if n > 0:
                lo += n * a // d
                hi -= -n * b // d                   # ceiling
            else:
                lo += n * b // d
                hi -= -n * a // d
        return lo, hi

    def _interval_bits(self, bits: int) -> int:
        n = 1 + self._weight() + abs(self._pi.numerator)
        return bits + n.bit_length() + 3

    def _scaled(self, bits: int) -> tuple[int, int]:
        """:meth:`_scaled_at`, or (rescaled) a narrower enclosure computed before."""
        e = self._enc
        if e is None or e[0] < bits:
            e = self._enc = (bits, *self._scaled_at(bits))
            return e[1], e[2]
        shift = e[0] - bits
        return e[1] >> shift, -(-e[2] >> shift)

    def __float__(self):
        # correctly rounded: the int quotients lo / 2^b and hi / 2^b are (Python's int
        # division rounds correctly); when they agree every number between them, theta
        # among them, rounds to that float
        terms = (1 + self._weight()).bit_length()
        bits = self._enc[0] if self._enc is not None else 72 + 2 * terms
        while True:
            lo, hi = self._scaled(bits)
            if lo <= 0 <= hi:
                if self.sign() == 0:
                    return 0.0
                bits = self._enc[0]             # the enclosure that decided the sign
                lo, hi = self._scaled(bits)
            x = lo / (1 << bits)
            if x == hi / (1 << bits):
                # below 2^-1075 both ends round to a zero, maybe -0.0 from an end below 0:
                # the correctly rounded float of theta has theta's own sign (exact)
                return x if x else math.copysign(0.0, self.sign())
            # 53 bits relative to |theta| >= small / 2^bits, the terms' widths and a guard
            # (usually one more enclosure); near a rounding boundary, twice the bits
            need = bits - min(abs(lo), abs(hi)).bit_length() + 64 + terms
            bits = need if need > bits else 2 * bits
            if bits > arccots.PRECISION_LIMIT * 4:   # cannot happen for theta != 0
                raise Undecidable(f"float({self!r}) did not converge")

    def __repr__(self):
        terms = []
        for c, m in sorted(self._parts.items(), key=lambda cm: _sort_key(cm[0])):
            terms.append(f"{m:+d}*arccot({c})")
        if self._pi or not terms:
            terms.insert(0, f"{self._pi}*pi")
        return "Angle(" + " ".join(terms) + ")"


#: the turning count (:func:`_sign_by_turning`) runs where the arccots have at most this many
#: square roots in all and this many arccots counted with multiplicity: its products have up
#: to 2^TURNING_ROOTS terms
TURNING_ROOTS, TURNING_STEPS = 12, 64


_ONE = Surd(1)


def _sign_by_turning(parts: dict, r: Fraction, roots: int = TURNING_ROOTS) -> int | None:
    """The sign of theta = sum m arccot(c) + r pi, exactly, by counting half-turns of exact
    products (no enclosure, so no precision limit): None where r is not a multiple of 1/2,
    or the arccots are too many or have more than ``roots`` square roots in all
    (TURNING_ROOTS, TURNING_STEPS).

    arccot(c) = arg(c + i) lies in (0, pi), -arccot(c) = arg(c - i) in (-pi, 0), and
    r pi is |2 r| steps of arg(+-i) = +-pi/2.  With A_j the sum of the first j steps and
    q_j = floor(A_j / pi), the point P_j = product of the first j factors lies on the ray
    of A_j: Im P_j has the sign (-1)^q_j, or is 0 exactly when A_j = q_j pi.  A step of
    (0, pi) keeps q (the new point strictly on q's side) or adds 1; a step of (-pi, 0) keeps
    q (strictly on q's side, or on the ray of q pi itself) or takes 1 away.  Every decision
    is the exact sign of a Surd.  Then theta = A_n - (-r) pi is compared through q_n."""
    if (2 * r).denominator != 1 or sum(abs(m) for m in parts.values()) + abs(2 * r) > TURNING_STEPS:
        return None
    # arccot(c) = arg(c + i) = arg(n + i d) for c = n / d, d > 0 (Surd.ratio: no division)
    pairs = {c: c.ratio or (c, _ONE) for c in parts}
    if len(refine([b for pair in pairs.values() for x in pair for b in x.base])) > roots:
        return None
    steps = [(*pairs[c], 1 if m > 0 else -1) for c, m in parts.items() for _ in range(abs(m))]
    quarter = int(2 * r)
    steps += [(Surd(0), _ONE, 1 if quarter > 0 else -1)] * abs(quarter)   # arg(+-i) = +-pi/2
    x, y, q = _ONE, Surd(0), 0                      # P = x + i y, A = 0: q = 0
    for a, b, d in steps:
        # P (a + d i b): arg grows by arccot(a / b) (d = 1) or shrinks by it (d = -1)
        x, y = x * a - d * y * b, y * a + d * x * b
        side = y.sign() * (1 if q % 2 == 0 else -1)     # > 0: strictly on q's side
        if d > 0:
            if side <= 0:
                q += 1
        elif side < 0:
            # below q pi: A lies in ((q - 1) pi, q pi), never on (q - 1) pi itself (the step
            # is shorter than pi); on the axis (side 0) it is q pi exactly, and q stays
            q -= 1
    # theta = A_n exactly (r pi is among the steps): A_n in [q pi, (q + 1) pi)
    if q > 0 or (q == 0 and y.sign() != 0):
        return 1
    if q == 0:
        return 0
    return -1


def _sort_key(c: Surd) -> float:
    """A float ordering cotangents for display: beyond the float range, +-inf (never an
    OverflowError: a repr inside an error message must not raise one)."""
    return float_view(c)


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
    ops = c.ratio or (c,)
    # a quotient of many terms (a cotangent after intrinsic flips) is not divided for this
    # normalization; it is exact either way (the zero test decides arccot(c) = j pi / 24)
    if any(x.n_terms > 4 for x in ops):
        return None
    c = ops[0] / ops[1] if len(ops) == 2 else c
    if c.n_terms > 4:
        return None
    # Only radicands built from 2 and 3 can give a multiple of pi/24.
    for r, _ in c.terms():
        while r % 2 == 0:
            r //= 2
        while r % 3 == 0:                 # divisibility by 3 (not halfedge arithmetic)
            r //= 3
        if r != 1:
            return None
    k = _pi24_multiple({c: 1})
    return None if k is None else Fraction(k, 24)


# -- the exact zero test: characters of the Galois group ------------------------------


def _pi24_multiple(parts: dict) -> int | None:
    """k when A = sum m arccot(c) over ``parts`` is exactly k pi / 24, else None (exact).

    A is a rational multiple of pi iff U = e^(2iA) = prod u_c^m, u_c = (c + i)/(c - i), is
    a root of unity.  U lies in L = Q(i, sqrt b_1, ..., sqrt b_N), b one coprime base of all
    the cotangents, whose roots of unity have orders dividing 24.  Expanding U costs up to
    2^N terms.  Instead, with G = Gal(L/Q(i)) (sigma_T: sqrt b -> -sqrt b for b in T) and
    its characters chi_S (S a set of base elements, chi_S(sigma_T) = (-1)^|S & T|),

        E_S(U) = prod over sigma in G of sigma(U)^chi_S(sigma),    U^(2^N) = prod_S E_S(U)

    (Fourier inversion on G), and E_S is multiplicative.  E_S(u_c) = 1 unless S lies in
    the span V_c (over F_2) of the radicands of c; then E_S(u_c) = e_S(u_c)^(2^(N - d_c)),
    with d_c = dim V_c and e_S taken over the 2^d_c automorphisms of Q(i, c) alone: d_c
    complex products, one per basis vector, whose operands halve each time.  With M_S the
    largest d_c over the c with S in V_c,

        X_S = prod over those c of e_S(u_c)^(m_c 2^(M_S - d_c))    in Q(i, sqrt(prod S)),

    and E_S(U) = X_S^(2^(N - M_S)).  So U is a root of unity iff every X_S is one, i.e.
    X_S^24 = 1: the work grows with the size of single cotangents, not with N, and never
    expands a product of cotangents of different faces.  The enclosure of A then only
    picks k.

    In practice on z_c = c + i (u_c = z_c^2 / |z_c|^2), every number only up to a positive
    real factor: e_S(u_c) = e_S(z_c)^2 times one, so X_S = Y_S^2 (Y_S the same product of
    the e_S(z_c)) and X_S^24 = 1 iff Y_S^48 is a positive real; e_S(z_c) = a + i b
    sqrt(prod S) (a, b rational: sigma maps it to its conjugate where chi_S(sigma) = -1),
    half the size of e_S(u_c).  A cotangent made as n / d (``Surd.ratio``: n / (4 A) after
    intrinsic flips) is read as z = n + i d = (c + i) d, whose coefficients are far smaller.

    >>> _pi24_multiple({Surd(2): 1, Surd(3): 1})          # arccot 2 + arccot 3 = pi/4
    6
    >>> _pi24_multiple({Surd(2): 1}) is None
    True
    """
    # a cotangent made as n / d (Surd.ratio: after intrinsic flips n / (4 A)) is read as the
    # pair: u_c = (n + i d)^2 / (n^2 + d^2), and n, d have far smaller coefficients than c
    operands = {c: c.ratio or (c,) for c in parts}
    base = refine([b for ops in operands.values() for x in ops for b in x.base])
    bits: dict[int, int] = {}                       # radicand -> bit mask over base
    weight = _Weights(base)                         # bit mask -> radicand
    factors: dict[int, list] = {}                   # S (mask) -> [(e_S(u_c), m_c, d_c, key)]
    for c, m in parts.items():
        ops = [x._terms if all(b in base for b in x.base) else reexpress(x._terms, base)
               for x in operands[c]]
        # u_c = z^2 / |z|^2 with z = c + i, or z = n + i d (c = n / d: z is (c + i) d): the
        # test runs on z, kept, like everything below, only up to a positive real factor
        # (integer coefficients, no Fraction arithmetic), and squares at the end (Y_S below)
        w = _primitive(tuple(ops) if len(ops) == 2 else (ops[0], {1: 1}))
        # from here on the terms are keyed by bit masks over the base: a product of two
        # square roots is an xor and a cached product, no gcd of (large) radicands
        w = tuple({_mask(r, base, bits): q for r, q in part.items()} for part in w)
        radicands = sorted({_mask(r, base, bits) for x in ops for r in x})
        basis = _f2_basis([r for r in radicands if r])
        items = [(w, 0)]
        for v, pivot in basis:
            items = [z for w, s in items for z in _split(w, s, pivot, v, weight)]
        key = tuple(radicands)
        for w, s in items:
            if any(r and r != s for part in w for r in part):   # pragma: no cover
                raise AssertionError(f"e_S(u) is not in Q(i, sqrt({weight(s)})): a wrong character")
            factors.setdefault(s, []).append((w, m, len(basis), key))
    for group in factors.values():
        top = max(d for _, _, d, _ in group)
        by_key: dict[tuple, list] = {}
        for w, m, d, key in group:
            if m < 0:                   # w^-1 is conj(w) / |w|^2: its conjugate, up to > 0
                w, m = (w[0], {r: -q for r, q in w[1].items()}), -m
            by_key.setdefault(key, []).append(_tpow(w, m << (top - d), weight))
        # Y_S times a positive real, X_S = Y_S^2: X_S^24 == 1 iff Y_S^48 is a positive real
        x, y = _tpow(_tprod([_tprod(ws, weight) for ws in by_key.values()], weight), 48, weight)
        if y or t_sign({weight(r): q for r, q in x.items()}, ()) <= 0:
            return None
    return _nearest_pi24(Angle._raw(parts, Fraction(0)))


def _nearest_pi24(a: Angle) -> int:
    """The integer k with a = k pi / 24, for an angle known to be such a multiple: the only
    integer in the enclosure of 24 a / pi, refined until one is left (k grows with the
    multiplicities: a fixed precision would pick a neighbour of a large k)."""
    size = (1 + a._weight()).bit_length()                # |a| < pi 2^size
    bits = 40 + size
    while True:
        lo, hi = a._scaled(bits)                    # lo <= a 2^bits <= hi
        plo, phi = pi_bounds(bits)                 # plo <= pi 2^bits <= phi, plo > 0
        first = -(-24 * lo // (plo if lo < 0 else phi))     # ceil of the least 24 a / pi
        last = 24 * hi // (phi if hi < 0 else plo)          # floor of the largest
        if first == last:
            return first
        if bits > 4 * arccots.PRECISION_LIMIT:      # pragma: no cover - a is such a multiple
            raise AssertionError(f"{a!r} is not a multiple of pi / 24")
        bits *= 2


def _primitive(z):
    """z times a positive rational: integer coefficients without a common factor."""
    den = 0
    for part in z:
        for q in part.values():
            if type(q) is not int:
                den = den * q.denominator // math.gcd(den, q.denominator) if den else q.denominator
    if den:
        z = tuple({r: int(q * den) for r, q in part.items()} for part in z)
    g = math.gcd(*z[0].values(), *z[1].values())       # stops scanning at a gcd of 1
    if g > 1:
        z = tuple({r: q // g for r, q in part.items()} for part in z)
    return z


def _power_primitive(z, base: tuple):
    """z made primitive where z is a power of a primitive element (integer coefficients):
    without the gcd of two coefficients (quadratic in their size; 190,000 bits each in a
    zero test of 9 square roots).  A prime p sharing all coefficients of such a power
    divides 2 or an element of ``base``: otherwise p is unramified in L = Q(i, sqrt b, ...)
    and prime to the index of Z[i, sqrt b, ...] in its ring of integers, so p | z^n there
    gives p | z, not primitive.  So dividing out 2 and the elements of ``base`` while they
    divide every coefficient (a gcd with a small number each time) leaves z primitive."""
    values = [q for part in z for q in part.values()]
    if not any(values):         # 0 (never a power of a nonzero element): nothing to divide
        return z
    k = min(((q & -q).bit_length() - 1 for q in values), default=0)
    if k > 0:
        values = [q >> k for q in values]
    g = 1 << max(k, 0)
    for b in base:
        while (h := math.gcd(b, *values)) > 1:
            g *= h
            values = [q // h for q in values]
    if g > 1:
        z = tuple({r: q // g for r, q in part.items()} for part in z)
    return z


def _mask(r: int, base: tuple, memo: dict) -> int:
    """The radicand r (a product of distinct base elements) as a bit mask over ``base``."""
    m = memo.get(r)
    if m is None:
        m = sum(1 << i for i, b in enumerate(base) if r % b == 0)
        memo[r] = m
    return m


def _f2_basis(masks: list[int]) -> list[tuple[int, int]]:
    """A reduced echelon basis of the span of ``masks`` over F_2: [(vector, pivot bit)].

    Reduced: no vector has another's pivot bit, so flipping the pivot's square root alone
    is an automorphism that changes that basis vector and no other (the dual basis).
    """
    basis: list[list[int]] = []
    for v in masks:
        for w, p in basis:
            if v >> p & 1:
                v ^= w
        if v:
            p = v.bit_length() - 1
            for row in basis:
                if row[0] >> p & 1:
                    row[0] ^= v
            basis.append([v, p])
    return [(v, p) for v, p in basis]


class _Weights:
    """The radicand of a bit mask over ``base`` (the product of its base elements),
    cached: ``weight(mask)``."""

    def __init__(self, base: tuple):
        self.base, self.known = base, {0: 1}

    def __call__(self, mask: int) -> int:
        r = self.known.get(mask)
        if r is None:
            r = self.known[mask] = math.prod(b for i, b in enumerate(self.base) if mask >> i & 1)
        return r


def _m_mul(ta: dict, tb: dict, weight: _Weights) -> dict:
    """``ta * tb`` for integer term dicts keyed by bit masks over one base:
    sqrt(r_S) sqrt(r_T) = r_(S & T) sqrt(r_(S ^ T)).  A square runs over each pair once."""
    acc: dict = {}
    if ta is tb:
        items = list(ta.items())
        pairs = ((items[i], items[j], 1 if i == j else 2)
                 for i in range(len(items)) for j in range(i, len(items)))
    else:
        pairs = ((a, b, 1) for a in ta.items() for b in tb.items())
    for (s1, q1), (s2, q2), k in pairs:
        common = s1 & s2
        q = k * q1 * q2 if not common else k * q1 * q2 * weight(common)
        r = s1 ^ s2
        t = acc.get(r)
        if t is None:
            acc[r] = q
        else:
            t += q
            if t:
                acc[r] = t
            else:
                del acc[r]
    return acc


def _split(w, s: int, pivot: int, v: int, weight: _Weights):
    """The two halves w sigma(w) and w / sigma(w) of w under sigma: sqrt b -> -sqrt b
    (b the base element of bit ``pivot``; terms keyed by bit masks).

    Up to a positive real factor (cotangents are real, so |sigma(w)|^2 > 0), w / sigma(w)
    is w * conj(sigma(w)); the second half carries the character of ``v`` (``s ^ v``).
    With w = x + i y and x = x0 + x1 sqrt b, y = y0 + y1 sqrt b (x0, ..., y1 free of
    sqrt b), x sigma(x) = x0^2 - b x1^2 (and so for y), x sigma(y) + y sigma(x) =
    2 (x0 y0 - b x1 y1) and y sigma(x) - x sigma(y) = 2 sqrt b (x0 y1 - x1 y0):

        w sigma(w)       = x sigma(x) - y sigma(y) + i (x sigma(y) + y sigma(x)),
        w conj(sigma(w)) = x sigma(x) + y sigma(y) + i (y sigma(x) - x sigma(y)),

    eight products of halves, a quarter of the work of the two complex products.
    """
    bit, b = 1 << pivot, weight(1 << pivot)
    (x0, x1), (y0, y1) = (({r: q for r, q in part.items() if not r & bit},
                           {r ^ bit: q for r, q in part.items() if r & bit}) for part in w)
    xx = t_add(_m_mul(x0, x0, weight), t_scale(_m_mul(x1, x1, weight), b), negate=True)[0]
    yy = t_add(_m_mul(y0, y0, weight), t_scale(_m_mul(y1, y1, weight), b), negate=True)[0]
    xy = t_add(_m_mul(x0, y0, weight), t_scale(_m_mul(x1, y1, weight), b), negate=True)[0]
    yx = t_add(_m_mul(x0, y1, weight), _m_mul(x1, y0, weight), negate=True)[0]
    yield _primitive((t_add(xx, yy, negate=True)[0], t_scale(xy, 2))), s
    yield _primitive((t_add(xx, yy)[0], {r | bit: 2 * q for r, q in yx.items()})), s ^ v


def _tmul(z, w, weight: _Weights, powers: bool = False):
    """Complex product of (real, imaginary) term dicts keyed by bit masks, made primitive
    (``powers``: z and w are powers of one primitive element, :func:`_power_primitive`)."""
    (a, b), (c, d) = z, w
    zw = (t_add(_m_mul(a, c, weight), _m_mul(b, d, weight), negate=True)[0],
          t_add(_m_mul(a, d, weight), _m_mul(b, c, weight))[0])
    return _power_primitive(zw, weight.base) if powers else _primitive(zw)


def _tpow(z, n: int, weight: _Weights):
    """z**n made primitive, n >= 0, z primitive, by repeated squaring."""
    out = ({0: 1}, {})
    while n:
        if n & 1:
            out = _tmul(out, z, weight, powers=True)
        n >>= 1
        if n:
            z = _tmul(z, z, weight, powers=True)
    return out


def _tprod(zs: list, weight: _Weights):
    """The product of ``zs`` by a balanced tree (operands of similar size)."""
    if not zs:
        return ({0: 1}, {})
    while len(zs) > 1:
        zs = [_tmul(zs[i], zs[i + 1], weight) if i + 1 < len(zs) else zs[i]
              for i in range(0, len(zs), 2)]
    return zs[0]


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


@lru_cache(maxsize=1024)
def _atan_eighth(k: int, bits: int) -> tuple[int, int]:
    """Bounds of atan(k/8) * 2**bits, 1 <= k <= 8 (the reduction points of _atan_bounds)."""
    return _atan_series(k, 8, bits)


@lru_cache(maxsize=64)
def pi_bounds(bits: int) -> tuple[int, int]:
    """Bounds (lo, hi) of pi * 2**bits, from pi = 4 atan(1)."""
    lo, hi = _atan_series(1, 1, bits)
    return 4 * lo, 4 * hi


def _atan_bounds(p: int, q: int, bits: int) -> tuple[int, int]:
    """Bounds (lo, hi) of atan(p/q) * 2**bits for integers p and q > 0 (no Fraction: this is
    the inner loop of every enclosure)."""
    if p < 0:
        lo, hi = _atan_bounds(-p, q, bits)
        return -hi, -lo
    if p > q:
        # atan(s) = pi/2 - atan(1/s)
        plo, phi = pi_bounds(bits)
        lo, hi = _atan_bounds(q, p, bits)
        return plo // 2 - hi, -(-phi // 2) - lo
    if 16 * p <= q:
        return _atan_series(p, q, bits)
    k = (16 * p + q) // (2 * q)                     # the nearest k/8 to p/q, k >= 1
    # atan(s) = atan(k/8) + atan(t), t = (8p - kq)/(8q + kp), |t| <= 1/16: Euler's series
    # then gains 8 bits per term instead of 1 (its ratio is t^2/(1 + t^2) < 1/257)
    alo, ahi = _atan_eighth(k, bits)
    tlo, thi = _atan_bounds(8 * p - k * q, 8 * q + k * p, bits)
    return alo + tlo, ahi + thi


def arccot_bounds(c: Surd, bits: int) -> tuple[int, int]:
    """Bounds (lo, hi) of arccot(c) * 2**bits, arccot in (0, pi): pi/2 - atan(c).

    Not cached: each cotangent of a mesh is enclosed about once per precision, and a
    cache's entries (a key, a link and a result per call, tens of thousands kept alive)
    cost more than the series they save: float views of the 56k bunny's angle defects
    1.36 s with an LRU cache of 65,536 entries, 0.98 s without (each Angle keeps its own
    last enclosure)."""
    k = bits + 2 + (2 * c._bound_count() + 1).bit_length()
    clo, chi = c._bounds(k)             # clo <= c 2^k <= chi, chi - clo <= 2^(k - bits - 2)
    plo, phi = pi_bounds(bits)
    # atan is increasing and 1-Lipschitz: atan(clo) <= atan(c) <= atan(clo) + (chi - clo) 2^-k,
    # one series instead of one per end
    alo, ahi = _atan_bounds(clo, 1 << k, bits)
    ahi += -(-(chi - clo) >> (k - bits))
    return plo // 2 - ahi, -(-phi // 2) - alo


#: The exact angle pi.
pi = Angle._raw({}, Fraction(1))
_ZERO_ANGLE = Angle._raw({}, _ZERO)
