"""Each derived bound of ``properties/bounds.py`` (and A4.13's ``total_area_bound``) against
the worst honest float method it claims to cover, on adversarial inputs: needles, caps,
near-right triangles, hinges folded nearly flat and nearly shut, vertex fans of slivers,
tiny and huge scales and large offsets, every coordinate representable in the format
(float64, and float32 with ``machine_epsilon = 2**-23``; the formats' ranges are the
strategies' own, ``properties.precision.FORMATS``).

Two assertions per bound: no honest method's error exceeds it anywhere (the bound covers
what it claims), and somewhere the worst of them comes within 1e-3 of it (the bound is not
so loose that it would miss a wrong implementation; a bound made useless fails here).  The
honest methods are the panel's (``tests/honest_panel.py``) plus the textbook route the
angle bound also names (acos of the normalised dot product).  Exact values: the reference
on the very floats, correctly rounded.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest

from ddg_oracle.properties.bounds import (K_COT, _conditioning, corner_tolerances,
                                          edge_mean_curvature_tolerances, entry_bounds,
                                          face_area_tolerances, float_geometry,
                                          gamma, heron_condition, heron_product,
                                          total_area_view,
                                          vertex_tolerances)
from ddg_oracle.properties.views import corner_angle_views, defect_views, mean_curvature_views
from ddg_oracle.properties import variants
from ddg_oracle.properties.example import Example
from ddg_oracle.properties.precision import FORMATS
from ddg_oracle.protocol.methods import at_machine_epsilon
from ddg_oracle.reference.exact import exact_sum, rounded_sum

from tests.honest_panel import (Atan2Cross, Atan2Cross32, KahanHalfAngle, KahanHalfAngle32,
                                IntrinsicFlips, LawOfCosines, LawOfCosines32, PANEL)

#: format name -> (input format, numpy type, machine epsilon, the panel at that precision)
PRECISIONS = {
    "float64": (FORMATS[53], np.float64, 2.0 ** -52, (Atan2Cross, LawOfCosines, KahanHalfAngle)),
    "float32": (FORMATS[24], np.float32, 2.0 ** -23,
                (Atan2Cross32, LawOfCosines32, KahanHalfAngle32)),
}
FLOOR = 1e-3          # somewhere the worst honest error is at least this fraction of its bound


# --- adversarial inputs ------------------------------------------------------------------------


def _rotation(rng):
    q, r = np.linalg.qr(rng.standard_normal((3, 3)))
    return q * np.sign(np.diag(r))


def _placed(P, rng, fmt, k_sliver):
    """Unit-size points rotated, scaled by 2**e and moved by 2**o times their size (as the
    strategies do: the offset keeps >= 12 bits of a 2**-k sliver), rounded to the format."""
    P = np.asarray(P, dtype=np.float64) @ _rotation(rng).T
    if rng.random() < 0.5:
        P = P * 2.0 ** int(rng.integers(-fmt.scale, fmt.scale + 1))
    if rng.random() < 0.5:
        top = max(0, min(fmt.offset, fmt.bits - 17 - k_sliver))
        d = rng.standard_normal(3)
        size = float(np.abs(P).max())
        P = P + 2.0 ** int(rng.integers(0, top + 1)) * size * d / np.linalg.norm(d)
    return np.asarray(P, dtype=np.float64).astype({53: np.float64, 24: np.float32}[fmt.bits]
                                                   ).astype(np.float64)


def _exactly_flat(P) -> bool:
    a, b, c = ([Fraction(float(x)) for x in p] for p in P)
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]) == (0, 0, 0)


KINDS = ("generic", "isosceles needle", "right needle", "oblique needle", "cap", "near right")


def _shape(kind, rng, d):
    """A unit-size triangle of the kind, d = 2**-k its thinness."""
    if kind == "generic":
        return rng.standard_normal((3, 3))
    if kind == "isosceles needle":                      # a small apex angle
        return [(0, 0, 0), (1, d, 0), (1, -d, 0)]
    if kind == "right needle":                          # short side at a right angle
        return [(0, 0, 0), (d, 0, 0), (0, 1, 0)]
    if kind == "oblique needle":                        # short side at any angle
        phi = rng.uniform(0, math.pi)
        return [(0, 0, 0), (1, 0, 0), (d * math.cos(phi), d * math.sin(phi), 0)]
    if kind == "cap":                                   # an angle near pi
        return [(0, 0, 0), (1, 0, 0), (rng.uniform(0.01, 0.99), d, 0)]
    x = rng.uniform(0.1, 0.9)                           # a right angle at (x, h), moved by d
    h = math.sqrt(x * (1 - x)) * (1 + d * rng.choice([-1, 1]))
    return [(0, 0, 0), (1, 0, 0), (x, h, 0)]


def triangles(fmt, seed: int, per_kind: int = 60):
    """(V, F): disjoint triangles of every kind, thin down to the format's sliver limit."""
    rng = np.random.default_rng(seed)
    out = []
    for kind in KINDS:
        for _ in range(per_kind):
            k = int(rng.integers(0, fmt.sliver + 1))
            P = _placed(_shape(kind, rng, 2.0 ** -k), rng, fmt, k)
            if not _exactly_flat(P):
                out.append(P)
    V = np.concatenate(out)
    return V, np.arange(len(V)).reshape(-1, 3)


def hinges(fmt, seed: int, count: int = 300):
    """(V, F): disjoint pairs of triangles sharing an edge, consistently oriented, at
    dihedral angles near 0, near +-pi and anywhere, wings as needles and caps."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < count:
        k = int(rng.integers(0, fmt.sliver + 1))
        d = 2.0 ** -k
        phi = rng.uniform(-math.pi, math.pi)
        psi = {0: phi + math.pi + rng.choice([-1, 1]) * d,        # nearly flat
               1: phi + rng.choice([-1, 1]) * max(d, 1e-3),        # nearly shut
               2: rng.uniform(-math.pi, math.pi)}[int(rng.integers(0, 3))]
        r1 = d if rng.random() < 0.3 else rng.uniform(0.2, 2)      # a needle wing
        r2 = rng.uniform(0.2, 2)
        x1 = rng.uniform(-0.5, 1.5)
        x2 = rng.uniform(0.01, 0.99) if rng.random() < 0.3 else rng.uniform(-0.5, 1.5)
        P = [(0, 0, 0), (1, 0, 0), (x1, r1 * math.cos(phi), r1 * math.sin(phi)),
             (x2, r2 * math.cos(psi), r2 * math.sin(psi))]
        P = _placed(P, rng, fmt, k)
        if _exactly_flat(P[[0, 1, 2]]) or _exactly_flat(P[[1, 0, 3]]):
            continue
        a, b, p, q = (np.array([Fraction(float(x)) for x in v], dtype=object) for v in P)
        e, u, w = b - a, p - a, q - a
        n1 = np.cross(e, u)
        if np.cross(n1, np.cross(e, w)).tolist() == [0, 0, 0] and np.dot(n1, np.cross(e, w)) > 0:
            continue                                    # folded shut exactly: no surface
        out.append(P)
    V = np.concatenate(out)
    F = np.array([f for h in range(count)
                  for f in ([4 * h, 4 * h + 1, 4 * h + 2], [4 * h + 1, 4 * h, 4 * h + 3])])
    return V, F


def fans(fmt, seed: int, count: int = 40):
    """Vertex stars (closed fans around vertex 0 of each) with sliver sectors and heights."""
    rng = np.random.default_rng(seed)
    V, F = [], []
    for _ in range(count):
        n = int(rng.integers(3, 17))
        k = int(rng.integers(0, fmt.sliver + 1))
        cuts = np.sort(rng.uniform(0, 2 * math.pi, n))
        j = int(rng.integers(0, n))
        cuts[j] = cuts[j - 1] + 2.0 ** -k                # one sector a needle
        cuts = np.sort(np.mod(cuts, 2 * math.pi))
        if np.any(np.diff(cuts) <= 0) or cuts[0] + 2 * math.pi - cuts[-1] <= 0:
            continue
        r = rng.uniform(0.5, 2, n) if rng.random() < 0.5 else np.ones(n)
        z = rng.uniform(-1, 1, n) * rng.choice([0, 2.0 ** -k, 1])
        ring = np.stack([r * np.cos(cuts), r * np.sin(cuts), z], axis=1)
        P = _placed(np.vstack([[0, 0, 0], ring]), rng, fmt, k)
        base = sum(len(p) for p in V)
        faces = [(base, base + 1 + i, base + 1 + (i + 1) % n) for i in range(n)]
        if any(_exactly_flat(P[[a - base, b - base, c - base]]) for a, b, c in faces):
            continue
        V.append(P)
        F += faces
    return np.concatenate(V), np.array(F)


def _pieces(V, F):
    """[(vertex slice, face slice)] of the disjoint pieces (consecutive vertex blocks)."""
    out, start_f = [], 0
    top = -1
    for k, f in enumerate(F):
        if k > start_f and min(f) > top:
            out.append((slice(int(F[start_f:k].min()), top + 1), slice(start_f, k)))
            start_f = k
        top = max(top, int(max(f)))
    if len(F):
        out.append((slice(int(F[start_f:].min()), top + 1), slice(start_f, len(F))))
    return out


def per_piece(method, V, F, per: str = "face"):
    """``method(V, F)`` called on each disjoint piece alone (a mesh's own scale: the
    panel rescales a mesh by one power of two, and these batches mix scales from 2**-60
    to 2**60), the answers put together: per face (m, ...) arrays, per vertex (n, ...)
    arrays, or dicts keyed by vertex pairs."""
    parts = []
    for vs, fs in _pieces(V, F):
        got = method(V[vs], F[fs] - vs.start)
        if isinstance(got, dict):
            got = {(i + vs.start, j + vs.start): h for (i, j), h in got.items()}
        parts.append(got)
    if isinstance(parts[0], dict):
        return {k: v for d in parts for k, v in d.items()}
    return np.concatenate([np.asarray(x) for x in parts])


def _case(V, F, recipe):
    pos = tuple(tuple(Fraction(float(x)) for x in p) for p in V)
    return Example.of_mesh(pos, tuple(tuple(int(v) for v in f) for f in F), recipe)


def _acos_of_normalised_dot(V, F, dtype):
    """The textbook route: acos(a . b / (|a| |b|)), clamped."""
    X = np.asarray(V, dtype=np.float64).astype(dtype)[F]
    out = np.empty(F.shape)
    for c in range(3):
        a, b = X[:, (c + 1) % 3] - X[:, c], X[:, (c + 2) % 3] - X[:, c]
        cos = (a * b).sum(axis=1) / (np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1))
        out[:, c] = np.arccos(np.clip(cos, dtype(-1), dtype(1)))
    return out


def _assert_covered(label, errors: dict, bound, floor=FLOOR):
    """Every route's error within ``bound``; the worst ratio over the routes >= ``floor``."""
    worst = 0.0
    for route, err in errors.items():
        err = np.asarray(err, dtype=np.float64)
        r = np.where(bound > 0, err / np.where(bound > 0, bound, 1), np.where(err > 0, np.inf, 0))
        assert np.all(np.isfinite(err)), f"{label}: {route} answered a non-finite value"
        k = int(np.argmax(r))
        assert r.flat[k] <= 1, (f"{label}: {route} is off by {err.flat[k]:.3g} = "
                                f"{r.flat[k]:.3g} x its bound {np.asarray(bound).flat[k]:.3g} at {k}")
        worst = max(worst, float(r.max()))
    assert worst >= floor, f"{label}: the worst honest error is {worst:.2g} of the bound: too loose"
    return worst


# --- angles: corner_tolerances, vertex_tolerances -----------------------------------------------


@pytest.mark.parametrize("name", PRECISIONS)
def test_corner_tolerances_cover_every_honest_angle_route(name):
    fmt, dtype, e, panel = PRECISIONS[name]
    V, F = triangles(fmt, seed=1)
    case = _case(V, F, f"adversarial triangles, {name}")
    exact = corner_angle_views(case.surface)
    with at_machine_epsilon(e):
        tol = corner_tolerances(case)
    errors = {cls.name: np.abs(per_piece(cls().corner_angles, V, F) - exact) for cls in panel}
    errors["acos of the normalised dot"] = np.abs(_acos_of_normalised_dot(V, F, dtype) - exact)
    _assert_covered(f"corner angles, {name}", errors, tol)
    # the side-length term (C_LENGTHS) is what the law of cosines needs: without it, on the
    # needles, the bound of before (C_ANGLE eps (1 + 1/sin)) is exceeded
    g = float_geometry(case)
    old = 16 * e * (1 + g["inv_sin"])
    assert np.max(errors[panel[1].name] / old) > 1


@pytest.mark.parametrize("name", PRECISIONS)
def test_vertex_tolerances_cover_honest_angle_defects(name):
    fmt, dtype, e, panel = PRECISIONS[name]
    V, F = fans(fmt, seed=2)
    case = _case(V, F, f"sliver fans, {name}")
    exact = defect_views(case.surface)
    centres = sorted(exact)
    with at_machine_epsilon(e):
        tol = vertex_tolerances(case, corner_tolerances(case))[centres]
    want = np.array([exact[v] for v in centres])
    errors = {cls.name: np.abs(per_piece(cls().angle_defects, V, F)[centres] - want)
              for cls in panel}
    _assert_covered(f"angle defects, {name}", errors, tol)


# --- dihedral angles: edge_mean_curvature_tolerances -------------------------------------------


@pytest.mark.parametrize("name", PRECISIONS)
def test_edge_mean_curvature_tolerances_cover_every_dihedral_route(name):
    fmt, dtype, e, panel = PRECISIONS[name]
    V, F = hinges(fmt, seed=3)
    case = _case(V, F, f"hinges, {name}")
    exact = mean_curvature_views(case.surface)
    keys = sorted(exact)
    with at_machine_epsilon(e):
        tol = edge_mean_curvature_tolerances(case)
    bound = np.array([tol[k] for k in keys])
    want = np.array([exact[k] for k in keys])
    errors = {}
    for cls in panel:                 # atan2 of the normals, acos (signed), Kahan's formula
        got = per_piece(cls().edge_mean_curvature, V, F)
        errors[f"{cls.name} ({cls.dihedral_rule})"] = np.abs(np.array([got[k] for k in keys]) - want)
    _assert_covered(f"edge mean curvature, {name}", errors, bound)


# --- areas: face_area_tolerances (area_tolerance), heron_condition --------------------------------


@pytest.mark.parametrize("name", PRECISIONS)
def test_face_area_tolerances_cover_the_cross_product_and_kahans_heron(name):
    fmt, dtype, e, panel = PRECISIONS[name]
    V, F = triangles(fmt, seed=4)
    case = _case(V, F, f"adversarial triangles, {name}")
    exact = np.array([float(a) for a in case.surface.metric().areas])
    g = float_geometry(case)
    with at_machine_epsilon(e):
        bound = face_area_tolerances(g["area"], g["sides"], heron_product(g["squared"]))
    errors = {}
    for cls in panel[:2]:                     # |a x b| / 2, and Kahan's sorted Heron
        impl = cls()

        def areas(V, F):
            Vd, Fd, unit = impl._unit(V, F)
            return impl._areas(Vd, Fd) / unit ** 2
        errors[f"{cls.name} ({cls.area_rule})"] = np.abs(per_piece(areas, V, F) - exact)
    def textbook(V, F):                       # sqrt(s (s - a) (s - b) (s - c)), unsorted
        impl = panel[0]()
        Vd, Fd, unit = impl._unit(V, F)
        L = np.sqrt(impl._geometry(Vd, Fd)[3])
        s = L.sum(axis=1) / dtype(2)
        q = s * (s - L[:, 0]) * (s - L[:, 1]) * (s - L[:, 2])
        return np.sqrt(np.maximum(q, dtype(0))) / unit ** 2
    errors["textbook Heron"] = np.abs(per_piece(textbook, V, F) - exact)
    _assert_covered(f"face areas, {name}", errors, bound)
    # the Heron term is what a cap needs: the bound of before (C_ANGLE eps A (1 + kappa))
    # is exceeded there
    old = 16 * e * (exact + g["sides"])
    assert np.max(errors[f"{panel[1].name} (heron)"] / old) > 1


def test_heron_condition_is_the_area_on_faces_without_an_obtuse_angle():
    """sum_c l_c cot_c = 4 A (signed): W_f = A exactly when no cotangent is negative, more on
    an obtuse face: A (1 + |cos beta| / (sin alpha sin gamma)), beta the obtuse angle."""
    V, F = triangles(FORMATS[53], seed=5, per_kind=20)
    case = _case(V, F, "adversarial triangles")
    m = case.surface.metric()
    cot = np.array([[float(c) for c in m.face_cots(f)] for f in range(len(F))])
    sq = np.array([[float(x) for x in m.face_squared_lengths(f)] for f in range(len(F))])[:, [1, 2, 0]]
    area = np.array([float(a) for a in m.areas])
    W = heron_condition(sq, cot)
    acute = (cot >= 0).all(axis=1)
    assert np.allclose(W[acute], area[acute], rtol=1e-12)
    assert np.all(W[~acute] >= area[~acute] * (1 - 1e-12))
    rho = sq.max(axis=1) / (2 * area)
    assert np.all(W <= 1.5 * area * rho ** 2 * (1 + 1e-12))       # A4.13's stand-in
    # the obtuse faces: 1 + |cos beta| / (sin alpha sin gamma), from the exact angles
    ang = corner_angle_views(case.surface)
    for f in np.flatnonzero(~acute):
        b = int(np.argmin(cot[f]))
        a, c = (ang[f, k] for k in range(3) if k != b)
        want = 1 + abs(math.cos(ang[f, b])) / (math.sin(a) * math.sin(c))
        assert W[f] / area[f] == pytest.approx(want, rel=1e-6)
    # heron_product bounds W A from above, from the squared lengths alone, by no more than
    # eps (sum l)^2 / 2 (its margin for cancellation and second-order terms)
    with at_machine_epsilon(2.0 ** -52):
        P = heron_product(sq)
    margin = 2.0 ** -52 * sq.sum(axis=1) ** 2 / 2
    assert np.all(P >= W * area * (1 - 1e-12))
    assert np.all(P <= W * area * (1 + 1e-12) + 2 * margin)


def test_a_face_beyond_float_resolution_has_bounds_that_accept_anything():
    """A triangle whose float cross product is 0 although its exact area is not (2**-104
    against edges of length ~1.4): its conditioning is infinite, so are its corner
    bounds; its area bound stays finite (the sides' product), at least the area."""
    e = 2.0 ** -52
    V = np.array([(0.0, 0.0, 0.0), (1.0, 1.0 + e, 0.0), (1.0 + e, 1.0 + 2 * e, 0.0)])
    case = _case(V, np.array([[0, 1, 2]]), "below float resolution")
    g = float_geometry(case)
    assert g["area"][0] == 0
    with at_machine_epsilon(2.0 ** -52):
        assert np.all(np.isinf(corner_tolerances(case)))
        bound = face_area_tolerances(g["area"], g["sides"], heron_product(g["squared"]))
    assert np.isfinite(bound[0]) and bound[0] >= float(case.surface.metric().areas[0])


def test_area_tolerance_covers_honest_total_areas():
    fmt, dtype, e, panel = PRECISIONS["float32"]
    V, F = triangles(fmt, seed=6, per_kind=20)
    case = _case(V, F, "adversarial triangles, float32")
    exact = rounded_sum(case.surface.metric().areas)          # within u A of the exact sum
    with at_machine_epsilon(e):
        from ddg_oracle.properties.bounds import area_tolerance
        bound = area_tolerance(case)
    errors = {cls.name: abs(float(per_piece(lambda V, F: [cls().area(V, F)], V, F).sum()) - exact)
              for cls in panel}
    _assert_covered("total area, float32", {k: [v] for k, v in errors.items()}, np.array([bound]))


# --- cotangents: entry_bounds' beta ----------------------------------------------------------------


@pytest.mark.parametrize("name", PRECISIONS)
def test_cotangent_bounds_cover_every_honest_cotangent_route(name):
    fmt, dtype, e, panel = PRECISIONS[name]
    V, F = triangles(fmt, seed=7)
    case = _case(V, F, f"adversarial triangles, {name}")
    m = case.surface.metric()
    exact = np.array([[float(c) for c in m.face_cots(f)] for f in range(len(F))])
    with at_machine_epsilon(e):
        b = entry_bounds(m, len(V))
        # faces whose float area a correct route may find 0 (harness.beyond_float_resolution)
        g = float_geometry(case)
        lost = (K_COT * e * b.rho >= 1) | (face_area_tolerances(
            exact_areas := np.array([float(a) for a in m.areas]), g["sides"],
            heron_product(g["squared"])) >= exact_areas)
    keep = ~lost
    errors = {}
    for cls in panel:                         # dot / |cross|, lengths / (4 A), half-angle
        impl = cls()

        def cots(V, F):
            with np.errstate(all="ignore"):
                return impl._face_cots(*impl._arrays(V, F))
        errors[f"{cls.name} ({cls.cot_rule})"] = np.abs(per_piece(cots, V, F) - exact)[keep]
    _assert_covered(f"cotangents, {name}", errors, b.beta[keep])


def test_conditioning_is_within_two_ulps_of_the_exact_values():
    V, F = triangles(FORMATS[53], seed=8, per_kind=10)
    case = _case(V, F, "adversarial triangles")
    m = case.surface.metric()
    for f in range(len(F)):
        rho, cots = _conditioning(m, f)
        sq = m.face_squared_lengths(f)
        exact_rho = max(sq) / (2 * m.area(f))
        assert abs(rho - float(exact_rho)) <= 2 * math.ulp(float(exact_rho))
        for c, x in zip(cots, m.face_cots(f)):
            assert abs(c - float(x)) <= 2 * math.ulp(float(x))


def _factors_hold(m, rho, cot, faces=None) -> int:
    """Assert that ``(rho, cot)`` bound face_conditioning's exact values from above within a
    relative 2^-29 (a |cot| below 2^-499 as 2^-499), with the exact signs, comparing
    exactly (squares against 16 A^2, no float); returns how many faces were checked."""
    top = (1 + Fraction(1, 2 ** 29)) ** 2
    tiny = Fraction(2) ** -499
    checked = 0
    for f in range(m.triangulation.n_faces) if faces is None else faces:
        l0, l1, l2 = m.face_squared_lengths(f)
        H = 2 * (l0 * l1 + l1 * l2 + l2 * l0) - l0 * l0 - l1 * l1 - l2 * l2     # 16 A^2
        # rho = max l / (2 A): (2 rho)^2 A^2 = rho^2 H / 4 against max l^2
        big = max((l0, l1, l2))
        want = big * big * 4
        r2 = Fraction(float(rho[f])) ** 2
        assert r2 * H >= want and r2 * H <= want * top, f
        for c, n in enumerate((l0 + l2 - l1, l0 + l1 - l2, l1 + l2 - l0)):     # cot = n / sqrt(H)
            x = Fraction(float(cot[f, c]))
            assert (x > 0) == (n > 0) and (x < 0) == (n < 0), (f, c)
            assert x * x * H >= n * n, (f, c)
            if n * n >= tiny * tiny * H:
                assert x * x * H <= n * n * top, (f, c)
            else:
                assert n == 0 or tiny <= abs(x) <= tiny * (1 + Fraction(1, 2 ** 50)), (f, c)
        checked += 1
    return checked


@pytest.mark.parametrize("seed", [8, 21])
def test_face_conditioning_bounds_the_exact_factors_from_above(seed, monkeypatch):
    """The vectorised factors (float64 with a derived error bound, the exact route where
    the bound is not small) against the exact values, on needles, caps and slivers down to
    the float64 limit, rescaled by 2^-150 and 2^150 (squared lengths within the filter's
    range) and 2^-300 and 2^300 (beyond it), with exact right angles (cot 0: the exact route)."""
    from ddg_oracle.properties import bounds
    exact_route = []
    monkeypatch.setattr(bounds, "_conditioning",
                        lambda m, f, slow=bounds._conditioning: exact_route.append(f) or slow(m, f))
    V, F = triangles(FORMATS[53], seed=seed, per_kind=12)
    # cotangents of 2^-522 to 2^-1022 at corner 0 (a hostile probe's: the exact route's float
    # underflowed to 0 or to a subnormal), then exact right angles (cot 0)
    tiny = np.array([[0, 0, 0], [2.0 ** 255, 0, 1], [0, 2.0 ** 255, 1],
                     [0, 0, 0], [2.0 ** 511, 0, 1], [0, 2.0 ** 511, 1],
                     [0, 0, 0], [1, 0, 2.0 ** -300], [0, 1, 2.0 ** -300],
                     [0, 0, 0], [float.fromhex("0x1.a9f7d4bd47f7ap+0"), 0,
                                 float.fromhex("-0x1.cb91ce3618240p-267")],
                     [0, 1, float.fromhex("0x1.d7210deee6618p-263")]])
    m = _case(tiny, np.arange(len(tiny)).reshape(-1, 3), "tiny cotangents").surface.metric()
    rho, cot = bounds.face_conditioning(m)
    assert _factors_hold(m, rho, cot) == 4
    assert list(np.sign(cot[:, 0])) == [1, 1, 1, -1] and np.all(np.abs(cot[:, 0]) < 2.0 ** -498)
    right = np.array([[0, 0, 0], [3, 0, 0], [0, 4, 0], [0, 0, 0], [1e-9, 0, 0], [0, 1, 0]])
    for scale in (1.0, 2.0 ** -150, 2.0 ** 150, 2.0 ** -300, 2.0 ** 300):
        W = np.concatenate([V, right]) * scale
        G = np.arange(len(W)).reshape(-1, 3)
        m = _case(W, G, f"adversarial triangles x {scale}").surface.metric()
        exact_route.clear()
        rho, cot = bounds.face_conditioning(m)
        assert _factors_hold(m, rho, cot) == len(G)
        assert cot[-2, 0] == 0 and cot[-1, 0] == 0              # the right angles, exactly
        # both routes taken: the filter decides the well-shaped faces, within its range
        assert len(G) - 2 in exact_route and len(G) - 1 in exact_route
        beyond = not 2.0 ** -200 < scale < 2.0 ** 200
        assert (len(exact_route) == len(G)) == beyond, len(exact_route)


def test_face_conditioning_bounds_flipped_faces_from_above():
    """After intrinsic flips (lazy exact lengths with square roots), the same, on the faces
    the flips made."""
    from fractions import Fraction as Q
    from ddg_oracle.properties.bounds import face_conditioning
    from ddg_oracle.properties.delaunay_exact import delaunay_of
    rng = np.random.default_rng(5)
    k = 12                       # a wavy grid: many flips, nearly right angles among them
    P = [(float(i + rng.uniform(-.45, .45)), float(j + rng.uniform(-.45, .45)),
          float(rng.uniform(-.3, .3))) for i in range(k) for j in range(k)]
    F = [f for i in range(k - 1) for j in range(k - 1) for f in
         ([i * k + j, (i + 1) * k + j, i * k + j + 1],
          [(i + 1) * k + j, (i + 1) * k + j + 1, i * k + j + 1])]
    d, log = delaunay_of(_case(np.array(P), np.array(F), "wavy grid").surface.metric())
    rho, cot = face_conditioning(d)
    flipped = [f for f in range(d.triangulation.n_faces)
               if not all(type(x) is Q for x in d.face_squared_lengths(f))]
    assert len(log) > 20 and len(flipped) > 20
    assert _factors_hold(d, rho, cot, flipped) == len(flipped)


# --- sums and views: gamma, total_area_view --------------------------------------------------------


def test_gamma_bounds_recursive_summation():
    rng = np.random.default_rng(9)
    worst = 0.0
    for k in (2, 10, 100, 1000):
        for _ in range(50):
            x = rng.standard_normal(k) * 2.0 ** rng.integers(-20, 20, k)
            x = np.concatenate([x, -x[: k // 3] * (1 + 2.0 ** -40)])      # cancellation
            s = 0.0
            for v in x:
                s += float(v)
            exact = float(sum(Fraction(float(v)) for v in x))
            with at_machine_epsilon(2.0 ** -52):
                bound = gamma(len(x) - 1) * float(np.abs(x).sum())
            assert abs(s - exact) <= bound
            worst = max(worst, abs(s - exact) / bound)
    assert worst >= FLOOR


def test_total_area_view_is_within_u_of_the_exact_sum():
    V, F = triangles(FORMATS[53], seed=10, per_kind=1)
    case = _case(V, F, "adversarial triangles")
    m = case.surface.metric()
    A, err = total_area_view(m)
    d = exact_sum(m.areas) - Fraction(A)                 # exact
    assert -Fraction(err) <= d <= Fraction(err)


# --- A4.13: the total area recomputed from flipped squared lengths --------------------------------


def test_total_area_bound_covers_the_reference_on_flips_into_caps():
    """Planar quadrilaterals whose Delaunay flip makes two thin triangles with an angle near
    pi (issue 40: the exact reference's own correctly rounded answer was off by 2.1e-12
    against the bound of before, 1.55e-13): the recomputed area stays within the bound of
    :func:`~ddg_oracle.properties.delaunay.total_area_bound`, which the bound of before
    (K_COT eps rho A amp per face) misses by orders of magnitude."""
    from ddg_oracle.oracles.exact_reference import ReferenceImplementation
    from ddg_oracle.properties.delaunay_exact import (DelaunayExact, angles_from_squared_lengths,
                                                      total_area_bound)
    from ddg_oracle.properties.strategies import mesh_case
    ref = ReferenceImplementation()
    rng = np.random.default_rng(11)
    worst_new = worst_old = 0.0
    for _ in range(400):
        k = int(rng.integers(1, 36))
        pts = [(0, 0), (1, 0), (Fraction(int(rng.integers(-64, 128)), 64), Fraction(1, 2 ** k)),
               (Fraction(int(rng.integers(-64, 128)), 64),
                -Fraction(int(rng.integers(1, 64)), 2 ** int(rng.integers(1, k + 1))))]
        case = mesh_case([(x, y, 0) for x, y in pts], ((0, 1, 2), (1, 0, 3)), "quad")
        D = DelaunayExact.of(case)
        if not D.log:
            continue
        F2, l2 = ref.intrinsic_delaunay_triangulation(*case.arrays())
        l2 = np.asarray(l2, dtype=np.float64)
        _, area = angles_from_squared_lengths(l2)
        if not np.all(area > 0):                 # a float Heron area of 0: no rho to compare
            continue
        rho = l2.max(axis=1) / (2 * area)
        amp = max(D.amplification)
        err = abs(float(area.sum()) - float(D.X.metric.total_area()))
        bound = total_area_bound(area, rho, amp, l2)
        assert err <= bound, (pts, err, bound)
        worst_new = max(worst_new, err / bound)
        old = K_COT * 2.0 ** -52 * amp * float(np.sum(area * rho)) + gamma(2) * float(area.sum())
        worst_old = max(worst_old, err / old)
    assert worst_new >= FLOOR and worst_old > 1


# --- input rounding, the entries of L, the float conditioning, intrinsic flips -------------------


def test_input_rounding_term_covers_the_rounding_of_a_moved_triangle():
    """corner_tolerances(input_rounding=True) adds 4 sqrt(3) eps |x| / |edge| (1 + 1/sin +
    S_f) for points rounded to floats after an exact motion (T2.5, X2.1): a rational
    rotation keeps every exact angle, so the rounded copy's exact angles differ from the
    original's by the rounding alone."""
    from ddg_oracle.reference import curvature as ref
    from ddg_oracle.properties.strategies import floated
    rng = np.random.default_rng(12)
    worst = 0.0
    for _ in range(60):
        V, F = triangles(FORMATS[53], seed=int(rng.integers(1 << 30)), per_kind=1)
        case = _case(V, F, "triangles")
        w = [Fraction(int(rng.integers(-4, 5)), int(rng.integers(1, 4))) for _ in range(3)]
        moved = floated(ref.rigid_motion(case.surface, ref.cayley_rotation(*w),
                                         (Fraction(int(rng.integers(-6, 7)), 2),) * 3))
        if variants.is_degenerate(moved):            # the rounding merged a sliver's points
            continue
        other = Example.of_surface(moved, 1, "moved")
        diff = np.abs(corner_angle_views(other.surface) - corner_angle_views(case.surface))
        with at_machine_epsilon(2.0 ** -52):
            plain = corner_tolerances(other)
            tol = corner_tolerances(other, input_rounding=True) - plain
        assert np.all(diff <= tol)
        worst = max(worst, float(np.max(diff / tol)))
    assert worst >= FLOOR


@pytest.mark.parametrize("name", PRECISIONS)
def test_entry_bounds_cover_every_honest_cotan_laplacian(name):
    """B (the corner bounds beta / 2 summed per entry, plus the summation) against the
    panel's cotan Laplacians on sliver fans: D3.1's comparison, entry by entry."""
    from ddg_oracle.properties.harness import Exact, beyond_float_resolution
    fmt, dtype, e, panel = PRECISIONS[name]
    V, F = fans(fmt, seed=13)
    case = _case(V, F, f"sliver fans, {name}")
    with at_machine_epsilon(e):
        X = Exact.of(case)
        B, L = X.B, X.Lf
        # entries of faces whose float area a correct route may find 0: ties (harness)
        lost = np.zeros_like(B, dtype=bool)
        for i, j in beyond_float_resolution(case):
            lost[i, j] = True
    errors = {}
    for cls in panel:
        A = np.zeros_like(L)
        for vs, fs in _pieces(V, F):
            with np.errstate(all="ignore"):
                A[vs, vs] = cls().cotan_laplacian(V[vs], F[fs] - vs.start).toarray()
        errors[cls.name] = np.abs(A - L)[(B > 0) & ~lost]
        assert np.all(np.abs(A - L)[B == 0] == 0)
    _assert_covered(f"entries of L, {name}", errors, B[(B > 0) & ~lost])


def test_float_conditioning_is_within_its_own_error_of_the_exact_one():
    """float_geometry's 1/sin (from the float cross product) is within a relative 8 eps
    kappa_f of the exact one where it is finite: a bound's constants dwarf it while
    eps kappa_f << 1, and beyond float resolution it is infinite (anything accepted)."""
    V, F = triangles(FORMATS[53], seed=14)
    case = _case(V, F, "adversarial triangles")
    m = case.surface.metric()
    exact = np.array([[float(1 / s) for s in _exact_sines(m, f)] for f in range(len(F))])
    got = float_geometry(case)["inv_sin"]
    kappa = exact.max(axis=1, keepdims=True)
    ok = 8 * 2.0 ** -52 * kappa < 0.5
    rel = np.abs(got - exact) / exact
    assert np.all(rel[ok.ravel()] <= (8 * 2.0 ** -52 * kappa)[ok.ravel()] + 1e-15)


def _exact_sines(m, f):
    """The exact sines of face f's corners as floats: 2 A / (b c)."""
    l0, l1, l2 = m.face_squared_lengths(f)       # opposite corners 2, 0, 1
    sq = (l1, l2, l0)                             # opposite corners 0, 1, 2
    A = m.area(f)
    out = []
    for c in range(3):
        b, cc = sq[(c + 1) % 3], sq[(c + 2) % 3]
        out.append(float(2 * A) / math.sqrt(float(b) * float(cc)))
    return out


@pytest.mark.parametrize("name", PRECISIONS)
def test_flip_amplification_covers_float_flips_of_caps(name):
    """An octahedron with a vertex pushed to a cap of height 2**-k over the middle of an
    edge (the test vectors' cap): its long edge is flipped; the panel's float flip (the two
    triangles laid out, their heights from Kahan's Heron) is that ill-conditioned, and the
    intrinsic Delaunay operator's bound (the flips' amplification, _flipped_error) covers
    it, where the bound of before (the areas' error like the lengths') was short by 1,600."""
    from ddg_oracle.properties.delaunay_exact import DelaunayExact
    fmt, dtype, e, panel = PRECISIONS[name]
    base = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    F = np.array([[0, 2, 6], [0, 5, 2], [0, 4, 3], [0, 3, 5], [1, 4, 2], [1, 2, 5],
                  [1, 3, 4], [1, 5, 3], [2, 4, 6], [4, 0, 6]])
    errors, bounds = {cls.name: [] for cls in panel}, []
    for k in range(4, fmt.sliver + 1, 2):
        V = np.array(base + [(0.5, 0.5, 2.0 ** -k)], dtype=np.float64)
        case = _case(V, F, f"cap 2^-{k}")
        with at_machine_epsilon(e):
            D = DelaunayExact.of(case)
            B, L = D.B, D.Lf
        for cls in panel:
            A = cls().intrinsic_delaunay_laplacian(V, F).toarray()
            errors[cls.name].append(np.abs(A - L)[B > 0])
        bounds.append(B[B > 0])
    _assert_covered(f"intrinsic Delaunay operator on caps, {name}",
                    {k: np.concatenate(v) for k, v in errors.items()}, np.concatenate(bounds))


@pytest.mark.parametrize("name", PRECISIONS)
def test_vertex_area_bounds_cover_honest_mixed_voronoi_and_barycentric_areas(name):
    """L3.7's bounds (harness.Exact.vertex_area_bounds: the corner cotangents' beta times the
    adjacent squared sides / 8, and each face area's own bound) against the panel's mixed
    Voronoi areas, whose obtuse rule is decided by the float cotangent's sign: near a right
    angle (the "near right" triangles) either rule may be taken, and the two agree there
    to within the bound; caps and needles through both area routes."""
    from ddg_oracle.properties.harness import Exact
    fmt, dtype, e, panel = PRECISIONS[name]
    V, F = triangles(fmt, seed=15)
    case = _case(V, F, f"adversarial triangles, {name}")
    with at_machine_epsilon(e):
        X = Exact.of(case)
        vb, bb = X.vertex_area_bounds
        exact = {k: X.vertex_areas(k) for k in ("vertex_areas_voronoi", "vertex_areas_barycentric")}
    for method, bound in (("vertex_areas_voronoi", vb), ("vertex_areas_barycentric", bb)):
        errors = {cls.name: np.abs(per_piece(getattr(cls(), method), V, F) - exact[method])
                  for cls in panel}
        _assert_covered(f"{method}, {name}", errors, bound)


@pytest.mark.parametrize("name", sorted(PANEL))
def test_the_flip_loops_corner_cotangent_is_the_panels_bit_for_bit(name):
    """IntrinsicFlips.cot (scalar, per corner) is the panel's array route, rounding included:
    random, degenerate, triangle-inequality-breaking and tiny or huge squared lengths."""
    impl = PANEL[name]()
    rng = np.random.default_rng(7)
    rows = [rng.random(3) * 10.0 ** rng.integers(-20, 20) for _ in range(400)]
    rows += [[1.0, 1.0, 4.0], [1.0, 1.0, 0.0], [0.0, 0.0, 0.0], [1e-30, 1.0, 1.0],
             [1.0, 1.0, 3.9999999], [2.0, 1.0, 1.0]]
    flips = IntrinsicFlips.__new__(IntrinsicFlips)
    flips.impl = impl
    rule = "lengths" if impl.cot_rule == "dotcross" else impl.cot_rule
    for row in rows:
        flips.l2 = np.array([row], dtype=impl.dtype)
        with np.errstate(all="ignore"):
            want = impl._cots_from_lengths(flips.l2, rule)[0]
        got = np.array([flips.cot(0, c) for c in range(3)], dtype=impl.dtype)
        assert np.array_equal(got, want, equal_nan=True), (row, got, want)


def _same_bounds(V, F, recipe) -> bool:
    """Asserts entry_bounds of a surface (from its positions) equal bit for bit those of
    its exact metric; returns whether the metric was built (a face the filter left exact)."""
    from ddg_oracle.properties.bounds import entry_bounds
    from ddg_oracle.reference.metric import face_area_floats, squared_length_floats
    from ddg_oracle.reference.polyhedral import PolyhedralSurface
    fresh, ref = (PolyhedralSurface.from_arrays(V, F) for _ in range(2))
    n = fresh.triangulation.n_vertices
    got = entry_bounds(fresh, n)
    built = fresh._metric is not None
    want = entry_bounds(ref.metric(), n)
    assert np.array_equal(got.rho, want.rho) and np.array_equal(got.cot, want.cot), recipe
    want.B = _entry_bounds_by_loop(ref.metric(), n, want.beta, want.cot)
    for a, b in ((got.B, want.B), (got.adjacent, want.adjacent)):
        assert np.array_equal(a.indptr, b.indptr) and np.array_equal(a.indices, b.indices)
        assert np.array_equal(a.data, b.data), recipe

    def floats(compute):
        try:
            return compute()
        except OverflowError:                   # beyond the float range, both ways
            return None
    assert floats(lambda: squared_length_floats(fresh.positions, fresh.triangulation)) == \
        floats(lambda: [float(x) for x in ref.metric().squared_lengths]), recipe
    assert floats(lambda: face_area_floats(fresh.positions, fresh.triangulation)) == \
        floats(lambda: [float(a) for a in ref.metric().areas]), recipe
    return built


def _entry_bounds_by_loop(metric, n, beta, cot):
    """entry_bounds' B as the loop over the edges that the vectorised assembly replaced."""
    import scipy.sparse as sp

    from ddg_oracle.protocol.methods import eps
    from ddg_oracle.reference.combinatorics import face_of, opposite_corner
    t = metric.triangulation
    rows, cols, faces, corners = [], [], [], []
    for e in range(t.n_edges):
        i, j = t.edge_vertices(e)
        if i == j:
            continue
        for h in t.edge_halfedges(e):
            if h < 0:
                continue
            for x, y in ((i, j), (j, i), (i, i), (j, j)):
                rows.append(x)
                cols.append(y)
                faces.append(face_of(h))
                corners.append(opposite_corner(h))

    def summed(data):
        M = sp.csr_matrix((data, (rows, cols)), shape=(n, n))
        M.sum_duplicates()
        return M
    b, m = summed(beta[faces, corners] / 2), summed(np.abs(cot[faces, corners]) / 2)
    cnt = summed(np.ones(len(rows)))
    B = b.copy()
    B.data = b.data + cnt.data * eps() * m.data
    return B


def test_entry_bounds_from_positions_are_the_metric_ones():
    """The entry bounds of D3.1, E3.12, T3.9 come from the positions (correctly rounded
    squared lengths by integer division, the metric only for the faces the float filter
    leaves exact), and L3.7's face areas too: bit for bit those of the exact metric, on
    needles, caps and fans (some faces exact), a jittered torus with a boundary cut
    (none), rational points without a shared denominator, and lengths beyond the float
    range."""
    for make, seed in ((triangles, 61), (fans, 67), (hinges, 71)):
        V, F = make(FORMATS[53], seed=seed)
        _same_bounds(V, F, make.__name__)
    from ddg_oracle.reference import surfaces
    s = surfaces.torus(8, 12)
    V, F = (np.asarray(a, dtype=float) for a in s.to_arrays())
    V = V + np.random.default_rng(7).uniform(-2 ** -6, 2 ** -6, V.shape)
    F = F.astype(np.int64)[:-5]                               # a boundary
    assert not _same_bounds(V.tolist(), F.tolist(), "torus")  # no face left exact
    odd = [[Fraction(1, 3 ** k), Fraction(k, 7 ** k), Fraction(1, 11 ** k)] for k in range(1, 5)]
    _same_bounds(odd, [[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]], "no shared denominator")
    from ddg_oracle.properties.bounds import entry_bounds
    from ddg_oracle.reference.polyhedral import PolyhedralSurface
    huge = [[0.0, 0.0, 0.0], [1e300, 0.0, 0.0], [0.0, 1e300, 0.0], [0.0, 0.0, 1e300]]
    for route in (lambda s: s, lambda s: s.metric()):        # beyond the float range: both
        with pytest.raises(OverflowError):
            entry_bounds(route(PolyhedralSurface.from_arrays(huge, [[0, 1, 2], [0, 2, 3],
                                                                    [0, 3, 1], [1, 3, 2]])), 4)
