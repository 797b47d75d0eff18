"""``ddg-oracle survey``: the scoreboard over a corpus, its files, interrupt and resume.

Three small meshes written as OBJ files (a tetrahedron and a cube, closed; a disk, with a
boundary), the exact reference (honest: everything agrees), two planted bugs of
tests/planted_bugs.py: ChiIgnoresBoundary (wrong Euler characteristic on the disk only)
and Float32Defects (angle defects off by ~1e-7, beyond the float64 bound), and
SlowOnCubes (honest, a second slow on the cube: the last mesh is still running when the
first ones are recorded, which the interrupt test needs on a fast machine).
"""

from __future__ import annotations

import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from ddg_oracle.application.meshfiles import write_obj
from ddg_oracle.reference import surfaces

ROOT = Path(__file__).resolve().parent.parent
IMPLS = ["--impl", "reference", "--impl", "tests.planted_bugs:ChiIgnoresBoundary",
         "--impl", "tests.planted_bugs:Float32Defects",
         # honest, but a second slow on the cube: an interrupt finds meshes left to do
         "--impl", "tests.planted_bugs:SlowOnCubes"]


@pytest.fixture(scope="module")
def corpus(tmp_path_factory) -> list[str]:
    d = tmp_path_factory.mktemp("corpus")
    paths = []
    for name, s in (("tetra", surfaces.tetrahedron()), ("disk", surfaces.disk(6)),
                    ("cube", surfaces.cube())):
        V, F = s.to_arrays()
        write_obj(d / f"{name}.obj", [list(p) + [0.0] * (3 - len(p)) for p in V], F)
        paths.append(str(d / f"{name}.obj"))
    return paths


def _survey(*argv, timeout=600) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "ddg_oracle", "survey", *argv], cwd=ROOT,
                          capture_output=True, text=True, timeout=timeout)


@pytest.fixture(scope="module")
def undisturbed(corpus, tmp_path_factory):
    # one worker: the exact values in process (a pool of 2 spawned per mesh costs a
    # second a mesh); the interrupted run below computes them in the default pool and
    # must score as this one
    report = tmp_path_factory.mktemp("runs") / "undisturbed"
    out = _survey(*corpus, *IMPLS, "--workers", "1", "--report", str(report))
    return out, report, json.loads((report / "results.json").read_text())


def _score(doc, implementation, quantity) -> dict:
    found = [s for s in doc["scoreboard"] if (s["implementation"], s["quantity"])
             == (implementation, quantity)]
    assert len(found) == 1, (implementation, quantity)
    return found[0]


def test_the_scoreboard_counts_each_implementation_and_quantity(corpus, undisturbed):
    out, report, doc = undisturbed
    assert out.returncode == 1, out.stdout + out.stderr        # a planted bug differs
    tetra, disk, cube = corpus
    # the honest implementation: every quantity it provides agrees on every mesh
    honest = [s for s in doc["scoreboard"] if s["implementation"] == "reference"]
    assert len(honest) > 10
    for s in honest:
        assert s["meshes"] == 3 and s["DIFFERS"] == s["crashed"] == 0, s
        assert s["agrees"] + s["not applicable"] == 3, s
    assert _score(doc, "reference", "cotan_laplacian")["agrees"] == 3
    # chi ignoring the boundary: wrong on the disk only, and nothing else of it differs
    chi = _score(doc, "chi-ignores-boundary", "euler_characteristic")
    assert (chi["agrees"], chi["DIFFERS"], chi["crashed"]) == (2, 1, 0)
    assert chi["differs_on"] == [disk] and chi["worst"] is None     # an exact quantity
    assert all(s["DIFFERS"] == 0 for s in doc["scoreboard"]
               if s["implementation"] == "chi-ignores-boundary"
               and s["quantity"] != "euler_characteristic")
    # float32 defects: beyond the bound, the worst error named with its mesh
    f32 = _score(doc, "float32-defects", "angle_defects")
    assert f32["DIFFERS"] >= 1 and f32["worst"] > 1 and f32["worst_mesh"] in corpus
    assert f32["median"] is not None and f32["median"] <= f32["worst"]
    assert _score(doc, "float32-defects", "corner_angles")["DIFFERS"] == 0
    assert _score(doc, "reference", "angle_defects")["worst"] <= 1
    # the terminal table says the same
    assert re.search(r"^chi-ignores-boundary\s+euler_characteristic\s+3\s+2\s+1\s+0\s+0\s+0\s+-\s+"
                     + re.escape(disk), out.stdout, re.M), out.stdout
    assert re.search(r"^float32-defects\s+angle_defects\s+3\s+\d\s+[1-3]\s+0\s+0\s+0\s+\S+\s+/",
                     out.stdout, re.M)


def test_results_json_holds_every_mesh_and_the_command(corpus, undisturbed):
    out, report, doc = undisturbed
    assert doc["format"] == "ddg-oracle survey" and doc["interrupted"] is False
    assert [m["mesh"] for m in doc["meshes"]] == corpus and doc["meshes_total"] == 3
    assert [m["faces"] for m in doc["meshes"]] == [4, 6, 12]
    assert doc["command"]["argv"][:3] == corpus and "tests.planted_bugs:Float32Defects" in \
        doc["command"]["argv"]
    disk = doc["meshes"][1]["rows"]
    row = next(r for r in disk if r["implementation"] == "chi-ignores-boundary"
               and r["quantity"] == "euler_characteristic")
    assert row["status"] == "DIFFERS" and row["expected"] == "1" and row["observed"] != "1"
    assert row["spec"] == "tests.planted_bugs:ChiIgnoresBoundary"
    # one line per mesh streamed, the command line kept for --resume
    lines = (report / "results.jsonl").read_text().splitlines()
    assert [json.loads(x)["mesh"] for x in lines] == corpus
    assert json.loads((report / "run.json").read_text())["format"] == "ddg-oracle survey"


def test_survey_md_and_the_heatmap(corpus, undisturbed):
    out, report, doc = undisturbed
    md = (report / "survey.md").read_text()
    assert re.search(r"^\| chi-ignores-boundary \| euler_characteristic \| 3 \| 2 \| 1 \| 0 \| 0 "
                     r"\|", md, re.M), md
    page = (report / "survey.html").read_text()
    svg = ET.fromstring(page[page.index("<svg"):page.index("</svg>") + 6])
    ns = "{http://www.w3.org/2000/svg}"
    cells = {r.find(f"{ns}title").text.split(":")[0]: r.get("fill")
             for r in svg.iter(f"{ns}rect") if r.find(f"{ns}title") is not None}
    assert len(cells) == len(doc["scoreboard"])
    assert cells["chi-ignores-boundary / euler_characteristic"] == "hsl(80, 70%, 55%)"  # 2 of 3
    assert cells["reference / euler_characteristic"] == "hsl(120, 70%, 55%)"            # all
    assert cells["reference / solve_dirichlet"] == "#d9d9d9"       # never applicable here


def test_an_honest_implementation_alone_exits_0(corpus, tmp_path):
    out = _survey(corpus[0], corpus[2], "--impl", "reference", "--workers", "1")
    assert out.returncode == 0, out.stdout + out.stderr
    assert "2 of 2 meshes, 1 implementations" in out.stdout and " 0 DIFFERS" in out.stdout


def _lines(path: Path) -> int:
    try:
        return len(path.read_text().splitlines())
    except OSError:
        return 0


@pytest.mark.parametrize("signum", [signal.SIGINT])
def test_interrupt_keeps_finished_meshes_and_resume_finishes_as_undisturbed(
        corpus, undisturbed, tmp_path, signum):
    report = tmp_path / "run"
    proc = subprocess.Popen([sys.executable, "-m", "ddg_oracle", "survey", *corpus, *IMPLS,
                             "--report", str(report)], cwd=ROOT, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 300
    while _lines(report / "results.jsonl") < 1:
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() < deadline, "no mesh finished in time"
        time.sleep(0.05)
    proc.send_signal(signum)
    out, err = proc.communicate(timeout=120)
    assert proc.returncode == 128 + signum, out + err
    assert "finish with: ddg-oracle survey --resume" in err and "Traceback" not in err
    partial = json.loads((report / "results.json").read_text())
    assert partial["interrupted"] is True
    kept = [m["mesh"] for m in partial["meshes"]]
    assert 1 <= len(kept) < 3 and kept == corpus[:len(kept)]
    # moved: it resumes where it is now
    moved = tmp_path / "moved"
    shutil.move(str(report), str(moved))
    again = _survey("--resume", str(moved))
    assert again.returncode == 1, again.stdout + again.stderr
    assert "[1/3]" not in again.stderr and "[3/3]" in again.stderr   # only the rest ran
    resumed = json.loads((moved / "results.json").read_text())
    _, _, whole = undisturbed
    assert resumed["interrupted"] is False and _same(resumed) == _same(whole)
    assert [json.loads(x)["mesh"] for x in (moved / "results.jsonl").read_text().splitlines()] \
        == corpus


def _same(doc):
    return {"scoreboard": doc["scoreboard"], "command": doc["command"]["argv"],
            "meshes": [{k: v for k, v in m.items() if k != "seconds"} for m in doc["meshes"]]}


def test_a_survey_on_a_dask_cluster_scores_as_the_local_one(corpus, undisturbed, tmp_path):
    """--scheduler local:2: one mesh per task, each worker starting the implementations
    once; the meshes finish in any order, the scoreboard and every row are the local run's."""
    import importlib.util
    if importlib.util.find_spec("distributed") is None:   # not imported here: see test_cluster
        pytest.skip("dask.distributed is not installed (pip install 'ddg-oracle[dask]')")
    report = tmp_path / "cluster"
    out = _survey(*corpus, *IMPLS, "--scheduler", "local:2", "--report", str(report))
    local, _, whole = undisturbed
    assert out.returncode == local.returncode == 1, out.stdout + out.stderr
    assert "3 meshes on 2 workers of local:2" in out.stderr and "Traceback" not in out.stderr
    assert _same(json.loads((report / "results.json").read_text())) == _same(whole)
    assert sorted(json.loads(x)["mesh"] for x in
                  (report / "results.jsonl").read_text().splitlines()) == sorted(corpus)


def _one_line_error(out, *words):
    assert out.returncode == 2, out.stdout + out.stderr
    assert out.stderr.startswith("ddg-oracle: error:") and out.stderr.count("\n") == 1, out.stderr
    for w in words:
        assert w in out.stderr, out.stderr


def test_usage_errors_are_one_line_exit_2(corpus, undisturbed, tmp_path):
    _one_line_error(_survey("--impl", "reference"), "name the meshes")
    _one_line_error(_survey(corpus[0], "--impl", "no_such_library_at_all"), "no_such_library")
    _one_line_error(_survey(str(tmp_path / "missing.obj"), "--impl", "reference"), "missing.obj")
    _one_line_error(_survey("--resume", str(tmp_path)), "run.json")
    # a damaged line (not the last) of the streamed results
    _, report, _ = undisturbed
    damaged = tmp_path / "damaged"
    shutil.copytree(report, damaged)
    lines = (damaged / "results.jsonl").read_text().splitlines()
    (damaged / "results.jsonl").write_text("\n".join([lines[0][:40], *lines[1:]]) + "\n")
    _one_line_error(_survey("--resume", str(damaged)), "line 1 is not JSON")
    # a line that is JSON but not a survey's result
    (damaged / "results.jsonl").write_text('{"mesh": 1, "rows": []}\n' + lines[1] + "\n")
    _one_line_error(_survey("--resume", str(damaged)), "line 1 is not a survey result")


def test_scoreboard_of_records_worst_and_median():
    from ddg_oracle.application.survey import MeshResult, scoreboard

    def row(status, worst, where="vertex 0", note=None):
        return {"quantity": "angle_defects", "implementation": "x", "spec": "x",
                "status": status, "worst": worst, "error": None, "bound": None, "where": where,
                "expected": None, "observed": None, "over": 0, "elements": 1, "note": note,
                "explained_by": []}
    done = [MeshResult("a", 3, 1, [row("agrees", 0.5)]),
            MeshResult("b", 3, 1, [row("DIFFERS", "inf", "vertex 2")]),
            MeshResult("c", 3, 1, [row("agrees", 0.25)]),
            MeshResult("d", 3, 1, [row("crashed", None)]),
            MeshResult("e", 3, 1, [row("not applicable", None, note="not provided")]),
            MeshResult("f", 3, 1, [row("undecided", None, note="the exact reference gave up")])]
    # through JSON and back, as --resume reads them
    done = [MeshResult.from_json(json.loads(json.dumps(m.to_json()))) for m in done]
    (s,) = scoreboard(done)
    assert s.counts == {"agrees": 2, "DIFFERS": 1, "crashed": 1, "undecided": 1,
                        "not applicable": 0}
    assert s.worst == float("inf") and s.worst_mesh == "b" and s.worst_where == "vertex 2"
    assert s.median == 0.5 and s.differs_on == ["b", "d"] and s.fraction() == 0.5


@pytest.mark.parametrize("workers", ["1", "2"])
def test_the_exact_reference_giving_up_is_undecided_not_a_verdict(tmp_path, workers):
    """An exact value past DDG_EXAMPLE_TIME_LIMIT (CGAL's part.off: the exact intrinsic
    Delaunay Laplacian of 346 faces took over 120 s) stalled compare and survey without a
    limit; now that quantity's rows are "undecided" (nothing said of the library), the
    other quantities stand, and the exit code does not blame anyone.  The limit is CPU
    time, counted in the kernel's ticks: a 0.1 ms limit stops the exact values that take
    a few ms of CPU (a 288-face jittered grid's curvature, Laplacians, flips), not the
    cheapest (its topology)."""
    import numpy as np
    from tests.test_mesh_checks import _bumpy_grid
    V, F = _bumpy_grid(12, seed=5)
    mesh = tmp_path / "grid.obj"
    write_obj(mesh, V.tolist(), F.tolist())
    report = tmp_path / "r"
    env = dict(os.environ, DDG_EXAMPLE_TIME_LIMIT="0.0001")
    out = subprocess.run([sys.executable, "-m", "ddg_oracle", "survey", str(mesh), "--impl",
                          "tests.honest_panel:Atan2Cross", "--workers", workers,
                          "--report", str(report)], cwd=ROOT, capture_output=True,
                         text=True, timeout=600, env=env)
    assert np.asarray(F).shape == (288, 3)
    assert out.returncode == 0, out.stdout + out.stderr
    doc = json.loads((report / "results.json").read_text())
    rows = [r for m in doc["meshes"] for r in m["rows"]]
    undecided = [r for r in rows if r["status"] == "undecided"]
    assert undecided and all("gave up" in r["note"] for r in undecided)
    assert not any(r["status"] in ("DIFFERS", "crashed") for r in rows)
    assert sum(s["undecided"] for s in doc["scoreboard"]) == len(undecided)


def test_survey_takes_meshes_as_check_does_with_mesh(corpus, tmp_path):
    """`survey --mesh A B` (as `check --mesh` takes them) is `survey A B`; both may be
    mixed.  docs/corpus.md showed `survey --mesh pyvista: compas:`, which was a usage error."""
    out = _survey(corpus[0], "--mesh", corpus[1], corpus[2], "--impl", "reference",
                  "--workers", "1", "--report", str(tmp_path / "r"))
    assert out.returncode == 0, out.stdout + out.stderr
    run = json.loads((tmp_path / "r" / "run.json").read_text())
    assert run["argv"][:3] == corpus
    assert "3 of 3 meshes" in out.stdout
