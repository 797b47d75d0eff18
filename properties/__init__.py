"""Hypothesis strategies of meshes and implementation-agnostic properties, one per catalog ID.

Use from your own tests::

    from properties import check_implementation
    check_implementation(MyImplementation())          # raises AssertionError on failure
"""

from . import profiles  # noqa: F401  (registers the default / ci / thorough profiles)
from .registry import PROPERTIES, Property, PropertyFailure, TieDisagreement, all_properties
from .runner import check_implementation, run_properties
from .strategies import (SurfaceCase, closed_surfaces, named_surfaces, triangulated_surfaces)

all_properties()        # registers every property, so PROPERTIES is complete on import

__all__ = ["PROPERTIES", "Property", "PropertyFailure", "TieDisagreement", "all_properties",
           "check_implementation", "run_properties", "SurfaceCase", "closed_surfaces", "named_surfaces",
           "triangulated_surfaces"]
