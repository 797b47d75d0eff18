"""Intrinsic Delaunay triangulations (chapter 4), exact.

Catalog rows implemented here:

* D4.4 / P4.9 -- :func:`is_delaunay_edge`: the angle criterion
  ``cot alpha + cot beta >= 0`` (alpha, beta the two angles opposite the edge;
  equivalently ``alpha + beta <= pi``).  Boundary edges are Delaunay.
  :func:`is_delaunay`: all edges are.
* T4.7 / D4.4 -- :func:`in_circumcircle`: the empty-circle criterion, computed
  independently of the angles by the exact in-circle determinant on the
  unfolded pair of triangles (:func:`ddg_oracle.reference.intrinsic.unfold`, points scaled
  by ``|ij|``, a similarity which does not change the sign).
* D4.7 / L4.17 -- :func:`harmonic_index`: ``h(T) = sum_faces (a^2 + b^2 + c^2) / A``
  (a, b, c side lengths, A area) ``= sum_faces 4 (cot + cot + cot)``.
* A4.13 / T4.12 / L4.11 / C4.19 -- :func:`flip_to_delaunay`: the edge-flip
  algorithm with a work queue; asserts that every non-Delaunay edge met is
  flippable (L4.11) and that the harmonic index strictly decreases on each flip
  (C4.19).
* R4.7 -- :func:`delaunay_tessellation_edges`: edges of a Delaunay
  triangulation with cotan weight exactly 0 are dropped.
* D4.8 / R4.9 -- :func:`laplace_beltrami`: the cotan Laplacian of a Delaunay
  triangulation of the surface (same vertex set).

Conventions: halfedge ``h = 3 f + c`` runs from corner ``c`` to corner
``c + 1`` of face ``f`` and is opposite corner ``c + 2``; squared lengths and
areas are exact (``Fraction`` or :class:`~ddg_oracle.reference.exact.Surd`); every sign is
decided exactly.
"""

from __future__ import annotations

from collections import deque

from .errors import DDGError, InputError
from . import cotangents
from .intrinsic import IntrinsicTriangulation, surface_metric, flip_obstruction, unfold
from .laplacian import cotan_laplacian, cotan_weights
from .exact import sign
from .metric import PiecewiseFlatSurface
from .exact.intervals import Interval
from .exact.lazy import Lazy, filtered_sign
from .exact.surds import Surd, exact_sum, simplest
from .combinatorics import corner_of, face_of, halfedge

__all__ = ["is_delaunay_edge", "incircle_determinant", "in_circumcircle", "is_delaunay",
           "delaunay_edges", "non_delaunay_edges",
           "face_harmonic_index", "harmonic_index", "FlipRecord", "flip_to_delaunay",
           "delaunay_tessellation_edges", "laplace_beltrami", "DelaunayError"]


class DelaunayError(DDGError, RuntimeError):
    """A statement of chapter 4 found violated at run time (L4.11 or C4.19):
    signals a bug (or a misprint), never an input problem."""


def is_delaunay_edge(surface, e: int) -> bool:
    """D4.4 / P4.9: edge ``e`` is Delaunay iff ``cot alpha + cot beta >= 0``.

    For a boundary edge: always True (D4.4 concerns interior edges only; note
    that its single opposite angle may be obtuse).

    >>> from ddg_oracle.reference import surfaces
    >>> s = surfaces.grid(1, 1).metric()
    >>> [is_delaunay_edge(s, e) for e in range(5)]
    [True, True, True, True, True]
    """
    m = surface_metric(surface)
    h, t = m.triangulation.edge_halfedges(e)
    if t < 0:
        return True
    # cot = N / (4 A) at each side: with A > 0 the sign of the sum is that of
    # N_h A_t + N_t A_h (N_h + N_t in one face), which needs no division
    f, g = face_of(h), face_of(t)
    data = (*m.face_squared_lengths(f), *m.face_squared_lengths(g), m.areas[f], m.areas[g])
    if any(isinstance(x, Lazy) for x in data):
        # lazy exact numbers (flip_to_delaunay(.., lazy=True)): the same sign, filtered
        ch, ct = corner_of(h), corner_of(t)
        return filtered_sign(lambda a, b, c, x, y, z, A_f, A_g:
                             (a + b + c - 2 * (a, b, c)[ch]) * A_g
                             + (x + y + z - 2 * (x, y, z)[ct]) * A_f, data) >= 0
    n_h, n_t = _cot_numerator(m, h), _cot_numerator(m, t)
    if f == g:
        return sign(simplest(n_h + n_t)) >= 0
    A_f, A_g = m.areas[f], m.areas[g]
    if _n_terms(n_h) * _n_terms(A_g) + _n_terms(n_t) * _n_terms(A_f) <= _SMALL_PRODUCT:
        # small products (a rational metric: one square root per area): exact at once,
        # cheaper than the enclosures
        return sign(simplest(n_h * A_g + n_t * A_f)) >= 0
    # enclosures first (relative to each factor's size: after flips the products have
    # thousands of terms, and a scaled mesh's values may lie near 2^-2400)
    for bits in (64, 256):
        s = (Interval.relative(n_h, bits) * Interval.relative(A_g, bits)
             + Interval.relative(n_t, bits) * Interval.relative(A_f, bits)).sign()
        if s is not None:
            return s > 0
    return sign(simplest(n_h * A_g + n_t * A_f)) >= 0


#: products of at most this many terms in all decide the D4.4 test exactly at once
_SMALL_PRODUCT = 8


def _n_terms(x) -> int:
    return x.n_terms if isinstance(x, Surd) else 1


def _cot_numerator(m: PiecewiseFlatSurface, h: int):
    """4 A cot of the corner opposite halfedge ``h``: ``a + b - o`` (squared lengths)."""
    a, b, c = m.face_squared_lengths(face_of(h))
    return a + b + c - 2 * (a, b, c)[corner_of(h)]


def incircle_determinant(a, b, c, d):
    """D4.1 / T4.7: the in-circle determinant of ``d`` against the circle through ``a, b,
    c`` (points as pairs; exact for exact coordinates): positive iff ``d`` is inside when
    ``(a, b, c)`` is counterclockwise, 0 iff the four are cocircular.  The one predicate
    of the intrinsic test (:func:`in_circumcircle`, on an unfolding) and the planar one
    (:func:`ddg_oracle.reference.planar.in_circle`)."""
    rows = []
    for p in (a, b, c):
        x, y = p[0] - d[0], p[1] - d[1]
        rows.append((x, y, x * x + y * y))
    (a1, a2, a3), (b1, b2, b3), (c1, c2, c3) = rows
    return a1 * (b2 * c3 - b3 * c2) - a2 * (b1 * c3 - b3 * c1) + a3 * (b1 * c2 - b2 * c1)


def in_circumcircle(surface, e: int) -> int:
    """T4.7: where the 4th vertex of the unfolded pair of ``e`` lies relative to the
    circumcircle of the other triangle: ``+1`` inside, ``0`` on, ``-1`` outside.

    Unfold the two triangles of ``e`` (``i = (0, 0)``, ``j = (e, 0)``, ``k``
    above, ``l`` below, all scaled by ``|ij|``) and take the sign of the exact
    in-circle determinant of ``l`` against the counterclockwise circle
    ``(i, j, k)``.  The relation is symmetric (``k`` against ``(j, i, l)`` gives
    the same sign).  Independent of the cotangents: ``e`` is Delaunay iff this
    is ``<= 0``.  Boundary edge: ``-1`` (no 4th vertex, Delaunay by convention).
    A degenerate unfolding where both sides lie in one face is still laid out
    (two copies of the face) and handled alike.

    >>> from ddg_oracle.reference import surfaces
    >>> in_circumcircle(surfaces.grid(1, 1).metric(), 2)     # cocircular square
    0
    """
    m = surface_metric(surface)
    h, t = m.triangulation.edge_halfedges(e)
    if t < 0:
        return -1
    i, j, k, l_ = unfold(m, e).scaled_points()
    return sign(incircle_determinant(i, j, k, l_))


def delaunay_edges(surface) -> list[bool]:
    """D4.4 for every edge, by edge id: :func:`is_delaunay_edge`, decided on the integers of
    the cotangents where the squared lengths are rational (a float mesh: one comparison of
    integer products per edge; equal to the definition, tested), else edge by edge.

    >>> from ddg_oracle.reference import surfaces
    >>> delaunay_edges(surfaces.grid(1, 1).metric())
    [True, True, True, True, True]
    """
    m = surface_metric(surface)
    known = _delaunay_by_integers(m)
    return [is_delaunay_edge(m, e) if known[e] == _UNKNOWN else known[e] == _YES
            for e in range(m.triangulation.n_edges)]


def non_delaunay_edges(surface) -> list[int]:
    """The edges failing the angle criterion (D4.4), in increasing order."""
    return [e for e, ok in enumerate(delaunay_edges(surface)) if not ok]


def is_delaunay(surface) -> bool:
    """D4.4: a triangulation is Delaunay iff every edge is (P4.9: angle criterion)."""
    return not non_delaunay_edges(surface)


def _face_data(m, f: int):
    """(a^2 + b^2 + c^2, A) of face ``f``: its harmonic index is the quotient (D4.7)."""
    a, b, c = m.face_squared_lengths(f)
    return simplest(a + b + c), simplest(m.areas[f])


def face_harmonic_index(surface, f: int):
    """D4.7: ``(a^2 + b^2 + c^2) / A`` of face ``f`` (squared side lengths over area)."""
    s, A = _face_data(surface_metric(surface), f)
    return simplest(s / A)


def harmonic_index(surface):
    """D4.7: ``h(T) = sum over faces (a^2 + b^2 + c^2) / A`` (exact).

    By L4.17 each term equals ``4 (cot + cot + cot)`` of the face's angles, and by
    L4.18 ``h(T) = 8 sum_i E(phi_i)`` over the hat functions; both are checked in
    the tests, not used here.

    >>> from ddg_oracle.reference import surfaces
    >>> harmonic_index(surfaces.grid(1, 1))       # two right isosceles: (1 + 1 + 2) / (1/2) each
    Fraction(16, 1)
    """
    m = surface_metric(surface)
    # a balanced sum: one term per face, each with its own square root on surfaces from R^3
    return simplest(exact_sum(face_harmonic_index(m, f) for f in range(m.triangulation.n_faces)))


class _History:
    """h(T) after each flip of one :func:`flip_to_delaunay` run, computed when asked."""

    def __init__(self, surface):
        self.surface = surface          # the input (immutable): h(T_0) is its harmonic index
        self.faces = []                 # per flip: ((s, A) out, (s, A) in), s = a^2 + b^2 + c^2
        self.changes = {}
        self.values = []                # h(T_0), h(T_1), ... as far as computed

    def change(self, k: int):
        c = self.changes.get(k)
        if c is None:
            out, into = self.faces[k]
            c = self.changes[k] = _exact_change(out, into)
        return c

    def h(self, k: int):
        while len(self.values) <= k:
            n = len(self.values)
            self.values.append(harmonic_index(self.surface) if n == 0 else
                               simplest(self.values[-1] + self.change(n - 1)))
        return self.values[k]


def _exact_change(out, into):
    """D4.7: h of the faces ``into`` minus h of the faces ``out``, exactly (pairs (s, A),
    s = a^2 + b^2 + c^2, A the area: each face's h is s / A)."""
    return simplest(exact_sum(s / A for s, A in into) - exact_sum(s / A for s, A in out))


def _decrease_sign(out, into) -> int:
    """C4.19: the exact sign of :func:`_exact_change` (pairs (s, A), A > 0): interval
    enclosures (:class:`~ddg_oracle.reference.exact.intervals.Interval`) at 64 and 256 bits
    relative to each value's size first, no division of square-root numbers; the exact
    quotients only when both contain 0.  Lazy exact numbers: their own enclosures decide."""
    if any(isinstance(x, Lazy) for pair in (out, into) for s_A in pair for x in s_A):
        (s1, A1), (s2, A2) = into
        (s3, A3), (s4, A4) = out
        return filtered_sign(lambda s1, A1, s2, A2, s3, A3, s4, A4:
                             s1 / A1 + s2 / A2 - s3 / A3 - s4 / A4,
                             (s1, A1, s2, A2, s3, A3, s4, A4))
    for bits in (64, 256):
        total = Interval(0)
        for direction, pairs in ((1, into), (-1, out)):
            for s, A in pairs:
                area = Interval.relative(A, bits)       # bits below each value's size
                if area.lo <= 0:
                    break
                q = Interval.relative(s, bits) / area
                total = total + q if direction > 0 else total - q
            else:
                continue
            break
        else:
            if total.sign() is not None:
                return total.sign()
    return sign(_exact_change(out, into))


class FlipRecord:
    """One flip of :func:`flip_to_delaunay`: the edge id, the exact change of h(T), and the
    quadrilateral that was flipped (``unfolding``).

    ``change`` = h(T) after - h(T) before, from the flip's two faces alone (two out, two
    in); C4.19 says it is < 0, and the loop checks its sign exactly.  ``change``,
    ``h_before`` and ``h_after`` (h(T) of the whole triangulation around the flip, D4.7)
    are computed when first asked and kept: h is a sum over all faces, which on a surface
    from R^3 has one square root per face, so a run on a real mesh builds none of them
    unless asked.
    """

    __slots__ = ("edge", "unfolding", "_history", "_index")

    def __init__(self, edge: int, history: _History, index: int, unfolding=None):
        self.edge, self._history, self._index = edge, history, index
        #: the flip's quadrilateral before the flip (:class:`~ddg_oracle.reference.intrinsic.
        #: Unfolding`: its five squared lengths, two areas and the new diagonal, exact)
        self.unfolding = unfolding

    @property
    def change(self):
        return self._history.change(self._index)

    @property
    def h_before(self):
        return self._history.h(self._index)

    @property
    def h_after(self):
        return self._history.h(self._index + 1)

    def __eq__(self, other):
        if not isinstance(other, FlipRecord):
            return NotImplemented
        return (self.edge, self.change, self.h_before) == (other.edge, other.change, other.h_before)

    __hash__ = None

    def __repr__(self):
        return f"FlipRecord(edge={self.edge}, change={self.change})"


def _edges_of_face(tri, f: int):
    return [tri.edge_of(halfedge(f, c)) for c in range(3)]


def flip_to_delaunay(surface, max_flips: int | None = None, lazy: bool = False):
    """A4.13: flip non-Delaunay edges until none is left; returns ``(surface, log)``.

    ``log`` is a list of :class:`FlipRecord`: the edge, the exact change of the
    harmonic index (D4.7), computed locally (two faces out, two in), and h of the
    whole triangulation before and after each flip, computed when asked.

    A work queue holds the edges to examine, initially all; after flipping
    ``e`` the four other edges of its two faces are queued again (only they
    change their opposite angles).  Every non-Delaunay edge is flippable (L4.11)
    and the flipped edge is Delaunay; each flip strictly decreases h (C4.19).
    Should any of these ever fail, :class:`DelaunayError` is raised, naming the
    edge.  Terminates (T4.12); ``max_flips`` (optional) bounds the number of
    flips and raises :class:`DelaunayError` if exceeded.

    The flips run in place on an
    :class:`~ddg_oracle.reference.intrinsic.IntrinsicTriangulation` (O(1) each, the
    surface is frozen once at the end); the result and the log are those of
    the same loop written with :func:`ddg_oracle.reference.intrinsic.flip` (tested).

    ``lazy=True``: the flipped squared lengths and areas are lazy exact numbers
    (:class:`~ddg_oracle.reference.exact.lazy.Lazy`, ``IntrinsicTriangulation(.., lazy=True)``):
    every decision is the same exact sign, taken from enclosures where they decide (the
    same flips, tested), and the exact forms are computed only where asked.  On a surface
    from R^3 the exact forms grow with each flip (hundreds of square roots after a few
    dozen): a 346-face CAD mesh's 231 flips take minutes, lazily well under a second.

    >>> from ddg_oracle.reference import surfaces
    >>> from ddg_oracle.reference.intrinsic import flip
    >>> s = flip(surfaces.grid(2, 1).metric(), 2)
    >>> d, log = flip_to_delaunay(s)
    >>> is_delaunay(d), len(log)
    (True, 0)
    """
    m = surface_metric(surface)
    history = _History(m)
    # each edge's test on the input, by integers where the squared lengths are rational;
    # an edge keeps its answer until a flip changes one of its faces (then UNKNOWN)
    known = _delaunay_by_integers(m)
    m = IntrinsicTriangulation(m, lazy)     # flipped in place, frozen at the end
    tri = m.triangulation                   # a live view: changes with every flip
    queue = deque(range(tri.n_edges))
    queued = [True] * tri.n_edges
    log = []
    while queue:
        e = queue.popleft()
        queued[e] = False
        if lazy and known[e] != _YES:
            # its faces' values as lazy leaves: enclosures decide the test and the flip
            m.make_lazy(*{face_of(x) for x in tri.edge_halfedges(e) if x >= 0})
        if is_delaunay_edge(m, e) if known[e] == _UNKNOWN else known[e] == _YES:
            continue
        if max_flips is not None and len(log) >= max_flips:
            raise DelaunayError(f"more than max_flips = {max_flips} flips needed")
        u, reason = flip_obstruction(m, e)
        if reason is not None:
            raise DelaunayError(f"L4.11 violated: edge {e} {tri.edge_vertices(e)} "
                                "is not Delaunay but cannot be flipped")
        f, g = u.faces
        out = (_face_data(m, f), _face_data(m, g))
        m.flip_unfolded(u)
        into = (_face_data(m, f), _face_data(m, g))
        if not is_delaunay_edge(m, e):
            raise DelaunayError(f"L4.11 violated: the flipped edge {e} is not Delaunay")
        if _decrease_sign(out, into) >= 0:
            raise DelaunayError(f"C4.19 violated: flipping edge {e} did not decrease the "
                                f"harmonic index (faces {f}, {g}: (a^2 + b^2 + c^2, A) "
                                f"{out} -> {into})")
        history.faces.append((out, into))
        log.append(FlipRecord(e, history, len(log), u))
        for x in _edges_of_face(tri, f) + _edges_of_face(tri, g):
            known[x] = _UNKNOWN
            if x != e and not queued[x]:
                queued[x] = True
                queue.append(x)
    return m.surface(), log


_NO, _YES, _UNKNOWN = 0, 1, 2


def _delaunay_by_integers(m: PiecewiseFlatSurface) -> bytearray:
    """Per edge _YES or _NO: :func:`is_delaunay_edge` decided on the integers of
    :func:`~ddg_oracle.reference.cotangents.face_data` (``cot = N / sqrt(G)`` per corner):
    ``N_h / sqrt(G_f) + N_t / sqrt(G_g) >= 0`` by the signs of the N, and for opposite
    signs by ``N^2 G`` of one side against the other's (exact).  All _UNKNOWN where the
    squared lengths are not all rational (the definition then decides each edge)."""
    t = m.triangulation
    if not cotangents.applies(m):
        return bytearray([_UNKNOWN]) * t.n_edges
    fd = cotangents.face_data(m)
    N, G = fd.N, fd.G
    out = bytearray(t.n_edges)
    for e in range(t.n_edges):
        h, k = t.edge_halfedges(e)
        if k < 0:
            out[e] = _YES                       # a boundary edge (D4.4: interior edges only)
            continue
        a, b = N[h], N[k]
        f, g = face_of(h), face_of(k)
        if f == g:
            ok = a + b >= 0
        elif a >= 0 and b >= 0:
            ok = True
        elif a <= 0 and b <= 0:
            ok = False                          # one < 0, neither > 0: the sum is < 0
        elif a > 0:
            ok = a * a * G[g] >= b * b * G[f]   # a / sqrt(G_f) >= -b / sqrt(G_g)
        else:
            ok = b * b * G[f] >= a * a * G[g]
        out[e] = _YES if ok else _NO
    return out


def delaunay_tessellation_edges(surface) -> set[int]:
    """R4.7: the edges of the Delaunay tessellation, as edge ids of ``surface``.

    ``surface`` must be a Delaunay triangulation (else :class:`InputError`; use
    :func:`flip_to_delaunay` first).  Kept: every boundary edge, and every
    interior edge with cotan weight ``!= 0`` (by P4.10 the weights are ``>= 0``;
    weight 0 means the two triangles are inscribed in one circle, so the edge
    only splits a cell of the tessellation).
    """
    m = surface_metric(surface)
    bad = non_delaunay_edges(m)
    if bad:
        raise InputError(f"not a Delaunay triangulation: edges {bad[:10]} fail the angle "
                         "criterion (use flip_to_delaunay first)")
    tri = m.triangulation
    return {e for e, w in cotan_weights(m).items()
            if tri.is_boundary_edge(e) or sign(w) != 0}


def laplace_beltrami(surface):
    """D4.8: the discrete Laplace-Beltrami operator, the cotan Laplacian
    (:func:`ddg_oracle.reference.laplacian.cotan_laplacian`, exact
    :class:`~ddg_oracle.reference.sparse.SparseMatrix`) of a Delaunay triangulation of the
    surface reached by :func:`flip_to_delaunay`.  Same vertex set and order.
    By R4.9 it does not depend on which Delaunay triangulation is reached."""
    return cotan_laplacian(flip_to_delaunay(surface)[0])
