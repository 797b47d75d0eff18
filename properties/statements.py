"""Properties of numbered statements of the notes that no protocol method asks about
(X1.1, the identities of section 1.2, T2.10 (uniqueness), X3.1, L4.8, R4.1, R4.2,
D4.3 / C4.6, X4.3 / X4.4, R4.11).

Each checks the reference's exact values on drawn inputs against an independent
formulation of the statement and raises AssertionError naming the item; an
implementation of the same quantity can be checked through the same function.  Their
inputs are drawn by strategy modules: the point sets by :mod:`.point_sets`, R2.3's moved
stars by :mod:`.stars` (:func:`~.stars.moved_counterexamples`), the closed rational
metrics of D4.3 by :mod:`.flipped` (:func:`~.flipped.closed_rational_metrics`, with
X4.1's cube :func:`~.flipped.cube_faces`).
"""

from __future__ import annotations

from fractions import Fraction

from hypothesis import assume

from ..reference import planar
from ..reference.combinatorics import connected_sum, face_of
from ..reference.errors import InputError
from ..reference.laplacian import graph_laplacian
from ..reference import surfaces
from ..reference.polyhedral import orientation3d

from .flipped import cube_faces

# --- chapter 1 ---------------------------------------------------------------------------


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


# --- Theorem 2.10 (Alexandrov), the uniqueness half on examples ------------------------------


def alexandrov_uniqueness_on_examples(points, face: int) -> None:
    """T2.10 (uniqueness): the convex hull P of drawn points in general position is
    infinitesimally rigid (Dehn: its isometric first-order motions are the 6 rigid ones,
    exact rank of the rigidity matrix); so is P with a low pyramid on a drawn face.
    Reflecting the pyramid's apex through its base keeps the triangulation and every
    edge length (the same metric) but gives a surface that is neither congruent to the
    capped P nor convex: among the realisations of this metric, the convex one is the
    one the theorem names, and without convexity uniqueness fails."""
    from ..reference import rigidity
    try:
        hull = surfaces.convex_hull(points)
    except InputError:
        assume(False)                          # 4 coplanar points: not general position
    assert rigidity.is_convex_surface(hull), "T2.10: the hull is not convex"
    motions = rigidity.infinitesimal_motions(hull)
    assert motions == 6, f"T2.10: the convex hull flexes ({motions} motions, not 6)"
    capped = rigidity.capped(hull, face % hull.triangulation.n_faces)
    assert rigidity.is_infinitesimally_rigid(capped), "T2.10: the capped polytope flexes"
    apex = capped.n_vertices - 1
    popped = rigidity.popped_vertex(capped, apex)
    assert popped.metric().squared_lengths == capped.metric().squared_lengths, \
        "T2.10: the reflected apex changed an edge length"
    assert not rigidity.is_congruent(popped, capped), \
        "T2.10: the popped surface is congruent to the convex one"
    assert not rigidity.is_convex_surface(popped), \
        "T2.10: a second convex polytope with the same metric"


# --- chapter 3 ---------------------------------------------------------------------------


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


def tangent_chord_angle(triple) -> None:
    """L4.8: the angle between the tangent at B and the secant BC equals the inscribed
    angle BSC (exact cotangents; the angle on the side of BC away from S)."""
    b, s, c = triple
    got, want = planar.tangent_chord_cot(b, s, c), planar.inscribed_angle_cot(b, s, c)
    assert got == want, f"L4.8: tangent-chord cot {got} != inscribed cot {want} at {triple}"


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
                on_plane = orientation3d(lifts[i], lifts[j], lifts[k], lifts[d]) == 0
                assert on_circle == on_plane, f"R4.2: point {d} and triangle {(i, j, k)}"
        empty = all(p <= 0 for p in positions)
        assert planar.is_lifted_hull_facet(pts, i, j, k) == empty, \
            f"R4.2: triangle {(i, j, k)} Delaunay={empty} but its lift disagrees"


def _catalan(n: int) -> int:
    from math import comb
    return comb(2 * n, n) // (n + 1)


def delaunay_triangulations_are_the_cells_triangulated(points) -> None:
    """R4.4 (second bullet) / R4.7 in the plane: the Delaunay triangulations of a point
    set are exactly the triangulations of the cells of its unique Delaunay tessellation
    (their number is the product of Catalan(k - 2) over the cells, k the number of
    vertices of a cell: unique iff no cell is a circular polygon with more than 3
    vertices), and deleting the edges of weight 0 from any of them gives the
    tessellation back.  All triangulations are enumerated (the flip graph)."""
    pts = planar.as_point_set(points)
    cells = planar.delaunay_tessellation(pts)
    delaunay = [t for t in planar.all_triangulations(pts) if planar.is_delaunay_by_angles(t)]
    want = 1
    for c in cells:
        want *= _catalan(len(c) - 2)
    assert len(delaunay) == want, \
        f"R4.4: {len(delaunay)} Delaunay triangulations, the cells {sorted(map(sorted, cells))} " \
        f"have {want}"
    for t in delaunay:
        got = planar.cocircular_cells(pts, t.triangulation.faces)
        assert got == cells, "R4.4: a Delaunay triangulation minus its ties is not the tessellation"


def voronoi_tessellation_of_the_cube(choices) -> None:
    """X4.1: on the cube with V its 8 vertices, every triangulation by face diagonals is
    Delaunay, each diagonal with weight exactly 0 (its two triangles share a circle: the
    square's, centred at the face centre, a Voronoi vertex); the Delaunay tessellation
    is the 6 squares (its 12 edges the cube's, weight 1), chi = 8 - 12 + 6 = 2."""
    from ..reference.delaunay import delaunay_tessellation_edges, is_delaunay
    from ..reference.laplacian import cotan_weights
    m = cube_faces(choices)
    assert is_delaunay(m), "X4.1: a triangulation of the cube's squares is not Delaunay"
    w = cotan_weights(m)
    kept = delaunay_tessellation_edges(m)
    t = m.triangulation
    assert len(kept) == 12 and all(m.squared_lengths[e] == 1 for e in kept), \
        "X4.1: the tessellation's edges are not the cube's 12 edges"
    assert all(w[e] == 0 for e in range(t.n_edges) if e not in kept), \
        "X4.1: a face diagonal is not a tie"
    assert all(w[e] == 1 for e in kept), "X4.1: a cube edge has weight != 1"
    assert t.n_vertices - len(kept) + (t.n_faces - (t.n_edges - len(kept))) == 2


# --- Remark 2.3: the converses of Lemma 2.4 fail ------------------------------------------

def converses_of_lemma_2_4_fail(case) -> None:
    """R2.3: none of the implications of Lemma 2.4 (convex => elliptic, planar => flat,
    saddle => hyperbolic) is reversible: each star is of the curvature type but not of
    the shape (vertex_type exact; is_convex_star, is_planar_star, is_saddle_star)."""
    from ..reference.curvature import (is_convex_star, is_planar_star,
                                                is_saddle_star, vertex_type)
    name, s = case
    kind, shape = {"elliptic, not convex": ("elliptic", is_convex_star),
                   "flat, not planar": ("flat", is_planar_star),
                   "hyperbolic, not a saddle": ("hyperbolic", is_saddle_star)}[name]
    assert vertex_type(s, 0) == kind, f"R2.3: the '{name}' star is {vertex_type(s, 0)}"
    assert not shape(s, 0), f"R2.3: the '{name}' star is {shape.__name__} after all"


# --- Definition 2.4, Remark 2.6, Example 2.2: the intrinsic distance of the cube ----------

def cube_distance_is_a_metric(points) -> None:
    """D2.4 / R2.6: the intrinsic distance of the cube's surface is a metric (d(p, p) = 0,
    d > 0 between distinct points, symmetric, triangle inequality, exactly on squares),
    at least the chord |p - q| and equal to it on a common face."""
    from ..reference.geodesics import (cube_faces_of, cube_squared_distance,
                                                root_sum_at_least)
    d = {}
    for x, y in ((0, 1), (1, 2), (0, 2)):
        a, b = points[x], points[y]
        d[x, y] = d[y, x] = cube_squared_distance(a, b)
        chord = sum((s - t) ** 2 for s, t in zip(a, b))
        assert (d[x, y] == 0) == (a == b), f"D2.4: d({a}, {b}) = 0 between distinct points"
        assert d[x, y] >= chord, f"R2.6: d({a}, {b})^2 = {d[x, y]} < chord^2 {chord}"
        if set(cube_faces_of(a)) & set(cube_faces_of(b)):
            assert d[x, y] == chord, f"R2.6: on a common face d({a}, {b}) is not the chord"
    assert cube_squared_distance(points[0], points[0]) == 0, "D2.4: d(p, p) != 0"
    assert cube_squared_distance(points[1], points[0]) == d[0, 1], "D2.4: d is not symmetric"
    for x, y, z in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        assert root_sum_at_least(d[x, z], d[x, y], d[y, z]), \
            f"D2.4: triangle inequality fails for {points[x]}, {points[y]}, {points[z]}"


def straight_unfoldings_need_not_be_shortest(points) -> None:
    """X2.2: between points of opposite faces of the cube, the straight segments of the
    unfoldings are paths on the surface and the shortest is d(p, q); some is longer."""
    from ..reference.geodesics import cube_squared_distance, cube_unfoldings
    p, q = points
    lengths = sorted({length for _, length in cube_unfoldings(p, q)})
    assert lengths[0] == cube_squared_distance(p, q)
    assert lengths[0] >= 1, "X2.2: a path between opposite faces shorter than their distance 1"
    assert len(lengths) > 1, f"X2.2: every unfolding from {p} to {q} is shortest"


# --- Definition 4.3 / Claim 4.6: the tessellation by empty immersed disks -------------------------


def empty_disks_give_the_tessellation(metric) -> None:
    """D4.3 / C4.6 (and T4.7 in its empty-disk form): developing each face's circumdisk
    over the surface (:func:`~ddg_oracle.reference.empty_disks.circumdisk`), every disk is
    empty iff the triangulation is Delaunay (angle criterion); on a Delaunay
    triangulation each disk's cell ``conv phi^-1(V)`` is a k-gon triangulated by k - 2
    distinct faces, the cells are exactly the faces glued across the edges of weight 0
    (R4.7's tessellation), and they form a cell decomposition: V - E + F = chi."""
    from ..reference.delaunay import delaunay_tessellation_edges, is_delaunay
    from ..reference.empty_disks import circumdisk
    t = metric.triangulation
    disks = [circumdisk(metric, f) for f in range(t.n_faces)]
    delaunay = is_delaunay(metric)
    assert all(d.empty for d in disks) == delaunay, (
        "D4.3 / T4.7: " + ("a Delaunay triangulation has a vertex inside the circumdisk of "
                           f"face {next(d.face for d in disks if not d.empty)}" if delaunay
                           else "a non-Delaunay triangulation has every circumdisk empty"))
    if not delaunay:
        return
    kept = delaunay_tessellation_edges(metric)
    parent = list(range(t.n_faces))

    def root(f):
        while parent[f] != f:
            parent[f] = parent[parent[f]]
            f = parent[f]
        return f

    for e in range(t.n_edges):
        if e not in kept:
            h, g = t.edge_halfedges(e)
            parent[root(face_of(h))] = root(face_of(g))
    for d in disks:
        k = len(d.on_circle)
        assert len(d.cell) == len(d.cell_faces) == k - 2, (
            f"C4.6: the cell of face {d.face} has {k} vertices on its circle but "
            f"{len(d.cell)} faces ({len(d.cell_faces)} distinct)")
        assert d.cell_faces == {g for g in range(t.n_faces) if root(g) == root(d.face)}, (
            f"D4.3: the empty disk of face {d.face} gives the cell {sorted(d.cell_faces)}, "
            "not the faces glued across weight-0 edges")
    cells = {d.cell_faces for d in disks}
    assert t.n_vertices - len(kept) + len(cells) == t.euler_characteristic(), \
        "C4.6: the empty-disk cells do not form a cell decomposition (V - E + F != chi)"


# --- Examples 4.3 / 4.4: T_(M,V) of the cube is infinite ---------------------------------------


def cube_triangulations_grow_without_bound(flips: int, sequence=None) -> None:
    """X4.3 / X4.4: ``flips`` twisting flips in the cube's belt
    (:func:`~ddg_oracle.reference.triangulations.cube_belt_twist`) give geodesic
    triangulations of the *same* surface with vertex set V (12 faces, chi = 2, every
    angle sum 3 pi / 2 and area 6, exactly), and the longest edge after n flips has
    l^2 >= 1 + ((n - 2) / 4)^2, so l(T) is unbounded on T_(M,V) and T_(M,V) infinite.
    ``sequence(flips)`` replaces ``cube_belt_twist`` (to check another construction)."""
    from ..reference.curvature import angle_sums
    from ..reference.exact import pi
    from ..reference.triangulations import cube_belt_twist, longest_squared_length
    previous = None
    for n, s in enumerate((sequence or cube_belt_twist)(flips)):
        t = s.triangulation
        assert (t.n_vertices, t.n_faces, t.euler_characteristic()) == (8, 12, 2), \
            f"X4.3: flip {n} left the cube's vertex set or topology"
        assert all(a == 3 * pi / 2 for a in angle_sums(s)), \
            f"X4.3: flip {n} changed an angle sum: not the cube's metric"
        assert s.total_area() == 6, f"X4.3: flip {n} changed the area"
        longest = longest_squared_length(s)
        if n >= 2:
            assert longest >= 1 + Fraction(n - 2, 4) ** 2, \
                f"X4.4: after {n} flips the longest edge is only sqrt({longest})"
        assert t != previous, f"X4.3: flip {n} changed nothing"
        previous = t


# --- Remark 4.11: the state of Algorithm 4.23 is the pair (S, T) ---------------------------------


def minimal_surface_state(surface) -> bool:
    """R4.11: one step of Algorithm 4.23 replaces (S, T) by (S~, T~): T~ is a Delaunay
    triangulation of the metric of S (A4.13), the new positions f~ are harmonic for the
    cotan Laplacian of (S, T~) off the boundary, which stays where it was, and
    :func:`~ddg_oracle.reference.minimal.next_surface` is f~ on the combinatorics of T~.
    Returns whether T~ is still Delaunay for S~ (the remark: it need not be)."""
    from ..reference.delaunay import is_delaunay
    from ..reference.laplacian import cotan_laplacian
    from ..reference.minimal import delaunay_minimal_surface_step, next_surface
    t = surface.triangulation
    boundary = t.boundary_vertices()
    delaunay, new = delaunay_minimal_surface_step(surface)
    assert is_delaunay(delaunay), "R4.11: T~ is not Delaunay for the metric of S"
    L = cotan_laplacian(delaunay)
    for k in range(len(new[0])):
        lap = L.matvec([p[k] for p in new])
        assert all(lap[v] == 0 for v in range(t.n_vertices) if v not in boundary), \
            "R4.11: f~ is not harmonic for the Laplacian of (S, T~)"
    assert all(new[v] == surface.positions[v] for v in boundary), "R4.11: the boundary moved"
    following = next_surface(surface)
    assert following.triangulation == delaunay.triangulation and \
        following.positions == tuple(tuple(p) for p in new), \
        "R4.11: the next surface is not f~ on T~"
    return is_delaunay(following)
