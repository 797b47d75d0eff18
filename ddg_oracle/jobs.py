"""Running a check: tasks of (implementation x property) or (implementation x mesh file),
serially or in worker processes.

Each task is independent: a property's Hypothesis run on one implementation
(derandomized under the ``ci`` profile, so its result does not depend on which
process runs it), or every applicable property on one mesh file.  With
``workers > 1`` tasks go to a pool of spawned processes; in every process the
exact reference runs in-process and each other implementation in its own
isolated worker (:class:`ddg_oracle.isolation.Isolated`: a crash or a hang is a
reported result), created once per process and reused.  Results come back in
completion order; :func:`run_tasks` returns them in task order, so the report
does not depend on scheduling.
"""

from __future__ import annotations

import concurrent.futures as cf
import multiprocessing as mp
from dataclasses import dataclass

IN_PROCESS = ("reference",)      # specs run in the checking process itself


@dataclass(frozen=True)
class Options:
    profile: str = "default"
    seed: int | None = None
    timeout: float = 60.0
    expect_conventions: bool = False
    only: frozenset | None = None
    budget: object = None           # properties.budget.Budget of each task; None: the profile's


@dataclass(frozen=True)
class Task:
    spec: str                   # implementation spec as given to --impl
    property_id: str | None     # a generated-example task ...
    mesh: int | None = None     # ... or the index of a mesh file: every applicable property


_STATE: dict = {"options": Options(), "meshes": [], "impls": {}, "examples": {}}


def _init(options: Options, meshes: list) -> None:
    _STATE.update(options=options, meshes=meshes, impls={}, examples={})


def implementation(spec: str, timeout: float):
    """The implementation of ``spec`` in this process: in-process for the reference,
    else an isolated worker (cached per process)."""
    impls = _STATE["impls"]
    if spec not in impls:
        if spec in IN_PROCESS:
            from ddg_oracle.implementations import load_implementation
            impls[spec] = load_implementation(spec)
        else:
            from ddg_oracle.isolation import Isolated
            impls[spec] = Isolated(spec, timeout=timeout)
    return impls[spec]


def adopt(spec: str, impl) -> None:
    """Use an already started implementation for ``spec`` in this process."""
    _STATE["impls"][spec] = impl


def close_all() -> None:
    for impl in _STATE["impls"].values():
        close = getattr(impl, "close", None)
        if close is not None:
            close()
    _STATE["impls"] = {}


def _counterpart(spec: str):
    from ddg_oracle.implementations import convention_counterpart
    opts = _STATE["options"]
    found = convention_counterpart(spec) if opts.expect_conventions else None
    if found is None:
        return None, None
    base, convention = found
    return implementation(base, opts.timeout), convention


def run_task(task: Task) -> list:
    """The results of one task (in this process)."""
    from ddg_oracle.properties.profiles import profile, profile_budget
    from ddg_oracle.properties.registry import PROPERTIES, all_properties
    from ddg_oracle.properties.runner import run_property

    opts = _STATE["options"]
    all_properties()
    impl = implementation(task.spec, opts.timeout)
    counterpart, convention = _counterpart(task.spec)
    if task.mesh is None:
        budget = opts.budget if opts.budget is not None else profile_budget(opts.profile)
        return [run_property(PROPERTIES[task.property_id], impl, profile(opts.profile), opts.seed,
                             counterpart=counterpart, convention=convention, budget=budget)]
    from ddg_oracle.compare import MeshExamples, run_mesh_properties
    examples = _STATE["examples"]
    if task.mesh not in examples:
        examples.clear()                 # one mesh's exact values at a time
        examples[task.mesh] = MeshExamples(_STATE["meshes"][task.mesh])
    return run_mesh_properties(examples[task.mesh], impl, opts.only, counterpart, convention)


def _crashed(task: Task, why: str) -> list:
    from ddg_oracle.properties.registry import PROPERTIES
    from ddg_oracle.properties.runner import CRASHED, Result
    p = PROPERTIES.get(task.property_id)
    return [Result(task.property_id or "-", p.name if p else "-", task.spec, CRASHED,
                   error=why, source="generated" if task.mesh is None else f"mesh {task.mesh}")]


def run_tasks(tasks: list[Task], options: Options, meshes: list, workers: int = 1,
              on_done=None) -> list:
    """Every task's results, in task order; ``on_done(task, results)`` as each finishes."""
    out: list = [None] * len(tasks)
    if workers <= 1 or len(tasks) <= 1:
        _STATE.update(options=options, meshes=meshes, examples={})
        for k, t in enumerate(tasks):
            out[k] = run_task(t)
            if on_done is not None:
                on_done(t, out[k])
        return [r for rs in out for r in rs]
    ctx = mp.get_context("spawn")       # no fork of a parent holding threads
    with cf.ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=_init,
                                initargs=(options, meshes)) as pool:
        futures = {pool.submit(run_task, t): k for k, t in enumerate(tasks)}
        for fut in cf.as_completed(futures):
            k = futures[fut]
            try:
                out[k] = fut.result()
            except cf.process.BrokenProcessPool as e:
                out[k] = _crashed(tasks[k], f"the worker process running it died: {e}")
            if on_done is not None:
                on_done(tasks[k], out[k])
    return [r for rs in out for r in rs]
