"""Mutants of reference/combinatorics.py killed on generic triangulations (docs/mutation.md).

Every triangulation here is checked against things computed from its face list alone
(which vertex pairs occur once or twice, which corners a vertex has), against the
classification of surfaces (T1.1 / C1.2 / R1.6: chi, orientability and the number of
boundary loops determine the surface, and surgery changes them as the notes say), and
against the halfedge identities.  The triangulations are non-regular (loops and multiple
edges after flips), non-orientable, with several boundary loops, and made by random
sequences of flips, edge splits, subdivisions, holes and connected sums.
"""

from __future__ import annotations

import pickle
import random
from collections import Counter

import pytest

from ddg_oracle.reference import combinatorics as C
from ddg_oracle.reference import surfaces
from ddg_oracle.reference.combinatorics import Classification, Triangulation, connected_sum
from ddg_oracle.reference.errors import (BadShape, EmptyMesh, IndexOutOfRange, InputError,
                                         NegativeIndex, NonIntegerIndex, NonManifoldEdge,
                                         NonManifoldVertex, NotConnected, NotFlippable,
                                         RepeatedVertexInFace, UnreferencedVertex)


def T(x):
    return x if isinstance(x, Triangulation) else x.triangulation


# (triangulation, (orientable, genus, boundary loops, chi)) by hand from the notes
KNOWN = [
    ("tetrahedron", T(surfaces.tetrahedron()), (True, 0, 0, 2)),
    ("icosahedron", T(surfaces.icosahedron()), (True, 0, 0, 2)),
    ("torus", T(surfaces.torus(4, 3)), (True, 1, 0, 0)),
    ("genus 2", T(surfaces.genus_surface(2)), (True, 2, 0, -2)),
    ("disk", T(surfaces.disk(5)), (True, 0, 1, 1)),
    ("annulus", T(surfaces.annulus(4)), (True, 0, 2, 0)),
    ("mobius", T(surfaces.mobius_strip(5)), (False, 1, 1, 0)),
    ("projective plane", surfaces.projective_plane(), (False, 1, 0, 1)),
    ("klein bottle", surfaces.klein_bottle(3, 4), (False, 2, 0, 0)),
    ("grid", T(surfaces.grid(3, 2)), (True, 0, 1, 1)),
]


def _random_surgery(t: Triangulation, seed: int, steps: int = 12) -> Triangulation:
    """Random flips and edge splits (chi and the surface unchanged, R1.5)."""
    rng = random.Random(seed)
    for _ in range(steps):
        e = rng.randrange(t.n_edges)
        if rng.random() < 0.7:
            h, k = t.edge_halfedges(e)
            if k >= 0 and h // 3 != k // 3:
                t = t.flip(e)
        else:
            t, _ = t.split_edge(e)
    return t


def generic_triangulations():
    out = []
    for i, (name, t, cls) in enumerate(KNOWN):
        out.append((name, t, cls))
        out.append((name + " after surgery", _random_surgery(t, i), cls))
    return out


GENERIC = generic_triangulations()
GIDS = [n for n, _, _ in GENERIC]


# --- structure read off the face list ----------------------------------------------------------


def _edge_counts(t):
    """{frozenset or (v,) pair: how often} from the faces of a *regular* triangulation,
    else None (then pairs do not determine edges)."""
    c = Counter()
    for a, b, d in t.faces:
        for u, v in ((a, b), (b, d), (d, a)):
            c[frozenset((u, v))] += 1
    return c


@pytest.mark.parametrize("case", GENERIC, ids=GIDS)
def test_halfedge_identities(case):
    name, t, _ = case
    H = 3 * t.n_faces
    seen = Counter()
    for h in range(H):
        f, c = divmod(h, 3)
        assert C.face_of(h) == f and C.corner_of(h) == c and C.halfedge(f, c) == h
        assert t.next(t.next(t.next(h))) == h and t.prev(t.next(h)) == h
        assert t.tail(h) == t.faces[f][c] and t.head(h) == t.faces[f][(c + 1) % 3]
        assert t.head(h) == t.tail(t.next(h)) and t.tail(h) == t.head(t.prev(h))
        assert C.opposite_corner(h) == (c + 2) % 3 == C.next_corner(C.next_corner(c))
        assert C.prev_corner(c) == (c + 2) % 3 and C.next_corner(c) == (c + 1) % 3
        assert C.opposite_halfedge(f, c) == 3 * f + (c + 1) % 3
        assert C.cyclic(t.faces[f], c) == tuple(t.faces[f][(c + k) % 3] for k in range(3))
        tw = t.twin(h)
        e = t.edge_of(h)
        seen[e] += 1
        assert h in t.edge_halfedges(e)
        if tw < 0:
            assert t.is_boundary_edge(e) and t.edge_halfedges(e) == (h, -1)
            continue
        assert t.twin(tw) == h and t.edge_of(tw) == e
        assert t.reversed_gluing(h) == t.reversed_gluing(tw)
        if t.reversed_gluing(h):
            assert (t.tail(tw), t.head(tw)) == (t.tail(h), t.head(h))
        else:
            assert (t.tail(tw), t.head(tw)) == (t.head(h), t.tail(h))
    assert all(seen[e] == (1 if t.is_boundary_edge(e) else 2) for e in range(t.n_edges))
    assert sum(seen.values()) == H
    assert t.edge_vertices(0) == (t.tail(t.edge_halfedges(0)[0]), t.head(t.edge_halfedges(0)[0]))
    t.validate()


@pytest.mark.parametrize("case", GENERIC, ids=GIDS)
def test_stars_against_the_face_list(case):
    name, t, _ = case
    corners = Counter(v for f in t.faces for v in f)
    ends = Counter()
    for e in range(t.n_edges):
        a, b = t.edge_vertices(e)
        ends[a] += 1
        ends[b] += 1
    boundary = set()
    for e in range(t.n_edges):
        if t.is_boundary_edge(e):
            boundary.update(t.edge_vertices(e))
    assert t.boundary_vertices() == boundary
    total = 0
    for v in range(t.n_vertices):
        around = t.corners_around(v)
        assert len(around) == corners[v]
        assert all(t.faces[f][c] == v for f, c in around)
        assert t.valence(v) == ends[v] == len(t.neighbours(v))
        total += t.valence(v)
        assert t.is_boundary_vertex(v) == (v in boundary)
        # a closed fan has as many corners as edge ends, an open one one corner fewer
        assert len(around) == t.valence(v) - (v in boundary)
        # neighbours with multiplicity: the other end of every edge end at v
        nb = Counter()
        for e in range(t.n_edges):
            a, b = t.edge_vertices(e)
            if a == v:
                nb[b] += 1
            if b == v:
                nb[a] += 1
        assert Counter(t.neighbours(v)) == nb
        # consecutive corners of the fan share an edge
        for (f, c), (g, d) in zip(around, around[1:]):
            a = {t.edge_of(3 * f + c), t.edge_of(3 * f + (c + 2) % 3)}
            b = {t.edge_of(3 * g + d), t.edge_of(3 * g + (d + 2) % 3)}
            assert a & b
    assert total == 2 * t.n_edges


@pytest.mark.parametrize("case", GENERIC, ids=GIDS)
def test_classification_and_boundary_loops(case):
    name, t, expected = case
    c = t.classify()
    assert (c.orientable, c.genus, c.boundary_components, c.euler_characteristic) == expected
    assert t.euler_characteristic() == t.n_vertices - t.n_edges + t.n_faces == expected[3]
    assert t.is_orientable() == expected[0]
    assert t.is_connected() and t.components() == [list(range(t.n_faces))]
    loops = t.boundary_loops()
    assert len(loops) == expected[2]
    # the loops use every boundary edge once: consecutive vertices joined by one
    bedges = Counter()
    for e in range(t.n_edges):
        if t.is_boundary_edge(e):
            bedges[frozenset(t.edge_vertices(e))] += 1
    used = Counter()
    for loop in loops:
        for a, b in zip(loop, loop[1:] + loop[:1]):
            used[frozenset((a, b))] += 1
    assert used == bedges
    assert sum(map(len, loops)) == sum(bedges.values())


def test_classification_names():
    names = {(True, 0, 0): "sphere", (True, 0, 1): "disk", (True, 0, 2): "annulus",
             (True, 1, 0): "torus", (False, 1, 0): "projective plane",
             (False, 2, 0): "Klein bottle", (False, 1, 1): "Möbius strip"}
    for (o, g, k), n in names.items():
        chi = 2 - (2 * g if o else g) - k
        assert Classification(o, g, k, chi).name == n == str(Classification(o, g, k, chi))
    assert Classification(True, 2, 0, -2).name == "orientable genus 2"
    assert Classification(False, 3, 1, -2).name == "non-orientable genus 3, 1 boundary loop"
    assert Classification(True, 1, 3, -3).name == "orientable genus 1, 3 boundary loops"


# --- surgery: the notes' formulas ------------------------------------------------------------


@pytest.mark.parametrize("case", GENERIC, ids=GIDS)
def test_subdivisions_keep_the_surface(case):
    name, t, expected = case
    V, E, F = t.n_vertices, t.n_edges, t.n_faces
    s, mids = t.subdivide_1to4()
    assert (s.n_vertices, s.n_edges, s.n_faces) == (V + E, 2 * E + 3 * F, 4 * F)
    assert mids == [t.edge_vertices(e) for e in range(E)]
    c = s.classify()
    assert (c.orientable, c.genus, c.boundary_components, c.euler_characteristic) == expected
    for f, x in enumerate(t.faces):
        m = tuple(V + t.edge_of(3 * f + k) for k in range(3))
        assert s.faces[4 * f:4 * f + 4] == ((x[0], m[0], m[2]), (x[1], m[1], m[0]), (x[2], m[2], m[1]), m)
    s.validate()
    b, prov = t.barycentric_subdivision()
    assert (b.n_vertices, b.n_edges, b.n_faces) == (V + E + F, 2 * E + 6 * F, 6 * F)
    assert prov == [t.edge_vertices(e) for e in range(E)] + list(t.faces)
    c = b.classify()
    assert (c.orientable, c.genus, c.boundary_components, c.euler_characteristic) == expected
    b.validate()
    # a subdivision of a regular triangulation is strongly regular (no loops, no doubles)
    assert b.is_regular()


@pytest.mark.parametrize("case", GENERIC, ids=GIDS)
def test_flips_and_splits_keep_the_surface(case):
    name, t, expected = case
    rng = random.Random(len(name))
    for e in rng.sample(range(t.n_edges), min(6, t.n_edges)):
        h, k = t.edge_halfedges(e)
        s, m = t.split_edge(e)
        assert m == t.n_vertices == s.n_vertices - 1
        assert s.n_faces == t.n_faces + (1 if k < 0 else 2)
        assert s.n_edges == t.n_edges + (2 if k < 0 else 3)
        a, b = t.edge_vertices(e)
        assert s.edge_vertices(e) in ((a, m), (m, a))
        assert Counter(s.neighbours(m)) == Counter([a, b] + [t.faces[x // 3][(x % 3 + 2) % 3] for x in (h, k) if x >= 0])
        c = s.classify()
        assert (c.orientable, c.genus, c.boundary_components) == expected[:3]
        s.validate()
        if k < 0:
            with pytest.raises(NotFlippable):
                t.flip(e)
            continue
        if h // 3 == k // 3:
            with pytest.raises(NotFlippable):
                t.flip(e)
            continue
        f = t.flip(e)
        i, j = t.edge_vertices(e)
        kk = t.faces[h // 3][(h % 3 + 2) % 3]
        ll = t.faces[k // 3][(k % 3 + 2) % 3]
        assert set(f.edge_vertices(e)) == {kk, ll}
        assert f.faces[h // 3] == (kk, ll, j) and f.faces[k // 3] == (ll, kk, i)
        c = f.classify()
        assert (c.orientable, c.genus, c.boundary_components) == expected[:3]
        f.validate()
        # every other edge keeps its vertices
        for x in range(t.n_edges):
            if x != e:
                assert set(f.edge_vertices(x)) == set(t.edge_vertices(x))


def test_flips_make_loops_and_multiple_edges():
    t = T(surfaces.tetrahedron())
    f = t.flip(0)
    assert f.is_regular() and not f.is_strongly_regular()
    rng = random.Random(3)
    seen_loop = False
    for _ in range(200):
        e = rng.randrange(f.n_edges)
        h, k = f.edge_halfedges(e)
        if h // 3 != k // 3:
            f = f.flip(e)
        if not f.is_regular():
            seen_loop = True
            assert any(len(set(x)) < 3 for x in f.faces)
            assert not f.is_strongly_regular()
            f.validate()
            c = f.classify()
            assert (c.orientable, c.genus, c.euler_characteristic) == (True, 0, 2)
    assert seen_loop
    assert T(surfaces.icosahedron()).is_strongly_regular()
    # two faces with the same vertex set, no double edge: not strongly regular
    pillow = Triangulation.from_faces([[0, 1, 2], [0, 2, 1]])
    assert pillow.is_regular() and not pillow.is_strongly_regular()


def test_holes_and_connected_sums():
    tor = T(surfaces.torus(4, 3))
    r = tor.remove_face(5)
    c = r.classify()
    assert (c.orientable, c.genus, c.boundary_components, c.euler_characteristic) == (True, 1, 1, -1)
    assert r.n_faces == tor.n_faces - 1 and r.faces[5] == tor.faces[6]
    far = next(f for f in range(r.n_faces) if not set(r.faces[f]) & set(tor.faces[5]))
    r2 = r.remove_face(far)
    c = r2.classify()
    assert (c.boundary_components, c.euler_characteristic, c.genus) == (2, -2, 1)
    with pytest.raises(NonManifoldVertex):
        # a face touching the hole at a corner only
        r.remove_face(next(f for f in range(r.n_faces)
                           if set(r.faces[f]) & set(tor.faces[5]) and len(set(r.faces[f]) & set(tor.faces[5])) == 1))
    with pytest.raises(EmptyMesh):
        Triangulation.from_faces([[0, 1, 2]]).remove_face(0)
    with pytest.raises(UnreferencedVertex):
        T(surfaces.grid(1, 1)).remove_face(0)         # vertex 2 lies on face 0 only
    kl = surfaces.klein_bottle(3, 3)
    rp = surfaces.projective_plane()
    for a, b, expected in ((tor, tor, (True, 2, 0, -2)), (rp, rp, (False, 2, 0, 0)),
                           (tor, rp, (False, 3, 0, -1)), (kl, tor, (False, 4, 0, -2)),
                           (T(surfaces.icosahedron()), kl, (False, 2, 0, 0))):
        for fa, fb in ((-1, -1), (0, 3), (2, -2)):
            s = connected_sum(a, b, fa, fb)
            c = s.classify()
            assert (c.orientable, c.genus, c.boundary_components, c.euler_characteristic) == expected
            assert s.n_faces == a.n_faces + b.n_faces - 2
            assert s.n_vertices == a.n_vertices + b.n_vertices - 3
            s.validate()
            assert s.faces[:a.n_faces - 1] == tuple(x for g, x in enumerate(a.faces) if g != fa % a.n_faces)
    assert connected_sum(surfaces.torus(4, 3), surfaces.cube()).classify().genus == 1
    with pytest.raises(TypeError):
        connected_sum([[0, 1, 2]], tor)
    with pytest.raises(InputError):
        connected_sum(T(surfaces.disk(5)), tor, 0, 0)
    with pytest.raises(IndexOutOfRange):
        connected_sum(tor, tor, tor.n_faces, 0)


def test_relabel_reverse_and_equality():
    t = _random_surgery(surfaces.klein_bottle(3, 3), 5)
    rng = random.Random(4)
    perm = list(range(t.n_vertices))
    rng.shuffle(perm)
    r = t.relabelled(perm)
    assert r.classify() == t.classify()
    assert all(r.edge_vertices(e) == tuple(perm[v] for v in t.edge_vertices(e)) for e in range(t.n_edges))
    assert r != t and t.relabelled(list(range(t.n_vertices))) == t
    for bad, err in (([0] * t.n_vertices, InputError), (perm[:-1], BadShape),
                     ([1.5] + perm[1:], NonIntegerIndex), ([t.n_vertices] + perm[1:], IndexOutOfRange)):
        with pytest.raises(err):
            t.relabelled(bad)
    tor = T(surfaces.torus(4, 3))
    half = set(range(0, tor.n_faces, 2))
    rv = tor.with_reversed_faces(half)
    assert rv.classify() == tor.classify() and rv.is_orientable()
    assert sum(rv.reversed_gluing(h) for h in range(3 * rv.n_faces)) > 0
    assert all(rv.faces[f] == ((tor.faces[f][0], tor.faces[f][2], tor.faces[f][1]) if f in half else tor.faces[f])
               for f in range(tor.n_faces))
    assert rv.with_reversed_faces(half) == tor
    assert pickle.loads(pickle.dumps(t)) == t and hash(pickle.loads(pickle.dumps(t))) == hash(t)
    assert repr(t) == f"Triangulation(V={t.n_vertices}, E={t.n_edges}, F={t.n_faces}, chi={t.euler_characteristic()})"
    assert (t == 3) is False
    assert t.to_face_list() == [list(f) for f in t.faces]


def test_components_of_a_disjoint_union():
    a = [[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]]
    b = [[x + 4 for x in f] for f in a]
    t = Triangulation.from_faces(b[:2] + a + b[2:])
    assert t.components() == [[0, 1, 6, 7], [2, 3, 4, 5]]
    assert not t.is_connected()
    with pytest.raises(NotConnected):
        t.classify()


# --- input validation ------------------------------------------------------------------------


@pytest.mark.parametrize("faces, kw, err", [
    ([], {}, EmptyMesh),
    ("abc", {}, BadShape),
    (None, {}, BadShape),
    (5, {}, BadShape),
    ([[0, 1]], {}, BadShape),
    ([[0, 1, [2]]], {}, BadShape),
    ([[0, 1, 2.0]], {}, NonIntegerIndex),
    ([[0, 1, True]], {}, NonIntegerIndex),
    ([[0, -1, 2]], {}, NegativeIndex),
    ([[0, 1, 2]], {"n_vertices": 2}, IndexOutOfRange),
    ([[0, 1, 2]], {"n_vertices": -1}, NegativeIndex),
    ([[0, 1, 2]], {"n_vertices": 2.5}, NonIntegerIndex),
    ([[0, 1, 1]], {}, RepeatedVertexInFace),
    ([[0, 1, 2], [0, 1, 3], [1, 0, 4]], {}, NonManifoldEdge),
    ([[0, 1, 2], [0, 3, 4]], {}, NonManifoldVertex),
    ([[0, 1, 2]], {"n_vertices": 4}, UnreferencedVertex),
    ([[0, 1, 2]], {"n_vertices": 10 ** 12}, UnreferencedVertex),
])
def test_from_faces_errors(faces, kw, err):
    with pytest.raises(err):
        Triangulation.from_faces(faces, **kw)


def test_from_faces_accepts_what_it_should():
    t = Triangulation.from_faces([(0, 1, 2), [1, 0, 3]], n_vertices=4)
    assert t.n_vertices == 4 and t.n_edges == 5 and not t.reversed_gluing(0)
    m = Triangulation.from_faces([[0, 1, 2], [0, 1, 3]])
    assert m.reversed_gluing(0) and m.is_orientable()       # re-orientable: not a Moebius strip
    np = pytest.importorskip("numpy")
    assert Triangulation.from_faces(np.array([[0, 1, 2], [1, 0, 3]]), np.int64(4)) == t
    assert Triangulation.from_faces([np.array([0, 1, 2]), np.array([1, 0, 3])]) == t   # numpy rows
    # edges numbered by first occurrence
    assert [t.edge_vertices(e) for e in range(t.n_edges)] == [(0, 1), (1, 2), (2, 0), (0, 3), (3, 1)]


@pytest.mark.parametrize("gluings, err", [
    ([(0, -1, False), (1, -1, False)], InputError),                  # halfedge 2 unglued
    ([(0, -1, False), (1, -1, False), (2, -1, False), (0, -1, False)], InputError),
    ([(0, 0, False), (1, -1, False), (2, -1, False)], InputError),   # glued to itself
    ([(0, 1, False), (2, -1, False)], InputError),                   # endpoints do not match
    ([(0, -1), (1, -1, False), (2, -1, False)], BadShape),
    ([(0.5, -1, False), (1, -1, False), (2, -1, False)], NonIntegerIndex),
    ([(3, -1, False), (1, -1, False), (2, -1, False)], IndexOutOfRange),
    ([(0, -2, False), (1, -1, False), (2, -1, False)], IndexOutOfRange),
])
def test_gluing_errors(gluings, err):
    with pytest.raises(err):
        Triangulation([[0, 1, 2]], gluings)


def test_gluings_build_the_same_as_from_faces():
    for name, t, _ in GENERIC:
        g = [(a, b, r) for a, b, r in t._gluings()]
        again = Triangulation(t.faces, g, t.n_vertices)
        assert again == t
        assert again.classify() == t.classify()
    # a reversed flag on a boundary edge is dropped
    t = Triangulation([[0, 1, 2]], [(0, -1, True), (1, -1, False), (2, -1, False)])
    assert not t.reversed_gluing(0)


def test_index_checks():
    assert C.checked_index(-1, 5, "face", allow_negative=True) == 4
    assert C.checked_index(-5, 5, "face", allow_negative=True) == 0
    for i, err in ((-6, NegativeIndex), (5, IndexOutOfRange), (1.0, NonIntegerIndex), (True, NonIntegerIndex)):
        with pytest.raises(err):
            C.checked_index(i, 5, "face", allow_negative=True)
    with pytest.raises(NegativeIndex):
        C.checked_index(-1, 5, "face")
    t = T(surfaces.tetrahedron())
    for bad in (-1, 6):
        with pytest.raises(InputError):
            t.flip(bad)
        with pytest.raises(InputError):
            t.split_edge(bad)
    with pytest.raises(InputError):
        t.valence(4)
    assert C._short("x" * 100).endswith("...") and len(C._short("x" * 100)) == 60
    assert C._short([1]) == "[1]"


def test_builder_reads_like_the_triangulation_it_builds():
    # long flip sequences on one builder (as IntrinsicTriangulation runs them): every
    # reading agrees with the frozen triangulation, on closed and bordered surfaces
    rng = random.Random(8)
    for t in (T(surfaces.torus(4, 3)), surfaces.klein_bottle(3, 3), T(surfaces.disk(6))):
        b = C.TriangulationBuilder(t)
        twin_zero = False
        for _ in range(60):
            e = rng.randrange(b.n_edges)
            h, k = b.edge_halfedges(e)
            if k >= 0 and h // 3 != k // 3:
                b.flip(e)
            built = b.build()
            built.validate()
            assert (b.n_vertices, b.n_edges, b.n_faces) == (built.n_vertices, built.n_edges, built.n_faces)
            for x in range(b.n_edges):
                assert b.edge_halfedges(x) == built.edge_halfedges(x)
                assert b.edge_vertices(x) == built.edge_vertices(x)
                assert b.is_boundary_edge(x) == built.is_boundary_edge(x) == (built.edge_halfedges(x)[1] < 0)
                twin_zero |= built.edge_halfedges(x)[1] == 0
            for h in range(3 * b.n_faces):
                assert (b.tail(h), b.head(h), b.twin(h), b.reversed_gluing(h), b.edge_of(h)) == \
                    (built.tail(h), built.head(h), built.twin(h), built.reversed_gluing(h), built.edge_of(h))
                assert b.next(h) == built.next(h) and b.prev(h) == built.prev(h) and b.face_of(h) == h // 3
            assert built.classify() == t.classify()
        assert twin_zero or t.boundary_vertices()


def test_hash_is_a_function_of_the_triangulation():
    ts = [t for _, t, _ in GENERIC]
    assert len({hash(t) for t in ts}) == len(set(ts)) > 10       # distinct ones hash apart here
    assert all(hash(t) == hash(Triangulation(t.faces, t._gluings(), t.n_vertices)) for t in ts)


def test_remove_a_face_next_to_halfedge_0_after_flips():
    # after flips an edge can run from another face to halfedge 0 (its twin): removing
    # that other face must keep the edge, now a boundary edge of face 0
    rng = random.Random(9)
    t = T(surfaces.torus(4, 3))
    for _ in range(400):
        x = next((e for e in range(t.n_edges) if t.edge_halfedges(e)[1] == 0), None)
        if x is not None:
            break
        e = rng.randrange(t.n_edges)
        h, k = t.edge_halfedges(e)
        if h // 3 != k // 3:
            t = t.flip(e)
    assert x is not None
    f = t.edge_halfedges(x)[0] // 3
    r = t.remove_face(f)
    r.validate()
    c = r.classify()
    assert (c.orientable, c.genus, c.boundary_components, c.euler_characteristic) == (True, 1, 1, -1)
    assert r.n_edges == t.n_edges and sum(r.is_boundary_edge(e) for e in range(r.n_edges)) == 3
