"""``python -m benchmarks large``: ``ddg-oracle check --mesh`` at issue 46's scale.

The mesh: PyMeshLab's bunny.obj (56,172 faces) loop-subdivided by ``igl.loop``, twice
(898,752 faces; ``--quick``: once, 224,688), written once into the temporary directory
(a deterministic function of the sample: the same file on every run).  Per row one run
(the check takes minutes), wall time, the CPU time of the check and every process it
started and the peak of the summed resident memory of its process tree, sampled every
0.2 s with psutil (the CPU of each process at its last sample: a worker's last 0.2 s,
and a peak shorter than that, can be missed; the kernel's RUSAGE_CHILDREN misses the
workers a pool ends without waiting for them, 47 s of a 202 s run on 2 cores)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from .common import ROOT, Mode, say

#: implementations per row: libigl alone, then every installed one (None)
PLAN = ["libigl", None]


def big_mesh(levels: int) -> Path:
    """bunny.obj loop-subdivided ``levels`` times, as an OBJ file (made once)."""
    import igl
    import numpy as np

    from ddg_oracle.application.meshes import sample_mesh_dir
    from ddg_oracle.application.meshfiles import read_mesh, write_obj

    out = Path(tempfile.gettempdir()) / "ddg-oracle-bench" / f"bunny-loop{levels}.obj"
    if not out.is_file():
        V, F = read_mesh(sample_mesh_dir() / "bunny.obj")[:2]
        V, F = np.asarray(V, dtype=float), np.asarray(F, dtype=np.int64)
        for _ in range(levels):
            V, F = igl.loop(V, F)
        out.parent.mkdir(parents=True, exist_ok=True)
        part = out.with_suffix(".part")
        write_obj(part, V, F)
        os.replace(part, out)                       # whole or not at all
    return out


#: the process tree's memory at which a run is stopped (MB; DDG_BENCH_MAX_MB): the machine
#: must keep working; a stopped row says so
MAX_MB = float(os.environ.get("DDG_BENCH_MAX_MB", 16 * 1024))


def measured(argv: list[str]) -> dict:
    """Run ``argv``; its wall time, exit code, CPU seconds of the process tree and the peak
    of the tree's summed resident memory (MB); stopped (every process of the tree killed,
    ``stopped`` True) when that memory passes :data:`MAX_MB`."""
    import psutil

    t0 = time.perf_counter()
    p = subprocess.Popen(argv, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                         text=True)
    top, peak, cpu = psutil.Process(p.pid), 0, {}
    while p.poll() is None:
        try:
            tree = [top, *top.children(recursive=True)]
        except psutil.Error:
            tree = []
        rss = 0
        for q in tree:
            try:
                with q.oneshot():
                    rss += q.memory_info().rss
                    t = q.cpu_times()
                    cpu[q.pid] = t.user + t.system      # the latest reading of each process
            except psutil.Error:                    # ended between the listing and now
                pass
        peak = max(peak, rss)
        if peak > MAX_MB * 2 ** 20:
            for q in reversed(tree):                # the workers first, then the check
                try:
                    q.kill()
                except psutil.Error:
                    pass
            p.wait()
            break
        time.sleep(0.2)
    p.stdout.read()
    wall = time.perf_counter() - t0
    return {"wall": wall, "exit": p.returncode, "cpu": sum(cpu.values()),
            "peak_mb": peak / 2 ** 20, "stopped": peak > MAX_MB * 2 ** 20}


def run(mode: Mode) -> dict:
    levels = 1 if mode.quick else 2
    mesh = big_mesh(levels)
    faces = sum(1 for line in open(mesh, encoding="utf-8") if line.startswith("f "))
    rows = []
    for impl in PLAN if not mode.quick else PLAN[:1]:
        load = round(os.getloadavg()[0], 1)
        with tempfile.TemporaryDirectory() as tmp:
            report = os.path.join(tmp, "report")
            argv = [sys.executable, "-m", "ddg_oracle", "check", "--mesh", str(mesh),
                    "--report", report] + (["--impl", impl] if impl else [])
            row = measured(argv)
            row.update(mesh=f"bunny.obj, igl.loop x {levels}", faces=faces, load=load,
                       impl=impl or "all installed", statuses={}, slowest=None)
            if not row["stopped"]:
                timings = json.loads(open(os.path.join(report, "timings.json")).read())
                results = json.loads(open(os.path.join(report, "results.json")).read())
                for r in results["results"]:
                    row["statuses"][r["status"]] = row["statuses"].get(r["status"], 0) + 1
                slow = max(timings["results"], key=lambda r: r["seconds"])
                row.update(slowest=f"{slow['property_id']} / {slow['implementation']}",
                           slowest_seconds=slow["seconds"])
        rows.append(row)
        say(f"  check --mesh {mesh.name} ({row['impl']}): {row['wall']:.0f} s wall, "
            f"{row['cpu']:.0f} s CPU, peak {row['peak_mb']:,.0f} MB, exit {row['exit']}"
            + (f" (stopped above {MAX_MB:,.0f} MB)" if row["stopped"] else ""))
    return {"rows": rows}
