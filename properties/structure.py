"""Structural properties of the reference's own data structures (catalog rows that
concern the representation rather than a computed quantity).

They take reference objects, not an implementation, and raise AssertionError
naming the catalog ID.  D1.4's triangulations flipped without keeping them regular are
drawn by :mod:`.flipped` (:func:`~.flipped.unrestricted_flips`, :func:`~.flipped.flip_freely`).
"""

from __future__ import annotations

from ..reference.combinatorics import Triangulation


def regularity_predicates(t: Triangulation) -> None:
    """D1.4: regular = no loops; strongly regular = also no double edges, no repeated faces.

    Checked against an independent scan of the edge list, and the halfedge
    structure stays valid (twin is an involution with matching endpoints).
    """
    ends = [t.edge_vertices(e) for e in range(t.n_edges)]
    loops = any(a == b for a, b in ends)
    pairs = [frozenset(p) for p in ends]
    double = len(set(pairs)) != len(pairs)
    faces = [frozenset(f) for f in t.faces]
    repeated_face = len(set(faces)) != len(faces)
    assert t.is_regular() == (not loops), "D1.4: is_regular disagrees with the loop scan"
    assert t.is_strongly_regular() == (not loops and not double and not repeated_face), \
        "D1.4: is_strongly_regular disagrees with the edge and face scan"
    for h in range(3 * t.n_faces):
        g = t.twin(h)
        if g < 0:
            continue
        assert t.twin(g) == h, f"D1.4: twin is not an involution at halfedge {h}"
        same = {t.tail(h), t.head(h)} == {t.tail(g), t.head(g)}
        assert same, f"D1.4: glued halfedges {h}, {g} have different endpoints"


def intrinsic_flip_keeps_the_metric(surface, e: int) -> None:
    """L2.8 / X2.5: an edge flips iff interior, two distinct faces and a strictly convex
    unfolding; the flip keeps every vertex's angle sum and the total area exactly,
    every face satisfies the strict triangle inequality, and flipping back restores
    the squared lengths.
    """
    from ..reference.errors import NotFlippable
    from ..reference.exact import corner_angle
    from ..reference.intrinsic import flip, is_flippable
    from ..reference.metric import heron16

    def sums(m):
        t = m.triangulation
        return [sum((corner_angle(m.corner_cot(f, c)) for f, c in t.corners_around(v)), 0 * corner_angle(1))
                for v in range(t.n_vertices)]

    if not is_flippable(surface, e):
        try:
            flip(surface, e)
        except NotFlippable:
            return
        raise AssertionError(f"L2.8: edge {e} is not flippable but flip() accepted it")
    m = flip(surface, e)
    assert sums(m) == sums(surface), f"L2.8: flipping edge {e} changed an angle sum"
    assert m.total_area() == surface.total_area(), f"L2.8: flipping edge {e} changed the area"
    for f in range(m.triangulation.n_faces):
        assert heron16(*m.face_squared_lengths(f)) > 0, f"L2.8: face {f} degenerate after flip"
    back = flip(m, e)
    assert sorted(map(str, back.squared_lengths)) == sorted(map(str, surface.squared_lengths)), \
        f"L2.8: flipping edge {e} twice did not restore the lengths"
