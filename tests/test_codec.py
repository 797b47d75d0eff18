"""Replay strings and resumed results are data, never code (issue 45, item 3): a crafted
report directory or replay string runs nothing; every drawn example round-trips."""

from __future__ import annotations

import base64
import json
import pickle
import zlib

import pytest
from hypothesis import HealthCheck, Phase, given, settings

from ddg_oracle.application.cli import main
from ddg_oracle.properties import codec
from ddg_oracle.properties.counterexample import decode_example, encode_example, replay
from ddg_oracle.properties.registry import all_properties
from ddg_oracle.properties.runner import Result


class _Touch:
    """Unpickling this creates a file: what a crafted pickle can do."""

    def __init__(self, path):
        self.path = path

    def __reduce__(self):
        return (open, (self.path, "w"))


def test_a_pickled_replay_string_is_refused_and_runs_nothing(tmp_path):
    marker = tmp_path / "ran"
    crafted = "ddg1:" + base64.b64encode(zlib.compress(pickle.dumps(_Touch(str(marker))))).decode()
    with pytest.raises(ValueError, match="pickle"):
        replay("D1.6", object(), crafted)
    assert not marker.exists()


@pytest.mark.parametrize("data", [
    {"r": "os.system", "v": "touch x"}, {"r": "Example", "v": {"t": []}}, {"q": [1, 0]},
    {"f": "__import__('os')"}, {"t": 1}, {"x": 1}, [{"d": [[[1], 2]]}],
])
def test_values_the_codec_did_not_write_are_refused(data):
    with pytest.raises(codec.BadEncoding):
        codec.decode(data)


def test_a_compressed_bomb_is_refused_without_inflating_it():
    bomb = "ddg2:" + base64.b64encode(zlib.compress(b"[" + b"0," * (40 << 20) + b"0]")).decode()
    with pytest.raises(codec.BadEncoding, match="inflates"):
        decode_example(bomb)


def test_every_property_example_round_trips():
    for p in all_properties():
        @settings(max_examples=3, database=None, suppress_health_check=list(HealthCheck),
                  phases=[Phase.generate], deadline=None)
        @given(p.strategy())
        def round_trip(example):
            assert decode_example(encode_example(example)) == example, p.id
        round_trip()


def test_a_result_round_trips_with_its_failure():
    from ddg_oracle.properties.registry import PropertyFailure, TieDisagreement
    f = TieDisagreement("L2.4", object(), "flat", mesh=([[0.0, 0, 0]], [[0, 0, 0]]),
                        element="vertex 0", expected=0.0, observed=1e-16, bound=4e-16)
    r = Result("L2.4", "p", "x", "tie disagreement", examples=3, wanted=25, failure=f,
               exact=[["1/3", "0", "0"]], diagnosis=[{"quantity": "angle_defects", "worst": 2.5}])
    back = Result.from_json(json.loads(json.dumps(r.to_json())))
    assert isinstance(back.failure, TieDisagreement) and str(back.failure) == str(f)
    assert back.exact == r.exact and back.diagnosis == r.diagnosis and back.wanted == 25
    with pytest.raises(codec.BadEncoding):
        Result.from_json({"d": [["status", "owned"]]})
    assert isinstance(f, PropertyFailure)


def test_a_crafted_report_directory_runs_nothing_on_resume(tmp_path, capsys):
    report = tmp_path / "report"
    rc = main(["check", "--impl", "reference", "--only", "D1.6", "X1.4", "--workers", "1",
               "--report", str(report)])
    assert rc == 0
    lines = (report / "results.jsonl").read_text().splitlines()
    marker = tmp_path / "ran"
    entry = json.loads(lines[0])
    # what an old reader unpickled, and a forged record in the new field
    entry["pickled"] = base64.b64encode(pickle.dumps([_Touch(str(marker))])).decode()
    entry["resume"] = [{"r": "Example", "v": {"d": [["positions", {"t": []}]]}}]
    (report / "results.jsonl").write_text(json.dumps(entry) + "\n" + "\n".join(lines[1:]) + "\n")
    capsys.readouterr()
    rc = main(["check", "--resume", str(report)])
    err = capsys.readouterr().err
    assert rc == 2 and "is not a result ddg-oracle wrote" in err and "Traceback" not in err
    assert not marker.exists()
