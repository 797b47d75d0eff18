"""scipy.spatial (Qhull) on the reference's conventions: planar Delaunay triangulations.

``planar_delaunay(P)`` is ``scipy.spatial.Delaunay(P).simplices``: Qhull's
triangulated output (scipy passes ``Qbb Qc Qz Q12`` and always ``Qt`` in 2D,
scipy/spatial/_qhull.pyx), indices into P, orientation not fixed.  The
properties compare it with the exact planar Delaunay tessellation as a
tessellation: how a cocircular cell is split into triangles is not compared.
"""

from __future__ import annotations


import numpy as np
import scipy.spatial


#: this adapter as ``ddg-oracle check --impl scipy`` finds it (read without importing the
#: module: ddg_oracle.application.implementations): the object, the library it needs (None: the
#: core's own dependencies), the pip extra that installs it, its place in reports
ADAPTER = {"name": "scipy", "object": "ScipySpatial", "library": "scipy", "extra": None,
           "rank": 3}


class ScipySpatial:
    name = "scipy"

    def planar_delaunay(self, P) -> np.ndarray:
        P = np.asarray(P, dtype=np.float64)
        if P.ndim != 2 or P.shape[1] != 2:
            raise ValueError(f"points must be an (n, 2) array, got shape {P.shape}")
        if not np.all(np.isfinite(P)):
            raise ValueError("non-finite point coordinate")
        return np.asarray(scipy.spatial.Delaunay(P).simplices, dtype=np.int64)
