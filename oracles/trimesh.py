"""trimesh (``import trimesh``, numpy) on the reference's conventions.

Every method builds ``trimesh.Trimesh(vertices=V, faces=F, process=False)`` and
reads the attribute that computes the quantity, applying only the documented
change of convention; the numbers compared are trimesh's.  ``process=False``:
trimesh's default ``process=True`` merges vertices at the same position and drops
unreferenced ones, so two components touching at a point would become one
non-manifold vertex and per-vertex answers would no longer match the input's
vertices (the protocol's vertices are the input's rows).

* ``corner_angles``: ``mesh.face_angles``, column c the angle at vertex F[f, c].
* ``angle_defects``: ``mesh.vertex_defects`` = 2 pi - angle sum at *every* vertex
  (trimesh 5.2 ``curvature.py``); with ``boundary="reference"`` the adapter adds
  -pi at boundary vertices (ends of edges of one face: ``mesh.edges_unique`` counts),
  giving the turning angle pi - angle sum (R2.4); ``boundary="library"`` keeps
  2 pi - sum.  A vertex used by no face keeps trimesh's 2 pi - 0 (the protocol's).
* ``edge_mean_curvature``: H(e) = 1/2 theta l over ``mesh.face_adjacency_edges``,
  theta = ``face_adjacency_angles`` (unsigned) signed by ``face_adjacency_convex``,
  as trimesh's own docstring of ``face_adjacency_angles`` says to; l the edge length.
  ``dihedral="library"`` keeps the unsigned angle (F-trimesh-5).
* ``area``: ``mesh.area``.

Bad input is checked first by :func:`~ddg_oracle.protocol.arrays.checked_arrays`
(trimesh would index out of range deep inside, or wrap negative indices).

>>> import numpy as np
>>> V = np.array([[0., 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
>>> F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
>>> round(float(Trimesh().angle_defects(V, F).sum() / np.pi), 12)
4.0
"""

from __future__ import annotations


import math

import numpy as np

import trimesh

from ..protocol.arrays import checked_arrays
from .conventions import declare


def _mesh(V, F) -> "trimesh.Trimesh":
    V, F = checked_arrays(V, F)
    return trimesh.Trimesh(vertices=V, faces=F, process=False, validate=False)


#: option -> (finding, what the library's own convention differs by) (docs/findings.md)
LIBRARY_CONVENTIONS = {
    "boundary": ("F-trimesh-1", "vertex_defects: 2 pi - angle sum at boundary vertices"),
    "dihedral": ("F-trimesh-5", "face_adjacency_angles: unsigned, reflex edges count as convex"),
}


#: this adapter as ``ddg-oracle check --impl trimesh`` finds it (read without importing the
#: module: ddg_oracle.application.implementations): the object, the library it needs (None: the
#: core's own dependencies), the pip extra that installs it, its place in reports
ADAPTER = {"name": "trimesh", "object": "Trimesh", "library": "trimesh", "extra": "peers",
           "rank": 7}


class Trimesh:
    """trimesh as an implementation of the protocol (``protocol/methods.py``)."""

    name = "trimesh"

    def __init__(self, boundary: str = "reference", dihedral: str = "reference"):
        self.name, self.conventions = declare("trimesh", LIBRARY_CONVENTIONS, boundary=boundary,
                                              dihedral=dihedral)
        self.boundary, self.dihedral = boundary, dihedral

    def __repr__(self) -> str:
        return f"Trimesh(boundary={self.boundary!r}, dihedral={self.dihedral!r})"

    def corner_angles(self, V, F) -> np.ndarray:
        """``mesh.face_angles``: (m, 3), column c the angle at vertex F[f, c]."""
        return np.asarray(_mesh(V, F).face_angles, dtype=np.float64)

    def angle_defects(self, V, F) -> np.ndarray:
        """``mesh.vertex_defects`` (2 pi - sum everywhere); -pi at boundary vertices with
        boundary="reference"."""
        m = _mesh(V, F)
        K = np.array(m.vertex_defects, dtype=np.float64)
        if self.boundary == "reference":
            # edges_unique_inverse maps each face edge to its unique edge: one use = boundary
            count = np.bincount(m.edges_unique_inverse, minlength=len(m.edges_unique))
            b = np.unique(m.edges_unique[count == 1])
            K[b] -= math.pi
        return K

    def edge_mean_curvature(self, V, F) -> dict[tuple[int, int], float]:
        """{(i, j): 1/2 theta l} over trimesh's face adjacency, theta signed by
        ``face_adjacency_convex`` (trimesh's recipe); unsigned with dihedral="library"."""
        m = _mesh(V, F)
        theta = np.asarray(m.face_adjacency_angles, dtype=np.float64)
        if self.dihedral == "reference":
            theta = np.where(m.face_adjacency_convex, 1.0, -1.0) * theta
        edges = np.sort(m.face_adjacency_edges, axis=1)
        Vf = np.asarray(m.vertices)
        length = np.linalg.norm(Vf[edges[:, 1]] - Vf[edges[:, 0]], axis=1)
        return {(int(i), int(j)): float(0.5 * t * l)
                for (i, j), t, l in zip(edges.tolist(), theta, length)}

    def area(self, V, F) -> float:
        """``mesh.area``: the sum of the face areas (cross products)."""
        return float(_mesh(V, F).area)
