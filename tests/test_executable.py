"""The executable protocol: programs in any language checked through ``exec:COMMAND``.

A C++ driver (examples/cpp/cotan_driver.cpp, built here with g++) passes the cotan
properties and its planted bug is caught on one triangle, by ``ddg-oracle check`` and
by the pytest plugin; the Python server (``serve``) round-trips every value shape; a
driver that dies, segfaults, hangs, writes garbage or answers the wrong shape or id is
reported as a crash with its input, and the run goes on.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from ddg_oracle.oracles.exact_reference import ReferenceImplementation
from ddg_oracle.oracles.executable import DriverFailed, Executable
from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.profiles import profile, profile_budget
from ddg_oracle.protocol.methods import OutsideDomain
from ddg_oracle.properties.runner import CRASHED, FAILED, PASSED, run_property
from ddg_oracle.reference import surfaces

ROOT = Path(__file__).resolve().parent.parent
DRIVER = [sys.executable, str(ROOT / "tests" / "misbehaving_driver.py")]
TET = surfaces.tetrahedron().to_arrays()


def _misbehaving(mode: str, timeout: float = 10.0) -> Executable:
    return Executable(DRIVER + [mode], timeout=timeout)


@pytest.fixture(scope="module")
def cpp_driver(tmp_path_factory):
    compiler = shutil.which("g++") or shutil.which("c++")
    if compiler is None:
        pytest.skip("needs a C++ compiler")
    exe = tmp_path_factory.mktemp("cpp") / "cotan_driver"
    out = subprocess.run([compiler, "-O2", "-std=c++17", "-o", str(exe),
                          str(ROOT / "examples" / "cpp" / "cotan_driver.cpp")],
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    return exe


def test_the_cpp_driver_agrees_with_the_reference(cpp_driver):
    impl = Executable(str(cpp_driver))
    assert impl.name == "cpp-cotan" and impl.methods == {"cotan_laplacian"}
    V, F = TET
    L = impl.cotan_laplacian(np.array(V, float), np.array(F))
    ref = ReferenceImplementation().cotan_laplacian(np.array(V, float), np.array(F))
    assert abs(L - ref).max() < 8 * np.finfo(float).eps
    for pid in ("D3.1", "T3.6", "C3.3"):
        assert run_property(PROPERTIES[pid], impl, profile("ci")).status == PASSED, pid
    impl.close()


def test_the_cpp_drivers_planted_bug_is_caught_on_one_triangle_by_the_cli(cpp_driver):
    out = subprocess.run([sys.executable, "-m", "ddg_oracle", "check", "--impl",
                          f"exec:{cpp_driver} --bug=boundary", "--only", "D3.1", "--profile",
                          "ci", "--workers", "1"], cwd=ROOT, capture_output=True, text=True,
                         timeout=600)
    assert out.returncode == 1, out.stdout + out.stderr
    assert "[D3.1] cpp-cotan-boundary-bug" in out.stdout
    faces = int(re.search(r"mesh: \d+ vertices, (\d+) faces", out.stdout).group(1))
    assert faces <= 2
    where = re.search(r"counterexample files \(mesh.obj, reproduce.py\):\s+(\S+)", out.stdout)
    [snippet] = Path(where.group(1)).glob("failures/*/reproduce.py")
    assert f"load_implementation('exec:{cpp_driver} --bug=boundary')" in snippet.read_text()
    rerun = subprocess.run([sys.executable, str(snippet)], cwd="/", capture_output=True,
                           text=True, timeout=120)
    assert "PropertyFailure: [D3.1] cpp-cotan-boundary-bug" in rerun.stderr


def test_the_cpp_driver_in_the_pytest_plugin(cpp_driver, tmp_path):
    out = subprocess.run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-q",
                          "--ddg-impl", f"exec:{cpp_driver} --bug=sign", "--ddg-only", "D3.1",
                          "--ddg-profile", "ci"], cwd=tmp_path, capture_output=True, text=True,
                         timeout=600)
    assert out.returncode == 1, out.stdout + out.stderr
    assert "1 failed" in out.stdout and "[D3.1] cpp-cotan-sign-bug" in out.stdout


def test_the_python_server_round_trips_every_protocol_value():
    impl = Executable([sys.executable, str(ROOT / "examples" / "exec_numpy_cotan.py")],
                      timeout=30)
    assert impl.name == "numpy-cotan" and impl.methods == {"cotan_laplacian"}
    V, F = (np.array(a) for a in surfaces.disk(5).to_arrays())
    from examples.numpy_cotan import NumpyCotan
    assert abs(impl.cotan_laplacian(V.astype(float), F) - NumpyCotan().cotan_laplacian(V, F)).max() == 0
    impl.close()


@pytest.mark.parametrize("mode, words", [
    ("dies", "closed its output"), ("segfault", "signal SIGSEGV"),
    ("hangs", "no answer within 2 s"), ("garbage", "not JSON"),
    ("wrong-shape", "expected a sparse matrix"), ("wrong-id", "to request id"),
])
def test_a_misbehaving_driver_is_a_crash_with_its_message(mode, words):
    impl = _misbehaving(mode, timeout=2.0)
    V, F = TET
    if mode == "wrong-shape":              # a right answer to the other method first
        assert impl.euler_characteristic(V, F) == 2
    with pytest.raises(DriverFailed, match=words) as err:
        impl.cotan_laplacian(V, F)
    if mode == "segfault":
        assert "it printed: driver.c:17" in str(err.value)
    impl.close()


def test_blank_lines_before_answers_are_skipped_not_a_crash():
    # console.log() with nothing to print: it was "answered a line that is not JSON: ''"
    impl = _misbehaving("blank-lines")
    V, F = TET
    assert impl.euler_characteristic(V, F) == 2 and impl.euler_characteristic(V, F) == 2
    impl.close()


def test_a_driver_restarts_after_dying_and_declines_and_fails_are_answers():
    flaky = _misbehaving("flaky")
    V, F = TET
    assert flaky.euler_characteristic(V, F) == 2
    with pytest.raises(DriverFailed, match="exited with code 3"):
        flaky.euler_characteristic(V, F)
    assert flaky.euler_characteristic(V, F) == 2          # a fresh process
    flaky.close()
    with pytest.raises(OutsideDomain):
        _misbehaving("outside").euler_characteristic(V, F)
    with pytest.raises(DriverFailed, match="failed: not written yet"):
        _misbehaving("fails").euler_characteristic(V, F)


def test_a_crashing_driver_is_a_crashed_result_and_the_run_goes_on():
    segfault = _misbehaving("segfault", timeout=5.0)
    # with the task budget the command gives it (crashes counted): not 100 restarts to shrink
    r = run_property(PROPERTIES["D3.1"], segfault, profile("default"),
                     budget=profile_budget("default"))
    assert r.status == CRASHED and "SIGSEGV" in r.error and r.mesh is not None
    ok = _misbehaving("ok")
    assert run_property(PROPERTIES["D1.6"], ok, profile("default")).status == PASSED
    wrong = run_property(PROPERTIES["D3.1"], ok, profile("ci"))    # an empty matrix
    assert wrong.status == FAILED
    segfault.close()
    ok.close()


def test_an_unstartable_command_is_a_usage_error(capsys):
    from ddg_oracle.application.cli import main
    assert main(["check", "--impl", "exec:/no/such/driver", "--only", "D1.6"]) == 2
    err = capsys.readouterr().err
    assert "cannot start" in err and "/no/such/driver" in err and err.count("\n") == 1


_NO_HANDSHAKE = '''
import json, sys
for line in sys.stdin:
    request = json.loads(line)
    if request["method"] == "hello":
        sys.exit(5)                       # a manifest stands for the handshake: none is sent
    chi = len(request["V"]) - len({tuple(sorted(e)) for f in request["F"]
                                   for e in zip(f, f[1:] + f[:1])}) + len(request["F"])
    print(json.dumps({"id": request["id"], "value": chi}), flush=True)
'''


def test_a_manifest_stands_for_the_handshake(tmp_path):
    import json
    (tmp_path / "chi.py").write_text(_NO_HANDSHAKE)
    manifest = {"command": [sys.executable, "chi.py"], "name": "chi-by-manifest",
                "methods": ["euler_characteristic"],
                "conventions": {"follows": {"X9": "a declared difference"},
                                "counterpart": "other.json"}}
    (tmp_path / "chi.json").write_text(json.dumps(manifest))
    impl = Executable(str(tmp_path / "chi.json"), cwd="/")
    assert impl.name == "chi-by-manifest" and impl.methods == {"euler_characteristic"}
    assert impl.argv[1] == str(tmp_path / "chi.py")             # relative to the manifest
    assert impl.conventions["counterpart"] == f"exec:{tmp_path / 'other.json'}"
    V, F = TET
    assert impl.euler_characteristic(np.array(V, float), np.array(F)) == 2
    assert run_property(PROPERTIES["D1.6"], impl, profile("ci")).status == PASSED
    impl.close()
    (tmp_path / "bad.json").write_text(json.dumps({"methods": ["area"]}))
    with pytest.raises(DriverFailed, match="command"):
        Executable(str(tmp_path / "bad.json"))


def test_a_handshake_interrupted_never_answers_the_next_request():
    """A program restarted inside a task whose budget's alarm rang mid-handshake: its hello
    answer stayed in the pipe and the next request read it (no id: "answered ... to request
    id 1", a false crash).  Now the half-started program is stopped; the next call starts a
    fresh one and gets its own answer."""
    from tests.alarms import interrupted

    impl = _misbehaving("slow-hello")
    impl._stop()
    # the alarm rings while the program is still answering the handshake (a second): on a
    # fast machine a plain driver's hello came back within an alarm of 20 ms
    interrupted(impl._start, 0.2)
    V, F = TET
    assert impl.euler_characteristic(np.array(V, float), np.array(F)) == 2
    impl.close()


# --- answers read element by element, declarations checked (a helper's hostile drivers) --------


@pytest.mark.parametrize("method,value,words", [
    ("angle_defects", ["1.5", "2.0"], "strings"),                  # numbers as strings
    ("planar_delaunay", [[0.4, 1.4, 2.4]], "0.4 in an array"),      # 0.4 read as index 0
    ("boundary_loops", [[0.4, 1.4, 2.4]], "not a vertex index"),
    ("is_locally_delaunay", [["yes", "", "yes"]], "not of bools"),  # "" and "yes" as flags
    ("edge_mean_curvature", [[1, 0, 1e9], [0, 1, 0.5]], "given twice"),   # the last one won
    ("edge_mean_curvature", [[0, 1, "0.5"]], "strings"),
    ("cotan_laplacian", {"shape": [2, 2], "rows": [0.4], "cols": [0], "values": [1.0]},
     "not a row index"),
    ("cotan_laplacian", {"shape": [2, 2], "rows": [0], "cols": [0], "values": ["1"]}, "strings"),
    ("intrinsic_delaunay_triangulation", {"F": [[0, 1, 2]], "l2": [["1", "1", "1"]]},
     "strings"),
    ("euler_characteristic", 2.5, "not an integer"),
    ("is_orientable", "true", "not a bool"),
])
def test_a_program_answer_not_of_its_kind_is_refused_not_converted(method, value, words):
    """Each of these was converted by numpy (or a dict) and passed the checks and verify."""
    from ddg_oracle.oracles.executable import decode_value
    with pytest.raises(DriverFailed, match=words):
        decode_value(method, value, 3, 1)


def test_an_integral_number_is_an_integer_as_json_schema_says():
    """``2.0`` validates as an integer against docs/protocol.schema.json; it was refused
    (a correct program crashed on D1.6); a Python implementation's 2.0 was taken."""
    from ddg_oracle.oracles.executable import decode_value
    assert decode_value("euler_characteristic", 2.0, 3, 1) == 2
    assert decode_value("boundary_loops", [[0.0, 1.0, 2.0]], 3, 1) == [[0, 1, 2]]


_EPSILON_DRIVER = '''
import json, sys
for line in sys.stdin:
    request = json.loads(line)
    if request["method"] == "hello":
        print('{"methods": ["area"], "machine_epsilon": %s}' % sys.argv[1], flush=True)
    else:
        print(json.dumps({"id": request["id"], "value": 100.0}), flush=True)
'''


@pytest.mark.parametrize("epsilon", ["1.0", "-1", "NaN", "Infinity", "true", "0.5"])
def test_a_machine_epsilon_that_lets_anything_pass_is_refused_at_the_handshake(
        tmp_path, capsys, epsilon):
    """machine_epsilon 1.0 let angle defects off by 3 rad pass D2.2; Infinity was our
    OverflowError (exit 3); -1 and NaN failed correct programs by nonsense bounds."""
    from ddg_oracle.application.cli import main
    (tmp_path / "eps.py").write_text(_EPSILON_DRIVER)
    rc = main(["check", "--impl", f"exec:{sys.executable} {tmp_path / 'eps.py'} {epsilon}",
               "--only", "T3.9"])
    err = capsys.readouterr().err
    assert rc == 2 and "declares machine_epsilon" in err and err.count("\n") == 1, err


def test_a_python_implementation_declaring_such_an_epsilon_is_refused():
    from ddg_oracle.properties.runner import run_properties
    from ddg_oracle.protocol.methods import BadDeclaration
    coarse = type("Coarse", (ReferenceImplementation,), {"machine_epsilon": 1.0,
                                                         "name": "coarse"})()
    with pytest.raises(BadDeclaration, match="machine_epsilon 1.0"):
        run_properties(coarse, only=["D2.2"])
    exact = type("Exact", (ReferenceImplementation,), {"machine_epsilon": 0, "name": "exact"})()
    assert run_properties(exact, only=["D1.6"])[0].status == PASSED


@pytest.mark.parametrize("hello,words", [
    ('{"methods": [["area"]]}', "methods must be names"),
    ('{"methods": [1, "area"]}', "methods must be names"),
    ('{"methods": ["area"], "conventions": {"laplacian": ["x"]}}', "laplacian is one of"),
    ('{"methods": ["area"], "conventions": {"preset": ["libigl"]}}', "preset must be"),
])
def test_a_handshake_of_the_wrong_shape_is_named_not_a_type_error(tmp_path, hello, words):
    """These were a bare "TypeError: unhashable type" (exit 2, no word of the handshake)."""
    (tmp_path / "h.py").write_text(
        "import json, sys\nfor line in sys.stdin:\n"
        "    if json.loads(line)['method'] == 'hello':\n"
        f"        print({hello!r}, flush=True)\n")
    with pytest.raises(DriverFailed, match=words):
        Executable([sys.executable, str(tmp_path / "h.py")])
