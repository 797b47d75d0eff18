"""No process a run starts outlives it (issue 45, item 1): a checked library's children, an
exec driver's children and the drivers themselves are stopped and reaped after a normal,
a failing and an interrupted run; SIGHUP stops a run as SIGINT does."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
import uuid
from pathlib import Path

import pytest

from tests.processes import cmdline, parent, pool_workers

ROOT = Path(__file__).resolve().parent.parent


def _strays(marker: str) -> list[int]:
    out = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/cmdline", "rb") as fh:
                if marker.encode() in fh.read():
                    out.append(int(entry))
        except OSError:
            continue
    return out


@pytest.fixture
def project(tmp_path):
    marker = f"ddg-stray-{uuid.uuid4().hex[:12]}"
    (tmp_path / "spawning.py").write_text(textwrap.dedent(f"""\
        import subprocess, sys
        from ddg_oracle.oracles.exact_reference import ReferenceImplementation
        SLEEP = [sys.executable, "-c", "import time; time.sleep(300)", "{marker}"]
        class Spawns(ReferenceImplementation):
            name = "spawns"
            def euler_characteristic(self, V, F):
                subprocess.Popen(SLEEP)                        # a helper process per call
                return super().euler_characteristic(V, F)
        class SpawnsAndFails(Spawns):
            name = "spawns-and-fails"
            def euler_characteristic(self, V, F):
                return super().euler_characteristic(V, F) + 1
        """))
    (tmp_path / "driver.py").write_text(textwrap.dedent(f"""\
        import json, subprocess, sys, time
        child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(300)",
                                  "{marker}"])
        for line in sys.stdin:
            r = json.loads(line)
            if r["method"] == "hello":
                print(json.dumps({{"methods": ["euler_characteristic"]}}), flush=True)
            else:
                time.sleep(300)                                 # hangs on the first request
        """))
    yield tmp_path, marker
    for p in _strays(marker):
        os.kill(p, signal.SIGKILL)


def _ddg(cwd, *args, **kw):
    exe = str(Path(sys.executable).with_name("ddg-oracle"))
    return subprocess.Popen([exe, "check", *args], cwd=cwd, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, **kw)


@pytest.mark.parametrize("impl, workers, rc", [("spawning:Spawns", "1", 0),
                                                ("spawning:Spawns", "2", 0),
                                                ("spawning:SpawnsAndFails", "1", 1)])
def test_a_librarys_children_end_with_the_run(project, impl, workers, rc):
    cwd, marker = project
    p = _ddg(cwd, "--impl", impl, "--only", "D1.6", "X1.4", "--workers", workers)
    out, err = p.communicate(timeout=300)
    assert p.returncode == rc, out + err
    time.sleep(0.3)
    assert _strays(marker) == []


def test_a_hanging_driver_and_its_children_end_with_the_run(project):
    cwd, marker = project
    spec = f"exec:{sys.executable} driver.py"
    p = _ddg(cwd, "--impl", spec, "--only", "D1.6", "--budget", "3", "--workers", "1")
    out, err = p.communicate(timeout=300)
    assert p.returncode == 1 and "hang" in out, out + err
    time.sleep(0.3)
    assert _strays(marker) == []


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGHUP])
def test_an_interrupted_run_leaves_no_process_and_says_how_to_resume(project, sig):
    cwd, marker = project
    p = _ddg(cwd, "--impl", "spawning:Spawns", "--only", "D1.6", "R1.5", "CS", "--profile", "ci",
             "--report", str(cwd / "report"))
    deadline = time.monotonic() + 60
    while not _strays(marker) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert _strays(marker), "the implementation never started a helper"
    p.send_signal(sig)
    out, err = p.communicate(timeout=120)
    assert p.returncode == 128 + sig, out + err
    assert f"interrupted by {signal.Signals(sig).name}" in err and "--resume" in err
    time.sleep(0.3)
    assert _strays(marker) == []


def test_a_stopped_pool_worker_is_replaced_and_the_run_completes(tmp_path):
    # a SIGSTOPped worker stalled the run forever: the heartbeat kills it, its task runs again
    # ci: tasks of seconds, so the worker is stopped while it runs one (the resource
    # tracker, also a "multiprocessing" child, is not a pool worker: stopping it tested
    # something else, see the next test); a worker is sent its first task as it starts,
    # so the stopped one holds a task, and its death makes the rest of the run wait for
    # a fresh worker to run that task again
    only = ["D2.2", "R2.4", "T2.6", "D2.6", "D3.1"]
    p = _ddg(tmp_path, "--impl", "reference", "--only", *only, "--workers", "2",
             "--profile", "ci")
    deadline = time.monotonic() + 60
    workers = []
    while time.monotonic() < deadline and len(workers) < 2:
        workers = pool_workers(p.pid)
        time.sleep(0.05)
    assert workers, "no pool worker started"
    time.sleep(0.5)
    os.kill(workers[0], signal.SIGSTOP)
    out, err = p.communicate(timeout=240)
    assert p.returncode == 0, out + err
    assert f"{len(only)} checks in" in out and f"{len(only)} passed" in out




def test_a_stopped_resource_tracker_does_not_hang_the_exit(tmp_path):
    # the run keeps multiprocessing's resource tracker alive to its end (killed first, the
    # exit handlers relaunch it and it prints tracebacks); a stopped one is killed instead,
    # or the interpreter's exit would wait for it forever (os.waitpid in its _stop)
    from ddg_oracle.application.containment import descendants
    p = _ddg(tmp_path, "--impl", "reference", "--only", "D2.2", "R2.4", "T2.6", "D2.6",
             "--workers", "2")
    deadline = time.monotonic() + 60
    trackers = []
    while time.monotonic() < deadline and not trackers and p.poll() is None:
        trackers = [q for q in descendants(p.pid) if parent(q) == p.pid
                    and b"resource_tracker" in cmdline(q)]
        time.sleep(0.05)
    if not trackers:
        pytest.skip("the run started no resource tracker before it ended")
    os.kill(trackers[0], signal.SIGSTOP)
    out, err = p.communicate(timeout=120)
    assert p.returncode == 0, out + err
    assert "4 checks in" in out





# --- how workers start: from a preloaded forkserver in the command, spawned elsewhere ------

_STARTS = """
import multiprocessing as mp, os, sys
from ddg_oracle.application.containment import start_workers_from_a_forkserver, worker_context
from tests.processes import report_environment

def seen(ctx):
    parent, child = ctx.Pipe()
    p = ctx.Process(target=report_environment, args=(child, "DDG_TEST_VALUE"))
    p.start()
    child.close()
    got = parent.recv()
    p.join()
    return got

if sys.argv[1] == "command":
    assert start_workers_from_a_forkserver()
os.environ["DDG_TEST_VALUE"] = "first"
print(*seen(worker_context()))
os.environ["DDG_TEST_VALUE"] = "second"          # after the forkserver started
print(*seen(worker_context()))
# the user's own forkserver: none of our modules preloaded (a user's process only)
print(*seen(mp.get_context("forkserver")))
"""


@pytest.mark.parametrize("process", ["command", "user"])
def test_workers_start_with_the_parents_environment_and_preload_only_in_the_command(process):
    out = subprocess.run([sys.executable, "-c", _STARTS, process], cwd=ROOT,
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    first, second, users = out.stdout.splitlines()
    preloaded = str(process == "command")
    # the environment when the worker starts, not the one the forkserver started with
    assert first == f"first {preloaded}" and second == f"second {preloaded}", out.stdout
    if process == "user":                 # the user's forkserver is left as it was
        assert users == "second False", out.stdout


_USERS_ISOLATION = """
import numpy as np
from ddg_oracle.application.isolation import ImplementationCrashed, Isolated
from ddg_oracle.reference import surfaces
from tests.processes import cmdline
closed, disk = (tuple(np.array(a) for a in s.to_arrays())
                for s in (surfaces.tetrahedron(), surfaces.disk(5)))
with Isolated("tests.misbehaving:SegfaultsOnBoundary", timeout=30) as impl:
    assert impl.euler_characteristic(*closed) == 2
    assert b"spawn_main" in cmdline(impl._proc.pid), cmdline(impl._proc.pid)
    try:
        impl.euler_characteristic(*disk)
        raise SystemExit("the segfault was not reported")
    except ImplementationCrashed as e:
        assert "SIGSEGV" in str(e), e
    assert impl.euler_characteristic(*closed) == 2          # a fresh worker, spawned again
print("ok")
"""


def test_in_a_users_process_an_isolated_crash_is_reported_from_a_spawned_worker():
    """The path a user's process takes (the plugin, main(argv)): no forkserver, the isolated
    library spawned; its crash is a reported crash and the next call starts a fresh one.
    (The suite's own processes fork their workers, as the command does: conftest.)"""
    out = subprocess.run([sys.executable, "-c", _USERS_ISOLATION], cwd=ROOT,
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stdout + out.stderr
