"""Area of triangles and simplicial surfaces as a Dirichlet energy (section 3.4 of the notes).

L3.7 (area from squared lengths and cotangents, and its derivative), L3.8 (the
area gradient at a vertex) and T3.9 (the area of a simplicial surface is the
Dirichlet energy of its coordinate functions; its gradient is the cotan
Laplacian of the positions).  Everything is exact: squared lengths and dot
products are Fractions, areas and cotangents are Surds.

Conventions: those of :mod:`ddg_oracle.reference.laplacian` (``Lap`` positive semidefinite,
``E(f) = 1/2 sum_edges nu(ij) (f(i) - f(j))^2``, cotan weights (3.3)).  For an
R^N-valued f, ``E(f) = sum_k E(f_k)`` and ``Lap`` acts coordinate-wise.

T3.9 is stated here with the right constant: ``A(S) = sum_k E(f_k) = 1/2 sum_edges
nu(ij) |f(i) - f(j)|^2`` and ``grad_{f(i)} A = (Lap f)(i)``.  The notes print
``A = 2 sum_k E(f_k) = sum nu |f(i) - f(j)|^2`` and ``grad A = 2 Lap f``, both
twice too large (see :func:`area_as_dirichlet_energy` for the evidence).

>>> from ddg_oracle.reference import surfaces
>>> s = surfaces.tetrahedron()
>>> area_as_dirichlet_energy(s) == s.metric().total_area()        # T3.9
True
"""

from __future__ import annotations

from fractions import Fraction
from typing import Sequence

from .errors import BadShape, DegenerateFace, InputError
from .exact import Surd, sqrt
from .exact.rationals import on_common_denominator
from .laplacian import cotan_laplacian, cotan_weighted_edges
from .metric import heron16
from .polyhedral import PolyhedralSurface
from .exact.surds import exact_sum, rounded_root_sum, simplest
from .combinatorics import next_corner, prev_corner
from .linear import cross, dot, sub

__all__ = ["triangle_area_heron", "triangle_cotangents", "area_from_cotangents",
           "heron_partial_derivatives", "area_length_derivatives", "area_gradient_cotan",
           "area_gradient_direct", "area_gradient_cross", "area_as_dirichlet_energy",
           "area_gradient", "area_gradient_floats", "laplacian_of_positions"]

_ZERO = Fraction(0)


def _triangle(points) -> tuple:
    if len(points) != 3:
        raise BadShape(f"a triangle has 3 vertices, got {len(points)}")
    pts = tuple(tuple(p) for p in points)
    if len({len(p) for p in pts}) != 1 or len(pts[0]) < 2:
        raise BadShape("the three vertices must be points of one R^N, N >= 2")
    return pts


# --- L3.7: area from edge lengths ------------------------------------------------------------


def triangle_area_heron(a2, b2, c2) -> Surd:
    """Heron: the area of the triangle with squared side lengths a2, b2, c2, ``sqrt(16 A^2)/4``.

    >>> triangle_area_heron(9, 16, 25)                 # the 3-4-5 triangle
    Surd('6')
    """
    h = heron16(Fraction(a2), Fraction(b2), Fraction(c2))
    if h <= 0:
        raise DegenerateFace(f"squared sides {a2}, {b2}, {c2} violate the strict triangle "
                             f"inequality (16 A^2 = {h})")
    return sqrt(h) / 4


def triangle_cotangents(points) -> tuple[Surd, Surd, Surd]:
    """cot of the angles at the three vertices of a triangle in R^N, from vectors only.

    ``cot alpha_i = <u, v> / |u ^ v|`` with u, v the edges leaving v_i and
    ``|u ^ v|^2 = |u|^2 |v|^2 - <u, v>^2`` (Lagrange identity): no length, no
    Heron, so this is independent of :func:`triangle_area_heron`.
    """
    p = _triangle(points)
    out = []
    for i in range(3):
        u, v = sub(p[next_corner(i)], p[i]), sub(p[prev_corner(i)], p[i])
        uv = dot(u, v)
        w2 = dot(u, u) * dot(v, v) - uv * uv
        if w2 <= 0:
            raise DegenerateFace(f"degenerate triangle {p}: its vertices are collinear")
        out.append(uv / sqrt(w2))
    return tuple(out)


def area_from_cotangents(squared_lengths: Sequence, cotangents: Sequence) -> Surd:
    """L3.7 (3.5): ``A = 1/4 (a1^2 cot alpha1 + a2^2 cot alpha2 + a3^2 cot alpha3)``,
    alpha_i the angle opposite the side a_i.

    >>> area_from_cotangents([9, 16, 25], triangle_cotangents([(0, 4), (3, 0), (0, 0)]))
    Fraction(6, 1)
    """
    acc = _ZERO
    for a2, c in zip(squared_lengths, cotangents):
        acc = acc + Fraction(a2) * c
    return simplest(acc / 4)


def heron_partial_derivatives(a2, b2, c2) -> tuple[Fraction, Fraction, Fraction]:
    """Exact partial derivatives of ``H = 16 A^2`` in the squared lengths (x1, x2, x3).

    H is a quadratic polynomial in each x_i, so the central difference quotient
    ``(H(x + e_i) - H(x - e_i)) / 2`` *is* the derivative, exactly (no limit, no
    symbolic algebra); it equals ``2 (x_j + x_k - x_i)``.
    """
    x = [Fraction(a2), Fraction(b2), Fraction(c2)]
    out = []
    for i in range(3):
        up, down = list(x), list(x)
        up[i] += 1
        down[i] -= 1
        out.append((heron16(*up) - heron16(*down)) / 2)
    return tuple(out)


def area_length_derivatives(a2, b2, c2) -> tuple[Surd, Surd, Surd]:
    """L3.7 (3.6), the left side: ``dA/da_i`` from Heron, by the chain rule, exactly.

    ``A = sqrt(H)/4`` with ``H = 16 A^2`` a polynomial in ``x_i = a_i^2``, so
    ``dA/da_i = dH/dx_i * dx_i/da_i / (8 sqrt H) = dH/dx_i * 2 a_i / (32 A)``;
    ``dH/dx_i`` from :func:`heron_partial_derivatives`.  The lemma says this is
    ``1/2 a_i cot alpha_i``.

    >>> area_length_derivatives(9, 16, 25)             # 3-4-5: cot of the right angle is 0
    (Fraction(2, 1), Fraction(3, 2), Fraction(0, 1))
    """
    area = triangle_area_heron(a2, b2, c2)
    dh = heron_partial_derivatives(a2, b2, c2)
    return tuple(simplest(d * 2 * sqrt(x) / (32 * area)) for d, x in zip(dh, (a2, b2, c2)))


# --- L3.8: the area gradient at a vertex --------------------------------------------------------


def area_gradient_cotan(points, i: int) -> tuple:
    """L3.8 (3.8): ``grad_{v_i} A = 1/2 cot alpha_j (v_i - v_k) + 1/2 cot alpha_k (v_i - v_j)``.

    alpha_j, alpha_k are the angles at the other two vertices (from
    :func:`triangle_cotangents`).  A vector of R^N with Surd coordinates.
    """
    p = _triangle(points)
    j, k = next_corner(i), prev_corner(i)
    cot = triangle_cotangents(p)
    return tuple(simplest((cot[j] * (a - c) + cot[k] * (a - b)) / 2)
                 for a, b, c in zip(p[i], p[j], p[k]))


def area_gradient_direct(points, i: int) -> tuple:
    """``grad_{v_i} A`` by differentiating ``A = 1/2 sqrt(|a|^2 |w|^2 - <a, w>^2)``, in any R^N.

    With ``a = v_i - v_j`` and ``w = v_k - v_j`` (the edge opposite v_i):
    ``grad = (|w|^2 a - <a, w> w) / (4 A)``, the component of a orthogonal to w,
    scaled: half the length of w times the unit height direction (the notes'
    ``1/2 J w_i``).  No cotangent is used.
    """
    p = _triangle(points)
    j, k = next_corner(i), prev_corner(i)
    a, w = sub(p[i], p[j]), sub(p[k], p[j])
    aw, ww = dot(a, w), dot(w, w)
    four_a2 = dot(a, a) * ww - aw * aw
    if four_a2 <= 0:
        raise DegenerateFace(f"degenerate triangle {p}: its vertices are collinear")
    inv = 1 / (2 * sqrt(four_a2))               # 1 / (4 A)
    return tuple(simplest((ww * x - aw * y) * inv) for x, y in zip(a, w))


def area_gradient_cross(points, i: int) -> tuple:
    """In R^3: ``grad_{v_i} A = 1/2 n x (v_k - v_j)``, n the unit normal of the triangle
    (v_i, v_j, v_k) in this order (i, j, k cyclic)."""
    p = _triangle(points)
    if len(p[0]) != 3:
        raise BadShape("the cross-product formula needs points of R^3")
    j, k = next_corner(i), prev_corner(i)
    u, v = sub(p[j], p[i]), sub(p[k], p[i])
    n = cross(u, v)
    nn = dot(n, n)
    if not nn:
        raise DegenerateFace(f"degenerate triangle {p}: its vertices are collinear")
    w = sub(p[k], p[j])
    c = cross(n, w)
    inv = 1 / (2 * sqrt(nn))
    return tuple(simplest(x * inv) for x in c)


# --- T3.9: area as Dirichlet energy -------------------------------------------------------------


def _positions(surface) -> PolyhedralSurface:
    if not isinstance(surface, PolyhedralSurface):
        raise InputError("T3.9 is about a simplicial surface in R^N: pass a PolyhedralSurface")
    return surface


def area_as_dirichlet_energy(surface: PolyhedralSurface):
    """T3.9 (3.10), corrected: ``sum_k E(f_k) = 1/2 sum_edges nu(ij) |f(i) - f(j)|^2``.

    f is the vertex map (the positions), nu its own cotan weights.  The theorem
    says this equals the total area; the notes print ``A = 2 sum_k E(f_k) =
    sum nu |f(i) - f(j)|^2``, twice the area.  Evidence: the right triangle
    (0,0), (1,0), (0,1) has weights 1/2 cot(pi/4) = 1/2 on the legs and
    1/2 cot(pi/2) = 0 on the hypotenuse, so ``sum nu |df|^2 = 1/2 + 1/2 = 1``
    while the area is 1/2; this function returns 1/2.

    >>> right = PolyhedralSurface.from_arrays([(0, 0), (1, 0), (0, 1)], [(0, 1, 2)])
    >>> area_as_dirichlet_energy(right), right.metric().total_area()
    (Fraction(1, 2), Surd('1/2'))
    """
    s = _positions(surface)
    p = s.positions
    terms = [w * dot(sub(p[i], p[j]), sub(p[i], p[j]))
             for i, j, w in cotan_weighted_edges(s) if i != j]
    return simplest(exact_sum(terms) / 2)


def area_gradient(surface: PolyhedralSurface) -> list[tuple]:
    """``grad_{f(i)} A(S)`` for every vertex: the sum over the faces at i of the direct
    per-triangle gradient (:func:`area_gradient_direct`; no cotangent).

    A face with a repeated vertex contributes once per corner (the chain rule).
    """
    s = _positions(surface)
    p = s.positions
    dim = s.dimension
    out = [tuple(_ZERO for _ in range(dim)) for _ in range(s.n_vertices)]
    for face in s.triangulation.faces:
        pts = [p[v] for v in face]
        for c in range(3):
            g = area_gradient_direct(pts, c)
            out[face[c]] = tuple(simplest(x + y) for x, y in zip(out[face[c]], g))
    return out


def area_gradient_floats(surface: PolyhedralSurface) -> list[tuple]:
    """L3.8 / T3.9: :func:`area_gradient` with every coordinate correctly rounded, fast on
    float meshes of any size (no Surd arithmetic unless a coordinate is 0 or within
    2^-2048 relative of a float's rounding boundary).

    With the points on one common denominator D (integers), the gradient at corner i
    of a face is ``n / (2 D sqrt(G))``: ``n = |w|^2 a - <a, w> w`` (a = v_i - v_j,
    w = v_k - v_j, as :func:`area_gradient_direct`) and ``G = |a|^2 |w|^2 - <a, w>^2``
    (integers; G is the same at the three corners).  A vertex coordinate is a sum
    ``sum n_t / sqrt(G_t) / (2D)``; each term times 2^p lies in [s, s + 1) for
    ``s = isqrt(n^2 4^p // G)`` (signed), so the sum lies in an interval of width
    (number of terms) 2^-p.  Its two ends rounding to one float decide the value's
    rounding (rounding is monotonic); else p doubles, up to 2048 bits, and then the
    exact Surd sum decides (a coordinate that is exactly 0: the in-plane gradient of
    an interior vertex of a planar mesh, linear precision).
    """
    s = _positions(surface)
    P, dim = s.positions, s.dimension
    flat, D = on_common_denominator([x for p in P for x in p])
    pts = [tuple(flat[dim * v:dim * v + dim]) for v in range(len(P))]
    terms: list[list[list]] = [[[] for _ in range(dim)] for _ in range(s.n_vertices)]
    for face in s.triangulation.faces:
        q = [pts[v] for v in face]
        a0 = [y - x for x, y in zip(q[1], q[0])]          # corner 0: a = v0 - v1, w = v2 - v1
        w0 = [y - x for x, y in zip(q[1], q[2])]
        G = _idot(a0, a0) * _idot(w0, w0) - _idot(a0, w0) ** 2
        if G <= 0:
            raise DegenerateFace(f"degenerate triangle {[P[v] for v in face]}: its vertices "
                                 "are collinear")
        for c in range(3):
            j, k = next_corner(c), prev_corner(c)
            a = [x - y for x, y in zip(q[c], q[j])]
            w = [x - y for x, y in zip(q[k], q[j])]
            ww, aw = _idot(w, w), _idot(a, w)
            for x in range(dim):
                n = ww * a[x] - aw * w[x]
                if n:
                    terms[face[c]][x].append((n, G))
    return [tuple(rounded_root_sum(t, 2 * D) for t in vertex) for vertex in terms]


def _idot(u, v) -> int:
    return sum(x * y for x, y in zip(u, v))


def laplacian_of_positions(surface: PolyhedralSurface) -> list[tuple]:
    """``(Lap f)(i)`` for the vertex map f, coordinate-wise, with its own cotan weights.

    T3.9 (3.11), corrected: this is ``grad_{f(i)} A(S)`` (the notes print ``2 Lap f``).
    On a planar surface it vanishes at interior vertices (moving an interior
    vertex within the plane does not change the area): linear precision.
    """
    s = _positions(surface)
    L = cotan_laplacian(s)
    cols = [L.matvec([p[k] for p in s.positions]) for k in range(s.dimension)]
    return [tuple(c[i] for c in cols) for i in range(s.n_vertices)]
