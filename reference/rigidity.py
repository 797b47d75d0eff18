"""The uniqueness half of Alexandrov's theorem (Theorem 2.10) on examples, exactly.

Theorem 2.10: a convex polyhedral metric on the sphere is the boundary of a convex
polytope P, and P is unique up to a rigid motion.  Existence is a pure existence
statement; uniqueness can be checked on examples in two ways, both exact:

* **Locally** (Dehn's theorem, 1916, the infinitesimal form of Cauchy's rigidity of
  convex polytopes): every motion of the vertices of a triangulated strictly convex
  polytope that keeps every edge length to first order is a rigid motion.  In linear
  algebra: the *rigidity matrix* R (one row per edge ij, with ``p_i - p_j`` in the
  columns of i and ``p_j - p_i`` in those of j, so ``R v = 0`` says
  ``<p_i - p_j, v_i - v_j> = 0`` for every edge) has a kernel of dimension 6 exactly,
  the infinitesimal rigid motions (3 translations, 3 rotations) of points spanning R^3
  (:func:`infinitesimal_motions`).  The rank is computed exactly over the rationals.
  A polytope with a vertex *inside* a face (flat, not strictly convex) flexes: the
  vertex can move off the face to first order.

* **Convexity is needed** (the notes: "the polyhedral surface we seek is not uniquely
  determined"): a vertex of valence 3 reflected through the plane of its three
  neighbours keeps every edge length, so the reflected surface has the same metric
  and triangulation; it is not congruent to P (a rigid motion fixing the other
  vertices, which span R^3, is the identity) and not convex
  (:func:`popped_vertex`, :func:`is_convex_surface`).  Of the two realisations with
  this triangulation exactly one is convex, as the theorem says.

Positions are exact rationals; :func:`capped` builds a valence-3 vertex on any face
of a convex polytope (a low pyramid, its height halved until it sees that face only).
"""

from __future__ import annotations

from fractions import Fraction

from .errors import InputError
from .polyhedral import PolyhedralSurface, orientation3d
from .sparse import rank
from .linear import sub

__all__ = ["rigidity_matrix", "infinitesimal_motions", "is_infinitesimally_rigid",
           "is_convex_surface", "capped", "popped_vertex", "is_congruent"]


def rigidity_matrix(surface: PolyhedralSurface) -> dict[int, dict[int, Fraction]]:
    """The rigidity matrix of a polyhedral surface in R^3: ``{edge: {3 i + k: value}}``
    (nonzero entries only), row ij holding ``p_i - p_j`` at vertex i and ``p_j - p_i``
    at vertex j.  Exact."""
    if surface.dimension != 3:
        raise InputError(f"rigidity is about surfaces in R^3, got dimension {surface.dimension}")
    t, p = surface.triangulation, surface.positions
    rows = {}
    for e in range(t.n_edges):
        i, j = t.edge_vertices(e)
        row: dict[int, Fraction] = {}
        for a, b in ((i, j), (j, i)):
            for k, x in enumerate(sub(p[a], p[b])):
                if x:
                    row[3 * a + k] = row.get(3 * a + k, 0) + x
        rows[e] = {c: x for c, x in row.items() if x}
    return rows


def infinitesimal_motions(surface: PolyhedralSurface) -> int:
    """The dimension of the space of infinitesimal motions keeping every edge length to
    first order: ``3 n - rank R`` (exact).  At least 6 for points spanning R^3 (the rigid
    motions); exactly 6 means infinitesimally rigid (Dehn)."""
    return 3 * surface.n_vertices - rank(rigidity_matrix(surface))


def is_infinitesimally_rigid(surface: PolyhedralSurface) -> bool:
    """Dehn's theorem's conclusion: the only infinitesimal isometric motions are the
    rigid ones (``infinitesimal_motions == 6``).

    >>> from ddg_oracle.reference import surfaces
    >>> is_infinitesimally_rigid(surfaces.octahedron())
    True
    """
    return infinitesimal_motions(surface) == 6


def is_convex_surface(surface: PolyhedralSurface) -> bool:
    """Every vertex lies on the inner side of (or on) the plane of every face: the
    surface is the boundary of a convex polytope (faces oriented outward, the
    orientation of :func:`ddg_oracle.reference.surfaces.convex_hull`).  Exact."""
    p = surface.positions
    for f in surface.triangulation.faces:
        a, b, c = (p[v] for v in f)
        if any(orientation3d(a, b, c, x) > 0 for x in p):
            return False
    return True


def capped(surface: PolyhedralSurface, face: int) -> PolyhedralSurface:
    """``surface`` (a convex polytope, faces outward) with a low pyramid on ``face``: a
    new vertex above the face's centroid, joined to its three corners (valence 3); the
    height starts at the face's size and is halved until the result is convex."""
    t, p = surface.triangulation, list(surface.positions)
    a, b, c = (p[v] for v in t.faces[face])
    u, w = sub(b, a), sub(c, a)
    normal = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
    centroid = tuple((x + y + z) / 3 for x, y, z in zip(a, b, c))
    faces = [f for g, f in enumerate(t.faces) if g != face]
    i, j, k = t.faces[face]
    n = len(p)
    faces += [(i, j, n), (j, k, n), (k, i, n)]
    height = Fraction(1)
    for _ in range(200):
        apex = tuple(x + height * m for x, m in zip(centroid, normal))
        out = PolyhedralSurface.from_arrays(p + [apex], faces)
        if is_convex_surface(out) and all(
                orientation3d(*(out.positions[v] for v in f), apex) < 0
                for f in faces[:-3]):
            return out
        height /= 2
    raise InputError(f"face {face}: no low pyramid keeps the polytope convex")


def popped_vertex(surface: PolyhedralSurface, v: int) -> PolyhedralSurface:
    """The vertex ``v`` of valence 3 reflected through the plane of its three neighbours:
    the same triangulation and the same edge lengths (the neighbours are on the mirror),
    exact rational positions."""
    t, p = surface.triangulation, list(surface.positions)
    ring = sorted(set(t.neighbours(v)))
    if len(ring) != 3 or t.valence(v) != 3:
        raise InputError(f"vertex {v} has valence {t.valence(v)}, not 3")
    a, b, c = (p[x] for x in ring)
    u, w = sub(b, a), sub(c, a)
    normal = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
    d = sub(p[v], a)
    s = 2 * sum(x * y for x, y in zip(d, normal)) / sum(x * x for x in normal)
    p[v] = tuple(x - s * m for x, m in zip(p[v], normal))
    return surface.with_positions(p)


def is_congruent(a: PolyhedralSurface, b: PolyhedralSurface) -> bool:
    """Some rigid motion (or reflection) maps vertex i of ``a`` to vertex i of ``b`` for
    every i: all pairwise squared distances agree (a labelled point set is determined by
    them up to an isometry of R^3).  Exact."""
    pa, pb = a.positions, b.positions
    if len(pa) != len(pb):
        return False

    def d2(p, i, j):
        return sum(x * x for x in sub(p[i], p[j]))

    return all(d2(pa, i, j) == d2(pb, i, j) for i in range(len(pa)) for j in range(i))
