"""Chapter 3 reference: graph and cotan Laplacians, Dirichlet energy, area (D3.1, T3.6, R3.3,
L3.7, L3.8, T3.9, E3.12, mass matrices), the 1,000-face timing, and the chapter-3 properties
(passing on the exact reference, catching planted bugs with small counterexamples)."""

import random
from fractions import Fraction

import numpy as np
import pytest
import scipy.sparse as sp
from hypothesis import given, strategies as st

from ddg_oracle.oracles.exact_reference import ReferenceImplementation
from ddg_oracle.properties.bounds import _conditioning
from ddg_oracle.properties.harness import ErrorLedger, Exact, recording
from ddg_oracle.properties.strategies import (acute_meshes, any_meshes, closed_meshes, jittered_surfaces,
                                             obtuse_meshes, planar_meshes, weighted_graphs,
                                             with_functions)
from ddg_oracle.properties.profiles import profile
from tests.property_checks import assert_caught, assert_passes_well_inside
from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.runner import PASSED, run_property
from ddg_oracle.reference import surfaces
from ddg_oracle.reference.areas import (area_as_dirichlet_energy, area_from_cotangents, area_gradient,
                            area_gradient_cotan, area_gradient_cross, area_gradient_direct,
                            area_length_derivatives, heron_partial_derivatives,
                            laplacian_of_positions, triangle_area_heron, triangle_cotangents)
from ddg_oracle.reference.combinatorics import Triangulation
from ddg_oracle.reference.errors import InputError
from ddg_oracle.reference.exact import Surd, corner_angle, exact_sum, pi, sqrt
from ddg_oracle.reference.laplacian import (cotan_laplacian, cotan_weight_by_sines, cotan_weighted_edges,
                                 cotan_weights, dirichlet_energy, dirichlet_energy_pl,
                                 dirichlet_inner_product_pl, dirichlet_energy_gradient_pl,
                                 graph_laplacian, gradient_pl,
                                 opposite_angle_sum, vertex_areas_barycentric,
                                 vertex_areas_voronoi, weight_sign_by_angles,
                                 weight_signs_by_angles)
from ddg_oracle.reference.dirichlet import kernel_dimension
from ddg_oracle.reference.metric import PiecewiseFlatSurface
from ddg_oracle.reference.polyhedral import PolyhedralSurface
from ddg_oracle.reference.sparse import SparseMatrix
from benchmarks.meshes import float_icosphere

CHAPTER3 = ["D3.1", "T3.1 / R3.2", "T3.2", "C3.3", "C3.4 / T3.5", "T3.6", "R3.3", "L3.7",
            "L3.8", "T3.9", "A3.6", "P3.10", "E3.12"]


# --- a tiny adapter: float views of the exact reference, and planted bugs ----------------------


class ExactViews(ReferenceImplementation):
    """The exact reference behind the protocol: every float correctly rounded."""

    name = "exact reference (float views)"


def _planted(V, F, corner_of, boundary_factor=0.5, sign=1.0):
    """A cotan Laplacian assembled per edge from the exact corner cotangents, with a bug."""
    s = PolyhedralSurface.from_arrays(V, F)
    m, t = s.metric(), s.triangulation
    rows, cols, vals = [], [], []
    for e in range(t.n_edges):
        i, j = t.edge_vertices(e)
        hs = [h for h in t.edge_halfedges(e) if h >= 0]
        w = sum(float(m.corner_cot(h // 3, corner_of(h))) for h in hs)
        w *= 0.5 if len(hs) == 2 else boundary_factor
        for a, b, x in ((i, j, -w), (j, i, -w), (i, i, w), (j, j, w)):
            rows.append(a)
            cols.append(b)
            vals.append(sign * x)
    n = t.n_vertices
    return sp.csr_matrix((vals, (rows, cols)), shape=(n, n))


def _opposite(h):
    return (h + 2) % 3          # halfedge 3f + k is opposite corner (k + 2) % 3


class SignError(ExactViews):
    """Returns libigl's sign convention (negative semidefinite) by mistake."""
    name = "sign error"

    def cotan_laplacian(self, V, F):
        return _planted(V, F, _opposite, sign=-1.0)


class BoundaryWithoutHalf(ExactViews):
    """Boundary edges get cot alpha instead of 1/2 cot alpha."""
    name = "boundary edge without 1/2"

    def cotan_laplacian(self, V, F):
        return _planted(V, F, _opposite, boundary_factor=1.0)


class CotOfWrongCorner(ExactViews):
    """Each halfedge takes the cotangent at its tail instead of the opposite corner."""
    name = "cot of the wrong corner"

    def cotan_laplacian(self, V, F):
        return _planted(V, F, lambda h: h % 3)


# --- D3.1: graph Laplacian and Dirichlet energy ------------------------------------------------


@given(weighted_graphs(positive=False, connected=False),
       st.lists(st.tuples(st.integers(0, 6), st.integers(-3, 3)), max_size=3))
def test_D3_1_graph_laplacian_is_the_edge_sum(g, loops):
    edges = list(g.edges) + [(i % g.n, i % g.n, Fraction(w)) for i, w in loops]   # loops
    L = graph_laplacian(g.n, edges)
    f = list(g.values)
    direct = [sum((w * (f[i] - f[j]) for i, j, w in edges if i == v), Fraction(0))
              + sum((w * (f[j] - f[i]) for i, j, w in edges if j == v), Fraction(0))
              for v in range(g.n)]
    assert L.matvec(f) == direct                       # (Lap f)(i) = sum_j nu(ij) (f(i) - f(j))
    assert L.is_symmetric()
    assert L.matvec([1] * g.n) == [0] * g.n            # zero row sums
    assert dirichlet_energy(L, f) == dirichlet_energy(edges, f)
    assert 2 * dirichlet_energy(L, f) == sum((a * b for a, b in zip(f, L.matvec(f))), Fraction(0))


def test_D3_1_example_3_1_combinatorial_laplacians_of_Z_and_Z2():
    path = graph_laplacian(5, [(i, i + 1, 1) for i in range(4)])
    f = [n * n for n in range(5)]
    assert path.matvec(f)[1:4] == [-2, -2, -2]          # 2 f(n) - f(n+1) - f(n-1) = -2
    grid = graph_laplacian(9, [(3 * i + j, 3 * i + j + 1, 1) for i in range(3) for j in range(2)]
                           + [(3 * i + j, 3 * i + j + 3, 1) for i in range(2) for j in range(3)])
    g = [(i - 1) ** 2 + 5 * (j - 1) for i in range(3) for j in range(3)]
    assert grid.matvec(g)[4] == 4 * g[4] - g[1] - g[3] - g[5] - g[7] == -2
    with pytest.raises(InputError):
        graph_laplacian(2, [(0, 2, 1)])


def test_sparse_matrix_is_exact_and_exports_correctly_rounded_floats():
    L = SparseMatrix.from_entries((2, 3), [(0, 0, 1), (0, 0, -1), (1, 2, sqrt(2)), (1, 1, 0.1)])
    assert L.nnz == 2 and L[0, 0] == 0 and L[1, 1] == Fraction(0.1)   # float taken exactly
    S = L.to_scipy()
    assert isinstance(S, sp.csr_matrix) and S.shape == (2, 3)
    assert S[1, 2] == float(sqrt(2)) and S[1, 1] == 0.1
    assert L.to_dense_floats()[1][2] == float(sqrt(2))
    assert L.matvec([0, 1, sqrt(2)]) == [0, Fraction(0.1) + 2]
    assert L.submatrix([1], [2, 1]).entries() == [(0, 0, sqrt(2)), (0, 1, Fraction(0.1))]
    assert not L.is_symmetric()
    assert SparseMatrix.from_entries((1, 1), [(0, 0, sqrt(2) * sqrt(2))])[0, 0] == Fraction(2)
    with pytest.raises(InputError):
        SparseMatrix.from_entries((1, 1), [(1, 0, 1)])


# --- (3.3): cotan weights ------------------------------------------------------------------------


@given(any_meshes())
def test_cotan_weights_from_vector_cotangents_boundary_halved(case):
    s = case.surface
    t = s.triangulation
    w = cotan_weights(s)
    assert set(w) == set(range(t.n_edges))
    for e, we in w.items():
        parts = []
        for h in t.edge_halfedges(e):
            if h >= 0:
                f, k = h // 3, (h + 2) % 3
                pts = [s.positions[v] for v in t.faces[f]]
                parts.append(triangle_cotangents(pts)[k])          # from vectors, not lengths
        assert we == sum(parts, Surd(0)) / 2                        # 1/2 cot on boundary edges
        assert len(parts) == (1 if t.is_boundary_edge(e) else 2)
    L = cotan_laplacian(s)
    for e, we in w.items():
        i, j = t.edge_vertices(e)
        assert L[i, j] == -we                                       # simplicial: one edge per pair
    assert L.is_symmetric() and all(x == 0 for x in L.matvec([1] * t.n_vertices))


def test_non_regular_triangulation_sums_multi_edges_and_ignores_loops():
    t = surfaces.tetrahedron().triangulation.flip(0)           # a double edge
    assert t.is_regular() and not t.is_strongly_regular()
    s = PiecewiseFlatSurface(t, [1] * t.n_edges)               # every face equilateral (D2.6)
    L = cotan_laplacian(s)
    w = cotan_weights(s)
    pairs = {}
    for e in range(t.n_edges):
        i, j = sorted(t.edge_vertices(e))
        pairs.setdefault((i, j), []).append(e)
    (i, j), es = next((p, es) for p, es in pairs.items() if len(es) == 2)
    assert L[i, j] == -(w[es[0]] + w[es[1]]) == -2 / sqrt(3)
    f = [Fraction(k * k) for k in range(t.n_vertices)]
    assert dirichlet_energy(L, f) == dirichlet_energy_pl(s, f)     # T3.6, intrinsically
    # flip on until a loop appears: it has a weight but contributes nothing to the matrix
    seen, frontier = None, [t]
    for _ in range(3):
        nxt = []
        for x in frontier:
            for e in range(x.n_edges):
                try:
                    nxt.append(x.flip(e))
                except InputError:
                    continue
        seen = next((x for x in nxt if not x.is_regular()), None)
        if seen:
            break
        frontier = nxt[:40]
    assert seen is not None
    s2 = PiecewiseFlatSurface(seen, [1] * seen.n_edges)
    loops = [e for e in range(seen.n_edges) if len(set(seen.edge_vertices(e))) == 1]
    assert loops and all(e in cotan_weights(s2) for e in loops)
    L2 = cotan_laplacian(s2)
    assert L2.is_symmetric() and all(x == 0 for x in L2.matvec([1] * seen.n_vertices))
    g = [Fraction(k + 1) ** 3 for k in range(seen.n_vertices)]
    assert dirichlet_energy(L2, g) == dirichlet_energy_pl(s2, g)
    assert dirichlet_energy(cotan_weighted_edges(s2), g) == dirichlet_energy(L2, g)


# --- T3.6 -----------------------------------------------------------------------------------------


@given(with_functions(any_meshes()))
def test_T3_6_energy_of_interpolant_equals_cotan_energy_exactly(case):
    s = case.surface
    f, g = list(case.values), list(case.second)
    L = cotan_laplacian(s)
    e = dirichlet_energy_pl(s, f)                               # per-face gradients
    assert e == dirichlet_energy(L, f) == dirichlet_energy(cotan_weighted_edges(s), f)
    assert dirichlet_energy_pl(s.metric(), f) == e              # intrinsic (Gram of lengths)
    assert dirichlet_inner_product_pl(s, f, g) == L.quadratic_form(f, g)   # polarisation
    assert e >= 0


@given(with_functions(any_meshes()), st.data())
def test_C3_4_energy_gradient_is_the_inner_product_with_each_hat_and_L_f(case, data):
    """dE/df(i) in one pass = <grad f, grad phi_i> face by face = (L f)_i (T3.6, the
    notes' sign: L positive semidefinite), extrinsic and intrinsic."""
    s, f = case.surface, list(case.values)
    n = s.triangulation.n_vertices
    grad = dirichlet_energy_gradient_pl(s, f)
    assert grad == dirichlet_energy_gradient_pl(s.metric(), f)
    assert grad == cotan_laplacian(s).matvec(f)
    # each inner product runs over every face: every hat up to 12 vertices, beyond that 12
    # drawn ones (a mesh of 64 vertices took 19 s over all of them)
    hats = range(n) if n <= 12 else data.draw(
        st.lists(st.integers(0, n - 1), min_size=12, max_size=12, unique=True), label="hats")
    for i in hats:
        assert grad[i] == dirichlet_inner_product_pl(s, f, [Fraction(int(v == i)) for v in range(n)])


@given(with_functions(any_meshes()))
def test_T3_6_inner_product_by_gram_matrices_is_the_one_of_the_gradient_vectors(case):
    """dirichlet_inner_product_pl takes <grad f, grad g> = df^T G^-1 dg face by face; the
    gradient vectors themselves (gradient_pl) and the area sqrt(det G) / 2 give the same
    exact number, on the surface and on its metric."""
    s, f, g = case.surface, list(case.values), list(case.second)
    by_vectors = exact_sum(
        s.metric().area(k) * sum((a * b for a, b in zip(gradient_pl(s, f, k), gradient_pl(s, g, k))),
                                 Fraction(0))
        for k in range(s.triangulation.n_faces))
    assert dirichlet_inner_product_pl(s, f, g) == by_vectors
    assert dirichlet_inner_product_pl(s.metric(), f, g) == by_vectors
    assert dirichlet_energy_pl(s, f) * 2 == dirichlet_inner_product_pl(s, f, list(f))


def test_T3_6_gradient_of_a_linear_function_is_its_coefficient_vector():
    s = surfaces.grid(2, 1)
    f = [3 * x - 2 * y for x, y, _ in s.positions]
    assert all(gradient_pl(s, f, k) == (3, -2, 0) for k in range(s.triangulation.n_faces))
    assert dirichlet_energy_pl(s, f) == Fraction(13, 2) * 2         # 1/2 |grad|^2 * area 2


_planar_triangles = st.tuples(*[st.tuples(st.integers(-4, 4), st.integers(-4, 4))] * 3).filter(
    lambda p: (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]) > 0)


@given(_planar_triangles, st.integers(0, 2))
def test_T3_6_proof_step_inner_product_of_hat_gradients(p, i):
    """The proof of T3.6 prints <grad phi_i, grad phi_i+1> = <w_i, w_i+1> / 4A^2 =
    a_i a_i+1 cos alpha_i-1 / 4A^2 = -cot alpha_i-1 / 2A: the middle term lacks a minus sign
    (<w_i, w_i+1> = -a_i a_i+1 cos alpha_i-1); first and last are right."""
    s = PolyhedralSurface.from_arrays(p, [(0, 1, 2)])
    j, k = (i + 1) % 3, (i - 1) % 3                       # v_i+1 and v_i-1
    hat = lambda m: [Fraction(int(v == m)) for v in range(3)]
    inner = sum((a * b for a, b in zip(gradient_pl(s, hat(i), 0), gradient_pl(s, hat(j), 0))),
                Fraction(0))
    area = s.metric().total_area()
    w_i = [x - y for x, y in zip(p[k], p[j])]             # v_i-1 - v_i+1
    w_j = [x - y for x, y in zip(p[i], p[k])]             # v_i - v_i+2 = v_i - v_i-1
    ww = sum(a * b for a, b in zip(w_i, w_j))
    aa_cos = sum((x - z) * (y - z) for x, y, z in zip(p[j], p[i], p[k]))   # a_i a_i+1 cos alpha_i-1
    cot = triangle_cotangents(p)[k]
    assert inner == ww / (4 * area * area) == -cot / (2 * area)
    assert ww == -aa_cos
    if aa_cos:
        assert inner != aa_cos / (4 * area * area)        # the printed middle term


@given(_planar_triangles, st.integers(0, 2))
def test_L3_7_proof_step_circumcentric_subtriangles(p, i):
    """The proof of L3.7 prints the sub-triangle area as 1/4 a_i l_i = 1/4 a_i^2 cot alpha_i;
    with l_i the (signed) height of the sub-triangle over a_i it is 1/2 a_i l_i (the second
    expression is right)."""
    P = [tuple(Fraction(x) for x in q) for q in p]
    a, b, c = P[(i + 1) % 3], P[(i + 2) % 3], P[i]        # side a_i = [a, b], opposite P[i]
    o = _circumcentre(*P)
    sub = _shoelace([o, a, b])                            # signed: negative if o is beyond a_i
    if _shoelace([c, a, b]) < 0:
        sub = -sub
    a2 = sum((x - y) ** 2 for x, y in zip(a, b))
    cot = triangle_cotangents(P)[i]
    assert sub == a2 * cot / 4
    l_i = 2 * sub / sqrt(a2)                               # the height of the sub-triangle
    assert sub == sqrt(a2) * l_i / 2
    if sub:
        assert sqrt(a2) * l_i / 4 != sub                  # the printed 1/4 a_i l_i


# --- R3.3 (exact part; the Dirichlet part is in test_dirichlet.py) ----------------------------------


@given(with_functions(obtuse_meshes()))
def test_R3_3_negative_weights_yet_positive_semidefinite(case):
    s = case.surface
    L = cotan_laplacian(s)
    f = list(case.values)
    assert dirichlet_energy(L, f) >= 0                          # = 1/2 integral |grad f|^2
    assert kernel_dimension(L) == len(s.triangulation.components())


def test_R3_3_obtuse_strategy_produces_negative_weights():
    from hypothesis import find
    case = find(obtuse_meshes(), lambda c: any(w < 0 for w in cotan_weights(c.surface).values()))
    L = cotan_laplacian(case.surface)
    assert any(v > 0 for i, j, v in L.entries() if i != j)      # a positive off-diagonal entry
    assert kernel_dimension(L) == 1


# --- L3.7 / L3.8 ----------------------------------------------------------------------------------


def _triangles(dim):
    pt = st.tuples(*[st.integers(-4, 4)] * dim)
    return st.tuples(pt, pt, pt).filter(lambda p: _nondegenerate(p))


def _nondegenerate(p):
    u = [b - a for a, b in zip(p[0], p[1])]
    v = [b - a for a, b in zip(p[0], p[2])]
    uv = sum(x * y for x, y in zip(u, v))
    return sum(x * x for x in u) * sum(y * y for y in v) - uv * uv != 0


@given(st.one_of(_triangles(2), _triangles(3), _triangles(4)))
def test_L3_7_area_from_cotangents_and_its_length_derivatives(p):
    sq = [sum((x - y) ** 2 for x, y in zip(p[(i + 1) % 3], p[(i + 2) % 3])) for i in range(3)]
    cot = triangle_cotangents(p)                 # alpha_i at p[i], opposite the side sq[i]
    area = triangle_area_heron(*sq)
    assert area_from_cotangents(sq, cot) == area                     # (3.5)
    dA = area_length_derivatives(*sq)                                # from Heron, exactly
    for i in range(3):
        assert dA[i] == sqrt(sq[i]) * cot[i] / 2                     # (3.6)
        x = sq[i]
        assert heron_partial_derivatives(*sq)[i] == 2 * (sum(sq) - 2 * x)


@given(st.one_of(_triangles(2), _triangles(3), _triangles(4)), st.integers(0, 2))
def test_L3_8_area_gradient_cotan_formula_equals_direct_derivative(p, i):
    g = area_gradient_cotan(p, i)
    assert g == area_gradient_direct(p, i)
    if len(p[0]) == 3:
        assert g == area_gradient_cross(p, i)
    # independent facts: g is orthogonal to the opposite edge and <g, v_i - v_j> = A
    # (A = 1/2 |v_k - v_j| * height, and g is 1/2 |v_k - v_j| times the unit height vector)
    j, k = (i + 1) % 3, (i + 2) % 3
    assert sum(a * (c - b) for a, b, c in zip(g, p[j], p[k])) == 0
    sq = [sum((x - y) ** 2 for x, y in zip(p[(m + 1) % 3], p[(m + 2) % 3])) for m in range(3)]
    assert sum(a * (c - b) for a, b, c in zip(g, p[j], p[i])) == triangle_area_heron(*sq)


# --- T3.9 and its misprint -------------------------------------------------------------------------


@given(st.one_of(planar_meshes(), planar_meshes(heights=True), closed_meshes(), obtuse_meshes()))
def test_T3_9_area_is_the_dirichlet_energy_of_the_coordinates(case):
    s = case.surface
    area = s.metric().total_area()
    assert area_as_dirichlet_energy(s) == area
    printed = sum((w * sum((a - b) ** 2 for a, b in zip(s.positions[i], s.positions[j]))
                   for i, j, w in cotan_weighted_edges(s)), Fraction(0))
    assert printed == 2 * area != area                               # (3.10) as printed: 2A
    grad = area_gradient(s)
    assert grad == laplacian_of_positions(s)                         # (3.11) corrected
    if all(p[2] == 0 for p in s.positions):                          # linear precision
        t = s.triangulation
        assert all(grad[v] == (0, 0, 0) for v in range(t.n_vertices) if not t.is_boundary_vertex(v))


def test_T3_9_misprint_evidence_on_the_right_triangle():
    s = PolyhedralSurface.from_arrays([(0, 0), (1, 0), (0, 1)], [(0, 1, 2)])
    w = sorted(cotan_weights(s).values(), key=float)
    assert w == [0, Fraction(1, 2), Fraction(1, 2)]
    assert area_as_dirichlet_energy(s) == Fraction(1, 2) == s.metric().total_area()
    lap = laplacian_of_positions(s)
    assert lap[0] == (Fraction(-1, 2), Fraction(-1, 2)) == area_gradient(s)[0]   # not 2 Lap f


# --- E3.12 ------------------------------------------------------------------------------------------


@given(st.one_of(obtuse_meshes(), planar_meshes()))
def test_E3_12_weight_sign_from_the_angle_sum(case):
    s = case.surface
    t = s.triangulation
    signs = weight_signs_by_angles(s)               # every edge at once: the same signs
    for e, w in cotan_weights(s).items():
        assert (w > 0) - (w < 0) == weight_sign_by_angles(s, e) == signs[e]
        assert cotan_weight_by_sines(s, e) == w                    # with the 1/2
        total = opposite_angle_sum(s, e)
        limit = pi if not t.is_boundary_edge(e) else pi * Fraction(1, 2)
        assert (w >= 0) == (total <= limit)


def test_E3_12_misprint_evidence_equilateral_pair():
    # two equilateral triangles of side 1: alpha = alpha' = pi/3, nu = 1/2 (2 / sqrt 3) = 1/sqrt 3
    t = Triangulation.from_faces([(0, 1, 2), (1, 0, 3)])
    s = PiecewiseFlatSurface(t, [1] * t.n_edges)
    e = next(e for e in range(t.n_edges) if not t.is_boundary_edge(e))
    nu = cotan_weights(s)[e]
    assert nu == 1 / sqrt(3) == cotan_weight_by_sines(s, e)
    a = corner_angle(Surd(1) / sqrt(3))
    assert opposite_angle_sum(s, e) == 2 * a == pi * Fraction(2, 3)
    sin_a, cos_a = sqrt(3) / 2, Fraction(1, 2)
    printed = (2 * sin_a * cos_a) / (sin_a * sin_a)                # sin(a + a') / (sin a sin a')
    assert printed == 2 / sqrt(3) == 2 * nu


# --- mass matrices ------------------------------------------------------------------------------------


def _shoelace(pts):
    return sum((a[0] * b[1] - b[0] * a[1] for a, b in zip(pts, pts[1:] + pts[:1])), Fraction(0)) / 2


@given(st.one_of(planar_meshes(), obtuse_meshes(), closed_meshes(), acute_meshes()))
def test_mass_matrices_sum_to_the_area_and_match_the_circumcentric_split(case):
    s = case.surface
    total = s.metric().total_area()
    vor, bar = vertex_areas_voronoi(s), vertex_areas_barycentric(s)
    assert sum(vor, Fraction(0)) == total == sum(bar, Fraction(0))
    assert all(a > 0 for a in vor) and all(a > 0 for a in bar)
    if all(p[2] == 0 for p in s.positions):
        # planar: the Voronoi region of a non-obtuse face is the quadrilateral
        # (vertex, edge midpoint, circumcentre, edge midpoint): a rational shoelace area
        expect = [Fraction(0)] * s.n_vertices
        for f in s.triangulation.faces:
            P = [s.positions[v][:2] for v in f]
            sq = [sum((x - y) ** 2 for x, y in zip(P[(c + 1) % 3], P[(c + 2) % 3])) for c in range(3)]
            obtuse = [c for c in range(3) if sq[c] > sq[(c + 1) % 3] + sq[(c + 2) % 3]]
            area = abs(_shoelace(P))
            for c in range(3):
                if obtuse:
                    expect[f[c]] += area / 2 if c == obtuse[0] else area / 4
                    continue
                a, b, d = P[c], P[(c + 1) % 3], P[(c + 2) % 3]
                cc = _circumcentre(a, b, d)
                mb = ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
                md = ((a[0] + d[0]) / 2, (a[1] + d[1]) / 2)
                expect[f[c]] += abs(_shoelace([a, mb, cc, md]))
        assert vor == expect


def _circumcentre(a, b, c):
    d = 2 * (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1]))
    n2 = [p[0] ** 2 + p[1] ** 2 for p in (a, b, c)]
    x = (n2[0] * (b[1] - c[1]) + n2[1] * (c[1] - a[1]) + n2[2] * (a[1] - b[1])) / d
    y = (n2[0] * (c[0] - b[0]) + n2[1] * (a[0] - c[0]) + n2[2] * (b[0] - a[0])) / d
    return (x, y)


def test_surfaces_are_checked():
    with pytest.raises(InputError):
        cotan_laplacian("not a surface")
    with pytest.raises(InputError):
        area_as_dirichlet_energy(surfaces.tetrahedron().metric())


# --- performance: exact cotan Laplacian of a 1,280-face float mesh --------------------------------


def test_exact_cotan_laplacian_of_1280_float_faces():
    # timings live in benchmarks/, not in tests
    s = float_icosphere()
    assert s.triangulation.n_faces == 1280
    L = cotan_laplacian(s)                      # metric (exact lengths, Surd areas) included
    S = L.to_scipy()
    assert L.is_symmetric() and all(x == 0 for x in L.matvec([1] * s.n_vertices))
    eps = np.finfo(float).eps
    absS = abs(S)
    assert np.all(np.abs(np.asarray(S.sum(axis=1))) <= 8 * eps * np.asarray(absS.sum(axis=1)))
    lam = np.linalg.eigvalsh(S.toarray())
    assert lam[0] >= -s.n_vertices * eps * np.abs(lam).max()          # positive semidefinite


def test_T3_6_exactly_on_a_320_face_float_mesh():
    s = float_icosphere(levels=2)
    rng = random.Random(3)
    f = [Fraction(rng.randint(-9, 9), 8) for _ in range(s.n_vertices)]
    assert dirichlet_energy(cotan_laplacian(s), f) == dirichlet_energy_pl(s, f)


# --- properties: pass on the reference, catch planted bugs ---------------------------------------


@pytest.mark.parametrize("pid", CHAPTER3)
def test_reference_passes_chapter3_property(pid):
    assert_passes_well_inside(pid, ExactViews())




def test_planted_sign_error_is_caught_on_one_triangle():
    r = assert_caught("T3.6", SignError(), 1)
    assert r.failure.expected * r.failure.observed < 0     # the energy came out negative
    assert_caught("R3.3", SignError(), 2)


def test_planted_missing_half_on_boundary_edges_is_caught_on_one_triangle():
    r = assert_caught("D3.1", BoundaryWithoutHalf(), 1)
    assert abs(r.failure.observed) > abs(r.failure.expected)


def test_planted_cotangent_of_the_wrong_corner_is_caught_on_one_triangle():
    assert_caught("T3.6", CotOfWrongCorner(), 1)
    assert_caught("E3.12", CotOfWrongCorner(), 2)


def test_a_float_implementation_stays_well_inside_the_bounds():
    class NumpyCotan(ExactViews):
        name = "numpy float cotangents"

        def cotan_laplacian(self, V, F):
            n = len(V)
            L = np.zeros((n, n))
            for f in F:
                for c in range(3):
                    i, j, k = f[c], f[(c + 1) % 3], f[(c + 2) % 3]
                    u, v = V[j] - V[i], V[k] - V[i]
                    half = np.dot(u, v) / np.linalg.norm(np.cross(u, v)) / 2
                    L[j, k] -= half
                    L[k, j] -= half
                    L[j, j] += half
                    L[k, k] += half
            return L

    with recording(ErrorLedger()) as ledger:
        r = run_property(PROPERTIES["D3.1"], NumpyCotan(), profile("default"))
    assert r.status == PASSED, r.failure
    assert 0 < ledger.ratios["D3.1"] < 0.5


@given(st.one_of(any_meshes(isolated=False), obtuse_meshes(), jittered_surfaces().map(
    lambda c: c.surface)))
def test_the_conditioning_factors_of_the_bounds_are_the_exact_ones_within_two_ulps(case):
    # entry_bounds takes rho and the cotangents from exact ratios through one float square
    # root: within 2 ulps of the correctly rounded exact values
    m = case.metric() if hasattr(case, "metric") else Exact.of(case).metric
    for f in range(m.triangulation.n_faces):
        rho, cot = _conditioning(m, f)
        want_rho = float(max(m.face_squared_lengths(f)) / (2 * m.area(f)))
        want_cot = [float(m.corner_cot(f, c)) for c in range(3)]
        for got, want in zip([rho, *cot], [want_rho, *want_cot]):
            assert abs(got - want) <= 2 * np.spacing(abs(want)), (f, got, want)


def test_the_dirichlet_harness_counts_a_repeated_boundary_vertex_once():
    """Issue 40: with V0 = [0, 0, 2] the boundary column of vertex 0 was added twice, so the
    correct solution of a correct matrix failed C3.4 and T3.2 (a false alarm)."""
    import numpy as np
    from ddg_oracle.properties.harness import dirichlet_solve
    A = np.array([[1.0, -1, 0], [-1, 2, -1], [0, -1, 1]])     # a path 0 - 1 - 2
    c = np.array([1.0, 0.0, 3.0])
    u, others = dirichlet_solve(A, [0, 0, 2], c)
    assert others == [1] and u[1] == 2.0                      # the mean of its neighbours
    assert np.array_equal(u, dirichlet_solve(A, [2, 0], c)[0])


def test_t39_asks_the_implementation_for_its_matrix_once():
    """T3.9 checks the energy and L V with one answer of ``cotan_laplacian`` (MeshLib's and
    mouette's Laplacians take seconds on a scanned mesh; mouette's area gradient asks for
    it once more), and the answer it checks is that one."""
    from ddg_oracle.properties.example import Example
    from ddg_oracle.properties.runner import run_on_example
    from ddg_oracle.reference.polyhedral import PolyhedralSurface
    from tests.honest_panel import Atan2Cross

    class Counting(Atan2Cross):
        calls = 0

        def cotan_laplacian(self, V, F):
            Counting.calls += 1
            return super().cotan_laplacian(V, F)
    s = surfaces.torus(6, 9)
    V, F = (np.asarray(a, dtype=float) for a in s.to_arrays())
    case = Example.of_surface(PolyhedralSurface.from_arrays(V + 2 ** -9, F.astype(np.int64)),
                              0, "torus")
    r = run_on_example(PROPERTIES["T3.9"], Counting(), case, "torus")
    assert r.status == PASSED and Counting.calls == 1, (r.status, Counting.calls)
