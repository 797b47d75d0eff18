"""Library conventions an adapter may select instead of the reference's.

An adapter option such as ``boundary="library"`` makes the adapter return the
library's own value where it follows another convention than the notes (each
documented in docs/findings.md and docs/conventions.md).  ``ddg-oracle check
--expect-conventions`` reports a failure of such an option as "convention" when
the same adapter with reference conventions passes the same example.
"""

from __future__ import annotations

#: Adapter options that select a library's own convention instead of the
#: reference's, each with the finding that documents the difference
#: (docs/findings.md, docs/conventions.md).  ``ddg-oracle check
#: --expect-conventions`` reports a failure of such a spec as "convention" when
#: the same spec without the option passes the same example.
DOCUMENTED_CONVENTIONS: dict[str, dict[tuple[str, str], str]] = {
    "libigl": {("boundary", "library"): "L2 (gaussian_curvature: 2 pi - angle sum at "
                                        "boundary vertices)"},
    "pymeshlab": {("boundary", "library"): "P2 (boundary term 2 pi - angle sum - phi)",
                  ("genus", "library"): "P1 (genus of a non-orientable mesh is floor(h / 2))"},
    "gpytoolbox": {("boundary", "library"): "G1 (angle_defect: 0 at boundary vertices)",
                   ("dihedral", "library"): "G2 (dihedral_angles: unsigned, reflex edges "
                                            "count as convex)"},
    "robust_laplacian": {("boundary", "library"): "R1 (tufted cover: boundary edges are "
                                                  "flipped in the double of the surface)",
                         ("mollify", "library"): "R3 (mollify_factor 1e-5 lengthens every "
                                                 "edge of a nearly degenerate mesh)"},
    "trimesh": {("boundary", "library"): "TM1 (vertex_defects: 2 pi - angle sum at boundary "
                                         "vertices)"},
}

#: The values of an adapter's convention option: the reference's or the library's own.
CONVENTIONS = ("reference", "library")


def convention_name(base: str, **options: str) -> str:
    """Display name of an adapter with convention options (each one of CONVENTIONS):
    ``base`` if all are "reference", else the non-default ones in parentheses.

    >>> convention_name("gpytoolbox", boundary="library", dihedral="reference")
    "gpytoolbox(boundary='library')"
    >>> convention_name("gpytoolbox", boundary="lib")
    Traceback (most recent call last):
    ...
    ValueError: boundary must be one of ('reference', 'library'), got 'lib'
    """
    for key, value in options.items():
        if value not in CONVENTIONS:
            raise ValueError(f"{key} must be one of {CONVENTIONS}, got {value!r}")
    chosen = [f"{k}={v!r}" for k, v in options.items() if v != "reference"]
    return f"{base}({', '.join(chosen)})" if chosen else base
