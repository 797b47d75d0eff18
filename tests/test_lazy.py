"""Lazy exact numbers (reference/exact/lazy.py) and the lazy intrinsic flips that use them:
every decision, float and exact value equal to the eager exact arithmetic's."""

import math
import random
import time
from fractions import Fraction

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ddg_oracle.reference import surfaces
from ddg_oracle.reference.delaunay import flip_to_delaunay, is_delaunay
from ddg_oracle.reference.errors import TermLimitExceeded
from ddg_oracle.reference.exact import limits, sign, simplest, sqrt
from ddg_oracle.reference.exact.lazy import PRECISIONS, Lazy, filtered_sign, flipped
from ddg_oracle.reference.polyhedral import PolyhedralSurface

from .test_delaunay import random_flips, start_surface

SETTINGS = settings(max_examples=60, deadline=None, database=None,
                    suppress_health_check=[HealthCheck.too_slow])

# --- the numbers ---------------------------------------------------------------------------

leaves = st.one_of(
    st.fractions(-5, 5, max_denominator=7),
    st.integers(1, 30).map(sqrt),
    st.tuples(st.integers(-3, 3), st.integers(1, 12)).map(lambda p: p[0] * sqrt(p[1])),
    st.floats(-4, 4, allow_nan=False, width=32).map(Fraction),
)


def trees(depth):
    """(lazy, eager) pairs: the same expression built lazily and with exact arithmetic."""
    if depth == 0:
        return leaves.map(lambda v: (Lazy.of(v), v))
    sub = trees(depth - 1)

    def combine(op, x, y):
        (lx, ex), (ly, ey) = x, y
        if op == "+":
            return lx + ly, simplest(ex + ey)
        if op == "-":
            return lx - ly, simplest(ex - ey)
        if op == "*":
            return lx * ly, simplest(ex * ey)
        if sign(ey) == 0:
            return lx - ly, simplest(ex - ey)
        return lx / ly, simplest(ex / ey)
    return st.one_of(sub, st.builds(combine, st.sampled_from("+-*/"), sub, sub))


@SETTINGS
@given(trees(3))
def test_decisions_floats_and_exact_values_equal_the_eager_ones(pair):
    lazy, eager = pair
    assert lazy.sign() == sign(eager)
    assert float(lazy) == float(eager)
    assert math.copysign(1, float(lazy)) == math.copysign(1, float(eager))   # +0.0, never -0.0
    assert lazy.exact() == eager and lazy == eager and hash(lazy) == hash(eager)
    for k in (0, 10, 200):
        lo, hi = lazy.scaled_bounds(k)
        assert hi - lo <= 2 and Fraction(lo, 1 << k) <= eager <= Fraction(hi, 1 << k)
    for p in PRECISIONS[:2]:                # each working precision's own enclosure
        lo, hi, k = lazy._enclosure(p)
        assert lo * Fraction(2) ** -k <= eager <= hi * Fraction(2) ** -k


@SETTINGS
@given(trees(2), trees(2))
def test_exact_zeros_and_ties_fall_back_to_the_exact_value(x, y):
    """Structurally different expressions of one value: no enclosure decides their
    difference; the exact value does."""
    (lx, _), (ly, ey) = x, y
    assert ((lx + ly) * lx - (lx * lx + ly * lx)).sign() == 0
    assert (lx * ly == ly * lx) and not (lx * ly < ly * lx)
    assert (lx + ly > lx) == (sign(ey) > 0)


FORMULAS = [lambda x, y: x * y - y * x + x, lambda x, y: (x + y) * (x - y) - x * x + y * y,
            lambda x, y: x / (y * y + 1) - 2 * x, lambda x, y: 3 - x * y / (x * x + 1),
            lambda x, y: -(x - y) * (y - x)]


@SETTINGS
@given(trees(2), trees(2), st.sampled_from(FORMULAS), st.booleans())
def test_filtered_sign_is_the_exact_sign(x, y, fn, plain):
    """filtered_sign: the formula on enclosures, else on Lazy numbers; with exact zeros
    (the second formula) and values given as Lazy numbers or as plain exact ones."""
    (lx, ex), (ly, ey) = x, y
    args = (ex, ey) if plain else (lx, ly)
    assert filtered_sign(fn, args) == sign(simplest(fn(ex, ey)))


def test_float_of_a_tie_between_two_floats_is_rounded_half_to_even():
    """A rational value exactly halfway between two floats: the enclosures never round alike;
    the exact value decides (half to even), as float(Fraction) does."""
    tie = Fraction(1) + Fraction(1, 2 ** 53)
    x = Lazy.of(sqrt(2)) * Lazy.of(sqrt(2)) / 2 - 1 + tie
    assert float(x) == float(tie) == 1.0


def test_integers_divide_exactly():
    """Ints divided by ints in the exact operations were floats (1 / 49 * 49 - 1 came out
    -1.1e-16, sign -1): a hostile probe's find."""
    x = Lazy.of(1) / 49 * 49 - 1
    assert x.sign() == 0 and x.exact() == 0 and type(x.exact()) is Fraction
    assert Lazy.of(1) / 49 * 49 == 1
    assert filtered_sign(lambda a: a / 49 * 49 - 1, [1]) == 0
    y = Lazy.of(1) / 3
    assert y == Fraction(1, 3) and hash(y) == hash(Fraction(1, 3))
    assert [v.exact() for v in flipped(3, 2, 2, 2, 2, 1, 1)] == [Fraction(31, 6), 1, 1]
    assert all(type(v.exact()) is Fraction for v in flipped(3, 2, 2, 2, 2, 1, 1))
    lo, hi = Lazy.of(sqrt(2)).interval(-3)          # as Surd.interval: any bits
    assert lo <= sqrt(2) <= hi


def test_a_flips_exact_values_share_one_inverse_of_2e(monkeypatch):
    """The exact values of a flip's new length and two areas: the formulas of
    reference/intrinsic.py with one inverse of 2e for the three (as the eager flip's
    ``_inv_2e``); each had its own, and the second area its own first area (cheese.off's exact
    ties: 4.3 s, 2.5 s with one)."""
    from ddg_oracle.reference.exact.surds import Surd
    calls = []
    real = Surd._inverse
    monkeypatch.setattr(Surd, "_inverse", lambda s: calls.append(s) or real(s))
    e, a, b, c, d = 3 + sqrt(2), 2 + sqrt(3), 3 + sqrt(3), 2 + sqrt(5), 3 + sqrt(5)
    A1, A2 = sqrt(7), sqrt(11)
    values = [v.exact() for v in flipped(e, a, b, c, d, A1, A2)]
    assert len(calls) == 1
    at_i = ((e + b - a) * A2 + (e + c - d) * A1) / (2 * e)
    assert values == [b + c - (e + b - a) * (e + c - d) / (2 * e) + 8 * A1 * A2 / e,
                      at_i, A1 + A2 - at_i]


def test_deep_chains_need_no_recursion():
    """A flip DAG is thousands of nodes deep: refining, deciding and computing the exact
    value walk it iteratively."""
    x = Lazy.of(sqrt(2))
    for k in range(5000):
        x = x + Fraction(1, k + 1) if k % 2 else x - Fraction(1, k + 2)
    eager = sqrt(2) + sum(Fraction(1, k + 1) if k % 2 else -Fraction(1, k + 2) for k in range(5000))
    assert x.sign() == sign(eager) and float(x) == float(eager)
    assert (x - eager).sign() == 0


@pytest.mark.parametrize("scale", [Fraction(1, 2 ** 3000), Fraction(2 ** 3000), Fraction(1, 3 ** 700)])
def test_tiny_and_huge_values_are_enclosed_relative_to_their_size(scale):
    x = (Lazy.of(sqrt(3)) - Lazy.of(sqrt(2))) * scale
    eager = (sqrt(3) - sqrt(2)) * scale
    assert x.sign() == 1 and (-x).sign() == -1
    lo, hi = x.interval(4000)
    assert lo <= eager <= hi and hi - lo <= Fraction(1, 2 ** 4000)
    if scale > 1:
        with pytest.raises(OverflowError):
            float(x)
    else:
        assert float(x) == float(eager) == 0.0 and math.copysign(1, float(x)) == 1


def test_a_lazy_number_mixes_with_exact_numbers_and_refuses_floats():
    x = Lazy.of(sqrt(2))
    assert 1 + x == x + 1 and 2 * x == x * 2 and 1 / x == x / 2 and sqrt(2) - x == 0
    assert Fraction(3, 2) > x > 1 and x >= sqrt(2) and abs(-x) == x
    with pytest.raises(TypeError):
        x + 0.5
    with pytest.raises(TypeError):
        Lazy.of(0.5)


# --- lazy flips: the same flips and values as the exact algorithm ---------------------------


def _same_run(m):
    d1, log1 = flip_to_delaunay(m, lazy=True)
    d2, log2 = flip_to_delaunay(m)
    assert [r.edge for r in log1] == [r.edge for r in log2]
    assert d1.triangulation == d2.triangulation
    assert d1.squared_lengths == d2.squared_lengths and list(d1.areas) == list(d2.areas)
    assert [float(x) for x in d1.squared_lengths] == [float(x) for x in d2.squared_lengths]
    assert all(a.h_after == b.h_after for a, b in zip(log1[-3:], log2[-3:]))
    return log1


@settings(max_examples=25, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(["grid", "torus"]), st.integers(0, 1 << 30))
def test_lazy_flips_equal_exact_flips_on_rational_metrics(kind, seed):
    _, m = start_surface(kind, seed)
    _same_run(m)


@settings(max_examples=6, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(["icosahedron", "torus"]), st.integers(0, 1 << 30))
def test_lazy_flips_equal_exact_flips_on_surfaces_from_R3(name, seed):
    m = random_flips(getattr(surfaces, name)().metric(), random.Random(seed), 25)
    _same_run(m)


@settings(max_examples=6, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 1 << 30))
def test_lazy_flips_one_by_one_equal_exact_flips(seed):
    """IntrinsicTriangulation(.., lazy=True).flip (its values made lazy at the flip, the
    path flip_to_delaunay does not take) against the eager flips, edge by edge."""
    from ddg_oracle.reference.intrinsic import IntrinsicTriangulation
    rng = random.Random(seed)
    base = surfaces.icosahedron().metric()
    lazy, eager = IntrinsicTriangulation(base, lazy=True), IntrinsicTriangulation(base)
    flips = 0
    for _ in range(12):
        e = rng.randrange(base.triangulation.n_edges)
        if eager.is_flippable(e):
            assert lazy.is_flippable(e)
            eager.flip(e)
            lazy.flip(e)
            flips += 1
        else:
            assert not lazy.is_flippable(e)
    a, b = lazy.surface(), eager.surface()
    assert a.triangulation == b.triangulation
    assert a.squared_lengths == b.squared_lengths and list(a.areas) == list(b.areas)
    assert flips == 0 or any(isinstance(x, Lazy) for x in a.squared_lengths)


def lifted_fan(n: int, seed: int = 0):
    """A fan of n - 2 triangles from vertex 0 over an ellipse, its vertices lifted at random:
    every flip depends on the one before (long chains, one more square root per flip)."""
    rnd = random.Random(seed)
    V = [(math.cos(2 * math.pi * k / n) * 3.0, math.sin(2 * math.pi * k / n),
          rnd.uniform(0, 0.25)) for k in range(n)]
    return PolyhedralSurface.from_arrays(V, [(0, k, k + 1) for k in range(1, n - 1)]).metric()


def test_lazy_flips_equal_exact_flips_on_a_lifted_fan():
    assert len(_same_run(lifted_fan(8))) >= 6


def _float_replay(m, log):
    """The flips of ``log`` replayed in float64 (the closed formulas of intrinsic.py)."""
    from ddg_oracle.reference.intrinsic import IntrinsicTriangulation, unfold
    w = IntrinsicTriangulation(m)
    sq = [float(x) for x in w.squared_lengths]
    areas = [float(x) for x in w.areas]
    for rec in log:
        u = unfold(w, rec.edge)
        t = w.triangulation
        h, k = u.halfedges
        ids = [t.eid[x] for x in (h, t.next(h), t.prev(h))]
        nt, pt = t.next(k), t.prev(k)
        c_, d_ = (t.eid[nt], t.eid[pt]) if not t.reversed_gluing(h) else (t.eid[pt], t.eid[nt])
        e, a, b, c, d = (sq[x] for x in (ids[0], ids[1], ids[2], c_, d_))
        A1, A2 = areas[u.faces[0]], areas[u.faces[1]]
        new = b + c + (16 * A1 * A2 - (e + b - a) * (e + c - d)) / (2 * e)
        at_i = ((e + b - a) * A2 + (e + c - d) * A1) / (2 * e)
        w.triangulation.flip(rec.edge)          # combinatorics only: the values are ours
        sq[rec.edge] = new
        areas[u.faces[0]], areas[u.faces[1]] = A1 + A2 - at_i, at_i
    return sq


def test_lazy_flips_finish_where_exact_flips_outgrow_the_term_limit():
    """A lifted 16-gon fan: the exact algorithm gives up (a square-root number of more than
    4,096 terms, after minutes; here with the limit at 256 terms, in seconds); the lazy one
    flips to Delaunay in well under a second, and its values agree with a float64 replay of
    its flips."""
    m = lifted_fan(16)
    with limits(term_limit=256), pytest.raises(TermLimitExceeded):
        flip_to_delaunay(m)
    t = time.process_time()
    d, log = flip_to_delaunay(m, lazy=True)
    assert is_delaunay(d) and len(log) >= 20
    assert time.process_time() - t < 2.0
    floats = _float_replay(m, log)
    assert all(math.isclose(float(x), y, rel_tol=1e-9)
               for x, y in zip(d.squared_lengths, floats))
