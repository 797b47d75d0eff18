"""PyMeshLab (MeshLab / VCG filters, ``import pymeshlab``) on the reference's conventions.

What PyMeshLab can answer of the protocol: topology from the filter
``get_topological_measures`` (vcg ``tri::Clean``), orientability from
``meshing_re_orient_faces_coherently`` (vcg ``Clean::OrientCoherentlyMesh``),
the total area from ``get_geometric_measures``, and angle defects from
``compute_scalar_by_discrete_curvature_per_vertex`` (vcg
``UpdateCurvature::MeanAndGaussian``).  It has no boundary-loop vertex lists
(only their number), no corner angles, no cotan matrix, no mass matrix and
no per-edge mean curvature.  ``docs/conventions.md`` pins every convention to
the MeshLab 2025.07 / vcglib c94ef4e source.

Conversions (each a named option; the defaults give the reference's conventions)
-------------------------------------------------------------------------------
* The Gaussian-curvature filter returns angle defect *divided by* Meyer et
  al.'s mixed area, computed by vcg in single precision.  The adapter
  multiplies by the same mixed area in double precision
  (:func:`mixed_voronoi_areas`; within a few units of 2^-53 of the exact
  :func:`exact_mixed_voronoi_areas`, ``ddg_oracle.reference.laplacian.vertex_areas_voronoi``),
  so the numbers compared are PyMeshLab's, not the conversion's.
* ``boundary="reference"`` (default): at a boundary vertex vcg returns
  ``2 pi - angle sum - phi`` where phi is the angle in R^3 between the two
  boundary edges at the vertex; the adapter adds ``phi - pi`` (phi computed
  here in float64) to get the turning angle ``pi - angle sum`` (R2.4).
  ``boundary="library"`` returns vcg's value times the exact area unchanged.
* ``genus="reference"`` (default): PyMeshLab's ``genus`` key is
  ``-((chi + holes - 2 components) / 2)`` (C++ integer division), which is g
  for an orientable surface but floor(h / 2) for a non-orientable one with h
  crosscaps; for a non-orientable surface the adapter returns
  ``2 - chi - holes`` from PyMeshLab's own counts (the reference's crosscap
  number).  ``genus="library"`` returns the key as is.

Vertex order: a ``pymeshlab.Mesh`` built from arrays keeps them, but a filter
may compact or drop vertices (the curvature filter removes unreferenced
ones: ``angle_defects`` sets them aside first and gives them the protocol's
value); every call checks that the mesh still has the input's vertices, in
order, and raises :class:`VertexOrderChanged` otherwise.

Bad input: NaN or infinite coordinates make the curvature filter abort the
process (glibc "double free or corruption", SIGABRT); the adapter rejects them
with ``ValueError`` before calling PyMeshLab.

>>> import numpy as np
>>> V = np.array([[0., 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
>>> F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
>>> PyMeshLab().euler_characteristic(V, F)
2
"""

from __future__ import annotations


import math

import numpy as np

from ..protocol.methods import ISOLATED_VERTEX

from ..protocol.arrays import Referenced, checked_arrays
from .conventions import declare

import pymeshlab
from ..reference.combinatorics import next_corner, prev_corner


class VertexOrderChanged(ValueError):
    """PyMeshLab's mesh no longer has the input's vertices in the input's order."""


def _arrays(V, F) -> tuple[np.ndarray, np.ndarray]:
    V, F = checked_arrays(V, F)
    if V.shape[0] >= 2 ** 31:
        raise ValueError("PyMeshLab takes 32-bit face indices")
    if not np.isfinite(V).all():
        raise ValueError("V has NaN or infinite coordinates (PyMeshLab's curvature filter "
                         "aborts the process on them)")
    return V, F


def _check_same(ms, V, F, after: str) -> None:
    m = ms.current_mesh()
    W = m.vertex_matrix()
    if W.shape != V.shape or not np.array_equal(W, V):
        raise VertexOrderChanged(
            f"after {after} PyMeshLab's mesh has {W.shape[0]} vertices, not the input's "
            f"{V.shape[0]} in the same order; its per-vertex values cannot be matched")
    G = m.face_matrix()
    if G.shape != F.shape:
        raise VertexOrderChanged(f"after {after} PyMeshLab's mesh has {G.shape[0]} faces, "
                                 f"not the input's {F.shape[0]}")


def _meshset(V, F) -> "pymeshlab.MeshSet":
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=V, face_matrix=F.astype(np.int32)))
    _check_same(ms, V, F, "loading")
    if not np.array_equal(ms.current_mesh().face_matrix(), F):
        raise VertexOrderChanged("PyMeshLab changed the face list on loading")
    return ms


def exact_mixed_voronoi_areas(V, F, exact: bool = False):
    """The reference's mixed Voronoi areas (Meyer et al. 2003) of the float input, exact.

    ``ddg_oracle.reference.laplacian.vertex_areas_voronoi`` when that module is present,
    else the same rule computed here from ``ddg_oracle.reference.metric`` (exact squared
    lengths, ``Surd`` cotangents and areas): a non-obtuse face gives corner c
    ``(l_a^2 cot(opposite a) + l_b^2 cot(opposite b)) / 8`` over its two sides
    a, b; an obtuse face (decided exactly) gives A/2 to the obtuse corner and
    A/4 to the others.  Sums are exact.  Returns floats (each correctly
    rounded), or the exact ``Surd`` values with ``exact=True``.
    """
    from ..reference import PolyhedralSurface

    surface = PolyhedralSurface.from_arrays(V, F)
    try:
        from ..reference.laplacian import vertex_areas_voronoi
    except ImportError:
        areas = _mixed_areas_from_metric(surface.metric())
    else:
        areas = vertex_areas_voronoi(surface)
    return list(areas) if exact else np.array([float(a) for a in areas])


def mixed_voronoi_areas(V, F) -> np.ndarray:
    """Meyer et al.'s mixed areas (the rule of :func:`exact_mixed_voronoi_areas`) in float64,
    vectorized: what the adapter multiplies vcg's Gaussian curvature by.  Each face's term
    is within about u (10 + 4 kappa^2) A_f of the exact one (kappa: the face's largest
    |cot|; u = 2^-53), against vcg's own single-precision area error of order 2^-24 A_f
    (tests/test_oracles_pymeshlab.py checks both): the conversion adds nothing a check of
    vcg could see, in milliseconds where the exact rule takes seconds per 10,000 faces.
    The obtuse test is the float one; at a right angle both rules give the same area."""
    V = np.asarray(V, dtype=np.float64)
    F = np.asarray(F, dtype=np.int64)
    P = V[F]                                    # (m, 3 corners, 3)
    e = np.roll(P, -1, axis=1) - P              # e[:, c]: the side from corner c to c + 1
    w = -np.roll(e, 1, axis=1)                  # the side from corner c to c - 1
    dot = np.einsum("mcd,mcd->mc", e, w)
    cross = np.linalg.norm(np.cross(e, w), axis=2)
    cot = dot / cross                           # cot of the angle at each corner
    sq = np.einsum("mcd,mcd->mc", e, e)
    area = cross[:, :1] / 2
    # corner c: (|side c|^2 cot(opposite it) + |side c-1|^2 cot(opposite it)) / 8
    voronoi = (sq * np.roll(cot, 1, axis=1) + np.roll(sq, 1, axis=1) * np.roll(cot, -1, axis=1)) / 8
    obtuse = dot < 0
    per_corner = np.where(obtuse.any(axis=1, keepdims=True),
                          np.where(obtuse, area / 2, area / 4), voronoi)
    return np.bincount(F.ravel(), weights=per_corner.ravel(), minlength=len(V))


def _mixed_areas_from_metric(metric) -> list:
    from ..reference.exact import Surd

    t = metric.triangulation
    acc = [Surd(0)] * t.n_vertices
    for f, face in enumerate(t.faces):
        sq = metric.face_squared_lengths(f)   # halfedge 3f + c runs c -> c+1, opposite c+2
        cot = [metric.corner_cot(f, c) for c in range(3)]
        A = metric.area(f)
        obtuse = [c for c in range(3) if cot[c] < 0]
        for c in range(3):
            if obtuse:
                a = A / 2 if c == obtuse[0] else A / 4
            else:
                a = (sq[c] * cot[prev_corner(c)] + sq[prev_corner(c)] * cot[next_corner(c)]) / 8
            acc[face[c]] = acc[face[c]] + a
    return acc


def boundary_edge_angles(V, F) -> dict[int, float]:
    """phi(v): the angle in R^3 between the two boundary edges at each boundary vertex v
    (what vcg's MeanAndGaussian subtracts there), float64 via atan2(|a x b|, a.b)."""
    edges = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
    uniq, counts = np.unique(edges, axis=0, return_counts=True)
    nbrs: dict[int, list[int]] = {}
    for i, j in uniq[counts == 1]:
        nbrs.setdefault(int(i), []).append(int(j))
        nbrs.setdefault(int(j), []).append(int(i))
    phi = {}
    for v, ns in nbrs.items():
        if len(ns) != 2:
            raise ValueError(f"vertex {v} has {len(ns)} boundary edges (non-manifold "
                             "vertex): vcg's boundary term is not defined there")
        x, y = V[ns[0]] - V[v], V[ns[1]] - V[v]
        phi[v] = math.atan2(float(np.linalg.norm(np.cross(x, y))), float(x @ y))
    return phi


#: option -> (finding, what the library's own convention differs by) (docs/findings.md)
LIBRARY_CONVENTIONS = {
    "boundary": ("F-pymeshlab-2", "boundary term 2 pi - angle sum - phi"),
    "genus": ("F-pymeshlab-1", "genus of a non-orientable mesh is floor(h / 2)"),
}


#: this adapter as ``ddg-oracle check --impl pymeshlab`` finds it (read without importing the
#: module: ddg_oracle.application.implementations): the object, the library it needs (None: the
#: core's own dependencies), the pip extra that installs it, its place in reports
ADAPTER = {"name": "pymeshlab", "object": "PyMeshLab", "library": "pymeshlab", "extra": "pymeshlab",
           "rank": 2}


class PyMeshLab:
    """PyMeshLab as an implementation of the protocol (``protocol/methods.py``)."""

    #: vcglib computes curvature and areas in float32: tolerances use its epsilon
    machine_epsilon = 2.0 ** -23

    name = "pymeshlab"

    def __init__(self, boundary: str = "reference", genus: str = "reference"):
        self.name, self.conventions = declare("pymeshlab", LIBRARY_CONVENTIONS,
                                              boundary=boundary, genus=genus)
        self.boundary = boundary
        self.genus_convention = genus

    def __repr__(self) -> str:
        return f"PyMeshLab(boundary={self.boundary!r}, genus={self.genus_convention!r})"

    # --- raw library values (not protocol methods) ------------------------------------

    def topological_measures(self, V, F) -> dict:
        """``get_topological_measures``: vertices_number, edges_number, faces_number,
        boundary_edges, number_holes, connected_components_number, genus,
        is_mesh_two_manifold, non_two_manifold_edges / _vertices, unreferenced_vertices, ..."""
        V, F = _arrays(V, F)
        ms = _meshset(V, F)
        out = dict(ms.get_topological_measures())
        _check_same(ms, V, F, "get_topological_measures")
        return out

    def discrete_curvature(self, V, F, kind: str = "Gaussian Curvature") -> np.ndarray:
        """Per-vertex quality after ``compute_scalar_by_discrete_curvature_per_vertex``:
        'Gaussian Curvature' = vcg KG (angle defect / mixed area; boundary term see module
        doc), 'Mean Curvature' = vcg KH = sign * |(L X)_v| / (2 A_v) with L the reference's
        cotan Laplacian and A_v vcg's mixed area (docs/conventions.md)."""
        V, F = _arrays(V, F)
        ms = _meshset(V, F)
        ms.compute_scalar_by_discrete_curvature_per_vertex(curvaturetype=kind)
        _check_same(ms, V, F, "compute_scalar_by_discrete_curvature_per_vertex")
        return np.array(ms.current_mesh().vertex_scalar_array(), dtype=np.float64)

    # --- chapter 1: topology ------------------------------------------------------------

    def euler_characteristic(self, V, F) -> int:
        """vertices_number - edges_number + faces_number of ``get_topological_measures``."""
        d = self.topological_measures(V, F)
        return int(d["vertices_number"]) - int(d["edges_number"]) + int(d["faces_number"])

    def is_orientable(self, V, F) -> bool:
        """Orientable iff ``meshing_re_orient_faces_coherently`` leaves no directed edge
        used twice.

        The filter runs vcg's OrientCoherentlyMesh, which computes an
        ``orientable`` flag but PyMeshLab does not return it; on an orientable
        surface the filter orients every face coherently, on a non-orientable
        one some edge is necessarily traversed twice in the same direction.
        The adapter only checks the filter's output faces.
        """
        V, F = _arrays(V, F)
        ms = _meshset(V, F)
        ms.meshing_re_orient_faces_coherently()
        _check_same(ms, V, F, "meshing_re_orient_faces_coherently")
        FF = np.asarray(ms.current_mesh().face_matrix(), dtype=np.int64)
        directed = np.concatenate([FF[:, [0, 1]], FF[:, [1, 2]], FF[:, [2, 0]]])
        return len(np.unique(directed, axis=0)) == len(directed)

    def genus(self, V, F) -> int:
        """``get_topological_measures()['genus']``; see the module doc for non-orientable
        surfaces (option ``genus``).  Raises ValueError where PyMeshLab says undefined
        (-1: not two-manifold) or the mesh is not connected."""
        d = self.topological_measures(V, F)
        if int(d["connected_components_number"]) != 1:
            raise ValueError(f"{d['connected_components_number']} components: genus needs a "
                             "connected surface")
        if int(d["number_holes"]) < 0:
            raise ValueError("PyMeshLab: genus undefined (mesh not two-manifold)")
        if self.genus_convention == "library" or self.is_orientable(V, F):
            return int(d["genus"])
        # the surface's chi: vertices_number counts the vertices no face uses too (points
        # beside the surface, not part of it; MeshGenus itself counts the referenced ones)
        referenced = len(np.unique(np.asarray(F, dtype=np.int64)))
        chi = referenced - int(d["edges_number"]) + int(d["faces_number"])
        return 2 - chi - int(d["number_holes"])

    # --- chapter 2: curvature -----------------------------------------------------------

    def area(self, V, F) -> float:
        """``get_geometric_measures()['surface_area']``."""
        V, F = _arrays(V, F)
        ms = _meshset(V, F)
        return float(ms.get_geometric_measures()["surface_area"])

    def angle_defects(self, V, F) -> np.ndarray:
        """vcg's KG times the reference's exact mixed area; boundary term per option.  The
        curvature filter drops vertices used by no face: they are set aside first and given
        the protocol's 2 pi (``ISOLATED_VERTEX``)."""
        r = Referenced(*_arrays(V, F))
        V, F = r.V, r.F
        K = self.discrete_curvature(V, F, "Gaussian Curvature") * mixed_voronoi_areas(V, F)
        if self.boundary == "reference":
            for v, phi in boundary_edge_angles(V, F).items():
                K[v] += phi - math.pi
        return r.scatter(K, ISOLATED_VERTEX["angle_defects"])

    # --- chapter 4: Delaunay flips ------------------------------------------------------

    def planar_flip_to_delaunay(self, V, F) -> np.ndarray:
        """``meshing_edge_flip_by_planar_optimization(planartype="delaunay", iterations=0)``.

        vcg's ``TriEdgeFlip`` (tri_edge_flip.h): an edge is a candidate when its
        two faces are coplanar within ``pthreshold`` degrees (here every z = 0,
        so the normals are equal) and its quadrilateral is convex; its priority
        is ``180 - (alpha + beta)`` in degrees (alpha, beta the opposite angles,
        double precision); the filter flips while the smallest priority is below
        ``-FLT_EPSILON`` degrees.  ``iterations=0``: by default the filter then
        moves the vertices by a planar Laplacian smoothing
        (``VertexCoordPlanarLaplacian``), which would change the points.
        """
        V, F = _arrays(V, F)
        if np.any(V[:, 2] != 0):
            raise ValueError("planar_flip_to_delaunay: the points must lie in the plane z = 0")
        ms = _meshset(V, F)
        ms.meshing_edge_flip_by_planar_optimization(planartype="delaunay", iterations=0)
        _check_same(ms, V, F, "meshing_edge_flip_by_planar_optimization")
        return np.asarray(ms.current_mesh().face_matrix(), dtype=np.int64)
