"""One registry: every property declares how it runs on a mesh file, every protocol method
how its answers compare (properties.registry), adapters declare themselves
(ddg_oracle.application.implementations reads their ADAPTER), and the application holds no per-method
or per-adapter table.  Adding a toy property and a toy adapter touches one file each: done
here in a temporary copy of the package, then ``ddg-oracle check`` runs them."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from ddg_oracle.protocol.methods import METHODS
from ddg_oracle.properties.registry import (PROPERTIES, REQUIREMENTS, all_properties,
                                            all_quantities, prop, quantity)

ROOT = Path(__file__).resolve().parent.parent


def test_every_protocol_method_declares_how_its_answers_compare():
    quantities = all_quantities()
    assert list(quantities) == list(METHODS)
    for q in quantities.values():
        assert q.kind == METHODS[q.method].kind
        if q.not_on_a_mesh is None and q.kind in ("numbers", "edges", "matrix"):
            assert q.bound is not None, q.method
    with pytest.raises(ValueError, match="declared twice"):
        quantity("euler_characteristic")
    with pytest.raises(ValueError, match="not a protocol method"):
        quantity("euler_characteristics")
    from ddg_oracle.properties import registry
    saved = registry.QUANTITIES.pop("area")
    try:
        with pytest.raises(ValueError, match="needs its derived bound"):
            quantity("area")                    # a numeric answer without its bound
    finally:
        registry.QUANTITIES["area"] = saved


def test_every_property_declares_its_mesh_mode():
    props = all_properties()
    assert all(p.on_mesh is None or set(p.on_mesh) <= set(REQUIREMENTS) for p in props)
    on_files = [p.id for p in props if p.on_mesh is not None]
    assert {"D1.6", "D2.2", "D3.1", "D4.8 / R4.9"} <= set(on_files)
    with pytest.raises(TypeError, match="on_mesh"):
        prop("X0.0", "no mesh mode", strategy=lambda: None)
    with pytest.raises(ValueError, match="unknown mesh requirements"):
        prop("X0.0", "a bad mode", strategy=lambda: None, on_mesh=("watertight",))
    assert "X0.0" not in PROPERTIES


def test_the_application_names_no_protocol_method_and_no_adapter():
    """compare, the exec protocol and its schema read the methods' shapes and quantities;
    the implementations table reads the adapters' declarations."""
    import ast
    for path in ("application/compare.py", "oracles/executable.py", "protocol/schema.py"):
        tree = ast.parse((ROOT / path).read_text(encoding="utf-8"))
        named = sorted({n.value for n in ast.walk(tree)
                        if isinstance(n, ast.Constant) and n.value in METHODS})
        assert named == [], f"{path} names {named} in its code"
    from ddg_oracle.application.implementations import BUILTIN
    text = (ROOT / "application/implementations.py").read_text(encoding="utf-8")
    assert not [name for name, target in BUILTIN.items() if target.split(":")[1] in text]


TOY_PROPERTY = '''

@prop("TOY1", "a toy property: chi = V - E + F is at most V (a triangle mesh has F <= E)",
      needs={"euler_characteristic"}, on_mesh=(), strategy=triangulated_surfaces)
def toy_property(impl, case: Example):
    V, F = case.arrays()
    chi = impl.euler_characteristic(V, F)
    if chi > len(V):
        raise PropertyFailure("TOY1", impl, "chi exceeds the vertex count", mesh=case.mesh,
                              expected=f"<= {len(V)}", observed=chi)
'''

TOY_ADAPTER = '''"""A toy adapter: V - E + F with numpy."""

import numpy as np

ADAPTER = {"name": "toylib", "object": "ToyLib", "library": "numpy", "extra": None}


class ToyLib:
    name = "toylib"

    def euler_characteristic(self, V, F):
        F = np.asarray(F)
        edges = {tuple(sorted(e)) for f in F.tolist() for e in ((f[0], f[1]), (f[1], f[2]),
                                                               (f[2], f[0]))}
        return len(V) - len(edges) + len(F)
'''


def test_a_toy_property_and_a_toy_adapter_touch_one_file_each(tmp_path):
    """The package laid out as installed in a temporary directory; one file edited for the
    property (properties/topology.py), one added for the adapter (oracles/toylib.py);
    ``ddg-oracle check`` then runs the property on the adapter, on drawn examples and on a
    mesh file."""
    pkg = tmp_path / "ddg_oracle"
    shutil.copytree(ROOT / "ddg_oracle", pkg, symlinks=False,
                    ignore=shutil.ignore_patterns("__pycache__"))
    for sub in ("reference", "protocol", "properties", "oracles", "application"):
        shutil.copytree(ROOT / sub, pkg / sub, ignore=shutil.ignore_patterns("__pycache__"))
    with open(pkg / "properties" / "topology.py", "a", encoding="utf-8") as out:
        out.write(TOY_PROPERTY)
    (pkg / "oracles" / "toylib.py").write_text(TOY_ADAPTER, encoding="utf-8")
    (tmp_path / "cube.obj").write_text(
        "".join(f"v {x} {y} {z}\n" for x in (0, 1) for y in (0, 1) for z in (0, 1))
        + "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\n"
          "f 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n", encoding="utf-8")
    env = {**os.environ, "PYTHONPATH": str(tmp_path)}

    def run(*args):
        return subprocess.run([sys.executable, "-m", "ddg_oracle", *args], cwd=tmp_path,
                              env=env, capture_output=True, text=True, timeout=600)

    where = subprocess.run([sys.executable, "-c", "import ddg_oracle; print(ddg_oracle.__file__)"],
                           cwd=tmp_path, env=env, capture_output=True, text=True)
    assert where.stdout.strip().startswith(str(tmp_path)), where.stdout + where.stderr
    drawn = run("check", "--impl", "toylib", "--only", "TOY1", "--profile", "ci",
                "--workers", "1", "--wide")
    assert drawn.returncode == 0, drawn.stdout + drawn.stderr
    assert "TOY1" in drawn.stdout and "toylib" in drawn.stdout
    assert "passed" in drawn.stdout
    on_file = run("check", "--impl", "toylib", "--only", "TOY1", "D1.6", "--mesh", "cube.obj",
                  "--workers", "1", "--wide")
    assert on_file.returncode == 0, on_file.stdout + on_file.stderr
    assert "TOY1" in on_file.stdout and "D1.6" in on_file.stdout
