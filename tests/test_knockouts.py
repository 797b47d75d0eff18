"""Public reference functions that a generic wrong version of their result survived in the
reference's tests (benchmarks/knockout.py, docs/knockout.md: the result negated, off by one,
shifted by 1/3, an element dropped, the body skipped, two vertex labels swapped, a face
reversed), or a hand-written one (benchmarks/knockout_hand.py: a realistic mistake in a
function no generic variant fits), or that no reference test called; each test here fails
on that wrong version.  Exact, and on generic inputs (unequal areas, boundary, points in
general position) wherever the function allows."""

import random
import re
from fractions import Fraction
from itertools import combinations

import pytest

from ddg_oracle.reference import planar, rigidity, surfaces
from ddg_oracle.reference.combinatorics import Triangulation
from ddg_oracle.reference.errors import (DegenerateFace, InputError, NonManifoldVertex,
                                         TriangleInequalityViolated)
from ddg_oracle.reference.exact import sqrt
from ddg_oracle.reference.geodesics import root_sum_at_least
from ddg_oracle.reference.metric import PiecewiseFlatSurface, degenerate_face
from ddg_oracle.reference.sparse import SparseMatrix

# --- never called by a reference test -------------------------------------------------------------


def test_root_sum_at_least_against_surds():
    """sqrt(b) + sqrt(c) >= sqrt(a), against the exact Surd comparison, equality included
    (9 = (2 + 1)^2, 8 = (sqrt 2 + sqrt 2)^2) and on both sides of it."""
    cases = [(9, 4, 1), (8, 2, 2), (Fraction(9, 4), 1, Fraction(1, 4)), (10, 4, 1),
             (Fraction(801, 100), 2, 2), (0, 0, 0), (1, 0, 0), (3, 1, 1), (4, 1, 1)]
    rng = random.Random(44)
    cases += [tuple(Fraction(rng.randint(0, 60), rng.randint(1, 7)) for _ in range(3))
              for _ in range(60)]
    got = [root_sum_at_least(a, b, c) for a, b, c in cases]
    want = [sqrt(b) + sqrt(c) >= sqrt(a) for a, b, c in cases]
    assert got == want
    assert True in got and False in got


def _points(seed, n=8):
    rng = random.Random(seed)
    pts = set()
    while len(pts) < n:
        pts.add((Fraction(rng.randint(-20, 20), rng.randint(1, 5)),
                 Fraction(rng.randint(-20, 20), rng.randint(1, 5))))
    return sorted(pts)


def test_lifted_hull_facets_are_the_empty_circle_triangles():
    """R4.2: the lifted triangle spans a supporting plane of the lifted hull iff no other
    point lies strictly inside the planar triangle's circumcircle (in_circle times the
    orientation), on random rational points and on four cocircular points."""
    seen = set()
    for pts in [_points(1), _points(2), _points(3),
                [(0, 0), (2, 0), (2, 2), (0, 2), (1, Fraction(1, 2))],
                [(1, 0), (0, 1), (-1, 0), (0, -1), (Fraction(3, 5), Fraction(4, 5))]]:
        for i, j, k in combinations(range(len(pts)), 3):
            o = planar.orientation(pts[i], pts[j], pts[k])
            if o == 0:
                continue
            empty = all(o * planar.in_circle(pts[i], pts[j], pts[k], d) <= 0
                        for n, d in enumerate(pts) if n not in (i, j, k))
            assert planar.is_lifted_hull_facet(pts, i, j, k) == empty, (pts, i, j, k)
            seen.add(empty)
    assert seen == {True, False}


def test_sparse_diagonal_holds_its_values_on_the_diagonal():
    values = [Fraction(1, 3), 0, -2, Fraction(7, 5)]
    m = SparseMatrix.diagonal(values)
    assert m.shape == (4, 4)
    assert m.entries() == [(i, i, v) for i, v in enumerate(values) if v]
    assert m.to_dense_floats() == [[float(values[i]) if i == j else 0.0 for j in range(4)]
                                   for i in range(4)]


def test_from_lengths_squares_each_edge_length():
    """A 3-4-5 triangle and a 5-5-6 one glued along an edge (unequal areas, boundary): the
    squared lengths are the squares of the given ones, edge by edge, and the areas those
    of the two triangles."""
    t = Triangulation.from_faces([(0, 1, 2), (0, 2, 3)])
    lengths = [Fraction(0)] * t.n_edges
    want = {}
    for (u, v), x in {(0, 1): 3, (1, 2): 4, (0, 2): 5, (2, 3): 5, (0, 3): 6}.items():
        e = next(e for e in range(t.n_edges) if set(t.edge_vertices(e)) == {u, v})
        lengths[e] = x
        want[e] = Fraction(x * x)
    s = PiecewiseFlatSurface.from_lengths(t, lengths)
    for h in range(3 * t.n_faces):
        assert s.squared_length(h) == want[t.edge_of(h)]
    assert s.area(0) == 6 and s.area(1) == 12      # 3-4-5 right; 5-5-6 isosceles, height 4


# --- combinatorics ---------------------------------------------------------------------------


def _gluings(t):
    """(faces, n_vertices, gluings) of ``t``: its pickled defining data."""
    return t.__reduce__()[1]


def test_validate_raises_on_each_broken_invariant():
    """Triangulation.validate re-checks the tables: built unchecked (``_trusted``, what the
    operations use) from a valid triangulation's data with one thing broken, each raises an
    InputError naming it; the valid data passes."""
    t = Triangulation.from_faces([(0, 1, 2), (0, 2, 3), (0, 3, 4), (3, 2, 5)])  # a disk
    faces, n, gl = _gluings(t)
    assert Triangulation._trusted(faces, n, gl).validate() is None
    e = next(k for k, (a, b, r) in enumerate(gl) if b >= 0)
    a, b, r = gl[e]
    broken = {
        "endpoints": gl[:e] + ((a, b, not r),) + gl[e + 1:],         # reversed flag flipped
        "twice": gl + ((a, -1, False),),                              # a halfedge in 2 edges
        "missing": gl[:e] + gl[e + 1:],                               # two halfedges in none
    }
    for what, g in broken.items():
        with pytest.raises(InputError, match=r"halfedge|edge"):
            Triangulation._trusted(faces, n, g).validate()
    # a bowtie: vertex 0 in two fans
    bow = Triangulation._trusted(((0, 1, 2), (0, 3, 4)), 5,
                                 tuple((h, -1, False) for h in range(6)))
    with pytest.raises(NonManifoldVertex):
        bow.validate()


def test_connected_sum_keeps_a_and_numbers_b_as_documented():
    """CS's documented numbering (its last two vertex labels swapped survived: the tests
    read only the sum's topology): the faces of ``a`` without ``face_a`` first, unchanged;
    then those of ``b`` without ``face_b``, renamed by one map read off them position by
    position, which sends ``face_b = (y0, y1, y2)`` to ``(x0, x2, x1)`` and ``b``'s other
    vertices to ``n_a, n_a + 1, ...`` in increasing order."""
    from ddg_oracle.reference.combinatorics import connected_sum
    cases = [(surfaces.torus(3, 4).triangulation, surfaces.icosahedron().triangulation, 5, 7),
             (surfaces.octahedron().triangulation, surfaces.genus_surface(2).triangulation,
              -1, -1),
             (surfaces.projective_plane(), surfaces.klein_bottle(3, 4), 2, 9),
             (Triangulation.from_faces([(0, 1, 2), (0, 2, 3), (0, 3, 1), (1, 3, 2)]),
              surfaces.cube().triangulation, 3, 0)]
    for a, b, fa, fb in cases:
        s = connected_sum(a, b, fa, fb)
        fa, fb = fa % a.n_faces, fb % b.n_faces
        kept_a = [f for g, f in enumerate(a.faces) if g != fa]
        kept_b = [f for g, f in enumerate(b.faces) if g != fb]
        assert list(s.faces[:len(kept_a)]) == kept_a
        assert s.n_faces == len(kept_a) + len(kept_b)
        m = {}
        for fb_, fs in zip(kept_b, s.faces[len(kept_a):]):
            for y, z in zip(fb_, fs):
                assert m.setdefault(y, z) == z, (y, z, m[y])
        (x0, x1, x2), (y0, y1, y2) = a.faces[fa], b.faces[fb]
        assert (m[y0], m[y1], m[y2]) == (x0, x2, x1)
        others = sorted(set(m) - {y0, y1, y2})
        assert others == [v for v in range(b.n_vertices) if v not in (y0, y1, y2)]
        assert [m[v] for v in others] == list(range(a.n_vertices, s.n_vertices))


def test_klein_bottle_is_the_twisted_grid():
    """surfaces.klein_bottle(m, n) against its docstring's grid (its last two vertex
    labels swapped, or its last face reversed, survived: the tests read only its
    topology): the edges are exactly the grid steps (i, j) -> (i + 1, j), (i, j + 1),
    (i + 1, j + 1) with vertex (i, j) = i n + j mod n and (m, j) ~ (0, -j); the faces are
    oriented as the grid is, so the only gluings reversing orientation are those of the
    circle i = 0 (= i = m) along which the grid is glued with its flip."""
    for m, n in [(3, 3), (4, 5), (5, 4), (3, 6)]:
        k = surfaces.klein_bottle(m, n)

        def vid(i, j):
            if i == m:
                i, j = 0, -j
            return i * n + j % n
        steps = {frozenset((vid(i, j), vid(i + di, j + dj)))
                 for i in range(m) for j in range(n) for di, dj in ((1, 0), (0, 1), (1, 1))}
        edges = [frozenset(k.edge_vertices(e)) for e in range(k.n_edges)]
        assert len(set(edges)) == len(edges) == 3 * m * n
        assert set(edges) == steps
        assert k.n_vertices == m * n and k.n_faces == 2 * m * n
        flipped = {e for e in range(k.n_edges) if k.reversed_gluing(k.edge_halfedges(e)[0])}
        circle = {e for e in range(k.n_edges) if all(v < n for v in k.edge_vertices(e))}
        assert flipped == circle and len(circle) == n


# --- planar and rigidity -----------------------------------------------------------------------


def test_quad_tessellation_faces_are_orthogonal_kites_crossing_iff_acute():
    """R4.1 on random rational points: every face's Voronoi segment q r is orthogonal to
    its Delaunay edge and equidistant from both ends (recomputed from q, r and the points),
    and ``crossing == acute`` for every face (the notes' identity), both values seen."""
    seen = set()
    for seed in (5, 6, 7):
        pts = _points(seed, 9)
        faces = planar.quad_tessellation_faces(pts)
        assert faces
        for f in faces:
            (i, j), (q, r) = f["edge"], f["voronoi"]
            pi, pj = pts[i], pts[j]
            d = (pj[0] - pi[0], pj[1] - pi[1])
            assert (q[0] - r[0]) * d[0] + (q[1] - r[1]) * d[1] == 0
            for c in (q, r):
                assert (c[0] - pi[0]) ** 2 + (c[1] - pi[1]) ** 2 == \
                    (c[0] - pj[0]) ** 2 + (c[1] - pj[1]) ** 2
            assert f["orthogonal"] and f["kite"] and f["bisected"]
            assert f["crossing"] == f["acute"], f
            seen.add(f["acute"])
    assert seen == {True, False}


def test_rigidity_matrix_rows_are_the_edge_vectors():
    """Row ij of the rigidity matrix holds p_i - p_j at vertex i and p_j - p_i at vertex j
    (nothing else), on a jittered octahedron (no two edges alike)."""
    s0 = surfaces.octahedron()
    rng = random.Random(3)
    s = s0.with_positions([[Fraction(c) + Fraction(rng.randint(-9, 9), 97) for c in p]
                           for p in s0.positions])
    t = s.triangulation
    m = rigidity.rigidity_matrix(s)
    assert sorted(m) == list(range(t.n_edges))
    for e in range(t.n_edges):
        i, j = t.edge_vertices(e)
        want = {}
        for k in range(3):
            d = s.positions[i][k] - s.positions[j][k]
            if d:
                want[3 * i + k], want[3 * j + k] = d, -d
        assert m[e] == want, e


def test_convex_hull_keeps_the_given_points_as_its_vertices():
    """surfaces.convex_hull with its last vertex moved by 1/3 survived: the tests read its
    faces and orientations from the input points, never the surface's positions.  The
    hull's vertices are the given points, in their order, exactly, and every face has all
    other vertices strictly on its inner side (X1.1 / X1.2)."""
    from ddg_oracle.reference.polyhedral import orientation3d
    rng = random.Random(11)
    pts = [(0, 0, 0), (4, 0, 1), (1, 5, 0), (1, 1, 4), (2, 2, -3)]
    pts += [(Fraction(rng.randint(-9, 9), 7), 6, Fraction(rng.randint(1, 9), 5))]
    hull = surfaces.convex_hull(pts)
    assert hull.positions == tuple(tuple(Fraction(x) for x in p) for p in pts)
    for f in hull.triangulation.faces:
        a, b, c = (hull.positions[v] for v in f)
        assert all(orientation3d(a, b, c, x) < 0
                   for v, x in enumerate(hull.positions) if v not in f)


def test_circumdisk_is_the_disk_of_the_face_asked_for():
    """Knockout gap (``circumdisk`` ``value``, the disk's ``face`` + 1, survived every
    reference test): the disk names the face it was asked for, whose own corners are on its
    circle, on every face of three closed surfaces (one with non-empty disks)."""
    from ddg_oracle.reference.empty_disks import circumdisk
    for s in (surfaces.octahedron(), surfaces.cube(), surfaces.torus(3, 3)):
        m = s.metric()
        for f in range(m.triangulation.n_faces):
            d = circumdisk(m, f)
            assert d.face == f
            assert f in d.cell_faces


def test_minimal_surface_iteration_returns_its_surfaces_areas_and_certificates():
    """Knockout gap (``minimal_surface_iteration`` ``value`` and ``last``: the last surface
    moved by 1/3, the last certificate changed, survived every reference test, which read
    only the certificates' verdicts and the areas' order): each surface is the previous
    one's exact step rounded to ``bits`` fractional bits, each area is its surface's, each
    certificate is that of the step from the previous surface."""
    from ddg_oracle.reference.minimal import (area_decrease_certificate,
                                              minimal_surface_iteration, minimal_surface_step)
    from ddg_oracle.reference.polyhedral import PolyhedralSurface
    s = PolyhedralSurface.from_arrays(
        [(0, 0, 2), (2, 0, 0), (1, 2, 1), (-1, 2, 0), (-2, 0, 1), (-1, -2, 0), (1, -2, 1)],
        [(0, 1 + t, 1 + (t + 1) % 6) for t in range(6)])
    bits, steps = 20, 2
    run = minimal_surface_iteration(s, steps, bits=bits)
    assert len(run.surfaces) == len(run.areas) == steps + 1 and len(run.certificates) == steps
    assert run.surfaces[0].positions == s.positions
    for before, after, cert in zip(run.surfaces, run.surfaces[1:], run.certificates):
        exact = minimal_surface_step(before)
        for p, q in zip(after.positions, exact):
            for x, y in zip(p, q):
                assert (x * 2 ** bits).denominator == 1 and abs(x - y) <= Fraction(1, 2 ** (bits + 1))
        assert cert == area_decrease_certificate(before, exact)
    for surface, area in zip(run.surfaces, run.areas):
        assert area == surface.metric().total_area()


# --- hand-written wrong versions (benchmarks/knockout_hand.py) ---------------------------------
# The functions no generic variant fits (results that are strings, exceptions, context
# managers, scipy matrices, a generator; or never called): each test below fails on a
# hand-written mistake that the reference tests let through.


def _edge_lengths(t, by_pair):
    """One length per edge of ``t`` from ``{(u, v): length}``."""
    out = [None] * t.n_edges
    for (u, v), x in by_pair.items():
        out[next(e for e in range(t.n_edges) if set(t.edge_vertices(e)) == {u, v})] = x
    return out


def test_from_lengths_takes_floats_exactly_and_refuses_lengths_not_positive():
    """PiecewiseFlatSurface.from_lengths squares each length exactly: a float length's
    square is its exact value's, ``Fraction(x) ** 2`` (not the rounded ``x * x``); a length
    <= 0 is refused even where its square would make valid faces (squaring hides the sign)."""
    t = Triangulation.from_faces([(0, 1, 2), (0, 2, 3)])
    pairs = {(0, 1): 0.3, (1, 2): 0.4, (0, 2): 0.6, (2, 3): 0.7, (0, 3): 0.9}
    s = PiecewiseFlatSurface.from_lengths(t, _edge_lengths(t, pairs))
    for (u, v), x in pairs.items():
        e = next(e for e in range(t.n_edges) if set(t.edge_vertices(e)) == {u, v})
        assert s.squared_lengths[e] == Fraction(x) * Fraction(x) != Fraction(x * x)
    for bad in (-0.3, 0):
        with pytest.raises(TriangleInequalityViolated):
            PiecewiseFlatSurface.from_lengths(t, _edge_lengths(t, {**pairs, (0, 1): bad}))


def test_sparse_diagonal_takes_floats_exactly():
    """SparseMatrix.diagonal makes its values exact (floats taken exactly, as every entry
    of a SparseMatrix is a Fraction or a Surd): products with it are exact."""
    values = [0.1, 3, Fraction(1, 3), -2.5, 0.7]
    m = SparseMatrix.diagonal(values)
    x = [3, 5, 7, 11, 13]
    assert m.matvec(x) == [Fraction(v) * k for v, k in zip(values, x)]
    assert m.quadratic_form(x) == sum(Fraction(v) * k * k for v, k in zip(values, x))
    assert all(type(v) is Fraction for _, _, v in m.entries())


def test_degenerate_face_names_the_edge_between_the_coincident_vertices():
    """metric.degenerate_face with positions: for every face of a fan and every pair of its
    corners made coincident, the error names an edge whose end points (read back from the
    triangulation) are those two vertices; without positions, or with distinct collinear
    ones, it names the face and its corners."""
    t = Triangulation.from_faces([(0, 1, 2), (0, 2, 3), (0, 3, 4)])
    base = [(0, 0), (4, 1), (1, 5), (-3, 2), (-2, -4)]
    for f, face in enumerate(t.faces):
        for a, b in combinations(face, 2):
            pos = list(base)
            pos[b] = pos[a]
            err = degenerate_face(t, f, pos)
            assert isinstance(err, DegenerateFace) and "coincident" in str(err)
            e, i, j = map(int, re.match(r"edge (\d+) between vertices (\d+) and (\d+)",
                                        str(err)).groups())
            assert {i, j} == {a, b} == set(t.edge_vertices(e))
        line = list(base)
        line[face[2]] = (2 * line[face[1]][0] - line[face[0]][0],
                         2 * line[face[1]][1] - line[face[0]][1])     # c = 2 b - a
        for err in (degenerate_face(t, f), degenerate_face(t, f, line)):
            assert isinstance(err, DegenerateFace)
            assert f"face {f} {face}" in str(err) and "collinear" in str(err)


def test_limits_restore_the_enclosing_value_and_none_keeps_it():
    """exact.surds.limits nests: leaving a block restores the value before it (the
    enclosing block's, not the default), also when the block raises; ``None`` keeps the
    current value; and the guard is the one in force (a product over it raises)."""
    from ddg_oracle.reference.errors import TermLimitExceeded
    from ddg_oracle.reference.exact.surds import Surd, limits, settings
    before = settings.term_limit
    try:
        with limits(term_limit=8):
            with limits(term_limit=16):
                assert settings.term_limit == 16
            assert settings.term_limit == 8
            with limits():
                assert settings.term_limit == 8
            with pytest.raises(RuntimeError):
                with limits(term_limit=3):
                    raise RuntimeError
            assert settings.term_limit == 8
            x = Surd(1)
            for p in (2, 3, 5):
                x = x * (1 + sqrt(p))                  # 8 terms: allowed
            with pytest.raises(TermLimitExceeded):
                x * (1 + sqrt(7))                      # 16 terms
        assert settings.term_limit == before
    finally:
        settings.term_limit = before


def test_to_scipy_keeps_underflowing_entries_and_rounds_each_entry_once():
    """SparseMatrix.to_scipy: an entry whose float is 0.0 stays a stored entry (its
    position kept), and every entry is its value correctly rounded, checked against
    mpmath's division of numerator by denominator rounded once to 53 bits (large
    numerators and denominators, where dividing two rounded floats is off)."""
    import mpmath
    rng = random.Random(45)
    entries = [(0, 0, Fraction(1, 10 ** 400)), (1, 2, Fraction(-3, 7 * 10 ** 350))]
    entries += [(2 + k // 5, k % 5, Fraction(rng.randrange(2 ** 60, 2 ** 80) * rng.choice((1, -1)),
                                             rng.randrange(2 ** 60, 2 ** 80)))
                for k in range(30)]
    m = SparseMatrix.from_entries((8, 5), entries)
    assert m.nnz == len(entries)
    S = m.to_scipy()
    assert S.shape == (8, 5)
    c = S.tocoo()
    got = {(i, j): x for i, j, x in zip(c.row.tolist(), c.col.tolist(), c.data.tolist())}
    assert len(got) == c.nnz == len(entries)
    for i, j, v in entries:
        assert got[i, j] == float(mpmath.fdiv(v.numerator, v.denominator, prec=53)), (i, j)


def _mp_defect(positions, v, neighbours):
    """2 pi minus the angles at ``v`` between consecutive neighbours, by mpmath (60 digits)."""
    import mpmath
    with mpmath.workdps(60):
        p = [mpmath.mpf(x.numerator) / x.denominator for x in map(Fraction, positions[v])]
        d = [[mpmath.mpf(Fraction(x).numerator) / Fraction(x).denominator - y
              for x, y in zip(positions[w], p)] for w in neighbours]
        total = 0
        for a, b in zip(d, d[1:] + d[:1]):
            dot = sum(x * y for x, y in zip(a, b))
            total += mpmath.acos(dot / mpmath.sqrt(sum(x * x for x in a) * sum(y * y for y in b)))
        return 2 * mpmath.pi - total


def test_vertex_type_decides_tiny_curvature_exactly():
    """curvature.vertex_type by the exact sign of K (D2.2): the apex of a very flat cone
    (|K| ~ 1e-12, below any float tolerance) is elliptic, a very flat saddle hyperbolic,
    as K evaluated by mpmath to 60 digits says; the planar star is flat."""
    from ddg_oracle.reference.curvature import vertex_type
    from ddg_oracle.reference.polyhedral import PolyhedralSurface
    ring = [(5, 0), (3, 4), (0, 5), (-4, 3), (-5, 0), (-3, -4), (0, -5), (4, -3)]
    n = len(ring)
    t = Triangulation.from_faces([(0, 1 + j, 1 + (j + 1) % n) for j in range(n)] +
                                 [(1 + (j + 1) % n, 1 + j, 9) for j in range(n)])  # closed
    seen = set()
    for h in (Fraction(1, 10 ** 6), Fraction(-1, 10 ** 6), Fraction(1, 10 ** 3), 0):
        for saddle in (False, True):
            pos = [(0, 0, 0)] + [(x, y, h * (-1) ** j if saddle else -h)
                                 for j, (x, y) in enumerate(ring)] + [(0, 0, -7)]
            s = PolyhedralSurface(t, pos)
            got = vertex_type(s, 0)
            if h == 0:
                assert got == "flat"
            else:
                k = _mp_defect(pos, 0, [1 + j for j in range(n)])
                assert abs(k) > 1e-40
                assert got == ("elliptic" if k > 0 else "hyperbolic"), (h, saddle, k)
            seen.add(got)
    assert seen == {"elliptic", "flat", "hyperbolic"}


def test_decimal_is_the_value_rounded_with_its_integer_part():
    """ArccotSum.decimal against mpmath (60 digits): the string is ``-?D+.D{digits}``
    (a 0 before the point below 1) and within 0.51 units of its last digit of the value,
    for positive and negative angles below and above 1 and several digit counts."""
    import mpmath
    from ddg_oracle.reference.exact import corner_angle, pi
    with mpmath.workdps(60):
        cases = [(pi / 7, mpmath.pi / 7), (-pi / 7, -mpmath.pi / 7), (-pi, -mpmath.pi),
                 (corner_angle(2), mpmath.acot(2)), (-corner_angle(3), -mpmath.acot(3)),
                 (pi * Fraction(-7, 3) + corner_angle(5), -7 * mpmath.pi / 3 + mpmath.acot(5))]
        for x, want in cases:
            for digits in (1, 2, 3, 5, 8, 13):
                s = x.decimal(digits)
                assert re.fullmatch(rf"-?[0-9]+\.[0-9]{{{digits}}}", s), s
                assert s.startswith("-") == (want < 0)
                assert abs(mpmath.mpf(s) - want) <= mpmath.mpf(51) / 100 / 10 ** digits, (s, want)


def test_cube_belt_twist_yields_flips_plus_one_triangulations_from_the_cube():
    """triangulations.cube_belt_twist(n) (Examples 4.3 / 4.4): n + 1 triangulations of the
    cube's surface (the same total area as the cube's), the first the cube's own, also for
    n = 0; each has an edge at least as long as Example 4.4's bound 1 + ((k - 2) / 4)^2
    after k flips (the flips twist the belt, they never undo each other)."""
    from ddg_oracle.reference.triangulations import cube_belt_twist
    c = surfaces.cube().metric()
    assert [s.squared_lengths for s in cube_belt_twist(0)] == [c.squared_lengths]
    with pytest.raises(ValueError):
        list(cube_belt_twist(-1))
    seq = list(cube_belt_twist(14))
    assert len(seq) == 15 and seq[0].squared_lengths == c.squared_lengths
    for k, s in enumerate(seq):
        assert s.total_area() == c.total_area() == 6
        assert max(s.squared_lengths) >= 1 + Fraction(k - 2, 4) ** 2, k


def test_face_data_scales_and_gram_integers_match_the_faces():
    """cotangents.face_data on a surface given by squared lengths whose denominators have
    primes above 100 (FaceData's docstring): per face, ``S[f]`` makes the face's squared
    lengths integers, ``G[f] = 16 area^2 S[f]^2`` with ``16 area^2`` by Heron's formula in
    the squared lengths, ``2(ab + bc + ca) - a^2 - b^2 - c^2``, and ``N[h] / sqrt(G)`` is
    the cotangent ``(x + y - o) / (4 area)`` at the corner opposite halfedge h."""
    from ddg_oracle.reference.cotangents import face_data
    t = Triangulation.from_faces([(0, 1, 2), (0, 2, 3), (0, 3, 1), (1, 3, 2)])
    rng = random.Random(46)
    primes = (101, 103, 107, 109, 113, 127)
    sq = [1 + Fraction(rng.randint(-20, 20), p) for p in primes[:t.n_edges]]
    m = PiecewiseFlatSurface(t, sq)
    fd = face_data(m)
    for f in range(t.n_faces):
        a, b, c = m.face_squared_lengths(f)             # halfedges 3f, 3f + 1, 3f + 2
        S = fd.S[f]
        assert all((S * x).denominator == 1 for x in (a, b, c))
        h16 = 2 * (a * b + b * c + c * a) - a * a - b * b - c * c
        assert fd.G[f] == h16 * S * S
        for h, (o, x, y) in zip(range(3 * f, 3 * f + 3), ((a, b, c), (b, c, a), (c, a, b))):
            # cot^2 = (x + y - o)^2 / h16, with the sign of x + y - o
            assert Fraction(fd.N[h] ** 2, fd.G[f]) == (x + y - o) ** 2 / h16
            assert (fd.N[h] > 0) == (x + y - o > 0)
