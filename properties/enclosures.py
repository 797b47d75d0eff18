"""Rigorous float enclosures of exact values, vectorised: issue 46's filtered kernels.

An :class:`Enclosure` is two float64 arrays, ``value`` and ``err``, with
``|value - exact| <= err`` entry by entry, where ``exact`` is the real number the
same formula gives on the exact inputs.  The arithmetic runs in numpy's round to
nearest; each operation adds its own rounding and propagates its operands' errors
(a running error analysis, Higham, *Accuracy and Stability of Numerical
Algorithms*, 2nd ed., sec. 3.3), and each error term, itself computed in floats,
is multiplied by ``1 + 2^-50`` (at most six roundings, each at most relative
2^-53, in its formula) and given ``2^-1060`` more (a result below the normal range
is rounded absolutely, by at most 2^-1075).  An infinite or NaN value or error
leaves the entry undecided; so does an angle whose error disc reaches the
origin (:func:`angle_from`).

What the enclosures are for: a check compares an implementation's float with the
correctly rounded float of an exact value; where the enclosure pins that float
between two floats (:func:`rounding_bounds`) and the comparison holds at both
(it is monotone on each side of the observed value), the check's verdict is the
one the exact value gives, without computing it.  The entries left undecided
are computed exactly (:func:`~ddg_oracle.properties.registry.within_enclosed`).
Floats decide nothing inside ``reference/``: this module is the checks'.

Assumed of the platform: IEEE 754 binary64 with round to nearest for numpy's
``+ - * /`` and ``sqrt`` (correctly rounded), and ``arctan2`` within 16 ulps.  glibc
does not promise correct rounding for atan2: its manual (sec. 19.7, "Known Maximum
Errors in Math Functions") states the goal "within a few ulp" and lists the errors its
tests measured, and its test suite refuses recorded errors above 9 ulps; 16 leaves a
margin at no cost (the propagated errors dominate).  tests/test_enclosures.py compares
numpy's arctan2 with mpmath on random and adversarial arguments.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["Enclosure", "rounding_bounds", "correctly_rounded", "points", "nondegenerate", "mean_curvature_enclosure",
           "corner_angle_enclosure", "corner_cot_enclosure", "area_gradient_enclosure",
           "vertex_area_enclosures",
           "summed", "angle_sum_enclosure", "total_area_enclosure"]

U = 2.0 ** -53                      # unit roundoff of binary64
_UP = 1.0 + 2.0 ** -50              # covers the rounding of an error term's own formula
_TINY = 2.0 ** -1060                # covers a result rounded below the normal range
_ATAN2_ULPS = 16.0


class Enclosure:
    """``value`` (float64 array) within ``err`` (float64 array, >= 0) of an exact value."""

    __slots__ = ("value", "err")

    def __init__(self, value, err=None):
        self.value = np.asarray(value, dtype=np.float64)
        self.err = (np.zeros_like(self.value) if err is None
                    else np.asarray(err, dtype=np.float64))

    @staticmethod
    def _rounded(value, propagated) -> "Enclosure":
        """``value`` computed in one rounding from operands within ``propagated``."""
        with np.errstate(over="ignore", invalid="ignore"):
            return Enclosure(value, (propagated + U * np.abs(value)) * _UP + _TINY)

    def __getitem__(self, index) -> "Enclosure":
        return Enclosure(self.value[index], self.err[index])

    def __add__(self, other: "Enclosure") -> "Enclosure":
        with np.errstate(over="ignore", invalid="ignore"):
            return self._rounded(self.value + other.value, self.err + other.err)

    def __sub__(self, other: "Enclosure") -> "Enclosure":
        with np.errstate(over="ignore", invalid="ignore"):
            return self._rounded(self.value - other.value, self.err + other.err)

    def __mul__(self, other: "Enclosure") -> "Enclosure":
        # x' y' - x y = x' (y' - y) + y' (x' - x) - (x' - x)(y' - y)
        a, b = self, other
        with np.errstate(over="ignore", invalid="ignore"):
            prop = (np.abs(a.value) * b.err + np.abs(b.value) * a.err + a.err * b.err) * _UP
            return self._rounded(a.value * b.value, prop)

    def __truediv__(self, other: "Enclosure") -> "Enclosure":
        # x'/y' - x/y = (x' (y - y') + y' (x' - x)) / (y y'), |y| >= |y'| - e_y > 0
        a, b = self, other
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            # a lower bound of |y| where > 0: the subtraction and product each round by at
            # most u relative (a subnormal difference: absolutely, and 0 or below decides nothing)
            below = (np.abs(b.value) - b.err) * (1 - 4 * U)
            prop = np.where(below > 0, (np.abs(a.value) * b.err + np.abs(b.value) * a.err)
                            * _UP / (np.abs(b.value) * below) * _UP, np.inf)
            return self._rounded(a.value / b.value, prop)

    def scaled(self, power_of_two: float) -> "Enclosure":
        """Times a power of two: exact unless it leaves the normal range (then undecided
        where it overflows, and ``_TINY`` covers an underflow)."""
        with np.errstate(over="ignore", invalid="ignore"):
            return Enclosure(self.value * power_of_two, self.err * power_of_two + _TINY)

    def abs(self) -> "Enclosure":
        return Enclosure(np.abs(self.value), self.err)          # | |x'| - |x| | <= |x' - x|

    def sqrt(self) -> "Enclosure":
        """The square root of an exact value known to be >= 0 (a sum of squares):
        |sqrt(x) - sqrt(y)| <= min(sqrt|x - y|, |x - y| / sqrt(max(x, y)))."""
        x = np.maximum(self.value, 0.0)          # closer to the exact value, which is >= 0
        root = np.sqrt(x)
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            prop = np.minimum(np.sqrt(self.err), np.where(root > 0, self.err / root, np.inf))
        return self._rounded(root, prop * _UP)

    def dot(self, other: "Enclosure") -> "Enclosure":
        """Sum over the last axis of the products (three-vectors: (n, 3) arrays)."""
        p = self * other
        out = p[..., 0]
        for c in range(1, p.value.shape[-1]):
            out = out + p[..., c]
        return out

    def cross(self, other: "Enclosure") -> "Enclosure":
        a, b = self, other

        def c(i, j):
            return a[..., i] * b[..., j] - a[..., j] * b[..., i]
        x, y, z = c(1, 2), c(2, 0), c(0, 1)
        return Enclosure(np.stack([x.value, y.value, z.value], axis=-1),
                         np.stack([x.err, y.err, z.err], axis=-1))

    def bounded(self) -> np.ndarray:
        """Where the enclosure says something: value and error finite."""
        return np.isfinite(self.value) & np.isfinite(self.err)


def angle_from(y: Enclosure, x: Enclosure) -> Enclosure:
    """atan2(y, x) in [0, pi] for an exact y >= 0.  The disc of radius rho = err_x + err_y
    around (x', y') holds the exact point; seen from the origin at distance r > rho it
    subtends at most asin(rho / r) <= (pi / 2) rho / r; atan2 is continuous on the closed
    upper half-plane without the origin.  Undecided (infinite error) where rho >= r."""
    yv = np.maximum(y.value, 0.0)
    value = np.arctan2(yv, x.value)
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        rho = (x.err + y.err) * _UP
        r = np.hypot(yv, x.value) * (1.0 - 4.0 * U)          # hypot within 1 ulp: r below it
        prop = np.where(rho < r, (math.pi / 2) * _UP * rho / r, np.inf)
        err = (prop + _ATAN2_ULPS * 2.0 * U * np.abs(value)) * _UP + _TINY
    return Enclosure(value, err)


def correctly_rounded(values) -> Enclosure:
    """Floats each the correctly rounded float of an exact value x: |fl(x) - x| <= U |x|
    <= U |fl(x)| / (1 - U), or 2^-1075 below the normal range."""
    v = np.asarray(values, dtype=np.float64)
    return Enclosure(v, U * np.abs(v) * _UP + _TINY)


def rounding_bounds(e: Enclosure) -> tuple[np.ndarray, np.ndarray]:
    """(lo, hi): floats with lo <= fl(exact) <= hi for the correctly rounded float of every
    exact value ``e`` encloses (-inf, inf where it is undecided).  fl(v - err) computed
    once is the rounding of the real v - err, at most its neighbour above; one step down
    is below it, and rounding is monotone."""
    with np.errstate(over="ignore", invalid="ignore"):
        lo = np.nextafter(e.value - e.err, -np.inf)
        hi = np.nextafter(e.value + e.err, np.inf)
    ok = e.bounded() & np.isfinite(lo) & np.isfinite(hi)
    return np.where(ok, lo, -np.inf), np.where(ok, hi, np.inf)


def exact_floats(positions) -> bool:
    """Whether every coordinate is exactly a float (the enclosures then start exact)."""
    return all(_is_float(x) for p in positions for x in p)


def _is_float(x) -> bool:
    if type(x) is float:
        return True
    d = getattr(x, "denominator", None)
    if d is not None and d & (d - 1) == 0 and d <= 2 ** 1074 \
            and abs(x.numerator).bit_length() <= 53:
        return True                  # n / 2^k with n of at most 53 bits, not below 2^-1074
    try:
        return float(x) == x         # exactly: a float compares with a Fraction exactly
    except OverflowError:
        return False


def nondegenerate(V, F) -> bool:
    """True when every face certainly has a nonzero area: some coordinate of the float
    cross product (p1 - p0) x (p2 - p0) exceeds its rounding error bound.  Each difference
    is rounded once (relative 2^-53), each product and the subtraction once more: the
    computed coordinate is within 4.1 * 2^-53 (|a| + |b|) of the exact one for its two
    products a, b (doubled below for the products' own perturbation), plus 2^-1070 for
    underflow.  False: some face is not certified, and the exact metric decides.

    >>> nondegenerate([[0, 0, 0], [1, 0, 0], [0, 1e-300, 0]], [[0, 1, 2]])
    True
    >>> nondegenerate([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [[0, 1, 2]])
    False
    """
    P = np.asarray(V, dtype=np.float64)[np.asarray(F, dtype=np.int64)]
    # underflow is in the bound (2^-1070) and overflow makes it infinite (not certified):
    # whatever numpy error settings the caller has (np.seterr(all="raise")), no warning
    with np.errstate(all="ignore"):
        u, w = P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]
        a = u[:, [1, 2, 0]] * w[:, [2, 0, 1]]
        b = u[:, [2, 0, 1]] * w[:, [1, 2, 0]]
        bound = 8.2 * 2.0 ** -53 * (np.abs(a) + np.abs(b)) + 2.0 ** -1070
        return bool(np.all(np.any(np.abs(a - b) > bound, axis=1)))


def points(positions) -> Enclosure:
    """The positions as an (n, 3) enclosure: exact (``err`` all 0) where every coordinate
    is a float, else within the rounding of each (U |x|) of the exact rational.  The
    functions below take the positions or this enclosure of them (built once per surface:
    :func:`.views.position_enclosure`)."""
    if isinstance(positions, Enclosure):
        return positions
    try:
        V = np.asarray(positions, dtype=np.float64)
    except OverflowError:                       # beyond the float range: every entry exactly
        V = np.full((len(positions), 3), np.nan)
    return Enclosure(V, None if exact_floats(positions) else U * np.abs(V) + _TINY)


def corner_angle_enclosure(positions, F) -> Enclosure:
    """(m, 3): the angle at each corner of each face (D2.6, the triangle's own angle: the
    metric's), atan2(|a x b|, a . b) with a, b the sides from the corner to the next and
    previous corners."""
    return _per_corner(positions, F, lambda a, b, n: angle_from(n.dot(n).sqrt(), a.dot(b)))


def _per_corner(positions, F, corner) -> Enclosure:
    """(m, 3): ``corner(a, b, a x b)`` at each corner of each face, a and b the sides from
    the corner to the next and previous corners."""
    X = points(positions)
    F = np.asarray(F, dtype=np.int64).reshape(-1, 3)
    out = []
    for c in range(3):
        x = X[F[:, c]]
        a, b = X[F[:, (c + 1) % 3]] - x, X[F[:, (c + 2) % 3]] - x
        out.append(corner(a, b, a.cross(b)))
    return Enclosure(np.stack([e.value for e in out], axis=1),
                     np.stack([e.err for e in out], axis=1))


def total_area_enclosure(positions, F) -> tuple[float, float]:
    """(A, err): the total area of the faces (D2.6: each |a x b| / 2, Heron's of the exact
    squared lengths identically) within err of the exact sum.  ``math.fsum`` of the faces'
    floats is within u |A| of their real sum, which is within the sum of their errors of
    the exact one; infinite err where some face is not enclosed."""
    X = points(positions)
    F = np.asarray(F, dtype=np.int64).reshape(-1, 3)
    x = X[F[:, 0]]
    n = (X[F[:, 1]] - x).cross(X[F[:, 2]] - x)
    areas = n.dot(n).sqrt().scaled(0.5)
    if not areas.bounded().all():
        return math.nan, math.inf
    total = math.fsum(areas.value.tolist())
    err = (math.fsum(areas.err.tolist()) * (1 + 2 * U) + U * abs(total)) * _UP + _TINY
    return total, err


def corner_cot_enclosure(positions, F) -> Enclosure:
    """(m, 3): the cotangent of the angle at each corner of each face (D3.1's terms),
    (a . b) / |a x b| with a, b the sides from the corner to the next and previous corners;
    undecided where |a x b|'s enclosure reaches 0."""
    return _per_corner(positions, F, lambda a, b, n: a.dot(b) / n.dot(n).sqrt())


def area_gradient_enclosure(positions, F, n: int) -> Enclosure:
    """(n, 3): L3.8 / T3.9's gradient of the total area at each vertex, the sum over its
    faces of (|w|^2 a - <a, w> w) / (2 |a x w|) at the corner (a = v_i - v_j, w = v_k - v_j,
    j and k the next and previous corners: ``reference.areas.area_gradient_direct``)."""
    X = points(positions)
    F = np.asarray(F, dtype=np.int64).reshape(-1, 3)
    values, errs = [], []
    for c in range(3):
        xj = X[F[:, (c + 1) % 3]]
        a, w = X[F[:, c]] - xj, X[F[:, (c + 2) % 3]] - xj
        cross = a.cross(w)
        den = cross.dot(cross).sqrt().scaled(2.0)
        ww, aw = w.dot(w), a.dot(w)
        for x in range(3):
            term = (ww * a[:, x] - aw * w[:, x]) / den
            values.append(term.value)
            errs.append(term.err)
    # values[3 c + x]: corner c, coordinate x; summed per (vertex, coordinate)
    value = np.stack(values).reshape(3, 3, -1).transpose(2, 0, 1)      # (m, corner, coord)
    err = np.stack(errs).reshape(3, 3, -1).transpose(2, 0, 1)
    index = (F[:, :, None] * 3 + np.arange(3)).ravel()
    total = summed(Enclosure(value.ravel(), err.ravel()), index, 3 * n)
    return Enclosure(total.value.reshape(n, 3), total.err.reshape(n, 3))


def vertex_area_enclosures(positions, F, n: int) -> tuple[Enclosure, Enclosure]:
    """L3.7: (n,) each, the mixed Voronoi and the barycentric area of every vertex as
    ``reference.laplacian.vertex_areas_voronoi`` and ``vertex_areas_barycentric`` define
    them: per face with squared sides l0 = |01|^2, l1 = |12|^2, l2 = |20|^2, an obtuse
    corner (its opposite side longer than the other two: o > a + b) takes A / 2 and the
    others A / 4, else corners 0, 1, 2 take (l0 k2 + l2 k1) / 8, (l0 k2 + l1 k0) / 8,
    (l1 k0 + l2 k1) / 8 (k the corner cotangents); A / 3 each for the barycentric areas.
    The Voronoi area of a vertex of a face whose obtuse test the enclosures cannot decide
    is undecided (infinite error)."""
    X = points(positions)
    F = np.asarray(F, dtype=np.int64).reshape(-1, 3)
    x0, x1, x2 = X[F[:, 0]], X[F[:, 1]], X[F[:, 2]]
    e01, e12, e20 = x1 - x0, x2 - x1, x0 - x2
    l0, l1, l2 = e01.dot(e01), e12.dot(e12), e20.dot(e20)
    cross = e01.cross(x2 - x0)
    area = cross.dot(cross).sqrt().scaled(0.5)
    k = corner_cot_enclosure(X, F)
    k0, k1, k2 = k[:, 0], k[:, 1], k[:, 2]
    acute = [(l0 * k2 + l2 * k1).scaled(0.125), (l0 * k2 + l1 * k0).scaled(0.125),
             (l1 * k0 + l2 * k1).scaled(0.125)]
    # n_c = a + b - o at corners 0, 1, 2 (sides a, b at the corner, o opposite): obtuse iff < 0
    slack = [l0 + l2 - l1, l0 + l1 - l2, l1 + l2 - l0]
    with np.errstate(invalid="ignore"):
        obtuse = np.stack([n.value + n.err < 0 for n in slack], axis=1)
        sure = np.stack([(n.value + n.err < 0) | (n.value - n.err >= 0) for n in slack],
                        axis=1).all(axis=1)
    half, quarter = area.scaled(0.5), area.scaled(0.25)
    any_obtuse = obtuse.any(axis=1)
    value, err = np.empty((len(F), 3)), np.empty((len(F), 3))
    for c in range(3):
        rule = Enclosure(np.where(obtuse[:, c], half.value, quarter.value),
                         np.where(obtuse[:, c], half.err, quarter.err))
        value[:, c] = np.where(any_obtuse, rule.value, acute[c].value)
        err[:, c] = np.where(sure, np.where(any_obtuse, rule.err, acute[c].err), np.inf)
    voronoi = summed(Enclosure(value, err), F, n)
    third = area / Enclosure(np.float64(3.0))
    bary = summed(Enclosure(np.repeat(third.value[:, None], 3, axis=1),
                            np.repeat(third.err[:, None], 3, axis=1)), F, n)
    return voronoi, bary


def summed(terms: Enclosure, index, n: int) -> Enclosure:
    """(n,): the sums of ``terms`` (flat) by ``index`` (numpy's bincount).  It adds each
    entry's k terms in some order: within gamma_{k-1} of the sum of their absolute values
    (Higham, eq. 4.4), which a float sum of absolute values underestimates by at most that
    factor again: both covered by 2 k U (k U <= 2^-20 for any mesh numpy holds)."""
    idx = np.asarray(index, dtype=np.int64).ravel()
    value, err = terms.value.ravel(), terms.err.ravel()
    k = np.bincount(idx, minlength=n).astype(np.float64)
    total = np.bincount(idx, weights=value, minlength=n)
    with np.errstate(over="ignore", invalid="ignore"):
        spread = np.bincount(idx, weights=err, minlength=n)
        size = np.bincount(idx, weights=np.abs(value) + err, minlength=n)
        err = ((1 + 2 * k * U) * spread + 2 * k * U * (1 + 2 * k * U) * size) * _UP + _TINY
    return Enclosure(total, err)


def angle_sum_enclosure(corners: Enclosure, F, n: int) -> Enclosure:
    """D2.2: (n,) the sum of the corner angles at each vertex (:func:`summed`)."""
    return summed(corners, F, n)


#: 2 pi and pi as enclosures: |pi - fl(pi)| < 1.23e-16 < 2^-52
TWO_PI = Enclosure(np.float64(2 * math.pi), np.float64(2.0 ** -51))
PI = Enclosure(np.float64(math.pi), np.float64(2.0 ** -52))


def mean_curvature_enclosure(positions, I, J, K, L) -> tuple[Enclosure, Enclosure]:
    """D2.3's H(e) = 1/2 theta(e) l(e) per interior edge, enclosed: the first halfedge of e
    runs I -> J in face (I, J, K), its twin J -> I in (J, I, L), and the formula is the
    reference's (``reference.curvature.dihedral_angles``): n_f = e x (x_K - x_I), n_g =
    (x_I - x_J) x (x_L - x_J), height = <n_f, x_L - x_I>, |theta| = atan2(|e| |height|,
    <n_f, n_g>), theta > 0 iff height < 0.  Where the sign of the height is not decided the
    enclosure is 0 +- |H|'s bound (it holds for either sign).  Returns it and the
    enclosure of <n_f, n_g> (where the height may be 0, its sign tells a fold)."""
    X = points(positions)
    xi, xj, xk, xl = X[I], X[J], X[K], X[L]
    edge = xj - xi
    nf = edge.cross(xk - xi)
    ng = (xi - xj).cross(xl - xj)
    height = nf.dot(xl - xi)
    cos_part = nf.dot(ng)
    length = edge.dot(edge).sqrt()
    theta = angle_from(length * height.abs(), cos_part)
    half = (theta * length).scaled(0.5)                 # |H|
    with np.errstate(over="ignore", invalid="ignore"):
        sign = np.where(height.value - height.err > 0, -1.0,
                        np.where(height.value + height.err < 0, 1.0, 0.0))
        undecided = sign == 0
        value = np.where(undecided, 0.0, sign * half.value)
        err = np.where(undecided, (np.abs(half.value) + half.err) * _UP, half.err)
    return Enclosure(value, err), cos_part
