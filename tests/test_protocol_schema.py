"""docs/protocol.schema.json: generated from ddg_oracle.protocol.schema, a valid
draft 2020-12 schema, and true of real traffic: every request ddg-oracle sends and every
answer of the reference served through the protocol validate, across the properties of
every protocol method; malformed answers do not."""

import json
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import settings

jsonschema = pytest.importorskip("jsonschema")

from ddg_oracle.protocol import schema as protocol_schema  # noqa: E402
from ddg_oracle.oracles.executable import Executable  # noqa: E402
from ddg_oracle.properties import PROPERTIES  # noqa: E402
from ddg_oracle.protocol.methods import METHODS  # noqa: E402
from ddg_oracle.properties.profiles import profile  # noqa: E402
from ddg_oracle.properties.runner import CRASHED, run_property  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
COMMITTED = ROOT / "docs" / "protocol.schema.json"
SCHEMA = json.loads(COMMITTED.read_text(encoding="utf-8"))


def _valid(message, kind: str) -> bool:
    v = jsonschema.Draft202012Validator({"$ref": f"#/$defs/{kind}", "$defs": SCHEMA["$defs"]})
    return v.is_valid(message)


def test_the_committed_schema_is_the_generated_one_and_valid():
    assert COMMITTED.read_text(encoding="utf-8") == protocol_schema.text(), \
        "regenerate: python -m ddg_oracle.protocol.schema docs/protocol.schema.json"
    jsonschema.Draft202012Validator.check_schema(SCHEMA)
    assert SCHEMA["version"] == 1
    assert {f"answer.{m}" for m in METHODS} | {f"request.{m}" for m in METHODS} <= set(SCHEMA["$defs"])


def test_the_method_table_of_the_manual_is_the_generated_one():
    doc = (ROOT / "docs" / "protocol.md").read_text(encoding="utf-8")
    assert protocol_schema.with_method_table(doc) == doc, \
        "regenerate: python -m ddg_oracle.protocol.schema --table docs/protocol.md"
    table = doc.split(protocol_schema.TABLE_START)[1].split(protocol_schema.TABLE_END)[0]
    assert [line.split("`")[1] for line in table.strip().splitlines()[2:]] == list(METHODS)
    with pytest.raises(ValueError, match="no method table markers"):
        protocol_schema.with_method_table("# a page without the table\n")


def test_every_request_and_answer_of_a_run_validates(tmp_path):
    counts = tmp_path / "counts.json"
    impl = Executable([sys.executable, str(ROOT / "tests" / "schema_checked_driver.py"),
                       str(counts)], cwd=ROOT)
    assert impl.methods == set(METHODS)
    used = set()
    for pid, p in PROPERTIES.items():
        if p.methods - used:
            used |= p.methods
            r = run_property(p, impl, settings(profile("default"), max_examples=4), seed=1)
            assert r.status != CRASHED, (pid, r.error, impl.stderr_tail())
    # no property asks for barycentric areas (L3.7 checks the Voronoi ones)
    V, F = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]), np.array([[0, 1, 2]])
    assert list(impl.vertex_areas_barycentric(V, F)) == pytest.approx([1 / 6] * 3)
    used.add("vertex_areas_barycentric")
    impl.close()
    assert used == set(METHODS)
    checked = json.loads(counts.read_text())
    assert checked["requests"] > 100 and checked["answers"] == checked["requests"]


@pytest.mark.parametrize("kind, message", [
    ("answer.boundary_loops", {"id": 1, "value": [1, 2, 3]}),
    ("answer.angle_defects", {"id": 1, "value": [[0.1, 0.2]]}),
    ("answer.corner_angles", {"id": 1, "value": [[0.1, 0.2]]}),
    ("answer.cotan_laplacian", {"id": 1, "value": {"shape": [2, 2], "rows": [0]}}),
    ("answer.intrinsic_delaunay_triangulation", {"id": 1, "value": {"F": [[0, 1, 2]]}}),
    ("answer.edge_mean_curvature", {"id": 1, "value": [[0, 1]]}),
    ("answer.area", {"value": 1.0}),
    ("hello.answer", {"methods": ["angle_defect"]}),
    ("error.answer", {"id": 1, "error": {"kind": "crashed", "message": "x"}}),
])
def test_malformed_messages_do_not_validate(kind, message):
    assert not _valid(message, kind)


def test_well_formed_messages_validate():
    assert _valid({"id": 1, "value": [[0, 1, 0.5]]}, "answer.edge_mean_curvature")
    assert _valid({"methods": ["area"], "conventions": {"follows": {"X1": "y"},
                                                       "counterpart_arguments": []}}, "hello.answer")
    assert _valid({"id": 3, "error": {"kind": "outside_domain", "message": "boundary"}},
                  "error.answer")
    assert _valid({"command": ["./driver", "--fast"], "methods": ["area"],
                   "conventions": {"follows": {"X1": "y"}, "counterpart": "reference.json"}},
                  "manifest")
    assert not _valid({"methods": ["area"]}, "manifest")
