"""The exact reference on real meshes (issue 18): PyMeshLab's sample meshes and generated fans.

Per mesh: the exact angle defects (D2.2), the exact sign of every one (each a decision:
elliptic / flat / hyperbolic), their correctly rounded floats computed from scratch (the float
view, on fresh values: no enclosure left by a sign), the Gauss-Bonnet decision (T2.6), how many
decisions were undecided (must be 0) and how many needed the exact zero test after the
enclosure, and libigl's float64 ``gaussian_curvature`` on the same arrays for scale.  Then
``flip_to_delaunay`` (the intrinsic Delaunay triangulation, every decision exact) on each mesh
and on fans with a high-valence apex, and the exact check that every angle sum survived.
"""

from __future__ import annotations

import importlib.util
import time

from ddg_oracle.reference.curvature import angle_defects, angle_sums, gauss_bonnet_holds
from ddg_oracle.reference import delaunay
from ddg_oracle.reference.delaunay import flip_to_delaunay
from ddg_oracle.reference.errors import DDGError, InputError
from ddg_oracle.reference.exact import angles
from ddg_oracle.reference.metric import as_metric
from ddg_oracle.reference.polyhedral import PolyhedralSurface

from .common import Mode, median_time, say, start_clock

SAMPLES = ("cube.obj", "airplane.obj", "bone.ply", "cow.obj", "bunny10k_textured.obj", "bunny.obj")
QUICK_SAMPLES = ("cube.obj", "bone.ply")
#: the exact angle-sum comparison after the flips only up to this many flips: the cotangents of
#: long flip cascades carry the square roots of many input faces (minutes on cow.obj)
CHECKED_FLIPS = 200


def _fans(mode: Mode):
    from .meshes import fan
    for n in ((16, 64) if mode.quick else (16, 32, 64, 128)):
        s = fan(n)
        yield f"fan {n}, exactly planar", PolyhedralSurface(
            s.triangulation, [(x, y, 3 * x - 2 * y) for x, y, _ in s.positions])
        yield f"fan {n}, float-tilted", fan(n, tilt=(0.3, 0.7))
        yield f"fan {n}, lifted 2^-100", fan(n, lift=2.0 ** -100)


def _samples(mode: Mode):
    import pymeshlab
    from pathlib import Path
    from ddg_oracle.application.meshes import load
    root = Path(pymeshlab.__file__).parent / "tests" / "sample_meshes"
    for name in QUICK_SAMPLES if mode.quick else SAMPLES:
        path = root / name
        if not path.exists():
            continue
        try:
            m = load(name, path)
        except InputError as e:
            say(f"  real {name}: skipped ({e})")
            continue
        yield name + (" (unreferenced vertices removed)" if m.note else ""), \
            PolyhedralSurface.from_arrays(m.V, m.F)


class _Counter:
    """Counts the calls of ``module.name`` inside the block: the exact zero tests
    (``angles._pi24_multiple``: decisions the enclosure alone did not settle), the exact
    harmonic-index decreases (``delaunay._exact_change`` in the flip loop: likewise)."""

    def __init__(self, module, name):
        self.calls, self._module, self._name = 0, module, name
        self._real = getattr(module, name)

    def __enter__(self):
        def counted(*args):
            self.calls += 1
            return self._real(*args)
        setattr(self._module, self._name, counted)
        return self

    def __exit__(self, *exc):
        setattr(self._module, self._name, self._real)


def _decide(K):
    undecided = 0
    for k in K.values():
        try:
            k.sign()
        except DDGError:
            undecided += 1
    return undecided


def _row(label: str, s: PolyhedralSurface, mode: Mode) -> dict:
    nf = s.triangulation.n_faces
    t_exact, _, K = median_time(lambda: angle_defects(s), mode)
    with _Counter(angles, "_pi24_multiple") as zero_tests:
        t0 = start_clock()
        undecided = _decide(K)
        t_sign = time.process_time() - t0
    fresh = angle_defects(s)
    t0 = start_clock()
    for k in fresh.values():
        float(k)
    t_float = time.process_time() - t0
    t_gb, _, gb = median_time(lambda: gauss_bonnet_holds(s), mode)
    row = {"mesh": label, "faces": nf, "vertices": s.triangulation.n_vertices,
           "defects": len(K), "exact_s": t_exact, "sign_s": t_sign, "float_s": t_float,
           "gauss_bonnet_s": t_gb, "gauss_bonnet": gb, "undecided": undecided,
           "zero_tests": zero_tests.calls, "libigl_s": None}
    if importlib.util.find_spec("igl") is not None:
        import numpy as np
        import igl
        V, F = s.to_arrays()
        V, F = np.asarray(V, dtype=float), np.asarray(F, dtype=np.int64)
        row["libigl_s"], _, _ = median_time(lambda: igl.gaussian_curvature(V, F), mode)
    # a tenth of a millisecond printed: sidebyside reads these lines, and a 10-ms
    # rounding step was a 25% move on the fans (a 1-ms step still 8% on a 12-ms line)
    say(f"  real {label:40} {nf:6} faces  exact {t_exact:8.4f}  signs {t_sign:8.4f}  "
        f"floats {t_float:8.4f}  undecided {undecided}  zero tests {zero_tests.calls}")
    return row


def _flip_row(label: str, s: PolyhedralSurface, check: bool = True) -> dict:
    m = as_metric(s)
    t0 = start_clock()
    with _Counter(delaunay, "_exact_change") as exact:
        d, log = flip_to_delaunay(m)
    t_flip = time.process_time() - t0
    kept = t_check = None
    if check and len(log) <= CHECKED_FLIPS:
        t0 = start_clock()
        with _Counter(angles, "_pi24_multiple") as zero_tests:
            kept = all(a == b for a, b in zip(angle_sums(m), angle_sums(d)))
        t_check = time.process_time() - t0
    view = _views(d)
    say(f"  real {label}: {len(log)} flips {t_flip:.4f} s ({exact.calls} exact decreases), "
        f"angle sums kept: {kept}" + (f" ({t_check:.2f} s)" if kept is not None else "")
        + f"; Laplacian view {view['view_s']:.3f} s, through the exact matrix "
        + (f"{view['exact_view_s']:.3f} s" if view["exact_view_s"] is not None
           else f"> {EXACT_VIEW_LIMIT} s"))
    return {"mesh": label, "faces": s.triangulation.n_faces, "flips": len(log),
            "flip_s": t_flip, "exact_decreases": exact.calls, "check_s": t_check, "kept": kept,
            "zero_tests": zero_tests.calls if kept is not None else None, **view}


#: CPU seconds the float view through the exact matrix may take before it is given up
EXACT_VIEW_LIMIT = 60


def _views(d) -> dict:
    """The float view of the Delaunay metric's cotan Laplacian (D3.2 after A4.13; what the
    checks compare implementations with): as the properties compute it (flipped faces'
    cotangents as quotients, no division: ``properties.views``), and through the exact
    matrix (``exact_laplacian(d).to_scipy()``, the way before issue 46), given up after
    :data:`EXACT_VIEW_LIMIT` CPU seconds; ``same``: the two bit for bit."""
    from ddg_oracle.properties import views
    from ddg_oracle.properties.profiles import example_time_limit
    from ddg_oracle.reference.errors import ExactArithmeticLimit
    from ddg_oracle.reference.laplacian import cotan_laplacian
    t0 = start_clock()
    V = views._laplacian_view(d)
    t_view = time.process_time() - t0
    t0 = start_clock()
    try:
        with example_time_limit("the exact Laplacian", EXACT_VIEW_LIMIT, cpu=True):
            E = cotan_laplacian(d).to_scipy()
        t_exact = time.process_time() - t0
    except ExactArithmeticLimit:
        return {"view_s": t_view, "exact_view_s": None, "same": None,
                "exact_view_limit": EXACT_VIEW_LIMIT}
    V.sort_indices()
    E.sort_indices()
    same = bool((V.indptr == E.indptr).all() and (V.indices == E.indices).all()
                and V.data.tobytes() == E.data.tobytes())
    return {"view_s": t_view, "exact_view_s": t_exact, "same": same}


def _cad(mode: Mode):
    """CGAL's CAD meshes whose exact Laplacian after the flips took minutes (issue 46), when
    the corpus is fetched (``ddg-oracle corpus fetch cgal``)."""
    from ddg_oracle.application.meshes import load, resolve
    for name in () if mode.quick else ("cgal:mpi.off", "cgal:mpi_triang.off", "cgal:elk.off"):
        try:
            (n, path, _), = resolve([name])
            m = load(n, path)
        except InputError:                      # the corpus is not fetched
            continue
        yield name, PolyhedralSurface.from_arrays(m.V, m.F)


def run(mode: Mode) -> dict:
    from .meshes import spiky_fan
    rows, flips = [], []
    if importlib.util.find_spec("pymeshlab") is not None:
        for label, s in _samples(mode):
            rows.append(_row(label, s, mode))
            flips.append(_flip_row(label, s))
    rows += [_row(label, s, mode) for label, s in _fans(mode)]
    flips += [_flip_row(f"spiky fan {n}", spiky_fan(n))
              for n in ((16,) if mode.quick else (16, 24, 32))]
    # the CAD meshes' angle sums after the flips: the exact zero tests of sums of angles
    # whose cotangents carry many square roots take minutes (issue 46): not checked
    flips += [_flip_row(label, s, check=False) for label, s in _cad(mode)]
    return {"rows": rows, "flips": flips}
