"""Tests of ddg_oracle.reference.intrinsic: exact intrinsic edge flips (L2.8, X2.5).

The closed formulas are checked against coordinates (planar rational quads,
exactly; quads in R^3, exactly via an independent decomposition and with
numpy by rotating one triangle about the hinge); flips are checked to keep
rational data rational and data from R^3 inside the field of the original
face areas, to preserve every vertex's angle sum and the total area exactly,
to be undone by flipping back, and to work on non-regular and non-orientable
triangulations.
"""

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, event, given, settings
from hypothesis import strategies as st

from ddg_oracle.reference import surfaces
from ddg_oracle.reference.combinatorics import Triangulation
from ddg_oracle.reference.errors import DegenerateFace, NotFlippable, TermLimitExceeded
from ddg_oracle.reference.exact import Surd, corner_angle, limits, pi, sqrt
from ddg_oracle.reference.intrinsic import (Unfolding, cot_sum, flip, is_flippable,
                                 regular_tetrahedron_flip, unfold)
from ddg_oracle.reference.metric import PiecewiseFlatSurface, heron16, metric_of

SETTINGS = settings(max_examples=40, deadline=None, database=None,
                    suppress_health_check=[HealthCheck.too_slow])
FEW = settings(max_examples=12, deadline=None, database=None,
               suppress_health_check=[HealthCheck.too_slow])

TET = [[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]]

coord = st.fractions(-6, 6, max_denominator=4)
point2 = st.tuples(coord, coord)
point3 = st.tuples(coord, coord, coord)
choices = st.lists(st.integers(0, 1 << 20), min_size=1, max_size=12)


# --- helpers ----------------------------------------------------------------------------


def orient(p, q, r):
    """Twice the signed area of the planar triangle p, q, r."""
    return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])


def sqdist(p, q):
    return sum((x - y) ** 2 for x, y in zip(p, q))


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def hinge(points, reverse=False):
    """Faces (0, 1, 2) and (1, 0, 3) sharing edge 0 = {0, 1}; ``reverse``: the second
    face listed as (0, 1, 3), so the gluing of edge 0 reverses orientation."""
    second = [0, 1, 3] if reverse else [1, 0, 3]
    return metric_of(points, Triangulation.from_faces([[0, 1, 2], second]))


def angle_sums(m):
    t = m.triangulation
    return [sum(corner_angle(m.corner_cot(f, c)) for f, c in t.corners_around(v))
            for v in range(t.n_vertices)]


def assert_faces_valid(m):
    """Every face: positive carried area, strict triangle inequality, and the carried
    area agrees exactly with the lengths (Heron: 16 A^2 = heron16)."""
    for f in range(m.triangulation.n_faces):
        a, b, c = m.face_squared_lengths(f)
        h = heron16(a, b, c)
        A = m.areas[f]
        assert A > 0, f"face {f}: area {A}"
        assert h > 0, f"face {f}: triangle inequality fails"
        assert 16 * A * A == h, f"face {f}: carried area disagrees with the lengths"


def random_flips(m, picks, check_raise=True):
    """Apply the chosen flips; unflippable edges must raise NotFlippable."""
    done = []
    for c in picks:
        e = c % m.triangulation.n_edges
        if is_flippable(m, e):
            m = flip(m, e)
            done.append(e)
        elif check_raise:
            with pytest.raises(NotFlippable, match=f"edge {e} "):
                flip(m, e)
    event(f"flips done: {min(len(done), 5)}{'+' if len(done) >= 5 else ''}")
    return m, done


def is_rational_number(x):
    return isinstance(x, Fraction) or (isinstance(x, Surd) and x.is_rational())


@st.composite
def jittered_grids(draw, max_size=3):
    """A planar grid with every vertex moved by a small rational vector (metric exact,
    all squared lengths and areas rational)."""
    m = draw(st.integers(1, max_size))
    n = draw(st.integers(1, max_size))
    g = surfaces.grid(m, n)
    jit = st.tuples(st.integers(-2, 2), st.integers(-2, 2))
    moves = draw(st.lists(jit, min_size=g.n_vertices, max_size=g.n_vertices))
    pts = [(x + Fraction(dx, 10), y + Fraction(dy, 10), z)
           for (x, y, z), (dx, dy) in zip(g.positions, moves)]
    for f in g.faces:
        assume(orient(*(pts[v] for v in f)) != 0)
    return metric_of(pts, g.triangulation)


def flat_torus(m, n, v1, v2):
    """The m x n grid on the flat torus R^2 / (m v1 Z + n v2 Z), squares split by a
    diagonal; squared lengths from the lattice vectors (rational), areas |det|/2."""
    def vid(i, j):
        return (i % m) * n + j % n

    faces, vecs = [], []
    w = (v1[0] + v2[0], v1[1] + v2[1])
    for i in range(m):
        for j in range(n):
            a, b, c, d = vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)
            faces += [(a, b, c), (a, c, d)]
            vecs += [v1, v2, w, w, v1, v2]            # |.|^2 of halfedges 3f, 3f+1, 3f+2
    t = Triangulation.from_faces(faces)
    sq = [None] * t.n_edges
    for h, v in enumerate(vecs):
        sq[t.edge_of(h)] = v[0] ** 2 + v[1] ** 2
    return PiecewiseFlatSurface(t, sq)


# --- the closed formulas against coordinates ------------------------------------------


@SETTINGS
@given(point2, point2, point2, point2)
def test_L2_8_closed_formulas_and_predicate_match_planar_coordinates(i, j, k, l):
    sk, sl = orient(i, j, k), orient(i, j, l)
    assume(sk != 0 and sl != 0 and (sk > 0) != (sl > 0))
    if sk < 0:
        k, l = l, k                       # k to the left of i -> j, l to the right
    pts = [i + (0,), j + (0,), k + (0,), l + (0,)]
    m = hinge(pts)
    u = unfold(m, 0)
    assert isinstance(u, Unfolding)
    assert u.vertices == (0, 1, 2, 3) and u.faces == (0, 1)
    e = sqdist(i, j)
    assert (u.sq_ij, u.sq_jk, u.sq_ki, u.sq_il, u.sq_lj) == (
        e, sqdist(j, k), sqdist(k, i), sqdist(i, l), sqdist(l, j))
    assert u.area_ijk == orient(i, j, k) / 2 and u.area_jil == orient(j, i, l) / 2
    # the printed formulas (no misprint): diagonal and the two signed new areas
    assert u.new_squared_length == sqdist(k, l)
    assert u.new_area_at_i == orient(l, k, i) / 2
    assert u.new_area_at_j == orient(k, l, j) / 2
    assert all(isinstance(x, Fraction) for x in
               (u.new_squared_length, u.new_area_at_i, u.new_area_at_j))
    # the scaled layout is congruent to the quad scaled by |ij|, same orientation
    P, Q = u.scaled_points(), (i, j, k, l)
    for x in range(4):
        for y in range(x + 1, 4):
            assert sqdist(P[x], P[y]) == e * sqdist(Q[x], Q[y])
    assert orient(*P[:3]) > 0 and orient(P[0], P[1], P[3]) < 0
    # L2.8 against an independent criterion: the diagonal kl crosses the open segment ij
    convex_i, convex_j = orient(l, k, i) > 0, orient(k, l, j) > 0
    assert is_flippable(m, 0) == (convex_i and convex_j)
    assert u.convexity() == (int(math.copysign(1, orient(l, k, i))) if orient(l, k, i) else 0,
                             int(math.copysign(1, orient(k, l, j))) if orient(k, l, j) else 0)
    if convex_i and convex_j:
        r = flip(m, 0)
        assert r.squared_lengths[0] == sqdist(k, l)
        assert r.triangulation.faces == ((2, 3, 1), (3, 2, 0))
        assert r.areas == (Surd(orient(k, l, j) / 2), Surd(orient(l, k, i) / 2))
        assert_faces_valid(r)
    else:
        bad = 0 if not convex_i else 1
        with pytest.raises(NotFlippable, match=f"not strictly convex at vertex {bad} "):
            flip(m, 0)


@SETTINGS
@given(point2, point2, point2, point2)
def test_orientation_reversing_gluing_flips_the_same_way(i, j, k, l):
    sk, sl = orient(i, j, k), orient(i, j, l)
    assume(sk != 0 and sl != 0 and (sk > 0) != (sl > 0))
    pts = [p + (0,) for p in (i, j, k, l)]
    m, mr = hinge(pts), hinge(pts, reverse=True)
    assert mr.triangulation.reversed_gluing(0)
    u, ur = unfold(m, 0), unfold(mr, 0)
    assert (u.sq_il, u.sq_lj, u.new_squared_length, u.new_area_at_i) == \
        (ur.sq_il, ur.sq_lj, ur.new_squared_length, ur.new_area_at_i)
    assert is_flippable(m, 0) == is_flippable(mr, 0)
    if is_flippable(m, 0):
        r, rr = flip(m, 0), flip(mr, 0)

        def by_ends(x):          # the two hinges number their boundary edges differently
            t = x.triangulation
            return {frozenset(t.edge_vertices(e)): x.squared_lengths[e]
                    for e in range(t.n_edges)}

        assert by_ends(r) == by_ends(rr) and r.areas == rr.areas
        assert rr.triangulation.faces == ((2, 3, 1), (3, 2, 0))
        assert_faces_valid(rr)


@SETTINGS
@given(point3, point3, point3, point3)
def test_closed_formulas_match_the_unfolded_hinge_in_r3(i, j, k, l):
    u_ = sub(j, i)
    uu = dot(u_, u_)
    assume(uu != 0)
    kk, ll = sub(k, i), sub(l, i)
    alpha, beta = dot(kk, u_) / uu, dot(ll, u_) / uu
    kp2 = dot(kk, kk) - dot(kk, u_) ** 2 / uu          # squared distances to the line ij
    lp2 = dot(ll, ll) - dot(ll, u_) ** 2 / uu
    assume(kp2 != 0 and lp2 != 0)
    m = hinge([i, j, k, l])
    u = unfold(m, 0)
    # Independent layout: x along ij, y across it (k up, l down):
    # k = (alpha |u|, |k_perp|), l = (beta |u|, -|l_perp|).
    su, sk, sl = sqrt(uu), sqrt(kp2), sqrt(lp2)
    assert u.new_squared_length == (alpha - beta) ** 2 * uu + kp2 + lp2 + 2 * sk * sl
    assert u.new_area_at_i == su * (beta * sk + alpha * sl) / 2
    assert u.new_area_at_j == su * ((1 - alpha) * sl + (1 - beta) * sk) / 2
    assert u.new_area_at_i + u.new_area_at_j == m.areas[0] + m.areas[1]


@FEW
@given(st.lists(st.tuples(*[st.floats(-3, 3, allow_nan=False)] * 3), min_size=4, max_size=4))
def test_new_diagonal_matches_a_numpy_rotation_about_the_hinge(P):
    i, j, k, l = (np.array(p) for p in P)
    n = j - i
    assume(np.linalg.norm(n) > 0.1)
    n = n / np.linalg.norm(n)
    kp = (k - i) - np.dot(k - i, n) * n
    lp = (l - i) - np.dot(l - i, n) * n
    assume(np.linalg.norm(kp) > 0.1 and np.linalg.norm(lp) > 0.1)
    try:
        m = hinge(P)
    except DegenerateFace:
        assume(False)
    # rotate l about the axis ij until l_perp points along -k_perp (Rodrigues)
    theta = math.atan2(np.dot(np.cross(lp, -kp), n), np.dot(lp, -kp))
    rot = (math.cos(theta) * lp + math.sin(theta) * np.cross(n, lp)
           + (1 - math.cos(theta)) * np.dot(n, lp) * n)
    l_unfolded = i + np.dot(l - i, n) * n + rot
    u = unfold(m, 0)
    assert float(u.new_squared_length) == pytest.approx(np.sum((k - l_unfolded) ** 2),
                                                        rel=1e-9, abs=1e-9)
    normal = np.cross(n, kp) / np.linalg.norm(kp)        # x along ij, y towards k
    quad_i = np.dot(np.cross(l_unfolded - i, k - i), normal)
    assert float(u.new_area_at_i) == pytest.approx(quad_i / 2, rel=1e-9, abs=1e-9)


# --- L2.8: the predicate and its error messages -------------------------------------------


def test_L2_8_non_convex_quads_raise_naming_the_vertex():
    z = (0,)
    reflex_i = hinge([(0, 0) + z, (4, 0) + z, (-1, 1) + z, (-1, -1) + z])
    with pytest.raises(NotFlippable, match=r"edge 0 \(0-1\).*vertex 0 .*more than pi"):
        flip(reflex_i, 0)
    reflex_j = hinge([(0, 0) + z, (4, 0) + z, (5, 1) + z, (5, -1) + z])
    with pytest.raises(NotFlippable, match=r"vertex 1 \(the head.*more than pi"):
        flip(reflex_j, 0)
    straight_i = hinge([(0, 0) + z, (4, 0) + z, (-1, 1) + z, (1, -1) + z])
    with pytest.raises(NotFlippable, match=r"vertex 0 .*exactly pi"):
        flip(straight_i, 0)
    assert not any(is_flippable(s, 0) for s in (reflex_i, reflex_j, straight_i))
    with pytest.raises(NotFlippable, match="edge 1 .*boundary edge"):
        flip(reflex_i, 1)
    with pytest.raises(NotFlippable, match="boundary edge"):
        unfold(reflex_i, 1)


def test_L2_8_same_face_on_both_sides_is_not_flippable():
    # X4.2-style: flips on a low tetrahedron end with a vertex of valence 1, whose only
    # edge has one face on both sides (that face has a loop)
    m0 = metric_of([(0, 0, 0), (4, 0, 0), (0, 4, 0), (1, 1, 1)], Triangulation.from_faces(TET))
    m = m0
    for e in (0, 1, 0):
        m = flip(m, e)
    t = m.triangulation
    assert sorted(t.valence(v) for v in range(4))[0] == 1
    one = next(v for v in range(4) if t.valence(v) == 1)
    e1 = next(e for e in range(t.n_edges) if one in t.edge_vertices(e))
    h, tw = t.edge_halfedges(e1)
    assert h // 3 == tw // 3
    u = unfold(m, e1)                              # still unfolds: two copies of one face
    assert u.faces == (h // 3, h // 3) and u.new_squared_length > 0
    assert not is_flippable(m, e1)
    with pytest.raises(NotFlippable, match=f"edge {e1} .*face {h // 3} lies on both sides"):
        flip(m, e1)
    assert not t.is_regular()
    assert_faces_valid(m)
    assert angle_sums(m) == angle_sums(m0)
    assert m.total_area() == m0.total_area()


@SETTINGS
@given(jittered_grids(), choices)
def test_cot_sum_decides_delaunay_and_non_delaunay_edges_flip_to_delaunay(m, picks):
    # L4.11 preview: cot_sum < 0 (angles opposite e sum to more than pi) => flippable,
    # and the flipped edge has cot_sum > 0
    m, _ = random_flips(m, picks, check_raise=False)
    t = m.triangulation
    for e in range(t.n_edges):
        h, tw = t.edge_halfedges(e)
        ang = corner_angle(m.corner_cot(h // 3, (h % 3 + 2) % 3))
        if tw >= 0:
            ang = ang + corner_angle(m.corner_cot(tw // 3, (tw % 3 + 2) % 3))
            assert (cot_sum(m, e) >= 0) == (ang <= pi)
        else:
            assert (cot_sum(m, e) >= 0) == (ang <= pi / 2)
        if tw >= 0 and cot_sum(m, e) < 0:
            assert is_flippable(m, e)
            assert cot_sum(flip(m, e), e) > 0


# --- rationality, invariants, flip back -----------------------------------------------


@SETTINGS
@given(jittered_grids(), choices)
def test_planar_rational_meshes_stay_rational_and_keep_angle_sums_and_area(m, picks):
    before_sums, before_area = angle_sums(m), m.total_area()
    r, done = random_flips(m, picks)
    assert all(type(x) is Fraction for x in r.squared_lengths)
    assert all(a.is_rational() for a in r.areas)
    assert r.total_area() == before_area
    assert_faces_valid(r)
    r.triangulation.validate()
    assert r.triangulation.euler_characteristic() == 1
    if done:
        assert angle_sums(r) == before_sums


@SETTINGS
@given(jittered_grids(), st.integers(0, 1 << 20))
def test_flip_back_restores_lengths_and_areas(m, pick):
    t = m.triangulation
    flippable = [e for e in range(t.n_edges) if is_flippable(m, e)]
    assume(flippable)
    e = flippable[pick % len(flippable)]
    r = flip(m, e)
    assert is_flippable(r, e)                 # the new diagonal of a convex quad
    back = flip(r, e)
    f, g = t.edge_halfedges(e)[0] // 3, t.edge_halfedges(e)[1] // 3
    assert back.squared_lengths == m.squared_lengths
    swap = list(range(t.n_faces))
    swap[f], swap[g] = g, f                    # the two faces trade places
    assert [back.areas[swap[x]] for x in range(t.n_faces)] == list(m.areas)
    def rotations(f):
        return {f, f[1:] + f[:1], f[2:] + f[:2]}

    for x in range(t.n_faces):                 # the same oriented triangles (corners rotated)
        assert back.triangulation.faces[swap[x]] in rotations(t.faces[x])
    for x in range(t.n_edges):
        assert sorted(back.triangulation.edge_vertices(x)) == sorted(t.edge_vertices(x))


@FEW
@given(st.integers(3, 4), st.integers(3, 4),
       st.tuples(st.integers(1, 3), st.integers(-2, 2), st.integers(-2, 2),
                 st.integers(1, 3)),
       st.lists(st.integers(0, 1 << 20), min_size=1, max_size=25))
def test_flat_tori_stay_rational_and_flat(m_, n_, lattice, picks):
    p, q, r_, s = lattice
    assume(p * s - q * r_ != 0)
    m = flat_torus(m_, n_, (Fraction(p), Fraction(q, 2)), (Fraction(r_, 3), Fraction(s)))
    assert all(a.is_rational() for a in m.areas)
    r, done = random_flips(m, picks)
    assert all(type(x) is Fraction for x in r.squared_lengths)
    assert all(a.is_rational() for a in r.areas)
    assert r.total_area() == m.total_area()
    assert_faces_valid(r)
    assert all(x == 2 * pi for x in angle_sums(r))       # flat: 2 pi at every vertex
    assert r.triangulation.euler_characteristic() == 0


def test_flat_torus_flips_reach_double_edges():
    # (no loops here: on a flat surface every vertex has angle sum 2 pi, so valence >= 3;
    # loops and valence 1 come from cone vertices, see the tetrahedron tests)
    m = flat_torus(3, 3, (Fraction(1), Fraction(0)), (Fraction(1, 3), Fraction(1)))
    seen_double = False
    for step in range(40):
        t = m.triangulation
        e = (7 * step + 3) % t.n_edges
        if is_flippable(m, e):
            m = flip(m, e)
            t = m.triangulation
            seen_double |= len({frozenset(t.edge_vertices(x)) for x in range(t.n_edges)}) \
                < t.n_edges
    assert seen_double
    assert_faces_valid(m)
    assert all(x == 2 * pi for x in angle_sums(m))


# --- surfaces in R^3: the field of the face areas -------------------------------------------


def _parities(r, base):
    """Exponent parities of r over ``base`` as a bitmask, or None if r has another factor."""
    mask = 0
    for bit, b in enumerate(base):
        k = 0
        while r % b == 0:
            r //= b
            k += 1
        if k & 1:
            mask |= 1 << bit
    s = math.isqrt(r)
    return mask if s * s == r else None


def _span(vectors):
    """Reduced GF(2) basis {pivot: vector}."""
    basis = {}
    for v in vectors:
        for p, b in basis.items():
            if v >> p & 1:
                v ^= b
        if v:
            p = v.bit_length() - 1
            for q in list(basis):
                if basis[q] >> p & 1:
                    basis[q] ^= v
            basis[p] = v
    return basis


def _in_span(v, basis):
    for p, b in basis.items():
        if v >> p & 1:
            v ^= b
    return v == 0


def _refine(ns):
    """Pairwise coprime integers > 1 such that every n is a product of their powers."""
    out, work = [], [n for n in ns if n > 1]
    while work:
        n = work.pop()
        for x, b in enumerate(out):
            g = math.gcd(n, b)
            if g != 1:
                out.pop(x)
                work += [y for y in (g, b // g, n // g) if y > 1]
                break
        else:
            out.append(n)
    for x, b in enumerate(out):                # 587**2 -> 587: parities need square-free
        while math.isqrt(b) ** 2 == b:
            b = math.isqrt(b)
        out[x] = b
    return out


def assert_in_area_field(m0, m):
    """Every squared length and area of m lies in Q(sqrt(A_f^2) : f faces of m0)."""
    radicands = [r for a in m0.areas for r, _ in a.terms() if r != 1]
    base = _refine(radicands)
    basis = _span(_parities(r, base) for r in radicands)
    dim = len(basis)
    for x in list(m.squared_lengths) + list(m.areas):
        x = Surd(x)
        assert x.n_terms <= 2 ** dim
        for r, _ in x.terms():
            v = _parities(r, base)
            assert v is not None and _in_span(v, basis), f"sqrt({r}) outside the area field"


R3 = {"tetrahedron": surfaces.tetrahedron, "octahedron": surfaces.octahedron,
      "icosahedron": surfaces.icosahedron, "mobius": lambda: surfaces.mobius_strip(3)}


@FEW
@given(st.sampled_from(sorted(R3)), st.lists(st.integers(0, 1 << 20), min_size=1, max_size=8),
       st.lists(st.integers(-2, 2), min_size=36, max_size=36))
def test_meshes_in_r3_stay_in_the_field_of_their_face_areas(name, picks, jitter):
    s = R3[name]()
    pts = [tuple(x + Fraction(jitter[(3 * v + c) % 36], 13) for c, x in enumerate(p))
           for v, p in enumerate(s.positions)]
    try:
        m0 = s.with_positions(pts).metric()
    except DegenerateFace:
        assume(False)
    r, done = random_flips(m0, picks)
    assert_in_area_field(m0, r)
    assert_faces_valid(r)
    assert r.total_area() == m0.total_area()
    e = next(e for e in range(r.triangulation.n_edges) if is_flippable(r, e))
    back = flip(flip(r, e), e)                     # flip back: the same numbers again
    assert back.squared_lengths == r.squared_lengths
    h, tw = r.triangulation.edge_halfedges(e)
    f, g = h // 3, tw // 3
    assert (back.areas[f], back.areas[g]) == (r.areas[g], r.areas[f])   # faces trade places
    assert [a for x, a in enumerate(back.areas) if x not in (f, g)] == \
        [a for x, a in enumerate(r.areas) if x not in (f, g)]
    for v, (a, b) in enumerate(zip(angle_sums(m0), angle_sums(r))):
        assert a == b, f"angle sum at vertex {v} changed"


def test_term_limit_guard_raises_a_clear_error():
    s = surfaces.icosahedron()
    pts = [tuple(x + Fraction((3 * v + c) % 5 - 2, 17) for c, x in enumerate(p))
           for v, p in enumerate(s.positions)]
    m = s.with_positions(pts).metric()
    with limits(term_limit=2):
        with pytest.raises(TermLimitExceeded, match=r"edge \d+.*more than the term limit 2"):
            for step in range(200):
                e = (11 * step + 5) % m.triangulation.n_edges
                if is_flippable(m, e):
                    m = flip(m, e)


# --- non-regular and non-orientable triangulations ---------------------------------------------


@SETTINGS
@given(st.sampled_from(["regular", "corner", "scalene"]),
       st.lists(st.integers(0, 1 << 20), min_size=1, max_size=16))
def test_L2_8_repeated_flips_on_non_regular_tetrahedron_triangulations(kind, picks):
    t = Triangulation.from_faces(TET)
    if kind == "regular":
        m = PiecewiseFlatSurface(t, [1] * 6)
    elif kind == "corner":
        m = surfaces.tetrahedron().metric()
    else:
        m = metric_of([(0, 0, 0), (3, 0, 0), (1, 2, 0), (1, 1, 2)], t)
    sums, area = angle_sums(m), m.total_area()
    r, done = random_flips(m, picks)
    event(f"regular after the flips: {r.triangulation.is_regular()}")
    assert_faces_valid(r)
    r.triangulation.validate()
    assert r.total_area() == area
    assert angle_sums(r) == sums


@FEW
@given(st.sampled_from(["klein bottle", "projective plane", "mobius"]),
       st.lists(st.integers(0, 1 << 20), min_size=1, max_size=12))
def test_flips_across_orientation_reversing_gluings(name, picks):
    if name == "mobius":
        m = surfaces.mobius_strip(4).metric()
    else:
        t = surfaces.klein_bottle() if name == "klein bottle" else surfaces.projective_plane()
        m = PiecewiseFlatSurface(t, [1] * t.n_edges)          # equilateral
    assert any(m.triangulation.reversed_gluing(h) for h in range(m.triangulation.n_halfedges))
    sums, area = angle_sums(m), m.total_area()
    r, done = random_flips(m, picks)
    assert_faces_valid(r)
    r.triangulation.validate()
    assert r.triangulation.classify() == m.triangulation.classify()
    assert r.total_area() == area
    assert angle_sums(r) == sums


def test_flips_of_orientation_reversing_gluings_on_an_equilateral_klein_bottle():
    t = surfaces.klein_bottle()
    m0 = m = PiecewiseFlatSurface(t, [1] * t.n_edges)
    sums = angle_sums(m0)
    flipped = 0
    for e in range(t.n_edges):
        if m.triangulation.reversed_gluing(m.triangulation.edge_halfedges(e)[0]) \
                and is_flippable(m, e):
            m = flip(m, e)
            flipped += 1
    assert flipped >= 3
    assert_faces_valid(m)
    m.triangulation.validate()
    assert m.triangulation.classify().name == "Klein bottle"
    assert angle_sums(m) == sums and all(x == 2 * pi for x in sums)
    assert m.total_area() == m0.total_area() == sqrt(3) * Fraction(t.n_faces, 4)


# --- X2.5 -------------------------------------------------------------------------------------


def test_X2_5_regular_tetrahedron_flip():
    s = regular_tetrahedron_flip()
    t = s.triangulation
    assert s.squared_lengths[0] == 3 and sqrt(s.squared_lengths[0]) == sqrt(3)
    assert not sqrt(s.squared_lengths[0]).is_rational()
    # a valid intrinsic triangulation of the same surface
    assert_faces_valid(s)
    t.validate()
    assert all(x == pi for x in angle_sums(s))
    assert s.total_area() == sqrt(3)
    assert t.classify().name == "sphere"
    # its combinatorics: regular, not strongly regular
    assert t.is_regular() and not t.is_strongly_regular()
    assert [t.valence(v) for v in range(4)] == [2, 2, 4, 4]
    vertex_sets = sorted(sorted(f) for f in t.faces)
    assert vertex_sets == [[0, 2, 3], [0, 2, 3], [1, 2, 3], [1, 2, 3]]
    between_2_3 = [e for e in range(t.n_edges) if set(t.edge_vertices(e)) == {2, 3}]
    assert len(between_2_3) == 2
    # why no polyhedron in R^3 realises it: straight edges between the same two points
    # have the same length, but these two have lengths 1 and sqrt(3)
    assert sorted(s.squared_lengths[e] for e in between_2_3) == [1, 3]


def test_X2_5_every_edge_of_a_regular_tetrahedron_flips_to_sqrt3():
    # from coordinates: the regular tetrahedron inscribed in the cube [-1, 1]^3 (edge^2 = 8)
    pts = [(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)]
    m = metric_of(pts, Triangulation.from_faces(TET))
    for e in range(6):
        assert is_flippable(m, e)
        r = flip(m, e)
        assert r.squared_lengths[e] == 24                 # 3 * 8
        assert not r.triangulation.is_strongly_regular()
        assert_faces_valid(r)


def test_flipped_surfaces_pass_the_validating_constructor():
    # flips build surfaces without re-validation; the public constructor (which
    # checks every length and takes irrational squared lengths as Surds) agrees
    cases = [(surfaces.tetrahedron().metric(), [0, 3, 1, 0]),     # irrational lengths appear
             (surfaces.grid(2, 2).metric(), [2, 5, 8, 2])]
    for m, edges in cases:
        for e in edges:
            if is_flippable(m, e):
                m = flip(m, e)
        checked = PiecewiseFlatSurface(m.triangulation, m.squared_lengths, m.areas)
        assert checked.squared_lengths == m.squared_lengths and checked.areas == m.areas
    assert any(isinstance(x, Surd) for x in flip(surfaces.tetrahedron().metric(), 3)
               .squared_lengths)


def test_flip_accepts_a_polyhedral_surface():
    g = surfaces.grid(1, 1)
    assert flip(g, 2).squared_lengths == flip(g.metric(), 2).squared_lengths
    assert cot_sum(g, 0) == 1                          # boundary edge: cot of 45 degrees


@given(st.sampled_from(["tetrahedron", "cube", "grid", "octahedron"]), st.integers(0, 1 << 16))
def test_L2_8_structural_property_on_constructors(name, pick):
    from ddg_oracle.properties.structure import intrinsic_flip_keeps_the_metric
    s = {"tetrahedron": surfaces.tetrahedron, "cube": surfaces.cube, "octahedron": surfaces.octahedron,
         "grid": lambda: surfaces.grid(2, 2)}[name]().metric()
    intrinsic_flip_keeps_the_metric(s, pick % s.triangulation.n_edges)


def test_X2_5_structural_property_on_the_regular_tetrahedron():
    from ddg_oracle.properties.structure import intrinsic_flip_keeps_the_metric
    from ddg_oracle.reference.intrinsic import regular_tetrahedron_flip
    m = regular_tetrahedron_flip()
    for e in range(m.triangulation.n_edges):
        intrinsic_flip_keeps_the_metric(m, e)
    assert not m.triangulation.is_strongly_regular()
