"""Mutants of reference/intrinsic.py killed on generic surfaces (docs/mutation.md).

An intrinsic flip (L2.8) keeps the surface: every cone angle, the total area, and the two
new faces' areas are Heron's areas of their new side lengths (computed here from the
squared lengths, not from the flip's closed formulas).  On surfaces where the two
triangles of an edge have different areas, a flip that gives face f the area meant for g
fails these checks (on a grid or a flat torus both areas are equal).  The unfolding's
coordinates against floats of the law of cosines; convexity against float angle sums.
"""

from __future__ import annotations

import math
import random
from fractions import Fraction

import pytest

from ddg_oracle.reference import intrinsic as I
from ddg_oracle.reference import surfaces
from ddg_oracle.reference.combinatorics import Triangulation
from ddg_oracle.reference.curvature import angle_sums_from_corners
from ddg_oracle.reference.errors import InputError, NotFlippable
from ddg_oracle.reference.metric import PiecewiseFlatSurface, heron16
from ddg_oracle.reference.polyhedral import PolyhedralSurface

from tests.test_mutants_surfaces import (all_cases, float_lengths_angles, hilly_grid, jittered,
                                         random_lengths)

CASES = all_cases()
IDS = [name for name, _ in CASES]


def _metric(s):
    return s.metric() if isinstance(s, PolyhedralSurface) else s


def _check_same_surface(before, after, e):
    """The flip of ``e`` gave the same surface: Heron areas, cone angles, total area."""
    t = after.triangulation
    for f in range(t.n_faces):
        a, b, c = after.face_squared_lengths(f)
        assert 16 * after.areas[f] * after.areas[f] == heron16(a, b, c), f      # Heron
        assert after.areas[f] > 0
    assert angle_sums_from_corners(after) == angle_sums_from_corners(before)
    assert after.total_area() == before.total_area()
    assert [x for k, x in enumerate(after.squared_lengths) if k != e] == \
        [x for k, x in enumerate(before.squared_lengths) if k != e]


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_every_flip_keeps_the_surface(case):
    name, s = case
    m = _metric(s)
    t = m.triangulation
    ang = float_lengths_angles(m)
    flipped = 0
    for e in range(t.n_edges):
        h, k = t.edge_halfedges(e)
        ok = I.is_flippable(m, e)
        if k < 0 or h // 3 == k // 3:
            assert not ok
            continue
        # L2.8 with floats: the quadrilateral is strictly convex at both ends of e
        u = I.unfold(m, e)
        i, j = u.vertices[:2]
        f, g = u.faces
        assert u.faces == (h // 3, k // 3)
        assert ok == all(x > 0 for x in u.convexity())
        # the angle sums of the two triangles at i and at j, from floats: < pi iff convex
        a, b = h % 3, k % 3
        if t.reversed_gluing(h):            # k runs i -> j too
            at_i, at_j = ang[f][a] + ang[g][b], ang[f][(a + 1) % 3] + ang[g][(b + 1) % 3]
        else:                               # k runs j -> i
            at_i, at_j = ang[f][a] + ang[g][(b + 1) % 3], ang[f][(a + 1) % 3] + ang[g][b]
        for x, sgn in zip((at_i, at_j), u.convexity()):
            if abs(x - math.pi) > 1e-9:
                assert (x < math.pi) == (sgn > 0), (name, e)
        if not ok:
            with pytest.raises(NotFlippable):
                I.flip(m, e)
            continue
        r = I.flip(m, e)
        flipped += 1
        _check_same_surface(m, r, e)
        nf, ng = r.areas[f], r.areas[g]
        assert nf == u.new_area_at_j and ng == u.new_area_at_i
        assert nf + ng == m.areas[f] + m.areas[g]
        assert r.squared_lengths[e] == u.new_squared_length
        back = I.flip(r, e)                                  # flipping back: the same lengths
        assert back.squared_lengths == m.squared_lengths
        assert sorted(map(float, back.areas)) == sorted(map(float, m.areas))
        w = I.IntrinsicTriangulation(m)
        w.flip(e)
        frozen = w.surface()
        assert frozen.squared_lengths == r.squared_lengths and frozen.areas == r.areas
        assert frozen.triangulation == r.triangulation
    assert flipped


def test_unfolding_coordinates_against_floats():
    for name, s in CASES:
        m = _metric(s)
        t = m.triangulation
        for e in range(t.n_edges):
            if t.is_boundary_edge(e):
                with pytest.raises(NotFlippable):
                    I.unfold(m, e)
                continue
            u = I.unfold(m, e)
            (ix, iy), (jx, jy), (kx, ky), (lx, ly) = (tuple(float(c) for c in p) for p in u.scaled_points())
            E = float(u.sq_ij)
            s_ = math.sqrt(E)
            # scaled by |ij|: distances are |ij| times the true ones
            assert (ix, iy) == (0.0, 0.0) and math.isclose(jx, E) and jy == 0.0
            assert ky > 0 > ly
            assert math.isclose(math.hypot(kx, ky) ** 2, E * float(u.sq_ki), rel_tol=1e-9)
            assert math.isclose(math.hypot(kx - jx, ky) ** 2, E * float(u.sq_jk), rel_tol=1e-9)
            assert math.isclose(math.hypot(lx, ly) ** 2, E * float(u.sq_il), rel_tol=1e-9)
            assert math.isclose(math.hypot(lx - jx, ly) ** 2, E * float(u.sq_lj), rel_tol=1e-9)
            # the new diagonal and the new triangles' signed areas
            assert math.isclose(float(u.new_squared_length), ((kx - lx) ** 2 + (ky - ly) ** 2) / E, rel_tol=1e-9)
            at_i = ((lx * ky - ly * kx) / 2) / E               # triangle (l, k, i), ccw positive
            at_j = (((kx - jx) * (ly - jy) - (ky - jy) * (lx - jx)) / 2) / E
            assert math.isclose(float(u.new_area_at_i), at_i, rel_tol=1e-9, abs_tol=1e-12)
            assert math.isclose(float(u.new_area_at_j), at_j, rel_tol=1e-9, abs_tol=1e-12)
            si, sj = u.convexity()
            assert si == (1 if at_i > 1e-12 else -1 if at_i < -1e-12 else si)
            assert sj == (1 if at_j > 1e-12 else -1 if at_j < -1e-12 else sj)
            assert s_ > 0


def test_flip_on_a_reversed_gluing_reads_the_right_lengths():
    # a Moebius strip and a Klein bottle: edges whose two faces are glued reversed
    for m in (random_lengths(surfaces.klein_bottle(3, 3), 31), _metric(jittered(surfaces.mobius_strip(5), 4))):
        t = m.triangulation
        rev = [e for e in range(t.n_edges) if not t.is_boundary_edge(e) and t.reversed_gluing(t.edge_halfedges(e)[0])]
        assert rev
        for e in rev:
            u = I.unfold(m, e)
            h, k = u.halfedges
            i, j, kk, l_ = u.vertices
            # c = |il|^2, d = |lj|^2 read off the twin's face by position
            g = t.faces[k // 3]
            assert l_ == g[(k % 3 + 2) % 3]
            assert u.sq_il == m.squared_length(t.prev(k)) and u.sq_lj == m.squared_length(t.next(k))
            if I.is_flippable(m, e):
                _check_same_surface(m, I.flip(m, e), e)


def test_flip_errors_name_the_reason():
    s = surfaces.grid(1, 1).metric()
    with pytest.raises(NotFlippable, match="boundary"):
        I.flip(s, 0)
    # a non-convex quadrilateral: the angle sum at one end exceeds pi
    m = PolyhedralSurface.from_arrays([[0, 0], [1, 0], [Fraction(2), Fraction(1, 3)], [Fraction(2), Fraction(-1, 3)]],
                                      [[0, 1, 2], [1, 0, 3]]).metric()
    assert not I.is_flippable(m, 0)
    with pytest.raises(NotFlippable, match="more than pi"):
        I.flip(m, 0)
    # exactly pi: k, j, l collinear
    m = PolyhedralSurface.from_arrays([[0, 0], [1, 0], [Fraction(2), Fraction(1)], [Fraction(0), Fraction(-1)]],
                                      [[0, 1, 2], [1, 0, 3]]).metric()
    assert not I.is_flippable(m, 0)
    with pytest.raises(NotFlippable, match="exactly pi"):
        I.flip(m, 0)
    with pytest.raises(InputError):
        I.flip(s.triangulation, 2)
    w = I.IntrinsicTriangulation(s)
    assert not w.is_flippable(0) and w.is_flippable(2)
    with pytest.raises(NotFlippable):
        w.flip(0)


def test_intrinsic_triangulation_reads_like_a_surface():
    m = _metric(hilly_grid(3, 3, 6))
    w = I.IntrinsicTriangulation(m)
    t = m.triangulation
    for h in range(3 * t.n_faces):
        assert w.squared_length(h) == m.squared_length(h)
    for f in range(t.n_faces):
        assert w.face_squared_lengths(f) == m.face_squared_lengths(f)
        assert w.area(f) == m.areas[f]
    assert repr(w) == f"IntrinsicTriangulation(V={t.n_vertices}, E={t.n_edges}, F={t.n_faces})"
    rng = random.Random(2)
    seq, r = [], m
    for _ in range(40):
        e = rng.randrange(t.n_edges)
        if w.is_flippable(e):
            assert I.is_flippable(r, e)
            w.flip(e)
            r = I.flip(r, e)
            seq.append(e)
        else:
            assert not I.is_flippable(r, e)
    assert len(seq) > 5
    frozen = w.surface()
    assert frozen.squared_lengths == r.squared_lengths and frozen.areas == r.areas
    assert I.IntrinsicTriangulation(w).surface().squared_lengths == frozen.squared_lengths
    assert I.flip(w, seq[-1]).squared_lengths == I.flip(frozen, seq[-1]).squared_lengths
    assert angle_sums_from_corners(frozen) == angle_sums_from_corners(m)


def test_cot_sum_against_floats():
    for name, s in CASES:
        m = _metric(s)
        ang = float_lengths_angles(m)
        t = m.triangulation
        for e in range(t.n_edges):
            expected = sum(1 / math.tan(ang[h // 3][(h % 3 + 2) % 3]) for h in t.edge_halfedges(e) if h >= 0)
            assert math.isclose(float(I.cot_sum(m, e)), expected, abs_tol=1e-9)


def test_regular_tetrahedron_flip_X2_5():
    s = I.regular_tetrahedron_flip()
    # hand-derived: the new diagonal of two unit equilateral triangles is sqrt(3)
    assert s.squared_lengths[0] == 3
    assert sorted(s.squared_lengths) == [1, 1, 1, 1, 1, 3]
    assert angle_sums_from_corners(s) == angle_sums_from_corners(
        PiecewiseFlatSurface(Triangulation.from_faces([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]]), [1] * 6))
    assert all(16 * a * a == 3 for a in s.areas)


def test_metric_of_other_inputs():
    s = jittered(surfaces.octahedron(), 2, Fraction(1, 4))
    assert I.surface_metric(s) is s.metric()
    w = I.IntrinsicTriangulation(s)
    assert I.surface_metric(w) is w
    with pytest.raises(InputError):
        I.surface_metric([1, 2, 3])
