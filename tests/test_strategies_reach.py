"""The surface strategies reach where real bugs hide, and shrink back to the plain case.

Scale (2^k, k in -60..60), offsets far from the origin (2^e times the mesh size, e up
to 30), Möbius strips and inconsistently oriented surfaces (for the properties of the
metric alone), needles and caps down to 2^-24, valence up to 64, several components
(touching at a point: two vertices at one position), isolated vertices, any order:
each is drawn, and a search for it shrinks to the simplest surface with the parameter
at its smallest value; a planted bug that only such inputs show is caught.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, find, settings
from hypothesis.errors import NoSuchExample

from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.strategies import jittered_surfaces
from ddg_oracle.protocol.budget import Budget
from ddg_oracle.properties.profiles import profile
from ddg_oracle.properties.runner import FAILED, run_property
from ddg_oracle.properties.strategies import (acute_meshes, any_meshes, scaled_meshes,
                                              surface_meshes, triangulated_surfaces,
                                              with_boundary, with_isolated)
from tests.property_checks import assert_element_on_mesh
from tests.planted_bugs import (AbsoluteZeroArea, BincountWithoutMinlength, BoundaryByMissingTwin,
                                BoundaryLoopsByDirectedTwin, ChiOfFirstComponent,
                                ChiOfUsedVertices, ClampedArccos, CompactedVertices,
                                DelaunayKeyedByUsedCount, IntrinsicCompacted,
                                IntrinsicFirstHoleOnly,
                                FirstComponentOnly, MaxValence32, OffsetCancellation,
                                OneBoundaryLoop, OrientableByDirectedEdges, TwinByReversedKey,
                                WeldedByPosition)

SEARCH = settings(max_examples=1000, database=None, deadline=None, derandomize=True,
                  suppress_health_check=list(HealthCheck),
                  # no explain phase: it reruns the found example under sys.settrace (7 s of
                  # this file's 40), to print a report no test here reads
                  phases=[p for p in Phase if p is not Phase.explain])
#: the first example found, unshrunk: for the tests that only say a kind of input is drawn
#: (shrinking it took 10 s of test_boundary_sets_come_unsorted_too's 10)
DRAWN = settings(SEARCH, phases=[Phase.generate])


def _param(case, key):
    return dict(case.params)[key]


def test_a_scale_below_2_to_the_minus_20_is_drawn_and_shrinks_to_exactly_that():
    case = find(jittered_surfaces(), lambda c: _param(c, "scale exponent") <= -20,
                settings=SEARCH)
    assert _param(case, "scale exponent") == -20
    assert case.recipe.startswith("tetrahedron [0, 0], scaled by 2^-20")
    V, _ = case.mesh
    assert max(abs(x) for p in V for x in p) <= 2.0 ** -19   # the positions really are tiny


def test_an_offset_far_from_the_origin_is_drawn_and_shrinks_to_exactly_that():
    case = find(jittered_surfaces(), lambda c: (_param(c, "offset exponent") or 0) >= 20,
                settings=SEARCH)
    assert _param(case, "offset exponent") == 20 and _param(case, "scale exponent") == 0
    V, _ = case.mesh
    assert min(abs(x) for p in V for x in p) >= 2.0 ** 19     # every coordinate far out
    # exact: the floats are the dyadic rationals the reference computes with
    assert all(Fraction(x) == y for p, q in zip(V, case.surface.positions) for x, y in zip(p, q))


@pytest.fixture(scope="module")
def orientation_search_of_the_extrinsic_strategy():
    # the search below is the same for both orientations (it does not read the parameter):
    # run once per module (1.4 CPU-s), each case still asserts its outcome
    try:
        return find(jittered_surfaces(), lambda c: _param(c, "orientation") != "consistent",
                    settings=settings(SEARCH, max_examples=300))
    except NoSuchExample as e:
        return e


@pytest.mark.parametrize("orientation", ["moebius", "faces reversed"])
def test_orientation_classes_are_drawn_for_intrinsic_properties_only(
        orientation, orientation_search_of_the_extrinsic_strategy):
    case = find(jittered_surfaces(intrinsic=True),
                lambda c: _param(c, "orientation") == orientation, settings=SEARCH)
    t = case.triangulation
    reversed_gluings = any(t.reversed_gluing(e) for e in range(t.n_edges))
    assert reversed_gluings                        # some edge listed twice in one direction
    assert t.is_orientable() == (orientation == "faces reversed")
    assert case.triangulation.n_faces <= 6 if orientation == "moebius" else \
        case.recipe.startswith("tetrahedron [0, 0]")
    # not for properties that need the orientation: that search found no example
    # (NoSuchExample, as pytest.raises(NoSuchExample) around it asserted)
    assert isinstance(orientation_search_of_the_extrinsic_strategy, NoSuchExample), \
        orientation_search_of_the_extrinsic_strategy


@pytest.mark.parametrize("bug, pid", [(BoundaryByMissingTwin, "D2.2"),
                                      (AbsoluteZeroArea, "D2.6"),
                                      (OffsetCancellation, "D2.6")])
def test_bugs_only_far_inputs_show_are_caught(bug, pid):
    r = run_property(PROPERTIES[pid], bug(), profile("ci"))
    assert r.status == FAILED, f"{bug.name} passed {pid}"
    assert_element_on_mesh(r.failure)


@pytest.mark.parametrize("kind", ["needle", "cap"])
def test_slivers_down_to_2_to_the_minus_15_are_drawn_and_shrink_to_one_split_tetrahedron(kind):
    case = find(jittered_surfaces(), lambda c: _param(c, "sliver") == kind
                and _param(c, "sliver exponent") >= 15, settings=SEARCH)
    assert _param(case, "sliver exponent") == 15
    assert case.triangulation.n_faces == 6 and case.recipe.startswith("tetrahedron [0, 0]")
    # the new vertex really is 2^-15 of the mesh from a corner (needle) or an edge (cap)
    V, F = case.arrays()
    edges = np.linalg.norm(V[F[:, [1, 2, 0]]] - V[F], axis=2)
    if kind == "needle":
        assert edges.min() / edges.max() < 2.0 ** -14
    else:
        A = V[F]
        double_area = np.linalg.norm(np.cross(A[:, 1] - A[:, 0], A[:, 2] - A[:, 0]), axis=1)
        assert double_area.min() / edges.max() ** 2 < 2.0 ** -14


def test_a_sliver_on_the_boundary_is_drawn():
    case = find(jittered_surfaces(closed=False), lambda c: _param(c, "sliver") == "cap"
                and "boundary" in _boundary_caps(c), settings=SEARCH)
    assert _param(case, "sliver exponent") == 1


def _boundary_caps(case):
    # "boundary" when the split face's edge opposite the new vertex is a boundary edge
    t, q = case.triangulation, case.surface.n_vertices - 1
    for h in range(t.n_halfedges):
        if t.twin(h) < 0 and q in t.faces[h // 3] and q not in (t.tail(h), t.head(h)):
            return "boundary"
    return ""


def test_valence_up_to_64_is_drawn_and_shrinks_to_valence_33():
    def valence(c):
        t = c.triangulation
        return max(sum(1 for f in t.faces if v in f) for v in range(t.n_vertices))
    case = find(jittered_surfaces(), lambda c: valence(c) > 32, settings=SEARCH)
    assert valence(case) == 33 and case.recipe.startswith(("fan of valence 33", "bipyramid of valence 33"))
    big = find(jittered_surfaces(), lambda c: valence(c) >= 60, settings=SEARCH)
    assert valence(big) == 60


@pytest.mark.parametrize("touching", [False, True])
def test_a_second_component_is_drawn_and_shrinks_to_a_triangle_beside_a_tetrahedron(touching):
    case = find(jittered_surfaces(), lambda c: _param(c, "components") == 2
                and _param(c, "touching") == touching, settings=SEARCH)
    assert len(case.triangulation.components()) == 2
    assert case.triangulation.n_faces == 5 and "and a triangle" in case.recipe
    V, _ = case.mesh
    distinct = {tuple(p) for p in V}
    # touching: two vertices (one per component) at exactly one position, not merged
    assert len(distinct) == len(V) - (1 if touching else 0)


def test_isolated_vertices_are_drawn_anywhere_and_shrink_to_one_at_the_end():
    case = find(jittered_surfaces(), lambda c: _param(c, "isolated") > 0, settings=SEARCH)
    assert [i for i, _ in case.isolated] == [4] and case.triangulation.n_faces == 4
    V, F = case.arrays()
    assert len(V) == 5 and 4 not in set(F.ravel().tolist())   # leftover vertex at the end
    inner = find(jittered_surfaces(), lambda c: any(0 < i < c.surface.n_vertices
                                                    for i, _ in c.isolated), settings=DRAWN)
    V, F = inner.arrays()
    used = set(F.ravel().tolist())
    assert any(0 < i < len(V) - 1 and i not in used for i in range(len(V)))   # in the middle
    # the Laplacian strategies draw them too
    c = find(with_isolated(acute_meshes(max_components=3)),
             lambda c: c.n > len({v for f in c.faces for v in f}), settings=SEARCH)
    assert c.n == len({v for f in c.faces for v in f}) + 1


def test_order_is_drawn_and_shrinks_to_the_constructors_order():
    case = find(jittered_surfaces(), lambda c: _param(c, "reordered"), settings=SEARCH)
    assert case.recipe.startswith("tetrahedron [0, 0], reordered")
    from ddg_oracle.reference import surfaces
    plain = surfaces.tetrahedron().triangulation.faces
    assert sorted(map(sorted, case.triangulation.faces)) != sorted(map(sorted, plain)) or \
        list(case.triangulation.faces) != list(plain)


def test_the_laplacian_strategies_draw_moebius_strips_and_reversed_faces():
    moebius = find(surface_meshes(), lambda c: _orientable(c) is False, settings=SEARCH)
    assert moebius.recipe.startswith("moebius strip") and len(moebius.faces) == 6
    flipped = find(surface_meshes(), lambda c: _orientable(c) and _reversed(c), settings=SEARCH)
    assert flipped.recipe.startswith("tetrahedron [0, 0]") and "reversed" in flipped.recipe


def _orientable(c):
    from ddg_oracle.reference.combinatorics import Triangulation
    return Triangulation.from_faces(c.faces, n_vertices=c.n).is_orientable() if \
        c.n == len({v for f in c.faces for v in f}) else None


def _reversed(c):
    from ddg_oracle.reference.combinatorics import Triangulation
    if c.n != len({v for f in c.faces for v in f}):
        return False
    t = Triangulation.from_faces(c.faces, n_vertices=c.n)
    return any(t.reversed_gluing(e) for e in range(t.n_edges))


DEFECTS = ("D2.2", "R2.4", "T2.6")          # the properties calling angle_defects first


@pytest.mark.parametrize("bug, pids, max_faces", [
    (ClampedArccos, ("D2.6",), 6),            # a tetrahedron with one face split at 2^-k
    (MaxValence32, DEFECTS, 66),              # valence 33: a fan of 33 faces, or a bipyramid
    # a closed surface and a triangle: the ci stream's shrink stops at an octahedron
    # with faces reversed (9 faces); Hypothesis's find reaches a tetrahedron (5)
    (FirstComponentOnly, DEFECTS, 9),
    (WeldedByPosition, DEFECTS, 8),           # ... touching it at a vertex
    (BincountWithoutMinlength, DEFECTS, 4),   # a tetrahedron and an isolated vertex last
    (CompactedVertices, DEFECTS, 4),          # a tetrahedron and an isolated vertex first
    # chapter 4 drew no unused vertex before: the compacted numbering passed every property
    (IntrinsicCompacted, ("A4.13", "D4.8 / R4.9"), 3),   # a triangle and an unused vertex
    (IntrinsicFirstHoleOnly, ("A4.13", "D4.8 / R4.9"), 3),   # ... and two unused vertices
    (DelaunayKeyedByUsedCount, ("D4.4 / T4.7 / P4.9",), 6),  # an unused vertex below the top
    (TwinByReversedKey, ("D3.1",), 6),        # a reversed face or a Möbius strip
])
def test_bugs_of_the_wider_classes_are_caught_and_shrink(bug, pids, max_faces):
    # as `ddg-oracle check --only` would run them, under ci: the first property that
    # catches it (the time and size over every property and seed: python -m benchmarks
    # catch).  A valence-33 counterexample is not shrunk here: 66 faces take a minute
    ci = profile("ci")
    if max_faces > 32:
        ci = settings(ci, phases=[Phase.explicit, Phase.reuse, Phase.generate])
    for p in pids:
        r = run_property(PROPERTIES[p], bug(), ci)
        if r.status == FAILED:
            break
    assert r.status == FAILED, f"{bug.name} passed {pids}"
    assert_element_on_mesh(r.failure)
    if max_faces <= 32:
        assert len(r.failure.mesh[1]) <= max_faces, f"{bug.name}: shrunk to {len(r.failure.mesh[1])} faces"
    else:                              # not shrunk: a vertex of valence > 32 is there
        assert np.bincount(np.asarray(r.failure.mesh[1]).ravel()).max() > 32


# --- topology: components, unused vertices, faces reversed (issue 40, item 4) -----------------


def test_topology_examples_know_chi_of_components_and_unused_vertices():
    wide = triangulated_surfaces(reversed=True, components=2, isolated=2)
    case = find(wide, lambda c: len(c.triangulation.components()) > 1 and c.isolated,
                settings=DRAWN)
    V, F = case.arrays()
    # chi counted directly from the arrays: V - E + F, every row of V counts
    edges = {frozenset((int(f[c]), int(f[(c + 1) % 3]))) for f in F for c in range(3)}
    assert case.expected.euler_characteristic == len(V) - len(edges) + len(F)
    assert case.expected.genus is None                 # no genus of a disconnected surface
    assert len({int(v) for v in F.ravel()}) < len(V)   # some row of V is used by no face
    assert "isolated vertices at" in case.recipe and ", and a " in case.recipe


def test_reversed_faces_keep_an_orientable_surface_orientable():
    case = find(triangulated_surfaces(reversed=True), lambda c: "reversed" in c.recipe,
                settings=DRAWN)
    t = case.triangulation
    assert any(t.reversed_gluing(e) for e in range(t.n_edges))
    assert t.is_orientable() == case.expected.orientable


@pytest.mark.parametrize("bug, pid", [(ChiOfUsedVertices, "D1.6"), (ChiOfFirstComponent, "D1.6"),
                                      (OrientableByDirectedEdges, "T1.1 / C1.2"),
                                      (BoundaryLoopsByDirectedTwin, "R1.6")])
def test_topology_bugs_only_components_unused_vertices_or_reversed_faces_show(bug, pid):
    r = run_property(PROPERTIES[pid], bug(), profile("ci"))
    assert r.status == FAILED, f"{bug.name} passed {pid}"
    assert len(r.failure.mesh[1]) <= 24


# --- slivers in families, boundary sets in any order, translated meshes ------------------------


@pytest.mark.parametrize("family", ["clustered", "banded"])
def test_sliver_families_are_drawn(family):
    case = find(jittered_surfaces(), lambda c: _param(c, "sliver family") == family,
                settings=DRAWN)
    assert f"{family} (" in case.recipe


def test_clustered_slivers_meet_at_one_point_and_banded_ones_cross_faces():
    from ddg_oracle.properties import variants
    from ddg_oracle.reference import surfaces
    grid = surfaces.grid(3, 3)
    k = 12
    size = Fraction(1, 2 ** (k - 2))              # every needle edge is shorter than this
    for family in ("clustered", "banded"):
        s = variants.slivers(grid, 7, "needle", k, None, family, 3)
        new = range(grid.n_vertices, s.n_vertices)
        assert len(new) == 3 if family == "clustered" else 1 <= len(new) <= 3
        x = s.positions

        def near(a, b):
            return max(abs(p - q) for p, q in zip(x[a], x[b])) < size
        # each new vertex is a needle: within 2**-k of an old or new vertex
        assert all(any(near(q, v) for v in range(s.n_vertices) if v != q) for q in new)
        if family == "clustered":                 # ... and of each other
            assert all(near(a, b) for a in new for b in new)
        else:                                     # in different faces of the grid: apart
            assert not any(near(a, b) for a in new for b in new if a != b)


def test_boundary_sets_come_unsorted_too():
    case = find(with_boundary(acute_meshes()), lambda c: len(c.boundary) > 2
                and list(c.boundary) != sorted(c.boundary), settings=DRAWN)
    assert sorted(case.boundary) != list(case.boundary)
    assert len(set(case.boundary)) == len(case.boundary)


def test_scaled_meshes_are_also_moved_far_and_stay_floats():
    case = find(scaled_meshes(any_meshes(far=False)), lambda c: "moved by 2**" in c.recipe,
                settings=DRAWN)
    V, _ = case.arrays()
    assert all(Fraction(float(x)) == x for p in case.positions for x in p)
    assert np.abs(V).min() > 0


def test_float32_implementations_get_float32_inputs():
    import struct
    from ddg_oracle.properties.precision import inputs_at

    def in_float32(c):
        return all(struct.unpack("f", struct.pack("f", float(x)))[0] == x
                   for p in c.mesh[0] for x in p)
    with inputs_at(2.0 ** -23):
        for strategy in (jittered_surfaces(), scaled_meshes(any_meshes(isolated=True, far=False)),
                         any_meshes(isolated=True)):
            with pytest.raises(NoSuchExample):
                find(strategy, lambda c: not in_float32(c), settings=settings(SEARCH, max_examples=150))
        # scales float32 holds with room for products of four coordinates
        with pytest.raises(NoSuchExample):
            find(jittered_surfaces(), lambda c: abs(_param(c, "scale exponent")) > 20,
                 settings=settings(SEARCH, max_examples=150))
    # and float64 ones get float64 numbers that float32 cannot hold
    find(jittered_surfaces(), lambda c: not in_float32(c), settings=DRAWN)


# --- where the planted variants hide (issue 40, items 4-5): near ties across their range,
# reversed faces and high valence in small meshes, small families scaled, flip cascades -----


def _ks_in(case):
    import re
    return [int(k) for k in re.findall(r"moved in by 2\^-(\d+)", case.recipe)]


def test_near_ties_are_drawn_across_the_range_and_shrink_to_one_quad():
    from ddg_oracle.properties.strategies import NEAR_TIE_EXPONENTS, near_cocircular_meshes
    case = find(near_cocircular_meshes(), lambda c: any(k >= 40 for k in _ks_in(c)),
                settings=SEARCH)
    assert len(case.faces) == 2 and case.recipe.startswith("cocircular quad, a corner moved in by 2^-40")
    # not integers(20, 44), which draws 20 in half the examples: every exponent is drawn
    from hypothesis import given
    seen = []

    @settings(max_examples=200, database=None, deadline=None, derandomize=True,
              suppress_health_check=list(HealthCheck), phases=[Phase.generate])
    @given(near_cocircular_meshes())
    def draw(c):
        seen.extend(_ks_in(c))
    draw()
    assert set(seen) == set(NEAR_TIE_EXPONENTS)
    assert sum(k >= 36 for k in seen) >= len(seen) / 3
    # the fourth point really is off the circle of the other three, inside it
    V, _ = case.arrays()
    assert 1 - np.hypot(V[3, 0], V[3, 1]) / 5 == 2.0 ** -40


def test_reversed_faces_are_drawn_in_small_meshes_and_shrink_small():
    from ddg_oracle.properties.flipped import delaunay_test_meshes, intrinsic_meshes
    for strategy in (delaunay_test_meshes(), intrinsic_meshes(), any_meshes()):
        case = find(strategy, lambda c: "reversed" in c.recipe and _reversed(c), settings=SEARCH)
        assert len(case.faces) <= 4 and "reversed" in case.recipe


def test_a_vertex_of_valence_17_is_drawn_in_a_small_mesh():
    def valence(c):
        return int(np.bincount(np.asarray(c.faces).ravel()).max())
    from ddg_oracle.properties.strategies import valence_fans
    case = find(any_meshes(), lambda c: valence(c) >= 17, settings=SEARCH)
    assert valence(case) == 17 and len(case.faces) <= 34     # a fan, or a bipyramid
    case = find(valence_fans(), lambda c: valence(c) >= 17, settings=SEARCH)
    assert valence(case) == 17 and len(case.faces) == 17


def test_sweep_triangulations_and_near_ties_are_a_third_of_the_intrinsic_examples_each():
    """... and, beside any kind, a near tie and a convex fan in about one example of two
    each (a default run's 25 examples drew too few of a kind: IntrinsicSinglePass and
    IntrinsicFlipTolerance1e6 were missed by one seed of three).  Counted over four fixed
    seeds: one derandomized run of 60 is one draw of Hypothesis's engine, whose mutations
    repeat a kind in runs (at 120 examples one such run drew 8 'other' where seeds 0-7 of
    60 draw 153 of 480)."""
    from hypothesis import given, seed
    from ddg_oracle.properties.flipped import intrinsic_meshes
    kinds, beside = [], []

    def draw(c):
        own, *extra = c.recipe.split("; beside it ")
        kinds.append("sweep" if own.startswith(("planar triangulation", "fan of")) else
                     "tie" if "cocircular quad" in own else "other")
        beside.extend(extra)
    for k in range(4):
        seed(k)(settings(max_examples=60, database=None, deadline=None,
                         suppress_health_check=list(HealthCheck),
                         phases=[Phase.generate])(given(intrinsic_meshes())(draw)))()
    counts = {k: kinds.count(k) for k in ("sweep", "tie", "other")}
    assert all(c >= len(kinds) // 6 for c in counts.values()), counts
    assert sum("cocircular quad" in x for x in beside) >= len(kinds) // 4
    assert sum("on a parabola" in x for x in beside) >= len(kinds) // 4


from benchmarks.planted import variants as planted  # noqa: E402


@pytest.mark.parametrize("bug, pid, max_faces", [
    (OneBoundaryLoop, "R1.6", 6),                           # an annulus
    (planted.IsOrientableFirstComponentOnly, "T1.1 / C1.2", 10),   # tetrahedron, Möbius strip
    (planted.IsOrientableByDirectedHalfedges, "T1.1 / C1.2", 4),   # a face reversed
], ids=lambda x: x.__name__ if isinstance(x, type) else None)
def test_topology_traps_catch_their_bugs_at_their_smallest(bug, pid, max_faces):
    """The smallest surfaces of each trap are drawn (annuli: two boundary loops in 6 faces,
    where punched surfaces needed 22 or more; the orientation traps of T1.1 a third each)."""
    r = run_property(PROPERTIES[pid], bug(), profile("ci"))
    assert r.status == FAILED, f"{bug.__name__} passed {pid}"
    assert len(r.failure.mesh[1]) <= max_faces, f"{bug.__name__}: {len(r.failure.mesh[1])} faces"


@pytest.mark.parametrize("bug, pids, max_faces", [
    (planted.DelaunayTolerance1e10, ("D4.4 / T4.7 / P4.9",), 2),   # a quad moved in by 2^-40
    (planted.DelaunayTolerance1e6, ("D4.4 / T4.7 / P4.9",), 2),
    (planted.DelaunayTwinByReversedKey, ("D4.4 / T4.7 / P4.9",), 6),
    (planted.IntrinsicFlipTolerance1e6, ("A4.13", "D4.8 / R4.9"), 2),
    (planted.IntrinsicAssumesOrientation, ("A4.13", "D4.8 / R4.9"), 12),
    (planted.IntrinsicSinglePass, ("A4.13", "D4.8 / R4.9"), 12),     # a flip cascade
    (planted.PlanarDelaunayFloat32, ("T4.1", "D4.1"), 4),            # nearly cocircular points
    (planted.PlanarFlipAbsoluteEpsilon, ("L4.3 / P4.4",), 6),        # a point set scaled down
    (planted.AreaGradientAbsoluteGuard, ("T3.9",), 6),
    (planted.VoronoiObtuseAbsoluteEpsilon, ("L3.7",), 6),
    (planted.BarycentricCompacted, ("L3.7",), 6),                    # an isolated vertex first
    (planted.CornerAnglesUnitizeThreshold, ("D4.7 / L4.17", "D2.6"), 6),
    (planted.MeanCurvatureUnsigned, ("R2.5", "D2.3"), 6),    # a reflex edge: a dented bipyramid
    (planted.DirichletInaccurateSolve, ("C3.4 / T3.5",), 72),        # a dozen unknowns or more
], ids=lambda x: x.__name__ if isinstance(x, type) else None)
def test_planted_variants_of_the_wider_classes_are_caught_and_shrink(bug, pids, max_faces):
    # each under ci by the first of its properties that catches it (the catch benchmark
    # measures every property and seed: python -m benchmarks catch)
    # DirichletInaccurateSolve (max_faces 72): ci is derandomized, its first failure is a
    # 40-face mesh that ~200 shrink candidates (8 CPU-s) never reduce.  Shrinking stays
    # but gets 2 s, as `check`'s own budgets give it (BUDGETS["ci"]: 10 s): a cut shrink
    # keeps the smallest failure seen (<= that 40-face one), so the same assertions below
    # decide; 600 s of task time keeps a call the cut interrupts from counting as a hang
    budget = Budget(600.0, None, 2.0) if max_faces > 32 else None
    for p in pids:
        r = run_property(PROPERTIES[p], bug(), profile("ci"), budget=budget)
        if r.status == FAILED:
            break
    assert r.status == FAILED, f"{bug.__name__} passed {pids}"
    assert_element_on_mesh(r.failure)
    assert len(r.failure.mesh[1]) <= max_faces, f"{bug.__name__}: shrunk to {len(r.failure.mesh[1])} faces"
