"""Mutation testing of the exact reference (issue 40, item 6): mutmut 3 on the core modules
of ``reference/``, each against the fast test files that exercise it; the per-module
mutation score (mutants killed or timed out / mutants run).

mutmut 3 runs the tests in a copy of the sources (its ``mutants/`` folder) and switches
mutants on by *module name*: ``ddg_oracle.reference.cotangents`` at run time must be the
path ``ddg_oracle/reference/cotangents.py`` of the copy.  This repository installs
``reference/`` as ``ddg_oracle.reference`` through a package-dir mapping (an editable
install), so each run first stages, under a temporary folder (never inside the
repository), the installed layout: ``ddg_oracle/`` with the layers' folders (``reference/``,
``protocol/``, ``properties/``, ``oracles/``, ``application/``) inside it, and beside it the
tests, examples, benchmarks, docs and vectors.
mutmut puts its ``mutants/`` first on ``sys.path``, so the tests import the staged, mutated
package, not the editable one.  The repository's own files are only read.

Each module gets its own staged copy and its own ``[tool.mutmut]`` (only that module is
mutated; the test files below are the selection, and mutmut runs, for each mutant, only
the tests that executed its function).  Workers are forked from a fork server that has
collected (not run) the tests, so no cache filled by an earlier test run hides a mutant.
Hypothesis runs with a fixed seed and no example database: two runs test the same inputs.

``python -m benchmarks mutation --no-write`` runs every module (long: about an hour on a
loaded 2-core machine); ``--quick`` only the first, every 16th mutant.
``python -m benchmarks.mutation MODULE ... [--keep DIR]`` runs the named ones and can keep
the staged copy for ``mutmut show NAME`` (in ``DIR/MODULE``).
See docs/mutation.md for the results and the equivalent mutants.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import tomllib
from collections import Counter
from pathlib import Path

from .common import ROOT, Mode, say

# Fast test files that exercise each module (together well under a minute each); tests_of()
# adds tests/test_doctests.py and every tests/test_mutants_*.py.
COMMON = ["tests/test_doctests.py"]
MODULES = {
    "cotangents": ["tests/test_laplacian.py", "tests/test_fast_paths.py", "tests/test_delaunay.py",
                   "tests/test_errata_proofs.py", "tests/test_zero_test.py", "tests/test_angles.py"],
    "curvature": ["tests/test_curvature.py", "tests/test_fast_paths.py", "tests/test_angles.py",
                  "tests/test_zero_test.py"],
    "laplacian": ["tests/test_laplacian.py", "tests/test_fast_paths.py", "tests/test_delaunay.py",
                  "tests/test_rippa.py", "tests/test_errata_proofs.py"],
    "delaunay": ["tests/test_delaunay.py", "tests/test_intrinsic.py", "tests/test_fast_paths.py",
                 "tests/test_minimal_delaunay.py", "tests/test_errata_proofs.py",
                 "tests/test_zero_test.py"],
    "intrinsic": ["tests/test_intrinsic.py", "tests/test_delaunay.py", "tests/test_combinatorics.py",
                  "tests/test_fast_paths.py"],
    "combinatorics": ["tests/test_combinatorics.py", "tests/test_surfaces.py",
                      "tests/test_intrinsic.py", "tests/test_curvature.py"],
}
PINNED = "mutmut>=3.8,<3.9"       # the optional extra ``mutation`` of pyproject.toml
# every k-th mutant of each function by default (a full run of one module can take hours on
# a shared 2-core machine); --sample 1 runs them all
SAMPLES = {"combinatorics": 12}
# what the staged copy needs beside the package (tests import tests.*, examples.*, benchmarks.*)
ALSO = ["tests", "examples", "benchmarks", "docs", "vectors"]
#: layer -> its folder in the repository (pyproject.toml's package-dir table), staged inside
#: ``ddg_oracle/`` as the wheel installs them
SUBPACKAGES = {package.split(".", 1)[1]: folder for package, folder in tomllib.loads(
    (ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-dir"].items()
    if "." in package}
_SKIP = shutil.ignore_patterns("__pycache__", ".hypothesis", "build", "mutants", "*.pyc")


def tests_of(module: str) -> list[str]:
    """The module's fast test files, then every tests/test_mutants_*.py (together ~10 s:
    a mutant of one module is often killed by another module's generic-surface tests)."""
    own = sorted(str(p.relative_to(ROOT)) for p in (ROOT / "tests").glob("test_mutants_*.py"))
    if os.environ.get("DDG_MUTATION_BASELINE"):       # the suite as it was before them
        own = []
    return MODULES[module] + COMMON + own


def stage(dest: Path, module: str, tests: list[str]) -> Path:
    """A copy of the repository in the installed layout, configured to mutate ``module``."""
    dest.mkdir(parents=True, exist_ok=True)
    pkg = dest / "ddg_oracle"
    shutil.copytree(ROOT / "ddg_oracle", pkg, ignore=_SKIP, symlinks=True)
    for sub, src in SUBPACKAGES.items():
        shutil.copytree(ROOT / src, pkg / sub, ignore=_SKIP)
    for name in ALSO:
        shutil.copytree(ROOT / name, dest / name, ignore=shutil.ignore_patterns(
            "__pycache__", ".hypothesis", "build", "cpp", "perf"), symlinks=True)
    config = {
        "source_paths": ["ddg_oracle"],
        "only_mutate": [f"ddg_oracle/reference/{module}.py"],
        "also_copy": ALSO,
        "pytest_add_cli_args": ["-p", "no:cacheprovider", "--hypothesis-seed=0"],
        "pytest_add_cli_args_test_selection": tests,
        "process_isolation": "forkserver",
        "forkserver_warmup": "collect",
        "use_git_change_detection": False,
        # a worker gets (the covering tests' time + 20 s) * 2 * 2 CPU seconds: the 20 s
        # pay for pytest's start in the worker (it collects its test files again); mutmut's
        # default multiplier 15 lets a looping mutant burn many minutes
        "timeout_multiplier": 2.0,
        "timeout_constant": 20.0,
    }
    lines = ["", "[tool.mutmut]"]
    for k, v in config.items():
        lines.append(f"{k} = {json.dumps(v)}")
    (dest / "pyproject.toml").write_text((ROOT / "pyproject.toml").read_text()
                                         + "\n".join(lines) + "\n")
    return dest


def counts(work: Path, module: str) -> dict:
    """Statuses of the mutants of one staged run, from mutmut's meta file."""
    from mutmut.stats import status_by_exit_code
    meta = json.loads((work / "mutants" / "ddg_oracle" / "reference" / f"{module}.py.meta")
                      .read_text())
    # only the mutants this run tested (a sample leaves the others "not checked")
    status = {k: status_by_exit_code[v] for k, v in meta["exit_code_by_key"].items()
              if v is not None}
    generated = len(meta["exit_code_by_key"])
    c = Counter(status.values())
    killed = c["killed"] + c["timeout"] + c["segfault"]   # a hang or a crash is detected too
    return {"module": module, "generated": generated, "mutants": len(status),
            "killed": c["killed"],
            "timeout": c["timeout"], "segfault": c["segfault"], "survived": c["survived"],
            "suspicious": c["suspicious"], "no_tests": c["no tests"],
            "score": round(100 * killed / len(status), 1) if status else None,
            "survivors": sorted(k for k, s in status.items() if s in ("survived", "suspicious")),
            "untested": sorted(k for k, s in status.items() if s == "no tests")}


def sample_patterns(k: int) -> list[str]:
    """mutmut name patterns of every k-th mutant of each function (its mutants 1, 1 + k,
    1 + 2k, ...): a sample stratified by function; [] (all) for k = 1."""
    if k <= 1:
        return []
    return [f"*__mutmut_{n}" for n in range(1, 2000, k)]


def run_module(module: str, root: Path, max_children: int = 2, sample: int = 1,
               names=None) -> dict:
    """Stage, run mutmut on ``module`` (every ``sample``-th mutant of each function, or
    only the mutants ``names``), and count."""
    tests = tests_of(module)
    work = stage(root / module, module, tests)
    env = {**os.environ, "DDG_HYPOTHESIS_DATABASE": "none", "PYTHONDONTWRITEBYTECODE": "1"}
    env.pop("CI", None)                      # the default profile, as a developer runs it
    cmd = [sys.executable, "-m", "mutmut", "run", "--max-children", str(max_children),
           *(names if names else sample_patterns(sample))]
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, cwd=work, env=env, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        out, err = p.communicate()
    except BaseException:
        os.killpg(p.pid, signal.SIGTERM)     # mutmut, its fork server and its workers
        raise
    wall = time.perf_counter() - t0
    (work / "mutmut.log").write_text(out + "\n--- stderr\n" + err)
    if p.returncode != 0:
        raise RuntimeError(f"mutmut on {module} exited {p.returncode}:\n{out[-3000:]}"
                           f"\n{err[-3000:]}")
    row = counts(work, module)
    shown = ["mutmut", *cmd[3:7]] + (["NAME ..."] if names else
                                     [f"'*__mutmut_{{1,{1 + sample},{1 + 2 * sample},...}}'"]
                                     if sample > 1 else [])
    row.update(wall=round(wall, 1), tests=tests, sample=sample, command=" ".join(shown))
    return row


def diffs(work: Path, names) -> str:
    """``mutmut show`` of each named mutant of a kept staged copy."""
    out = []
    for name in names:
        p = subprocess.run([sys.executable, "-m", "mutmut", "show", name], cwd=work,
                           capture_output=True, text=True)
        out.append(p.stdout.strip())
    return "\n\n".join(out) + "\n"


def table(rows) -> str:
    out = ["| module | mutants | killed | timeout | survived | suspicious | no tests | score |",
           "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for r in rows:
        out.append(f"| {r['module']} | {r['mutants']} | {r['killed']} | {r['timeout']} | "
                   f"{r['survived']} | {r['suspicious']} | {r['no_tests']} | {r['score']}% |")
    return "\n".join(out)


def run(mode: Mode, modules=None, keep: Path | None = None, max_children: int = 2,
        sample: int | None = None, show: bool = False, names_of=None) -> dict:
    """Each module in turn; ``sample``: every k-th mutant of each function (default 8, 12
    for combinatorics, as in docs/mutation.md; 1 for all; ``--quick``: 16, the first
    module only)."""
    import importlib.util
    if importlib.util.find_spec("mutmut") is None:
        raise RuntimeError(f"mutation testing needs mutmut: pip install '{PINNED}' "
                           "(or the extra: pip install -e '.[mutation]')")
    modules = list(modules or (list(MODULES)[:1] if mode.quick else MODULES))
    if mode.quick:
        sample = sample or 16
    rows = []
    root = Path(keep) if keep else Path(tempfile.mkdtemp(prefix="ddg-mutation-"))
    try:
        for m in modules:
            if (root / m).exists():
                shutil.rmtree(root / m)
            names = (names_of or {}).get(m)
            if names_of is not None and not names:
                continue                       # nothing survived there: nothing to re-run
            row = run_module(m, root, max_children, sample or SAMPLES.get(m, 8), names)
            rows.append(row)
            if show and row["survivors"]:
                (root / f"survivors-{m}.diff").write_text(diffs(root / m, row["survivors"]))
            say(f"  mutation {m:14} {row['mutants']:5} of {row['generated']} mutants, "
                f"{row['killed']} killed, "
                f"{row['timeout']} timeout, {row['survived']} survived, "
                f"{row['suspicious']} suspicious, {row['no_tests']} no tests: "
                f"score {row['score']}% ({row['wall']:.0f} s)")
    finally:
        if not keep:
            shutil.rmtree(root, ignore_errors=True)
    print(table(rows))
    return {"rows": rows, "tool": _version()}


def _version() -> str:
    from importlib.metadata import version
    return f"mutmut {version('mutmut')}"


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m benchmarks.mutation", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("modules", nargs="*", choices=[[], *MODULES], metavar="MODULE")
    p.add_argument("--keep", type=Path, default=None,
                   help="stage under this folder and leave it (for mutmut show/results)")
    p.add_argument("--max-children", type=int, default=2)
    p.add_argument("--sample", type=int, default=None,
                   help="every k-th mutant of each function (1: all; default 8, 12 for "
                   "combinatorics)")
    p.add_argument("--show", action="store_true",
                   help="with --keep: write survivors-MODULE.diff (mutmut show of each)")
    p.add_argument("--json", type=Path, default=None, help="write the rows to this file")
    p.add_argument("--survivors-of", type=Path, nargs="+", default=None, metavar="JSON",
                   help="re-run only the surviving and untested mutants listed in these --json "
                   "outputs of earlier runs (after adding tests)")
    args = p.parse_args(argv)
    names_of = None
    if args.survivors_of:
        names_of = {}
        for path in args.survivors_of:
            for row in json.loads(path.read_text())["rows"]:
                names_of.setdefault(row["module"], []).extend(
                    row["survivors"] + row.get("untested", []))
    res = run(Mode.of(False), args.modules or None, args.keep, args.max_children, args.sample,
              args.show and args.keep is not None, names_of)
    if args.json:
        args.json.write_text(json.dumps(res, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
