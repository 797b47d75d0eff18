"""Misprints of the notes (docs/errata.md), most of them inside proofs, each settled by a
computation independent of the printed formula: exact rationals (areas, gradients of affine
functions, polynomial integrals), the exact reference where it computes the quantity by
another route, and mpmath at 50 digits for the derivatives of the angles of a triangle with
respect to its side lengths."""

from fractions import Fraction
from math import isqrt

import mpmath
from hypothesis import assume, given
from hypothesis import strategies as st

from ddg_oracle.reference import surfaces
from ddg_oracle.reference.delaunay import harmonic_index
from ddg_oracle.reference.dirichlet import (kernel_dimension, satisfies_maximum_principle,
                                            solve_dirichlet)
from ddg_oracle.reference.exact import Surd, sqrt
from ddg_oracle.reference.laplacian import (cotan_laplacian, dirichlet_energy,
                                            dirichlet_energy_pl, graph_laplacian)
from ddg_oracle.reference.metric import PiecewiseFlatSurface
from ddg_oracle.reference.planar import circumcircle, quad_tessellation_faces
from ddg_oracle.reference.polyhedral import PolyhedralSurface


def _cross(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


triangles = st.lists(st.tuples(st.integers(-9, 9), st.integers(-9, 9)), min_size=3,
                     max_size=3, unique=True).filter(lambda t: _cross(*t) != 0)


@given(triangles)
def test_ER_9_circumcentric_subtriangle_area_is_half_base_times_height(tri):
    """Proof of Lemma 3.7 (line 1342): the sub-triangle (O, v_j, v_k) on side a_i has
    area 1/2 a_i l_i = 1/4 a_i^2 cot alpha_i (signed); the notes print 1/4 a_i l_i."""
    v = [tuple(map(Fraction, p)) for p in tri]
    if _cross(*v) < 0:
        v = [v[0], v[2], v[1]]
    o, _ = circumcircle(*v)
    for i in range(3):
        j, k = (i + 1) % 3, (i + 2) % 3
        sub = _cross(o, v[j], v[k]) / 2                           # signed area, exact
        a2 = (v[j][0] - v[k][0]) ** 2 + (v[j][1] - v[k][1]) ** 2
        u, w = [(v[x][0] - v[i][0], v[x][1] - v[i][1]) for x in (j, k)]
        cot = (u[0] * w[0] + u[1] * w[1]) / (u[0] * w[1] - u[1] * w[0])
        assert sub == a2 * cot / 4                                 # (3.5) term by term
        # l_i, the distance of O from side i, measured independently: l_i = a_i cot / 2,
        # so the sub-triangle's area 1/2 a_i l_i is (3.5)'s term; the printed
        # 1/4 a_i l_i = 1/4 a_i^2 cot alpha_i would need l_i = a_i cot alpha_i
        l_squared = _cross(o, v[j], v[k]) ** 2 / a2
        assert l_squared == a2 * cot ** 2 / 4
        if cot:
            assert l_squared != a2 * cot ** 2


def _angles(a1, a2, a3):
    return [mpmath.acos((b * b + c * c - a * a) / (2 * b * c))
            for a, b, c in ((a1, a2, a3), (a2, a3, a1), (a3, a1, a2))]


@given(st.lists(st.integers(5, 40), min_size=3, max_size=3).filter(
    lambda s: 2 * max(s) < sum(s)))
def test_ER_10_the_angle_sum_is_differentiated_in_a_i_not_a_j(sides):
    """Proof of Lemma 3.7 (lines 1384-1418): sum_j d alpha_j / d a_i = 0 (the angle sum is
    pi); the notes print d alpha_j / d a_j in the sum, which is not 0."""
    with mpmath.workdps(50):
        a = [mpmath.mpf(x) for x in sides]
        for i in range(3):
            def angle_sum(t, i=i):
                b = list(a)
                b[i] = t
                return mpmath.fsum(_angles(*b))
            assert abs(mpmath.diff(angle_sum, a[i])) < mpmath.mpf(10) ** -40
        printed = mpmath.fsum(
            mpmath.diff(lambda t, j=j: _angles(*[t if k == j else a[k] for k in range(3)])[j], a[j])
            for j in range(3))
        # each alpha_j grows with its own opposite side: the printed sum is positive
        assert printed > mpmath.mpf(10) ** -3


# --- ER-11: section 3.1, Green's formula (a lost sign) --------------------------------------------


def _padd(p, q):
    out = dict(p)
    for k, v in q.items():
        out[k] = out.get(k, 0) + v
    return out


def _pmul(p, q):
    out: dict = {}
    for (a, b), x in p.items():
        for (c, d), y in q.items():
            out[(a + c, b + d)] = out.get((a + c, b + d), 0) + x * y
    return out


def _pd(p, axis):
    """d/dx (axis 0) or d/dy (axis 1) of a polynomial {(i, j): coefficient of x^i y^j}."""
    out: dict = {}
    for (a, b), x in p.items():
        k = (a, b)[axis]
        if k:
            key = (a - 1, b) if axis == 0 else (a, b - 1)
            out[key] = out.get(key, 0) + k * x
    return out


def _integral_over_square(p):
    """The exact integral over [-1, 1]^2: odd powers vanish, x^(2k) gives 2 / (2k + 1)."""
    return sum(Fraction(x) * Fraction(2, a + 1) * Fraction(2, b + 1)
               for (a, b), x in p.items() if a % 2 == 0 and b % 2 == 0)


#: phi = (1 - x^2)^2 (1 - y^2)^2: C^1 on R^2 and zero with its gradient outside the open
#: square, an admissible test function of section 3.1 (Omega the open square)
_ONE_MINUS_X2, _ONE_MINUS_Y2 = {(0, 0): 1, (2, 0): -1}, {(0, 0): 1, (0, 2): -1}
_PHI = _pmul(_pmul(_ONE_MINUS_X2, _ONE_MINUS_X2), _pmul(_ONE_MINUS_Y2, _ONE_MINUS_Y2))


def _green_terms(f):
    gradient_term = _integral_over_square(_padd(_pmul(_pd(f, 0), _pd(_PHI, 0)),
                                                _pmul(_pd(f, 1), _pd(_PHI, 1))))
    lap_f = _padd(_pd(_pd(f, 0), 0), _pd(_pd(f, 1), 1))
    return gradient_term, _integral_over_square(_pmul(_PHI, lap_f))


@given(st.dictionaries(st.tuples(st.integers(0, 4), st.integers(0, 4)), st.integers(-5, 5),
                       min_size=1, max_size=6))
def test_ER_11_greens_formula_has_a_minus_sign(f):
    """Section 3.1 (line 867): with Lap f = sum d^2 f / dx_i^2 (the notes' definition) and
    phi in C^1_0, integral <grad f, grad phi> dA = - integral phi Lap f dA; the notes print
    + integral phi Lap f dA.  Exact integrals of polynomials over the square."""
    gradient_term, laplacian_term = _green_terms(f)
    assert gradient_term == -laplacian_term
    if laplacian_term:
        assert gradient_term != laplacian_term          # the printed sign


def test_ER_11_on_f_equal_to_x_squared():
    gradient_term, laplacian_term = _green_terms({(2, 0): 1})   # Lap f = 2 > 0
    assert laplacian_term == 2 * _integral_over_square(_PHI) == Fraction(512, 225)
    assert gradient_term == -laplacian_term


# --- ER-12: Theorem 3.2, the maximum principle (false as printed) ---------------------------------


def test_ER_12_printed_maximum_principle_fails_on_a_path():
    """Theorem 3.2 (line 1009) prints: f harmonic on V \\ V0 'can not attain its maximum
    (and minimum) on V \\ V0'.  On the path 0 - 1 - 2 - 3 with unit weights and
    V0 = {0, 2, 3}, c = (1, ., 1, 0), the solution has f(1) = 1 = max f, attained at
    1 in V \\ V0, and f is not constant.  What holds (and what the reference checks) is
    the weak form: max and min over each component are attained on V0."""
    L = graph_laplacian(4, [(0, 1, 1), (1, 2, 1), (2, 3, 1)])
    f = solve_dirichlet(L, {0: 1, 2: 1, 3: 0})
    assert f == [1, 1, 1, 0]
    assert L.matvec(f)[1] == 0                          # harmonic at 1 (the premise)
    assert f[1] == max(f)                               # the printed statement fails
    assert satisfies_maximum_principle(L, f, {0, 2, 3})  # the weak form holds


@given(st.integers(3, 8), st.data())
def test_ER_12_constant_boundary_values_defeat_the_printed_statement(n, data):
    """Any connected graph with positive weights, any V0 with V \\ V0 nonempty, and a
    constant c: the solution is constant, so it attains its max on V \\ V0; the proof's
    'Lap f(i) > 0 at a local maximum' holds only at a strict one (here Lap f = 0)."""
    extra = data.draw(st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)),
                               max_size=n))
    edges = [(i, i + 1, data.draw(st.integers(1, 5))) for i in range(n - 1)]
    edges += [(i, j, data.draw(st.integers(1, 5))) for i, j in extra if i != j]
    V0 = data.draw(st.sets(st.integers(0, n - 1), min_size=1, max_size=n - 1))
    c = data.draw(st.fractions(-5, 5, max_denominator=7))
    L = graph_laplacian(n, edges)
    f = solve_dirichlet(L, {v: c for v in V0})
    interior = [i for i in range(n) if i not in V0]
    assert all(x == c for x in f) and all(L.matvec(f)[i] == 0 for i in interior)
    assert max(f[i] for i in interior) == max(f)        # printed: impossible
    assert satisfies_maximum_principle(L, f, V0)


# --- ER-13: proof of Theorem 3.5, a lost square ---------------------------------------------------


def test_ER_13_printed_energy_bound_fails_below_one():
    """Proof of Theorem 3.5 (line 1065): from footnote 11, sum over a path gamma_k of
    (f(i) - f(j))^2 >= (R - c0)^2 / |E|, so E(f) >= 1/2 nu0 (R - c0)^2 / |E|; the notes
    print 1/2 nu0 (R - c0) / |E|, which fails for R - c0 < 1: one edge of weight 1,
    V0 = {0}, c = 0, R = 1/4 and f(1) = 1/3 > R give E = 1/18 < 1/8."""
    f, R, c0, nu0, n_edges = [0, Fraction(1, 3)], Fraction(1, 4), 0, 1, 1
    E = dirichlet_energy([(0, 1, 1)], f)
    assert E == Fraction(1, 18)
    assert E < Fraction(1, 2) * nu0 * (R - c0) / n_edges                # printed
    assert E >= Fraction(1, 2) * nu0 * (R - c0) ** 2 / n_edges          # corrected


@given(st.lists(st.fractions(-4, 4, max_denominator=5), min_size=2, max_size=7),
       st.lists(st.fractions(Fraction(1, 4), 4, max_denominator=4), min_size=6, max_size=6),
       st.fractions(0, 1, max_denominator=9))
def test_ER_13_corrected_bound_holds_on_paths(values, weights, fraction_of_gap):
    """On a path 0 - 1 - ... - k with V0 = {0}: for any R in [c0, f(k)), E(f) >=
    1/2 nu0 (R - c0)^2 / |E|, exactly."""
    n = len(values)
    edges = [(i, i + 1, weights[i]) for i in range(n - 1)]
    c0, top = values[0], values[-1]
    assume(top > c0)
    R = c0 + fraction_of_gap * (top - c0)
    nu0 = min(w for _, _, w in edges)
    assert dirichlet_energy(edges, values) >= Fraction(1, 2) * nu0 * (R - c0) ** 2 / len(edges)


# --- ER-14, ER-15: proof of Theorem 3.6, equation (3.4) and the inner product of gradients --------


def _affine_gradients(v):
    """grad phi_i of the hat functions of the planar triangle v (exact): phi_i is 1 at v_i,
    0 at the other two corners; solved from two linear equations, no formula of the notes."""
    out = []
    for i in range(3):
        j, k = (i + 1) % 3, (i + 2) % 3
        # grad . (v_j - v_i) = -1 and grad . (v_k - v_i) = -1
        a, b = (v[j][0] - v[i][0], v[j][1] - v[i][1]), (v[k][0] - v[i][0], v[k][1] - v[i][1])
        det = a[0] * b[1] - a[1] * b[0]
        out.append((Fraction(-b[1] + a[1], det), Fraction(b[0] - a[0], det)))
    return out


def _dot(u, w):
    return u[0] * w[0] + u[1] * w[1]


def _equation_3_4(g, f):
    """(|sum f_i grad phi_i|^2, its expansion as it should be, the printed left side
    |sum f_i^2 grad phi_i|^2, the printed right side sum f_i |grad phi_i|^2 + ...)."""
    def norm2(c):
        vec = tuple(sum(c[i] * g[i][k] for i in range(3)) for k in range(2))
        return _dot(vec, vec)
    cross = 2 * sum(f[i] * f[(i + 1) % 3] * _dot(g[i], g[(i + 1) % 3]) for i in range(3))
    return (norm2(f), sum(f[i] ** 2 * _dot(g[i], g[i]) for i in range(3)) + cross,
            norm2([x * x for x in f]), sum(f[i] * _dot(g[i], g[i]) for i in range(3)) + cross)


@given(triangles, st.lists(st.integers(-6, 6), min_size=3, max_size=3))
def test_ER_14_the_square_of_equation_3_4_belongs_to_f_i_on_the_right(tri, f):
    """(3.4), line 1185: |sum f_i grad phi_i|^2 = sum f_i^2 |grad phi_i|^2 + 2 sum f_i
    f_(i+1) <grad phi_i, grad phi_(i+1)>; the notes print the square on f_i in the left
    side and drop it on the right."""
    g = _affine_gradients([tuple(map(Fraction, p)) for p in tri])
    left, right, _, _ = _equation_3_4(g, f)
    assert left == right


def test_ER_14_the_printed_sides_on_f_equal_to_2_0_0():
    g = _affine_gradients([(Fraction(0), Fraction(0)), (Fraction(1), Fraction(0)),
                           (Fraction(0), Fraction(1))])
    left, right, printed_left, printed_right = _equation_3_4(g, [2, 0, 0])
    n0 = _dot(g[0], g[0])                           # |grad phi_1|^2 = 2 on this triangle
    assert (left, right, printed_left, printed_right) == (4 * n0, 4 * n0, 16 * n0, 2 * n0)
    assert n0 == 2


@given(triangles)
def test_ER_15_the_inner_product_of_two_sides_has_a_minus_sign(tri):
    """Proof of Theorem 3.6, line 1229: <w_i, w_(i+1)> = - a_i a_(i+1) cos alpha_(i-1)
    (w_i = v_(i-1) - v_(i+1) and w_(i+1) = v_i - v_(i-1) both run around the triangle,
    so at v_(i-1) the angle is between -w_i and w_(i+1)); the notes print it without the
    minus, then go on to the right -cot alpha_(i-1) / (2 A)."""
    v = [tuple(map(Fraction, p)) for p in tri]
    g = _affine_gradients(v)
    area2 = abs((v[1][0] - v[0][0]) * (v[2][1] - v[0][1]) - (v[1][1] - v[0][1]) * (v[2][0] - v[0][0]))
    for i in range(3):
        p, q, o = v[(i - 1) % 3], v[(i + 1) % 3], v[i]
        w_i = (p[0] - q[0], p[1] - q[1])                         # v_(i-1) - v_(i+1)
        w_next = (o[0] - p[0], o[1] - p[1])                      # v_i - v_(i-1)
        # a_i a_(i+1) cos alpha_(i-1), from the two sides at v_(i-1)
        at_corner = _dot((q[0] - p[0], q[1] - p[1]), (o[0] - p[0], o[1] - p[1]))
        cot = at_corner / area2                                   # cot alpha_(i-1)
        assert _dot(w_i, w_next) == -at_corner
        assert _dot(g[i], g[(i + 1) % 3]) == _dot(w_i, w_next) / area2 ** 2 == -cot / area2
        if at_corner:                                             # not a right angle
            assert _dot(w_i, w_next) != at_corner


# --- ER-16: Remark 3.3, positive semidefinite, not definite ---------------------------------------


def test_ER_16_cotan_dirichlet_energy_vanishes_on_constants():
    """Remark 3.3 (line 1299) prints 'the discrete Dirichlet energy with cotan-weights is
    always positive definite'.  E(1) = 0 on every mesh (each row of L sums to 0), so E is
    positive semidefinite with the locally constant functions as kernel (C3.3), and
    positive definite on F_(V0,0) when V0 meets every component: that is what makes the
    Dirichlet problem uniquely solvable."""
    for s in (surfaces.grid(3, 2), surfaces.torus(3, 4), surfaces.octahedron()):
        L = cotan_laplacian(s)
        n = s.triangulation.n_vertices
        assert dirichlet_energy(L, [1] * n) == 0
        assert kernel_dimension(L) == len(s.triangulation.components()) == 1
    grid = surfaces.grid(3, 2)
    L = cotan_laplacian(grid)
    boundary = [v for v in range(12) if grid.triangulation.is_boundary_vertex(v)]
    assert len(boundary) < 12
    # restricted to F_(V0,0) (V0 = the boundary) E is definite: the Dirichlet problem with
    # c = 0 has the zero solution only (a singular system would raise)
    assert solve_dirichlet(L, {v: 0 for v in boundary}) == [0] * 12


# --- ER-17: proof of Lemma 4.14 (Rippa), u0 for u0* ----------------------------------------------


@given(st.lists(st.fractions(Fraction(1, 5), 5, max_denominator=5), min_size=4, max_size=4),
       st.lists(st.fractions(-4, 4, max_denominator=3), min_size=4, max_size=4))
def test_ER_17_the_second_identity_of_rippas_proof_has_u0_star(r, u):
    """Proof of Lemma 4.14, line 2665: u2/r2 + u4/r4 = u0* (r2 + r4) / (r2 r4), with u0*
    = (r4 u2 + r2 u4) / (r2 + r4) the value of u24 at the crossing of the diagonals; the
    notes print u0.  The next line of the proof uses u0* again."""
    r1, r2, r3, r4 = r
    u1, u2, u3, u4 = u
    u0 = (r3 * u1 + r1 * u3) / (r1 + r3)
    u0s = (r4 * u2 + r2 * u4) / (r2 + r4)
    assert u1 / r1 + u3 / r3 == u0 * (r1 + r3) / (r1 * r3)        # the first, as printed
    assert u2 / r2 + u4 / r4 == u0s * (r2 + r4) / (r2 * r4)
    if u0 != u0s:
        assert u2 / r2 + u4 / r4 != u0 * (r2 + r4) / (r2 * r4)     # the printed second


# --- ER-18: proof of Lemma 4.20, a lost square ----------------------------------------------------


def _regular_tetrahedron(squared_side):
    t = surfaces.tetrahedron().triangulation
    return PiecewiseFlatSurface(t, [squared_side] * t.n_edges)


@given(st.integers(0, 12))
def test_ER_18_harmonic_index_bounds_the_squared_longest_edge(k):
    """Proof of Lemma 4.20, line 2879: h(T) >= l(T)^2 / A (h(Delta) = (a^2 + b^2 + c^2) /
    A(Delta) >= l^2 / A(M)); the notes print l(T) / A, which scaling refutes: h is scale
    invariant while l / A grows like 1 / scale.  Regular tetrahedron of side s = 2^-k:
    h = 16 sqrt 3, A = sqrt 3 s^2, so h A = 48 s^2 >= s^2 always, >= s only for s >= 1/48."""
    m = _regular_tetrahedron(Fraction(1, 4 ** k))
    h, A, l2 = harmonic_index(m), m.total_area(), max(m.squared_lengths)
    assert h * h == 768                                           # h = 16 sqrt 3, any scale
    assert h * A >= l2                                            # corrected: l^2 <= h A
    printed = h * A >= sqrt(l2)                                   # printed: l <= h A
    assert printed == (k <= 5)


# --- ER-19: Theorem 4.21, the Dirichlet energy without its 1/2 ------------------------------------


@given(triangles, st.lists(st.integers(-6, 6), min_size=3, max_size=3))
def test_ER_19_the_energy_of_theorem_4_21_is_half_the_integral(tri, f):
    """Theorem 4.21 (line 2895) writes E(f_T) = integral_M |grad f_T|^2 dA; everywhere else
    (section 3.1, T3.6, D3.2) E = 1/2 integral |grad f|^2 dA = 1/2 sum nu (f(i) - f(j))^2.
    On a triangle: the integral, from the exact gradient of the affine interpolant times
    the area, is twice the cotan energy."""
    v = [tuple(map(Fraction, p)) for p in tri]
    g = _affine_gradients(v)
    grad = tuple(sum(f[i] * g[i][k] for i in range(3)) for k in range(2))
    area = abs(_cross(*v)) / 2
    integral = _dot(grad, grad) * area
    s = PolyhedralSurface.from_arrays(v, [(0, 1, 2)])
    assert dirichlet_energy(cotan_laplacian(s), f) == integral / 2 == dirichlet_energy_pl(s, f)
    if integral:
        assert dirichlet_energy(cotan_laplacian(s), f) != integral    # the printed E


# --- ER-20: Remark 4.1, the Voronoi edge and the Delaunay edge ------------------------------------


def test_ER_20_the_voronoi_edge_need_not_bisect_its_delaunay_edge():
    """Remark 4.1 (line 1805): 'corresponding edges ... do not necessarily intersect ...
    The Voronoi edge bisects the corresponding Delaunay edge.'  The *line* through the
    Voronoi edge bisects it (the quad-tessellation bullet says so); the Voronoi edge, the
    segment between the centres of the two cells, does not when they do not intersect.
    Obtuse triangle (0,0), (6,0), (3,1) beside (0,0), (6,0), (3,-20): the midpoint (3, 0)
    of the Delaunay edge is not on the segment between the two circumcentres."""
    pts = [(0, 0), (6, 0), (3, 1), (3, -20)]
    face = {f["edge"]: f for f in quad_tessellation_faces(pts)}[(0, 1)]
    (qx, qy), (rx, ry) = face["voronoi"]
    assert qx == rx == 3                                 # on the perpendicular bisector x = 3
    assert face["bisected"] and not face["crossing"]
    assert min(qy, ry) > 0 or max(qy, ry) < 0           # the segment misses y = 0
    o, _ = circumcircle(*(tuple(map(Fraction, pts[i])) for i in (0, 1, 2)))
    assert o == (3, -4)                                  # the obtuse cell's centre is beyond


# --- ER-21: proof of Theorem 3.9, a factor 1/4 and a lost square ----------------------------------


@given(st.integers(0, 3), st.integers(1, 3))
def test_ER_21_area_as_a_sum_over_corners(which, scale):
    """Proof of Theorem 3.9, line 1549: A(S) = sum over faces of A(f(i), f(j), f(k)) (the
    notes print 1/4 of that sum) = 1/4 sum over the corners of cot alpha_ij |f(i) - f(j)|^2
    (the notes print |f(i) - f(j)| without the square; their factor 1/2 belongs to (3.10),
    ER-2).  Exact on closed and bordered surfaces: the face areas from the metric, the
    corner sum from exact cotangents; scaling the positions by k multiplies the area by
    k^2 while an unsquared sum would scale by k."""
    base = (surfaces.octahedron(), surfaces.grid(2, 3), surfaces.torus(3, 4),
            surfaces.icosahedron())[which]
    s = base.with_positions([tuple(scale * x for x in p) for p in base.positions])
    m = s.metric()
    t = s.triangulation
    faces_sum = sum((m.area(f) for f in range(t.n_faces)), Surd(0))
    corner_sum = sum((m.corner_cot(f, c) * m.squared_length(3 * f + (c + 1) % 3)
                      for f in range(t.n_faces) for c in range(3)), Surd(0)) / 4
    assert faces_sum == corner_sum == m.total_area()
    assert faces_sum / 4 != m.total_area()                       # the printed 1/4


# --- ER-22 to ER-27 ---------------------------------------------------------------------


def _planar_surface(points, faces):
    return PolyhedralSurface.from_arrays([tuple(map(Fraction, p)) for p in points], faces)


def test_ER_22_the_energy_of_theorem_3_6_has_a_square():
    """Theorem 3.6 (line 1107) prints E(f) = 1/2 integral_S |grad f| A. = 1/2 sum nu (f(i) -
    f(j))^2.  The left side needs the square, 1/2 integral |grad f|^2 dA (the proof's last
    line, and section 3.1): on the right triangle (0,0), (1,0), (0,1) with f = 2 x, |grad f|
    = 2 on an area 1/2, so the printed left side is 1/2 while the cotan sum is 1 = 1/2 * 4 *
    1/2.  Scaling f by t scales the right side by t^2 and the printed left by |t|."""
    s = _planar_surface([(0, 0), (1, 0), (0, 1)], [(0, 1, 2)])
    from ddg_oracle.reference.laplacian import cotan_weighted_edges
    for t in (1, 2, 3, Fraction(1, 2)):
        f = [2 * t * x for x, _ in s.positions]
        cotan = Fraction(1, 2) * sum((w * (f[i] - f[j]) ** 2
                                      for i, j, w in cotan_weighted_edges(s)), Fraction(0))
        grad_norm, area = 2 * t, Fraction(1, 2)            # |grad f| = 2 t, exactly
        assert cotan == Fraction(1, 2) * grad_norm ** 2 * area == dirichlet_energy_pl(s, f)
        printed = Fraction(1, 2) * grad_norm * area
        assert (printed == cotan) == (t == Fraction(1, 2))   # equal only where 2t = (2t)^2


@given(triangles, st.lists(st.integers(-6, 6), min_size=3, max_size=3))
def test_ER_22_corrected_energy_on_random_triangles(tri, f):
    """1/2 |grad f|^2 A(F) (the gradient of the affine interpolant solved from its values) is
    the cotan energy of Theorem 3.6 on every triangle; with |grad f| (no square) it is not,
    unless 1/2 |grad f| A = 1/2 |grad f|^2 A, i.e. |grad f| is 0 or 1."""
    v = [tuple(map(Fraction, p)) for p in tri]
    g = _affine_gradients(v)
    gx, gy = (sum(fi * gi[k] for fi, gi in zip(f, g)) for k in range(2))
    n2 = gx * gx + gy * gy                                   # |grad f|^2, rational
    area = abs(_cross(*v)) / 2
    s = _planar_surface(v, [(0, 1, 2)] if _cross(*v) > 0 else [(0, 2, 1)])
    assert dirichlet_energy(cotan_laplacian(s), f) == n2 * area / 2
    if n2 not in (0, 1):
        assert sqrt(n2) * area / 2 != n2 * area / 2


def _corner_cot(p, q, r):
    """cot of the angle at p of the planar triangle p, q, r (exact, rational)."""
    u, w = (q[0] - p[0], q[1] - p[1]), (r[0] - p[0], r[1] - p[1])
    return Fraction(u[0] * w[0] + u[1] * w[1], abs(u[0] * w[1] - u[1] * w[0]))


def _direct_area_gradients(points, faces):
    """grad_{v_i} of the total area of a planar triangulation (faces counterclockwise): the
    gradient of 1/2 cross(v_j - v_i, v_k - v_i) in v_i, summed over the faces at i."""
    out = [[Fraction(0), Fraction(0)] for _ in points]
    for f in faces:
        for c in range(3):
            i, j, k = f[c], f[(c + 1) % 3], f[(c + 2) % 3]
            (xj, yj), (xk, yk) = points[j], points[k]
            out[i][0] += Fraction(yj - yk, 2)
            out[i][1] += Fraction(xk - xj, 2)
    return [tuple(g) for g in out]


def _printed_gradient_sum(points, faces, i):
    """The proof of Theorem 3.9's last member at i: sum over the faces (i j k) at i, over
    their two edges (i j) at i, of cot(angle opposite (i j)) (f(i) - f(j)) (line 1589)."""
    total = [Fraction(0), Fraction(0)]
    for f in faces:
        if i not in f:
            continue
        c = f.index(i)
        j, k = f[(c + 1) % 3], f[(c + 2) % 3]
        for a, b in ((j, k), (k, j)):                      # edge (i a), angle at b
            cot = _corner_cot(points[b], points[i], points[a])
            total[0] += cot * (points[i][0] - points[a][0])
            total[1] += cot * (points[i][1] - points[a][1])
    return tuple(total)


def test_ER_23_the_area_gradient_in_theorem_3_9s_proof_lost_a_half():
    """Proof of Theorem 3.9 (line 1589): from (3.8) each face at i contributes 1/2 cot
    alpha_j (v_i - v_k) + 1/2 cot alpha_k (v_i - v_j), so grad_{f(i)} A(S) = 1/2 sum over the
    faces of cot(angle opposite (ij)) (f(i) - f(j)) = (Lap f)(i); the notes print the sum
    without the 1/2.  Right triangle (0,0), (1,0), (0,1) at (0,0): the gradient is
    (-1/2, -1/2), the printed sum (-1, -1)."""
    pts, faces = [(0, 0), (1, 0), (0, 1)], [(0, 1, 2)]
    assert _direct_area_gradients(pts, faces)[0] == (Fraction(-1, 2), Fraction(-1, 2))
    assert _printed_gradient_sum(pts, faces, 0) == (-1, -1)


@given(st.lists(st.tuples(st.integers(-1, 1), st.integers(-1, 1)), min_size=9, max_size=9))
def test_ER_23_on_jittered_planar_grids(jitter):
    """A 2 x 2 grid of squares split by diagonals, vertices moved by up to 1/4: at every
    vertex the exact area gradient (no cotangent) is half the printed sum, and equals the
    reference's cotan Laplacian of the positions (3.11, corrected as ER-2)."""
    from ddg_oracle.reference.areas import laplacian_of_positions
    pts = [(Fraction(4 * x + jitter[3 * x + y][0], 4), Fraction(4 * y + jitter[3 * x + y][1], 4))
           for x in range(3) for y in range(3)]
    faces = []
    for x in range(2):
        for y in range(2):
            a, b, c, d = 3 * x + y, 3 * (x + 1) + y, 3 * (x + 1) + y + 1, 3 * x + y + 1
            faces += [(a, b, c), (a, c, d)]
    assume(all(_cross(*(pts[v] for v in f)) > 0 for f in faces))
    direct = _direct_area_gradients(pts, faces)
    lap = laplacian_of_positions(_planar_surface(pts, faces))
    for i in range(9):
        printed = _printed_gradient_sum(pts, faces, i)
        assert printed == tuple(2 * x for x in direct[i])
        assert tuple(lap[i][:2]) == direct[i]


def _lattice_triangulations(bound):
    """The geodesic triangulations of the square torus R^2 / Z^2 with one vertex, as
    superbases {+-x, +-y, +-(x + y)} (det(x, y) = +-1), with |x|^2 + |y|^2 + |x + y|^2 <=
    bound: each line by its representative with a positive first nonzero coordinate."""
    def line(v):
        return v if v > (0, 0) and v[0] >= 0 and (v[0] > 0 or v[1] > 0) else (-v[0], -v[1])
    r = isqrt(bound)
    out = set()
    vecs = [(a, b) for a in range(-r, r + 1) for b in range(-r, r + 1) if a * a + b * b <= bound]
    for x in vecs:
        for y in vecs:
            if abs(x[0] * y[1] - x[1] * y[0]) != 1:
                continue
            z = (x[0] + y[0], x[1] + y[1])
            if sum(v[0] ** 2 + v[1] ** 2 for v in (x, y, z)) <= bound:
                out.add(frozenset(line(v) for v in (x, y, z)))
    return out


def test_ER_24_lemma_4_20_bounds_l_by_an_inequality_not_an_equality():
    """Proof of Lemma 4.20 (line 2887): 'h(T) <= c => l(T) <= sqrt(h(T) A) = sqrt(c A)'; the
    last '=' holds only when h(T) = c, the argument needs l(T) <= sqrt(h(T) A) <= sqrt(c A).
    On the square torus with one vertex (A = 1, h(T) = 4 (|x|^2 + |y|^2 + |x + y|^2)) every
    triangulation with h(T) <= c = 64 satisfies l(T)^2 <= h(T) A <= c A, and all but those
    with h(T) = 64 have h(T) A < c A."""
    c = 64
    below = _lattice_triangulations(c // 4)
    hs = {T: 4 * sum(a * a + b * b for a, b in T) for T in below}
    assert len(below) > 1 and all(h <= c for h in hs.values())
    for T, h in hs.items():
        l2 = max(a * a + b * b for a, b in T)
        assert l2 <= h * 1 <= c * 1                            # the corrected chain
    assert sum(h < c for h in hs.values()) >= 2                # the printed '=' fails there


def test_ER_25_theorem_3_5s_estimate_covers_only_f_above_R():
    """Proof of Theorem 3.5 (lines 1045-1069): with c0 = max c(i) and 'f(k) > R' the estimate
    E(f) >= 1/2 nu0 (R - c0)^2 / |E| (ER-13's square) covers only values above R, while the
    compact set {|f(i)| <= R} needs the values below -R too.  One edge of weight 1, V0 = {0},
    c(0) = -10 (c0 = -10), R = 1 > c0 and f(1) = -2, |f(1)| > R: E(f) = 32 < 121/2.  With c0
    = max |c(i)| the estimate holds for |f(k)| > R > c0 (checked on paths below)."""
    edges, f, c0, R = [(0, 1, 1)], [-10, -2], -10, 1
    E = dirichlet_energy(edges, f)
    assert E == 32 and abs(f[1]) > R > c0
    assert E < Fraction(1, 2) * (R - c0) ** 2 / len(edges)
    c0_abs = 10
    for value in (11, -11, 25, -40):
        R = abs(value) - Fraction(1, 2)                  # |f(1)| > R > max |c|
        E = dirichlet_energy(edges, [-10, value])
        assert E >= Fraction(1, 2) * (R - c0_abs) ** 2 / len(edges)


@given(st.lists(st.fractions(-4, 4, max_denominator=5), min_size=2, max_size=7),
       st.lists(st.integers(1, 5), min_size=6, max_size=6),
       st.fractions(0, 1, max_denominator=9))
def test_ER_25_both_signs_with_c0_the_largest_absolute_value(values, weights, fraction_of_gap):
    """A weighted path 0 - 1 - ... - k, V0 = {0}, c0 = |c(0)|: for every R between c0 and
    |f(k)|, E(f) >= 1/2 nu0 (R - c0)^2 / |E|, whether f(k) is above R or below -R."""
    n = len(values)
    edges = [(i, i + 1, weights[i]) for i in range(n - 1)]
    c0, top = abs(values[0]), abs(values[-1])
    assume(top > c0)
    R = c0 + fraction_of_gap * (top - c0)
    nu0 = min(w for _, _, w in edges)
    for sign in (1, -1):
        f = values[:-1] + [sign * top]
        assert dirichlet_energy(edges, f) >= Fraction(1, 2) * nu0 * (R - c0) ** 2 / len(edges)


def _J(w):
    """The rotation by +pi/2 (the triangles below are counterclockwise)."""
    return (-w[1], w[0])


def _direct_proof_of_3_8(v):
    """The members of the direct proof of (3.8) (lines 1481-1517) for the counterclockwise
    triangle v = (v1, v2, v3), exactly: w_i = v_(i-1) - v_(i+1); m_i from the midpoint of w_i
    to the circumcentre O (the reading under which 1/2 J w1 = -J (m2 - m3)); the signed
    coefficient c_i with -J m_i = c_i w_i, and cot alpha_i."""
    o, _ = circumcircle(*v)
    w = [tuple(v[(i - 1) % 3][k] - v[(i + 1) % 3][k] for k in range(2)) for i in range(3)]
    mid = [tuple((v[(i - 1) % 3][k] + v[(i + 1) % 3][k]) / 2 for k in range(2)) for i in range(3)]
    m = [tuple(o[k] - mid[i][k] for k in range(2)) for i in range(3)]
    coeff = []
    for i in range(3):
        jm = _J(m[i])
        c = -(jm[0] * w[i][0] + jm[1] * w[i][1]) / (w[i][0] ** 2 + w[i][1] ** 2)
        assert (-jm[0], -jm[1]) == (c * w[i][0], c * w[i][1])      # -J m_i is parallel to w_i
        coeff.append(c)
    cots = [_corner_cot(v[i], v[(i + 1) % 3], v[(i + 2) % 3]) for i in range(3)]
    return w, m, coeff, cots


def test_ER_26_the_direct_proof_of_3_8_covers_acute_angles_only():
    """Direct proof of (3.8) (line 1503): -J (m2 - m3) = |m2| / |w2| w2 - |m3| / |w3| w3 =
    1/2 cot alpha2 w2 - 1/2 cot alpha3 w3.  -J m_i = (l_i / a_i) w_i with l_i the *signed*
    height of the sub-triangle (negative past an obtuse angle, as the proof of Lemma 3.7 says),
    l_i / a_i = 1/2 cot alpha_i, while |m_i| / |w_i| = 1/2 |cot alpha_i|: the printed middle
    member is right only when alpha2, alpha3 <= pi/2.  Triangle (0,0), (2,0), (3,1), obtuse at
    v2 (135 degrees): -J m2 = -1/2 w2 = 1/2 cot alpha2 w2, while |m2| / |w2| w2 = +1/2 w2."""
    v = [(Fraction(0), Fraction(0)), (Fraction(2), Fraction(0)), (Fraction(3), Fraction(1))]
    assert _cross(*v) > 0
    w, m, coeff, cots = _direct_proof_of_3_8(v)
    half_jw1 = tuple(x / 2 for x in _J(w[0]))
    assert half_jw1 == tuple(-x / 2 for x in _J((w[1][0] + w[2][0], w[1][1] + w[2][1])))
    assert half_jw1 == tuple(-x for x in _J((m[1][0] - m[2][0], m[1][1] - m[2][1])))
    assert cots[1] == -1 and coeff[1] == Fraction(-1, 2) == cots[1] / 2       # obtuse at v2
    assert [c == cot / 2 for c, cot in zip(coeff, cots)] == [True] * 3
    # the printed |m_i| / |w_i| = |cot alpha_i| / 2 (squares compared exactly)
    for i in range(3):
        assert (m[i][0] ** 2 + m[i][1] ** 2) / (w[i][0] ** 2 + w[i][1] ** 2) == cots[i] ** 2 / 4
    printed = tuple(abs(cots[1]) / 2 * w[1][k] - abs(cots[2]) / 2 * w[2][k] for k in range(2))
    right = tuple(cots[1] / 2 * w[1][k] - cots[2] / 2 * w[2][k] for k in range(2))
    assert right == half_jw1 != printed
    # with m_i from O to the midpoint (the other reading) the second '=' fails instead
    assert tuple(-x for x in _J((-m[1][0] + m[2][0], -m[1][1] + m[2][1]))) != half_jw1


@given(triangles)
def test_ER_26_signed_heights_on_random_triangles(tri):
    """On every triangle the chain holds with the signed coefficient 1/2 cot alpha_i and
    with |m_i| / |w_i| exactly when no angle at v2, v3 is obtuse."""
    v = [tuple(map(Fraction, p)) for p in tri]
    if _cross(*v) < 0:
        v = [v[0], v[2], v[1]]
    w, m, coeff, cots = _direct_proof_of_3_8(v)
    assert coeff == [c / 2 for c in cots]
    half_jw1 = tuple(x / 2 for x in _J(w[0]))
    assert half_jw1 == tuple(cots[1] / 2 * w[1][k] - cots[2] / 2 * w[2][k] for k in range(2))
    printed = tuple(abs(cots[1]) / 2 * w[1][k] - abs(cots[2]) / 2 * w[2][k] for k in range(2))
    assert (printed == half_jw1) == (cots[1] >= 0 and cots[2] >= 0)


def test_ER_27_the_voronoi_vertex_radius_is_measured_from_Q():
    """Section 4.1.1 (line 1783): 'Let Q be a vertex of the Voronoi tessellation, i.e.
    exists i, j, k for all m: r_Q := |P P_i| = |P P_j| = |P P_k| <= |P P_m|', then D_Q = {P :
    |P Q| < r_Q} 'contains no points of V'.  The condition must be on Q: |Q P_i| = |Q P_j| =
    |Q P_k| <= |Q P_m|.  As printed it does not involve Q: it holds for any Q once some point P
    (a true Voronoi vertex) satisfies it, and then D_Q may hold points of V.  With Q: exactly
    the Voronoi vertices (reference, T4.1) satisfy it, and their disks are empty."""
    from ddg_oracle.reference.planar import delaunay_tessellation, voronoi_vertices
    pts = [(0, 0), (4, 0), (0, 4), (5, 5), (6, 1)]
    P = [tuple(map(Fraction, p)) for p in pts]

    def d2(a, b):
        return (a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2

    def condition(X):                                  # exists i, j, k: 3 nearest tied, radius
        ds = sorted(d2(X, p) for p in P)
        return ds[0] == ds[1] == ds[2], ds[0]

    centres = voronoi_vertices(pts, delaunay_tessellation(pts))
    assert centres
    for q in centres.values():
        holds, r2 = condition(q)
        assert holds and all(d2(q, p) >= r2 for p in P)           # D_Q is empty (corrected)
    q_true = next(iter(centres.values()))
    # printed: Q = P_0 passes (the condition is met at P = q_true), with r_Q = |P P_i|
    holds, r2 = condition(q_true)
    Q = P[0]
    assert holds and d2(Q, P[0]) < r2                              # P_0 lies in D_Q
    assert not condition(Q)[0]                                     # corrected: Q is no vertex


# --- ER-28 ------------------------------------------------------------------------------


def _superbasis_faces(T):
    """The two faces (0, p, p + q) and (0, p + q, q) of the one-vertex square torus whose
    edges are the three lines of the superbasis T (as from `_lattice_triangulations`)."""
    p, q, r = sorted(T)
    if (p[0] - q[0], p[1] - q[1]) in (r, (-r[0], -r[1])):
        q = (-q[0], -q[1])                                   # then r = +-(p + q)
    s = (p[0] + q[0], p[1] + q[1])
    assert s in (r, (-r[0], -r[1]))
    return [((0, 0), p, s), ((0, 0), s, q)]


def _incircle(a, b, c, d):
    """> 0 iff d is strictly inside the circle through a, b, c (integers, exact)."""
    rows = [(x[0] - d[0], x[1] - d[1]) for x in (a, b, c)]
    m = [(u, v, u * u + v * v) for u, v in rows]
    det = (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
           - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
           + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
    return det * (1 if _cross(a, b, c) > 0 else -1)


def _theorem_4_7_set_A(faces):
    """The set A of the proof of Theorem 4.7 (lines 2039-2043) on the square torus R^2 / Z^2
    with one vertex v (every lattice point is a lift of v), and the angle alpha on it (line
    2047), as an exact cotangent (a larger angle has a smaller cotangent): (Delta, a, S) with
    Delta a face with no empty immersed disk (a lattice point strictly inside its circumcircle),
    a = (B C) an edge of Delta whose largest empty disk segment D_(Delta, a) beyond a lies in
    D_Delta (a lattice point beyond a in the closed circumdisk), S = v on its arc (a lattice
    point beyond a of largest angle BSC).  On the flat torus every disk segment extends the
    immersion of Delta, so only the lattice points decide."""
    A = {}
    for f, (P0, P1, P2) in enumerate(faces):
        tri = (P0, P1, P2)
        xs, ys = [t[0] for t in tri], [t[1] for t in tri]
        den = 2 * _cross(*tri)
        d = [t[0] ** 2 + t[1] ** 2 for t in tri]
        cx = Fraction(d[0] * (P1[1] - P2[1]) + d[1] * (P2[1] - P0[1]) + d[2] * (P0[1] - P1[1]), den)
        cy = Fraction(d[0] * (P2[0] - P1[0]) + d[1] * (P0[0] - P2[0]) + d[2] * (P1[0] - P0[0]), den)
        r = isqrt(int((cx - P0[0]) ** 2 + (cy - P0[1]) ** 2)) + 2
        box = [(i, j) for i in range(int(cx) - r, int(cx) + r + 1)
               for j in range(int(cy) - r, int(cy) + r + 1)]       # holds the closed circumdisk
        assert min(xs) >= int(cx) - r and max(xs) <= int(cx) + r
        assert min(ys) >= int(cy) - r and max(ys) <= int(cy) + r
        if not any(_incircle(*tri, z) > 0 for z in box):
            continue                                          # Delta has an empty disk
        for e in range(3):
            B, C, O = tri[e], tri[(e + 1) % 3], tri[(e + 2) % 3]
            beyond = [z for z in box if _cross(B, C, z) * _cross(B, C, O) < 0]
            if not any(_incircle(*tri, z) >= 0 for z in beyond):
                continue                                      # D_(Delta, a) leaves D_Delta
            cots = [Fraction((B[0] - z[0]) * (C[0] - z[0]) + (B[1] - z[1]) * (C[1] - z[1]),
                             abs(_cross(z, B, C))) for z in beyond]
            A[(f, e, "v")] = min(cots)                        # the first lattice point hit
    return A


def test_ER_28_the_maximum_in_theorem_4_7s_proof_is_taken_over_A():
    """Proof of Theorem 4.7 (line 2049): 'Let (Delta, a, S) in D such that alpha(Delta, a, S)
    = max over (Delta, a, S) in A of alpha (4.1)'.  The triple must lie in A (lines 2039-2045),
    the set alpha is defined on (alpha : A -> (0, pi)); the proof's D's are disks (D_Delta,
    D') and disk segments (D_(Delta, a), the family of segments fitting along a), which hold
    no triples.  On the one-vertex square torus, for every triangulation with |x|^2 + |y|^2 +
    |x + y|^2 <= 52 (34 of them): A (computed from lattice points, exact) is empty iff every
    edge is Delaunay (the theorem), and otherwise the maximiser of alpha over A has a
    non-Delaunay edge a, which is what the proof derives by contradiction from (4.1).  None
    of the segments D_(Delta*, a*) fitting along its edge is a triple."""
    seen_non_delaunay = 0
    for T in _lattice_triangulations(52):
        faces = _superbasis_faces(T)
        delaunay = []                                  # each edge, from both of its faces
        for (P0, P1, P2) in faces:
            tri = (P0, P1, P2)
            for e in range(3):
                B, C, O = tri[e], tri[(e + 1) % 3], tri[(e + 2) % 3]
                X = (B[0] + C[0] - O[0], B[1] + C[1] - O[1])   # across (B C): a parallelogram
                delaunay.append(_incircle(*tri, X) <= 0)
        A = _theorem_4_7_set_A(faces)
        assert (not A) == all(delaunay)
        if not A:
            continue
        seen_non_delaunay += 1
        best = min(A.values())                          # the largest angle alpha
        star = next(t for t, c in A.items() if c == best)
        f, e, S = star
        assert star in A                                # corrected: (Delta, a, S) in A
        assert not delaunay[3 * f + e]                  # the proof's conclusion: a is not Delaunay
        segments = {("segment", faces[f][e], faces[f][(e + 1) % 3], c) for c in A.values()}
        assert star not in segments                     # printed: no D holds the triple
    assert seen_non_delaunay >= 3
