"""The report leads with the root cause: one group per wrong protocol method, with the wrong
answer on the smallest counterexample; one line per crash message; ties in one line (issue 41,
item 2)."""

from __future__ import annotations

import re

from ddg_oracle.application.cli import main


def _run(capsys, *argv):
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def test_one_planted_method_bug_is_one_root_cause_naming_the_method_and_the_entry(capsys):
    rc, out, _ = _run(capsys, "check", "--impl", "examples.numpy_cotan:SignError", "--only",
                      "D3.1", "T3.6", "T3.1", "R3.3", "L4.18", "--workers", "1", "--profile", "ci")
    assert rc == 1
    head = out.split("passed (of the applicable checks)")[0]
    assert re.search(r"^FAILED \(\d+\): 1 root cause$", head, re.M), head
    cause = head.splitlines()[1]
    assert "cotan_laplacian is wrong" in cause and "properties fail" in cause
    # the wrong entry of the smallest counterexample, from compare's diagnosis
    assert re.search(r"cotan_laplacian at entry \(\d+, \d+\): expected -?[\d.e-]+, observed "
                     r"-?[\d.e-]+ \([\d.e+]+ x the bound\)", head.replace("\n  ", " ")), head
    # one full block for the cause, naming the others
    assert out.count("reproduce (raises the same failure)") == 1
    assert "the same cause" in out


def test_identical_crashes_collapse_into_one_line_with_a_count(capsys):
    rc, out, _ = _run(capsys, "check", "--impl", "tests.misbehaving:AbortsAlways", "--only",
                      "D1.6", "R1.5", "CS", "--workers", "1", "--budget", "20")
    assert rc == 1
    head = out.split("passed (of the applicable checks)")[0]
    assert re.search(r"^crashed \(3\): 1 message$", head, re.M), head
    assert re.search(r"\[x3\]$", head, re.M)


def test_ties_are_one_line_per_implementation_unless_listed(capsys):
    args = ("check", "--impl", "tests.test_cli:RoundsFlatVertices", "--only", "L2.4",
            "--profile", "ci", "--workers", "1")
    rc, out, _ = _run(capsys, *args)
    assert rc == 0
    assert re.search(r"^tie disagreements \(1\): .*--ties lists them\)$", out, re.M)
    assert re.search(r"^  rounds-flat-vertices 1 \(L2\.4\)$", out, re.M), out
    assert "tie disagreement: exactly flat vertex" not in out
    rc, out, _ = _run(capsys, *args, "--ties")
    assert "tie disagreement: exactly flat vertex" in out


def test_a_wrong_genus_in_r1_6_is_blamed_on_genus():
    """R1.6 reads genus when the implementation has it (Property.also): its failure was
    blamed on euler_characteristic or boundary_loops, and the catch benchmark, which runs
    the properties that call a planted method, never ran R1.6 on a genus bug (0 of 3)."""
    from benchmarks.planted.variants import GenusIgnoresBoundary
    from ddg_oracle.properties import PROPERTIES
    from ddg_oracle.properties.profiles import profile
    from ddg_oracle.properties.runner import FAILED, run_property
    assert "genus" in PROPERTIES["R1.6"].methods
    r = run_property(PROPERTIES["R1.6"], GenusIgnoresBoundary(), profile("ci"))
    assert r.status == FAILED and "wrong" in str(r.failure) and "genus" in str(r.failure)


def test_a_convention_hint_needs_every_diagnosed_member_and_no_method_it_would_break():
    """Two misleading hints a helper found: a bug doubling only the interior weights agrees
    with weights=full on D3.1's closed tetrahedron, and the root cause of 9 properties took
    that one member's hint (the other 8 diagnoses explained nothing); a bug doubling only
    area_gradient was told to declare weights=full, which would halve its right Laplacian."""
    from types import SimpleNamespace as R
    from ddg_oracle.application.causes import convention_hint, group_hint

    def row(q, status, *names):
        return {"quantity": q, "status": status, "explained_by": list(names), "where": None,
                "expected": None, "observed": None, "worst": None, "note": None}
    full = R(diagnosis=[row("cotan_laplacian", "DIFFERS", "weights=full")])
    plain = R(diagnosis=[row("cotan_laplacian", "DIFFERS")])
    assert "declare" in convention_hint(full)
    assert group_hint([full, plain], [0, 1]) is None
    assert group_hint([full, full, R(diagnosis=None)], [0, 1, 2]) == convention_hint(full)
    gradient_only = R(diagnosis=[row("area_gradient", "DIFFERS", "weights=full"),
                                 row("cotan_laplacian", "agrees")])
    assert convention_hint(gradient_only) is None
