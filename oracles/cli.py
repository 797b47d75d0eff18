"""``ddg-oracle``: check implementations against the exact reference; compare on one mesh;
print the catalog.

Exit codes: 0 all good (passes, not applicable, tie disagreements, expected
conventions), 1 a property failed or an implementation crashed (or the table
is not true, or compare found a difference), 2 bad usage or bad input (one
line on stderr, no traceback).
"""

from __future__ import annotations

import argparse
import concurrent.futures as cf
import os
import sys
import time

from reference.errors import InputError

DEFAULT_WORKERS = 2


def _default_workers() -> int:
    return max(1, min(DEFAULT_WORKERS, os.cpu_count() or 1))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="ddg-oracle", description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)

    c = sub.add_parser("check", help="run every property against implementations")
    c.add_argument("--impl", action="append", metavar="NAME|module:object",
                   help="implementation to check (repeatable; default: every installed one); "
                        "options in parentheses, e.g. 'libigl(boundary=library)'")
    c.add_argument("--profile", default="default", help="Hypothesis profile: default, ci, thorough")
    c.add_argument("--seed", type=int, default=None, help="Hypothesis seed")
    c.add_argument("--only", action="append", metavar="ID", help="only these catalog IDs")
    c.add_argument("--timeout", type=float, default=60.0,
                   help="seconds per call of a checked implementation before it is killed "
                        "and reported as hanging (default 60)")
    c.add_argument("--mesh", action="extend", nargs="+", metavar="FILE",
                   help="check on these mesh files (OBJ, OFF, PLY, STL) instead of generated "
                        "meshes; 'pymeshlab:' = every sample mesh PyMeshLab ships, "
                        "'pymeshlab:NAME' one of them")
    c.add_argument("--report", metavar="DIR",
                   help="write results.json, summary.md, timings.json and, per failure, the "
                        "mesh (OBJ), a picture (PNG) and a reproducing snippet into DIR")
    c.add_argument("--workers", type=int, default=None, metavar="N",
                   help=f"worker processes (default {_default_workers()}: "
                        f"min({DEFAULT_WORKERS}, number of CPUs)); 1 runs in this process")
    c.add_argument("--expect-conventions", action="store_true",
                   help="a failure of an implementation using a documented library convention "
                        "(e.g. 'libigl(boundary=library)') that the reference-convention adapter "
                        "passes is reported as 'convention', not as a failure")

    m = sub.add_parser("compare", help="every quantity on one mesh: reference vs implementations")
    m.add_argument("mesh", nargs="+", metavar="MESH",
                   help="mesh file, or 'pymeshlab:' / 'pymeshlab:NAME' (sample meshes)")
    m.add_argument("--impl", action="append", metavar="NAME|module:object",
                   help="implementation to compare (repeatable; default: every installed one)")
    m.add_argument("--timeout", type=float, default=60.0, help="seconds per call (default 60)")

    t = sub.add_parser("theorems", help="print the traceability table")
    t.add_argument("--check", action="store_true",
                   help="exit 1 unless every named function, property and test exists "
                        "and every row of a claimed chapter is verified")

    args = parser.parse_args(argv)
    if os.getcwd() not in sys.path and "" not in sys.path:
        # module:object specs import from the current directory, as with python -m
        # (worker processes inherit sys.path)
        sys.path.insert(0, os.getcwd())
    try:
        if args.command == "check":
            return _check(args, argv)
        if args.command == "compare":
            return _compare(args)
        return _theorems(args)
    except (InputError, ValueError) as e:
        print(f"ddg-oracle: error: {e}", file=sys.stderr)
        return 2
    except BrokenPipeError:                  # e.g. piped into head: stop quietly
        sys.stdout = open(os.devnull, "w")
        return 1


def _theorems(args) -> int:
    from properties import traceability
    claimed, entries = traceability.load()
    width = max(len(e.id) for e in entries)
    print(f"{'ID'.ljust(width)}  {'status':9}  reference / property")
    for e in entries:
        ref = ", ".join(r.split(":")[-1] for r in e.reference) or "-"
        prop = ", ".join(p.split(":")[-1] for p in e.property) or "-"
        print(f"{e.id.ljust(width)}  {e.status:9}  {ref} / {prop}")
    counts = {s: sum(e.status == s for e in entries) for s in traceability.STATUSES}
    print(f"\n{len(entries)} rows: " + ", ".join(f"{n} {s}" for s, n in counts.items())
          + f"; claimed chapters: {', '.join(map(str, claimed)) or 'none'}")
    if not args.check:
        return 0
    problems = traceability.check()
    for p in problems:
        print(f"NOT TRUE: {p}", file=sys.stderr)
    if problems:
        return 1
    print("traceability table: true")
    return 0


def _warn(message: str) -> None:
    print(f"ddg-oracle: note: {message}", file=sys.stderr)


def _start(specs, timeout):
    """{spec: implementation}: the reference in this process, the others isolated, started
    in parallel; an unloadable spec raises ImplementationNotFound (exit 2)."""
    from oracles.implementations import load_implementation
    from oracles.isolation import Isolated

    def one(spec):
        return load_implementation(spec) if spec == "reference" else Isolated(spec, timeout=timeout)

    with cf.ThreadPoolExecutor(max_workers=max(1, len(specs))) as pool:
        futures = {s: pool.submit(one, s) for s in specs}
    started, error = {}, None
    for s, f in futures.items():
        try:
            started[s] = f.result()
        except Exception as e:  # noqa: BLE001  (re-raised below after closing the others)
            error = error or e
    if error is not None:
        for impl in started.values():
            getattr(impl, "close", lambda: None)()
        raise error
    return started


class Progress:
    """A one-line bar on stderr when it is a terminal; otherwise silent until the end."""

    def __init__(self, total: int, stream=None):
        self.total, self.done = total, 0
        self.stream = stream or sys.stderr
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self.t0 = time.perf_counter()

    def __call__(self, task, results) -> None:
        self.done += 1
        if not self.tty:
            return
        bar = "#" * (24 * self.done // max(self.total, 1))
        what = task.property_id or f"mesh {task.mesh}"
        bad = sum(not r.ok for r in results)
        print(f"\r[{bar:<24}] {self.done}/{self.total} {time.perf_counter() - self.t0:5.0f} s  "
              f"{task.spec[:24]}: {what[:14]:<14}{' FAIL' if bad else '     '}",
              end="", file=self.stream, flush=True)

    def finish(self) -> None:
        if self.tty:
            print(file=self.stream)


def _check(args, argv) -> int:
    from oracles import jobs
    from oracles.implementations import available
    from properties.profiles import profile
    from properties.registry import all_properties
    from properties.runner import describe

    profile(args.profile)                              # a typo is a usage error, before work
    if args.workers is not None and args.workers < 1:
        raise ValueError(f"--workers must be >= 1, got {args.workers}")
    workers = args.workers or _default_workers()
    only = set(args.only) if args.only else None
    props = [p for p in all_properties() if only is None or p.id in only]
    if only:
        unknown = only - {p.id for p in props}
        if unknown:
            raise ValueError(f"no property for catalog ID(s) {', '.join(sorted(unknown))}")
    meshes = []
    if args.mesh:
        from oracles.compare import FILE_PROPERTIES, load_all
        meshes = load_all(args.mesh, warn=_warn)
        if not meshes:
            raise InputError("no usable mesh among " + ", ".join(args.mesh))
        if only and not only & set(FILE_PROPERTIES):
            raise ValueError(f"none of {', '.join(sorted(only))} applies to a mesh file; "
                             f"those that do: {', '.join(FILE_PROPERTIES)}")
    specs = list(dict.fromkeys(args.impl or available()))
    t0 = time.perf_counter()
    started = _start(specs, args.timeout)
    names = {s: getattr(i, "name", s) for s, i in started.items()}
    options = jobs.Options(args.profile, args.seed, args.timeout, args.expect_conventions,
                           frozenset(only) if only else None)
    if meshes:
        tasks = [jobs.Task(s, None, k) for k in range(len(meshes)) for s in specs]
    else:
        tasks = [jobs.Task(s, p.id) for p in props for s in specs]
    workers = min(workers, len(tasks))
    if workers <= 1:
        for s, impl in started.items():
            jobs.adopt(s, impl)
    else:
        for impl in started.values():
            getattr(impl, "close", lambda: None)()
    progress = Progress(len(tasks))
    try:
        results = jobs.run_tasks(tasks, options, meshes, workers, on_done=progress)
    finally:
        progress.finish()
        jobs.close_all()
    seconds = time.perf_counter() - t0

    from oracles.report import counts, table, write_report
    print(table(results))
    bad = [r for r in results if not r.ok]
    shown = [r for r in results if r.failure is not None or r.error]
    for r in shown:
        print("\n" + describe(r))
    c = counts(results)
    print(f"\n{len(results)} checks in {seconds:.1f} s with {workers} worker"
          f"{'s' if workers != 1 else ''} (profile {args.profile}): "
          + ", ".join(f"{n} {s}" for s, n in c.items() if n))
    if args.report:
        command = {"profile": args.profile, "seed": args.seed, "implementations": specs,
                   "only": sorted(only) if only else None,
                   "meshes": [m.name for m in meshes] or None,
                   "expect_conventions": args.expect_conventions,
                   "argv": [a for a in (argv if argv is not None else sys.argv[2:])]}
        spec_of = {n: s for s, n in names.items()}
        timings = {"seconds": round(seconds, 3), "workers": workers,
                   "results": [{"property_id": r.property_id, "implementation": r.implementation,
                                "source": r.source, "seconds": round(r.seconds, 4)}
                               for r in results]}
        d = write_report(args.report, results, command, spec_of, timings)
        print(f"report: {d / 'summary.md'}")
    return 1 if bad else 0


def _compare(args) -> int:
    from oracles.compare import format_comparisons, load_all, compare_mesh
    from oracles.exact_reference import ReferenceImplementation
    from oracles.implementations import available

    meshes = load_all(args.mesh, warn=_warn)
    if not meshes:
        raise InputError("no usable mesh among " + ", ".join(args.mesh))
    specs = list(dict.fromkeys(args.impl or [s for s in available() if s != "reference"]))
    started = _start(specs, args.timeout)
    worse = 0
    try:
        for k, mesh in enumerate(meshes):
            rows = compare_mesh(mesh, [started[s] for s in specs], ReferenceImplementation())
            print(("\n" if k else "") + format_comparisons(mesh, rows))
            worse += sum(r.status in ("DIFFERS", "crashed") for r in rows)
    finally:
        for impl in started.values():
            getattr(impl, "close", lambda: None)()
    return 1 if worse else 0


if __name__ == "__main__":
    sys.exit(main())
