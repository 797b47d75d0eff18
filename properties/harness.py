"""The shared harness of the matrix properties: the exact reference on an example with its
float views and derived bounds (:class:`Exact`), an implementation's matrix read and
checked for shape and finiteness, the worst error in units of its bound, failures, and
the error ledger.

The properties of chapters 3 and 4 and ``ddg-oracle compare`` use these; the bounds
themselves are :mod:`.bounds`'.
"""

from __future__ import annotations

import contextlib
import contextvars
from fractions import Fraction
from functools import cached_property

import numpy as np

from ..reference.areas import area_gradient_floats
from ..reference.laplacian import vertex_areas_floats
from ..reference.metric import face_area_floats
from ..reference.polyhedral import PolyhedralSurface

from . import memo
from .conventions import pointwise_area
from .bounds import (K_COT, entry_bounds, face_area_tolerances, gamma, heron_product,
                     surface_squared_floats)
from .example import Example
from ..protocol.methods import FLOAT64_EPSILON, ISOLATED_VERTEX, at_machine_epsilon, eps
from .registry import PropertyFailure, TieDisagreement, decided_within, judgeable
from .views import exact_laplacian, laplacian_view, laplacian_view_bounds, validate

__all__ = ["Exact", "DenseViews", "ErrorLedger", "recording", "ledger_open", "record", "ratios",
           "fail", "implementation_matrix", "implementation_dense", "entries_at", "worst",
           "worst_sparse", "dirichlet_solve", "exact_spectrum", "dirichlet_solution", "widened"]


# --- the error ledger --------------------------------------------------------------------------------


class ErrorLedger:
    """The largest observed error / derived bound per catalog ID over the checks run while it
    records (:func:`recording`): how close an implementation came to its bounds.

    >>> ledger = ErrorLedger()
    >>> with recording(ledger):
    ...     _ = record("D3.1", [1.0, 3.0], [4.0, 4.0])
    >>> ledger.ratios
    {'D3.1': 0.75}
    """

    def __init__(self):
        self.ratios: dict[str, float] = {}

    def record(self, pid: str, ratio: float) -> None:
        self.ratios[pid] = max(self.ratios.get(pid, 0.0), ratio)


_LEDGER: contextvars.ContextVar = contextvars.ContextVar("ddg_error_ledger", default=None)


@contextlib.contextmanager
def recording(ledger: ErrorLedger):
    """Record the error ratios of the checks run inside this block into ``ledger``."""
    token = _LEDGER.set(ledger)
    try:
        yield ledger
    finally:
        _LEDGER.reset(token)


def ledger_open() -> bool:
    """Whether an :class:`ErrorLedger` is recording now (a check then records its exact
    error ratios, not only its verdict)."""
    return _LEDGER.get() is not None


def matrix_decided(A, keep, view, bound) -> bool:
    """True when float enclosures of an exact matrix decide that every entry of A (sparse,
    on a case's vertices) is within its bound of the correctly rounded exact entry x (issue
    46): ``view`` = (rows, cols, lo, hi) holds every entry that may be nonzero, on the
    exact matrix's vertices (``keep`` maps them to A's), lo <= x <= hi; ``bound`` its
    bounds there.  |A - x| <= bound at both ends of x's rounding interval (the rounded |A -
    x| is monotone in x on each side of A), every stored nonzero of A on those positions
    and every bound finite: the exact comparison (err / B <= 1) then passes too.  False
    leaves every verdict, failure report and recorded ratio to it, and so does an open
    :class:`ErrorLedger` (it records the exact ratios)."""
    if view is None or ledger_open():
        return False
    import scipy.sparse as sp
    rows, cols, lo, hi = view
    keep = np.asarray(keep, dtype=np.int64)
    r, c = keep[rows], keep[cols]
    C = A.tocoo()
    nz = C.data != 0
    pattern = sp.csr_matrix((np.ones(len(r)), (r, c)), shape=A.shape)
    if not (entries_at(pattern, C.row[nz], C.col[nz]) > 0).all():
        return False                            # a nonzero off the pattern: reported exactly
    return decided_within(entries_at(A, r, c), lo, hi, bound)


def ratios(err, bound) -> np.ndarray:
    """``err / bound`` elementwise: an error in units of its derived bound (inf where the
    bound is 0 and the error is not, 0 where both are).  An infinite (or NaN) bound judges
    nothing: where the error is not 0 there the entry is counted unjudged
    (:func:`~.registry.judgeable`, reported by the runner) and its ratio is 0."""
    err, bound = judgeable(err, bound)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(bound > 0, err / np.where(bound > 0, bound, 1), np.where(err > 0, np.inf, 0))


def record(pid: str, err, bound) -> float:
    """The largest :func:`ratios` of ``err`` and ``bound``, entered in the ledger recording
    now, if any; returned."""
    r = ratios(err, bound)
    ratio = float(np.max(r)) if r.size else 0.0
    ledger = _LEDGER.get()
    if ledger is not None:
        ledger.record(pid, ratio)
    return ratio


# --- the exact reference on an example ------------------------------------------------------------


class DenseViews:
    """Dense arrays ``Lf`` and ``B`` of an operator's sparse float view ``Ls`` and entry
    bounds ``Bs``, built only if a check of a small example asks for them."""

    @cached_property
    def Lf(self) -> np.ndarray:
        return self.Ls.toarray()

    @cached_property
    def B(self) -> np.ndarray:
        return self.Bs.toarray()


class Exact(DenseViews):
    """The exact reference on the floats of a case, with float views and entry bounds.
    ``Exact.of(case)``: the same, computed once per case content and machine epsilon (the
    bounds are the checked implementation's: float64 or float32) in this process
    (:mod:`.memo`: every implementation of a property is checked on the same examples);
    read-only."""

    @classmethod
    def of(cls, case: Example) -> "Exact":
        return memo.shared((cls.__name__, eps(), case.mesh_key), lambda: cls(case))

    def __init__(self, case: Example):
        self.case = case
        # the epsilon of its memo key: the bounds computed later (cached properties) are
        # this one's, whatever a watched call has raised the current epsilon to since
        self.epsilon = eps()
        # vertices used by no face are not part of the surface (the reference refuses
        # them): the surface is built on the others, ``keep[v]`` is the case's index of
        # its vertex v, and the matrices below are embedded back on all case.n vertices
        # with zero rows and columns at the isolated ones (protocol.ISOLATED_VERTEX)
        self.keep = sorted({v for f in case.faces for v in f})
        self.surface = case.surface if len(self.keep) == case.n else compact(case, self.keep)
        validate(self.surface)                  # raises DegenerateFace, as the metric would
        self.triangulation = self.surface.triangulation
        # the rest when first asked: a pointwise curvature's widened bound (in compare's own
        # process, beside the workers that compute the Laplacian) needs only the vertex
        # areas' bounds

    @property
    def metric(self):
        """The exact metric (D2.6), built when first asked (once per surface)."""
        return self.surface.metric()

    @cached_property
    def L(self):
        """The exact cotan Laplacian (D3.2; a SparseMatrix of exact numbers)."""
        return exact_laplacian(self.surface)

    @cached_property
    def bounds(self):
        """:func:`.bounds.entry_bounds` of the metric, at this object's epsilon (from the
        positions: the metric built only for a face the float filter leaves exact)."""
        with at_machine_epsilon(self.epsilon):
            return entry_bounds(self.surface, self.triangulation.n_vertices)

    @property
    def cot(self) -> np.ndarray:
        return self.bounds.cot

    @property
    def rho(self) -> np.ndarray:
        return self.bounds.rho

    @property
    def beta(self) -> np.ndarray:
        return self.bounds.beta

    # sparse (scipy CSR) on the case's n vertices: the float view of L, the entry bounds,
    # the edge pattern; Lf, B, adjacent are their dense arrays, built only if asked
    @cached_property
    def Ls(self):
        return self.embed(laplacian_view(self.surface).copy())

    @cached_property
    def Bs(self):
        return self.embed(self.bounds.B)

    @cached_property
    def adjacent_s(self):
        return self.embed(self.bounds.adjacent)

    @property
    def n(self) -> int:
        return self.case.n

    @cached_property
    def adjacent(self) -> np.ndarray:
        return self.adjacent_s.toarray()

    @cached_property
    def area_gradient(self) -> np.ndarray:
        """(k, 3) floats of the exact area gradient (T3.9, L3.8) at the surface's vertices,
        each correctly rounded: computed once, shared by every implementation."""
        return np.array(area_gradient_floats(self.surface),
                        dtype=np.float64).reshape(-1, self.surface.dimension)

    def vertex_areas(self, name: str) -> np.ndarray:
        """Floats of the exact ``vertex_areas_voronoi`` or ``vertex_areas_barycentric``
        (L3.7) at the surface's vertices, each correctly rounded; once per name."""
        kept = self.__dict__.setdefault("_vertex_areas", {})
        if name not in kept:
            kind = {"vertex_areas_voronoi": "voronoi", "vertex_areas_barycentric": "barycentric"}
            kept[name] = np.array(vertex_areas_floats(self.surface, kind[name]), dtype=np.float64)
        return kept[name]

    @cached_property
    def face_area_bounds(self) -> np.ndarray:
        """(k,) bound on the error of each face's area computed from the float points, by
        either route (:func:`.bounds.face_area_tolerances`: the cross product, or Heron on
        the side lengths), from the exact face (its area and squared sides as floats)."""
        with at_machine_epsilon(self.epsilon):
            return self._face_area_bounds()

    @cached_property
    def squared_floats(self) -> np.ndarray:
        """(k, 3) the faces' squared lengths (opposite corners 2, 0, 1), correctly rounded
        (from the positions: :func:`.bounds.surface_squared_floats`; a length beyond the
        float range raises OverflowError, as ``float()`` of the metric's did)."""
        return surface_squared_floats(self.surface)

    def _face_area_bounds(self) -> np.ndarray:
        k = self.triangulation.n_faces
        # correctly rounded, from the positions (no metric)
        area = np.array(face_area_floats(self.surface.positions, self.triangulation),
                        dtype=np.float64).reshape(k)
        # face_squared_lengths: opposite corners 2, 0, 1; columns here: corners 0, 1, 2
        squared = self.squared_floats[:, [1, 2, 0]]
        s = np.sqrt(squared)
        sides = np.stack([s[:, 1] * s[:, 2], s[:, 2] * s[:, 0], s[:, 0] * s[:, 1]],
                         axis=1).max(axis=1) / 2 if k else np.zeros(0)
        return face_area_tolerances(area, sides, heron_product(squared))

    @cached_property
    def vertex_area_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """(n,) bounds on the error of each vertex's mixed Voronoi area and of its
        barycentric area (L3.7): the corner cotangent bounds beta times the adjacent squared
        sides / 8, their rounding, and the face area's own bound (:attr:`face_area_bounds`)
        for the obtuse rule's A/2 and A/4 and the barycentric A/3."""
        with at_machine_epsilon(self.epsilon):
            return self._vertex_area_bounds()

    def _vertex_area_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        vb = np.zeros(self.n)      # bound of the Voronoi area of each vertex
        bb = np.zeros(self.n)      # of the barycentric one
        if not self.triangulation.n_faces:
            return vb, bb
        fa = self.face_area_bounds
        l0, l1, l2 = self.squared_floats.T
        beta, cot = self.beta, np.abs(self.cot)
        vor = []
        # sides at the corner and their opposite corners, corners 0, 1, 2
        for la, lb, ca, cb in ((l0, l2, 2, 1), (l0, l1, 2, 0), (l1, l2, 0, 1)):
            # either rule may be taken near a right angle; they agree there, so bound both
            vor.append((la * beta[:, ca] + lb * beta[:, cb]
                        + 8 * eps() * (la * cot[:, ca] + lb * cot[:, cb])) / 8 + fa)
        # added face by face, corner by corner (np.add.at keeps the order of its indices)
        at = np.asarray(self.keep, dtype=np.int64)[np.array(self.triangulation.faces,
                                                            dtype=np.int64)].ravel()
        np.add.at(vb, at, np.stack(vor, axis=1).ravel())
        np.add.at(bb, at, np.repeat(fa / 3, 3))
        return vb, bb

    def embed(self, M):
        """A sparse (k, k) matrix on the surface's vertices -> (n, n) CSR on the case's,
        zero at the isolated vertices."""
        import scipy.sparse as sp
        M = sp.csr_matrix(M)
        if len(self.keep) == self.case.n:
            return M
        C = M.tocoo()
        keep = np.asarray(self.keep, dtype=np.int64)
        return sp.csr_matrix((C.data, (keep[C.row], keep[C.col])),
                             shape=(self.case.n, self.case.n))

    def restrict(self, values) -> list:
        """Values on the case's vertices -> on the surface's (the isolated ones dropped)."""
        return [values[v] for v in self.keep]

    def components(self) -> list[list[int]]:
        """Vertex sets (case indices) of the components; an isolated vertex is one."""
        t, keep = self.triangulation, self.keep
        comps = [sorted({keep[v] for f in comp for v in t.faces[f]}) for comp in t.components()]
        used = set(keep)
        return comps + [[v] for v in range(self.case.n) if v not in used]

    def own_route_bound(self, u):
        """:meth:`residual_bound` for an implementation's own solver or gradient, whose
        matrix is unseen: any matrix within the entry bounds of the exact L (|A| <= |L's
        float view| + B), used backward-stably."""
        return self.residual_bound(self.L_magnitude + self.Bs, u)

    @cached_property
    def L_magnitude(self):
        """Sparse, on the case's vertices: an upper bound of ``abs(Ls)`` entry by entry, from
        the enclosures of the exact L where they hold every entry
        (:func:`.views.laplacian_view_bounds`: max(|lo|, |hi|) >= |x|, within a few ulps
        of it), else ``abs(Ls)`` itself.  A bound built on it is never smaller than one
        built on the view (float sums of non-negative terms are monotone in each)."""
        import scipy.sparse as sp
        view = laplacian_view_bounds(self.surface)
        if view is None or not (np.isfinite(view[2]).all() and np.isfinite(view[3]).all()):
            return abs(self.Ls)
        rows, cols, lo, hi = view
        k = self.triangulation.n_vertices
        return self.embed(sp.csr_matrix((np.maximum(np.abs(lo), np.abs(hi)), (rows, cols)),
                                        shape=(k, k)))

    def area_gradient_bound(self, P) -> tuple[np.ndarray, np.ndarray]:
        """(n, 3) exact area gradient (correctly rounded; the protocol's value at an
        isolated vertex) and the bound on an implementation's own ``area_gradient`` at the
        float positions P (T3.9): L V with a matrix within the entry bounds, plus its
        rounding.  Its own route may differ (1/2 n x (v_k - v_j)); that one has the same
        conditioning, 1 / sin of the face's smallest angle, as the cotangents."""
        exact = self.area_gradient_at(P)
        return exact, self.own_route_bound(P) + eps() * np.abs(exact)

    def area_gradient_at(self, P) -> np.ndarray:
        """(n, 3) exact area gradient (correctly rounded) at the case's vertices, the
        protocol's value at an isolated vertex; P only gives the shape."""
        exact = np.full(np.shape(P), ISOLATED_VERTEX["area_gradient"])
        exact[self.keep] = self.area_gradient
        return exact

    def dirichlet_solution_bound(self, boundary, u) -> np.ndarray:
        """(n,) bound on |u~ - u| for an implementation's ``solve_dirichlet`` answer u~ whose
        exact solution (C3.4) is ``u`` (floats): eps |u| on the ``boundary`` set (the given
        values are kept); elsewhere |L_II^-1| times :meth:`own_route_bound` at the interior
        rows, the first-order error of a backward-stable solve with any matrix within the
        entry bounds (u~ - u = L_II^-1 (r) for a residual r within that bound), doubled to
        cover the second-order terms and the float inverse.  Dense: for small meshes (the
        test vectors); L_II is invertible when every component meets the boundary set."""
        u = np.asarray(u, dtype=np.float64)
        fixed = np.zeros(self.n, dtype=bool)
        fixed[np.asarray(boundary, dtype=np.int64)] = True
        inner = np.flatnonzero(~fixed)
        out = eps() * np.abs(u)
        if len(inner):
            r = self.own_route_bound(u)[inner]
            inverse = np.linalg.inv(self.Ls[inner][:, inner].toarray())
            out[inner] = 2 * (np.abs(inverse) @ r) + eps() * np.abs(u[inner])
        return out

    def residual_bound(self, A, u):
        """Per row: sum_j (B_ij + gamma_{3n} |A_ij|) |u_j| (u: n or n x k): how far A u may be
        from the exact L u through the entry errors and a backward-stable evaluation or solve."""
        absu = np.abs(u)
        return self.Bs @ absu + gamma(3 * self.n + 3) * (abs(A) @ absu)


def widened(conventions, method: str, answer, case, bound):
    """``bound`` on ``method``'s ``answer`` (already mapped) on ``case``, widened by what the
    declared conventions' maps cannot carry back exactly: a pointwise curvature multiplied
    back by a float vertex area (:func:`.conventions.pointwise_area`).  The library divided by its own
    float area and the map multiplies by another, each within L3.7's vertex-area bound B of
    the exact A (:attr:`Exact.vertex_area_bounds`), so the answer is the angle
    defect times 1 + d, |d| <= 2 B / (A - B): the bound grows by d (|answer| + bound), is
    infinite where 0 < A <= B (the float area is not even of certain sign) and unchanged at
    a vertex of no face (A = B = 0).  Every other
    map adds at most two roundings, inside the bounds: ``bound`` unchanged.  ``case``: the
    Example, or a function building it (called only if needed)."""
    name = pointwise_area(c for c in conventions if c.applies(method))
    if name is None:
        return bound
    X = Exact.of(case() if callable(case) else case)
    B = X.vertex_area_bounds[0 if name == "vertex_areas_voronoi" else 1]
    A = np.zeros(len(B))
    A[X.keep] = X.vertex_areas(name)
    with np.errstate(divide="ignore", invalid="ignore"):
        # no area at all (a vertex of no face: the map puts the protocol's value there,
        # nothing is divided): nothing to add; an area not even of certain sign: no bound
        d = np.where(A > B, 2 * B / (A - B), np.where(B == 0, 0.0, np.inf))
        extra = d * (np.abs(np.asarray(answer, dtype=np.float64)) + bound)
    # inf * 0 is NaN, and a NaN bound fails every comparison: infinite stays infinite
    return bound + np.where(np.isinf(d), np.inf, extra)


def compact(case: Example, keep) -> PolyhedralSurface:
    new = {v: i for i, v in enumerate(keep)}
    return PolyhedralSurface.from_arrays([case.positions[v] for v in keep],
                                         [[new[v] for v in f] for f in case.faces])


def implementation_matrix(impl, case: Example, pid: str, method: str = "cotan_laplacian",
                          flips: bool = False):
    """The implementation's matrix (``method``) as scipy CSR of float64, duplicates summed;
    a failure if it is not n x n or has a non-finite entry, a tie if every non-finite entry
    is at a face beyond float resolution.  ``flips``: a matrix after intrinsic flips, where
    such a face's infinite cotangents (and the NaN of inf - inf) reach edges the input does
    not have, and spread through later flips: then any non-finite entry is a tie when some
    input face is beyond float resolution."""
    import scipy.sparse as sp
    M = getattr(impl, method)(*case.arrays())
    if sp.issparse(M):
        A = sp.csr_matrix(M, dtype=np.float64)
    else:
        a = np.asarray(M, dtype=np.float64)
        if a.ndim != 2:
            raise PropertyFailure(pid, impl, f"{method} has the wrong shape", mesh=case.mesh,
                                  expected=(case.n, case.n), observed=a.shape)
        A = sp.csr_matrix(a)
    if A.shape != (case.n, case.n):
        raise PropertyFailure(pid, impl, f"{method} has the wrong shape", mesh=case.mesh,
                              expected=(case.n, case.n), observed=A.shape)
    A.sum_duplicates()
    if not np.all(np.isfinite(A.data)):
        C = A.tocoo()
        bad = ~np.isfinite(C.data)
        beyond = beyond_float_resolution(case)
        pairs = set(zip(C.row[bad].tolist(), C.col[bad].tolist()))
        if pairs <= beyond or (flips and beyond):
            raise TieDisagreement(pid, impl, f"{method} has non-finite entries, all at faces "
                                  "beyond float resolution (K_COT eps rho >= 1, or an area "
                                  "bound at least the area: a float area, from the coordinates "
                                  "or from the side lengths, may be 0)", mesh=case.mesh)
        i, j = min(pairs - beyond)
        raise PropertyFailure(pid, impl, f"{method} has non-finite entries (first: {(i, j)})",
                              mesh=case.mesh, element=(i, j))
    return A


def beyond_float_resolution(case: Example) -> set:
    """Vertex pairs (i, j), i == j included, of the faces whose conditioning puts their
    float area out of reach: K_COT eps rho >= 1 (rho = l_max^2 / (2 A), exact A), or the
    face area's derived bound (:attr:`Exact.face_area_bounds`) at least the area (Heron on
    the float side lengths of a cap, whose error grows as rho^2).  There a float cross product, or a
    float Heron area, can be 0 although the exact face is not degenerate (the area's
    derived bound is at least the area itself), and a cotangent from it infinite: rounding
    decides, as at a tie."""
    X = Exact.of(case)
    out = set()
    area = np.array([float(X.metric.area(f)) for f in range(X.triangulation.n_faces)])
    lost = (K_COT * eps() * np.asarray(X.rho) >= 1) | (X.face_area_bounds >= area)
    for f in np.flatnonzero(lost).tolist():
        face = [X.keep[v] for v in X.triangulation.faces[f]]
        out.update((a, b) for a in face for b in face)
    return out


def implementation_dense(impl, case: Example, pid: str, method: str = "cotan_laplacian",
                         flips: bool = False) -> np.ndarray:
    """:func:`implementation_matrix` as a dense array, for the checks of small examples that factor it."""
    return implementation_matrix(impl, case, pid, method, flips).toarray()


def entries_at(M, rows, cols) -> np.ndarray:
    """The entries of the sparse matrix ``M`` at the index arrays ``rows``, ``cols``."""
    if len(rows) == 0:
        return np.zeros(0)
    return np.asarray(M[np.asarray(rows), np.asarray(cols)], dtype=np.float64).ravel()


def worst_sparse(err, bound):
    """((i, j), largest err / bound) over the stored entries of the sparse ``err`` (bound 0
    where err > 0: infinite); ((0, 0), 0.0) if it has none."""
    E = err.tocoo()
    if E.nnz == 0:
        return (0, 0), 0.0
    r = ratios(E.data, entries_at(bound, E.row, E.col))
    k = int(np.argmax(r))
    return (int(E.row[k]), int(E.col[k])), float(r[k])


def fail(pid, impl, case, message, **kw):
    raise PropertyFailure(pid, impl, message, mesh=case.mesh, **kw)


def worst(err, bound):
    """(index, largest err / bound) over an array of errors and their bounds."""
    r = ratios(err, bound)
    idx = tuple(int(x) for x in np.unravel_index(int(np.argmax(r)), r.shape))
    return idx, float(r[idx])


def dirichlet_solve(A, V0, c):
    """The Dirichlet solution with the implementation's matrix (dense LU): ``c`` (values,
    or positions n x k) kept on V0, ``A u = 0`` solved at the others; returns (u, others)."""
    n = A.shape[0]
    B0 = sorted(set(V0))            # a boundary vertex given twice is still one column
    I = [v for v in range(n) if v not in set(B0)]
    u = np.array(c, dtype=float).copy()
    if I:
        u[I] = np.linalg.solve(A[np.ix_(I, I)], -A[np.ix_(I, B0)] @ u[B0])
    return u, I


# --- exact values the chapter-3 checks and compare decide on --------------------------------------


def exact_spectrum(M) -> tuple[np.ndarray, float]:
    """(eigenvalues ascending, err) of the exact symmetric matrix whose correctly rounded
    float view is the dense ``M`` (entries within u = 2**-53 relative): Weyl, |lambda(view)
    - lambda(exact)| <= u ||M||_F, plus eigvalsh's own backward error gamma_4k ||M||_F
    (k the order).  The exact quantity a sign or definiteness statement is decided on."""
    k = M.shape[0]
    if k == 0:
        return np.zeros(0), 0.0
    # our own float64 eigvalsh: float64's gamma, whatever the checked implementation declares
    return np.linalg.eigvalsh(M), float((2.0 ** -53 + gamma(4 * k, FLOAT64_EPSILON))
                                        * np.linalg.norm(M))


def dirichlet_solution(example: Example) -> list:
    """C3.4 / T3.5: the exact solution with the example's boundary set and values (the
    floats taken exactly)."""
    from ..reference.dirichlet import solve_dirichlet
    return solve_dirichlet(example.surface, {v: Fraction(c) for v, c in
                                             zip(example.boundary, example.values)})
