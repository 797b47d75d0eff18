"""Finding implementations by name: built-in adapters or ``module:object``.

A spec may carry keyword options in parentheses, passed to the class:
``"libigl(boundary=library)"``, ``"pymeshlab(boundary=library, genus=library)"``,
``"mypkg.mod:Impl(scale=2)"`` (values are Python literals, or bare words taken
as strings).
"""

from __future__ import annotations

import ast
import importlib
import os
import re
import sys

# name -> "module:object"; grows with the adapters (libigl, pymeshlab, ...).
BUILTIN: dict[str, str] = {
    "reference": "oracles.exact_reference:ReferenceImplementation",
    "libigl": "oracles.libigl:Libigl",
    "pymeshlab": "oracles.pymeshlab:PyMeshLab",
    "scipy": "oracles.scipy_spatial:ScipySpatial",
    # optional peers (`pip install -e '.[peers]'`): omitted by available() when not installed
    "gpytoolbox": "oracles.gpytoolbox:Gpytoolbox",
    "robust_laplacian": "oracles.robust_laplacian:RobustLaplacian",
    "potpourri3d": "oracles.potpourri3d:Potpourri3d",
}

#: Adapter options that select a library's own convention instead of the
#: reference's, each with the finding that documents the difference
#: (docs/findings.md, docs/conventions.md).  ``ddg-oracle check
#: --expect-conventions`` reports a failure of such a spec as "convention" when
#: the same spec without the option passes the same example.
DOCUMENTED_CONVENTIONS: dict[str, dict[tuple[str, str], str]] = {
    "libigl": {("boundary", "library"): "L2 (gaussian_curvature: 2 pi - angle sum at "
                                        "boundary vertices)"},
    "pymeshlab": {("boundary", "library"): "P2 (boundary term 2 pi - angle sum - phi)",
                  ("genus", "library"): "P1 (genus of a non-orientable mesh is floor(h / 2))"},
    "gpytoolbox": {("boundary", "library"): "G1 (angle_defect: 0 at boundary vertices)",
                   ("dihedral", "library"): "G2 (dihedral_angles: unsigned, reflex edges "
                                            "count as convex)"},
    "robust_laplacian": {("boundary", "library"): "R1 (tufted cover: boundary edges are "
                                                  "flipped in the double of the surface)",
                         ("mollify", "library"): "R3 (mollify_factor 1e-5 lengthens every "
                                                 "edge of a nearly degenerate mesh)"},
}

#: The values of an adapter's convention option: the reference's or the library's own.
CONVENTIONS = ("reference", "library")


def convention_name(base: str, **options: str) -> str:
    """Display name of an adapter with convention options (each one of CONVENTIONS):
    ``base`` if all are "reference", else the non-default ones in parentheses.

    >>> convention_name("gpytoolbox", boundary="library", dihedral="reference")
    "gpytoolbox(boundary='library')"
    >>> convention_name("gpytoolbox", boundary="lib")
    Traceback (most recent call last):
    ...
    ValueError: boundary must be one of ('reference', 'library'), got 'lib'
    """
    for key, value in options.items():
        if value not in CONVENTIONS:
            raise ValueError(f"{key} must be one of {CONVENTIONS}, got {value!r}")
    chosen = [f"{k}={v!r}" for k, v in options.items() if v != "reference"]
    return f"{base}({', '.join(chosen)})" if chosen else base


_OPTIONS = re.compile(r"^\s*([^()\s]+)\s*\((.*)\)\s*$", re.S)


class ImplementationNotFound(ValueError):
    """An --impl argument that names nothing importable."""


def parse_spec(spec: str) -> tuple[str, dict]:
    """(name or module:object, keyword options) of a spec.

    >>> parse_spec("libigl(boundary=library)")
    ('libigl', {'boundary': 'library'})
    >>> parse_spec("pkg.mod:Impl(scale=2, name='x')")
    ('pkg.mod:Impl', {'scale': 2, 'name': 'x'})
    """
    m = _OPTIONS.match(spec)
    if not m:
        return spec.strip(), {}
    base, body = m.group(1), m.group(2).strip()
    options = {}
    for part in filter(None, (p.strip() for p in body.split(","))):
        key, eq, value = part.partition("=")
        key, value = key.strip(), value.strip()
        if not eq or not key.isidentifier():
            raise ImplementationNotFound(f"bad option {part!r} in {spec!r}: use key=value")
        try:
            options[key] = ast.literal_eval(value)
        except (ValueError, SyntaxError):
            options[key] = value
    return base, options


def load_implementation(spec: str):
    """An implementation object from a built-in name or ``module:object``, with options.

    A class is instantiated with the spec's options (none: no arguments); any
    other object is used as is (and takes no options).
    """
    base, options = parse_spec(spec)
    target = BUILTIN.get(base, base)
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
    if not isinstance(obj, type):
        if options:
            raise ImplementationNotFound(f"{spec!r}: options need a class, {qual!r} is not one")
        return obj
    try:
        return obj(**options)
    except (TypeError, ValueError) as e:
        raise ImplementationNotFound(f"{spec!r}: {e}") from None


def convention_counterpart(spec: str) -> tuple[str, str] | None:
    """(spec with reference conventions, the findings it differs by) when every option
    of ``spec`` selects a documented library convention, else None.

    >>> convention_counterpart("pymeshlab(genus=library)")
    ('pymeshlab', 'P1 (genus of a non-orientable mesh is floor(h / 2))')
    >>> convention_counterpart("libigl") is None
    True
    """
    base, options = parse_spec(spec)
    documented = DOCUMENTED_CONVENTIONS.get(base, {})
    if not options or not all((k, v) in documented for k, v in options.items()):
        return None
    return base, "; ".join(documented[(k, v)] for k, v in options.items())


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
