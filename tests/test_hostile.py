"""Hostile input: every kind of bad mesh gets one typed error naming the problem and where.

The corpus and the decisions (what is an error, what is valid) are in
tests/hostile.py.  Guards: the square-root term limit and the time limit per
property example, each with a message saying what to change.
"""

import time
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import Phase, settings

from ddg_oracle.protocol.arrays import checked_arrays
from ddg_oracle.oracles.exact_reference import ReferenceImplementation
from ddg_oracle.application.meshfiles import MeshFileError, read_mesh
from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.profiles import TIME_LIMIT_ENV, example_time_limit, time_limit_seconds
from ddg_oracle.properties.runner import CRASHED, run_property
from ddg_oracle.reference import PiecewiseFlatSurface, PolyhedralSurface, Triangulation
from ddg_oracle.reference.curvature import (angle_defects, dihedral_angles, gauss_bonnet_holds,
                                 mean_curvature)
from ddg_oracle.reference.errors import (DegenerateFace, InputError, TermLimitExceeded,
                              TimeLimitExceeded)
from ddg_oracle.reference.exact import limits, sqrt
from ddg_oracle.reference.laplacian import cotan_laplacian, vertex_areas_barycentric, vertex_areas_voronoi
from tests.hostile import (ARRAY_CASES, FILE_CASES, ICO_F, ICO_V, LENGTH_CASES, hostile_paths,
                           MESH_FILE_CASES, TET_F, TET_V, TRIANGULATION_CASES, valid_files, write)


def _ids(case):
    return case.name


def _says(err, words):
    message = str(err).lower()
    missing = [w for w in words if w.lower() not in message]
    assert not missing, f"message {str(err)!r} lacks {missing}"


# --- arrays: the reference ------------------------------------------------------------

@pytest.mark.parametrize("case", [c for c in ARRAY_CASES if c.error], ids=_ids)
def test_reference_rejects_bad_arrays_with_a_typed_error(case):
    with pytest.raises(InputError) as err:
        PolyhedralSurface.from_arrays(case.V, case.F)
    assert type(err.value) is case.error, f"{type(err.value).__name__}: {err.value}"
    _says(err.value, case.words)


@pytest.mark.parametrize("case", [c for c in ARRAY_CASES if c.geometry_error], ids=_ids)
def test_degenerate_geometry_is_valid_input_but_quantities_raise(case):
    s = PolyhedralSurface.from_arrays(case.V, case.F)
    assert s.triangulation.euler_characteristic() == 2        # combinatorics still answers
    for quantity in (angle_defects, cotan_laplacian, vertex_areas_barycentric,
                     vertex_areas_voronoi, mean_curvature):
        with pytest.raises(case.geometry_error) as err:
            quantity(s)
        _says(err.value, case.geometry_words)
    # the exact reference as an implementation says the same through its float interface
    with pytest.raises(DegenerateFace):
        ReferenceImplementation().cotan_laplacian(np.array(case.V, float), np.array(case.F))


def test_inconsistent_orientation_is_valid_but_signed_quantities_name_the_edge():
    bad = PolyhedralSurface.from_arrays(TET_V, [[0, 1, 2]] + TET_F[1:])
    good = PolyhedralSurface.from_arrays(TET_V, TET_F)
    # orientability belongs to the surface, not to the orientation the faces were given in
    assert bad.triangulation.is_orientable() and bad.triangulation.reversed_gluing(0)
    # intrinsic quantities do not see orientation
    assert angle_defects(bad) == angle_defects(good)
    assert cotan_laplacian(bad) == cotan_laplacian(good)
    for signed in (dihedral_angles, mean_curvature):
        with pytest.raises(InputError, match=r"edge \d+ .*oriented inconsistently"):
            signed(bad)


@pytest.mark.parametrize("mesh, scale", [
    ((TET_V, TET_F), 1e300), ((TET_V, TET_F), 1e-300),
    # powers of two keep the float products exact, so the scaled icosahedron is similar
    ((ICO_V, ICO_F), 2.0 ** 997), ((ICO_V, ICO_F), 2.0 ** -997)])
def test_huge_and_tiny_coordinates_are_computed_exactly(mesh, scale):
    V, F = mesh
    unit = PolyhedralSurface.from_arrays(V, F)
    scaled = PolyhedralSurface.from_arrays([[x * scale for x in p] for p in V], F)
    s = Fraction(scale)
    assert scaled.positions == tuple(tuple(x * s for x in p) for p in unit.positions)
    # angles and cotan weights are scale invariant, areas scale by s^2: exactly
    assert angle_defects(scaled) == angle_defects(unit)
    assert cotan_laplacian(scaled) == cotan_laplacian(unit)
    assert scaled.metric().total_area() == s * s * unit.metric().total_area()
    assert vertex_areas_voronoi(scaled) == [s * s * a for a in vertex_areas_voronoi(unit)]


def test_huge_and_ordinary_coordinates_mixed_keep_gauss_bonnet_exact():
    V = [list(p) for p in TET_V]
    V[3] = [1e-300, 1e300, 1.0]            # a needle: angles near 0 and pi, exactly
    assert gauss_bonnet_holds(PolyhedralSurface.from_arrays(V, TET_F))


# --- arrays: the adapters' check ---------------------------------------------------

@pytest.mark.parametrize("case", ARRAY_CASES, ids=_ids)
def test_adapter_array_check_on_the_same_corpus(case):
    if case.adapter_error is None:
        # mesh-level problems go through to the library, as float64 / int64 n x 3 arrays
        V, F = checked_arrays(case.V, case.F)
        assert V.dtype == np.float64 and F.dtype == np.int64
        assert V.shape[1] == 3 and F.shape[1] == 3 and F.min() >= 0 and F.max() < len(V)
        assert np.isfinite(V).all()
        return
    with pytest.raises(InputError) as err:
        checked_arrays(case.V, case.F)
    assert type(err.value) is case.adapter_error, f"{type(err.value).__name__}: {err.value}"
    _says(err.value, case.adapter_words)
    assert isinstance(err.value, ValueError)       # what adapters and their callers catch


# --- face lists and lengths -------------------------------------------------------

@pytest.mark.parametrize("case", TRIANGULATION_CASES, ids=_ids)
def test_triangulation_rejects_bad_face_lists(case):
    with pytest.raises(InputError) as err:
        Triangulation.from_faces(case.faces, n_vertices=case.n_vertices)
    assert type(err.value) is case.error
    _says(err.value, case.words)


@pytest.mark.parametrize("case", LENGTH_CASES, ids=_ids)
def test_piecewise_flat_surface_rejects_bad_lengths(case):
    t = Triangulation.from_faces(case.faces)
    build = PiecewiseFlatSurface if case.squared else PiecewiseFlatSurface.from_lengths
    with pytest.raises(InputError) as err:
        build(t, case.values)
    assert type(err.value) is case.error, f"{type(err.value).__name__}: {err.value}"
    _says(err.value, case.words)


def test_piecewise_flat_surface_needs_a_triangulation():
    with pytest.raises(InputError, match="expected a Triangulation, got list"):
        PiecewiseFlatSurface([[0, 1, 2]], [1, 1, 1])
    with pytest.raises(InputError, match="expected a Triangulation, got list"):
        PolyhedralSurface([[0, 1, 2]], TET_V[:3])


@pytest.mark.parametrize("length", [1e300, 1e-300])
def test_huge_and_tiny_lengths_are_exact(length):
    t = Triangulation.from_faces([[0, 1, 2]])
    s = PiecewiseFlatSurface.from_lengths(t, [length] * 3)
    assert s.area(0) == Fraction(length) ** 2 * sqrt(3) / 4
    assert s.corner_cot(0, 0) == 1 / sqrt(3)


# --- files -----------------------------------------------------------------------

@pytest.mark.parametrize("case", FILE_CASES, ids=_ids)
def test_malformed_files_give_one_mesh_file_error(tmp_path, case):
    path = write(case, tmp_path)
    with pytest.raises(MeshFileError) as err:
        read_mesh(path)
    assert type(err.value) is MeshFileError and isinstance(err.value, InputError)
    message = str(err.value)
    assert message.startswith(str(path)) and "\n" not in message     # names the file, one line
    _says(message, case.words)


@pytest.mark.parametrize("case", MESH_FILE_CASES, ids=_ids)
def test_well_formed_files_of_bad_meshes_are_rejected_by_the_reference(tmp_path, case):
    V, F = read_mesh(write(case, tmp_path))      # the file itself is fine
    with pytest.raises(InputError) as err:
        PolyhedralSurface.from_arrays(V, F)
    assert type(err.value) is case.error
    _says(err.value, case.words)


@pytest.mark.parametrize("variant", sorted(valid_files()))
def test_every_valid_variant_reads_back_the_icosahedron(tmp_path, variant):
    name, content = valid_files()[variant]
    p = tmp_path / name
    p.write_bytes(content)
    V, F = read_mesh(p)
    if name.endswith(".stl"):               # float32 soup, merged back in order of appearance
        assert len(V) == len(ICO_V) and len(F) == len(ICO_F)
        assert PolyhedralSurface.from_arrays(V, F).triangulation.euler_characteristic() == 2
    else:
        assert (V, F) == (ICO_V, ICO_F)


def test_missing_file_and_directory(tmp_path):
    with pytest.raises(MeshFileError, match="cannot read"):
        read_mesh(tmp_path / "absent.obj")
    (tmp_path / "d.obj").mkdir()
    with pytest.raises(MeshFileError, match="cannot read"):
        read_mesh(tmp_path / "d.obj")


# --- guards ------------------------------------------------------------------------

def test_term_limit_says_which_limit_and_how_to_raise_it():
    primes = [2, 3, 5, 7, 11, 13]
    with limits(term_limit=4):
        with pytest.raises(TermLimitExceeded) as err:
            sum((sqrt(p) for p in primes), start=sqrt(1))
    _says(err.value, ("5 terms", "term limit 4", "ddg_oracle.reference.exact.limits(term_limit="))
    with limits(term_limit=8):                     # raised as the message says: fine
        assert sum((sqrt(p) for p in primes), start=sqrt(1)).n_terms == 7


def test_term_limit_reached_inside_a_reference_quantity():
    # a float mesh: one square root per face area, summed into many terms
    V = [[x + 0.1 * i * (k + 1) for k, x in enumerate(p)] for i, p in enumerate(ICO_V)]
    s = PolyhedralSurface.from_arrays(V, ICO_F)
    with limits(term_limit=3):
        with pytest.raises(TermLimitExceeded) as err:
            s.metric().total_area()
    _says(err.value, ("term limit 3", "limits(term_limit="))
    assert s.metric().total_area() > 0                      # default limit: fine


def test_time_limit_per_example_names_the_property_and_the_setting():
    with pytest.raises(TimeLimitExceeded) as err:
        with example_time_limit("[D1.6] demo", seconds=0.05):
            while True:
                pass
    _says(err.value, ("[D1.6] demo", "time limit of 0.05 s", f"{TIME_LIMIT_ENV}=SECONDS"))


@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")
def test_time_limit_that_fires_inside_a_finalizer_still_stops_the_example():
    # Python prints and swallows an exception raised inside __del__ (or a garbage-collector
    # callback, which Hypothesis installs): the overrun must not be lost with it
    import time

    class Slow:
        def __del__(self):
            time.sleep(0.3)

    t0 = time.monotonic()
    with pytest.raises(TimeLimitExceeded, match="time limit of 0.05 s"):
        with example_time_limit("[D1.6] demo", seconds=0.05):
            Slow().__class__       # the instance is finalized at once, the timer fires there
    assert time.monotonic() - t0 < 2


def test_time_limit_setting(monkeypatch):
    monkeypatch.delenv(TIME_LIMIT_ENV, raising=False)
    assert time_limit_seconds() == 120
    monkeypatch.setenv(TIME_LIMIT_ENV, "0")
    assert time_limit_seconds() is None
    monkeypatch.setenv(TIME_LIMIT_ENV, "2.5")
    assert time_limit_seconds() == 2.5
    monkeypatch.setenv(TIME_LIMIT_ENV, "soon")
    with pytest.raises(InputError, match=f"{TIME_LIMIT_ENV}='soon' is not a number"):
        time_limit_seconds()


class _SlowOnLargeMeshes(ReferenceImplementation):
    name = "slow-on-large-meshes"

    def euler_characteristic(self, V, F):
        if len(F) > 12:
            time.sleep(30)                 # cut short by the time limit
        return super().euler_characteristic(V, F)


def test_property_run_reports_an_overrunning_example_and_goes_on(monkeypatch):
    monkeypatch.setenv(TIME_LIMIT_ENV, "0.2")
    quick = settings(max_examples=10, deadline=None, database=None, derandomize=True,
                     phases=[Phase.generate])       # no shrinking: each try costs 0.2 s
    r = run_property(PROPERTIES["D1.6"], _SlowOnLargeMeshes(), quick)
    # the clock stopped the implementation's own call: its hang, not the reference's time
    assert r.status == CRASHED
    _says(r.error, ("hang:", "slow-on-large-meshes.euler_characteristic", "0.2 s",
                    TIME_LIMIT_ENV))
    assert r.example.triangulation.n_faces > 12                    # the input that overran
    monkeypatch.setenv(TIME_LIMIT_ENV, "0")
    fine = run_property(PROPERTIES["X1.4"], ReferenceImplementation(), quick)
    assert fine.status != CRASHED


def test_reference_float_views_beyond_the_float_range_are_inf():
    import math

    import numpy as np

    from ddg_oracle.oracles.exact_reference import ReferenceImplementation
    V = np.array([[0.0, 0, 0], [1e300, 0, 0], [0, 1e300, 0]])
    F = np.array([[0, 1, 2]])
    r = ReferenceImplementation()
    assert r.area(V, F) == math.inf                      # exactly 5e599: beyond every double
    assert list(r.vertex_areas_voronoi(V, F)) == [math.inf] * 3
    # scale-free views stay finite: three correctly rounded angles summing to pi
    assert abs(r.corner_angles(V, F).sum() - math.pi) <= 4 * np.finfo(float).eps * math.pi


# --- paths that must not hang or exhaust memory (issue: readers with bounds) ----------------------

#: runs argv[1:] and prints the child's peak RSS (KiB).  The peak of a process started
#: straight from the test process would include the test process's own size: Linux keeps
#: the high-water mark of the memory a process had before exec (subprocess forks, or
#: vforks, the pytest worker, some 500 MB late in a run).  A small wrapper's child
#: starts from the wrapper's few MB instead.
_PEAK = ("import os, subprocess, sys\n"
         "p = subprocess.Popen(sys.argv[1:], stdout=subprocess.DEVNULL)\n"
         "_, status, usage = os.wait4(p.pid, 0)\n"
         "print(os.waitstatus_to_exitcode(status), usage.ru_maxrss)\n")


def _ddg_oracle_bounded(args, seconds=5.0):
    """Run ``ddg-oracle ARGS``: (exit code, stderr, wall seconds, peak RSS in MB) of the
    ddg-oracle process alone (see _PEAK); killed if it runs 6x too long."""
    import os
    import signal
    import subprocess
    import sys
    import tempfile
    import time
    with tempfile.TemporaryFile("w+") as err_file:
        t0 = time.monotonic()
        p = subprocess.Popen([sys.executable, "-c", _PEAK, sys.executable, "-m", "ddg_oracle",
                              *args], stdout=subprocess.PIPE, stderr=err_file, text=True,
                             start_new_session=True)
        try:
            out, _ = p.communicate(timeout=6 * seconds)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            out, _ = p.communicate()
        wall = time.monotonic() - t0
        err_file.seek(0)
        err = err_file.read()
    if not out.strip():
        return -9, err, wall, float("inf")       # killed: ran too long
    rc, kib = map(int, out.split())
    return rc, err, wall, kib / 1024


@pytest.mark.parametrize("command", ["check", "compare"])
def test_hostile_paths_are_one_line_and_exit_2_fast_and_small(tmp_path, command):
    for what, (path, words) in hostile_paths(tmp_path).items():
        args = ["check", "--mesh", path, "--impl", "reference", "--workers", "1"] \
            if command == "check" else ["compare", path, "--impl", "reference"]
        rc, err, wall, peak = _ddg_oracle_bounded(args)
        assert rc == 2, (what, rc, err)
        assert err.startswith("ddg-oracle: error:") and err.count("\n") == 1, (what, err)
        assert words in err, (what, err)
        assert wall < 5.0, (what, wall)
        assert peak < 500, (what, peak)


def test_a_mesh_file_over_the_size_limit_is_refused(tmp_path, monkeypatch):
    from ddg_oracle.application.meshfiles import SIZE_ENV
    path = tmp_path / "t.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    monkeypatch.setenv(SIZE_ENV, "20")
    with pytest.raises(MeshFileError, match=f"over the limit of 20 .*{SIZE_ENV}"):
        read_mesh(path)
    monkeypatch.setenv(SIZE_ENV, "1K")
    assert read_mesh(path)[1] == [[0, 1, 2]]


def test_compare_answers_a_single_triangle(tmp_path):
    import subprocess
    import sys
    path = tmp_path / "one.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    out = subprocess.run([sys.executable, "-m", "ddg_oracle", "compare", str(path),
                          "--impl", "libigl"], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "edge_mean_curvature" in out.stdout and "no element to compare" in out.stdout
    assert "DIFFERS" not in out.stdout and "Traceback" not in out.stderr
