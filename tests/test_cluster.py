"""check --scheduler: the tasks on a real dask.distributed cluster of worker processes,
results identical to the local run, a killed worker's tasks run again, --resume."""

import json
import os
import signal
import threading
import time

import pytest

distributed = pytest.importorskip("distributed")
import dask  # noqa: E402

from ddg_oracle.cli import main  # noqa: E402

ARGS = ["check", "--impl", "reference", "--impl", "tests.misbehaving:SlowChi",
        "--impl", "tests.planted_bugs:ChiIgnoresBoundary", "--only", "D1.6", "--only", "T1.1",
        "--only", "R1.6", "--seed", "0"]


def _check(capsys, tmp_path, name, *extra):
    report = tmp_path / name
    rc = main([*ARGS, "--report", str(report), *extra])
    out, err = capsys.readouterr()
    return rc, report, out + err


@pytest.fixture(scope="module")
def cluster():
    # as a user would start one (dask scheduler / dask worker --nthreads 1), with worker
    # processes that may start the libraries' processes
    # (for the whole module: the nannies read it again when they restart a killed worker)
    with dask.config.set({"distributed.worker.daemon": False}):
        c = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                     dashboard_address=":0")
        yield c
        c.close()


def test_results_on_a_cluster_are_byte_identical_to_the_local_run(capsys, tmp_path, cluster):
    rc_local, local, _ = _check(capsys, tmp_path, "local", "--workers", "1")
    rc, remote, out = _check(capsys, tmp_path, "remote", "--scheduler", cluster.scheduler_address)
    assert rc == rc_local == 1                      # ChiIgnoresBoundary fails D1.6
    assert (remote / "results.json").read_bytes() == (local / "results.json").read_bytes()
    assert "2 workers" in out


def test_a_killed_worker_loses_no_result(capsys, tmp_path, cluster):
    rc_local, local, _ = _check(capsys, tmp_path, "local", "--workers", "1")
    client = distributed.Client(cluster)
    pids = client.run(os.getpid)
    killed = []

    def kill_a_busy_worker():
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and not killed:
            busy = [w for w, keys in client.processing().items()
                    if any(str(k).startswith("ddg-oracle-") for k in keys)]
            if busy and busy[0] in pids:
                time.sleep(0.3)                     # mid-task
                os.kill(pids[busy[0]], signal.SIGKILL)
                killed.append(busy[0])
            time.sleep(0.05)

    killer = threading.Thread(target=kill_a_busy_worker, daemon=True)
    killer.start()
    try:
        rc, remote, _ = _check(capsys, tmp_path, "remote", "--scheduler", cluster.scheduler_address)
    finally:
        killer.join(timeout=70)
    assert killed, "no worker was killed mid-run"
    assert rc == rc_local
    results = json.loads((remote / "results.json").read_text())["results"]
    assert all(r["status"] != "crashed" for r in results), [r for r in results if r["status"] == "crashed"]
    assert (remote / "results.json").read_bytes() == (local / "results.json").read_bytes()
    client.wait_for_workers(2, timeout=60)          # the nanny restarted it
    client.close()


def test_resume_finishes_a_run_on_a_local_cluster(capsys, tmp_path):
    rc_full, full, _ = _check(capsys, tmp_path, "full", "--workers", "1")
    rc, part, _ = _check(capsys, tmp_path, "part", "--scheduler", "local:2")
    lines = (part / "results.jsonl").read_text().splitlines()
    (part / "results.jsonl").write_text("\n".join(lines[:3]) + "\n")   # as if interrupted
    (part / "results.json").unlink()
    rc = main(["check", "--resume", str(part)])
    out, err = capsys.readouterr()
    assert rc == rc_full
    assert (part / "results.json").read_bytes() == (full / "results.json").read_bytes()


def test_a_bad_scheduler_address_is_a_usage_error(capsys):
    rc = main(["check", "--impl", "reference", "--only", "D1.6", "--scheduler", "local:zero"])
    _, err = capsys.readouterr()
    assert rc == 2 and "local:N" in err and err.count("\n") == 1
