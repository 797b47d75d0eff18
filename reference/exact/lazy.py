"""Lazy exact numbers: an exact value known by how it is computed, decided by enclosures.

CGAL's lazy exact paradigm, for the exact intrinsic flips of chapter 4
(:func:`ddg_oracle.reference.delaunay.flip_to_delaunay`, A4.13): after a few dozen flips a
squared length of a surface from R^3 is a :class:`~.surds.Surd` with hundreds of square
roots, and computing it (a product of two such) takes seconds; the decisions of the flip
algorithm need only its sign, which an enclosure almost always gives at once.

A :class:`Lazy` number is a node of an expression DAG: a *leaf* holding an exact number
(int, Fraction or Surd), or an operation (sum, difference, product, quotient, negation, an
n-ary sum, an intrinsic flip's new diagonal or area) on Lazy numbers.  Each node carries an
enclosure, a pair of integers ``lo <= x 2**k <= hi`` computed from its operands' enclosures
with outward rounding at a working precision of ``p`` bits (relative to its size).
:meth:`Lazy.sign`, comparisons, ``float()`` (correctly rounded) and the enclosures asked
by :class:`~.surds.Quotient` and :func:`~.surds.rounded_sum` refine the enclosures along the
DAG (precision 64, 256, 1024, 4096 bits) and compute the exact value
(:meth:`Lazy.exact`: the same operations on the exact operands, as :class:`~.surds.Surd`
arithmetic) only where they cannot decide: an exact zero, a rounding tie.  Nothing is decided
by a float or a tolerance.  ``hash()`` is the exact value's (so it computes it).

>>> from ddg_oracle.reference.exact import sqrt
>>> x = Lazy.of(sqrt(2)) * Lazy.of(sqrt(3)) - Lazy.of(sqrt(6))
>>> x.sign(), x.exact()                      # undecided by enclosures: an exact zero
(0, Fraction(0, 1))
>>> y = (Lazy.of(sqrt(2)) + 1) / 3
>>> y > Fraction(4, 5), float(y) == float((sqrt(2) + 1) / 3)
(True, True)
"""

from __future__ import annotations

from fractions import Fraction

from .intervals import scaled_bounds, top_bit
from .surds import exact_sum, sign as exact_sign, simplest

__all__ = ["Lazy", "filtered_sign", "flipped"]

#: working precisions (bits) of the enclosures, tried in turn before the exact value
PRECISIONS = (64, 256, 1024, 4096)

_UNSET = object()


# --- enclosures: (lo, hi, k) meaning lo <= x 2**k <= hi; lo is None: none known ----------


def _trim(lo, hi, k, p):
    """The enclosure rounded outward to about ``p`` significant bits."""
    s = max(abs(lo), abs(hi)).bit_length() - p
    if s > 0:
        return lo >> s, -((-hi) >> s), k - s
    return lo, hi, k


def _sum(xs, p):
    # the enclosures on one scale, the finest (shifting up is exact), added end by end
    k = max(x[2] for x in xs)
    lo = hi = 0
    for a, b, j in xs:
        lo += a << (k - j)
        hi += b << (k - j)
    return _trim(lo, hi, k, p)


def _neg(x):
    return -x[1], -x[0], x[2]


def _mul(x, y, p):
    a, b, i = x
    c, d, j = y
    if a >= 0 and c >= 0:
        return _trim(a * c, b * d, i + j, p)
    ps = (a * c, a * d, b * c, b * d)
    return _trim(min(ps), max(ps), i + j, p)


def _div(x, y, p):
    """x / y, or None when the enclosure of y contains 0."""
    a, b, i = x
    c, d, j = y
    if c <= 0 <= d:
        return None
    if a == 0 and b == 0:
        return 0, 0, 0
    # |x / y| < 2^(top x - bottom y): p bits below it
    top = max(abs(a), abs(b)).bit_length() - i
    bottom = min(abs(c), abs(d)).bit_length() - 1 - j
    k = p - (top - bottom) + 2
    s = j - i + k                           # x / y * 2^k = (A / B) * 2^s
    if s >= 0:
        ns, ds = (a << s, b << s), (c, d)
    else:
        ns, ds = (a, b), (c << -s, d << -s)
    qs = [(n // m, -((-n) // m)) for n in ns for m in ds]
    return _trim(min(q[0] for q in qs), max(q[1] for q in qs), k, p)


def _leaf(v, p):
    """The enclosure of an exact number at precision p (exact for dyadic rationals)."""
    if type(v) is int:
        return v, v, 0
    if type(v) is Fraction:
        n, d = v.numerator, v.denominator
        if d & (d - 1) == 0:                # a float's value: a point
            return n, n, d.bit_length() - 1
        k = max(0, p - (n.bit_length() - d.bit_length()) + 2)
        return (n << k) // d, -((-n << k) // d), k
    k = max(0, p - top_bit(v) + 2)
    lo, hi = scaled_bounds(v, k)
    return lo, hi, k


# --- the operations: enclosure and exact value of each node kind ----------------------------


def _flip_parts(x, p):
    """The enclosures of a flip's ``(e + b - a) / 2``, ``(e + c - d) / 2`` and ``2e``."""
    e, a, b, c, d = x[:5]
    return _sum((e, b, _neg(a)), p), _sum((e, c, _neg(d)), p), _sum((e, e), p)


def _flip_length(x, p):
    # |kl|^2 = b + c + (16 A1 A2 - (e + b - a)(e + c - d)) / (2e) (intrinsic.py's module doc)
    u, v, two_e = _flip_parts(x, p)
    A1, A2 = x[5], x[6]
    num = _sum((_mul(_mul(A1, A2, p), (16, 16, 0), p), _neg(_mul(u, v, p))), p)
    q = _div(num, two_e, p)
    return None if q is None else _sum((x[2], x[3], q), p)


def _flip_area_at_i(x, p):
    # area(l, k, i) = ((e + b - a) A2 + (e + c - d) A1) / (2e)
    u, v, two_e = _flip_parts(x, p)
    return _div(_sum((_mul(u, x[6], p), _mul(v, x[5], p)), p), two_e, p)


def _flip_area_at_j(x, p):
    # area(k, l, j) = A1 + A2 - area(l, k, i) (computed so, as intrinsic.py does); its
    # operands are A1, A2 and the node of area(l, k, i), whose enclosure and exact value it
    # shares
    return _sum((x[0], x[1], _neg(x[2])), p)


# The exact values of a flip's new length and first area both divide by 2e: they take
# 1 / (2e) as their first operand (:func:`_half_inverse`), computed once per flip (a Surd's
# inverse, by conjugates, is the costly part of both).

def _exact_flip_length(inv, e, a, b, c, d, A1, A2):
    return b + c + ((-(e + b - a)) * (e + c - d) + 16 * A1 * A2) * inv


def _exact_flip_area_at_i(inv, e, a, b, c, d, A1, A2):
    return ((e + b - a) * A2 + (e + c - d) * A1) * inv


def _exact_flip_area_at_j(A1, A2, at_i):
    return A1 + A2 - at_i


#: the nodes whose exact operation takes 1 / (2e) of their first operand e first
_OVER_2E = frozenset({"flip_length", "flip_area_at_i"})


def _half_inverse(e: "Lazy"):
    """1 / (2e), exact, for the squared length e (a Lazy node) of the edge a flip replaces;
    kept on that node."""
    inv = getattr(e, "_half_inv", None)
    if inv is None:
        inv = e._half_inv = simplest(1 / (2 * e.exact()))
    return inv


#: op name -> (enclosure from the operands' enclosures at precision p, exact value)
_OPS = {
    "add": (lambda x, p: _sum(x, p), lambda a, b: a + b),
    "sub": (lambda x, p: _sum((x[0], _neg(x[1])), p), lambda a, b: a - b),
    "mul": (lambda x, p: _mul(x[0], x[1], p), lambda a, b: a * b),
    "div": (lambda x, p: _div(x[0], x[1], p), lambda a, b: a / b),
    "neg": (lambda x, p: _neg(x[0]), lambda a: -a),
    "sum": (_sum, lambda *a: exact_sum(a)),
    "flip_length": (_flip_length, _exact_flip_length),
    "flip_area_at_i": (_flip_area_at_i, _exact_flip_area_at_i),
    "flip_area_at_j": (_flip_area_at_j, _exact_flip_area_at_j),
}


def _is_exact_number(v) -> bool:
    return type(v) is int or type(v) is Fraction or (
        hasattr(v, "scaled_bounds") and hasattr(v, "terms"))       # a Surd


class Lazy:
    """An exact number as a node of an expression DAG with an integer enclosure (module doc).

    Built with :meth:`of` (a leaf) and arithmetic (``+ - * /``, unary ``-``) with other Lazy
    numbers, ints, Fractions and Surds; decided with :meth:`sign`, comparisons, ``bool``,
    ``float()``; :meth:`exact` is the exact value (a Fraction where rational, else a Surd).
    """

    __slots__ = ("_op", "_args", "_exact", "_p", "_lo", "_hi", "_k", "_half_inv", "__weakref__")

    # -- construction ----------------------------------------------------------------------

    @classmethod
    def of(cls, v) -> "Lazy":
        """``v`` as a Lazy number (a leaf; a Lazy number is returned as it is)."""
        if isinstance(v, Lazy):
            return v
        if not _is_exact_number(v):
            raise TypeError(f"a lazy exact number needs an int, Fraction or Surd, got "
                            f"{type(v).__name__}")
        x = object.__new__(cls)
        # an int as its Fraction: int / int would be a float in the exact operations
        x._op, x._args, x._p, x._lo = "leaf", (), -1, None
        x._exact = Fraction(v) if type(v) is int else v
        return x

    @classmethod
    def _node(cls, op: str, args: tuple) -> "Lazy":
        x = object.__new__(cls)
        x._op, x._args, x._exact, x._p, x._lo = op, args, _UNSET, -1, None
        _refine(x, PRECISIONS[0])
        return x

    @classmethod
    def sum(cls, values) -> "Lazy":
        """The exact sum of ``values`` (Lazy numbers and exact numbers) as one node."""
        return cls._node("sum", tuple(cls.of(v) for v in values))

    def _lazy_sum(self, values):
        # the hook of surds.exact_sum: a sum with a Lazy term stays lazy
        return Lazy.sum(values)

    @property
    def is_leaf(self) -> bool:
        return self._op == "leaf"

    # -- arithmetic ------------------------------------------------------------------------

    def _binary(op, swap=False):
        def method(self, other):
            if not isinstance(other, Lazy):
                if not _is_exact_number(other):
                    return NotImplemented
                other = Lazy.of(other)
            return Lazy._node(op, (other, self) if swap else (self, other))
        return method

    __add__, __radd__ = _binary("add"), _binary("add", True)
    __sub__, __rsub__ = _binary("sub"), _binary("sub", True)
    __mul__, __rmul__ = _binary("mul"), _binary("mul", True)
    __truediv__, __rtruediv__ = _binary("div"), _binary("div", True)
    del _binary

    def __neg__(self):
        return Lazy._node("neg", (self,))

    def __pos__(self):
        return self

    # -- the exact value -------------------------------------------------------------------

    def exact(self):
        """The exact value (Fraction where rational, else Surd): the node's operations on
        its operands' exact values, computed once (iteratively: DAGs of thousands of
        flips are deeper than Python's recursion limit)."""
        if self._exact is _UNSET:
            stack = [self]
            while stack:
                x = stack[-1]
                if x._exact is not _UNSET:
                    stack.pop()
                    continue
                todo = [a for a in x._args if a._exact is _UNSET]
                if todo:
                    stack.extend(todo)
                    continue
                stack.pop()
                values = [a._exact for a in x._args]
                if x._op in _OVER_2E:
                    values.insert(0, _half_inverse(x._args[0]))
                x._exact = simplest(_OPS[x._op][1](*values))
        return self._exact

    # -- decisions -------------------------------------------------------------------------

    def _enclosure(self, p: int):
        _refine(self, p)
        return None if self._lo is None else (self._lo, self._hi, self._k)

    def sign(self) -> int:
        """-1, 0 or 1, exactly: from enclosures at growing precision, else the exact value."""
        if self._exact is not _UNSET:
            return exact_sign(self._exact)
        for p in PRECISIONS:
            x = self._enclosure(p)
            s = None if x is None else _decided(x[0], x[1])
            if s is not None:
                return s
        return exact_sign(self.exact())

    def __bool__(self):
        return self.sign() != 0

    def _cmp(self, other) -> int | None:
        if other is self:
            return 0
        if not isinstance(other, Lazy):
            if not _is_exact_number(other):
                return None
            if type(other) in (int, Fraction) and not other:
                return self.sign()              # against 0: no node for self - 0
        return (self - other).sign()

    def __eq__(self, other):
        s = self._cmp(other)
        return NotImplemented if s is None else s == 0

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

    def __hash__(self):
        return hash(self.exact())

    def __abs__(self):
        return -self if self.sign() < 0 else self

    def __float__(self):
        """The correctly rounded float: enclosures refined until both ends round alike
        (rounding is monotonic), else the exact value's.  OverflowError beyond the float
        range, as for a Surd."""
        if self._exact is not _UNSET:
            return float(self._exact)
        p = PRECISIONS[0]
        while p <= PRECISIONS[-1]:
            x = self._enclosure(p)
            p *= 2
            if x is None:
                continue
            lo, hi, k = x
            if lo == hi == 0:
                return 0.0
            if lo > 0 or hi < 0:
                a, b = _to_float(lo, k), _to_float(hi, k)
                if a == b:
                    if a in (float("inf"), float("-inf")):
                        raise OverflowError("Lazy number too large to convert to float")
                    return a
        return float(self.exact())

    def scaled_bounds(self, k: int) -> tuple[int, int]:
        """Integers ``lo <= self * 2**k <= hi``, ``hi - lo <= 2`` (as
        :meth:`Surd.scaled_bounds`: what :class:`~.surds.Quotient` and
        :func:`~.surds.rounded_sum` enclose with)."""
        if self._exact is not _UNSET:
            return scaled_bounds(self._exact, k)
        p = _ladder(k + self.top_bit() + 4)              # bits down to 2**-k, and more
        while p <= 4 * max(PRECISIONS[-1], k):
            x = self._enclosure(p)
            p *= 2
            if x is None:
                continue
            lo, hi, j = x
            if j >= k:
                lo, hi = lo >> (j - k), -((-hi) >> (j - k))
            else:
                lo, hi = lo << (k - j), hi << (k - j)
            if hi - lo <= 2:
                return lo, hi
        return scaled_bounds(self.exact(), k)

    def interval(self, bits: int):
        """A rational enclosure ``(lo, hi)``, ``hi - lo <= 2**-bits`` (as :meth:`Surd.interval`)."""
        k = max(0, bits) + 2
        lo, hi = self.scaled_bounds(k)
        return Fraction(lo, 1 << k), Fraction(hi, 1 << k)

    def top_bit(self) -> int:
        """t with ``|self| < 2**t`` (:func:`~.intervals.top_bit`)."""
        for p in PRECISIONS:
            x = self._enclosure(p)
            if x is not None:
                lo, hi, k = x
                return max(abs(lo), abs(hi)).bit_length() - k + 1
        return top_bit(self.exact())

    def __repr__(self):
        if self._exact is not _UNSET:
            return f"Lazy({self._exact!r})"
        return f"Lazy({self._op}, ~{float(self)!r})"

    def __reduce__(self):
        return Lazy.of, (self.exact(),)


def _ladder(bits: int) -> int:
    """The working precision for ``bits``: the next power of two from 64 on, so that the
    many enclosures asked of one DAG (a matrix's entries) share its nodes' refinements."""
    return max(PRECISIONS[0], 1 << max(0, bits - 1).bit_length())


def _decided(lo: int, hi: int) -> int | None:
    """The sign an enclosure [lo, hi] decides (0 only for the point 0), else None."""
    if lo > 0:
        return 1
    if hi < 0:
        return -1
    return 0 if lo == hi == 0 else None


def _to_float(n: int, k: int) -> float:
    """n / 2**k, correctly rounded (int true division is); +-inf beyond the range."""
    try:
        return n / (1 << k) if k >= 0 else float(n << -k)
    except OverflowError:
        return float("inf") if n > 0 else float("-inf")


def _refine(root: Lazy, p: int) -> None:
    """Give ``root`` and the nodes below it enclosures at working precision ``p`` (those that
    have one at p or more keep it); iterative, post-order."""
    if root._p >= p:
        return
    stack = [root]
    while stack:
        x = stack[-1]
        if x._p >= p:
            stack.pop()
            continue
        todo = [a for a in x._args if a._p < p]
        if todo:
            stack.extend(todo)
            continue
        stack.pop()
        if x._op == "leaf":
            x._lo, x._hi, x._k = _leaf(x._exact, p)
        else:
            args = []
            for a in x._args:
                if a._lo is None:
                    break
                args.append((a._lo, a._hi, a._k))
            else:
                r = _OPS[x._op][0](args, p)
                if r is None:
                    x._lo = None
                else:
                    x._lo, x._hi, x._k = r
                x._p = p
                continue
            x._lo = None
        x._p = p


class _Enclosure:
    """An enclosure ``lo <= x 2**k <= hi`` (``lo`` None: none known) with the arithmetic of
    Lazy numbers but no DAG and no rounding of sums and products (a filter's formula is
    short: its integers stay small): :func:`filtered_sign`'s first, cheap evaluation."""

    __slots__ = ("lo", "hi", "k")

    def __init__(self, lo, hi, k):
        self.lo, self.hi, self.k = lo, hi, k

    @staticmethod
    def of(v) -> "_Enclosure":
        if type(v) is _Enclosure:
            return v
        if isinstance(v, Lazy):
            if v._p < PRECISIONS[0]:
                _refine(v, PRECISIONS[0])
            return _NONE if v._lo is None else _Enclosure(v._lo, v._hi, v._k)
        if type(v) is int:
            return _Enclosure(v, v, 0)
        return _Enclosure(*_leaf(v, PRECISIONS[0]))

    def __add__(a, b):
        if type(b) is not _Enclosure:
            b = _Enclosure.of(b)
        if a.lo is None or b.lo is None:
            return _NONE
        i, j = a.k, b.k
        if i == j:
            return _Enclosure(a.lo + b.lo, a.hi + b.hi, i)
        if i > j:                               # to the finer scale: exact
            return _Enclosure(a.lo + (b.lo << (i - j)), a.hi + (b.hi << (i - j)), i)
        return _Enclosure((a.lo << (j - i)) + b.lo, (a.hi << (j - i)) + b.hi, j)

    __radd__ = __add__

    def __neg__(a):
        return _NONE if a.lo is None else _Enclosure(-a.hi, -a.lo, a.k)

    def __sub__(a, b):
        return a + -_Enclosure.of(b)

    def __rsub__(a, b):
        return _Enclosure.of(b) + -a

    def __mul__(a, b):
        if type(b) is not _Enclosure:
            b = _Enclosure.of(b)
        if a.lo is None or b.lo is None:
            return _NONE
        x, y, c, d = a.lo, a.hi, b.lo, b.hi
        if x >= 0 and c >= 0:
            return _Enclosure(x * c, y * d, a.k + b.k)
        ps = (x * c, x * d, y * c, y * d)
        return _Enclosure(min(ps), max(ps), a.k + b.k)

    __rmul__ = __mul__

    def __truediv__(a, b):
        if type(b) is not _Enclosure:
            b = _Enclosure.of(b)
        if a.lo is None or b.lo is None:
            return _NONE
        r = _div((a.lo, a.hi, a.k), (b.lo, b.hi, b.k), PRECISIONS[0])
        return _NONE if r is None else _Enclosure(*r)

    def __rtruediv__(a, b):
        return _Enclosure.of(b) / a


_NONE = _Enclosure(None, None, 0)


def filtered_sign(fn, values) -> int:
    """The exact sign of ``fn(*values)`` (``fn`` built of ``+ - * /`` on its arguments; the
    values exact numbers or Lazy ones): first ``fn`` on the values' enclosures (no DAG is
    built), and only when that does not decide, ``fn`` on Lazy numbers (:meth:`Lazy.sign`:
    enclosures refined, else the exact value).  One formula, two number types: the cheap
    filter and the exact decision cannot disagree on what they compute."""
    x = fn(*[_Enclosure.of(v) for v in values])
    s = None if x.lo is None else _decided(x.lo, x.hi)
    if s is not None:
        return s
    return Lazy.of(fn(*(Lazy.of(v) for v in values))).sign()


def flipped(e, a, b, c, d, A1, A2) -> tuple[Lazy, Lazy, Lazy]:
    """The intrinsic flip of the quadrilateral with squared lengths ``e`` (the edge), ``a,
    b, c, d`` and areas ``A1, A2`` (L2.8; names of :mod:`ddg_oracle.reference.intrinsic`)
    as three Lazy numbers: ``|kl|^2``, ``area(l, k, i)``, ``area(k, l, j)``."""
    args = tuple(Lazy.of(v) for v in (e, a, b, c, d, A1, A2))
    at_i = Lazy._node("flip_area_at_i", args)
    return (Lazy._node("flip_length", args), at_i,
            Lazy._node("flip_area_at_j", (args[5], args[6], at_i)))
