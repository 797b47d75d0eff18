"""The traceability table: catalog ID -> reference function, property, tests, status.

The table is ``ddg_oracle/traceability.toml`` (package data, so an installed
copy checks itself).  :func:`check` verifies that it is true: every named
function and property exists, every row of a claimed chapter is verified (or
an erratum listed in the errata, ``docs/errata.md``, installed as
``ddg_oracle/data/errata.md``); where the repository is at hand (a checkout,
or an editable install) also every named test exists and every row of the
catalog ``../shared/THEOREMS.md`` is present.
"""

from __future__ import annotations

import ast
import importlib
import os
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path

TABLE = Path(__file__).with_name("traceability.toml")
DATA = Path(__file__).with_name("data")          # errata.md, findings.md (links into docs/)


def repository() -> Path | None:
    """The repository checkout this package runs from (editable install), else None."""
    root = Path(__file__).resolve().parent.parent
    return root if (root / "pyproject.toml").is_file() and (root / "reference").is_dir() else None

STATUSES = ("verified", "erratum", "not yet")


@dataclass(frozen=True)
class Entry:
    id: str
    chapter: int
    statement: str
    reference: tuple[str, ...]
    property: tuple[str, ...]
    tests: tuple[str, ...]
    status: str
    erratum: str = ""


def load(path: Path | None = None) -> tuple[list[int], list[Entry]]:
    """(claimed chapters, entries in table order) of the table at ``path`` (default: ours)."""
    with open(path or TABLE, "rb") as fh:
        data = tomllib.load(fh)
    claimed = list(data.pop("claimed_chapters", []))
    entries = [Entry(id=k, chapter=v["chapter"], statement=v["statement"],
                     reference=tuple(v.get("reference", ())), property=tuple(v.get("property", ())),
                     tests=tuple(v.get("tests", ())), status=v.get("status", "not yet"),
                     erratum=v.get("erratum", ""))
               for k, v in data.items()]
    return claimed, entries


def catalog_path() -> Path | None:
    """THEOREMS.md: $DDG_CATALOG, else ../shared/THEOREMS.md beside the repository."""
    env = os.environ.get("DDG_CATALOG")
    candidates = [Path(env)] if env else []
    repo = repository()
    if repo is not None:
        candidates.append(repo.parent / "shared" / "THEOREMS.md")
    return next((p for p in candidates if p.is_file()), None)


def catalog_ids(path: Path) -> dict[str, int]:
    """Row IDs of the catalog with their chapter, in order."""
    ids: dict[str, int] = {}
    chapter = None
    for line in path.read_text(encoding="utf-8").splitlines():
        m = re.match(r"## Chapter (\d+)", line)
        if m:
            chapter = int(m.group(1))
        elif chapter and line.startswith("| ") and not line.startswith(("| ID", "|---")):
            ids[line.strip("|").split("|")[0].strip()] = chapter
    return ids


def _resolve(dotted: str) -> bool:
    """'package.module:Qual.name' names an existing object."""
    module, _, qual = dotted.partition(":")
    try:
        obj = importlib.import_module(module)
        for part in filter(None, qual.split(".")):
            obj = getattr(obj, part)
    except (ImportError, AttributeError):
        return False
    return True


def _test_exists(spec: str) -> bool | None:
    """'tests/test_x.py::test_name' (or ::Class::test_name) exists; None outside a checkout."""
    repo = repository()
    if repo is None:
        return None
    path, *names = spec.split("::")
    file = repo / path
    if not file.is_file():
        return False
    if not names:
        return True
    scope = ast.parse(file.read_text(encoding="utf-8")).body
    for name in names:
        found = [n for n in scope if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef,
                                                    ast.ClassDef)) and n.name == name]
        if not found:
            return False
        scope = getattr(found[0], "body", [])
    return True


def errata_ids() -> set[str]:
    """IDs of the entries of the errata (docs/errata.md, headings '## E<n>: ...')."""
    path = DATA / "errata.md"
    return set(re.findall(r"^## (E\d+)\b", path.read_text(encoding="utf-8"), re.M))


def check(path: Path | None = None) -> list[str]:
    """Every way the table is not true, as messages; empty when it is."""
    problems: list[str] = []
    claimed, entries = load(path)
    by_id = {e.id: e for e in entries}
    cat = catalog_path()
    if cat is not None:
        ids = catalog_ids(cat)
        for i, ch in ids.items():
            if i not in by_id:
                problems.append(f"{i}: catalog row (chapter {ch}) missing from the table")
        for i in by_id:
            if i not in ids:
                problems.append(f"{i}: in the table but not in the catalog {cat}")
    errata = errata_ids()
    for e in entries:
        if e.status not in STATUSES:
            problems.append(f"{e.id}: unknown status {e.status!r}")
        if e.chapter in claimed:
            if e.status == "not yet":
                problems.append(f"{e.id}: chapter {e.chapter} is claimed but the row is 'not yet'")
            for kind in ("reference", "property", "tests"):
                if not getattr(e, kind):
                    problems.append(f"{e.id}: no {kind} named")
        if e.status == "erratum" and e.erratum not in errata:
            problems.append(f"{e.id}: erratum {e.erratum!r} is not in docs/errata.md")
        for name in e.reference + e.property:
            if not _resolve(name):
                problems.append(f"{e.id}: {name} does not exist")
        for t in e.tests:
            if _test_exists(t) is False:
                problems.append(f"{e.id}: test {t} does not exist")
    return problems
