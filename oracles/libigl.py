"""libigl (the ``libigl`` Python bindings, ``import igl``) on the reference's conventions.

Every method calls the libigl function that computes the quantity and applies
only the documented change of convention (sign, boundary term, layout); the
numbers compared are libigl's.  ``docs/conventions.md`` lists, for every
method, what libigl returns, how it is mapped and the libigl source that
defines it (libigl commit 678e1fff, the one pinned by the bindings 2.6.x).

Option
------
``Libigl(boundary="reference")`` (the default, also what ``load_implementation("libigl")``
builds) maps ``igl.gaussian_curvature`` to the reference's angle defect: libigl
returns ``2 pi - angle sum`` at *every* vertex (gaussian_curvature.h: "for
boundary vertices, this quantity is not so meaningful"), the reference wants
the turning angle ``pi - angle sum`` at boundary vertices (R2.4), so pi is
subtracted at the vertices ``igl.is_border_vertex`` marks.  ``boundary="library"``
returns libigl's values unchanged.

Bad input
---------
libigl does not check face indices: an index >= n or < 0 reads out of bounds
(SIGSEGV in cotmatrix, gaussian_curvature, internal_angles, massmatrix,
doublearea, euler_characteristic, boundary_loop_all), and ``boundary_loop_all``
also segfaults on an F with 2 columns.  :func:`_arrays` therefore checks shapes
and index ranges in Python before anything reaches libigl and raises
``ValueError`` instead.

>>> import numpy as np
>>> V = np.array([[0., 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
>>> F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
>>> Libigl().euler_characteristic(V, F)
2
"""

from __future__ import annotations


import math

import numpy as np
import scipy.sparse

import igl

from ..protocol.arrays import checked_arrays
from .conventions import declare


_arrays = checked_arrays


def _pad(x: np.ndarray, n: int) -> np.ndarray:
    # libigl sizes per-vertex outputs of massmatrix / is_border_vertex by max(F) + 1, not by
    # #V; vertices after the last referenced one are unreferenced (area 0, not on a boundary).
    x = np.asarray(x).ravel()
    if len(x) >= n:
        return x[:n]
    return np.concatenate([x, np.zeros(n - len(x), dtype=x.dtype)])


#: option -> (finding, what the library's own convention differs by) (docs/findings.md)
LIBRARY_CONVENTIONS = {
    "boundary": ("F-libigl-2", "gaussian_curvature: 2 pi - angle sum at boundary vertices"),
}


#: this adapter as ``ddg-oracle check --impl libigl`` finds it (read without importing the
#: module: ddg_oracle.application.implementations): the object, the library it needs (None: the
#: core's own dependencies), the pip extra that installs it, its place in reports
ADAPTER = {"name": "libigl", "object": "Libigl", "library": "igl", "extra": "libigl",
           "rank": 1}


class Libigl:
    """libigl as an implementation of the protocol (``protocol/methods.py``)."""

    name = "libigl"

    def __init__(self, boundary: str = "reference"):
        self.name, self.conventions = declare("libigl", LIBRARY_CONVENTIONS, boundary=boundary)
        self.boundary = boundary

    def __repr__(self) -> str:
        return f"Libigl(boundary={self.boundary!r})"

    # --- chapter 1: topology ------------------------------------------------------------

    def euler_characteristic(self, V, F) -> int:
        """``igl.euler_characteristic(F)``: (max(F) + 1) - #unique edges + #F, plus the
        vertices after max(F) (libigl sees only F; the protocol counts every vertex of V,
        a vertex used by no face as a point)."""
        V, F = _arrays(V, F)
        return int(igl.euler_characteristic(F)) + len(V) - (int(F.max()) + 1 if F.size else 0)

    def boundary_loops(self, V, F) -> list[list[int]]:
        """``igl.boundary_loop_all(F)``: every loop, walked along the faces' orientation.

        On a non-orientable surface this walk breaks the boundary into pieces
        (docs/findings.md, F-libigl-1): returned as libigl gives it.
        """
        _, F = _arrays(V, F)
        return [[int(v) for v in loop] for loop in igl.boundary_loop_all(F)]

    def is_orientable(self, V, F) -> bool:
        """Orientable iff ``igl.bfs_orient`` finds an orientation.

        libigl has no orientability predicate (``orientable_patches`` counts a
        Möbius strip as one patch, its header says so; ``is_edge_manifold``
        does not look at orientation).  ``bfs_orient`` flips faces breadth
        first to agree with their neighbours; on an orientable surface the
        result has every directed edge at most once, on a non-orientable one
        some edge is necessarily used twice in the same direction.  The adapter
        only checks bfs_orient's output for such a repeated directed edge.
        """
        _, F = _arrays(V, F)
        FF, _ = igl.bfs_orient(F)
        FF = np.asarray(FF, dtype=np.int64)
        directed = np.concatenate([FF[:, [0, 1]], FF[:, [1, 2]], FF[:, [2, 0]]])
        return len(np.unique(directed, axis=0)) == len(directed)

    def genus(self, V, F) -> int:
        """From libigl's chi and number of boundary loops k: (2 - chi - k) / 2 if orientable,
        else the number of crosscaps 2 - chi - k (the reference's convention: docs/reference.md,
        Conventions).

        A disconnected mesh raises ValueError, like the reference's ``classify()``.
        """
        V, F = _arrays(V, F)
        n_components, _ = igl.facet_components(F)
        if int(n_components) > 1:
            raise ValueError(f"{int(n_components)} components: genus needs a connected surface")
        # the surface's chi: a vertex used by no face is a point beside it, not part of it
        chi = self.euler_characteristic(V, F) - (len(V) - len(np.unique(F)))
        k = len(self.boundary_loops(V, F))
        deficit = 2 - chi - k
        if not self.is_orientable(V, F):
            return deficit
        if deficit % 2:
            raise ValueError(f"libigl's counts chi = {chi}, k = {k} give an odd 2 - chi - k "
                             "for an orientable surface")
        return deficit // 2

    # --- chapter 2: curvature -----------------------------------------------------------

    def corner_angles(self, V, F) -> np.ndarray:
        """``igl.internal_angles(V, F)``: column c is the angle at vertex F[f, c] (same layout
        as the reference's corner c), computed as 2 atan(|u - w| / |u + w|) of unit vectors."""
        V, F = _arrays(V, F)
        return np.asarray(igl.internal_angles(V, F), dtype=np.float64)

    def angle_defects(self, V, F) -> np.ndarray:
        """``igl.gaussian_curvature(V, F)`` = 2 pi - angle sum at every vertex; with
        boundary="reference" minus pi at libigl's border vertices (turning angle, R2.4)."""
        V, F = _arrays(V, F)
        K = np.asarray(igl.gaussian_curvature(V, F), dtype=np.float64).ravel()
        if self.boundary == "reference":
            border = _pad(np.asarray(igl.is_border_vertex(F), dtype=bool), len(V))
            K = K - np.where(border, math.pi, 0.0)
        return K

    def edge_mean_curvature(self, V, F) -> dict[tuple[int, int], float]:
        """H(e) = 1/2 theta(e) l(e) over interior edges, theta from libigl's face normals.

        libigl has no dihedral angle of a triangle mesh (``igl.dihedral_angles``
        takes tetrahedra).  The adapter uses libigl's own formula from
        ``sharp_edges.cpp``: with unit face normals n_i, n_j (``igl.per_face_normals``)
        and the unit direction e of the edge as it runs in face i
        (``igl.unique_edge_map``'s directed edge), libigl's interior dihedral
        angle is pi - atan2((n_i x n_j).e, n_i.n_j); the bending angle is
        theta = atan2((n_i x n_j).e, n_i.n_j), in (-pi, pi], > 0 where convex
        for faces oriented counterclockwise seen from outside.  l(e) is
        ``igl.edge_lengths``.  Edges with one face (boundary) or more than two
        (non-manifold) are left out.
        """
        V, F = _arrays(V, F)
        m = len(F)
        E, uE, EMAP, uEC, uEE = igl.unique_edge_map(F)
        E = np.asarray(E)
        N = np.asarray(igl.per_face_normals(V, F))
        L = np.asarray(igl.edge_lengths(V, F))        # L[f, c]: edge opposite corner c
        uEC, uEE, uE = np.asarray(uEC), np.asarray(uEE), np.asarray(uE)
        inner = np.flatnonzero(np.diff(uEC) == 2)
        # one array operation per step over all interior edges: a loop in Python took over
        # 120 s on 900k faces (the time limit: libigl reported as hanging)
        ei, ej = uEE[uEC[inner]], uEE[uEC[inner] + 1]
        fi, fj = ei % m, ej % m                       # E row f + c m lies in face f
        ev = V[E[ei, 1]] - V[E[ei, 0]]
        ev = ev / np.linalg.norm(ev, axis=1)[:, None]
        y = np.einsum("ij,ij->i", np.cross(N[fi], N[fj]), ev)
        x = np.einsum("ij,ij->i", N[fi], N[fj])
        length = L[fi, ei // m]
        ij = np.sort(uE[inner], axis=1)
        return {(i, j): 0.5 * math.atan2(a, b) * c
                for i, j, a, b, c in zip(ij[:, 0].tolist(), ij[:, 1].tolist(), y.tolist(),
                                         x.tolist(), length.tolist())}

    def area(self, V, F) -> float:
        """``igl.doublearea(V, F)`` summed (math.fsum, correctly rounded) and halved."""
        V, F = _arrays(V, F)
        return math.fsum(np.asarray(igl.doublearea(V, F)).ravel()) / 2

    # --- chapter 3: Laplacian and mass matrices ------------------------------------------

    def cotan_laplacian(self, V, F) -> scipy.sparse.csr_matrix:
        """``-igl.cotmatrix(V, F)``: libigl's L is negative semidefinite with off-diagonal
        entries 1/2 (cot a + cot b) (cotmatrix_entries: "1/2*cotangents"), so only the sign
        changes."""
        V, F = _arrays(V, F)
        return scipy.sparse.csr_matrix(-igl.cotmatrix(V, F))

    def area_gradient(self, V, F) -> np.ndarray:
        """``-igl.cotmatrix(V, F) @ V``: libigl's mean curvature normal before the mass
        matrix (tutorial 202: HN = -M^-1 L V), the area gradient with the sign changed."""
        V, F = _arrays(V, F)
        return np.asarray(-(igl.cotmatrix(V, F) @ V))

    def solve_dirichlet(self, V, F, boundary, values) -> np.ndarray:
        """``igl.harmonic(V, F, b, bc, 1)``: min_quad_with_fixed on libigl's cotmatrix with
        the values fixed on b (k = 1: the mass matrix plays no part)."""
        V, F = _arrays(V, F)
        b = np.asarray(boundary, dtype=np.int64).reshape(-1)
        bc = np.asarray(values, dtype=np.float64).reshape(-1, 1)
        return np.asarray(igl.harmonic(V, F, b, bc, 1)).reshape(-1)[:len(V)]

    def vertex_areas_barycentric(self, V, F) -> np.ndarray:
        """Diagonal of ``igl.massmatrix(V, F, MASSMATRIX_TYPE_BARYCENTRIC)``: dblA / 6 per
        corner."""
        V, F = _arrays(V, F)
        M = igl.massmatrix(V, F, igl.MASSMATRIX_TYPE_BARYCENTRIC)
        return _pad(M.diagonal(), len(V)).astype(np.float64)

    def vertex_areas_voronoi(self, V, F) -> np.ndarray:
        """Diagonal of ``igl.massmatrix(V, F, MASSMATRIX_TYPE_VORONOI)``: Meyer et al.'s mixed
        areas (circumcentric Voronoi; obtuse triangle: A/2 at the obtuse corner, A/4 else)."""
        V, F = _arrays(V, F)
        M = igl.massmatrix(V, F, igl.MASSMATRIX_TYPE_VORONOI)
        return _pad(M.diagonal(), len(V)).astype(np.float64)

    # chapter 4: intrinsic Delaunay.  libigl's per-face layouts already put in column c
    # the edge opposite corner c (edge_lengths.h: columns [1,2], [2,0], [0,1]).
    def is_locally_delaunay(self, V, F) -> np.ndarray:
        """``igl.is_intrinsic_delaunay(igl.edge_lengths(V, F), F)``: per face, columns "23 31
        12" (opposite corners 0, 1, 2); boundary edges True; an undirected vertex pair
        shared by more than two faces is "by definition not Delaunay"
        (is_intrinsic_delaunay.cpp), unchanged here.  Its test is cot a + cot b >= 0 with
        cot from Fisher et al.'s half-angle tangent."""
        V, F = _arrays(V, F)
        return np.asarray(igl.is_intrinsic_delaunay(igl.edge_lengths(V, F), F), dtype=bool)

    def intrinsic_delaunay_laplacian(self, V, F) -> scipy.sparse.csr_matrix:
        """``-L`` of ``L, l, F2 = igl.intrinsic_delaunay_cotmatrix(V, F)`` (edge_lengths,
        intrinsic_delaunay_triangulation, cotmatrix_intrinsic: the same sign and 1/2 as
        cotmatrix)."""
        V, F = _arrays(V, F)
        L, _, _ = igl.intrinsic_delaunay_cotmatrix(V, F)
        L = scipy.sparse.csr_matrix(-L)
        if L.shape[0] < len(V):             # sized by max(F) + 1: the vertices after it are
            L.resize((len(V), len(V)))      # used by no face, their rows and columns zero
        return L

    def intrinsic_delaunay_triangulation(self, V, F):
        """``(F2, l**2)`` of ``igl.intrinsic_delaunay_triangulation(igl.edge_lengths(V, F), F)``:
        libigl returns plain lengths; the protocol wants squared ones."""
        V, F = _arrays(V, F)
        l, F2, *_ = igl.intrinsic_delaunay_triangulation(igl.edge_lengths(V, F), F)
        return np.asarray(F2, dtype=np.int64), np.asarray(l, dtype=float) ** 2

    def planar_flip_to_delaunay(self, V, F):
        """The faces of :meth:`intrinsic_delaunay_triangulation`: for points in the plane
        z = 0 the intrinsic flips are the ordinary straight-line flips (a non-Delaunay
        edge's quadrilateral is convex, L4.11), so libigl's intrinsic result is a planar
        triangulation of the same polygon."""
        V, F = _arrays(V, F)
        if np.any(V[:, 2] != 0):
            raise ValueError("planar_flip_to_delaunay: the points must lie in the plane z = 0")
        F2, _ = self.intrinsic_delaunay_triangulation(V, F)
        return F2
