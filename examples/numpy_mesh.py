"""A correct float64 implementation of the curvature and Laplacian methods, written the plain
way with numpy: what a library does, and what the properties must never fail (the
false-positive test, tests/test_false_positives.py).

    ddg-oracle check --impl examples.numpy_mesh:NumpyMesh

Conventions as the protocol's: corner angles by atan2(|a x b|, a . b); boundary edges
are the edges of one face (unordered: right for any orientation, a Möbius strip
included); a vertex used by no face gets 2 pi - 0 and area 0, since the sums below
start at zero for every vertex.
"""

import math

import numpy as np

from examples.numpy_cotan import NumpyCotan


class NumpyMesh(NumpyCotan):
    name = "numpy-mesh"

    @staticmethod
    def corner_angles(V, F):
        V, F = np.asarray(V, float), np.asarray(F)
        X = V[F]
        out = np.empty(F.shape)
        for c in range(3):
            a, b = X[:, (c + 1) % 3] - X[:, c], X[:, (c + 2) % 3] - X[:, c]
            out[:, c] = np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), (a * b).sum(axis=1))
        return out

    @staticmethod
    def _boundary(V, F):
        count = {}
        for f in np.asarray(F).tolist():
            for c in range(3):
                e = tuple(sorted((f[c], f[(c + 1) % 3])))
                count[e] = count.get(e, 0) + 1
        b = np.zeros(len(V), dtype=bool)
        for (i, j), k in count.items():
            if k == 1:
                b[i] = b[j] = True
        return b

    def angle_defects(self, V, F):
        F = np.asarray(F)
        sums = np.zeros(len(V))
        np.add.at(sums, F.reshape(-1), self.corner_angles(V, F).reshape(-1))
        return np.where(self._boundary(V, F), np.pi, 2 * np.pi) - sums

    @staticmethod
    def edge_mean_curvature(V, F):
        V, F = np.asarray(V, float), np.asarray(F)
        X = V[F]
        N = np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0])
        N /= np.linalg.norm(N, axis=1)[:, None]
        face_of = {(f[c], f[(c + 1) % 3]): k for k, f in enumerate(F.tolist()) for c in range(3)}
        out = {}
        for (i, j), f in face_of.items():
            g = face_of.get((j, i))
            if g is not None and i < j:
                e = V[j] - V[i]
                length = float(np.linalg.norm(e))
                theta = math.atan2(float(np.cross(N[f], N[g]) @ e) / length, float(N[f] @ N[g]))
                out[(i, j)] = 0.5 * theta * length
        return out

    @staticmethod
    def area(V, F):
        V, F = np.asarray(V, float), np.asarray(F)
        X = V[F]
        return 0.5 * float(np.linalg.norm(np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]), axis=1).sum())

    @staticmethod
    def vertex_areas_barycentric(V, F):
        V, F = np.asarray(V, float), np.asarray(F)
        X = V[F]
        third = np.linalg.norm(np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]), axis=1) / 6
        out = np.zeros(len(V))
        np.add.at(out, F, third[:, None])
        return out

    @staticmethod
    def area_gradient(V, F):
        # no cotangent: per face, grad_{v_i} A = 1/2 n x (v_k - v_j) (L3.8), n the unit normal
        V, F = np.asarray(V, float), np.asarray(F)
        X = V[F]
        N = np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0])
        N /= np.linalg.norm(N, axis=1)[:, None]
        out = np.zeros_like(V)
        for c in range(3):
            j, k = (c + 1) % 3, (c + 2) % 3
            np.add.at(out, F[:, c], 0.5 * np.cross(N, X[:, k] - X[:, j]))
        return out

    def solve_dirichlet(self, V, F, boundary, values):
        # the Dirichlet problem with the cotan Laplacian: L_II u_I = -L_IB c (sparse LU)
        import scipy.sparse.linalg as sla
        L = self.cotan_laplacian(V, F).tocsr()
        boundary = np.asarray(boundary, dtype=np.int64)
        u = np.zeros(L.shape[0])
        u[boundary] = values
        inner = np.setdiff1d(np.arange(L.shape[0]), boundary)
        if len(inner):
            u[inner] = sla.spsolve(L[inner][:, inner].tocsc(), -(L[inner][:, boundary] @ u[boundary]))
        return u
