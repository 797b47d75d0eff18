"""The exact reference wrapped as an implementation of the protocol.

Answers are exact (topology is integers); float views of exact values are
correctly rounded.  This is what every other implementation is compared with.
"""

from __future__ import annotations


import math

import numpy as np

from ..reference import delaunay, laplacian
from ..reference.combinatorics import Triangulation, next_corner, opposite_halfedge
from ..reference.exact import float_view, rounded_sum
from ..reference.polyhedral import PolyhedralSurface

from ..properties import memo, views
from ..properties.delaunay_exact import delaunay_of
from ..properties.example import surface_key
from ..protocol.methods import ISOLATED_VERTEX, OutsideDomain

from ..protocol.arrays import Referenced


#: this adapter as ``ddg-oracle check --impl reference`` finds it (read without importing the
#: module: ddg_oracle.application.implementations): the object, the library it needs (None: the
#: core's own dependencies), the pip extra that installs it, its place in reports
ADAPTER = {"name": "reference", "object": "ReferenceImplementation", "library": None, "extra": None,
           "rank": 0}


class ReferenceImplementation:
    """The reference on arrays.  A triangulated surface has no vertex outside its faces, so
    vertices used by no face are set aside and given the protocol's values
    (``ISOLATED_VERTEX``: angle defect 2 pi, area 0, a zero Laplacian row; each counts
    1 in V - E + F); topology questions other than chi are asked of the rest."""

    name = "reference"

    def _t(self, V, F) -> Triangulation:
        """The triangulation of these faces, built once per content for the last couple of
        meshes (a mesh file's topology properties ask for it several times)."""
        r = Referenced(V, F)
        try:
            table = self._triangulations
        except AttributeError:          # made here, not in __init__: a subclass need not call it
            table = self._triangulations = memo.Table(2)
        return table.shared((len(r.V), r.F.shape, r.F.tobytes()),
                            lambda: Triangulation.from_faces(r.F, n_vertices=len(r.V)))

    def _s(self, V, F) -> PolyhedralSurface:
        """The exact surface of these arrays, built once per content for the last couple of
        meshes: every method asked about the same mesh shares one surface, so one exact
        metric (cached on it) and one set of exact values (:func:`.memo.of`); the example
        the arrays were made from, if this process has it (:data:`.memo.DRAWN`, looked up
        by exact content, never added to), is that surface."""
        r = Referenced(V, F)
        key = (r.V.shape, r.V.tobytes(), r.F.shape, r.F.tobytes())

        def build():
            s = PolyhedralSurface.from_arrays(r.V, r.F)
            return memo.DRAWN.get(surface_key(s.positions, s.faces), s)
        try:
            table = self._surfaces
        except AttributeError:          # made here, not in __init__: a subclass need not call it
            table = self._surfaces = memo.Table(2)      # the last couple of meshes
        return table.shared(key, build)

    # chapter 1
    def euler_characteristic(self, V, F) -> int:
        return self._t(V, F).euler_characteristic() + Referenced(V, F).isolated

    def boundary_loops(self, V, F) -> list[list[int]]:
        r = Referenced(V, F)
        return [[r.index(v) for v in loop] for loop in self._t(V, F).boundary_loops()]

    def is_orientable(self, V, F) -> bool:
        return self._t(V, F).is_orientable()

    def genus(self, V, F) -> int:
        return self._t(V, F).classify().genus

    # chapter 2
    # the float views below are the properties' (views.*: once per surface object, so a
    # check of this adapter on a mesh file does not compute the exact values twice)
    def corner_angles(self, V, F):
        return views.corner_angle_views(self._s(V, F)).copy()

    def angle_defects(self, V, F):
        s, r = self._s(V, F), Referenced(V, F)
        K = np.zeros(s.n_vertices)
        for v, k in {**views.defect_views(s), **views.turning_views(s)}.items():
            K[v] = k
        return r.scatter(K, ISOLATED_VERTEX["angle_defects"])

    def edge_mean_curvature(self, V, F):
        s, r = self._s(V, F), Referenced(V, F)
        if not r.isolated:
            return dict(views.mean_curvature_views(s))
        return {tuple(sorted(r.index(v) for v in e)): h
                for e, h in views.mean_curvature_views(s).items()}

    def area(self, V, F) -> float:
        # the exact sum correctly rounded, from enclosures (no canonical form: any size)
        try:
            return rounded_sum(self._s(V, F).metric().areas)
        except OverflowError:
            return math.inf

    # chapter 3
    def cotan_laplacian(self, V, F):
        return Referenced(V, F).embed(views.laplacian_view(self._s(V, F)).copy())

    def area_gradient(self, V, F):
        from ..reference.areas import area_gradient_floats
        r = Referenced(V, F)
        out = np.full((r.n, 3), ISOLATED_VERTEX["area_gradient"])   # no face: no area to move
        out[r.keep] = np.array(area_gradient_floats(self._s(V, F)), dtype=np.float64).reshape(-1, 3)
        return out

    def solve_dirichlet(self, V, F, boundary, values):
        """The exact solution (C3.4, exact elimination over the Surd cotan weights; the
        boundary values taken exactly as the floats they are), correctly rounded.  Only
        on planar meshes (every z equal: the cotan weights are rational, the elimination
        is over Fractions); elsewhere :class:`OutsideDomain`, because exact elimination
        over the square roots of every face does not finish on float meshes (issue 18).
        The properties do not need it: they check a solver by the exact energy."""
        from fractions import Fraction
        from ..reference.dirichlet import solve_dirichlet
        r = Referenced(V, F)
        boundary = np.asarray(boundary, dtype=np.int64).reshape(-1)
        values = np.asarray(values, dtype=np.float64).reshape(-1)
        if len(boundary) != len(values):
            raise ValueError(f"solve_dirichlet: {len(boundary)} boundary vertices but "
                             f"{len(values)} values")
        if len(r.V) and np.any(r.V[:, 2] != r.V[0, 2]):
            raise OutsideDomain("the reference solves the Dirichlet problem exactly only on "
                                "planar meshes (rational cotan weights)")
        compact = {int(v): k for k, v in enumerate(r.keep)}
        fixed = {}
        for v, c in zip(boundary.tolist(), values.tolist()):
            if not 0 <= v < r.n:
                raise IndexError(f"solve_dirichlet: boundary vertex {v} is not a vertex 0..{r.n - 1}")
            if not math.isfinite(c):
                raise ValueError(f"solve_dirichlet: boundary value {c} at vertex {v} is not finite")
            fixed[v] = c
        if r.isolated and any(v not in fixed for v in range(r.n) if v not in compact):
            raise ValueError("solve_dirichlet: a vertex used by no face is not in the boundary "
                             "set: its value is not determined")
        u = solve_dirichlet(self._s(V, F), {compact[v]: Fraction(c) for v, c in fixed.items()
                                            if v in compact})
        out = np.array([fixed.get(v, 0.0) for v in range(r.n)], dtype=np.float64)
        out[r.keep] = [float_view(x) for x in u]
        return out

    def vertex_areas_barycentric(self, V, F):
        # the exact areas, correctly rounded from integers (== their float views)
        areas = laplacian.vertex_areas_floats(self._s(V, F), "barycentric")
        return Referenced(V, F).scatter(areas, ISOLATED_VERTEX["vertex_areas_barycentric"])

    def vertex_areas_voronoi(self, V, F):
        areas = laplacian.vertex_areas_floats(self._s(V, F), "voronoi")
        return Referenced(V, F).scatter(areas, ISOLATED_VERTEX["vertex_areas_voronoi"])

    # chapter 4 (column c: the edge opposite corner c, i.e. halfedge 3f + c + 1 (mod 3))
    def is_locally_delaunay(self, V, F):
        m = self._s(V, F).metric()
        t = m.triangulation
        flags = memo.of(_delaunay_flags, m)        # once per edge, not per side
        return np.array([[flags[t.edge_of(opposite_halfedge(f, c))] for c in range(3)]
                         for f in range(t.n_faces)], dtype=bool)

    def intrinsic_delaunay_laplacian(self, V, F):
        # delaunay.laplace_beltrami, with the flips and the matrix the properties' (once)
        d, _ = delaunay_of(self._s(V, F).metric())
        return Referenced(V, F).embed(views.laplacian_view(d).copy())

    def intrinsic_delaunay_triangulation(self, V, F):
        d, _ = delaunay_of(self._s(V, F).metric())
        t = d.triangulation
        l2 = [[float_view(d.face_squared_lengths(f)[next_corner(c)]) for c in range(3)]
              for f in range(t.n_faces)]
        keep = Referenced(V, F).keep
        return keep[np.array(t.faces, dtype=np.int64)], np.array(l2, dtype=float)

    def planar_delaunay(self, P):
        from ..reference.planar import delaunay_triangulation
        return np.array(delaunay_triangulation([tuple(p) for p in np.asarray(P, float)])
                        .triangulation.faces, dtype=np.int64)

    def planar_flip_to_delaunay(self, V, F):
        from ..reference.planar import planar_flip_to_delaunay
        V = np.asarray(V, float)
        if V.ndim == 2 and V.shape[1] == 3 and np.any(V[:, 2] != 0):
            raise ValueError("planar_flip_to_delaunay: the points must lie in the plane z = 0")
        pts = [(x, y) for x, y, *_ in V]
        return np.array(planar_flip_to_delaunay(pts, np.asarray(F).tolist()).triangulation.faces,
                        dtype=np.int64)


def _delaunay_flags(metric) -> list[bool]:
    """D4.4, decided exactly for every edge of ``metric``, by edge id."""
    return delaunay.delaunay_edges(metric)
