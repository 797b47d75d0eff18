"""Derived bounds: how far a correct float64 (or float32) implementation may be from the
exact value, per element, from machine epsilon and the example's conditioning.

Every tolerance of a property comes from here; none is a bare constant.  ``eps`` is the
checked implementation's declared machine epsilon (:func:`~.protocol.eps`: 2**-52 for
float64 unless it declares float32, 2**-23); ``gamma_k = k eps / (1 - k eps)`` bounds the
relative error of k roundings (Higham: recursive summation of k terms adds at most
``gamma_k`` times the sum of their magnitudes).

Angles (chapter 2).  Counted in units of u = eps / 2 (one rounding), an angle alpha
between the edge vectors a, b of a corner (opposite side a', sides b, c adjacent) is
computed from float points by one of three routes, each within its own conditioning:

- atan2(|a x b|, a . b): the edge vectors' subtractions turn each by <= u (2u), the cross
  product and the dot product are off by <= 4u |a||b| and 3u |a||b|, |a x b|'s norm 3u
  more, and atan2(y, x) moves by at most |(dx, dy)| / |(x, y)| = that over |a||b|, plus
  its own rounding pi u: about 16u = 8 eps, whatever the shape;
- acos of a normalised dot product: the cosine is off by delta <= 11u, and acos turns a
  cosine error delta into at most 3.63 delta / sin(alpha) (for delta <= 3/8 sin^2 alpha
  the slope of acos stays below 3.02 / sin alpha; beyond, |acos x - acos y| <=
  acos(1 - |x - y|) <= 2.22 sqrt(delta) < 3.63 delta / sin alpha); clamping to [-1, 1]
  only moves towards the true cosine: <= 10 eps / sin(alpha) + 3 eps;
- through the side lengths (the law of cosines; Kahan's half-angle formula; any formula in
  l = |side|^2): squared lengths from coordinates carry relative errors theta <= gamma_5
  = 5u, 7u once a square root is squared again, and relative errors theta of the squared
  sides move the angle by d alpha <= theta (S_f + |cot alpha|) to first order, S_f =
  (a'^2 + b^2 + c^2) / (4 A) the sum of the face's cotangents (d cos = (theta_b l_b +
  theta_c l_c - theta_a l_a) / (2 b c) - cos (theta_b + theta_c) / 2, and 2 b c sin =
  4 A).  S_f >= 1 / sin of every corner of the face (b^2 + c^2 >= 2 b c) and S_f <=
  3 kappa_f: on a needle every corner, the wide ones too, is conditioned like the face's
  sharpest one.  The law of cosines (b^2 + c^2 - a'^2) / (2 b c) is off by <= 7u sum l /
  (2 b c) + 9u |cos|, hence after acos (factor 3.63, as above, and pi u) by <= 12.7 eps
  S_f + 16.3 eps / sin(alpha) + 1.6 eps; Kahan's formula adds <= 7u alpha to the lengths'
  theta (S_f + |cot|): <= 3.5 eps (S_f + 1/sin(alpha)) + 11 eps.

So the corner bound is ``C_ANGLE eps (1 + 1/sin(alpha)) + C_LENGTHS eps S_f`` with
``C_ANGLE = 16``, ``C_LENGTHS = 20`` (the law of cosines' count: 12.7 S_f + 16.3 /
sin(alpha) + 1.6 <= 16 (1 + 1/sin) + 20 S_f since 1/sin <= S_f) (:func:`corner_tolerances`;
before issue 40 the bound had no S_f term, and a real library's law of cosines came to 2.07
times it on a needle's wide corner).  An angle defect adds the rounding of 2 pi minus the
sum of k angles (:func:`vertex_tolerances`).  When points were rounded to floats after an
exact motion each edge vector carries a further relative error of up to 2 sqrt(3) eps
|x| / |edge| ("input rounding").  A face normal from float points has direction error at
most ``C_ANGLE eps kappa_f`` (kappa_f = max 1/sin of the face's angles; the cross product
is off by <= 6u |a||b| = 3 eps A kappa_f relative to 2 A); a dihedral angle recovered
from the cosine and sine of two normals (atan2, acos, or Kahan's 2 atan2(|n1 - n2|, |n1 +
n2|)) is off by ``2 delta / max(|sin theta|, sqrt(delta))``, ``delta = C_ANGLE eps (1 +
kappa_f + kappa_g)`` (:func:`edge_mean_curvature_tolerances`).

Areas.  A face area from float points (:func:`face_area_tolerances`; :func:`area_tolerance`
sums them and the rounding of the sum) by |a x b| / 2 is off by <= 3u |a||b| + 3u A <=
``C_ANGLE eps (A_f + A_f kappa_f)``; by Heron on the side lengths (Kahan's sorted formula:
a few ulps for the lengths given) the lengths' errors theta move 16 A^2 by <= 32 theta
P_f (:func:`heron_product`: P_f ~ sum_c l_c |n_c| / 16, n_c = 4 A cot_c) and so A by <=
min(2 theta P_f / A, sqrt(2 theta P_f)): ``C_HERON eps min(P_f / A, ...)`` with ``C_HERON
= 12``.  P_f / A_f ~ W_f = sum_c l_c |cot_c| / 4 equals A_f on a face without an obtuse
angle; with an obtuse angle beta, W_f = A_f (1 + |cos beta| / (sin alpha sin gamma)):
about A / (alpha gamma) on a cap of small angles alpha, gamma (A rho^2 / 4 when alpha =
gamma).  Heron's route loses there what the cross product keeps (before issue 40 the bound
was C_ANGLE eps A_f (1 + kappa_f) only, which Kahan's Heron exceeded on caps).

Cotangents (chapters 3, 4).  A stable float cotangent of a corner is the exact cotangent
of a triangle whose side lengths (or coordinates) are perturbed relatively by a few units
of eps.  A relative change delta of one side a moves an angle by at most ``delta a^2 /
(2 A) <= delta rho_T`` with ``rho_T = l_max^2 / (2 A_T)`` (the aspect ratio: large for
needles), and ``d cot / d alpha = -(1 + cot^2)`` (large near a zero or straight angle), so
the corner bound is

    beta_c = K_COT eps (1 + cot_c^2) rho_T,     K_COT = 32

(3 sides x at most 8 rounded operations each, plus the quotient, rounded up).  An entry of
L sums k halves of cotangents: its bound ``B_ij`` is the sum of the ``beta_c / 2`` plus
``k eps sum |cot_c| / 2`` for the summation (:func:`entry_bounds`).  Every derived quantity
(``f^T L f``, ``L x``, eigenvalues, solves) propagates ``B`` and its own rounding
(``gamma_k`` times the sum of the magnitudes of the summed terms).  The routes of the
angles above all fit this model: a cotangent a . b / |a x b| is off by a few u (1 +
|cot|) / sin = a few eps (1 + cot^2) at most kappa_f <= rho_T; one from the side lengths,
(b^2 + c^2 - a'^2) / (4 A) with Kahan's Heron or (1/t - t) / 2 from Kahan's t =
tan(alpha / 2), by (1 + cot^2) theta (S_f + |cot|) <= 2.5 theta (1 + cot^2) rho_T plus its
roundings (S_f <= 1.5 rho_T, |cot| <= 1/sin <= rho_T).  The textbook Heron sqrt(s (s - a)
(s - b) (s - c)) stays within the area bound as well: its cancellation s - a on a needle
costs about u rho A, within the cross product's own C_ANGLE eps A kappa_f, and on a cap
what the lengths' errors cost.  tests/test_bounds_vs_honest.py pits every bound here
against these routes on needles, caps, offsets and scales.  The conditioning factors
themselves are upper bounds of the exact values within a relative 2^-29
(:func:`face_conditioning`: float64 with a derived error bound, exact where that bound is
not small): a bound's constants dwarf the difference; where a face's float area is 0
(beyond float resolution) its conditioning is infinite and its bounds accept anything.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from ..reference.combinatorics import next_corner, prev_corner
from ..reference.exact import Quotient, rounded_sum
from ..reference.exact.rationals import on_common_denominator
from ..reference.metric import heron16

from . import memo
from .example import Example
from ..protocol.methods import eps

__all__ = ["gamma", "C_ANGLE", "C_LENGTHS", "C_HERON", "K_COT", "corner_tolerances",
           "vertex_tolerances", "face_condition", "edge_mean_curvature_tolerances",
           "edge_geometry", "area_tolerance", "face_area_tolerances", "heron_product",
           "heron_condition", "float_geometry", "EntryBounds", "entry_bounds", "face_conditioning",
           "total_area_view", "area_view", "surface_conditioning", "surface_squared_floats"]


def gamma(k: int, epsilon: float | None = None) -> float:
    """Higham's gamma_k = k EPS / (1 - k EPS): bound on the relative error of k roundings,
    EPS = ``epsilon``, by default eps() (the checked implementation's; ddg-oracle's own
    float64 computations pass FLOAT64_EPSILON).  Where k EPS >= 1 (a float16 sum of 1024
    terms) there is no bound: the largest float, never a negative one (nor inf, whose
    product with a zero term would be NaN and fail every comparison).

    >>> gamma(2, 2.0 ** -10) == 2 / 1022, gamma(1024, 2.0 ** -10) == sys.float_info.max
    (True, True)
    """
    e = eps() if epsilon is None else epsilon
    return k * e / (1 - k * e) if k * e < 1 else sys.float_info.max


# --- angles, curvature and areas from float points (chapter 2) -------------------------------


C_ANGLE = 16.0                               # see the module docstring
C_LENGTHS = 20.0                             # angles through the side lengths (docstring)
C_HERON = 12.0                               # areas through the side lengths (docstring)


def float_geometry(case: Example):
    """Float geometry for the *tolerances* only (conditioning need not be exact): per corner
    the angle and 1/sin of it, per face the area, and ``edges``: arrays (I, J, length,
    theta, f, g) over the interior edges glued preserving orientation, i < j, f the face
    that runs i -> j, theta the dihedral angle.  Expected values never come from here."""
    return case.derived("geometry", _float_geometry)


def _float_geometry(case: Example) -> dict:
    V, F = case.surface_arrays()
    X = V[F]
    cross = np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0])
    twice_area = np.linalg.norm(cross, axis=1)
    angles = np.empty(F.shape)
    inv_sin = np.empty(F.shape)
    sides = np.empty(F.shape)                         # column k: the sides' product at corner k
    squared = np.empty(F.shape)                       # column k: the side opposite corner k
    for k in range(3):
        a, b = X[:, next_corner(k)] - X[:, k], X[:, prev_corner(k)] - X[:, k]
        la, lb = np.linalg.norm(a, axis=1), np.linalg.norm(b, axis=1)
        angles[:, k] = np.arctan2(twice_area, (a * b).sum(axis=1))
        sides[:, k] = la * lb
        squared[:, k] = ((b - a) ** 2).sum(axis=1)
    # a face whose float cross product is 0 (beyond float resolution): 1/sin infinite
    with np.errstate(divide="ignore", invalid="ignore"):
        inv_sin[:] = sides / twice_area[:, None]
        normal = cross / twice_area[:, None]
    # the interior edges glued preserving orientation, (i, j) with i < j, f the face that
    # runs i -> j and g the one that runs j -> i, ordered by f's halfedge
    from .views import halfedge_table
    table = halfedge_table(case.surface)
    h, h2 = table[table[:, 1] >= 0].T
    I, J = F[h // 3, h % 3], F[h // 3, (h + 1) % 3]
    kept = (F[h2 // 3, h2 % 3] == J) & (F[h2 // 3, (h2 + 1) % 3] == I)
    h, h2, I, J = h[kept], h2[kept], I[kept], J[kept]
    first, second = np.where(I < J, h, h2), np.where(I < J, h2, h)
    order = np.argsort(first, kind="stable")
    first, second = first[order], second[order]
    I, J = np.minimum(I, J)[order], np.maximum(I, J)[order]
    Fi, Gi = first // 3, second // 3
    # all interior edges at once (one np.cross per edge cost 3 s on a 52k-face mesh)
    e = V[J] - V[I]
    length = np.linalg.norm(e, axis=1)
    nf, ng = normal[Fi], normal[Gi]
    with np.errstate(divide="ignore", invalid="ignore"):
        theta = np.arctan2((np.cross(nf, ng) * e).sum(axis=1) / length, (nf * ng).sum(axis=1))
        cot_sum = squared.sum(axis=1) / (2 * twice_area)
    return dict(angles=angles, inv_sin=inv_sin, area=twice_area / 2,
                edges=(I, J, length, theta, Fi, Gi),
                cot_sum=cot_sum, sides=sides.max(axis=1) / 2, squared=squared)


def edge_geometry(case: Example, key) -> tuple[float, float]:
    """D2.3: (length, theta) of interior edge ``key`` = (i, j), i < j, as :func:`float_geometry`
    has them (for a failure's message)."""
    I, J, length, theta, _, _ = float_geometry(case)["edges"]
    k = int(np.flatnonzero((I == key[0]) & (J == key[1]))[0])
    return float(length[k]), float(theta[k])


def _input_scale(case: Example) -> np.ndarray:
    """Per corner: max |x| over the face's vertices / the shorter adjacent edge (input rounding)."""
    V, F = case.surface_arrays()
    X = V[F]                                               # (m, 3, 3)
    size = np.abs(X).max(axis=(1, 2))
    out = np.empty(F.shape, dtype=np.float64)
    for c in range(3):
        a = np.linalg.norm(X[:, next_corner(c)] - X[:, c], axis=1)
        b = np.linalg.norm(X[:, prev_corner(c)] - X[:, c], axis=1)
        out[:, c] = size / np.minimum(a, b)
    return out


def corner_tolerances(case: Example, input_rounding: bool = False) -> np.ndarray:
    """(m, 3) bounds on |computed angle - exact angle| (see the module docstring).

    C_ANGLE eps (1 + 1/sin alpha) + C_LENGTHS eps S_f (S_f = (a^2 + b^2 + c^2) / (4 A),
    the face's cotangent sum: the route through the side lengths); with
    ``input_rounding`` also 4 sqrt(3) eps (|x| / |edge|) (1 + 1/sin alpha + S_f) for
    points rounded to floats.
    """
    g = float_geometry(case)
    cond = 1 + g["inv_sin"] + g["cot_sum"][:, None] * (C_LENGTHS / C_ANGLE)
    tol = C_ANGLE * eps() * cond
    if input_rounding:
        tol = tol + 4 * math.sqrt(3) * eps() * _input_scale(case) * cond
    return tol


def vertex_tolerances(case: Example, corner_tol: np.ndarray) -> np.ndarray:
    """(n,) bounds on |computed K(v) - exact K(v)|: the corner bounds at v plus the rounding
    of 2 pi - (sum of k angles), gamma_(k+1) (2 pi + sum of the angles)."""
    t = case.triangulation
    angles = float_geometry(case)["angles"]
    n = t.n_vertices
    tol = np.zeros(n)
    mass = np.full(n, 2 * math.pi)
    count = np.ones(n, dtype=np.int64)
    for f, face in enumerate(t.faces):
        for c, v in enumerate(face):
            tol[v] += corner_tol[f, c]
            mass[v] += angles[f, c]
            count[v] += 1
    return tol + np.array([gamma(int(k)) for k in count]) * mass


def face_condition(case: Example) -> np.ndarray:
    """(m,) max over the corners of 1/sin(alpha): the conditioning of a face normal."""
    return float_geometry(case)["inv_sin"].max(axis=1)


def edge_mean_curvature_tolerances(case: Example) -> dict:
    """{(i, j): bound on |computed H(e) - exact H(e)|}.

    A face normal from float points has direction error <= C_ANGLE eps kappa_f
    (kappa_f = max 1/sin of the face's angles), so the cosine and the sine of
    theta are off by delta = C_ANGLE eps (1 + kappa_f + kappa_g); theta recovered
    from them (atan2, or acos near 0 and pi) is off by at most
    2 delta / max(|sin theta|, sqrt(delta)).  Then H = theta l / 2 adds the
    length's and the product's rounding: (tol_theta l + |theta| 2 eps l) / 2 + eps |H|.
    """
    kappa = face_condition(case)
    I, J, length, theta, f, g = float_geometry(case)["edges"]
    e = eps()
    with np.errstate(invalid="ignore", over="ignore"):
        delta = C_ANGLE * e * (1 + kappa[f] + kappa[g])
        # math.sin per edge: numpy's may differ from it in the last bit
        sin = np.abs(np.fromiter(map(math.sin, theta.tolist()), np.float64, len(theta)))
        tol_theta = 2 * delta / np.maximum(sin, np.sqrt(delta))
        H = theta * length / 2
        tol = (tol_theta * length + np.abs(theta) * 2 * e * length) / 2 + e * np.abs(H)
    # a face whose float normal is 0: beyond resolution
    tol[~(np.isfinite(delta) & np.isfinite(theta))] = math.inf
    return dict(zip(zip(I.tolist(), J.tolist()), tol.tolist()))


def heron_product(squared) -> np.ndarray:
    """(m,) P_f >= sum_c l_c |n_c| / 16, n_c = l_a + l_b - l_c (= 4 A cot_c), from the
    squared sides l_c opposite corner c ((m, 3)): Heron's 16 A^2 = P(l) has dP/dl_c = 2 n_c
    and P is quadratic (Hessian entries +-2), so squared lengths with relative errors up to
    theta move 16 A^2 by at most 32 theta sum l_c |n_c| / 16 + theta^2 (sum l)^2.  P_f is
    that sum as floats plus eps (sum l)^2 / 2, which covers both the second-order term
    (theta <= 3.5 eps: theta (sum l)^2 / 32 <= 0.11 eps (sum l)^2) and the cancellation in
    n_c (a right angle: n_c = 0 while its float, from squared lengths within 8 u relative,
    may be off by 8 u sum l; 8 u (sum l)^2 / 16 = 0.25 eps (sum l)^2).  P_f / A_f ~ W_f =
    sum_c l_c |cot_c| / 4 (:func:`heron_condition`), the absolute conditioning of a face
    area from its side lengths."""
    l = np.asarray(squared, dtype=np.float64).reshape(-1, 3)
    n = np.stack([l[:, next_corner(c)] + l[:, prev_corner(c)] - l[:, c] for c in range(3)], axis=1)
    total = l.sum(axis=1)
    return (l * np.abs(n)).sum(axis=1) / 16 + eps() * total * total / 2


def heron_condition(squared, cot=None) -> np.ndarray:
    """(m,) W_f = sum_c l_c |cot_c| / 4 from the squared sides and the cotangents (without
    them, :func:`heron_product` over the area: an upper bound)."""
    if cot is not None:
        return (np.asarray(squared, dtype=np.float64)
                * np.abs(np.asarray(cot, dtype=np.float64))).sum(axis=1) / 4
    l = np.asarray(squared, dtype=np.float64).reshape(-1, 3)
    H = 2 * (l[:, 0] * l[:, 1] + l[:, 1] * l[:, 2] + l[:, 2] * l[:, 0]) - (l * l).sum(axis=1)
    return heron_product(l) / (np.sqrt(np.maximum(H, 0)) / 4)


def face_area_tolerances(area, sides, heron) -> np.ndarray:
    """(m,) bounds on |computed face area - exact area| from float points, by either route
    (module docstring): ``area`` the faces' areas, ``sides`` A_f kappa_f = the largest
    product of two sides / 2, ``heron`` P_f (:func:`heron_product`).

    - the cross product |a x b| / 2: C_ANGLE eps (A_f + A_f kappa_f);
    - Heron on the side lengths (Kahan's sorted formula): the lengths carry relative errors
      theta <= 3.5 eps (squared: 2.5 eps; 3.5 eps when a square root is squared again),
      which move 16 A^2 by at most D = 32 theta P_f (second order: theta^2 (sum l)^2, below
      one rounding of D); then |A~ - A| = |A~^2 - A^2| / (A~ + A) <= min(D / (16 A),
      sqrt(D / 16)); Kahan's formula adds 3.5 eps A~ (about 7 roundings) <= 3.5 eps W_f.
      With D / 16 = 7 eps P_f: C_HERON eps min(P_f / A_low, sqrt(P_f / (C_HERON eps)))
      with C_HERON = 12 >= 7 + 3.5 (A_low: the area minus the cross route's bound, a lower
      bound on the exact area where the areas given are float views).  The square root
      branch holds where the area is below its own resolution (a cap flatter than
      sqrt(eps)): there a float Heron area may be 0."""
    area, sides, heron = (np.asarray(x, dtype=np.float64) for x in (area, sides, heron))
    cross = C_ANGLE * eps() * (area + sides)
    low = np.maximum(area - cross, 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        first = np.where(low > 0, C_HERON * eps() * heron / np.where(low > 0, low, 1), np.inf)
    return cross + np.minimum(first, np.sqrt(C_HERON * eps() * heron))


def area_tolerance(case: Example) -> float:
    """Bound on |computed total area - exact area|: each face area from float points is off by
    at most :func:`face_area_tolerances`, the sum adds gamma_m sum A_f."""
    g = float_geometry(case)
    areas = np.asarray(g["area"], dtype=np.float64)
    per_face = face_area_tolerances(areas, g["sides"], heron_product(g["squared"]))
    return float(per_face.sum()) + gamma(len(areas)) * float(areas.sum())


# --- cotangents and the entries of L (chapters 3 and 4) --------------------------------------------


K_COT = 32


@dataclass
class EntryBounds:
    """Float views of the exact cotan corners of a metric and the entry bounds ``B`` of its
    Laplacian (module docstring); ``amplification[f]`` scales the length perturbation
    of face f (1 for lengths computed from coordinates; more after float flips, see
    :mod:`ddg_oracle.properties.delaunay_exact`).  ``B`` and ``adjacent`` (the pairs of vertices
    joined by an edge, and each such vertex with itself) are sparse (scipy CSR): a real
    mesh's n x n arrays would not fit; ``.toarray()`` for a small case."""

    cot: np.ndarray
    rho: np.ndarray
    beta: np.ndarray
    B: object
    adjacent: object


def entry_bounds(metric, n: int, amplification=None) -> EntryBounds:
    """``metric``: a metric, or a surface (its metric's bounds, the metric built only where
    :func:`surface_conditioning` needs it)."""
    from .views import halfedge_table
    t = metric.triangulation
    rho, cot = (face_conditioning(metric) if hasattr(metric, "face_squared_lengths")
                else surface_conditioning(metric))
    return bounds_of(np.asarray(t.faces, dtype=np.int64).reshape(-1, 3), halfedge_table(metric),
                     rho, cot, n, amplification)


def bounds_of(F, table, rho, cot, n: int, amplification=None) -> EntryBounds:
    """:func:`entry_bounds` of the triangulation with faces ``F`` (m, 3) and halfedge table
    ``table`` (:func:`~.views.halfedge_table`'s) whose faces have the conditioning factors
    ``rho``, ``cot`` (:func:`face_conditioning`'s)."""
    import scipy.sparse as sp
    amp = np.ones(len(F)) if amplification is None else np.asarray(amplification, float)
    beta = K_COT * eps() * (1 + cot ** 2) * (rho * amp)[:, None]
    # per edge (i, j), i != j, and each of its halfedges h in order: the entries (i, j),
    # (j, i), (i, i), (j, j) of h's face and opposite corner, in that order (the order
    # fixes the float sums below)
    h0 = table[:, 0]
    i, j = F[h0 // 3, h0 % 3], F[h0 // 3, (h0 % 3 + 1) % 3]
    keep = (i != j)[:, None] & (table >= 0)                       # (edges, 2)
    h = np.where(table >= 0, table, 0)
    x = np.stack([i, j, i, j], axis=1)[:, None, :].repeat(2, axis=1)[keep]
    y = np.stack([j, i, i, j], axis=1)[:, None, :].repeat(2, axis=1)[keep]
    rows, cols = x.ravel(), y.ravel()
    faces = (h // 3)[:, :, None].repeat(4, axis=2)[keep].ravel()
    corners = ((h % 3 + 2) % 3)[:, :, None].repeat(4, axis=2)[keep].ravel()

    def summed(data):
        # one coordinate list for all three: after summing duplicates the same structure
        M = sp.csr_matrix((data, (rows, cols)), shape=(n, n))
        M.sum_duplicates()
        return M
    if len(rows):
        b = summed(beta[faces, corners] / 2)
        m = summed(np.abs(cot[faces, corners]) / 2)
        cnt = summed(np.ones(len(rows)))
        B = b.copy()
        B.data = b.data + cnt.data * eps() * m.data
    else:
        B = sp.csr_matrix((n, n))
        cnt = B
    adjacent = cnt.copy()
    adjacent.data = adjacent.data > 0
    return EntryBounds(cot, rho, beta, B, adjacent.astype(bool))


def face_conditioning(metric) -> tuple[np.ndarray, np.ndarray]:
    """(rho, cot): every face's aspect ratio rho = max l / (2 A) and its corners'
    cotangents (F x 3), as conditioning factors of bounds, once per metric object (read
    only).  Upper bounds: rho and |cot| are at least the exact values and exceed them by at
    most a relative 2^-29, except a |cot| below 2^-499, given as 2^-499; the signs are the
    exact ones (a bound's constants dwarf the difference, and a larger factor only widens a
    bound).  A rho beyond the float range raises OverflowError (as the exact route always
    did: callers report an exact value beyond the float range).

    Vectorised (float64, numpy) from the correctly rounded squared lengths, with an error
    bound derived below for each face; a face whose bound is not that small (a needle, a
    cap, a corner within rounding of a right angle, lengths far out of the float range) is
    computed exactly (:func:`_conditioning`).  On CGAL's bull after its 2,481 intrinsic
    Delaunay flips the exact route takes 0.7-1.3 s (its 3,736 faces with irrational
    lengths), this 0.03 s."""
    return memo.of(_face_conditioning, metric)


#: a face's factors from floats where their relative error bound is at most this
_FILTER = 2.0 ** -31


def surface_conditioning(surface) -> tuple[np.ndarray, np.ndarray]:
    """:func:`face_conditioning` of ``surface.metric()``, the same arrays, without building
    the metric unless some face needs the exact route: the correctly rounded squared
    lengths come from the positions (``reference.metric.squared_length_floats``: one
    integer division per edge, no Fraction).  Once per surface object."""
    return memo.of(_surface_conditioning, surface)


def _surface_conditioning(surface):
    try:
        L = surface_squared_floats(surface)
    except OverflowError:                           # a length beyond the float range
        return face_conditioning(surface.metric())
    return _conditioning_of(L, [], surface.metric)


def surface_squared_floats(surface) -> np.ndarray:
    """(F, 3): each face's squared side lengths as ``metric.face_squared_lengths`` orders
    them (opposite corners 2, 0, 1), correctly rounded, from the positions
    (``reference.metric.squared_length_floats``: no metric); OverflowError for a length
    beyond the float range.  Once per surface object; read-only."""
    return memo.of(_surface_squared_floats, surface)


def _surface_squared_floats(surface):
    from ..reference.metric import squared_length_floats
    from .views import halfedge_table
    t = surface.triangulation
    sq = np.array(squared_length_floats(surface.positions, t), dtype=np.float64)
    table = halfedge_table(surface)
    edge_of = np.empty(3 * t.n_faces, dtype=np.int64)
    edge_of[table[:, 0]] = np.arange(len(table))
    inner = table[:, 1] >= 0
    edge_of[table[inner, 1]] = np.flatnonzero(inner)
    # face_squared_lengths(f): the edges of halfedges 3f, 3f + 1, 3f + 2
    L = sq[edge_of].reshape(-1, 3)
    L.flags.writeable = False
    return L


def _face_conditioning(metric):
    n_faces = metric.triangulation.n_faces
    L = np.zeros((n_faces, 3))
    exact = []                          # faces left to the exact route
    for f in range(n_faces):
        try:                            # correctly rounded (Fractions, Surds, lazy numbers)
            L[f] = [float(x) for x in metric.face_squared_lengths(f)]
        except OverflowError:
            exact.append(f)
    return _conditioning_of(L, exact, lambda: metric)


def _conditioning_of(L, exact, metric_of):
    """(rho, cot) from the correctly rounded squared lengths L (F x 3, opposite corners 2,
    0, 1), the faces in ``exact`` and those the filter leaves to the exact route computed
    from ``metric_of()`` (called only if there are any)."""
    n_faces = len(L)
    rho, cot = np.zeros(n_faces), np.zeros((n_faces, 3))
    u = 2.0 ** -53
    l0, l1, l2 = L[:, 0], L[:, 1], L[:, 2]               # opposite corners 2, 0, 1
    with np.errstate(all="ignore"):
        # each L = l (1 + d), |d| <= u.  n = a + b - o (two roundings): |n~ - n| <= e_n
        n = np.stack([l0 + l2 - l1, l0 + l1 - l2, l1 + l2 - l0], axis=1)   # corners 0, 1, 2
        S = l0 + l1 + l2
        e_n = 4 * u * S                 # u S (inputs) + 2 u S (roundings), rounded up
        # H = 16 A^2 = n0 n1 + n1 n2 + n2 n0 (the cotangents' identity cot cot + ... = 1):
        # each product off by e_n (|n~i| + |n~j|) + e_n^2 before rounding, then gamma_3 of
        # the sum of the products' magnitudes
        a = np.abs(n)
        P = a[:, 0] * a[:, 1] + a[:, 1] * a[:, 2] + a[:, 2] * a[:, 0]
        H = n[:, 0] * n[:, 1] + n[:, 1] * n[:, 2] + n[:, 2] * n[:, 0]
        e_H = (2 * e_n * a.sum(axis=1) + 3 * e_n * e_n + 4 * u * P) * (1 + 2.0 ** -40)
        rel_H = e_H / H
        # |cot| <= (|n~| + e_n) / sqrt(H (1 - rel_H)), sqrt(1 / (1 - r)) <= 1 + r for r <= 1/2;
        # 2^-45 covers the roundings of these few operations and of the inputs (~ 8 u)
        grow = 1 + rel_H + 2.0 ** -45
        root = np.sqrt(H)
        rho_f = 2 * L.max(axis=1) / root * grow
        cot_f = np.copysign((a + e_n[:, None]) / root[:, None] * grow[:, None], n)
        ok = ((L.min(axis=1) >= 2.0 ** -400) & (L.max(axis=1) <= 2.0 ** 400)
              & (H > 0) & (rel_H <= _FILTER) & np.all(a > e_n[:, None] / _FILTER, axis=1))
    ok[exact] = False
    rho[ok], cot[ok] = rho_f[ok], cot_f[ok]
    slow = np.flatnonzero(~ok)
    metric = metric_of() if len(slow) else None
    for f in slow:
        rho[f], cot[f] = _conditioning(metric, int(f))
        # below 2^-499 the exact route's float may have underflowed (to 0: a sign lost, or
        # to a subnormal: its relative error unbounded), off by at most 2^-537 absolutely:
        # 2^-499 with the exact sign bounds it (a bound's terms 1 + cot^2 and eps |cot|
        # cannot tell the difference)
        for c, n in enumerate(metric.face_cot_numerators(int(f))):
            if abs(cot[f, c]) < _TINY:
                cot[f, c] = 0.0 if n == 0 else _TINY if n > 0 else -_TINY
    # the exact route is within 2 ulps either way: 4 ulps away from 0 make it an upper bound
    r, c = rho[slow], cot[slow]
    for _ in range(4):
        r = np.nextafter(r, np.inf)
        c = np.where(c == 0, 0.0, np.nextafter(c, np.copysign(np.inf, c)))
    rho[slow], cot[slow] = r, c
    rho.flags.writeable = cot.flags.writeable = False       # shared by every caller (memo.of)
    return rho, cot


#: the smallest |cot| face_conditioning gives a corner that is not right (see there)
_TINY = 2.0 ** -499


def _conditioning(metric, f: int) -> tuple[float, list[float]]:
    """(rho, the three corner cotangents) of face f as floats, within 2 ulps of the exact
    values: conditioning factors of a bound (its constants dwarf a few ulps).  From exact
    scale-free ratios, so tiny and huge meshes neither underflow nor overflow: with the
    squared lengths l on one common denominator (integers L) and H = 16 A^2 (Heron) in the
    same units, rho = max l / (2 A) = sqrt(4 max L^2 / H) and cot = n / (4 A) = sign(n)
    sqrt(n^2 / H), n = a + b - o: integer quotients (correctly rounded), one float square
    root.  Irrational lengths (after intrinsic flips): the same ratios as exact quotients,
    correctly rounded without dividing (an area with hundreds of square roots has a costly
    exact inverse)."""
    sq = metric.face_squared_lengths(f)                   # opposite corners 2, 0, 1
    if all(type(x) is Fraction for x in sq):
        L, _ = on_common_denominator(sq)                 # the scale cancels in each ratio
        l0, l1, l2 = L
        H = heron16(l0, l1, l2)
        n = (l0 + l2 - l1, l0 + l1 - l2, l1 + l2 - l0)     # corners 0, 1, 2
        try:
            return (math.sqrt(4 * max(L) ** 2 / H),
                    [math.copysign(math.sqrt(x * x / H), x) for x in n])
        except OverflowError:
            pass                            # beyond the float range: as the exact route says
    A = metric.area(f)
    # the largest by float: equal floats are within an ulp of either (no exact comparison
    # of equal lazy lengths, which would compute their exact forms)
    return (float(Quotient(max(sq, key=float), 2 * A)),
            [float(Quotient(n, 4 * A)) for n in metric.face_cot_numerators(f)])


def total_area_view(metric) -> tuple[float, float]:
    """(A, err): the exact total area (T3.9, L3.7, R2.5's A; the face areas of D2.6, Heron
    on exact squared lengths) correctly rounded to float64, and err = u A (u = 2**-53)
    bounding |A - exact total area|.  For a mesh of any size: the exact sum of a float mesh
    has one square root per face, so it is rounded from integer enclosures of the face
    areas (:func:`~ddg_oracle.reference.exact.rounded_sum`; 0.1 s at 56,172 faces).
    Once per metric object."""
    total = memo.of(_rounded_total_area, metric)
    return total, 2.0 ** -53 * abs(total)


def _rounded_total_area(metric) -> float:
    return rounded_sum(metric.areas)


def area_view(surface) -> tuple[float, float]:
    """(A, err) with |A - the exact total area| <= err (D2.6's face areas summed): for
    positions in R^3 that are floats, an fsum of the faces' area enclosures
    (:func:`.enclosures.total_area_enclosure`, err about 3 u A, no exact metric); else the
    exact total correctly rounded (:func:`total_area_view`, err u A).  Raises
    DegenerateFace as the metric would."""
    from .enclosures import total_area_enclosure
    from .views import float_positions, position_enclosure, validate
    validate(surface)
    if float_positions(surface):
        value, err = total_area_enclosure(position_enclosure(surface), surface.triangulation.faces)
        if np.isfinite(err):
            return value, err
    return total_area_view(surface.metric())
