"""The meshes the benchmarks run on (the test suite's builders, reused)."""

from __future__ import annotations

import math
import random
from fractions import Fraction
from pathlib import Path

from ddg_oracle.reference import surfaces
from ddg_oracle.reference.intrinsic import IntrinsicTriangulation
from ddg_oracle.reference.polyhedral import PolyhedralSurface
from ddg_oracle.properties.metrics import flat_torus


def float_icosphere(levels=3, seed=7) -> PolyhedralSurface:
    """The icosahedron subdivided 1-to-4 ``levels`` times (new vertices at edge midpoints)
    and every coordinate jittered by a random float: 20 * 4**levels faces (the benchmarks'
    and the tests' float mesh)."""
    s = surfaces.icosahedron()
    t, P = s.triangulation, [tuple(float(x) for x in p) for p in s.positions]
    for _ in range(levels):
        t, mids = t.subdivide_1to4()
        P = P + [tuple((a + b) / 2 for a, b in zip(P[i], P[j])) for i, j in mids]
    rng = random.Random(seed)
    return PolyhedralSurface(t, [tuple(x + rng.uniform(-1e-2, 1e-2) for x in p) for p in P])


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
    from ddg_oracle.application.meshfiles import read_mesh
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


def fan(n, *, lift=0.0, tilt=None, seed=0):
    """A star of valence n around vertex 0, float coordinates: ring radii and angles jittered."""
    rng = random.Random(seed)
    V = [[0.0, 0.0, lift]]
    for k in range(n):
        t = 2 * math.pi * k / n + rng.uniform(-0.2, 0.2) / n
        r = 1 + rng.uniform(-0.3, 0.3)
        V.append([r * math.cos(t), r * math.sin(t), 0.0])
    if tilt:
        a, b = tilt
        def turn(p):
            x, y, z = p
            x, z = x * math.cos(a) - z * math.sin(a), x * math.sin(a) + z * math.cos(a)
            y, z = y * math.cos(b) - z * math.sin(b), y * math.sin(b) + z * math.cos(b)
            return [x, y, z]
        V = [turn(p) for p in V]
    return PolyhedralSurface.from_arrays(V, [[0, 1 + k, 1 + (k + 1) % n] for k in range(n)])


def spiky_fan(n, seed=0):
    """Valence-n apex with two jittered float rings: many non-Delaunay edges at the apex."""
    rng = random.Random(seed)
    V = [[0.0, 0.0, 0.3]]
    for ring, rad in ((1, 1.0), (2, 2.0)):
        for k in range(n):
            t = 2 * math.pi * (k + 0.5 * (ring - 1)) / n
            r = rad * (1 + rng.uniform(-0.4, 0.4))
            V.append([r * math.cos(t), r * math.sin(t), rng.uniform(-0.2, 0.2)])
    F = []
    for k in range(n):
        a, b, A, B = 1 + k, 1 + (k + 1) % n, 1 + n + k, 1 + n + (k + 1) % n
        F += [[0, a, b], [a, A, b], [b, A, B]]
    return PolyhedralSurface.from_arrays(V, F)
