"""Every finding in docs/findings.md is reproduced by its snippet (each asserts the
disagreement, so a library fix or a wrong entry makes this fail).  A C++ snippet is
built with the ``// build:`` command of its first line; without its library's headers it
is skipped, unless DDG_ORACLE_REQUIRE_CPP=1 (set by .ci/run, which installs them)."""

import os
import re
import runpy
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
TEXT = (ROOT / "docs" / "findings.md").read_text(encoding="utf-8")
SECTIONS = {s.split("\n", 1)[0]: s for s in TEXT.split("\n## ")[1:]}
SNIPPETS = {name: (m[1], m[2]) for name, s in SECTIONS.items()
            for m in [re.search(r"```(python|cpp)\n(.*?)```", s, re.S)] if m}


def test_every_finding_of_the_summary_has_a_section_and_a_snippet():
    summary = re.findall(r"^\| \[([\w-]+)\]\(#[\w-]+\)", TEXT, re.M)
    assert summary and set(summary) == set(SNIPPETS)


@pytest.mark.parametrize("finding", sorted(SNIPPETS))
def test_snippet_reproduces_the_finding(finding, tmp_path, monkeypatch, capsys):
    language, code = SNIPPETS[finding]
    if language == "cpp":
        out = _built(code, tmp_path)
        assert out.returncode == 0, out.stdout + out.stderr
        stdout = out.stdout
    else:
        # run as `python snippet.py` from the checkout would, but in this process: a fresh
        # interpreter per snippet re-imported its library (0.5-1 s each, 30 s in all); a
        # snippet that can crash the process (F-libigl-4) contains that in its own child
        script = tmp_path / f"{finding}.py"
        script.write_text(code, encoding="utf-8")
        monkeypatch.chdir(ROOT)
        monkeypatch.setattr(sys, "argv", [str(script)])
        runpy.run_path(str(script), run_name="__main__")
        stdout = capsys.readouterr().out
    assert stdout.strip()                             # it prints the values it compares


def _built(code: str, where: Path) -> subprocess.CompletedProcess:
    """Compile a C++ snippet with its ``// build: g++ ... NAME.cpp -o NAME ...`` line, run it.

    The program is kept in examples/cpp/build/findings/, keyed by the hash of the snippet,
    its build line, the compiler's version and the newest file of each library header
    directory it includes (``<CGAL/...>``: /usr/include/CGAL): a second run of the suite
    runs it without compiling CGAL's headers again (4-6 s of CPU per snippet, 17 s for the
    five); a changed snippet, build line, compiler or library (an upgrade rewrites its
    headers) builds anew."""
    import hashlib
    command = shlex.split(re.match(r"// build: (.*)\n", code)[1])
    source = next(a for a in command if a.endswith(".cpp"))
    exe = command[command.index("-o") + 1]
    try:
        version = subprocess.run([command[0], "--version"], capture_output=True, text=True,
                                 timeout=60).stdout
    except OSError:
        version = ""
    key = hashlib.sha256("\0".join((code, " ".join(command), version,
                                     *_headers_stamp(code, command))).encode()).hexdigest()
    kept = ROOT / "examples" / "cpp" / "build" / "findings" / key[:16]
    if not (kept / exe).is_file():
        (where / source).write_text(code, encoding="utf-8")
        built = subprocess.run(command, cwd=where, capture_output=True, text=True, timeout=600)
        if built.returncode and "No such file or directory" in built.stderr \
                and os.environ.get("DDG_ORACLE_REQUIRE_CPP") != "1":
            pytest.skip(f"its library is not installed: {built.stderr.splitlines()[0]}")
        assert built.returncode == 0, built.stderr
        kept.mkdir(parents=True, exist_ok=True)
        os.replace(where / exe, kept / exe)             # whole or not at all
    return subprocess.run([str(kept / exe)], capture_output=True, text=True, timeout=300)


def _headers_stamp(code: str, command: list[str]) -> list[str]:
    """For each library header directory a snippet includes (``#include <Dir/...>``), where
    it is and its newest file's modification time: what a library upgrade changes.  Looked
    for where the compiler looks: the build line's ``-I`` directories, then the system's."""
    out = []
    includes = [Path(a[2:]) for a in command if a.startswith("-I") and len(a) > 2]
    includes += [Path(b) for a, b in zip(command, command[1:]) if a == "-I"]
    for top in sorted(set(re.findall(r"^#include <(\w+)/", code, re.M))):
        for root in (*includes, Path("/usr/include"), Path("/usr/local/include")):
            if (root / top).is_dir():
                newest = max((e.stat().st_mtime_ns for d, _, files in os.walk(root / top)
                              for e in map(lambda f: Path(d) / f, files)), default=0)
                out.append(f"{root / top}:{newest}")
    return out


def test_a_crash_is_the_finding_of_a_crash_and_a_wrong_answer_the_other():
    """libigl has two findings for D4.8 / R4.9: F-libigl-4 (its intrinsic flips never return:
    a hang, or memory exhausted) and F-libigl-6 (a wrong metric on non-orientable meshes).
    A crashed result is the first, a failed one the second (a main job called a
    std::bad_alloc on 7 faces F-libigl-6)."""
    from types import SimpleNamespace

    from ddg_oracle.application.report import known_finding, known_findings
    findings = known_findings()

    def result(status):
        return SimpleNamespace(status=status, implementation="libigl",
                               property_id="D4.8 / R4.9")
    assert known_finding(result("crashed"), findings) == "F-libigl-4"
    assert known_finding(result("FAILED"), findings) == "F-libigl-6"
    # A4.13 calls the same flips: a main job at 750cb8a (seed 2518554403) ran out of memory
    assert known_finding(SimpleNamespace(status="crashed", implementation="libigl",
                                         property_id="A4.13"), findings) == "F-libigl-4"


def test_a_crash_is_never_labeled_with_a_finding_that_is_not_a_crash():
    """A main job (seed 1650902268) labeled CGAL's intrinsic Delaunay hanging on A4.13
    "(known: F-cgal-2)", CGAL's precision limit on that property: a crash fell back to any
    finding of its library and property.  A crash is only a finding that never returns,
    or one whose row says the property found it by a crash (F-libigl-1 on T1.1 / C1.2);
    a wrong answer is never a finding that only never returns."""
    from types import SimpleNamespace

    from ddg_oracle.application.report import known_finding, known_findings
    findings = {f["id"]: f for f in known_findings()}

    def label(impl, prop, status):
        return known_finding(SimpleNamespace(status=status, implementation=impl,
                                             property_id=prop), list(findings.values()))
    assert "A4.13" in findings["F-cgal-2"]["properties"]
    assert label("cgal", "A4.13", "crashed") != "F-cgal-2"
    assert label("cgal", "A4.13", "tie") == "F-cgal-2"
    assert label("libigl", "T1.1 / C1.2", "crashed") == "F-libigl-1"
    assert label("libigl", "R1.6", "FAILED") == "F-libigl-1"
    assert label("libigl", "R1.6", "crashed") is None         # R1.6 found it by an answer
    assert label("libigl", "C4.19", "FAILED") is None          # F-libigl-4 never returns
    assert label("lapy", "R1.6", "FAILED") is None              # F-lapy-4 never returns
    for f in findings.values():                                 # every label is of its kind
        for prop in f["properties"]:
            for status, kind in (("crashed", "crashes"), ("FAILED", "answers")):
                got = label(f["library"], prop, status)
                assert got is None or prop in findings[got][kind], (f["id"], prop, status)
