"""PyTorch Geometric's mesh Laplacian (``torch_geometric.utils.get_mesh_laplacian``) in its
own conventions.

``get_mesh_laplacian(pos, face, normalization=None)`` returns ``(edge_index, edge_weight)``:
the cotangent matrix C of its docstring, C_ij = (cot a + cot b) / 2 on an edge and
C_ii = -sum_j C_ij, as a sparse edge list (``torch_geometric/utils/mesh_laplacian.py``).
That is the notes' Laplacian with the other sign: negative semidefinite, the factor 1/2 the
notes'.  Declared: ``conventions = {"laplacian": "negative"}``; ddg-oracle maps it back.

How it computes (the installed ``torch_geometric/utils/mesh_laplacian.py`` of 2.8.1): per
corner, the edge vectors to the other two vertices u, v and ``cot / 2 = (u . v) / |u x v| /
2`` (``get_cots``), on the opposite edge; ``to_undirected`` adds an edge's two faces; the
diagonal is minus the row sum (``scatter``, ``add_self_loops``).  A vertex used by no face
gets a zero row, as the protocol's.  (The development branch computes the third edge vector
of a face as ``-(e_21 + e_02)`` and the cotangents over 4 A instead: a later release is
checked by the same tests.)

The positions are handed over as float64 tensors (``torch.from_numpy``), so the
computation is in float64 (its default dtype, float32, would be the caller's choice:
``pos.float()``); the faces as the 3 x m int64 tensor PyG expects.  ``normalization``
("sym", "rw": the barycentric mass M^-1/2 C M^-1/2 or M^-1 C) is not a protocol method.

Install: ``pip install 'ddg-oracle[torch-geometric]'`` (not in ``all``: torch is a
download of several GB unless a CPU build is at hand, e.g. ``pip install torch==2.13.0
--index-url https://download.pytorch.org/whl/cpu`` first).

>>> import numpy as np
>>> V = np.array([[0., 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
>>> F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
>>> C = TorchGeometric().cotan_laplacian(V, F)
>>> C.shape, float(C[0, 1]), bool(abs(C.sum()) < 1e-15)
((4, 4), 1.0, True)
"""

from __future__ import annotations

import numpy as np
import scipy.sparse
import torch
from torch_geometric.utils import get_mesh_laplacian

from ..protocol.arrays import checked_arrays

#: this adapter as ``ddg-oracle check --impl torch_geometric`` finds it (read without
#: importing the module: ddg_oracle.application.implementations): the object, the library it needs,
#: the pip extra that installs it, its place in reports
ADAPTER = {"name": "torch_geometric", "object": "TorchGeometric", "library": "torch_geometric",
           "extra": "torch-geometric", "rank": 14}


class TorchGeometric:
    """PyTorch Geometric as an implementation of the protocol (``protocol/methods.py``)."""

    name = "torch_geometric"
    conventions = {"laplacian": "negative"}      # C = -L (module doc)

    def __repr__(self) -> str:
        return "TorchGeometric()"

    def cotan_laplacian(self, V, F) -> scipy.sparse.csr_matrix:
        """``get_mesh_laplacian(pos, face)`` as an n x n CSR matrix (C, declared negative)."""
        V, F = checked_arrays(V, F)
        pos = torch.from_numpy(V)
        face = torch.from_numpy(np.ascontiguousarray(F.T))
        index, weight = get_mesh_laplacian(pos, face)
        rows, cols = index.numpy()
        n = len(V)
        return scipy.sparse.csr_matrix((weight.numpy(), (rows, cols)), shape=(n, n))
