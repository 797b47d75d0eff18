"""Misprints inside proofs of the notes (docs/errata.md), each settled by a computation
independent of the reference: exact rationals for areas, mpmath at 50 digits for the
derivatives of the angles of a triangle with respect to its side lengths."""

from fractions import Fraction

import mpmath
from hypothesis import given
from hypothesis import strategies as st

from ddg_oracle.reference.planar import circumcircle


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
