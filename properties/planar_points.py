"""Hypothesis strategies of planar point sets and quadrilaterals (chapter 4 properties and tests).

Everything is drawn as small integers and built from them, so failures shrink
to a few points: free points in a small box, cocircular subsets (integer points
on the circle of radius 5 and rational points on the unit circle, from
Pythagorean triples), collinear subsets (arithmetic progressions), and an
optional common denominator for rational (non-integer) coordinates.
"""

from __future__ import annotations

from fractions import Fraction

from hypothesis import strategies as st

from ..reference.combinatorics import halfedge
from ..reference.planar import orientation

from .precision import representable
from .draws import once, spread

#: the 12 integer points on the circle x^2 + y^2 = 25 (from 3^2 + 4^2 = 5^2)
CIRCLE5 = ((5, 0), (4, 3), (3, 4), (0, 5), (-3, 4), (-4, 3),
           (-5, 0), (-4, -3), (-3, -4), (0, -5), (3, -4), (4, -3))


def unit_circle_point(m: int, n: int) -> tuple[Fraction, Fraction]:
    """The rational point ((m^2 - n^2), 2 m n) / (m^2 + n^2) of the unit circle."""
    d = m * m + n * n
    return Fraction(m * m - n * n, d), Fraction(2 * m * n, d)


def spans_plane(points) -> bool:
    """At least 3 distinct points, not all on one line (exact)."""
    pts = list(points)
    if len(pts) < 3 or len(set(pts)) < len(pts):
        return False
    return any(orientation(pts[0], pts[1], c) for c in pts[2:])


small = st.integers(-6, 6)


def _completed(pts: list, extra) -> list:
    """``pts`` plus as few of the three non-collinear points ``extra`` as make it span
    the plane (so a drawn set is never rejected)."""
    for p in extra:
        if spans_plane(pts):
            break
        if p not in pts:
            pts.append(p)
    return pts


@once
@st.composite
def integer_point_sets(draw, max_points: int = 8, bound: int = 6):
    """Distinct integer points, not all collinear; often with a cocircular subset
    (a translate of part of :data:`CIRCLE5`) and a collinear one."""
    pts: list = []
    if draw(st.booleans()):
        cx, cy = draw(st.integers(-2, 2)), draw(st.integers(-2, 2))
        arc = draw(st.lists(spread(CIRCLE5), min_size=3, max_size=6, unique=True))
        pts += [(cx + x, cy + y) for x, y in arc]
    if draw(st.booleans()):
        a = (draw(st.integers(-bound, bound)), draw(st.integers(-bound, bound)))
        d = draw(spread(((1, 0), (0, 1), (1, 1), (1, -1), (2, 1), (1, 2))))
        k = draw(st.integers(3, 4))
        pts += [(a[0] + i * d[0], a[1] + i * d[1]) for i in range(k)]
    coord = st.integers(-bound, bound)
    pts += draw(st.lists(st.tuples(coord, coord), min_size=0, max_size=max_points))
    pts = list(dict.fromkeys(pts))[:max_points]
    return _completed(pts, [(bound + 1, bound + 2), (-bound - 1, bound + 3), (0, -bound - 1)])


@once
@st.composite
def rational_point_sets(draw, max_points: int = 8):
    """:func:`integer_point_sets` divided by a common denominator in 1..3, sometimes
    with rational points of the unit circle added (scaled by 5), sometimes with one point
    moved off its circle by a relative 2**-k, k in 20..40 (a near-tie)."""
    pts = [tuple(Fraction(x) for x in p) for p in draw(integer_point_sets(max_points))]
    den = draw(st.integers(1, 3))
    pts = [(x / den, y / den) for x, y in pts]
    if draw(st.booleans()):
        pairs = draw(st.lists(st.tuples(st.integers(1, 4), st.integers(1, 4)), min_size=1,
                              max_size=3))
        for m, n in pairs:
            x, y = unit_circle_point(m, n)
            pts.append((5 * x, 5 * y))
    pts = list(dict.fromkeys(pts))[:max_points]
    if draw(st.integers(0, 3)) == 3 and pts:
        # a near-tie: one point moved radially by a relative 2**-k (1e-6 .. 1e-12), off
        # the circle through its cocircular neighbours (every in-circle test beside a tie)
        i = draw(st.integers(0, len(pts) - 1))
        k = draw(st.integers(20, 40))
        scale = 1 + (1 if draw(st.booleans()) else -1) * Fraction(1, 2 ** k)
        pts[i] = (pts[i][0] * scale, pts[i][1] * scale)
        pts = list(dict.fromkeys(pts))
    return _completed(pts, [(Fraction(7), Fraction(8)), (Fraction(-7), Fraction(9)),
                            (Fraction(0), Fraction(-7))])


@st.composite
def parameter_quadrilaterals(draw):
    """Q(r1, r2, r3, r4, theta) with rational r_i and a rational direction
    (cos theta, sin theta) from a Pythagorean triple: ``X = 0``,
    ``P1 = r1 (1, 0)``, ``P2 = r2 (c, s)``, ``P3 = -r3 (1, 0)``, ``P4 = -r4 (c, s)``.
    Returns ``(points, (r1, r2, r3, r4), (c, s))``."""
    r = [Fraction(draw(st.integers(1, 12)), draw(st.integers(1, 3))) for _ in range(4)]
    m = draw(st.integers(1, 5))
    n = draw(st.integers(-5, 5).filter(lambda k: k != 0))
    c, s = unit_circle_point(m, n)
    if s < 0:                                  # n < 0: the opposite direction
        c, s = -c, -s
    r1, r2, r3, r4 = r
    pts = [(r1, Fraction(0)), (r2 * c, r2 * s), (-r3, Fraction(0)), (-r4 * c, -r4 * s)]
    return pts, tuple(r), (c, s)


def is_convex_ccw(pts) -> bool:
    return all(orientation(pts[i - 1], pts[i], pts[(i + 1) % 4]) > 0 for i in range(4))


def counterclockwise(pts) -> list:
    """The points sorted counterclockwise around the lowest one (exact comparisons)."""
    low = min(pts, key=lambda p: (p[1], p[0]))
    rest = [p for p in pts if p != low]
    for i in range(len(rest)):            # insertion sort by the orientation around low
        j = i
        while j > 0 and orientation(low, rest[j - 1], rest[j]) < 0:
            rest[j - 1], rest[j] = rest[j], rest[j - 1]
            j -= 1
    return [low] + rest


#: strictly convex counterclockwise quadrilaterals with small integer vertices (any
#: four points in convex position, put in counterclockwise order)
integer_quadrilaterals = st.lists(st.tuples(small, small), min_size=4, max_size=4,
                                  unique=True).map(counterclockwise).filter(is_convex_ccw)


@st.composite
def planar_triangulations(draw, max_points: int = 12):
    """``(points, faces, on_hull)``: a straight-line triangulation of planar points, far
    from Delaunay, to be flipped to Delaunay (A4.13 in the plane).

    The points are :func:`rational_point_sets` rounded to floats (of the checked
    implementation's input format, :mod:`.precision`) and taken exactly
    (what a float implementation sees is what the reference sees).  The start is
    the sweep triangulation (long fans: rarely Delaunay), then random flips of
    strictly convex quadrilaterals, then sometimes a boundary face removed (a
    non-convex polygon: ``on_hull`` is False, the flips keep its boundary).
    Faces are counterclockwise.  Shrinks towards three points.
    """
    from ..reference.errors import InputError
    from ..reference.planar import planar_triangulation, straight_line_flip

    pts = tuple((representable(x), representable(y))
                for x, y in draw(rational_point_sets(max_points)))
    if not spans_plane(pts) or len(set(pts)) < len(pts):
        pts = ((Fraction(0), Fraction(0)), (Fraction(1), Fraction(0)), (Fraction(0), Fraction(1)))
    t = planar_triangulation(pts).triangulation
    for e in draw(st.lists(st.integers(0, 10 ** 6), max_size=12)):
        t = straight_line_flip(pts, t, e % t.n_edges) or t     # convex quadrilaterals only
    on_hull = True
    if t.n_faces > 1 and draw(st.booleans()):
        f = draw(st.integers(0, t.n_faces - 1))
        if any(t.is_boundary_edge(t.edge_of(halfedge(f, c))) for c in range(3)):
            try:
                t = t.remove_face(f)
                on_hull = False
            except InputError:                  # would pinch a vertex or orphan one
                pass
    return pts, tuple(tuple(f) for f in t.faces), on_hull
