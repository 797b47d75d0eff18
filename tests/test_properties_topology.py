"""Chapter 1 properties: the reference passes each; planted bugs are caught with small counterexamples."""

import pytest
from hypothesis import given

from ddg_oracle.oracles.exact_reference import ReferenceImplementation
from ddg_oracle.properties import PROPERTIES, closed_surfaces, named_surfaces, triangulated_surfaces
from ddg_oracle.properties.profiles import profile
from ddg_oracle.properties.runner import FAILED, PASSED, run_property
from ddg_oracle.properties.topology import (boundary_loops_and_genus, classification_of_closed_surfaces,
                                 euler_characteristic_of_known_surfaces)
from ddg_oracle.properties.flipped import unrestricted_flips
from tests.planted_bugs import AlwaysOrientable, ChiIgnoresBoundary, OneBoundaryLoop

REF = ReferenceImplementation()
CHAPTER1 = ["D1.6", "R1.5", "X1.4", "CS", "T1.1 / C1.2", "R1.6"]


@pytest.mark.parametrize("pid", CHAPTER1)
def test_reference_passes_chapter1_property(pid):
    r = run_property(PROPERTIES[pid], REF, profile("default"))
    assert r.status == PASSED, r.failure or r.error
    assert r.examples > 0


@given(triangulated_surfaces())
def test_D1_6_reference_chi_matches_construction(case):
    euler_characteristic_of_known_surfaces(REF, case)
    t = case.triangulation
    assert t.euler_characteristic() == t.n_vertices - t.n_edges + t.n_faces


@given(closed_surfaces(max_genus=3))
def test_T1_1_reference_classifies_closed_surfaces(case):
    classification_of_closed_surfaces(REF, case)
    assert case.triangulation.classify() == case.expected


@given(triangulated_surfaces(max_holes=3))
def test_R1_6_reference_boundary_and_genus(case):
    assert case.triangulation.classify() == case.expected
    boundary_loops_and_genus(REF, case)          # chi = 2 - 2g - k, or 2 - h - k


@given(named_surfaces())
def test_X1_4_named_surfaces(case):
    assert case.triangulation.classify() == case.expected


def _caught(pid, impl):
    r = run_property(PROPERTIES[pid], impl, profile("ci"))
    assert r.status == FAILED, f"{impl.name} was not caught by {pid}"
    assert r.failure.property_id == pid
    return r


def test_planted_chi_bug_is_caught_and_shrinks():
    r = _caught("D1.6", ChiIgnoresBoundary())
    V, F = r.failure.mesh
    assert r.failure.expected != r.failure.observed
    assert len(F) <= 40, f"counterexample did not shrink: {len(F)} faces"


def test_planted_orientability_bug_is_caught_on_a_small_non_orientable_surface():
    r = _caught("T1.1 / C1.2", AlwaysOrientable())
    assert r.failure.expected is False and r.failure.observed is True
    assert len(r.failure.mesh[1]) <= 20          # RP^2 has 10 faces


def test_planted_boundary_loop_bug_is_caught():
    r = _caught("R1.6", OneBoundaryLoop())
    assert r.failure.expected != r.failure.observed


def test_finding_F_libigl_1_is_caught_by_R1_6_on_the_smallest_mobius_strip():
    from ddg_oracle.oracles.libigl import Libigl
    r = _caught("R1.6", Libigl())
    assert len(r.failure.mesh[1]) == 6                      # mobius_strip(3)
    assert (r.failure.expected, r.failure.observed) == (1, 4)


def test_finding_F_pymeshlab_1_is_caught_by_T1_1_and_explained_by_the_documented_convention():
    from ddg_oracle.oracles.pymeshlab import PyMeshLab
    r = run_property(PROPERTIES["T1.1 / C1.2"], PyMeshLab(genus="library"), profile("ci"),
                     counterpart=PyMeshLab(), convention="F-pymeshlab-1")
    assert r.status == "convention" and r.failure.expected == 2 * r.failure.observed + 1
    assert len(r.failure.mesh[1]) == 10                     # the projective plane


@given(unrestricted_flips())
def test_D1_4_flips_create_non_regular_triangulations(example):
    from ddg_oracle.properties.flipped import flip_freely
    from ddg_oracle.properties.structure import regularity_predicates
    case, choices = example
    t = flip_freely(case.triangulation, choices)
    regularity_predicates(t)
    assert t.euler_characteristic() == case.expected.euler_characteristic


def test_D1_4_a_flip_sequence_reaches_a_loop_and_a_double_edge():
    from ddg_oracle.properties.structure import regularity_predicates
    from ddg_oracle.reference import surfaces
    t = surfaces.tetrahedron().triangulation
    # flipping any edge of a tetrahedron joins two vertices already joined: a double edge
    u = t.flip(0)
    regularity_predicates(u)
    assert u.is_regular() and not u.is_strongly_regular()
    # keep flipping: some sequence makes a loop (a face with a repeated vertex)
    seen_loop = False
    frontier = [u]
    for _ in range(3):
        nxt = []
        for s in frontier:
            for e in range(s.n_edges):
                try:
                    w = s.flip(e)
                except Exception:
                    continue
                regularity_predicates(w)
                seen_loop |= not w.is_regular()
                nxt.append(w)
        frontier = nxt[:40]
    assert seen_loop


def test_tolerances_follow_the_declared_machine_epsilon():
    from tests.planted_bugs import Float32Defects, Float32DefectsDeclared
    from hypothesis import Phase, settings
    quick = settings(max_examples=5, phases=[Phase.generate], derandomize=True, database=None,
                     deadline=None)        # no shrinking: the verdict is what is tested
    # float32-accurate answers fail float64 bounds, and pass once float32 is declared
    assert run_property(PROPERTIES["X2.1"], Float32Defects(), quick).status == FAILED
    assert run_property(PROPERTIES["X2.1"], Float32DefectsDeclared(), quick).status == PASSED
