"""A correct float64 implementation of every protocol method, written the plain way with numpy
(and scipy for sparse matrices, the sparse solve and Qhull): the base of the planted-bug
benchmark's variants (:mod:`.variants`).

    ddg-oracle check --impl benchmarks.planted.numpy_all:NumpyAll --profile ci

Each method is written in small steps, the ``_``-prefixed methods below: a variant replaces
one step with one wrong line (a sign, an index, a threshold, a float32 array, a lookup that
assumes an orientation, ...).  Every step serves one protocol method (its docstring names it),
and a method that needs another one's answer asks the correct implementation
(:func:`correct`), so that a variant changes exactly the methods it declares as ``planted``.

Conventions are the protocol's (``protocol/methods.py``): the surface's own metric, any
orientation (Möbius strips and reversed faces included: edges are unordered vertex pairs,
and the intrinsic flips reorient a face where its gluing needs it), vertices used by no face
keep 2 pi, area 0, a zero Laplacian row, and count in V - E + F.  Reused from
``examples/numpy_mesh.py`` (:class:`NumpyMesh`): the boundary test of ``angle_defects``;
the other methods are NumpyMesh's formulas with their steps named.
"""

from __future__ import annotations

import math
from collections import defaultdict

import numpy as np
import scipy.sparse as sp

from examples.numpy_mesh import NumpyMesh

EPS = 2.0 ** -52


def _v(V) -> np.ndarray:
    return np.asarray(V, dtype=np.float64)


def _f(F) -> np.ndarray:
    return np.asarray(F, dtype=np.int64).reshape(-1, 3)


def sides(F) -> np.ndarray:
    """(m, 3, 2): side c of face f is the edge opposite corner c, (F[f, c+1], F[f, c+2]),
    in the direction the face lists it."""
    return np.stack([F[:, [1, 2]], F[:, [2, 0]], F[:, [0, 1]]], axis=1)


def squared_lengths(V, F) -> np.ndarray:
    """(m, 3): squared length of the edge opposite each corner."""
    X = V[F]
    return np.stack([((X[:, (c + 1) % 3] - X[:, (c + 2) % 3]) ** 2).sum(1) for c in range(3)],
                    axis=1)


def twins(F) -> np.ndarray:
    """(m, 3): for each side, the index 3 g + d of the other side of its edge (edges as
    unordered vertex pairs: right for any orientation), -1 if the edge has one side (or more
    than two)."""
    S = sides(F).reshape(-1, 2)
    _, inv, cnt = np.unique(np.sort(S, axis=1), axis=0, return_inverse=True, return_counts=True)
    inv = inv.reshape(-1)
    order = np.argsort(inv, kind="stable")
    out = np.full(len(S), -1, dtype=np.int64)
    a, b = order[:-1], order[1:]
    pair = (inv[a] == inv[b]) & (cnt[inv[a]] == 2)
    out[a[pair]], out[b[pair]] = b[pair], a[pair]
    return out.reshape(-1, 3)


def directed_twins(F) -> np.ndarray:
    """As :func:`twins`, but the twin of side i -> j looked up as the side j -> i: right only
    on a consistently oriented mesh (what a halfedge structure built by key assumes)."""
    S = sides(F).reshape(-1, 2).tolist()
    at = {(i, j): s for s, (i, j) in enumerate(S)}
    return np.array([at.get((j, i), -1) for i, j in S], dtype=np.int64).reshape(-1, 3)


def kahan_area(a2, b2, c2):
    """Triangle areas from squared lengths, Kahan's stable Heron (lengths sorted, parentheses
    as written): accurate on needles and caps."""
    a, b, c = np.sort(np.sqrt(np.stack([a2, b2, c2], axis=-1)), axis=-1)[..., ::-1].T
    return 0.25 * np.sqrt(np.maximum((a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c)),
                                     0.0))


def incircle(a, b, c, d) -> tuple[float, float]:
    """(the in-circle determinant of d against the counterclockwise triangle a, b, c: > 0
    when d is inside, evaluated in floats; the permanent that bounds its rounding error)."""
    adx, ady, bdx, bdy = a[0] - d[0], a[1] - d[1], b[0] - d[0], b[1] - d[1]
    cdx, cdy = c[0] - d[0], c[1] - d[1]
    la, lb, lc = adx * adx + ady * ady, bdx * bdx + bdy * bdy, cdx * cdx + cdy * cdy
    det = la * (bdx * cdy - cdx * bdy) + lb * (cdx * ady - adx * cdy) + lc * (adx * bdy - bdx * ady)
    perm = (la * (abs(bdx * cdy) + abs(cdx * bdy)) + lb * (abs(cdx * ady) + abs(adx * cdy))
            + lc * (abs(adx * bdy) + abs(bdx * ady)))
    return det, perm


_CORRECT = []


def correct() -> "NumpyAll":
    """The correct implementation: what one method asks of another (angle_defects of
    corner_angles, solve_dirichlet of cotan_laplacian, genus of boundary_loops), so that a
    variant changes only the methods it declares."""
    if not _CORRECT:
        _CORRECT.append(NumpyAll())
    return _CORRECT[0]


class _Intrinsic:
    """A float intrinsic triangulation: faces (vertex triples), squared lengths per side,
    each face's area and corner cotangents, and the gluing of sides (``twin``; ``comp``: the
    two sides list their edge in opposite directions, as in a consistently oriented pair).
    Faces may become loops and multi-edges, and a non-orientable surface is glued like any
    other."""

    def __init__(self, faces, l2, area, cot, twin, comp):
        self.faces, self.l2, self.area, self.cot = faces, l2, area, cot
        self.twin, self.comp = twin, comp

    def _move(self, moves: dict) -> None:
        """Renumber sides ``old -> new`` (a bijection on the affected sides); partners follow."""
        old = {s: (self.twin[s], self.comp[s]) for s in moves}
        for s, (t, c) in old.items():
            ns, nt = moves[s], (moves.get(t, t) if t >= 0 else -1)
            self.twin[ns], self.comp[ns] = nt, c
            if nt >= 0 and t not in moves:
                self.twin[nt], self.comp[nt] = ns, c

    def reverse(self, g: int) -> None:
        """List face g the other way round (corners 1 and 2 swapped)."""
        f, l, k = self.faces[g], self.l2[g], self.cot[g]
        self.faces[g], self.l2[g], self.cot[g] = [f[0], f[2], f[1]], [l[0], l[2], l[1]], [k[0], k[2], k[1]]
        self._move({3 * g: 3 * g, 3 * g + 1: 3 * g + 2, 3 * g + 2: 3 * g + 1})
        for k in range(3):
            s = 3 * g + k
            t = self.twin[s]
            if t >= 0 and t // 3 != g:
                self.comp[s] = self.comp[t] = not self.comp[s]


class NumpyAll(NumpyMesh):
    """Every protocol method, float64, the plain way (module docstring)."""

    name = "numpy-all"

    # --- chapter 1: topology ------------------------------------------------------------------

    def euler_characteristic(self, V, F):
        F = _f(F)
        return int(self._chi_vertices(V, F) - self._chi_edges(F) + len(F))

    @staticmethod
    def _chi_vertices(V, F):
        """V of V - E + F: every vertex, a vertex used by no face included."""
        return len(V)

    @staticmethod
    def _chi_edges(F):
        """E of V - E + F: distinct unordered vertex pairs of the sides."""
        return len(np.unique(np.sort(sides(F).reshape(-1, 2), axis=1), axis=0))

    def boundary_loops(self, V, F):
        F = _f(F)
        B = self._boundary_edges(F)
        steps = defaultdict(list)
        for i, j in self._boundary_steps(B).tolist():
            steps[i].append(j)
        used, loops = set(), []
        for i, j in B.tolist():
            if frozenset((i, j)) in used:
                continue
            loop, cur = [i], j
            used.add(frozenset((i, j)))
            while cur != i:
                loop.append(cur)
                nxt = next((w for w in steps[cur] if frozenset((cur, w)) not in used), None)
                if nxt is None:
                    break
                used.add(frozenset((cur, nxt)))
                cur = nxt
            loops.append(loop)
        return loops

    @staticmethod
    def _boundary_edges(F):
        """(boundary_loops) the sides whose edge has one side, as their face lists them."""
        S = sides(F).reshape(-1, 2)
        _, inv, cnt = np.unique(np.sort(S, axis=1), axis=0, return_inverse=True,
                                return_counts=True)
        return S[cnt[inv.reshape(-1)] == 1]

    @staticmethod
    def _boundary_steps(B):
        """(boundary_loops) the walk may take a boundary edge either way."""
        return np.concatenate([B, B[:, ::-1]])

    def is_orientable(self, V, F):
        F = _f(F)
        twin, S = twins(F).reshape(-1), sides(F).reshape(-1, 2)
        sign = np.zeros(len(F), dtype=np.int64)
        for start in self._orientation_starts(F):
            if sign[start]:
                continue
            sign[start], todo = 1, [start]
            while todo:
                f = todo.pop()
                for s in range(3 * f, 3 * f + 3):
                    t = twin[s]
                    if t < 0:
                        continue
                    g = t // 3
                    # listed the same way round in both faces: g is reversed relative to f
                    want = -sign[f] if S[s][0] == S[t][0] else sign[f]
                    if sign[g] == 0:
                        sign[g] = want
                        todo.append(g)
                    elif sign[g] != want:
                        return False
        return True

    @staticmethod
    def _orientation_starts(F):
        """(is_orientable) a search from every face not reached yet: every component."""
        return range(len(F))

    def genus(self, V, F):
        F = _f(F)
        base = correct()
        return self._genus_formula(self._surface_chi(V, F), len(base.boundary_loops(V, F)),
                                   base.is_orientable(V, F))

    @staticmethod
    def _surface_chi(V, F):
        """(genus) chi of the surface: the vertices its faces use."""
        return len(np.unique(F)) - len(np.unique(np.sort(sides(F).reshape(-1, 2), axis=1),
                                                 axis=0)) + len(F)

    @staticmethod
    def _genus_formula(chi, k, orientable):
        """(genus) chi = 2 - 2g - k, or 2 - h - k for h crosscaps."""
        return (2 - chi - k) // 2 if orientable else 2 - chi - k

    # --- chapter 2: curvature -----------------------------------------------------------------

    def corner_angles(self, V, F):
        V, F = _v(V), _f(F)
        X = V[F]
        out = np.empty(F.shape)
        for c in range(3):
            out[:, c] = self._angle(X[:, (c + 1) % 3] - X[:, c], X[:, (c + 2) % 3] - X[:, c])
        return out

    @staticmethod
    def _angle(a, b):
        """(corner_angles) the angle between edge vectors a and b: atan2(|a x b|, a . b)."""
        return np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), (a * b).sum(axis=1))

    def angle_defects(self, V, F):
        V, F = _v(V), _f(F)
        keep = self._summed_faces(V, F)
        sums = self._angle_sums(len(V), F[keep], correct().corner_angles(V, F)[keep])
        return self._defects(V, F, sums, NumpyMesh._boundary(V, F))

    @staticmethod
    def _summed_faces(V, F):
        """(angle_defects) the faces whose angles enter the sums: all of them."""
        return np.ones(len(F), dtype=bool)

    @staticmethod
    def _angle_sums(n, F, angles):
        """(angle_defects) the angle sum at every vertex, 0 at a vertex used by no face."""
        sums = np.zeros(n)
        np.add.at(sums, F.reshape(-1), angles.reshape(-1))
        return sums

    @staticmethod
    def _defects(V, F, sums, boundary):
        """(angle_defects) 2 pi - sum inside, pi - sum (the turning angle) on the boundary."""
        return np.where(boundary, np.pi, 2 * np.pi) - sums

    def edge_mean_curvature(self, V, F):
        V, F = _v(V), _f(F)
        N = self._face_normals(V[F])
        face_of = {(f[c], f[(c + 1) % 3]): k for k, f in enumerate(F.tolist()) for c in range(3)}
        out = {}
        for (i, j), f in face_of.items():
            g = face_of.get((j, i))
            if g is not None and i < j:
                e = V[j] - V[i]
                length = float(np.linalg.norm(e))
                out[(i, j)] = self._edge_value(self._dihedral(N[f], N[g], e / length), length)
        return out

    @staticmethod
    def _face_normals(X):
        """(edge_mean_curvature) unit normals of the faces."""
        C = np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0])
        return C / np.linalg.norm(C, axis=1)[:, None]

    @staticmethod
    def _dihedral(nf, ng, t):
        """(edge_mean_curvature) the signed angle between the normals about the unit edge t."""
        return math.atan2(float(np.cross(nf, ng) @ t), float(nf @ ng))

    @staticmethod
    def _edge_value(theta, length):
        """(edge_mean_curvature) H(e) = 1/2 theta(e) l(e)."""
        return 0.5 * theta * length

    def area(self, V, F):
        V, F = _v(V), _f(F)
        return 0.5 * float(self._double_areas(V, F).sum())

    @staticmethod
    def _double_areas(V, F):
        """(area) |(v1 - v0) x (v2 - v0)| per face."""
        X = V[F]
        return np.linalg.norm(np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]), axis=1)

    # --- chapter 3: Laplacians and mass matrices ---------------------------------------------

    def cotan_laplacian(self, V, F):
        V, F = _v(V), _f(F)
        rows, cols, vals = [], [], []
        for c in range(3):                        # corner c, opposite edge (i, j)
            k, i, j = F[:, c], F[:, (c + 1) % 3], F[:, (c + 2) % 3]
            w = self._cot(V[k], V[i], V[j]) / 2
            rows += [i, j]
            cols += [j, i]
            vals += [w, w]
        W = self._assemble(len(V), np.concatenate(rows), np.concatenate(cols), np.concatenate(vals))
        return self._graph_laplacian(W)

    @staticmethod
    def _cot(pk, pi, pj):
        """(cotan_laplacian) cot of the angle at pk of the triangles (pk, pi, pj)."""
        u, v = pi - pk, pj - pk
        return (u * v).sum(1) / np.linalg.norm(np.cross(u, v), axis=1)

    @staticmethod
    def _assemble(n, rows, cols, vals):
        """(cotan_laplacian) the weight matrix: repeated (i, j) summed (both faces of an edge)."""
        return sp.csr_matrix((vals, (rows, cols)), shape=(n, n))

    @staticmethod
    def _graph_laplacian(W):
        """(cotan_laplacian) L = D - W, D the row sums of the weights."""
        return (sp.diags(np.asarray(W.sum(axis=1)).ravel()) - W).tocsr()

    def area_gradient(self, V, F):
        # per face, grad_{v_i} A = 1/2 n x (v_k - v_j) (L3.8), n the unit normal
        V, F = _v(V), _f(F)
        X = V[F]
        N = self._gradient_normals(np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]))
        out = np.zeros_like(V)
        for c in range(3):
            j, k = (c + 1) % 3, (c + 2) % 3
            np.add.at(out, F[:, c], 0.5 * np.cross(N, X[:, k] - X[:, j]))
        return out

    @staticmethod
    def _gradient_normals(C):
        """(area_gradient) the unit normals from the faces' cross products."""
        return C / np.linalg.norm(C, axis=1)[:, None]

    def solve_dirichlet(self, V, F, boundary, values):
        # the Dirichlet problem with the cotan Laplacian: L_II u_I = -L_IB c (sparse LU)
        L = correct().cotan_laplacian(V, F).tocsr()
        boundary = np.asarray(boundary, dtype=np.int64).reshape(-1)
        values = np.asarray(values, dtype=np.float64).reshape(-1)
        n = L.shape[0]
        u = np.zeros(n)
        self._fix(u, boundary, values)
        fixed = np.unique(boundary)
        inner = np.setdiff1d(np.arange(n), fixed)
        if len(inner):
            rhs = self._dirichlet_rhs(L[inner], u, boundary, fixed)
            u[inner] = self._linear_solve(L[inner][:, inner].tocsc(), rhs)
        return u

    @staticmethod
    def _fix(u, boundary, values):
        """(solve_dirichlet) the given values on the boundary set, in the given order."""
        u[boundary] = values

    @staticmethod
    def _dirichlet_rhs(L_I, u, boundary, fixed):
        """(solve_dirichlet) -L_IB c, each fixed vertex once."""
        return -(L_I[:, fixed] @ u[fixed])

    @staticmethod
    def _linear_solve(A, b):
        """(solve_dirichlet) a direct sparse solve."""
        import scipy.sparse.linalg as sla
        return sla.spsolve(A, b)

    def vertex_areas_barycentric(self, V, F):
        V, F = _v(V), _f(F)
        out = np.zeros(len(V))
        np.add.at(out, F, (self._face_thirds(V, F))[:, None])
        return out

    @staticmethod
    def _face_thirds(V, F):
        """(vertex_areas_barycentric) a third of each face's area."""
        X = V[F]
        return np.linalg.norm(np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]), axis=1) / 6

    def vertex_areas_voronoi(self, V, F):
        # Meyer et al. 2003: the circumcentric (Voronoi) split of a non-obtuse face,
        # 1/8 sum over the corner's two edges of l^2 cot(opposite angle); an obtuse face gives
        # A/2 to its obtuse corner and A/4 to the others
        V, F = _v(V), _f(F)
        X = V[F]
        l2 = squared_lengths(V, F)
        dots, crosses = np.empty(F.shape), np.empty(F.shape)
        for c in range(3):
            a, b = X[:, (c + 1) % 3] - X[:, c], X[:, (c + 2) % 3] - X[:, c]
            dots[:, c] = (a * b).sum(1)
            crosses[:, c] = np.linalg.norm(np.cross(a, b), axis=1)
        A = crosses[:, 0] / 2
        cot = dots / crosses
        lc = l2 * cot
        voronoi = np.stack([(lc[:, (c + 1) % 3] + lc[:, (c + 2) % 3]) / 8 for c in range(3)], axis=1)
        obtuse = self._obtuse_corners(dots)
        parts = np.where(obtuse.any(axis=1)[:, None], self._obtuse_split(A, obtuse), voronoi)
        out = np.zeros(len(V))
        np.add.at(out, F, parts)
        return out

    @staticmethod
    def _obtuse_corners(dots):
        """(vertex_areas_voronoi) corners of an angle above pi/2: a negative dot product."""
        return dots < 0

    @staticmethod
    def _obtuse_split(A, obtuse):
        """(vertex_areas_voronoi) A/2 to the obtuse corner, A/4 to the two others."""
        return np.where(obtuse, A[:, None] / 2, A[:, None] / 4)

    # --- chapter 4: Delaunay --------------------------------------------------------------------

    def is_locally_delaunay(self, V, F):
        V, F = _v(V), _f(F)
        X = V[F]
        cot = np.empty(F.shape)
        for c in range(3):
            a, b = X[:, (c + 1) % 3] - X[:, c], X[:, (c + 2) % 3] - X[:, c]
            cot[:, c] = (a * b).sum(1) / np.linalg.norm(np.cross(a, b), axis=1)
        twin = self._delaunay_twins(F).reshape(-1)
        a = cot.reshape(-1)
        b = a[np.maximum(twin, 0)]
        inner = twin >= 0
        return np.where(inner, self._delaunay_test(a + b, a, b), self._boundary_flag).reshape(-1, 3)

    #: (is_locally_delaunay) a boundary edge is Delaunay (D4.4)
    _boundary_flag = True

    @staticmethod
    def _delaunay_twins(F):
        """(is_locally_delaunay) the other side of each side's edge, edges unordered."""
        return twins(F)

    @staticmethod
    def _delaunay_test(s, a, b):
        """(is_locally_delaunay) cot a + cot b >= 0."""
        return s >= 0

    # intrinsic Delaunay: float edge flips on squared lengths

    def intrinsic_delaunay_triangulation(self, V, F):
        t = self._intrinsic_flips(V, F)
        return self._intrinsic_output(np.array(t.faces, dtype=np.int64),
                                      np.array(t.l2, dtype=np.float64))

    @staticmethod
    def _intrinsic_output(F2, l2):
        """(intrinsic_delaunay_triangulation) faces and squared lengths, column c opposite
        corner c."""
        return F2, l2

    def intrinsic_delaunay_laplacian(self, V, F):
        n = len(V)
        t = self._intrinsic_flips(V, F)
        F2 = np.array(t.faces, dtype=np.int64).reshape(-1, 3)
        cot = np.array(t.cot, dtype=np.float64).reshape(-1)
        twin = np.array(t.twin, dtype=np.int64)
        first = (twin < 0) | (np.arange(len(twin)) < twin)        # each edge once
        w = (cot + np.where(twin >= 0, cot[np.maximum(twin, 0)], 0.0))[first] / 2
        i, j = sides(F2).reshape(-1, 2)[first].T
        keep = i != j                                               # a loop: no weight
        i, j, w = i[keep], j[keep], w[keep]
        W = self._intrinsic_assemble(n, np.concatenate([i, j]), np.concatenate([j, i]),
                                     np.concatenate([w, w]))
        return (sp.diags(np.asarray(W.sum(axis=1)).ravel()) - W).tocsr()

    @staticmethod
    def _intrinsic_assemble(n, rows, cols, vals):
        """(intrinsic_delaunay_laplacian) the weight matrix from one entry per edge and
        direction: the edges between the same two vertices (a multi-edge) summed."""
        return sp.csr_matrix((vals, (rows, cols)), shape=(n, n))

    @staticmethod
    def _intrinsic_area(a2, b2, c2):
        """(intrinsic flips) the area of a face made by a flip, from its squared lengths
        (Kahan's Heron)."""
        return kahan_area(a2, b2, c2)

    def _flipped_area(self, t, x):
        """(intrinsic flips) the area of face x just made by a flip, from its new lengths."""
        return float(self._intrinsic_area(*(np.array(y) for y in t.l2[x])))

    @staticmethod
    def _input_faces(V, F, l2):
        """(intrinsic flips) the input faces' areas and corner cotangents, from the positions
        (cross and dot products): a cap keeps the area its float squared lengths lost."""
        X = V[F]
        dots, crosses = np.empty(F.shape), np.empty(F.shape)
        for c in range(3):
            a, b = X[:, (c + 1) % 3] - X[:, c], X[:, (c + 2) % 3] - X[:, c]
            dots[:, c], crosses[:, c] = (a * b).sum(1), np.linalg.norm(np.cross(a, b), axis=1)
        return crosses.max(axis=1) / 2, dots / crosses

    @staticmethod
    def _intrinsic_twins(F):
        """(intrinsic flips) the gluing of the input's sides, edges unordered."""
        return twins(F)

    def _flip_length(self, a, b, c, d, e, A1, A2):
        """(intrinsic flips) the squared new diagonal p-q of the quadrilateral p, i, q, j
        whose diagonal i-j (squared e) is flipped: b = |ip|^2, a = |jp|^2, c = |iq|^2,
        d = |jq|^2, areas A1 of (p, i, j) and A2 of (q, j, i), laying both out in the plane:
        b + c - (e + b - a)(e + c - d) / (2 e) + 8 A1 A2 / e."""
        return b + c - (e + b - a) * (e + c - d) / (2 * e) + 8 * A1 * A2 / e

    @staticmethod
    def _should_flip(ca, cb):
        """(intrinsic flips) not Delaunay: cot a + cot b < 0 beyond rounding."""
        return ca + cb < -2 * EPS * (abs(ca) + abs(cb))

    #: (intrinsic flips) after a flip, the four edges around it are checked again
    _requeue = True

    def _intrinsic_flips(self, V, F) -> _Intrinsic:
        V, F = _v(V), _f(F)
        l2 = squared_lengths(V, F)
        twin = self._intrinsic_twins(F).reshape(-1)
        S = sides(F).reshape(-1, 2)
        comp = [bool(t >= 0 and S[s][0] == S[t][1]) for s, t in enumerate(twin.tolist())]
        area, cot = self._input_faces(V, F, l2)
        t = _Intrinsic(F.tolist(), l2.tolist(), area.tolist(), cot.tolist(), twin.tolist(), comp)
        todo = list(range(3 * len(F)))[::-1]
        budget = 1000 + 100 * len(F)
        while todo and budget:
            s = todo.pop()
            f, c = divmod(s, 3)
            o = t.twin[s]
            if o < 0 or o // 3 == f:
                continue
            if not self._should_flip(t.cot[f][c], t.cot[o // 3][o % 3]):
                continue
            budget -= 1
            new = self._flip(t, s)
            if self._requeue:
                todo += new
        return t

    def _flip(self, t: _Intrinsic, s: int) -> list:
        f, c = divmod(s, 3)
        if not t.comp[s]:
            t.reverse(t.twin[s] // 3)             # glued the same way round: reorient g
        o = t.twin[s]
        g, d = divmod(o, 3)
        p, i, j = t.faces[f][c], t.faces[f][(c + 1) % 3], t.faces[f][(c + 2) % 3]
        q = t.faces[g][d]
        Lf, Lg = t.l2[f], t.l2[g]
        e, a, b = Lf[c], Lf[(c + 1) % 3], Lf[(c + 2) % 3]          # |ij|^2, |jp|^2, |ip|^2
        cc, dd = Lg[(d + 1) % 3], Lg[(d + 2) % 3]                  # |iq|^2, |jq|^2
        new = float(self._flip_length(a, b, cc, dd, e, t.area[f], t.area[g]))
        t._move({3 * f + (c + 2) % 3: 3 * f + 2, 3 * g + (d + 1) % 3: 3 * f,
                 3 * f + (c + 1) % 3: 3 * g, 3 * g + (d + 2) % 3: 3 * g + 2})
        t.faces[f], t.l2[f] = [p, i, q], [cc, new, b]
        t.faces[g], t.l2[g] = [q, j, p], [a, new, dd]
        for x in (f, g):
            L = t.l2[x]
            t.area[x] = A = self._flipped_area(t, x)
            t.cot[x] = [(L[(k + 1) % 3] + L[(k + 2) % 3] - L[k]) / (4 * A) for k in range(3)]
        t.twin[3 * f + 1], t.twin[3 * g + 1] = 3 * g + 1, 3 * f + 1
        t.comp[3 * f + 1] = t.comp[3 * g + 1] = True
        return [3 * f, 3 * f + 2, 3 * g, 3 * g + 2]

    # planar Delaunay

    def planar_flip_to_delaunay(self, V, F):
        P = _v(V)[:, :2]
        faces = _f(F).tolist()
        at = {(f[c], f[(c + 1) % 3]): k for k, f in enumerate(faces) for c in range(3)}
        todo = sorted(at)[::-1]
        budget = 1000 + 100 * len(faces)
        while todo and budget:
            i, j = todo.pop()
            if (i, j) not in at or (j, i) not in at:
                continue
            f, g = at[(i, j)], at[(j, i)]
            p = next(v for v in faces[f] if v not in (i, j))      # f = (i, j, p) counterclockwise
            q = next(v for v in faces[g] if v not in (i, j))      # g = (j, i, q)
            if not self._planar_should_flip(*incircle(P[i], P[j], P[p], P[q])):
                continue
            budget -= 1
            for x in (f, g):
                for c in range(3):
                    del at[(faces[x][c], faces[x][(c + 1) % 3])]
            faces[f], faces[g] = self._planar_new_faces(p, i, q, j)
            for x in (f, g):
                for c in range(3):
                    at[(faces[x][c], faces[x][(c + 1) % 3])] = x
            if self._planar_requeue:
                todo += [(p, i), (i, q), (q, j), (j, p)]
        return np.array(faces, dtype=np.int64).reshape(-1, 3)

    @staticmethod
    def _planar_should_flip(det, perm):
        """(planar_flip_to_delaunay) the apex of the other face inside the circle, beyond the
        rounding of the in-circle determinant (a tie is left as it is)."""
        return det > 4 * EPS * perm

    @staticmethod
    def _planar_new_faces(p, i, q, j):
        """(planar_flip_to_delaunay) the flipped quadrilateral p, i, q, j: both faces
        counterclockwise."""
        return [p, i, q], [q, j, p]

    #: (planar_flip_to_delaunay) after a flip, the four edges around it are checked again
    _planar_requeue = True

    def planar_delaunay(self, P):
        import scipy.spatial
        return np.asarray(scipy.spatial.Delaunay(self._qhull_points(P),
                                                 qhull_options=self._qhull_options).simplices,
                          dtype=np.int64)

    #: (planar_delaunay) scipy's default options (Qbb Qc Qz Q12, and Qt)
    _qhull_options = None

    @staticmethod
    def _qhull_points(P):
        """(planar_delaunay) the points as given: Qhull's indices are theirs."""
        return np.asarray(P, dtype=np.float64)
