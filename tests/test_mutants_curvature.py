"""Mutants of reference/curvature.py killed on generic surfaces (docs/mutation.md).

Angle sums, defects and turning angles against float geometry from the positions (or the
law of cosines on the lengths), Gauss-Bonnet (T2.6 / R2.4) on surfaces with cone points
and boundary, Lemma 2.4's star predicates against a float convex-hull computation
(scipy) and against the sign of K, dihedral angles and mean curvature against float
normals, the Cayley rotation against numpy, and push_vertex_in against a float reflection.
"""

from __future__ import annotations

import math
import random
from fractions import Fraction

import numpy as np
import pytest
from scipy.spatial import ConvexHull

from ddg_oracle.reference import curvature as K
from ddg_oracle.reference import surfaces
from ddg_oracle.reference.errors import InputError
from ddg_oracle.reference.exact import Angle, pi
from ddg_oracle.reference.polyhedral import PolyhedralSurface

from tests.test_mutants_surfaces import (all_cases, float_corner_angles, float_lengths_angles,
                                         jittered, polyhedral_cases)

CASES = all_cases()
IDS = [name for name, _ in CASES]


def _metric(s):
    return s.metric() if isinstance(s, PolyhedralSurface) else s


def _float_sums(s):
    m = _metric(s)
    angles = float_corner_angles(s) if isinstance(s, PolyhedralSurface) else float_lengths_angles(m)
    sums = [0.0] * m.triangulation.n_vertices
    for face, a in zip(m.triangulation.faces, angles):
        for v, x in zip(face, a):
            sums[v] += x
    return angles, sums


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_angles_defects_and_turning_angles_against_floats(case):
    name, s = case
    m = _metric(s)
    t = m.triangulation
    angles, sums = _float_sums(s)
    for exact, flt in zip(K.corner_angles_from_cotangents(s), angles):
        assert all(math.isclose(float(a), b, abs_tol=1e-9) for a, b in zip(exact, flt))
    assert K.corner_angles(s) == K.corner_angles_from_cotangents(s)
    by_corners = K.angle_sums_from_corners(s)
    assert K.angle_sums(s) == by_corners
    assert all(math.isclose(float(a), b, abs_tol=1e-9) for a, b in zip(by_corners, sums))
    boundary = {v for v in range(t.n_vertices) if t.is_boundary_vertex(v)}
    defects, turning = K.angle_defects(s), K.turning_angles(s)
    assert set(defects) == set(range(t.n_vertices)) - boundary
    assert set(turning) == boundary
    for v, k in defects.items():
        assert math.isclose(float(k), 2 * math.pi - sums[v], abs_tol=1e-9)
    for v, k in turning.items():
        assert math.isclose(float(k), math.pi - sums[v], abs_tol=1e-9)
    # T2.6 / R2.4: the total is the sum of both, and 2 pi chi, exactly
    total = K.total_curvature(s)
    chi = t.euler_characteristic()
    assert total == sum(defects.values(), Angle()) + sum(turning.values(), Angle())
    assert total == 2 * chi * pi
    assert K.gauss_bonnet_holds(s) and K.gauss_bonnet_holds_by_faces(s)
    for v in range(t.n_vertices):
        if v in boundary:
            with pytest.raises(InputError):
                K.vertex_type(s, v)
            continue
        k = 2 * math.pi - sums[v]
        expected = "elliptic" if k > 1e-9 else "hyperbolic" if k < -1e-9 else "flat"
        if abs(k) > 1e-9 or expected == "flat":
            assert K.vertex_type(s, v) == expected, (name, v)


def test_vertex_types_of_all_three_kinds_and_flat_interior_vertices():
    # a planar disk with its centre off-centre: the centre is flat (K = 0 exactly)
    s = jittered(surfaces.disk(7), 3, Fraction(1, 5), dims=(0, 1))
    assert K.vertex_type(s, 0) == "flat"
    assert K.angle_defects(s)[0] == 0
    # a cone point up (elliptic) and a saddle (hyperbolic)
    up = s.with_positions([(x, y, Fraction(1, 2) if i == 0 else z) for i, (x, y, z) in enumerate(s.positions)])
    assert K.vertex_type(up, 0) == "elliptic"
    saddle = s.with_positions([(x, y, Fraction((-1) ** i, 2) if i else z)
                               for i, (x, y, z) in enumerate(s.positions)])
    kind = K.vertex_type(saddle, 0)
    _, sums = _float_sums(saddle)
    assert kind == ("hyperbolic" if sums[0] > 2 * math.pi else "elliptic")


def test_gauss_bonnet_by_faces_sums_the_faces():
    # the two routes of T2.6 and the total itself on a surface whose angle sums all differ
    s = jittered(surfaces.torus(4, 3), 8)
    assert K.gauss_bonnet_holds_by_faces(s.metric())
    assert K.total_curvature(s.metric()) == 0


# --- Lemma 2.4: stars ------------------------------------------------------------------------


def _star_points(s, v):
    t = s.triangulation
    p = np.array([float(x) for x in s.positions[v]])
    q = np.array([[float(x) for x in s.positions[w]] for w in t.neighbours(v)])
    return p, q


def _float_saddle(p, q):
    """p strictly inside the convex hull of its neighbours (scipy)."""
    try:
        hull = ConvexHull(q)
    except Exception:            # flat neighbours: no interior at all
        return False
    return bool(np.all(hull.equations[:, :3] @ p + hull.equations[:, 3] < -1e-12))


def _float_planar(p, q):
    d = q - p
    n = np.cross(d[0], d[1])
    return bool(np.all(np.abs(d @ n) < 1e-12))


def _float_convex(p, q):
    """Every face plane of the star supports it, and the normals span R^3 (the star is a
    pointed convex cone around p); the fan winds once for these generic stars."""
    d = q - p
    normals = np.cross(d, np.roll(d, -1, axis=0))
    dots = normals @ d.T
    same_side = bool(np.all(dots <= 1e-12) or np.all(dots >= -1e-12))
    return same_side and np.linalg.matrix_rank(normals, tol=1e-9) == 3


def _fan(n, heights, apex=(0, 0, 0), radius=1, seed=0):
    """A star: apex 0 and n neighbours at the given heights around it (jittered circle)."""
    rng = random.Random(seed)
    pts = [tuple(Fraction(x) for x in apex)]
    for k in range(n):
        c, sn = surfaces._circle_point(k, n)
        r = Fraction(radius) + Fraction(rng.randint(-3, 3), 17)
        pts.append((r * c, r * sn, Fraction(heights[k])))
    faces = [(0, 1 + k, 1 + (k + 1) % n) for k in range(n)]
    # close it into a sphere-like surface with a bottom vertex so vertex 0 is interior
    pts.append((Fraction(0), Fraction(0), Fraction(-5)))
    faces += [(n + 1, 1 + (k + 1) % n, 1 + k) for k in range(n)]
    return PolyhedralSurface.from_arrays(pts, faces)


STARS = [
    ("pyramid", _fan(6, [0] * 6, apex=(Fraction(1, 7), 0, 1))),
    ("flat", _fan(5, [0] * 5, apex=(Fraction(1, 9), Fraction(-1, 11), 0))),
    ("pit", _fan(5, [0] * 5, apex=(0, 0, Fraction(-1, 3)))),
    ("saddle", _fan(6, [1, -1, 1, -1, 1, -1])),
    ("monkey", _fan(6, [Fraction(1, 2), 1, Fraction(-1, 3), -1, 1, Fraction(-3, 4)], seed=3)),
    ("crease", _fan(6, [1, 1, 1, 0, 0, 0], seed=4)),
    ("tilted", _fan(7, [Fraction(k, 7) for k in range(7)], apex=(0, 0, Fraction(1, 5)), seed=5)),
    ("pinch", _fan(6, [1, 1, -1, 1, 1, 1], apex=(0, 0, Fraction(1, 2)), seed=6)),
]


@pytest.mark.parametrize("star", STARS, ids=[n for n, _ in STARS])
def test_star_predicates_against_floats_and_lemma_2_4(star):
    name, s = star
    p, q = _star_points(s, 0)
    convex, planar, saddle = K.is_convex_star(s, 0), K.is_planar_star(s, 0), K.is_saddle_star(s, 0)
    assert planar == _float_planar(p, q), name
    assert saddle == _float_saddle(p, q), name
    assert convex == _float_convex(p, q), name
    assert convex + planar + saddle <= 1
    kind = K.vertex_type(s, 0)
    if convex:
        assert kind == "elliptic"
    if planar:
        assert kind == "flat"
    if saddle:
        assert kind == "hyperbolic"


def test_each_star_kind_occurs():
    kinds = {(K.is_convex_star(s, 0), K.is_planar_star(s, 0), K.is_saddle_star(s, 0)) for _, s in STARS}
    assert {(True, False, False), (False, True, False), (False, False, True),
            (False, False, False)} <= kinds


@pytest.mark.parametrize("name", ["icosahedron", "torus", "octahedron"])
def test_star_predicates_on_every_vertex_of_a_jittered_closed_surface(name):
    s = dict(polyhedral_cases())[name]
    for v in range(s.triangulation.n_vertices):
        p, q = _star_points(s, v)
        assert K.is_saddle_star(s, v) == _float_saddle(p, q)
        assert K.is_convex_star(s, v) == _float_convex(p, q)
        assert not K.is_planar_star(s, v)


def test_star_predicates_reject_boundary_vertices_and_other_inputs():
    s = jittered(surfaces.disk(6), 1)
    for f in (K.is_convex_star, K.is_planar_star, K.is_saddle_star):
        with pytest.raises(InputError):
            f(s, 1)
        with pytest.raises(InputError):
            f(s.metric(), 0)
        with pytest.raises(InputError):
            f(PolyhedralSurface.from_arrays([[0, 0], [1, 0], [0, 1]], [[0, 1, 2]]), 0)


def _fan_directions(step_degrees, n, scale=1):
    out = []
    for k in range(n):
        a = math.radians(step_degrees * k)
        out.append((Fraction(math.cos(a)).limit_denominator(1000) * scale,
                    Fraction(math.sin(a)).limit_denominator(1000) * scale, Fraction(scale)))
    return out


def test_turns_counts_windings():
    axis = (Fraction(0), Fraction(0), Fraction(1))
    for scale in (1, Fraction(1, 10), Fraction(1, 1000)):
        # 9 steps of 80 degrees: twice round, d_0's direction strictly inside a sector once
        assert K._turns(_fan_directions(80, 9, scale), axis) == 2
        # 10 steps of 72 degrees: twice round, d_0's direction met again at d_5
        assert K._turns(_fan_directions(72, 10, scale), axis) == 2
        assert K._turns(_fan_directions(72, 5, scale), axis) == 1
        assert K._turns(_fan_directions(50, 7, scale), axis) == 1
        assert K._turns(_fan_directions(100, 11, scale), axis) == 3
        assert K._turns(_fan_directions(80, 9, scale), tuple(x * scale for x in axis)) == 2


def test_star_predicates_do_not_depend_on_the_scale():
    # Lemma 2.4's predicates are invariant under scaling about the vertex: tiny stars
    for name, s in STARS:
        k = Fraction(1, 1000)
        tiny = s.with_positions([tuple(k * x for x in p) for p in s.positions])
        assert (K.is_convex_star(tiny, 0), K.is_planar_star(tiny, 0), K.is_saddle_star(tiny, 0)) == \
            (K.is_convex_star(s, 0), K.is_planar_star(s, 0), K.is_saddle_star(s, 0)), name


def test_rank_of_vectors():
    assert K._rank([(1, 0, 0), (2, 0, 0), (0, 0, 0)]) == 1
    assert K._rank([(1, 2, 3), (2, 4, 6), (0, 1, 0)]) == 2
    assert K._rank([(0, 1, 0), (0, 0, 1), (1, 0, 0), (1, 1, 1)]) == 3
    assert K._rank([(0, 0, 1), (0, 0, 2)]) == 1
    assert K._rank([]) == 0
    rng = random.Random(9)
    for _ in range(50):
        rows = [tuple(Fraction(rng.randint(-3, 3)) for _ in range(3)) for _ in range(rng.randint(1, 4))]
        assert K._rank(rows) == np.linalg.matrix_rank(np.array(rows, dtype=float))


# --- dihedral angles, mean curvature, Steiner (D2.3, T2.7) -----------------------------------


def _float_dihedral(s, e):
    t = s.triangulation
    h, h2 = t.edge_halfedges(e)
    f, g = h // 3, h2 // 3
    c = h % 3
    face = t.faces[f]
    i, j, k = face[c], face[(c + 1) % 3], face[(c + 2) % 3]
    l_ = t.faces[g][(h2 % 3 + 2) % 3]
    x = [np.array([float(v) for v in p]) for p in s.positions]
    nf = np.cross(x[j] - x[i], x[k] - x[i])
    ng = np.cross(x[i] - x[j], x[l_] - x[j])
    ang = math.acos(max(-1.0, min(1.0, nf @ ng / (np.linalg.norm(nf) * np.linalg.norm(ng)))))
    return ang if nf @ (x[l_] - x[i]) < 0 else -ang, float(np.linalg.norm(x[j] - x[i]))


@pytest.mark.parametrize("name", ["icosahedron", "torus", "octahedron", "disk", "hilly grid",
                                  "per-face denominators", "annulus"])
def test_dihedral_angles_and_mean_curvature_against_floats(name):
    s = dict(polyhedral_cases())[name]
    t = s.triangulation
    theta = K.dihedral_angles(s)
    H = K.mean_curvature(s)
    interior = [e for e in range(t.n_edges) if not t.is_boundary_edge(e)]
    assert sorted(theta) == interior == sorted(H)
    total = 0.0
    for e in interior:
        a, length = _float_dihedral(s, e)
        assert math.isclose(float(theta[e]), a, abs_tol=1e-9), e
        assert math.isclose(float(H[e]), a * length / 2, abs_tol=1e-9), e
        total += a * length / 2
    assert math.isclose(float(K.total_mean_curvature(s)), total, abs_tol=1e-9)
    if name in ("torus", "hilly grid"):
        assert {float(x) < 0 for x in theta.values()} == {True, False}   # concave edges too


def test_dihedral_angles_flat_fold_and_orientation_errors():
    # two coplanar faces: theta = 0; folded flat onto each other: error
    flat = PolyhedralSurface.from_arrays([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], [[0, 1, 2], [2, 1, 3]])
    assert K.dihedral_angles(flat) == {1: 0}
    with pytest.raises(InputError):                  # the 4th vertex folded back over
        K.dihedral_angles(PolyhedralSurface.from_arrays(
            [[0, 0, 0], [1, 0, 0], [0, 1, 0], [Fraction(1, 3), Fraction(1, 2), 0]], [[0, 1, 2], [2, 1, 3]]))
    with pytest.raises(InputError):
        K.dihedral_angles(jittered(surfaces.mobius_strip(5), 4))


@pytest.mark.parametrize("name", ["icosahedron", "torus", "octahedron", "per-face denominators"])
def test_steiner_coefficients(name):
    s = dict(polyhedral_cases())[name]
    A, H2, KS = K.steiner_coefficients(s)
    m = s.metric()
    assert math.isclose(float(A), sum(float(a) for a in m.areas), rel_tol=1e-12)
    assert math.isclose(float(H2), 2 * float(K.total_mean_curvature(s)), rel_tol=1e-12)
    assert KS == 2 * s.triangulation.euler_characteristic() * pi
    with pytest.raises(InputError):
        K.steiner_coefficients(jittered(surfaces.disk(5), 1))


# --- isometries (T2.5, X2.3) -----------------------------------------------------------------


def test_cayley_rotation_against_numpy():
    rng = random.Random(10)
    for _ in range(20):
        w = [Fraction(rng.randint(-9, 9), rng.randint(1, 5)) for _ in range(3)]
        R = np.array(K.cayley_rotation(*w), dtype=float)
        S = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]], dtype=float)
        expected = np.linalg.solve(np.eye(3) - S, np.eye(3) + S)
        assert np.allclose(R, expected, atol=1e-12)
        assert math.isclose(np.linalg.det(R), 1.0, abs_tol=1e-12)


def test_rigid_motion_moves_points_and_keeps_the_metric():
    s = jittered(surfaces.icosahedron(), 11)
    R = K.cayley_rotation(1, Fraction(-2, 3), Fraction(1, 2))
    tr = (Fraction(1, 3), 2, Fraction(-5, 7))
    moved = K.rigid_motion(s, R, tr)
    Rf = np.array(R, dtype=float)
    for p, q in zip(s.positions, moved.positions):
        assert np.allclose(Rf @ np.array(p, dtype=float) + np.array(tr, dtype=float),
                           np.array(q, dtype=float), atol=1e-12)
    assert moved.metric().squared_lengths == s.metric().squared_lengths
    assert K.angle_defects(moved) == K.angle_defects(s)


def test_push_vertex_in_reflects_in_the_plane_of_the_neighbours():
    # a star whose neighbours are coplanar (a tilted plane) but not evenly spaced
    s = _fan(6, [0] * 6, apex=(Fraction(1, 7), Fraction(-1, 5), Fraction(2, 3)), seed=12)
    tilt = [(x, y, z + (x + 2 * y) / 3 if i != 7 else z) for i, (x, y, z) in enumerate(s.positions)]
    s = s.with_positions(tilt)
    pushed = K.push_vertex_in(s, 0)
    x = np.array(s.positions[0], dtype=float)
    q = [np.array(s.positions[w], dtype=float) for w in s.triangulation.neighbours(0)]
    n = np.cross(q[1] - q[0], q[2] - q[0])
    n /= np.linalg.norm(n)
    expected = x - 2 * ((x - q[0]) @ n) * n
    assert np.allclose(np.array(pushed.positions[0], dtype=float), expected, atol=1e-12)
    assert pushed.positions[1:] == s.positions[1:]
    assert pushed.metric().squared_lengths == s.metric().squared_lengths
    with pytest.raises(InputError):
        K.push_vertex_in(_fan(5, [0, 0, 1, 0, 0]), 0)         # neighbours not coplanar
