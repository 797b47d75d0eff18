"""Run properties against an implementation and collect results.

``check_implementation(impl)`` is the one-call check for a user's own tests: it
runs every applicable property under a Hypothesis profile and raises an
``AssertionError`` listing each failure (ID, shrunk mesh, element, expected vs
observed).  The CLI uses :func:`run_properties` and prints the results instead.

A :class:`Result` has one of these statuses:

* ``passed``: every example held, and the property ran the profile's number of examples
  on the implementation (or Hypothesis exhausted the examples its strategy can draw);
* ``incomplete``: every example that ran held, but fewer than the profile's number ran:
  the task's time budget ran out in our own computation (a call of the implementation
  still running then is its hang: ``crashed``), or the implementation declined so many
  examples as outside its domain that the search stopped.  Not a pass: :attr:`Result.ok`
  is False, ``ddg-oracle check`` exits 1 unless ``--accept-incomplete``;
* ``FAILED``: a :class:`~ddg_oracle.properties.registry.PropertyFailure` on the shrunk example;
* ``tie disagreement``: no failure, but on some example the exact reference
  decided an exact tie the implementation decided otherwise within its rounding
  (:class:`~ddg_oracle.properties.registry.TieDisagreement`); the smallest such example is kept;
* ``convention``: a failure that disappears when the implementation's documented
  convention is mapped onto the reference's (``counterpart``, see
  :func:`run_property`): expected, not an error;
* ``crashed``: the implementation raised, died, answered NaN where a failure is not
  the property's own, or hung (a call still running when the time ran out) on the
  (shrunk) example;
* ``undecided``: the exact reference hit one of its guards (a term limit, a precision
  limit, the time limit per example while our own computation ran:
  :class:`ddg_oracle.reference.errors.ExactArithmeticLimit`) before deciding, or an exact
  value the check needs as a float lies beyond the float range (``BeyondFloatRange``);
  the message says which;
* ``not applicable``: the implementation lacks a method the property needs, or
  declined every example as outside its domain
  (:class:`~ddg_oracle.protocol.methods.OutsideDomain`; a declined example is not
  counted, and Hypothesis draws another in its place);
* ``internal error``: ddg-oracle itself raised (in a strategy, the exact reference's
  arithmetic or a property's own code), not the implementation: nothing is said about
  the implementation, and the traceback is kept for a bug report (a failure found
  before it still stands, with a note).

``FAILED``, ``crashed``, ``incomplete`` and ``internal error`` are not ok
(:attr:`Result.ok` is False).
"""

from __future__ import annotations

import textwrap
import time
import weakref
from dataclasses import dataclass, field, replace
from fractions import Fraction

from hypothesis import HealthCheck, Phase, given, reject, seed as hypothesis_seed, settings as Settings
from hypothesis.errors import Unsatisfiable, UnsatisfiedAssumption
from hypothesis.reporting import with_reporter

from ..reference.errors import BeyondFloatRange, ExactArithmeticLimit

from ..protocol.budget import (Budget, BudgetExceeded, Hang, ImplementationHang, shrink_from_now,
                              task_budget)
from ..protocol.processes import SelfDescribed
from .calls import Watched, raised_by_implementation
from .counterexample import (INLINE_VERTICES, encode_example, exact_mesh, float_mesh,
                             implementation_spec, mesh_text, rounded_by_floats, snippet)
from .profiles import profile as named_profile, profile_budget
from .precision import inputs_at
from ..protocol.methods import (OutsideDomain, capabilities, implementation_name, machine_epsilon,
                       near_miss_warning, require_protocol)
from .registry import Property, PropertyFailure, TieDisagreement, select_properties, unjudged_entries
from .stream import generated_seed, keyed, same_stream, with_database

PASSED, FAILED, CRASHED, NOT_APPLICABLE = "passed", "FAILED", "crashed", "not applicable"
TIE, CONVENTION, UNDECIDED = "tie disagreement", "convention", "undecided"
INCOMPLETE, INTERNAL = "incomplete", "internal error"
#: every status, in the order of the summary counts
STATUSES = (PASSED, FAILED, TIE, CONVENTION, CRASHED, INCOMPLETE, UNDECIDED, INTERNAL,
            NOT_APPLICABLE)
#: statuses that are not a verdict of "holds": FAILED and crashed are the implementation's
#: failures, incomplete a check that did not run all its examples, internal error ours
NOT_OK = (FAILED, CRASHED, INCOMPLETE, INTERNAL)
#: what stops a search at once, without shrinking: the task's time ran out between calls
#: (BudgetExceeded) or inside one (ImplementationHang, recorded as a crash first)
_STOPS = (BudgetExceeded, ImplementationHang)


class _InternalError(BaseException):
    """Our own code raised while checking an example: stop the search at once (nothing
    more is learnt about the implementation, and shrinking our bug is not its job)."""


class NearMissWarning(UserWarning):
    """An implementation has a public method that looks like a protocol method it lacks."""


@dataclass
class Result:
    property_id: str
    property_name: str
    implementation: str
    status: str
    examples: int = 0
    wanted: int = 0                   # examples the profile asks for (0: one given example)
    seconds: float = 0.0
    failure: PropertyFailure | None = None   # the failure (or tie) on the shrunk example
    error: str | None = None          # the exception of a crash of the implementation
    example: object = None            # the shrunk example (in this process only; not pickled)
    mesh: tuple | None = None         # (V, F) nested lists of the failing or crashing input
    ties: int = 0                     # examples on which a tie was decided differently
    note: str | None = None           # why: not applicable, or which convention explains it
    source: str = "generated"         # "generated" (Hypothesis) or the name of a mesh file
    also: list = field(default_factory=list)   # other distinct failures Hypothesis reported
    replay: str | None = None         # the example, encoded (counterexample.encode_example)
    spec: str | None = None           # how to load the implementation again (None: unknown)
    exact: list | None = None         # exact coordinates (str) where the floats round them
    # per protocol method the property called, how its answer on the counterexample compares
    # with the exact one (ddg_oracle.application.compare.diagnose: quantity, status, where, expected,
    # observed, worst): which method is wrong, and where
    diagnosis: list | None = None
    # examples on which some entries had an infinite derived bound and an answer other than
    # the exact float view: those entries were not judged (the note says so)
    unjudged: int = 0

    @property
    def ok(self) -> bool:
        return self.status not in NOT_OK

    def summary(self) -> str:
        """The table cell."""
        if self.status == PASSED:
            partly = f"; {self.unjudged} partly judged" if self.unjudged else ""
            return f"passed ({self.examples} example{'s' if self.examples != 1 else ''}{partly})"
        if self.status == INCOMPLETE:
            return f"incomplete ({self.examples} of {self.wanted} examples)"
        if self.status == TIE:
            return f"tie disagreement ({self.ties}/{self.examples})"
        return self.status

    def __getstate__(self):
        state = self.__dict__.copy()
        state["example"] = None       # examples hold exact surfaces: not worth sending
        return state

    def to_json(self) -> dict:
        """Every field but the example, as JSON that :meth:`from_json` reads back without
        running code (:mod:`.codec`; ``--resume`` reads it from a report directory).  A
        mesh file's mesh is left out: the resumed run reads the file again."""
        from dataclasses import fields
        from .codec import encode
        state = {f.name: getattr(self, f.name) for f in fields(self) if f.name != "example"}
        if self.source != "generated":
            state["mesh"] = None
        return encode(state, lenient=True)

    @classmethod
    def from_json(cls, data) -> "Result":
        """The result :meth:`to_json` wrote; :class:`.codec.BadEncoding` for anything else
        (a field that is not one, a status that is not one)."""
        from dataclasses import fields
        from .codec import BadEncoding, decode
        state = decode(data)
        names = {f.name for f in fields(cls)} - {"example"}
        # a record written before a field was added lacks it: its default stands
        if not isinstance(state, dict) or not names - _ADDED <= set(state) <= names:
            raise BadEncoding("not a result record")
        if state["status"] not in STATUSES or not all(
                isinstance(state[k], str) for k in ("property_id", "property_name",
                                                     "implementation", "source")):
            raise BadEncoding(f"not a result record: status {state['status']!r}")
        if state["failure"] is not None and not isinstance(state["failure"], PropertyFailure):
            raise BadEncoding("not a result record: its failure is not one")
        return cls(**state)


#: fields added to :class:`Result` since results.json was first written (``--resume`` reads
#: older records without them)
_ADDED = frozenset({"unjudged"})


def example_mesh(example):
    """(V, F) as nested lists of floats of a property example (``.mesh``, ``.vertices`` and
    ``.faces``, or exact positions and faces: :func:`~.counterexample.exact_mesh`; the
    first such part of a tuple), or None."""
    if isinstance(example, tuple):
        for part in example:
            m = example_mesh(part)
            if m is not None:
                return m
        m = exact_mesh(example)
        return float_mesh(m) if m is not None else None
    mesh = getattr(example, "mesh", None)
    if isinstance(mesh, tuple) and len(mesh) == 2:
        return mesh
    if hasattr(example, "vertices") and hasattr(example, "faces"):
        return (example.vertices, example.faces)
    m = exact_mesh(example)
    return float_mesh(m) if m is not None else None


def _flatten(e: BaseException) -> list[BaseException]:
    if isinstance(e, BaseExceptionGroup):
        return [x for sub in e.exceptions for x in _flatten(sub)]
    return [e]


def _crash_text(e: BaseException) -> str:
    """``module.Type: message`` of what the implementation raised, without the notes
    Hypothesis attaches (its seed, "Failing test case: body(...)", explanations): the
    input is reported on its own, as a mesh; ``hang: ...`` for a call the clock stopped."""
    if isinstance(e, Hang):                 # the budget's, or an isolated call's own limit
        return f"hang: {e}"
    if isinstance(e, SelfDescribed):        # "lib.method raised ValueError: ...": as it is
        return str(e)
    name = type(e).__qualname__
    module = type(e).__module__
    if module not in ("builtins", "__main__"):
        name = f"{module}.{name}"
    text = str(e)
    return f"{name}: {text}" if text else name


def internal_text(e: BaseException) -> str:
    """Our own exception, with where it was raised (the last frames of its traceback) and a
    request for a bug report: the implementation is not to blame."""
    import traceback
    frames = traceback.extract_tb(e.__traceback__)[-3:]
    where = "; ".join(f"{f.filename.rsplit('/', 1)[-1]}:{f.lineno} in {f.name}" for f in frames)
    return (f"ddg-oracle raised {_crash_text(e)} (at {where}), not the implementation: "
            "this is a bug of ddg-oracle; please report it with this example")


@dataclass
class _Search:
    """What one property's search on one implementation has seen so far: written by the
    checked body as examples run, read to make the :class:`Result`."""
    wanted: int = 0                 # examples the profile asks for
    shrink: float | None = None     # the budget's shrink seconds (None: no limit)
    t0: float = 0.0                 # when the search started (perf_counter)
    n: int = 0                      # examples drawn, declined ones included
    last: object = None             # the last example drawn
    outside: int = 0                # examples the implementation declined as outside its domain
    why: str | None = None          # the first reason it gave
    ties: int = 0                   # tie disagreements seen
    tie: tuple | None = None        # (the smallest tie, its example)
    ties_raise: bool = False        # the second pass: a tie stops the search, to be shrunk
    failure: tuple | None = None    # (exception, example, mesh) of the smallest failure
    crash: tuple | None = None      # the same for the smallest crash
    crashes: int = 0                # crashes seen
    abort: bool = False             # stop: every later example is rejected
    stopped: str | None = None      # why the budget stopped the search
    refused: bool = False           # stopped because the implementation declines nearly all
    internal: tuple | None = None   # (our own exception, its example): a bug of ddg-oracle
    unjudged: int = 0               # examples with entries an infinite bound could not judge
    decided: int = 0                # examples that judged an entry (or needed no bound)


def _keep_smallest(state: _Search, key: str, e: BaseException, example) -> None:
    """Remember the smallest failing (``key="failure"``) or crashing example seen, in case
    the budget stops the search before Hypothesis has replayed its shrunk one.  The first
    one starts the shrinking, and its budget (:func:`_start_shrinking`)."""
    _start_shrinking(state)
    mesh = getattr(e, "mesh", None) or example_mesh(example)
    best = getattr(state, key)
    if best is None or _size(mesh) <= _size(best[2]):
        setattr(state, key, (e, example, mesh))


def _start_shrinking(state: _Search) -> None:
    """The first failure or crash (Hypothesis shrinks from here): the rest of the task
    gets at most the budget's shrink seconds."""
    if state.failure is None and state.crash is None:
        shrink_from_now(state.shrink)


def _size(mesh) -> int:
    return len(mesh[1]) if mesh is not None else 1 << 30


def _outcome(p: Property, impl, errors: list[BaseException], state: _Search) -> dict:
    """Status and details from what the run raised (several if Hypothesis found several)."""
    failures = [e for e in errors if isinstance(e, PropertyFailure)
                and not isinstance(e, TieDisagreement)]
    # the reference's guards (term, precision, and time limits: an overrun inside a call of
    # the implementation is an ImplementationHang instead, a crash)
    limits = [e for e in errors if isinstance(e, ExactArithmeticLimit)]
    crashes = [e for e in errors if not isinstance(e, PropertyFailure) and e not in limits
               and (raised_by_implementation(e) or isinstance(e, ImplementationHang))]
    ours = [e for e in errors if not isinstance(e, PropertyFailure) and e not in limits
            and e not in crashes]
    ties = [e for e in errors if isinstance(e, TieDisagreement)]
    if ours and not failures:
        return dict(status=INTERNAL, error=internal_text(ours[0]),
                    mesh=example_mesh(state.last))
    if failures:
        f = failures[0]
        return dict(status=FAILED, failure=f, mesh=f.mesh or example_mesh(state.last),
                    also=[str(e) for e in failures[1:]] + [_crash_text(e) for e in crashes])
    if crashes:
        return dict(status=CRASHED, error=_crash_text(crashes[0]),
                    mesh=example_mesh(state.last), also=[_crash_text(e) for e in crashes[1:]])
    if limits:
        return dict(status=UNDECIDED, error=_crash_text(limits[0]),
                    mesh=example_mesh(state.last))
    if ties or state.tie is not None:
        t = ties[0] if ties else state.tie[0]
        return dict(status=TIE, failure=t, mesh=t.mesh or example_mesh(state.tie[1]))
    return dict(status=PASSED)


_STRATEGIES: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()


def strategy_of(p: Property):
    """``p``'s strategy, built once per process: Hypothesis validates a strategy object and
    computes its emptiness, reusability and cacheability over the whole tree the first
    time it is drawn from, so a strategy built afresh for every run pays that again."""
    s = _STRATEGIES.get(p.strategy)
    if s is None:
        s = _STRATEGIES[p.strategy] = p.strategy()
    return s


def run_property(p: Property, impl, settings: Settings, seed: int | None = None,
                 counterpart=None, convention: str | None = None,
                 budget: Budget | None = None) -> Result:
    """Run one property on one implementation; never raises for a failing impl.

    ``counterpart``: the same library with its documented conventions mapped
    onto the reference's (e.g. ``Libigl()`` for ``Libigl(boundary="library")``).
    If ``impl`` fails and the counterpart passes the same (shrunk) example, the
    result is ``convention`` and ``note`` says which (``convention``).

    ``budget`` (:class:`~.budget.Budget`): wall-clock seconds and crash outcomes
    the whole run may take, shrinking included; when it runs out the search stops
    and the smallest failing (or crashing) example seen so far is the result, with
    a note; with none seen, the result is ``incomplete`` (a call of the implementation
    still running then is its hang: ``crashed``).  Every implementation of a property
    sees the same examples (the derandomized stream, or the same ``seed``): results
    are comparable across libraries.
    """
    name = implementation_name(impl)
    if not p.applies_to(capabilities(impl)):
        return Result(p.id, p.name, name, NOT_APPLICABLE,
                      note=f"lacks {p.lacks(capabilities(impl))} (protocol methods this "
                           "property needs)")
    state = _Search(wanted=settings.max_examples,
                    shrink=budget.shrink if budget is not None else None)
    max_crashes = budget.crashes if budget is not None else None
    watched = Watched(impl, p.id)
    # examples the implementation declines are counted, not checked; the check is wrapped
    # here so that `run` below keeps its source, hence Hypothesis's derandomized seeds
    prop, p = p, replace(p, check=_in_domain(p.check, state))

    def body(example):
        if state.abort:
            return
        # Hypothesis replays the shrunk example last, so "last" is minimal.
        state.n += 1
        state.last = example
        declined = state.outside
        try:
            _check(p, watched, example, state)
        except TieDisagreement as t:
            # keep the smallest tie of either pass
            if state.tie is None or _size(t.mesh) < _size(state.tie[0].mesh):
                state.tie = (t, example)
            if state.ties_raise:
                raise                               # the second pass: shrink the tie
            # not an error: keep going (a tie never hides a failure)
            state.ties += 1
        except PropertyFailure as e:
            if not state.ties_raise:
                _keep_smallest(state, "failure", e, example)
            raise
        except (BudgetExceeded, UnsatisfiedAssumption):
            raise                    # the task's clock; a property's assume(): not an example
        except BaseException as e:
            if not isinstance(e, (KeyboardInterrupt, SystemExit, ExactArithmeticLimit,
                                  ImplementationHang)) and not raised_by_implementation(e):
                # not the implementation's: ddg-oracle's own code raised
                state.internal = (e, example)
                raise _InternalError() from e
            if not state.ties_raise:
                if not isinstance(e, (KeyboardInterrupt, SystemExit)):
                    _keep_smallest(state, "crash", e, example)
                    state.crashes += 1
                    if max_crashes is not None and state.crashes > max_crashes:
                        raise BudgetExceeded(f"{max_crashes} crashes or hangs of the "
                                             "implementation") from None
                raise
            # the second pass only shrinks a tie: a crash or hang on one of its simpler
            # candidates is not chased (each hang costs the call timeout); stop here, the
            # smallest tie seen so far stands
            state.abort = True
        if state.outside > declined:
            # declined (OutsideDomain): not an example of its domain, so Hypothesis draws
            # another in its place (and the shrinker never steps into the declined part);
            # while no failure is found, an implementation that declines nearly
            # everything stops the search
            if state.failure is None and state.crash is None and _futile(state):
                state.refused = True
                raise BudgetExceeded(f"the implementation declined {state.outside} "
                                     f"examples as outside its domain")
            reject()

    # each property its own database key and derandomized seed, the same for every
    # implementation (one example stream per property: results comparable across libraries,
    # a failing example saved for one library replayed on the others).  Hypothesis derives
    # both from the test function, the same `body` for every property; this is the hook
    # its pytest plugin uses for parametrized tests (no public API exists for it)
    keyed(body, p.id.encode())
    t0 = state.t0 = time.perf_counter()
    # examples drawn in the implementation's own input format (float32 ones for a float32
    # implementation): it receives exactly the numbers the reference computes with
    with task_budget(budget.seconds if budget is not None else None), \
            inputs_at(machine_epsilon(impl)):
        errors, run = _search(body, p, settings, seed, state=state)
        # the second pass only shrinks: without the shrink phase it would replay, up to the
        # first tie, examples the first pass ran already
        if not errors and state.tie is not None and state.stopped is None \
                and Phase.shrink in settings.phases:
            errors = _shrink_tie(body, p, settings, seed, run, state)
    out = _outcome(p, impl, errors, state)
    r = Result(p.id, p.name, name, examples=state.n - state.outside,
               wanted=settings.max_examples, seconds=time.perf_counter() - t0,
               ties=state.ties, example=state.last, **out)
    _note_outside(r, state)
    _judge_completeness(r, state)
    _note_unjudged(r, state)
    if state.internal is not None and r.status != INTERNAL:
        r.note = _joined(r.note, "then " + internal_text(state.internal[0]))
    r.spec = implementation_spec(impl)
    _attach_counterexample(r, impl, state.tie[1] if r.status == TIE else state.last)
    if r.status == FAILED and counterpart is not None:
        _explain_by_convention(r, prop, counterpart, convention)
    return r


def _futile(state: _Search) -> bool:
    """Whether the search should stop drawing in place of declined examples.

    Declines are replaced, but not without end.  Up to 8 per wanted example the search
    goes on whatever the rate (room for OpenMesh, which declines the non-orientable and
    inconsistently oriented draws: CS draws two surfaces, each may be either); past that
    it stops if nothing ran, or if at the rate seen so far all wanted examples would
    cost more than 32 declines each (PyGEL3D declines the non-orientable, inconsistently
    oriented and touching draws of D2.2, about 12 in 13; a fixed cap of 8 ended its runs
    ``incomplete`` on some seeds).  Hypothesis's own limit is 458 + 100 per valid example.
    """
    outside, wanted = state.outside, state.wanted
    accepted = state.n - outside
    if outside < 8 * wanted:
        return False
    return accepted <= 0 or outside >= 32 * wanted or outside > 32 * accepted


def _judge_completeness(r: Result, state: _Search) -> None:
    """A search that found nothing wrong but ran fewer examples than the profile asks
    for is ``incomplete`` (or ``not applicable`` if the implementation declined them
    all), whether the budget or the implementation's refusals stopped it; one that
    Hypothesis ended by itself with fewer (every example the strategy can draw was run,
    none declined) is a pass.  A failure or crash keeps its status, with a note."""
    stopped = state.stopped
    if r.status in (FAILED, CRASHED, INTERNAL):
        if stopped is not None and stopped not in (r.error or ""):
            r.note = _joined(r.note, f"shrinking stopped early: {stopped}")
        return
    if r.status not in (PASSED, TIE) or r.examples >= r.wanted:
        return
    draws = state.n
    if stopped is None and not (state.outside and draws >= r.wanted):
        return                       # Hypothesis exhausted the strategy: every example ran
    if r.examples == 0 and state.outside and (state.refused or stopped is None):
        r.status = NOT_APPLICABLE
        return
    why = stopped if stopped is not None and not state.refused else \
        f"the implementation declined {state.outside} examples as outside its domain " \
        f"({state.why})"
    r.note = f"{r.examples} of {r.wanted} examples ran: {why}"
    r.status = INCOMPLETE


def _joined(*notes) -> str:
    return "; ".join(filter(None, notes))


def _search(body, p: Property, settings: Settings, seed, state=None, **changes):
    """Run Hypothesis on ``body``: (what it raised, flattened; the wrapped test).

    A :class:`~.budget.BudgetExceeded` or an :class:`~.budget.ImplementationHang` stops
    the search: what it raised is then the smallest failure (else crash, the hang
    included) ``state`` recorded, and ``state.stopped`` says why."""
    # one failure per property, the shrunk one: several distinct failures would come
    # back as an ExceptionGroup and read as a crash.  No explain phase: its report is not
    # ours to print, and on Python < 3.12 it runs the failing example under sys.settrace,
    # where the example time limit's SIGALRM raised inside the tracer (seen in a fresh-clone
    # run: "Exception ignored in ... scrutineer trace", and once a segfault of the worker)
    if "phases" not in changes:
        changes["phases"] = tuple(x for x in settings.phases if x != Phase.explain)
    # declined examples are rejected (body): many of them are the implementation's choice,
    # not a strategy that filters too much
    changes["suppress_health_check"] = tuple(settings.suppress_health_check) + (
        HealthCheck.filter_too_much,)
    run = Settings(settings, report_multiple_bugs=False, **changes)(given(strategy_of(p))(body))
    if seed is None and settings.derandomize:
        seed = derandomized_seed(p.id)
    if seed is not None:
        run = hypothesis_seed(seed)(run)
        if settings.database is not None and "database" not in changes:
            # Hypothesis's @seed turns the example database off; a chosen database must
            # still replay saved failures first and save new ones (the same key for every
            # implementation of the property), seed or not
            run = with_database(run, settings.database)
    try:
        # the property's stream, whatever this process loaded; Hypothesis's own reports
        # ("You can reproduce this failure by adding @seed...", falsifying examples) are not
        # ours to print: the result says what happened, with its own replay
        with same_stream(), with_reporter(lambda text: None):
            run()
    except _STOPS as e:
        if state is None:
            raise
        state.stopped = str(e)
        best = state.failure or state.crash
        if best is None:
            return [], run
        state.last = best[1]
        return [best[0]], run
    except _InternalError:
        if state is None:
            raise
        e, example = state.internal
        best = state.failure or state.crash
        if best is None:                     # our bug on this example: that is the result
            state.last = example
            return [e], run
        state.last = best[1]
        return [best[0]], run
    except Unsatisfiable:
        return [], run                 # every example declined: judged from the counts
    except BaseException as e:  # noqa: BLE001  (anything the implementation did is a result)
        if isinstance(e, (KeyboardInterrupt, SystemExit)):
            raise
        return _flatten(e), run
    return [], run


def derandomized_seed(property_id: str) -> int:
    """The seed of a derandomized run (the ``ci`` profile) of a property: from its catalog
    ID alone.  Hypothesis would derive it from the test function's source, so every edit of
    the runner would change which examples ci draws; this way the stream changes only
    with the property's strategy.

    >>> derandomized_seed("D1.6") == derandomized_seed("D1.6") != derandomized_seed("D2.2")
    True
    """
    import hashlib
    return int.from_bytes(hashlib.sha256(b"ddg-oracle " + property_id.encode()).digest()[:16],
                          "big")


def _shrink_tie(body, p: Property, settings: Settings, seed, run, state) -> list:
    """Tie disagreements do not stop the search, so Hypothesis does not shrink them.
    Second pass: the same example stream (the same seed, or the same derandomized
    digest), this time with ties raising, so the first tie is shrunk; ``state.tie``
    ends as the smallest tie of both passes (if the stream differs, e.g. after a
    database replay, the first pass's stands).  A crash or hang of the implementation
    on a candidate of this pass stops it (not chased: each hang costs the timeout).
    Returns a real failure this pass found on a simpler example, if any."""
    n, ties, outside = state.n, state.ties, state.outside
    # this pass replays at most the first pass's examples, then shrinks: it gets the first
    # pass's time plus the shrink budget (body's source stays as it is: it seeds the
    # derandomized example stream)
    if state.shrink is not None:
        shrink_from_now(state.shrink + time.perf_counter() - state.t0)
    # the seed Hypothesis generated for the first pass: no public API exposes it (it is
    # printed only with a failure), and this pass must replay that very stream
    seed = seed if seed is not None else generated_seed(run)
    state.ties_raise = True
    try:
        # the first pass's examples that ran (declined ones are drawn past, as there)
        errors, _ = _search(body, p, settings, seed, database=None,
                            max_examples=max(1, n - outside))
    except (*_STOPS, _InternalError):
        errors = []                      # out of time: the smallest tie so far stands
    finally:
        state.n, state.ties, state.outside, state.ties_raise, state.abort = \
            n, ties, outside, False, False
    state.last = state.tie[1]                 # body kept the smallest tie of both passes
    # a real failure on a simpler example the first pass missed is a result too
    return [e for e in errors if isinstance(e, PropertyFailure)
            and not isinstance(e, TieDisagreement)]


#: generated examples up to this many faces are encoded for replay (a mesh file's are
#: not: its snippet checks the file again)
REPLAY_FACES = 2000


def _attach_counterexample(r: Result, impl, example) -> None:
    """What a user needs to act on a non-passing result: the implementation's spec, the
    exact coordinates where its floats round them, the example encoded for replay."""
    if r.status in (PASSED, NOT_APPLICABLE, INCOMPLETE) or example is None:
        return                                  # nothing failed: no counterexample
    r.spec = implementation_spec(impl)
    try:
        if r.mesh is None:
            r.mesh = example_mesh(example)
        exact = exact_mesh(example)
        if exact is not None and rounded_by_floats(exact[0]):
            r.exact = [[str(Fraction(c)) for c in p] for p in exact[0]]
    except Exception as e:  # noqa: BLE001  (our own bug must not hide the verdict)
        r.note = _joined(r.note, f"ddg-oracle could not attach the exact mesh "
                                 f"({type(e).__name__}: {e}); please report it")
    if r.source != "generated" or (r.mesh is not None and len(r.mesh[1]) > REPLAY_FACES):
        return                                  # a mesh file's snippet checks the file again
    try:
        r.replay = encode_example(example)
    except Exception:  # noqa: BLE001  (an example the codec does not write: no replay line)
        r.replay = None


def _in_domain(check, state: _Search):
    """``check`` that counts an OutsideDomain of the implementation instead of raising it."""
    def check_in_domain(impl, example):
        try:
            check(impl, example)
        except OutsideDomain as o:
            state.outside += 1
            state.why = state.why or str(o)
    return check_in_domain


def _note_outside(r: Result, state: _Search) -> None:
    """Examples the implementation declined (OutsideDomain): a note; all of them: not applicable."""
    if not state.outside:
        return
    r.note = f"{state.outside} example(s) outside its domain: {state.why}"
    if r.status == PASSED and r.examples == 0:
        r.status = NOT_APPLICABLE


def _note_unjudged(r: Result, state: _Search) -> None:
    """Examples with entries no finite bound could judge: said, so that a pass says what
    it covers (those entries are neither passed nor failed; the others of the example
    were judged)."""
    if state.unjudged and r.status not in (NOT_APPLICABLE, INTERNAL):
        # examples, not entries: a check may compare one entry more than once; and at most
        # the examples counted (a failure's shrinking runs examples again)
        n = max(r.examples, 1)
        r.unjudged = min(state.unjudged, n)
        if r.status == PASSED and not state.decided:
            # not one entry of one example compared against a finite bound: nothing was
            # checked (a mesh below the float range's resolution), so nothing passed
            r.status = UNDECIDED
            r.note = _joined(r.note, f"no entry of {'the' if n == 1 else 'any'} example could "
                             "be judged: every derived bound is infinite (beyond the "
                             "resolution of the declared precision)")
            return
        r.note = _joined(r.note, f"{r.unjudged} of {n} examples had entries no finite bound "
                         "could judge (an infinite derived bound: beyond the resolution of the "
                         "declared precision); those entries were neither passed nor failed")


def _explain_by_convention(r: Result, p: Property, counterpart, convention) -> None:
    """Re-check the shrunk example with the reference-convention counterpart."""
    try:
        p.check(Watched(counterpart, p.id), r.example)
    except TieDisagreement:
        pass
    except BaseException as e:  # noqa: BLE001
        if isinstance(e, (KeyboardInterrupt, SystemExit)):
            raise
        return
    r.status = CONVENTION
    r.note = (f"documented convention {convention or ''}: "
              f"{implementation_name(counterpart)} passes the same example").replace("  ", " ")


def _check(p: Property, watched, example, state: _Search | None = None) -> None:
    """``p.check(watched, example)``; an OverflowError of ours (a float view or bound of an
    exact value beyond the float range: a needle's cotangent) is the reference's limit,
    :class:`~ddg_oracle.reference.errors.BeyondFloatRange` (``undecided``), not an internal
    error; the implementation's own stays its crash.  Entries the check could not judge
    (an infinite bound: :class:`~.registry.Unjudged`) are counted in ``state``."""
    try:
        with unjudged_entries() as tally:
            try:
                p.check(watched, example)
            finally:
                if state is not None:
                    state.unjudged += bool(tally.entries)
                    # an example whose every bounded comparison met an infinite bound decided
                    # nothing; one with no such comparison compared in its own way
                    state.decided += bool(tally.judged or not tally.entries)
    except OverflowError as e:
        # only the float of an exact number (int, Fraction, Surd: "... too large ... float"):
        # float arithmetic on an implementation's answer overflows with other messages
        # ("Numerical result out of range"), and that stays ours to explain, not undecided
        if raised_by_implementation(e) or not ("too large" in str(e) and "float" in str(e)):
            raise
        raise BeyondFloatRange(f"[{p.id}] an exact value this check needs lies beyond the "
                               f"float range ({e})") from e


def run_on_example(p: Property, impl, example, source: str, counterpart=None,
                   convention: str | None = None) -> Result:
    """One property on one given example (e.g. built from a mesh file), no Hypothesis;
    ``counterpart`` and ``convention`` as in :func:`run_property`."""
    name = implementation_name(impl)
    if not p.applies_to(capabilities(impl)):
        return Result(p.id, p.name, name, NOT_APPLICABLE, source=source,
                      note=f"lacks {p.lacks(capabilities(impl))}")
    state = _Search(n=1, last=example)
    t0 = time.perf_counter()
    try:
        _check(p, Watched(impl, p.id), example, state)
        errors = []
    except OutsideDomain as o:
        state.outside, state.why, errors = 1, str(o), []
    except BaseException as e:  # noqa: BLE001
        if isinstance(e, (KeyboardInterrupt, SystemExit)):
            raise
        errors = [e]
        state.ties = int(isinstance(e, TieDisagreement))
    out = _outcome(p, impl, errors, state)
    r = Result(p.id, p.name, name, examples=1 - state.outside, seconds=time.perf_counter() - t0,
               ties=state.ties, example=example, source=source, **out)
    _note_outside(r, state)
    _note_unjudged(r, state)
    _attach_counterexample(r, impl, example)
    if r.status == FAILED and counterpart is not None:
        _explain_by_convention(r, p, counterpart, convention)
    return r


def run_properties(impl, profile: str = "default", only=None, seed: int | None = None,
                   on_result=None) -> list[Result]:
    """Every registered property (or those of the catalog IDs ``only``, parts of joint IDs
    included) on ``impl``; :class:`~.protocol.NotAnImplementation` if ``impl`` defines
    none of the protocol's methods (every property would pass vacuously), a warning if it
    has a method that looks like one it lacks (:func:`~.protocol.near_miss_warning`)."""
    require_protocol(impl)
    said = near_miss_warning(impl)
    if said:
        import warnings
        warnings.warn(said, NearMissWarning, stacklevel=3)
    s, budget = named_profile(profile), profile_budget(profile)
    results = []
    for p in select_properties(only):
        r = run_property(p, impl, s, seed, budget=budget)
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


def describe(r: Result, limit: int | None = None, snippet_lines: int | None = None,
             files: str | None = None) -> str:
    """A failure, crash, tie or convention, as a user reads it: what, where, expected vs
    observed, the bound, the whole mesh (``V`` as round-tripping floats, the exact
    coordinates where the floats round them, ``F``) and a snippet that replays it.

    ``limit``: vertices and faces shown before eliding (default
    :data:`~.counterexample.INLINE_VERTICES`); ``snippet_lines``: a longer snippet is
    not shown but pointed to in ``files`` (where the full mesh and snippet are)."""
    if r.failure is not None:
        # the failure's one-line mesh summary is replaced by the whole mesh below
        text = "\n".join(line for line in str(r.failure).splitlines()
                         if not line.startswith("  mesh: "))
    else:
        text = f"[{r.property_id}] {r.implementation}: {r.status}"
        if r.error:
            text += "\n  " + r.error.replace("\n", "\n  ")
        if r.mesh is None and r.example is not None and r.status not in (INCOMPLETE, PASSED):
            text += f"\n  input: {r.example!r}"
    if r.source != "generated":
        text += f"\n  on: {r.source}"
    if r.note and r.status not in (PASSED, NOT_APPLICABLE):
        text += f"\n  note: {r.note}"
    for other in r.also:
        text += "\n  also: " + other.replace("\n", "\n  ")
    if r.mesh is not None:
        exact = (r.exact, r.mesh[1]) if r.exact is not None else None
        text += "\n" + mesh_text(r.mesh, exact, **({"limit": limit} if limit else {}))
        shown = limit or INLINE_VERTICES
        if files and (len(r.mesh[0]) > shown or len(r.mesh[1]) > shown):
            text += f"\n  the whole mesh: {files}"
    if r.replay is not None:
        code = snippet(r.property_id, r.spec, r.replay)
        if snippet_lines is not None and code.count("\n") + 1 > snippet_lines:
            text += f"\n  reproduce: the snippet is {code.count(chr(10)) + 1} lines" + (
                f", in {files}" if files else "; see results.json of --report DIR")
        else:
            text += "\n  reproduce (raises the same failure):\n" + textwrap.indent(code, "    ")
    return text
