"""MeshLib (``meshlib.mrmeshpy``, ``meshlib.mrmeshnumpy``; MeshInspector/MeshLib, C++) in
its own conventions.

Every method builds ``mrmeshnumpy.meshFromFacesVerts(F, V, BuildSettings(), False)`` (a
half-edge ``MR::Mesh``) and calls the MeshLib function that computes the quantity; the
numbers compared are MeshLib's.  Sources: ``MeshInspector/MeshLib`` at commit ``8b04355``
(2026-08-23, the newest snapshot read; the wheel is meshlib / meshlib-core 3.1.4.297 of
2026-09-16, whose behaviour the tests measure).  Line numbers below are of that commit.

Single precision.  MeshLib stores coordinates as ``Vector3f``: ``meshFromFacesVerts``
casts every float64 coordinate with ``float( data[ind] )``
(``source/mrmeshnumpy/MRPythonNumpyExposing.cpp`` l. 31-34), and angles, cotangents,
dihedral angles, edge lengths, the intrinsic lengths of ``EdgeLengthMesh`` and the solved
scalar field are ``float`` (``MRMeshMath.h`` l. 132, 285, 298, 312; ``MRLaplacian.cpp``
``applyToScalar``).  The adapter declares ``machine_epsilon = 2 ** -23``: bounds are
float32 bounds.  Only ``Mesh.area()`` sums in double (``MRMeshMath.cpp`` l. 190-201), of
float32 face areas.

Vertex numbering.  ``MeshBuilder::fromTriangles`` keeps the input's ``VertId`` s and the
faces' ids (face i of F is ``FaceId(i)``); a vertex used by no face stays in ``points``
but not in the topology (``hasVert`` is false).  The builder does not check its input:
it *skips* a face with a repeated vertex (``MRMeshBuilder.cpp`` l. 131) or one that would
make a non-manifold vertex (l. 174, 180), and a face whose edge already has a face on the
same side gets a second, parallel edge (``findEdgeNoLeft``, l. 85, 154; the default
``allowNonManifoldEdge = true``): an inconsistently oriented pair of faces, or an edge
of three faces, is silently cut apart ("Vertices of triangles should have consistent
bypass direction", ``MRMeshBuilder.h`` l. 27).  The adapter compares MeshLib's mesh with
the input (every face kept with its vertices, one edge per vertex pair of F, every used
vertex present) and raises ``OutsideDomain`` naming the difference otherwise: MeshLib has
no value for the input's surface there.

Conventions (declared: ``{"weights": "full", "boundary_defect": "two_pi"}``)
------------------------------------------------------------------------------
* ``angle_defects``: ``mrmeshnumpy.getNumpyGaussianCurvature(mesh)``, i.e.
  ``discreteGaussianCurvature(v) = 2 * PI_F - sumAngles(v)`` (``MRMeshMath.h`` l. 298-300)
  at *every* vertex, boundary ones included (``sumAngles`` only reports the boundary,
  ``MRMeshMath.cpp`` l. 559-577): integrated, the vocabulary's
  ``boundary_defect=two_pi``.  Each corner angle is ``atan2(|d0 x d1|, d0 . d1)`` of float
  edge vectors (``MRVector3.h`` ``angle``).  Not covered by the vocabulary (mapped here by
  hand): the array has ``lastValidVert() + 1`` rows and 0.0 at a vertex not in the
  topology (``MRPythonNumpyExposing.cpp`` l. 454-466); the adapter gives every row of V
  and, at a vertex of no face, the protocol's value 2 pi (MeshLib has none there).
* ``cotan_laplacian``: off-diagonal ``-cotan(ue)`` with ``cotan(ue) = leftCotan(e) +
  leftCotan(e.sym())`` (``MRMeshMath.h`` l. 312-316), a missing face's cotangent 0
  (``MRMeshMath.cpp`` l. 661-666), each ``nom / den`` of a dot and a cross product
  (``MRTriMath.h`` l. 453-462); the diagonal the row sum (positive semidefinite).  An edge
  weighs cot a + cot b: the vocabulary's ``weights=full``.
* ``intrinsic_delaunay_triangulation`` / ``_laplacian``: ``EdgeLengthMesh.fromMesh`` and
  ``makeDeloneEdgeFlips(EdgeLengthMesh, IntrinsicDeloneSettings(), numIters)`` (Bobenko and
  Springborn's flip algorithm, ``MRMeshDelone.cpp`` l. 249-293), with ``numIters`` large
  enough to finish (the default 1 considers every edge once and may stop early); the
  Laplacian from ``EdgeLengthMesh.cotan(ue)`` (lengths, ``MRTriMath.h`` l. 471-481),
  ``weights=full``.  ``canFlipEdge`` (``MRMeshDelone.cpp`` l. 78-119) refuses a flip that
  makes a loop edge (l. 91) or a second edge between two vertices (l. 116-117): see the
  findings.
* ``is_locally_delaunay``: ``EdgeLengthMesh.isDelone(ue)`` = ``cotan(ue) >= 0``
  (``MREdgeLengthMesh.h`` l. 31) per interior edge.  Not covered by the vocabulary
  (mapped here by hand): on a boundary edge ``isDelone`` tests the one cotangent, and the
  flip algorithm never flips it (``canFlipEdge``: ``isInnerEdge``); the protocol says
  True there, which the adapter answers.
* ``solve_dirichlet``: ``Laplacian(mesh).init(free, EdgeWeights.Cotan, VertexMass.Unit,
  RememberShape.No)``, every boundary vertex ``fixVertex(v, smooth=False)`` (so no
  equation of a fixed vertex is added: the system is square), ``applyToScalar``.  Each
  row is normalised by its weights' sum (no effect on the solution), but each weight is
  ``std::clamp(cotan(e), -1.0f, 10.0f)`` (``MRLaplacian.cpp`` l. 99): a documented
  deviation, F-meshlib-1.
* ``corner_angles``: ``mrmeshpy.angle(d0, d1)`` of MeshLib's float edge vectors, the
  routine ``sumAngles`` sums (``MRMeshMath.cpp`` l. 566-569).
* ``edge_mean_curvature``: 1/2 ``dihedralAngle(ue)`` ``edgeLength(ue)`` per interior edge
  (``MRMeshMath.cpp`` l. 614-620: ``atan2(sin, cos)`` of the unit normals, "positive if
  the faces form convex surface", ``MRMeshMath.h`` l. 281-285): the notes' sign.
  (``discreteMeanCurvature(ue)`` divides the same product by a third of the two faces'
  area: pointwise, not in the vocabulary; not used.)
* ``area``: ``Mesh.area()``, 1/2 the double sum of float ``dblArea(f)`` (the length of a
  float cross product).
* ``euler_characteristic``: ``numValidVerts() - computeNotLoneUndirectedEdges() +
  numValidFaces()`` of MeshLib's topology, plus the input's unused vertices (the protocol
  counts a vertex of no face as a point; MeshLib's topology does not hold it).
* ``boundary_loops``: ``findHoleRepresentiveEdges()`` and ``trackRightBoundaryLoop`` per
  hole, each loop as the origins of its edges.

MeshLib has no orientability test, genus, mass matrix or area gradient: those methods are
absent (not applicable).

>>> import numpy as np
>>> V = np.array([[0., 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
>>> F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
>>> MeshLib().euler_characteristic(V, F), len(MeshLib().boundary_loops(V, F[1:]))
(2, 1)
"""

from __future__ import annotations

import numpy as np
import scipy.sparse

from meshlib import mrmeshnumpy as mn
from meshlib import mrmeshpy as mm

from ..protocol.methods import ISOLATED_VERTEX, OutsideDomain

from ..protocol.arrays import checked_arrays

#: this adapter as ``ddg-oracle check --impl meshlib`` finds it (read without importing the
#: module: ddg_oracle.application.implementations): the object, the library it needs, the pip extra
#: that installs it, its place in reports
ADAPTER = {"name": "meshlib", "object": "MeshLib", "library": "meshlib", "extra": "meshlib",
           "rank": 13}

#: ``makeDeloneEdgeFlips``' ``numIters``: a bound on the passes over the flip candidates,
#: far above what a mesh of the checks needs (the loop ends at the first pass without a
#: flip, ``MRMeshDelone.cpp`` l. 287-288)
FLIP_PASSES = 1 << 20


class _Built:
    """MeshLib's mesh of (V, F), checked to hold the input's surface."""

    def __init__(self, V, F):
        V, F = checked_arrays(V, F)
        if len(V) >= 2 ** 31:
            raise ValueError("MeshLib takes 32-bit vertex ids")
        self.V, self.F, self.n = V, F, len(V)
        self.mesh = mn.meshFromFacesVerts(F, V, mm.MeshBuilder.BuildSettings(), False)
        t = self.topology = self.mesh.topology
        self.used = np.unique(F)
        if t.numValidFaces() != len(F):
            raise OutsideDomain(
                f"MeshLib's MeshBuilder kept {t.numValidFaces()} of the {len(F)} faces (it "
                "skips a face with a repeated vertex or one making a non-manifold vertex, "
                "MRMeshBuilder.cpp l. 131, 174)")
        keys = np.unique(np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]),
                                 axis=1), axis=0)
        if t.computeNotLoneUndirectedEdges() != len(keys):
            raise OutsideDomain(
                f"MeshLib's mesh has {t.computeNotLoneUndirectedEdges()} edges where F has "
                f"{len(keys)}: faces not consistently oriented, or an edge of more than two "
                "faces, are cut apart (MRMeshBuilder.h l. 27: 'Vertices of triangles should "
                "have consistent bypass direction')")
        if t.numValidVerts() != len(self.used):
            raise OutsideDomain(f"MeshLib's mesh has {t.numValidVerts()} vertices, F uses "
                                f"{len(self.used)}")
        G = np.asarray(mn.getNumpyFaces(t), dtype=np.int64)
        same = (G == F) | (G == np.roll(F, 1, axis=1)) | (G == np.roll(F, 2, axis=1))
        if G.shape != F.shape or not all(
                any((G[f] == np.roll(F[f], r)).all() for r in range(3)) for f in
                np.flatnonzero(~same.all(axis=1))):
            raise OutsideDomain("MeshLib's faces are not the input's")

    def edges(self):
        """(undirected edge id, org, dest) of every edge of the topology."""
        t = self.topology
        for u in range(t.undirectedEdgeSize()):
            e = mm.EdgeId(mm.UndirectedEdgeId(u))
            if t.isLoneEdge(e):
                continue
            yield u, e, t.org(e).get(), t.dest(e).get()


def _matrix(n, entries) -> scipy.sparse.csr_matrix:
    """The Laplacian of edge weights [(i, j, w)]: -w off the diagonal, the row sums on it;
    loop edges (i == j) add nothing (f(i) - f(i) = 0)."""
    rows, cols, vals = [], [], []
    for i, j, w in entries:
        if i == j:
            continue
        rows += [i, j, i, j]
        cols += [j, i, i, j]
        vals += [-w, -w, w, w]
    return scipy.sparse.csr_matrix((np.asarray(vals, dtype=np.float64), (rows, cols)),
                                   shape=(n, n))


def _flipped(b: _Built):
    """MeshLib's intrinsic Delaunay ``EdgeLengthMesh`` of the input's metric."""
    elm = mm.EdgeLengthMesh.fromMesh(b.mesh)
    mm.makeDeloneEdgeFlips(elm, mm.IntrinsicDeloneSettings(), FLIP_PASSES)
    return elm


class MeshLib:
    """MeshLib as an implementation of the protocol (``protocol/methods.py``)."""

    name = "meshlib"
    machine_epsilon = 2.0 ** -23          # float coordinates and arithmetic (module doc)
    conventions = "meshlib"            # weights full, boundary_defect two_pi

    def __repr__(self) -> str:
        return "MeshLib()"

    # --- chapter 1: topology ------------------------------------------------------------

    def euler_characteristic(self, V, F) -> int:
        """#V - #E + #F of MeshLib's topology, plus the input's unused vertices."""
        b = _Built(V, F)
        t = b.topology
        chi = t.numValidVerts() - t.computeNotLoneUndirectedEdges() + t.numValidFaces()
        return int(chi + b.n - len(b.used))

    def boundary_loops(self, V, F) -> list[list[int]]:
        """``trackRightBoundaryLoop`` from each of ``findHoleRepresentiveEdges()``."""
        b = _Built(V, F)
        t = b.topology
        return [[int(t.org(e).get()) for e in mm.trackRightBoundaryLoop(t, e0)]
                for e0 in t.findHoleRepresentiveEdges()]

    # --- chapter 2: curvature -----------------------------------------------------------

    def corner_angles(self, V, F) -> np.ndarray:
        """``mrmeshpy.angle`` of the two float edge vectors leaving each corner."""
        b = _Built(V, F)
        P = b.mesh.points
        out = np.empty(b.F.shape, dtype=np.float64)
        for f, face in enumerate(b.F.tolist()):
            p = [P.vec_[i] for i in face]
            for c in range(3):
                out[f, c] = mm.angle(p[(c + 1) % 3] - p[c], p[(c + 2) % 3] - p[c])
        return out

    def angle_defects(self, V, F) -> np.ndarray:
        """``getNumpyGaussianCurvature(mesh)`` (2 pi - angle sum everywhere: declared), on
        every row of V; 2 pi at a vertex of no face (MeshLib: 0 or no row)."""
        b = _Built(V, F)
        K = np.asarray(mn.getNumpyGaussianCurvature(b.mesh), dtype=np.float64)
        out = np.full(b.n, ISOLATED_VERTEX["angle_defects"])
        out[b.used] = K[b.used]
        return out

    def edge_mean_curvature(self, V, F) -> dict:
        """1/2 ``dihedralAngle(ue)`` ``edgeLength(ue)`` over the interior edges."""
        b = _Built(V, F)
        t, P = b.topology, b.mesh.points
        out = {}
        for u, e, i, j in b.edges():
            if t.isBdEdge(e):
                continue
            ue = mm.UndirectedEdgeId(u)
            theta = mm.dihedralAngle(t, P, ue)
            out[(min(i, j), max(i, j))] = 0.5 * theta * mm.edgeLength(t, P, ue)
        return out

    def area(self, V, F) -> float:
        """``Mesh.area()``."""
        return float(_Built(V, F).mesh.area())

    # --- chapter 3: Laplacian -----------------------------------------------------------

    def cotan_laplacian(self, V, F) -> scipy.sparse.csr_matrix:
        """Weights ``cotan(ue)`` = cot a + cot b (declared ``weights=full``)."""
        b = _Built(V, F)
        t, P = b.topology, b.mesh.points
        return _matrix(b.n, ((i, j, mm.cotan(t, P, mm.UndirectedEdgeId(u)))
                             for u, _, i, j in b.edges()))

    def solve_dirichlet(self, V, F, boundary, values) -> np.ndarray:
        """``Laplacian.applyToScalar`` with the boundary vertices fixed sharp and the others
        free (clamped cotangent weights, F-meshlib-1)."""
        b = _Built(V, F)
        bd = np.asarray(boundary, dtype=np.int64).reshape(-1)
        vals = np.asarray(values, dtype=np.float64).reshape(-1)
        free = np.zeros(b.n, dtype=bool)
        free[b.used] = True
        free[bd] = False
        u = np.zeros(b.n)
        u[bd] = vals
        if not free.any():
            return u
        lap = mm.Laplacian(b.mesh)
        lap.init(mn.vertBitSetFromBools(free), mm.EdgeWeights.Cotan, mm.VertexMass.Unit,
                 mm.RememberShape.No)
        for v in bd.tolist():
            lap.fixVertex(mm.VertId(int(v)), False)
        field = mm.VertScalars(b.n)
        for v, x in zip(bd.tolist(), vals.tolist()):
            field.vec_[v] = x
        lap.applyToScalar(field)
        out = np.asarray([field.vec_[i] for i in range(b.n)], dtype=np.float64)
        out[bd] = vals               # MeshLib keeps fixed values; float32 rounding undone
        return out

    # --- chapter 4: intrinsic Delaunay --------------------------------------------------

    def is_locally_delaunay(self, V, F) -> np.ndarray:
        """``EdgeLengthMesh.isDelone(ue)`` per interior edge; True at the boundary."""
        b = _Built(V, F)
        t = b.topology
        elm = mm.EdgeLengthMesh.fromMesh(b.mesh)
        ok = {}
        for u, e, i, j in b.edges():
            ok[(min(i, j), max(i, j))] = t.isBdEdge(e) or elm.isDelone(mm.UndirectedEdgeId(u))
        out = np.empty(b.F.shape, dtype=bool)
        for f, (x, y, z) in enumerate(b.F.tolist()):
            for c, (i, j) in enumerate(((y, z), (z, x), (x, y))):
                out[f, c] = ok[(min(i, j), max(i, j))]
        return out

    def intrinsic_delaunay_triangulation(self, V, F):
        """(faces, squared lengths) of the flipped ``EdgeLengthMesh``: column c the edge
        opposite corner c."""
        b = _Built(V, F)
        elm = _flipped(b)
        t = elm.topology
        L = elm.edgeLengths.vec_
        faces, l2 = [], []
        for f in range(t.faceSize()):
            fid = mm.FaceId(f)
            if not t.hasFace(fid):
                continue
            e0 = t.edgeWithLeft(fid)
            e1 = t.prev(e0.sym())          # getLeftTriEdges (MRMeshTopology.cpp l. 407-412)
            e2 = t.prev(e1.sym())
            ring = (e0, e1, e2)            # a -> b, b -> c, c -> a
            faces.append([t.org(e).get() for e in ring])
            la, lb, lc = (float(L[e.undirected().get()]) for e in ring)   # |ab|, |bc|, |ca|
            l2.append([lb * lb, lc * lc, la * la])
        return np.asarray(faces, dtype=np.int64), np.asarray(l2, dtype=np.float64)

    def intrinsic_delaunay_laplacian(self, V, F) -> scipy.sparse.csr_matrix:
        """Weights ``EdgeLengthMesh.cotan(ue)`` after the flips (declared ``weights=full``)."""
        b = _Built(V, F)
        elm = _flipped(b)
        t = elm.topology
        entries = []
        for u in range(t.undirectedEdgeSize()):
            e = mm.EdgeId(mm.UndirectedEdgeId(u))
            if t.isLoneEdge(e):
                continue
            entries.append((t.org(e).get(), t.dest(e).get(), elm.cotan(mm.UndirectedEdgeId(u))))
        return _matrix(b.n, entries)

