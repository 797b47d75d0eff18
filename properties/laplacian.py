"""Chapter 3 properties: Laplacians, Dirichlet energy and area, on any implementation.

Every property takes an implementation providing ``cotan_laplacian(V, F)`` (and,
for L3.7, ``vertex_areas_voronoi`` / ``vertex_areas_barycentric``), V float64
n x 3 and F int m x 3, in the reference's conventions: ``(L f)(i) = sum_j nu(ij)
(f(i) - f(j))``, positive semidefinite, ``nu = 1/2 (cot a + cot b)``, boundary
``1/2 cot a`` (see ``properties/protocol.py``).  The truth comes from the exact
reference (``ddg_oracle.reference.laplacian``, ``ddg_oracle.reference.areas``) evaluated on the very
floats the implementation received (every float is a dyadic rational, taken
exactly), or from how the example was built.

Tolerances are derived, never a bare constant.  A stable floating point
cotangent of a corner is the exact cotangent of a triangle whose side lengths
(or coordinates) are perturbed relatively by a few units of ``EPS``, the
checked implementation's declared machine epsilon (:func:`ddg_oracle.properties.protocol.eps`:
2**-52 for float64 unless the implementation declares e.g. float32).  A
relative change ``delta`` of one side ``a`` moves an angle by at most
``delta a^2 / (2A) <= delta rho_T`` with ``rho_T = l_max^2 / (2 A_T)`` (the
aspect ratio: large for needles), and ``d cot / d alpha = -(1 + cot^2)`` (large
near a zero or straight angle).  So the corner bound is

    beta_c = K_COT * EPS * (1 + cot_c^2) * rho_T,     K_COT = 32

(3 sides x at most 8 rounded operations each, plus the quotient, rounded up).
An entry of L sums ``k`` halves of cotangents: its bound ``B_ij`` is the sum of
the ``beta_c / 2`` plus ``k * EPS * sum |cot_c| / 2`` for the summation.  Every
derived quantity (``f^T L f``, ``L x``, eigenvalues, solves) propagates ``B``
and its own rounding (``gamma_k = k EPS / (1 - k EPS)`` times the sum of the
magnitudes of the summed terms).  Each check reports the observed error in
units of its bound; :data:`ERROR_RATIOS` keeps the largest ratio seen per ID.
A naive Heron formula loses accuracy on needles faster than this model
(``EPS rho^2``) and is reported as a failure there: that is a real loss.

Strategies build meshes from a few small integers (grid sizes, jitters in
sixteenths, ring radii) so that failures shrink to meshes of a few faces.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from fractions import Fraction

import numpy as np
from hypothesis import strategies as st

from ddg_oracle.reference.areas import area_gradient_floats
from ddg_oracle.reference.dirichlet import directional_derivative
from ddg_oracle.reference.laplacian import (cotan_laplacian, dirichlet_energy_pl, dirichlet_inner_product_pl,
                                 vertex_areas_floats, weight_sign_by_angles)
from ddg_oracle.reference.exact.rationals import on_common_denominator
from ddg_oracle.reference.metric import heron16
from ddg_oracle.reference.polyhedral import PolyhedralSurface

from . import memo
from .protocol import ISOLATED_VERTEX, capabilities, eps
from .strategies import (Example, acute_meshes, any_meshes, closed_meshes, jittered_grids,
                         obtuse_fans, obtuse_meshes, planar_meshes, scaled_meshes, single_triangles,
                         surface_meshes, with_boundary, with_functions, with_isolated)
from .registry import PropertyFailure, TieDisagreement, prop
from ddg_oracle.reference.combinatorics import face_of, opposite_corner

K_COT = 32

#: catalog ID -> largest observed error / bound over all checks run in this process
ERROR_RATIOS: dict[str, float] = {}


def gamma(k: int) -> float:
    """Higham's gamma_k = k EPS / (1 - k EPS), EPS = eps(): bound on the relative error of k roundings."""
    return k * eps() / (1 - k * eps())


def _record(pid: str, err, bound) -> float:
    err = np.asarray(err, dtype=float)
    bound = np.asarray(bound, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(bound > 0, err / np.where(bound > 0, bound, 1), np.where(err > 0, np.inf, 0))
    ratio = float(np.max(r)) if r.size else 0.0
    ERROR_RATIOS[pid] = max(ERROR_RATIOS.get(pid, 0.0), ratio)
    return ratio


# --- the exact reference on a case, and the error model --------------------------------------------


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


class Exact:
    """The exact reference on the floats of a case, with float views and entry bounds.
    ``Exact.of(case)``: the same, computed once per case content and machine epsilon (the
    bounds are the checked implementation's: float64 or float32) in this process
    (:mod:`.memo`: every implementation of a property is checked on the same examples);
    read-only."""

    @classmethod
    def of(cls, case: Example) -> "Exact":
        return memo.shared((cls.__name__, eps(), case.positions, case.faces), lambda: cls(case))

    def __init__(self, case: Example):
        self.case = case
        # vertices used by no face are not part of the surface (the reference refuses
        # them): the surface is built on the others, ``keep[v]`` is the case's index of
        # its vertex v, and the matrices below are embedded back on all case.n vertices
        # with zero rows and columns at the isolated ones (protocol.ISOLATED_VERTEX)
        self.keep = sorted({v for f in case.faces for v in f})
        self.surface = case.surface if len(self.keep) == case.n else _compact(case, self.keep)
        self.metric = self.surface.metric()
        t = self.triangulation = self.surface.triangulation
        k = t.n_vertices
        self.L = cotan_laplacian(self.surface)
        b = entry_bounds(self.metric, k)
        self.cot, self.rho, self.beta = b.cot, b.rho, b.beta
        # sparse (scipy CSR) on the case's n vertices: the float view of L, the entry bounds,
        # the edge pattern; Lf, B, adjacent are their dense arrays, built only if asked
        self.Ls = self.embed(self.L.to_scipy())
        self.Bs = self.embed(b.B)
        self.adjacent_s = self.embed(b.adjacent)

    @property
    def n(self) -> int:
        return self.case.n

    @cached_property
    def Lf(self) -> np.ndarray:
        return self.Ls.toarray()

    @cached_property
    def B(self) -> np.ndarray:
        return self.Bs.toarray()

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
        return self.residual_bound(abs(self.Ls) + self.Bs, u)

    def area_gradient_bound(self, P) -> tuple[np.ndarray, np.ndarray]:
        """(n, 3) exact area gradient (correctly rounded; the protocol's value at an
        isolated vertex) and the bound on an implementation's own ``area_gradient`` at the
        float positions P (T3.9): L V with a matrix within the entry bounds, plus its
        rounding.  Its own route may differ (1/2 n x (v_k - v_j)); that one has the same
        conditioning, 1 / sin of the face's smallest angle, as the cotangents."""
        exact = np.full(np.shape(P), ISOLATED_VERTEX["area_gradient"])
        exact[self.keep] = self.area_gradient
        return exact, self.own_route_bound(P) + eps() * np.abs(exact)

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


def total_area_view(metric) -> tuple[float, float]:
    """(A, err): the total area (T3.9, L3.7, R2.5's A) as ``math.fsum`` of the exact face
    areas (D2.6, Heron on exact squared lengths), each correctly
    rounded to float64 (error <= u a_f, u = 2**-53), and a bound on |A - exact total area|:
    u sum a_f for the faces plus u A for the correctly rounded sum.  For a mesh of any size:
    the exact total of a float mesh has one square root per face (float() of it takes
    minutes on 10,000 faces)."""
    areas = [float(a) for a in metric.areas]
    total = math.fsum(areas)
    u = 2.0 ** -53
    return total, u * (math.fsum(areas) + abs(total))


def _compact(case: Example, keep) -> PolyhedralSurface:
    new = {v: i for i, v in enumerate(keep)}
    return PolyhedralSurface.from_arrays([case.positions[v] for v in keep],
                                         [[new[v] for v in f] for f in case.faces])


def _sparse(impl, case: Example, pid: str, method: str = "cotan_laplacian"):
    """The implementation's matrix (``method``) as scipy CSR of float64, duplicates summed;
    a failure if it is not n x n or has a non-finite entry."""
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
        beyond = _beyond_float_resolution(case)
        pairs = set(zip(C.row[bad].tolist(), C.col[bad].tolist()))
        if pairs <= beyond:
            raise TieDisagreement(pid, impl, f"{method} has non-finite entries, all at faces "
                                  "beyond float resolution (K_COT eps rho >= 1: the float area "
                                  "from the coordinates may be 0)", mesh=case.mesh)
        i, j = min(pairs - beyond)
        raise PropertyFailure(pid, impl, f"{method} has non-finite entries (first: {(i, j)})",
                              mesh=case.mesh, element=(i, j))
    return A


def _beyond_float_resolution(case: Example) -> set:
    """Vertex pairs (i, j), i == j included, of the faces whose conditioning puts their
    float area out of reach: K_COT eps rho >= 1 (rho = l_max^2 / (2 A), exact A).  There a
    float cross product can be 0 although the exact face is not degenerate, and a cotangent
    from it infinite: rounding decides, as at a tie."""
    X = Exact.of(case)
    out = set()
    for f in np.flatnonzero(K_COT * eps() * np.asarray(X.rho) >= 1).tolist():
        face = [X.keep[v] for v in X.triangulation.faces[f]]
        out.update((a, b) for a in face for b in face)
    return out


def _dense(impl, case: Example, pid: str, method: str = "cotan_laplacian") -> np.ndarray:
    """:func:`_sparse` as a dense array, for the checks of small examples that factor it."""
    return _sparse(impl, case, pid, method).toarray()


def _at(M, rows, cols) -> np.ndarray:
    """The entries of the sparse matrix ``M`` at the index arrays ``rows``, ``cols``."""
    if len(rows) == 0:
        return np.zeros(0)
    return np.asarray(M[np.asarray(rows), np.asarray(cols)], dtype=np.float64).ravel()


def _worst_sparse(err, bound):
    """((i, j), largest err / bound) over the stored entries of the sparse ``err`` (bound 0
    where err > 0: infinite); ((0, 0), 0.0) if it has none."""
    E = err.tocoo()
    if E.nnz == 0:
        return (0, 0), 0.0
    b = _at(bound, E.row, E.col)
    r = np.where(b > 0, E.data / np.where(b > 0, b, 1), np.where(E.data > 0, np.inf, 0))
    k = int(np.argmax(r))
    return (int(E.row[k]), int(E.col[k])), float(r[k])


def _fail(pid, impl, case, message, **kw):
    raise PropertyFailure(pid, impl, message, mesh=case.mesh, **kw)


def _worst(err, bound):
    r = np.where(bound > 0, err / np.where(bound > 0, bound, 1), np.where(err > 0, np.inf, 0))
    idx = np.unravel_index(int(np.argmax(r)), r.shape)
    return idx, float(r[idx])


# --- properties ------------------------------------------------------------------------------------


@prop("D3.1", "cotan_laplacian is a weighted graph Laplacian on the mesh edges: symmetric, zero "
      "row sums, supported on edges, entries = the exact cotan weights (3.3) within the derived bound",
      needs={"cotan_laplacian"}, strategy=lambda: scaled_meshes(any_meshes(isolated=True)))
def cotan_laplacian_is_the_graph_laplacian_of_cotan_weights(impl, case: Example):
    # sparse throughout: runs on a mesh file of any size (ddg-oracle check --mesh)
    A = _sparse(impl, case, "D3.1")
    X = Exact.of(case)
    n = X.n
    C = A.tocoo()
    nz = C.data != 0
    r, c = C.row[nz], C.col[nz]
    off = (r != c) & (_at(X.adjacent_s, r, c) == 0)
    if np.any(off):
        k = int(np.argmax(off))
        i, j = int(r[k]), int(c[k])
        _fail("D3.1", impl, case, "nonzero entry between vertices that share no edge",
              element=(i, j), expected=0.0, observed=float(A[i, j]))
    (i, j), q = _worst_sparse(abs(A - A.T), X.Bs + X.Bs.T)
    if q > 1:
        _fail("D3.1", impl, case, f"not symmetric ({q:.3g} x the bound)", element=(i, j),
              expected=float(A[j, i]), observed=float(A[i, j]))
    sums = np.asarray(A.sum(axis=1)).ravel()
    rb = np.asarray(X.Bs.sum(axis=1)).ravel() + gamma(n) * np.asarray(abs(A).sum(axis=1)).ravel()
    (i,), q = _worst(np.abs(sums), rb)
    if q > 1:
        _fail("D3.1", impl, case, f"row sum is not 0 ({q:.3g} x the bound): constants are not "
              "in the kernel", element=f"row {i}", expected=0.0, observed=float(sums[i]))
    err = abs(A - X.Ls).tocoo()
    _record("D3.1", err.data, _at(X.Bs, err.row, err.col))
    (i, j), q = _worst_sparse(err, X.Bs)
    if q > 1:
        b = float(X.Bs[i, j])
        _fail("D3.1", impl, case, f"entry differs from the exact cotan Laplacian by {q:.3g} x "
              f"the bound {b:.3g}", element=(i, j), expected=float(X.Ls[i, j]),
              observed=float(A[i, j]), bound=b)


@prop("T3.6", "f^T L f / 2 equals the Dirichlet energy 1/2 integral |grad f|^2 of the piecewise "
      "linear interpolant (computed exactly from per-face gradients)",
      needs={"cotan_laplacian"}, strategy=lambda: with_functions(any_meshes(isolated=True)))
def energy_of_the_interpolant(impl, case: Example):
    A = _dense(impl, case, "T3.6")
    X = Exact.of(case)
    f = np.array([float(x) for x in case.values])
    q = float(f @ (A @ f)) / 2
    exact = float(dirichlet_energy_pl(X.surface, X.restrict(case.values)))
    af = np.abs(f)
    bound = 0.5 * af @ (X.B + gamma(2 * X.n + 2) * np.abs(A)) @ af + eps() * abs(exact)
    err = abs(q - exact)
    r = _record("T3.6", err, bound)
    if r > 1:
        _fail("T3.6", impl, case, f"f^T L f / 2 differs from the gradient energy by {r:.3g} x the "
              f"bound {bound:.3g}", element=f"f = {[str(x) for x in case.values]}",
              expected=exact, observed=q, bound=bound)


@prop("T3.1 / R3.2", "grad E = L f: phi . (L f) equals the exact derivative at t = 0 of "
      "E(f + t phi), E the piecewise linear Dirichlet energy",
      needs={"cotan_laplacian"}, strategy=lambda: with_functions(any_meshes(isolated=True)))
def gradient_of_the_energy(impl, case: Example):
    A = _dense(impl, case, "T3.1 / R3.2")
    X = Exact.of(case)
    f, phi = list(case.values), list(case.second)
    exact = float(directional_derivative(lambda g: dirichlet_energy_pl(X.surface, g),
                                         X.restrict(f), X.restrict(phi)))
    ff, pf = np.array([float(x) for x in f]), np.array([float(x) for x in phi])
    got = float(pf @ (A @ ff))
    bound = np.abs(pf) @ (X.B + gamma(2 * X.n + 2) * np.abs(A)) @ np.abs(ff) + eps() * abs(exact)
    r = _record("T3.1 / R3.2", abs(got - exact), bound)
    if r > 1:
        _fail("T3.1 / R3.2", impl, case, f"phi . (L f) is not dE(f + t phi)/dt at 0 ({r:.3g} x "
              "the bound)", expected=exact, observed=got, bound=bound)


def _eig_tol(X: Exact, A) -> float:
    """Weyl: |lambda(A) - lambda(L)| <= ||A - L||_2 <= ||B||_F; eigvalsh adds ~ n eps() ||A||_F."""
    return float(np.linalg.norm(X.B) + gamma(4 * X.n) * np.linalg.norm(A))


@prop("R3.3", "with negative cotan weights, L is still positive semidefinite and L restricted to "
      "the vertices off a nonempty V0 is positive definite (the Dirichlet problem is uniquely solvable)",
      needs={"cotan_laplacian"}, strategy=lambda: with_boundary(obtuse_meshes()))
def negative_weights_keep_the_energy_positive(impl, case: Example):
    A = _dense(impl, case, "R3.3")
    X = Exact.of(case)
    tol = _eig_tol(X, A)
    lam = float(np.linalg.eigvalsh((A + A.T) / 2)[0])
    _record("R3.3", max(-lam, 0.0), tol)
    if lam < -tol:
        _fail("R3.3", impl, case, "L has a negative eigenvalue: the Dirichlet energy is not "
              "positive semidefinite", expected=f">= {-tol:.3g}", observed=lam)
    I = [v for v in range(X.n) if v not in set(case.boundary)]
    if I:
        AII = A[np.ix_(I, I)]
        lam_i = float(np.linalg.eigvalsh((AII + AII.T) / 2)[0])
        if lam_i <= tol:
            _fail("R3.3", impl, case, "L restricted to the vertices off V0 is not positive "
                  f"definite: the Dirichlet problem is not uniquely solvable (V0 = {list(case.boundary)})",
                  expected=f"> {tol:.3g}", observed=lam_i)


@prop("C3.3", "Liouville: on a mesh of c components (an isolated vertex is one) with positive weights, L has exactly c "
      "eigenvalues within the bound of 0 and kills each component's indicator",
      needs={"cotan_laplacian"}, strategy=lambda: with_isolated(acute_meshes(max_components=3)))
def harmonic_functions_are_locally_constant(impl, case: Example):
    A = _dense(impl, case, "C3.3")
    X = Exact.of(case)
    tol = _eig_tol(X, A)
    comps = X.components()
    lam = np.linalg.eigvalsh((A + A.T) / 2)
    small = int(np.sum(np.abs(lam) <= tol))
    _record("C3.3", np.abs(lam[:len(comps)]), tol)
    for comp in comps:
        ind = np.zeros(X.n)
        ind[comp] = 1
        res = np.abs(A @ ind)
        (i,), r = _worst(res, X.residual_bound(A, ind))
        if r > 1:
            _fail("C3.3", impl, case, f"the indicator of a component is not harmonic ({r:.3g} x "
                  "the bound)", element=f"vertex {i}", expected=0.0, observed=float((A @ ind)[i]))
    if small != len(comps):
        _fail("C3.3", impl, case, "kernel dimension differs from the number of components",
              expected=len(comps), observed=f"{small} eigenvalues within {tol:.3g} of 0: "
              f"{lam[:len(comps) + 1].tolist()}")


def _solve(A, V0, c):
    """The Dirichlet solution with the implementation's matrix (dense LU): ``c`` (values,
    or positions n x k) kept on V0, ``A u = 0`` solved at the others; returns (u, others)."""
    n = A.shape[0]
    I = [v for v in range(n) if v not in set(V0)]
    u = np.array(c, dtype=float).copy()
    if I:
        B0 = list(V0)
        u[I] = np.linalg.solve(A[np.ix_(I, I)], -A[np.ix_(I, B0)] @ u[B0])
    return u, I


def _dirichlet_solutions(impl, case: Example, pid: str):
    """The implementation's solutions of the case's Dirichlet problem (V0 = case.boundary,
    values case.values there), one per route it has: its matrix (``cotan_laplacian``,
    solved here by dense LU) and its own solver (``solve_dirichlet``).  Yields (route,
    X, u, I, M, r): I the unknowns, M a float matrix within the entry bounds of the exact
    L (the implementation's, or the exact L's float view for its solver), r per row the
    bound on |(L u)(i)| of a backward-stable solve with a matrix within those bounds."""
    X = Exact.of(case)
    V0 = list(case.boundary)
    c = np.array([float(x) for x in case.values])
    if "cotan_laplacian" in capabilities(impl):
        A = _dense(impl, case, pid)
        u, I = _solve(A, V0, c)
        yield "cotan_laplacian", X, u, I, A, X.residual_bound(A, u)
    if "solve_dirichlet" in capabilities(impl):
        V, F = case.arrays()
        route = "solve_dirichlet"
        u = np.asarray(impl.solve_dirichlet(V, F, np.array(V0, dtype=np.int64), c[V0]),
                       dtype=np.float64)
        if u.shape != (case.n,):
            _fail(pid, impl, case, f"{route}: the solution has shape {u.shape}",
                  expected=(case.n,), observed=u.shape)
        if not np.all(np.isfinite(u)):
            i = int(np.argmax(~np.isfinite(u)))
            _fail(pid, impl, case, f"{route}: the solution is not finite",
                  element=f"vertex {i}", observed=float(u[i]))
        # the boundary values are given: a solver keeps them (a penalty method does not)
        off = np.abs(u[V0] - c[V0])
        k = int(np.argmax(off)) if len(V0) else 0
        if len(V0) and off[k] > eps() * abs(c[V0][k]):
            _fail(pid, impl, case, f"{route}: the solution does not take the given value on "
                  "the boundary set", element=f"vertex {V0[k]}", expected=float(c[V0][k]),
                  observed=float(u[V0][k]), bound=eps() * abs(c[V0][k]))
        I = [v for v in range(case.n) if v not in set(V0)]
        yield route, X, u, I, X.Lf, X.own_route_bound(u)


@prop("T3.2", "maximum principle: with positive weights, the solution of the Dirichlet problem "
      "(the implementation's L, and its own solver) takes its max and min on V0, within the "
      "propagated bound", needs_any={"cotan_laplacian", "solve_dirichlet"},
      strategy=lambda: with_boundary(acute_meshes()))
def maximum_principle(impl, case: Example):
    V0 = list(case.boundary)
    c = np.array([float(x) for x in case.values])
    for route, X, u, I, A, res in _dirichlet_solutions(impl, case, "T3.2"):
        if not I:
            return
        # L_exact,II (u - u*) = r with |r| <= residual bound; ||L_II^-1||_inf from the computed inverse
        inv_norm = float(np.abs(np.linalg.inv(A[np.ix_(I, I)])).sum(axis=1).max())
        tol = 2 * inv_norm * float(res[I].max())
        hi, lo = float(c[V0].max()), float(c[V0].min())
        excess = max(float(u[I].max()) - hi, lo - float(u[I].min()), 0.0)
        r = _record("T3.2", excess, tol)
        if r > 1:
            i = I[int(np.argmax(np.maximum(u[I] - hi, lo - u[I])))]
            _fail("T3.2", impl, case, f"{route}: a harmonic function leaves [min, max] of its "
                  "boundary values", element=f"vertex {i}, V0 = {V0}",
                  expected=f"in [{lo}, {hi}] +- {tol:.3g}", observed=float(u[i]))


@prop("C3.4 / T3.5", "the Dirichlet solution (the implementation's L, and its own solver) is "
      "the minimiser of the exact piecewise linear energy: its exact gradient vanishes off V0 "
      "and E(u + phi) >= E(u)", needs_any={"cotan_laplacian", "solve_dirichlet"},
      strategy=lambda: with_boundary(st.one_of(acute_meshes(), planar_meshes(), jittered_grids())))
def dirichlet_solution_minimises_the_energy(impl, case: Example):
    V0 = list(case.boundary)
    for route, X, u, I, _, res in _dirichlet_solutions(impl, case, "C3.4 / T3.5"):
        if not I:
            return
        ue = [Fraction(float(x)) for x in u]
        rb = 4 * res
        errs, bounds = [], []
        for i in I:
            e = [Fraction(0)] * X.n
            e[i] = Fraction(1)
            g = float(dirichlet_inner_product_pl(X.surface, ue, e))     # dE/du(i), exact
            errs.append(abs(g))
            bounds.append(rb[i])
            if abs(g) > rb[i]:
                _fail("C3.4 / T3.5", impl, case, f"{route}: the solution is not a critical "
                      "point of the energy", element=f"vertex {i}, V0 = {V0}",
                      expected=f"0 +- {rb[i]:.3g}", observed=g)
        _record("C3.4 / T3.5", errs, bounds)
        phi = [Fraction(0) if v in set(V0) else x for v, x in enumerate(case.second)]
        gain = float(dirichlet_energy_pl(X.surface, [a + b for a, b in zip(ue, phi)])
                     - dirichlet_energy_pl(X.surface, ue))
        slack = float(sum(abs(float(p)) * b for p, b in zip(phi, rb)))
        if gain < -slack:
            _fail("C3.4 / T3.5", impl, case, f"{route}: a perturbation vanishing on V0 lowers "
                  "the energy", element=f"phi = {[str(x) for x in phi]}",
                  expected=f">= {-slack:.3g}", observed=gain)


@prop("P3.10", "positive weights, u harmonic at i => u(i) in the convex hull of its neighbours: "
      "no direction d has d.u(i) > max_j d.u(j) beyond the bound",
      needs={"cotan_laplacian"}, strategy=lambda: with_functions(acute_meshes()))
def harmonic_value_in_convex_hull(impl, case: Example):
    A = _dense(impl, case, "P3.10")
    X = Exact.of(case)
    vals = np.array([float(x) for x in case.values])
    sec = np.array([float(x) for x in case.second])
    U = np.stack([vals, sec, vals * sec], axis=1)             # a map to R^3
    dirs = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 0], [1, -1, 1]], dtype=float)
    dirs = np.vstack([dirs, -dirs])
    worst = 0.0
    for i in range(X.n):
        nb = [j for j in range(X.n) if j != i and X.adjacent[i, j]]
        if not nb or A[i, i] == 0:
            continue
        ui = -(A[i, nb] @ U[nb]) / A[i, i]
        # |u(i) - exact| per coordinate: entry errors and rounding, divided by the pivot
        err = ((X.B[i, nb] + gamma(X.n + 2) * np.abs(A[i, nb])) @ np.abs(U[nb])
               + X.B[i, i] * np.abs(ui)) / abs(A[i, i])
        for d in dirs:
            excess = float(d @ ui - np.max(U[nb] @ d))
            tol = float(np.abs(d) @ err) + gamma(4) * float(np.abs(d) @ np.abs(ui))
            worst = max(worst, excess / tol if tol > 0 else (np.inf if excess > 0 else 0))
            if excess > tol:
                _fail("P3.10", impl, case, "the value harmonic at a vertex lies outside the convex "
                      "hull of its neighbours' values", element=f"vertex {i}, direction {d.tolist()}",
                      expected=f"<= {float(np.max(U[nb] @ d))} + {tol:.3g}", observed=float(d @ ui))
    ERROR_RATIOS["P3.10"] = max(ERROR_RATIOS.get("P3.10", 0.0), max(worst, 0.0))


@prop("E3.12", "nu(ij) >= 0 iff alpha_ij + alpha_ji <= pi: the sign of each off-diagonal entry "
      "agrees with the exact angle sum (edges whose weight is within the bound of 0 are undecided "
      "and must be, when the angle sum is exactly pi)",
      needs={"cotan_laplacian"}, strategy=lambda: st.one_of(obtuse_meshes(), planar_meshes()))
def weight_sign_by_opposite_angles(impl, case: Example):
    A = _sparse(impl, case, "E3.12")
    X = Exact.of(case)
    t = X.triangulation
    ERROR_RATIOS.setdefault("E3.12", 0.0)
    tie = None
    pairs = [[X.keep[v] for v in t.edge_vertices(e)] for e in range(t.n_edges)]
    I, J = (np.array([p[k] for p in pairs], dtype=np.int64) for k in (0, 1))
    weights, bounds = -_at(A, I, J), _at(X.Bs, I, J)
    for e in range(t.n_edges):
        i, j = pairs[e]
        s = weight_sign_by_angles(X.surface, e)
        w, b = float(weights[e]), float(bounds[e])
        if s == 0:
            _record("E3.12", abs(w), b)                   # an exactly zero weight
        if s == 0 and abs(w) > b:
            _fail("E3.12", impl, case, "the opposite angles sum to pi exactly but the weight is "
                  "not 0 within the bound", element=(i, j), expected=0.0, observed=w, bound=b)
        if s != 0 and abs(w) > b and (w > 0) != (s > 0):
            _fail("E3.12", impl, case, "the weight's sign contradicts the opposite angle sum",
                  element=(i, j), expected="positive (angle sum < pi)" if s > 0 else
                  "negative (angle sum > pi)", observed=w)
        if s == 0 and w != 0 and tie is None:             # exact tie, decided by rounding
            tie = (i, j, w, b)
    if tie is not None:
        i, j, w, b = tie
        raise TieDisagreement("E3.12", impl, "the opposite angles sum to pi exactly (weight 0) "
                              "but the weight has a sign, within the bound", mesh=case.mesh,
                              element=(i, j), expected=0.0, observed=w, bound=b)


@prop("L3.8", "on one triangle, (L V)(i) equals the area gradient 1/2 n x (v_k - v_j) computed "
      "directly (no cotangent)", needs={"cotan_laplacian"}, strategy=single_triangles)
def area_gradient_of_a_triangle(impl, case: Example):
    _area_gradient_check("L3.8", impl, case)


def _area_gradient_check(pid, impl, case, route: str = "cotan_laplacian"):
    """(L V)(i) of the implementation's matrix, or its own ``area_gradient``, against the
    exact area gradient (T3.9, L3.8), within :meth:`Exact.residual_bound` of its matrix,
    or :meth:`Exact.area_gradient_bound` for its own gradient."""
    X = Exact.of(case)
    P = np.array([[float(x) for x in p] for p in case.positions])
    exact, bound = X.area_gradient_bound(P)
    if route == "cotan_laplacian":
        A = _sparse(impl, case, pid)
        got = A @ P
        bound = X.residual_bound(A, P) + eps() * np.abs(exact)
    else:
        V, F = case.arrays()
        got = np.asarray(impl.area_gradient(V, F), dtype=np.float64)
        if got.shape != P.shape:
            _fail(pid, impl, case, f"area_gradient has shape {got.shape}", expected=P.shape,
                  observed=got.shape)
    err = np.abs(got - exact)
    err[~np.isfinite(got)] = np.inf
    _record(pid, err, bound)
    (i, k), r = _worst(err, bound)
    if r > 1:
        planar = all(p[2] == case.positions[0][2] for p in case.positions)
        what = " (linear precision fails: a planar interior vertex)" if planar and \
            i in X.keep and not X.triangulation.is_boundary_vertex(X.keep.index(i)) else ""
        label = "(L V)(i)" if route == "cotan_laplacian" else "area_gradient"
        _fail(pid, impl, case, f"{label} is not the area gradient ({r:.3g} x the bound){what}",
              element=f"vertex {i}, coordinate {k}", expected=exact[i].tolist(),
              observed=got[i].tolist())


@prop("T3.9", "area as Dirichlet energy: sum_k x_k^T L x_k / 2 = A(S) and L V = grad A (so L V = 0 "
      "at interior vertices of a planar mesh: linear precision); the implementation's own "
      "area_gradient equals grad A too", needs_any={"cotan_laplacian", "area_gradient"},
      strategy=lambda: st.one_of(planar_meshes(), jittered_grids(), closed_meshes(), obtuse_meshes(),
                                 surface_meshes(isolated=True)))
def area_as_dirichlet_energy(impl, case: Example):
    caps = capabilities(impl)
    if "cotan_laplacian" in caps:
        A = _sparse(impl, case, "T3.9")
        X = Exact.of(case)
        P = np.array([[float(x) for x in p] for p in case.positions])
        energy = float(sum(P[:, k] @ (A @ P[:, k]) for k in range(3))) / 2
        area, area_err = total_area_view(X.metric)
        aP, absA = np.abs(P), abs(A)
        bound = 0.5 * sum(aP[:, k] @ (X.Bs @ aP[:, k]) + gamma(2 * X.n + 6) * (aP[:, k] @ (absA @ aP[:, k]))
                          for k in range(3)) + eps() * area + area_err
        r = _record("T3.9", abs(energy - area), bound)
        if r > 1:
            _fail("T3.9", impl, case, f"sum_k E(x_k) is not the area ({r:.3g} x the bound)",
                  expected=area, observed=energy, bound=bound)
        _area_gradient_check("T3.9", impl, case)
    if "area_gradient" in caps:
        _area_gradient_check("T3.9", impl, case, route="area_gradient")


@prop("A3.6", "one minimal surface step (solve L_S x = 0 off the boundary with the "
      "implementation's L) does not increase the area, within the propagated bound",
      needs={"cotan_laplacian"},
      strategy=lambda: with_boundary(st.one_of(jittered_grids(), obtuse_fans()), mesh_boundary=True))
def minimal_surface_step_decreases_area(impl, case: Example):
    A = _dense(impl, case, "A3.6")
    X = Exact.of(case)
    P = np.array([[float(x) for x in p] for p in case.positions])
    U, I = _solve(A, list(case.boundary), P)
    if not I:
        return
    AII = A[np.ix_(I, I)]
    before = float(X.metric.total_area())
    new = PolyhedralSurface(X.triangulation, [[Fraction(float(x)) for x in p] for p in U])
    try:
        after = float(new.metric().total_area())
    except ValueError:                       # a face collapsed: area of the others, exactly
        after = float(sum(_face_areas(new), Fraction(0)))
    # E_S(u) - E_S(u*) = 1/2 r^T L_II^-1 r <= |r|^2 / (2 lambda_min), r the exact residual
    lam = float(np.linalg.eigvalsh((AII + AII.T) / 2)[0])
    r = X.residual_bound(A, U)[I]
    tol = (float(np.sum(r ** 2)) / lam if lam > 0 else np.inf) + 4 * eps() * before
    ratio = _record("A3.6", max(after - before, 0.0), tol)
    if ratio > 1:
        _fail("A3.6", impl, case, "the area increased in one minimal surface step",
              expected=f"<= {before} + {tol:.3g}", observed=after)


def _face_areas(surface):
    from ddg_oracle.reference.exact import sqrt
    p = surface.positions
    for a, b, c in surface.triangulation.faces:
        u = [y - x for x, y in zip(p[a], p[b])]
        v = [y - x for x, y in zip(p[a], p[c])]
        uv = sum(x * y for x, y in zip(u, v))
        yield sqrt(sum(x * x for x in u) * sum(y * y for y in v) - uv * uv) / 2


def vertex_area_bounds(X: Exact) -> tuple[np.ndarray, np.ndarray]:
    """(n,) bounds on the error of each vertex's mixed Voronoi area and of its barycentric
    area: the corner cotangent bounds beta times the adjacent squared sides / 8, their
    rounding, and K_COT eps rho_f A_f for the face area itself."""
    if "_area_bounds" in X.__dict__:          # once per Exact (its key has eps())
        return X.__dict__["_area_bounds"]
    t, m = X.triangulation, X.metric
    vb = np.zeros(X.n)      # bound of the Voronoi area of each vertex
    bb = np.zeros(X.n)      # of the barycentric one
    for f, face in enumerate(t.faces):
        a = float(m.area(f))
        l0, l1, l2 = (float(x) for x in m.face_squared_lengths(f))
        adj = ((l0, l2, 2, 1), (l0, l1, 2, 0), (l1, l2, 0, 1))    # sides at corner, their opposite corners
        for c in range(3):
            la, lb, ca, cb = adj[c]
            # either rule may be taken near a right angle; they agree there, so bound both
            vor = (la * X.beta[f, ca] + lb * X.beta[f, cb]
                   + 8 * eps() * (la * abs(X.cot[f, ca]) + lb * abs(X.cot[f, cb]))) / 8
            v = X.keep[face[c]]
            vb[v] += vor + K_COT * eps() * X.rho[f] * a
            bb[v] += K_COT * eps() * X.rho[f] * a / 3
    X.__dict__["_area_bounds"] = vb, bb
    return vb, bb


@prop("L3.7", "mass matrices: mixed Voronoi areas (the circumcentric split of L3.7 on non-obtuse "
      "faces) and barycentric areas agree with the exact ones and sum to the total area",
      needs={"vertex_areas_voronoi"},
      strategy=lambda: st.one_of(obtuse_meshes(), planar_meshes(), jittered_grids(), closed_meshes(),
                                 surface_meshes(isolated=True)))
def vertex_areas_sum_to_the_area(impl, case: Example):
    X = Exact.of(case)
    V, F = case.arrays()
    n = X.n
    area, area_err = total_area_view(X.metric)
    vb, bb = vertex_area_bounds(X)
    checks = [("vertex_areas_voronoi", vb)]
    if callable(getattr(impl, "vertex_areas_barycentric", None)):
        checks.append(("vertex_areas_barycentric", bb))
    for name, bound in checks:
        got = np.asarray(getattr(impl, name)(V, F), dtype=float).reshape(-1)
        if got.shape != (n,):
            _fail("L3.7", impl, case, f"{name} has the wrong shape", expected=(n,), observed=got.shape)
        exact = np.array([ISOLATED_VERTEX[name]] * n)
        exact[X.keep] = X.vertex_areas(name)
        err = np.abs(got - exact)
        _record("L3.7", err, bound)
        (i,), r = _worst(err, bound)
        if r > 1:
            _fail("L3.7", impl, case, f"{name} differs from the exact area ({r:.3g} x the bound)",
                  element=f"vertex {i}", expected=float(exact[i]), observed=float(got[i]),
                  bound=bound[i])
        total_bound = float(bound.sum()) + gamma(n) * float(np.abs(got).sum()) + area_err
        if abs(float(got.sum()) - area) > total_bound:
            _fail("L3.7", impl, case, f"{name} does not sum to the total area",
                  expected=area, observed=float(got.sum()))
