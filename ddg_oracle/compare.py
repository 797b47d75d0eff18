"""One given mesh: which properties apply to it, and every quantity reference vs implementation.

``ddg-oracle check --mesh FILE`` runs the properties that make sense on a
single fixed mesh (agreement with the exact reference: Euler characteristic,
classification, angle defects, turning angles, Gauss-Bonnet, corner angles,
mean curvature, Steiner coefficients, cotan Laplacian, mass matrices, the sign
of each cotan weight, the intrinsic Delaunay Laplacian) on that mesh; ``ddg-oracle compare MESH`` prints, per
protocol method, the largest error of each implementation in units of the
derived bound, and where.  Both take the same mesh arguments:

* a path to an OBJ, OFF, PLY or STL file (:func:`ddg_oracle.meshfiles.read_mesh`);
* a directory: every such file below it (a corpus; one that cannot be read is
  skipped with a note);
* ``pymeshlab:`` -- every sample mesh shipped inside the installed PyMeshLab
  package (``pymeshlab/tests/sample_meshes``), or ``pymeshlab:NAME`` one of them.

The reference needs every vertex to lie in a face: unreferenced vertices are
removed (the remaining ones renumbered in order) with a note.  A mesh the
reference cannot take (non-manifold, a zero-area face, ...) raises the
reference's typed error; named files are then a usage error (exit 2), sample
meshes are skipped with a note.

The matrix checks (cotan Laplacian, intrinsic Delaunay Laplacian) are sparse:
they run on meshes of any size.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ddg_oracle.reference.errors import InputError

from .meshfiles import MeshFileError, read_mesh

SAMPLE_PREFIX = "pymeshlab:"
MESH_SUFFIXES = (".obj", ".off", ".ply", ".stl")
#: largest face count for an exact total area: a float mesh's face areas are square roots
#: of distinct rationals, and their exact sum has a term per face (R2.5 beyond it is not
#: applicable; compare then sums the correctly rounded face areas and widens the bound)
EXACT_SUM_LIMIT = 400


# --- mesh arguments -------------------------------------------------------------------------------


def sample_mesh_dir() -> Path:
    """``pymeshlab/tests/sample_meshes`` of the installed PyMeshLab (InputError if absent)."""
    try:
        import pymeshlab
    except ImportError:
        raise InputError("pymeshlab: sample meshes need the pymeshlab package") from None
    d = Path(pymeshlab.__file__).parent / "tests" / "sample_meshes"
    if not d.is_dir():
        raise InputError(f"pymeshlab: no sample meshes in this installation ({d})")
    return d


def sample_meshes() -> list[Path]:
    """Every mesh file PyMeshLab ships (sorted by path)."""
    d = sample_mesh_dir()
    return sorted(p for p in d.rglob("*") if p.suffix.lower() in MESH_SUFFIXES)


def resolve(args: list[str]) -> list[tuple[str, Path, bool]]:
    """(display name, path, strict) per mesh argument; strict: a named file, whose problems
    are errors, vs a sample mesh found by ``pymeshlab:``, which is skipped with a note."""
    out = []
    for a in args:
        if a.startswith(SAMPLE_PREFIX):
            name = a[len(SAMPLE_PREFIX):]
            d = sample_mesh_dir()
            if not name:
                out += [(f"{SAMPLE_PREFIX}{p.relative_to(d)}", p, False) for p in sample_meshes()]
                continue
            p = d / name
            if not p.is_file():
                names = ", ".join(str(q.relative_to(d)) for q in sample_meshes())
                raise MeshFileError(f"{a}: no such sample mesh (PyMeshLab ships {names})")
            out.append((a, p, True))
        elif Path(a).is_dir():
            # a corpus: every mesh file below it, sorted; one that cannot be read is
            # skipped with a note, as a sample mesh is
            found = sorted(p for p in Path(a).rglob("*")
                           if p.suffix.lower() in MESH_SUFFIXES and p.is_file())
            if not found:
                raise MeshFileError(f"{a}: a directory with no mesh file "
                                    f"({', '.join(MESH_SUFFIXES)}) in it")
            out += [(str(p), p, False) for p in found]
        else:
            out.append((a, Path(a), True))
    return out


@dataclass
class MeshInput:
    """A mesh as read, with unreferenced vertices removed (``note`` says so)."""

    name: str
    V: list
    F: list
    note: str | None = None


def load(name: str, path: Path) -> MeshInput:
    """Read and validate for the reference (typed InputError naming the problem)."""
    V, F = read_mesh(path)
    first: dict = {}
    for k, f in enumerate(F):
        key = frozenset(f)
        if key in first and len(key) == 3:
            same = "the same" if list(F[first[key]]) == list(f) else "the opposite"
            raise MeshFileError(f"{name}: faces {first[key]} and {k} are one triangle "
                                f"{sorted(key)} ({same} orientation): a duplicated face")
        first.setdefault(key, k)
    used = sorted({i for f in F for i in f})
    note = None
    if len(used) < len(V):
        new = {v: k for k, v in enumerate(used)}
        note = (f"{len(V) - len(used)} unreferenced vertices removed (first: "
                f"{next(v for v in range(len(V)) if v not in new)}); the rest renumbered in order")
        V = [V[v] for v in used]
        F = [[new[i] for i in f] for f in F]
    try:
        from ddg_oracle.reference.polyhedral import PolyhedralSurface
        PolyhedralSurface.from_arrays(V, F).metric()      # manifold, no zero-area face
    except InputError as e:
        raise type(e)(f"{name}: {e}") from None
    return MeshInput(name, V, F, note)


def load_all(args: list[str], warn=None) -> list[MeshInput]:
    """Every mesh the arguments name; named files raise, skipped samples go to ``warn``."""
    meshes = []
    for name, path, strict in resolve(args):
        try:
            meshes.append(load(name, path))
        except InputError as e:
            if strict:
                raise
            if warn is not None:
                warn(f"skipped {name}: {e}".replace(f"{name}: {name}: ", f"{name}: "))
            continue
        if meshes[-1].note and warn is not None:
            warn(f"{name}: {meshes[-1].note}")
    return meshes


# --- property examples built from one mesh --------------------------------------------------------


@dataclass
class MeshExamples:
    """The example objects the properties take, built once from one mesh (their exact
    values are cached on them, so several properties and implementations share them)."""

    mesh: MeshInput
    _cache: dict = field(default_factory=dict, repr=False)

    def _get(self, key, build):
        if key not in self._cache:
            self._cache[key] = build()
        return self._cache[key]

    @property
    def surface(self):
        from ddg_oracle.properties import memo
        from ddg_oracle.properties.example import surface_key
        from ddg_oracle.reference.polyhedral import PolyhedralSurface

        def build():
            s = PolyhedralSurface.from_arrays(self.mesh.V, self.mesh.F)
            # the mesh case's surface is this one (the same exact positions and faces):
            # its metric is computed once per process, not once per example kind
            memo.DRAWN.shared(surface_key(s.positions, self.mesh.F), lambda: s)
            return s
        return self._get("surface", build)

    @property
    def facts(self) -> dict:
        def build():
            t = self.surface.triangulation
            return dict(n=t.n_vertices, faces=t.n_faces, chi=t.euler_characteristic(),
                        boundary=len(t.boundary_loops()), orientable=t.is_orientable(),
                        components=len(t.components()))
        return self._get("facts", build)

    def surface_case(self):
        from ddg_oracle.reference.combinatorics import Classification
        from ddg_oracle.properties.strategies import Example

        def build():
            t, f = self.surface.triangulation, self.facts
            cls = t.classify() if f["components"] == 1 else \
                Classification(f["orientable"], -1, f["boundary"], f["chi"])
            return Example.of_triangulation(t, self.surface.positions, cls, self.mesh.name)
        return self._get("surface_case", build)

    def curvature_case(self):
        from ddg_oracle.properties.strategies import Example
        return self._get("curvature_case", lambda: Example.of_surface(
            self.surface, self.facts["chi"], self.mesh.name))

    def mesh_case(self):
        from ddg_oracle.properties.strategies import Example
        return self._get("mesh_case", lambda: Example.of_mesh(
            self.surface.positions, tuple(tuple(f) for f in self.mesh.F), self.mesh.name))

    def example(self, kind: str):
        return {"surface": self.surface_case, "curvature": self.curvature_case,
                "mesh": self.mesh_case}[kind]()


def _closed(f):
    return None if f["boundary"] == 0 else "the mesh has a boundary"


def _connected(f):
    return None if f["components"] == 1 else f"{f['components']} components"


def _all(*conds):
    def check(f):
        for c in conds:
            why = c(f)
            if why:
                return why
        return None
    return check


def _has_boundary(f):
    return None if f["boundary"] else "the mesh is closed"


def _orientable(f):
    return None if f["orientable"] else "the mesh is not orientable"


def _exact_sum(f):
    return None if f["faces"] <= EXACT_SUM_LIMIT else \
        f"{f['faces']} faces > {EXACT_SUM_LIMIT} (exact total area: one square root per face)"


#: catalog ID -> (example kind, why not applicable to a mesh with these facts or None)
FILE_PROPERTIES: dict[str, tuple[str, object]] = {
    "D1.6": ("surface", lambda f: None),
    "T1.1 / C1.2": ("surface", _all(_closed, _connected)),
    "R1.6": ("surface", _all(_orientable, _connected)),
    "D2.2": ("curvature", lambda f: None),
    "R2.4": ("curvature", _has_boundary),
    "T2.6": ("curvature", _closed),
    "D2.6": ("curvature", lambda f: None),
    "D2.3": ("curvature", _orientable),
    "R2.5": ("curvature", _all(_closed, _orientable, _exact_sum)),
    "D3.1": ("mesh", lambda f: None),
    "T3.9": ("mesh", lambda f: None),
    "E3.12": ("mesh", lambda f: None),
    "L3.7": ("mesh", lambda f: None),
    "D4.8 / R4.9": ("mesh", lambda f: None),
}


def run_mesh_properties(examples: MeshExamples, impl, only=None, counterpart=None,
                        convention=None) -> list:
    """Every property of :data:`FILE_PROPERTIES` (or ``only`` those IDs) on one mesh."""
    from ddg_oracle.properties.registry import all_properties
    from ddg_oracle.properties.runner import NOT_APPLICABLE, Result, run_on_example
    from ddg_oracle.properties.protocol import implementation_name

    results = []
    for p in all_properties():
        if p.id not in FILE_PROPERTIES or (only is not None and p.id not in only):
            continue
        kind, why_not = FILE_PROPERTIES[p.id]
        why = why_not(examples.facts)
        if why:
            results.append(Result(p.id, p.name, implementation_name(impl), NOT_APPLICABLE,
                                  source=examples.mesh.name, note=why))
            continue
        results.append(run_on_example(p, impl, examples.example(kind), examples.mesh.name,
                                      counterpart=counterpart, convention=convention))
    return results


# --- compare: every quantity, reference vs implementation -----------------------------------------


@dataclass
class Comparison:
    """One quantity of one implementation on one mesh."""

    quantity: str
    implementation: str
    status: str                      # "agrees", "DIFFERS", "crashed", "not applicable", "skipped"
    worst: float | None = None       # largest error / bound (None: exact quantity or none)
    error: float | None = None       # the error there
    bound: float | None = None
    where: str | None = None
    expected: object = None
    observed: object = None
    over: int = 0                    # elements whose error exceeds the bound
    elements: int = 0
    note: str | None = None


def _epsilon_of(impl):
    from ddg_oracle.properties.protocol import at_machine_epsilon, machine_epsilon
    return at_machine_epsilon(machine_epsilon(impl))


def _worst(err: np.ndarray, bound: np.ndarray):
    """(index, largest err / bound, how many exceed their bound)."""
    from ddg_oracle.properties.harness import ratios, worst
    k, ratio = worst(err, bound)
    return k, ratio, int(np.sum(ratios(err, bound) > 1))


def _numeric(quantity, name, got, want, bound, where_of) -> Comparison:
    got = np.asarray(got, dtype=np.float64)
    want = np.asarray(want, dtype=np.float64)
    if got.shape != want.shape:
        return Comparison(quantity, name, "DIFFERS", note=f"shape {got.shape}, expected {want.shape}")
    bad = ~np.isfinite(got)
    if bad.any():
        k = tuple(int(x) for x in np.argwhere(bad)[0])
        return Comparison(quantity, name, "DIFFERS", where=where_of(k), expected=float(want[k]),
                          observed=float(got[k]), over=int(bad.sum()), elements=got.size,
                          note="non-finite value")
    err = np.abs(got - want)
    if err.size == 0:                  # e.g. the interior edges of a single triangle: none
        return Comparison(quantity, name, "agrees", elements=0, note="no element to compare")
    k, ratio, over = _worst(err, np.broadcast_to(bound, err.shape))
    return Comparison(quantity, name, "agrees" if over == 0 else "DIFFERS", worst=ratio,
                      error=float(err[k]), bound=float(np.broadcast_to(bound, err.shape)[k]),
                      where=where_of(k), expected=float(want[k]), observed=float(got[k]),
                      over=over, elements=err.size)


def compare_mesh(mesh: MeshInput, impls, reference) -> list[Comparison]:
    """Every protocol method every implementation has, against the reference, on ``mesh``."""
    from ddg_oracle.properties.protocol import METHODS, OutsideDomain, capabilities, implementation_name

    ex = MeshExamples(mesh)
    V = np.array(mesh.V, dtype=np.float64)
    F = np.array(mesh.F, dtype=np.int64)
    facts = ex.facts
    expected_cache: dict = {}

    def expected(method):
        if method not in expected_cache:
            if method == "area_gradient":       # Exact.area_gradient_bound holds it
                expected_cache[method] = None
            elif method == "area" and facts["faces"] > EXACT_SUM_LIMIT:
                from ddg_oracle.properties.bounds import total_area_view
                expected_cache[method] = total_area_view(ex.surface.metric())
            else:
                expected_cache[method] = getattr(reference, method)(V, F)
        return expected_cache[method]

    rows = []
    for impl in impls:
        name = implementation_name(impl)
        caps = capabilities(impl)
        for method in METHODS:
            if method not in caps:
                rows.append(Comparison(method, name, "not applicable", note="not provided"))
                continue
            if method == "genus" and facts["components"] != 1:
                rows.append(Comparison(method, name, "not applicable",
                                       note=f"{facts['components']} components"))
                continue
            if method == "edge_mean_curvature" and not facts["orientable"]:
                rows.append(Comparison(method, name, "not applicable", note="not orientable"))
                continue
            if method in ("planar_delaunay", "intrinsic_delaunay_triangulation",
                          "planar_flip_to_delaunay", "solve_dirichlet"):
                rows.append(Comparison(method, name, "not applicable",
                                       note="not unique, or needs more than a mesh: checked by "
                                            "the properties (T4.1, A4.13, L4.3 / P4.4, T3.2, "
                                            "C3.4 / T3.5)"))
                continue
            try:
                got = getattr(impl, method)(V, F)
            except OutsideDomain as e:          # the implementation has no value on this mesh
                rows.append(Comparison(method, name, "not applicable", note=str(e)))
                continue
            except Exception as e:  # noqa: BLE001  (a crash of the implementation is a result)
                rows.append(Comparison(method, name, "crashed", note=f"{type(e).__name__}: {e}"))
                continue
            with _epsilon_of(impl):
                rows.append(_compare_one(method, name, got, expected(method), ex))
    return rows


def _matrix(quantity, name, got, want, bound) -> Comparison:
    """A matrix against the exact one's float view ``want`` within the entry bounds
    ``bound`` (both scipy sparse): over the stored entries of either, any mesh size.  The
    elements counted are the entries of ``want``'s pattern and the implementation's."""
    import scipy.sparse as sp
    A = sp.csr_matrix(got, dtype=np.float64) if sp.issparse(got) else \
        np.asarray(got, dtype=np.float64)
    if A.shape != want.shape:
        return Comparison(quantity, name, "DIFFERS", note=f"shape {A.shape}, expected {want.shape}")
    A = sp.csr_matrix(A)
    A.sum_duplicates()
    if not np.all(np.isfinite(A.data)):
        C = A.tocoo()
        k = int(np.argmax(~np.isfinite(C.data)))
        i, j = int(C.row[k]), int(C.col[k])
        return Comparison(quantity, name, "DIFFERS", where=f"entry {(i, j)}",
                          expected=float(want[i, j]), observed=float(C.data[k]),
                          over=int((~np.isfinite(C.data)).sum()), elements=A.nnz,
                          note="non-finite value")
    err = abs(A - want).tocoo()
    elements = (abs(A) + abs(want)).nnz
    if err.nnz == 0:                   # equal floats everywhere: name the first entry
        W = sp.csr_matrix(want).tocoo()
        if W.nnz == 0:
            return Comparison(quantity, name, "agrees", worst=0.0, error=0.0, elements=elements)
        i, j = int(W.row[0]), int(W.col[0])
        return Comparison(quantity, name, "agrees", worst=0.0, error=0.0,
                          bound=float(bound[i, j]), where=f"entry {(i, j)}",
                          expected=float(W.data[0]), observed=float(A[i, j]), elements=elements)
    from ddg_oracle.properties.harness import entries_at
    b = entries_at(bound, err.row, err.col)
    (k,), ratio, over = _worst(err.data, b)
    i, j = int(err.row[k]), int(err.col[k])
    return Comparison(quantity, name, "agrees" if over == 0 else "DIFFERS", worst=ratio,
                      error=float(err.data[k]), bound=float(b[k]), where=f"entry {(i, j)}",
                      expected=float(want[i, j]), observed=float(A[i, j]), over=over,
                      elements=elements)


def loop_edges(loops) -> list:
    """The undirected edges of boundary loops (consecutive vertices, the last to the first),
    sorted: two answers of ``boundary_loops`` agree when these and the loop counts do (a
    loop may start anywhere and run either way)."""
    return sorted(tuple(sorted((int(a), int(b)))) for loop in loops
                  for a, b in zip(loop, list(loop[1:]) + list(loop[:1])))


def derived_bound(method: str, ex: MeshExamples, want=None):
    """The derived bound on |implementation - exact| for each element of ``method``'s
    answer on ``ex``'s mesh, at the current machine epsilon (:func:`_epsilon_of`): an array
    of the answer's shape, a scipy matrix (Laplacians), or {edge: bound}
    (``edge_mean_curvature``).  ``want``: the reference's ``area`` answer (a (total,
    widening) pair above :data:`EXACT_SUM_LIMIT` faces).  Used by ``compare`` and by the
    test vectors (:mod:`ddg_oracle.vectors`)."""
    from ddg_oracle.properties import bounds as cv
    from ddg_oracle.properties.harness import Exact
    if method in ("corner_angles", "angle_defects", "edge_mean_curvature", "area"):
        case = ex.curvature_case()
        if method == "corner_angles":
            return cv.corner_tolerances(case)
        if method == "angle_defects":
            return cv.vertex_tolerances(case, cv.corner_tolerances(case))
        if method == "edge_mean_curvature":
            return cv.edge_mean_curvature_tolerances(case)
        extra = want[1] if isinstance(want, tuple) else 0.0
        return cv.area_tolerance(case) + extra
    if method == "intrinsic_delaunay_laplacian":
        from ddg_oracle.properties.delaunay import DelaunayExact
        return DelaunayExact.of(ex.mesh_case()).Bs
    X = Exact.of(ex.mesh_case())            # once per mesh (shared with the properties)
    if method == "cotan_laplacian":
        return X.Bs
    if method == "area_gradient":           # T3.9's bound on an implementation's own gradient
        return X.area_gradient_bound(ex.mesh_case().arrays()[0])[1]
    vb, bb = X.vertex_area_bounds
    return vb if method == "vertex_areas_voronoi" else bb


def _compare_one(method, name, got, want, ex) -> Comparison:
    if method in ("euler_characteristic", "is_orientable", "genus"):
        same = type(want)(got) == want
        return Comparison(method, name, "agrees" if same else "DIFFERS", expected=want,
                          observed=got, elements=1, over=int(not same))
    if method == "boundary_loops":
        same = len(got) == len(want) and loop_edges(got) == loop_edges(want)
        return Comparison(method, name, "agrees" if same else "DIFFERS",
                          expected=f"{len(want)} loops", observed=f"{len(got)} loops",
                          elements=1, over=int(not same),
                          note=None if same else f"loops {[list(map(int, x)) for x in got]}"[:300])
    if method == "is_locally_delaunay":
        got, want = np.asarray(got, dtype=bool), np.asarray(want, dtype=bool)
        diff = np.argwhere(got != want)
        note = None if not len(diff) else (f"face {diff[0][0]}, corner {diff[0][1]} (exact "
                                           "ties may go either way)")
        return Comparison(method, name, "agrees" if not len(diff) else "DIFFERS",
                          elements=int(want.size), over=int(len(diff)), note=note)
    bound = derived_bound(method, ex, want)
    if method == "corner_angles":
        return _numeric(method, name, got, want, bound, lambda k: f"face {k[0]}, corner {k[1]}")
    if method == "edge_mean_curvature":
        got = {(int(min(i, j)), int(max(i, j))): float(h) for (i, j), h in dict(got).items()}
        if set(got) != set(want):
            return Comparison(method, name, "DIFFERS", note="not the same set of interior edges",
                              expected=len(want), observed=len(got))
        keys = sorted(want)
        return _numeric(method, name, [got[k] for k in keys], [want[k] for k in keys],
                        np.array([bound[k] for k in keys]), lambda k: f"edge {keys[k[0]]}")
    if method == "area":
        total = want[0] if isinstance(want, tuple) else want
        return _numeric(method, name, [float(got)], [float(total)], bound, lambda k: "total")
    if method in ("cotan_laplacian", "intrinsic_delaunay_laplacian"):
        from ddg_oracle.properties.delaunay import DelaunayExact
        from ddg_oracle.properties.harness import Exact
        exact = (Exact if method == "cotan_laplacian" else DelaunayExact).of(ex.mesh_case())
        return _matrix(method, name, got, exact.Ls, bound)
    if method == "area_gradient":
        from ddg_oracle.properties.harness import Exact
        exact = Exact.of(ex.mesh_case()).area_gradient_bound(ex.mesh_case().arrays()[0])[0]
        return _numeric(method, name, np.asarray(got, dtype=np.float64), exact, bound,
                        lambda k: f"vertex {k[0]}, coordinate {k[1]}")
    return _numeric(method, name, np.asarray(got).reshape(-1), want, bound,
                    lambda k: f"vertex {k[0]}")


def format_comparisons(mesh: MeshInput, rows: list[Comparison]) -> str:
    """The compare table: one line per quantity and implementation."""
    head = f"{mesh.name}: {len(mesh.V)} vertices, {len(mesh.F)} faces"
    if mesh.note:
        head += f" ({mesh.note})"
    lines = [head, ""]
    cols = ("quantity", "implementation", "status", "max err/bound", "where", "expected",
            "observed")
    table = [cols]
    for c in rows:
        ratio = "-" if c.worst is None else ("inf" if math.isinf(c.worst) else f"{c.worst:.3g}")
        if c.over and c.elements > 1:
            ratio += f" ({c.over}/{c.elements} over)"
        table.append((c.quantity, c.implementation, c.status, ratio, c.where or "-",
                      _short(c.expected), _short(c.observed) + (f"  [{c.note}]" if c.note else "")))
    widths = [max(len(r[k]) for r in table) for k in range(len(cols) - 1)]
    for r in table:
        lines.append("  ".join(x.ljust(w) for x, w in zip(r, widths)) + "  " + r[-1])
    return "\n".join(lines)


def _short(x) -> str:
    if x is None:
        return "-"
    if isinstance(x, float):
        return f"{x:.17g}"
    return str(x)
