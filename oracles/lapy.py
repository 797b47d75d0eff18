"""LaPy (``import lapy``, numpy / scipy; Deep-MI/LaPy) in its own conventions.

Every method builds ``lapy.TriaMesh(V, F)`` and calls the LaPy function that
computes the quantity; the numbers compared are LaPy's.  Sources: the installed
``lapy/tria_mesh.py`` and ``lapy/solver.py`` of LaPy 1.7.0 (pure Python, the files
of ``Deep-MI/LaPy``).

Conventions (declared, ``conventions = "lapy"``: ``unused_vertices=dropped``)
--------------------------------------------------------------------------------
LaPy's per-vertex answers and matrices are not indexed by the rows of V: ``Solver``
assembles ``sparse.csc_matrix((data, (i, j)))`` with no shape (``solver.py``
``_fem_tria``), so its matrices are (max F + 1) x (max F + 1), a vertex used by no face
below the largest index gets a zero row, one above it no row at all;
``TriaMesh.vertex_areas`` is a ``np.bincount`` (same length).  LaPy's remedy is
``TriaMesh.rm_free_vertices_()`` ("They can produce problems when constructing, e.g.,
Laplace matrices", ``tria_mesh.py``), which renumbers the used vertices in order.  The
adapter calls it before every per-vertex method and declares the vocabulary's
``unused_vertices=dropped``; ddg-oracle puts the answers back on every row of V.

The same declaration covers ``TriaMesh.euler()``, which counts only the vertices some
triangle uses ("v can contain unused vertices so we get vnum from trias"); the protocol
counts an unused vertex as a point, and ddg-oracle adds their number.

* ``cotan_laplacian``: ``Solver(mesh).stiffness``, positive semidefinite, off-diagonal
  ``dot / (4 A)`` = -1/2 cot per corner (``a12 = sum(v3mv2 * v1mv3) / vol`` with
  ``vol = 2 |cross|``): the reference's sign and factor, no map.
* ``vertex_areas_barycentric``: diagonal of ``Solver(mesh, lump=True).mass``
  (``b_ii = vol / 12`` = A / 3 per corner).
* ``area``: ``TriaMesh.area()`` (Heron's formula on unsorted lengths, F-lapy-2).
* ``solve_dirichlet``: ``Solver(mesh).poisson(h=0, dtup=(boundary, values))``.
* topology: ``euler``, ``boundary_loops``, ``is_orientable``, ``genus``.
  ``boundary_loops`` needs a manifold, *oriented* mesh (``ValueError`` otherwise): an
  orientable mesh is first oriented with LaPy's own ``orient_()`` (on a copy); a
  non-orientable or non-manifold one is outside LaPy's domain (``OutsideDomain``), as
  is ``genus`` of a non-orientable or non-manifold mesh (LaPy raises ``ValueError``),
  and a mesh of several components that is not oriented, where ``orient_()`` never
  returns (F-lapy-4).

>>> import numpy as np
>>> V = np.array([[0., 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
>>> F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
>>> Lapy().euler_characteristic(V, F), Lapy().genus(V, F)
(2, 0)
"""

from __future__ import annotations

import numpy as np
import scipy.sparse

import lapy

from ..protocol.methods import OutsideDomain

from ..protocol.arrays import checked_arrays

#: this adapter as ``ddg-oracle check --impl lapy`` finds it (read without importing the
#: module: ddg_oracle.application.implementations): the object, the library it needs, the pip extra
#: that installs it, its place in reports
ADAPTER = {"name": "lapy", "object": "Lapy", "library": "lapy", "extra": "lapy", "rank": 9}


def _mesh(V, F) -> "lapy.TriaMesh":
    V, F = checked_arrays(V, F)
    return lapy.TriaMesh(V, F)


def _used_mesh(V, F) -> tuple["lapy.TriaMesh", np.ndarray]:
    """The mesh after LaPy's ``rm_free_vertices_()`` and the kept (original) indices."""
    m = _mesh(V, F)
    keep, _ = m.rm_free_vertices_()
    return m, np.asarray(keep, dtype=np.int64)


class Lapy:
    """LaPy as an implementation of the protocol (``protocol/methods.py``)."""

    name = "lapy"
    conventions = "lapy"            # {"unused_vertices": "dropped"} (module doc)

    def __repr__(self) -> str:
        return "Lapy()"

    # --- chapter 1: topology ------------------------------------------------------------

    def euler_characteristic(self, V, F) -> int:
        """``TriaMesh.euler()``: #used V - #E + #T (declared: ``unused_vertices=dropped``)."""
        return int(_mesh(V, F).euler())

    def boundary_loops(self, V, F) -> list[list[int]]:
        """``TriaMesh.boundary_loops()``, after ``orient_()`` if the mesh is not oriented."""
        m = _mesh(V, F)
        if not m.is_manifold():
            raise OutsideDomain("LaPy's boundary_loops needs a manifold mesh")
        if not m.is_oriented():
            if not m.is_orientable():
                raise OutsideDomain("LaPy's boundary_loops needs an oriented mesh; this one "
                                    "is not orientable")
            labels = m.connected_components()[1]
            if len(np.unique(labels[np.unique(m.t)])) > 1:     # of the used vertices
                # orient_() floods from triangle 0 until every triangle is reached: never
                # on a second component (F-lapy-4)
                raise OutsideDomain("LaPy's orient_() does not return on a mesh of several "
                                    "components that is not oriented (F-lapy-4)")
            m.orient_()
        return [[int(v) for v in loop] for loop in m.boundary_loops()]

    def is_orientable(self, V, F) -> bool:
        """``TriaMesh.is_orientable()`` (orientation double cover)."""
        m = _mesh(V, F)
        try:
            return bool(m.is_orientable())
        except ValueError as e:             # an edge of more than two triangles
            raise OutsideDomain(f"LaPy: {e}") from None

    def genus(self, V, F) -> int:
        """``TriaMesh.genus()``: (2 c - b - chi) / 2, for manifold orientable meshes only."""
        m = _mesh(V, F)
        try:
            return int(m.genus())
        except ValueError as e:             # not manifold or not orientable
            raise OutsideDomain(f"LaPy: {e}") from None

    # --- areas ------------------------------------------------------------------------

    def area(self, V, F) -> float:
        """``TriaMesh.area()``: the sum of Heron's formula per triangle."""
        return float(_mesh(V, F).area())

    def vertex_areas_barycentric(self, V, F) -> np.ndarray:
        """Diagonal of ``Solver(mesh, lump=True).mass`` on the used vertices."""
        m, _ = _used_mesh(V, F)
        return np.asarray(lapy.Solver(m, lump=True).mass.diagonal(), dtype=np.float64)

    # --- chapter 3: Laplacian -----------------------------------------------------------

    def cotan_laplacian(self, V, F) -> scipy.sparse.csr_matrix:
        """``Solver(mesh).stiffness`` on the used vertices, unchanged."""
        m, _ = _used_mesh(V, F)
        return scipy.sparse.csr_matrix(lapy.Solver(m).stiffness, dtype=np.float64)

    def area_gradient(self, V, F) -> np.ndarray:
        """``Solver(mesh).stiffness @ mesh.v`` on the used vertices (positive semidefinite:
        the area gradient itself)."""
        m, _ = _used_mesh(V, F)
        return np.asarray(lapy.Solver(m).stiffness @ m.v, dtype=np.float64)

    def solve_dirichlet(self, V, F, boundary, values) -> np.ndarray:
        """``Solver(mesh).poisson(h=0, dtup=(boundary, values))`` on the used vertices
        (boundary indices renumbered), put back on every row of V: a boundary vertex used
        by no face, which LaPy never sees, keeps its given value (the protocol's u[boundary]
        = values; the "dropped" map would give it 0)."""
        m, keep = _used_mesh(V, F)
        n = len(checked_arrays(V, F)[0])
        new = np.full(n, -1, dtype=np.int64)
        new[keep] = np.arange(len(keep))
        given = np.asarray(boundary, dtype=np.int64).reshape(-1)
        b = new[given]
        vals = np.asarray(values, dtype=np.float64).reshape(-1)
        inside = b >= 0
        x = lapy.Solver(m).poisson(h=0.0, dtup=(b[inside], vals[inside]))
        u = np.zeros(n)
        u[keep] = np.asarray(x, dtype=np.float64).reshape(-1)
        u[given[~inside]] = vals[~inside]
        return u
