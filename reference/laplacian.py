"""Laplacians and Dirichlet energy (chapter 3 of the notes): exact, standard library only.

Conventions (the notes' own; every function below uses them):

* a weighted graph has one weight ``nu(e)`` per edge; the discrete Laplacian is
  ``(Lap f)(i) = sum_j nu(ij) (f(i) - f(j))`` (D3.1), *positive* semidefinite
  for nonnegative weights -- libigl's ``cotmatrix`` is its negative -- and the
  Dirichlet energy is ``E(f) = 1/2 sum_edges nu(ij) (f(i) - f(j))^2``, so that
  ``E(f) = 1/2 f^T Lap f`` and ``grad E = Lap f`` (R3.2);
* cotan weights (3.3): ``nu(ij) = 1/2 (cot alpha_ij + cot alpha_ji)`` on an
  interior edge, ``1/2 cot alpha_ij`` on a boundary edge, alpha the angles
  opposite the edge;
* weights are per EDGE (edge ids of the :class:`~ddg_oracle.reference.combinatorics.Triangulation`),
  never per vertex pair: non-regular triangulations have several edges between
  two vertices.  The matrix sums the weights of all edges between i and j; a
  loop edge contributes nothing to the matrix (``f(i) - f(i) = 0``);
* mass matrices are lumped (diagonal, one area per vertex), integrated values.

Geometry flows one way: positions -> exact squared lengths and areas
(:class:`~ddg_oracle.reference.metric.PiecewiseFlatSurface`) -> cotangents -> weights ->
operators.  Cotangents and weights are :class:`~ddg_oracle.reference.exact.Surd` values
(one square root per face area); energies of rational functions are Surds.

>>> from ddg_oracle.reference import surfaces
>>> s = surfaces.grid(1, 1)              # unit square, diagonal (0,0)-(1,1)
>>> L = cotan_laplacian(s)
>>> L[0, 1], L[0, 3], L[0, 0]            # the diagonal's weight is 0 (two right angles)
(Fraction(-1, 2), Fraction(0, 1), Fraction(1, 1))
>>> dirichlet_energy(L, [0, 1, 0, 1]) == dirichlet_energy_pl(s, [0, 1, 0, 1])   # T3.6
True
"""

from __future__ import annotations

from fractions import Fraction
from typing import Iterable, Sequence

from . import cotan_fast, cotangents
from .curvature import corner_angles
from .errors import BadShape, InputError
from .exact import Angle, Surd, corner_angle, pi, sqrt
from .exact.rationals import on_common_denominator
from .metric import PiecewiseFlatSurface, as_metric, heron16
from .polyhedral import PolyhedralSurface
from .exact.surds import exact_sum, rounded_root_sum, simplest
from .sparse import SparseMatrix, exact_number
from .combinatorics import face_of, opposite_corner
from .linear import dot, sub

__all__ = ["graph_laplacian", "dirichlet_energy", "cotan_weights", "cotan_weights_from_corners", "cotan_weighted_edges",
           "cotan_laplacian", "cotan_laplacian_from_weights", "dirichlet_energy_pl",
           "dirichlet_inner_product_pl", "dirichlet_energy_gradient_pl",
           "gradient_pl", "vertex_areas_barycentric", "vertex_areas_voronoi",
           "opposite_angle_sum", "weight_sign_by_angles", "weight_signs_by_angles",
           "cotan_weight_by_sines",
           "metric_of_surface"]

_ZERO = Fraction(0)


# Kept as a name for the chapter-3 modules; one definition: ddg_oracle.reference.metric.as_metric.
metric_of_surface = as_metric


# --- D3.1: weighted graphs ----------------------------------------------------------


def graph_laplacian(n: int, weighted_edges: Iterable) -> SparseMatrix:
    """D3.1: the Laplacian of a weighted graph on vertices ``0..n-1``, any real weights.

    ``weighted_edges``: ``(i, j, nu)`` triples, one per edge (several edges between
    the same vertices are allowed and summed; loops ``i == j`` contribute
    nothing).  ``(Lap f)(i) = sum_j nu(ij) (f(i) - f(j))``: diagonal ``sum nu``,
    off-diagonal ``-nu``.  Weights are taken exactly (floats as dyadic rationals).

    >>> L = graph_laplacian(3, [(0, 1, 1), (1, 2, 1)])      # the path Z, Example 3.1
    >>> L.matvec([0, 1, 4])                                  # 2 f(1) - f(0) - f(2) = -2
    [Fraction(-1, 1), Fraction(-2, 1), Fraction(3, 1)]
    """
    entries = []
    for i, j, w in weighted_edges:
        if not (0 <= i < n and 0 <= j < n):
            raise InputError(f"edge ({i}, {j}) has an endpoint outside 0..{n - 1}")
        if i == j:
            continue
        w = exact_number(w, f"weight of edge ({i}, {j})")
        entries += [(i, i, w), (j, j, w), (i, j, -w), (j, i, -w)]
    return SparseMatrix.from_entries((n, n), entries)


def dirichlet_energy(weights, f: Sequence):
    """D3.1: ``E(f) = 1/2 sum_edges nu(ij) (f(i) - f(j))^2``, exact.

    ``weights`` is either a Laplacian (:class:`SparseMatrix`, then
    ``E = 1/2 f^T Lap f``) or an iterable of ``(i, j, nu)`` edge triples (the
    sum over edges, computed without any matrix).

    >>> dirichlet_energy([(0, 1, 2), (1, 2, 1)], [0, 1, 3])   # 1/2 (2*1 + 1*4)
    Fraction(3, 1)
    >>> dirichlet_energy(graph_laplacian(3, [(0, 1, 2), (1, 2, 1)]), [0, 1, 3])
    Fraction(3, 1)
    """
    if isinstance(weights, SparseMatrix):
        return simplest(weights.quadratic_form(list(f)) / 2)
    terms = []
    for i, j, w in weights:
        d = f[i] - f[j]
        if d:
            terms.append(exact_number(w) * d * d)
    return simplest(exact_sum(terms) / 2)


# --- (3.3): cotan weights and the cotan Laplacian ---------------------------------------


def cotan_weights(surface) -> dict[int, Surd]:
    """(3.3): the cotan weight of every edge, keyed by edge id (boundary edges included).

    ``nu(e) = 1/2 (cot alpha + cot alpha')`` for an interior edge, ``1/2 cot alpha``
    for a boundary edge, alpha, alpha' the corner angles opposite the edge; a
    loop edge gets its weight too.  Exact: Surds, or Fractions where rational.

    The definition is :func:`cotan_weights_from_corners`.  For a polyhedral
    surface, or a piecewise flat one with rational squared lengths, this
    returns the equal weights computed by
    :func:`ddg_oracle.reference.cotan_fast.cotan_weights_fast` (integer arithmetic,
    canonical forms on demand; equality tested edge by edge).

    >>> from ddg_oracle.reference import surfaces
    >>> w = cotan_weights(surfaces.grid(1, 1))
    >>> sorted(str(x) for x in w.values())
    ['0', '1/2', '1/2', '1/2', '1/2']
    """
    if cotangents.applies(surface):
        return cotan_fast.cotan_weights_fast(surface)
    return cotan_weights_from_corners(surface)


def cotan_weights_from_corners(surface) -> dict[int, Surd]:
    """The definition of :func:`cotan_weights` (3.3), corner by corner: accepts every
    surface (irrational squared lengths too).  The cotan weight of every edge, keyed by
    edge id (boundary edges included).

    ``nu(e) = 1/2 (cot alpha + cot alpha')`` for an interior edge, ``1/2 cot alpha``
    for a boundary edge, alpha, alpha' the corner angles opposite the edge.  A
    loop edge gets its weight too (it is an edge of the triangulation); only the
    matrix ignores it.  Exact: Surds, or Fractions where rational.

    >>> from ddg_oracle.reference import surfaces
    >>> w = cotan_weights_from_corners(surfaces.grid(1, 1))
    >>> sorted(str(x) for x in w.values())
    ['0', '1/2', '1/2', '1/2', '1/2']
    """
    m = metric_of_surface(surface)
    t = m.triangulation
    cot = m.corner_cot
    out = {}
    for e in range(t.n_edges):
        h, g = t.edge_halfedges(e)
        # halfedge 3f + k is opposite corner k + 2 (mod 3) of face f
        w = cot(face_of(h), opposite_corner(h))
        if g >= 0:
            w = w + cot(face_of(g), opposite_corner(g))
        out[e] = simplest(w / 2)
    return out


def cotan_weighted_edges(surface) -> list[tuple[int, int, Surd]]:
    """``(i, j, nu(e))`` for every edge e (the input of :func:`graph_laplacian` and
    :func:`dirichlet_energy`); loops included, with i == j."""
    t = metric_of_surface(surface).triangulation
    return [(*t.edge_vertices(e), w) for e, w in cotan_weights(surface).items()]


def cotan_laplacian(surface) -> SparseMatrix:
    """Definition 3.2: the cotan Laplacian, ``(Lap f)(i) = sum_j nu(ij) (f(i) - f(j))``.

    Exact sparse matrix, positive semidefinite (its negative is libigl's
    ``cotmatrix``); entry (i, j), i != j, is minus the sum of the cotan weights
    of all edges between i and j; loops contribute nothing.

    The definition is :func:`cotan_laplacian_from_weights`.  For a polyhedral
    surface, or a piecewise flat one with rational squared lengths, this
    returns the equal matrix computed by
    :func:`ddg_oracle.reference.cotan_fast.cotan_laplacian_fast` (integer arithmetic,
    ~10x faster on float meshes; equality tested entry by entry); with some irrational
    squared lengths (after intrinsic flips), mostly rational ones, by
    :func:`~ddg_oracle.reference.cotan_fast.cotan_laplacian_mixed` (the same, on the
    rational faces).

    >>> from ddg_oracle.reference import surfaces
    >>> L = cotan_laplacian(surfaces.tetrahedron())
    >>> L.is_symmetric(), sum(L.matvec([1, 1, 1, 1])) == 0
    (True, True)
    """
    if cotangents.applies(surface):
        return cotan_fast.cotan_laplacian_fast(surface)
    if cotan_fast.partly_applies(surface):
        return cotan_fast.cotan_laplacian_mixed(surface)
    return cotan_laplacian_from_weights(surface)


def cotan_laplacian_from_weights(surface) -> SparseMatrix:
    """Definition 3.2 as written: the cotan weights (:func:`cotan_weights_from_corners`) added
    edge by edge into the matrix.  The definition :func:`cotan_laplacian` is
    tested against; it accepts every surface (irrational squared lengths too).

    >>> from ddg_oracle.reference import surfaces
    >>> cotan_laplacian_from_weights(surfaces.grid(1, 1))[0, 1]
    Fraction(-1, 2)
    """
    m = metric_of_surface(surface)
    t = m.triangulation
    n = t.n_vertices
    w = cotan_weights_from_corners(m)
    rows: dict[int, dict[int, object]] = {}
    diag: list = [None] * n
    for e, we in w.items():
        i, j = t.edge_vertices(e)
        if i == j or not we:
            continue
        for a, b in ((i, j), (j, i)):
            r = rows.setdefault(a, {})
            r[b] = r[b] - we if b in r else -we
            diag[a] = we if diag[a] is None else diag[a] + we
    for i, d in enumerate(diag):
        if d is not None:
            rows.setdefault(i, {})[i] = d
    return SparseMatrix((n, n), rows)


# --- T3.6: the Dirichlet energy of the piecewise linear interpolant -------------------------


def _triangulation(surface):
    if isinstance(surface, PolyhedralSurface):
        return surface.triangulation
    return metric_of_surface(surface).triangulation


def gradient_pl(surface: PolyhedralSurface, f: Sequence, face: int) -> tuple:
    """The gradient of the affine interpolant of f on ``face``, a vector of R^n, exact.

    With u, v the edge vectors from corner 0 and G their Gram matrix,
    ``grad f = c1 u + c2 v`` where ``G (c1, c2) = (f1 - f0, f2 - f0)``: the
    unique vector in the face's plane with ``<grad f, u> = f1 - f0`` and
    ``<grad f, v> = f2 - f0``.  Rational for rational positions and values.
    """
    if not isinstance(surface, PolyhedralSurface):
        raise InputError("gradient_pl needs positions (a PolyhedralSurface); use "
                         "dirichlet_inner_product_pl for an intrinsic surface")
    p = surface.positions
    a, b, c = surface.triangulation.faces[face]
    u, v = sub(p[b], p[a]), sub(p[c], p[a])
    uu, uv, vv = dot(u, u), dot(u, v), dot(v, v)
    d1, d2 = f[b] - f[a], f[c] - f[a]
    det = uu * vv - uv * uv
    if not det:
        raise InputError(f"face {face} is degenerate (zero area): no gradient")
    c1 = (vv * d1 - uv * d2) / det
    c2 = (uu * d2 - uv * d1) / det
    return tuple(c1 * x + c2 * y for x, y in zip(u, v))


def dirichlet_inner_product_pl(surface, f: Sequence, g: Sequence):
    """``integral over S of <grad f, grad g> dA`` for the piecewise linear interpolants.

    Computed face by face from the Gram matrix G of the edge vectors u = p1 - p0,
    v = p2 - p0 (or of the edge lengths, for an intrinsic surface), independently of any
    cotangent: the gradients are ``grad f = c1 u + c2 v`` with ``G (c1, c2) = df``
    (:func:`gradient_pl`), so ``<grad f, grad g> = df^T G^-1 dg``, and the face's area is
    ``sqrt(det G) / 2``; ``df = (f1 - f0, f2 - f0)``.  Exact (a Surd).  T3.6: equals
    ``f^T Lap g`` with the cotan Laplacian.
    """
    t = _triangulation(surface)
    if len(f) != t.n_vertices or len(g) != t.n_vertices:
        raise BadShape(f"functions of lengths {len(f)}, {len(g)} on {t.n_vertices} vertices")
    m = metric_of_surface(surface)          # raises DegenerateFace naming a zero-area face
    terms = []
    for face, (a, b, c) in enumerate(t.faces):
        # the Gram route for positions too: the gradient vectors themselves (gradient_pl,
        # twice per face) took 1.7 times as long for the same number (tests/test_laplacian.py
        # keeps the two equal); G and the area from the metric's exact squared lengths and
        # areas (integers on a common denominator, computed once per surface)
        uu, uv, vv, det = _gram_of_lengths(m, face)
        df1, df2 = f[b] - f[a], f[c] - f[a]
        dg1, dg2 = (df1, df2) if g is f else (g[b] - g[a], g[c] - g[a])
        inner = (vv * df1 * dg1 - uv * (df1 * dg2 + df2 * dg1) + uu * df2 * dg2) / det
        if inner:
            terms.append(m.area(face) * inner)
    return exact_sum(terms)


def _gram_of_lengths(m: PiecewiseFlatSurface, face: int) -> tuple:
    """(uu, uv, vv, det G) of a face from its exact squared lengths: u, v the edges from
    corner 0 to corners 1 and 2, ``uv = (|u|^2 + |v|^2 - |u - v|^2) / 2``, ``det G = 4 A^2``
    (positive: the metric is valid)."""
    l0, l1, l2 = m.face_squared_lengths(face)   # |01|^2, |12|^2, |20|^2
    uv = (l0 + l2 - l1) / 2
    return l0, uv, l2, l0 * l2 - uv * uv


def dirichlet_energy_gradient_pl(surface, f: Sequence) -> list:
    """C3.4 / T3.6: the gradient of ``E(f)``, ``dE/df(i) = integral <grad f, grad phi_i> dA``
    (``phi_i`` the hat function of vertex i), for every vertex in one pass, exact Surds.

    Face by face from the Gram matrix G of the edge vectors u = p1 - p0, v = p2 - p0
    (or of the edge lengths), as in :func:`dirichlet_inner_product_pl`: with
    ``(d1, d2) = (f1 - f0, f2 - f0)``, the hats of corners 1 and 2 give
    ``(vv d1 - uv d2) / det G`` and ``(uu d2 - uv d1) / det G``, the hat of corner 0 minus
    their sum (the three hats sum to 1), each times the area ``sqrt(det G) / 2``.  Equals
    ``dirichlet_inner_product_pl(surface, f, e_i)`` for every i, without touching the faces
    away from i n times.
    """
    t = _triangulation(surface)
    if len(f) != t.n_vertices:
        raise BadShape(f"a function of length {len(f)} on {t.n_vertices} vertices")
    m = metric_of_surface(surface)          # raises DegenerateFace naming a zero-area face
    terms: list = [[] for _ in range(t.n_vertices)]
    for face, (a, b, c) in enumerate(t.faces):
        d1, d2 = f[b] - f[a], f[c] - f[a]
        if not (d1 or d2):
            continue
        uu, uv, vv, det = _gram_of_lengths(m, face)
        area = m.area(face)
        hat_b, hat_c = (vv * d1 - uv * d2) / det, (uu * d2 - uv * d1) / det
        for v, x in ((a, -(hat_b + hat_c)), (b, hat_b), (c, hat_c)):
            if x:
                terms[v].append(area * x)
    return [exact_sum(ts) for ts in terms]


def dirichlet_energy_pl(surface, f: Sequence):
    """T3.6: ``E(f) = 1/2 integral |grad f|^2 dA`` of the piecewise linear interpolant.

    Face by face from gradients (see :func:`dirichlet_inner_product_pl`), an
    independent computation of what ``1/2 sum nu(ij) (f(i) - f(j))^2`` gives
    with cotan weights.  Exact.

    >>> from ddg_oracle.reference import surfaces
    >>> dirichlet_energy_pl(surfaces.grid(2, 2), [i for i in range(3) for j in range(3)])
    Fraction(2, 1)
    """
    return dirichlet_inner_product_pl(surface, f, f) / 2


# --- mass matrices (lumped vertex areas) -------------------------------------------------


def vertex_areas_barycentric(surface) -> list:
    """One third of the area of every incident face, per vertex (exact Surds).

    A lumped mass matrix, integrated (an area per vertex, not a density).

    A face with a repeated vertex (non-regular triangulations) gives that vertex
    a third per corner.  Sums to the total area.
    """
    m = metric_of_surface(surface)
    t = m.triangulation
    out: list = [_ZERO] * t.n_vertices
    for f, face in enumerate(t.faces):
        third = m.areas[f] / 3
        for v in face:
            out[v] = out[v] + third
    return out


def vertex_areas_voronoi(surface) -> list:
    """Mixed Voronoi areas (Meyer, Desbrun, Schröder, Barr 2003), exact Surds.

    A lumped mass matrix, integrated (an area per vertex, not a density).

    Per face: if no angle is obtuse, the vertex at corner c gets its Voronoi
    region ``1/8 (|e1|^2 cot(opp e1) + |e2|^2 cot(opp e2))`` (e1, e2 the two
    sides at c, each with the cotangent of the angle opposite it); if the face
    is obtuse, the obtuse vertex gets area/2 and the other two area/4.  The
    obtuse test is exact on squared lengths.  A right triangle takes the first
    rule (both rules agree there).  The regions of a non-obtuse face are its
    circumcentric subdivision (Figure 3.4), so they sum to the face area by L3.7;
    the areas sum to the total area.
    """
    m = metric_of_surface(surface)
    t = m.triangulation
    out: list = [_ZERO] * t.n_vertices
    for f, face in enumerate(t.faces):
        l0, l1, l2 = m.face_squared_lengths(f)       # |01|^2, |12|^2, |20|^2
        # (adjacent, adjacent, opposite) squared lengths at corners 0, 1, 2
        sides = ((l0, l2, l1), (l0, l1, l2), (l1, l2, l0))
        obtuse = [c for c in range(3) if sides[c][2] > sides[c][0] + sides[c][1]]
        if obtuse:
            a = m.areas[f]
            for c in range(3):
                out[face[c]] = out[face[c]] + (a / 2 if c == obtuse[0] else a / 4)
            continue
        k0, k1, k2 = (m.corner_cot(f, c) for c in range(3))
        parts = ((l0 * k2 + l2 * k1) / 8, (l0 * k2 + l1 * k0) / 8, (l1 * k0 + l2 * k1) / 8)
        for c in range(3):
            out[face[c]] = out[face[c]] + parts[c]
    return out


def vertex_areas_floats(surface, kind: str = "voronoi") -> list[float]:
    """L3.7's mass matrices as floats: :func:`vertex_areas_voronoi` (``kind="voronoi"``) or
    :func:`vertex_areas_barycentric` (``"barycentric"``), each area correctly rounded, from
    integers (no Surd
    arithmetic unless an area is within 2^-2048 relative of a rounding boundary).

    Per face, with the squared lengths on their common denominator d (integers L) and
    ``G = heron16(L) = 16 A^2 d^2``: ``A = sqrt(G) / (4 d)``, ``cot = n / sqrt(G)`` with
    ``n = a + b - o`` (integers), so each part the definition adds at a vertex is
    ``N / (D sqrt(G))`` with integers N, D: a Voronoi part ``(L_a n_a + L_b n_b) / (8 d
    sqrt(G))``, ``A / 2 = G / (8 d sqrt(G))``, ``A / 4``, ``A / 3``; the same obtuse test
    on the same squared lengths.  Sums of such terms are rounded by
    :func:`~ddg_oracle.reference.exact.surds.rounded_root_sum`.
    """
    if kind not in ("voronoi", "barycentric"):
        raise InputError(f"vertex areas: kind must be 'voronoi' or 'barycentric', got {kind!r}")
    m = metric_of_surface(surface)
    t = m.triangulation
    if not all(isinstance(x, Fraction) for x in m.squared_lengths):
        exact = vertex_areas_voronoi(m) if kind == "voronoi" else vertex_areas_barycentric(m)
        return [float(a) for a in exact]
    terms: list[list] = [[] for _ in range(t.n_vertices)]
    for f, face in enumerate(t.faces):
        (l0, l1, l2), d = on_common_denominator(m.face_squared_lengths(f))
        G = heron16(l0, l1, l2)
        if kind == "barycentric":
            parts = [(G, 12 * d)] * 3
        else:
            sides = ((l0, l2, l1), (l0, l1, l2), (l1, l2, l0))
            obtuse = [c for c in range(3) if sides[c][2] > sides[c][0] + sides[c][1]]
            if obtuse:
                parts = [(G, 8 * d) if c == obtuse[0] else (G, 16 * d) for c in range(3)]
            else:
                n0, n1, n2 = l0 + l2 - l1, l0 + l1 - l2, l1 + l2 - l0     # corners 0, 1, 2
                parts = [(l0 * n2 + l2 * n1, 8 * d), (l0 * n2 + l1 * n0, 8 * d),
                         (l1 * n0 + l2 * n1, 8 * d)]
        for c in range(3):
            N, D = parts[c]
            if N:
                terms[face[c]].append((N, D * D * G))      # N / (D sqrt(G)) = N / sqrt(D^2 G)
    return [rounded_root_sum(x) for x in terms]


# --- E3.12: the sign of a cotan weight ----------------------------------------------------


def _opposite_corners(t, e: int) -> list[tuple[int, int]]:
    return [(face_of(h), opposite_corner(h)) for h in t.edge_halfedges(e) if h >= 0]


def opposite_angle_sum(surface, e: int) -> Angle:
    """``alpha_ij + alpha_ji`` (interior edge) or ``alpha_ij`` (boundary edge): exact Angle."""
    m = metric_of_surface(surface)
    total = Angle()
    for f, c in _opposite_corners(m.triangulation, e):
        total = total + corner_angle(m.corner_cot(f, c))
    return total


def weight_signs_by_angles(surface) -> list[int]:
    """E3.12 for every edge: ``[weight_sign_by_angles(surface, e) for e in edges]``, from
    the corner angles computed once (:func:`ddg_oracle.reference.curvature.corner_angles`,
    the fast route where it applies: equal angles)."""
    m = metric_of_surface(surface)
    t = m.triangulation
    angles = corner_angles(m)
    half = pi * Fraction(1, 2)
    out = []
    for e in range(t.n_edges):
        total = sum((angles[f][c] for f, c in _opposite_corners(t, e)), Angle())
        out.append(((half if t.is_boundary_edge(e) else pi) - total).sign())
    return out


def weight_sign_by_angles(surface, e: int) -> int:
    """E3.12: the sign of ``nu(e)`` read off the angles alone, decided exactly.

    ``nu = sin(alpha + alpha') / (2 sin alpha sin alpha')`` with both angles in
    (0, pi), so ``sign(nu) = sign(pi - (alpha + alpha'))`` on an interior edge and
    ``sign(pi/2 - alpha)`` on a boundary edge.  Computed with exact
    :class:`~ddg_oracle.reference.exact.Angle` sums compared to pi, never from a cotangent
    sum: an independent check of the sign of :func:`cotan_weights`.
    """
    m = metric_of_surface(surface)
    interior = not m.triangulation.is_boundary_edge(e)
    bound = pi if interior else pi * Fraction(1, 2)
    return (bound - opposite_angle_sum(m, e)).sign()


def _sin_cos(m: PiecewiseFlatSurface, f: int, c: int) -> tuple[Surd, Surd]:
    """(sin, cos) of corner c of face f from lengths: sin = 2A / (l1 l2), cos by the cosine law."""
    l0, l1, l2 = m.face_squared_lengths(f)
    a, b, o = ((l0, l2, l1), (l0, l1, l2), (l1, l2, l0))[c]
    ab = sqrt(a * b)
    return 2 * m.areas[f] / ab, (a + b - o) / (2 * ab)


def cotan_weight_by_sines(surface, e: int) -> Surd:
    """(3.12) done right: ``nu = sin(alpha + alpha') / (2 sin alpha sin alpha')``, exact.

    Sines and cosines come from lengths and the face area (not from
    cotangents), so this is an independent evaluation of the cotan weight.
    The notes print ``sin(alpha + alpha') / (sin alpha sin alpha')``, twice the
    weight (catalog E3.12; the sign statement is unaffected).  On a boundary
    edge: ``cos alpha / (2 sin alpha)``.
    """
    m = metric_of_surface(surface)
    corners = _opposite_corners(m.triangulation, e)
    if len(corners) == 1:
        s, c = _sin_cos(m, *corners[0])
        return c / (2 * s)
    (s1, c1), (s2, c2) = (_sin_cos(m, *fc) for fc in corners)
    return (s1 * c2 + c1 * s2) / (2 * s1 * s2)
