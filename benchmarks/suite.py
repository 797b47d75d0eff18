"""Hypothesis throughput of a reference-vs-libigl property (issue 7, item 5), and the
wall time of the test suite and of ``ddg-oracle check`` on 2 workers (item 4)."""

from __future__ import annotations

import os
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
    from ddg_oracle.properties.registry import PROPERTIES
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


COMMANDS = [
    ("test suite, default profile", [sys.executable, "-m", "pytest", "-n", "2", "-q",
                                     "-p", "no:cacheprovider", "tests"], {}),
    ("test suite, ci profile", [sys.executable, "-m", "pytest", "-n", "2", "-q",
                                "-p", "no:cacheprovider", "tests"], {"CI": "true"}),
    ("ddg-oracle check (default)", [sys.executable, "-m", "ddg_oracle", "check"], {}),
]


def run_suite(mode: Mode) -> dict:
    """One run each (minutes): wall time, exit status."""
    rows = []
    for label, cmd, env in COMMANDS:
        t0 = time.perf_counter()
        p = subprocess.run(cmd, cwd=ROOT, env={**os.environ, **env}, capture_output=True,
                           text=True)
        wall = time.perf_counter() - t0
        last = (p.stdout.strip().splitlines() or [""])[-1]
        rows.append({"command": label, "wall": wall, "exit": p.returncode, "summary": last})
        say(f"  suite {label:30} {wall:8.1f} s exit {p.returncode}: {last}")
    return {"rows": rows}


MAIN_RUNS = 3


def run_main(mode: Mode) -> dict:
    """``ddg-oracle check`` as README command 1 runs it (every installed implementation),
    default profile ``MAIN_RUNS`` times and ci once: wall time of each run, its median, and
    the slowest task (from the report's timings.json); the load average before each run."""
    import json
    import statistics
    import tempfile

    rows = []
    plan = [("default", k) for k in range(1 if mode.quick else MAIN_RUNS)] + [("ci", 0)]
    for profile, k in plan:
        with tempfile.TemporaryDirectory() as tmp:
            load = round(os.getloadavg()[0], 1)
            report = os.path.join(tmp, "report")
            t0 = time.perf_counter()
            p = subprocess.run([sys.executable, "-m", "ddg_oracle", "check", "--profile", profile,
                                "--report", report], cwd=ROOT, capture_output=True, text=True)
            wall = time.perf_counter() - t0
            timings = json.loads(open(os.path.join(report, "timings.json")).read())
        slow = max(timings["results"], key=lambda r: r["seconds"])
        rows.append({"profile": profile, "run": k + 1, "wall": wall, "exit": p.returncode,
                     "load": load, "slowest": f"{slow['property_id']} / {slow['implementation']}",
                     "slowest_seconds": slow["seconds"], "checks": len(timings["results"])})
        say(f"  main {profile} run {k + 1}: {wall:.1f} s exit {p.returncode}, slowest "
            f"{rows[-1]['slowest']} {slow['seconds']:.1f} s (load {load})")
    default = [r["wall"] for r in rows if r["profile"] == "default"]
    return {"rows": rows, "median_default": statistics.median(default),
            "slowest_default": max(r["slowest_seconds"] for r in rows if r["profile"] == "default"),
            "ci": next(r["wall"] for r in rows if r["profile"] == "ci")}
