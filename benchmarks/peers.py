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

import math
from collections import deque
from fractions import Fraction

from ddg_oracle.reference.delaunay import face_harmonic_index, harmonic_index, is_delaunay_edge
from ddg_oracle.reference.intrinsic import flip, is_flippable
from ddg_oracle.reference.exact.angles import Angle, _f2_basis, _mask, _nearest_pi24, _primitive
from ddg_oracle.reference.exact.terms import reexpress, refine, t_add, t_mul, t_scale, t_sign


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


# --- the exact zero test of angles as it was before 2026-12-06 (side by side) ------------------
# reference/exact/angles.py's _pi24_multiple and the helpers that changed since, at 3430653,
# unchanged but for the name: cotangents as single Surds (no Surd.ratio), terms keyed by
# radicands (a gcd per product of two square roots), two full complex products per split;
# _primitive, _mask and _f2_basis are the module's own (unchanged).


def pi24_multiple_before(parts: dict) -> int | None:
    """k when sum m arccot(c) over ``parts`` is exactly k pi / 24, else None: the exact
    zero test as it was (the mathematics: ``reference.exact.angles._pi24_multiple``)."""
    base = refine([b for c in parts for b in c.base])
    bits: dict[int, int] = {}                       # radicand -> bit mask over base
    factors: dict[int, list] = {}                   # S (mask) -> [(e_S(u_c), m_c, d_c, key)]
    for c, m in parts.items():
        terms = c._terms if all(b in base for b in c.base) else reexpress(c._terms, base)
        # u_c = (c + i)^2 / (c^2 + 1): kept, like everything below, only up to a positive
        # real factor (integer coefficients, no Fraction arithmetic); see the test below
        c2 = t_mul(terms, terms)
        w = _primitive((t_add(c2, {1: -1})[0], t_scale(terms, 2)))
        basis = _f2_basis([_mask(r, base, bits) for r in terms if r != 1])
        items = [(w, 0)]
        for v, pivot in basis:
            b = base[pivot]
            items = [z for w, s in items for z in _split(w, s, b, v)]
        key = tuple(sorted(terms))
        for w, s in items:
            rad = math.prod(base[i] for i in range(len(base)) if s >> i & 1)
            if any(r != 1 and r != rad for part in w for r in part):   # pragma: no cover
                raise AssertionError(f"e_S(u) is not in Q(i, sqrt({rad})): a wrong character")
            factors.setdefault(s, []).append((w, m, len(basis), key))
    for group in factors.values():
        top = max(d for _, _, d, _ in group)
        by_key: dict[tuple, list] = {}
        for w, m, d, key in group:
            if m < 0:                   # w^-1 is conj(w) / |w|^2: its conjugate, up to > 0
                w, m = (w[0], {r: -q for r, q in w[1].items()}), -m
            by_key.setdefault(key, []).append(_tpow(w, m << (top - d)))
        # X_S times a positive real: X_S^24 == 1 iff that power is a positive real
        x, y = _tpow(_tprod([_tprod(ws) for ws in by_key.values()]), 24)
        if y or t_sign(x, ()) <= 0:
            return None
    return _nearest_pi24(Angle._raw(parts, Fraction(0)))


def _split(w, s: int, b: int, v: int):
    """The two halves w sigma(w) and w / sigma(w) of w under sigma: sqrt b -> -sqrt b.

    Up to a positive real factor (cotangents are real, so |sigma(w)|^2 > 0), w / sigma(w)
    is w * conj(sigma(w)); the second half carries the character of ``v`` (``s ^ v``).
    """
    x, y = w
    fx = {r: (-q if r % b == 0 else q) for r, q in x.items()}
    fy = {r: (-q if r % b == 0 else q) for r, q in y.items()}
    yield _tmul(w, (fx, fy)), s
    yield _tmul(w, (fx, {r: -q for r, q in fy.items()})), s ^ v


def _tmul(z, w):
    """Complex product of (real, imaginary) term dicts over one base, made primitive."""
    (a, b), (c, d) = z, w
    return _primitive((t_add(t_mul(a, c), t_mul(b, d), negate=True)[0],
                       t_add(t_mul(a, d), t_mul(b, c))[0]))


def _tpow(z, n: int):
    """z**n, n >= 0, by repeated squaring."""
    out = ({1: 1}, {})
    while n:
        if n & 1:
            out = _tmul(out, z)
        n >>= 1
        if n:
            z = _tmul(z, z)
    return out


def _tprod(zs: list):
    """The product of ``zs`` by a balanced tree (operands of similar size)."""
    if not zs:
        return ({1: 1}, {})
    while len(zs) > 1:
        zs = [_tmul(zs[i], zs[i + 1]) if i + 1 < len(zs) else zs[i] for i in range(0, len(zs), 2)]
    return zs[0]
