"""Example surfaces of chapter 1 (X1.4, T1.1 / C1.2, CS), all strongly regular (D1.4).

Surfaces that embed in R^3 are returned as :class:`PolyhedralSurface` with
exact integer or ``Fraction`` coordinates; points on circles use the rational
parametrisation ``cos = (1 - t^2)/(1 + t^2), sin = 2t/(1 + t^2)`` with a
rational ``t`` close to ``tan(angle/2)``, so they lie exactly on the circle and
are nearly evenly spaced.  The closed non-orientable surfaces (projective
plane, Klein bottle) do not embed in R^3 and are returned as bare
:class:`Triangulation` objects.  Orientable closed surfaces are oriented
consistently, with outward normals.

>>> from ddg_oracle.reference import surfaces
>>> [surfaces.tetrahedron().triangulation.euler_characteristic(),
...  surfaces.torus().triangulation.euler_characteristic(),
...  surfaces.genus_surface(2).triangulation.euler_characteristic()]
[2, 0, -2]
"""

from __future__ import annotations

import math
from fractions import Fraction

from .combinatorics import Triangulation, connected_sum
from .errors import InputError
from .polyhedral import PolyhedralSurface, orientation3d

__all__ = ["tetrahedron", "octahedron", "cube", "icosahedron", "torus", "genus_surface",
           "disk", "annulus", "grid", "mobius_strip", "projective_plane", "klein_bottle",
           "connected_sum", "convex_hull"]


def _count(name: str, value, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise InputError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return value


def _from_t(t: Fraction) -> tuple[Fraction, Fraction]:
    """The rational point ((1 - t^2)/(1 + t^2), 2t/(1 + t^2)) of the unit circle."""
    d = 1 + t * t
    return (1 - t * t) / d, 2 * t / d


def _half_tangent(angle: float, n: int) -> Fraction:
    # A denominator bound growing with n keeps the angular error (~1/den^2) far
    # below the spacing 2 pi / n, so points stay distinct and evenly spaced.
    return Fraction(math.tan(angle / 2)).limit_denominator(max(16, 4 * n))


def _circle_point(k: int, n: int) -> tuple[Fraction, Fraction]:
    """An exact rational point of the unit circle near angle 2 pi k / n."""
    k %= n
    if 2 * k == n:
        return Fraction(-1), Fraction(0)     # tan(pi/2) is infinite
    angle = 2 * math.pi * k / n
    if angle > math.pi:
        angle -= 2 * math.pi
    return _from_t(_half_tangent(angle, n))


def _surface(faces, positions) -> PolyhedralSurface:
    return PolyhedralSurface(Triangulation.from_faces(faces, n_vertices=len(positions)),
                             positions)


# --- spheres (X1.4: chi = 2) -------------------------------------------------------


def tetrahedron() -> PolyhedralSurface:
    """The tetrahedron with vertices 0, e1, e2, e3: V=4, E=6, F=4, chi=2 (X1.4, sphere).

    >>> tetrahedron().triangulation.classify().name
    'sphere'
    """
    return _surface([(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)],
                    [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)])


def convex_hull(points) -> PolyhedralSurface:
    """X1.1 / X1.2 (1): the boundary of the convex hull of points of R^3 in general
    position (no 4 coplanar), as a triangulated sphere with outward faces, exact.

    A triple ``i j k`` is a facet iff every other point is strictly on one side of
    its plane (:func:`~ddg_oracle.reference.polyhedral.orientation3d`); O(n^4), for small point sets.
    Every point is a vertex (general position with n >= 4 also needs every point on
    the hull; an interior point raises).  Raises :class:`InputError` naming 4
    coplanar points, or a point inside the hull.

    >>> convex_hull([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]).triangulation.n_faces
    4
    """
    from itertools import combinations
    pts = [tuple(Fraction(c) for c in p) for p in points]
    if len(pts) < 4 or any(len(p) != 3 for p in pts):
        raise InputError(f"convex_hull needs at least 4 points of R^3, got {len(pts)}")

    faces = []
    for i, j, k in combinations(range(len(pts)), 3):
        signs = set()
        for m in range(len(pts)):
            if m not in (i, j, k):
                s = orientation3d(pts[i], pts[j], pts[k], pts[m])
                if s == 0:
                    raise InputError(f"points {i}, {j}, {k}, {m} are coplanar "
                                     "(convex_hull needs general position)")
                signs.add(s)
        if len(signs) == 1:                      # outward: the others on the negative side
            faces.append((i, j, k) if signs == {-1} else (i, k, j))
    used = {v for f in faces for v in f}
    inner = sorted(set(range(len(pts))) - used)
    if inner:
        raise InputError(f"point {inner[0]} is inside the convex hull (not a vertex)")
    return _surface(faces, pts)


def octahedron() -> PolyhedralSurface:
    """The octahedron with vertices +-e_i: V=6, E=12, F=8, chi=2 (X1.4, sphere)."""
    return _surface([(0, 2, 4), (0, 5, 2), (0, 4, 3), (0, 3, 5),
                     (1, 4, 2), (1, 2, 5), (1, 3, 4), (1, 5, 3)],
                    [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)])


def cube() -> PolyhedralSurface:
    """The unit cube [0, 1]^3, each square split by a diagonal: V=8, E=18, F=12, chi=2 (X1.4)."""
    return _polycube({(0, 0, 0)})


def icosahedron() -> PolyhedralSurface:
    """A convex icosahedron with rational vertices: V=12, E=30, F=20, chi=2 (X1.4).

    The vertices are the cyclic permutations of (0, +-1, +-p) with the golden
    ratio replaced by p = 8/5; the convex hull keeps the icosahedron's
    combinatorics (it is not regular: edges have two lengths).
    """
    p = Fraction(8, 5)
    faces = [(0, 2, 8), (0, 9, 2), (0, 4, 6), (0, 8, 4), (0, 6, 9), (1, 10, 3), (1, 3, 11),
             (1, 6, 4), (1, 4, 10), (1, 11, 6), (2, 7, 5), (2, 5, 8), (2, 9, 7), (3, 5, 7),
             (3, 10, 5), (3, 7, 11), (4, 8, 10), (5, 10, 8), (6, 11, 9), (7, 9, 11)]
    pts = [(0, 1, p), (0, 1, -p), (0, -1, p), (0, -1, -p),
           (1, p, 0), (1, -p, 0), (-1, p, 0), (-1, -p, 0),
           (p, 0, 1), (-p, 0, 1), (p, 0, -1), (-p, 0, -1)]
    return _surface(faces, pts)


# --- tori and higher genus -----------------------------------------------------------


def torus(m: int = 8, n: int = 6) -> PolyhedralSurface:
    """An m x n grid on a torus of revolution (radii 3 and 1): V=mn, E=3mn, F=2mn, chi=0 (X1.4).

    Vertex ``i*n + j`` lies at major angle ~ 2 pi i/m and minor angle ~ 2 pi j/n,
    exactly on the torus ((3 + cos v) cos u, (3 + cos v) sin u, sin v) with
    rational cosines and sines.  Requires m, n >= 3 (strong regularity).
    """
    m, n = _count("m", m, 3), _count("n", n, 3)
    big = [_circle_point(i, m) for i in range(m)]
    small = [_circle_point(j, n) for j in range(n)]
    pts = [((3 + cv) * cu, (3 + cv) * su, sv) for cu, su in big for cv, sv in small]
    faces = []
    for i in range(m):
        for j in range(n):
            a, b = i * n + j, ((i + 1) % m) * n + j
            c, d = ((i + 1) % m) * n + (j + 1) % n, i * n + (j + 1) % n
            # a -> b runs along u, b -> c along v: X_u x X_v is the outward normal
            faces += [(a, b, c), (a, c, d)]
    return _surface(faces, pts)


def _polycube(cells) -> PolyhedralSurface:
    """Boundary of a union of unit cubes (cells given by their minimal corner), each
    exposed unit square split along the diagonal from its first corner, outward."""
    index = {}
    faces = []

    def vid(p):
        if p not in index:
            index[p] = len(index)
        return index[p]

    for cell in sorted(cells):
        for a in range(3):
            b, c = (a + 1) % 3, (a + 2) % 3      # the other two axes (not corners)
            for s in (1, -1):
                nb = list(cell)
                nb[a] += s
                if tuple(nb) in cells:
                    continue
                p0 = list(cell)
                p0[a] += 1 if s > 0 else 0
                p1, p3 = list(p0), list(p0)
                p1[b] += 1
                p3[c] += 1
                p2 = list(p1)
                p2[c] += 1
                q = [vid(tuple(p)) for p in (p0, p1, p2, p3)]   # normal e_b x e_c = e_a
                if s > 0:
                    faces += [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
                else:
                    faces += [(q[0], q[2], q[1]), (q[0], q[3], q[2])]
    pts = sorted(index, key=index.get)
    return _surface(faces, pts)


def genus_surface(g: int) -> PolyhedralSurface:
    """A closed orientable surface of genus g (X1.4, T1.1): chi = 2 - 2g.

    The boundary of a slab of 3 x (2g+1) x 1 unit cubes with the cells (1, 2i+1),
    i < g, removed (g square holes), every unit square split into two triangles;
    integer coordinates, outward orientation.  ``genus_surface(0)`` is the cube.
    Counts for g >= 1: V = 16g + 16, E = 3V - 6 + 6g, F = 2V - 4 + 4g.
    """
    g = _count("g", g, 0)
    if g == 0:
        return cube()
    cells = {(x, y, 0) for x in range(3) for y in range(2 * g + 1)}
    cells -= {(1, 2 * i + 1, 0) for i in range(g)}
    return _polycube(cells)


# --- surfaces with boundary ------------------------------------------------------------


def disk(n: int = 8) -> PolyhedralSurface:
    """A planar fan: centre 0 and n rational points of the unit circle (z = 0), n >= 3.

    V = n + 1, E = 2n, F = n, chi = 1 (X1.4, disk).  Counterclockwise (normal +z).
    """
    n = _count("n", n, 3)
    pts = [(0, 0, 0)] + [(c, s, 0) for c, s in (_circle_point(k, n) for k in range(n))]
    faces = [(0, 1 + k, 1 + (k + 1) % n) for k in range(n)]
    return _surface(faces, pts)


def annulus(n: int = 8) -> PolyhedralSurface:
    """Two concentric rings of n rational points, radii 1 (vertices 0..n-1) and 2 (n..2n-1).

    V = 2n, E = 4n, F = 2n, chi = 0, two boundary loops (X1.4, R1.6); z = 0,
    counterclockwise.  n >= 3.
    """
    n = _count("n", n, 3)
    ring = [_circle_point(k, n) for k in range(n)]
    pts = [(c, s, 0) for c, s in ring] + [(2 * c, 2 * s, 0) for c, s in ring]
    faces = []
    for i in range(n):
        j = (i + 1) % n
        faces += [(i, n + i, n + j), (i, n + j, j)]
    return _surface(faces, pts)


def grid(m: int = 4, n: int = 4) -> PolyhedralSurface:
    """The planar grid [0, m] x [0, n] of integer points, squares split by diagonals.

    Vertex ``i*(n+1) + j`` is (i, j, 0).  V = (m+1)(n+1), E = 3mn + m + n,
    F = 2mn, chi = 1 (X1.4, disk); counterclockwise.  m, n >= 1.
    """
    m, n = _count("m", m, 1), _count("n", n, 1)
    pts = [(i, j, 0) for i in range(m + 1) for j in range(n + 1)]
    faces = []
    for i in range(m):
        for j in range(n):
            a, b = i * (n + 1) + j, (i + 1) * (n + 1) + j
            faces += [(a, b, b + 1), (a, b + 1, a + 1)]
    return _surface(faces, pts)


def mobius_strip(n: int = 8) -> PolyhedralSurface:
    """A Möbius strip of n >= 3 segments embedded in R^3 with rational coordinates.

    V = 2n, E = 4n, F = 2n, chi = 0; non-orientable with one boundary loop of 2n
    edges (X1.4, T1.1).  Vertex i (resp. n + i) is the point s = +1 (resp. -1) of
    ((3 + s cos(u/2)) cos u, (3 + s cos(u/2)) sin u, s sin(u/2)) at u ~ 2 pi i/n;
    with rational t ~ tan(u/4) both the half-angle and (by the double-angle
    formulas) the full-angle circle points are exactly rational.
    """
    n = _count("n", n, 3)
    pts_top, pts_bottom = [], []
    for i in range(n):
        c2, s2 = _from_t(Fraction(math.tan(math.pi * i / (2 * n))).limit_denominator(max(8, 2 * n)))
        cu, su = c2 * c2 - s2 * s2, 2 * s2 * c2
        for s, out in ((1, pts_top), (-1, pts_bottom)):
            r = 3 + s * c2
            out.append((r * cu, r * su, s * s2))

    def top(i):          # going once round flips the strip: top_n = bottom_0
        return i if i < n else n

    def bottom(i):
        return n + i if i < n else 0

    faces = []
    for i in range(n):
        faces += [(top(i), bottom(i), bottom(i + 1)), (top(i), bottom(i + 1), top(i + 1))]
    return _surface(faces, pts_top + pts_bottom)


# --- closed non-orientable surfaces (no embedding in R^3) ----------------------------


def projective_plane() -> Triangulation:
    """The hemi-icosahedron RP^2_6: V=6, E=15, F=10, chi=1; non-orientable, h = 1 (T1.1).

    The 6-vertex triangulation of the real projective plane (the icosahedron with
    antipodal points identified); every pair of vertices is an edge.
    """
    return Triangulation.from_faces([(0, 1, 2), (0, 2, 3), (0, 3, 4), (0, 4, 5), (0, 5, 1),
                                     (1, 2, 4), (2, 3, 5), (3, 4, 1), (4, 5, 2), (5, 1, 3)])


def klein_bottle(m: int = 3, n: int = 3) -> Triangulation:
    """A twisted m x n grid: V=mn, E=3mn, F=2mn, chi=0; non-orientable, h = 2 (T1.1).

    Grid vertex (i, j) is ``i*n + j``, indices mod (m, n), except that crossing
    i = m flips the other direction: (m, j) ~ (0, -j).  Strongly regular for m, n >= 3.
    """
    m, n = _count("m", m, 3), _count("n", n, 3)

    def vid(i, j):
        if i == m:
            i, j = 0, -j
        return i * n + j % n

    faces = []
    for i in range(m):
        for j in range(n):
            a, b, c, d = vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)
            faces += [(a, b, c), (a, c, d)]
    return Triangulation.from_faces(faces)
