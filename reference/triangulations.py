"""The set T_(M,V) of geodesic triangulations (Definition 4.5): Examples 4.3 and 4.4.

Example 4.3 of the notes: the unit cube with V its 8 vertices has infinitely many
geodesic triangulations, with edges as long as we like; Example 4.4: so the longest
edge length l(T) is unbounded on T_(M,V) (while bounding it leaves finitely many
triangulations, Claim 4.13, checked by row L4.20 / C4.13).  The notes suggest the
unwrapping of Figure 2.8; here the long edges are made by intrinsic flips
(:mod:`ddg_oracle.reference.intrinsic`, L2.8), exactly, which is the tool of
section 4.3.

The belt.  The four side squares of the cube (the faces that meet both z = 0 and
z = 1) form a flat cylinder of circumference 4 and height 1, developed as
``R / 4Z x [0, 1]``.  Its 8 triangles join a bottom and a top vertex by 8 *rungs*;
a rung from ``(a, 0)`` to ``(c, 1)`` has *shift* ``d = c - a`` and squared length
``d^2 + 1``.  Two consecutive rungs bound a triangle with its base on the bottom
(type B) or on the top (type T).  Where a B triangle lies on the left of a rung
(oriented bottom to top, faces seen from outside) and a T triangle on its right,
the two form a parallelogram (strictly convex), and flipping the rung turns
``(a, c)`` into ``(a - 1, c + 1)``: its shift grows by 2 and no other shift
changes.  Such a rung exists in every state (the 8 triangles are 4 of each type
around the cylinder), so the flips go on forever, the sum of the shifts grows by 2
per flip, and since every shift starts at >= -1 and never decreases, after n flips
some rung has shift >= (2n + S_0) / 8 >= (n - 2) / 4 (S_0 >= -4, the initial
sum): its squared length is at least 1 + ((n - 2) / 4)^2.  That is a Dehn twist
along the belt, one flip at a time.

Every triangulation in the sequence is a geodesic triangulation of the same
piecewise flat surface (each flip is exact and keeps the metric), with vertex set
V: nothing but flips is used, and properties check the invariants (angle sums,
area, Euler characteristic) exactly.
"""

from __future__ import annotations

from collections.abc import Iterator

from .intrinsic import IntrinsicTriangulation
from .metric import PiecewiseFlatSurface
from .surfaces import cube
from .combinatorics import face_of

__all__ = ["cube_belt_twist", "belt_rungs", "longest_squared_length"]


def _heights() -> list:
    return [p[2] for p in cube().positions]


def belt_rungs(surface) -> list[int]:
    """The rungs of the cube's belt in a triangulation of the cube from
    :func:`cube_belt_twist`: the edges joining a vertex at z = 0 to one at z = 1."""
    z = _heights()
    t = surface.triangulation
    return [e for e in range(t.n_edges) if {z[v] for v in t.edge_vertices(e)} == {0, 1}]


def _twist_rung(w: IntrinsicTriangulation, z) -> int:
    """The first rung with a bottom-based triangle on its left and a top-based one on
    its right (oriented from z = 0 to z = 1): the flip that adds 2 to its shift."""
    t = w.triangulation

    def bottom_corners(f):
        return sum(z[v] == 0 for v in t.faces[f])

    for e in range(t.n_edges):
        h, g = t.edge_halfedges(e)
        ends = {z[t.tail(h)], z[t.head(h)]}
        if ends != {0, 1}:
            continue
        if z[t.tail(h)] == 1:              # orient the rung from the bottom to the top
            h, g = g, h
        if bottom_corners(face_of(h)) == 2 and bottom_corners(face_of(g)) == 1:
            return e
    raise AssertionError("no twisting rung: the belt is not a triangulated cylinder")


def cube_belt_twist(flips: int) -> Iterator[PiecewiseFlatSurface]:
    """Examples 4.3 / 4.4: ``flips + 1`` geodesic triangulations of the unit cube with
    vertex set its 8 vertices, the first ``surfaces.cube()``'s, each from the one
    before by one intrinsic flip in the belt (a Dehn twist, see the module
    docstring).  After n flips the longest edge has squared length at least
    ``1 + ((n - 2) / 4)^2``: l(T) is unbounded on T_(M,V).  Exact (every squared
    length is an integer ``d^2 + 1`` or 1 or 2).

    >>> [longest_squared_length(s) for s in cube_belt_twist(12)][::4]
    [Fraction(2, 1), Fraction(5, 1), Fraction(10, 1), Fraction(26, 1)]
    """
    if flips < 0:
        raise ValueError(f"flips must be >= 0, got {flips}")
    z = _heights()
    w = IntrinsicTriangulation(cube().metric())
    yield w.surface()
    for _ in range(flips):
        w.flip(_twist_rung(w, z))
        yield w.surface()


def longest_squared_length(surface):
    """l(T)^2 of Example 4.4: the largest squared edge length of a triangulation (exact)."""
    return max(surface.squared_lengths)
