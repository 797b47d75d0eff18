"""properties/memo.py: values derived from an example are shared only where they are the
same -- per example content and, for bounds, per machine epsilon."""

import contextvars

import numpy as np

from ddg_oracle.properties import memo, protocol
from ddg_oracle.properties.laplacian import Exact
from ddg_oracle.properties.strategies import mesh_case


def _tetrahedron():
    V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    return mesh_case(V, [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)], "tetrahedron")


def test_equal_cases_share_one_exact_reference():
    memo.clear()
    a, b = _tetrahedron(), _tetrahedron()
    assert a is not b and Exact.of(a) is Exact.of(b)


def test_the_bounds_of_a_float32_implementation_are_not_a_float64_ones():
    memo.clear()
    case = _tetrahedron()
    B64 = Exact.of(case).B

    def as_float32():
        protocol._epsilon.set(2.0 ** -23)
        return Exact.of(case).B

    B32 = contextvars.copy_context().run(as_float32)
    assert Exact.of(case).B is B64                 # float64 again: the float64 bounds
    nz = B64 > 0
    assert nz.any() and np.allclose(B32[nz] / B64[nz], 2.0 ** 29)
