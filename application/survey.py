"""``ddg-oracle survey``: every implementation x every quantity x a corpus of meshes.

``compare`` over many meshes, aggregated into a scoreboard: per implementation and
protocol quantity, on how many meshes it was checked, how many agree with the exact
reference, differ, crashed or were not applicable, the worst error in units of the
derived bound (and on which mesh) and the median of each mesh's worst error.

The unit of work is one mesh: every implementation answers on it
(:func:`ddg_oracle.application.compare.compare_mesh`, the exact values computed by a pool of
workers), and its rows are appended to ``DIR/results.jsonl`` as one JSON line the moment
it finishes (:class:`SurveyStream`, a :class:`~ddg_oracle.application.report.ResultStream` whose unit
is a mesh).  An interrupted survey keeps its finished meshes; ``--resume DIR`` runs
only the others.  The scoreboard is written as ``DIR/results.json``, ``DIR/survey.md``
(a markdown table) and ``DIR/survey.html`` (a heatmap, one self-contained SVG).

With ``--scheduler ADDRESS`` the meshes are tasks of a ``dask.distributed`` cluster
(:func:`ddg_oracle.application.cluster.map_on_cluster`): each worker process starts the
implementations once per run (:func:`survey_mesh_in_worker`) and compares one mesh at a
time; finished meshes arrive in any order and the scoreboard is the local run's.
"""

from __future__ import annotations

import html
import json
import math
import statistics
from dataclasses import dataclass, field
from pathlib import Path

from .report import ResultStream

#: the statuses a scoreboard counts, in its order ("skipped" counts as not applicable;
#: "undecided": the exact reference gave up on the mesh, which says nothing of the library)
STATUSES = ("agrees", "DIFFERS", "crashed", "undecided", "not applicable")
NOT_PROVIDED = "not provided"          # compare's note for a method an implementation lacks
FORMAT = "ddg-oracle survey"


# --- the rows of one mesh, as JSON ---------------------------------------------------------------


def _number(x):
    """A float for JSON (infinities and NaN as strings: JSON has none)."""
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else repr(x)


def _float(x):
    if x is None:
        return None
    if isinstance(x, str):
        if x not in ("inf", "-inf", "nan"):
            raise ValueError(f"not a number: {x!r}")
        return float(x)
    if isinstance(x, bool) or not isinstance(x, (int, float)):
        raise ValueError(f"not a number: {x!r}")
    return float(x)


def record(row, spec: str) -> dict:
    """One compare row (:class:`~ddg_oracle.application.compare.Comparison`) as plain JSON values."""
    from .compare import value_text
    return {"quantity": row.quantity, "implementation": row.implementation, "spec": spec,
            "status": row.status, "worst": _number(row.worst), "error": _number(row.error),
            "bound": _number(row.bound), "where": row.where,
            "expected": None if row.expected is None else value_text(row.expected),
            "observed": None if row.observed is None else value_text(row.observed),
            "over": int(row.over), "elements": int(row.elements), "note": row.note,
            "explained_by": list(row.explained_by)}


_TEXT = ("quantity", "implementation", "spec", "status")


def checked_record(x) -> dict:
    """A record read back from a results file: only plain values of the expected kinds
    (ValueError otherwise); nothing in it is run."""
    if not isinstance(x, dict):
        raise ValueError("a row is not an object")
    for key in _TEXT:
        if not isinstance(x.get(key), str):
            raise ValueError(f"row field {key!r} is not a string")
    for key in ("where", "expected", "observed", "note"):
        if x.get(key) is not None and not isinstance(x[key], str):
            raise ValueError(f"row field {key!r} is not a string")
    for key in ("over", "elements"):
        if not isinstance(x.get(key), int) or isinstance(x[key], bool):
            raise ValueError(f"row field {key!r} is not an integer")
    out = dict(x)
    for key in ("worst", "error", "bound"):
        out[key] = _number(_float(x.get(key)))
    if not (isinstance(x.get("explained_by"), list)
            and all(isinstance(c, str) for c in x["explained_by"])):
        raise ValueError("row field 'explained_by' is not a list of names")
    return out


@dataclass
class MeshResult:
    """One finished unit: a mesh and every implementation's rows on it."""

    name: str
    vertices: int
    faces: int
    rows: list                       # records (:func:`record`), "not provided" rows left out
    seconds: float = 0.0
    note: str | None = None

    def to_json(self) -> dict:
        return {"mesh": self.name, "vertices": self.vertices, "faces": self.faces,
                "seconds": round(self.seconds, 3), "note": self.note, "rows": self.rows}

    @classmethod
    def from_json(cls, x) -> "MeshResult":
        if not (isinstance(x, dict) and isinstance(x.get("mesh"), str)
                and isinstance(x.get("rows"), list)):
            raise ValueError("not a mesh's results")
        for key in ("vertices", "faces"):
            if not isinstance(x.get(key), int) or isinstance(x[key], bool):
                raise ValueError(f"{key!r} is not an integer")
        seconds = _float(x.get("seconds", 0.0))
        note = x.get("note")
        if note is not None and not isinstance(note, str):
            raise ValueError("'note' is not a string")
        return cls(x["mesh"], x["vertices"], x["faces"],
                   [checked_record(r) for r in x["rows"]], seconds or 0.0, note)


class SurveyStream(ResultStream):
    """``DIR/results.jsonl`` of a survey: one line per finished mesh
    (:meth:`MeshResult.to_json`), flushed as it finishes; ``DIR/run.json``: the command
    line.  The report directory's handling (created, a FIFO refused, appended to) is
    :class:`~ddg_oracle.application.report.ResultStream`'s; only what a line holds differs."""

    def finished(self) -> dict:
        """{mesh name: MeshResult} of the lines already there (the meshes of this run
        only); a damaged line, other than a last one cut short, is a usage error."""
        from .commands import UsageError
        wanted = set(self.tasks)
        out = {}
        for n, entry in self.entries():
            try:
                done = MeshResult.from_json(entry)
            except (ValueError, TypeError) as e:
                raise UsageError(f"--resume {self.directory}: {self.LINES} line {n} is not a "
                                 f"survey result ddg-oracle wrote ({e})") from None
            if done.name in wanted:
                out[done.name] = done
        return out

    def add(self, done: MeshResult) -> None:
        self._fh.write(json.dumps(done.to_json(), sort_keys=True, allow_nan=False) + "\n")
        self._fh.flush()


def command_of(directory) -> dict:
    """The run.json of a survey's report directory (a usage error if it is not one)."""
    from .commands import UsageError
    if not (Path(directory) / ResultStream.RUN).is_file():
        raise UsageError(f"--resume {directory}: no {ResultStream.RUN} there (not the report "
                         "directory of an interrupted ddg-oracle survey --report run)")
    command = ResultStream.command_of(directory)
    if command.get("format") != FORMAT:
        raise UsageError(f"--resume {directory}: not the report directory of a ddg-oracle "
                         "survey run (of check? resume it with ddg-oracle check --resume)")
    return command


# --- the scoreboard ------------------------------------------------------------------------------


@dataclass
class Score:
    """One implementation and quantity over the meshes."""

    implementation: str
    quantity: str
    counts: dict = field(default_factory=lambda: dict.fromkeys(STATUSES, 0))
    worst: float | None = None
    worst_mesh: str | None = None
    worst_where: str | None = None
    ratios: list = field(default_factory=list)
    differs_on: list = field(default_factory=list)

    @property
    def meshes(self) -> int:
        return sum(self.counts.values())

    @property
    def applicable(self) -> int:
        return self.meshes - self.counts["not applicable"] - self.counts["undecided"]

    @property
    def median(self) -> float | None:
        return statistics.median(self.ratios) if self.ratios else None

    def fraction(self) -> float | None:
        """The fraction of the meshes it was applicable on where it agrees."""
        return self.counts["agrees"] / self.applicable if self.applicable else None

    def to_json(self) -> dict:
        return {"implementation": self.implementation, "quantity": self.quantity,
                "meshes": self.meshes, **{s: self.counts[s] for s in STATUSES},
                "worst": _number(self.worst), "worst_mesh": self.worst_mesh,
                "worst_where": self.worst_where, "median": _number(self.median),
                "differs_on": self.differs_on}


def scoreboard(done: list[MeshResult], implementations: list[str] | None = None) -> list[Score]:
    """A :class:`Score` per implementation and quantity it provides, over ``done`` (in
    mesh order, so a resumed survey scores as an undisturbed one); implementations in
    the order given (else first seen), quantities in the protocol's order."""
    from ..protocol.methods import METHODS
    scores: dict = {}
    for m in done:
        for r in m.rows:
            if r["status"] == "not applicable" and r["note"] == NOT_PROVIDED:
                continue
            key = (r["implementation"], r["quantity"])
            s = scores.setdefault(key, Score(*key))
            status = r["status"] if r["status"] in STATUSES else "not applicable"
            s.counts[status] += 1
            if status in ("DIFFERS", "crashed"):
                s.differs_on.append(m.name)
            worst = _float(r["worst"])
            if worst is not None and status in ("agrees", "DIFFERS"):
                s.ratios.append(worst)
                if s.worst is None or worst > s.worst:
                    s.worst, s.worst_mesh, s.worst_where = worst, m.name, r["where"]
    order = list(dict.fromkeys((implementations or []) + [i for i, _ in scores]))
    methods = list(METHODS)

    def key(k):
        i, q = k
        return (order.index(i), methods.index(q) if q in methods else len(methods), q)
    return [scores[k] for k in sorted(scores, key=key)]


def _ratio(x) -> str:
    if x is None:
        return "-"
    return "inf" if math.isinf(x) else f"{x:.3g}"


COLUMNS = ("implementation", "quantity", "meshes", "agrees", "DIFFERS", "crashed",
           "undecided", "not applicable", "worst err/bound", "worst on", "median err/bound")


def _cells(s: Score) -> tuple:
    # an exact quantity (an integer, flags, loops) has no error ratio: where it first differs
    where = s.worst_mesh or (s.differs_on[0] if s.differs_on else "-")
    return (s.implementation, s.quantity, str(s.meshes), *(str(s.counts[x]) for x in STATUSES),
            _ratio(s.worst), where, _ratio(s.median))


def format_table(scores: list[Score]) -> str:
    """The scoreboard as a plain-text table (columns aligned; numbers right-aligned)."""
    rows = [COLUMNS] + [_cells(s) for s in scores]
    widths = [max(len(r[k]) for r in rows) for k in range(len(COLUMNS))]
    right = {2, 3, 4, 5, 6, 7, 9}
    return "\n".join("  ".join(x.rjust(w) if k in right else x.ljust(w)
                               for k, (x, w) in enumerate(zip(r, widths))).rstrip()
                     for r in rows)


def markdown_table(scores: list[Score]) -> str:
    def cell(x: str) -> str:
        return x.replace("|", "\\|")
    lines = ["| " + " | ".join(COLUMNS) + " |",
             "|" + "|".join("---:" if k in (2, 3, 4, 5, 6, 7, 9) else "---"
                            for k in range(len(COLUMNS))) + "|"]
    lines += ["| " + " | ".join(cell(x) for x in _cells(s)) + " |" for s in scores]
    return "\n".join(lines)


def _colour(fraction: float | None) -> str:
    """Red (none agree) through yellow to green (all agree); grey: never applicable."""
    if fraction is None:
        return "#d9d9d9"
    return f"hsl({round(120 * fraction)}, 70%, 55%)"


def heatmap_html(scores: list[Score], title: str) -> str:
    """A self-contained HTML page: one SVG, a row per implementation, a column per
    quantity, each cell coloured by the fraction of the meshes (where the quantity
    applies) on which the implementation agrees; its counts in the cell's tooltip."""
    from ..protocol.methods import METHODS
    impls = list(dict.fromkeys(s.implementation for s in scores))
    present = {s.quantity for s in scores}
    quantities = [q for q in METHODS if q in present] + sorted(present - set(METHODS))
    by = {(s.implementation, s.quantity): s for s in scores}
    cell, left, top = 22, 8 + 7 * max([len(i) for i in impls] + [10]), \
        8 + 6 * max([len(q) for q in quantities] + [10])
    # the column labels, rotated 60 degrees, reach right of their column by ~half their length
    width = left + cell * len(quantities) + 10 + 3 * max([len(q) for q in quantities] + [10])
    width = max(width, left + 4 * 110)                     # the legend
    height = top + cell * len(impls) + 40
    e = html.escape
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'font-family="sans-serif" font-size="11">']
    for j, q in enumerate(quantities):
        x = left + cell * j + cell // 2 + 4
        out.append(f'<text transform="translate({x},{top - 6}) rotate(-60)">{e(q)}</text>')
    for i, impl in enumerate(impls):
        y = top + cell * i
        out.append(f'<text x="{left - 6}" y="{y + cell - 7}" text-anchor="end">{e(impl)}</text>')
        for j, q in enumerate(quantities):
            s = by.get((impl, q))
            x = left + cell * j
            if s is None:
                continue               # not provided by this implementation: no cell
            f = s.fraction()
            tip = (f"{impl} / {q}: " + ", ".join(f"{s.counts[k]} {k}" for k in STATUSES)
                   + f"; worst err/bound {_ratio(s.worst)}"
                   + (f" on {s.worst_mesh}" if s.worst_mesh else ""))
            out.append(f'<rect x="{x}" y="{y}" width="{cell - 2}" height="{cell - 2}" '
                       f'fill="{_colour(f)}"><title>{e(tip)}</title></rect>')
            if s.counts["DIFFERS"] or s.counts["crashed"]:
                out.append(f'<text x="{x + cell / 2 - 1}" y="{y + cell - 7}" '
                           f'text-anchor="middle">{s.counts["DIFFERS"] + s.counts["crashed"]}'
                           '</text>')
    y = top + cell * len(impls) + 20
    for k, (f, label) in enumerate(((1.0, "all agree"), (0.5, "half"), (0.0, "none agree"),
                                    (None, "not applicable"))):
        x = left + 110 * k
        out.append(f'<rect x="{x}" y="{y - 10}" width="12" height="12" fill="{_colour(f)}"/>'
                   f'<text x="{x + 16}" y="{y}">{label}</text>')
    out.append("</svg>")
    return ("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" + e(title)
            + "</title></head>\n<body style=\"font-family:sans-serif\">\n<h1>" + e(title)
            + "</h1>\n<p>Colour: the fraction of the meshes (where the quantity applies) on "
              "which the implementation agrees with the exact reference; a number: the meshes "
              "where it differs or crashed; no cell: a method it does not provide.  Hover a "
              "cell for its counts.</p>\n" + "\n".join(out) + "\n</body></html>\n")


def summary_line(scores: list[Score], done: list[MeshResult], total: int) -> str:
    impls = len({s.implementation for s in scores})
    n = {k: sum(s.counts[k] for s in scores) for k in STATUSES}
    return (f"{len(done)} of {total} meshes, {impls} implementations, {len(scores)} "
            f"implementation x quantity pairs: " + ", ".join(f"{n[k]} {k}" for k in STATUSES))


def write(directory, done: list[MeshResult], scores: list[Score], command: dict,
          total: int, seconds: float, interrupted: bool) -> dict:
    """DIR/results.json, DIR/survey.md and DIR/survey.html; returns their paths."""
    d = Path(directory)
    title = "ddg-oracle survey"
    doc = {"format": FORMAT, "command": command, "interrupted": interrupted,
           "meshes_total": total, "seconds": round(seconds, 3),
           "meshes": [m.to_json() for m in done],
           "scoreboard": [s.to_json() for s in scores]}
    files = {"json": d / "results.json", "md": d / "survey.md", "html": d / "survey.html"}
    files["json"].write_text(json.dumps(doc, indent=1, sort_keys=True, allow_nan=False) + "\n",
                             encoding="utf-8")
    meshes = ", ".join(f"{m.name} ({m.faces:,} faces)" for m in done) or "none"
    md = [f"# {title}", "",
          f"`ddg-oracle survey {' '.join(command.get('argv', []))}`"
          + (" (interrupted: resume with `ddg-oracle survey --resume DIR`)" if interrupted
             else ""), "",
          summary_line(scores, done, total) + f"; {seconds:.0f} s.", "",
          f"Meshes: {meshes}.", "",
          "Errors are in units of the derived bound (1 = the bound); the worst is over "
          "every mesh, the median over each mesh's worst.  Heatmap: survey.html.", "",
          markdown_table(scores), ""]
    files["md"].write_text("\n".join(md), encoding="utf-8")
    files["html"].write_text(heatmap_html(scores, title), encoding="utf-8")
    return files


# --- the command -------------------------------------------------------------------------------


def _argv(args, specs: list[str]) -> list[str]:
    """The survey's command line as run.json keeps it: the meshes, every implementation
    (resolved: a resumed survey runs the same ones) and the timeout."""
    out = list(args.mesh)
    for s in specs:
        out += ["--impl", s]
    return out + ["--timeout", repr(args.timeout)]


def survey_mesh(mesh, started: dict, specs: list[str], reference, workers: int) -> MeshResult:
    """One mesh's :class:`MeshResult`: every started implementation (spec -> object)
    compared with the exact reference on it (:func:`~ddg_oracle.application.compare.compare_mesh`,
    ``workers`` processes computing its exact values)."""
    import time
    from .compare import compare_mesh
    from ..protocol.methods import implementation_name
    t = time.perf_counter()
    rows = compare_mesh(mesh, [started[s] for s in specs], reference, workers=workers)
    spec_of: dict = {}
    for s in specs:
        spec_of.setdefault(implementation_name(started[s]), s)
    return MeshResult(mesh.name, len(mesh.V), len(mesh.F),
                      [record(r, spec_of.get(r.implementation, r.implementation))
                       for r in rows if r.note != NOT_PROVIDED],
                      time.perf_counter() - t, mesh.note)


#: in a dask worker: (the run's token, its started implementations, the reference)
_IN_WORKER: dict = {}


def survey_mesh_in_worker(run, mesh) -> dict:
    """:func:`survey_mesh` in a dask worker (``--scheduler``), as JSON: the run's
    implementations (``run``: token, specs, timeout) are started once per worker process
    and kept until the next run or :func:`close_in_worker`."""
    from . import commands
    from ..oracles.exact_reference import ReferenceImplementation
    token, specs, timeout = run
    if _IN_WORKER.get("token") != token:
        close_in_worker()
        _IN_WORKER.update(token=token, reference=ReferenceImplementation(),
                          started=commands.start_implementations(specs, timeout))
    return survey_mesh(mesh, _IN_WORKER["started"], specs, _IN_WORKER["reference"],
                       workers=1).to_json()


def close_in_worker() -> None:
    """Stop the implementations a dask worker started for a survey (their processes)."""
    for impl in (_IN_WORKER.pop("started", None) or {}).values():
        getattr(impl, "close", lambda: None)()
    _IN_WORKER.clear()


def _lost_mesh(mesh, specs: list[str], why: str) -> MeshResult:
    """The result of a mesh the cluster could not finish (its workers died): a crash of
    every implementation on it, said as such (quantity ``*``: not one of them in
    particular)."""
    from .compare import Comparison
    return MeshResult(mesh.name, len(mesh.V), len(mesh.F),
                      [record(Comparison("*", s, "crashed", note=why), s) for s in specs],
                      0.0, mesh.note)


def run(args) -> int:
    """``ddg-oracle survey``: see the module's docstring.  Exit 0 when every row agrees or
    is not applicable, 1 when something differs or crashed, 2 for a usage error, 128 + N
    when signal N stopped it (the finished meshes kept for ``--resume``)."""
    import signal
    import sys
    import time
    import uuid
    from . import commands
    from .meshes import load_all
    from .implementations import available
    from .jobs import stopped_by_signals
    from ..oracles.exact_reference import ReferenceImplementation

    workers = args.workers
    if workers is not None and workers < 1:
        raise commands.UsageError(f"--workers must be >= 1, got {workers}")
    workers = workers or commands.default_workers()
    commands.check_timeout(args)
    if not args.mesh:
        raise commands.UsageError("survey: name the meshes (files, directories, 'pymeshlab:'), "
                             "or --resume DIR")
    if args.report and not args.resume:
        commands.refuse_used_report_dir(args.report)
    meshes = load_all(args.mesh, warn=commands.warn)
    seen: set = set()
    meshes = [m for m in meshes if not (m.name in seen or seen.add(m.name))]   # each name once
    if not meshes:
        from ..reference.errors import InputError
        raise InputError("no usable mesh among " + ", ".join(args.mesh))
    specs = list(dict.fromkeys(args.impl or [s for s in available() if s != "reference"]))
    argv = _argv(args, specs)
    names = [m.name for m in meshes]
    stream, done = None, {}
    if args.report:
        command = {"format": FORMAT, "argv": argv,
                   "report": str(Path(args.report).resolve())}
        try:
            stream = SurveyStream(args.report, names, command)
        except OSError as e:
            raise commands.UsageError(f"--report {args.report}: cannot write there: "
                                 f"{e.strerror or e}") from None
        done = stream.finished()
    todo = [m for m in meshes if m.name not in done]
    t0 = time.perf_counter()
    interrupted = None
    started: dict = {}
    lost: list = []                     # the report directory stopped taking writes

    def finished(result: MeshResult) -> None:
        done[result.name] = result
        if stream is not None and not lost:
            try:
                stream.add(result)
            except OSError as e:        # full, read-only or gone: the run goes on
                lost.append(e)
    try:
        with stopped_by_signals():
            if todo:
                started = commands.start_implementations(specs, args.timeout)
                commands.warn_near_misses(started.values())
            if todo and args.scheduler:
                # the workers start their own: here they were only seen to load (exit 2 at
                # once for a mistake), and a worker may be on another machine
                for impl in started.values():
                    getattr(impl, "close", lambda: None)()
                started = {}
                from . import cluster as dask
                client, cluster_ = dask.connect(args.scheduler)
                print(f"ddg-oracle: {len(todo)} meshes on {dask.n_workers(client)} workers of "
                      f"{args.scheduler}", file=sys.stderr, flush=True)

                def arrived(k, result, error):
                    mesh = todo[k]
                    print(f"ddg-oracle: [{len(done) + 1}/{len(meshes)}] {mesh.name} "
                          f"({len(mesh.F):,} faces)", file=sys.stderr, flush=True)
                    finished(_lost_mesh(mesh, specs, error) if error is not None
                             else MeshResult.from_json(result))
                try:
                    dask.map_on_cluster(client, survey_mesh_in_worker,
                                        (uuid.uuid4().hex, specs, args.timeout), todo, arrived)
                finally:
                    try:
                        client.run(close_in_worker)
                    except Exception:  # noqa: BLE001  (workers gone: their processes with them)
                        pass
                    finally:
                        dask.close(client, cluster_)
            else:
                reference = ReferenceImplementation()
                for k, mesh in enumerate(todo, len(done) + 1):
                    print(f"ddg-oracle: [{k}/{len(meshes)}] {mesh.name} ({len(mesh.F):,} faces)",
                          file=sys.stderr, flush=True)
                    finished(survey_mesh(mesh, started, specs, reference, workers))
    except KeyboardInterrupt as e:
        interrupted = e
    finally:
        for impl in started.values():
            getattr(impl, "close", lambda: None)()
        if stream is not None:
            stream.close()
    seconds = time.perf_counter() - t0
    finished = [done[n] for n in names if n in done]           # mesh order, not finish order
    impl_names = [m for m in dict.fromkeys(r["implementation"] for d in finished for r in d.rows)]
    scores = scoreboard(finished, impl_names)
    print(format_table(scores))
    print("\n" + summary_line(scores, finished, len(meshes)) + f"; {seconds:.0f} s")
    if args.report:
        try:
            files = write(args.report, finished, scores, {"argv": argv, "workers": workers},
                          len(meshes), seconds, interrupted is not None)
        except OSError as e:
            raise commands.UsageError(f"--report {args.report}: could not write ({e.strerror or e})"
                                 ) from None
        print(f"scoreboard: {files['md']}, heatmap: {files['html']}")
        if lost:
            e = lost[0]
            print(f"ddg-oracle: error: --report {args.report}: could not write "
                  f"{SurveyStream.LINES} ({e.strerror or e}); an interrupted run would not "
                  "resume from it", file=sys.stderr)
    if interrupted is not None:
        signum = getattr(interrupted, "signal", signal.SIGINT)
        print(f"ddg-oracle: interrupted by {signal.Signals(signum).name}: {len(finished)} of "
              f"{len(meshes)} meshes finished"
              + (f", kept in {args.report}; finish with: ddg-oracle survey --resume "
                 f"{args.report}" if args.report else " (--report DIR keeps them for --resume)"),
              file=sys.stderr)
        return 128 + signum
    bad = any(s.counts["DIFFERS"] or s.counts["crashed"] for s in scores)
    return 1 if bad else 0
