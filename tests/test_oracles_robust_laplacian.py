"""The robust-laplacian adapter: on closed meshes the notes' Laplace-Beltrami operator (D4.8)
within the derived bound; with boundary it is the operator of the doubled surface (the
tufted cover), checked exactly against the reference on the double; its options return
the library's raw values; bad input is refused first.

Needs the ``peers`` extra (``pip install -e '.[peers]'``; the ``test`` extra includes it).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import settings

rl = pytest.importorskip("robust_laplacian")

from ddg_oracle.protocol.arrays import boundary_edges  # noqa: E402
from ddg_oracle.oracles.robust_laplacian import RobustLaplacian  # noqa: E402
from ddg_oracle.properties import PROPERTIES  # noqa: E402
from ddg_oracle.properties.delaunay_exact import DelaunayExact, flip_amplification  # noqa: E402
from ddg_oracle.properties.bounds import entry_bounds  # noqa: E402
from ddg_oracle.protocol.budget import Budget  # noqa: E402
from ddg_oracle.properties.harness import Exact  # noqa: E402
from ddg_oracle.properties.profiles import profile  # noqa: E402
from ddg_oracle.protocol.methods import OutsideDomain  # noqa: E402
from ddg_oracle.properties.runner import (FAILED, NOT_APPLICABLE, PASSED, run_on_example,  # noqa: E402
                                         run_property)
from ddg_oracle.reference import PolyhedralSurface, Triangulation  # noqa: E402
from ddg_oracle.reference.delaunay import flip_to_delaunay, laplace_beltrami  # noqa: E402
from ddg_oracle.reference.laplacian import cotan_laplacian, vertex_areas_barycentric  # noqa: E402
from tests import peer_checks as pc  # noqa: E402
from tests.property_checks import every_property_unshrunk  # noqa: E402

RL = RobustLaplacian()
TUFTED = RobustLaplacian(boundary="library")
WITH_BOUNDARY = [k for k in pc.MESHES if k not in pc.CLOSED]


@pytest.mark.parametrize("name", list(pc.CLOSED) + ["jittered torus"])
def test_closed_meshes_give_the_laplace_beltrami_operator(name):
    """(The exact torus(5,4) has cocircular quads: there robust-laplacian and the reference may
    pick different diagonals of weight exactly 0; D4.8's bound covers them, R4.9.)"""
    if name == "jittered torus":
        V, F = pc.jittered_torus()
        assert len(DelaunayExact(pc.mesh_case(V, F)).log) > 0          # flips are needed
        name = pc.mesh_case(V, F, name)
    pc.check_intrinsic_delaunay_laplacian(RL, name)


@pytest.mark.parametrize("name", WITH_BOUNDARY)
def test_meshes_with_boundary_are_outside_the_reference_conventions_domain(name):
    V, F = pc.arrays(name)
    with pytest.raises(OutsideDomain, match="F-robust-laplacian-1"):
        RL.intrinsic_delaunay_laplacian(V, F)
    assert isinstance(OutsideDomain("x"), ValueError)


# --- the tufted cover at the boundary (finding F-robust-laplacian-1), exactly ------------------------------------


def double(V, F):
    """(surface, fold): the double of the mesh (a second, reversed copy of every face, glued to
    the first along the boundary edges; interior vertices copied, boundary vertices shared)
    as an exact PolyhedralSurface on the float positions, and fold[w] = the input vertex of
    each of its vertices.  Built from explicit gluings: an interior edge between two
    boundary vertices occurs twice, once per copy."""
    t = PolyhedralSurface.from_arrays(V, F).triangulation
    n, m = t.n_vertices, t.n_faces
    inner = [v for v in range(n) if not t.is_boundary_vertex(v)]
    copy = {v: v for v in range(n)}
    copy.update({v: n + k for k, v in enumerate(inner)})
    faces = [list(f) for f in t.faces] + [[copy[a], copy[c], copy[b]] for a, b, c in t.faces]

    def back(h):                      # the reversed copy of halfedge 3f + c is 3(m + f) + 2 - c
        return 3 * (m + h // 3) + 2 - h % 3

    gluings = []
    for e in range(t.n_edges):
        a, b = t.edge_halfedges(e)
        if b >= 0:
            r = t.reversed_gluing(a)
            gluings += [(a, b, r), (back(a), back(b), r)]
        else:
            gluings.append((a, back(a), False))
    positions = [[Fraction(float(x)) for x in p] for p in V]
    positions += [positions[v] for v in inner]
    fold = list(range(n)) + inner
    return PolyhedralSurface(Triangulation(faces, gluings), positions), fold


@pytest.mark.parametrize("name", WITH_BOUNDARY)
def test_tufted_cover_is_half_the_folded_operator_of_the_double(name):
    """buildTuftedLaplacian (tufted_laplacian.cpp l. 14-36): 1/2 of the intrinsic Delaunay
    cotan Laplacian of the cover, whose faces are the mesh's twice, glued along every edge
    (a boundary edge to its own back copy), vertices shared.  That is the double of the
    surface with each vertex's copies identified: robust = 1/2 P^T L_double P, with L_double
    the reference's exact Laplace-Beltrami operator of the double and the bounds of D4.8."""
    V, F = pc.arrays(name)
    D, fold = double(V, F)
    n, N = len(V), len(fold)
    delaunay, log = flip_to_delaunay(D.metric())
    Ld = np.array(cotan_laplacian(delaunay).to_dense_floats(), dtype=float).reshape(N, N)
    amp = flip_amplification(D.metric(), log)
    Bd = entry_bounds(delaunay, N, amp).B.toarray()
    P = np.zeros((N, n))
    P[np.arange(N), fold] = 1
    want, bound = P.T @ Ld @ P / 2, P.T @ Bd @ P / 2
    got = TUFTED.intrinsic_delaunay_laplacian(V, F).toarray()
    assert np.all(np.abs(got - want) <= bound), float(np.max(np.abs(got - want) - bound))
    np.testing.assert_array_equal(got, rl.mesh_laplacian(V, F, mollify_factor=0)[0].toarray())


def test_finding_F_robust_laplacian_1_differs_from_the_notes_exactly_where_they_have_a_negative_boundary_weight():
    """disk(3): three 120-degree corners at the centre, opposite the three boundary edges.
    The notes never flip a boundary edge (D4.4): weight 1/2 cot 120 < 0 there.  The cover
    flips them (in the double they are interior, with opposite angles summing to 240)."""
    V, F = pc.arrays("disk(3)")
    notes = np.array(cotan_laplacian(flip_to_delaunay(PolyhedralSurface.from_arrays(V, F)
                                                      .metric())[0]).to_dense_floats()).reshape(4, 4)
    got = TUFTED.intrinsic_delaunay_laplacian(V, F).toarray()
    i, j = (int(x) for x in boundary_edges(F)[0])
    assert notes[i, j] > 0.25                          # weight -notes[i, j] = 1/2 cot 120 < 0
    assert got[i, j] <= 0                              # robust-laplacian's weight is >= 0
    off = got[~np.eye(4, dtype=bool)]
    assert np.all(off <= 1e-15)                        # no negative weight anywhere


# --- finding F-robust-laplacian-2: the flip threshold delaunayEPS = 1e-6 -----------------------------------------


def pillow(d):
    """A flat closed surface: the quad (-1,0), (0,-1), (1,0), (0,1-d) triangulated with the
    diagonal (0,2) on top and (1,3) below.  The top diagonal's cotan weight is about -d/2."""
    V = np.array([[-1.0, 0, 0], [0, -1, 0], [1, 0, 0], [0, 1 - d, 0]])
    F = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
    return V, F


def test_finding_F_robust_laplacian_2_an_edge_with_weight_above_minus_1e_6_is_not_flipped():
    """simple_idt.h l. 16-17: flipToDelaunay(..., delaunayEPS = 1e-6) flips only edges whose
    weight is < -1e-6 (simple_idt.cpp l. 111-112); tufted_laplacian.cpp l. 29 uses the
    default.  With d = 2e-7 the non-Delaunay diagonal (weight -1e-7) stays."""
    V, F = pillow(2e-7)
    case = pc.mesh_case(V, F, "pillow")
    with pytest.raises(AssertionError):
        pc.check_intrinsic_delaunay_laplacian(RL, case)
    got = RL.intrinsic_delaunay_laplacian(V, F).toarray()
    assert 0.9e-7 < got[0, 2] < 1.1e-7                 # weight -1e-7: a non-Delaunay edge kept
    V, F = pillow(2e-5)                                # weight -1e-5 < -1e-6: flipped, exact
    pc.check_intrinsic_delaunay_laplacian(RL, pc.mesh_case(V, F, "pillow"))


# --- mollification (finding F-robust-laplacian-3) -----------------------------------------------------------------


def needle_tetrahedron():
    """A tetrahedron whose vertex 3 is 1.2e-6 from vertex 0: two needles with a short side far
    below 1e-5 x the mean edge length; Delaunay as it is (no flips)."""
    V = np.array([[0.0, 0, 0], [1, 0, 0], [0.5, np.sqrt(3) / 2, 0], [0.5e-6, 0.25e-6, 1e-6]])
    F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    return V, F


def test_finding_F_robust_laplacian_3_mollify_library_changes_a_mesh_with_a_short_edge():
    """intrinsic_mollification.cpp l. 20-37: every edge length gets + max(0, max over corners
    of l_c - l_a - l_b + 1e-5 mean(l)); here ~9e-6 on every edge, which turns the needles'
    cotangents (~1e6) into others: entries off by ~8e5.  mollify="reference" (0) gives the
    exact operator within D4.8's bound."""
    V, F = needle_tetrahedron()
    case = pc.mesh_case(V, F, "needle tetrahedron")
    assert len(DelaunayExact(case).log) == 0
    pc.check_intrinsic_delaunay_laplacian(RL, case)
    raw = rl.mesh_laplacian(V, F)[0].toarray()                  # the library's default 1e-5
    library = RobustLaplacian(mollify="library").intrinsic_delaunay_laplacian(V, F).toarray()
    np.testing.assert_array_equal(library, raw)
    with pytest.raises(AssertionError):
        pc.check_intrinsic_delaunay_laplacian(RobustLaplacian(mollify="library"), case)
    W, G = pc.arrays("icosahedron")                             # no short edge: no change
    mollified = RobustLaplacian(mollify="library").intrinsic_delaunay_laplacian(W, G)
    np.testing.assert_array_equal(mollified.toarray(), RL.intrinsic_delaunay_laplacian(W, G).toarray())


def test_mass_matrix_is_the_barycentric_mass_of_the_flipped_cover():
    """M = 1/2 vertexLumpedMassMatrix of the cover (tufted_laplacian.cpp l. 36): one third of
    each face's area per corner of the *Delaunay* triangulation, so it sums to the area;
    on the icosahedron (already Delaunay) it is the input's barycentric areas."""
    V, F = pc.arrays("icosahedron")
    _, M = RL.mesh_laplacian(V, F)
    X = Exact(pc.mesh_case(V, F, "icosahedron"))
    _, bb = X.vertex_area_bounds
    want = np.array([float(a) for a in vertex_areas_barycentric(X.surface)])
    assert np.all(np.abs(M.diagonal() - want) <= bb)
    V, F = pc.arrays("disk(3)")
    _, M = TUFTED.mesh_laplacian(V, F)
    area = float(PolyhedralSurface.from_arrays(V, F).metric().total_area())
    assert abs(M.diagonal().sum() - area) <= 16 * 2.0 ** -53 * area


# --- options, bad input, the runner's domain, the whole adapter --------------------------------


def test_unknown_options_are_rejected():
    for bad in ({"boundary": "tufted"}, {"mollify": 1e-5}):
        with pytest.raises(ValueError, match=next(iter(bad))):
            RobustLaplacian(**bad)
    assert TUFTED.name == "robust_laplacian(boundary='library')"


def test_bad_input_raises_a_value_error_before_the_library():
    """geometry-central answers an index >= #V with a RuntimeError (GC_SAFETY_ASSERT) and a
    negative one wraps to 2^64 - 1; the adapter refuses both, and NaN, first."""
    V, F = pc.arrays("tetrahedron")
    W = V.copy()
    W[1, 1] = np.nan
    for bad in [(V, np.array([[0, 1, 9], [0, 1, 2]])), (V, np.array([[0, 1, -1], [0, 1, 2]])),
                (W, F), (V, F[:, :2])]:
        for impl in (RL, TUFTED):
            with pytest.raises(ValueError) as err:
                impl.intrinsic_delaunay_laplacian(*bad)
            assert not isinstance(err.value, OutsideDomain)


def test_runner_skips_examples_outside_the_domain():
    """D4.9 draws planar meshes only (all with boundary): not applicable, with the reason;
    X4.2 (a closed tetrahedron) is checked; a single given example outside: not applicable."""
    d49 = run_property(PROPERTIES["D4.9 / R4.10"], RL, profile("default"))
    assert d49.status == NOT_APPLICABLE and d49.examples == 0 and "F-robust-laplacian-1" in d49.note
    tufted = run_property(PROPERTIES["D4.9 / R4.10"], TUFTED, profile("default"))
    assert tufted.examples > 0 and tufted.note is None        # the library option checks them
    x42 = run_property(PROPERTIES["X4.2"], RL, profile("default"))
    assert x42.status == PASSED and x42.examples == 1 and x42.note is None
    one = run_on_example(PROPERTIES["D4.9 / R4.10"], RL, d49.example, "given")
    assert one.status == NOT_APPLICABLE and one.examples == 0


def test_outside_domain_crosses_the_worker_process():
    from ddg_oracle.application.isolation import Isolated
    V, F = pc.arrays("disk(6)")
    with Isolated("robust_laplacian", timeout=60) as impl:
        with pytest.raises(OutsideDomain, match="F-robust-laplacian-1"):
            impl.intrinsic_delaunay_laplacian(V, F)
        W, G = pc.arrays("cube")
        assert impl.intrinsic_delaunay_laplacian(W, G).shape == (8, 8)


def test_every_applicable_property_passes_but_D48_on_the_flip_threshold_RL2():
    """X4.2 passes; D4.8 fails on its closed near ties (a quad moved in by 2^-20, coned
    off) and on nothing else: the 1e-6 flip threshold of F-robust-laplacian-2, which the
    report names."""
    from ddg_oracle.application.report import known_finding, known_findings
    # which properties pass or fail (known_finding reads the status and property ID, not
    # the example): no shrink phase, the same seed, examples and budget as
    # run_properties(RL, "default", seed=1) had; the shrunk D4.8 example is checked below
    # from a run of its own that does shrink.  Seed 1: since the intrinsic examples draw a
    # vertex of no face (half of them), seed 0's 25 examples hold no closed near tie; one
    # seed of 32 misses the threshold, as one of 32 did before (seeds 0-31, measured)
    results = {r.property_id: r for r in every_property_unshrunk(RL, 1)}
    assert results["X4.2"].status == PASSED
    d48 = results["D4.8 / R4.9"]
    assert d48.status == FAILED, d48.status
    assert known_finding(d48, known_findings()) == "F-robust-laplacian-2"
    # how far it shrinks, from this seed alone: no example database (the suite's shared
    # one replays D4.8 failures that other tests saved for other implementations, and a
    # fresh clone's CI shrank from one of those to 24 faces) and no wall-clock limit on
    # shrinking (the default profile's 3 s); about 1 s
    d48 = run_property(PROPERTIES["D4.8 / R4.9"], RL, settings(profile("default"), database=None),
                       1, budget=Budget(None, None))
    assert d48.status == FAILED, d48.status
    V, F = (np.asarray(x) for x in d48.mesh)
    assert len(F) <= 12 and not len(boundary_edges(F)), d48.mesh     # shrunk, closed
    L = rl.mesh_laplacian(V.astype(float), F, mollify_factor=0)[0].toarray()
    s = PolyhedralSurface.from_arrays(V, F)
    exact = laplace_beltrami(s).to_scipy().toarray()
    kept = (exact == 0) & (L != 0)           # an edge the exact flips remove, the library keeps
    i, j = np.argwhere(kept)[0]
    w = -cotan_laplacian(s)[int(i), int(j)]   # its exact weight in the input triangulation
    assert -1e-6 < w < 0                     # inside the threshold (-1e-6, 0)
    assert all(r.ok for r in results.values() if r.property_id != "D4.8 / R4.9")
