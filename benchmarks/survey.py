"""``python -m benchmarks survey``: ``ddg-oracle survey`` over PyMeshLab's sample meshes (and
the CGAL corpus, ``cgal:``, when its cache has been fetched) with every installed
implementation; writes docs/survey.md (the command, commit, date, machine load, wall
time and the scoreboard).

The exact reference's cost grows quickly with a mesh's size, so the corpus is the meshes
of at most ``MAX_FACES`` faces (``QUICK_MAX_FACES`` with --quick); the others are listed
in the document as left out.  ``DDG_SURVEY_MAX_FACES`` overrides the limit,
``DDG_SURVEY_SETS`` the mesh sets (``cgal:`` for the whole CGAL corpus alone).
"""

from __future__ import annotations

import json
import os
import shlex
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from .common import ROOT, Mode, machine, say

DOC = ROOT / "docs" / "survey.md"
MAX_FACES = 60000
QUICK_MAX_FACES = 100
#: CPU seconds the exact reference may take per quantity and mesh (DDG_EXAMPLE_TIME_LIMIT,
#: unless set): the exact intrinsic Delaunay Laplacian of some 200-face CAD meshes does not
#: finish in minutes (thousands of nested square roots), and is then "undecided"
EXACT_SECONDS = 20
def _uptime() -> str:
    try:
        out = subprocess.run(["uptime"], capture_output=True, text=True, timeout=5).stdout
        return out.rsplit("load average:", 1)[1].strip()
    except (OSError, IndexError, subprocess.SubprocessError):
        return "-"


def _faces(name: str, path: Path) -> int | str:
    """The number of (triangulated) faces of a corpus mesh as survey reads and validates
    it, or why it cannot be surveyed (a mesh with no faces, a degenerate or non-manifold
    one): named one by one, survey would stop at it."""
    from ddg_oracle.application.meshes import load
    from ddg_oracle.reference.errors import InputError
    try:
        return len(load(name, path).F)
    except InputError as e:
        return str(e).replace(f"{path}: ", "").replace(f"{name}: ", "")


def corpus_sets() -> list[str]:
    """``pymeshlab:``, and ``cgal:`` if its cache is there (``DDG_SURVEY_SETS``: these,
    separated by spaces)."""
    if os.environ.get("DDG_SURVEY_SETS"):
        return os.environ["DDG_SURVEY_SETS"].split()
    sets = ["pymeshlab:"]
    try:
        from ddg_oracle.application import corpus
        if (corpus.corpus_dir() / corpus.MANIFEST).is_file():
            sets.append("cgal:")
    except Exception:  # noqa: BLE001  (no corpus support in this version: PyMeshLab only)
        pass
    return sets


def choose(sets: list[str], max_faces: int) -> tuple[list[tuple[str, int]], list]:
    """(the meshes to survey, those left out (too large, too slow or unreadable)), each (name, faces)."""
    from ddg_oracle.application.meshes import resolve
    chosen, left = [], []
    for name, path, _ in resolve(sets):
        n = _faces(name, path)
        if isinstance(n, str):
            left.append((name, None, n))
        elif n > max_faces:
            left.append((name, n, f"over {max_faces:,} faces"))
        else:
            chosen.append((name, n))
    return chosen, left


def _left_out_notes(left) -> str:
    """The "Not done" lines on the meshes left out: too large, or not readable."""
    notes = []
    if any(n is not None for _, n, _ in left):
        notes.append("- The meshes left out above as too large (the exact reference on them "
                     "takes long;\n  `DDG_SURVEY_MAX_FACES=N` raises the limit).\n")
    if any(n is None for _, n, _ in left):
        notes.append("- The meshes left out above as unreadable (no faces, degenerate or "
                     "non-manifold:\n  `ddg-oracle survey` skips each with its reason).\n")
    return "".join(notes)


def run(mode: Mode) -> dict:
    max_faces = int(os.environ.get("DDG_SURVEY_MAX_FACES")
                    or (QUICK_MAX_FACES if mode.quick else MAX_FACES))
    sets = corpus_sets()
    chosen, left = choose(sets, max_faces)
    report = Path(tempfile.mkdtemp(prefix="ddg-oracle-survey-"))
    argv = ["survey", *[name for name, _ in chosen], "--report", str(report)]
    # the meshes are named one by one (the face limit), listed in the document's table
    shown = ("ddg-oracle survey " + (" ".join(shlex.quote(a) for a in argv[1:-2])
                                     if len(chosen) <= 8 else "MESHES") + " --report DIR")
    load = _uptime()
    m = machine()
    say(f"survey: {len(chosen)} meshes of {', '.join(sets)} up to {max_faces:,} faces "
        f"({len(left)} left out); report in {report}")
    t0 = time.monotonic()
    env = dict(os.environ)
    env.setdefault("DDG_EXAMPLE_TIME_LIMIT", str(EXACT_SECONDS))
    exact_seconds = env["DDG_EXAMPLE_TIME_LIMIT"]
    out = subprocess.run([sys.executable, "-m", "ddg_oracle", *argv], cwd=ROOT, text=True,
                         stdout=subprocess.PIPE, stderr=None, env=env)
    wall = time.monotonic() - t0
    print(out.stdout)
    if out.returncode not in (0, 1):          # a usage error, our bug, or interrupted
        raise RuntimeError(f"ddg-oracle survey exited {out.returncode}; {DOC.name} left as it was")
    doc = json.loads((report / "results.json").read_text())
    from ddg_oracle.application.survey import MeshResult, markdown_table, scoreboard, summary_line
    done = [MeshResult.from_json(x) for x in doc["meshes"]]
    scores = scoreboard(done, list(dict.fromkeys(s["implementation"]
                                                 for s in doc["scoreboard"])))
    impls = list(dict.fromkeys(s.implementation for s in scores))
    worst = sorted((s for s in scores if s.counts["DIFFERS"] or s.counts["crashed"]),
                   key=lambda s: (-(s.counts["DIFFERS"] + s.counts["crashed"]),
                                  s.implementation, s.quantity))
    meshes = "\n".join(f"| {x.name} | {x.vertices:,} | {x.faces:,} | {x.seconds:.1f} |"
                       for x in done)
    left_out = ", ".join(f"{name} ({why})" if n is None else f"{name} ({n:,} faces: {why})"
                         for name, n, why in left) or "none"
    limit_env = "".join(f"{k}={shlex.quote(os.environ[k])} "
                        for k in ("DDG_SURVEY_SETS", "DDG_SURVEY_MAX_FACES") if os.environ.get(k))
    text = f"""# Survey: every implementation x every quantity x a mesh corpus

Generated by `{limit_env}python -m benchmarks survey --no-write` (benchmarks/survey.py); do not edit.

`{shown}`{f" (MESHES: the {len(chosen)} meshes of the table below)" if len(chosen) > 8 else ""}: commit {m['commit']}, {m['date']}, wall time {wall:.0f} s, exit {out.returncode},
load average {load} (uptime, at the start), {m['cpus']} CPUs, Python {m['python']};
`DDG_EXAMPLE_TIME_LIMIT={exact_seconds}` (CPU seconds the exact reference may take per quantity
and mesh; beyond it the quantity is *undecided* on that mesh: nothing is said of the
implementations' answers there).

{summary_line(scores, done, doc['meshes_total'])}.
Implementations: {', '.join(impls)}.

What the columns mean: per implementation and protocol quantity (methods it does not
provide are left out), on how many meshes it was checked, and on how many its answer
agrees with the exact reference within the derived bound, DIFFERS, crashed (or hung), or
was not applicable (the quantity has no value on the mesh, e.g. a closed mesh's Dirichlet
problem).  Errors are in units of the derived bound (above 1 = outside it): the worst over
every mesh (and the mesh), the median of each mesh's worst.  An exact quantity (integers,
loops, flags) has no ratio: "worst on" names the first mesh where it differs.
`ddg-oracle survey ... --report DIR` also writes DIR/survey.html, a heatmap (colour: the
fraction of the meshes where the implementation agrees).

## Corpus

Meshes of {', '.join(f'`{s}`' for s in sets)} with at most {max_faces:,} faces
(`DDG_SURVEY_MAX_FACES=N` sets the limit).
Left out: {left_out}.

| mesh | vertices | faces | seconds |
|---|---:|---:|---:|
{meshes}

## Where implementations differ or crash

""" + ("\n".join(f"- {s.implementation} / {s.quantity}: {s.counts['DIFFERS']} DIFFERS, "
                  f"{s.counts['crashed']} crashed of {s.meshes} meshes"
                  + (f"; worst {s.worst:.3g} x the bound on {s.worst_mesh}" if s.worst else "")
                  for s in worst) or "Nowhere.") + f"""

## Scoreboard

{markdown_table(scores)}

## Not done

- This document is measured locally (`--workers`: processes computing each mesh's exact
  values, meshes one after another); `ddg-oracle survey --scheduler ADDRESS` runs one mesh
  per task on a dask cluster and scores the same.
{_left_out_notes(left)}"""
    DOC.write_text(text)
    say(f"wrote {DOC.relative_to(ROOT)}")
    return {"wall": wall, "command": shown, "exit": out.returncode, "meshes": len(done),
            "implementations": impls, "left_out": [n for n, _, _ in left],
            "differs": [[s.implementation, s.quantity, s.counts["DIFFERS"],
                         s.counts["crashed"]] for s in worst]}
