"""Rational-metric surfaces: every squared length and every face area is rational, so every
chapter-4 quantity (flips, cotangents, harmonic index, Laplace-Beltrami) is exact Fraction
arithmetic on them, and cocircular ties are everywhere.

* :func:`flat_torus` / :func:`flat_tori`: R^2 modulo a rational lattice, an m x n grid of
  parallelograms split by diagonals (a piecewise flat surface, not embedded).
* :func:`polycube` / :func:`polycube_surfaces`: the boundary of a union of unit cubes in
  a 3 x (2g + 1) slab with g holes, every unit square split along a drawn diagonal: an
  embedded surface of genus g with integer vertices (usable by any implementation).
* :func:`randomly_flipped`: a metric after drawn intrinsic flips (non-Delaunay, and in
  time non-regular: loops, double edges).
* :func:`bump` / :func:`bumps`: a square grid of unit squares with a box-shaped bump of
  integer height: a disk with integer vertices whose faces lie in coordinate planes, so
  its Delaunay weights and the Dirichlet solutions on it are rational (A4.23, R4.11).

Strategies draw small integers and build the surface, so failures shrink.
"""

from __future__ import annotations

from fractions import Fraction

from hypothesis import strategies as st

from ..reference.combinatorics import Triangulation, halfedge, next_corner
from ..reference.intrinsic import flip, is_flippable
from ..reference.metric import PiecewiseFlatSurface
from ..reference.polyhedral import PolyhedralSurface

__all__ = ["flat_torus", "flat_tori", "polycube", "polycube_surfaces", "randomly_flipped",
           "bump", "bumps"]


def flat_torus(m: int, n: int, u=(1, 0), v=(0, 1)) -> PiecewiseFlatSurface:
    """The flat torus R^2 / (m u Z + n v Z), an m x n grid (m, n >= 3, so the grid is a
    regular triangulation) of parallelograms spanned by u, v split by diagonals; exact
    rational squared lengths and areas |u x v| / 2."""
    u = tuple(Fraction(x) for x in u)
    v = tuple(Fraction(x) for x in v)
    area = abs(u[0] * v[1] - u[1] * v[0]) / 2
    if area == 0 or m < 3 or n < 3:
        raise ValueError(f"need independent u, v and m, n >= 3; got {u}, {v}, {m} x {n}")

    def vid(i, j):
        return (i % m) * n + (j % n)

    faces, corners = [], []
    for i in range(m):
        for j in range(n):
            faces += [(vid(i, j), vid(i + 1, j), vid(i + 1, j + 1)),
                      (vid(i, j), vid(i + 1, j + 1), vid(i, j + 1))]
            corners += [((i, j), (i + 1, j), (i + 1, j + 1)), ((i, j), (i + 1, j + 1), (i, j + 1))]
    t = Triangulation.from_faces(faces, m * n)
    sq = [None] * t.n_edges
    for f, p in enumerate(corners):
        for c in range(3):
            (a, b), (x, y) = p[c], p[next_corner(c)]
            dx, dy = x - a, y - b
            w = (dx * u[0] + dy * v[0], dx * u[1] + dy * v[1])
            sq[t.edge_of(halfedge(f, c))] = w[0] ** 2 + w[1] ** 2
    return PiecewiseFlatSurface(t, sq, [area] * t.n_faces)


_vec = st.tuples(st.integers(-2, 3), st.integers(-2, 3))


@st.composite
def flat_tori(draw, max_size: int = 4):
    """A flat torus from a drawn rational lattice (integer vectors over a drawn
    denominator) and grid size; shrinks to the square 3 x 3 torus."""
    m, n = draw(st.integers(3, max_size)), draw(st.integers(3, max_size))
    d = draw(st.integers(1, 3))
    u = draw(_vec.filter(lambda w: w != (0, 0)))
    v = draw(_vec.filter(lambda w: u[0] * w[1] - u[1] * w[0] != 0))
    return flat_torus(m, n, (Fraction(u[0], d), Fraction(u[1], d)),
                      (Fraction(v[0], d), Fraction(v[1], d)))


_FACES = (  # the unit square of each cube face, outward counterclockwise: (axis, side, corners)
    (0, 0, ((0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0))),
    (0, 1, ((1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1))),
    (1, 0, ((0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1))),
    (1, 1, ((0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0))),
    (2, 0, ((0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0))),
    (2, 1, ((0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1))),
)


def polycube(genus: int, diagonals=()) -> PolyhedralSurface:
    """The boundary of the cubes ``[x, x+1] x [y, y+1] x [0, 1]`` for 0 <= x <= 2g,
    0 <= y <= 2, except the holes (2i + 1, 1): a closed embedded surface of genus g with
    integer vertices (g = 0: the 1 x 3 x 1 block, x = 0 only).

    Every unit square is split along one of its diagonals, ``diagonals[k]`` (bool,
    cycled; default False) for the k-th square; all faces are right isosceles
    triangles of area 1/2, and each square's diagonal is exactly cocircular (weight 0).
    """
    if genus < 0:
        raise ValueError(f"genus must be >= 0, got {genus}")
    width = 2 * genus + 1 if genus else 1
    cells = {(x, y) for x in range(width) for y in range(3)} - {(2 * i + 1, 1) for i in range(genus)}
    index: dict[tuple, int] = {}
    faces = []
    k = 0
    for (x, y) in sorted(cells):
        for axis, side, quad in _FACES:
            step = [0, 0, 0]
            step[axis] = 1 if side else -1
            if (x + step[0], y + step[1]) in cells and step[2] == 0:
                continue                              # shared with a neighbouring cube
            ids = []
            for p in quad:
                key = (x + p[0], y + p[1], p[2])
                ids.append(index.setdefault(key, len(index)))
            a, b, c, d = ids
            flipped = bool(diagonals[k % len(diagonals)]) if diagonals else False
            k += 1
            faces += [(a, b, c), (a, c, d)] if not flipped else [(a, b, d), (b, c, d)]
    positions = sorted(index, key=index.get)
    return PolyhedralSurface.from_arrays(positions, faces)


@st.composite
def polycube_surfaces(draw, max_genus: int = 2):
    """A :func:`polycube` of drawn genus with drawn diagonals; shrinks to the genus-0 block."""
    g = draw(st.integers(0, max_genus))
    diagonals = draw(st.lists(st.booleans(), min_size=1, max_size=64))
    return polycube(g, diagonals)


def randomly_flipped(metrics, max_flips: int = 40):
    """``metrics`` (a strategy of piecewise flat surfaces) after up to ``max_flips`` drawn
    intrinsic flips (L2.8; non-flippable draws are skipped): still rational, usually not
    Delaunay, and after enough flips not regular."""
    @st.composite
    def build(draw):
        m = draw(metrics)
        picks = draw(st.lists(st.integers(0, 10 ** 6), max_size=max_flips))
        for k in picks:
            e = k % m.triangulation.n_edges
            if is_flippable(m, e):
                m = flip(m, e)
        return m
    return build()


def bump(size: int, box: tuple, height: int, diagonals=()) -> PolyhedralSurface:
    """The ``size x size`` grid of unit squares in the plane z = 0 with the cells
    ``x0 <= x < x1, y0 <= y < y1`` (``box``, inside the rim) raised to z = ``height``, walls
    included: a disk bounded by the grid's rim, every face in a coordinate plane,
    oriented consistently (upward on the top, outward on the walls).  Each unit square
    is split along ``diagonals[k]`` (cycled; default False) for the k-th square."""
    x0, x1, y0, y1 = box
    if not (1 <= x0 < x1 <= size - 1 and 1 <= y0 < y1 <= size - 1) or height < 1:
        raise ValueError(f"the box {box} must lie inside the rim of the {size} x {size} grid "
                         f"and the height {height} be >= 1")
    index: dict[tuple, int] = {}
    faces = []
    squares = []

    def z(x, y):
        return height if x0 <= x < x1 and y0 <= y < y1 else 0

    for x in range(size):
        for y in range(size):
            h = z(x, y)
            squares.append(((x, y, h), (x + 1, y, h), (x + 1, y + 1, h), (x, y + 1, h)))
    for k in range(height):                 # the walls, outward counterclockwise
        for x in range(x0, x1):
            squares.append(((x + 1, y0, k), (x, y0, k), (x, y0, k + 1), (x + 1, y0, k + 1)))
            squares.append(((x, y1, k), (x + 1, y1, k), (x + 1, y1, k + 1), (x, y1, k + 1)))
        for y in range(y0, y1):
            squares.append(((x0, y, k), (x0, y + 1, k), (x0, y + 1, k + 1), (x0, y, k + 1)))
            squares.append(((x1, y + 1, k), (x1, y, k), (x1, y, k + 1), (x1, y + 1, k + 1)))
    for k, quad in enumerate(squares):
        a, b, c, d = (index.setdefault(p, len(index)) for p in quad)
        flipped = bool(diagonals[k % len(diagonals)]) if diagonals else False
        faces += [(a, b, c), (a, c, d)] if not flipped else [(a, b, d), (b, c, d)]
    return PolyhedralSurface.from_arrays(sorted(index, key=index.get), faces)


@st.composite
def bumps(draw, max_size: int = 4):
    """A :func:`bump` of drawn grid size, box, height and diagonals; shrinks to the 3 x 3
    grid with its centre raised by 1."""
    size = draw(st.integers(3, max_size))
    x0 = draw(st.integers(1, size - 2))
    x1 = draw(st.integers(x0 + 1, size - 1))
    y0 = draw(st.integers(1, size - 2))
    y1 = draw(st.integers(y0 + 1, size - 1))
    height = draw(st.integers(1, 2))
    diagonals = draw(st.lists(st.booleans(), min_size=1, max_size=16))
    return bump(size, (x0, x1, y0, y1), height, diagonals)
