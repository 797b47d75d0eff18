"""Mutants of reference/laplacian.py killed on generic surfaces (docs/mutation.md).

The cotan weights against float cotangents of the float corner angles; the matrix against
the graph Laplacian of the weighted edges (D3.1) and against floats; T3.6 (``E = 1/2 f^T L
f`` equals the energy of the piecewise linear interpolant, from gradients) on surfaces with
unequal faces, boundary, non-orientable ones and intrinsic ones (the Gram route); the
gradient against a float least-squares solve; both lumped mass matrices against float
implementations written here (Meyer et al.'s mixed areas with the obtuse rule); E3.12's
sign and (3.12)'s sine formula against the weights.
"""

from __future__ import annotations

import math
import random
from fractions import Fraction

import numpy as np
import pytest

from ddg_oracle.reference import laplacian as L
from ddg_oracle.reference import surfaces
from ddg_oracle.reference.errors import BadShape, InputError
from ddg_oracle.reference.exact import sign
from ddg_oracle.reference.polyhedral import PolyhedralSurface
from ddg_oracle.reference.sparse import SparseMatrix

from tests.test_mutants_surfaces import (all_cases, flipped, float_corner_angles,
                                         float_lengths_angles, hilly_grid, jittered,
                                         polyhedral_cases)

CASES = all_cases()
IDS = [name for name, _ in CASES]


def _metric(s):
    return s.metric() if isinstance(s, PolyhedralSurface) else s


def _angles(s):
    m = _metric(s)
    return float_corner_angles(s) if isinstance(s, PolyhedralSurface) else float_lengths_angles(m)


def _float_weights(s):
    """(3.3) from float angles: 1/2 (cot alpha + cot beta), 1/2 cot alpha on the boundary."""
    m = _metric(s)
    t = m.triangulation
    ang = _angles(s)
    w = [0.0] * t.n_edges
    for h in range(3 * t.n_faces):
        f, c = divmod(h, 3)
        w[t.edge_of(h)] += 0.5 / math.tan(ang[f][(c + 2) % 3])    # corner opposite h
    return w


def _values(n, seed):
    rng = random.Random(seed)
    return [Fraction(rng.randint(-20, 20), rng.randint(1, 6)) for _ in range(n)]


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_weights_and_matrix_against_floats_and_the_graph_laplacian(case):
    name, s = case
    m = _metric(s)
    t = m.triangulation
    w = L.cotan_weights_from_corners(s)
    fw = _float_weights(s)
    assert sorted(w) == list(range(t.n_edges))
    for e, x in w.items():
        assert math.isclose(float(x), fw[e], abs_tol=1e-9), e
    assert L.cotan_weights(s) == w
    edges = L.cotan_weighted_edges(s)
    assert [(i, j) for i, j, _ in edges] == [t.edge_vertices(e) for e in range(t.n_edges)]
    G = L.graph_laplacian(t.n_vertices, edges)
    M = L.cotan_laplacian_from_weights(s)
    assert M == G == L.cotan_laplacian(s)
    dense = np.array(M.to_dense_floats())
    expected = np.zeros((t.n_vertices, t.n_vertices))
    for e in range(t.n_edges):
        i, j = t.edge_vertices(e)
        if i != j:
            expected[i, j] -= fw[e]
            expected[j, i] -= fw[e]
            expected[i, i] += fw[e]
            expected[j, j] += fw[e]
    assert np.allclose(dense, expected, atol=1e-9)


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_T3_6_energy_of_the_interpolant_equals_the_cotan_form(case):
    name, s = case
    t = _metric(s).triangulation
    n = t.n_vertices
    f, g = _values(n, 1), _values(n, 2)
    M = L.cotan_laplacian(s)
    assert L.dirichlet_energy_pl(s, f) == M.quadratic_form(f) / 2 == L.dirichlet_energy(M, f)
    assert L.dirichlet_energy(L.cotan_weighted_edges(s), f) == M.quadratic_form(f) / 2
    ip = L.dirichlet_inner_product_pl(s, f, g)
    assert ip == sum(a * b for a, b in zip(f, M.matvec(g)))
    assert ip == L.dirichlet_inner_product_pl(s, g, f)
    # the intrinsic route (Gram matrix of the lengths) gives the same as the positions
    if isinstance(s, PolyhedralSurface):
        assert L.dirichlet_inner_product_pl(s.metric(), f, g) == ip
    with pytest.raises(BadShape):
        L.dirichlet_inner_product_pl(s, f[:-1], g)
    with pytest.raises(BadShape):
        L.dirichlet_inner_product_pl(s, f, g + [0])


def test_T3_6_after_intrinsic_flips():
    # planar positions: rational areas, so the flipped squared lengths stay rational and
    # the Gram route of dirichlet_energy_pl applies (it takes square roots of rationals only)
    m = flipped(dict(polyhedral_cases())["planar grid"].metric(), 5, flips=4)
    f = _values(m.triangulation.n_vertices, 3)
    M = L.cotan_laplacian(m)
    assert M == L.cotan_laplacian_from_weights(m)
    assert L.dirichlet_energy_pl(m, f) == M.quadratic_form(f) / 2
    # irrational squared lengths (a surface from R^3 after flips): the mixed route
    r = flipped(jittered(surfaces.icosahedron(), 1).metric(), 5, flips=4)
    M = L.cotan_laplacian(r)
    assert M == L.cotan_laplacian_from_weights(r)
    fw = _float_weights(r)
    t = r.triangulation
    for e in range(t.n_edges):
        i, j = t.edge_vertices(e)
        assert math.isclose(float(L.cotan_weights(r)[e]), fw[e], abs_tol=1e-9)


@pytest.mark.parametrize("name", ["icosahedron", "hilly grid", "planar grid", "mobius"])
def test_gradient_against_floats(name):
    s = dict(polyhedral_cases())[name]
    f = _values(s.triangulation.n_vertices, 4)
    for face, (a, b, c) in enumerate(s.triangulation.faces):
        g = np.array([float(x) for x in L.gradient_pl(s, f, face)])
        P = [np.array([float(x) for x in s.positions[v]]) for v in (a, b, c)]
        u, v = P[1] - P[0], P[2] - P[0]
        A = np.array([u, v])
        # the minimum-norm solution of <g, u> = f1 - f0, <g, v> = f2 - f0 lies in the plane
        expected = np.linalg.lstsq(A, np.array([float(f[b] - f[a]), float(f[c] - f[a])]), rcond=None)[0]
        assert np.allclose(g, expected, atol=1e-9)
    with pytest.raises(InputError):
        L.gradient_pl(s.metric(), f, 0)
    flat = PolyhedralSurface.from_arrays([[0, 0, 0], [1, 1, 1], [2, 2, 2]], [[0, 1, 2]])
    with pytest.raises(InputError):
        L.gradient_pl(flat, [0, 1, 2], 0)


def test_graph_laplacian_and_energy_of_a_weighted_multigraph():
    edges = [(0, 1, 2), (1, 2, Fraction(1, 3)), (0, 1, Fraction(1, 2)), (2, 2, 7), (3, 0, -1)]
    G = L.graph_laplacian(4, edges)
    A = np.zeros((4, 4))
    for i, j, w in edges:
        if i != j:
            A[i, j] -= float(w)
            A[j, i] -= float(w)
            A[i, i] += float(w)
            A[j, j] += float(w)
    assert np.allclose(np.array(G.to_dense_floats()), A)
    f = [1, Fraction(-2, 3), 5, 2]
    expected = sum(Fraction(w) * (f[i] - f[j]) ** 2 for i, j, w in edges) / 2
    assert L.dirichlet_energy(edges, f) == expected == L.dirichlet_energy(G, f)
    for bad in ([(0, 4, 1)], [(-1, 0, 1)], [(4, 0, 1)]):
        with pytest.raises(InputError):
            L.graph_laplacian(4, bad)


# --- mass matrices ------------------------------------------------------------------------------


def _float_mixed_areas(s):
    """Meyer, Desbrun, Schroeder, Barr: Voronoi parts on non-obtuse faces, area/2 at the
    obtuse corner and area/4 at the others."""
    m = _metric(s)
    t = m.triangulation
    ang = _angles(s)
    out = [0.0] * t.n_vertices
    for f, face in enumerate(t.faces):
        l0, l1, l2 = (float(x) for x in m.face_squared_lengths(f))     # |01|^2, |12|^2, |20|^2
        area = float(m.areas[f])
        a = ang[f]
        obtuse = [c for c in range(3) if a[c] > math.pi / 2 + 1e-12]
        for c in range(3):
            if obtuse:
                out[face[c]] += area / 2 if c == obtuse[0] else area / 4
            else:
                # sides at corner c: to c+1 (opposite corner c+2) and to c+2 (opposite c+1)
                to_next = (l0, l1, l2)[c]
                to_prev = (l2, l0, l1)[c]
                out[face[c]] += (to_next / math.tan(a[(c + 2) % 3]) + to_prev / math.tan(a[(c + 1) % 3])) / 8
    return out


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_lumped_masses_against_floats(case):
    name, s = case
    m = _metric(s)
    t = m.triangulation
    total = sum(float(a) for a in m.areas)
    bary = L.vertex_areas_barycentric(s)
    fbary = [0.0] * t.n_vertices
    for f, face in enumerate(t.faces):
        for v in face:
            fbary[v] += float(m.areas[f]) / 3
    assert np.allclose([float(x) for x in bary], fbary, atol=1e-12)
    vor = L.vertex_areas_voronoi(s)
    assert np.allclose([float(x) for x in vor], _float_mixed_areas(s), atol=1e-9)
    assert math.isclose(sum(float(x) for x in vor), total, rel_tol=1e-12)
    assert L.vertex_areas_floats(s) == [float(x) for x in vor]
    assert L.vertex_areas_floats(s, "barycentric") == [float(x) for x in bary]
    with pytest.raises(InputError):
        L.vertex_areas_floats(s, "mixed")


def test_lumped_masses_with_irrational_lengths_take_the_exact_route():
    m = flipped(jittered(surfaces.octahedron(), 2, Fraction(1, 4)).metric(), 6, flips=3)
    assert L.vertex_areas_floats(m) == [float(x) for x in L.vertex_areas_voronoi(m)]
    assert L.vertex_areas_floats(m, "barycentric") == [float(x) for x in L.vertex_areas_barycentric(m)]


def test_right_triangle_takes_the_voronoi_rule():
    # a 3-4-5 triangle: circumcentre at the hypotenuse's midpoint; the right-angle vertex
    # gets half the area (both rules agree), the acute ones 25/8 * cot parts
    s = PolyhedralSurface.from_arrays([[0, 0, 0], [4, 0, 0], [0, 3, 0]], [[0, 1, 2]])
    a = L.vertex_areas_voronoi(s)
    # hand-derived: vertex (4,0): |01|^2 cot(corner 2) / 8 = 16 * (3/4) / 8 = 3/2; vertex
    # (0,3): |20|^2 cot(corner 1) / 8 = 9 * (4/3) / 8 = 3/2; vertex 0 gets the other 3
    assert a == [3, Fraction(3, 2), Fraction(3, 2)]


# --- E3.12 and (3.12) ---------------------------------------------------------------------------


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_weight_signs_by_angles_and_sines(case):
    name, s = case
    m = _metric(s)
    t = m.triangulation
    w = L.cotan_weights(s)
    ang = _angles(s)
    signs = L.weight_signs_by_angles(s)
    for e in range(t.n_edges):
        expected = sign(w[e])
        assert L.weight_sign_by_angles(s, e) == expected == signs[e], e
        assert L.cotan_weight_by_sines(s, e) == w[e]
        total = sum(ang[h // 3][(h % 3 + 2) % 3] for h in t.edge_halfedges(e) if h >= 0)
        assert math.isclose(float(L.opposite_angle_sum(s, e)), total, abs_tol=1e-9)


def test_negative_and_zero_weights_occur():
    s = hilly_grid(3, 3, 6)
    signs = set(L.weight_signs_by_angles(s))
    assert signs >= {-1, 1}
    grid = surfaces.grid(2, 1)
    assert 0 in L.weight_signs_by_angles(grid)           # the diagonals: right angles
    assert L.metric_of_surface is L.as_metric
    assert isinstance(L.cotan_laplacian(grid), SparseMatrix)


def test_weight_of_an_edge_whose_second_halfedge_is_halfedge_0():
    # after a flip the edge's halfedges are (3f, 3g): with g = 0 its second halfedge is 0
    from ddg_oracle.reference.intrinsic import flip, is_flippable
    r = _metric(hilly_grid(2, 2, 50))
    for _ in range(6):
        t = r.triangulation
        # an edge whose first halfedge lies in another face and whose twin lies in face 0
        e = next((e for e in range(t.n_edges) if t.edge_halfedges(e)[1] >= 0
                  and t.edge_halfedges(e)[1] // 3 == 0 and t.edge_halfedges(e)[0] // 3 != 0
                  and is_flippable(r, e)), None)
        if e is not None:
            r = flip(r, e)
            break
        r = flip(r, next(t.edge_of(h) for h in range(3) if is_flippable(r, t.edge_of(h))))
    assert r.triangulation.edge_halfedges(e)[1] == 0
    w = L.cotan_weights_from_corners(r)
    fw = _float_weights(r)
    assert all(math.isclose(float(w[x]), fw[x], abs_tol=1e-9) for x in w)
    assert w == L.cotan_weights(r)
