"""Where rounding decides chapter 4's Delaunay tests: the exact value of a test as a float,
with the bound on the error of a float evaluation of it.  A value within its bound of 0 is
an (exact or near) tie, which either answer passes: an edge's cot a + cot b (D4.4), the
in-circle determinant of four planar points (D4.1), and per face and corner whether the
edge opposite it is a tie (``is_locally_delaunay``'s bound in ``compare`` and the vectors).
"""

from __future__ import annotations


import numpy as np

from ..protocol.methods import eps
from ..reference import cotangents
from ..reference.combinatorics import face_of, opposite_corner, opposite_halfedge
from ..reference.exact import float_view
from ..reference.exact.surds import rounded_root_sum

from . import memo
from .example import Example
from .harness import Exact


def cot_sum_with_bound(X: Exact, e: int) -> tuple[float, float]:
    """(cot a + cot b of edge e as float, the bound on a float evaluation's error): an edge
    whose sum is within the bound of 0 is an (exact or near) tie, which rounding decides
    (D4.4; boundary edges: the one corner)."""
    hs = [x for x in X.triangulation.edge_halfedges(e) if x >= 0]
    cots = memo.of(corner_cot_floats, X.metric)
    s = sum(float(cots[face_of(x), opposite_corner(x)]) for x in hs)
    return s, sum(X.beta[face_of(x), opposite_corner(x)] for x in hs) + 2 * eps() * abs(s)


def corner_cot_floats(metric) -> np.ndarray:
    """(m, 3): the exact corner cotangents of ``metric`` (D2.6), correctly rounded, column c
    corner c: from the integers of the fast route where the squared lengths are rational
    (``cot = N / sqrt(G)``, :mod:`~ddg_oracle.reference.cotangents`; one integer square
    root per corner), else from the metric's exact cotangents; +-inf beyond the float range
    (a needle's cotangent, as :func:`~ddg_oracle.reference.exact.surds.rounded_root_sum`)."""
    t = metric.triangulation
    if not cotangents.applies(metric):
        return np.array([[float_view(metric.corner_cot(f, c)) for c in range(3)]
                         for f in range(t.n_faces)], dtype=np.float64).reshape(-1, 3)
    fd = cotangents.face_data(metric)
    N, G = fd.N, fd.G
    # corner c of face f is opposite halfedge 3 f + c + 1 (mod 3)
    return np.array([[rounded_root_sum([(n, G[f])]) if (n := N[opposite_halfedge(f, c)])
                      else 0.0 for c in range(3)] for f in range(t.n_faces)],
                    dtype=np.float64).reshape(-1, 3)


def incircle_with_bound(a, b, c, d) -> tuple[float, float]:
    """(exact in-circle determinant of the exact points (D4.1), as float; the bound on the
    error of a float evaluation of it): Shewchuk's incircle error bound, (10 + 96 eps) eps times
    the permanent of the lifted 3 x 3 matrix, rounded up to 16 eps."""
    from ..reference.delaunay import incircle_determinant
    rows = [(p[0] - d[0], p[1] - d[1]) for p in (a, b, c)]
    lifts = [x * x + y * y for x, y in rows]
    (ax, ay), (bx, by), (cx, cy) = rows
    det = incircle_determinant(a, b, c, d)
    perm = (lifts[0] * (abs(bx * cy) + abs(cx * by)) + lifts[1] * (abs(ax * cy) + abs(cx * ay))
            + lifts[2] * (abs(ax * by) + abs(bx * ay)))
    return float(det), 16 * eps() * float(perm)


def delaunay_ties(example: Example, want=None) -> np.ndarray:
    """(m, 3) bool, per face and corner: whether the edge opposite it is an (exact or near)
    tie, its float cot sum within :func:`cot_sum_with_bound`'s bound of 0 at the current
    machine epsilon, where rounding decides and either answer agrees (D4.4's ties; the
    flat rectangles of CAD meshes are exact ties).  ``want`` unused (a quantity's bound)."""
    X = Exact.of(example)
    t = X.triangulation
    tie = np.zeros(t.n_edges, dtype=bool)
    for e in range(t.n_edges):
        s, bound = cot_sum_with_bound(X, e)
        tie[e] = abs(s) <= bound
    return np.array([[tie[t.edge_of(opposite_halfedge(f, c))] for c in range(3)]
                     for f in range(t.n_faces)], dtype=bool).reshape(t.n_faces, 3)
