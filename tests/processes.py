"""Which processes of a run are its pool workers, read from /proc (Linux), whether they
were spawned (an in-process run: a user's process) or forked from the command's
forkserver (``ddg-oracle``'s own process)."""

from pathlib import Path


def parent(pid: int) -> int:
    try:
        return int(Path(f"/proc/{pid}/stat").read_bytes().rsplit(b")", 1)[1].split()[1])
    except OSError:
        return -1


def cmdline(pid: int) -> bytes:
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes()
    except OSError:
        return b""


def _children(pid: int) -> list[int]:
    return [int(e.name) for e in Path("/proc").iterdir()
            if e.name.isdigit() and parent(int(e.name)) == pid]


def pool_workers(pid: int) -> list[int]:
    """The pool workers of the run whose process is ``pid``: its spawned children, or the
    children of its forkserver (multiprocessing's resource tracker is neither)."""
    out = []
    for child in _children(pid):
        line = cmdline(child)
        if b"resource_tracker" in line:
            continue
        if b"spawn_main" in line:
            out.append(child)
        elif b"forkserver" in line:
            out.extend(_children(child))
    return out


def report_environment(conn, name: str) -> None:
    """A worker's target: send back its value of the environment variable ``name`` and
    whether it has the properties imported already (forked from a preloaded forkserver)."""
    import os
    import sys
    conn.send((os.environ.get(name), "ddg_oracle.properties.registry" in sys.modules))
    conn.close()
