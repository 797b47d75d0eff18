"""Exact intrinsic flips to Delaunay (issue 7, item 3): rational-metric flat tori of
2,000 to 50,000 faces, and rational surfaces in R^3 where square roots accumulate."""

from __future__ import annotations

from ddg_oracle.reference.delaunay import flip_to_delaunay
from ddg_oracle.reference.exact import Surd

from . import meshes, peers
from .common import Mode, fit_exponent, median_time, say

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
