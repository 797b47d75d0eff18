"""Tests of ddg_oracle.reference.combinatorics: input validation, the halfedge structure,
D1.4 / D1.6 / R1.5 / CS / T1.1 / R1.6, and non-regular triangulations from flips."""


import pytest
from hypothesis import HealthCheck, find, given, settings
from hypothesis import strategies as st

from ddg_oracle.reference import surfaces
from ddg_oracle.reference.combinatorics import Classification, Triangulation, connected_sum
from ddg_oracle.reference.errors import (BadShape, EmptyMesh, IndexOutOfRange, InputError, NegativeIndex,
                              NonIntegerIndex, NonManifoldEdge, NonManifoldVertex,
                              NotConnected, NotFlippable, RepeatedVertexInFace,
                              UnreferencedVertex)

TET = [[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]]
SETTINGS = settings(max_examples=150, deadline=None, database=None,
                    suppress_health_check=[HealthCheck.too_slow])


def tet():
    return Triangulation.from_faces(TET)


def assert_valid(t: Triangulation):
    """Structural invariants, checked independently of Triangulation.validate()."""
    H = t.n_halfedges
    for h in range(H):
        tw = t.twin(h)
        if tw < 0:
            assert t.is_boundary_edge(t.edge_of(h))
            continue
        assert tw != h and t.twin(tw) == h
        assert t.reversed_gluing(h) == t.reversed_gluing(tw)
        assert t.edge_of(h) == t.edge_of(tw)
        if t.reversed_gluing(h):
            assert (t.tail(h), t.head(h)) == (t.tail(tw), t.head(tw))
        else:
            assert (t.tail(h), t.head(h)) == (t.head(tw), t.tail(tw))
    seen = []
    for e in range(t.n_edges):
        h, tw = t.edge_halfedges(e)
        assert t.edge_of(h) == e and t.twin(h) == tw
        seen += [h] + ([tw] if tw >= 0 else [])
    assert sorted(seen) == list(range(H))
    corners = []
    for v in range(t.n_vertices):
        around = t.corners_around(v)
        assert around, f"vertex {v} unused"
        assert all(t.faces[f][c] == v for f, c in around)
        corners += around
        assert t.valence(v) == len(t.neighbours(v))
        assert t.valence(v) == len(around) + (1 if t.is_boundary_vertex(v) else 0)
    assert sorted(corners) == [(f, c) for f in range(t.n_faces) for c in range(3)]
    assert sum(t.valence(v) for v in range(t.n_vertices)) == 2 * t.n_edges   # handshake
    t.validate()


# --- input validation -----------------------------------------------------------------


def test_empty_mesh():
    with pytest.raises(EmptyMesh):
        Triangulation.from_faces([])
    with pytest.raises(EmptyMesh):
        Triangulation.from_faces(())


@pytest.mark.parametrize("faces, where", [
    ([[0, 1, 2], [0, 1]], "face 1"),
    ([[0, 1, 2, 3]], "face 0"),
    ([[0, 1, 2], [1, 2, 3], 7], "face 2"),
    ([[0, 1, 2], "abc"], "face 1"),
    ([[0, 1, 2], {0, 1, 3}], "face 1"),
])
def test_bad_shape(faces, where):
    with pytest.raises(BadShape) as err:
        Triangulation.from_faces(faces)
    assert where in str(err.value)


def test_bad_shape_not_a_sequence():
    for faces in (None, 3, "012"):
        with pytest.raises(BadShape):
            Triangulation.from_faces(faces)


@pytest.mark.parametrize("bad", [1.0, 2.5, True, None, "2", float("nan"), float("inf"), 1j])
def test_non_integer_index(bad):
    with pytest.raises(NonIntegerIndex) as err:
        Triangulation.from_faces([[0, 1, 2], [0, 2, 3], [0, bad, 3]])
    assert "face 2" in str(err.value) and "corner 1" in str(err.value)
    assert repr(bad)[:3] in str(err.value)


def test_negative_index():
    with pytest.raises(NegativeIndex) as err:
        Triangulation.from_faces([[0, 1, 2], [2, 1, -4]])
    assert "face 1" in str(err.value) and "-4" in str(err.value)


def test_index_out_of_range():
    with pytest.raises(IndexOutOfRange) as err:
        Triangulation.from_faces([[0, 1, 2], [0, 2, 5]], n_vertices=4)
    assert "face 1" in str(err.value) and "5" in str(err.value)


def test_repeated_vertex():
    with pytest.raises(RepeatedVertexInFace) as err:
        Triangulation.from_faces([[0, 1, 2], [3, 1, 3]])
    assert "face 1" in str(err.value) and "vertex 3" in str(err.value)


def test_non_manifold_edge():
    with pytest.raises(NonManifoldEdge) as err:
        Triangulation.from_faces([[0, 1, 2], [1, 2, 3], [2, 1, 4]])
    msg = str(err.value)
    assert "(1, 2)" in msg and "faces 0, 1, 2" in msg


def test_non_manifold_vertex_two_cones():
    two_tets = TET + [[a + 3 if a else 0 for a in f] for f in TET]   # share vertex 0 only
    with pytest.raises(NonManifoldVertex) as err:
        Triangulation.from_faces(two_tets)
    assert "vertex 0" in str(err.value)
    assert "2 separate fans" in str(err.value)


def test_non_manifold_vertex_bowtie():
    with pytest.raises(NonManifoldVertex) as err:
        Triangulation.from_faces([[0, 1, 2], [0, 3, 4]])
    assert "vertex 0" in str(err.value)


def test_unreferenced_vertex():
    with pytest.raises(UnreferencedVertex) as err:
        Triangulation.from_faces([[0, 1, 2]], n_vertices=4)
    assert "vertex 3" in str(err.value)
    with pytest.raises(UnreferencedVertex) as err:
        Triangulation.from_faces([[0, 1, 3]])
    assert "vertex 2" in str(err.value)


def test_validation_order():
    # each list has two problems; the earlier kind in the documented order wins
    with pytest.raises(BadShape):
        Triangulation.from_faces([[0, 1, -1], [0, 1]])
    with pytest.raises(NonIntegerIndex):
        Triangulation.from_faces([[0, 1, -1], [0, 1, 0.5]])
    with pytest.raises(NegativeIndex):
        Triangulation.from_faces([[0, 0, 9], [0, 1, -1]], n_vertices=3)
    with pytest.raises(IndexOutOfRange):
        Triangulation.from_faces([[0, 0, 1], [0, 1, 9]], n_vertices=3)
    with pytest.raises(RepeatedVertexInFace):
        Triangulation.from_faces([[0, 1, 2], [1, 2, 3], [2, 1, 4], [5, 5, 6]])
    with pytest.raises(NonManifoldEdge):
        Triangulation.from_faces([[0, 1, 2], [1, 2, 3], [2, 1, 4], [0, 5, 6]], n_vertices=9)


def test_errors_are_value_errors():
    for exc in (EmptyMesh, BadShape, NonIntegerIndex, NegativeIndex, IndexOutOfRange,
                RepeatedVertexInFace, NonManifoldEdge, NonManifoldVertex, UnreferencedVertex):
        assert issubclass(exc, InputError) and issubclass(exc, ValueError)


def test_numpy_input():
    np = pytest.importorskip("numpy")
    t = Triangulation.from_faces(np.array(TET, dtype=np.int64))
    assert t.faces == tuple(map(tuple, TET)) and all(type(v) is int for f in t.faces for v in f)
    mixed = [[np.int64(0), np.int32(1), np.uint8(2)], [0, 2, 3], [0, 3, 1], [1, 3, 2]]
    assert Triangulation.from_faces(mixed).euler_characteristic() == 2
    assert Triangulation.from_faces(TET, n_vertices=np.int64(4)).n_vertices == 4
    with pytest.raises(NonIntegerIndex):
        Triangulation.from_faces(np.array(TET, dtype=float))
    with pytest.raises(NonIntegerIndex):
        Triangulation.from_faces([[np.float64(0), 1, 2]])
    with pytest.raises(NonIntegerIndex):
        Triangulation.from_faces([[np.bool_(True), 1, 2]])
    with pytest.raises(EmptyMesh):
        Triangulation.from_faces(np.zeros((0, 3), dtype=int))
    with pytest.raises(BadShape):
        Triangulation.from_faces(np.zeros((2, 4), dtype=int))


def test_gluing_constructor_validates():
    faces = [[0, 1, 2], [1, 0, 3]]
    ok = [(0, 3, False), (1, -1, False), (2, -1, False), (4, -1, False), (5, -1, False)]
    assert Triangulation(faces, ok).n_edges == 5
    with pytest.raises(InputError, match="endpoints"):
        Triangulation(faces, [(0, 3, True)] + ok[1:])
    with pytest.raises(InputError, match="halfedge 5"):
        Triangulation(faces, ok[:-1])
    with pytest.raises(InputError, match="already glued"):
        Triangulation(faces, ok + [(5, -1, False)])


# --- the halfedge structure -----------------------------------------------------------


def test_halfedge_navigation():
    t = Triangulation.from_faces([[0, 1, 2], [1, 0, 3]])
    assert [(t.tail(h), t.head(h)) for h in range(3)] == [(0, 1), (1, 2), (2, 0)]
    assert [t.next(h) for h in range(6)] == [1, 2, 0, 4, 5, 3]
    assert [t.prev(h) for h in range(6)] == [2, 0, 1, 5, 3, 4]
    assert t.face_of(4) == 1
    assert t.twin(0) == 3 and t.twin(1) == -1 and not t.reversed_gluing(0)
    assert t.n_edges == 5 and t.edge_of(0) == t.edge_of(3) == 0
    assert t.edge_halfedges(0) == (0, 3) and t.edge_vertices(0) == (0, 1)
    assert t.is_boundary_edge(1) and not t.is_boundary_edge(0)


def test_reversed_gluing_flag():
    t = Triangulation.from_faces([[0, 1, 2], [0, 1, 3]])       # both run 0 -> 1
    assert t.twin(0) == 3 and t.reversed_gluing(0) and t.reversed_gluing(3)
    assert t.is_orientable()                                    # just inconsistently oriented
    assert all(not tet().reversed_gluing(h) for h in range(12))


def test_fans_disk_and_boundary():
    d = surfaces.disk(5).triangulation
    around = d.corners_around(0)
    assert [f for f, _ in around] == [0, 1, 2, 3, 4]            # counterclockwise
    assert d.valence(0) == 5 and not d.is_boundary_vertex(0)
    assert d.neighbours(0) == [2, 3, 4, 5, 1]       # ends between consecutive corners
    assert d.is_boundary_vertex(1) and d.valence(1) == 3
    assert sorted(d.neighbours(1)) == [0, 2, 5]
    # an open fan runs from one boundary edge to the other
    nb = d.neighbours(3)
    assert {nb[0], nb[-1]} == {2, 4} and nb[1] == 0
    g = surfaces.grid(1, 1).triangulation
    assert g.corners_around(1) == [(1, 2)] and g.valence(1) == 2


def test_loop_and_valence_one_from_gluings():
    # Two triangles (v, a, a) and (w, a, a), each folded along its edges at v (w),
    # glued along their loops a -> a: a sphere with a vertex of valence 1 at v and w.
    faces = [[0, 2, 2], [1, 2, 2]]
    t = Triangulation(faces, [(0, 2, False), (3, 5, False), (1, 4, False)])
    assert_valid(t)
    assert t.euler_characteristic() == 2 and str(t.classify()) == "sphere"
    assert t.valence(0) == 1 and t.neighbours(0) == [2]
    assert t.valence(2) == 4 and sorted(t.neighbours(2)) == [0, 1, 2, 2]   # loop twice
    assert len(t.corners_around(2)) == 4
    assert not t.is_regular() and not t.is_strongly_regular()
    with pytest.raises(NotFlippable, match="face 0 on both sides"):
        t.flip(0)
    # both sides of edge 0 lie in face 0: that face becomes 3, the second split
    # joining the two copies of m by a loop (2 halves + 1 diagonal + loop twice)
    s, m = t.split_edge(0)
    assert (s.n_vertices, s.n_edges, s.n_faces) == (4, 6, 4) and s.valence(m) == 5
    assert sorted(s.neighbours(m)) == [0, 2, 2, m, m]
    assert_valid(s)
    assert str(s.classify()) == "sphere"


def test_non_manifold_gluing_rejected():
    # two cones glued to a bowtie at vertex 0 through gluings
    faces = [[0, 1, 2], [0, 3, 4]]
    gl = [(h, -1, False) for h in range(6)]
    with pytest.raises(NonManifoldVertex, match="vertex 0"):
        Triangulation(faces, gl)


# --- global invariants ---------------------------------------------------------------


def test_euler_characteristic_d16():
    t = tet()
    assert t.n_vertices - t.n_edges + t.n_faces == t.euler_characteristic() == 2
    assert Triangulation.from_faces([[0, 1, 2]]).euler_characteristic() == 1


def test_components_and_not_connected():
    t = Triangulation.from_faces([[0, 1, 2], [3, 4, 5], [1, 0, 6]])
    assert t.components() == [[0, 2], [1]] and not t.is_connected()
    with pytest.raises(NotConnected, match="2 components"):
        t.classify()
    assert tet().is_connected()


def test_boundary_loops():
    a = surfaces.annulus(5).triangulation
    loops = sorted(a.boundary_loops())
    assert [sorted(l) for l in loops] == [[0, 1, 2, 3, 4], [5, 6, 7, 8, 9]]
    for loop in loops:     # consecutive vertices are joined by boundary edges
        pairs = {frozenset(a.edge_vertices(e)) for e in range(a.n_edges) if a.is_boundary_edge(e)}
        assert all(frozenset((loop[i], loop[i - 1])) in pairs for i in range(len(loop)))
    m = surfaces.mobius_strip(5).triangulation
    (loop,) = m.boundary_loops()
    assert sorted(loop) == list(range(10))
    assert tet().boundary_loops() == []


def test_orientability():
    assert tet().is_orientable()
    assert tet().with_reversed_faces([1]).is_orientable()
    assert not surfaces.mobius_strip(4).triangulation.is_orientable()
    assert not surfaces.projective_plane().is_orientable()


def test_regularity_d14():
    pillow = Triangulation.from_faces([[0, 1, 2], [1, 0, 2]])
    assert pillow.is_regular() and not pillow.is_strongly_regular()
    assert pillow.euler_characteristic() == 2
    assert tet().is_strongly_regular()
    flipped = tet().flip(0)               # the new diagonal doubles an existing edge
    assert flipped.is_regular() and not flipped.is_strongly_regular()


def test_classification_names():
    cases = {(True, 0, 0): "sphere", (True, 1, 0): "torus", (True, 0, 1): "disk",
             (True, 0, 2): "annulus", (False, 1, 0): "projective plane",
             (False, 2, 0): "Klein bottle", (False, 1, 1): "Möbius strip",
             (True, 2, 1): "orientable genus 2, 1 boundary loop",
             (True, 3, 0): "orientable genus 3",
             (False, 3, 2): "non-orientable genus 3, 2 boundary loops"}
    for (o, g, k), name in cases.items():
        chi = 2 - (2 * g if o else g) - k
        c = Classification(o, g, k, chi)
        assert c.name == str(c) == name
    with pytest.raises(Exception):
        Classification(True, 0, 0, 2).genus = 1      # frozen


# --- operations ------------------------------------------------------------------------


def canonical(faces):
    def rot(f):
        i = f.index(min(f))
        return tuple(f[i:] + f[:i])
    return sorted(rot(list(f)) for f in faces)


def test_flip_convention():
    t = Triangulation.from_faces([[0, 1, 2], [1, 0, 3], [2, 1, 4]])
    f = t.flip(0)
    assert f.faces[:2] == ((2, 3, 1), (3, 2, 0)) and f.faces[2] == (2, 1, 4)
    assert f.edge_halfedges(0) == (0, 3) and f.edge_vertices(0) == (2, 3)
    # every other edge keeps its id and its endpoints
    for e in range(1, t.n_edges):
        assert set(f.edge_vertices(e)) == set(t.edge_vertices(e))
    assert f.edge_halfedges(1) == (2, 6)               # 1 -> 2 moved into slot 2, still glued
    assert_valid(f)
    assert t.faces[0] == (0, 1, 2)                       # not mutated


def test_flip_twice_restores_the_triangles():
    t = surfaces.octahedron().triangulation
    for e in range(t.n_edges):
        assert canonical(t.flip(e).flip(e).faces) == canonical(t.faces)


def test_flip_errors():
    d = surfaces.disk(4).triangulation
    boundary = next(e for e in range(d.n_edges) if d.is_boundary_edge(e))
    with pytest.raises(NotFlippable, match=f"edge {boundary}"):
        d.flip(boundary)
    with pytest.raises(IndexOutOfRange):
        d.flip(d.n_edges)
    with pytest.raises(NegativeIndex):
        d.flip(-1)


def test_flip_reversed_gluing():
    m = surfaces.mobius_strip(5).triangulation
    e = next(e for e in range(m.n_edges)
             if not m.is_boundary_edge(e) and m.reversed_gluing(m.edge_halfedges(e)[0]))
    f = m.flip(e)
    assert_valid(f)
    assert not f.reversed_gluing(f.edge_halfedges(e)[0])
    assert f.classify() == m.classify()


def test_flips_create_loops():
    t = tet().flip(0).flip(1)
    assert not t.is_regular()
    assert_valid(t)
    assert min(t.valence(v) for v in range(4)) == 1


def apply_flips(t, seq):
    for e in seq:
        try:
            t = t.flip(e % t.n_edges)
        except NotFlippable:
            pass
    return t


def test_some_flip_sequence_is_non_regular():
    for base in (tet(), surfaces.octahedron().triangulation):
        seq = find(st.lists(st.integers(0, 11)), lambda s: not apply_flips(base, s).is_regular(),
                   settings=settings(max_examples=2000, database=None))
        assert not apply_flips(base, seq).is_regular()


BASES = {"tetrahedron": lambda: tet(),
         "octahedron": lambda: surfaces.octahedron().triangulation,
         "projective plane": surfaces.projective_plane,
         "Möbius strip": lambda: surfaces.mobius_strip(3).triangulation,
         "Klein bottle": surfaces.klein_bottle}


@SETTINGS
@given(st.sampled_from(sorted(BASES)), st.lists(st.integers(0, 10 ** 6), max_size=25))
def test_random_flips_keep_structure_r15(name, seq):
    t0 = BASES[name]()
    t = t0
    for e in seq:
        try:
            t = t.flip(e % t.n_edges)
        except NotFlippable:
            h, tw = t.edge_halfedges(e % t.n_edges)
            assert tw < 0 or h // 3 == tw // 3
    assert_valid(t)
    assert t.euler_characteristic() == t0.euler_characteristic()
    assert t.classify() == t0.classify()
    assert (t.n_vertices, t.n_edges, t.n_faces) == (t0.n_vertices, t0.n_edges, t0.n_faces)


@SETTINGS
@given(st.sampled_from(sorted(BASES)), st.lists(st.integers(0, 10 ** 6), max_size=12),
       st.integers(0, 10 ** 6))
def test_operations_keep_chi_and_type_on_non_regular_input(name, seq, pick):
    t = apply_flips(BASES[name](), seq)
    c = t.classify()
    V, E, F = t.n_vertices, t.n_edges, t.n_faces
    e = pick % E
    s, m = t.split_edge(e)
    assert m == V and s.n_vertices == V + 1
    assert_valid(s)
    assert s.classify() == c
    h, tw = t.edge_halfedges(e)
    if tw < 0:
        assert (s.n_edges, s.n_faces) == (E + 2, F + 1)
    elif h // 3 != tw // 3:
        assert (s.n_edges, s.n_faces) == (E + 3, F + 2)
    for sub, extra_v, extra_e, factor in (
            (t.subdivide_1to4()[0], E, E + 3 * F, 4),
            (t.barycentric_subdivision()[0], E + F, E + 6 * F, 6)):
        assert (sub.n_vertices, sub.n_edges, sub.n_faces) == (V + extra_v, E + extra_e, factor * F)
        assert_valid(sub)
        assert sub.classify() == c
    r = t.with_reversed_faces([pick % F])
    assert_valid(r)
    assert r.classify() == c


@pytest.mark.parametrize("make", [tet, surfaces.projective_plane, surfaces.klein_bottle,
                                  lambda: surfaces.mobius_strip(4).triangulation,
                                  lambda: surfaces.annulus(4).triangulation,
                                  lambda: surfaces.genus_surface(2).triangulation])
def test_subdivisions_r15(make):
    t = make()
    V, E, F = t.n_vertices, t.n_edges, t.n_faces
    s, mids = t.subdivide_1to4()
    assert (s.n_vertices, s.n_edges, s.n_faces) == (V + E, 2 * E + 3 * F, 4 * F)
    assert mids == [t.edge_vertices(e) for e in range(E)]
    assert s.classify() == t.classify() and s.is_strongly_regular() == t.is_strongly_regular()
    b, prov = t.barycentric_subdivision()
    assert (b.n_vertices, b.n_edges, b.n_faces) == (V + E + F, 2 * E + 6 * F, 6 * F)
    assert prov[:E] == mids and prov[E:] == list(t.faces)
    assert b.classify() == t.classify() and b.is_strongly_regular()
    assert_valid(s)
    assert_valid(b)
    for e in range(0, E, 3):
        x, m = t.split_edge(e)
        assert x.euler_characteristic() == t.euler_characteristic() and x.classify() == t.classify()
        assert x.valence(m) == (3 if t.is_boundary_edge(e) else 4)


def test_multi_edges_get_distinct_midpoints():
    t = tet().flip(0)               # two edges join the same pair of vertices
    pairs = [frozenset(t.edge_vertices(e)) for e in range(t.n_edges)]
    assert len(set(pairs)) < len(pairs)
    s, mids = t.subdivide_1to4()
    assert s.n_vertices == t.n_vertices + t.n_edges
    assert s.is_regular()
    assert_valid(s)


def test_remove_face_punches_a_hole():
    for t in (tet(), surfaces.torus(4, 3).triangulation, surfaces.klein_bottle()):
        c = t.classify()
        r = t.remove_face(1)
        assert r.euler_characteristic() == t.euler_characteristic() - 1
        assert len(r.boundary_loops()) == 1
        rc = r.classify()
        assert (rc.orientable, rc.genus, rc.boundary_components) == (c.orientable, c.genus, 1)
        assert r.faces == t.faces[:1] + t.faces[2:]
        assert_valid(r)


def test_remove_face_errors():
    t = surfaces.torus(4, 4).triangulation.remove_face(0)
    hole = set(surfaces.torus(4, 4).triangulation.faces[0])
    # a face meeting the hole in one vertex only would pinch that vertex
    f = next(i for i, g in enumerate(t.faces) if len(hole & set(g)) == 1
             and all(t.twin(h) >= 0 for h in range(3 * i, 3 * i + 3)))
    with pytest.raises(NonManifoldVertex, match=f"removing face {f}"):
        t.remove_face(f)
    # a face sharing an edge with the hole just enlarges it
    g = next(i for i in range(t.n_faces) if any(t.twin(h) < 0 for h in range(3 * i, 3 * i + 3)))
    assert t.remove_face(g).euler_characteristic() == t.euler_characteristic()
    with pytest.raises(UnreferencedVertex, match="vertex 2"):
        surfaces.grid(1, 1).triangulation.remove_face(0)
    with pytest.raises(EmptyMesh):
        Triangulation.from_faces([[0, 1, 2]]).remove_face(0)


def test_relabelled():
    t = surfaces.octahedron().triangulation
    perm = [3, 5, 0, 1, 4, 2]
    r = t.relabelled(perm)
    assert r.faces[0] == tuple(perm[v] for v in t.faces[0])
    assert r.classify() == t.classify() and r.is_strongly_regular()
    assert_valid(r)
    with pytest.raises(BadShape):
        t.relabelled([0, 1, 2])
    with pytest.raises(InputError, match="twice"):
        t.relabelled([0, 0, 1, 2, 3, 4])
    with pytest.raises(IndexOutOfRange):
        t.relabelled([0, 1, 2, 3, 4, 6])


def test_with_reversed_faces():
    t = surfaces.cube().triangulation
    r = t.with_reversed_faces([0, 5])
    assert r.faces[0] == (t.faces[0][0], t.faces[0][2], t.faces[0][1])
    assert sum(r.reversed_gluing(h) for h in range(r.n_halfedges)) > 0
    assert r.is_orientable() and r.classify() == t.classify()
    assert_valid(r)
    assert r.with_reversed_faces([0, 5]).faces == t.faces
    assert not any(r.with_reversed_faces([0, 5]).reversed_gluing(h) for h in range(36))


def test_equality_and_immutability():
    t = tet()
    assert t == Triangulation.from_faces(TET) and hash(t) == hash(Triangulation.from_faces(TET))
    before = t.to_face_list()
    t.flip(0), t.split_edge(1), t.subdivide_1to4(), t.remove_face(0)
    assert t.to_face_list() == before and t == tet()
    assert t != t.flip(0)


# --- connected sum (CS, T1.1) -----------------------------------------------------------


def test_connected_sum_examples():
    rp = surfaces.projective_plane()
    k = connected_sum(rp, rp)
    assert k.classify() == surfaces.klein_bottle().classify()
    assert str(k.classify()) == "Klein bottle"
    t = surfaces.torus(4, 3).triangulation
    g2 = connected_sum(t, t)
    assert str(g2.classify()) == "orientable genus 2" and g2.is_strongly_regular()
    assert not any(g2.reversed_gluing(h) for h in range(g2.n_halfedges))   # orientation kept
    s = connected_sum(tet(), tet())
    assert (s.n_vertices, s.n_faces) == (5, 6) and s.is_strongly_regular()
    assert_valid(k)
    assert_valid(g2)


def test_connected_sum_face_choice_and_errors():
    a, b = tet(), surfaces.octahedron().triangulation
    s = connected_sum(a, b, face_a=0, face_b=3)
    assert s.faces[:3] == a.faces[1:]
    assert s.n_vertices == a.n_vertices + b.n_vertices - 3
    with pytest.raises(InputError, match="boundary edge"):
        connected_sum(a, surfaces.disk(5).triangulation)
    with pytest.raises(IndexOutOfRange):
        connected_sum(a, b, face_a=4)


CLOSED = {"sphere": lambda: tet(), "octahedron": lambda: surfaces.octahedron().triangulation,
          "torus": lambda: surfaces.torus(3, 3).triangulation,
          "RP2": surfaces.projective_plane, "Klein": surfaces.klein_bottle,
          "holed torus": lambda: surfaces.torus(4, 4).triangulation.remove_face(0)}


@SETTINGS
@given(st.sampled_from(sorted(CLOSED)), st.sampled_from(sorted(CLOSED)),
       st.integers(1, 10 ** 6), st.integers(1, 10 ** 6))
def test_connected_sum_random_pairs(na, nb, fa, fb):
    a, b = CLOSED[na](), CLOSED[nb]()
    fa, fb = fa % a.n_faces, fb % b.n_faces
    # only faces away from any boundary (the holed torus's hole) can be used
    if not all(x.twin(h) >= 0 and not x.is_boundary_vertex(x.tail(h))
               for x, f in ((a, fa), (b, fb)) for h in range(3 * f, 3 * f + 3)):
        return
    s = connected_sum(a, b, fa, fb)
    assert s.euler_characteristic() == a.euler_characteristic() + b.euler_characteristic() - 2
    ca, cb, cs = a.classify(), b.classify(), s.classify()
    assert cs.orientable == (ca.orientable and cb.orientable)
    assert cs.boundary_components == ca.boundary_components + cb.boundary_components

    def deficit(c):          # 2g or h: additive under connected sum (T1.1)
        return 2 - c.euler_characteristic - c.boundary_components
    assert deficit(cs) == deficit(ca) + deficit(cb)
    assert s.is_strongly_regular() == (a.is_strongly_regular() and b.is_strongly_regular())
    assert_valid(s)


def test_classify_genus_g_sums_r16():
    t = surfaces.torus(3, 3).triangulation
    s = t
    for g in range(2, 5):
        s = connected_sum(s, t)
        assert s.classify() == Classification(True, g, 0, 2 - 2 * g)
    holed = s.remove_face(0)
    assert holed.classify() == Classification(True, 4, 1, 2 - 8 - 1)


# --- scale (timings live in benchmarks/, never in tests) -------------------------------


def test_large_torus_classifies():
    n = 224                                      # 2 * 224^2 = 100352 faces (a torus)
    faces = []
    for i in range(n):
        for j in range(n):
            a, b = i * n + j, ((i + 1) % n) * n + j
            c, d = ((i + 1) % n) * n + (j + 1) % n, i * n + (j + 1) % n
            faces += [(a, b, c), (a, c, d)]
    t = Triangulation.from_faces(faces)
    assert str(t.classify()) == "torus"
    assert t.flip(12345).euler_characteristic() == 0


# --- the halfedge interface (HalfedgeMesh, Metric) and its helpers -----------------------------


def test_halfedge_helpers_are_the_numbering():
    from ddg_oracle.reference.combinatorics import (corner_of, cyclic, face_of, halfedge,
                                                    next_corner, opposite_corner,
                                                    opposite_halfedge, prev_corner)
    for f in range(4):
        for c in range(3):
            h = halfedge(f, c)
            assert (face_of(h), corner_of(h)) == (f, c) == divmod(h, 3)
            assert next_corner(c) == (c + 1) % 3 and prev_corner(c) == (c + 2) % 3
            assert opposite_corner(h) == (c + 2) % 3
            assert opposite_halfedge(f, c) == 3 * f + (c + 1) % 3
            assert opposite_corner(opposite_halfedge(f, c)) == c
    assert cyclic("abc", 1) == ("b", "c", "a")


@pytest.mark.parametrize("name", ["torus", "mobius_strip", "klein_bottle", "disk"])
def test_triangulation_and_its_builder_read_alike(name):
    """The builder an IntrinsicTriangulation flips in place answers every HalfedgeMesh
    question as the frozen Triangulation does, before and after flips."""
    from ddg_oracle.reference.combinatorics import HalfedgeMesh, TriangulationBuilder, face_of
    t = getattr(surfaces, name)()
    t = getattr(t, "triangulation", t)          # some constructors give the combinatorics only
    b = TriangulationBuilder(t)
    e = next(e for e in range(t.n_edges) if not t.is_boundary_edge(e)
             and len({face_of(x) for x in t.edge_halfedges(e)}) == 2)
    b.flip(e)
    frozen = b.build()
    for x in (t, b, frozen):
        assert isinstance(x, HalfedgeMesh)
    for h in range(3 * frozen.n_faces):
        assert (b.tail(h), b.head(h), b.twin(h), b.next(h), b.prev(h), b.face_of(h),
                b.reversed_gluing(h), b.edge_of(h)) == \
            (frozen.tail(h), frozen.head(h), frozen.twin(h), frozen.next(h), frozen.prev(h),
             frozen.face_of(h), frozen.reversed_gluing(h), frozen.edge_of(h))
    for e in range(frozen.n_edges):
        assert (b.edge_halfedges(e), b.edge_vertices(e), b.is_boundary_edge(e)) == \
            (frozen.edge_halfedges(e), frozen.edge_vertices(e), frozen.is_boundary_edge(e))
    assert (b.n_vertices, b.n_faces, b.n_edges, list(b.faces)) == \
        (frozen.n_vertices, frozen.n_faces, frozen.n_edges, list(frozen.faces))


def test_metric_interface_is_shared_by_the_flipped_in_place_surface():
    from ddg_oracle.reference.empty_disks import circumdisk
    from ddg_oracle.reference.intrinsic import IntrinsicTriangulation
    from ddg_oracle.reference.metric import Metric
    m = surfaces.octahedron().metric()
    w = IntrinsicTriangulation(m)
    w.flip(0)
    frozen = w.surface()
    assert isinstance(m, Metric) and isinstance(w, Metric)
    assert [w.squared_length(h) for h in range(24)] == [frozen.squared_length(h)
                                                        for h in range(24)]
    # edge-local code runs on either: the same developed circumdisks
    assert [circumdisk(w, f).on_circle for f in range(8)] == \
        [circumdisk(frozen, f).on_circle for f in range(8)]
