"""Exact intrinsic flips to Delaunay (issue 7, item 3): rational-metric flat tori of
2,000 to 50,000 faces, and rational surfaces in R^3 where square roots accumulate."""

from __future__ import annotations

import contextlib
import math
import random
import time

from ddg_oracle.reference.curvature import angle_sums, gauss_bonnet_holds
from ddg_oracle.reference.delaunay import flip_to_delaunay
from ddg_oracle.reference.exact import Surd
from ddg_oracle.reference.exact import angles
from ddg_oracle.reference.polyhedral import PolyhedralSurface

from . import meshes, peers
from .common import Mode, fit_exponent, median_time, say, start_clock

TORI = (32, 50, 71, 100, 158)          # 2 n^2 faces: 2,048 ... 49,928


def run(mode: Mode) -> dict:
    rows = []
    for n in TORI[:4] if mode.quick else TORI:
        m = meshes.randomised_flat_torus(n)
        nf = m.triangulation.n_faces
        t, runs, (d, log) = median_time(lambda: flip_to_delaunay(m), mode)
        rows.append({"faces": nf, "peer": "in place (IntrinsicTriangulation)", "seconds": t,
                     "runs": runs, "flips": len(log), "flips_per_s": len(log) / t})
        say(f"  flips {nf:6} in place   {len(log):6} flips {t:8.4f} s")
        if nf <= (2100 if mode.quick else 5100):
            t, runs, (d, log) = median_time(lambda: peers.flip_to_delaunay_immutable(m), mode)
            rows.append({"faces": nf, "peer": "immutable flips (before)", "seconds": t,
                         "runs": runs, "flips": len(log), "flips_per_s": len(log) / t})
            say(f"  flips {nf:6} immutable {len(log):6} flips {t:8.4f} s")
    fits = {}
    for peer in {r["peer"] for r in rows}:
        pts = [(r["faces"], r["seconds"]) for r in rows if r["peer"] == peer]
        if len(pts) >= 2:
            fits[peer] = fit_exponent(*zip(*pts))
    return {"rows": rows, "fits": fits}


def _terms(x) -> int:
    return x.n_terms if isinstance(x, Surd) else 1


def run_r3(mode: Mode) -> dict:
    """Flips on surfaces from R^3: squared lengths and areas in Q(sqrt r1, ...); the
    largest number of terms of a squared length or area, and of the harmonic index
    carried by the log (one square root per face)."""
    cases = [("torus", lambda: meshes.rational_torus(10, 10)),
             ("torus", lambda: meshes.rational_torus(20, 20)),
             ("icosphere / 256", lambda: meshes.rational_icosphere(1))]
    if not mode.quick:
        cases += [("torus", lambda: meshes.rational_torus(40, 25)),
                  ("icosphere / 256", lambda: meshes.rational_icosphere(2))]
    rows = []
    for label, build in cases:
        m = build()
        t, runs, (d, log) = median_time(lambda: flip_to_delaunay(m), mode)
        data = list(m.squared_lengths) + list(m.areas) + list(d.squared_lengths) + list(d.areas)
        rows.append({"surface": label, "faces": m.triangulation.n_faces, "seconds": t,
                     "runs": runs, "flips": len(log),
                     "max_terms": max(_terms(x) for x in data),
                     "max_terms_h": max((_terms(r.h_after) for r in log), default=0)})
        say(f"  r3 {label:16} {m.triangulation.n_faces:5} {len(log):5} flips {t:8.4f} s")
    return {"rows": rows}


def _float_sphere(seed: int, n: int = 28):
    """A closed float mesh of 2 n - 4 faces: the convex hull of n random unit vectors
    (float64), its faces oriented outwards."""
    rng = random.Random(seed)
    pts = []
    while len(pts) < n:
        p = [rng.gauss(0, 1) for _ in range(3)]
        r = sum(x * x for x in p) ** 0.5
        if r > 1e-3:
            pts.append([x / r for x in p])
    from scipy.spatial import ConvexHull
    faces = ConvexHull(pts).simplices.tolist()
    for f in faces:
        a, b, c = (pts[i] for i in f)
        u, w = [b[k] - a[k] for k in range(3)], [c[k] - a[k] for k in range(3)]
        normal = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
        if sum(normal[k] * a[k] for k in range(3)) < 0:
            f[1], f[2] = f[2], f[1]
    return PolyhedralSurface.from_arrays(pts, faces)


@contextlib.contextmanager
def _zero_test_as(test):
    """The exact zero test of angles replaced by another (the one before, side by side)."""
    here = angles._pi24_multiple
    angles._pi24_multiple = test
    try:
        yield
    finally:
        angles._pi24_multiple = here


#: the zero test before 2026-12-06 is run only where a cotangent has at most this many square
#: roots: with 9 (seed 4) one vertex's T2.5 alone took 525 s (cProfile, 2026-12-06)
BEFORE_MAX_ROOTS = 6


def run_egregium(mode: Mode) -> dict:
    """Issue 46's target: T2.5 (every vertex's angle sum after intrinsic flips equals the
    one before, decided exactly) and Gauss-Bonnet (``gauss_bonnet_holds``) on a 52-face
    float mesh after 60 random flip attempts, CPU seconds each, per seed; the exact zero
    test of angle sums as it is and as it was (``peers.pi24_multiple_before``), side by
    side in one run."""
    rows = []
    for seed in range(2 if mode.quick else 6):
        m = _float_sphere(seed).metric()
        before = angle_sums(m)
        flipped = meshes.random_flips(m, 60, seed=seed)
        n_flips = sum(1 for a, b in zip(m.triangulation.faces, flipped.triangulation.faces)
                      if a != b)
        roots = max(len(flipped.corner_cot(f, c).base)
                    for f in range(flipped.triangulation.n_faces) for c in range(3))
        for impl, test in (("now", angles._pi24_multiple), ("before", peers.pi24_multiple_before)):
            if impl == "before" and roots > BEFORE_MAX_ROOTS:
                continue
            with _zero_test_as(test):
                t1, runs, same = median_time(
                    lambda x: all(a == b for a, b in zip(before, angle_sums(x))), mode,
                    setup=lambda: meshes.random_flips(m, 60, seed=seed))
                t2, _, gb = median_time(gauss_bonnet_holds, mode,
                                        setup=lambda: meshes.random_flips(m, 60, seed=seed))
            assert same and gb
            rows.append({"seed": seed, "faces": m.triangulation.n_faces,
                         "faces_changed": n_flips, "max_roots": roots, "impl": impl,
                         "t25_s": t1, "gauss_bonnet_s": t2, "runs": runs})
            say(f"  egregium seed {seed} {impl:6} T2.5 {t1:7.3f} s  Gauss-Bonnet {t2:7.3f} s"
                f"  ({roots} square roots in a cotangent)")
    return {"rows": rows}


#: CPU seconds the eager exact flips may take on one mesh before they are given up
EAGER_LIMIT = 30


def lifted_fan(n: int, seed: int = 0) -> PolyhedralSurface:
    """A fan of n - 2 triangles from vertex 0 over an ellipse (axes 3 and 1), its vertices
    lifted at random by up to 0.25: every flip depends on the one before (tests/test_lazy.py)."""
    rng = random.Random(seed)
    V = [(math.cos(2 * math.pi * k / n) * 3.0, math.sin(2 * math.pi * k / n),
          rng.uniform(0, 0.25)) for k in range(n)]
    return PolyhedralSurface.from_arrays(V, [(0, k, k + 1) for k in range(1, n - 1)])


def _lazy_meshes(mode: Mode):
    """(label, PolyhedralSurface): lifted fans, PyMeshLab's bunnies and, when the corpus is
    fetched, CGAL's meshes whose exact flips outgrew the survey's time limit (issue 42)."""
    import importlib.util
    from ddg_oracle.application.meshes import load, resolve
    from ddg_oracle.reference.errors import InputError
    for n in (10, 16) if mode.quick else (10, 16, 40):
        yield f"lifted fan {n}", lifted_fan(n)
    names = ["pymeshlab:bunny10k_textured.obj"]
    if not mode.quick:
        names += ["pymeshlab:bunny.obj", "cgal:part.off", "cgal:anchor.off", "cgal:camel.off",
                  "cgal:cheese.off"]
    if importlib.util.find_spec("pymeshlab") is None:
        names = [n for n in names if not n.startswith("pymeshlab:")]
    for name in names:
        try:
            (n, path, _), = resolve([name])
            m = load(n, path)
        except (InputError, ValueError):           # the corpus is not fetched
            continue
        yield name, PolyhedralSurface.from_arrays(m.V, m.F)


def run_lazy(mode: Mode) -> dict:
    """Issue 46's target for the exact intrinsic Delaunay of float meshes (>= 0.05 x libigl's
    float64 ``intrinsic_delaunay_triangulation``, the same flips as the exact algorithm):
    ``flip_to_delaunay`` eager (exact square-root numbers, given up after
    :data:`EAGER_LIMIT` CPU seconds) and lazy (``lazy=True``), libigl from the same float
    edge lengths, side by side on each mesh; ``same``: the two exact runs' flip sequences
    and final squared lengths equal (where the eager one finished)."""
    import importlib.util
    from ddg_oracle.properties.profiles import example_time_limit
    from ddg_oracle.reference.errors import ExactArithmeticLimit, TermLimitExceeded
    rows = []
    for label, s in _lazy_meshes(mode):
        m = s.metric()
        nf = m.triangulation.n_faces
        t_lazy, runs, (dl, logl) = median_time(lambda: flip_to_delaunay(m, lazy=True), mode)
        t0 = start_clock()
        try:
            with example_time_limit("the eager exact flips", EAGER_LIMIT, cpu=True):
                de, loge = flip_to_delaunay(m)
            t_eager = time.process_time() - t0
            same = ([r.edge for r in logl] == [r.edge for r in loge]
                    and dl.squared_lengths == de.squared_lengths)
        except (ExactArithmeticLimit, TermLimitExceeded) as e:
            t_eager, same = None, None
            gave_up = type(e).__name__
        else:
            gave_up = None
        t_igl = None
        if importlib.util.find_spec("igl") is not None:
            import numpy as np
            import igl
            V, F = s.to_arrays()
            V, F = np.asarray(V, dtype=float), np.asarray(F, dtype=np.int64)
            l = igl.edge_lengths(V, F)
            t_igl, _, _ = median_time(lambda: igl.intrinsic_delaunay_triangulation(l, F), mode)
        rows.append({"mesh": label, "faces": nf, "flips": len(logl), "lazy_s": t_lazy,
                     "runs": runs, "eager_s": t_eager, "eager_gave_up": gave_up,
                     "same": same, "libigl_s": t_igl})
        say(f"  lazy {label:34} {nf:6} faces {len(logl):6} flips  lazy {t_lazy:8.4f} s  "
            f"eager " + (f"{t_eager:8.4f} s" if t_eager is not None else f"gave up ({gave_up})")
            + (f"  libigl {t_igl:8.5f} s" if t_igl is not None else ""))
    return {"rows": rows, "eager_limit": EAGER_LIMIT}
