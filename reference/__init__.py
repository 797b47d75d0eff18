"""ddg_oracle.reference: exact discrete differential geometry after Bobenko's notes.

Standard library only; no float and no tolerance decides anything.  Data flows
one way: combinatorics -> metric -> operators -> algorithms.  Every public
function of the chapter modules is here under the name the notes use, each on
the fastest exact route for its quantity (the integer kernels of :mod:`.cotangents`,
:mod:`.cotan_fast` and :mod:`.curvature_fast` are internal routes of
``cotan_weights``, ``cotan_laplacian``, ``angle_sums``, ``angle_defects``,
``turning_angles``, ``total_curvature`` and ``gauss_bonnet_holds``; the
definitions they are tested against stay public: ``cotan_weights_from_corners``,
``cotan_laplacian_from_weights``, ``angle_sums_from_corners``,
``gauss_bonnet_holds_by_faces``).  Surfaces: :class:`Triangulation`
(combinatorics), :class:`PiecewiseFlatSurface` (lengths), :class:`PolyhedralSurface`
(positions); a function of an intrinsic quantity accepts both of the last two.

>>> import ddg_oracle.reference as R
>>> s = R.surfaces.icosahedron()
>>> R.gauss_bonnet_holds(s), R.total_curvature(s) == 4 * R.exact.pi
(True, True)
>>> R.is_delaunay(s), float(R.area(R.surfaces.cube()))
(True, 6.0)

Chapter by chapter (the modules keep their own ``__all__``):

- chapter 1: :mod:`.combinatorics`, :mod:`.surfaces`;
- chapter 2: :mod:`.metric`, :mod:`.polyhedral`, :mod:`.curvature`, :mod:`.geodesics`,
  :mod:`.rigidity`, :mod:`.intrinsic`
  (``flip`` there is ``intrinsic_flip`` here);
- chapter 3: :mod:`.laplacian`, :mod:`.sparse`, :mod:`.dirichlet`, :mod:`.areas`,
  :mod:`.minimal`;
- chapter 4: :mod:`.delaunay`, :mod:`.empty_disks`, :mod:`.triangulations`, :mod:`.planar`,
  :mod:`.rippa` (``energy_difference`` there is ``rippa_energy_difference`` here).
"""

from . import (areas, combinatorics, curvature, delaunay, dirichlet, empty_disks, errors, exact,
               geodesics, intrinsic, laplacian, metric, minimal, planar, polyhedral, rigidity,
               rippa, sparse, surfaces, triangulations)
from .areas import *  # noqa: F401,F403  (each module's __all__)
from .combinatorics import *  # noqa: F401,F403
from .curvature import *  # noqa: F401,F403
from .delaunay import *  # noqa: F401,F403
from .dirichlet import *  # noqa: F401,F403
from .empty_disks import *  # noqa: F401,F403
from .geodesics import *  # noqa: F401,F403
from .intrinsic import *  # noqa: F401,F403
from .intrinsic import flip as intrinsic_flip
from .laplacian import *  # noqa: F401,F403
from .metric import *  # noqa: F401,F403
from .minimal import *  # noqa: F401,F403
from .planar import *  # noqa: F401,F403
from .polyhedral import *  # noqa: F401,F403
from .rigidity import *  # noqa: F401,F403
from .rippa import *  # noqa: F401,F403
from .rippa import energy_difference as rippa_energy_difference
from .sparse import *  # noqa: F401,F403
from .triangulations import *  # noqa: F401,F403

# names that read ambiguously without their module stay in it only
_AMBIGUOUS = {"flip", "energy_difference"}
del flip, energy_difference  # noqa: F821  (star-imported above)

_CHAPTERS = (combinatorics, metric, polyhedral, curvature, geodesics, rigidity, intrinsic,
             laplacian, sparse, dirichlet, areas, minimal, delaunay, empty_disks, triangulations, planar,
             rippa)
__all__ = sorted({name for m in _CHAPTERS for name in m.__all__} - _AMBIGUOUS
                 | {"intrinsic_flip", "rippa_energy_difference", "errors", "exact", "surfaces"})
