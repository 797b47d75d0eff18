"""Finding implementations by name: built-in adapters, ``module:object``, or
``exec:COMMAND`` (a program speaking the executable protocol, docs/protocol.md).

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

_DECLARATION = re.compile(r"^ADAPTER\s*=\s*", re.M)


def _literal_from(text: str, path) -> dict:
    """The Python literal at the start of ``text`` (it may span lines)."""
    lines = text.splitlines(keepends=True)
    for k in range(1, len(lines) + 1):
        try:
            return ast.literal_eval("".join(lines[:k]))
        except SyntaxError:
            continue
    raise SyntaxError(f"{path}: ADAPTER is not a literal")


def _declared_adapters() -> list[dict]:
    """The ``ADAPTER`` declarations of the adapter modules in ``ddg_oracle/oracles/`` (a
    dict literal naming the implementation, its object, the library it needs, the pip
    extra that installs it and its rank in reports), read from the source without
    importing the module (importing a library costs seconds and may fail where it is not
    installed).  Adding an adapter is adding its module: nothing here names it."""
    import importlib.util
    from pathlib import Path
    # the package's directory, found without running its __init__ (editable or installed)
    spec = importlib.util.find_spec("ddg_oracle.oracles")
    found = []
    paths = sorted(p for d in spec.submodule_search_locations for p in Path(d).glob("*.py"))
    for path in paths:
        # only the declaration is parsed, not the module: a whole module's syntax tree
        # cost every process that starts ddg-oracle 23 ms (3,000 lines of adapters)
        text = path.read_text(encoding="utf-8")
        m = _DECLARATION.search(text)
        if m:
            d = _literal_from(text[m.end():], path)
            d["module"] = f"ddg_oracle.oracles.{path.stem}"
            found.append(d)
    return sorted(found, key=lambda d: (d.get("rank", len(found)), d["name"]))


_ADAPTERS = _declared_adapters()

# name -> "module:object": the adapters' own declarations, in their report order
BUILTIN: dict[str, str] = {d["name"]: f"{d['module']}:{d['object']}" for d in _ADAPTERS}

#: The pip extra that installs each built-in adapter's library (absent: the core's).
EXTRAS: dict[str, str] = {d["name"]: d["extra"] for d in _ADAPTERS if d.get("extra")}

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
    other object is used as is (and takes no options).  ``module`` resolves as
    Python resolves it, with the current directory *appended* to ``sys.path``
    (so a user's module next to where they run is found, and never shadows an
    installed package).  Any failure to import it is
    :class:`ImplementationNotFound` ("cannot import your module ...").
    """
    if spec.startswith("exec:"):
        # a program speaking the executable protocol (docs/protocol.md)
        from ..oracles.executable import DriverFailed, Executable
        try:
            return Executable(spec[len("exec:"):])
        except (DriverFailed, ValueError) as e:
            raise ImplementationNotFound(f"cannot start {spec!r}: {e}") from None
    base, options = parse_spec(spec)
    target = BUILTIN.get(base, base)
    module, sep, qual = target.partition(":")
    if not sep or not module or not qual:
        raise ImplementationNotFound(
            f"unknown implementation {spec!r}: use one of {', '.join(BUILTIN)} or module:object")
    builtin = base in BUILTIN
    if not builtin and os.getcwd() not in sys.path and "" not in sys.path:
        # like `python -m` and pytest, the user's modules resolve from where they run;
        # appended, so nothing of theirs can replace an installed module
        sys.path.append(os.getcwd())
    try:
        obj = importlib.import_module(module)
    except Exception as e:  # noqa: BLE001  (a user module may fail in any way: say which)
        if builtin and "undefined symbol" in str(e):
            # installed, but a shared library another package bundles (pymeshlab's
            # libtbb before lagrange's) was loaded first in this process
            raise ImplementationNotFound(
                f"{base} is installed but cannot load in this process ({type(e).__name__}: "
                f"{e}): a library imported before it loaded another version of a shared "
                f"library it needs; check it in a process of its own (ddg-oracle check "
                f"does) or import it first") from None
        if builtin:
            raise ImplementationNotFound(
                f"{base} is not installed ({type(e).__name__}: {e}); "
                f"pip install 'ddg-oracle[{EXTRAS.get(base, 'all')}]'") from None
        raise ImplementationNotFound(
            f"cannot import your module {module!r} (for {spec!r}): {type(e).__name__}: {e}"
        ) from None
    try:
        for part in qual.split("."):
            obj = getattr(obj, part)
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


#: The library each built-in adapter wraps (None: the core's own dependencies).
LIBRARIES: dict[str, str | None] = {d["name"]: d.get("library") for d in _ADAPTERS}


def available() -> list[str]:
    """Built-in implementations whose libraries are installed on this machine."""
    gone = missing()
    return [name for name in BUILTIN if name not in gone]


#: The library drivers of examples/cpp (C++, the executable protocol), by file name.
DRIVERS = ("cgal_driver", "openmesh_driver")


def drivers_directory(directory: str | None = None) -> str:
    """Where built C++ drivers are looked for: ``directory``, else the environment's
    ``DDG_ORACLE_DRIVERS``, else ``examples/cpp/build`` under the current directory
    (where ``bash examples/cpp/build.sh`` of a checkout puts them)."""
    return directory or os.environ.get("DDG_ORACLE_DRIVERS") or os.path.join(
        "examples", "cpp", "build")


def built_drivers(directory: str | None = None) -> list[str]:
    """``exec:`` specs of the library drivers (:data:`DRIVERS`) built in
    :func:`drivers_directory`; the template driver is not one (it checks nothing of a
    library)."""
    import shlex
    where = drivers_directory(directory)
    found = [os.path.abspath(os.path.join(where, name)) for name in DRIVERS]
    return ["exec:" + shlex.quote(path) for path in found if os.access(path, os.X_OK)]


def missing() -> dict[str, str]:
    """{built-in name: why it is not available}: its library is not installed.  Found
    without importing it (``importlib.util.find_spec``): importing every library only to
    see that it is there costs seconds, and the workers import it again anyway."""
    import importlib.util
    out = {}
    for name in BUILTIN:
        lib = LIBRARIES.get(name)
        if lib is not None and importlib.util.find_spec(lib) is None:
            out[name] = (f"{name} is not installed (no module {lib!r}); "
                         f"pip install 'ddg-oracle[{EXTRAS.get(name, 'all')}]'")
    return out
