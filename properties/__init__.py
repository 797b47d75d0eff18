"""Hypothesis strategies of meshes and implementation-agnostic properties, one per catalog ID.

Importing this package registers our properties in our own registry and
nothing else: no Hypothesis profile is loaded or registered (see
:mod:`.profiles`), so a user's own ``@given`` tests keep their settings.

Use from your own tests::

    from ddg_oracle.properties import check_implementation
    check_implementation(MyImplementation())          # raises AssertionError on failure

or draw meshes for your own properties::

    from hypothesis import given
    from ddg_oracle.properties import any_meshes

    @given(any_meshes())
    def test_mine(case):
        V, F = case.arrays()                          # float64 n x 3, int64 m x 3
"""

from .registry import PROPERTIES, Property, PropertyFailure, TieDisagreement, all_properties
from .runner import check_implementation, run_properties
from .strategies import (CurvatureCase, MeshCase, SurfaceCase, acute_meshes, any_meshes,
                         closed_meshes, closed_surfaces, jittered_grids, jittered_surfaces,
                         named_surfaces, obtuse_meshes, planar_meshes, scaled_meshes,
                         single_triangles, surface_meshes, triangulated_surfaces, weighted_graphs,
                         with_functions, with_isolated)
# strategies that live beside the properties they serve (star kinds, Delaunay flips, flat tori)
from .curvature import rational_motions, vertex_stars
from .delaunay import delaunay_meshes, flipped_meshes, two_triangulations
from .metrics import flat_tori, polycube_surfaces, randomly_flipped
from .planar_points import integer_point_sets, integer_quadrilaterals, rational_point_sets

all_properties()        # registers every property, so PROPERTIES is complete on import

__all__ = ["PROPERTIES", "Property", "PropertyFailure", "TieDisagreement", "all_properties",
           "check_implementation", "run_properties", "SurfaceCase", "closed_surfaces", "named_surfaces",
           "triangulated_surfaces", "jittered_surfaces", "rational_motions", "vertex_stars",
           "delaunay_meshes", "flipped_meshes", "two_triangulations", "MeshCase", "CurvatureCase",
           "surface_meshes", "with_isolated", "acute_meshes",
           "any_meshes", "closed_meshes", "jittered_grids", "obtuse_meshes", "planar_meshes",
           "scaled_meshes", "single_triangles", "weighted_graphs", "with_functions", "flat_tori",
           "polycube_surfaces", "randomly_flipped", "integer_point_sets", "integer_quadrilaterals",
           "rational_point_sets"]
