"""Portable test vectors: the exact reference's answers as JSON, for code in any language.

``ddg-oracle vectors --out DIR`` writes a versioned, deterministic corpus (the model:
Project Wycheproof): per protocol method a file ``METHOD.json`` of cases, each with its
input (the executable protocol's request fields: ``V``, ``F``, and ``boundary`` /
``values`` or ``P``), a ``result`` (``valid``: the answer must match; ``invalid``: the input
is bad, the answer must be an error; ``acceptable``: outside the notes' domain, any answer
passes) and the expected answer: for numbers the exact value
(an expression in integers, ``sqrt``, ``pi`` and ``arccot``), its correctly rounded float64
and the derived tolerances for float64 and float32 implementations (the bounds ``check``
uses: each method's quantity's ``bound``, :mod:`ddg_oracle.properties.registry`).
``DIR/README.md`` says how to use it without Python; ``DIR/schema.json`` is its JSON
Schema (:func:`schema`).

``ddg-oracle verify DIR ANSWERS`` checks an answers file (JSON Lines, one
``{"id", "value"}`` or ``{"id", "error"}`` per case, values encoded as in the executable
protocol) against the corpus: one line per failing case.  :func:`answers` produces such a
file from any implementation (``verify DIR --impl SPEC``).

The cases (:func:`cases`) are named hard ones (exact ties, needles, caps, obtuse fans,
scales 2**-60 and 2**60, boundary, non-orientable, a valence-1 vertex with a loop after
intrinsic flips, cocircular grids, high valence, an isolated vertex, two components),
seeded jittered ones, and invalid inputs.  Every number comes from the exact reference.
"""

from __future__ import annotations

import json
import math
import random
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path

import numpy as np

from ..protocol.methods import (FLOAT64_EPSILON, ISOLATED_VERTEX, METHODS, WHERE, OutsideDomain,
                                at_machine_epsilon)

from .files import read_text
from ..reference.errors import InputError
from ..reference.exact import float_view
from ..reference.combinatorics import next_corner, prev_corner

FORMAT = "ddg-oracle-test-vectors"
#: the corpus format's version: bumped when a field changes meaning (new cases do not)
VERSION = 1
FLOAT32_EPSILON = 2.0 ** -23
EPSILONS = {"64": FLOAT64_EPSILON, "32": FLOAT32_EPSILON}
def kind_of(method: str) -> str:
    """How ``method``'s answers are compared in the corpus (README.md of the corpus,
    "Comparing answers"): the protocol method's kind (:class:`~ddg_oracle.properties.
    protocol.Method`), with underscores."""
    return METHODS[method].kind.replace(" ", "_")


class VectorsError(InputError):
    """A corpus directory or an answers file that cannot be read (exit 2)."""


# --- the cases ---------------------------------------------------------------------------------


@dataclass
class Case:
    """One input: exact (float-representable) positions and faces, or planar points."""

    name: str
    flags: tuple
    comment: str
    V: list = field(default_factory=list)       # floats (n x 3)
    F: list = field(default_factory=list)
    #: "valid"; "invalid": bad input, the answer must be an error (or carry the NaN on);
    #: "acceptable": outside the notes' domain (the reference refuses it), any answer passes
    result: str = "valid"

    @property
    def invalid(self) -> bool:
        return self.result != "valid"

    @property
    def planar(self) -> bool:
        return bool(self.V) and all(p[2] == 0 for p in self.V)


def _floats(surface) -> list:
    return [[float(x) for x in p] + [0.0] * (3 - len(p)) for p in surface.positions]


def _case(name, flags, comment, surface) -> Case:
    from ..properties.strategies import floated
    s = floated(surface)
    return Case(name, tuple(flags), comment, _floats(s), [list(f) for f in s.triangulation.faces])


def _scaled(surface, k: int):
    return surface.with_positions([tuple(x * Fraction(2) ** k for x in p)
                                   for p in surface.positions])


def _placed(t, seed: int):
    """A triangulation without geometry (RP^2, the Klein bottle) at seeded dyadic points
    (not an embedding: a piecewise flat metric needs only non-degenerate faces)."""
    from ..reference.polyhedral import PolyhedralSurface
    rng = random.Random(seed)
    return PolyhedralSurface(t, [tuple(Fraction(rng.randint(-64, 64), 16) for _ in range(3))
                                 for _ in range(t.n_vertices)])


def _square_tie():
    from ..reference.polyhedral import PolyhedralSurface
    return PolyhedralSurface.from_arrays([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)],
                                         [(0, 1, 2), (0, 2, 3)])


def _obtuse_fan():
    """A planar fan of 6 faces around (0, 0) with obtuse angles at the rim (non-Delaunay
    spokes, negative cotan weights)."""
    from ..reference.polyhedral import PolyhedralSurface
    ring = [(4, 0), (1, 1), (-4, 1), (-4, -1), (-1, -1), (4, -1)]
    pts = [(0, 0, 0)] + [(Fraction(x, 2), Fraction(y, 3), 0) for x, y in ring]
    return PolyhedralSurface.from_arrays(pts, [(0, 1 + j, 1 + (j + 1) % 6) for j in range(6)])


def _x42():
    from ..properties.flipped import X42
    from ..reference.polyhedral import PolyhedralSurface
    return PolyhedralSurface.from_arrays(*X42)


def _flipped_grid(m: int, n: int, seed: int):
    """An m x n unit grid in z = 0 with seeded diagonals, points jittered by seeded dyadics
    (not cocircular: a unique Delaunay triangulation, reached by flips)."""
    from ..properties.strategies import grid_faces
    from ..reference.polyhedral import PolyhedralSurface
    rng = random.Random(seed)
    faces = grid_faces(m, n, [rng.random() < 0.5 for _ in range(m * n)])
    pts = [(i + Fraction(rng.randint(-3, 3), 16), j + Fraction(rng.randint(-3, 3), 16), 0)
           for i in range(m + 1) for j in range(n + 1)]      # vertex i (n + 1) + j at (i, j)
    return PolyhedralSurface.from_arrays(pts, faces)


def named_cases() -> list[Case]:
    """The hand-picked hard cases (valid inputs)."""
    from ..properties import variants
    from ..reference import surfaces
    from ..properties.strategies import floated
    from ..reference.polyhedral import PolyhedralSurface
    oct_ = surfaces.octahedron()
    out = [
        _case("tetrahedron", ["closed"], "the reference's tetrahedron (rational)", surfaces.tetrahedron()),
        _case("octahedron", ["closed"], "the octahedron: six vertices of valence 4", oct_),
        _case("cube", ["closed", "tie"], "the triangulated cube: right angles, every face "
              "diagonal's cotan weight exactly 0", surfaces.cube()),
        _case("icosahedron", ["closed"], "the icosahedron, positions rounded to floats",
              surfaces.icosahedron()),
        _case("torus", ["closed", "genus-1"], "a 4 x 3 torus of revolution, floats",
              surfaces.torus(4, 3)),
        _case("double-torus", ["closed", "genus-2"], "a polycube surface of genus 2",
              surfaces.genus_surface(2)),
        _case("octahedron-scale-2^-60", ["closed", "scale"], "the octahedron times 2**-60",
              _scaled(oct_, -60)),
        _case("octahedron-scale-2^60", ["closed", "scale"], "the octahedron times 2**60",
              _scaled(oct_, 60)),
        _case("icosahedron-scale-2^-60", ["closed", "scale"], "the icosahedron (rounded to "
              "floats) times 2**-60", _scaled(floated(surfaces.icosahedron()), -60)),
        _case("needle-2^-30", ["closed", "needle"], "an octahedron face split 1-to-3 at a point "
              "2**-30 from a corner: two needles", variants.with_sliver(oct_, 0, "needle", 30)),
        _case("cap-2^-30", ["closed", "cap"], "an octahedron face split 1-to-3 at a point 2**-30 "
              "from an edge's midpoint: an angle near pi", variants.with_sliver(oct_, 0, "cap", 30)),
        _case("bipyramid-32", ["closed", "high-valence"], "two apexes of valence 32",
              variants.bipyramid(32)),
        _case("fan-64-planar", ["boundary", "high-valence", "planar"], "a planar fan of 64 faces: "
              "angle defect exactly 0 at the centre", variants.fan(64)),
        _case("fan-32-lifted-2^-20", ["boundary", "high-valence", "nearly-flat"], "a fan of 32 "
              "faces, centre lifted by 2**-20", variants.fan(32, 20)),
        _case("x42-tetrahedron", ["closed", "valence-1", "loop"], "X4.2: a flat tetrahedron whose "
              "intrinsic Delaunay triangulation has a vertex of valence 1 inside a loop", _x42()),
        _case("single-triangle", ["boundary", "planar"], "one triangle",
              PolyhedralSurface.from_arrays([(0, 0, 0), (3, 0, 0), (1, 2, 0)], [(0, 1, 2)])),
        _case("square-tie", ["boundary", "planar", "tie", "cocircular"], "a unit square split "
              "by a diagonal: the diagonal's cotan weight is exactly 0", _square_tie()),
        _case("grid-4x4", ["boundary", "planar", "tie", "cocircular"], "a 4 x 4 unit grid: every "
              "cell cocircular, every diagonal an exact tie", surfaces.grid(4, 4)),
        _case("obtuse-fan", ["boundary", "planar", "obtuse"], "a planar fan of obtuse triangles: "
              "negative cotan weights, non-Delaunay spokes, the Voronoi-area obtuse rule",
              _obtuse_fan()),
        _case("flipped-grid-3x3", ["boundary", "planar", "non-delaunay"], "a jittered 3 x 3 grid "
              "with seeded diagonals", _flipped_grid(3, 3, 5)),
        _case("disk-8", ["boundary"], "a disk: an octagon fan", surfaces.disk(8)),
        _case("annulus-8", ["boundary", "two-boundary-loops"], "an annulus", surfaces.annulus(8)),
        _case("mobius-strip", ["boundary", "non-orientable"], "a Moebius strip",
              surfaces.mobius_strip(8)),
        _case("projective-plane", ["closed", "non-orientable"], "the 6-vertex RP^2 at seeded "
              "points (immersed, not embedded)", _placed(surfaces.projective_plane(), 1)),
        _case("klein-bottle", ["closed", "non-orientable"], "a 3 x 3 Klein bottle at seeded points",
              _placed(surfaces.klein_bottle(3, 3), 2)),
        _case("two-components", ["closed", "components"], "a tetrahedron and an octahedron",
              variants.disjoint_union(surfaces.tetrahedron(), oct_)),
    ]
    iso = _case("isolated-vertex", ["closed", "isolated-vertex"], "a tetrahedron plus a vertex "
                "used by no face (the protocol's values there: defect 2 pi, area 0, zero row)",
                surfaces.tetrahedron())
    iso.V.append([5.0, 5.0, 5.0])
    out.append(iso)
    return out


def seeded_cases(count: int = 4, seed: int = 2026) -> list[Case]:
    """Generated cases: closed and bounded surfaces with every coordinate moved by a seeded
    random float (no exact structure left), deterministic in ``seed``."""
    from ..properties.strategies import jittered
    from ..reference import surfaces
    bases = [("octahedron", surfaces.octahedron), ("cube", surfaces.cube),
             ("grid", lambda: surfaces.grid(3, 3)), ("disk", lambda: surfaces.disk(6))]
    out = []
    for k in range(count):
        name, build = bases[k % len(bases)]
        s = jittered(build(), 1, seed + k, floats=True)
        flags = ["seeded"] + (["boundary"] if name in ("grid", "disk") else ["closed"])
        out.append(_case(f"seeded-{name}-{seed + k}", flags, f"the {name}, every coordinate "
                         f"moved by a random float (seed {seed + k})", s))
    return out


def invalid_cases() -> list[Case]:
    """Bad inputs (``invalid``: an error is due) and inputs outside the notes' domain
    (``acceptable``: the reference refuses them; an implementation may answer)."""
    tri = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
    return [
        Case("nan-coordinate", ("invalid",), "a NaN coordinate in a square of two faces",
             [[math.nan, 0.0, 0.0]] + tri[1:] + [[1.0, 1.0, 0.5]], [[0, 1, 2], [1, 3, 2]],
             result="invalid"),
        Case("index-out-of-range", ("invalid",), "a face names vertex 3 of 3", tri, [[0, 1, 3]],
             result="invalid"),
        Case("non-manifold-edge", ("invalid",), "three faces on the edge (0, 1)",
             tri + [[0.0, -1.0, 0.0], [0.0, 0.0, 1.0]], [[0, 1, 2], [1, 0, 3], [0, 1, 4]],
             result="acceptable"),
        Case("degenerate-face", ("invalid",), "a face of zero area (collinear corners)",
             [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]], [[0, 1, 2]], result="acceptable"),
        Case("repeated-vertex", ("invalid",), "a face (0, 0, 1)", tri, [[0, 0, 1], [0, 1, 2]],
             result="acceptable"),
    ]


def cases() -> list[Case]:
    return named_cases() + seeded_cases() + invalid_cases()


# --- exact values as text ---------------------------------------------------------------------


def exact_text(x) -> str:
    """An exact value as an expression: integers, ``p/q``, ``sqrt(r)``, ``pi`` and ``arccot``
    (values in (0, pi)); ``+``, ``-``, ``*`` and parentheses.  Angle and AngleLength print
    as their repr without the type name."""
    if isinstance(x, (int, Fraction)):
        return str(x)
    r = repr(x)
    for head in ("Angle(", "AngleLength("):
        if r.startswith(head):
            return r[len(head):-1]
    return str(x)


# --- expected answers -------------------------------------------------------------------------


class _NotApplicable(Exception):
    pass


def _request(method: str, case: Case, rng: random.Random) -> dict:
    """The protocol request fields of ``case`` for ``method``: its arguments, read from the
    case (``V``, ``F``; planar points ``P``) or drawn on it (a ``boundary`` set: every
    boundary vertex; its ``values``)."""
    from ..properties.registry import all_quantities
    q = all_quantities()[method]
    arguments = METHODS[method].arguments
    if q.planar and not case.planar:
        raise _NotApplicable              # the reference answers in the plane z = 0 only
    if "connected" in q.requires and "isolated-vertex" in case.flags:
        raise _NotApplicable              # a surface and a point: two components
    req = {}
    for a in arguments:
        if a == "P":
            used = range(len(case.V)) if case.invalid else sorted({v for f in case.F for v in f})
            req["P"] = [case.V[v][:2] for v in used]
        elif a in ("V", "F"):
            req[a] = getattr(case, a)
        elif case.invalid:
            raise _NotApplicable          # nothing to draw on a bad mesh
        elif a == "boundary":
            from ..reference.combinatorics import Triangulation
            t = Triangulation.from_faces(case.F, n_vertices=len(case.V))
            boundary = sorted({v for loop in t.boundary_loops() for v in loop})
            if not boundary or len(boundary) == len(case.V):
                raise _NotApplicable      # nothing to solve for
            req["boundary"] = boundary
        elif a == "values":
            req["values"] = [rng.randint(-64, 64) / 16 for _ in req["boundary"]]
        else:
            raise AssertionError(f"{method}: no way to draw its argument {a!r}")
    return req


def _reference_answer(method, req):
    from ..oracles.exact_reference import ReferenceImplementation
    return _call(ReferenceImplementation(), method, req)


def rounded_up(x):
    """A bound (a float or nested lists of them) rounded up to 3 significant digits: a bound
    needs no more, and the corpus's bytes then do not depend on the last bit of a numpy or
    LAPACK sum (the committed corpus is compared byte for byte on other machines)."""
    if isinstance(x, list):
        return [rounded_up(v) for v in x]
    x = float(x)
    if x <= 0 or not math.isfinite(x):
        return x
    mantissa, exponent = f"{x:.2e}".split("e")
    y = float(f"{mantissa}e{exponent}")
    if y < x:
        y = float(f"{float(mantissa) + 0.01:.2f}e{exponent}")
    return y


def _numbers(exact, float64, bounds) -> dict:
    out = {"exact": exact, "float64": float64}
    for k, b in bounds.items():
        out[f"tolerance{k}"] = rounded_up(b)
    return out


def _nested(a) -> list:
    return np.asarray(a, dtype=np.float64).tolist()


def _bounds(q, example, want=None) -> dict:
    """{"64": bound, "32": bound}: the quantity ``q``'s derived bound on ``example`` at each
    machine epsilon (as ``compare`` derives it)."""
    out = {}
    for k, e in EPSILONS.items():
        with at_machine_epsilon(e):
            out[k] = q.bound(example, want)
    return out


def _matrix_expected(M_exact, Ls, bounds, n: int, keep) -> dict:
    """Entries of the union of the exact matrix's pattern and the bounds' patterns."""
    import scipy.sparse as sp
    exact = {(int(keep[i]), int(keep[j])): v for i, j, v in M_exact.entries()}
    pattern = set(exact)
    for B in bounds.values():
        C = sp.coo_matrix(B)
        pattern |= {(int(i), int(j)) for i, j in zip(C.row, C.col)}
    entries = sorted(pattern)
    rows = np.array([e[0] for e in entries], dtype=np.int64)
    cols = np.array([e[1] for e in entries], dtype=np.int64)
    out = {"shape": [n, n], "entries": [list(e) for e in entries],
           "exact": [exact_text(exact.get(e, 0)) for e in entries],
           "float64": np.asarray(Ls[rows, cols]).reshape(-1).tolist() if entries else []}
    for k, B in bounds.items():
        out[f"tolerance{k}"] = rounded_up(np.asarray(sp.csr_matrix(B)[rows, cols]).reshape(-1)
                                          .tolist() if entries else [])
    return out


#: the exact value of what a method answers at a vertex used by no face (ISOLATED_VERTEX)
_ISOLATED_TEXT = {0.0: "0", math.tau: "2*pi"}


def expected(method: str, case: Case, req: dict) -> dict:
    """The ``expected`` object of ``method`` on ``case`` (:class:`_NotApplicable` if the
    reference has no value there): by the answer's kind and element, the values from the
    method's quantity (``exact``, ``bound``)."""
    from .meshes import MeshExamples, MeshInput
    from ..properties.registry import all_quantities
    from ..protocol.arrays import Referenced

    try:
        answer = _reference_answer(method, req)
    except (OutsideDomain, NotImplementedError):
        raise _NotApplicable from None
    q = all_quantities()[method]
    kind = kind_of(method)
    if kind in ("integer", "boolean"):
        return {"value": answer}
    if kind == "loops":
        return {"value": [list(map(int, loop)) for loop in answer]}
    if kind == "planar_triangulation":           # the reference's answer is one valid answer
        faces = np.asarray(answer).tolist()
        return {"boundary": [list(e) for e in sorted(_boundary_edges(faces))],
                "one_answer": faces}
    r = Referenced(req["V"], req["F"])
    drawn = {a: tuple(req[a]) for a in METHODS[method].arguments if a not in ("V", "F")}
    if drawn and r.isolated:
        raise _NotApplicable              # drawn vertex indices: of the mesh's surface only
    keep = r.keep
    ex = MeshExamples(MeshInput(case.name, r.V.tolist(), r.F.tolist()))
    example = ex.example().with_data(**drawn) if drawn else ex.example()
    n = len(req["V"])
    if kind == "flags":
        return _flags_expected(answer, _bounds(q, example))
    if kind == "intrinsic_triangulation":
        return _intrinsic_expected(all_quantities()[q.via], req, answer, ex, r)
    if kind == "matrix":
        return _matrix_expected(q.exact(example), answer.tocsr(),
                                _embedded(_bounds(q, example), r), n, keep)
    exact = q.exact(example)
    if kind == "edges":
        exact = {tuple(sorted(int(keep[v]) for v in e)): h for e, h in exact.items()}
        edges = sorted(exact)
        compact = {int(w): v for v, w in enumerate(keep)}
        b = {k: [float(v[tuple(sorted(compact[x] for x in e))]) for e in edges]
             for k, v in _bounds(q, example).items()}
        out = {"edges": [list(e) for e in edges]}
        out.update(_numbers([exact_text(exact[e]) for e in edges],
                            [float(answer[e]) for e in edges], b))
        return out
    element = METHODS[method].element
    u = np.asarray(answer, dtype=np.float64)
    bounds = _bounds(q, example, u if drawn else None)
    if element == "total":
        return _numbers(exact_text(exact), float(answer), {k: float(v) for k, v in bounds.items()})
    if element == "corner":
        return _numbers([[exact_text(a) for a in f] for f in exact], _nested(answer),
                        {k: _nested(b) for k, b in bounds.items()})
    # per vertex (or vertex coordinate): a vertex used by no face has the protocol's value
    isolated = ISOLATED_VERTEX.get(method, 0.0)
    values = exact.items() if isinstance(exact, dict) else enumerate(exact)
    fill = _ISOLATED_TEXT.get(isolated)
    if fill is None:
        raise ValueError(f"{method}: ISOLATED_VERTEX value {isolated!r} has no exact text "
                         "in vectors._ISOLATED_TEXT")
    texts = [fill if element == "vertex" else [fill] * 3 for _ in range(n)]
    for v, x in values:
        texts[int(keep[v])] = exact_text(x) if element == "vertex" else [exact_text(c) for c in x]
    return _numbers(texts, u.tolist(),
                    {k: _scatter(b, keep, n, EPSILONS[k] * isolated) for k, b in bounds.items()})


def _scatter(values, keep, n, fill) -> list:
    """Per surface vertex values -> per input vertex, ``fill`` at the isolated ones."""
    values = np.asarray(values, dtype=np.float64)
    out = np.full((n,) + values.shape[1:], fill, dtype=np.float64)
    out[keep] = values
    return out.tolist()


def _embedded(bounds: dict, r) -> dict:
    return {k: r.embed(b) for k, b in bounds.items()}


def _boundary_edges(F) -> set:
    """Directed boundary edges (a, b) of counterclockwise faces: used by one face only."""
    directed = {(f[c], f[next_corner(c)]) for f in F for c in range(3)}
    return {e for e in directed if e[::-1] not in directed}


def _flags_expected(answer, ties: dict) -> dict:
    out = {"value": np.asarray(answer, dtype=bool).tolist()}
    for k, t in ties.items():                   # either answer agrees there
        out[f"either{k}"] = np.argwhere(t).tolist()
    return out


def _intrinsic_expected(q, req, answer, ex, r) -> dict:
    """The Laplace-Beltrami operator (the same for every intrinsic Delaunay triangulation,
    R4.9: the values of quantity ``q``) and the total area, which any answer's (F2, l2)
    must reproduce."""
    from ..reference.exact import exact_sum
    from ..properties.delaunay_exact import DelaunayExact
    F2, l2 = answer
    example = ex.example()
    amp = max(DelaunayExact.of(example).amplification)   # flips' amplification
    lap = _matrix_expected(q.exact(example), _reference_answer(q.method, req).tocsr(),
                           _embedded(_bounds(q, example), r), len(req["V"]), r.keep)
    total = exact_sum(ex.surface.metric().areas)
    area = _numbers(exact_text(total), float_view(total),
                    {k: _intrinsic_area_bound(l2, amp, e) for k, e in EPSILONS.items()})
    return {"faces": len(req["F"]), "laplacian": lap, "area": area,
            "one_answer": {"F": np.asarray(F2).tolist(), "l2": np.asarray(l2).tolist()}}


def _intrinsic_area_bound(l2, amp: float, e: float) -> float:
    """A4.13's bound (:func:`ddg_oracle.properties.delaunay_exact.total_area_bound`) on the total
    area recomputed from the squared lengths ``l2`` of a triangulation after flips."""
    from ..properties.delaunay_exact import angles_from_squared_lengths, total_area_bound
    _, area = angles_from_squared_lengths(np.asarray(l2, dtype=np.float64))
    rho = np.asarray(l2).max(axis=1) / (2 * area)
    with at_machine_epsilon(e):
        return total_area_bound(area, rho, amp)


# --- the corpus -------------------------------------------------------------------------------


def build() -> dict[str, dict]:
    """{file name: JSON object} of the corpus (deterministic)."""
    from ddg_oracle import __version__
    from ..oracles.executable import PROTOCOL_VERSION
    from ..properties.registry import all_quantities
    quantities = all_quantities()
    all_cases = cases()
    files = {}
    total = 0
    for method in METHODS:
        rng = random.Random(f"{method}-values")
        entries = []
        for case in all_cases:
            try:
                req = _request(method, case, rng)
            except _NotApplicable:
                continue
            entry = {"id": f"{method}/{case.name}", "name": case.name, "flags": list(case.flags),
                     "comment": case.comment, "input": _portable(req)}
            if case.invalid:
                try:
                    _reference_answer(method, req)
                except (InputError, ValueError, IndexError) as e:
                    entry["result"] = case.result
                    entry["expected"] = {"error": f"{type(e).__name__}: {e}"}
                    entries.append(entry)
                    continue
                continue              # e.g. topology of a degenerate face: a valid question
            try:
                entry["expected"] = expected(method, case, req)
            except _NotApplicable:
                continue
            except InputError:
                # no value where the quantity's requirements fail (as in compare): the genus
                # of a disconnected mesh, signed dihedral angles on a non-orientable one;
                # anything else is a bug of ours
                if quantities[method].requires:
                    continue
                raise
            entry["result"] = "valid"
            entries.append(entry)
        total += len(entries)
        files[f"{method}.json"] = {
            "format": FORMAT, "version": VERSION, "method": method, "kind": kind_of(method),
            "contract": METHODS[method].contract, "cases": entries}
    files["manifest.json"] = {
        "format": FORMAT, "version": VERSION, "protocol_version": PROTOCOL_VERSION,
        "generator": f"ddg-oracle {__version__.split('+')[0]} (ddg-oracle vectors)",
        "epsilons": {"float64": FLOAT64_EPSILON, "float32": FLOAT32_EPSILON},
        "methods": {m: f"{m}.json" for m in METHODS}, "cases": total}
    files["schema.json"] = schema()
    return files


def _portable(x):
    """JSON has no NaN or infinity: an input coordinate that is one is the string "NaN",
    "Infinity" or "-Infinity" (README.md of the corpus); :func:`_unportable` reads it back."""
    if isinstance(x, float) and not math.isfinite(x):
        return "NaN" if math.isnan(x) else ("Infinity" if x > 0 else "-Infinity")
    if isinstance(x, dict):
        return {k: _portable(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_portable(v) for v in x]
    return x


def _unportable(x):
    if isinstance(x, str) and x in ("NaN", "Infinity", "-Infinity"):
        return float(x.replace("Infinity", "inf"))
    if isinstance(x, dict):
        return {k: _unportable(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_unportable(v) for v in x]
    return x


def dumps(obj) -> str:
    """Deterministic JSON: the top-level fields one per line, each case on one line (a diff
    of the corpus names the cases that changed)."""
    def one(x):
        return json.dumps(x, separators=(",", ":"), allow_nan=False)
    lines = []
    for k, v in obj.items():
        if k == "cases" and isinstance(v, list):
            body = ",\n".join("  " + one(c) for c in v)
            lines.append(f'"cases": [\n{body}\n ]' if v else '"cases": []')
        else:
            lines.append(f"{one(k)}: {one(v)}")
    return "{\n " + ",\n ".join(lines) + "\n}\n"


def write(out: str | Path) -> list[Path]:
    """Write the corpus and its README into ``out`` (created; files overwritten)."""
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise VectorsError(f"--out {out}: is an existing file; name a directory (new, or one "
                           "written by ddg-oracle vectors)")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise VectorsError(f"--out {out}: cannot create it: {e.strerror or e}") from None
    written = []
    for name, obj in build().items():
        p = out / name
        p.write_text(dumps(obj), encoding="utf-8")
        written.append(p)
    readme = out / "README.md"
    readme.write_text(corpus_readme(), encoding="utf-8")
    return written + [readme]


def corpus_readme() -> str:
    from importlib.resources import files
    return (files("ddg_oracle.application") / "data" / "vectors.md").read_text(encoding="utf-8")


# --- the schema -------------------------------------------------------------------------------


def schema() -> dict:
    """JSON Schema (draft 2020-12) of a method file of the corpus and of manifest.json."""
    num = {"type": "number"}
    nested = {"anyOf": [{"type": "number"}, {"type": "array", "items": {"$ref": "#/$defs/nested"}}]}
    texts = {"anyOf": [{"type": "string"}, {"type": "array", "items": {"$ref": "#/$defs/texts"}}]}
    pair = {"type": "array", "items": {"type": "integer", "minimum": 0}, "minItems": 2, "maxItems": 2}
    triple = {"type": "array", "items": {"type": "integer", "minimum": 0}, "minItems": 3, "maxItems": 3}
    numbers = {"type": "object", "required": ["exact", "float64", "tolerance64", "tolerance32"],
               "properties": {"exact": {"$ref": "#/$defs/texts"},
                              "float64": {"$ref": "#/$defs/nested"},
                              "tolerance64": {"$ref": "#/$defs/nested"},
                              "tolerance32": {"$ref": "#/$defs/nested"}}}
    matrix = {"type": "object", "required": ["shape", "entries", "exact", "float64",
                                             "tolerance64", "tolerance32"],
              "properties": {"shape": pair, "entries": {"type": "array", "items": pair},
                             "exact": {"type": "array", "items": {"type": "string"}},
                             "float64": {"type": "array", "items": num},
                             "tolerance64": {"type": "array", "items": num},
                             "tolerance32": {"type": "array", "items": num}}}
    cells = {"type": "object", "required": ["boundary", "one_answer"],
             "properties": {"boundary": {"type": "array", "items": pair},
                            "one_answer": {"type": "array", "items": triple}}}
    kinds = {
        "integer": {"type": "object", "required": ["value"], "properties": {"value": {"type": "integer"}}},
        "boolean": {"type": "object", "required": ["value"], "properties": {"value": {"type": "boolean"}}},
        "loops": {"type": "object", "required": ["value"], "properties": {
            "value": {"type": "array", "items": {"type": "array", "items": {"type": "integer"}}}}},
        "numbers": {"$ref": "#/$defs/numbers"},
        "edges": {"allOf": [{"$ref": "#/$defs/numbers"}, {"type": "object", "required": ["edges"],
                                                         "properties": {"edges": {"type": "array", "items": pair}}}]},
        "matrix": {"$ref": "#/$defs/matrix"},
        "flags": {"type": "object", "required": ["value", "either64", "either32"], "properties": {
            "value": {"type": "array", "items": {"type": "array", "items": {"type": "boolean"}}},
            "either64": {"type": "array", "items": pair}, "either32": {"type": "array", "items": pair}}},
        "intrinsic_triangulation": {"type": "object", "required": ["faces", "laplacian", "area", "one_answer"],
                                    "properties": {"faces": {"type": "integer"},
                                                   "laplacian": {"$ref": "#/$defs/matrix"},
                                                   "area": {"$ref": "#/$defs/numbers"}}},
        "planar_triangulation": cells,
    }
    case = {"type": "object", "required": ["id", "name", "flags", "comment", "input", "result", "expected"],
            "properties": {"id": {"type": "string"}, "name": {"type": "string"},
                           "flags": {"type": "array", "items": {"type": "string"}},
                           "comment": {"type": "string"}, "input": {"type": "object"},
                           "result": {"enum": ["valid", "invalid", "acceptable"]},
                           "expected": {"type": "object"}},
            "if": {"properties": {"result": {"enum": ["invalid", "acceptable"]}}},
            "then": {"properties": {"expected": {"type": "object", "required": ["error"],
                                                 "properties": {"error": {"type": "string"}}}}}}
    method_file = {"type": "object", "required": ["format", "version", "method", "kind", "contract", "cases"],
                   "properties": {"format": {"const": FORMAT}, "version": {"const": VERSION},
                                  "method": {"enum": list(METHODS)}, "kind": {"enum": sorted(kinds)},
                                  "contract": {"type": "string"},
                                  "cases": {"type": "array", "items": {"$ref": "#/$defs/case"}}},
                   "allOf": [{"if": {"properties": {"kind": {"const": k}}},
                              "then": {"properties": {"cases": {"type": "array", "items": {
                                  "if": {"properties": {"result": {"const": "valid"}}},
                                  "then": {"properties": {"expected": {"$ref": f"#/$defs/kind.{k}"}}}}}}}}
                             for k in sorted(kinds)]}
    manifest = {"type": "object", "required": ["format", "version", "protocol_version", "generator",
                                               "epsilons", "methods", "cases"],
                "properties": {"format": {"const": FORMAT}, "version": {"const": VERSION},
                               "methods": {"type": "object", "additionalProperties": {"type": "string"}},
                               "cases": {"type": "integer"}}}
    answer = {"type": "object", "required": ["id"], "properties": {"id": {"type": "string"}},
              "oneOf": [{"required": ["value"]}, {"required": ["error"], "properties": {"error": {
                  "type": "object", "required": ["kind", "message"], "properties": {
                      "kind": {"enum": ["outside_domain", "failed"]}, "message": {"type": "string"}}}}}]}
    defs = {"nested": nested, "texts": texts, "numbers": numbers, "matrix": matrix, "case": case,
            "method_file": method_file, "manifest": manifest, "answer": answer}
    defs.update({f"kind.{k}": v for k, v in kinds.items()})
    return {"$schema": "https://json-schema.org/draft/2020-12/schema",
            "$id": f"https://ddg-oracle/test-vectors/v{VERSION}/schema.json",
            "title": "ddg-oracle test vectors",
            "description": "A method file (METHOD.json) is $defs/method_file, manifest.json is "
                           "$defs/manifest, each line of an answers file is $defs/answer.",
            "$defs": defs, "anyOf": [{"$ref": "#/$defs/method_file"}, {"$ref": "#/$defs/manifest"}]}


# --- answers and verify -----------------------------------------------------------------------


def load(directory: str | Path) -> dict[str, dict]:
    """{method: method file} of a corpus directory (VectorsError if it is not one)."""
    d = Path(directory)
    try:
        manifest = json.loads(read_text(d / "manifest.json", "a corpus manifest",
                                        error=VectorsError))
    except ValueError as e:
        raise VectorsError(f"{d}: not a test-vector directory (manifest.json: {e})") from None
    if manifest.get("format") != FORMAT or manifest.get("version") != VERSION:
        raise VectorsError(f"{d}: manifest.json is format {manifest.get('format')!r} version "
                           f"{manifest.get('version')!r}; this ddg-oracle reads {FORMAT} {VERSION}")
    out = {}
    for method, name in manifest.get("methods", {}).items():
        if not isinstance(name, str) or "/" in name or name.startswith("."):
            raise VectorsError(f"{d}: manifest.json names {name!r} for {method}: not a file "
                               "of the corpus directory")
        try:
            out[method] = json.loads(read_text(d / name, "a corpus file", error=VectorsError))
        except ValueError as e:
            raise VectorsError(f"{d / name}: {e}") from None
    return out


def _call(impl, method: str, req: dict):
    """``impl``'s answer to the request fields ``req`` of ``method`` (as a corpus case's
    ``input``: non-finite coordinates as strings)."""
    from ..properties.conventions import declared, to_reference
    from ..protocol.answers import read
    inp = _unportable(req)
    # integer arrays for faces and vertex sets, floats for points and values
    dtypes = {"F": np.int64, "boundary": np.int64}
    args = [np.array(inp[a], dtype=dtypes.get(a, np.float64)) for a in METHODS[method].arguments]
    # of its method's kind (protocol.answers: MalformedAnswer, its failure, otherwise), a
    # single value as a Python int, bool or number (2.0 for chi reads as 2, as in check)
    answer = read(method, getattr(impl, method)(*args))
    if METHODS[method].arguments[:2] == ("V", "F"):      # its declared conventions, mapped
        answer = to_reference(declared(impl), method, answer, args[0], args[1])
    return answer


def answers(corpus: dict[str, dict], impl) -> list[dict]:
    """The answers-file lines of ``impl`` on every case of the methods it has (values encoded
    as in the executable protocol; an exception is an error line: ``outside_domain`` for
    :class:`OutsideDomain`, else ``failed`` with the exception's type and message).  A case
    the implementation never received (a program of the executable protocol cannot be sent
    a NaN coordinate) is a ``{"id", "not_run": why}`` line: no answer, and no pass."""
    from ..oracles.executable import encode_value
    from ..protocol.processes import NotSent
    from ..protocol.methods import capabilities
    caps = capabilities(impl)
    out = []
    for method, file in corpus.items():
        if method not in caps:
            continue
        for c in file["cases"]:
            try:
                value = encode_value(method, _call(impl, method, c["input"]))
            except NotSent as e:
                out.append({"id": c["id"], "not_run": str(e)})
                continue
            except OutsideDomain as e:
                out.append({"id": c["id"], "error": {"kind": "outside_domain", "message": str(e)}})
                continue
            except Exception as e:  # noqa: BLE001  (an implementation's failure is its answer)
                out.append({"id": c["id"], "error": {"kind": "failed",
                                                     "message": f"{type(e).__name__}: {e}"}})
                continue
            out.append({"id": c["id"], "value": _portable(value)})
    return out


def read_answers(path: str | Path) -> list[dict]:
    """The lines of an answers file (JSON Lines; VectorsError naming a bad line, or a case
    answered twice)."""
    out, seen = [], {}
    text = read_text(path, "an answers file", error=VectorsError)
    for k, line in enumerate(text.splitlines(), 1):
        if not line.strip():
            continue
        try:
            obj = json.loads(line)
        except (ValueError, RecursionError) as e:   # a value nested beyond the parser
            raise VectorsError(f"{path}:{k}: not JSON ({e})") from None
        if not (isinstance(obj, dict) and isinstance(obj.get("id"), str)
                and ("value" in obj) != ("error" in obj)):
            raise VectorsError(f'{path}:{k}: expected {{"id": ..., "value": ...}} or '
                               f'{{"id": ..., "error": {{"kind", "message"}}}}')
        if obj["id"] in seen:           # which would count? (both were, "72 cases" of 36)
            raise VectorsError(f"{path}:{k}: case {obj['id']!r} is answered again (first on "
                               f"line {seen[obj['id']]}): one answer per case")
        seen[obj["id"]] = k
        out.append(obj)
    if not out:
        raise VectorsError(f"{path}: no answer in it (an empty answers file checks nothing)")
    return out


@dataclass
class Verdict:
    """One case of one answers file: ``pass``, ``FAIL``, ``acceptable`` (a value for an input
    the reference refuses), ``not applicable`` (the implementation said outside_domain, or
    float32 rounding of the input leaves no value), or ``not run`` (the implementation never
    received the case)."""

    id: str
    status: str
    message: str = ""


class _Wrong(Exception):
    """The answer does not match (its message says where and how)."""


def _short(x, width: int = 60) -> str:
    t = x if isinstance(x, str) else json.dumps(x)
    return t if len(t) <= width else t[:width - 3] + "..."


def _widened(conventions, method: str, got, inp: dict, want: dict, bits: str) -> dict:
    """``want`` with its bound at ``bits`` widened for the declared conventions' maps, on the
    case's mesh at that machine epsilon."""
    from ..properties.harness import widened
    from ..protocol.methods import at_machine_epsilon
    from ..properties.strategies import mesh_case
    key = f"tolerance{bits}"
    tol = np.asarray(want[key], dtype=np.float64)
    with at_machine_epsilon(2.0 ** -23 if bits == "32" else 2.0 ** -52):
        wider = widened(conventions, method, got,
                        lambda: mesh_case(inp["V"], [list(f) for f in inp["F"]], "a test vector"),
                        tol)
    return want if wider is tol else {**want, key: wider}


def _rounding_widened(conventions, inp: dict, want: dict, bits: str) -> dict:
    """``want`` with every bound at ``bits`` widened for an implementation that declares
    rounding its own input (:func:`~ddg_oracle.properties.conventions.bound_epsilon`: e'
    instead of e).  The written bounds are at e; each is a sum, minimum or maximum of terms
    linear in e, sublinear (a square root) or gamma_k = k e / (1 - k e) with k <= K = 3 m
    + n + 8 (no sum of the corpus has more terms), so 2 e' / e times it covers the bound at
    e' where K e' <= 1/2; beyond, infinite (nothing judged)."""
    from ..properties.conventions import bound_epsilon
    e = EPSILONS[bits]
    wider = bound_epsilon(conventions, e, inp["V"], inp.get("F", []))
    if wider == e:
        return want
    K = 3 * len(inp.get("F", [])) + len(inp["V"]) + 8
    factor = 2 * wider / e if K * wider <= 0.5 else math.inf
    key = f"tolerance{bits}"

    def scaled(x):
        if isinstance(x, dict):
            return {k: _times(v, factor) if k == key else scaled(v) for k, v in x.items()}
        return x
    return scaled(want)


def _times(bound, factor: float):
    t = np.asarray(bound, dtype=np.float64)
    out = np.where(t > 0, t * factor, t)          # an exact entry (bound 0) stays exact
    return out.tolist() if out.ndim else float(out)


def _elementwise(got, want: dict, bits: str, label) -> None:
    exp = np.asarray(want["float64"], dtype=np.float64)
    tol = np.asarray(want[f"tolerance{bits}"], dtype=np.float64)
    got = np.asarray(got, dtype=np.float64)
    if got.shape != exp.shape:
        raise _Wrong(f"shape {got.shape}, expected {exp.shape}")
    with np.errstate(invalid="ignore"):
        bad = ~(np.abs(got - exp) <= tol)           # NaN is bad too
    if bad.any():
        k = tuple(int(i) for i in np.argwhere(bad)[0])
        exact = np.asarray(want["exact"], dtype=object)[k] if exp.ndim else want["exact"]
        raise _Wrong(f"{label(k)}: got {float(got[k]):.17g}, expected {float(exp[k]):.17g} "
                     f"+- {float(tol[k]):.3g} (exact {_short(str(exact))}); "
                     f"{int(bad.sum())} of {bad.size} elements off")


def _matrix_check(L, want: dict, bits: str) -> None:
    import scipy.sparse as sp
    n = want["shape"][0]
    if L.shape != (n, n):
        raise _Wrong(f"shape {L.shape}, expected {(n, n)}")
    A = sp.csr_matrix(L, dtype=np.float64)
    A.sum_duplicates()
    entries = [tuple(e) for e in want["entries"]]
    rows = np.array([e[0] for e in entries], dtype=np.int64)
    cols = np.array([e[1] for e in entries], dtype=np.int64)
    got = np.asarray(A[rows, cols]).reshape(-1) if entries else np.zeros(0)
    _elementwise(got, want, bits, lambda k: f"entry {entries[k[0]]}")
    C = A.tocoo()
    listed = set(entries)
    for i, j, v in zip(C.row.tolist(), C.col.tolist(), C.data.tolist()):
        if v != 0 and (i, j) not in listed:
            raise _Wrong(f"entry {(i, j)}: got {v:.17g}, expected exactly 0 (not an entry of "
                         "the exact matrix)")


def _cotan_from_lengths(F2, l2, n: int):
    """The cotan Laplacian (protocol sign) of faces F2 with squared lengths l2 (column c:
    the edge opposite corner c): float64, Kahan's stable Heron as in A4.13."""
    import scipy.sparse as sp
    from ..properties.delaunay_exact import angles_from_squared_lengths
    ang, area = angles_from_squared_lengths(l2)
    rows, cols, vals = [], [], []
    for c in range(3):
        i, j = F2[:, next_corner(c)], F2[:, prev_corner(c)]
        w = 0.5 / np.tan(ang[:, c])
        keep = i != j                                 # a loop edge adds nothing to L
        i, j, w = i[keep], j[keep], w[keep]
        rows += [i, j, i, j]
        cols += [j, i, i, j]
        vals += [-w, -w, w, w]
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(n, n)), area


def _planar_check(F, pts, want: dict, e: float) -> None:
    """The triangulation rule of README.md ("planar_triangulation"), with exact predicates on
    the float points: :func:`ddg_oracle.properties.delaunay.planar_delaunay_problems` (faces
    counterclockwise, no directed edge twice, the expected boundary edges, every interior
    edge Delaunay up to the in-circle bound at machine epsilon ``e``: nearly cocircular
    points may split either way), and the vertices and total area of ``one_answer``."""
    from ..properties.delaunay import NotPlanarDelaunay, planar_delaunay_problems
    P = [(Fraction(x), Fraction(y)) for x, y in pts]
    tris = [tuple(int(v) for v in f) for f in F]
    if any(not 0 <= v < len(P) for t in tris for v in t):
        raise _Wrong(f"a vertex index outside 0..{len(P) - 1}")
    try:
        with at_machine_epsilon(e):
            planar_delaunay_problems(P, tris, {tuple(b) for b in want["boundary"]})
    except NotPlanarDelaunay as problem:
        raise _Wrong(problem.message) from None
    if {v for t in tris for v in t} != {v for t in want["one_answer"] for v in t}:
        raise _Wrong("not the expected vertices (every point must be a vertex)")

    def area2(t):
        a, b, c = (P[v] for v in t)
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    if sum(area2(t) for t in tris) != sum(area2(t) for t in want["one_answer"]):
        raise _Wrong("the faces do not cover the expected region once")


def _check_value(method: str, c: dict, value, bits: str, conventions=()) -> None:
    from ..oracles.executable import DriverFailed, decode_value
    inp = _unportable(c["input"])
    want = c["expected"]
    n = len(inp["P"]) if "P" in inp else len(inp["V"])
    m = len(inp["F"]) if "F" in inp else 0
    try:
        got = decode_value(method, _unportable(value), n, m)
    except (DriverFailed, ValueError, TypeError) as e:
        raise _Wrong(f"malformed answer: {e}") from None
    kind = kind_of(method)
    if conventions and kind == "numbers":
        want = _widened(conventions, method, got, inp, want, bits)
    if conventions and "V" in inp:
        want = _rounding_widened(conventions, inp, want, bits)
    if kind in ("integer", "boolean"):
        if got != want["value"]:
            raise _Wrong(f"got {got!r}, expected {want['value']!r}")
    elif kind == "loops":
        from .compare import loop_edges
        if len(got) != len(want["value"]) or loop_edges(got) != loop_edges(want["value"]):
            raise _Wrong(f"loops {_short(got)}, expected {_short(want['value'])}")
    elif kind == "numbers":
        _elementwise(got, want, bits, WHERE[METHODS[method].element])
    elif kind == "edges":
        keys = [tuple(e) for e in want["edges"]]
        if set(got) != set(keys):
            raise _Wrong(f"{len(got)} edges, expected the {len(keys)} interior edges "
                         f"(first missing or extra: {sorted(set(got) ^ set(keys))[0]})")
        _elementwise([got[k] for k in keys], want, bits, lambda k: f"edge {list(keys[k[0]])}")
    elif kind == "matrix":
        _matrix_check(got, want, bits)
    elif kind == "flags":
        got = np.asarray(got, dtype=bool)
        either = {tuple(e) for e in want[f"either{bits}"]}
        for f, cs in enumerate(want["value"]):
            for k, w in enumerate(cs):
                if bool(got[f, k]) != w and (f, k) not in either:
                    raise _Wrong(f"face {f}, corner {k}: got {bool(got[f, k])}, expected {w}")
    elif kind == "intrinsic_triangulation":
        F2, l2 = got
        if len(F2) != want["faces"] or (len(F2) and (F2.min() < 0 or F2.max() >= n)):
            raise _Wrong(f"{len(F2)} faces on vertices 0..{n - 1} expected {want['faces']}")
        if not np.all(np.isfinite(l2)) or np.any(l2 <= 0):
            raise _Wrong("a squared length is not a positive finite number")
        L, area = _cotan_from_lengths(F2, l2, n)
        try:
            _matrix_check(L, want["laplacian"], bits)
        except _Wrong as e:
            raise _Wrong(f"its cotan Laplacian is not the Laplace-Beltrami operator: {e}") from None
        _elementwise(float(np.sum(area)), want["area"], bits, lambda k: "total area")
    elif kind == "planar_triangulation":
        pts = inp["P"] if "P" in inp else [p[:2] for p in inp["V"]]
        _planar_check(np.asarray(got), pts, want, EPSILONS[bits])
    else:
        raise AssertionError(kind)


def _has_non_finite(x) -> bool:
    if isinstance(x, float):
        return not math.isfinite(x)
    if isinstance(x, dict):
        return any(_has_non_finite(v) for v in x.values())
    if isinstance(x, list):
        return any(_has_non_finite(v) for v in x)
    return False


def _as_read_in_float32(method: str, c: dict, value, wrong: "_Wrong") -> Verdict:
    """The verdict on a float32 answer off the expected values of case ``c``: those are of
    the input as written, and a float32 code reads the coordinates float32 cannot hold
    rounded (a 2^-30 needle collapses).  Such a case is compared again with the exact
    values of the rounded input (what the code computed with); a FAIL either way."""
    from ..properties.precision import FORMATS, rounded_to
    V = _unportable(c["input"].get("V") or [])
    try:
        V32 = [[rounded_to(FORMATS[24], x) for x in p] for p in V]
    except (OverflowError, TypeError, ValueError):
        return Verdict(c["id"], "FAIL", str(wrong))
    if V32 == V:
        return Verdict(c["id"], "FAIL", str(wrong))
    req = {**_unportable(c["input"]), "V": V32}
    try:
        again = expected(method, Case(c["name"], tuple(c["flags"]), c["comment"], V32,
                                      req.get("F", [])), req)
    except (_NotApplicable, InputError) as e:
        return Verdict(c["id"], "not applicable", f"its input rounded to float32 (as a float32 "
                       f"code reads it) has no value: {_short(str(e), 120)}")
    try:
        _check_value(method, {**c, "expected": again}, value, "32")
    except _Wrong as e:
        return Verdict(c["id"], "FAIL", f"{wrong}; and against its input rounded to float32: {e}")
    return Verdict(c["id"], "pass", "against its input rounded to float32 (what a float32 "
                   "code reads)")


def verify(corpus: dict[str, dict], lines: list[dict], float32: bool = False,
           conventions=()) -> list[Verdict]:
    """A verdict per answered case (the answers of one implementation; ``conventions``: the
    ones it declares, its answers already mapped by them (:func:`answers`), whose maps may
    widen a case's written bound: :func:`~ddg_oracle.properties.harness.widened`)."""
    bits = "32" if float32 else "64"
    by_id = {c["id"]: (m, c) for m, f in corpus.items() for c in f["cases"]}
    out = []
    for line in lines:
        if line["id"] not in by_id:
            raise VectorsError(f"answer for {line['id']!r}: no such case in the corpus "
                               "(another corpus version?)")
        method, c = by_id[line["id"]]
        if "not_run" in line:
            out.append(Verdict(c["id"], "not run", str(line["not_run"])))
            continue
        if c["result"] != "valid":
            if "error" in line or _has_non_finite(_unportable(line["value"])):
                out.append(Verdict(c["id"], "pass"))
            elif c["result"] == "acceptable":
                out.append(Verdict(c["id"], "acceptable", f"answered outside the notes' domain "
                                   f"({c['comment']}; the reference: {c['expected']['error']})"))
            else:
                out.append(Verdict(c["id"], "FAIL", f"a finite answer to an invalid input "
                                   f"({c['comment']}; the reference: {c['expected']['error']})"))
            continue
        if "error" in line:
            err = line["error"] if isinstance(line["error"], dict) else {"message": line["error"]}
            if err.get("kind") == "outside_domain":
                out.append(Verdict(c["id"], "not applicable", str(err.get("message", ""))))
            else:
                out.append(Verdict(c["id"], "FAIL", f"failed: {_short(str(err.get('message')), 200)}"))
            continue
        try:
            _check_value(method, c, line["value"], bits, conventions)
        except _Wrong as e:
            out.append(_as_read_in_float32(method, c, line["value"], e) if float32
                       else Verdict(c["id"], "FAIL", str(e)))
        else:
            out.append(Verdict(c["id"], "pass"))
    answered = {line["id"] for line in lines}
    for method in sorted({by_id[i][0] for i in answered}):
        for c in corpus[method]["cases"]:
            if c["id"] not in answered:
                out.append(Verdict(c["id"], "FAIL", "no answer (the method is answered for "
                                   "other cases)"))
    return out
