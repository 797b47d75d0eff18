"""Tests of ddg_oracle.reference.surfaces: X1.4 counts and chi, T1.1 / C1.2 / R1.6 classification,
exact embeddings, and the CS / remove_face relations on the example surfaces."""

import math
from fractions import Fraction

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ddg_oracle.reference import surfaces
from ddg_oracle.reference.combinatorics import Classification, Triangulation
from ddg_oracle.reference.errors import InputError
from ddg_oracle.reference.polyhedral import PolyhedralSurface

SETTINGS = settings(max_examples=80, deadline=None, database=None,
                    suppress_health_check=[HealthCheck.too_slow])

# name: (constructor, V, E, F, orientable, genus, boundary loops, readable name)
TABLE = {
    "tetrahedron": (surfaces.tetrahedron, 4, 6, 4, True, 0, 0, "sphere"),
    "octahedron": (surfaces.octahedron, 6, 12, 8, True, 0, 0, "sphere"),
    "cube": (surfaces.cube, 8, 18, 12, True, 0, 0, "sphere"),
    "icosahedron": (surfaces.icosahedron, 12, 30, 20, True, 0, 0, "sphere"),
    "torus": (lambda: surfaces.torus(5, 4), 20, 60, 40, True, 1, 0, "torus"),
    "torus 3x3": (lambda: surfaces.torus(3, 3), 9, 27, 18, True, 1, 0, "torus"),
    "genus 0": (lambda: surfaces.genus_surface(0), 8, 18, 12, True, 0, 0, "sphere"),
    "genus 1": (lambda: surfaces.genus_surface(1), 32, 96, 64, True, 1, 0, "torus"),
    "genus 2": (lambda: surfaces.genus_surface(2), 48, 150, 100, True, 2, 0,
                "orientable genus 2"),
    "genus 3": (lambda: surfaces.genus_surface(3), 64, 204, 136, True, 3, 0,
                "orientable genus 3"),
    "disk": (lambda: surfaces.disk(7), 8, 14, 7, True, 0, 1, "disk"),
    "annulus": (lambda: surfaces.annulus(6), 12, 24, 12, True, 0, 2, "annulus"),
    "grid": (lambda: surfaces.grid(3, 2), 12, 23, 12, True, 0, 1, "disk"),
    "mobius": (lambda: surfaces.mobius_strip(5), 10, 20, 10, False, 1, 1, "Möbius strip"),
    "mobius 3": (lambda: surfaces.mobius_strip(3), 6, 12, 6, False, 1, 1, "Möbius strip"),
    "projective plane": (surfaces.projective_plane, 6, 15, 10, False, 1, 0, "projective plane"),
    "klein bottle": (surfaces.klein_bottle, 9, 27, 18, False, 2, 0, "Klein bottle"),
    "klein bottle 4x5": (lambda: surfaces.klein_bottle(4, 5), 20, 60, 40, False, 2, 0,
                         "Klein bottle"),
}

EMBEDDED = [k for k in TABLE if k not in ("projective plane", "klein bottle",
                                          "klein bottle 4x5")]


def tri(obj) -> Triangulation:
    return obj.triangulation if isinstance(obj, PolyhedralSurface) else obj


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


@pytest.mark.parametrize("name", sorted(TABLE))
def test_counts_chi_and_classification_x14(name):
    make, V, E, F, orientable, genus, k, readable = TABLE[name]
    t = tri(make())
    assert (t.n_vertices, t.n_edges, t.n_faces) == (V, E, F)
    chi = V - E + F
    assert t.euler_characteristic() == chi
    assert chi == (2 - 2 * genus - k if orientable else 2 - genus - k)   # R1.6 / T1.1
    c = t.classify()
    assert c == Classification(orientable, genus, k, chi)
    assert str(c) == readable
    assert len(t.boundary_loops()) == k and t.is_orientable() == orientable


@pytest.mark.parametrize("name", sorted(TABLE))
def test_strongly_regular_d14(name):
    t = tri(TABLE[name][0]())
    assert t.is_regular() and t.is_strongly_regular()
    t.validate()


@pytest.mark.parametrize("name", sorted(TABLE))
def test_orientable_ones_are_consistently_oriented(name):
    t = tri(TABLE[name][0]())
    consistent = not any(t.reversed_gluing(h) for h in range(t.n_halfedges))
    assert consistent == TABLE[name][4]


@pytest.mark.parametrize("name", EMBEDDED)
def test_exact_embedding_in_r3(name):
    s = TABLE[name][0]()
    assert isinstance(s, PolyhedralSurface) and s.dimension == 3
    assert all(isinstance(x, Fraction) for p in s.positions for x in p)
    assert len(set(s.positions)) == len(s.positions)
    for f in s.faces:          # no degenerate triangles
        a, b, c = (s.positions[v] for v in f)
        assert cross(sub(b, a), sub(c, a)) != (0, 0, 0)


def test_closed_non_orientable_are_bare_triangulations():
    assert type(surfaces.projective_plane()) is Triangulation
    assert type(surfaces.klein_bottle()) is Triangulation


@pytest.mark.parametrize("name", ["tetrahedron", "octahedron", "cube", "icosahedron"])
def test_convex_polyhedra_convex_and_outward(name):
    """Every other vertex lies on the inner side of each face's plane (exactly);
    strictly so except for the cube, whose squares are split into coplanar pairs."""
    s = TABLE[name][0]()
    P = s.positions
    for f in s.faces:
        a, b, c = (P[v] for v in f)
        n = cross(sub(b, a), sub(c, a))
        side = [dot(n, sub(P[v], a)) for v in range(len(P)) if v not in f]
        if name == "cube":
            assert all(x <= 0 for x in side) and sum(x == 0 for x in side) == 1
        else:
            assert all(x < 0 for x in side)


def test_icosahedron_combinatorics():
    s = surfaces.icosahedron()
    t = s.triangulation
    assert all(t.valence(v) == 5 for v in range(12))
    assert all(isinstance(x, Fraction) and x.denominator in (1, 5) for p in s.positions for x in p)


def test_cube_integer_unit_cube():
    s = surfaces.cube()
    assert sorted(s.positions) == sorted((x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1))


def test_torus_points_exactly_on_torus():
    s = surfaces.torus(7, 5)
    for x, y, z in s.positions:
        # (x^2 + y^2 + z^2 + R^2 - r^2)^2 = 4 R^2 (x^2 + y^2), R = 3, r = 1
        assert (x * x + y * y + z * z + 8) ** 2 == 36 * (x * x + y * y)
    # outward: the normal points away from the core circle of radius 3 (floats
    # suffice: the margin is large)
    for f in s.faces:
        a, b, c = (s.positions[v] for v in f)
        n = cross(sub(b, a), sub(c, a))
        g = [float(sum(p[i] for p in (a, b, c)) / 3) for i in range(3)]
        rho = math.hypot(g[0], g[1])
        away = (g[0] - 3 * g[0] / rho, g[1] - 3 * g[1] / rho, g[2])
        assert dot([float(x) for x in n], away) > 0


def test_torus_evenly_spaced():
    s = surfaces.torus(12, 6)
    big = [math.atan2(float(p[1]), float(p[0])) % (2 * math.pi) for p in s.positions[::6]]
    steps = [(big[(i + 1) % 12] - big[i]) % (2 * math.pi) for i in range(12)]
    assert max(steps) - min(steps) < 0.01
    small = [math.atan2(float(p[2]), math.hypot(float(p[0]), float(p[1])) - 3)
             for p in s.positions[:6]]
    steps = [(small[(j + 1) % 6] - small[j]) % (2 * math.pi) for j in range(6)]
    assert max(steps) - min(steps) < 0.01


def test_disk_and_annulus_on_circles():
    d = surfaces.disk(9)
    assert d.positions[0] == (0, 0, 0)
    assert all(x * x + y * y == 1 and z == 0 for x, y, z in d.positions[1:])
    a = surfaces.annulus(9)
    assert all(x * x + y * y == 1 for x, y, _ in a.positions[:9])
    assert all(x * x + y * y == 4 for x, y, _ in a.positions[9:])
    for s in (d, a, surfaces.grid(2, 3)):      # counterclockwise in the plane z = 0
        for f in s.faces:
            p, q, r = (s.positions[v] for v in f)
            assert cross(sub(q, p), sub(r, p))[2] > 0


def test_grid_integer_points():
    s = surfaces.grid(3, 2)
    assert sorted(s.positions) == sorted((i, j, 0) for i in range(4) for j in range(3))
    assert all(x.denominator == 1 for p in s.positions for x in p)


def test_genus_surface_integer_coordinates():
    for g in range(4):
        s = surfaces.genus_surface(g)
        assert all(x.denominator == 1 for p in s.positions for x in p)
        assert s.triangulation.classify().genus == g


def test_mobius_strip_embedding():
    for n in (3, 4, 7):
        s = surfaces.mobius_strip(n)
        P = s.positions
        (loop,) = s.triangulation.boundary_loops()
        assert len(loop) == 2 * n
        for i in range(n):
            top, bottom = P[i], P[n + i]
            mid = tuple((a + b) / 2 for a, b in zip(top, bottom))
            assert mid[0] ** 2 + mid[1] ** 2 == 9 and mid[2] == 0      # the core circle
            assert dot(sub(top, bottom), sub(top, bottom)) == 4        # width 2
            assert dot(sub(top, bottom), (-mid[1], mid[0], 0)) == 0    # rung across the core


def test_projective_plane_is_k6():
    t = surfaces.projective_plane()
    pairs = {frozenset(t.edge_vertices(e)) for e in range(t.n_edges)}
    assert len(pairs) == 15                                  # every pair is an edge
    assert t.classify() == Classification(False, 1, 0, 1)


@pytest.mark.parametrize("m, n", [(3, 3), (3, 4), (4, 3), (5, 6)])
def test_klein_bottles(m, n):
    k = surfaces.klein_bottle(m, n)
    assert k.is_strongly_regular()
    assert k.classify() == Classification(False, 2, 0, 0)


@pytest.mark.parametrize("call", [lambda: surfaces.torus(2, 3), lambda: surfaces.torus(3, 1.5),
                                  lambda: surfaces.disk(2), lambda: surfaces.annulus(True),
                                  lambda: surfaces.grid(0, 2), lambda: surfaces.mobius_strip(2),
                                  lambda: surfaces.genus_surface(-1),
                                  lambda: surfaces.klein_bottle(2, 5)])
def test_bad_parameters(call):
    with pytest.raises(InputError, match="must be an integer >="):
        call()


# --- CS and holes --------------------------------------------------------------------


def test_rp2_sum_rp2_is_klein_bottle():
    rp = surfaces.projective_plane()
    s = surfaces.connected_sum(rp, rp)
    assert s.classify() == surfaces.klein_bottle().classify()
    assert s.is_strongly_regular()
    assert s.euler_characteristic() == 2 * rp.euler_characteristic() - 2


def test_torus_sum_torus_is_genus_two():
    t = surfaces.torus(3, 3).triangulation
    s = surfaces.connected_sum(t, t)
    assert s.classify() == surfaces.genus_surface(2).triangulation.classify()


def test_klein_sum_rp2_equals_torus_sum_rp2():
    rp, k = surfaces.projective_plane(), surfaces.klein_bottle()
    t = surfaces.torus(3, 3).triangulation
    a, b = surfaces.connected_sum(k, rp), surfaces.connected_sum(t, rp)
    assert a.classify() == b.classify() == Classification(False, 3, 0, -1)


CLOSED = ["tetrahedron", "octahedron", "cube", "icosahedron", "torus", "torus 3x3",
          "genus 1", "genus 2", "projective plane", "klein bottle"]


@SETTINGS
@given(st.sampled_from(CLOSED), st.sampled_from(CLOSED), st.integers(0, 10 ** 6),
       st.integers(0, 10 ** 6))
def test_connected_sum_chi_cs(na, nb, fa, fb):
    a, b = tri(TABLE[na][0]()), tri(TABLE[nb][0]())
    s = surfaces.connected_sum(a, b, fa % a.n_faces, fb % b.n_faces)
    assert s.euler_characteristic() == a.euler_characteristic() + b.euler_characteristic() - 2
    assert s.is_strongly_regular()
    ca, cb, cs = a.classify(), b.classify(), s.classify()
    assert cs.orientable == (ca.orientable and cb.orientable)
    if cs.orientable:
        assert cs.genus == ca.genus + cb.genus
    else:   # crosscaps: a handle counts as two (T1.1: K # RP^2 = T^2 # RP^2)
        assert cs.genus == sum(c.genus * (2 if c.orientable else 1) for c in (ca, cb))


@SETTINGS
@given(st.sampled_from(CLOSED), st.integers(0, 10 ** 6))
def test_remove_face_lowers_chi_cs(name, f):
    t = tri(TABLE[name][0]())
    r = t.remove_face(f % t.n_faces)
    assert r.euler_characteristic() == t.euler_characteristic() - 1
    assert len(r.boundary_loops()) == 1
    assert r.classify().genus == t.classify().genus


@SETTINGS
@given(st.sampled_from(["torus", "genus 2", "genus 3", "icosahedron", "klein bottle 4x5"]),
       st.lists(st.integers(0, 10 ** 6), min_size=1, max_size=4))
def test_holes_r16(name, picks):
    """Punch holes at faces sharing no vertex: chi = 2 - 2g - k (orientable), 2 - h - k."""
    t = tri(TABLE[name][0]())
    c0 = t.classify()
    chosen, used = [], set()
    for p in picks:
        f = p % t.n_faces
        if not used & set(t.faces[f]):
            chosen.append(f)
            used |= set(t.faces[f])
    for f in sorted(chosen, reverse=True):       # later faces first: indices stay valid
        t = t.remove_face(f)
    c = t.classify()
    k = len(chosen)
    assert c.boundary_components == k and c.genus == c0.genus
    assert c.orientable == c0.orientable
    expected = 2 - 2 * c.genus - k if c.orientable else 2 - c.genus - k
    assert t.euler_characteristic() == expected
