"""The potpourri3d adapter agrees with the exact reference within the properties' derived bounds;
bad input is refused before it reaches geometry-central (a negative index segfaults there).

Needs the ``peers`` extra (``pip install -e '.[peers]'``; the ``test`` extra includes it).
"""

from __future__ import annotations

import numpy as np
import pytest

pp3d = pytest.importorskip("potpourri3d")

from ddg_oracle.oracles.potpourri3d import Potpourri3d  # noqa: E402
from ddg_oracle.properties import check_implementation  # noqa: E402
from ddg_oracle.protocol.methods import capabilities  # noqa: E402
from tests import peer_checks as pc  # noqa: E402

PP = Potpourri3d()


@pytest.mark.parametrize("name", list(pc.MESHES))
def test_euler_characteristic_area_laplacian_and_barycentric_areas(name):
    pc.check_euler_characteristic(PP, name)
    pc.check_area(PP, name)
    pc.check_cotan_laplacian(PP, name)
    pc.check_vertex_areas(PP, name, "barycentric")     # no property checks it: L3.7 needs voronoi


def test_cotan_factor_is_one_half_on_a_unit_right_triangle():
    """mesh.py l. 200: ``cotans = 0.5 * dots / cross_mags`` per corner, the diagonal +, the
    off-diagonal - (l. 204-215): already the reference's L (positive semidefinite)."""
    V = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    F = np.array([[0, 1, 2]])
    np.testing.assert_allclose(PP.cotan_laplacian(V, F).toarray(),
                               [[1, -0.5, -0.5], [-0.5, 0.5, 0], [-0.5, 0, 0.5]],
                               rtol=0, atol=4 * 2.0 ** -53)


def test_capabilities_are_what_potpourri3d_computes():
    assert capabilities(PP) == {"euler_characteristic", "area", "cotan_laplacian",
                                "vertex_areas_barycentric"}


def test_bad_input_raises_a_value_error_before_potpourri3d():
    """potpourri3d.edges passes F to geometry-central's SurfaceMesh unchecked: a negative index
    is a SIGSEGV there (docs/conventions.md); validate_mesh only checks shapes."""
    V, F = pc.arrays("tetrahedron")
    W = V.copy()
    W[2, 0] = np.inf
    for bad in [(V, np.array([[0, 1, 9], [0, 1, 2]])), (V, np.array([[0, 1, -1], [0, 1, 2]])),
                (W, F), (V, F[:, :2]), (V, np.zeros((0, 3), dtype=np.int64))]:
        for method in sorted(capabilities(PP)):
            with pytest.raises(ValueError):
                getattr(PP, method)(*bad)


def test_a_negative_index_crashes_potpourri3d_edges_in_a_worker():
    """The isolation layer reports the crash of the raw library call as such."""
    from ddg_oracle.application.isolation import ImplementationCrashed, Isolated
    V, F = pc.arrays("tetrahedron")
    with Isolated("tests.test_oracles_potpourri3d:RawEdges", timeout=60) as impl:
        assert impl.euler_characteristic(V, F) == 2
        with pytest.raises(ImplementationCrashed, match="SIGSEGV"):
            impl.euler_characteristic(V, np.array([[0, 1, 2], [0, 1, -1]]))


class RawEdges:
    """potpourri3d.edges without the adapter's check (for the crash test above only)."""

    name = "raw potpourri3d.edges"

    def euler_characteristic(self, V, F):
        return len(V) - len(pp3d.edges(V, F)) + len(F)


def test_every_applicable_property_passes():
    results = check_implementation(PP, profile="default", seed=0)     # reproducible
    assert {r.property_id for r in results if r.status == "passed"} >= {"D3.1", "D1.6", "T3.9"}
