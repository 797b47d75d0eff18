"""Deliberately wrong implementations: each must be caught by a property.

Each class is the reference with one plausible bug planted, the kind a
developer actually writes; ``planted`` names the protocol methods it changes
(``python -m benchmarks catch`` checks each bug on the properties that call them).
"""

import math

import time

import numpy as np

from ddg_oracle.oracles.exact_reference import ReferenceImplementation
from examples.numpy_mesh import NumpyMesh      # its boundary test: edges of one face


class ChiIgnoresBoundary(ReferenceImplementation):
    """Assumes a closed surface: E = 3F/2 (wrong as soon as there is a boundary)."""

    name = "chi-ignores-boundary"
    planted = ("euler_characteristic",)

    def euler_characteristic(self, V, F):
        return len(V) - (3 * len(F)) // 2 + len(F)


class SlowOnCubes(ReferenceImplementation):
    """No bug: the reference, but a second slow on the Euler characteristic of a 12-face
    mesh (the cube).  A survey of tetrahedron, disk and cube (tests/test_survey.py) is then
    still running after its first meshes are recorded, however fast the machine, so that
    an interrupt reliably finds meshes left to do."""

    name = "slow-on-cubes"

    def euler_characteristic(self, V, F):
        if len(F) == 12:
            time.sleep(1)
        return super().euler_characteristic(V, F)


class AlwaysOrientable(ReferenceImplementation):
    """Never looks for an orientation-reversing loop."""

    name = "always-orientable"
    planted = ("is_orientable", "genus")

    def is_orientable(self, V, F):
        return True

    def genus(self, V, F):
        return (2 - self.euler_characteristic(V, F)) // 2


class OneBoundaryLoop(ReferenceImplementation):
    """Chains all boundary edges into a single loop."""

    name = "one-boundary-loop"
    planted = ("boundary_loops",)

    def boundary_loops(self, V, F):
        loops = super().boundary_loops(V, F)
        return [sum(loops, [])] if loops else []


class Float32Defects(ReferenceImplementation):
    """Correct angle defects, rounded to float32 (as a float32 library computes them)."""

    name = "float32-defects"
    planted = ("angle_defects",)

    def angle_defects(self, V, F):
        import numpy as np
        K = super().angle_defects(V, F)
        return (K.astype(np.float32) + np.float32(1e-7) * (K != 0)).astype(np.float64)


class Float32DefectsDeclared(Float32Defects):
    """Not a bug: the same float32 values, declared (held to float32 bounds, it passes)."""

    name = "float32-defects-declared"
    planted = ()
    machine_epsilon = 2.0 ** -23


# --- chapter 4: intrinsic Delaunay -----------------------------------------------------------

class NoFlips(ReferenceImplementation):
    """Returns the cotan Laplacian of the input triangulation: forgets to flip."""

    name = "delaunay-without-flips"
    planted = ("intrinsic_delaunay_laplacian", "planar_flip_to_delaunay",
               "intrinsic_delaunay_triangulation")

    def intrinsic_delaunay_laplacian(self, V, F):
        return self.cotan_laplacian(V, F)

    def planar_flip_to_delaunay(self, V, F):
        return F

    def intrinsic_delaunay_triangulation(self, V, F):
        import numpy as np
        V, F = np.asarray(V, float), np.asarray(F)
        l2 = np.stack([((V[F[:, (c + 1) % 3]] - V[F[:, (c + 2) % 3]]) ** 2).sum(1)
                       for c in range(3)], axis=1)
        return F, l2


class OneFlipTooMany(ReferenceImplementation):
    """Flips to Delaunay, then flips one more edge: the first interior edge whose
    quadrilateral is strictly convex (a loop that tests its stopping rule after acting)."""

    name = "one-flip-too-many"
    planted = ("planar_flip_to_delaunay",)

    def planar_flip_to_delaunay(self, V, F):
        import numpy as np
        from ddg_oracle.reference.combinatorics import Triangulation
        from ddg_oracle.reference.planar import straight_line_flip
        F2 = super().planar_flip_to_delaunay(V, F)
        pts = [(x, y) for x, y, _ in np.asarray(V, float)]
        t = Triangulation.from_faces(F2.tolist(), n_vertices=len(pts))
        for e in range(t.n_edges):
            u = straight_line_flip(pts, t, e)
            if u is not None:
                return np.array(u.faces, dtype=np.int64)
        return F2


class OneSidedDelaunayTest(ReferenceImplementation):
    """Tests only the angle in one of the two triangles: cot a >= 0 instead of cot a + cot b >= 0."""

    name = "one-sided-delaunay-test"
    planted = ("is_locally_delaunay",)

    def is_locally_delaunay(self, V, F):
        import numpy as np
        ang = self.corner_angles(V, F)
        return np.cos(ang) >= 0


class LaplaceBeltramiWithoutHalf(ReferenceImplementation):
    """The Laplace-Beltrami weights cot a + cot b, without the 1/2."""

    name = "laplace-beltrami-without-half"
    planted = ("intrinsic_delaunay_laplacian",)

    def intrinsic_delaunay_laplacian(self, V, F):
        return 2 * super().intrinsic_delaunay_laplacian(V, F)


# --- bugs that only inputs far from the plain case show (scale, offset, orientation) ---------


def _numpy_corner_angles(V, F, squared_lengths):
    """Corner angles by the law of cosines from per-corner squared edge lengths."""
    import numpy as np
    out = np.empty(F.shape)
    for c in range(3):
        i, j, k = F[:, c], F[:, (c + 1) % 3], F[:, (c + 2) % 3]
        a2, b2, c2 = squared_lengths(V, i, j), squared_lengths(V, i, k), squared_lengths(V, j, k)
        out[:, c] = np.arccos(np.clip((a2 + b2 - c2) / (2 * np.sqrt(a2 * b2)), -1, 1))
    return out


class BoundaryByMissingTwin(ReferenceImplementation):
    """Boundary vertices found as the ends of halfedges i -> j whose twin j -> i is missing:
    right on consistently oriented meshes, wrong on a Möbius strip or with a reversed face
    (an interior edge listed twice in one direction looks like two boundary edges)."""

    name = "boundary-by-missing-twin"
    planted = ("angle_defects",)

    def angle_defects(self, V, F):
        import numpy as np
        F = np.asarray(F)
        sums = np.zeros(len(V))
        np.add.at(sums, F, super().corner_angles(V, F))
        halfedges = {(int(f[c]), int(f[(c + 1) % 3])) for f in F for c in range(3)}
        boundary = {v for i, j in halfedges if (j, i) not in halfedges for v in (i, j)}
        return np.array([(np.pi if v in boundary else 2 * np.pi) - sums[v]
                         for v in range(len(V))])


class AbsoluteZeroArea(ReferenceImplementation):
    """Corner angles with a 'degenerate triangle' guard on an absolute threshold: a face of
    |cross| < 1e-13 (any face of a mesh scaled below about 1e-7) gets angles pi/3."""

    name = "absolute-zero-area"
    planted = ("corner_angles",)

    def corner_angles(self, V, F):
        import numpy as np
        V, F = np.asarray(V, float), np.asarray(F)
        angles = super().corner_angles(V, F)
        cross = np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), axis=1)
        angles[cross < 1e-13] = np.pi / 3
        return angles


class OffsetCancellation(ReferenceImplementation):
    """Squared edge lengths as |x|^2 + |y|^2 - 2 x.y: exact far from nothing, but far from
    the origin the three terms cancel catastrophically (and the angles with them)."""

    name = "offset-cancellation"
    planted = ("corner_angles",)

    def corner_angles(self, V, F):
        import numpy as np
        V, F = np.asarray(V, float), np.asarray(F)

        def squared(V, i, j):
            x, y = V[i], V[j]
            return (x * x).sum(1) + (y * y).sum(1) - 2 * (x * y).sum(1)
        return _numpy_corner_angles(V, F, squared)


# --- bugs that slivers, high valence, components and isolated vertices show (issue 16) -------


def _angle_sums(V, F, angles, n):
    import numpy as np
    sums = np.zeros(n)
    np.add.at(sums, np.asarray(F), angles)
    return sums


def _defects_from_sums(sums, boundary):
    """2 pi - sum, pi - sum where ``boundary`` (a bool per vertex) is set; one value per sum
    (a short ``sums`` stays short: that is BincountWithoutMinlength's bug)."""
    import numpy as np
    return np.where(boundary[:len(sums)], np.pi, 2 * np.pi) - sums


class ClampedArccos(ReferenceImplementation):
    """Corner angles as arccos of the cosine clipped to [-1 + 1e-10, 1 - 1e-10] 'to avoid NaN':
    every angle below 1.4e-5 rad (a needle) or above pi - 1.4e-5 (a cap) is moved there."""

    name = "clamped-arccos"
    planted = ("corner_angles",)

    def corner_angles(self, V, F):
        import numpy as np
        V, F = np.asarray(V, float), np.asarray(F)
        out = np.empty(F.shape)
        for c in range(3):
            a = V[F[:, (c + 1) % 3]] - V[F[:, c]]
            b = V[F[:, (c + 2) % 3]] - V[F[:, c]]
            cos = (a * b).sum(1) / (np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1))
            out[:, c] = np.arccos(np.clip(cos, -1 + 1e-10, 1 - 1e-10))
        return out


class MaxValence32(ReferenceImplementation):
    """One-ring tables of a fixed width 32 (as GPU and C codes allocate them): a vertex of
    valence above 32 sums only the angles of its first 32 corners."""

    name = "max-valence-32"
    planted = ("angle_defects",)

    def angle_defects(self, V, F):
        import numpy as np
        F = np.asarray(F)
        angles = super().corner_angles(V, F)
        sums, seen = np.zeros(len(V)), np.zeros(len(V), dtype=int)
        for f, face in enumerate(F):
            for c, v in enumerate(face):
                if seen[v] < 32:
                    sums[v] += angles[f, c]
                    seen[v] += 1
        return _defects_from_sums(sums, NumpyMesh._boundary(V, F))


class FirstComponentOnly(ReferenceImplementation):
    """Walks the mesh from face 0 across edges and sums the angles of the faces it reaches:
    right on a connected mesh; the vertices of any other component keep 2 pi."""

    name = "first-component-only"
    planted = ("angle_defects",)

    def angle_defects(self, V, F):
        import numpy as np
        F = np.asarray(F)
        by_edge = {}
        for f, face in enumerate(F):
            for c in range(3):
                by_edge.setdefault(frozenset((int(face[c]), int(face[(c + 1) % 3]))), []).append(f)
        reached, todo = {0}, [0]
        while todo:
            f = todo.pop()
            for c in range(3):
                for g in by_edge[frozenset((int(F[f][c]), int(F[f][(c + 1) % 3])))]:
                    if g not in reached:
                        reached.add(g)
                        todo.append(g)
        angles = super().corner_angles(V, F)
        keep = sorted(reached)
        sums = _angle_sums(V, F[keep], angles[keep], len(V))
        return _defects_from_sums(sums, NumpyMesh._boundary(V, F))


class WeldedByPosition(ReferenceImplementation):
    """Merges vertices at the same position first (as mesh loaders do by default), then
    computes defects per merged vertex: two components touching at a point share one
    angle sum, and an isolated vertex on a used one takes that one's defect."""

    name = "welded-by-position"
    planted = ("angle_defects",)

    def angle_defects(self, V, F):
        import numpy as np
        V, F = np.asarray(V, float), np.asarray(F)
        _, weld = np.unique(V, axis=0, return_inverse=True)
        weld = weld.reshape(-1)
        W = weld[F]
        sums = _angle_sums(V, W, super().corner_angles(V, F), len(V))
        K = _defects_from_sums(sums, NumpyMesh._boundary(V, W))
        return K[weld]


class BincountWithoutMinlength(ReferenceImplementation):
    """Angle sums by np.bincount(F.ravel(), weights) without minlength=len(V): one value
    short per unreferenced vertex at the end of V (right everywhere else: 2 pi - 0)."""

    name = "bincount-without-minlength"
    planted = ("angle_defects",)

    def angle_defects(self, V, F):
        import numpy as np
        F = np.asarray(F)
        sums = np.bincount(F.ravel(), weights=super().corner_angles(V, F).ravel())
        return _defects_from_sums(sums, NumpyMesh._boundary(V, F))


class CompactedVertices(ReferenceImplementation):
    """Drops unreferenced vertices (np.unique of F), computes on the compacted mesh, and pads
    the answer with 2 pi at the end: every vertex after an isolated one gets its
    neighbour's value."""

    name = "compacted-vertices"
    planted = ("angle_defects",)

    def angle_defects(self, V, F):
        import numpy as np
        V, F = np.asarray(V, float), np.asarray(F)
        used, inverse = np.unique(F, return_inverse=True)
        K = super().angle_defects(V[used], inverse.reshape(F.shape))
        return np.concatenate([K, np.full(len(V) - len(used), 2 * np.pi)])


class IntrinsicCompacted(ReferenceImplementation):
    """Intrinsic Delaunay on the compacted mesh (np.unique of F), the faces of the result
    left in the compacted numbering: right whenever every row of V is used."""

    name = "intrinsic-compacted"
    planted = ("intrinsic_delaunay_triangulation", "intrinsic_delaunay_laplacian")

    def intrinsic_delaunay_triangulation(self, V, F):
        import numpy as np
        V, F = np.asarray(V, float), np.asarray(F)
        used, inverse = np.unique(F, return_inverse=True)
        return super().intrinsic_delaunay_triangulation(V[used], inverse.reshape(F.shape))

    def intrinsic_delaunay_laplacian(self, V, F):
        import numpy as np
        import scipy.sparse as sp
        V, F = np.asarray(V, float), np.asarray(F)
        used, inverse = np.unique(F, return_inverse=True)
        L = sp.coo_matrix(super().intrinsic_delaunay_laplacian(V[used], inverse.reshape(F.shape)))
        return sp.csr_matrix((L.data, (L.row, L.col)), shape=(len(V), len(V)))


class IntrinsicFirstHoleOnly(ReferenceImplementation):
    """Intrinsic Delaunay on the compacted mesh, mapped back by shifting the indices past the
    first unused vertex by one: right with at most one unused vertex."""

    name = "intrinsic-first-hole-only"
    planted = ("intrinsic_delaunay_triangulation", "intrinsic_delaunay_laplacian")

    @staticmethod
    def _compacted(V, F):
        import numpy as np
        V, F = np.asarray(V, float), np.asarray(F)
        used, inverse = np.unique(F, return_inverse=True)
        k = np.arange(len(used))
        holes = np.setdiff1d(np.arange(len(V)), used)
        back = np.where(k >= holes[0], k + 1, k) if len(holes) else k
        return V[used], inverse.reshape(F.shape), back

    def intrinsic_delaunay_triangulation(self, V, F):
        Vc, Fc, back = self._compacted(V, F)
        F2, l2 = super().intrinsic_delaunay_triangulation(Vc, Fc)
        return back[F2], l2

    def intrinsic_delaunay_laplacian(self, V, F):
        import scipy.sparse as sp
        Vc, Fc, back = self._compacted(V, F)
        L = sp.coo_matrix(super().intrinsic_delaunay_laplacian(Vc, Fc))
        return sp.csr_matrix((L.data, (back[L.row], back[L.col])), shape=(len(V), len(V)))


class DelaunayKeyedByUsedCount(ReferenceImplementation):
    """is_locally_delaunay pairing halfedge i -> j with its twin under the key i k + j, k the
    number of vertices the faces use (not len(V)): keys collide once an unused vertex sits
    below the largest index, and an edge is paired with another edge's corner."""

    name = "delaunay-keyed-by-used-count"
    planted = ("is_locally_delaunay",)

    def is_locally_delaunay(self, V, F):
        import numpy as np
        V, F = np.asarray(V, float), np.asarray(F, dtype=np.int64)
        k = len(np.unique(F))
        cot = np.empty(F.shape)
        for c in range(3):
            a = V[F[:, (c + 1) % 3]] - V[F[:, c]]
            b = V[F[:, (c + 2) % 3]] - V[F[:, c]]
            cot[:, c] = (a * b).sum(axis=1) / np.linalg.norm(np.cross(a, b), axis=1)
        opposite = {}                   # key of the directed edge -> the corner opposite it
        for f, face in enumerate(F):
            for c in range(3):
                i, j = face[(c + 1) % 3], face[(c + 2) % 3]
                opposite[i * k + j] = (f, c)
        out = np.ones(F.shape, dtype=bool)
        for f, face in enumerate(F):
            for c in range(3):
                i, j = face[(c + 1) % 3], face[(c + 2) % 3]
                twin = opposite.get(j * k + i)
                if twin is not None and twin != (f, c):
                    out[f, c] = cot[f, c] + cot[twin] >= 0
        return out


class TwinByReversedKey(ReferenceImplementation):
    """Cotan Laplacian that pairs halfedge i -> j with its twin by looking up j -> i: an
    interior edge between two inconsistently oriented faces (a reversed face, a Möbius
    strip) is taken for two boundary edges and gets only one of its cotangents."""

    name = "twin-by-reversed-key"
    planted = ("cotan_laplacian",)

    def cotan_laplacian(self, V, F):
        import numpy as np
        import scipy.sparse as sp
        V, F = np.asarray(V, float), np.asarray(F)
        cot = {}
        for f, face in enumerate(F):
            for c in range(3):
                i, j, k = int(face[c]), int(face[(c + 1) % 3]), int(face[(c + 2) % 3])
                a, b = V[i] - V[k], V[j] - V[k]
                cot[(i, j)] = float(a @ b / np.linalg.norm(np.cross(a, b)))
        rows, cols, vals = [], [], []
        for (i, j), x in cot.items():
            twin = cot.get((j, i))
            if twin is not None and i > j:
                continue                     # counted once, from the other halfedge
            w = (x + twin) / 2 if twin is not None else x / 2
            rows += [i, j, i, j]
            cols += [j, i, i, j]
            vals += [-w, -w, w, w]
        return sp.csr_matrix((vals, (rows, cols)), shape=(len(V), len(V)))


class TwoPiAtTheBoundary(ReferenceImplementation):
    """A third-party library's convention, declared by the implementation itself:
    2 pi - angle sum at boundary vertices too (as libigl's gaussian_curvature), with the
    reference as its counterpart on the notes' conventions."""

    name = "two-pi-at-the-boundary"
    conventions = {"follows": {"MYLIB-7": "2 pi - angle sum at boundary vertices"},
                   "counterpart": "reference"}

    def angle_defects(self, V, F):
        K = super().angle_defects(V, F)
        boundary = {v for loop in self.boundary_loops(V, F) for v in loop}
        return np.array([k + math.pi if v in boundary else k for v, k in enumerate(K)])


# --- topology on the inputs where it breaks: components, unused vertices, face direction ------


class ChiOfUsedVertices(ReferenceImplementation):
    """V - E + F with V the vertices some face uses (``np.unique(F)``): a vertex used by no
    face, which counts 1, is dropped."""

    name = "chi-of-used-vertices"
    planted = ("euler_characteristic",)

    def euler_characteristic(self, V, F):
        F = np.asarray(F)
        edges = {frozenset((int(f[c]), int(f[(c + 1) % 3]))) for f in F for c in range(3)}
        return len(np.unique(F)) - len(edges) + len(F)


class ChiOfFirstComponent(ReferenceImplementation):
    """V - E + F of the component of face 0 (a flood fill over shared edges), the other
    components forgotten."""

    name = "chi-of-first-component"
    planted = ("euler_characteristic",)

    def euler_characteristic(self, V, F):
        F = [tuple(int(v) for v in f) for f in np.asarray(F)]
        by_edge = {}
        for f, face in enumerate(F):
            for c in range(3):
                by_edge.setdefault(frozenset((face[c], face[(c + 1) % 3])), []).append(f)
        reached, todo = {0}, [0]
        while todo:
            f = todo.pop()
            for c in range(3):
                for g in by_edge[frozenset((F[f][c], F[f][(c + 1) % 3]))]:
                    if g not in reached:
                        reached.add(g)
                        todo.append(g)
        faces = [F[f] for f in reached]
        verts = {v for f in faces for v in f}
        edges = {frozenset((f[c], f[(c + 1) % 3])) for f in faces for c in range(3)}
        return len(verts) - len(edges) + len(faces)


class OrientableByDirectedEdges(ReferenceImplementation):
    """Orientable iff no directed edge is listed twice: that is whether the faces are
    *consistently oriented*, so an orientable surface given with a reversed face is called
    non-orientable (and its genus then counts crosscaps)."""

    name = "orientable-by-directed-edges"
    planted = ("is_orientable", "genus")

    def is_orientable(self, V, F):
        seen = set()
        for f in np.asarray(F).tolist():
            for c in range(3):
                e = (f[c], f[(c + 1) % 3])
                if e in seen:
                    return False
                seen.add(e)
        return True

    def genus(self, V, F):
        chi = self.euler_characteristic(V, F)
        k = len(self.boundary_loops(V, F))
        return (2 - chi - k) // 2 if self.is_orientable(V, F) else 2 - chi - k


class BoundaryLoopsByDirectedTwin(ReferenceImplementation):
    """Boundary edges as the halfedges i -> j whose twin j -> i is missing, chained into
    loops: an interior edge between a face and a reversed one (listed twice in one
    direction) becomes two boundary edges."""

    name = "boundary-loops-by-directed-twin"
    planted = ("boundary_loops",)

    def boundary_loops(self, V, F):
        halfedges = {(int(f[c]), int(f[(c + 1) % 3])) for f in np.asarray(F) for c in range(3)}
        nxt = {}
        for i, j in halfedges:
            if (j, i) not in halfedges:
                nxt.setdefault(i, []).append(j)
        loops, used = [], set()
        for start in sorted(nxt):
            for j0 in nxt[start]:
                if (start, j0) in used:
                    continue
                loop, i, j = [start], start, j0
                while (i, j) not in used:
                    used.add((i, j))
                    if j == start:
                        break
                    loop.append(j)
                    i, j = j, next((k for k in nxt.get(j, []) if (j, k) not in used), start)
                loops.append(loop)
        return loops
