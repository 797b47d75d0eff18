"""check --scheduler on a real dask.distributed cluster: a scheduler and two workers started
as a user starts them (``dask scheduler``, ``dask worker --nthreads 1``), each a process of
its own; the results are the local run's byte for byte, a worker killed mid-run loses no
result, --resume finishes a run on the cluster.  ``local:N`` (a LocalCluster started by the
run) is tests/test_survey.py's, through the same module.

Everything dask runs in processes of its own, as for a user: the suite's own processes
never import distributed."""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

if not any((Path(p) / "distributed").is_dir() for p in sys.path if p):
    pytest.skip("dask.distributed is not installed", allow_module_level=True)

ROOT = Path(__file__).resolve().parents[1]
ARGS = ["--impl", "reference", "--impl", "tests.misbehaving:SlowChi",
        "--impl", "tests.planted_bugs:ChiIgnoresBoundary", "--only", "D1.6", "--only", "T1.1",
        "--only", "R1.6", "--seed", "0"]
#: no example database: a failure the local run saved would be replayed first by the
#: next run (by design), which then counts fewer examples and differs byte for byte
ENV = {**os.environ, "DDG_HYPOTHESIS_DATABASE": "none"}


def _check(report, *extra, wait=True):
    argv = [sys.executable, "-m", "ddg_oracle", "check", *ARGS, "--report", str(report), *extra]
    p = subprocess.Popen(argv, cwd=ROOT, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if not wait:
        return p
    out, err = p.communicate(timeout=300)
    return p.returncode, out + err


@pytest.fixture(scope="module")
def local_run(tmp_path_factory):
    report = tmp_path_factory.mktemp("local") / "report"
    rc, out = _check(report, "--workers", "1")
    assert rc == 1, out                              # ChiIgnoresBoundary fails D1.6
    return rc, (report / "results.json").read_bytes()


#: waits until the scheduler's workers are exactly the named ones (a killed worker gone)
_WAIT_FOR = ("import sys, time; from distributed import Client\n"
             "c = Client(sys.argv[1], timeout=60); want = set(sys.argv[2:])\n"
             "deadline = time.monotonic() + 60\n"
             "while {w['name'] for w in c.scheduler_info()['workers'].values()} != want:\n"
             "    assert time.monotonic() < deadline, c.scheduler_info()['workers']\n"
             "    time.sleep(0.1)\n")


@pytest.fixture(scope="module")
def _scheduler(tmp_path_factory):
    """(scheduler address, worker processes so far): one `dask scheduler` for the module;
    its workers are started by `cluster` (each test's)."""
    sched_file = tmp_path_factory.mktemp("dask") / "scheduler.json"
    procs = [subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_scheduler",
                               "--scheduler-file", str(sched_file), "--port", "0",
                               "--no-dashboard"], cwd=ROOT,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    try:
        deadline = time.monotonic() + 60
        while not sched_file.exists() and time.monotonic() < deadline:
            time.sleep(0.1)
        time.sleep(0.2)                              # written at once, but not atomically
        address = json.loads(sched_file.read_text())["address"]
        yield address, procs
    finally:
        for p in procs:
            p.kill()
            p.wait()


@pytest.fixture
def cluster(_scheduler):
    """(scheduler address, worker processes): the module's `dask scheduler` and two live
    `dask worker`s without nannies (a killed worker stays dead: its tasks must go to the
    other one).  The workers are shared by the tests; one a test killed is replaced by a
    fresh one, and the scheduler knows exactly the two live ones before the test starts."""
    address, procs = _scheduler
    workers = [p for p in procs[1:] if p.poll() is None]
    started = False
    while len(workers) < 2:
        name = f"w{len(procs)}"
        w = subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", address,
                              "--nthreads", "1", "--no-nanny", "--no-dashboard", "--name", name],
                             cwd=ROOT, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        w.name, started = name, True
        procs.append(w)
        workers.append(w)
    if started:
        subprocess.run([sys.executable, "-c", _WAIT_FOR, address, *(w.name for w in workers)],
                       check=True, timeout=120, capture_output=True)
    return address, workers


def test_results_on_a_cluster_are_byte_identical_and_resume_finishes_them(tmp_path, cluster,
                                                                         local_run):
    address, _ = cluster
    report = tmp_path / "remote"
    rc, out = _check(report, "--scheduler", address)
    assert rc == local_run[0], out
    assert (report / "results.json").read_bytes() == local_run[1]
    assert "2 workers" in out
    # as if interrupted after three results: --resume runs the rest on the same cluster (its
    # command line, --scheduler included, is the run's own) and ends with the same bytes
    lines = (report / "results.jsonl").read_text().splitlines()
    (report / "results.jsonl").write_text("\n".join(lines[:3]) + "\n")
    (report / "results.json").unlink()
    p = subprocess.run([sys.executable, "-m", "ddg_oracle", "check", "--resume", str(report)],
                       cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=300)
    assert p.returncode == local_run[0], p.stdout + p.stderr
    assert (report / "results.json").read_bytes() == local_run[1]


def test_a_worker_killed_mid_run_loses_no_result(tmp_path, cluster, local_run):
    address, workers = cluster
    report = tmp_path / "remote"
    p = _check(report, "--scheduler", address, wait=False)
    lines = report / "results.jsonl"
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and p.poll() is None:
        if lines.exists() and lines.read_text().count("\n") >= 1:
            break                                    # tasks are running on both workers
        time.sleep(0.05)
    assert p.poll() is None, "the run ended before a worker could be killed"
    workers[0].send_signal(signal.SIGKILL)
    out, err = p.communicate(timeout=300)
    assert p.returncode == local_run[0], out + err
    results = json.loads((report / "results.json").read_text())["results"]
    assert not [r for r in results if r["status"] == "crashed"]
    assert (report / "results.json").read_bytes() == local_run[1]
    assert workers[0].wait() == -signal.SIGKILL and workers[1].poll() is None


def test_a_bad_scheduler_address_is_a_usage_error(capsys):
    from ddg_oracle.application.cli import main
    rc = main(["check", "--impl", "reference", "--only", "D1.6", "--scheduler", "local:zero"])
    _, err = capsys.readouterr()
    assert rc == 2 and "local:N" in err and err.count("\n") == 1
    assert "distributed" not in sys.modules          # refused before dask is imported


def test_an_unreachable_scheduler_is_a_usage_error():
    p = subprocess.run([sys.executable, "-m", "ddg_oracle", "check", "--impl", "reference",
                        "--only", "D1.6", "--scheduler", "tcp://127.0.0.1:9"],
                       cwd=ROOT, capture_output=True, text=True, timeout=120,
                       env={**os.environ, "DASK_DISTRIBUTED__COMM__TIMEOUTS__CONNECT": "2s"})
    assert p.returncode == 2 and "cannot reach a dask scheduler" in p.stderr, p.stderr
