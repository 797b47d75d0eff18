"""Every quantity of one given mesh, reference vs implementation.

``ddg-oracle compare MESH`` prints, per protocol method, the largest error of each
implementation in units of the derived bound, and where; ``ddg-oracle check --mesh FILE``
runs the properties that make sense on a single fixed mesh
(:func:`ddg_oracle.application.meshes.run_mesh_properties`).  Both take the same mesh
arguments, read and made into examples by :mod:`ddg_oracle.application.meshes`.

The matrix checks (cotan Laplacian, intrinsic Delaunay Laplacian) are sparse:
they run on meshes of any size.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..protocol.methods import WHERE
from ..reference.errors import ExactArithmeticLimit, InputError

from .meshes import MeshExamples, MeshInput, as_read_by

# --- compare: every quantity, reference vs implementation -----------------------------------------


@dataclass
class Comparison:
    """One quantity of one implementation on one mesh."""

    quantity: str
    implementation: str
    status: str        # "agrees", "DIFFERS", "crashed", "undecided", "not applicable", "skipped"
    worst: float | None = None       # largest error / bound (None: exact quantity or none)
    error: float | None = None       # the error there
    bound: float | None = None
    where: str | None = None
    expected: object = None
    observed: object = None
    over: int = 0                    # elements whose error exceeds the bound
    elements: int = 0
    note: str | None = None
    # the conventions (properties.conventions) under which a differing answer agrees
    explained_by: tuple = ()


def _worst(err: np.ndarray, bound: np.ndarray):
    """(index, largest err / bound, how many exceed their bound)."""
    from ..properties.harness import ratios, worst
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
    bound = np.broadcast_to(bound, err.shape)
    # an infinite bound (floats cannot compute that element: a needle's normal) decides
    # nothing; a quantity with no element decided is undecided, not "agrees"
    open_ = ~(bound < np.inf)
    if open_.all():
        k = tuple(int(x) for x in np.argwhere(open_)[0])
        return Comparison(quantity, name, "undecided", where=where_of(k),
                          expected=float(want[k]), observed=float(got[k]), elements=err.size,
                          note="the derived bound is infinite on every element (floats "
                               "cannot compute them here): nothing is decided")
    k, ratio, over = _worst(err, bound)
    note = (f"{int(open_.sum())} of {err.size} elements not decided (infinite bound)"
            if open_.any() else None)
    return Comparison(quantity, name, "agrees" if over == 0 else "DIFFERS", worst=ratio,
                      error=float(err[k]), bound=float(bound[k]),
                      where=where_of(k), expected=float(want[k]), observed=float(got[k]),
                      over=over, elements=err.size, note=note)


def compare_mesh(mesh: MeshInput, impls, reference, workers: int = 1,
                 methods=None, explain: bool = True) -> list[Comparison]:
    """Every protocol method every implementation has, against the reference, on ``mesh``:
    how each answer compares is its declared quantity's
    (:data:`ddg_oracle.properties.registry.QUANTITIES`).

    ``workers > 1``: the exact values and their bounds are computed by that many worker
    processes, one method at a time (the costly chapters first), while this process asks
    the implementations; the rows are the same as with one worker.  ``methods``: only
    these protocol methods (default: every one).  An implementation's answers are first
    mapped from the conventions it declares (:mod:`ddg_oracle.properties.conventions`);
    with ``explain``, a differing answer is tried under the conventions it did not
    declare, and those under which it agrees are named (``explained_by``)."""
    from ..properties.precision import format_of
    from ..protocol.methods import (METHODS, capabilities, implementation_name,
                                                machine_epsilon)
    # each implementation against the exact values of the input it reads (as_read_by)
    formats: dict = {}
    for impl in impls:
        formats.setdefault(format_of(machine_epsilon(impl)).bits, []).append(impl)
    rows, plans = [], []
    for group in formats.values():
        try:
            read = as_read_by(mesh, machine_epsilon(group[0]))
        except InputError as e:
            rows += [Comparison(m, implementation_name(i), "not applicable", note=str(e))
                     for i in group for m in METHODS if m in capabilities(i)
                     and (methods is None or m in methods)]
            continue
        plans.append(_Plan.of(read, group, methods))
    # one pool for every reading: a float32 reading's exact values are computed beside the
    # float64 one's, not after them (two exact intrinsic flips that each ran to the time
    # limit took 2 x 20 s per mesh of the CGAL corpus, one after the other)
    asked = [(plan.mesh, plan.asked) for plan in plans]
    pending = _expected_in_workers(asked, workers) \
        if workers > 1 and any(a for _, a in asked) else None
    try:
        answers = [_answers(plan.todo, plan.V, plan.F) for plan in plans]
        done = pending() if pending is not None else None
    except BaseException:
        # a signal or an error while the library answers: the pool is stopped here, not
        # left to the interpreter's exit (whose Pool.__del__ then writes to pipes of killed
        # workers, and multiprocessing's resource tracker prints tracebacks)
        if pending is not None:
            pending.close()
        raise
    for k, plan in enumerate(plans):
        expected = done(k) if done is not None else _ExpectedValues(
            plan.ex, lambda method, plan=plan: getattr(reference, method)(plan.V, plan.F))
        rows += _rows(plan, answers[k], expected, explain)
    if len(formats) == 1:
        return rows
    order = {implementation_name(i): k for k, i in enumerate(impls)}
    return sorted(rows, key=lambda r: order.get(r.implementation, len(order)))


@dataclass
class _Plan:
    """What :func:`compare_mesh` asks on one reading of the mesh: (impl, method, why not
    applicable) per pair, and the machine epsilons of each asked method's bounds."""

    mesh: MeshInput
    ex: MeshExamples
    V: np.ndarray
    F: np.ndarray
    todo: list
    asked: dict

    @classmethod
    def of(cls, mesh: MeshInput, impls, methods) -> "_Plan":
        from ..protocol.methods import METHODS, capabilities
        from ..properties.conventions import bounds_epsilon_of
        from ..properties.registry import all_quantities, unmet
        quantities = all_quantities()
        ex = MeshExamples(mesh)
        V, F = np.array(mesh.V, dtype=np.float64), np.array(mesh.F, dtype=np.int64)
        asked: dict = {}                    # method -> the machine epsilons of its bounds
        todo = []
        for impl in impls:
            caps = capabilities(impl)
            for method in METHODS:
                if methods is not None and method not in methods:
                    continue
                q = quantities[method]
                why = ("not provided" if method not in caps else q.not_on_a_mesh
                       or unmet(q.requires, ex.facts))
                todo.append((impl, method, why))
                if not why:
                    asked.setdefault(method, set()).add(bounds_epsilon_of(impl, (V, F)))
        return cls(mesh, ex, V, F, todo, asked)


def _rows(plan: _Plan, answers, expected, explain) -> list:
    """The comparisons of one reading's answers with its expected values."""
    from ..protocol.methods import at_machine_epsilon, implementation_name
    from ..properties.conventions import bounds_epsilon_of, declared
    from ..properties.harness import widened
    from ..properties.registry import all_quantities

    quantities = all_quantities()
    ex, V, F = plan.ex, plan.V, plan.F
    rows = []
    for impl, method, got in answers:
        if isinstance(got, Comparison):
            rows.append(got)
            continue
        epsilon = bounds_epsilon_of(impl, (V, F))
        with at_machine_epsilon(epsilon):
            try:
                want, bound = expected(quantities[method], epsilon)
            except ExactArithmeticLimit as e:
                # the exact reference gave up (time or precision): nothing is said of the
                # implementation's answer here
                rows.append(Comparison(method, implementation_name(impl), "undecided",
                                       note=f"the exact reference gave up: {e}"))
                continue
            except InputError as e:
                # the quantity has no value on this mesh (a folded edge's dihedral angle
                # is +-pi: no mean curvature); the other quantities stand
                rows.append(Comparison(method, implementation_name(impl), "not applicable",
                                       note=f"no exact value on this mesh: {e}"))
                continue
            # what a declared convention's map cannot carry back exactly (a pointwise
            # curvature's area): this implementation's bound only
            bound = widened(declared(impl), method, got, ex.example(), bound)
            row = _compare_one(quantities[method], implementation_name(impl), got, want, ex,
                               bound)
            if explain and row.status == "DIFFERS":
                row.explained_by = _explained(quantities[method], impl, got, want, ex, bound,
                                              V, F)
            rows.append(row)
    return rows


def _answers(todo, V, F) -> list:
    """(impl, method, answer on the reference's conventions, or a Comparison saying why
    there is none) for each of ``todo``'s (impl, method, why not applicable)."""
    from ..properties.conventions import declared, to_reference
    from ..protocol.answers import MalformedAnswer, read, short
    from ..protocol.methods import OutsideDomain, implementation_name
    answers = []
    for impl, method, why in todo:
        name = implementation_name(impl)
        if why:
            answers.append((impl, method, Comparison(method, name, "not applicable", note=why)))
            continue
        try:
            got = getattr(impl, method)(V, F)
        except OutsideDomain as e:          # the implementation has no value on this mesh
            got = Comparison(method, name, "not applicable", note=str(e))
        except Exception as e:  # noqa: BLE001  (a crash of the implementation is a result)
            got = Comparison(method, name, "crashed", note=f"{type(e).__name__}: {e}")
        else:
            # not of its method's kind (a string, 2.5 for an integer): it differs, said so,
            # before anything reads it (int(2.5) == 2 would agree)
            try:
                got = to_reference(declared(impl), method, read(method, got), V, F)
            except MalformedAnswer as e:
                got = Comparison(method, name, "DIFFERS", note=str(e), observed=short(got))
        answers.append((impl, method, got))
    return answers


def _explained(q, impl, got, want, ex, bound, V, F) -> tuple:
    """The conventions under which ``got`` (already mapped from the declared ones)
    agrees with the exact answer: what a failing implementation probably follows."""
    from ..properties.conventions import declared, explaining
    from ..protocol.methods import implementation_name

    def agrees(mapped) -> bool:
        return _compare_one(q, implementation_name(impl), mapped, want, ex,
                            bound).status == "agrees"
    return tuple(c.name for c in explaining(q.method, got, V, F, agrees, declared(impl)))


class _ExpectedValues:
    """(the values to compare with, their bound) per method and machine epsilon, computed
    once each: the float views do not depend on the epsilon, the bounds do."""

    def __init__(self, ex: "MeshExamples", answer):
        self.ex, self.answer, self.wanted, self.bounds = ex, answer, {}, {}
        self.gave_up: dict = {}

    def __call__(self, q, epsilon: float):
        """(want, bound); the exact reference's giving up (its time limit per example,
        ``DDG_EXAMPLE_TIME_LIMIT`` seconds of CPU time, or its precision limit) raised as
        :class:`~ddg_oracle.reference.errors.ExactArithmeticLimit`, once per method.  CPU
        time, not wall-clock: whether the reference decides a quantity on a mesh does not
        depend on what else runs (the survey computes two readings' values side by side;
        with a wall-clock limit they shared the cores and two of MeshLib's intrinsic
        Delaunay rows became undecided)."""
        from ..properties.profiles import example_time_limit
        from ..reference.errors import BeyondFloatRange, ExactArithmeticLimit
        if q.method in self.gave_up:
            raise self.gave_up[q.method]
        try:
            try:
                with example_time_limit(f"[{q.method}] the exact reference on this mesh",
                                        cpu=True):
                    return self._values(q, epsilon)
            except OverflowError as e:
                # a float view or bound of an exact value beyond the float range (a needle)
                raise BeyondFloatRange(f"[{q.method}] an exact value lies beyond the float "
                                       f"range on this mesh ({e})") from e
        except ExactArithmeticLimit as e:
            self.gave_up[q.method] = e
            raise

    def _values(self, q, epsilon: float):
        from ..protocol.methods import at_machine_epsilon
        if q.method not in self.wanted:
            answer = lambda: self.answer(q.method)       # noqa: E731
            self.wanted[q.method] = q.expected(self.ex.example(), answer) if q.expected \
                else answer()
        want = self.wanted[q.method]
        if (q.method, epsilon) not in self.bounds:
            with at_machine_epsilon(epsilon):
                self.bounds[q.method, epsilon] = _bound_of(q, self.ex, want)
        return want, self.bounds[q.method, epsilon]


def _bound_of(q, ex: "MeshExamples", want):
    """The quantity's derived bound for ``want`` (flags: where either answer agrees; None
    for exact kinds: integers, loops...)."""
    if q.kind in ("integer", "boolean", "loops") or q.bound is None:
        return None
    return q.bound(ex.example(), want)


class _Worker:
    """What a compare worker process keeps between its methods: each reading's mesh and
    examples, and the reference (one per process, set by the pool's initializer, read only
    in this module)."""

    meshes = examples = reference = None


def _start_worker(meshes: list) -> None:
    from ..oracles.exact_reference import ReferenceImplementation
    _Worker.meshes = meshes
    _Worker.examples = [MeshExamples(m) for m in meshes]
    _Worker.reference = ReferenceImplementation()


def _expected_in_worker(job):
    """(reading, method, the pickle of {epsilon: (want, bound)}) in a worker; an exception
    comes back as a value.  Pickled here and unpickled by the caller: the pool's result
    thread would otherwise import the values' modules (scipy.sparse, ours) while the main
    thread may be importing them too, and two threads importing one package's circular
    modules deadlock (the main thread's reference raised ``_DeadlockError``, reported as
    its crash)."""
    import pickle
    from ..properties.registry import all_quantities
    k, method, epsilons = job
    V = np.array(_Worker.meshes[k].V, dtype=np.float64)
    F = np.array(_Worker.meshes[k].F, dtype=np.int64)
    values = _ExpectedValues(_Worker.examples[k],
                             lambda m: getattr(_Worker.reference, m)(V, F))
    q = all_quantities()[method]
    try:
        got = {e: values(q, e) for e in sorted(epsilons)}
    except Exception as e:  # noqa: BLE001  (raised again in the parent, where it is asked for)
        got = e
    return k, method, pickle.dumps(got)


def _expected_in_workers(readings: list, workers: int):
    """Start computing every asked method's values and bounds of each reading ((mesh,
    {method: epsilons}) pairs) in ``workers`` worker processes; returns a function that
    waits for them and gives, per reading, a function answering as :class:`_ExpectedValues`."""
    from ..protocol.methods import METHODS
    # the later chapters hold the costly quantities (curvature, Laplacians, Delaunay): first,
    # each reading's in turn
    jobs = [(k, m, asked[m]) for m in reversed(METHODS)
            for k, (_, asked) in enumerate(readings) if m in asked]
    from .containment import worker_context
    pool = worker_context().Pool(min(workers, len(jobs)), _start_worker,
                                 ([mesh for mesh, _ in readings],))
    running = pool.imap_unordered(_expected_in_worker, jobs)

    def close():
        pool.terminate()
        pool.join()

    def wait():
        import pickle
        try:
            done = {(k, method): pickle.loads(got) for k, method, got in running}   # here
        finally:
            close()

        def reading(k):
            def expected(q, epsilon):
                got = done[k, q.method]
                if isinstance(got, BaseException):
                    raise got       # for this method's rows only: the others stand
                return got[epsilon]
            return expected
        return reading
    wait.close = close
    return wait


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
    from ..properties.harness import entries_at
    b = entries_at(bound, err.row, err.col)
    (k,), ratio, over = _worst(err.data, b)
    i, j = int(err.row[k]), int(err.col[k])
    # as in _numeric: an entry whose bound is infinite decides nothing
    open_ = int(np.sum(~(b < np.inf)))
    return Comparison(quantity, name, "agrees" if over == 0 else "DIFFERS", worst=ratio,
                      error=float(err.data[k]), bound=float(b[k]), where=f"entry {(i, j)}",
                      expected=float(want[i, j]), observed=float(A[i, j]), over=over,
                      elements=elements,
                      note=(f"{open_} differing entries not decided (infinite bound)"
                            if open_ else None))


def loop_edges(loops) -> list:
    """The undirected edges of boundary loops (consecutive vertices, the last to the first),
    sorted: two answers of ``boundary_loops`` agree when these and the loop counts do (a
    loop may start anywhere and run either way)."""
    return sorted(tuple(sorted((int(a), int(b)))) for loop in loops
                  for a, b in zip(loop, list(loop[1:]) + list(loop[:1])))


def _compare_one(q, name, got, want, ex, bound=None) -> Comparison:
    """One answer against ``want`` by its quantity's kind (``bound``: its derived bound,
    computed here if None)."""
    method = q.method
    if q.kind in ("integer", "boolean"):
        same = got == want                 # an int or a bool (protocol.answers.normalized)
        return Comparison(method, name, "agrees" if same else "DIFFERS", expected=want,
                          observed=got, elements=1, over=int(not same))
    if q.kind == "loops":
        same = len(got) == len(want) and loop_edges(got) == loop_edges(want)
        return Comparison(method, name, "agrees" if same else "DIFFERS",
                          expected=f"{len(want)} loops", observed=f"{len(got)} loops",
                          elements=1, over=int(not same),
                          note=None if same else f"loops {[list(map(int, x)) for x in got]}"[:300])
    if bound is None:
        bound = _bound_of(q, ex, want)
    if q.kind == "flags":
        got, want = np.asarray(got, dtype=bool), np.asarray(want, dtype=bool)
        either = np.zeros(want.shape, dtype=bool) if bound is None else np.asarray(bound)
        diff = np.argwhere((got != want) & ~either)
        ties = int(((got != want) & either).sum())
        if len(diff):
            f, c = diff[0]
            note = (f"face {f}, corner {c}: {'' if want[f, c] else 'not '}Delaunay, not a tie"
                    + (f"; and {ties} ties decided the other way" if ties else ""))
        else:
            note = (f"{ties} ties (cot sums within the float bound of 0) decided the other "
                    "way: either answer agrees") if ties else None
        return Comparison(method, name, "agrees" if not len(diff) else "DIFFERS",
                          elements=int(want.size), over=int(len(diff)), note=note)
    if q.kind == "edges":
        got = {(int(min(i, j)), int(max(i, j))): float(h) for (i, j), h in dict(got).items()}
        if set(got) != set(want):
            return Comparison(method, name, "DIFFERS", note="not the same set of interior edges",
                              expected=len(want), observed=len(got))
        keys = sorted(want)
        return _numeric(method, name, [got[k] for k in keys], [want[k] for k in keys],
                        np.array([bound[k] for k in keys]), lambda k: f"edge {keys[k[0]]}")
    if q.kind == "matrix":
        return _matrix(method, name, got, want, bound)
    if q.element == "total":
        return _numeric(method, name, [float(got)], [float(want)], bound, WHERE["total"])
    got, shape = np.asarray(got, dtype=np.float64), np.shape(want)
    if got.size == int(np.prod(shape)):    # e.g. corner angles as one flat (3m,) array
        got = got.reshape(shape)
    return _numeric(method, name, got, want, bound, WHERE[q.element])


def diagnose(mesh, impl, methods, faces_limit: int = 200) -> list[dict]:
    """How each of ``methods`` (the protocol methods a failing property called) that
    ``impl`` has answers on a counterexample ``mesh`` = (V, F), against the exact reference:
    compare's row per method (quantity, status, where, expected, observed, worst, note).
    The report names from these which method is wrong, and where ("cotan_laplacian:
    entry (0, 1) expected -0.5, observed 0.5").  Empty for a mesh compare does not take
    (a vertex used by no face, a degenerate face), a large one, or methods whose answer
    one mesh does not determine."""
    from ..oracles.exact_reference import ReferenceImplementation
    from ..protocol.methods import capabilities
    from ..reference.polyhedral import PolyhedralSurface
    V, F = mesh
    methods = set(methods) & capabilities(impl)
    if not methods or len(F) > faces_limit:
        return []
    if len({v for f in F for v in f}) < len(V):
        return _diagnose_unused(V, F, impl, methods)
    try:
        PolyhedralSurface.from_arrays(V, F).metric()
    except (InputError, ValueError):
        return []
    rows = compare_mesh(MeshInput("counterexample", V, F), [impl], ReferenceImplementation(),
                        workers=1, methods=methods)
    return [{"quantity": c.quantity, "status": c.status, "where": c.where,
             "expected": value_text(c.expected), "observed": value_text(c.observed),
             "worst": c.worst, "note": c.note, "explained_by": list(c.explained_by)}
            for c in rows if c.status in ("agrees", "DIFFERS", "crashed")]


def _diagnose_unused(V, F, impl, methods) -> list[dict]:
    """The diagnosis on a mesh with vertices no face uses, which compare does not take: an
    answer sized for the used vertices only, that agrees on the mesh without the others,
    is the convention unused_vertices=dropped (LaPy's); anything else says nothing."""
    from ..properties.conventions import declared, to_reference
    from ..protocol.methods import METHODS
    used = sorted({int(v) for f in F for v in f})
    new = {v: k for k, v in enumerate(used)}
    compact = ([list(V[v]) for v in used], [[new[int(v)] for v in f] for f in F])
    out = []
    for method in sorted(methods):
        if METHODS[method].arguments != ("V", "F"):
            continue
        try:
            got = to_reference(declared(impl), method, getattr(impl, method)(V, F), V, F)
            rows = got.shape if hasattr(got, "shape") else (len(got),)
        except Exception:  # noqa: BLE001  (nothing to say)
            continue
        if rows and rows[0] == len(V) and len(used) < len(V):
            # a value for every vertex: its rows (and columns) of the used vertices, on the
            # mesh without the others, say what the answer is where it is determined
            for row in diagnose(compact, _on_used(impl, method, got, used), {method}):
                row["where"] = _renumbered(row["where"], used)
                out.append(row)
            continue
        if not rows or rows[0] != len(used):
            continue
        there = diagnose(compact, impl, {method})
        if there and there[0]["status"] == "agrees":
            out.append({"quantity": method, "status": "DIFFERS", "where": "its size",
                        "expected": f"{len(V)} rows", "observed": f"{len(used)} rows",
                        "worst": math.inf, "note": None,
                        "explained_by": ["unused_vertices=dropped"]})
    return out


def _renumbered(where, used: list):
    """A row's place ("entry (0, 1)", "vertex 2, coordinate 0") on the mesh without its
    unused vertices, in the vertex numbers of the mesh with them."""
    import re
    if not where:
        return where
    m = re.fullmatch(r"entry \((\d+), (\d+)\)", where)
    if m:
        return f"entry ({used[int(m[1])]}, {used[int(m[2])]})"
    return re.sub(r"^vertex (\d+)", lambda v: f"vertex {used[int(v[1])]}", where)


def _on_used(impl, method: str, got, used: list):
    """An implementation of ``method`` alone whose answer is ``got`` (``impl``'s, already on
    the reference's conventions, for every vertex) restricted to the ``used`` vertices:
    per-vertex rows, or the rows and columns of a matrix."""
    import scipy.sparse as sp
    from ..protocol.methods import METHODS, implementation_name, machine_epsilon
    idx = np.asarray(used, dtype=np.int64)
    if sp.issparse(got):
        part = sp.csr_matrix(got)[idx][:, idx]
    else:
        a = np.asarray(got)
        part = a[np.ix_(idx, idx)] if METHODS[method].kind == "matrix" else a[idx]

    class OnUsed:
        name = implementation_name(impl)
    w = OnUsed()
    w.machine_epsilon = machine_epsilon(impl)
    setattr(w, method, lambda V, F: part)
    return w


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
        note = "; ".join(filter(None, [c.note, ("agrees under " + ", ".join(c.explained_by))
                                             if c.explained_by else None]))
        table.append((c.quantity, c.implementation, c.status, ratio, c.where or "-",
                      value_text(c.expected), value_text(c.observed) + (f"  [{note}]" if note else "")))
    widths = [max(len(r[k]) for r in table) for k in range(len(cols) - 1)]
    for r in table:
        lines.append("  ".join(x.ljust(w) for x, w in zip(r, widths)) + "  " + r[-1])
    return "\n".join(lines)


def value_text(x) -> str:
    """A value as the comparison table prints it: a float to 17 digits, None as -."""
    if x is None:
        return "-"
    if isinstance(x, float):
        return f"{x:.17g}"
    return str(x)
