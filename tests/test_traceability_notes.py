"""`ddg-oracle theorems --check` notices every numbered item of the notes (algorithm figures
included) and every row that does not say what its check covers and what it cannot."""

import re

import pytest

from ddg_oracle.application import traceability
from ddg_oracle.application.cli import main

NOTES = traceability.notes_path()
needs_notes = pytest.mark.skipif(NOTES is None, reason="the notes' text (../shared/seed) is "
                                                       "not beside the repository")


@needs_notes
def test_every_numbered_item_is_found_and_listed():
    """116 numbered items: the eight heading kinds and the three algorithm figures (Figure
    3.6, 4.13, 4.23: the text calls Figure 4.13 'Algorithm 4.13'), each in notes.toml at its
    line, and nothing else."""
    headings = traceability.note_headings(NOTES)
    assert len(headings) == 116
    assert {n: l for n, l in headings.items() if n.startswith("Algorithm")} == {
        "Algorithm 3.6": 1633, "Algorithm 4.13": 2147, "Algorithm 4.23": 3015}
    kinds = {n.split()[0] for n in headings}
    assert kinds == set(traceability.KINDS) | {"Algorithm"}
    items = {i.name: i for i in traceability.load_notes()}
    assert set(headings) == {n for n in items if not n.startswith("Section ")}
    assert all(items[n].line == line for n, line in headings.items())
    assert traceability.note_heading_problems(NOTES) == []
    assert traceability.check_notes() == []


@needs_notes
def test_check_fails_when_any_single_item_is_missing(tmp_path):
    """Drop each of the 116 items from a copy of notes.toml in turn: the check names it."""
    text = traceability.NOTES.read_text(encoding="utf-8")
    blocks = re.split(r'(?m)^(?=\[")', text)
    header, items = blocks[0], blocks[1:]
    entries = traceability.load()[1]
    path = tmp_path / "notes.toml"
    names = [re.match(r'\["(.+)"\]', b).group(1) for b in items]
    numbered = [n for n in names if not n.startswith("Section ")]
    assert len(numbered) == 116
    for k, name in enumerate(names):
        if name.startswith("Section "):
            continue
        path.write_text(header + "".join(items[:k] + items[k + 1:]), encoding="utf-8")
        problems = traceability.check_notes(path, entries=entries)
        assert any(p.startswith(f"{name} (line ") and "is not in application/notes.toml" in p
                   for p in problems), (name, problems)


@needs_notes
def test_algorithm_figures_and_unknown_kinds_in_a_changed_text(tmp_path, monkeypatch):
    """A text with a new algorithm figure (named in its caption, or pseudo-code under a
    plain caption), a reference to an algorithm whose figure is not recognisable, and a
    numbered heading of a new kind: each is reported."""
    lines = NOTES.read_text(encoding="utf-8").splitlines()
    lines += ["",
              "Figure 4.90. A second edge-flip algorithm.",
              "",
              "Data: a triangulation.Result: another one.while something do",
              "end",
              "Figure 4.91. Iteration.",
              "",
              "Figure 4.92. A picture. We run Algorithm 4.92 (or Algorithm 4.93) on it.",
              "",
              "Conjecture 4.30. Something about flips."]
    changed = tmp_path / "notes.txt"
    changed.write_text("\n".join(lines) + "\n", encoding="utf-8")
    n = len(lines)
    found = traceability.note_headings(changed)
    assert found["Algorithm 4.90"] == n - 8 and found["Algorithm 4.91"] == n - 4
    assert "Algorithm 4.92" not in found
    problems = traceability.note_heading_problems(changed)
    assert any("'Conjecture 4.30' is a numbered heading of a kind" in p for p in problems)
    assert any(p.startswith("Algorithm 4.92 is referred to") for p in problems)
    assert any(p.startswith("Algorithm 4.93 is referred to") for p in problems)
    monkeypatch.setenv("DDG_NOTES", str(changed))
    notes_problems = traceability.check_notes()
    for name in ("Algorithm 4.90", "Algorithm 4.91"):
        assert any(p.startswith(f"{name} (line ") for p in notes_problems)
    assert any("Conjecture 4.30" in p for p in notes_problems)


def test_every_row_says_what_it_covers_and_what_it_cannot(tmp_path):
    """Every row has `covers` and `limits` in words; a row without one, with a placeholder
    or with covers repeating its statement fails the check."""
    claimed, entries = traceability.load()
    assert all(len(e.covers.split()) >= traceability.MIN_WORDS and
               len(e.limits.split()) >= traceability.MIN_WORDS for e in entries)
    text = traceability.TABLE.read_text(encoding="utf-8")
    i = text.index('["T4.12"]')
    block_end = text.index("\n[", i + 1)
    block = text[i:block_end]
    cov = re.search(r'(?m)^covers = ".*"$', block).group(0)
    lim = re.search(r'(?m)^limits = ".*"$', block).group(0)
    statement = re.search(r'(?m)^statement = (".*")$', block).group(1)
    cases = {
        "no covers": (block.replace(cov + "\n", ""), 'T4.12: no covers = "..."'),
        "placeholder": (block.replace(lim, 'limits = "examples"'), 'T4.12: no limits = "..."'),
        "repeated": (block.replace(cov, f"covers = {statement}"), "T4.12: covers repeats"),
    }
    for name, (changed, message) in cases.items():
        bad = tmp_path / f"{name.replace(' ', '_')}.toml"
        bad.write_text(text[:i] + changed + text[block_end:], encoding="utf-8")
        assert any(p.startswith(message) for p in traceability.check(bad)), name


def test_theorems_prints_what_each_row_covers(capsys):
    assert main(["theorems"]) == 0
    out = capsys.readouterr().out
    claimed, entries = traceability.load()
    assert out.count("\n    covers: ") == out.count("\n    limits: ") == len(entries)
    assert "Algorithm 4.13" in out


def test_a_property_with_a_made_up_catalog_id_and_no_row_fails_the_check():
    """Issue 43: a property registered under an ID no row of the table names passed
    `theorems --check`."""
    from types import SimpleNamespace
    from ddg_oracle.properties.registry import all_properties
    _, entries = traceability.load()
    assert traceability._untraced_properties(entries) == []
    made_up = SimpleNamespace(id="X9.99", name="a_property_nobody_traced")
    problems = traceability._untraced_properties(entries, all_properties() + [made_up])
    assert problems == ["X9.99: property a_property_nobody_traced is named by no row of the "
                        "traceability table"]
