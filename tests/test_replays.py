"""Replays that replay anywhere (issue 41, item 4): the reproduce.py that ``check --report``
writes runs from another directory for a user's module, an ``exec:`` program and a mesh
file, and raises the failure again; a pytest node id of a plugin item reruns that item."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

BUG = textwrap.dedent("""\
    class ClosedChi:
        name = "closed-chi"
        def euler_characteristic(self, V, F):
            return len(V) - (3 * len(F)) // 2 + len(F)      # assumes a closed surface
    """)


def _env():
    # no PYTHONPATH to the user's project: the replay must find it by itself
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PATH"] = os.path.dirname(sys.executable) + os.pathsep + env.get("PATH", "")
    return env


def _check(cwd, *args):
    # the console script, as a user runs it: unlike `python -m`, it does not put the
    # current directory on sys.path (the user's module is found by load_implementation)
    # one worker (was 2; only the two-property run below had two tasks for a pool): the
    # replay of the written reproduce.py is what these tests check, not the pool, and the
    # same report and snippet are written either way (workers do not change the examples)
    command = str(Path(sys.executable).with_name("ddg-oracle"))
    return subprocess.run([command, "check", *args, "--workers", "1"],
                          cwd=cwd, capture_output=True, text=True, env=_env(), timeout=300)


def _replay(report: Path, elsewhere: Path):
    scripts = sorted(report.glob("failures/*/reproduce.py"))
    assert scripts, sorted(p.name for p in report.glob("**/*"))
    return subprocess.run([sys.executable, str(scripts[0])], cwd=elsewhere, capture_output=True,
                          text=True, env=_env(), timeout=300)


def test_a_user_module_replays_from_another_directory(tmp_path):
    project, elsewhere = tmp_path / "project", tmp_path / "elsewhere"
    project.mkdir()
    elsewhere.mkdir()
    (project / "mygeom.py").write_text(BUG)
    out = _check(project, "--impl", "mygeom:ClosedChi", "--only", "D1.6", "R1.5",
                 "--report", str(tmp_path / "report"))
    assert out.returncode == 1, out.stdout + out.stderr
    again = _replay(tmp_path / "report", elsewhere)
    assert "No module named" not in again.stderr
    assert again.returncode != 0 and "PropertyFailure" in again.stderr, again.stderr[-2000:]


def test_an_exec_program_replays_from_another_directory(tmp_path):
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    spec = f"exec:{sys.executable} examples/exec_numpy_cotan.py SignError"
    out = _check(ROOT, "--impl", spec, "--only", "D3.1", "--report", str(tmp_path / "report"))
    assert out.returncode == 1, out.stdout + out.stderr
    again = _replay(tmp_path / "report", elsewhere)
    assert again.returncode != 0 and "PropertyFailure" in again.stderr, again.stderr[-2000:]


def test_a_mesh_file_failure_replays_from_another_directory(tmp_path):
    project, elsewhere = tmp_path / "project", tmp_path / "elsewhere"
    project.mkdir()
    elsewhere.mkdir()
    (project / "mygeom.py").write_text(BUG)
    (project / "disk.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n")
    out = _check(project, "--impl", "mygeom:ClosedChi", "--mesh", "disk.obj", "--only", "D1.6",
                 "--report", str(tmp_path / "report"))
    assert out.returncode == 1, out.stdout + out.stderr
    again = _replay(tmp_path / "report", elsewhere)
    # the file snippet runs the check on the mesh beside it, where the module loads from
    assert again.returncode == 1 and "wrong Euler characteristic" in again.stdout, \
        again.stdout[-2000:] + again.stderr[-2000:]


def test_a_plugin_node_id_reruns_its_item_alone(tmp_path):
    (tmp_path / "mygeom.py").write_text(BUG)
    (tmp_path / "test_own.py").write_text("def test_own():\n    assert True\n")
    env = {**_env(), "PYTHONPATH": str(tmp_path)}
    run = [sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-q", "-rf"]
    first = subprocess.run(run + ["--ddg-impl", "mygeom:ClosedChi", "--ddg-only", "D1.6",
                                  "--ddg-only", "X1.4"], cwd=tmp_path, capture_output=True,
                           text=True, env=env, timeout=300)
    failed = [line.split()[1] for line in first.stdout.splitlines() if line.startswith("FAILED ")]
    assert failed and all("ddg[mygeom:ClosedChi]" in f for f in failed), first.stdout
    again = subprocess.run(run + [failed[0]], cwd=tmp_path, capture_output=True, text=True,
                           env=env, timeout=300)
    assert again.returncode == 1, again.stdout + again.stderr
    assert "1 failed" in again.stdout and "passed" not in again.stdout.splitlines()[-1]


class ScaledDefects:
    """A constructor option the object keeps: with scale 2 its angle defects are twice the
    numpy example's (a bug); with the default 1 they are right."""
    name = "scaled-defects"

    def __init__(self, scale=1.0, label="plain"):
        self.scale, self._label = scale, label

    def angle_defects(self, V, F):
        from examples.numpy_mesh import NumpyMesh
        return self.scale * NumpyMesh().angle_defects(V, F)


def test_an_object_checked_in_process_replays_with_its_constructor_options():
    # check_implementation gets an object: its replay was load_implementation('module:Class'),
    # built without the options, and passed where the object had failed
    import pytest
    from ddg_oracle.application.implementations import load_implementation
    from ddg_oracle.properties.counterexample import replay
    from ddg_oracle.properties.registry import PropertyFailure
    from ddg_oracle.properties.runner import check_implementation
    with pytest.raises(AssertionError):
        check_implementation(ScaledDefects(scale=2.0), profile="ci", only={"D2.2"})
    from ddg_oracle.properties import PROPERTIES
    from ddg_oracle.properties.profiles import profile
    from ddg_oracle.properties.runner import run_property
    r = run_property(PROPERTIES["D2.2"], ScaledDefects(scale=2.0, label="mine"), profile("ci"))
    assert r.spec == "tests.test_replays:ScaledDefects(scale=2.0, label='mine')", r.spec
    again = load_implementation(r.spec)
    assert again.scale == 2.0 and again._label == "mine"
    with pytest.raises(PropertyFailure):
        replay("D2.2", again, r.replay)
