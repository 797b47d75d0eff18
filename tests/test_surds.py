"""Tests of ddg_oracle.reference.exact.surds: canonical form, field axioms, exact signs,
correctly rounded float, enclosures, hashing, the term guard, mixed arithmetic.

Reference values are computed independently here: with ``decimal`` at 220
significant digits, or with integer square roots at thousands of bits.
"""

from __future__ import annotations

import decimal
import math
import pickle
from fractions import Fraction
from math import isqrt

import pytest
from hypothesis import assume, given, settings as hsettings, strategies as st

from ddg_oracle.reference.errors import (ExactArithmeticLimit, InputError, NonFiniteValue,
                              NotANumber, TermLimitExceeded)
from ddg_oracle.reference.exact import terms as terms_module
from ddg_oracle.reference.exact.surds import Surd, limits, settings, sqrt

# --- independent reference evaluation -------------------------------------------

DEC = decimal.Context(prec=420)      # the 330-digit sign test below needs > 350
EPS = Fraction(1, 10**190)   # bound on the Decimal evaluation error used below


def dec_value(x: Surd) -> decimal.Decimal:
    """x evaluated with 220-digit decimals (test-side reference)."""
    total = decimal.Decimal(0)
    for r, q in x.terms():
        c = DEC.divide(decimal.Decimal(q.numerator), decimal.Decimal(q.denominator))
        total = DEC.add(total, DEC.multiply(c, DEC.sqrt(decimal.Decimal(r))))
    return total


def float_by_isqrt(n: int, q: Fraction = Fraction(1), bits: int = 2000) -> float:
    """Correctly rounded float of q*sqrt(n) from a 2000-bit integer enclosure."""
    a, d = abs(q.numerator), q.denominator
    s = isqrt(a * a * n << (2 * bits))
    lo, hi = Fraction(s, d << bits), Fraction(s + 1, d << bits)
    if s * s == a * a * n << (2 * bits):
        hi = lo
    flo, fhi = float(lo), float(hi)
    assert flo == fhi, "test enclosure too wide"
    return flo if q >= 0 else -flo


# --- strategies -----------------------------------------------------------------

SMALL_RADICANDS = [2, 3, 5, 6, 7, 8, 10, 12, 15, 18, 20, 21, 30, 35, 42, 50, 70]
BIG_PRIMES = [1000003, 998244353, 10**9 + 7, 2**61 - 1]

small_rationals = st.fractions(min_value=-20, max_value=20, max_denominator=30)
nonzero_rationals = small_rationals.filter(bool)


@st.composite
def big_radicands(draw):
    """Products of big primes (shared between draws, so bases must be refined),
    small primes and squares: exercises gcd splitting and square detection."""
    r = 1
    for p in draw(st.lists(st.sampled_from(BIG_PRIMES), min_size=1, max_size=2)):
        r *= p
    r *= draw(st.sampled_from([1, 2, 3, 6, 4, 9 * 5]))
    return r


radicands = st.one_of(st.sampled_from(SMALL_RADICANDS), big_radicands(),
                      st.integers(2, 10**15))


@st.composite
def surds(draw, max_terms=3):
    ts = draw(st.lists(st.tuples(small_rationals, radicands), max_size=max_terms))
    x = Surd(draw(small_rationals))
    for q, r in ts:
        x = x + q * sqrt(r)
    return x


nonzero_surds = surds().filter(bool)


# --- construction and canonical form ---------------------------------------------

def test_perfect_squares_and_small_square_factors():
    assert sqrt(8) == 2 * sqrt(2)
    assert sqrt(8).terms() == (2 * sqrt(2)).terms() == ((2, Fraction(2)),)
    assert sqrt(12).terms() == ((3, Fraction(2)),)
    assert sqrt(49).terms() == ((1, Fraction(7)),) and sqrt(49).is_rational()
    assert sqrt(0).terms() == () and sqrt(0) == 0
    assert sqrt(Fraction(9, 4)).as_fraction() == Fraction(3, 2)


def test_products_of_roots():
    assert sqrt(2) * sqrt(3) == sqrt(6)
    assert (sqrt(2) * sqrt(3)).terms() == sqrt(6).terms() == ((6, Fraction(1)),)
    assert (sqrt(6) * sqrt(10)).terms() == ((15, Fraction(2)),)
    assert (sqrt(2) * sqrt(2)).as_fraction() == 2
    assert (sqrt(2) * sqrt(2)).base == ()


def test_zero_has_no_terms():
    x = 3 * sqrt(2) - Fraction(1, 5) * sqrt(15) + 7
    z = x - x
    assert z.terms() == ()
    assert not bool(z)
    assert z == 0 and z.n_terms == 0 and z.is_rational()
    assert bool(x) and x.n_terms == 3


def test_large_prime_square_factor_meets_its_reduced_form():
    p = 2**61 - 1
    a, b = sqrt(p * p * 3), p * sqrt(3)
    assert a.base != b.base          # not factored on creation ...
    assert a == b                    # ... but equal once they meet
    assert (a - b).terms() == ()
    assert hash(a) == hash(b)
    assert (a + b).terms() == ((3, Fraction(2 * p)),)
    assert sqrt(p**3) * sqrt(p) == p * p
    assert sqrt(p**3) == p * sqrt(p)


def test_sqrt_of_fraction():
    assert sqrt(Fraction(1, 2)) == sqrt(2) / 2
    assert sqrt(Fraction(1, 2)).terms() == ((2, Fraction(1, 2)),)
    assert sqrt(Fraction(8, 3)) == 2 * sqrt(6) / 3
    assert sqrt(0.25) == Fraction(1, 2)           # floats taken exactly
    assert sqrt(0.5) == sqrt(2) / 2


def test_refinement_of_shared_factors():
    p, q = 1000003, 998244353
    x = sqrt(p * q) + sqrt(p)
    y = sqrt(q * 6)
    assert x.base == (p, q)
    assert (x * y).base == (6, p, q)
    assert (x * y).terms() == ((6 * p, Fraction(q)), (6 * p * q, Fraction(1)))
    assert (x * y) / y == x
    assert sqrt(p * q) * sqrt(p * 5) == p * sqrt(q * 5)


_FACTORS = (2, 3, 5, 7, 11, 13, *BIG_PRIMES)      # small primes shared by many elements


@given(st.lists(st.lists(st.sampled_from(_FACTORS), min_size=1, max_size=4),
                min_size=1, max_size=30),
       st.lists(st.sampled_from(_FACTORS), unique=True, max_size=4))
def test_refine_many_elements_is_the_coprime_base_merged_one_by_one(factor_lists, coprime):
    """More than 8 elements take the product shortcut (one gcd with the product of the
    base so far); merged one at a time they take the gcd per element.  Both give the
    same base: pairwise coprime, every element a product of powers of it."""
    elements = [math.prod(f) for f in factor_lists]
    base = terms_module.refine(elements, coprime=tuple(coprime))
    one_by_one = tuple(coprime)
    for n in elements:
        one_by_one = terms_module.refine([n], coprime=one_by_one)
    assert base == one_by_one
    assert all(math.gcd(a, b) == 1 for i, a in enumerate(base) for b in base[:i])
    for n in elements + list(coprime):
        for b in base:
            while n % b == 0:
                n //= b
        assert n == 1


def test_refine_many_coprime_elements_costs_one_gcd_each(monkeypatch):
    """The product shortcut is taken: 40 distinct primes cost one gcd each against the
    product of the base so far, not one per element of it (780 for 40)."""
    primes = [p for p in range(10**6, 10**6 + 600) if all(p % q for q in range(2, 1001))][:40]
    calls = []
    monkeypatch.setattr(terms_module, "gcd", lambda a, b: calls.append(1) or math.gcd(a, b))
    assert terms_module.refine(primes) == tuple(primes)
    assert len(calls) == len(primes)


def test_constructor_inputs():
    assert Surd() == 0 and Surd(3) == 3 and Surd(Fraction(2, 3)) == Fraction(2, 3)
    assert Surd(0.1) == Fraction(0.1)
    x = sqrt(2) + 1
    assert Surd(x) is x
    assert Surd("3/2 + 2*sqrt(6)") == Fraction(3, 2) + 2 * sqrt(6)
    assert Surd("-sqrt(2) - 1/3*sqrt(5) + 7") == 7 - sqrt(2) - sqrt(5) / 3
    assert Surd("0") == 0
    for bad in ["", "sqrt(-2)", "2 3", "abc", "1 + + 2"]:
        with pytest.raises(InputError):
            Surd(bad)
    with pytest.raises(NotANumber):
        Surd(True)
    with pytest.raises(NotANumber):
        Surd(None)
    with pytest.raises(NonFiniteValue):
        Surd(float("nan"))
    with pytest.raises(NonFiniteValue):
        sqrt(float("inf"))


def test_sqrt_rejects_negative_and_irrational():
    with pytest.raises(InputError, match="-2"):
        sqrt(-2)
    with pytest.raises(InputError, match="-1/2"):
        sqrt(Fraction(-1, 2))
    with pytest.raises(InputError):
        sqrt(sqrt(2))
    assert sqrt(sqrt(2) * sqrt(8)) == 2


def test_str_repr_roundtrip():
    x = Fraction(3, 2) + 2 * sqrt(6)
    assert str(x) == "3/2 + 2*sqrt(6)"
    assert repr(x) == "Surd('3/2 + 2*sqrt(6)')"
    assert str(-sqrt(2) + 1) == "1 - sqrt(2)"
    assert str(Surd(0)) == "0"
    y = (sqrt(2) + sqrt(3) + sqrt(5)) ** -1
    assert eval(repr(y), {"Surd": Surd}) == y


@given(surds())
def test_repr_and_pickle_roundtrip(x):
    assert Surd(str(x)) == x
    assert pickle.loads(pickle.dumps(x)) == x
    assert pickle.loads(pickle.dumps(x)).terms() == x.terms()


@given(surds())
def test_terms_are_canonical(x):
    ts = x.terms()
    rads = [r for r, _ in ts]
    assert rads == sorted(set(rads))
    assert all(q != 0 and isinstance(q, Fraction) for _, q in ts)
    base = x.base
    assert list(base) == sorted(base)
    for i, b in enumerate(base):
        assert b > 1 and isqrt(b) ** 2 != b
        assert all(math.gcd(b, c) == 1 for c in base[i + 1:])
        assert any(r % b == 0 for r in rads)          # pruned
    for r in rads:                                     # squarefree over the base
        for b in base:
            assert r % (b * b) != 0
        rest = r
        for b in base:
            if rest % b == 0:
                rest //= b
        assert rest == 1
    assert x.n_terms == len(ts)
    assert x.is_rational() == (not base)


# --- field axioms ------------------------------------------------------------------

@given(surds(), surds())
def test_commutativity(x, y):
    assert x + y == y + x
    assert x * y == y * x


@given(surds(2), surds(2), surds(2))
def test_associativity_and_distributivity(x, y, z):
    assert (x + y) + z == x + (y + z)
    assert (x * y) * z == x * (y * z)
    assert x * (y + z) == x * y + x * z
    assert (x - y) - z == x - (y + z)


@given(surds())
def test_additive_inverse(x):
    assert x + (-x) == 0
    assert (x + (-x)).terms() == ()
    assert x - x == 0
    assert -(-x) == x
    assert +x == x


@given(nonzero_surds)
def test_multiplicative_inverse(x):
    inv = 1 / x
    assert x * inv == 1
    assert (x * inv).terms() == ((1, Fraction(1)),)
    assert 1 / inv == x
    assert x ** -1 == inv


@given(surds(), nonzero_surds)
def test_division_undoes_multiplication(x, y):
    assert (x * y) / y == x
    assert (x / y) * y == x


@given(surds(2), st.integers(0, 5))
def test_integer_powers(x, n):
    expected = Surd(1)
    for _ in range(n):
        expected = expected * x
    assert x ** n == expected
    if x:
        assert x ** -n * x ** n == 1


def test_power_edge_cases():
    assert (1 + sqrt(2)) ** 3 == 7 + 5 * sqrt(2)
    assert Surd(0) ** 0 == 1
    with pytest.raises(ZeroDivisionError):
        Surd(0) ** -1
    assert 2 ** Surd(3) == 8
    assert sqrt(2) ** Fraction(4) == 4
    with pytest.raises(TypeError):
        sqrt(2) ** Fraction(1, 2)
    with pytest.raises(TypeError):
        2 ** sqrt(2)


# --- signs and comparisons -----------------------------------------------------------

def test_nearly_cancelling_signs():
    assert sqrt(10**12 + 1) - 10**6 > 0
    assert (sqrt(10**12 + 1) - 10**6).sign() == 1
    assert (sqrt(10**12 - 1) - 10**6).sign() == -1
    # 5 + 2*sqrt(6) = 9.899... < 10
    assert sqrt(2) + sqrt(3) < sqrt(10)
    assert sqrt(2) + sqrt(3) > sqrt(9)
    assert sqrt(5) + sqrt(6) + sqrt(7) < sqrt(54)
    assert sqrt(5) + sqrt(6) + sqrt(7) > sqrt(53)
    # Pell convergents of sqrt(2): 665857^2 - 2*470832^2 = 1
    assert sqrt(2) < Fraction(665857, 470832)
    assert (470832 * sqrt(2) - 665857).sign() == -1
    assert (985 * sqrt(2) - 1393).sign() == 1          # 1393^2 - 2*985^2 = -1
    assert sqrt(2) > Fraction(1393, 985)


def test_exact_zero_constructions():
    assert (sqrt(2) + sqrt(3)) ** 2 - 5 - 2 * sqrt(6) == 0
    assert ((sqrt(2) + sqrt(3)) ** 2 - 5 - 2 * sqrt(6)).sign() == 0
    x = sqrt(2) + sqrt(3) + sqrt(5) + sqrt(7)
    assert (x * (1 / x) - 1).sign() == 0
    assert (x / x) == 1


def _truncate(x: Surd, digits: int) -> Fraction:
    d = dec_value(x)
    return Fraction(DEC.quantize(d, decimal.Decimal(10) ** -digits))


@pytest.mark.parametrize("digits", [30, 150, 330])
def test_signs_beyond_enclosure_filters(digits, monkeypatch):
    """x - (x rounded to `digits` decimals) is tiny: 330 digits force the exact recursion
    (the enclosures stop at 1,024 bits below the largest term, about 308 digits here)."""
    splits = []
    real_split = terms_module.t_split
    monkeypatch.setattr(terms_module, "t_split",
                        lambda t, p: splits.append(p) or real_split(t, p))
    for x in [sqrt(2) + sqrt(3) + sqrt(5),
              sqrt(5) + sqrt(6) + sqrt(7) - sqrt(11),
              sqrt(2) * 3 - sqrt(1000003) / 7 + sqrt(6 * 1000003),
              sqrt(2) + sqrt(3) + sqrt(5) + sqrt(7) + sqrt(11)]:
        approx = _truncate(x, digits)
        y = x - approx
        exact_sign = dec_value(y)
        assert abs(exact_sign) > decimal.Decimal(10) ** -(digits + 20)
        expected = 1 if exact_sign > 0 else -1
        assert y.sign() == expected
        assert (x > approx) == (expected == 1)
        assert (x < approx) == (expected == -1)
        assert x != approx
    assert bool(splits) == (digits > 308)


@hsettings(max_examples=200)
@given(surds(4), surds(4))
def test_sign_and_order_against_decimal(x, y):
    d = x - y
    ref = dec_value(d)
    if abs(ref) > decimal.Decimal(10) ** -150:
        expected = 1 if ref > 0 else -1
    else:
        assume(d.terms() == ())
        expected = 0
    assert d.sign() == expected
    assert (x < y) == (expected < 0)
    assert (x <= y) == (expected <= 0)
    assert (x > y) == (expected > 0)
    assert (x >= y) == (expected >= 0)
    assert (x == y) == (expected == 0)
    assert (x != y) == (expected != 0)
    assert abs(d).sign() == abs(expected)
    assert abs(d) == (d if expected >= 0 else -d)


@given(surds(3))
def test_near_zero_combination_of_three_roots(x):
    """Shift x by a 120-digit rational approximation: the sign is decided exactly."""
    assume(not x.is_rational())
    approx = _truncate(x, 120)
    ref = dec_value(x - approx)
    assume(abs(ref) > decimal.Decimal(10) ** -170)
    assert (x - approx).sign() == (1 if ref > 0 else -1)


# --- float() -------------------------------------------------------------------------

@given(st.integers(0, 2**52))
def test_float_matches_math_sqrt(n):
    assert float(sqrt(n)) == math.sqrt(n)


@given(st.integers(2, 2**400))
def test_float_correctly_rounded_big_radicands(n):
    assert float(sqrt(n)) == float_by_isqrt(n)


@given(st.integers(2, 10**6), st.fractions(min_value=-10**6, max_value=10**6,
                                           max_denominator=10**9).filter(bool))
def test_float_correctly_rounded_scaled(n, q):
    assert float(q * sqrt(n)) == float_by_isqrt(n, q)


@given(surds(4))
def test_float_correctly_rounded_sums(x):
    ref = Fraction(dec_value(x))
    lo, hi = ref - EPS, ref + EPS
    assume(float(lo) == float(hi))       # not (unluckily) next to a rounding midpoint
    assert float(x) == float(lo)


@given(st.lists(surds(3), min_size=1, max_size=12), st.booleans())
def test_rounded_sum_is_the_exact_sums_float(xs, cancel):
    """exact.rounded_sum (integer enclosures, no canonical form) == float(exact_sum), also
    when the sum cancels to exactly 0 or nearly so (a value and its negative appended)."""
    from ddg_oracle.reference.exact import exact_sum, rounded_sum
    if cancel:
        xs = xs + [-x for x in xs[:-1]]
    assert rounded_sum(xs) == float(exact_sum(xs))


def test_rounded_sum_of_many_radicands_and_exact_cancellation():
    from ddg_oracle.reference.exact import rounded_sum
    roots = [sqrt(p) for p in (2, 3, 5, 7, 11, 13, 17, 19, 23, 29)]
    assert rounded_sum(roots + [-r for r in roots]) == 0.0
    tiny = Fraction(1, 2**200)
    assert rounded_sum(roots + [-r for r in roots] + [tiny]) == float(tiny)


def test_float_extremes():
    assert float(sqrt(2) * 2**1000) == math.sqrt(2) * 2.0**1000
    assert float(sqrt(2) * 2**1023) == math.sqrt(2) * 2.0**1023
    with pytest.raises(OverflowError):
        float(sqrt(2) * 2**1024)
    with pytest.raises(OverflowError):
        float(-sqrt(3) * 10**400)
    with pytest.raises(OverflowError):
        float(Surd(10**400))                      # same as float(Fraction)
    for e in (1060, 1073, 1074, 1075, 1076, 1100):
        x = sqrt(3) / 2**e
        assert float(x) == float_by_isqrt(3, Fraction(1, 2**e), bits=3000)
        assert float(-x) == -float(x)
    assert math.copysign(1.0, float(-sqrt(2) / 2**1100)) == -1.0
    assert float(Surd(Fraction(1, 3))) == 1 / 3


# --- interval() ------------------------------------------------------------------------

@given(surds(4), st.integers(0, 300))
def test_interval_encloses_and_is_narrow(x, bits):
    lo, hi = x.interval(bits)
    assert isinstance(lo, Fraction) and isinstance(hi, Fraction)
    assert lo <= hi
    assert hi - lo <= Fraction(1, 2**bits)
    ref = Fraction(dec_value(x))
    assert lo <= ref + EPS and ref - EPS <= hi
    assert lo <= x <= hi
    if x.is_rational():
        assert lo == hi == x


def test_interval_coarse_and_rejects_non_integers():
    lo, hi = (sqrt(2) * 10**6).interval(-10)
    assert hi - lo <= 2**10 and lo <= sqrt(2) * 10**6 <= hi
    with pytest.raises(InputError):
        sqrt(2).interval(1.5)


# --- hashing ---------------------------------------------------------------------------

def test_hash_of_rationals_matches_fraction_and_float():
    assert hash(Surd(Fraction(1, 2))) == hash(Fraction(1, 2)) == hash(0.5)
    assert hash(sqrt(2) * sqrt(2)) == hash(2)
    assert hash(Surd(0)) == hash(0)
    assert hash(sqrt(Fraction(9, 4))) == hash(Fraction(3, 2))
    assert Surd(0.5) == 0.5 and Surd(Fraction(1, 2)) == Fraction(1, 2)


def test_surds_as_dict_keys():
    p = 2**61 - 1
    d = {sqrt(8): "a", Fraction(1, 2): "b"}
    assert d[2 * sqrt(2)] == "a"
    assert d[sqrt(2) * sqrt(2) / 4] == "b"
    assert d[Surd(0.5)] == "b"
    s = {sqrt(p * p * 3), p * sqrt(3), sqrt(12) * p / 2, sqrt(2), sqrt(8) / 2}
    assert len(s) == 2


@given(surds(), nonzero_surds)
def test_equal_values_hash_equal(x, y):
    z = (x * y) / y
    assert z == x and hash(z) == hash(x)
    w = (x + y) - y
    assert w == x and hash(w) == hash(x)
    if x.is_rational():
        assert hash(x) == hash(x.as_fraction())


# --- term guard ------------------------------------------------------------------------

def test_term_limit():
    assert settings.term_limit == 4096
    x = Surd(1)
    with limits(term_limit=8):
        assert settings.term_limit == 8
        for p in (2, 3, 5):
            x = x * (1 + sqrt(p))
        assert x.n_terms == 8
        with pytest.raises(TermLimitExceeded) as info:
            x * (1 + sqrt(7))
        message = str(info.value)
        assert "16" in message and "8" in message and "limits(term_limit=" in message
        assert isinstance(info.value, ExactArithmeticLimit)
    assert settings.term_limit == 4096
    assert (x * (1 + sqrt(7))).n_terms == 16


def test_term_limit_restored_after_exception():
    with pytest.raises(RuntimeError):
        with limits(term_limit=3):
            raise RuntimeError
    assert settings.term_limit == 4096
    with pytest.raises(InputError):
        with limits(term_limit=0):
            pass
    assert settings.term_limit == 4096


# --- mixed arithmetic --------------------------------------------------------------------

@pytest.mark.parametrize("other", [3, Fraction(2, 7), 0.5, -1.25])
def test_mixed_arithmetic_both_sides(other):
    x = sqrt(2) + Fraction(1, 3)
    o = Surd(other)
    assert x + other == other + x == x + o
    assert x - other == x - o and other - x == o - x
    assert x * other == other * x == x * o
    assert x / other == x / o and other / x == o / x
    assert isinstance(other + x, Surd) and isinstance(other / x, Surd)
    assert (x < other) == (x < o) and (other < x) == (o < x)
    assert (x >= other) == (x >= o) and (other >= x) == (o >= x)
    assert x != other and other != x


def test_mixed_comparisons_with_rationals():
    assert Fraction(7, 5) < sqrt(2) < Fraction(3, 2)
    assert 1.4142135623730951 > sqrt(2) > 1.4142135623730950
    assert 1 < sqrt(2) < 2 and 2 > sqrt(2) > 1
    assert sqrt(4) == 2 and 2 == sqrt(4) and sqrt(4) == 2.0 and sqrt(4) == Fraction(2)
    assert sqrt(2) < float("inf") and sqrt(2) > float("-inf")
    assert not (sqrt(2) == float("nan")) and not (sqrt(2) < float("nan"))
    assert sqrt(2) != "sqrt(2)"
    assert sorted([sqrt(3), 1, sqrt(2), Fraction(3, 2), 1.7]) == [1, sqrt(2), Fraction(3, 2), 1.7, sqrt(3)]


def test_unsupported_operands():
    with pytest.raises(TypeError):
        sqrt(2) + "1"
    with pytest.raises(TypeError):
        "1" * sqrt(2)
    with pytest.raises(TypeError):
        sqrt(2) < "1"
    with pytest.raises(TypeError):
        sqrt(2) + 1j


def test_division_by_zero():
    for zero in (0, Fraction(0), 0.0, Surd(0), sqrt(2) - sqrt(2)):
        with pytest.raises(ZeroDivisionError):
            sqrt(2) / zero
        with pytest.raises(ZeroDivisionError):
            1 / Surd(zero)
    with pytest.raises(ZeroDivisionError):
        Fraction(1, 2) / (sqrt(8) - 2 * sqrt(2))


def test_abs_neg_pos():
    x = 1 - sqrt(2)
    assert abs(x) == sqrt(2) - 1 and abs(-x) == abs(x)
    assert -x == sqrt(2) - 1 and +x is x
    assert abs(Surd(0)) == 0


def test_as_fraction():
    assert (sqrt(3) * sqrt(12)).as_fraction() == 6
    with pytest.raises(ValueError):
        sqrt(2).as_fraction()


def test_floor_ceil_trunc_are_exact():
    n = 10**40
    x = sqrt(n - 1)                       # float(x) rounds to exactly 1e20
    assert math.floor(x) == 10**20 - 1
    assert math.ceil(x) == 10**20
    assert math.trunc(-x) == int(-x) == -(10**20 - 1)
    assert math.floor(-x) == -(10**20)
    assert math.floor(Surd(Fraction(-7, 2))) == -4 and math.ceil(Surd(Fraction(7, 2))) == 4
    assert math.floor(sqrt(2) + sqrt(3)) == 3 and math.ceil(sqrt(2) * sqrt(8)) == 4


@given(st.integers(1, 10**60), st.lists(st.sampled_from([2, 3, 5, 7, 97, 101, 193]), max_size=8))
def test_strip_small_squares_keeps_the_value_and_strips_only_small_prime_squares(m, squares):
    """m = c^2 m' exactly, m' has no square of a prime below 100, and squares of larger
    primes stay (the gcd shortcut must neither miss a small prime nor strip a large one)."""
    from math import prod
    n = m * prod(p * p for p in squares)
    c, rest = terms_module.strip_small_squares(n)
    assert c * c * rest == n
    assert all(rest % (p * p) for p, _ in terms_module.SMALL_SQUARES)
    assert rest % 101 ** (2 * squares.count(101)) == 0 and rest % 193 ** (2 * squares.count(193)) == 0


# --- the term product on integer pairs (one reduction per output term) ------------------------

_RADICANDS = (1, 2, 3, 5, 6, 10, 15, 30, 7, 14, 21, 42, 105, 210)


def _naive_product(ta, tb):
    """sum q1 q2 sqrt(r1 r2) term by term, Fraction arithmetic, sqrt(g^2 m) = g sqrt(m)."""
    out = {}
    for r1, q1 in ta.items():
        for r2, q2 in tb.items():
            g = math.gcd(r1, r2)
            r = (r1 // g) * (r2 // g)
            out[r] = out.get(r, 0) + Fraction(q1) * q2 * g
    return {r: q for r, q in out.items() if q}


def _term_dicts(values):
    return st.dictionaries(st.sampled_from(_RADICANDS), values.filter(bool), max_size=6)


_BIG_FRACTIONS = st.builds(Fraction, st.integers(-2 ** 300, 2 ** 300), st.integers(1, 2 ** 200))


@given(_term_dicts(_BIG_FRACTIONS), _term_dicts(_BIG_FRACTIONS))
def test_term_product_equals_the_fraction_products(ta, tb):
    # equal denominators and different ones meet in one output term (radicand 1 collects
    # r * r from every pair of equal radicands); zero sums drop out
    got = terms_module.t_mul(ta, tb)
    assert got == _naive_product(ta, tb)
    assert all(type(q) is Fraction and q.denominator > 0 for q in got.values())


@given(_term_dicts(st.integers(-10, 10)), _term_dicts(st.integers(-10, 10)))
def test_term_product_of_integers_stays_integer(ta, tb):
    got = terms_module.t_mul(ta, tb)
    assert got == _naive_product(ta, tb)
    assert all(type(q) is int for q in got.values())


@given(_term_dicts(st.one_of(st.integers(-10, 10), _BIG_FRACTIONS)),
       _term_dicts(st.one_of(st.integers(-10, 10), _BIG_FRACTIONS)))
def test_term_product_of_a_mix_is_exact_whichever_way_it_takes(ta, tb):
    # the first coefficients pick the way (integers as they are, or integer pairs): any
    # mix behind them still gives the exact product
    assert terms_module.t_mul(ta, tb) == _naive_product(ta, tb)


def test_term_product_cancels_to_nothing():
    # (sqrt2 + sqrt3)(sqrt2 - sqrt3) = 2 - 3: the sqrt6 terms cancel, and are dropped
    assert terms_module.t_mul({2: 1, 3: 1}, {2: 1, 3: -1}) == {1: -1}
    half = Fraction(1, 2)
    assert terms_module.t_mul({2: half, 3: Fraction(1, 3)},
                               {2: half, 3: Fraction(-1, 3)}) == {1: Fraction(1, 2) - Fraction(1, 3)}
