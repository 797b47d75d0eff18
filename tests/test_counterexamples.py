"""Counterexamples are complete and runnable wherever they are shown.

A planted bug in a user's own module (a file in a temporary project, as a user
has it) is caught by ``check_implementation``, by the pytest plugin and by
``ddg-oracle check``; the snippet printed with the failure, run in a fresh
process from another directory, raises the same failure.  A planted crash
gives a ``crashed`` result whose text is the implementation's own exception
(no Hypothesis internals) and whose snippet raises it again.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from ddg_oracle.properties import check_implementation
from ddg_oracle.properties.counterexample import (decode_example, encode_example, exact_mesh,
                                                  mesh_text)
from ddg_oracle.properties.runner import CRASHED, FAILED, run_properties

USER_MODULE = '''
import numpy as np


class EulerBug:
    """V - E + F with E = 3F/2: wrong on every surface with boundary."""
    name = "euler-bug"

    def euler_characteristic(self, V, F):
        return len(V) - 3 * len(F) // 2 + len(F)


class Crashes:
    """Not written yet: raises on every call."""
    name = "crashes"

    def euler_characteristic(self, V, F):
        raise NotImplementedError("euler_characteristic is not written yet")
'''


@pytest.fixture()
def user_project(tmp_path, monkeypatch):
    project = tmp_path / "project"
    project.mkdir()
    (project / "planted_user_impl.py").write_text(USER_MODULE, encoding="utf-8")
    monkeypatch.syspath_prepend(str(project))
    yield project
    sys.modules.pop("planted_user_impl", None)


def snippet_of(text: str) -> str:
    """The reproducing snippet in a failure's text (the indented block after 'reproduce')."""
    lines = text.splitlines()
    start = next(k for k, line in enumerate(lines) if line.strip().startswith("reproduce ("))
    indent = len(lines[start]) - len(lines[start].lstrip()) + 2
    body = []
    for line in lines[start + 1:]:
        if line.strip() and len(line) - len(line.lstrip()) < indent:
            break
        body.append(line)
    return textwrap.dedent("\n".join(body))


def run_elsewhere(code: str, tmp_path: Path) -> subprocess.CompletedProcess:
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir(exist_ok=True)
    (elsewhere / "snippet.py").write_text(code, encoding="utf-8")
    return subprocess.run([sys.executable, "snippet.py"], cwd=elsewhere, capture_output=True,
                          text=True, timeout=300)


def test_check_implementations_failure_reproduces_from_its_own_text(user_project, tmp_path):
    import planted_user_impl

    with pytest.raises(AssertionError) as err:
        check_implementation(planted_user_impl.EulerBug(), only=["D1.6"], profile="ci")
    text = str(err.value)
    assert "V = [" in text and "F = [" in text             # the whole mesh, with positions
    code = snippet_of(text)
    assert "planted_user_impl:EulerBug" in code and str(user_project) in code
    out = run_elsewhere(code, tmp_path)
    assert out.returncode != 0
    assert "PropertyFailure: [D1.6] euler-bug: wrong Euler characteristic" in out.stderr


def test_a_crash_is_the_implementations_own_error_and_reproduces(user_project, tmp_path):
    import planted_user_impl

    [r] = run_properties(planted_user_impl.Crashes(), only=["D1.6"], profile="ci")
    assert r.status == CRASHED
    assert r.error == "NotImplementedError: euler_characteristic is not written yet"
    from ddg_oracle.properties.runner import describe
    text = describe(r)
    assert "Failing test case" not in text and "Explanation" not in text
    assert "V = [" in text
    out = run_elsewhere(snippet_of(text), tmp_path)
    assert out.returncode != 0
    assert "NotImplementedError: euler_characteristic is not written yet" in out.stderr


def test_pytest_plugin_failure_reproduces_from_its_output(user_project, tmp_path):
    out = subprocess.run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-q",
                          "--ddg-impl", "planted_user_impl:EulerBug", "--ddg-only", "D1.6",
                          "--ddg-profile", "ci", "--rootdir", str(user_project)],
                         cwd=user_project, capture_output=True, text=True, timeout=600)
    assert out.returncode == 1, out.stdout + out.stderr
    assert "[D1.6] euler-bug: wrong Euler characteristic" in out.stdout
    rerun = run_elsewhere(snippet_of(out.stdout), tmp_path)
    assert "PropertyFailure: [D1.6] euler-bug" in rerun.stderr


def test_cli_prints_the_snippet_and_writes_the_files(user_project, tmp_path):
    out = subprocess.run([sys.executable, "-m", "ddg_oracle", "check", "--impl",
                          "planted_user_impl:EulerBug", "--only", "D1.6", "--profile", "ci",
                          "--workers", "1"], cwd=user_project, capture_output=True, text=True,
                         timeout=600)
    assert out.returncode == 1, out.stdout + out.stderr
    assert max(len(line) for line in out.stdout.splitlines()) <= 100
    where = re.search(r"counterexample files \(mesh.obj, reproduce.py\):\s+(\S+)", out.stdout)
    assert where is not None, out.stdout
    [folder] = Path(where.group(1)).glob("failures/*")
    rerun = run_elsewhere((folder / "reproduce.py").read_text(), tmp_path)
    assert "PropertyFailure: [D1.6] euler-bug" in rerun.stderr


def test_counterexample_folders_go_where_ddg_counterexamples_says(user_project, tmp_path):
    """$DDG_COUNTEREXAMPLES (created if missing): check's counterexample folder is made
    there, not in the system's temporary directory; a path that cannot hold folders is one
    line and exit 2 before anything runs."""
    home = tmp_path / "artifacts" / "ddg"
    argv = [sys.executable, "-m", "ddg_oracle", "check", "--impl", "planted_user_impl:EulerBug",
            "--only", "D1.6", "--profile", "ci", "--workers", "1"]
    out = subprocess.run(argv, cwd=user_project, capture_output=True, text=True, timeout=600,
                         env={**os.environ, "DDG_COUNTEREXAMPLES": str(home)})
    assert out.returncode == 1, out.stdout + out.stderr
    [made] = home.glob("ddg-oracle-counterexamples-*")
    said = re.search(r"counterexample files \(mesh.obj, reproduce.py\):\s+(\S+)", out.stdout)
    assert said is not None and Path(said.group(1)) == made, out.stdout
    # the folder on a line of its own when the line would pass 100 columns
    assert all(len(x) <= 100 or x == f"  {made}" for x in out.stdout.splitlines()), out.stdout
    assert list(made.glob("failures/*/reproduce.py"))
    blocked = tmp_path / "a-file"
    blocked.write_text("")
    out = subprocess.run(argv, cwd=user_project, capture_output=True, text=True, timeout=600,
                         env={**os.environ, "DDG_COUNTEREXAMPLES": str(blocked / "sub")})
    assert out.returncode == 2 and out.stdout == "", out.stdout + out.stderr
    assert out.stderr.count("\n") == 1 and "DDG_COUNTEREXAMPLES=" in out.stderr, out.stderr


def test_examples_round_trip_and_planar_examples_have_their_mesh():
    from fractions import Fraction
    example = (((Fraction(1, 3), Fraction(0)), (Fraction(1), Fraction(0)), (Fraction(0), 1)),
               ((0, 1, 2),), True)
    assert decode_example(encode_example(example)) == example
    points, faces = exact_mesh(example)
    assert faces == [[0, 1, 2]] and points[0] == [Fraction(1, 3), Fraction(0)]
    text = mesh_text(([[float(c) for c in p] + [0.0] for p in points], faces),
                     exact=(points, faces))
    # 1/3 is not a float: the exact coordinates are shown beside the rounded ones
    assert "0.3333333333333333" in text and "1/3" in text


def test_the_replayed_failure_is_the_same_failure(user_project):
    import planted_user_impl
    from ddg_oracle.properties.counterexample import replay

    [r] = run_properties(planted_user_impl.EulerBug(), only=["D1.6"], profile="ci")
    assert r.status == FAILED
    with pytest.raises(AssertionError) as again:
        replay("D1.6", planted_user_impl.EulerBug(), r.replay)
    assert again.value.expected == r.failure.expected
    assert again.value.observed == r.failure.observed
