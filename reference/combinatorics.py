"""Combinatorics of triangulated surfaces (chapter 1 of the notes).

A :class:`Triangulation` holds connectivity only -- no positions, no lengths
(geometry-central's split between a mesh and its geometries).  It implements
the Euler characteristic (D1.6), the regularity predicates (D1.4), the
classification by orientability, Euler characteristic and number of boundary
loops (T1.1 / C1.2 / R1.6), the connected sum (CS), and the refinements and
flips under which chi is invariant (R1.5).

Representation.  Faces are triples of vertex ids in corner order.  Halfedge
``h = 3*f + c`` runs in face ``f`` from corner ``c`` to corner ``(c+1) % 3``;
"corner ``k``" is the corner at the tail of halfedge ``k``, so corners and
halfedges share their numbering.  Each edge is a *gluing* of one or two
halfedges, stored explicitly together with a flag saying whether the gluing
reverses orientation (both halfedges run the same way).  Edges are never
identified by their vertex pair (only :meth:`Triangulation.from_faces` uses
vertex pairs, to build the gluings), so the structure represents the
non-regular triangulations that intrinsic edge flips produce: self-loops,
several edges between two vertices, vertices of valence 1.

Every object is immutable; operations return new triangulations.

>>> t = Triangulation.from_faces([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
>>> t.euler_characteristic(), str(t.classify())
(2, 'sphere')
>>> f = t.flip(0)
>>> f.is_regular(), f.is_strongly_regular(), f.euler_characteristic()
(True, False, 2)
"""

from __future__ import annotations

import numbers
from collections.abc import Sequence
from dataclasses import dataclass
from operator import itemgetter
from typing import Protocol, runtime_checkable

from .errors import (BadShape, EmptyMesh, IndexOutOfRange, InputError, NegativeIndex,
                     NonIntegerIndex, NonManifoldEdge, NonManifoldVertex, NotConnected,
                     NotFlippable, RepeatedVertexInFace, UnreferencedVertex)

# the halfedge helpers (face_of, corner_of, ...) are public but stay out of the flat
# namespace of ddg_oracle.reference: they are infrastructure, not the notes' terms
__all__ = ["Triangulation", "Classification", "connected_sum", "HalfedgeMesh"]


# --- halfedge arithmetic -------------------------------------------------------
#
# The one place where halfedge and corner numbers are computed: halfedge h = 3 f + c of
# face f runs from corner c to corner c + 1 (mod 3) and is opposite corner c + 2; corner c
# of f is the corner at the tail of halfedge 3 f + c.  Every other module calls these.


def face_of(h: int) -> int:
    """The face of halfedge (or corner) ``h``."""
    return h // 3


def corner_of(h: int) -> int:
    """The corner index (0, 1, 2) within its face of the tail of halfedge ``h``."""
    return h % 3


def halfedge(f: int, c: int) -> int:
    """Halfedge ``c`` of face ``f`` (from corner c to corner c + 1)."""
    return 3 * f + c


def next_corner(c: int) -> int:
    """c + 1 mod 3: the corner after ``c`` in its face."""
    return c - 2 if c == 2 else c + 1


def prev_corner(c: int) -> int:
    """c - 1 mod 3: the corner before ``c`` in its face."""
    return c + 2 if c == 0 else c - 1


def opposite_corner(h: int) -> int:
    """The corner index (within its face) opposite halfedge ``h``: c + 2 mod 3."""
    return prev_corner(h % 3)


def opposite_halfedge(f: int, c: int) -> int:
    """The halfedge of face ``f`` opposite its corner ``c``: halfedge c + 1 mod 3."""
    return 3 * f + next_corner(c)


def cyclic(triple, c: int) -> tuple:
    """``(triple[c], triple[c + 1], triple[c + 2])`` with indices mod 3: a face's corners
    (or anything per corner) starting at corner ``c``.

    >>> cyclic((10, 11, 12), 2)
    (12, 10, 11)
    """
    return (triple[c], triple[next_corner(c)], triple[prev_corner(c)])


@runtime_checkable
class HalfedgeMesh(Protocol):
    """The halfedge interface that :class:`Triangulation` (immutable) and its in-place
    builder (the combinatorics of :class:`~ddg_oracle.reference.intrinsic.IntrinsicTriangulation`,
    flipped in place) share: code that walks a triangulation relies on these and nothing
    else, so it runs on both.  Halfedge numbering: see the helpers above."""

    @property
    def n_vertices(self) -> int: ...

    @property
    def n_faces(self) -> int: ...

    @property
    def n_edges(self) -> int: ...

    @property
    def faces(self) -> Sequence: ...

    def tail(self, h: int) -> int: ...

    def head(self, h: int) -> int: ...

    def twin(self, h: int) -> int: ...

    def next(self, h: int) -> int: ...

    def prev(self, h: int) -> int: ...

    def face_of(self, h: int) -> int: ...

    def reversed_gluing(self, h: int) -> bool: ...

    def edge_of(self, h: int) -> int: ...

    def edge_halfedges(self, e: int) -> tuple[int, int]: ...

    def edge_vertices(self, e: int) -> tuple[int, int]: ...

    def is_boundary_edge(self, e: int) -> bool: ...


def _next(h: int) -> int:
    return h - 2 if h % 3 == 2 else h + 1


def _prev(h: int) -> int:
    return h + 2 if h % 3 == 0 else h - 1


def _other(k: int, x: int) -> int:
    """The edge at corner ``k`` other than ``x`` (corner k has out-edge k, in-edge prev(k))."""
    return _prev(k) if x == k else k


def _cross(twin, rev, k: int, y: int):
    """Cross halfedge ``y`` (an edge at corner ``k``) to the neighbouring face.

    Returns ``(corner, arrived_via)``: the corner of the twin's face at the same
    point as corner ``k``, and the twin; ``(-1, -1)`` on the boundary.  Which end
    of the twin matches depends on the reversed flag, not on vertex ids, so this
    is right for self-loops too.
    """
    t = twin[y]
    if t < 0:
        return -1, -1
    # corner k is at the tail of y iff y == k.  An orientation-preserving gluing
    # matches tail(y) with head(t) (corner next(t)); a reversing one tail with tail.
    return (_next(t) if (y == k) != rev[y] else t), t


def _walk_fan(twin, rev, k0: int):
    """Corners around the point of corner ``k0`` in fan order.

    Returns ``(corners, ends, closed)``.  ``ends`` are the halfedges of the edge
    ends at the vertex in the same order: for a closed fan ``ends[i]`` lies between
    ``corners[i]`` and ``corners[i+1]`` (cyclically); for an open fan ``ends[0]``
    is the boundary edge at ``corners[0]``, ``ends[i+1]`` lies between
    ``corners[i]`` and ``corners[i+1]``, and ``ends[-1]`` is the boundary edge at
    ``corners[-1]``.  For a consistently oriented
    neighbourhood the order is counterclockwise (crossing incoming halfedges) and
    an open fan starts at the corner whose outgoing halfedge is on the boundary.
    """
    # Walk backwards (through outgoing halfedges) to a boundary edge, or round.
    k, y = k0, k0
    while True:
        nk, t = _cross(twin, rev, k, y)
        if nk < 0:
            start, leave, ends = k, _other(k, y), [y]
            break
        if nk == k0:
            start, leave, ends = k0, _prev(k0), []
            break
        k, y = nk, _other(nk, t)
    corners = [start]
    k, y = start, leave
    while True:
        ends.append(y)
        nk, t = _cross(twin, rev, k, y)
        if nk < 0:
            return corners, ends, False
        if nk == start:
            return corners, ends, True
        corners.append(nk)
        k, y = nk, _other(nk, t)


# --- input parsing -------------------------------------------------------------


def _is_int(x) -> bool:
    # numpy integer scalars register as numbers.Integral; bool (and numpy.bool_,
    # which is not Integral) must not pass as a vertex id.
    return isinstance(x, numbers.Integral) and not isinstance(x, bool)


def _short(x, limit: int = 60) -> str:
    s = repr(x)
    return s if len(s) <= limit else s[:limit - 3] + "..."


def _parse_faces(faces, n_vertices, allow_repeats: bool):
    """Validate a face list; returns (tuple of int triples, n_vertices).

    Checks, in this order over the whole list: emptiness, row shape, integer
    entries, negative entries, range, repeated vertices (unless allowed), and
    a vertex count above the number of corners (so an unused vertex exists).
    """
    if hasattr(faces, "tolist"):          # numpy arrays, without importing numpy
        faces = faces.tolist()
    if faces is None or isinstance(faces, (str, bytes)):
        raise BadShape(f"faces must be a sequence of rows of 3 vertex indices, got {_short(faces)}")
    try:
        rows = list(faces)
    except TypeError:
        raise BadShape(f"faces must be a sequence of rows of 3 vertex indices, "
                       f"got {type(faces).__name__}") from None
    if not rows:
        raise EmptyMesh("no faces")
    for i, row in enumerate(rows):
        if hasattr(row, "tolist"):
            row = rows[i] = row.tolist()
        if (isinstance(row, (str, bytes)) or not isinstance(row, Sequence)
                or len(row) != 3):
            raise BadShape(f"face {i}: expected a row of 3 vertex indices, got {_short(row)}")
    for i, row in enumerate(rows):
        for c, x in enumerate(row):
            if type(x) is int:
                continue                  # the common case, without the ABC checks below
            if isinstance(x, Sequence) and not isinstance(x, (str, bytes)):
                # a 3-d array or a nested list: a shape problem, not a bad index
                raise BadShape(f"face {i}, corner {c}: expected a vertex index, got the "
                               f"sequence {_short(x)}; faces must be an m x 3 array")
            if not _is_int(x):
                raise NonIntegerIndex(f"face {i}, corner {c}: vertex index {_short(x)} "
                                      f"({type(x).__name__}) is not an integer")
    out = [(int(a), int(b), int(c)) for a, b, c in rows]
    for i, row in enumerate(out):
        for c, x in enumerate(row):
            if x < 0:
                raise NegativeIndex(f"face {i}, corner {c}: negative vertex index {x}")
    top = max(max(r) for r in out)
    if n_vertices is None:
        n = top + 1
    else:
        if hasattr(n_vertices, "item"):
            n_vertices = n_vertices.item()
        if not _is_int(n_vertices):
            raise NonIntegerIndex(f"n_vertices = {_short(n_vertices)} is not an integer")
        n = int(n_vertices)
        if n < 0:
            raise NegativeIndex(f"n_vertices = {n} is negative")
        if top >= n:
            for i, row in enumerate(out):
                for c, x in enumerate(row):
                    if x >= n:
                        raise IndexOutOfRange(f"face {i}, corner {c}: vertex index {x} "
                                              f">= n_vertices = {n}")
    if not allow_repeats:
        for i, (a, b, c) in enumerate(out):
            if a == b or b == c or a == c:
                v = b if b in (a, c) else a
                raise RepeatedVertexInFace(f"face {i} = ({a}, {b}, {c}) repeats vertex {v}")
    if n > 3 * len(out):
        # More vertices than corners: some vertex is unused.  Say so now, before
        # per-vertex tables of length n are built (a stray index such as 10**12
        # would otherwise exhaust memory instead of raising).
        used = {x for row in out for x in row}
        v = next(v for v in range(len(used) + 1) if v not in used)
        raise UnreferencedVertex(f"vertex {v} is used by no face (n_vertices = {n}, "
                                 f"but {len(out)} faces use only {len(used)} vertices)")
    return tuple(out), n


def checked_index(i, size: int, what: str, allow_negative: bool = False) -> int:
    if not _is_int(i):
        raise NonIntegerIndex(f"{what} index {_short(i)} is not an integer")
    i = int(i)
    if allow_negative and -size <= i < 0:
        return i + size
    if i < 0:
        raise NegativeIndex(f"{what} index {i} is negative")
    if i >= size:
        raise IndexOutOfRange(f"{what} {i} out of range (there are {size})")
    return i


# --- classification --------------------------------------------------------------


@dataclass(frozen=True)
class Classification:
    """Topological type of a compact connected surface (T1.1 / C1.2 / R1.6).

    ``genus`` is g for orientable surfaces (chi = 2 - 2g - k) and the number h of
    crosscaps for non-orientable ones (chi = 2 - h - k); k = ``boundary_components``.
    Two surfaces are homeomorphic iff their classifications are equal.

    >>> str(Classification(False, 2, 0, 0))
    'Klein bottle'
    """

    orientable: bool
    genus: int
    boundary_components: int
    euler_characteristic: int

    @property
    def name(self) -> str:
        """A readable name, e.g. "sphere", "Möbius strip", "orientable genus 2, 1 boundary loop"."""
        g, k = self.genus, self.boundary_components
        special = {(True, 0, 0): "sphere", (True, 0, 1): "disk", (True, 0, 2): "annulus",
                   (True, 1, 0): "torus", (False, 1, 0): "projective plane",
                   (False, 2, 0): "Klein bottle", (False, 1, 1): "Möbius strip"}
        key = (self.orientable, g, k)
        if key in special:
            return special[key]
        base = f"{'orientable' if self.orientable else 'non-orientable'} genus {g}"
        if k:
            base += f", {k} boundary loop{'s' if k > 1 else ''}"
        return base

    def __str__(self) -> str:
        return self.name


# --- the triangulation -------------------------------------------------------------


class Triangulation:
    """A triangulated compact surface, possibly non-regular (D1.4), as glued triangles.

    Build one with :meth:`from_faces` (a simplicial face list) or directly from
    gluings: ``Triangulation(faces, gluings, n_vertices=None)`` where
    ``gluings[e] = (h, t, reversed)`` glues halfedge ``h`` to ``t`` (``t = -1``:
    boundary) and defines edge ``e``; every halfedge must occur exactly once,
    glued halfedges must have matching vertex ids, and every vertex must be a
    manifold vertex (one fan of corners).

    >>> t = Triangulation([[0, 1, 2]], [(0, -1, False), (1, -1, False), (2, -1, False)])
    >>> t.n_edges, str(t.classify())
    (3, 'disk')
    """

    __slots__ = ("_faces", "_n", "_twin", "_rev", "_edges", "_edge_of", "_vcorner", "_fans")

    def __init__(self, faces, gluings, n_vertices=None):
        faces, n = _parse_faces(faces, n_vertices, allow_repeats=True)
        gl = _parse_gluings(gluings, 3 * len(faces))
        self._setup(faces, n, gl)
        self._check_gluings()
        self._check_vertices()

    def __reduce__(self):
        # pickled as its defining data (faces, gluings, vertex count), not its tables:
        # replayable counterexamples stay short
        gluings = tuple((a, b, self._rev[a]) for a, b in self._edges)
        return (Triangulation._trusted, (self._faces, self._n, gluings))

    @classmethod
    def _trusted(cls, faces, n_vertices: int, gluings) -> "Triangulation":
        """Internal constructor from already valid data (operations build these)."""
        self = object.__new__(cls)
        self._setup(tuple(tuple(f) for f in faces), n_vertices, gluings)
        return self

    def _setup(self, faces, n, gluings) -> None:
        H = 3 * len(faces)
        twin = [-1] * H
        rev = [False] * H
        edge_of = [-1] * H
        edges = []
        for e, (a, b, r) in enumerate(gluings):
            edge_of[a] = e
            if b >= 0:
                edge_of[b] = e
                twin[a] = b
                twin[b] = a
                rev[a] = rev[b] = bool(r)
            edges.append((a, b))
        vcorner = [-1] * n
        k = H
        for f in reversed(faces):     # so that vcorner[v] is v's first corner
            k -= 3
            vcorner[f[2]] = k + 2
            vcorner[f[1]] = k + 1
            vcorner[f[0]] = k
        self._faces = faces
        self._n = n
        self._twin = tuple(twin)
        self._rev = tuple(rev)
        self._edges = tuple(edges)
        self._edge_of = tuple(edge_of)
        self._vcorner = tuple(vcorner)
        self._fans = {}

    # --- construction from a face list ---------------------------------------------

    @classmethod
    def from_faces(cls, faces, n_vertices=None) -> "Triangulation":
        """Build from a simplicial face list (rows of 3 vertex ids; lists or numpy arrays).

        Faces sharing a vertex pair are glued along it; when both list the pair in
        the same direction the gluing reverses orientation (Möbius strips,
        inconsistently oriented input).  Edges are numbered by first occurrence.
        Validation order: EmptyMesh, BadShape, NonIntegerIndex, NegativeIndex,
        IndexOutOfRange, RepeatedVertexInFace, NonManifoldEdge, NonManifoldVertex,
        UnreferencedVertex (``n_vertices`` defaults to the largest index + 1; a
        vertex count above 3 x the number of faces is reported as
        UnreferencedVertex at once, before any table of that length is built).

        >>> Triangulation.from_faces([[0, 1, 2], [0, 1, 3]]).reversed_gluing(0)
        True
        """
        faces, n = _parse_faces(faces, n_vertices, allow_repeats=False)
        # Pair halfedges by vertex pair; an integer key is faster than a tuple.
        N = n + 1
        slot = {}
        groups = []
        h = 0
        for a, b, c in faces:
            for u, v in ((a, b), (b, c), (c, a)):
                key = u * N + v if u < v else v * N + u
                e = slot.get(key)
                if e is None:
                    slot[key] = len(groups)
                    groups.append([h])
                else:
                    groups[e].append(h)
                h += 1
        gluings = []
        for g in groups:
            if len(g) == 1:
                gluings.append((g[0], -1, False))
            elif len(g) == 2:
                a, b = g
                gluings.append((a, b, faces[a // 3][a % 3] == faces[b // 3][b % 3]))
            else:
                a = g[0]
                i, j = sorted((faces[a // 3][a % 3], faces[a // 3][(a + 1) % 3]))
                raise NonManifoldEdge(f"non-manifold edge at vertices ({i}, {j}): faces "
                                      + ", ".join(str(x // 3) for x in g))
        self = cls._trusted(faces, n, gluings)
        self._check_vertices()
        return self

    # --- validation -------------------------------------------------------------------

    def _check_gluings(self) -> None:
        F = self._faces
        for e, (a, b) in enumerate(self._edges):
            if b < 0:
                continue
            ta, ha = F[a // 3][a % 3], F[a // 3][(a + 1) % 3]
            tb, hb = F[b // 3][b % 3], F[b // 3][(b + 1) % 3]
            ok = (ta, ha) == (tb, hb) if self._rev[a] else (ta, ha) == (hb, tb)
            if not ok:
                raise InputError(f"edge {e}: halfedge {a} ({ta}->{ha}) glued "
                                 f"{'reversed' if self._rev[a] else 'preserving orientation'} "
                                 f"to halfedge {b} ({tb}->{hb}): endpoints do not match")

    def _check_vertices(self, vertices=None) -> None:
        """Every (given) vertex is used and its corners form exactly one fan."""
        count = [0] * self._n
        for f in self._faces:
            for v in f:
                count[v] += 1
        check = range(self._n) if vertices is None else sorted(set(vertices))
        twin, rev = self._twin, self._rev
        for v in check:
            if not count[v]:
                continue
            corners, _, _ = _walk_fan(twin, rev, self._vcorner[v])
            if len(corners) != count[v]:
                fans = self._all_fans(v)
                raise NonManifoldVertex(
                    f"non-manifold vertex {v}: its faces form {len(fans)} separate fans ("
                    + "; ".join("faces " + ", ".join(str(k // 3) for k in fan) for fan in fans)
                    + ")")
        for v in check:
            if not count[v]:
                raise UnreferencedVertex(f"vertex {v} is used by no face "
                                         f"(n_vertices = {self._n})")

    def _all_fans(self, v):
        left = [k for k in range(3 * len(self._faces)) if self._faces[k // 3][k % 3] == v]
        fans = []
        while left:
            corners, _, _ = _walk_fan(self._twin, self._rev, left[0])
            fans.append(corners)
            left = [k for k in left if k not in set(corners)]
        return fans

    def validate(self) -> None:
        """Re-check every structural invariant; raises an ``InputError`` if one fails.

        Twins are an involution with symmetric reversed flags, the edge table covers
        each halfedge once, glued halfedges have matching endpoints, and every
        vertex is used and is a manifold vertex (one fan).
        """
        H = 3 * len(self._faces)
        seen = [0] * H
        for e, (a, b) in enumerate(self._edges):
            for x in (a, b):
                if x >= 0:
                    seen[x] += 1
                    if self._edge_of[x] != e:
                        raise InputError(f"halfedge {x} is in edge {e} but edge_of says "
                                         f"{self._edge_of[x]}")
            if b >= 0 and (self._twin[a] != b or self._twin[b] != a
                           or self._rev[a] != self._rev[b]):
                raise InputError(f"edge {e}: twins {a}, {b} are not symmetric")
            if b < 0 and self._twin[a] != -1:
                raise InputError(f"edge {e}: boundary halfedge {a} has a twin")
        for x in range(H):
            if seen[x] != 1:
                raise InputError(f"halfedge {x} is in {seen[x]} edges")
        self._check_gluings()
        self._check_vertices()

    # --- elements ---------------------------------------------------------------------

    @property
    def faces(self) -> tuple:
        """Faces as triples of vertex ids in corner order."""
        return self._faces

    @property
    def n_vertices(self) -> int:
        return self._n

    @property
    def n_faces(self) -> int:
        return len(self._faces)

    @property
    def n_edges(self) -> int:
        return len(self._edges)

    @property
    def n_halfedges(self) -> int:
        return 3 * len(self._faces)

    def tail(self, h: int) -> int:
        """Vertex at the start of halfedge ``h``."""
        return self._faces[h // 3][h % 3]

    def head(self, h: int) -> int:
        """Vertex at the end of halfedge ``h``."""
        return self._faces[h // 3][(h + 1) % 3]

    @staticmethod
    def face_of(h: int) -> int:
        return h // 3

    @staticmethod
    def next(h: int) -> int:
        """The next halfedge in the same face."""
        return _next(h)

    @staticmethod
    def prev(h: int) -> int:
        """The previous halfedge in the same face."""
        return _prev(h)

    def twin(self, h: int) -> int:
        """The halfedge glued to ``h``, or -1 if ``h`` is on the boundary."""
        return self._twin[h]

    def reversed_gluing(self, h: int) -> bool:
        """True when ``h`` and its twin run the same way (the gluing reverses orientation)."""
        return self._rev[h]

    def edge_of(self, h: int) -> int:
        return self._edge_of[h]

    def edge_halfedges(self, e: int) -> tuple[int, int]:
        """``(h, twin)`` of edge ``e``; twin is -1 for a boundary edge."""
        return self._edges[e]

    def edge_vertices(self, e: int) -> tuple[int, int]:
        """``(tail, head)`` of the first halfedge of edge ``e`` (equal for a loop)."""
        h = self._edges[e][0]
        return self.tail(h), self.head(h)

    def is_boundary_edge(self, e: int) -> bool:
        return self._edges[e][1] < 0

    # --- vertex stars ---------------------------------------------------------------------

    def _fan(self, v: int):
        fan = self._fans.get(v)
        if fan is None:
            v = checked_index(v, self._n, "vertex")
            fan = self._fans[v] = _walk_fan(self._twin, self._rev, self._vcorner[v])
        return fan

    def corners_around(self, v: int) -> list[tuple[int, int]]:
        """``(face, corner)`` pairs around ``v`` in fan order.

        For a boundary vertex, from one boundary edge to the other.  With
        self-loops a face can appear twice (at two of its corners).
        """
        return [(k // 3, k % 3) for k in self._fan(v)[0]]

    def valence(self, v: int) -> int:
        """Number of edge ends at ``v`` (a loop at ``v`` counts twice)."""
        return len(self._fan(v)[1])

    def neighbours(self, v: int) -> list[int]:
        """Vertices at the other end of each edge end at ``v``, in fan order, with multiplicity."""
        corners, ends, closed = self._fan(v)
        out = []
        # The corner each end is read at: ends[i] leaves corners[i] in a closed fan;
        # an open fan starts with the boundary edge at corners[0].
        at = corners if closed else corners[:1] + corners
        for k, y in zip(at, ends):
            out.append(self.head(y) if y == k else self.tail(y))
        return out

    def is_boundary_vertex(self, v: int) -> bool:
        return not self._fan(v)[2]

    def boundary_vertices(self) -> set[int]:
        """The boundary vertices, all at once: the endpoints of the boundary edges (a
        vertex has one fan, open iff a boundary edge ends there).  Without walking
        the fans, so cheaper than :meth:`is_boundary_vertex` on every vertex."""
        out = set()
        for h, t in self._edges:
            if t < 0:
                out.add(self.tail(h))
                out.add(self.head(h))
        return out

    # --- global invariants ----------------------------------------------------------------

    def euler_characteristic(self) -> int:
        """D1.6: chi = V - E + F."""
        return self._n - len(self._edges) + len(self._faces)

    def components(self) -> list[list[int]]:
        """Connected components as sorted lists of face indices (faces connected by gluings)."""
        F = len(self._faces)
        comp = [-1] * F
        out = []
        twin = self._twin
        for f0 in range(F):
            if comp[f0] >= 0:
                continue
            c = len(out)
            comp[f0] = c
            stack, members = [f0], [f0]
            while stack:
                f = stack.pop()
                for h in (3 * f, 3 * f + 1, 3 * f + 2):
                    t = twin[h]
                    if t >= 0 and comp[t // 3] < 0:
                        comp[t // 3] = c
                        stack.append(t // 3)
                        members.append(t // 3)
            out.append(sorted(members))
        return out

    def is_connected(self) -> bool:
        return len(self.components()) == 1

    def boundary_loops(self) -> list[list[int]]:
        """Boundary cycles, each the list of its vertex ids in order (a Möbius strip has one)."""
        twin, rev, faces = self._twin, self._rev, self._faces
        loops = []
        visited = set()
        for b0 in range(3 * len(faces)):
            if twin[b0] >= 0 or b0 in visited:
                continue
            loop = []
            b, near = b0, b0
            while True:
                visited.add(b)
                loop.append(faces[near // 3][near % 3])
                far = _next(b) if near == b else b
                # turn around the vertex at the far end to the next boundary edge
                k, y = far, _other(far, b)
                while True:
                    nk, t = _cross(twin, rev, k, y)
                    if nk < 0:
                        break
                    k, y = nk, _other(nk, t)
                b, near = y, k
                if b == b0:
                    break
            loops.append(loop)
        return loops

    def is_orientable(self) -> bool:
        """Whether the faces can be given signs so that every gluing preserves orientation.

        Breadth first search over faces: across a reversed gluing the neighbour gets
        the opposite sign; a contradiction means non-orientable.
        """
        F = len(self._faces)
        sign = [0] * F
        twin, rev = self._twin, self._rev
        for f0 in range(F):
            if sign[f0]:
                continue
            sign[f0] = 1
            stack = [f0]
            while stack:
                f = stack.pop()
                for h in (3 * f, 3 * f + 1, 3 * f + 2):
                    t = twin[h]
                    if t < 0:
                        continue
                    want = -sign[f] if rev[h] else sign[f]
                    g = t // 3
                    if not sign[g]:
                        sign[g] = want
                        stack.append(g)
                    elif sign[g] != want:
                        return False
        return True

    def is_regular(self) -> bool:
        """D1.4 regular: no face has a repeated vertex (equivalently: no loops)."""
        return all(a != b and b != c and a != c for a, b, c in self._faces)

    def is_strongly_regular(self) -> bool:
        """D1.4 strongly regular: regular, no two edges with the same endpoints, no two
        faces with the same vertex set (so closed cells meet in one cell or not at all)."""
        if not self.is_regular():
            return False
        pairs = {frozenset(self.edge_vertices(e)) for e in range(len(self._edges))}
        if len(pairs) != len(self._edges):
            return False
        return len({frozenset(f) for f in self._faces}) == len(self._faces)

    def classify(self) -> Classification:
        """T1.1 / C1.2 / R1.6: orientability, genus (g or crosscaps h), boundary loops, chi.

        Raises NotConnected if there are several components.

        >>> hemi = [[0,1,2],[0,2,3],[0,3,4],[0,4,5],[0,5,1],[1,2,4],[2,3,5],[3,4,1],[4,5,2],[5,1,3]]
        >>> Triangulation.from_faces(hemi).classify().name
        'projective plane'
        """
        comps = self.components()
        if len(comps) > 1:
            raise NotConnected(f"{len(comps)} components (starting at faces "
                               + ", ".join(str(c[0]) for c in comps)
                               + "); classify needs a connected surface")
        chi = self.euler_characteristic()
        k = len(self.boundary_loops())
        orientable = self.is_orientable()
        deficit = 2 - chi - k
        genus = deficit // 2 if orientable else deficit
        return Classification(orientable, genus, k, chi)

    # --- operations ------------------------------------------------------------------------

    def to_face_list(self) -> list[list[int]]:
        return [list(f) for f in self._faces]

    def flip(self, e: int) -> "Triangulation":
        """Combinatorial edge flip (R1.5: chi unchanged); loops and multi-edges may appear.

        Let ``h: i -> j`` be the first halfedge of ``e`` in face ``f = (i, j, k)``
        and ``t: j -> i`` its twin in face ``g = (j, i, l)``.  After the flip
        ``f = (k, l, j)``, ``g = (l, k, i)`` (both in their old orientation), and
        edge ``e`` is the new diagonal with first halfedge ``3*f: k -> l`` and twin
        ``3*g: l -> k``.  Other edges keep their ids.  If the gluing of ``e`` is
        reversed, ``g`` is first re-oriented to match ``f`` (its corner order
        reversed, the flags of its other gluings toggled).  Raises NotFlippable
        for a boundary edge or when both sides of ``e`` lie in one face.

        >>> t = Triangulation.from_faces([[0, 1, 2], [1, 0, 3]]).flip(0)
        >>> t.faces, t.edge_vertices(0)
        (((2, 3, 1), (3, 2, 0)), (2, 3))
        """
        e = checked_index(e, len(self._edges), "edge")
        h, t = self._edges[e]
        if t < 0:
            raise NotFlippable(f"edge {e} is a boundary edge")
        if h // 3 == t // 3:
            raise NotFlippable(f"edge {e} has face {h // 3} on both sides")
        b = TriangulationBuilder(self)
        b.flip(e)
        return b.build()

    def split_edge(self, e: int) -> tuple["Triangulation", int]:
        """Insert a new vertex ``m = n_vertices`` on edge ``e`` (R1.5: chi unchanged).

        Each face on either side of ``e`` is split into two by an edge from ``m`` to
        its opposite corner: 1 face for a boundary edge, 2 otherwise (if both sides
        of ``e`` lie in one face, that face becomes 3).  The face containing a
        halfedge keeps its index and the half from the halfedge's tail to ``m``; new
        faces are appended.  Edge ``e`` becomes the half from ``edge_vertices(e)[0]``
        to ``m``; the other half and the new interior edges get ids from
        ``n_edges`` on.  Returns ``(triangulation, m)``.
        """
        e = checked_index(e, len(self._edges), "edge")
        h, t = self._edges[e]
        r = self._rev[h]
        b = TriangulationBuilder(self)
        m = b.n
        b.n += 1
        x1, x2, moved = b.split_halfedge(h, m)
        if t < 0:
            b.glue(x1, -1, False, e)
            b.glue(x2, -1, False)
        else:
            y1, y2, moved2 = b.split_halfedge(moved.get(t, t), m)
            x1, x2 = moved2.get(x1, x1), moved2.get(x2, x2)
            # orientation-preserving: tail(t) = head(h), so t's first half meets h's second
            if r:
                b.glue(x1, y1, True, e)
                b.glue(x2, y2, True)
            else:
                b.glue(x1, y2, False, e)
                b.glue(x2, y1, False)
        return b.build(), m

    def subdivide_1to4(self) -> tuple["Triangulation", list[tuple[int, int]]]:
        """Split every face into 4 at new edge midpoints (R1.5: chi unchanged).

        V' = V + E, E' = 2E + 3F, F' = 4F.  The midpoint of edge ``e`` is vertex
        ``n_vertices + e`` and ``midpoints[e] = edge_vertices(e)``, so distinct
        edges between the same vertices get distinct midpoints.  Face ``f =
        (x0, x1, x2)`` becomes faces ``4f + c = (x_c, m_c, m_{c+2})`` and the middle
        face ``4f + 3 = (m0, m1, m2)``, where ``m_c`` is the midpoint of the edge of
        halfedge ``3f + c``; orientations are kept.  Edge ``e`` becomes edges ``2e``
        (at ``edge_vertices(e)[0]``) and ``2e + 1``; interior edges follow.

        >>> t, mids = Triangulation.from_faces([[0, 1, 2]]).subdivide_1to4()
        >>> t.n_vertices, t.n_edges, t.n_faces, mids
        (6, 9, 4, [(0, 1), (1, 2), (2, 0)])
        """
        n, F, E = self._n, len(self._faces), len(self._edges)
        eo = self._edge_of
        faces = []
        for f, x in enumerate(self._faces):
            m = (n + eo[3 * f], n + eo[3 * f + 1], n + eo[3 * f + 2])
            faces += [(x[0], m[0], m[2]), (x[1], m[1], m[0]), (x[2], m[2], m[1]), m]

        def first(h):           # tail(h) -> midpoint, in the corner face at tail(h)
            return 12 * (h // 3) + 3 * (h % 3)

        def second(h):          # midpoint -> head(h), in the corner face at head(h)
            return 12 * (h // 3) + 3 * ((h % 3 + 1) % 3) + 2

        gluings = _split_gluings(self, first, second)
        for f in range(F):
            for c in range(3):
                gluings.append((12 * f + 3 * c + 1, 12 * f + 9 + (c + 2) % 3, False))
        mids = [self.edge_vertices(e) for e in range(E)]
        return Triangulation._trusted(faces, n + E, gluings), mids

    def barycentric_subdivision(self) -> tuple["Triangulation", list[tuple[int, ...]]]:
        """Barycentric subdivision (R1.5: chi unchanged): V' = V + E + F, E' = 2E + 6F, F' = 6F.

        New vertex ``n_vertices + e`` is the midpoint of edge ``e``, then
        ``n_vertices + n_edges + f`` the barycentre of face ``f``;
        ``provenance[i]`` lists the old vertices averaged for vertex
        ``n_vertices + i`` (``edge_vertices(e)``, then the face's three vertices).
        Face ``f`` becomes faces ``6f + 2c = (x_c, m_c, b)`` and
        ``6f + 2c + 1 = (m_c, x_{c+1}, b)``, orientation kept.

        >>> t, prov = Triangulation.from_faces([[0, 1, 2]]).barycentric_subdivision()
        >>> t.n_faces, prov[-1]
        (6, (0, 1, 2))
        """
        n, F, E = self._n, len(self._faces), len(self._edges)
        eo = self._edge_of
        faces = []
        for f, x in enumerate(self._faces):
            bc = n + E + f
            for c in range(3):
                m = n + eo[3 * f + c]
                faces += [(x[c], m, bc), (m, x[(c + 1) % 3], bc)]

        def first(h):
            return 18 * (h // 3) + 6 * (h % 3)

        def second(h):
            return 18 * (h // 3) + 6 * (h % 3) + 3

        gluings = _split_gluings(self, first, second)
        for f in range(F):
            for c in range(3):
                A = 18 * f + 6 * c
                gluings.append((A + 1, A + 5, False))                     # m_c -- b
                gluings.append((A + 4, 18 * f + 6 * ((c + 1) % 3) + 2, False))  # x_{c+1} -- b
        prov = [self.edge_vertices(e) for e in range(E)] + list(self._faces)
        return Triangulation._trusted(faces, n + E + F, gluings), prov

    def remove_face(self, f: int) -> "Triangulation":
        """Delete face ``f`` (faces after it move down by one); its edges become boundary.

        For a face with no boundary edge this punches a hole (CS: chi drops by 1,
        one more boundary loop); edges lying only on ``f`` disappear.  Raises
        NonManifoldVertex if a vertex of ``f`` would be left with two fans (``f``
        touches the boundary at a corner), UnreferencedVertex if a vertex would be
        left unused, EmptyMesh for the last face.
        """
        F = len(self._faces)
        f = checked_index(f, F, "face")
        if F == 1:
            raise EmptyMesh("removing the only face would leave no faces")
        lo, hi = 3 * f, 3 * f + 3

        def hm(x):
            return x if x < lo else x - 3

        gluings = []
        for a, t in self._edges:
            a_in = lo <= a < hi
            t_in = lo <= t < hi
            if a_in and (t < 0 or t_in):
                continue                  # the edge lay only on f
            if a_in:
                gluings.append((hm(t), -1, False))
            elif t_in:
                gluings.append((hm(a), -1, False))
            else:
                gluings.append((hm(a), hm(t) if t >= 0 else -1, self._rev[a]))
        faces = self._faces[:f] + self._faces[f + 1:]
        out = Triangulation._trusted(faces, self._n, gluings)
        used = set(v for g in faces for v in g)
        for v in self._faces[f]:
            if v not in used:
                raise UnreferencedVertex(f"removing face {f} would leave vertex {v} unused")
        try:
            out._check_vertices(self._faces[f])
        except NonManifoldVertex as err:
            raise NonManifoldVertex(f"removing face {f}: {err}") from None
        return out

    def relabelled(self, perm) -> "Triangulation":
        """The same triangulation with vertex ``v`` renamed ``perm[v]`` (gluings unchanged)."""
        if hasattr(perm, "tolist"):
            perm = perm.tolist()
        perm = list(perm)
        if len(perm) != self._n:
            raise BadShape(f"permutation has {len(perm)} entries, need n_vertices = {self._n}")
        for v, p in enumerate(perm):
            if not _is_int(p):
                raise NonIntegerIndex(f"perm[{v}] = {_short(p)} is not an integer")
            if not 0 <= p < self._n:
                raise IndexOutOfRange(f"perm[{v}] = {p} is not in range({self._n})")
        perm = [int(p) for p in perm]
        if len(set(perm)) != self._n:
            dup = next(p for p in perm if perm.count(p) > 1)
            raise InputError(f"perm is not a permutation: {dup} occurs twice")
        faces = [tuple(perm[v] for v in f) for f in self._faces]
        return Triangulation._trusted(faces, self._n, self._gluings())

    def with_reversed_faces(self, face_indices) -> "Triangulation":
        """Reverse the corner order of the given faces: ``(a, b, c) -> (a, c, b)``.

        Gluings of a reversed face with a non-reversed one toggle their reversed
        flag, so the surface is the same; only the orientation of those faces changes.
        """
        fs = {checked_index(f, len(self._faces), "face") for f in face_indices}
        b = TriangulationBuilder(self)
        b.reverse_faces(fs)
        return b.build()

    def _gluings(self):
        return [(a, t, self._rev[a]) for a, t in self._edges]

    # --- dunder ---------------------------------------------------------------------

    def _key(self):
        return (self._n, self._faces, self._edges, self._rev)

    def __eq__(self, other):
        if not isinstance(other, Triangulation):
            return NotImplemented
        return self._key() == other._key()

    def __hash__(self):
        return hash(self._key())

    def __repr__(self) -> str:
        return (f"Triangulation(V={self._n}, E={len(self._edges)}, F={len(self._faces)}, "
                f"chi={self.euler_characteristic()})")


def _parse_gluings(gluings, H: int):
    if hasattr(gluings, "tolist"):
        gluings = gluings.tolist()
    out = []
    seen = [False] * H
    for e, g in enumerate(gluings):
        try:
            a, b, r = g
        except (TypeError, ValueError):
            raise BadShape(f"gluing {e}: expected (halfedge, twin or -1, reversed), "
                           f"got {_short(g)}") from None
        for x in (a, b):
            if not _is_int(x):
                raise NonIntegerIndex(f"gluing {e}: halfedge {_short(x)} is not an integer")
        a, b = int(a), int(b)
        if not 0 <= a < H or not -1 <= b < H:
            raise IndexOutOfRange(f"gluing {e}: halfedge out of range({H}) in ({a}, {b})")
        if a == b:
            raise InputError(f"gluing {e}: halfedge {a} glued to itself")
        for x in (a, b):
            if x >= 0:
                if seen[x]:
                    raise InputError(f"gluing {e}: halfedge {x} is already glued")
                seen[x] = True
        out.append((a, b, bool(r) and b >= 0))
    for x in range(H):
        if not seen[x]:
            raise InputError(f"halfedge {x} (face {x // 3}, corner {x % 3}) is in no gluing")
    return out


def _split_gluings(tri: Triangulation, first, second):
    """Gluings of the two halves of every edge, edge ``e`` -> edges ``2e`` and ``2e+1``.

    ``first(h)``/``second(h)`` are the new halfedges from tail(h) to the midpoint
    and from the midpoint to head(h).  An orientation-preserving gluing matches
    tail(h) with head(t), so h's first half meets t's second half.
    """
    out = []
    rev = tri._rev
    for a, t in tri._edges:
        if t < 0:
            out += [(first(a), -1, False), (second(a), -1, False)]
        elif rev[a]:
            out += [(first(a), first(t), True), (second(a), second(t), True)]
        else:
            out += [(first(a), second(t), False), (second(a), first(t), False)]
    return out


class TriangulationBuilder:
    """Mutable copy of a triangulation for local surgery (flip, split, reversal).

    It also reads like a :class:`Triangulation` (``tail``, ``head``,
    ``edge_halfedges``, ...), so that a long sequence of flips can run on one
    builder, O(1) each, and be frozen once with :meth:`build`
    (:class:`ddg_oracle.reference.intrinsic.IntrinsicTriangulation`); ``Triangulation.flip``
    is one :meth:`flip` on a fresh copy, so both give identical triangulations.
    """

    def __init__(self, tri: Triangulation):
        # Plain list copies (C speed); faces stay tuples and only the few faces an
        # operation touches are replaced, so a flip costs no Python loop over F.
        self.faces = list(tri._faces)
        self.twins = list(tri._twin)
        self.revs = list(tri._rev)
        self.eid = list(tri._edge_of)
        self.first = list(map(itemgetter(0), tri._edges))
        self.edges = list(tri._edges)
        self.dirty = set()                # edges whose halfedges moved or were re-glued
        self.n = tri._n
        self.vcorner = list(tri._vcorner)
        self.touched = set()
        self.old_vertices = set()

    def set_face(self, f: int, corners) -> None:
        self.old_vertices.update(self.faces[f])
        self.touched.add(f)
        self.faces[f] = tuple(corners)

    def add_face(self, corners) -> int:
        self.touched.add(len(self.faces))
        self.faces.append(tuple(corners))
        self.twins += [-1, -1, -1]
        self.revs += [False, False, False]
        self.eid += [-1, -1, -1]
        return len(self.faces) - 1

    def move(self, mapping: dict) -> None:
        """Move the gluing data of halfedge slots ``old -> new`` (simultaneously).

        Vacated slots are left unglued for the caller to fill.
        """
        twin, rev, eid, first = self.twins, self.revs, self.eid, self.first
        snap = [(s, twin[s], rev[s], eid[s]) for s in mapping]
        firsts = [(e, mapping[s]) for s, _, _, e in snap if e >= 0 and first[e] == s]
        dests = set(mapping.values())
        for s in mapping:
            if s not in dests:
                twin[s], rev[s], eid[s] = -1, False, -1
        for s, t, r, e in snap:
            self.dirty.add(e)
            d = mapping[s]
            nt = mapping.get(t, t) if t >= 0 else -1
            twin[d], rev[d], eid[d] = nt, r, e
            if nt >= 0 and t not in mapping:
                twin[nt] = d
        for e, d in firsts:
            first[e] = d

    def glue(self, a: int, b: int, r: bool, e: int | None = None) -> int:
        """Make ``a``, ``b`` (``b = -1``: boundary) edge ``e`` (a new edge if None)."""
        if e is None:
            e = len(self.first)
            self.first.append(a)
        else:
            self.first[e] = a
        self.dirty.add(e)
        r = bool(r) and b >= 0
        self.twins[a], self.revs[a], self.eid[a] = b, r, e
        if b >= 0:
            self.twins[b], self.revs[b], self.eid[b] = a, r, e
        return e

    def reverse_faces(self, fs) -> None:
        """``(x0, x1, x2) -> (x0, x2, x1)`` for faces in ``fs``; halfedge slots
        ``3g`` and ``3g+2`` swap, and gluings to faces outside ``fs`` toggle."""
        twin, rev = self.twins, self.revs
        for g in fs:
            for s in (3 * g, 3 * g + 1, 3 * g + 2):
                t = twin[s]
                if t >= 0 and t // 3 not in fs:
                    rev[s] = not rev[s]
                    rev[t] = not rev[t]
        mapping = {}
        for g in fs:
            x0, x1, x2 = self.faces[g]
            self.set_face(g, (x0, x2, x1))
            mapping[3 * g] = 3 * g + 2
            mapping[3 * g + 2] = 3 * g
        self.move(mapping)

    def split_halfedge(self, x: int, m: int):
        """Insert vertex ``m`` on halfedge ``x`` of face ``(a, b, k)``, splitting the face
        into ``(a, m, k)`` (same index, ``x`` becomes ``a -> m``) and a new face
        ``(m, b, k)``.  The gluings of the two halves are left to the caller.
        Returns ``(first half, second half, moved slots)``."""
        f, c = x // 3, x % 3
        corners = list(self.faces[f])
        b, k = corners[(c + 1) % 3], corners[(c + 2) % 3]
        N = self.add_face([m, b, k])
        xn = _next(x)
        moved = {xn: 3 * N + 1}
        self.move(moved)
        corners[(c + 1) % 3] = m
        self.set_face(f, corners)
        self.glue(xn, 3 * N + 2, False)           # the new edge m -- k
        return x, 3 * N, moved

    def flip(self, e: int) -> None:
        """:meth:`Triangulation.flip` in place (``e`` a valid interior edge with two
        distinct faces; the caller checks).  O(1)."""
        h = self.first[e]
        t = self.twins[h]
        f, g = h // 3, t // 3
        if self.revs[h]:
            self.reverse_faces({g})
            t = self.twins[h]
        i, j, k = self.faces[f][h % 3], self.faces[f][(h + 1) % 3], self.faces[f][(h + 2) % 3]
        l_ = self.faces[g][(t + 2) % 3]
        self.move({_prev(t): 3 * f + 1, _next(h): 3 * f + 2,
                   _prev(h): 3 * g + 1, _next(t): 3 * g + 2})
        self.set_face(f, (k, l_, j))
        self.set_face(g, (l_, k, i))
        self.glue(3 * f, 3 * g, False, e)
        # settle vertex corners after every flip, as a fresh build would: the
        # corner a vertex's star starts from then does not depend on how many
        # flips ran on this builder
        self.settle_vertices()

    def settle_vertices(self) -> None:
        """Point every vertex that lost its corner to its first corner in a touched face."""
        faces, vcorner = self.faces, self.vcorner
        vcorner += [-1] * (self.n - len(vcorner))
        # Only vertices of touched faces can have lost the corner vcorner points to.
        fresh = {}
        for f in sorted(self.touched):
            for c, v in enumerate(faces[f]):
                fresh.setdefault(v, 3 * f + c)
        for v in self.old_vertices | set(fresh):
            k = vcorner[v]
            if k < 0 or faces[k // 3][k % 3] != v:
                vcorner[v] = fresh[v]          # every operation keeps v in a touched face
        self.touched.clear()
        self.old_vertices.clear()

    # --- reading like a Triangulation (for long flip sequences) -------------------------

    @property
    def n_vertices(self) -> int:
        return self.n

    @property
    def n_faces(self) -> int:
        return len(self.faces)

    @property
    def n_edges(self) -> int:
        return len(self.first)

    def tail(self, h: int) -> int:
        return self.faces[h // 3][h % 3]

    def head(self, h: int) -> int:
        return self.faces[h // 3][(h + 1) % 3]

    next = staticmethod(_next)
    prev = staticmethod(_prev)
    face_of = staticmethod(face_of)

    def twin(self, h: int) -> int:
        return self.twins[h]

    def reversed_gluing(self, h: int) -> bool:
        return self.revs[h]

    def edge_of(self, h: int) -> int:
        return self.eid[h]

    def edge_halfedges(self, e: int) -> tuple[int, int]:
        h = self.first[e]
        return h, self.twins[h]

    def edge_vertices(self, e: int) -> tuple[int, int]:
        h = self.first[e]
        return self.tail(h), self.head(h)

    def is_boundary_edge(self, e: int) -> bool:
        return self.twins[self.first[e]] < 0

    def build(self) -> Triangulation:
        self.settle_vertices()
        faces, vcorner = self.faces, self.vcorner
        out = object.__new__(Triangulation)
        out._faces = tuple(faces)
        out._n = self.n
        out._twin = tuple(self.twins)
        out._rev = tuple(self.revs)
        out._edge_of = tuple(self.eid)
        edges = self.edges
        edges += [None] * (len(self.first) - len(edges))
        for e in self.dirty:
            if e >= 0:
                edges[e] = (self.first[e], self.twins[self.first[e]])
        out._edges = tuple(edges)
        out._vcorner = tuple(vcorner)
        out._fans = {}
        return out


# --- connected sum -------------------------------------------------------------------


def _combinatorics_of(x, name: str) -> Triangulation:
    """The triangulation of ``x``: itself, or a surface's ``.triangulation``; TypeError else."""
    if isinstance(x, Triangulation):
        return x
    t = getattr(x, "triangulation", None)
    if isinstance(t, Triangulation):
        return t
    raise TypeError(f"connected_sum: {name} is a {type(x).__name__}; pass a Triangulation, or a "
                    f"surface (PolyhedralSurface, PiecewiseFlatSurface) whose triangulation is "
                    f"summed")


def connected_sum(a, b, face_a: int = -1, face_b: int = -1) -> Triangulation:
    """CS: the connected sum ``a # b``; chi(a # b) = chi(a) + chi(b) - 2.

    Combinatorial: ``a`` and ``b`` are Triangulations, or surfaces of any type
    (:class:`~ddg_oracle.reference.polyhedral.PolyhedralSurface`, ...) whose
    triangulations are summed; the result is a :class:`Triangulation` (positions
    have no canonical connected sum).

    Removes face ``face_a`` of ``a`` and ``face_b`` of ``b`` (default: the last
    face of each; negative indices count from the end) and glues the two
    triangle boundaries.  With ``face_a = (x0, x1, x2)`` and ``face_b = (y0, y1,
    y2)``, ``y0 ~ x0, y1 ~ x2, y2 ~ x1``: the two triangles are identified with
    opposite orientations, so two consistently oriented inputs give a
    consistently oriented (orientable) result.  The faces of ``a`` (without
    ``face_a``) come first, then those of ``b``; ``a``'s vertices keep their ids
    and ``b``'s other vertices follow in increasing order.  Both faces need three
    distinct vertices and no boundary edge.  Strongly regular inputs give a
    strongly regular result.

    >>> tet = [[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]]
    >>> s = connected_sum(Triangulation.from_faces(tet), Triangulation.from_faces(tet))
    >>> s.n_vertices, s.n_faces, s.euler_characteristic()
    (5, 6, 2)
    >>> from ddg_oracle.reference import surfaces
    >>> connected_sum(surfaces.torus(3, 4), surfaces.genus_surface(2)).classify().genus
    3
    """
    a, b = _combinatorics_of(a, "a"), _combinatorics_of(b, "b")
    fa = checked_index(face_a, a.n_faces, "face", allow_negative=True)
    fb = checked_index(face_b, b.n_faces, "face", allow_negative=True)
    for name, tri, f in (("a", a, fa), ("b", b, fb)):
        x = tri.faces[f]
        if len(set(x)) < 3:
            raise InputError(f"connected_sum: face {f} of {name} = {x} repeats a vertex")
        for h in range(3 * f, 3 * f + 3):
            if tri._twin[h] < 0:
                raise InputError(f"connected_sum: face {f} of {name} has boundary edge "
                                 f"{tri._edge_of[h]}")
    xa, yb = a.faces[fa], b.faces[fb]
    nA, FA = a.n_vertices, a.n_faces
    vmap = {yb[0]: xa[0], yb[1]: xa[2], yb[2]: xa[1]}
    for v in range(b.n_vertices):
        if v not in vmap:
            vmap[v] = nA + len(vmap) - 3
    faces = [x for g, x in enumerate(a.faces) if g != fa]
    faces += [tuple(vmap[v] for v in x) for g, x in enumerate(b.faces) if g != fb]

    def hA(x):
        return x if x < 3 * fa else x - 3

    def hB(x):
        return 3 * (FA - 1) + (x if x < 3 * fb else x - 3)

    gluings = []
    for h, t in a._edges:
        if h // 3 == fa or t // 3 == fa:
            p, P = (h, t) if h // 3 == fa else (t, h)
            # halfedge q_c of face_b is identified with p_{(2-c) % 3}, opposite direction
            q = 3 * fb + (2 - p % 3) % 3
            Q = b._twin[q]
            gluings.append((hA(P), hB(Q), a._rev[p] != b._rev[q]))
        else:
            gluings.append((hA(h), hA(t) if t >= 0 else -1, a._rev[h]))
    for h, t in b._edges:
        if h // 3 != fb and t // 3 != fb:
            gluings.append((hB(h), hB(t) if t >= 0 else -1, b._rev[h]))
    out = Triangulation._trusted(faces, nA + b.n_vertices - 3, gluings)
    try:
        out._check_vertices(xa)
    except NonManifoldVertex as err:
        raise NonManifoldVertex(f"connected_sum: {err} (both faces touch the boundary)") from None
    return out
