"""The project's own promises: README commands, CI script, traceability table, CLI exit codes."""

import ast
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from ddg_oracle.application.cli import main
from ddg_oracle.application import traceability

ROOT = Path(__file__).resolve().parent.parent


def _readme_commands():
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = text.split("## The two commands", 1)[1].split("\n## ", 1)[0]
    return [c.strip() for c in re.findall(r"```bash\n(.+?)\n\s*```", section, re.S)]


def test_readme_has_exactly_two_commands_and_ci_runs_both_verbatim():
    commands = _readme_commands()
    assert len(commands) == 2
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    for c in commands:
        assert c.strip() in ci.splitlines(), f"CI does not run README's command: {c}"
    assert "ddg-oracle check" in commands[0]
    assert "pytest" in commands[1]
    assert '"$rc" -eq 5' in ci            # pytest's "no tests collected" fails CI


def test_reference_imports_only_the_standard_library():
    # The one exception is an export adapter (to_scipy) marked as such in a comment.
    allowed = set(sys.stdlib_module_names) | {"reference"}
    for path in (ROOT / "reference").rglob("*.py"):
        source = path.read_text(encoding="utf-8")
        lines = source.splitlines()
        for node in ast.walk(ast.parse(source)):
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0:
                names = [node.module]
            else:
                continue
            for name in names:
                top = name.split(".")[0]
                if top not in allowed:
                    assert "export adapter" in lines[node.lineno - 1] + lines[node.lineno - 2], \
                        f"{path.name}:{node.lineno} imports {name}"


def test_reference_uses_no_float_literals_or_float_calls_in_decisions():
    # floats may appear only in conversions out (float views); never math.isclose / tolerances
    for path in (ROOT / "reference").rglob("*.py"):
        text = path.read_text(encoding="utf-8")
        assert "isclose" not in text and "1e-" not in text, path.name


def test_traceability_table_is_true():
    assert traceability.check() == []


def test_traceability_check_catches_a_missing_function(tmp_path):
    bad = tmp_path / "t.toml"
    text = traceability.TABLE.read_text(encoding="utf-8")
    text = text.replace('reference = ["ddg_oracle.reference.combinatorics:Triangulation.euler_characteristic"]',
                        'reference = ["ddg_oracle.reference.combinatorics:Triangulation.no_such_thing"]', 1)
    bad.write_text(text, encoding="utf-8")
    assert any("no_such_thing does not exist" in p for p in traceability.check(bad))


def test_every_claimed_row_has_a_registered_property():
    from ddg_oracle.properties.registry import all_properties
    claimed, entries = traceability.load()
    registered = {f"{p.check.__module__}:{p.name}" for p in all_properties()}
    for e in entries:
        if e.chapter in claimed:
            # structure / statements: properties of the reference's own values, no protocol
            structural = {p for p in e.property if ".structure:" in p or ".statements:" in p}
            assert set(e.property) <= registered | structural, e.id


def test_traceability_check_catches_a_missing_test_and_an_unverified_claimed_row(tmp_path):
    bad = tmp_path / "t.toml"
    text = traceability.TABLE.read_text(encoding="utf-8")
    text = text.replace("test_X1_4_named_surfaces", "test_that_was_never_written", 1)
    i = text.index('["R1.6"]')
    text = text[:i] + text[i:].replace('status = "verified"', 'status = "not yet"', 1)
    bad.write_text(text, encoding="utf-8")
    problems = traceability.check(bad)
    assert any("test_that_was_never_written does not exist" in p for p in problems)
    assert any(p.startswith("R1.6: chapter 1 is claimed") for p in problems)


def test_cli_theorems_check_exits_zero(capsys):
    assert main(["theorems", "--check"]) == 0
    assert "traceability table and notes table: true" in capsys.readouterr().out


def test_cli_check_passes_on_the_reference(capsys):
    assert main(["check", "--impl", "reference", "--only", "D1.6", "--only", "X1.4"]) == 0
    out = capsys.readouterr().out
    assert re.search(r"^passed .*\n  reference 2/2$", out, re.M)


def test_cli_check_fails_with_exit_1_on_a_wrong_implementation(capsys):
    assert main(["check", "--impl", "tests.planted_bugs:ChiIgnoresBoundary", "--only", "D1.6"]) == 1
    out = capsys.readouterr().out
    assert "FAILED" in out and "[D1.6]" in out


def test_cli_bad_usage_is_one_line_and_exit_2(capsys):
    assert main(["check", "--impl", "no.such.module:Thing"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("ddg-oracle: error:") and err.count("\n") == 1
    assert main(["check", "--impl", "reference", "--only", "Z9.9"]) == 2


def test_console_script_is_installed():
    exe = shutil.which("ddg-oracle")
    if exe is None:
        pytest.skip("ddg-oracle is not on PATH (package not installed)")
    out = subprocess.run([exe, "theorems"], capture_output=True, text=True)
    assert out.returncode == 0 and "D1.6" in out.stdout


def test_cli_check_reports_a_segfaulting_implementation_and_goes_on(capsys):
    # one worker: the crash and the tasks after it in one process (no pool of 2 to start)
    rc = main(["check", "--impl", "tests.misbehaving:SegfaultsOnBoundary", "--impl", "reference",
               "--only", "R1.6", "--only", "T1.1 / C1.2", "--profile", "ci", "--timeout", "20",
               "--workers", "1"])
    assert rc == 1
    out = capsys.readouterr().out
    assert "crashed" in out and "SIGSEGV" in out
    # the run went on: T1.1 / C1.2 passed on both, R1.6 on the reference
    assert re.search(r"^  segfaults-on-boundary 1/2, reference 2/2$", out, re.M), out


def _notes_copy(tmp_path, edit):
    from ddg_oracle.application import traceability
    text = traceability.NOTES.read_text(encoding="utf-8")
    path = tmp_path / "notes.toml"
    path.write_text(edit(text), encoding="utf-8")
    return traceability.check_notes(path)


def test_notes_table_lists_every_heading_of_the_notes_at_its_line():
    from ddg_oracle.application import traceability
    text = traceability.notes_path()
    if text is None:
        pytest.skip("the notes' text (../shared/seed) is not beside the repository")
    headings = traceability.note_headings(text)
    items = {i.name: i for i in traceability.load_notes()}
    assert len(headings) >= 115 and set(headings) <= set(items)
    assert all(items[n].line == line for n, line in headings.items())
    assert traceability.check_notes() == []


def test_notes_check_fails_on_a_missing_item_a_wrong_line_and_an_unknown_row(tmp_path):
    from ddg_oracle.application import traceability
    if traceability.notes_path() is None:
        pytest.skip("the notes' text (../shared/seed) is not beside the repository")
    import re as _re
    dropped = _notes_copy(tmp_path, lambda t: _re.sub(r'\["Lemma 4\.8"\]\n(.+\n)+', "", t))
    assert any(p.startswith("Lemma 4.8 (line 2099 of the notes) is not in") for p in dropped)
    moved = _notes_copy(tmp_path, lambda t: t.replace("line = 2099", "line = 2100"))
    assert "Lemma 4.8: line 2100, but the notes have it at line 2099" in moved
    unknown = _notes_copy(tmp_path, lambda t: t.replace('rows = ["L4.8"]', 'rows = ["L9.9"]'))
    assert "Lemma 4.8: row 'L9.9' is not in the traceability table" in unknown
    bare = _notes_copy(tmp_path, lambda t: t.replace(
        'reason = "pure existence statement (Burago', 'note = "pure existence statement (Burago'))
    assert "Theorem 2.9: status 'not verifiable' needs a reason" in bare
    off = _notes_copy(tmp_path, lambda t: t.replace("line = 203", "line = 204"))
    assert "Section 1.2: M # S^2 = M: line 204 of the notes holds no connected sum" in off


def test_every_erratum_has_its_fields_and_an_existing_test(tmp_path):
    from ddg_oracle.application import traceability
    assert traceability.errata_problems() == []
    text = (traceability.DATA / "errata.md").read_text(encoding="utf-8")
    broken = tmp_path / "errata.md"
    broken.write_text(text.replace("- relied on: nothing (existence", "- used by: nothing (existence")
                      .replace("test_ER_17_the_second_identity_of_rippas_proof_has_u0_star",
                               "test_ER_17_gone"), encoding="utf-8")
    problems = traceability.errata_problems(broken)
    assert "ER-13: no '- relied on:' line in docs/errata.md" in problems
    if traceability.repository() is not None:
        assert ("ER-17: test tests/test_errata_proofs.py::test_ER_17_gone does not exist"
                in problems)


def test_the_manuals_counts_of_the_notes_items_and_errata_are_true():
    from ddg_oracle.application import traceability
    # the manual's page on the reference says them (README points there)
    readme = (Path(__file__).parent.parent / "docs" / "reference.md").read_text(encoding="utf-8")
    readme = " ".join(readme.split())
    items = traceability.load_notes()
    count = {s: sum(i.status == s for i in items) for s in traceability.NOTE_STATUSES}
    assert f"**{len(items)} items**" in readme
    assert f"{count['verified'] + count['erratum']} verified ({count['erratum']} of them" in readme
    assert f"{count['definition']} definitions, {count['not verifiable']} not verifiable" in readme
    assert f"**{count['open']} open**" in readme
    claimed, rows = traceability.load()
    assert f"table has {len(rows)} rows, {sum(r.source == 'notes' for r in rows)} of them" in readme
    assert f"**{len(traceability.errata_ids())} misprints**" in readme
