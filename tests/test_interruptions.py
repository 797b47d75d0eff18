"""Runs that lose nothing: SIGINT / SIGTERM mid-run, ``--resume``, a killed pool worker.

Each run is a real ``ddg-oracle check --report DIR`` subprocess in a session of its
own (so its process group can be counted afterwards), with 2 pool workers under
the derandomized ``ci`` profile, whose results.json is byte-identical from run to
run; an undisturbed run of the same command is the yardstick.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.processes import pool_workers

ROOT = Path(__file__).resolve().parent.parent
ONLY = ["D1.6", "R1.5", "X1.4", "CS", "D2.2", "T2.6", "D3.1"]


def _command(report: Path) -> list[str]:
    return [sys.executable, "-m", "ddg_oracle", "check", "--impl", "reference", "--only", *ONLY,
            "--profile", "ci", "--workers", "2", "--report", str(report)]


def _start(report: Path) -> subprocess.Popen:
    return subprocess.Popen(_command(report), cwd=ROOT, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, start_new_session=True)


def _lines(report: Path) -> int:
    try:
        return len((report / "results.jsonl").read_text().splitlines())
    except OSError:
        return 0


def _wait_for_lines(report: Path, n: int, proc, seconds: float = 120) -> None:
    deadline = time.monotonic() + seconds
    while _lines(report) < n:
        assert proc.poll() is None, "the run ended before it could be interrupted"
        assert time.monotonic() < deadline, "no result streamed in time"
        time.sleep(0.05)


def _group_after(pgid: int, seconds: float = 0.5) -> list[int]:
    """Processes of process group ``pgid`` still alive ``seconds`` after now, found as soon
    as there are none: a group with no live member never gets one again (only a member can
    start a process in it), so polling says what one look after ``seconds`` says."""
    deadline = time.monotonic() + seconds
    while (left := _group(pgid)) and time.monotonic() < deadline:
        time.sleep(0.05)
    return left


def _group(pgid: int) -> list[int]:
    """Processes of process group ``pgid`` still alive (zombies excluded)."""
    out = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                fields = open(f"/proc/{entry}/stat", "rb").read().rsplit(b")", 1)[1].split()
            except OSError:
                continue
            if int(fields[2]) == pgid and fields[0] != b"Z":
                out.append(int(entry))
    return out


@pytest.fixture(scope="module")
def undisturbed(tmp_path_factory):
    report = tmp_path_factory.mktemp("runs") / "undisturbed"
    out = subprocess.run(_command(report), cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stdout + out.stderr
    doc = json.loads((report / "results.json").read_text())
    assert doc["interrupted"] is False and len(doc["results"]) == len(ONLY)
    return (report / "results.json").read_bytes()


@pytest.mark.parametrize("signum, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_signal_mid_run_keeps_a_partial_report_and_leaves_no_process(tmp_path, undisturbed,
                                                                        signum, code):
    report = tmp_path / "report"
    proc = _start(report)
    _wait_for_lines(report, 2, proc)
    proc.send_signal(signum)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == code, out + err
    assert "Traceback" not in err and "interrupted by" in err and "--resume" in err
    doc = json.loads((report / "results.json").read_text())
    assert doc["interrupted"] is True
    assert 2 <= len(doc["results"]) < len(ONLY)
    assert all(r["status"] == "passed" for r in doc["results"])
    assert (report / "index.html").is_file() and "interrupted" in (report / "summary.md").read_text()
    assert _group_after(proc.pid, 0.5) == []        # no worker or library process left behind

    # --resume finishes it: the same results as the undisturbed run, byte for byte
    done = _lines(report)
    resumed = subprocess.run([sys.executable, "-m", "ddg_oracle", "check", "--resume",
                              str(report)], cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert resumed.returncode == 0, resumed.stdout + resumed.stderr
    assert (report / "results.json").read_bytes() == undisturbed
    assert _lines(report) == len(ONLY) and done < len(ONLY)   # finished tasks were not rerun


def test_a_killed_pool_worker_is_replaced_and_nothing_is_lost(tmp_path, undisturbed):
    report = tmp_path / "report"
    proc = _start(report)
    _wait_for_lines(report, 1, proc)
    workers = pool_workers(proc.pid)
    assert workers, "no pool worker found"
    os.kill(workers[0], signal.SIGKILL)
    out, err = proc.communicate(timeout=600)
    assert proc.returncode == 0, out + err
    assert (report / "results.json").read_bytes() == undisturbed


SPAWNING = '''
import subprocess, sys, time
from ddg_oracle.oracles.exact_reference import ReferenceImplementation


class SpawnsSlowly(ReferenceImplementation):
    """A library that starts a helper process per Laplacian and takes a second."""
    name = "spawns-slowly"

    def cotan_laplacian(self, V, F):
        subprocess.Popen([sys.executable, "-c", "import time; time.sleep(300)"])
        time.sleep(1.0)
        return super().cotan_laplacian(V, F)
'''


def _children_started(pid: int) -> bool:
    from ddg_oracle.application.containment import descendants
    return len(descendants(pid)) >= 2


@pytest.mark.parametrize("command", ["compare", "verify"])
@pytest.mark.parametrize("signum, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143),
                                          (signal.SIGHUP, 129)])
def test_a_signal_to_compare_or_verify_is_one_line_and_leaves_no_process(tmp_path, command,
                                                                         signum, code):
    # compare and verify had no handler: SIGTERM killed them at once (exit -15) and left
    # the library's helpers and the exact values' pool running; SIGINT printed
    # multiprocessing's tracebacks (its resource tracker had been killed first)
    from ddg_oracle.reference import surfaces
    (tmp_path / "spawning.py").write_text(SPAWNING)
    s = surfaces.icosahedron()
    obj = tmp_path / "ico.obj"
    obj.write_text("".join("v %r %r %r\n" % tuple(float(x) for x in p) for p in s.positions)
                   + "".join("f %d %d %d\n" % tuple(v + 1 for v in f)
                             for f in s.triangulation.faces))
    target = str(obj) if command == "compare" else str(ROOT / "vectors")
    env = dict(os.environ, PYTHONPATH=str(tmp_path) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    proc = subprocess.Popen([sys.executable, "-m", "ddg_oracle", command, target, "--impl",
                             "spawning:SpawnsSlowly"], cwd=tmp_path, env=env, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True)
    deadline = time.monotonic() + 60
    while not _children_started(proc.pid):
        assert proc.poll() is None and time.monotonic() < deadline, proc.communicate()
        time.sleep(0.05)
    time.sleep(0.3)
    proc.send_signal(signum)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == code, out + err
    assert err.strip() == f"ddg-oracle: interrupted by {signal.Signals(signum).name}", err
    assert _group_after(proc.pid, 0.5) == []        # no helper, pool or library process left
