"""D4.8 / R4.9 decided without the exact metric (issue 46): the local flips of
:func:`~ddg_oracle.properties.delaunay_exact.local_delaunay` are the whole metric's, the
bounds are the exact route's bit for bit, the view's rounding intervals hold the exact
view, and the check's verdicts are the exact route's."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings

from ddg_oracle.properties import PROPERTIES, delaunay, delaunay_exact
from ddg_oracle.properties.bounds import bounds_of
from ddg_oracle.properties.delaunay_exact import DelaunayExact, local_delaunay
from ddg_oracle.properties.example import Example
from ddg_oracle.properties.flipped import intrinsic_meshes
from ddg_oracle.properties.harness import Exact, entries_at
from ddg_oracle.properties.runner import FAILED, PASSED, run_on_example
from ddg_oracle.properties.views import halfedge_table, laplacian_view
from ddg_oracle.reference import surfaces
from ddg_oracle.reference.polyhedral import PolyhedralSurface
from tests.honest_panel import Atan2Cross
from tests.test_enclosures import shifted


def _same_as_the_exact_route(case) -> int | None:
    """Asserts :func:`local_delaunay` of the case's surface is the exact route's
    triangulation (faces, halfedges, amplification), its entry bounds are the exact ones bit
    for bit and its view bounds hold the exact view; returns the number of flips (None where
    it gives nothing)."""
    X = Exact.of(case)
    found = local_delaunay(X.surface)
    if found is None:
        return None
    D = DelaunayExact.of(case)
    d = D.delaunay
    assert np.array_equal(np.asarray(d.triangulation.faces).reshape(-1, 3), found.faces)
    assert np.array_equal(halfedge_table(d), found.table)
    assert np.array_equal(np.asarray(D.amplification), found.amplification())
    k = X.surface.triangulation.n_vertices
    B = bounds_of(found.faces, found.table, found.rho, found.cot_factors, k,
                  found.amplification()).B
    assert B.shape == D.bounds.B.shape and (B != D.bounds.B).nnz == 0
    view = delaunay_exact.delaunay_view_bounds(X.surface)
    if view is not None:
        rows, cols, lo, hi, Bv = view
        x = entries_at(laplacian_view(d), rows, cols)
        assert ((lo <= x) & (x <= hi)).all()
        keep = np.asarray(X.keep)
        assert np.array_equal(Bv, entries_at(D.Bs, keep[rows], keep[cols]))  # widened elsewhere
    return len(D.log)


def _lattice(rows=14, cols=18, pinched=((3, 4), (9, 12), (10, 5)), seed=3):
    """A triangular lattice (every interior edge's cot sum about 2 cot 60) on a gentle bump,
    jittered, with the vertices at ``pinched`` pushed most of the way to the edge above
    them: a few non-Delaunay edges, each with a flip or a few around it."""
    rng = np.random.default_rng(seed)
    V = np.array([[c + 0.5 * (r % 2), r * np.sqrt(3) / 2, 0.0]
                  for r in range(rows) for c in range(cols)])
    V[:, 2] = 0.3 * np.sin(V[:, 0] / 3) * np.cos(V[:, 1] / 4)
    V += rng.uniform(-0.02, 0.02, V.shape)
    for r, c in pinched:
        V[r * cols + c, 1] += 0.75 * np.sqrt(3) / 2
    F = []
    for r in range(rows - 1):
        for c in range(cols - 1):
            a, b, x, y = r * cols + c, r * cols + c + 1, (r + 1) * cols + c, (r + 1) * cols + c + 1
            F += [[a, b, y], [a, y, x]] if r % 2 else [[a, b, x], [b, y, x]]
    return V, np.array(F, dtype=np.int64)


def _case(V, F, recipe="test"):
    return Example.of_surface(PolyhedralSurface.from_arrays(V, F), 0, recipe)


def _fan_in_a_disk(k=24, rings=3, seed=1):
    """A convex k-gon near a circle triangulated as a fan from one of its corners (far from
    Delaunay: its flips cascade), inside ``rings`` rings of a jittered polar grid (kept)."""
    rng = np.random.default_rng(seed)
    V = [[np.cos(2 * np.pi * i / k), np.sin(2 * np.pi * i / k), 0.0] for i in range(k)]
    V = [[x * (1 + rng.uniform(-0.01, 0.01)), y * (1 + rng.uniform(-0.01, 0.01)), z]
         for x, y, z in V]
    F = [[0, i, i + 1] for i in range(1, k - 1)]
    inner = list(range(k))
    for r in range(1, rings + 1):
        radius = 1 + 0.5 * r
        start = len(V)
        V += [[radius * np.cos(2 * np.pi * (i + 0.5 * r) / k),
               radius * np.sin(2 * np.pi * (i + 0.5 * r) / k), rng.uniform(-0.05, 0.05)]
              for i in range(k)]
        outer = list(range(start, start + k))
        for i in range(k):
            a, b = inner[i], inner[(i + 1) % k]
            c, d = outer[i], outer[(i + 1) % k]
            F += [[a, c, b], [b, c, d]]
        inner = outer
    return np.array(V), np.array(F, dtype=np.int64)


@settings(max_examples=40, deadline=None, suppress_health_check=list(HealthCheck))
@given(intrinsic_meshes())
def test_local_flips_are_the_whole_metrics_on_drawn_meshes(monkeypatch, case):
    """Any region may be the whole surface (the share a performance limit only): the drawn
    meshes are small, most of their faces in doubt."""
    monkeypatch.setattr(delaunay_exact, "_SHARE", 1.0)
    _same_as_the_exact_route(case)


def test_local_flips_on_a_lattice_and_a_fan_grow_and_agree(monkeypatch):
    """A pinched lattice has a few flips in three places; a fan in a disk has a cascade that
    reaches the first region's border (the region grows: more than one run)."""
    monkeypatch.setattr(delaunay_exact, "_SHARE", 1.0)
    runs = []
    flipped = delaunay_exact._flipped_region
    monkeypatch.setattr(delaunay_exact, "_flipped_region",
                        lambda *a: runs.append(flipped(*a)) or runs[-1])
    assert _same_as_the_exact_route(_case(*_lattice())) > 0
    assert len(runs) == 1 and len(runs[0][0]) < 0.1 * 442
    runs.clear()
    assert _same_as_the_exact_route(_case(*_fan_in_a_disk(rings=8))) > 20
    assert len(runs) >= 2 and runs[0] is None and runs[-1] is not None


def test_a_region_too_large_leaves_the_exact_route(monkeypatch):
    """The fan alone: every face is in doubt; local_delaunay gives None and D4.8 decides
    exactly (the exact operator passes itself)."""
    V, F = _fan_in_a_disk(rings=0)
    case = _case(V, F)
    assert local_delaunay(Exact.of(case).surface) is None
    assert delaunay_exact.delaunay_view_bounds(Exact.of(case).surface) is None


class _ShiftedOperator(Atan2Cross):
    """The exact Laplace-Beltrami operator's view moved to ``factor`` times its entry bound
    at every 7th stored entry (:func:`tests.test_enclosures.shifted`)."""

    def __init__(self, case, factor, below=False):
        super().__init__()
        D = DelaunayExact.of(case)
        self._A = shifted(D.Ls, D.Bs, factor, below)

    def intrinsic_delaunay_laplacian(self, V, F):
        return self._A.copy()


def _jittered_torus(rows=12, cols=20, seed=5, amount=2 ** -8):
    s = surfaces.torus(rows, cols)
    V, F = (np.asarray(a, dtype=float) for a in s.to_arrays())
    V = V + np.random.default_rng(seed).uniform(-amount, amount, V.shape)
    return V, F.astype(np.int64)


@pytest.mark.parametrize("mesh", ["lattice", "torus"])
@pytest.mark.parametrize("below", [False, True])
@pytest.mark.parametrize("factor", [0.5, 0.999, 1.0, 1.001, 2.0])
def test_operator_verdicts_from_enclosures_are_those_of_the_exact_operator(factor, below, mesh,
                                                                            monkeypatch):
    """D4.8 / R4.9 with entries at 0.5 - 2 times their bound, on a pinched lattice (3 flips)
    and a jittered torus (123 flips, one region: the enclosures' widths there at most 6% of
    the bounds): the same status, message and tally whether the enclosures decide or the
    exact operator."""
    monkeypatch.setattr(delaunay_exact, "_SHARE", 1.0)
    V, F = _lattice() if mesh == "lattice" else _jittered_torus()
    decided = []
    enclosed = delaunay._operator_enclosed
    monkeypatch.setattr(delaunay, "_operator_enclosed",
                        lambda *a: decided.append(enclosed(*a)) or decided[-1])

    def run():
        fresh = _case(V, F, mesh)
        r = run_on_example(PROPERTIES["D4.8 / R4.9"], _ShiftedOperator(fresh, factor, below),
                           fresh, "torus")
        return r.status, r.summary(), str(r.failure), r.unjudged
    filtered = run()
    first = list(decided)
    monkeypatch.setattr(delaunay_exact, "_delaunay_view", lambda surface: None)
    exact = run()
    assert first == [factor == 0.5] and not any(decided[1:])
    assert filtered == exact
    if factor in (0.5, 2.0):
        assert filtered[0] == (PASSED if factor < 1 else FAILED), filtered


def test_the_bounds_follow_the_checked_implementations_epsilon(monkeypatch):
    """The local triangulation is kept once per surface, but its bounds are the checked
    implementation's: float32 first, then float64 on the same surface object (a mesh file
    whose coordinates float32 holds is one surface for both), each equal to the exact
    route's bounds at that epsilon.  Kept from the first, a float64 implementation would
    be judged with float32's bounds: a pass the exact route refuses."""
    from ddg_oracle.protocol.methods import at_machine_epsilon
    monkeypatch.setattr(delaunay_exact, "_SHARE", 1.0)
    case = _case(*_jittered_torus())
    X = Exact.of(case)
    for e in (2.0 ** -23, 2.0 ** -52, 2.0 ** -23):
        with at_machine_epsilon(e):
            rows, cols, _, _, B = delaunay_exact.delaunay_view_bounds(X.surface)
            keep = np.asarray(Exact.of(case).keep)
            want = entries_at(DelaunayExact.of(case).Bs, keep[rows], keep[cols])
            assert np.array_equal(B, want), e
