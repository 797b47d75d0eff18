"""Finding implementations by name: built-in adapters or ``module:object``."""

from __future__ import annotations

import importlib
import os
import sys

# name -> "module:object"; grows with the adapters (libigl, pymeshlab, ...).
BUILTIN: dict[str, str] = {
    "reference": "oracles.exact_reference:ReferenceImplementation",
    "libigl": "oracles.libigl:Libigl",
    "pymeshlab": "oracles.pymeshlab:PyMeshLab",
    "scipy": "oracles.scipy_spatial:ScipySpatial",
}


class ImplementationNotFound(ValueError):
    """An --impl argument that names nothing importable."""


def load_implementation(spec: str):
    """An implementation object from a built-in name or ``module:object``.

    A class is instantiated without arguments; any other object is used as is.
    """
    target = BUILTIN.get(spec, spec)
    module, sep, qual = target.partition(":")
    if not sep or not module or not qual:
        raise ImplementationNotFound(
            f"unknown implementation {spec!r}: use one of {', '.join(BUILTIN)} or module:object")
    if spec not in BUILTIN and os.getcwd() not in sys.path:
        # like `python -m` and pytest: the user's own modules resolve from where they run
        sys.path.insert(0, os.getcwd())
    try:
        obj = importlib.import_module(module)
        for part in qual.split("."):
            obj = getattr(obj, part)
    except ImportError as e:
        raise ImplementationNotFound(f"cannot import {module!r} for {spec!r}: {e}") from None
    except AttributeError:
        raise ImplementationNotFound(f"{module!r} has no {qual!r} (from {spec!r})") from None
    return obj() if isinstance(obj, type) else obj


def available() -> list[str]:
    """Built-in implementations whose libraries import on this machine."""
    names = []
    for name in BUILTIN:
        try:
            load_implementation(name)
        except ImplementationNotFound:
            continue
        names.append(name)
    return names
