"""The results of a check as a table, a JSON file, a Markdown summary and per-failure files.

``ddg-oracle check --report DIR`` writes:

* ``index.html``: one self-contained page (:mod:`ddg_oracle.application.html_report`): the
  table with filters and, per non-passing result, a view of its mesh;
* ``results.json``: every result (schema below), deterministic: no times, no
  paths outside DIR, keys sorted, floats as Python's shortest round-trip repr;
  two runs of the derandomized ``ci`` profile give identical bytes;
* ``timings.json``: wall time of the run and of every result (not deterministic);
* ``summary.md``: the table and every non-passing result;
* ``failures/NN-<ID>-<implementation>/``: for each result that is not a pass
  (FAILED, crashed, tie disagreement, convention) with a mesh: ``mesh.obj``
  (the shrunk mesh), ``mesh.png`` (the element in red) and ``reproduce.py``
  (replays the example on the implementation, from any directory:
  :mod:`ddg_oracle.properties.counterexample`).

results.json::

    {"schema": 4,
     "command": {"profile", "seed", "implementations", "only", "meshes", "expect_conventions"},
     "versions": {"python", "numpy", "scipy", "hypothesis", "libigl", "pymeshlab", ...},
     "counts": {status: number}, "interrupted": false | true (a partial run),
     "results": [{"property_id", "property_name", "statement", "implementation", "spec",
                  "source", "status", "ok", "examples", "wanted" (the profile's examples),
                  "ties", "unjudged" (examples with entries an infinite bound could not
                  judge: "passed (N examples; k partly judged)"), "note", "crash", "also",
                  "failure": null | {"message", "element", "element_ids", "expected",
                                     "observed", "error", "bound", "error_in_bounds"},
                  "mesh": null | {"V", "F", "exact_V"?} | {"file", "vertices", "faces"},
                  "files": null | {"obj", "png", "snippet"},
                  "replay": null | "ddg2:..." (the example as JSON, for counterexample.replay),
                  "diagnosis": null | [{"quantity", "status", "where", "expected",
                                        "observed", "worst", "note"}] (how each method the
                               property called answers on the counterexample: compare's rows)}]}

``error_in_bounds`` is the observed error in units of the property's derived
bound (> 1 is a failure), where the property states a bound.
"""

from __future__ import annotations

import json
import math
import re
import sys
import textwrap
from fractions import Fraction
from pathlib import Path

from .causes import counterexample_faces, element_ids, group_hint, root_causes

SCHEMA = 4        # 4: "unjudged" per result
VERSIONED = ("numpy", "scipy", "hypothesis", "libigl", "pymeshlab", "matplotlib")


def jsonable(x):
    """x as JSON values: numpy and Fractions converted, non-finite floats as strings."""
    if x is None or isinstance(x, (bool, str)):
        return x
    if isinstance(x, int):
        return int(x)
    if isinstance(x, float):
        return x if math.isfinite(x) else repr(x)
    if isinstance(x, Fraction):
        return str(x)
    if hasattr(x, "tolist"):                      # numpy scalars and arrays
        return jsonable(x.tolist())
    if isinstance(x, dict):
        return {str(k): jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple, set, frozenset)):
        items = sorted(x, key=repr) if isinstance(x, (set, frozenset)) else x
        return [jsonable(v) for v in items]
    return str(x)


_SCALAR_LIST = re.compile(r'\[\n\s+([^\[\]{}"]*?)\n\s*\]')


def dumps(doc) -> str:
    """Indented JSON, keys sorted, with lists of numbers on one line (a vertex, a face).

    >>> print(dumps({"F": [[0, 1, 2]], "b": None}))
    {
     "F": [
      [0, 1, 2]
     ],
     "b": null
    }
    <BLANKLINE>
    """
    text = json.dumps(doc, indent=1, sort_keys=True, ensure_ascii=False)
    return _SCALAR_LIST.sub(lambda m: "[" + re.sub(r",\s+", ", ", m[1]) + "]", text) + "\n"


def versions() -> dict:
    from importlib import metadata
    out = {"python": sys.version.split()[0]}
    for name in VERSIONED:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            continue
    return out


def _failure_record(f) -> dict | None:
    if f is None:
        return None
    return {"message": f.message, "element": jsonable(f.element),
            "element_ids": element_ids(f.element), "expected": jsonable(f.expected),
            "observed": jsonable(f.observed), "error": jsonable(f.error),
            "bound": jsonable(f.bound), "error_in_bounds": jsonable(f.error_in_bounds)}


def _mesh_record(r) -> dict | None:
    if r.mesh is None:
        return None
    V, F = r.mesh
    if r.source != "generated":
        return {"file": r.source, "vertices": len(V), "faces": len(F)}
    record = {"V": jsonable(V), "F": jsonable(F)}
    if r.exact is not None:
        record["exact_V"] = r.exact          # the floats of V round these rationals
    return record


def result_record(r, statement: str, spec: str, files: dict | None = None) -> dict:
    """One result as the JSON object of results.json."""
    return {"property_id": r.property_id, "property_name": r.property_name,
            "statement": statement, "implementation": r.implementation, "spec": spec,
            "source": r.source, "status": r.status, "ok": r.ok, "examples": r.examples,
            "wanted": r.wanted, "ties": r.ties, "unjudged": r.unjudged, "note": r.note, "crash": r.error, "also": list(r.also),
            "failure": _failure_record(r.failure), "mesh": _mesh_record(r), "files": files,
            "replay": r.replay, "diagnosis": r.diagnosis}


def counts(results) -> dict:
    from ..properties.runner import STATUSES
    return {s: sum(r.status == s for r in results) for s in STATUSES}


# --- table ----------------------------------------------------------------------------------------


def table(results, markdown: bool = False) -> str:
    """One table per source (generated meshes, then each mesh file): a row per property
    (ID and name), a column per implementation, the cell :meth:`Result.summary`."""
    impls = list(dict.fromkeys(r.implementation for r in results))
    sources = list(dict.fromkeys(r.source for r in results))
    blocks = []
    for source in sources:
        rows = [r for r in results if r.source == source]
        props = list(dict.fromkeys((r.property_id, r.property_name) for r in rows))
        cell = {(r.property_id, r.implementation): r.summary() for r in rows}
        head = ["property" if source == "generated" else f"property on {source}"] + impls
        body = [[f"{pid} ({name})"] + [cell.get((pid, n), "-") for n in impls]
                for pid, name in props]
        if markdown:
            lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
            lines += ["| " + " | ".join(row) + " |" for row in body]
        else:
            widths = [max(len(x[k]) for x in [head] + body) + 2 for k in range(len(head))]
            lines = ["".join(x.ljust(w) for x, w in zip(row, widths)).rstrip()
                     for row in [head] + body]
        blocks.append("\n".join(lines))
    return "\n\n".join(blocks)


# --- results as they finish ------------------------------------------------------------------


class ResultStream:
    """``DIR/results.jsonl``: one line per finished task, written and flushed as it
    finishes, so an interrupted run keeps every finished result; ``DIR/run.json``: the
    command line and seed, so ``--resume DIR`` runs the same tasks on the same examples.

    Each line: ``{"task": [spec, property_id, mesh], "results": [record, ...],
    "resume": [Result.to_json(), ...]}`` (the records as in results.json, for people and
    other tools; every field of each Result, for ``--resume``: JSON read back without
    running any code, so a crafted report directory is data, not a program)."""

    RUN, LINES = "run.json", "results.jsonl"

    def __init__(self, directory, tasks, command: dict):
        self.directory = Path(directory)
        self.directory.mkdir(parents=True, exist_ok=True)
        self.tasks = tasks
        run = self.directory / self.RUN
        if not run.exists():
            run.write_text(json.dumps(command, indent=1, sort_keys=True) + "\n", encoding="utf-8")
        lines = self.directory / self.LINES
        # opening a FIFO (or a device) to append blocks, or writes nowhere: refuse it first
        if lines.exists() and not lines.is_file():
            from .commands import UsageError
            from .files import kind_of
            raise UsageError(f"{lines}: cannot keep a run's results there: it is "
                             f"{kind_of(lines.stat().st_mode)}, not a regular file")
        self._fh = open(lines, "a", encoding="utf-8")

    @staticmethod
    def _key(task) -> list:
        return [task.spec, task.property_id, task.mesh]

    @classmethod
    def command_of(cls, directory) -> dict:
        """The run.json of an interrupted run (a usage error if there is none)."""
        from .commands import UsageError
        from .files import read_text
        path = Path(directory) / cls.RUN
        if not path.is_file():
            raise UsageError(f"--resume {directory}: no {cls.RUN} there (not the report "
                             "directory of an interrupted ddg-oracle check --report run)")
        try:
            command = json.loads(read_text(path, "a run's command line", error=UsageError))
        except ValueError as e:
            raise UsageError(f"--resume {directory}: {cls.RUN} is not JSON ({e})") from None
        if not (isinstance(command, dict) and isinstance(command.get("argv"), list)
                and all(isinstance(a, str) for a in command["argv"])):
            raise UsageError(f"--resume {directory}: {cls.RUN} is not one ddg-oracle wrote")
        # the directory it was given, wherever it was moved since (not the path inside)
        command["report"] = str(Path(directory).resolve())
        return command

    def entries(self):
        """(line number, the JSON value) of each line already in results.jsonl; a line that
        is not JSON, other than a last one cut short by an interruption, is a usage error."""
        from .commands import UsageError
        from .files import read_text
        lines = read_text(self.directory / self.LINES, "a run's results",
                          error=UsageError).splitlines()
        for n, line in enumerate(lines, 1):
            try:
                yield n, json.loads(line)
            except json.JSONDecodeError:
                if n == len(lines):
                    continue                # the last line, cut short by the interruption
                raise UsageError(f"--resume {self.directory}: {self.LINES} line {n} is not "
                                 "JSON (not a file ddg-oracle wrote)") from None

    def finished(self) -> dict:
        """{task index: its results} of the lines already in results.jsonl; a line that is
        not one this class wrote (damaged past its last line, or crafted) is a usage error
        naming it, and nothing of it is run or built but plain values."""
        from .commands import UsageError
        from ..properties.codec import BadEncoding
        from ..properties.runner import Result
        index = {tuple(self._key(t)): k for k, t in enumerate(self.tasks)}
        out = {}
        for n, entry in self.entries():
            try:
                k = index.get(tuple(entry["task"]))
                if k is not None:
                    out[k] = [Result.from_json(x) for x in entry["resume"]]
            except (BadEncoding, KeyError, TypeError) as e:
                raise UsageError(f"--resume {self.directory}: {self.LINES} line {n} is not a "
                                 f"result ddg-oracle wrote ({e})") from None
        return out

    def add(self, k: int, results) -> None:
        from ..properties import PROPERTIES
        records = [result_record(r, getattr(PROPERTIES.get(r.property_id), "statement", ""),
                                 self.tasks[k].spec) for r in results]
        line = {"task": self._key(self.tasks[k]), "results": records,
                "resume": [r.to_json() for r in results]}
        self._fh.write(json.dumps(line, sort_keys=True) + "\n")
        self._fh.flush()

    def close(self) -> None:
        try:
            self._fh.close()
        except OSError:
            # a full disk: the failed write was recorded by add() already; closing flushes
            # the same buffer again, which must not turn into an internal error (exit 3)
            pass


# --- the terminal report -------------------------------------------------------------------


def _base(implementation: str) -> str:
    """The library of an implementation's display name: 'libigl(boundary=...)' -> 'libigl'."""
    return implementation.split("(")[0].strip().lower().replace("-", "_")


def known_findings() -> list[dict]:
    """The summary table of docs/findings.md (installed as package data): per finding its
    id, library, kind and the property IDs that find it, split into those on which it is a
    crash or hang (``crashes``) and those on which it is a wrong answer (``answers``)."""
    path = Path(__file__).with_name("data") / "findings.md"
    rows = []
    for line in path.read_text(encoding="utf-8").splitlines():
        m = re.match(r"^\| \[(F-[a-z0-9-]+-\d+)\]\(#[a-z0-9-]+\) \| (\S+)[^|]*\| ([^|(]*)[^|]*\|[^|]*\|"
                     r" ([^|]*)\|$", line)
        if not m:
            continue
        ident, library, kind, found_by = m.groups()
        detail = line.split("|")[3].strip()            # "bug (never returns)"
        # "with `libigl(boundary=library)`": the finding is that option's, not the default's
        options = re.findall(r"with `?[\w-]+\(([^)`]*)\)", found_by)
        ids, crashes = set(), set()
        groups = list(re.finditer(r"propert(?:y|ies) ((?:[A-Z][\w.]*(?: / [A-Z][\w.]*)*"
                                  r"(?:, )?)+)", found_by))
        for i, group in enumerate(groups):
            # what follows a group up to the next one says how it was found: "(... a crash)"
            said = found_by[group.end():groups[i + 1].start() if i + 1 < len(groups) else None]
            for part in re.split(r",\s*|\s*/\s*", group.group(1)):
                if part:
                    ids.add(part.strip())
                    if _CRASH_WORDS.search(said):
                        crashes.add(part.strip())
        never_answers = bool(_CRASH_WORDS.search(detail))      # "bug (never returns)"
        rows.append({"id": ident, "library": _base(re.sub(r"('s|[^\w-])+$", "", library)),
                     "kind": kind.strip(), "detail": detail, "properties": ids,
                     "crashes": ids if never_answers else crashes,
                     "answers": set() if never_answers else ids, "options": options})
    return rows


def known_finding(r, findings) -> str | None:
    """The id of the documented finding a non-passing result is, if any: never for a result
    that is not the implementation's (undecided: the exact reference gave up; internal
    error; incomplete)."""
    from ..properties.runner import CRASHED, INCOMPLETE, INTERNAL, TIE, UNDECIDED
    if r.status in (UNDECIDED, INTERNAL, INCOMPLETE):
        return None

    parts = {x.strip() for x in r.property_id.split("/")}
    # a crash or hang is only ever the finding of a crash or hang on that property ("never
    # returns", or "a crash" where the finding names it), an answer only one of an answer:
    # a hang of CGAL's flips is not its documented precision limit on the same property
    seen = "crashes" if r.status == CRASHED else "answers"
    hits = [f for f in findings
            if f["library"] == _base(r.implementation) and parts & f[seen]
            and (not f["options"]) == ("(" not in r.implementation)
            and all(o.replace("=", "='") in r.implementation or o in r.implementation
                    for o in f["options"])]
    # a tie is first a precision limit; a failure first a bug or convention
    tie_kind = [f for f in hits if (f["kind"] == "precision limit") == (r.status == TIE)]
    return (tie_kind or hits or [{"id": None}])[0]["id"]


_CRASH_WORDS = re.compile(r"never returns|crash|segfault|hang|abort|out of memory|bad_alloc",
                          re.I)


def fit(text: str, width: int) -> str:
    """Every line at most ``width`` columns: long lines wrapped, keeping their indent."""
    out = []
    for line in text.splitlines():
        if len(line) <= width:
            out.append(line)
            continue
        indent = " " * (len(line) - len(line.lstrip()) + 2)
        out.extend(textwrap.wrap(line, width, subsequent_indent=indent,
                                 break_long_words=True, break_on_hyphens=False))
    return "\n".join(out)


def _ids(results, members, limit: int = 8) -> str:
    ids = [results[k].property_id for k in members]
    return ", ".join(ids[:limit]) + (f", ... ({len(ids) - limit} more)" if len(ids) > limit else "")


def terminal_report(results, width: int = 100, files: dict | None = None,
                    list_ties: bool = False) -> str:
    """What ``ddg-oracle check`` prints: at most ``width`` columns.  Root causes first: the
    failures of each implementation grouped by the protocol method they blame, with the
    wrong answer on the smallest counterexample ("cotan_laplacian at entry (0, 1):
    expected -0.5, observed 0.5"), one line per failing property under it; crashes with
    one message collapsed into one group with a count; then incomplete, undecided,
    conventions and our own internal errors; tie disagreements in one line per
    implementation (``list_ties``: in full); the passes per implementation, the
    not-applicable ones in one line per implementation; then one full block per root
    cause and crash group (its smallest counterexample; the others named) and per other
    non-passing result (``files``: result index -> where its whole mesh and snippet are)."""
    from ..properties.runner import CONVENTION, FAILED, NOT_APPLICABLE, PASSED
    from ..properties.runner import INCOMPLETE, INTERNAL, TIE, UNDECIDED, describe

    findings = known_findings()
    impls = list(dict.fromkeys(r.implementation for r in results))
    lines = []
    sources = list(dict.fromkeys(r.source for r in results))
    causes, crashes = root_causes(results)

    def row(r, indent="  ", more=""):
        what = (r.failure.message if r.failure is not None else
                (r.error or (r.note if r.status == INCOMPLETE else None) or r.status)
                ).splitlines()[0]
        known = known_finding(r, findings)
        where = "" if r.source == "generated" else f" [{r.source}]"
        head = f"{indent}{r.property_id:<14} {r.implementation[:22]:<22} "
        tail = more + (f"  (known: {known})" if known else "")
        room = max(10, width - len(head) - len(tail) - len(where))
        what = what if len(what) <= room else what[:room - 3] + "..."
        return head + what + where + tail

    def group_known(c):
        ids = sorted({k for m in c.members if (k := known_finding(results[m], findings))})
        return f" (known: {', '.join(ids)})" if ids else ""

    failed = sum(r.status == FAILED for r in results)
    if failed:
        lines.append(f"FAILED ({failed}): {len(causes)} root cause{'s' if len(causes) != 1 else ''}")
        for c in causes:
            n = len(c.members)
            blame = " or ".join(c.methods) if c.methods else "an answer"
            head = (f"{c.implementation}: {blame} {'is' if len(c.methods) <= 1 else 'are'} wrong, "
                    f"{n} propert{'ies' if n != 1 else 'y'} fail{'s' if n == 1 else ''}"
                    + group_known(c))
            if c.where:
                first = results[c.first]
                head += (f"; smallest counterexample {counterexample_faces(first)} face"
                         f"{'s' if counterexample_faces(first) != 1 else ''} ({first.property_id}): {c.where}")
            hint = group_hint(results, c.members)
            if hint:
                head += f"; {hint}"
            lines.append(fit(head, width))
            lines.extend(row(results[k]) for k in c.members)
    if crashes:
        n = sum(len(c.members) for c in crashes)
        lines.append(f"crashed ({n}): {len(crashes)} message{'s' if len(crashes) != 1 else ''}")
        for c in crashes:
            first = results[c.first]
            lines.append(row(first, more=f"  [x{len(c.members)}]" if len(c.members) > 1 else ""))
    for title, statuses in (("internal errors of ddg-oracle (not the implementation's: please "
                             "report them)", (INTERNAL,)),
                            ("incomplete: fewer examples ran than the profile asks for",
                             (INCOMPLETE,)),
                            ("conventions", (CONVENTION,)), ("undecided", (UNDECIDED,))):
        chosen = [r for r in results if r.status in statuses]
        if chosen:
            lines.append(f"{title} ({len(chosen)})")
            lines.extend(row(r) for r in chosen)
    ties = [r for r in results if r.status == TIE]
    if ties:
        per = {}
        for r in ties:
            per.setdefault(r.implementation, []).append(r)
        lines.append(f"tie disagreements ({len(ties)}): exact ties rounding decided otherwise, "
                     "not errors" + ("" if list_ties else " (--ties lists them)"))
        if list_ties:
            lines.extend(row(r) for r in ties)
        else:
            lines.append(fit("  " + "; ".join(
                f"{n} {len(rs)} ({', '.join(r.property_id for r in rs)})" for n, rs in per.items()),
                width))
    passed = [(n, sum(r.status == PASSED for r in results if r.implementation == n),
               sum(r.status != NOT_APPLICABLE for r in results if r.implementation == n))
              for n in impls]
    lines.append("passed (of the applicable checks" + (
        f", {len(sources)} sources" if len(sources) > 1 else "") + ")")
    lines.append(fit("  " + ", ".join(f"{n} {k}/{m}" for n, k, m in passed), width))
    partly = [r for r in results if r.status == PASSED and r.unjudged]
    if partly:
        lines.append(f"passed, partly judged ({len(partly)}): some entries had an infinite "
                     "derived bound (beyond the declared precision's resolution) and an answer "
                     "other than the exact value's float; they were not judged")
        lines.extend(row(r, more=f"  ({r.note})") for r in partly)
    na = [(n, sum(r.status == NOT_APPLICABLE for r in results if r.implementation == n))
          for n in impls]
    if any(k for _, k in na):
        lines.append("not applicable (a method the property needs is missing, or every example "
                     "was declined)")
        lines.append(fit("  " + ", ".join(f"{n} {k}" for n, k in na if k), width))

    def block(k, others=()):
        where = (files or {}).get(k)
        text = describe(results[k], limit=12, snippet_lines=14, files=where)
        if others:
            text += (f"\n  the same cause, {len(others)} more (their rows above): "
                     + _ids(results, others, limit=len(others)))
        lines.append("")
        lines.append(fit(text, width))

    for c in causes + crashes:
        block(c.first, c.members[1:])
    shown = {k for c in causes + crashes for k in c.members}
    for k, r in enumerate(results):
        if k in shown or r.status in (PASSED, NOT_APPLICABLE) or (r.status == TIE and not list_ties):
            continue
        block(k)
    return "\n".join(lines)


def closing_line(results, seconds: float, workers: int, profile: str, seed,
                 accept_incomplete: bool = False) -> str:
    """The last lines: counts, what the exit code means, what to run next."""
    from ..properties.runner import CRASHED, FAILED, INCOMPLETE, INTERNAL

    c = counts(results)
    findings = known_findings()
    bad = [r for r in results if r.status in (FAILED, CRASHED)]
    partial = sum(r.status == INCOMPLETE for r in results)
    known = sorted({k for r in bad if (k := known_finding(r, findings))})
    head = (f"{len(results)} checks in {seconds:.1f} s, {workers} worker"
            f"{'s' if workers != 1 else ''}, profile {profile}"
            + (f", seed {seed} (rerun: --seed {seed})" if seed is not None else "") + ": "
            + ", ".join(f"{n} {s}" for s, n in c.items() if n))
    ours = sum(r.status == INTERNAL for r in results)
    if ours:
        meaning = (f"exit 3: ddg-oracle itself failed on {ours} check{'s' if ours != 1 else ''} "
                   "(internal error: not the implementation's; please report it with the "
                   "example shown)" + (f"; {len(bad)} failed or crashed" if bad else ""))
    elif bad:
        unknown = len(bad) - sum(1 for r in bad if known_finding(r, findings))
        meaning = (f"exit 1: {len(bad)} check{'s' if len(bad) != 1 else ''} failed or crashed"
                   + (f"; known findings {', '.join(known)} (docs/findings.md)" if known else "")
                   + (f"; {unknown} not documented" if unknown and known else "")
                   + (f"; {partial} incomplete" if partial else ""))
    elif partial and not accept_incomplete:
        meaning = (f"exit 1: no failure, but {partial} check{'s' if partial != 1 else ''} "
                   "ran fewer examples than the profile asks for (incomplete: not a pass; "
                   "--budget SECONDS gives each more time, --accept-incomplete exits 0)")
    else:
        meaning = "exit 0: no failure" + (f" ({partial} incomplete, accepted)" if partial else "")
    return (head + "\n" + meaning + "\nnext: ddg-oracle check --impl module:Class checks your "
            "own code; --report DIR writes every counterexample; --wide shows the full grid")


# --- files per failure ----------------------------------------------------------------------------


_SNIPPET = '''"""Reproduce: {title}

Found by `ddg-oracle check`{how}.  Run it wherever ddg-oracle and the checked
implementation are installed:  python {name}
It runs the property once more on the same example and raises the same failure
(or the implementation's crash); it prints "passes now" if the failure is gone.
"""

{code}
print("passes now")
'''

_SNIPPET_FILE = '''"""Reproduce: {title}

Found by `ddg-oracle check`{how}: a mesh too large to replay inline; this runs
the same check on mesh.obj beside this file.  Run:  python {name}
"""

import subprocess
import sys
from pathlib import Path

mesh = str(Path(__file__).with_name("mesh.obj"))
sys.exit(subprocess.call([sys.executable, "-m", "ddg_oracle", "check", "--mesh", mesh,
                          "--impl", {spec!r}, "--only", {pid!r}, "--workers", "1"],
                         cwd={cwd!r}))   # where the implementation loads from
'''


def snippet(r, spec: str, name: str = "reproduce.py") -> str:
    """The Python file that reproduces result ``r`` (see the module doc)."""
    from ..properties.counterexample import snippet as replay_snippet

    title = describe_line(r)
    how = "" if r.source == "generated" else f" on {r.source}"
    if r.replay is not None:
        return _SNIPPET.format(title=title, how=how, name=name,
                               code=replay_snippet(r.property_id, r.spec or spec, r.replay))
    from ..properties.counterexample import module_dir, program_dir
    spec = r.spec or spec
    cwd = module_dir(spec) or program_dir(spec)
    return _SNIPPET_FILE.format(title=title, how=how, name=name, spec=spec, pid=r.property_id,
                                cwd=cwd)


def describe_line(r) -> str:
    if r.failure is not None:
        return str(r.failure).splitlines()[0]
    said = (r.error or r.note or "").splitlines()
    return f"[{r.property_id}] {r.implementation}: {r.status}" + (f": {said[0]}" if said else "")


def _slug(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9.]+", "_", text).strip("_")[:60]


def write_failure_files(directory: Path, k: int, r, spec: str, picture: bool = True) -> dict:
    """mesh.obj, mesh.png (with the ``pictures`` extra) and reproduce.py of result ``r``;
    their paths relative to ``directory``."""
    from .meshfiles import write_obj

    sub = Path("failures") / f"{k:02d}-{_slug(r.property_id)}-{_slug(r.implementation)}"
    d = directory / sub
    d.mkdir(parents=True, exist_ok=True)
    V, F = r.mesh
    write_obj(d / "mesh.obj", [[float(c) for c in (list(p) + [0] * (3 - len(p)))] for p in V], F)
    out = {"obj": f"{sub.as_posix()}/mesh.obj", "snippet": f"{sub.as_posix()}/reproduce.py"}
    if picture and _has_matplotlib():
        from .render import render_mesh
        ids = element_ids(r.failure.element) if r.failure is not None else None
        render_mesh(d / "mesh.png", V, F, ids, title=describe_line(r)[:240])
        out["png"] = f"{sub.as_posix()}/mesh.png"
    (d / "reproduce.py").write_text(snippet(r, spec), encoding="utf-8")
    return out


def _has_matplotlib() -> bool:
    import importlib.util
    return importlib.util.find_spec("matplotlib") is not None


def write_counterexamples(directory, results, spec_of: dict, picture: bool = False) -> dict:
    """The failure files of every non-passing result with a mesh; {result index: its folder}."""
    from ..properties.runner import NOT_APPLICABLE, PASSED

    directory = Path(directory)
    out, k = {}, 0
    for i, r in enumerate(results):
        if r.status in (PASSED, NOT_APPLICABLE) or r.mesh is None:
            continue
        k += 1
        files = write_failure_files(directory, k, r, spec_of.get(r.implementation,
                                                                   r.implementation), picture)
        out[i] = files
    return out


def write_report(directory, results, command: dict, spec_of: dict, timings: dict,
                 interrupted: bool = False) -> dict:
    """Write results.json, index.html, timings.json, summary.md and the failure files into
    ``directory``;
    returns {result index: its failure files} (paths relative to ``directory``)."""
    from ..properties import PROPERTIES
    from ..properties.runner import PASSED, NOT_APPLICABLE, describe

    from .files import write_atomically
    from .html_report import page_data, write_html

    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    failure_files = write_counterexamples(directory, results, spec_of, picture=True)
    records, sections = [], []
    for i, r in enumerate(results):
        p = PROPERTIES.get(r.property_id)
        spec = spec_of.get(r.implementation, r.implementation)
        files = failure_files.get(i)
        if r.status not in (PASSED, NOT_APPLICABLE):
            sections.append((r, files))
        records.append(result_record(r, p.statement if p else "", spec, files))
    doc = {"schema": SCHEMA, "command": jsonable({k: v for k, v in command.items() if k != "argv"}),
           "versions": versions(), "counts": counts(results), "results": records,
           "interrupted": interrupted}
    text = dumps(doc)
    write_atomically(directory / "results.json", text)
    findings = known_findings()
    known = {i: k for i, r in enumerate(results)
             if r.status not in (PASSED, NOT_APPLICABLE) and (k := known_finding(r, findings))}
    snippets = {i: snippet(r, spec_of.get(r.implementation, r.implementation))
                for i, r in enumerate(results) if i in failure_files}
    write_html(directory, text, known, page_data(results, known, command.get("argv"), snippets))
    write_atomically(directory / "timings.json", json.dumps(timings, indent=1, sort_keys=True) + "\n")
    c = counts(results)
    md = ["# ddg-oracle check" + (" (interrupted: partial)" if interrupted else ""), "",
          "Command: `ddg-oracle check " + " ".join(command.get("argv", [])) + "`", "",
          ", ".join(f"{n} {s}" for s, n in c.items() if n), "", table(results, markdown=True), ""]
    if sections:
        md += ["## Not passed", ""]
    for r, files in sections:
        md += [f"### [{r.property_id}] {r.implementation}: {r.status}"
               + ("" if r.source == "generated" else f" on {r.source}"), "",
               "```", describe(r), "```", ""]
        if files:
            if "png" in files:
                md += [f"![{r.property_id} {r.implementation}]({files['png']})", ""]
            md += [f"Mesh: [{files['obj']}]({files['obj']}); reproduce: "
                   f"`python {files['snippet']}`", ""]
    write_atomically(directory / "summary.md", "\n".join(md))
    return failure_files
