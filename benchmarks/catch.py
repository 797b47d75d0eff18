"""Time to catch planted bugs (issue 16, item 3): ``ddg-oracle check --impl BUG`` under the
default profile, on the properties that call the methods the bug plants.

For every bug of ``examples/numpy_cotan.py`` and ``tests/planted_bugs.py`` and every
seed: the failing properties, the task seconds of the fastest failing one (its
examples, the failure and the shrinking, from the report's timings.json), the
faces of its shrunk counterexample, and the wall time of the whole check.
"""

from __future__ import annotations

import inspect
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

from .common import ROOT, Mode, say

SEEDS = (1, 2, 3)
NUMPY_COTAN = ("SignError", "BoundaryWithoutHalf", "WrongCorner", "AbsoluteThreshold")


def bugs() -> list[tuple[str, tuple]]:
    """(spec, planted methods) of every planted bug."""
    sys.path.insert(0, str(ROOT))          # the benchmark runs from the repository
    try:
        import tests.planted_bugs as planted
    finally:
        sys.path.remove(str(ROOT))
    out = [(f"examples.numpy_cotan:{name}", ("cotan_laplacian",)) for name in NUMPY_COTAN]
    for name, cls in inspect.getmembers(planted, inspect.isclass):
        if cls.__module__ == planted.__name__ and getattr(cls, "planted", ()):
            out.append((f"tests.planted_bugs:{name}", cls.planted))
    return out


def properties_calling(methods) -> list[str]:
    from ddg_oracle.properties import PROPERTIES
    return [pid for pid, p in PROPERTIES.items() if set(p.methods) & set(methods)]


def _one(spec: str, ids: list[str], seed: int) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        report = os.path.join(tmp, "report")
        cmd = [sys.executable, "-m", "ddg_oracle", "check", "--impl", spec, "--seed", str(seed),
               "--report", report, "--only", *ids]
        t0 = time.perf_counter()
        p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        if p.returncode not in (0, 1):          # not a check result: the tool itself failed
            raise RuntimeError(f"{' '.join(cmd)} exited {p.returncode}:\n{p.stderr[-3000:]}")
        with open(os.path.join(report, "results.json")) as fh:
            results = json.load(fh)["results"]
        with open(os.path.join(report, "timings.json")) as fh:
            seconds = {t["property_id"]: t["seconds"] for t in json.load(fh)["results"]}
    failed = [r for r in results if r["status"] in ("FAILED", "crashed")]
    row = {"seed": seed, "wall": wall, "failed": [r["property_id"] for r in failed]}
    if failed:
        first = min(failed, key=lambda r: seconds.get(r["property_id"], float("inf")))
        mesh = first.get("mesh") or {}
        row.update(first=first["property_id"], seconds=seconds.get(first["property_id"]),
                   faces=len(mesh.get("F", [])) if mesh else None,
                   faces_min=min(len((r.get("mesh") or {}).get("F", [])) or 10 ** 9
                                 for r in failed))
    return row


def run(mode: Mode) -> dict:
    seeds = SEEDS[:1] if mode.quick else SEEDS
    rows = []
    for spec, methods in bugs():
        ids = properties_calling(methods)
        runs = [_one(spec, ids, s) for s in seeds]
        caught = [r for r in runs if r["failed"]]
        row = {"bug": spec.split(":")[1], "spec": spec, "planted": list(methods),
               "properties": len(ids), "runs": len(runs), "caught": len(caught),
               "wall": statistics.median(r["wall"] for r in runs)}
        if caught:
            firsts = [r["first"] for r in caught]
            row.update(first=max(set(firsts), key=firsts.count),
                       seconds=statistics.median(r["seconds"] for r in caught),
                       faces=statistics.median(r["faces"] for r in caught),
                       faces_min=min(r["faces_min"] for r in caught),
                       failing=sorted({p for r in caught for p in r["failed"]}))
        rows.append(row)
        say(f"  catch {row['bug']:28} caught {row['caught']}/{row['runs']} "
            f"first {row.get('first', '-'):12} {row.get('seconds') or 0:6.1f} s "
            f"{row.get('faces', '-')} faces, check {row['wall']:.1f} s")
    return {"rows": rows, "seeds": list(seeds)}
