"""Delaunay tessellations of planar point sets (section 4.1), exact.

Points are pairs of rationals (ints, Fractions, floats taken exactly); every
predicate is the sign of an exact polynomial in the coordinates, so no
tolerance decides anything.  Catalog rows:

* D4.1 -- :func:`orientation`, :func:`in_circle`, :func:`circle_position`:
  the exact predicates; :func:`empty_disk_violations` checks the empty disk
  property of a tessellation, :func:`is_empty_disk_edge` the Delaunay edge
  property of an edge of a planar triangulation.
* T4.1 -- :func:`delaunay_triangulation` (the intrinsic edge-flip algorithm,
  :func:`ddg_oracle.reference.delaunay.flip_to_delaunay`, started from the sweep
  triangulation :func:`planar_triangulation`) and :func:`delaunay_tessellation`
  (its triangles merged across the edges of weight exactly 0, R4.7): the
  unique Delaunay tessellation, each cell a convex polygon inscribed in an
  empty circle.  Its dual: :func:`voronoi_vertices` (circumcentres of the
  cells) and :func:`voronoi_edges` (dual edges, orthogonal to their Delaunay
  edges).
* A4.13 in the plane -- :func:`planar_flip_to_delaunay`: the edge-flip
  algorithm started from a given triangulation of a polygon (boundary kept);
  :func:`straight_line_flip` (L4.11) the flip of a strictly convex quadrilateral.
* L4.3 / P4.4 -- :func:`angle_criterion`: ``alpha + beta`` against ``pi`` with
  exact :class:`~ddg_oracle.reference.exact.Angle` values, independent of the in-circle
  determinant; :func:`is_delaunay_by_angles` for a whole triangulation.
* T4.2 -- :func:`invert`, :func:`inversion` (rational centre and squared
  radius: rational points stay rational), :func:`cells_avoiding` and
  :func:`inversion_obstructions`: the precise planar statement of Moebius
  invariance, proved in the docstring of :func:`inversion_obstructions`.
* T4.21 -- :func:`all_triangulations` (breadth-first search of the flip
  graph, which is connected for planar point sets) and
  :func:`laplacian_difference`: ``L_T - L_Delaunay`` is positive
  semidefinite (:func:`ddg_oracle.reference.sparse.is_positive_semidefinite`), so the
  Delaunay triangulation minimises the Dirichlet energy of every function.
* L4.8 -- :func:`inscribed_angle_cot`, :func:`tangent_chord_cot`: the
  tangent-chord angle equals the inscribed angle, as exact cotangents.
* R4.1 -- :func:`quad_tessellation_faces`: the Voronoi-Delaunay quad
  tessellation, each face a kite with orthogonal diagonals, the Delaunay one
  bisected; dual edges cross iff both opposite angles are at most pi/2.
* R4.2 -- :func:`stereographic_lift`, :func:`is_lifted_hull_facet`: Delaunay
  triangles are the hull facets of the points lifted to the sphere.

Triangulations are returned as :class:`~ddg_oracle.reference.polyhedral.PolyhedralSurface`
with two-dimensional positions (the input points, in input order: vertex ``i``
is point ``i``) and counterclockwise faces.  A tessellation is a frozenset of
cells, each cell the frozenset of its vertex ids (a convex polygon is
determined by its vertices; :func:`cell_boundary` orders them).

Bad input raises :class:`~ddg_oracle.reference.errors.TooFewPoints`,
:class:`~ddg_oracle.reference.errors.RepeatedPoint` (naming both indices) or
:class:`~ddg_oracle.reference.errors.CollinearPoints`.

>>> square = [(0, 0), (1, 0), (1, 1), (0, 1), (2, 0)]
>>> sorted(sorted(c) for c in delaunay_tessellation(square))
[[0, 1, 2, 3], [1, 2, 4]]
"""

from __future__ import annotations

from collections import deque
from fractions import Fraction
from functools import cmp_to_key
from typing import Iterable

from .delaunay import delaunay_tessellation_edges, flip_to_delaunay, incircle_determinant
from .errors import (BadInversion, BadQuadrilateral, BadShape, ClockwiseFace, CollinearPoints,
                     DegenerateFace, InputError, RepeatedPoint, TooFewPoints)
from .exact import corner_angle, pi, sign
from .exact.rationals import rational
from .intrinsic import flip, is_flippable
from .laplacian import cotan_laplacian
from .polyhedral import PolyhedralSurface, orientation3d
from .sparse import SparseMatrix
from .combinatorics import face_of, next_corner, opposite_corner
from .linear import cross2, dot, sub

__all__ = ["as_point", "as_point_set", "orientation", "in_circle", "circle_position", "cocircular_cells",
           "circumcircle", "planar_triangulation", "straight_line_flip", "planar_flip_to_delaunay", "delaunay_triangulation",
           "delaunay_tessellation", "cell_boundary", "tessellation_edges", "voronoi_vertices",
           "voronoi_edges", "empty_disk_violations", "is_empty_disk_edge", "angle_criterion",
           "is_delaunay_by_angles", "invert", "inversion", "cells_avoiding",
           "inversion_obstructions", "all_triangulations", "triangulation_key",
           "laplacian_difference", "inscribed_angle_cot", "tangent_chord_cot",
           "quad_tessellation_faces", "stereographic_lift", "is_lifted_hull_facet"]

_ZERO = Fraction(0)


# --- points ---------------------------------------------------------------------------


def as_point(p, where: str = "point") -> tuple[Fraction, Fraction]:
    """``p`` as an exact point of the plane, a pair of Fractions.

    >>> as_point((1, 0.5))
    (Fraction(1, 1), Fraction(1, 2))
    """
    if hasattr(p, "tolist"):              # numpy rows, without importing numpy
        p = p.tolist()
    try:
        coords = list(p)
    except TypeError:
        raise BadShape(f"{where}: a point is a pair of coordinates, got {p!r}") from None
    if len(coords) != 2:
        raise BadShape(f"{where} has {len(coords)} coordinates; a planar point has 2")
    return (rational(coords[0], f"{where}, x"), rational(coords[1], f"{where}, y"))


def as_point_set(points) -> tuple[tuple[Fraction, Fraction], ...]:
    """The points, exact, checked to span a triangulation: at least three,
    pairwise distinct, not all on one line.

    >>> as_point_set([(0, 0), (1, 0), (0, 0)])
    Traceback (most recent call last):
    ...
    ddg_oracle.reference.errors.RepeatedPoint: points 0 and 2 coincide: (0, 0)
    """
    if hasattr(points, "tolist"):
        points = points.tolist()
    pts = tuple(as_point(p, f"point {i}") for i, p in enumerate(points))
    if len(pts) < 3:
        raise TooFewPoints(f"{len(pts)} point(s): a triangulation needs at least 3")
    first: dict = {}
    for i, p in enumerate(pts):
        if p in first:
            raise RepeatedPoint(f"points {first[p]} and {i} coincide: "
                                f"({_fmt(p[0])}, {_fmt(p[1])})")
        first[p] = i
    a, b = pts[0], pts[1]
    if all(orientation(a, b, c) == 0 for c in pts[2:]):
        raise CollinearPoints(f"all {len(pts)} points lie on one line (through points 0 and 1): "
                              "their convex hull has no interior")
    return pts


def _fmt(x: Fraction) -> str:
    return str(x.numerator) if x.denominator == 1 else f"{x.numerator}/{x.denominator}"


# --- D4.1: exact predicates ---------------------------------------------------------------


def _cross(a, b, c):
    """``(b - a) x (c - a)``: twice the signed area of the triangle ``a b c``."""
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def orientation(a, b, c) -> int:
    """The orientation of the triangle ``a b c``: ``+1`` counterclockwise (``c`` to
    the left of the line from ``a`` to ``b``), ``-1`` clockwise, ``0`` collinear.

    The sign of ``(b - a) x (c - a)``, exact (D4.1's predicates start here).

    >>> orientation((0, 0), (1, 0), (0, 1)), orientation((0, 0), (1, 1), (2, 2))
    (1, 0)
    """
    return sign(_cross(as_point(a), as_point(b), as_point(c)))


def in_circle(a, b, c, d) -> int:
    """The sign of the in-circle determinant (D4.1), exact.

    ``det [[ax - dx, ay - dy, |a - d|^2], [b ...], [c ...]]``: positive iff
    ``d`` lies inside the circle through ``a, b, c`` *when (a, b, c) is
    counterclockwise*; for any non-collinear ``a, b, c`` it is
    ``orientation(a, b, c)`` times :func:`circle_position` (``+1`` inside,
    ``0`` on, ``-1`` outside).  For collinear ``a, b, c`` the circle degenerates
    into their line and the sign says on which side of it ``d`` lies (0 on
    it).  The same determinant as the intrinsic test
    :func:`ddg_oracle.reference.delaunay.in_circumcircle`.

    >>> in_circle((0, 0), (1, 0), (0, 1), (1, 1))        # the unit square is cocircular
    0
    >>> in_circle((0, 0), (1, 0), (0, 1), (Fraction(1, 2), Fraction(1, 2)))
    1
    >>> in_circle((0, 0), (0, 1), (1, 0), (Fraction(1, 2), Fraction(1, 2)))   # clockwise
    -1
    """
    return sign(incircle_determinant(as_point(a), as_point(b), as_point(c), as_point(d)))


def circle_position(a, b, c, d) -> int:
    """Where ``d`` lies relative to the circle through ``a, b, c``: ``+1`` inside,
    ``0`` on, ``-1`` outside; independent of the orientation of ``a, b, c``.

    Raises :class:`~ddg_oracle.reference.errors.CollinearPoints` if ``a, b, c`` are collinear
    (no circle).

    >>> circle_position((0, 0), (0, 1), (1, 0), (Fraction(1, 2), Fraction(1, 2)))
    1
    """
    o = orientation(a, b, c)
    if o == 0:
        raise CollinearPoints(f"{a}, {b}, {c} are collinear: no circle passes through them")
    return o * in_circle(a, b, c, d)


def circumcircle(a, b, c) -> tuple[tuple[Fraction, Fraction], Fraction]:
    """``(centre, squared radius)`` of the circle through ``a, b, c``, exact.

    The centre is the Voronoi vertex dual to the triangle (T4.1).

    >>> circumcircle((0, 0), (2, 0), (0, 2))
    ((Fraction(1, 1), Fraction(1, 1)), Fraction(2, 1))
    """
    a, b, c = as_point(a), as_point(b), as_point(c)
    bx, by = b[0] - a[0], b[1] - a[1]
    cx, cy = c[0] - a[0], c[1] - a[1]
    d = 2 * (bx * cy - by * cx)
    if not d:
        raise CollinearPoints(f"{a}, {b}, {c} are collinear: no circle passes through them")
    b2, c2 = bx * bx + by * by, cx * cx + cy * cy
    ux = (cy * b2 - by * c2) / d
    uy = (bx * c2 - cx * b2) / d
    return (a[0] + ux, a[1] + uy), ux * ux + uy * uy


# --- a first triangulation ----------------------------------------------------------------


def planar_triangulation(points) -> PolyhedralSurface:
    """A triangulation of the convex hull of ``points`` with every point as a
    vertex (a sweep triangulation), exact; faces counterclockwise.

    The points are swept in lexicographic order.  The first ones that are
    collinear are joined by a fan to the first point off their line; every
    later point ``p`` is lexicographically largest so far, hence strictly
    outside the current hull, and is joined to every hull edge ``a -> b``
    (counterclockwise) that it sees strictly (``orientation(a, b, p) < 0``);
    these edges form one chain.  Hull edges that ``p`` sees at angle 0 (``p`` on
    their line) are not used, so no triangle is degenerate, and points on hull
    edges stay vertices of the boundary.  ``O(n^2)``.

    >>> t = planar_triangulation([(0, 0), (2, 0), (1, 0), (1, 1)])
    >>> sorted(sorted(f) for f in t.faces)
    [[0, 2, 3], [1, 2, 3]]
    """
    pts = as_point_set(points)
    order = sorted(range(len(pts)), key=lambda i: pts[i])
    p0, p1 = pts[order[0]], pts[order[1]]
    k = next(m for m in range(2, len(order)) if orientation(p0, p1, pts[order[m]]) != 0)
    apex = order[k]
    faces = []
    side = orientation(p0, p1, pts[apex])
    line = order[:k]
    for a, b in zip(line, line[1:]):
        faces.append((a, b, apex) if side > 0 else (b, a, apex))
    hull = line + [apex] if side > 0 else [apex] + line[::-1]     # counterclockwise cycle
    for v in order[k + 1:]:
        p = pts[v]
        n = len(hull)
        seen = [orientation(pts[hull[i]], pts[hull[(i + 1) % n]], p) < 0 for i in range(n)]
        start = next(i for i in range(n) if seen[i] and not seen[i - 1])
        i = start
        while seen[i % n]:
            a, b = hull[i % n], hull[(i + 1) % n]
            faces.append((b, a, v))
            i += 1
        end = i % n                       # hull[start] .. hull[end] were the chain's ends
        if end > start:
            hull = hull[:start + 1] + [v] + hull[end:]
        else:                             # the chain wraps past index 0
            hull = hull[end:start + 1] + [v]
    return PolyhedralSurface.from_arrays(pts, faces)


# --- T4.1: the Delaunay triangulation and tessellation -------------------------------------


def delaunay_triangulation(points) -> PolyhedralSurface:
    """A Delaunay triangulation of ``points`` (T4.1), exact.

    :func:`planar_triangulation`, then the edge-flip algorithm
    :func:`ddg_oracle.reference.delaunay.flip_to_delaunay` (A4.13) on its metric: for
    planar points the intrinsic flip of a convex quadrilateral is the ordinary
    flip, so the flipped triangulation is a straight-line triangulation of the
    same points, rational throughout.  Returned with the input positions;
    every interior edge satisfies the angle criterion (P4.4).  Cocircular
    points make it non-unique (which diagonals are chosen); the tessellation
    (:func:`delaunay_tessellation`) is unique.

    >>> d = delaunay_triangulation([(0, 0), (4, 0), (4, 1), (0, 1), (2, -1)])
    >>> sorted(sorted(f) for f in d.faces)
    [[0, 3, 4], [1, 2, 4], [2, 3, 4]]
    """
    start = planar_triangulation(points)
    return planar_flip_to_delaunay(start.positions, start.triangulation.faces)


def straight_line_flip(points, triangulation, e: int):
    """L4.11 in the plane: the triangulation with interior edge ``e`` flipped when its
    quadrilateral is strictly convex (both new faces counterclockwise, exact), else
    None: the flip that keeps a counterclockwise triangulation of ``points`` a
    straight-line one.  A non-Delaunay edge always has a strictly convex
    quadrilateral, so :func:`planar_flip_to_delaunay` never meets None.

    >>> from ddg_oracle.reference.combinatorics import Triangulation
    >>> pts = [(0, 0), (2, -1), (4, 0), (2, 1)]
    >>> t = Triangulation.from_faces([(0, 1, 2), (0, 2, 3)])
    >>> e = next(e for e in range(t.n_edges) if set(t.edge_vertices(e)) == {0, 2})
    >>> sorted(sorted(f) for f in straight_line_flip(pts, t, e).faces)
    [[0, 1, 3], [1, 2, 3]]
    >>> straight_line_flip([(0, 0), (-1, -1), (4, 0), (-1, 1)], t, e) is None  # reflex at 0
    True
    """
    pts = as_point_set(points)
    if triangulation.is_boundary_edge(e):
        return None
    u = triangulation.flip(e)
    h, t = u.edge_halfedges(e)                  # the two faces the flip rebuilt
    if all(orientation(*(pts[v] for v in u.faces[face_of(x)])) > 0 for x in (h, t)):
        return u
    return None


def planar_flip_to_delaunay(points, faces) -> PolyhedralSurface:
    """A4.13 in the plane: the triangulation ``faces`` of ``points`` after flipping
    interior edges until every one is Delaunay (P4.4), exact; boundary kept.

    ``faces`` must be counterclockwise and non-degenerate (a straight-line
    triangulation of a polygon, possibly non-convex, possibly with holes); the
    flips are those of its flat metric
    (:func:`ddg_oracle.reference.delaunay.flip_to_delaunay`): in the plane a non-Delaunay
    edge has a strictly convex quadrilateral (L4.11), so each flip is the
    ordinary one and the result is again a straight-line triangulation of the
    same polygon, with the input positions.  On the convex hull of the points it
    is a Delaunay triangulation of the points (T4.1).

    Raises :class:`~ddg_oracle.reference.errors.DegenerateFace` or
    :class:`~ddg_oracle.reference.errors.ClockwiseFace` naming the face, besides the face
    list errors of :class:`~ddg_oracle.reference.combinatorics.Triangulation`.

    >>> t = planar_flip_to_delaunay([(0, 0), (2, -1), (4, 0), (2, 1)], [(0, 1, 2), (0, 2, 3)])
    >>> sorted(sorted(f) for f in t.faces)
    [[0, 1, 3], [1, 2, 3]]
    """
    pts = as_point_set(points)
    start = PolyhedralSurface.from_arrays(pts, faces)
    for k, face in enumerate(start.triangulation.faces):
        o = orientation(*(pts[v] for v in face))
        if o == 0:
            raise DegenerateFace(f"face {k} {tuple(face)} is degenerate: its points are collinear")
        if o < 0:
            raise ClockwiseFace(f"face {k} {tuple(face)} runs clockwise; a planar triangulation "
                                "here has counterclockwise faces")
    m, _log = flip_to_delaunay(start.metric())
    return PolyhedralSurface(m.triangulation, start.positions)


def _components(n: int, pairs: Iterable[tuple[int, int]]) -> list[list[int]]:
    """The classes of ``0..n-1`` under the equivalence generated by ``pairs``."""
    label = list(range(n))            # class label of each element: merge by relabelling
    members = {i: [i] for i in range(n)}
    for a, b in pairs:
        ka, kb = label[a], label[b]
        if ka == kb:
            continue
        if len(members[ka]) < len(members[kb]):
            ka, kb = kb, ka
        for x in members.pop(kb):    # the smaller class joins the larger one
            label[x] = ka
            members[ka].append(x)
    return list(members.values())


def delaunay_tessellation(points) -> frozenset:
    """The Delaunay tessellation of ``points`` (T4.1): a frozenset of cells, each
    the frozenset of its vertex ids; exact and unique.

    The triangles of :func:`delaunay_triangulation` are merged across every
    interior edge whose cotan weight is exactly 0 (R4.7,
    :func:`ddg_oracle.reference.delaunay.delaunay_tessellation_edges`): such an edge joins
    two triangles inscribed in one circle.  Each cell is a convex polygon
    whose vertices are all the points on an empty circle (D4.1,
    :func:`empty_disk_violations` checks it).

    >>> grid = [(x, y) for x in range(3) for y in range(2)]
    >>> sorted(sorted(c) for c in delaunay_tessellation(grid))
    [[0, 1, 2, 3], [2, 3, 4, 5]]
    """
    d = delaunay_triangulation(points)
    m = d.metric()
    tri = m.triangulation
    keep = delaunay_tessellation_edges(m)
    merge = []
    for e in range(tri.n_edges):
        h, t = tri.edge_halfedges(e)
        if t >= 0 and e not in keep:
            merge.append((face_of(h), face_of(t)))
    cells = []
    for group in _components(tri.n_faces, merge):
        cells.append(frozenset(v for f in group for v in tri.faces[f]))
    return frozenset(cells)


def cocircular_cells(points, triangles) -> frozenset:
    """R4.7 for any list of triangles (vertex-id triples) of ``points``: the triangles
    merged across every shared edge whose four points lie exactly on one circle
    (:func:`in_circle` is 0), as a frozenset of cells (frozensets of vertex ids).

    For a Delaunay triangulation this is the Delaunay tessellation, however a
    library split its cocircular cells (T4.1 compares implementations by it).

    >>> sorted(sorted(c) for c in cocircular_cells([(0, 0), (1, 0), (1, 1), (0, 1)],
    ...                                            [(0, 1, 2), (0, 2, 3)]))
    [[0, 1, 2, 3]]

    Two triangles on the same three points (a triangle given twice) form no quadrilateral:
    nothing is merged across their edges.

    >>> sorted(sorted(c) for c in cocircular_cells([(0, 0), (1, 0), (0, 1)],
    ...                                            [(0, 1, 2), (0, 1, 2)]))
    [[0, 1, 2]]
    """
    pts = as_point_set(points)
    tris = [tuple(t) for t in triangles]
    by_edge: dict = {}
    for k, t in enumerate(tris):
        for c in range(3):
            by_edge.setdefault(frozenset((t[c], t[next_corner(c)])), []).append(k)
    merge = []
    for ks in by_edge.values():
        if len(ks) == 2:
            a, b = (tris[k] for k in ks)
            other = set(b) - set(a)
            if len(other) != 1:
                continue                    # the same three points: no quadrilateral
            (d,) = other
            if in_circle(*(pts[v] for v in a), pts[d]) == 0:    # the sign of a's orientation
                merge.append(tuple(ks))                          # does not matter for 0
    return frozenset(frozenset(v for k in group for v in tris[k])
                     for group in _components(len(tris), merge))


def cell_boundary(points, cell) -> tuple[int, ...]:
    """The vertices of a convex cell in counterclockwise order, starting at the
    smallest id (exact; the cell's points must be in strictly convex position,
    as the vertices of a Delaunay cell are).

    >>> cell_boundary([(0, 0), (1, 1), (1, 0), (0, 1)], {0, 1, 2, 3})
    (0, 2, 1, 3)
    """
    pts = [as_point(p, f"point {i}") for i, p in enumerate(points)]
    ids = sorted(cell)
    low = min(ids, key=lambda i: (pts[i][1], pts[i][0]))   # extreme: the others within pi

    def cmp(i, j):
        return -orientation(pts[low], pts[i], pts[j])

    ring = [low] + sorted((i for i in ids if i != low), key=cmp_to_key(cmp))
    k = ring.index(ids[0])
    return tuple(ring[k:] + ring[:k])


def tessellation_edges(points, cells) -> frozenset:
    """The edges of a tessellation: the pairs ``frozenset({i, j})`` of consecutive
    vertices of some cell's boundary (:func:`cell_boundary`)."""
    out = set()
    for cell in cells:
        ring = cell_boundary(points, cell)
        out.update(frozenset(p) for p in zip(ring, ring[1:] + ring[:1]))
    return frozenset(out)


def voronoi_vertices(points, cells) -> dict:
    """T4.1: the Voronoi vertex of every cell, the centre of its circle
    (:func:`circumcircle` of any three of its vertices), exact."""
    pts = [as_point(p, f"point {i}") for i, p in enumerate(points)]
    out = {}
    for cell in cells:
        a, b, c = cell_boundary(pts, cell)[:3]
        out[cell] = circumcircle(pts[a], pts[b], pts[c])[0]
    return out


def voronoi_edges(points, cells) -> dict:
    """T4.1: ``{frozenset({i, j}): (q, r)}`` for every interior edge ``ij`` of the
    tessellation, ``q, r`` the Voronoi vertices of its two cells: the Voronoi
    edge dual to ``ij``.  (Boundary edges have unbounded Voronoi edges, left out.)
    Duality: ``q`` and ``r`` are equidistant from ``i`` and ``j``, so the dual
    edge lies on the perpendicular bisector of ``ij`` and ``(q - r) . (i - j) = 0``.
    """
    centres = voronoi_vertices(points, cells)
    sides: dict = {}
    for cell in cells:
        ring = cell_boundary(points, cell)
        for e in zip(ring, ring[1:] + ring[:1]):
            sides.setdefault(frozenset(e), []).append(cell)
    return {e: (centres[cs[0]], centres[cs[1]]) for e, cs in sides.items() if len(cs) == 2}


def empty_disk_violations(points, cells) -> list[tuple[frozenset, int, str]]:
    """D4.1: every failure of the empty disk property of a tessellation, exact.

    For each cell: its vertices must lie on one circle (``"not cocircular"``)
    and no point may lie strictly inside that circle (``"inside"``).  Returns
    ``(cell, point id, reason)`` triples; empty iff the tessellation has the
    empty disk property.  Accepts triangulations too (faces as cells).

    >>> pts = [(0, 0), (4, 0), (0, 4), (1, 1)]
    >>> empty_disk_violations(pts, [{0, 1, 2}])
    [(frozenset({0, 1, 2}), 3, 'inside')]
    """
    pts = [as_point(p, f"point {i}") for i, p in enumerate(points)]
    out = []
    for cell in cells:
        cell = frozenset(cell)
        a, b, c = cell_boundary(pts, cell)[:3]
        for v in sorted(cell):
            if circle_position(pts[a], pts[b], pts[c], pts[v]) != 0:
                out.append((cell, v, "not cocircular"))
        for v in range(len(pts)):
            if v not in cell and circle_position(pts[a], pts[b], pts[c], pts[v]) > 0:
                out.append((cell, v, "inside"))
    return out


def is_empty_disk_edge(surface: PolyhedralSurface, e: int) -> bool:
    """D4.1: edge ``e`` of a planar triangulation is a Delaunay edge iff neither
    face on it has the other's opposite vertex strictly inside its circumcircle.

    Both tests are made on the positions (``circle_position``), as the
    definition states them; boundary edges are Delaunay.  (The intrinsic test
    :func:`ddg_oracle.reference.delaunay.in_circumcircle` does the same on an unfolding.)
    """
    tri = surface.triangulation
    h, t = tri.edge_halfedges(e)
    if t < 0:
        return True
    p = surface.positions
    f, g = tri.faces[face_of(h)], tri.faces[face_of(t)]
    k = f[opposite_corner(h)]
    l_ = g[opposite_corner(t)]
    return (circle_position(*(p[v] for v in f), p[l_]) <= 0
            and circle_position(*(p[v] for v in g), p[k]) <= 0)


# --- L4.3 / P4.4: the angle criterion --------------------------------------------------------


def _angle_at(apex, a, b):
    """The angle of ``a apex b`` in (0, pi), exact: ``cot = (u . v) / |u x v|``."""
    u = (a[0] - apex[0], a[1] - apex[1])
    v = (b[0] - apex[0], b[1] - apex[1])
    return corner_angle((u[0] * v[0] + u[1] * v[1]) / abs(u[0] * v[1] - u[1] * v[0]))


def angle_criterion(p1, p2, p3, p4) -> int:
    """L4.3: the sign of ``alpha + beta - pi``, ``alpha = angle P1 P2 P3`` (at P2),
    ``beta = angle P3 P4 P1`` (at P4); exact.

    By the lemma ``+1`` iff P4 lies inside the circle through P1, P2, P3, ``0``
    on it, ``-1`` outside (the same values as :func:`circle_position`).  The
    angles are exact :class:`~ddg_oracle.reference.exact.Angle` values (arccot of a
    rational), summed and compared with ``pi`` by certified enclosures and an
    exact zero test: no determinant is involved.

    Hypothesis ("cyclically ordered"): P2 and P4 lie strictly on opposite
    sides of the line P1 P3 (the quadrilateral need not be convex; by the
    inscribed angle theorem the points seeing the chord P1 P3 at the angle
    ``pi - alpha`` from that side are exactly the arc).  Otherwise
    :class:`~ddg_oracle.reference.errors.BadQuadrilateral`.

    >>> angle_criterion((1, 0), (0, 1), (-1, 0), (0, -1))      # a square: on the circle
    0
    >>> angle_criterion((1, 0), (0, 1), (-1, 0), (0, Fraction(-1, 2)))
    1
    """
    p1, p2, p3, p4 = (as_point(p, f"P{i + 1}") for i, p in enumerate((p1, p2, p3, p4)))
    if orientation(p1, p3, p2) * orientation(p1, p3, p4) >= 0:
        raise BadQuadrilateral("L4.3 needs P2 and P4 strictly on opposite sides of the line "
                               f"P1 P3; got P1 = {p1}, P2 = {p2}, P3 = {p3}, P4 = {p4}")
    return (_angle_at(p2, p1, p3) + _angle_at(p4, p3, p1) - pi).sign()


def is_delaunay_by_angles(surface: PolyhedralSurface) -> bool:
    """P4.4: a planar triangulation is Delaunay iff for every interior edge the two
    opposite angles sum to at most pi (:func:`angle_criterion` of the edge's
    quadrilateral ``i, k, j, l`` is ``<= 0``); exact."""
    tri = surface.triangulation
    p = surface.positions
    for e in range(tri.n_edges):
        h, t = tri.edge_halfedges(e)
        if t < 0:
            continue
        i, j = tri.tail(h), tri.head(h)
        k = tri.faces[face_of(h)][opposite_corner(h)]
        l_ = tri.faces[face_of(t)][opposite_corner(t)]
        if angle_criterion(p[i], p[k], p[j], p[l_]) > 0:
            return False
    return True


# --- T4.2: Moebius invariance ----------------------------------------------------------------


def invert(point, centre, squared_radius=1) -> tuple[Fraction, Fraction]:
    """Inversion in the circle with ``centre`` and ``squared_radius`` (> 0):
    ``x -> c + rho (x - c) / |x - c|^2``.  Rational data give a rational image.

    >>> invert((2, 0), (0, 0), 4)
    (Fraction(2, 1), Fraction(0, 1))
    >>> invert((1, 1), (0, 0))
    (Fraction(1, 2), Fraction(1, 2))
    """
    x, c = as_point(point), as_point(centre, "centre")
    rho = rational(squared_radius, "squared radius")
    if rho <= 0:
        raise BadInversion(f"squared radius {rho} <= 0")
    dx, dy = x[0] - c[0], x[1] - c[1]
    d2 = dx * dx + dy * dy
    if not d2:
        raise BadInversion(f"the point {x} is the centre of the inversion (its image is infinity)")
    return (c[0] + rho * dx / d2, c[1] + rho * dy / d2)


def inversion(points, centre, squared_radius=1) -> tuple:
    """:func:`invert` applied to every point (same order); the centre must not be
    one of them (:class:`~ddg_oracle.reference.errors.BadInversion`, naming it)."""
    out = []
    for i, p in enumerate(points):
        try:
            out.append(invert(p, centre, squared_radius))
        except BadInversion as err:
            raise BadInversion(f"point {i}: {err}") from None
    return tuple(out)


def _closed_disk_contains(pts, cell, c) -> bool:
    a, b, d = cell_boundary(pts, cell)[:3]
    return circle_position(pts[a], pts[b], pts[d], c) >= 0


def cells_avoiding(points, cells, centre) -> frozenset:
    """The cells whose *closed* circumdisk does not contain ``centre``.

    T4.2, local form: for an inversion ``M`` with centre ``c`` (not a point),
    ``M`` maps these cells of the Delaunay tessellation of ``V`` one to one onto
    the cells of the Delaunay tessellation of ``M(V)`` whose closed circumdisks
    do not contain ``c`` (same vertex ids).  Proof: ``M`` maps a circle not
    through ``c`` to a circle not through ``c``, and the open disk it bounds
    (not containing ``c``) onto the open disk bounded by the image (not
    containing ``c``); so an empty disk with the cell's points on its boundary
    maps to one, and ``M`` is its own inverse.
    """
    pts = [as_point(p, f"point {i}") for i, p in enumerate(points)]
    c = as_point(centre, "centre")
    return frozenset(cell for cell in cells if not _closed_disk_contains(pts, cell, c))


def inversion_obstructions(points, centre) -> list[tuple[str, frozenset]]:
    """T4.2, precise planar statement: what keeps the inversion ``M`` with centre
    ``c`` from mapping the Delaunay tessellation of ``V`` onto that of ``M(V)``.

    The notes state (Theorem 4.2) that being Delaunay is Moebius invariant.
    For planar point sets that holds cell by cell (:func:`cells_avoiding`) but
    not for the whole tessellation.  Exactly:

    **Statement.**  Let ``V`` (at least 3 points, not all collinear, not all on
    one circle) and ``c`` not in ``V``; let ``M`` be an inversion centred at
    ``c`` (any radius) with ``M(V)`` not collinear.  Then
    ``D(M(V)) = M(D(V))`` (as sets of vertex sets) iff none of these holds:

    * ``"delaunay disk"``: ``c`` lies in the closed circumdisk of a cell of
      ``D(V)``;
    * ``"farthest disk"``: ``c`` lies in the open disk of a circle through at
      least 3 points of ``V`` whose closed disk contains all of ``V`` (a cell of
      the farthest-point Delaunay tessellation);
    * ``"supporting line"``: a line through at least 3 points of ``V`` with all
      of ``V`` on one closed side has ``c`` strictly on that side.

    If ``V`` lies on one circle ``C``: ``D(V) = {V}`` and ``D(M(V)) = {M(V)}``
    whenever ``c`` is not on ``C`` (then nothing is returned), while ``c`` on
    ``C`` makes ``M(V)`` collinear (returned as ``"delaunay disk"``).

    **Proof.**  Write ``D`` for the open disk of a circle ``S``; ``M`` swaps
    ``c`` and infinity and is its own inverse.  (1) A cell ``C`` of ``D(V)``
    with ``c`` outside its closed disk maps to a cell (:func:`cells_avoiding`).
    If ``c`` lies on ``S``, ``M(S)`` is a line and ``M(C)`` (at least 3
    points) is collinear, not a cell.  If ``c`` lies in ``D``, ``M`` maps the
    exterior of ``S`` into the open disk of ``M(S)``, so the points of
    ``V - C`` (there are some) lie strictly inside the only circle through
    ``M(C)``: not a cell.  (2) Conversely let ``C'`` be a cell of ``D(M(V))``
    with empty open disk ``D'``.  If ``c`` is outside the closure of ``D'``
    then ``C' = M(C)`` for a cell ``C`` avoiding ``c`` (as in (1)).  If ``c``
    is in ``D'``, ``M(D')`` is the exterior of a circle ``S`` through
    ``M(C')``, empty of ``V``, and ``c`` is not in it: ``S`` is a farthest
    circle with ``c`` in its open disk; ``M(C')`` is no cell of ``D(V)``, since
    a cell's open disk is empty and this one contains the rest of ``V``.  If
    ``c`` is on the circle ``dD'``, ``M(dD')`` is a line through the at least 3
    points ``M(C')`` with the open half-plane ``M(D')`` empty, and ``c`` on
    the other side: a supporting line, and ``M(C')`` is collinear, no cell of
    ``D(V)``.  Read backwards, each obstruction produces such a ``C'`` or
    destroys such a ``C``, which proves "iff".  (On the sphere, with infinity
    as one more point, the statement is plain invariance: Remark 4.2.)

    Returns ``(kind, vertex ids)`` pairs, sorted; empty iff the tessellation
    is preserved.  Brute force over triples and pairs of points (``O(n^4)``):
    meant for small point sets.

    >>> V = [(0, 0), (1, 0), (2, 0), (1, 5)]        # three points on a hull line
    >>> inversion_obstructions(V, (-3, 1))
    [('supporting line', frozenset({0, 1, 2}))]
    """
    pts = as_point_set(points)
    c = as_point(centre, "centre")
    if c in pts:
        raise BadInversion(f"the centre {c} is point {pts.index(c)}")
    n = len(pts)
    cells = delaunay_tessellation(pts)
    if len(cells) == 1 and len(next(iter(cells))) == n:          # all on one circle
        (cell,) = cells
        a, b, d = cell_boundary(pts, cell)[:3]
        on = circle_position(pts[a], pts[b], pts[d], c) == 0
        return [("delaunay disk", cell)] if on else []
    out = set()
    for cell in cells:
        if _closed_disk_contains(pts, cell, c):
            out.add(("delaunay disk", cell))
    for i in range(n):
        for j in range(i + 1, n):
            for k in range(j + 1, n):
                if orientation(pts[i], pts[j], pts[k]) == 0:
                    continue
                where = [circle_position(pts[i], pts[j], pts[k], q) for q in pts]
                # V in the closed disk (V is not all on the circle: handled above)
                if min(where) >= 0 and circle_position(pts[i], pts[j], pts[k], c) > 0:
                    out.add(("farthest disk", frozenset(v for v in range(n) if where[v] == 0)))
    for i in range(n):
        for j in range(i + 1, n):
            side = [orientation(pts[i], pts[j], q) for q in pts]
            on = frozenset(v for v in range(n) if side[v] == 0)
            if len(on) < 3 or (min(side) < 0 < max(side)):
                continue
            inner = max(side) if max(side) else min(side)
            if orientation(pts[i], pts[j], c) == inner:
                out.add(("supporting line", on))
    return sorted(out, key=lambda kv: (kv[0], sorted(kv[1])))


# --- T4.21: all triangulations, the Delaunay triangulation minimises the energy ----------------


def triangulation_key(surface) -> frozenset:
    """The faces of a triangulation as a frozenset of sorted vertex triples: two
    straight-line triangulations of one point set are equal iff their keys are."""
    tri = surface.triangulation
    return frozenset(tuple(sorted(f)) for f in tri.faces)


def all_triangulations(points, limit: int = 20000) -> list[PolyhedralSurface]:
    """Every triangulation of the point set with all points as vertices (T4.21),
    by breadth-first search of the flip graph from :func:`planar_triangulation`.

    A flip replaces the diagonal of a strictly convex quadrilateral of two
    triangles (:func:`ddg_oracle.reference.intrinsic.is_flippable`, exact); the flip graph
    of a planar point set is connected (every triangulation flips to a
    Delaunay triangulation, and the triangulations of one convex cocircular
    cell are connected by flips), so the search finds them all.  Identified by
    :func:`triangulation_key`.  Raises :class:`~ddg_oracle.reference.errors.InputError` if
    there are more than ``limit`` (the count grows exponentially with the
    number of points: keep point sets small).

    >>> len(all_triangulations([(0, 0), (2, 0), (3, 2), (1, 3), (-1, 2)]))   # convex pentagon
    5
    """
    start = planar_triangulation(points)
    positions = start.positions
    seen = {triangulation_key(start): start.metric()}
    queue = deque([start.metric()])
    while queue:
        m = queue.popleft()
        tri = m.triangulation
        for e in range(tri.n_edges):
            if tri.is_boundary_edge(e) or not is_flippable(m, e):
                continue
            r = flip(m, e)
            key = frozenset(tuple(sorted(f)) for f in r.triangulation.faces)
            if key not in seen:
                if len(seen) >= limit:
                    raise InputError(f"more than limit = {limit} triangulations; pass a larger "
                                     "limit or use fewer points")
                seen[key] = r
                queue.append(r)
    return [PolyhedralSurface(m.triangulation, positions) for m in seen.values()]


def laplacian_difference(surface, other) -> SparseMatrix:
    """``L_surface - L_other`` of two triangulations of the same vertex set, exact
    (cotan Laplacians, :func:`ddg_oracle.reference.laplacian.cotan_laplacian`).

    T4.21: for ``other`` a Delaunay triangulation this is positive
    semidefinite for every triangulation ``surface``
    (:func:`ddg_oracle.reference.sparse.is_positive_semidefinite`), i.e.
    ``E_T(f) - E_Delaunay(f) = 1/2 f^T (L_T - L_D) f >= 0`` for every ``f``.
    """
    a, b = cotan_laplacian(surface), cotan_laplacian(other)
    if a.shape != b.shape:
        raise BadShape(f"Laplacians of shapes {a.shape} and {b.shape}: not the same vertex set")
    return SparseMatrix.from_entries(a.shape, a.entries() + [(i, j, -v) for i, j, v in b.entries()])


# --- circles, the Voronoi-Delaunay quad tessellation, the sphere (L4.8, R4.1, R4.2) --------


def inscribed_angle_cot(b, s, c) -> Fraction:
    """L4.8: ``cot`` of the inscribed angle ``alpha = angle BSC`` at ``s``, exact
    (``cot = (u . v) / |u x v|`` for ``u = b - s``, ``v = c - s``; an angle in
    (0, pi) is determined by its cotangent).

    >>> inscribed_angle_cot((1, 0), (0, 1), (-1, 0))       # Thales: a right angle
    Fraction(0, 1)
    """
    b, s, c = as_point(b, "B"), as_point(s, "S"), as_point(c, "C")
    u, v = sub(b, s), sub(c, s)
    if not cross2(u, v):
        raise CollinearPoints(f"B, S, C = {b}, {s}, {c} are collinear: no angle BSC in (0, pi)")
    return dot(u, v) / abs(cross2(u, v))


def tangent_chord_cot(b, s, c) -> Fraction:
    """L4.8: ``cot`` of the angle between the tangent at ``b`` to the circle through
    ``b, s, c`` and the secant ``BC``, on the side of ``BC`` away from ``s`` (the
    alternate segment), exact.  The tangent direction is ``(B - O)`` turned by 90
    degrees, ``O`` the centre (:func:`circumcircle`); Lemma 4.8 says this equals
    :func:`inscribed_angle_cot` ``(b, s, c)``.

    >>> tangent_chord_cot((1, 0), (0, 1), (-1, 0))
    Fraction(0, 1)
    """
    b, s, c = as_point(b, "B"), as_point(s, "S"), as_point(c, "C")
    o, _ = circumcircle(b, s, c)
    r = sub(b, o)
    t = (-r[1], r[0])
    chord = sub(c, b)
    # the tangent ray on the other side of the line BC than S
    if sign(cross2(chord, t)) == sign(cross2(chord, sub(s, b))):
        t = (-t[0], -t[1])
    return dot(t, chord) / abs(cross2(t, chord))


def quad_tessellation_faces(points) -> list[dict]:
    """R4.1: the faces of the Voronoi-Delaunay quad tessellation of planar points, one
    per interior edge ``ij`` of the Delaunay tessellation, exact.

    Each is ``{"edge": (i, j), "voronoi": (q, r), "orthogonal": (q - r) . (pj - pi)
    == 0, "bisected": the line qr passes through the midpoint of ij, "kite": |q - pi|
    == |q - pj| and |r - pi| == |r - pj|, "crossing": the segments qr and ij meet
    (closed segments), "acute": both angles opposite ij are at most pi/2 in the
    triangles ``i j k`` of the cells (``k`` any other vertex of the cell)}``.  The
    notes: every face is a (convex or non-convex) kite with orthogonal diagonals, the
    Delaunay diagonal bisected; the dual edges need not cross.  ``crossing ==
    acute`` holds exactly (a cell's centre lies on the far side of a chord iff the
    inscribed angle over it is obtuse)."""
    pts = as_point_set(points)
    cells = delaunay_tessellation(pts)
    sides: dict = {}
    for cell in cells:
        ring = cell_boundary(pts, cell)
        for e in zip(ring, ring[1:] + ring[:1]):
            sides.setdefault(frozenset(e), []).append((cell, ring))
    centres = voronoi_vertices(pts, cells)
    out = []
    for e, cs in sorted(sides.items(), key=lambda x: sorted(x[0])):
        if len(cs) != 2:
            continue
        i, j = sorted(e)
        pi_, pj = pts[i], pts[j]
        q, r = centres[cs[0][0]], centres[cs[1][0]]
        mid = ((pi_[0] + pj[0]) / 2, (pi_[1] + pj[1]) / 2)
        qr = sub(r, q)

        def opposite_cot(cell_ring):
            k = next(v for v in cell_ring if v not in e)
            return dot(sub(pi_, pts[k]), sub(pj, pts[k]))   # the sign of cot at k

        crossing = (sign(cross2(qr, sub(pi_, q))) * sign(cross2(qr, sub(pj, q))) <= 0
                    and sign(cross2(sub(pj, pi_), sub(q, pi_)))
                    * sign(cross2(sub(pj, pi_), sub(r, pi_))) <= 0)
        out.append({
            "edge": (i, j), "voronoi": (q, r),
            "orthogonal": dot(qr, sub(pj, pi_)) == 0,
            "bisected": cross2(qr, sub(mid, q)) == 0,
            "kite": (dot(sub(q, pi_), sub(q, pi_)) == dot(sub(q, pj), sub(q, pj))
                     and dot(sub(r, pi_), sub(r, pi_)) == dot(sub(r, pj), sub(r, pj))),
            "crossing": crossing,
            "acute": all(opposite_cot(ring) >= 0 for _, ring in cs),
        })
    return out


def stereographic_lift(p) -> tuple[Fraction, Fraction, Fraction]:
    """R4.2: the inverse stereographic projection of the plane onto the unit sphere
    from the north pole ``(0, 0, 1)``: ``(2x, 2y, x^2 + y^2 - 1) / (x^2 + y^2 + 1)``;
    rational points go to rational points, exactly.

    >>> stereographic_lift((0, 0))
    (Fraction(0, 1), Fraction(0, 1), Fraction(-1, 1))
    """
    x, y = as_point(p)
    n = x * x + y * y + 1
    return (2 * x / n, 2 * y / n, (n - 2) / n)


NORTH_POLE = (Fraction(0), Fraction(0), Fraction(1))


def is_lifted_hull_facet(points, i: int, j: int, k: int) -> bool:
    """R4.2: whether the lifted triangle ``i j k`` (:func:`stereographic_lift`) spans a
    supporting plane of the convex hull of the lifted points and the north pole: every
    other lifted point and the pole on one closed side.  The notes: this holds iff the
    planar triangle ``i j k`` is a Delaunay triangle (no point strictly inside its
    circumcircle), cocircular points lifting to coplanar ones."""
    pts = as_point_set(points)
    lifted = [stereographic_lift(p) for p in pts] + [NORTH_POLE]
    a, b, c = lifted[i], lifted[j], lifted[k]
    sides = {orientation3d(a, b, c, d) for n, d in enumerate(lifted) if n not in (i, j, k)}
    return not (1 in sides and -1 in sides)
