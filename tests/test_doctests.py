"""Every docstring example of every module of the installed package runs (doctest).

Collected by import name (``ddg_oracle.reference.exact.surds``), not by path, so the
examples run against the modules the package really installs.
"""

import doctest
import importlib
import pkgutil
import tomllib
from pathlib import Path

import pytest

from ddg_oracle.application.implementations import BUILTIN, LIBRARIES

# each layer walked by its own path (in an editable install they live apart), the layers
# read from pyproject.toml's package-dir table; the package's face is one module
LAYERS = tuple(package for package in tomllib.loads(
    (Path(__file__).resolve().parent.parent / "pyproject.toml").read_text())["tool"][
        "setuptools"]["package-dir"] if package != "ddg_oracle")
MODULES = sorted({m.name for pkg in LAYERS
                  for m in pkgutil.walk_packages(importlib.import_module(pkg).__path__, pkg + ".")}
                 | set(LAYERS) | {"ddg_oracle"})    # not __main__: importing it runs the command
# adapters of libraries not installed here import nothing useful: their doctests need them.
# Read from the adapters' own declarations (a new adapter adds no line here)
OPTIONAL = {BUILTIN[name].split(":")[0]: library for name, library in LIBRARIES.items()
            if library is not None}


def test_every_package_is_walked():
    assert len(LAYERS) == 5
    for package in ("reference", "reference.exact", "protocol", "properties", "oracles",
                    "application"):
        assert any(m.startswith(f"ddg_oracle.{package}.") for m in MODULES), package


@pytest.mark.parametrize("name", MODULES)
def test_doctests(name):
    if name in OPTIONAL:
        pytest.importorskip(OPTIONAL[name])
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.NORMALIZE_WHITESPACE, verbose=False)
    assert result.failed == 0, f"{result.failed} of {result.attempted} doctest examples of {name} failed"
