"""Tests of ddg_oracle.reference.delaunay: intrinsic Delaunay triangulations (chapter 4), exact.

Rows: D4.4 / T4.7 / P4.9 (angle criterion vs in-circle determinant), P4.10,
L4.11, A4.13 / T4.12 / C4.19 / L4.20 (runs of the flip algorithm, replayed
flip by flip), D4.7 / L4.17 / L4.18 (harmonic index), T4.5 / R4.7 / D4.8 /
R4.9 (one tessellation and one operator from different starting
triangulations), X4.2 (valence-1 vertex).
"""

import random
from collections import Counter
from fractions import Fraction

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ddg_oracle.reference import surfaces
from ddg_oracle.reference.combinatorics import Triangulation
from ddg_oracle.reference.delaunay import (DelaunayError, delaunay_tessellation_edges, face_harmonic_index,
                                flip_to_delaunay, harmonic_index, in_circumcircle,
                                is_delaunay, is_delaunay_edge, laplace_beltrami,
                                non_delaunay_edges)
from ddg_oracle.reference.errors import InputError
from ddg_oracle.reference.exact import corner_angle
from ddg_oracle.reference.intrinsic import cot_sum, flip, is_flippable
from ddg_oracle.reference.laplacian import cotan_laplacian, cotan_weights
from ddg_oracle.properties.metrics import flat_torus
from ddg_oracle.reference.metric import metric_of

SETTINGS = settings(max_examples=40, deadline=None, database=None,
                    suppress_health_check=[HealthCheck.too_slow])

seeds = st.integers(0, 1 << 30)
vec = st.tuples(st.fractions(-3, 3, max_denominator=3), st.fractions(-3, 3, max_denominator=3))


# --- helpers ----------------------------------------------------------------------------


def random_flips(m, rng, k):
    for _ in range(k):
        e = rng.randrange(m.triangulation.n_edges)
        if is_flippable(m, e):
            m = flip(m, e)
    return m


def angle_sums(m):
    t = m.triangulation
    return [sum(corner_angle(m.corner_cot(f, c)) for f, c in t.corners_around(v))
            for v in range(t.n_vertices)]


def max_sq_length(m):
    return max(m.squared_lengths)


def tessellation_key(m):
    t = m.triangulation
    return Counter((tuple(sorted(t.edge_vertices(e))), m.squared_lengths[e])
                   for e in delaunay_tessellation_edges(m))


def nondegenerate(u, v):
    return u[0] * v[1] - u[1] * v[0] != 0


def start_surface(kind, seed, flips=80):
    rng = random.Random(seed)
    if kind == "grid":
        base = surfaces.grid(rng.randint(2, 4), rng.randint(2, 4)).metric()
    else:
        while True:
            u = (rng.randint(1, 3), rng.randint(-1, 1))
            v = (rng.randint(-2, 2), rng.randint(1, 3))
            if nondegenerate(u, v):
                break
        base = flat_torus(3 + rng.randrange(2), 3 + rng.randrange(2), u, v)
    return base, random_flips(base, rng, flips)


kinds = st.sampled_from(["grid", "torus"])


# --- D4.4 / T4.7 / P4.9, P4.10, L4.11 ---------------------------------------------------------


@SETTINGS
@given(kinds, seeds)
def test_angle_criterion_agrees_with_incircle_on_every_edge(kind, seed):
    _, m = start_surface(kind, seed)
    t = m.triangulation
    for e in range(t.n_edges):
        d = is_delaunay_edge(m, e)
        assert d == (cot_sum(m, e) >= 0 or t.is_boundary_edge(e))
        if not t.is_boundary_edge(e):
            s = in_circumcircle(m, e)
            assert d == (s <= 0)
            assert (s == 0) == (cot_sum(m, e) == 0)          # on the circle iff angle sum pi
    assert is_delaunay(m) == (not non_delaunay_edges(m))


@SETTINGS
@given(kinds, seeds)
def test_weights_nonnegative_iff_delaunay_P410(kind, seed):
    _, m = start_surface(kind, seed)
    for s in (m, flip_to_delaunay(m)[0]):
        interior = [w for e, w in cotan_weights(s).items() if not s.triangulation.is_boundary_edge(e)]
        assert is_delaunay(s) == all(w >= 0 for w in interior)


@SETTINGS
@given(kinds, seeds)
def test_non_delaunay_edges_flippable_and_become_delaunay_L411(kind, seed):
    _, m = start_surface(kind, seed)
    for e in non_delaunay_edges(m):
        assert is_flippable(m, e)
        assert is_delaunay_edge(flip(m, e), e)
        assert in_circumcircle(flip(m, e), e) <= 0


# --- D4.7 / L4.17 / L4.18 --------------------------------------------------------------------


@SETTINGS
@given(kinds, seeds)
def test_harmonic_index_three_ways(kind, seed):
    _, m = start_surface(kind, seed)
    t = m.triangulation
    for f in range(t.n_faces):                           # L4.17
        assert face_harmonic_index(m, f) == 4 * sum(m.corner_cot(f, c) for c in range(3))
    # L4.18: h = 8 sum_i E(phi_i), E(phi_i) = 1/2 L[i, i].  It needs a triangulation
    # without loops: a loop edge at i carries phi_i = 1 at both ends, so it adds nothing
    # to E(phi_i) although it adds 8 nu(e) to h (exactly that difference is asserted).
    L = cotan_laplacian(m)
    w = cotan_weights(m)
    loops = [e for e in range(t.n_edges) if len(set(t.edge_vertices(e))) == 1]
    energies = 8 * sum(Fraction(1, 2) * L[i, i] for i in range(t.n_vertices))
    assert harmonic_index(m) == energies + 8 * sum(w[e] for e in loops)
    if not loops:
        assert harmonic_index(m) == energies


def test_L418_fails_with_a_loop_edge():
    """The exception to L4.18: a flipped flat torus with a loop edge of nonzero weight."""
    _, m = start_surface("torus", 154)
    t = m.triangulation
    loops = [e for e in range(t.n_edges) if len(set(t.edge_vertices(e))) == 1]
    assert loops and any(cotan_weights(m)[e] != 0 for e in loops)
    L = cotan_laplacian(m)
    assert harmonic_index(m) != 4 * sum(L[i, i] for i in range(t.n_vertices))


# --- A4.13 / T4.12 / C4.19 / L4.20 ------------------------------------------------------------


@SETTINGS
@given(kinds, seeds)
def test_flip_algorithm_runs(kind, seed):
    _, m = start_surface(kind, seed)
    d, log = flip_to_delaunay(m)
    assert is_delaunay(d)
    assert all(in_circumcircle(d, e) <= 0 for e in range(d.triangulation.n_edges))
    assert d.total_area() == m.total_area()
    assert angle_sums(d) == angle_sums(m)
    A = m.total_area()
    # replay the run flip by flip: the log's h values, C4.19 and L4.20 at every step
    cur, h = m, harmonic_index(m)
    assert h * A >= max_sq_length(cur)
    for rec in log:
        assert rec.h_before == h
        assert not is_delaunay_edge(cur, rec.edge)
        cur = flip(cur, rec.edge)
        h = harmonic_index(cur)
        assert rec.h_after == h
        assert rec.h_after < rec.h_before                # C4.19, strict
        assert h * A >= max_sq_length(cur)               # L4.20, squares compared exactly
    assert cur.squared_lengths == d.squared_lengths
    assert cur.triangulation == d.triangulation
    # T4.12: bounded by the number of triangulations below h; at least no revisits
    assert len(log) <= 10 * m.triangulation.n_edges


def test_max_flips_and_error_messages():
    m = flat_torus(3, 3, (1, 0), (3, 1))
    assert non_delaunay_edges(m)
    with pytest.raises(DelaunayError, match="max_flips"):
        flip_to_delaunay(m, max_flips=0)
    with pytest.raises(InputError, match="not a Delaunay"):
        delaunay_tessellation_edges(m)
    g = surfaces.grid(2, 2).metric()
    assert all(is_delaunay_edge(g, e) for e in range(g.triangulation.n_edges)
               if g.triangulation.is_boundary_edge(e))
    boundary = [e for e in range(g.triangulation.n_edges) if g.triangulation.is_boundary_edge(e)]
    assert boundary and all(in_circumcircle(g, e) == -1 for e in boundary)


# --- T4.5 / R4.7 / D4.8 / R4.9 ---------------------------------------------------------------


@SETTINGS
@given(kinds, seeds, seeds)
def test_unique_tessellation_and_operator(kind, seed1, seed2):
    base, a = start_surface(kind, seed1)
    rng = random.Random(seed2)
    b = random_flips(base, rng, 60)
    da, db = flip_to_delaunay(a)[0], flip_to_delaunay(b)[0]
    assert tessellation_key(da) == tessellation_key(db)                  # T4.5, R4.7
    assert laplace_beltrami(a) == laplace_beltrami(b) == cotan_laplacian(da)   # R4.9
    assert laplace_beltrami(a) == laplace_beltrami(base)
    assert laplace_beltrami(a).shape == (base.triangulation.n_vertices,) * 2
    for e, w in cotan_weights(da).items():                             # nonnegative weights
        if not da.triangulation.is_boundary_edge(e):
            assert w >= 0
            assert (e in delaunay_tessellation_edges(da)) == (w > 0)


def test_grid_tessellation_is_squares():
    g = surfaces.grid(3, 2).metric()
    kept = delaunay_tessellation_edges(g)
    t = g.triangulation
    assert len(kept) == t.n_edges - 6                  # the 6 diagonals have weight 0
    assert all(g.squared_lengths[e] == 1 for e in kept)


@SETTINGS
@given(vec, vec, seeds)
def test_flat_torus_parallelogram(u, v, seed):
    if not nondegenerate(u, v):
        return
    base = flat_torus(3, 3, u, v)
    rng = random.Random(seed)
    a, b = random_flips(base, rng, 30), random_flips(base, rng, 30)
    da, db = flip_to_delaunay(a)[0], flip_to_delaunay(b)[0]
    assert is_delaunay(da) and is_delaunay(db)
    assert tessellation_key(da) == tessellation_key(db)
    assert cotan_laplacian(da) == cotan_laplacian(db)


def cayley(a, b, c):
    """The rational rotation (I + S)(I - S)^{-1} = I + 2 (S + S^2) / (1 + |w|^2)."""
    S = [[0, -c, b], [c, 0, -a], [-b, a, 0]]
    S2 = [[sum(S[i][k] * S[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    n = 1 + a * a + b * b + c * c
    return [[(i == j) + Fraction(2) * (S[i][j] + S2[i][j]) / n for j in range(3)] for i in range(3)]


@SETTINGS
@given(st.fractions(-3, 3, max_denominator=3), st.fractions(-3, 3, max_denominator=3),
       st.fractions(-3, 3, max_denominator=3))
def test_rotated_grid_is_delaunay_nothing_flipped(a, b, c):
    R = cayley(a, b, c)
    assert all(sum(R[k][i] * R[k][j] for k in range(3)) == (i == j)
               for i in range(3) for j in range(3))
    g = surfaces.grid(3, 2)
    t = g.metric().triangulation
    pts = [(i, j, 0) for i in range(4) for j in range(3)]
    rp = [tuple(sum(R[r][k] * p[k] for k in range(3)) for r in range(3)) for p in pts]
    m = metric_of(rp, t)
    d, log = flip_to_delaunay(m)
    assert log == []
    diagonals = [e for e in range(t.n_edges) if m.squared_lengths[e] == 2]
    assert len(diagonals) == 6
    assert all(in_circumcircle(m, e) == 0 and cot_sum(m, e) == 0 for e in diagonals)


# --- X4.2 ------------------------------------------------------------------------------------


def test_tetrahedron_with_valence_one_vertex_X42():
    """A flat tetrahedron (base triangle (0,0,0), (10,0,0), (0,1,0), low apex
    (1, 1/3, 1/10)): its Delaunay triangulation has a vertex of valence 1."""
    t = Triangulation.from_faces([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
    P = [(0, 0, 0), (10, 0, 0), (0, 1, 0), (1, Fraction(1, 3), Fraction(1, 10))]
    m = metric_of(P, t)
    d, log = flip_to_delaunay(m)
    assert log and is_delaunay(d)
    val = [d.triangulation.valence(v) for v in range(4)]
    assert 1 in val
    assert not d.triangulation.is_regular()
    assert angle_sums(d) == angle_sums(m)


# --- performance -----------------------------------------------------------------------------


def test_large_torus_to_delaunay():
    """~2,000 faces (flat torus 32 x 32, 3000 random flips): about 0.6 s to Delaunay."""
    m = random_flips(flat_torus(32, 32, (3, 1), (1, 2)), random.Random(7), 3000)
    assert m.triangulation.n_faces == 2048
    assert non_delaunay_edges(m)
    d, log = flip_to_delaunay(m)
    assert is_delaunay(d) and log
    assert d.total_area() == m.total_area()


@settings(max_examples=6, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(["icosahedron", "torus"]), seeds)
def test_surfaces_from_R3_irrational_data(name, seed):
    """Surd data (face areas from R^3): random flips then the flip algorithm gets back a
    Delaunay triangulation with the original (Delaunay) surface's operator (R4.9)."""
    base = getattr(surfaces, name)().metric()
    assert is_delaunay(base)
    m = random_flips(base, random.Random(seed), 25)
    d, log = flip_to_delaunay(m)
    assert is_delaunay(d)
    assert all(r.h_after < r.h_before for r in log)
    assert cotan_laplacian(d) == cotan_laplacian(base)
    assert d.total_area() == base.total_area()


def test_flips_of_a_tiny_bicone_are_decided_by_relative_enclosures():
    """A metric drawn by tests/test_fast_paths.py::hard_meshes (a 30-gon bicone scaled far
    below 1: squared lengths with 731-bit denominators, benchmarks/data): after a few flips
    the cotangent sums lie near 2^-1200 and have thousands of square-root terms.  Absolute
    2^-256 enclosures said nothing about them, so every Delaunay test and Surd sign fell to
    exact expansion (more than 4 minutes, or TermLimitExceeded); enclosures relative to
    each value's size decide them."""
    import json
    from pathlib import Path
    from ddg_oracle.reference.metric import PiecewiseFlatSurface
    data = json.loads((Path(__file__).parents[1] / "benchmarks" / "data"
                       / "flip_limit_bicone.json").read_text())
    m = PiecewiseFlatSurface(Triangulation.from_faces(data["faces"]),
                             [Fraction(x) for x in data["squared_lengths"]])
    assert max(x.denominator.bit_length() for x in m.squared_lengths) > 700
    d, log = flip_to_delaunay(m)        # raises DelaunayError should a flip not decrease h
    assert len(log) == 26 and is_delaunay(d)
    assert d.triangulation.faces != m.triangulation.faces
    assert d.triangulation.n_vertices == m.triangulation.n_vertices
