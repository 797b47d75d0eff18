"""Bad options, bad files and unwritable places are one-line errors with exit 2, checked
before any work starts, never a traceback nor a result blamed on a library (issue 45,
items 4 and 5)."""

from __future__ import annotations

import json
import os
import time

import pytest

from ddg_oracle.cli import main

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VECTORS = os.path.join(ROOT, "vectors")


def _run(capsys, *argv):
    t0 = time.monotonic()
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err, time.monotonic() - t0


def _one_line(err: str) -> str:
    lines = [x for x in err.splitlines() if x.strip()]
    assert len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


@pytest.mark.parametrize("answers, words", [("/dev/zero", "it is a device"),
                                            ("FIFO", "it is a FIFO"),
                                            ("EMPTY", "no answer in it")])
def test_verify_refuses_a_device_a_fifo_and_an_empty_file_at_once(capsys, tmp_path, answers, words):
    if answers == "FIFO":
        answers = str(tmp_path / "fifo")
        os.mkfifo(answers)
    elif answers == "EMPTY":
        answers = str(tmp_path / "empty.jsonl")
        open(answers, "w").close()
    rc, _, err, seconds = _run(capsys, "verify", VECTORS, answers)
    assert rc == 2 and words in _one_line(err) and seconds < 5


@pytest.mark.parametrize("args, words", [
    (["--timeout", "0"], "--timeout must be a positive"), (["--timeout", "-1"], "--timeout"),
    (["--width", "0"], "--width must be at least"), (["--only", ""], "no catalog ID given"),
    (["--workers", "0"], "--workers must be >= 1"),
])
def test_bad_check_options_are_usage_errors_before_any_work(capsys, args, words):
    rc, out, err, seconds = _run(capsys, "check", "--impl", "reference", *args)
    assert rc == 2 and words in _one_line(err) and out == ""


@pytest.mark.parametrize("variable, value", [("DDG_EXAMPLE_TIME_LIMIT", "soon"),
                                             ("DDG_MEMORY_LIMIT", "lots"),
                                             ("DDG_MESH_SIZE_LIMIT", "big")])
def test_bad_environment_values_are_usage_errors_not_library_crashes(capsys, monkeypatch,
                                                                      variable, value):
    monkeypatch.setenv(variable, value)
    rc, out, err, _ = _run(capsys, "check", "--impl", "reference", "--only", "D1.6")
    assert rc == 2 and variable in _one_line(err) and "crashed" not in out


def test_vectors_onto_an_existing_file_is_a_usage_error(capsys, tmp_path):
    target = tmp_path / "taken"
    target.write_text("mine")
    rc, _, err, _ = _run(capsys, "vectors", "--out", str(target))
    assert rc == 2 and "is an existing file" in _one_line(err)
    assert target.read_text() == "mine"


def test_an_unwritable_report_directory_is_a_usage_error(capsys):
    rc, _, err, _ = _run(capsys, "check", "--impl", "reference", "--only", "D1.6",
                         "--report", "/proc/ddg-oracle-cannot/report")
    assert rc == 2 and "--report" in _one_line(err)


@pytest.mark.parametrize("run", [{"argv": "check", "seed": 1}, {"argv": ["--only", "D1.6"],
                                                                  "seed": "zero"}, []])
def test_a_damaged_run_file_is_a_usage_error_on_resume(capsys, tmp_path, run):
    (tmp_path / "run.json").write_text(json.dumps(run))
    (tmp_path / "results.jsonl").write_text("")
    rc, _, err, _ = _run(capsys, "check", "--resume", str(tmp_path))
    assert rc == 2 and "--resume" in _one_line(err)


def test_a_moved_report_directory_resumes_where_it_is(capsys, tmp_path):
    first = tmp_path / "first"
    rc, _, _, _ = _run(capsys, "check", "--impl", "reference", "--only", "D1.6", "X1.4",
                       "--workers", "1", "--report", str(first))
    assert rc == 0
    lines = (first / "results.jsonl").read_text().splitlines()
    (first / "results.jsonl").write_text(lines[0] + "\n")        # as if interrupted
    moved = tmp_path / "moved"
    first.rename(moved)
    rc, out, err, _ = _run(capsys, "check", "--resume", str(moved))
    assert rc == 0, err
    assert f"report: {moved}" in out and not first.exists()
    assert len((moved / "results.jsonl").read_text().splitlines()) == 2
