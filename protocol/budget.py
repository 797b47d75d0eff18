"""The budget of one check task: wall-clock seconds and crashes, so no task runs away.

A property's Hypothesis run on an implementation that crashes or hangs would
otherwise shrink that input one crash (or one call timeout) at a time: minutes
per task.  A task runs under :func:`task_budget`:

- ``seconds``: wall-clock time for the whole task, shrinking included.  A call
  of an isolated implementation waits at most the time left (a call cut short
  is a hang of the implementation, reported with its input), and the example
  time limit (:func:`ddg_oracle.properties.profiles.example_time_limit`) is at most the time left;
  when nothing is left, :class:`BudgetExceeded` stops the search.
- ``shrink``: wall-clock time for shrinking, counted from the first failure,
  crash or shrunk tie on (the task's deadline moves closer then, never further):
  a failure found late still gets its shrink, one found early does not spend
  the whole task shrinking.  What a user waits for in the default profile is
  the verdict; the ci and thorough profiles shrink longer.
- ``crashes``: outcomes of the implementation that are crashes or hangs (not
  property failures).  Deterministic, unlike time: after this many, the search
  stops and the smallest crashing input seen so far is the result.

The runner (:func:`ddg_oracle.properties.runner.run_property`) catches :class:`BudgetExceeded` and
reports the smallest failing or crashing example it has seen, noting that
shrinking stopped early.  Budgets per profile: :data:`BUDGETS`.
"""

from __future__ import annotations

import contextvars
import time
from contextlib import contextmanager
from dataclasses import dataclass


class BudgetExceeded(BaseException):
    """The task's budget ran out between two calls of the implementation: stop the search
    (a BaseException, so that Hypothesis stops at once instead of treating it as a failure
    to shrink).  Out of time *inside* a call is :class:`ImplementationHang` instead."""


class Hang:
    """Marks an exception as a hang of the checked implementation (reported as ``hang:
    ...``, whichever clock stopped it: the task's budget, the time limit per example, or an
    isolated call's own limit)."""


class ImplementationHang(Hang, BaseException):
    """A call of the checked implementation was still running when its time ran out (the
    task's budget or the time limit per example): a hang of the implementation, reported
    with its input.  A BaseException, so that the implementation's own ``except
    Exception`` cannot swallow it and Hypothesis does not spend the budget shrinking it."""


#: a call the task's budget cuts short is a hang once it has run this share of the
#: budget (6 s of the default 18): no protocol method takes that long on a drawn mesh of a
#: few hundred faces; a call cut sooner merely began late, and the task is incomplete
HANG_SHARE = 1 / 3

_call: contextvars.ContextVar[tuple[str, float] | None] = contextvars.ContextVar(
    "ddg_implementation_call", default=None)
_hang_after: contextvars.ContextVar[float | None] = contextvars.ContextVar(
    "ddg_hang_after", default=None)


@contextmanager
def calling(what: str):
    """Mark the block as a call of the checked implementation (``what``: "name.method"):
    a clock that stops it there stops the implementation (:func:`current_call`)."""
    token = _call.set((what, time.monotonic()))
    try:
        yield
    finally:
        _call.reset(token)


def current_call() -> str | None:
    """The implementation call running now ("name.method"), or None: our own code (the
    exact reference, the property's arithmetic) or between calls.

    >>> with calling("mine.angle_defects"):
    ...     current_call()
    'mine.angle_defects'
    >>> current_call() is None
    True
    """
    call = _call.get()
    return None if call is None else call[0]


def cut_short(what: str, started: float | None = None) -> BaseException:
    """What to raise when the task's budget runs out during a call of the implementation
    (``what``: "name.method", running since ``started``, by default the marked call's
    start): :class:`ImplementationHang` if it has run :data:`HANG_SHARE` of the budget or
    more, else :class:`BudgetExceeded` (the call began late: the task is incomplete).

    >>> with task_budget(30):
    ...     type(cut_short("mine.area", time.monotonic())).__name__
    'BudgetExceeded'
    >>> with task_budget(30):
    ...     type(cut_short("mine.area", time.monotonic() - 11)).__name__
    'ImplementationHang'
    """
    if started is None:
        call = _call.get()
        started = call[1] if call is not None else time.monotonic()
    ran = time.monotonic() - started
    limit = _hang_after.get()
    if limit is None or ran >= limit:
        return ImplementationHang(
            f"{what} did not return within {ran:.3g} s, when the check task's time budget "
            f"ran out (a longer budget: ddg-oracle check --budget SECONDS)")
    return BudgetExceeded(f"the task's time budget ran out during a call of {what}, "
                          f"{ran:.2g} s after it began")


@dataclass(frozen=True)
class Budget:
    seconds: float | None       # wall clock of the whole task; None: no limit
    crashes: int | None         # crash or hang outcomes of the implementation; None: no limit
    shrink: float | None = None  # seconds of shrinking from the first failure on; None: the rest


#: Per profile: the default run must stay within about a minute on 2 cores with every
#: library installed (`python -m benchmarks main` measures it); ci gets more room;
#: thorough none.  Shrinking a failure on a wide mesh costs 20-100 ms per candidate
#: (exact reference included): 3 s is 30-150 candidates, which takes the planted bugs
#: of `python -m benchmarks catch` to their small counterexamples (Hypothesis shrinks
#: the big choices first: components, subdivision, scale); ci shrinks 10 s.
BUDGETS = {"default": Budget(18.0, 6, 3.0), "ci": Budget(40.0, 12, 10.0),
           "thorough": Budget(None, None)}

_deadline: contextvars.ContextVar[float | None] = contextvars.ContextVar(
    "ddg_task_deadline", default=None)


@contextmanager
def task_budget(seconds: float | None):
    """Run the block with a wall-clock deadline ``seconds`` from now (None: none)."""
    token = _deadline.set(None if seconds is None else time.monotonic() + seconds)
    share = _hang_after.set(None if seconds is None else seconds * HANG_SHARE)
    try:
        yield
    finally:
        _hang_after.reset(share)
        _deadline.reset(token)


def shrink_from_now(seconds: float | None) -> None:
    """Bring the current task's deadline to at most ``seconds`` from now (None: nothing
    changes); called when shrinking starts, inside :func:`task_budget` (which restores
    the deadline outside it when the task ends).

    >>> with task_budget(30):
    ...     shrink_from_now(2)
    ...     time_left() <= 2
    True
    """
    deadline = _deadline.get()
    if seconds is None:
        return
    end = time.monotonic() + seconds
    _deadline.set(end if deadline is None else min(deadline, end))


def time_left() -> float | None:
    """Seconds left of the current task's budget (may be <= 0), or None without a budget.

    >>> time_left() is None
    True
    >>> with task_budget(30):
    ...     0 < time_left() <= 30
    True
    """
    deadline = _deadline.get()
    return None if deadline is None else deadline - time.monotonic()


def check_time_left(what: str) -> None:
    """Raise :class:`BudgetExceeded` if the current task has no time left."""
    left = time_left()
    if left is not None and left <= 0:
        raise BudgetExceeded(f"{what}: the task's time budget is used up")
