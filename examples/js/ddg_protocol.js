// The executable protocol (docs/protocol.md) for JavaScript drivers: one JSON request per
// line on stdin, one JSON answer per line on stdout.  Node.js 18 or later (Debian's nodejs),
// standard library only.
//
//   const ddg = require("./ddg_protocol.js");
//   ddg.serve({name: "my-lib", methods: ["area", "cotan_laplacian"]}, (method, req) => {
//       if (method === "area") return myArea(req.V, req.F);          // a number
//       throw new ddg.OutsideDomain("no value here in the reference's conventions");
//   });
//
// The handler gets the method's name and the request ({V, F} as arrays of numbers; P,
// boundary and values where the method has them) and returns the answer's `value` as a
// plain JavaScript value: a number, an integer, true/false, an array (of numbers or of
// arrays), or a sparse matrix (`sparse(n, triplets)` or a `Triplets` object).  It throws
// OutsideDomain for "no value on this input in the reference's conventions"; anything else
// it throws is answered as a failure (kind "failed", with its message), and the driver goes
// on with the next request.
//
// Numbers: JSON.parse reads the float64 coordinates ddg-oracle writes exactly (correctly
// rounded, like strtod), and numbers are written as JavaScript's shortest round-trip form,
// so float64 values cross the pipe unchanged.  NaN and the infinities, which JSON has no
// words for, are written as Python's json module reads them (NaN, Infinity, -Infinity): a
// wrong value is then reported as a wrong value, not as garbage.
"use strict";

const readline = require("readline");

const PROTOCOL_VERSION = 1;
const FLOAT64_EPSILON = 2.220446049250313e-16;

/** The program has no value on this input in the reference's conventions. */
class OutsideDomain extends Error {
    constructor(message) {
        super(message);
        this.name = "OutsideDomain";
    }
}

/** One number as JSON text (see the note above on NaN and infinities). */
function num(x) {
    if (typeof x !== "number") throw new TypeError(`not a number: ${x}`);
    if (Number.isNaN(x)) return "NaN";
    if (x === Infinity) return "Infinity";
    if (x === -Infinity) return "-Infinity";
    if (Object.is(x, -0)) return "-0.0";
    return String(x);            // the shortest text that reads back as the same float64
}

/** Any answer value as JSON text: numbers by num(), the rest as JSON. */
function encode(value) {
    if (typeof value === "number") return num(value);
    if (typeof value === "boolean" || typeof value === "string" || value === null) {
        return JSON.stringify(value);
    }
    if (value instanceof Triplets) return encode(value.json());
    if (Array.isArray(value) || ArrayBuffer.isView(value)) {
        return "[" + Array.from(value, encode).join(",") + "]";
    }
    if (typeof value === "object") {
        return "{" + Object.entries(value).map(([k, v]) => JSON.stringify(k) + ":" + encode(v))
            .join(",") + "}";
    }
    throw new TypeError(`cannot encode ${typeof value} in an answer`);
}

/** A sparse n x n matrix as the protocol's {"shape", "rows", "cols", "values"} (duplicate
 *  entries are summed by ddg-oracle). */
class Triplets {
    constructor(n) {
        this.n = n;
        this.rows = [];
        this.cols = [];
        this.values = [];
    }

    add(row, col, value) {
        this.rows.push(row);
        this.cols.push(col);
        this.values.push(value);
    }

    /** The protocol's Laplacian sign: (L f)(i) = sum_j w_ij (f(i) - f(j)). */
    addEdgeWeight(i, j, w) {
        this.add(i, j, -w);
        this.add(j, i, -w);
        this.add(i, i, w);
        this.add(j, j, w);
    }

    json() {
        return {shape: [this.n, this.n], rows: this.rows, cols: this.cols, values: this.values};
    }
}

/** The hello answer (docs/protocol.md, "Handshake").  conventions (docs/conventions.md): {}
 *  (the reference's), a preset's name ("ddg-course", "libigl", ...), {key: value} of the
 *  vocabulary ({regularization: 1e-8}, {preset: "ddg-course", ...}), or the older
 *  {follows: {ID: what differs}, counterpart_arguments: [...]}. */
function hello({name, methods, machineEpsilon = FLOAT64_EPSILON, conventions = {}}) {
    if (!Array.isArray(methods) || methods.length === 0) {
        throw new Error("a driver lists at least one protocol method");
    }
    return {name, methods, machine_epsilon: machineEpsilon, conventions};
}

/** The answer line to one request (an object with id and value, or id and error). */
function answer(id, handler, method, request) {
    try {
        return "{\"id\":" + id + ",\"value\":" + encode(handler(method, request)) + "}";
    } catch (e) {
        const kind = e instanceof OutsideDomain || (e && e.name === "OutsideDomain")
            ? "outside_domain" : "failed";
        const message = e && e.message !== undefined ? String(e.message) : String(e);
        return JSON.stringify({id, error: {kind, message}});
    }
}

/**
 * Serve requests from stdin until it closes.  info: {name, methods, machineEpsilon,
 * conventions} for the handshake; handler(method, request) returns the value.
 */
function serve(info, handler) {
    const greeting = JSON.stringify(hello(info));
    const lines = readline.createInterface({input: process.stdin, crlfDelay: Infinity});
    lines.on("line", (line) => {
        if (!line.trim()) return;
        let request;
        try {
            request = JSON.parse(line);
        } catch (e) {
            process.stderr.write(`cannot parse request: ${e.message}\n`);
            process.exit(1);
        }
        if (request.method === "hello") {
            // a later protocol version adds fields and methods: refuse what we do not speak
            if (request.version !== undefined && request.version > PROTOCOL_VERSION) {
                process.stderr.write(`protocol version ${request.version} is not supported\n`);
                process.exit(1);
            }
            process.stdout.write(greeting + "\n");
            return;
        }
        // stdout is a pipe: Node writes it synchronously on Linux, so each answer is out
        // before the next request is read
        process.stdout.write(answer(request.id, handler, request.method, request) + "\n");
    });
}

module.exports = {FLOAT64_EPSILON, OutsideDomain, Triplets, encode, hello, num, serve};
