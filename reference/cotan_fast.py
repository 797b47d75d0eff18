"""Exact cotan weights and cotan Laplacian, fast: integer arithmetic, same values.

:mod:`reference.laplacian` is the definition of the cotan weights (3.3) and of
the cotan Laplacian (D3.2): exact squared lengths and Surd face areas
(:class:`~reference.metric.PiecewiseFlatSurface`), one cotangent per corner,
weights added edge by edge.  This module computes the *same* exact values
(``==`` on every entry, tested with Hypothesis and on a 1,280-face float
icosphere) about 10 to 15 times faster, standard library only.
:func:`reference.laplacian.cotan_laplacian` dispatches here whenever it
applies (:func:`applies`).

How, exactly at every step:

1. *Integers per face.*  The three points of a face are rationals (floats are
   dyadic rationals), so times ``D``, the lcm of their denominators, they are
   integer vectors; ``u = B - A``, ``v = C - A``.  A cotangent is scale
   invariant, ``cot = <x, y> / |x ^ y|``, hence

       cot(corner c) = N_c / sqrt(G),   N_0 = <u, v>,  N_1 = |u|^2 - <u, v>,
                                         N_2 = |v|^2 - <u, v>,
       G = |u|^2 |v|^2 - <u, v>^2        (= 4 area^2, Lagrange, any dimension).

   From squared side lengths (a piecewise flat surface with rational lengths)
   the same with ``N = a + b - o`` and ``G = 16 area^2`` (Heron, :func:`heron16`).
2. *One square root per face.*  ``G = c^2 m`` with ``m`` free of squares of the
   primes below 100 -- the radicand :func:`reference.exact.sqrt` gives for the
   face -- and ``m = s M``: ``s`` the product of the primes below 100 dividing
   ``m``, ``M`` free of them.  Half a cotangent is ``N_c / (2 c m) * sqrt(m)``:
   the three corners of a face share one denominator.  (When the denominator
   ``D`` is not a power of two, the known square ``D^4`` is divided out of
   ``G`` first, as ``sqrt`` would: it may hold squares of primes above 100.)
3. *Canonical Surds without re-merging.*  An entry is a sum over a few faces
   of ``q_f sqrt(m_f)``.  A :class:`~reference.exact.Surd` needs a base of
   pairwise coprime non-squares whose subset products are the radicands.  When
   the large parts ``M`` of the faces around a vertex are pairwise coprime
   (checked exactly, one gcd per face against the product of the previous
   ones; an edge weight checks its two radicands with one gcd), the base is
   read off the factors: group the primes below 100 and the large parts by the
   set of radicands they divide, one base element per group -- the coarsest
   coprime base, the one Surd addition computes.  Every pair of faces sharing
   an edge shares a vertex, so the vertex checks cover the edge weights too.
   When two large parts share a prime (a few vertices of a float mesh), the
   factors are refined by gcd splitting as Surd addition does (:func:`_refined`).

The cost left is mostly gcds of 200-bit integers (reducing Fractions, checking
coprimality), about ten per face: see docs/performance.md.

No float is used anywhere; a sign is never needed (zero is decided by the
canonical form: an entry is zero iff no term is left).
"""

from __future__ import annotations

import gc
from contextlib import contextmanager
from functools import lru_cache
from fractions import Fraction
from math import gcd, isqrt, lcm, prod
from operator import mul

from .exact.surds import _SMALL_SQUARES, _make, _refine, _reexpress
from .metric import PiecewiseFlatSurface, degenerate_face, heron16
from .polyhedral import PolyhedralSurface
from .sparse import SparseMatrix, _normal

__all__ = ["applies", "face_cotangents", "cotan_weights_fast", "cotan_laplacian_fast"]

_ZERO = Fraction(0)
_PRIMES = tuple(p for p, _ in _SMALL_SQUARES)                   # the primes below 100
_ODD_PRIMES = _PRIMES[1:]
_ODD_PRIMORIAL = prod(_ODD_PRIMES)


def applies(surface) -> bool:
    """Whether the fast path handles ``surface``: a :class:`PolyhedralSurface`, or a
    :class:`PiecewiseFlatSurface` whose squared lengths are all rational."""
    if isinstance(surface, PolyhedralSurface):
        return True
    return (isinstance(surface, PiecewiseFlatSurface)
            and all(isinstance(x, Fraction) for x in surface.squared_lengths))


# --- step 1: integer Gram data per face ------------------------------------------------

# One denominator for the whole mesh if it stays this small (float meshes: all
# coordinates of magnitude above 2**-70 or zero); else one per face, so that a
# single tiny coordinate does not blow up every face's integers.
_COMMON_DENOMINATOR_BITS = 128


def _integer_faces(surface: PolyhedralSurface):
    """``(D, A, B, C)`` per face: its three points times D, integer vectors."""
    P, faces = surface.positions, surface.triangulation.faces
    D = lcm(*{x.denominator for p in P for x in p})
    if D.bit_length() <= _COMMON_DENOMINATOR_BITS:
        pts = [tuple([x.numerator * (D // x.denominator) for x in p]) for p in P]
        return [(D, pts[a], pts[b], pts[c]) for a, b, c in faces]
    out = []
    for face in faces:
        D = lcm(*{x.denominator for v in face for x in P[v]})
        out.append((D, *(tuple([x.numerator * (D // x.denominator) for x in P[v]])
                          for v in face)))
    return out


def _gram_from_positions(surface: PolyhedralSurface):
    """Per face ``(N0, N1, N2, G, S)`` in integers (see the module docstring): the
    points were scaled by D, so ``G = S^2 * 4 area^2`` with ``S = D^2``."""
    t = surface.triangulation
    out = []
    if surface.dimension == 3:          # the common case, written out (2x faster)
        for f, (D, (ax, ay, az), (bx, by, bz), (cx, cy, cz)) in enumerate(_integer_faces(surface)):
            ux, uy, uz = bx - ax, by - ay, bz - az
            vx, vy, vz = cx - ax, cy - ay, cz - az
            uu = ux * ux + uy * uy + uz * uz
            vv = vx * vx + vy * vy + vz * vz
            uv = ux * vx + uy * vy + uz * vz
            G = uu * vv - uv * uv
            if not G:
                raise degenerate_face(t, f, surface.positions)
            out.append((uv, uu - uv, vv - uv, G, D * D))
        return out
    for f, (D, A, B, C) in enumerate(_integer_faces(surface)):
        u = [y - x for x, y in zip(A, B)]
        v = [y - x for x, y in zip(A, C)]
        uu = sum(map(mul, u, u))
        vv = sum(map(mul, v, v))
        uv = sum(map(mul, u, v))
        G = uu * vv - uv * uv
        if not G:
            raise degenerate_face(t, f, surface.positions)
        out.append((uv, uu - uv, vv - uv, G, D * D))
    return out


def _gram_from_lengths(m: PiecewiseFlatSurface):
    """Per face ``(N0, N1, N2, G, S)`` in integers from rational squared lengths (scaled
    by S = D, so ``G = S^2 * 16 area^2``)."""
    sq, eo = m.squared_lengths, m.triangulation.edge_of
    out = []
    for f in range(m.triangulation.n_faces):
        l0, l1, l2 = sq[eo(3 * f)], sq[eo(3 * f + 1)], sq[eo(3 * f + 2)]
        D = lcm(l0.denominator, l1.denominator, l2.denominator)
        a, b, c = (x.numerator * (D // x.denominator) for x in (l0, l1, l2))
        # cot at corner 0 = (|01|^2 + |20|^2 - |12|^2) / (4 area), 4 area = sqrt(16 area^2)
        out.append((a + c - b, a + b - c, b + c - a, heron16(a, b, c), D))
    return out


# --- step 2: one square root per face --------------------------------------------------------


def _split_root(G: int):
    """``(c, s, M)`` with ``G = c^2 * s * M``: ``s`` the product of the primes below
    100 dividing G an odd number of times, ``M`` free of primes below 100 and not a
    square (``M = 1`` when G / s is a square)."""
    v = (G & -G).bit_length() - 1             # the power of 2, at once
    G >>= v
    c = 1 << (v >> 1)
    s = 2 if v & 1 else 1
    g = gcd(G, _ODD_PRIMORIAL)                # the odd primes below 100 dividing G
    if g != 1:
        if gcd(G // g, g) == 1:               # each divides G once (4 faces in 5)
            G //= g
            s *= g
        else:
            for p in _ODD_PRIMES:
                if g % p == 0:
                    G //= p
                    v = 1
                    while G % p == 0:
                        G //= p
                        v += 1
                    if v > 1:
                        c *= p ** (v >> 1)
                    if v & 1:
                        s *= p
                    g //= p
                    if g == 1:
                        break
    if G & 7 == 1:                            # an odd square is 1 mod 8: else no square
        r = isqrt(G)
        if r * r == G:                        # includes G == 1
            return c * r, s, 1
    return c, s, G


@lru_cache(maxsize=4096)
def _small_primes(s: int) -> tuple:
    """The primes below 100 of a product of distinct ones."""
    return tuple(p for p in _PRIMES if s % p == 0)


class _Faces:
    """Per face: radicand ``m`` (1 if rational), denominator ``2 c m`` shared by its
    three half-cotangents (``N_c / (2 c m) * sqrt(m)``), numerators ``(N0, N1, N2)``;
    per radicand its factors ``(s, M)``: the product of its primes below 100, the rest."""

    __slots__ = ("rad", "den", "num", "parts")

    def __init__(self, gram):
        self.rad, self.den, self.num = [], [], []
        self.parts = {1: (1, 1)}
        rad, den, num = self.rad.append, self.den.append, self.num.append
        roots = {}                                  # equal G on many faces (regular meshes)
        for x in gram:
            n0, n1, n2, G, S = x
            key = (G, S) if S & (S - 1) else G      # S matters only if not a power of 2
            hit = roots.get(key)
            if hit is None:
                hit = roots[key] = self._root(G, S)
            rad(hit[0])
            den(hit[1])
            k = hit[2]
            num((n0 * k, n1 * k, n2 * k) if k != 1 else x)    # x[:3] are the numerators

    def _root(self, G: int, S: int):
        """``(m, 2 c m S', k)`` with ``sqrt(G) = (c S' / k) sqrt(m)``, m the radicand
        :func:`reference.exact.sqrt` gives for the face (``G / S^2``)."""
        k = scale = 1
        if S & (S - 1):
            # S is not a power of two: its odd primes would stay in G as squares of
            # primes above 100 that sqrt() never sees; take G / S^2 = n / d in lowest
            # terms as sqrt() does: sqrt(G) = S sqrt(n d) / d
            g = gcd(G, S * S)
            n, k = G // g, S * S // g
            G, scale = n * k, S
        c, s, M = _split_root(G)
        m = s * M
        self.parts.setdefault(m, (s, M))
        return m, 2 * c * m * scale, k

    def edge_value(self, h: int, t: int, sign: int = 1, checked: bool = False):
        """``sign`` times the weight of the edge of halfedges ``h``, ``t`` as an exact
        value (:func:`_value` of :meth:`edge_terms`, the common case inlined: two
        faces with coprime radicands, which are then their own base)."""
        rad, num = self.rad, self.num
        f = h // 3
        m1, n1 = rad[f], num[f][(h + 2) % 3]
        if t >= 0 and n1:
            g = t // 3
            m2, n2 = rad[g], num[g][(t + 2) % 3]
            if n2 and m1 != m2 and m1 != 1 and m2 != 1 and (
                    gcd(self.parts[m1][0], self.parts[m2][0]) == 1 if checked
                    else gcd(m1, m2) == 1):
                if sign < 0:
                    n1, n2 = -n1, -n2
                return _make((m1, m2) if m1 < m2 else (m2, m1),
                             {m1: _fraction(n1, self.den[f]), m2: _fraction(n2, self.den[g])},
                             prune=False)
        return _value(self.edge_terms(h, t, sign), self.parts, checked)

    def edge_terms(self, h: int, t: int, sign: int = 1) -> dict:
        """``{m: q}``: ``sign`` times the half-cotangents opposite halfedge ``h`` and its
        twin ``t`` (``t = -1``: boundary), equal radicands added, zeros dropped."""
        rad, den, num = self.rad, self.den, self.num
        f = h // 3
        m1, n1, d1 = rad[f], sign * num[f][(h + 2) % 3], den[f]
        if t < 0:
            return {m1: _fraction(n1, d1)} if n1 else {}
        g = t // 3
        m2, n2, d2 = rad[g], sign * num[g][(t + 2) % 3], den[g]
        if m1 == m2:                    # one radicand on both sides (regular meshes)
            if d1 != d2:
                n1, n2, d1 = n1 * d2, n2 * d1, d1 * d2
            return {m1: _fraction(n1 + n2, d1)} if n1 + n2 else {}
        out = {m1: _fraction(n1, d1)} if n1 else {}
        if n2:
            out[m2] = _fraction(n2, d2)
        return out


def _gram(surface):
    if isinstance(surface, PolyhedralSurface):
        return _gram_from_positions(surface)
    return _gram_from_lengths(surface)


# --- step 3: canonical Surds ------------------------------------------------------------

def _from_slots(n: int, d: int) -> Fraction:
    # what Fraction(n, d) stores once reduced, without re-checking the types
    x = object.__new__(Fraction)
    x._numerator, x._denominator = n, d
    return x


def _coprime_fraction_maker():
    """A constructor of Fractions from coprime ints (d > 0) that skips the checks:
    ``Fraction._from_coprime_ints`` (Python >= 3.12) or slot assignment (3.11),
    used only if it passes a probe; else plain ``Fraction``."""
    make = getattr(Fraction, "_from_coprime_ints", _from_slots)
    try:
        probe = make(-3, 4)
        if probe == Fraction(-3, 4) and hash(probe) == hash(Fraction(-3, 4)) \
                and str(probe) == "-3/4" and probe + 1 == Fraction(1, 4):
            return make
    except Exception:   # pragma: no cover - another Fraction implementation
        pass
    return Fraction     # pragma: no cover


_coprime_fraction = _coprime_fraction_maker()


def _fraction(n: int, d: int) -> Fraction:
    """``Fraction(n, d)`` for ints, ``d > 0``, in half the time (the types are known)."""
    g = gcd(n, d)
    if g != 1:
        n //= g
        d //= g
    return _coprime_fraction(n, d)


def _coprime_large_parts(rads, parts) -> bool:
    """Whether the distinct large parts of the radicands are pairwise coprime (exact):
    each against the product of the previous ones, one gcd per radicand."""
    seen = set()
    P = 1
    for m in rads:
        M = parts[m][1]
        if M != 1 and M not in seen:
            if P != 1 and gcd(P, M) != 1:
                return False
            seen.add(M)
            P *= M
    return True


def _value(terms: dict, parts, checked: bool = False):
    """``sum q * sqrt(m)`` over ``terms = {m: q}`` (q nonzero Fractions) as a canonical
    Surd, or a Fraction when rational.  ``checked``: the large parts are known to be
    pairwise coprime."""
    if len(terms) < 2:
        if not terms:
            return _ZERO
        (m, q), = terms.items()
        return q if m == 1 else _make((m,), terms, prune=False)
    if len(terms) == 2:                 # an edge: two faces, the common case
        m1, m2 = terms
        (s1, M1), (s2, M2) = parts[m1], parts[m2]
        if gcd(s1, s2) == 1 and (checked or gcd(M1, M2) == 1):
            # coprime radicands are their own base (1, the rational part, is none)
            base = (m2,) if m1 == 1 else (m1,) if m2 == 1 else (m1, m2) if m1 < m2 else (m2, m1)
            return _make(base, terms, prune=False)
    if not checked and not _coprime_large_parts(terms, parts):
        return _refined(terms, parts)
    # The coarsest coprime base: one element per set of radicands a factor divides.
    pattern: dict[int, int] = {}
    bit = 1
    for m in terms:
        s, M = parts[m]
        for x in _small_primes(s):
            pattern[x] = pattern.get(x, 0) | bit
        if M != 1:
            pattern[M] = pattern.get(M, 0) | bit
        bit <<= 1
    group: dict[int, int] = {}
    for x, key in pattern.items():
        group[key] = group.get(key, 1) * x
    return _make(tuple(sorted(group.values())), terms, prune=False)


def _refined(terms: dict, parts):
    """:func:`_value` when a prime above 100 divides two radicands (a few vertices of a
    float mesh): refine the factors by gcd splitting, as Surd addition does, and
    rewrite the terms over that base (a square factor may move into a coefficient)."""
    factors = set()
    for m in terms:
        s, M = parts[m]
        factors.update(_small_primes(s))
        if M != 1:
            factors.add(M)
    base = _refine(list(factors))
    return _normal(_make(base, _reexpress(terms, base)))


@contextmanager
def _collector_paused():
    """Pause the cyclic garbage collector while building the result.

    The fast path allocates a few acyclic objects per face (Fractions, Surds,
    dicts) that all survive; the collector would traverse them again and again
    (about a fifth of the time on a 10,000-face mesh).  Restored on exit.
    """
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was:
            gc.enable()


# --- the public functions -----------------------------------------------------------------


def face_cotangents(surface) -> list[tuple]:
    """The exact cotangents of the three corners of every face, fast.

    ``[(cot0, cot1, cot2), ...]`` equal to
    ``PiecewiseFlatSurface.corner_cot(f, c)`` (Fractions where rational).

    >>> from reference import surfaces
    >>> face_cotangents(surfaces.grid(1, 1))[0]
    (Fraction(1, 1), Fraction(0, 1), Fraction(1, 1))
    """
    fc = _Faces(_gram(surface))
    return [tuple(_value({m: _fraction(2 * n, d)}, fc.parts) if n else _ZERO for n in ns[:3])
            for m, d, ns in zip(fc.rad, fc.den, fc.num)]


def cotan_weights_fast(surface) -> dict:
    """(3.3): the cotan weights, equal to :func:`reference.laplacian.cotan_weights`.

    Same keys (every edge id) and values (``==``), Fractions where rational;
    computed as described in the module docstring.  For surfaces that
    :func:`applies` rejects, use the definition.

    >>> from reference import surfaces
    >>> from reference.laplacian import cotan_weights
    >>> s = surfaces.icosahedron()
    >>> cotan_weights_fast(s) == cotan_weights(s)
    True
    """
    t = surface.triangulation
    with _collector_paused():
        fc = _Faces(_gram(surface))
        return {e: fc.edge_value(*t.edge_halfedges(e)) for e in range(t.n_edges)}


def cotan_laplacian_fast(surface) -> SparseMatrix:
    """D3.2: the cotan Laplacian, equal to the definition
    :func:`reference.laplacian.cotan_laplacian_from_weights` (``==`` entrywise).

    Diagonal first: vertex ``i`` collects, from each face at one of its corners,
    the half-cotangents of the two other corners (one term per face); then each
    off-diagonal entry is minus the weight of the edge(s) between ``i`` and ``j``
    (several edges between two vertices are summed, loops ignored).

    >>> from reference import surfaces
    >>> from reference.laplacian import cotan_laplacian_from_weights
    >>> s = surfaces.torus(6, 4)
    >>> cotan_laplacian_fast(s) == cotan_laplacian_from_weights(s)
    True
    """
    with _collector_paused():
        return _laplacian(surface)


def _laplacian(surface) -> SparseMatrix:
    t = surface.triangulation
    fc = _Faces(_gram(surface))
    n = t.n_vertices
    rad, den, num, parts = fc.rad, fc.den, fc.num, fc.parts
    # diag[i] = {m: [numerator, denominator]}: integer sums, one Fraction per term at the end
    diag: list[dict] = [{} for _ in range(n)]

    def add(i, m, N, d):
        acc = diag[i].get(m)
        if acc is None:
            diag[i][m] = [N, d]
        elif acc[1] == d:
            acc[0] += N
        else:
            acc[0], acc[1] = acc[0] * d + N * acc[1], acc[1] * d

    for f, (a, b, c) in enumerate(t.faces):
        n0, n1, n2 = num[f][:3]
        m, d = rad[f], den[f]
        if a != b and b != c and a != c:
            # corner a: halfedges a->b (opposite corner 2) and c->a (opposite corner 1)
            add(a, m, n1 + n2, d)
            add(b, m, n0 + n2, d)
            add(c, m, n0 + n1, d)
        else:                   # a loop halfedge (tail == head) adds nothing
            for k, N in ((0, n2), (1, n0), (2, n1)):
                x, y = (a, b, c)[k], (a, b, c)[(k + 1) % 3]
                if x != y:
                    add(x, m, N, d)
                    add(y, m, N, d)
    rows: dict[int, dict] = {}
    clean = [True] * n          # the large parts of the faces at i are pairwise coprime
    for i, acc in enumerate(diag):
        if len(acc) > 1:        # every face at i, also those whose terms cancel
            clean[i] = _coprime_large_parts(acc, parts)
        terms = {m: _fraction(N, d) for m, (N, d) in acc.items() if N}
        v = _value(terms, parts, checked=clean[i])
        if v:
            rows[i] = {i: v}
    for e in range(t.n_edges):
        h, tw = t.edge_halfedges(e)
        i, j = t.tail(h), t.head(h)
        if i == j:
            continue
        w = fc.edge_value(h, tw, -1, clean[i] or clean[j])  # both faces are at i and j
        if not w:               # zero, or equal radicands in two spellings cancelled
            continue
        ri, rj = rows.setdefault(i, {}), rows.setdefault(j, {})
        if j in ri:                                  # another edge between i and j
            w = _normal(ri[j] + w)
            if not w:
                del ri[j], rj[i]
                continue
        ri[j] = rj[i] = w
    # exact nonzero entries already, rational ones Fractions; drop rows emptied by
    # cancelling multi-edges
    return SparseMatrix._trusted((n, n), {i: r for i, r in rows.items() if r})
