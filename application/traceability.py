"""The traceability table: catalog ID -> reference function, property, tests, status.

The table is ``application/traceability.toml`` (package data, so an installed
copy checks itself).  :func:`check` verifies that it is true: every named
function and property exists, every row of a claimed chapter is verified (or
an erratum listed in the errata, ``docs/errata.md``, installed as
``application/data/errata.md``), every row says in words what its check covers
(``covers``) and what it cannot (``limits``); where the repository is at hand (a
checkout, or an editable install) also every named test exists and every row of the
catalog ``../shared/THEOREMS.md`` is present.

The notes table ``application/notes.toml`` lists every numbered item of chapters 1-4
of the notes with its line and a status (:data:`NOTE_STATUSES`); :func:`check_notes`
verifies it, against the notes' text where it is at hand (``$DDG_NOTES``, else
``../shared/seed/*.txt`` beside the repository): every heading of the text is an
item, every item's line holds its heading.
"""

from __future__ import annotations

import ast
import functools
import importlib
import os
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path

TABLE = Path(__file__).with_name("traceability.toml")
NOTES = Path(__file__).with_name("notes.toml")
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
    scope: str = ""
    source: str = "catalog"
    covers: str = ""             # in words: what the row's check covers
    limits: str = ""             # in words: what it cannot (examples only, a special case, ...)


#: the least length of ``covers`` and ``limits``: a sentence, not a placeholder
MIN_WORDS = 4


def load(path: Path | None = None) -> tuple[list[int], list[Entry]]:
    """(claimed chapters, entries in table order) of the table at ``path`` (default: ours)."""
    with open(path or TABLE, "rb") as fh:
        data = tomllib.load(fh)
    claimed = list(data.pop("claimed_chapters", []))
    entries = [Entry(id=k, chapter=v["chapter"], statement=v["statement"],
                     reference=tuple(v.get("reference", ())), property=tuple(v.get("property", ())),
                     tests=tuple(v.get("tests", ())), status=v.get("status", "not yet"),
                     erratum=v.get("erratum", ""), scope=v.get("scope", ""),
                     source=v.get("source", "catalog"), covers=v.get("covers", ""),
                     limits=v.get("limits", ""))
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


@functools.lru_cache(maxsize=256)
def _module_body(path: str, mtime_ns: int, size: int) -> list:
    """The top-level statements of a test file, parsed once per version of the file (the
    table names about 300 tests in some 30 files)."""
    return ast.parse(Path(path).read_text(encoding="utf-8")).body


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
    stat = file.stat()
    scope = _module_body(str(file), stat.st_mtime_ns, stat.st_size)
    for name in names:
        found = [n for n in scope if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef,
                                                    ast.ClassDef)) and n.name == name]
        if not found:
            return False
        scope = getattr(found[0], "body", [])
    return True


def errata_ids() -> set[str]:
    """IDs of the entries of the errata (docs/errata.md, headings '## ER-<n>: ...')."""
    path = DATA / "errata.md"
    return set(re.findall(r"^## (ER-\d+):", path.read_text(encoding="utf-8"), re.M))


def scope_ids() -> set[str]:
    """IDs of the scope notes of docs/errata.md (headings '### SC-<n>: ...')."""
    path = DATA / "errata.md"
    return set(re.findall(r"^### (SC-\d+):", path.read_text(encoding="utf-8"), re.M))


#: the fields every erratum has (docs/errata.md, "Format of an entry")
ERRATUM_FIELDS = ("line", "printed", "correct", "evidence", "relied on")


def errata_problems(path: Path | None = None) -> list[str]:
    """Every entry of the errata (default: ours) without one of :data:`ERRATUM_FIELDS`, or
    naming a test (```tests/...::name```) that does not exist; empty when the list is true."""
    text = (path or DATA / "errata.md").read_text(encoding="utf-8")
    problems = []
    for m in re.finditer(r"^## (ER-\d+):.*?(?=^## |^### |\Z)", text, re.M | re.S):
        entry, eid = m.group(0), m.group(1)
        for field in ERRATUM_FIELDS:
            if not re.search(rf"^- {field}:", entry, re.M):
                problems.append(f"{eid}: no '- {field}:' line in docs/errata.md")
        named = re.findall(r"`(tests/[\w/]+\.py::\w+)`", entry)
        if not named:
            problems.append(f"{eid}: names no test that settles it")
        for t in named:
            if _test_exists(t) is False:
                problems.append(f"{eid}: test {t} does not exist")
    return problems


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
        for i, e in by_id.items():
            if i not in ids and e.source != "notes":
                problems.append(f"{i}: in the table but not in the catalog {cat} "
                                "(a statement of the notes only needs source = \"notes\")")
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
        if e.scope and e.scope not in scope_ids():
            problems.append(f"{e.id}: scope note {e.scope!r} is not in docs/errata.md")
        for field, what in (("covers", "what its check covers"), ("limits", "what it cannot")):
            words = getattr(e, field).split()
            if len(words) < MIN_WORDS:
                problems.append(f"{e.id}: no {field} = \"...\" saying in words {what}")
        if e.covers and e.covers.strip() == e.statement.strip():
            problems.append(f"{e.id}: covers repeats the statement; say what the check covers")
        for name in e.reference + e.property:
            if not _resolve(name):
                problems.append(f"{e.id}: {name} does not exist")
        for t in e.tests:
            if _test_exists(t) is False:
                problems.append(f"{e.id}: test {t} does not exist")
    problems += _untraced_properties(entries)
    return problems + errata_problems() + check_notes(entries=entries)


def _untraced_properties(entries, properties=None) -> list[str]:
    """A registered property that no row names (by its function or its catalog ID): a
    made-up catalog ID would otherwise check something nobody can trace to the notes."""
    if properties is None:
        from ..properties.registry import all_properties
        properties = all_properties()
    named = {n.split(":")[-1].split(".")[-1] for e in entries for n in e.property}
    ids = {e.id for e in entries}
    return [f"{p.id}: property {p.name} is named by no row of the traceability table"
            for p in properties if p.name not in named and p.id not in ids]


# --- the notes' numbered items ----------------------------------------------------------------

NOTE_STATUSES = ("verified", "erratum", "definition", "not verifiable", "open")

#: The kinds of numbered items of the notes (besides the algorithms, which are figures).
KINDS = ("Definition", "Theorem", "Lemma", "Proposition", "Corollary", "Remark", "Example",
         "Claim")

#: A numbered item's heading at the start of a line of the notes' text.
HEADING = re.compile(r"^ ?(" + "|".join(KINDS) + r") ([1-4]\.\d+)\b")

#: Any "<Word> <chapter>.<n>." at the start of a line: a numbered heading of some kind.  A
#: kind that is neither in :data:`KINDS` nor "Figure" is reported (a new kind of item).
ANY_HEADING = re.compile(r"^ ?([A-Z][a-z]+) ([1-4]\.\d+)\. ")

#: A figure caption of chapters 1-4.  The algorithms of the notes are figures (the text
#: calls Figure 4.13 "Algorithm 4.13"): a caption is an algorithm when its first sentence
#: names an algorithm ("Edge-flip algorithm.", "Simplicial minimal surface algorithm (with
#: ...)", not "... from Algorithm 4.23.") or when the figure is pseudo-code (a "Data:" line
#: since the previous caption).
FIGURE = re.compile(r"^ ?Figure ([1-4]\.\d+)\. ([^.]*(?:\.\d[^.]*)*)")
_NAMES_AN_ALGORITHM = re.compile(r"\balgorithm\b(?! \d)", re.I)

#: A reference to an algorithm anywhere in the text ("use Algorithm 4.13"): every one must be
#: a figure found as an algorithm, else the algorithm rule above has missed one.
ALGORITHM_REFERENCE = re.compile(r"\bAlgorithm ([1-4]\.\d+)\b")


@dataclass(frozen=True)
class NoteItem:
    name: str                    # "Theorem 2.6", "Algorithm 4.23", "Section 1.2: ..."
    line: int
    title: str
    status: str
    rows: tuple[str, ...] = ()
    reason: str = ""
    note: str = ""                 # what of the item the rows leave out, if anything


def load_notes(path: Path | None = None) -> list[NoteItem]:
    """The items of ``notes.toml`` (default: ours), in the notes' order."""
    with open(path or NOTES, "rb") as fh:
        data = tomllib.load(fh)
    return [NoteItem(name=k, line=v["line"], title=v.get("title", ""), status=v["status"],
                     rows=tuple(v.get("rows", ())), reason=v.get("reason", ""),
                     note=v.get("note", ""))
            for k, v in data.items()]


def notes_path() -> Path | None:
    """The notes' text: $DDG_NOTES, else ../shared/seed/*.txt beside the repository."""
    env = os.environ.get("DDG_NOTES")
    if env:
        return Path(env) if Path(env).is_file() else None
    repo = repository()
    if repo is None:
        return None
    return next(iter(sorted((repo.parent / "shared" / "seed").glob("*.txt"))), None)


def note_headings(path: Path) -> dict[str, int]:
    """{item name: line} of every numbered item of chapters 1-4 in the notes' text (the
    first occurrence at the start of a line): the headings of :data:`KINDS` and the
    algorithm figures ("Algorithm 4.13" for the caption "Figure 4.13. Edge-flip
    algorithm.")."""
    found: dict[str, int] = {}
    pseudo_code = False                       # a "Data:" line since the last caption
    for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        m = HEADING.match(line)
        if m:
            found.setdefault(f"{m.group(1)} {m.group(2)}", n)
            continue
        f = FIGURE.match(line)
        if f:
            if pseudo_code or _NAMES_AN_ALGORITHM.search(f.group(2)):
                found.setdefault(f"Algorithm {f.group(1)}", n)
            pseudo_code = False
        elif line.lstrip().startswith("Data:"):
            pseudo_code = True
    return found


def note_heading_problems(path: Path) -> list[str]:
    """What :func:`note_headings` may have missed in the text at ``path``: a numbered
    heading of a kind it does not know, and an algorithm the text refers to ("Algorithm
    4.13") that is not one of its algorithm figures."""
    text = path.read_text(encoding="utf-8")
    found = note_headings(path)
    problems = []
    for n, line in enumerate(text.splitlines(), 1):
        m = ANY_HEADING.match(line)
        if m and m.group(1) not in KINDS + ("Figure",):
            problems.append(f"line {n} of the notes: '{m.group(1)} {m.group(2)}' is a numbered "
                            "heading of a kind application/traceability.py does not know (KINDS)")
    refs = set(ALGORITHM_REFERENCE.findall(text))
    for ref in sorted(refs, key=lambda x: tuple(map(int, x.split(".")))):
        if f"Algorithm {ref}" not in found:
            problems.append(f"Algorithm {ref} is referred to in the notes but no algorithm figure "
                            f"{ref} was found (application/traceability.py, FIGURE)")
    return problems


def check_notes(path: Path | None = None, entries=None) -> list[str]:
    """Every way the notes table is not true, as messages; empty when it is."""
    problems: list[str] = []
    items = load_notes(path)
    rows = {e.id: e for e in (entries if entries is not None else load()[1])}
    for it in items:
        if it.status not in NOTE_STATUSES:
            problems.append(f"{it.name}: unknown status {it.status!r}")
        if it.status in ("verified", "erratum"):
            if not it.rows:
                problems.append(f"{it.name}: {it.status} but no traceability row named")
            for r in it.rows:
                if r not in rows:
                    problems.append(f"{it.name}: row {r!r} is not in the traceability table")
                elif rows[r].status not in ("verified", "erratum"):
                    problems.append(f"{it.name}: row {r} is {rows[r].status!r}")
            if it.status == "erratum" and not any(rows.get(r) and rows[r].status == "erratum"
                                                  for r in it.rows):
                problems.append(f"{it.name}: 'erratum' but none of its rows is an erratum")
        elif not it.reason:
            problems.append(f"{it.name}: status {it.status!r} needs a reason")
    text = notes_path()
    if text is not None:
        lines = text.read_text(encoding="utf-8").splitlines()
        headings = note_headings(text)
        problems += note_heading_problems(text)
        named = {it.name for it in items}
        for name, n in headings.items():
            if name not in named:
                problems.append(f"{name} (line {n} of the notes) is not in application/notes.toml")
        for it in items:
            if it.name in headings and headings[it.name] != it.line:
                problems.append(f"{it.name}: line {it.line}, but the notes have it at line "
                                f"{headings[it.name]}")
            elif it.name not in headings and not it.name.startswith("Section "):
                problems.append(f"{it.name}: no such heading in the notes")
            elif not 1 <= it.line <= len(lines):
                problems.append(f"{it.name}: line {it.line} is past the end of the notes")
            elif it.name.startswith("Section ") and "#" not in lines[it.line - 1]:
                problems.append(f"{it.name}: line {it.line} of the notes holds no connected sum")
    return problems
