"""The libigl adapter agrees with the exact reference, within bounds derived from float64.

The truth is always the reference's exact value *for the float input libigl
sees*: ``PolyhedralSurface.from_arrays(V, F)`` takes every float exactly (a
dyadic rational), so the comparison measures libigl's arithmetic only, never
the rounding of the constructors' rational coordinates.  The expected values
are assembled in this file from the reference's exact primitives
(``corner_angle``, ``corner_cot``, ``area``, squared lengths: ``Angle`` /
``Surd`` arithmetic, rounded once; dihedral angles from mpmath at 40 digits on
the exact rational positions), written while ``ddg_oracle.reference.curvature`` and
``ddg_oracle.reference.laplacian`` were being written;
``test_expectations_are_the_reference_chapter_2_3_functions`` checks that they
are exactly what those modules return.

Error bounds (u = 2^-53, the unit roundoff of float64)
------------------------------------------------------
Per face f let kappa_f = (l0^2 + l1^2 + l2^2) / (4 A_f) = cot a + cot b + cot c
(>= sqrt 3, large only for needles and caps).  libigl forms squared lengths
with relative error <= 4u; the face area from them (Kahan-Heron) has
relative error <= u (11 + 3 kappa_f^2) since d(ln A)/d(ln l_i^2) = cot_i l_i^2 / (4A)
<= kappa_f^2 in absolute sum; a cotangent N / (4A) with |dN| <= 4u sum l^2 gets
|d cot| <= 4u kappa_f + |cot| u (11 + 3 kappa_f^2) <= u (15 kappa_f + 3 kappa_f^3).
Each bound below is that first-order estimate times a safety factor 2 (for
the second-order terms and the final sums), written next to its use.
"""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import igl
import numpy as np
import pytest

from ddg_oracle.oracles.libigl import Libigl
from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.profiles import profile
from ddg_oracle.properties.runner import PASSED, run_property
from ddg_oracle.reference import PolyhedralSurface, surfaces
from ddg_oracle.reference.exact import Angle, Surd, pi

U = 2.0 ** -53
IGL = Libigl()

MESHES = {
    "cube": surfaces.cube,
    "tetrahedron": surfaces.tetrahedron,
    "icosahedron": surfaces.icosahedron,
    "torus(5,4)": lambda: surfaces.torus(5, 4),
    "disk(6)": lambda: surfaces.disk(6),
    "grid(3,3)": lambda: surfaces.grid(3, 3),
    "annulus(5)": lambda: surfaces.annulus(5),
    "mobius_strip(5)": lambda: surfaces.mobius_strip(5),
    # extra: reflex (concave) edges, and obtuse triangles (centre angle 120 degrees)
    "genus_surface(1)": lambda: surfaces.genus_surface(1),
    "disk(3)": lambda: surfaces.disk(3),
}
ORIENTABLE = [k for k in MESHES if k != "mobius_strip(5)"]


class Case:
    """Float arrays of a constructor and the exact surface of exactly those floats."""

    def __init__(self, name):
        V, F = MESHES[name]().to_arrays()
        self.name = name
        self.V = np.array(V, dtype=np.float64)
        self.F = np.array(F, dtype=np.int64)
        self.surface = PolyhedralSurface.from_arrays(self.V, self.F)
        self.metric = self.surface.metric()
        self.t = self.metric.triangulation
        m = self.metric
        self.kappa = np.array([float(sum(m.face_squared_lengths(f)) / (4 * m.area(f)))
                               for f in range(self.t.n_faces)])
        self.face_area = np.array([float(m.area(f)) for f in range(self.t.n_faces)])

    def faces_at(self, v):
        return [f for f, face in enumerate(self.t.faces) if v in face]


_CASES: dict[str, Case] = {}


def case(name) -> Case:
    if name not in _CASES:
        _CASES[name] = Case(name)
    return _CASES[name]


# --- exact expectations from the reference's primitives ---------------------------------


def exact_corner_angles(c: Case) -> np.ndarray:
    return np.array([[float(c.metric.corner_angle(f, k)) for k in range(3)]
                     for f in range(c.t.n_faces)])


def exact_angle_sums(c: Case) -> list[Angle]:
    sums = [Angle() for _ in range(c.t.n_vertices)]
    for f, face in enumerate(c.t.faces):
        for k in range(3):
            sums[face[k]] = sums[face[k]] + c.metric.corner_angle(f, k)
    return sums


def exact_angle_defects(c: Case) -> np.ndarray:
    """2 pi - sum at interior vertices, pi - sum (turning angle) at boundary vertices."""
    return np.array([float((pi if c.t.is_boundary_vertex(v) else 2 * pi) - s)
                     for v, s in enumerate(exact_angle_sums(c))])


def exact_cotan_weights(c: Case) -> dict[tuple[int, int], Surd]:
    """nu(ij) = sum over the corners opposite edge ij of cot / 2 (one corner on the boundary)."""
    w: dict[tuple[int, int], Surd] = {}
    for f, face in enumerate(c.t.faces):
        for k in range(3):
            i, j = sorted((face[(k + 1) % 3], face[(k + 2) % 3]))
            w[(i, j)] = w.get((i, j), Surd(0)) + c.metric.corner_cot(f, k) / 2
    return w


def exact_laplacian(c: Case) -> np.ndarray:
    n = c.t.n_vertices
    L = np.zeros((n, n))
    diag = [Surd(0)] * n
    for (i, j), w in exact_cotan_weights(c).items():
        L[i, j] = L[j, i] = -float(w)
        diag[i] = diag[i] + w
        diag[j] = diag[j] + w
    for i in range(n):
        L[i, i] = float(diag[i])
    return L


def exact_barycentric_areas(c: Case) -> np.ndarray:
    acc = [Surd(0)] * c.t.n_vertices
    for f, face in enumerate(c.t.faces):
        for v in face:
            acc[v] = acc[v] + c.metric.area(f) / 3
    return np.array([float(a) for a in acc])


def exact_mixed_areas(c: Case) -> list[Surd]:
    """Meyer et al. 2003: circumcentric Voronoi area in non-obtuse faces; in an obtuse face
    A/2 to the obtuse corner and A/4 to the others (obtuseness decided exactly)."""
    m = c.metric
    acc = [Surd(0)] * c.t.n_vertices
    for f, face in enumerate(c.t.faces):
        sq = m.face_squared_lengths(f)   # halfedge 3f + k runs k -> k+1, opposite corner k+2
        cot = [m.corner_cot(f, k) for k in range(3)]
        A = m.area(f)
        obtuse = [k for k in range(3) if cot[k] < 0]
        for k in range(3):
            if obtuse:
                a = A / 2 if k == obtuse[0] else A / 4
            else:
                a = (sq[k] * cot[(k + 2) % 3] + sq[(k + 2) % 3] * cot[(k + 1) % 3]) / 8
            acc[face[k]] = acc[face[k]] + a
    return acc


def exact_edge_mean_curvature(c: Case) -> dict[tuple[int, int], float]:
    """H(e) = 1/2 theta l on interior edges, at 40 digits from the exact rational positions.

    |theta| = angle between the face normals; theta > 0 iff the far vertex of the
    second face lies below the first face's plane (convex), for a consistently
    oriented surface.  Independent of libigl's atan2 formula.
    """
    with mpmath.workdps(40):          # local precision: other tests set mp.dps globally
        return _edge_mean_curvature_mp(c)


def _edge_mean_curvature_mp(c: Case) -> dict[tuple[int, int], float]:
    P = c.surface.positions

    def sub(a, b):
        return [x - y for x, y in zip(a, b)]

    def cross(a, b):
        return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

    def dot(a, b):
        return sum(x * y for x, y in zip(a, b))

    def mp(q: Fraction):
        return mpmath.mpf(q.numerator) / q.denominator

    where: dict[tuple[int, int], list[tuple[int, int]]] = {}
    for f, face in enumerate(c.t.faces):
        for k in range(3):
            i, j = sorted((face[k], face[(k + 1) % 3]))
            where.setdefault((i, j), []).append((f, k))
    out = {}
    for (i, j), incident in where.items():
        if len(incident) != 2:
            continue
        (f1, _), (f2, _) = incident
        a, b, d = (P[v] for v in c.t.faces[f1])
        n1 = cross(sub(b, a), sub(d, a))
        x, y, z = (P[v] for v in c.t.faces[f2])
        n2 = cross(sub(y, x), sub(z, x))
        far = next(v for v in c.t.faces[f2] if v not in (i, j))
        side = dot(sub(P[far], P[i]), n1)
        c12 = cross(n1, n2)
        magnitude = mpmath.atan2(mpmath.sqrt(mp(dot(c12, c12))), mp(dot(n1, n2)))
        theta = -magnitude if side > 0 else magnitude
        length = mpmath.sqrt(mp(dot(sub(P[i], P[j]), sub(P[i], P[j]))))
        out[(i, j)] = float(theta * length / 2)
    return out


@pytest.mark.parametrize("name", list(MESHES))
def test_expectations_are_the_reference_chapter_2_3_functions(name):
    """The expected values above, assembled from the reference's primitives, equal what
    ``ddg_oracle.reference.curvature`` / ``ddg_oracle.reference.laplacian`` return (exactly, or as floats of the
    same exact numbers)."""
    curvature = pytest.importorskip("ddg_oracle.reference.curvature")
    laplacian = pytest.importorskip("ddg_oracle.reference.laplacian")
    c = case(name)
    s = c.surface
    defects = {**curvature.angle_defects(s), **curvature.turning_angles(s)}
    np.testing.assert_array_equal(exact_angle_defects(c),
                                  [float(defects[v]) for v in range(c.t.n_vertices)])
    np.testing.assert_array_equal(exact_corner_angles(c),
                                  [[float(a) for a in row] for row in curvature.corner_angles(s)])
    np.testing.assert_array_equal(exact_laplacian(c),
                                  laplacian.cotan_laplacian(s).to_scipy().toarray())
    assert exact_mixed_areas(c) == laplacian.vertex_areas_voronoi(s)
    np.testing.assert_array_equal(exact_barycentric_areas(c),
                                  [float(a) for a in laplacian.vertex_areas_barycentric(s)])
    if name in ORIENTABLE:
        H = curvature.mean_curvature(s)
        ours = exact_edge_mean_curvature(c)
        assert set(ours) == {tuple(sorted(c.t.edge_vertices(e))) for e in H}
        for e, h in H.items():
            key = tuple(sorted(c.t.edge_vertices(e)))
            assert abs(float(h) - ours[key]) <= math.ulp(ours[key])      # 40 digits, rounded


# --- chapter 1: topology -------------------------------------------------------------


def _cyclic(loop):
    k = loop.index(min(loop))
    return tuple(loop[k:] + loop[:k])


@pytest.mark.parametrize("name", list(MESHES))
def test_euler_characteristic(name):
    c = case(name)
    assert IGL.euler_characteristic(c.V, c.F) == c.t.euler_characteristic()


@pytest.mark.parametrize("name", ORIENTABLE)
def test_boundary_loops_and_genus_on_orientable_surfaces(name):
    c = case(name)
    got = sorted(_cyclic(loop) for loop in IGL.boundary_loops(c.V, c.F))
    want = sorted(_cyclic(loop) for loop in c.t.boundary_loops())
    assert got == want              # same loops, same direction (along the faces' orientation)
    assert IGL.is_orientable(c.V, c.F) is True
    assert IGL.genus(c.V, c.F) == c.t.classify().genus


@pytest.mark.parametrize("n", [3, 5])
def test_finding_F_libigl_1_boundary_loop_all_breaks_the_boundary_of_a_mobius_strip(n):
    """libigl walks boundary edges along each face's orientation (boundary_loop.cpp:
    next = F(f, vLoc + 1) where TT(f, vLoc) < 0).  On a non-orientable strip the
    orientation flips once, so the walk stops and restarts: the one boundary loop of
    2n edges comes back as n + 1 "loops", and the genus from chi and k is wrong.
    Minimal case: ``mobius_strip(3)`` (6 faces): [[0], [1], [2], [3, 4, 5]]."""
    V, F = (np.array(a) for a in surfaces.mobius_strip(n).to_arrays())
    t = surfaces.mobius_strip(n).triangulation
    assert t.boundary_loops() == [list(range(n, 2 * n)) + list(range(n))]
    assert IGL.boundary_loops(V, F) == [[v] for v in range(n)] + [list(range(n, 2 * n))]
    assert IGL.is_orientable(V, F) is False                      # bfs_orient: right
    assert t.classify().genus == 1                               # one crosscap
    assert IGL.genus(V, F) == 2 - 0 - (n + 1)                    # from libigl's k = n + 1


def test_is_orientable_on_closed_non_orientable_surfaces():
    from ddg_oracle.properties.strategies import extend_positions
    for t in (surfaces.projective_plane(), surfaces.klein_bottle()):
        V = np.array([[float(x) for x in p] for p in extend_positions(t, ())])
        F = np.array(t.to_face_list())
        assert IGL.is_orientable(V, F) is False
        assert IGL.genus(V, F) == t.classify().genus


# R1.6 and T1.1 / C1.2: finding F-libigl-1 (below)
CHAPTER1 = ["D1.6", "R1.5", "X1.4", "CS"]


@pytest.mark.parametrize("pid", CHAPTER1)
def test_chapter1_properties_pass(pid):
    r = run_property(PROPERTIES[pid], IGL, profile("default"))
    assert r.status == PASSED, r.failure or r.error


def test_T1_1_meets_F_libigl_1_on_a_reversed_face():
    """T1.1's orientation traps (a surface with faces listed the other way) make libigl's
    boundary walk find loops on a closed surface; the adapter's genus then refuses the odd
    2 - chi - k: a crash of the genus, reported with its mesh (F-libigl-1)."""
    from ddg_oracle.properties.runner import CRASHED
    r = run_property(PROPERTIES["T1.1 / C1.2"], IGL, profile("ci"))
    assert r.status == CRASHED and "odd 2 - chi - k" in r.error, r.failure or r.error


def test_R1_6_holds_on_orientable_surfaces_the_non_orientable_failure_is_L1():
    from hypothesis import given, settings
    from ddg_oracle.properties.strategies import triangulated_surfaces
    from ddg_oracle.properties.topology import boundary_loops_and_genus

    @settings(max_examples=25, deadline=None, database=None, derandomize=True)
    @given(triangulated_surfaces(orientable=True, max_holes=3))
    def orientable(case):
        boundary_loops_and_genus(IGL, case)          # raises PropertyFailure if wrong

    orientable()


# --- chapter 2: curvature --------------------------------------------------------------


@pytest.mark.parametrize("name", list(MESHES))
def test_corner_angles(name):
    c = case(name)
    got = IGL.corner_angles(c.V, c.F)
    # internal_angles: 2 atan(|p - q| / |p + q|) of unit vectors p, q (each within 3u):
    # |d theta| <= 6 sqrt(2) u + 2u theta (atan, doubling) < 6u pi; times safety 2.
    tol = 2 * 6 * U * math.pi
    assert got.shape == (c.t.n_faces, 3)
    np.testing.assert_allclose(got, exact_corner_angles(c), rtol=0, atol=tol)


@pytest.mark.parametrize("name", list(MESHES))
def test_angle_defects(name):
    c = case(name)
    want = exact_angle_defects(c)
    got = IGL.angle_defects(c.V, c.F)
    for v in range(c.t.n_vertices):
        d = len(c.faces_at(v))
        # d corner angles within 6u pi each (above), d + 2 roundings of sums of size <= 2 pi
        tol = 2 * (d * 6 * U * math.pi + (d + 2) * U * 2 * math.pi)
        assert abs(got[v] - want[v]) <= tol, (v, got[v], want[v])


@pytest.mark.parametrize("name", ["disk(6)", "grid(3,3)", "annulus(5)", "mobius_strip(5)"])
def test_angle_defects_library_boundary_convention_is_2pi_minus_sum(name):
    """gaussian_curvature.cpp: K = 2 pi - sum at every vertex; the reference's turning
    angle at a boundary vertex is pi - sum, so the two differ by exactly pi there."""
    c = case(name)
    raw = Libigl(boundary="library").angle_defects(c.V, c.F)
    ref = IGL.angle_defects(c.V, c.F)
    boundary = np.array([c.t.is_boundary_vertex(v) for v in range(c.t.n_vertices)])
    np.testing.assert_array_equal(raw[~boundary], ref[~boundary])
    np.testing.assert_allclose(raw[boundary] - ref[boundary], math.pi, rtol=0, atol=4 * U * math.pi)


@pytest.mark.parametrize("name", ORIENTABLE)
def test_edge_mean_curvature(name):
    c = case(name)
    want = exact_edge_mean_curvature(c)
    got = IGL.edge_mean_curvature(c.V, c.F)
    assert set(got) == set(want)          # interior edges only, keys (i, j) with i < j
    faces_of = {}
    for f, face in enumerate(c.t.faces):
        for k in range(3):
            faces_of.setdefault(tuple(sorted((face[k], face[(k + 1) % 3]))), []).append(f)
    for e, h in want.items():
        f1, f2 = faces_of[e]
        length = math.dist(c.V[e[0]], c.V[e[1]])
        # unit normals from cross products: direction within u (4 + 2 kappa_f) each
        # (1 / sin of the angle between the two edges <= kappa_f); atan2 and the edge
        # direction add 4u; H = theta l / 2 adds 2u |H|.  Safety 2.
        dtheta = U * (8 + 2 * c.kappa[f1] + 2 * c.kappa[f2] + 4)
        tol = 2 * (length / 2 * dtheta + 2 * U * abs(h))
        assert abs(got[e] - h) <= tol, (e, got[e], h)


def test_edge_mean_curvature_sign_convex_positive_reflex_negative():
    cube = case("cube")
    H = IGL.edge_mean_curvature(cube.V, cube.F)
    assert sum(abs(h - math.pi / 4) < 1e-15 for h in H.values()) == 12      # 1/2 (pi/2) 1
    assert sum(abs(h) < 1e-15 for h in H.values()) == 6                     # diagonals: flat
    g1 = case("genus_surface(1)")
    assert min(IGL.edge_mean_curvature(g1.V, g1.F).values()) == pytest.approx(-math.pi / 4,
                                                                          abs=1e-15)


@pytest.mark.parametrize("name", list(MESHES))
def test_area(name):
    c = case(name)
    want = float(c.metric.total_area())
    # doublearea: 3D cross-product norm, relative error <= u (6 + kappa_f) per face;
    # fsum of the faces and the halving are exact or correctly rounded.  Safety 2.
    tol = 2 * U * float(np.sum(c.face_area * (6 + c.kappa))) + U * want
    assert abs(IGL.area(c.V, c.F) - want) <= tol


# --- chapter 3: Laplacian and mass matrices --------------------------------------------


def _face_cot_bound(c: Case) -> np.ndarray:
    # |d (cot / 2)| <= u (15 kappa + 3 kappa^3) / 2 per corner (module doc); safety 2.
    return 2 * U * (15 * c.kappa + 3 * c.kappa ** 3) / 2


@pytest.mark.parametrize("name", list(MESHES))
def test_cotan_laplacian(name):
    c = case(name)
    L = IGL.cotan_laplacian(c.V, c.F)
    assert L.shape == (c.t.n_vertices, c.t.n_vertices)
    got = L.toarray()
    want = exact_laplacian(c)
    per_face = _face_cot_bound(c)
    # an off-diagonal entry sums the corners opposite its edge (one per incident face); a
    # diagonal entry sums 2 corners per incident face, plus u per term of the sparse sum
    tol = np.zeros_like(want)
    for f, face in enumerate(c.t.faces):
        for a in face:
            for b in face:
                if a == b:
                    tol[a, a] += 3 * per_face[f] + U * abs(want[a, a])
                else:
                    tol[a, b] += per_face[f]
    assert np.all(np.abs(got - want) <= tol), np.max(np.abs(got - want) - tol)
    # structure of the reference's convention: symmetric, rows sum to 0, PSD sign
    np.testing.assert_array_equal(got, got.T)
    assert np.all(np.diag(got) > 0)


def test_cotan_laplacian_factor_is_one_half_on_a_unit_right_triangle():
    """cotmatrix_entries.h: "1/2*cotangents"; L = -cotmatrix.  Right angle at vertex 0:
    the edge opposite it gets 1/2 cot(pi/2) = 0, the legs 1/2 cot(pi/4) = 1/2."""
    V = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    F = np.array([[0, 1, 2]])
    L = IGL.cotan_laplacian(V, F).toarray()
    np.testing.assert_allclose(L, [[1, -0.5, -0.5], [-0.5, 0.5, 0], [-0.5, 0, 0.5]],
                               rtol=0, atol=4 * U)


@pytest.mark.parametrize("name", list(MESHES))
def test_vertex_areas_barycentric(name):
    c = case(name)
    got = IGL.vertex_areas_barycentric(c.V, c.F)
    want = exact_barycentric_areas(c)
    for v in range(c.t.n_vertices):
        fs = c.faces_at(v)
        # massmatrix_intrinsic: dblA / 6 from edge lengths (Kahan-Heron): relative
        # u (11 + 3 kappa^2) per face (module doc), sparse summation adds u per term.
        tol = 2 * U * float(sum(c.face_area[f] / 3 * (12 + 3 * c.kappa[f] ** 2) for f in fs))
        assert abs(got[v] - want[v]) <= tol, (v, got[v], want[v])


@pytest.mark.parametrize("name", list(MESHES))
def test_vertex_areas_voronoi_are_meyers_mixed_areas(name):
    c = case(name)
    exact = exact_mixed_areas(c)
    assert sum(exact, Surd(0)) == c.metric.total_area()          # exact partition of area
    got = IGL.vertex_areas_voronoi(c.V, c.F)
    for v in range(c.t.n_vertices):
        fs = c.faces_at(v)
        # cosines from lengths: |d cos| <= u (6 + 2 kappa^2); the circumcentric barycentric
        # weights l cos / sum(l cos) then carry relative error <= u kappa (12 + 4 kappa^2)
        # (the normaliser sum(l cos) >= 2A / R > 0 of a non-obtuse face); times A.
        tol = 2 * U * float(sum(c.face_area[f] * (16 + c.kappa[f] * (12 + 4 * c.kappa[f] ** 2))
                                for f in fs))
        assert abs(got[v] - float(exact[v])) <= tol, (v, got[v], float(exact[v]))


def test_voronoi_uses_the_obtuse_triangle_rule():
    """A triangle with a 120 degree corner: the pure circumcentric Voronoi areas would be
    (A, 0, 0) (the circumcentre lies on the far side of the long edge); libigl gives A/2
    to the obtuse corner and A/4 to each other one (massmatrix_intrinsic.cpp)."""
    s = math.sqrt(3)
    V = np.array([[0.0, 0, 0], [-s, -1, 0], [s, -1, 0]])   # angles 120, 30, 30 degrees
    F = np.array([[0, 1, 2]])
    A = IGL.area(V, F)
    got = IGL.vertex_areas_voronoi(V, F)
    np.testing.assert_allclose(got, [A / 2, A / 4, A / 4], rtol=16 * U)
    cot30, cot120 = s, -1 / s
    circumcentric = [(4 * cot30 + 4 * cot30) / 8, (4 * cot30 + 12 * cot120) / 8,
                     (12 * cot120 + 4 * cot30) / 8]
    np.testing.assert_allclose(circumcentric, [A, 0, 0], atol=1e-15)
    assert abs(got[0] - circumcentric[0]) > A / 4


# --- intrinsic Delaunay API (notes for a later adapter, docs/conventions.md) --------------


def test_intrinsic_delaunay_api_conventions():
    """A thin rhombus whose long diagonal is not Delaunay (cot a + cot b < 0)."""
    V = np.array([[0.0, 0, 0], [1, -0.2, 0], [2, 0, 0], [1, 0.2, 0]])
    F = np.array([[0, 1, 2], [0, 2, 3]])
    lengths = igl.edge_lengths(V, F)                  # column c: edge opposite corner c
    D = np.asarray(igl.is_intrinsic_delaunay(lengths, F))
    assert D.tolist() == [[1, 0, 1], [1, 1, 0]]       # (f, c): edge opposite corner c
    l2, F2, *_ = igl.intrinsic_delaunay_triangulation(lengths, F)
    assert sorted(map(sorted, F2.tolist())) == [[0, 1, 3], [1, 2, 3]]    # flipped to 1-3
    # the new length comes from cos(a + d) via tan half angles: as conditioned as a cot
    # of the input faces, |d| <= u (15 kappa + 3 kappa^3) (module doc), safety 2
    kappa = float(np.max(np.sum(lengths ** 2, axis=1) / (2 * igl.doublearea(V, F))))
    np.testing.assert_allclose(np.sort(l2, axis=1)[:, 0], 0.4, rtol=0,
                               atol=2 * U * (15 * kappa + 3 * kappa ** 3))
    L, il, iF = igl.intrinsic_delaunay_cotmatrix(V, F)
    assert np.all(np.diag(L.toarray()) < 0)            # negative semidefinite, like cotmatrix
    # a cocircular square: w = 0 counts as Delaunay, nothing is flipped
    Q = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])
    G = np.array([[0, 1, 2], [0, 2, 3]])
    assert igl.intrinsic_delaunay_triangulation(igl.edge_lengths(Q, G), G)[1].tolist() == G.tolist()


def test_finding_F_libigl_3_is_delaunay_reads_only_x_and_y():
    """is_delaunay.cpp: incircle of (V(v, 0), V(v, 1)): the same rhombus stood up in the
    xz-plane is reported Delaunay everywhere, although its long diagonal is not."""
    V = np.array([[0.0, 0, 0], [1, 0, -0.2], [2, 0, 0], [1, 0, 0.2]])
    F = np.array([[0, 1, 2], [0, 2, 3]])
    assert np.asarray(igl.is_delaunay(V, F)).all()
    assert not np.asarray(igl.is_intrinsic_delaunay(igl.edge_lengths(V, F), F)).all()


# --- option and guards ----------------------------------------------------------------


def test_unknown_boundary_option_is_rejected():
    with pytest.raises(ValueError, match="boundary"):
        Libigl(boundary="whatever")


def test_bad_indices_raise_instead_of_segfaulting():
    """libigl reads out of bounds on such F (SIGSEGV, see docs/conventions.md); the
    adapter checks first."""
    V = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    for F in ([[0, 1, 3]], [[0, 1, -1]], [[0, 1]], np.zeros((0, 3))):
        with pytest.raises(ValueError):
            IGL.cotan_laplacian(V, np.array(F))
        with pytest.raises(ValueError):
            IGL.boundary_loops(V, np.array(F))


def test_runs_in_a_worker_process():
    from ddg_oracle.application.isolation import Isolated
    c = case("torus(5,4)")
    with Isolated("ddg_oracle.oracles.libigl:Libigl", timeout=60) as impl:
        assert impl.euler_characteristic(c.V, c.F) == 0
        assert impl.genus(c.V, c.F) == 1


def test_the_adapter_works_on_arrays():
    from ddg_oracle.protocol.methods import capabilities
    from tests import peer_checks as pc
    pc.check_array_methods(Libigl(), sorted(capabilities(Libigl())))
