"""Intrinsic edge flips on piecewise flat surfaces (L2.8, X2.5; the tool of chapter 4).

An edge ``e`` of a geodesic triangulation is the common side of two triangles.
Unfolding them into the plane gives a quadrilateral with ``e`` as a diagonal;
when the two triangles are distinct and the quadrilateral is strictly convex,
``e`` can be replaced by the other diagonal (Lemma 2.8).  The result is a new
geodesic triangulation of the *same* piecewise flat surface, which need not be
regular and need not come from any polyhedron in R^3 (Example 2.5).

Names.  Let ``h: i -> j`` be the first halfedge of ``e`` (``edge_halfedges(e)[0]``)
in face ``f = (i, j, k)`` and ``t`` its twin in face ``g``, whose third vertex
is ``l``.  Squared lengths and areas:

    e = |ij|^2,  a = |jk|^2,  b = |ki|^2,  c = |il|^2,  d = |lj|^2,
    A1 = area(i, j, k),  A2 = area(j, i, l).

The unfolding, exactly.  Place ``i`` at the origin, ``j`` on the positive
x-axis, ``k`` above and ``l`` below it.  With ``s = sqrt(e)`` the coordinates
are ``k = ((e + b - a)/(2s), 2 A1/s)`` and ``l = ((e + c - d)/(2s), -2 A2/s)``.
Multiplying by ``s`` (a similarity) removes every square root:

    i = (0, 0),  j = (e, 0),  k = ((e + b - a)/2, 2 A1),  l = ((e + c - d)/2, -2 A2)

(:meth:`Unfolding.scaled_points`).  From these, with no new square root:

    |kl|^2       = b + c - (e + b - a)(e + c - d)/(2e) + 8 A1 A2 / e
    area(l,k,i)  = ((e + b - a) A2 + (e + c - d) A1) / (2e)     (the new triangle at i)
    area(k,l,j)  = ((e + a - b) A2 + (e + d - c) A1) / (2e)     (the new triangle at j)

(the second is ``A1 + A2 - area(l,k,i)``; both are signed areas, counterclockwise
positive).  So a surface whose squared lengths and areas are rational stays
rational under any number of flips, and one whose data lie in a field
``Q(sqrt r_1, ..., sqrt r_n)`` stays in that field: no nested radical ever appears.

Convexity, exactly (L2.8).  The quadrilateral ``i, l, j, k`` always has angles
< pi at ``k`` and ``l`` (triangle angles).  At ``i`` its angle is
``alpha + beta`` with ``alpha`` the angle of ``f`` and ``beta`` that of ``g``,
both in (0, pi), and ``sin(alpha + beta) = sin alpha sin beta (cot alpha + cot beta)``.
Hence ``alpha + beta < pi`` iff ``cot alpha + cot beta > 0``; with
``cot alpha = (e + b - a)/(4 A1)`` and ``cot beta = (e + c - d)/(4 A2)`` this is

    N_i = (e + b - a) A2 + (e + c - d) A1 > 0,   i.e.  area(l,k,i) > 0,

and likewise ``N_j = (e + a - b) A2 + (e + d - c) A1 > 0`` at ``j``.  ``N = 0``
means the angle is exactly pi (``k``, ``i``, ``l`` collinear: the new
triangle would be degenerate), so strict convexity is required.  Both signs
are decided exactly (:meth:`~ddg_oracle.reference.exact.Surd.sign`).

Squared lengths that become irrational (surfaces from R^3) are stored as
:class:`~ddg_oracle.reference.exact.Surd` values; rational ones stay ``Fraction``.

>>> from ddg_oracle.reference import surfaces
>>> s = surfaces.grid(1, 1).metric()     # unit square; edge 2 is the diagonal (1,1)-(0,0)
>>> is_flippable(s, 2), is_flippable(s, 0)
(True, False)
>>> r = flip(s, 2)                        # the other diagonal (1,0)-(0,1)
>>> r.triangulation.edge_vertices(2), r.squared_lengths[2], r.areas
((2, 1), Fraction(2, 1), (Surd('1/2'), Surd('1/2')))
>>> flip(r, 2).squared_lengths == s.squared_lengths
True
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property

from .combinatorics import Triangulation, TriangulationBuilder, checked_index, face_of, opposite_corner
from .errors import InputError, NotFlippable, TermLimitExceeded
from .exact import Surd, sign
from .exact.lazy import Lazy, flipped
from .exact.surds import simplest
from .metric import PiecewiseFlatSurface

__all__ = ["Unfolding", "unfold", "is_flippable", "flip", "IntrinsicTriangulation",
           "cot_sum", "regular_tetrahedron_flip"]


def surface_metric(surface) -> PiecewiseFlatSurface:
    if isinstance(surface, (PiecewiseFlatSurface, IntrinsicTriangulation)):
        return surface
    metric = getattr(surface, "metric", None)
    if callable(metric):                       # a PolyhedralSurface
        return metric()
    raise InputError(f"expected a PiecewiseFlatSurface or a PolyhedralSurface, "
                     f"got {type(surface).__name__}")


@dataclass(frozen=True)
class Unfolding:
    """The two triangles of an interior edge laid out in the plane (exact).

    ``h: i -> j`` is the first halfedge of ``edge`` in face ``f = (i, j, k)``,
    ``t`` its twin in face ``g`` with third vertex ``l`` (see the module
    docstring).  The quadrilateral is given by its five squared lengths and two
    areas; :meth:`scaled_points` gives exact coordinates scaled by ``|ij|``.
    ``f == g`` is possible (both sides of the edge in one face: two copies of
    that face are laid out); such an edge is not flippable.
    """

    edge: int
    halfedges: tuple            # (h, t)
    faces: tuple                # (f, g)
    vertices: tuple             # (i, j, k, l), vertex ids (may repeat)
    sq_ij: object               # e
    sq_jk: object               # a
    sq_ki: object               # b
    sq_il: object               # c
    sq_lj: object               # d
    area_ijk: object            # A1
    area_jil: object            # A2

    def scaled_points(self):
        """``(i, j, k, l)`` as exact points of the plane, scaled by ``|ij|``:
        ``i = (0, 0)``, ``j = (e, 0)``, ``k = ((e + b - a)/2, 2 A1)``,
        ``l = ((e + c - d)/2, -2 A2)``."""
        e, a, b, c, d = self.sq_ij, self.sq_jk, self.sq_ki, self.sq_il, self.sq_lj
        zero = Fraction(0)
        return ((zero, zero), (e, zero), ((e + b - a) / 2, 2 * self.area_ijk),
                ((e + c - d) / 2, -2 * self.area_jil))

    @cached_property
    def _n(self):
        # N_i = S + P, N_j = S - P with S = e (A1 + A2), P = (b - a) A2 + (c - d) A1:
        # three products instead of four (they dominate on surfaces from R^3)
        e, a, b, c, d = self.sq_ij, self.sq_jk, self.sq_ki, self.sq_il, self.sq_lj
        s = e * (self.area_ijk + self.area_jil)
        p = (b - a) * self.area_jil + (c - d) * self.area_ijk
        return s + p, s - p

    @property
    def _n_i(self):
        return self._n[0]

    @property
    def _n_j(self):
        return self._n[1]

    @cached_property
    def _lazy(self):
        # the flip as lazy exact numbers (.exact.lazy) when the data are (flip_to_delaunay's
        # lazy mode): enclosures decide, the exact values are computed where asked
        data = (self.sq_ij, self.sq_jk, self.sq_ki, self.sq_il, self.sq_lj, self.area_ijk,
                self.area_jil)
        return flipped(*data) if any(isinstance(x, Lazy) for x in data) else None

    @cached_property
    def _inv_2e(self):
        # one exact inverse per flip: for an irrational e it is the costly step
        return 1 / (2 * self.sq_ij)

    @cached_property
    def new_squared_length(self):
        """``|kl|^2 = b + c - (e + b - a)(e + c - d)/(2e) + 8 A1 A2 / e`` (exact)."""
        if self._lazy:
            return self._lazy[0]
        e, a, b, c, d = self.sq_ij, self.sq_jk, self.sq_ki, self.sq_il, self.sq_lj
        return simplest(b + c + ((-(e + b - a)) * (e + c - d)
                                + 16 * self.area_ijk * self.area_jil) * self._inv_2e)

    @cached_property
    def new_area_at_i(self):
        """Signed area of the new triangle ``(l, k, i)``: ``N_i / (2e)``."""
        if self._lazy:
            return self._lazy[1]
        return simplest(self._n_i * self._inv_2e)

    @cached_property
    def new_area_at_j(self):
        """Signed area of the new triangle ``(k, l, j)``: ``N_j / (2e)``
        ``= A1 + A2 - area(l, k, i)`` (computed so)."""
        if self._lazy:
            return self._lazy[2]
        return simplest(self.area_ijk + self.area_jil - self.new_area_at_i)

    def convexity(self):
        """``(sign at i, sign at j)``: the signs of ``N_i`` and ``N_j``, i.e. of
        ``pi - (angle sum of the two triangles)`` at ``i`` and at ``j``."""
        if self._lazy:                  # N = 2e times the new area at that end, e > 0
            return sign(self._lazy[1]), sign(self._lazy[2])
        return sign(self._n_i), sign(self._n_j)


def unfold(surface, e: int) -> Unfolding:
    """The two triangles of the interior edge ``e`` unfolded into the plane (exact).

    Reads the five squared lengths and two areas by halfedge position, not by
    vertex id, so loops, multiple edges and orientation-reversing gluings are
    handled.  Raises :class:`~ddg_oracle.reference.errors.NotFlippable` for a boundary edge
    (it has one triangle only).

    >>> from ddg_oracle.reference import surfaces
    >>> u = unfold(surfaces.grid(1, 1).metric(), 2)      # the diagonal 3 -> 0 of the unit square
    >>> u.vertices, u.sq_ij, u.area_ijk, u.new_squared_length
    ((3, 0, 2, 1), Fraction(2, 1), Fraction(1, 2), Fraction(2, 1))
    >>> u.scaled_points()[2:]                          # k and l, scaled by |ij| = sqrt(2)
    ((Fraction(1, 1), Fraction(1, 1)), (Fraction(1, 1), Fraction(-1, 1)))
    """
    m = surface_metric(surface)
    tri = m.triangulation
    e = checked_index(e, tri.n_edges, "edge")
    h, t = tri.edge_halfedges(e)
    i, j = tri.tail(h), tri.head(h)
    if t < 0:
        raise NotFlippable(f"edge {e} ({i}-{j}) is a boundary edge: it has one triangle only, "
                           "nothing to unfold or flip")
    f, g = face_of(h), face_of(t)
    k = tri.faces[f][opposite_corner(h)]
    l_ = tri.faces[g][opposite_corner(t)]
    sq = m.squared_length
    nt, pt = tri.next(t), tri.prev(t)
    if tri.reversed_gluing(h):       # t: i -> j too, so next(t): j -> l, prev(t): l -> i
        c, d = sq(pt), sq(nt)
    else:                            # t: j -> i, next(t): i -> l, prev(t): l -> j
        c, d = sq(nt), sq(pt)
    return Unfolding(e, (h, t), (f, g), (i, j, k, l_),
                     sq(h), sq(tri.next(h)), sq(tri.prev(h)), c, d,
                     simplest(m.areas[f]), simplest(m.areas[g]))


def flip_obstruction(m: PiecewiseFlatSurface, e: int):
    """``(unfolding, None)`` if ``e`` is flippable, else ``(unfolding or None, reason)``."""
    tri = m.triangulation
    e = checked_index(e, tri.n_edges, "edge")
    h, t = tri.edge_halfedges(e)
    i, j = tri.tail(h), tri.head(h)
    if t < 0:
        return None, (f"edge {e} ({i}-{j}) cannot be flipped: it is a boundary edge "
                      "(one triangle only)")
    if face_of(h) == face_of(t):
        return None, (f"edge {e} ({i}-{j}) cannot be flipped: face {face_of(h)} lies on both "
                      "sides, the two triangles are not distinct (L2.8, Remark 2.9)")
    u = unfold(m, e)
    try:
        si, sj = u.convexity()
    except TermLimitExceeded as err:
        raise TermLimitExceeded(f"deciding whether edge {e} can be flipped: {err}") from None
    for s, v, end in ((si, i, "tail"), (sj, j, "head")):
        if s <= 0:
            how = "exactly pi" if s == 0 else "more than pi"
            return u, (f"edge {e} ({i}-{j}) cannot be flipped: the unfolded quadrilateral is "
                       f"not strictly convex at vertex {v} (the {end} of the edge): the angles "
                       f"of the two triangles there sum to {how}")
    return u, None


def is_flippable(surface, e: int) -> bool:
    """L2.8: whether edge ``e`` can be flipped, decided exactly.

    True iff ``e`` is interior, its two triangles are distinct faces, and the
    unfolded quadrilateral is strictly convex at both ends of ``e``:
    ``N_i = (e + b - a) A2 + (e + c - d) A1 > 0`` and
    ``N_j = (e + a - b) A2 + (e + d - c) A1 > 0`` (equivalently
    ``cot alpha_f(i) + cot alpha_g(i) > 0`` and the same at ``j``; see the module
    docstring for the derivation).  Convexity at the other two corners is
    automatic.  Signs are exact (Surd arithmetic, no tolerance).

    >>> from ddg_oracle.reference import PiecewiseFlatSurface, Triangulation
    >>> t = Triangulation.from_faces([[0, 1, 2], [1, 0, 3]])
    >>> is_flippable(PiecewiseFlatSurface(t, [1, 1, 1, 1, 1]), 0)      # two equilateral
    True
    >>> is_flippable(PiecewiseFlatSurface(t, [1, 1, 1, 1, 1]), 1)      # boundary edge
    False
    """
    m = surface_metric(surface)
    return flip_obstruction(m, e)[1] is None


def flip(surface, e: int) -> PiecewiseFlatSurface:
    """L2.8: the intrinsic flip of edge ``e``: the same surface, the other diagonal.

    The combinatorics come from :meth:`Triangulation.flip`: face ``f`` (of the
    first halfedge ``i -> j`` of ``e``) becomes ``(k, l, j)``, face ``g``
    becomes ``(l, k, i)``, edge ``e`` is the new diagonal ``k -- l``, every other
    edge and face keeps its id.  The new squared length and the two new areas
    come from the closed formulas of the module docstring (no new square root):
    ``g`` gets ``area(l, k, i)``, ``f`` gets ``area(k, l, j)``.  Accepts a
    ``PiecewiseFlatSurface`` (any triangulation, non-regular and
    non-orientable ones included) or a ``PolyhedralSurface`` (its metric).

    Raises :class:`~ddg_oracle.reference.errors.NotFlippable` naming the edge and the
    reason (boundary edge; the same face on both sides; not strictly convex at
    vertex i or j, naming it) and
    :class:`~ddg_oracle.reference.errors.TermLimitExceeded` (naming the edge) if the
    exact numbers outgrow ``ddg_oracle.reference.exact.settings.term_limit``.

    Flipping ``e`` twice gives back the squared lengths; the faces ``f`` and
    ``g`` trade places (with their areas).

    >>> from ddg_oracle.reference import PiecewiseFlatSurface, Triangulation
    >>> t = Triangulation.from_faces([[0, 1, 2], [1, 0, 3]])
    >>> r = flip(PiecewiseFlatSurface(t, [1, 1, 1, 1, 1]), 0)
    >>> r.triangulation.faces, r.squared_lengths[0], r.areas
    (((2, 3, 1), (3, 2, 0)), Fraction(3, 1), (Surd('1/4*sqrt(3)'), Surd('1/4*sqrt(3)')))
    """
    m = surface_metric(surface)
    if isinstance(m, IntrinsicTriangulation):
        m = m.surface()                  # flip() never changes its argument
    u = _flippable_unfolding(m, e)
    e = u.edge
    new_sq, at_i, at_j = _flipped_data(u)
    tri = m.triangulation.flip(e)
    f, g = u.faces
    sq = list(m.squared_lengths)
    sq[e] = new_sq
    areas = list(m.areas)
    areas[f] = at_j        # f = (k, l, j)
    areas[g] = at_i        # g = (l, k, i)
    # valid by construction: no re-validation of every edge (most of a flip's cost)
    return PiecewiseFlatSurface._trusted(tri, sq, areas)


def _flippable_unfolding(m, e: int) -> Unfolding:
    """The unfolding of ``e``, or :class:`NotFlippable` saying why not."""
    u, reason = flip_obstruction(m, e)
    if reason is not None:
        raise NotFlippable(reason)
    return u


def _flipped_data(u: Unfolding):
    """``(|kl|^2, area(l, k, i), area(k, l, j))`` of a flippable unfolding (exact)."""
    try:
        if u._lazy:
            return u._lazy
        return u.new_squared_length, Surd(u.new_area_at_i), Surd(u.new_area_at_j)
    except TermLimitExceeded as err:
        raise TermLimitExceeded(f"flip of edge {u.edge}: {err}") from None


class IntrinsicTriangulation:
    """A piecewise flat surface that is flipped in place: O(1) per flip (L2.8).

    :func:`flip` returns a new immutable surface and so copies O(F) data per
    flip; long flip sequences (:func:`ddg_oracle.reference.delaunay.flip_to_delaunay`,
    random flips on large meshes) run here instead and freeze the result once
    with :meth:`surface`.  Each :meth:`flip` is exactly :func:`flip` (same
    checks, errors, closed formulas, face and edge numbering), so
    ``IntrinsicTriangulation(s)`` flipped at ``e1, e2, ...`` then frozen equals
    ``flip(flip(s, e1), e2) ...``.

    With ``lazy=True`` each flip's new squared length and areas are lazy exact numbers
    (:class:`~ddg_oracle.reference.exact.lazy.Lazy`): the same values, their signs and
    floats decided by enclosures, their exact forms computed only where asked (after dozens
    of flips of a surface from R^3 an exact squared length has hundreds of square roots).

    It reads like a :class:`~ddg_oracle.reference.metric.PiecewiseFlatSurface` where the
    edge-local functions need it (``squared_length``, ``face_squared_lengths``,
    ``areas``, and ``triangulation`` with ``tail``, ``head``, ``edge_halfedges``
    ...), so :func:`unfold`, :func:`is_flippable`,
    :func:`ddg_oracle.reference.delaunay.is_delaunay_edge` and
    :func:`ddg_oracle.reference.delaunay.face_harmonic_index` accept it.  Its
    ``triangulation`` is a live view that changes with every flip.

    >>> from ddg_oracle.reference import surfaces
    >>> s = surfaces.grid(1, 1).metric()
    >>> w = IntrinsicTriangulation(s)
    >>> w.flip(2); w.flip(2)
    >>> w.surface().squared_lengths == s.squared_lengths
    True
    """

    __slots__ = ("triangulation", "squared_lengths", "areas", "lazy",
                 "__weakref__")   # weakref: as metric.py

    def __init__(self, surface, lazy: bool = False):
        m = surface_metric(surface)
        if isinstance(m, IntrinsicTriangulation):
            m = m.surface()
        self.triangulation = TriangulationBuilder(m.triangulation)
        self.squared_lengths = list(m.squared_lengths)
        self.areas = list(m.areas)
        self.lazy = lazy

    def squared_length(self, h: int):
        """Squared length of the edge of halfedge h."""
        return self.squared_lengths[self.triangulation.eid[h]]

    def face_squared_lengths(self, f: int):
        """Squared lengths of halfedges 3f, 3f+1, 3f+2 (opposite corners 2, 0, 1)."""
        eid, sq = self.triangulation.eid, self.squared_lengths
        return sq[eid[3 * f]], sq[eid[3 * f + 1]], sq[eid[3 * f + 2]]  # inline halfedge(f, c): hot

    def area(self, f: int):
        return self.areas[f]

    def is_flippable(self, e: int) -> bool:
        """L2.8, exactly as :func:`is_flippable`."""
        return flip_obstruction(self, e)[1] is None

    def flip(self, e: int) -> None:
        """Flip edge ``e`` in place, exactly as :func:`flip` (same errors)."""
        self.flip_unfolded(_flippable_unfolding(self, e))

    def flip_unfolded(self, u: Unfolding) -> None:
        """Flip the edge of ``u``, an unfolding of this surface already found
        flippable (saves unfolding twice in :func:`~ddg_oracle.reference.delaunay.flip_to_delaunay`)."""
        if self.lazy and not u._lazy:
            u = self._lazy_unfolding(u)
        new_sq, at_i, at_j = _flipped_data(u)
        self.triangulation.flip(u.edge)
        f, g = u.faces
        self.squared_lengths[u.edge] = new_sq
        self.areas[f] = at_j
        self.areas[g] = at_i

    def make_lazy(self, *faces: int) -> None:
        """Make the squared lengths and areas of ``faces`` lazy exact numbers in place
        (leaves: the same values, their enclosures computed once and shared by every later
        test and flip that reads them)."""
        eid, sq, areas = self.triangulation.eid, self.squared_lengths, self.areas
        for f in faces:
            for h in (3 * f, 3 * f + 1, 3 * f + 2):     # inline halfedge(f, c): hot
                e = eid[h]
                if not isinstance(sq[e], Lazy):
                    sq[e] = Lazy.of(sq[e])
            if not isinstance(areas[f], Lazy):
                areas[f] = Lazy.of(areas[f])

    def _lazy_unfolding(self, u: Unfolding) -> Unfolding:
        """``u`` again, its values made lazy (:meth:`make_lazy`)."""
        self.make_lazy(*u.faces)
        return unfold(self, u.edge)

    def surface(self) -> PiecewiseFlatSurface:
        """The current surface, frozen (O(F)); a value made lazy but never flipped is given
        back as it was (a leaf's exact number)."""
        def plain(xs):
            return [x.exact() if isinstance(x, Lazy) and x.is_leaf else x for x in xs]
        return PiecewiseFlatSurface._trusted(self.triangulation.build(),
                                             plain(self.squared_lengths), plain(self.areas))

    def __repr__(self) -> str:
        t = self.triangulation
        return f"IntrinsicTriangulation(V={t.n_vertices}, E={t.n_edges}, F={t.n_faces})"


def cot_sum(surface, e: int):
    """``cot alpha + cot beta`` of the two angles opposite edge ``e`` (exact).

    For a boundary edge, the one opposite angle's cotangent.  The edge is
    Delaunay (D4.4 / P4.9) iff ``alpha + beta <= pi`` iff this is ``>= 0``.
    Works when both sides of ``e`` lie in one face (two corners of that face).

    >>> from ddg_oracle.reference import surfaces
    >>> cot_sum(surfaces.grid(1, 1).metric(), 2)          # the diagonal: two right angles
    Fraction(0, 1)
    """
    m = surface_metric(surface)
    tri = m.triangulation
    e = checked_index(e, tri.n_edges, "edge")
    h, t = tri.edge_halfedges(e)
    total = m.corner_cot(face_of(h), opposite_corner(h))
    if t >= 0:
        total = total + m.corner_cot(face_of(t), opposite_corner(t))
    return simplest(total)


def regular_tetrahedron_flip() -> PiecewiseFlatSurface:
    """X2.5: the regular tetrahedron (all edges of length 1) with edge 0 flipped.

    The tetrahedron ``(0,1,2), (0,2,3), (0,3,1), (1,3,2)``; edge 0 joins 0 and 1.
    Its triangles ``(0,1,2)`` and ``(0,3,1)`` unfold to a rhombus with angles 60
    and 120 degrees, convex, so the flip is allowed and the new diagonal ``2 -- 3``
    has squared length ``1 + 1 - 1/2 + 8 (sqrt3/4)^2 = 3``: length sqrt(3), the
    long diagonal of the rhombus.  The result is a valid geodesic triangulation
    of the same surface (every face satisfies the strict triangle inequality,
    every vertex keeps its angle sum pi), regular but not strongly regular:

    * vertices 0 and 1 have valence 2 and lie in two faces each, with the same
      vertex sets: ``{0, 2, 3}`` twice and ``{1, 2, 3}`` twice;
    * vertices 2 and 3 are joined by two edges: the old one, of length 1, and the
      new one, of length sqrt(3).

    No polyhedral surface in R^3 realizes this triangulation.  Its edges would be
    straight segments, so both edges between 2 and 3 would be the segment from
    p2 to p3 and have the same length, but their lengths are 1 and sqrt(3).
    (Even forgetting the lengths, the two faces on ``{1, 2, 3}`` would both be the
    triangle p1 p2 p3, so the surface would have to fold onto itself.)

    >>> s = regular_tetrahedron_flip()
    >>> s.squared_lengths[0], s.triangulation.edge_vertices(0)
    (Fraction(3, 1), (2, 3))
    >>> s.triangulation.faces
    ((2, 3, 1), (0, 2, 3), (3, 2, 0), (1, 3, 2))
    >>> [s.triangulation.valence(v) for v in range(4)], s.triangulation.is_strongly_regular()
    ([2, 2, 4, 4], False)
    """
    t = Triangulation.from_faces([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
    return flip(PiecewiseFlatSurface(t, [1] * t.n_edges), 0)
