"""The fast exact paths agree exactly with the definitions they replace (issue 7).

* ddg_oracle.reference.cotan_fast (integer cotan weights and Laplacian) against
  ddg_oracle.reference.laplacian.cotan_weights / cotan_laplacian_from_weights: ``==`` on
  every entry, on generated meshes, float meshes, intrinsic surfaces with loops,
  and the 1,280-face float icosphere of the benchmarks;
* IntrinsicTriangulation (in-place O(1) flips) against chains of the immutable
  ddg_oracle.reference.intrinsic.flip, and flip_to_delaunay against the same loop written
  with immutable flips: same surface, same triangulation, same vertex stars,
  same log.

No timings here (they live in benchmarks/).
"""

import pickle
import random
from math import gcd, prod
from fractions import Fraction
from unittest import mock

import pytest
from hypothesis import assume, given, settings, strategies as st

from benchmarks.peers import flip_to_delaunay_immutable
from ddg_oracle.properties.strategies import any_meshes, closed_meshes
from ddg_oracle.properties.strategies import triangulated_surfaces
from ddg_oracle.reference import cotangents, curvature_fast, surfaces
from ddg_oracle.reference.combinatorics import Triangulation
from ddg_oracle.reference.cotan_fast import cotan_laplacian_fast, cotan_weights_fast
from ddg_oracle.reference.cotangents import CotanSum, applies, face_cotangents
from ddg_oracle.reference.curvature import (angle_defects, angle_sums_from_corners, corner_angles,
                                            corner_angles_from_cotangents, gauss_bonnet_holds,
                                            gauss_bonnet_holds_by_faces, turning_angles)
from ddg_oracle.reference.delaunay import (DelaunayError, delaunay_edges, flip_to_delaunay,
                                           is_delaunay)
from ddg_oracle.reference.errors import (DegenerateFace, InputError, NotFlippable,
                                         TermLimitExceeded)
from ddg_oracle.reference.curvature_fast import CornerSum
from ddg_oracle.reference.exact import Angle, Surd, angles, pi, sqrt
from ddg_oracle.reference.intrinsic import IntrinsicTriangulation, flip, is_flippable
from ddg_oracle.reference.laplacian import (cotan_laplacian, cotan_laplacian_from_weights,
                                            cotan_weights_from_corners as cotan_weights)
from ddg_oracle.reference.metric import PiecewiseFlatSurface
from ddg_oracle.reference.polyhedral import PolyhedralSurface
from tests.test_delaunay import flat_torus, random_flips
from benchmarks.meshes import float_icosphere

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
    assert_same_cotan(case.surface)


@pytest.mark.parametrize("build", [surfaces.torus, surfaces.cube, surfaces.icosahedron,
                                   lambda: surfaces.genus_surface(2), surfaces.disk,
                                   surfaces.annulus, surfaces.mobius_strip,
                                   lambda: surfaces.torus(5, 7)])
def test_fast_cotan_on_named_surfaces(build):
    # rational points with odd denominators (circle points): the fast path must take the
    # known square out of G, or radicands carry squares of primes above 100
    assert_same_cotan(build())


def jittered(case, draw, exponents):
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
    s = jittered(case, data.draw, [8, 20, 60, 200])
    assert_same_cotan(s)


@settings(max_examples=25)
@given(closed_meshes(), st.data())
def test_mixed_route_equals_definition_after_intrinsic_flips(case, data):
    # float points: after flips to Delaunay some squared lengths are irrational; the faces
    # with rational ones go the integer route, the others the Surd formula
    from ddg_oracle.reference.cotan_fast import cotan_laplacian_mixed
    s = jittered(case, data.draw, [4, 8, 20])
    d, log = flip_to_delaunay(s.metric())
    expected = cotan_laplacian_from_weights(d)
    assert cotan_laplacian_mixed(d) == expected
    assert cotan_laplacian(d) == expected


def test_mixed_route_on_a_flipped_float_torus_uses_both_routes():
    # deterministic: 24 flips leave irrational squared lengths on some faces and rational
    # ones on most, so both halves of the mixed route are exercised (a sign or a factor
    # 1/2 wrong in either breaks ==)
    from ddg_oracle.reference.cotan_fast import cotan_laplacian_mixed, partly_applies
    rng = random.Random(2)
    V, F = surfaces.torus(8, 6).to_arrays()
    V = [[float(x) + rng.uniform(-0.08, 0.08) for x in v] for v in V]
    d, log = flip_to_delaunay(PolyhedralSurface.from_arrays(V, F).metric())
    irrational = [x for x in d.squared_lengths if not isinstance(x, Fraction)]
    assert log and irrational and partly_applies(d) and not applies(d)
    assert cotan_laplacian_mixed(d) == cotan_laplacian_from_weights(d) == cotan_laplacian(d)


def test_mixed_route_on_a_metric_with_every_length_irrational():
    # every face left out: the fast part is empty, the Surd part is the whole matrix
    from ddg_oracle.reference.cotan_fast import cotan_laplacian_mixed
    t = surfaces.tetrahedron().triangulation
    side2 = 2 + sqrt(2)                       # equilateral faces: area sqrt(3)/4 side^2
    m = PiecewiseFlatSurface(t, [side2] * t.n_edges,
                             areas=[sqrt(3) * side2 / 4] * t.n_faces)
    assert cotan_laplacian_mixed(m) == cotan_laplacian_from_weights(m)


def assert_same_view(d):
    """The float view of a flipped metric (quotients, no division) == the exact matrix's
    float view: every entry correctly rounded, exact zeros left out the same way."""
    from ddg_oracle.properties.views import _flipped_laplacian_view, exact_laplacian
    assert not all(isinstance(x, Fraction) for x in d.squared_lengths)
    got, want = _flipped_laplacian_view(d), exact_laplacian(d).to_scipy()
    got.sort_indices()
    want.sort_indices()
    assert (got.indptr == want.indptr).all() and (got.indices == want.indices).all()
    assert got.data.tobytes() == want.data.tobytes()         # bit for bit, signs of 0 too


@settings(max_examples=25)
@given(closed_meshes(), st.data())
def test_filtered_view_of_flipped_metrics_is_the_exact_view(case, data):
    # issue 46: float meshes flipped to Delaunay (irrational squared lengths on some faces)
    # and the same metric flipped at random first (irrational lengths on most draws)
    s = jittered(case, data.draw, [4, 8, 20])
    m = random_flips(s.metric(), random.Random(data.draw(st.integers(0, 2 ** 32))), 12)
    checked = 0
    for x in (flip_to_delaunay(s.metric())[0], m, flip_to_delaunay(m)[0]):
        if not all(isinstance(y, Fraction) for y in x.squared_lengths):
            assert_same_view(x)
            checked += 1
    assume(checked)


@pytest.mark.parametrize("seed", range(6))
def test_filtered_view_on_random_flips_with_loops_and_zero_weights(seed):
    # metrics flipped at random (not Delaunay: negative weights, loops on the tori), and a
    # grid's cocircular squares: exact zero weights between irrational faces are left out
    rng = random.Random(seed)
    for name in ("flat torus", "icosahedron", "Klein bottle"):
        m = random_flips(_BASES[name](), rng, 40)
        if not all(isinstance(x, Fraction) for x in m.squared_lengths):
            assert_same_view(m)
    grid = surfaces.grid(4, 3).metric()
    m = random_flips(PiecewiseFlatSurface(grid.triangulation,
                                          [x * (2 + sqrt(2)) for x in grid.squared_lengths],
                                          areas=[a * (2 + sqrt(2)) for a in grid.areas]),
                     rng, 30)
    assert_same_view(m)
    assert any(w == 0 for w in cotan_weights(m).values())


def test_rounded_sums_of_quotients_at_ties_tiny_scales_and_exact_zeros():
    from ddg_oracle.reference.exact import Quotient, limits, rounded_sum
    from ddg_oracle.reference.exact.surds import sum_is_zero
    r = sqrt(2) + sqrt(3) + sqrt(5)
    q = Quotient(sqrt(7) - 1, r)
    assert float(q) == float((sqrt(7) - 1) / r)
    tiny = Quotient((sqrt(7) - 1) / 2 ** 1200, r)               # far below 2**-64
    assert float(tiny) == float((sqrt(7) - 1) / r / 2 ** 1200)
    # exactly 0 with two denominators (cross-multiplied) and with three (divided)
    a, b = Quotient(sqrt(3), r), Quotient(-2 * sqrt(3), 2 * r + 0)
    assert rounded_sum([a, b]) == 0.0 and sum_is_zero([a, b])
    c = Quotient(1, sqrt(11) + 1)
    assert rounded_sum([a, c, Quotient(-1, sqrt(11) + 1), b]) == 0.0
    # a rounding tie: 1 + 2**-53 lies halfway between two floats (round half to even)
    half = Fraction(1, 2 ** 53)
    assert rounded_sum([1, Quotient(half * r, r)]) == 1.0
    assert rounded_sum([1 + 2 * half, Quotient(half * r, r)]) == 1 + 4 * float(half)
    # signs as in float(): -x rounds to -float(x)
    assert rounded_sum([Quotient(1 - sqrt(7), r)]) == -float(q)
    with pytest.raises(InputError, match="positive denominator"):
        Quotient(1, sqrt(2) - sqrt(3))
    # products beyond the term limit: undecided when cheap (the caller refines), else raised
    wide = [Quotient(sqrt(3) + sqrt(7), r), Quotient(1, sqrt(11) + sqrt(13) + 1)]
    with limits(term_limit=4):
        assert sum_is_zero(wide, cheap=True) is None
        with pytest.raises(TermLimitExceeded):
            sum_is_zero(wide)
    assert sum_is_zero(wide) is False


@settings(max_examples=30)
@given(any_meshes(), st.data())
def test_vertex_area_floats_are_the_exact_areas_correctly_rounded(case, data):
    # obtuse, right and acute faces; exact and jittered points; both kinds
    from ddg_oracle.reference.laplacian import (vertex_areas_barycentric, vertex_areas_floats,
                                                vertex_areas_voronoi)
    for s in (case.surface, jittered(case, data.draw, [4, 20, 60])):
        assert vertex_areas_floats(s) == [float(a) for a in vertex_areas_voronoi(s)]
        assert vertex_areas_floats(s, "barycentric") == \
            [float(a) for a in vertex_areas_barycentric(s)]


def _float_area_gradient(s):
    from ddg_oracle.reference.areas import area_gradient
    return [tuple(float(x) for x in g) for g in area_gradient(s)]


@settings(max_examples=30)
@given(any_meshes(), st.data())
def test_area_gradient_floats_are_the_exact_gradient_correctly_rounded(case, data):
    # planar meshes (exact zeros at interior vertices: the exact fallback), tiny and
    # ordinary perturbations, 2-D and 4-D points
    from ddg_oracle.reference.areas import area_gradient_floats
    s = case.surface
    assert area_gradient_floats(s) == _float_area_gradient(s)
    j = jittered(case, data.draw, [8, 20, 60, 200])
    assert area_gradient_floats(j) == _float_area_gradient(j)
    dim = data.draw(st.sampled_from([2, 4]))
    pts = [tuple(p[:2]) if dim == 2 else tuple(p) + (p[0] * p[1],) for p in case.positions]
    try:
        other = PolyhedralSurface.from_arrays(pts, case.faces)
        expected = _float_area_gradient(other)
    except DegenerateFace:
        return
    assert area_gradient_floats(other) == expected


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
    real = cotangents._refined
    monkeypatch.setattr(cotangents, "_refined", lambda *a: calls.append(1) or real(*a))
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
    the factors equal sums of ddg_oracle.reference.exact.sqrt."""
    G = [101 * 103, 101 * 107 * 4, 101 ** 2 * 2 * 9, 103, 49, 6 * 101 * 113, 6 * 5]
    fd = cotangents.FaceData(G, [1] * len(G), [1] * (3 * len(G)))
    for f, g in enumerate(G):
        m, d, k = fd.root(f)
        c = d // (2 * m)
        assert k == 1 and c * c * m == g and sqrt(g) == c * sqrt(m)
    rng = random.Random(5)
    for _ in range(60):
        terms, expected = {}, 0
        for f in rng.sample(range(len(G)), rng.randint(1, 5)):
            q = Fraction(rng.choice([-1, 1]) * rng.randint(1, 9), rng.randint(1, 9))
            m = fd.root(f)[0]
            terms[m] = terms.get(m, 0) + q
            expected = expected + q * sqrt(m)
        terms = {m: q for m, q in terms.items() if q}
        assert cotangents._value(terms, fd.parts) == expected
        if len(terms) > 1:
            assert cotangents._refined(terms, fd.parts) == expected


_PRIMORIAL_100 = prod(p for p in range(2, 100) if all(p % q for q in range(2, p)))


def _assert_coprime_base(base, terms, coarsest):
    """``base``: sorted, pairwise coprime, every radicand of ``terms`` the product of some of
    its elements; ``coarsest``: no two elements dividing the same radicands (one would do)."""
    assert list(base) == sorted(base) and all(b > 1 for b in base)
    assert all(gcd(a, b) == 1 for i, a in enumerate(base) for b in base[i + 1:])
    for m in terms:
        assert m == prod(b for b in base if m % b == 0)
    patterns = [frozenset(m for m in terms if m % b == 0) for b in base]
    assert all(patterns) and (not coarsest or len(set(patterns)) == len(patterns))


def test_edge_values_are_the_general_route_written_out():
    """FaceData.value of an edge's four integers (f1, n1, f2, n2) takes its own route
    (equal, coprime, sharing small primes, sharing a large prime, a rational face,
    terms that cancel); it gives the canonical form the general route (terms, then
    _value) gives, base and coefficients alike, and the value 1/2 sum n / sqrt(G)."""
    G = [101 * 103, 101 * 107 * 4, 101 ** 2 * 2 * 9, 103, 4 * 103, 49, 4 * 49,
         6 * 101 * 113, 6 * 5, 9 * 30, 10 * 7, 101 ** 2 * 103 * 3]
    fd = cotangents.FaceData(G, [1] * len(G), [1] * (3 * len(G)))
    seen = set()
    for f in range(len(G)):
        for g in range(len(G)):
            for n1, n2 in ((1, 1), (1, -1), (1, -2), (-3, 2), (2, -1), (5, 7)):
                raw = (f, n1, g, n2)
                fast = fd.value(raw)
                general = cotangents._value(fd.terms(raw), fd.parts)
                expected = (Fraction(n1, 2) * sqrt(Fraction(1, G[f]))
                            + Fraction(n2, 2) * sqrt(Fraction(1, G[g])))
                assert type(fast) is type(general) and fast == general == expected
                if type(fast) is Surd:
                    assert fast.base == general.base and fast._terms == general._terms
                    # the coarsest base unless two different large parts (primes above
                    # 100) share a prime: then gcd splitting refines it further
                    L = [m // gcd(m, _PRIMORIAL_100) for m in (fd.root(f)[0], fd.root(g)[0])]
                    shared = L[0] != L[1] and gcd(*L) != 1
                    _assert_coprime_base(fast.base, fast._terms, coarsest=not shared)
                seen.add((type(fast), len(fast.base) if type(fast) is Surd else 0))
    # rational values (a square G, or terms that cancel) and bases of 1, 2 and 3 elements
    assert {(Fraction, 0), (Surd, 1), (Surd, 2), (Surd, 3)} <= seen


# --- the lazy values: CotanSum ------------------------------------------------------------


@st.composite
def hard_meshes(draw):
    """Meshes of every kind (boundaries, obtuse and needle faces, closed ones) under the
    transformations the fast path must survive: huge and tiny power-of-two scales,
    a common factor with odd primes in its denominator (S not a power of two), float
    jitter of drawn magnitudes (one denominator per face when they differ wildly)."""
    case = draw(any_meshes())
    k = draw(st.sampled_from([0, 0, -300, -64, 64, 300]))
    odd = draw(st.sampled_from([1, Fraction(1, 3), Fraction(7, 5), Fraction(1, 1000001)]))
    pts = [tuple(x * odd * Fraction(2) ** k for x in p) for p in case.positions]
    if draw(st.booleans()):
        pts = [tuple(x + draw(st.sampled_from([0, 1, -1])) * draw(st.floats(0.5, 1.0))
                     * Fraction(2) ** -draw(st.sampled_from([10, 40, 200])) * Fraction(2) ** k
                     for x in p) for p in pts]
    try:
        s = PolyhedralSurface(case.surface.triangulation, pts)
        s.metric()
    except DegenerateFace:                  # a jitter collapsed a needle: not this test
        assume(False)
    return s


@st.composite
def thin_triangles(draw):
    """Faces next to degenerate ones: an apex at height 2**-k above a long base, glued
    to a fan around it, with right angles (N = 0) and equal faces (equal G)."""
    k = draw(st.sampled_from([1, 20, 60, 500]))
    x = draw(st.sampled_from([Fraction(0), Fraction(1, 2), Fraction(1), Fraction(3, 2),
                              Fraction(-1, 3)]))
    h = Fraction(1, 2 ** k)
    pts = [(0, 0, 0), (1, 0, 0), (x, h, 0), (x, -h, 0), (Fraction(1, 2), Fraction(1, 2), h)]
    faces = [(0, 1, 2), (1, 0, 3), (1, 4, 2), (0, 2, 4)]
    faces = faces[:draw(st.integers(1, 4))]
    used = sorted({v for f in faces for v in f})
    return PolyhedralSurface.from_arrays([pts[v] for v in used],
                                         [[used.index(v) for v in f] for f in faces])


def _unset(x) -> bool:
    """Whether the canonical form of ``x`` was never computed (the slot is empty)."""
    try:
        Surd._terms.__get__(x, Surd)
    except AttributeError:
        return True
    return False


def assert_lazy_like_canonical(x, bits=80):
    """A CotanSum answers sign, float, hash, enclosures, negation and comparisons with 0
    from its integers -- as its canonical Surd does -- without computing its canonical form."""
    assert isinstance(x, CotanSum) and _unset(x)
    sign, value, h, (lo, hi) = x.sign(), float(x), hash(x), x.interval(bits)
    neg = -x
    answers = (sign, x < 0, x > 0, x <= 0, x == 0, bool(x), abs(x).sign(), neg.sign(),
               float(neg), x.is_rational())
    assert _unset(x) and _unset(neg)
    c = Surd(x)                                     # the canonical form, now computed
    assert type(c) is Surd and not _unset(x) and c.base and x.base == c.base
    assert answers == (c.sign(), c < 0, c > 0, c <= 0, c == 0, bool(c), abs(c).sign(),
                       (-c).sign(), float(-c), False)
    assert sign != 0 and value == float(c) and h == hash(c) == hash(Surd(c))
    assert lo <= c <= hi and hi - lo <= Fraction(1, 2 ** bits)
    assert neg == -c and x == c and c == x and x != c + 1 and x - c == 0
    assert pickle.loads(pickle.dumps(x)) == c and str(x) == str(c)


def lazy_values(s):
    """The CotanSums among fresh weights and Laplacian entries (L[i, j] is L[j, i])."""
    w = cotan_weights_fast(s)
    L = cotan_laplacian_fast(s)
    xs = list(w.values()) + [v for i, j, v in L.entries() if i <= j]
    return [v for v in xs if isinstance(v, CotanSum)]


@settings(max_examples=60, deadline=None)
@given(st.one_of(hard_meshes(), thin_triangles()))
def test_fast_cotan_equals_definition_on_hard_meshes(s):
    assert_same_cotan(s)
    for x in lazy_values(s):
        assert_lazy_like_canonical(x)


def test_lazy_values_on_the_benchmark_icosphere():
    """Every irrational weight and Laplacian entry of the float icosphere is a CotanSum
    (the residue test lets almost none through to the canonical route), and each
    behaves as its canonical Surd."""
    s = float_icosphere(2)
    xs = lazy_values(s)
    assert len(xs) > 0.99 * (s.triangulation.n_edges * 2 + s.n_vertices)
    for x in xs:
        assert_lazy_like_canonical(x)


@given(st.integers(1, 2 ** 300), st.integers(1, 2 ** 300))
def test_residue_test_never_rejects_a_square(x, y):
    M = cotangents._RESIDUE_MODULUS
    (rx, px), (ry, py) = cotangents._odd_residue(x * x), cotangents._odd_residue(y * y)
    assert px == py == 0 and cotangents.maybe_square(rx)
    assert cotangents.maybe_square(rx * ry)                    # G1 G2 from residues
    assert cotangents.maybe_square(x * x) and cotangents.maybe_square(x * x % M)
    assert cotangents._is_square(x * x) and not cotangents._is_square(x * x + 2 * x + 2)
    fd = cotangents.FaceData([x * x + 1, y * y], [1, 1], [1] * 6)
    assert fd.is_square(1) and not fd.is_square(0)


def test_residue_test_rejects_almost_every_non_square():
    """The claim of the module docstring: about 1 odd non-square in 3,000 gets through."""
    rng = random.Random(7)
    xs = [rng.getrandbits(200) | 1 for _ in range(30000)]
    assert sum(cotangents.maybe_square(x) for x in xs) < 30


# --- exact angle sums, defects and the Gauss-Bonnet decision ---------------------------------


def assert_same_curvature(s):
    """The fast angle sums equal the definition's, Angle by Angle; the dispatching
    public functions give the definition's defects and turning angles; the integer
    Gauss-Bonnet decision agrees with the one by exact Angles."""
    assert curvature_fast.applies(s)
    sums = angle_sums_from_corners(s)
    fast = curvature_fast.angle_sums_fast(s)
    assert len(fast) == len(sums) and all(a == b for a, b in zip(fast, sums))
    corners, defined = corner_angles(s), corner_angles_from_cotangents(s)
    assert len(corners) == len(defined) == s.triangulation.n_faces
    assert all(a == b and float(a) == float(b) for fa, fb in zip(corners, defined)
               for a, b in zip(fa, fb))
    boundary = {v for v in range(len(sums)) if s.triangulation.is_boundary_vertex(v)}
    assert angle_defects(s) == {v: 2 * pi - x for v, x in enumerate(sums) if v not in boundary}
    assert turning_angles(s) == {v: pi - x for v, x in enumerate(sums) if v in boundary}
    assert curvature_fast.gauss_bonnet_holds_fast(s) is True
    assert gauss_bonnet_holds_by_faces(s) is True and gauss_bonnet_holds(s) is True
    return fast


@settings(max_examples=40, deadline=None)
@given(st.one_of(hard_meshes(), thin_triangles()))
def test_fast_angle_sums_and_gauss_bonnet_equal_definition(s):
    assert_same_curvature(s)


# rational angles (pi/4, pi/2, 3 pi/4) and irrational multiples of pi/24 (pi/3 on the
# octahedron and icosahedron, pi/6 and 2 pi/3 on the last triangle): the definition's route
@pytest.mark.parametrize("build", [surfaces.cube, surfaces.octahedron, surfaces.icosahedron,
                                   lambda: surfaces.grid(2, 3), lambda: surfaces.torus(5, 7),
                                   surfaces.mobius_strip, surfaces.annulus,
                                   lambda: PolyhedralSurface.from_arrays(
                                       [(0, 0, 0), (1, -1, 0), (0, 1, -1)], [(0, 1, 2)])])
def test_fast_angle_sums_on_named_surfaces(build):
    s = build()
    fast = assert_same_curvature(s)
    if build is surfaces.cube:                      # pi parts, as the definition stores them
        assert all(not a.parts and a.pi_coefficient == Fraction(3, 2) for a in fast)


def test_fast_angle_sums_on_intrinsic_surfaces_and_the_benchmark_icosphere():
    rng = random.Random(4)
    t = surfaces.octahedron().triangulation
    for _ in range(8):
        try:
            t = t.flip(rng.randrange(t.n_edges))
        except NotFlippable:
            pass
    assert_same_curvature(PiecewiseFlatSurface(t, [1] * t.n_edges))
    assert_same_curvature(random_flips(flat_torus(4, 5, (3, 1), (1, 2)), rng, 40))
    s = float_icosphere()
    fast = assert_same_curvature(s)
    cots = [c for a in fast for c in a.parts]         # the residue test lets a few through
    assert len(cots) == 3 * s.triangulation.n_faces
    assert sum(isinstance(c, CotanSum) for c in cots) > 0.95 * len(cots)


def _parts_built(a) -> bool:
    """Whether a CornerSum's parts slot is set (read through the slot itself, not through
    ``__getattr__``, which would build them)."""
    try:
        Angle.__dict__["_parts"].__get__(a, type(a))
    except AttributeError:
        return False
    return True


@settings(max_examples=30, deadline=None)
@given(st.one_of(hard_meshes(), thin_triangles()))
def test_corner_sums_answer_from_their_integers_as_their_parts_would(s):
    """A CornerSum (the fast angle sum of a vertex without multiples of pi / 24) gives the
    enclosures, sign, float and hash of the Angle of its parts, and keeps its form under
    negation and a multiple of pi added (defects, turning angles) without building them;
    pickled, it is that plain Angle.  Only the exact decisions (the zero test, the turning
    count) read the parts: a sum that is a multiple of pi (two corners with cotangents c and
    -c, then a - pi = 0) needs them."""
    lazy = [a for a in curvature_fast.angle_sums_fast(s) if isinstance(a, CornerSum)]
    assume(lazy)
    for a in lazy:
        assert a + 0 is a and 0 + a is a
        for b in (a, -a, 2 * pi - a, a - pi, pi * Fraction(-3, 2) + a):
            assert type(b) is CornerSum
            for bits in (8, 70, 200):
                b._scaled_at(bits)
            with mock.patch.object(angles, "_pi24_multiple",
                                   wraps=angles._pi24_multiple) as zero_test, \
                    mock.patch.object(angles, "_sign_by_turning",
                                      wraps=angles._sign_by_turning) as turning:
                sign, x, h = b.sign(), float(b), hash(b)
            # the exact decisions (the zero test, the turning count) read the parts
            assert _parts_built(b) == (zero_test.called or turning.called)
            plain = Angle._raw(b._parts, b._pi)             # builds them
            assert _parts_built(b) and type(plain) is Angle
            for bits in (8, 70, 200):
                assert b._scaled_at(bits) == plain._scaled_at(bits)
            assert (sign, x, h) == (plain.sign(), float(plain), hash(plain))
            assert b._weight() == plain._weight() == len(b._corners) // 2
            assert b._one_signed() == plain._one_signed() == b._s
            copy = pickle.loads(pickle.dumps(b))
            assert type(copy) is Angle and copy == b and copy.parts == b.parts
        assert type(a + a) is Angle and a + a == 2 * a


def test_gauss_bonnet_falls_back_to_the_definition(monkeypatch):
    """A face whose angle sum the integer test cannot show to be pi (a corrupted G
    here) makes the fast decision abstain, and the definition decides."""
    real = curvature_fast.face_data

    def corrupted(surface):
        fd = real(surface)
        fd.G[0] += 1
        return fd

    monkeypatch.setattr(curvature_fast, "face_data", corrupted)
    s = surfaces.torus(4, 3)
    assert curvature_fast.gauss_bonnet_holds_fast(s) is None
    assert gauss_bonnet_holds(s) is True


@given(triangulated_surfaces())
def test_boundary_vertices_are_the_open_fans(case):
    t = case.triangulation
    assert t.boundary_vertices() == {v for v in range(t.n_vertices) if t.is_boundary_vertex(v)}


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


# --- the Delaunay test on integers (flip_to_delaunay's first pass) ------------------------------

from ddg_oracle.reference.delaunay import _delaunay_by_integers, is_delaunay_edge  # noqa: E402


@settings(max_examples=40, deadline=None)
@given(st.one_of(hard_meshes(), thin_triangles(), any_meshes().map(lambda c: c.surface)))
def test_delaunay_by_integers_equals_the_definition(s):
    """Every edge's D4.4 answer from the integers N, G equals is_delaunay_edge's (exact
    Surd sums), cocircular pairs (cot sum exactly 0: Delaunay) and right angles (N = 0)
    included."""
    m = s.metric() if isinstance(s, PolyhedralSurface) else s
    known = _delaunay_by_integers(m)
    definition = [is_delaunay_edge(m, e) for e in range(m.triangulation.n_edges)]
    assert [k == 1 for k in known] == definition
    assert delaunay_edges(s) == delaunay_edges(m) == definition     # the public route


@settings(max_examples=30, deadline=None)
@given(st.one_of(hard_meshes(), thin_triangles(), any_meshes().map(lambda c: c.surface)),
       st.integers(0, 2 ** 32))
def test_corner_cotangent_floats_are_the_exact_ones_correctly_rounded(s, seed):
    """properties.ties.corner_cot_floats (the integers' route, one isqrt per corner) gives
    float(corner_cot) bit for bit, on rational metrics and after random flips (irrational
    squared lengths: the metric's own route)."""
    from ddg_oracle.properties.ties import corner_cot_floats
    from ddg_oracle.reference.exact import float_view as rounded     # +-inf beyond range
    m = s.metric() if isinstance(s, PolyhedralSurface) else s
    for x in (m, random_flips(m, random.Random(seed), 6)):
        want = [[rounded(x.corner_cot(f, c)) for c in range(3)]
                for f in range(x.triangulation.n_faces)]
        assert corner_cot_floats(x).tolist() == want


@pytest.mark.parametrize("build", [
    lambda: surfaces.torus(5, 7).metric(),
    lambda: random_flips(flat_torus(6, 6, (3, 1), (1, 2)), random.Random(2), 200),
    lambda: random_flips(surfaces.genus_surface(2).metric(), random.Random(5), 30)])
def test_flip_to_delaunay_from_the_integer_answers_equals_the_immutable_loop(build):
    """flip_to_delaunay starts from the integer answers (rational squared lengths) and asks
    the definition only for edges a flip changed: the same flips as the loop that asks the
    definition for every edge."""
    m = build()
    assert applies(m)
    d, log = flip_to_delaunay(m)
    d0, log0 = flip_to_delaunay_immutable(m)
    assert_same_surface(d, d0)
    assert [(r.edge, r.h_before, r.h_after) for r in log] == log0 and log


def test_delaunay_by_integers_on_cocircular_and_irrational_metrics():
    g = surfaces.grid(3, 2).metric()              # squares cut by diagonals: cot sums 0
    known = _delaunay_by_integers(g)
    inner = [e for e in range(g.triangulation.n_edges) if not g.triangulation.is_boundary_edge(e)]
    assert all(known[e] == 1 for e in range(g.triangulation.n_edges))
    assert any(cotan_weights(g)[e] == 0 for e in inner)
    t = random_flips(_BASES["icosahedron"](), random.Random(3), 10)     # sqrt lengths
    assert not applies(t) and set(_delaunay_by_integers(t)) == {2}    # the definition decides
    d, log = flip_to_delaunay(t)
    assert [(r.edge, r.h_before, r.h_after) for r in log] == flip_to_delaunay_immutable(t)[1]


def test_scaled_roots_are_the_rounded_root_sums_at_squares_midpoints_and_every_size():
    """face_area_floats' direct sqrt(G) 2^-k (float meshes: a power-of-two denominator)
    equals rounded_root_sum's bit for bit: exact squares and their neighbours (a root just
    below or above an integer), G of 1 to 2,000 bits, results near the ends of the normal
    range; None (the general route) below it."""
    import random

    from ddg_oracle.reference.exact.surds import rounded_root_sum
    from ddg_oracle.reference.metric import _scaled_root
    rng = random.Random(7)
    cases = [rng.getrandbits(b) | 1 << (b - 1)
             for b in (1, 2, 3, 52, 53, 54, 105, 106, 107, 108, 200, 2000) for _ in range(300)]
    for b in (27, 53, 54, 80):
        for _ in range(300):
            r = rng.getrandbits(b) | 1
            cases += [r * r - 1, r * r, r * r + 1]
    compared = 0
    for G in cases:
        for k in (0, 1, 300, 1000, G.bit_length() // 2 + 1021):
            got = _scaled_root(G, k)
            if got is not None:
                compared += 1
                assert got == rounded_root_sum(((G, G),), 1 << k), (G, k)
    assert compared > 20000
    assert _scaled_root(1, 1074) is None and _scaled_root(2 ** 60, 1060) is None   # 2^-1030
    # at 2^-1022: a root the 53-bit float rounds up to it is right; one just below the
    # subnormal midpoint 2^-1022 - 2^-1075 (its float 53 bits below 2^-1022, which ldexp
    # would round up to 2^-1022, half to even) is left to the general route
    assert _scaled_root(2 ** 106 - 1, 1075) == 2.0 ** -1022 == \
        rounded_root_sum(((2 ** 106 - 1, 2 ** 106 - 1),), 1 << 1075)
    G = (2 ** 53 - 1) ** 2 - 1
    assert _scaled_root(G, 1075) is None
    assert rounded_root_sum(((G, G),), 1 << 1075) == 2.0 ** -1022 - 2.0 ** -1074
