"""trimesh on the reference's conventions (ddg_oracle.oracles.trimesh): the adapter maps only
the documented convention (F-trimesh-1), and ``ddg-oracle check`` finds trimesh's small-scale
bugs (F-trimesh-2, F-trimesh-3) from generated meshes, not only from hand-made files."""

import math

import numpy as np
import pytest

trimesh = pytest.importorskip("trimesh")

from ddg_oracle.oracles.trimesh import Trimesh  # noqa: E402
from ddg_oracle.properties import PROPERTIES  # noqa: E402
from ddg_oracle.properties.profiles import profile  # noqa: E402
from ddg_oracle.properties.runner import FAILED, PASSED, run_property  # noqa: E402
from ddg_oracle.reference import curvature, surfaces  # noqa: E402

V = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])


def test_turning_angles_at_the_boundary_and_the_library_convention():
    open_F = F[1:]                                  # the tetrahedron minus a face: a disk
    ours, theirs = Trimesh().angle_defects(V, open_F), Trimesh(boundary="library").angle_defects(V, open_F)
    exact = curvature.turning_angles(surfaces.tetrahedron().__class__.from_arrays(V, open_F))
    for v, k in exact.items():
        assert ours[v] == pytest.approx(float(k), abs=1e-14)
        assert theirs[v] - ours[v] == pytest.approx(math.pi)      # F-trimesh-1: 2 pi - sum
    assert Trimesh(boundary="library").name == "trimesh(boundary='library')"


def test_the_signed_dihedral_follows_trimeshs_convexity_flag():
    # a convex tetrahedron: every edge convex, H > 0; the same reflected inside out: H < 0
    H = Trimesh().edge_mean_curvature(V, F)
    assert len(H) == 6 and all(h > 0 for h in H.values())
    inside_out = Trimesh().edge_mean_curvature(V, F[:, ::-1])
    assert all(inside_out[e] == pytest.approx(-h) for e, h in H.items())


def test_process_false_keeps_vertices_at_one_position_apart():
    # two tetrahedra touching at (1, 0, 0): trimesh's default would weld them
    W = np.vstack([V, V + [1, 0, 0]])
    G = np.vstack([F, F + 4])
    K = Trimesh().angle_defects(W, G)
    assert K.shape == (8,) and K.sum() == pytest.approx(8 * math.pi)   # chi = 2 + 2


def test_check_finds_the_small_scale_dihedral_bug_TM2_from_generated_meshes():
    r = run_property(PROPERTIES["D2.3"], Trimesh(), profile("ci"))
    assert r.status == FAILED
    Vf, Ff = r.failure.mesh
    assert len(Ff) <= 6
    # shrunk to a mesh below F-trimesh-2's threshold: some face with |cross| <= 1e-13
    X = np.asarray(Vf)[np.asarray(Ff)]
    cross = np.linalg.norm(np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]), axis=1)
    assert cross.min() <= 1e-13


def test_check_finds_trimeshs_angles_off_on_needles_TM4_and_zeroed_on_tiny_meshes_TM3():
    r = run_property(PROPERTIES["D2.6"], Trimesh(), profile("ci"))
    assert r.status == FAILED
    Vf, Ff = r.failure.mesh
    X = np.asarray(Vf)[np.asarray(Ff)]
    edges = np.linalg.norm(X[:, [1, 2, 0]] - X, axis=2)
    tiny = edges.max() < 1e-6                                  # F-trimesh-3: every angle zeroed
    needle = (edges.min(1) < edges.max(1) / 16).any()         # F-trimesh-4: pi minus two arccos
    # F-trimesh-3 too: an edge below TOL_ZERO (1e-13) is not unit-ized, its angles near pi/2
    short = (edges.min(1) < 1e-12).any()
    assert (tiny and r.failure.observed == 0.0) or needle or short, r.failure
    small = Trimesh().corner_angles(V * 2.0 ** -44, F)
    assert np.all(small == 0)                                  # F-trimesh-3 on the tetrahedron
    # on meshes trimesh's thresholds do not reach, its angles are within the bounds
    assert run_property(PROPERTIES["X2.1"], Trimesh(), profile("ci")).status == PASSED


def test_the_library_dihedral_is_unsigned_TM5():
    inside_out = F[:, ::-1]                          # every edge reflex: H < 0 in the notes
    ours = Trimesh().edge_mean_curvature(V, inside_out)
    theirs = Trimesh(dihedral="library").edge_mean_curvature(V, inside_out)
    assert all(ours[e] < 0 and theirs[e] == pytest.approx(-ours[e]) for e in ours)
    assert Trimesh(dihedral="library").conventions["follows"] == {
        "F-trimesh-5": "face_adjacency_angles: unsigned, reflex edges count as convex"}
    r = run_property(PROPERTIES["D2.3"], Trimesh(dihedral="library"), profile("ci"))
    assert r.status == FAILED
