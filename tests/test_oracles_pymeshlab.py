"""The PyMeshLab adapter agrees with the exact reference, within bounds derived from
float32 and float64 roundoff; its documented disagreements are asserted as such.

As in ``test_oracles_libigl.py`` the truth is the reference's exact value for
the float input PyMeshLab sees (``PolyhedralSurface.from_arrays(V, F)``),
assembled here from the reference's exact primitives (the libigl tests check
that these equal ``ddg_oracle.reference.curvature`` / ``ddg_oracle.reference.laplacian``).

Error bounds
------------
u = 2^-53 (float64), u32 = 2^-24 (float32).  vcg's ``MeanAndGaussian``
(vcg/complex/algorithms/update/curvature.h) keeps corner angles, squared edge
lengths and mixed areas in ``float``: each corner angle is within 3 u32 pi
(rounding of angle0, angle1 to float, and angle2 = pi - (angle0 + angle1) in
float), so an angle sum over d corners is within 3 u32 pi d.  A mixed-area
contribution e cot / 8 takes cot = 1 / tan of a float angle: |d cot| <=
3 u32 pi (1 + cot^2) <= 3 u32 pi (1 + kappa^2), and e / 8 summed over the two
sides is <= A kappa / 2, so a face adds <= A_f u32 (1.5 pi kappa_f (1 + kappa_f^2) + 3)
to the error of A_v (kappa_f = sum l^2 / (4 A_f) as in the libigl tests), plus
u32 per float accumulation.  The boundary angle phi is a double acos: within
sqrt(8u) (acos near +-1).  Each bound is that estimate times a safety factor 2.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from ddg_oracle.oracles.pymeshlab import (PyMeshLab, VertexOrderChanged, boundary_edge_angles,
                               exact_mixed_voronoi_areas, mixed_voronoi_areas)
from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.profiles import profile
from ddg_oracle.properties.runner import NOT_APPLICABLE, PASSED, run_property
from ddg_oracle.reference import PolyhedralSurface, surfaces
from ddg_oracle.reference.exact import Angle, pi

U = 2.0 ** -53
U32 = 2.0 ** -24
PML = PyMeshLab()

MESHES = {
    "cube": surfaces.cube,
    "tetrahedron": surfaces.tetrahedron,
    "icosahedron": surfaces.icosahedron,
    "torus(5,4)": lambda: surfaces.torus(5, 4),
    "disk(6)": lambda: surfaces.disk(6),
    "grid(3,3)": lambda: surfaces.grid(3, 3),
    "annulus(5)": lambda: surfaces.annulus(5),
    "mobius_strip(5)": lambda: surfaces.mobius_strip(5),
    "genus_surface(1)": lambda: surfaces.genus_surface(1),
    "disk(3)": lambda: surfaces.disk(3),            # obtuse triangles
}
ORIENTABLE = [k for k in MESHES if k != "mobius_strip(5)"]


class Case:
    """Float arrays and the exact surface of exactly those floats."""

    def __init__(self, name=None, arrays=None):
        V, F = MESHES[name]().to_arrays() if arrays is None else arrays
        self.V = np.array(V, dtype=np.float64)
        self.F = np.array(F, dtype=np.int64)
        self.metric = PolyhedralSurface.from_arrays(self.V, self.F).metric()
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


def exact_angle_defects(c: Case) -> np.ndarray:
    sums = [Angle() for _ in range(c.t.n_vertices)]
    for f, face in enumerate(c.t.faces):
        for k in range(3):
            sums[face[k]] = sums[face[k]] + c.metric.corner_angle(f, k)
    return np.array([float((pi if c.t.is_boundary_vertex(v) else 2 * pi) - s)
                     for v, s in enumerate(sums)])


def numpy_mixed_areas(V, F) -> np.ndarray:
    """Meyer et al.'s mixed areas in plain float64 numpy (independent of the adapter)."""
    A = np.zeros(len(V))
    for f in F:
        p = V[f]
        e = [p[(k + 2) % 3] - p[(k + 1) % 3] for k in range(3)]      # e[k] opposite corner k
        area = np.linalg.norm(np.cross(e[0], e[1])) / 2
        cot = [-(e[(k + 1) % 3] @ e[(k + 2) % 3]) / (2 * area) for k in range(3)]
        sq = [x @ x for x in e]
        for k in range(3):
            if min(cot) < 0:
                A[f[k]] += area / 2 if cot[k] < 0 else area / 4
            else:
                a, b = (k + 1) % 3, (k + 2) % 3              # the two sides at corner k
                A[f[k]] += (sq[a] * cot[a] + sq[b] * cot[b]) / 8
    return A


def _area_error(c: Case, v: int) -> float:
    """Bound on |vcg's float mixed area - exact| at v (module doc), before the safety 2."""
    fs = c.faces_at(v)
    per_face = sum(c.face_area[f] * (1.5 * math.pi * c.kappa[f] * (1 + c.kappa[f] ** 2) + 3)
                   for f in fs)
    return U32 * (per_face + len(fs) * float(sum(c.face_area[f] for f in fs)))


# --- the exact area conversion the adapter uses -----------------------------------------


@pytest.mark.parametrize("name", list(MESHES))
def test_exact_mixed_areas_partition_the_area_and_match_numpy(name):
    c = case(name)
    got = exact_mixed_voronoi_areas(c.V, c.F)
    # the exact areas sum to the exact total; their float roundings within n u of it
    total = float(c.metric.total_area())
    assert abs(math.fsum(got) - total) <= len(got) * U * total
    # independent float64 computation: each term within ~ u (10 + 4 kappa^2) A_f; safety 2
    ref = numpy_mixed_areas(c.V, c.F)
    for v in range(len(got)):
        tol = 2 * U * sum(c.face_area[f] * (10 + 4 * c.kappa[f] ** 2) for f in c.faces_at(v))
        assert abs(got[v] - ref[v]) <= tol


@pytest.mark.parametrize("name", list(MESHES))
def test_the_adapters_float_mixed_areas_are_the_exact_ones_rounded_in_double(name):
    """What angle_defects multiplies by: each vertex within the float64 error of its faces'
    terms (as above) of the exact areas, far inside vcg's single-precision error."""
    c = case(name)
    exact = exact_mixed_voronoi_areas(c.V, c.F)
    got = mixed_voronoi_areas(c.V, c.F)
    for v in range(len(exact)):
        tol = 2 * U * sum(c.face_area[f] * (10 + 4 * c.kappa[f] ** 2) for f in c.faces_at(v))
        assert abs(got[v] - exact[v]) <= tol
        assert tol < _area_error(c, v) / 100


def test_exact_mixed_areas_fallback_equals_the_reference_function():
    """The adapter's own rule (used only if ddg_oracle.reference.laplacian is missing) is the
    reference's vertex_areas_voronoi, exactly."""
    laplacian = pytest.importorskip("ddg_oracle.reference.laplacian")
    from ddg_oracle.oracles.pymeshlab import _mixed_areas_from_metric
    for name in MESHES:
        c = case(name)
        surface = PolyhedralSurface.from_arrays(c.V, c.F)
        ref = laplacian.vertex_areas_voronoi(surface)
        assert _mixed_areas_from_metric(surface.metric()) == ref
        assert exact_mixed_voronoi_areas(c.V, c.F, exact=True) == ref


# --- chapter 1: topology --------------------------------------------------------------


@pytest.mark.parametrize("name", list(MESHES))
def test_euler_characteristic_and_orientability(name):
    c = case(name)
    assert PML.euler_characteristic(c.V, c.F) == c.t.euler_characteristic()
    assert PML.is_orientable(c.V, c.F) is c.t.is_orientable()
    assert PML.genus(c.V, c.F) == c.t.classify().genus


def test_topological_measures_keys_and_hole_count():
    c = case("annulus(5)")
    d = PML.topological_measures(c.V, c.F)
    assert {"vertices_number", "edges_number", "faces_number", "boundary_edges",
            "number_holes", "connected_components_number", "genus", "is_mesh_two_manifold",
            "non_two_manifold_edges", "non_two_manifold_vertices",
            "unreferenced_vertices"} <= set(d)
    assert (d["number_holes"], d["boundary_edges"], d["genus"]) == (2, 10, 0)


def _closed(t):
    """A closed abstract surface with the strategies' distinct placeholder points."""
    from ddg_oracle.properties.strategies import extend_positions
    V = np.array([[float(x) for x in p] for p in extend_positions(t, ())])
    return V, np.array(t.to_face_list())


def test_finding_F_pymeshlab_1_library_genus_of_non_orientable_surfaces_is_half_the_crosscaps():
    """filter_measure.cpp computeTopologicalMeasures -> vcg Clean::MeshGenus:
    genus = -((V + F - E + holes - 2 C) / 2) with C++ integer division.  For h crosscaps
    that is h / 2 rounded toward zero: RP^2 0, Klein bottle 1, RP^2 # RP^2 # RP^2 1,
    Moebius strip 0.  The default adapter returns h = 2 - chi - holes instead."""
    from ddg_oracle.reference.combinatorics import connected_sum
    rp2 = surfaces.projective_plane()
    raw = PyMeshLab(genus="library")
    for t, h in ((rp2, 1), (surfaces.klein_bottle(), 2),
                 (connected_sum(connected_sum(rp2, rp2), rp2), 3)):
        V, F = _closed(t)
        assert t.classify().genus == h
        assert raw.genus(V, F) == h // 2
        assert PML.genus(V, F) == h
        assert PML.is_orientable(V, F) is False
    c = case("mobius_strip(5)")
    assert raw.genus(c.V, c.F) == 0 and PML.genus(c.V, c.F) == 1


CHAPTER1 = ["D1.6", "R1.5", "X1.4", "CS", "T1.1 / C1.2"]


@pytest.mark.parametrize("pid", CHAPTER1)
def test_chapter1_properties_pass(pid):
    r = run_property(PROPERTIES[pid], PML, profile("default"))
    assert r.status == PASSED, r.failure or r.error


def test_R1_6_is_not_applicable_without_boundary_loop_lists():
    # PyMeshLab reports the number of holes, never the loops' vertices
    assert run_property(PROPERTIES["R1.6"], PML, profile("default")).status == NOT_APPLICABLE


# --- chapter 2: area and angle defects ---------------------------------------------------


@pytest.mark.parametrize("name", list(MESHES))
def test_area(name):
    """filter_measure.cpp: ``float Area = Stat::ComputeMeshArea(m)`` -- the double sum of
    the cross-product norms is rounded to float32: within u32 A (plus the double sum's
    u (6 + kappa_f) A_f per face), safety 2."""
    c = case(name)
    want = float(c.metric.total_area())
    tol = 2 * (U32 * want + U * float(np.sum(c.face_area * (6 + c.kappa))))
    got = PML.area(c.V, c.F)
    assert abs(got - want) <= tol
    assert got == float(np.float32(got))                  # it really is a float32


@pytest.mark.parametrize("name", ORIENTABLE)
def test_angle_defects(name):
    c = case(name)
    want = exact_angle_defects(c)
    got = PML.angle_defects(c.V, c.F)
    areas = exact_mixed_voronoi_areas(c.V, c.F)
    for v in range(c.t.n_vertices):
        d = len(c.faces_at(v))
        r_area = _area_error(c, v) / areas[v]             # relative error of vcg's area
        defect_error = 3 * U32 * math.pi * d + math.sqrt(8 * U) + 4 * U * math.pi * (d + 2)
        tol = 2 * (defect_error * (1 + r_area) + abs(want[v]) * r_area)
        assert abs(got[v] - want[v]) <= tol, (v, got[v], want[v], tol)


@pytest.mark.parametrize("name", ["disk(6)", "grid(3,3)", "annulus(5)", "disk(3)"])
def test_finding_F_pymeshlab_2_library_boundary_term_is_2pi_minus_sum_minus_boundary_angle(name):
    """curvature.h MeanAndGaussian: at a boundary vertex KG = 2 pi - sum - phi, phi the
    angle in R^3 between the two boundary edges.  On planar convex boundary vertices
    (phi = sum) that is twice the turning angle pi - sum, not the turning angle (R2.4)."""
    c = case(name)
    raw = PyMeshLab(boundary="library").angle_defects(c.V, c.F)
    ref = PML.angle_defects(c.V, c.F)
    phi = boundary_edge_angles(c.V, c.F)
    want = exact_angle_defects(c)
    planar = not c.V[:, 2].any()
    assert planar
    for v in range(c.t.n_vertices):
        if v in phi:
            assert raw[v] - ref[v] == pytest.approx(math.pi - phi[v], abs=4 * U * math.pi)
            # float32 angles: within 3 u32 pi per corner (module doc), safety 2
            tol = 2 * 3 * U32 * math.pi * (len(c.faces_at(v)) + 1)
            if want[v] >= 0:              # convex (or straight) corner: phi = angle sum
                assert abs(raw[v] - 2 * want[v]) <= tol
            else:                         # reflex corner: phi = 2 pi - angle sum
                assert abs(raw[v]) <= tol
        else:
            assert raw[v] == ref[v]


@pytest.mark.parametrize("n", [3, 5])
def test_finding_F_pymeshlab_3_boundary_term_follows_face_orientation_on_a_mobius_strip(n):
    """vcg subtracts phi at vertex V(i) of each border edge i of a face, i.e. at the tail
    of the edge in that face's orientation.  On a Moebius strip the orientation flips,
    so one boundary vertex gets phi twice and another none: the angle defect there is
    off by its phi, whichever boundary convention the adapter applies.  Minimal case:
    ``mobius_strip(3)`` (6 faces), vertices 0 (none) and 3 (twice)."""
    c = Case(arrays=surfaces.mobius_strip(n).to_arrays())
    V, F = c.V, c.F
    want = exact_angle_defects(c)
    got = PML.angle_defects(V, F)
    raw = PyMeshLab(boundary="library").angle_defects(V, F)
    phi = boundary_edge_angles(V, F)
    off = {v: got[v] - want[v] for v in range(2 * n) if abs(got[v] - want[v]) > 1e-5}
    assert set(off) == {0, n}
    angle_sum = {v: math.pi - want[v] for v in (0, n)}
    # vertex 0 (tail of neither of its border edges in their faces' order): nothing subtracted
    assert raw[0] == pytest.approx(2 * math.pi - angle_sum[0], abs=1e-5)
    # vertex n (tail of both of its border edges): phi subtracted twice
    assert raw[n] == pytest.approx(2 * math.pi - angle_sum[n] - 2 * phi[n], abs=1e-5)
    assert off[0] == pytest.approx(phi[0], abs=1e-5)
    assert off[n] == pytest.approx(-phi[n], abs=1e-5)


def test_finding_F_pymeshlab_4_curvature_is_zeroed_below_an_absolute_area_threshold():
    """curvature.h:513: ``if (A <= numeric_limits<ScalarType>::epsilon()) KG = KH = 0``
    compares an absolute mixed area with a relative epsilon (2.2e-16 in this double
    build).  The tetrahedron scaled by 1e-9 (mixed areas ~ 1e-19) gets angle defect 0
    at every vertex instead of pi/2, 7 pi/6, ...; scaled by 1e-7 it is right."""
    c = case("tetrahedron")
    want = exact_angle_defects(c)
    small = PML.angle_defects(c.V * 1e-9, c.F)
    assert np.all(small == 0) and np.all(want > 1)
    np.testing.assert_allclose(PML.angle_defects(c.V * 1e-7, c.F), want, rtol=0, atol=1e-5)


def test_finding_F_pymeshlab_5_single_precision_overflow_and_underflow():
    """Squared edge lengths are ``float`` in MeanAndGaussian (curvature.h:434) and the total
    area is ``float Area`` (filter_measure.cpp:424): the tetrahedron scaled by 1e20 has area
    2.4e40 > FLT_MAX, reported as inf, and its angle defects as 0; scaled by 1e-20 the
    area 2.4e-40 is a float32 subnormal with only ~5 significant digits."""
    c = case("tetrahedron")
    want = float(c.metric.total_area())
    assert PML.area(c.V * 1e20, c.F) == math.inf
    assert np.all(PML.angle_defects(c.V * 1e20, c.F) == 0)
    tiny = PML.area(c.V * 1e-20, c.F)
    assert 1e-7 < abs(tiny / (want * 1e-40) - 1) < 1e-4


def test_mean_curvature_is_half_the_cotan_laplacian_of_positions_over_mixed_area():
    """Not a protocol quantity: vcg's KH = sign((L X)_v . n_v) |(L X)_v| / (2 A_v), L the
    reference's positive semidefinite cotan Laplacian (TDContr = 1/2 (L X)), A_v vcg's
    mixed area, n_v vcg's area-weighted vertex normal.  Checked on the icosahedron
    (convex, outward faces: KH > 0)."""
    c = case("icosahedron")
    KH = PML.discrete_curvature(c.V, c.F, "Mean Curvature")
    L = np.zeros((c.t.n_vertices, c.t.n_vertices))
    for f, face in enumerate(c.t.faces):
        for k in range(3):
            i, j = face[(k + 1) % 3], face[(k + 2) % 3]
            w = float(c.metric.corner_cot(f, k)) / 2
            L[i, j] -= w
            L[j, i] -= w
            L[i, i] += w
            L[j, j] += w
    LX = np.linalg.norm(L @ c.V, axis=1)
    A = exact_mixed_voronoi_areas(c.V, c.F)
    assert np.all(KH > 0)
    for v in range(c.t.n_vertices):
        fs = c.faces_at(v)
        # each cot within 3 u32 pi (1 + kappa^2), times |e| / 4 per side, two sides per face
        d_contr = sum(3 * U32 * math.pi * (1 + c.kappa[f] ** 2) * 2 * math.sqrt(
            4 * c.face_area[f] * c.kappa[f]) / 4 for f in fs)
        r_area = _area_error(c, v) / A[v]
        tol = 2 * (2 * d_contr * (1 + r_area) + LX[v] * r_area) + 64 * U * LX[v]
        assert abs(2 * KH[v] * A[v] - LX[v]) <= tol


# --- guards ---------------------------------------------------------------------------


def test_planar_flip_to_delaunay_flips_a_non_delaunay_quadrilateral_in_place():
    # a kite whose long diagonal 0-2 is not Delaunay (both opposite angles obtuse): one flip
    V = np.array([[0.0, 0, 0], [2, -1, 0], [4, 0, 0], [2, 1, 0]])
    F = np.array([[0, 1, 2], [0, 2, 3]])
    got = PyMeshLab().planar_flip_to_delaunay(V, F)        # vertices unmoved: checked inside
    assert sorted(sorted(f) for f in got.tolist()) == [[0, 1, 3], [1, 2, 3]]
    # already Delaunay: nothing changes (the stopping rule is met before the first pop)
    assert np.array_equal(PyMeshLab().planar_flip_to_delaunay(V, got), got)


def test_planar_flip_to_delaunay_refuses_points_off_the_plane():
    V = np.array([[0.0, 0, 0], [2, -1, 0], [4, 0, 0], [2, 1, 1e-9]])
    with pytest.raises(ValueError, match="z = 0"):
        PyMeshLab().planar_flip_to_delaunay(V, np.array([[0, 1, 2], [0, 2, 3]]))


def test_options_are_checked():
    with pytest.raises(ValueError, match="boundary"):
        PyMeshLab(boundary="whatever")
    with pytest.raises(ValueError, match="genus"):
        PyMeshLab(genus="whatever")


def test_non_finite_coordinates_raise_instead_of_aborting():
    """compute_scalar_by_discrete_curvature_per_vertex aborts the process (glibc "double
    free or corruption", SIGABRT) on a NaN or infinite coordinate; the adapter checks."""
    c = case("tetrahedron")
    for bad in (math.nan, math.inf):
        V = c.V.copy()
        V[0, 0] = bad
        with pytest.raises(ValueError, match="NaN or infinite"):
            PML.angle_defects(V, c.F)


def test_unreferenced_vertex_is_reported_not_silently_dropped():
    """The curvature filter deletes unreferenced vertices (RemoveUnreferencedVertex), which
    would shift every later index; the adapter notices the changed vertex list."""
    c = case("tetrahedron")
    V = np.vstack([c.V, [[5.0, 5.0, 5.0]]])
    with pytest.raises(VertexOrderChanged):
        PML.discrete_curvature(V, c.F)


def test_runs_in_a_worker_process():
    from ddg_oracle.application.isolation import Isolated
    c = case("annulus(5)")
    with Isolated("ddg_oracle.oracles.pymeshlab:PyMeshLab", timeout=60) as impl:
        assert impl.euler_characteristic(c.V, c.F) == 0
        assert impl.genus(c.V, c.F) == 0
