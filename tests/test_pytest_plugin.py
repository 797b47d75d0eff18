"""The pytest plugin: `pytest --ddg-impl module:object` runs every property on an implementation."""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _pytest(*args, cwd):
    # the plugin is loaded through its pytest11 entry point (the package is installed)
    return subprocess.run([sys.executable, "-m", "pytest",
                           "-p", "no:cacheprovider", "-q", *args],
                          cwd=cwd, capture_output=True, text=True,
                          env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})


def test_plugin_passes_the_reference(tmp_path):
    out = _pytest("--ddg-impl", "reference", "--ddg-only", "D1.6", "--ddg-only", "X1.4", cwd=tmp_path)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "2 passed" in out.stdout


def test_plugin_fails_a_planted_bug_with_the_counterexample(tmp_path):
    mod = tmp_path / "mytopology.py"
    mod.write_text(
        "class Impl:\n"
        "    name = 'mine'\n"
        "    def euler_characteristic(self, V, F):\n"
        "        return len(V) - 3 * len(F) // 2 + len(F)   # assumes a closed surface\n")
    out = _pytest("--ddg-impl", "mytopology:Impl", "--ddg-only", "D1.6", "--ddg-only", "T1.1 / C1.2",
                  "--ddg-profile", "ci", cwd=tmp_path)
    assert out.returncode == 1, out.stdout + out.stderr
    assert "1 failed" in out.stdout and "1 skipped" in out.stdout     # T1.1 not applicable
    assert "[D1.6] mine: wrong Euler characteristic" in out.stdout
    assert "V = [" in out.stdout and "F = [" in out.stdout            # the shrunk mesh is shown


def test_plugin_reports_an_unknown_implementation_as_usage_error(tmp_path):
    out = _pytest("--ddg-impl", "nowhere:Nothing", cwd=tmp_path)
    assert out.returncode == 4 and "cannot import your module 'nowhere'" in out.stderr


def test_plugin_fails_a_hang_and_an_incomplete_item(tmp_path):
    # issue 40: a call that never returns was "passed (1 example)"; a search its budget cut
    # short is not a pass either
    (tmp_path / "mine.py").write_text(
        "import time\n"
        "from ddg_oracle.oracles.exact_reference import ReferenceImplementation\n"
        "class Hangs:\n"
        "    name = 'hangs'\n"
        "    def euler_characteristic(self, V, F):\n"
        "        while True:\n"
        "            time.sleep(0.05)\n"
        "class Slow(ReferenceImplementation):\n"
        "    name = 'slow'\n"
        "    def euler_characteristic(self, V, F):\n"
        "        time.sleep(0.3)\n"
        "        return super().euler_characteristic(V, F)\n")
    out = _pytest("--ddg-impl", "mine:Hangs", "--ddg-impl", "mine:Slow", "--ddg-only", "D1.6",
                  "--ddg-budget", "1.5", cwd=tmp_path)
    assert out.returncode == 1, out.stdout + out.stderr
    assert "2 failed" in out.stdout
    assert "hang: hangs.euler_characteristic did not return" in out.stdout
    assert "[D1.6] slow: incomplete" in out.stdout and "of 25 examples ran" in out.stdout


#: chi and a near miss (cotmatrix), and a property that raises when read
_HALF = """
from ddg_oracle.oracles.exact_reference import ReferenceImplementation


class Half:
    name = "half"

    def euler_characteristic(self, V, F):
        return ReferenceImplementation().euler_characteristic(V, F)

    def cotmatrix(self, V, F):
        return None

    @property
    def costly(self):
        raise RuntimeError("computed on demand")
"""

#: angle defects times k, a constructor option
_SCALED = """
from ddg_oracle.oracles.exact_reference import ReferenceImplementation


class Scaled(ReferenceImplementation):
    def __init__(self, k=1):
        self.k, self.name = k, f"scaled-{k}"

    def angle_defects(self, V, F):
        return self.k * super().angle_defects(V, F)
"""


def test_a_near_miss_hint_under_warnings_as_errors_stops_nothing(tmp_path):
    """With filterwarnings = error, the hint ("cotmatrix is not a protocol method") was
    raised at configuration time: INTERNALERROR, and the user's own tests never ran.  A
    property that raises when read stopped the plugin the same way."""
    (tmp_path / "pytest.ini").write_text("[pytest]\nfilterwarnings =\n    error\n")
    (tmp_path / "test_theirs.py").write_text("def test_theirs():\n    assert True\n")
    (tmp_path / "mine.py").write_text(_HALF)
    out = _pytest("--ddg-impl", "mine:Half", "--ddg-only", "D1.6", cwd=tmp_path)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "2 passed" in out.stdout and "did you mean `cotan_laplacian`" in out.stdout


def test_the_replay_of_a_failure_builds_the_implementation_with_its_options(tmp_path):
    """The plugin's replay loaded 'scaled:Scaled' for --ddg-impl 'scaled:Scaled(k=2)': the
    class with no options, which does not fail, under "reproduce (raises the same
    failure)"."""
    (tmp_path / "scaled.py").write_text(_SCALED)
    out = _pytest("--ddg-impl", "scaled:Scaled(k=2)", "--ddg-only", "D2.2", cwd=tmp_path)
    assert out.returncode == 1, out.stdout + out.stderr
    assert "load_implementation('scaled:Scaled(k=2)')" in out.stdout, out.stdout
