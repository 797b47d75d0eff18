"""Chapter 4 properties: intrinsic Delaunay triangulations and the Laplace-Beltrami operator.

Protocol methods used (``protocol/methods.py``): ``cotan_laplacian``,
``corner_angles``, ``is_locally_delaunay`` (per face and corner: is the edge
opposite the corner locally Delaunay), ``intrinsic_delaunay_laplacian`` (the
cotan Laplacian of an intrinsic Delaunay triangulation of the mesh's metric,
reference sign: positive semidefinite) and ``intrinsic_delaunay_triangulation``
(faces and squared lengths, ``l2[f, c]`` the edge opposite corner c).

The truth is the exact reference on the very floats the implementation received
(:class:`ddg_oracle.properties.harness.Exact`) and its exact flip algorithm
(:func:`ddg_oracle.reference.delaunay.flip_to_delaunay`).

The exact operator on an example and the error model of float flips:
:mod:`.delaunay_exact`; where rounding decides a Delaunay test (ties): :mod:`.ties`.  The
examples are drawn by :mod:`.strategies` and :mod:`.flipped`.

Exact ties (a cot sum exactly 0: the four points cocircular) accept either
answer; near ties (the exact value within the bound of 0) answered the other
way are not failures, since rounding decides them.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from ..reference.curvature import corner_angles
from ..reference.delaunay import harmonic_index, is_delaunay_edge, laplace_beltrami

from .bounds import K_COT, corner_tolerances, gamma
from .delaunay_exact import (DelaunayExact, angles_from_squared_lengths, delaunay_view_bounds,
                             total_area_bound)
from .views import corner_angle_views
from .harness import (Exact, dirichlet_solve, entries_at, fail, implementation_dense,
                      implementation_matrix, ledger_open, matrix_decided, record, worst,
                      worst_sparse)
from .flipped import (delaunay_meshes, delaunay_test_meshes, interior_meshes, intrinsic_meshes,
                      planar_delaunay_points, quads_with_values, scaled_planar_triangulations,
                      two_triangulations, x42_tetrahedron)
from .strategies import Example, mesh_case, planar_meshes
from .ties import cot_sum_with_bound, delaunay_ties, incircle_with_bound
from ..protocol.methods import eps
from .registry import PropertyFailure, TieDisagreement, faces_text, prop, quantity, within
from ..reference.combinatorics import next_corner, opposite_halfedge, prev_corner


def _compare(pid, impl, case, A, exact, B, what):
    """Every entry of ``A`` (dense or sparse) within ``B`` of ``exact`` (sparse)."""
    import scipy.sparse as sp
    A = sp.csr_matrix(A)
    err = abs(A - exact).tocoo()
    record(pid, err.data, entries_at(B, err.row, err.col))
    (i, j), r = worst_sparse(err, B)
    if r > 1:
        fail(pid, impl, case, f"{what} entry differs from the exact value by {r:.3g} x the "
              f"bound {float(B[i, j]):.3g}", element=(int(i), int(j)),
              expected=float(exact[i, j]), observed=float(A[i, j]))


# --- properties --------------------------------------------------------------------------------


@prop("D4.4 / T4.7 / P4.9", "is_locally_delaunay agrees with the exact angle criterion "
      "cot a + cot b >= 0 on every edge (boundary edges are Delaunay); exact ties accept both",
      needs={"is_locally_delaunay"}, on_mesh=None, strategy=delaunay_test_meshes)
def locally_delaunay_edges(impl, case: Example):
    pid = "D4.4 / T4.7 / P4.9"
    X = Exact.of(case)
    t = X.triangulation
    got = np.asarray(impl.is_locally_delaunay(*case.arrays()))
    if got.shape != (t.n_faces, 3):
        fail(pid, impl, case, "is_locally_delaunay has the wrong shape",
              expected=(t.n_faces, 3), observed=got.shape)
    tie = None
    for f in range(t.n_faces):
        for c in range(3):
            h = opposite_halfedge(f, c)
            e = t.edge_of(h)
            want = is_delaunay_edge(X.metric, e)
            if bool(got[f, c]) == want:
                continue
            s, bound = cot_sum_with_bound(X, e)
            if abs(s) <= bound:                     # an (exact or near) tie: rounding decides
                tie = tie or (f, c, e, want, bool(got[f, c]), s, bound)
                continue
            fail(pid, impl, case, f"edge {t.edge_vertices(e)} opposite corner {c} of face {f} "
                  f"is {'' if want else 'not '}Delaunay (cot sum {s:.6g}, the bound {bound:.3g})",
                  element=t.edge_vertices(e), expected=want, observed=bool(got[f, c]))
    if tie:
        f, c, e, want, seen, s, bound = tie
        _near_tie(pid, impl, case.mesh, f"the edge opposite corner {c} of face {f} has the cot "
                  f"sum {s:.3g}, within the float bound {bound:.3g} of 0",
                  element=t.edge_vertices(e), expected=want, observed=seen)


@prop("P4.10", "the interior-edge cotan weights of the implementation's cotan_laplacian are all "
      ">= 0 iff the triangulation is Delaunay: each weight's sign agrees with the exact one "
      "(weights within the bound of 0 are ties)",
      needs={"cotan_laplacian"}, on_mesh=None, strategy=delaunay_meshes)
def nonnegative_weights_iff_delaunay(impl, case: Example):
    A = implementation_dense(impl, case, "P4.10")
    X = Exact.of(case)
    n = X.n
    off = X.adjacent & ~np.eye(n, dtype=bool)
    W, exact = -A, -X.Lf                            # weights: minus the off-diagonal entries
    clear_neg = off & (exact < -X.B)
    if np.any(clear_neg):                           # not Delaunay: some weight must be negative
        i, j = np.argwhere(clear_neg)[0]
        if W[i, j] >= 0:
            fail("P4.10", impl, case, "a non-Delaunay edge has a nonnegative weight",
                  element=(int(i), int(j)), expected=float(exact[i, j]), observed=float(W[i, j]))
    low = off & (W < -X.B) & (exact >= 0)
    if np.any(low):
        i, j = np.argwhere(low)[0]
        fail("P4.10", impl, case, "a Delaunay edge has a negative weight beyond the bound",
              element=(int(i), int(j)), expected=float(exact[i, j]), observed=float(W[i, j]))


@prop("D4.8 / R4.9", "intrinsic_delaunay_laplacian is the exact Laplace-Beltrami operator "
      "(cotan Laplacian of the intrinsic Delaunay triangulation) within the derived bound; its "
      "weights on interior edges are >= 0", needs={"intrinsic_delaunay_laplacian"},
      on_mesh=(), strategy=intrinsic_meshes)
def laplace_beltrami_operator(impl, case: Example):
    pid = "D4.8 / R4.9"
    # sparse throughout: runs on a mesh file of any size (ddg-oracle check --mesh)
    A = implementation_matrix(impl, case, pid, "intrinsic_delaunay_laplacian", flips=True)
    if _operator_enclosed(A, Exact.of(case)):
        return
    D = DelaunayExact.of(case)
    C = A.tocoo()
    neg = (entries_at(D.interior_s, C.row, C.col) != 0) & (C.data > entries_at(D.Bs, C.row, C.col))
    if np.any(neg):                                 # a weight -A_ij clearly below 0
        k = int(np.argmax(neg))
        i, j = int(C.row[k]), int(C.col[k])
        fail(pid, impl, case, "negative weight in the Laplace-Beltrami operator",
              element=(i, j), expected=float(D.Ls[i, j]), observed=float(A[i, j]))
    _compare(pid, impl, case, A, D.Ls, D.Bs, "Laplace-Beltrami")


def _operator_enclosed(A, X: Exact) -> bool:
    """True when enclosures decide that D4.8 / R4.9 passes on A
    (:func:`.delaunay_exact.delaunay_view_bounds`, :func:`.harness.matrix_decided`): every
    entry within its bound.  A weight -A_ij of an interior edge below minus its bound is
    then none: the exact weight is >= 0 (the triangulation is Delaunay).  False leaves the
    verdict to the exact operator."""
    view = None if ledger_open() else delaunay_view_bounds(X.surface)
    return view is not None and matrix_decided(A, X.keep, view[:4], view[4])


@prop("T4.5", "two triangulations of one planar point set (one flat metric) give the same "
      "intrinsic Delaunay Laplacian: the Delaunay tessellation is unique",
      needs={"intrinsic_delaunay_laplacian"}, on_mesh=None, strategy=two_triangulations)
def unique_delaunay_operator(impl, pair):
    c1, c2 = pair
    A1 = implementation_dense(impl, c1, "T4.5", "intrinsic_delaunay_laplacian", flips=True)
    A2 = implementation_dense(impl, c2, "T4.5", "intrinsic_delaunay_laplacian", flips=True)
    B = DelaunayExact.of(c1).B + DelaunayExact.of(c2).B
    err = np.abs(A1 - A2)
    record("T4.5", err, B)
    (i, j), r = worst(err, B)
    if r > 1:
        # the mesh is (V, F) of the second triangulation, the first's faces in the message
        raise PropertyFailure("T4.5", impl, f"the operators of two triangulations of one point "
                              f"set differ by {r:.3g} x the bound (the other triangulation: "
                              f"{[list(f) for f in c1.faces]})", mesh=c2.mesh,
                              element=(int(i), int(j)), expected=float(A1[i, j]),
                              observed=float(A2[i, j]))


@prop("T4.21", "L_T - L_Delaunay is positive semidefinite: the Delaunay triangulation minimises "
      "the Dirichlet energy of every function (Weyl bound from both entry bounds)",
      needs={"cotan_laplacian", "intrinsic_delaunay_laplacian"},
      on_mesh=None, strategy=delaunay_meshes)
def delaunay_minimises_the_energy(impl, case: Example):
    L = implementation_dense(impl, case, "T4.21")
    D = implementation_dense(impl, case, "T4.21", "intrinsic_delaunay_laplacian", flips=True)
    De = DelaunayExact.of(case)
    M = (L - D + (L - D).T) / 2
    lam = float(np.linalg.eigvalsh(M)[0])
    tol = float(np.linalg.norm(De.X.B) + np.linalg.norm(De.B)
                + gamma(4 * De.X.n) * (np.linalg.norm(L) + np.linalg.norm(D)))
    record("T4.21", max(-lam, 0.0), tol)
    if lam < -tol:
        fail("T4.21", impl, case, f"L_T - L_Delaunay has the eigenvalue {lam:.6g} < -{tol:.3g}",
              expected=">= 0", observed=lam)


@prop("X4.2", "on the X4.2 tetrahedron (its Delaunay triangulation has a vertex of valence 1, a "
      "non-regular triangulation) the intrinsic Delaunay Laplacian is the exact one",
      needs={"intrinsic_delaunay_laplacian"}, on_mesh=None, strategy=x42_tetrahedron)
def valence_one_vertex(impl, case: Example):
    A = implementation_dense(impl, case, "X4.2", "intrinsic_delaunay_laplacian", flips=True)
    D = DelaunayExact.of(case)
    if D.delaunay.triangulation.is_regular():
        raise AssertionError("X4.2 case: the reference's Delaunay triangulation is regular")
    _compare("X4.2", impl, case, A, D.Ls, D.Bs, "Laplace-Beltrami")


@prop("L4.18", "h(T) = 8 sum_i E(phi_i) = 4 trace(L): the diagonal of cotan_laplacian sums to a "
      "quarter of the exact harmonic index", needs={"cotan_laplacian"},
      on_mesh=None, strategy=delaunay_meshes)
def harmonic_index_is_the_trace(impl, case: Example):
    A = implementation_dense(impl, case, "L4.18")
    X = Exact.of(case)
    exact = float(harmonic_index(X.metric))
    got = 4 * float(np.trace(A))
    bound = 4 * float(np.trace(X.B)) + gamma(X.n) * abs(got)
    r = record("L4.18", abs(got - exact), bound)
    if r > 1:
        fail("L4.18", impl, case, f"4 trace(L) is not h(T) ({r:.3g} x the bound)",
              expected=exact, observed=got)


@prop("D4.7 / L4.17", "h(T) = sum (a^2 + b^2 + c^2) / A = 4 sum cot: from the implementation's "
      "corner angles", needs={"corner_angles"}, on_mesh=None, strategy=delaunay_meshes)
def harmonic_index_from_angles(impl, case: Example):
    """The cotangents come from the implementation's angles, each within its corner bound
    tol (:func:`~.bounds.corner_tolerances`) of the exact angle alpha: cot moves by at most
    tol / min(sin(alpha - tol), sin(alpha + tol))^2 (|d cot / d alpha| = 1 / sin^2, sin
    concave on [0, pi]), and 1/tan adds two roundings.  Where [alpha - tol, alpha + tol]
    reaches 0 or pi the float angle does not determine its cotangent at all (a float32
    needle's angle of 1e-4 may come out 0, its cotangent infinite): a tie, unless the
    answer is within the bound of the other corners anyway."""
    X = Exact.of(case)
    ang = np.asarray(impl.corner_angles(*case.arrays()), dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        got = float(4 * np.sum(1 / np.tan(ang)))
    exact = float(harmonic_index(X.metric))
    alpha = corner_angle_views(case.surface)
    tol = corner_tolerances(case)
    lo, hi = alpha - tol, alpha + tol
    open_ = (lo > 0) & (hi < np.pi)
    with np.errstate(divide="ignore", invalid="ignore"):
        slope = np.where(open_, 1 / np.minimum(np.sin(lo), np.sin(hi)) ** 2, np.inf)
    bound = (4 * float(np.sum(np.where(open_, tol * slope, 0)))
             + gamma(ang.size + 2) * 4 * float(np.sum(np.abs(X.cot))))
    r = record("D4.7 / L4.17", abs(got - exact), bound)
    if not r > 1:
        return
    if not np.all(open_):
        f, c = (int(x) for x in np.argwhere(~open_)[0])
        raise TieDisagreement("D4.7 / L4.17", impl, f"the angle at corner {c} of face {f} is "
                              f"within its float bound {tol[f, c]:.3g} of 0 or pi: its "
                              "cotangent, hence h(T), is not determined by the float angle",
                              mesh=case.mesh, element=f"face {f}, corner {c}",
                              expected=exact, observed=got)
    fail("D4.7 / L4.17", impl, case, f"4 sum cot(angles) is not h(T) ({r:.3g} x the bound)",
          expected=exact, observed=got)


def _triangulation_result(impl, case: Example, pid: str):
    """The implementation's (F2, l2) with shape checks and the triangle inequality."""
    out = impl.intrinsic_delaunay_triangulation(*case.arrays())
    F2, l2 = (np.asarray(x) for x in out)
    m = len(case.faces)
    if F2.shape != (m, 3) or l2.shape != (m, 3):
        fail(pid, impl, case, "intrinsic_delaunay_triangulation: wrong shapes",
              expected=((m, 3), (m, 3)), observed=(F2.shape, l2.shape))
    if F2.min() < 0 or F2.max() >= case.n or not np.all(np.isfinite(l2)) or np.any(l2 <= 0):
        fail(pid, impl, case, "intrinsic_delaunay_triangulation: bad indices or lengths")
    return F2.astype(int), l2.astype(float)


@prop("A4.13", "intrinsic_delaunay_triangulation returns a triangulation of the same metric "
      "(every vertex's angle sum and the total area unchanged) whose edges are all Delaunay",
      needs={"intrinsic_delaunay_triangulation"}, on_mesh=None, strategy=intrinsic_meshes)
def flip_algorithm_result(impl, case: Example):
    pid = "A4.13"
    F2, l2 = _triangulation_result(impl, case, pid)
    D = DelaunayExact.of(case)
    amp = max(D.amplification)
    ang, area = angles_from_squared_lengths(l2)
    rho = l2.max(axis=1) / (2 * np.maximum(area, np.finfo(float).tiny))
    cot = 1 / np.tan(ang)
    beta = K_COT * eps() * (1 + cot ** 2) * (rho * amp)[:, None]
    # angle sums: each corner angle moves by at most K_COT eps rho amp (module doc)
    sums = np.zeros(case.n)
    tol = np.zeros(case.n)
    np.add.at(sums, F2.ravel(), ang.ravel())
    np.add.at(tol, F2.ravel(), (K_COT * eps() * rho * amp)[:, None].repeat(3, 1).ravel())
    exact = np.zeros(case.n)
    np.add.at(exact, np.asarray(case.faces).ravel(),
              np.array([[float(x) for x in face] for face in corner_angles(D.X.surface)]).ravel())
    tol += np.array([K_COT * eps() * sum(D.X.rho[f] for f, face in enumerate(case.faces)
                                          if v in face) for v in range(case.n)])
    (v,), r = worst(np.abs(sums - exact), tol)
    record(pid, np.abs(sums - exact), tol)
    if r > 1:
        fail(pid, impl, case, f"the angle sum at vertex {v} changed ({r:.3g} x the bound): the "
              "metric is not kept", element=v, expected=float(exact[v]), observed=float(sums[v]))
    total, want = float(area.sum()), float(D.X.metric.total_area())
    if abs(total - want) > total_area_bound(area, rho, amp, l2):
        fail(pid, impl, case, "the total area changed", expected=want, observed=total)
    # Delaunay: pair the two corners opposite each unordered vertex pair used exactly twice
    opposite: dict[tuple[int, int], list[tuple[int, int]]] = {}
    for f, (i, j, k) in enumerate(F2):
        for c, (x, y) in enumerate(((j, k), (k, i), (i, j))):
            if x != y:
                opposite.setdefault((min(x, y), max(x, y)), []).append((f, c))
    for pair, corners in opposite.items():
        if len(corners) != 2:
            continue                                # boundary, or a multi-edge: ambiguous
        s = sum(cot[f, c] for f, c in corners)
        if s < -sum(beta[f, c] for f, c in corners) - 2 * eps() * abs(s):
            fail(pid, impl, case, f"edge {pair} of the result is not Delaunay (cot sum {s:.6g})",
                  element=pair, expected=">= 0", observed=float(s))


@prop("C4.19", "the harmonic index never increases under Delaunay flips: h of the "
      "implementation's Delaunay triangulation <= h of the input, strictly when the reference "
      "had to flip", needs={"intrinsic_delaunay_triangulation"},
      on_mesh=None, strategy=intrinsic_meshes)
def harmonic_index_decreases(impl, case: Example):
    F2, l2 = _triangulation_result(impl, case, "C4.19")
    D = DelaunayExact.of(case)
    ang, _ = angles_from_squared_lengths(l2)
    h = float(4 * np.sum(1 / np.tan(ang)))
    before = float(harmonic_index(D.X.metric))
    after = float(D.log[-1].h_after) if D.log else before
    bound = 4 * float(np.sum(D.bounds.beta)) + gamma(l2.size) * abs(h)
    r = record("C4.19", max(h - before, 0.0), bound)
    if r > 1:
        fail("C4.19", impl, case, f"h increased from {before:.6g} to {h:.6g}",
              expected=f"<= {before}", observed=h)
    if after < before - 2 * bound and h >= before:
        fail("C4.19", impl, case, "the input is clearly not Delaunay, yet h did not decrease",
              expected=after, observed=h)


@prop("L4.20 / C4.13", "h(T) >= l(T)^2 / A (A the total area, l(T) the longest edge) on the "
      "implementation's Delaunay triangulation", needs={"intrinsic_delaunay_triangulation"},
      on_mesh=None,
      strategy=intrinsic_meshes)
def harmonic_index_bounds_the_longest_edge(impl, case: Example):
    F2, l2 = _triangulation_result(impl, case, "L4.20 / C4.13")
    ang, area = angles_from_squared_lengths(l2)
    h = float(4 * np.sum(1 / np.tan(ang)))
    lhs, A = float(l2.max()), float(area.sum())
    D = DelaunayExact.of(case)
    bound = (4 * float(np.sum(D.bounds.beta)) + gamma(l2.size) * abs(h)) * A + gamma(8) * lhs
    if not within(max(lhs - h * A, 0.0), bound):
        fail("L4.20 / C4.13", impl, case, "the longest edge exceeds sqrt(h A)",
              expected=f"l^2 <= {h * A}", observed=lhs)


def _interior(X: Exact) -> np.ndarray:
    """Which vertices of the case's own triangulation are interior."""
    boundary = X.triangulation.boundary_vertices()
    return np.array([v not in boundary for v in range(X.n)])


@prop("D4.9 / R4.10", "a flat mesh is minimal in the wide sense (Laplace-Beltrami of the "
      "coordinates = 0 at interior vertices) and every interior vertex is a convex combination "
      "of its Delaunay neighbours", needs={"intrinsic_delaunay_laplacian"},
      on_mesh=None,
      strategy=lambda: planar_meshes(min_size=2))
def flat_meshes_are_minimal(impl, case: Example):
    pid = "D4.9 / R4.10"
    A = implementation_dense(impl, case, pid, "intrinsic_delaunay_laplacian", flips=True)
    D = DelaunayExact.of(case)
    V, _ = case.arrays()
    inner = _interior(D.X)
    got = A @ V
    bound = (D.B + gamma(3 * D.X.n) * np.abs(A)) @ np.abs(V)
    err = np.where(inner[:, None], np.abs(got), 0)
    (v, k), r = worst(err, bound)
    record(pid, err, bound)
    if r > 1:
        fail(pid, impl, case, f"(L x)({v}) is not 0 at an interior vertex ({r:.3g} x the bound)",
              element=f"vertex {v}, coordinate {k}", expected=0.0, observed=float(got[v, k]))
    off = ~np.eye(D.X.n, dtype=bool) & inner[:, None]
    neg = off & (A > D.B)
    if np.any(neg):
        i, j = np.argwhere(neg)[0]
        fail(pid, impl, case, "a negative convex weight: the vertex may leave the hull of its "
              "Delaunay neighbours", element=(int(i), int(j)), expected=float(D.Lf[i, j]),
              observed=float(A[i, j]))


@prop("A4.23", "one minimal-surface step with the intrinsic Laplace-Beltrami operator (boundary "
      "fixed) does not increase the Dirichlet energy above the area: E(x~) <= E(x) <= A(S)",
      needs={"intrinsic_delaunay_laplacian"}, on_mesh=None, strategy=interior_meshes)
def delaunay_minimal_surface_step(impl, case: Example):
    pid = "A4.23"
    A = implementation_dense(impl, case, pid, "intrinsic_delaunay_laplacian", flips=True)
    D = DelaunayExact.of(case)
    V, _ = case.arrays()
    inner = _interior(D.X)
    if not inner.any():
        return
    new, _ = dirichlet_solve(A, list(np.flatnonzero(~inner)), V)
    area = float(D.X.metric.total_area())

    def energy(P):
        return 0.5 * float(sum(P[:, k] @ A @ P[:, k] for k in range(3)))

    def slack(P):
        aP = np.abs(P)
        return 0.5 * float(sum(aP[:, k] @ (D.B + gamma(2 * D.X.n + 6) * np.abs(A)) @ aP[:, k]
                               for k in range(3)))

    e_old, e_new = energy(V), energy(new)
    tol_old = slack(V) + eps() * area
    r = record(pid, max(e_old - area, 0.0), tol_old)
    if r > 1:
        fail(pid, impl, case, f"E(x) = {e_old:.9g} exceeds the area {area:.9g} ({r:.3g} x the "
              "bound): a negative Delaunay weight or a wrong factor", expected=f"<= {area}",
              observed=e_old)
    if e_new > e_old + slack(new) + slack(V):
        fail(pid, impl, case, "the harmonic step increased the energy", expected=f"<= {e_old}",
              observed=e_new)


# --- planar Delaunay (T4.1, D4.1) and Rippa's lemma (L4.14) -------------------------------------


def _near_tie(pid, impl, mesh, message, **kw):
    """A disagreement that rounding decides (an exact tie, or within the float bound): a
    tie disagreement, reported apart from real failures."""
    raise TieDisagreement(pid, impl, message, mesh=mesh, **kw)


def _planar_result(impl, pts, pid):
    """D4.1, T4.1: (the triangles of ``impl.planar_delaunay(pts)`` that are not flat, the mesh to show,
    the indices of the flat ones).  A triangle repeating a point is a failure.  A triangle
    of three exactly collinear points is a failure of an exact implementation; for a float
    one it is an orientation tie (exactly 0) that rounding decided otherwise: its caller
    checks the other triangles and reports a tie disagreement if they pass."""
    from ..reference.planar import orientation
    P = np.array([[float(x), float(y)] for x, y in pts], dtype=np.float64)
    T = np.asarray(impl.planar_delaunay(P))
    mesh = ([[float(x), float(y), 0.0] for x, y in pts], T.tolist() if T.ndim == 2 else [])
    # indices as floats (JSON numbers of a driver, a library's float array) are indices
    # when integral; 0.5 is not
    if (T.ndim != 2 or T.shape[1:] != (3,) or T.size == 0
            or not (np.issubdtype(T.dtype, np.integer)
                    or (np.issubdtype(T.dtype, np.floating) and np.all(T == np.floor(T))))
            or T.min() < 0 or T.max() >= len(pts)):
        raise PropertyFailure(pid, impl, "planar_delaunay: not an (m, 3) array of point indices",
                              mesh=mesh, observed=getattr(T, "shape", None))
    tris = [tuple(int(v) for v in t) for t in T]
    flat = []
    for k, t in enumerate(tris):
        if len(set(t)) < 3:
            raise PropertyFailure(pid, impl, f"degenerate triangle {k}: {list(t)} repeats a point",
                                  mesh=mesh, element=f"face {k}")
        if orientation(*(pts[v] for v in t)) == 0:
            if eps() == 0:
                raise PropertyFailure(pid, impl, f"degenerate triangle {k}: {list(t)} (its "
                                      "three points are collinear)", mesh=mesh, element=f"face {k}")
            flat.append(k)
    return [t for k, t in enumerate(tris) if k not in flat], mesh, flat


def _hull_problem(pts, tris) -> str | None:
    """T4.1: why the triangles do not tile the convex hull of the points, or None: no edge in
    more than two triangles, and their areas (exact) sum to the hull's.  A tessellation
    that differs from the Delaunay one only across near-cocircular edges still tiles the
    hull; a subset of its triangles does not (it must not pass as a tie)."""
    from collections import Counter

    def _cross(a, b, c):                    # twice the signed area of a b c, exact
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    used = Counter(frozenset(e) for t in tris for e in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])))
    over = [sorted(e) for e, n in used.items() if n > 2]
    if over:
        return f"edge {over[0]} is in {used[frozenset(over[0])]} triangles: they overlap"
    # Andrew's monotone chain, exact
    P = sorted(set(pts))
    hull = []
    for chain in (P, P[::-1]):
        start = len(hull)
        for q in chain:
            while len(hull) >= start + 2 and _cross(hull[-2], hull[-1], q) <= 0:
                hull.pop()
            hull.append(q)
        hull.pop()
    twice_hull = sum(_cross(hull[0], hull[i], hull[i + 1]) for i in range(1, len(hull) - 1))
    twice_tris = sum(abs(_cross(*(pts[v] for v in t))) for t in tris)
    # a float implementation may leave out slivers of nearly collinear points (Qhull merges
    # them): each has |cross| within the float orientation bound, (3 + 16 eps) eps (|dx1 dy2|
    # + |dy1 dx2|) <= 8 eps W H in the points' bounding box W x H, and there are fewer than
    # n of them (each leaves out a point's triangle)
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    slack = len(pts) * 8 * Fraction(eps()) * (max(xs) - min(xs)) * (max(ys) - min(ys))
    if abs(twice_tris - twice_hull) > slack:
        return (f"the triangles cover {float(twice_tris / 2):.17g} of the convex hull's area "
                f"{float(twice_hull / 2):.17g}")
    return None


def _flat_tie(pid, impl, mesh, flat):
    """D4.1, T4.1: the tie of :func:`_planar_result`'s flat triangles, once the others passed."""
    _near_tie(pid, impl, mesh, f"{len(flat)} triangle(s) of exactly collinear points (faces "
              f"{flat[:5]}): their orientation is exactly 0, which float rounding decided "
              "otherwise; the other triangles are Delaunay")


def _real_violations(pts, tris):
    """Empty-disk violations of the triangles beyond the float in-circle bound, and the
    number within it (near ties, which rounding decides)."""
    from ..reference.planar import empty_disk_violations, orientation
    real, ties = [], 0
    for cell, v, why in empty_disk_violations(pts, [frozenset(t) for t in tris]):
        t = sorted(cell)
        a, b, c = (pts[i] for i in t)
        if orientation(a, b, c) < 0:
            a, b = b, a
        det, bound = incircle_with_bound(a, b, c, pts[v])
        if abs(det) <= bound:
            ties += 1
        else:
            real.append((t, v, why, det, bound))
    return real, ties


@prop("D4.1", "every triangle of planar_delaunay is non-degenerate and its circumdisk holds no "
      "other point in its interior (exact in-circle test on the float points)",
      needs={"planar_delaunay"}, on_mesh=None, strategy=planar_delaunay_points)
def empty_disk_property(impl, pts):
    tris, mesh, flat = _planar_result(impl, pts, "D4.1")
    real, ties = _real_violations(pts, tris)
    if real:
        t, v, why, det, bound = real[0]
        raise PropertyFailure("D4.1", impl, f"point {v} violates the empty disk of triangle "
                              f"{t} ({why}; in-circle determinant {det:.3g}, float bound "
                              f"{bound:.3g})", mesh=mesh, element=t)
    if ties:
        _near_tie("D4.1", impl, mesh, f"{ties} empty-disk violation(s) within the float "
                  "in-circle bound: nearly cocircular points split the other way")
    if flat:
        _flat_tie("D4.1", impl, mesh, flat)


@prop("T4.1", "planar_delaunay is the unique Delaunay tessellation of the points once "
      "cocircular triangles are merged (compared with the exact flip algorithm's)",
      needs={"planar_delaunay"}, on_mesh=None, strategy=planar_delaunay_points)
def unique_planar_tessellation(impl, pts):
    from ..reference.planar import cocircular_cells, delaunay_tessellation
    tris, mesh, flat = _planar_result(impl, pts, "T4.1")
    want = delaunay_tessellation(pts)
    # a triangulation first (a triangle given twice has no quadrilateral to merge across)
    gap = _hull_problem(pts, tris)
    if gap:
        raise PropertyFailure("T4.1", impl, f"not a triangulation of the points: {gap}",
                              mesh=mesh, expected=sorted(sorted(c) for c in want),
                              observed=sorted(sorted(t) for t in tris))
    got = cocircular_cells(pts, tris)
    if got != want or flat:
        extra = sorted(sorted(c) for c in got - want)
        missing = sorted(sorted(c) for c in want - got)
        real, _ = _real_violations(pts, tris)
        if not real and got == want:                # the right cells and flat slivers
            _flat_tie("T4.1", impl, mesh, flat)
        if not real:                                # differs only across near-cocircular edges
            _near_tie("T4.1", impl, mesh, "the tessellation differs only where points are "
                      "cocircular within the float in-circle bound"
                      + (f", and {len(flat)} triangle(s) of exactly collinear points" if flat
                         else ""), expected=missing, observed=extra)
            return
        raise PropertyFailure("T4.1", impl, "not the Delaunay tessellation", mesh=mesh,
                              expected=missing, observed=extra)


class NotPlanarDelaunay(Exception):
    """What :func:`planar_delaunay_problems` found first: ``message`` and the
    PropertyFailure details (element, expected, observed, bound)."""

    def __init__(self, message: str, **details):
        super().__init__(message)
        self.message, self.details = message, details


def planar_delaunay_problems(pts, tris, boundary) -> int:
    """L4.3 / P4.4 / D4.1 on a triangulation ``tris`` (vertex triples) of exact planar
    points ``pts``: every face counterclockwise and non-degenerate, no directed edge used
    twice, the directed edges used once exactly ``boundary``, and every interior edge
    (a, b) with opposite corners c, d Delaunay: in_circle(a, b, c, d) <= 0, or within
    Shewchuk's float bound of 0 (:func:`incircle_with_bound`, at :func:`eps`).  Raises
    :class:`NotPlanarDelaunay` for the first problem; returns the number of edges
    non-Delaunay within the bound (near ties, which rounding decides).  Shared by the
    property and the test vectors (``ddg_oracle.application.vectors``)."""
    from ..reference.planar import in_circle, orientation
    for k, t in enumerate(tris):
        if len(set(t)) < 3 or orientation(*(pts[v] for v in t)) <= 0:
            raise NotPlanarDelaunay(f"face {k} {t} is degenerate or clockwise",
                                    element=f"face {k}")
    got = {(f[c], f[next_corner(c)]): f[prev_corner(c)] for f in tris for c in range(3)}
    if len(got) < 3 * len(tris):
        raise NotPlanarDelaunay("a directed edge is used twice: faces overlap")
    edges = {e for e in got if e[::-1] not in got}
    if edges != set(boundary):
        raise NotPlanarDelaunay("the boundary edges are not the expected ones (flips keep the "
                                "polygon)", expected=sorted(boundary), observed=sorted(edges))
    ties = 0
    for (a, b), c in sorted(got.items()):
        if a < b and (b, a) in got:
            d = got[(b, a)]
            if in_circle(pts[a], pts[b], pts[c], pts[d]) > 0:
                det, bound = incircle_with_bound(pts[a], pts[b], pts[c], pts[d])
                if abs(det) > bound:
                    raise NotPlanarDelaunay(
                        f"interior edge {(a, b)} is not Delaunay: point {d} is inside the circle "
                        f"through {(a, b)} and {c} (in-circle determinant {det:.3g}, float bound "
                        f"{bound:.3g})", element=(a, b), expected="<= 0", observed=det, bound=bound)
                ties += 1
    return ties


@prop("L4.3 / P4.4", "planar_flip_to_delaunay returns a triangulation of the same polygon (same "
      "vertices and boundary edges, faces counterclockwise) whose interior edges all have "
      "opposite angles summing to at most pi (L4.3: exact in-circle test on the float points); "
      "started on the convex hull, the Delaunay tessellation (T4.1)",
      needs={"planar_flip_to_delaunay"}, on_mesh=None, strategy=scaled_planar_triangulations)
def planar_flips_reach_delaunay(impl, example):
    from ..reference.planar import cocircular_cells, delaunay_tessellation
    pid = "L4.3 / P4.4"
    pts, faces, on_hull = example
    V = np.array([[float(x), float(y), 0.0] for x, y in pts])
    out = np.asarray(impl.planar_flip_to_delaunay(V, np.array(faces, dtype=np.int64)))
    # failures carry the input (what reproduces them); the result goes into the message
    mesh = (V.tolist(), [list(f) for f in faces])
    if (out.shape != (len(faces), 3) or not np.issubdtype(out.dtype, np.integer)
            or out.min() < 0 or out.max() >= len(pts)):
        raise PropertyFailure(pid, impl, "planar_flip_to_delaunay: not an (m, 3) array of "
                              "vertex indices, m the input's face count", mesh=mesh,
                              expected=(len(faces), 3), observed=getattr(out, "shape", None))
    tris = [tuple(int(v) for v in f) for f in out]
    result = f" (result faces {faces_text(tris)})"

    def sides(fs):
        return {(f[c], f[next_corner(c)]) for f in fs for c in range(3)}
    given = sides(faces)
    try:
        ties = planar_delaunay_problems(pts, tris, {e for e in given if e[::-1] not in given})
    except NotPlanarDelaunay as e:
        raise PropertyFailure(pid, impl, e.message + result, mesh=mesh, **e.details) from None
    if ties:
        _near_tie(pid, impl, mesh, f"{ties} interior edge(s) non-Delaunay within the float "
                  "in-circle bound: nearly cocircular points split the other way" + result)
    if on_hull and cocircular_cells(pts, tris) != delaunay_tessellation(pts):
        raise PropertyFailure(pid, impl, "every edge passes, yet the cells are not the "
                              "Delaunay tessellation" + result, mesh=mesh)


@prop("L4.14", "Rippa: 1/2 u^T (L13 - L24) u from the implementation's cotan Laplacians of the "
      "two triangulations of a convex quadrilateral equals the exact right side of (4.2); its "
      "sign is that of r1 r3 - r2 r4 (L4.15, C4.16) unless within the bound",
      needs={"cotan_laplacian"}, on_mesh=None, strategy=quads_with_values)
def rippa_energy_difference(impl, quad_u):
    from ..reference.rippa import TRIANGLES_13, TRIANGLES_24, circularity, rippa_right_side
    pts, u = quad_u
    exact = float(rippa_right_side(pts, u))
    V = [(x, y, 0) for x, y in pts]
    c13, c24 = mesh_case(V, TRIANGLES_13, "quad 13"), mesh_case(V, TRIANGLES_24, "quad 24")
    A13, A24 = implementation_dense(impl, c13, "L4.14"), implementation_dense(impl, c24, "L4.14")
    f = np.array(u, dtype=float)
    got = 0.5 * float(f @ (A13 - A24) @ f)
    af = np.abs(f)
    X13, X24 = Exact.of(c13), Exact.of(c24)
    bound = 0.5 * float(af @ (X13.B + X24.B + gamma(12) * (np.abs(A13) + np.abs(A24))) @ af)
    r = record("L4.14", abs(got - exact), bound)
    if r > 1:
        fail("L4.14", impl, c13, f"E(u13) - E(u24) = {got:.9g}, Rippa's formula gives "
              f"{exact:.9g} ({r:.3g} x the bound)", expected=exact, observed=got)
    s = circularity(pts)
    if exact != 0 and abs(got) > bound and (got > 0) != (s > 0):
        fail("L4.14", impl, c13, "the energy difference has the wrong sign for the "
              "quadrilateral's circularity (L4.15)", expected=s, observed=got)


# --- how the chapter-4 methods' answers compare on a given mesh (compare, vectors) ------------

quantity("is_locally_delaunay", bound=delaunay_ties)
quantity("intrinsic_delaunay_laplacian",
         bound=lambda example, want: DelaunayExact.of(example).Bs,
         expected=lambda example, reference: DelaunayExact.of(example).Ls,
         exact=lambda example: laplace_beltrami(example.surface))
quantity("intrinsic_delaunay_triangulation", via="intrinsic_delaunay_laplacian",
         not_on_a_mesh="not unique: checked by A4.13 and D4.8 / R4.9")
quantity("planar_flip_to_delaunay", planar=True,
         not_on_a_mesh="not unique, and needs a planar triangulation: checked by L4.3 / P4.4")
quantity("planar_delaunay", planar=True,
         not_on_a_mesh="takes planar points, not a mesh: checked by T4.1 and D4.1")
