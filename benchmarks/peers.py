"""Other ways to compute what the reference computes, for side-by-side timings.

Exact cotan weights, each from float positions ``V`` (taken exactly) and faces
``F``; the exact weight of an edge is ``sum over its faces of q_f sqrt(G_f)``
(``q = N / (2 G)``, ``N`` the dot product at the opposite corner,
``G = |u x v|^2``, see ddg_oracle.reference.cotangents):

* :func:`weights_fractions`: straightforward ``fractions.Fraction`` code, the
  weight kept as its list of ``(q, G)`` pairs (exact, no canonical form, so no
  exact equality test);
* :func:`weights_gmpy2`: the same with ``gmpy2.mpq`` (optional);
* :func:`weights_sympy`: sympy ``Rational`` and ``sqrt``, canonical sympy
  expressions (optional);
* :func:`laplacian_libigl`: libigl's float ``cotmatrix``;
* :func:`weights_numpy`: vectorised float64 cotangents.

:func:`flip_to_delaunay_immutable`: the flip algorithm as it was before
issue 7, one immutable (O(F)) flip at a time; the tests check that it gives
what :func:`ddg_oracle.reference.delaunay.flip_to_delaunay` gives.
"""

from __future__ import annotations

from collections import deque
from fractions import Fraction

from ddg_oracle.reference.delaunay import face_harmonic_index, harmonic_index, is_delaunay_edge
from ddg_oracle.reference.intrinsic import flip, is_flippable


def _faces(V, F, number):
    """Per face ``(a, b, c, uu, vv, uv)``: the Gram entries of ``u = B - A``,
    ``v = C - A`` with the coordinates converted by ``number``."""
    P = [tuple(number(x) for x in p) for p in V]
    for a, b, c in F:
        A, B, C = P[a], P[b], P[c]
        u = [y - x for x, y in zip(A, B)]
        v = [y - x for x, y in zip(A, C)]
        yield (a, b, c, sum(x * x for x in u), sum(x * x for x in v),
               sum(x * y for x, y in zip(u, v)))


def _weights(V, F, number):
    w = {}
    for a, b, c, uu, vv, uv in _faces(V, F, number):
        G = uu * vv - uv * uv
        for (i, j), N in (((a, b), vv - uv), ((b, c), uv), ((c, a), uu - uv)):
            w.setdefault((i, j) if i < j else (j, i), []).append((N / (2 * G), G))
    return w


def weights_fractions(V, F):
    return _weights(V, F, Fraction)


def weights_gmpy2(V, F):
    import gmpy2
    return _weights(V, F, gmpy2.mpq)


def weights_sympy(V, F):
    import sympy
    sympy.core.cache.clear_cache()     # else a repeated run reuses every square root
    w = {}
    for a, b, c, uu, vv, uv in _faces(V, F, sympy.Rational):
        root = sympy.sqrt(uu * vv - uv * uv)
        for (i, j), N in (((a, b), vv - uv), ((b, c), uv), ((c, a), uu - uv)):
            key = (i, j) if i < j else (j, i)
            w[key] = w.get(key, 0) + N / (2 * root)
    return w


def laplacian_libigl(V, F):
    import igl
    return igl.cotmatrix(V, F)


def weights_numpy(V, F):
    import numpy as np
    a, b, c = (V[F[:, k]] for k in range(3))
    out = []
    for p, q, r in ((c, a, b), (a, b, c), (b, c, a)):      # corner p, edge q-r
        x, y = q - p, r - p
        out.append(np.einsum("ij,ij->i", x, y) / np.linalg.norm(np.cross(x, y), axis=1) / 2)
    return out


def flip_to_delaunay_immutable(m):
    """A4.13 with one immutable flip (O(F)) at a time: the loop before issue 7.
    Returns ``(surface, [(edge, h_before, h_after), ...])``."""
    queue = deque(range(m.triangulation.n_edges))
    queued = [True] * m.triangulation.n_edges
    h_total, log = harmonic_index(m), []
    while queue:
        e = queue.popleft()
        queued[e] = False
        if is_delaunay_edge(m, e):
            continue
        assert is_flippable(m, e), f"L4.11: edge {e} is not Delaunay but not flippable"
        h, t = m.triangulation.edge_halfedges(e)
        f, g = h // 3, t // 3
        old = face_harmonic_index(m, f) + face_harmonic_index(m, g)
        m = flip(m, e)
        new = face_harmonic_index(m, f) + face_harmonic_index(m, g)
        log.append((e, h_total, h_total - old + new))
        h_total = h_total - old + new
        for x in (m.triangulation.edge_of(3 * y + c) for y in (f, g) for c in range(3)):
            if x != e and not queued[x]:
                queued[x] = True
                queue.append(x)
    return m, log
