"""PyGEL3D (``from pygel3d import hmesh``; the C++ library GEL, janba/GEL) in its own
conventions.

Every method builds ``hmesh.Manifold.from_triangles(V, F)`` (GEL's ``build``, a halfedge
mesh) and calls the GEL function that computes the quantity.  Sources: ``janba/GEL``
(``src/GEL/HMesh/curvature.cpp``, ``src/PyGEL/Manifold.cpp``); the wheel is PyGEL3D 0.8.2.

The halfedge mesh does not keep the input's numbering: ``from_triangles`` creates the
vertices some face uses, in the order of their first appearance in F, and drops the others
(measured; ``hmesh.Manifold.positions()``).  The adapter maps GEL's vertex ids back to the
rows of V by position and declines (``OutsideDomain``) a mesh where that is not one-to-one
(two rows at one position; a non-manifold vertex GEL splits): GEL has no value for the
input's vertices there.

Conventions (declared: ``{"curvature": "per_mixed_area"}``)
------------------------------------------------------------
``Manifold.gaussian_curvature(v)`` is ``(2 pi - angle sum) / mixed_area(v)``
(``curvature.cpp`` l. 155-175): pointwise, per Meyer et al.'s mixed area -- the
vocabulary's ``curvature=per_mixed_area``; ddg-oracle multiplies it back.  At a boundary
vertex GEL returns **0** (l. 157-158: ``if(boundary(m, v)) return 0;``), with no value to
recover the turning angle from: with ``boundary="reference"`` (the default) a mesh with
boundary is outside the domain (``OutsideDomain``); ``boundary="library"`` returns GEL's 0
there (F-pygel3d-1).

* ``vertex_areas_voronoi``: ``Manifold.mixed_area(v)`` (l. 64-90: Meyer's Voronoi area in
  a non-obtuse face, A/2 at an obtuse corner, A/4 at the others; the angles by ``acos``).
* ``area``: ``hmesh.area(m)``, the sum of the faces' areas.
* ``euler_characteristic``: #vertices - #halfedges / 2 + #faces of GEL's mesh, plus the
  input's unused vertices (the protocol counts them; GEL drops them).

>>> import numpy as np
>>> V = np.array([[0., 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
>>> F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
>>> Pygel3d().euler_characteristic(V, F)
2
"""

from __future__ import annotations

import numpy as np

from pygel3d import hmesh

from ..protocol.methods import OutsideDomain

from ..protocol.arrays import checked_arrays
from .conventions import declare

#: option -> (finding, what the library's own convention differs by) (docs/findings.md)
LIBRARY_CONVENTIONS = {
    "boundary": ("F-pygel3d-1", "gaussian_curvature: 0 at boundary vertices"),
}

#: this adapter as ``ddg-oracle check --impl pygel3d`` finds it (read without importing the
#: module: ddg_oracle.application.implementations): the object, the library it needs, the pip extra that
#: installs it, its place in reports
ADAPTER = {"name": "pygel3d", "object": "Pygel3d", "library": "pygel3d", "extra": "pygel3d",
           "rank": 11}


def _manifold(V, F):
    """(GEL's mesh, its vertex ids, the input row of each, #V, #F)."""
    V, F = checked_arrays(V, F)
    m = hmesh.Manifold.from_triangles(V, F)
    ids = np.asarray(list(m.vertices()), dtype=np.int64)
    P = np.asarray(m.positions(), dtype=np.float64)[ids]
    used = np.unique(F)
    rows = {}
    for i in used:
        rows.setdefault(tuple(V[i]), []).append(int(i))
    if len(ids) != len(used) or any(len(r) != 1 for r in rows.values()):
        raise OutsideDomain("PyGEL3D's halfedge mesh does not keep the input's vertices one to "
                            "one (coincident or non-manifold vertices)")
    try:
        back = np.array([rows[tuple(p)][0] for p in P], dtype=np.int64)
    except KeyError:
        raise OutsideDomain("PyGEL3D moved a vertex while building its mesh") from None
    return m, ids, back, len(V), len(F)


class Pygel3d:
    """PyGEL3D as an implementation of the protocol (``protocol/methods.py``)."""

    name = "pygel3d"

    def __init__(self, boundary: str = "reference"):
        # the display name of the option; the declaration is the vocabulary's map (pointwise
        # per mixed area), which the older {"follows": ...} form cannot carry alongside
        self.name, _ = declare("pygel3d", LIBRARY_CONVENTIONS, boundary=boundary)
        self.boundary = boundary
        self.conventions = {"curvature": "per_mixed_area"}

    def __repr__(self) -> str:
        return f"Pygel3d(boundary={self.boundary!r})"

    def euler_characteristic(self, V, F) -> int:
        """#V - #E + #F of GEL's halfedge mesh, plus the unused input vertices."""
        m, ids, _, n, _ = _manifold(V, F)
        return int(len(ids) - len(m.halfedges()) // 2 + len(m.faces()) + (n - len(ids)))

    def angle_defects(self, V, F) -> np.ndarray:
        """``Manifold.gaussian_curvature(v)`` per input vertex (pointwise: declared); a mesh
        with boundary declines with boundary="reference"; 0 at a vertex of no face."""
        m, ids, back, n, _ = _manifold(V, F)
        if self.boundary == "reference" and any(m.is_vertex_at_boundary(int(v)) for v in ids):
            raise OutsideDomain("PyGEL3D's gaussian_curvature is 0 at boundary vertices "
                                "(F-pygel3d-1): no turning angle to compare")
        K = np.zeros(n)
        K[back] = [m.gaussian_curvature(int(v)) for v in ids]
        return K

    def vertex_areas_voronoi(self, V, F) -> np.ndarray:
        """``Manifold.mixed_area(v)`` per input vertex; 0 at a vertex of no face."""
        m, ids, back, n, _ = _manifold(V, F)
        A = np.zeros(n)
        A[back] = [m.mixed_area(int(v)) for v in ids]
        return A

    def area(self, V, F) -> float:
        """``hmesh.area(m)``: the sum of the faces' areas."""
        m, _, _, _, _ = _manifold(V, F)
        return float(hmesh.area(m))
