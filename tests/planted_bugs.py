"""Deliberately wrong implementations: each must be caught by a property.

Each class is the reference with one plausible bug planted, the kind a
developer actually writes.
"""

from ddg_oracle.oracles.exact_reference import ReferenceImplementation


class ChiIgnoresBoundary(ReferenceImplementation):
    """Assumes a closed surface: E = 3F/2 (wrong as soon as there is a boundary)."""

    name = "chi-ignores-boundary"

    def euler_characteristic(self, V, F):
        return len(V) - (3 * len(F)) // 2 + len(F)


class AlwaysOrientable(ReferenceImplementation):
    """Never looks for an orientation-reversing loop."""

    name = "always-orientable"

    def is_orientable(self, V, F):
        return True

    def genus(self, V, F):
        return (2 - self.euler_characteristic(V, F)) // 2


class OneBoundaryLoop(ReferenceImplementation):
    """Chains all boundary edges into a single loop."""

    name = "one-boundary-loop"

    def boundary_loops(self, V, F):
        loops = super().boundary_loops(V, F)
        return [sum(loops, [])] if loops else []


class Float32Defects(ReferenceImplementation):
    """Correct angle defects, rounded to float32 (as a float32 library computes them)."""

    name = "float32-defects"

    def angle_defects(self, V, F):
        import numpy as np
        K = super().angle_defects(V, F)
        return (K.astype(np.float32) + np.float32(1e-7) * (K != 0)).astype(np.float64)


class Float32DefectsDeclared(Float32Defects):
    name = "float32-defects-declared"
    machine_epsilon = 2.0 ** -23


# --- chapter 4: intrinsic Delaunay -----------------------------------------------------------

class NoFlips(ReferenceImplementation):
    """Returns the cotan Laplacian of the input triangulation: forgets to flip."""

    name = "delaunay-without-flips"

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

    def is_locally_delaunay(self, V, F):
        import numpy as np
        ang = self.corner_angles(V, F)
        return np.cos(ang) >= 0


class LaplaceBeltramiWithoutHalf(ReferenceImplementation):
    """The Laplace-Beltrami weights cot a + cot b, without the 1/2."""

    name = "laplace-beltrami-without-half"

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

    def corner_angles(self, V, F):
        import numpy as np
        V, F = np.asarray(V, float), np.asarray(F)

        def squared(V, i, j):
            x, y = V[i], V[j]
            return (x * x).sum(1) + (y * y).sum(1) - 2 * (x * y).sum(1)
        return _numpy_corner_angles(V, F, squared)
