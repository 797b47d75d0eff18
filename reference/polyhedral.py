"""Polyhedral surfaces: a triangulation with exact vertex positions in R^n.

Only the container lives here (and extrinsic quantities in later chapters);
everything that depends on edge lengths alone belongs to the piecewise flat
surface.  Positions are stored as tuples of ``Fraction``; floats are taken
exactly (every float is a dyadic rational), NaN and infinities are rejected.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Iterable, Sequence

from .combinatorics import Triangulation
from .errors import BadShape, EmptyMesh, IndexOutOfRange, InputError, UnreferencedVertex
from .exact.rationals import rational
from .metric import PiecewiseFlatSurface, metric_of

__all__ = ["PolyhedralSurface", "orientation3d"]


class PolyhedralSurface:
    """A triangulation plus exact positions, one point of R^n (n >= 2) per vertex.

    >>> from ddg_oracle.reference import PolyhedralSurface
    >>> s = PolyhedralSurface.from_arrays([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    >>> s.positions[1]
    (Fraction(1, 1), Fraction(0, 1), Fraction(0, 1))
    """

    __slots__ = ("triangulation", "positions", "_metric", "__weakref__")
    # weakly referenceable: a caller may keep values computed from one surface beside it
    # (a memo of derived values) without keeping the surface alive

    def __init__(self, triangulation: Triangulation, positions: Iterable[Sequence]):
        if not isinstance(triangulation, Triangulation):
            raise InputError(f"expected a Triangulation, got {type(triangulation).__name__} "
                             "(use PolyhedralSurface.from_arrays(V, F) for a face list)")
        rows = tuple(_point(p, i) for i, p in enumerate(_rows(positions)))
        if not rows:
            raise EmptyMesh("no vertex positions")
        dim = len(rows[0])
        for i, p in enumerate(rows):
            if len(p) != dim:
                raise BadShape(f"vertex {i} has {len(p)} coordinates, vertex 0 has {dim}")
        n = triangulation.n_vertices
        if len(rows) < n:
            raise IndexOutOfRange(
                f"faces use vertex {n - 1} but only {len(rows)} positions are given")
        if len(rows) > n:
            raise UnreferencedVertex(
                f"vertex {n} has a position but no face uses it ({len(rows)} positions, "
                f"faces use {n} vertices)")
        self.triangulation = triangulation
        self.positions = rows
        self._metric = None

    def __reduce__(self):
        # pickled as its defining data, without the cached metric
        return (PolyhedralSurface, (self.triangulation, self.positions))

    @classmethod
    def from_arrays(cls, V, F) -> "PolyhedralSurface":
        """Build from a (n_vertices x dim) position array and an (n_faces x 3) face array.

        Accepts nested sequences or numpy arrays; every vertex must be used by a face.
        Errors (all :class:`~ddg_oracle.reference.errors.InputError`) name the face, corner,
        vertex or coordinate: EmptyMesh, BadShape, NonIntegerIndex, NegativeIndex,
        IndexOutOfRange, RepeatedVertexInFace, NonManifoldEdge, NonManifoldVertex,
        UnreferencedVertex, NotANumber, NonFiniteValue.  Zero-area faces are valid
        here; the metric (and every quantity built on it) raises DegenerateFace.
        """
        rows = _rows(V)
        if not rows:
            raise EmptyMesh("no vertex positions (V is empty)")
        return cls(Triangulation.from_faces(F, n_vertices=len(rows)), rows)

    @property
    def dimension(self) -> int:
        return len(self.positions[0])

    @property
    def faces(self):
        return self.triangulation.faces

    @property
    def n_vertices(self) -> int:
        return self.triangulation.n_vertices

    def metric(self) -> PiecewiseFlatSurface:
        """The intrinsic metric: exact squared edge lengths and face areas (cached).

        Raises :class:`~ddg_oracle.reference.errors.DegenerateFace` naming a zero-area face.
        """
        if self._metric is None:
            self._metric = metric_of(self.positions, self.triangulation)
        return self._metric

    def to_arrays(self) -> tuple[list[list[float]], list[list[int]]]:
        """Float positions (each coordinate correctly rounded) and the face list."""
        return ([[float(x) for x in p] for p in self.positions],
                [list(f) for f in self.triangulation.faces])

    def with_positions(self, positions) -> "PolyhedralSurface":
        """The same triangulation with other positions."""
        return PolyhedralSurface(self.triangulation, positions)

    def __repr__(self) -> str:
        t = self.triangulation
        return (f"PolyhedralSurface(V={t.n_vertices}, F={t.n_faces}, "
                f"dimension={self.dimension})")


def _rows(array) -> list:
    if hasattr(array, "tolist"):      # numpy arrays, without importing numpy
        array = array.tolist()
    try:
        return list(array)
    except TypeError:
        raise BadShape(f"positions must be a sequence of points, got {type(array).__name__}") from None


def _point(p, i: int) -> tuple[Fraction, ...]:
    if hasattr(p, "tolist"):
        p = p.tolist()
    try:
        coords = list(p)
    except TypeError:
        raise BadShape(f"vertex {i}: a point must be a sequence of coordinates, got {p!r}") from None
    if len(coords) < 2:
        raise BadShape(f"vertex {i} has {len(coords)} coordinate(s); need at least 2")
    # a Fraction as it is and a finite float taken exactly, without the message built:
    # every surface a strategy draws or derives comes here with Fractions (a tenth of
    # drawing an example went to the messages), a mesh file with floats (4.5 s of 1.35
    # million coordinates went to them, 1.2 s without)
    return tuple(x if type(x) is Fraction
                 else Fraction(x) if type(x) is float and math.isfinite(x)
                 else rational(x, where=f"vertex {i}, coordinate {j}")
                 for j, x in enumerate(coords))


def orientation3d(a, b, c, d) -> int:
    """The side of the plane through ``a, b, c`` (points of R^3) that ``d`` is on: the
    sign of ``det(b - a, c - a, d - a)``, exact (0: the four points are coplanar).  Used
    by the convex hull (X1.1) and the stereographic lift (R4.2).

    >>> orientation3d((0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1))
    1
    """
    a, b, c, d = ([Fraction(x) for x in p] for p in (a, b, c, d))
    u, v, w = ([q[k] - a[k] for k in range(3)] for q in (b, c, d))
    det = (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
           + u[2] * (v[0] * w[1] - v[1] * w[0]))
    return (det > 0) - (det < 0)
