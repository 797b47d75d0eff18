"""pytest plugin: ``pytest --ddg-impl mylib.geometry:Impl`` checks an implementation.

Every registered property becomes one test item ``ddg[<impl>][<catalog ID>]``;
a property whose protocol methods the implementation lacks is skipped as not
applicable.  Hypothesis settings come from the loaded profile: select one with
``--hypothesis-profile default|ci|thorough``.  Installed with ddg-oracle (entry
point ``pytest11``), so no conftest is needed.
"""

from __future__ import annotations

import pytest


def pytest_addoption(parser):
    group = parser.getgroup("ddg-oracle")
    group.addoption("--ddg-impl", action="append", default=[], metavar="module:object",
                    help="check this implementation with every ddg-oracle property (repeatable)")
    group.addoption("--ddg-only", action="append", default=[], metavar="ID",
                    help="only the properties of these catalog IDs")


def pytest_configure(config):
    if config.getoption("ddg_impl"):
        from . import profiles  # noqa: F401  (registers default / ci / thorough)


class PropertyItem(pytest.Item):
    def __init__(self, *, prop, impl, spec, **kw):
        super().__init__(**kw)
        self.prop, self.impl, self.spec = prop, impl, spec

    def runtest(self):
        from hypothesis import settings

        from .runner import CRASHED, FAILED, NOT_APPLICABLE, UNDECIDED, describe, run_property
        r = run_property(self.prop, self.impl, settings())
        if r.status == NOT_APPLICABLE:
            pytest.skip(f"{self.spec} lacks {', '.join(sorted(self.prop.needs))}")
        if r.status == UNDECIDED:            # the exact reference hit a guard: nothing checked
            pytest.skip(f"undecided: {r.error}")
        if r.status in (FAILED, CRASHED):
            raise PropertyCheckFailed(describe(r))

    def repr_failure(self, excinfo):
        if isinstance(excinfo.value, PropertyCheckFailed):
            return str(excinfo.value)
        return super().repr_failure(excinfo)

    def reportinfo(self):
        return self.spec, None, f"ddg[{self.spec}][{self.prop.id}] {self.prop.statement}"


class PropertyCheckFailed(AssertionError):
    pass


def pytest_collection_modifyitems(session, config, items):
    specs = config.getoption("ddg_impl")
    if not specs:
        return
    from oracles.implementations import ImplementationNotFound, load_implementation

    from .registry import all_properties
    only = set(config.getoption("ddg_only"))
    for spec in specs:
        try:
            impl = load_implementation(spec)
        except ImplementationNotFound as e:
            raise pytest.UsageError(str(e)) from None
        for p in all_properties():
            if only and p.id not in only:
                continue
            items.append(PropertyItem.from_parent(
                session, name=f"ddg[{spec}][{p.id}]", prop=p, impl=impl, spec=spec))
