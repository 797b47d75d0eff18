"""Hypothesis strategies for meshes.

Strategies draw a few small integers (genus, number of holes, which edges to
flip, which refinement to apply) and *construct* the surface from the
reference's exact constructors, so a failing example shrinks toward a
tetrahedron-sized mesh.  Every example knows its true topology from how it was
built, independently of any counting.
"""

from __future__ import annotations

import random
from dataclasses import dataclass
from fractions import Fraction

from hypothesis import strategies as st

from ddg_oracle.reference import surfaces
from ddg_oracle.reference.combinatorics import Classification, Triangulation, connected_sum
from ddg_oracle.reference.errors import InputError, NotFlippable


@dataclass(frozen=True)
class SurfaceCase:
    """A triangulated surface whose topology is known by construction.

    ``positions`` are points in R^3 for every vertex (exact where the surface
    embeds; for abstract surfaces such as RP^2 they are arbitrary distinct
    points, since only the combinatorics matter for topology).
    """

    triangulation: Triangulation
    positions: tuple
    expected: Classification
    recipe: str

    @property
    def faces(self) -> list[list[int]]:
        return [list(f) for f in self.triangulation.faces]

    @property
    def vertices(self) -> list[list[float]]:
        return [[float(x) for x in p] for p in self.positions]

    def arrays(self):
        """(V float64 n x 3, F int64 m x 3) numpy arrays, as implementations take them."""
        import numpy as np
        return (np.array(self.vertices, dtype=np.float64).reshape(-1, 3),
                np.array(self.faces, dtype=np.int64).reshape(-1, 3))

    def __repr__(self) -> str:
        t = self.triangulation
        return f"SurfaceCase({self.recipe}; V={t.n_vertices}, F={t.n_faces}, F={self.faces})"


def expected_classification(orientable: bool, genus: int, holes: int) -> Classification:
    """Classification of the connected sum of ``genus`` tori (or crosscaps) minus ``holes`` disks."""
    chi = (2 - 2 * genus if orientable else 2 - genus) - holes
    return Classification(orientable, genus, holes, chi)


def base_surface(orientable: bool, genus: int) -> Triangulation:
    """A closed surface: sphere, # of `genus` tori, or # of `genus` projective planes (T1.1)."""
    if orientable:
        if genus == 0:
            return surfaces.tetrahedron().triangulation
        piece = surfaces.torus(3, 3).triangulation
    else:
        if genus < 1:
            raise ValueError("a non-orientable surface has at least one crosscap")
        piece = surfaces.projective_plane()
    t = piece
    for _ in range(genus - 1):
        t = connected_sum(t, piece)
    return t


def punch_holes(t: Triangulation, holes: int, start: int = 0) -> Triangulation:
    """Remove ``holes`` faces far apart (CS: each removal lowers chi by 1, adds a boundary loop)."""
    done = 0
    while done < holes:
        if t.n_faces < 8 * (holes + 1):
            t, _ = t.subdivide_1to4()
            continue
        for i in range(t.n_faces):
            f = (start + i) % t.n_faces
            # a face touching a hole would make its vertex non-manifold
            if any(t.is_boundary_vertex(v) for v in t.faces[f]):
                continue
            t = t.remove_face(f)
            done += 1
            break
        else:
            t, _ = t.subdivide_1to4()        # no room left: refine and go on
    return t


def surface_moves(max_size: int = 4):
    """Lists of refinement and flip moves: (name, integer choosing where)."""
    return st.lists(
        st.tuples(st.sampled_from(["flip", "split", "1to4"]), st.integers(0, 1 << 16)),
        max_size=max_size)


def apply_moves(t: Triangulation, moves, regular: bool = True) -> Triangulation:
    """Apply edge flips, edge splits and 1-to-4 subdivisions (R1.5: none changes chi).

    With ``regular`` a flip that would create a loop or a double edge is skipped,
    so the result stays a simplicial complex (what array-based libraries accept).
    """
    for kind, where in moves:
        if kind == "1to4":
            if t.n_faces <= 400:
                t, _ = t.subdivide_1to4()
        elif kind == "split":
            t, _ = t.split_edge(where % t.n_edges)
        else:
            for i in range(t.n_edges):
                e = (where + i) % t.n_edges
                if t.is_boundary_edge(e):
                    continue
                try:
                    u = t.flip(e)
                except NotFlippable:
                    continue
                if not regular or u.is_strongly_regular():
                    t = u
                    break
    return t


def extend_positions(t: Triangulation, positions) -> tuple:
    """Keep the given points for the old vertices, add distinct points for new ones."""
    return tuple(positions) + _placeholder_positions(t)[len(positions):]


def _placeholder_positions(t: Triangulation) -> tuple:
    # Distinct points on the moment curve: no three collinear, no four coplanar.
    return tuple((Fraction(i), Fraction(i * i), Fraction(i * i * i)) for i in range(t.n_vertices))


def _relabel(t: Triangulation, positions, key: int):
    if key == 0:
        return t, positions
    perm = list(range(t.n_vertices))
    random.Random(key).shuffle(perm)
    inverse = [0] * len(perm)
    for v, w in enumerate(perm):
        inverse[w] = v
    return t.relabelled(perm), tuple(positions[inverse[w]] for w in range(len(perm)))


@st.composite
def triangulated_surfaces(draw, orientable=None, genus=None, holes=None,
                          max_genus: int = 2, max_holes: int = 2, moves: bool = True,
                          relabel: bool = True):
    """A :class:`SurfaceCase`: any topology (orientable or not, genus, holes), refined and flipped.

    Fixed arguments pin the topology; the rest is drawn.  The combinatorics are
    always a simplicial complex (strongly regular), as array-based libraries expect.
    """
    if max_genus < 0 or max_holes < 0:
        raise ValueError("max_genus and max_holes must be >= 0")
    o = draw(st.booleans()) if orientable is None else bool(orientable)
    lowest = 0 if o else 1
    g = draw(st.integers(lowest, max(lowest, max_genus))) if genus is None else int(genus)
    if g < lowest:
        raise ValueError(f"genus {g} impossible for a {'non-' if not o else ''}orientable surface")
    k = draw(st.integers(0, max_holes)) if holes is None else int(holes)
    t = base_surface(o, g)
    recipe = (f"{'genus' if o else 'crosscaps'} {g}")
    if moves:
        ms = draw(surface_moves())
        t = apply_moves(t, ms)
        if ms:
            recipe += f", moves {ms}"
    if k:
        start = draw(st.integers(0, 1 << 16))
        t = punch_holes(t, k, start)
        recipe += f", {k} hole(s)"
    positions = _placeholder_positions(t)
    if relabel:
        key = draw(st.integers(0, 1 << 16))
        t, positions = _relabel(t, positions, key)
    return SurfaceCase(t, positions, expected_classification(o, g, k), recipe)


def closed_surfaces(**kw):
    """Closed surfaces of any (or the given) orientability and genus."""
    return triangulated_surfaces(holes=0, **kw)


_NAMED = {
    "disk": lambda: surfaces.disk(6),
    "sphere (tetrahedron)": surfaces.tetrahedron,
    "sphere (icosahedron)": surfaces.icosahedron,
    "torus": lambda: surfaces.torus(4, 3),
    "double torus": lambda: surfaces.genus_surface(2),
    "annulus": lambda: surfaces.annulus(5),
    "Möbius strip": lambda: surfaces.mobius_strip(5),
}


def named_surfaces():
    """The constructors of ``ddg_oracle.reference.surfaces`` with their known topology (X1.4)."""
    truth = {
        "disk": expected_classification(True, 0, 1),
        "sphere (tetrahedron)": expected_classification(True, 0, 0),
        "sphere (icosahedron)": expected_classification(True, 0, 0),
        "torus": expected_classification(True, 1, 0),
        "double torus": expected_classification(True, 2, 0),
        "annulus": expected_classification(True, 0, 2),
        "Möbius strip": expected_classification(False, 1, 1),
    }

    def build(name):
        s = _NAMED[name]()
        return SurfaceCase(s.triangulation, s.positions, truth[name], name)

    return st.sampled_from(sorted(_NAMED)).map(build)


def mobius_strips(max_size: int = 6):
    """Möbius strips of 2n faces, n = 3..max_size (``surfaces.mobius_strip``): the smallest
    non-orientable surfaces with boundary, where a boundary walk that follows the faces'
    orientation breaks (put first in a ``one_of`` so failures shrink to one of them)."""
    truth = expected_classification(False, 1, 1)

    def build(n):
        s = surfaces.mobius_strip(n)
        return SurfaceCase(s.triangulation, s.positions, truth, f"Möbius strip, {2 * n} faces")

    return st.integers(3, max_size).map(build)
