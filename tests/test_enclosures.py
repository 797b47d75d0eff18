"""The float enclosures of properties/enclosures.py hold the exact values, and the checks
that decide from them give the verdicts of the exact values (issue 46).

The enclosures are tested against the exact reference entry by entry on the adversarial
hinges of tests/test_bounds_vs_honest.py (dihedral angles near 0 and +-pi, needle and cap
wings, scaled by 2^-60 .. 2^60 and moved far from the origin), at scales down to the
float range's edge, on rational (not float) coordinates and on drawn surfaces; the
verdicts of D2.3 and R2.5 are compared with the loop over the exact values for
implementations whose errors sit at the bound itself."""

from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings

from ddg_oracle.properties import PROPERTIES, views
from ddg_oracle.properties.bounds import edge_mean_curvature_tolerances
from ddg_oracle.properties.enclosures import (Enclosure, U, angle_from, mean_curvature_enclosure,
                                              rounding_bounds)
from ddg_oracle.properties.example import Example
from ddg_oracle.properties.precision import FORMATS
from ddg_oracle.properties.registry import first_outside, unjudged_entries, within
from ddg_oracle.properties.runner import FAILED, PASSED, run_on_example
from ddg_oracle.properties.strategies import jittered_surfaces
from ddg_oracle.reference import curvature as ref
from ddg_oracle.reference import surfaces
from tests.honest_panel import Atan2Cross
from tests.test_bounds_vs_honest import fans, hinges, triangles


def st_obtuse_or_planar():
    """E3.12's own strategy: obtuse and planar meshes."""
    from hypothesis import strategies as st

    from ddg_oracle.properties.strategies import obtuse_meshes, planar_meshes
    return st.one_of(obtuse_meshes(), planar_meshes())


def _case(V, F, recipe, exact=False):
    conv = (lambda x: x) if exact else (lambda x: Fraction(float(x)))
    pos = tuple(tuple(conv(x) for x in p) for p in V)
    return Example.of_mesh(pos, tuple(tuple(int(v) for v in f) for f in F), recipe)


def _holds(value: float, err: float, exact) -> bool:
    """Whether the exact Angle or AngleLength lies in [value - err, value + err]."""
    a, b = Fraction(value) - Fraction(err), Fraction(value) + Fraction(err)
    for bits in (64, 128, 256, 1024, 4096):
        lo, hi = exact.interval_at(bits)
        if a <= lo and hi <= b:
            return True
        if hi < a or b < lo:
            return False
    raise AssertionError("undecided at 4,096 bits")


def _enclosures_hold(case) -> tuple[int, int]:
    """(edges, edges whose views are pinned) after asserting every enclosure holds its
    exact H(e) and every [lo, hi] its correctly rounded float."""
    s = case.surface
    keys, edges, lo, hi = views.mean_curvature_view_bounds(s)
    _, I, J, K, L, _ = views.interior_edge_corners(s)
    enc, _ = mean_curvature_enclosure(s.positions, I, J, K, L)
    exact = ref.mean_curvature(s)
    assert list(exact) == edges                     # the same edges, in the same order
    for n, e in enumerate(edges):
        x = exact[e]
        if np.isfinite(enc.err[n]):
            assert _holds(float(enc.value[n]), float(enc.err[n]), x), (case.recipe, e)
        assert lo[n] <= float(x) <= hi[n], (case.recipe, e, lo[n], float(x), hi[n])
    return len(edges), int(np.count_nonzero(np.isfinite(lo)))


@pytest.mark.parametrize("bits", [53, 24])
def test_mean_curvature_enclosures_hold_on_adversarial_hinges(bits):
    V, F = hinges(FORMATS[bits], seed=11, count=150)
    n, bounded = _enclosures_hold(_case(V, F, f"hinges, {bits} bits"))
    assert n == 150 and bounded >= 140          # a few shut or flat hinges stay undecided


@pytest.mark.parametrize("scale", [2.0 ** -520, 2.0 ** -30, 1.0, 2.0 ** 40, 2.0 ** 500])
def test_mean_curvature_enclosures_hold_at_every_scale_and_far_away(scale):
    s = surfaces.icosahedron()
    V, F = (np.asarray(a) for a in s.to_arrays())
    rng = np.random.default_rng(5)
    V = (V + rng.uniform(-0.1, 0.1, V.shape)) * scale + np.array([3.0, 0, 0]) * scale * 2 ** 20
    _enclosures_hold(_case(V, F, f"scale {scale:g}"))


def test_mean_curvature_enclosures_hold_on_rational_coordinates_and_flat_edges():
    # a grid with thirds (not floats: the enclosure starts from the rounding) and a flat
    # interior, one vertex lifted by 2^-40: dihedral angles of 0 and of about 2^-40
    s = surfaces.grid(3, 3)
    V, F = (np.asarray(a, dtype=object) for a in s.to_arrays())
    pos = [[Fraction(x) / 3 for x in p] for p in V]
    pos[5][2] = Fraction(1, 2 ** 40)
    case = Example.of_mesh(tuple(map(tuple, pos)), tuple(map(tuple, F.tolist())), "thirds")
    _enclosures_hold(case)


@settings(max_examples=15, deadline=None)
@given(jittered_surfaces(closed=True))
def test_mean_curvature_enclosures_hold_on_drawn_surfaces(case):
    _enclosures_hold(case)


def _angles_hold(case) -> None:
    """Every corner angle's and every angle defect's and turning angle's enclosure holds
    its exact value, and [lo, hi] its correctly rounded float."""
    from ddg_oracle.properties.enclosures import (PI, TWO_PI, angle_sum_enclosure,
                                                  corner_angle_enclosure)
    s = case.surface
    t = s.triangulation
    corners = corner_angle_enclosure(s.positions, t.faces)
    exact = ref.corner_angles(s)
    lo, hi = views.corner_angle_view_bounds(s)
    for f, angles in enumerate(exact):
        for c, a in enumerate(angles):
            if np.isfinite(corners.err[f, c]):
                assert _holds(float(corners.value[f, c]), float(corners.err[f, c]), a), (f, c)
            assert lo[f, c] <= float(a) <= hi[f, c], (case.recipe, f, c)
    sums = angle_sum_enclosure(corners, t.faces, t.n_vertices)
    boundary = t.boundary_vertices()
    for what, turn, keep in (("defects", TWO_PI, False), ("turning", PI, True)):
        vs, lo, hi = views.vertex_angle_view_bounds(s, what)
        assert vs == [v for v in range(t.n_vertices) if (v in boundary) == keep]
        enc = turn - sums[np.array(vs, dtype=np.int64)]
        want = (views.defect_views if what == "defects" else views.turning_views)(s)
        exact_v = (ref.angle_defects if what == "defects" else ref.turning_angles)(s)
        for n, v in enumerate(vs):
            if np.isfinite(enc.err[n]):
                assert _holds(float(enc.value[n]), float(enc.err[n]), exact_v[v]), (what, v)
            assert lo[n] <= want[v] <= hi[n], (case.recipe, what, v)


@pytest.mark.parametrize("bits", [53, 24])
def test_corner_angle_enclosures_hold_on_needles_caps_and_near_right_angles(bits):
    V, F = triangles(FORMATS[bits], seed=13, per_kind=20)
    _angles_hold(_case(V, F, f"triangles, {bits} bits"))


@pytest.mark.parametrize("bits", [53, 24])
def test_angle_defect_enclosures_hold_on_fans_with_needle_sectors(bits):
    V, F = fans(FORMATS[bits], seed=17, count=20)
    _angles_hold(_case(V, F, f"fans, {bits} bits"))


@settings(max_examples=15, deadline=None)
@given(jittered_surfaces(closed=False))
def test_angle_enclosures_hold_on_drawn_surfaces(case):
    _angles_hold(case)


def _signs_equal(case) -> int:
    """Asserts E3.12's weight signs from the enclosures equal the exact ones; returns how
    many edges the enclosures decided."""
    from ddg_oracle.reference.laplacian import weight_signs_by_angles
    got = views.weight_signs(case.surface)
    assert got == weight_signs_by_angles(case.surface), case.recipe
    return len(got)


@pytest.mark.parametrize("bits", [53, 24])
def test_weight_signs_from_enclosures_are_the_exact_signs(bits):
    for make, seed in ((hinges, 19), (triangles, 23), (fans, 29)):
        V, F = make(FORMATS[bits], seed=seed)
        _signs_equal(_case(V, F, f"{make.__name__}, {bits} bits"))
    # exactly cocircular and exactly right: pi - (alpha + alpha') = 0, decided exactly
    s = surfaces.grid(4, 4)
    V, F = (np.asarray(a, dtype=float) for a in s.to_arrays())
    assert 0 in views.weight_signs(_case(V, F.astype(np.int64), "grid").surface)
    _signs_equal(_case(V, F.astype(np.int64), "grid"))


@settings(max_examples=15, deadline=None)
@given(st_obtuse_or_planar())
def test_weight_signs_from_enclosures_are_the_exact_signs_on_drawn_meshes(case):
    _signs_equal(case)


def _total_area_holds(case):
    """Asserts total_area_enclosure's (A, err) holds the exact total area (Heron on the
    exact metric); returns err / A."""
    from ddg_oracle.properties.enclosures import total_area_enclosure
    s = case.surface
    value, err = total_area_enclosure(s.positions, s.triangulation.faces)
    exact = s.metric().total_area()
    assert np.isfinite(err) and _holds_surd(value, err, exact), case.recipe
    return err / value


def _holds_surd(value: float, err: float, exact) -> bool:
    a, b = Fraction(value) - Fraction(err), Fraction(value) + Fraction(err)
    return exact >= a and exact <= b           # exact comparisons of a Surd with Fractions


@pytest.mark.parametrize("bits", [53, 24])
def test_total_area_enclosures_hold_on_needles_caps_and_fans(bits):
    for make, seed in ((triangles, 31), (fans, 37), (hinges, 41)):
        V, F = make(FORMATS[bits], seed=seed)
        assert _total_area_holds(_case(V, F, f"{make.__name__}, {bits} bits")) < 2.0 ** -48
    V, F = triangles(FORMATS[bits], seed=43, per_kind=10)
    for f in F:                     # each face alone: its own error is the total's
        _total_area_holds(_case([V[v] for v in f], [[0, 1, 2]], f"triangle {f}, {bits} bits"))


@settings(max_examples=15, deadline=None)
@given(jittered_surfaces(closed=False))
def test_total_area_enclosures_hold_on_drawn_surfaces(case):
    _total_area_holds(case)                 # rational coordinates too: enclosed as rounded


def test_validate_raises_as_the_metric_and_builds_it_only_when_uncertified():
    """views.validate: DegenerateFace with the exact metric's message (a zero-length edge
    first, then a collinear face), the metric left unbuilt where the float certificate
    holds (R2.5, D2.2, D2.3 and D2.6 decide a float mesh without it)."""
    from ddg_oracle.reference.errors import DegenerateFace
    from ddg_oracle.reference.polyhedral import PolyhedralSurface
    F = [[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]]
    good = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    s = PolyhedralSurface.from_arrays(good, F)
    views.validate(s)
    assert s._metric is None                            # certified: no exact metric
    for bad in ([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
                [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
                [[1.0, 2.0, 3.0], [4.0, 6.0, 8.0], [7.0, 10.0, 13.0], [0.0, 0.0, 1.0]]):
        with pytest.raises(DegenerateFace) as want:
            PolyhedralSurface.from_arrays(bad, F).metric()
        with pytest.raises(DegenerateFace) as got:
            views.validate(PolyhedralSurface.from_arrays(bad, F))
        assert str(got.value) == str(want.value)


def test_arctan2_is_within_the_assumed_ulps():
    """numpy's arctan2 (the platform's libm) within the ulps the enclosures assume."""
    from ddg_oracle.properties.enclosures import _ATAN2_ULPS
    rng = np.random.default_rng(7)
    y = np.concatenate([rng.uniform(0, 1, 2000), 2.0 ** -rng.integers(1, 1000, 500),
                        rng.uniform(0, 1e-300, 200)])
    x = np.concatenate([rng.standard_normal(2000), -np.ones(500), rng.uniform(-1, 1, 200)])
    got = np.arctan2(y, x)
    mpmath.mp.prec = 200
    for yy, xx, v in zip(y.tolist(), x.tolist(), got.tolist()):
        exact = mpmath.atan2(mpmath.mpf(yy), mpmath.mpf(xx))
        assert abs(mpmath.mpf(v) - exact) <= _ATAN2_ULPS * 2 * U * abs(exact) + 2.0 ** -1074, \
            (yy, xx)


def test_an_angle_whose_disc_reaches_the_origin_is_undecided():
    a = angle_from(Enclosure([1e-20], [1e-19]), Enclosure([1e-20], [1e-19]))
    assert not np.isfinite(a.err[0])
    lo, hi = rounding_bounds(a)
    assert lo[0] == -np.inf and hi[0] == np.inf


def _loop(observed, exact, bound):
    """The checks' loop over exact values: the first failing index and the tally."""
    with unjudged_entries() as tally:
        for n, (o, x, b) in enumerate(zip(observed, exact, bound)):
            if not within(abs(o - x), b):
                return (n, x), (tally.entries, tally.judged)
        return None, (tally.entries, tally.judged)


@pytest.mark.parametrize("seed", range(6))
def test_first_outside_is_the_loop_over_the_exact_values(seed):
    rng = np.random.default_rng(seed)
    n = 400
    exact = rng.standard_normal(n) * 2.0 ** rng.integers(-30, 30, n)
    bound = np.abs(exact) * 2.0 ** -40 * rng.uniform(0.5, 2, n)
    bound[rng.random(n) < 0.05] = np.inf
    bound[rng.random(n) < 0.02] = np.nan
    with np.errstate(invalid="ignore"):                 # inf * 0
        gross = 0.05 * (seed % 2)                       # odd seeds: gross errors too
        observed = exact + bound * rng.choice([-1, 1], n) * rng.choice(
            [0, 0.5, 1 - 2 ** -20, 1, 1 + 2 ** -20, 3], n,
            p=[0.2, 0.4, 0.1, 0.25 - gross, 0.05, gross])
    same = np.isinf(bound) & (rng.random(n) < 0.5)       # an infinite bound, no error: judged
    observed[same] = exact[same]
    observed[rng.random(n) < 0.01 * (seed % 2)] = np.nan
    width = np.abs(exact) * 2.0 ** -rng.choice([38, 41, 45, 52, 60, 1000], n)
    lo = np.where(rng.random(n) < 0.1, exact, np.nextafter(exact - width, -np.inf))
    hi = np.where(lo == exact, exact, np.nextafter(exact + width, np.inf))
    asked = []
    start = 0
    b = np.where(np.isnan(bound), np.inf, bound)
    while True:                      # every failure in turn: the loop resumed after each
        def exact_at(k, start=start):
            asked.append(start + k)
            return exact[start + k]
        with unjudged_entries() as tally:
            got = first_outside(observed[start:], lo[start:], hi[start:], bound[start:],
                                exact_at)
            counted = (tally.entries, tally.judged)
        want, want_counted = _loop(observed[start:].tolist(), exact[start:].tolist(),
                                   b[start:].tolist())
        assert got == want and counted == want_counted, start
        if got is None:
            break
        start += got[0] + 1
    assert len(set(asked)) < 0.6 * n                # most decided by the enclosures alone


class _Shifted(Atan2Cross):
    """An honest implementation whose H(e) is moved to ``factor`` times the bound from
    the exact value on a few edges (the rest as computed): errors at the bound itself."""

    def __init__(self, case, factor, every=7):
        super().__init__()
        exact = views.mean_curvature_views(case.surface)
        tol = edge_mean_curvature_tolerances(case)
        self._moved = {k: exact[k] + factor * tol[k] * (-1) ** n
                       for n, k in enumerate(sorted(exact)) if n % every == 0}

    def edge_mean_curvature(self, V, F):
        out = dict(super().edge_mean_curvature(V, F))
        out.update(self._moved)
        return out


_FILTERED = views._mean_curvature_view_bounds


def _exact_route(surface):
    """mean_curvature_view_bounds as the exact values give it: lo = hi = the views."""
    keys, edges, lo, hi = _FILTERED(surface)
    x = np.array([views.mean_curvature_views(surface)[k] for k in keys])
    return keys, edges, x, x.copy()


@pytest.mark.parametrize("factor", [0.5, 0.999, 1.0, 1.001, 2.0])
@pytest.mark.parametrize("pid", ["D2.3", "R2.5"])
def test_verdicts_from_enclosures_are_those_of_the_exact_values(pid, factor, monkeypatch):
    """Errors at 0.5, 0.999, 1, 1.001 and 2 times the bound on every 7th edge (alternating
    signs; the others as Atan2Cross computes them): the same status and message whether
    the check decides from the enclosures or from the exact values."""
    from ddg_oracle.reference.polyhedral import PolyhedralSurface
    s = surfaces.torus(12, 20)                  # 480 faces: R2.5 beyond its exact sums
    V, F = (np.asarray(a, dtype=float) for a in s.to_arrays())
    F = F.astype(np.int64)
    V = V + np.random.default_rng(3).uniform(-2 ** -8, 2 ** -8, V.shape)

    def run():
        fresh = Example.of_surface(PolyhedralSurface.from_arrays(V, F), 0, "jittered torus")
        r = run_on_example(PROPERTIES[pid], _Shifted(fresh, factor), fresh, "torus")
        return r.status, r.summary(), str(r.failure), r.unjudged
    filtered = run()
    monkeypatch.setattr(views, "_mean_curvature_view_bounds", _exact_route)
    exact = run()
    assert filtered == exact
    if pid == "D2.3" and factor in (0.5, 2.0):
        assert filtered[0] == (PASSED if factor < 1 else FAILED), filtered


class _ShiftedAngles(Atan2Cross):
    """Honest corner angles and angle defects moved to ``factor`` times the bound from the
    exact values at every 7th entry (alternating signs)."""

    def __init__(self, case, factor):
        from ddg_oracle.properties.bounds import corner_tolerances
        from ddg_oracle.properties.curvature import _defect_bounds
        super().__init__()
        x = views.corner_angle_views(case.surface)
        tol = corner_tolerances(case)
        self._corners = x + factor * tol * np.where(np.arange(x.size).reshape(x.shape) % 7, 0,
                                                    (-1) ** np.arange(x.size).reshape(x.shape))
        K = np.asarray(super().angle_defects(*case.arrays()), dtype=np.float64)
        tolK = np.asarray(_defect_bounds(self, case, K, tol), dtype=np.float64)
        exact = {**views.defect_views(case.surface), **views.turning_views(case.surface)}
        self._defects = K.copy()
        for n, v in enumerate(sorted(exact)):
            if n % 7 == 0:
                self._defects[v] = exact[v] + factor * tolK[v] * (-1) ** n

    def corner_angles(self, V, F):
        return self._corners.copy()

    def angle_defects(self, V, F):
        return self._defects.copy()


def _exact_corners(surface):
    x = views.corner_angle_views(surface)
    return x, x.copy()


def _exact_vertices(surface):
    t = surface.triangulation
    boundary = t.boundary_vertices()
    out = {}
    for what, keep, f in (("defects", False, views.defect_views),
                          ("turning", True, views.turning_views)):
        vs = [v for v in range(t.n_vertices) if (v in boundary) == keep]
        x = np.array([f(surface)[v] for v in vs], dtype=np.float64)
        out[what] = (vs, x, x.copy())
    return out


@pytest.mark.parametrize("factor", [0.5, 0.999, 1.0, 1.001, 2.0])
@pytest.mark.parametrize("pid", ["D2.6", "D2.2", "R2.4"])
def test_angle_verdicts_from_enclosures_are_those_of_the_exact_values(pid, factor, monkeypatch):
    """As for the mean curvature: corner angles and angle defects (turning angles on a
    grid with a boundary) at 0.5 .. 2 times their bounds, every 7th entry."""
    from ddg_oracle.reference.polyhedral import PolyhedralSurface
    s = surfaces.torus(6, 8) if pid != "R2.4" else surfaces.grid(6, 6)
    V, F = (np.asarray(a, dtype=float) for a in s.to_arrays())
    F = F.astype(np.int64)
    V = V + np.random.default_rng(4).uniform(-2 ** -8, 2 ** -8, V.shape)
    chi = 0 if pid != "R2.4" else 1

    def run():
        fresh = Example.of_surface(PolyhedralSurface.from_arrays(V, F), chi, "jittered")
        r = run_on_example(PROPERTIES[pid], _ShiftedAngles(fresh, factor), fresh, "mesh")
        return r.status, r.summary(), str(r.failure), r.unjudged
    filtered = run()
    monkeypatch.setattr(views, "_corner_angle_view_bounds", _exact_corners)
    monkeypatch.setattr(views, "_vertex_angle_view_bounds", _exact_vertices)
    exact = run()
    assert filtered == exact
    if factor in (0.5, 2.0):
        assert filtered[0] == (PASSED if factor < 1 else FAILED), filtered


def _cotangents_hold(case) -> None:
    """Asserts every corner's cotangent enclosure holds the exact cot (D2.6's, of the
    metric), and every entry of the Laplacian's view bounds the correctly rounded exact
    entry (0 where the exact view stores none)."""
    from ddg_oracle.properties.enclosures import corner_cot_enclosure
    s = case.surface
    m = s.metric()
    enc = corner_cot_enclosure(s.positions, s.triangulation.faces)
    for f in range(s.triangulation.n_faces):
        for c in range(3):
            if np.isfinite(enc.err[f, c]):
                assert _holds_surd(float(enc.value[f, c]), float(enc.err[f, c]),
                                   m.corner_cot(f, c)), (case.recipe, f, c)
    rows, cols, lo, hi = views.laplacian_view_bounds(s)
    x = np.asarray(views.laplacian_view(s)[rows, cols], dtype=np.float64).ravel()
    assert ((lo <= x) & (x <= hi)).all(), case.recipe
    assert len(rows) == 2 * s.triangulation.n_edges + s.triangulation.n_vertices


@pytest.mark.parametrize("bits", [53, 24])
def test_cotangent_and_laplacian_enclosures_hold_on_needles_caps_and_fans(bits):
    for make, seed in ((triangles, 47), (fans, 53), (hinges, 59)):
        V, F = make(FORMATS[bits], seed=seed)
        _cotangents_hold(_case(V, F, f"{make.__name__}, {bits} bits"))


@settings(max_examples=15, deadline=None)
@given(jittered_surfaces(closed=False))
def test_cotangent_and_laplacian_enclosures_hold_on_drawn_surfaces(case):
    _cotangents_hold(case)


def test_a_quotient_by_an_enclosure_of_zero_is_undecided():
    """x / y where y's enclosure reaches 0: infinite error, never a finite claim."""
    q = Enclosure(np.array([1.0, 1.0]), np.array([0.0, 0.0])) / Enclosure(
        np.array([1e-300, 2.0]), np.array([1e-300, 0.0]))
    assert np.isinf(q.err[0]) and q.value[1] == 0.5 and 0 < q.err[1] <= 2 * U


def _filtered_and_exact(pid, shifted, filter_name, view_name, monkeypatch, rows=12, cols=20,
                        seed=5):
    """(status, summary, failure, unjudged) of property ``pid`` on a jittered torus for the
    implementation ``shifted(case)``, decided with the enclosures and then with the exact
    values (``views.<view_name>`` giving None), and what the check's filter
    ``laplacian.<filter_name>`` returned, in order, in the first run."""
    from ddg_oracle.properties import laplacian
    from ddg_oracle.reference.polyhedral import PolyhedralSurface
    s = surfaces.torus(rows, cols)
    V, F = (np.asarray(a, dtype=float) for a in s.to_arrays())
    F = F.astype(np.int64)
    V = V + np.random.default_rng(seed).uniform(-2 ** -8, 2 ** -8, V.shape)
    decided = []
    filter_ = getattr(laplacian, filter_name)
    monkeypatch.setattr(laplacian, filter_name,
                        lambda *a: decided.append(filter_(*a)) or decided[-1])

    def run():
        fresh = Example.of_surface(PolyhedralSurface.from_arrays(V, F), 0, "jittered torus")
        r = run_on_example(PROPERTIES[pid], shifted(fresh), fresh, "torus")
        return r.status, r.summary(), str(r.failure), r.unjudged
    filtered = run()
    first = list(decided)
    monkeypatch.setattr(views, view_name, lambda surface: None)
    exact = run()
    assert not any(decided[len(first):])                # the second run: exact throughout
    return filtered, exact, first


def shifted(Ls, Bs, factor, below=False):
    """The symmetric view ``Ls`` moved to ``factor`` times its entry bound ``Bs`` at every 7th
    stored entry (alternating signs, or all below with ``below``; symmetric pairs alike)."""
    import scipy.sparse as sp

    from ddg_oracle.properties.harness import entries_at
    L = sp.triu(Ls).tocoo()
    b = entries_at(Bs, L.row, L.col)
    n = np.arange(len(L.data))
    shift = np.where(n % 7 == 0, factor * b * (-1.0 if below else (-1.0) ** n), 0.0)
    upper = sp.coo_matrix((L.data + shift, (L.row, L.col)), shape=L.shape)
    return (upper + sp.triu(upper, k=1).T).tocsr()


class _ShiftedLaplacian(Atan2Cross):
    """The exact Laplacian's view :func:`shifted`."""

    def __init__(self, case, factor, below=False):
        from ddg_oracle.properties.harness import Exact
        super().__init__()
        X = Exact.of(case)
        self._A = shifted(X.Ls, X.Bs, factor, below)

    def cotan_laplacian(self, V, F):
        return self._A.copy()


@pytest.mark.parametrize("below", [False, True])
@pytest.mark.parametrize("factor", [0.5, 0.999, 1.0, 1.001, 2.0])
def test_laplacian_verdicts_from_enclosures_are_those_of_the_exact_values(factor, below,
                                                                           monkeypatch):
    """D3.1 with entries at 0.5, 0.999, 1, 1.001 and 2 times their bound (on both sides, or
    all below: within the bound of the enclosure's lower end, not of the exact value): the
    same status, message and tally whether the enclosures decide or the exact view does."""
    filtered, exact, decided = _filtered_and_exact(
        "D3.1", lambda case: _ShiftedLaplacian(case, factor, below), "_entries_within_enclosed",
        "_laplacian_view_bounds", monkeypatch)
    # at 0.5 the enclosures decide every entry; nearer the bound than their width (a few
    # per cent of it here) the moved entries are left to the exact view
    assert decided[-1] == (factor == 0.5)
    assert filtered == exact
    if factor in (0.5, 2.0):
        assert filtered[0] == (PASSED if factor < 1 else FAILED), filtered


def _gradients_hold(case) -> None:
    """Asserts the area gradient's enclosure holds the exact gradient coordinate by
    coordinate, and its view bounds the correctly rounded one."""
    from ddg_oracle.properties.enclosures import area_gradient_enclosure
    from ddg_oracle.reference.areas import area_gradient, area_gradient_floats
    s = case.surface
    t = s.triangulation
    enc = area_gradient_enclosure(s.positions, t.faces, t.n_vertices)
    exact = area_gradient(s)
    for v in range(t.n_vertices):
        for x in range(3):
            if np.isfinite(enc.err[v, x]):
                assert _holds_surd(float(enc.value[v, x]), float(enc.err[v, x]),
                                   exact[v][x]), (case.recipe, v, x)
    view = views.area_gradient_view_bounds(s)
    if view is not None:
        lo, hi = view
        x = np.array(area_gradient_floats(s), dtype=np.float64)
        assert ((lo <= x) & (x <= hi)).all(), case.recipe


@pytest.mark.parametrize("bits", [53, 24])
def test_area_gradient_enclosures_hold_on_needles_caps_and_fans(bits):
    for make, seed in ((triangles, 73), (fans, 79), (hinges, 83)):
        V, F = make(FORMATS[bits], seed=seed, count=12) if make is not triangles else \
            make(FORMATS[bits], seed=seed, per_kind=6)
        _gradients_hold(_case(V, F, f"{make.__name__}, {bits} bits"))


@settings(max_examples=10, deadline=None)
@given(jittered_surfaces(closed=False))
def test_area_gradient_enclosures_hold_on_drawn_surfaces(case):
    _gradients_hold(case)


class _ShiftedGradient(Atan2Cross):
    """An area gradient at the exact one moved by ``factor`` times its bound at every 7th
    coordinate (alternating signs, or all below)."""

    def __init__(self, case, factor, below=False):
        from ddg_oracle.properties.harness import Exact
        super().__init__()
        V = np.asarray(case.arrays()[0], dtype=np.float64)
        exact, bound = Exact.of(case).area_gradient_bound(V)
        n = np.arange(exact.size).reshape(exact.shape)
        sign = -1.0 if below else (-1.0) ** n
        self._G = exact + np.where(n % 7 == 0, factor * bound * sign, 0.0)

    def area_gradient(self, V, F):
        return self._G.copy()


@pytest.mark.parametrize("below", [False, True])
@pytest.mark.parametrize("factor", [0.5, 0.999, 1.0, 1.001, 2.0])
def test_area_gradient_verdicts_from_enclosures_are_those_of_the_exact_values(factor, below,
                                                                               monkeypatch):
    """T3.9's area_gradient route at 0.5 - 2 times its bound: the same status, message and
    tally whether the enclosures decide or the exact gradient does."""
    filtered, exact, decided = _filtered_and_exact(
        "T3.9", lambda case: _ShiftedGradient(case, factor, below), "_gradient_within_enclosed",
        "_area_gradient_view_bounds", monkeypatch, 10, 16, 9)
    # the matrix route's L V and, at 0.5, the own route: decided by the enclosures
    assert decided[0] and decided[-1] == (factor == 0.5)
    assert filtered == exact
    if factor in (0.5, 2.0):
        assert filtered[0] == (PASSED if factor < 1 else FAILED), filtered


def _vertex_areas_hold(case) -> None:
    """Asserts the vertex area enclosures hold the exact areas, and their views bound the
    correctly rounded ones."""
    from ddg_oracle.properties.enclosures import vertex_area_enclosures
    from ddg_oracle.reference.laplacian import (vertex_areas_barycentric, vertex_areas_floats,
                                                vertex_areas_voronoi)
    s = case.surface
    t = s.triangulation
    encs = vertex_area_enclosures(s.positions, t.faces, t.n_vertices)
    for enc, exact in zip(encs, (vertex_areas_voronoi(s), vertex_areas_barycentric(s))):
        for v in range(t.n_vertices):
            if np.isfinite(enc.err[v]):
                assert _holds_surd(float(enc.value[v]), float(enc.err[v]), exact[v]), \
                    (case.recipe, v)
    view = views.vertex_area_view_bounds(s)
    if view is not None:
        for name, kind in (("vertex_areas_voronoi", "voronoi"),
                           ("vertex_areas_barycentric", "barycentric")):
            lo, hi = view[name]
            x = np.array(vertex_areas_floats(s, kind), dtype=np.float64)
            assert ((lo <= x) & (x <= hi)).all(), (case.recipe, name)


@pytest.mark.parametrize("bits", [53, 24])
def test_vertex_area_enclosures_hold_on_needles_caps_right_angles_and_fans(bits):
    for make, seed in ((triangles, 89), (fans, 97), (hinges, 101)):
        V, F = make(FORMATS[bits], seed=seed, count=12) if make is not triangles else \
            make(FORMATS[bits], seed=seed, per_kind=8)
        _vertex_areas_hold(_case(V, F, f"{make.__name__}, {bits} bits"))
    right = _case([[0.0, 0.0, 0.0], [3.0, 0.0, 0.0], [0.0, 4.0, 0.0]], [[0, 1, 2]], "right")
    _vertex_areas_hold(right)


@settings(max_examples=10, deadline=None)
@given(jittered_surfaces(closed=False))
def test_vertex_area_enclosures_hold_on_drawn_surfaces(case):
    _vertex_areas_hold(case)


class _ShiftedAreas(Atan2Cross):
    """Vertex areas at the exact ones moved by ``factor`` times their bound at every 7th
    vertex (alternating signs, or all below)."""

    def __init__(self, case, factor, below=False):
        from ddg_oracle.properties.harness import Exact
        super().__init__()
        X = Exact.of(case)
        self._areas = {}
        for name, bound in zip(("vertex_areas_voronoi", "vertex_areas_barycentric"),
                               X.vertex_area_bounds):
            exact = np.asarray(X.vertex_areas(name), dtype=np.float64)
            n = np.arange(len(exact))
            sign = -1.0 if below else (-1.0) ** n
            self._areas[name] = exact + np.where(n % 7 == 0, factor * bound * sign, 0.0)

    def vertex_areas_voronoi(self, V, F):
        return self._areas["vertex_areas_voronoi"].copy()

    def vertex_areas_barycentric(self, V, F):
        return self._areas["vertex_areas_barycentric"].copy()


@pytest.mark.parametrize("below", [False, True])
@pytest.mark.parametrize("factor", [0.5, 0.999, 1.0, 1.001, 2.0])
def test_vertex_area_verdicts_from_enclosures_are_those_of_the_exact_values(factor, below,
                                                                             monkeypatch):
    """L3.7 at 0.5 - 2 times its bound: the same status, message and tally whether the
    enclosures decide or the exact areas do."""
    filtered, exact, decided = _filtered_and_exact(
        "L3.7", lambda case: _ShiftedAreas(case, factor, below), "_areas_within_enclosed",
        "_vertex_area_view_bounds", monkeypatch, 10, 16, 11)
    assert decided[0] == (factor == 0.5)
    assert filtered == exact
    if factor in (0.5, 2.0):
        assert filtered[0] == (PASSED if factor < 1 else FAILED), filtered
