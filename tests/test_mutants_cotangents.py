"""Mutants of reference/cotangents.py killed on generic surfaces (docs/mutation.md).

Every assertion compares the integer route with something computed another way: the
definition's corner cotangents (``PiecewiseFlatSurface.corner_cot``, Surd arithmetic on
the squared lengths), ``math.isqrt``, a residue table written out here, or float geometry
from the positions.  Values of the lazy :class:`CotanSum` are checked *before* anything
computes their canonical form (sign, float, hash, enclosures, negation are decided from
the integers), and then for equality.
"""

from __future__ import annotations

import math
import random
from fractions import Fraction
from math import isqrt

import pytest

from ddg_oracle.reference import cotangents as C
from ddg_oracle.reference import surfaces
from ddg_oracle.reference.cotan_fast import cotan_laplacian_fast, cotan_weights_fast
from ddg_oracle.reference.errors import DegenerateFace
from ddg_oracle.reference.exact import Surd, sign
from ddg_oracle.reference.laplacian import cotan_laplacian_from_weights, cotan_weights_from_corners
from ddg_oracle.reference.metric import PiecewiseFlatSurface
from ddg_oracle.reference.polyhedral import PolyhedralSurface

from tests.test_mutants_surfaces import (all_cases, float_corner_angles, float_lengths_angles,
                                         hilly_grid, jittered)

CASES = all_cases()
IDS = [name for name, _ in CASES]


def _metric(s):
    return s.metric() if isinstance(s, PolyhedralSurface) else s


# --- the residue tests that exclude squares ----------------------------------------------------


@pytest.mark.parametrize("m", [1, 2, 8, 64, 3 * 5 * 7, 17 * 19, 29 * 31 * 37])
def test_square_residue_table_lists_the_squares(m):
    squares = {y * y % m for y in range(m)}
    assert C._square_residues(m) == bytes(int(r in squares) for r in range(m))


def _two_adic(n):
    v = 0
    while n % 2 == 0:
        n //= 2
        v += 1
    return n, v


def test_odd_residue_is_the_odd_part_and_the_parity_of_the_power_of_two():
    rng = random.Random(1)
    for n in list(range(1, 300)) + [rng.getrandbits(rng.randint(10, 300)) | 1 << 3 for _ in range(200)]:
        odd, v = _two_adic(n)
        assert C._odd_residue(n) == (odd % C._RESIDUE_MODULUS, v % 2)


def test_is_square_is_isqrt():
    rng = random.Random(2)
    numbers = list(range(1, 20000))
    for _ in range(300):
        k = rng.getrandbits(rng.randint(20, 200))
        numbers += [k * k, k * k + 1, 4 * k * k, 2 * k * k, (2 * k + 1) ** 2 * 9, k * k * 4 + 4]
    for n in numbers:
        if n > 0:
            assert C._is_square(n) == (isqrt(n) ** 2 == n), n


def test_maybe_square_never_rejects_a_square():
    rng = random.Random(3)
    for _ in range(2000):
        k = rng.getrandbits(rng.randint(1, 150)) | 1
        assert C.maybe_square((k * k) % C._RESIDUE_MODULUS)
        assert C.maybe_square(k * k)


def test_split_root_factors_G():
    # G = c^2 s M: s the squarefree product of the primes below 100 dividing G an odd
    # number of times, M free of them; M = 1 exactly when G / s is a square
    rng = random.Random(4)
    primes = [p for p in range(2, 100) if all(p % q for q in range(2, p))]
    for _ in range(400):
        G = 1
        for p in rng.sample(primes, rng.randint(0, 6)):
            G *= p ** rng.randint(1, 5)
        G *= rng.choice([1, 1, 101, 103 * 107, 101 ** 2, 10007 * 101])
        c, s, M = C._split_root(G)
        assert c * c * s * M == G
        assert all(s % (p * p) for p in primes) and all(M % p for p in primes)
        rest = s
        for p in primes:
            if rest % p == 0:
                rest //= p
        assert rest == 1                                  # s: distinct primes below 100
        assert (M == 1) == (isqrt(G // s) ** 2 == G // s)
        if M != 1:
            assert isqrt(M) ** 2 != M


# --- face data: the integers of step 1 --------------------------------------------------------


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_face_integers_give_the_definition_cotangents(case):
    name, s = case
    m = _metric(s)
    fd = C.face_data(s)
    assert len(fd.G) == m.triangulation.n_faces
    for f in range(m.triangulation.n_faces):
        cots = m.face_cots(f)
        for c in range(3):
            h = 3 * f + (c + 1) % 3                         # the halfedge opposite corner c
            # cot = N / sqrt(G): N^2 / G = cot^2 and the signs agree
            assert Fraction(fd.N[h] ** 2, fd.G[f]) == cots[c] * cots[c]
            assert (fd.N[h] > 0) - (fd.N[h] < 0) == cots[c].sign()
        assert fd.is_square(f) == (isqrt(fd.G[f]) ** 2 == fd.G[f])
        odd, v = _two_adic(fd.G[f])
        assert (fd.residue[f], fd.twos[f]) == (odd % C._RESIDUE_MODULUS, v % 2)


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_face_cotangents_equal_the_definition_and_the_floats(case):
    name, s = case
    m = _metric(s)
    cots = C.face_cotangents(s)
    floats = float_corner_angles(s) if isinstance(s, PolyhedralSurface) else float_lengths_angles(m)
    for f, (triple, angles) in enumerate(zip(cots, floats)):
        assert triple == m.face_cots(f)
        for x, a in zip(triple, angles):
            assert math.isclose(float(x), 1 / math.tan(a), rel_tol=1e-9, abs_tol=1e-9)
            assert isinstance(x, Fraction) == x.is_rational() if isinstance(x, Surd) else True


def test_face_cotangents_of_rational_and_right_triangles_are_fractions():
    # a 3-4-5 triangle (G a square) has rational cotangents 4/3, 3/4, 0
    s = PolyhedralSurface.from_arrays([[0, 0, 0], [4, 0, 0], [0, 3, 0]], [[0, 1, 2]])
    assert C.face_cotangents(s) == [(0, Fraction(4, 3), Fraction(3, 4))]
    assert all(type(x) is Fraction for x in C.face_cotangents(s)[0])


def test_zero_area_face_raises_degenerate_face():
    for pts in ([[0, 0, 0], [1, 1, 1], [2, 2, 2]], [[0, 0], [1, 1], [3, 3]]):
        s = PolyhedralSurface.from_arrays(pts, [[0, 1, 2]])
        with pytest.raises(DegenerateFace):
            C.face_data(s)


def test_applies_only_to_rational_lengths_and_positions():
    assert C.applies(surfaces.cube())
    m = surfaces.cube().metric()
    assert C.applies(m)
    flipped = jittered(surfaces.icosahedron(), 1).metric()
    from ddg_oracle.reference.intrinsic import flip
    e = next(e for e in range(flipped.triangulation.n_edges)
             if not isinstance(flip(flipped, e).squared_lengths[e], Fraction))
    assert not C.applies(flip(flipped, e))
    assert not C.applies(surfaces.cube().triangulation)


# --- edge weights: CotanSum decided from integers --------------------------------------------


def _lazy_checks(w, d):
    """Compare a fresh value ``w`` of the fast route with the definition's ``d`` on
    everything decided from the integers, then for equality."""
    if not isinstance(d, Surd) or d.is_rational():
        assert type(w) is Fraction and w == d          # rational values are Fractions
        return
    assert bool(w) == bool(d)
    assert w.sign() == d.sign()
    assert (w > 0) == (d > 0) and (w < 0) == (d < 0)
    assert float(w) == float(d)
    assert hash(w) == hash(d)
    lo, hi = w.interval(40)
    assert lo <= d <= hi and hi - lo <= Fraction(1, 2 ** 40)
    n = -w
    assert n.sign() == -d.sign() and float(n) == -float(d)
    assert w.is_rational() == d.is_rational()
    assert w == d and n == -d            # (radicands are square-free only of primes < 100:
    #                                      equal values may be spelled differently)


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_lazy_edge_weights_equal_the_definition(case):
    name, s = case
    d = cotan_weights_from_corners(s)
    w = cotan_weights_fast(s)
    assert w.keys() == d.keys()
    signs = set()
    for e in w:
        _lazy_checks(w[e], d[e])
        signs.add(sign(d[e]))
    if name == "hilly grid":
        assert signs == {-1, 1}            # negative weights: the opposite-signs branch


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_fast_laplacian_entries_equal_the_definition(case):
    name, s = case
    fast, slow = cotan_laplacian_fast(s), cotan_laplacian_from_weights(s)
    n = _metric(s).triangulation.n_vertices
    for i in range(n):
        for j in range(n):
            a, b = fast[i, j], slow[i, j]
            if isinstance(a, Surd) and not a.is_rational():
                _lazy_checks(a, b)
            assert a == b


def test_weights_sign_with_opposite_signs_on_many_random_pairs():
    # two triangles on the edge (0,0)-(1,0): apexes above (one obtuse corner) and below
    rng = random.Random(5)
    seen = set()
    for _ in range(150):
        k = (Fraction(rng.randint(-40, 140), 100), Fraction(rng.randint(5, 90), 100 + rng.randint(0, 7)))
        l_ = (Fraction(rng.randint(-40, 140), 100), -Fraction(rng.randint(5, 90), 100 + rng.randint(0, 7)))
        s = PolyhedralSurface.from_arrays([[0, 0], [1, 0], list(k), list(l_)], [[0, 1, 2], [1, 0, 3]])
        w, d = cotan_weights_fast(s), cotan_weights_from_corners(s)
        _lazy_checks(w[0], d[0])
        seen.add(sign(d[0]))
    assert seen == {-1, 1}


def test_bounds_of_a_lazy_value_enclose_it_at_every_scale():
    s = hilly_grid(2, 2, 21)
    d = cotan_weights_from_corners(s)
    for e, w in cotan_weights_fast(s).items():
        if isinstance(w, C.CotanSum):
            for k in (0, 1, 7, 64, 200):
                lo, hi = w._bounds(k)
                assert Fraction(lo, 1 << k) <= d[e] <= Fraction(hi, 1 << k)
                assert hi - lo <= 2 * w._bound_count() + 1
            assert w._bound_count() == len(w._raw) // 2


def test_diagonal_entries_with_many_terms_and_mixed_signs():
    # a vertex star of 6 faces with obtuse corners: the diagonal is a CotanSum of 6 terms
    # whose numerators have both signs (Surd.sign decides it); and its negation
    s = jittered(surfaces.disk(6), 30, Fraction(1, 3))
    s = s.with_positions([(x, y, z + Fraction(i % 3, 5)) for i, (x, y, z) in enumerate(s.positions)])
    fast, slow = cotan_laplacian_fast(s), cotan_laplacian_from_weights(s)
    a, b = fast[0, 0], slow[0, 0]
    assert isinstance(a, C.CotanSum) and a._bound_count() == 6
    _lazy_checks(a, b)


def test_lazy_sums_of_many_terms_of_both_signs():
    # CotanSum's own value 1/2 sum n / sqrt(G) against the same sum in Surd arithmetic
    from ddg_oracle.reference.exact import sqrt
    s = hilly_grid(3, 3, 40)
    fd = C.face_data(s)
    rng = random.Random(7)
    for _ in range(60):
        faces = rng.sample(range(len(fd.G)), rng.randint(1, 5))
        raw = []
        for f in faces:
            raw += [f, rng.choice([-1, 1]) * rng.randint(1, 50)]
        raw = tuple(raw)
        d = sum((Fraction(n, 2) / sqrt(fd.G[f]) for f, n in zip(raw[::2], raw[1::2])), Fraction(0))
        if not isinstance(d, Surd) or d.is_rational():
            continue
        _lazy_checks(fd.lazy(raw), d)
        assert fd.value(raw) == d
    # two terms of opposite signs with numerators +-1, +-2: the larger modulus decides
    # (n^2 G of one against the other's), whichever numerator is 1
    for f in range(0, len(fd.G), 3):
        for g in range(1, len(fd.G), 4):
            for n1, n2 in ((1, -1), (-1, 1), (1, -2), (-2, 1), (2, -1), (-1, 2)):
                raw = (f, n1, g, n2)
                d = Fraction(n1, 2) / sqrt(fd.G[f]) + Fraction(n2, 2) / sqrt(fd.G[g])
                if isinstance(d, Surd) and not d.is_rational():
                    assert fd.lazy(raw).sign() == d.sign()
                    assert (-fd.lazy(raw)).sign() == -d.sign()


def test_per_face_and_non_dyadic_scales_give_the_definition():
    # _root with S not a power of two (lengths over denominators 3, 5, 7), equal G on
    # several faces of different scale, and the rational part of a radicand 1
    from ddg_oracle.reference.combinatorics import Triangulation
    t = Triangulation.from_faces([[0, 1, 2], [1, 0, 3], [2, 1, 4], [0, 2, 5]])
    for sq in ([Fraction(9, 25)] * 9, [Fraction(1, 3), Fraction(1, 3), Fraction(1, 3),
                                       Fraction(4, 3), Fraction(4, 3), Fraction(3, 7),
                                       Fraction(3, 7), Fraction(1, 5), Fraction(2, 5)]):
        m = PiecewiseFlatSurface(t, sq)
        d = cotan_weights_from_corners(m)
        for e, w in cotan_weights_fast(m).items():
            assert w == d[e] and float(w) == float(d[e])
        fd = C.face_data(m)
        for f in range(4):
            mm, den, k = fd.root(f)
            # half the cotangent n / sqrt(G) is (n k / den) sqrt(mm)
            cot = m.face_cots(f)[0]
            n = fd.N[3 * f + 1]
            assert Fraction(n * k, den) ** 2 * mm == (cot / 2) ** 2


def test_refined_radicands_sharing_a_large_prime():
    # radicands with the same prime above 100 in different squarefree parts: _refined
    p, q = 101, 103
    from ddg_oracle.reference.combinatorics import Triangulation
    t = Triangulation.from_faces([[0, 1, 2], [1, 0, 3], [0, 3, 4]])
    rng = random.Random(6)
    for _ in range(30):
        sq = [Fraction(rng.choice([p, q, p * q, 2 * p, 3 * q, 5 * p]), rng.choice([100, 120, 150])) + 1
              for _ in range(t.n_edges)]
        try:
            m = PiecewiseFlatSurface(t, sq)
        except Exception:
            continue
        d = cotan_weights_from_corners(m)
        for e, w in cotan_weights_fast(m).items():
            assert w == d[e]
        fast, slow = cotan_laplacian_fast(m), cotan_laplacian_from_weights(m)
        assert fast == slow
