"""The exact zero test of angle sums where square roots pile up (float meshes, flips).

Every case here made the reference give no answer before (TermLimitExceeded: the old test
expanded prod (c + i) over all cotangents of the sum); the expected values come from mpmath
at 400 digits or from an identity built exactly, never from the reference itself.
"""

import math
import random
from fractions import Fraction

import mpmath
import pytest
from hypothesis import given, settings, strategies as st

from ddg_oracle.reference import PolyhedralSurface
from ddg_oracle.reference.curvature import angle_defects, angle_sums, gauss_bonnet_holds
from ddg_oracle.reference.delaunay import flip_to_delaunay
from ddg_oracle.reference.exact import Angle, Surd, corner_angle, limits, pi, sqrt
from ddg_oracle.reference.metric import as_metric

from benchmarks.meshes import fan, spiky_fan


def mp_defect(s, n):
    """2 pi - the angle sum at vertex 0 of ``fan(n)``, by mpmath at 400 digits."""
    with mpmath.workdps(400):
        P = [[mpmath.mpf(x.numerator) / x.denominator for x in p] for p in s.positions]
        total = mpmath.mpf(0)
        for k in range(n):
            a = [P[1 + k][i] - P[0][i] for i in range(3)]
            b = [P[1 + (k + 1) % n][i] - P[0][i] for i in range(3)]
            cross = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
            total += mpmath.atan2(mpmath.sqrt(sum(x * x for x in cross)),
                                  sum(x * y for x, y in zip(a, b)))
        return 2 * mpmath.pi - total


@pytest.mark.parametrize("n, lift, tilt", [
    (15, 1e-30, None),            # the nearly flat valence-15 vertex, defect ~1e-60
    (15, 2.0 ** -100, None),
    (32, 0.0, (0.3, 0.7)),        # a float-tilted fan-triangulated 32-gon (a CAD cylinder cap)
    (128, 2.0 ** -100, None),
    (128, 0.0, (0.3, 0.7)),
])
def test_nearly_flat_float_vertices_get_the_sign_of_their_defect(n, lift, tilt):
    s = fan(n, lift=lift, tilt=tilt)
    want = mp_defect(s, n)
    assert 0 < abs(want) < 1e-25                  # a hard case: far below float resolution
    assert angle_defects(s)[0].sign() == (1 if want > 0 else -1)
    assert gauss_bonnet_holds(s)                  # and the exact identity is still exact


@pytest.mark.parametrize("n", [15, 64, 128])
def test_exactly_planar_fans_are_flat(n):
    # rational points of a plane with an irrational normal length: one radicand for all faces
    s = fan(n)
    V = [(x, y, 3 * x - 2 * y) for x, y, _ in s.positions]
    planar = PolyhedralSurface(s.triangulation, V)
    assert angle_defects(planar)[0] == 0


def test_angle_sums_are_intrinsic_after_flips_at_a_valence_16_vertex():
    # T4.5 / L2.8: intrinsic flips keep the metric, so every angle sum is unchanged; the
    # flipped triangles' cotangents mix the square roots of several original faces
    s = spiky_fan(16)
    delaunay, log = flip_to_delaunay(as_metric(s))
    assert len(log) >= 10 and delaunay.triangulation.valence(0) != 16
    before, after = angle_sums(s), angle_sums(delaunay)
    assert all(a == b for a, b in zip(before, after))
    tiny = corner_angle(Surd(7)) - corner_angle(Surd(7) + Fraction(1, 10 ** 40))
    assert (after[0] - before[0] + tiny).sign() == 1       # arccot decreases: 1e-41 > 0


def _surd(rng, p):
    return Fraction(rng.randint(1, 50), rng.randint(1, 50)) + \
        Fraction(rng.choice((-1, 1)) * rng.randint(1, 30), rng.randint(1, 30)) * sqrt(p)


PRIMES = [p for p in range(1009, 2000) if all(p % d for d in range(2, math.isqrt(p) + 1))]


def _addition_identity(rng, pairs):
    """sum of arccot a + arccot b - arccot((ab - 1)/(a + b)) over ``pairs`` of radicands:
    exactly 0 (cot(x + y) = (cot x cot y - 1)/(cot x + cot y), x + y < pi as a, b > 0)."""
    theta = Angle()
    for p, q in pairs:
        a = b = Surd(-1)
        while not (a > 0 and b > 0):
            a, b = _surd(rng, p), _surd(rng, q)
        theta = theta + corner_angle(a) + corner_angle(b) - corner_angle((a * b - 1) / (a + b))
    return theta


@pytest.mark.parametrize("linked", [False, True])
def test_identities_over_64_radicands_are_exact_and_stay_small(linked):
    # 64 independent radicands; linked: every third cotangent mixes two of them and the 64
    # form one cycle.  The test must never expand a product over different cotangents: with
    # a term limit of 16 nothing it builds may exceed what one cotangent has.
    rng = random.Random(7)
    pairs = ([(PRIMES[k], PRIMES[(k + 1) % 64]) for k in range(64)] if linked else
             [(PRIMES[2 * k], PRIMES[2 * k + 1]) for k in range(32)])
    theta = _addition_identity(rng, pairs)
    assert len({b for c in theta.parts for b in c.base}) == 64
    with limits(term_limit=16):
        assert theta == 0
        assert theta.as_multiple_of_pi() == 0
        assert (theta + pi / 7).as_multiple_of_pi() == Fraction(1, 7)
        assert (5 * theta + corner_angle(2) + corner_angle(3)).as_multiple_of_pi() == Fraction(1, 4)
        assert (theta + corner_angle(2)).as_multiple_of_pi() is None
        off = theta + corner_angle(Surd(7)) - corner_angle(Surd(7) + Fraction(1, 10 ** 40))
        assert off.sign() == 1 and off.as_multiple_of_pi() is None


@settings(max_examples=25, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 40), st.integers(0, 40)), min_size=1, max_size=6),
       st.integers(-3, 3), st.integers(0, 2 ** 32), st.integers(-47, 47))
def test_built_identities_are_zero_and_their_shifts_are_not(pairs, m, seed, j):
    # an exact identity times m plus j pi/24: a rational multiple of pi exactly when built so
    rng = random.Random(seed)
    theta = m * _addition_identity(rng, [(PRIMES[p], PRIMES[q]) for p, q in pairs])
    shifted = theta + pi * Fraction(j, 24)
    assert shifted.as_multiple_of_pi() == Fraction(j, 24)
    assert shifted.sign() == (j > 0) - (j < 0)
    c = _surd(rng, PRIMES[pairs[0][0]])
    assert (theta + corner_angle(c) - corner_angle(c + Fraction(1, 10 ** 30))).sign() == 1


def test_flips_of_a_float_mesh_never_build_the_whole_harmonic_index():
    # h(T) of a surface from R^3 has one square root per face (48 here): the flip loop must
    # work with each flip's two faces only, so it runs under a term limit h itself exceeds
    from ddg_oracle.reference.delaunay import harmonic_index, is_delaunay
    from ddg_oracle.reference.errors import TermLimitExceeded
    m = as_metric(spiky_fan(16))
    with limits(term_limit=32):
        delaunay, log = flip_to_delaunay(m)
        assert is_delaunay(delaunay) and len(log) >= 10
        with pytest.raises(TermLimitExceeded):
            harmonic_index(m)
    assert log[0].h_before == harmonic_index(m)
    assert log[-1].h_after == harmonic_index(delaunay)
    assert all(r.change < 0 and r.h_after - r.h_before == r.change for r in log)   # C4.19
