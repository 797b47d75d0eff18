"""Simplicial minimal surfaces (I): the Pinkall-Polthier iteration (A3.6), exact steps.

One step (Figure 3.6 of the notes): with the cotan weights of the CURRENT
surface S fixed, solve ``Lap_S f = 0`` at the interior vertices with the
boundary fixed, coordinate-wise (a Dirichlet problem, C3.4 / T3.5; unique by
R3.3).  The new vertex map f defines the next surface.

Why the area cannot increase (exact certificate, :func:`area_decrease_certificate`):

    A(f(S)) = sum_T A(f(T)) <= sum_T E_T(f) = E_S(f) <= E_S(id) = A(S)

* per triangle, the area of an affine image is at most its Dirichlet energy
  (``A <= 1/2 integral |df|^2``, since ``s1 s2 <= (s1^2 + s2^2)/2`` for the
  singular values of df): decided as ``A(f(T))^2 <= E_T(f)^2`` with
  ``E_T(f) = 1/4 sum_corners cot * |opposite edge of f(T)|^2``;
* f minimises ``E_S`` among maps with the same boundary (T3.5, cotan weights:
  R3.3), and the identity map has ``E_S(id) = A(S)`` (T3.9).

Exactness: the weights of S are Surds, so the new positions are Surds (with
up to 2^F terms) and the new surface's area (a sum of square roots of Surds)
is *not* a Surd.  The certificate above avoids it, and decides each
inequality by certified rational enclosures of the exact values (ties are
detected exactly; see :func:`area_decrease_certificate`): no float decides.  A second exact step would need the cotangents of
a surface with Surd coordinates (square roots of Surds), which the field does
not hold; :func:`minimal_surface_iteration` therefore rounds each step's result
to dyadic rationals (``bits`` fractional bits, correctly rounded) before the
next step, and reports the exact areas of the rounded surfaces.  That rounding
is the only inexact operation, and it is stated.

Keep the meshes small: the elimination runs over Surd entries (a handful of
interior vertices; see the term guard in :mod:`ddg_oracle.reference.dirichlet`).

>>> from ddg_oracle.reference.polyhedral import PolyhedralSurface
>>> star = PolyhedralSurface.from_arrays(
...     [(0, 0, 1), (2, 0, 0), (0, 2, 0), (-2, 0, 0), (0, -2, 0)],
...     [(0, 1, 2), (0, 2, 3), (0, 3, 4), (0, 4, 1)])
>>> new = minimal_surface_step(star)
>>> new[0]                                   # the tip comes down into the plane
(Fraction(0, 1), Fraction(0, 1), Fraction(0, 1))
>>> area_decrease_certificate(star, new).strict
True
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from math import isqrt
from typing import Sequence

from .errors import InputError
from .exact import Surd
from .exact.intervals import Interval, dot
from .delaunay import flip_to_delaunay, is_delaunay, laplace_beltrami
from .dirichlet import neighbour_convex_combination, separates, solve_dirichlet
from .laplacian import cotan_laplacian, metric_of_surface
from .polyhedral import PolyhedralSurface

__all__ = ["minimal_surface_step", "area_decrease_certificate", "AreaDecrease",
           "area_enclosure", "minimal_surface_iteration", "MinimalSurfaceRun",
           "figure_3_7_star", "is_minimal_wide", "is_minimal_narrow",
           "delaunay_neighbour_hull", "delaunay_minimal_surface_step", "next_surface"]

_ZERO = Fraction(0)


def _boundary_vertices(surface: PolyhedralSurface) -> list[int]:
    t = surface.triangulation
    return [v for v in range(t.n_vertices) if t.is_boundary_vertex(v)]


def minimal_surface_step(surface: PolyhedralSurface, fixed: Sequence[int] | None = None,
                         *, term_limit: int | None = None) -> list[tuple]:
    """A3.6, one step: the positions f with ``Lap_S f = 0`` off ``fixed``, exact.

    ``fixed`` defaults to the boundary vertices; it must meet every component.
    Weights: the cotan weights of ``surface`` itself (Surds).  Returns one
    tuple of exact coordinates (Fraction or Surd) per vertex.
    """
    if not isinstance(surface, PolyhedralSurface):
        raise InputError("a minimal surface step moves vertices: pass a PolyhedralSurface")
    fixed = _boundary_vertices(surface) if fixed is None else list(fixed)
    L = cotan_laplacian(surface)
    values = {v: surface.positions[v] for v in fixed}
    return solve_dirichlet(L, values, term_limit=term_limit)


# --- the area certificate: interval filters (exact.intervals), exact fallback ------------------

#: precision (bits) after which a comparison falls back to exact Surd arithmetic
PRECISION_CAP = 2048


def _diff(p, q):
    return tuple(x - y for x, y in zip(p, q))


def _face_quantities(cots, p, bits):
    """Enclosures (:class:`~ddg_oracle.reference.exact.intervals.Interval`) of
    E_T(f) = 1/4 sum_c cot_c |f(opposite edge of c)|^2 (T3.6 on one face) and of
    A(f(T))^2 = (|u|^2 |v|^2 - <u, v>^2) / 4, from exact differences."""
    edges = (_diff(p[1], p[2]), _diff(p[2], p[0]), _diff(p[0], p[1]))   # opposite corners 0, 1, 2
    iv_edges = [tuple(Interval.enclosing(x, bits) for x in e) for e in edges]
    energy = Interval(0)
    for c in range(3):
        w = iv_edges[c]
        energy = energy + Interval.enclosing(cots[c], bits) * dot(w, w)
    u, v = iv_edges[2], tuple(-x for x in iv_edges[1])          # p1 - p0, p2 - p0
    a2 = (dot(u, u) * dot(v, v) - dot(u, v).square()).clamped_below(_ZERO)
    return energy / 4, a2 / 4


def _face_exact(cots, p):
    """The same two quantities exactly (Surd arithmetic; the fallback)."""
    def sq(e):
        acc = _ZERO
        for x in e:
            acc = acc + x * x
        return acc
    e0, e1, e2 = _diff(p[1], p[2]), _diff(p[2], p[0]), _diff(p[0], p[1])
    energy = (cots[0] * sq(e0) + cots[1] * sq(e1) + cots[2] * sq(e2)) / 4
    u, v = e2, tuple(-x for x in e1)
    uv = _ZERO
    for a, b in zip(u, v):
        uv = uv + a * b
    return energy, (sq(u) * sq(v) - uv * uv) / 4


@dataclass(frozen=True)
class AreaDecrease:
    """The chain ``A(f(S)) <= E_S(f) <= E_S(id) = A(S)`` of one A3.6 step, decided.

    ``area_before`` = A(S) (exact Surd); ``energy_after`` = a certified rational
    enclosure ``(lo, hi)`` of E_S(f); ``faces_ok``: ``A(f(T)) <= E_T(f)`` was
    established on every face; ``energy_ok``: ``E_S(f) <= A(S)``; ``strict``: f
    differs from the old positions (then ``E_S(f) < A(S)`` strictly, by
    uniqueness of the minimiser).
    """

    area_before: object
    energy_after: tuple
    faces_ok: bool
    energy_ok: bool
    strict: bool

    @property
    def holds(self) -> bool:
        """A(f(S)) <= A(S), proved by the chain."""
        return self.faces_ok and self.energy_ok


def area_decrease_certificate(surface: PolyhedralSurface, new_positions, *,
                              domain=None) -> AreaDecrease:
    """Decide the chain ``A(f(S)) <= E_S(f) <= A(S)`` for a step S -> f(S) (A3.6).

    Works for any ``new_positions`` (the last link fails for a non-minimising
    f).  New positions are Surds with many terms; multiplying them exactly is
    costly, so each inequality is decided by certified rational enclosures
    (``Surd.interval``, interval arithmetic, precision doubled until the sides
    separate).  Ties are exact, never numeric: a face whose three vertices did
    not move has ``E_T = A(T)`` exactly (T3.9 on one face), and ``f = id`` has
    ``E_S(f) = A(S)``; any other tie (a face mapped by a similarity) falls back
    to exact Surd arithmetic past ``PRECISION_CAP`` bits.

    ``domain`` (A4.23): another triangulation of the same metric, a
    :class:`~ddg_oracle.reference.metric.PiecewiseFlatSurface` (e.g. the intrinsic Delaunay
    one); E is then the Dirichlet energy on ``domain`` and the new surface has
    the combinatorics of ``domain``.  The shortcut "unmoved face: E_T = A(T)"
    holds only on the surface's own triangulation, so every face is decided.
    """
    own = domain is None
    m = metric_of_surface(surface) if own else metric_of_surface(domain)
    t = m.triangulation
    old = surface.positions
    new = [tuple(p) for p in new_positions]
    moved = [tuple(p) != tuple(q) for p, q in zip(old, new)]
    if not own:
        moved = [True] * len(new)
    cots = [tuple(m.corner_cot(f, k) for k in range(3)) for f in range(t.n_faces)]
    before = m.total_area()
    faces_ok = True
    pending = [f for f, face in enumerate(t.faces) if any(moved[v] for v in face)]
    bits = 64
    energies: dict[int, tuple] = {}
    while pending:
        left = []
        for f in pending:
            p = [new[v] for v in t.faces[f]]
            if bits > PRECISION_CAP:
                e, a2 = _face_exact(cots[f], p)
                faces_ok = faces_ok and e >= 0 and a2 <= e * e
                energies[f] = Interval.enclosing(e, PRECISION_CAP)
                continue
            e, a2 = _face_quantities(cots[f], p, bits)
            energies[f] = e
            if e.lo >= 0 and a2.hi <= e.lo * e.lo:
                continue                                   # A(f(T)) <= E_T(f)
            if e.hi < 0 or a2.lo > e.hi * e.hi:
                faces_ok = False                           # certainly violated
                continue
            left.append(f)
        pending, bits = left, 2 * bits
    for f in range(t.n_faces):
        if f not in energies:                             # unmoved: E_T = A(T) exactly
            energies[f] = Interval.enclosing(m.areas[f], 64)
    energy = sum(energies.values(), Interval(0))
    strict = any(tuple(p) != tuple(q) for p, q in zip(old, new))
    if own and not strict:
        energy_ok = True                                   # E_S(id) = A(S), T3.9
    else:
        energy_ok = None
        bits = 64
        while energy_ok is None:
            lo, hi = Interval.enclosing(before, bits)
            if energy.hi < lo:
                energy_ok = True
            elif energy.lo > hi:
                energy_ok = False
            elif bits > PRECISION_CAP:
                exact = _ZERO
                for f in range(t.n_faces):
                    exact = exact + _face_exact(cots[f], [new[v] for v in t.faces[f]])[0]
                energy_ok = exact <= before
            else:
                bits *= 2
                energy = _recompute_energy(cots, t, new, moved, m, bits)
    return AreaDecrease(before, tuple(energy), faces_ok, energy_ok, strict)


def _recompute_energy(cots, t, new, moved, m, bits) -> Interval:
    total = Interval(0)
    for f, face in enumerate(t.faces):
        if any(moved[v] for v in face):
            total = total + _face_quantities(cots[f], [new[v] for v in face], bits)[0]
        else:
            total = total + Interval.enclosing(m.areas[f], bits)
    return total


def _sqrt_bounds(x: Fraction, bits: int) -> tuple[Fraction, Fraction]:
    """Rational lo <= sqrt(x) <= hi for x >= 0 with hi - lo <= 2**-bits (integer square roots)."""
    s = 1 << bits
    n = x * s * s
    lo = isqrt(n.numerator // n.denominator)
    return Fraction(lo, s), Fraction(lo + 1, s)


def area_enclosure(triangulation, positions, bits: int = 64) -> tuple[Fraction, Fraction]:
    """Certified rational bounds on the area of a surface with exact (Surd) positions.

    Per face: an interval enclosure of ``A(T)^2`` from enclosures of the
    coordinates, then integer square roots rounded outwards.
    """
    lo = hi = _ZERO
    zero = (Fraction(0),) * 3
    for a, b, c in triangulation.faces:
        p = [positions[a], positions[b], positions[c]]
        _, a2 = _face_quantities(zero, p, 2 * bits + 8)
        lo += _sqrt_bounds(a2.lo, bits)[0]
        hi += _sqrt_bounds(a2.hi, bits)[1]
    return lo, hi


def _round(x, bits: int) -> Fraction:
    """x (Fraction or Surd) rounded to the nearest multiple of 2**-bits."""
    if isinstance(x, Surd):
        if x.is_rational():
            x = x.as_fraction()
        else:
            lo, hi = x.interval(bits + 8)
            x = (lo + hi) / 2
    return Fraction(round(x * (1 << bits)), 1 << bits)


@dataclass(frozen=True)
class MinimalSurfaceRun:
    """The surfaces of an A3.6 run (rounded, rational), their exact areas and the
    certificates of the exact steps."""

    surfaces: tuple
    areas: tuple
    certificates: tuple


def minimal_surface_iteration(surface: PolyhedralSurface, steps: int, *, bits: int = 64,
                              fixed: Sequence[int] | None = None) -> MinimalSurfaceRun:
    """A3.6: ``steps`` exact steps, each result rounded to ``bits`` fractional bits.

    Returns every surface (the input first), the exact area of each (Surds),
    and for each step the :class:`AreaDecrease` certificate of the exact step.
    The areas of consecutive rounded surfaces are compared by the caller
    (exactly); rounding moves each coordinate by at most ``2**-(bits+1)``.
    """
    surf = surface
    out, areas, certs = [surf], [surf.metric().total_area()], []
    for _ in range(steps):
        new = minimal_surface_step(surf, fixed)
        certs.append(area_decrease_certificate(surf, new))
        surf = surf.with_positions([tuple(_round(x, bits) for x in p) for p in new])
        out.append(surf)
        areas.append(surf.metric().total_area())
    return MinimalSurfaceRun(tuple(out), tuple(areas), tuple(certs))


def figure_3_7_star(spike: int = 3, shoulder: int = 2, lift: int = 1):
    """P3.10 fails for cotan weights: a minimal-surface step puts a vertex outside
    the convex hull of its neighbours (in the spirit of Figure 3.7).

    The star of vertex 0 (at the origin) with the ring ``m = (spike, 0, lift/4)``,
    ``(shoulder/4, 1, 0)``, ``(-1, 1, 0)``, ``(-1, -1, 0)``, ``(shoulder/4, -1, 0)``:
    the spike m is far out and its ring neighbours are close to the centre, so
    the two angles opposite the edge 0m sum to more than pi and its cotan
    weight is negative (E3.12).  One step of A3.6 (weights of this surface, ring
    fixed) gives 0 the height ``nu(0m) * lift/4 / C < 0`` (C > 0), below every
    neighbour: outside their convex hull, certified by the direction (0, 0, -1).

    Returns ``(surface, new_positions, certified)`` where ``certified`` is
    :func:`separates` for that direction.  Since only m is lifted, ``certified``
    holds exactly when ``nu(0m) < 0``; in the flat limit that is
    ``s (spike - s) > 1`` with ``s = shoulder/4`` (the angle at each shoulder is
    obtuse).  The defaults give ``nu(0m) < 0``.

    >>> surface, new, certified = figure_3_7_star()
    >>> certified, new[0][2] < 0
    (True, True)
    """
    ring = [(spike, 0, Fraction(lift, 4)), (Fraction(shoulder, 4), 1, 0), (-1, 1, 0),
            (-1, -1, 0), (Fraction(shoulder, 4), -1, 0)]
    s = PolyhedralSurface.from_arrays([(0, 0, 0)] + ring,
                                      [(0, 1 + k, 1 + (k + 1) % 5) for k in range(5)])
    new = minimal_surface_step(s)
    ok = separates((0, 0, -1), new[0], [new[j] for j in range(1, 6)])
    return s, new, ok


# --- Simplicial minimal surfaces (II): section 4.5 -------------------------------------------------


def _harmonic_off(L, surface: PolyhedralSurface, fixed) -> bool:
    dim = len(surface.positions[0])
    free = [v for v in range(surface.triangulation.n_vertices) if v not in set(fixed)]
    for k in range(dim):
        lap = L.matvec([p[k] for p in surface.positions])
        if any(lap[v] for v in free):
            return False
    return True


def is_minimal_wide(surface: PolyhedralSurface, fixed: Sequence[int] | None = None) -> bool:
    """D4.9, wide sense: ``Lap f = 0`` off ``fixed`` (default: the boundary),
    with Lap the discrete Laplace-Beltrami operator of the surface's metric (D4.8,
    the cotan Laplacian of its intrinsic Delaunay triangulation).  Exact.

    Only in the narrow sense is the surface a critical point of the area (R4.10):
    a planar non-Delaunay mesh is minimal in the wide sense (linear precision of
    the Delaunay triangulation of the same flat region), not in the narrow one.
    """
    fixed = _boundary_vertices(surface) if fixed is None else list(fixed)
    return _harmonic_off(laplace_beltrami(surface), surface, fixed)


def is_minimal_narrow(surface: PolyhedralSurface, fixed: Sequence[int] | None = None) -> bool:
    """D4.9, narrow sense: the triangulation is Delaunay and ``Lap f = 0`` off
    ``fixed``; then Lap is the cotan Laplacian of the surface itself.  Exact."""
    if not is_delaunay(surface):
        return False
    fixed = _boundary_vertices(surface) if fixed is None else list(fixed)
    return _harmonic_off(cotan_laplacian(surface), surface, fixed)


def delaunay_neighbour_hull(surface: PolyhedralSurface, i: int) -> dict[int, object]:
    """R4.10: ``{j: lambda_j}``, the convex combination ``f(i) = sum lambda_j f(j)``
    over the neighbours j of i in the Delaunay tessellation, when f is harmonic
    at i for the Laplace-Beltrami operator.

    The weights are ``nu(ij) / sum nu`` of the Laplace-Beltrami operator, so
    every lambda_j >= 0 (P4.10) and the j with lambda_j > 0 are exactly the
    tessellation neighbours (R4.7); exact.  Whether f is harmonic at i is for the
    caller to check (:func:`is_minimal_wide`).
    """
    return {j: w for j, w in neighbour_convex_combination(laplace_beltrami(surface), i).items()
            if w}


def delaunay_minimal_surface_step(surface: PolyhedralSurface, fixed: Sequence[int] | None = None,
                                  *, term_limit: int | None = None):
    """A4.23, one step: ``(T~, f~)`` with T~ an intrinsic Delaunay triangulation
    of the surface's metric (A4.13) and f~ the positions with ``Lap_(S,T~) f~ = 0``
    off ``fixed`` (default: the boundary), exact.  The new simplicial surface is
    ``f~`` on the combinatorics of T~ (which may be non-regular).

    The area does not increase (the notes state the algorithm; the proof is a
    chain, decided by :func:`area_decrease_certificate` with ``domain=`` the
    Delaunay metric):

        A(f~(T~)) <= E_T~(f~) <= E_T~(f) <= 1/2 sum nu~ l~^2 = A(S)

    per face area <= energy; f~ minimises E_T~ (T3.5); the Delaunay weights nu~
    are >= 0 (P4.10) and each chord |f(i) - f(j)| is at most the intrinsic length
    l~ of the edge ij of T~ (a path on S); the last equality is T3.9 (ER-2) on the
    metric of T~.

    Returns ``(delaunay_metric, new_positions)``.
    """
    if not isinstance(surface, PolyhedralSurface):
        raise InputError("a minimal surface step moves vertices: pass a PolyhedralSurface")
    fixed = _boundary_vertices(surface) if fixed is None else list(fixed)
    delaunay, _ = flip_to_delaunay(metric_of_surface(surface))
    values = {v: surface.positions[v] for v in fixed}
    return delaunay, solve_dirichlet(cotan_laplacian(delaunay), values, term_limit=term_limit)


def next_surface(surface: PolyhedralSurface, fixed: Sequence[int] | None = None,
                 *, term_limit: int | None = None) -> PolyhedralSurface:
    """A4.23 / R4.11: the next state of the algorithm, the simplicial surface S~ given by
    the new positions f~ on the combinatorics of T~ (:func:`delaunay_minimal_surface_step`).

    R4.11: the state is the pair (S, T); T~ is Delaunay for the metric of S, and need
    not be Delaunay for S~ (``is_delaunay(next_surface(s))`` may be False).  Needs
    rational positions f~ (rational Delaunay weights, e.g. faces in coordinate planes);
    otherwise the new surface is outside the exact field of
    :class:`~ddg_oracle.reference.polyhedral.PolyhedralSurface` and :class:`InputError`
    says so.  T~ must not have a loop (an edge from a vertex to itself has no straight
    realisation).

    >>> from ddg_oracle.reference import surfaces
    >>> c = surfaces.cube()
    >>> box = PolyhedralSurface.from_arrays(          # the cube without its top
    ...     c.positions, [f for f in c.triangulation.faces
    ...                   if any(c.positions[v][2] == 0 for v in f)])
    >>> s = next_surface(box)                  # the bottom comes up into the top plane
    >>> s.positions[0], is_delaunay(s)
    ((Fraction(2, 3), Fraction(1, 3), Fraction(1, 1)), True)
    """
    delaunay, new = delaunay_minimal_surface_step(surface, fixed, term_limit=term_limit)
    t = delaunay.triangulation
    loops = [e for e in range(t.n_edges) if len(set(t.edge_vertices(e))) == 1]
    if loops:
        raise InputError(f"T~ has loop edges {loops[:5]}: no simplicial surface realises it")
    if any(isinstance(x, Surd) for p in new for x in p):
        raise InputError("the new positions are irrational (Surds): the next surface's "
                         "metric would need square roots of Surds")
    return PolyhedralSurface(t, new)
