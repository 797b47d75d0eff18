"""Every finding in docs/findings.md is reproduced by its snippet (each asserts the
disagreement, so a library fix or a wrong entry makes this fail)."""

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
TEXT = (ROOT / "docs" / "findings.md").read_text(encoding="utf-8")
SECTIONS = {s.split("\n", 1)[0]: s for s in TEXT.split("\n## ")[1:]}
SNIPPETS = {name: m[1] for name, s in SECTIONS.items()
            for m in [re.search(r"```python\n(.*?)```", s, re.S)] if m}


def test_every_finding_of_the_summary_has_a_section_and_a_snippet():
    summary = re.findall(r"^\| \[(\w+)\]\(#\w+\)", TEXT, re.M)
    assert summary and set(summary) == set(SNIPPETS)


@pytest.mark.parametrize("finding", sorted(SNIPPETS))
def test_snippet_reproduces_the_finding(finding, tmp_path):
    script = tmp_path / f"{finding}.py"
    script.write_text(SNIPPETS[finding], encoding="utf-8")
    out = subprocess.run([sys.executable, str(script)], cwd=ROOT, capture_output=True, text=True,
                         timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr
    assert out.stdout.strip()                         # it prints the values it compares
