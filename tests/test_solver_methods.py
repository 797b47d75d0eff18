"""The protocol's area_gradient and solve_dirichlet (T3.9, T3.2, C3.4 / T3.5 checked on the
implementation's own gradient and solver, not on its matrix): libigl and gpytoolbox pass,
planted bugs in a solver and in a gradient are caught."""

import numpy as np
import pytest

from examples.numpy_mesh import NumpyMesh
from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.profiles import profile
from ddg_oracle.properties.runner import FAILED, PASSED, run_property


class _Only:
    """Only the two methods of a NumpyMesh, so the properties check them and nothing else."""
    def __init__(self):
        self._m = NumpyMesh()

    def solve_dirichlet(self, V, F, boundary, values):
        return self._m.solve_dirichlet(V, F, boundary, values)

    def area_gradient(self, V, F):
        return self._m.area_gradient(V, F)


class UniformWeights(_Only):
    """Planted: the graph Laplacian with weight 1 per edge (a combinatorial Laplacian)."""
    name = "uniform-weights-solver"

    def solve_dirichlet(self, V, F, boundary, values):
        import scipy.sparse as sp
        import scipy.sparse.linalg as sla
        F = np.asarray(F)
        E = np.unique(np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), 1), axis=0)
        n = len(V)
        W = sp.coo_matrix((np.ones(len(E)), (E[:, 0], E[:, 1])), shape=(n, n))
        W = (W + W.T).tocsr()
        L = (sp.diags(np.asarray(W.sum(1)).ravel()) - W).tocsr()
        u = np.zeros(n)
        u[boundary] = values
        inner = np.setdiff1d(np.arange(n), boundary)
        if len(inner):
            u[inner] = sla.spsolve(L[inner][:, inner].tocsc(), -(L[inner][:, boundary] @ u[boundary]))
        return u


class HalfGradient(_Only):
    """Planted: the mean curvature normal's factor 1/2 applied twice."""
    name = "half-gradient"

    def area_gradient(self, V, F):
        return self._m.area_gradient(V, F) / 2


def _run(pid, impl):
    return run_property(PROPERTIES[pid], impl, profile("ci"))


@pytest.mark.parametrize("pid", ["T3.2", "C3.4 / T3.5", "T3.9"])
def test_a_correct_solver_and_gradient_pass(pid):
    r = _run(pid, _Only())
    assert r.status == PASSED and r.examples > 0, r.failure or r.error


def test_a_solver_with_uniform_weights_is_caught_by_the_energy():
    r = _run("C3.4 / T3.5", UniformWeights())
    assert r.status == FAILED
    assert "solve_dirichlet: the solution is not a critical point" in str(r.failure)


class LibiglSign(_Only):
    """Planted: libigl's cotmatrix @ V taken as it is (negative semidefinite: the sign)."""
    name = "libigl-sign-gradient"

    def area_gradient(self, V, F):
        return -self._m.area_gradient(V, F)


@pytest.mark.parametrize("planted", [HalfGradient, LibiglSign])
def test_a_wrong_factor_or_sign_of_the_area_gradient_is_caught(planted):
    r = _run("T3.9", planted())
    assert r.status == FAILED and "area_gradient is not the area gradient" in str(r.failure)
    assert len(r.failure.mesh[1]) <= 2             # shrunk to a face or two


@pytest.mark.parametrize("spec", ["libigl", "gpytoolbox"])
@pytest.mark.parametrize("pid", ["T3.2", "C3.4 / T3.5", "T3.9"])
def test_libraries_solvers_and_gradients(spec, pid):
    from ddg_oracle.application.implementations import load_implementation
    impl = load_implementation(spec)
    assert {"solve_dirichlet", "area_gradient"} <= set(dir(impl))
    r = _run(pid, impl)
    assert r.status == PASSED and r.examples > 0, r.failure or r.error


def test_solve_dirichlet_through_the_executable_protocol():
    import sys
    from ddg_oracle.oracles.executable import Executable
    impl = Executable([sys.executable, "-c", "from examples.numpy_mesh import NumpyMesh; "
                       "from ddg_oracle.oracles.executable import serve; serve(NumpyMesh())"])
    V = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0]])
    F = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]])
    u = impl.solve_dirichlet(V, F, np.array([1, 2, 3, 4]), np.array([1.0, 2.0, 3.0, 2.0]))
    # the square's centre: equal cotan weights, the mean of the four values
    assert u.tolist() == pytest.approx([2.0, 1.0, 2.0, 3.0, 2.0], abs=4 * 2.0 ** -52)
    assert impl.area_gradient(V, F)[0].tolist() == pytest.approx([0, 0, 0], abs=2.0 ** -50)
    impl.close()
