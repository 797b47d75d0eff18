"""Chapter 4 checked beyond examples: properness of h and l (L4.20 / C4.13), termination of
the flip algorithm by the decreasing quantity of its proof (T4.12 / A4.13 / C4.19),
uniqueness of the tessellation from every start (T4.5 / T4.7) and independence of the
Laplace-Beltrami operator from the Delaunay triangulation over *all* of them (D4.8 / R4.9).

Properness and termination are counted exactly on a surface whose triangulations are known:
the square torus R^2 / Z^2 with one vertex.  Its geodesic triangulations are the
*superbases* {x, y, x + y} of Z^2 (det(x, y) = +-1): two triangles, three edges (x, y and
the diagonal), area 1, h(T) = 4 (|x|^2 + |y|^2 + |x + y|^2) (D4.7: each triangle has
(a^2 + b^2 + c^2) / (1/2)).  Flipping the edge z of {x, y, z} (x + y + z = 0) gives
{x, y, x - y} (the other diagonal of the parallelogram spanned by x and y).  The tests
enumerate every superbase below a bound by integer arithmetic, independently of the
reference, and compare with what the reference's flips and harmonic index do.

Independence of the Laplace-Beltrami operator: on the cube (six square cells: 2^6 Delaunay
triangulations) and on a doubled cocircular hexagon (two hexagonal cells: Catalan(4)^2 =
196 Delaunay triangulations), every Delaunay triangulation is reached by flipping ties
(edges with opposite angles summing to pi), counted, and each gives the same operator.
"""

from collections import deque
from fractions import Fraction
from math import isqrt
import random

from hypothesis import given, settings
from hypothesis import strategies as st

from ddg_oracle.reference import surfaces
from ddg_oracle.reference.combinatorics import Triangulation
from ddg_oracle.reference.delaunay import (delaunay_tessellation_edges, flip_to_delaunay,
                                           harmonic_index, is_delaunay, laplace_beltrami)
from ddg_oracle.reference.exact import Surd
from ddg_oracle.reference.intrinsic import cot_sum, flip, is_flippable
from ddg_oracle.reference.laplacian import cotan_laplacian, cotan_weights
from ddg_oracle.reference.metric import PiecewiseFlatSurface
from ddg_oracle.reference.triangulations import cube_belt_twist

# --- the square torus with one vertex ---------------------------------------------------------


def _line(v):
    """A lattice line +-v by its representative with a positive first nonzero coordinate."""
    return v if (v[0] > 0 or (v[0] == 0 and v[1] > 0)) else (-v[0], -v[1])


def _norm2(v):
    return v[0] * v[0] + v[1] * v[1]


def _h(T):
    """h of the superbase T (three lines): 4 (|x|^2 + |y|^2 + |z|^2), an integer."""
    return 4 * sum(_norm2(v) for v in T)


def superbases(bound_h=None, bound_l2=None):
    """Every triangulation of the one-vertex square torus with h <= bound_h and / or
    longest squared edge <= bound_l2: a finite search, since each |v|^2 is at most the
    bound (|v|^2 <= h / 4 and |v|^2 <= l^2)."""
    r2 = min(b for b in (bound_h // 4 if bound_h is not None else None, bound_l2) if b is not None)
    r = isqrt(r2)
    vecs = [(a, b) for a in range(-r, r + 1) for b in range(-r, r + 1) if 0 < a * a + b * b <= r2]
    out = set()
    for x in vecs:
        for y in vecs:
            if x[0] * y[1] - x[1] * y[0] != 1:
                continue
            T = frozenset(_line(v) for v in (x, y, (x[0] + y[0], x[1] + y[1])))
            if (bound_h is None or _h(T) <= bound_h) and (
                    bound_l2 is None or max(map(_norm2, T)) <= bound_l2):
                out.add(T)
    return out


def _flips(T):
    """The three superbases one flip away from T."""
    out = []
    for z in T:
        x, y = sorted(T - {z})
        s, d = _line((x[0] + y[0], x[1] + y[1])), _line((x[0] - y[0], x[1] - y[1]))
        out.append(frozenset({x, y, d if s == z else s}))
    return out


DELAUNAY = {frozenset({(1, 0), (0, 1), (1, 1)}), frozenset({(1, 0), (0, 1), (1, -1)})}


def _reachable(inside):
    """Superbases reached from the Delaunay ones by flips through ``inside`` only."""
    seen, queue = set(DELAUNAY), deque(DELAUNAY)
    while queue:
        for U in _flips(queue.popleft()):
            if U not in seen and inside(U):
                seen.add(U)
                queue.append(U)
    return seen


def torus_surface(T):
    """The reference surface of the superbase T, with the lattice vector of each edge:
    the unit square's one-vertex triangulation (faces (A, B, C), (A, C, D); edges bottom =
    top, right = left, diagonal) mapped by the unimodular matrix (x y)."""
    for x in T:
        for y in T:
            for sy in (1, -1):
                yy = (sy * y[0], sy * y[1])
                if x[0] * yy[1] - x[1] * yy[0] == 1 and _line((x[0] + yy[0], x[1] + yy[1])) in T:
                    vectors = [x, yy, (x[0] + yy[0], x[1] + yy[1])]
                    t = Triangulation([[0, 0, 0], [0, 0, 0]],
                                      [(0, 4, False), (1, 5, False), (2, 3, False)])
                    return PiecewiseFlatSurface(t, [_norm2(v) for v in vectors]), vectors
    raise AssertionError(f"{T} is not a superbase")


def test_L4_20_C4_13_sublevel_sets_are_finite_and_all_reached_from_delaunay():
    """L4.20 / C4.13 on the one-vertex torus: every sublevel set {h <= c} and {l^2 <= L} is
    finite (enumerated exactly), the reference's h is 4 (|x|^2 + |y|^2 + |x + y|^2) on each
    member with l(T)^2 <= h(T) A, and each sublevel set is exactly what flips from the Delaunay
    triangulations reach without leaving it (so every triangulation below c flips down to
    Delaunay inside it: C4.19 and T4.12 on the whole set).  The sets grow without bound (X4.4)."""
    sizes = []
    for c in (16, 32, 64, 100, 160, 240, 400):
        below = superbases(bound_h=c)
        assert _reachable(lambda U: _h(U) <= c) == below
        for T in below:
            m, _ = torus_surface(T)
            h = harmonic_index(m)
            assert h == _h(T) and m.total_area() == 1
            assert max(m.squared_lengths) <= h * m.total_area()            # l^2 <= h A (ER-18)
        sizes.append(len(below))
    assert sizes[0] == 2 and all(a < b for a, b in zip(sizes, sizes[1:]))
    for L in (2, 5, 10, 25, 50):
        short = superbases(bound_l2=L)
        assert _reachable(lambda U: max(map(_norm2, U)) <= L) == short
        assert superbases(bound_h=4 * L) >= {T for T in short if _h(T) <= 4 * L}
        assert all(T in short for T in superbases(bound_h=4 * L) if max(map(_norm2, T)) <= L)


def test_T4_12_every_start_below_a_bound_flips_down_by_the_proofs_quantity():
    """T4.12 / A4.13 / C4.19 / T4.5 from every triangulation with h <= 400 of the one-vertex
    torus (54 of them): the reference's flips, mirrored on the lattice vectors, keep every
    edge length right, h (from the lattice, not the reference) strictly decreases at every
    flip and equals
    the log's h_before / h_after, the number of flips is at most the number of triangulations
    with a smaller h (the termination argument), and every run ends in a Delaunay
    triangulation whose tessellation is the unit square (one cell, two edges of length 1)."""
    c = 400
    starts = superbases(bound_h=c)
    smaller = {T: sum(_h(U) < _h(T) for U in starts) for T in starts}
    for T in starts:
        m, vectors = torus_surface(T)
        d, log = flip_to_delaunay(m)
        cur, h = m, _h(T)
        for rec in log:
            e = rec.edge
            u, w = (vectors[k] for k in range(3) if k != e)
            plus, minus = (u[0] + w[0], u[1] + w[1]), (u[0] - w[0], u[1] - w[1])
            vectors[e] = minus if _line(plus) == _line(vectors[e]) else plus
            cur = flip(cur, e)
            assert list(cur.squared_lengths) == [_norm2(v) for v in vectors]
            h_after = _h(frozenset(map(_line, vectors)))
            assert (rec.h_before, rec.h_after) == (h, h_after) and h_after < h
            h = h_after
        assert len(log) <= smaller[T]
        assert frozenset(map(_line, vectors)) in DELAUNAY and is_delaunay(d)
        kept = delaunay_tessellation_edges(d)
        assert sorted(d.squared_lengths[e] for e in kept) == [1, 1]


# --- termination on drawn surfaces, h recomputed independently ------------------------------


def _independent_h(m):
    """h(T) = sum over faces of (a^2 + b^2 + c^2) / A(face) (D4.7) from the surface's exact
    squared lengths and face areas, not by the reference's harmonic index; where the areas
    are rational, A is checked against Heron's formula (16 A^2 = 2 (a2 b2 + b2 c2 + c2 a2) -
    a2^2 - b2^2 - c2^2)."""
    t = m.triangulation
    total = Surd(0)
    for f in range(t.n_faces):
        a2, b2, c2 = (m.squared_lengths[t.edge_of(3 * f + k)] for k in range(3))
        area = m.area(f)
        assert 16 * area * area == 2 * (a2 * b2 + b2 * c2 + c2 * a2) - a2 * a2 - b2 * b2 - c2 * c2
        total = total + (a2 + b2 + c2) / area
    return total


def _drawn_start(kind, seed):
    rng = random.Random(seed)
    if kind == "belt":                        # the long edges of Example 4.3
        *_, m = cube_belt_twist(rng.randint(4, 24))
        return m
    base = {"tetrahedron": surfaces.tetrahedron, "octahedron": surfaces.octahedron,
            "cube": surfaces.cube, "icosahedron": surfaces.icosahedron,
            "torus": lambda: surfaces.torus(4, 3)}[kind]()
    pts = [tuple(x + Fraction(rng.randint(-2, 2), 9) for x in p) for p in base.positions]
    m = base.with_positions(pts).metric() if kind in ("cube", "torus") else base.metric()
    for _ in range(30):
        e = rng.randrange(m.triangulation.n_edges)
        if is_flippable(m, e):
            m = flip(m, e)
    return m


@settings(max_examples=12, deadline=None, database=None)
@given(st.sampled_from(["belt", "tetrahedron", "octahedron", "cube", "icosahedron", "torus"]),
       st.integers(0, 1 << 20))
def test_T4_12_h_decreases_strictly_at_every_flip_on_drawn_surfaces(kind, seed):
    """T4.12 / C4.19 at every flip of every drawn run (closed polyhedra with random flips,
    jittered, and the cube's belt twisted into long edges): h recomputed from the lengths by
    Heron's formula equals the log's h_before / h_after and strictly decreases, so no
    triangulation is visited twice."""
    m = _drawn_start(kind, seed)
    d, log = flip_to_delaunay(m)
    cur, h = m, _independent_h(m)
    for rec in log:
        assert rec.h_before == h
        cur = flip(cur, rec.edge)
        h_after = _independent_h(cur)
        assert rec.h_after == h_after and h_after < h
        h = h_after
    assert is_delaunay(d) and cur.squared_lengths == d.squared_lengths


# --- the Laplace-Beltrami operator over all Delaunay triangulations -------------------------


def _face_key(m):
    """A triangulation of the surface as the set of its oriented faces (vertex triples up to
    rotation): distinguishes the diagonals of two cells with the same end points."""
    def canon(f):
        k = f.index(min(f))
        return f[k:] + f[:k]
    return frozenset(canon(tuple(f)) for f in m.triangulation.faces)


def _all_delaunay_triangulations(m):
    """Every Delaunay triangulation reached from the Delaunay ``m`` by flipping ties (interior
    edges with cot alpha + cot beta = 0: opposite angles summing to pi)."""
    seen = {_face_key(m): m}
    queue = deque([m])
    while queue:
        cur = queue.popleft()
        t = cur.triangulation
        for e in range(t.n_edges):
            if t.is_boundary_edge(e) or cot_sum(cur, e) != 0:
                continue
            nxt = flip(cur, e)
            k = _face_key(nxt)
            if k not in seen:
                seen[k] = nxt
                queue.append(nxt)
    return list(seen.values())


def _doubled_hexagon():
    """Two copies of a cocircular hexagon (integer points on the circle of radius 5) glued
    along the boundary: a flat sphere with six cone points whose Delaunay tessellation is the
    two hexagons.  Top fan from vertex 0, bottom (reversed) fan from vertex 1: no diagonal
    is shared."""
    P = [(5, 0), (4, 3), (0, 5), (-4, 3), (-5, 0), (0, -5)]
    top = [(0, k, k + 1) for k in range(1, 5)]
    bottom = [(1, (k + 1) % 6, k % 6) for k in range(2, 6)]
    t = Triangulation.from_faces(top + bottom)
    sq = []
    for e in range(t.n_edges):
        i, j = t.edge_vertices(e)
        sq.append((P[i][0] - P[j][0]) ** 2 + (P[i][1] - P[j][1]) ** 2)
    return PiecewiseFlatSurface(t, sq)


def _check_one_operator(all_delaunay, tessellation_edges):
    L0 = laplace_beltrami(all_delaunay[0])
    for m in all_delaunay:
        assert is_delaunay(m)
        assert cotan_laplacian(m) == L0 == laplace_beltrami(m)
        w = cotan_weights(m)
        t = m.triangulation
        kept = delaunay_tessellation_edges(m)
        assert {frozenset(t.edge_vertices(e)) for e in kept} == tessellation_edges
        assert all((w[e] > 0) == (e in kept) and w[e] >= 0 for e in range(t.n_edges))


def test_D4_8_R4_9_the_cube_all_64_delaunay_triangulations_give_one_operator():
    """The cube with V its 8 vertices: the Delaunay tessellation is the 6 squares, each
    triangulated by either diagonal, 2^6 = 64 Delaunay triangulations, all reached; the cotan
    Laplacian of every one is the same matrix (the Laplace-Beltrami operator), its diagonals
    have weight 0 and the 12 cube edges positive weight."""
    cube = surfaces.cube()
    found = _all_delaunay_triangulations(cube.metric())
    assert len(found) == 64
    p = cube.positions
    edges = {frozenset((i, j)) for i in range(8) for j in range(i)
             if sum((a - b) ** 2 for a, b in zip(p[i], p[j])) == 1}
    assert len(edges) == 12
    _check_one_operator(found, edges)


def test_D4_8_R4_9_a_doubled_cocircular_hexagon_all_196_delaunay_triangulations():
    """Two cocircular hexagonal cells: Catalan(4)^2 = 14^2 = 196 Delaunay triangulations, all
    reached (the diagonals of both cells, same end points, told apart by their faces); one
    operator for all, the 6 hexagon sides the tessellation edges."""
    found = _all_delaunay_triangulations(_doubled_hexagon())
    assert len(found) == 196
    _check_one_operator(found, {frozenset((k, (k + 1) % 6)) for k in range(6)})
