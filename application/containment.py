"""Every process a run starts ends with it: checked libraries, their children, exec drivers.

A checked library may start processes of its own (a worker pool, a helper binary), and an
isolated worker killed on a hang leaves an exec driver it started behind; such strays
would keep running (at 100% CPU for a hanging driver) after ``ddg-oracle`` has exited.
:func:`contained` wraps a command: the command's process becomes a *child subreaper*
(Linux ``prctl(PR_SET_CHILD_SUBREAPER)``, when it is ddg-oracle's own process), so an
orphaned descendant is re-parented to it instead of to init, and at the end of the block,
on every path (normal, error, signal), every descendant started inside it is stopped
(SIGTERM, then SIGKILL after a grace period) and reaped.  Descendants that existed before
the block (a test's browser, say) are left alone.
"""

from __future__ import annotations

import os
import signal
import time
from contextlib import contextmanager

__all__ = ["contained", "descendants", "kill_descendants", "become_subreaper", "stopped",
           "worker_context", "WorkerContext", "start_workers_from_a_forkserver",
           "forkserver_in_use", "PRELOAD", "LIBRARY_PRELOAD"]

PR_SET_CHILD_SUBREAPER = 36


def become_subreaper() -> bool:
    """Make this process the reaper of its orphaned descendants (Linux); False elsewhere."""
    try:
        import ctypes
        libc = ctypes.CDLL(None, use_errno=True)
        return libc.prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0) == 0
    except (OSError, AttributeError):
        return False


#: what a forkserver imports once for every worker it forks: a spawned worker imported them
#: itself (0.5 s of CPU each; a run starts 2 pool workers and, in each, an isolated worker per
#: library, a new one after every crash).  No checked library: importing one may start
#: threads, and a process holding threads must not fork.
PRELOAD = ("ddg_oracle.application.jobs", "ddg_oracle.application.isolation", "ddg_oracle.properties.registry",
           "ddg_oracle.properties.runner", "ddg_oracle.properties.strategies",
           "ddg_oracle.oracles.exact_reference", "scipy.sparse")
#: what a pool worker's forkserver imports: it forks isolated library workers only, which
#: import ``isolation`` (not the properties) and an adapter (numpy, scipy.sparse)
LIBRARY_PRELOAD = ("ddg_oracle.application.isolation", "ddg_oracle.protocol.arrays", "scipy.sparse")
_forkserver = False


def start_workers_from_a_forkserver(preload=PRELOAD) -> bool:
    """From now on, start this process's workers from a forkserver that imported
    ``preload`` (POSIX; False where there is none).  For ddg-oracle's own processes
    only: the preload list is the whole process's, and the forkserver keeps the
    environment it started with (:class:`WorkerContext` gives each worker its parent's)."""
    global _forkserver
    import multiprocessing as mp
    if "forkserver" in mp.get_all_start_methods():
        mp.set_forkserver_preload(list(preload))
        _forkserver = True
    return _forkserver


def worker_context() -> "WorkerContext":
    """The multiprocessing context our workers start from: a forkserver in ddg-oracle's own
    processes (:func:`start_workers_from_a_forkserver`), else spawn (never a plain fork of a
    process that may hold threads; a user's process keeps its multiprocessing state)."""
    import multiprocessing as mp
    return WorkerContext(mp.get_context("forkserver" if _forkserver else "spawn"))


class WorkerContext:
    """A multiprocessing context whose processes and pool workers start with the environment
    this process has when it starts them: a forkserver's children would have the one the
    forkserver started with (the database, memory and time limits are read from it)."""

    def __init__(self, ctx):
        self._ctx = ctx

    def __getattr__(self, name):
        return getattr(self._ctx, name)

    def Process(self, target, args=(), **kwargs):
        return self._ctx.Process(target=_in_environment, args=(dict(os.environ), target, args),
                                 **kwargs)

    def Pool(self, processes, initializer=None, initargs=()):
        return self._ctx.Pool(processes, _in_environment, (dict(os.environ), initializer, initargs))


def _in_environment(environ: dict, target, args):
    """``target(*args)`` in a worker, with its parent's environment ``environ``."""
    os.environ.clear()
    os.environ.update(environ)
    if target is not None:
        return target(*args)


def forkserver_in_use() -> bool:
    """Whether :func:`worker_context` is a forkserver here (passed on to pool workers)."""
    return _forkserver


def descendants(pid: int | None = None) -> list[int]:
    """Every process below ``pid`` (default: this one), children first, read from /proc
    (Linux; elsewhere an empty list)."""
    pid = os.getpid() if pid is None else pid
    children: dict[int, list[int]] = {}
    try:
        entries = os.listdir("/proc")
    except OSError:
        return []
    for entry in entries:
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat", "rb") as fh:
                fields = fh.read().rsplit(b")", 1)[1].split()
        except OSError:
            continue
        children.setdefault(int(fields[1]), []).append(int(entry))
    out, todo = [], list(children.get(pid, []))
    while todo:
        p = todo.pop(0)
        out.append(p)
        todo.extend(children.get(p, []))
    return out


def alive(pid: int) -> bool:
    """The process ``pid`` exists and is not a zombie (its /proc stat)."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as fh:
            return fh.read().rsplit(b")", 1)[1].split()[0] != b"Z"
    except OSError:
        return False


def stopped(pid: int) -> bool:
    """Whether the process is stopped (state T: SIGSTOP) or traced, from /proc (Linux)."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as fh:
            return fh.read().rsplit(b")", 1)[1].split()[0] in (b"T", b"t")
    except OSError:
        return False


def kill_descendants(grace: float = 1.0, keep=frozenset()) -> int:
    """SIGTERM every descendant process but ``keep``, then SIGKILL those still there after
    ``grace`` s, and reap those that are our children; returns how many were stopped.
    multiprocessing's resource tracker and forkserver are kept: they end by themselves when
    this process exits; killed before, this process's exit handlers would start a new
    tracker that prints a traceback for every semaphore they release."""
    keep = set(keep)
    tracker = _resource_tracker()
    if tracker is not None and not stopped(tracker):
        # (a stopped tracker would never end: this process's exit waits for it)
        keep.add(tracker)
    server = _forkserver_pid()
    if server is not None and not stopped(server):
        # multiprocessing's forkserver too: it ends when this process exits, and killed
        # (and reaped here) the next worker's start in this process fails on its waitpid
        keep.add(server)
    procs = [p for p in descendants() if p not in keep]
    for p in procs:
        try:
            os.kill(p, signal.SIGTERM)
        except OSError:
            pass
    deadline = time.monotonic() + grace
    while time.monotonic() < deadline and any(alive(p) for p in procs):
        time.sleep(0.05)
    for p in procs + [q for q in descendants() if q not in keep and q not in procs]:
        try:
            os.kill(p, signal.SIGKILL)
        except OSError:
            pass
    _reap(procs)
    return len(procs)


def _resource_tracker() -> int | None:
    """The pid of multiprocessing's resource tracker process, if this process started one."""
    import sys
    module = sys.modules.get("multiprocessing.resource_tracker")
    return getattr(getattr(module, "_resource_tracker", None), "_pid", None)


def _forkserver_pid() -> int | None:
    """The pid of multiprocessing's forkserver, if this process started one."""
    import sys
    module = sys.modules.get("multiprocessing.forkserver")
    return getattr(getattr(module, "_forkserver", None), "_forkserver_pid", None)


def _reap(pids) -> None:
    """Collect the exit status of those of ``pids`` that are our (adopted) children."""
    deadline = time.monotonic() + 2.0
    for p in pids:
        while True:
            try:
                done, _ = os.waitpid(p, os.WNOHANG)
            except ChildProcessError:
                break                         # not our child, or already reaped
            if done or time.monotonic() > deadline:
                break
            time.sleep(0.01)


@contextmanager
def contained(subreaper: bool = False):
    """Run the block, then stop every descendant process it started (see the module doc);
    ``subreaper``: adopt orphaned descendants first (ddg-oracle's own process only: it
    changes how this process is treated by the kernel)."""
    if subreaper:
        become_subreaper()
    before = frozenset(descendants())
    try:
        yield
    finally:
        kill_descendants(grace=0.5, keep=before)
