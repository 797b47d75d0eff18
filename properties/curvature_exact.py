"""Chapter 2's expected values beyond the float views of :mod:`.views`: the integral of a
convex polyhedron's support function (T2.7), R2.5's Steiner coefficients as floats within
a stated error, and what ``compare`` and the test vectors hold the curvature methods'
answers to (the exact mean curvature keyed by vertex pair, the bound of the total area).
"""

from __future__ import annotations

import math

import numpy as np

from ..protocol.methods import FLOAT64_EPSILON
from ..reference import curvature as ref

from .bounds import area_tolerance, area_view, gamma, total_area_view
from .example import Example
from .registry import EXACT_SUM_LIMIT
from .views import mean_curvature_view_bounds, mean_curvature_views


def support_function_integral(points, n_theta: int = 256, n_coarse: int = 16) -> tuple[float, float]:
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

    Coarse to fine: the test runs first on n_coarse x 2 n_coarse blocks of cells, and
    only a block it cannot decide is split in four, down to the cells themselves.  A
    decided block is every one of its cells decided (the integral is additive), so the
    cells left undecided are a subset of those a test of every cell leaves: the bound is
    no larger, for a small fraction of the work (the undecided cells lie along the
    boundaries of the vertices' normal cones).
    """
    P = np.asarray(points, dtype=np.float64)
    P = P - P.mean(axis=0)
    R = float(np.sqrt((P * P).sum(axis=1)).max())
    # every block's sides are lines of the finest grid: the blocks partition the sphere
    th = np.linspace(0.0, np.pi, n_theta + 1)
    ph = np.linspace(0.0, 2 * np.pi, 2 * n_theta + 1)
    D = np.sqrt(((P[:, None, :] - P[None, :, :]) ** 2).sum(-1))
    step = n_theta // n_coarse
    if n_theta % n_coarse or step & (step - 1):
        raise ValueError("n_theta must be n_coarse times a power of two")
    I, J = np.meshgrid(np.arange(0, n_theta, step), np.arange(0, 2 * n_theta, step), indexing="ij")
    I, J = I.ravel(), J.ravel()
    exact_parts = []
    while True:
        t0, t1, f0, f1 = th[I], th[I + step], ph[J], ph[J + step]
        tc, fc, dt, df = (t0 + t1) / 2, (f0 + f1) / 2, t1 - t0, f1 - f0
        smax = np.where((t0 <= np.pi / 2) & (t1 >= np.pi / 2), 1.0, np.maximum(np.sin(t0), np.sin(t1)))
        r = dt / 2 + smax * df / 2            # geodesic (hence chordal) radius about the centre
        uc = np.stack([np.sin(tc) * np.cos(fc), np.sin(tc) * np.sin(fc), np.cos(tc)], axis=-1)
        vals = uc @ P.T
        top = vals.argmax(axis=1)
        rows = np.arange(len(top))
        best = vals[rows, top]
        margin = best[:, None] - vals - D[top] * r[:, None]
        margin[rows, top] = np.inf
        pure = (margin > 0).all(axis=1)
        # the integral of u over a block, in closed form
        sin2 = dt[pure] / 2 - (np.sin(2 * t1[pure]) - np.sin(2 * t0[pure])) / 4    # of sin^2
        sincos = (np.sin(t1[pure]) ** 2 - np.sin(t0[pure]) ** 2) / 2               # of sin cos
        U = np.stack([sin2 * (np.sin(f1[pure]) - np.sin(f0[pure])),
                      sin2 * (np.cos(f0[pure]) - np.cos(f1[pure])), sincos * df[pure]], axis=-1)
        exact_parts.append((U * P[top[pure]]).sum(axis=1))
        if step == 1:
            area = (np.cos(t0) - np.cos(t1)) * df
            approx_part = best[~pure] * area[~pure]
            bound = float((area[~pure] * R * r[~pure]).sum())
            break
        step //= 2
        I, J = I[~pure], J[~pure]
        I, J = np.concatenate([I, I, I + step, I + step]), np.concatenate([J, J + step, J, J + step])
    exact_part = np.concatenate(exact_parts)
    value = float(exact_part.sum() + approx_part.sum())
    # our own float64 sums: float64's gamma, whatever the checked implementation declares
    bound += gamma(len(exact_part) + len(approx_part) + 16, FLOAT64_EPSILON) * float(
        np.abs(exact_part).sum() + np.abs(approx_part).sum())
    return value, bound


def steiner_area_view(case: Example) -> tuple[float, float]:
    """(A, err_A): R2.5's area as a float within err_A of the exact one.  Up to
    EXACT_SUM_LIMIT faces the exact sum correctly rounded (err 0); beyond, an exact sum
    has a square root per face: :func:`~.bounds.area_view` (err about 3 u A).  The check
    widens its bound by err: a pass is then certain; a failure by less than err (about
    1e-16 relative) would go unseen."""
    if len(case.faces) <= EXACT_SUM_LIMIT:
        return float(_steiner(case)[0]), 0.0
    return area_view(case.surface)


def steiner_mean_curvature_view(case: Example) -> tuple[float, float]:
    """(2 H(S), err_H): R2.5's total mean curvature as a float within err_H of the exact
    one.  Up to EXACT_SUM_LIMIT faces the exact sum correctly rounded (err 0); beyond,
    2 fsum of the correctly rounded H(e) (each within u |H(e)|, the fsum within u of its
    value: err_H = 2 u sum |H(e)| + u |2 H(S)|, with a factor 1.0001 for |H(e)| <= (1 + u)
    |its float|), widening the check's bound as err_A does."""
    if len(case.faces) <= EXACT_SUM_LIMIT:
        return float(_steiner(case)[1]), 0.0
    views = list(mean_curvature_views(case.surface).values())
    twoH = 2 * math.fsum(views)
    return twoH, _fsum_err(views, twoH)


def _steiner(case: Example):
    return case.derived("steiner", lambda c: ref.steiner_coefficients(c.surface))


def _fsum_err(views, twoH: float) -> float:
    u = 2.0 ** -53
    return 1.0001 * u * (2 * math.fsum(abs(h) for h in views) + abs(twoH))


def twice_mean_curvature_range(case: Example) -> tuple[float, float, float] | None:
    """(lo, hi, err): beyond EXACT_SUM_LIMIT faces, :func:`steiner_mean_curvature_view`'s
    2 H(S) lies in [lo, hi] and its err_H is at least ``err``, from the enclosures of the
    H(e) alone (:func:`~.views.mean_curvature_view_bounds`: each correctly rounded H(e) in
    [lo_e, hi_e]; fsum is monotone in each term, err_H in each |H(e)| and in |2 H(S)|).  A
    check that holds at both ends within a bound widened by ``err`` holds for the exact
    views.
    None up to EXACT_SUM_LIMIT faces (the exact sums are cheap there)."""
    if len(case.faces) <= EXACT_SUM_LIMIT:
        return None
    _, _, lo, hi = mean_curvature_view_bounds(case.surface)
    if not (np.isfinite(lo).all() and np.isfinite(hi).all()):
        return None
    low, high = 2 * math.fsum(lo.tolist()), 2 * math.fsum(hi.tolist())
    least = np.where((lo <= 0) & (hi >= 0), 0.0, np.minimum(np.abs(lo), np.abs(hi)))
    least_total = 0.0 if low <= 0 <= high else min(abs(low), abs(high))
    # the float formula of err_H is monotone in each input: at the least |H(e)| it is least
    return low, high, _fsum_err(least.tolist(), least_total)


def area_bound(example: Example, want) -> float:
    """The bound of ``area`` against the reference's answer (``compare``, the vectors)."""
    # the reference's answer is the exact total correctly rounded: within u A of it
    return area_tolerance(example) + total_area_view(example.surface.metric())[1]


def mean_curvature_by_pair(example: Example) -> dict:
    """D2.3: {(i, j) with i < j: H(e)} exactly, keyed by the edge's vertices."""
    t = example.surface.triangulation
    return {tuple(sorted(t.edge_vertices(e))): h
            for e, h in ref.mean_curvature(example.surface).items()}
