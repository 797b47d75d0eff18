"""Run properties against an implementation and collect results.

``check_implementation(impl)`` is the one-call check for a user's own tests: it
runs every applicable property under a Hypothesis profile and raises an
``AssertionError`` listing each failure (ID, shrunk mesh, element, expected vs
observed).  The CLI uses :func:`run_properties` and prints the results instead.

A :class:`Result` has one of these statuses:

* ``passed``: every example held;
* ``FAILED``: a :class:`~ddg_oracle.properties.registry.PropertyFailure` on the shrunk example;
* ``tie disagreement``: no failure, but on some example the exact reference
  decided an exact tie the implementation decided otherwise within its rounding
  (:class:`~ddg_oracle.properties.registry.TieDisagreement`); the smallest such example is kept;
* ``convention``: a failure that disappears when the implementation's documented
  convention is mapped onto the reference's (``counterpart``, see
  :func:`run_property`): expected, not an error;
* ``crashed``: the implementation raised, died or hung on the (shrunk) example;
* ``undecided``: the exact reference hit one of its guards (a term limit, a
  precision limit; the per-example time limit counts as a hang:
  :class:`ddg_oracle.reference.errors.ExactArithmeticLimit`) before deciding; the message
  says which limit to raise;
* ``not applicable``: the implementation lacks a method the property needs, or
  declined every example as outside its domain
  (:class:`~ddg_oracle.properties.protocol.OutsideDomain`; declined examples are not counted).

Only ``FAILED`` and ``crashed`` are failures (:attr:`Result.ok` is False).
"""

from __future__ import annotations

import time
import traceback
from dataclasses import dataclass, field, replace

from hypothesis import given, seed as hypothesis_seed, settings as Settings

from ddg_oracle.reference.errors import ExactArithmeticLimit, TimeLimitExceeded

from .profiles import profile as named_profile
from .protocol import OutsideDomain, capabilities, implementation_name, require_protocol
from .registry import Property, PropertyFailure, TieDisagreement, faces_text, select_properties

PASSED, FAILED, CRASHED, NOT_APPLICABLE = "passed", "FAILED", "crashed", "not applicable"
TIE, CONVENTION, UNDECIDED = "tie disagreement", "convention", "undecided"
#: every status, in the order of the summary counts
STATUSES = (PASSED, FAILED, TIE, CONVENTION, CRASHED, UNDECIDED, NOT_APPLICABLE)


@dataclass
class Result:
    property_id: str
    property_name: str
    implementation: str
    status: str
    examples: int = 0
    seconds: float = 0.0
    failure: PropertyFailure | None = None   # the failure (or tie) on the shrunk example
    error: str | None = None          # the exception of a crash of the implementation
    example: object = None            # the shrunk example (in this process only; not pickled)
    mesh: tuple | None = None         # (V, F) nested lists of the failing or crashing input
    ties: int = 0                     # examples on which a tie was decided differently
    note: str | None = None           # why: not applicable, or which convention explains it
    source: str = "generated"         # "generated" (Hypothesis) or the name of a mesh file
    also: list = field(default_factory=list)   # other distinct failures Hypothesis reported

    @property
    def ok(self) -> bool:
        return self.status not in (FAILED, CRASHED)

    def summary(self) -> str:
        """The table cell."""
        if self.status == PASSED:
            return f"passed ({self.examples} example{'s' if self.examples != 1 else ''})"
        if self.status == TIE:
            return f"tie disagreement ({self.ties}/{self.examples})"
        return self.status

    def __getstate__(self):
        state = self.__dict__.copy()
        state["example"] = None       # examples hold exact surfaces: not worth sending
        return state


def example_mesh(example):
    """(V, F) as nested lists of a property example (``.mesh``, or ``.vertices`` and
    ``.faces``; the first such part of a tuple), or None."""
    if isinstance(example, tuple):
        for part in example:
            m = example_mesh(part)
            if m is not None:
                return m
        return None
    mesh = getattr(example, "mesh", None)
    if isinstance(mesh, tuple) and len(mesh) == 2:
        return mesh
    if hasattr(example, "vertices") and hasattr(example, "faces"):
        return (example.vertices, example.faces)
    return None


def _flatten(e: BaseException) -> list[BaseException]:
    if isinstance(e, BaseExceptionGroup):
        return [x for sub in e.exceptions for x in _flatten(sub)]
    return [e]


def _crash_text(e: BaseException) -> str:
    return "".join(traceback.format_exception_only(type(e), e)).strip()


def _size(mesh) -> int:
    return len(mesh[1]) if mesh is not None else 1 << 30


def _outcome(p: Property, impl, errors: list[BaseException], state: dict) -> dict:
    """Status and details from what the run raised (several if Hypothesis found several)."""
    failures = [e for e in errors if isinstance(e, PropertyFailure)
                and not isinstance(e, TieDisagreement)]
    # an example over its time limit counts as a hang of the implementation (a failure),
    # not as undecided: the reference's own guards are term and precision limits
    limits = [e for e in errors if isinstance(e, ExactArithmeticLimit)
              and not isinstance(e, TimeLimitExceeded)]
    crashes = [e for e in errors if not isinstance(e, PropertyFailure) and e not in limits]
    ties = [e for e in errors if isinstance(e, TieDisagreement)]
    if failures:
        f = failures[0]
        return dict(status=FAILED, failure=f, mesh=f.mesh or example_mesh(state["last"]),
                    also=[str(e) for e in failures[1:]] + [_crash_text(e) for e in crashes])
    if crashes:
        return dict(status=CRASHED, error=_crash_text(crashes[0]),
                    mesh=example_mesh(state["last"]), also=[_crash_text(e) for e in crashes[1:]])
    if limits:
        return dict(status=UNDECIDED, error=_crash_text(limits[0]),
                    mesh=example_mesh(state["last"]))
    if ties or state["tie"] is not None:
        t = ties[0] if ties else state["tie"][0]
        return dict(status=TIE, failure=t, mesh=t.mesh or example_mesh(state["tie"][1]))
    return dict(status=PASSED)


def run_property(p: Property, impl, settings: Settings, seed: int | None = None,
                 counterpart=None, convention: str | None = None) -> Result:
    """Run one property on one implementation; never raises for a failing impl.

    ``counterpart``: the same library with its documented conventions mapped
    onto the reference's (e.g. ``Libigl()`` for ``Libigl(boundary="library")``).
    If ``impl`` fails and the counterpart passes the same (shrunk) example, the
    result is ``convention`` and ``note`` says which (``convention``).
    """
    name = implementation_name(impl)
    if not p.applies_to(capabilities(impl)):
        missing = sorted(p.needs - capabilities(impl))
        return Result(p.id, p.name, name, NOT_APPLICABLE,
                      note=f"lacks {', '.join(missing)} (protocol method"
                           f"{'s' if len(missing) > 1 else ''} this property needs)")
    state = {"n": 0, "last": None, "ties": 0, "tie": None, "ties_raise": False, "outside": 0,
             "why": None, "abort": False}
    # examples the implementation declines are counted, not checked; the check is wrapped
    # here so that `run` below keeps its source, hence Hypothesis's derandomized seeds
    prop, p = p, replace(p, check=_in_domain(p.check, state))

    def body(example):
        if state["abort"]:
            return
        # Hypothesis replays the shrunk example last, so "last" is minimal.
        state["n"] += 1
        state["last"] = example
        try:
            p.check(impl, example)
        except TieDisagreement as t:
            # keep the smallest tie of either pass
            if state["tie"] is None or _size(t.mesh) < _size(state["tie"][0].mesh):
                state["tie"] = (t, example)
            if state["ties_raise"]:
                raise                               # the second pass: shrink the tie
            # not an error: keep going (a tie never hides a failure)
            state["ties"] += 1
        except PropertyFailure:
            raise
        except BaseException:
            if not state["ties_raise"]:
                raise
            # the second pass only shrinks a tie: a crash or hang on one of its simpler
            # candidates is not chased (each hang costs the call timeout); stop here, the
            # smallest tie seen so far stands
            state["abort"] = True

    # each (property, implementation) its own database key and derandomized seed: Hypothesis
    # derives both from the test function, the same `body` for every property (as its pytest
    # plugin does for parametrized tests)
    body._hypothesis_internal_add_digest = f"{p.id}|{name}".encode()
    t0 = time.perf_counter()
    errors, run = _search(body, p, settings, seed)
    if not errors and state["tie"] is not None:
        errors = _shrink_tie(body, p, settings, seed, run, state)
    out = _outcome(p, impl, errors, state)
    r = Result(p.id, p.name, name, examples=state["n"] - state["outside"],
               seconds=time.perf_counter() - t0, ties=state["ties"], example=state["last"], **out)
    _note_outside(r, state)
    if r.status == FAILED and counterpart is not None:
        _explain_by_convention(r, prop, counterpart, convention)
    return r


def _search(body, p: Property, settings: Settings, seed, **changes):
    """Run Hypothesis on ``body``: (what it raised, flattened; the wrapped test)."""
    # one failure per property, the shrunk one: several distinct failures would come
    # back as an ExceptionGroup and read as a crash
    run = Settings(settings, report_multiple_bugs=False, **changes)(given(p.strategy())(body))
    if seed is not None:
        run = hypothesis_seed(seed)(run)
    try:
        run()
    except BaseException as e:  # noqa: BLE001  (anything the implementation did is a result)
        if isinstance(e, (KeyboardInterrupt, SystemExit)):
            raise
        return _flatten(e), run
    return [], run


def _shrink_tie(body, p: Property, settings: Settings, seed, run, state) -> list:
    """Tie disagreements do not stop the search, so Hypothesis does not shrink them.
    Second pass: the same example stream (the same seed, or the same derandomized
    digest), this time with ties raising, so the first tie is shrunk; ``state["tie"]``
    ends as the smallest tie of both passes (if the stream differs, e.g. after a
    database replay, the first pass's stands).  A crash or hang of the implementation
    on a candidate of this pass stops it (not chased: each hang costs the timeout).
    Returns a real failure this pass found on a simpler example, if any."""
    n, ties, outside = state["n"], state["ties"], state["outside"]
    seed = seed if seed is not None else getattr(run, "_hypothesis_internal_use_generated_seed",
                                                 None)
    state["ties_raise"] = True
    try:
        errors, _ = _search(body, p, settings, seed, database=None, max_examples=n)
    finally:
        state.update(n=n, ties=ties, outside=outside, ties_raise=False, abort=False)
    state["last"] = state["tie"][1]                 # body kept the smallest tie of both passes
    # a real failure on a simpler example the first pass missed is a result too
    return [e for e in errors if isinstance(e, PropertyFailure)
            and not isinstance(e, TieDisagreement)]


def _in_domain(check, state: dict):
    """``check`` that counts an OutsideDomain of the implementation instead of raising it."""
    def check_in_domain(impl, example):
        try:
            check(impl, example)
        except OutsideDomain as o:
            state["outside"] += 1
            state["why"] = state["why"] or str(o)
    return check_in_domain


def _note_outside(r: Result, state: dict) -> None:
    """Examples the implementation declined (OutsideDomain): a note; all of them: not applicable."""
    if not state["outside"]:
        return
    r.note = f"{state['outside']} example(s) outside its domain: {state['why']}"
    if r.status == PASSED and r.examples == 0:
        r.status = NOT_APPLICABLE


def _explain_by_convention(r: Result, p: Property, counterpart, convention) -> None:
    """Re-check the shrunk example with the reference-convention counterpart."""
    try:
        p.check(counterpart, r.example)
    except TieDisagreement:
        pass
    except BaseException as e:  # noqa: BLE001
        if isinstance(e, (KeyboardInterrupt, SystemExit)):
            raise
        return
    r.status = CONVENTION
    r.note = (f"documented convention {convention or ''}: "
              f"{implementation_name(counterpart)} passes the same example").replace("  ", " ")


def run_on_example(p: Property, impl, example, source: str, counterpart=None,
                   convention: str | None = None) -> Result:
    """One property on one given example (e.g. built from a mesh file), no Hypothesis;
    ``counterpart`` and ``convention`` as in :func:`run_property`."""
    name = implementation_name(impl)
    if not p.applies_to(capabilities(impl)):
        missing = sorted(p.needs - capabilities(impl))
        return Result(p.id, p.name, name, NOT_APPLICABLE, source=source,
                      note=f"lacks {', '.join(missing)}")
    state = {"n": 1, "last": example, "ties": 0, "tie": None, "outside": 0, "why": None}
    t0 = time.perf_counter()
    try:
        p.check(impl, example)
        errors = []
    except OutsideDomain as o:
        state["outside"], state["why"], errors = 1, str(o), []
    except BaseException as e:  # noqa: BLE001
        if isinstance(e, (KeyboardInterrupt, SystemExit)):
            raise
        errors = [e]
        state["ties"] = int(isinstance(e, TieDisagreement))
    out = _outcome(p, impl, errors, state)
    r = Result(p.id, p.name, name, examples=1 - state["outside"], seconds=time.perf_counter() - t0,
               ties=state["ties"], example=example, source=source, **out)
    _note_outside(r, state)
    if r.status == FAILED and counterpart is not None:
        _explain_by_convention(r, p, counterpart, convention)
    return r


def run_properties(impl, profile: str = "default", only=None, seed: int | None = None,
                   on_result=None) -> list[Result]:
    """Every registered property (or those of the catalog IDs ``only``, parts of joint IDs
    included) on ``impl``; :class:`~.protocol.NotAnImplementation` if ``impl`` defines
    none of the protocol's methods (every property would pass vacuously)."""
    require_protocol(impl)
    s = named_profile(profile)
    results = []
    for p in select_properties(only):
        r = run_property(p, impl, s, seed)
        results.append(r)
        if on_result is not None:
            on_result(r)
    return results


def check_implementation(impl, profile: str = "default", only=None,
                         seed: int | None = None) -> list[Result]:
    """Run every applicable property on ``impl``; raise AssertionError on any failure.

    >>> from ddg_oracle.oracles.exact_reference import ReferenceImplementation
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
    """A failure, crash, tie or convention, as a user reads it."""
    if r.failure is not None:
        text = str(r.failure)
    else:
        text = f"[{r.property_id}] {r.implementation}: {r.status}"
        if r.error:
            text += f"\n  {r.error}"
        if r.mesh is not None:
            V, F = r.mesh
            text += f"\n  mesh: {len(V)} vertices, {len(F)} faces; F = {faces_text(F)}"
        elif r.example is not None:
            text += f"\n  input: {r.example!r}"
    if r.source != "generated":
        text += f"\n  on: {r.source}"
    if r.note and r.status in (CONVENTION,):
        text += f"\n  {r.note}"
    for other in r.also:
        text += "\n  also: " + other.replace("\n", "\n  ")
    return text
