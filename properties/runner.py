"""Run properties against an implementation and collect results.

``check_implementation(impl)`` is the one-call check for a user's own tests: it
runs every applicable property under a Hypothesis profile and raises an
``AssertionError`` listing each failure (ID, shrunk mesh, element, expected vs
observed).  The CLI uses :func:`run_properties` and prints the results instead.
"""

from __future__ import annotations

import time
import traceback
from dataclasses import dataclass

from hypothesis import given, seed as hypothesis_seed, settings as Settings

from .profiles import profile as named_profile
from .protocol import capabilities, implementation_name
from .registry import Property, PropertyFailure, all_properties

PASSED, FAILED, CRASHED, NOT_APPLICABLE = "passed", "FAILED", "crashed", "not applicable"


@dataclass
class Result:
    property_id: str
    property_name: str
    implementation: str
    status: str
    examples: int = 0
    seconds: float = 0.0
    failure: PropertyFailure | None = None
    error: str | None = None          # traceback of a crash of the implementation
    example: object = None            # the shrunk example of a failure or crash

    @property
    def ok(self) -> bool:
        return self.status in (PASSED, NOT_APPLICABLE)

    def summary(self) -> str:
        if self.status == PASSED:
            return f"passed ({self.examples} examples)"
        return self.status


def run_property(p: Property, impl, settings: Settings, seed: int | None = None) -> Result:
    """Run one property on one implementation; never raises for a failing impl."""
    name = implementation_name(impl)
    if not p.applies_to(capabilities(impl)):
        return Result(p.id, p.name, name, NOT_APPLICABLE)
    state = {"n": 0, "last": None}

    # one failure per property, the shrunk one: several distinct failures would come
    # back as an ExceptionGroup and read as a crash
    @Settings(settings, report_multiple_bugs=False)
    @given(p.strategy())
    def run(example):
        # Hypothesis replays the shrunk example last, so "last" is minimal.
        state["n"] += 1
        state["last"] = example
        p.check(impl, example)

    # each (property, implementation) its own database key and derandomized seed: Hypothesis
    # derives both from the test function, the same `run` for every property (as its pytest
    # plugin does for parametrized tests)
    run._hypothesis_internal_add_digest = f"{p.id}|{name}".encode()
    if seed is not None:
        run = hypothesis_seed(seed)(run)
    t0 = time.perf_counter()
    try:
        run()
    except PropertyFailure as f:
        return Result(p.id, p.name, name, FAILED, state["n"], time.perf_counter() - t0,
                      failure=f, example=state["last"])
    except Exception as e:  # the implementation itself raised: a crash on this input
        tb = "".join(traceback.format_exception_only(type(e), e)).strip()
        return Result(p.id, p.name, name, CRASHED, state["n"], time.perf_counter() - t0,
                      error=tb, example=state["last"])
    return Result(p.id, p.name, name, PASSED, state["n"], time.perf_counter() - t0)


def run_properties(impl, profile: str = "default", only=None, seed: int | None = None,
                   on_result=None) -> list[Result]:
    """Every registered (or ``only`` the given IDs) property on ``impl``."""
    s = named_profile(profile)
    results = []
    for p in all_properties():
        if only is not None and p.id not in only:
            continue
        r = run_property(p, impl, s, seed)
        results.append(r)
        if on_result is not None:
            on_result(r)
    return results


def check_implementation(impl, profile: str = "default", only=None,
                         seed: int | None = None) -> list[Result]:
    """Run every applicable property on ``impl``; raise AssertionError on any failure.

    >>> from oracles.exact_reference import ReferenceImplementation
    >>> results = check_implementation(ReferenceImplementation(), only={"D1.6"})
    >>> [r.status for r in results]
    ['passed']
    """
    results = run_properties(impl, profile, only, seed)
    bad = [r for r in results if not r.ok]
    if bad:
        raise AssertionError("\n\n".join(describe(r) for r in bad))
    return results


def describe(r: Result) -> str:
    """A failure or crash, as a user reads it."""
    if r.failure is not None:
        return str(r.failure)
    head = f"[{r.property_id}] {r.implementation}: {r.status}"
    if r.error:
        head += f"\n  {r.error}"
    if r.example is not None:
        head += f"\n  input: {r.example!r}"
    return head
