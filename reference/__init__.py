"""ddg-oracle reference: exact discrete differential geometry after Bobenko's notes.

Standard library only; no float and no tolerance decides anything.  Data flows
one way: combinatorics -> metric -> operators -> algorithms.

>>> from ddg_oracle.reference import surfaces
>>> surfaces.tetrahedron().triangulation.euler_characteristic()
2
"""

from . import errors, exact, surfaces
from .combinatorics import Classification, Triangulation, connected_sum
from .metric import PiecewiseFlatSurface
from .polyhedral import PolyhedralSurface

__all__ = ["Classification", "PiecewiseFlatSurface", "PolyhedralSurface", "Triangulation",
           "connected_sum", "errors", "exact", "surfaces"]
