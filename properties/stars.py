"""Strategies of chapter 2's curvature properties (:mod:`.curvature`): the star of one
vertex built to be of a given kind (convex, planar, saddle, folded), surfaces with a vertex
whose neighbours are coplanar, rational rigid motions and relabellings, convex polyhedra;
and R2.3's stars (:mod:`.statements`): the converses of Lemma 2.4 that fail
(:data:`CONVERSE_COUNTEREXAMPLES`), rigidly moved and scaled (:func:`moved_counterexamples`).

Each draws a few small integers, builds its surface exactly and rounds it to floats once,
in a way that keeps what its property relies on (the kind of a star, coplanar neighbours,
convexity); R2.3's stars stay exact.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
from hypothesis import assume, strategies as st

from ..reference import curvature as ref
from ..reference import surfaces
from ..reference.combinatorics import Triangulation
from ..reference.linear import cross, det3, dot, sub
from ..reference.polyhedral import PolyhedralSurface

from . import memo
from . import variants
from .example import Example
from .draws import once, spread
from .strategies import floated
from .variants import circle_point


def relabel_surface(surface: PolyhedralSurface, key: int):
    """(relabelled surface, perm) with vertex v renamed perm[v] (:func:`.variants.relabelled`)."""
    t, positions, perm = variants.relabelled(surface.triangulation, surface.positions, key)
    return PolyhedralSurface(t, positions), perm


@st.composite
def rational_motions(draw):
    """(R, t): a rational rotation (Cayley transform of a rational skew matrix, T2.5) and a
    translation with small rational entries."""
    w = [Fraction(draw(st.integers(-4, 4)), draw(st.integers(1, 3))) for _ in range(3)]
    tr = tuple(Fraction(draw(st.integers(-6, 6)), 2) for _ in range(3))
    return ref.cayley_rotation(*w), tr


def _signed_permutation(k: int):
    """One of the 48 symmetries of the cube (exact on floats): a signed permutation matrix."""
    perms = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]
    p, signs = perms[k % 6], k // 6
    return [[(-1 if signs >> i & 1 else 1) if j == p[i] else 0 for j in range(3)]
            for i in range(3)]


def _star_surface(directions, kind, params, symmetry, shift):
    """The star of vertex 0 at ``shift`` with neighbours 0 + d_j, faces (0, j, j+1)."""
    n = len(directions)
    faces = [(0, 1 + j, 1 + (j + 1) % n) for j in range(n)]
    P = _signed_permutation(symmetry)
    pts = [(0, 0, 0)] + list(directions)
    pts = [tuple(sum(P[i][k] * p[k] for k in range(3)) + shift[i] for i in range(3))
           for p in pts]
    s = floated(PolyhedralSurface(Triangulation.from_faces(faces), pts))
    return Example.of_surface(s, 1, f"{kind} star {params}, symmetry {symmetry}, shift {shift}",
                         vertex=0, kind=kind, params=params)


@once
@st.composite
def vertex_stars(draw, kind: str | None = None):
    """The star of one interior vertex (a disk, chi = 1), built to be of a given kind (L2.4, R2.2).

    * convex: rays of a pyramid over a convex polygon around the apex's foot,
      each scaled by its own factor (the cone, hence convexity, is unchanged);
    * planar: neighbours in the plane of p, all around it (sectors < pi);
    * saddle: m >= 3 directions d and their opposites -d (scaled), spanning R^3
      (p is then in the interior of the hull of its neighbours);
    * folded: n = 2m neighbours on a unit circle, alternately at heights +h, -h
      (K <= 2 pi - 2 n atan(h), unbounded below as n grows, R2.2).

    Then one of the 48 symmetries of the cube and a dyadic translation, both
    exact on floats, so the kind survives rounding to floats.
    """
    kind = kind or draw(spread(("convex", "planar", "saddle", "folded")))
    symmetry = draw(st.integers(0, 47))
    shift = tuple(Fraction(draw(st.integers(-8, 8)), 4) for _ in range(3))
    scale = (Fraction(1, 2), Fraction(1), Fraction(3, 2), Fraction(2))
    if kind in ("convex", "planar"):
        n = draw(st.integers(3, 8))
        gaps = draw(st.lists(st.integers(1, 3), min_size=n, max_size=n))
        assume(2 * max(gaps) < sum(gaps))              # every sector below pi
        lam = draw(st.lists(spread(scale), min_size=n, max_size=n))
        steep = draw(spread((Fraction(1, 4), Fraction(1), Fraction(3))))
        angles, acc = [], Fraction(1, 3)
        for g in gaps:
            angles.append(2 * math.pi * float(acc) / sum(gaps))
            acc += g
        dirs = []
        for a, l in zip(angles, lam):
            c, s = circle_point(a)
            dirs.append((l * c, l * s, -l * steep if kind == "convex" else 0))
        params = (n, tuple(gaps), str(steep)) if kind == "convex" else (n, tuple(gaps))
    elif kind == "saddle":
        m = draw(st.integers(3, 4))          # d and -d for m = 2 directions span a plane only
        gaps = draw(st.lists(st.integers(1, 3), min_size=m, max_size=m))
        heights = draw(st.lists(st.integers(-3, 3), min_size=m, max_size=m))
        lam = draw(st.lists(spread(scale), min_size=2 * m, max_size=2 * m))
        total = sum(gaps) + 1
        half, acc = [], Fraction(1, 2)
        for g in gaps:
            half.append(math.pi * float(acc) / total)
            acc += g
        base = [(*circle_point(a), Fraction(z)) for a, z in zip(half, heights)]
        if det3(base[0], base[1], base[2]) == 0:
            # coplanar: lift the third; its foot is off the line of the first two, so det != 0
            base[2] = (*base[2][:2], base[2][2] + 1)
            heights[2] += 1
        dirs = [tuple(l * x for x in d) for d, l in zip(base, lam[:m])]
        dirs += [tuple(-l * x for x in d) for d, l in zip(base, lam[m:])]
        params = (m, tuple(gaps), tuple(heights))
    elif kind == "folded":
        m = draw(st.integers(2, 6))
        h = draw(st.integers(1, 8))
        n = 2 * m
        dirs = []
        for j in range(n):
            c, s = circle_point(2 * math.pi * (j + Fraction(1, 3)) / n)
            dirs.append((c, s, h if j % 2 == 0 else -h))
        params = (n, h)
    else:
        raise ValueError(f"unknown star kind {kind!r}")
    # built once per drawn star in this process: every implementation's task draws the same
    return memo.DRAWN.shared(("star", tuple(dirs), kind, params, symmetry, shift),
                             lambda: _star_surface(dirs, kind, params, symmetry, shift))


@st.composite
def pushable_surfaces(draw):
    """(case, v): a surface with a vertex v whose neighbours are coplanar (X2.3).

    A bipyramid over a rational polygon in z = 0 (closed, chi 2) or a planar grid
    with one interior vertex lifted (a disk); every coordinate a float.
    """
    if draw(st.booleans()):
        n = draw(st.integers(3, 7))
        top, bottom = Fraction(draw(st.integers(1, 8)), 4), Fraction(draw(st.integers(1, 8)), 4)
        ring = [(*circle_point(2 * math.pi * (k + Fraction(1, 3)) / n), 0) for k in range(n)]
        faces = [(0, 2 + k, 2 + (k + 1) % n) for k in range(n)]
        faces += [(1, 2 + (k + 1) % n, 2 + k) for k in range(n)]
        s = PolyhedralSurface(Triangulation.from_faces(faces),
                              [(0, 0, top), (0, 0, -bottom)] + ring)
        case = Example.of_surface(floated(s), 2, f"bipyramid n={n}, apexes {top}, -{bottom}")
        return case, draw(spread((0, 1)))
    m, n = draw(st.integers(2, 4)), draw(st.integers(2, 4))
    g = surfaces.grid(m, n)
    i, j = draw(st.integers(1, m - 1)), draw(st.integers(1, n - 1))
    v = i * (n + 1) + j
    h = Fraction(draw(st.integers(1, 12)), 4)
    pos = [(x, y, h if w == v else z) for w, (x, y, z) in enumerate(g.positions)]
    return Example.of_surface(floated(g.with_positions(pos)), 1, f"grid {m}x{n}, vertex {v} at {h}"), v


def convex_hull_surface(points) -> PolyhedralSurface | None:
    """The boundary of the convex hull of integer points, faces oriented outward, or None.

    scipy's ConvexHull proposes the faces; orientation and convexity are then
    checked exactly (every point weakly inside every face plane, the centroid
    strictly inside); None if the hull is flat or the check fails.
    """
    from scipy.spatial import ConvexHull
    from scipy.spatial import QhullError
    pts = [tuple(Fraction(x) for x in p) for p in points]
    try:
        hull = ConvexHull(np.array(points, dtype=np.float64))
    except (QhullError, ValueError):
        return None
    used = sorted({int(i) for s in hull.simplices for i in s})
    index = {v: k for k, v in enumerate(used)}
    centre = tuple(sum(pts[v][k] for v in used) / len(used) for k in range(3))
    faces = []
    for s in hull.simplices:
        a, b, c = (pts[int(i)] for i in s)
        n = cross(sub(b, a), sub(c, a))
        side = dot(n, sub(centre, a))
        if side == 0:
            return None
        face = [index[int(i)] for i in s]
        if side > 0:
            face[1], face[2] = face[2], face[1]
            n = tuple(-x for x in n)
        if any(dot(n, sub(p, a)) > 0 for p in pts):
            return None
        faces.append(face)
    try:
        return PolyhedralSurface(Triangulation.from_faces(faces), [pts[v] for v in used])
    except Exception:
        return None


_DIRECTIONS = st.tuples(st.integers(-3, 3), st.integers(-3, 3), st.integers(-3, 3)).filter(any)


@st.composite
def convex_polyhedra(draw):
    """A convex polyhedron: the hull of 4..12 integer points near the sphere of radius 8.

    Each point is a small integer direction (entries in -3..3) scaled to length
    about 8 and rounded to integers, so coordinates are exact floats.
    """
    n = draw(st.integers(4, 12))
    dirs = draw(st.lists(_DIRECTIONS, min_size=n, max_size=n, unique=True))
    pts = tuple(sorted({tuple(round(8 * x / math.sqrt(sum(y * y for y in d))) for x in d)
                        for d in dirs}))
    # the hull depends on the points alone: built once per point set in this process
    s = memo.DRAWN.shared(("convex hull", pts), lambda: convex_hull_surface(pts))
    assume(s is not None)
    return Example.of_surface(s, 2, f"convex hull of {list(pts)}")


# --- Remark 2.3: the converses of Lemma 2.4 fail ------------------------------------------

def _star(p, ring):
    n = len(ring)
    t = Triangulation.from_faces([(0, 1 + i, 1 + (i + 1) % n) for i in range(n)])
    return PolyhedralSurface(t, [p] + list(ring))


_HEXAGON = [(2, 0), (1, 2), (-1, 2), (-2, 0), (-1, -2)]
_CROWN = [(2, 0), (1, 1), (0, 2), (-1, 1), (-2, 0), (-1, -1), (0, -2), (1, -1)]

#: R2.3: a star for each converse of Lemma 2.4 that fails, vertex 0 the centre:
#: elliptic, not convex (a cone with one neighbour pulled in); flat, not planar (the
#: middle of a straight crease); hyperbolic, not a saddle (a zigzag crown below p).
CONVERSE_COUNTEREXAMPLES = {
    "elliptic, not convex": ((0, 0, 4), [(x, y, 0) for x, y in _HEXAGON]
                             + [(Fraction(1, 4), Fraction(-1, 2), 1)]),
    "flat, not planar": ((0, 0, 0), [(1, 0, 0), (0, 1, 0), (-1, 0, 0), (0, -1, 1)]),
    "hyperbolic, not a saddle": ((0, 0, 0), [(x, y, -Fraction(1, 10) if i % 2 == 0 else -3)
                                             for i, (x, y) in enumerate(_CROWN)]),
}


@st.composite
def moved_counterexamples(draw):
    """(name, star) of :data:`CONVERSE_COUNTEREXAMPLES` under a drawn rational rotation
    (Cayley), scale and translation: the vertex types and star predicates are invariant."""
    from ..reference.curvature import cayley_rotation, rigid_motion
    name = draw(st.sampled_from(sorted(CONVERSE_COUNTEREXAMPLES)))
    p, ring = CONVERSE_COUNTEREXAMPLES[name]
    k = Fraction(draw(st.integers(1, 9)), draw(st.integers(1, 9)))
    scaled = _star(tuple(k * x for x in p), [tuple(k * x for x in q) for q in ring])
    abc = draw(st.tuples(*[st.integers(-4, 4)] * 3))
    shift = draw(st.tuples(*[st.integers(-9, 9)] * 3))
    return name, rigid_motion(scaled, cayley_rotation(*abc), shift)
