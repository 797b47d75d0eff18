"""mouette (``import mouette as M``, pure Python / numpy; GCoiffier/mouette) in its own
conventions.

Every method builds ``M.mesh.from_arrays(V, F=F)`` afresh (mouette caches attributes on the
mesh: a cached ``"angles"`` attribute changes how ``cotangent`` computes, see below) and
calls the mouette function that computes the quantity.  Sources: the installed package,
mouette 1.2.8 (the files ``mouette/...`` of ``GCoiffier/mouette``).

mouette's conventions are the notes' where it has the quantity:

* ``angle_defects``: ``M.attributes.angle_defects(mesh)`` starts every vertex at 2 pi, sets
  the boundary vertices to pi (``zero_border=False``, the default) and subtracts the corner
  angles (``attributes/attr_vertices.py`` l. 63-74): pi - angle sum at boundary vertices,
  2 pi at a vertex of no face -- the reference's (R2.4).  No declaration.
* ``cotan_laplacian``: ``M.operators.laplacian(mesh)`` adds ``cot / 2`` per corner to
  (i, i), (j, j) and ``-cot / 2`` to (i, j), (j, i) (``operators/laplacian_op.py``
  l. 74-89): positive semidefinite, the notes' 1/2 (cot a + cot b).  The matrix is built
  without a shape (``sp.csc_matrix((coeffs, (rows, cols)))``), so it has max F + 1 rows:
  the adapter pads it with zero rows to #V (a vertex of no face, the protocol's value).
* ``corner_angles``: ``M.attributes.corner_angles`` (``atan2(|BA x BC|, BA . BC)``,
  ``geometry/geometry.py`` l. 130-145), corner c of face f at index 3 f + c.
* ``euler_characteristic``: ``M.attributes.euler_characteristic`` = #V - #E + #F over all
  vertices (an unused one counts 1, as the protocol).
* ``boundary_loops``: ``M.processing.border.extract_border_cycle_all`` (F-mouette-2).
* ``area``: ``M.attributes.total_area`` (cross products, summed in order).

``M.operators.area_weight_matrix(mesh)`` ("diagonal matrix of vertex areas") adds the
*whole* area of every incident face to each of its vertices (``operators/mass.py``
l. 21-27): three times the barycentric area (F-mouette-1).  ``Mouette(mass="reference")``
(the default) declares it, ``conventions = "mouette"`` (``mass=whole_area``), and
ddg-oracle divides by 3; ``mass="library"`` declares nothing of it (the finding, for
``--expect-conventions``).

>>> import numpy as np
>>> V = np.array([[0., 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
>>> F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
>>> Mouette().euler_characteristic(V, F), round(float(Mouette().angle_defects(V, F).sum() / np.pi), 12)
(2, 4.0)
"""

from __future__ import annotations

import numpy as np
import scipy.sparse

import mouette as M
from mouette.processing.border import extract_border_cycle_all

from ..protocol.arrays import checked_arrays
from .conventions import declare

#: option -> (finding, what the library's own convention differs by) (docs/findings.md)
LIBRARY_CONVENTIONS = {
    "mass": ("F-mouette-1", "area_weight_matrix: the whole area of each incident face (3x)"),
}

#: this adapter as ``ddg-oracle check --impl mouette`` finds it (read without importing the
#: module: ddg_oracle.application.implementations): the object, the library it needs, the pip extra that
#: installs it, its place in reports
ADAPTER = {"name": "mouette", "object": "Mouette", "library": "mouette", "extra": "mouette",
           "rank": 10}


def _mesh(V, F):
    V, F = checked_arrays(V, F)
    return M.mesh.from_arrays(V, F=F), len(V), len(F)


def _padded(A, n: int) -> scipy.sparse.csr_matrix:
    A = scipy.sparse.coo_matrix(A)
    return scipy.sparse.csr_matrix((A.data, (A.row, A.col)), shape=(n, n), dtype=np.float64)


class Mouette:
    """mouette as an implementation of the protocol (``protocol/methods.py``)."""

    name = "mouette"

    def __init__(self, mass: str = "reference"):
        self.name, self.conventions = declare("mouette", LIBRARY_CONVENTIONS, mass=mass)
        if mass == "reference":
            self.conventions = "mouette"          # the vocabulary's mass=whole_area
        self.mass = mass

    def __repr__(self) -> str:
        return f"Mouette(mass={self.mass!r})"

    # --- chapter 1: topology ------------------------------------------------------------

    def euler_characteristic(self, V, F) -> int:
        """``M.attributes.euler_characteristic``: len(vertices) - len(edges) + len(faces)."""
        m, _, _ = _mesh(V, F)
        return int(M.attributes.euler_characteristic(m))

    def boundary_loops(self, V, F) -> list[list[int]]:
        """``M.processing.border.extract_border_cycle_all(mesh)``, unchanged."""
        m, _, _ = _mesh(V, F)
        return [[int(v) for v in loop] for loop in extract_border_cycle_all(m)]

    # --- chapter 2: curvature -----------------------------------------------------------

    def corner_angles(self, V, F) -> np.ndarray:
        """``M.attributes.corner_angles(mesh)``: (m, 3), column c the angle at F[f, c]."""
        m, _, nf = _mesh(V, F)
        a = M.attributes.corner_angles(m, persistent=False)
        return np.asarray(a.as_array(3 * nf), dtype=np.float64).reshape(nf, 3)

    def angle_defects(self, V, F) -> np.ndarray:
        """``M.attributes.angle_defects(mesh)``: 2 pi - angle sum, pi - angle sum at
        boundary vertices (its default ``zero_border=False``)."""
        m, n, _ = _mesh(V, F)
        return np.asarray(M.attributes.angle_defects(m, persistent=False).as_array(n),
                          dtype=np.float64)

    def area(self, V, F) -> float:
        """``M.attributes.total_area(mesh)``."""
        m, _, _ = _mesh(V, F)
        return float(M.attributes.total_area(m))

    # --- chapter 3: Laplacian and mass --------------------------------------------------

    def cotan_laplacian(self, V, F) -> scipy.sparse.csr_matrix:
        """``M.operators.laplacian(mesh)`` (cotan=True), padded to #V rows."""
        m, n, _ = _mesh(V, F)
        return _padded(M.operators.laplacian(m), n)

    def area_gradient(self, V, F) -> np.ndarray:
        """``M.operators.laplacian(mesh) @ V`` (positive semidefinite: no sign change)."""
        V, F = checked_arrays(V, F)
        return np.asarray(self.cotan_laplacian(V, F) @ V, dtype=np.float64)

    def vertex_areas_barycentric(self, V, F) -> np.ndarray:
        """Diagonal of ``M.operators.area_weight_matrix(mesh)``: the whole incident area
        (declared with mass="reference"; F-mouette-1)."""
        m, n, _ = _mesh(V, F)
        A = np.zeros(n)
        d = np.asarray(M.operators.area_weight_matrix(m).diagonal(), dtype=np.float64)
        A[:len(d)] = d
        return A
