"""Timing, fitting and the results file shared by the benchmark groups."""

from __future__ import annotations

import gc
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RESULTS = ROOT / "docs" / "perf" / "results.json"


@dataclass
class Mode:
    """How hard to measure: ``quick`` (under a minute in all) or the default."""

    quick: bool
    runs: int            # at most this many runs per measurement (median reported)
    budget: float        # stop repeating once a measurement used this many CPU seconds
    gc_paused: bool = False   # the collector paused around each timed run (as timeit does)

    @classmethod
    def of(cls, quick: bool, runs: int | None = None, gc_paused: bool = False) -> "Mode":
        if quick:
            return cls(True, runs or 3, 0.5, gc_paused)
        return cls(False, runs or 5, 3.0, gc_paused)


def start_clock() -> float:
    """``time.process_time()`` after a full garbage collection, so that a timed call pays
    for collecting its own objects, not for those its untimed setup left (CPython starts
    a full collection once enough objects have survived, whoever made them; the
    interpreter's settings are left as they are)."""
    gc.collect()
    return time.process_time()


def median_time(run, mode: Mode, setup=None) -> tuple[float, int, object]:
    """Median CPU seconds of ``run(setup())`` over up to ``mode.runs`` runs (fewer
    once ``mode.budget`` is spent); returns ``(median, runs, last result)``."""
    times, out = [], None
    while len(times) < mode.runs and (not times or sum(times) < mode.budget):
        arg = setup() if setup is not None else None
        t0 = start_clock()
        if mode.gc_paused:
            gc.disable()          # the benchmark's process only, restored below
        try:
            out = run(arg) if setup is not None else run()
        finally:
            gc.enable()
        times.append(time.process_time() - t0)
    return statistics.median(times), len(times), out


def fit_exponent(sizes, seconds) -> float | None:
    """Least-squares slope of log(time) against log(size): time ~ size^slope."""
    pts = [(math.log(n), math.log(t)) for n, t in zip(sizes, seconds) if t and t > 0]
    if len(pts) < 2:
        return None
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    sxx = sum((x - mx) ** 2 for x, _ in pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sxx if sxx else None


def machine() -> dict:
    """Where and when: enough to read a table months later."""
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                                capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        commit = "unknown"
    return {"date": time.strftime("%Y-%m-%d %H:%M"), "commit": commit,
            "python": platform.python_version(), "cpus": os.cpu_count(),
            "load": round(os.getloadavg()[0], 1) if hasattr(os, "getloadavg") else None,
            "platform": platform.platform(terse=True)}


def load_results() -> dict:
    if RESULTS.exists():
        return json.loads(RESULTS.read_text())
    return {}


def save_results(results: dict) -> None:
    RESULTS.parent.mkdir(parents=True, exist_ok=True)
    RESULTS.write_text(json.dumps(results, indent=1, sort_keys=True) + "\n")


def say(*args) -> None:
    print(*args, file=sys.stderr, flush=True)
