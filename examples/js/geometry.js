// A finished "Geometry" exercise of the DDG course (CMU 15-458/858, Keenan Crane), written
// for this driver: what a student's core/geometry.js of ddg-exercises-js computes once its
// TODOs are done.  Written from the notes and the exercise's documented interface, not
// from the course's code.  It is a browser-style script like the student's file (no
// require, no exports): driver.js runs it with the framework of course.js as globals
// (Vector, Triplet, SparseMatrix, ...), and runs a student's file the same way:
//
//   node driver.js --geometry=path/to/ddg-exercises-js/core/geometry.js
//
// The conventions, as the exercise states them in its doc comments
// (cmu-geometry/ddg-exercises-js, core/geometry.js):
//   angle(c)       the angle at corner c, in [0, pi]; c.halfedge is the halfedge opposite c
//   cotan(h)       the cotangent of the angle opposite halfedge h (0 for a halfedge of a
//                  boundary loop: the boundary edges then get 1/2 cot of their one angle)
//   dihedralAngle(h)  the signed angle between the faces of h and of h.twin
//   angleDefect(v) 2 pi - angle sum at an interior vertex, pi - angle sum at a boundary one
//   barycentricDualArea(v), circumcentricDualArea(v)  (the latter from the cotan formula of
//                  the "triangle areas cheat sheet": negative parts on obtuse triangles)
//   laplaceMatrix(vertexIndex)  the cotan Laplacian as a positive semidefinite matrix
//                  "shifting the diagonal elements by a small constant (e.g. 1e-8)"
//   massMatrix(vertexIndex)     diagonal, the barycentric dual areas
//   new Geometry(mesh, positions, normalizePositions = true): normalizePositions centres the
//                  mesh and scales it to unit radius; the course's tests pass false.
"use strict";

class Geometry {
    constructor(mesh, positions, normalizePositions = true) {
        this.mesh = mesh;
        this.positions = {};                      // vertex -> Vector
        mesh.vertices.forEach((v, i) => { this.positions[v] = positions[i]; });
        if (normalizePositions) normalize(this.positions, mesh.vertices);
    }

    /** The vector along h, from its tail to its head. */
    vector(h) {
        return this.positions[h.next.vertex].minus(this.positions[h.vertex]);
    }

    length(e) { return this.vector(e.halfedge).norm(); }

    midpoint(e) {
        const h = e.halfedge;
        return this.positions[h.vertex].plus(this.positions[h.twin.vertex]).over(2);
    }

    meanEdgeLength() {
        let sum = 0;
        for (const e of this.mesh.edges) sum += this.length(e);
        return sum / this.mesh.edges.length;
    }

    area(f) {
        if (f.isBoundaryLoop()) return 0;
        return this.areaVector(f).norm() / 2;
    }

    totalArea() {
        let sum = 0;
        for (const f of this.mesh.faces) sum += this.area(f);
        return sum;
    }

    faceNormal(f) {
        if (f.isBoundaryLoop()) return undefined;
        return this.areaVector(f).unit();
    }

    /**
     * Twice the area times the unit normal of f (counterclockwise: (b - a) x (c - a)),
     * as the cross product of the two edges at the corner opposite f's longest edge (not
     * in the course's interface).  Any corner gives it exactly, but in floats the cross
     * product of two edges loses |u| |v| eps to cancellation, least at that corner: on a
     * needle the two long edges' product can round to zero, and the normal to NaN.
     */
    areaVector(f) {
        let h = f.halfedge;
        for (const g of [f.halfedge.next, f.halfedge.prev]) {
            if (this.vector(g).norm2() > this.vector(h).norm2()) h = g;
        }
        return this.vector(h.prev).cross(this.vector(h.next).negated());
    }

    /**
     * The angle at corner c: between the two edges leaving its vertex, as
     * atan2(|u x v|, u . v), accurate at every angle.  (The acos of the cosine of the
     * unit vectors, clamped to [-1, 1], loses half the digits near 0 and pi; it stays
     * within ddg-oracle's angle bound, C eps (1 + 1/sin alpha), all the same.)
     */
    angle(c) {
        const h = c.halfedge;                     // opposite c: c is at h.prev's tail
        const u = this.vector(h.prev);            // from c's vertex to h's tail
        const v = this.vector(h.next).negated();  // from c's vertex to h's head
        return Math.atan2(u.cross(v).norm(), u.dot(v));
    }

    /** cot of the angle opposite h (at h.prev's tail); 0 on a boundary loop. */
    cotan(h) {
        if (h.onBoundary) return 0;
        const u = this.vector(h.prev);
        const v = this.vector(h.next).negated();
        return u.dot(v) / u.cross(v).norm();
    }

    /** The angle between the normals of h's face and its twin's, positive where the
     *  surface bends away from its normal (convex); 0 at the boundary. */
    dihedralAngle(h) {
        if (h.onBoundary || h.twin.onBoundary) return 0;
        const n1 = this.faceNormal(h.face);
        const n2 = this.faceNormal(h.twin.face);
        const along = this.vector(h).unit();
        return Math.atan2(along.dot(n1.cross(n2)), n1.dot(n2));
    }

    barycentricDualArea(v) {
        let area = 0;
        for (const f of v.adjacentFaces()) area += this.area(f) / 3;
        return area;
    }

    /** The area of v's cell cut by the circumcentres of its triangles: per triangle,
     *  1/8 (|e1|^2 cot(opposite e1) + |e2|^2 cot(opposite e2)) over its two edges e1, e2
     *  at v.  Not the mixed Voronoi area on obtuse triangles (it can be negative there). */
    circumcentricDualArea(v) {
        let area = 0;
        for (const h of v.adjacentHalfedges()) {
            if (h.onBoundary) continue;
            // h leaves v, h.prev enters v: the triangle's two edges at v
            area += (this.vector(h).norm2() * this.cotan(h) +
                     this.vector(h.prev).norm2() * this.cotan(h.prev)) / 8;
        }
        return area;
    }

    angleDefect(v) {
        let sum = 0;
        for (const c of v.adjacentCorners()) sum += this.angle(c);
        return (v.onBoundary() ? Math.PI : 2 * Math.PI) - sum;
    }

    scalarGaussCurvature(v) { return this.angleDefect(v); }

    scalarMeanCurvature(v) {
        let sum = 0;
        for (const h of v.adjacentHalfedges()) sum += this.length(h.edge) * this.dihedralAngle(h) / 2;
        return sum;
    }

    /** The unit mean curvature normal: the area gradient (L V)(v) = -sum_h 1/2 (cot a +
     *  cot b) vector(h) over the halfedges h leaving v, normalised (driver.js answers
     *  area_gradient with the sum before normalising). */
    vertexNormalMeanCurvature(v) {
        const n = new Vector();
        for (const h of v.adjacentHalfedges()) {
            n.decrementBy(this.vector(h).times((this.cotan(h) + this.cotan(h.twin)) / 2));
        }
        return n.unit();
    }

    totalAngleDefect() {
        let sum = 0;
        for (const v of this.mesh.vertices) sum += this.angleDefect(v);
        return sum;
    }

    /** -Delta as a matrix: (L f)(i) = sum_j w_ij (f(i) - f(j)), w_ij = 1/2 (cot a + cot b),
     *  plus 1e-8 on the diagonal (the course's shift, so that a Cholesky factorisation
     *  of L succeeds). */
    laplaceMatrix(vertexIndex) {
        const n = this.mesh.vertices.length;
        const T = new Triplet(n, n);
        for (const v of this.mesh.vertices) {
            const i = vertexIndex[v];
            let diagonal = 1e-8;
            for (const h of v.adjacentHalfedges()) {
                const w = (this.cotan(h) + this.cotan(h.twin)) / 2;
                T.addEntry(-w, i, vertexIndex[h.twin.vertex]);
                diagonal += w;
            }
            T.addEntry(diagonal, i, i);
        }
        return SparseMatrix.fromTriplet(T);
    }

    massMatrix(vertexIndex) {
        const n = this.mesh.vertices.length;
        const T = new Triplet(n, n);
        for (const v of this.mesh.vertices) T.addEntry(this.barycentricDualArea(v), vertexIndex[v], vertexIndex[v]);
        return SparseMatrix.fromTriplet(T);
    }
}

/** Centre the positions at their mean and (rescale) scale them to unit radius. */
function normalize(positions, vertices, rescale = true) {
    const centre = new Vector();
    for (const v of vertices) centre.incrementBy(positions[v]);
    centre.divideBy(vertices.length);
    let radius = 0;
    for (const v of vertices) {
        positions[v].decrementBy(centre);
        radius = Math.max(radius, positions[v].norm());
    }
    if (rescale) for (const v of vertices) positions[v].divideBy(radius);
}
