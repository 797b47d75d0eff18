"""Adobe Lagrange (``import lagrange``; PyPI ``adobe-lagrange``, the C++ library
adobe/lagrange with nanobind bindings) in its own conventions.

Every method builds a fresh ``lagrange.SurfaceMesh`` from (V, F) (``add_vertices``,
``add_triangles``: Lagrange's ``SurfaceMesh<double, uint32_t>``) and calls the Lagrange
function that computes the quantity; the numbers compared are Lagrange's.  Sources:
``adobe/lagrange`` at 6.43.0 (commit ``771d8588``, the newest public sync; the wheel is
6.49.0, built from internal commit ``c6f2517e``: every convention below was also
measured on the wheel by ``tests/test_oracles_lagrange.py``).  Paths are under
``modules/core`` unless they say ``polyddg``.

Lagrange's conventions are the notes' where it has the quantity; nothing is declared:

* ``euler_characteristic``: ``lagrange.compute_euler`` = #V - #E + #F over *all* vertices
  (``src/topology.cpp`` l. 35-48): a vertex of no face counts 1, as the protocol.
* ``boundary_loops``: ``lagrange.extract_boundary_loops`` (``src/extract_boundary_loops.cpp``
  l. 32-53): the boundary edges, each directed as ``get_edge_vertices`` gives it (as it
  runs in its one face), chained by ``chain_directed_edges`` (``src/utils/chain_edges.cpp``
  l. 50-245); only the closed *loops* are returned, open chains are dropped with a warning
  (l. 47-53 of the first file): F-lagrange-1.
* ``area``: ``lagrange.compute_mesh_area`` (``src/compute_area.cpp`` l. 271-302): the sum of
  ``triangle_area_3d`` (``include/lagrange/utils/triangle_area.h`` l. 28-36: half the norm
  of the cross product of the edge *differences* a - b, a - c).
* ``cotan_laplacian``: ``polyddg.DifferentialOperators(mesh).laplacian(beta=1)`` (de Goes,
  Butts, Desbrun 2020), ``d0^T M1 d0`` (``polyddg/src/DifferentialOperators.cpp``
  l. 501-506) with the per-face 1-form inner product ``M1_f = area U_f^T U_f + lambda
  P_f^T P_f`` (l. 400-436, l. 419); ``U_f`` the sharp (l. 915-942: ``a x (m_e - c) /
  |a|^2``, ``a`` the face's vector area), ``P_f = I - V_f U_f`` (l. 947-958).  On a
  triangle ``U_f d0 u`` is the gradient of the linear interpolant and ``P_f d0 u = 0``, so
  ``u^T L u = sum_f area |grad u|^2`` for every lambda: L is the notes' cotan Laplacian,
  positive semidefinite, weights 1/2 (cot a + cot b) -- no declaration (the lambda term adds
  only roundings, which give an exactly-zero weight a sign: F-lagrange-4; ``beta`` is the
  Python name of lambda).  A vertex of no face has a zero row (the matrix is #V x #V).
* ``vertex_areas_barycentric``: the diagonal of ``DifferentialOperators.star0()`` =
  ``inner_product_0_form`` (l. 368-396): ``|a_f| / facet_size`` per corner (l. 389), A / 3
  on triangles.
* ``area_gradient``: ``laplacian() @ V`` (T3.9; positive semidefinite: no sign change).
* Both polyddg quantities take the face's area from its *vector area*
  ``compute_facet_vector_area`` (``src/compute_area.cpp`` l. 324-363): ``1/2 sum p_i x
  p_{i+1}`` on absolute coordinates (l. 355-356), not on differences like ``area``
  (F-lagrange-2).

Option ``Lagrange(dihedral="reference")`` (the default): ``lagrange.compute_dihedral_angles``
is the *unsigned* angle between the two faces' unit normals, ``atan2(|n0 x n1|, n0 . n1)``
in [0, pi] (``src/compute_dihedral_angles.cpp`` l. 71-76, ``include/lagrange/utils/
geometry3d.h`` ``angle_between``), 0 on a boundary edge (l. 59-62) and 2 pi on an edge of
three or more faces (l. 64-69): it cannot tell a convex edge from a reflex one, and the
vocabulary has no "unsigned" convention to declare.  ``edge_mean_curvature`` gives the
angle the sign of ``(n0 x n1) . e`` (Lagrange's own facet normals, kept by
``keep_facet_normals=True``; e the edge as it runs in the first face, positive where
convex for outward faces), as the gpytoolbox adapter does; l(e) from
``lagrange.compute_edge_lengths``.  ``dihedral="library"`` keeps the unsigned angle
(F-lagrange-3).

Not adapted (Lagrange has no such function): corner angles and angle defects (no binding;
``polyddg.compute_principal_curvatures`` is the de Goes shape operator's eigenvalues, not an
angle defect), Voronoi areas, orientability and genus (``lagrange.is_oriented`` says
whether the faces are *consistently oriented* -- every interior edge used once each way,
``src/orientation.cpp`` l. 31-79 -- not whether the surface is orientable), the Dirichlet
problem and the intrinsic Delaunay methods.

>>> import numpy as np
>>> V = np.array([[0., 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
>>> F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
>>> Lagrange().euler_characteristic(V, F), Lagrange().boundary_loops(V, F[1:])
(2, [[0, 1, 2]])
"""

from __future__ import annotations

import numpy as np
import scipy.sparse

import lagrange
from lagrange import polyddg

from ..protocol.arrays import checked_arrays
from .conventions import declare

#: option -> (finding, what the library's own convention differs by) (docs/findings.md)
LIBRARY_CONVENTIONS = {
    "dihedral": ("F-lagrange-3", "compute_dihedral_angles: unsigned, reflex edges count as "
                                 "convex"),
}

#: this adapter as ``ddg-oracle check --impl lagrange`` finds it (read without importing the
#: module: ddg_oracle.application.implementations): the object, the library it needs, the pip extra
#: that installs it, its place in reports
ADAPTER = {"name": "lagrange", "object": "Lagrange", "library": "lagrange",
                   "extra": "lagrange", "rank": 12}


def _mesh(V, F):
    """(Lagrange's SurfaceMesh of (V, F), V, F) after the adapters' input checks."""
    V, F = checked_arrays(V, F)
    m = lagrange.SurfaceMesh()
    m.add_vertices(np.ascontiguousarray(V, dtype=np.float64))
    m.add_triangles(np.ascontiguousarray(F, dtype=np.uint32))
    return m, V, F


def _attribute(m, attribute_id) -> np.ndarray:
    return np.array(m.attribute(attribute_id).data, dtype=np.float64)


class Lagrange:
    """Adobe Lagrange as an implementation of the protocol (``protocol/methods.py``)."""

    name = "lagrange"

    def __init__(self, dihedral: str = "reference"):
        self.name, self.conventions = declare("lagrange", LIBRARY_CONVENTIONS,
                                              dihedral=dihedral)
        self.dihedral = dihedral

    def __repr__(self) -> str:
        return f"Lagrange(dihedral={self.dihedral!r})"

    # --- chapter 1: topology ------------------------------------------------------------

    def euler_characteristic(self, V, F) -> int:
        """``lagrange.compute_euler(mesh)``: #V - #E + #F, every vertex counted."""
        m, _, _ = _mesh(V, F)
        return int(lagrange.compute_euler(m))

    def boundary_loops(self, V, F) -> list[list[int]]:
        """``lagrange.extract_boundary_loops(mesh)``, unchanged (F-lagrange-1: chains that
        do not close as directed edges are dropped)."""
        m, _, _ = _mesh(V, F)
        return [[int(v) for v in loop] for loop in lagrange.extract_boundary_loops(m)]

    # --- chapter 2: curvature -----------------------------------------------------------

    def edge_mean_curvature(self, V, F) -> dict[tuple[int, int], float]:
        """{(i, j): 1/2 theta l} over the edges of exactly two faces: theta from
        ``compute_dihedral_angles`` (unsigned), signed with dihedral="reference" by Lagrange's
        facet normals (module doc); l from ``compute_edge_lengths``."""
        m, _, _ = _mesh(V, F)
        normal_name = "@ddg_facet_normal"
        theta = _attribute(m, lagrange.compute_dihedral_angles(
            m, facet_normal_attribute_name=normal_name, keep_facet_normals=True))
        N = _attribute(m, m.get_attribute_id(normal_name)).reshape(-1, 3)
        length = _attribute(m, lagrange.compute_edge_lengths(m))
        X = np.asarray(m.vertices, dtype=np.float64)
        out = {}
        for e in range(m.num_edges):
            corners = [int(c) for c in m.corners_around_edge(e)]
            if len(corners) != 2:
                continue                        # boundary (0) or non-manifold (2 pi)
            i, j = (int(v) for v in m.get_edge_vertices(e))
            if i == j:
                continue
            t = float(theta[e])
            if self.dihedral == "reference":
                c0 = corners[0]
                f0, f1 = m.get_corner_facet(c0), m.get_corner_facet(corners[1])
                a = int(m.get_corner_vertex(c0))        # the edge as it runs in f0: a -> b
                b = j if a == i else i
                side = float(np.cross(N[f0], N[f1]) @ (X[b] - X[a]))
                t = -t if side < 0 else t
            out[(min(i, j), max(i, j))] = 0.5 * t * float(length[e])
        return out

    def area(self, V, F) -> float:
        """``lagrange.compute_mesh_area(mesh)``: the sum of the facet areas."""
        m, _, _ = _mesh(V, F)
        return float(lagrange.compute_mesh_area(m))

    # --- chapter 3: Laplacian and mass --------------------------------------------------

    def cotan_laplacian(self, V, F) -> scipy.sparse.csr_matrix:
        """``polyddg.DifferentialOperators(mesh).laplacian()`` (beta = lambda = 1), unchanged:
        positive semidefinite, the notes' weights on triangles (module doc)."""
        m, _, _ = _mesh(V, F)
        ops = polyddg.DifferentialOperators(m)      # keeps a reference to m: m stays alive
        return scipy.sparse.csr_matrix(ops.laplacian(), dtype=np.float64)

    def area_gradient(self, V, F) -> np.ndarray:
        """``laplacian() @ V`` (positive semidefinite: the area gradient itself)."""
        m, V, _ = _mesh(V, F)
        ops = polyddg.DifferentialOperators(m)
        return np.asarray(ops.laplacian() @ V, dtype=np.float64)

    def vertex_areas_barycentric(self, V, F) -> np.ndarray:
        """Diagonal of ``polyddg.DifferentialOperators(mesh).star0()``: |vector area| / 3 of
        each incident triangle; 0 at a vertex of no face."""
        m, _, _ = _mesh(V, F)
        ops = polyddg.DifferentialOperators(m)
        return np.asarray(ops.star0().diagonal(), dtype=np.float64)
