"""Isolation: a crashing or looping implementation is reported with its input; the run goes on."""

import numpy as np
import pytest
from hypothesis import Phase, settings

from ddg_oracle.application.isolation import ImplementationCrashed, Isolated, memory_limit
from ddg_oracle.properties import PROPERTIES
from ddg_oracle.protocol.budget import BUDGETS
from ddg_oracle.properties.runner import CRASHED, PASSED, run_property
from ddg_oracle.reference import surfaces
from ddg_oracle.reference.errors import InputError

CLOSED = surfaces.tetrahedron().to_arrays()
OPEN = surfaces.disk(5).to_arrays()
QUICK = settings(max_examples=15, deadline=None, database=None, derandomize=True)


def _arrays(mesh):
    V, F = mesh
    return np.array(V, dtype=float), np.array(F, dtype=np.int64)


def test_segfault_is_reported_and_the_worker_restarts():
    with Isolated("tests.misbehaving:SegfaultsOnBoundary", timeout=30) as impl:
        assert impl.euler_characteristic(*_arrays(CLOSED)) == 2
        with pytest.raises(ImplementationCrashed, match="SIGSEGV"):
            impl.euler_characteristic(*_arrays(OPEN))
        assert impl.euler_characteristic(*_arrays(CLOSED)) == 2      # restarted


def test_abort_is_reported():
    with Isolated("tests.misbehaving:AbortsAlways", timeout=30) as impl:
        with pytest.raises(ImplementationCrashed, match="SIGABRT"):
            impl.euler_characteristic(*_arrays(CLOSED))


def test_a_crash_reports_what_the_library_printed_before_dying():
    with Isolated("tests.misbehaving:AssertsInC", timeout=30) as impl:
        with pytest.raises(ImplementationCrashed) as err:
            impl.euler_characteristic(*_arrays(CLOSED))
        assert "SIGABRT" in str(err.value)
        assert "it printed: mesh.cpp:42: int Mesh::euler(): Assertion" in str(err.value)
        path = impl._stderr
    import os
    assert not os.path.exists(path)                 # closed: its stderr file is gone


def test_hang_is_killed_after_the_time_limit():
    # 0.75 s (was 1.5): the hang busy-loops until killed, so its CPU is the limit; any limit
    # is reported by the same message, and the call after the restart (a tetrahedron's
    # euler_characteristic, milliseconds) still has a wide margin on a loaded machine
    from ddg_oracle.properties.runner import _crash_text
    with Isolated("tests.misbehaving:HangsOnBoundary", timeout=0.75) as impl:
        with pytest.raises(ImplementationCrashed, match="did not return within 0.75 s") as e:
            impl.euler_characteristic(*_arrays(OPEN))
        assert impl.euler_characteristic(*_arrays(CLOSED)) == 2
    # reported as the hang it is, as a call the task's budget stops is (not as a class path)
    assert _crash_text(e.value).startswith("hang: hangs-on-boundary.euler_characteristic did not")


def test_an_exception_of_the_implementation_reads_as_its_own_not_our_wrapper():
    """An isolated call that raised: "lib.method raised ValueError: ..." is the news; our
    wrapper's class path before it (ddg_oracle.application.isolation.ImplementationError)
    was noise in every crash line."""
    from ddg_oracle.application.isolation import ImplementationError
    from ddg_oracle.properties.runner import _crash_text
    e = ImplementationError("libigl.genus raised ValueError: odd 2 - chi - k")
    assert _crash_text(e) == "libigl.genus raised ValueError: odd 2 - chi - k"
    assert _crash_text(ValueError("x")) == "ValueError: x"        # a raw exception: its type


def test_the_time_limit_grows_with_the_mesh():
    # 1 s per 10,000 faces: a 2-second call is killed on a small mesh, not on 40,000 faces
    big = _arrays(surfaces.grid(100, 200).to_arrays())
    assert len(big[1]) == 40_000
    with Isolated("tests.misbehaving:TakesTwoSeconds", timeout=1.0) as impl:
        with pytest.raises(ImplementationCrashed, match=r"did not return within 1 s \(killed\)"):
            impl.euler_characteristic(*_arrays(CLOSED))
        assert impl.euler_characteristic(*big) == 1
    with Isolated("tests.misbehaving:TakesTwoSeconds", timeout=0.25) as impl:
        with pytest.raises(ImplementationCrashed, match=r"within 1 s \(0.25 s per 10,000 faces\)"):
            impl.euler_characteristic(*big)


def test_property_run_reports_the_crash_with_a_shrunk_input_and_goes_on():
    with Isolated("tests.misbehaving:SegfaultsOnBoundary", timeout=30) as impl:
        # the default profile's budget: a crash restarts the worker, so shrinking stops
        # after 6 crash outcomes (unbounded, it took 17 s for the same bound below)
        r = run_property(PROPERTIES["D1.6"], impl, QUICK, budget=BUDGETS["default"])
        assert r.status == CRASHED and "SIGSEGV" in r.error
        faces = r.example.triangulation.n_faces
        assert r.example.expected.boundary_components >= 1
        assert faces <= 40, f"crashing input not shrunk: {faces} faces"
        # the same worker goes on to pass a property that only sees closed surfaces
        r2 = run_property(PROPERTIES["X1.4"], impl, QUICK)
        assert r2.status in (CRASHED, PASSED)
        assert run_property(PROPERTIES["T1.1 / C1.2"], impl, QUICK).status == PASSED


def test_memory_limit_is_reported_and_the_worker_restarts():
    # 1 GiB of address space: the worker needs ~170 MiB, the call asks for 2 GiB more
    with Isolated("tests.misbehaving:AllocatesOnBoundary", timeout=30, memory=1 << 30) as impl:
        assert impl.euler_characteristic(*_arrays(CLOSED)) == 2
        with pytest.raises(ImplementationCrashed,
                           match=r"ran out of memory under the limit of 1 GiB .*DDG_MEMORY_LIMIT"):
            impl.euler_characteristic(*_arrays(OPEN))
        assert impl.euler_characteristic(*_arrays(CLOSED)) == 2      # restarted


def test_property_run_reports_memory_exhaustion_with_its_input_and_goes_on():
    with Isolated("tests.misbehaving:AllocatesOnBoundary", timeout=30, memory=1 << 30) as impl:
        # no shrink phase: every shrink step that crashes restarts the worker, and this test
        # asserts the verdict and that the reported input has a boundary, not its size (the
        # first crashing example has one as much as the shrunk one; shrinking is asserted by
        # test_property_run_reports_the_crash_with_a_shrunk_input_and_goes_on)
        unshrunk = settings(QUICK, phases=[Phase.explicit, Phase.reuse, Phase.generate])
        r = run_property(PROPERTIES["D1.6"], impl, unshrunk, budget=BUDGETS["default"])
        assert r.status == CRASHED and "ran out of memory" in r.error
        assert r.example.expected.boundary_components >= 1            # the input that did it
        assert run_property(PROPERTIES["T1.1 / C1.2"], impl, QUICK).status == PASSED


def test_memory_limit_setting(monkeypatch):
    assert memory_limit("512M") == 512 << 20 and memory_limit("none") is None
    monkeypatch.setenv("DDG_MEMORY_LIMIT", "2G")
    assert memory_limit() == 2 << 30
    with pytest.raises(InputError, match="positive size such as 4G"):
        memory_limit("lots")
    with pytest.raises(InputError, match="DDG_MEMORY_LIMIT"):
        memory_limit("-1G")


def test_an_answer_interrupted_mid_read_is_never_read_as_the_next_calls():
    # the task budget's alarm can fire after the worker answered and before the answer is
    # read: that worker is abandoned, not asked again (its stale answer came back as the next
    # example's in a fresh-clone main job: 4 values for a 206-vertex mesh)
    pytest.importorskip("igl")
    from ddg_oracle.reference import surfaces

    class InterruptedOnce:
        def __init__(self, conn):
            self.conn, self.fired = conn, False

        def recv(self):
            if not self.fired:
                self.fired = True
                raise KeyboardInterrupt
            return self.conn.recv()

        def __getattr__(self, name):
            return getattr(self.conn, name)

    tet = [np.array(a) for a in surfaces.tetrahedron().to_arrays()]
    octa = [np.array(a) for a in surfaces.octahedron().to_arrays()]
    with Isolated("libigl", timeout=60) as impl:
        impl._conn = InterruptedOnce(impl._conn)
        with pytest.raises(KeyboardInterrupt):
            impl.angle_defects(*tet)
        assert len(impl.angle_defects(*octa)) == 6
        assert len(impl.angle_defects(*tet)) == 4


def test_a_worker_start_interrupted_never_answers_the_next_call():
    """The false alarm: a worker replaced (after a crash) while the task budget's alarm
    rang left its "ready" message in the pipe; the next call read it as its answer and
    every later call the answer of the call before (a tetrahedron's genus 1,
    non-orientable: FAILED on a correct implementation).  Now the half-started worker is
    killed and the next call starts a fresh one."""
    from tests.alarms import interrupted

    with Isolated("tests.misbehaving:LoadsSlowly", timeout=30) as impl:
        interrupted(impl._start, 0.05)      # loading takes longer than that
        V, F = _arrays(CLOSED)
        assert impl.euler_characteristic(V, F) == 2
        assert impl.genus(V, F) == 0 and impl.is_orientable(V, F) is True
