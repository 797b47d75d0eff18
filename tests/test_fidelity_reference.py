"""Public reference functions that no test could fail before (found by replacing each with a
plausible wrong version: a constant, a negation, an off-by-one, and running the tests that
exercise it); each test here fails on such a version.  Exact throughout."""

from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ddg_oracle.reference import rigidity, surfaces
from ddg_oracle.reference.curvature import cayley_rotation
from ddg_oracle.reference.polyhedral import PolyhedralSurface

# --- rigidity.is_congruent (T2.10) --------------------------------------------------------------


def _moved(s, w, shift, mirror=False):
    """``s`` moved by the rational rotation of Cayley parameter ``w`` and the translation
    ``shift`` (and a reflection in z first, if ``mirror``)."""
    R = cayley_rotation(*w)
    pts = []
    for p in s.positions:
        q = (p[0], p[1], -p[2]) if mirror else p
        pts.append(tuple(sum(R[r][k] * q[k] for k in range(3)) + shift[r] for r in range(3)))
    return s.with_positions(pts)


@settings(max_examples=20, deadline=None, database=None)
@given(st.sampled_from(["tetrahedron", "octahedron", "cube", "icosahedron"]),
       st.tuples(*[st.fractions(-3, 3, max_denominator=4)] * 3),
       st.tuples(*[st.fractions(-5, 5, max_denominator=3)] * 3), st.booleans())
def test_T2_10_is_congruent_under_rigid_motions_and_reflections(name, w, shift, mirror):
    """A rigid motion (exact rational rotation and translation), with or without a
    reflection, keeps every labelled distance: congruent, both ways."""
    s = getattr(surfaces, name)()
    if name == "icosahedron":                     # irrational positions: rotate, no shift
        shift = (0, 0, 0)
    moved = _moved(s, w, shift, mirror)
    assert moved.positions != s.positions or w == (0, 0, 0) and shift == (0, 0, 0) and not mirror
    assert rigidity.is_congruent(s, moved) and rigidity.is_congruent(moved, s)
    assert rigidity.is_congruent(s, s)


def test_T2_10_is_congruent_under_relabellings():
    """The same polytope with its faces listed in another order, or its vertices relabelled
    by a symmetry (positions and faces permuted together), is congruent; relabelled by a
    permutation that is no symmetry, it is not (the map must send vertex i to vertex i)."""
    o = surfaces.octahedron()
    faces = [tuple(f[1:] + f[:1]) for f in reversed(o.triangulation.faces)]
    assert rigidity.is_congruent(o, PolyhedralSurface.from_arrays(o.positions, faces))
    p = o.positions
    # the symmetry x -> -x swaps the two vertices on the x axis
    ix = [i for i, q in enumerate(p) if q[1] == q[2] == 0]
    assert len(ix) == 2
    sigma = list(range(len(p)))
    sigma[ix[0]], sigma[ix[1]] = ix[1], ix[0]
    sym = PolyhedralSurface.from_arrays([p[sigma[i]] for i in range(len(p))],
                                        [tuple(sigma[v] for v in f) for f in o.triangulation.faces])
    assert rigidity.is_congruent(o, sym)
    # the reflection in the plane x = y relabels (x, y, z) -> (y, x, z): a symmetry too;
    # a transposition of one x-axis and one y-axis vertex alone is not
    tau = [p.index((q[1], q[0], q[2])) for q in p]
    assert rigidity.is_congruent(o, o.with_positions([p[tau[i]] for i in range(len(p))]))
    iy = [i for i, q in enumerate(p) if q[0] == q[2] == 0]
    swap = list(range(len(p)))
    swap[ix[0]], swap[iy[0]] = iy[0], ix[0]
    assert not rigidity.is_congruent(o, o.with_positions([p[swap[i]] for i in range(len(p))]))
    # a cube's vertices: swapping two adjacent corners only is no isometry of the labels
    c = surfaces.cube()
    q = list(c.positions)
    i, j = next((i, j) for i in range(8) for j in range(i)
                if sum((a - b) ** 2 for a, b in zip(q[i], q[j])) == 1)
    q[i], q[j] = q[j], q[i]
    assert not rigidity.is_congruent(c, c.with_positions(q))


def test_T2_10_is_congruent_fails_on_every_non_isometry():
    """Scaled, one vertex moved (however little), one vertex dropped, the popped vertex
    (same edge lengths, not congruent): never congruent."""
    t = surfaces.tetrahedron()
    assert not rigidity.is_congruent(t, t.with_positions([tuple(2 * x for x in p) for p in t.positions]))
    for v in range(4):
        for k in range(3):
            pts = [list(p) for p in t.positions]
            pts[v][k] += Fraction(1, 10 ** 6)
            assert not rigidity.is_congruent(t, t.with_positions([tuple(p) for p in pts]))
    o = surfaces.octahedron()
    capped = rigidity.capped(o, 0)
    assert not rigidity.is_congruent(o, capped) and not rigidity.is_congruent(capped, o)
    popped = rigidity.popped_vertex(capped, capped.n_vertices - 1)
    assert popped.metric().squared_lengths == capped.metric().squared_lengths
    assert not rigidity.is_congruent(capped, popped)


def test_T2_10_capped_puts_a_low_valence_3_pyramid_on_the_given_face():
    """capped(P, f) on every face of the tetrahedron, the octahedron and a bipyramid hull:
    one new vertex of valence 3 joined to exactly the corners of face f, above its centroid
    along the normal (on the outer side of f's plane), the result convex and infinitesimally
    rigid with F + 2 faces.  On the cube (two coplanar triangles per square) no pyramid
    keeps it convex: refused."""
    from ddg_oracle.reference.errors import InputError
    from ddg_oracle.reference.polyhedral import orientation3d
    with pytest.raises(InputError, match="no low pyramid"):
        rigidity.capped(surfaces.cube(), 0)
    hull = surfaces.convex_hull([(0, 0, 0), (4, 0, 1), (1, 5, 0), (1, 1, 4), (2, 2, -3)])
    for s in (surfaces.tetrahedron(), surfaces.octahedron(), hull):
        t, p = s.triangulation, s.positions
        for f in range(t.n_faces):
            c = rigidity.capped(s, f)
            n = s.n_vertices
            assert c.n_vertices == n + 1 and c.triangulation.n_faces == t.n_faces + 2
            assert c.positions[:n] == p
            corners = [p[v] for v in t.faces[f]]
            assert c.triangulation.valence(n) == 3
            assert set(c.triangulation.neighbours(n)) == set(t.faces[f])
            apex = c.positions[n]
            assert orientation3d(*corners, apex) == 1               # outside the face's plane
            centroid = [sum(q[k] for q in corners) / 3 for k in range(3)]
            d = [a - b for a, b in zip(apex, centroid)]
            u = [b - a for a, b in zip(corners[0], corners[1])]
            w = [b - a for a, b in zip(corners[0], corners[2])]
            assert sum(x * y for x, y in zip(d, u)) == sum(x * y for x, y in zip(d, w)) == 0
            assert rigidity.is_convex_surface(c) and rigidity.is_infinitesimally_rigid(c)


def test_X4_3_belt_rungs_are_the_edges_between_the_two_heights():
    """belt_rungs on the cube in two face orders (different edge ids) and after twists:
    exactly the 8 edges joining a vertex at z = 0 to one at z = 1 (4 vertical edges and 4
    side diagonals on the cube itself)."""
    from ddg_oracle.reference.triangulations import belt_rungs, cube_belt_twist
    c = surfaces.cube()
    z = [q[2] for q in c.positions]
    reordered = PolyhedralSurface.from_arrays(c.positions, list(reversed(c.triangulation.faces)))
    twisted = list(cube_belt_twist(5))[-1]
    for s in (c.metric(), reordered.metric(), twisted):
        t = s.triangulation
        rungs = belt_rungs(s)
        assert len(rungs) == 8 == len(set(rungs))
        assert all({z[v] for v in t.edge_vertices(e)} == {0, 1} for e in rungs)
        assert all(e in rungs for e in range(t.n_edges) if {z[v] for v in t.edge_vertices(e)} == {0, 1})
    sq = sorted(c.metric().squared_lengths[e] for e in belt_rungs(c.metric()))
    assert sq == [1, 1, 1, 1, 2, 2, 2, 2]
    assert belt_rungs(c.metric()) != belt_rungs(reordered.metric())


# --- functions whose tests called them on one input only ------------------------------------


def test_D2_4_cube_unfoldings_are_simple_face_sequences_from_p_to_q():
    """Every unfolding of cube_unfoldings(p, q) is a sequence of distinct faces, each
    adjacent to the next (faces on different axes), from a face containing p to one
    containing q, with squared length at least the chord's; the shortest is the distance;
    on a common face the straight segment is among them."""
    from ddg_oracle.reference.geodesics import (cube_faces_of, cube_squared_distance,
                                                cube_unfoldings)
    h, q3 = Fraction(1, 2), Fraction(1, 3)
    pairs = [((Fraction(1, 4), h, 0), (Fraction(1, 4), h, 1)), ((0, 0, 0), (1, 1, 1)),
             ((h, q3, 0), (h, 0, Fraction(2, 3))), ((q3, h, 0), (Fraction(3, 4), Fraction(1, 5), 0))]
    for p, q in pairs:
        found = cube_unfoldings(p, q)
        assert found
        chord = sum((Fraction(a) - Fraction(b)) ** 2 for a, b in zip(p, q))
        for seq, length in found:
            assert len(set(seq)) == len(seq)
            assert seq[0] in cube_faces_of(p) and seq[-1] in cube_faces_of(q)
            assert all(f[0] != g[0] for f, g in zip(seq, seq[1:]))
            assert length >= chord
        assert min(length for _, length in found) == cube_squared_distance(p, q)
        common = set(cube_faces_of(p)) & set(cube_faces_of(q))
        if common:
            assert any(len(seq) == 1 and length == chord for seq, length in found)


def test_C3_3_is_constant_on_components_both_ways():
    """Constant on each component (different constants on different components): True; a
    function that changes inside one component: False."""
    from ddg_oracle.reference.dirichlet import is_constant_on_components
    from ddg_oracle.reference.laplacian import graph_laplacian
    L = graph_laplacian(5, [(0, 1, 1), (1, 2, 2), (3, 4, 1)])
    assert is_constant_on_components(L, [7, 7, 7, -1, -1])
    assert is_constant_on_components(L, [0] * 5)
    assert not is_constant_on_components(L, [7, 7, 8, -1, -1])
    assert not is_constant_on_components(L, [7, 7, 7, -1, 0])


def test_R4_10_delaunay_neighbour_hull_is_the_tessellation_star():
    """On the cube every vertex's Delaunay neighbours are its 3 cube-edge neighbours (the
    face diagonals have weight 0), 1/3 each; on a flat square grid an interior vertex has its
    4 axis neighbours, 1/4 each, whichever diagonals the triangulation has."""
    from ddg_oracle.reference.minimal import delaunay_neighbour_hull
    cube = surfaces.cube()
    p = cube.positions
    for v in range(8):
        lam = delaunay_neighbour_hull(cube, v)
        assert set(lam) == {u for u in range(8) if sum((a - b) ** 2 for a, b in zip(p[u], p[v])) == 1}
        assert set(lam.values()) == {Fraction(1, 3)}
    g = surfaces.grid(2, 2)
    q = g.positions
    centre = next(v for v, x in enumerate(q) if x[:2] == (1, 1))
    lam = delaunay_neighbour_hull(g, centre)
    assert {q[u][:2] for u in lam} == {(0, 1), (2, 1), (1, 0), (1, 2)}
    assert set(lam.values()) == {Fraction(1, 4)}


def test_D4_3_empty_disk_cells_on_three_surfaces():
    """The cells from the empty circumdisks: the cube's 6 squares (2 faces each), the
    icosahedron's 20 triangles, and the 9 unit squares of the 3 x 3 square flat torus."""
    from ddg_oracle.reference.empty_disks import empty_disk_cells
    from ddg_oracle.properties.metrics import flat_torus
    cube = empty_disk_cells(surfaces.cube().metric())
    assert len(cube) == 6 and all(len(c) == 2 for c in cube)
    assert sorted(f for c in cube for f in c) == list(range(12))
    ico = empty_disk_cells(surfaces.icosahedron().metric())
    assert sorted(ico, key=min) == [frozenset({f}) for f in range(20)]
    torus = empty_disk_cells(flat_torus(3, 3))
    assert len(torus) == 9 and all(len(c) == 2 for c in torus)


@pytest.mark.parametrize("spike, shoulder, lift, negative", [
    (3, 2, 1, True), (5, 3, 2, True), (1, 1, 1, False), (2, 1, 4, False)])
def test_P3_10_figure_3_7_star_follows_its_parameters(spike, shoulder, lift, negative):
    """The star is the documented ring for the given parameters; the step leaves the hull
    (certified) exactly when the weight of the spike's edge is negative: s (spike - s) > 1
    with s = shoulder / 4 in the flat limit."""
    from ddg_oracle.reference.laplacian import cotan_weights
    from ddg_oracle.reference.minimal import figure_3_7_star
    s, new, certified = figure_3_7_star(spike, shoulder, lift)
    ring = [(spike, 0, Fraction(lift, 4)), (Fraction(shoulder, 4), 1, 0), (-1, 1, 0), (-1, -1, 0),
            (Fraction(shoulder, 4), -1, 0)]
    assert s.positions == tuple(tuple(map(Fraction, x)) for x in [(0, 0, 0)] + ring)
    t = s.triangulation
    spoke = next(e for e in range(t.n_edges) if set(t.edge_vertices(e)) == {0, 1})
    assert (cotan_weights(s)[spoke] < 0) == negative == certified
    assert (new[0][2] < 0) == negative
    assert [tuple(x) for x in new[1:]] == list(s.positions[1:])


def test_T2_10_is_infinitesimally_rigid_both_ways():
    """Strictly convex triangulated polytopes are infinitesimally rigid (Dehn); with a vertex
    added at a face's centroid (convex, not strictly) the polytope flexes: not rigid."""
    for s in (surfaces.tetrahedron(), surfaces.octahedron(), surfaces.icosahedron()):
        assert rigidity.is_infinitesimally_rigid(s)
    o = surfaces.octahedron()
    t, p = o.triangulation, list(o.positions)
    i, j, k = t.faces[0]
    centroid = tuple(sum(p[v][c] for v in (i, j, k)) / 3 for c in range(3))
    flat = PolyhedralSurface.from_arrays(
        p + [centroid], [f for g, f in enumerate(t.faces) if g] + [(i, j, 6), (j, k, 6), (k, i, 6)])
    assert rigidity.is_convex_surface(flat) and not rigidity.is_infinitesimally_rigid(flat)
