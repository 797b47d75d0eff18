"""Exact cotan weights and Laplacian, faces per second, peers side by side (issue 7, item 1)
and exact curvature on the same meshes (item 2)."""

from __future__ import annotations

import importlib.util

from ddg_oracle.reference.cotan_fast import cotan_laplacian_fast, cotan_weights_fast
from ddg_oracle.reference.curvature import (angle_defects, angle_sums_from_corners, gauss_bonnet_holds,
                                 gauss_bonnet_holds_by_faces)
from ddg_oracle.reference.exact import Surd, pi
from ddg_oracle.reference.laplacian import (cotan_laplacian_from_weights, cotan_weights,
                                            cotan_weights_from_corners)
from ddg_oracle.reference.polyhedral import PolyhedralSurface

from . import meshes, peers
from .common import Mode, fit_exponent, median_time, say

def _canonical(values):
    """Compute the canonical form of every irrational value (what equality, arithmetic
    with other Surds and str need; the fast path's CotanSum leaves it to them)."""
    for v in values:
        if isinstance(v, Surd):
            v.terms()
    return values


def weights_canonical(s):
    return _canonical(cotan_weights_fast(s).values())


def laplacian_canonical(s):
    L = cotan_laplacian_fast(s)
    return _canonical([v for i, j, v in L.entries() if i <= j])


# (name, what, function, largest faces default / quick, needs module).  The reference's
# entries get a freshly built PolyhedralSurface (exact positions, no cached metric; the
# building is timed separately as "input"); the others start from the float lists.
PEERS = [
    ("reference fast path", "weights", cotan_weights_fast, (10 ** 6, 10 ** 4), None),
    ("reference fast path", "Laplacian", cotan_laplacian_fast, (10 ** 6, 10 ** 4), None),
    ("reference fast path", "weights, canonical forms", weights_canonical, (10 ** 6, 10 ** 4),
     None),
    ("reference fast path", "Laplacian, canonical forms", laplacian_canonical,
     (10 ** 6, 10 ** 4), None),
    ("reference public cotan_weights", "weights", cotan_weights, (10 ** 6, 10 ** 4), None),
    ("reference definition", "weights", cotan_weights_from_corners, (6000, 1300), None),
    ("reference definition", "Laplacian", cotan_laplacian_from_weights, (6000, 1300), None),
    ("reference input", "PolyhedralSurface.from_arrays", None, (10 ** 6, 10 ** 4), None),
    ("Fraction pairs", "weights", peers.weights_fractions, (6000, 1300), None),
    ("gmpy2 pairs", "weights", peers.weights_gmpy2, (10 ** 6, 6000), "gmpy2"),
    ("sympy", "weights", peers.weights_sympy, (400, 100), "sympy"),
    ("libigl cotmatrix (float64)", "Laplacian", peers.laplacian_libigl, (10 ** 6, 10 ** 6),
     "igl"),
    ("numpy (float64)", "weights", peers.weights_numpy, (10 ** 6, 10 ** 6), "numpy"),
]
FLOAT_PEERS = ("libigl cotmatrix (float64)", "numpy (float64)")


def _surface(V, F) -> PolyhedralSurface:
    return PolyhedralSurface.from_arrays(V, F)


def _meshes(mode: Mode):
    """(label, faces, V, F): icospheres of 4 or 5 sizes, then pymeshlab's bunnies."""
    for levels in (1, 2, 3, 4) if mode.quick else (1, 2, 3, 4, 5):
        V, F = meshes.icosphere_arrays(levels)
        yield "icosphere", len(F), V, F
    for name in ("bunny10k_textured.obj",) if mode.quick else ("bunny10k_textured.obj",
                                                                 "bunny.obj"):
        mesh = meshes.pymeshlab_sample(name)
        if mesh is not None:
            yield name.split(".")[0], len(mesh[1]), mesh[0], mesh[1]


def run(mode: Mode) -> dict:
    import numpy as np
    rows = []
    for label, nf, V, F in _meshes(mode):
        arrays = np.asarray(V, dtype=float), np.asarray(F, dtype=np.int64)
        for name, what, fn, limits, module in PEERS:
            if nf > limits[mode.quick] or (module and importlib.util.find_spec(module) is None):
                continue
            if label != "icosphere" and name in ("Fraction pairs", "sympy"):
                continue
            if name == "reference input":
                t, runs, _ = median_time(lambda: _surface(V, F), mode)
            elif name.startswith("reference"):
                t, runs, _ = median_time(fn, mode, setup=lambda: _surface(V, F))
            else:
                args = arrays if name in FLOAT_PEERS else (V, F)
                t, runs, _ = median_time(lambda: fn(*args), mode)
            rows.append({"mesh": label, "faces": nf, "peer": name, "quantity": what,
                         "seconds": t, "runs": runs, "faces_per_s": nf / t if t else None})
            say(f"  cotan {label:10} {nf:6} {name:32} {what:9} {t:9.4f} s")
    fits = {}
    for name, what, *_ in PEERS:
        pts = [(r["faces"], r["seconds"]) for r in rows
               if r["peer"] == name and r["quantity"] == what and r["mesh"] == "icosphere"]
        if len(pts) >= 2:
            fits[f"{name} / {what}"] = fit_exponent(*zip(*pts))
    return {"rows": rows, "fits": fits, "curvature": _curvature(mode)}


def angle_defects_definition(s):
    """``ddg_oracle.reference.curvature.angle_defects`` as defined: the angle sums of the
    metric's corner angles (``angle_sums_from_corners``), minus 2 pi."""
    sums = angle_sums_from_corners(s)
    t = s.triangulation
    return {v: 2 * pi - x for v, x in enumerate(sums) if not t.is_boundary_vertex(v)}


# (quantity, fast path, definition); the definitions run up to 5,120 faces (1,280 quick)
CURVATURE = [("angle defects", angle_defects, angle_defects_definition),
             ("Gauss-Bonnet decision", gauss_bonnet_holds, gauss_bonnet_holds_by_faces)]


def _curvature(mode: Mode) -> dict:
    """Exact angle defects and the exact Gauss-Bonnet decision (metric included): the
    fast paths the public functions dispatch to, and the definitions, on the same
    meshes in the same run."""
    rows = []
    for label, nf, V, F in _meshes(mode):
        for what, fast, definition in CURVATURE:
            for impl, fn in (("fast path", fast), ("definition", definition)):
                if impl == "definition" and (label != "icosphere"
                                             or nf > (1300 if mode.quick else 6000)):
                    continue
                t, runs, _ = median_time(fn, mode, setup=lambda: _surface(V, F))
                rows.append({"mesh": label, "faces": nf, "quantity": what, "impl": impl,
                             "seconds": t, "runs": runs, "faces_per_s": nf / t})
                say(f"  curvature {label:10} {nf:6} {what:22} {impl:10} {t:9.4f} s")
    fits = {}
    for what, *_ in CURVATURE:
        for impl in ("fast path", "definition"):
            pts = [(r["faces"], r["seconds"]) for r in rows if r["mesh"] == "icosphere"
                   and r["quantity"] == what and r["impl"] == impl]
            if len(pts) >= 2:
                fits[f"{what} / {impl}"] = fit_exponent(*zip(*pts))
    return {"rows": rows, "fits": fits}
