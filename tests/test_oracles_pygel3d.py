"""PyGEL3D (ddg_oracle.oracles.pygel3d) in its own conventions: the pointwise Gaussian
curvature declared (``curvature=per_mixed_area``), GEL's vertex numbering mapped back to
the input's, 0 at boundary vertices (F-pygel3d-1) and face areas from absolute
coordinates (F-pygel3d-2).

Needs ``pip install -e '.[pygel3d]'``."""

from __future__ import annotations

import numpy as np
import pytest

hmesh = pytest.importorskip("pygel3d.hmesh")

from ddg_oracle.oracles.exact_reference import ReferenceImplementation  # noqa: E402
from ddg_oracle.oracles.pygel3d import Pygel3d  # noqa: E402
from ddg_oracle.properties.conventions import declared, to_reference  # noqa: E402
from ddg_oracle.protocol.methods import OutsideDomain  # noqa: E402

from tests.property_checks import every_property_unshrunk  # noqa: E402

V = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0.2, 0.2, 0.1]])   # obtuse faces too
F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
REF = ReferenceImplementation()


def test_every_applicable_property_passes_except_F_pygel3d_2():
    results = every_property_unshrunk(Pygel3d(), 1)
    failed = {r.property_id for r in results
              if r.status not in ("passed", "not applicable", "tie disagreement")}
    assert failed <= {"D2.2", "T2.6", "R2.2", "X2.1", "T2.5", "L3.7"}, failed
    passed = {r.property_id for r in results if r.status == "passed"}
    assert {"D1.6", "X1.4", "CS"} <= passed
    for r in results:
        if r.status == "FAILED":          # F-pygel3d-2: faces far from the origin for their size
            # GEL's shoelace sum on absolute coordinates loses relative precision as
            # (distance / size)^2: near the origin too, for faces tiny beside their distance
            # (drawn failures: ratios 3e4 to 9e8, GEL's own areas failing L3.7 on them)
            Vf, Ff = (np.asarray(x, dtype=float) for x in r.failure.mesh)
            ratio = max(np.linalg.norm(Vf[f].mean(axis=0))
                        / max(np.linalg.norm(Vf[f[1]] - Vf[f[0]]),
                              np.linalg.norm(Vf[f[2]] - Vf[f[0]]))
                        for f in Ff.astype(int))
            assert ratio >= 16, (r.property_id, ratio)
            # the error grows as eps ratio^2; a wrong formula would be off by O(1)
            error = abs(r.failure.observed - r.failure.expected)
            assert error < min(1e-12 * ratio ** 2, 1e-3), (r.property_id, ratio, error)


def test_pointwise_curvature_times_the_mixed_area_is_the_angle_defect():
    """curvature.cpp l. 155-175: (2 pi - angle sum) / mixed_area(v); declared, and mapped."""
    impl = Pygel3d()
    assert [c.name for c in declared(impl)] == ["curvature=per_mixed_area"]
    K = impl.angle_defects(V, F)
    np.testing.assert_allclose(to_reference(declared(impl), "angle_defects", K, V, F),
                               REF.angle_defects(V, F), atol=1e-14)
    np.testing.assert_allclose(impl.vertex_areas_voronoi(V, F), REF.vertex_areas_voronoi(V, F),
                               rtol=1e-14)


def test_gel_renumbers_vertices_and_the_adapter_maps_them_back():
    m = hmesh.Manifold.from_triangles(V, F)
    assert not np.array_equal(m.positions(), V)              # first appearance in F: 0, 2, 1, 3
    W = np.vstack([[9.0, 9, 9], V])                          # an unused vertex 0: GEL drops it
    np.testing.assert_allclose(Pygel3d().vertex_areas_voronoi(W, F + 1)[1:],
                               REF.vertex_areas_voronoi(V, F), rtol=1e-14)
    assert Pygel3d().euler_characteristic(W, F + 1) == 3
    flipped = F.copy()
    flipped[3] = flipped[3, ::-1]                            # GEL splits vertices: declined
    with pytest.raises(OutsideDomain):
        Pygel3d().angle_defects(V, flipped)


def test_finding_F_pygel3d_1_zero_at_boundary_vertices():
    open_F = F[1:]
    with pytest.raises(OutsideDomain):
        Pygel3d().angle_defects(V, open_F)
    K = Pygel3d(boundary="library").angle_defects(V, open_F)
    exact = REF.angle_defects(V, open_F)
    for v in (0, 1, 2):                                      # the boundary vertices
        assert K[v] == 0 and abs(exact[v]) > 0.1
    assert Pygel3d(boundary="library").name == "pygel3d(boundary='library')"


def test_finding_F_pygel3d_2_face_areas_lose_precision_far_from_the_origin():
    """Manifold.cpp l. 1662-1681: ``area_normal`` sums d x s with s = p_i + p_(i+1), absolute
    positions (the centroid c is computed, l. 1666-1672, and never used)."""
    T = np.array([[0.0, 0, 0], [1, 0.1, 0.2], [0.3, 0.9, 0.4]])
    G = np.array([[0, 1, 2]])
    near = Pygel3d().area(T, G)
    far = Pygel3d().area(T + 1e6, G)
    exact = REF.area(T + 1e6, G)
    assert abs(near - REF.area(T, G)) <= 2e-16
    assert 1e-12 < abs(far - exact) / exact < 1e-9                  # 6e-11 measured
