"""No false positives: the exact reference (declared float64, and declared float32), a
correct float64 implementation (numpy, the plain way) and a panel of honest float
implementations at float64 and float32 (tests/honest_panel.py: atan2 of cross and dot,
the law of cosines, Kahan's half-angle formula and sorted Heron, cot = dot / |cross| or
from the lengths, float flips on lengths, float in-circle flips) pass every property, on
the widest strategies (slivers, high valence, several components, isolated and
duplicated vertices, reversed faces, Möbius strips, any order, any scale).  A failure
here is a wrong bound or a wrong expected value, never a bug of the implementation
(issue 40: "no false alarm").

Under the ci profile (derandomized, 60 examples, shrinking on) where CI runs (``$CI``
set, as for the rest of the suite: tests/conftest.py).  Under default on a developer's
machine, the reference and numpy run FULL_EXAMPLES examples per property, the float32
reference and the panel PANEL_EXAMPLES, without the shrink phase (a smoke test: the
whole file stays within about a minute on two cores, the default suite within its 5
minutes); CI and the opt-in sweep run them in full.

The thorough sweep (1,000 examples per property and implementation, no budget: about
two hours on two cores) is opt-in: ``DDG_THOROUGH_PANEL=1 pytest
tests/test_false_positives.py -k thorough``.  Its float32 half (``-k "thorough and f32"``:
the float32 reference and the three float32 panel members, 174 tests) ran at 9d32ef7 on
2026-12-06 in 33 min on two cores (nice 19, beside other work): 173 passed, and one false
alarm, fixed with its test below (non-finite entries after flips across a face beyond
float resolution).  Its float64 half (``-k "thorough and not f32 and not reference"``: the
three float64 panel members, 126 tests) at 60df306: 126 passed in 20 min; the float32
T2.7, C3.3 and R3.3, whose bounds b6580a8 tightened, again there: 12 passed."""

import os

import pytest
from hypothesis import Phase, settings

from examples.numpy_mesh import NumpyMesh
from ddg_oracle.oracles.exact_reference import ReferenceImplementation
from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.profiles import profile
from ddg_oracle.protocol.methods import capabilities
from ddg_oracle.properties.runner import NOT_APPLICABLE, PASSED, TIE, run_property

from tests.honest_panel import PANEL


class Reference32(ReferenceImplementation):
    """The exact reference's correctly rounded answers, declared float32: its inputs are
    float32 numbers (the strategies round to the declared format) and its bounds float32
    ones; it is at least as accurate as any float32 implementation can be."""
    name = "reference-f32"
    machine_epsilon = 2.0 ** -23


PROFILE = "ci" if os.environ.get("CI") else "default"
#: examples per property for the float32 reference and the panel under the default profile
PANEL_EXAMPLES = 5
#: examples per property for the reference and numpy under the default profile (the
#: profile's own is 25).  Not derandomized: every developer run draws a fresh sample, and
#: CI runs all of them at 60 derandomized examples (the ci profile, unchanged), so 6 keeps
#: this a smoke test of the same properties on the same strategies (the reference alone
#: took ~50 of the file's ~70 CPU-s at 25; at 10 the file took 32 of the suite's 560
#: test-seconds, and the suite ran just over its 5 minutes).
#: What each test asserts is unchanged: the status is in ALLOWED and at least one example ran.
FULL_EXAMPLES = 6
#: no shrink phase under default: a passing run never shrinks, and a FAILED, crashed or
#: undecided result (not in ALLOWED) is that status already on the first failing example,
#: so the test fails the same, showing the unshrunk input; what is skipped is shrinking a
#: tie (an allowed status; unbudgeted here, once 27 s on one panel property).  ci keeps it.
NO_SHRINK = (Phase.explicit, Phase.reuse, Phase.generate)
IMPLEMENTATIONS = {"reference": ReferenceImplementation(), "numpy": NumpyMesh(),
                   "reference-f32": Reference32(),
                   **{name: cls() for name, cls in PANEL.items()}}
# what each may answer: the reference decides exact ties exactly; floats may round a tie
# (an exactly flat vertex, a cocircular quad) either way, which is reported as a tie, and
# so may a face whose float area is beyond the format's resolution
ALLOWED = {name: {PASSED, TIE, NOT_APPLICABLE} for name in IMPLEMENTATIONS}
ALLOWED["reference"] = ALLOWED["reference-f32"] = {PASSED, NOT_APPLICABLE}
FULL = {"reference", "numpy"}           # FULL_EXAMPLES under default, the ci profile in CI


def _applicable(name):
    impl = IMPLEMENTATIONS[name]
    return [pid for pid, p in PROPERTIES.items()
            if p.applies_to(capabilities(impl))]


def _settings(name, profile_name=PROFILE):
    s = profile(profile_name)
    if profile_name == "default":
        return settings(s, max_examples=FULL_EXAMPLES if name in FULL else PANEL_EXAMPLES,
                        phases=NO_SHRINK)
    return s


@pytest.mark.parametrize("name, pid", [(n, pid) for n in IMPLEMENTATIONS for pid in _applicable(n)])
def test_no_false_positive(name, pid):
    r = run_property(PROPERTIES[pid], IMPLEMENTATIONS[name], _settings(name))
    assert r.status in ALLOWED[name], f"{pid} on {name}: {r.status}\n{r.failure or r.error}"
    assert r.examples > 0 or r.status == NOT_APPLICABLE


@pytest.mark.skipif(not os.environ.get("DDG_THOROUGH_PANEL"),
                    reason="the thorough sweep is opt-in: DDG_THOROUGH_PANEL=1")
@pytest.mark.parametrize("name, pid", [(n, pid) for n in IMPLEMENTATIONS
                                       for pid in _applicable(n) if n not in FULL])
def test_no_false_positive_thorough(name, pid):
    r = run_property(PROPERTIES[pid], IMPLEMENTATIONS[name], profile("thorough"))
    assert r.status in ALLOWED[name], f"{pid} on {name}: {r.status}\n{r.failure or r.error}"


def test_the_panel_reaches_every_numeric_method_of_the_protocol():
    """Not vacuous: the panel defines every protocol method whose answer is a float
    computation (topology is integers), at both precisions."""
    from ddg_oracle.protocol.methods import METHODS
    numeric = set(METHODS) - {"euler_characteristic", "boundary_loops", "is_orientable", "genus"}
    for name, cls in PANEL.items():
        assert numeric <= capabilities(cls()), (name, numeric - capabilities(cls()))
    assert {getattr(cls, "machine_epsilon", 2.0 ** -52) for cls in PANEL.values()} == {
        2.0 ** -52, 2.0 ** -23}


def test_the_float32_reference_passes_R3_3_on_a_single_triangle():
    """The false alarm of issue 40: L_II's exact smallest eigenvalue (0.025 on the unit
    right triangle with V0 = [0]) lies below the float32 Weyl bound (0.09); the check
    decides the exact eigenvalue first and fails only a matrix that cannot be within the
    entry bounds of the exact one."""
    from fractions import Fraction
    from ddg_oracle.properties.runner import FAILED, run_on_example
    from ddg_oracle.properties.strategies import Example
    tri = ((Fraction(0),) * 3, (Fraction(1), Fraction(0), Fraction(0)),
           (Fraction(0), Fraction(1), Fraction(0)))
    case = Example.of_mesh(tri, ((0, 1, 2),), "unit right triangle", boundary=(0,),
                           values=(Fraction(1),))
    assert run_on_example(PROPERTIES["R3.3"], Reference32(), case, "triangle").status == PASSED

    class Indefinite(Reference32):          # L_II with a negative eigenvalue: caught
        def cotan_laplacian(self, V, F):
            L = super().cotan_laplacian(V, F).toarray()
            L[1, 1] = L[2, 2] = -1.0
            import scipy.sparse as sp
            return sp.csr_matrix(L)
    assert run_on_example(PROPERTIES["R3.3"], Indefinite(), case, "triangle").status == FAILED


def test_the_numpy_implementation_is_checked_on_the_curvature_and_laplacian_properties():
    # the test above is not vacuous: the numpy implementation reaches these properties
    assert {"D2.2", "R2.4", "T2.6", "D2.6", "D2.3", "R2.5", "D3.1", "T3.6", "C3.3",
            "T3.9"} <= set(_applicable("numpy"))


def test_an_infinite_cotangent_is_a_tie_only_beyond_float_resolution():
    """A triangle whose float cross product is exactly 0 although its exact area is not
    (2^-104 against edges of length ~1.4): numpy's cotangent is infinite, which rounding
    decided (a tie); an implementation with NaN on a plain triangle fails, naming the entry."""
    from fractions import Fraction
    import numpy as np
    from ddg_oracle.properties.runner import FAILED, run_on_example
    from ddg_oracle.properties.strategies import Example
    e = 2.0 ** -52
    pts = [(0.0, 0.0, 0.0), (1.0, 1.0 + e, 0.0), (1.0 + e, 1.0 + 2 * e, 0.0)]
    u, v = np.subtract(pts[1], pts[0]), np.subtract(pts[2], pts[0])
    assert np.cross(u, v)[2] == 0                   # in floats: degenerate
    exact = [tuple(Fraction(x) for x in p) for p in pts]
    cap = Example.of_mesh(tuple(exact), ((0, 1, 2),), "cross product below float resolution")
    r = run_on_example(PROPERTIES["T3.6"], NumpyMesh(), cap, "cap")
    assert r.status == TIE and "beyond float resolution" in str(r.failure)

    class NaNWeights(NumpyMesh):
        def cotan_laplacian(self, V, F):
            L = super().cotan_laplacian(V, F).tolil()
            L[0, 1] = np.nan
            return L.tocsr()
    plain = Example.of_mesh(((Fraction(0),) * 3, (Fraction(1), Fraction(0), Fraction(0)),
                      (Fraction(0), Fraction(1), Fraction(0))), ((0, 1, 2),), "triangle")
    r = run_on_example(PROPERTIES["T3.6"], NaNWeights(), plain, "triangle")
    assert r.status == FAILED and "non-finite entries (first: (0, 1))" in str(r.failure)


class Reference16(ReferenceImplementation):
    """The exact reference declared float16 (a format the strategies know: its inputs are
    float16 numbers)."""
    name = "reference-f16"
    machine_epsilon = 2.0 ** -10


def test_our_own_float64_bounds_do_not_take_the_implementations_epsilon():
    """T2.7's quadrature and C3.3 / R3.3's spectrum of the exact L are ddg-oracle's own
    float64 computations: their bounds took the declared epsilon.  At float32 that loosened
    T2.7's quadrature bound 47x (1.36 against 0.029 on an octahedron); at float16 gamma went
    negative (a bound of -64: T2.7 failed the float16 reference) and the exact L's kernel
    could not be counted (C3.3: an internal error)."""
    import numpy as np
    from ddg_oracle.properties.bounds import gamma
    from ddg_oracle.properties.curvature_exact import support_function_integral
    from ddg_oracle.protocol.methods import at_machine_epsilon
    V = np.array([[0.0, 0, -8], [0, 0, 8], [0, 8, 0], [8, 0, 0], [0, -8, 0], [-8, 0, 0]])
    here = support_function_integral(V)
    for e in (2.0 ** -23, 2.0 ** -10):
        with at_machine_epsilon(e):
            assert support_function_integral(V) == here
            assert 0 < gamma(3) < gamma(1000) < np.finfo(float).max
            assert gamma(2000) == (np.finfo(float).max if e == 2.0 ** -10
                                   else 2000 * e / (1 - 2000 * e))
    for pid in ("T2.7", "C3.3", "R3.3"):          # both broke on every example
        r = run_property(PROPERTIES[pid], Reference16(), profile("default"))
        assert r.status == PASSED, (pid, r.status, r.failure or r.error)


def test_non_finite_entries_after_flips_across_a_face_beyond_float_resolution_are_a_tie():
    """The thorough sweep's one false alarm (D4.8 / R4.9 on Kahan's half-angle flips in
    float32): 0, 2, 3 almost collinear, the face (3, 0, 2) flat in float32 lengths; flipping
    its edge carries the face's infinite cotangents (inf - inf: NaN) to the new edge (1, 2),
    which the input does not have.  Rounding decides there: a tie.  NaN entries on a mesh
    with no face beyond float resolution still fail."""
    from fractions import Fraction
    import numpy as np
    from ddg_oracle.properties.runner import FAILED, run_on_example
    from ddg_oracle.properties.strategies import Example
    from tests.honest_panel import Atan2Cross, KahanHalfAngle32
    pts = [(4 / 3, 0.0), (5 / 3, 2 / 3), (2.0, 4 / 3), (7 / 3, 2.0), (7 / 3, 8 / 3)]
    V = tuple(tuple(Fraction(float(np.float32(x))) for x in (*p, 0.0)) for p in pts)
    F = ((0, 3, 1), (3, 0, 2), (1, 3, 4), (0, 1, 4))
    case = Example.of_mesh(V, F, "a face flat in float32 lengths")
    r = run_on_example(PROPERTIES["D4.8 / R4.9"], KahanHalfAngle32(), case, "flat")
    assert r.status == TIE, (r.status, r.failure)

    class NaNAfterFlips(Atan2Cross):
        def intrinsic_delaunay_laplacian(self, V, F):
            L = super().intrinsic_delaunay_laplacian(V, F).tolil()
            L[0, 1] = L[1, 0] = np.nan
            return L.tocsr()
    plain = Example.of_mesh(((Fraction(0),) * 3, (Fraction(1), Fraction(0), Fraction(0)),
                             (Fraction(0), Fraction(1), Fraction(0))), ((0, 1, 2),), "triangle")
    r = run_on_example(PROPERTIES["D4.8 / R4.9"], NaNAfterFlips(), plain, "triangle")
    assert r.status == FAILED and "non-finite entries" in str(r.failure)


def test_the_panels_flips_end_at_float_ties_without_their_budget():
    """A fan of 7 faces and a 2-face disk (squared lengths of a float32 hunt example): two
    of its sides are Delaunay ties that float32 rounding calls non-Delaunay both ways.
    Flipping on a bare ``cot a + cot b >= 0`` flipped them back and forth until the flip
    budget (50 m^2 + 1000 = 5,050 flips) ran out, in 7 of 270 runs of the default hunt; the
    panel's relative tolerance (geometry-central's delaunayEPS, scaled) ends it in a few."""
    import numpy as np
    from tests.honest_panel import IntrinsicFlips, KahanHalfAngle32
    F = np.array([[1, 2, 3], [1, 3, 4], [1, 4, 5], [1, 5, 6], [1, 6, 7], [1, 7, 8], [1, 8, 0],
                  [9, 10, 11], [9, 11, 12]])
    l2 = np.array([[float.fromhex(x) for x in row] for row in (
        ("0x1.ap-10", "0x1.1p-8", "0x1.4p-11"), ("0x1.9p-9", "0x1.d4p-7", "0x1.1p-8"),
        ("0x1.48p-8", "0x1.28p-5", "0x1.d4p-7"), ("0x1.e8p-8", "0x1.388p-4", "0x1.28p-5"),
        ("0x1.54p-7", "0x1.248p-3", "0x1.388p-4"), ("0x1.c4p-7", "0x1.f64p-3", "0x1.248p-3"),
        ("0x1.04p-2", "0x1p-13", "0x1.f64p-3"), ("0x1.f4p-7", "0x1.194p-3", "0x1.388p-3"),
        ("0x1.9p-4", "0x1.f4p-7", "0x1.194p-3"))], dtype=np.float32)
    flips = IntrinsicFlips(F.copy(), l2.copy(), KahanHalfAngle32())
    done = []
    flip = flips.flip
    flips.flip = lambda f, c: done.append((f, c)) or flip(f, c)
    F2, L2 = flips.run()
    assert 0 < len(done) <= 3 * len(F), len(done)
    assert np.isfinite(L2).all() and (L2 > 0).all()
    # and every side it kept is Delaunay up to that tolerance, in its own float32 cotangents
    for f in range(len(F2)):
        for c in range(3):
            g, d = (int(x) for x in flips.nb[f, c])
            if g >= 0 and g != f:
                a, b = flips.cot(f, c), flips.cot(g, d)
                assert a + b >= -8 * float(np.finfo(np.float32).eps) * (abs(a) + abs(b))
