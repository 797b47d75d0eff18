"""Switch one wrong version of one reference function on for a pytest run (issue 44).

Loaded with ``-p benchmarks.knockout_plugin`` by ``benchmarks/knockout.py`` in a fresh
``python -m pytest`` child; the environment names what to do:

* ``DDG_KNOCKOUT=MODULE:QUALNAME:VARIANT`` (``ddg_oracle.reference.cotangents:face_data:last``):
  at ``pytest_configure``, before any test module is imported, the function object itself
  is patched (its ``__code__`` replaced by a wrapper's), so a name imported elsewhere
  with ``from .cotangents import face_data`` is switched too.
* ``DDG_KNOCKOUT_HAND=MODULE:QUALNAME:NAME`` (``curvature:vertex_type:sign_reversed``): the
  same, with a wrong version written by hand (``HAND_WRITTEN`` in
  benchmarks/knockout_hand.py, loaded as a second plugin, ``-p benchmarks.knockout_hand``,
  which switches it on with this module's ``Patch``: a realistic mistake for a function no
  generic variant fits; the function's code becomes a wrapper calling it, a generator
  function's too).
* ``DDG_KNOCKOUT_STATS=PATH`` (with either): at the end, how many calls of the function the
  tests made and how many results the variant changed (a survivor with none changed was
  never really switched on).
* ``DDG_KNOCKOUT_RECORD=PATH``: every target is wrapped by a recorder that leaves results
  alone and writes to PATH, per target, the kinds of result it returned and the tests (and
  test modules, while they were being imported) that called it.

The wrong versions (``VARIANTS``) are generic, decided from the result of each call:

* ``value``: a number made wrong by its type: ``bool`` negated, ``int`` + 1, ``Fraction``
  + 1/3, ``float`` * (1 + 2**-10) + 2**-10, a Surd + 1/3, an Angle or AngleLength + pi/3,
  an Interval shifted by 1/3; and an object by a small change that keeps it valid: a
  SparseMatrix's last stored entry + 1/3, a PolyhedralSurface's last vertex moved by 1/3
  along x, a Triangulation's last two vertex labels swapped (same gluings), a
  PiecewiseFlatSurface's squared length of one edge (the last whose faces have rational
  squared lengths) x 9/8, or 8/9 where 9/8 breaks a strict triangle inequality (areas of
  its faces recomputed);
* ``last``: a tuple or list with its last element made wrong (recursively: ``value``,
  ``last`` of it, or ``drop`` of a set), a dict with its last key's value made wrong, a
  Triangulation with its last face's corner order reversed (its gluings' reversed flags
  toggled to match, as ``with_reversed_faces`` does: the same surface, one face oriented
  against its neighbours);
  a dataclass instance (a certificate, a run, a classification) with its first field that
  can be made wrong (by ``value`` of it, or ``last`` of it) made wrong, and with ``last``
  its last such field (``dataclasses.replace``: the class's own checks still run);
* ``drop``: a tuple or list without its last element, a set or frozenset without one;
* ``skip``: the function returns None without running its body (for functions that return
  None: validators that never raise, procedures that do nothing).

A call whose result the variant does not fit (another type, an empty tuple, a perturbation
that raises, a changed triangulation failing its own structural checks) returns the original
result: the knockout only ever changes a value, it never makes the wrapper crash.
"""

from __future__ import annotations

import dataclasses
import functools
import importlib
import inspect
import json
import os
import types
from fractions import Fraction

ENV = "DDG_KNOCKOUT"
RECORD_ENV = "DDG_KNOCKOUT_RECORD"
HAND_ENV = "DDG_KNOCKOUT_HAND"           # a hand-written wrong version (knockout_hand.py)
STATS_ENV = "DDG_KNOCKOUT_STATS"         # where to write how many results were changed
VARIANTS = ("value", "last", "drop", "skip")
PACKAGE = "ddg_oracle.reference"
SKIP_MODULES = (PACKAGE + ".errors",)      # exception classes only


class NotApplicable(Exception):
    """The variant does not fit this result: the original is returned."""


# -- what a result is, and its wrong versions --------------------------------------------------

def _exact_types():
    from ddg_oracle.reference.exact.angles import Angle
    from ddg_oracle.reference.exact.intervals import Interval
    from ddg_oracle.reference.exact.measures import AngleLength
    from ddg_oracle.reference.exact.surds import Surd
    return Surd, Angle, AngleLength, Interval


def kind(x) -> str:
    """The kind of a result, as the variants see it ('other:NAME' when none fits)."""
    if x is None:
        return "None"
    if isinstance(x, bool):
        return "bool"
    if isinstance(x, int):
        return "int"
    if isinstance(x, Fraction):
        return "Fraction"
    if isinstance(x, float):
        return "float"
    Surd, Angle, AngleLength, Interval = _exact_types()
    for t in (Surd, Angle, AngleLength, Interval):
        if isinstance(x, t):
            return t.__name__
    if isinstance(x, (tuple, list)):
        return type(x).__name__ if type(x) in (tuple, list) else "tuple" if _is_namedtuple(x) \
            else f"other:{type(x).__name__}"
    if type(x) is dict:
        return "dict"
    if isinstance(x, (set, frozenset)) and type(x) in (set, frozenset):
        return type(x).__name__
    if type(x) in _object_types():
        return type(x).__name__
    if dataclasses.is_dataclass(x) and not isinstance(x, type):
        return "dataclass"
    return f"other:{type(x).__name__}"


def _object_types():
    from ddg_oracle.reference.combinatorics import Triangulation
    from ddg_oracle.reference.metric import PiecewiseFlatSurface
    from ddg_oracle.reference.polyhedral import PolyhedralSurface
    from ddg_oracle.reference.sparse import SparseMatrix
    return SparseMatrix, PolyhedralSurface, Triangulation, PiecewiseFlatSurface


VARIANTS_OF_KIND = {
    "bool": ("value",), "int": ("value",), "Fraction": ("value",), "float": ("value",),
    "Surd": ("value",), "Angle": ("value",), "AngleLength": ("value",), "Interval": ("value",),
    "tuple": ("last", "drop"), "list": ("last", "drop"), "dict": ("last",),
    "set": ("drop",), "frozenset": ("drop",),
    "SparseMatrix": ("value",), "PolyhedralSurface": ("value",),
    "Triangulation": ("value", "last"), "PiecewiseFlatSurface": ("value",),
    "dataclass": ("value", "last"),
}


def _is_namedtuple(x) -> bool:
    return isinstance(x, tuple) and hasattr(type(x), "_fields")


def wrong_value(x):
    """``x`` made wrong by its type (raises NotApplicable when no rule fits)."""
    if isinstance(x, bool):
        return not x
    if isinstance(x, int):
        return x + 1
    if isinstance(x, Fraction):
        return x + Fraction(1, 3)
    if isinstance(x, float):
        return x * (1 + 2.0 ** -10) + 2.0 ** -10
    Surd, Angle, AngleLength, Interval = _exact_types()
    if isinstance(x, Surd):                       # CotanSum too: a Surd
        return x + Fraction(1, 3)
    if isinstance(x, (Angle, AngleLength)):
        return x + Angle(pi_coefficient=Fraction(1, 3))       # + pi/3
    if isinstance(x, Interval):
        return x + Fraction(1, 3)
    SparseMatrix, PolyhedralSurface, Triangulation, PiecewiseFlatSurface = _object_types()
    if type(x) is SparseMatrix:                   # its last stored entry + 1/3
        n = x.shape[0]
        rows = {i: dict(x.row(i)) for i in range(n)}
        full = [i for i in range(n) if rows[i]]
        if not full:
            raise NotApplicable("no entry")
        i = full[-1]
        j = max(rows[i])
        rows[i][j] = rows[i][j] + Fraction(1, 3)
        return SparseMatrix(x.shape, rows)
    if type(x) is PolyhedralSurface:              # its last vertex moved by 1/3 along x
        p = list(x.positions)
        p[-1] = (p[-1][0] + Fraction(1, 3), *p[-1][1:])
        return x.with_positions(p)
    if type(x) is Triangulation:                  # its last two vertex labels swapped
        return _swapped_labels(x)
    if type(x) is PiecewiseFlatSurface:           # one edge's squared length x 9/8 (or 8/9)
        return _stretched_edge(x)
    if dataclasses.is_dataclass(x) and not isinstance(x, type):
        return _wrong_field(x, dataclasses.fields(x))
    raise NotApplicable(type(x).__name__)


def _wrong_field(x, fields):
    """``x`` with the first of ``fields`` that can be made wrong (by its own kind) made
    wrong; the class's __init__ and __post_init__ check the result."""
    for f in fields:
        try:
            return dataclasses.replace(x, **{f.name: _wrong_element(getattr(x, f.name))})
        except Exception:             # NotApplicable, a type no rule takes, a check refusing it
            continue
    raise NotApplicable(f"{type(x).__name__}: no field can be made wrong")


def _checked(t):
    """``t`` if it passes the triangulation's own structural checks (the private ones, so
    that a knocked-out ``validate`` plays no part), else NotApplicable."""
    try:
        t._check_gluings()
        t._check_vertices()
    except Exception as e:
        raise NotApplicable(f"invalid: {e}") from None
    return t


def _swapped_labels(t):
    """The same gluings with vertices n-2 and n-1 renamed into each other (a relabelling
    bug: a valid triangulation of the same surface, its vertices out of step with
    whatever they index, e.g. positions)."""
    from ddg_oracle.reference.combinatorics import Triangulation
    n = t._n
    if n < 2:
        raise NotApplicable("one vertex")
    swap = {n - 2: n - 1, n - 1: n - 2}
    faces = tuple(tuple(swap.get(v, v) for v in f) for f in t._faces)
    gluings = tuple((a, b, t._rev[a]) for a, b in t._edges)
    return _checked(Triangulation._trusted(faces, n, gluings))


def _reversed_last_face(t):
    """Its last face's corner order reversed, ``(a, b, c) -> (a, c, b)``, its gluings'
    reversed flags toggled to match (the reference's own face reversal, ``TriangulationBuilder``):
    the same surface, one face oriented against its neighbours (an orientation bug)."""
    from ddg_oracle.reference.combinatorics import TriangulationBuilder
    if not t._faces:
        raise NotApplicable("no face")
    b = TriangulationBuilder(t)
    b.reverse_faces({len(t._faces) - 1})
    return _checked(b.build())


def _stretched_edge(s):
    """The same surface with the squared length of its last edge whose faces have rational
    squared lengths multiplied by 9/8 (8/9 where 9/8 breaks a strict triangle inequality),
    the areas of its faces recomputed by Heron: a valid surface, one length wrong."""
    from ddg_oracle.reference.exact import sqrt
    from ddg_oracle.reference.metric import PiecewiseFlatSurface, heron16
    t = s.triangulation
    sq = list(s.squared_lengths)
    for e in reversed(range(len(sq))):
        faces = sorted({h // 3 for h in t._edges[e] if h >= 0})
        if not all(type(x) is Fraction for f in faces for x in s.face_squared_lengths(f)):
            continue
        for k in (Fraction(9, 8), Fraction(8, 9)):
            new = sq[:e] + [sq[e] * k] + sq[e + 1:]
            out = PiecewiseFlatSurface._trusted(t, new, s.areas)
            h = {f: heron16(*out.face_squared_lengths(f)) for f in faces}
            if all(v > 0 for v in h.values()):
                areas = list(s.areas)
                for f, v in h.items():
                    areas[f] = sqrt(v) / 4
                return PiecewiseFlatSurface._trusted(t, new, areas)
    raise NotApplicable("no edge with rational faces can be stretched")


def _rebuild(x, items):
    if _is_namedtuple(x):
        return type(x)._make(items)
    if type(x) in (tuple, list):
        return type(x)(items)
    raise NotApplicable(type(x).__name__)


def wrong_last(x):
    """The last element of a tuple/list (the last key's value of a dict) made wrong; a
    Triangulation with its last face's orientation reversed."""
    if type(x) is _object_types()[2]:
        return _reversed_last_face(x)
    if dataclasses.is_dataclass(x) and not isinstance(x, type):
        return _wrong_field(x, reversed(dataclasses.fields(x)))
    if isinstance(x, (tuple, list)):
        if not x:
            raise NotApplicable("empty")
        return _rebuild(x, [*x[:-1], _wrong_element(x[-1])])
    if type(x) is dict:
        if not x:
            raise NotApplicable("empty")
        out = dict(x)
        k = next(reversed(out))
        out[k] = _wrong_element(out[k])
        return out
    raise NotApplicable(type(x).__name__)


def _wrong_element(x):
    """An element made wrong by its own kind: a number by ``value``, a tuple, list or dict
    by ``last``, a set by ``drop``."""
    if type(x) in (set, frozenset):
        return wrong_drop(x)
    try:
        return wrong_value(x)
    except NotApplicable:
        return wrong_last(x)


def wrong_drop(x):
    """A tuple/list without its last element, a set/frozenset without one element."""
    if isinstance(x, (tuple, list)):
        if not x or _is_namedtuple(x):
            raise NotApplicable("empty" if not x else "namedtuple")
        return type(x)(x[:-1]) if type(x) in (tuple, list) else _rebuild(x, x[:-1])
    if type(x) in (set, frozenset):
        if not x:
            raise NotApplicable("empty")
        drop = min(x, key=repr)                     # one element, the same every run
        return type(x)(e for e in x if e is not drop)
    raise NotApplicable(type(x).__name__)


PERTURB = {"value": wrong_value, "last": wrong_last, "drop": wrong_drop}


STATS = {"calls": 0, "changed": 0}     # calls of the knocked-out function, results changed


def perturber(variant: str):
    """result -> wrong result, or the result itself when the variant does not fit."""
    f = PERTURB[variant]

    def perturb(r):
        STATS["calls"] += 1
        try:
            w = f(r)
        except Exception:                 # NotApplicable, or a type the rule cannot take
            return r
        STATS["changed"] += 1
        return w
    return perturb


def _skipped():
    STATS["calls"] += 1
    STATS["changed"] += 1


# -- the targets: public functions and methods ---------------------------------------------------

def reference_modules() -> list[str]:
    import pkgutil
    pkg = importlib.import_module(PACKAGE)
    names = sorted(m.name for m in pkgutil.walk_packages(pkg.__path__, PACKAGE + "."))
    return [n for n in names if n not in SKIP_MODULES]


def targets_of(module_name: str) -> list[tuple[str, str]]:
    """``(qualname, how)`` of the module's public functions and its public classes' public
    methods (``how``: function, cached (lru_cache), method, staticmethod, classmethod,
    property, cached_property), in source order.  Not the exception classes, nor the
    methods of a typing.Protocol (HalfedgeMesh, Metric: interfaces)."""
    mod = importlib.import_module(module_name)
    out = []
    for name, obj in vars(mod).items():
        if name.startswith("_"):
            continue
        if isinstance(obj, functools._lru_cache_wrapper) \
                and getattr(obj, "__module__", "") == module_name:
            out.append((name, "cached"))
        elif inspect.isfunction(obj) and obj.__module__ == module_name:
            out.append((name, "function"))
        elif inspect.isclass(obj) and obj.__module__ == module_name \
                and not issubclass(obj, BaseException) and not _is_protocol(obj):
            for k, v in vars(obj).items():
                if k.startswith("_"):
                    continue
                how = ("method" if inspect.isfunction(v) else
                       "staticmethod" if isinstance(v, staticmethod) else
                       "classmethod" if isinstance(v, classmethod) else
                       "cached_property" if isinstance(v, functools.cached_property) else
                       "property" if isinstance(v, property) and v.fget is not None else None)
                if how:
                    out.append((f"{name}.{k}", how))
    return out


def _is_protocol(cls) -> bool:
    """A typing.Protocol (an interface: its methods have no body to knock out)."""
    return bool(getattr(cls, "_is_protocol", False))


def function_of(module_name: str, qualname: str):
    """The function object whose code is patched, and the lru_cache wrapper (or None)."""
    mod = importlib.import_module(module_name)
    parts = qualname.split(".")
    if len(parts) == 1:
        obj = getattr(mod, parts[0])
        if isinstance(obj, functools._lru_cache_wrapper):
            return obj.__wrapped__, obj
        return obj, None
    cls = getattr(mod, parts[0])
    v = vars(cls)[parts[1]]
    if isinstance(v, (staticmethod, classmethod)):
        return v.__func__, None
    if isinstance(v, functools.cached_property):
        return v.func, None
    if isinstance(v, property):
        return v.fget, None
    return v, None


# -- patching a function object in place ---------------------------------------------------------

_WRAPPER = """\
def _factory():
    {cells}
    def wrapper(*args, **kwargs):
        {touch}
        {body}
    return wrapper
"""
_CALL = "return {perturb}({orig}(*args, **kwargs))"
_REPLACE = "return {perturb}({orig}, *args, **kwargs)"
_SKIP = "{perturb}(); return None"
_counter = [0]


def _wrapper_code(freevars: tuple, body: str):
    cells = "; ".join(f"{v} = None" for v in freevars) or "pass"
    touch = "; ".join(freevars) or "pass"
    ns: dict = {}
    exec(_WRAPPER.format(cells=cells, touch=touch, body=body), ns)
    code = ns["_factory"]().__code__
    if code.co_freevars != freevars:
        raise NotApplicable(f"free variables {freevars} (a wrapper has {code.co_freevars})")
    return code


class Patch:
    """``f``'s code replaced by ``wrapper(*args, **kwargs)``: ``perturb(copy(*args,
    **kwargs))`` (or ``return None`` for ``skip``), where ``copy`` is a new function with
    f's original code, globals, defaults and closure.  With ``replace``: ``replace(copy,
    *args, **kwargs)`` (a hand-written wrong version; a generator function can take one,
    its code becoming a plain function's returning what ``replace`` returns).
    :meth:`undo` restores f."""

    def __init__(self, f, perturb=None, skip=False, cache=None, replace=None):
        if replace is None and (inspect.isgeneratorfunction(f) or inspect.iscoroutinefunction(f)):
            raise NotApplicable("a generator function")
        self.f, self.cache = f, cache
        self.saved = (f.__code__, f.__defaults__, f.__kwdefaults__)
        _counter[0] += 1
        tag = f"__ddg_knockout_{_counter[0]}"
        self.names = (tag + "_orig", tag + "_perturb")
        copy = types.FunctionType(f.__code__, f.__globals__, f.__name__, f.__defaults__,
                                  f.__closure__)
        copy.__kwdefaults__ = f.__kwdefaults__
        copy.__qualname__ = f.__qualname__
        self.original = copy
        body = (_REPLACE if replace is not None else _SKIP if skip else _CALL).format(
            orig=self.names[0], perturb=self.names[1])
        code = _wrapper_code(f.__code__.co_freevars, body)
        f.__globals__[self.names[0]] = copy
        f.__globals__[self.names[1]] = (replace if replace is not None else
                                        _skipped if skip else perturb)
        f.__code__ = code
        f.__defaults__ = None
        f.__kwdefaults__ = None
        if cache is not None:
            cache.cache_clear()

    def undo(self) -> None:
        f = self.f
        f.__code__, f.__defaults__, f.__kwdefaults__ = self.saved
        for n in self.names:
            f.__globals__.pop(n, None)
        if self.cache is not None:
            self.cache.cache_clear()


def knock_out(spec: str) -> Patch:
    """Switch on ``MODULE:QUALNAME:VARIANT``; returns the Patch (``.undo()`` to restore)."""
    module_name, qualname, variant = spec.rsplit(":", 2)
    if variant not in VARIANTS:
        raise ValueError(f"unknown variant {variant!r} (one of {', '.join(VARIANTS)})")
    f, cache = function_of(module_name, qualname)
    if variant == "skip":
        return Patch(f, skip=True, cache=cache)
    return Patch(f, perturber(variant), cache=cache)


# -- recording what each target returns and who calls it ----------------------------------------

class Recorder:
    def __init__(self):
        self.context = "<configure>"
        self.seen: dict = {}
        self.patches = []
        self.unpatchable: dict = {}

    def wrap_all(self) -> None:
        for m in reference_modules():
            for qualname, how in targets_of(m):
                key = f"{m}:{qualname}"
                try:
                    f, cache = function_of(m, qualname)
                    self.patches.append(Patch(f, self._recorder(key), cache=cache))
                except NotApplicable as e:
                    self.unpatchable[key] = str(e)

    def _recorder(self, key):
        def record(r):
            entry = self.seen.setdefault(key, {"kinds": {}, "tests": {}})
            k = kind(r)
            entry["kinds"][k] = entry["kinds"].get(k, 0) + 1
            entry["tests"][self.context] = entry["tests"].get(self.context, 0) + 1
            return r
        return record

    def write(self, path: str) -> None:
        out = {"seen": {k: {"kinds": v["kinds"], "tests": sorted(v["tests"])}
                        for k, v in sorted(self.seen.items())},
               "unpatchable": self.unpatchable}
        with open(path, "w") as fh:
            json.dump(out, fh, indent=1, sort_keys=True)


_STATE: dict = {}


def pytest_configure(config):
    spec = os.environ.get(ENV)
    if spec:
        _STATE["patch"] = knock_out(spec)
    if os.environ.get(RECORD_ENV):
        rec = Recorder()
        rec.wrap_all()
        _STATE["recorder"] = rec


def pytest_collectstart(collector):
    rec = _STATE.get("recorder")
    if rec is not None and getattr(collector, "path", None) is not None \
            and collector.path.suffix == ".py":
        rec.context = "collect:" + collector.nodeid


def pytest_runtest_logstart(nodeid, location):
    rec = _STATE.get("recorder")
    if rec is not None:
        rec.context = nodeid


def pytest_sessionfinish(session, exitstatus):
    path = os.environ.get(STATS_ENV)
    if path and "patch" in _STATE:
        with open(path, "w") as fh:
            json.dump(STATS, fh)
    rec = _STATE.get("recorder")
    if rec is not None:
        rec.write(os.environ[RECORD_ENV])
