"""The planted-bug benchmark's implementation and variants (benchmarks/planted/, issue 40 item 5):
the correct NumpyAll passes a few properties on a few examples, and every one-line variant
really differs from it on a small hand-made mesh (none is silently equivalent)."""

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import settings

from benchmarks.planted.numpy_all import NumpyAll
from benchmarks.planted.variants import VARIANTS
from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.profiles import profile
from ddg_oracle.protocol.methods import METHODS, capabilities
from ddg_oracle.properties.runner import PASSED, TIE, run_property
from ddg_oracle.reference import surfaces
from ddg_oracle.reference.planar import planar_triangulation

BASE = NumpyAll()


def test_numpy_all_has_every_protocol_method():
    assert capabilities(BASE) == frozenset(METHODS)


@pytest.mark.parametrize("pid", ["D1.6", "R1.6", "D2.2", "D3.1", "C3.4 / T3.5", "L3.7", "D4.4 / T4.7 / P4.9",
                                 "A4.13", "L4.3 / P4.4", "T4.1"])
def test_numpy_all_passes_a_few_properties(pid):
    few = settings(profile("default"), max_examples=4, database=None)
    r = run_property(PROPERTIES[pid], BASE, few, seed=1)
    assert r.status in (PASSED, TIE), f"{pid}: {r.status}\n{r.failure or r.error}"


# --- small hand-made meshes --------------------------------------------------------------------


def _arrays(s, jitter=0.0, seed=0):
    V, F = s.to_arrays()
    V = np.array(V, dtype=float)
    if jitter:
        V = V + np.random.default_rng(seed).uniform(-jitter, jitter, V.shape)
    return V, np.array(F, dtype=np.int64)


def _with_isolated(V, F, at=1):
    return np.insert(V, at, V[0] * 3 + 1, axis=0), np.where(F >= at, F + 1, F)


def _union(a, b):
    (V1, F1), (V2, F2) = a, b
    return np.concatenate([V1, V2 + 10]), np.concatenate([F1, F2 + len(V1)])


def _rp2(seed=3):
    t = surfaces.projective_plane()
    V = np.random.default_rng(seed).integers(-64, 64, (t.n_vertices, 3)) / 16
    return V, np.array(t.faces, dtype=np.int64)


def _split(V, F, f, point):
    """Face f split 1-to-3 at ``point``."""
    a, b, c = F[f]
    m = len(V)
    return (np.vstack([V, point]),
            np.vstack([np.delete(F, f, axis=0), [[a, b, m], [b, c, m], [c, a, m]]]))


def _planar(points, faces=None):
    pts = [tuple(Fraction(x) for x in p) for p in points]
    if faces is None:
        faces = planar_triangulation(pts).triangulation.faces
    return np.array([[x, y, 0.0] for x, y in points]), np.array(faces, dtype=np.int64)


def _near_tie(d):
    """Four points of the unit circle at 0, 60, 120 and 240 degrees (angles 120 and 60 degrees
    opposite the diagonal (0, 2)), the last moved in by d: the diagonal is not Delaunay, by a
    cot sum of about -d."""
    h = np.sqrt(3) / 2
    return (np.array([[1, 0, 0], [0.5, h, 0], [-0.5, h, 0], [-0.5 * (1 - d), -h * (1 - d), 0]]),
            np.array([[0, 1, 2], [0, 2, 3]]))


def _needle_fan(d=1e-10):
    """F-pymeshlab-8's planar disk: vertex 4 at distance d from vertex 1."""
    V = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [-0.5, 0.8660254037844386, 0.0],
                  [-0.5, -0.8660254037844386, 0.0], [1 - d, 0.33 * d, 0.0]])
    return V, np.array([[1, 2, 4], [0, 2, 3], [0, 3, 1], [2, 0, 4], [0, 1, 4]])


def _meshes():
    tet = _arrays(surfaces.tetrahedron(), 0.05, 1)
    ico = _arrays(surfaces.icosahedron(), 0.05, 2)
    grid = _arrays(surfaces.grid(3, 3))
    grid = (grid[0] + np.random.default_rng(4).uniform(-0.1, 0.1, grid[0].shape) * [1, 1, 3], grid[1])
    octa = _arrays(surfaces.octahedron())
    a, b, c = octa[1][0]
    mid = (octa[0][a] + octa[0][b]) / 2
    rng = np.random.default_rng(6)     # a sweep triangulation that needs flip cascades
    random_pts = [tuple(p) for p in rng.integers(-12, 12, (12, 2)) / 4]
    random_pts = list(dict.fromkeys(random_pts))
    fan_n = 20
    fan = (np.array([[0, 0, 0.3]] + [[np.cos(2 * np.pi * k / fan_n), np.sin(2 * np.pi * k / fan_n), 0]
                                       for k in range(fan_n)]),
           np.array([[0, 1 + k, 1 + (k + 1) % fan_n] for k in range(fan_n)]))
    reversed_tet = (tet[0], tet[1].copy())
    reversed_tet[1][0] = reversed_tet[1][0][::-1]
    obtuse = (np.array([[0, 0, 0], [4, 0, 0], [1, 0.5, 0.3], [2, -0.4, 0]]), np.array([[0, 1, 2], [1, 0, 3]]))
    return {
        "tetrahedron": tet, "icosahedron": ico, "grid": grid, "fan of valence 20": fan,
        "Moebius strip": _arrays(surfaces.mobius_strip(4), 0.02, 6),
        "projective plane": _rp2(), "tetrahedron, a face reversed": reversed_tet,
        "tetrahedron and an isolated vertex": _with_isolated(*tet),
        "tetrahedron and a projective plane": _union(tet, _rp2()),
        "needle fan": _needle_fan(),
        "cap": _split(*octa, 0, mid + 2.0 ** -30 * (octa[0][c] - mid)),
        "tetrahedron scaled by 2^-40": (tet[0] * 2.0 ** -40, tet[1]),
        "obtuse quad scaled by 2^-30": (obtuse[0] * 2.0 ** -30, obtuse[1]),
        "icosahedron moved by 2^30": (ico[0] + 2.0 ** 30, ico[1]),
        "obtuse quad": obtuse,
        "cap triangle": (np.array([[0, 0, 0], [1, 0, 0], [0.5, 2.0 ** -30, 0]]), np.array([[0, 1, 2]])),
        "sweep triangulation": _planar(random_pts),
        "small sweep triangulation": (_planar(random_pts)[0] * 2.0 ** -10, _planar(random_pts)[1]),
        "near tie 1e-8": _near_tie(1e-8), "near tie 1e-12": _near_tie(1e-12),
    }


MESHES = _meshes()
GRID = MESHES["grid"]
_boundary = [v for v in range(16) if v // 4 in (0, 3) or v % 4 in (0, 3)]
_values = np.linspace(-1, 1, len(_boundary)) ** 3
_big = _arrays(surfaces.grid(8, 8), 0.05, 8)
_big_boundary = [v for v in range(81) if v // 9 in (0, 8) or v % 9 in (0, 8)]
DIRICHLET = {   # (V, F, boundary, values) on the 4 x 4 grid: unsorted, and with a repeat; 9 x 9
    "unsorted": (*GRID, np.array(_boundary[::-1]), _values[::-1]),
    "repeated": (*GRID, np.array(_boundary + _boundary[:2]), np.concatenate([_values, _values[:2]])),
    "49 unknowns": (*_big, np.array(_big_boundary), np.cos(np.arange(len(_big_boundary)))),
}
POINTS = {      # planar point sets: unsorted, and nearly cocircular (a square, one corner moved)
    "unsorted": np.array(list(dict.fromkeys(tuple(p) for p in
                                           np.random.default_rng(7).integers(-9, 9, (10, 2)) / 3))),
    # the fourth point outside the circle of the others by about d: float32 (d = 1e-8) or
    # Qhull's joggle (d = 1e-12) moves it across
    "nearly cocircular 1e-8": np.array([[0, 0], [1, 0], [1, 1], [1e-8, 1 + 2e-8]]),
    "nearly cocircular 1e-12": np.array([[0, 0], [1, 0], [1, 1], [1e-12, 1 + 2e-12]]),
}


def _as_array(x):
    if isinstance(x, dict):
        return x
    if hasattr(x, "toarray"):
        return np.asarray(x.toarray(), dtype=float)
    if isinstance(x, tuple):
        return tuple(_as_array(y) for y in x)
    if isinstance(x, list):
        return sorted(sorted(map(int, loop)) for loop in x)
    return np.asarray(x)


def _differ(a, b) -> bool:
    """Clearly different answers: another shape, structure or value (beyond 1e-9 relative to
    the answer's size), or a NaN where the other has a number."""
    if isinstance(a, tuple):
        return len(a) != len(b) or any(_differ(x, y) for x, y in zip(a, b))
    if isinstance(a, dict):
        if set(a) != set(b):
            return True
        a, b = np.array([a[k] for k in sorted(a)]), np.array([b[k] for k in sorted(b)])
    if isinstance(a, list) or isinstance(b, list):
        return a != b
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape:
        return True
    if a.dtype == bool or b.dtype == bool or np.issubdtype(a.dtype, np.integer):
        return not np.array_equal(a, b)
    if not np.array_equal(np.isnan(a), np.isnan(b)):
        return True
    a, b = np.nan_to_num(a), np.nan_to_num(b)
    return bool(np.abs(a - b).max(initial=0) > 1e-9 * max(np.abs(a).max(initial=0), 1e-300))


def _answers(impl, method):
    if method == "solve_dirichlet":
        cases = DIRICHLET.values()
    elif method == "planar_delaunay":
        cases = [(P,) for P in POINTS.values()]
    elif method == "planar_flip_to_delaunay":
        cases = [MESHES[k] for k in ("sweep triangulation", "small sweep triangulation")]
    else:
        cases = MESHES.values()
    for args in cases:
        try:
            yield _as_array(getattr(impl, method)(*args))
        except Exception as e:  # noqa: BLE001  (a variant that raises differs)
            yield e


def _sorted_triangles(x):
    return sorted(tuple(sorted(map(int, t))) for t in x) if isinstance(x, np.ndarray) else x


@pytest.mark.parametrize("variant", VARIANTS, ids=lambda v: v.__name__)
def test_every_variant_differs_from_the_correct_implementation(variant):
    bug = variant()
    assert variant.planted and variant.__doc__ and variant.bug_class
    assert set(variant.planted) <= set(METHODS)
    for method in variant.planted:
        for want, got in zip(_answers(BASE, method), _answers(bug, method)):
            assert not isinstance(want, Exception), f"NumpyAll.{method} raised {want!r}"
            if isinstance(got, Exception):
                break
            if method in ("planar_delaunay", "planar_flip_to_delaunay"):
                want, got = _sorted_triangles(want), _sorted_triangles(got)
                if want != got:
                    break
            elif _differ(want, got):
                break
        else:
            pytest.fail(f"{variant.__name__}.{method} answers as NumpyAll on every test mesh")


def test_the_variants_change_only_their_planted_methods():
    # methods not planted answer exactly as NumpyAll's on a mesh where many differ
    V, F = MESHES["tetrahedron and an isolated vertex"]
    for variant in VARIANTS:
        bug = variant()
        for method in set(METHODS) - set(variant.planted) - {"solve_dirichlet", "planar_delaunay",
                                                             "planar_flip_to_delaunay"}:
            a, b = _as_array(getattr(BASE, method)(V, F)), _as_array(getattr(bug, method)(V, F))
            assert not _differ(a, b), f"{variant.__name__} changes {method}, not planted"


@pytest.mark.parametrize("variant", [v for v in VARIANTS if v.admitted], ids=lambda v: v.__name__)
def test_an_admitted_variant_passes_every_property_that_calls_it(variant):
    """A variant the contract admits (within the derived bound by design, or mishandling an
    input outside the protocol's domain) is no bug: were one to fail, either the bound
    stopped admitting an honest method (a false alarm) or the claim is wrong."""
    from benchmarks.catch import properties_calling
    for pid in properties_calling(variant.planted):
        r = run_property(PROPERTIES[pid], variant(), profile("default"), seed=1)
        assert r.status in (PASSED, TIE), f"{pid}: {r.status}\n{r.failure or r.error}"
