"""A panel of honest float implementations: the protocol's numeric methods written the way
careful people write them, each at float64 and at float32.  No ddg-oracle internals and
no exact arithmetic: numpy and scipy on the arrays the properties hand over.

ddg-oracle must pass every one of them on every property (issue 40, "no false alarm"):
a failure is either a careless formula here (then this file is wrong) or a bound or a
decision of ddg-oracle that is not derived right (then ``properties/`` is wrong).

Three routes, each a class, each at two precisions (``*32``: the inputs cast to float32,
every operation in float32, ``machine_epsilon = 2**-23``; answers returned as float64):

- :class:`Atan2Cross`: corner angles atan2(|a x b|, a . b); face areas |a x b| / 2;
  cotangents a . b / |a x b|; dihedral angles atan2 of the normals' cross and dot; the
  area gradient 1/2 n x (v_k - v_j) per face (no cotangent);
- :class:`LawOfCosines`: squared lengths from the coordinates; angles acos((b^2 + c^2 -
  a^2) / (2 b c)), clamped; areas by Kahan's sorted Heron; cotangents (b^2 + c^2 - a^2) /
  (4 A); dihedral angles acos(n1 . n2), clamped, signed by (n1 x n2) . e; the area
  gradient L V;
- :class:`KahanHalfAngle`: Kahan's half-angle formula on the side lengths ("Miscalculating
  area and angles of a needle-like triangle") for the angles, tan(alpha / 2) for the
  cotangents (cot = (1/t - t) / 2), Kahan's sorted Heron for the areas, Kahan's stable
  angle between two vectors 2 atan2(|x |y| - |x| y|, |x |y| + |x| y|) for the dihedral
  angles.

Careful, as a library would be: a mesh is first brought to unit size by a power of two
(exact; so that float32's products of four coordinates neither underflow nor overflow
on a mesh scaled by 2**-60 or 2**60, the answers with a unit scaled back), a NaN
coordinate or a vertex index out of range is refused (ValueError), and a face normal whose
float cross product is exactly 0 stays 0 (no 0 / 0).  Nothing else is guarded: no
thresholds, no special cases for slivers.  The intrinsic flips are Lawson's, on squared
lengths, flipping a side where cot a + cot b < -8 eps (|cot a| + |cot b|): the tolerance
geometry-central's flipToDelaunay has (delaunayEPS), relative, so that float ties end.

Shared: angle defects (2 pi, or pi on the boundary, minus the angle sum), mixed Voronoi
areas (Meyer et al.: the circumcentric split on non-obtuse faces, A/2 at an obtuse corner,
A/4 at the others), barycentric areas, the cotan Laplacian, the Dirichlet problem (sparse
LU of L_II), locally Delaunay edges (cot a + cot b >= 0), intrinsic Delaunay flips on
squared lengths (the new diagonal from a planar layout of the two triangles), planar
Lawson flips with the float in-circle and orientation tests, and planar Delaunay as a
sweep triangulation flipped by Lawson's algorithm.
"""

from __future__ import annotations

import math
from collections import deque

import numpy as np
import scipy.sparse as sp

__all__ = ["HonestMesh", "Atan2Cross", "Atan2Cross32", "LawOfCosines", "LawOfCosines32",
           "KahanHalfAngle", "KahanHalfAngle32", "PANEL"]


def _nx(c):
    return (c + 1) % 3


def _pv(c):
    return (c + 2) % 3


def _sort3(l):
    """(a, b, c) lengths sorted a >= b >= c, per row."""
    s = np.sort(l, axis=1)
    return s[:, 2], s[:, 1], s[:, 0]


class HonestMesh:
    """The shared machinery; subclasses choose the routes (class attributes)."""

    name = "honest"
    dtype = np.float64
    angle_rule = "atan2"          # atan2 | cosines | kahan
    area_rule = "cross"           # cross | heron
    cot_rule = "dotcross"         # dotcross | lengths | halfangle
    dihedral_rule = "atan2"       # atan2 | acos | kahan
    gradient_rule = "cross"       # cross | laplacian

    # --- per-face geometry in the member's precision ----------------------------------------

    def _checked(self, V, F):
        """The input as float64 and int64 arrays; ValueError for what is no mesh (a NaN or
        infinite coordinate, a face naming a vertex that is not there)."""
        V = np.asarray(V, dtype=np.float64).reshape(-1, 3)
        F = np.asarray(F, dtype=np.int64).reshape(-1, 3)
        if not np.all(np.isfinite(V)):
            raise ValueError("V has a non-finite coordinate")
        if F.size and (F.min() < 0 or F.max() >= len(V)):
            raise ValueError("F names a vertex index out of range")
        return V, F

    def _unit(self, V, F):
        """(V * s in the member's precision, F, s): s a power of two bringing the longest
        edge to [1/2, 1), so that products of four coordinates (|a x b|^2, Heron's) neither
        underflow nor overflow float32 on a tiny or huge mesh; exact, and undone on the
        answers that have a unit (areas / s^2, lengths / s)."""
        V, F = self._checked(V, F)
        X = V[F]
        size = float(np.abs(X - X[:, [1, 2, 0]]).max()) if F.size else 0.0
        s = 2.0 ** -math.frexp(size)[1] if size > 0 else 1.0
        return (V * s).astype(self.dtype), F, s

    def _arrays(self, V, F):
        V, F, _ = self._unit(V, F)
        return V, F

    def _geometry(self, V, F):
        """Per face: edge vectors at each corner, squared lengths (column c: the side
        opposite corner c), lengths."""
        X = V[F]                                            # (m, 3, 3)
        U = [X[:, _nx(c)] - X[:, c] for c in range(3)]      # corner c -> next vertex
        W = [X[:, _pv(c)] - X[:, c] for c in range(3)]      # corner c -> previous vertex
        E = [X[:, _pv(c)] - X[:, _nx(c)] for c in range(3)]  # side opposite corner c
        l2 = np.stack([(e * e).sum(axis=1) for e in E], axis=1)
        return X, U, W, l2

    def _heron(self, l2):
        """Kahan's sorted Heron: area from squared lengths (m, 3)."""
        a, b, c = _sort3(np.sqrt(l2))
        q = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c))
        return self.dtype(0.25) * np.sqrt(np.maximum(q, self.dtype(0)))

    def _areas(self, V, F):
        X, U, W, l2 = self._geometry(V, F)
        if self.area_rule == "cross":
            return np.linalg.norm(np.cross(U[0], W[0]), axis=1) / self.dtype(2)
        return self._heron(l2)

    def _kahan_tan_half(self, l2):
        """(m, 3): tan(alpha_c / 2) per corner by Kahan's formula on the side lengths."""
        L = np.sqrt(l2)
        out = np.empty_like(L)
        for c in range(3):
            o, p, q = L[:, c], L[:, _nx(c)], L[:, _pv(c)]
            a, b = np.maximum(p, q), np.minimum(p, q)       # adjacent sides a >= b
            mu = np.where(b >= o, o - (a - b), b - (a - o))
            # float lengths may break the triangle inequality on a sliver: clamped, a
            # side at least the sum of the others makes a straight angle (t = inf) or a
            # zero one (t = 0)
            num = np.maximum(((a - b) + o) * mu, self.dtype(0))
            den = (a + (b + o)) * np.maximum((a - o) + b, self.dtype(0))
            with np.errstate(divide="ignore", invalid="ignore"):
                out[:, c] = np.sqrt(num / den)
        return out

    def _unit_normals(self, N):
        """Cross products normalised; one that is exactly 0 in floats (a face beyond the
        format's resolution) stays 0 rather than 0 / 0: no threshold, no NaN."""
        norm = np.linalg.norm(N, axis=1)
        return np.divide(N, norm[:, None], out=np.zeros_like(N), where=norm[:, None] > 0)

    def _face_angles(self, V, F):
        X, U, W, l2 = self._geometry(V, F)
        out = np.empty(F.shape, dtype=self.dtype)
        if self.angle_rule == "atan2":
            for c in range(3):
                out[:, c] = np.arctan2(np.linalg.norm(np.cross(U[c], W[c]), axis=1),
                                       (U[c] * W[c]).sum(axis=1))
        elif self.angle_rule == "cosines":
            L = np.sqrt(l2)
            for c in range(3):
                o, p, q = l2[:, c], l2[:, _nx(c)], l2[:, _pv(c)]
                cos = (p + q - o) / (self.dtype(2) * L[:, _nx(c)] * L[:, _pv(c)])
                out[:, c] = np.arccos(np.clip(cos, self.dtype(-1), self.dtype(1)))
        else:
            out[:] = self.dtype(2) * np.arctan(self._kahan_tan_half(l2))
        return out

    def _cots_from_lengths(self, l2, rule=None):
        rule = rule or self.cot_rule
        if rule == "halfangle":
            t = self._kahan_tan_half(l2)
            with np.errstate(divide="ignore"):
                return (self.dtype(1) / t - t) / self.dtype(2)
        A = self._heron(l2)
        out = np.empty_like(l2)
        with np.errstate(divide="ignore", invalid="ignore"):
            for c in range(3):
                out[:, c] = (l2[:, _nx(c)] + l2[:, _pv(c)] - l2[:, c]) / (self.dtype(4) * A)
        return out

    def _face_cots(self, V, F):
        if self.cot_rule != "dotcross":
            return self._cots_from_lengths(self._geometry(V, F)[3])
        X, U, W, l2 = self._geometry(V, F)
        out = np.empty(F.shape, dtype=self.dtype)
        with np.errstate(divide="ignore", invalid="ignore"):
            for c in range(3):
                out[:, c] = (U[c] * W[c]).sum(axis=1) / np.linalg.norm(np.cross(U[c], W[c]), axis=1)
        return out

    # --- chapter 2 ---------------------------------------------------------------------------

    def corner_angles(self, V, F):
        V, F = self._arrays(V, F)
        return self._face_angles(V, F).astype(np.float64)

    @staticmethod
    def _boundary_vertices(n, F):
        count = {}
        for f in F.tolist():
            for c in range(3):
                e = (min(f[c], f[_nx(c)]), max(f[c], f[_nx(c)]))
                count[e] = count.get(e, 0) + 1
        b = np.zeros(n, dtype=bool)
        for (i, j), k in count.items():
            if k == 1:
                b[i] = b[j] = True
        return b

    def angle_defects(self, V, F):
        V, F = self._arrays(V, F)
        sums = np.zeros(len(V), dtype=self.dtype)
        np.add.at(sums, F.reshape(-1), self._face_angles(V, F).reshape(-1))
        full = np.where(self._boundary_vertices(len(V), F), self.dtype(np.pi), self.dtype(2 * np.pi))
        return (full.astype(self.dtype) - sums).astype(np.float64)

    def edge_mean_curvature(self, V, F):
        V, F, unit = self._unit(V, F)
        X = V[F]
        N = np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0])
        N = self._unit_normals(N)
        face_of = {(f[c], f[_nx(c)]): k for k, f in enumerate(F.tolist()) for c in range(3)}
        out = {}
        for (i, j), f in face_of.items():
            g = face_of.get((j, i))
            if g is None or i >= j:
                continue
            e = V[j] - V[i]
            length = np.sqrt((e * e).sum())
            side = np.dot(np.cross(N[f], N[g]), e)          # > 0 where convex
            if self.dihedral_rule == "atan2":
                theta = np.arctan2(side / length, np.dot(N[f], N[g]))
            elif self.dihedral_rule == "acos":
                theta = np.arccos(np.clip(np.dot(N[f], N[g]), self.dtype(-1), self.dtype(1)))
                theta = theta if side >= 0 else -theta
            else:                                          # Kahan: both normals are unit
                theta = self.dtype(2) * np.arctan2(np.linalg.norm(N[f] - N[g]),
                                                   np.linalg.norm(N[f] + N[g]))
                theta = theta if side >= 0 else -theta
            out[(i, j)] = float(self.dtype(0.5) * theta * length) / unit
        return out

    def area(self, V, F):
        V, F, unit = self._unit(V, F)
        return float(self._areas(V, F).sum()) / unit ** 2

    # --- chapter 3 ---------------------------------------------------------------------------

    def _laplacian(self, n, F, cot):
        rows, cols, vals = [], [], []
        for c in range(3):
            i, j = F[:, _nx(c)], F[:, _pv(c)]
            w = cot[:, c] / self.dtype(2)
            rows += [i, j]
            cols += [j, i]
            vals += [w, w]
        W = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                          shape=(n, n), dtype=self.dtype)
        W.setdiag(0)
        W.eliminate_zeros()
        return (sp.diags(np.asarray(W.sum(axis=1)).ravel().astype(self.dtype)) - W).tocsr()

    def _own_laplacian(self, V, F):
        V, F = self._arrays(V, F)
        return self._laplacian(len(V), F, self._face_cots(V, F))

    def cotan_laplacian(self, V, F):
        return self._own_laplacian(V, F).astype(np.float64)

    def area_gradient(self, V, F):
        if self.gradient_rule == "laplacian":
            V1, F1, unit = self._unit(V, F)
            L = self._laplacian(len(V1), F1, self._face_cots(V1, F1))
            return np.asarray(L @ V1, dtype=np.float64) / unit
        V, F, unit = self._unit(V, F)
        X = V[F]
        N = np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0])
        N = self._unit_normals(N)
        out = np.zeros_like(V)
        for c in range(3):
            j, k = _nx(c), _pv(c)
            np.add.at(out, F[:, c], self.dtype(0.5) * np.cross(N, X[:, k] - X[:, j]))
        return out.astype(np.float64) / unit

    def solve_dirichlet(self, V, F, boundary, values):
        import scipy.sparse.linalg as sla
        L = self._own_laplacian(V, F)
        boundary = np.asarray(boundary, dtype=np.int64)
        if boundary.size and (boundary.min() < 0 or boundary.max() >= L.shape[0]):
            raise ValueError("a boundary vertex index out of range")
        u = np.zeros(L.shape[0], dtype=self.dtype)
        u[boundary] = np.asarray(values, dtype=np.float64).astype(self.dtype)
        inner = np.setdiff1d(np.arange(L.shape[0]), boundary)
        if len(inner):
            rhs = -(L[inner][:, boundary] @ u[boundary])
            u[inner] = sla.spsolve(L[inner][:, inner].tocsc(), rhs)
        return u.astype(np.float64)

    def vertex_areas_barycentric(self, V, F):
        V, F, unit = self._unit(V, F)
        third = self._areas(V, F) / self.dtype(3)
        out = np.zeros(len(V), dtype=self.dtype)
        np.add.at(out, F, third[:, None])
        return out.astype(np.float64) / unit ** 2

    def vertex_areas_voronoi(self, V, F):
        """Meyer et al.'s mixed areas: circumcentric on non-obtuse faces, else A/2 at the
        obtuse corner and A/4 at the others; obtuse decided by the cotangent's sign."""
        V, F, unit = self._unit(V, F)
        _, _, _, l2 = self._geometry(V, F)
        cot = self._face_cots(V, F)
        A = self._areas(V, F)
        obtuse = cot < 0
        any_obtuse = obtuse.any(axis=1)
        out = np.zeros(len(V), dtype=self.dtype)
        for c in range(3):
            # corner c: sides to the next and previous vertices, opposite corners prev, next
            vor = (l2[:, _pv(c)] * cot[:, _pv(c)] + l2[:, _nx(c)] * cot[:, _nx(c)]) / self.dtype(8)
            mixed = np.where(obtuse[:, c], A / self.dtype(2), A / self.dtype(4))
            np.add.at(out, F[:, c], np.where(any_obtuse, mixed, vor))
        return out.astype(np.float64) / unit ** 2

    # --- chapter 4 ---------------------------------------------------------------------------

    def is_locally_delaunay(self, V, F):
        V, F = self._arrays(V, F)
        cot = self._face_cots(V, F)
        sides = {}
        for f, face in enumerate(F.tolist()):
            for c in range(3):
                key = (min(face[_nx(c)], face[_pv(c)]), max(face[_nx(c)], face[_pv(c)]))
                sides.setdefault(key, []).append((f, c))
        out = np.ones(F.shape, dtype=bool)
        for corners in sides.values():
            if len(corners) == 2:
                s = sum(cot[f, c] for f, c in corners)
                for f, c in corners:
                    out[f, c] = bool(s >= 0)
        return out

    def _intrinsic(self, V, F):
        V, F, unit = self._unit(V, F)
        _, _, _, l2 = self._geometry(V, F)
        F2, l2 = IntrinsicFlips(F.copy(), l2.copy(), self).run()
        return F2, l2, unit

    def intrinsic_delaunay_triangulation(self, V, F):
        F2, l2, unit = self._intrinsic(V, F)
        return F2, l2.astype(np.float64) / unit ** 2

    def intrinsic_delaunay_laplacian(self, V, F):
        F2, l2, _ = self._intrinsic(V, F)
        rule = "lengths" if self.cot_rule == "dotcross" else self.cot_rule
        return self._laplacian(len(V), F2, self._cots_from_lengths(l2, rule)).astype(np.float64)

    def planar_flip_to_delaunay(self, V, F):
        V, F, _ = self._unit(V, F)                   # the predicates' signs: scale-free
        return lawson_flips(V[:, :2], [tuple(int(v) for v in f) for f in F], self.dtype)

    def planar_delaunay(self, P):
        P = np.asarray(P, dtype=np.float64).reshape(-1, 2)
        if not np.all(np.isfinite(P)):
            raise ValueError("P has a non-finite coordinate")
        size = float(np.abs(P - P.mean(axis=0)).max()) if len(P) else 0.0
        P = (P * (2.0 ** -math.frexp(size)[1] if size > 0 else 1.0)).astype(self.dtype)
        return lawson_flips(P, sweep_triangulation(P), self.dtype)


# --- intrinsic flips on squared lengths ---------------------------------------------------------


class IntrinsicFlips:
    """Lawson's flip algorithm on an intrinsic triangulation given by faces and squared
    lengths (column c: the side opposite corner c), any surface (non-orientable ones
    included: a side glued with the same orientation is reversed before a flip).  Sides
    are glued by the unordered vertex pair of the input (a regular mesh), afterwards by
    the flips' own bookkeeping (loops and multi-edges allowed)."""

    def __init__(self, F, l2, impl):
        self.F, self.l2, self.impl = F, l2, impl
        m = len(F)
        self.nb = -np.ones((m, 3, 2), dtype=np.int64)   # (face, corner) across the side
        self.same = np.zeros((m, 3), dtype=bool)        # glued with the same orientation
        sides = {}
        for f, face in enumerate(F.tolist()):
            for c in range(3):
                a, b = face[_nx(c)], face[_pv(c)]
                sides.setdefault((min(a, b), max(a, b)), []).append((f, c, a))
        for glued in sides.values():
            if len(glued) == 2:
                (f, c, a), (g, d, b) = glued
                self.nb[f, c] = g, d
                self.nb[g, d] = f, c
                self.same[f, c] = self.same[g, d] = a == b

    def cot(self, f, c):
        """``impl._cots_from_lengths(l2[f])[c]`` (the same operations on the dtype's
        scalars, bit for bit: tests/test_bounds_vs_honest.py): the flip loop asks per
        corner, and numpy's per-call cost on 1-row arrays made this loop most of the
        panel's time."""
        dt, row = self.impl.dtype, self.l2[f]
        o2, p2, q2 = row[c], row[_nx(c)], row[_pv(c)]
        with np.errstate(divide="ignore", invalid="ignore"):
            if self.impl.cot_rule == "halfangle":
                o, p, q = np.sqrt(o2), np.sqrt(p2), np.sqrt(q2)
                a, b = max(p, q), min(p, q)
                mu = o - (a - b) if b >= o else b - (a - o)
                num = max(((a - b) + o) * mu, dt(0))
                den = (a + (b + o)) * max((a - o) + b, dt(0))
                t = np.sqrt(num / den)
                return (dt(1) / t - t) / dt(2)
            a, b, cc = sorted((np.sqrt(o2), np.sqrt(p2), np.sqrt(q2)), reverse=True)
            h = (a + (b + cc)) * (cc - (a - b)) * (cc + (a - b)) * (a + (b - cc))
            area = dt(0.25) * np.sqrt(max(h, dt(0)))
            return (p2 + q2 - o2) / (dt(4) * area)

    def _reverse(self, g):
        """Swap corners 1 and 2 of face g (its orientation), keeping every gluing: a
        gluing to another face changes its relative orientation, one to g itself not."""
        perm = [0, 2, 1]                                 # its own inverse
        old_nb, old_same = self.nb[g].copy(), self.same[g].copy()
        self.F[g] = self.F[g][perm]
        self.l2[g] = self.l2[g][perm]
        for k in range(3):
            h, e = (int(x) for x in old_nb[perm[k]])
            s = bool(old_same[perm[k]])
            if h == g:
                self.nb[g, k] = g, perm[e]
                self.same[g, k] = s
            else:
                self.nb[g, k] = h, e
                self.same[g, k] = (not s) if h >= 0 else s
                if h >= 0:
                    self.nb[h, e] = g, k
                    self.same[h, e] = not s

    def flip(self, f, c):
        g, d = (int(x) for x in self.nb[f, c])
        if g == f:
            return False
        if self.same[f, c]:
            self._reverse(g)
            g, d = (int(x) for x in self.nb[f, c])
        F, l2, dt = self.F, self.l2, self.impl.dtype
        p, a, b = F[f, c], F[f, _nx(c)], F[f, _pv(c)]
        q = F[g, d]
        e2 = l2[f, c]
        l_pb, l_pa = l2[f, _nx(c)], l2[f, _pv(c)]
        l_qa, l_qb = l2[g, _nx(d)], l2[g, _pv(d)]
        # the two triangles laid out in the plane on either side of the edge a -> b
        A = self.impl._heron(np.array([l2[f], l2[g]], dtype=dt))
        e = np.sqrt(e2)
        xp = (l_pa + e2 - l_pb) / (dt(2) * e)
        xq = (l_qa + e2 - l_qb) / (dt(2) * e)
        yp, yq = dt(2) * A[0] / e, dt(2) * A[1] / e
        new = (xp - xq) ** 2 + (yp + yq) ** 2
        # old outer sides -> their place in f' = (p, a, q) and g' = (q, b, p)
        where = {(f, _nx(c)): (g, 0), (f, _pv(c)): (f, 2), (g, _nx(d)): (f, 0),
                 (g, _pv(d)): (g, 2)}
        outer = {}
        for side, mine in where.items():
            h, k = (int(x) for x in self.nb[side])
            s = bool(self.same[side])
            if (h, k) in where:
                outer[mine] = (where[(h, k)], s, True)
            else:
                outer[mine] = ((h, k), s, False)
        F[f] = [p, a, q]
        F[g] = [q, b, p]
        l2[f] = [l_qa, new, l_pa]
        l2[g] = [l_pb, new, l_qb]
        self.nb[f, 1] = g, 1
        self.nb[g, 1] = f, 1
        self.same[f, 1] = self.same[g, 1] = False
        for mine, ((h, k), s, inside) in outer.items():
            self.nb[mine] = h, k
            self.same[mine] = s
            if h >= 0 and not inside:
                self.nb[h, k] = mine
                self.same[h, k] = s
        return True

    def run(self):
        m = len(self.F)
        queue = deque((f, c) for f in range(m) for c in range(3))
        budget = 50 * m * m + 1000
        # a side is Delaunay up to a tolerance, as geometry-central's flipToDelaunay has it
        # (simple_idt.cpp: cWeight < -delaunayEPS flips, docs/findings.md), here relative
        # to the two cotangents: without one, two float ties flipped each other until the
        # budget ran out (7 of 270 runs of the default hunt, 99% of its 88,000 flips)
        tol = 8 * float(np.finfo(self.impl.dtype).eps)
        while queue and budget > 0:
            f, c = queue.popleft()
            g, d = self.nb[f, c]
            if g < 0 or g == f:
                continue
            a, b = self.cot(f, c), self.cot(g, d)
            s = a + b
            if s >= 0 or (np.isfinite(s) and -s <= tol * (abs(a) + abs(b))):
                continue                                 # (a cap's infinite cot is flipped)
            budget -= 1
            if self.flip(f, c):
                queue.extend((h, k) for h in (f, g) for k in range(3))
        return self.F, self.l2


# --- planar Delaunay by flips --------------------------------------------------------------------


def _orient(P, a, b, c):
    """The sign of the orientation of a b c, as careful float code decides it (Shewchuk's
    filter: the float determinant where it exceeds its error bound, exact otherwise), so
    that exactly collinear points never make a triangle and no point is lost."""
    l = (P[b, 0] - P[a, 0]) * (P[c, 1] - P[a, 1])
    r = (P[b, 1] - P[a, 1]) * (P[c, 0] - P[a, 0])
    det = l - r
    if abs(det) > 4 * np.finfo(P.dtype).eps * (abs(l) + abs(r)):
        return det
    from fractions import Fraction
    pa, pb, pc = ([Fraction(float(x)) for x in P[i]] for i in (a, b, c))
    exact = (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pb[1] - pa[1]) * (pc[0] - pa[0])
    return (exact > 0) - (exact < 0)


def _incircle(P, a, b, c, d):
    """> 0 iff d is inside the circle through the counterclockwise a, b, c (float)."""
    adx, ady = P[a, 0] - P[d, 0], P[a, 1] - P[d, 1]
    bdx, bdy = P[b, 0] - P[d, 0], P[b, 1] - P[d, 1]
    cdx, cdy = P[c, 0] - P[d, 0], P[c, 1] - P[d, 1]
    return ((adx * adx + ady * ady) * (bdx * cdy - cdx * bdy)
            + (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy)
            + (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady))


def sweep_triangulation(P):
    """A triangulation of the convex hull of the points: sorted by x then y, each point
    joined to the hull edges it sees (float orientation tests)."""
    order = sorted(range(len(P)), key=lambda i: (P[i, 0], P[i, 1]))
    # the first points up to one off their line
    k = 2
    while k < len(order) and _orient(P, order[0], order[1], order[k]) == 0:
        k += 1
    if k == len(order):
        return []
    first = order[:k]
    apex = order[k]
    faces = []
    for i in range(len(first) - 1):
        a, b = first[i], first[i + 1]
        faces.append((a, b, apex) if _orient(P, a, b, apex) > 0 else (b, a, apex))
    # hull as a counterclockwise cycle
    if _orient(P, first[0], first[-1], apex) > 0:
        hull = list(first) + [apex]
    else:
        hull = [apex] + list(reversed(first))
        hull = hull[1:] + hull[:1]
    for v in order[k + 1:]:
        n = len(hull)
        visible = [_orient(P, hull[i], hull[(i + 1) % n], v) < 0 for i in range(n)]
        if not any(visible) or all(visible):
            continue                                   # on the hull within rounding: skipped
        s = next(i for i in range(n) if visible[i] and not visible[i - 1])
        t = s
        while visible[(t + 1) % n]:
            t += 1
        for i in range(s, t + 1):
            faces.append((hull[(i + 1) % n], hull[i % n], v))
        # hull[s] -> v -> hull[t + 1]: the vertices strictly inside the chain leave it
        hull = [hull[(t + 1 + j) % n] for j in range(n - (t - s))] + [v]
    return [tuple(f[::-1]) if _orient(P, *f) < 0 else f for f in faces]


def lawson_flips(P, faces, dtype):
    """Lawson's algorithm: flip every interior edge whose float in-circle test says the
    opposite vertex is inside, if the quadrilateral is convex (float orientation)."""
    faces = [list(f) for f in faces]
    where = {}
    for k, f in enumerate(faces):
        for c in range(3):
            where[(f[c], f[_nx(c)])] = k
    queue = deque(e for e in where if e[::-1] in where and e[0] < e[1])
    budget = 50 * len(faces) ** 2 + 1000
    while queue and budget > 0:
        a, b = queue.popleft()
        f, g = where.get((a, b)), where.get((b, a))
        if f is None or g is None:
            continue
        c = next(v for v in faces[f] if v not in (a, b))
        d = next(v for v in faces[g] if v not in (a, b))
        if not _incircle(P, a, b, c, d) > 0:
            continue
        if not (_orient(P, c, a, d) > 0 and _orient(P, d, b, c) > 0):
            continue
        budget -= 1
        for x in (f, g):
            for i in range(3):
                where.pop((faces[x][i], faces[x][_nx(i)]), None)
        faces[f], faces[g] = [c, a, d], [d, b, c]
        for x in (f, g):
            for i in range(3):
                where[(faces[x][i], faces[x][_nx(i)])] = x
        queue.extend([(min(a, d), max(a, d)), (min(d, b), max(d, b)),
                      (min(b, c), max(b, c)), (min(c, a), max(c, a))])
    return np.array(faces, dtype=np.int64).reshape(-1, 3)


# --- the panel -----------------------------------------------------------------------------------


class Atan2Cross(HonestMesh):
    name = "honest-atan2-cross"


class LawOfCosines(HonestMesh):
    name = "honest-law-of-cosines"
    angle_rule, area_rule, cot_rule = "cosines", "heron", "lengths"
    dihedral_rule, gradient_rule = "acos", "laplacian"


class KahanHalfAngle(HonestMesh):
    name = "honest-kahan-half-angle"
    angle_rule, area_rule, cot_rule = "kahan", "heron", "halfangle"
    dihedral_rule, gradient_rule = "kahan", "cross"


class Atan2Cross32(Atan2Cross):
    name, dtype, machine_epsilon = "honest-atan2-cross-f32", np.float32, 2.0 ** -23


class LawOfCosines32(LawOfCosines):
    name, dtype, machine_epsilon = "honest-law-of-cosines-f32", np.float32, 2.0 ** -23


class KahanHalfAngle32(KahanHalfAngle):
    name, dtype, machine_epsilon = "honest-kahan-half-angle-f32", np.float32, 2.0 ** -23


PANEL = {cls.name: cls for cls in (Atan2Cross, LawOfCosines, KahanHalfAngle,
                                   Atan2Cross32, LawOfCosines32, KahanHalfAngle32)}
