"""Float views of the exact reference: the correctly rounded values the checks compare
implementations with and the reference adapter answers with, each computed once per
surface object (:func:`.memo.of`), read-only.

Corner angles (D2.6), angle defects (D2.2), turning angles (R2.4), mean curvature per
edge (D2.3) and the cotan Laplacian (D3.1) with its exact matrix.  Exact values are
rounded once (``float()`` of an exact number is correctly rounded); the derived bounds
they are compared within are :mod:`.bounds`'.  For positions in R^3, the ``*_view_bounds``
functions give floats lo <= view <= hi from rigorous float enclosures (:mod:`.enclosures`,
issue 46) of those, the weight signs (E3.12), the area gradient (T3.9) and the vertex
areas (L3.7), so that a check decides without the exact values where the enclosures can.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from ..reference import curvature as ref
from ..reference.cotan_fast import laplacian_parts
from ..reference.exact.surds import Quotient, rounded_sum, sum_is_zero
from ..reference.laplacian import cotan_laplacian
from ..reference.metric import PiecewiseFlatSurface

from . import memo

__all__ = ["validate", "position_enclosure", "float_positions", "corner_angle_views",
           "corner_angle_view_bounds", "defect_views", "turning_views",
           "vertex_angle_view_bounds", "weight_signs", "mean_curvature_views",
           "mean_curvature_view_bounds", "halfedge_table", "interior_edge_corners",
           "exact_laplacian", "laplacian_view", "laplacian_view_bounds",
           "area_gradient_view_bounds", "vertex_area_view_bounds"]


def validate(surface) -> None:
    """Raise :class:`~ddg_oracle.reference.errors.DegenerateFace` where ``surface.metric()``
    would (a zero-length edge, or a face of zero area), without building the exact metric
    when a float certificate shows every face's area nonzero (:func:`.enclosures.nondegenerate`:
    positions in R^3 that are all floats); otherwise the exact metric decides, and names
    the face.  Once per surface object."""
    memo.of(_validate, surface)


def _validate(surface) -> bool:
    from .enclosures import nondegenerate
    t = surface.triangulation
    if not (float_positions(surface)
            and nondegenerate(position_enclosure(surface).value, t.faces)):
        surface.metric()
    return True


def position_enclosure(surface):
    """The positions of a surface in R^3 as an enclosure (:func:`.enclosures.points`), once
    per surface object: every enclosure of its quantities starts from it."""
    return memo.of(_position_enclosure, surface)


def _position_enclosure(surface):
    from .enclosures import points
    return points(surface.positions)


def given_float_positions(surface, V) -> None:
    """Say that ``surface``'s exact positions are the floats ``V`` ((n, 3) float64, exactly):
    its :func:`position_enclosure` is then ``V`` with no error, without converting 3 n
    Fractions to floats and checking each (898,752 faces: 1.5 s per process)."""
    from .enclosures import Enclosure
    memo.given(_position_enclosure, surface, Enclosure(V))


def float_positions(surface) -> bool:
    """Whether ``surface`` has positions in R^3 that are all floats (its enclosures then
    start exact)."""
    return (getattr(surface, "dimension", None) == 3
            and not position_enclosure(surface).err.any())


def corner_angle_views(surface) -> np.ndarray:
    """(m, 3) float views of the exact corner angles of the piecewise flat metric of
    ``surface`` (D2.6), once per surface object.  The metric's cotangents are functions of
    the squared edge lengths and the face areas, and its areas are Heron's of the lengths
    identically (``reference.metric.metric_of``): these are the angles the lengths alone
    determine (tests/test_curvature.py checks them against a metric built from lengths)."""
    return memo.of(_corner_angle_views, surface)


def _corner_angle_views(surface) -> np.ndarray:
    return np.array([[float(a) for a in face] for face in ref.corner_angles(surface.metric())])


def corner_angle_view_bounds(surface) -> tuple[np.ndarray, np.ndarray]:
    """D2.6: (lo, hi), (m, 3) each: floats lo <= :func:`corner_angle_views` <= hi from rigorous
    float enclosures of the exact angles (:mod:`.enclosures`), once per surface object;
    the exact views themselves (lo = hi) for a surface without positions in R^3."""
    return memo.of(_corner_angle_view_bounds, surface)


def _corner_angle_view_bounds(surface):
    from .enclosures import rounding_bounds
    validate(surface)                                       # raises DegenerateFace
    if getattr(surface, "dimension", None) != 3:
        x = corner_angle_views(surface)
        return x, x
    return rounding_bounds(_corner_enclosure(surface))


def _corner_enclosure(surface):
    """The corners' angle enclosure of a surface in R^3, once per surface object."""
    return memo.of(_corners_of, surface)


def _corners_of(surface):
    from .enclosures import corner_angle_enclosure
    return corner_angle_enclosure(position_enclosure(surface), surface.triangulation.faces)


def weight_signs(surface) -> list[int]:
    """E3.12's sign of pi - (alpha + alpha') per edge (pi / 2 - alpha on the boundary), as
    ``reference.laplacian.weight_signs_by_angles`` gives them: from the enclosures of the
    corner angles where they decide it (0 outside the enclosure), exactly per edge where
    not; once per surface object."""
    return memo.of(_weight_signs, surface)


def _weight_signs(surface):
    from .enclosures import PI, Enclosure
    from ..reference.laplacian import weight_sign_by_angles, weight_signs_by_angles
    if getattr(surface, "dimension", None) != 3:
        return weight_signs_by_angles(surface)
    validate(surface)                                       # raises DegenerateFace
    corners = _corner_enclosure(surface)
    pairs = halfedge_table(surface)
    h, h2 = pairs[:, 0], pairs[:, 1]
    inner = h2 >= 0
    total = corners[h // 3, (h % 3 + 2) % 3]                 # the opposite corner of h
    twin = corners[np.where(inner, h2, h) // 3, (np.where(inner, h2, h) % 3 + 2) % 3]
    total = total + Enclosure(np.where(inner, twin.value, 0.0), np.where(inner, twin.err, 0.0))
    half = Enclosure(np.where(inner, PI.value, PI.value / 2), np.where(inner, PI.err, PI.err / 2))
    left = half - total
    with np.errstate(invalid="ignore"):
        sure = np.where(left.value - left.err > 0, 1, np.where(left.value + left.err < 0, -1, 0))
    return [int(x) if x else weight_sign_by_angles(surface, e)
            for e, x in enumerate(sure.tolist())]


def vertex_angle_view_bounds(surface, what: str):
    """D2.2 / R2.4: (vertices, lo, hi): ``what="defects"``: the interior vertices in
    :func:`defect_views`' order and floats lo <= float(K(v)) <= hi; ``"turning"``: the
    boundary vertices and the turning angles' (:func:`turning_views`); from the enclosures
    of the corner angles summed (:mod:`.enclosures`), once per surface object."""
    return memo.of(_vertex_angle_view_bounds, surface)[what]


def _vertex_angle_view_bounds(surface):
    from .enclosures import PI, TWO_PI, angle_sum_enclosure, rounding_bounds
    t = surface.triangulation
    boundary = t.boundary_vertices()
    out = {}
    for what, keep in (("defects", False), ("turning", True)):
        out[what] = [v for v in range(t.n_vertices) if (v in boundary) == keep]
    if getattr(surface, "dimension", None) != 3:
        surface.metric()
        exact = {"defects": defect_views(surface), "turning": turning_views(surface)}
        return {w: (vs, *(2 * (np.array([exact[w][v] for v in vs], dtype=np.float64),)))
                for w, vs in out.items()}
    validate(surface)                                       # raises DegenerateFace
    corners = _corner_enclosure(surface)
    sums = angle_sum_enclosure(corners, t.faces, t.n_vertices)
    result = {}
    for what, vs in out.items():
        idx = np.array(vs, dtype=np.int64)
        lo, hi = rounding_bounds((TWO_PI if what == "defects" else PI) - sums[idx])
        result[what] = (vs, lo, hi)
    return result


def defect_views(surface) -> dict:
    """{v: float(K(v))}: the correctly rounded exact angle defects (D2.2) of the interior
    vertices of ``surface``, once per surface object (:func:`.memo.of`: the reference
    adapter answers with these)."""
    return memo.of(_defect_views, surface)


def _defect_views(surface) -> dict:
    return {v: float(k) for v, k in ref.angle_defects(surface.metric()).items()}


def turning_views(surface) -> dict:
    """{v: float(kappa(v))}: the correctly rounded exact turning angles (R2.4) of the
    boundary vertices, once per surface object."""
    return memo.of(_turning_views, surface)


def _turning_views(surface) -> dict:
    return {v: float(k) for v, k in ref.turning_angles(surface.metric()).items()}


def mean_curvature_views(surface) -> dict:
    """{(i, j): float(H(e))} (i < j) of the exact D2.3 values over the interior edges,
    correctly rounded, once per surface object."""
    return memo.of(_mean_curvature_views, surface)


def _mean_curvature_views(surface) -> dict:
    t = surface.triangulation
    return {tuple(sorted(t.edge_vertices(e))): float(h)
            for e, h in ref.mean_curvature(surface).items()}


def mean_curvature_view_bounds(surface):
    """(keys, edges, lo, hi): per interior edge of ``surface`` in :func:`mean_curvature_views`'
    order, its key (i, j) (i < j), its edge id, and floats lo <= float(H(e)) <= hi from a
    rigorous float enclosure of the exact H(e) (:mod:`.enclosures`), without the exact
    values; once per surface object.  Raises as the exact values would: the faces'
    degeneracy checked on the exact metric, and the edges where the exact route may raise
    (faces oriented inconsistently, or folded onto each other) computed exactly first, in
    order."""
    return memo.of(_mean_curvature_view_bounds, surface)


def _mean_curvature_view_bounds(surface):
    from .enclosures import mean_curvature_enclosure, rounding_bounds
    if getattr(surface, "dimension", None) != 3:
        mean_curvature_views(surface)                       # raises as the exact route
    validate(surface)                                       # raises DegenerateFace
    edges, I, J, K, L, reversed_ = interior_edge_corners(surface)
    enc, cos_part = mean_curvature_enclosure(position_enclosure(surface), I, J, K, L)
    # the exact route raises at an inconsistent gluing or a fold (height 0, <n_f, n_g> <= 0):
    # those edges exactly, first and in order, so that the same edge raises
    with np.errstate(invalid="ignore"):
        maybe_folded = (enc.value == 0) & ~(cos_part.value - cos_part.err > 0)
    for n in sorted(set(reversed_) | set(np.flatnonzero(maybe_folded).tolist())):
        ref.mean_curvature_at(surface, edges[n])
    lo, hi = rounding_bounds(enc)
    keys = list(zip(np.minimum(I, J).tolist(), np.maximum(I, J).tolist()))
    return keys, edges, lo, hi


def halfedge_table(surface) -> np.ndarray:
    """(n_edges, 2): each edge's two halfedges (-1 for a boundary edge's missing twin), once
    per surface object."""
    return memo.of(_halfedge_table, surface)


def _halfedge_table(surface) -> np.ndarray:
    t = surface.triangulation
    return np.array([t.edge_halfedges(e) for e in range(t.n_edges)],
                    dtype=np.int64).reshape(-1, 2)


def interior_edge_corners(surface):
    """(edges, I, J, K, L, reversed): the interior edges' ids and, per interior edge, the
    vertices of D2.3's formula (its first halfedge runs I -> J in face (I, J, K), its twin
    J -> I in (J, I, L)) and the positions (in that list) of the edges whose gluing is
    reversed; once per surface object."""
    return memo.of(_interior_edge_corners, surface)


def _interior_edge_corners(surface):
    t = surface.triangulation
    F = np.asarray(t.faces, dtype=np.int64).reshape(-1, 3)
    table = halfedge_table(surface)
    inner = table[:, 1] >= 0
    h, h2 = table[inner, 0], table[inner, 1]
    f, c, g, c2 = h // 3, h % 3, h2 // 3, h2 % 3
    I, J, K = F[f, c], F[f, (c + 1) % 3], F[f, (c + 2) % 3]   # h runs I -> J in (I, J, K)
    L = F[g, (c2 + 2) % 3]                                   # the twin's opposite corner
    reversed_ = [n for n, x in enumerate(h.tolist()) if t.reversed_gluing(x)]
    return np.flatnonzero(inner).tolist(), I, J, K, L, reversed_


def exact_laplacian(surface):
    """The exact cotan Laplacian (D3.1) of ``surface`` (a surface or a metric), once per
    object (:func:`.memo.of`: the properties' reference values and the reference adapter's
    answer on a mesh file are one computation); read-only."""
    return memo.of(cotan_laplacian, surface)


def laplacian_view(surface):
    """The float view (scipy CSR, each entry correctly rounded) of :func:`exact_laplacian`,
    once per object; read-only (copy before changing it)."""
    return memo.of(_laplacian_view, surface)


def _laplacian_view(surface):
    if isinstance(surface, PiecewiseFlatSurface) and not all(
            type(x) is Fraction for x in surface.squared_lengths):
        return _flipped_laplacian_view(surface)
    return exact_laplacian(surface).to_scipy()


def laplacian_view_bounds(surface):
    """D3.1: (rows, cols, lo, hi) or None: every edge's two off-diagonal entries of the exact
    cotan Laplacian and every vertex's diagonal entry (arrays on the surface's vertices),
    with floats lo <= x <= hi for the correctly rounded view x of each
    (:func:`laplacian_view`'s entry; exact zeros included) from rigorous float enclosures
    of the corner cotangents summed (:mod:`.enclosures`), without the exact values; once
    per surface object.  None for a surface without positions in R^3 or with two edges
    between one pair of vertices (their weights share an entry)."""
    return memo.of(_laplacian_view_bounds, surface)


def _laplacian_view_bounds(surface):
    if getattr(surface, "dimension", None) != 3:
        return None
    validate(surface)                                       # raises DegenerateFace
    t = surface.triangulation
    return view_bounds_of(np.asarray(t.faces, dtype=np.int64).reshape(-1, 3),
                          halfedge_table(surface), corner_cots(surface), t.n_vertices)


def corner_cots(surface):
    """D2.6 / D3.1: (m, 3) :class:`~.enclosures.Enclosure`, every corner's cotangent from the
    positions (:func:`~.enclosures.corner_cot_enclosure`), once per surface object;
    read-only."""
    return memo.of(_corner_cots, surface)


def _corner_cots(surface):
    from .enclosures import corner_cot_enclosure
    return corner_cot_enclosure(position_enclosure(surface), surface.triangulation.faces)


def view_bounds_of(F, table, cot, n: int):
    """D3.1: :func:`laplacian_view_bounds` of the triangulation with faces ``F`` (m, 3), halfedge
    table ``table`` (:func:`halfedge_table`'s) and corner cotangents enclosed by ``cot``
    ((m, 3) Enclosure) on ``n`` vertices: (rows, cols, lo, hi), the first ``len(table)``
    entries the edges' (i, j) in edge order, or None where two edges join one pair of
    vertices or an edge is a loop."""
    from .enclosures import Enclosure, rounding_bounds, summed
    h, h2 = table[:, 0], table[:, 1]
    I, J = F[h // 3, h % 3], F[h // 3, (h % 3 + 1) % 3]
    if np.any(I == J) or len(np.unique(np.minimum(I, J) * n + np.maximum(I, J))) != len(I):
        return None
    inner = h2 >= 0
    first = cot[h // 3, (h % 3 + 2) % 3]                     # the corner opposite h
    g = np.where(inner, h2, h)
    twin = cot[g // 3, (g % 3 + 2) % 3]
    # nu(ij) = 1/2 (cot a + cot b), 1/2 cot a on the boundary (D3.1, 3.3)
    w = (first + Enclosure(np.where(inner, twin.value, 0.0),
                           np.where(inner, twin.err, 0.0))).scaled(0.5)
    diag = summed(Enclosure(np.concatenate([w.value, w.value]), np.concatenate([w.err, w.err])),
                  np.concatenate([I, J]), n)
    lo, hi = rounding_bounds(Enclosure(np.concatenate([-w.value, -w.value, diag.value]),
                                       np.concatenate([w.err, w.err, diag.err])))
    every = np.arange(n, dtype=np.int64)
    return np.concatenate([I, J, every]), np.concatenate([J, I, every]), lo, hi


def area_gradient_view_bounds(surface):
    """L3.8 / T3.9: (lo, hi), (k, 3) each, floats lo <= x <= hi for the correctly rounded
    exact area gradient x at each vertex of ``surface``
    (``reference.areas.area_gradient_floats``) from rigorous float enclosures
    (:mod:`.enclosures`), or None for positions that are not floats in R^3; once per
    surface object."""
    return memo.of(_area_gradient_view_bounds, surface)


def _area_gradient_view_bounds(surface):
    from .enclosures import area_gradient_enclosure, rounding_bounds
    enc = _per_vertex_enclosure(surface, area_gradient_enclosure)
    return None if enc is None else rounding_bounds(enc)


def _per_vertex_enclosure(surface, enclose):
    """``enclose(positions, faces, n_vertices)`` for a surface whose positions are floats in
    R^3 (validated first: raises DegenerateFace as the metric would), else None."""
    if not float_positions(surface):
        return None
    validate(surface)
    t = surface.triangulation
    return enclose(position_enclosure(surface), t.faces, t.n_vertices)


def vertex_area_view_bounds(surface):
    """L3.7: {"vertex_areas_voronoi": (lo, hi), "vertex_areas_barycentric": (lo, hi)}, (k,)
    each, floats lo <= x <= hi for the correctly rounded exact vertex areas x
    (``reference.laplacian.vertex_areas_floats``) from rigorous float enclosures
    (:mod:`.enclosures`), or None for positions that are not floats in R^3; once per
    surface object."""
    return memo.of(_vertex_area_view_bounds, surface)


def _vertex_area_view_bounds(surface):
    from .enclosures import rounding_bounds, vertex_area_enclosures
    encs = _per_vertex_enclosure(surface, vertex_area_enclosures)
    if encs is None:
        return None
    voronoi, bary = encs
    return {"vertex_areas_voronoi": rounding_bounds(voronoi),
            "vertex_areas_barycentric": rounding_bounds(bary)}


def _flipped_laplacian_view(m):
    """:func:`laplacian_view` of a metric with irrational squared lengths (after intrinsic
    flips), equal entry by entry and in its structure (exact zeros left out) to
    ``exact_laplacian(m).to_scipy()`` without that matrix: a flipped face's cotangent
    n / (4 A) has an area A with up to hundreds of square roots, whose exact inverse takes
    seconds; each entry is the correctly rounded sum of the exact rational faces' part and
    the flipped faces' half cotangents as quotients n / (8 A)
    (:func:`~ddg_oracle.reference.exact.rounded_sum`: enclosures, no division; an exact
    zero decided by cross-multiplying)."""
    import scipy.sparse as sp
    part, halves = laplacian_parts(m)
    quotients: dict = {}                    # the flipped faces' terms, per entry
    per_face: dict = {}
    for i, j, f, c in halves:
        q = per_face.get(f)
        if q is None:                       # a face's three corners share its 8 A
            d = 8 * m.areas[f]
            q = per_face[f] = [Quotient(n, d) if n else None
                               for n in m.face_cot_numerators(f)]
        q = q[c]
        if q is None:
            continue                        # a right angle: cot 0
        for key in ((i, j), (j, i), (i, i), (j, j)):
            quotients.setdefault(key, []).append(q)
    rows, cols, vals = [], [], []
    exact = {(i, j): v for i, j, v in part.entries()}     # nonzero: zeros are left out
    for (i, j), v in exact.items():         # the entries no flipped face touches: as they are
        if (i, j) not in quotients:
            rows.append(i)
            cols.append(j)
            vals.append(float(v))           # correctly rounded
    for (i, j), qs in quotients.items():
        v = exact.get((i, j))
        if i == j:                          # a diagonal: the quotients added
            ts = qs if v is None else [v, *qs]
            x = rounded_sum(ts)
        else:                               # off the diagonal: minus the quotients' sum
            ts = qs if v is None else [-v, *qs]
            x = -rounded_sum(ts)            # rounding is symmetric: float(-s) = -float(s)
        if not (x == 0 and sum_is_zero(ts)):
            rows.append(i)
            cols.append(j)
            vals.append(x)
    n = m.triangulation.n_vertices
    return sp.csr_matrix((vals, (rows, cols)), shape=(n, n), dtype=float)
