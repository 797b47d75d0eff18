// The framework a DDG course's Geometry exercise runs on, written for this driver: a
// halfedge Mesh built from a polygon soup, its elements, a 3-vector and a small sparse
// matrix.  Self-contained (Node.js's standard library only), no course code copied.
//
// The names and conventions are those of the course framework (CMU 15-458/858, Keenan
// Crane: ddg-exercises-js, on GeometryCollective/geometry-processing-js), so that a
// student's core/geometry.js runs on it unchanged (driver.js --geometry=FILE):
//   core/mesh.js      Mesh: vertices, edges, faces, corners, halfedges, boundaries;
//                     build({v: [Vector], f: [i0, j0, k0, i1, ...]}) -> true/false (f is a
//                     flat index list); eulerCharacteristic() = |V| - |E| + |F|;
//                     indexElements(list) -> {element: index}
//   core/halfedge.js  Halfedge: vertex (its tail), edge, face, corner (the one opposite),
//                     next, prev, twin, onBoundary (true on the halfedges of boundary loops)
//   core/corner.js    Corner: halfedge (the one opposite it); vertex = halfedge.prev.vertex,
//                     face, next, prev
//   core/vertex.js    Vertex: halfedge (outgoing), degree(), isIsolated(), onBoundary(),
//                     adjacentVertices/Edges/Faces/Halfedges/Corners() (iterables;
//                     halfedges outgoing; faces and corners skip the boundary loops)
//   core/edge.js, core/face.js   Edge: halfedge, onBoundary(); Face: halfedge,
//                     isBoundaryLoop(), adjacent*(ccw = true)
//   every element: index, and toString() = its index, so elements key plain objects
//   ({} maps such as Geometry.positions[v] and vertexIndex[v])
//   linear-algebra/vector.js         Vector(x, y, z) and its methods
//   linear-algebra/sparse-matrix.js  Triplet(m, n).addEntry(x, i, j) (A(i, j) += x),
//                     SparseMatrix.fromTriplet / identity / diag, ...
//
// Where this Mesh differs from the course's (mesh.build there returns false on isolated
// vertices and isolated faces; here they are kept: an isolated vertex has no halfedge and
// its iterators are empty, and a lone triangle is a disk), build() still returns false on
// what a halfedge mesh cannot hold: a non-manifold edge, a non-manifold vertex (two fans),
// faces oriented inconsistently (a Möbius strip, reversed faces), a face repeating a vertex
// or an index out of range.
"use strict";

// --- linear-algebra/vector.js ----------------------------------------------------------

class Vector {
    constructor(x = 0, y = 0, z = 0) {
        this.x = x;
        this.y = y;
        this.z = z;
    }

    norm() { return Math.sqrt(this.norm2()); }
    norm2() { return this.dot(this); }
    normalize() { this.divideBy(this.norm()); }
    unit() { return this.over(this.norm()); }
    isValid() { return [this.x, this.y, this.z].every(Number.isFinite); }
    incrementBy(v) { this.x += v.x; this.y += v.y; this.z += v.z; }
    decrementBy(v) { this.x -= v.x; this.y -= v.y; this.z -= v.z; }
    scaleBy(s) { this.x *= s; this.y *= s; this.z *= s; }
    divideBy(s) { this.x /= s; this.y /= s; this.z /= s; }
    plus(v) { return new Vector(this.x + v.x, this.y + v.y, this.z + v.z); }
    minus(v) { return new Vector(this.x - v.x, this.y - v.y, this.z - v.z); }
    times(s) { return new Vector(this.x * s, this.y * s, this.z * s); }
    over(s) { return new Vector(this.x / s, this.y / s, this.z / s); }
    negated() { return new Vector(-this.x, -this.y, -this.z); }
    dot(v) { return this.x * v.x + this.y * v.y + this.z * v.z; }
    cross(v) {
        return new Vector(this.y * v.z - this.z * v.y,
                          this.z * v.x - this.x * v.z,
                          this.x * v.y - this.y * v.x);
    }
}

// --- linear-algebra: a small sparse matrix in the course's interface --------------------

class DenseMatrix {
    constructor(m, n, data = new Float64Array(m * n)) {
        this.m = m;
        this.n = n;
        this.data = data;
    }

    static zeros(m, n = 1) { return new DenseMatrix(m, n); }
    static ones(m, n = 1) { return new DenseMatrix(m, n, new Float64Array(m * n).fill(1)); }
    nRows() { return this.m; }
    nCols() { return this.n; }
    get(i, j = 0) { return this.data[i * this.n + j]; }
    set(x, i, j = 0) { this.data[i * this.n + j] = x; }
}

/** Entries of a sparse matrix under construction; addEntry(x, i, j) adds x to A(i, j). */
class Triplet {
    constructor(m, n) {
        this.m = m;
        this.n = n;
        this.entries = [];
    }

    addEntry(x, i, j) {
        if (!(i >= 0 && i < this.m && j >= 0 && j < this.n)) {
            throw new RangeError(`Triplet(${this.m}, ${this.n}).addEntry: (${i}, ${j}) is outside`);
        }
        this.entries.push([i, j, x]);
    }
}

/** An m x n matrix holding its nonzero entries: a Map from row*n + col to the value
 *  (entries added to the same place are summed, in the order they were added). */
class SparseMatrix {
    constructor(m, n, cells = new Map()) {
        this.m = m;
        this.n = n;
        this.cells = cells;
    }

    static fromTriplet(T) {
        const A = new SparseMatrix(T.m, T.n);
        for (const [i, j, x] of T.entries) A.cells.set(i * T.n + j, (A.cells.get(i * T.n + j) || 0) + x);
        return A;
    }

    static identity(m, n) {
        const A = new SparseMatrix(m, n);
        for (let i = 0; i < Math.min(m, n); i++) A.cells.set(i * n + i, 1);
        return A;
    }

    static diag(d) {
        const A = new SparseMatrix(d.nRows(), d.nRows());
        for (let i = 0; i < d.nRows(); i++) A.cells.set(i * A.n + i, d.get(i, 0));
        return A;
    }

    nRows() { return this.m; }
    nCols() { return this.n; }
    nnz() { return this.cells.size; }
    get(i, j) { return this.cells.get(i * this.n + j) || 0; }

    /** [[row, col, value], ...] of the stored entries, by row then column (not in the
     *  course's interface: how the driver reads a matrix back). */
    triplets() {
        return [...this.cells].sort((a, b) => a[0] - b[0])
            .map(([k, x]) => [Math.floor(k / this.n), k % this.n, x]);
    }

    transpose() {
        const A = new SparseMatrix(this.n, this.m);
        for (const [i, j, x] of this.triplets()) A.cells.set(j * this.m + i, x);
        return A;
    }

    timesReal(s) { return new SparseMatrix(this.m, this.n, new Map([...this.cells].map(([k, x]) => [k, x * s]))); }
    scaleBy(s) { for (const [k, x] of this.cells) this.cells.set(k, x * s); }
    plus(B) { const A = this.timesReal(1); A.incrementBy(B); return A; }
    minus(B) { const A = this.timesReal(1); A.decrementBy(B); return A; }
    incrementBy(B) { for (const [k, x] of B.cells) this.cells.set(k, (this.cells.get(k) || 0) + x); }
    decrementBy(B) { for (const [k, x] of B.cells) this.cells.set(k, (this.cells.get(k) || 0) - x); }
    frobeniusNorm() { return Math.hypot(...this.cells.values()); }

    timesDense(X) {
        const Y = DenseMatrix.zeros(this.m, X.nCols());
        for (const [i, j, x] of this.triplets()) {
            for (let c = 0; c < X.nCols(); c++) Y.set(Y.get(i, c) + x * X.get(j, c), i, c);
        }
        return Y;
    }

    toDense() {
        const D = DenseMatrix.zeros(this.m, this.n);
        for (const [i, j, x] of this.triplets()) D.set(x, i, j);
        return D;
    }
}

// --- core: the halfedge mesh -------------------------------------------------------------

/** Walk around the vertex at the tail of h: h, h.twin.next, ... back to h (outgoing). */
function* outgoing(h) {
    if (h === undefined) return;                  // an isolated vertex
    let he = h;
    do {
        yield he;
        he = he.twin.next;
    } while (he !== h);
}

/** Walk around a face or boundary loop from h: next (ccw) or prev. */
function* around(h, ccw) {
    let he = h;
    do {
        yield he;
        he = ccw ? he.next : he.prev;
    } while (he !== h);
}

class Vertex {
    constructor() {
        this.halfedge = undefined;                // one outgoing halfedge
        this.index = -1;
    }

    degree() { let k = 0; for (const _ of this.adjacentEdges()) k++; return k; }
    isIsolated() { return this.halfedge === undefined; }
    onBoundary() { for (const h of outgoing(this.halfedge)) if (h.onBoundary) return true; return false; }
    * adjacentVertices() { for (const h of outgoing(this.halfedge)) yield h.twin.vertex; }
    * adjacentEdges() { for (const h of outgoing(this.halfedge)) yield h.edge; }
    * adjacentFaces() { for (const h of outgoing(this.halfedge)) if (!h.onBoundary) yield h.face; }
    * adjacentHalfedges() { yield* outgoing(this.halfedge); }
    // the corner at this vertex in the face of h is opposite h.next
    * adjacentCorners() { for (const h of outgoing(this.halfedge)) if (!h.onBoundary) yield h.next.corner; }
    toString() { return String(this.index); }
}

class Edge {
    constructor() {
        this.halfedge = undefined;
        this.index = -1;
    }

    onBoundary() { return this.halfedge.onBoundary || this.halfedge.twin.onBoundary; }
    toString() { return String(this.index); }
}

class Face {
    constructor() {
        this.halfedge = undefined;
        this.index = -1;                          // among faces, or among boundary loops
    }

    isBoundaryLoop() { return this.halfedge.onBoundary; }
    * adjacentVertices(ccw = true) { for (const h of around(this.halfedge, ccw)) yield h.vertex; }
    * adjacentEdges(ccw = true) { for (const h of around(this.halfedge, ccw)) yield h.edge; }
    * adjacentFaces(ccw = true) { for (const h of around(this.halfedge, ccw)) if (!h.twin.onBoundary) yield h.twin.face; }
    * adjacentHalfedges(ccw = true) { yield* around(this.halfedge, ccw); }
    * adjacentCorners(ccw = true) { for (const h of around(this.halfedge, ccw)) yield h.corner; }
    toString() { return String(this.index); }
}

class Halfedge {
    constructor() {
        this.vertex = undefined;                  // its tail
        this.edge = undefined;
        this.face = undefined;
        this.corner = undefined;                  // the corner opposite it (not on boundary loops)
        this.next = undefined;
        this.prev = undefined;
        this.twin = undefined;
        this.onBoundary = undefined;
        this.index = -1;
    }

    toString() { return String(this.index); }
}

class Corner {
    constructor() {
        this.halfedge = undefined;                // the halfedge opposite this corner
        this.index = -1;
    }

    get vertex() { return this.halfedge.prev.vertex; }
    get face() { return this.halfedge.face; }
    get next() { return this.halfedge.next.corner; }
    get prev() { return this.halfedge.prev.corner; }
    toString() { return String(this.index); }
}

class Mesh {
    constructor() {
        this.vertices = [];
        this.edges = [];
        this.faces = [];
        this.corners = [];
        this.halfedges = [];
        this.boundaries = [];
        this.generators = [];
    }

    eulerCharacteristic() {
        return this.vertices.length - this.edges.length + this.faces.length;
    }

    /**
     * Build from a polygon soup {v: positions, f: flat list of vertex indices, three per
     * triangle}.  Face t's halfedges are 3t, 3t+1, 3t+2 (from its 1st, 2nd, 3rd vertex),
     * its corners likewise (corner 3t+J is opposite halfedge 3t+J); the halfedges of the
     * boundary loops come after them.  Returns false (and leaves the mesh empty) where a
     * halfedge mesh cannot represent the soup (see the top of this file).
     */
    build(polygonSoup) {
        const nv = polygonSoup.v.length, f = polygonSoup.f;
        const mesh = new Mesh();
        if (f.length % 3 !== 0) return false;
        mesh.vertices = Array.from({length: nv}, () => new Vertex());
        const byDirected = new Map();             // "i,j" -> the halfedge from i to j
        for (let t = 0; t < f.length / 3; t++) {
            const ids = [f[3 * t], f[3 * t + 1], f[3 * t + 2]];
            if (!ids.every((i) => Number.isInteger(i) && i >= 0 && i < nv)) return false;
            if (ids[0] === ids[1] || ids[1] === ids[2] || ids[2] === ids[0]) return false;
            const face = new Face();
            mesh.faces.push(face);
            const hs = ids.map(() => new Halfedge());
            for (let J = 0; J < 3; J++) {
                const h = hs[J], i = ids[J], j = ids[(J + 1) % 3];
                h.vertex = mesh.vertices[i];
                h.next = hs[(J + 1) % 3];
                h.prev = hs[(J + 2) % 3];
                h.face = face;
                h.onBoundary = false;
                h.vertex.halfedge = h;
                // a third face on an edge, or two faces crossing it the same way
                if (byDirected.has(`${i},${j}`)) return false;
                byDirected.set(`${i},${j}`, h);
                const twin = byDirected.get(`${j},${i}`);
                if (twin !== undefined) {
                    h.twin = twin;
                    twin.twin = h;
                    h.edge = twin.edge;
                } else {
                    h.edge = new Edge();
                    h.edge.halfedge = h;
                    mesh.edges.push(h.edge);
                }
            }
            face.halfedge = hs[0];
            mesh.halfedges.push(...hs);
        }
        // corners: one per interior halfedge, opposite it
        for (const h of mesh.halfedges) {
            const c = new Corner();
            c.halfedge = h;
            h.corner = c;
            mesh.corners.push(c);
        }
        // the boundary: a halfedge h from i to j without a twin gets one, b from j to i, in a
        // boundary loop; b.next is the boundary halfedge leaving i
        const leaving = new Map();                // vertex -> its boundary halfedge
        const border = [];
        for (const h of mesh.halfedges) {
            if (h.twin !== undefined) continue;
            const b = new Halfedge();
            b.vertex = h.next.vertex;
            b.edge = h.edge;
            b.onBoundary = true;
            b.twin = h;
            h.twin = b;
            if (leaving.has(b.vertex)) return false;      // two boundary fans: not manifold
            leaving.set(b.vertex, b);
            border.push(b);
        }
        for (const b of border) {
            b.next = leaving.get(b.twin.vertex);
            b.next.prev = b;
        }
        for (const b of border) {
            if (b.face !== undefined) continue;
            const loop = new Face();
            loop.halfedge = b;
            for (const he of around(b, true)) he.face = loop;
            mesh.boundaries.push(loop);
        }
        mesh.halfedges.push(...border);
        // every halfedge leaving a vertex is met walking around it from one of them
        const out = new Map();
        for (const h of mesh.halfedges) out.set(h.vertex, (out.get(h.vertex) || 0) + 1);
        for (const v of mesh.vertices) {
            let k = 0;
            for (const _ of outgoing(v.halfedge)) k++;
            if (k !== (out.get(v) || 0)) return false;    // a vertex where fans meet
        }
        for (const kind of ["vertices", "edges", "faces", "corners", "halfedges", "boundaries"]) {
            mesh[kind].forEach((x, i) => { x.index = i; });
        }
        Object.assign(this, mesh);
        return true;
    }
}

/** {element: index} for a list of mesh elements (keys are the elements' toString()). */
function indexElements(elementList) {
    const index = {};
    elementList.forEach((element, i) => { index[element] = i; });
    return index;
}

module.exports = {
    Corner, DenseMatrix, Edge, Face, Halfedge, Mesh, SparseMatrix, Triplet, Vector, Vertex,
    indexElements,
};
