"""The term algebra behind :class:`~.surds.Surd`: exact sums ``sum q_r * sqrt(r)`` as term
dicts ``{radicand: coefficient}`` over a *base*, a sorted tuple of pairwise coprime
integers > 1, none a square, every radicand a product of a subset of the base (1 for
the rational part).  Pure functions on integers, Fractions and dicts (no Surd):
coprime refinement of bases, rewriting terms over a refined base, sums, products and
scalings of term dicts, and their exact sign.

Package-internal: :mod:`.surds` builds its number type on it, and the exact angles
(:mod:`.angles`, :mod:`.measures`) and the exact cotangents
(:mod:`ddg_oracle.reference.cotangents`) use it where they work on the terms of many
numbers at once.  Exact: no float decides anything.
"""

from __future__ import annotations

from fractions import Fraction
from math import gcd, isqrt, prod

from .intervals import terms_top_bit

__all__ = ["SMALL_SQUARES", "strip_small_squares", "refine", "reexpress", "pruned_base", "t_add",
           "t_mul", "t_scale", "t_split", "t_bounds", "t_sign"]



# (p, p*p) for the primes below 100: squares stripped from new radicands.
SMALL_SQUARES = tuple(
    (p, p * p) for p in range(2, 100) if all(p % d for d in range(2, isqrt(p) + 1))
)


_ODD_SMALL_PRIMES = prod(p for p, _ in SMALL_SQUARES[1:])


def strip_small_squares(m):
    """``(c, m')`` with ``m == c*c*m'`` and m' free of squares of primes < 100 (m > 0).

    >>> strip_small_squares(2**5 * 3**3 * 97**2 * 101**2)
    (1164, 61206)
    """
    c = 1
    twos = (m & -m).bit_length() - 1            # the power of 2 in m, by a bit trick
    if twos > 1:
        m >>= twos & ~1
        c <<= twos >> 1
    g = gcd(m, _ODD_SMALL_PRIMES)               # one gcd finds the odd primes to try
    if g > 1:
        for p, pp in SMALL_SQUARES[1:]:
            if g % p == 0:
                while m % pp == 0:
                    m //= pp
                    c *= p
    return c, m


def refine(elements, coprime=()):
    """Coprime refinement: sorted tuple of pairwise coprime non-squares > 1.

    Every input element (> 1) is a product of powers of the output elements.
    Uses gcd splitting only: the product of the work list and the output
    strictly decreases at every split, so the loop terminates.  ``coprime``:
    elements already pairwise coprime (a base), taken as they are, so that
    merging a few elements into a base of n costs O(n) gcds, not O(n^2).

    >>> refine([6, 10])
    (2, 3, 5)
    >>> refine([12, 18])
    (2, 3)
    >>> refine([10], coprime=(3, 7, 22))
    (2, 3, 5, 7, 11)
    """
    out = list(coprime)
    work = [n for n in elements if n > 1]
    # many elements (the zero test of a 128-corner vertex refines 128 distinct 300-bit
    # radicands): one gcd with the product of ``out`` tells that n is coprime to all of
    # it, the common case, where a gcd per element made the loop quadratic.  A few merged
    # into a large base: the product would cost more than the gcds it saves.
    whole = prod(out) if len(work) > 8 else None
    while work:
        n = work.pop()
        if whole is not None and gcd(n, whole) == 1:
            out.append(n)
            whole *= n
            continue
        for i, b in enumerate(out):
            g = gcd(n, b)
            if g != 1:
                out[i] = out[-1]
                out.pop()
                if whole is not None:
                    whole //= b
                work.append(g)
                if b != g:
                    work.append(b // g)
                if n != g:
                    work.append(n // g)
                break
        else:               # never with the product: gcd(n, whole) != 1 named such a b
            out.append(n)
    result = []
    for c in out:
        s = isqrt(c)
        while s * s == c:
            c = s
            s = isqrt(c)
        result.append(c)
    result.sort()
    return tuple(result)


def reexpress(terms, base):
    """``terms`` (over an old base) rewritten over ``base``, a refinement of it."""
    out = {}
    for r, q in terms.items():
        rad = 1
        if r != 1:
            k = 1
            for c in base:
                if r % c == 0:
                    e = 0
                    while r % c == 0:
                        r //= c
                        e += 1
                    if e & 1:
                        rad *= c
                    if e > 1:
                        k *= c ** (e >> 1)
                    if r == 1:
                        break
            if k != 1:
                q = q * k
        if rad in out:
            s = out[rad] + q
            if s:
                out[rad] = s
            else:
                del out[rad]
        else:
            out[rad] = q
    return out


def pruned_base(base, terms):
    """The elements of ``base`` that divide some radicand of ``terms``."""
    if not terms or not base:
        return ()
    if len(base) == 1:
        for r in terms:
            if r != 1:
                return base
        return ()
    lcm = 1
    for r in terms:
        if r != 1 and lcm % r:
            lcm = lcm * (r // gcd(lcm, r))
    if lcm == 1:
        return ()
    used = tuple(b for b in base if lcm % b == 0)
    return base if len(used) == len(base) else used


def t_add(ta, tb, negate=False):
    """``ta + tb`` (``ta - tb`` if negate) for term dicts over one base.

    Returns ``(terms, cancelled)``; ``cancelled`` tells whether a radicand vanished.
    """
    out = dict(ta)
    cancelled = False
    for r, q in tb.items():
        s = out.get(r)
        if s is None:
            out[r] = -q if negate else q
        else:
            s = s - q if negate else s + q
            if s:
                out[r] = s
            else:
                del out[r]
                cancelled = True
    return out, cancelled


#: t_mul multiplies and adds coefficients with denominators up to this size as they are
_SMALL_DENOMINATOR_BITS = 64


def t_mul(ta, tb):
    """``ta * tb`` for term dicts over one base (radicands squarefree over it).

    ``sqrt(r1)*sqrt(r2) = g*sqrt((r1/g)*(r2/g))`` with ``g = gcd(r1, r2)``.  Integers and
    small fractions (the exact zero test's products) are multiplied and added as they are;
    integer coefficients stay integers (``angles.py`` relies on that).  Large fractions are
    accumulated as integer pairs (numerator, denominator) and reduced once per output
    term: a Fraction product and sum cost about four gcds each, and after many intrinsic
    flips the coefficients have hundreds of digits (the gcds were most of the time).  The
    first coefficient of each picks the way (a scan of every one cost more than the small
    products): both are exact for any mix.
    """
    if not ta or not tb:
        return {}
    q1, q2 = next(iter(ta.values())), next(iter(tb.values()))
    direct = ((type(q1) is int or q1.denominator.bit_length() <= _SMALL_DENOMINATOR_BITS)
              and (type(q2) is int or q2.denominator.bit_length() <= _SMALL_DENOMINATOR_BITS))
    acc: dict = {}
    for r1, q1 in ta.items():
        for r2, q2 in tb.items():
            if r1 == 1:
                r, g = r2, 1
            elif r2 == 1:
                r, g = r1, 1
            else:
                g = gcd(r1, r2)
                r = r1 * r2 if g == 1 else (r1 // g) * (r2 // g)
            if direct:
                # a nonzero product; a sum that cancels leaves the dict at once (no
                # filtering pass over the result: this runs in every exact zero test)
                q = q1 * q2 if g == 1 else q1 * q2 * g
                s = acc.get(r)
                if s is None:
                    acc[r] = q
                else:
                    s += q
                    if s:
                        acc[r] = s
                    else:
                        del acc[r]
                continue
            n, d = q1.numerator * q2.numerator * g, q1.denominator * q2.denominator
            a = acc.get(r)
            if a is None:
                acc[r] = [n, d]
            elif a[1] == d:
                a[0] += n
            else:
                # one common denominator (the lcm: a plain product would grow with every
                # term that lands here)
                e = a[1]
                g = gcd(e, d)
                a[0], a[1] = a[0] * (d // g) + n * (e // g), e // g * d
    if direct:
        return acc
    return {r: Fraction(n, d) for r, (n, d) in acc.items() if n}


def t_scale(terms, k):
    """``terms * k`` for a nonzero rational k."""
    return {r: q * k for r, q in terms.items()}


def t_split(terms, p):
    """``(a, b)`` with ``terms == a + b*sqrt(p)`` and neither using p."""
    a, b = {}, {}
    for r, q in terms.items():
        if r % p:
            a[r] = q
        else:
            b[r // p] = q
    return a, b


def t_bounds(terms, k):
    """Integers ``lo <= x * 2**k <= hi`` with ``hi - lo <= 2*len(terms) + 1``.

    An irrational term ``(n/d)*sqrt(r)`` is bounded by
    ``s = isqrt(n*n*r * 4**k)``, so ``|n|*sqrt(r)*2**k`` lies in (s, s+1)
    (r is not a square), then divided by ``d`` rounding outwards (floor
    below, ceiling above, swapped for a negative coefficient).  The rational
    part is rounded outwards the same way.
    """
    lo = hi = 0
    for r, q in terms.items():
        n, d = q.numerator, q.denominator
        if r == 1:
            v = n << k
            lo += v // d
            hi -= -v // d
        else:
            s = isqrt((n * n * r) << (2 * k))
            if n > 0:
                lo += s // d
                hi -= -(s + 1) // d
            else:
                lo += -(s + 1) // d
                hi -= s // d
    return lo, hi


def t_sign(terms, base):
    """Exact sign of a term dict whose radicands are subset products of ``base``."""
    n = len(terms)
    if n == 0:
        return 0
    if n == 1:
        for q in terms.values():
            return 1 if q > 0 else -1
    if n == 2:
        (r1, q1), (r2, q2) = terms.items()
        s1 = 1 if q1 > 0 else -1
        if (q2 > 0) == (s1 > 0):
            return s1
        # q1^2 r1 != q2^2 r2: the two square roots are independent over Q
        return s1 if q1 * q1 * r1 > q2 * q2 * r2 else -s1
    extra = (2 * n + 1).bit_length()
    # relative precision: bits below the largest term (about 2^top), so that a tiny mesh's
    # values (terms near 2^-1200 after a scaling) are enclosed as finely as unit-size ones
    top = terms_top_bit(terms.items())
    for bits in (64, 256, 1024):
        lo, hi = t_bounds(terms, max(0, bits + extra - top))
        if lo > 0:
            return 1
        if hi < 0:
            return -1
    # exact: x = a + b*sqrt(p) on the largest base element p in use
    for i in range(len(base) - 1, -1, -1):
        p = base[i]
        if any(r % p == 0 for r in terms):
            break
    else:  # pragma: no cover - rational terms have n <= 1
        raise AssertionError("irrational terms without a base element")
    rest = base[:i]
    a, b = t_split(terms, p)
    sa, sb = t_sign(a, rest), t_sign(b, rest)
    if sb == 0:
        return sa
    if sa == 0 or sa == sb:
        return sb
    d, _ = t_add(t_mul(a, a), t_scale(t_mul(b, b), p), negate=True)
    return sa * t_sign(d, rest)
