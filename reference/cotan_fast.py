"""Exact cotan weights and cotan Laplacian, fast: integer arithmetic, same values.

:mod:`ddg_oracle.reference.laplacian` is the definition of the cotan weights (3.3) and of
the cotan Laplacian (D3.2): exact squared lengths and Surd face areas
(:class:`~ddg_oracle.reference.metric.PiecewiseFlatSurface`), one cotangent per corner,
weights added edge by edge.  This module computes the *same* exact values (``==`` on
every entry, tested with Hypothesis and on a 1,280-face float icosphere) about 60 times
faster on float meshes, standard library only, from the integer cotangents of
:mod:`~ddg_oracle.reference.cotangents` (per face ``G = 16 area^2``, per corner a numerator
``N``; values kept as :class:`~ddg_oracle.reference.cotangents.CotanSum`, canonical forms
on demand).  :func:`ddg_oracle.reference.laplacian.cotan_laplacian` dispatches here
whenever it applies (:func:`~ddg_oracle.reference.cotangents.applies`).

An edge weight is ``1/2 (n_1 / sqrt(G_1) + n_2 / sqrt(G_2))`` over the corners opposite
the edge; a diagonal entry of the Laplacian ``1/2 sum_f n_f / sqrt(G_f)`` over the faces
at the vertex (one positive term per face).  Whether such a value is rational, and its
sign, are decided on the integers (:mod:`~ddg_oracle.reference.cotangents`, step 2).
"""

from __future__ import annotations

from fractions import Fraction
from collections import Counter
from itertools import accumulate, chain
from math import isqrt

from .combinatorics import face_of, next_corner
from .cotangents import CotanSum, FaceData, lengths_data, face_data
from .exact.surds import simplest
from .metric import PiecewiseFlatSurface
from .sparse import SparseMatrix

__all__ = ["cotan_weights_fast", "cotan_laplacian_fast", "partly_applies",
           "cotan_laplacian_mixed"]

_ZERO = Fraction(0)


def _weight(fd: FaceData, h: int, t: int, sign: int = 1):
    """``sign`` times the cotan weight of the edge of halfedges ``h`` and ``t``
    (``t = -1``: boundary): a :class:`CotanSum` when it is certainly irrational, else
    the canonical value (a Fraction when rational)."""
    N = fd.N
    f, n1 = face_of(h), N[h] * sign
    if t < 0:
        if not n1:
            return _ZERO
        raw = (f, n1)
        return fd.value(raw) if fd.is_square(f) else fd.lazy(raw)
    g, n2 = face_of(t), N[t] * sign
    if n1 and n2:
        raw = (f, n1, g, n2)
        if fd.certainly_irrational(f, g):
            return fd.lazy(raw)
        P = fd.G[f] * fd.G[g]
        return fd.value(raw) if isqrt(P) ** 2 == P else fd.lazy(raw)
    if n1 or n2:
        raw = (f, n1) if n1 else (g, n2)
        return fd.value(raw) if fd.is_square(raw[0]) else fd.lazy(raw)
    return _ZERO


# --- the public functions -----------------------------------------------------------------


def cotan_weights_fast(surface) -> dict:
    """(3.3): the cotan weights, equal to the definition
    :func:`ddg_oracle.reference.laplacian.cotan_weights_from_corners` (the route
    :func:`~ddg_oracle.reference.laplacian.cotan_weights` takes where it applies).

    Same keys (every edge id) and values (``==``), Fractions where rational,
    irrational ones as :class:`CotanSum` (Surds whose canonical form is computed
    when first needed); see the module docstring.  For surfaces that
    :func:`applies` rejects, use the definition.

    >>> from ddg_oracle.reference import surfaces
    >>> from ddg_oracle.reference.laplacian import cotan_weights_from_corners
    >>> s = surfaces.icosahedron()
    >>> cotan_weights_fast(s) == cotan_weights_from_corners(s)
    True
    """
    t = surface.triangulation
    fd = face_data(surface)
    N, new = fd.N, object.__new__
    # the common case's raw (f, n1, g, n2) of every edge in one list, as in _laplacian
    edge_raws: list[int] = []
    extend = edge_raws.extend
    out = {}
    for e, (h, tw) in enumerate(map(t.edge_halfedges, range(t.n_edges))):
        # the common case inline (an interior edge, both corners not right, G_f G_g not a
        # square: a CotanSum), the rest through _weight; h // 3 is face_of(h) and the
        # CotanSum is made in place, in this loop over every edge
        if tw >= 0:
            n1, n2 = N[h], N[tw]
            f, g = h // 3, tw // 3
            if n1 and n2 and fd.certainly_irrational(f, g):
                k = len(edge_raws)
                extend((f, n1, g, n2))
                w = out[e] = new(CotanSum)         # FaceData.lazy_slice, written out
                w._src, w._seq, w._lo, w._hi, w._hash = fd, edge_raws, k, k + 4, None
                continue
        out[e] = _weight(fd, h, tw)
    return out


def cotan_laplacian_fast(surface) -> SparseMatrix:
    """D3.2: the cotan Laplacian, equal to the definition
    :func:`ddg_oracle.reference.laplacian.cotan_laplacian_from_weights` (``==`` entrywise).

    Diagonal: vertex ``i`` collects, from each face at one of its corners, the
    half-cotangents of the two other corners (one positive term per face); then
    each off-diagonal entry is minus the weight of the edge(s) between ``i`` and
    ``j`` (several edges between two vertices are summed, loops ignored).
    Irrational entries are :class:`CotanSum` values.

    >>> from ddg_oracle.reference import surfaces
    >>> from ddg_oracle.reference.laplacian import cotan_laplacian_from_weights
    >>> s = surfaces.torus(6, 4)
    >>> cotan_laplacian_fast(s) == cotan_laplacian_from_weights(s)
    True
    """
    return _laplacian(surface)


def partly_applies(surface) -> bool:
    """Whether :func:`cotan_laplacian_mixed` helps: a :class:`PiecewiseFlatSurface` (after
    intrinsic flips) whose squared lengths are rational on most edges."""
    if not isinstance(surface, PiecewiseFlatSurface):
        return False
    sq = surface.squared_lengths
    return 2 * sum(isinstance(x, Fraction) for x in sq) >= len(sq)


def cotan_laplacian_mixed(m: PiecewiseFlatSurface) -> SparseMatrix:
    """D3.2 on a piecewise flat surface some of whose squared lengths are irrational (a
    float mesh after intrinsic flips): the faces with three rational squared lengths by
    the integers of this module (:func:`laplacian_parts`), then each other face's three half
    cotangents (:meth:`~ddg_oracle.reference.metric.PiecewiseFlatSurface.face_cots`, the
    definition's formula, exact Surds) added to the four entries of the edge opposite
    each corner.  Equal (``==``) to :func:`~ddg_oracle.reference.laplacian.
    cotan_laplacian_from_weights` entry by entry: the same exact terms, summed in another
    order.
    """
    part, halves = laplacian_parts(m)
    rows = {i: dict(r) for i, r in part._rows.items()}
    for i, j, f, c in halves:
        half = m.face_cots(f)[c] / 2
        if not half:
            continue
        ri, rj = rows.setdefault(i, {}), rows.setdefault(j, {})
        for r, b, w in ((ri, j, -half), (rj, i, -half), (ri, i, half), (rj, j, half)):
            r[b] = r[b] + w if b in r else w
    return SparseMatrix(part.shape, rows)


def laplacian_parts(m: PiecewiseFlatSurface) -> tuple[SparseMatrix, list]:
    """D3.2 in two parts: ``(part, halves)``, ``part`` the exact Laplacian of the faces whose
    three squared lengths are rational (this module's integers), ``halves`` for every other
    face ``f`` and each of its halfedges ``i -> j`` with ``i != j`` (a loop adds nothing, as
    in the definition) a tuple ``(i, j, f, c)``: half the cotangent of corner ``c`` of face
    ``f`` (the corner opposite that halfedge) is added to ``(i, i)`` and ``(j, j)`` and
    subtracted from ``(i, j)`` and ``(j, i)``.  The Laplacian is ``part`` plus those terms
    (:func:`cotan_laplacian_mixed` adds them exactly; the float view of a flipped metric
    rounds their sums without dividing, ``ddg_oracle.properties.views``)."""
    t = m.triangulation
    sq, eo = m.squared_lengths, t.edge_of
    left_out = {f for f in range(t.n_faces)
                # inline halfedge(f, c): hot
                if not all(isinstance(sq[eo(3 * f + k)], Fraction) for k in range(3))}
    part = _laplacian(m, lengths_data(m, left_out), left_out)
    halves = []
    for f in sorted(left_out):
        # halfedge 3f + k is opposite corner k + 2 (mod 3); its edge gets half that cotangent
        # inline halfedge(f, c): hot
        for h, c in ((3 * f, 2), (3 * f + 1, 0), (3 * f + 2, 1)):
            i, j = t.tail(h), t.head(h)
            if i != j:
                halves.append((i, j, f, c))
    return part, halves


def _laplacian(surface, fd=None, left_out=()) -> SparseMatrix:
    t = surface.triangulation
    fd = face_data(surface) if fd is None else fd
    n = t.n_vertices
    N = fd.N
    faces = t.faces
    # vertex i's diagonal as pairs f, n (the faces at i and the numerators of their two
    # other corners' cotangents, summed: positive, see the module docstring) in
    # flat[start[i]:pos[i]]: one list for all vertices, not one per vertex for the garbage
    # collector to visit.  Room for two pairs per corner: on a face with a loop halfedge
    # the third vertex gets two.
    count = Counter(chain.from_iterable(faces))
    start = list(accumulate((4 * count[i] for i in range(n)), initial=0))
    pos, flat = start[:n], [0] * start[n]
    rational = [True] * n          # every face at i has a square G
    for f, (a, b, c) in enumerate(faces):
        if f in left_out:
            continue
        n2, n0, n1 = N[3 * f], N[3 * f + 1], N[3 * f + 2]  # inline halfedge(f, c): hot
        if a != b and b != c and a != c:
            # corner a: halfedges a->b (opposite corner 2) and c->a (opposite corner 1)
            p = pos[a]
            flat[p], flat[p + 1], pos[a] = f, n1 + n2, p + 2
            p = pos[b]
            flat[p], flat[p + 1], pos[b] = f, n0 + n2, p + 2
            p = pos[c]
            flat[p], flat[p + 1], pos[c] = f, n0 + n1, p + 2
            at = (a, b, c)
        else:                   # a loop halfedge (tail == head) adds nothing
            at = []
            for k, x in ((0, n2), (1, n0), (2, n1)):
                i, j = (a, b, c)[k], (a, b, c)[next_corner(k)]
                if i != j and x:
                    for v in (i, j):
                        p = pos[v]
                        flat[p], flat[p + 1], pos[v] = f, x, p + 2
                    at += (i, j)
        if not fd.is_square(f):
            for i in at:
                rational[i] = False
    rows: dict[int, dict] = {}
    lazy_slice = fd.lazy_slice
    for i, lo, hi in zip(range(n), start, pos):
        if hi > lo:
            rows[i] = {i: fd.value(flat[lo:hi]) if rational[i] else lazy_slice(flat, lo, hi)}
    # the common case's raw (f, -n1, g, -n2) of every edge, in one list (only appended to;
    # each CotanSum reads its four ints): one object, not one tuple per edge
    edge_raws: list[int] = []
    extend, new = edge_raws.extend, object.__new__
    for h, tw in map(t.edge_halfedges, range(t.n_edges)):
        # face_of(h), corner_of(h), tail and head inline in this loop over every edge;
        # face[c - 2] is face[next_corner(c)]
        f, c = divmod(h, 3)
        face = faces[f]
        i, j = face[c], face[c - 2]
        if i == j:
            continue
        n1 = N[h]
        if tw >= 0 and n1 and N[tw] and fd.certainly_irrational(f, tw // 3):
            # the common case inline, as in cotan_weights_fast: minus an irrational weight
            # (never 0: no zero test); FaceData.lazy_slice written out
            k = len(edge_raws)
            extend((f, -n1, tw // 3, -N[tw]))
            w = new(CotanSum)
            w._src, w._seq, w._lo, w._hi, w._hash = fd, edge_raws, k, k + 4, None
        else:
            w = _weight(fd, h, tw, -1)
            if not w:           # zero, or equal radicands in two spellings cancelled
                continue
        ri, rj = rows.setdefault(i, {}), rows.setdefault(j, {})
        if j in ri:                                  # another edge between i and j
            w = simplest(ri[j] + w)
            if not w:
                del ri[j], rj[i]
                continue
        ri[j] = rj[i] = w
    # exact nonzero entries already, rational ones Fractions; drop rows emptied by
    # cancelling multi-edges
    return SparseMatrix._trusted((n, n), {i: r for i, r in rows.items() if r})
