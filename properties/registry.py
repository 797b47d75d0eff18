"""Properties: one per catalog row, named by its ID, runnable on any implementation.

A :class:`Property` couples a Hypothesis strategy of examples with a check
``check(impl, example)`` that raises :class:`PropertyFailure` naming the catalog
ID, the implementation, the (shrunk) mesh, the offending element and the
expected vs observed values (and, where the property derived one, the error
bound the observed error is measured against).

A property that compares a *decision* (a sign, a predicate) raises
:class:`TieDisagreement` instead when the exact reference decides an exact tie
(a cotan weight exactly 0, an exactly flat vertex) and the implementation
decides it the other way by no more than its own rounding: the runner reports
that separately from a real error and lets the run go on.
"""

from __future__ import annotations

import contextlib
import contextvars
import functools
import math
import numbers
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from .arithmetic import own_arithmetic
from .profiles import example_time_limit
from ..protocol.methods import at_machine_epsilon, implementation_name, machine_epsilon


class PropertyFailure(AssertionError):
    """A property does not hold for an implementation on an example.

    ``bound`` is the derived bound on |observed - expected| the property
    tested against, when it compares a number; :attr:`error` and
    :attr:`error_in_bounds` are then filled in.
    """

    kind = ""                           # prefix of the message (see TieDisagreement)

    def __init__(self, property_id: str, impl, message: str, *, mesh=None,
                 element=None, expected=None, observed=None, bound=None):
        self.property_id = property_id
        self.implementation = implementation_name(impl)
        self.message = message
        self.mesh = mesh                # (V, F) as nested lists, when there is one
        self.element = element
        self.expected = expected
        self.observed = observed
        self.bound = None if bound is None else float(bound)
        super().__init__(str(self))

    def __reduce__(self):
        # picklable (worker processes send failures back): rebuilt from the fields,
        # not from Exception.args
        return _restore, (type(self), self.__dict__.copy())

    @property
    def error(self) -> float | None:
        """|observed - expected| when both are real numbers, else None."""
        if _is_real(self.expected) and _is_real(self.observed):
            try:
                return abs(float(self.observed) - float(self.expected))
            except OverflowError:       # an answer beyond the float range (chi = 10**400)
                return math.inf
        return None

    @property
    def error_in_bounds(self) -> float | None:
        """:attr:`error` / :attr:`bound`, when both are known (inf for a zero bound)."""
        err = self.error
        if err is None or self.bound is None:
            return None
        if self.bound > 0:
            return err / self.bound
        return float("inf") if err > 0 else 0.0

    def __str__(self) -> str:
        lines = [f"[{self.property_id}] {self.implementation}: {self.kind}{self.message}"]
        if self.element is not None:
            lines.append(f"  at: {self.element}")
        if self.expected is not None or self.observed is not None:
            lines.append(f"  expected: {self.expected!r}")
            lines.append(f"  observed: {self.observed!r}")
        ratio = self.error_in_bounds
        if ratio is not None:
            lines.append(f"  error: {self.error:.3g} = {ratio:.3g} x the derived bound "
                         f"{self.bound:.3g}")
        if self.mesh is not None:
            V, F = self.mesh
            lines.append(f"  mesh: {len(V)} vertices, {len(F)} faces; F = {faces_text(F)}")
        return "\n".join(lines)


def faces_text(F, limit: int = 40) -> str:
    """The face list as text, cut after ``limit`` faces (a mesh file may have thousands)."""
    F = [list(f) for f in F]
    if len(F) <= limit:
        return str(F)
    return str(F[:limit])[:-1] + f", ... ({len(F) - limit} more)]"


class TieDisagreement(PropertyFailure):
    """The exact reference decides an exact tie; the implementation decides it otherwise,
    within its own rounding (``bound``).  Not an error of the implementation: floats
    cannot see exact ties.  Raise it only after every element was checked for a real
    failure, so a tie never hides one."""

    kind = "tie disagreement: "


class Unjudged:
    """Entries a check compared against an infinite derived bound (a face whose float normal
    is 0, an area whose lower bound is not positive, ...) where the implementation's answer
    differs from the exact float view: the check cannot say whether that answer is right at
    this precision, so the entry is not judged (neither passed nor failed).  The runner
    opens one tally per example (:func:`unjudged_entries`) and reports the examples that
    had such entries; :func:`~.harness.ratios` counts them."""

    def __init__(self):
        self.entries = 0
        self.judged = 0                 # entries compared against a finite bound (or equal)


_UNJUDGED: contextvars.ContextVar = contextvars.ContextVar("ddg_unjudged", default=None)


@contextlib.contextmanager
def unjudged_entries():
    """A fresh :class:`Unjudged` tally for the checks run inside this block."""
    tally = Unjudged()
    token = _UNJUDGED.set(tally)
    try:
        yield tally
    finally:
        _UNJUDGED.reset(token)


def count_unjudged(k: int, judged: int = 0) -> None:
    """Add ``k`` unjudged entries (and ``judged`` judged ones) to the tally open now, if any."""
    tally = _UNJUDGED.get()
    if tally is not None:
        tally.entries += int(k)
        tally.judged += int(judged)


def judgeable(err, bound) -> tuple[np.ndarray, np.ndarray]:
    """(err, bound) as float arrays, a NaN bound made infinite: 0/0 of a quantity below
    the float range's resolution (a triangle of side 1e-300) decides nothing, as an
    infinite bound; read as a number it failed the exact answer itself ("error 0 = 0 x the
    derived bound nan").  The entries it leaves undecided are counted
    (:func:`count_unjudged`), the others counted judged."""
    e, b = np.asarray(err, dtype=np.float64), np.asarray(bound, dtype=np.float64)
    b = np.where(np.isnan(b), np.inf, b)
    open_ = np.isposinf(b) & (e != 0)
    count_unjudged(np.count_nonzero(open_), open_.size - np.count_nonzero(open_))
    return e, b


def within(err, bound):
    """``err <= bound`` (elementwise for arrays: a bool array), with the entries whose bound
    is infinite (or NaN: :func:`judgeable`) and whose error is not 0 counted unjudged: an
    infinite bound passes them, and the runner says so.  A NaN error is never within."""
    e, b = judgeable(err, bound)
    ok = e <= b
    return bool(ok) if ok.ndim == 0 else ok


def _sure(observed, lo, hi, bound):
    """(observed, bound, sure, known, e_lo) as arrays: ``sure`` where the comparison of
    :func:`first_outside` holds at both ends of [lo, hi] (an infinite bound: where the
    value is known, lo == hi, and the error is not NaN, "never within")."""
    o = np.asarray(observed, dtype=np.float64)
    b = np.asarray(bound, dtype=np.float64)
    b = np.where(np.isnan(b), np.inf, b)
    with np.errstate(invalid="ignore", over="ignore"):
        e_lo, e_hi = np.abs(o - lo), np.abs(o - hi)
        known = lo == hi
        sure = np.where(np.isinf(b), known & ~np.isnan(e_lo), (e_lo <= b) & (e_hi <= b))
    return o, b, sure, known, e_lo


def _count_sure(sure, b, e_lo) -> None:
    """Count the sure entries as :func:`within` would have (an infinite bound and an error
    other than 0: unjudged)."""
    open_ = sure & np.isinf(b) & (e_lo != 0)
    count_unjudged(np.count_nonzero(open_), np.count_nonzero(sure) - np.count_nonzero(open_))


def first_outside(observed, lo, hi, bound, exact_at):
    """``within(|observed[n] - x[n]|, bound[n])`` for every n in order, where x[n] is the
    correctly rounded exact value known only to lie in [lo[n], hi[n]] (an enclosure's
    :func:`~.enclosures.rounding_bounds`): the first n where it fails and its x[n], or
    None.  The rounded |o - x| is monotone in x on each side of o, so where it holds at lo
    and at hi it holds at x; where lo == hi, x is known; the other entries ask
    ``exact_at(n)`` for x[n], in order.  The verdict, the failing entry and the tally of
    unjudged entries are those of the loop over the exact values."""
    o, b, sure, known, e_lo = _sure(observed, lo, hi, bound)
    stop = len(o)
    found = None
    for n in np.flatnonzero(~sure).tolist():
        x = float(lo[n]) if known[n] else float(exact_at(n))
        if not within(abs(float(o[n]) - x), float(b[n])):        # counts this entry
            stop, found = n, (n, x)
            break
    _count_sure(sure[:stop], b[:stop], e_lo[:stop])  # the sure ones before the stop
    return found


def within_enclosed(observed, lo, hi, bound, exact_at):
    """``(within(|observed - x|, bound), x)`` over whole arrays, x the correctly rounded
    exact values known to lie in [lo, hi] (as :func:`first_outside`): ``exact_at(index)``
    gives x at the (flat) indices the ends cannot decide; x is lo elsewhere (a stand-in: the
    entry passes).  Result and tally are those of ``within`` on the exact values."""
    o, b, sure, known, e_lo = _sure(observed, lo, hi, bound)
    x = np.array(lo, dtype=np.float64, copy=True)
    ok = sure.copy()
    ask = np.flatnonzero(~sure & ~known)
    if len(ask):
        x.flat[ask] = [float(exact_at(int(n))) for n in ask]
    rest = np.flatnonzero(~sure)
    if len(rest):
        ok.flat[rest] = within(np.abs(o.flat[rest] - x.flat[rest]), b.flat[rest])
    _count_sure(sure, b, e_lo)
    return ok, x


def decided_within(observed, lo, hi, bound) -> bool:
    """True when ``within(|observed - x|, bound)`` holds for every entry whatever the
    correctly rounded exact x in [lo, hi] is (at both ends, every bound finite: the rounded
    |o - x| is monotone in x on each side of o), the entries then counted judged as
    :func:`within` counts them; False decides nothing (the caller compares exactly)."""
    o = np.asarray(observed, dtype=np.float64)
    b = np.asarray(bound, dtype=np.float64)
    with np.errstate(invalid="ignore", over="ignore"):
        ok = np.isfinite(o) & np.isfinite(b) & (np.abs(o - lo) <= b) & (np.abs(o - hi) <= b)
    if not ok.all():
        return False
    count_unjudged(0, ok.size)
    return True


def _is_real(x) -> bool:
    return isinstance(x, numbers.Real) and not isinstance(x, bool)


def _restore(cls, state):
    f = cls.__new__(cls)
    f.__dict__.update(state)
    AssertionError.__init__(f, str(f))
    return f


@dataclass(frozen=True)
class Property:
    id: str                      # catalog ID as in THEOREMS.md, e.g. "D1.6"
    name: str                    # python name of the check function
    statement: str               # what it checks, one line
    needs: frozenset[str]        # protocol methods the implementation must have
    strategy: Callable[[], Any]  # () -> hypothesis strategy of examples
    check: Callable[[Any, Any], None] = field(repr=False)
    # at least one of these too, when given: the property checks each one the
    # implementation has (T3.2 on its matrix and on its own Dirichlet solver)
    needs_any: frozenset[str] = frozenset()
    # how it runs on a given mesh file (``check --mesh``): None, on drawn examples only;
    # else the requirements (REQUIREMENTS) a mesh must meet, () for any mesh
    on_mesh: tuple | None = None
    # called when the implementation has them, not required (R1.6 reads genus if given)
    also: frozenset[str] = frozenset()

    @property
    def methods(self) -> frozenset[str]:
        """Every protocol method the check may call."""
        return self.needs | self.needs_any | self.also

    def applies_to(self, caps: frozenset[str]) -> bool:
        return self.needs <= caps and (not self.needs_any or bool(self.needs_any & caps))

    def lacks(self, caps: frozenset[str]) -> str:
        """What an implementation with ``caps`` lacks for this property, as text ('' if none)."""
        missing = sorted(self.needs - caps)
        if self.needs_any and not self.needs_any & caps:
            missing.append(" or ".join(sorted(self.needs_any)))
        return ", ".join(missing)


PROPERTIES: dict[str, Property] = {}


def prop(catalog_id: str, statement: str, *, needs=(), strategy, on_mesh, needs_any=(),
         also=()):
    """Register ``check(impl, example)`` as the property of ``catalog_id``: it applies to an
    implementation with every method of ``needs`` and at least one of ``needs_any``, and
    also calls those of ``also`` that the implementation has.

    ``on_mesh`` (required: every property declares it) says how it runs on a mesh file
    given to ``check --mesh``: ``None`` if it needs drawn examples (what it checks is not
    a quantity of one given mesh: a motion, a flip, a drawn function), else the names of
    the :data:`REQUIREMENTS` the mesh must meet (``()``: any mesh).  There the example is
    the mesh's :class:`~.example.Example` (its classification and chi known when it is
    connected)."""
    unknown = set(on_mesh or ()) - set(REQUIREMENTS)
    if unknown:
        raise ValueError(f"{catalog_id}: unknown mesh requirements {sorted(unknown)}; "
                         f"known: {sorted(REQUIREMENTS)}")
    def register(check):
        if catalog_id in PROPERTIES:
            raise ValueError(f"property {catalog_id} registered twice")

        @functools.wraps(check)
        def checked(impl, example):
            # tolerances inside the check read the implementation's own epsilon (coarser
            # where it declares rounding its own input: .conventions.bound_epsilon)
            with at_machine_epsilon(_bound_epsilon(impl, example)), own_arithmetic(), \
                    example_time_limit(f"[{catalog_id}] {implementation_name(impl)}"):
                check(impl, example)

        PROPERTIES[catalog_id] = Property(
            catalog_id, check.__name__, statement, frozenset(needs), strategy, checked,
            frozenset(needs_any), None if on_mesh is None else tuple(on_mesh), frozenset(also))
        check.property_id = catalog_id
        return check
    return register


def _bound_epsilon(impl, example) -> float:
    """The epsilon of ``impl``'s bounds on ``example``'s mesh (:func:`.conventions.
    bounds_epsilon_of`; an example without one: the declared epsilon); each further mesh it
    is called on widens it again (:class:`~.calls.Watched`)."""
    from .conventions import bounds_epsilon_of
    if not hasattr(example, "mesh"):
        return machine_epsilon(impl)
    return bounds_epsilon_of(impl, lambda: example.mesh)


# --- what a mesh file must be for a check (check --mesh, compare) ------------------------------

#: A file check's requirements: name -> (the facts of the mesh -> why it is not met, or None).
#: Facts: n, faces, chi, boundary (loops), orientable, oriented (consistently: no reversed
#: gluing), components (MeshExamples.facts).
REQUIREMENTS: dict[str, Callable[[dict], str | None]] = {
    "closed": lambda f: None if f["boundary"] == 0 else "the mesh has a boundary",
    "bordered": lambda f: None if f["boundary"] else "the mesh is closed",
    "connected": lambda f: None if f["components"] == 1 else f"{f['components']} components",
    "orientable": lambda f: None if f["orientable"] else "the mesh is not orientable",
    # the sign of a dihedral angle (convex > 0) is read from the faces' own orientation
    "oriented": lambda f: None if f["oriented"] else (
        "the faces are not consistently oriented (the sign of a dihedral angle depends on "
        "it)" if f["orientable"] else "the mesh is not orientable"),
}

#: largest face count for R2.5's exact sums (one square root per face of a float mesh):
#: beyond it the total mean curvature is the fsum of the correctly rounded H(e), the bound
#: widened (properties.curvature_exact.steiner_mean_curvature_view), decided from the
#: enclosures of the H(e) where they can (twice_mean_curvature_range)
EXACT_SUM_LIMIT = 400


def unmet(requires, facts: dict) -> str | None:
    """Why a mesh with ``facts`` does not meet ``requires`` (the first unmet requirement),
    or None."""
    for name in requires:
        why = REQUIREMENTS[name](facts)
        if why:
            return why
    return None


# --- the protocol's quantities: how each method's answer is compared on one mesh -------------


@dataclass(frozen=True)
class Quantity:
    """How closely the answers of one protocol method must match the exact reference's on a
    given mesh (``compare``, ``check --mesh`` through the properties, the test vectors).
    The answer's shape is the method's own (:class:`~.protocol.Method`: ``kind``,
    ``element``).

    ``requires``: :data:`REQUIREMENTS` of the mesh.  ``not_on_a_mesh``: why one mesh is not
    enough to compare it (the answer is not unique, or the method takes more than a
    mesh), else None.  ``bound(example, want)``: the derived bound on each element of the
    answer (:mod:`.bounds`), ``want`` what it is compared with; ``expected(example,
    reference)``: the values to compare with when not the reference's answer itself
    (``reference()`` gives that), e.g. a float view kept with the bounds.

    ``exact(example)``: the exact values of a numeric answer on the example's surface
    (its vertices are the ones a face uses), in the method's shape: per face its 3 corner
    values (``corner``), a sequence or {vertex: value} (``vertex``), per vertex 3 values
    (``vertex coordinate``), one value (``total``), {(i, j) with i < j: value}
    (``edges``), a sparse exact matrix (``matrix``); the test vectors print them.
    ``planar``: the reference answers only for points in the plane z = 0.  ``via``: the
    method whose values an answer of this one is compared through (an intrinsic
    triangulation is not unique, its Laplace-Beltrami operator is).
    """

    method: str
    requires: tuple = ()
    not_on_a_mesh: str | None = None
    bound: Callable | None = field(default=None, repr=False)
    expected: Callable | None = field(default=None, repr=False)
    exact: Callable | None = field(default=None, repr=False)
    planar: bool = False
    via: str | None = None

    @property
    def kind(self) -> str:
        from ..protocol.methods import METHODS
        return METHODS[self.method].kind

    @property
    def element(self) -> str:
        from ..protocol.methods import METHODS
        return METHODS[self.method].element


QUANTITIES: dict[str, Quantity] = {}


def quantity(method: str, **how) -> Quantity:
    """Declare how closely ``method``'s answers must match (:class:`Quantity`); once per
    protocol method, beside the properties that check it."""
    from ..protocol.methods import METHODS
    if method not in METHODS:
        raise ValueError(f"{method!r} is not a protocol method (protocol.methods.METHODS)")
    if method in QUANTITIES:
        raise ValueError(f"quantity {method!r} declared twice")
    unknown = set(how.get("requires", ())) - set(REQUIREMENTS)
    if unknown:
        raise ValueError(f"{method}: unknown mesh requirements {sorted(unknown)}")
    numeric = METHODS[method].kind in ("numbers", "edges", "matrix")
    if how.get("bound") is None and how.get("not_on_a_mesh") is None and numeric:
        raise ValueError(f"{method}: a numeric answer needs its derived bound")
    if how.get("exact") is None and numeric:
        raise ValueError(f"{method}: a numeric answer needs its exact values (exact=)")
    if how.get("via") is not None and how["via"] not in METHODS:
        raise ValueError(f"{method}: via {how['via']!r} is not a protocol method")
    QUANTITIES[method] = q = Quantity(method, **how)
    return q


def all_quantities() -> dict[str, Quantity]:
    """Every declared quantity, in the protocol's order (the chapter modules imported)."""
    from ..protocol.methods import METHODS
    all_properties()
    return {m: QUANTITIES[m] for m in METHODS if m in QUANTITIES}


#: Modules whose import registers properties, one per chapter topic.
PROPERTY_MODULES = ("topology", "curvature", "laplacian", "delaunay")


def all_properties() -> list[Property]:
    """Every registered property, chapter module by chapter module (PROPERTY_MODULES), each
    in its order of registration: the same order whichever module was imported first."""
    import importlib
    for m in PROPERTY_MODULES:
        importlib.import_module(f"{__package__}.{m}")
    order = {f"{__package__}.{m}": k for k, m in enumerate(PROPERTY_MODULES)}
    registered = list(PROPERTIES.values())
    return sorted(registered, key=lambda p: (order.get(p.check.__module__, len(order)),
                                             registered.index(p)))


def _parts(catalog_id: str) -> set[str]:
    """The IDs a (possibly joint) catalog ID is made of: 'L4.3 / P4.4' -> {'L4.3', 'P4.4'}."""
    return {part.strip() for part in catalog_id.split("/")}


def select_properties(only=None) -> list[Property]:
    """The registered properties whose catalog ID is, or has as one of its parts, one of
    ``only`` (every property if ``only`` is None); ValueError naming an ID that selects
    none.  Entries of ``only`` may themselves be comma-separated.

    >>> [p.id for p in select_properties(["L4.3", "D1.6"])]
    ['D1.6', 'L4.3 / P4.4']
    """
    props = all_properties()
    if only is None:
        return props
    wanted = {w.strip() for entry in only for w in str(entry).split(",") if w.strip()}
    if not wanted:
        raise ValueError("no catalog ID given to select properties by (an empty selection "
                         "would check nothing); e.g. D1.6 or L4.3")
    chosen = [p for p in props if p.id in wanted or _parts(p.id) & wanted]
    known = {part for p in props for part in _parts(p.id) | {p.id}}
    unknown = sorted(wanted - known)
    if unknown:
        import difflib
        hints = [f"{u} (did you mean {', '.join(m)}?)" if (m := difflib.get_close_matches(
            u, sorted(known), n=3, cutoff=0.6)) else u for u in unknown]
        raise ValueError(f"no property for catalog ID(s) {', '.join(hints)}")
    return chosen
