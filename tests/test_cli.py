"""`ddg-oracle check` and `ddg-oracle compare`: options, exit codes, the report, determinism,
one-line errors for bad mesh files."""

import contextlib
import io
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from ddg_oracle.application.cli import Progress, main
from ddg_oracle.oracles.exact_reference import ReferenceImplementation
from ddg_oracle.application.meshfiles import read_mesh, write_obj
from ddg_oracle.application.causes import element_ids
from ddg_oracle.application.report import jsonable
from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.runner import CONVENTION, FAILED, PASSED, TIE, run_on_example, run_property
from ddg_oracle.reference import surfaces

ROOT = Path(__file__).resolve().parent.parent


class RoundsFlatVertices(ReferenceImplementation):
    """The exact angle defects, but an exactly flat vertex gets the float sum's noise
    (4 ulp of 2 pi): a tie decided otherwise within rounding, not an error."""

    name = "rounds-flat-vertices"

    def angle_defects(self, V, F):
        K = super().angle_defects(V, F)
        return np.where(K == 0, 4 * np.spacing(2 * np.pi), K)


class FlatVerticesCurved(ReferenceImplementation):
    """Flat vertices get K = 1e-3: far beyond rounding, a real error."""

    name = "flat-vertices-curved"

    def angle_defects(self, V, F):
        K = super().angle_defects(V, F)
        return np.where(K == 0, 1e-3, K)


def _run(capsys, *argv):
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


# --- exit codes and the table ---------------------------------------------------------------------


def test_check_passes_with_exit_0_and_prints_the_table(capsys):
    rc, out, _ = _run(capsys, "check", "--impl", "reference", "--only", "D1.6", "--only", "L2.4",
                      "--workers", "1", "--wide")
    assert rc == 0
    assert re.search(r"^property\s+reference$", out, re.M)
    assert re.search(r"^D1\.6 \(euler_characteristic_of_known_surfaces\)\s+passed \(\d+ examples\)",
                     out, re.M)
    assert "2 checks in" in out and "2 passed" in out


def test_failure_gives_exit_1_and_the_counterexample(capsys):
    rc, out, _ = _run(capsys, "check", "--impl", "tests.planted_bugs:ChiIgnoresBoundary",
                      "--only", "D1.6", "--workers", "1")
    assert rc == 1
    # the root cause first (the method blamed), then the property's row
    assert re.search(r"^FAILED \(1\): 1 root cause\nchi-ignores-boundary: euler_characteristic "
                     r"is wrong, 1 property fails(.*\n)*?  D1\.6 +chi-ignores-boundary +wrong "
                     r"Euler characteristic$", out, re.M)
    assert "expected: " in out and "observed: " in out and "mesh: " in out


@pytest.mark.parametrize("argv", [
    ["check", "--workers", "0"],
    ["check", "--profile", "nope"],
    ["check", "--impl", "reference", "--only", "Z9.9"],
    ["check", "--impl", "libigl(boundary=sideways)"],
    ["check", "--impl", "libigl(boundary)"],
    ["compare", "no/such/mesh.obj"],
])
def test_bad_usage_is_one_line_and_exit_2(capsys, argv):
    rc, out, err = _run(capsys, *argv)
    assert rc == 2
    assert err.startswith("ddg-oracle: error:") and err.count("\n") == 1, err


# --- tie disagreements and conventions ------------------------------------------------------------


def test_a_tie_decided_within_rounding_is_a_tie_disagreement_not_a_failure():
    from hypothesis import settings
    quick = settings(max_examples=40, deadline=None, database=None, derandomize=True)
    r = run_property(PROPERTIES["L2.4"], RoundsFlatVertices(), quick)
    assert r.status == TIE and r.ok and 0 < r.ties <= r.examples
    assert r.failure.expected == 0.0 and r.failure.observed > 0
    assert r.failure.error_in_bounds < 1
    assert len(r.mesh[1]) == 3                     # shrunk: the smallest star of a vertex
    worse = run_property(PROPERTIES["L2.4"], FlatVerticesCurved(), quick)
    assert worse.status == FAILED and not worse.ok
    assert worse.failure.error_in_bounds > 1


def test_without_the_shrink_phase_a_tie_is_not_searched_twice():
    """The tie's second pass exists to shrink it: without the shrink phase it would only
    replay examples the first pass ran (each of them a call of the implementation)."""
    from hypothesis import Phase, settings
    calls = []

    class Counted(RoundsFlatVertices):
        def angle_defects(self, V, F):
            calls.append(len(F))
            return super().angle_defects(V, F)
    quick = settings(max_examples=40, deadline=None, database=None, derandomize=True,
                     phases=(Phase.explicit, Phase.generate))
    r = run_property(PROPERTIES["L2.4"], Counted(), quick)
    assert r.status == TIE and r.ties > 0
    assert len(calls) == r.examples                # one call per example: one pass


def test_tie_disagreement_keeps_exit_0(capsys):
    rc, out, _ = _run(capsys, "check", "--impl", "tests.test_cli:RoundsFlatVertices",
                      "--only", "L2.4", "--profile", "ci", "--workers", "1", "--wide")
    assert rc == 0
    assert re.search(r"^L2\.4 .*tie disagreement \(\d+/60\)$", out, re.M)
    assert "tie disagreement: exactly flat vertex" in out


def test_expect_conventions_turns_a_documented_convention_into_an_expected_result(capsys):
    argv = ["check", "--impl", "libigl(boundary=library)", "--only", "R2.4", "--only", "D2.2",
            "--profile", "ci", "--workers", "1", "--wide"]
    rc, out, _ = _run(capsys, *argv)
    assert rc == 1 and re.search(r"^R2\.4 .*FAILED$", out, re.M)
    rc, out, _ = _run(capsys, *argv, "--expect-conventions")
    assert rc == 0
    assert re.search(r"^R2\.4 .*convention$", out, re.M)
    assert re.search(r"^D2\.2 .*passed", out, re.M)
    assert "documented convention F-libigl-2" in out and "libigl passes the same example" in out


def test_conventions_are_declared_by_the_implementation_itself():
    from ddg_oracle.application.implementations import load_implementation
    from ddg_oracle.protocol.methods import NotAnImplementation, declared_conventions
    assert declared_conventions(load_implementation("libigl(boundary=library)"))[0] == "libigl"
    assert declared_conventions(load_implementation("pymeshlab(genus=library, boundary=library)")) \
        == ("pymeshlab", "F-pymeshlab-2 (boundary term 2 pi - angle sum - phi); "
                         "F-pymeshlab-1 (genus of a non-orientable mesh is floor(h / 2))")
    assert declared_conventions(load_implementation("tests.planted_bugs:ChiIgnoresBoundary")) is None
    assert declared_conventions(load_implementation("libigl")) is None

    class Malformed:
        conventions = {"follows": {"X1": "something"}}          # no counterpart
    with pytest.raises(NotAnImplementation, match="counterpart"):
        declared_conventions(Malformed())


def test_expect_conventions_works_for_a_third_party_implementation(capsys):
    argv = ["check", "--impl", "tests.planted_bugs:TwoPiAtTheBoundary", "--only", "R2.4",
            "--profile", "ci", "--workers", "1", "--wide"]
    rc, out, _ = _run(capsys, *argv)
    assert rc == 1 and re.search(r"^R2\.4 .*FAILED$", out, re.M)
    rc, out, _ = _run(capsys, *argv, "--expect-conventions")
    assert rc == 0 and re.search(r"^R2\.4 .*convention$", out, re.M), out
    assert "documented convention MYLIB-7" in out and "reference passes the same example" in out


# --- the report -----------------------------------------------------------------------------------


def _report(d, workers):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = main(["check", "--profile", "ci", "--impl", "reference",
                   "--impl", "tests.planted_bugs:ChiIgnoresBoundary",
                   "--impl", "tests.test_cli:RoundsFlatVertices",
                   "--only", "D1.6", "--only", "L2.4", "--workers", str(workers),
                   "--report", str(d)])
    assert rc == 1, out.getvalue() + err.getvalue()
    return d


@pytest.fixture(scope="module")
def report_in_two_workers(tmp_path_factory):
    """The report of one run in 2 workers: its files are read by one test and its
    results.json compared with a run in 1 worker by another (the run costs seconds)."""
    return _report(tmp_path_factory.mktemp("report") / "b", 2)


def test_report_files_and_json_schema(report_in_two_workers):
    d = report_in_two_workers
    doc = json.loads((d / "results.json").read_text())
    assert doc["schema"] == 4
    assert doc["command"]["profile"] == "ci" and "argv" not in doc["command"]
    assert doc["counts"]["FAILED"] == 1 and doc["counts"]["tie disagreement"] == 1
    assert set(doc["versions"]) >= {"python", "numpy", "hypothesis"}
    keys = {"property_id", "property_name", "statement", "implementation", "spec", "source",
            "status", "ok", "examples", "wanted", "ties", "unjudged", "note", "crash", "also", "failure",
            "mesh", "files", "replay", "diagnosis"}
    assert len(doc["results"]) == 6 and all(set(r) == keys for r in doc["results"])
    failed = [r for r in doc["results"] if r["status"] == FAILED]
    assert len(failed) == 1
    f = failed[0]
    assert f["property_id"] == "D1.6" and f["spec"] == "tests.planted_bugs:ChiIgnoresBoundary"
    assert f["ok"] is False and f["failure"]["expected"] != f["failure"]["observed"]
    assert set(f["failure"]) == {"message", "element", "element_ids", "expected", "observed",
                                 "error", "bound", "error_in_bounds"}
    tie = next(r for r in doc["results"] if r["status"] == TIE)
    assert tie["failure"]["element_ids"] == {"vertex": 0}
    assert 0 < tie["failure"]["error_in_bounds"] < 1
    # the files of the failure: the shrunk mesh, its picture, a snippet that reproduces it
    V, F = read_mesh(d / f["files"]["obj"])
    assert V == f["mesh"]["V"] and F == f["mesh"]["F"]
    assert (d / f["files"]["png"]).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert f["replay"].startswith("ddg2:") and tie["replay"].startswith("ddg2:")
    assert all(r["replay"] is None for r in doc["results"] if r["status"] == "passed")
    out = subprocess.run([sys.executable, str(d / f["files"]["snippet"])], cwd=ROOT,
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 1                             # the snippet raises the failure again
    assert (f"expected: {f['failure']['expected']}\n  observed: {f['failure']['observed']}"
            in out.stderr), out.stderr
    assert (d / "index.html").is_file()
    summary = (d / "summary.md").read_text()
    assert "| D1.6 (euler_characteristic_of_known_surfaces) |" in summary
    assert f"]({f['files']['png']})" in summary
    assert json.loads((d / "timings.json").read_text())["seconds"] > 0


def test_report_json_is_identical_across_runs_and_worker_counts(tmp_path, report_in_two_workers):
    a = _report(tmp_path / "a", 1)
    b = report_in_two_workers
    assert (a / "results.json").read_bytes() == (b / "results.json").read_bytes()


def test_a_crash_is_reported_with_its_input_in_the_report(tmp_path, capsys):
    d = tmp_path / "crash"
    # R1.6: its search meets a boundary (the segfault) and shrinks in 3 examples; D1.6's
    # shrinking respawned the crashed library 12 times (the ci crash budget), ~7 s of CPU
    rc, out, _ = _run(capsys, "check", "--impl", "tests.misbehaving:SegfaultsOnBoundary",
                      "--only", "R1.6", "--profile", "ci", "--timeout", "20", "--workers", "1",
                      "--report", str(d))
    assert rc == 1 and "SIGSEGV" in out
    r = json.loads((d / "results.json").read_text())["results"][0]
    assert r["status"] == "crashed" and "SIGSEGV" in r["crash"]
    assert r["mesh"]["F"] and (d / r["files"]["snippet"]).is_file()


def test_element_ids_and_jsonable():
    assert element_ids("edge (3, 9), theta ~ 0.1, l ~ 2") == {"edge": [3, 9]}
    assert element_ids(np.int64(4)) == {"vertex": 4}
    assert element_ids("row 7") == {"vertex": 7}
    assert jsonable({(1, 2): np.float64(0.5), "x": float("nan"), "y": np.arange(2)}) == \
        {"(1, 2)": 0.5, "x": "nan", "y": [0, 1]}


def test_progress_bar_only_on_a_terminal():
    import io

    class Tty(io.StringIO):
        def isatty(self):
            return True

    from ddg_oracle.application.jobs import Task
    tty, pipe = Tty(), io.StringIO()
    for stream in (tty, pipe):
        p = Progress(2, stream)
        p(Task("reference", "D1.6"), [])
        p.finish()
    assert "1/2" in tty.getvalue() and "#" in tty.getvalue()
    assert pipe.getvalue() == ""


# --- --mesh and compare ---------------------------------------------------------------------------


@pytest.fixture
def tetra_obj(tmp_path):
    V, F = surfaces.tetrahedron().to_arrays()
    path = tmp_path / "tetra.obj"
    write_obj(path, V, F)
    return path


@pytest.fixture
def disk_obj(tmp_path):
    V, F = surfaces.disk(6).to_arrays()
    path = tmp_path / "disk.obj"
    write_obj(path, [list(p) + [0.0] * (3 - len(p)) for p in V], F)
    return path


def test_check_on_a_mesh_file(capsys, tetra_obj, disk_obj):
    rc, out, _ = _run(capsys, "check", "--mesh", str(tetra_obj), str(disk_obj),
                      "--impl", "reference", "--impl", "tests.planted_bugs:ChiIgnoresBoundary",
                      "--workers", "2", "--wide")
    assert rc == 1
    assert f"property on {tetra_obj}" in out and f"property on {disk_obj}" in out
    assert re.search(r"^D2\.2 \(angle_defects_match_reference\)\s+passed \(1 example\)", out, re.M)
    tetra, disk = out.split(f"property on {disk_obj}")[0], out.split(f"property on {disk_obj}")[1]
    assert re.search(r"^D1\.6 .*passed \(1 example\)\s+passed \(1 example\)$", tetra, re.M)
    assert re.search(r"^D1\.6 .*passed \(1 example\)\s+FAILED$", disk, re.M)   # chi of a disk
    assert re.search(r"^T2\.6 .*not applicable", disk, re.M)                  # has a boundary
    assert f"on: {disk_obj}" in out


def test_sample_meshes_of_pymeshlab(capsys):
    rc, out, err = _run(capsys, "check", "--mesh", "pymeshlab:cube.obj", "--impl", "reference",
                        "--only", "D2.2", "--only", "X1.4", "--wide")
    assert rc == 0 and "property on pymeshlab:cube.obj" in out
    from ddg_oracle.application.meshes import resolve
    everything = [name for name, _, _ in resolve(["pymeshlab:"])]
    assert "pymeshlab:cube.obj" in everything and "pymeshlab:bunny.obj" in everything
    rc, _, err = _run(capsys, "check", "--mesh", "pymeshlab:no-such.obj")
    assert rc == 2 and "no such sample mesh" in err and err.count("\n") == 1


def test_only_without_a_mesh_property_is_a_usage_error(capsys, tetra_obj):
    rc, _, err = _run(capsys, "check", "--mesh", str(tetra_obj), "--only", "X1.4")
    assert rc == 2 and "applies to a mesh file" in err


BAD_FILES = {
    "missing.obj": None,
    "malformed.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n",
    "nan.obj": "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n",
    "nonmanifold.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n"
                       "f 1 2 3\nf 2 1 4\nf 1 2 5\n",
    "flat.obj": "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
    "quad.off": "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
    "mesh.xyz": "1 2 3\n",
}


@pytest.mark.parametrize("name", sorted(BAD_FILES))
@pytest.mark.parametrize("command", ["check", "compare"])
def test_bad_mesh_file_is_one_line_exit_2_no_traceback(capsys, tmp_path, name, command):
    path = tmp_path / name
    if BAD_FILES[name] is not None:
        path.write_text(BAD_FILES[name])
    argv = [command, str(path)] if command == "compare" else [command, "--mesh", str(path)]
    rc, out, err = _run(capsys, *argv, "--impl", "reference")
    assert rc == 2
    assert err.startswith("ddg-oracle: error:") and err.count("\n") == 1, err
    assert "Traceback" not in err and name in err


def test_unreferenced_vertices_are_removed_with_a_note(capsys, tmp_path):
    path = tmp_path / "extra.obj"
    V, F = surfaces.tetrahedron().to_arrays()
    write_obj(path, list(V) + [[5.0, 5.0, 5.0]], F)
    rc, out, err = _run(capsys, "check", "--mesh", str(path), "--impl", "reference",
                        "--only", "D1.6")
    assert rc == 0 and "1 unreferenced vertices removed" in err


def test_run_on_example_uses_the_property_check_once():
    from ddg_oracle.application.meshes import MeshExamples, MeshInput
    V, F = surfaces.cube().to_arrays()
    ex = MeshExamples(MeshInput("cube", V, F))
    r = run_on_example(PROPERTIES["D2.2"], ReferenceImplementation(), ex.example(), "cube")
    assert r.status == PASSED and r.examples == 1 and r.source == "cube"


def test_compare_lists_every_quantity_with_its_worst_element(capsys, tetra_obj):
    rc, out, _ = _run(capsys, "compare", str(tetra_obj), "--impl", "libigl")
    assert rc == 0
    from ddg_oracle.protocol.methods import METHODS
    not_comparable = {"intrinsic_delaunay_triangulation", "planar_delaunay",   # not unique / no mesh
                      "planar_flip_to_delaunay", "solve_dirichlet"}   # needs boundary data
    for method in METHODS:
        status = "not applicable" if method in not_comparable else "agrees"
        assert re.search(rf"^{method}\s+libigl\s+{status}", out, re.M), method
    assert re.search(r"^angle_defects\s+libigl\s+agrees\s+[\d.e-]+\s+vertex \d", out, re.M)
    assert re.search(r"^cotan_laplacian\s+libigl\s+agrees\s+[\d.e-]+\s+entry \(\d+, \d+\)", out, re.M)


def test_compare_finds_the_planted_bug_and_exits_1(capsys, disk_obj):
    rc, out, _ = _run(capsys, "compare", str(disk_obj), "--impl",
                      "tests.planted_bugs:ChiIgnoresBoundary", "--impl", "tests.test_cli:FlatVerticesCurved")
    assert rc == 1
    assert re.search(r"^euler_characteristic\s+chi-ignores-boundary\s+DIFFERS.*\s1\s+-?\d", out, re.M)
    # the disk's centre is flat: K = 1e-3 instead of 0, beyond the bound, at vertex 0
    assert re.search(r"^angle_defects\s+flat-vertices-curved\s+DIFFERS\s+\S+\s+\(1/7 over\)\s+vertex 0",
                     out, re.M)


def test_undecided_when_the_exact_reference_hits_a_guard(monkeypatch):
    from ddg_oracle.reference.errors import TermLimitExceeded
    from ddg_oracle.properties.runner import UNDECIDED

    class Limited(ReferenceImplementation):
        def euler_characteristic(self, V, F):
            raise TermLimitExceeded("a square-root number would have too many terms")
    from ddg_oracle.application.meshes import MeshExamples, MeshInput
    V, F = surfaces.cube().to_arrays()
    ex = MeshExamples(MeshInput("cube", V, F))
    r = run_on_example(PROPERTIES["D1.6"], Limited(), ex.example(), "cube")
    assert r.status == UNDECIDED and r.ok and "too many terms" in r.error


def test_convention_status_from_run_property():
    from hypothesis import settings
    from ddg_oracle.oracles.libigl import Libigl
    quick = settings(max_examples=20, deadline=None, database=None, derandomize=True)
    r = run_property(PROPERTIES["R2.4"], Libigl(boundary="library"), quick,
                     counterpart=Libigl(), convention="F-libigl-2")
    assert r.status == CONVENTION and r.ok and "F-libigl-2" in r.note


def test_report_of_a_failure_on_a_large_mesh_file_reads_the_obj(tmp_path, capsys):
    V, F = surfaces.grid(15, 15).to_arrays()               # 256 vertices, a boundary
    mesh = tmp_path / "grid.obj"
    write_obj(mesh, [list(p) + [0.0] * (3 - len(p)) for p in V], F)
    d = tmp_path / "big"
    rc, out, _ = _run(capsys, "check", "--mesh", str(mesh), "--only", "D1.6", "--workers", "1",
                      "--impl", "tests.planted_bugs:ChiIgnoresBoundary", "--report", str(d))
    assert rc == 1
    assert "more)]" in out                                  # the face list is cut in the text
    r = json.loads((d / "results.json").read_text())["results"][0]
    assert r["mesh"] == {"file": str(mesh), "vertices": 256, "faces": 450}
    snippet = (d / r["files"]["snippet"]).read_text()
    assert 'Path(__file__).with_name("mesh.obj")' in snippet
    out = subprocess.run([sys.executable, str(d / r["files"]["snippet"])], cwd=ROOT,
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 1, out.stderr               # the same check fails again
    assert "wrong Euler characteristic" in out.stdout


@pytest.mark.parametrize("element", [{"vertex": 3}, {"edge": [0, 5]}, {"face": 2, "corner": 1},
                                     {"face": 40}, None])
def test_render_writes_a_png_for_each_kind_of_element(tmp_path, element):
    from ddg_oracle.application.render import RING_LIMIT, render_mesh
    s = surfaces.torus(24, 12) if element == {"face": 40} else surfaces.disk(6)
    V, F = s.to_arrays()
    if element == {"face": 40}:
        assert len(F) > RING_LIMIT                          # only the neighbourhood is drawn
    path = tmp_path / "m.png"
    render_mesh(path, V, F, element, title="demo")
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and path.stat().st_size > 5000


def test_seed_and_timeout_options_are_accepted(capsys):
    rc, out, _ = _run(capsys, "check", "--impl", "reference", "--only", "X2.1", "--seed", "7",
                      "--timeout", "30", "--workers", "1", "--wide")
    assert rc == 0 and re.search(r"^X2\.1 .*passed \(\d+ examples\)$", out, re.M)


# --- the hostile corpus through the command line: one line, exit 2 ----------------------------

from tests import hostile  # noqa: E402


@pytest.mark.parametrize("case", hostile.FILE_CASES + hostile.MESH_FILE_CASES,
                         ids=lambda c: c.name)
def test_every_hostile_mesh_file_is_one_line_and_exit_2(capsys, tmp_path, case):
    path = hostile.write(case, tmp_path)
    if "unreferenced" in case.name:
        # the command line drops unreferenced vertices of real meshes, saying so
        rc, out, err = _run(capsys, "check", "--mesh", str(path), "--impl", "reference",
                            "--only", "D1.6")
        assert rc == 0 and "unreferenced vertices removed" in err
        return
    for command in (["check", "--mesh", str(path), "--impl", "reference", "--only", "D1.6"],
                    ["compare", str(path), "--impl", "reference"]):
        rc, out, err = _run(capsys, *command)
        assert rc == 2, (command, out, err)
        assert err.startswith("ddg-oracle: error:") and err.count("\n") == 1, err
        assert "Traceback" not in err
        low = err.lower()
        assert any(w.lower() in low for w in case.words), (case.words, err)


# --- exit codes CI can rely on, help, version, selection ---------------------------------------


def test_a_crash_of_the_tool_itself_is_exit_3_with_its_traceback(capsys, monkeypatch):
    import ddg_oracle.application.cli as cli

    def broken(args):
        raise ValueError("an internal bug, not a usage error")
    monkeypatch.setattr(cli, "_theorems", broken)
    rc, _, err = _run(capsys, "theorems")
    assert rc == cli.EXIT_TOOL == 3
    assert "Traceback" in err and "an internal bug" in err and "bug in ddg-oracle" in err


def test_report_into_a_used_path_is_refused_before_the_run(capsys, tmp_path):
    used = tmp_path / "used"
    used.mkdir()
    (used / "results.json").write_text("{}")
    a_file = tmp_path / "a-file"
    a_file.write_text("x")
    for path in (used, a_file):
        rc, out, err = _run(capsys, "check", "--impl", "reference", "--only", "D1.6",
                            "--workers", "1", "--report", str(path))
        assert rc == 2 and out == "" and "new or empty directory" in err, err
    empty = tmp_path / "empty"
    empty.mkdir()
    rc, _, _ = _run(capsys, "check", "--impl", "reference", "--only", "D1.6", "--workers", "1",
                    "--report", str(empty))
    assert rc == 0 and (empty / "results.json").is_file()


def test_only_takes_several_ids_and_any_part_of_a_joint_id(capsys):
    rc, out, _ = _run(capsys, "check", "--impl", "reference", "--workers", "1", "--wide",
                      "--only", "D1.6", "L4.3,R1.5")
    assert rc == 0
    assert re.search(r"^D1\.6 ", out, re.M) and re.search(r"^L4\.3 / P4\.4 ", out, re.M)
    assert re.search(r"^R1\.5", out, re.M)
    rc, _, err = _run(capsys, "check", "--impl", "reference", "--only", "D1.7")
    assert rc == 2 and "did you mean" in err and "D1.6" in err


def test_version_and_help_are_plain_text_with_examples_and_exit_codes(capsys):
    from ddg_oracle import __version__
    rc, out, _ = _run(capsys, "--version")
    assert rc == 0 and out.strip() == f"ddg-oracle {__version__}"
    for command in ("check", "compare", "theorems", "verify", "methods"):
        rc, out, _ = _run(capsys, command, "--help")
        assert rc == 0
        assert "examples:" in out and f"ddg-oracle {command}" in out and "exit codes:" in out
        assert "``" not in out and ":func:" not in out and ":mod:" not in out
        if command in ("check", "compare", "verify"):    # every kind of --impl, with an example
            for kind in ("NAME", "module:object", "exec:COMMAND", "exec:FILE.json", "libigl",
                         "'exec:node driver.js'", "ddg-oracle methods"):
                assert kind in out, (command, kind)


def test_methods_lists_every_protocol_method_and_the_properties_calling_it(capsys):
    from ddg_oracle.protocol.methods import METHODS
    rc, out, _ = _run(capsys, "methods")
    assert rc == 0
    for name, m in METHODS.items():
        assert f"{name}({', '.join(m.arguments)})" in out
    assert re.search(r"cotan_laplacian\(V, F\)\n(.*\n){1,3}    checked by: D3\.1", out)


class Typo:
    """Protocol methods misspelt: would pass every property vacuously."""

    def angle_defect(self, V, F):
        return np.zeros(len(V))

    def cotmatrix(self, V, F):
        return None


def test_an_object_without_protocol_methods_is_refused_with_did_you_mean(capsys, tmp_path,
                                                                         monkeypatch):
    from ddg_oracle.properties import check_implementation
    from ddg_oracle.protocol.methods import NotAnImplementation

    with pytest.raises(NotAnImplementation, match="did you mean `angle_defects` for "
                                                  "`angle_defect`, `cotan_laplacian` for `cotmatrix`"):
        check_implementation(Typo())
    (tmp_path / "typo_impl.py").write_text("class Typo:\n    def angle_defect(self, V, F):\n"
                                           "        return None\n")
    monkeypatch.chdir(tmp_path)
    rc, out, err = _run(capsys, "check", "--impl", "typo_impl:Typo", "--workers", "1")
    assert rc == 2 and "did you mean `angle_defects`" in err and err.count("\n") == 1, err


def test_a_user_module_that_fails_to_import_is_a_usage_error(capsys, tmp_path, monkeypatch):
    (tmp_path / "broken_impl.py").write_text("import no_such_dependency_anywhere\n")
    monkeypatch.chdir(tmp_path)
    rc, _, err = _run(capsys, "check", "--impl", "broken_impl:Impl", "--workers", "1")
    assert rc == 2
    assert "cannot import your module 'broken_impl'" in err and "no_such_dependency" in err
    assert "crash" not in err.lower()


def test_the_current_directory_never_shadows_an_installed_module(tmp_path, monkeypatch):
    import ddg_oracle.application.implementations as impls

    (tmp_path / "mine_impl.py").write_text("class Impl:\n    def genus(self, V, F):\n"
                                           "        return 0\n")
    (tmp_path / "json.py").write_text("raise RuntimeError('shadowed the standard library')\n")
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(sys, "path", [p for p in sys.path if p not in ("", str(tmp_path))])
    impl = impls.load_implementation("mine_impl:Impl")
    assert impl.genus(None, None) == 0
    assert sys.path[-1] == str(tmp_path)            # appended, not put first
    import importlib
    assert importlib.import_module("json").__name__ == "json"


def test_the_compact_report_fits_100_columns_with_every_kind_of_result():
    argv = [sys.executable, "-m", "ddg_oracle", "check", "--impl", "reference",
            "--impl", "libigl", "--impl", "libigl(boundary=library)",
            "--impl", "tests.misbehaving:SegfaultsOnBoundary",
            "--impl", "tests.test_cli:RoundsFlatVertices", "--impl", "scipy",
            "--only", "R1.6", "L2.4", "R2.4", "X1.4", "T1.1", "--expect-conventions",
            "--seed", "1", "--timeout", "20", "--workers", "1"]
    # X1.4 (not D1.6) for the segfault's second crash, collapsed with R1.6's ("[x2]"): it
    # crashes in 3 examples, D1.6 respawned the crashed library 12 times (~7 s of CPU).
    # One worker: the report does not depend on the count (test_report_json_is_identical...)
    out = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert out.returncode == 1, out.stdout + out.stderr
    lines = out.stdout.splitlines()
    assert max(map(len, lines)) <= 100, max(lines, key=len)
    for heading in ("FAILED (", "crashed (", "tie disagreements (", "conventions (",
                    "passed (of the applicable checks)", "not applicable ("):
        assert any(line.startswith(heading) for line in lines), heading
    assert any(line.endswith("  [x2]") for line in lines)   # one crash, two properties: one row
    assert re.search(r"^  R1\.6 +libigl +wrong number of boundary loops +\(known: F-libigl-1\)$",
                     out.stdout, re.M)
    assert any(re.match(r"exit 1: \d+ checks failed or crashed; known findings F-libigl-1", line)
               for line in lines[-6:]), lines[-6:]
    # without a terminal: a line per finished applicable task on stderr
    assert re.search(r"^\[\d+/\d+ \d+ s\] R1\.6 libigl: FAILED$", out.stderr, re.M)


def test_a_directory_is_a_corpus_of_its_mesh_files(capsys, tmp_path, tetra_obj, disk_obj):
    corpus = tmp_path / "corpus"
    (corpus / "sub").mkdir(parents=True)
    (corpus / "a.obj").write_bytes(tetra_obj.read_bytes())
    (corpus / "sub" / "b.obj").write_bytes(disk_obj.read_bytes())
    (corpus / "broken.obj").write_text("v 0 0 0\nf 1 2 x\n")
    (corpus / "notes.txt").write_text("not a mesh")
    rc, out, err = _run(capsys, "check", "--mesh", str(corpus), "--impl",
                        "tests.planted_bugs:ChiIgnoresBoundary", "--only", "D1.6", "--workers", "1",
                        "--wide")
    assert rc == 1                                  # chi of the disk
    assert f"property on {corpus / 'a.obj'}" in out and f"property on {corpus / 'sub' / 'b.obj'}" in out
    assert "broken.obj" in err and "notes.txt" not in out + err
    empty = tmp_path / "empty"
    empty.mkdir()
    rc, _, err = _run(capsys, "check", "--mesh", str(empty))
    assert rc == 2 and "no mesh file" in err and err.count("\n") == 1


def test_methods_with_impl_lists_what_it_defines_and_warns_of_near_misses(capsys, tmp_path,
                                                                         monkeypatch):
    (tmp_path / "half_impl.py").write_text(
        "class Half:\n    machine_epsilon = 2.0 ** -23\n    conventions = 'libigl'\n"
        "    def angle_defects(self, V, F):\n        return None\n"
        "    def cotmatrix(self, V, F):\n        return None\n")
    monkeypatch.chdir(tmp_path)
    rc, out, err = _run(capsys, "methods", "--impl", "half_impl:Half")
    assert rc == 0, err
    assert "machine_epsilon 1.1920928955078125e-07" in out and "laplacian=negative" in out
    assert re.search(r"defines  angle_defects  \(D2\.2", out)
    assert re.search(r"-        cotan_laplacian\n", out)
    assert re.search(r"\n1 of \d+ methods", out)
    assert "`cotmatrix` is not a protocol method (did you mean `cotan_laplacian`?)" in err
    rc, _, err = _run(capsys, "methods", "--impl", "no_such_module_here:X")
    assert rc == 2 and err.count("\n") == 1


@pytest.mark.parametrize("command", ["compare", "verify"])
@pytest.mark.parametrize("timeout", ["-1", "0"])
def test_a_bad_timeout_of_compare_and_verify_is_a_usage_error(capsys, tmp_path, command, timeout):
    """Fault suite (issue 45): compare --timeout -1 blamed every call on the library, verify
    --timeout 0 restarted the worker per call."""
    mesh = tmp_path / "t.obj"
    mesh.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    target = str(mesh) if command == "compare" else str(Path(__file__).parents[1] / "vectors")
    rc, _, err = _run(capsys, command, target, "--impl", "reference", "--timeout", timeout)
    assert rc == 2 and "--timeout must be a positive number" in err and err.count("\n") == 1


def test_read_bytes_reserves_the_file_not_the_limit(tmp_path, monkeypatch):
    """Fault suite (issue 45): read(limit + 1) reserved the 2 GiB mesh limit up front, a
    MemoryError under ulimit -v for a 20-face file.  The buffer follows the file's size."""
    import io
    from ddg_oracle.application import files
    path = tmp_path / "small.bin"
    path.write_bytes(b"x" * 100)
    asked = []
    real_open = open

    class Recorder(io.BufferedReader):
        def read(self, n=-1):
            asked.append(n)
            return super().read(n)

    monkeypatch.setattr("builtins.open", lambda p, mode="r", *a, **k:
                        Recorder(io.FileIO(p, "rb")) if mode == "rb" else real_open(p, mode, *a, **k))
    assert files.read_bytes(path, "a test file", limit=2 ** 31) == b"x" * 100
    assert max(asked) <= 1 << 20, asked
    from ddg_oracle.reference.errors import InputError
    with pytest.raises(InputError, match="over the limit"):
        files.read_bytes(path, "a test file", limit=50)


def test_an_undecided_result_is_never_attributed_to_a_library_finding():
    """The exact reference giving up (time or precision limit) on a mesh says nothing about
    the library: "(known: F-libigl-6)" beside an undecided D4.8 blamed libigl."""
    from ddg_oracle.properties.runner import INTERNAL, UNDECIDED, Result
    from ddg_oracle.application.report import known_finding, known_findings
    findings = known_findings()
    failed = Result("D4.8 / R4.9", "laplace_beltrami_operator", "libigl", FAILED)
    assert known_finding(failed, findings) is not None            # libigl has D4.8 findings
    for status in (UNDECIDED, INTERNAL):
        r = Result("D4.8 / R4.9", "laplace_beltrami_operator", "libigl", status)
        assert known_finding(r, findings) is None


def test_a_mesh_file_with_inconsistently_oriented_faces_is_not_a_dihedral_sign_check(
        tmp_path, capsys):
    """CGAL's tet-shuffled.off: an orientable tetrahedron listed with faces both ways.  The
    sign of a dihedral angle reads the faces' orientation: R2.5 was an internal error
    (exit 3) and D2.3 blamed the reference's own answer; both are not applicable there."""
    path = tmp_path / "tet-shuffled.obj"
    write_obj(path, [[0.0, 0, 0], [0, 1, 0], [1, 1, 0], [0, 0, 1]],
              [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]])
    rc = main(["check", "--mesh", str(path), "--impl", "reference", "--workers", "1",
               "--only", "D2.3", "R2.5", "D2.2", "--report", str(tmp_path / "r")])
    out, err = capsys.readouterr()
    assert rc == 0, out + err
    results = json.loads((tmp_path / "r" / "results.json").read_text())["results"]
    status = {r["property_id"].split(" ")[0]: r for r in results}
    assert status["D2.2"]["status"] == "passed"
    for pid in ("D2.3", "R2.5"):
        assert status[pid]["status"] == "not applicable", status[pid]
        assert "not consistently oriented" in json.dumps(status[pid])


def test_the_command_loads_no_third_party_hypothesis_plugin():
    """trio's Hypothesis plugin (installed with selenium) cost 0.17 s of every check
    process's and worker's start; the command skips plugins unless the user set
    HYPOTHESIS_NO_PLUGINS, and a call of main() from Python changes no environment."""
    env = {k: v for k, v in os.environ.items() if k != "HYPOTHESIS_NO_PLUGINS"}
    probe = ("import os, sys; sys.argv = ['ddg-oracle', '--version']\n"
             "from ddg_oracle.application.cli import main\n"
             "{call}\n"
             "import hypothesis\n"
             "print(sorted(m for m in ('trio', 'pytest') if m in sys.modules), "
             "os.environ.get('HYPOTHESIS_NO_PLUGINS'))")

    def loaded(call):
        out = subprocess.run([sys.executable, "-c", probe.format(call=call)], cwd=ROOT, env=env,
                             capture_output=True, text=True, timeout=120)
        assert out.returncode == 0, out.stderr
        return out.stdout.split("\n")[-2]
    control = loaded("pass")
    if not control.startswith("['pytest', 'trio']"):
        pytest.skip(f"no Hypothesis plugin to skip here: {control}")
    assert loaded("main()") == "[] 1"                        # as the command: none loaded
    assert loaded("main(['--version'])") == control          # from Python: nothing changed


def test_examples_sets_how_many_examples_each_check_runs(capsys, tmp_path):
    rc, out, err = _run(capsys, "check", "--impl", "reference", "--only", "D1.6", "D3.1",
                        "--examples", "3", "--seed", "1", "--workers", "1",
                        "--report", str(tmp_path / "r"))
    assert rc == 0 and "(3 examples each)" in out, out
    results = json.loads((tmp_path / "r" / "results.json").read_text())["results"]
    assert [(r["status"], r["examples"], r["wanted"]) for r in results] == [("passed", 3, 3)] * 2
    rc, _, err = _run(capsys, "check", "--impl", "reference", "--examples", "0")
    assert rc == 2 and "--examples must be at least 1" in err and err.count("\n") == 1
    # a mesh file is checked once: a count would be silently ignored
    mesh = tmp_path / "t.obj"
    mesh.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    rc, _, err = _run(capsys, "check", "--impl", "reference", "--mesh", str(mesh),
                      "--examples", "5")
    assert rc == 2 and "with --mesh each file is checked once" in err and err.count("\n") == 1


def test_a_tmpdir_too_long_for_worker_sockets_is_one_line_and_exit_2(tmp_path):
    """Python's worker processes talk over AF_UNIX sockets named in TMPDIR (at most 107
    bytes): a long TMPDIR made `check` end with a traceback and "a bug in ddg-oracle"
    (exit 3); it is the machine's setting, said in one line (exit 2)."""
    pytest.importorskip("igl")                 # a library: checked in a worker process
    deep = tmp_path / ("d" * max(10, 100 - len(str(tmp_path))))
    deep.mkdir()
    out = subprocess.run([sys.executable, "-m", "ddg_oracle", "check", "--impl", "libigl",
                          "--only", "D1.6", "--workers", "1"], capture_output=True, text=True,
                         timeout=120, env={**os.environ, "TMPDIR": str(deep)})
    assert out.returncode == 2, out.stdout + out.stderr
    assert out.stderr.count("\n") == 1 and f"TMPDIR={deep}" in out.stderr, out.stderr
