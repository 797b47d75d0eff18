"""Properties of numbered statements of the notes that no protocol method asks about
(X1.1, the identities of section 1.2, X3.1, L4.8, R4.1, R4.2).

Each checks the reference's exact values on drawn inputs against an independent
formulation of the statement and raises AssertionError naming the item; an
implementation of the same quantity can be checked through the same function.
"""

from __future__ import annotations

from fractions import Fraction

from hypothesis import assume
from hypothesis import strategies as st

from ddg_oracle.reference import planar
from ddg_oracle.reference.combinatorics import connected_sum
from ddg_oracle.reference.errors import InputError
from ddg_oracle.reference.laplacian import graph_laplacian
from ddg_oracle.reference import surfaces

from .planar_points import integer_point_sets, unit_circle_point

# --- chapter 1 ---------------------------------------------------------------------------


@st.composite
def sphere_point_sets(draw, max_points: int = 9):
    """Rational points on the unit sphere (lifted planar integer points divided by a
    drawn denominator), no 4 coplanar: the vertices of a convex polyhedron."""
    n = draw(st.integers(4, max_points))
    den = draw(st.integers(1, 4))
    flat = draw(st.lists(st.tuples(st.integers(-5, 5), st.integers(-5, 5)), min_size=n,
                         max_size=n, unique=True))
    return [planar.stereographic_lift((Fraction(x, den), Fraction(y, den))) for x, y in flat]


def convex_polyhedron_is_a_strongly_regular_sphere(points) -> None:
    """X1.1 / X1.2 (1): a convex polyhedron's boundary is a strongly regular cell
    decomposition of S^2: closed, orientable, chi = 2, no loop, no double edge."""
    try:
        hull = surfaces.convex_hull(points)
    except InputError:
        assume(False)                          # 4 coplanar points: not general position
    t = hull.triangulation
    c = t.classify()
    assert (c.orientable, c.genus, c.boundary_components, c.euler_characteristic) == \
        (True, 0, 0, 2), f"X1.1: the hull of {len(points)} points is {c}, not a sphere"
    assert t.is_strongly_regular(), "X1.1: the hull's decomposition is not strongly regular"
    assert 2 * (t.n_vertices - 2) == t.n_faces, "X1.1: a triangulated sphere has 2V - 4 faces"


def connected_sum_identities(m) -> None:
    """Section 1.2: M # S^2 = M; RP^2 # RP^2 = K; K # RP^2 = T^2 # RP^2 (homeomorphic:
    equal classification, T1.1 / C1.2), for a drawn closed surface ``m``."""
    sphere = surfaces.tetrahedron()
    rp2, klein = surfaces.projective_plane(), surfaces.klein_bottle()
    torus = surfaces.torus(3, 3)
    assert connected_sum(m, sphere).classify() == m.classify(), "M # S^2 != M"
    assert connected_sum(sphere, m).classify() == m.classify(), "S^2 # M != M"
    assert connected_sum(rp2, rp2).classify() == klein.classify(), "RP^2 # RP^2 != K"
    assert connected_sum(klein, rp2).classify() == connected_sum(torus, rp2).classify(), \
        "K # RP^2 != T^2 # RP^2"
    # and the monoid is commutative on classifications (section 1.2)
    assert connected_sum(m, rp2).classify() == connected_sum(rp2, m).classify()


# --- chapter 3 ---------------------------------------------------------------------------


@st.composite
def lattice_functions(draw):
    """(dimension 1 or 2, window size, integer function values on the window)."""
    dim = draw(st.sampled_from((1, 2)))
    size = draw(st.integers(3, 6))
    n = size ** dim
    return dim, size, draw(st.lists(st.integers(-50, 50), min_size=n, max_size=n))


def combinatorial_laplacian_on_lattices(case) -> None:
    """X3.1: with nu = 1, (Lap f)(n) = 2 f(n) - f(n + 1) - f(n - 1) on Z and
    (Lap f)(m, n) = 4 f(m, n) - f(m -+ 1, n) - f(m, n -+ 1) on Z^2, at every vertex of a
    window whose neighbours are all in it (the graph Laplacian of D3.1, exact)."""
    dim, size, values = case
    index = (lambda p: p[0]) if dim == 1 else (lambda p: p[0] * size + p[1])
    cells = [(i,) for i in range(size)] if dim == 1 else \
        [(i, j) for i in range(size) for j in range(size)]
    steps = [(1,)] if dim == 1 else [(1, 0), (0, 1)]
    shifted = [(p, tuple(a + b for a, b in zip(p, s))) for p in cells for s in steps]
    edges = [(index(p), index(q), 1) for p, q in shifted if all(x < size for x in q)]
    lap = graph_laplacian(len(cells), edges).matvec(values)
    for p in cells:
        if all(0 < x < size - 1 for x in p):
            f = lambda *q: values[index(q)]                         # noqa: E731
            if dim == 1:
                (n,) = p
                want = 2 * f(n) - f(n + 1) - f(n - 1)
            else:
                m, n = p
                want = 4 * f(m, n) - f(m - 1, n) - f(m + 1, n) - f(m, n - 1) - f(m, n + 1)
            assert lap[index(p)] == want, f"X3.1: (Lap f){p} = {lap[index(p)]}, want {want}"


# --- chapter 4 ---------------------------------------------------------------------------


@st.composite
def circle_triples(draw):
    """Three distinct rational points B, S, C on a circle with rational centre and
    radius (scaled rational points of the unit circle)."""
    params = draw(st.lists(st.tuples(st.integers(-9, 9), st.integers(1, 9)), min_size=3,
                           max_size=3, unique_by=lambda t: Fraction(t[0], t[1])))
    r = Fraction(draw(st.integers(1, 20)), draw(st.integers(1, 5)))
    cx, cy = draw(st.integers(-5, 5)), draw(st.integers(-5, 5))
    pts = [unit_circle_point(m, n) for m, n in params]
    assume(len(set(pts)) == 3)
    return tuple((cx + r * x, cy + r * y) for x, y in pts)


def tangent_chord_angle(triple) -> None:
    """L4.8: the angle between the tangent at B and the secant BC equals the inscribed
    angle BSC (exact cotangents; the angle on the side of BC away from S)."""
    b, s, c = triple
    got, want = planar.tangent_chord_cot(b, s, c), planar.inscribed_angle_cot(b, s, c)
    assert got == want, f"L4.8: tangent-chord cot {got} != inscribed cot {want} at {triple}"


def planar_points():
    return integer_point_sets(max_points=8)


def voronoi_delaunay_kites(points) -> None:
    """R4.1: every face of the Voronoi-Delaunay quad tessellation is a kite with
    orthogonal diagonals, the Delaunay diagonal bisected by the Voronoi edge's line;
    the two cross exactly when both angles opposite the Delaunay edge are at most
    pi/2 (so dual edges need not intersect); the Delaunay triangulation is strongly
    regular."""
    for face in planar.quad_tessellation_faces(points):
        for what in ("orthogonal", "bisected", "kite"):
            assert face[what], f"R4.1: the face at Delaunay edge {face['edge']} is not {what}"
        assert face["crossing"] == face["acute"], \
            f"R4.1: at edge {face['edge']} crossing={face['crossing']}, acute={face['acute']}"
    t = planar.delaunay_triangulation(points).triangulation
    assert t.is_strongly_regular(), "R4.1: the planar Delaunay triangulation is not strongly regular"


def delaunay_is_the_lifted_hull(points) -> None:
    """R4.2: a planar triangle is Delaunay (no point strictly inside its circumcircle)
    iff its stereographic lift spans a supporting plane of the hull of the lifted
    points and the north pole; a fourth point is on the circle iff its lift is on the
    plane."""
    from itertools import combinations
    pts = planar.as_point_set(points)
    lifts = [planar.stereographic_lift(p) for p in pts]
    for i, j, k in combinations(range(len(pts)), 3):
        if not planar.orientation(pts[i], pts[j], pts[k]):
            continue
        positions = [planar.circle_position(pts[i], pts[j], pts[k], pts[d])
                     for d in range(len(pts)) if d not in (i, j, k)]
        for d in range(len(pts)):
            if d not in (i, j, k):
                on_circle = planar.circle_position(pts[i], pts[j], pts[k], pts[d]) == 0
                on_plane = planar.plane_side(lifts[i], lifts[j], lifts[k], lifts[d]) == 0
                assert on_circle == on_plane, f"R4.2: point {d} and triangle {(i, j, k)}"
        empty = all(p <= 0 for p in positions)
        assert planar.is_lifted_hull_facet(pts, i, j, k) == empty, \
            f"R4.2: triangle {(i, j, k)} Delaunay={empty} but its lift disagrees"
