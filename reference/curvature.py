"""Curvature of polyhedral surfaces (chapter 2 of the notes), exact.

Intrinsic quantities (everything here that needs edge lengths only) take a
:class:`~ddg_oracle.reference.metric.PiecewiseFlatSurface` or a
:class:`~ddg_oracle.reference.polyhedral.PolyhedralSurface` (whose ``metric()`` is used):

* corner angles, angle sums, the discrete Gaussian curvature (angle defect)
  K(p) = 2 pi - sum of the angles at an interior vertex p (D2.2), the turning
  angle pi - sum at a boundary vertex (R2.4), their total and the exact
  Gauss-Bonnet decision sum = 2 pi chi (T2.6, R2.4), the elliptic / flat /
  hyperbolic type of a vertex (D2.2, L2.4).

Extrinsic quantities take a polyhedral surface in R^3 with exact positions:

* the star predicates of Lemma 2.4 (convex, planar, saddle star);
* dihedral angles theta(e), the discrete mean curvature H(e) = 1/2 theta(e) l(e)
  and its total H(S) (D2.3), and the Steiner coefficients (T2.7, R2.5);
* rigid motions with rational rotations (Cayley transform) and "pushing a
  vertex in" (T2.5, X2.3), isometries under which K does not change.

Values are exact: angles are :class:`~ddg_oracle.reference.exact.Angle`, lengths and
areas :class:`~ddg_oracle.reference.exact.Surd`, angle-times-length sums
:class:`~ddg_oracle.reference.exact.measures.AngleLength`.  No float decides anything.
Faces of zero area raise :class:`~ddg_oracle.reference.errors.DegenerateFace` naming the
face (from ``PolyhedralSurface.metric()``).

>>> from ddg_oracle.reference import surfaces
>>> from ddg_oracle.reference.exact import pi
>>> cube = surfaces.cube()
>>> set(angle_defects(cube).values()) == {pi / 2}          # X2.1
True
>>> total_curvature(cube) == 4 * pi, gauss_bonnet_holds(cube)
(True, True)
>>> total_mean_curvature(cube) == 3 * pi                    # D2.3 / T2.7
True
"""

from __future__ import annotations

from fractions import Fraction

from . import curvature_fast
from .errors import InputError
from .exact import Angle, Surd, corner_angle, pi, sign, sqrt
from .exact.measures import AngleLength
from .exact.rationals import points_on_common_denominator, shared_denominator
from .exact.surds import exact_sum
from .metric import as_metric
from .polyhedral import PolyhedralSurface
from .combinatorics import corner_of, cyclic, face_of, opposite_corner
from .linear import cross, det3, dot, sub

__all__ = [
    "corner_angles", "corner_angles_from_cotangents", "angle_sums", "angle_sums_from_corners",
    "angle_sum_at", "angle_defects",
    "turning_angles", "total_curvature", "gauss_bonnet_holds", "gauss_bonnet_holds_by_faces",
    "vertex_type",
    "is_convex_star", "is_planar_star", "is_saddle_star",
    "dihedral_angles", "mean_curvature", "mean_curvature_at", "total_mean_curvature",
    "steiner_coefficients",
    "cayley_rotation", "rigid_motion", "push_vertex_in",
]

_ZERO_ANGLE = Angle()


# --- the two kinds of input -----------------------------------------------------------------------


def _in_r3(surface, what: str) -> PolyhedralSurface:
    """A polyhedral surface in R^3 with non-degenerate faces (extrinsic quantities)."""
    if not isinstance(surface, PolyhedralSurface):
        raise InputError(f"{what} needs vertex positions: expected a PolyhedralSurface, got "
                         f"{type(surface).__name__}")
    if surface.dimension != 3:
        raise InputError(f"{what} needs a surface in R^3, got dimension {surface.dimension}")
    surface.metric()                  # raises DegenerateFace naming a zero-area face
    return surface


def _sum_angles(angles) -> Angle:
    parts: dict = {}
    r = Fraction(0)
    for a in angles:
        for c, m in a.parts.items():
            parts[c] = parts.get(c, 0) + m
        r += a.pi_coefficient
    return Angle(parts, r)


# --- Gaussian curvature (D2.2, T2.6, R2.4, L2.4) --------------------------------------------------


def corner_angles(surface) -> list[tuple[Angle, Angle, Angle]]:
    """The three corner angles of every face (D2.2, D2.6: what angle defects sum and the
    lengths determine), exact, each in (0, pi).

    Entry ``f`` lists the angles at corners 0, 1, 2 of face ``f`` (the corners
    of ``triangulation.faces[f]`` in order).  The definition is
    :func:`corner_angles_from_cotangents`; for a polyhedral surface, or a piecewise flat
    one with rational squared lengths, this returns the equal angles of
    :func:`ddg_oracle.reference.curvature_fast.corner_angles_fast` (tested angle by angle).

    >>> from ddg_oracle.reference import surfaces
    >>> from ddg_oracle.reference.exact import pi
    >>> corner_angles(surfaces.cube())[0] == (pi / 4, pi / 2, pi / 4)   # face (0, 1, 2)
    True
    """
    if curvature_fast.applies(surface):
        return curvature_fast.corner_angles_fast(surface)
    return corner_angles_from_cotangents(surface)


def corner_angles_from_cotangents(surface) -> list[tuple[Angle, Angle, Angle]]:
    """D2.6, the definition of :func:`corner_angles`: ``arccot`` of the metric's exact corner
    cotangents (:meth:`~ddg_oracle.reference.metric.PiecewiseFlatSurface.corner_angle`).
    Accepts every surface (irrational squared lengths too)."""
    m = as_metric(surface)
    return [(m.corner_angle(f, 0), m.corner_angle(f, 1), m.corner_angle(f, 2))
            for f in range(m.triangulation.n_faces)]


def angle_sums(surface) -> list[Angle]:
    """The sum of the corner angles at each vertex (the cone angle), exact.

    The definition is :func:`angle_sums_from_corners`.  For a polyhedral surface,
    or a piecewise flat one with rational squared lengths, this returns the equal
    list computed by :func:`ddg_oracle.reference.curvature_fast.angle_sums_fast` (integer
    arithmetic; equality tested angle by angle).
    """
    if curvature_fast.applies(surface):
        return curvature_fast.angle_sums_fast(surface)
    return angle_sums_from_corners(surface)


def angle_sums_from_corners(surface) -> list[Angle]:
    """The definition of :func:`angle_sums`: the corner angles of the metric
    (:meth:`~ddg_oracle.reference.metric.PiecewiseFlatSurface.corner_angle`) added vertex by
    vertex.  Accepts every surface (irrational squared lengths too)."""
    m = as_metric(surface)
    t = m.triangulation
    parts = [{} for _ in range(t.n_vertices)]
    r = [Fraction(0)] * t.n_vertices
    for f, face in enumerate(t.faces):
        for c, v in enumerate(face):
            a = m.corner_angle(f, c)
            acc = parts[v]
            for cot, k in a.parts.items():
                acc[cot] = acc.get(cot, 0) + k
            r[v] += a.pi_coefficient
    return [Angle(p, q) for p, q in zip(parts, r)]


def angle_sum_at(surface, v: int) -> Angle:
    """The sum of the corner angles at the one vertex ``v`` (D2.2), exact: as
    :func:`angle_sums` gives it, from the corners at ``v`` alone (its one fan: a
    triangulation's vertices are manifold)."""
    m = as_metric(surface)
    return _sum_angles(m.corner_angle(f, c) for f, c in m.triangulation.corners_around(v))


def angle_defects(surface) -> dict[int, Angle]:
    """D2.2: K(p) = 2 pi - (sum of the angles at p), for every interior vertex p.

    Integrated (not divided by an area), exact.  Boundary vertices are left
    out: their curvature is the turning angle (:func:`turning_angles`, R2.4).

    >>> from ddg_oracle.reference import surfaces
    >>> from ddg_oracle.reference.exact import pi
    >>> K = angle_defects(surfaces.disk(6))                   # the flat centre only
    >>> list(K), K[0] == 0
    ([0], True)
    """
    sums = angle_sums(surface)          # checks the surface first
    boundary = surface.triangulation.boundary_vertices()
    return {v: 2 * pi - s for v, s in enumerate(sums) if v not in boundary}


def turning_angles(surface) -> dict[int, Angle]:
    """R2.4: the turning angle phi(p) = pi - (sum of the angles at p) of each boundary vertex.

    Positive where the boundary turns towards the surface (a convex corner of a
    planar polygon), zero where it runs straight.
    """
    sums = angle_sums(surface)          # checks the surface first
    boundary = surface.triangulation.boundary_vertices()
    return {v: pi - s for v, s in enumerate(sums) if v in boundary}


def total_curvature(surface) -> Angle:
    """T2.6 / R2.4: sum of K(p) over interior vertices plus the turning angles at the boundary.

    2 pi |V_interior| + pi |V_boundary| - (sum of all corner angles), exact
    (the angle sums of :func:`angle_sums`, on its fast route where it applies).
    Equal to 2 pi chi (:func:`gauss_bonnet_holds`); certified numeric values
    come from ``total_curvature(s).enclosure(digits)``.

    >>> from ddg_oracle.reference import surfaces
    >>> from ddg_oracle.reference.exact import pi
    >>> total_curvature(surfaces.torus(3, 4)) == 0, total_curvature(surfaces.cube()) == 4 * pi
    (True, True)
    """
    sums = angle_sums(surface)          # checks the surface first
    t = as_metric(surface).triangulation
    boundary = len(t.boundary_vertices())
    interior = t.n_vertices - boundary
    return pi * (2 * interior + boundary) - _sum_angles(sums)


def gauss_bonnet_holds(surface) -> bool:
    """T2.6 / R2.4: decide exactly whether ``total_curvature(surface) == 2 pi chi``.

    The definition is :func:`gauss_bonnet_holds_by_faces`.  For a polyhedral
    surface, or a piecewise flat one with rational squared lengths, the same
    decision is taken by :func:`ddg_oracle.reference.curvature_fast.gauss_bonnet_holds_fast`
    (each face's angle sum shown to be pi with integers; tested to agree).
    """
    if curvature_fast.applies(surface):
        holds = curvature_fast.gauss_bonnet_holds_fast(surface)
        if holds is not None:
            return holds
    return gauss_bonnet_holds_by_faces(surface)


def gauss_bonnet_holds_by_faces(surface) -> bool:
    """The definition of :func:`gauss_bonnet_holds`, with exact Angle arithmetic.

    The total minus 2 pi chi is regrouped face by face,

        sum_f (pi - (sum of the angles of f))  +  (2 |V_int| + |V_bd| - F - 2 chi) pi,

    which is the same exact angle (a rearrangement of the same finite sum).
    Each face term has three primitive angles, so its exact zero test is cheap;
    if all are 0 the answer is whether the integer in front of the last pi
    vanishes.  Should a face term not vanish, the whole sum is decided directly
    (slow on large meshes: the exact zero test then multiplies one direction per
    face).  On a 1,000-face mesh with float coordinates this takes well under a
    second where the direct test takes minutes.
    """
    m = as_metric(surface)
    t = m.triangulation
    boundary = sum(1 for v in range(t.n_vertices) if t.is_boundary_vertex(v))
    interior = t.n_vertices - boundary
    chi = t.euler_characteristic()
    for f in range(t.n_faces):
        face_term = pi - _sum_angles(m.corner_angle(f, c) for c in range(3))
        if face_term.sign() != 0:
            return total_curvature(m) == 2 * chi * pi
    return 2 * interior + boundary - t.n_faces - 2 * chi == 0


def vertex_type(surface, v: int) -> str:
    """D2.2: ``"elliptic"``, ``"flat"`` or ``"hyperbolic"`` by the exact sign of K(v) > 0, = 0, < 0.

    Only for interior vertices (D2.2 defines K there); a boundary vertex raises
    :class:`~ddg_oracle.reference.errors.InputError`.

    >>> from ddg_oracle.reference import surfaces
    >>> vertex_type(surfaces.cube(), 0), vertex_type(surfaces.grid(2, 2), 4)
    ('elliptic', 'flat')
    """
    m = as_metric(surface)
    t = m.triangulation
    if t.is_boundary_vertex(v):
        raise InputError(f"vertex {v} is a boundary vertex: its curvature is a turning angle "
                         "(R2.4), it has no elliptic / flat / hyperbolic type")
    k = 2 * pi - _sum_angles(m.corner_angle(f, c) for f, c in t.corners_around(v))
    return {1: "elliptic", 0: "flat", -1: "hyperbolic"}[k.sign()]


# --- vertex stars (L2.4) --------------------------------------------------------------------------


def _star(surface, v: int, what: str):
    """Edge vectors d_i = q_i - p to the neighbours of interior vertex v, in fan order.

    Consecutive d_i, d_(i+1) (cyclically) span the faces of the star.
    """
    s = _in_r3(surface, what)
    t = s.triangulation
    if t.is_boundary_vertex(v):
        raise InputError(f"{what}: vertex {v} is a boundary vertex; Lemma 2.4 is about "
                         "interior vertices")
    p = s.positions[v]
    return [sub(s.positions[w], p) for w in t.neighbours(v)]


def _rank(vectors) -> int:
    rows = [list(x) for x in vectors if any(x)]
    rank, col = 0, 0
    while rows and col < 3:
        pivot = next((r for r in rows if r[col] != 0), None)
        if pivot is None:
            col += 1
            continue
        rows.remove(pivot)
        rows = [[a - r[col] / pivot[col] * b for a, b in zip(r, pivot)] for r in rows]
        rows = [r for r in rows if any(r)]
        rank += 1
        col += 1
    return rank


def _turns(d, axis) -> int:
    """How often the cyclic fan d_0, d_1, ... winds around ``axis``.

    Assumes every sector (d_i, d_(i+1)) turns positively around the axis by an
    angle in (0, pi), i.e. det(axis, d_i, d_(i+1)) > 0.  Counts the sectors,
    half-open (d_i, d_(i+1)], that contain the direction of d_0 (seen along
    the axis): exact, with rational triple and dot products.
    """
    aa = dot(axis, axis)
    d0 = d[0]
    n = 0
    for a, b in zip(d, d[1:] + d[:1]):
        if det3(axis, a, d0) > 0 and det3(axis, d0, b) > 0:
            n += 1
        elif det3(axis, d0, b) == 0 and dot(d0, b) * aa - dot(d0, axis) * dot(b, axis) > 0:
            n += 1                      # d_0 points along b (projected)
    return n


def is_planar_star(surface, v: int) -> bool:
    """L2.4 "p planar": the interior vertex p and all its neighbours lie in one plane.

    As in the notes (Definition 1.5: a geometric realization is a homeomorphism
    onto its image) the star is also required to be embedded in that plane:
    all its triangles have the same orientation in the plane and wind once
    around p.  (Without this a folded planar star -- p outside the triangle of
    three coplanar neighbours -- is "planar" with K > 0.)  Exact: rational
    triple products.  Then K(p) = 0 (Lemma 2.4).
    """
    d = _star(surface, v, "is_planar_star")
    normal = cross(d[0], d[1])
    if any(dot(normal, x) != 0 for x in d):
        return False
    sectors = zip(d, d[1:] + d[:1])
    if any(det3(normal, a, b) <= 0 for a, b in sectors):
        return False
    return _turns(d, normal) == 1


def is_convex_star(surface, v: int) -> bool:
    """L2.4 "p convex": the spherical polygon of the face normals around p is convex.

    Made precise, exactly decidable with rational arithmetic, for the star of
    an interior vertex p with neighbours q_1, ..., q_n in fan order,
    d_i = q_i - p and fan-oriented face normals n_i = d_i x d_(i+1):

    1. every face plane supports the star: the numbers <n_i, d_j> (all i, j)
       are all <= 0 or all >= 0 (the star lies on the boundary of a convex cone);
    2. the cone is pointed, i.e. the spherical polygon of the normals is not
       degenerate: the normals n_i span R^3 (p is a vertex, not a point on an
       edge or in a face, of the convex hull of its star);
    3. the star wraps once around the cone's axis G = sum_j d_j (an interior
       direction): every sector turns the same way around G and the turning
       number is 1 (embeddedness, as in the notes; a star wrapping twice around
       a convex cone satisfies 1 and 2 but can have K < 0).

    Then K(p) > 0 (Lemma 2.4).  Orientation-free: the faces' own orientations
    are not used.
    """
    d = _star(surface, v, "is_convex_star")
    normals = [cross(a, b) for a, b in zip(d, d[1:] + d[:1])]
    signs = {sign(dot(nv, x)) for nv in normals for x in d} - {0}
    if len(signs) != 1:
        return False                          # both sides (not convex) or planar
    if _rank(normals) < 3:
        return False
    axis = tuple(sum(x[k] for x in d) for k in range(3))
    turn = {sign(det3(axis, a, b)) for a, b in zip(d, d[1:] + d[:1])}
    if len(turn) != 1 or 0 in turn:
        return False
    if turn == {-1}:
        axis = tuple(-x for x in axis)
    return _turns(d, axis) == 1


def is_saddle_star(surface, v: int) -> bool:
    """L2.4 "p saddle": p lies in the *interior* of the convex hull of its neighbours.

    The notes print "p lies in the convex hull of its neighbors (and p not
    planar)"; with the closed hull the lemma fails: a vertex in the middle of
    a straight crease (e.g. a cube edge split at its midpoint) lies on the
    segment between two neighbours, is not planar, and has K = 0.  With the
    interior (which implies "not planar") K(p) < 0 holds for every star:
    the unit vectors to the neighbours then lie in no closed hemisphere, so the
    closed spherical polygon through them is longer than 2 pi.

    Decided exactly: p is interior iff no plane through p has all neighbours
    weakly on one side; it suffices to test the planes spanned by two
    independent edge vectors d_i x d_k (extreme rays of the polar cone).
    """
    d = _star(surface, v, "is_saddle_star")
    found_plane = False
    for i in range(len(d)):
        for k in range(i + 1, len(d)):
            c = cross(d[i], d[k])
            if not any(c):
                continue
            found_plane = True
            signs = {sign(dot(c, x)) for x in d}
            if 1 not in signs or -1 not in signs:
                return False
    return found_plane


# --- mean curvature (D2.3) and Steiner (T2.7, R2.5) -----------------------------------------------


def dihedral_angles(surface) -> dict[int, Angle]:
    """D2.3: the signed angle theta(e) in (-pi, pi) between the two face normals at each interior edge.

    Convention.  Face normals follow the corner order of each face by the
    right-hand rule (outward for the constructors in ``ddg_oracle.reference.surfaces``).
    For an interior edge e whose first halfedge runs i -> j in face f = (i, j, k)
    and whose twin runs j -> i in face g = (j, i, l) (a consistent orientation),
    n_f = (x_j - x_i) x (x_k - x_i), n_g = (x_i - x_j) x (x_l - x_j), and

        |theta(e)| = angle(n_f, n_g),   theta(e) > 0  iff  <n_f, x_l - x_i> < 0,

    i.e. theta is positive where the edge is convex (the other face bends away
    from the side the normal points to) and negative where it is concave;
    0 for coplanar faces.  Exactly: cot |theta| = <n_f, n_g> / (|e| |<n_f, x_l - x_i>|).

    Keyed by edge id (``triangulation.edge_vertices(e)`` gives its vertices);
    boundary edges have no dihedral angle.  Raises
    :class:`~ddg_oracle.reference.errors.InputError` at an edge whose two faces are
    oriented inconsistently (a non-orientable surface, or faces not oriented
    alike) or folded flat onto each other (theta = +-pi).

    >>> from ddg_oracle.reference import surfaces
    >>> from ddg_oracle.reference.exact import pi
    >>> sorted(set(dihedral_angles(surfaces.cube()).values()), key=float) == [0, pi / 2]
    True
    """
    return {e: theta for e, theta, _ in _dihedral_angles_and_lengths(surface, "dihedral_angles")}


def _dihedral_angles_and_lengths(surface, what: str):
    """(e, theta(e), l(e)) for every interior edge: :func:`dihedral_angles`' angle and the
    exact length, both from the edge's integer vector (one square root per edge)."""
    s = _in_r3(surface, what)
    t = s.triangulation
    # the points over a common denominator D: integer arithmetic, and the cotangent below
    # is homogeneous of degree 0 in the positions (D^4 / (D D^3)), so the integers give it
    # exactly; the signs are those of the rationals (D > 0)
    shared = shared_denominator(s.positions)
    for e in range(t.n_edges):
        if t.edge_halfedges(e)[1] >= 0:
            yield (e, *_dihedral_angle_and_length(s, e, shared))


def _dihedral_angle_and_length(s: PolyhedralSurface, e: int, shared=None):
    """(theta(e), l(e)) of the interior edge ``e`` of ``s`` (``shared``: the positions over
    their common denominator, if known; else the edge's four points are put over theirs)."""
    t, x = s.triangulation, s.positions
    h, h2 = t.edge_halfedges(e)
    f, g = face_of(h), face_of(h2)
    if t.reversed_gluing(h):
        raise InputError(
            f"edge {e} {t.edge_vertices(e)}: faces {f} {t.faces[f]} and {g} {t.faces[g]} are "
            "oriented inconsistently; the sign of a dihedral angle needs a consistent "
            "orientation")
    i, j, k = cyclic(t.faces[f], corner_of(h))
    l_ = t.faces[g][opposite_corner(h2)]
    if shared is not None:
        P, D = shared
        xi, xj, xk, xl = P[i], P[j], P[k], P[l_]
    else:
        (xi, xj, xk, xl), D = points_on_common_denominator(x[i], x[j], x[k], x[l_])
    edge = sub(xj, xi)
    nf = cross(edge, sub(xk, xi))
    ng = cross(sub(xi, xj), sub(xl, xj))
    height = dot(nf, sub(xl, xi))
    cos_part = dot(nf, ng)
    E = dot(edge, edge)
    root = sqrt(E)                                      # D l(e)
    length = root * Fraction(1, D)
    if height == 0:
        if cos_part > 0:
            return _ZERO_ANGLE, length
        raise InputError(f"edge {e} {t.edge_vertices(e)}: faces {f} and {g} are folded onto "
                         "each other (dihedral angle +-pi)")
    # cot |theta| = <n_f, n_g> / (sqrt(E) |height|) = <n_f, n_g> sqrt(E) / (E |height|)
    theta = corner_angle(root * Fraction(cos_part, E * abs(height)))
    return (theta if height < 0 else -theta), length


def mean_curvature(surface) -> dict[int, AngleLength]:
    """D2.3: H(e) = 1/2 theta(e) l(e) at every interior edge, exact (angle times length).

    theta(e) as in :func:`dihedral_angles` (positive where convex), l(e) the
    exact length (a Surd).  Integrated over the edge, not divided by an area.
    """
    return {e: AngleLength.of(theta, length / 2)
            for e, theta, length in _dihedral_angles_and_lengths(surface, "mean_curvature")}


def mean_curvature_at(surface, e: int) -> AngleLength:
    """D2.3: H(e) = 1/2 theta(e) l(e) of the one interior edge ``e``, exact, as
    :func:`mean_curvature` gives it (the edge's four points alone over a common
    denominator: no pass over the whole surface)."""
    s = _in_r3(surface, "mean_curvature")
    if s.triangulation.edge_halfedges(e)[1] < 0:
        raise InputError(f"edge {e} {s.triangulation.edge_vertices(e)} is a boundary edge: it "
                         "has no dihedral angle")
    theta, length = _dihedral_angle_and_length(s, e)
    return AngleLength.of(theta, length / 2)


def total_mean_curvature(surface) -> AngleLength:
    """D2.3: H(S) = sum_e H(e) = 1/2 sum_e theta(e) l(e) over the interior edges, exact.

    >>> from ddg_oracle.reference import surfaces
    >>> from ddg_oracle.reference.exact import pi
    >>> H = total_mean_curvature(surfaces.cube())
    >>> H.parts, H.pi_coefficient                  # structurally 3 pi
    ({}, Surd('3'))
    """
    return sum(mean_curvature(surface).values(), AngleLength())


def steiner_coefficients(surface) -> tuple[Surd, AngleLength, Angle]:
    """T2.7 / R2.5: (A, 2 H(S), K(S)) with area(S_rho) = A + 2 H(S) rho + K(S) rho^2.

    A is the total area, H(S) the total mean curvature (D2.3, theta > 0 where
    convex), K(S) the total Gaussian curvature, which equals 2 pi chi exactly
    (T2.6; 4 pi for a convex polyhedron, T2.7).  For a convex polyhedron this
    is the area of the boundary of the parallel body at distance rho (T2.7); for
    any closed oriented polyhedral surface it is the signed area of the
    parallel surface of Remark 2.5.  Needs a closed, consistently oriented
    surface in R^3.
    """
    s = _in_r3(surface, "steiner_coefficients")
    t = s.triangulation
    if any(t.is_boundary_edge(e) for e in range(t.n_edges)):
        raise InputError("steiner_coefficients needs a closed surface (T2.7, R2.5); this one has "
                         "boundary edges")
    return Surd(exact_sum(s.metric().areas)), 2 * total_mean_curvature(s), total_curvature(s)


# --- isometries (T2.5, X2.3) ----------------------------------------------------------------------


def cayley_rotation(a, b, c) -> tuple[tuple[Fraction, ...], ...]:
    """The rational rotation R = (I - S)^-1 (I + S) of the skew matrix S of w = (a, b, c).

    S x = w x x; R = I + 2/(1 + |w|^2) (S + S^2), exactly orthogonal with det 1
    for rational a, b, c (every rotation without eigenvalue -1 arises so).

    >>> R = cayley_rotation(1, 2, 3)
    >>> all(sum(R[i][k] * R[j][k] for k in range(3)) == (i == j) for i in range(3) for j in range(3))
    True
    """
    w = [Fraction(a), Fraction(b), Fraction(c)]
    S = [[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]]
    S2 = [[sum(S[i][k] * S[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    f = Fraction(2) / (1 + sum(x * x for x in w))
    return tuple(tuple(Fraction(i == j) + f * (S[i][j] + S2[i][j]) for j in range(3))
                 for i in range(3))


def rigid_motion(surface: PolyhedralSurface, rotation, translation=(0, 0, 0)) -> PolyhedralSurface:
    """The surface moved by x -> R x + t (exact; R e.g. from :func:`cayley_rotation`)."""
    s = _in_r3(surface, "rigid_motion")
    R = [[Fraction(x) for x in row] for row in rotation]
    tr = [Fraction(x) for x in translation]
    return s.with_positions([tuple(sum(R[i][k] * p[k] for k in range(3)) + tr[i]
                                   for i in range(3)) for p in s.positions])


def push_vertex_in(surface: PolyhedralSurface, v: int) -> PolyhedralSurface:
    """X2.3: reflect vertex v in the plane of its neighbours (which must be coplanar).

    Every edge length, hence the metric, every angle and K, is unchanged
    (the neighbours are fixed and |p - q| = |p' - q| for the reflection p' of p);
    the polyhedral surface is a different one (Example 2.3).  Raises
    :class:`~ddg_oracle.reference.errors.InputError` when the neighbours of v are not
    coplanar or all collinear.

    >>> from ddg_oracle.reference import surfaces
    >>> push_vertex_in(surfaces.octahedron(), 4).positions[4]      # (0, 0, 1) -> (0, 0, -1)
    (Fraction(0, 1), Fraction(0, 1), Fraction(-1, 1))
    """
    s = _in_r3(surface, "push_vertex_in")
    x = s.positions
    q = [x[w] for w in dict.fromkeys(s.triangulation.neighbours(v))]
    normal = next((n for n in (cross(sub(q[1], q[0]), sub(r, q[0])) for r in q[2:]) if any(n)),
                  None)
    if normal is None:
        raise InputError(f"push_vertex_in: the neighbours of vertex {v} are collinear; they span "
                         "no plane")
    if any(dot(normal, sub(r, q[0])) != 0 for r in q):
        raise InputError(f"push_vertex_in: the neighbours of vertex {v} are not coplanar (X2.3 "
                         "reflects a star whose neighbours lie in a plane)")
    k = 2 * dot(normal, sub(x[v], q[0])) / dot(normal, normal)
    moved = tuple(a - k * n for a, n in zip(x[v], normal))
    return s.with_positions([moved if w == v else p for w, p in enumerate(x)])
