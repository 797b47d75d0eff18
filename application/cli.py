"""The ddg-oracle command: check implementations against the exact reference, compare
them on given meshes, print the catalog.

Exit codes (the same for every subcommand, so CI can tell a finding from a broken tool):

- 0: no failure (passes, not applicable, tie disagreements, expected conventions);
- 1: a property failed, a checked implementation crashed or hung, or a check ran fewer
  examples than its profile asks for (``incomplete``; ``check --accept-incomplete``
  accepts it) (or, for ``theorems
  --check``, the table is not true; for ``compare``, an implementation differs);
- 2: bad usage or bad input (one line on stderr, no traceback);
- 3: ddg-oracle itself failed (its traceback, and a request for a bug report).
"""

from __future__ import annotations

import argparse
import os
import random
import sys
import tempfile
import textwrap
import time
import traceback
from functools import partial
from pathlib import Path

from ddg_oracle import __version__
from .commands import (DEFAULT_WORKERS, UsageError, check_timeout, default_workers,
                                 refuse_used_report_dir, start_implementations, warn,
                                 warn_near_misses)
from ..reference.errors import InputError

EXIT_OK, EXIT_FINDINGS, EXIT_USAGE, EXIT_TOOL = 0, 1, 2, 3
BUG_REPORT = ("ddg-oracle: internal error (exit 3): this is a bug in ddg-oracle, not in the "
              "checked code; please report it with the command line and the traceback above")
EXIT_CODES = """\
exit codes:
  0  no failure (passes, not applicable, tie disagreements, expected conventions)
  1  a property failed or a checked implementation crashed
     (check: or hung, or a check was incomplete, unless --accept-incomplete)
  2  bad usage or bad input (one line on stderr)
  3  ddg-oracle itself failed (traceback; please report it)"""


def exit_codes(one: str | None) -> str:
    """:data:`EXIT_CODES` of another command: exit 1 means ``one`` (None: it has no exit 1),
    and the check-only remark goes."""
    out = []
    for line in EXIT_CODES.splitlines():
        if line.startswith("     (check:"):
            continue
        if line.startswith("  1 "):
            if one is None:
                continue
            line = f"  1  {one}"
        out.append(line)
    return "\n".join(out)


class _Parser(argparse.ArgumentParser):
    """Usage errors in one line, as every other error of ours (no usage block)."""

    def error(self, message):
        self.exit(EXIT_USAGE, f"ddg-oracle: error: {message} (see: {self.prog} --help)\n")


def _epilog(examples: str, codes: str = EXIT_CODES, specs: bool = False) -> str:
    kinds = ""
    if specs:
        from .implementations import BUILTIN
        names = textwrap.fill(", ".join(BUILTIN), 70, subsequent_indent=" " * 20)
        kinds = SPEC_KINDS.format(builtin=names) + "\n\n"
    return ("examples:\n" + textwrap.indent(textwrap.dedent(examples).strip(), "  ") + "\n\n"
            + kinds + codes)


#: the kinds of implementation spec every --impl takes, one example each (the help's words)
SPEC_KINDS = """\
implementations (--impl SPEC):
  NAME              a built-in adapter: {builtin}
                    (options in parentheses: 'libigl(boundary=library)')
  module:object     your Python class or object, imported as Python does with the current
                    directory appended: --impl mypkg.geometry:MyImpl
  exec:COMMAND      a program in any language speaking the executable protocol
                    (docs/protocol.md): --impl 'exec:node driver.js', 'exec:./my_driver'
  exec:FILE.json    a driver manifest (docs/protocol.md), for a program without a handshake
the protocol methods an implementation may define: ddg-oracle methods"""


def parser() -> argparse.ArgumentParser:
    """The argument parser of ``ddg-oracle`` (plain-text help, examples, exit codes)."""
    fmt = argparse.RawDescriptionHelpFormatter
    top = _Parser(
        prog="ddg-oracle", formatter_class=fmt,
        description="Check discrete differential geometry code against an exact reference "
                    "of Bobenko's notes.",
        epilog=_epilog("""
            ddg-oracle check                          every installed library, every property
            ddg-oracle check --impl mymodule:MyImpl   your own implementation
            ddg-oracle check --impl 'exec:node drv.js'  a program in any language
            ddg-oracle methods                        the methods an implementation may define
            ddg-oracle compare bunny.obj              every quantity on one mesh
            ddg-oracle theorems --check               is the traceability table true?"""))
    top.add_argument("--version", action="version", version=f"ddg-oracle {__version__}")
    sub = top.add_subparsers(dest="command", required=True, metavar="COMMAND",
                             parser_class=_Parser)

    c = sub.add_parser(
        "check", formatter_class=fmt, help="run every property against implementations",
        description="Run every applicable property (one per catalog ID) on generated meshes, "
                    "or on given mesh files, against each implementation, and print a table "
                    "and every counterexample.",
        epilog=_epilog("""
            ddg-oracle check
            ddg-oracle check --impl mypkg.geometry:MyImpl --profile ci
            ddg-oracle check --impl 'exec:node driver.js'
            ddg-oracle check --impl libigl --only D3.1 L4.3 --report out/
            ddg-oracle check --mesh bunny.obj --impl 'libigl(boundary=library)'""", specs=True))
    c.add_argument("--impl", action="append", metavar="SPEC",
                   help="implementation to check (repeatable; default: every installed one): "
                        "NAME, module:object, exec:COMMAND or exec:FILE.json (below)")
    c.add_argument("--drivers", metavar="DIR",
                   help="without --impl, also check the C++ library drivers built in DIR "
                        "(cgal_driver, openmesh_driver; default: $DDG_ORACLE_DRIVERS, else "
                        "examples/cpp/build, where bash examples/cpp/build.sh puts them)")
    c.add_argument("--profile", default="default", choices=("default", "ci", "thorough"),
                   help="Hypothesis profile (ci: derandomized, more examples; default: default)")
    c.add_argument("--seed", type=int, default=None,
                   help="Hypothesis seed (default: derandomized under ci, else one random seed "
                        "for the run, printed; every implementation sees the same examples)")
    c.add_argument("--budget", type=float, default=None, metavar="SECONDS",
                   help="wall-clock seconds per task (one property on one implementation), "
                        "shrinking included; a call still running then is a hang; 0: none "
                        "(default: 18, at most 3 of them shrinking, with --profile default; "
                        "40, at most 10 shrinking, with ci; none with thorough)")
    c.add_argument("--examples", type=int, default=None, metavar="N",
                   help="examples per property and implementation (default: the profile's: "
                        "25 default, 60 ci, 1,000 thorough); fewer: a quick smoke run")
    c.add_argument("--only", action="extend", nargs="+", metavar="ID",
                   help="only these catalog IDs (several, or comma-separated; any part of a "
                        "joint ID: L4.3 selects 'L4.3 / P4.4')")
    c.add_argument("--timeout", type=float, default=60.0,
                   help="seconds per call of a checked implementation before it is killed "
                        "and reported as hanging, per 10,000 faces of the input (never less; "
                        "default 60)")
    c.add_argument("--mesh", action="extend", nargs="+", metavar="FILE",
                   help="check on these mesh files (OBJ, OFF, PLY, STL) instead of generated "
                        "meshes; 'pymeshlab:' = every sample mesh PyMeshLab ships, "
                        "'pymeshlab:NAME' one of them; 'cgal:' = every mesh of the CGAL "
                        "corpus, 'cgal:NAME' one of them (fetched once by: ddg-oracle corpus "
                        "fetch); 'pyvista:' and 'compas:' the meshes those wheels ship "
                        "(ddg-oracle corpus fetch pyvista compas)")
    c.add_argument("--report", metavar="DIR",
                   help="write results.json, summary.md, timings.json and, per failure, the "
                        "mesh (OBJ), a picture (PNG) and a reproducing snippet into DIR "
                        "(a new or empty directory)")
    c.add_argument("--resume", metavar="DIR",
                   help="finish an interrupted run from its report directory (the tasks "
                        "already in DIR/results.jsonl are not run again; the same command "
                        "line and seed)")
    c.add_argument("--workers", type=int, default=None, metavar="N",
                   help=f"worker processes (default {default_workers()}: "
                        f"min({DEFAULT_WORKERS}, number of CPUs)); 1 runs in this process")
    c.add_argument("--scheduler", metavar="ADDRESS",
                   help="run the tasks on a dask.distributed cluster: a scheduler's address "
                        "(tcp://host:8786) or local:N (N worker processes started for the run); "
                        "a lost worker's tasks run again elsewhere; needs "
                        "pip install 'ddg-oracle[dask]'")
    c.add_argument("--wide", action="store_true",
                   help="print the full grid (property x implementation) instead of the "
                        "compact report")
    c.add_argument("--ties", action="store_true",
                   help="list every tie disagreement in full (default: one line per "
                        "implementation; they are exact ties that rounding decides, not errors)")
    c.add_argument("--width", type=int, default=100, metavar="COLUMNS",
                   help="columns of the compact report (default 100)")
    c.add_argument("--accept-incomplete", action="store_true",
                   help="exit 0 although some checks are incomplete (their budget ran out, "
                        "or the implementation declined most examples, before the profile's "
                        "number of examples ran); they are still reported as incomplete")
    c.add_argument("--expect-conventions", action="store_true",
                   help="a failure of an implementation using a documented library convention "
                        "(e.g. 'libigl(boundary=library)') that the reference-convention adapter "
                        "passes is reported as 'convention', not as a failure")

    m = sub.add_parser(
        "compare", formatter_class=fmt,
        help="every quantity on given meshes: reference vs implementations",
        description="For each mesh, every protocol quantity of every implementation against "
                    "the exact reference: agrees or DIFFERS, the largest error in units of "
                    "the derived bound, and where.",
        epilog=_epilog("""
            ddg-oracle compare bunny.obj
            ddg-oracle compare pymeshlab:bunny10k_textured.obj --impl libigl
            ddg-oracle compare a.off b.ply --impl mymodule:MyImpl --impl 'exec:./my_driver'""",
                       exit_codes("an implementation differs or crashed"), specs=True))
    m.add_argument("mesh", nargs="+", metavar="MESH",
                   help="mesh file, or 'pymeshlab:' / 'pymeshlab:NAME' (sample meshes), "
                        "'cgal:' / 'cgal:NAME' (the CGAL corpus: ddg-oracle corpus fetch), "
                        "'pyvista:', 'compas:' (ddg-oracle corpus fetch pyvista compas)")
    m.add_argument("--impl", action="append", metavar="SPEC",
                   help="implementation to compare (repeatable; default: every installed one): "
                        "NAME, module:object, exec:COMMAND or exec:FILE.json (below)")
    m.add_argument("--timeout", type=float, default=60.0,
                   help="seconds per call, per 10,000 faces of the input (never less; default 60)")

    s = sub.add_parser(
        "survey", formatter_class=fmt,
        help="every implementation x every quantity x a mesh corpus: a scoreboard",
        description="Compare every implementation with the exact reference on every mesh of "
                    "a corpus (one mesh at a time, all implementations on it) and print a "
                    "scoreboard per implementation and quantity: meshes checked, agrees, "
                    "DIFFERS, crashed, not applicable, the worst error in units of the derived "
                    "bound (and on which mesh) and the median.  With --report DIR, each "
                    "finished mesh is kept in DIR/results.jsonl as it finishes (an interrupted "
                    "survey resumes with --resume DIR), and the scoreboard is written to "
                    "DIR/survey.md, DIR/survey.html (a heatmap) and DIR/results.json.",
        epilog=_epilog("""
            ddg-oracle survey pymeshlab:
            ddg-oracle survey meshes/ --impl libigl --impl trimesh --report out/
            ddg-oracle survey --resume out/""",
                       exit_codes("an implementation differs or crashed")
                       + "\n  130, 143  interrupted by SIGINT, SIGTERM (--resume DIR finishes it)",
                       specs=True))
    s.add_argument("mesh", nargs="*", metavar="MESH",
                   help="mesh files, directories of them, or mesh sets ('pymeshlab:', any set "
                        "compare takes)")
    s.add_argument("--mesh", dest="mesh_option", action="extend", nargs="+", metavar="MESH",
                   help="the same, as check --mesh takes them (added to the MESH arguments)")
    s.add_argument("--impl", action="append", metavar="SPEC",
                   help="implementation to survey (repeatable; default: every installed one): "
                        "NAME, module:object, exec:COMMAND or exec:FILE.json (below)")
    s.add_argument("--timeout", type=float, default=60.0,
                   help="seconds per call, per 10,000 faces of the input (never less; default 60)")
    s.add_argument("--workers", type=int, default=None, metavar="N",
                   help=f"processes computing the exact values of each mesh (default "
                        f"{default_workers()}); 1 computes them in this process")
    s.add_argument("--scheduler", metavar="ADDRESS",
                   help="survey the meshes on a dask.distributed cluster, one mesh per task "
                        "(each worker starts the implementations once): a scheduler's "
                        "address (tcp://host:8786) or local:N; a lost worker's mesh runs "
                        "again elsewhere; needs pip install 'ddg-oracle[dask]'")
    s.add_argument("--report", metavar="DIR",
                   help="keep each finished mesh in DIR/results.jsonl and write the scoreboard "
                        "to DIR/survey.md, DIR/survey.html and DIR/results.json (a new or "
                        "empty directory)")
    s.add_argument("--resume", metavar="DIR",
                   help="finish an interrupted survey from its report directory (its command "
                        "line is read from DIR/run.json; the meshes already in "
                        "DIR/results.jsonl are not run again)")

    v = sub.add_parser(
        "vectors", formatter_class=fmt, help="write the portable test vectors (JSON)",
        description="Write the test-vector corpus: per protocol method a JSON file of cases "
                    "(input, exact value, correctly rounded float64, float64 and float32 "
                    "tolerances), manifest.json, schema.json and a README for suites in any "
                    "language.  Deterministic: the same ddg-oracle writes the same bytes.",
        epilog=_epilog("""
            ddg-oracle vectors --out vectors/
            ddg-oracle verify vectors/ my_answers.jsonl""", exit_codes(None)))
    v.add_argument("--out", required=True, metavar="DIR", help="directory to write (created)")

    w = sub.add_parser(
        "verify", formatter_class=fmt, help="check an answers file against the test vectors",
        description="Check an implementation's answers (JSON Lines, one {\"id\", \"value\"} or "
                    "{\"id\", \"error\"} per case, values as in the executable protocol) against "
                    "a corpus written by 'ddg-oracle vectors': one line per failing case.  With "
                    "--impl, the answers are computed by that implementation (any spec 'check' "
                    "takes, e.g. 'exec:./my_driver').",
        epilog=_epilog("""
            ddg-oracle verify vectors/ answers.jsonl
            ddg-oracle verify vectors/ answers.jsonl --float32
            ddg-oracle verify vectors/ --impl 'exec:./my_driver' --write-answers answers.jsonl""",
                       exit_codes("a case failed"), specs=True))
    w.add_argument("corpus", metavar="DIR", help="a directory written by 'ddg-oracle vectors'")
    w.add_argument("answers", nargs="?", metavar="ANSWERS", help="the answers file (JSON Lines)")
    w.add_argument("--impl", metavar="SPEC",
                   help="compute the answers with this implementation instead of reading them: "
                        "NAME, module:object, exec:COMMAND or exec:FILE.json (below)")
    w.add_argument("--write-answers", metavar="FILE", help="with --impl: also save its answers")
    w.add_argument("--float32", action="store_true",
                   help="hold the answers to the float32 tolerances (default: float64; with "
                        "--impl: the implementation's declared machine_epsilon)")
    w.add_argument("--timeout", type=float, default=60.0,
                   help="with --impl: seconds per call, per 10,000 faces (default 60)")

    m = sub.add_parser(
        "methods", formatter_class=fmt,
        help="list the protocol methods an implementation may define",
        description="Every protocol method: its arguments, what it answers in the reference's "
                    "conventions, and the catalog IDs of the properties that call it.  Define "
                    "any of them on a class (or list them in an exec driver's handshake); the "
                    "properties of the others are not applicable.",
        epilog=_epilog("""
            ddg-oracle methods
            ddg-oracle methods --impl mymodule:MyImpl   which of them it defines
            ddg-oracle methods | grep cotan""", exit_codes(None)))
    m.add_argument("--impl", metavar="SPEC",
                   help="an implementation (as for check): the methods it defines, its declared "
                        "precision and conventions, and names that look like a method it lacks")
    m.add_argument("--timeout", type=float, default=60.0, help=argparse.SUPPRESS)

    from . import corpus
    k = sub.add_parser(
        "corpus", formatter_class=fmt, help="fetch and list the mesh corpora (cgal:, pyvista:, "
                                            "compas:)",
        description=corpus.DESCRIPTION,
        epilog=_epilog("""
            ddg-oracle corpus fetch              CGAL's meshes (apt-get download libcgal-demo)
            ddg-oracle corpus fetch all          CGAL's, PyVista's and COMPAS's
            ddg-oracle corpus list pyvista
            ddg-oracle check --mesh cgal: --impl libigl""",
            exit_codes(None)))
    corpus.add_arguments(k)

    t = sub.add_parser(
        "theorems", formatter_class=fmt, help="print the traceability table and the notes' items",
        description="Print the traceability table (catalog ID, status, reference function "
                    "and property) and every numbered item of chapters 1-4 of the notes "
                    "with its line and status (verified, erratum, definition, not "
                    "verifiable, open).",
        epilog=_epilog("""
            ddg-oracle theorems
            ddg-oracle theorems --check""",
                       exit_codes("--check: the table is not true")))
    t.add_argument("--check", action="store_true",
                   help="exit 1 unless every named function, property and test exists, "
                        "every row of a claimed chapter is verified, and every numbered "
                        "item of the notes is listed at its line with rows or a reason")
    return top


def main(argv=None) -> int:
    if argv is None:
        # as the command (not called from Python): no third-party Hypothesis plugin in this
        # process or its workers.  The properties use none, and trio's (which selenium
        # installs) costs 0.17 s of CPU at every start of a process.  A value set stands.
        os.environ.setdefault("HYPOTHESIS_NO_PLUGINS", "1")
        # and its workers forked from a forkserver that imported the properties once
        from .containment import start_workers_from_a_forkserver
        start_workers_from_a_forkserver()
    try:
        args = parser().parse_args(argv)
    except SystemExit as e:                # --help, --version (0) or a bad command line (2)
        return e.code if isinstance(e.code, int) else EXIT_USAGE
    from .containment import contained
    from .jobs import stopped_by_signals
    with contained(subreaper=argv is None), stopped_by_signals():
        return _main(args, argv)


def _main(args, argv) -> int:
    """The command of ``args``, with every expected failure a one-line error (exit 2) and
    any other a bug report (exit 3); inside :func:`~ddg_oracle.application.containment.contained`."""
    from .implementations import ImplementationNotFound
    from ..protocol.methods import NotAnImplementation
    try:
        if args.command == "check":
            # the check's own arguments: after the command name (the first argument)
            return _check(args, None if argv is None else list(argv)[1:])
        if args.command == "compare":
            return _compare(args)
        if args.command == "survey":
            return _survey(args)
        if args.command == "vectors":
            return _vectors(args)
        if args.command == "verify":
            return _verify(args)
        if args.command == "methods":
            return _methods(args)
        if args.command == "corpus":
            from . import corpus
            return corpus.run(args)
        return _theorems(args)
    except (InputError, ImplementationNotFound, NotAnImplementation) as e:
        print(f"ddg-oracle: error: {e}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt as e:           # before or after the run itself: no traceback
        import signal
        signum = getattr(e, "signal", signal.SIGINT)
        print(f"ddg-oracle: interrupted by {signal.Signals(signum).name}", file=sys.stderr)
        return 128 + signum
    except BrokenPipeError:                  # e.g. piped into head: stop quietly
        sys.stdout = open(os.devnull, "w")
        return EXIT_FINDINGS
    except Exception as e:  # noqa: BLE001  (anything else is a bug of ours: say so, distinctly)
        if isinstance(e, OSError) and "AF_UNIX path too long" in str(e):
            # the machine's setting, not our bug: Python's worker processes talk over sockets
            # named in TMPDIR, and a socket's path holds at most 107 bytes
            where = tempfile.gettempdir()
            print(f"ddg-oracle: error: TMPDIR={where} ({len(where)} characters) is too long for "
                  "the sockets of Python's worker processes (107 bytes with the names Python "
                  "adds): set TMPDIR to a shorter folder, such as /tmp", file=sys.stderr)
            return EXIT_USAGE
        traceback.print_exc()
        print(BUG_REPORT, file=sys.stderr)
        return EXIT_TOOL


def _methods(args) -> int:
    """``ddg-oracle methods``: the protocol (protocol.methods.METHODS) and who checks it."""
    from ..protocol.methods import METHODS
    from ..properties.registry import all_properties
    props = all_properties()
    if args.impl:
        return _methods_of(args, METHODS, props)
    for name, m in METHODS.items():
        ids = [p.id for p in props if name in p.methods]
        print(f"{name}({', '.join(m.arguments)})")
        print(textwrap.fill(str(m), 96, initial_indent="    ", subsequent_indent="    "))
        print(textwrap.fill("checked by: " + (", ".join(ids) or "compare and the test vectors "
                                               "only"), 96, initial_indent="    ",
                            subsequent_indent="      "))
    print(f"\n{len(METHODS)} methods; an implementation defines any of them "
          "(ddg_oracle.protocol.methods.METHODS, docs/protocol.md for other languages)")
    return 0


def _methods_of(args, METHODS, props) -> int:
    """``ddg-oracle methods --impl SPEC``: what the properties would see of SPEC."""
    from ..protocol.methods import (capabilities, declared_conventions,
                                                implementation_name, machine_epsilon,
                                                near_miss_warning)
    from ..properties.conventions import declared
    impl = start_implementations([args.impl], args.timeout)[args.impl]
    try:
        has = capabilities(impl)
        eps, follows = machine_epsilon(impl), declared_conventions(impl)
        conventions = [c.name for c in declared(impl)] + ([f"follows {follows[1]}"] if follows
                                                         else [])
        said, name = near_miss_warning(impl), implementation_name(impl)
    finally:
        getattr(impl, "close", lambda: None)()
    print(f"{name} ({args.impl}): machine_epsilon {eps!r}; "
          + (f"conventions: {', '.join(conventions)}" if conventions else "no conventions declared"))
    for method in METHODS:
        mark = "defines" if method in has else "-      "
        ids = [p.id for p in props if method in p.methods]
        print(f"  {mark}  {method}" + (f"  ({', '.join(ids)})" if method in has and ids else ""))
    applicable = [p.id for p in props if p.applies_to(has)]
    print(f"\n{len(has & set(METHODS))} of {len(METHODS)} methods; {len(applicable)} of "
          f"{len(props)} properties apply")
    if said:
        print(f"ddg-oracle: warning: {said}", file=sys.stderr)
    return 0


def _theorems(args) -> int:
    from . import traceability
    claimed, entries = traceability.load()
    width = max(len(e.id) for e in entries)
    print(f"{'ID'.ljust(width)}  {'status':9}  reference / property")
    for e in entries:
        ref = ", ".join(r.split(":")[-1] for r in e.reference) or "-"
        prop = ", ".join(p.split(":")[-1] for p in e.property) or "-"
        print(f"{e.id.ljust(width)}  {e.status:9}  {ref} / {prop}")
        for label, text in (("covers", e.covers), ("limits", e.limits)):
            print(textwrap.fill(f"{label}: {text or '-'}", 100, initial_indent="    ",
                                subsequent_indent="      ", break_on_hyphens=False))
    counts = {s: sum(e.status == s for e in entries) for s in traceability.STATUSES}
    print(f"\n{len(entries)} rows: " + ", ".join(f"{n} {s}" for s, n in counts.items())
          + f"; claimed chapters: {', '.join(map(str, claimed)) or 'none'}")
    items = traceability.load_notes()
    width = max(len(i.name) for i in items)
    print(f"\nThe notes, chapters 1-4 (application/notes.toml):\n"
          f"{'item'.ljust(width)}  {'line':>4}  {'status':14}  rows / reason")
    for i in items:
        print(f"{i.name.ljust(width)}  {i.line:>4}  {i.status:14}  "
              f"{', '.join(i.rows) if i.rows else i.reason}"
              + (f" ({i.note})" if i.note else ""))
    tally = {s: sum(i.status == s for i in items) for s in traceability.NOTE_STATUSES}
    print(f"\n{len(items)} items: " + ", ".join(f"{n} {s}" for s, n in tally.items()))
    if not args.check:
        return 0
    problems = traceability.check()
    for p in problems:
        print(f"NOT TRUE: {p}", file=sys.stderr)
    if problems:
        return 1
    print("traceability table and notes table: true")
    return 0


def _budget(args):
    """The task budget of ``check``: the profile's, or ``--budget`` seconds (0: none)."""
    from ..protocol.budget import Budget
    from ..properties.profiles import profile_budget

    budget = profile_budget(args.profile)
    if args.budget is None:
        return budget
    if args.budget < 0 or args.budget != args.budget:
        raise UsageError(f"--budget must be >= 0 seconds (0: none), got {args.budget}")
    return Budget(args.budget or None, budget.crashes if args.budget else None)


class Progress:
    """Signs of life on stderr.  On a terminal, a one-line bar.  Otherwise (a CI log, a
    pipe) one line per finished task that was applicable, and every ``every`` seconds a
    line with how far the run is, so a log never goes quiet for long."""

    def __init__(self, total: int, stream=None, every: float = 10.0, already: int = 0):
        import threading

        self.total, self.done = total, already
        self.stream = stream or sys.stderr
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self.t0 = time.perf_counter()
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._ticker = None
        if not self.tty and every > 0:
            self._ticker = threading.Thread(target=self._tick, args=(every,), daemon=True)
            self._ticker.start()

    def _tick(self, every: float) -> None:
        while not self._stop.wait(every):
            with self._lock:
                print(f"ddg-oracle: {self.done}/{self.total} tasks done, "
                      f"{time.perf_counter() - self.t0:.0f} s", file=self.stream, flush=True)

    def __call__(self, task, results) -> None:
        from ..properties.runner import NOT_APPLICABLE

        with self._lock:
            self.done += 1
            what = task.property_id or f"mesh {task.mesh}"
            elapsed = time.perf_counter() - self.t0
            if not self.tty:
                for r in results:
                    if r.status != NOT_APPLICABLE:
                        print(f"[{self.done}/{self.total} {elapsed:.0f} s] {r.property_id} "
                              f"{r.implementation}: {r.summary()}", file=self.stream, flush=True)
                return
            bar = "#" * (24 * self.done // max(self.total, 1))
            bad = sum(not r.ok for r in results)
            print(f"\r[{bar:<24}] {self.done}/{self.total} {elapsed:5.0f} s  "
                  f"{task.spec[:24]}: {what[:14]:<14}{' FAIL' if bad else '     '}",
                  end="", file=self.stream, flush=True)

    def finish(self) -> None:
        self._stop.set()
        if self.tty:
            print(file=self.stream)


def _validate_check(args) -> None:
    """Every option and environment value of ``check`` checked before any work starts: a
    bad one is a one-line usage error (exit 2), never a result blamed on a library."""
    from .isolation import memory_limit
    from .meshfiles import size_limit
    from ..properties.profiles import time_limit_seconds
    if args.examples is not None and args.examples < 1:
        raise UsageError(f"--examples must be at least 1, got {args.examples}")
    if args.examples is not None and args.mesh:
        # a mesh file is one example: a count would be silently ignored
        raise UsageError("--examples counts generated examples; with --mesh each file is "
                         "checked once: drop one of them")
    if args.workers is not None and args.workers < 1:
        raise UsageError(f"--workers must be >= 1, got {args.workers}")
    check_timeout(args)
    if args.width < 40:
        raise UsageError(f"--width must be at least 40 columns, got {args.width}")
    time_limit_seconds()               # DDG_EXAMPLE_TIME_LIMIT
    memory_limit()                     # DDG_MEMORY_LIMIT
    size_limit()                       # DDG_MESH_SIZE_LIMIT


def _check_arguments(argv) -> list[str]:
    """The arguments of the check command after its name (what --resume parses again)."""
    return list(argv if argv is not None else sys.argv[2:])


def counterexample_parent() -> str | None:
    """Where ``check`` without ``--report`` makes its folder of counterexample files:
    ``$DDG_COUNTEREXAMPLES`` (created if missing; a CI job's artifact folder), else None
    (the system's temporary directory).  A folder that cannot be made or written is a usage
    error before the run, not a lost report after it."""
    parent = os.environ.get("DDG_COUNTEREXAMPLES") or None
    if parent is not None:
        try:
            os.makedirs(parent, exist_ok=True)
            tempfile.TemporaryDirectory(dir=parent).cleanup()      # writable
        except OSError as e:
            raise UsageError(f"DDG_COUNTEREXAMPLES={parent}: cannot make folders there "
                             f"({e.strerror or e})") from None
    return parent


def _check(args, argv) -> int:
    from . import jobs
    from .implementations import available, built_drivers, missing
    from ..properties.profiles import profile
    from ..properties.registry import select_properties
    from ..properties.runner import describe
    from .report import ResultStream

    stream_done: dict = {}
    if args.resume:
        # the interrupted run's own command line, seed included: the same tasks, the same
        # examples; only the tasks not in its results.jsonl run
        stored = ResultStream.command_of(args.resume)
        args = parser().parse_args(["check", *stored["argv"]])
        seed = stored.get("seed")
        if not (seed is None or (isinstance(seed, int) and not isinstance(seed, bool))):
            raise UsageError(f"--resume {stored['report']}: its seed {seed!r} is not a number")
        args.report, args.resume, args.seed = stored["report"], stored["report"], seed
        argv = stored["argv"]
    _validate_check(args)
    workers = args.workers or default_workers()
    try:
        props = select_properties(args.only)
    except ValueError as e:
        raise UsageError(str(e)) from None
    only = frozenset(p.id for p in props) if args.only else None
    budget = _budget(args)
    seed = args.seed
    if seed is None and not profile(args.profile).derandomize:
        # one seed for the run: every implementation of a property sees the same examples
        seed = random.SystemRandom().getrandbits(32)
    if args.report and not args.resume:
        refuse_used_report_dir(args.report)             # before the run, not after it
    counterexamples = None if args.report else counterexample_parent()
    meshes = []
    if args.mesh:
        from .meshes import file_properties, load_all
        meshes = load_all(args.mesh, warn=warn)
        if not meshes:
            raise InputError("no usable mesh among " + ", ".join(args.mesh))
        on_files = [p.id for p in file_properties()]
        if only and not only & set(on_files):
            raise UsageError(f"none of {', '.join(sorted(only))} applies to a mesh file; "
                             f"those that do: {', '.join(on_files)}")
    if not args.impl:
        for name, why in missing().items():
            warn(f"not checked: {why}")
    drivers = [] if args.impl else built_drivers(args.drivers)
    if not args.impl and not drivers and os.path.exists(os.path.join("examples", "cpp",
                                                                     "CMakeLists.txt")):
        warn("not checked: the C++ drivers (CGAL, OpenMesh) are not built; "
              "bash examples/cpp/build.sh builds them")
    specs = list(dict.fromkeys(args.impl or available() + drivers))
    t0 = time.perf_counter()
    options = jobs.Options(args.profile, seed, args.timeout, args.expect_conventions, only, budget,
                           args.examples)
    if meshes:
        # one task per (mesh, implementation, property): a worker keeps to one property's
        # tasks (jobs.next_task), so each exact value is computed by one worker, not all
        tasks = [jobs.Task(s, p, k) for k in range(len(meshes)) for s in specs
                 for p in on_files if only is None or p in only]
    else:
        tasks = [jobs.Task(s, p.id) for p in props for s in specs]
    workers = min(workers, len(tasks))
    client = cluster = None
    if args.scheduler:
        from . import cluster as dask_cluster
        client, cluster = dask_cluster.connect(args.scheduler)
        workers = dask_cluster.n_workers(client)
    # Started here: what this process runs itself (one worker), or what must be seen to
    # load before the run (a user's module, a program) so that a mistake is exit 2 at
    # once.  With a pool, a built-in adapter whose library is installed is started by the
    # pool's workers only: starting it here too would cost every library's import again.
    from .implementations import BUILTIN
    plain = {s for s in specs if s in BUILTIN}         # a built-in name without options
    pool = workers > 1 or client is not None
    if not pool:
        # no pool worker is forked in this run, only isolated library workers: the
        # forkserver, if not started yet, imports what they need, not the properties (a
        # process that needs more imports it itself)
        from .containment import LIBRARY_PRELOAD, forkserver_in_use, start_workers_from_a_forkserver
        if forkserver_in_use():
            start_workers_from_a_forkserver(LIBRARY_PRELOAD)
    started = start_implementations([s for s in specs if not pool or s not in plain], args.timeout)
    warn_near_misses(started.values())
    names = {s: getattr(i, "name", s) for s, i in started.items()}
    names.update({s: s for s in plain if s not in names})   # their display name is the name
    if not pool:
        for s, impl in started.items():
            jobs.adopt(s, impl)
    else:
        for impl in started.values():
            getattr(impl, "close", lambda: None)()
    stream = None
    if args.report:
        given = _check_arguments(argv)
        try:
            stream = ResultStream(args.report, tasks, {"argv": given, "seed": seed,
                                                       "report": str(Path(args.report).resolve())})
        except OSError as e:
            for impl in started.values():
                getattr(impl, "close", lambda: None)()
            raise UsageError(f"--report {args.report}: cannot write there: "
                             f"{e.strerror or e}") from None
        stream_done = stream.finished()                 # a resumed run's finished tasks
        by_name = {m.name: m for m in meshes}
        for results_of_task in stream_done.values():
            for r in results_of_task:                   # a mesh file's mesh: read again
                if r.source in by_name and r.mesh is None:
                    r.mesh = (by_name[r.source].V, by_name[r.source].F)
    progress = Progress(len(tasks), already=len(stream_done))

    lost = []                           # the report directory stopped taking writes

    def on_done(k, task, results):
        if stream is not None and not lost:
            try:
                stream.add(k, results)
            except OSError as e:        # full, read-only or gone: the run goes on
                lost.append(e)
        progress(task, results)

    interrupted = None
    try:
        results = jobs.run_tasks(tasks, options, meshes, workers, on_done=on_done,
                                 done=stream_done,
                                 remote=None if client is None
                                 else partial(dask_cluster.run_on_cluster, client))
    except jobs.Interrupted as e:
        interrupted, results = e, e.done
    finally:
        progress.finish()
        jobs.close_all()
        if client is not None:
            dask_cluster.close(client, cluster)
        if stream is not None:
            stream.close()
    seconds = time.perf_counter() - t0

    from .report import fit, closing_line, table, terminal_report, write_counterexamples
    from .report import write_report
    from ..properties.runner import INCOMPLETE, INTERNAL
    bad = [r for r in results if not r.ok
           and not (args.accept_incomplete and r.status == INCOMPLETE)]
    ours = any(r.status == INTERNAL for r in results)
    # display name -> spec: of the implementations started here, else as results say
    spec_of = {r.implementation: r.spec for r in results if r.spec}
    spec_of.update({n: s for s, n in names.items()})
    if args.report:
        command = {"profile": args.profile, "seed": seed, "implementations": specs,
                   "only": sorted(only) if only else None,
                   "meshes": [m.name for m in meshes] or None,
                   "expect_conventions": args.expect_conventions,
                   "argv": _check_arguments(argv)}
        timings = {"seconds": round(seconds, 3), "workers": workers,
                   "results": [{"property_id": r.property_id, "implementation": r.implementation,
                                "source": r.source, "seconds": round(r.seconds, 4)}
                               for r in results]}
        where = Path(args.report)
        try:
            files = write_report(where, results, command, spec_of, timings,
                                 interrupted=interrupted is not None)
        except OSError as e:
            lost.append(e)
            files = {}
    else:
        # the whole mesh and the snippet of each counterexample, for those the terminal elides
        where = Path(tempfile.mkdtemp(prefix="ddg-oracle-counterexamples-", dir=counterexamples))
        files = write_counterexamples(where, results, spec_of)
        if not files:
            where.rmdir()
    folders = {k: str(where / Path(f["obj"]).parent) for k, f in files.items()}
    if args.wide:
        print(table(results))
        for k, r in enumerate(results):
            if r.failure is not None or r.error:
                print("\n" + describe(r, files=folders.get(k)))
    else:
        print(terminal_report(results, width=args.width, files=folders,
                              list_ties=args.ties))
    shown = args.profile + (f" ({args.examples} examples each)" if args.examples else "")
    print("\n" + fit(closing_line(results, seconds, workers, shown, seed,
                                  args.accept_incomplete), args.width))
    if args.report and lost:
        e = lost[0]
        print(f"ddg-oracle: error: --report {args.report}: could not write ({e.strerror or e}); "
              "the results above are complete, the report is not", file=sys.stderr)
        return EXIT_USAGE
    if args.report:
        print(f"report: {where / 'summary.md'}")
    elif files:
        said = "counterexample files (mesh.obj, reproduce.py):"
        # a long folder (a deep $TMPDIR or $DDG_COUNTEREXAMPLES) on a line of its own
        print(f"{said} {where}" if len(f"{said} {where}") <= args.width else f"{said}\n  {where}")
    if interrupted is not None:
        import signal
        name = signal.Signals(interrupted.signal).name
        print(f"ddg-oracle: interrupted by {name}: {len(results)} results of the finished tasks "
              + (f"kept in {args.report}; finish with: ddg-oracle check --resume {args.report}"
                 if args.report else "shown above (--report DIR keeps them for --resume)"),
              file=sys.stderr)
        return interrupted.code
    if ours:                         # a bug of ours on some example: the run went on, said so
        return EXIT_TOOL
    return 1 if bad else 0


def _compare(args) -> int:
    check_timeout(args)
    from .compare import format_comparisons, compare_mesh
    from .meshes import load_all
    from ..oracles.exact_reference import ReferenceImplementation
    from .implementations import available

    meshes = load_all(args.mesh, warn=warn)
    if not meshes:
        raise InputError("no usable mesh among " + ", ".join(args.mesh))
    specs = list(dict.fromkeys(args.impl or [s for s in available() if s != "reference"]))
    started = start_implementations(specs, args.timeout)
    worse = 0
    try:
        for k, mesh in enumerate(meshes):
            rows = compare_mesh(mesh, [started[s] for s in specs], ReferenceImplementation(),
                                workers=default_workers())
            print(("\n" if k else "") + format_comparisons(mesh, rows))
            worse += sum(r.status in ("DIFFERS", "crashed") for r in rows)
    finally:
        for impl in started.values():
            getattr(impl, "close", lambda: None)()
    return 1 if worse else 0


def _survey(args) -> int:
    """``ddg-oracle survey``: compare over a corpus, aggregated (:mod:`ddg_oracle.application.survey`)."""
    args.mesh = list(args.mesh) + list(args.mesh_option or [])
    if args.resume and (args.mesh or args.impl or args.report):
        raise UsageError("survey --resume DIR takes no mesh, --impl or --report: the "
                         "interrupted run's are read from DIR/run.json")
    from . import survey
    if args.resume:
        # the interrupted run's own options (its run.json), in the directory as it is now
        stored = survey.command_of(args.resume)
        workers, scheduler, report = args.workers, args.scheduler, stored["report"]
        args = parser().parse_args(["survey", *stored["argv"]])
        args.mesh = list(args.mesh) + list(args.mesh_option or [])
        args.report, args.resume, args.workers, args.scheduler = report, report, workers, \
            scheduler
    check_timeout(args)
    return survey.run(args)


def _vectors(args) -> int:
    from . import vectors
    written = vectors.write(args.out)
    corpus = vectors.load(args.out)
    n = sum(len(f["cases"]) for f in corpus.values())
    print(f"wrote {len(written)} files, {n} cases of {len(corpus)} methods, to {args.out} "
          f"(format {vectors.FORMAT} {vectors.VERSION})")
    return 0


def _verify(args) -> int:
    check_timeout(args)
    import json
    from . import vectors
    from ..protocol.methods import FLOAT64_EPSILON, implementation_name, machine_epsilon

    corpus = vectors.load(args.corpus)
    if (args.answers is None) == (args.impl is None):
        raise UsageError("verify: give an answers file or --impl SPEC (one of them)")
    if args.write_answers and not args.impl:
        raise UsageError("verify: --write-answers needs --impl")
    float32 = args.float32
    conventions = ()
    if args.impl:
        from ..properties.conventions import declared
        started = start_implementations([args.impl], args.timeout)
        impl = started[args.impl]
        warn_near_misses([impl])
        try:
            lines = vectors.answers(corpus, impl)
            float32 = float32 or machine_epsilon(impl) > FLOAT64_EPSILON
            name, conventions = implementation_name(impl), declared(impl)
        finally:
            getattr(impl, "close", lambda: None)()
        if args.write_answers:
            Path(args.write_answers).write_text(
                "".join(json.dumps(x, allow_nan=False) + "\n" for x in lines
                        if "not_run" not in x), encoding="utf-8")
    else:
        lines = vectors.read_answers(args.answers)
        name = args.answers
    verdicts = vectors.verify(corpus, lines, float32=float32, conventions=conventions)
    for x in verdicts:
        if x.status in ("FAIL", "not run"):
            print(f"{x.status.upper() if x.status == 'FAIL' else x.status} {x.id}: {x.message}")
    counts = {s: sum(x.status == s for x in verdicts)
              for s in ("pass", "FAIL", "acceptable", "not applicable", "not run")}
    print(f"{name}: {len(verdicts)} cases ({'float32' if float32 else 'float64'} tolerances): "
          + ", ".join(f"{n} {s}" for s, n in counts.items() if n or s in ("pass", "FAIL")))
    return 1 if counts["FAIL"] else 0


if __name__ == "__main__":
    sys.exit(main())
