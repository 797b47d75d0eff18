"""Derived bounds: how far a correct float64 (or float32) implementation may be from the
exact value, per element, from machine epsilon and the example's conditioning.

Every tolerance of a property comes from here; none is a bare constant.  ``eps`` is the
checked implementation's declared machine epsilon (:func:`~.protocol.eps`: 2**-52 for
float64 unless it declares float32, 2**-23); ``gamma_k = k eps / (1 - k eps)`` bounds the
relative error of k roundings (Higham: recursive summation of k terms adds at most
``gamma_k`` times the sum of their magnitudes).

Angles (chapter 2).  An angle alpha computed from float points -- by atan2(|a x b|, a . b),
by acos of a normalised dot product, or by the law of cosines -- comes from a cosine or a
ratio with relative error at most about 7 eps, plus at most 2 sqrt(3) eps from the
edge-vector subtractions; since d alpha = d cos(alpha) / sin(alpha) the error is at most
``C_ANGLE eps (1 + 1/sin(alpha))`` with ``C_ANGLE = 16`` (a margin of about 2 over these
counts) (:func:`corner_tolerances`).  An angle defect adds the rounding of 2 pi minus the
sum of k angles (:func:`vertex_tolerances`).  When points were rounded to floats after an
exact motion each edge vector carries a further relative error of up to 2 sqrt(3) eps
|x| / |edge| ("input rounding").  A face normal from float points has direction error at
most ``C_ANGLE eps kappa_f`` (kappa_f = max 1/sin of the face's angles); a dihedral angle
recovered from the cosine and sine of two normals is off by ``2 delta / max(|sin theta|,
sqrt(delta))``, ``delta = C_ANGLE eps (1 + kappa_f + kappa_g)``
(:func:`edge_mean_curvature_tolerances`); a total area by ``C_ANGLE eps A_f (1 + kappa_f)``
per face plus the sum (:func:`area_tolerance`).

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
(``gamma_k`` times the sum of the magnitudes of the summed terms).  A naive Heron formula
loses accuracy on needles faster than this model (``eps rho^2``) and is reported as a
failure there: that is a real loss.  The conditioning factors themselves are float views
within a few ulps of exact values (:func:`_conditioning`): a bound's constants dwarf them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from ddg_oracle.reference.combinatorics import face_of, next_corner, opposite_corner, prev_corner
from ddg_oracle.reference.exact import rounded_sum
from ddg_oracle.reference.exact.rationals import on_common_denominator
from ddg_oracle.reference.metric import heron16

from . import memo
from .example import Example
from .protocol import eps

__all__ = ["gamma", "C_ANGLE", "K_COT", "corner_tolerances", "vertex_tolerances",
           "face_condition", "edge_mean_curvature_tolerances", "area_tolerance",
           "float_geometry", "EntryBounds", "entry_bounds", "total_area_view"]


def gamma(k: int) -> float:
    """Higham's gamma_k = k EPS / (1 - k EPS), EPS = eps(): bound on the relative error of k roundings."""
    return k * eps() / (1 - k * eps())


# --- angles, curvature and areas from float points (chapter 2) -------------------------------


C_ANGLE = 16.0                               # see the module docstring


def float_geometry(case: Example):
    """Float geometry for the *tolerances* only (conditioning need not be exact): per corner
    the angle and 1/sin of it, per face the area, per interior edge (i, j) its length, its
    dihedral angle theta and its two faces.  Expected values never come from here."""
    return case.derived("geometry", _float_geometry)


def _float_geometry(case: Example) -> dict:
    V, F = case.surface_arrays()
    X = V[F]
    cross = np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0])
    twice_area = np.linalg.norm(cross, axis=1)
    angles = np.empty(F.shape)
    inv_sin = np.empty(F.shape)
    for k in range(3):
        a, b = X[:, next_corner(k)] - X[:, k], X[:, prev_corner(k)] - X[:, k]
        la, lb = np.linalg.norm(a, axis=1), np.linalg.norm(b, axis=1)
        angles[:, k] = np.arctan2(twice_area, (a * b).sum(axis=1))
        inv_sin[:, k] = la * lb / twice_area
    normal = cross / twice_area[:, None]
    face_of = {}
    for f, face in enumerate(F.tolist()):
        for k in range(3):
            face_of[(face[k], face[next_corner(k)])] = f
    edges = {}
    for (i, j), f in face_of.items():
        g = face_of.get((j, i))
        if g is not None and i < j:
            e = V[j] - V[i]
            length = float(np.linalg.norm(e))
            theta = math.atan2(float(np.cross(normal[f], normal[g]) @ e) / length,
                               float(normal[f] @ normal[g]))
            edges[(i, j)] = (length, theta, f, g)
    return dict(angles=angles, inv_sin=inv_sin, area=twice_area / 2, edges=edges)


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

    C_ANGLE eps (1 + 1/sin alpha); with ``input_rounding`` also
    4 sqrt(3) eps (|x| / |edge|) (1 + 1/sin alpha) for points rounded to floats.
    """
    cond = 1 + float_geometry(case)["inv_sin"]                  # 1 + 1/sin(alpha)
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
    out = {}
    for key, (length, theta, f, g) in float_geometry(case)["edges"].items():
        delta = C_ANGLE * eps() * (1 + kappa[f] + kappa[g])
        tol_theta = 2 * delta / max(abs(math.sin(theta)), math.sqrt(delta))
        H = theta * length / 2
        out[key] = (tol_theta * length + abs(theta) * 2 * eps() * length) / 2 + eps() * abs(H)
    return out


def area_tolerance(case: Example) -> float:
    """Bound on |computed total area - exact area|: each face area from float points is off by
    at most C_ANGLE eps A_f (1 + kappa_f), the sum adds gamma_m sum A_f."""
    cond = 1 + face_condition(case)
    areas = [float(a) for a in float_geometry(case)["area"]]
    return sum(C_ANGLE * eps() * a * k for a, k in zip(areas, cond)) + gamma(len(areas)) * sum(areas)


# --- cotangents and the entries of L (chapters 3 and 4) --------------------------------------------


K_COT = 32


@dataclass
class EntryBounds:
    """Float views of the exact cotan corners of a metric and the entry bounds ``B`` of its
    Laplacian (module docstring); ``amplification[f]`` scales the length perturbation
    of face f (1 for lengths computed from coordinates; more after float flips, see
    :mod:`ddg_oracle.properties.delaunay`).  ``B`` and ``adjacent`` (the pairs of vertices
    joined by an edge, and each such vertex with itself) are sparse (scipy CSR): a real
    mesh's n x n arrays would not fit; ``.toarray()`` for a small case."""

    cot: np.ndarray
    rho: np.ndarray
    beta: np.ndarray
    B: object
    adjacent: object


def entry_bounds(metric, n: int, amplification=None) -> EntryBounds:
    import scipy.sparse as sp
    t = metric.triangulation
    cot = np.zeros((t.n_faces, 3))
    rho = np.zeros(t.n_faces)
    for f in range(t.n_faces):
        rho[f], cot[f] = _conditioning(metric, f)
    amp = np.ones(t.n_faces) if amplification is None else np.asarray(amplification, float)
    beta = K_COT * eps() * (1 + cot ** 2) * (rho * amp)[:, None]
    rows, cols, faces, corners = [], [], [], []
    for e in range(t.n_edges):
        i, j = t.edge_vertices(e)
        if i == j:
            continue
        for h in t.edge_halfedges(e):
            if h < 0:
                continue
            f, c = face_of(h), opposite_corner(h)
            for x, y in ((i, j), (j, i), (i, i), (j, j)):
                rows.append(x)
                cols.append(y)
                faces.append(f)
                corners.append(c)
    rows, cols = np.array(rows, dtype=np.int64), np.array(cols, dtype=np.int64)
    faces, corners = np.array(faces, dtype=np.int64), np.array(corners, dtype=np.int64)

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


def _conditioning(metric, f: int) -> tuple[float, list[float]]:
    """(rho, the three corner cotangents) of face f as floats, within 2 ulps of the exact
    values: conditioning factors of a bound (its constants dwarf a few ulps).  From exact
    scale-free ratios, so tiny and huge meshes neither underflow nor overflow: with the
    squared lengths l on one common denominator (integers L) and H = 16 A^2 (Heron) in the
    same units, rho = max l / (2 A) = sqrt(4 max L^2 / H) and cot = n / (4 A) = sign(n)
    sqrt(n^2 / H), n = a + b - o: integer quotients (correctly rounded), one float square
    root.  Irrational lengths (after intrinsic flips) take the exact cotangents."""
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
    return (float(max(sq) / (2 * metric.area(f))), [float(c) for c in metric.face_cots(f)])


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
