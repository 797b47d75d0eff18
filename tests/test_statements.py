"""Numbered statements of the notes without a protocol method (properties.statements):
X1.1 / X1.2 (1), the identities of section 1.2, X3.1, L4.8, R4.1, R4.2, R2.8.

Each property runs on drawn examples, and each is shown able to fail: a planted
mistake (a wrong side, a missing factor) is caught on an explicit input."""

from fractions import Fraction
from math import isqrt

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ddg_oracle.properties import flipped, point_sets, stars, statements as S
from ddg_oracle.properties.metrics import bump, bumps
from ddg_oracle.properties.strategies import closed_surfaces
from ddg_oracle.reference import planar, surfaces
from ddg_oracle.reference.errors import InputError


@given(point_sets.sphere_point_sets())
def test_X1_1_convex_polyhedra_are_strongly_regular_spheres(points):
    S.convex_polyhedron_is_a_strongly_regular_sphere(points)


def test_X1_1_hull_refuses_coplanar_and_interior_points():
    with pytest.raises(InputError, match="coplanar"):
        surfaces.convex_hull([(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0), (0, 0, 1)])
    with pytest.raises(InputError, match="point 4 is inside"):
        surfaces.convex_hull([(0, 0, 0), (4, 0, 0), (0, 4, 0), (0, 0, 4), (1, 1, 1)])


def test_X1_1_a_bipyramid_hull():
    # a bipyramid over a scalene triangle: V = 5, E = 9, F = 6, every face outward
    pts = [(0, 0, 0), (4, 0, 1), (1, 5, 0), (1, 1, 4), (2, 2, -3)]
    hull = surfaces.convex_hull(pts)
    t = hull.triangulation
    assert (t.n_vertices, t.n_edges, t.n_faces) == (5, 9, 6)
    from ddg_oracle.reference.polyhedral import orientation3d
    for f in t.faces:                         # outward: the centroid is on the negative side
        centroid = tuple(sum(Fraction(p[k]) for p in pts) / 5 for k in range(3))
        assert orientation3d(*(pts[v] for v in f), centroid) == -1
    S.convex_polyhedron_is_a_strongly_regular_sphere(pts)


@given(closed_surfaces(max_genus=2))
def test_section_1_2_connected_sum_identities(case):
    S.connected_sum_identities(case.triangulation)


def test_section_1_2_identities_distinguish_what_they_should():
    from ddg_oracle.reference.combinatorics import connected_sum
    rp2, torus = surfaces.projective_plane(), surfaces.torus(3, 3)
    # K # RP^2 = T^2 # RP^2, yet T^2 and K differ, and T^2 # T^2 is not K # K
    assert torus.triangulation.classify() != surfaces.klein_bottle().classify()
    tt = connected_sum(torus, torus).classify()
    kk = connected_sum(surfaces.klein_bottle(), surfaces.klein_bottle()).classify()
    assert tt.euler_characteristic == kk.euler_characteristic == -2 and tt != kk
    assert connected_sum(rp2, rp2).classify().euler_characteristic == 0


@given(point_sets.lattice_functions())
def test_X3_1_combinatorial_laplacian_on_Z_and_Z2(case):
    S.combinatorial_laplacian_on_lattices(case)


def test_X3_1_the_printed_left_side_swaps_m_and_n():
    """ER: Example 3.1 prints (Lap f)(n, m) = 4 f(m, n) - ...; the left side is
    (Lap f)(m, n).  On f(m, n) = m the two differ at (1, 2) of a 4 x 4 window."""
    from ddg_oracle.reference.laplacian import graph_laplacian
    size = 4
    idx = lambda m, n: m * size + n                           # noqa: E731
    edges = [(idx(m, n), idx(m + a, n + b), 1) for m in range(size) for n in range(size)
             for a, b in ((1, 0), (0, 1)) if m + a < size and n + b < size]
    def f(m, n):
        return m ** 3
    lap = graph_laplacian(size * size, edges).matvec(
        [f(m, n) for m in range(size) for n in range(size)])
    m, n = 1, 2
    rhs = 4 * f(m, n) - f(m - 1, n) - f(m + 1, n) - f(m, n - 1) - f(m, n + 1)
    assert lap[idx(m, n)] == rhs == -6
    assert lap[idx(n, m)] == -12 != rhs                        # the printed left side (n, m)


@given(point_sets.circle_triples())
def test_L4_8_tangent_chord_angle(triple):
    S.tangent_chord_angle(triple)


def test_L4_8_the_other_tangent_ray_gives_the_supplement():
    b, s, c = (5, 0), (3, 4), (0, 5)            # S on the short arc: alpha = 135 degrees
    assert planar.inscribed_angle_cot(b, s, c) == -1
    assert planar.tangent_chord_cot(b, s, c) == -1
    assert planar.tangent_chord_cot(b, (-3, -4), c) == 1      # S on the long arc: 45 degrees
    with pytest.raises(InputError, match="collinear"):
        planar.inscribed_angle_cot((0, 0), (1, 1), (2, 2))


@given(point_sets.planar_points())
def test_R4_1_voronoi_delaunay_quads_are_kites(points):
    S.voronoi_delaunay_kites(points)


def test_R4_1_dual_edges_need_not_cross():
    # an obtuse triangle beside an acute one: the obtuse cell's centre is beyond the edge
    pts = [(0, 0), (6, 0), (3, 1), (3, -20)]
    faces = {f["edge"]: f for f in planar.quad_tessellation_faces(pts)}
    shared = faces[(0, 1)]
    assert not shared["acute"] and not shared["crossing"]
    assert shared["orthogonal"] and shared["bisected"] and shared["kite"]
    S.voronoi_delaunay_kites(pts)


@given(point_sets.planar_points())
def test_R4_2_delaunay_triangles_are_lifted_hull_facets(points):
    S.delaunay_is_the_lifted_hull(points)


def test_R4_2_lift_is_on_the_sphere_and_a_non_delaunay_triangle_is_not_a_facet():
    for p in [(0, 0), (3, -2), (Fraction(1, 3), 5)]:
        x, y, z = planar.stereographic_lift(p)
        assert x * x + y * y + z * z == 1
    pts = [(0, 0), (4, 0), (2, 1), (2, -3)]     # 0 1 2 is not Delaunay (3 inside its circle)
    assert planar.circle_position(pts[0], pts[1], pts[2], pts[3]) == 1
    assert not planar.is_lifted_hull_facet(pts, 0, 1, 2)
    assert planar.is_lifted_hull_facet(pts, 0, 2, 3)


def test_R2_8_a_flipped_tetrahedron_comes_from_no_polyhedral_surface():
    """R2.8: the regular tetrahedron with one edge flipped (X2.5) is a geodesic
    triangulation with two edges between vertices 2 and 3 of lengths 1 and sqrt(3);
    in a polyhedral surface both would be the segment p2 p3, so no polyhedral
    surface realises it."""
    from ddg_oracle.reference.intrinsic import regular_tetrahedron_flip
    m = regular_tetrahedron_flip()
    t = m.triangulation
    between = [e for e in range(t.n_edges) if set(t.edge_vertices(e)) == {2, 3}]
    assert sorted(m.squared_lengths[e] for e in between) == [1, 3]
    assert t.is_regular() and not t.is_strongly_regular()


@given(point_sets.planar_points())
def test_R4_4_delaunay_triangulations_triangulate_the_cells(points):
    S.delaunay_triangulations_are_the_cells_triangulated(points)


def test_R4_4_a_cocircular_hexagon_has_catalan_4_delaunay_triangulations():
    from ddg_oracle.properties.planar_points import CIRCLE5
    hexagon = [(5, 0), (4, 3), (0, 5), (-4, 3), (-5, 0), (0, -5)]
    assert set(hexagon) <= set(CIRCLE5)
    delaunay = [t for t in planar.all_triangulations(hexagon) if planar.is_delaunay_by_angles(t)]
    assert len(delaunay) == 14 == len(planar.all_triangulations(hexagon))
    S.delaunay_triangulations_are_the_cells_triangulated(hexagon)
    moved = hexagon[:-1] + [(0, -6)]               # off the circle: the cells split
    S.delaunay_triangulations_are_the_cells_triangulated(moved)
    assert len(planar.delaunay_tessellation(moved)) > 1


@given(st.lists(st.booleans(), min_size=6, max_size=6))
def test_X4_1_the_cube_tessellation_is_its_six_squares(choices):
    S.voronoi_tessellation_of_the_cube(choices)


def test_X4_1_a_bent_square_is_not_a_tie():
    from ddg_oracle.reference.laplacian import cotan_weights
    from ddg_oracle.reference.polyhedral import PolyhedralSurface
    from ddg_oracle.reference.combinatorics import Triangulation
    # a square folded along its diagonal: the diagonal's weight is no longer 0
    t = Triangulation.from_faces([(0, 1, 2), (0, 2, 3)])
    flat = PolyhedralSurface(t, [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)])
    bent = PolyhedralSurface(t, [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 1)])
    diagonal = next(e for e in range(t.n_edges) if set(t.edge_vertices(e)) == {0, 2})
    assert cotan_weights(flat)[diagonal] == 0 and cotan_weights(bent)[diagonal] != 0


@given(stars.moved_counterexamples())
def test_R2_3_none_of_the_implications_of_lemma_2_4_is_reversible(case):
    S.converses_of_lemma_2_4_fail(case)


def test_R2_3_the_forward_implications_hold_where_the_shapes_do():
    from ddg_oracle.reference.curvature import is_convex_star, is_planar_star, vertex_type
    cone = stars._star((0, 0, 4), [(x, y, 0) for x, y in stars._HEXAGON] + [(1, -2, 0)])
    assert is_convex_star(cone, 0) and vertex_type(cone, 0) == "elliptic"
    flat = stars._star((0, 0, 0), [(1, 0, 0), (0, 1, 0), (-1, 0, 0), (0, -1, 0)])
    assert is_planar_star(flat, 0) and vertex_type(flat, 0) == "flat"
    with pytest.raises(AssertionError, match="R2.3"):          # a star that is convex too
        S.converses_of_lemma_2_4_fail(("elliptic, not convex", cone))


# the intrinsic distance enumerates every unfolding: 70 ms an example, so fewer examples
@settings(max_examples=20)
@given(point_sets.cube_surface_points())
def test_D2_4_the_cube_distance_is_a_metric(points):
    S.cube_distance_is_a_metric(points)


@settings(max_examples=30)
@given(point_sets.opposite_cube_points())
def test_X2_2_straight_unfoldings_need_not_be_shortest(points):
    S.straight_unfoldings_need_not_be_shortest(points)


def test_X2_2_the_two_ways_around_an_edge_and_known_distances():
    from ddg_oracle.reference.geodesics import (cube_squared_distance, cube_unfoldings,
                                                root_sum_at_least)
    p, q = (Fraction(1, 4), Fraction(1, 2), 0), (Fraction(1, 4), Fraction(1, 2), 1)
    lengths = {seq: length for seq, length in cube_unfoldings(p, q)}
    near, far = ((2, 0), (0, 0), (2, 1)), ((2, 0), (0, 1), (2, 1))
    assert lengths[near] == Fraction(9, 4) == cube_squared_distance(p, q)   # over x = 0
    assert lengths[far] == Fraction(25, 4)                                   # over x = 1: longer
    assert cube_squared_distance((0, 0, 0), (1, 1, 1)) == 5                  # opposite corners
    centre = (Fraction(1, 2), Fraction(1, 2), 0)
    assert cube_squared_distance(centre, (Fraction(1, 2), Fraction(1, 2), 1)) == 4
    assert root_sum_at_least(4, 1, 1) and not root_sum_at_least(5, 1, 1)


def test_D2_4_points_off_the_surface_are_refused():
    from ddg_oracle.reference.geodesics import cube_squared_distance
    with pytest.raises(InputError, match="inside the unit cube"):
        cube_squared_distance((Fraction(1, 2),) * 3, (0, 0, 0))
    with pytest.raises(InputError, match="not a point of the unit cube"):
        cube_squared_distance((2, 0, 0), (0, 0, 0))


# --- each property catches a planted bug in the quantity it checks -------------------------

def _planted(monkeypatch, module, name, wrong):
    import importlib
    monkeypatch.setattr(importlib.import_module(module), name, wrong)


def test_planted_bugs_are_caught(monkeypatch):
    from ddg_oracle.reference import geodesics, laplacian
    cases = []
    # L4.8: the tangent ray on S's side (the supplement)
    right = planar.tangent_chord_cot
    cases.append(("ddg_oracle.reference.planar", "tangent_chord_cot",
                  lambda b, s, c: -right(b, s, c),
                  lambda: S.tangent_chord_angle(((5, 0), (3, 4), (0, 5)))))
    # R4.1: the opposite angle's sign swapped (acute read as obtuse)
    faces = planar.quad_tessellation_faces
    cases.append(("ddg_oracle.reference.planar", "quad_tessellation_faces",
                  lambda pts: [dict(f, acute=not f["acute"]) for f in faces(pts)],
                  lambda: S.voronoi_delaunay_kites([(0, 0), (6, 0), (3, 1), (3, -20)])))
    # R4.2: the lift from the south pole instead of the north one
    lift = planar.stereographic_lift
    cases.append(("ddg_oracle.reference.planar", "stereographic_lift",
                  lambda p: (lambda x, y, z: (x, y, -z))(*lift(p)),
                  lambda: S.delaunay_is_the_lifted_hull([(0, 0), (4, 0), (2, 1), (2, -3), (5, 5)])))
    # X3.1: the graph Laplacian with a factor 1/2
    graph = laplacian.graph_laplacian
    cases.append(("ddg_oracle.properties.statements", "graph_laplacian",
                  lambda n, edges: graph(n, [(i, j, Fraction(w) / 2) for i, j, w in edges]),
                  lambda: S.combinatorial_laplacian_on_lattices((2, 3, [i * i for i in range(9)]))))
    # D2.4: a squared distance halved
    dist = geodesics.cube_squared_distance
    cases.append(("ddg_oracle.reference.geodesics", "cube_squared_distance",
                  lambda p, q: dist(p, q) / 2,
                  lambda: S.cube_distance_is_a_metric([(0, 0, 0), (1, 1, 1), (1, 0, 0)])))
    # X4.1: cotan weights with a factor 2
    weights = laplacian.cotan_weights
    cases.append(("ddg_oracle.reference.laplacian", "cotan_weights",
                  lambda m: {e: 2 * w for e, w in weights(m).items()},
                  lambda: S.voronoi_tessellation_of_the_cube([False] * 6)))
    for module, name, wrong, run in cases:
        run()                                               # passes as it is
        with monkeypatch.context() as mp:
            _planted(mp, module, name, wrong)
            with pytest.raises(AssertionError):
                run()
                print(f"planted bug in {module}.{name} not caught")


@given(st.integers(0, 120))
@settings(deadline=None)
def test_X4_3_X4_4_the_cubes_triangulations_have_unbounded_edges(flips):
    S.cube_triangulations_grow_without_bound(flips)


def test_X4_3_each_flip_adds_two_to_the_sum_of_the_shifts():
    """The module's argument, measured: once every rung has shift d >= 1 (from flip 8 on;
    the squared length d^2 + 1 then gives d), each flip adds exactly 2 to the sum of the 8
    shifts, and every 8 flips each rung's shift has grown by 2 (one Dehn twist per 16)."""
    from ddg_oracle.reference.triangulations import belt_rungs, cube_belt_twist
    seq = list(cube_belt_twist(64))[8:]
    shifts = []
    for s in seq:
        sq = [int(s.squared_lengths[e]) for e in belt_rungs(s)]
        assert len(sq) == 8 and all(x >= 2 and isqrt(x - 1) ** 2 == x - 1 for x in sq)
        shifts.append(sorted(isqrt(x - 1) for x in sq))
    assert [sum(b) - sum(a) for a, b in zip(shifts, shifts[1:])] == [2] * (len(shifts) - 1)
    assert all([y - x for x, y in zip(a, b)] == [2] * 8
               for a, b in zip(shifts[8::8], shifts[16::8]))


def test_X4_4_a_sequence_that_does_not_twist_is_caught():
    """Planted: flipping one diagonal of a side square back and forth stays among two
    triangulations, so the longest edge stays sqrt 2 and the property fails."""
    from ddg_oracle.reference.intrinsic import IntrinsicTriangulation
    from ddg_oracle.reference.triangulations import belt_rungs

    def back_and_forth(flips):
        w = IntrinsicTriangulation(surfaces.cube().metric())
        e = next(e for e in belt_rungs(w.surface()) if w.is_flippable(e))
        yield w.surface()
        for _ in range(flips):
            w.flip(e)
            yield w.surface()

    with pytest.raises(AssertionError, match="X4.4: after 7 flips the longest edge is only sqrt.2."):
        S.cube_triangulations_grow_without_bound(12, back_and_forth)


@given(point_sets.sphere_point_sets(max_points=8), st.integers(0, 20))
@settings(deadline=None)
def test_T2_10_convex_polytopes_are_rigid_and_the_convex_one_is_unique(points, face):
    S.alexandrov_uniqueness_on_examples(points, face)


def test_T2_10_a_vertex_inside_a_face_flexes_and_a_pop_is_isometric():
    """The checks can fail: a vertex at a face's centroid (a polytope that is not strictly
    convex) has 7 infinitesimal motions, not 6; the octahedron capped and popped keeps its
    metric, loses its convexity, and is not congruent to the capped one."""
    from ddg_oracle.reference import rigidity
    from ddg_oracle.reference.polyhedral import PolyhedralSurface
    o = surfaces.octahedron()
    assert rigidity.infinitesimal_motions(o) == 6 and rigidity.is_convex_surface(o)
    t, p = o.triangulation, list(o.positions)
    i, j, k = t.faces[0]
    centroid = tuple(sum(p[v][c] for v in (i, j, k)) / 3 for c in range(3))
    flat = PolyhedralSurface.from_arrays(
        p + [centroid], [f for g, f in enumerate(t.faces) if g] + [(i, j, 6), (j, k, 6), (k, i, 6)])
    assert rigidity.is_convex_surface(flat) and rigidity.infinitesimal_motions(flat) == 7
    capped = rigidity.capped(o, 0)
    popped = rigidity.popped_vertex(capped, 6)
    assert popped.positions[6] == tuple(2 * c - a for c, a in zip(centroid, capped.positions[6]))
    assert popped.metric().squared_lengths == capped.metric().squared_lengths
    assert not rigidity.is_convex_surface(popped) and not rigidity.is_congruent(popped, capped)
    with pytest.raises(InputError, match="valence 4"):
        rigidity.popped_vertex(o, 0)


@given(flipped.closed_rational_metrics())
@settings(deadline=None)
def test_D4_3_C4_6_empty_immersed_disks_give_the_delaunay_tessellation(metric):
    S.empty_disks_give_the_tessellation(metric)


@pytest.mark.parametrize("name", ["octahedron", "icosahedron", "cube", "tetrahedron"])
def test_D4_3_on_surfaces_with_irrational_areas(name):
    """Surds in the development: the icosahedron's and octahedron's areas are irrational;
    flipped to Delaunay after a flip that breaks it."""
    from ddg_oracle.reference.delaunay import flip_to_delaunay
    from ddg_oracle.reference.intrinsic import flip, is_flippable
    m = getattr(surfaces, name)().metric()
    S.empty_disks_give_the_tessellation(m)
    e = next(e for e in range(m.triangulation.n_edges) if is_flippable(m, e))
    flipped = flip(m, e)
    S.empty_disks_give_the_tessellation(flipped)
    S.empty_disks_give_the_tessellation(flip_to_delaunay(flipped)[0])


def _one_vertex_square_torus():
    """The unit square with opposite sides glued: one vertex, edges 0 (bottom = top),
    1 (right = left), 2 (the diagonal), faces (A, B, C) and (A, C, D)."""
    from ddg_oracle.reference.combinatorics import Triangulation
    from ddg_oracle.reference.metric import PiecewiseFlatSurface
    t = Triangulation([[0, 0, 0], [0, 0, 0]], [(0, 4, False), (1, 5, False), (2, 3, False)])
    return PiecewiseFlatSurface(t, [1, 1, 2])


def test_D4_3_the_square_torus_with_one_vertex_is_one_cell():
    """One vertex, two triangles, three edges: one Delaunay cell (the square, 4 lifts of
    the vertex on its circle) and two tessellation edges: V - E + F = 1 - 2 + 1 = 0 =
    chi.  The disk wraps: it meets both faces at several places."""
    from ddg_oracle.reference.empty_disks import circumdisk, empty_disk_cells
    m = _one_vertex_square_torus()
    d = circumdisk(m, 0)
    assert d.empty and len(d.on_circle) == 4 and d.cell_faces == {0, 1}
    assert {v for _, v in d.on_circle} == {0} and d.copies > 2
    assert empty_disk_cells(m) == [frozenset({0, 1})]
    S.empty_disks_give_the_tessellation(m)


def test_D4_3_a_vertex_inside_is_found_and_named(monkeypatch):
    """The sheared flat torus (lattice (1, 0), (2, 1)) split along long diagonals is not
    Delaunay: circumdisks hold vertices, found by the development and named (vertex 1 at
    (2, 1) in face 0's plane, inside the circle through (0, 0), (1, 0), (3, 1)); the
    property fails if told the opposite (a planted wrong Delaunay test)."""
    from ddg_oracle.reference.delaunay import is_delaunay
    from ddg_oracle.reference.empty_disks import circumdisk, empty_disk_cells
    from ddg_oracle.properties.metrics import flat_torus
    m = flat_torus(3, 3, (1, 0), (2, 1))
    assert not is_delaunay(m)
    d = circumdisk(m, 0)
    assert d.inside == (1, (2, 1))
    with pytest.raises(InputError, match="face 0: vertex 1 lies inside its circumdisk"):
        empty_disk_cells(m)
    import ddg_oracle.reference.delaunay as D
    monkeypatch.setattr(D, "is_delaunay", lambda s: True)      # planted: says Delaunay
    with pytest.raises(AssertionError, match="D4.3 / T4.7: a Delaunay triangulation"):
        S.empty_disks_give_the_tessellation(m)


def test_D4_3_refuses_boundary_and_a_runaway_development():
    from ddg_oracle.reference.empty_disks import DevelopmentLimitExceeded, circumdisk
    with pytest.raises(InputError, match="without boundary: this one has 8 boundary edges"):
        circumdisk(surfaces.grid(2, 2).metric(), 0)
    with pytest.raises(DevelopmentLimitExceeded, match="more than 2 faces"):
        circumdisk(_one_vertex_square_torus(), 0, limit=2)


@given(bumps())
@settings(deadline=None)
def test_R4_11_one_step_of_algorithm_4_23(surface):
    S.minimal_surface_state(surface)


def test_R4_11_the_delaunay_triangulation_of_S_need_not_be_delaunay_for_the_next_surface():
    """R4.11, both ways: the 3 x 3 grid with its centre raised by 1: T~ (Delaunay for S)
    is not Delaunay for S~, whose bump comes down into the plane, so its walls' long
    edges now face obtuse angles summing past pi; the cube without its top: T~ stays
    Delaunay for S~ (the bottom comes up into the top plane)."""
    from ddg_oracle.reference.delaunay import is_delaunay, non_delaunay_edges
    from ddg_oracle.reference.minimal import next_surface
    from ddg_oracle.reference.polyhedral import PolyhedralSurface
    s = bump(3, (1, 2, 1, 2), 1)
    assert is_delaunay(s)
    assert S.minimal_surface_state(s) is False
    following = next_surface(s)
    assert non_delaunay_edges(following) == [2, 35]
    assert all(p[2] == 0 for p in following.positions)      # the bump is flattened
    c = surfaces.cube()
    box = PolyhedralSurface.from_arrays(c.positions, [f for f in c.triangulation.faces
                                                      if any(c.positions[v][2] == 0 for v in f)])
    assert S.minimal_surface_state(box) is True


def _skewed_flat_grid():
    """The 3 x 2 grid in the plane with its bottom row split by the long diagonal from
    (0, 0) to (2, 1): that edge faces two angles of 3 pi / 4, so the triangulation is not
    Delaunay (one intrinsic flip fixes it); interior vertices (1, 1), (2, 1)."""
    from ddg_oracle.reference.polyhedral import PolyhedralSurface
    pts = [(x, y, 0) for y in range(3) for x in range(4)]
    v = {(x, y): 4 * y + x for y in range(3) for x in range(4)}
    b = [v[(x, 0)] for x in range(4)]
    m = [v[(x, 1)] for x in range(4)]
    faces = [(b[0], b[1], m[2]), (b[0], m[2], m[1]), (b[0], m[1], m[0]), (b[1], b[2], m[2]),
             (b[2], b[3], m[3]), (b[2], m[3], m[2])]
    for x in range(3):
        a, c, d, e = v[(x, 1)], v[(x + 1, 1)], v[(x + 1, 2)], v[(x, 2)]
        faces += [(a, c, d), (a, d, e)]
    return PolyhedralSurface.from_arrays(pts, faces)


def test_R4_11_a_step_that_keeps_the_old_triangulation_is_caught(monkeypatch):
    """On the skewed flat grid T~ differs from T (the long diagonal is flipped) and S~ is
    S's positions on T~ (flat: the Laplace-Beltrami operator keeps linear functions).
    Planted: a next surface on the *old* combinatorics T, Algorithm 3.6's state, is
    caught."""
    import ddg_oracle.reference.minimal as M
    from ddg_oracle.reference.delaunay import is_delaunay
    from ddg_oracle.reference.polyhedral import PolyhedralSurface
    s = _skewed_flat_grid()
    assert not is_delaunay(s)
    assert S.minimal_surface_state(s) is True
    following = M.next_surface(s)
    assert following.triangulation != s.triangulation and following.positions == s.positions
    real = M.next_surface

    def stale(surface, fixed=None, **kw):
        return PolyhedralSurface(surface.triangulation, real(surface, fixed, **kw).positions)

    monkeypatch.setattr(M, "next_surface", stale)
    with pytest.raises(AssertionError, match="R4.11: the next surface is not f~ on T~"):
        S.minimal_surface_state(s)
