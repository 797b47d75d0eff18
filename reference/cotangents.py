"""Exact cotangents of corners, fast: integers per face, canonical forms on demand.

The cotangent of a corner of a triangle is intrinsic (D2.6): from the squared side
lengths ``a``, ``b``, ``c`` of the halfedges 0, 1, 2 of a face, ``cot(corner c) =
N_c / sqrt(G)`` with ``G = 16 area^2`` and integer numerators ``N``.  This module holds
that representation, shared by the chapter-2 fast routes
(:mod:`~ddg_oracle.reference.curvature_fast`: angle sums, Gauss-Bonnet) and the
chapter-3 ones (:mod:`~ddg_oracle.reference.cotan_fast`: cotan weights, Laplacian).
Data flow one way: positions -> integer squared lengths -> ``G``, ``N`` -> values.

How, exactly at every step:

1. *Integers per face, from lengths.*  A surface with positions first becomes integer
   squared edge lengths over the common denominator ``D`` of its coordinates (times
   ``D^2``; one denominator per face where the common one would be too large); a
   piecewise flat surface's rational squared lengths are scaled per face.  Then, with
   ``s = a + c - b`` (twice the inner product of the two sides at corner 0),

       G = 16 area^2 = 4 a c - s^2,   N_0 = s,   N_1 = 2 a - s,   N_2 = 2 c - s

   (two products per face where Heron's formula needs six; the same ``G``).
   :class:`FaceData` holds ``G`` per face and ``N`` per halfedge (the corner opposite
   it).
2. *The value kept as it comes.*  A sum ``1/2 sum_f n_f / sqrt(G_f)`` (an edge weight,
   a diagonal entry, a corner cotangent) is returned as a :class:`CotanSum`: a
   :class:`~ddg_oracle.reference.exact.Surd` that keeps these integers and computes its
   canonical form (base, terms) only when something needs it -- equality with another
   Surd, arithmetic, ``str``.  What is cheap is done on the integers, exactly:

   * *rational or not* (a Fraction must be returned where the value is rational, as
     the definition does): with nonzero ``n_1, n_2`` an edge weight is irrational
     unless ``G_1 G_2`` is a perfect square (the square roots of 1 and of integers with
     different square-free parts are linearly independent over Q); a diagonal entry is
     a sum of *positive* terms (two cotangents of one triangle add up to
     ``sin(alpha + beta) / (sin alpha sin beta) > 0``), so it is irrational unless
     every ``G_f`` is a square.  Squares are excluded by the power of 2 and the
     residues of the odd part modulo ``2^6 * 3 * 5 * ... * 37`` (:func:`_odd_residue`,
     :func:`maybe_square`: about 1 odd non-square in 3,000 passes), then by
     :func:`math.isqrt`.  Values that may be rational take the canonical route at once
     (step 3);
   * the *sign*: the signs of the ``n``, or for two terms of opposite signs
     ``n_1^2 G_2`` against ``n_2^2 G_1`` (never equal: the value is irrational);
   * ``float()``, ``hash()`` and enclosures, correctly rounded / rigorous as for every
     Surd: ``|n| 2^k / (2 sqrt(G))`` lies in ``[s, s + 1]`` for
     ``s = isqrt(n^2 4^k // 4G)`` (:meth:`CotanSum._bounds`).
3. *Canonical form on demand.*  ``G = c^2 m`` with ``m`` free of squares of the primes
   below 100 -- the radicand :func:`ddg_oracle.reference.exact.sqrt` gives for the face --
   and ``m = s M``: ``s`` the product of the primes below 100 dividing ``m``, ``M`` free
   of them (:func:`_split_root`; computed once per face, when first needed).  Half a
   cotangent is ``N_c / (2 c m) * sqrt(m)``.  An entry's terms ``{m: q}`` become a
   canonical Surd (:func:`_value`): when the large parts ``M`` are pairwise coprime
   (checked exactly with gcds), the base is read off the factors -- group the primes
   below 100 and the large parts by the set of radicands they divide, one base element
   per group, the coarsest coprime base, the one Surd addition computes; when two large
   parts share a prime the factors are refined by gcd splitting as Surd addition does
   (:func:`_refined`).

Hence building the values costs integer products and one residue test per edge; the
gcds of 200-bit integers that canonical forms need (about ten per face) are paid by the
values that are compared, added or printed.  No float is used anywhere, and the
interpreter's state (the garbage collector, ``Fraction``'s internals) is left alone.
"""

from __future__ import annotations

from functools import lru_cache
from fractions import Fraction
from math import gcd, isqrt, lcm, prod

from .combinatorics import next_corner
from .exact.rationals import (points_on_common_denominator, shared_denominator,
                              shared_denominator_of_fractions)
from .exact.surds import Surd, from_terms, simplest
from .exact.terms import SMALL_SQUARES, reexpress, refine
from .metric import PiecewiseFlatSurface, degenerate_face
from .polyhedral import PolyhedralSurface

__all__ = ["applies", "FaceData", "CotanSum", "face_data", "face_cotangents"]

_ZERO = Fraction(0)
_PRIMES = tuple(p for p, _ in SMALL_SQUARES)                   # the primes below 100
_ODD_PRIMES = _PRIMES[1:]
_ODD_PRIMORIAL = prod(_ODD_PRIMES)


def applies(surface) -> bool:
    """Whether the fast path handles ``surface``: a :class:`PolyhedralSurface`, or a
    :class:`PiecewiseFlatSurface` whose squared lengths are all rational."""
    if isinstance(surface, PolyhedralSurface):
        return True
    return (isinstance(surface, PiecewiseFlatSurface)
            and all(isinstance(x, Fraction) for x in surface.squared_lengths))


# --- perfect squares, excluded cheaply ---------------------------------------------------------


def _square_residues(m: int) -> bytes:
    """``t[r] == 1`` iff ``r`` is a square modulo ``m``."""
    t = bytearray(m)
    for y in range(m):
        t[y * y % m] = 1
    return bytes(t)


_SQ64 = _square_residues(64)
#: three moduli, products of the odd primes up to 37, and their tables of squares
_M1, _M2, _M3 = 3 * 5 * 7 * 11 * 13, 17 * 19 * 23, 29 * 31 * 37
_SQ1, _SQ2, _SQ3 = _square_residues(_M1), _square_residues(_M2), _square_residues(_M3)
#: A square is a square modulo every m; faces keep their G's odd part modulo this.
_RESIDUE_MODULUS = 64 * _M1 * _M2 * _M3


def maybe_square(r: int) -> bool:
    """False if ``r`` (an integer, or its residue modulo :data:`_RESIDUE_MODULUS`, or a
    product of such residues) is certainly no perfect square; True if it may be one.
    Meant for odd numbers (a multiple of 64 passes the first test)."""
    return bool(_SQ64[r & 63] and _SQ1[r % _M1] and _SQ2[r % _M2] and _SQ3[r % _M3])


def _odd_residue(n: int) -> tuple[int, int]:
    """``(r, p)``: the odd part of ``n > 0`` modulo :data:`_RESIDUE_MODULUS` and the
    parity of the power of 2 in ``n``.  ``n`` can be a square only if ``p == 0`` and
    ``maybe_square(r)``; about 1 odd non-square in 3,000 passes."""
    v = (n & -n).bit_length() - 1
    return (n >> v) % _RESIDUE_MODULUS, v & 1


def _is_square(n: int) -> bool:
    """Whether the integer ``n > 0`` is a perfect square (residues first)."""
    r, p = _odd_residue(n)
    return not p and maybe_square(r) and isqrt(n) ** 2 == n


# --- step 1: integers per face, from lengths ------------------------------------------------

# One denominator for the whole mesh if it stays small (exact.rationals.shared_denominator;
# float meshes: all coordinates of magnitude above 2**-70 or zero); else one per face, so
# that a single tiny coordinate does not blow up every face's integers.

class FaceData:
    """The integers of step 1 for every face of a surface (see the module docstring).

    ``G[f]``: ``16 area^2`` (``4 area^2`` on the R^3 route of :func:`_positions_data_3d`)
    times a square ``S[f]^2`` (``S`` the scale that made the squared lengths integers); ``N[h]``: the numerator of the cotangent of the corner
    opposite halfedge ``h``, ``cot = N[h] / sqrt(G[face_of(h)])``; ``residue[f]``,
    ``twos[f]``: the odd part of ``G[f]`` modulo :data:`_RESIDUE_MODULUS` and the
    parity of its power of 2 (:func:`_odd_residue`).  Square roots (step 3) are
    computed per face when first needed and kept.
    """

    __slots__ = ("G", "S", "N", "residue", "twos", "parts", "_roots", "_by_G")

    def __init__(self, G: list, S: list, N: list):
        self.G, self.S, self.N = G, S, N
        # _odd_residue of every G, written out (one call per face was a tenth of the
        # Gauss-Bonnet decision's time)
        vs = [(g & -g).bit_length() - 1 for g in G]
        self.residue = [(g >> v) % _RESIDUE_MODULUS for g, v in zip(G, vs)]
        self.twos = [v & 1 for v in vs]
        self.parts = {1: (1, 1)}          # radicand m -> (s, M), see _split_root
        self._roots = [None] * len(G)
        self._by_G = {}                   # equal G on many faces (regular meshes)

    def certainly_irrational(self, f: int, g: int) -> bool:
        """``G_f G_g`` is certainly no square (from residues), so a cotan weight (3.3)
        ``1/2 (n_1 / sqrt(G_f) + n_2 / sqrt(G_g))`` with both numerators nonzero is
        irrational; exact (a residue that is no square mod m proves it).  False means
        "maybe a square": the caller then decides with ``isqrt``.  (:func:`maybe_square`
        written out: this runs for every edge of a mesh.)"""
        if self.twos[f] != self.twos[g]:
            return True
        r = self.residue[f] * self.residue[g]
        return not (_SQ64[r & 63] and _SQ1[r % _M1] and _SQ2[r % _M2] and _SQ3[r % _M3])

    def is_square(self, f: int) -> bool:
        """Whether ``G[f]`` is a perfect square (the face's cotangents are rational)."""
        return (not self.twos[f] and maybe_square(self.residue[f])
                and isqrt(self.G[f]) ** 2 == self.G[f])

    def root(self, f: int) -> tuple:
        """``(m, den, k)``: half the cotangent ``n / sqrt(G[f])`` of a corner of face f
        is ``(n k / den) sqrt(m)``, m the radicand :func:`ddg_oracle.reference.exact.sqrt` gives."""
        r = self._roots[f]
        if r is None:
            G, S = self.G[f], self.S[f]
            key = (G, S) if S & (S - 1) else G      # S matters only if not a power of 2
            r = self._by_G.get(key)
            if r is None:
                r = self._by_G[key] = self._root(G, S)
            self._roots[f] = r
        return r

    def _root(self, G: int, S: int):
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

    def terms(self, raw) -> dict:
        """``{m: q}`` with ``sum q sqrt(m) = 1/2 sum n / sqrt(G[f])`` over the pairs
        ``raw = (f1, n1, f2, n2, ...)``: equal radicands added, zeros dropped."""
        acc: dict[int, list] = {}
        roots, root = self._roots, self.root
        for i in range(0, len(raw), 2):
            f = raw[i]
            m, d, k = roots[f] or root(f)
            n = raw[i + 1] * k
            a = acc.get(m)
            if a is None:
                acc[m] = [n, d]
            elif a[1] == d:
                a[0] += n
            else:
                a[0], a[1] = a[0] * d + n * a[1], a[1] * d
        return {m: Fraction(n, d) for m, (n, d) in acc.items() if n}

    def value(self, raw):
        """``1/2 sum n / sqrt(G[f])`` over ``raw`` as a canonical Surd, or a Fraction."""
        if len(raw) == 4 and raw[1] and raw[3]:
            # an edge weight, the common case: what terms() and _value() give, without
            # their dict of lists (this runs for every edge of a mesh)
            f1, n1, f2, n2 = raw
            m1, d1, k1 = self._roots[f1] or self.root(f1)
            m2, d2, k2 = self._roots[f2] or self.root(f2)
            if m1 == m2:
                # one radicand (faces of one shape: a quarter of a regular mesh's edges)
                n = n1 * k1 + n2 * k2 if d1 == d2 else n1 * k1 * d2 + n2 * k2 * d1
                if not n:
                    return _ZERO
                q = Fraction(n, d1 if d1 == d2 else d1 * d2)
                return q if m1 == 1 else from_terms((m1,), {m1: q}, prune=False)
            base = _pair_base(m1, m2, self.parts)
            if base is None:
                return _refined(self.terms(raw), self.parts)
            return from_terms(base, {m1: Fraction(n1 * k1, d1), m2: Fraction(n2 * k2, d2)},
                         prune=False)
        return _value(self.terms(raw), self.parts)

    def lazy(self, raw) -> "CotanSum":
        """The same value as a :class:`CotanSum`; only for values known to be irrational
        (and raw numerators that are not 0)."""
        return self.lazy_slice(raw, 0, len(raw))

    def lazy_slice(self, seq, lo: int, hi: int) -> "CotanSum":
        """:meth:`lazy` of ``seq[lo:hi]``, without that slice: a sequence shared by many
        values (every edge weight of a Laplacian) costs the garbage collector one object,
        not one per value.  ``seq[lo:hi]`` must not change afterwards (appending to the
        list is fine)."""
        x = _new(CotanSum)
        x._src, x._seq, x._lo, x._hi, x._hash = self, seq, lo, hi, None
        return x


_new = object.__new__


def _integer_squared_lengths(surface: PolyhedralSurface):
    """Positions -> lengths: ``(a, b, c), S`` with ``a[f], b[f], c[f]`` the squared lengths
    of the halfedges 0, 1, 2 of face f times ``S = D^2`` (integers; D the common
    denominator of every coordinate), or None when D is too large to share
    (:data:`~ddg_oracle.reference.exact.rationals.SHARED_DENOMINATOR_BITS`)."""
    shared = shared_denominator(surface.positions)
    if shared is None:
        return None
    pts, D = shared
    out = ([], [], [])
    for face in surface.triangulation.faces:
        for lengths, (i, j) in zip(out, ((0, 1), (1, 2), (2, 0))):
            lengths.append(sum((x - y) * (x - y) for x, y in zip(pts[face[i]], pts[face[j]])))
    return out, D * D


def _positions_data_3d(surface: PolyhedralSurface, pts: list, D: int) -> FaceData:
    """Step 1 of a surface in R^3 with one common denominator D, written out in one loop
    (the common case, 2x faster): per face the three integer squared lengths, then
    :func:`_face_integers`'s G and N from them, both divided by their common factor (s is
    even for integer points, so ``G / 4 = a c - (s/2)^2`` and ``N / 2`` are integers: the
    cotangents ``N / sqrt(G)`` are unchanged); ``pts`` the positions times D, integers."""
    G, N = [], []
    gram, add = G.append, N.extend
    for f, (i, j, k) in enumerate(surface.triangulation.faces):
        px, py, pz = pts[i]
        qx, qy, qz = pts[j]
        rx, ry, rz = pts[k]
        ux, uy, uz = qx - px, qy - py, qz - pz
        vx, vy, vz = rx - qx, ry - qy, rz - qz
        wx, wy, wz = px - rx, py - ry, pz - rz
        a = ux * ux + uy * uy + uz * uz                 # |01|^2, |12|^2, |20|^2
        b = vx * vx + vy * vy + vz * vz
        c = wx * wx + wy * wy + wz * wz
        h = (a + c - b) >> 1        # <u, -w>, an integer here: s / 2 exactly
        g = a * c - h * h           # G / 4 and N / 2: the same cotangents
        if not g:
            _degenerate(surface, f)
        gram(g)
        add((c - h, h, a - h))
    return FaceData(G, [D * D] * len(G), N)


def _face_integers(a_b_c, S, left_out=(), degenerate=None) -> FaceData:
    """Lengths -> step 1.  ``a_b_c``: three sequences, the integer squared lengths of the
    halfedges 0, 1, 2 of each face (scaled by ``S[f]``; see :class:`FaceData`).  Per face
    ``G = 16 area^2 = 4 a c - s^2`` with ``s = a + c - b`` (twice the inner product of the
    two sides at corner 0: two products, Heron needs six) and the cotangent numerators
    ``N_2 = 2 c - s, N_0 = s, N_1 = 2 a - s``.  Faces in ``left_out`` get numerators 0;
    ``degenerate(f)`` raises for a face of zero area."""
    G, N = [], []
    gram, add = G.append, N.extend
    for f, (a, b, c) in enumerate(zip(*a_b_c)):
        if left_out and f in left_out:
            gram(1)
            add((0, 0, 0))
            continue
        s = a + c - b
        g = 4 * a * c - s * s
        if not g:
            degenerate(f)
        gram(g)
        add((2 * c - s, s, 2 * a - s))         # N_2, N_0, N_1: halfedges 3f, 3f+1, 3f+2
    return FaceData(G, S, N)


def _positions_data(surface: PolyhedralSurface) -> FaceData:
    """Step 1 of a surface with positions, through its squared lengths (the cotangents are
    intrinsic): one common denominator where it stays small, else one per face."""
    t = surface.triangulation
    P = surface.positions
    degenerate = lambda f: _degenerate(surface, f)              # noqa: E731
    if surface.dimension == 3:
        # a PolyhedralSurface's coordinates are Fractions (polyhedral._point)
        shared = shared_denominator_of_fractions(P, True)
        if shared is not None:
            return _positions_data_3d(surface, *shared)
    shared = _integer_squared_lengths(surface)
    if shared is not None:
        abc, S = shared
        return _face_integers(abc, [S] * t.n_faces, degenerate=degenerate)
    per_face, S = [], []
    for face in t.faces:
        (A, B, C), D = points_on_common_denominator(*(P[v] for v in face))
        per_face.append(tuple(sum((x - y) * (x - y) for x, y in zip(p, q))
                              for p, q in ((A, B), (B, C), (C, A))))
        S.append(D * D)
    return _face_integers(list(zip(*per_face)), S, degenerate=degenerate)


def _degenerate(surface: PolyhedralSurface, f: int):
    """Raise the error the definition raises for a surface with the zero-area face f
    (its metric checks coincident vertices everywhere first)."""
    surface.metric()
    raise degenerate_face(surface.triangulation, f, surface.positions)   # pragma: no cover


def lengths_data(m: PiecewiseFlatSurface, left_out=()) -> FaceData:
    """Step 1 from rational squared lengths (one denominator per face); the faces in
    ``left_out`` (irrational squared lengths: :func:`cotan_laplacian_mixed`) get
    numerators 0, so they contribute nothing."""
    sq, eo = m.squared_lengths, m.triangulation.edge_of
    per_face, S = [], []
    for f in range(m.triangulation.n_faces):
        if f in left_out:
            per_face.append((1, 1, 1))
            S.append(1)
            continue
        # inline halfedge(f, c): hot
        l0, l1, l2 = sq[eo(3 * f)], sq[eo(3 * f + 1)], sq[eo(3 * f + 2)]
        D = lcm(l0.denominator, l1.denominator, l2.denominator)
        per_face.append(tuple(x.numerator * (D // x.denominator) for x in (l0, l1, l2)))
        S.append(D)
    return _face_integers(list(zip(*per_face)), S, left_out)


def face_data(surface) -> FaceData:
    """The integers of step 1 for a surface that :func:`applies`; raises
    :class:`~ddg_oracle.reference.errors.DegenerateFace` at a face of zero area."""
    if isinstance(surface, PolyhedralSurface):
        return _positions_data(surface)
    return lengths_data(surface)


# --- step 2: the value kept as it comes -----------------------------------------------------


class CotanSum(Surd):
    """An irrational :class:`~ddg_oracle.reference.exact.Surd` known as ``1/2 sum n_k / sqrt(G_k)``.

    The terms are integers of a :class:`FaceData` (``_raw = (f1, n1, f2, n2, ...)``,
    ``G_k = G[f_k]``, nonzero ``n_k``); the value is known to be irrational when
    it is made.  It *is* a Surd: everything a Surd does works, equal Surds
    compare and hash equal.  The canonical form (``_base``, ``_terms``) is
    computed on first use (``__getattr__``: those slots stay unset until then);
    the sign, ``float()``, ``hash()``, enclosures, negation and comparisons with
    0 are decided from the integers without it.
    """

    __slots__ = ("_src", "_seq", "_lo", "_hi")

    @property
    def _raw(self):
        """``(f1, n1, f2, n2, ...)``: ``_seq[_lo:_hi]`` (the whole of ``_seq`` but on the
        Laplacian's shared sequences, see :meth:`FaceData.lazy_slice`)."""
        return self._seq[self._lo:self._hi]

    def __getattr__(self, name):
        if name != "_base" and name != "_terms":
            raise AttributeError(f"'CotanSum' object has no attribute {name!r}")
        v = self._src.value(self._seq[self._lo:self._hi])          # self._raw
        if type(v) is not Surd or not v._base:       # pragma: no cover - a bug
            raise AssertionError(f"a CotanSum made for the rational value {v}")
        self._base, self._terms = v._base, v._terms
        return v._base if name == "_base" else v._terms

    def is_rational(self):
        return False

    def __bool__(self):
        return True

    def sign(self):
        raw = self._raw
        positive = raw[1] > 0
        if all((n > 0) == positive for n in raw[3::2]):
            return 1 if positive else -1
        if len(raw) == 4:
            # n1 / sqrt(G1) + n2 / sqrt(G2) with opposite signs: the larger modulus wins
            G = self._src.G
            f1, n1, f2, n2 = raw
            big = n1 if n1 * n1 * G[f2] > n2 * n2 * G[f1] else n2
            return 1 if big > 0 else -1
        return Surd.sign(self)

    def __neg__(self):
        raw = self._raw
        return self._src.lazy(tuple(-x if i & 1 else x for i, x in enumerate(raw)))

    def _bound_count(self):
        return (self._hi - self._lo) // 2

    def _bounds(self, k):
        if k > 8192:
            # float() refines until the enclosure is narrow, which ends for irrational
            # values only: make sure (the canonical form raises if it is rational)
            self._terms
        # |n| 2^k / (2 sqrt(G)) = sqrt(n^2 4^k / 4G) lies in [s, s + 1], s = isqrt(floor)
        G, raw = self._src.G, self._raw
        lo = hi = 0
        for i in range(0, len(raw), 2):
            n = raw[i + 1]
            s = isqrt((n * n << 2 * k) // (G[raw[i]] << 2))
            if n > 0:
                lo += s
                hi += s + 1
            else:
                lo -= s + 1
                hi -= s
        return lo, hi


# --- step 3: canonical Surds --------------------------------------------------------------


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


def _pair_base(m1: int, m2: int, parts):
    """The coarsest coprime base of two distinct radicands (what :func:`_value`'s grouping
    gives for two), or None when their large parts share a prime (:func:`_refined`)."""
    g = gcd(m1, m2)
    if g == 1:
        # coprime radicands are their own base (1, the rational part, is none)
        return (m2,) if m1 == 1 else (m1,) if m2 == 1 else (m1, m2) if m1 < m2 else (m2, m1)
    M1, M2 = parts[m1][1], parts[m2][1]
    if M1 != M2 and gcd(M1, M2) != 1:
        return None
    # equal or coprime large parts, squarefree small ones: g, m1 / g and m2 / g are
    # pairwise coprime (what both share, what each has alone)
    return tuple(sorted(x for x in (g, m1 // g, m2 // g) if x != 1))


def _value(terms: dict, parts):
    """``sum q * sqrt(m)`` over ``terms = {m: q}`` (q nonzero Fractions) as a canonical
    Surd, or a Fraction when rational."""
    if len(terms) < 2:
        if not terms:
            return _ZERO
        (m, q), = terms.items()
        return q if m == 1 else from_terms((m,), terms, prune=False)
    if len(terms) == 2:                 # an edge: two faces, the common case
        base = _pair_base(*terms, parts)
        return _refined(terms, parts) if base is None else from_terms(base, terms, prune=False)
    if not _coprime_large_parts(terms, parts):
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
    return from_terms(tuple(sorted(group.values())), terms, prune=False)


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
    base = refine(list(factors))
    return simplest(from_terms(base, reexpress(terms, base)))


# --- the public function -----------------------------------------------------------------


def face_cotangents(surface) -> list[tuple]:
    """The exact cotangents of the three corners of every face, fast, canonical.

    ``[(cot0, cot1, cot2), ...]`` equal to
    ``PiecewiseFlatSurface.corner_cot(f, c)`` (Fractions where rational).

    >>> from ddg_oracle.reference import surfaces
    >>> face_cotangents(surfaces.grid(1, 1))[0]
    (Fraction(1, 1), Fraction(0, 1), Fraction(1, 1))
    """
    fd = face_data(surface)
    N = fd.N
    # inline halfedge(f, c): hot
    return [tuple(fd.value((f, 2 * N[3 * f + next_corner(c)])) for c in range(3))
            for f in range(len(fd.G))]
