"""The certified Dirichlet enclosure (reference.dirichlet_certificate): sound against the
exact solution wherever the exact solve is affordable, failing with the right error
where the certificate does not apply, and at a size the exact solve cannot reach."""

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, strategies as st

from benchmarks.dirichlet import lifted_lattice
from ddg_oracle.reference.dirichlet import solve_dirichlet
from ddg_oracle.reference.dirichlet_certificate import CertificateFailed, certify_dirichlet
from ddg_oracle.reference.errors import BadShape, InputError, NonFiniteValue
from ddg_oracle.reference.exact import Surd
from ddg_oracle.reference.laplacian import cotan_laplacian, graph_laplacian
from ddg_oracle.reference.polyhedral import PolyhedralSurface


def _float_solution(L, c):
    """A float solve of the Dirichlet problem and of L_II v = 1 (the candidate and the
    positive vector a user would hand in)."""
    n = L.shape[0]
    A = np.array([[float(L.row(i).get(j, 0)) for j in range(n)] for i in range(n)])
    I = [i for i in range(n) if i not in c]
    B = list(c)
    u = np.zeros(n)
    u[B] = [float(c[i]) for i in B]
    v = np.zeros(n)
    if I:
        AII = A[np.ix_(I, I)]
        u[I] = np.linalg.solve(AII, -A[np.ix_(I, B)] @ u[B])
        v[I] = np.linalg.solve(AII, np.ones(len(I)))
    return u, v


@st.composite
def dirichlet_problems(draw):
    """A connected graph with nonnegative rational weights (a path keeps it connected),
    a nonempty V0 with rational values."""
    n = draw(st.integers(2, 9))
    weight = st.fractions(min_value=Fraction(1, 8), max_value=8, max_denominator=16)
    edges = [(i, i + 1, draw(weight)) for i in range(n - 1)]
    for _ in range(draw(st.integers(0, 2 * n))):
        i, j = draw(st.integers(0, n - 1)), draw(st.integers(0, n - 1))
        edges.append((i, j, draw(st.one_of(st.just(Fraction(0)), weight))))
    V0 = draw(st.sets(st.integers(0, n - 1), min_size=1, max_size=n))
    c = {v: draw(st.fractions(min_value=-10, max_value=10, max_denominator=12)) for v in V0}
    return graph_laplacian(n, edges), c


@given(dirichlet_problems(), st.lists(st.floats(-1e-3, 1e-3), min_size=9, max_size=9))
def test_the_exact_solution_lies_in_the_enclosure(problem, noise):
    L, c = problem
    exact = solve_dirichlet(L, c)
    u, v = _float_solution(L, c)
    u = u + np.array(noise[:len(u)])                      # a worse candidate: still sound
    e = certify_dirichlet(L, c, u.tolist(), v.tolist())
    for i in range(L.shape[0]):
        assert e.contains(i, exact[i]), (i, exact[i], e.interval(i))
        if i in c:
            assert e.radius[i] == 0 and e.center[i] == c[i]


@given(dirichlet_problems())
def test_the_exact_solution_as_candidate_leaves_only_the_enclosure_width(problem):
    # the residual of the exact solution is 0; its enclosure is a few units of 2^-2bits
    # per entry (the weights 1/3, ... are not dyadic), so t and the radii are that small
    L, c = problem
    exact = solve_dirichlet(L, c)
    _, v = _float_solution(L, c)
    e = certify_dirichlet(L, c, exact, v.tolist())
    assert e.scale < Fraction(1, 2 ** 80)
    dyadic = certify_dirichlet(graph_laplacian(3, [(0, 1, 1), (1, 2, 3)]), {0: 0, 2: 4},
                               [0, 3, 4], [0, 1, 0])
    assert dyadic.scale == 0 and dyadic.radius == [0, 0, 0]


def test_the_radius_follows_the_residual_on_a_path():
    # Z (Example 3.1) with V0 = {0, 4}: u* is linear, u*(2) = 2; a candidate off by 1 at
    # vertex 2 has residual 2 there (and -1 at 1 and 3); v = (0, 3/2, 2, 3/2, 0) solves
    # L_II v = 1, so t = 2 and the radius at vertex 2 is 4 >= |3 - 2|
    L = graph_laplacian(5, [(i, i + 1, 1) for i in range(4)])
    e = certify_dirichlet(L, {0: 0, 4: 4}, [0, 1, 3, 3, 4], [0, 1.5, 2, 1.5, 0])
    assert e.scale == 2 and e.interval(2) == (-1, 7) and e.contains(2, 2)
    assert not e.contains(2, 8)


def test_irrational_weights_against_the_exact_solve():
    # a lifted float lattice (a planar mesh would have rational weights: 16 area^2 is a
    # square there): one unknown and two apart, solved exactly (Surd quotients), lie in the
    # enclosures of a float solve (two adjacent unknowns take seconds exactly, three minutes:
    # python -m benchmarks dirichlet)
    V, F, boundary = lifted_lattice(4)
    L = cotan_laplacian(PolyhedralSurface.from_arrays(V, F))
    assert any(isinstance(x, Surd) for x in L.row(6).values())
    for unknowns in ([6], [6, 18]):
        c = {i: Fraction(i * i % 7 - 3, 7) for i in range(len(V)) if i not in unknowns}
        exact = solve_dirichlet(L, c)
        u, v = _float_solution(L, c)
        e = certify_dirichlet(L, c, u.tolist(), v.tolist())
        for i in unknowns:
            assert e.contains(i, exact[i])
            assert e.radius[i] < Fraction(1, 10 ** 12)        # a float solve is that close


def test_a_negative_weight_between_unknowns_is_named():
    # a flat kite with its long diagonal 0-2: the corners 1 and 3 opposite it are obtuse,
    # so the diagonal's cotan weight is negative (L[0, 2] > 0)
    s = PolyhedralSurface.from_arrays([(0, 0, 0), (2, -0.5, 0), (4, 0, 0), (2, 0.5, 0)],
                                      [[0, 1, 2], [0, 2, 3]])
    L = cotan_laplacian(s)
    assert L.row(0)[2] > 0
    with pytest.raises(CertificateFailed, match=r"L\[0, 2\]") as err:
        certify_dirichlet(L, {1: 0, 3: 1}, [0, 0, 0, 0], [1, 1, 1, 1])
    assert err.value.where == (0, 2)
    # with 0 in V0 that weight no longer joins two unknowns: vertex 2 alone is certified
    c = {0: 0, 1: 0, 3: 1}
    e = certify_dirichlet(L, c, [0, 0, 0.5, 1], [0, 0, 1, 0])
    assert e.contains(2, solve_dirichlet(L, c)[2])


def test_a_vector_that_proves_nothing_is_refused():
    # v = (0, 1, 100, 1, 0) on the path: (L v)(1) = 2 - 100 < 0
    L = graph_laplacian(5, [(i, i + 1, 1) for i in range(4)])
    with pytest.raises(CertificateFailed, match="vertex 1") as err:
        certify_dirichlet(L, {0: 0, 4: 4}, [0, 1, 2, 3, 4], [0, 1, 100, 1, 0])
    assert err.value.where == (1,)
    # a component of unknowns without an edge to V0 has no such v at all
    L2 = graph_laplacian(4, [(0, 1, 1), (2, 3, 1)])
    with pytest.raises(CertificateFailed, match="no edge to V0"):
        certify_dirichlet(L2, {0: 1}, [1, 1, 0, 0], [1, 1, 1, 1])


def test_bad_input_gets_a_typed_error():
    L = graph_laplacian(3, [(0, 1, 1), (1, 2, 1)])
    with pytest.raises(BadShape):
        certify_dirichlet(L, {0: 0}, [0, 0], [1, 1, 1])
    with pytest.raises(InputError, match="must be > 0"):
        certify_dirichlet(L, {0: 0}, [0, 0, 0], [1, 0, 1])
    with pytest.raises(NonFiniteValue):
        certify_dirichlet(L, {0: 0}, [0, float("nan"), 0], [1, 1, 1])
    with pytest.raises(InputError, match="V0 is empty"):
        certify_dirichlet(L, {}, [0, 0, 0], [1, 1, 1])
    with pytest.raises(InputError, match="not a vertex"):
        certify_dirichlet(L, {3: 0}, [0, 0, 0], [1, 1, 1])


def test_a_lattice_too_large_for_the_exact_solve_is_certified():
    # 31 x 31 lifted lattice: 841 unknowns with irrational weights, far beyond exact
    # elimination (3 adjacent unknowns already take minutes); the certificate needs the
    # float solves only
    V, F, boundary = lifted_lattice(30)
    L = cotan_laplacian(PolyhedralSurface.from_arrays(V, F))
    c = {v: Fraction(v % 7) for v in boundary}
    u, v = _float_solution(L, c)
    e = certify_dirichlet(L, c, u.tolist(), v.tolist())
    assert 0 < e.scale and max(e.radius) < Fraction(1, 10 ** 9)
    # a candidate off by 1e-6 at one vertex: still sound, and the radius grows to cover it
    u[500] += 1e-6
    worse = certify_dirichlet(L, c, u.tolist(), v.tolist())
    assert worse.radius[500] >= Fraction(1, 10 ** 6) - e.radius[500]
