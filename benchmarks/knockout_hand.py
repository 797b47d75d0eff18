"""Hand-written wrong versions of the reference functions no generic knockout fits (issue 44).

benchmarks/knockout_plugin.py makes generic wrong versions from a function's *result*
(a number + 1/3, a tuple's last element changed, ...); twelve public functions got none:
four no reference test called, seven return what no generic rule changes (a string, an
exception, a context manager, FaceData, a scipy matrix) and one is a generator function.
Here each gets 1-3 realistic mistakes written by hand, one line of its meaning wrong (a
strict inequality for a non-strict one, a sign flipped, a digit dropped, the previous
value not restored, ...), registered in ``HAND_WRITTEN`` under ``MODULE:QUALNAME:NAME``.

A wrong version is ``wrong(orig, *args, **kwargs)``: ``orig`` is a copy of the original
function, the arguments are the call's; it returns the wrong result and calls
:func:`changed` when that result differs from the right one (the stats tell a survivor
never switched on from one the tests do not see).  The plugin switches one on with
``DDG_KNOCKOUT_HAND=MODULE:QUALNAME:NAME`` (the function object's ``__code__`` replaced,
as for the generic ones, so ``from .module import name`` sees it; a generator function
too: its code becomes a plain function's that returns the wrong generator).

``python -m benchmarks.knockout_hand [NAME ...] [--timeout 180] [--record PATH]
[--as KEY] [--list]``: each wrong version (NAME: a full name or a prefix such as
``curvature:vertex_type``), screened with ``-x`` on the reference test files that call
the function (a recording run, or ``--record`` reusing one; for a function the recorder
cannot wrap, the files naming it), survivors run again on all of them
(benchmarks/knockout.py's ``reference_tests()``, tests/test_knockouts.py included).
Results go to docs/perf/knockout_hand.json under KEY (default ``latest``; the measure
of docs/knockout.md is stored under ``before`` and ``after``, left alone by other keys).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import time
from collections.abc import Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from fractions import Fraction
from typing import Callable

from . import knockout_plugin
from .knockout_plugin import HAND_ENV, PACKAGE, STATS, Patch, function_of

# -- the table -------------------------------------------------------------------------------


@dataclass(frozen=True)
class Hand:
    target: str           # MODULE:QUALNAME, MODULE short (``curvature``, ``exact.surds``)
    name: str
    wrong: Callable
    doc: str              # one line: the mistake

    @property
    def key(self) -> str:
        return f"{self.target}:{self.name}"

    def call(self, orig, *args, **kwargs):
        STATS["calls"] += 1
        return self.wrong(orig, *args, **kwargs)


HAND_WRITTEN: dict[str, Hand] = {}


def hand(target: str, name: str):
    def register(f):
        doc = (f.__doc__ or "").strip().splitlines()[0]
        h = Hand(target, name, f, doc)
        HAND_WRITTEN[h.key] = h
        return f
    return register


def changed() -> None:
    """The wrong version's result differs from the right one on this call."""
    STATS["changed"] += 1


def _note(right, wrong):
    if wrong != right:
        changed()
    return wrong


# -- geodesics.root_sum_at_least ------------------------------------------------------------------

@hand("geodesics:root_sum_at_least", "strict")
def _root_sum_strict(orig, a, b, c):
    """strict inequalities (s < 0 or s^2 < 4bc): equality counted as violating."""
    a, b, c = Fraction(a), Fraction(b), Fraction(c)
    s = a - b - c
    return _note(orig(a, b, c), s < 0 or s * s < 4 * b * c)


@hand("geodesics:root_sum_at_least", "no_sign_test")
def _root_sum_no_sign(orig, a, b, c):
    """squares a - b - c without first testing its sign: (a - b - c)^2 <= 4bc only."""
    a, b, c = Fraction(a), Fraction(b), Fraction(c)
    s = a - b - c
    return _note(orig(a, b, c), s * s <= 4 * b * c)


@hand("geodesics:root_sum_at_least", "two_bc")
def _root_sum_two_bc(orig, a, b, c):
    """(sqrt b + sqrt c)^2 expanded with 2 sqrt(bc) squared to 2bc: s^2 <= 2bc."""
    a, b, c = Fraction(a), Fraction(b), Fraction(c)
    s = a - b - c
    return _note(orig(a, b, c), s <= 0 or s * s <= 2 * b * c)


# -- metric.PiecewiseFlatSurface.from_lengths -----------------------------------------------------

def _lengths_list(lengths):
    from ddg_oracle.reference.errors import BadShape
    if hasattr(lengths, "tolist"):
        lengths = lengths.tolist()
    if isinstance(lengths, (str, bytes)) or not isinstance(lengths, Sequence):
        raise BadShape(f"lengths must be a sequence, one per edge, got {type(lengths).__name__}")
    return lengths


def _positive(ls):
    from ddg_oracle.reference.errors import TriangleInequalityViolated
    for e, x in enumerate(ls):
        if x <= 0:
            raise TriangleInequalityViolated(f"edge {e} has length {x} <= 0")


def _same_surface(a, b) -> bool:
    return a.squared_lengths == b.squared_lengths


@hand("metric:PiecewiseFlatSurface.from_lengths", "as_squared")
def _from_lengths_as_squared(orig, cls, triangulation, lengths):
    """the lengths taken as squared lengths (not squared)."""
    from ddg_oracle.reference.exact.rationals import rational
    ls = [rational(x, where=f"length of edge {e}")
          for e, x in enumerate(_lengths_list(lengths))]
    _positive(ls)
    out = cls(triangulation, ls)
    if any(x != 1 for x in ls):
        changed()
    return out


@hand("metric:PiecewiseFlatSurface.from_lengths", "sign_unchecked")
def _from_lengths_sign_unchecked(orig, cls, triangulation, lengths):
    """no check that each length is > 0: a negative length is squared into a valid one."""
    from ddg_oracle.reference.exact.rationals import rational
    ls = [rational(x, where=f"length of edge {e}")
          for e, x in enumerate(_lengths_list(lengths))]
    if any(x <= 0 for x in ls):
        changed()
    return cls(triangulation, [x * x for x in ls])


@hand("metric:PiecewiseFlatSurface.from_lengths", "float_squared")
def _from_lengths_float_squared(orig, cls, triangulation, lengths):
    """each length squared before it is taken exactly (x * x of a float, rounded)."""
    from ddg_oracle.reference.exact.rationals import rational
    raw = _lengths_list(lengths)
    ls = [rational(x, where=f"length of edge {e}") for e, x in enumerate(raw)]
    _positive(ls)
    sq = [rational(x * x, where=f"length of edge {e}") for e, x in enumerate(raw)]
    if sq != [x * x for x in ls]:
        changed()
    return cls(triangulation, sq)


# -- planar.is_lifted_hull_facet ------------------------------------------------------------------

def _lifted_sides(points, i, j, k, pole=True):
    from ddg_oracle.reference.planar import NORTH_POLE, as_point_set, stereographic_lift
    from ddg_oracle.reference.polyhedral import orientation3d
    pts = as_point_set(points)
    lifted = [stereographic_lift(p) for p in pts] + ([NORTH_POLE] if pole else [])
    a, b, c = lifted[i], lifted[j], lifted[k]
    return {orientation3d(a, b, c, d) for n, d in enumerate(lifted) if n not in (i, j, k)}


@hand("planar:is_lifted_hull_facet", "one_side")
def _hull_facet_one_side(orig, points, i, j, k):
    """the side fixed for a counterclockwise triangle: no lifted point on side -1."""
    return _note(orig(points, i, j, k), -1 not in _lifted_sides(points, i, j, k))


@hand("planar:is_lifted_hull_facet", "no_pole")
def _hull_facet_no_pole(orig, points, i, j, k):
    """the north pole left out of the hull (the lifted points only)."""
    sides = _lifted_sides(points, i, j, k, pole=False)
    return _note(orig(points, i, j, k), not (1 in sides and -1 in sides))


@hand("planar:is_lifted_hull_facet", "open_side")
def _hull_facet_open_side(orig, points, i, j, k):
    """open sides: a coplanar lifted point (a cocircular planar one) counted against."""
    sides = _lifted_sides(points, i, j, k)
    return _note(orig(points, i, j, k), sides == {1} or sides == {-1})


# -- sparse.SparseMatrix.diagonal -----------------------------------------------------------------

@hand("sparse:SparseMatrix.diagonal", "not_exact")
def _diagonal_not_exact(orig, cls, values):
    """the values stored as given, not made exact (a float stays a float)."""
    n = len(values)
    out = cls((n, n), {i: {i: v} for i, v in enumerate(values)})
    if any(isinstance(v, float) for v in values):
        changed()
    return out


@hand("sparse:SparseMatrix.diagonal", "antidiagonal")
def _diagonal_antidiagonal(orig, cls, values):
    """value i put at (i, n - 1 - i): the anti-diagonal."""
    from ddg_oracle.reference.sparse import exact_number
    n = len(values)
    return _note(orig(cls, values),
                 cls((n, n), {i: {n - 1 - i: exact_number(v)} for i, v in enumerate(values)}))


@hand("sparse:SparseMatrix.diagonal", "zeros_first")
def _diagonal_zeros_first(orig, cls, values):
    """the zero values dropped before numbering: later values move up the diagonal."""
    from ddg_oracle.reference.sparse import exact_number
    n = len(values)
    vals = [exact_number(v) for v in values if v]
    return _note(orig(cls, values), cls((n, n), {i: {i: v} for i, v in enumerate(vals)}))


# -- metric.degenerate_face ------------------------------------------------------------------------

@hand("metric:degenerate_face", "wrong_edge")
def _degenerate_wrong_edge(orig, t, f, positions=None):
    """two coincident corners found, the next halfedge's edge named (the wrong corner)."""
    from ddg_oracle.reference.errors import DegenerateFace
    if positions is not None:
        for c in range(3):
            i, j = t.edge_vertices(t.edge_of(3 * f + c))
            if positions[i] == positions[j]:
                e = t.edge_of(3 * f + (c + 1) % 3)
                if e != t.edge_of(3 * f + c):
                    changed()
                return DegenerateFace(f"edge {e} between vertices {i} and {j} has length zero "
                                      "(coincident vertices); its faces have zero area")
    return orig(t, f, positions)


@hand("metric:degenerate_face", "positions_ignored")
def _degenerate_positions_ignored(orig, t, f, positions=None):
    """positions ignored: always the collinear message, never the coincident edge."""
    out = orig(t, f)
    if str(out) != str(orig(t, f, positions)):
        changed()
    return out


@hand("metric:degenerate_face", "wrong_class")
def _degenerate_wrong_class(orig, t, f, positions=None):
    """a TriangleInequalityViolated (zero area: a degenerate triangle inequality)."""
    from ddg_oracle.reference.errors import TriangleInequalityViolated
    changed()
    return TriangleInequalityViolated(str(orig(t, f, positions)))


# -- cotangents.face_data -------------------------------------------------------------------------

@hand("cotangents:face_data", "cot_swapped")
def _face_data_cot_swapped(orig, surface):
    """per face the cotangent numerators N_2 and N_0 swapped (halfedges 3f, 3f + 1)."""
    from ddg_oracle.reference.cotangents import FaceData
    fd = orig(surface)
    N = list(fd.N)
    N[0::3], N[1::3] = fd.N[1::3], fd.N[0::3]
    if N != list(fd.N):
        changed()
    return FaceData(list(fd.G), list(fd.S), N)


@hand("cotangents:face_data", "area_doubled")
def _face_data_area_doubled(orig, surface):
    """G = 64 area^2 S^2 (16 (2 area)^2: the R^3 route's 4 area^2 convention mixed up)."""
    from ddg_oracle.reference.cotangents import FaceData
    fd = orig(surface)
    if fd.G:
        changed()
    return FaceData([4 * g for g in fd.G], list(fd.S), list(fd.N))


@hand("cotangents:face_data", "scale_dropped")
def _face_data_scale_dropped(orig, surface):
    """the scales S[f] forgotten (all 1): G / S^2 no longer the face's own radicand."""
    from ddg_oracle.reference.cotangents import FaceData
    fd = orig(surface)
    if any(s != 1 for s in fd.S):
        changed()
    return FaceData(list(fd.G), [1] * len(fd.S), list(fd.N))


# -- exact.surds.limits ---------------------------------------------------------------------------

_DEFAULT_TERM_LIMIT = 4096


@hand("exact.surds:limits", "restores_default")
def _limits_restores_default(orig, term_limit=None):
    """on exit the default (4096) put back, not the value before: nesting breaks."""
    from ddg_oracle.reference.exact.surds import _check_limit, settings

    @contextmanager
    def cm():
        old = settings.term_limit
        if term_limit is not None:
            settings.term_limit = _check_limit(term_limit, "term_limit")
        try:
            yield settings
        finally:
            if old != _DEFAULT_TERM_LIMIT:
                changed()
            settings.term_limit = _DEFAULT_TERM_LIMIT
    return cm()


@hand("exact.surds:limits", "no_finally")
def _limits_no_finally(orig, term_limit=None):
    """the old value restored after the block only when it ends normally (no finally)."""
    from ddg_oracle.reference.exact.surds import _check_limit, settings

    @contextmanager
    def cm():
        old = settings.term_limit
        if term_limit is not None:
            settings.term_limit = _check_limit(term_limit, "term_limit")
        try:
            yield settings
        except BaseException:
            if settings.term_limit != old:
                changed()
            raise
        settings.term_limit = old
    return cm()


@hand("exact.surds:limits", "none_resets")
def _limits_none_resets(orig, term_limit=None):
    """``None`` sets the default (4096) instead of keeping the current value."""
    from ddg_oracle.reference.exact.surds import _check_limit, settings

    @contextmanager
    def cm():
        old = settings.term_limit
        if term_limit is None and old != _DEFAULT_TERM_LIMIT:
            changed()
        settings.term_limit = _check_limit(
            _DEFAULT_TERM_LIMIT if term_limit is None else term_limit, "term_limit")
        try:
            yield settings
        finally:
            settings.term_limit = old
    return cm()


# -- sparse.SparseMatrix.to_scipy -----------------------------------------------------------------

def _csr_differs(a, b) -> bool:
    if a.shape != b.shape or a.nnz != b.nnz:
        return True
    x, y = a.tocoo(), b.tocoo()
    return sorted(zip(x.row.tolist(), x.col.tolist(), x.data.tolist())) != \
        sorted(zip(y.row.tolist(), y.col.tolist(), y.data.tolist()))


@hand("sparse:SparseMatrix.to_scipy", "transposed")
def _to_scipy_transposed(orig, self):
    """rows and columns exchanged: the transpose (shape reversed)."""
    import scipy.sparse
    rows, cols, vals = [], [], []
    for i, j, v in self.entries():
        rows.append(i)
        cols.append(j)
        vals.append(float(v))
    n, m = self.shape
    out = scipy.sparse.csr_matrix((vals, (cols, rows)), shape=(m, n), dtype=float)
    if _csr_differs(out, orig(self)):
        changed()
    return out


@hand("sparse:SparseMatrix.to_scipy", "underflow_dropped")
def _to_scipy_underflow_dropped(orig, self):
    """entries whose float is 0.0 (underflow) left out instead of kept as explicit zeros."""
    import scipy.sparse
    rows, cols, vals = [], [], []
    for i, j, v in self.entries():
        if float(v) != 0.0:
            rows.append(i)
            cols.append(j)
            vals.append(float(v))
    out = scipy.sparse.csr_matrix((vals, (rows, cols)), shape=self.shape, dtype=float)
    if _csr_differs(out, orig(self)):
        changed()
    return out


def _ratio(v) -> float:
    if isinstance(v, Fraction):
        return float(v.numerator) / float(v.denominator)
    return float(v)


@hand("sparse:SparseMatrix.to_scipy", "ratio_of_floats")
def _to_scipy_ratio_of_floats(orig, self):
    """a Fraction entry as float(numerator) / float(denominator): rounded twice."""
    import scipy.sparse
    rows, cols, vals = [], [], []
    for i, j, v in self.entries():
        rows.append(i)
        cols.append(j)
        vals.append(_ratio(v))
    out = scipy.sparse.csr_matrix((vals, (rows, cols)), shape=self.shape, dtype=float)
    if _csr_differs(out, orig(self)):
        changed()
    return out


# -- combinatorics.Classification.name ------------------------------------------------------------

_SPECIAL = {(True, 0, 0): "sphere", (True, 0, 1): "disk", (True, 0, 2): "annulus",
            (True, 1, 0): "torus", (False, 1, 0): "projective plane",
            (False, 2, 0): "Klein bottle", (False, 1, 1): "Möbius strip"}


def _name(c, special=_SPECIAL, orientable=("orientable", "non-orientable"),
          plural=lambda k: k > 1):
    g, k = c.genus, c.boundary_components
    key = (c.orientable, g, k)
    if key in special:
        return special[key]
    base = f"{orientable[0] if c.orientable else orientable[1]} genus {g}"
    if k:
        base += f", {k} boundary loop{'s' if plural(k) else ''}"
    return base


@hand("combinatorics:Classification.name", "orientability_swapped")
def _name_orientability_swapped(orig, self):
    """the general name says non-orientable for an orientable surface and vice versa."""
    return _note(orig(self), _name(self, orientable=("non-orientable", "orientable")))


@hand("combinatorics:Classification.name", "plural_one")
def _name_plural_one(orig, self):
    """"1 boundary loops": the plural from one loop on."""
    return _note(orig(self), _name(self, plural=lambda k: k >= 1))


@hand("combinatorics:Classification.name", "crosscaps_swapped")
def _name_crosscaps_swapped(orig, self):
    """one and two crosscaps confused: projective plane and Klein bottle swapped."""
    special = dict(_SPECIAL)
    special[(False, 1, 0)], special[(False, 2, 0)] = "Klein bottle", "projective plane"
    return _note(orig(self), _name(self, special=special))


# -- curvature.vertex_type ------------------------------------------------------------------------

@hand("curvature:vertex_type", "sign_reversed")
def _vertex_type_sign_reversed(orig, surface, v):
    """K's sign read the wrong way (angle sum - 2 pi): elliptic and hyperbolic swapped."""
    r = orig(surface, v)
    return _note(r, {"elliptic": "hyperbolic", "hyperbolic": "elliptic"}.get(r, r))


@hand("curvature:vertex_type", "saddle_flat")
def _vertex_type_saddle_flat(orig, surface, v):
    """only K > 0 told apart: a saddle (K < 0) reported "flat"."""
    r = orig(surface, v)
    return _note(r, "flat" if r == "hyperbolic" else r)


@hand("curvature:vertex_type", "float_tolerance")
def _vertex_type_float_tolerance(orig, surface, v):
    """K decided in floats with a tolerance: |K| <= 1e-9 reported "flat"."""
    from ddg_oracle.reference.errors import InputError
    from ddg_oracle.reference.metric import as_metric
    m = as_metric(surface)
    t = m.triangulation
    if t.is_boundary_vertex(v):
        raise InputError(f"vertex {v} is a boundary vertex: its curvature is a turning angle "
                         "(R2.4), it has no elliptic / flat / hyperbolic type")
    k = 2 * math.pi - sum(float(m.corner_angle(f, c)) for f, c in t.corners_around(v))
    wrong = "flat" if abs(k) <= 1e-9 else "elliptic" if k > 0 else "hyperbolic"
    return _note(orig(surface, v), wrong)


# -- exact.arccots.ArccotSum.decimal --------------------------------------------------------------

def _decimal(self, digits, q, width):
    sign = "-" if q < 0 else ""
    s = str(abs(q)).rjust(width, "0")
    return f"{sign}{s[:-digits]}.{s[-digits:]}" if digits else f"{sign}{s}"


@hand("exact.arccots:ArccotSum.decimal", "truncated")
def _decimal_truncated(orig, self, digits=30):
    """the midpoint truncated toward zero instead of rounded."""
    lo, hi = self.enclosure(digits + 2)
    q = int((lo + hi) / 2 * 10 ** digits)
    return _note(orig(self, digits), _decimal(self, digits, q, digits + 1))


@hand("exact.arccots:ArccotSum.decimal", "short_pad")
def _decimal_short_pad(orig, self, digits=30):
    """padded to ``digits`` characters, not digits + 1: no leading 0 below 1 (".5")."""
    lo, hi = self.enclosure(digits + 2)
    q = round((lo + hi) / 2 * 10 ** digits)
    return _note(orig(self, digits), _decimal(self, digits, q, digits))


@hand("exact.arccots:ArccotSum.decimal", "half_up")
def _decimal_half_up(orig, self, digits=30):
    """rounded as int(x + 1/2): right for x >= 0, one unit off (toward 0) for most x < 0."""
    lo, hi = self.enclosure(digits + 2)
    q = int((lo + hi) / 2 * 10 ** digits + Fraction(1, 2))
    return _note(orig(self, digits), _decimal(self, digits, q, digits + 1))


# -- triangulations.cube_belt_twist ---------------------------------------------------------------

def _belt(flips, *, refuse_zero=False, rung=None, missing=0):
    from ddg_oracle.reference.intrinsic import IntrinsicTriangulation
    from ddg_oracle.reference.surfaces import cube
    from ddg_oracle.reference.triangulations import _heights, _twist_rung
    if flips < 0 or (refuse_zero and flips == 0):
        raise ValueError(f"flips must be >= 0, got {flips}")
    z = _heights()
    w = IntrinsicTriangulation(cube().metric())
    yield w.surface()
    for _ in range(flips - missing):
        w.flip((rung or _twist_rung)(w, z))
        yield w.surface()


def _either_side_rung(w, z) -> int:
    """The first rung between a bottom-based and a top-based triangle, on either side."""
    from ddg_oracle.reference.combinatorics import face_of
    from ddg_oracle.reference.triangulations import _twist_rung
    e = _first_mixed_rung(w, z, face_of)
    if e != _twist_rung(w, z):
        changed()
    return e


def _first_mixed_rung(w, z, face_of) -> int:
    t = w.triangulation

    def bottom_corners(f):
        return sum(z[v] == 0 for v in t.faces[f])

    for e in range(t.n_edges):
        h, g = t.edge_halfedges(e)
        if {z[t.tail(h)], z[t.head(h)]} != {0, 1}:
            continue
        if {bottom_corners(face_of(h)), bottom_corners(face_of(g))} == {1, 2}:
            return e
    raise AssertionError("no rung between a bottom and a top triangle")


@hand("triangulations:cube_belt_twist", "one_fewer")
def _belt_one_fewer(orig, flips):
    """range(flips - 1): one flip fewer, ``flips`` triangulations instead of flips + 1."""
    if flips > 0:
        changed()
    return _belt(flips, missing=1)


@hand("triangulations:cube_belt_twist", "zero_refused")
def _belt_zero_refused(orig, flips):
    """flips <= 0 refused: no sequence of the cube alone for flips = 0."""
    if flips == 0:
        changed()
    return _belt(flips, refuse_zero=True)


@hand("triangulations:cube_belt_twist", "either_side")
def _belt_either_side(orig, flips):
    """the rung to flip chosen without looking at which side its bottom triangle is on."""
    return _belt(flips, rung=_either_side_rung)


# -- switching one on in a pytest run --------------------------------------------------------------


def knock_out_by_hand(key: str) -> Patch:
    """Switch on the hand-written wrong version ``MODULE:QUALNAME:NAME`` (MODULE short, as
    ``curvature`` or ``exact.surds``); returns the Patch (``.undo()`` to restore)."""
    if key not in HAND_WRITTEN:
        raise ValueError(f"no hand-written wrong version {key!r} (one of "
                         f"{', '.join(HAND_WRITTEN)})")
    h = HAND_WRITTEN[key]
    module, qualname = h.target.split(":")
    f, cache = function_of(f"{PACKAGE}.{module}", qualname)
    return Patch(f, cache=cache, replace=h.call)


def pytest_configure(config):
    """Loaded with ``-p benchmarks.knockout_hand`` beside the knockout plugin (a pytest
    plugin of its own, so that the plugin never imports this module and the runner below
    may import benchmarks/knockout.py without a cycle): ``DDG_KNOCKOUT_HAND`` switches one
    on, and the knockout plugin writes its stats at the end."""
    key = os.environ.get(HAND_ENV)
    if key:
        knockout_plugin._STATE["patch"] = knock_out_by_hand(key)


# -- running them -------------------------------------------------------------------------------


def selected(names) -> list[Hand]:
    if not names:
        return list(HAND_WRITTEN.values())
    out = [h for h in HAND_WRITTEN.values() if any(h.key == n or h.key.startswith(n + ":")
                                                    or h.target == n for n in names)]
    missing = [n for n in names if not any(h.key == n or h.key.startswith(n + ":")
                                            or h.target == n for h in out)]
    if missing:
        raise SystemExit(f"no hand-written wrong version named {', '.join(missing)}")
    return out


def callers(h: Hand, rec: dict | None, files: list[str]) -> list[str]:
    """The test files calling ``h``'s function (the recording run's, most calls first), or
    for a function the recorder could not wrap, the files that name it."""
    from .common import ROOT
    from .knockout import caller_files
    seen = (rec or {}).get("seen", {}).get(f"{PACKAGE}.{h.target}")
    if seen:
        return caller_files(seen["tests"], files)
    name = h.target.rsplit(":", 1)[1].rsplit(".", 1)[-1]
    word = re.compile(rf"\b{re.escape(name)}\b")
    out = [f for f in files if word.search((ROOT / f).read_text())]
    if "tests/test_doctests.py" in files and "tests/test_doctests.py" not in out:
        out.append("tests/test_doctests.py")            # the reference's docstring examples
    return out


def run(hands: list[Hand], timeout: float, rec: dict | None) -> list[dict]:
    from .knockout import reference_tests, run_knockout
    from .common import say
    files = reference_tests()
    out = []
    t0 = time.monotonic()
    for n, h in enumerate(hands, 1):
        first = callers(h, rec, files)
        r = {"key": h.key, "doc": h.doc, "files": first}
        res = r["screen"] = run_knockout(h.key, first or files, timeout, hand=True)
        if res["status"] == "survived" and set(first) != set(files):
            ordered = first + [f for f in files if f not in first]
            res = r["confirm"] = run_knockout(h.key, ordered, timeout, hand=True)
        r.update(status=res["status"], by=res["by"], calls=res.get("calls"),
                 changed=res.get("changed"))
        out.append(r)
        say(f"  [{n}/{len(hands)} {time.monotonic() - t0:5.0f} s] {r['status']:8} {h.key} "
            f"({res['seconds']} s; calls {r['calls']}, changed {r['changed']}) {r['by'][:100]}")
    return out


def main(argv=None) -> None:
    from .common import ROOT, machine
    from .knockout import record, reference_tests
    p = argparse.ArgumentParser(prog="python -m benchmarks.knockout_hand",
                                description=__doc__.split("\n\n")[0])
    p.add_argument("names", nargs="*", help="MODULE:QUALNAME[:NAME] (default: all)")
    p.add_argument("--timeout", type=float, default=180.0)
    p.add_argument("--record", type=str, default=None,
                   help="reuse a recording run's JSON (else one is made, then written here)")
    p.add_argument("--out", type=str, default=str(ROOT / "docs" / "perf" / "knockout_hand.json"))
    p.add_argument("--as", dest="key", default="latest",
                   help="the key of the results in --out (the others are kept)")
    p.add_argument("--list", action="store_true", help="list the wrong versions and stop")
    a = p.parse_args(argv)
    hands = selected(a.names)
    if a.list:
        for h in hands:
            print(f"{h.key}: {h.doc}")
        return
    rec = None
    if a.record:
        try:
            with open(a.record) as fh:
                rec = json.load(fh)
        except FileNotFoundError:
            rec = None
    if rec is None:
        rec = record(reference_tests())
        if a.record:
            with open(a.record, "w") as fh:
                json.dump(rec, fh, indent=1)
    where = machine()                      # commit, date (UTC), load at the start
    t0 = time.monotonic()
    results = run(hands, a.timeout, rec)
    try:
        with open(a.out) as fh:
            stored = json.load(fh)
    except FileNotFoundError:
        stored = {}
    stored[a.key] = {**where, "timeout": a.timeout, "recording_seconds": rec.get("seconds"),
                     "seconds": round(time.monotonic() - t0), "runs": results}
    with open(a.out, "w") as fh:
        json.dump(stored, fh, indent=1, ensure_ascii=False)
        fh.write("\n")


if __name__ == "__main__":
    main()
