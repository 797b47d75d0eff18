"""The exact intrinsic Delaunay operator on an example (A4.13, D4.8 / R4.9) with its float
view, entry bounds and the error model of float flips; the same view's rounding intervals
and bounds found without the whole exact metric, the exact flips run on the region the
enclosures leave in doubt (:func:`local_delaunay`, :func:`delaunay_view_bounds`: issue 46);
the total-area bound of a triangulation given by squared lengths.  Expected values and
bounds only: the chapter-4 checks are :mod:`.delaunay`'s.

Error model, derived and stated.  For the input triangulation: the corner bound
``beta = K_COT eps (1 + cot^2) rho`` of :mod:`ddg_oracle.properties.bounds`.  A float
implementation that flips edges computes each new squared diagonal from the
five squared lengths and two areas of its quadrilateral, in the reference's
notation ``b + c - (e+b-a)(e+c-d)/(2e) + 8 A1 A2 / e``; its error is at most
theta times the summed magnitudes of the polynomial terms, theta the largest
relative error of its inputs (+ a few roundings), plus the error of the areas,
each from its lengths off by min(2 theta W, sqrt(2 theta P)) (W = sum l |cot| / 4:
the area itself without an obtuse angle, about A / (alpha gamma) on a cap of small
angles alpha, gamma;
:func:`_flipped_error`).
Replaying the reference's flip log gives each face of the Delaunay
triangulation an amplification ``1 + sum of those chains`` that multiplies its
corner bounds (:func:`flip_amplification`).  The implementation's own flip
path may differ from the reference's at ties; there the two paths cross
cocircular configurations, where the operator is continuous, so the model
stays first-order right.  Each check reports its error in units of the bound.
"""

from __future__ import annotations

import math
from functools import cached_property
from typing import NamedTuple

import numpy as np

from ..reference.delaunay import flip_to_delaunay
from ..reference.exact import Quotient, rounded_sum

from . import memo
from .bounds import (bounds_of, entry_bounds, face_conditioning, gamma, heron_product,
                     surface_conditioning)
from .enclosures import Enclosure, correctly_rounded
from .views import (corner_cots, exact_laplacian, halfedge_table, laplacian_view, validate,
                    view_bounds_of)
from .harness import DenseViews, Exact, entries_at
from .example import Example
from ..protocol.methods import eps
from ..reference.combinatorics import (TriangulationBuilder, face_of, halfedge, next_corner,
                                       opposite_corner, prev_corner)


# --- the exact Delaunay operator on a case, with its error model ---------------------------------


def _magnitude(u):
    """The closed flip formula for the quadrilateral ``u`` (an
    :class:`~ddg_oracle.reference.intrinsic.Unfolding`; module doc), as floats: (Mp, (A1,
    A2), (P1, P2), e2) with Mp the summed magnitudes of its polynomial terms, A1, A2 the two
    faces' areas, P1, P2 their :func:`~.bounds.heron_product`, e2 the squared length of the
    edge."""
    e2, a, b, c, d = (float(x) for x in (u.sq_ij, u.sq_jk, u.sq_ki, u.sq_il, u.sq_lj))
    A1, A2 = float(u.area_ijk), float(u.area_jil)
    P1, P2 = (float(heron_product([L])[0]) for L in ((e2, a, b), (e2, c, d)))
    Mp = b + c + abs((e2 + b - a) * (e2 + c - d)) / (2 * e2)
    return Mp, (A1, A2), (P1, P2), e2


def _flipped_error(Mp, areas, products, e2, theta: float) -> float:
    """Bound on |new~ - new| for the squared diagonal new = b + c - (e+b-a)(e+c-d)/(2e) +
    8 A1 A2 / e computed from squared lengths with relative errors up to ``theta`` (the
    formula's own roundings included): theta Mp for the polynomial terms (first order), and
    for the product of the areas 8 / e (dA1 A2 + A1 dA2 + dA1 dA2), each area from its
    lengths off by dA <= min(2 theta W, sqrt(2 theta P)) (W = P / A;
    :func:`~.bounds.face_area_tolerances`' derivation: |A~ - A| <= |A~^2 - A^2| / A with
    |16 A~^2 - 16 A^2| <= 32 theta P).  On a face without an obtuse angle W = A and the
    area term is about 32 theta A1 A2 / e (the magnitude 8 A1 A2 / e of before, times
    4); on a cap (small angles alpha, gamma) W ~ A / (alpha gamma): a float flip of a cap's
    long edge is
    that ill-conditioned (the test vectors' 2**-30 cap: a layout flip with Heron areas off
    by 2.8e-10 relative, against the bound of before, 4.9e-13)."""
    (A1, A2), (P1, P2) = areas, products

    def dA(A, P):
        return min(2 * theta * P / A if A > 0 else math.inf, math.sqrt(2 * theta * P))
    d1, d2 = dA(A1, P1), dA(A2, P2)
    return theta * Mp + 8 * (d1 * A2 + A1 * d2 + d1 * d2) / e2


def flip_amplification(metric, log) -> list[float]:
    """``amplification[f]`` for each face f of the triangulation after the flips of ``log``
    (from :func:`flip_to_delaunay` on ``metric``): the factor of face f's length
    perturbation (module doc), 1 + the largest relative error, in units of eps, of its
    squared lengths, each flipped one's propagated by :func:`_flipped_error` from its
    inputs' (+ 4 roundings).  The flips' quadrilaterals are the log's (exact values the
    flips computed: floats of them, no exact arithmetic again); only the combinatorics are
    replayed, for the ids of each quadrilateral's edges."""
    t = TriangulationBuilder(metric.triangulation)   # flipped in place, O(1) per flip
    rel = [0.0] * t.n_edges                      # relative error of each squared length, in eps
    for rec in log:
        u, e = rec.unfolding, rec.edge
        Mp, areas, products, e2 = _magnitude(u)
        inputs = {t.edge_of(halfedge(x, c)) for x in u.faces for c in range(3)}
        t.flip(e)
        theta = (max(rel[x] for x in inputs) + 4) * eps()
        rel[e] = _flipped_error(Mp, areas, products, e2, theta) / (
            float(u.new_squared_length) * eps())
    return [1 + max(rel[t.edge_of(halfedge(f, c))] for c in range(3))
            for f in range(t.n_faces)]


def delaunay_of(metric):
    """``flip_to_delaunay(metric, lazy=True)`` (A4.13: the Delaunay metric and the flip log;
    lazy exact numbers: the same flips and values, exact forms only where asked), once per
    metric object (:func:`.memo.of`: the property's reference values and the reference
    adapter's answer on a mesh file are one run); read-only."""
    return memo.of(_lazy_flip_to_delaunay, metric)


def _lazy_flip_to_delaunay(metric):
    return flip_to_delaunay(metric, lazy=True)


class DelaunayExact(DenseViews):
    """The exact Laplace-Beltrami operator of a case's metric, float view and entry bounds:
    sparse (``Ls``, ``Bs``, ``interior_s``: scipy CSR on the case's vertices, any mesh size),
    dense arrays ``Lf``, ``B``, ``interior_pairs`` built only if a check of a small example
    asks for them."""

    of = classmethod(Exact.of.__func__)      # once per case content, read-only (.memo)

    def __init__(self, case: Example):
        import scipy.sparse as sp
        self.X = X = Exact.of(case)
        self.delaunay, self.log = delaunay_of(X.metric)
        self.amplification = flip_amplification(X.metric, self.log)
        t = self.delaunay.triangulation
        k = t.n_vertices
        self.bounds = entry_bounds(self.delaunay, k, self.amplification)
        self.Ls = X.embed(laplacian_view(self.delaunay).copy())
        self.Bs = X.embed(self._widen_on_cocircular_cells(self.bounds.B))
        # P4.10 / R4.9 speak of interior edges: a boundary edge opposite an obtuse angle has
        # the weight 1/2 cot < 0 in every triangulation (docs/errata.md, SC-1)
        pairs = {False: set(), True: set()}
        for e in range(t.n_edges):
            i, j = t.edge_vertices(e)
            if i != j:                              # a loop (after flips) has no off-diagonal
                pairs[t.is_boundary_edge(e)].update(((i, j), (j, i)))
        inner = sorted(pairs[False] - pairs[True])
        rows = np.array([p[0] for p in inner], dtype=np.int64)
        cols = np.array([p[1] for p in inner], dtype=np.int64)
        self.interior_s = X.embed(sp.csr_matrix((np.ones(len(inner), dtype=bool), (rows, cols)),
                                                shape=(k, k)))

    @cached_property
    def L(self):
        """The exact matrix (D3.2 of the Delaunay metric; a SparseMatrix of exact numbers).
        The checks need only its float view and bounds (``Ls``, ``Bs``), computed without
        it: after many flips its entries divide by areas with hundreds of square roots."""
        return exact_laplacian(self.delaunay)

    @cached_property
    def interior_pairs(self) -> np.ndarray:
        return self.interior_s.toarray()

    def _weight_floats(self) -> dict:
        """{edge: float of its exact cotan weight} of the Delaunay triangulation, correctly
        rounded: minus the float view of L's entry where one edge joins its two vertices
        (the entry is that weight), else from the exact corner cotangents as quotients
        n / (8 A) (correctly rounded without dividing)."""
        t, m = self.delaunay.triangulation, self.delaunay
        ends = [t.edge_vertices(e) for e in range(t.n_edges)]
        count: dict = {}
        for i, j in ends:
            key = (min(i, j), max(i, j))
            count[key] = count.get(key, 0) + 1
        single = [e for e, (i, j) in enumerate(ends)
                  if i != j and count[(min(i, j), max(i, j))] == 1]
        at = np.array([ends[e] for e in single], dtype=np.int64).reshape(-1, 2)
        # one vectorised lookup (scipy's element indexing: 20 us per entry)
        entries = entries_at(laplacian_view(self.delaunay), at[:, 0], at[:, 1])
        out = {e: -float(x) if x else 0.0 for e, x in zip(single, entries)}
        for e in range(t.n_edges):
            if e not in out:                    # a multi-edge or a loop: the edge's own
                halves = [Quotient(m.face_cot_numerators(f)[opposite_corner(h)], 8 * m.area(f))
                          for h in t.edge_halfedges(e) if h >= 0 for f in (face_of(h),)]
                out[e] = rounded_sum(halves)
        return out

    def _widen_on_cocircular_cells(self, B):
        """R4.9: on a cell of cocircular triangles (joined across edges of weight exactly 0)
        every choice of diagonals is Delaunay and gives the same operator, so an
        implementation that chose other diagonals has weights exactly 0 (in floats: about
        eps) at vertex pairs that are no edge here, where the bound would be 0.  Those
        pairs get the largest bound of the cell's own zero-weight edges: the same corners'
        conditioning, a weight that is 0 either way.  Weights within their bound of 0 count
        as 0: there rounding decides which diagonal is Delaunay.  ``B``: the entry bounds
        (sparse, the Delaunay triangulation's vertices); returns them widened."""
        import scipy.sparse as sp
        t = self.delaunay.triangulation
        w = self._weight_floats()
        root = list(range(t.n_faces))

        def find(f):
            while root[f] != f:
                root[f] = root[root[f]]
                f = root[f]
            return f

        # exactly 0, or within the entry's float bound of 0 (the input's floats made an
        # exactly cocircular quadrilateral nearly so: rounding may choose either diagonal)
        inner = [e for e in range(t.n_edges) if not t.is_boundary_edge(e)]
        if not inner:
            return B
        ends = np.array([t.edge_vertices(e) for e in inner], dtype=np.int64).reshape(-1, 2)
        b = entries_at(B, ends[:, 0], ends[:, 1])
        zero = [(e, float(be)) for e, be in zip(inner, b) if abs(w[e]) <= be]
        for e, _ in zero:
            h, tw = t.edge_halfedges(e)
            root[find(face_of(h))] = find(face_of(tw))
        bound: dict[int, float] = {}
        for e, be in zero:
            r = find(face_of(t.edge_halfedges(e)[0]))
            bound[r] = max(bound.get(r, 0.0), be)
        cells: dict[int, set] = {}
        for f in range(t.n_faces):
            if find(f) in bound:
                cells.setdefault(find(f), set()).update(t.faces[f])
        rows, cols, vals = [], [], []
        for r, vs in cells.items():
            vs = sorted(vs)
            I = np.repeat(vs, len(vs))
            J = np.tile(vs, len(vs))
            off = I != J
            I, J = I[off], J[off]
            have = entries_at(B, I, J)
            new = have == 0
            rows.extend(I[new])
            cols.extend(J[new])
            vals.extend([bound[r]] * int(new.sum()))
        if not rows:
            return B
        return sp.csr_matrix(B + sp.csr_matrix((vals, (rows, cols)), shape=B.shape))


# --- the same operator decided from enclosures (issue 46) ----------------------------------------


class LocalDelaunay(NamedTuple):
    """The Delaunay triangulation of a surface's metric as :func:`delaunay_of` reaches it,
    found without the whole exact metric (:func:`local_delaunay`): faces (m, 3) and halfedge
    table (:func:`.views.halfedge_table`'s) of the flipped triangulation, in the numbering
    of ``delaunay_of(surface.metric())``'s; ``cot``, the corner cotangents enclosed; ``rho``,
    ``cot_factors``: :func:`~.bounds.face_conditioning`'s factors; ``region``: the faces the
    flips ran on (ids of the surface), ``flips``: their metric and flip log (None without
    flips).  Nothing here depends on the machine epsilon: :meth:`amplification` does."""

    faces: np.ndarray
    table: np.ndarray
    cot: object
    rho: np.ndarray
    cot_factors: np.ndarray
    region: np.ndarray
    flips: tuple | None

    def amplification(self) -> np.ndarray:
        """:func:`flip_amplification` per face, at the current machine epsilon (the checked
        implementation's: its flips' error model scales with it), 1 off the region."""
        out = np.ones(len(self.faces))
        if self.flips is not None:
            out[self.region] = flip_amplification(*self.flips)
        return out


def local_delaunay(surface):
    """:class:`LocalDelaunay` of a surface with positions in R^3, or None where it is not
    found this way; once per surface object.

    Every interior edge whose enclosed cot sum is certainly > 0 is Delaunay, and stays so
    until a flip changes one of its faces (:func:`~ddg_oracle.reference.delaunay.
    flip_to_delaunay` then skips it).  The faces of the other edges, with a ring around
    them, make a region R; the exact flip algorithm runs on R's own metric, its border
    edges (one face in R) boundary there.  When no flip touches a border edge, the run on
    R makes the same flips in the same order as the run on the whole metric (every edge it
    tests has the same two faces there; the edges outside R are never tested differently:
    certified and unchanged), so its result, stitched into the surface, is that run's.
    Otherwise R grows by a ring and the run repeats (at most ``_ROUNDS`` times, R at most a
    ``_SHARE`` of the faces; else None).  None too where the run raises: the exact route
    then decides and says why.  A4.13's flips, for D4.8 / R4.9's operator."""
    return memo.of(_local_delaunay, surface)


_ROUNDS, _SHARE = 6, 0.25


def _local_delaunay(surface):
    if getattr(surface, "dimension", None) != 3:
        return None
    validate(surface)                                       # raises DegenerateFace
    try:
        rho, cot_factors = surface_conditioning(surface)
    except OverflowError:               # a face the flips may remove: the exact route decides
        return None
    t = surface.triangulation
    F = np.asarray(t.faces, dtype=np.int64).reshape(-1, 3)
    table = halfedge_table(surface)
    cot = corner_cots(surface)
    inner = table[:, 1] >= 0
    h, g = table[:, 0], np.where(inner, table[:, 1], table[:, 0])
    s = cot[h // 3, (h % 3 + 2) % 3] + cot[g // 3, (g % 3 + 2) % 3]
    with np.errstate(invalid="ignore"):
        doubt = inner & ~(s.value - s.err > 0)
    m = len(F)
    if not doubt.any():
        return LocalDelaunay(F, table, cot, rho, cot_factors, np.zeros(0, dtype=np.int64), None)
    # the faces across each edge of every face: (m, 3), -1 on the boundary
    across = np.full(3 * m, -1, dtype=np.int64)
    across[table[inner, 0]] = table[inner, 1] // 3
    across[table[inner, 1]] = table[inner, 0] // 3
    across = across.reshape(m, 3)
    region = np.zeros(m, dtype=bool)
    region[table[doubt].ravel() // 3] = True
    for _ in range(_ROUNDS):
        region[across[region][across[region] >= 0]] = True          # one ring more
        if region.sum() > _SHARE * m:
            return None
        try:
            found = _flipped_region(surface, F, table, np.flatnonzero(region))
        except Exception:                       # the exact route decides, and says why
            return None
        if found is not None:
            break
    else:
        return None
    faces, rows, tab, cots, (r, c), flips = found
    F2, table2, rho2, cf2 = F.copy(), table.copy(), rho.copy(), cot_factors.copy()
    value, err = cot.value.copy(), cot.err.copy()
    F2[faces], table2[rows], rho2[faces], cf2[faces] = tab[0], tab[1], r, c
    value[faces], err[faces] = cots.value, cots.err
    return LocalDelaunay(F2, table2, Enclosure(value, err), rho2, cf2, faces, flips)


def _flipped_region(surface, F, table, faces):
    """The exact flips of the region ``faces`` (global ids, ascending) on its own metric
    (:func:`local_delaunay`): None where a flip touched a border edge, else (faces, the
    global ids of the region's edges but its border's, (the flipped faces in global vertex
    ids, those edges' halfedges in global ids), the corner cotangents enclosed, the
    conditioning factors, (the region's metric, the flip log))."""
    from ..reference.combinatorics import Triangulation
    from ..reference.metric import metric_of
    m = len(F)
    local = np.full(m, -1, dtype=np.int64)
    local[faces] = np.arange(len(faces))
    verts = np.unique(F[faces])
    vloc = np.full(int(F.max()) + 1, -1, dtype=np.int64)
    vloc[verts] = np.arange(len(verts))
    t = surface.triangulation

    def loc(x):                                 # a global halfedge in the region, or -1
        return -1 if x < 0 or local[x // 3] < 0 else 3 * int(local[x // 3]) + x % 3
    edges, gluings, border = [], [], []
    touching = (local[table[:, 0] // 3] >= 0) | (
        (table[:, 1] >= 0) & (local[np.maximum(table[:, 1], 0) // 3] >= 0))
    for e in np.flatnonzero(touching):
        a, b = (loc(int(x)) for x in table[e])
        if table[e, 1] >= 0 and (a < 0 or b < 0):       # one face in the region: a border edge
            border.append(len(gluings))
            gluings.append((max(a, b), -1, False))
        else:                                   # both faces in the region, or a boundary edge
            edges.append((len(gluings), int(e)))
            gluings.append((a, b, b >= 0 and t.reversed_gluing(int(table[e, 0]))))
    sub = Triangulation._trusted(vloc[F[faces]].tolist(), len(verts), tuple(gluings))
    positions = surface.positions
    metric = metric_of([positions[int(v)] for v in verts], sub)
    d, log = flip_to_delaunay(metric, lazy=True)
    flipped = {f for rec in log for f in rec.unfolding.faces}
    dt = d.triangulation
    if any(dt.edge_halfedges(b)[0] // 3 in flipped for b in border):
        return None
    lf = np.asarray(dt.faces, dtype=np.int64).reshape(-1, 3)
    lh = np.array([dt.edge_halfedges(le) for le, _ in edges], dtype=np.int64).reshape(-1, 2)
    gh = np.where(lh >= 0, 3 * faces[lh // 3] + lh % 3, -1)     # local halfedges to global
    rows = np.array([e for _, e in edges], dtype=np.int64)
    value = np.empty((len(faces), 3))
    for f in range(len(faces)):                         # cot = n / (4 A), correctly rounded
        four_a = 4 * d.area(f)
        value[f] = [rounded_sum([Quotient(n, four_a)]) if n else 0.0
                    for n in d.face_cot_numerators(f)]
    return (faces, rows, (verts[lf], gh), correctly_rounded(value), face_conditioning(d),
            (metric, log))


def delaunay_view_bounds(surface):
    """D4.8 / R4.9: (rows, cols, lo, hi, B) or None: every edge's two off-diagonal entries
    and every vertex's diagonal entry of the exact Laplace-Beltrami operator
    (:class:`DelaunayExact`'s ``L``; arrays on the surface's vertices), floats lo <= x <= hi
    for the correctly rounded view x of each and its entry bound, from
    :func:`local_delaunay` without the exact metric.  The view once per surface object,
    the bounds at each call: they are the current machine epsilon's (the checked
    implementation's; a float32 and a float64 one may read one surface object).  They are
    ``Bs``'s floats at these entries (R4.9 widens ``Bs`` only at vertex pairs joined by no
    edge: :meth:`DelaunayExact._widen_on_cocircular_cells`).  None where the triangulation
    is not found, or where an edge is a loop or two edges join one pair of vertices."""
    view = memo.of(_delaunay_view, surface)
    if view is None:
        return None
    found, (rows, cols, lo, hi) = view
    B = bounds_of(found.faces, found.table, found.rho, found.cot_factors,
                  surface.triangulation.n_vertices, found.amplification()).B
    return rows, cols, lo, hi, entries_at(B, rows, cols)


def _delaunay_view(surface):
    found = local_delaunay(surface)
    if found is None:
        return None
    view = view_bounds_of(found.faces, found.table, found.cot, surface.triangulation.n_vertices)
    return None if view is None else (found, view)


def angles_from_squared_lengths(l2):
    """Corner angles (law of cosines in atan2 form, stable) and doubled areas per face."""
    # Kahan's stable Heron (lengths sorted a >= b >= c, parentheses as written): the
    # textbook s(s-a)(s-b)(s-c) loses about rho digits on a cap, more than the bound allows
    a, b, c = np.sort(np.sqrt(l2), axis=1)[:, ::-1].T
    out = np.zeros_like(l2)
    area = 0.25 * np.sqrt(np.maximum((a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c)),
                                     0))
    for c in range(3):
        o, p, q = l2[:, c], l2[:, next_corner(c)], l2[:, prev_corner(c)]
        out[:, c] = np.arctan2(4 * area, p + q - o)
    return out, area


#: relative error, in units of eps, of a squared length computed from float coordinates
#: (three differences, three squares, two additions: gamma_5(u) = 2.5 eps; squaring a
#: length computed with a square root: 3.5 eps), rounded up: the base the flips' chain
#: amplification ``amp`` multiplies (:func:`flip_amplification`)
LENGTH_ERROR = 4.0


def total_area_bound(area, rho, amp: float, l2=None) -> float:
    """Bound on |sum of the face areas recomputed from a triangulation's float squared
    lengths - its exact total area| (A4.13).

    Heron: 16 A^2 = P(l) = 2 (l_a l_b + l_b l_c + l_c l_a) - (l_a^2 + l_b^2 + l_c^2), and
    dP/dl_c = 2 n_c with n_c = l_a + l_b - l_c (= 4 A cot_c).  Squared lengths with relative
    errors up to theta = (LENGTH_ERROR amp + 1) eps (the implementation's, after its
    flips, and the square roots this check takes of them) move 16 A^2 by at most D = 2
    theta sum_c l_c |n_c| + theta^2 (sum l)^2 (P is quadratic; the sum as
    :func:`~.bounds.heron_product`, which covers the float cancellation in n_c).  Then
    |A~ - A| = |A~^2 - A^2| / (A~ + A) <= min(D / (16 A~), sqrt(D / 16)), A~ the computed
    area (both from the float lengths alone: no conditioning factor to estimate).  To
    first order D / (16 A) = 2 theta W_f, W_f = sum_c l_c |cot_c| / 4
    (:func:`~.bounds.heron_condition`): W_f = A on a face without an obtuse angle, but
    about A / (alpha gamma) on a cap (small angles alpha, gamma; A rho^2 / 4 when they are
    equal), where a bound linear in rho (K_COT eps rho A, before issue 40) is short: the
    flip of a planar quadrilateral into two thin triangles with an angle near pi was off
    by 2.1e-12 against 1.55e-13.  Kahan's Heron in float64 adds at most 7 units of 2**-53 of A~ (3.5 eps A~),
    and the sum gamma_m sum A~.  ``l2`` (m, 3): the squared lengths; without them (an
    older caller) W_f <= 3 l_max rho / 4 = 1.5 A rho^2 stands in."""
    area = np.asarray(area, dtype=np.float64)
    theta = (LENGTH_ERROR * amp + 1) * eps()          # + 1: the check's own square roots
    if l2 is None:
        per_face = 2 * theta * 1.5 * area * np.asarray(rho, dtype=np.float64) ** 2
    else:
        l2 = np.asarray(l2, dtype=np.float64).reshape(-1, 3)
        total = l2.sum(axis=1)
        D16 = 2 * theta * heron_product(l2) + theta * theta * total * total / 16
        with np.errstate(divide="ignore", invalid="ignore"):
            first = np.where(area > 0, D16 / area, np.inf)
        per_face = np.minimum(first, np.sqrt(D16))
    return (float(per_face.sum()) + 3.5 * eps() * float(area.sum())
            + gamma(len(area)) * float(area.sum()))
