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


def _failing_test():
    """A fresh test function that fails on every integer above 10 (the same code each
    time: its database key is then the digest's alone)."""
    def test(x):
        assert x <= 10
    return test


def _run(test):
    try:
        test()
    except AssertionError:
        return
    raise AssertionError("the test did not fail")


def test_the_hypothesis_internals_we_use_still_work(tmp_path):
    """Each of properties/stream.py's hooks into Hypothesis's internals still does what
    the runner relies on: fails loudly on a Hypothesis outside the tested range (then pin
    it in pyproject.toml, or move the hook to the new internals)."""
    from hypothesis import seed
    from hypothesis.database import DirectoryBasedExampleDatabase
    from ddg_oracle.properties.stream import generated_seed, keyed, with_database

    assert _providers() is not None, "Hypothesis no longer has the local constants pool"
    db_path = tmp_path / "db"
    # derandomize=False whatever profile is loaded: the ci profile derandomizes, and a
    # derandomized run has no generated seed (and ignores the database)
    quick = settings(max_examples=50, database=DirectoryBasedExampleDatabase(db_path),
                     deadline=None, derandomize=False,
                     phases=[Phase.generate, Phase.shrink, Phase.reuse])

    def keys():
        return {p.name for p in db_path.iterdir()} if db_path.exists() else set()

    # keyed: the digest is part of the database key (one key per property)
    _run(quick(given(st.integers())(keyed(_failing_test(), b"D1.6"))))
    first = keys()
    assert first
    _run(quick(given(st.integers())(keyed(_failing_test(), b"D1.6"))))
    assert keys() == first                                  # the same key again
    _run(quick(given(st.integers())(keyed(_failing_test(), b"D2.2"))))
    assert keys() > first                                   # another property, another key

    # with_database: @seed turns the database off, with_database turns it back on
    seeded = tmp_path / "seeded"
    s = settings(quick, database=DirectoryBasedExampleDatabase(seeded))
    _run(seed(7)(s(given(st.integers())(keyed(_failing_test(), b"T3.6")))))
    assert not seeded.exists() or not any(seeded.iterdir())
    _run(with_database(seed(7)(s(given(st.integers())(keyed(_failing_test(), b"T3.6")))),
                       s.database))
    assert any(seeded.iterdir())

    # generated_seed: the seed of an unseeded run, which replays the same stream
    unseeded = settings(quick, database=None)(given(st.integers())(_failing_test()))
    _run(unseeded)
    assert isinstance(generated_seed(unseeded), int)


def test_no_other_module_reaches_into_hypothesis_internals():
    """Issue 43: every use of Hypothesis's internals is in properties/stream.py, where the
    test above checks it."""
    from pathlib import Path
    root = Path(__file__).resolve().parent.parent
    users = sorted(str(p.relative_to(root))
                   for folder in ("reference", "protocol", "properties", "oracles", "application")
                   for p in (root / folder).rglob("*.py")
                   if ("_hypothesis_internal" in (text := p.read_text(encoding="utf-8"))
                       or "hypothesis.internal" in text))
    assert users == ["properties/stream.py"]
