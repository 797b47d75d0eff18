"""The layers of docs/ARCHITECTURE.md, kept true: who may import whom.

Five layers, each a folder of the repository installed as ``ddg_oracle.<folder>``:
reference (the standard library and itself) < protocol < properties (and numpy, scipy,
hypothesis) < oracles (and the libraries they adapt) < application.  A module imports
only its own layer and the ones below.  The layers are read from pyproject.toml's
package-dir table (a folder added there is checked at once), the imports from the
import statements themselves (ast), so a lazy import inside a function counts too.
"""

from __future__ import annotations

import ast
import functools
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
#: the layers, lowest first
ORDER = ("reference", "protocol", "properties", "oracles", "application")
LAYERS = {name: rank for rank, name in enumerate(ORDER)}
#: package -> folder, as pyproject.toml installs them
PACKAGE_DIR = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"][
    "package-dir"]


def _layer_of_module(name: str) -> str | None:
    """The layer of an absolute module name of ours, or None for anything else (the
    package's face, ``ddg_oracle`` itself, belongs to no layer: it imports none)."""
    parts = name.split(".")
    if parts[0] != "ddg_oracle" or len(parts) == 1:
        return None
    return parts[1] if parts[1] in LAYERS else None


def _nodes(path: Path) -> list:
    """Every node of ``path``'s syntax tree: parsed once per file and content for the whole
    module: six tests read the same files, and parsing them for each took the module from
    3.1 to 5.8 CPU-s (measured side by side)."""
    stat = path.stat()
    return _nodes_of(path, stat.st_mtime_ns, stat.st_size)


@functools.lru_cache(maxsize=None)
def _nodes_of(path: Path, mtime_ns: int, size: int) -> list:
    return list(ast.walk(ast.parse(path.read_text(encoding="utf-8"))))


def _imports(path: Path, package: str) -> list[tuple[int, str]]:
    """(line, absolute module name) of every import in ``path``."""
    out = []
    for node in _nodes(path):
        if isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:                       # relative: resolve against the package
                base = package.split(".")[:len(package.split(".")) - node.level + 1]
                name = ".".join(base + ([node.module] if node.module else []))
            else:
                name = node.module or ""
            out.append((node.lineno, name))
            if node.module is None or name == "ddg_oracle":
                out += [(node.lineno, f"{name}.{a.name}") for a in node.names]
    return out


def _files():
    for layer in ORDER:
        folder, package = PACKAGE_DIR[f"ddg_oracle.{layer}"], f"ddg_oracle.{layer}"
        for path in sorted((ROOT / folder).rglob("*.py")):
            sub = ".".join(path.relative_to(ROOT / folder).with_suffix("").parts[:-1])
            yield path, layer, package + (f".{sub}" if sub else "")


def test_the_layers_are_the_installed_folders():
    """Every folder pyproject.toml installs is a layer (or the package's face), each layer
    is a folder of its own at the top of the repository, and the face holds no module
    but __init__ and __main__: a module added anywhere is under the layer checks."""
    assert set(PACKAGE_DIR) == {"ddg_oracle"} | {f"ddg_oracle.{x}" for x in ORDER}
    assert all(PACKAGE_DIR[f"ddg_oracle.{x}"] == x for x in ORDER)
    assert {p.name for p in (ROOT / PACKAGE_DIR["ddg_oracle"]).glob("*.py")} == {
        "__init__.py", "__main__.py"}


def test_a_checkout_without_install_imports_its_layers():
    """Issue 43: without ``pip install``, from the checkout's root, ``ddg_oracle.<layer>``
    is the folder of that name (Python run with no site-packages and no environment)."""
    code = ("import ddg_oracle.reference, ddg_oracle.protocol.methods as m\n"
            "print(ddg_oracle.reference.__file__); print(m.__file__)")
    out = subprocess.run([sys.executable, "-E", "-s", "-S", "-c", code], cwd=ROOT,
                         capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == [str(ROOT / "reference" / "__init__.py"),
                                  str(ROOT / "protocol" / "methods.py")]


def test_relative_imports_cross_the_layers_as_the_folders_do():
    """Between layers the product imports relatively (``from ..reference import x``), so
    that the import graph of the checkout, folder by folder, is the installed one."""
    absolute = [f"{path.relative_to(ROOT)}:{node.lineno}"
                for path, _, _ in _files()
                for node in _nodes(path)
                if isinstance(node, ast.ImportFrom) and not node.level
                and (node.module or "").startswith("ddg_oracle.")]
    assert absolute == []


@pytest.mark.parametrize("path, layer, package", list(_files()),
                         ids=lambda x: str(x.relative_to(ROOT)) if isinstance(x, Path) else None)
def test_every_import_goes_down_the_layers(path, layer, package):
    for line, name in _imports(path, package):
        other = _layer_of_module(name)
        # (that the reference imports only the standard library besides itself is
        # tests/test_project.py's test_reference_imports_only_the_standard_library)
        if other is not None:
            assert LAYERS[other] <= LAYERS[layer], (
                f"{path.relative_to(ROOT)}:{line} imports {name} ({other} layer) from the "
                f"{layer} layer")


def test_the_layer_check_catches_an_upward_import(tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text("def f():\n    from ddg_oracle.application.cli import main\n")
    [(line, name)] = _imports(bad, "ddg_oracle.properties")
    assert (line, _layer_of_module(name)) == (2, "application")
    rel = tmp_path / "rel.py"
    rel.write_text("from ..oracles import libigl\n")
    assert _imports(rel, "ddg_oracle.properties")[0][1] == "ddg_oracle.oracles"


def test_a_library_worker_does_not_import_hypothesis_or_the_properties():
    # an isolated library worker imports ddg_oracle.application.isolation (the protocol
    # layer) and its adapter, not the properties package, so such a process
    # starts without Hypothesis (0.5 s per worker, 16 workers in a main job)
    import subprocess
    import sys
    code = ("import sys, ddg_oracle.application.isolation, ddg_oracle.protocol.arrays\n"
            "print(sorted(m for m in sys.modules if m == 'hypothesis'\n"
            "             or m.startswith('ddg_oracle.properties')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
    import ddg_oracle.properties as p
    assert p.PROPERTIES["D1.6"].id == "D1.6" and len(p.PROPERTIES) == len(p.all_properties())


def _benchmark_files():
    """The benchmarks' modules (package ``benchmarks``, the repository's folder): outside
    the five layers, held to the same one-way imports among themselves."""
    for path in sorted((ROOT / "benchmarks").rglob("*.py")):
        sub = ".".join(path.relative_to(ROOT / "benchmarks").with_suffix("").parts[:-1])
        yield path, None, "benchmarks" + (f".{sub}" if sub else "")


def _module_graph(benchmarks: bool = False) -> dict[str, set[str]]:
    """{module: the modules of ours it imports} over the five folders (and the benchmarks'
    with ``benchmarks``), lazy imports inside functions included (a cycle through them
    still ties two modules into one)."""
    modules = {}
    for path, _, package in [*_files(), *(_benchmark_files() if benchmarks else ())]:
        modules[package if path.stem == "__init__" else f"{package}.{path.stem}"] = path
    graph = {}
    for name, path in modules.items():
        package = name if path.stem == "__init__" else name.rpartition(".")[0]
        out = set()
        for _, imported in _imports(path, package):
            while imported and imported not in modules:
                imported = imported.rpartition(".")[0]
            # its own packages' __init__ modules run first anyway (``from . import x``
            # names the package too): not an arrow of the data flow
            if imported and imported != name and not name.startswith(imported + "."):
                out.add(imported)
        graph[name] = out
    return graph


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_no_two_modules_import_each_other():
    """Issue 43: data flows one way; the cycles cli <-> report, report <-> html_report,
    jobs <-> cluster and rationals <-> surds were cut, and none comes back."""
    assert _cycles(_module_graph()) == []


def test_no_two_benchmark_modules_import_each_other():
    """The benchmarks too: knockout.py, knockout_plugin.py and knockout_hand.py imported
    each other (the plugin lazily) until the hand-written versions became a pytest plugin
    of their own."""
    graph = _module_graph(benchmarks=True)
    assert "benchmarks.knockout_plugin" in graph["benchmarks.knockout"]
    assert _cycles(graph) == []


def test_the_cycle_check_sees_a_lazy_cycle():
    assert _cycles({"a": {"b"}, "b": {"a"}, "c": {"a"}}) == [["a", "b"]]
    graph = _module_graph()
    assert "ddg_oracle.reference.exact.rationals" in graph["ddg_oracle.reference.exact.surds"]
    assert "ddg_oracle.application.causes" in graph["ddg_oracle.application.html_report"]


def test_no_private_name_is_imported_across_modules():
    """Issue 43: a name one module keeps private (``_refine``) is no other module's to
    import; what modules share has a public name, the term algebra its own module
    (reference/exact/terms.py).  Attribute reads of private names are not covered."""
    private = [f"{path.relative_to(ROOT)}:{node.lineno}: {a.name}"
               for path, _, _ in _files()
               for node in _nodes(path)
               if isinstance(node, ast.ImportFrom) and node.module != "__future__"
               for a in node.names
               if a.name.startswith("_") and not a.name.startswith("__")]
    assert private == []


def test_vector_helpers_live_in_one_module():
    """Issue 43: differences, inner and cross products of coordinate tuples are
    reference/linear.py's (they were written out in seven modules); a function of two
    vectors by one of those names anywhere else is a second copy.  The exact number types
    (reference/exact/: a Surd's own subtraction, an Interval's inner product) are other
    ideas."""
    names = {"sub", "dot", "cross", "det", "det2", "det3", "sub2", "sub3", "dot2", "dot3",
             "cross2", "cross3", "minus", "inner", "outer"}
    copies = [f"{path.relative_to(ROOT)}:{node.lineno}: {node.name}"
              for path, _, _ in _files()
              if path != ROOT / "reference" / "linear.py" and "exact" not in path.parts
              for node in _nodes(path)
              if isinstance(node, ast.FunctionDef) and node.name.lstrip("_") in names
              and len(node.args.args) == 2 and node.args.args[0].arg != "self"]
    assert copies == []


def test_halfedge_numbers_come_from_the_combinatorics_helpers():
    """Issue 43: ``3 f + c`` is computed by reference/combinatorics.py's helpers
    (``halfedge``, ``opposite_halfedge``, ``face_of``, ``corner_of``); the few per-face hot
    paths that write it out say so on the line or the line before (``inline halfedge``)."""
    import re
    written = []
    for path, _, _ in _files():
        if path == ROOT / "reference" / "combinatorics.py":
            continue
        lines = path.read_text(encoding="utf-8").split("\n")
        written += [f"{path.relative_to(ROOT)}:{k + 1}" for k, line in enumerate(lines)
                    if re.search(r"\b3 \* (f|face)\b", line.split("#")[0])
                    and "inline halfedge" not in line + lines[k - 1]]
    assert written == []


def test_expected_values_are_not_read_from_check_modules():
    """Issue 43, point 3: the float views and exact expected values live in modules of
    their own (properties/views.py, harness.py, delaunay_exact.py); the reference adapter,
    the protocol and every module of properties but the chapter check modules import no
    check module (the registry loads them by name)."""
    from ddg_oracle.properties.registry import PROPERTY_MODULES
    checks = set(PROPERTY_MODULES)
    readers = [p for p in sorted((ROOT / "properties").glob("*.py")) if p.stem not in checks]
    readers += sorted((ROOT / "oracles").glob("*.py")) + sorted((ROOT / "protocol").glob("*.py"))
    found = []
    for path in readers:
        for node in _nodes(path):
            if isinstance(node, ast.ImportFrom):
                # the module's name below ddg_oracle: the folder is the layer's package
                base = [path.parent.name][:max(0, 2 - node.level)] if node.level else []
                target = base + [m for m in (node.module or "").split(".") if m]
                if target[:1] == ["ddg_oracle"]:
                    target = target[1:]
                names = {a.name for a in node.names}
                if target[:1] == ["properties"] and (
                        (len(target) > 1 and target[1] in checks) or
                        (len(target) == 1 and names & checks)):
                    found.append(f"{path.relative_to(ROOT)}:{node.lineno}")
    assert found == []


def test_check_modules_define_no_strategies():
    """Issue 43, point 3: a chapter check module holds its checks and quantity
    declarations; what draws their examples lives in a strategy module (strategies, stars,
    flipped, metrics, planar_points, point_sets), so no check module defines a
    ``@st.composite`` and no property's strategy is a named function of a check module (a
    lambda composing strategies in the ``@prop`` line is the check's own).  The modules of
    assertion checks of the reference itself (statements, structure: the other modules
    whose functions application/traceability.toml names as properties) have no ``@prop``
    line to compose strategies in, so they do not import ``hypothesis.strategies`` at all
    (which also keeps out a plain function returning a strategy)."""
    from ddg_oracle.properties.registry import PROPERTIES, PROPERTY_MODULES, all_properties
    all_properties()
    checks = {f"ddg_oracle.properties.{m}" for m in PROPERTY_MODULES}
    table = tomllib.loads((ROOT / "application" / "traceability.toml").read_text(
        encoding="utf-8"))
    named = {name.split(":")[0].removeprefix("ddg_oracle.properties.")
             for row in table.values() if isinstance(row, dict)
             for name in row.get("property", [])}
    assertions = sorted(named - set(PROPERTY_MODULES))
    assert {"statements", "structure"} <= set(assertions)
    trees = {m: ast.parse((ROOT / "properties" / f"{m}.py").read_text(encoding="utf-8"))
             for m in (*PROPERTY_MODULES, *assertions)}
    found = [f"properties/{m}.py:{node.lineno}: {node.name}"
             for m, tree in trees.items()
             for node in ast.walk(tree)
             if isinstance(node, ast.FunctionDef)
             and any("composite" in ast.unparse(d) for d in node.decorator_list)]
    found += [f"properties/{m}.py:{node.lineno}: imports hypothesis.strategies"
              for m in assertions
              for node in ast.walk(trees[m])
              if (isinstance(node, ast.ImportFrom) and node.module == "hypothesis"
                  and any(a.name == "strategies" for a in node.names))
              or (isinstance(node, ast.ImportFrom) and node.module == "hypothesis.strategies")
              or (isinstance(node, ast.Import)
                  and any(a.name == "hypothesis.strategies" for a in node.names))]
    found += [f"{p.id}: {p.strategy.__module__}.{p.strategy.__qualname__}"
              for p in PROPERTIES.values()
              if p.strategy.__module__ in checks and p.strategy.__name__ != "<lambda>"]
    assert found == []
