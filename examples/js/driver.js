// The DDG course's Geometry exercise (CMU 15-458/858, ddg-exercises-js; the finished code
// is GeometryCollective/geometry-processing-js), checked by ddg-oracle through the
// executable protocol (docs/protocol.md; the JSON lines are in ddg_protocol.js):
//
//   ddg-oracle check --impl 'exec:node examples/js/driver.js'             # passes
//   ddg-oracle check --impl 'exec:node examples/js/driver.js --planted'   # D3.1 FAILED, 1 triangle
//   ddg-oracle check --impl 'exec:node examples/js/driver.js --geometry=student/core/geometry.js'
//
// A template for grading: --geometry=FILE runs a student's core/geometry.js (a browser
// script defining `class Geometry`) on the course framework of course.js (Mesh, Vector,
// Triplet, SparseMatrix, ... as globals), exactly as the course's viewer and tests run it.
// Each request's V and F become the course's objects: a Mesh built from the polygon soup
// {v: [Vector], f: [flat indices]} and new Geometry(mesh, positions, false) (false: the
// positions as given, as the course's own tests build it).  The answers are the
// exercise's methods, unchanged:
//
//   corner_angles            angle(c) for every corner (c.vertex, c.face -> [face][corner])
//   angle_defects            angleDefect(v): 2 pi - sum inside, pi - sum at the boundary,
//                            the notes' convention (the exercise's doc comment)
//   edge_mean_curvature      1/2 length(e) dihedralAngle(h) per interior edge
//   area                     totalArea()
//   cotan_laplacian          laplaceMatrix(vertexIndex) as it is: positive semidefinite,
//                            weights 1/2 (cot a + cot b) (1/2 cot a at the boundary:
//                            cotan(h) = 0 on a boundary loop), PLUS 1e-8 ON THE DIAGONAL,
//                            the course's shift that makes L positive definite for Cholesky.
//                            The hello declares it ("conventions": "ddg-course", the preset
//                            {"regularization": 1e-8} of docs/conventions.md): ddg-oracle
//                            subtracts it before comparing.  --shift=X declares another one.
//   area_gradient            the mean curvature normal of vertexNormalMeanCurvature(v)
//                            before it is normalised: -sum_h 1/2 (cotan(h) + cotan(h.twin))
//                            vector(h) = (L V)(v)
//   vertex_areas_barycentric the diagonal of massMatrix(vertexIndex)
//   vertex_areas_voronoi     circumcentricDualArea(v), on meshes without an obtuse triangle
//                            only: it is the circumcentric (cotan) area, which the notes'
//                            mixed Voronoi area (Meyer et al.) replaces on obtuse
//                            triangles; elsewhere outside_domain
//   euler_characteristic     mesh.eulerCharacteristic()
//   boundary_loops           the vertices of each of mesh.boundaries
//   genus                    (2 - chi - #boundaries) / 2 on a connected mesh; else
//                            outside_domain
//
// A mesh the halfedge mesh cannot hold (non-manifold, or faces not consistently oriented:
// a Möbius strip) is outside_domain for every method.
//
// Options:
//   --geometry=FILE  the Geometry to check (default: geometry.js beside this file)
//   --planted        the planted bug: one line of laplaceMatrix without its parentheses
//                    (see plant() below); caught by D3.1 on a single triangle
//   --shift=X        the constant the checked laplaceMatrix adds to its diagonal, if not
//                    the course's 1e-8 (declared as {"regularization": X})
"use strict";

const fs = require("fs");
const path = require("path");
const vm = require("vm");

const ddg = require("./ddg_protocol.js");
const course = require("./course.js");

const METHODS = ["corner_angles", "angle_defects", "edge_mean_curvature", "area",
                 "cotan_laplacian", "area_gradient", "vertex_areas_barycentric",
                 "vertex_areas_voronoi", "euler_characteristic", "boundary_loops", "genus"];

const COURSE_SHIFT = 1e-8;

// --- the planted bug ---------------------------------------------------------------------

/**
 * The Geometry with one realistic student mistake: laplaceMatrix as in geometry.js but for
 * one line, whose parentheses are missing, so the weight is cot a + 1/2 cot b instead of
 * 1/2 (cot a + cot b).  At a boundary edge the matrix is then not even symmetric (the
 * interior halfedge's end gets cot a, the other 1/2 cot a): one triangle shows it.
 */
function plant(Geometry, shift) {
    return class extends Geometry {
        laplaceMatrix(vertexIndex) {
            const n = this.mesh.vertices.length;
            const T = new course.Triplet(n, n);
            for (const v of this.mesh.vertices) {
                const i = vertexIndex[v];
                let diagonal = shift;
                for (const h of v.adjacentHalfedges()) {
                    const w = this.cotan(h) + this.cotan(h.twin) / 2;   // PLANTED: (... + ...) / 2
                    T.addEntry(-w, i, vertexIndex[h.twin.vertex]);
                    diagonal += w;
                }
                T.addEntry(diagonal, i, i);
            }
            return course.SparseMatrix.fromTriplet(T);
        }
    };
}

// --- command line ----------------------------------------------------------------------

function options(argv) {
    const o = {geometry: path.join(__dirname, "geometry.js"), planted: false, shift: null};
    for (const arg of argv) {
        const at = arg.indexOf("=");
        const [key, value] = at < 0 ? [arg, null] : [arg.slice(0, at), arg.slice(at + 1)];
        if (key === "--geometry" && value) {
            o.geometry = path.resolve(value);
        } else if (arg === "--planted") {
            o.planted = true;
        } else if (key === "--shift" && value !== null && Number(value) > 0 && Number(value) < 1) {
            o.shift = Number(value);
        } else {
            process.stderr.write(`unknown argument ${arg}; options: --geometry=FILE, --planted, ` +
                                 "--shift=X\n");
            process.exit(2);
        }
    }
    return o;
}

/** The handshake's conventions, in ddg-oracle's vocabulary (docs/conventions.md): the
 *  course's diagonal shift, the preset "ddg-course" = {"regularization": 1e-8}.  Nothing
 *  else differs from the notes (see the table at the top). */
function conventions(o) {
    return o.shift === null ? "ddg-course" : {regularization: o.shift};
}

/**
 * The Geometry class of a course-style script (top-level `class Geometry`, the
 * framework's classes as globals), run in a context holding course.js's framework.  Also
 * takes a CommonJS file (module.exports = {Geometry}) or an ES module's text with its
 * import and export lines dropped.
 */
function loadGeometry(file) {
    const source = fs.readFileSync(file, "utf8")
        .replace(/^\s*import\s[^\n]*$/gm, "")
        .replace(/^\s*export\s+default\s+[\w$]+\s*;?\s*$/gm, "")
        .replace(/^\s*export\s+\{[^}]*\}\s*;?\s*$/gm, "")
        .replace(/^(\s*)export\s+(class|function|const|let)\b/gm, "$1$2");
    const module = {exports: {}};
    const context = vm.createContext({...course, console, module, exports: module.exports,
                                     require: require("module").createRequire(file)});
    vm.runInContext(source, context, {filename: file});
    const G = vm.runInContext("typeof Geometry === 'undefined' ? undefined : Geometry", context) ||
        module.exports.Geometry || (typeof module.exports === "function" ? module.exports : undefined);
    if (typeof G !== "function") throw new Error(`${file} defines no class Geometry`);
    return G;
}

// --- the protocol methods on the course's objects --------------------------------------

/** The course's objects for a request: its mesh and geometry (or outside_domain). */
function build(Geometry, V, F) {
    const positions = V.map(([x, y, z]) => new course.Vector(x, y, z));
    const mesh = new course.Mesh();
    if (!mesh.build({v: positions, f: F.flat()})) {
        throw new ddg.OutsideDomain("not a manifold triangle mesh with consistently oriented " +
                                    "faces: the course's halfedge mesh cannot hold it");
    }
    return {mesh, geometry: new Geometry(mesh, positions, false)};
}

function obtuse(V, F) {
    const d = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    return F.some((f) => [0, 1, 2].some((c) => {
        const p = V[f[c]];
        return dot(d(V[f[(c + 1) % 3]], p), d(V[f[(c + 2) % 3]], p)) < 0;
    }));
}

function components(mesh) {
    const seen = new Set();
    let count = 0;
    for (const start of mesh.vertices) {
        if (seen.has(start)) continue;
        count += 1;
        const stack = [start];
        seen.add(start);
        while (stack.length) {
            for (const u of stack.pop().adjacentVertices()) {
                if (!seen.has(u)) { seen.add(u); stack.push(u); }
            }
        }
    }
    return count;
}

function diagonalOf(matrix, n, what) {
    const d = new Array(n).fill(0);
    for (const [i, j, x] of matrix.triplets()) {
        if (i === j) d[i] += x;
        else if (x !== 0) throw new Error(`${what} is not diagonal: entry (${i}, ${j}) = ${x}`);
    }
    return d;
}

function handler(Geometry) {
    return (method, request) => {
        const {V, F} = request;
        const {mesh, geometry} = build(Geometry, V, F);
        const n = V.length;
        switch (method) {
        case "corner_angles": {
            const out = F.map(() => [0, 0, 0]);
            for (const c of mesh.corners) {
                const t = c.face.index;
                out[t][F[t].indexOf(c.vertex.index)] = geometry.angle(c);
            }
            return out;
        }
        case "angle_defects":
            return mesh.vertices.map((v) => geometry.angleDefect(v));
        case "edge_mean_curvature":
            return mesh.edges.filter((e) => !e.onBoundary()).map((e) => {
                const h = e.halfedge;
                return [h.vertex.index, h.twin.vertex.index,
                        geometry.length(e) * geometry.dihedralAngle(h) / 2];
            });
        case "area":
            return geometry.totalArea();
        case "cotan_laplacian": {
            // the course's matrix as it is, its shift included (declared in the hello)
            const L = geometry.laplaceMatrix(course.indexElements(mesh.vertices));
            const T = new ddg.Triplets(n);
            for (const [i, j, x] of L.triplets()) T.add(i, j, x);
            return T;
        }
        case "area_gradient":
            // vertexNormalMeanCurvature(v) before its normalize()
            return mesh.vertices.map((v) => {
                const g = new course.Vector();
                for (const h of v.adjacentHalfedges()) {
                    g.decrementBy(geometry.vector(h).times((geometry.cotan(h) +
                                                            geometry.cotan(h.twin)) / 2));
                }
                return [g.x, g.y, g.z];
            });
        case "vertex_areas_barycentric":
            return diagonalOf(geometry.massMatrix(course.indexElements(mesh.vertices)), n,
                              "massMatrix");
        case "vertex_areas_voronoi":
            if (obtuse(V, F)) {
                throw new ddg.OutsideDomain("an obtuse triangle: the course's circumcentric dual " +
                                            "area is not the mixed Voronoi area there");
            }
            return mesh.vertices.map((v) => geometry.circumcentricDualArea(v));
        case "euler_characteristic":
            return mesh.eulerCharacteristic();
        case "boundary_loops":
            return mesh.boundaries.map((b) => [...b.adjacentVertices()].map((v) => v.index));
        case "genus":
            if (components(mesh) !== 1) throw new ddg.OutsideDomain("not connected");
            return (2 - mesh.eulerCharacteristic() - mesh.boundaries.length) / 2;
        default:
            throw new Error(`${method}: not implemented`);
        }
    };
}

function main() {
    const o = options(process.argv.slice(2));
    let Geometry = loadGeometry(o.geometry);
    if (o.planted) Geometry = plant(Geometry, o.shift === null ? COURSE_SHIFT : o.shift);
    const own = o.geometry === path.join(__dirname, "geometry.js");
    const name = "ddg-course-js" +
        (own ? "" : `(${path.basename(path.dirname(o.geometry))}/${path.basename(o.geometry)})`) +
        (o.planted ? "-planted" : "");
    ddg.serve({name, methods: METHODS, conventions: conventions(o)}, handler(Geometry));
}

main();
