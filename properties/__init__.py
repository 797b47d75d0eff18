"""Hypothesis strategies of meshes and implementation-agnostic properties, one per catalog ID.

Modules by kind: the strategies (:mod:`.strategies`, the shared ones; :mod:`.stars`,
:mod:`.flipped`, :mod:`.metrics` and :mod:`.planar_points`, those of one chapter;
:mod:`.point_sets`, those of the notes' statements); the check modules (:mod:`.topology`,
:mod:`.curvature`, :mod:`.laplacian`, :mod:`.delaunay`: the ``@prop`` checks and the
``quantity`` declarations only; :mod:`.statements` and :mod:`.structure`: the assertion
checks of the reference itself only); the expected values and bounds (:mod:`.views`,
:mod:`.harness`, :mod:`.bounds`, :mod:`.delaunay_exact`, :mod:`.curvature_exact`,
:mod:`.ties`).  Data flows one way: no strategy or expected-value module imports a check
module.

Importing this package registers our properties in our own registry and
nothing else: no Hypothesis profile is loaded or registered (see
:mod:`.profiles`), so a user's own ``@given`` tests keep their settings.
The public names are loaded when first used (PEP 562): a process that needs
only a small module (an isolated library worker importing :mod:`.protocol` or
:mod:`.budget`) does not import Hypothesis and every property with it.

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

#: public name -> the module defining it (the strategies of one chapter's properties live in
#: strategy modules of their own, never in a check module: star kinds and rigid motions in
#: stars, Delaunay flips in flipped, flat tori in metrics, planar point sets in planar_points)
_PUBLIC = {
    **dict.fromkeys(["PROPERTIES", "Property", "PropertyFailure", "TieDisagreement",
                     "all_properties"], "registry"),
    **dict.fromkeys(["check_implementation", "run_properties"], "runner"),
    **dict.fromkeys(["Example"], "example"),
    **dict.fromkeys(["acute_meshes", "any_meshes",
                     "closed_meshes", "closed_surfaces", "jittered_grids", "jittered_surfaces",
                     "named_surfaces", "obtuse_meshes", "planar_meshes", "scaled_meshes",
                     "single_triangles", "surface_meshes", "triangulated_surfaces",
                     "weighted_graphs", "with_functions", "with_isolated"], "strategies"),
    **dict.fromkeys(["rational_motions", "vertex_stars"], "stars"),
    **dict.fromkeys(["delaunay_meshes", "flipped_meshes", "two_triangulations"], "flipped"),
    **dict.fromkeys(["flat_tori", "polycube_surfaces", "randomly_flipped"], "metrics"),
    **dict.fromkeys(["integer_point_sets", "integer_quadrilaterals", "rational_point_sets"],
                    "planar_points"),
}

__all__ = list(_PUBLIC)


def __getattr__(name: str):
    module = _PUBLIC.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    import importlib
    from .registry import all_properties
    all_properties()        # every property registered: PROPERTIES is complete once it is seen
    value = getattr(importlib.import_module(f"{__name__}.{module}"), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_PUBLIC))
