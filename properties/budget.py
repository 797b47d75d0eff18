"""The budget of one check task: wall-clock seconds and crashes, so no task runs away.

A property's Hypothesis run on an implementation that crashes or hangs would
otherwise shrink that input one crash (or one call timeout) at a time: minutes
per task.  A task runs under :func:`task_budget`:

- ``seconds``: wall-clock time for the whole task, shrinking included.  A call
  of an isolated implementation waits at most the time left (a call cut short
  is a hang of the implementation, reported with its input), and the example
  time limit (:func:`~.profiles.example_time_limit`) is at most the time left;
  when nothing is left, :class:`BudgetExceeded` stops the search.
- ``shrink``: wall-clock time for shrinking, counted from the first failure,
  crash or shrunk tie on (the task's deadline moves closer then, never further):
  a failure found late still gets its shrink, one found early does not spend
  the whole task shrinking.  What a user waits for in the default profile is
  the verdict; the ci and thorough profiles shrink longer.
- ``crashes``: outcomes of the implementation that are crashes or hangs (not
  property failures).  Deterministic, unlike time: after this many, the search
  stops and the smallest crashing input seen so far is the result.

The runner (:func:`~.runner.run_property`) catches :class:`BudgetExceeded` and
reports the smallest failing or crashing example it has seen, noting that
shrinking stopped early.  Budgets per profile: :data:`BUDGETS`.
"""

from __future__ import annotations

import contextvars
import time
from contextlib import contextmanager
from dataclasses import dataclass


class BudgetExceeded(BaseException):
    """The task's budget ran out: stop the search (a BaseException, so that Hypothesis
    stops at once instead of treating it as a failure to shrink)."""


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
    try:
        yield
    finally:
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
