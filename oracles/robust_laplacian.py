"""robust-laplacian (``import robust_laplacian``, Sharp and Crane 2020) on the reference's conventions.

``robust_laplacian.mesh_laplacian(V, F, mollify_factor)`` returns ``(L, M)``:
``L`` is the cotan Laplacian of an intrinsic Delaunay triangulation of the
*tufted cover* of the mesh, times 1/2 (geometry-central
``src/surface/tufted_laplacian.cpp`` ``buildTuftedLaplacian``, l. 36), positive
semidefinite with weights 1/2 (cot a + cot b); ``M`` its lumped (barycentric)
mass matrix, of the *flipped* triangulation.  The tufted cover takes every face
twice (front and back) and glues the copies around each edge, so every edge
of the cover has two faces.  Of the protocol it computes only
``intrinsic_delaunay_laplacian``; ``M`` is the barycentric mass of the
Delaunay triangulation, not of the input mesh, so it maps to no protocol
method.  ``point_cloud_laplacian`` is out of scope.

What the cover means for the notes' operator (D4.8)
---------------------------------------------------
On a closed mesh the cover is two copies of the surface, each flipped to
Delaunay independently, and 1/2 of its Laplacian is the notes' Laplace-
Beltrami operator (R4.9: it does not depend on which Delaunay triangulation).
On a mesh with boundary the cover is the *double* of the surface (two copies
glued along the boundary): a boundary edge becomes an interior edge between
the two copies of its face, and is flipped when its opposite angle is obtuse,
whereas the notes never flip a boundary edge (D4.4).  The two operators agree
exactly when the notes' operator has no negative weight on a boundary edge
(docs/findings.md, F-robust-laplacian-1); where it has one, robust-laplacian's weights are all
>= 0 and no mapping of its output gives the notes' operator back.

Options (the defaults give the reference's conventions)
-------------------------------------------------------
``RobustLaplacian(boundary="reference")``: meshes with a boundary edge (an
edge of exactly one face) are outside the domain: the method raises
:class:`ddg_oracle.protocol.methods.OutsideDomain` and the properties do not check
that example.  ``boundary="library"``: the tufted-cover operator on every mesh.

``RobustLaplacian(mollify="reference")``: ``mollify_factor=0``, no intrinsic
mollification.  ``mollify="library"``: the library's default
``mollify_factor=1e-5``: every edge length is increased by the same epsilon
= max over corners of (l_c - l_a - l_b + 1e-5 x mean edge length), 0 unless
some triangle is that close to degenerate (geometry-central
``intrinsic_mollification.cpp`` l. 20-37); then every weight changes (F-robust-laplacian-3).

Bad input: the C++ code indexes vertices by the face list unchecked;
:func:`_arrays` (``ddg_oracle.protocol.arrays.checked_arrays``) checks shapes, index ranges
and finite coordinates first and raises the reference's typed ``ValueError``s.

>>> import numpy as np
>>> V = np.array([[0., 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
>>> F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
>>> L = RobustLaplacian().intrinsic_delaunay_laplacian(V, F)
>>> bool(abs(L.sum()) < 1e-12), L.shape
(True, (4, 4))
"""

from __future__ import annotations


import scipy.sparse

import robust_laplacian

from ..protocol.methods import OutsideDomain

from ..protocol.arrays import Referenced, boundary_edges, checked_arrays
from .conventions import declare

MOLLIFY_FACTOR = {"reference": 0.0, "library": 1e-5}   # mollify option -> mollify_factor


_arrays = checked_arrays


#: option -> (finding, what the library's own convention differs by) (docs/findings.md)
LIBRARY_CONVENTIONS = {
    "boundary": ("F-robust-laplacian-1", "tufted cover: boundary edges are flipped in the double of the surface"),
    "mollify": ("F-robust-laplacian-3", "mollify_factor 1e-5 lengthens every edge of a nearly degenerate mesh"),
}


#: this adapter as ``ddg-oracle check --impl robust_laplacian`` finds it (read without importing the
#: module: ddg_oracle.application.implementations): the object, the library it needs (None: the
#: core's own dependencies), the pip extra that installs it, its place in reports
ADAPTER = {"name": "robust_laplacian", "object": "RobustLaplacian", "library": "robust_laplacian", "extra": "peers",
           "rank": 5}


class RobustLaplacian:
    """robust-laplacian as an implementation of the protocol (``protocol/methods.py``)."""

    name = "robust_laplacian"

    def __init__(self, boundary: str = "reference", mollify: str = "reference"):
        self.name, self.conventions = declare("robust_laplacian", LIBRARY_CONVENTIONS,
                                              boundary=boundary, mollify=mollify)
        self.boundary, self.mollify = boundary, mollify

    def __repr__(self) -> str:
        return f"RobustLaplacian(boundary={self.boundary!r}, mollify={self.mollify!r})"

    def mesh_laplacian(self, V, F) -> tuple[scipy.sparse.csr_matrix, scipy.sparse.csr_matrix]:
        """``robust_laplacian.mesh_laplacian(V, F, mollify_factor)`` on checked arrays, as
        CSR matrices: (L, M) of the tufted cover, unchanged (not a protocol method)."""
        V, F = _arrays(V, F)
        L, M = robust_laplacian.mesh_laplacian(V, F, mollify_factor=MOLLIFY_FACTOR[self.mollify])
        return scipy.sparse.csr_matrix(L), scipy.sparse.csr_matrix(M)

    def intrinsic_delaunay_laplacian(self, V, F) -> scipy.sparse.csr_matrix:
        """L of :meth:`mesh_laplacian`, unchanged (sign and factor 1/2 already the
        reference's) on the vertices the faces use; a vertex used by no face gets the
        protocol's zero row and column (the library puts 1 on its diagonal); with
        boundary="reference" a mesh with boundary raises OutsideDomain."""
        r = Referenced(V, F)
        V, F = r.V, r.F
        if self.boundary == "reference":
            b = boundary_edges(F)
            if len(b):
                raise OutsideDomain(
                    f"robust_laplacian(boundary=reference) has no value on a mesh with "
                    f"boundary (edge {tuple(int(x) for x in b[0])} has one face): the tufted "
                    "cover flips boundary edges (docs/findings.md F-robust-laplacian-1); "
                    "use robust_laplacian(boundary=library) for its own operator")
        return scipy.sparse.csr_matrix(r.embed(self.mesh_laplacian(V, F)[0]))
