"""properties/memo.py: values derived from an example are shared only where they are the
same -- per example content and, for bounds, per machine epsilon."""

import contextvars

import pytest

import numpy as np

from ddg_oracle.properties import memo
from ddg_oracle.protocol import methods as protocol
from ddg_oracle.properties.harness import Exact
from ddg_oracle.properties.strategies import mesh_case


def _tetrahedron():
    V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    return mesh_case(V, [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)], "tetrahedron")


def test_equal_cases_share_one_exact_reference():
    memo.clear()
    a, b = _tetrahedron(), _tetrahedron()
    assert a is not b and Exact.of(a) is Exact.of(b)


def test_the_bounds_of_a_float32_implementation_are_not_a_float64_ones():
    memo.clear()
    case = _tetrahedron()
    B64 = Exact.of(case).B

    def as_float32():
        protocol._epsilon.set(2.0 ** -23)
        return Exact.of(case).B

    B32 = contextvars.copy_context().run(as_float32)
    assert Exact.of(case).B is B64                 # float64 again: the float64 bounds
    nz = B64 > 0
    assert nz.any() and np.allclose(B32[nz] / B64[nz], 2.0 ** 29)


def _drawn(strategy, n, monkeypatch=None):
    """The content of the first ``n`` examples of a derandomized run of ``strategy``."""
    from hypothesis import HealthCheck, given, settings
    seen = []

    @settings(max_examples=n, derandomize=True, database=None, deadline=None,
              suppress_health_check=list(HealthCheck))
    @given(strategy)
    def run(case):
        seen.append((case.content, case.recipe, case.mesh))

    run()
    return seen


@pytest.mark.parametrize("name", ["jittered", "intrinsic", "closed", "stars", "convex"])
def test_a_drawn_example_is_the_one_built_without_the_memo(name, monkeypatch):
    # the building steps of a drawn surface are kept per key (memo.DRAWN): a key missing
    # one drawn choice would hand one example another's surface.  The same derandomized
    # stream drawn with the table, then with it bypassed, gives the same examples
    from ddg_oracle.properties import stars, strategies
    strategy = {"jittered": strategies.jittered_surfaces(),
                "intrinsic": strategies.jittered_surfaces(intrinsic=True),
                "closed": strategies.jittered_surfaces(closed=True, far=False),
                "stars": stars.vertex_stars(),
                "convex": stars.convex_polyhedra()}[name]
    memo.clear()
    with_table = _drawn(strategy, 100)
    assert len(memo.DRAWN) > 0                      # the steps were kept ...
    again = _drawn(strategy, 100)                   # ... and a warm table changes nothing
    monkeypatch.setattr(memo.DRAWN, "shared", lambda key, compute: compute())
    without = _drawn(strategy, 100)
    assert with_table == again == without


def test_the_drawn_table_is_bounded():
    table = memo.Table(3)
    for k in range(10):
        table.shared(k, lambda k=k: k * k)
    assert len(table) == 3 and table.shared(9, lambda: None) == 81
    assert table.shared(0, lambda: "again") == "again"      # dropped, computed again


def test_what_a_float32_implementation_derived_is_not_handed_to_a_float64_one():
    # a derived value may read the checked implementation's input format (a moved copy of
    # the example is rounded to it) and machine epsilon (its bounds): both are in the key
    from ddg_oracle.properties.precision import input_format, inputs_at
    memo.clear()
    case = _tetrahedron()

    def seen(c):
        return input_format().name, protocol.eps()

    with inputs_at(2.0 ** -23), protocol.at_machine_epsilon(2.0 ** -23):
        assert case.derived("seen", seen) == ("float32", 2.0 ** -23)
    assert case.derived("seen", seen) == ("float64", 2.0 ** -52)


def test_what_one_object_derived_is_shared_across_contexts():
    # memo.of: the exact values of one object (a float32 reading is another object), once
    # whatever the checked implementation's format and epsilon (its bounds are not kept
    # there): a float32 reading's Delaunay flips served its float64 views and float32 bounds
    from ddg_oracle.properties.precision import inputs_at
    memo.clear()
    calls = []

    class Surface:                                   # memo.of keeps values per live object
        pass

    def of(obj):
        calls.append(obj)
        return len(calls)

    s, t = Surface(), Surface()
    with inputs_at(2.0 ** -23), protocol.at_machine_epsilon(2.0 ** -23):
        assert memo.of(of, s) == 1
    assert memo.of(of, s) == 1 and memo.of(of, t) == 2 and calls == [s, t]


def test_every_property_passes_the_float64_reference_after_its_float32_twin():
    """The same seed, so the same examples where float32 holds their coordinates, checked in
    one process for the float32 reference, then the float64 one: both pass (T2.5 once failed the float64 reference with the float32 rounding of its moved
    copy, kept from the float32 task: a false alarm of ``ddg-oracle check`` whenever a
    worker ran MeshLib before libigl)."""
    from hypothesis import Phase, settings
    from ddg_oracle.oracles.exact_reference import ReferenceImplementation
    from ddg_oracle.properties import PROPERTIES
    from ddg_oracle.properties.profiles import profile
    from ddg_oracle.properties.runner import NOT_APPLICABLE, PASSED, run_property

    class Reference32(ReferenceImplementation):
        name, machine_epsilon = "reference-f32", 2.0 ** -23

    s = settings(profile("default"), max_examples=6,
                 phases=(Phase.explicit, Phase.generate), database=None)
    memo.clear()
    wrong = []
    for pid, p in PROPERTIES.items():
        for impl in (Reference32(), ReferenceImplementation()):
            r = run_property(p, impl, s, 1)
            if r.status not in (PASSED, NOT_APPLICABLE):
                wrong.append(f"{pid} {impl.name}: {r.status} {r.failure or r.error}")
    assert not wrong, "\n".join(wrong)


def test_a_cases_exact_values_are_found_again_without_hashing_its_positions():
    """Exact.of hashes a case's positions once (a million Fractions take seconds to hash,
    and every check of a mesh file asks for its exact values several times)."""
    from fractions import Fraction

    from ddg_oracle.properties.example import Example

    class Counted(Fraction):
        calls = 0

        def __hash__(self):
            Counted.calls += 1
            return super().__hash__()
    memo.clear()
    P = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    case = Example.of_mesh([tuple(Counted(x) for x in p) for p in P],
                           [(0, 1, 2), (0, 3, 1), (1, 3, 2), (0, 2, 3)], "counted")
    first = Exact.of(case)
    seen = Counted.calls
    assert Exact.of(case) is first and Exact.of(case.with_data(recipe="again")) is first
    assert Counted.calls == seen
