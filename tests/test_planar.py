"""Tests of ddg_oracle.reference.planar: Delaunay tessellations of planar point sets (section 4.1).

Rows: D4.1 (exact predicates, empty disk property), T4.1 (against
scipy.spatial.Delaunay and scipy.spatial.Voronoi, as tessellations), L4.3 /
P4.4 (angle criterion against in-circle), T4.2 (Moebius invariance, the
precise planar statement), T4.21 (exhaustive over all triangulations of small
point sets: L_T - L_Delaunay positive semidefinite, exactly), and the exact
semidefiniteness test of ddg_oracle.reference.sparse.
"""

import itertools
import random
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st
from scipy.spatial import Delaunay, Voronoi

from ddg_oracle.reference.delaunay import flip_to_delaunay, is_delaunay
from ddg_oracle.reference.errors import (BadInversion, BadQuadrilateral, BadShape, ClockwiseFace,
                              CollinearPoints, DegenerateFace, InputError, RepeatedPoint,
                              TooFewPoints)
from ddg_oracle.reference.exact import sqrt
from ddg_oracle.reference.laplacian import cotan_laplacian, dirichlet_energy, dirichlet_energy_pl
from ddg_oracle.reference.planar import (all_triangulations, angle_criterion, cell_boundary,
                              cells_avoiding, cocircular_cells, circle_position, circumcircle,
                              delaunay_tessellation, delaunay_triangulation,
                              empty_disk_violations, in_circle, inversion,
                              inversion_obstructions, is_delaunay_by_angles,
                              is_empty_disk_edge, laplacian_difference, orientation,
                              planar_flip_to_delaunay, planar_triangulation,
                              straight_line_flip, tessellation_edges, triangulation_key,
                              voronoi_edges, voronoi_vertices)
from ddg_oracle.reference.polyhedral import PolyhedralSurface
from ddg_oracle.reference.sparse import SparseMatrix, is_positive_semidefinite, negative_direction
from ddg_oracle.properties.planar_points import (integer_point_sets, planar_triangulations,
                                      rational_point_sets, spans_plane, unit_circle_point)

rationals = st.fractions(-4, 4, max_denominator=4)
rational_points = st.tuples(rationals, rationals)


# --- independent helpers (no ddg_oracle.reference.planar inside) ----------------------------------------


def cross(a, b, c):
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def hull_area(pts):
    """The exact area of the convex hull (Andrew's monotone chain, shoelace)."""
    p = sorted(set(pts))

    def half(seq):
        out = []
        for q in seq:
            while len(out) >= 2 and cross(out[-2], out[-1], q) <= 0:
                out.pop()
            out.append(q)
        return out

    ring = half(p)[:-1] + half(p[::-1])[:-1]
    return abs(sum(a[0] * b[1] - a[1] * b[0] for a, b in zip(ring, ring[1:] + ring[:1]))) / 2


def on_hull_boundary(pts):
    """Indices of the points on the boundary of the convex hull: those on a line
    through two points with all points on one closed side."""
    out = set()
    for i, j in itertools.permutations(range(len(pts)), 2):
        if all(cross(pts[i], pts[j], q) >= 0 for q in pts):
            out.update(k for k in range(len(pts)) if cross(pts[i], pts[j], pts[k]) == 0)
    return out


def scipy_tessellation(pts):
    """scipy.spatial.Delaunay's triangles merged across the edges whose four points are
    exactly cocircular: the tessellation, ignoring how cocircular cells are split."""
    d = Delaunay(np.array([[float(x), float(y)] for x, y in pts]))
    assert len(d.coplanar) == 0                       # every point is a vertex
    simplices = [tuple(int(v) for v in s) for s in d.simplices]
    assert all(cross(*(pts[v] for v in s)) != 0 for s in simplices)   # no degenerate triangle
    parent = list(range(len(simplices)))

    def root(x):
        while parent[x] != x:
            x = parent[x]
        return x

    by_edge = {}
    for k, s in enumerate(simplices):
        for a, b in itertools.combinations(s, 2):
            by_edge.setdefault(frozenset((a, b)), []).append(k)
    for ks in by_edge.values():
        if len(ks) == 2:
            s, t = simplices[ks[0]], simplices[ks[1]]
            (l_,) = set(t) - set(s)
            a, b, c = (pts[v] for v in s)
            if cocircular(a, b, c, pts[l_]):
                parent[root(ks[0])] = root(ks[1])
    cells = {}
    for k, s in enumerate(simplices):
        cells.setdefault(root(k), set()).update(s)
    return frozenset(frozenset(c) for c in cells.values())


def cocircular(a, b, c, d):
    """d on the circle through a, b, c: the exact circumcentre (solved here by Cramer's
    rule) is equidistant from all four."""
    bx, by, cx, cy = b[0] - a[0], b[1] - a[1], c[0] - a[0], c[1] - a[1]
    det = 2 * (bx * cy - by * cx)
    ux = (cy * (bx * bx + by * by) - by * (cx * cx + cy * cy)) / Fraction(det)
    uy = (bx * (cx * cx + cy * cy) - cx * (bx * bx + by * by)) / Fraction(det)
    o = (a[0] + ux, a[1] + uy)
    return (d[0] - o[0]) ** 2 + (d[1] - o[1]) ** 2 == ux * ux + uy * uy


def brute_force_triangulations(pts):
    """Every triangulation as its edge set: the non-crossing sets of 3n - 3 - h segments
    (segments with no point in their interior), h the number of boundary points."""
    n = len(pts)
    segs = []
    for i, j in itertools.combinations(range(n), 2):
        inside = any(cross(pts[i], pts[j], pts[k]) == 0 and k not in (i, j)
                     and min(pts[i], pts[j]) < pts[k] < max(pts[i], pts[j]) for k in range(n))
        if not inside:
            segs.append((i, j))

    def crossing(s, t):
        if set(s) & set(t):
            return False
        a, b = (pts[v] for v in s)
        c, d = (pts[v] for v in t)
        return (cross(a, b, c) * cross(a, b, d) < 0 and cross(c, d, a) * cross(c, d, b) < 0) or \
            (cross(a, b, c) == 0 and cross(a, b, d) == 0 and
             max(min(a, b), min(c, d)) < min(max(a, b), max(c, d)))     # collinear overlap

    size = 3 * n - 3 - len(on_hull_boundary(pts))
    ok = {(s, t): not crossing(s, t) for s, t in itertools.combinations(segs, 2)}
    out = set()

    def extend(chosen, start):
        if len(chosen) == size:
            out.add(frozenset(frozenset(s) for s in chosen))
            return
        for k in range(start, len(segs)):
            s = segs[k]
            if all(ok[(c, s)] for c in chosen):
                extend(chosen + [s], k + 1)

    extend([], 0)
    return out


def edge_set(surface):
    t = surface.triangulation
    return frozenset(frozenset(t.edge_vertices(e)) for e in range(t.n_edges))


# --- input validation ------------------------------------------------------------------------


def test_bad_point_sets_raise_typed_errors_naming_the_problem():
    with pytest.raises(TooFewPoints, match="2 point"):
        planar_triangulation([(0, 0), (1, 0)])
    with pytest.raises(RepeatedPoint, match="points 1 and 3 coincide"):
        planar_triangulation([(0, 0), (1, 0), (0, 1), (1, 0)])
    with pytest.raises(CollinearPoints, match="one line"):
        delaunay_triangulation([(0, 0), (1, 1), (3, 3), (-2, -2)])
    with pytest.raises(BadShape, match="point 1 has 3 coordinates"):
        planar_triangulation([(0, 0), (1, 0, 0), (0, 1)])
    with pytest.raises(InputError, match="NaN|nan|finite"):
        planar_triangulation([(0, 0), (1, float("nan")), (0, 1)])
    with pytest.raises(CollinearPoints):
        circle_position((0, 0), (1, 1), (2, 2), (0, 1))
    with pytest.raises(BadInversion, match="point 1"):
        inversion([(0, 0), (1, 2)], (1, 2))
    with pytest.raises(BadInversion, match="squared radius"):
        inversion([(0, 0)], (1, 2), 0)
    with pytest.raises(InputError, match="limit"):
        all_triangulations([(0, 0), (2, 0), (3, 2), (1, 3), (-1, 2)], limit=3)


# --- D4.1: the exact predicates --------------------------------------------------------------


@given(rational_points, rational_points, rational_points, rational_points)
def test_D4_1_predicates_against_an_independent_circumcentre(a, b, c, d):
    o = orientation(a, b, c)
    assert o == (cross(a, b, c) > 0) - (cross(a, b, c) < 0)
    assert orientation(b, a, c) == -o == orientation(a, c, b)
    assert orientation(b, c, a) == o
    assume(o != 0)
    centre, r2 = circumcircle(a, b, c)
    for p in (a, b, c):
        assert (p[0] - centre[0]) ** 2 + (p[1] - centre[1]) ** 2 == r2
    dist = (d[0] - centre[0]) ** 2 + (d[1] - centre[1]) ** 2
    inside = (dist < r2) - (dist > r2)                  # +1 inside, 0 on, -1 outside
    assert circle_position(a, b, c, d) == inside
    assert in_circle(a, b, c, d) == o * inside          # the sign convention of the docstring
    assert circle_position(b, a, c, d) == inside        # independent of the orientation


def test_D4_1_in_circle_on_pythagorean_points_is_exactly_zero():
    pts = [unit_circle_point(m, n) for m, n in [(1, 2), (2, 1), (3, 1), (1, -3), (2, -5)]]
    for a, b, c, d in itertools.permutations(pts, 4):
        assert in_circle(a, b, c, d) == 0
    a, b, c, _, _ = pts
    assert circle_position(a, b, c, (Fraction(0), Fraction(0))) == 1
    assert circle_position(a, b, c, (Fraction(1), Fraction(1))) == -1


# --- the sweep triangulation -----------------------------------------------------------------


@given(rational_point_sets(max_points=9))
def test_planar_triangulation_triangulates_the_convex_hull(pts):
    s = planar_triangulation(pts)
    t = s.triangulation
    assert s.positions == tuple(tuple(Fraction(x) for x in p) for p in pts)
    assert all(cross(*(s.positions[v] for v in f)) > 0 for f in t.faces)   # ccw, none flat
    assert t.euler_characteristic() == 1 and len(t.boundary_loops()) == 1  # a disk
    boundary = on_hull_boundary(s.positions)
    assert set(t.boundary_loops()[0]) == boundary
    assert t.n_faces == 2 * len(pts) - len(boundary) - 2
    area = sum(cross(*(s.positions[v] for v in f)) for f in t.faces) / 2
    assert area == hull_area(s.positions)


# --- T4.1: against scipy ---------------------------------------------------------------------


def test_T4_1_readme_style_examples():
    grid = [(x, y) for x in range(3) for y in range(3)]
    cells = delaunay_tessellation(grid)
    assert len(cells) == 4 and all(len(c) == 4 for c in cells)        # four unit squares
    circle = [(5, 0), (4, 3), (3, 4), (0, 5), (-3, 4), (-4, 3), (-5, 0), (0, -5)]
    assert delaunay_tessellation(circle) == {frozenset(range(8))}      # one cocircular cell


@given(integer_point_sets(max_points=9))
def test_T4_1_delaunay_tessellation_equals_scipy_as_tessellations(pts):
    assert delaunay_tessellation(pts) == scipy_tessellation(pts)


@given(integer_point_sets(max_points=9))
def test_T4_1_voronoi_duality_against_scipy(pts):
    cells = delaunay_tessellation(pts)
    edges = tessellation_edges(pts, cells)
    v = Voronoi(np.array(pts, dtype=float))
    # neighbouring Voronoi cells <-> Delaunay edges; one Voronoi vertex per Delaunay cell
    assert frozenset(frozenset(int(i) for i in r) for r in v.ridge_points) == edges
    assert len(v.vertices) == len(cells)
    centres = voronoi_vertices(pts, cells)
    for cell, q in centres.items():                       # centre of an empty circle
        ring = cell_boundary(pts, cell)
        r2 = {(pts[i][0] - q[0]) ** 2 + (pts[i][1] - q[1]) ** 2 for i in ring}
        assert len(r2) == 1
        assert all((x - q[0]) ** 2 + (y - q[1]) ** 2 > min(r2)
                   for k, (x, y) in enumerate(pts) if k not in cell)
    for e, (q, r) in voronoi_edges(pts, cells).items():   # dual edges are orthogonal
        i, j = sorted(e)
        d = (pts[i][0] - pts[j][0], pts[i][1] - pts[j][1])
        assert (q[0] - r[0]) * d[0] + (q[1] - r[1]) * d[1] == 0
        assert q != r                                     # cells of one circle were merged


@given(rational_point_sets(max_points=8))
def test_T4_1_flip_algorithm_on_planar_points_is_the_planar_flip(pts):
    start = planar_triangulation(pts)
    m, log = flip_to_delaunay(start.metric())
    d = delaunay_triangulation(pts)
    assert d.triangulation == m.triangulation
    # the intrinsic lengths and areas after the flips are those of the positions
    assert d.metric().squared_lengths == m.squared_lengths
    assert d.metric().areas == m.areas
    assert all(cross(*(d.positions[v] for v in f)) > 0 for f in d.faces)
    assert not empty_disk_violations(pts, d.faces)
    assert not empty_disk_violations(pts, delaunay_tessellation(pts))


def _boundary(faces):
    directed = {(f[c], f[(c + 1) % 3]) for f in faces for c in range(3)}
    return {e for e in directed if e[::-1] not in directed}


@given(planar_triangulations())
def test_A4_13_planar_flips_keep_the_polygon_and_reach_delaunay(example):
    pts, faces, on_hull = example
    d = planar_flip_to_delaunay(pts, faces)
    assert d.positions == tuple(pts) and len(d.faces) == len(faces)
    assert all(orientation(*(pts[v] for v in f)) > 0 for f in d.faces)
    assert _boundary(d.faces) == _boundary(faces)            # boundary edges never flip
    t = d.triangulation
    assert all(is_empty_disk_edge(d, e) for e in range(t.n_edges))          # D4.1
    assert is_delaunay_by_angles(d)                                          # P4.4
    if on_hull:                                                              # T4.1
        assert delaunay_tessellation(pts) == cocircular_cells(pts, d.faces)


@given(planar_triangulations())
def test_L4_11_non_delaunay_planar_edges_have_convex_quadrilaterals(example):
    # every non-Delaunay interior edge flips to a straight-line triangulation (its
    # quadrilateral is strictly convex) and its new edge is Delaunay; boundary edges never flip
    pts, faces, _ = example
    s = PolyhedralSurface.from_arrays(pts, faces)
    t = s.triangulation
    for e in range(t.n_edges):
        if t.is_boundary_edge(e):
            assert straight_line_flip(pts, t, e) is None
            continue
        u = straight_line_flip(pts, t, e)
        if not is_empty_disk_edge(s, e):
            assert u is not None
            assert is_empty_disk_edge(PolyhedralSurface(u, s.positions), e)
            assert all(orientation(*(pts[v] for v in f)) > 0 for f in u.faces)


def test_A4_13_planar_flips_on_a_non_convex_polygon_keep_its_reflex_corner():
    # an L-shaped hexagon (reflex corner at 3) fanned from 0: the diagonal 0-3 is not
    # Delaunay (its opposite angles are both obtuse), its quadrilateral is convex: one flip
    pts = [(0, 0), (4, 0), (4, 1), (1, 1), (1, 4), (0, 4)]
    faces = [(0, 1, 2), (0, 2, 3), (0, 3, 4), (0, 4, 5)]
    d = planar_flip_to_delaunay(pts, faces)
    assert _boundary(d.faces) == _boundary(faces)
    assert all(is_empty_disk_edge(d, e) for e in range(d.triangulation.n_edges))
    assert {frozenset(f) for f in d.faces} != {frozenset(f) for f in faces}


def test_planar_flips_reject_clockwise_and_degenerate_faces():
    pts = [(0, 0), (2, -1), (4, 0), (2, 1)]
    with pytest.raises(ClockwiseFace, match="face 1 .*clockwise"):
        planar_flip_to_delaunay(pts, [(0, 1, 2), (0, 3, 2)])      # the second face reversed
    with pytest.raises(DegenerateFace, match="face 0 .*collinear"):
        planar_flip_to_delaunay([(0, 0), (1, 0), (2, 0), (1, 1)], [(0, 1, 2), (0, 2, 3)])


# --- D4.1 / L4.3 / P4.4 ------------------------------------------------------------------------


@given(st.lists(st.tuples(st.integers(1, 6), st.integers(-6, 6).filter(bool)), min_size=4,
                max_size=4, unique_by=lambda mn: Fraction(mn[1], mn[0])),
       st.sampled_from([Fraction(1), Fraction(1, 2), Fraction(9, 10), Fraction(11, 10), 2]))
def test_L4_3_angle_criterion_on_a_circle_and_off_it(params, k):
    # four points of the unit circle in counterclockwise order (angle 2 atan(n/m)),
    # then P4 moved radially by k: inside iff k < 1
    p1, p2, p3, p4 = (unit_circle_point(m, n) for m, n in
                      sorted(params, key=lambda mn: Fraction(mn[1], mn[0])))
    p4 = (k * p4[0], k * p4[1])
    assume(orientation(p1, p3, p2) * orientation(p1, p3, p4) < 0)   # moving may cross P1 P3
    expected = (k < 1) - (k > 1)
    assert angle_criterion(p1, p2, p3, p4) == expected
    assert circle_position(p1, p2, p3, p4) == expected


@given(rational_points, rational_points, rational_points, rational_points)
def test_L4_3_angle_criterion_agrees_with_in_circle(p1, p2, p3, p4):
    assume(orientation(p1, p3, p2) * orientation(p1, p3, p4) < 0)
    assert angle_criterion(p1, p2, p3, p4) == circle_position(p1, p2, p3, p4)
    assert angle_criterion(p3, p4, p1, p2) == circle_position(p3, p4, p1, p2)


def test_L4_3_needs_opposite_sides():
    with pytest.raises(BadQuadrilateral, match="opposite sides"):
        angle_criterion((0, 0), (1, 1), (2, 0), (1, 2))
    with pytest.raises(BadQuadrilateral):
        angle_criterion((0, 0), (1, 1), (2, 0), (5, 0))


@given(integer_point_sets(max_points=6))
def test_P4_4_four_delaunay_tests_agree_on_every_triangulation(pts):
    assume(len(pts) >= 4)
    tess = delaunay_tessellation(pts)
    delaunay_keys = set()
    for s in all_triangulations(pts):
        t = s.triangulation
        local = all(is_empty_disk_edge(s, e) for e in range(t.n_edges))   # D4.1, per edge
        whole = not empty_disk_violations(pts, s.faces)                     # D4.1, empty disks
        angles = is_delaunay_by_angles(s)                                   # P4.4
        intrinsic = is_delaunay(s.metric())                                 # cot a + cot b >= 0
        assert local == whole == angles == intrinsic
        if whole:
            delaunay_keys.add(triangulation_key(s))
            # every Delaunay triangulation refines the one tessellation
            assert all(any(set(f) <= c for c in tess) for f in s.faces)
    assert triangulation_key(delaunay_triangulation(pts)) in delaunay_keys
    if all(len(c) == 3 for c in tess):
        assert len(delaunay_keys) == 1


# --- T4.2: Moebius invariance ------------------------------------------------------------------


def _images(points, centre, rho):
    image = inversion(points, centre, rho)
    assume(spans_plane(image))
    return image


@given(rational_point_sets(max_points=7), rational_points,
       st.sampled_from([1, 2, Fraction(1, 3), 25]))
def test_T4_2_inversion_is_rational_and_an_involution(pts, c, rho):
    assume(c not in [tuple(Fraction(x) for x in p) for p in pts])
    image = inversion(pts, c, rho)
    assert all(isinstance(x, Fraction) for p in image for x in p)
    assert inversion(image, c, rho) == tuple(tuple(Fraction(x) for x in p) for p in pts)


@given(rational_point_sets(max_points=7), rational_points,
       st.sampled_from([1, 2, Fraction(1, 3), 25]))
def test_T4_2_cells_avoiding_the_centre_correspond(pts, c, rho):
    assume(c not in [tuple(Fraction(x) for x in p) for p in pts])
    image = _images(pts, c, rho)
    d, d_image = delaunay_tessellation(pts), delaunay_tessellation(image)
    assert cells_avoiding(pts, d, c) == cells_avoiding(image, d_image, c)


@given(integer_point_sets(max_points=7),
       st.tuples(st.fractions(-12, 12, max_denominator=3), st.fractions(-12, 12, max_denominator=3)),
       st.sampled_from([1, 3, Fraction(1, 2)]))
def test_T4_2_precise_statement(pts, c, rho):
    """D(M(V)) = M(D(V)) iff inversion_obstructions is empty (the statement proved in
    the docstring), checked against the two tessellations computed independently."""
    assume(c not in [tuple(Fraction(x) for x in p) for p in pts])
    image = _images(pts, c, rho)
    same = delaunay_tessellation(pts) == delaunay_tessellation(image)
    assert same == (not inversion_obstructions(pts, c))


@given(st.integers(3, 4), st.lists(st.tuples(st.integers(-2, 5), st.integers(1, 4)), min_size=1,
                                   max_size=3, unique=True),
       st.tuples(st.fractions(-8, 8, max_denominator=2), st.fractions(-8, 8, max_denominator=2)))
def test_T4_2_precise_statement_with_points_on_a_hull_line(k, above, c):
    """As above, with k >= 3 points on the hull line y = 0 (the "supporting line" case)."""
    pts = [(i, 0) for i in range(k)] + above
    assume(c not in [tuple(Fraction(x) for x in p) for p in pts])
    image = _images(pts, c, 1)
    same = delaunay_tessellation(pts) == delaunay_tessellation(image)
    obstructions = inversion_obstructions(pts, c)
    assert same == (not obstructions)
    assert (("supporting line", frozenset(range(k))) in obstructions) == (c[1] > 0)


def _changes(pts, c):
    d, d_image = delaunay_tessellation(pts), delaunay_tessellation(inversion(pts, c))
    return sorted(sorted(x) for x in d), sorted(sorted(x) for x in d_image)


def test_T4_2_centre_outside_every_delaunay_disk_is_not_enough():
    """Evidence for the qualification of Theorem 4.2 in the plane.  Both centres lie
    outside every closed Delaunay circumdisk of V, yet the image gains a cell."""
    # (1) three points on a hull line: their images lie on a circle through c with an
    # empty disk, a new thin cell
    v = [(0, 0), (1, 0), (2, 0), (1, 5)]
    assert cells_avoiding(v, delaunay_tessellation(v), (-3, 1)) == delaunay_tessellation(v)
    assert _changes(v, (-3, 1)) == ([[0, 1, 3], [1, 2, 3]], [[0, 1, 2], [0, 1, 3], [1, 2, 3]])
    assert inversion_obstructions(v, (-3, 1)) == [("supporting line", frozenset({0, 1, 2}))]
    # (2) no three collinear: c inside the circle through 0, 1, 3, which holds all of V
    v = [(0, 0), (0, 1), (1, 0), (1, 2)]
    assert cells_avoiding(v, delaunay_tessellation(v), (2, 0)) == delaunay_tessellation(v)
    assert _changes(v, (2, 0)) == ([[0, 1, 2], [1, 2, 3]], [[0, 1, 2], [0, 1, 3], [1, 2, 3]])
    assert inversion_obstructions(v, (2, 0)) == [("farthest disk", frozenset({0, 1, 3}))]


def test_T4_2_cocircular_points_stay_one_cell_whatever_the_centre():
    v = [(5, 0), (3, 4), (-4, 3), (0, -5), (4, -3)]
    for c in [(0, 0), (1, 1), (9, 9), (-1, 2)]:                 # inside and outside the circle
        assert delaunay_tessellation(inversion(v, c)) == {frozenset(range(5))}
        assert inversion_obstructions(v, c) == []
    assert inversion_obstructions(v, (-5, 0)) == [("delaunay disk", frozenset(range(5)))]
    with pytest.raises(CollinearPoints):                        # centre on the circle
        delaunay_tessellation(inversion(v, (-5, 0)))


# --- T4.21: the Delaunay triangulation minimises the Dirichlet energy --------------------------


@pytest.mark.parametrize("n, catalan", [(5, 5), (6, 14), (7, 42)])
def test_T4_21_convex_polygons_have_catalan_many_triangulations(n, catalan):
    pts = [(x, x * x) for x in range(n)]         # convex position, no four cocircular
    ts = all_triangulations(pts)
    assert len(ts) == catalan == len({triangulation_key(s) for s in ts})


@given(integer_point_sets(max_points=6))
def test_T4_21_flip_graph_search_finds_every_triangulation(pts):
    assume(len(pts) >= 4)
    found = {edge_set(s) for s in all_triangulations(pts)}
    assert found == brute_force_triangulations(pts)


@given(integer_point_sets(max_points=7).filter(lambda p: len(p) >= 5),
       st.lists(st.integers(-5, 5), min_size=7, max_size=7))
def test_T4_21_delaunay_minimises_the_dirichlet_energy(pts, values):
    f = values[:len(pts)]
    d = delaunay_triangulation(pts)
    e_delaunay = dirichlet_energy(cotan_laplacian(d), f)
    energies = []
    for s in all_triangulations(pts):
        gap = laplacian_difference(s, d)
        assert is_positive_semidefinite(gap)                       # for every f at once
        e = dirichlet_energy_pl(s, f)                              # gradients, no cotangent
        assert e >= e_delaunay
        assert e - e_delaunay == gap.quadratic_form(f) / 2
        assert (gap == SparseMatrix((len(pts), len(pts)))) == is_delaunay(s.metric())
        energies.append(e)
    assert min(energies) == e_delaunay


def test_T4_21_exhaustive_on_fixed_sets_of_five_to_seven_points():
    rng = random.Random(421)
    sets = [[(0, 0), (4, 0), (5, 3), (2, 5), (-1, 3), (2, 2)],
            [(0, 0), (3, 0), (4, 2), (2, 4), (-1, 3), (-2, 1), (1, -2)],
            [(x, y) for x in range(3) for y in range(2)] + [(1, 2)],
            [(5, 0), (3, 4), (-3, 4), (-5, 0), (0, -5), (0, 0), (1, 1)]]
    for pts in sets:
        d = delaunay_triangulation(pts)
        ts = all_triangulations(pts)
        for s in ts:
            assert is_positive_semidefinite(laplacian_difference(s, d))
        for _ in range(5):
            f = [rng.randint(-9, 9) for _ in pts]
            assert min(dirichlet_energy_pl(s, f) for s in ts) == dirichlet_energy_pl(d, f)


# --- the exact semidefiniteness test -----------------------------------------------------------


def principal_minors_nonnegative(rows):
    n = len(rows)
    for k in range(1, n + 1):
        for idx in itertools.combinations(range(n), k):
            if det([[rows[i][j] for j in idx] for i in idx]) < 0:
                return False
    return True


def det(a):
    a = [[Fraction(x) for x in r] for r in a]
    n, sign, out = len(a), 1, Fraction(1)
    for c in range(n):
        p = next((r for r in range(c, n) if a[r][c]), None)
        if p is None:
            return Fraction(0)
        if p != c:
            a[c], a[p] = a[p], a[c]
            sign = -sign
        out *= a[c][c]
        for r in range(c + 1, n):
            f = a[r][c] / a[c][c]
            a[r] = [x - f * y for x, y in zip(a[r], a[c])]
    return sign * out


@given(st.integers(1, 5).flatmap(lambda n: st.tuples(
    st.just(n), st.lists(st.integers(-3, 3), min_size=n * n, max_size=n * n),
    st.booleans())))
def test_semidefiniteness_against_all_principal_minors(case):
    n, flat, gram = case
    b = [flat[i * n:(i + 1) * n] for i in range(n)]
    if gram:     # B^T B, semidefinite (often singular)
        rows = [[sum(b[k][i] * b[k][j] for k in range(n)) for j in range(n)] for i in range(n)]
    else:        # symmetric part, often indefinite
        rows = [[b[i][j] + b[j][i] for j in range(n)] for i in range(n)]
    a = SparseMatrix.from_entries((n, n), [(i, j, rows[i][j]) for i in range(n) for j in range(n)])
    x = negative_direction(a)
    assert (x is None) == principal_minors_nonnegative(rows) == is_positive_semidefinite(a)
    if gram:
        assert x is None
    if x is not None:
        assert a.quadratic_form(x) < 0


def test_semidefiniteness_with_square_roots():
    s = sqrt(2)
    ok = SparseMatrix.from_rows((2, 2), {0: {0: s, 1: 1}, 1: {0: 1, 1: s / 2}})     # det = 0
    bad = SparseMatrix.from_rows((2, 2), {0: {0: s, 1: 1}, 1: {0: 1, 1: s / 3}})
    assert is_positive_semidefinite(ok)
    assert bad.quadratic_form(negative_direction(bad)) < 0
    with pytest.raises(InputError):
        negative_direction(SparseMatrix.from_rows((2, 2), {0: {1: 1}}))


@given(rational_point_sets())
def test_R4_7_cocircular_merging_by_in_circle_equals_merging_by_zero_weights(pts):
    # two independent criteria for "same cell": in_circle == 0 of the four points, and cotan
    # weight exactly 0 of the edge (delaunay_tessellation)
    from ddg_oracle.reference.planar import cocircular_cells
    d = delaunay_triangulation(pts)
    assert cocircular_cells(pts, d.triangulation.faces) == delaunay_tessellation(pts)


def test_R4_7_cocircular_cells_merge_a_square_but_not_a_kite():
    from ddg_oracle.reference.planar import cocircular_cells
    square = [(0, 0), (1, 0), (1, 1), (0, 1)]
    for split in ([(0, 1, 2), (0, 2, 3)], [(0, 1, 3), (1, 2, 3)]):      # either diagonal
        assert cocircular_cells(square, split) == {frozenset(range(4))}
    kite = [(2, 0), (0, 1), (-1, 0), (0, -1)]
    assert cocircular_cells(kite, [(0, 1, 3), (1, 2, 3)]) == {frozenset({0, 1, 3}),
                                                              frozenset({1, 2, 3})}
