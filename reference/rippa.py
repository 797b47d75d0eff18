"""Dirichlet energy and edge flips (section 4.3.1): Rippa's lemma, exact.

A convex non-degenerate quadrilateral with vertices ``1, 2, 3, 4``
(counterclockwise) is determined by ``Q(r1, r2, r3, r4, theta)``: ``r_i`` the
distance from the intersection point ``X`` of the diagonals to vertex ``i``,
``theta`` the angle at ``X`` between the segments to vertices 1 and 2
(Figure 4.16).  ``u13`` is the piecewise linear interpolation of vertex values
``u1..u4`` on the triangles ``(123), (134)``, ``u24`` the one on
``(234), (241)``; ``u0`` and ``u0*`` are their values at ``X``.

Catalog rows:

* L4.14 (Rippa's lemma) -- :func:`energy_difference` computes
  ``E(u13) - E(u24)`` from the two triangulations' Dirichlet energies
  (:func:`ddg_oracle.reference.laplacian.dirichlet_energy_pl`, gradients face by face);
  :func:`rippa_right_side` evaluates the notes' formula (4.2)

      1/4 (u0 - u0*)^2 / sin(theta) * (r1 + r3)(r2 + r4) / (r1 r2 r3 r4) * (r1 r3 - r2 r4)

  literally, with ``r_i``, ``sin(theta)``, ``u0``, ``u0*`` as exact square-root
  numbers (:class:`~ddg_oracle.reference.exact.Surd`): ``r_i = sqrt(r_i^2)``,
  ``sin(theta) = |(P1 - X) x (P2 - X)| / (r1 r2)``,
  ``u0 = (r3 u1 + r1 u3) / (r1 + r3)``, ``u0* = (r4 u2 + r2 u4) / (r2 + r4)``.
  The two agree exactly (tests); the formula is printed correctly.
* L4.15 -- :func:`circularity`: the sign of ``r1 r3 - r2 r4``; 0 iff the
  quadrilateral is circular, ``> 0`` iff the diagonal 24 is Delaunay and 13 is
  not (intersecting chords, see the function).
* C4.16 -- :func:`is_affine_on`: whether the values come from one affine
  function.  A flip to the Delaunay diagonal never increases ``E``, and
  strictly decreases it unless the quadrilateral is circular or ``u`` is
  affine on it (then ``u0 = u0*``).  The notes' Corollary 4.16 says "unless
  all of ``u1..u4`` are equal", which is not enough: erratum ER-6
  (``docs/errata.md``).

Vertices are numbered 1..4 in the notes and 0..3 here (list positions).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Sequence

from .errors import BadQuadrilateral, BadShape
from .exact import Surd, sqrt
from .exact.rationals import rational
from .laplacian import dirichlet_energy_pl
from .planar import as_point, orientation
from .polyhedral import PolyhedralSurface
from .exact.surds import simplest

__all__ = ["Quadrilateral", "quadrilateral", "energy_difference", "rippa_right_side",
           "circularity", "is_affine_on", "TRIANGLES_13", "TRIANGLES_24"]

#: the triangulation with diagonal 13: triangles (123), (134), counterclockwise
TRIANGLES_13 = ((0, 1, 2), (0, 2, 3))
#: the triangulation with diagonal 24: triangles (234), (241), counterclockwise
TRIANGLES_24 = ((1, 2, 3), (1, 3, 0))


@dataclass(frozen=True)
class Quadrilateral:
    """A strictly convex counterclockwise quadrilateral ``P1 P2 P3 P4`` (exact).

    ``x``: the intersection point of the diagonals, ``x = P1 + s (P3 - P1)
    = P2 + t (P4 - P2)`` with ``0 < s, t < 1``; ``r_squared``: the exact
    squared distances ``r_i^2 = |P_i - x|^2``.
    """

    points: tuple
    x: tuple
    s: Fraction
    t: Fraction
    r_squared: tuple

    @property
    def r(self) -> tuple:
        """``(r1, r2, r3, r4)`` as exact square-root numbers."""
        return tuple(sqrt(q) for q in self.r_squared)

    @property
    def sin_theta(self) -> Surd:
        """``sin(theta)`` of the angle at ``x`` between the segments to ``P1`` and
        ``P2``: ``|(P1 - x) x (P2 - x)| / (r1 r2)`` (the same for the other three
        angles, ``pi - theta`` and ``theta``)."""
        (p1, p2), x = self.points[:2], self.x
        cross = (p1[0] - x[0]) * (p2[1] - x[1]) - (p1[1] - x[1]) * (p2[0] - x[0])
        r1, r2 = self.r[:2]
        return abs(cross) / (r1 * r2)


def quadrilateral(points) -> Quadrilateral:
    """The quadrilateral of four points, checked to be strictly convex and
    counterclockwise (:class:`~ddg_oracle.reference.errors.BadQuadrilateral` otherwise,
    naming the corner).

    >>> q = quadrilateral([(1, 0), (0, 1), (-1, 0), (0, -1)])
    >>> q.x, q.r, q.sin_theta
    ((Fraction(0, 1), Fraction(0, 1)), (Surd('1'), Surd('1'), Surd('1'), Surd('1')), Surd('1'))
    """
    pts = [as_point(p, f"P{i + 1}") for i, p in enumerate(points)]
    if len(pts) != 4:
        raise BadShape(f"a quadrilateral has 4 vertices, got {len(pts)}")
    for i in range(4):
        if orientation(pts[i - 1], pts[i], pts[(i + 1) % 4]) <= 0:
            raise BadQuadrilateral(f"P1 P2 P3 P4 must be strictly convex and counterclockwise; "
                                   f"the corner at P{i + 1} = {pts[i]} is not a left turn")
    p1, p2, p3, p4 = pts
    d13 = (p3[0] - p1[0], p3[1] - p1[1])
    d24 = (p4[0] - p2[0], p4[1] - p2[1])
    w = (p2[0] - p1[0], p2[1] - p1[1])
    den = d13[0] * d24[1] - d13[1] * d24[0]
    s = (w[0] * d24[1] - w[1] * d24[0]) / den
    t = (w[0] * d13[1] - w[1] * d13[0]) / den
    x = (p1[0] + s * d13[0], p1[1] + s * d13[1])
    r2 = tuple((p[0] - x[0]) ** 2 + (p[1] - x[1]) ** 2 for p in pts)
    return Quadrilateral(tuple(pts), x, s, t, r2)


def _values(u: Sequence) -> list[Fraction]:
    if len(u) != 4:
        raise BadShape(f"four vertex values u1..u4 are needed, got {len(u)}")
    return [rational(v, f"u{i + 1}") for i, v in enumerate(u)]


def energy_difference(points, u: Sequence):
    """L4.14, left side: ``E(u13) - E(u24)``, exact (rational for rational data).

    Each energy is ``1/2 integral |grad u|^2`` of the piecewise linear
    interpolant on the triangulation (:data:`TRIANGLES_13` or
    :data:`TRIANGLES_24`), computed face by face from gradients
    (:func:`ddg_oracle.reference.laplacian.dirichlet_energy_pl`), not from the formula.

    >>> energy_difference([(1, 0), (0, 1), (-1, 0), (0, -1)], [1, 0, 0, 0])   # circular
    Fraction(0, 1)
    """
    q = quadrilateral(points)
    u = _values(u)
    e13 = dirichlet_energy_pl(PolyhedralSurface.from_arrays(q.points, TRIANGLES_13), u)
    e24 = dirichlet_energy_pl(PolyhedralSurface.from_arrays(q.points, TRIANGLES_24), u)
    return simplest(e13 - e24)


def rippa_right_side(points, u: Sequence):
    """L4.14, right side of (4.2), evaluated as printed, exact:

        1/4 (u0 - u0*)^2 / sin(theta) * (r1 + r3)(r2 + r4) / (r1 r2 r3 r4) * (r1 r3 - r2 r4)

    with every quantity an exact :class:`~ddg_oracle.reference.exact.Surd` (see the module
    docstring); the result is returned as a Fraction when rational (it always
    is for rational points and values).

    Example: ``X = 0``, ``r = (2, 1, 1, 1)``, ``theta = pi/2``, ``u = (0, 0, 0, 1)``:
    ``u0 = 0``, ``u0* = 1/2``, so ``1/4 * 1/4 * 3 * 2 / 2 * (2 - 1) = 3/16``.

    >>> rippa_right_side([(2, 0), (0, 1), (-1, 0), (0, -1)], [0, 0, 0, 1])
    Fraction(3, 16)
    >>> energy_difference([(2, 0), (0, 1), (-1, 0), (0, -1)], [0, 0, 0, 1])
    Fraction(3, 16)
    """
    q = quadrilateral(points)
    u1, u2, u3, u4 = _values(u)
    r1, r2, r3, r4 = q.r
    u0 = (r3 * u1 + r1 * u3) / (r1 + r3)
    u0s = (r4 * u2 + r2 * u4) / (r2 + r4)
    value = (Fraction(1, 4) * (u0 - u0s) ** 2 / q.sin_theta
             * (r1 + r3) * (r2 + r4) / (r1 * r2 * r3 * r4) * (r1 * r3 - r2 * r4))
    return simplest(Surd(value))


def circularity(points) -> int:
    """L4.15: the sign of ``r1 r3 - r2 r4``, exact (``r_i`` square-root numbers).

    ``0`` iff the quadrilateral is circular; ``+1`` iff the diagonal 24 is
    Delaunay and 13 is not; ``-1`` iff 13 is Delaunay and 24 is not.  Why:
    along the line 1 3 the circle through 2, 3, 4 meets the ray from ``X``
    towards 1 at distance ``r2 r4 / r3`` (power of the point ``X``: ``-r2 r4``),
    so vertex 1 lies outside that circle iff ``r1 > r2 r4 / r3``.  (The notes'
    "r1 r3 > r2 r4 iff (24) Delaunay" reads "strictly": with ``=`` both
    diagonals are Delaunay.)

    >>> circularity([(2, 0), (0, 1), (-1, 0), (0, -1)])
    1
    """
    q = quadrilateral(points)
    r1, r2, r3, r4 = q.r
    return (r1 * r3 - r2 * r4).sign()


def is_affine_on(points, u: Sequence) -> bool:
    """C4.16: whether ``u1..u4`` are the values of one affine function ``a x + b y + c``
    at the four points (the points ``(P_i, u_i)`` of R^3 are coplanar), decided
    exactly by the 4 x 4 determinant ``det [x_i, y_i, u_i, 1]``.  Then
    ``u13 = u24`` and ``u0 = u0*``, so the energies agree whatever the shape.

    >>> is_affine_on([(2, 0), (0, 1), (-1, 0), (0, -1)], [2, 0, -1, 0])   # u = x
    True
    """
    pts = [as_point(p, f"P{i + 1}") for i, p in enumerate(points)]
    vals = _values(u)
    # subtract row 4 from the others: a 3 x 3 determinant of differences
    rows = [(p[0] - pts[3][0], p[1] - pts[3][1], v - vals[3]) for p, v in zip(pts[:3], vals[:3])]
    (a, b, c), (d, e, f), (g, h, i) = rows
    return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g) == 0
