"""Counterexamples a user can act on: the full mesh, and a snippet that reproduces them.

A property's example is what its strategy built (a mesh with exact positions,
perhaps a function on it, boundary data, a point set); the implementation saw
its float arrays ``V``, ``F``.  Wherever a failure, crash or tie is shown (the
terminal, ``check_implementation``'s AssertionError, a pytest failure,
``results.json``) it carries:

- ``V`` as floats whose ``repr`` round-trips (the implementation's exact input),
  the exact rationals the example was built from where they differ, and ``F``;
- a snippet of a few lines that runs the property once more on the very same
  example, with only ddg-oracle and the user's module installed::

      from ddg_oracle.properties.counterexample import replay
      from ddg_oracle.application.implementations import load_implementation
      replay("D1.6", load_implementation("mymod:Impl"), "eNqr...")

  :func:`replay` raises what the check raised (the PropertyFailure, or the
  implementation's own exception), or returns None if it now passes.  The last
  argument is the example itself as JSON, compressed and base64-encoded
  (:func:`encode_example`, :mod:`.codec`): examples hold exact surfaces that no
  short text would rebuild.  Decoding it runs no code (a replay string from a
  downloaded report is data, not a program): only numbers, Fractions, tuples and
  the example's own records are rebuilt, each through its validating constructor.
"""

from __future__ import annotations

import importlib.machinery
import importlib.util
import os
import sys
import sysconfig
import textwrap
from fractions import Fraction
from pathlib import Path

#: vertices and faces shown inline; a longer mesh is elided (its file says the rest)
INLINE_VERTICES = 24
PREFIX = "ddg2:"                     # version of the encoding: JSON (ddg1: was a pickle)


def encode_example(example) -> str:
    """The example as text: ``ddg2:`` + base64 of the zlib-compressed JSON of
    :func:`.codec.encode`; :class:`.codec.UnsafeValue` for an example of a type the
    codec does not write.

    >>> decode_example(encode_example((1, Fraction(1, 3))))
    (1, Fraction(1, 3))
    """
    from .codec import to_text
    return to_text(example, PREFIX)


def decode_example(text: str):
    """The example :func:`encode_example` encoded, rebuilt without running any code;
    :class:`.codec.BadEncoding` (a ValueError) for any other text.  An old ``ddg1:``
    string was a pickle, which could run code: it is refused, not decoded."""
    from .codec import BadEncoding, from_text
    if text.startswith("ddg1:"):
        raise BadEncoding("a ddg1: replay string is a pickle, which could run code when "
                          "decoded: it is not read; run the check again for a ddg2: string")
    return from_text(text, PREFIX)


def replay(property_id: str, impl, example):
    """Run property ``property_id`` once on ``impl`` with ``example`` (an example, or the
    text of :func:`encode_example`); raises what the check raises, None if it passes.
    ``impl`` is called as the runner calls it (:class:`~.calls.Watched`: its declared
    conventions mapped, its answers screened, its own numpy error state)."""
    from .calls import Watched
    from .registry import PROPERTIES, all_properties

    all_properties()
    if property_id not in PROPERTIES:
        raise KeyError(f"no property {property_id!r}")
    if isinstance(example, str):
        example = decode_example(example)
    if not isinstance(impl, Watched):
        impl = Watched(impl, property_id)
    PROPERTIES[property_id].check(impl, example)


# --- the mesh of an example ---------------------------------------------------------------


def _is_points(x) -> bool:
    return (isinstance(x, (tuple, list)) and len(x) > 0
            and all(isinstance(p, (tuple, list)) and len(p) in (2, 3) for p in x)
            and all(isinstance(c, (int, float, Fraction)) for p in x for c in p))


def _is_faces(x) -> bool:
    return (isinstance(x, (tuple, list)) and len(x) > 0
            and all(isinstance(f, (tuple, list)) and len(f) == 3
                    and all(isinstance(i, int) for i in f) for f in x))


def exact_mesh(example):
    """(points as exact coordinates, faces) of an example, or None: an
    :class:`~.example.Example`'s ``exact_mesh`` (indexed as the arrays the implementation
    received), ``.positions`` / ``.surface.positions`` with ``.faces`` / a triangulation, or a (points, faces, ...)
    tuple such as the planar examples; the first such part of a tuple otherwise."""
    if isinstance(example, tuple):
        if len(example) >= 2 and _is_points(example[0]) and _is_faces(example[1]):
            return [list(p) for p in example[0]], [list(f) for f in example[1]]
        for part in example:
            m = exact_mesh(part)
            if m is not None:
                return m
        return None
    given = getattr(example, "exact_mesh", None)           # an Example: as it was drawn
    if isinstance(given, tuple):
        return given
    surface = getattr(example, "surface", None)
    holder = surface if surface is not None and not callable(surface) else example
    positions = getattr(holder, "positions", None)
    if positions is None:
        return None
    faces = getattr(example, "faces", None)
    if faces is None or callable(faces):
        t = getattr(holder, "triangulation", None)
        faces = getattr(t, "faces", None)
    if faces is None:
        return None
    return [list(p) for p in positions], [list(f) for f in faces]


def float_mesh(mesh):
    """(V, F) with every coordinate a float, every z present (planar points get z = 0)."""
    V, F = mesh
    V = [[float(c) for c in (list(p) + [0] * (3 - len(p)))] for p in V]
    return V, [[int(i) for i in f] for f in F]


def rounded_by_floats(exact) -> bool:
    """Whether some coordinate is not exactly its float (the float view rounds it)."""
    return any(Fraction(float(c)) != c for p in exact for c in p
               if isinstance(c, (int, Fraction)))


def mesh_text(mesh, exact=None, limit: int = INLINE_VERTICES, indent: str = "  ") -> str:
    """``V = [...]`` (floats, repr round-trips), ``F = [...]``, and the exact rationals where
    the floats round them; elided past ``limit`` vertices or faces."""
    V, F = float_mesh(mesh)
    lines = [f"mesh: {len(V)} vertices, {len(F)} faces"]

    def listing(name, rows):
        shown = rows if len(rows) <= limit else rows[:limit]
        body = ",\n".join(f"{indent}  {r!r}" for r in shown)
        more = "" if len(rows) <= limit else f",\n{indent}  ... ({len(rows) - limit} more)"
        return f"{name} = [\n{body}{more}]"

    lines.append(listing("V", V))
    lines.append(listing("F", F))
    if exact is not None and rounded_by_floats(exact[0]):
        rows = [[str(Fraction(c)) for c in p] for p in exact[0]]
        lines.append(listing("exact V (the floats above round these)", rows))
    return textwrap.indent("\n".join(lines), indent)


# --- the snippet ---------------------------------------------------------------------------


def implementation_spec(impl) -> str | None:
    """How :func:`ddg_oracle.application.implementations.load_implementation` loads ``impl`` again: its
    ``spec`` (an isolated or built-in implementation), else ``module:Class`` of its class,
    with the constructor's options the object keeps (:func:`constructor_options`); None for
    an object no import can rebuild (a class defined in a function, ``__main__``)."""
    spec = getattr(impl, "spec", None)
    if isinstance(spec, str):
        return spec
    cls = type(impl)
    if cls.__module__ == "__main__" or "<locals>" in cls.__qualname__:
        return None
    options = constructor_options(impl)
    shown = ", ".join(f"{k}={v!r}" for k, v in options.items())
    return f"{cls.__module__}:{cls.__qualname__}" + (f"({shown})" if shown else "")


def constructor_options(impl) -> dict:
    """{parameter: value} of ``impl``'s constructor that the object keeps under the same
    name (``self.tol = tol``, or ``self._tol``) with a value other than the default: a
    number, a string, a bool or None, as a spec's options can say them.  An object built
    with ``Mine(tol=0.5)`` failed and its replay built ``Mine()``, which passed.

    >>> class Mine:
    ...     def __init__(self, tol=1e-3, name="x", data=None):
    ...         self.tol, self._name, self.data = tol, name, data
    >>> constructor_options(Mine(tol=0.5)), constructor_options(Mine(data=[1, 2]))
    ({'tol': 0.5}, {})
    """
    import inspect
    import math
    init = type(impl).__init__
    if init is object.__init__:
        return {}
    try:
        parameters = list(inspect.signature(init).parameters.values())[1:]
    except (TypeError, ValueError):
        return {}
    kept, out = getattr(impl, "__dict__", {}), {}
    for p in parameters:
        if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
            continue
        value = kept.get(p.name, kept.get("_" + p.name, p.default))
        plain = value is None or isinstance(value, (bool, int, str)) or \
            (isinstance(value, float) and math.isfinite(value))
        if plain and not (isinstance(value, str) and any(c in value for c in ",()'\"\\")) \
                and (p.default is p.empty or value != p.default):
            out[p.name] = value
    return out


def module_dir(spec: str) -> str | None:
    """The directory to append to sys.path for ``spec``'s module, when it is not installed
    (a user's module next to their tests), else None.  Found as loading it finds it: on
    sys.path, else in the current directory (which ``load_implementation`` appends, in
    whichever process loaded it: a pool worker, not this one)."""
    if spec.startswith("exec:"):
        return None
    module = spec.split("(")[0].partition(":")[0]
    if ":" not in spec.split("(")[0]:
        return None                                       # a built-in name
    top = module.split(".")[0]
    try:
        found = importlib.util.find_spec(top)
        if found is None:
            found = importlib.machinery.PathFinder.find_spec(top, [os.getcwd()])
    except (ImportError, ValueError):
        return None
    if found is None or not found.origin:
        return None
    path = Path(found.origin).resolve().parent
    if found.submodule_search_locations:                  # a package: its parent
        path = path.parent
    installed = {Path(p).resolve() for p in (sysconfig.get_paths()["purelib"],
                                             sysconfig.get_paths()["platlib"], sys.prefix)}
    if any(path == p or p in path.parents for p in installed):
        return None
    return str(path)


def program_dir(spec: str) -> str | None:
    """For an ``exec:`` spec, the directory its program ran in (the current one: its own
    files are named absolutely in the spec, but it may read others relative to where it
    runs); None for any other spec."""
    return os.getcwd() if spec.startswith("exec:") else None


def snippet(property_id: str, spec: str | None, encoded: str, width: int = 88) -> str:
    """A few lines of Python that replay the example on the implementation ``spec``."""
    lines = []
    where = module_dir(spec) if spec else None
    if where is not None:
        lines.append(f"import sys; sys.path.append({where!r})  # where your module was found")
    ran_in = program_dir(spec) if spec else None
    if ran_in is not None:
        lines.append(f"import os; os.chdir({ran_in!r})  # where the program ran")
    lines.append("from ddg_oracle.properties.counterexample import replay")
    if spec is None:
        lines.append("impl = ...  # your implementation object (its class could not be imported)")
    else:
        lines.append("from ddg_oracle.application.implementations import load_implementation")
        lines.append(f"impl = load_implementation({spec!r})")
    chunk = width - 8
    parts = [encoded[k:k + chunk] for k in range(0, len(encoded), chunk)] or [""]
    if len(parts) == 1:
        lines.append(f"replay({property_id!r}, impl, {encoded!r})")
    else:
        lines.append(f"replay({property_id!r}, impl, (")
        lines.extend(f"    {p!r}" for p in parts)
        lines.append("))")
    return "\n".join(lines)
