"""Before and after a change, side by side: the same benchmarks on another version's package.

``python -m benchmarks sidebyside --base-python PY [--rounds N]``: ``PY`` is an interpreter
whose environment has the other version installed (``git worktree add DIR REV && python -m
venv V && V/bin/pip install -e 'DIR[test,bench]'``; ``--base-python V/bin/python``).  This
checkout's benchmark code (:data:`GROUPS`) runs with ``PY`` and with this interpreter, each
importing its own ``ddg_oracle`` (``python -P``: nothing from the working directory),
alternately (base, this, base, this, ...: a machine that slows down during the run slows
both), and each line keeps the fastest of the rounds (each already a median of runs).  Then
the cotan group once more on both with the collector paused around each timed run
(``--gc-paused``, as :mod:`timeit` does): where a line is slower with the collector running
but not with it paused, the difference is the collector's passes over the objects the call
made, not the code.  The lines printed are read back here (:func:`parse`)."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

from .common import ROOT, Mode, say

GROUPS = ("cotan", "flips", "r3", "real")

#: one timing per printed line: (pattern, key from the groups, seconds from the groups)
_LINES = [
    (re.compile(r"\s+(cotan|curvature) (.+?)\s+(\d+) (.+?)\s{2,}(.+?)\s+([\d.]+) s$"),
     lambda g: (g[0], g[1], int(g[2]), g[3].strip(), g[4].strip()), lambda g: [(None, g[5])]),
    (re.compile(r"\s+flips\s+(\d+) (in place|immutable)\s+(\d+) flips\s+([\d.]+) s"),
     lambda g: ("flips", "torus", int(g[0]), g[1], ""), lambda g: [(None, g[3])]),
    (re.compile(r"\s+r3 (.+?)\s+(\d+)\s+(\d+) flips\s+([\d.]+) s"),
     lambda g: ("r3", g[0].strip(), int(g[1]), "flips", ""), lambda g: [(None, g[3])]),
    (re.compile(r"\s+real (.+?)\s+(\d+) faces\s+exact\s+([\d.]+)\s+signs\s+([\d.]+)\s+"
                r"floats\s+([\d.]+)"),
     lambda g: ("real", g[0].strip(), int(g[1]), "", ""),
     lambda g: [("exact", g[2]), ("signs", g[3]), ("floats", g[4])]),
    (re.compile(r"\s+real (.+?): (\d+) flips ([\d.]+) s"),
     lambda g: ("real", g[0].strip(), 0, "intrinsic Delaunay", ""), lambda g: [(None, g[2])]),
]


def parse(text: str) -> dict:
    """``{(group, mesh, faces, route, quantity): seconds}`` from a benchmark run's output."""
    out = {}
    for line in text.splitlines():
        for pattern, key, values in _LINES:
            m = pattern.match(line.rstrip())
            if m:
                group, mesh, faces, route, what = key(m.groups())
                for name, seconds in values(m.groups()):
                    out[(group, mesh, faces, route, name or what)] = float(seconds)
                break
    return out


def _run(python: str, groups, paused: bool, quick: bool) -> dict:
    """This checkout's benchmarks under ``python`` and whatever ``ddg_oracle`` it has
    installed: from a directory that holds only a link to ``benchmarks``."""
    argv = [python, "-P", "-m", "benchmarks", *groups, "--no-write"] + \
        (["--gc-paused"] if paused else []) + (["--quick"] if quick else [])
    with tempfile.TemporaryDirectory() as tmp:
        os.symlink(ROOT / "benchmarks", Path(tmp) / "benchmarks")
        p = subprocess.run(argv, cwd=tmp, capture_output=True, text=True,
                           env={**os.environ, "PYTHONPATH": tmp})
    if p.returncode:
        raise RuntimeError(f"{' '.join(argv)} failed:\n{p.stderr[-2000:]}")
    return parse(p.stderr)          # the groups say() their lines on stderr


def _version(python: str) -> str:
    code = "import ddg_oracle, os; print(os.path.dirname(os.path.dirname(ddg_oracle.__file__)))"
    where = subprocess.run([python, "-P", "-c", code], capture_output=True, text=True,
                           cwd=tempfile.gettempdir()).stdout.strip()
    rev = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=where or None,
                         capture_output=True, text=True).stdout.strip()
    dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                           cwd=where or None, capture_output=True, text=True).stdout.strip()
    return (rev or where) + (" (with uncommitted changes)" if rev and dirty else "")


def _fastest(runs: list[dict]) -> dict:
    out: dict = {}
    for r in runs:
        for k, v in r.items():
            out[k] = min(out.get(k, v), v)
    return out


def run(mode: Mode, base_python: str | None = None, rounds: int = 2) -> dict:
    if not base_python:
        raise SystemExit("sidebyside needs --base-python (see python -m benchmarks --help)")
    base, this = _version(base_python), _version(sys.executable)
    before, after, paused_before, paused_after = [], [], [], []
    for k in range(rounds):
        say(f"  sidebyside round {k + 1} of {rounds}: {base}, then {this}")
        before.append(_run(base_python, GROUPS, False, mode.quick))
        after.append(_run(sys.executable, GROUPS, False, mode.quick))
    for k in range(rounds):
        say(f"  sidebyside, collector paused, round {k + 1} of {rounds}")
        paused_before.append(_run(base_python, ["cotan"], True, mode.quick))
        paused_after.append(_run(sys.executable, ["cotan"], True, mode.quick))
    b, a = _fastest(before), _fastest(after)
    pb, pa = _fastest(paused_before), _fastest(paused_after)
    rows = []
    for key in b:
        if key in a:
            row = {"key": list(key), "before": b[key], "after": a[key]}
            if key in pb and key in pa:
                row["paused_before"], row["paused_after"] = pb[key], pa[key]
            rows.append(row)
    say(f"  sidebyside: {len(rows)} lines")
    return {"rows": rows, "base": base, "this": this, "rounds": rounds}
