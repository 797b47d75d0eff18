"""The fault suite (``python -m benchmarks faults``, issue 45 item 7) and the mesh-read memory
measurement (``python -m benchmarks meshread``, item 4), through their public functions: a
few fast cases of each area are handled, the verdict rule catches what it must (a wrong exit
code, a stray process), and a tiny file's peak/size ratio is a finite number."""

from __future__ import annotations

import math
import sys

import pytest

from ddg_oracle.application.containment import alive

from benchmarks import faults, meshread

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"),
                                reason="counts processes through /proc")

FAST = ["Python library starting a helper per call, 1 worker",
        "crafted report directory (a pickle) on --resume",
        "damaged run.json []",
        "compare a FIFO",
        "verify: answers /dev/zero",
        "verify: answers a FIFO",
        "verify: an empty answers file",
        "check --only ",
        "DDG_EXAMPLE_TIME_LIMIT=soon"]


def test_a_few_cases_of_the_fault_suite_are_handled(tmp_path):
    by_name = {c.name: c for c in faults.cases()}
    outcomes = faults.run_cases([by_name[n] for n in FAST], kit=tmp_path)
    assert len(outcomes) == len(FAST)
    bad = {o.case.name: (o.problems, o.command, o.err[-300:]) for o in outcomes if not o.handled}
    assert not bad, bad
    rows = {r["area"]: r for r in faults.summary(outcomes)}
    assert sum(r["cases"] for r in rows.values()) == len(FAST)
    assert all(r["badly"] == 0 for r in rows.values())
    assert "| **all** | 9 | 9 | 0 | 0 |" in faults.table(outcomes)


def test_the_verdict_rule_sees_a_wrong_exit_and_a_stray(tmp_path):
    # a usage error where success was expected; a program that leaves a process in a
    # session of its own (found by the marker in its environment, then killed)
    leaves = ("import subprocess, sys\n"
              "subprocess.Popen([sys.executable, '-c', 'import time; time.sleep(60)'],\n"
              "                 start_new_session=True)\n")
    cases = [faults.Case("error paths, exit codes", "expects success",
                         lambda c: c.ddg("check", "--impl", "reference", "--only", ""), rc=0),
             faults.Case("containment", "leaves a stray",
                         lambda c: [sys.executable, "-c", leaves], rc=0)]
    wrong, stray = faults.run_cases(cases, kit=tmp_path)
    assert not wrong.handled and "exit 2, expected 0" in wrong.problems
    assert not stray.handled and stray.strays
    assert "1 stray process(es) left after the run" in stray.problems
    assert all(not alive(p) for p in stray.strays)          # killed by the suite


def test_meshread_measures_a_finite_ratio_on_a_tiny_file(tmp_path):
    path = meshread.make_file(tmp_path, "obj", 0.02)
    r = meshread.measure(path)
    assert r["exit"] == 0 and r["bytes"] == path.stat().st_size
    assert math.isfinite(r["ratio"]) and r["ratio"] > 0 and r["peak_mb"] > 0 < r["baseline_mb"]
    assert math.isfinite(r["net_ratio"])          # a tiny read is within the noise: any sign
