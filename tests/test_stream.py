"""A property's example stream does not depend on which local modules the process loaded."""

import importlib
import contextlib

import numpy as np
from hypothesis import Phase, settings

from ddg_oracle.oracles.exact_reference import ReferenceImplementation
from ddg_oracle.properties import runner
from ddg_oracle.properties.profiles import profile
from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.runner import PASSED, run_property
from ddg_oracle.properties.stream import _providers


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


def test_without_same_stream_the_loaded_constants_change_the_stream(tmp_path, monkeypatch):
    # what same_stream prevents, as Hypothesis does it: this test fails if Hypothesis
    # stops drawing local constants (then same_stream can go)
    if _providers() is None:
        return
    monkeypatch.setattr(runner, "same_stream", contextlib.nullcontext)
    # one integer draw in twenty takes a constant: enough examples that some do
    before = _stream(200)
    _load_local_module_with_constants(tmp_path, monkeypatch, "ddg_user_adapter_constants_2", 9001)
    assert _stream(200) != before


def test_the_pool_is_restored_for_the_users_own_tests():
    providers = _providers()
    if providers is None:
        return
    own = providers._get_local_constants
    _stream()
    assert providers._get_local_constants is own
