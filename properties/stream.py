"""One example stream per property, the same in every process: every use of Hypothesis's
internals by ddg-oracle, in this one module.

Hypothesis has no public API for four things the runner needs; each is reached here and
nowhere else, and tests/test_stream.py fails on a Hypothesis where one of them no longer
works (pyproject.toml pins the range it was tested on: 6.132.0, 6.150.0, 6.170.27):

- :func:`keyed`: each property its own example-database key and derandomized stream,
  whatever the test function (``_hypothesis_internal_add_digest``, the hook Hypothesis's
  pytest plugin uses for parametrized tests);
- :func:`with_database`: a seeded run still replays and saves failures in the chosen
  database (``@seed`` turns it off; ``_hypothesis_internal_use_settings``);
- :func:`generated_seed`: the seed Hypothesis drew for an unseeded run, so that a second
  pass replays that very stream (``_hypothesis_internal_use_generated_seed``);
- :func:`same_stream`: no constants of the process's local modules in the draws (below).

Hypothesis (6.132 on) draws about 5% of its integers, floats and strings from
pools of "interesting" constants: its own, and those found in the source of
every *local* module loaded in the process (not the standard library, not
site-packages, not test files).  Which local modules are loaded depends on the
process's history: a user's adapter file given to ``--impl``, an editable
install of ddg-oracle, what an xdist or Dask worker ran before.  So a
derandomized run of one property drew other examples in another process, or
for an implementation whose adapter is a local file: a planted valence-33 bug
was caught by the ``ci`` stream with 770 modules loaded and missed with 800.

:func:`same_stream` empties the local pool while our own properties run
(Hypothesis's global constants stay): the stream is then a function of the
property, the profile and the seed only, as :func:`~.runner.run_property`
promises.  A user's own Hypothesis tests are left alone: the pool is restored
when the block ends.  No public switch exists (Hypothesis 6.170), so this sets
``hypothesis.internal.conjecture.providers._get_local_constants`` and clears
its ``CONSTANTS_CACHE`` (the permitted constants per choice type, computed
from the pool); with a Hypothesis that has neither, nothing is changed.
"""

from __future__ import annotations

import threading
from contextlib import contextmanager

_lock = threading.Lock()
_depth = 0
_saved = None


def _providers():
    try:
        from hypothesis.internal.conjecture import providers
    except ImportError:                                  # pragma: no cover
        return None
    ok = all(hasattr(providers, a) for a in ("_get_local_constants", "CONSTANTS_CACHE",
                                             "Constants"))
    return providers if ok else None


def _clear_cache(providers) -> None:
    cache = getattr(providers.CONSTANTS_CACHE, "cache", None)
    if cache is not None:
        cache.clear()


@contextmanager
def same_stream():
    """Run the block with no constants from loaded local modules in Hypothesis's draws
    (see the module doc).  Re-entrant and thread-safe: the pool comes back when the
    outermost block ends."""
    global _depth, _saved
    providers = _providers()
    if providers is None:
        yield
        return
    with _lock:
        if _depth == 0:
            _saved = providers._get_local_constants
            empty = providers.Constants()
            providers._get_local_constants = lambda: empty
            _clear_cache(providers)
        _depth += 1
    try:
        yield
    finally:
        with _lock:
            _depth -= 1
            if _depth == 0:
                providers._get_local_constants = _saved
                _saved = None
                _clear_cache(providers)


def keyed(test, key: bytes):
    """``test`` (a function Hypothesis will wrap) with ``key`` in its database key and
    derandomized seed: one example stream per property, the same test function for all."""
    test._hypothesis_internal_add_digest = key
    return test


def with_database(run, database):
    """The seeded Hypothesis test ``run`` with ``database`` used again (replayed first,
    failures saved), which ``@seed`` turned off."""
    from hypothesis import settings
    run._hypothesis_internal_use_settings = settings(run._hypothesis_internal_use_settings,
                                                     database=database)
    return run


def generated_seed(run):
    """The seed Hypothesis generated for the last unseeded run of ``run``, or None."""
    return getattr(run, "_hypothesis_internal_use_generated_seed", None)

