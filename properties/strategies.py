"""Hypothesis strategies for meshes.

Strategies draw a few small integers (genus, number of holes, which edges to
flip, which refinement to apply) and *construct* the surface from the
reference's exact constructors, so a failing example shrinks toward a
tetrahedron-sized mesh.  Every example knows its true topology from how it was
built, independently of any counting.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass
from fractions import Fraction

from hypothesis import assume, strategies as st

from ..reference import surfaces
from ..reference.combinatorics import Classification, Triangulation, connected_sum
from ..reference.errors import NotFlippable
from ..reference.polyhedral import PolyhedralSurface

from . import memo, variants
from .draws import once, spread
from .example import Example
from .precision import input_format, representable


_LIFTS = st.one_of(st.none(), st.integers(0, 8))    # a sliver's apex lifted by 2^-k, or not


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


@once
def surface_moves(max_size: int = 4):
    """Lists of refinement and flip moves: (name, integer choosing where)."""
    return st.lists(
        st.tuples(spread(("flip", "split", "1to4")), st.integers(0, 1 << 16)),
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


#: second components of :func:`triangulated_surfaces` (name -> triangulation, its class)
_TOPOLOGY_COMPONENTS = {
    "tetrahedron": (lambda: surfaces.tetrahedron().triangulation, (True, 0, 0)),
    "disk": (lambda: surfaces.disk(4).triangulation, (True, 0, 1)),
    "Möbius strip": (lambda: surfaces.mobius_strip(3).triangulation, (False, 1, 1)),
    "projective plane": (surfaces.projective_plane, (False, 1, 0)),
    "torus": (lambda: surfaces.torus(3, 3).triangulation, (True, 1, 0)),
}


@st.composite
def triangulated_surfaces(draw, orientable=None, genus=None, holes=None,
                          max_genus: int = 2, max_holes: int = 2, moves: bool = True,
                          relabel: bool = True, reversed: bool = False, components: int = 0,
                          isolated: int = 0):
    """A :class:`Example`: any topology (orientable or not, genus, holes), refined and flipped.

    Fixed arguments pin the topology; the rest is drawn.  The combinatorics are
    always a simplicial complex (strongly regular), as array-based libraries expect.
    Where bugs hide (each drawn 0 first, so a failure shrinks to the plain surface):

    * ``reversed``: some faces listed the other way (the same surface inconsistently
      oriented: orientable stays orientable; what breaks is code that follows the
      faces' own direction);
    * ``components``: up to this many more components (a tetrahedron, a disk, a Möbius
      strip, a projective plane, a torus), listed after the surface or before it; the
      expected class then has chi, orientability and boundary loops of the union, and
      no genus (None);
    * ``isolated``: up to this many vertices used by no face (each counts 1 in
      chi = V - E + F), at drawn indices of the arrays.
    """
    if max_genus < 0 or max_holes < 0:
        raise ValueError("max_genus and max_holes must be >= 0")
    # drawn as "not False" so a failure shrinks to an orientable surface (a tetrahedron),
    # not to the 10-face projective plane
    o = (not draw(st.booleans())) if orientable is None else bool(orientable)
    lowest = 0 if o else 1
    g = draw(st.integers(lowest, max(lowest, max_genus))) if genus is None else int(genus)
    if g < lowest:
        raise ValueError(f"genus {g} impossible for a {'non-' if not o else ''}orientable surface")
    # the count of other components before the holes: a failure that needs a boundary
    # shrinks to one surface with a hole (a disk), not to a closed one beside an annulus
    n_comp = draw(st.integers(0, components)) if components else 0
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
    expected = expected_classification(o, g, k)
    if reversed and draw(st.integers(0, 2)) == 2:
        t, n = variants.reversed_faces(t, draw(st.integers(0, 1 << 16)))
        recipe += f", {n} face(s) reversed"
    for _ in range(n_comp):
        name = draw(spread(sorted(_TOPOLOGY_COMPONENTS)))
        build, (o2, g2, k2) = _TOPOLOGY_COMPONENTS[name]
        other = expected_classification(o2, g2, k2)
        # listed after the surface, or before it (its faces and vertices first: where code
        # that looks at the first component only, face 0's, sees the other one)
        first = draw(st.booleans())
        t = variants.union_of(build(), t) if first else variants.union_of(t, build())
        expected = Classification(expected.orientable and other.orientable, None,
                                  expected.boundary_components + other.boundary_components,
                                  expected.euler_characteristic + other.euler_characteristic)
        recipe += f", and a {name}" + (" listed first" if first else "")
    positions = _placeholder_positions(t)
    if relabel:
        key = draw(st.integers(0, 1 << 16))
        t, positions, _ = variants.relabelled(t, positions, key)
    case = Example.of_triangulation(t, positions, expected, recipe)
    n_iso = draw(st.integers(0, isolated)) if isolated else 0
    if not n_iso:
        return case
    size = t.n_vertices + n_iso
    spots = sorted(draw(st.lists(st.integers(0, size - 1), min_size=n_iso, max_size=n_iso,
                                 unique=True)))
    # a far point, past the moment curve's (distinct from every vertex's)
    iso = tuple((i, (Fraction(-1 - i), Fraction(0), Fraction(0))) for i in spots)
    expected = Classification(expected.orientable, expected.genus, expected.boundary_components,
                              expected.euler_characteristic + len(iso))
    return case.with_data(isolated=iso, expected=expected,
                          recipe=recipe + f", isolated vertices at {list(spots)}")


@st.composite
def orientation_traps(draw):
    """Where a test of orientability that follows the faces' own direction, or looks at
    one component only, goes wrong: one of three kinds, each drawn a third of the time
    (so that a default run meets each a few times),

    * an orientable surface (tetrahedron, disk, torus) with some faces reversed:
      orientable, but the faces' own directions disagree (4 faces at the least);
    * an orientable component then a non-orientable one (Möbius strip, projective
      plane): an orientation propagated from face 0 alone never reaches the second
      (10 faces at the least);
    * the same two the other way round (code that looks at the last component)."""
    kind = draw(st.integers(0, 2))
    yes = [n for n, (_, c) in _TOPOLOGY_COMPONENTS.items() if c[0]]
    no = [n for n, (_, c) in _TOPOLOGY_COMPONENTS.items() if not c[0]]
    names = [draw(spread(yes))] + ([draw(spread(no))] if kind else [])
    if kind == 2:
        names.reverse()
    built = [_TOPOLOGY_COMPONENTS[n][0]() for n in names]
    if kind == 0:
        built[0], n = variants.reversed_faces(built[0], draw(st.integers(0, 1 << 16)))
        names[0] += f" ({n} face(s) reversed)"
    t = built[0] if len(built) == 1 else variants.union_of(*built)
    parts = [expected_classification(*_TOPOLOGY_COMPONENTS[n.split(" (")[0]][1]) for n in names]
    expected = parts[0] if len(parts) == 1 else Classification(
        False, None, sum(c.boundary_components for c in parts),
        sum(c.euler_characteristic for c in parts))
    return Example.of_triangulation(t, _placeholder_positions(t), expected,
                                    ", then a ".join(f"a {n}" for n in names))


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
        return Example.of_triangulation(s.triangulation, s.positions, truth[name], name)

    return st.sampled_from(sorted(_NAMED)).map(build)


def mobius_strips(max_size: int = 6):
    """Möbius strips of 2n faces, n = 3..max_size (``surfaces.mobius_strip``): the smallest
    non-orientable surfaces with boundary, where a boundary walk that follows the faces'
    orientation breaks (put first in a ``one_of`` so failures shrink to one of them)."""
    truth = expected_classification(False, 1, 1)

    def build(n):
        s = surfaces.mobius_strip(n)
        return Example.of_triangulation(s.triangulation, s.positions, truth, f"Möbius strip, {2 * n} faces")

    return st.integers(3, max_size).map(build)


def annuli(max_size: int = 6):
    """Annuli of 2n faces, n = 3..max_size (``surfaces.annulus``): the smallest orientable
    surfaces with two boundary loops (where code that finds one loop, or counts loops by
    their vertices, breaks; punched surfaces need 22 faces for two holes).  In one draw of
    two from n = 4 on, the two loops touch in space: a vertex of each, sharing no face, at
    one position (distinct points elsewhere), as in a mesh to be stitched (CGAL's
    quads_to_stitch.off): the surface and its loops are the same, and code that finds
    boundary vertices by position (VTK's vtkFeatureEdges, F-vtk-4) merges them."""
    truth = expected_classification(True, 0, 2)

    def build(args):
        n, touching = args
        s = surfaces.annulus(n)
        if not touching or n < 4:
            return Example.of_triangulation(s.triangulation, s.positions, truth,
                                            f"annulus, {2 * n} faces")
        t = s.triangulation
        pts = list(_placeholder_positions(t))
        inner, outer = t.boundary_loops()
        a, b = next((a, b) for a in inner for b in outer
                    if not any(a in f and b in f for f in t.faces))
        pts[b] = pts[a]
        return Example.of_triangulation(t, tuple(pts), truth, f"annulus, {2 * n} faces, "
                                        f"boundary vertices {a} and {b} at one position")

    return st.tuples(st.integers(3, max_size), st.booleans()).map(build)


# --- polyhedral surfaces with float coordinates (curvature, Laplacian, mass matrices) ---------


def floated(surface: PolyhedralSurface) -> PolyhedralSurface:
    """The surface with every coordinate rounded to the nearest float of the checked
    implementation's input format (:mod:`.precision`; then taken exactly)."""
    return surface.with_positions([floated_point(p) for p in surface.positions])


def _subdivided(s: PolyhedralSurface) -> PolyhedralSurface:
    t, mids = s.triangulation.subdivide_1to4()
    x = s.positions
    return PolyhedralSurface(t, list(x) + [tuple((a + b) / 2 for a, b in zip(x[i], x[j]))
                                           for i, j in mids])


def jittered(s: PolyhedralSurface, level: int, seed: int, floats: bool) -> PolyhedralSurface:
    """Every coordinate moved by at most 2**-(4 + level): k/2**(6+level) or a random float."""
    if level == 0:
        return s
    rng = random.Random(seed)
    scale = Fraction(1, 2 ** (6 + level))
    if floats:
        off = lambda: Fraction(rng.uniform(-4.0, 4.0)) * scale   # noqa: E731
    else:
        off = lambda: rng.randint(-4, 4) * scale                   # noqa: E731
    return s.with_positions([tuple(x + off() for x in p) for p in s.positions])


_CLOSED = {
    "tetrahedron": lambda a, b: surfaces.tetrahedron(),
    # the smallest closed surface with reflex edges (a saddle's dihedral angles are
    # negative, which an unsigned angle gets wrong): listed second, so that a failure on
    # a larger closed surface can shrink to these 6 faces
    "dented bipyramid": lambda a, b: variants.bipyramid(3, Fraction(1 + a, 2), -Fraction(1 + a, 4)),
    "octahedron": lambda a, b: surfaces.octahedron(),
    "cube": lambda a, b: surfaces.cube(),
    "icosahedron": lambda a, b: surfaces.icosahedron(),
    "torus": lambda a, b: surfaces.torus(3 + a % 3, 3 + b % 2),      # sizes, not corners
    "double torus": lambda a, b: surfaces.genus_surface(2),
}
_CHI = {"tetrahedron": 2, "dented bipyramid": 2, "octahedron": 2, "cube": 2, "icosahedron": 2, "torus": 0,
        "double torus": -2}
_WITH_BOUNDARY = {
    "disk": (lambda a, b: surfaces.disk(3 + a % 6), 1),
    "annulus": (lambda a, b: surfaces.annulus(3 + a % 4), 0),
    "grid": (lambda a, b: surfaces.grid(1 + a % 3, 1 + b % 3), 1),    # sizes, not corners
}
#: second components (name -> (surface, chi, closed)): small, so a shrunk union stays small
_COMPONENTS = {
    "triangle": (lambda: PolyhedralSurface(Triangulation.from_faces([(0, 1, 2)]), [
        (Fraction(0), Fraction(0), Fraction(0)), (Fraction(1), Fraction(0), Fraction(0)),
        (Fraction(0), Fraction(1), Fraction(0))]), 1, False),
    "tetrahedron": (surfaces.tetrahedron, 2, True),
    "octahedron": (surfaces.octahedron, 2, True),
    "disk": (lambda: surfaces.disk(4), 1, False),
    "moebius strip": (lambda: surfaces.mobius_strip(3), 0, False),
}
#: largest k of a 2**-k sliver drawn.  The corner bound C_ANGLE eps (1 + 1/sin) of a
#: needle's own small angle stays below the angle while 2 k < 52 - log2 C_ANGLE (k < 24);
#: beyond, that angle is no longer checked, but the face's other corners, its area and
#: every cotangent still are (a "degenerate triangle" rule that zeroes a whole face below
#: 1e-8 rad shows there), and 30 keeps 22 bits of the sliver in float coordinates
SLIVER_LIMIT = 30
#: highest valence drawn for fans and bipyramids (CAD end caps are fans of 32-128 faces)
MAX_VALENCE = 64
#: smallest lift 2**-k of a high-valence fan's centre: beyond k = 20 the reference's exact
#: zero test of a nearly flat angle sum over 14+ square roots reaches its term limit
#: (issue 18), so nearer-flat stars are drawn exactly planar instead
FAN_LIFT_LIMIT = 20


def _reversed_faces(s: PolyhedralSurface, seed: int) -> tuple[PolyhedralSurface, int]:
    """The surface with a random nonempty subset of its faces reversed (same vertices, same
    metric: an orientable surface inconsistently oriented); (surface, faces reversed)."""
    t, k = variants.reversed_faces(s.triangulation, seed)
    return PolyhedralSurface(t, s.positions), k


def _scaled_and_moved(s: PolyhedralSurface, k: int, e: int | None, signs: int) -> PolyhedralSurface:
    """Every position times 2**k, then moved by 2**e times the (scaled) mesh size along
    (+-1, +-1, +-1) (``signs``: three bits): exact, dyadic, so the reference stays exact."""
    scale = Fraction(2) ** k
    pts = [tuple(x * scale for x in p) for p in s.positions]
    if e is not None:
        size = max(abs(x) for p in pts for x in p)
        log2 = size.numerator.bit_length() - size.denominator.bit_length()   # log2 |x|, +-1
        unit = Fraction(2) ** (log2 + e)
        shift = [-unit if signs >> d & 1 else unit for d in range(3)]
        pts = [tuple(x + o for x, o in zip(p, shift)) for p in pts]
    return s.with_positions(pts)


def _built(key: tuple, build):
    """``build()``, once per ``key`` in this process (:data:`.memo.DRAWN`): a drawn surface
    is a chain of exact steps, each determined by the previous one and its drawn choices,
    and every implementation's task draws the same choices.  ``key`` is the chain so far."""
    return memo.DRAWN.shared(("jittered",) + key, build)


def _base(draw, closed, intrinsic, max_valence=MAX_VALENCE):
    """(surface, chi, recipe): a constructor's surface, maybe minus a face, a high-valence
    fan or bipyramid, or (``intrinsic``) a Möbius strip; also the orientation code."""
    names = []
    if closed is not False:
        names += list(_CLOSED)
    if closed is not True:
        names += list(_WITH_BOUNDARY) + ["holed " + n for n in ("tetrahedron", "cube", "torus")]
    # high valence: one draw in four, so that it is reached in a default run (25 examples)
    high = [n for n, c in (("bipyramid", True), ("fan", False)) if closed in (None, c)]
    # orientation first, so that it shrinks to the plain case: 0 consistently oriented,
    # 1 a Möbius strip (non-orientable, with boundary), 2 some faces reversed
    orientation = draw(st.integers(0, 2)) if intrinsic else 0
    if orientation == 1 and closed is True:
        orientation = 2
    name = draw(spread(names))      # drawn always: the choices stay aligned when
    if draw(spread((False, False, False, True))):   # orientation or valence shrinks to 0
        name = draw(spread(high))
    if orientation == 1:
        name = "moebius strip"
    a, b = draw(st.integers(0, 5)), draw(st.integers(0, 5))
    if name in _CLOSED:
        s, chi = _built((name, a, b), lambda: _CLOSED[name](a, b)), _CHI[name]
    elif name in _WITH_BOUNDARY:
        build, chi = _WITH_BOUNDARY[name]
        s = _built((name, a, b), lambda: build(a, b))
    elif name == "moebius strip":
        s, chi = _built((name, a % 5), lambda: surfaces.mobius_strip(3 + a % 5)), 0
    elif name in ("fan", "bipyramid"):
        n = draw(st.integers(3, max_valence))
        if name == "fan":
            lift = draw(st.integers(0, FAN_LIFT_LIMIT))           # 0: exactly planar
            s, chi = _built((name, n, lift), lambda: variants.fan(n, lift or None)), 1
            name = f"fan of valence {n}" + (f", centre lifted by 2^-{lift}" if lift else ", planar")
        else:
            # dented: the lower apex pushed up inside, to half the upper one's height (a
            # closed embedded surface whose lower edges are reflex: a saddle's dihedral
            # angles are negative, which an unsigned angle gets wrong)
            dented = draw(st.booleans())
            bottom = -Fraction(1 + a, 4) if dented else Fraction(1 + b, 2)
            s = _built((name, n, a, b, dented),
                       lambda: variants.bipyramid(n, Fraction(1 + a, 2), bottom))
            chi, name = 2, f"{'dented ' if dented else ''}bipyramid of valence {n}"
    else:
        base = name.split(" ", 1)[1]
        s0 = _built((base, a, b), lambda: _CLOSED[base](a, b))
        f = draw(st.integers(0, 1 << 10)) % s0.triangulation.n_faces
        s = _built((base, a, b, "minus face", f),
                   lambda: PolyhedralSurface(s0.triangulation.remove_face(f), s0.positions))
        chi = _CHI[base] - 1
        name = f"{name} (face {f})"
    return s, chi, f"{name} [{a}, {b}]", orientation


@once
@st.composite
def jittered_surfaces(draw, closed: bool | None = None, subdivide: bool = True,
                      intrinsic: bool = False, far: bool = True, wide: bool = True,
                      isolated: bool = True, max_valence: int = MAX_VALENCE):
    """A :class:`Example` from a constructor's surface (X1.4), drawn where bugs hide.

    Draws small integers, each 0 for the plain case, and builds exactly:

    * the surface: a constructor's closed surface or disk, annulus, grid, a closed
      one minus a face, a fan of valence 3..64 (exactly planar or its centre
      lifted by 2**-k) or a bipyramid of valence 3..64 (one in two dented: its lower
      apex pushed up inside, reflex edges on a 6-face sphere); maybe 1-to-4 subdivided
      (exact midpoints), some interior edges flipped (``wide``: a random valence
      distribution) and jittered (2**-(4 + level), rational or float);
    * ``intrinsic=True`` (properties of the metric alone: angle defects, turning
      angles, corner angles): Möbius strips (non-orientable) and orientable
      surfaces with a random subset of faces reversed -- same metric, other halfedges;
    * ``wide=True``: a sliver (a face split at 2**-k, k <= 30, from a corner --
      needles -- or from an edge's midpoint -- a cap, on the boundary if that edge
      is), alone or 2-5 of them clustered at one point or banded across the mesh
      (as the degenerate-mesh benchmarks draw them); a second component (beside
      it, or touching it at one point: two vertices at one position), up to 2
      isolated vertices (used by no face; at a far point or exactly at a vertex's
      position; ``isolated=False`` leaves them out), and a random order of
      vertices, faces and corners;
    * ``far=True``: scaled by 2**k (k in -60..60) and moved by 2**e (e in 0..30)
      times its size (``far=False`` for a property that moves the surface itself:
      a rotated far-away surface rounded to floats can lose a face).  ``max_valence``
      caps the fans and bipyramids.

    Coordinates end as floats of the checked implementation's input format
    (:mod:`.precision`: a float32 implementation gets float32 numbers, and smaller
    scales, offsets and slivers that float32 can hold).  Shrinks towards the tetrahedron at scale 1, at the
    origin, consistently oriented, connected, in its constructor's order.  Each
    building step is kept per drawn choices (:data:`.memo.DRAWN`), and so is the case:
    equal draws give the same, shared, read-only case object.
    """
    s, chi, recipe, orientation = _base(draw, closed, intrinsic, max_valence)
    key = (recipe,)             # the base's recipe determines it; each step extends the key
    if subdivide and draw(st.integers(0, 3)) == 3 and s.triangulation.n_faces <= 100:
        key += ("1-to-4",)
        s = _built(key, lambda s=s: _subdivided(s))
        recipe += ", 1-to-4"
    flips = draw(st.lists(st.integers(0, 1 << 16), max_size=4)) if wide else []
    if flips:
        # random valence: flip interior edges (kept a simplicial complex); the vertices
        # stay, the faces become the other diagonals of (generally non-planar) quads
        def flip(s=s):
            flipped = PolyhedralSurface(apply_moves(s.triangulation, [("flip", w) for w in flips]),
                                        s.positions)
            # a flip across a reflex quad folds two faces: not taken
            return None if variants.has_fold(flipped) else flipped
        flipped = _built(key + ("flips", tuple(flips)), flip)
        if flipped is not None:
            s, key = flipped, key + ("flips", tuple(flips))
            recipe += f", flips {flips}"
    level = draw(st.integers(0, 2))
    if level:
        seed, floats = draw(st.integers(0, 1 << 16)), draw(st.booleans())
        key += ("jitter", level, seed, floats)
        s = _built(key, lambda s=s: jittered(s, level, seed, floats))
        recipe += f", jitter {level} ({'floats' if floats else 'rationals'}, seed {seed})"
    fmt = input_format()              # the checked implementation's floats (precision)
    sliver = draw(st.integers(0, 2)) if wide and fmt.sliver else 0   # 0 none, 1 needle, 2 cap
    k_sliver, family = 0, None
    if sliver:
        kind = ("needle", "cap")[sliver - 1]
        # every exponent about equally often (integers() would draw 2^-1 half the time)
        k_sliver = draw(spread(range(1, min(SLIVER_LIMIT, fmt.sliver) + 1)))
        h = draw(st.integers(0, 1 << 16))
        if draw(st.booleans()):                               # a boundary edge, if any
            t = s.triangulation
            border = [x for x in range(t.n_halfedges) if t.twin(x) < 0]
            h = border[h % len(border)] if border else h
        lift = draw(_LIFTS)
        h %= s.triangulation.n_halfedges
        # one sliver, or a cluster of them at one point, or a band across the mesh
        family = variants.SLIVER_FAMILIES[draw(st.integers(0, 2))]
        count = draw(st.integers(2, 5)) if family != "isolated" else 1
        key += (kind, h, k_sliver, lift, family, count)
        s = _built(key, lambda s=s: variants.slivers(s, h, kind, k_sliver, lift, family, count))
        recipe += f", {kind} 2^-{k_sliver} at halfedge {h}" + (
            f" lifted 2^-{lift}" if lift is not None else "") + (
            f", {family} ({count})" if count > 1 else "")
    if orientation == 2:
        which = draw(st.integers(0, 1 << 16))
        key += ("reversed", which)
        s, k = _built(key, lambda s=s: _reversed_faces(s, which))
        recipe += f", {k} face(s) reversed"
    comp = draw(st.integers(0, 2)) if wide else 0             # 0 none, 1 beside, 2 touching
    if comp:
        # a Möbius strip only when the first component is one: then dropping the second
        # shrinks towards the strip alone (a strip beside a consistently oriented
        # surface would be a minimum the shrinker cannot leave: it never raises the
        # orientation choice from "consistent" to "Möbius")
        names = [n for n, (_, _, c) in _COMPONENTS.items()
                 if (c or closed is not True) and (orientation == 1 or n != "moebius strip")]
        other = draw(spread(names))
        build, chi2, _ = _COMPONENTS[other]
        key += ("and", other, comp)
        s = _built(key, lambda s=s: variants.disjoint_union(s, build(), touch=comp == 2))
        chi += chi2
        recipe += f", and a {other} {'touching it at a vertex' if comp == 2 else 'beside it'}"
    order = draw(st.integers(0, 1 << 16)) if wide and draw(st.booleans()) else 0
    if order:
        key += ("reordered", order)
        s = _built(key, lambda s=s: variants.permuted(s, order))
        recipe += f", reordered (seed {order})"
    # scaling by 2**k is exact in floats, so a bug of the unit-size mesh shows scaled too:
    # scale most examples (a threshold bug shows only there)
    # (three draws of four; Hypothesis's integers() favour 0 and the ends of the range,
    # where an absolute threshold of 1e-13 on an edge shows: k <= -44)
    k = draw(st.integers(-fmt.scale, fmt.scale)) if far and draw(spread((False, True, True, True))) else 0
    e = draw(st.integers(0, fmt.offset)) if far and draw(st.integers(0, 3)) >= 2 else None
    if e is not None and sliver:
        # keep >= 12 bits of the sliver after rounding
        e = max(0, min(e, fmt.bits - 17 - k_sliver))
    if k or e is not None:
        signs = draw(st.integers(0, 7)) if e is not None else 0
        key += ("scaled", k, e, signs)
        s = _built(key, lambda s=s: _scaled_and_moved(s, k, e, signs))
        recipe += f", scaled by 2^{k}" + (f", moved by 2^{e} x its size" if e is not None else "")
    def rounded(s=s):
        try:
            s = floated(s)
        except OverflowError:
            return None                          # beyond the input format's range
        # rounding collapsed a sliver or folded a flip: not an example (None)
        return None if variants.is_degenerate(s) or variants.has_fold(s) else s
    key += ("floated", fmt.name)
    s = _built(key, rounded)
    assume(s is not None)
    allow_isolated, isolated = isolated, ()
    n_iso = draw(st.integers(0, 2)) if wide and allow_isolated else 0
    if n_iso:
        spots = []
        for _ in range(n_iso):
            v = draw(st.integers(0, s.n_vertices - 1))
            at_vertex = draw(st.booleans())
            p = s.positions[v] if at_vertex else tuple(x * 3 + 1 for x in s.positions[v])
            # where in V: last (leftover vertices of a file), first, or anywhere
            where = draw(st.integers(0, 2))
            size = s.n_vertices + n_iso
            i = (size - 1, 0, None)[where]
            spots.append((draw(st.integers(0, size - 1)) if i is None else i, floated_point(p)))
        used, isolated = set(), []
        for i, p in spots:                   # distinct indices, in order
            while i in used:
                i = (i + 1) % (s.n_vertices + n_iso)
            used.add(i)
            isolated.append((i, p))
        isolated = tuple(sorted(isolated))
        recipe += f", isolated vertices at {[i for i, _ in isolated]}"
    params = (("scale exponent", k), ("offset exponent", e),
              ("orientation", ("consistent", "moebius", "faces reversed")[orientation]),
              ("sliver", (None, "needle", "cap")[sliver]), ("sliver exponent", k_sliver),
              ("sliver family", family),
              ("components", 1 + (comp > 0)), ("touching", comp == 2),
              ("isolated", len(isolated)), ("reordered", order != 0))
    # one case object per drawn example: its float arrays and content key are computed once
    # for every implementation's task (a case is a value: nothing mutates it)
    return _built(key + ("case", isolated), lambda: Example.of_surface(s, chi, recipe, params=params,
                                                                  isolated=isolated))


def floated_point(p) -> tuple:
    """A point with each coordinate rounded to the nearest float of the input format
    (:func:`~.precision.representable`; then taken exactly)."""
    return tuple(representable(x) for x in p)


# --- meshes with exact dyadic positions (Laplacian, mass matrices, Delaunay) ------------------


def _dyadic(x) -> Fraction:
    """The exact value of the float nearest to x in the input format (what an
    implementation will see)."""
    return representable(x)


def mesh_case(positions, faces, recipe) -> Example:
    """A :class:`Example` of the floats nearest to ``positions`` (2-D points get z = 0)."""
    pts = tuple(tuple(_dyadic(x) for x in (tuple(p) + (0,) * (3 - len(p)))) for p in positions)
    return Example.of_mesh(pts, tuple(tuple(int(v) for v in f) for f in faces), recipe)


def _orientation_ok(positions, faces) -> bool:
    """Every face has positive area in the xy-projection (exact): a valid planar layout."""
    for a, b, c in faces:
        (ax, ay), (bx, by), (cx, cy) = (positions[v][:2] for v in (a, b, c))
        if (bx - ax) * (cy - ay) - (by - ay) * (cx - ax) <= 0:
            return False
    return True


@st.composite
def single_triangles(draw):
    """One triangle in R^3 from small integers: needles (long base, low apex), obtuse
    (apex beyond the base), right, skew.  Shrinks to (0,0,0), (1/4,0,0), (0,1/16,0)."""
    L = draw(st.integers(1, 16))
    a = draw(st.integers(-16, 32))
    h = draw(st.integers(1, 16))
    z = draw(st.integers(-8, 8))
    pts = [(0, 0, 0), (Fraction(L, 4), 0, 0), (Fraction(a, 4), Fraction(h, 16), Fraction(z, 16))]
    return mesh_case(pts, [(0, 1, 2)], f"triangle L={L}/4 apex=({a}/4, {h}/16, {z}/16)")


def grid_faces(m: int, n: int, flips) -> list[tuple[int, int, int]]:
    """Faces of the (m+1) x (n+1) vertex grid (vertex i (n+1) + j), square (i, j) split
    along the diagonal chosen by ``flips[i n + j]``; every face positively oriented."""
    faces = []
    for i in range(m):
        for j in range(n):
            a, b = i * (n + 1) + j, (i + 1) * (n + 1) + j
            if flips[i * n + j]:
                faces += [(a, b, a + 1), (b, b + 1, a + 1)]
            else:
                faces += [(a, b, b + 1), (a, b + 1, a + 1)]
    return faces


@once
@st.composite
def planar_meshes(draw, heights: bool = False, min_size: int = 1, max_size: int = 3,
                  max_m: int | None = None):
    """An m x n grid (min_size <= n <= max_size, min_size <= m <= max_m or max_size) in z = 0, each square split along a drawn diagonal, every
    vertex moved by at most 3/16 in x and y (faces stay positively oriented: a move
    below 1/5 cannot collapse a right triangle of legs 1).  ``heights``: z drawn in
    eighths (a jittered grid in R^3)."""
    if not 1 <= min_size <= max_size:
        raise ValueError(f"need 1 <= min_size <= max_size, got {min_size}, {max_size}")
    m = draw(st.integers(min_size, max_size if max_m is None else max_m))
    n = draw(st.integers(min_size, max_size))
    nv = (m + 1) * (n + 1)
    jit = draw(st.lists(st.tuples(st.integers(-3, 3), st.integers(-3, 3)), min_size=nv, max_size=nv))
    zs = draw(st.lists(st.integers(-4, 4), min_size=nv, max_size=nv)) if heights else [0] * nv
    flips = draw(st.lists(st.booleans(), min_size=m * n, max_size=m * n))
    pts = []
    for i in range(m + 1):
        for j in range(n + 1):
            dx, dy = jit[i * (n + 1) + j]
            pts.append((i + Fraction(dx, 16), j + Fraction(dy, 16), Fraction(zs[i * (n + 1) + j], 8)))
    faces = grid_faces(m, n, flips)
    kind = "jittered grid" if heights else "planar grid"
    return mesh_case(pts, faces, f"{kind} {m}x{n}")


def jittered_grids():
    """Grids with drawn heights: simplicial disks in R^3."""
    return planar_meshes(heights=True)


_H = Fraction(7, 8)      # ~ sqrt(3)/2: the lattice triangles have angles 59.5 and 60.3 degrees


_NO_HEIGHT = st.just(0)


@st.composite
def acute_meshes(draw, max_components: int = 1, heights: bool = True):
    """Triangular lattices (angles ~60 degrees) moved by at most 1/32 per coordinate:
    every angle stays below 70 degrees, so every cotan weight is positive (boundary
    ones too).  ``max_components`` > 1 draws a disjoint union of such patches."""
    k = draw(st.integers(1, max_components))
    pts, faces = [], []
    for comp in range(k):
        rows = draw(st.integers(1, 3))
        cols = draw(st.integers(1, 3))
        nv = (rows + 1) * (cols + 1)
        jit = draw(st.lists(st.tuples(st.integers(-1, 1), st.integers(-1, 1),
                                      st.integers(-1, 1) if heights else _NO_HEIGHT),
                            min_size=nv, max_size=nv))
        base = len(pts)
        for j in range(rows + 1):
            for i in range(cols + 1):
                dx, dy, dz = jit[j * (cols + 1) + i]
                pts.append((10 * comp + i + Fraction(j, 2) + Fraction(dx, 32),
                            j * _H + Fraction(dy, 32), Fraction(dz, 32)))

        def vid(i, j, base=base, cols=cols):
            return base + j * (cols + 1) + i

        for j in range(rows):
            for i in range(cols):
                faces += [(vid(i, j), vid(i + 1, j), vid(i, j + 1)),
                          (vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1))]
    return mesh_case(pts, faces, f"acute lattice, {k} component(s)")


@st.composite
def obtuse_fans(draw):
    """A star of k = 3..7 ring points at drawn radii 1..3 around a centre moved off the
    middle: obtuse and needle triangles, negative cotan weights (E3.12, R3.3)."""
    k = draw(st.integers(3, 7))
    radii = draw(st.lists(st.integers(1, 3), min_size=k, max_size=k))
    cx, cy = draw(st.integers(-12, 12)), draw(st.integers(-12, 12))
    zs = draw(st.lists(st.integers(-2, 2), min_size=k + 1, max_size=k + 1))
    ring = []
    for t in range(k):           # directions rounded to 1/64: exact dyadic points
        ang = 2 * math.pi * t / k
        ring.append((radii[t] * Fraction(round(math.cos(ang) * 64), 64),
                     radii[t] * Fraction(round(math.sin(ang) * 64), 64)))
    faces = [(0, 1 + t, 1 + (t + 1) % k) for t in range(k)]
    centre = (Fraction(cx, 16), Fraction(cy, 16))
    if not _orientation_ok([centre] + ring, faces):
        centre = (Fraction(0), Fraction(0))
    pts = [(centre[0], centre[1], Fraction(zs[0], 8))] + \
          [(x, y, Fraction(z, 8)) for (x, y), z in zip(ring, zs[1:])]
    return mesh_case(pts, faces, f"fan k={k} radii={radii} centre=({cx}/16, {cy}/16)")


@st.composite
def obtuse_quads(draw):
    """Two triangles on a diagonal of length L, apexes at heights h1, h2 (sixteenths):
    low apexes make the opposite angles sum to more than pi (a negative weight)."""
    L = draw(st.integers(1, 8))
    x1, x2 = draw(st.integers(0, 4 * L)), draw(st.integers(0, 4 * L))
    h1, h2 = draw(st.integers(1, 16)), draw(st.integers(1, 16))
    z = draw(st.integers(-4, 4))
    pts = [(0, 0, 0), (L, 0, 0), (Fraction(x1, 4), Fraction(h1, 16), Fraction(z, 16)),
           (Fraction(x2, 4), -Fraction(h2, 16), 0)]
    return mesh_case(pts, [(0, 1, 2), (1, 0, 3)], f"quad L={L} apexes ({x1}/4,{h1}/16), ({x2}/4,-{h2}/16)")


#: near ties are drawn 2**-k off an exact tie, k one of these (evenly): 1e-6 .. 6e-14
#: relative, up to where float64's own tie bound begins (k about 45 on the circle of radius
#: 5), denser towards that end: a tolerance of 1e-6 relative shows from k = 20 on, one of
#: 1e-10 only from k = 35 or so, and one fine near tie shows every coarser tolerance.
#: First (what a failure shrinks to, and what Hypothesis's simplest examples draw) 40: the
#: finest that every quad drawn decides in float64, so it shows any tolerance of 1e-12
#: relative or more.  (``integers(20, 40)`` would draw 20 in about half of the examples.)
NEAR_TIE_EXPONENTS = (40, 20, 24, 28, 31, 34, 36, 38, 41, 42, 43, 44)


def _near_tie_quad(draw, tie: bool = True):
    """(exact points, recipe) of :func:`near_cocircular_quads` (``tie``: the exact tie is
    drawn too, in one draw of three)."""
    from .planar_points import CIRCLE5
    picks = sorted(draw(st.lists(st.integers(0, len(CIRCLE5) - 1), min_size=4, max_size=4,
                                 unique=True)))
    a, b, c, d = (tuple(Fraction(x) for x in CIRCLE5[i]) for i in picks)   # counterclockwise
    moved = draw(spread((False, True, True))) if tie else True
    k = draw(spread(NEAR_TIE_EXPONENTS)) if moved else None
    # in (the edge not Delaunay by a hair, what a tolerance "for robustness" calls
    # Delaunay) two times of three, out (Delaunay by a hair) the third
    inward = moved and draw(spread((True, True, False)))
    if moved:
        scale = 1 - Fraction(1, 2 ** k) if inward else 1 + Fraction(1, 2 ** k)
        d = (d[0] * scale, d[1] * scale)
    # tilted: rotated about the x axis by atan(4/3) and scaled by 5, (x, y) -> (5 x, 3 y,
    # 4 y): still exact integers (dyadic after the move), still on one circle
    tilt = draw(st.booleans())
    pts = [(5 * x, 3 * y, 4 * y) if tilt else (x, y, Fraction(0)) for x, y in (a, b, c, d)]
    recipe = ("cocircular quad" + (f", a corner moved {'in' if inward else 'out'} by 2^-{k}"
                                   if moved else "") + (", tilted" if tilt else ""))
    return pts, recipe


@st.composite
def near_cocircular_quads(draw):
    """Two triangles on four points of the circle of radius 5 (integer points: an exact
    tie, cot a + cot b = 0 on the diagonal) with the fourth point moved radially by a
    relative 2**-k, k in :data:`NEAR_TIE_EXPONENTS` (in, not Delaunay, or out: Delaunay,
    by a margin of 1e-6 .. 6e-14; in two times of three), in two draws of three, or not
    at all: every sign decision on the diagonal (a Delaunay flag, a weight's sign, a flip)
    is made at the tie or just beside it, where an absolute or relative tolerance decides
    it wrongly.  In z = 0, or tilted (rotated out of it, exactly).  Shrinks to the exact
    tie in the plane."""
    pts, recipe = _near_tie_quad(draw)
    return mesh_case(pts, [(0, 1, 2), (0, 2, 3)], recipe)


_MOVED_QUADS = st.composite(lambda d: _near_tie_quad(d, tie=False))()


@st.composite
def near_cocircular_meshes(draw, max_quads: int = 4):
    """1 .. ``max_quads`` :func:`near_cocircular_quads` side by side (64 apart in x, each a
    component of its own), each moved in or out by its own 2**-k (never the exact tie:
    :func:`near_cocircular_quads` in :func:`obtuse_meshes` draw it): several near ties per
    example, since only a move in one direction, at a fine enough k, shows a given
    tolerance (1e-10 relative: an inward move with k >= 35, about one quad in three).
    Shrinks to one quad moved in by 2**-40 (a list: the shrinker deletes the quads that
    do not fail, whichever is the one that does)."""
    quads = draw(st.lists(_MOVED_QUADS, min_size=1, max_size=max_quads))
    count = len(quads)
    pts, faces, recipes = [], [], []
    for i, (quad, recipe) in enumerate(quads):
        faces += [(len(pts), len(pts) + 1, len(pts) + 2), (len(pts), len(pts) + 2, len(pts) + 3)]
        pts += [(x + 64 * i, y, z) for x, y, z in quad]
        recipes.append(recipe)
    return mesh_case(pts, faces, "; ".join(recipes) if count == 1 else
                     f"{count} quads side by side: " + "; ".join(recipes))


def with_traps_beside(meshes):
    """``meshes`` with, each in one draw of two, a near-tie quad (as in
    :func:`near_cocircular_meshes`) and a :func:`convex_fans` beside them, each a component
    of its own 64 to the left: every example meets a near tie and a flip cascade besides
    its own kind (a default run's 25 examples are too few to count on drawing each kind
    often).  Shrinks to the mesh alone."""
    @st.composite
    def build(draw):
        c = draw(meshes)
        extra = []
        if draw(st.booleans()):
            quad, recipe = _near_tie_quad(draw, tie=False)
            extra.append((quad, ((0, 1, 2), (0, 2, 3)), recipe))
        if draw(st.booleans()):
            fan = draw(convex_fans())
            extra.append((fan.positions, fan.faces, fan.recipe))
        if not extra:
            return c
        pts, faces, recipes = list(c.positions), [tuple(f) for f in c.faces], [c.recipe]
        left = min(p[0] for p in pts)
        for q, fs, recipe in extra:
            shift = left - 64 - max(p[0] for p in q)
            faces += [tuple(len(pts) + v for v in f) for f in fs]
            pts += [(x + shift, y, z) for x, y, z in q]
            left = shift + min(p[0] for p in q)
            recipes.append(f"beside it {recipe}")
        return mesh_case(pts, faces, "; ".join(recipes))
    return build()


def with_reversed_faces(meshes):
    """``meshes`` with, in about one draw of three, 1 to 3 drawn faces listed the other way:
    the same surface inconsistently oriented (an orientable one stays orientable, as a mesh
    file may list it), where code that finds the face across an edge i -> j as the face
    listing j -> i takes an interior edge for a boundary edge (and a Delaunay test, a flip
    or a weight is skipped there).  Shrinks to none, then to face 0 alone."""
    from dataclasses import replace

    @st.composite
    def build(draw):
        c = draw(meshes)
        if not draw(spread((False, False, True))) or not c.faces:
            return c
        which = sorted(set(draw(st.lists(st.integers(0, len(c.faces) - 1), min_size=1,
                                         max_size=3))))
        faces = tuple((f[0], f[2], f[1]) if i in which else tuple(f)
                      for i, f in enumerate(c.faces))
        return replace(c, faces=faces, recipe=f"{c.recipe}, face(s) {which} reversed",
                       _given=None, _cache={})
    return build()


def coned(meshes):
    """``meshes`` with, in about one draw of two, every boundary loop closed by a cone to a
    new apex above the loop's centroid (at the height of the loop's extent): a closed
    surface with the drawn triangulation inside it, every edge decision of which is
    unchanged (the cone's faces only touch former boundary edges).  Implementations that
    decline boundary (a tufted cover, a closed-surface solver) are given the same near
    ties and flip cascades.  Shrinks to the open mesh."""
    from dataclasses import replace

    @st.composite
    def build(draw):
        c = draw(meshes)
        if not draw(st.booleans()):
            return c
        t = c.triangulation
        loops = t.boundary_loops()
        if not loops:
            return c
        pts, faces = list(c.positions), [tuple(f) for f in c.faces]
        apex_of = {}
        for loop in loops:
            xs = [c.positions[v] for v in loop]
            centre = [sum(p[i] for p in xs) / len(xs) for i in range(3)]
            extent = max(max(p[i] for p in xs) - min(p[i] for p in xs) for i in range(3))
            apex = (centre[0], centre[1], centre[2] + extent)
            for v in loop:
                apex_of[v] = len(pts)
            pts.append(tuple(_dyadic(x) for x in apex))
        # the faces' own direction of each boundary edge, reversed: the cone is oriented
        # with the surface wherever the surface is
        uses = {}
        for f in c.faces:
            for i in range(3):
                a, b = f[i], f[(i + 1) % 3]
                uses.setdefault(frozenset((a, b)), []).append((a, b))
        for pairs in uses.values():
            if len(pairs) == 1:
                a, b = pairs[0]
                faces.append((b, a, apex_of[a]))
        for a, b, x in faces[len(c.faces):]:
            p, q, r = pts[a], pts[b], pts[x]
            u = [q[i] - p[i] for i in range(3)]
            w = [r[i] - p[i] for i in range(3)]
            if all(u[(i + 1) % 3] * w[(i + 2) % 3] == u[(i + 2) % 3] * w[(i + 1) % 3]
                   for i in range(3)):
                return c        # an apex on a boundary edge's line (no closed surface here)
        return replace(c, positions=tuple(pts), faces=tuple(faces),
                       recipe=f"{c.recipe}, {len(loops)} boundary loop(s) coned off",
                       _given=None, _cache={}, boundary=(), expected=None, chi=None)
    return build()


@st.composite
def near_cocircular_point_sets(draw):
    """4 to 6 of the integer points of the circle of radius 5 (an exact cocircular set)
    around a drawn integer centre, one of them moved radially by a relative 2**-k, k in
    :data:`NEAR_TIE_EXPONENTS`, in or out (the exact ties come with
    :func:`.planar_points.rational_point_sets`' cocircular subsets): planar Delaunay
    decided beside a tie, where a float32 rounding of the points (k > 24), a joggle or an
    epsilon picks the other diagonal.  Rounded to the input format (a float32
    implementation gets the rounded points: its ties are exact).  Shrinks to four points,
    the last moved in by 2**-40."""
    from .planar_points import CIRCLE5
    count = draw(spread((4, 5, 6)))
    picks = sorted(draw(st.lists(st.integers(0, len(CIRCLE5) - 1), min_size=count,
                                 max_size=count, unique=True)))
    pts = [(Fraction(x), Fraction(y)) for x, y in (CIRCLE5[i] for i in picks)]
    i = count - 1 - draw(st.integers(0, count - 1))
    k = draw(spread(NEAR_TIE_EXPONENTS))
    scale = 1 - Fraction(1, 2 ** k) if draw(spread((True, False))) else 1 + Fraction(1, 2 ** k)
    pts[i] = (pts[i][0] * scale, pts[i][1] * scale)
    cx, cy = draw(st.integers(-3, 3)), draw(st.integers(-3, 3))
    pts = tuple((representable(x + cx), representable(y + cy)) for x, y in pts)
    assume(len(set(pts)) == len(pts))
    return pts


@once
@st.composite
def convex_fans(draw, max_points: int = 10):
    """A convex polygon of 4 .. ``max_points`` points on the parabola y = x^2 (exact
    integers, x = 0, 1, ...), triangulated as the fan from a drawn corner (the long fans
    of CAD caps and of sweep triangulations), as a flat mesh in z = 0: its Delaunay
    triangulation is reached by a cascade of flips (a flip makes an edge met earlier
    non-Delaunay; one pass over the edges stops early from 6 points on)."""
    n = draw(st.integers(4, max_points))
    apex = draw(st.integers(0, n - 1))
    pts = [(Fraction(i), Fraction(i * i), Fraction(0)) for i in range(n)]   # counterclockwise
    order = [(apex + k) % n for k in range(n)]
    faces = [(order[0], order[k], order[k + 1]) for k in range(1, n - 1)]
    return mesh_case(pts, faces, f"fan of {n} points on a parabola from corner {apex}")


def sweep_meshes(max_points: int = 12):
    """Straight-line triangulations of planar point sets (:func:`.planar_points.planar_triangulations`:
    the sweep triangulation's long fans, flipped at random, sometimes a boundary face
    removed) as flat meshes in z = 0: far from Delaunay, so that an intrinsic flip algorithm
    meets cascades (a flip makes a neighbouring edge non-Delaunay, which must be flipped
    in turn; one pass over the edges stops early); or, in one draw of two, a
    :func:`convex_fans` (a cascade in 4 faces).  Shrinks to a triangle."""
    from .planar_points import planar_triangulations

    def mesh(example):
        pts, faces, _ = example
        return mesh_case([(x, y, 0) for x, y in pts], faces,
                         f"planar triangulation of {len(pts)} points, {len(faces)} faces")
    return st.one_of(planar_triangulations(max_points).map(mesh), convex_fans())


def scaled_planar(triangulations):
    """``(points, faces, on_hull)`` of ``triangulations`` with the points multiplied by 2**k,
    k from :data:`SCALES` (exact powers of two; an in-circle determinant, of degree 4 in
    the coordinates, stays a normal number): an absolute epsilon on it (``det > 1e-9``)
    decides nothing on a small point set.  Shrinks to scale 1."""
    @st.composite
    def build(draw):
        pts, faces, on_hull = draw(triangulations)
        k = draw(spread(SCALES[input_format().name]))
        if k:
            s = Fraction(2) ** k
            pts = tuple((x * s, y * s) for x, y in pts)
        return pts, faces, on_hull
    return build()


#: valences of :func:`valence_fans`, simplest first: small stars, and just past the fixed
#: one-ring widths of C and GPU codes (16, 32 neighbours)
FAN_VALENCES = (3, 4, 5, 6, 8, 12, 16, 17, 20, 24, 32, 33)


@st.composite
def valence_fans(draw):
    """The star of one vertex with n neighbours on the unit circle (n faces: a disk), n
    drawn evenly from :data:`FAN_VALENCES`, exactly planar or with the centre lifted by
    2**-k: a vertex of high valence in a small mesh (a one-ring table of fixed width
    drops the weights past its last column).  Shrinks to the planar fan of valence 3."""
    n = draw(spread(FAN_VALENCES))
    lift = draw(spread((0, 1, 4, 10, FAN_LIFT_LIMIT)))      # 0: exactly planar
    s = _built(("fan", n, lift), lambda: variants.fan(n, lift or None))
    return mesh_case(s.positions, s.triangulation.faces, f"fan of valence {n}" + (
        f", centre lifted by 2^-{lift}" if lift else ", planar"))


def obtuse_meshes():
    """Meshes with obtuse and needle triangles (negative cotan weights are common), and
    quads at or beside an exact Delaunay tie (:func:`near_cocircular_quads`)."""
    return st.one_of(obtuse_quads(), obtuse_fans(), single_triangles(), near_cocircular_quads())


_PLATONIC = {"tetrahedron": surfaces.tetrahedron, "octahedron": surfaces.octahedron,
           "icosahedron": surfaces.icosahedron}


@once
@st.composite
def closed_meshes(draw):
    """Tetrahedron, octahedron or icosahedron, maybe 1-to-4 subdivided (midpoints), every
    vertex moved by at most 2/64 per coordinate."""
    name = draw(spread(sorted(_PLATONIC)))
    s = _PLATONIC[name]()
    t, pts = s.triangulation, [tuple(p) for p in s.positions]
    sub = draw(st.booleans())
    if sub and name != "icosahedron":
        t, mids = t.subdivide_1to4()
        pts += [tuple((x + y) / 2 for x, y in zip(pts[i], pts[j])) for i, j in mids]
    jit = draw(st.lists(st.tuples(*[st.integers(-2, 2)] * 3), min_size=len(pts), max_size=len(pts)))
    pts = [tuple(_dyadic(x) + Fraction(d, 64) for x, d in zip(p, dj)) for p, dj in zip(pts, jit)]
    return mesh_case(pts, t.faces, f"{name}{' 1-to-4' if sub else ''}, jittered")


@st.composite
def surface_meshes(draw, closed: bool | None = None, isolated: bool = False, far: bool = True):
    """:func:`jittered_surfaces` as a :class:`Example`: any topology, orientable or not,
    faces reversed, high valence, slivers alone, clustered or banded, several components,
    isolated and duplicated vertices (``isolated=True``: then :meth:`Example.surface`
    refuses the case, as the reference does; properties use :class:`~.laplacian.Exact`),
    any order; ``far``: scaled by 2**k and moved by 2**e times its size (the chapter-3
    bounds are relative to each face's own size: an implementation's edge vector
    V[j] - V[i] of two floats is rounded once, relatively, wherever the mesh lies).
    Shrinks towards the tetrahedron at the origin."""
    c = draw(jittered_surfaces(closed=closed, intrinsic=True, far=far, isolated=isolated))
    V, F = c.mesh
    return Example.of_mesh(tuple(tuple(Fraction(x) for x in p) for p in V), tuple(tuple(f) for f in F),
                    c.recipe)


def any_meshes(isolated: bool = False, far: bool = True):
    """Every kind above (``isolated=True``: also vertices used by no face; ``far``: as
    :func:`surface_meshes`): half the draws one of the small families (and fans of high
    valence, :func:`valence_fans`; a third of them with faces reversed,
    :func:`with_reversed_faces`), half :func:`surface_meshes`, where the wide classes are
    (reversed faces, Möbius strips, slivers, components, scales, offsets); shrinks
    towards a single triangle.  (The small families are one strategy, not flattened into
    the outer ``one_of``: seven families beside one :func:`surface_meshes` would leave it
    one draw in eight.)"""
    small = with_reversed_faces(st.one_of(
        single_triangles(), planar_meshes(), jittered_grids(), obtuse_meshes(),
        acute_meshes(), closed_meshes(), valence_fans()))
    if isolated:
        # the small families too: a vertex used by no face is a bug class of its own
        # (dropped and renumbered, a row of NaN), not only of the wide surfaces
        small = with_isolated(small, 1)
    return st.one_of(small, surface_meshes(isolated=isolated, far=far))


#: binary exponents of the scales drawn by :func:`scaled_meshes`, per input format: 0
#: (shrinks there; a quarter of the draws), and scales far from 1 at which products of
#: four coordinates (|cross|^2, l^2 l^2) still stay normal numbers of the format
#: (float64: 2**-800 .. 2**800; float32: 2**-96 .. 2**96), so only absolute thresholds
#: fail; below 1 in three draws of eight (an absolute epsilon of 1e-12 on a dot product
#: or a cross product bites from about 2**-20 down)
SCALES = {"float64": (0, 0, -24, 24, -64, 64, -200, 200),
          "float32": (0, 0, -8, 8, -12, 12, -24, 24),
          "float16": (0, 0, 0, 0, -1, 1, -2, 2)}


def scaled_meshes(meshes):
    """``meshes`` multiplied by 2**k, k drawn from :data:`SCALES` (exact: powers of two),
    and one draw in four moved by 2**e times its size (e up to the input format's
    offset, 30 in float64) along (+-1, +-1, +-1), rounded to the input format again.

    Scale-invariant quantities (cotan weights, angles) must not change, nor do
    translation-invariant ones.  Catches absolute thresholds (``if area < 1e-12``),
    unscaled epsilons and formulas that cancel in absolute coordinates.  Beyond these
    scales float64 itself runs out (e.g. libigl's ``doublearea`` squares the projected
    cross products, which underflow for coordinates below about 1e-77): that is a range
    limit, checked directly in the oracle tests, not here."""
    @st.composite
    def build(draw):
        c = draw(meshes)
        fmt = input_format()
        k = draw(spread(SCALES[fmt.name]))
        e = draw(st.integers(0, fmt.offset)) if draw(st.integers(0, 3)) == 3 else None
        if k == 0 and e is None:
            return c
        s = Fraction(2) ** k
        pts = [tuple(x * s for x in p) for p in c.positions]
        recipe = f"{c.recipe}, scaled by 2**{k}"
        if e is not None:
            signs = draw(st.integers(0, 7))
            size = max((abs(x) for p in pts for x in p), default=Fraction(1)) or Fraction(1)
            unit = Fraction(2) ** (size.numerator.bit_length() - size.denominator.bit_length() + e)
            shift = [-unit if signs >> d & 1 else unit for d in range(3)]
            try:
                pts = [tuple(representable(x + o) for x, o in zip(p, shift)) for p in pts]
            except OverflowError:
                assume(False)
            # rounding may have collapsed a face: not an example
            assume(not variants.degenerate_faces(pts, c.faces))
            recipe += f", moved by 2**{e} x its size"
        return Example.of_mesh(tuple(pts), c.faces, recipe, c.boundary, c.values, c.second)
    return build()


def with_isolated(meshes, max_isolated: int = 2):
    """``meshes`` with up to ``max_isolated`` vertices used by no face inserted at drawn
    indices (the faces renumbered around them), each at a far point or exactly at an
    existing vertex's position.  Shrinks to none."""
    @st.composite
    def build(draw):
        c = draw(meshes)
        k = draw(st.integers(0, max_isolated))
        if not k:
            return c
        pos, faces, spots = list(c.positions), [list(f) for f in c.faces], []
        for _ in range(k):
            v = draw(st.integers(0, len(pos) - 1))
            p = pos[v] if draw(st.booleans()) else floated_point(3 * x + 1 for x in pos[v])
            i = draw(st.integers(0, len(pos)))
            pos.insert(i, p)
            faces = [[w + (w >= i) for w in f] for f in faces]
            spots = [s + (s >= i) for s in spots] + [i]
        return Example.of_mesh(tuple(pos), tuple(tuple(f) for f in faces),
                        f"{c.recipe}, isolated vertices at {sorted(spots)}")
    return build()


_EIGHTHS = st.integers(-8, 8).map(lambda k: Fraction(k, 8))


def _values(n: int):
    return st.lists(_EIGHTHS, min_size=n, max_size=n)


def with_functions(meshes):
    """A mesh with two drawn vertex functions (eighths): ``values`` and ``second``."""
    @st.composite
    def build(draw):
        c = draw(meshes)
        f = draw(_values(c.n))
        g = draw(_values(c.n))
        return Example.of_mesh(c.positions, c.faces, c.recipe, c.boundary, tuple(f), tuple(g))
    return build()


def with_boundary(meshes, mesh_boundary: bool = False, unused: int = 0):
    """A mesh with a nonempty drawn boundary set V0 (or its boundary vertices) and
    values on all vertices (only those on V0 are used).  V0 is listed sorted, reversed
    or shuffled (the order an implementation receives it in): a solver that assumes
    sorted indices fails on the others.  Never a vertex listed twice: the protocol's
    boundary indices are distinct, as in the libraries (gpytoolbox asserts it, LaPy raises,
    libigl's min_quad_with_fixed crashes on a repeat).  ``unused``: up to this many
    vertices used by no face (drawn 0 first), at drawn rows of V, each in V0 (no face
    gives it an equation): a solver that drops them must still give them their values."""
    @st.composite
    def build(draw):
        c = draw(meshes)
        extra = draw(st.integers(0, unused)) if unused else 0
        if extra:
            c = _with_unused_vertices(c, draw(st.lists(st.integers(0, c.n), min_size=extra,
                                                       max_size=extra)))
        # the surface on the vertices some face uses (a triangulation has no other)
        used = sorted({v for f in c.faces for v in f})
        at = {v: k for k, v in enumerate(used)}
        t = Triangulation.from_faces([[at[v] for v in f] for f in c.faces],
                                     n_vertices=len(used))
        if mesh_boundary:
            V0 = [used[k] for k in range(len(used)) if t.is_boundary_vertex(k)]
        else:
            picks = draw(st.lists(st.booleans(), min_size=c.n, max_size=c.n))
            V0 = [v for v in range(c.n) if picks[v]]
        comps = [sorted({used[v] for f in comp for v in t.faces[f]}) for comp in t.components()]
        for comp in comps:                      # every component meets V0
            if not any(v in V0 for v in comp):
                V0.append(comp[draw(st.integers(0, len(comp) - 1))])
        V0 += [v for v in range(c.n) if v not in at and v not in V0]
        f = draw(_values(c.n))
        g = draw(_values(c.n))
        V0 = sorted(V0)
        order = draw(st.integers(0, 2))          # sorted, reversed, shuffled
        if order == 1:
            V0.reverse()
        elif order == 2:
            random.Random(draw(st.integers(0, 1 << 16))).shuffle(V0)
        recipe = c.recipe + ("", ", V0 reversed", ", V0 shuffled")[order]
        return Example.of_mesh(c.positions, c.faces, recipe, tuple(V0), tuple(f), tuple(g))
    return build()


def _with_unused_vertices(c, rows) -> Example:
    """``c`` with a vertex used by no face inserted at each of ``rows`` (indices of the new
    V, counted before each insertion; the faces renumbered), placed 3 units past the
    mesh's largest x: a point, as an OBJ file's leftover vertex."""
    positions, faces = list(c.positions), [list(f) for f in c.faces]
    far = max(p[0] for p in positions) + 3
    for r in rows:
        r = min(r, len(positions))
        positions.insert(r, (far, *positions[0][1:]))
        faces = [[v + (v >= r) for v in f] for f in faces]
    return Example.of_mesh(positions, faces, c.recipe + f", unused vertices at rows {list(rows)}")


@dataclass(frozen=True)
class GraphCase:
    """A weighted graph (edges ``(i, j, nu)``, several between two vertices allowed) with a
    boundary set V0 (nonempty, meeting every component) and values."""

    n: int
    edges: tuple
    boundary: tuple
    values: tuple


@st.composite
def weighted_graphs(draw, positive: bool = True, max_vertices: int = 7, connected: bool = True):
    """Graphs from a drawn spanning tree plus extra edges (repeats allowed), weights
    p/q with small p, q (``positive``: p >= 1, else any sign), a nonempty V0."""
    n = draw(st.integers(2, max_vertices))
    w = st.builds(Fraction, st.integers(1 if positive else -4, 6), st.integers(1, 4))
    edges = []
    for v in range(1, n):
        if connected or draw(st.booleans()):
            edges.append((draw(st.integers(0, v - 1)), v, draw(w)))
    extra = draw(st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1), w), max_size=n))
    edges += [e for e in extra if e[0] != e[1]]
    picks = draw(st.lists(st.booleans(), min_size=n, max_size=n))
    V0 = {v for v in range(n) if picks[v]}
    # every component meets V0
    parent = list(range(n))

    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x
    for i, j, _ in edges:
        parent[find(i)] = find(j)
    roots = {}
    for v in range(n):
        roots.setdefault(find(v), []).append(v)
    for comp in roots.values():
        if not V0 & set(comp):
            V0.add(comp[0])
    vals = draw(st.lists(st.integers(-9, 9).map(Fraction), min_size=n, max_size=n))
    return GraphCase(n, tuple(edges), tuple(sorted(V0)), tuple(vals))
