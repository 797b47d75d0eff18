"""gpytoolbox (``import gpytoolbox``, pure numpy / scipy) on the reference's conventions.

Every method calls the gpytoolbox function that computes the quantity and
applies only the documented change of convention; the numbers compared are
gpytoolbox's.  ``docs/conventions.md`` lists, for every method, what
gpytoolbox returns, how it is mapped and the source line that defines it
(gpytoolbox 0.3.8, the files ``src/gpytoolbox/<name>.py`` of
``sgsellan/gpytoolbox``, installed unchanged as ``gpytoolbox/<name>.py``).

gpytoolbox has no orientability test, no genus, no Delaunay predicate and no
intrinsic flips: those protocol methods are absent (not applicable).

Options (the defaults give the reference's conventions)
-------------------------------------------------------
``Gpytoolbox(boundary="reference")``: ``gpytoolbox.angle_defect`` returns
``2 pi - angle sum`` at interior vertices and **0** at boundary vertices
(its docstring: "except at boundary vertices, where it is 0"; the value is
set by ``k[b] = 0.``).  The reference wants the turning angle
``pi - angle sum`` there (R2.4); the adapter takes it from gpytoolbox's own
corner angles (``tip_angles``, summed per vertex as ``angle_defect`` sums
them) at gpytoolbox's ``boundary_vertices``.  ``boundary="library"``
returns ``angle_defect`` unchanged.

``Gpytoolbox(dihedral="reference")``: ``gpytoolbox.dihedral_angles`` is the
*unsigned* angle between the two face normals at an edge, in [0, pi] ("0 when
the two faces are coplanar ... approaching pi when they fold back"), so it
cannot tell a convex edge from a reflex one.  The reference's mean curvature
H(e) = 1/2 theta(e) l(e) needs theta < 0 at reflex edges (D2.3); the adapter
gives gpytoolbox's angle the sign of ``(n_f x n_g) . e`` (gpytoolbox's unit
normals ``per_face_normals``, e the edge as it runs in face f: positive where
convex for outward faces).  ``dihedral="library"`` keeps the unsigned angle.

Bad input: gpytoolbox does not check indices (a negative one silently wraps
around in numpy, one >= #V raises IndexError deep inside); :func:`_arrays`
(``ddg_oracle.protocol.arrays.checked_arrays``) checks shapes, index ranges and finite
coordinates first and raises the reference's typed ``ValueError``s.

>>> import numpy as np
>>> V = np.array([[0., 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
>>> F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
>>> Gpytoolbox().euler_characteristic(V, F)
2
"""

from __future__ import annotations


import math

import numpy as np
import scipy.sparse

import gpytoolbox as gpy

from ..protocol.arrays import checked_arrays
from .conventions import declare
from ..reference.combinatorics import next_corner, prev_corner

_arrays = checked_arrays
#: next_corner and prev_corner as tables, for arrays of corners
_NEXT = np.array([next_corner(c) for c in range(3)])
_PREV = np.array([prev_corner(c) for c in range(3)])


#: option -> (finding, what the library's own convention differs by) (docs/findings.md)
LIBRARY_CONVENTIONS = {
    "boundary": ("F-gpytoolbox-1", "angle_defect: 0 at boundary vertices"),
    "dihedral": ("F-gpytoolbox-2", "dihedral_angles: unsigned, reflex edges count as convex"),
}


#: this adapter as ``ddg-oracle check --impl gpytoolbox`` finds it (read without importing the
#: module: ddg_oracle.application.implementations): the object, the library it needs (None: the
#: core's own dependencies), the pip extra that installs it, its place in reports
ADAPTER = {"name": "gpytoolbox", "object": "Gpytoolbox", "library": "gpytoolbox", "extra": "peers",
           "rank": 4}


class Gpytoolbox:
    """gpytoolbox as an implementation of the protocol (``protocol/methods.py``)."""

    name = "gpytoolbox"

    def __init__(self, boundary: str = "reference", dihedral: str = "reference"):
        self.name, self.conventions = declare("gpytoolbox", LIBRARY_CONVENTIONS,
                                              boundary=boundary, dihedral=dihedral)
        self.boundary, self.dihedral = boundary, dihedral

    def __repr__(self) -> str:
        return f"Gpytoolbox(boundary={self.boundary!r}, dihedral={self.dihedral!r})"

    # --- chapter 1: topology ------------------------------------------------------------

    def euler_characteristic(self, V, F) -> int:
        """#V - #``gpytoolbox.edges(F)`` + #F: gpytoolbox has no Euler characteristic, but
        its unique undirected edges (``edges.py``: sorted halfedge pairs, ``np.unique``)."""
        V, F = _arrays(V, F)
        return len(V) - len(gpy.edges(F)) + len(F)

    def boundary_loops(self, V, F) -> list[list[int]]:
        """``gpytoolbox.boundary_loops(F)`` (default ``allow_wrong_orientations=True``): each
        loop starts with a boundary edge as it runs in its face and follows whichever unseen
        boundary edge meets the current head, so a Möbius strip's one loop stays one loop."""
        _, F = _arrays(V, F)
        return [[int(v) for v in loop] for loop in gpy.boundary_loops(F)]

    # --- chapter 2: curvature -----------------------------------------------------------

    def corner_angles(self, V, F) -> np.ndarray:
        """``gpytoolbox.tip_angles(V, F)``: column c is the angle at vertex F[f, c],
        ``arccos((a + b - c) / (2 sqrt(a b)))`` of squared lengths; where the opposite
        squared length is below sqrt(float eps) (absolute) the chord 2 sin(angle / 2)
        instead (docs/findings.md, F-gpytoolbox-3, F-gpytoolbox-4)."""
        V, F = _arrays(V, F)
        return np.asarray(gpy.tip_angles(V, F), dtype=np.float64)

    def angle_defects(self, V, F) -> np.ndarray:
        """``gpytoolbox.angle_defect(V, F)`` = 2 pi - angle sum, 0 at boundary vertices; with
        boundary="reference" pi - (sum of gpytoolbox's tip angles) there (turning angle)."""
        V, F = _arrays(V, F)
        K = np.asarray(gpy.angle_defect(V, F), dtype=np.float64)
        if self.boundary == "reference":
            b = np.asarray(gpy.boundary_vertices(F), dtype=np.int64)
            if len(b):
                sums = np.bincount(F.ravel(), np.asarray(gpy.tip_angles(V, F)).ravel(),
                                   minlength=len(V))
                K[b] = math.pi - sums[b]
        return K

    def edge_mean_curvature(self, V, F) -> dict[tuple[int, int], float]:
        """H(e) = 1/2 theta(e) l(e) over edges with two faces, theta from
        ``gpytoolbox.dihedral_angles(V, F)`` (entry (f, c): the edge opposite corner c of
        face f; unsigned), signed with dihedral="reference" (module doc); l(e) from
        ``gpytoolbox.halfedge_lengths`` (same layout)."""
        V, F = _arrays(V, F)
        theta = np.asarray(gpy.dihedral_angles(V, F), dtype=np.float64)
        lengths = np.asarray(gpy.halfedge_lengths(V, F), dtype=np.float64)
        TT, _ = gpy.triangle_triangle_adjacency(F)
        N = np.asarray(gpy.per_face_normals(V, F, unit_norm=True), dtype=np.float64)
        pairs = np.sort(np.stack([F[:, [1, 2]], F[:, [2, 0]], F[:, [0, 1]]], axis=1), axis=2)
        uniq, inverse, counts = np.unique(pairs.reshape(-1, 2), axis=0, return_inverse=True,
                                          return_counts=True)
        two = counts[inverse.ravel()].reshape(-1, 3) == 2
        # array operations over all such edges at once (with a loop in Python over the edges
        # the method took 2.4 s on bunny.obj's 56k faces, 0.9 s without)
        f, c = np.nonzero(two)
        g = np.asarray(TT)[f, c]
        keep = g > f                        # each edge once, from its lower face (-1: no face)
        f, c, g = f[keep], c[keep], g[keep]
        i, j = F[f, _NEXT[c]], F[f, _PREV[c]]
        t = theta[f, c]
        if self.dihedral == "reference":
            side = np.einsum("ij,ij->i", np.cross(N[f], N[g]), V[j] - V[i])
            t = np.where(side < 0, -t, t)
        h = 0.5 * t * lengths[f, c]
        return {(a, b): x for a, b, x in zip(np.minimum(i, j).tolist(), np.maximum(i, j).tolist(),
                                              h.tolist())}

    def area(self, V, F) -> float:
        """``gpytoolbox.doublearea(V, F)`` summed with math.fsum and halved; gpytoolbox takes
        it from the square roots of the squared edge lengths (Kahan's product, unsorted), so
        a cap loses precision (docs/findings.md, F-gpytoolbox-4)."""
        V, F = _arrays(V, F)
        return math.fsum(np.asarray(gpy.doublearea(V, F)).ravel()) / 2

    # --- chapter 3: Laplacian and mass matrices ------------------------------------------

    def cotan_laplacian(self, V, F) -> scipy.sparse.csr_matrix:
        """``gpytoolbox.cotangent_laplacian(V, F)`` unchanged: positive semidefinite ("pos.
        def.") with off-diagonal entries minus ``cotangent_weights`` = cot / 2 per corner."""
        V, F = _arrays(V, F)
        return scipy.sparse.csr_matrix(gpy.cotangent_laplacian(V, F))

    def area_gradient(self, V, F) -> np.ndarray:
        """``gpytoolbox.cotangent_laplacian(V, F) @ V`` (positive semidefinite: no sign change)."""
        V, F = _arrays(V, F)
        return np.asarray(gpy.cotangent_laplacian(V, F) @ V)

    def solve_dirichlet(self, V, F, boundary, values) -> np.ndarray:
        """``gpytoolbox.min_quad_with_fixed(Q=cotangent_laplacian, k=boundary, y=values)``:
        the minimiser of 1/2 u^T L u with u fixed on the boundary set (T3.5)."""
        V, F = _arrays(V, F)
        return np.asarray(gpy.min_quad_with_fixed(
            scipy.sparse.csr_matrix(gpy.cotangent_laplacian(V, F)),
            k=np.asarray(boundary, dtype=np.int64).reshape(-1),
            y=np.asarray(values, dtype=np.float64).reshape(-1))).reshape(-1)

    def vertex_areas_barycentric(self, V, F) -> np.ndarray:
        """Diagonal of ``gpytoolbox.massmatrix(V, F, type="barycentric")``: dblA / 6 per
        corner."""
        V, F = _arrays(V, F)
        return np.asarray(gpy.massmatrix(V, F, type="barycentric").diagonal(), dtype=np.float64)

    def vertex_areas_voronoi(self, V, F) -> np.ndarray:
        """Diagonal of ``gpytoolbox.massmatrix(V, F, type="voronoi")`` (the default): Meyer et
        al.'s mixed areas, A/2 at an obtuse corner (cos < 0) and A/4 at the others."""
        V, F = _arrays(V, F)
        return np.asarray(gpy.massmatrix(V, F, type="voronoi").diagonal(), dtype=np.float64)
