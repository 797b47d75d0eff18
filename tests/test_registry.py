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


def _method_names_used(tree) -> list[str]:
    """Protocol method names a module decides by: compared with (``method == "area"``,
    ``method in (...)``), passed to a call, or two or more of them in one table (dict keys,
    a tuple, list or set).  A name that is only a record's field (``want["area"]``, the
    vectors' ``{"faces", "laplacian", "area"}``) is not a decision."""
    import ast

    def names(nodes):
        return [n.value for n in nodes if isinstance(n, ast.Constant) and n.value in METHODS]
    used = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Compare):
            for side in [node.left, *node.comparators]:
                used += names([side]) + names(getattr(side, "elts", []))
        elif isinstance(node, ast.Call):
            used += names(node.args) + names(k.value for k in node.keywords)
        elif isinstance(node, ast.Dict) and len(names(node.keys)) >= 2:
            used += names(node.keys)
        elif isinstance(node, (ast.Tuple, ast.List, ast.Set)) and len(names(node.elts)) >= 2:
            used += names(node.elts)
    return sorted(set(used))


def test_the_application_names_no_protocol_method_and_no_adapter():
    """Every module of the application and of the protocol (but the table of methods
    itself) reads the methods' shapes and quantities: none decides by a method's name;
    the implementations table reads the adapters' declarations."""
    import ast
    paths = sorted((ROOT / "application").rglob("*.py")) + sorted(
        p for p in (ROOT / "protocol").glob("*.py") if p.name != "methods.py") + [
        ROOT / "oracles" / "executable.py"]
    assert len(paths) > 20
    for path in paths:
        named = _method_names_used(ast.parse(path.read_text(encoding="utf-8")))
        assert named == [], f"{path.relative_to(ROOT)} decides by {named}"
    planted = ast.parse('if method == "genus" or method in ("area", "x"):\n'
                        '    f("corner_angles")\nt = {"area": 1, "genus": 2}\n'
                        'ok = want["area"], {"faces": 1, "area": 2}')
    assert _method_names_used(planted) == ["area", "corner_angles", "genus"]
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


def _installed_copy(tmp_path) -> Path:
    """The package laid out as installed, in ``tmp_path/ddg_oracle``."""
    pkg = tmp_path / "ddg_oracle"
    shutil.copytree(ROOT / "ddg_oracle", pkg, symlinks=False,
                    ignore=shutil.ignore_patterns("__pycache__"))
    for sub in ("reference", "protocol", "properties", "oracles", "application"):
        shutil.copytree(ROOT / sub, pkg / sub, ignore=shutil.ignore_patterns("__pycache__"))
    return pkg


def _runner(tmp_path):
    env = {**os.environ, "PYTHONPATH": str(tmp_path)}

    def run(*args, module="ddg_oracle"):
        return subprocess.run([sys.executable, "-m", module, *args], cwd=tmp_path,
                              env=env, capture_output=True, text=True, timeout=600)
    where = subprocess.run([sys.executable, "-c", "import ddg_oracle; print(ddg_oracle.__file__)"],
                           cwd=tmp_path, env=env, capture_output=True, text=True)
    assert where.stdout.strip().startswith(str(tmp_path)), where.stdout + where.stderr
    return run


def test_a_toy_property_and_a_toy_adapter_touch_one_file_each(tmp_path):
    """The package laid out as installed in a temporary directory; one file edited for the
    property (properties/topology.py), one added for the adapter (oracles/toylib.py);
    ``ddg-oracle check`` then runs the property on the adapter, on drawn examples and on a
    mesh file."""
    pkg = _installed_copy(tmp_path)
    with open(pkg / "properties" / "topology.py", "a", encoding="utf-8") as out:
        out.write(TOY_PROPERTY)
    (pkg / "oracles" / "toylib.py").write_text(TOY_ADAPTER, encoding="utf-8")
    (tmp_path / "cube.obj").write_text(
        "".join(f"v {x} {y} {z}\n" for x in (0, 1) for y in (0, 1) for z in (0, 1))
        + "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\n"
          "f 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n", encoding="utf-8")
    run = _runner(tmp_path)
    drawn = run("check", "--impl", "toylib", "--only", "TOY1", "--profile", "ci",
                "--workers", "1", "--wide")
    assert drawn.returncode == 0, drawn.stdout + drawn.stderr
    assert "TOY1" in drawn.stdout and "toylib" in drawn.stdout
    assert "passed" in drawn.stdout
    on_file = run("check", "--impl", "toylib", "--only", "TOY1", "D1.6", "--mesh", "cube.obj",
                  "--workers", "1", "--wide")
    assert on_file.returncode == 0, on_file.stdout + on_file.stderr
    assert "TOY1" in on_file.stdout and "D1.6" in on_file.stdout


TOY_METHOD = '''
METHODS["faces_at_vertex"] = Method("(n,) float array: the number of faces at each vertex",
                                    "numbers", element="vertex")
'''

TOY_METHOD_PROPERTY = '''

def _faces_at_vertex(example):
    faces = example.surface.triangulation.faces
    return [sum(v in f for f in faces) for v in range(example.surface.n_vertices)]


@prop("TOY2", "a toy method: the faces at the vertices number three times the faces",
      needs={"faces_at_vertex"}, on_mesh=(), strategy=triangulated_surfaces)
def toy_method_counts_corners(impl, case: Example):
    V, F = case.arrays()
    got = impl.faces_at_vertex(V, F)
    if sum(got) != 3 * len(F):
        raise PropertyFailure("TOY2", impl, "the counts miss a corner", mesh=case.mesh,
                              expected=3 * len(F), observed=sum(got))


quantity("faces_at_vertex", bound=lambda example, want: [0.0] * example.surface.n_vertices,
         exact=_faces_at_vertex)
'''

TOY_METHOD_ANSWER = '''
    def faces_at_vertex(self, V, F):
        return np.bincount(np.asarray(F, dtype=np.int64).reshape(-1),
                           minlength=len(V)).astype(np.float64)
'''


def test_a_toy_protocol_method_touches_three_files(tmp_path):
    """A new protocol method: its Method (protocol/methods.py), its quantity and property
    (properties/topology.py), the reference's answer (oracles/exact_reference.py) -- three
    files edited by hand in a copy of the package; then ``check`` runs the property, the
    test vectors, their verification and the protocol's schema carry the method, and the
    generated method table of docs/protocol.md lists it."""
    pkg = _installed_copy(tmp_path)
    with open(pkg / "protocol" / "methods.py", "a", encoding="utf-8") as out:
        out.write(TOY_METHOD)
    with open(pkg / "properties" / "topology.py", "a", encoding="utf-8") as out:
        out.write(TOY_METHOD_PROPERTY)
    adapter = pkg / "oracles" / "exact_reference.py"
    text = adapter.read_text(encoding="utf-8")
    head, tail = text.split("\n\ndef _delaunay_flags", 1)
    adapter.write_text(head + "\n" + TOY_METHOD_ANSWER + "\n\ndef _delaunay_flags" + tail,
                       encoding="utf-8")
    run = _runner(tmp_path)
    checked = run("check", "--impl", "reference", "--only", "TOY2", "--profile", "ci",
                  "--workers", "1", "--wide")
    assert checked.returncode == 0, checked.stdout + checked.stderr
    assert "TOY2" in checked.stdout and "passed" in checked.stdout
    made = run("vectors", "--out", "v")
    assert made.returncode == 0, made.stdout + made.stderr
    import json
    cases = json.loads((tmp_path / "v" / "faces_at_vertex.json").read_text())["cases"]
    valid = [c for c in cases if c["result"] == "valid"]
    assert len(valid) > 10
    isolated = [c for c in valid if "isolated-vertex" in c["flags"]]
    assert isolated and "0" in isolated[0]["expected"]["exact"]
    verified = run("verify", "v", "--impl", "reference")
    assert verified.returncode == 0, verified.stdout + verified.stderr
    schema = run(str(tmp_path / "schema.json"), module="ddg_oracle.protocol.schema")
    assert schema.returncode == 0, schema.stderr
    defs = json.loads((tmp_path / "schema.json").read_text())["$defs"]
    assert "request.faces_at_vertex" in defs and "answer.faces_at_vertex" in defs
    doc = tmp_path / "protocol.md"
    shutil.copy(ROOT / "docs" / "protocol.md", doc)
    table = run("--table", str(doc), module="ddg_oracle.protocol.schema")
    assert table.returncode == 0, table.stderr
    assert "| `faces_at_vertex` | `V`, `F` | n numbers |" in doc.read_text(encoding="utf-8")
