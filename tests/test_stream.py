"""A property's example stream does not depend on which local modules the process loaded."""

import importlib
import contextlib

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, given, settings, strategies as st

from ddg_oracle.oracles.exact_reference import ReferenceImplementation
from ddg_oracle.properties import profiles
from ddg_oracle.properties.profiles import PREFIX, profile
from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.runner import PASSED, run_property
from ddg_oracle.properties.stream import _providers, same_stream


class Recording(ReferenceImplementation):
    """The reference, recording every mesh it is asked about."""

    def __init__(self):
        self.seen = []

    def angle_defects(self, V, F):
        self.seen.append((np.asarray(V).tobytes(), np.asarray(F).tobytes()))
        return super().angle_defects(V, F)


def _stream(n: int = 30):
    impl = Recording()
    ci = settings(profile("ci"), max_examples=n, phases=[Phase.generate])
    assert run_property(PROPERTIES["D2.2"], impl, ci).status == PASSED
    return impl.seen


def _load_local_module_with_constants(tmp_path, monkeypatch, name, start):
    # a user's adapter file: a local module (not site-packages, not a test file) whose
    # source holds integers the strategies' draws permit (new ones: Hypothesis keeps one
    # pool per process, so a second module with the same constants changes nothing)
    values = ", ".join(str(v) for v in range(start, start + 400, 7))
    (tmp_path / f"{name}.py").write_text(f"LOOKUP = ({values}, 5, 17, 29, 41, -37)\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    importlib.import_module(name)


def test_the_stream_is_the_same_after_a_local_module_with_constants_is_loaded(tmp_path, monkeypatch):
    before = _stream()
    _load_local_module_with_constants(tmp_path, monkeypatch, "ddg_user_adapter_constants", 4001)
    assert _stream() == before


#: integers no draw of st.integers(0, 2**40) hits by chance (nor Hypothesis's own
#: constants, which are near powers of two): each is drawn only as a loaded module's constant
DISTINCT = tuple(1_000_003 + 7_919 * k for k in range(500))


def _hits_of_distinct_constants(stream) -> int:
    """How many of 4000 derandomized integer draws are constants of :data:`DISTINCT`."""
    hits = []

    @settings(max_examples=200, derandomize=True, database=None, deadline=None,
              phases=[Phase.generate], suppress_health_check=list(HealthCheck))
    @given(st.lists(st.integers(0, 2 ** 40), min_size=20, max_size=20))
    def draw(xs):
        hits.extend(x for x in xs if x in DISTINCT)

    with stream():
        draw()
    return len(hits)


def test_without_same_stream_the_loaded_constants_are_drawn(tmp_path, monkeypatch):
    # the canary of what same_stream prevents, as Hypothesis does it: a module loaded in
    # the process puts its constants into about one integer draw in fifty to a hundred here
    # (one in twenty draws a constant, half of those from the local pool, most of that pool
    # ours: 55-70 hits of 4000 draws; a few hundred other local constants change that
    # little), and none under same_stream (the same draws otherwise).  This test fails if Hypothesis
    # stops drawing local constants (then same_stream can go)
    if _providers() is None:
        return
    (tmp_path / "ddg_user_adapter_distinct.py").write_text(f"LOOKUP = {DISTINCT!r}\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    importlib.import_module("ddg_user_adapter_distinct")
    assert _hits_of_distinct_constants(contextlib.nullcontext) >= 5
    assert _hits_of_distinct_constants(same_stream) == 0


def test_the_ci_stream_is_the_same_after_a_test_chose_a_database_for_one_check(tmp_path):
    # as tests/test_faults.py does: registration undone, a database in the environment,
    # a check, then both set back (by monkeypatch).  The profiles registered with that
    # database stayed: every later ci run of the process was randomized (no
    # derandomize) and drew another stream (a test worker's planted bugs missed)
    ci = profile("ci")
    before = _stream()
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(profiles, "_registered", False)
        mp.setenv(profiles.DATABASE_ENV, str(tmp_path / "db"))
        assert profile("ci").database is not None and not profile("ci").derandomize
        mp.setattr(profiles, "_registered", False)
    after = profile("ci")
    assert (after.derandomize, after.database) == (ci.derandomize, ci.database)
    assert settings.get_profile(PREFIX + "ci") is after     # and loading it by name
    assert _stream() == before


def test_the_pool_is_restored_for_the_users_own_tests():
    providers = _providers()
    if providers is None:
        return
    own = providers._get_local_constants
    _stream()
    assert providers._get_local_constants is own
