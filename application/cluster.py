"""A check's tasks on a ``dask.distributed`` cluster: ``ddg-oracle check --scheduler ADDRESS``.

``ADDRESS`` is a running scheduler (``tcp://host:8786``, what ``dask scheduler``
prints) or ``local:N``: a :class:`distributed.LocalCluster` of N worker
processes started for this run and stopped after it.  The tasks are the same
as a local run's (:class:`~ddg_oracle.application.jobs.Task`: implementation x property, or
implementation x mesh file) and run the same way inside a worker
(:func:`~ddg_oracle.application.jobs.run_task`: the reference in the worker process, every
other library isolated in a process of its own, a crash or hang of it a
result).  So the results are the local run's: a property's examples depend
only on the property, the profile and the seed (``properties/stream.py``),
under ``ci`` results.json is byte-identical to the local run's.

What the cluster adds:

* a worker that dies (killed, out of memory, its machine gone) loses no
  result: the scheduler runs its unfinished tasks again on another worker; a
  task that has killed :data:`ALLOWED_FAILURES` + 1 workers is reported as
  ``crashed`` with the task named, and the run goes on;
* with ``--report DIR`` each finished task is written to ``DIR/results.jsonl``
  as it arrives, so ``ddg-oracle check --resume DIR`` continues an interrupted
  run (locally or on a cluster) with only the unfinished tasks.

Workers need ddg-oracle and the checked libraries installed (the same
versions as the client), their worker processes must be allowed children
(``DASK_DISTRIBUTED__WORKER__DAEMON=False`` in the environment of
``dask worker``: a library runs in a child process), one thread per worker
process (``--nthreads 1``: a property's example time limit uses SIGALRM of
the main thread; in another thread it is skipped and only the libraries' own
call limits apply), and a user's ``module:object`` must import from the
worker's working directory.  A check of a cluster that breaks these is a
usage error, said before any task runs.
"""

from __future__ import annotations

import uuid

from ..reference.errors import InputError

LOCAL_PREFIX = "local:"
#: worker deaths a task may cause before it is reported as crashed (dask's own setting,
#: ``distributed.scheduler.allowed-failures``, for the clusters this module starts)
ALLOWED_FAILURES = 2


def _distributed():
    try:
        import dask
        import distributed
    except ImportError:
        raise InputError("--scheduler needs dask.distributed: pip install 'ddg-oracle[dask]'") \
            from None
    return dask, distributed


def connect(address: str):
    """(client, cluster or None) for ``address`` (see the module doc)."""
    n = None
    if address.startswith(LOCAL_PREFIX):
        try:
            n = int(address[len(LOCAL_PREFIX):])
        except ValueError:
            n = 0
        if n < 1:
            raise InputError(f"--scheduler {address}: write local:N with N >= 1 worker processes")
    dask, distributed = _distributed()
    cluster = None
    if n is not None:
        import logging
        # set for the rest of this process, not for a block: the cluster's nannies live
        # here and read the daemon flag again whenever they restart a worker that died
        dask.config.set({"distributed.worker.daemon": False,
                         "distributed.scheduler.allowed-failures": ALLOWED_FAILURES})
        # CRITICAL, not ERROR: a worker whose heartbeat meets the scheduler closing at the
        # end of a run (a loaded machine) logs "Stream is closed" with a traceback; what a
        # run reports (results, lost workers) is ours, never read from dask's logs
        cluster = distributed.LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                           dashboard_address=":0",
                                           silence_logs=logging.CRITICAL)
        client = distributed.Client(cluster)
    else:
        client = _client(distributed, address)
    try:
        _require_usable(client, address)
    except BaseException:
        close(client, cluster)
        raise
    return client, cluster


#: seconds to wait for a scheduler's answer before --scheduler is a usage error
SCHEDULER_TIMEOUT = 30.0


def _client(distributed, address: str):
    """A client of the scheduler at ``address``, or an InputError in one line: an address
    that is not one, nothing listening, or something listening that does not answer as a
    dask scheduler within SCHEDULER_TIMEOUT (dask's own connect timeout covers only the
    first of these, and a silent port would hang forever)."""
    import threading
    _refuse_a_closed_port(address)
    got: list = []

    def connect():
        try:
            got.append(distributed.Client(address, timeout=SCHEDULER_TIMEOUT))
        except BaseException as e:  # noqa: BLE001  (handed to the caller below)
            got.append(e)
    # a daemon thread: a scheduler that never answers must not keep the process alive
    thread = threading.Thread(target=connect, daemon=True, name="ddg-oracle-scheduler")
    thread.start()
    # dask's own error, if it comes within a little longer, is the more precise message
    thread.join(SCHEDULER_TIMEOUT + min(5.0, SCHEDULER_TIMEOUT))
    if not got:
        raise InputError(f"--scheduler {address}: no dask scheduler answered within "
                         f"{SCHEDULER_TIMEOUT:g} s")
    if isinstance(got[0], (OSError, TimeoutError, ValueError, TypeError)):
        raise InputError(f"--scheduler {address}: cannot reach a dask scheduler there "
                         f"({got[0]})")
    if isinstance(got[0], BaseException):
        raise got[0]
    return got[0]


def _refuse_a_closed_port(address: str) -> None:
    """A tcp address where nothing listens is an InputError at once: dask's client retries
    a refused connection for its whole timeout (30 s for a typo in a port number)."""
    import socket
    from urllib.parse import urlsplit
    try:
        parts = urlsplit(address if "://" in address else "tcp://" + address)
        host, port = parts.hostname, parts.port
    except ValueError:
        return                          # not an address we can read: dask says what it is
    if parts.scheme != "tcp" or not host or port is None:
        return
    try:
        socket.create_connection((host, port), timeout=5).close()
    except ConnectionRefusedError as e:
        raise InputError(f"--scheduler {address}: cannot reach a dask scheduler there "
                         f"(nothing listens: {e.strerror})") from None
    except OSError:
        return                          # unresolvable, filtered, slow: dask's timeout decides


def _worker_facts():
    import multiprocessing
    return {"daemon": multiprocessing.current_process().daemon}


def _require_usable(client, address: str) -> None:
    info = client.scheduler_info()["workers"]
    if not info:
        client.wait_for_workers(1, timeout=60)
        info = client.scheduler_info()["workers"]
    bad = [w for w, facts in client.run(_worker_facts).items() if facts["daemon"]]
    if bad:
        raise InputError(f"--scheduler {address}: worker {bad[0]} runs as a daemonic process, "
                         "which may not start the libraries' processes; start the workers with "
                         "DASK_DISTRIBUTED__WORKER__DAEMON=False")
    threads = {w: i.get("nthreads", 1) for w, i in info.items()}
    many = [w for w, k in threads.items() if k != 1]
    if many:
        raise InputError(f"--scheduler {address}: worker {many[0]} has {threads[many[0]]} "
                         "threads; start workers with --nthreads 1 (one task per process)")


def close(client, cluster) -> None:
    import logging
    # the client's own heartbeats and comms may log the closing streams as errors too
    log = logging.getLogger("distributed")
    level = log.level
    log.setLevel(logging.CRITICAL)
    try:
        client.close()
    finally:
        try:
            if cluster is not None:
                cluster.close()
        finally:
            log.setLevel(level)


def n_workers(client) -> int:
    return len(client.scheduler_info()["workers"])


# --- in a worker ----------------------------------------------------------------------------------


def _run(run, task):
    """One task in a dask worker: the run's options and meshes (``run``: token, options,
    meshes, sent once per worker) installed in this process when the run changes."""
    from . import jobs
    token, options, meshes = run
    jobs.install(options, meshes, run=token)
    return jobs.run_task(task)


# --- in the client --------------------------------------------------------------------------------


def map_on_cluster(client, fn, shared, items, finish, check=lambda: None) -> None:
    """``fn(shared, item)`` for every item on ``client``'s cluster (``shared`` sent once per
    worker); ``finish(k, result, error)`` as each arrives, in any order: ``error`` is None,
    or why the cluster could not finish item ``k`` (its workers died
    :data:`ALLOWED_FAILURES` + 1 times, or ``fn`` raised); ``check()`` at least twice a
    second (raise there, or on a signal, to stop: the unfinished items are cancelled)."""
    from distributed import wait

    token = uuid.uuid4().hex
    [run] = client.scatter([shared], broadcast=True)
    index = {}
    for k, item in enumerate(items):
        f = client.submit(fn, run, item, key=f"ddg-oracle-{token}-{k}", pure=False)
        index[f] = k
    remaining = set(index)
    try:
        while remaining:
            check()
            try:
                done, _ = wait(list(remaining), timeout=0.5, return_when="FIRST_COMPLETED")
            except TimeoutError:
                continue
            for f in done:
                remaining.discard(f)
                try:
                    result, error = f.result(), None
                except Exception as e:  # noqa: BLE001  (KilledWorker: a result, the run goes on)
                    result, error = None, (
                        f"the cluster could not finish this task ({type(e).__name__}: {e}); a "
                        f"task is run again when its worker dies, {ALLOWED_FAILURES} times at most")
                finish(index[f], result, error)
                f.release()
    except BaseException:
        client.cancel(list(remaining))
        raise


def run_on_cluster(client, tasks, todo, options, meshes, finish, check) -> None:
    """Run the tasks ``todo`` (indices into ``tasks``) on ``client``'s cluster; ``finish(k,
    results)`` as each arrives (any order), ``check()`` at least twice a second (raises on
    SIGINT or SIGTERM: the unfinished tasks are cancelled)."""
    from . import jobs

    def arrived(i, results, error):
        k = todo[i]
        finish(k, jobs.crashed(tasks[k], error) if error is not None else results)
    map_on_cluster(client, _run, (uuid.uuid4().hex, options, meshes), [tasks[k] for k in todo],
                   arrived, check)
