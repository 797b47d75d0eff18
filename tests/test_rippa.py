"""Tests of ddg_oracle.reference.rippa: Dirichlet energy and edge flips (section 4.3.1), exact.

Rows: L4.14 (Rippa's lemma: both sides computed independently, on integer
quadrilaterals where r_i and sin(theta) are irrational and on Q(r1, r2, r3,
r4, theta) with rational parameters), L4.15 (circularity against the angle
criterion and the in-circle predicate), C4.16 (a flip to the Delaunay diagonal
never increases E; strictly unless circular or u affine; erratum ER-6).
"""

from fractions import Fraction

import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from ddg_oracle.reference.errors import BadQuadrilateral, BadShape
from ddg_oracle.reference.exact import Surd
from ddg_oracle.reference.laplacian import cotan_laplacian, dirichlet_energy
from ddg_oracle.reference.planar import angle_criterion, circle_position
from ddg_oracle.reference.polyhedral import PolyhedralSurface
from ddg_oracle.reference.rippa import (TRIANGLES_13, TRIANGLES_24, circularity, energy_difference,
                             is_affine_on, quadrilateral, rippa_right_side)
from ddg_oracle.properties.planar_points import integer_quadrilaterals, parameter_quadrilaterals, unit_circle_point

values = st.lists(st.integers(-4, 4), min_size=4, max_size=4)


def energies(points, u):
    """E(u13), E(u24) by the cotan formula (T3.6), a second route to the left side."""
    return tuple(dirichlet_energy(cotan_laplacian(PolyhedralSurface.from_arrays(points, t)), u)
                 for t in (TRIANGLES_13, TRIANGLES_24))


# --- L4.14 -------------------------------------------------------------------------------------


@given(integer_quadrilaterals, values)
def test_L4_14_rippa_on_integer_quadrilaterals(points, u):
    q = quadrilateral(points)
    left = energy_difference(points, u)
    assert left == rippa_right_side(points, u)
    e13, e24 = energies(points, u)
    assert left == e13 - e24
    # the r_i and sin(theta) really are square-root numbers here, often irrational
    assert all(isinstance(r, Surd) for r in q.r)
    assert all(r * r == r2 for r, r2 in zip(q.r, q.r_squared))


@given(parameter_quadrilaterals(), st.lists(st.fractions(-3, 3, max_denominator=3), min_size=4,
                                             max_size=4))
def test_L4_14_rippa_on_parameter_quadrilaterals(case, u):
    points, r, (c, s) = case
    q = quadrilateral(points)
    assert q.x == (0, 0)
    assert q.r == tuple(Surd(x) for x in r)                    # r_i as constructed
    assert q.sin_theta == s
    r1, r2, r3, r4 = r
    u1, u2, u3, u4 = u
    u0 = (r3 * u1 + r1 * u3) / (r1 + r3)
    u0s = (r4 * u2 + r2 * u4) / (r2 + r4)
    printed = (Fraction(1, 4) * (u0 - u0s) ** 2 / s * (r1 + r3) * (r2 + r4)
               / (r1 * r2 * r3 * r4) * (r1 * r3 - r2 * r4))      # (4.2), all rational here
    assert energy_difference(points, u) == printed == rippa_right_side(points, u)


def test_L4_14_with_irrational_parameters():
    """r_i and sin(theta) irrational, the difference rational: the comparison is exact,
    so a wrong factor (1/2 instead of 1/4, sin^2 for sin) would be caught."""
    points, u = [(3, 0), (1, 2), (-1, 1), (0, -3)], [1, -2, 0, 3]
    q = quadrilateral(points)
    assert not q.sin_theta.is_rational() and not any(r.is_rational() for r in q.r)
    left = energy_difference(points, u)
    assert left != 0 and left == rippa_right_side(points, u)
    assert left != 2 * rippa_right_side(points, u)
    assert left != rippa_right_side(points, u) / q.sin_theta


def test_L4_14_bad_input():
    with pytest.raises(BadQuadrilateral, match="P3"):
        quadrilateral([(0, 0), (2, 0), (1, 1), (2, 2)])          # reflex at P3
    with pytest.raises(BadQuadrilateral):
        quadrilateral([(0, 0), (0, 1), (1, 1), (1, 0)])          # clockwise
    with pytest.raises(BadShape):
        quadrilateral([(0, 0), (1, 0), (0, 1)])
    with pytest.raises(BadShape):
        energy_difference([(1, 0), (0, 1), (-1, 0), (0, -1)], [1, 2, 3])


# --- L4.15 -------------------------------------------------------------------------------------


@given(integer_quadrilaterals)
def test_L4_15_circularity_against_the_angle_criterion(points):
    p1, p2, p3, p4 = points
    c = circularity(points)
    # 13 is Delaunay iff P4 is not inside the circle through P1, P2, P3 (angles at 2 and 4)
    assert c == angle_criterion(p1, p2, p3, p4) == circle_position(p1, p2, p3, p4)
    # 24 is Delaunay iff P1 is not inside the circle through P2, P3, P4 (angles at 3 and 1)
    assert c == -angle_criterion(p2, p3, p4, p1)


@given(st.lists(st.tuples(st.integers(1, 6), st.integers(-6, 6).filter(bool)), min_size=4,
                max_size=4, unique_by=lambda mn: Fraction(mn[1], mn[0])),
       st.sampled_from([Fraction(1), Fraction(1, 2), Fraction(3, 2)]))
def test_L4_15_on_cocircular_quadrilaterals_and_radial_moves(params, k):
    p1, p2, p3, p4 = (unit_circle_point(m, n) for m, n in
                      sorted(params, key=lambda mn: Fraction(mn[1], mn[0])))
    p4 = (k * p4[0], k * p4[1])
    pts = [p1, p2, p3, p4]
    assume(quadrilateral_is_convex(pts))          # moving P4 may break convexity
    # P4 inside the unit circle (k < 1): 13 is not Delaunay, r1 r3 > r2 r4
    assert circularity(pts) == (k < 1) - (k > 1)


def quadrilateral_is_convex(pts):
    try:
        quadrilateral(pts)
    except BadQuadrilateral:
        return False
    return True


# --- C4.16 -------------------------------------------------------------------------------------


@given(integer_quadrilaterals, values)
def test_C4_16_flip_to_the_delaunay_diagonal_never_increases_the_energy(points, u):
    c = circularity(points)
    diff = energy_difference(points, u)           # E(u13) - E(u24)
    affine = is_affine_on(points, u)
    if c > 0:                                     # 24 Delaunay: flipping 13 -> 24 helps
        assert diff >= 0
    if c < 0:
        assert diff <= 0
    assert (diff == 0) == (c == 0 or affine)      # strict unless circular or u affine
    if not affine:
        assert (diff > 0) - (diff < 0) == c


@given(integer_quadrilaterals, st.integers(-3, 3), st.integers(-3, 3), st.integers(-3, 3))
def test_C4_16_affine_functions_have_equal_energies_on_any_quadrilateral(points, a, b, c):
    u = [a * x + b * y + c for x, y in points]
    assert is_affine_on(points, u)
    assert energy_difference(points, u) == 0
    e13, e24 = energies(points, u)
    assert e13 == e24 == Fraction(a * a + b * b, 2) * shoelace(points)


def shoelace(points):
    return sum(p[0] * q[1] - p[1] * q[0] for p, q in zip(points, points[1:] + points[:1])) / 2


def test_C4_16_printed_corollary_fails_for_affine_u_erratum_ER_6():
    """Corollary 4.16 as printed: "not all u_i equal => (E(u13) = E(u24) iff Q circular)".
    u = x on a kite that is not circular: the u_i are not all equal, Q is not circular
    (24 is strictly Delaunay), yet the energies are equal."""
    kite = [(2, 0), (0, 1), (-1, 0), (0, -1)]
    u = [x for x, _ in kite]
    assert len(set(u)) > 1
    assert circularity(kite) == 1 and circle_position(*kite) == 1     # P4 inside: 24 Delaunay
    assert energy_difference(kite, u) == 0
    assert energies(kite, u) == (Fraction(3, 2), Fraction(3, 2))     # 1/2 |grad x|^2 * area 3
    # the corrected hypothesis (u not affine on Q, i.e. u0 != u0*) restores the statement
    assert energy_difference(kite, [2, 0, -1, 1]) > 0
