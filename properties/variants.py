"""Exact variants of a polyhedral surface, where real bugs hide (issue 16).

Each function takes a :class:`PolyhedralSurface` with exact (rational) positions
and returns another one, exactly: no float is involved, so the reference stays
exact on the result and a strategy can round to floats once, at the end.

* :func:`permuted` -- vertices relabelled, faces reordered, corners rotated;
* :func:`with_sliver` -- one face split 1-to-3 at a point 2**-k from a corner
  (two needles) or from an edge's midpoint (a cap, with an angle near pi; on the
  boundary when that edge is a boundary edge);
* :func:`disjoint_union` -- a second component beside the first, or touching it
  at one point (two vertices at the same position, not merged);
* :func:`fan` and :func:`bipyramid` -- vertices of valence up to 128 (CAD end
  caps), exactly planar or lifted by 2**-k.

Strategies draw the small integers these take; every integer 0 is the plain case,
so a failing example shrinks to it.
"""

from __future__ import annotations

import math
import random
from fractions import Fraction

from ..reference.combinatorics import Triangulation, cyclic, face_of, opposite_corner
from ..reference.exact.rationals import on_common_denominator
from ..reference.polyhedral import PolyhedralSurface
from ..reference.linear import cross

__all__ = ["relabelled", "permuted", "reversed_faces", "with_sliver", "slivers", "disjoint_union",
           "union_of", "fan", "bipyramid", "circle_point", "is_degenerate", "degenerate_faces",
           "has_fold"]


def relabelled(t: Triangulation, positions, key: int) -> tuple[Triangulation, tuple, list]:
    """``(t', positions', perm)``: vertex v renamed ``perm[v]`` (a shuffle chosen by ``key``;
    0 is the identity), the gluings kept (:meth:`Triangulation.relabelled`, so loops and
    double edges survive), each position moved with its vertex."""
    n = t.n_vertices
    perm = list(range(n))
    if key:
        random.Random(key).shuffle(perm)
    inverse = [0] * n
    for v, w in enumerate(perm):
        inverse[w] = v
    return t.relabelled(perm), tuple(positions[inverse[w]] for w in range(n)), perm


def permuted(s: PolyhedralSurface, seed: int) -> PolyhedralSurface:
    """The same surface with its vertex ids shuffled, its faces reordered and each face's
    corners rotated (orientation kept), all chosen by ``seed``; seed 0 is the identity."""
    if not seed:
        return s
    rng = random.Random(seed)
    n = s.n_vertices
    perm = list(range(n))
    rng.shuffle(perm)                           # old vertex v is now perm[v]
    faces = [tuple(perm[v] for v in f) for f in s.triangulation.faces]
    rng.shuffle(faces)
    faces = [f[r:] + f[:r] for f, r in ((f, rng.randrange(3)) for f in faces)]
    positions = [None] * n
    for v, w in enumerate(perm):
        positions[w] = s.positions[v]
    return PolyhedralSurface(Triangulation.from_faces(faces, n_vertices=n), positions)


def reversed_faces(t: Triangulation, seed: int) -> tuple[Triangulation, int]:
    """``t`` with a random nonempty subset of its faces listed in the other direction
    (chosen by ``seed``): the same surface, inconsistently oriented (an orientable one
    stays orientable: no gluing changes, only which halfedges are listed); (t', how many).
    A boundary walk or an orientation test that follows the faces' own direction breaks."""
    rng = random.Random(seed)
    faces = [list(f) for f in t.faces]
    flip = [f for f in range(len(faces)) if rng.random() < 0.5] or [0]
    for f in flip:
        a, b, c = faces[f]
        faces[f] = [a, c, b]
    return Triangulation.from_faces(faces, n_vertices=t.n_vertices), len(flip)


def union_of(t: Triangulation, other: Triangulation) -> Triangulation:
    """Two triangulations as the components of one (``other``'s vertices after ``t``'s)."""
    n = t.n_vertices
    faces = [tuple(f) for f in t.faces] + [tuple(v + n for v in f) for f in other.faces]
    return Triangulation.from_faces(faces, n_vertices=n + other.n_vertices)


def with_sliver(s: PolyhedralSurface, halfedge: int, kind: str, k: int,
                lift: int | None = None) -> PolyhedralSurface:
    """Face f = face_of(halfedge) split 1-to-3 at a new point p, with (a, b) the edge of that
    halfedge and c the third corner:

    * ``kind="needle"``: p = x_a + 2**-k (centroid - x_a): the two faces at a
      get an edge 2**-k times the others (needles), the third is nearly f;
    * ``kind="cap"``: p = mid(a, b) + 2**-k (x_c - mid(a, b)): face (a, b, p)
      has an angle near pi at p (a cap, at the boundary when (a, b) is a
      boundary edge).

    ``lift``: p is also moved off f's plane by 2**-(k + lift) times f's normal
    (the cross product, exact), so the new vertex is not exactly flat.  The
    faces keep f's orientation; the surface's topology is unchanged.
    """
    faces = [tuple(f) for f in s.triangulation.faces]
    f, r = divmod(halfedge % (3 * len(faces)), 3)
    a, b, c = cyclic(faces[f], r)
    x = s.positions
    t = Fraction(1, 2 ** k)
    if kind == "needle":
        centroid = [(x[a][i] + x[b][i] + x[c][i]) / 3 for i in range(3)]
        p = [x[a][i] + t * (centroid[i] - x[a][i]) for i in range(3)]
    elif kind == "cap":
        mid = [(x[a][i] + x[b][i]) / 2 for i in range(3)]
        p = [mid[i] + t * (x[c][i] - mid[i]) for i in range(3)]
    else:
        raise ValueError(f"unknown sliver kind {kind!r}")
    if lift is not None:
        nrm = cross([x[b][i] - x[a][i] for i in range(3)], [x[c][i] - x[a][i] for i in range(3)])
        p = [p[i] + t * Fraction(1, 2 ** lift) * nrm[i] for i in range(3)]
    q = s.n_vertices
    faces[f] = (a, b, q)
    faces += [(b, c, q), (c, a, q)]
    return PolyhedralSurface(Triangulation.from_faces(faces, n_vertices=q + 1),
                             list(x) + [tuple(p)])


#: how several slivers lie (:func:`slivers`), as the degenerate-mesh benchmarks draw them
SLIVER_FAMILIES = ("isolated", "clustered", "banded")


def slivers(s: PolyhedralSurface, halfedge: int, kind: str, k: int, lift: int | None = None,
            family: str = "isolated", count: int = 1) -> PolyhedralSurface:
    """``count`` slivers (:func:`with_sliver`, all of one ``kind`` and size 2**-k): one
    (``isolated``); each next one in a face at the previous one's new vertex
    (``clustered``: several needles or caps around one point); or each next one in the
    face across the previous face's far edge (``banded``: a row of slivers across the
    mesh, which stops at the boundary)."""
    if family not in SLIVER_FAMILIES:
        raise ValueError(f"unknown sliver family {family!r}; one of {SLIVER_FAMILIES}")
    h = halfedge % s.triangulation.n_halfedges
    for i in range(count):
        s = with_sliver(s, h, kind, k, lift)
        m = s.triangulation.n_faces - 2            # the new faces: (b, c, q) = m, (c, a, q) = m + 1
        if family == "clustered":
            # the edge (q, b) of the face (b, c, q), the one of f's three that is not a
            # sliver itself: the next sliver is as small, at q (not one inside another)
            h = 3 * m + 2
        elif family == "banded":
            h = s.triangulation.twin(3 * m)         # across the edge (b, c), away from a
            if h < 0:
                break                               # the band reached the boundary
    return s


def disjoint_union(s: PolyhedralSurface, other: PolyhedralSurface,
                   touch: bool = False) -> PolyhedralSurface:
    """``s`` and ``other`` as two components of one mesh (other's vertices numbered after s's).

    ``other`` is moved by a dyadic translation: beside ``s`` (its bounding box
    shifted past s's along x), or, with ``touch``, so that one of its vertices lands
    exactly on one of s's: two vertices at one position, which an implementation
    must not merge.
    """
    if touch:
        # s's lexicographically largest vertex on other's smallest: other then lies beyond
        # s's extreme point, and (halving other about that vertex until it does) the two
        # share exactly that one position
        a, b = max(s.positions), min(other.positions)
        pts = other.positions
        own = set(map(tuple, s.positions))
        while len({tuple(x + ai - bi for x, ai, bi in zip(q, a, b)) for q in pts} & own) > 1:
            pts = [tuple(bi + (x - bi) / 2 for x, bi in zip(q, b)) for q in pts]
        other = other.with_positions(pts)
        shift = [ai - bi for ai, bi in zip(a, b)]
    else:
        hi = max(p[0] for p in s.positions)
        lo = min(p[0] for p in other.positions)
        width = max(p[0] for p in other.positions) - lo
        shift = [hi - lo + max(width, Fraction(1)) / 2, Fraction(0), Fraction(0)]
    positions = list(s.positions) + [tuple(p + d for p, d in zip(q, shift))
                                     for q in other.positions]
    return PolyhedralSurface(union_of(s.triangulation, other.triangulation), positions)


def circle_point(angle: float, denominator: int = 1000) -> tuple[Fraction, Fraction]:
    """A rational point of the unit circle near ``angle`` (not at angle pi): the rational
    parametrisation ((1 - t^2), 2 t) / (1 + t^2) at t ~ tan(angle / 2)."""
    t = Fraction(math.tan(angle / 2)).limit_denominator(denominator)
    d = 1 + t * t
    return (1 - t * t) / d, 2 * t / d


def _ring(n: int):
    # rational unit-circle points at angles 2 pi (j + 1/3) / n: distinct, never at pi,
    # exact cosines and sines, so an exactly planar star stays exactly planar
    return [circle_point(2 * math.pi * (j + 1 / 3) / n, 64 * n) for j in range(n)]


def fan(n: int, lift: int | None = None) -> PolyhedralSurface:
    """The star of vertex 0 with n neighbours on the unit circle (a disk of n faces): exactly
    planar in z = 0, or with the centre lifted to z = 2**-lift (nearly flat)."""
    h = Fraction(0) if lift is None else Fraction(1, 2 ** lift)
    faces = [(0, 1 + j, 1 + (j + 1) % n) for j in range(n)]
    return PolyhedralSurface(Triangulation.from_faces(faces),
                             [(Fraction(0), Fraction(0), h)] + [(c, s_, Fraction(0))
                                                                for c, s_ in _ring(n)])


def bipyramid(n: int, top: Fraction = Fraction(1), bottom: Fraction = Fraction(1)) -> PolyhedralSurface:
    """A closed sphere: apexes (0, 0, top), (0, 0, -bottom) over an n-gon on the unit circle;
    both apexes have valence n, the ring vertices 4."""
    faces = [(0, 2 + j, 2 + (j + 1) % n) for j in range(n)]
    faces += [(1, 2 + (j + 1) % n, 2 + j) for j in range(n)]
    pts = [(Fraction(0), Fraction(0), top), (Fraction(0), Fraction(0), -bottom)]
    pts += [(c, s_, Fraction(0)) for c, s_ in _ring(n)]
    return PolyhedralSurface(Triangulation.from_faces(faces), pts)


def _integer_positions(s: PolyhedralSurface) -> list[tuple[int, int, int]]:
    """The positions times one common positive denominator, as integers: the same surface
    scaled, so every sign and zero test below is unchanged, at the price of integer
    arithmetic (these tests run on every drawn example)."""
    flat, _ = on_common_denominator([c for p in s.positions for c in p])
    return [tuple(flat[k:k + 3]) for k in range(0, len(flat), 3)]


def is_degenerate(s: PolyhedralSurface) -> bool:
    """Whether some face has exactly zero area (its corners collinear), exactly."""
    return degenerate_faces(s.positions, s.triangulation.faces)


def degenerate_faces(positions, faces) -> bool:
    """Whether some face of these exact positions has zero area (corners collinear or
    equal), exactly (integer arithmetic on the common denominator)."""
    flat, _ = on_common_denominator([c for p in positions for c in p])
    x = [tuple(flat[k:k + 3]) for k in range(0, len(flat), 3)]
    for a, b, c in faces:
        u = [x[b][i] - x[a][i] for i in range(3)]
        v = [x[c][i] - x[a][i] for i in range(3)]
        if not any(cross(u, v)):
            return True
    return False


def has_fold(s: PolyhedralSurface) -> bool:
    """Whether two faces sharing an edge are folded onto each other (dihedral angle exactly
    +-pi: both opposite vertices on the same side of the edge, in one plane with it),
    exactly, whatever the faces' orientation.  The reference refuses such a surface."""
    t, x = s.triangulation, _integer_positions(s)
    for e in range(t.n_edges):
        h, g = t.edge_halfedges(e)
        if g < 0:
            continue
        ax, ay, az = x[t.tail(h)]
        bx, by, bz = x[t.head(h)]
        px, py, pz = x[t.faces[face_of(h)][opposite_corner(h)]]
        qx, qy, qz = x[t.faces[face_of(g)][opposite_corner(g)]]
        dx, dy, dz = bx - ax, by - ay, bz - az
        ux, uy, uz = px - ax, py - ay, pz - az
        wx, wy, wz = qx - ax, qy - ay, qz - az
        # with n = d x u and m = d x w: p, q and the edge are coplanar iff n . w = 0, and
        # then on the same side iff n . m = |d|^2 (u' . w') > 0 (u', w': the parts of u, w
        # perpendicular to d), the projection test without a division.  Written out: this
        # runs on every edge of every drawn example (a fifth of drawing a surface)
        nx, ny, nz = dy * uz - dz * uy, dz * ux - dx * uz, dx * uy - dy * ux
        if nx * wx + ny * wy + nz * wz:
            continue
        mx, my, mz = dy * wz - dz * wy, dz * wx - dx * wz, dx * wy - dy * wx
        if nx * mx + ny * my + nz * mz > 0:
            return True
    return False
