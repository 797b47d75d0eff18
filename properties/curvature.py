"""Chapter 2 properties: curvature of polyhedral surfaces (D2.2, R2.2, L2.4, T2.5, T2.6,
X2.1, R2.4, D2.3, T2.7, R2.5, D2.6, X2.3).

Each property takes an implementation (see :mod:`ddg_oracle.protocol.methods`) and an
example drawn from its strategy.  Expected values come from the exact reference
(:mod:`ddg_oracle.reference.curvature`) evaluated on *exactly the float coordinates the
implementation receives* (every float is a rational), or from how the example
was built (chi, the kind of a vertex star, a support-function integral).

Tolerances are derived, never guessed: the error model of angles, angle defects,
dihedral angles, mean curvature and areas computed from float points is
:mod:`ddg_oracle.properties.bounds`'.  Every failure message reports the observed error in
units of its bound.
"""

from __future__ import annotations

import math

from fractions import Fraction

import numpy as np
from hypothesis import assume, strategies as st

from ..reference import curvature as ref
from ..reference import surfaces
from ..reference.combinatorics import Triangulation
from ..reference.exact import exact_sum
from ..reference.linear import cross, det3, dot, sub
from ..reference.polyhedral import PolyhedralSurface

from . import memo
from .views import corner_angle_views, defect_views, mean_curvature_views, turning_views
from .bounds import (area_tolerance, corner_tolerances, edge_mean_curvature_tolerances,
                     float_geometry, gamma, total_area_view, vertex_tolerances)
from .conventions import declared, widened
from ..protocol.methods import FLOAT64_EPSILON, ISOLATED_VERTEX, eps
from .registry import EXACT_SUM_LIMIT, PropertyFailure, TieDisagreement, prop, quantity
from .strategies import Example, floated, jittered_surfaces
from . import variants
from .variants import circle_point


# --- examples -------------------------------------------------------------------------------------


def _relabel_surface(surface: PolyhedralSurface, key: int):
    """(relabelled surface, perm) with vertex v renamed perm[v] (:func:`.variants.relabelled`)."""
    t, positions, perm = variants.relabelled(surface.triangulation, surface.positions, key)
    return PolyhedralSurface(t, positions), perm


@st.composite
def rational_motions(draw):
    """(R, t): a rational rotation (Cayley transform of a rational skew matrix, T2.5) and a
    translation with small rational entries."""
    w = [Fraction(draw(st.integers(-4, 4)), draw(st.integers(1, 3))) for _ in range(3)]
    tr = tuple(Fraction(draw(st.integers(-6, 6)), 2) for _ in range(3))
    return ref.cayley_rotation(*w), tr


def _signed_permutation(k: int):
    """One of the 48 symmetries of the cube (exact on floats): a signed permutation matrix."""
    perms = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]
    p, signs = perms[k % 6], k // 6
    return [[(-1 if signs >> i & 1 else 1) if j == p[i] else 0 for j in range(3)]
            for i in range(3)]


def _star_surface(directions, kind, params, symmetry, shift):
    """The star of vertex 0 at ``shift`` with neighbours 0 + d_j, faces (0, j, j+1)."""
    n = len(directions)
    faces = [(0, 1 + j, 1 + (j + 1) % n) for j in range(n)]
    P = _signed_permutation(symmetry)
    pts = [(0, 0, 0)] + list(directions)
    pts = [tuple(sum(P[i][k] * p[k] for k in range(3)) + shift[i] for i in range(3))
           for p in pts]
    s = floated(PolyhedralSurface(Triangulation.from_faces(faces), pts))
    return Example.of_surface(s, 1, f"{kind} star {params}, symmetry {symmetry}, shift {shift}",
                         vertex=0, kind=kind, params=params)


@st.composite
def vertex_stars(draw, kind: str | None = None):
    """The star of one interior vertex (a disk, chi = 1), built to be of a given kind (L2.4, R2.2).

    * convex: rays of a pyramid over a convex polygon around the apex's foot,
      each scaled by its own factor (the cone, hence convexity, is unchanged);
    * planar: neighbours in the plane of p, all around it (sectors < pi);
    * saddle: m >= 3 directions d and their opposites -d (scaled), spanning R^3
      (p is then in the interior of the hull of its neighbours);
    * folded: n = 2m neighbours on a unit circle, alternately at heights +h, -h
      (K <= 2 pi - 2 n atan(h), unbounded below as n grows, R2.2).

    Then one of the 48 symmetries of the cube and a dyadic translation, both
    exact on floats, so the kind survives rounding to floats.
    """
    kind = kind or draw(st.sampled_from(["convex", "planar", "saddle", "folded"]))
    symmetry = draw(st.integers(0, 47))
    shift = tuple(Fraction(draw(st.integers(-8, 8)), 4) for _ in range(3))
    scale = [Fraction(1, 2), Fraction(1), Fraction(3, 2), Fraction(2)]
    if kind in ("convex", "planar"):
        n = draw(st.integers(3, 8))
        gaps = draw(st.lists(st.integers(1, 3), min_size=n, max_size=n))
        assume(2 * max(gaps) < sum(gaps))              # every sector below pi
        lam = draw(st.lists(st.sampled_from(scale), min_size=n, max_size=n))
        steep = draw(st.sampled_from([Fraction(1, 4), Fraction(1), Fraction(3)]))
        angles, acc = [], Fraction(1, 3)
        for g in gaps:
            angles.append(2 * math.pi * float(acc) / sum(gaps))
            acc += g
        dirs = []
        for a, l in zip(angles, lam):
            c, s = circle_point(a)
            dirs.append((l * c, l * s, -l * steep if kind == "convex" else 0))
        params = (n, tuple(gaps), str(steep)) if kind == "convex" else (n, tuple(gaps))
    elif kind == "saddle":
        m = draw(st.integers(3, 4))          # d and -d for m = 2 directions span a plane only
        gaps = draw(st.lists(st.integers(1, 3), min_size=m, max_size=m))
        heights = draw(st.lists(st.integers(-3, 3), min_size=m, max_size=m))
        lam = draw(st.lists(st.sampled_from(scale), min_size=2 * m, max_size=2 * m))
        total = sum(gaps) + 1
        half, acc = [], Fraction(1, 2)
        for g in gaps:
            half.append(math.pi * float(acc) / total)
            acc += g
        base = [(*circle_point(a), Fraction(z)) for a, z in zip(half, heights)]
        if det3(base[0], base[1], base[2]) == 0:
            # coplanar: lift the third; its foot is off the line of the first two, so det != 0
            base[2] = (*base[2][:2], base[2][2] + 1)
            heights[2] += 1
        dirs = [tuple(l * x for x in d) for d, l in zip(base, lam[:m])]
        dirs += [tuple(-l * x for x in d) for d, l in zip(base, lam[m:])]
        params = (m, tuple(gaps), tuple(heights))
    elif kind == "folded":
        m = draw(st.integers(2, 6))
        h = draw(st.integers(1, 8))
        n = 2 * m
        dirs = []
        for j in range(n):
            c, s = circle_point(2 * math.pi * (j + Fraction(1, 3)) / n)
            dirs.append((c, s, h if j % 2 == 0 else -h))
        params = (n, h)
    else:
        raise ValueError(f"unknown star kind {kind!r}")
    # built once per drawn star in this process: every implementation's task draws the same
    return memo.DRAWN.shared(("star", tuple(dirs), kind, params, symmetry, shift),
                             lambda: _star_surface(dirs, kind, params, symmetry, shift))


# --- reference values and tolerances --------------------------------------------------------------


def _reference(case: Example, what: str) -> dict:
    """Float views (correctly rounded) of the exact angle defects (``what="defects"``, D2.2)
    or turning angles (``"turning"``, R2.4) of a case."""
    return (defect_views if what == "defects" else turning_views)(case.surface)


def _reference_mean_curvature(case: Example):
    """{(i, j): float(H(e))} of the exact D2.3 values over the interior edges."""
    return mean_curvature_views(case.surface)


def _call(impl, method: str, case: Example):
    V, F = case.arrays()              # new arrays: an implementation may work in place
    return getattr(impl, method)(V, F)


ISOLATED_ANGLE_DEFECT = ISOLATED_VERTEX["angle_defects"]     # docs/reference.md, Conventions


def _defects(impl, case: Example, pid: str) -> np.ndarray:
    """The implementation's angle defects, checked for shape and, at isolated vertices, for
    the convention 2 pi; returned in the surface's indexing (the reference's)."""
    K = np.asarray(_call(impl, "angle_defects", case), dtype=np.float64).reshape(-1)
    at = case.layout
    n = len(at) + len(case.isolated)
    if K.shape != (n,):
        raise PropertyFailure(pid, impl, "angle_defects must return one value per vertex",
                              mesh=case.mesh, expected=(n,), observed=K.shape)
    for i, _ in case.isolated:
        bound = gamma(1) * ISOLATED_ANGLE_DEFECT     # 2 pi minus an empty sum: one rounding
        if not abs(K[i] - ISOLATED_ANGLE_DEFECT) <= bound:
            raise PropertyFailure(pid, impl, "a vertex used by no face has angle defect 2 pi "
                                  "(the empty angle sum; docs/reference.md, Conventions)", mesh=case.mesh,
                                  element=f"vertex {i} (isolated)",
                                  expected=ISOLATED_ANGLE_DEFECT, observed=float(K[i]), bound=bound)
    return K[at] if case.isolated else K


def _defect_bounds(impl, case: Example, K, corner_tol) -> np.ndarray:
    """The bounds of the angle defects ``K`` (:func:`.bounds.vertex_tolerances`), widened
    for a declared pointwise curvature (:func:`.conventions.widened`)."""
    return widened(declared(impl), "angle_defects", K, case, vertex_tolerances(case, corner_tol))


def _units(err: float, bound: float) -> str:
    return f"error {err:.3g} = {err / bound:.3g} x its bound {bound:.3g}"


# --- Gaussian curvature (D2.2, R2.2, L2.4, T2.5, T2.6, X2.1, R2.4, X2.3, D2.6) --------------------


@prop("D2.2", "angle_defects = 2 pi - angle sum at every interior vertex, as the exact reference, "
      "within the derived float bound",
      needs={"angle_defects"}, on_mesh=(), strategy=lambda: jittered_surfaces(intrinsic=True))
def angle_defects_match_reference(impl, case: Example):
    K = _defects(impl, case, "D2.2")
    tol = _defect_bounds(impl, case, K, corner_tolerances(case))
    for v, k in _reference(case, "defects").items():
        err = abs(K[v] - k)
        if not err <= tol[v]:
            raise PropertyFailure("D2.2", impl, f"angle defect off: {_units(err, tol[v])}",
                                  mesh=case.mesh, element=f"vertex {v}", expected=k,
                                  observed=float(K[v]), bound=tol[v])


@prop("R2.4", "boundary vertices get the turning angle pi - angle sum; interior K plus turning "
      "angles sum to 2 pi chi", needs={"angle_defects"},
      on_mesh=("bordered",),
      strategy=lambda: jittered_surfaces(closed=False, intrinsic=True))
def turning_angles_and_gauss_bonnet_with_boundary(impl, case: Example):
    K = _defects(impl, case, "R2.4")
    tol = _defect_bounds(impl, case, K, corner_tolerances(case))
    _check_total("R2.4", impl, case, K, tol)           # cheap: needs no exact values
    for v, k in _reference(case, "turning").items():
        err = abs(K[v] - k)
        if not err <= tol[v]:
            raise PropertyFailure("R2.4", impl, f"turning angle off: {_units(err, tol[v])}",
                                  mesh=case.mesh, element=f"boundary vertex {v}", expected=k,
                                  observed=float(K[v]), bound=tol[v])


def _check_total(pid, impl, case, K, tol):
    total = float(math.fsum(K))
    expected = 2 * math.pi * case.chi
    bound = float(tol.sum()) + gamma(len(K)) * float(np.abs(K).sum()) + 2 * eps() * abs(expected)
    err = abs(total - expected)
    if not err <= bound:
        raise PropertyFailure(pid, impl, f"total curvature != 2 pi chi: {_units(err, bound)}",
                              mesh=case.mesh, element=f"chi = {case.chi}", expected=expected,
                              observed=total, bound=bound)


@prop("T2.6", "Gauss-Bonnet: the angle defects of a closed surface sum to 2 pi chi, within the "
      "derived bound", needs={"angle_defects"},
      on_mesh=("closed",),
      strategy=lambda: jittered_surfaces(closed=True, intrinsic=True))
def gauss_bonnet(impl, case: Example):
    K = _defects(impl, case, "T2.6")
    tol = _defect_bounds(impl, case, K, corner_tolerances(case))
    _check_total("T2.6", impl, case, K, tol)


@prop("X2.1", "unit cube (any rational rotation, any labelling): K = pi/2 at every vertex, total 4 pi",
      needs={"angle_defects"},
      on_mesh=None,
      strategy=lambda: st.tuples(rational_motions(), st.integers(0, 1 << 16)))
def cube_angle_defects(impl, example):
    (R, tr), key = example
    moved, _ = _relabel_surface(ref.rigid_motion(surfaces.cube(), R, tr), key)
    case = Example.of_surface(floated(moved), 2, f"unit cube moved by {R}, {tr}, relabelled {key}")
    K = _defects(impl, case, "X2.1")
    tol = _defect_bounds(impl, case, K, corner_tolerances(case, input_rounding=True))
    for v in range(8):
        err = abs(K[v] - math.pi / 2)
        if not err <= tol[v]:
            raise PropertyFailure("X2.1", impl, f"cube vertex defect != pi/2: {_units(err, tol[v])}",
                                  mesh=case.mesh, element=f"vertex {v}", expected=math.pi / 2,
                                  observed=float(K[v]), bound=tol[v])
    _check_total("X2.1", impl, case, K, tol)


@prop("T2.5", "Theorema Egregium: angle defects are unchanged by a rational rigid motion and a "
      "relabelling (within both bounds plus input rounding)", needs={"angle_defects"},
      on_mesh=None,
      strategy=lambda: st.tuples(jittered_surfaces(far=False),
                                 rational_motions(),
                                 st.integers(0, 1 << 16)))
def angle_defects_are_invariant(impl, example):
    """The moved copy is rounded to floats: a nearly flat vertex of high valence (up to 64)
    then has an angle sum over as many independent square roots, which the reference
    decides exactly (its zero test works per cotangent: reference/exact/angles.py)."""
    case, (R, tr), key = example
    motion = (tuple(map(tuple, R)), tuple(tr), key)
    moved, perm = case.derived(("moved", motion),
                               lambda c: _relabel_surface(floated(ref.rigid_motion(c.surface, R, tr)), key))
    # rounding the moved points to floats may merge two of a cluster or a sliver's points
    # (a face of zero area, or two faces folded onto each other): then it is no surface,
    # and not an example (as the strategies reject such a rounding)
    assume(not case.derived(("moved degenerate", motion),
                            lambda c: variants.is_degenerate(moved) or variants.has_fold(moved)))
    other = Example.of_surface(moved, case.chi, case.recipe + f", moved, relabelled {key}")
    K1, K2 = _defects(impl, case, "T2.5"), _defects(impl, other, "T2.5")
    tol1 = _defect_bounds(impl, case, K1, corner_tolerances(case))
    tol2 = _defect_bounds(impl, other, K2, corner_tolerances(other, input_rounding=True))
    for v in range(case.triangulation.n_vertices):
        w = perm[v]
        err, bound = abs(K1[v] - K2[w]), tol1[v] + tol2[w]
        if not err <= bound:
            raise PropertyFailure("T2.5", impl, f"K changed under a rigid motion: {_units(err, bound)}",
                                  mesh=other.mesh, element=f"vertex {v} (now {w})",
                                  expected=float(K1[v]), observed=float(K2[w]), bound=bound)


@st.composite
def pushable_surfaces(draw):
    """(case, v): a surface with a vertex v whose neighbours are coplanar (X2.3).

    A bipyramid over a rational polygon in z = 0 (closed, chi 2) or a planar grid
    with one interior vertex lifted (a disk); every coordinate a float.
    """
    if draw(st.booleans()):
        n = draw(st.integers(3, 7))
        top, bottom = Fraction(draw(st.integers(1, 8)), 4), Fraction(draw(st.integers(1, 8)), 4)
        ring = [(*circle_point(2 * math.pi * (k + Fraction(1, 3)) / n), 0) for k in range(n)]
        faces = [(0, 2 + k, 2 + (k + 1) % n) for k in range(n)]
        faces += [(1, 2 + (k + 1) % n, 2 + k) for k in range(n)]
        s = PolyhedralSurface(Triangulation.from_faces(faces),
                              [(0, 0, top), (0, 0, -bottom)] + ring)
        case = Example.of_surface(floated(s), 2, f"bipyramid n={n}, apexes {top}, -{bottom}")
        return case, draw(st.sampled_from([0, 1]))
    m, n = draw(st.integers(2, 4)), draw(st.integers(2, 4))
    g = surfaces.grid(m, n)
    i, j = draw(st.integers(1, m - 1)), draw(st.integers(1, n - 1))
    v = i * (n + 1) + j
    h = Fraction(draw(st.integers(1, 12)), 4)
    pos = [(x, y, h if w == v else z) for w, (x, y, z) in enumerate(g.positions)]
    return Example.of_surface(floated(g.with_positions(pos)), 1, f"grid {m}x{n}, vertex {v} at {h}"), v


@prop("X2.3", "pushing a vertex in (reflecting it in the plane of its coplanar neighbours) "
      "changes no corner angle and no angle defect", needs={"angle_defects", "corner_angles"},
      on_mesh=None,
      strategy=pushable_surfaces)
def pushing_a_vertex_in_keeps_the_metric(impl, example):
    case, v = example
    pushed = Example.of_surface(floated(ref.push_vertex_in(case.surface, v)), case.chi,
                           case.recipe + f", vertex {v} pushed in")
    ct1, ct2 = corner_tolerances(case), corner_tolerances(pushed)
    A1 = np.asarray(_call(impl, "corner_angles", case), dtype=np.float64)
    A2 = np.asarray(_call(impl, "corner_angles", pushed), dtype=np.float64)
    err = np.abs(A1 - A2) - (ct1 + ct2)
    if (err > 0).any():
        f, c = np.unravel_index(int(np.argmax(err)), err.shape)
        e = abs(A1[f, c] - A2[f, c])
        bound = ct1[f, c] + ct2[f, c]
        raise PropertyFailure("X2.3", impl, f"corner angle changed: {_units(e, bound)}",
                              mesh=pushed.mesh, element=f"face {f}, corner {c}",
                              expected=float(A1[f, c]), observed=float(A2[f, c]), bound=bound)
    K1, K2 = _defects(impl, case, "X2.3"), _defects(impl, pushed, "X2.3")
    tol = _defect_bounds(impl, case, K1, ct1) + _defect_bounds(impl, pushed, K2, ct2)
    bad = np.abs(K1 - K2) - tol
    if (bad > 0).any():
        w = int(np.argmax(bad))
        raise PropertyFailure("X2.3", impl, f"K changed: {_units(abs(K1[w] - K2[w]), tol[w])}",
                              mesh=pushed.mesh, element=f"vertex {w}", expected=float(K1[w]),
                              observed=float(K2[w]), bound=tol[w])


@prop("R2.2", "K < 2 pi everywhere; a folded star of n neighbours at heights +-h has "
      "K <= 2 pi - 2 n atan(h) (unbounded below)", needs={"angle_defects"},
      on_mesh=None,
      strategy=lambda: st.tuples(jittered_surfaces(), vertex_stars("folded")))
def curvature_bounded_above_not_below(impl, example):
    case, star = example
    K = _defects(impl, case, "R2.2")
    tol = _defect_bounds(impl, case, K, corner_tolerances(case))
    t = case.triangulation
    for v in range(t.n_vertices):
        bound = math.pi if t.is_boundary_vertex(v) else 2 * math.pi    # turning angle < pi
        if not K[v] < bound + tol[v]:
            raise PropertyFailure("R2.2", impl, "K >= 2 pi (or turning angle >= pi)",
                                  mesh=case.mesh, element=f"vertex {v}", expected=f"< {bound}",
                                  observed=float(K[v]))
    n, h = star.params
    Ks = _defects(impl, star, "R2.2")
    tol_s = _defect_bounds(impl, star, Ks, corner_tolerances(star))[0]
    # The star was rounded to floats: its unit-circle points moved by <= eps, which
    # moves each of the n angles by <= 4 eps / sin; the float evaluation of the bound
    # itself is off by <= gamma_4 (2 pi + 2 n atan h).  Both are in `slack`.
    bound = 2 * math.pi - 2 * n * math.atan(h)
    slack = tol_s + gamma(4) * (2 * math.pi + 2 * n * math.atan(h)) + 4 * n * eps() * (1 + h * h)
    if not Ks[0] <= bound + slack:
        raise PropertyFailure("R2.2", impl, f"folded star not as negative as it must be "
                              f"(K <= 2 pi - 2 n atan h = {bound:.6g})", mesh=star.mesh,
                              element="vertex 0", expected=f"<= {bound}", observed=float(Ks[0]))


_PREDICATES = {"convex": ref.is_convex_star, "planar": ref.is_planar_star,
               "saddle": ref.is_saddle_star}
_SIGN = {"convex": 1, "planar": 0, "saddle": -1}


@prop("L2.4", "convex star => K > 0, planar star => K = 0, saddle star => K < 0 (stars built "
      "to be of each kind; K decided beyond the float bound)", needs={"angle_defects"},
      on_mesh=None,
      strategy=lambda: st.sampled_from(["convex", "planar", "saddle"]).flatmap(vertex_stars))
def star_kind_decides_curvature_sign(impl, star: Example):
    # the kind survived rounding to floats
    assume(star.derived("kind", lambda c: _PREDICATES[c.kind](c.surface, 0)))
    Ks = _defects(impl, star, "L2.4")
    K, tol = float(Ks[0]), float(_defect_bounds(impl, star, Ks, corner_tolerances(star))[0])
    want = _SIGN[star.kind]
    exact = _reference(star, "defects")[0]
    if want == 0:
        ok = abs(K) <= tol
    elif abs(exact) > tol:
        ok = (K > 0) if want > 0 else (K < 0)
    else:                                   # |K| below the bound: the sign is not observable
        ok = abs(K - exact) <= tol
    if not ok:
        rel = {1: ">", 0: "=", -1: "<"}[want]
        raise PropertyFailure("L2.4", impl, f"{star.kind} star needs K {rel} 0 "
                              f"(float bound {tol:.3g})", mesh=star.mesh, element="vertex 0",
                              expected=exact, observed=K, bound=tol)
    if want == 0 and K != 0:                # exactly flat; the float K calls it curved
        raise TieDisagreement("L2.4", impl, "exactly flat vertex (K = 0) given a nonzero K "
                              "within the float bound", mesh=star.mesh, element="vertex 0",
                              expected=0.0, observed=K, bound=tol)


@prop("D2.6", "the corner angles are those of the triangles with the mesh's edge lengths "
      "(the piecewise flat metric built from squared lengths alone)", needs={"corner_angles"},
      on_mesh=(),
      strategy=lambda: jittered_surfaces(intrinsic=True))
def corner_angles_from_edge_lengths(impl, case: Example):
    expected = corner_angle_views(case.surface)
    A = np.asarray(_call(impl, "corner_angles", case), dtype=np.float64)
    if A.shape != expected.shape:
        raise PropertyFailure("D2.6", impl, "corner_angles must be an (m, 3) array", mesh=case.mesh,
                              expected=expected.shape, observed=A.shape)
    tol = corner_tolerances(case)
    bad = np.abs(A - expected) - tol
    if (bad > 0).any():
        f, c = np.unravel_index(int(np.argmax(bad)), bad.shape)
        raise PropertyFailure("D2.6", impl,
                              f"corner angle off: {_units(abs(A[f, c] - expected[f, c]), tol[f, c])}",
                              mesh=case.mesh, element=f"face {f}, corner {c}",
                              expected=float(expected[f, c]), observed=float(A[f, c]), bound=tol[f, c])


# --- mean curvature (D2.3, T2.7, R2.5) ------------------------------------------------------------


def _edge_dict(impl, case, pid):
    raw = _call(impl, "edge_mean_curvature", case)
    back = {w: v for v, w in enumerate(case.layout)}       # array index -> surface vertex
    out = {}
    for (i, j), value in dict(raw).items():
        i, j = back.get(int(i), -1 - int(i)), back.get(int(j), -1 - int(j))
        out[(min(i, j), max(i, j))] = float(value)
    return out


@prop("D2.3", "edge_mean_curvature: H(e) = 1/2 theta(e) l(e) on every interior edge, theta > 0 "
      "where convex, as the exact reference within the derived bound",
      needs={"edge_mean_curvature"}, on_mesh=("oriented",), strategy=jittered_surfaces)
def edge_mean_curvature_matches_reference(impl, case: Example):
    H = _edge_dict(impl, case, "D2.3")
    expected = _reference_mean_curvature(case)
    if set(H) != set(expected):
        raise PropertyFailure("D2.3", impl, "edge_mean_curvature must have exactly the interior edges",
                              mesh=case.mesh, expected=sorted(expected)[:20], observed=sorted(H)[:20])
    tol = edge_mean_curvature_tolerances(case)
    for key, h in expected.items():
        err = abs(H[key] - h)
        if not err <= tol[key]:
            length, theta, _, _ = float_geometry(case)["edges"][key]
            raise PropertyFailure("D2.3", impl, f"H(e) off: {_units(err, tol[key])}", mesh=case.mesh,
                                  element=f"edge {key}, theta ~ {theta:.6g}, l ~ {length:.6g}",
                                  expected=h, observed=H[key], bound=tol[key])


def support_function_integral(points, n_theta: int = 256) -> tuple[float, float]:
    """(value, bound): the integral of h(u) = max_p <u, p> over the unit sphere, numerically.

    For a convex polyhedron with vertices ``points`` this is H(S) (T2.7), i.e.
    2 pi times the mean width.  Quadrature on the n_theta x 2 n_theta
    longitude-latitude cells, after centring (the integral of <u, c> vanishes):
    on a cell where one vertex p_i provably maximises <u, .> (its lead over every
    p_j at the cell's centre exceeds |p_i - p_j| r, r a bound on the distance from
    the centre to the cell), h = <u, p_i> is integrated in closed form; on the
    other cells h(centre) times the cell's area is used, with error <= area R r
    (h is R-Lipschitz, R = max |p|).  ``bound`` is the sum of those errors plus
    the float rounding of the sums, gamma_(N + 16) sum |terms|.
    """
    P = np.asarray(points, dtype=np.float64)
    P = P - P.mean(axis=0)
    R = float(np.sqrt((P * P).sum(axis=1)).max())
    n_phi = 2 * n_theta
    th = np.linspace(0.0, np.pi, n_theta + 1)
    ph = np.linspace(0.0, 2 * np.pi, n_phi + 1)
    t0, t1, f0, f1 = th[:-1], th[1:], ph[:-1], ph[1:]
    dth, dph = np.pi / n_theta, 2 * np.pi / n_phi
    tc, fc = (t0 + t1) / 2, (f0 + f1) / 2
    smax = np.where((t0 <= np.pi / 2) & (t1 >= np.pi / 2), 1.0, np.maximum(np.sin(t0), np.sin(t1)))
    r = dth / 2 + smax * dph / 2          # geodesic (hence chordal) radius of a cell about its centre
    sin2 = (t1 - t0) / 2 - (np.sin(2 * t1) - np.sin(2 * t0)) / 4      # integral of sin^2
    sincos = (np.sin(t1) ** 2 - np.sin(t0) ** 2) / 2                  # integral of sin cos
    U = np.stack([sin2[:, None] * (np.sin(f1) - np.sin(f0))[None, :],
                  sin2[:, None] * (np.cos(f0) - np.cos(f1))[None, :],
                  sincos[:, None] * np.full(n_phi, dph)[None, :]], axis=-1).reshape(-1, 3)
    uc = np.stack([np.sin(tc)[:, None] * np.cos(fc)[None, :],
                   np.sin(tc)[:, None] * np.sin(fc)[None, :],
                   np.cos(tc)[:, None] * np.ones(n_phi)[None, :]], axis=-1).reshape(-1, 3)
    rc = np.repeat(r, n_phi)
    area = np.repeat((np.cos(t0) - np.cos(t1)) * dph, n_phi)
    vals = uc @ P.T
    top = vals.argmax(axis=1)
    rows = np.arange(len(top))
    best = vals[rows, top]
    D = np.sqrt(((P[:, None, :] - P[None, :, :]) ** 2).sum(-1))
    margin = best[:, None] - vals - D[top] * rc[:, None]
    margin[rows, top] = np.inf
    pure = (margin > 0).all(axis=1)
    exact_part = (U[pure] * P[top[pure]]).sum(axis=1)
    approx_part = best[~pure] * area[~pure]
    value = float(exact_part.sum() + approx_part.sum())
    bound = float((area[~pure] * R * rc[~pure]).sum())
    # our own float64 sums: float64's gamma, whatever the checked implementation declares
    bound += gamma(len(top) + 16, FLOAT64_EPSILON) * float(np.abs(exact_part).sum()
                                                           + np.abs(approx_part).sum())
    return value, bound


def convex_hull_surface(points) -> PolyhedralSurface | None:
    """The boundary of the convex hull of integer points, faces oriented outward, or None.

    scipy's ConvexHull proposes the faces; orientation and convexity are then
    checked exactly (every point weakly inside every face plane, the centroid
    strictly inside); None if the hull is flat or the check fails.
    """
    from scipy.spatial import ConvexHull
    from scipy.spatial import QhullError
    pts = [tuple(Fraction(x) for x in p) for p in points]
    try:
        hull = ConvexHull(np.array(points, dtype=np.float64))
    except (QhullError, ValueError):
        return None
    used = sorted({int(i) for s in hull.simplices for i in s})
    index = {v: k for k, v in enumerate(used)}
    centre = tuple(sum(pts[v][k] for v in used) / len(used) for k in range(3))
    faces = []
    for s in hull.simplices:
        a, b, c = (pts[int(i)] for i in s)
        n = cross(sub(b, a), sub(c, a))
        side = dot(n, sub(centre, a))
        if side == 0:
            return None
        face = [index[int(i)] for i in s]
        if side > 0:
            face[1], face[2] = face[2], face[1]
            n = tuple(-x for x in n)
        if any(dot(n, sub(p, a)) > 0 for p in pts):
            return None
        faces.append(face)
    try:
        return PolyhedralSurface(Triangulation.from_faces(faces), [pts[v] for v in used])
    except Exception:
        return None


@st.composite
def convex_polyhedra(draw):
    """A convex polyhedron: the hull of 4..12 integer points near the sphere of radius 8.

    Each point is a small integer direction (entries in -3..3) scaled to length
    about 8 and rounded to integers, so coordinates are exact floats.
    """
    n = draw(st.integers(4, 12))
    dirs = draw(st.lists(st.tuples(st.integers(-3, 3), st.integers(-3, 3), st.integers(-3, 3))
                         .filter(any), min_size=n, max_size=n, unique=True))
    pts = tuple(sorted({tuple(round(8 * x / math.sqrt(sum(y * y for y in d))) for x in d)
                        for d in dirs}))
    # the hull depends on the points alone: built once per point set in this process
    s = memo.DRAWN.shared(("convex hull", pts), lambda: convex_hull_surface(pts))
    assume(s is not None)
    return Example.of_surface(s, 2, f"convex hull of {list(pts)}")


@prop("T2.7", "total mean curvature of a convex polyhedron = integral of its support function over "
      "the unit sphere (2 pi x mean width), within quadrature plus float bounds",
      needs={"edge_mean_curvature"}, on_mesh=None, strategy=convex_polyhedra)
def total_mean_curvature_is_support_integral(impl, case: Example):
    H = _edge_dict(impl, case, "T2.7")
    total = math.fsum(H.values())
    value, quad_bound = case.derived("support integral",
                                     lambda c: support_function_integral(c.surface.to_arrays()[0]))
    tol = edge_mean_curvature_tolerances(case)
    bound = quad_bound + sum(tol.values()) + gamma(len(H)) * sum(abs(h) for h in H.values())
    err = abs(total - value)
    if not err <= bound:
        raise PropertyFailure("T2.7", impl, f"H(S) != integral of the support function: "
                              f"{_units(err, bound)}", mesh=case.mesh, expected=value,
                              observed=total, bound=bound)


@prop("R2.5", "Steiner coefficients of a closed surface: area, 2 H(S) and K(S) = 2 pi chi agree "
      "with the exact (A, 2 H(S), 2 pi chi)", needs={"area", "edge_mean_curvature", "angle_defects"},
      on_mesh=("closed", "oriented"),
      strategy=lambda: jittered_surfaces(closed=True))
def steiner_coefficients_match(impl, case: Example):
    A_ref, err_A, twoH_ref, err_H = _steiner_views(case)
    A = float(_call(impl, "area", case))
    bound_A = area_tolerance(case) + err_A
    if not abs(A - float(A_ref)) <= bound_A:
        raise PropertyFailure("R2.5", impl, f"area off: {_units(abs(A - float(A_ref)), bound_A)}",
                              mesh=case.mesh, expected=float(A_ref), observed=A, bound=bound_A)
    H = _edge_dict(impl, case, "R2.5")
    tol = edge_mean_curvature_tolerances(case)
    twoH = 2 * math.fsum(H.values())
    bound_H = 2 * (sum(tol.values()) + gamma(len(H)) * sum(abs(h) for h in H.values())) + err_H
    if not abs(twoH - float(twoH_ref)) <= bound_H:
        err = abs(twoH - float(twoH_ref))
        raise PropertyFailure("R2.5", impl, f"2 H(S) off: {_units(err, bound_H)}",
                              mesh=case.mesh, expected=float(twoH_ref), observed=twoH, bound=bound_H)
    K = _defects(impl, case, "R2.5")
    _check_total("R2.5", impl, case, K, _defect_bounds(impl, case, K, corner_tolerances(case)))


def _steiner_views(case: Example) -> tuple[float, float, float, float]:
    """(A, err_A, 2 H(S), err_H): R2.5's area and total mean curvature as floats within
    err of the exact ones.  Up to EXACT_SUM_LIMIT faces the exact sums correctly rounded
    (err 0); beyond, an exact sum has a square root per face, so: the area correctly
    rounded from enclosures (:func:`total_area_view`, err u A), and 2 H(S) = 2 fsum of the correctly rounded H(e) (each within
    u |H(e)|, the fsum within u of its value: err_H = 2 u sum |H(e)| + u |2 H(S)|, with a
    factor 1.0001 for |H(e)| <= (1 + u) |its float|).  The checks widen their bounds by err:
    a pass is then certain; a failure by less than err (about 1e-16 relative) would go
    unseen."""
    if len(case.faces) <= EXACT_SUM_LIMIT:
        A, twoH, _ = case.derived("steiner", lambda c: ref.steiner_coefficients(c.surface))
        return float(A), 0.0, float(twoH), 0.0
    A, err_A = total_area_view(case.surface.metric())
    views = list(mean_curvature_views(case.surface).values())
    twoH = 2 * math.fsum(views)
    u = 2.0 ** -53
    return A, err_A, twoH, 1.0001 * u * (2 * math.fsum(abs(h) for h in views) + abs(twoH))


# --- how the curvature methods' answers compare on a given mesh (compare, vectors) ------------


def _area_bound(example: Example, want) -> float:
    # the reference's answer is the exact total correctly rounded: within u A of it
    return area_tolerance(example) + total_area_view(example.surface.metric())[1]


def _mean_curvature_by_pair(example: Example) -> dict:
    """D2.3: {(i, j) with i < j: H(e)} exactly, keyed by the edge's vertices."""
    t = example.surface.triangulation
    return {tuple(sorted(t.edge_vertices(e))): h
            for e, h in ref.mean_curvature(example.surface).items()}


quantity("corner_angles", bound=lambda example, want: corner_tolerances(example),
         exact=lambda example: ref.corner_angles(example.surface))
quantity("angle_defects",
         bound=lambda example, want: vertex_tolerances(example, corner_tolerances(example)),
         exact=lambda example: {**ref.angle_defects(example.surface),
                                **ref.turning_angles(example.surface)})
quantity("edge_mean_curvature", requires=("oriented",),
         bound=lambda example, want: edge_mean_curvature_tolerances(example),
         exact=_mean_curvature_by_pair)
quantity("area", bound=_area_bound,
         exact=lambda example: exact_sum(example.surface.metric().areas))
