"""Hypothesis settings profiles, the example database, and the time limit per example.

Profiles: ``default`` (fast), ``ci`` (derandomized, more examples) and
``thorough``, registered with Hypothesis under our own names
``ddg-oracle-default``, ``ddg-oracle-ci`` and ``ddg-oracle-thorough`` the first
time one is asked for (:func:`profile`), never at import.  Nothing here loads
a profile or touches the profiles Hypothesis or a user own: importing
ddg-oracle leaves every other Hypothesis test exactly as strong as it was.
Select ours with ``ddg-oracle check --profile``, pytest's ``--ddg-profile``,
or ``settings.load_profile("ddg-oracle-ci")`` after :func:`register_profiles`.

Example database (where Hypothesis saves every failing example and from which
it replays them first on the next run): chosen by the environment variable
``DDG_HYPOTHESIS_DATABASE`` when this module is imported, or later by
:func:`use_database`:

- unset: Hypothesis's default, the directory ``.hypothesis/examples``;
- ``redis://host:port[/db]`` (or ``rediss://``, ``unix://``): a Redis server
  shared by a team's CI machines (Hypothesis's ``RedisExampleDatabase``;
  needs ``pip install 'ddg-oracle[redis]'``).  The client reconnects with
  backoff, so a restart of the server (with persistence) loses nothing;
- ``none``: no database;
- anything else: a directory.

Hypothesis forbids a database together with ``derandomize``.  So ``ci`` is
derandomized and database-free (two runs test the same examples) unless a
database is chosen; then ``ci`` saves and replays through it, and a fixed seed
keeps its runs reproducible: ``pytest --hypothesis-seed 0`` or
``ddg-oracle check --seed 0``.

Time limit: every property example runs under :func:`example_time_limit`
(``DDG_EXAMPLE_TIME_LIMIT`` seconds, default 120, ``0`` for none).  Whose time ran
out decides what an overrun is: inside a call of the implementation
(:func:`~.budget.current_call`) it is the implementation's hang
(:class:`~.budget.ImplementationHang`, a crash with its input); in our own computation
it raises :class:`~ddg_oracle.reference.errors.TimeLimitExceeded` (the result is
``undecided``: the implementation is not blamed for the reference's time).  (Hypothesis's
own ``deadline`` stays off: it only measures after the example has returned,
so it cannot stop one that never returns.)
"""

from __future__ import annotations

import os
import signal
import threading
import time
from contextlib import contextmanager

from hypothesis import HealthCheck, Phase, Verbosity, settings
from hypothesis.database import DirectoryBasedExampleDatabase, ExampleDatabase

from ..reference.errors import InputError, TimeLimitExceeded

from ..protocol.budget import (BUDGETS, Budget, BudgetExceeded, ImplementationHang, current_call,
                     cut_short, time_left)

PROFILES = ("default", "ci", "thorough")
#: Hypothesis profile name of each of ours: a prefix no user or Hypothesis profile has.
PREFIX = "ddg-oracle-"
DATABASE_ENV = "DDG_HYPOTHESIS_DATABASE"
TIME_LIMIT_ENV = "DDG_EXAMPLE_TIME_LIMIT"
#: Seconds per property example when ``DDG_EXAMPLE_TIME_LIMIT`` is unset: far
#: above any example of the shipped profiles (well under a second each), and
#: above ``ddg-oracle check --timeout`` (60 s per isolated call), which reports
#: a hanging library more precisely.
DEFAULT_TIME_LIMIT = 120.0

# Mesh strategies build structure from a few small integers; building is not
# instant, so the too_slow and data_too_large checks only add noise.
_quiet = [HealthCheck.too_slow, HealthCheck.data_too_large]

_DEFAULT_DATABASE = object()      # "let Hypothesis choose" (its local directory)


class TolerantDatabase(ExampleDatabase):
    """An example database that never fails a check: an error of the database (a Redis
    server that does not answer, a full disk) is one warning, and the run goes on as if
    it had nothing saved.  A verdict is the implementation's, never the database's."""

    def __init__(self, inner: ExampleDatabase, name: str):
        super().__init__()
        self.inner, self.name, self.failed = inner, name, None

    def _guard(self, what, default=None):
        if self.failed is not None:
            return default
        try:
            return what()
        except Exception as e:  # noqa: BLE001  (any trouble of the store: warn, go on)
            import warnings
            self.failed = e
            warnings.warn(f"ddg-oracle: the example database {self.name} failed "
                          f"({type(e).__name__}: {e}); the run goes on without it",
                          RuntimeWarning, stacklevel=2)
            return default

    def save(self, key: bytes, value: bytes) -> None:
        self._guard(lambda: self.inner.save(key, value))

    def fetch(self, key: bytes):
        return iter(self._guard(lambda: list(self.inner.fetch(key)), []))

    def delete(self, key: bytes, value: bytes) -> None:
        self._guard(lambda: self.inner.delete(key, value))

    def move(self, src: bytes, dest: bytes, value: bytes) -> None:
        self._guard(lambda: self.inner.move(src, dest, value))

    def __repr__(self) -> str:
        return f"TolerantDatabase({self.inner!r})"


def database_from(spec: str | None):
    """The example database a ``DDG_HYPOTHESIS_DATABASE`` value names (see module doc).

    Returns an ``ExampleDatabase``, None for ``"none"``, or a private marker
    for "Hypothesis's default" when ``spec`` is None or empty.

    >>> database_from("none") is None
    True
    """
    if spec is None or not spec.strip():
        return _DEFAULT_DATABASE
    spec = spec.strip()
    if spec.lower() == "none":
        return None
    if spec.startswith(("redis://", "rediss://", "unix://")):
        try:
            import redis
            from hypothesis.extra.redis import RedisExampleDatabase
            from redis.backoff import ExponentialBackoff
            from redis.retry import Retry
        except ImportError:
            raise InputError(f"{DATABASE_ENV}={spec} needs the redis package: "
                             "pip install 'ddg-oracle[redis]'") from None
        # Retries with backoff (about 5 s in all) ride out a server restart;
        # the pooled connections it broke are reopened on the next command.
        client = redis.Redis.from_url(
            spec, socket_connect_timeout=5, socket_timeout=30,
            retry=Retry(ExponentialBackoff(cap=1.0, base=0.05), REDIS_RETRIES),
            retry_on_error=[redis.ConnectionError, redis.TimeoutError])
        return TolerantDatabase(RedisExampleDatabase(client), spec)
    if os.path.exists(spec) and not os.path.isdir(spec):
        # Hypothesis's directory database ignores its own write errors: a failure would
        # go unsaved without a word
        import warnings
        warnings.warn(f"ddg-oracle: the example database {spec} is not a directory; the run "
                      "goes on without it", RuntimeWarning, stacklevel=2)
        return None
    return TolerantDatabase(DirectoryBasedExampleDatabase(spec), spec)


#: retries of a failed Redis command (backoff 0.05 s doubling, at most 1 s: 4.6 s for 8)
REDIS_RETRIES = 8


def _register(database) -> None:
    global _registered
    db = {} if database is _DEFAULT_DATABASE else {"database": database}
    if db and database is not None:
        # derandomize excludes a database: reproducible through a fixed seed instead
        ci = {"derandomize": False, "database": database}
    else:
        ci = {"derandomize": True, "database": None}
    # every setting that changes what runs is given here: the others would come from the
    # profile loaded when these are built, the user's (phases=[explicit, reuse] made every
    # property run 1 of 25 examples and pass, or none: "told to run no test cases")
    base = dict(deadline=None, suppress_health_check=_quiet, phases=tuple(Phase),
                verbosity=Verbosity.normal, report_multiple_bugs=True, stateful_step_count=50)
    ours = {"default": settings(max_examples=25, derandomize=False, print_blob=False,
                                **base, **db),
            "ci": settings(max_examples=60, print_blob=True, **base, **ci),
            "thorough": settings(max_examples=1000, derandomize=False, print_blob=False,
                                 **base, **db)}
    _registered = _with_hypothesis(ours)


def _with_hypothesis(ours: dict) -> dict:
    """``ours`` (short name -> settings) registered with Hypothesis under :data:`PREFIX`
    (for ``settings.load_profile`` and ``--hypothesis-profile``), as the very objects
    Hypothesis keeps, so that :func:`profile` can tell whether its registry still holds
    them."""
    kept = {}
    for short, s in ours.items():
        settings.register_profile(PREFIX + short, s)
        kept[short] = settings.get_profile(PREFIX + short)
    return kept


def use_database(spec: str | None) -> ExampleDatabase | None:
    """Re-register every profile with the database ``spec`` names; returns it.

    For a command-line option such as ``--database redis://host:6379``: call
    it before :func:`profile` (or ``settings.load_profile``) picks a profile.
    """
    db = database_from(spec)
    _register(db)
    return None if db is _DEFAULT_DATABASE else db


#: our profiles (short name -> the settings registered with Hypothesis), None until the
#: first :func:`profile` or :func:`register_profiles` (or :func:`use_database`).  The one
#: place they live: :func:`profile` reads them here, not from Hypothesis's registry, so that
#: whoever saves and restores this variable (a test choosing a database for one check)
#: restores the profiles, the ci profile's ``derandomize`` included.  (A flag here and
#: the settings in Hypothesis's registry did not: a test that set the flag back left ci
#: with its database and no ``derandomize`` for the rest of the process, and every later
#: ci run in it drew a random stream.)
_registered: dict | None = None


def register_profiles() -> None:
    """Register ``ddg-oracle-default``, ``-ci`` and ``-thorough`` (database from
    ``DDG_HYPOTHESIS_DATABASE``) unless done already; loads none of them."""
    if not _registered:
        _register(database_from(os.environ.get(DATABASE_ENV)))


def _short(name: str) -> str:
    short = name[len(PREFIX):] if name.startswith(PREFIX) else name
    if short not in PROFILES:
        raise ValueError(f"unknown Hypothesis profile {name!r}; choose one of {', '.join(PROFILES)}")
    return short


def profile_budget(name: str) -> Budget:
    """The task budget (:mod:`.budget`) that goes with one of our profiles.

    >>> profile_budget("ddg-oracle-thorough")
    Budget(seconds=None, crashes=None, shrink=None)
    """
    return BUDGETS[_short(name)]


def profile(name: str) -> settings:
    """The settings of one of our profiles, by short name (``"ci"``) or Hypothesis name
    (``"ddg-oracle-ci"``), with a clear error for a typo.

    >>> profile("ci").derandomize or profile("ci").database is not None
    True
    """
    global _registered
    short = _short(name)
    register_profiles()
    if any(_hypothesis_profile(PREFIX + k) is not v for k, v in _registered.items()):
        # Hypothesis's registry holds other settings under our names (registered since,
        # e.g. by a test that chose a database): ours again, so that loading one by name
        # gives these too
        _registered = _with_hypothesis(_registered)
    return _registered[short]


def _hypothesis_profile(name: str):
    try:
        return settings.get_profile(name)
    except Exception:  # noqa: BLE001  (InvalidArgument: not registered there)
        return None


# --- time limit per property example ------------------------------------------


def time_limit_seconds() -> float | None:
    """Seconds per property example from ``DDG_EXAMPLE_TIME_LIMIT`` (None: no limit)."""
    raw = os.environ.get(TIME_LIMIT_ENV, "").strip()
    if not raw:
        return DEFAULT_TIME_LIMIT
    try:
        seconds = float(raw)
    except ValueError:
        raise InputError(f"{TIME_LIMIT_ENV}={raw!r} is not a number of seconds "
                         "(use e.g. 300, or 0 for no limit)") from None
    if seconds != seconds or seconds < 0:
        raise InputError(f"{TIME_LIMIT_ENV}={raw!r} must be >= 0 seconds (0: no limit)")
    return seconds or None


@contextmanager
def example_time_limit(what: str, seconds: float | None = -1.0, cpu: bool = False):
    """Raise :class:`~ddg_oracle.reference.errors.TimeLimitExceeded` if the block runs over
    ``seconds``: of wall-clock time, or with ``cpu`` of this process's CPU time (for a
    block that runs only our own computation: its verdict then does not depend on what
    else the machine runs; a hang that uses no CPU is not caught so).

    ``what`` names the property and implementation in the message; ``seconds``
    defaults to :func:`time_limit_seconds`, None means no limit.  Inside a task
    budget (:mod:`.budget`) the block gets at most the time the task has left,
    and running out of that raises :class:`~.budget.BudgetExceeded` instead
    (the task stops; the example is not a failure).  Uses SIGALRM, so it only
    acts in the main thread on Unix (elsewhere, and inside an outer timer that
    fires sooner, the block runs without it).

    >>> with example_time_limit("[D1.6] demo", seconds=5):
    ...     1 + 1
    2
    """
    if seconds is not None and seconds < 0:
        seconds = time_limit_seconds()
    left = time_left()
    if left is not None and left <= 0:
        raise BudgetExceeded(f"{what}: the task's time budget is used up")
    by_budget = left is not None and (not seconds or left < seconds)
    if by_budget:
        seconds = max(left, 1e-3)
    if (not seconds or not hasattr(signal, "setitimer")
            or threading.current_thread() is not threading.main_thread()):
        yield
        return
    # a task budget is wall-clock time: the budget's limit is measured as it is
    clock, alarm, now = (signal.ITIMER_PROF, signal.SIGPROF, time.process_time) \
        if cpu and not by_budget else (signal.ITIMER_REAL, signal.SIGALRM, time.monotonic)
    outer = signal.getitimer(clock)
    if outer[0] and outer[0] <= seconds:     # someone else's timer fires first: leave it
        yield
        return

    def error():
        # whose time it was: a call of the implementation still running is its hang; else
        # our own computation (the exact reference, the property) was running
        call = current_call()
        if call is not None and by_budget:
            return cut_short(call)         # a hang, or a call that merely began late
        if call is not None:
            return ImplementationHang(
                f"{call} did not return within the time limit of {seconds:g} s per property "
                f"example (raise it with {TIME_LIMIT_ENV}=SECONDS)")
        if by_budget:
            return BudgetExceeded(f"{what}: the task's time budget ran out during an example, "
                                  "outside the implementation's calls")
        return TimeLimitExceeded(
            f"{what}: the exact reference did not finish one example within the time limit "
            f"of {seconds:g} s{' of CPU time' if clock == signal.ITIMER_PROF else ''} per "
            f"property example. If it is just slow, raise the limit "
            f"with the environment variable {TIME_LIMIT_ENV}=SECONDS (0: no limit)")

    fired = []

    def overrun(signum, frame):
        fired.append(signum)
        raise error()

    previous = signal.signal(alarm, overrun)
    start = now()
    signal.setitimer(clock, seconds)
    try:
        yield
    finally:
        signal.setitimer(clock, 0)
        signal.signal(alarm, previous)
        if outer[0]:                         # give an outer timer what it has left
            left = outer[0] - (now() - start)
            signal.setitimer(clock, max(left, 1e-3), outer[1])
    if fired:
        # the timer fired, yet the block ended normally: the signal arrived inside a
        # finalizer or garbage-collector callback, where Python prints an exception and
        # swallows it; the overrun still stands
        raise error()
