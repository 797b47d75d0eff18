"""Input arrays as adapters hand them to libraries: checked first, because some
libraries segfault on a bad index instead of raising.

:func:`checked_arrays` checks what a library cannot survive or would silently
misread: shapes, dtypes (a float index would be truncated), index range, NaN
and infinite coordinates.  It raises the reference's typed errors
(:mod:`ddg_oracle.reference.errors`, all ``ValueError``), naming the face and corner or
the vertex and coordinate, with the same wording as the reference.  Mesh-level
properties (repeated vertex in a face, non-manifold edges and vertices,
unreferenced vertices, zero-area faces) are left to the library on purpose:
how it handles them is part of what a check observes.
"""

from __future__ import annotations

import numpy as np

from ..reference.errors import (BadShape, EmptyMesh, IndexOutOfRange, NegativeIndex,
                              NonFiniteValue, NonIntegerIndex, NotANumber)
from ..reference.combinatorics import corner_of, face_of


def _array(x, what: str) -> np.ndarray:
    try:
        return np.asarray(x)
    except ValueError as e:          # ragged nested lists
        raise BadShape(f"{what} is not a rectangular array: {e}") from None


def checked_arrays(V, F) -> tuple[np.ndarray, np.ndarray]:
    """(V float64 C-contiguous n x 3, F int64 C-contiguous m x 3), or an InputError saying why.

    >>> V, F = checked_arrays([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    >>> V.dtype, F.dtype, F.shape
    (dtype('float64'), dtype('int64'), (1, 3))
    >>> checked_arrays([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 3]])
    Traceback (most recent call last):
    ...
    ddg_oracle.reference.errors.IndexOutOfRange: face 0, corner 2: vertex index 3 >= number of vertices 3
    """
    V = _array(V, "V")
    F = _array(F, "F")
    if V.size == 0:
        raise EmptyMesh(f"V has no vertices (shape {V.shape})")
    if V.ndim != 2 or V.shape[1] != 3:
        raise BadShape(f"V must be n x 3, got shape {V.shape}")
    if V.dtype == object:
        V = _array(V.tolist(), "V")      # Python numbers: let numpy pick the dtype
    if V.dtype == bool or not (np.issubdtype(V.dtype, np.integer)
                               or np.issubdtype(V.dtype, np.floating)):
        raise NotANumber(f"V has dtype {V.dtype}; coordinates must be real numbers")
    if F.size == 0:
        raise EmptyMesh(f"F has no faces (shape {F.shape})")
    if F.ndim != 2 or F.shape[1] != 3:
        raise BadShape(f"F must be m x 3, got shape {F.shape}")
    if F.dtype == object:
        F = _array(F.tolist(), "F")
    if F.dtype == bool or not np.issubdtype(F.dtype, np.integer):
        # a cast would truncate 1.5 to 1 and turn NaN into -2**63
        flat = F.reshape(-1).tolist()
        k = next((k for k, x in enumerate(flat)
                  if not (isinstance(x, float) and x.is_integer())), 0)
        raise NonIntegerIndex(f"F has dtype {F.dtype} (face {face_of(k)}, corner {corner_of(k)} is "
                              f"{flat[k]!r}); face indices must be integers")
    # range before the int64 cast: a uint64 index above 2**63 would wrap negative
    n = V.shape[0]
    bad = np.argwhere(F < 0)
    if len(bad):
        f, c = (int(k) for k in bad[0])
        raise NegativeIndex(f"face {f}, corner {c}: negative vertex index {int(F[f, c])}")
    bad = np.argwhere(F >= n)
    if len(bad):
        f, c = (int(k) for k in bad[0])
        raise IndexOutOfRange(f"face {f}, corner {c}: vertex index {int(F[f, c])} "
                              f">= number of vertices {n}")
    V = np.ascontiguousarray(V, dtype=np.float64)
    bad = np.argwhere(~np.isfinite(V))
    if len(bad):
        i, j = (int(k) for k in bad[0])
        raise NonFiniteValue(f"V has NaN or infinite coordinates: non-finite value {V[i, j]} "
                             f"at vertex {i}, coordinate {j}")
    return V, np.ascontiguousarray(F, dtype=np.int64)


class Referenced:
    """The vertices a face uses, for a library (or the reference) that refuses or drops the
    others: ``V``, ``F`` compacted to them, ``keep[v]`` the input index of compact vertex v.

    Answers are put back on the input's indices with the protocol's values at the
    isolated vertices (:data:`ddg_oracle.protocol.methods.ISOLATED_VERTEX`).

    >>> r = Referenced([[0, 0, 0], [5, 5, 5], [1, 0, 0], [0, 1, 0]], [[0, 2, 3]])
    >>> r.keep.tolist(), r.F.tolist(), r.isolated
    ([0, 2, 3], [[0, 1, 2]], 1)
    >>> r.scatter([1.0, 2.0, 3.0], fill=9.0).tolist()
    [1.0, 9.0, 2.0, 3.0]
    """

    def __init__(self, V, F):
        V, F = checked_arrays(V, F)
        self.n = V.shape[0]
        self.keep = np.unique(F)
        self.isolated = self.n - len(self.keep)
        if self.isolated:
            new = np.full(self.n, -1, dtype=np.int64)
            new[self.keep] = np.arange(len(self.keep))
            V, F = V[self.keep], new[F]
        self.V, self.F = V, F

    def scatter(self, values, fill: float) -> np.ndarray:
        """Per compact vertex values -> per input vertex, ``fill`` at the isolated ones."""
        values = np.asarray(values, dtype=np.float64)
        if not self.isolated:
            return values
        out = np.full(self.n, fill, dtype=np.float64)
        out[self.keep] = values
        return out

    def embed(self, M):
        """A compact (k, k) sparse matrix -> (n, n), zero rows and columns at isolated vertices."""
        if not self.isolated:
            return M
        import scipy.sparse as sp
        C = sp.coo_matrix(M)
        return sp.csr_matrix((C.data, (self.keep[C.row], self.keep[C.col])), shape=(self.n, self.n))

    def index(self, v) -> int:
        """The input index of compact vertex v."""
        return int(self.keep[v])


def boundary_edges(F: np.ndarray) -> np.ndarray:
    """(k, 2) sorted vertex pairs of the edges with exactly one face: the boundary edges
    (their ends are where R2.4 takes the turning angle), for adapters mapping a library's
    boundary convention."""
    pairs = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
    uniq, counts = np.unique(pairs, axis=0, return_counts=True)
    return uniq[counts == 1]
