"""The intrinsic distance on the surface of the unit cube (Definition 2.4, Remark 2.6,
Example 2.2), exact.

A point of the surface is a rational point of the boundary of [0, 1]^3.  A face is
``(axis, side)``: the points with coordinate ``axis`` equal to ``side`` (0 or 1).
A shortest path on a convex polyhedron passes through no vertex and visits every
face at most once (a second visit could be replaced by the chord inside the convex
face), so it is a straight segment in the unfolding of a simple sequence of adjacent
faces; conversely every such segment that crosses the shared edges in order is a path
on the surface.  :func:`cube_unfoldings` lists all of them with their exact squared
lengths, :func:`cube_squared_distance` takes the least: d(p, q)^2, a rational.

Unfolding across the edge between faces with outward normals ``n`` (the current one)
and ``m`` (the next) is the quarter turn ``R = d d^T + n m^T - m n^T`` about the edge
direction ``d = n x m`` (``R m = n``, ``R n = -m``): integer matrices, so every unfolded
point stays rational.
"""

from __future__ import annotations

import functools
from fractions import Fraction

from .errors import InputError

__all__ = ["cube_faces_of", "cube_unfoldings", "cube_squared_distance", "root_sum_at_least"]

FACES = tuple((axis, side) for axis in range(3) for side in (0, 1))


def _normal(face):
    axis, side = face
    return tuple((1 if side else -1) if k == axis else 0 for k in range(3))


def cube_faces_of(point) -> list[tuple[int, int]]:
    """The faces of the unit cube containing ``point`` (1 inside a face, 2 on an edge, 3
    at a vertex); :class:`InputError` if the point is not on the cube's surface."""
    p = tuple(Fraction(x) for x in point)
    if len(p) != 3 or any(not 0 <= x <= 1 for x in p):
        raise InputError(f"{point} is not a point of the unit cube [0, 1]^3")
    faces = [(a, s) for a, s in FACES if p[a] == s]
    if not faces:
        raise InputError(f"{point} is inside the unit cube, not on its surface")
    return faces


def _apply(M, t, x):
    return tuple(sum(M[i][k] * x[k] for k in range(3)) + t[i] for i in range(3))


def _turn(n, m):
    d = (n[1] * m[2] - n[2] * m[1], n[2] * m[0] - n[0] * m[2], n[0] * m[1] - n[1] * m[0])
    return [[d[i] * d[j] + n[i] * m[j] - m[i] * n[j] for j in range(3)] for i in range(3)]


def _edge(f, g):
    """The shared edge of adjacent faces f, g as its two endpoints."""
    (a, s), (b, r) = f, g
    c = 3 - a - b
    lo = [0, 0, 0]
    lo[a], lo[b] = s, r
    hi = list(lo)
    hi[c] = 1
    return tuple(map(Fraction, lo)), tuple(map(Fraction, hi))


def _cross2(u, v, axis):
    i, j = [k for k in range(3) if k != axis]
    return u[i] * v[j] - u[j] * v[i]


def _segments_meet(p, q, a, b, axis) -> bool:
    """Closed segments pq and ab of the plane ``x_axis = const`` meet (exact)."""
    def side(x, y, z):
        c = _cross2(tuple(y[k] - x[k] for k in range(3)), tuple(z[k] - x[k] for k in range(3)), axis)
        return (c > 0) - (c < 0)
    d1, d2, d3, d4 = side(p, q, a), side(p, q, b), side(a, b, p), side(a, b, q)
    if d1 * d2 > 0 or d3 * d4 > 0:
        return False
    if d1 == d2 == 0:                        # collinear: the projections must overlap
        return all(min(p[k], q[k]) <= max(a[k], b[k]) and min(a[k], b[k]) <= max(p[k], q[k])
                   for k in range(3))
    return True


@functools.lru_cache(maxsize=None)
def _charts(start) -> tuple:
    """Every simple sequence of adjacent faces from ``start``, with the isometry (M, t)
    that unfolds its last face into the plane of ``start`` and the unfolded shared edges
    (independent of the points: computed once per start face)."""
    identity = ((1, 0, 0), (0, 1, 0), (0, 0, 1))
    out, stack = [], [((start,), identity, (0, 0, 0), ())]
    while stack:
        seq, M, t, edges = stack.pop()
        out.append((seq, M, t, edges))
        face = seq[-1]
        n = _normal(face)
        for g in FACES:
            if g in seq or g[0] == face[0]:
                continue
            e0, e1 = _edge(face, g)
            a, b = _apply(M, t, e0), _apply(M, t, e1)
            R = _turn(n, _normal(g))
            shift = tuple(e0[i] - sum(R[i][k] * e0[k] for k in range(3)) for i in range(3))
            M2 = tuple(tuple(sum(M[i][k] * R[k][j] for k in range(3)) for j in range(3))
                       for i in range(3))
            stack.append((seq + (g,), M2, _apply(M, t, shift), edges + ((a, b),)))
    return tuple(out)


def cube_unfoldings(p, q) -> list[tuple[tuple, Fraction]]:
    """Every straight segment from ``p`` to ``q`` in an unfolding of a simple sequence of
    adjacent faces that crosses the shared edges in order: ``(faces, squared length)``,
    exact.  Each is a path on the surface (Example 2.2: not each a shortest one)."""
    p = tuple(Fraction(x) for x in p)
    q = tuple(Fraction(x) for x in q)
    ends = set(cube_faces_of(q))
    out = []
    for start in cube_faces_of(p):
        for seq, M, t, edges in _charts(start):
            if seq[-1] in ends:
                q2 = _apply(M, t, q)
                if all(_segments_meet(p, q2, a, b, start[0]) for a, b in edges):
                    out.append((seq, sum((x - y) ** 2 for x, y in zip(p, q2))))
    return out


def cube_squared_distance(p, q) -> Fraction:
    """D2.4 / R2.6: d(p, q)^2 for the intrinsic distance of the unit cube's surface (the
    infimum of the lengths of curves on the surface), exact.

    >>> cube_squared_distance((0, 0, 0), (1, 1, 1))       # opposite corners: sqrt 5
    Fraction(5, 1)
    """
    return min(length for _, length in cube_unfoldings(p, q))


def root_sum_at_least(a, b, c) -> bool:
    """sqrt(b) + sqrt(c) >= sqrt(a) for rationals a, b, c >= 0, exact (the triangle
    inequality on squared distances): a - b - c <= 0 or (a - b - c)^2 <= 4 b c."""
    a, b, c = Fraction(a), Fraction(b), Fraction(c)
    s = a - b - c
    return s <= 0 or s * s <= 4 * b * c
