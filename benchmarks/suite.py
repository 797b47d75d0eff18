"""Hypothesis throughput of a reference-vs-libigl property (issue 7, item 5), and the
wall time of the test suite and of ``ddg-oracle check`` on 2 workers (item 4)."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import time

from .common import ROOT, Mode, say

PROPERTY = "D3.1"        # cotan_laplacian equals the exact cotan weights, within the bound


def run_hypothesis(mode: Mode) -> dict:
    from hypothesis import settings

    from ddg_oracle.properties.profiles import profile
    from ddg_oracle.oracles.exact_reference import ReferenceImplementation
    from ddg_oracle.oracles.libigl import Libigl
    from ddg_oracle.properties import PROPERTIES
    from ddg_oracle.properties.runner import run_property

    n = 25 if mode.quick else 200
    s = settings(profile("ci"), max_examples=n)
    rows = []
    for impl in (Libigl(), ReferenceImplementation()):
        t0, c0 = time.perf_counter(), time.process_time()
        r = run_property(PROPERTIES[PROPERTY], impl, s, seed=0)
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
        rows.append({"property": PROPERTY, "implementation": r.implementation,
                     "status": r.status, "examples": r.examples, "seconds": cpu,
                     "wall": wall, "examples_per_s": r.examples / cpu if cpu else None})
        say(f"  hypothesis {PROPERTY} {r.implementation:12} {r.status} {r.examples} examples "
            f"{cpu:.2f} s")
    return {"rows": rows}


def readme_workers() -> str:
    """The xdist worker count of README's test command (``python -m pytest -n N tests``)."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    return re.search(r"python -m pytest -n (\d+) tests", text).group(1)


def commands() -> list:
    """(label, argv, environment) of the suite exactly as README runs it, and of the check."""
    suite = [sys.executable, "-m", "pytest", "-n", readme_workers(), "-q", "-p",
             "no:cacheprovider", "tests"]
    return [("test suite, default profile", suite, {}),
            ("test suite, ci profile", suite, {"CI": "true"}),
            ("ddg-oracle check (default)", [sys.executable, "-m", "ddg_oracle", "check"], {})]


def run_suite(mode: Mode) -> dict:
    """One run each (minutes): wall time, the CPU time of the command and every process it
    waited for (user + system: less noisy than wall on a shared machine), exit status."""
    import resource
    rows = []
    for label, cmd, env in commands():
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        p = subprocess.run(cmd, cwd=ROOT, env={**os.environ, **env}, capture_output=True,
                           text=True)
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        last = (p.stdout.strip().splitlines() or [""])[-1]
        rows.append({"command": label, "wall": wall, "cpu": cpu, "exit": p.returncode,
                     "summary": last})
        say(f"  suite {label:30} {wall:8.1f} s ({cpu:.0f} CPU-s) exit {p.returncode}: {last}")
    return {"rows": rows}


MAIN_RUNS = 3


def run_main(mode: Mode) -> dict:
    """``ddg-oracle check`` exactly as README command 1 runs it (every installed
    implementation, no ``--report``), default profile ``MAIN_RUNS`` times: the wall time of
    each run and their median; then once more with ``--report`` (its pictures and files
    make it slower) for the slowest task, from the report's timings.json, and ``--profile
    ci`` once, with ``--report`` too.  The load average before each run."""
    import json
    import statistics
    import tempfile

    rows = []
    plan = [("default", k, False) for k in range(1 if mode.quick else MAIN_RUNS)]
    plan += [("default", len(plan), True), ("ci", 0, True)]
    for profile, k, with_report in plan:
        with tempfile.TemporaryDirectory() as tmp:
            load = round(os.getloadavg()[0], 1)
            report = os.path.join(tmp, "report")
            argv = [sys.executable, "-m", "ddg_oracle", "check", "--profile", profile]
            argv += ["--report", report] if with_report else []
            t0 = time.perf_counter()
            p = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True)
            wall = time.perf_counter() - t0
            row = {"profile": profile, "run": k + 1, "wall": wall, "exit": p.returncode,
                   "load": load, "report": with_report, "slowest": None, "slowest_seconds": None,
                   "checks": int(re.search(r"(\d+) checks? in", p.stdout).group(1))}
            if with_report:
                timings = json.loads(open(os.path.join(report, "timings.json")).read())
                slow = max(timings["results"], key=lambda r: r["seconds"])
                row.update(slowest=f"{slow['property_id']} / {slow['implementation']}",
                           slowest_seconds=slow["seconds"])
        rows.append(row)
        say(f"  main {profile} run {k + 1}{' --report' if with_report else ''}: {wall:.1f} s "
            f"exit {p.returncode}" + (f", slowest {row['slowest']} {row['slowest_seconds']:.1f} s"
                                      if with_report else "") + f" (load {load})")
    default = [r["wall"] for r in rows if r["profile"] == "default" and not r["report"]]
    return {"rows": rows, "median_default": statistics.median(default),
            "slowest_default": max(r["slowest_seconds"] for r in rows
                                   if r["profile"] == "default" and r["report"]),
            "ci": next(r["wall"] for r in rows if r["profile"] == "ci")}


#: (mesh, implementations): README's check on PyMeshLab's bunnies, every installed
#: implementation (None) and libigl alone
MESH_CHECKS = [("pymeshlab:bunny10k_textured.obj", None), ("pymeshlab:bunny10k_textured.obj", "libigl"),
               ("pymeshlab:bunny.obj", None), ("pymeshlab:bunny.obj", "libigl")]


def run_mesh_checks(mode: Mode) -> dict:
    """``ddg-oracle check --mesh MESH [--impl libigl] --report DIR`` per row of
    :data:`MESH_CHECKS` (``--quick``: the 10k bunny only), then ``ddg-oracle compare`` on
    the same meshes (every installed implementation), each 3 times (``--quick``: once),
    alternating: the median wall time, every wall time, exit code, the load average before
    the first run, and from the median run's timings.json the task-seconds per
    implementation and the slowest (property, implementation)."""
    import json
    import statistics
    import tempfile

    rounds = 1 if mode.quick else 3
    plan = [(m, i) for m, i in MESH_CHECKS if not mode.quick or "10k" in m]
    plan += [(m, "compare") for m in dict.fromkeys(m for m, _ in plan)]
    runs: dict = {k: [] for k in plan}
    load0 = {}
    for _ in range(rounds):
        for mesh, impl in plan:
            load0.setdefault((mesh, impl), round(os.getloadavg()[0], 1))
            with tempfile.TemporaryDirectory() as tmp:
                report = os.path.join(tmp, "report")
                if impl == "compare":
                    argv = [sys.executable, "-m", "ddg_oracle", "compare", mesh]
                else:
                    argv = [sys.executable, "-m", "ddg_oracle", "check", "--mesh", mesh,
                            "--report", report] + (["--impl", impl] if impl else [])
                t0 = time.perf_counter()
                p = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True)
                wall = time.perf_counter() - t0
                run = {"wall": wall, "exit": p.returncode}
                if impl != "compare":
                    timings = json.loads(open(os.path.join(report, "timings.json")).read())
                    results = json.loads(open(os.path.join(report, "results.json")).read())
                    run["timings"], run["results"] = timings["results"], results["results"]
            runs[mesh, impl].append(run)
            say(f"  {'compare' if impl == 'compare' else 'check --mesh'} {mesh} "
                f"({impl or 'all installed'}): {wall:.1f} s exit {p.returncode}")
    rows = []
    for (mesh, impl), done in runs.items():
        walls = [r["wall"] for r in done]
        mid = sorted(done, key=lambda r: r["wall"])[(len(done) - 1) // 2]
        row = {"mesh": mesh, "impl": impl or "all installed", "wall": statistics.median(walls),
               "walls": walls, "exit": mid["exit"], "load": load0[mesh, impl],
               "command": "compare" if impl == "compare" else "check --mesh"}
        if "timings" in mid:
            per: dict = {}
            for r in mid["timings"]:
                per[r["implementation"]] = per.get(r["implementation"], 0.0) + r["seconds"]
            slow = max(mid["timings"], key=lambda r: r["seconds"])
            statuses: dict = {}
            for r in mid["results"]:
                statuses[r["status"]] = statuses.get(r["status"], 0) + 1
            row.update(task_seconds=per, statuses=statuses,
                       slowest=f"{slow['property_id']} / {slow['implementation']}",
                       slowest_seconds=slow["seconds"])
        if impl == "compare":
            row["impl"] = "all installed"
        rows.append(row)
    return {"rows": rows}
