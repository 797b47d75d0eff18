"""Every docstring example of every module of the installed package runs (doctest).

Collected by import name (``ddg_oracle.reference.exact.surds``), not by path, so the
examples run against the modules the package really installs.
"""

import doctest
import importlib
import pkgutil

import pytest

from ddg_oracle.implementations import BUILTIN, LIBRARIES

# each subpackage walked by its own path: in an editable install they live apart
PACKAGES = ("ddg_oracle", "ddg_oracle.reference", "ddg_oracle.properties", "ddg_oracle.oracles")
MODULES = sorted(({m.name for pkg in PACKAGES
                   for m in pkgutil.walk_packages(importlib.import_module(pkg).__path__, pkg + ".")}
                  | set(PACKAGES)) - {"ddg_oracle.__main__"})   # importing it runs the command
# adapters of libraries not installed here import nothing useful: their doctests need them.
# Read from the adapters' own declarations (a new adapter adds no line here)
OPTIONAL = {BUILTIN[name].split(":")[0]: library for name, library in LIBRARIES.items()
            if library is not None}


def test_every_package_is_walked():
    for package in ("reference", "reference.exact", "properties", "oracles"):
        assert any(m.startswith(f"ddg_oracle.{package}.") for m in MODULES), package


@pytest.mark.parametrize("name", MODULES)
def test_doctests(name):
    if name in OPTIONAL:
        pytest.importorskip(OPTIONAL[name])
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.NORMALIZE_WHITESPACE, verbose=False)
    assert result.failed == 0, f"{result.failed} of {result.attempted} doctest examples of {name} failed"
