"""README is the front door: its first example runs as shown, and every link in README and
in the manual's index points to a file that exists (issue 41, item 1)."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text(encoding="utf-8")


def _links(text: str, base: Path) -> list[Path]:
    return [base / m.split("#")[0] for m in re.findall(r"\]\(([^)#][^)]*)\)", text)
            if not m.startswith("http")]


def test_every_link_of_readme_and_the_index_exists():
    index = (ROOT / "docs" / "index.md").read_text(encoding="utf-8")
    missing = [p for p in _links(README, ROOT) + _links(index, ROOT / "docs") if not p.exists()]
    assert not missing, missing


def test_the_index_lists_every_page_of_the_manual():
    index = (ROOT / "docs" / "index.md").read_text(encoding="utf-8")
    listed = {p.name for p in _links(index, ROOT / "docs")}
    pages = {p.name for p in (ROOT / "docs").glob("*.md")} - {"index.md"}
    assert pages <= listed, pages - listed


def test_readme_is_a_front_door():
    assert len(README.splitlines()) <= 170
    first_screen = "\n".join(README.splitlines()[:45])
    assert "ddg-oracle check --impl mygeom:MyGeometry" in first_screen


def test_readme_first_example_runs_as_shown(tmp_path):
    code = re.search(r"Put this in `mygeom.py`.*?```python\n(.*?)```", README, re.S)[1]
    (tmp_path / "mygeom.py").write_text(code, encoding="utf-8")
    command = re.search(r"```bash\n(ddg-oracle check --impl mygeom:MyGeometry)\n```", README)[1]
    exe = str(Path(sys.executable).with_name("ddg-oracle"))
    # README's profile (default) with a seed, so the run is the same every time; one
    # worker: the output is the same in any number (a pool of 2 cost ~30% more CPU)
    out = subprocess.run([exe, *command.split()[1:], "--seed", "1", "--workers", "1"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert out.returncode == 1, out.stdout + out.stderr
    shown = re.search(r"```text\n(.*?)```", README, re.S)[1].splitlines()
    # the lines README shows that do not depend on the seed
    assert out.stdout.startswith(shown[0].split(":")[0])                 # "FAILED (2)"
    assert "mygeom:MyGeometry: angle_defects is wrong" in out.stdout
    assert re.search(r"^  R2\.4 +mygeom:MyGeometry +total curvature != 2 pi chi", out.stdout, re.M)
    # the convention its answer follows, named, and the one line that declares it
    assert "declare conventions = {'boundary_defect': 'two_pi'}" in out.stdout.replace("\n  ", " ")


def test_readme_example_passes_once_it_declares_its_convention(tmp_path):
    """The one line README offers turns the example's failure into a pass: the failure
    was the convention, not a bug."""
    code = re.search(r"Put this in `mygeom.py`.*?```python\n(.*?)```", README, re.S)[1]
    declared = code.replace('    """Corner angles and angle defects, written the plain numpy way."""\n',
                            '    """Corner angles and angle defects, written the plain numpy way."""\n'
                            '    conventions = {"boundary_defect": "two_pi"}\n')
    assert declared != code
    (tmp_path / "mygeom.py").write_text(declared, encoding="utf-8")
    exe = str(Path(sys.executable).with_name("ddg-oracle"))
    out = subprocess.run([exe, "check", "--impl", "mygeom:MyGeometry", "--seed", "1",
                          "--workers", "1"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stdout + out.stderr
