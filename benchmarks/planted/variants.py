"""One-line variants of :class:`~.numpy_all.NumpyAll`: the planted-bug benchmark (issue 40, item 5).

Each variant is a subclass replacing one step of NumpyAll (or one short method) with the
line a developer actually writes: its docstring says what the line does wrong, ``planted``
names the protocol methods it changes (``python -m benchmarks catch`` checks it on the
properties that call them), ``bug_class`` says where the bug hides (the classes of issue 40:
topology, far from the origin, scale, needles and caps, Dirichlet boundary sets, near ties,
flip formulas; or a plain slip: an index, a sign, a factor, float32), and ``finding`` names
the entry of docs/findings.md where a real library had it (as a bug, or as its documented
convention, which is a bug in an implementation claiming the reference's conventions).

    ddg-oracle check --impl benchmarks.planted.variants:GenusIgnoresBoundary --only R1.6

Every variant differs from NumpyAll on a small hand-made mesh (tests/test_planted_variants.py).
"""

from __future__ import annotations

import math
import sys

import numpy as np
import scipy.sparse as sp

from .numpy_all import EPS, NumpyAll, _f, _v, correct, directed_twins, sides, squared_lengths, twins


class Variant(NumpyAll):
    """A one-line variant: ``planted`` (the protocol methods it changes), ``bug_class`` (where
    the bug hides), ``finding`` (the docs/findings.md entry of a library that had it); its
    name in reports is its class name in kebab case."""

    planted: tuple = ()
    bug_class: str = ""
    finding: str | None = None
    #: why the variant is not a bug under the protocol's contract (its error within the
    #: derived bound by design, as honest float methods have it; or an input outside the
    #: protocol's domain), else None: the catch benchmark lists it apart, and a test keeps
    #: it passing (tests/test_planted_variants.py)
    admitted: str | None = None

    def __init_subclass__(cls, **kw):
        super().__init_subclass__(**kw)
        cls.name = "".join("-" + ch.lower() if ch.isupper() else ch for ch in cls.__name__).lstrip("-")


# --- chapter 1: topology ----------------------------------------------------------------------


class ChiDropsIsolated(Variant):
    """V of V - E + F counted as the vertices the faces use (np.unique(F)), as a loader that
    drops unreferenced vertices: chi is one short per vertex used by no face."""
    planted, bug_class = ("euler_characteristic",), "isolated vertices"

    @staticmethod
    def _chi_vertices(V, F):
        return len(np.unique(F))


class ChiEdgesFromHalfedges(Variant):
    """E = (3F + B) / 2 with B the halfedges i -> j whose j -> i is missing: right on a
    consistently oriented mesh; on a Möbius strip (or with a reversed face) an interior edge
    listed twice the same way counts as two boundary edges."""
    planted, bug_class = ("euler_characteristic",), "orientation"

    @staticmethod
    def _chi_edges(F):
        return (3 * len(F) + int((directed_twins(F) < 0).sum())) // 2


class BoundaryLoopsByMissingTwin(Variant):
    """Boundary edges found as halfedges without a reversed twin: an interior edge whose two
    faces list it the same way (Möbius strip, reversed face) becomes two boundary edges."""
    planted, bug_class = ("boundary_loops",), "orientation"

    @staticmethod
    def _boundary_edges(F):
        return sides(F).reshape(-1, 2)[directed_twins(F).reshape(-1) < 0]


class BoundaryLoopsFollowFaceOrientation(Variant):
    """The boundary walk goes from i to j only along a boundary edge that its face lists as
    i -> j: on a Möbius strip the direction flips once and the loop breaks into pieces."""
    planted, bug_class, finding = ("boundary_loops",), "orientation", "F-libigl-1"

    @staticmethod
    def _boundary_steps(B):
        return B


class IsOrientableByDirectedHalfedges(Variant):
    """Orientable iff no halfedge i -> j is listed twice: true of a consistently oriented
    mesh, false of an orientable surface whose faces are listed inconsistently."""
    planted, bug_class = ("is_orientable",), "orientation"

    def is_orientable(self, V, F):
        return len(np.unique(sides(_f(F)).reshape(-1, 2), axis=0)) == 3 * len(_f(F))


class IsOrientableFirstComponentOnly(Variant):
    """Propagates an orientation from face 0 only: the faces of another component are never
    reached, so a non-orientable second component goes unseen."""
    planted, bug_class = ("is_orientable",), "components"

    @staticmethod
    def _orientation_starts(F):
        return range(min(1, len(F)))


class GenusIgnoresBoundary(Variant):
    """g = (2 - chi) / 2, forgetting the boundary loops (chi = 2 - 2g - k)."""
    planted, bug_class = ("genus",), "boundary"

    @staticmethod
    def _genus_formula(chi, k, orientable):
        return (2 - chi) // 2 if orientable else 2 - chi


class GenusAsIfOrientable(Variant):
    """g = (2 - chi - k) / 2 always: a non-orientable surface's crosscaps counted as handles."""
    planted, bug_class = ("genus",), "non-orientable"

    @staticmethod
    def _genus_formula(chi, k, orientable):
        return (2 - chi - k) // 2


class GenusCountsIsolated(Variant):
    """The genus from the Euler characteristic of all of V: a vertex used by no face adds 1
    to chi, and the genus drops by 1/2 (a crosscap by 1)."""
    planted, bug_class = ("genus",), "isolated vertices"

    @staticmethod
    def _surface_chi(V, F):
        return correct().euler_characteristic(V, F)


# --- chapter 2: curvature ---------------------------------------------------------------------


class CornerAnglesPiMinusTwo(Variant):
    """Two angles by arccos of the unit edge vectors' dot product and the third as pi minus
    them: the error of both arccos (about eps / sin of each) lands on the third angle."""
    planted, bug_class, finding = ("corner_angles",), "needles and caps", "F-trimesh-4"
    admitted = ("within D2.6's bound: its corner bound has the side-length term C_LENGTHS eps "
                "S_f for every corner of a face (F-trimesh-4: a precision limit)")

    @staticmethod
    def _angle(a, b):
        return np.arccos(np.clip((a * b).sum(1) / (np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1)),
                                 -1, 1))

    def corner_angles(self, V, F):
        out = NumpyAll.corner_angles(self, V, F)
        out[:, 2] = np.pi - out[:, 0] - out[:, 1]
        return out


class CornerAnglesUnitizeThreshold(Variant):
    """Edge vectors unit-ized with an absolute threshold (a vector shorter than 1e-13 becomes
    0), the angle as arccos of the unit vectors' dot product: on a mesh scaled below about
    1e-13 every angle is pi/2."""
    planted, bug_class, finding = ("corner_angles",), "scale", "F-trimesh-3"

    @staticmethod
    def _angle(a, b):
        a, b = (x / np.where(n < 1e-13, np.inf, n)[:, None]
                for x, n in ((a, np.linalg.norm(a, axis=1)), (b, np.linalg.norm(b, axis=1))))
        return np.arccos(np.clip((a * b).sum(1), -1, 1))


class DefectsTwoPiAtBoundary(Variant):
    """2 pi - angle sum at every vertex, the boundary included (not the turning angle)."""
    planted, bug_class, finding = ("angle_defects",), "boundary", "F-libigl-2"

    @staticmethod
    def _defects(V, F, sums, boundary):
        return 2 * np.pi - sums


class DefectsZeroAtBoundary(Variant):
    """Angle defect 0 at boundary vertices (curvature 'undefined' there)."""
    planted, bug_class, finding = ("angle_defects",), "boundary", "F-gpytoolbox-1"

    @staticmethod
    def _defects(V, F, sums, boundary):
        return np.where(boundary, 0.0, 2 * np.pi - sums)


class DefectsFloat32Sums(Variant):
    """Angle sums accumulated in a float32 array."""
    planted, bug_class, finding = ("angle_defects",), "float32", "F-pymeshlab-6"

    @staticmethod
    def _angle_sums(n, F, angles):
        sums = np.zeros(n, dtype=np.float32)
        np.add.at(sums, F.reshape(-1), angles.reshape(-1).astype(np.float32))
        return sums.astype(np.float64)


class DefectsAbsoluteAreaThreshold(Variant):
    """K = 0 where the vertex's mixed area is below 2.2e-16 (an absolute area compared with
    machine epsilon): every vertex of a mesh scaled below about 1e-8, and isolated ones."""
    planted, bug_class, finding = ("angle_defects",), "scale", "F-pymeshlab-4"

    @staticmethod
    def _defects(V, F, sums, boundary):
        return np.where(correct().vertex_areas_voronoi(V, F) <= 2.2e-16, 0.0,
                        np.where(boundary, np.pi, 2 * np.pi) - sums)


class DefectsDropNeedleFaces(Variant):
    """Faces whose shortest edge is below 1e-8 of their longest are left out of the angle
    sums (a relative 'degenerate face' test)."""
    planted, bug_class, finding = ("angle_defects",), "needles and caps", "F-pymeshlab-8"

    @staticmethod
    def _summed_faces(V, F):
        l2 = squared_lengths(V, F)
        return l2.min(axis=1) >= 1e-16 * l2.max(axis=1)


class DefectsDropFarFaces(Variant):
    """Faces with |cross| below 1e-12 times the largest squared coordinate are left out of
    the sums: a 'degenerate face' threshold scaled by the bounding box, not by the face, so
    far from the origin every face is degenerate."""
    planted, bug_class = ("angle_defects",), "far from the origin"

    @staticmethod
    def _summed_faces(V, F):
        X = V[F]
        cross = np.linalg.norm(np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]), axis=1)
        return cross > 1e-12 * float((V * V).sum(axis=1).max())


class MeanCurvatureUnsigned(Variant):
    """The dihedral angle as arccos of the normals' dot product: never negative (a saddle
    edge gets theta > 0), and imprecise at nearly flat edges."""
    planted, bug_class, finding = ("edge_mean_curvature",), "sign", "F-gpytoolbox-2"

    @staticmethod
    def _dihedral(nf, ng, t):
        return math.acos(max(-1.0, min(1.0, float(nf @ ng))))


class MeanCurvatureWithoutHalf(Variant):
    """H(e) = theta(e) l(e), without the 1/2."""
    planted, bug_class = ("edge_mean_curvature",), "factor"

    @staticmethod
    def _edge_value(theta, length):
        return theta * length


class MeanCurvatureAbsoluteNormalGuard(Variant):
    """Face normals unit-ized with an absolute threshold: a cross product below 1e-12 (any
    face of a mesh scaled by about 2^-20) gives a zero normal, hence theta = 0."""
    planted, bug_class, finding = ("edge_mean_curvature",), "scale", "F-trimesh-2"

    @staticmethod
    def _face_normals(X):
        C = np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0])
        n = np.linalg.norm(C, axis=1)
        return C / np.where(n < 1e-12, np.inf, n)[:, None]


class AreaFloat32Sum(Variant):
    """The total area summed in float32."""
    planted, bug_class, finding = ("area",), "float32", "F-pymeshlab-5"

    def area(self, V, F):
        return 0.5 * float(self._double_areas(_v(V), _f(F)).astype(np.float32).sum())


class AreaAbsoluteThreshold(Variant):
    """'Degenerate' faces, |cross| below 1e-12, left out of the total area: every face of a
    mesh scaled below about 1e-6."""
    planted, bug_class = ("area",), "scale"

    @staticmethod
    def _double_areas(V, F):
        d = NumpyAll._double_areas(V, F)
        return np.where(d < 1e-12, 0.0, d)


class AreaShoelace(Variant):
    """Twice a face's area as |v0 x v1 + v1 x v2 + v2 x v0| (the polygon formula from the
    positions themselves): far from the origin the three products cancel."""
    planted, bug_class = ("area",), "far from the origin"

    @staticmethod
    def _double_areas(V, F):
        X = V[F]
        return np.linalg.norm(np.cross(X[:, 0], X[:, 1]) + np.cross(X[:, 1], X[:, 2])
                              + np.cross(X[:, 2], X[:, 0]), axis=1)


class AreaTextbookHeron(Variant):
    """Face areas by Heron's formula s(s-a)(s-b)(s-c) from the edge lengths: a cap (or a
    needle) loses its area in the cancellation."""
    planted, bug_class, finding = ("area",), "needles and caps, precision", "F-libigl-5"
    admitted = ("within the derived bound: areas from the side lengths are admitted (bounds.py: "
                "C_HERON, C_LENGTHS), as every honest method from lengths has them (F-libigl-5)")

    @staticmethod
    def _double_areas(V, F):
        a, b, c = np.sqrt(squared_lengths(V, F)).T
        s = (a + b + c) / 2
        return 2 * np.sqrt(np.maximum(s * (s - a) * (s - b) * (s - c), 0))


# --- chapter 3: Laplacians and mass matrices ------------------------------------------------


class CotanOverwrites(Variant):
    """Weights stored in a dict by (i, j) with `=`, not `+=`: an interior edge keeps the
    cotangent of one of its two faces."""
    planted, bug_class = ("cotan_laplacian",), "index"

    @staticmethod
    def _assemble(n, rows, cols, vals):
        d = dict(zip(zip(rows.tolist(), cols.tolist()), vals.tolist()))
        return sp.csr_matrix((list(d.values()), tuple(np.array(list(d)).reshape(-1, 2).T)),
                             shape=(n, n))


class CotanFloat32(Variant):
    """The weight matrix assembled in float32."""
    planted, bug_class, finding = ("cotan_laplacian",), "float32", "F-pymeshlab-6"

    @staticmethod
    def _assemble(n, rows, cols, vals):
        return sp.csr_matrix((vals.astype(np.float32), (rows, cols)), shape=(n, n))


class CotanDiagonalOfAbs(Variant):
    """The diagonal as the sum of |w| (to keep L 'positive'): rows with a negative weight
    no longer sum to 0."""
    planted, bug_class = ("cotan_laplacian",), "sign"

    @staticmethod
    def _graph_laplacian(W):
        return (sp.diags(np.asarray(abs(W).sum(axis=1)).ravel()) - W).tocsr()


class CotanClampsNegative(Variant):
    """Negative cotan weights clamped to 0 (to keep an M-matrix): no longer the cotan
    Laplacian of a mesh with obtuse angles."""
    planted, bug_class = ("cotan_laplacian",), "sign"

    @staticmethod
    def _graph_laplacian(W):
        return NumpyAll._graph_laplacian(W.maximum(0))


class CotanBoundingBoxGuard(Variant):
    """cot = dot / max(|cross|, 1e-12 * (largest coordinate)^2): a guard scaled by the
    bounding box, not by the face; far from the origin every face hits it."""
    planted, bug_class = ("cotan_laplacian",), "far from the origin"

    @staticmethod
    def _cot(pk, pi, pj):
        u, v = pi - pk, pj - pk
        return (u * v).sum(1) / np.maximum(np.linalg.norm(np.cross(u, v), axis=1),
                                           1e-12 * float(np.abs(pk).max()) ** 2)


class CotanFromArccos(Variant):
    """cot = 1 / tan(arccos(cos)), the cosine from the normalized dot product: on a needle
    or a cap the angle, hence the cotangent, loses its digits."""
    planted, bug_class, finding = ("cotan_laplacian",), "needles and caps", "F-openmesh-1"

    @staticmethod
    def _cot(pk, pi, pj):
        u, v = pi - pk, pj - pk
        cos = (u * v).sum(1) / (np.linalg.norm(u, axis=1) * np.linalg.norm(v, axis=1))
        return 1 / np.tan(np.arccos(np.clip(cos, -1, 1)))


class CotanCompactedIsolated(Variant):
    """Computed on the compacted mesh (np.unique(F)) and padded with zero rows at the end:
    after a vertex used by no face, every row belongs to the next vertex."""
    planted, bug_class = ("cotan_laplacian",), "isolated vertices"

    def cotan_laplacian(self, V, F):
        used, inv = np.unique(_f(F), return_inverse=True)
        return sp.block_diag([NumpyAll.cotan_laplacian(self, _v(V)[used], inv.reshape(-1, 3)),
                              sp.csr_matrix((len(V) - len(used),) * 2)]).tocsr()


class CotanMaxValence16(Variant):
    """A one-ring table of fixed width 16 (as C and GPU codes allocate it): weights past a
    vertex's 16th neighbour are dropped (its row; the matrix is no longer symmetric)."""
    planted, bug_class = ("cotan_laplacian",), "high valence"

    @staticmethod
    def _assemble(n, rows, cols, vals):
        W = sp.csr_matrix((vals, (rows, cols)), shape=(n, n))
        W.data[np.arange(W.nnz) - np.repeat(W.indptr[:-1], np.diff(W.indptr)) >= 16] = 0
        return W


class AreaGradientAbsoluteGuard(Variant):
    """Unit normals as C / max(|C|, 1e-12): on a mesh scaled below about 1e-6 the normals,
    hence the gradient, shrink."""
    planted, bug_class = ("area_gradient",), "scale"

    @staticmethod
    def _gradient_normals(C):
        return C / np.maximum(np.linalg.norm(C, axis=1), 1e-12)[:, None]


class AreaGradientUnitless(Variant):
    """The cross product used as the normal without normalizing: each face's gradient
    is 2A times too large."""
    planted, bug_class = ("area_gradient",), "factor"

    @staticmethod
    def _gradient_normals(C):
        return C


class DirichletBoundaryMask(Variant):
    """The boundary values written through a mask (u[mask] = values): they land on the
    boundary vertices in increasing order, not in the order given."""
    planted, bug_class = ("solve_dirichlet",), "Dirichlet boundary order"

    @staticmethod
    def _fix(u, boundary, values):
        mask = np.zeros(len(u), dtype=bool)
        mask[boundary] = True
        u[mask] = values


class DirichletDuplicatedBoundary(Variant):
    """-L_IB c with the boundary as given: a vertex listed twice in the boundary set has its
    column counted twice."""
    planted, bug_class = ("solve_dirichlet",), "Dirichlet boundary order"
    admitted = ("outside the protocol's domain: solve_dirichlet's boundary indices are distinct "
                "(gpytoolbox and LaPy refuse duplicates, libigl crashes on them)")

    @staticmethod
    def _dirichlet_rhs(L_I, u, boundary, fixed):
        return -(L_I[:, boundary] @ u[boundary])


class DirichletInaccurateSolve(Variant):
    """Conjugate gradients stopped at a relative residual of 1e-5 (scipy's default rtol)."""
    planted, bug_class = ("solve_dirichlet",), "inaccurate solve"

    @staticmethod
    def _linear_solve(A, b):
        import scipy.sparse.linalg as sla
        return sla.cg(A, b, rtol=1e-5)[0]


class DirichletRhsSign(Variant):
    """L_II u_I = L_IB c: the known values moved to the right without the minus sign."""
    planted, bug_class = ("solve_dirichlet",), "sign"

    @staticmethod
    def _dirichlet_rhs(L_I, u, boundary, fixed):
        return L_I[:, fixed] @ u[fixed]


class BarycentricCompacted(Variant):
    """Computed on the compacted mesh (np.unique(F)) and padded with zeros at the end: after
    a vertex used by no face, every area belongs to the next vertex."""
    planted, bug_class = ("vertex_areas_barycentric",), "isolated vertices"

    def vertex_areas_barycentric(self, V, F):
        used, inv = np.unique(_f(F), return_inverse=True)
        return np.concatenate([NumpyAll.vertex_areas_barycentric(self, _v(V)[used],
                                                                 inv.reshape(-1, 3)),
                               np.zeros(len(V) - len(used))])


class BarycentricFloat32(Variant):
    """The vertex areas accumulated in a float32 array (a float32 mass matrix)."""
    planted, bug_class, finding = ("vertex_areas_barycentric",), "float32", "F-pymeshlab-5"

    def vertex_areas_barycentric(self, V, F):
        V, F = _v(V), _f(F)
        out = np.zeros(len(V), dtype=np.float32)
        np.add.at(out, F, self._face_thirds(V, F).astype(np.float32)[:, None])
        return out.astype(np.float64)


class BarycentricTextbookHeron(Variant):
    """Face areas by Heron's formula from the edge lengths: a cap loses its area."""
    planted, bug_class, finding = ("vertex_areas_barycentric",), "needles and caps, precision", "F-libigl-5"
    admitted = ("within the derived bound: areas from the side lengths are admitted (bounds.py: "
                "C_HERON, C_LENGTHS), as every honest method from lengths has them (F-libigl-5)")

    @staticmethod
    def _face_thirds(V, F):
        a, b, c = np.sqrt(squared_lengths(V, F)).T
        s = (a + b + c) / 2
        return np.sqrt(np.maximum(s * (s - a) * (s - b) * (s - c), 0)) / 3


class VoronoiHalfToEveryObtuseCorner(Variant):
    """An obtuse face gives A/2 to each of its corners (its three parts sum to 3A/2)."""
    planted, bug_class, finding = ("vertex_areas_voronoi",), "obtuse", "F-cgal-1"

    @staticmethod
    def _obtuse_split(A, obtuse):
        return np.broadcast_to(A[:, None] / 2, obtuse.shape)


class VoronoiWithoutObtuseRule(Variant):
    """The circumcentric split everywhere: an obtuse face's circumcentre lies outside it,
    and its parts are negative."""
    planted, bug_class = ("vertex_areas_voronoi",), "obtuse"

    @staticmethod
    def _obtuse_corners(dots):
        return np.zeros(dots.shape, dtype=bool)


class VoronoiObtuseAbsoluteEpsilon(Variant):
    """A corner is obtuse when its dot product is below -1e-12: on a small mesh no corner
    is, and obtuse faces get the circumcentric split."""
    planted, bug_class = ("vertex_areas_voronoi",), "scale"

    @staticmethod
    def _obtuse_corners(dots):
        return dots < -1e-12


class VoronoiObtuseShareShifted(Variant):
    """A/2 to the corner after the obtuse one (np.roll on the wrong side)."""
    planted, bug_class = ("vertex_areas_voronoi",), "index"

    @staticmethod
    def _obtuse_split(A, obtuse):
        return np.where(np.roll(obtuse, 1, axis=1), A[:, None] / 2, A[:, None] / 4)


# --- chapter 4: Delaunay --------------------------------------------------------------------


class DelaunayTwinByReversedKey(Variant):
    """The other face of the edge i -> j looked up as the face listing j -> i: at a reversed
    face (or a Möbius strip's seam) the edge is taken for a boundary edge, hence Delaunay."""
    planted, bug_class = ("is_locally_delaunay",), "orientation"

    @staticmethod
    def _delaunay_twins(F):
        return directed_twins(F)


class DelaunayTolerance1e6(Variant):
    """cot a + cot b >= -1e-6 (|cot a| + |cot b|) 'for robustness': a near tie up to 1e-6
    relative is called Delaunay."""
    planted, bug_class = ("is_locally_delaunay",), "near ties"

    @staticmethod
    def _delaunay_test(s, a, b):
        return s >= -1e-6 * (np.abs(a) + np.abs(b))


class DelaunayTolerance1e10(Variant):
    """cot a + cot b >= -1e-10 (|cot a| + |cot b|): a near tie up to 1e-10 relative is
    called Delaunay."""
    planted, bug_class = ("is_locally_delaunay",), "near ties"

    @staticmethod
    def _delaunay_test(s, a, b):
        return s >= -1e-10 * (np.abs(a) + np.abs(b))


class DelaunayBoundaryFalse(Variant):
    """Boundary edges flagged not Delaunay (no second angle, so the test 'fails')."""
    planted, bug_class = ("is_locally_delaunay",), "boundary"
    _boundary_flag = False


class DelaunayTwinCornerShifted(Variant):
    """The other face's angle taken at the corner after the one opposite the edge."""
    planted, bug_class = ("is_locally_delaunay",), "index"

    @staticmethod
    def _delaunay_twins(F):
        t = twins(F)
        return np.where(t >= 0, 3 * (t // 3) + (t + 1) % 3, -1)


_INTRINSIC = ("intrinsic_delaunay_triangulation", "intrinsic_delaunay_laplacian")


class IntrinsicFlipLayoutPythagoras(Variant):
    """The two triangles laid out in the plane with the apexes' heights by Pythagoras,
    y = sqrt(b - x^2), not from the area: a face whose apex is near the flipped edge (a cap,
    the faces flips start from) loses its height to the cancellation, and the new diagonal
    with it."""
    planted, bug_class = _INTRINSIC, "flip formula, precision"
    admitted = ("within the derived bound: flips from the side lengths are admitted (bounds.py: "
                "K_COT eps (1 + cot^2) rho), as every intrinsic flip code has them")

    def _flip_length(self, a, b, c, d, e, A1, A2):
        x1, x2 = (e + b - a) / (2 * np.sqrt(e)), (e + c - d) / (2 * np.sqrt(e))
        return (x1 - x2) ** 2 + (np.sqrt(max(b - x1 * x1, 0)) + np.sqrt(max(c - x2 * x2, 0))) ** 2


class IntrinsicTextbookHeron(Variant):
    """The input faces' areas by Heron's formula s(s-a)(s-b)(s-c) from the float lengths, and
    their cotangents from those areas (everything from the edge lengths, as the intrinsic
    codes do): a cap's area, its cotangents and the lengths flipped from them lose their
    digits."""
    planted, bug_class, finding = _INTRINSIC, "flip formula, precision", "F-libigl-7"
    admitted = ("within the derived bound: flips from the side lengths are admitted (bounds.py: "
                "K_COT eps (1 + cot^2) rho), as every intrinsic flip code has them (F-libigl-7)")

    @staticmethod
    def _input_faces(V, F, l2):
        a, b, c = np.sqrt(l2).T
        s = (a + b + c) / 2
        A = np.sqrt(np.maximum(s * (s - a) * (s - b) * (s - c), 0))
        return A, np.stack([(np.roll(l2, -1, 1) + np.roll(l2, -2, 1) - l2)[:, k] / (4 * A)
                            for k in range(3)], axis=1)


class IntrinsicStaleArea(Variant):
    """After a flip, a new face keeps the area stored for the old face at its index (a cache
    not updated): its cotangents, hence the next flips and the weights, are wrong."""
    planted, bug_class = _INTRINSIC, "flip loop"

    def _flipped_area(self, t, x):
        return t.area[x]


class IntrinsicSinglePass(Variant):
    """One pass over the edges, flipping each non-Delaunay edge met, without checking the
    edges around a flip again: a flip cascade stops early."""
    planted, bug_class = _INTRINSIC, "flip loop"
    _requeue = False


class IntrinsicAssumesOrientation(Variant):
    """The gluing of the input by reversed halfedge keys (j -> i for i -> j): on a
    non-orientable surface (or a reversed face) some interior edges are taken for boundary
    edges and never flipped."""
    planted, bug_class, finding = _INTRINSIC, "non-orientable", "F-libigl-6"

    @staticmethod
    def _intrinsic_twins(F):
        return directed_twins(F)


class IntrinsicFlipTolerance1e6(Variant):
    """Flips only when cot a + cot b < -1e-6 (|cot a| + |cot b|): a near tie up to 1e-6
    relative is left unflipped."""
    planted, bug_class = _INTRINSIC, "near ties"

    @staticmethod
    def _should_flip(ca, cb):
        return ca + cb < -1e-6 * (abs(ca) + abs(cb))


class IntrinsicMultiEdgeOverwrites(Variant):
    """The Laplace-Beltrami weights stored by vertex pair with `=`: of two edges between the
    same two vertices (a multi-edge after flips) only one weight is kept."""
    planted, bug_class = ("intrinsic_delaunay_laplacian",), "multi-edges"

    @staticmethod
    def _intrinsic_assemble(n, rows, cols, vals):
        d = dict(zip(zip(rows.tolist(), cols.tolist()), vals.tolist()))
        return sp.csr_matrix((list(d.values()), tuple(np.array(list(d)).reshape(-1, 2).T)),
                             shape=(n, n))


class IntrinsicLengthsShifted(Variant):
    """The squared lengths returned with column c the edge opposite corner c - 1."""
    planted, bug_class = ("intrinsic_delaunay_triangulation",), "index"

    @staticmethod
    def _intrinsic_output(F2, l2):
        return F2, np.roll(l2, 1, axis=1)


class PlanarFlipAbsoluteEpsilon(Variant):
    """Flips when the in-circle determinant exceeds 1e-9 (an absolute epsilon): a small
    point set (its determinant scales as the fourth power) is never flipped."""
    planted, bug_class = ("planar_flip_to_delaunay",), "scale"

    @staticmethod
    def _planar_should_flip(det, perm):
        return det > 1e-9


class PlanarFlipClockwiseTest(Variant):
    """The in-circle test written for clockwise triangles: flips the Delaunay edges."""
    planted, bug_class = ("planar_flip_to_delaunay",), "sign"

    @staticmethod
    def _planar_should_flip(det, perm):
        return det < -4 * EPS * perm


class PlanarFlipSinglePass(Variant):
    """One pass over the edges, without checking the edges around a flip again."""
    planted, bug_class = ("planar_flip_to_delaunay",), "flip loop"
    _planar_requeue = False


class PlanarDelaunayUniqueSorted(Variant):
    """The points deduplicated by np.unique(P, axis=0) before Qhull: the triangles index the
    sorted points, not the given ones."""
    planted, bug_class = ("planar_delaunay",), "np.unique order"

    @staticmethod
    def _qhull_points(P):
        return np.unique(np.asarray(P, dtype=np.float64), axis=0)


class PlanarDelaunayJoggled(Variant):
    """Qhull with 'QJ' (joggled input, to avoid precision errors; where Qhull accepts it,
    from 4 points on): the triangulation of randomly moved points, not Delaunay for nearly
    cocircular ones."""
    planted, bug_class = ("planar_delaunay",), "near ties"

    def planar_delaunay(self, P):
        import scipy.spatial
        P = np.asarray(P, dtype=np.float64)
        return np.asarray(scipy.spatial.Delaunay(P, qhull_options="QJ" if len(P) > 3 else None)
                          .simplices, dtype=np.int64)


class PlanarDelaunayFloat32(Variant):
    """The points rounded to float32 before Qhull: nearly cocircular points decided on other
    points."""
    planted, bug_class = ("planar_delaunay",), "float32"

    @staticmethod
    def _qhull_points(P):
        return np.asarray(P, dtype=np.float32).astype(np.float64)


#: every variant, in the order above
#: (the module's names keep their definition order; inspect.getsourcelines parsed this file
#: once per class, 0.75 s at each import)
VARIANTS = [cls for cls in list(vars(sys.modules[__name__]).values())
            if isinstance(cls, type) and issubclass(cls, Variant) and cls.planted
            and cls.__module__ == __name__]
