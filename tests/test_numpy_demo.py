"""Issue 5's promise: a cotan Laplacian written the obvious way in numpy is checked with one
line of test code or one command, and the usual bugs in it are caught on a triangle or two."""

import subprocess
import sys
from pathlib import Path

import pytest

from examples.numpy_cotan import (AbsoluteThreshold, BoundaryWithoutHalf, NumpyCotan, SignError,
                                  WrongCorner)
from ddg_oracle.properties import check_implementation
from ddg_oracle.properties.profiles import profile
from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.runner import FAILED, PASSED, TIE, run_property

ROOT = Path(__file__).resolve().parent.parent


def test_the_obvious_numpy_implementation_passes_in_one_line():
    results = check_implementation(NumpyCotan())            # raises on any failure
    # a tie (rounding decided: a face beyond float resolution) is not a failure
    ran = [r for r in results if r.status in (PASSED, TIE)]
    assert {"D3.1", "T3.6", "T3.9", "E3.12", "P4.10", "L4.18"} <= {r.property_id for r in ran}


@pytest.mark.parametrize("bug, pids", [
    (SignError, ["D3.1", "T3.6", "L4.18"]),
    (BoundaryWithoutHalf, ["D3.1", "T3.9"]),
    (WrongCorner, ["D3.1", "E3.12"]),
    (AbsoluteThreshold, ["D3.1"]),                          # on a mesh scaled by 2**-64
])
def test_each_planted_bug_is_caught_with_a_counterexample_of_a_few_faces(bug, pids):
    for pid in pids:
        r = run_property(PROPERTIES[pid], bug(), profile("ci"))
        assert r.status == FAILED, f"{bug.name} not caught by {pid}"
        V, F = r.failure.mesh
        assert len(F) <= 2, f"{pid}: counterexample of {len(F)} faces"
        assert r.failure.expected != r.failure.observed


def _run(*args):
    return subprocess.run([sys.executable, "-m", *args], cwd=ROOT, capture_output=True, text=True,
                          timeout=600)


def test_one_command_finds_the_wrong_corner():
    out = _run("ddg_oracle.application.cli", "check", "--impl", "examples.numpy_cotan:WrongCorner",
               "--only", "D3.1", "--profile", "ci")
    assert out.returncode == 1, out.stdout + out.stderr
    assert "[D3.1] numpy-cotan-wrong-corner" in out.stdout
    assert "mesh: 3 vertices, 1 faces" in out.stdout        # shrunk to one triangle


def test_the_pytest_plugin_checks_it_in_the_users_ci(tmp_path):
    out = subprocess.run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-q",
                          "--ddg-impl", "examples.numpy_cotan:BoundaryWithoutHalf",
                          "--ddg-only", "D3.1", "--ddg-only", "T3.6", "--ddg-profile", "ci"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=600,
                         env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
    assert out.returncode == 1, out.stdout + out.stderr
    assert "2 failed" in out.stdout                         # D3.1 and T3.6 both see it
    assert "[D3.1] numpy-cotan-boundary-without-half" in out.stdout
