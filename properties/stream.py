"""One example stream per property, the same in every process.

Hypothesis (6.131 on) draws about 5% of its integers, floats and strings from
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
