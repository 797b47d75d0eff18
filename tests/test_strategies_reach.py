"""The curvature strategies reach where real bugs hide, and shrink back to the plain case.

Scale (2^k, k in -60..60), offsets far from the origin (2^e times the mesh size, e up
to 30), Möbius strips and inconsistently oriented surfaces (for the properties of the
metric alone): each is drawn, and a search for it shrinks to the simplest surface with
the parameter at its smallest value; a planted bug that only such inputs show is caught.
"""

from __future__ import annotations

from fractions import Fraction

import pytest
from hypothesis import HealthCheck, find, settings
from hypothesis.errors import NoSuchExample

from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.curvature import jittered_surfaces
from ddg_oracle.properties.profiles import profile
from ddg_oracle.properties.runner import FAILED, run_property
from tests.planted_bugs import AbsoluteZeroArea, BoundaryByMissingTwin, OffsetCancellation

SEARCH = settings(max_examples=1000, database=None, deadline=None, derandomize=True,
                  suppress_health_check=list(HealthCheck))


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


@pytest.mark.parametrize("orientation", ["moebius", "faces reversed"])
def test_orientation_classes_are_drawn_for_intrinsic_properties_only(orientation):
    case = find(jittered_surfaces(intrinsic=True),
                lambda c: _param(c, "orientation") == orientation, settings=SEARCH)
    t = case.triangulation
    reversed_gluings = any(t.reversed_gluing(e) for e in range(t.n_edges))
    assert reversed_gluings                        # some edge listed twice in one direction
    assert t.is_orientable() == (orientation == "faces reversed")
    assert case.triangulation.n_faces <= 6 if orientation == "moebius" else \
        case.recipe.startswith("tetrahedron [0, 0]")
    with pytest.raises(NoSuchExample):      # not for properties that need the orientation
        find(jittered_surfaces(), lambda c: _param(c, "orientation") != "consistent",
             settings=settings(SEARCH, max_examples=300))


@pytest.mark.parametrize("bug, pid", [(BoundaryByMissingTwin, "D2.2"),
                                      (AbsoluteZeroArea, "D2.6"),
                                      (OffsetCancellation, "D2.6")])
def test_bugs_only_far_inputs_show_are_caught(bug, pid):
    r = run_property(PROPERTIES[pid], bug(), profile("ci"))
    assert r.status == FAILED, f"{bug.name} passed {pid}"
    assert r.failure.mesh is not None
