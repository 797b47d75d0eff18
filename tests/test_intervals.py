"""ddg_oracle.reference.exact.intervals: every operation encloses the exact result of every
choice of points in its operands, and the enclosure of an exact value contains it."""

from fractions import Fraction

import pytest
from hypothesis import given
from hypothesis import strategies as st

from ddg_oracle.reference.exact import corner_angle, sqrt
from ddg_oracle.reference.exact.intervals import Interval, dot

q = st.fractions(-20, 20, max_denominator=12)


@st.composite
def intervals_with_points(draw):
    a, b = sorted((draw(q), draw(q)))
    t = draw(st.fractions(0, 1, max_denominator=7))
    return Interval(a, b), a + t * (b - a)


@given(intervals_with_points(), intervals_with_points())
def test_operations_enclose_their_exact_results(xa, yb):
    (x, a), (y, b) = xa, yb
    assert (x + y).lo <= a + b <= (x + y).hi
    assert (x - y).lo <= a - b <= (x - y).hi
    assert (x * y).lo <= a * b <= (x * y).hi
    assert x.square().lo <= a * a <= x.square().hi
    assert (-x).lo <= -a <= (-x).hi
    if y.lo > 0 or y.hi < 0:
        assert (x / y).lo <= a / b <= (x / y).hi
    else:
        with pytest.raises(ZeroDivisionError, match="containing 0"):
            x / y
    # the square is never wider than the product of the interval with itself
    assert (x * x).lo <= x.square().lo and x.square().hi <= (x * x).hi and x.square().lo >= 0


@given(st.lists(intervals_with_points(), min_size=1, max_size=4))
def test_dot_encloses_the_inner_product(pairs):
    u = [x for x, _ in pairs]
    p = [a for _, a in pairs]
    d = dot(u, u)
    assert d.lo <= sum(a * a for a in p) <= d.hi and d.lo >= 0


@given(st.integers(2, 50), st.integers(8, 80))
def test_enclosures_of_exact_values_contain_them_and_decide_signs(n, bits):
    r = sqrt(n)
    x = Interval.enclosing(r, bits)
    assert x.width <= Fraction(1, 2 ** bits)
    assert x.lo ** 2 <= n <= x.hi ** 2
    assert Interval.enclosing(Fraction(n, 3), bits) == Interval(Fraction(n, 3))
    quarter_pi = Interval.enclosing(corner_angle(1), bits)       # arccot(1) = pi/4
    assert quarter_pi.lo <= Fraction("0.7853981633974483096156608458") <= quarter_pi.hi
    assert (x - x).sign() is None and (x + 1).sign() == 1 and (-x - 1).sign() == -1


def test_an_interval_needs_its_ends_in_order():
    with pytest.raises(ValueError, match="lo <= hi"):
        Interval(2, 1)
    assert list(Interval(1, 2)) == [1, 2] and Interval(3).width == 0
