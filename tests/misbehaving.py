"""Implementations that crash the interpreter or never return, on some inputs.

Used to show that a check run reports them and goes on (issues 6 and 8).
"""

import ctypes
import os

from ddg_oracle.oracles.exact_reference import ReferenceImplementation


def _has_boundary(F) -> bool:
    from collections import Counter
    count = Counter(tuple(sorted((int(f[i]), int(f[(i + 1) % 3])))) for f in F for i in range(3))
    return any(c == 1 for c in count.values())


class SegfaultsOnBoundary(ReferenceImplementation):
    name = "segfaults-on-boundary"

    def euler_characteristic(self, V, F):
        if _has_boundary(F):
            ctypes.string_at(0)          # reads address 0: SIGSEGV
        return super().euler_characteristic(V, F)


class AbortsAlways(ReferenceImplementation):
    name = "aborts"

    def euler_characteristic(self, V, F):
        os.abort()


class AssertsInC(ReferenceImplementation):
    """Like a C++ library's failed assert: a message on stderr (fd 2, not sys.stderr), then
    abort."""
    name = "asserts-in-c"

    def euler_characteristic(self, V, F):
        os.write(2, b"mesh.cpp:42: int Mesh::euler(): Assertion `halfedges.valid()' failed.\n")
        os.abort()


class HangsOnBoundary(ReferenceImplementation):
    name = "hangs-on-boundary"

    def euler_characteristic(self, V, F):
        while _has_boundary(F):
            pass
        return super().euler_characteristic(V, F)


class Hangs(ReferenceImplementation):
    """Its Laplacian never returns: a check must never call that a pass."""
    name = "hangs"

    def cotan_laplacian(self, V, F):
        import time
        while True:
            time.sleep(0.05)


class AllocatesOnBoundary(ReferenceImplementation):
    """Asks for 2 GiB of address space on meshes with boundary.

    ``numpy.empty`` maps the memory without touching it, so without a limit the
    call would succeed cheaply; under a smaller ``Isolated(memory=...)`` the
    allocation itself fails.
    """
    name = "allocates-on-boundary"

    def euler_characteristic(self, V, F):
        if _has_boundary(F):
            import numpy as np
            np.empty(2 << 30, dtype=np.uint8)
        return super().euler_characteristic(V, F)


class TakesTwoSeconds(ReferenceImplementation):
    name = "takes-two-seconds"

    def euler_characteristic(self, V, F):
        import time
        time.sleep(2.0)
        return super().euler_characteristic(V, F)


class SlowChi(ReferenceImplementation):
    """The reference, 20 ms per Euler characteristic: a task that is still running when a
    cluster worker is killed (tests/test_cluster.py: 64 calls, 1.3 s slept, in a run of its
    three properties)."""

    name = "slow-chi"

    def euler_characteristic(self, V, F):
        import time
        time.sleep(0.02)
        return super().euler_characteristic(V, F)


class LoadsSlowly(ReferenceImplementation):
    """The reference, 0.3 s to construct: a worker still loading when an alarm rings, however
    fast the worker process itself starts (forked from a preloaded forkserver, in ms)."""

    name = "loads-slowly"

    def __init__(self):
        import time
        time.sleep(0.3)
        super().__init__()
