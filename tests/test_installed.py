"""ddg-oracle installed from a wheel, outside the repository, in someone else's project.

The wheel is built from the working tree's tracked files, installed into a fresh
virtual environment in a temporary directory, and used from a throw-away user
project that has its own ``properties.py``, ``reference/__init__.py`` and
``oracles.py`` (names our own packages had before they were namespaced), its own
Hypothesis tests, and an implementation with a planted bug.  What is checked:

- the wheel installs one top-level import package, ``ddg_oracle``, and nothing else;
- the user's unrelated tests run with their Hypothesis settings unchanged (100
  examples, the deadline Hypothesis gives), with and without ``CI`` set, although
  our pytest plugin is loaded and ``ddg_oracle.properties`` imported;
- ``pytest --ddg-impl`` and ``ddg-oracle check --impl`` check the user's module and
  find its planted bug; an object with none of the protocol's methods is refused
  with a did-you-mean; ``ddg-oracle theorems --check`` passes from the wheel.

Needs the network or pip's cache for numpy, scipy, hypothesis and pytest (the
core dependencies: the extras are not installed, as a user's ``pip install
ddg-oracle`` would not).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
ENV = {k: v for k, v in os.environ.items()
       if k not in ("CI", "PYTHONPATH", "VIRTUAL_ENV", "HYPOTHESIS_NO_PLUGINS")}

USER_FILES = {
    # the user's own modules, named as our packages once were at top level
    "properties.py": "WHO = 'the user'\n",
    "reference/__init__.py": "WHO = 'the user'\n",
    "oracles.py": "WHO = 'the user'\n",
    # the user's unrelated Hypothesis tests: their strength must not change
    "test_theirs.py": '''
import datetime
import os

from hypothesis import given, settings, strategies as st

import oracles
import properties
import reference


def expected():
    # what Hypothesis itself gives in this environment (its own "ci" profile under CI)
    return settings.get_profile("ci" if os.environ.get("CI") else "default")


def test_their_own_modules_resolve():
    assert properties.WHO == reference.WHO == oracles.WHO == "the user"


@given(st.integers())
def test_their_settings(x):
    s = settings()
    assert s.max_examples == 100
    assert s.deadline == expected().deadline
    assert s.derandomize == expected().derandomize
    if not os.environ.get("CI"):
        assert s.deadline == datetime.timedelta(milliseconds=200)


def test_their_settings_after_importing_ddg_oracle_properties():
    import ddg_oracle.properties  # noqa: F401
    import ddg_oracle.reference as R
    assert R.angle_defects and R.cotan_weights and R.flip_to_delaunay
    assert R.laplace_beltrami and R.area
    assert settings().max_examples == 100
    assert settings().deadline == expected().deadline
''',
    # the user's implementation: Euler characteristic with E = 3F/2, wrong with boundary
    "mymod.py": '''
class Impl:
    name = "mine"

    def euler_characteristic(self, V, F):
        return len(V) - 3 * len(F) // 2 + len(F)
''',
    "typo.py": '''
class Typo:
    def angle_defect(self, V, F):
        return None
''',
}


def _run(args, cwd, env=None, timeout=600):
    return subprocess.run(args, cwd=cwd, env=env or ENV, capture_output=True, text=True,
                          timeout=timeout)


def _copy_tracked_tree(dest: Path) -> None:
    """The working tree's tracked files (symlinks kept), so no stale build/ dir is used."""
    files = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True,
                           check=True).stdout.decode().split("\0")
    for name in filter(None, files):
        src, dst = ROOT / name, dest / name
        if not src.exists() and not src.is_symlink():
            continue                       # deleted in the working tree
        dst.parent.mkdir(parents=True, exist_ok=True)
        if src.is_symlink():
            os.symlink(os.readlink(src), dst)
        else:
            shutil.copy2(src, dst)


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        pytest.skip("needs a git checkout to build the wheel from")
    base = tmp_path_factory.mktemp("installed")
    tree, dist, venv, project = base / "tree", base / "dist", base / "venv", base / "project"
    _copy_tracked_tree(tree)
    out = _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(dist),
                str(tree)], cwd=base)
    assert out.returncode == 0, out.stderr
    wheel = next(dist.glob("ddg_oracle-*.whl"))
    # a venv without its own copy of pip (ensurepip costs seconds), installed into by this
    # environment's pip (--python: the same pip, run by the venv's interpreter); no
    # byte-compiling of every installed file (half of the 11 s install): the tests
    # compile the modules they import
    out = _run([sys.executable, "-m", "venv", "--without-pip", str(venv)], cwd=base)
    assert out.returncode == 0, out.stderr
    python = venv / "bin" / "python"
    out = _run([sys.executable, "-m", "pip", "--python", str(python), "install", "-q",
                "--no-compile", str(wheel), "pytest>=8,<10"], cwd=base)
    assert out.returncode == 0, out.stderr
    for name, text in USER_FILES.items():
        (project / name).parent.mkdir(parents=True, exist_ok=True)
        (project / name).write_text(text.lstrip(), encoding="utf-8")
    return {"wheel": wheel, "python": python, "bin": venv / "bin", "project": project}


def test_the_wheel_installs_one_namespaced_package(installed):
    names = zipfile.ZipFile(installed["wheel"]).namelist()
    top = {n.split("/")[0] for n in names}
    assert {t for t in top if not t.endswith(".dist-info")} == {"ddg_oracle"}
    # what the installed tool reads is installed with it
    for data in ("ddg_oracle/application/traceability.toml", "ddg_oracle/application/data/errata.md",
                 "ddg_oracle/application/data/findings.md"):
        assert data in names


def test_the_wheel_has_no_heavy_hard_dependency(installed):
    meta = next(n for n in zipfile.ZipFile(installed["wheel"]).namelist()
                if n.endswith(".dist-info/METADATA"))
    text = zipfile.ZipFile(installed["wheel"]).read(meta).decode()
    hard = [line for line in text.splitlines()
            if line.startswith("Requires-Dist:") and "extra ==" not in line]
    assert sorted(line.split()[1].split(">")[0].split("<")[0] for line in hard) == \
        ["hypothesis", "numpy", "scipy"]


@pytest.mark.parametrize("ci", [False, True])
def test_their_hypothesis_tests_keep_their_strength(installed, ci):
    env = dict(ENV, CI="true") if ci else ENV
    out = _run([str(installed["python"]), "-m", "pytest", "-q", "-p", "no:cacheprovider",
                "test_theirs.py"], cwd=installed["project"], env=env)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "3 passed" in out.stdout
    # the plugin was loaded (and so had its chance to do harm)
    plugins = _run([str(installed["python"]), "-m", "pytest", "--help"],
                   cwd=installed["project"], env=env)
    assert "--ddg-impl" in plugins.stdout


def test_pytest_plugin_finds_the_planted_bug(installed):
    out = _run([str(installed["python"]), "-m", "pytest", "-q", "-p", "no:cacheprovider",
                "--ddg-impl", "mymod:Impl", "--ddg-only", "D1.6", "test_theirs.py"],
               cwd=installed["project"])
    assert out.returncode == 1, out.stdout + out.stderr
    assert "ddg[mymod:Impl][D1.6]" in out.stdout and "3 passed" in out.stdout


def test_cli_finds_the_planted_bug(installed):
    out = _run([str(installed["bin"] / "ddg-oracle"), "check", "--impl", "mymod:Impl",
                "--only", "D1.6", "--workers", "1"], cwd=installed["project"])
    assert out.returncode == 1, out.stdout + out.stderr
    assert "FAILED" in out.stdout and "Traceback" not in out.stderr


def test_cli_refuses_an_object_without_protocol_methods(installed):
    out = _run([str(installed["bin"] / "ddg-oracle"), "check", "--impl", "typo:Typo"],
               cwd=installed["project"])
    assert out.returncode == 2, out.stdout + out.stderr
    assert "did you mean `angle_defects` for `angle_defect`" in out.stderr


def test_theorems_check_passes_from_the_wheel(installed):
    out = _run([str(installed["bin"] / "ddg-oracle"), "theorems", "--check"],
               cwd=installed["project"])
    assert out.returncode == 0, out.stdout + out.stderr
    assert "traceability table and notes table: true" in out.stdout


def test_cli_says_which_libraries_are_not_installed(installed):
    out = _run([str(installed["bin"] / "ddg-oracle"), "check", "--only", "D1.6",
                "--workers", "1"], cwd=installed["project"])
    assert out.returncode == 0, out.stdout + out.stderr
    assert "libigl is not installed" in out.stderr and "pip install 'ddg-oracle[libigl]'" in out.stderr


def test_the_wheel_writes_the_committed_test_vectors(installed, tmp_path):
    """With only the hard dependencies and no repository around: the same bytes."""
    out = _run([str(installed["bin"] / "ddg-oracle"), "vectors", "--out", str(tmp_path)],
               cwd=installed["project"])
    assert out.returncode == 0, out.stdout + out.stderr
    committed = ROOT / "vectors"
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(p.name for p in committed.iterdir())
    for p in committed.iterdir():
        assert (tmp_path / p.name).read_bytes() == p.read_bytes(), p.name
    out = _run([str(installed["bin"] / "ddg-oracle"), "verify", str(tmp_path), "--impl",
                "reference"], cwd=installed["project"])
    assert out.returncode == 0 and " 0 FAIL" in out.stdout, out.stdout + out.stderr
