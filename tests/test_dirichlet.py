"""Chapter 3 reference, section 3.2 and 3.4: the Dirichlet problem and its theorems (T3.1 / R3.2,
T3.2, C3.3, C3.4 / T3.5, R3.3, P3.10) and the minimal surface iteration (A3.6), exactly."""

from fractions import Fraction

import pytest
from hypothesis import given, strategies as st

from ddg_oracle.properties.strategies import obtuse_meshes, planar_meshes, weighted_graphs, with_boundary
from ddg_oracle.reference.dirichlet import (SingularDirichletProblem, directional_derivative,
                                 energy_gradient, energy_increase, has_positive_weights,
                                 is_constant_on_components, is_harmonic_at, kernel_dimension,
                                 matrix_components, neighbour_convex_combination,
                                 satisfies_maximum_principle, separates, solve_dirichlet,
                                 strict_interior_extrema)
from ddg_oracle.reference.laplacian import (cotan_laplacian, cotan_weights, dirichlet_energy,
                                 dirichlet_energy_pl, graph_laplacian)
from ddg_oracle.reference.minimal import (area_decrease_certificate, area_enclosure, figure_3_7_star,
                               minimal_surface_iteration, minimal_surface_step)
from ddg_oracle.reference.polyhedral import PolyhedralSurface


def _vector(n):
    return st.lists(st.integers(-6, 6).map(Fraction), min_size=n, max_size=n)


def _dot(a, b):
    return sum((x * y for x, y in zip(a, b)), Fraction(0))


# --- T3.1 / R3.2 -------------------------------------------------------------------------------


@given(weighted_graphs(positive=False, connected=False), st.data())
def test_T3_1_R3_2_gradient_of_the_energy_is_the_laplacian(g, data):
    L = graph_laplacian(g.n, g.edges)
    f, phi = list(g.values), data.draw(_vector(g.n))
    E = lambda h: dirichlet_energy(g.edges, h)        # the edge sum, no matrix
    Lf = energy_gradient(L, f)
    assert directional_derivative(E, f, phi) == _dot(phi, Lf)            # (3.1)
    t = data.draw(st.integers(-3, 3).map(Fraction))
    # the expansion in the proof: E(f + t phi) = E(f) + t sum phi Lap f + t^2 E(phi)
    assert E([a + t * b for a, b in zip(f, phi)]) == E(f) + t * _dot(phi, Lf) + t * t * E(phi)
    for i in range(g.n):                               # dE/df(i) = (Lap f)(i)
        e = [Fraction(int(j == i)) for j in range(g.n)]
        assert directional_derivative(E, f, e) == Lf[i]


@given(weighted_graphs(positive=True))
def test_T3_1_critical_points_on_F_V0_c_are_the_harmonic_functions(g):
    L = graph_laplacian(g.n, g.edges)
    c = {v: g.values[v] for v in g.boundary}
    f = solve_dirichlet(L, c)
    E = lambda h: dirichlet_energy(L, h)
    interior = [i for i in range(g.n) if i not in c]
    for i in interior:
        assert is_harmonic_at(L, f, i)
        e = [Fraction(int(j == i)) for j in range(g.n)]
        assert directional_derivative(E, f, e) == 0               # critical on F_{V0,c}
    # a function of F_{V0,c} that is not harmonic somewhere is not critical there
    if interior:
        i = interior[0]
        h = list(f)
        h[i] += 1
        e = [Fraction(int(j == i)) for j in range(g.n)]
        assert not is_harmonic_at(L, h, i) and directional_derivative(E, h, e) != 0


# --- T3.2, C3.3 -----------------------------------------------------------------------------------


@given(weighted_graphs(positive=True))
def test_T3_2_maximum_principle_for_positive_weights(g):
    L = graph_laplacian(g.n, g.edges)
    assert has_positive_weights(L)
    f = solve_dirichlet(L, {v: g.values[v] for v in g.boundary})
    assert satisfies_maximum_principle(L, f, g.boundary)
    assert strict_interior_extrema(L, f, g.boundary) == []


def test_T3_2_fails_with_a_negative_weight():
    # path 0 - 1 - 2 with weights 3 and -1: f(1) = (3 f(0) - f(2)) / 2
    L = graph_laplacian(3, [(0, 1, 3), (1, 2, -1)])
    f = solve_dirichlet(L, {0: 1, 2: 0})
    assert f[1] == Fraction(3, 2)                       # above both boundary values
    assert not satisfies_maximum_principle(L, f, [0, 2])
    assert strict_interior_extrema(L, f, [0, 2]) == [1]


@given(weighted_graphs(positive=True, connected=False))
def test_C3_3_liouville_harmonic_everywhere_means_locally_constant(g):
    L = graph_laplacian(g.n, g.edges)
    comps = matrix_components(L)
    assert kernel_dimension(L) == len(comps)
    # Lap f = 0 everywhere with f fixed at one vertex per component: only constants
    anchors = {comp[0]: g.values[comp[0]] for comp in comps}
    f = solve_dirichlet(L, anchors)
    assert all(x == 0 for x in L.matvec(f))
    assert is_constant_on_components(L, f)
    assert [f[comp[-1]] for comp in comps] == [g.values[comp[0]] for comp in comps]


# --- C3.4 / T3.5 -----------------------------------------------------------------------------------


@given(weighted_graphs(positive=True, connected=False), st.data())
def test_C3_4_T3_5_unique_solution_is_the_unique_minimiser(g, data):
    L = graph_laplacian(g.n, g.edges)
    c = {v: g.values[v] for v in g.boundary}
    f = solve_dirichlet(L, c)
    assert all(f[v] == c[v] for v in c)
    assert all(is_harmonic_at(L, f, i) for i in range(g.n) if i not in c)
    phi = [Fraction(0) if v in c else x for v, x in enumerate(data.draw(_vector(g.n)))]
    gain = energy_increase(L, f, phi)
    assert gain == dirichlet_energy(L, phi) >= 0                       # T3.5
    assert (gain == 0) == all(x == 0 for x in phi)      # E(phi) = 0 iff phi = 0 on F_{V0,0}
    # uniqueness: relabel the vertices (another elimination order), same solution
    perm = list(reversed(range(g.n)))
    L2 = graph_laplacian(g.n, [(perm[i], perm[j], w) for i, j, w in g.edges])
    f2 = solve_dirichlet(L2, {perm[v]: x for v, x in c.items()})
    assert [f2[perm[v]] for v in range(g.n)] == f


def test_singular_problems_name_the_component():
    L = graph_laplacian(5, [(0, 1, 1), (2, 3, 1), (3, 4, 2)])
    with pytest.raises(SingularDirichletProblem) as err:
        solve_dirichlet(L, {0: 1})
    assert err.value.component == (2, 3, 4) and "[2, 3, 4]" in str(err.value)
    with pytest.raises(SingularDirichletProblem):
        solve_dirichlet(L, {})
    # mixed signs can make the system singular although every component has V0
    M = graph_laplacian(3, [(0, 1, 1), (1, 2, -1)])          # (Lap f)(1) = f(2) - f(0)
    with pytest.raises(SingularDirichletProblem, match="no pivot") as err:
        solve_dirichlet(M, {0: 0, 2: 1})
    assert err.value.component == (1,)


def test_vector_valued_boundary_values_and_term_limit_guard():
    L = graph_laplacian(3, [(0, 1, 1), (1, 2, 1)])
    assert solve_dirichlet(L, {0: (0, 2), 2: (4, 0)})[1] == (2, 1)
    from ddg_oracle.reference.errors import TermLimitExceeded
    s = PolyhedralSurface.from_arrays(
        [(0, 0, 0), (3, 0, 1), (1, 2, 0), (-2, 1, 1), (-1, -2, 0), (2, -3, 1)],
        [(0, 1, 2), (0, 2, 3), (0, 3, 4), (0, 4, 5), (0, 5, 1)])
    with pytest.raises(TermLimitExceeded):
        solve_dirichlet(s, {1: 0, 3: 1}, term_limit=2)


# --- R3.3 -------------------------------------------------------------------------------------------


@given(with_boundary(obtuse_meshes()))
def test_R3_3_cotan_dirichlet_problem_is_uniquely_solvable_despite_negative_weights(case):
    s = case.surface
    L = cotan_laplacian(s)
    c = {v: case.values[v] for v in case.boundary}
    f = solve_dirichlet(L, c, term_limit=1 << 14)          # no SingularDirichletProblem
    assert all(is_harmonic_at(L, f, i) for i in range(len(f)) if i not in c)
    phi = [Fraction(0) if v in c else x for v, x in enumerate(case.second)]
    assert energy_increase(L, f, phi) == dirichlet_energy_pl(s, phi) >= 0
    assert kernel_dimension(L) == len(s.triangulation.components())


def test_R3_3_a_negative_weight_breaks_the_maximum_principle_but_not_uniqueness():
    s, _, _ = figure_3_7_star()
    L = cotan_laplacian(s)
    assert cotan_weights(s)[0] < 0 and not has_positive_weights(L)
    f = solve_dirichlet(L, {v: Fraction(int(v == 1)) for v in range(1, 6)})
    assert f[0] < 0                                        # below every boundary value
    assert not satisfies_maximum_principle(L, f, range(1, 6))
    assert kernel_dimension(L) == 1


# --- P3.10 --------------------------------------------------------------------------------------------


@given(weighted_graphs(positive=True), st.data())
def test_P3_10_harmonic_value_is_a_convex_combination_of_the_neighbours(g, data):
    L = graph_laplacian(g.n, g.edges)
    i = data.draw(st.integers(0, g.n - 1))
    if not L.row(i):
        return
    values = {v: (Fraction(v), g.values[v], Fraction(v * v)) for v in range(g.n) if v != i}
    u = solve_dirichlet(L, values)                  # harmonic at i, u: V -> R^3
    lam = neighbour_convex_combination(L, i)
    assert all(x > 0 for x in lam.values()) and sum(lam.values()) == 1
    assert tuple(sum((lam[j] * u[j][k] for j in lam), Fraction(0)) for k in range(3)) == u[i]


@given(st.integers(3, 6), st.integers(1, 3), st.integers(1, 4))
def test_P3_10_fails_for_cotan_weights_figure_3_7(spike, shoulder, lift):
    s, new, certified = figure_3_7_star(spike, shoulder, lift)
    nu = cotan_weights(s)[0]                               # the edge from the centre to the spike
    assert certified == (nu < 0)
    if certified:
        assert separates((0, 0, -1), new[0], new[1:])
        assert any(x < 0 for x in neighbour_convex_combination(cotan_laplacian(s), 0).values())
    assert area_decrease_certificate(s, new).holds


def test_P3_10_counterexample_exists_with_the_defaults():
    s, new, certified = figure_3_7_star()
    assert certified and new[0][2] < 0


# --- A3.6 ---------------------------------------------------------------------------------------------


_RINGS = {4: [(2, 0), (0, 2), (-2, 0), (0, -2)],
          5: [(2, 0), (1, 2), (-2, 1), (-2, -1), (1, -2)],
          6: [(2, 0), (1, 2), (-1, 2), (-2, 0), (-1, -2), (1, -2)]}


def _fan(k, h, zs):
    ring = [(x, y, z) for (x, y), z in zip(_RINGS[k], zs)]
    return PolyhedralSurface.from_arrays([(0, 0, h)] + ring,
                                         [(0, 1 + t, 1 + (t + 1) % k) for t in range(k)])


def _small_surfaces():
    """Small disks in R^3 with one interior vertex: fans with a lifted centre and 2 x 2 grids
    with heights.  (With Surd weights the exact solve grows like 2^F in the number of faces
    around the unknowns; see ddg_oracle.reference.minimal.)"""
    fan = st.builds(_fan, st.integers(4, 6), st.integers(-2, 3),
                    st.lists(st.integers(-1, 1), min_size=6, max_size=6))
    grid = planar_meshes(heights=True, min_size=2, max_size=2).map(lambda c: c.surface)
    return st.one_of(fan, grid)


@given(_small_surfaces())
def test_A3_6_one_step_does_not_increase_the_area(s):
    new = minimal_surface_step(s)
    t = s.triangulation
    L = cotan_laplacian(s)
    for i in range(t.n_vertices):
        if not t.is_boundary_vertex(i):
            assert all(x == 0 for x in (sum((v * new[j][k] for j, v in L.row(i).items()), Fraction(0))
                                        for k in range(3)))
        else:
            assert tuple(new[i]) == s.positions[i]
    cert = area_decrease_certificate(s, new)
    assert cert.holds and cert.energy_ok and cert.faces_ok
    e_lo, e_hi = cert.energy_after                             # enclosure of E_S(f)
    assert e_lo <= e_hi and (e_hi < cert.area_before or not cert.strict)
    lo, hi = area_enclosure(t, new, bits=40)
    assert lo <= e_hi                                          # A(f(S)) <= E_S(f)
    assert lo <= cert.area_before                              # the enclosure agrees
    again = area_decrease_certificate(s, s.positions)          # f = id: no decrease, E = A
    assert again.holds and not again.strict
    a_lo, a_hi = again.area_before.interval(64)                # enclosures of one number meet
    assert again.energy_after[0] <= a_hi and a_lo <= again.energy_after[1]


def test_A3_6_iteration_areas_never_increase():
    s = PolyhedralSurface.from_arrays(
        [(0, 0, 2), (2, 0, 0), (1, 2, 1), (-1, 2, 0), (-2, 0, 1), (-1, -2, 0), (1, -2, 1)],
        [(0, 1 + t, 1 + (t + 1) % 6) for t in range(6)])
    run = minimal_surface_iteration(s, 3, bits=48)
    assert all(c.holds and c.strict for c in run.certificates)
    assert all(b < a for a, b in zip(run.areas, run.areas[1:]))       # exact Surd comparisons
    # the planar case is a fixed point: one step leaves a planar star where it is
    flat = PolyhedralSurface.from_arrays([(0, 0, 0), (2, 0, 0), (0, 2, 0), (-2, 0, 0), (0, -2, 0)],
                                         [(0, 1, 2), (0, 2, 3), (0, 3, 4), (0, 4, 1)])
    assert minimal_surface_step(flat) == [tuple(p) for p in flat.positions]
