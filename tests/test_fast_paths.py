"""The fast exact paths agree exactly with the definitions they replace (issue 7).

* reference.cotan_fast (integer cotan weights and Laplacian) against
  reference.laplacian.cotan_weights / cotan_laplacian_from_weights: ``==`` on
  every entry, on generated meshes, float meshes, intrinsic surfaces with loops,
  and the 1,280-face float icosphere of the benchmarks;
* IntrinsicTriangulation (in-place O(1) flips) against chains of the immutable
  reference.intrinsic.flip, and flip_to_delaunay against the same loop written
  with immutable flips: same surface, same triangulation, same vertex stars,
  same log.

No timings here (they live in benchmarks/).
"""

import random
from fractions import Fraction

import pytest
from hypothesis import given, settings, strategies as st

from benchmarks.peers import flip_to_delaunay_immutable
from properties.laplacian import any_meshes, closed_meshes
from reference import cotan_fast, surfaces
from reference.combinatorics import Triangulation
from reference.cotan_fast import (applies, cotan_laplacian_fast, cotan_weights_fast,
                                  face_cotangents)
from reference.delaunay import DelaunayError, flip_to_delaunay, is_delaunay
from reference.errors import DegenerateFace, NotFlippable
from reference.exact import sqrt
from reference.intrinsic import IntrinsicTriangulation, flip, is_flippable
from reference.laplacian import cotan_laplacian, cotan_laplacian_from_weights, cotan_weights
from reference.metric import PiecewiseFlatSurface
from reference.polyhedral import PolyhedralSurface
from tests.test_delaunay import flat_torus, random_flips
from tests.test_laplacian import float_icosphere

# --- exact cotan weights and Laplacian --------------------------------------------------------


def assert_same_cotan(s):
    """Fast path == definition, entry by entry (and the dispatch picks the fast path)."""
    assert applies(s)
    assert cotan_weights_fast(s) == cotan_weights(s)
    L = cotan_laplacian_fast(s)
    assert L == cotan_laplacian_from_weights(s)
    assert cotan_laplacian(s) == L
    m = s.metric() if isinstance(s, PolyhedralSurface) else s
    assert face_cotangents(s) == [tuple(m.corner_cot(f, c) for c in range(3))
                                  for f in range(m.triangulation.n_faces)]
    return L


@given(any_meshes())
def test_fast_cotan_equals_definition_on_generated_meshes(case):
    assert_same_cotan(case.surface())


@pytest.mark.parametrize("build", [surfaces.torus, surfaces.cube, surfaces.icosahedron,
                                   lambda: surfaces.genus_surface(2), surfaces.disk,
                                   surfaces.annulus, surfaces.mobius_strip,
                                   lambda: surfaces.torus(5, 7)])
def test_fast_cotan_on_named_surfaces(build):
    # rational points with odd denominators (circle points): the fast path must take the
    # known square out of G, or radicands carry squares of primes above 100
    assert_same_cotan(build())


def _jittered(case, draw, exponents):
    """The mesh's points moved by floats of drawn magnitudes (dyadic rationals with
    denominators from 2**-exponent): per-face denominators when they differ wildly."""
    pts = []
    for p in case.positions:
        pts.append(tuple(float(x) + draw(st.sampled_from([0.0, 1.0, -1.0]))
                         * draw(st.floats(0.5, 1.0)) * 2.0 ** -draw(st.sampled_from(exponents))
                         for x in p))
    return PolyhedralSurface.from_arrays(pts, case.faces)


@settings(max_examples=30)
@given(closed_meshes(), st.data())
def test_fast_cotan_equals_definition_on_float_meshes(case, data):
    # tiny and ordinary perturbations: one common denominator, or one per face
    s = _jittered(case, data.draw, [8, 20, 60, 200])
    assert_same_cotan(s)


@given(any_meshes(), st.sampled_from([2, 4]))
def test_fast_cotan_in_other_dimensions(case, dim):
    pts = [tuple(p[:2]) if dim == 2 else tuple(p) + (p[0] * p[1],) for p in case.positions]
    try:
        s = PolyhedralSurface.from_arrays(pts, case.faces)
        expected = cotan_laplacian_from_weights(s)
    except DegenerateFace as err:           # a fold projected flat: same error, same face
        with pytest.raises(DegenerateFace) as fast:
            cotan_laplacian_fast(PolyhedralSurface.from_arrays(pts, case.faces))
        assert str(fast.value) == str(err)
        return
    assert cotan_laplacian_fast(s) == expected
    assert cotan_weights_fast(s) == cotan_weights(s)


def test_fast_cotan_on_the_benchmark_icosphere(monkeypatch):
    """1,280 faces with float coordinates: equal matrices, and the mesh exercises the
    fallback for radicands sharing a prime above 100 (else that path is untested)."""
    calls = []
    real = cotan_fast._refined
    monkeypatch.setattr(cotan_fast, "_refined", lambda *a: calls.append(1) or real(*a))
    s = float_icosphere()
    L = assert_same_cotan(s)
    assert calls
    assert L.is_symmetric() and all(x == 0 for x in L.matvec([1] * s.n_vertices))


def test_degenerate_face_raises_the_same_error():
    s = PolyhedralSurface.from_arrays([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0]],
                                      [[0, 1, 2], [0, 2, 3]])
    with pytest.raises(DegenerateFace) as slow:
        cotan_laplacian_from_weights(s)
    with pytest.raises(DegenerateFace) as fast:
        cotan_laplacian_fast(s)
    assert str(fast.value) == str(slow.value) and "face 0" in str(fast.value)


def test_canonical_values_with_large_shared_primes_and_hidden_squares():
    """Radicands sharing the prime 101, a large part that is a square (101^2 * 2), a
    rational face: each face's sqrt(G) = c sqrt(m), and the canonical Surds built from
    the factors equal sums of reference.exact.sqrt."""
    G = [101 * 103, 101 * 107 * 4, 101 ** 2 * 2 * 9, 103, 49, 6 * 101 * 113, 6 * 5]
    fc = cotan_fast._Faces([(1, 1, 1, g, 1) for g in G])
    for g, m, d in zip(G, fc.rad, fc.den):
        c = d // (2 * m)
        assert c * c * m == g and sqrt(g) == c * sqrt(m)
    rng = random.Random(5)
    for _ in range(60):
        terms, expected = {}, 0
        for f in rng.sample(range(len(G)), rng.randint(1, 5)):
            q = Fraction(rng.choice([-1, 1]) * rng.randint(1, 9), rng.randint(1, 9))
            m = fc.rad[f]
            terms[m] = terms.get(m, 0) + q
            expected = expected + q * sqrt(m)
        terms = {m: q for m, q in terms.items() if q}
        assert cotan_fast._value(terms, fc.parts) == expected
        if len(terms) > 1:
            assert cotan_fast._refined(terms, fc.parts) == expected


def test_intrinsic_surfaces_with_loops_and_multi_edges():
    """Rational piecewise flat surfaces after random intrinsic flips (non-regular
    triangulations: loops, several edges between two vertices) go the fast way too."""
    rng = random.Random(1)
    seen_loop = False
    for name in ("tetrahedron", "octahedron", "tetrahedron", "octahedron"):
        t = getattr(surfaces, name)().triangulation
        for _ in range(8):                      # combinatorial flips; all faces equilateral
            try:
                t = t.flip(rng.randrange(t.n_edges))
            except NotFlippable:
                pass
        seen_loop |= not t.is_regular()
        assert_same_cotan(PiecewiseFlatSurface(t, [1] * t.n_edges))
    assert seen_loop
    assert_same_cotan(random_flips(flat_torus(4, 5, (3, 1), (1, 2)), rng, 40))


def test_dispatch_falls_back_for_irrational_squared_lengths():
    m = random_flips(surfaces.icosahedron().metric(), random.Random(3), 10)
    assert not applies(m)                        # Surd squared lengths after flips
    assert cotan_laplacian(m) == cotan_laplacian_from_weights(m)


# --- in-place flips ------------------------------------------------------------------------------


def stars(m):
    t = m.triangulation
    return [t.corners_around(v) for v in range(t.n_vertices)]


def assert_same_surface(a, b):
    assert a.triangulation == b.triangulation
    assert a.squared_lengths == b.squared_lengths and a.areas == b.areas
    assert stars(a) == stars(b)                  # the same corner starts every vertex star


_BASES = {
    "flat torus": lambda: flat_torus(4, 4, (3, 1), (1, 2)),
    "icosahedron": lambda: surfaces.icosahedron().metric(),
    "Moebius strip": lambda: surfaces.mobius_strip(6).metric(),   # reversed gluings
    "Klein bottle": lambda: PiecewiseFlatSurface(surfaces.klein_bottle(3, 3),
                                                 [1] * surfaces.klein_bottle(3, 3).n_edges),
}


@given(st.sampled_from(sorted(_BASES)), st.lists(st.integers(0, 10 ** 6), max_size=25))
def test_in_place_flips_equal_immutable_flips(name, picks):
    m = _BASES[name]()
    w = IntrinsicTriangulation(m)
    for k in picks:
        e = k % m.triangulation.n_edges
        assert w.is_flippable(e) == is_flippable(m, e)
        if is_flippable(m, e):
            m = flip(m, e)
            w.flip(e)
        else:
            with pytest.raises(NotFlippable) as slow:
                flip(m, e)
            with pytest.raises(NotFlippable) as fast:
                w.flip(e)
            assert str(fast.value) == str(slow.value)
    assert_same_surface(w.surface(), m)
    e = next((e for e in range(m.triangulation.n_edges) if is_flippable(m, e)), None)
    if e is not None:                          # flip() takes it too, and leaves it alone
        assert_same_surface(flip(w, e), flip(m, e))
        assert_same_surface(w.surface(), m)


@settings(max_examples=10, deadline=None)
@given(st.sampled_from(["flat torus", "icosahedron", "Moebius strip"]), st.integers(0, 99))
def test_flip_to_delaunay_equals_the_immutable_loop(name, seed):
    m = random_flips(_BASES[name](), random.Random(seed), 30)
    d, log = flip_to_delaunay(m)
    d0, log0 = flip_to_delaunay_immutable(m)
    assert_same_surface(d, d0)
    assert [(r.edge, r.h_before, r.h_after) for r in log] == log0
    assert is_delaunay(d)


def test_flip_to_delaunay_leaves_its_input_alone_and_keeps_max_flips():
    m = random_flips(flat_torus(6, 6, (3, 1), (1, 2)), random.Random(2), 200)
    before = (m.triangulation, m.squared_lengths, m.areas)
    d, log = flip_to_delaunay(m)
    assert (m.triangulation, m.squared_lengths, m.areas) == before and len(log) > 2
    with pytest.raises(DelaunayError, match="max_flips = 2"):
        flip_to_delaunay(m, max_flips=2)


def test_triangulation_flip_is_one_builder_flip():
    t = Triangulation.from_faces([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
    w = IntrinsicTriangulation(PiecewiseFlatSurface(t, [1] * 6))
    for e in (0, 3, 0, 5):
        t = t.flip(e)
        w.triangulation.flip(e)
    assert w.triangulation.build() == t


def test_one_tiny_coordinate_takes_per_face_denominators():
    s = surfaces.icosahedron()
    pts = [[float(x) for x in p] for p in s.positions]
    pts[0][0] += 1e-300                  # a denominator of 2**1049 on one vertex only
    t = PolyhedralSurface.from_arrays(pts, s.faces)
    assert max(x.denominator for p in t.positions for x in p).bit_length() > 1000
    assert_same_cotan(t)
