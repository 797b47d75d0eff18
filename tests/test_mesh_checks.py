"""The matrix checks of `ddg-oracle check --mesh` are sparse: they run on meshes of any size
(they were dense n x n and not applicable above 2,500 vertices), and still find one wrong
entry among a hundred thousand."""

import numpy as np
import pytest

from ddg_oracle.application.compare import compare_mesh
from ddg_oracle.application.meshes import MeshExamples, MeshInput, run_mesh_properties
from ddg_oracle.oracles.exact_reference import ReferenceImplementation
from ddg_oracle.properties.runner import FAILED, PASSED
from tests.planted_bugs import LaplaceBeltramiWithoutHalf

pytest.importorskip("igl")
from ddg_oracle.oracles.libigl import Libigl  # noqa: E402

MATRIX_CHECKS = {"D3.1", "T3.9", "E3.12", "L3.7"}


def _bumpy_grid(m: int, seed: int = 3):
    """A float grid of (m + 1)^2 vertices, jittered and bumped (not planar, some obtuse
    angles), squares split by alternating diagonals."""
    rng = np.random.default_rng(seed)
    i, j = np.meshgrid(np.arange(m + 1), np.arange(m + 1), indexing="ij")
    V = np.stack([i.ravel() + rng.uniform(-0.3, 0.3, i.size),
                  j.ravel() + rng.uniform(-0.3, 0.3, i.size),
                  rng.uniform(-0.2, 0.2, i.size)], axis=1) / m
    F = []
    for a in range(m):
        for b in range(m):
            p, q, r, s = a * (m + 1) + b, (a + 1) * (m + 1) + b, (a + 1) * (m + 1) + b + 1, \
                a * (m + 1) + b + 1
            F += [[p, q, r], [p, r, s]] if (a + b) % 2 else [[p, q, s], [q, r, s]]
    return V, np.array(F)


class LaplacianOnly:
    """libigl's cotan Laplacian and nothing else (compare then skips the other quantities)."""

    name = "libigl-laplacian"

    def cotan_laplacian(self, V, F):
        return Libigl().cotan_laplacian(V, F)


class OneWrongWeight(LaplacianOnly):
    """libigl's cotan Laplacian with the weight of one edge deep inside off by 1e-9 relative
    (both entries, so the matrix stays symmetric with zero row sums if the diagonal follows)."""

    name = "one-wrong-weight"

    def __init__(self, i, j):
        self.i, self.j = i, j

    def cotan_laplacian(self, V, F):
        A = super().cotan_laplacian(V, F).tolil()
        i, j = self.i, self.j
        d = A[i, j] * 1e-9
        A[i, j] += d
        A[j, i] += d
        A[i, i] -= d
        A[j, j] -= d
        return A.tocsr()


@pytest.fixture(scope="module")
def grid():
    V, F = _bumpy_grid(51)                    # 2,704 vertices, 5,202 faces
    return MeshExamples(MeshInput("bumpy grid", V.tolist(), F.tolist()))


def test_matrix_checks_run_beyond_the_old_dense_limit_and_pass_on_libigl(grid):
    assert len(grid.mesh.V) > 2500
    results = {r.property_id: r for r in run_mesh_properties(grid, Libigl(), only=MATRIX_CHECKS)}
    assert set(results) == MATRIX_CHECKS
    assert {r.status for r in results.values()} == {PASSED}, \
        {k: (r.status, r.note) for k, r in results.items()}


def test_one_wrong_weight_among_all_entries_is_found_and_named(grid):
    F = np.array(grid.mesh.F)
    i, j = int(F[2600, 0]), int(F[2600, 1])  # an edge near the middle
    r, = run_mesh_properties(grid, OneWrongWeight(i, j), only={"D3.1"})
    assert r.status == FAILED
    assert r.failure.element in ((i, j), (j, i), (i, i), (j, j))


def test_compare_reports_the_wrong_entry_of_a_sparse_matrix(grid):
    F = np.array(grid.mesh.F)
    i, j = int(F[2600, 0]), int(F[2600, 1])
    rows = compare_mesh(grid.mesh, [LaplacianOnly(), OneWrongWeight(i, j)], ReferenceImplementation())
    lap = {c.implementation: c for c in rows if c.quantity == "cotan_laplacian"}
    assert lap["libigl-laplacian"].status == "agrees" and lap["libigl-laplacian"].worst <= 1
    bad = lap["one-wrong-weight"]
    assert bad.status == "DIFFERS" and bad.over >= 2
    assert bad.where in {f"entry {(a, b)}" for a in (i, j) for b in (i, j)}
    assert bad.elements >= grid.surface.triangulation.n_edges * 2 + len(grid.mesh.V)


def test_the_intrinsic_delaunay_laplacian_is_a_mesh_file_check():
    # D4.8 / R4.9 on a float mesh that needs flips: libigl passes, the Laplace-Beltrami
    # weights without their 1/2 fail (the check was not run on mesh files before)
    V, F = _bumpy_grid(10, seed=5)
    ex = MeshExamples(MeshInput("small bumpy grid", V.tolist(), F.tolist()))
    from ddg_oracle.properties.delaunay_exact import DelaunayExact
    assert DelaunayExact.of(ex.example()).log          # not Delaunay as given
    r, = run_mesh_properties(ex, Libigl(), only={"D4.8 / R4.9"})
    assert r.status == PASSED, (r.note, r.error)
    r, = run_mesh_properties(ex, LaplaceBeltramiWithoutHalf(), only={"D4.8 / R4.9"})
    assert r.status == FAILED and "Laplace-Beltrami" in str(r.failure)


def test_compare_with_worker_processes_gives_the_rows_of_one_process():
    # the exact values and bounds computed in two spawned processes, the implementations
    # asked here: every row as in a single process (a wrong weight still found)
    V, F = _bumpy_grid(8, seed=3)
    mesh = MeshInput("small bumpy grid", V.tolist(), F.tolist())
    i, j = int(F[40, 0]), int(F[40, 1])
    impls = [Libigl(), OneWrongWeight(i, j)]
    one = compare_mesh(mesh, impls, ReferenceImplementation())
    two = compare_mesh(mesh, impls, ReferenceImplementation(), workers=2)
    assert [vars(r) for r in two] == [vars(r) for r in one]
    assert any(r.status == "DIFFERS" and r.quantity == "cotan_laplacian" for r in two)
    assert sum(r.status == "agrees" for r in two) >= 10


class AreaOffByOnePart(Libigl):
    """libigl with the total area 1 + 1e-9 times too large (a bug far above rounding)."""

    name = "area-off"

    def area(self, V, F):
        return super().area(V, F) * (1 + 1e-9)


def test_steiner_coefficients_run_on_a_mesh_beyond_the_exact_sum_limit():
    # R2.5 on 1,280 float faces (> EXACT_SUM_LIMIT): the sums from the correctly rounded
    # face areas and H(e), the bounds widened by their error; libigl passes, a total area
    # off by 1e-9 relative fails on the area
    from benchmarks.meshes import float_icosphere
    from ddg_oracle.properties.registry import EXACT_SUM_LIMIT
    s = float_icosphere(3)
    mesh = MeshInput("icosphere", [[float(x) for x in p] for p in s.positions],
                     [list(f) for f in s.triangulation.faces])
    assert len(mesh.F) > EXACT_SUM_LIMIT
    ex = MeshExamples(mesh)
    r, = run_mesh_properties(ex, Libigl(), only={"R2.5"})
    assert r.status == PASSED, (r.note, r.error)
    r, = run_mesh_properties(ex, AreaOffByOnePart(), only={"R2.5"})
    assert r.status == FAILED and "area off" in str(r.failure)


def test_the_zero_area_filter_certifies_only_what_is_certain():
    # enclosures.nondegenerate: a float cross product beyond its rounding bound certifies a
    # nonzero area; a face collinear in exact arithmetic is never certified (the exact
    # metric then names it), nor is one whose cross product is below the bound
    from ddg_oracle.properties.enclosures import nondegenerate
    rng = np.random.default_rng(5)
    V = rng.standard_normal((30, 3))
    F = np.array([[i, i + 1, i + 2] for i in range(0, 27, 3)])
    assert nondegenerate(V, F)
    P = V.copy()
    P[0:3] = [[1, 2, 3], [4, 6, 8], [7, 10, 13]]       # collinear, exactly
    assert not nondegenerate(P, F)
    P[2, 2] += 2.0 ** -40                              # off the line: certified again
    assert nondegenerate(P, F)
    P[2, 2] = 13 + 2.0 ** -50 * 13                     # within the bound (8.2 u |a| ~ 1e-14)
    assert not nondegenerate(P, F)


@pytest.mark.parametrize("epsilon", [2.0 ** -52, 2.0 ** -23])
def test_a_mesh_files_floats_are_its_examples_arrays_and_exact_positions(tmp_path, epsilon):
    """A mesh read from a file gives its example the arrays and the position enclosure it
    has already (floats, and their triangulation pickled): the same as computing them from
    the exact positions, for float64 and for the float32 reading; a mesh given with
    Fractions or ints gets none (they are computed)."""
    from fractions import Fraction
    from pathlib import Path

    from ddg_oracle.application.meshes import as_read_by, load
    from ddg_oracle.application.meshfiles import write_obj
    from ddg_oracle.properties.enclosures import points
    from ddg_oracle.properties.example import _as_arrays
    from ddg_oracle.properties.views import position_enclosure
    V, F = _bumpy_grid(6)
    V = np.asarray(V, dtype=float) * (1 + 1e-9)            # not float32 numbers
    V[0, 2] = -0.0                                          # the exact 0: +0.0 as a float
    write_obj(tmp_path / "m.obj", V, F)
    mesh = as_read_by(load("m.obj", Path(tmp_path / "m.obj")), epsilon)
    ex = MeshExamples(mesh)
    case = ex.example()
    assert ex.floats is not None and mesh.triangulation is not None
    got, want = position_enclosure(case.surface), points(case.surface.positions)
    assert np.array_equal(got.value, want.value) and np.array_equal(got.err, want.err)
    (V1, F1), (V2, F2) = case.arrays(), _as_arrays(case.mesh)
    assert np.array_equal(V1, V2) and np.array_equal(F1, F2) and V1.flags.writeable
    assert np.array_equal(np.signbit(V1), np.signbit(V2)) and not np.signbit(V1[0, 2])
    exact = MeshExamples(MeshInput("exact", [[Fraction(x) for x in p] for p in mesh.V], mesh.F))
    assert exact.floats is None and "arrays" not in exact.example()._cache
