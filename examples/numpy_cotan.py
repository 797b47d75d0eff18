"""A cotan Laplacian written the obvious way with numpy: what a user checks with ddg-oracle.

    ddg-oracle check --impl examples.numpy_cotan:NumpyCotan
    pytest --ddg-impl examples.numpy_cotan:NumpyCotan

The planted variants below are the bugs people write (sign, boundary factor, wrong
corner, an absolute threshold that breaks on small meshes); the tests show that each is
caught, with a counterexample that shrinks to a triangle or two.
"""

import numpy as np
import scipy.sparse as sp


class NumpyCotan:
    name = "numpy-cotan"
    sign, boundary_half, swap, guard = 1.0, True, False, 0.0

    def cotan_laplacian(self, V, F):
        V, F = np.asarray(V, float), np.asarray(F)
        n, rows, cols, vals = len(V), [], [], []
        for c in range(3):                       # corner c, opposite edge (i, j)
            k, i, j = F[:, c], F[:, (c + 1) % 3], F[:, (c + 2) % 3]
            u, v = V[i] - V[k], V[j] - V[k]
            if self.swap:                        # bug: the angle at i instead of at k
                u, v = V[k] - V[i], V[j] - V[i]
            # bug when guard > 0: a "safe" division with an absolute threshold
            cot = (u * v).sum(1) / np.maximum(np.linalg.norm(np.cross(u, v), axis=1), self.guard)
            rows += [i, j]
            cols += [j, i]
            vals += [cot / 2, cot / 2]
        W = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                          shape=(n, n))
        if not self.boundary_half:               # bug: boundary edges get cot, not 1/2 cot
            ones = np.ones(len(np.concatenate(rows)))
            count = sp.csr_matrix((ones, (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))
            W = W + W.multiply(count == 1)       # an edge seen from one face only: doubled
        L = sp.diags(np.asarray(W.sum(axis=1)).ravel()) - W
        return self.sign * L


class SignError(NumpyCotan):
    name, sign = "numpy-cotan-sign-error", -1.0


class BoundaryWithoutHalf(NumpyCotan):
    name, boundary_half = "numpy-cotan-boundary-without-half", False


class WrongCorner(NumpyCotan):
    name, swap = "numpy-cotan-wrong-corner", True


class AbsoluteThreshold(NumpyCotan):
    name, guard = "numpy-cotan-absolute-threshold", 1e-12
