"""The meshes the benchmarks run on (the test suite's builders, reused)."""

from __future__ import annotations

import random
from fractions import Fraction
from pathlib import Path

from ddg_oracle.reference import surfaces
from ddg_oracle.reference.intrinsic import IntrinsicTriangulation
from ddg_oracle.reference.polyhedral import PolyhedralSurface
from ddg_oracle.properties.metrics import flat_torus
from tests.test_laplacian import float_icosphere


def icosphere(levels: int) -> PolyhedralSurface:
    """The perturbed float icosphere of the tests: 20 * 4**levels faces."""
    return float_icosphere(levels)


def icosphere_arrays(levels: int):
    """``(V, F)`` float / int lists of :func:`icosphere`."""
    return icosphere(levels).to_arrays()


def pymeshlab_sample(name: str):
    """``(V, F)`` of a mesh shipped with pymeshlab's tests, or None if not installed."""
    try:
        import pymeshlab
    except ImportError:
        return None
    from ddg_oracle.meshfiles import read_mesh
    path = Path(pymeshlab.__file__).parent / "tests" / "sample_meshes" / name
    return read_mesh(path) if path.exists() else None


def random_flips(surface, k: int, seed: int = 7):
    """``k`` random flip attempts, in place (O(1) each); returns the frozen surface."""
    w = IntrinsicTriangulation(surface)
    rng = random.Random(seed)
    n = w.triangulation.n_edges
    for _ in range(k):
        e = rng.randrange(n)
        if w.is_flippable(e):
            w.flip(e)
    return w.surface()


def randomised_flat_torus(n: int):
    """The flat torus R^2 / (n (3, 1) Z + n (1, 2) Z) as a 2 n^2-face rational metric,
    randomised by 1.5 F random flips (as the 2,000-face test does)."""
    m = flat_torus(n, n, (3, 1), (1, 2))
    return random_flips(m, 3 * m.triangulation.n_faces // 2)


def rational_torus(m: int, n: int):
    """``surfaces.torus(m, n)`` (rational points on circles) randomised by F / 2 flips:
    irrational squared lengths and areas (Surds) after the first flips."""
    s = surfaces.torus(m, n).metric()
    return random_flips(s, s.triangulation.n_faces // 2, seed=1)


def rational_icosphere(levels: int):
    """The icosphere with coordinates rounded to 1/256 (a rational mesh with a square
    root per face) randomised by 1.2 F flips."""
    s = icosphere(levels)
    pts = [tuple(Fraction(round(x * 256), 256) for x in p) for p in s.positions]
    m = PolyhedralSurface(s.triangulation, pts).metric()
    return random_flips(m, 6 * m.triangulation.n_faces // 5, seed=1)
