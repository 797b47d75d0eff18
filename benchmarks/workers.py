"""How long one of our workers takes to start and answer: spawned (a user's process) against
forked from the preloaded forkserver (the ddg-oracle command), alternating in one process,
median of 10 each, wall milliseconds.  ``python -m benchmarks.workers``."""

import statistics
import time

from ddg_oracle.application import containment


def _ready(conn) -> None:
    """A worker's start: what a pool worker needs imported, then one message."""
    import ddg_oracle.application.isolation  # noqa: F401
    import ddg_oracle.properties.registry  # noqa: F401
    conn.send(1)
    conn.close()


def _once(ctx) -> float:
    parent, child = ctx.Pipe()
    t = time.perf_counter()
    p = ctx.Process(target=_ready, args=(child,))
    p.start()
    child.close()
    parent.recv()
    seconds = time.perf_counter() - t
    p.join()
    return seconds


def main() -> None:
    spawn = containment.worker_context()            # before the command's switch: spawn
    containment.start_workers_from_a_forkserver()
    fork = containment.worker_context()
    first = _once(fork)                             # starts the forkserver
    spawned, forked = [], []
    for _ in range(10):
        spawned.append(_once(spawn))
        forked.append(_once(fork))
    print(f"spawn median {statistics.median(spawned) * 1000:.0f} ms; forkserver median "
          f"{statistics.median(forked) * 1000:.0f} ms (its first worker, the server's start "
          f"included: {first * 1000:.0f} ms)")


if __name__ == "__main__":
    main()
