"""Strategies of chapter 4's Delaunay properties (:mod:`.delaunay`), and D1.4's flips.

* meshes far from Delaunay: drawn combinatorial flips (:func:`flipped_meshes`), the
  examples of the cotan and Delaunay checks (:func:`delaunay_meshes`,
  :func:`delaunay_test_meshes`), non-orientable surfaces (:func:`non_orientable_meshes`),
  the examples of the intrinsic Delaunay triangulation (:func:`intrinsic_meshes`), two
  triangulations of one flat metric (:func:`two_triangulations`), the X4.2 tetrahedron
  (:data:`X42`), meshes with interior vertices and boundary (:func:`interior_meshes`);
* planar inputs: point sets for ``planar_delaunay`` (:func:`planar_delaunay_points`),
  triangulations for ``planar_flip_to_delaunay`` (:func:`scaled_planar_triangulations`),
  convex quadrilaterals with values for Rippa's lemma (:func:`quads_with_values`);
* triangulations flipped without keeping them regular (D1.4, :mod:`.structure`);
* the notes' statements (:mod:`.statements`): the cube with drawn face diagonals flipped
  (X4.1, :func:`cube_faces`), closed rational metrics after drawn intrinsic flips, half of
  them flipped on to Delaunay (D4.3 / C4.6, :func:`closed_rational_metrics`).
"""

from __future__ import annotations

from fractions import Fraction

from hypothesis import strategies as st

from ..reference.combinatorics import Triangulation
from ..reference.polyhedral import PolyhedralSurface

from .draws import grouped, once, spread
from .example import Example
from .metrics import flat_tori, polycube_surfaces, randomly_flipped
from .precision import representable
from .strategies import (acute_meshes, closed_meshes, closed_surfaces, grid_faces, jittered_grids,
                         mesh_case, obtuse_fans, obtuse_meshes, planar_meshes, single_triangles)


@once
def _flip_bases():
    return st.one_of(closed_meshes(), jittered_grids(), polycube_surfaces(max_genus=1).map(
        lambda s: mesh_case(s.positions, s.triangulation.faces, "polycube")))


@st.composite
def flipped_meshes(draw):
    """A closed jittered polyhedron (or a grid in R^3) with up to 12 drawn combinatorial
    flips: long, thin, folded triangles whose intrinsic Delaunay triangulation needs many
    flips.  Flips that would make a loop or a double edge, or a face of area 0, are skipped."""
    from ..reference.errors import InputError
    case = draw(_flip_bases())
    t = case.surface.triangulation
    picks = draw(st.lists(st.integers(0, 10 ** 6), max_size=12))
    for k in picks:
        e = k % t.n_edges
        if t.is_boundary_edge(e):
            continue
        u = t.flip(e)
        if not u.is_strongly_regular():
            continue
        try:
            PolyhedralSurface(u, case.positions).metric()
        except InputError:                          # a degenerate (collinear) new face
            continue
        t = u
    return Example.of_mesh(case.positions, tuple(t.faces), f"{case.recipe}, {len(picks)} flips drawn")


def delaunay_meshes():
    """Meshes that are often not Delaunay: obtuse fans, jittered grids (in the plane and
    in R^3), closed jittered polyhedra, and those with random flips; shrinks towards a
    single triangle.  Not the wide surface meshes (random float jitter, valence 64,
    slivers): exact intrinsic flips on their float lengths are too slow to shrink a
    failure today (issue 18); and no vertex used by no face (D3.1 draws them for
    ``cotan_laplacian``; :func:`intrinsic_meshes` adds one).  Scaled by 2**k and sometimes
    moved far (:func:`~.strategies.scaled_meshes`: exact; what these properties check is
    scale-invariant, and an absolute threshold on an edge or an area shows there)."""
    from .strategies import scaled_meshes
    return scaled_meshes(st.one_of(*_delaunay_kinds()))


def delaunay_test_meshes():
    """D4.4's examples: half :func:`delaunay_meshes`, half quads beside an exact tie
    (:func:`~.strategies.near_cocircular_meshes`: a test with a tolerance decides them
    wrongly); a third of either with faces reversed (:func:`~.strategies.with_reversed_faces`:
    a test that finds the other face of an edge by the reversed directed edge calls the
    edge a boundary edge, hence Delaunay); up to two vertices used by no face
    (:func:`~.strategies.with_isolated`: a test keyed by compacted vertex numbers)."""
    from .strategies import near_cocircular_meshes, with_isolated, with_reversed_faces
    return with_isolated(with_reversed_faces(st.one_of(grouped(*_delaunay_kinds()),
                                                       near_cocircular_meshes())))


def _delaunay_kinds() -> list:
    return [single_triangles(), planar_meshes(), jittered_grids(), obtuse_meshes(),
            acute_meshes(), closed_meshes(), flipped_meshes()]


_SIXTEENTHS = st.integers(-64, 64).map(lambda k: Fraction(k, 16))


@st.composite
def non_orientable_meshes(draw):
    """The 6-vertex projective plane, a 3 x 3 Klein bottle (at drawn dyadic points: an
    immersion, whose metric is all an intrinsic triangulation needs) or a Moebius strip:
    D4.8, A4.13, C4.19 and L4.20 hold for any piecewise flat surface, orientable or not
    (docs/findings.md F-libigl-6: a flip algorithm that assumes an orientation breaks there)."""
    from ..reference import surfaces
    from ..reference.errors import InputError
    kind = draw(spread(("Moebius strip", "projective plane", "Klein bottle")))
    if kind == "Moebius strip":
        s = surfaces.mobius_strip(draw(st.integers(3, 6)))
        return mesh_case(s.positions, s.triangulation.faces, f"Moebius strip, {s.n_vertices} vertices")
    t = surfaces.projective_plane() if kind == "projective plane" else surfaces.klein_bottle(3, 3)
    points = draw(st.lists(st.tuples(_SIXTEENTHS, _SIXTEENTHS, _SIXTEENTHS),
                           min_size=t.n_vertices, max_size=t.n_vertices))
    try:
        PolyhedralSurface(t, points).metric()
    except InputError:                              # a degenerate face: draw again
        from hypothesis import assume
        assume(False)
    return mesh_case(points, t.faces, f"{kind} at dyadic points")


def intrinsic_meshes():
    """The examples of the properties that ask for an intrinsic Delaunay triangulation, in
    three equal parts: :func:`delaunay_meshes`' kinds and non-orientable surfaces
    (:func:`non_orientable_meshes`, one kind among eight: an implementation that declines
    non-orientable input keeps most of its examples); quads beside an exact tie
    (:func:`~.strategies.near_cocircular_meshes`: a flip decided with a tolerance); and
    planar triangulations far from Delaunay (:func:`~.strategies.sweep_meshes`: flip
    cascades).  A third of them with faces reversed (:func:`~.strategies.with_reversed_faces`:
    a flip algorithm that glues by reversed halfedge keys takes an interior edge for a
    boundary edge and never flips it).  Half of the near ties and cascades closed by cones
    (:func:`~.strategies.coned`): an implementation that declines boundary meets them too.
    Every kind maybe with a near-tie quad and a convex fan beside it
    (:func:`~.strategies.with_traps_beside`), and two thirds of them with one or two
    vertices used by no face (:func:`~.strategies.with_isolated`: an implementation that
    computes on the compacted mesh and answers in its numbering passed every chapter-4
    property before; one that maps back past the first unused vertex only, two)."""
    from .strategies import (coned, near_cocircular_meshes, sweep_meshes, with_isolated,
                             with_reversed_faces, with_traps_beside)
    return with_isolated(with_reversed_faces(with_traps_beside(st.one_of(
        grouped(*_delaunay_kinds(), non_orientable_meshes()),
        coned(near_cocircular_meshes()), coned(sweep_meshes())))))


@st.composite
def two_triangulations(draw):
    """One jittered planar point grid, triangulated twice (each square's diagonal drawn
    twice): two triangulations of the same flat metric with the same vertex set."""
    c = draw(planar_meshes(min_size=1, max_size=3))
    rows = [p for p in c.positions]
    m = round(float(max(p[0] for p in rows)))
    n = round(float(max(p[1] for p in rows)))
    flips = draw(st.lists(st.booleans(), min_size=m * n, max_size=m * n))
    other = Example.of_mesh(c.positions, tuple(tuple(f) for f in grid_faces(m, n, flips)),
                     c.recipe + " retriangulated")
    return c, other


#: X4.2: a flat tetrahedron (positions, faces) whose Delaunay triangulation has a vertex
#: of valence 1 inside a loop
X42 = ([(0, 0, 0), (10, 0, 0), (0, 1, 0), (1, Fraction(1, 3), Fraction(1, 10))],
       [(0, 1, 2), (0, 2, 3), (0, 3, 1), (1, 3, 2)])


def x42_tetrahedron():
    """X4.2 (:data:`X42`) as the one example of its property, rounded to the input format
    of the run that draws it (the strategy is kept across runs: :func:`~.runner.strategy_of`)."""
    return st.builds(lambda: mesh_case(*X42, "X4.2 tetrahedron"))


def interior_meshes():
    """Meshes with interior vertices and boundary: grids in R^3 and fans."""
    return st.one_of(jittered_grids(), obtuse_fans())


# --- planar inputs (D4.1, T4.1, L4.3 / P4.4, L4.14) ----------------------------------------------


def planar_delaunay_points():
    """D4.1's and T4.1's examples: planar point sets (:func:`~.planar_points.rational_point_sets`
    rounded to the input format) or nearly cocircular ones
    (:func:`~.strategies.near_cocircular_point_sets`)."""
    from .planar_points import rational_point_sets
    from .strategies import near_cocircular_point_sets
    # rounded to the checked implementation's input format; distinct points after it.  Half
    # the draws points of one circle, one moved off it by 2**-k (k in 20..44): the
    # nearly cocircular sets where a float32 rounding or a joggle picks the other diagonal
    return st.one_of(rational_point_sets().map(lambda pts: tuple((representable(x), representable(y))
                                                                 for x, y in pts)).filter(
        lambda pts: len(set(pts)) == len(pts)), near_cocircular_point_sets())


def scaled_planar_triangulations():
    """L4.3 / P4.4's examples: (points, faces, on_hull) of
    :func:`~.planar_points.planar_triangulations`, scaled by 2**k
    (:func:`~.strategies.scaled_planar`)."""
    from .planar_points import planar_triangulations
    from .strategies import scaled_planar
    # scaled by 2**k (exact): an absolute epsilon on the in-circle determinant shows
    return scaled_planar(planar_triangulations())


def quads_with_values():
    """L4.14's examples: (a strictly convex integer quadrilateral, four integer values u)."""
    from .planar_points import integer_quadrilaterals
    values = st.lists(st.integers(-4, 4), min_size=4, max_size=4)
    return st.tuples(integer_quadrilaterals, values)


# --- flips that keep no regularity (D1.4) --------------------------------------------------------


def unrestricted_flips():
    """(surface, flip choices): flips applied without keeping the triangulation regular."""
    return st.tuples(closed_surfaces(max_genus=1, relabel=False),
                     st.lists(st.integers(0, 1 << 16), min_size=1, max_size=12))


def flip_freely(t: Triangulation, choices) -> Triangulation:
    """Flip the edges chosen (skipping unflippable ones); loops and double edges may appear."""
    from ..reference.errors import NotFlippable
    for c in choices:
        e = c % t.n_edges
        try:
            t = t.flip(e)
        except NotFlippable:
            continue
    return t


# --- the notes' statements: the cube's triangulations by face diagonals (X4.1), closed
# rational metrics for the empty immersed disks (D4.3 / C4.6) ----------------------------


def cube_faces(choices):
    """The unit cube with the diagonal of square ``k`` flipped where ``choices[k]``
    (every one of the 2^6 straight triangulations of its squares), as a piecewise flat
    surface (intrinsic flips of the reference's cube)."""
    from ..reference import surfaces
    from ..reference.intrinsic import flip
    from ..reference.metric import PiecewiseFlatSurface
    cube = surfaces.cube()
    t = cube.triangulation
    m = PiecewiseFlatSurface(t, [sum((a - b) ** 2 for a, b in zip(
        cube.positions[t.edge_vertices(e)[0]], cube.positions[t.edge_vertices(e)[1]]))
        for e in range(t.n_edges)])
    diagonals = [e for e in range(t.n_edges) if m.squared_lengths[e] == 2]
    for e, c in zip(diagonals, choices):
        if c:
            m = flip(m, e)
    return m


def closed_rational_metrics():
    """Closed surfaces with rational metrics (flat tori, polycubes) after drawn intrinsic
    flips, and half of them flipped on to Delaunay (so both answers of T4.7 are drawn)."""
    from ..reference.delaunay import flip_to_delaunay
    base = randomly_flipped(st.one_of(flat_tori(), polycube_surfaces(max_genus=1).map(
        lambda s: s.metric())), max_flips=30)
    return st.tuples(base, st.booleans()).map(
        lambda x: flip_to_delaunay(x[0])[0] if x[1] else x[0])
