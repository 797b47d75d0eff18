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
