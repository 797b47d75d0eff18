"""Shared assertions of the property tests: an implementation passes a property well inside
its bounds, or a planted bug is caught with a shrunk counterexample."""

from ddg_oracle.properties.harness import ErrorLedger, recording
from ddg_oracle.application.causes import element_ids
from ddg_oracle.properties.profiles import profile
from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.runner import FAILED, PASSED, run_property


def assert_passes_well_inside(pid, impl, ratio=0.05):
    """``impl`` passes ``pid`` on the default profile and its largest observed error stays
    below ``ratio`` of the derived bound (correctly rounded float views of exact values)."""
    with recording(ErrorLedger()) as ledger:
        r = run_property(PROPERTIES[pid], impl, profile("default"))
    assert r.status == PASSED, r.failure or r.error
    assert r.examples > 0
    assert ledger.ratios.get(pid, 0.0) < ratio
    return r


def assert_caught(pid, impl, max_faces):
    """``impl`` fails ``pid`` on the ci profile with a counterexample of <= max_faces faces."""
    r = run_property(PROPERTIES[pid], impl, profile("ci"))
    assert r.status == FAILED, f"{impl.name} was not caught by {pid}"
    assert r.failure.property_id == pid
    F = r.failure.mesh[1]
    assert len(F) <= max_faces, f"counterexample did not shrink: {len(F)} faces"
    assert_element_on_mesh(r.failure)
    return r


def assert_element_on_mesh(failure):
    """The element a failure names (what the report's picture highlights) is one of its
    mesh's: vertex and face indices in range."""
    ids = element_ids(failure.element) or {}
    V, F = failure.mesh
    for v in ids.get("edge", []) + [ids[k] for k in ("vertex",) if k in ids]:
        assert 0 <= v < len(V), f"{failure.element!r} names vertex {v} of {len(V)}"
    if "face" in ids:
        assert 0 <= ids["face"] < len(F), f"{failure.element!r} names a face of {len(F)}"


#: examples per property of an adapter's whole-catalog test in the suite: about half the
#: default profile's 25, for half the time; ``DDG_THOROUGH_PANEL=1`` runs the profile's own
WHOLE_CATALOG_EXAMPLES = 12


def every_property_unshrunk(impl, seed):
    """Every registered property on ``impl`` under the default profile with ``seed`` and its
    budget, :data:`WHOLE_CATALOG_EXAMPLES` examples each (the profile's with
    ``DDG_THOROUGH_PANEL=1``), no example database, and no shrink phase: which properties pass or fail (an
    adapter's whole-catalog test), not their smallest examples, for a quarter to a half of
    the time.  Each finding's minimal example is its own snippet's (tests/test_findings.py)."""
    import os
    from hypothesis import Phase, settings
    from ddg_oracle.properties.profiles import profile_budget
    from ddg_oracle.properties.runner import select_properties
    base = profile("default")
    examples = base.max_examples if os.environ.get("DDG_THOROUGH_PANEL") else WHOLE_CATALOG_EXAMPLES
    # no example database: the key of a property is shared by every implementation (by
    # design, a failure of one library is replayed on the others), so a failure another
    # test of the suite saved (a planted bug's) would be replayed here first, and which
    # example an adapter's test sees would depend on the tests run before it
    s = settings(base, max_examples=examples, database=None,
                 phases=(Phase.explicit, Phase.generate))
    return [run_property(p, impl, s, seed, budget=profile_budget("default"))
            for p in select_properties(None)]
