"""Running a check: tasks of (implementation x property) or (implementation x mesh file),
serially or in worker processes.

Each task is independent: a property's Hypothesis run on one implementation
(derandomized under the ``ci`` profile, so its result does not depend on which
process runs it), or every applicable property on one mesh file.  With
``workers > 1`` tasks go to a pool of spawned processes; in every process the
exact reference runs in-process and each other implementation in its own
isolated worker (:class:`ddg_oracle.application.isolation.Isolated`: a crash or a hang is a
reported result), created once per process and reused.  Results come back in
completion order; :func:`run_tasks` returns them in task order, so the report
does not depend on scheduling.
"""

from __future__ import annotations

import time
from contextlib import contextmanager
from dataclasses import dataclass

from .containment import (LIBRARY_PRELOAD, forkserver_in_use,
                                    start_workers_from_a_forkserver, stopped, worker_context)
from ..protocol.processes import exit_text

IN_PROCESS = ("reference",)      # specs run in the checking process itself


@dataclass(frozen=True)
class Options:
    profile: str = "default"
    seed: int | None = None
    timeout: float = 60.0
    expect_conventions: bool = False
    only: frozenset | None = None
    budget: object = None           # protocol.budget.Budget of each task; None: the profile's
    examples: int | None = None     # examples per property (check --examples); None: the profile's


@dataclass(frozen=True)
class Task:
    spec: str                   # implementation spec as given to --impl
    property_id: str | None     # the property (None on a mesh: every applicable one)
    mesh: int | None = None     # the index of a mesh file; None: generated examples


class _Process:
    """What this process keeps between the tasks of one run: the run's options and mesh
    files, the implementations started here (an isolated worker per library, reused), the
    exact values of the mesh file being checked, and which run they belong to.  One per
    process (a pool worker, a dask worker, or the checking process itself when serial),
    read only in this module; other modules go through :func:`install`."""

    def __init__(self):
        self.options = Options()
        self.meshes: list = []
        self.impls: dict = {}
        self.examples: dict = {}
        self.run = None


_HERE = _Process()


def install(options: Options, meshes: list, run=None) -> None:
    """Prepare this process for the tasks of a run (``run``: a token naming it; the same
    token again keeps what is installed, a new one closes the previous run's
    implementations first)."""
    if run is not None and run == _HERE.run:
        return
    if run is not None:
        close_all()
    _HERE.options, _HERE.meshes, _HERE.examples, _HERE.run = options, meshes, {}, run


def implementation(spec: str, timeout: float):
    """The implementation of ``spec`` in this process: in-process for the reference,
    else an isolated worker (cached per process)."""
    impls = _HERE.impls
    if spec not in impls:
        if spec in IN_PROCESS:
            from .implementations import load_implementation
            impls[spec] = load_implementation(spec)
        else:
            from .isolation import Isolated
            impls[spec] = Isolated(spec, timeout=timeout)
    return impls[spec]


def adopt(spec: str, impl) -> None:
    """Use an already started implementation for ``spec`` in this process."""
    _HERE.impls[spec] = impl


def close_all() -> None:
    for impl in _HERE.impls.values():
        close = getattr(impl, "close", None)
        if close is not None:
            close()
    _HERE.impls = {}


def _counterpart(impl):
    """(the counterpart, what differs) that ``impl`` declares (its ``conventions``:
    protocol.methods.declared_conventions), with --expect-conventions; else (None, None)."""
    from ..protocol.methods import declared_conventions
    opts = _HERE.options
    found = declared_conventions(impl) if opts.expect_conventions else None
    if found is None:
        return None, None
    spec, convention = found
    return implementation(spec, opts.timeout), convention


def run_task(task: Task) -> list:
    """The results of one task (in this process); a bug of ours while running it is an
    ``internal error`` result, never a dead worker that would read as the library's crash."""
    try:
        return _run_task(task)
    except Exception as e:  # noqa: BLE001  (ours: reported as such, the run goes on)
        from ..properties.runner import INTERNAL, internal_text
        return crashed(task, internal_text(e), status=INTERNAL)


def _run_task(task: Task) -> list:
    from ..properties.profiles import profile, profile_budget
    from ..properties.registry import PROPERTIES, all_properties
    from ..properties.runner import run_property

    opts = _HERE.options
    all_properties()
    try:
        impl = implementation(task.spec, opts.timeout)
        counterpart, convention = _counterpart(impl)
    except Exception as e:  # noqa: BLE001  (installed but broken: a result, not a dead worker)
        return crashed(task, f"{task.spec} cannot be loaded: {e}")
    if task.mesh is None:
        budget = opts.budget if opts.budget is not None else profile_budget(opts.profile)
        p = PROPERTIES[task.property_id]
        settings = profile(opts.profile)
        if opts.examples is not None:
            from hypothesis import settings as Settings
            settings = Settings(settings, max_examples=opts.examples)
        r = run_property(p, impl, settings, opts.seed,
                         counterpart=counterpart, convention=convention, budget=budget)
        return [with_diagnosis(r, p, impl)]
    from .meshes import MeshExamples, as_read_by, run_mesh_properties
    from ..properties.precision import format_of
    from ..protocol.methods import machine_epsilon
    from ..reference.errors import InputError
    only = opts.only if task.property_id is None else frozenset([task.property_id])
    examples = _HERE.examples
    # the mesh as this implementation reads it (a float32 one: rounded to float32), its
    # exact values computed once per format; one mesh's at a time
    key = (task.mesh, format_of(machine_epsilon(impl)).bits)
    if key not in examples:
        for k in [k for k in examples if k[0] != task.mesh]:
            del examples[k]
        try:
            examples[key] = MeshExamples(as_read_by(_HERE.meshes[task.mesh], machine_epsilon(impl)))
        except InputError as e:          # the rounding collapsed a face: nothing to check
            examples[key] = e
    if isinstance(examples[key], InputError):
        from .meshes import file_properties
        from ..properties.runner import NOT_APPLICABLE, Result
        return [Result(p.id, p.name, task.spec, NOT_APPLICABLE, source=_HERE.meshes[task.mesh].name,
                       note=str(examples[key])) for p in file_properties(only)]
    return run_mesh_properties(examples[key], impl, only, counterpart, convention)


def with_diagnosis(r, p, impl):
    """``r`` with, when it is a failure on a small generated counterexample, how each
    protocol method the property calls answers there (``compare.diagnose``): the report
    names the wrong method from it.  Our own trouble diagnosing never changes the result."""
    from ..properties.runner import FAILED
    if r.status != FAILED or r.source != "generated" or r.mesh is None:
        return r
    try:
        from .compare import diagnose
        r.diagnosis = diagnose(r.mesh, impl, p.methods) or None
    except Exception:  # noqa: BLE001  (a diagnosis is extra; the verdict stands without it)
        r.diagnosis = None
    return r


def crashed(task: Task, why: str, status: str | None = None) -> list:
    """The one result of a task that could not run: ``crashed`` (the implementation), or
    the given ``status``."""
    from ..properties import PROPERTIES
    from ..properties.runner import CRASHED, Result
    p = PROPERTIES.get(task.property_id)
    return [Result(task.property_id or "-", p.name if p else "-", task.spec, status or CRASHED,
                   error=why, source="generated" if task.mesh is None else f"mesh {task.mesh}")]


class Interrupted(KeyboardInterrupt):
    """SIGINT, SIGTERM or SIGHUP stopped the run; ``signal`` is which, ``code`` the exit code
    (130, 143); ``done`` the results of the tasks that had finished, in task order.  A
    KeyboardInterrupt, so that the property runner, which records every other exception of
    a call as the implementation's crash, lets it through: a signal during a call of the
    checked code is the user's stop, not the code's crash (and --resume reruns the task)."""

    def __init__(self, signum: int, done: list | None = None):
        self.signal, self.code, self.done = signum, 128 + signum, done or []
        super().__init__(f"interrupted by signal {signum}")


def _starting_a_pool(frame) -> bool:
    """Whether ``frame`` (where a signal arrived) is inside the construction of a
    multiprocessing pool (its workers being spawned)."""
    import multiprocessing.pool
    pool_file = multiprocessing.pool.__file__
    while frame is not None:
        if frame.f_code.co_filename == pool_file and frame.f_code.co_name in (
                "__init__", "_repopulate_pool", "_repopulate_pool_static"):
            return True
        frame = frame.f_back
    return False


@contextmanager
def stopped_by_signals():
    """SIGINT, SIGTERM and SIGHUP raise :class:`Interrupted` in the block (the command
    unwinds, its pools and library processes are closed, it exits 128 + N with one line),
    instead of SIGTERM and SIGHUP killing it at once and leaving them running.
    :func:`run_tasks` installs its own handlers around a check's run; these are restored
    after.  Only in the main thread (the only one that may install handlers)."""
    import os
    import signal
    import threading
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def stop(signum, frame):
        if _starting_a_pool(frame):
            # raised inside multiprocessing's Pool(), the pool is never returned (so never
            # closed), and a worker spawned a moment before reads a cut pipe and prints a
            # traceback: the signal is taken again once the pool exists
            threading.Timer(0.05, os.kill, (os.getpid(), signum)).start()
            return
        raise Interrupted(signum)
    previous = {s: signal.signal(s, stop) for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)}
    try:
        yield
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)


def _worker_main(options: Options, meshes: list, conn, forkserver: bool = False) -> None:
    """A pool worker: run the tasks it is sent, one at a time, answer each with its results.
    On SIGTERM it closes its isolated library workers first (no orphan).  ``forkserver``:
    its isolated library workers start from a forkserver too, as its parent's did."""
    import os
    import signal
    if forkserver:
        start_workers_from_a_forkserver(LIBRARY_PRELOAD)

    def stop(signum, frame):
        close_all()
        # not sys.exit: a SystemExit raised while a garbage-collector callback runs (which
        # Hypothesis installs) is printed as "Exception ignored" and swallowed, and the
        # worker would go on; the library workers are closed, nothing else needs unwinding
        os._exit(128 + signum)

    signal.signal(signal.SIGTERM, stop)
    signal.signal(signal.SIGINT, signal.SIG_IGN)      # the parent decides what an interrupt does
    install(options, meshes)
    try:
        while True:
            try:
                k, task = conn.recv()
                results = run_task(task)
                conn.send((k, results))
            except (EOFError, BrokenPipeError, ConnectionResetError):
                return                      # the parent is gone or stopped the run
    finally:
        close_all()


#: how often a task whose pool worker died is run again in a fresh worker
RETRIES = 1


def run_tasks(tasks: list[Task], options: Options, meshes: list, workers: int = 1,
              on_done=None, done: dict | None = None, remote=None) -> list:
    """Every task's results, in task order; ``on_done(k, task, results)`` as each finishes.

    ``done``: {task index: results} already known (a resumed run): not run again.
    With ``workers > 1`` each task runs in one of ``workers`` spawned processes; a process
    that dies while running a task (killed, out of memory) is replaced and the task run
    once more (:data:`RETRIES`), then reported as ``crashed``; no other task's result is
    lost.  SIGINT / SIGTERM / SIGHUP raise :class:`Interrupted` carrying the finished results, after
    every worker and library process is gone.  ``remote``: runs the tasks elsewhere instead
    (``workers`` unused), called as ``remote(tasks, todo, options, meshes, finish, check)``:
    ``finish(k, results)`` as each task ends, ``check()`` at least twice a second (it raises
    on a signal); the command line passes a dask cluster's (:func:`ddg_oracle.application.cluster.
    run_on_cluster`), so this module knows nothing of dask."""
    import signal

    out: dict = dict(done or {})
    todo = [k for k in range(len(tasks)) if k not in out]
    serial = remote is None and (workers <= 1 or len(todo) <= 1)
    caught: list[int] = []

    def finish(k, results):
        out[k] = results
        if on_done is not None:
            on_done(k, tasks[k], results)

    def stop(signum, frame):
        # remembered first: an exception raised here can be swallowed (a signal that
        # arrives inside a garbage-collector callback), the flag cannot
        caught.append(signum)
        if serial:
            raise Interrupted(signum)      # the task runs here: stop it now

    def check():
        if caught:
            raise Interrupted(caught[0])

    # SIGHUP too: a closed terminal or ssh session stops the run as Ctrl-C does (a report,
    # a hint to resume), instead of leaving the workers computing
    previous = {s: signal.signal(s, stop) for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)}
    try:
        if serial:
            install(options, meshes)
            for k in todo:
                check()
                finish(k, run_task(tasks[k]))
                check()
        elif remote is not None:
            remote(tasks, todo, options, meshes, finish, check)
        else:
            _run_pool(tasks, todo, options, meshes, workers, finish, check)
    except (KeyboardInterrupt, Interrupted) as e:
        from .containment import kill_descendants
        kill_descendants()
        signum = e.signal if isinstance(e, Interrupted) else signal.SIGINT
        raise Interrupted(signum, [r for k in sorted(out) for r in out[k]]) from None
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
    return [r for k in range(len(tasks)) for r in out[k]]


def task_group(task: Task):
    """The tasks that share memoized exact values: one property's (every implementation
    sees its examples), on generated examples or on one mesh file."""
    return task.property_id if task.mesh is None else ("mesh", task.mesh, task.property_id)


def next_task(queue: list[int], tasks: list[Task], mine, others: set, score=None) -> int:
    """The position in ``queue`` of the task a free worker takes next: one of its own group
    ``mine`` while any is left (the implementations see the same examples, whose exact
    reference values the worker has memoized: properties.memo), else one of a group no
    other worker is on (``others``; of those the first with the highest ``score(group)``,
    if given), else the first.

    >>> ts = [Task("a", "P"), Task("b", "P"), Task("a", "Q"), Task("b", "Q")]
    >>> next_task([0, 1, 2, 3], ts, "Q", {"P"}), next_task([0, 1, 2, 3], ts, None, {"P"})
    (2, 2)
    >>> ts += [Task("a", "R")]
    >>> next_task([0, 2, 4], ts, None, set(), score=lambda g: g == "R")
    2
    """
    for i, k in enumerate(queue):
        if task_group(tasks[k]) == mine:
            return i
    free = [i for i, k in enumerate(queue) if task_group(tasks[k]) not in others]
    if not free:
        return 0
    if score is None:
        return free[0]
    best = max(score(task_group(tasks[queue[i]])) for i in free)
    return next(i for i in free if score(task_group(tasks[queue[i]])) == best)


def needs_of(group) -> frozenset:
    """The protocol methods a mesh file's property group calls (its exact values are those
    methods' reference values: groups that share methods share memoized values); empty for
    generated examples, which differ per property."""
    if not isinstance(group, tuple):
        return frozenset()
    from ..properties.registry import PROPERTIES
    p = PROPERTIES.get(group[2])
    return p.methods if p is not None else frozenset()


def _wedge_limit(options) -> float | None:
    """Seconds after which a generated-example task still running is taken for a wedged
    worker: four times the task's budget plus two call timeouts (a budget bounds the
    task, shrinking and a cut-short call included); None without a budget (thorough)."""
    from ..properties.profiles import profile_budget
    budget = options.budget if options.budget is not None else profile_budget(options.profile)
    if budget.seconds is None:
        return None
    return 4 * budget.seconds + 2 * options.timeout


def _run_pool(tasks, todo, options, meshes, workers, finish, check) -> None:
    from multiprocessing.connection import wait

    ctx = worker_context()
    forkserver = forkserver_in_use()
    # dispatched from the last task on: the catalog's later chapters hold the costly
    # properties (curvature, Laplacian, Delaunay) and chapter 1 the cheap ones (topology),
    # which then fill both workers at the end instead of one worker finishing a long task
    # alone (results still come back in task order)
    queue = list(reversed(todo))
    attempts: dict[int, int] = {}
    running: dict = {}                  # connection -> (process, task index or None)
    why_died: dict[int, str] = {}
    last: dict = {}                     # connection -> group of the last task it was sent

    done_needs: dict = {}               # connection -> the methods of the groups it ran
    since: dict = {}                    # connection -> when its task was sent
    wedged_after = _wedge_limit(options)

    def pick(conn) -> int | None:
        # the groups other workers are running a task of now (an idle worker's last group
        # is free: two idle workers must not wait on each other)
        others = {last.get(c) for c in running if c is not conn and running[c][1] is not None}
        mine = done_needs.setdefault(conn, set())
        if conn in last:
            mine |= needs_of(last[conn])
        theirs = set().union(*(needs_of(g) for g in others if g is not None))

        # a mesh file's next property: one whose methods this worker has computed the
        # values of (memoized here), not one another worker is computing them for now
        def score(group):
            needs = needs_of(group)
            return len(needs & mine) - len(needs & theirs)
        i = next_task(queue, tasks, last.get(conn), others, score)
        group = task_group(tasks[queue[i]])
        if isinstance(group, tuple) and group != last.get(conn) and group in others:
            # only a mesh property another worker is on is left: its exact values cost
            # more than its remaining tasks (memoized there), so wait rather than compute
            # them again; fed again when a task finishes
            return None
        return queue.pop(i)

    def start():
        parent, child = ctx.Pipe()
        # not a daemon: it starts the isolated library workers; when this process dies its
        # pipe closes, and the worker, reading EOF, closes them and exits
        proc = ctx.Process(target=_worker_main, args=(options, meshes, child, forkserver),
                           daemon=False)
        proc.start()
        child.close()
        running[parent] = (proc, None)

    def feed(conn):
        proc, _ = running[conn]
        if queue:
            k = pick(conn)
            if k is None:
                running[conn] = (proc, None)          # idle until another task finishes
                return
            last[conn] = task_group(tasks[k])
            try:
                conn.send((k, tasks[k]))
            except (BrokenPipeError, OSError):
                # the worker died between tasks: k never reached it; a fresh worker takes it
                queue.insert(0, k)
                running[conn] = (proc, None)
                return
            attempts[k] = attempts.get(k, 0) + 1
            running[conn] = (proc, k)
            since[conn] = time.monotonic()
        else:
            conn.close()
            proc.join(5)
            del running[conn]

    try:
        for _ in range(min(workers, len(queue))):
            start()
        for conn in list(running):
            feed(conn)
        while running:
            check()                         # a signal: stop here, between two answers
            sentinels = {running[c][0].sentinel: c for c in running}
            for ready in wait(list(running) + list(sentinels), timeout=0.2):
                conn = sentinels.get(ready, ready)
                if conn not in running:
                    continue
                proc, k = running[conn]
                try:
                    got, results = conn.recv()
                except (EOFError, OSError):
                    # the worker died while running task k: a fresh worker, and k once more
                    proc.join(5)
                    del running[conn]
                    conn.close()
                    how = exit_text(proc.exitcode)
                    if k is not None:
                        why_died[k] = how
                        if attempts[k] <= RETRIES:
                            queue.insert(0, k)
                        else:
                            finish(k, crashed(tasks[k], f"the worker process running it died "
                                                         f"{attempts[k]} times ({how})"))
                    if queue:
                        start()
                        feed(list(running)[-1])
                    continue
                finish(got, results)
                feed(conn)
            for idle in [c for c in running if running[c][1] is None]:
                feed(idle)                  # a waiting worker: a task may be free for it now
            # heartbeat: a worker stopped (SIGSTOP, a debugger) or wedged far past its task's
            # budget is killed; its death is handled above (a fresh worker, the task again)
            for conn, (proc, k) in list(running.items()):
                if k is None or not proc.is_alive():
                    continue
                late = (wedged_after is not None and tasks[k].mesh is None
                        and time.monotonic() - since.get(conn, time.monotonic()) > wedged_after)
                if late or stopped(proc.pid):
                    proc.kill()
    finally:
        for conn, (proc, _) in list(running.items()):
            if proc.is_alive():
                proc.terminate()            # SIGTERM: it closes its library workers first
        for conn, (proc, _) in list(running.items()):
            proc.join(5)
            if proc.is_alive():
                proc.kill()
            conn.close()


