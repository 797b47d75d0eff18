"""Delaunay tessellations by empty immersed disks (Definitions 4.2, 4.3, Claim 4.6), exact.

Definition 4.3 of the notes defines the Delaunay tessellation of a closed piecewise
flat surface without Voronoi cells: a closed cell is ``phi(conv phi^-1(V))`` for an
immersed empty disk ``phi : D -> M`` (Definition 4.2: an isometric immersion of an
open disk meeting no vertex) with vertices on its boundary; Claim 4.6 says these cells
form a tessellation.  This module builds, for a face of a triangulation, the immersed
disk bounded by the face's circumcircle, by *developing* it:

* the face is laid out in the plane (scaled by the length of its first side, a
  similarity, so that no square root of a squared length is needed: the corners are
  ``(0, 0)``, ``(e, 0)``, ``((e + b - a) / 2, 2 A)``, as in :mod:`.intrinsic`);
* every face that the open disk reaches is laid out next to the one it was reached
  from, across their common edge, from its squared lengths and area alone
  (``X = P + t (Q - P) + h J (Q - P)`` with ``t = (|PQ|^2 + |PX|^2 - |QX|^2) /
  (2 |PQ|^2)`` and ``h = +-2 A / |PQ|^2``, both ratios, so the similarity is kept);
  an edge is crossed when its open segment meets the open disk (an exact quadratic
  test, no division), faces reached twice at the same place are laid out once;
* each vertex laid out is classified by the sign of its power with respect to the
  circle (exact; the origin is on the circle, so the power is ``|X|^2 - 2 <X, c>``,
  multiplied by ``2 A > 0`` to clear the denominator of the centre ``c``).

The disk is *empty* (Definition 4.2) when no vertex is laid out strictly inside; then
its vertices on the circle are ``phi^-1(V)`` and the faces with all three corners on
the circle triangulate the cell ``conv phi^-1(V)``.  If a vertex lies inside, it is
found at a finite depth of the breadth-first development (the disk around it would be
developed forever otherwise) and returned as the witness.

Exact throughout: positions are Fractions or :class:`~ddg_oracle.reference.exact.Surd`
numbers in the field of the surface's areas and squared lengths; the number of faces
developed is bounded by ``limit`` (a typed error when exceeded, never a hang).
Rational-metric surfaces (flat tori, polycubes, their flips) stay rational.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

from .errors import InputError, TermLimitExceeded
from .exact.surds import sign, simplest
from .intrinsic import surface_metric
from .combinatorics import corner_of, face_of, next_corner, prev_corner
from .linear import cross2, dot, sub

__all__ = ["ImmersedDisk", "circumdisk", "empty_disk_cells", "DevelopmentLimitExceeded"]


class DevelopmentLimitExceeded(TermLimitExceeded):
    """More faces would have to be laid out than the limit allows."""


@dataclass(frozen=True)
class ImmersedDisk:
    """The circumdisk of ``face`` developed over the surface (see the module docstring).

    ``inside``: ``(vertex, position)`` of a vertex strictly inside (the disk is not
    empty), else None.  ``on_circle``: the distinct positions on the circle with the
    vertex at each (``phi^-1(V)`` when empty).  ``cell``: the faces laid out with all
    three corners on the circle, as ``(face, corner positions)`` pairs.  ``copies``: the
    number of faces laid out.  Positions are in the face's scaled plane."""

    face: int
    inside: tuple | None
    on_circle: tuple
    cell: tuple
    copies: int

    @property
    def empty(self) -> bool:
        return self.inside is None

    @property
    def cell_faces(self) -> frozenset:
        return frozenset(g for g, _ in self.cell)


def circumdisk(surface, face: int, limit: int = 20_000) -> ImmersedDisk:
    """D4.2 / D4.3: the circumdisk of ``face`` developed as an immersed disk, exact.

    ``surface``: a closed :class:`~ddg_oracle.reference.metric.Metric` (a
    :class:`~ddg_oracle.reference.metric.PiecewiseFlatSurface`, an
    :class:`~ddg_oracle.reference.intrinsic.IntrinsicTriangulation`) or a polyhedral surface.  Raises :class:`InputError` on a surface with boundary
    (Definition 4.3 is for surfaces without boundary) and
    :class:`DevelopmentLimitExceeded` past ``limit`` faces laid out.

    >>> from ddg_oracle.reference import surfaces
    >>> d = circumdisk(surfaces.octahedron().metric(), 0)
    >>> d.empty, len(d.on_circle), sorted(d.cell_faces)
    (True, 3, [0])
    """
    m = surface_metric(surface)
    t = m.triangulation
    boundary = [e for e in range(t.n_edges) if t.is_boundary_edge(e)]
    if boundary:
        raise InputError("Definition 4.3 is for surfaces without boundary: this one has "
                         f"{len(boundary)} boundary edges")
    if not 0 <= face < t.n_faces:
        raise InputError(f"face {face} out of range: {t.n_faces} faces")
    e, a, b = (simplest(x) for x in m.face_squared_lengths(face))
    two_area = simplest(2 * m.area(face))
    start = ((0, 0), (e, 0), (simplest((e + b - a) / 2), two_area))
    x2, y2 = start[2]
    n_centre = simplest(x2 * x2 + y2 * y2 - e * x2)   # c = (e / 2, n_centre / (2 y2))

    def power(p):
        """sign(|p - c|^2 - R^2) times y2 > 0: y2 |p|^2 - y2 e p_x - n_centre p_y."""
        return simplest(y2 * dot(p, p) - y2 * e * p[0] - n_centre * p[1])

    def meets_disk(p, q) -> bool:
        """The open segment pq meets the open disk (p, q not strictly inside)."""
        d = sub(q, p)
        alpha = y2 * dot(d, d)
        beta = simplest(2 * y2 * dot(p, d) - y2 * e * d[0] - n_centre * d[1])
        gamma = power(p)
        # the minimum of alpha t^2 + beta t + gamma lies in (0, 1) and is negative
        return 0 < -beta < 2 * alpha and beta * beta > 4 * alpha * gamma

    on_circle: dict = {}
    for c, p in enumerate(start):
        on_circle[p] = t.faces[face][c]
    cell = []
    seen = {(face, start)}
    queue = deque([(face, start, -1)])
    copies = 0
    while queue:
        g, pos, came_from = queue.popleft()
        copies += 1
        if copies > limit:
            raise DevelopmentLimitExceeded(
                f"circumdisk of face {face}: more than {limit} faces laid out")
        if all(p in on_circle for p in pos):
            cell.append((g, pos))
        for c in range(3):
            h = 3 * g + c
            if h == came_from:
                continue
            p, q, w = pos[c], pos[next_corner(c)], pos[prev_corner(c)]
            if not meets_disk(p, q):
                continue
            th = t.twin(h)
            g2, c2 = face_of(th), corner_of(th)
            # corner c2 of g2 is the tail of th: the head of h, or its tail if reversed
            tail, head = (p, q) if t.reversed_gluing(h) else (q, p)
            sq_pq = simplest(m.squared_length(th))
            sq_px = simplest(m.squared_length(3 * g2 + prev_corner(c2)))   # X -> tail
            sq_qx = simplest(m.squared_length(3 * g2 + next_corner(c2)))   # head -> X
            d = sub(head, tail)
            along = simplest((sq_pq + sq_px - sq_qx) / (2 * sq_pq))
            height = simplest(2 * m.area(g2) / sq_pq)
            if sign(cross2(d, sub(w, tail))) > 0:      # X on the other side of the edge
                height = -height
            x = (simplest(tail[0] + along * d[0] - height * d[1]),
                 simplest(tail[1] + along * d[1] + height * d[0]))
            new = [None, None, None]
            new[c2], new[next_corner(c2)], new[prev_corner(c2)] = tail, head, x
            key = (g2, tuple(new))
            if key in seen:
                continue
            seen.add(key)
            s = sign(power(x))
            vertex = t.faces[g2][prev_corner(c2)]
            if s < 0:
                return ImmersedDisk(face, (vertex, x), tuple(on_circle.items()), tuple(cell),
                                    copies)
            if s == 0:
                on_circle.setdefault(x, vertex)
            queue.append((g2, tuple(new), th))
    return ImmersedDisk(face, None, tuple(on_circle.items()), tuple(cell), copies)


def empty_disk_cells(surface, limit: int = 20_000) -> list[frozenset]:
    """D4.3 / C4.6: the 2-cells of the Delaunay tessellation of a Delaunay triangulation,
    as sets of faces, read off the empty circumdisks: face f is in the cell
    ``phi(conv phi^-1(V))`` of its own disk.  Raises :class:`InputError` if some face's
    circumdisk is not empty (the triangulation is not Delaunay, T4.7), naming the face and
    the vertex inside."""
    m = surface_metric(surface)
    cells = {}
    for f in range(m.triangulation.n_faces):
        d = circumdisk(m, f, limit)
        if not d.empty:
            raise InputError(f"face {f}: vertex {d.inside[0]} lies inside its circumdisk "
                             "(not a Delaunay triangulation)")
        cells.setdefault(d.cell_faces, None)
    return list(cells)
