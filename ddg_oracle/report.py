"""The results of a check as a table, a JSON file, a Markdown summary and per-failure files.

``ddg-oracle check --report DIR`` writes:

* ``results.json``: every result (schema below), deterministic: no times, no
  paths outside DIR, keys sorted, floats as Python's shortest round-trip repr;
  two runs of the derandomized ``ci`` profile give identical bytes;
* ``timings.json``: wall time of the run and of every result (not deterministic);
* ``summary.md``: the table and every non-passing result;
* ``failures/NN-<ID>-<implementation>/``: for each result that is not a pass
  (FAILED, crashed, tie disagreement, convention) with a mesh: ``mesh.obj``
  (the shrunk mesh), ``mesh.png`` (the element in red) and ``reproduce.py``
  (imports the implementation, builds V and F, calls the methods the property
  needs and prints them next to the exact reference's, at the element).

results.json::

    {"schema": 1,
     "command": {"profile", "seed", "implementations", "only", "meshes", "expect_conventions"},
     "versions": {"python", "numpy", "scipy", "hypothesis", "libigl", "pymeshlab", ...},
     "counts": {status: number},
     "results": [{"property_id", "property_name", "statement", "implementation", "spec",
                  "source", "status", "ok", "examples", "ties", "note", "crash", "also",
                  "failure": null | {"message", "element", "element_ids", "expected",
                                     "observed", "error", "bound", "error_in_bounds"},
                  "mesh": null | {"V", "F"} | {"file", "vertices", "faces"},
                  "files": null | {"obj", "png", "snippet"}}]}

``error_in_bounds`` is the observed error in units of the property's derived
bound (> 1 is a failure), where the property states a bound.
"""

from __future__ import annotations

import json
import math
import numbers
import re
import sys
from fractions import Fraction
from pathlib import Path

SCHEMA = 1
INLINE_LIMIT = 200          # vertices up to which a snippet carries V and F inline
VERSIONED = ("numpy", "scipy", "hypothesis", "libigl", "pymeshlab", "matplotlib")


def jsonable(x):
    """x as JSON values: numpy and Fractions converted, non-finite floats as strings."""
    if x is None or isinstance(x, (bool, str)):
        return x
    if isinstance(x, int):
        return int(x)
    if isinstance(x, float):
        return x if math.isfinite(x) else repr(x)
    if isinstance(x, Fraction):
        return str(x)
    if hasattr(x, "tolist"):                      # numpy scalars and arrays
        return jsonable(x.tolist())
    if isinstance(x, dict):
        return {str(k): jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple, set, frozenset)):
        items = sorted(x, key=repr) if isinstance(x, (set, frozenset)) else x
        return [jsonable(v) for v in items]
    return str(x)


_PATTERNS = [
    (re.compile(r"face (\d+), corner (\d+)"), lambda m: {"face": int(m[1]), "corner": int(m[2])}),
    (re.compile(r"\(now (\d+)\)"), lambda m: {"vertex": int(m[1])}),
    (re.compile(r"edge \((\d+), (\d+)\)"), lambda m: {"edge": [int(m[1]), int(m[2])]}),
    (re.compile(r"\bvertex (\d+)"), lambda m: {"vertex": int(m[1])}),
    (re.compile(r"\brow (\d+)"), lambda m: {"vertex": int(m[1])}),
    (re.compile(r"\bface (\d+)"), lambda m: {"face": int(m[1])}),
    (re.compile(r"^\((\d+), (\d+)\)$"), lambda m: {"edge": [int(m[1]), int(m[2])]}),
]


def element_ids(element) -> dict | None:
    """The mesh element a failure names, as {"vertex": i}, {"edge": [i, j]}, {"face": f} or
    {"face": f, "corner": c}; None if it names none.

    >>> element_ids("face 3, corner 1"), element_ids((2, 5)), element_ids((4, 4))
    ({'face': 3, 'corner': 1}, {'edge': [2, 5]}, {'vertex': 4})
    >>> element_ids("vertex 0 (now 7)"), element_ids("boundary vertex 2"), element_ids("chi = 2")
    ({'vertex': 7}, {'vertex': 2}, None)
    """
    if element is None or isinstance(element, bool):
        return None
    if isinstance(element, numbers.Integral):
        return {"vertex": int(element)}
    if isinstance(element, (tuple, list)) and len(element) == 2 and \
            all(isinstance(v, numbers.Integral) for v in element):
        i, j = int(element[0]), int(element[1])
        return {"vertex": i} if i == j else {"edge": [i, j]}
    text = str(element)
    for pattern, build in _PATTERNS:
        m = pattern.search(text)
        if m:
            return build(m)
    return None


_SCALAR_LIST = re.compile(r'\[\n\s+([^\[\]{}"]*?)\n\s*\]')


def dumps(doc) -> str:
    """Indented JSON, keys sorted, with lists of numbers on one line (a vertex, a face).

    >>> print(dumps({"F": [[0, 1, 2]], "b": None}))
    {
     "F": [
      [0, 1, 2]
     ],
     "b": null
    }
    <BLANKLINE>
    """
    text = json.dumps(doc, indent=1, sort_keys=True, ensure_ascii=False)
    return _SCALAR_LIST.sub(lambda m: "[" + re.sub(r",\s+", ", ", m[1]) + "]", text) + "\n"


def versions() -> dict:
    from importlib import metadata
    out = {"python": sys.version.split()[0]}
    for name in VERSIONED:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            continue
    return out


def _failure_record(f) -> dict | None:
    if f is None:
        return None
    return {"message": f.message, "element": jsonable(f.element),
            "element_ids": element_ids(f.element), "expected": jsonable(f.expected),
            "observed": jsonable(f.observed), "error": jsonable(f.error),
            "bound": jsonable(f.bound), "error_in_bounds": jsonable(f.error_in_bounds)}


def _mesh_record(r) -> dict | None:
    if r.mesh is None:
        return None
    V, F = r.mesh
    if r.source != "generated":
        return {"file": r.source, "vertices": len(V), "faces": len(F)}
    return {"V": jsonable(V), "F": jsonable(F)}


def result_record(r, statement: str, spec: str, files: dict | None = None) -> dict:
    """One result as the JSON object of results.json."""
    return {"property_id": r.property_id, "property_name": r.property_name,
            "statement": statement, "implementation": r.implementation, "spec": spec,
            "source": r.source, "status": r.status, "ok": r.ok, "examples": r.examples,
            "ties": r.ties, "note": r.note, "crash": r.error, "also": list(r.also),
            "failure": _failure_record(r.failure), "mesh": _mesh_record(r), "files": files}


def counts(results) -> dict:
    from ddg_oracle.properties.runner import STATUSES
    return {s: sum(r.status == s for r in results) for s in STATUSES}


# --- table ----------------------------------------------------------------------------------------


def table(results, markdown: bool = False) -> str:
    """One table per source (generated meshes, then each mesh file): a row per property
    (ID and name), a column per implementation, the cell :meth:`Result.summary`."""
    impls = list(dict.fromkeys(r.implementation for r in results))
    sources = list(dict.fromkeys(r.source for r in results))
    blocks = []
    for source in sources:
        rows = [r for r in results if r.source == source]
        props = list(dict.fromkeys((r.property_id, r.property_name) for r in rows))
        cell = {(r.property_id, r.implementation): r.summary() for r in rows}
        head = ["property" if source == "generated" else f"property on {source}"] + impls
        body = [[f"{pid} ({name})"] + [cell.get((pid, n), "-") for n in impls]
                for pid, name in props]
        if markdown:
            lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
            lines += ["| " + " | ".join(row) + " |" for row in body]
        else:
            widths = [max(len(x[k]) for x in [head] + body) + 2 for k in range(len(head))]
            lines = ["".join(x.ljust(w) for x, w in zip(row, widths)).rstrip()
                     for row in [head] + body]
        blocks.append("\n".join(lines))
    return "\n\n".join(blocks)


# --- files per failure ----------------------------------------------------------------------------


_SNIPPET = '''"""Reproduce: {title}

Found by `ddg-oracle check`{how}.  Run from a checkout of ddg-oracle, in its
environment (pip install -e .):  python {name}

It calls the methods the property needs on the mesh below, with the checked
implementation and with the exact reference, and prints both{at}.
"""

import os
import sys

import numpy as np

sys.path.insert(0, os.getcwd())     # a module:object implementation imports from here, as in the CLI
from ddg_oracle.oracles.exact_reference import ReferenceImplementation  # noqa: E402
from ddg_oracle.implementations import load_implementation  # noqa: E402
{mesh}
ELEMENT = {element!r}
EXPECTED, OBSERVED = {expected!r}, {observed!r}     # as the property reported them


def at(x):
    """x at ELEMENT: a vertex, edge, face or corner of a per-element result."""
    if ELEMENT is None or np.isscalar(x) or isinstance(x, (bool, int, float)):
        return x
    if isinstance(x, dict):
        key = tuple(sorted(ELEMENT.get("edge", ())))
        return x.get(key, f"{{len(x)}} entries, none at {{key}}")
    if hasattr(x, "toarray"):
        x = x.toarray()
    x = np.asarray(x)
    if "edge" in ELEMENT and x.ndim == 2 and x.shape[0] == x.shape[1] == len(V):
        i, j = ELEMENT["edge"]
        return x[i, j]
    if "vertex" in ELEMENT and x.ndim >= 1 and len(x) == len(V):
        return x[ELEMENT["vertex"]]
    if "face" in ELEMENT and x.ndim >= 1 and len(x) == len(F):
        return x[ELEMENT["face"]] if "corner" not in ELEMENT else x[ELEMENT["face"], ELEMENT["corner"]]
    return x


impl = load_implementation({spec!r})
reference = ReferenceImplementation()
for method in {methods!r}:
    print(method)
    expected = at(getattr(reference, method)(V, F))
    print("  reference:     ", expected)
    observed = at(getattr(impl, method)(V, F))      # a crash here reproduces a crash
    print("  implementation:", observed)
'''


def snippet(r, spec: str, methods, name: str = "reproduce.py") -> str:
    """The Python file that reproduces result ``r`` (see the module doc)."""
    V, F = r.mesh
    if len(V) <= INLINE_LIMIT:
        mesh = ("\nV = np.array(" + repr([[float(x) for x in p] for p in V]) + ", dtype=np.float64)"
                "\nF = np.array(" + repr([[int(i) for i in f] for f in F]) + ", dtype=np.int64)\n")
    else:
        mesh = ("from pathlib import Path  # noqa: E402\n\nfrom ddg_oracle.meshfiles import read_mesh  # noqa: E402\n\n"
                "V, F = (np.array(a) for a in read_mesh(Path(__file__).with_name(\"mesh.obj\")))\n")
    f = r.failure
    ids = element_ids(f.element) if f is not None else None
    title = describe_line(r)
    how = "" if r.source == "generated" else f" on {r.source}"
    return _SNIPPET.format(title=title, how=how, name=name, mesh=mesh, element=ids,
                           expected=jsonable(f.expected) if f else None,
                           observed=jsonable(f.observed) if f else None,
                           spec=spec, methods=sorted(methods),
                           at=f" at {ids}" if ids else "")


def describe_line(r) -> str:
    if r.failure is not None:
        return str(r.failure).splitlines()[0]
    return f"[{r.property_id}] {r.implementation}: {r.status}: {(r.error or '').splitlines()[0]}"


def _slug(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9.]+", "_", text).strip("_")[:60]


def write_failure_files(directory: Path, k: int, r, spec: str, methods) -> dict:
    """mesh.obj, mesh.png and reproduce.py of result ``r``; their paths relative to the report."""
    from .meshfiles import write_obj
    from .render import render_mesh

    sub = Path("failures") / f"{k:02d}-{_slug(r.property_id)}-{_slug(r.implementation)}"
    d = directory / sub
    d.mkdir(parents=True, exist_ok=True)
    V, F = r.mesh
    write_obj(d / "mesh.obj", V, F)
    ids = element_ids(r.failure.element) if r.failure is not None else None
    render_mesh(d / "mesh.png", V, F, ids, title=describe_line(r)[:240])
    (d / "reproduce.py").write_text(snippet(r, spec, methods), encoding="utf-8")
    return {"obj": f"{sub.as_posix()}/mesh.obj", "png": f"{sub.as_posix()}/mesh.png",
            "snippet": f"{sub.as_posix()}/reproduce.py"}


def write_report(directory, results, command: dict, spec_of: dict, timings: dict) -> Path:
    """Write results.json, timings.json, summary.md and the failure files into ``directory``."""
    from ddg_oracle.properties.registry import PROPERTIES
    from ddg_oracle.properties.runner import PASSED, NOT_APPLICABLE, describe

    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    records, sections = [], []
    k = 0
    for r in results:
        p = PROPERTIES.get(r.property_id)
        spec = spec_of.get(r.implementation, r.implementation)
        files = None
        if r.status not in (PASSED, NOT_APPLICABLE):
            if r.mesh is not None:
                k += 1
                files = write_failure_files(directory, k, r, spec, p.needs if p else ())
            sections.append((r, files))
        records.append(result_record(r, p.statement if p else "", spec, files))
    doc = {"schema": SCHEMA, "command": jsonable({k: v for k, v in command.items() if k != "argv"}),
           "versions": versions(), "counts": counts(results), "results": records}
    (directory / "results.json").write_text(dumps(doc), encoding="utf-8")
    (directory / "timings.json").write_text(json.dumps(timings, indent=1, sort_keys=True) + "\n",
                                            encoding="utf-8")
    c = counts(results)
    md = ["# ddg-oracle check", "",
          "Command: `ddg-oracle check " + " ".join(command.get("argv", [])) + "`", "",
          ", ".join(f"{n} {s}" for s, n in c.items() if n), "", table(results, markdown=True), ""]
    if sections:
        md += ["## Not passed", ""]
    for r, files in sections:
        md += [f"### [{r.property_id}] {r.implementation}: {r.status}"
               + ("" if r.source == "generated" else f" on {r.source}"), "",
               "```", describe(r), "```", ""]
        if files:
            md += [f"![{r.property_id} {r.implementation}]({files['png']})", "",
                   f"Mesh: [{files['obj']}]({files['obj']}); reproduce: "
                   f"`python {files['snippet']}`", ""]
    (directory / "summary.md").write_text("\n".join(md), encoding="utf-8")
    return directory
