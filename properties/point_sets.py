"""Strategies of the point sets in the notes' statements checked by :mod:`.statements`:
rational points on the unit sphere (X1.1, T2.10), integer functions on a window of the
lattice Z or Z^2 (X3.1), three rational points on a circle (L4.8), planar integer points
(R4.1, R4.2, R4.4), rational points on the unit cube's surface (D2.4 / R2.6, X2.2).

Each draws small integers and builds its points exactly from them, so failures shrink.
"""

from __future__ import annotations

from fractions import Fraction

from hypothesis import assume
from hypothesis import strategies as st

from ..reference import planar

from .planar_points import integer_point_sets, unit_circle_point

# --- chapter 1 ---------------------------------------------------------------------------


@st.composite
def sphere_point_sets(draw, max_points: int = 9):
    """Rational points on the unit sphere (lifted planar integer points divided by a
    drawn denominator), no 4 coplanar: the vertices of a convex polyhedron."""
    n = draw(st.integers(4, max_points))
    den = draw(st.integers(1, 4))
    flat = draw(st.lists(st.tuples(st.integers(-5, 5), st.integers(-5, 5)), min_size=n,
                         max_size=n, unique=True))
    return [planar.stereographic_lift((Fraction(x, den), Fraction(y, den))) for x, y in flat]


# --- chapter 3 ---------------------------------------------------------------------------


@st.composite
def lattice_functions(draw):
    """(dimension 1 or 2, window size, integer function values on the window)."""
    dim = draw(st.sampled_from((1, 2)))
    size = draw(st.integers(3, 6))
    n = size ** dim
    return dim, size, draw(st.lists(st.integers(-50, 50), min_size=n, max_size=n))


# --- chapter 4 ---------------------------------------------------------------------------


@st.composite
def circle_triples(draw):
    """Three distinct rational points B, S, C on a circle with rational centre and
    radius (scaled rational points of the unit circle)."""
    params = draw(st.lists(st.tuples(st.integers(-9, 9), st.integers(1, 9)), min_size=3,
                           max_size=3, unique_by=lambda t: Fraction(t[0], t[1])))
    r = Fraction(draw(st.integers(1, 20)), draw(st.integers(1, 5)))
    cx, cy = draw(st.integers(-5, 5)), draw(st.integers(-5, 5))
    pts = [unit_circle_point(m, n) for m, n in params]
    assume(len(set(pts)) == 3)
    return tuple((cx + r * x, cy + r * y) for x, y in pts)


def planar_points():
    return integer_point_sets(max_points=8)


# --- Definition 2.4, Remark 2.6, Example 2.2: the intrinsic distance of the cube ----------

@st.composite
def cube_surface_points(draw, n: int = 3):
    """``n`` rational points of the unit cube's surface (often on edges and vertices)."""
    out = []
    for _ in range(n):
        axis, side = draw(st.integers(0, 2)), draw(st.integers(0, 1))
        den = draw(st.integers(1, 6))
        u, v = (Fraction(draw(st.integers(0, den)), den) for _ in range(2))
        rest = iter((u, v))
        out.append(tuple(Fraction(side) if k == axis else next(rest) for k in range(3)))
    return out


@st.composite
def opposite_cube_points(draw):
    """A rational point of the cube's bottom face and one of its top face."""
    den = draw(st.integers(1, 8))
    u1, v1, u2, v2 = (Fraction(draw(st.integers(0, den)), den) for _ in range(4))
    return (u1, v1, Fraction(0)), (u2, v2, Fraction(1))
