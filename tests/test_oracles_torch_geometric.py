"""PyTorch Geometric (ddg_oracle.oracles.torch_geometric) in its own conventions:
``laplacian=negative`` declared, the factor 1/2 the notes', computed in float64 on the
positions handed over; every applicable property passes, and without the declaration the
diagnosis names it.

Needs ``pip install -e '.[torch-geometric]'`` (torch: a CPU build, see the adapter)."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("torch_geometric")

from ddg_oracle.application.causes import convention_hint  # noqa: E402
from ddg_oracle.application.jobs import with_diagnosis  # noqa: E402
from ddg_oracle.oracles.exact_reference import ReferenceImplementation  # noqa: E402
from ddg_oracle.oracles.torch_geometric import TorchGeometric  # noqa: E402
from ddg_oracle.properties import PROPERTIES  # noqa: E402
from ddg_oracle.properties.conventions import declared, to_reference  # noqa: E402
from ddg_oracle.properties.profiles import profile  # noqa: E402
from ddg_oracle.protocol.methods import capabilities  # noqa: E402
from ddg_oracle.properties.runner import FAILED, run_property  # noqa: E402
from tests.property_checks import every_property_unshrunk  # noqa: E402

#: a generic tetrahedron (obtuse corners, no symmetry) and a vertex used by no face
V = np.array([[0.0, 0, 0], [1, 0.1, 0.2], [0.3, 0.9, 0.4], [0.2, 0.3, 1.1], [5, 5, 5]])
F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
TG = TorchGeometric()
REF = ReferenceImplementation()


def test_declares_its_convention_and_computes_the_laplacian_only():
    assert [c.name for c in declared(TG)] == ["laplacian=negative"]
    assert capabilities(TG) == {"cotan_laplacian"}


def test_the_matrix_is_minus_the_notes_laplacian_in_float64():
    C = TG.cotan_laplacian(V, F)
    L = REF.cotan_laplacian(V, F)
    np.testing.assert_allclose(C.toarray(), -L.toarray(), rtol=0, atol=1e-15)
    assert C[4].nnz == 0 or not C[4].toarray().any()          # the unused vertex: a zero row
    np.testing.assert_allclose(to_reference(declared(TG), "cotan_laplacian", C, V, F).toarray(),
                               L.toarray(), rtol=0, atol=1e-15)


def test_every_applicable_property_passes():
    results = every_property_unshrunk(TG, 1)
    ran = {r.property_id: r for r in results if r.status != "not applicable"}
    assert {"D3.1", "T3.6", "R3.3"} <= set(ran), sorted(ran)
    assert all(r.status in ("passed", "tie disagreement") for r in ran.values()), \
        [(r.property_id, r.status, str(r.failure)) for r in ran.values() if not r.ok]


def test_undeclared_the_sign_fails_and_the_diagnosis_names_it():
    undeclared = type("Undeclared", (TorchGeometric,), {"conventions": None,
                                                        "name": "torch-geometric-undeclared"})()
    p = PROPERTIES["D3.1"]
    r = with_diagnosis(run_property(p, undeclared, profile("default"), seed=0), p, undeclared)
    assert r.status == FAILED
    hint = convention_hint(r)
    assert hint is not None and "laplacian=negative" in hint, r.diagnosis
