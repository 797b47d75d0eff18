"""pytest plugin: ``pytest --ddg-impl mylib.geometry:Impl`` checks an implementation.

Inert unless asked: loading it (every pytest run in an environment where
ddg-oracle is installed, entry point ``pytest11``) adds the options below and
nothing else: no import of the properties, no Hypothesis profile registered or
loaded, nothing on ``sys.path``.  With ``--ddg-impl`` every registered
property becomes one test item ``ddg[<impl>][<catalog ID>]``; a property
whose protocol methods the implementation lacks is skipped, naming them; an item
fails when the property fails, the implementation crashes or hangs, or fewer examples
ran than the profile asks for (``incomplete``: ``--ddg-budget`` gives more time).  The
items run under our own profile (``--ddg-profile default|ci|thorough``,
Hypothesis profile ``ddg-oracle-<name>``), so the user's own Hypothesis
profile is neither changed nor used by them.
"""

from __future__ import annotations

import os
import re

import pytest

#: a node id of one of our items, as pytest prints it: ddg[<spec>][<catalog ID>]
_NODE = re.compile(r"(?:.*::)?ddg\[(.+)\]\[([^\[\]]+)\]")


def pytest_load_initial_conftests(early_config, parser, args):
    """A node id of one of our items given back to pytest (``pytest 'ddg[mine:Impl][D3.1]'``,
    copied from a failure) reruns that item: it becomes ``--ddg-impl mine:Impl --ddg-only
    D3.1``, and only our items run.  Nothing happens without such an argument."""
    ours = [(a, m) for a in args if (m := _NODE.fullmatch(a))]
    for a, m in ours:
        args.remove(a)
        args += ["--ddg-impl", m[1], "--ddg-only", m[2], "--ddg-items-only"]


def pytest_addoption(parser):
    group = parser.getgroup("ddg-oracle")
    group.addoption("--ddg-impl", action="append", default=[], metavar="module:object",
                    help="check this implementation with every ddg-oracle property (repeatable)")
    group.addoption("--ddg-only", action="append", default=[], metavar="ID",
                    help="only the properties of these catalog IDs (any part of a joint ID "
                         "such as 'L4.3' of 'L4.3 / P4.4')")
    group.addoption("--ddg-budget", default=None, type=float, metavar="SECONDS",
                    help="wall-clock seconds per item, shrinking included (0: none; default: "
                         "the profile's, as ddg-oracle check --budget): a call still running "
                         "then is a hang, a search stopped before its examples ran fails the "
                         "item as incomplete")
    group.addoption("--ddg-items-only", action="store_true", help=argparse_suppress())
    group.addoption("--ddg-profile", default=None, metavar="NAME",
                    help="ddg-oracle's Hypothesis profile for its items: default, ci, thorough "
                         "(default: ci when $CI is set, else default)")


class PropertyItem(pytest.Item):
    def __init__(self, *, prop, impl, spec, profile, budget=None, **kw):
        super().__init__(**kw)
        self.prop, self.impl, self.spec, self.profile = prop, impl, spec, profile
        self.budget = budget

    def runtest(self):
        from ..properties.runner import (NOT_APPLICABLE, UNDECIDED, describe,
                                                  run_property)
        r = run_property(self.prop, self.impl, self.profile, budget=self.budget)
        # the spec as given, options included ('mine:Scaled(k=2)'): what its replay loads;
        # the object's class alone would build it without them, and not replay the failure
        r.spec = self.spec or r.spec
        if r.status == NOT_APPLICABLE:
            pytest.skip(f"{self.spec} {r.note}")
        if r.status == UNDECIDED:            # the exact reference hit a guard: nothing checked
            pytest.skip(f"undecided: {r.error}")
        if not r.ok:                         # FAILED, crashed (a hang too), incomplete
            from .jobs import with_diagnosis
            from .causes import convention_hint, wrong_answer
            text = describe(with_diagnosis(r, self.prop, self.impl))
            first = "\n".join(filter(None, [wrong_answer(r), convention_hint(r)]))
            if first:                        # the root cause first: the wrong answer
                text = f"{first}\n{text}"
            raise PropertyCheckFailed(text)
        if r.unjudged:                       # passed, and says what it could not judge (-rP)
            self.add_report_section("call", "ddg-oracle", r.note)

    def repr_failure(self, excinfo):
        if isinstance(excinfo.value, PropertyCheckFailed):
            return str(excinfo.value)
        return super().repr_failure(excinfo)

    def reportinfo(self):
        return self.spec, None, f"ddg[{self.spec}][{self.prop.id}] {self.prop.statement}"


class PropertyCheckFailed(AssertionError):
    pass


def argparse_suppress():
    import argparse
    return argparse.SUPPRESS            # an option of node-id reruns, not for users


def pytest_collection_modifyitems(session, config, items):
    specs = config.getoption("ddg_impl")
    if not specs:
        return
    if config.getoption("ddg_items_only"):
        # a rerun by node id: the project's own tests were collected, not asked for
        config.hook.pytest_deselected(items=list(items))
        items.clear()
    from .implementations import ImplementationNotFound, load_implementation
    from ..protocol.budget import Budget
    from ..properties.profiles import profile, profile_budget
    from ..protocol.methods import (NotAnImplementation, near_miss_warning,
                                                require_protocol)
    from ..properties.registry import select_properties

    name = config.getoption("ddg_profile") or ("ci" if os.environ.get("CI") else "default")
    try:
        settings = profile(name)
        budget = profile_budget(name)
        seconds = config.getoption("ddg_budget")
        if seconds is not None:
            if not seconds >= 0:
                raise ValueError(f"--ddg-budget must be >= 0 seconds (0: none), got {seconds}")
            budget = Budget(seconds or None, budget.crashes if seconds else None, budget.shrink)
        props = select_properties(config.getoption("ddg_only") or None)
    except ValueError as e:
        raise pytest.UsageError(f"ddg-oracle: {e}") from None
    for spec in specs:
        try:
            impl = load_implementation(spec)
            require_protocol(impl)
        except (ImplementationNotFound, NotAnImplementation) as e:
            raise pytest.UsageError(f"ddg-oracle: {e}") from None
        said = near_miss_warning(impl)
        if said:
            try:
                config.issue_config_time_warning(pytest.PytestWarning(f"ddg-oracle: {said}"),
                                                 stacklevel=2)
            except pytest.PytestWarning:
                # the project turns warnings into errors (filterwarnings = error): a hint of
                # ours must not stop the session and the user's own tests with it
                reporter = config.pluginmanager.get_plugin("terminalreporter")
                if reporter is not None:
                    reporter.write_line(f"warning: ddg-oracle: {said}", yellow=True)
        for p in props:
            items.append(PropertyItem.from_parent(
                session, name=f"ddg[{spec}][{p.id}]", prop=p, impl=impl, spec=spec,
                profile=settings, budget=budget))
    if config.getoption("ddg_items_only"):
        # only the items named: their (spec, ID) pairs, not every spec x every ID given
        wanted = {(m[1], m[2]) for a in config.invocation_params.args
                  if (m := _NODE.fullmatch(a))}
        if wanted:
            keep = [i for i in items if (i.spec, i.prop.id) in wanted]
            config.hook.pytest_deselected(items=[i for i in items if i not in keep])
            items[:] = keep
