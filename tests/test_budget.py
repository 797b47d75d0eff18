"""The task budget (protocol/budget.py): a failure is shrunk for at most the budget's
shrink seconds, then the smallest failing example seen so far is the result."""

import time

import pytest

from ddg_oracle.oracles.exact_reference import ReferenceImplementation
from ddg_oracle.protocol.budget import Budget
from ddg_oracle.properties.profiles import profile
from ddg_oracle.properties.registry import PROPERTIES, all_properties
from ddg_oracle.properties.runner import FAILED, run_property

all_properties()

CALL = 0.05         # seconds per call of the slow implementation below


class SlowWrongDefects(ReferenceImplementation):
    """Angle defects off by one on every mesh but the tetrahedron, CALL seconds per call:
    nearly every example fails and each shrink step costs a call, so shrinking to the
    smallest failing mesh (5 faces or more) takes many seconds."""

    name = "slow-wrong-defects"

    def angle_defects(self, V, F):
        time.sleep(CALL)
        return super().angle_defects(V, F) + (1.0 if len(F) > 4 else 0.0)


def test_shrinking_stops_after_the_shrink_budget_with_the_smallest_failure_so_far():
    shrink = 0.5
    t0 = time.perf_counter()
    r = run_property(PROPERTIES["D2.2"], SlowWrongDefects(), profile("ci"),
                     budget=Budget(seconds=120.0, crashes=None, shrink=shrink))
    took = time.perf_counter() - t0
    assert r.status == FAILED
    assert "shrinking stopped early" in r.note
    # the first example already fails: the search takes a call or two, then shrinking
    # gets `shrink` seconds and one call more (the one running when it ran out is cut)
    assert took < shrink + 20 * CALL + 2.0, took
    assert r.failure.mesh is not None and len(r.failure.mesh[1]) >= 1


def test_without_a_shrink_budget_the_same_failure_is_shrunk_further():
    # the counterpart of the test above: the whole task budget for shrinking, and the
    # counterexample is at least as small (the shrink budget cut something real)
    cut = run_property(PROPERTIES["D2.2"], SlowWrongDefects(), profile("ci"),
                       budget=Budget(seconds=120.0, crashes=None, shrink=0.5))
    full = run_property(PROPERTIES["D2.2"], SlowWrongDefects(), profile("ci"),
                        budget=Budget(seconds=120.0, crashes=None))
    assert full.status == FAILED and "stopped early" not in (full.note or "")
    assert full.seconds > cut.seconds
    assert len(full.failure.mesh[1]) <= len(cut.failure.mesh[1])


def test_the_manual_and_the_help_state_the_budgets_in_force():
    import re
    from pathlib import Path

    from ddg_oracle.protocol.budget import BUDGETS
    root = Path(__file__).resolve().parents[1]
    readme = re.sub(r"\s+", " ", (root / "docs" / "check.md").read_text(encoding="utf-8"))
    cli = re.sub(r'"\s+"', "", (root / "application" / "cli.py").read_text(encoding="utf-8"))
    d, ci = BUDGETS["default"], BUDGETS["ci"]
    assert (f"{d.seconds:g} s of wall clock, at most {d.shrink:g} s of it shrinking" in readme
            and f"{ci.seconds:g} s, {ci.shrink:g} s shrinking" in readme)
    assert (f"default: {d.seconds:g}, at most {d.shrink:g} of them shrinking" in cli
            and f"{ci.seconds:g}, at most {ci.shrink:g} shrinking, with ci" in cli)


class TracedWrongDefects(ReferenceImplementation):
    """Angle defects off by one, recording whether a tracer is set during each call."""

    name = "traced-wrong-defects"

    def __init__(self):
        self.traced = []

    def angle_defects(self, V, F):
        import sys
        self.traced.append(sys.gettrace() is not None)
        return super().angle_defects(V, F) + (1.0 if len(F) > 4 else 0.0)


def test_no_example_runs_under_a_tracer():
    # Hypothesis's explain phase re-runs the failing example under sys.settrace on Python
    # < 3.12, where a budget's SIGALRM raised inside the tracer (once a worker segfaulted):
    # our searches leave that phase out
    impl = TracedWrongDefects()
    r = run_property(PROPERTIES["D2.2"], impl, profile("ci"))
    assert r.status == FAILED and len(impl.traced) > 1
    assert not any(impl.traced)


def test_a_cpu_time_limit_counts_the_processs_cpu_not_the_clock():
    """compare and survey limit the exact reference by CPU time (its verdict, decided or
    undecided, must not depend on what else the machine runs): a block that waits passes
    a CPU limit it would overrun on the clock; a block that computes is stopped."""
    from ddg_oracle.properties.profiles import example_time_limit
    from ddg_oracle.reference.errors import TimeLimitExceeded
    with example_time_limit("[X] waiting", seconds=0.05, cpu=True):
        time.sleep(0.3)
    with pytest.raises(TimeLimitExceeded, match="0.05 s of CPU time"):
        with example_time_limit("[X] computing", seconds=0.05, cpu=True):
            deadline = time.monotonic() + 10    # a CPU timer that never fires: a failure,
            while time.monotonic() < deadline:  # not a hang
                sum(range(1000))
    with pytest.raises(TimeLimitExceeded, match=r"0.05 s per"):
        with example_time_limit("[X] waiting on the clock", seconds=0.05):
            time.sleep(0.3)
