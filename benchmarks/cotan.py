"""Exact cotan weights and Laplacian, faces per second, peers side by side (issue 7, item 1)
and exact curvature on the same meshes (item 2)."""

from __future__ import annotations

import importlib.util

from reference.cotan_fast import cotan_laplacian_fast, cotan_weights_fast
from reference.curvature import angle_defects, gauss_bonnet_holds
from reference.laplacian import cotan_laplacian_from_weights, cotan_weights
from reference.polyhedral import PolyhedralSurface

from . import meshes, peers
from .common import Mode, fit_exponent, median_time, say

# (name, what, function, largest faces default / quick, needs module).  The reference's
# entries get a freshly built PolyhedralSurface (exact positions, no cached metric; the
# building is timed separately as "input"); the others start from the float lists.
PEERS = [
    ("reference fast path", "weights", cotan_weights_fast, (10 ** 6, 10 ** 4), None),
    ("reference fast path", "Laplacian", cotan_laplacian_fast, (10 ** 6, 10 ** 4), None),
    ("reference definition", "weights", cotan_weights, (6000, 1300), None),
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
            say(f"  cotan {label:10} {nf:6} {name:28} {what:9} {t:9.4f} s")
    fits = {}
    for name, what, *_ in PEERS:
        pts = [(r["faces"], r["seconds"]) for r in rows
               if r["peer"] == name and r["quantity"] == what and r["mesh"] == "icosphere"]
        if len(pts) >= 2:
            fits[f"{name} / {what}"] = fit_exponent(*zip(*pts))
    return {"rows": rows, "fits": fits, "curvature": _curvature(mode)}


def _curvature(mode: Mode) -> list:
    """Exact angle defects and the exact Gauss-Bonnet decision (definitions, metric
    included) on the icospheres."""
    rows = []
    for levels in (1, 2, 3) if mode.quick else (1, 2, 3, 4):
        V, F = meshes.icosphere_arrays(levels)
        for what, fn in (("angle defects", angle_defects),
                         ("Gauss-Bonnet decision", gauss_bonnet_holds)):
            t, runs, _ = median_time(lambda: fn(_surface(V, F)), mode)
            rows.append({"faces": len(F), "quantity": what, "seconds": t, "runs": runs,
                         "faces_per_s": len(F) / t})
            say(f"  curvature {len(F):6} {what:22} {t:9.4f} s")
    return rows
