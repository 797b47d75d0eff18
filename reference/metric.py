"""Piecewise flat surfaces: a triangulation with exact squared edge lengths (D2.6).

Everything that depends on edge lengths alone is computed here once: face
areas, corner cotangents, corner angles.  Squared lengths are Fractions; a face
area is a :class:`~ddg_oracle.reference.exact.Surd` (one square root per face), carried
alongside the lengths and never recomputed once known, so that intrinsic edge
flips (chapter 4) stay exact.

Conventions: halfedge h = 3 f + c runs in face f from corner c to corner c+1;
the corner c of face f is opposite to halfedge 3 f + c + 1 (mod 3)
(:func:`~ddg_oracle.reference.combinatorics.opposite_halfedge`).

:class:`Metric` is the interface that :class:`PiecewiseFlatSurface` (immutable) and
:class:`~ddg_oracle.reference.intrinsic.IntrinsicTriangulation` (flipped in place) share:
edge-local code (unfolding, flips, Delaunay tests, the harmonic index of a face) asks for
nothing else.
"""

from __future__ import annotations

import math
from fractions import Fraction
from math import isqrt
from typing import Protocol, Sequence, runtime_checkable

from .combinatorics import HalfedgeMesh, Triangulation, halfedge
from .errors import BadShape, DegenerateFace, InputError, TriangleInequalityViolated
from .exact import Angle, Surd, corner_angle, exact_sum, rational, sqrt
from .exact.rationals import points_on_common_denominator, shared_denominator
from .exact.surds import rounded_root_sum

__all__ = ["PiecewiseFlatSurface", "Metric", "area", "as_metric", "metric_of",
           "squared_length_floats", "face_area_floats", "heron16"]


@runtime_checkable
class Metric(Protocol):
    """Exact lengths on a triangulation, as edge-local code reads them: the combinatorics
    (a :class:`~ddg_oracle.reference.combinatorics.HalfedgeMesh`), squared lengths per edge
    (Fractions, or Surds after flips), areas per face (Surds), and per halfedge / face."""

    @property
    def triangulation(self) -> HalfedgeMesh: ...

    @property
    def squared_lengths(self) -> Sequence: ...

    @property
    def areas(self) -> Sequence: ...

    def squared_length(self, h: int): ...

    def face_squared_lengths(self, f: int) -> tuple: ...

    def area(self, f: int): ...


def heron16(a: Fraction, b: Fraction, c: Fraction) -> Fraction:
    """16 A^2 of a triangle with squared side lengths a, b, c (Heron, exact).

    Positive iff the side lengths satisfy the strict triangle inequality.
    """
    return 2 * (a * b + b * c + c * a) - a * a - b * b - c * c


class PiecewiseFlatSurface:
    """A triangulation with exact squared edge lengths and face areas (D2.6).

    Squared lengths are Fractions, or Surds where intrinsic flips of a surface
    from R^3 made them irrational (see :mod:`ddg_oracle.reference.intrinsic`).

    Build from squared lengths (``PiecewiseFlatSurface(t, squared_lengths)``),
    from lengths (:meth:`from_lengths`, each squared exactly), or from a
    polyhedral surface (``PolyhedralSurface.metric()``).  Every face must
    satisfy the strict triangle inequality; the error names the face.

    >>> from ddg_oracle.reference import Triangulation
    >>> t = Triangulation.from_faces([[0, 1, 2]])
    >>> s = PiecewiseFlatSurface(t, [1, 1, 1])            # equilateral, side 1
    >>> s.area(0)
    Surd('1/4*sqrt(3)')
    """

    __slots__ = ("triangulation", "squared_lengths", "areas", "_cots", "_face_cots", "__weakref__")
    # weakly referenceable: a caller may keep values computed from one surface beside it
    # (a memo of derived values) without keeping the surface alive

    def __init__(self, triangulation: Triangulation, squared_lengths: Sequence, areas=None):
        t = triangulation
        if not isinstance(t, Triangulation):
            raise InputError(f"expected a Triangulation, got {type(t).__name__} "
                             "(build one with Triangulation.from_faces)")
        if hasattr(squared_lengths, "tolist"):      # numpy arrays, without importing numpy
            squared_lengths = squared_lengths.tolist()
        if (isinstance(squared_lengths, (str, bytes))
                or not isinstance(squared_lengths, Sequence)):
            raise BadShape(f"squared lengths must be a sequence, one per edge, got "
                           f"{type(squared_lengths).__name__}")
        if len(squared_lengths) != t.n_edges:
            raise BadShape(f"{len(squared_lengths)} squared lengths for {t.n_edges} edges")
        sq = tuple(_squared_length(x, e) for e, x in enumerate(squared_lengths))
        for e, x in enumerate(sq):
            if x <= 0:
                raise TriangleInequalityViolated(f"edge {e} has squared length {x} <= 0")
        self.triangulation = t
        self.squared_lengths = sq
        if areas is not None and len(areas) != t.n_faces:
            raise BadShape(f"{len(areas)} areas for {t.n_faces} faces")
        checked = []
        for f in range(t.n_faces):
            a, b, c = self.face_squared_lengths(f)
            h = heron16(a, b, c)
            if h <= 0:
                raise TriangleInequalityViolated(
                    f"face {f} {t.faces[f]}: squared side lengths {a}, {b}, {c} violate the "
                    f"strict triangle inequality (16 A^2 = {h})")
            if areas is None:
                if isinstance(h, Surd):
                    raise InputError(f"face {f}: irrational squared lengths need the face "
                                     "areas given (their square root would be nested)")
                checked.append(sqrt(h) / 4)
            else:
                A = areas[f] if isinstance(areas[f], Surd) else Surd(areas[f])
                if A <= 0 or 16 * A * A != h:
                    raise InputError(f"face {f}: area {A} does not match its squared side "
                                     f"lengths (16 A^2 must equal {h})")
                checked.append(A)
        self.areas = tuple(checked)
        self._cots = None
        self._face_cots = {}

    @classmethod
    def _trusted(cls, triangulation: Triangulation, squared_lengths, areas) -> "PiecewiseFlatSurface":
        """Internal: from data valid by construction (operations such as flips)."""
        out = object.__new__(cls)
        out.triangulation = triangulation
        out.squared_lengths = tuple(squared_lengths)
        out.areas = tuple(areas)
        out._cots = None
        out._face_cots = {}
        return out

    @classmethod
    def from_lengths(cls, triangulation: Triangulation, lengths: Sequence) -> "PiecewiseFlatSurface":
        """From edge lengths (ints, Fractions, floats: squared exactly)."""
        if hasattr(lengths, "tolist"):
            lengths = lengths.tolist()
        if isinstance(lengths, (str, bytes)) or not isinstance(lengths, Sequence):
            raise BadShape(f"lengths must be a sequence, one per edge, got {type(lengths).__name__}")
        ls = [rational(x, where=f"length of edge {e}") for e, x in enumerate(lengths)]
        for e, x in enumerate(ls):
            if x <= 0:      # squaring would hide the sign of a negative length
                raise TriangleInequalityViolated(f"edge {e} has length {x} <= 0")
        return cls(triangulation, [x * x for x in ls])

    # -- per element ----------------------------------------------------------------

    def squared_length(self, h: int) -> Fraction:
        """Squared length of the edge of halfedge h."""
        return self.squared_lengths[self.triangulation.edge_of(h)]

    def face_squared_lengths(self, f: int) -> tuple[Fraction, Fraction, Fraction]:
        """Squared lengths of halfedges 3f, 3f+1, 3f+2 (opposite corners 2, 0, 1)."""
        e = self.triangulation.edge_of
        sq = self.squared_lengths
        return sq[e(3 * f)], sq[e(3 * f + 1)], sq[e(3 * f + 2)]  # inline halfedge(f, c): hot

    def area(self, f: int) -> Surd:
        """Area of face f (exact)."""
        return self.areas[f]

    def total_area(self) -> Surd:
        """Sum of the face areas (exact; summed over one common base, fast on float meshes)."""
        return Surd(exact_sum(self.areas))

    def corner_cot(self, f: int, c: int) -> Surd:
        """cot of the angle at corner c of face f: (a + b - o) / (4 A), exact.

        a, b are the squared lengths of the two sides at the corner, o that of
        the opposite side.
        """
        if self._cots is None:
            self._cots = self._all_cots()
        return self._cots[3 * f + c]  # inline halfedge(f, c): hot

    def corner_angle(self, f: int, c: int) -> Angle:
        """The angle at corner c of face f, an exact angle in (0, pi)."""
        return corner_angle(self.corner_cot(f, c))

    def face_cots(self, f: int) -> tuple[Surd, Surd, Surd]:
        """The cotangents of corners 0, 1, 2 of face f (as :meth:`corner_cot`), computed for
        this face alone unless every face's are known already."""
        if self._cots is not None:
            return tuple(self._cots[3 * f:3 * f + 3])  # inline halfedge(f, c): hot
        kept = self._face_cots.get(f)
        if kept is None:
            kept = self._face_cots[f] = tuple(Surd.quotients(self.face_cot_numerators(f),
                                                             4 * self.areas[f]))
        return kept

    def face_cot_numerators(self, f: int) -> tuple:
        """D2.6: ``(a + b - o)`` of corners 0, 1, 2 of face f (a, b the squared lengths of
        the sides at the corner, o the opposite one): cot = n / (4 A), exact.  Enclosures
        of the cotangents need no division (:class:`~ddg_oracle.reference.exact.Quotient`)."""
        l0, l1, l2 = self.face_squared_lengths(f)       # opposite corners 2, 0, 1
        return l0 + l2 - l1, l0 + l1 - l2, l1 + l2 - l0

    def _all_cots(self) -> list[Surd]:
        cots = []
        for f in range(self.triangulation.n_faces):
            cots += self.face_cots(f)
        self._face_cots = {}                        # the list holds them now
        return cots

    def __repr__(self) -> str:
        t = self.triangulation
        return f"PiecewiseFlatSurface(V={t.n_vertices}, E={t.n_edges}, F={t.n_faces})"


def _squared_length(x, e: int):
    """A Fraction, or a Surd when it is irrational (after intrinsic flips)."""
    if isinstance(x, Surd):
        return x.as_fraction() if x.is_rational() else x
    return rational(x, where=f"squared length of edge {e}")


def as_metric(surface) -> PiecewiseFlatSurface:
    """The piecewise flat surface of ``surface`` (itself, or a polyhedral surface's metric)."""
    if isinstance(surface, PiecewiseFlatSurface):
        return surface
    metric = getattr(surface, "metric", None)
    if metric is None:
        raise InputError(f"expected a PolyhedralSurface or a PiecewiseFlatSurface, "
                         f"got {type(surface).__name__}")
    return metric()    # raises DegenerateFace naming a zero-area face


def area(surface) -> Surd:
    """The total area of a surface, the sum of its face areas (Heron's formula on the exact
    squared lengths, D2.6): exact (a Surd, a Fraction where rational).  Accepts a
    PolyhedralSurface or a PiecewiseFlatSurface; the protocol's ``area``.

    >>> from ddg_oracle.reference import surfaces
    >>> area(surfaces.cube()), area(surfaces.tetrahedron().metric()) == area(surfaces.tetrahedron())
    (Fraction(6, 1), True)
    """
    a = as_metric(surface).total_area()
    return a.as_fraction() if a.is_rational() else a


def metric_of(points, triangulation: Triangulation) -> PiecewiseFlatSurface:
    """The intrinsic metric (D2.6) of a triangulation with exact points in R^n.

    Areas come from the Lagrange identity 4 A^2 = |u|^2 |v|^2 - (u.v)^2, which
    holds in every dimension; a zero-area face raises :class:`DegenerateFace`.
    Exact: the points are written on one common denominator D (x = X / D, X integer;
    one per edge and per face when the common one would be large), so |X_i - X_j|^2 / D^2 and the Lagrange
    identity are integer arithmetic, one Fraction per result (float input: D a
    power of two).  16 A^2 = 4 (4 A^2) is then Heron's 16 A^2 of the squared
    lengths identically, and 4 A^2 > 0 is the strict triangle inequality: the
    metric is valid by construction.

    >>> from ddg_oracle.reference import Triangulation
    >>> m = metric_of([(0, 0, 0), (1, 0, 0), (0, Fraction(1, 3), 0)], Triangulation.from_faces([[0, 1, 2]]))
    >>> m.squared_lengths, m.area(0)
    ((Fraction(1, 1), Fraction(10, 9), Fraction(1, 9)), Surd('1/6'))
    """
    t = triangulation
    points, shared = _on_shared_denominator(points)

    def on_denominator(*vertices):
        if shared is not None:                  # one denominator for all (float meshes)
            return [shared[0][v] for v in vertices], shared[1]
        return points_on_common_denominator(*(points[v] for v in vertices))

    sq = []
    for e in range(t.n_edges):
        (X, Y), D = on_denominator(*t.edge_vertices(e))
        sq.append(Fraction(_squared_distance(X, Y), D * D))
    for e, x in enumerate(sq):
        # checked before the areas: a zero edge makes its faces zero-area, and
        # "coincident vertices" says more than "collinear"
        if x == 0:
            i, j = t.edge_vertices(e)
            raise DegenerateFace(f"edge {e} between vertices {i} and {j} has length zero "
                                 "(coincident vertices); its faces have zero area")
    areas = []
    for f, (i, j, k) in enumerate(t.faces):
        (P, Q, R), D = on_denominator(i, j, k)
        four_a2 = _lagrange(P, Q, R)
        if four_a2 == 0:
            raise degenerate_face(t, f)
        areas.append(sqrt(Fraction(four_a2, 4 * D ** 4)))      # sqrt(4 A^2 / 4): no division
    return PiecewiseFlatSurface._trusted(t, sq, areas)


def squared_length_floats(points, triangulation: Triangulation) -> list[float]:
    """D2.6: the exact squared length of every edge of a triangulation with exact points
    in R^n, correctly rounded to a float, without building the metric: the points on one
    common denominator D (as :func:`metric_of`), each |X_i - X_j|^2 / D^2 one correctly
    rounded integer division (Python's int / int), no Fraction per edge.  A length beyond
    the float range raises OverflowError (as ``float()`` of it would).

    >>> from ddg_oracle.reference import Triangulation
    >>> squared_length_floats([(0, 0, 0), (1, 0, 0), (0, Fraction(1, 3), 0)],
    ...                       Triangulation.from_faces([[0, 1, 2]]))
    [1.0, 1.1111111111111112, 0.1111111111111111]
    """
    t = triangulation
    points, shared = _on_shared_denominator(points)
    out = []
    for e in range(t.n_edges):
        i, j = t.edge_vertices(e)
        if shared is not None:
            (X, Y), D = (shared[0][i], shared[0][j]), shared[1]
        else:
            (X, Y), D = points_on_common_denominator(points[i], points[j])
        out.append(_squared_distance(X, Y) / (D * D))
    return out


def face_area_floats(points, triangulation: Triangulation) -> list[float]:
    """D2.6: the exact area of every face of a triangulation with exact points in R^n,
    correctly rounded to a float, without building the metric: with the points on one
    common denominator D (as :func:`metric_of`), 4 A^2 D^4 = |u|^2 |v|^2 - (u.v)^2 = G
    (an integer, the Lagrange identity) and A = G / sqrt(G) / (2 D^2), rounded by
    :func:`~ddg_oracle.reference.exact.surds.rounded_root_sum`.  A zero area raises
    :class:`DegenerateFace` as :func:`metric_of` does (checked first there).

    >>> from ddg_oracle.reference import Triangulation
    >>> face_area_floats([(0, 0, 0), (1, 0, 0), (0, Fraction(1, 3), 0)],
    ...                  Triangulation.from_faces([[0, 1, 2]]))
    [0.16666666666666666]
    """
    t = triangulation
    points, shared = _on_shared_denominator(points)
    # D a power of two (float coordinates): A = sqrt(G) 2^-(1 + 2 log2 D), rounded directly
    shift = (None if shared is None or shared[1] & (shared[1] - 1)
             else 2 * shared[1].bit_length() - 1)
    out = []
    for f, face in enumerate(t.faces):
        if shared is not None:
            (P, Q, R), D = [shared[0][v] for v in face], shared[1]
        else:
            (P, Q, R), D = points_on_common_denominator(*(points[v] for v in face))
        G = _lagrange(P, Q, R)
        if G == 0:
            raise degenerate_face(t, f)
        a = _scaled_root(G, shift) if shift is not None else None
        out.append(a if a is not None else rounded_root_sum(((G, G),), 2 * D * D))
    return out


def _squared_distance(X, Y):
    """D2.6: |X - Y|^2 of two points with integer (or exact) coordinates."""
    if len(X) == 3:                             # R^3 written out: twice as fast
        dx, dy, dz = X[0] - Y[0], X[1] - Y[1], X[2] - Y[2]
        return dx * dx + dy * dy + dz * dz
    return sum((x - y) ** 2 for x, y in zip(X, Y))


def _lagrange(P, Q, R):
    """D2.6: |u|^2 |v|^2 - (u.v)^2 = 4 A^2 for u = Q - P, v = R - P (the Lagrange identity,
    any dimension; exact)."""
    if len(P) == 3:                             # R^3 written out: twice as fast
        (px, py, pz), (qx, qy, qz), (rx, ry, rz) = P, Q, R
        ux, uy, uz, vx, vy, vz = qx - px, qy - py, qz - pz, rx - px, ry - py, rz - pz
        uv = ux * vx + uy * vy + uz * vz
        return (ux * ux + uy * uy + uz * uz) * (vx * vx + vy * vy + vz * vz) - uv * uv
    u = [y - x for x, y in zip(P, Q)]
    v = [y - x for x, y in zip(P, R)]
    uv = sum(x * y for x, y in zip(u, v))
    return sum(x * x for x in u) * sum(y * y for y in v) - uv * uv


def _scaled_root(G: int, k: int) -> float | None:
    """The correctly rounded float of sqrt(G) 2^-k (G > 0 an integer), or None where it is
    not a normal float.  r = isqrt(G 4^s) has at least 55 bits; sqrt(G 4^s) lies in [r, r +
    1), so r with its last bit set where r^2 < G 4^s (a sticky bit, two places below the
    53rd) rounds as the root does; ``float()`` of an int rounds correctly (half to even),
    and 2^-(s + k) is exact where that float times it is normal (checked on the float's
    exponent, before a rounding into the subnormals could round it up to 2^-1022).

    >>> _scaled_root(2, 0) == 2 ** 0.5, _scaled_root(9, 1), _scaled_root(1, 1074)
    (True, 1.5, None)
    """
    s = max(0, (111 - G.bit_length()) // 2)
    N = G << (2 * s)
    r = isqrt(N)
    if r * r != N:
        r |= 1
    try:
        x = float(r)
        if math.frexp(x)[1] - (s + k) < -1021:          # below 2^-1022
            return None
        return math.ldexp(x, -(s + k))
    except OverflowError:
        return None


def _on_shared_denominator(points):
    """(the points with every coordinate exact, :func:`shared_denominator` of them): points
    may come as floats, each taken exactly."""
    if {type(x) for p in points for x in p} <= {Fraction, int}:
        return points, shared_denominator(points)
    points = [tuple(x if isinstance(x, Fraction) else rational(x, where=f"vertex {i}")
                    for x in p) for i, p in enumerate(points)]
    return points, shared_denominator(points)


def degenerate_face(t: Triangulation, f: int, positions=None) -> DegenerateFace:
    """The error for face f of points in R^n with zero area: two coincident vertices
    (named by the edge between them, when ``positions`` are given) or three collinear ones."""
    if positions is not None:
        for c in range(3):
            e = t.edge_of(halfedge(f, c))
            i, j = t.edge_vertices(e)
            if positions[i] == positions[j]:
                return DegenerateFace(f"edge {e} between vertices {i} and {j} has length zero "
                                      "(coincident vertices); its faces have zero area")
    return DegenerateFace(f"degenerate face {f} {t.faces[f]}: its vertices are collinear "
                          "(zero area)")
