"""Mutants of reference/delaunay.py killed on generic surfaces (docs/mutation.md).

The angle criterion (D4.4) against the in-circle determinant of the unfolded pair (T4.7)
and against float cotangents, on edges whose two triangles have *different* areas (on
grids and flat tori every triangle has the same area, so swapping the two faces' areas in
``cot = N / 4A`` goes unnoticed there); the in-circle determinant against numpy's 4x4
determinant; the flip algorithm's output against T4.7 (every edge passes the in-circle
test), the unchanged cone angles and area (the same surface), Rippa's theorem (the
Dirichlet energy does not increase) and the log's identities (C4.19); the integer route
against the definition edge by edge.
"""

from __future__ import annotations

import math
import random
from fractions import Fraction

import numpy as np
import pytest

from ddg_oracle.reference import delaunay as D
from ddg_oracle.reference import surfaces
from ddg_oracle.reference.combinatorics import Triangulation
from ddg_oracle.reference.curvature import angle_sums
from ddg_oracle.reference.errors import InputError
from ddg_oracle.reference.exact import sign
from ddg_oracle.reference.intrinsic import IntrinsicTriangulation, flip, is_flippable
from ddg_oracle.reference.laplacian import cotan_laplacian, dirichlet_energy
from ddg_oracle.reference.metric import PiecewiseFlatSurface
from ddg_oracle.reference.polyhedral import PolyhedralSurface

from tests.test_mutants_surfaces import (all_cases, flipped, float_lengths_angles, hilly_grid,
                                         jittered, planar, random_lengths)

CASES = all_cases()
IDS = [name for name, _ in CASES]


def _metric(s):
    return s.metric() if isinstance(s, PolyhedralSurface) else s


def _float_cot_sum(m, e):
    t = m.triangulation
    ang = float_lengths_angles(m)
    return sum(1 / math.tan(ang[h // 3][(h % 3 + 2) % 3]) for h in t.edge_halfedges(e) if h >= 0)


def _quad(k, l_):
    """Two triangles on the edge (0,0)-(1,0) with apexes k (above) and l (below)."""
    return PolyhedralSurface.from_arrays([[0, 0], [1, 0], list(k), list(l_)],
                                         [[0, 1, 2], [1, 0, 3]]).metric()


def test_angle_criterion_on_pairs_of_unequal_areas():
    # one small and one large triangle: cot alpha + cot beta has the sign of
    # N_h A_g + N_t A_f (N the 4 A cot numerators), not of N_h A_f + N_t A_g
    rng = random.Random(1)
    outcomes = set()
    for _ in range(200):
        k = (Fraction(rng.randint(-50, 150), 100), Fraction(rng.randint(2, 30), 100))
        l_ = (Fraction(rng.randint(-50, 150), 100), -Fraction(rng.randint(50, 300), 100))
        m = _quad(k, l_)
        d = D.is_delaunay_edge(m, 0)
        inc = D.in_circumcircle(m, 0)
        assert d == (inc <= 0)
        c = _float_cot_sum(m, 0)
        if abs(c) > 1e-9:
            assert d == (c > 0)
        assert D._delaunay_by_integers(m)[0] == (D._YES if d else D._NO)
        outcomes.add((d, m.areas[0] < m.areas[1]))
    assert outcomes == {(True, True), (False, True)}


def _on_circle(t, cx, cy, r):
    """The rational point of the circle (cx, cy), r at the parameter t."""
    c, s = (1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)
    return cx + r * c, cy + r * s


def test_cocircular_quads_are_delaunay_with_weight_zero():
    # circles through (0,0) and (1,0) with rational radius: centre (1/2, y0),
    # r^2 = 1/4 + y0^2 (y0 = 0, r = 1/2; y0 = 3/8, r = 5/8; y0 = -2/3, r = 5/6); apexes on
    # both arcs: the angles opposite the edge sum to pi exactly, the triangles' areas differ
    for y0, r in ((Fraction(0), Fraction(1, 2)), (Fraction(3, 8), Fraction(5, 8)),
                  (Fraction(-2, 3), Fraction(5, 6))):
        for tk, tl in ((Fraction(1, 2), Fraction(-3)), (Fraction(2), Fraction(-1, 5)),
                       (Fraction(4, 3), Fraction(-7, 2))):
            k, l_ = _on_circle(tk, Fraction(1, 2), y0, r), _on_circle(tl, Fraction(1, 2), y0, r)
            if k[1] <= 0 or l_[1] >= 0:
                continue
            m = _quad(k, l_)
            assert m.areas[0] != m.areas[1]
            assert D.in_circumcircle(m, 0) == 0
            assert D.is_delaunay_edge(m, 0)
            assert D._delaunay_by_integers(m)[0] == D._YES
            assert abs(_float_cot_sum(m, 0)) < 1e-12
            assert D.delaunay_tessellation_edges(m) == {1, 2, 3, 4}       # the diagonal dropped
    sq = surfaces.grid(1, 1).metric()
    assert D.in_circumcircle(sq, 2) == 0 and D.is_delaunay_edge(sq, 2)


def test_incircle_determinant_against_numpy():
    rng = random.Random(2)
    for _ in range(200):
        pts = [(Fraction(rng.randint(-20, 20), rng.randint(1, 4)), Fraction(rng.randint(-20, 20), rng.randint(1, 4)))
               for _ in range(4)]
        a, b, c, d = pts
        M = np.array([[float(p[0]), float(p[1]), float(p[0] ** 2 + p[1] ** 2), 1.0] for p in pts])
        expected = np.linalg.det(M)          # the lifted determinant, rows a, b, c, d
        got = D.incircle_determinant(a, b, c, d)
        # the 3x3 form (rows translated by d) is the 4x4 lifted determinant
        assert math.isclose(float(got), expected, rel_tol=1e-9, abs_tol=1e-6)
        orient = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        if orient > 0 and abs(expected) > 1e-6:
            # counterclockwise: positive iff d inside (distance to the circumcentre)
            ax, ay, bx, by, cx, cy = (float(x) for x in (*a, *b, *c))
            dd = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
            ux = ((ax * ax + ay * ay) * (by - cy) + (bx * bx + by * by) * (cy - ay) + (cx * cx + cy * cy) * (ay - by)) / dd
            uy = ((ax * ax + ay * ay) * (cx - bx) + (bx * bx + by * by) * (ax - cx) + (cx * cx + cy * cy) * (bx - ax)) / dd
            inside = math.hypot(float(d[0]) - ux, float(d[1]) - uy) < math.hypot(ax - ux, ay - uy)
            assert (got > 0) == inside


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_angle_criterion_against_incircle_and_floats_on_generic_surfaces(case):
    name, s = case
    m = _metric(s)
    t = m.triangulation
    by_ints = D._delaunay_by_integers(m)
    for e in range(t.n_edges):
        d = D.is_delaunay_edge(m, e)
        assert by_ints[e] == (D._YES if d else D._NO)
        if t.is_boundary_edge(e):
            assert d and D.in_circumcircle(m, e) == -1
            continue
        assert d == (D.in_circumcircle(m, e) <= 0)
        c = _float_cot_sum(m, e)
        if abs(c) > 1e-9:
            assert d == (c > 0)
    bad = [e for e in range(t.n_edges) if not D.is_delaunay_edge(m, e)]
    assert D.non_delaunay_edges(m) == bad
    assert D.is_delaunay(m) == (not bad)


def test_angle_criterion_after_flips_uses_enclosures_and_exact_sums():
    # irrational squared lengths with many terms: the products exceed _SMALL_PRODUCT
    rng = random.Random(3)
    m = jittered(surfaces.icosahedron(), 4).metric()
    w = IntrinsicTriangulation(m)
    big = 0
    for _ in range(60):
        e = rng.randrange(m.triangulation.n_edges)
        if w.is_flippable(e):
            w.flip(e)
    r = w.surface()
    for e in range(r.triangulation.n_edges):
        h, t = r.triangulation.edge_halfedges(e)
        n_h, n_t = D._cot_numerator(r, h), D._cot_numerator(r, t)
        A_f, A_g = r.areas[h // 3], r.areas[t // 3]
        if D._n_terms(n_h) * D._n_terms(A_g) + D._n_terms(n_t) * D._n_terms(A_f) > D._SMALL_PRODUCT:
            big += 1
        d = D.is_delaunay_edge(r, e)
        assert d == (D.in_circumcircle(r, e) <= 0)
        c = _float_cot_sum(r, e)
        if abs(c) > 1e-9:
            assert d == (c > 0)
        # the live IntrinsicTriangulation gives the same
        assert D.is_delaunay_edge(w, e) == d
    assert big > 0
    assert all(x == D._UNKNOWN for x in D._delaunay_by_integers(r)) or all(
        isinstance(x, Fraction) for x in r.squared_lengths)


def test_edge_with_both_sides_in_one_face():
    # random flips of a small intrinsic sphere until an edge has one face on both sides
    rng = random.Random(5)
    t = Triangulation.from_faces([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
    found = 0
    for seed in range(40):
        m = random_lengths(t, seed)
        for _ in range(30):
            e = rng.randrange(t.n_edges)
            if is_flippable(m, e):
                m = flip(m, e)
            tri = m.triangulation
            for x in range(tri.n_edges):
                h, k = tri.edge_halfedges(x)
                if h // 3 == k // 3:
                    found += 1
                    assert D.is_delaunay_edge(m, x)        # two angles of one triangle < pi
                    assert D._delaunay_by_integers(m)[x] in (D._YES, D._UNKNOWN)
                    assert _float_cot_sum(m, x) > 0
        if found > 5:
            break
    assert found


def test_harmonic_index_is_four_cotangent_sums_L4_17():
    for name, s in CASES:
        m = _metric(s)
        total = 0
        for f in range(m.triangulation.n_faces):
            a, b, c = m.face_cots(f)
            assert D.face_harmonic_index(m, f) == 4 * (a + b + c)
            l0, l1, l2 = (float(x) for x in m.face_squared_lengths(f))
            assert math.isclose(float(D.face_harmonic_index(m, f)), (l0 + l1 + l2) / float(m.areas[f]), rel_tol=1e-12)
            total += float(D.face_harmonic_index(m, f))
        assert math.isclose(float(D.harmonic_index(m)), total, rel_tol=1e-12)


FLIP_CASES = [("hilly grid", hilly_grid(3, 3, 6)), ("planar", planar(hilly_grid(3, 3, 16))),
              ("klein", flipped(random_lengths(surfaces.klein_bottle(3, 4), 17), 3, flips=8)),
              ("flipped icosahedron", flipped(jittered(surfaces.icosahedron(), 1).metric(), 2, flips=8)),
              ("torus", jittered(surfaces.torus(4, 3), 3, Fraction(1, 3)))]


@pytest.mark.parametrize("case", FLIP_CASES, ids=[n for n, _ in FLIP_CASES])
def test_flip_to_delaunay_output_and_log(case):
    name, s = case
    m = _metric(s)
    d, log = D.flip_to_delaunay(s)
    t = d.triangulation
    assert all(D.in_circumcircle(d, e) <= 0 for e in range(t.n_edges))         # T4.7
    assert D.is_delaunay(d)
    assert angle_sums(d) == angle_sums(m)                                    # same surface
    assert d.total_area() == m.total_area()
    assert t.n_edges == m.triangulation.n_edges and t.euler_characteristic() == m.triangulation.euler_characteristic()
    if name != "torus":
        assert log                                                           # something flipped
    h0 = D.harmonic_index(m)
    for k, r in enumerate(log):
        assert r.change < 0                                                  # C4.19
        assert r.h_after - r.h_before == r.change
        assert r.h_before == (h0 if k == 0 else log[k - 1].h_after)
        assert r == r and repr(r) == f"FlipRecord(edge={r.edge}, change={r.change})"
    if log:
        assert log[-1].h_after == D.harmonic_index(d)
        assert log[0] != log[-1] or len(log) == 1
        assert (log[0] == 1) is False
    # the same loop with the immutable flip gives the same surface
    again = m
    for r in log:
        again = flip(again, r.edge)
    assert again.squared_lengths == d.squared_lengths and again.triangulation == d.triangulation
    # Rippa: the Dirichlet energy of any function does not increase (T4.?; R4.9's operator)
    n = t.n_vertices
    rng = random.Random(7)
    f = [Fraction(rng.randint(-9, 9), 3) for _ in range(n)]
    if all(isinstance(x, Fraction) for x in d.squared_lengths + m.squared_lengths):
        assert dirichlet_energy(cotan_laplacian(d), f) <= dirichlet_energy(cotan_laplacian(m), f)
    assert D.laplace_beltrami(s) == cotan_laplacian(d)


def test_flip_to_delaunay_bounds_flips():
    s = planar(hilly_grid(3, 3, 16))
    _, log = D.flip_to_delaunay(s)
    assert len(log) >= 2
    with pytest.raises(D.DelaunayError):
        D.flip_to_delaunay(s, max_flips=len(log) - 1)
    d, again = D.flip_to_delaunay(s, max_flips=len(log))
    assert [r.edge for r in again] == [r.edge for r in log]


def test_decrease_sign_is_the_sign_of_the_exact_change():
    rng = random.Random(8)
    m = jittered(surfaces.icosahedron(), 9).metric()
    data = [D._face_data(m, f) for f in range(m.triangulation.n_faces)]
    for _ in range(100):
        out = tuple(rng.sample(data, 2))
        into = tuple(rng.sample(data, 2))
        assert D._decrease_sign(out, into) == sign(D._exact_change(out, into))
        expected = sum(float(s) / float(A) for s, A in into) - sum(float(s) / float(A) for s, A in out)
        assert math.isclose(float(D._exact_change(out, into)), expected, rel_tol=1e-9, abs_tol=1e-12)
    assert D._decrease_sign(out, out) == 0


def test_tessellation_edges():
    g = surfaces.grid(2, 2).metric()
    edges = D.delaunay_tessellation_edges(g)
    t = g.triangulation
    # the squares' diagonals (weight 0) are dropped, every side kept
    assert edges == {e for e in range(t.n_edges) if g.squared_lengths[e] == 1}
    s = planar(hilly_grid(2, 2, 20))
    d, _ = D.flip_to_delaunay(s)
    w = {e for e in range(d.triangulation.n_edges)
         if d.triangulation.is_boundary_edge(e) or D.in_circumcircle(d, e) != 0}
    assert D.delaunay_tessellation_edges(d) == w
    bad = hilly_grid(3, 3, 6).metric()
    with pytest.raises(InputError):
        D.delaunay_tessellation_edges(bad)


def test_cot_numerator_is_four_area_times_cot():
    for name, s in CASES:
        m = _metric(s)
        for h in range(3 * m.triangulation.n_faces):
            f, c = divmod(h, 3)
            assert D._cot_numerator(m, h) == 4 * m.areas[f] * m.face_cots(f)[(c + 2) % 3]


def test_cocircular_pair_with_many_term_data_is_delaunay():
    # four points of the unit circle at 30, 165 (the edge), 105 and 315 degrees, exact in
    # Q(sqrt 2, sqrt 3): cocircular, so the angles opposite the edge sum to pi exactly
    # (cot sum 0: Delaunay, on the circle); their squared lengths and areas have several
    # terms, so the products exceed _SMALL_PRODUCT, both enclosures contain 0 and the
    # exact sign decides
    from ddg_oracle.reference.exact import sqrt as xsqrt
    s2, s6 = xsqrt(2), xsqrt(6)
    c15, s15 = (s6 + s2) / 4, (s6 - s2) / 4

    def on_circle(k):                              # (cos, sin) of 15 k degrees, exactly
        c, s = Fraction(1), Fraction(0)
        for _ in range(k):
            c, s = c * c15 - s * s15, s * c15 + c * s15
        return c, s

    pts = [on_circle(k) for k in (2, 11, 7, 21)]
    t = Triangulation.from_faces([[0, 1, 2], [1, 0, 3]])
    sq = [(pts[a][0] - pts[b][0]) ** 2 + (pts[a][1] - pts[b][1]) ** 2
          for a, b in (t.edge_vertices(e) for e in range(t.n_edges))]

    def area(a, b, c):
        return abs(((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])) / 2)

    m = PiecewiseFlatSurface(t, sq, [area(*pts[:3]), area(pts[1], pts[0], pts[3])])
    h, k = t.edge_halfedges(0)
    assert (D._n_terms(D._cot_numerator(m, h)) * D._n_terms(m.areas[1])
            + D._n_terms(D._cot_numerator(m, k)) * D._n_terms(m.areas[0])) > D._SMALL_PRODUCT
    assert D.in_circumcircle(m, 0) == 0
    assert D.is_delaunay_edge(m, 0) and D.is_delaunay(m)
    assert abs(_float_cot_sum(m, 0)) < 1e-12
