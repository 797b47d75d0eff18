"""Time to catch planted bugs (issue 16, item 3; issue 40, item 5): ``ddg-oracle check --impl
BUG`` on the properties that call the methods the bug plants, under the default profile and,
on request, under ci and thorough.

The bugs: ``examples/numpy_cotan.py``'s four, ``tests/planted_bugs.py``'s, and the one-line
variants of ``benchmarks/planted/`` (:data:`benchmarks.planted.variants.VARIANTS`: a correct
numpy implementation of every protocol method, one line changed).  For every bug, profile and
run: the failing properties, the task seconds of the fastest failing one (its examples, the
failure and the shrinking, from the report's timings.json), the faces of its shrunk
counterexample, the smallest counterexample of any failing property, and the wall time of the
whole check.

Runs: default with seeds 1, 2, 3 (:data:`SEEDS`); ci derandomized (no seed: as CI runs it,
one stream per property); thorough with seed 1, only on the bugs that some default or ci run
missed, unless ``--thorough-all``: it has no time budget and 1000 examples (each check is
stopped after :data:`TIMEOUT` seconds, and counted as not caught).  Every check runs without
an example database (``DDG_HYPOTHESIS_DATABASE=none``): a failure saved by one bug's check
would otherwise be replayed first for the next bug on the same property, and the shared
``.hypothesis`` directory would fill with other bugs' counterexamples.  At most :data:`JOBS` checks run at
once, each with one worker (``--workers 1``).

    python -m benchmarks catch                       # default profile, seeds 1, 2, 3
    CATCH_PROFILES=default,ci,thorough python -m benchmarks catch
    python -m benchmarks.catch --profiles default,ci,thorough [--only NAME ...] [--no-write]

(``python -m benchmarks.catch`` updates the catch entry of docs/perf/results.json and this
section of docs/performance.md only; ``python -m benchmarks catch`` regenerates the whole file.)

The section of docs/performance.md is written by :func:`section` (the variants' table with
each profile's result, the counts, and the "not yet caught" list with the diagnoses of
:data:`DIAGNOSES`); ``python -m benchmarks catch`` writes it too, through the hook this module
puts on ``benchmarks.report.write`` (the report's own catch table has one profile's columns).
"""

from __future__ import annotations

import argparse
import concurrent.futures
import hashlib
import inspect
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

from .common import ROOT, Mode, load_results, machine, save_results, say

SEEDS = (1, 2, 3)
#: profiles run by default; more with $CATCH_PROFILES or ``--profiles`` (comma-separated)
CATCH_PROFILES = ("default",)
PROFILE_SEEDS = {"default": SEEDS, "ci": (None,), "thorough": (1,)}
#: checks run at once (each with one worker): the machine has 2 cores
JOBS = 2
#: wall seconds after which a check is stopped (thorough has no budget of its own)
TIMEOUT = {"thorough": 900.0}
#: "caught small": a counterexample of at most this many faces (issue 40's target)
SMALL = 6
NUMPY_COTAN = ("SignError", "BoundaryWithoutHalf", "WrongCorner", "AbsoluteThreshold")

#: where each older planted bug hides (the variants say it themselves: ``bug_class``)
OLD_CLASSES = {
    "SignError": "sign", "BoundaryWithoutHalf": "boundary", "WrongCorner": "index",
    "AbsoluteThreshold": "scale", "ChiIgnoresBoundary": "boundary",
    "AlwaysOrientable": "non-orientable", "OneBoundaryLoop": "boundary",
    "Float32Defects": "float32 (F-pymeshlab-6)", "NoFlips": "flip loop",
    "OneFlipTooMany": "flip loop (F-pymeshlab-7)", "OneSidedDelaunayTest": "index",
    "LaplaceBeltramiWithoutHalf": "factor", "BoundaryByMissingTwin": "orientation",
    "AbsoluteZeroArea": "scale (F-trimesh-3)", "OffsetCancellation": "far from the origin",
    "ClampedArccos": "needles and caps", "MaxValence32": "high valence",
    "FirstComponentOnly": "components", "WeldedByPosition": "components",
    "BincountWithoutMinlength": "isolated vertices", "CompactedVertices": "isolated vertices",
    "TwinByReversedKey": "orientation",
    "ChiOfUsedVertices": "isolated vertices", "ChiOfFirstComponent": "components",
    "OrientableByDirectedEdges": "orientation",
    "BoundaryLoopsByDirectedTwin": "orientation (F-libigl-1)",
    "IntrinsicCompacted": "isolated vertices", "IntrinsicFirstHoleOnly": "isolated vertices",
    "DelaunayKeyedByUsedCount": "isolated vertices",
}

#: why a bug is not (yet) caught under the default profile, and which properties should catch
#: it: shown in the "not yet caught" list of docs/performance.md while the run misses it.
#: Measured on the working tree of 2026-12-05 (HEAD 03b7637 with uncommitted strategy changes;
#: the entries naming "the working tree of 2026-12-05 16:40": HEAD e2a4825 with uncommitted
#: strategy changes, whose catch figures are in docs/performance.md section 7):
#: "N of 100 draws" counts Hypothesis's own draws (default profile, no database) of the
#: property's strategy; "probe": the property run by run_on_example on a hand-made example.
_BY_DESIGN = ("not a miss of the strategies: within the derived bound by design. bounds.py "
              "admits areas and cotangents computed through the side lengths (C_HERON, "
              "C_LENGTHS; K_COT eps (1 + cot^2) rho for the flips), and these formulas are "
              "backward stable in the lengths; probe: an octahedron with a face split 2^-20 "
              "(and 2^-26) from an edge's midpoint (a cap) passes {pids} ({numbers}). Catching "
              "them would need bounds from the coordinates (the cross-product route) where the "
              "implementation had coordinates; whether the notes call this a bug is the "
              "lead's call.")
DIAGNOSES: dict[str, str] = {
    # topology
    "IsOrientableFirstComponentOnly": (
        "T1.1 / C1.2 draws, in one example of two since 2026-12-06, an orientation trap "
        "(strategies.orientation_traps: an orientable surface with faces reversed, or an "
        "orientable component before or after a non-orientable one, a third each). Inherent "
        "size: a non-orientable component has at least 6 faces (the Möbius strip of "
        "surfaces.mobius_strip(3)), so the smallest counterexample is 10 faces."),
    "GenusCountsIsolated": (
        "should be T1.1 / C1.2 or R1.6 (the properties calling genus): both draw a vertex "
        "used by no face now (isolated=1); the expected genus of a surface plus isolated "
        "points is the surface's."),
    "AlwaysOrientable": (
        "caught every time, but only with the 10-face projective plane: on a Möbius strip "
        "(6 faces) its genus (2 - chi) // 2 = 1 is right by accident. Inherent: no closed "
        "non-orientable surface has fewer than 10 faces."),
    "OneBoundaryLoop": (
        "R1.6 needs two boundary loops: since 2026-12-06 it draws annuli (surfaces.annulus(n), "
        "n = 3..6: two loops in 6 to 12 faces) beside Möbius strips and punched surfaces (a "
        "two-hole punched surface has 22 faces or more)."),
    "MaxValence32": "inherent: a vertex of valence 33 needs 33 faces.",
    "ChiOfUsedVertices": (
        "D1.6 catches it every time but shrinks to the 10-face projective plane (plus the "
        "isolated vertex), not the 4-face tetrahedron: triangulated_surfaces draws "
        "`orientable` with st.booleans(), which Hypothesis shrinks to False, and the "
        "simplest non-orientable base is the projective plane. `not draw(st.booleans())` "
        "would shrink to the tetrahedron (4 faces + 1 vertex)."),
    "ChiDropsIsolated": "the same as ChiOfUsedVertices (its twin): shrinks to the projective "
                        "plane, 10 faces, because `orientable` shrinks to False.",
    "ChiOfFirstComponent": "the same shrinking target as ChiOfUsedVertices (orientable -> "
                           "False: the projective plane, 10 faces).",
    "MeanCurvatureUnsigned": (
        "an unsigned dihedral angle is wrong only on a reflex (saddle) edge: since 2026-12-06 "
        "the 6-face dented bipyramid is the second of jittered_surfaces' closed surfaces "
        "(after the tetrahedron), so a failure on a larger surface shrinks to it."),
    # chapter 2
    "CornerAnglesPiMinusTwo": (
        "not a miss of the strategies: within D2.6's bound by design. Since D2.6's corner "
        "bound has the side-length term C_LENGTHS eps S_f (S_f the face's cotangent sum, about "
        "1 / alpha_min on a needle) for every corner of the face, pi minus two arccos (error "
        "about 2 eps / alpha_min on the third corner) passes: probe, a tetrahedron with a "
        "needle face 2^-10, 2^-20, 2^-30 whose small angle is corner 0: the third angle off "
        "by 3.6e-13, 1.6e-10, 9.3e-10 from NumpyAll's, D2.6 passes. F-trimesh-4 (2.07 x "
        "the bound) was measured against the bound before that term."),
    "CornerAnglesUnitizeThreshold": (
        "edges below 1e-13 need a scale 2^k, k <= -44 (D2.6: jittered_surfaces scales three "
        "draws of four by k in -60..60, about 1 example in 10); since the working tree of "
        "2026-12-05 16:40 D4.7 draws delaunay_meshes scaled by scaled_meshes (2^-64, 2^-200 "
        "in one draw of four) and catches it on one triangle."),
    "AreaTextbookHeron": _BY_DESIGN.format(
        pids="R2.5", numbers="total area off by 4.4e-11 resp. 3.7e-10 of 3.46, inside the "
        "Heron-route bound of face_area_tolerances"),
    "BarycentricTextbookHeron": _BY_DESIGN.format(
        pids="L3.7", numbers="vertex areas off by 1.5e-11 resp. 1.2e-10"),
    "IntrinsicTextbookHeron": _BY_DESIGN.format(
        pids="D4.8 / R4.9 and A4.13", numbers="Laplace-Beltrami entries off by 1.2e-10 resp. "
        "1.0e-9; intrinsic_meshes draw no caps anyway (delaunay_meshes exclude slivers)"),
    "IntrinsicFlipLayoutPythagoras": _BY_DESIGN.format(
        pids="D4.8 / R4.9 and A4.13", numbers="Laplace-Beltrami entries off by 9e-11 resp. "
        "5.3e-9; intrinsic_meshes draw no caps anyway"),
    # chapter 3
    "TwinByReversedKey": (
        "T3.9 / D3.1 catch it when an interior edge joins two inconsistently listed faces: "
        "since the working tree of 2026-12-05 16:40 any_meshes' small families are one branch "
        "(half the draws, not one in eight: Hypothesis flattens nested one_of) with faces "
        "reversed in a third of them (with_reversed_faces), besides surface_meshes' reversed "
        "faces and Möbius strips."),
    "CotanFromArccos": (
        "1/tan(arccos) stays within K_COT eps (1 + cot^2) rho (its error, eps / alpha^2 "
        "relative, is that bound's order) until a needle's small angle falls below about "
        "sqrt(eps) = 2^-26, where the cosine rounds to 1: only needles 2^-26 .. 2^-30 show it "
        "(T3.9, T3.1, T3.6, D3.1; a tetrahedron with a face split next to a corner, 6 faces). "
        "Since the working tree of 2026-12-05 16:40 the sliver exponent is drawn evenly over "
        "1..30 (integers(1, 30) drew 2^-1 in half the examples)."),
    "CotanMaxValence16": (
        "caught every time (T3.9, D3.1, T3.6, T3.1) since the working tree of 2026-12-05 "
        "16:40: any_meshes' small families include valence_fans (a fan of valence 3 .. 33, 17 "
        "and above in 5 of 12 draws) and are half the draws. Inherent size: a vertex of "
        "valence 17 needs 17 faces (a fan; a bipyramid of the surface arm has 34)."),
    "AreaGradientAbsoluteGuard": (
        "T3.9 (area_gradient route) catches a mesh scaled below 1e-6; since the working tree "
        "of 2026-12-05 16:40 T3.9's small families are scaled_meshes (2^-24, 2^-64, 2^-200 in "
        "three draws of eight) and caught it on 2-4 faces."),
    "DirichletDuplicatedBoundary": (
        "outside the protocol's domain, not a miss: solve_dirichlet's boundary indices are "
        "distinct (protocol.METHODS; the libraries agree: gpytoolbox asserts 'No duplicate "
        "indices', LaPy raises 'dtup indices need to be unique', libigl's "
        "min_quad_with_fixed crashes the process on V0 = [1, 1, 2, ...], probe 2026-12-05), "
        "so with_boundary never lists a vertex twice."),
    "DirichletInaccurateSolve": (
        "caught every time by C3.4 since the working tree of 2026-12-05 16:40: its strategy "
        "draws planar grids of 4 x 4 and 5 x 5 squares (a dozen to thirty unknowns), where CG "
        "stopped at rtol 1e-5 leaves its residual (probe: 11 of 12 4 x 4 grids with a random "
        "half of V0). Inherent size: on the few unknowns of a 2 x 3 grid CG converges to "
        "rounding within n steps; the smallest counterexample seen had 18 faces."),
    "BarycentricCompacted": (
        "L3.7 catches an isolated vertex before a used one; since the working tree of "
        "2026-12-05 16:40 L3.7's small families come with_isolated (one vertex used by no "
        "face, at a drawn index) and are half the draws."),
    "VoronoiObtuseAbsoluteEpsilon": (
        "L3.7 catches an obtuse face scaled below about 1e-6; since the working tree of "
        "2026-12-05 16:40 L3.7's small families (obtuse quads and fans, grids) are "
        "scaled_meshes (below 1 in three draws of eight) and caught it on 2 faces."),
    # chapter 4
    "DelaunayTwinByReversedKey": (
        "D4.4 catches it on any non-Delaunay edge next to a reversed face: since the working "
        "tree of 2026-12-05 16:40 D4.4's examples (delaunay_test_meshes) have faces reversed "
        "in a third of the draws (with_reversed_faces); 2 faces (a near-tie quad moved in, "
        "one face reversed) or a grid (12) when that came first."),
    "DelaunayTolerance1e6": (
        "D4.4 catches it on a near-tie quad moved inward by less than 1e-6 (|cot a| + |cot "
        "b|): since the working tree of 2026-12-05 16:40 half of D4.4's draws are "
        "near_cocircular_meshes (1-4 quads, each moved in (two times of three) or out by "
        "2^-k, k from NEAR_TIE_EXPONENTS, 40 first; the tilted quads are a rotation now: the "
        "old tilt z = x / 4 put them on an ellipse, far from any tie)."),
    "DelaunayTolerance1e10": (
        "as DelaunayTolerance1e6, but only inward moves with k >= 34 .. 36 count (k = 44 is a "
        "tie for a third of the quads, within float64's bound); a quad whose diagonal is a "
        "diameter (cot a = cot b = 0) never shows a relative tolerance."),
    "IntrinsicSinglePass": (
        "A4.13 / D4.8 catch it only where a flip makes a neighbour non-Delaunay (a cascade): "
        "since 2026-12-06 every intrinsic example has, in one draw of two, a convex fan "
        "beside it (strategies.with_traps_beside, convex_fans: points on a parabola fanned "
        "from a corner, a cascade from 6 points on), and sweep_meshes draw them too."),
    "IntrinsicAssumesOrientation": (
        "A4.13 catches it on a non-Delaunay interior edge next to a reversed face or on a "
        "non-orientable surface: since the working tree of 2026-12-05 16:40 intrinsic_meshes "
        "have faces reversed in a third of the draws (with_reversed_faces over every kind), "
        "caught with 2 faces (a near-tie quad moved in, one face reversed)."),
    "IntrinsicFlipTolerance1e6": (
        "D4.8 / A4.13 catch it on a near-tie quad moved inward by 2^-20 .. 2^-40: a third "
        "of intrinsic_meshes are near_cocircular_meshes, and since 2026-12-06 every "
        "intrinsic example has, in one draw of two, a near-tie quad beside it "
        "(strategies.with_traps_beside)."),
    "PlanarFlipAbsoluteEpsilon": (
        "L4.3 / P4.4 catches it on any non-Delaunay start scaled down: since the working tree "
        "of 2026-12-05 16:40 its triangulations are scaled_planar (2^k, k from SCALES: 2^-24, "
        "2^-64, 2^-200 in three draws of eight; the in-circle determinant, of degree 4, below "
        "1e-9)."),
    "PlanarDelaunayFloat32": (
        "T4.1 / D4.1 catch it when float32 rounding moves a nearly cocircular point back onto "
        "the circle (k > 24) and Qhull picks the other diagonal (about one near tie in two): "
        "since the working tree of 2026-12-05 16:40 half of the planar point sets are "
        "near_cocircular_point_sets (4-6 points of the circle of radius 5, one moved by 2^-k, "
        "k from NEAR_TIE_EXPONENTS)."),
}


def bugs() -> list[dict]:
    """Every planted bug: spec, planted methods, source, class."""
    sys.path.insert(0, str(ROOT))          # the benchmark runs from the repository
    try:
        import tests.planted_bugs as planted
        from benchmarks.planted.variants import VARIANTS
    finally:
        sys.path.remove(str(ROOT))
    out = [{"spec": f"examples.numpy_cotan:{name}", "planted": ("cotan_laplacian",),
            "source": "examples/numpy_cotan.py", "class": OLD_CLASSES.get(name, "")}
           for name in NUMPY_COTAN]
    members = inspect.getmembers(planted, inspect.isclass)
    members.sort(key=lambda m: inspect.getsourcelines(m[1])[1])
    for name, cls in members:
        if cls.__module__ == planted.__name__ and getattr(cls, "planted", ()):
            out.append({"spec": f"tests.planted_bugs:{name}", "planted": tuple(cls.planted),
                        "source": "tests/planted_bugs.py", "class": OLD_CLASSES.get(name, "")})
    for cls in VARIANTS:
        out.append({"spec": f"benchmarks.planted.variants:{cls.__name__}",
                    "planted": tuple(cls.planted), "source": "benchmarks/planted",
                    "class": cls.bug_class + (f" ({cls.finding})" if cls.finding else ""),
                    "admitted": cls.admitted})
    return out


def properties_calling(methods) -> list[str]:
    from ddg_oracle.properties import PROPERTIES
    return [pid for pid, p in PROPERTIES.items() if set(p.methods) & set(methods)]


def _faces(result) -> int | None:
    mesh = result.get("mesh") or {}
    F = mesh.get("F") if isinstance(mesh, dict) else None
    return len(F) if F else None


def _one(spec: str, ids: list[str], seed: int | None, profile: str) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        report = os.path.join(tmp, "report")
        cmd = [sys.executable, "-m", "ddg_oracle", "check", "--impl", spec, "--profile", profile,
               "--workers", "1", "--report", report, "--only", *ids]
        if seed is not None:
            cmd[cmd.index("--report"):cmd.index("--report")] = ["--seed", str(seed)]
        env = {**os.environ, "DDG_HYPOTHESIS_DATABASE": "none"}
        t0 = time.perf_counter()
        try:
            p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, env=env,
                               timeout=TIMEOUT.get(profile))
        except subprocess.TimeoutExpired:
            return {"seed": seed, "wall": time.perf_counter() - t0, "failed": [],
                    "statuses": {f"check stopped after {TIMEOUT[profile]:.0f} s": 1}}
        wall = time.perf_counter() - t0
        # exit 3 (an internal error of ddg-oracle on some check) still reports the others
        if p.returncode not in (0, 1, 3) or not os.path.exists(os.path.join(report, "results.json")):
            raise RuntimeError(f"{' '.join(cmd)} exited {p.returncode}:\n{p.stderr[-3000:]}")
        with open(os.path.join(report, "results.json")) as fh:
            results = json.load(fh)["results"]
        with open(os.path.join(report, "timings.json")) as fh:
            seconds = {t["property_id"]: t["seconds"] for t in json.load(fh)["results"]}
    failed = [r for r in results if r["status"] in ("FAILED", "crashed")]
    others = {}
    for r in results:
        if r["status"] not in ("passed", "FAILED", "crashed"):
            others[r["status"]] = others.get(r["status"], 0) + 1
    row = {"seed": seed, "wall": wall, "failed": [r["property_id"] for r in failed],
           "statuses": others}
    if failed:
        first = min(failed, key=lambda r: seconds.get(r["property_id"], float("inf")))
        sizes = [_faces(r) for r in failed if _faces(r)]
        row.update(first=first["property_id"], seconds=seconds.get(first["property_id"]),
                   status=first["status"], faces=_faces(first),
                   faces_min=min(sizes) if sizes else None)
    return row


def _summary(runs: list[dict]) -> dict:
    caught = [r for r in runs if r["failed"]]
    out = {"runs": len(runs), "caught": len(caught),
           "wall": statistics.median(r["wall"] for r in runs)}
    statuses: dict = {}
    for r in runs:
        for k, v in r["statuses"].items():
            statuses[k] = statuses.get(k, 0) + v
    if statuses:
        out["statuses"] = statuses
    if caught:
        firsts = [r["first"] for r in caught]
        faces = [r["faces"] for r in caught if r["faces"] is not None]
        mins = [r["faces_min"] for r in caught if r["faces_min"] is not None]
        secs = [r["seconds"] for r in caught if r["seconds"] is not None]
        out.update(first=max(set(firsts), key=firsts.count),
                   seconds=statistics.median(secs) if secs else None,
                   faces=statistics.median(faces) if faces else None,
                   faces_min=min(mins) if mins else None,
                   failing=sorted({p for r in caught for p in r["failed"]}))
    return out


def _missed(row: dict) -> bool:
    """Missed by default or ci: some run did not catch it (a bug caught every time, if only
    with a large counterexample, is not run again under thorough)."""
    return not row.get("admitted") and any(s["caught"] < s["runs"] for name, s in
                                           row["profiles"].items() if name in ("default", "ci"))


def _tree_state() -> str:
    """The working tree's properties/ and tests/planted_bugs.py as this run read them: a hash
    of their diff against HEAD ("clean" if none)."""
    try:
        diff = subprocess.run(["git", "diff", "HEAD", "--", "properties", "tests/planted_bugs.py"],
                              cwd=ROOT, capture_output=True, text=True, check=True).stdout
        new = subprocess.run(["git", "ls-files", "--others", "--exclude-standard", "properties"],
                             cwd=ROOT, capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    for path in new.split():
        with open(ROOT / path, "rb") as fh:
            diff += path + hashlib.sha1(fh.read()).hexdigest()
    return "clean" if not diff else "modified, diff sha1 " + hashlib.sha1(diff.encode()).hexdigest()[:10]


def run(mode: Mode, profiles=None, only=None, thorough_all: bool = False,
        progress: str | None = None) -> dict:
    """Every bug under ``profiles`` (default :data:`CATCH_PROFILES`, or $CATCH_PROFILES);
    ``only``: bug names to run (the others keep no row); ``mode.quick``: one seed.
    ``progress``: a JSON file where every finished check is kept as it ends, and from which
    the checks of an interrupted run with the same arguments are taken instead of rerun."""
    if profiles is None:
        env = os.environ.get("CATCH_PROFILES", "").strip()
        profiles = tuple(p.strip() for p in env.split(",") if p.strip()) if env else CATCH_PROFILES
    bad = [p for p in profiles if p not in PROFILE_SEEDS]
    if bad:
        raise ValueError(f"unknown profile(s) {bad}: choose from {', '.join(PROFILE_SEEDS)}")
    items = [b for b in bugs() if not only or b["spec"].split(":")[1] in only]
    before = _tree_state()
    t_start = time.perf_counter()
    import threading
    lock, done = threading.Lock(), {}
    if progress and os.path.exists(progress):
        with open(progress) as fh:
            done = json.load(fh)
        say(f"  catch: {len(done)} checks taken from {progress}")
    rows = []
    for b in items:
        ids = properties_calling(b["planted"])
        rows.append({"bug": b["spec"].split(":")[1], "spec": b["spec"], "planted": list(b["planted"]),
                     "class": b["class"], "source": b["source"], "properties": len(ids),
                     "admitted": b.get("admitted"),
                     "ids": ids, "profiles": {}})
    for name in [p for p in ("default", "ci", "thorough") if p in profiles]:
        seeds = PROFILE_SEEDS[name][:1] if mode.quick else PROFILE_SEEDS[name]
        todo = [r for r in rows if name != "thorough" or thorough_all or _missed(r)
                or not any(p in r["profiles"] for p in ("default", "ci"))]
        say(f"  catch: {name}, {len(todo)} bugs x {len(seeds)} run(s)")
        jobs = [(r, s) for r in todo for s in seeds]

        def one(job, name=name):
            r, seed = job
            key = f"{r['spec']}|{name}|{seed}"
            if key not in done:
                row = _one(r["spec"], r["ids"], seed, name)
                # under the lock: another thread's dump iterates over `done` (a key added
                # meanwhile stopped a run with "dictionary changed size during iteration"),
                # and written whole, then renamed (an interrupted dump leaves the last one)
                with lock:
                    done[key] = row
                    if progress:
                        with open(progress + ".tmp", "w") as fh:
                            json.dump(done, fh)
                        os.replace(progress + ".tmp", progress)
            return done[key]

        with concurrent.futures.ThreadPoolExecutor(JOBS) as pool:
            out = list(pool.map(one, jobs))
        for r in todo:
            runs = [o for (rr, _), o in zip(jobs, out) if rr is r]
            r["profiles"][name] = s = _summary(runs)
            say(f"  {name:8} {r['bug']:36} caught {s['caught']}/{s['runs']} first "
                f"{s.get('first', '-'):12} {s.get('seconds') or 0:6.1f} s "
                f"{s.get('faces', '-')} faces (smallest {s.get('faces_min', '-')}), "
                f"check {s['wall']:.1f} s")
    for r in rows:                  # the report's own table reads these: the default profile
        d = r["profiles"].get("default") or next(iter(r["profiles"].values()))
        r.update({k: d[k] for k in ("runs", "caught", "wall", "first", "seconds", "faces",
                                    "faces_min", "failing") if k in d})
        del r["ids"]
    after = _tree_state()
    return {"rows": rows, "seeds": list(SEEDS[:1] if mode.quick else SEEDS),
            "profiles": [p for p in ("default", "ci", "thorough") if p in profiles],
            "thorough_all": thorough_all, "tree": before if before == after else
            f"{before} at the start, {after} at the end", "minutes": (time.perf_counter() - t_start) / 60,
            "uptime": _uptime()}


def _uptime() -> str:
    try:
        return subprocess.run(["uptime"], capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return ""


# --- docs/performance.md ------------------------------------------------------------------------

HEADING = "## 7. Time to catch planted bugs"

INTRO = f"""\
{HEADING}

`python -m benchmarks catch` (profiles: `CATCH_PROFILES=default,ci,thorough python -m
benchmarks catch`, or `python -m benchmarks.catch --profiles default,ci,thorough`): each
planted bug checked by `ddg-oracle check --impl BUG --only IDS --profile P [--seed S]
--workers 1` (IDS = the properties that call the methods the bug plants; two checks at a
time; no example database, `DDG_HYPOTHESIS_DATABASE=none`, so that no check replays another
bug's saved counterexample).  The bugs: `examples/numpy_cotan.py` and `tests/planted_bugs.py`
(each the reference or numpy with one bug), and the one-line variants of
`benchmarks/planted/variants.py`: `NumpyAll` (`benchmarks/planted/numpy_all.py`, a correct
numpy float64 implementation of every protocol method; it passes `--profile ci`, ties
aside) with one line changed, each named after its mistake, with the finding of
docs/findings.md where a real library had it.  *default*: caught in how many of the runs
with seeds 1, 2, 3; *ci*: the derandomized run (no seed, as CI runs it); *thorough*: seed 1,
run only where some default or ci run missed (each check stopped after 15 minutes).
*first*: the failing property whose task ended soonest (the most frequent over the default
runs); *seconds*: that task's time, its examples, the failure and
the shrinking included (median over the default runs that caught it); *faces*: its shrunk
counterexample (median); *smallest*: the smallest counterexample of any failing property and
run.  Under *class*, where the bug hides (issue 40's classes) and the finding.
"""


def _cell(s: dict | None) -> str:
    if s is None:
        return "-"
    text = f"{s['caught']}/{s['runs']}"
    if s["caught"] and s.get("faces_min") is not None:
        text += f" ({s['faces_min']:g})"
    return text


def _fmt(x, spec) -> str:
    return "-" if x is None else format(x, spec)


def section(res: dict) -> str:
    rows, profiles = res["rows"], res.get("profiles", ["default"])
    meta = res.get("meta", {})
    lines = [INTRO, f"*Measured {meta.get('date')} at commit {meta.get('commit')} (working tree "
             f"of properties/ and tests/planted_bugs.py: {res.get('tree', 'unknown')}), Python "
             f"{meta.get('python')}, {meta.get('cpus')} CPUs, load average {meta.get('load')} at "
             f"start (`uptime`: {res.get('uptime', '-')}), "
             f"{'quick' if meta.get('quick') else 'default'} mode, {res.get('minutes', 0):.0f} "
             f"minutes in all.*" + (f" {res['note']}" if res.get("note") else ""), ""]
    admitted = [r for r in rows if r.get("admitted")]
    bugs_ = [r for r in rows if not r.get("admitted")]
    variants = [r for r in bugs_ if r.get("source") == "benchmarks/planted"]
    if admitted:
        lines.append(f"Of the {len(rows)} planted changes, {len(admitted)} are not bugs under the "
                     "protocol's contract (listed apart below, and kept passing by a test); "
                     "the counts are of the other " + f"{len(bugs_)}.")
        lines.append("")
    for label, group in (("all planted bugs", bugs_), ("the one-line variants", variants)):
        if not group:
            continue
        parts = []
        for p in profiles:
            have = [r for r in group if p in r["profiles"]]
            if not have:
                continue
            every = sum(r["profiles"][p]["caught"] == r["profiles"][p]["runs"] for r in have)
            some = sum(r["profiles"][p]["caught"] > 0 for r in have)
            small = sum(r["profiles"][p]["caught"] > 0
                        and (r["profiles"][p].get("faces_min") or 10 ** 9) <= SMALL for r in have)
            parts.append(f"{p}: {every} of {len(have)} caught in every run, {some} in some, "
                         f"{small} with a counterexample of at most {SMALL} faces")
        lines.append(f"- {label} ({len(group)}): " + "; ".join(parts) + ".")
    lines += ["", "| bug | planted | class | default | ci | thorough | first | seconds | faces "
              "| smallest |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        d = r["profiles"].get("default", {})
        lines.append(
            f"| {r['bug']} | {', '.join(r['planted'])} | {r.get('class', '')}"
            f"{' (admitted)' if r.get('admitted') else ''} | "
            f"{_cell(r['profiles'].get('default'))} | {_cell(r['profiles'].get('ci'))} | "
            f"{_cell(r['profiles'].get('thorough'))} | {d.get('first', '-')} | "
            f"{_fmt(d.get('seconds'), '.1f')} | {_fmt(d.get('faces'), 'g')} | "
            f"{_fmt(d.get('faces_min'), 'g')} |")
    lines += ["", "Cells: runs that caught the bug / runs, and in parentheses the smallest "
              "counterexample (faces) of those runs.", ""]
    odd = []
    for r in rows:
        for p in profiles:
            st_ = {k: n for k, n in r["profiles"].get(p, {}).get("statuses", {}).items()
                   if k not in ("tie disagreement", "not applicable")}
            if st_:
                odd.append(f"{r['bug']} ({p}: " + ", ".join(f"{n} {k}" for k, n in sorted(st_.items()))
                           + ")")
    if odd:
        lines += ["Other outcomes of some checks (summed over the runs): " + "; ".join(odd) + ".", ""]
    missed = [r for r in bugs_ if "default" in r["profiles"] and (
        r["profiles"]["default"]["caught"] < r["profiles"]["default"]["runs"]
        or (r["profiles"]["default"].get("faces_min") or 10 ** 9) > SMALL)]
    lines += ["### Not yet caught under the default profile", "",
              f"Missed in some default run, or caught only with more than {SMALL} faces: what "
              "should catch each, and why it does not (the to-do list of the strategies).", ""]
    if not missed:
        lines.append("None.")
    for r in missed:
        d = r["profiles"]["default"]
        how = (f"caught {d['caught']}/{d['runs']}" + (f", smallest {d['faces_min']:g} faces"
                                                     if d.get("faces_min") else ""))
        others = ", ".join(f"{p} {_cell(r['profiles'][p])}" for p in ("ci", "thorough")
                           if p in r["profiles"])
        why = DIAGNOSES.get(r["bug"], "not diagnosed yet.")
        lines.append(f"- **{r['bug']}** ({', '.join(r['planted'])}; default {how}"
                     f"{'; ' + others if others else ''}): {why}")
    if admitted:
        lines += ["", "### Admitted by the contract: not bugs", "",
                  "Planted changes that a correct implementation may make: their error is within "
                  "the derived bound by design (honest float methods from the side lengths have "
                  "the same), or the input they mishandle is outside the protocol's domain. "
                  "`tests/test_planted_variants.py` checks that each passes its properties.", ""]
        for r in admitted:
            d = r["profiles"].get("default")
            seen = f"; default {_cell(d)}" if d else ""
            lines.append(f"- **{r['bug']}** ({', '.join(r['planted'])}{seen}): {r['admitted']}. "
                         + DIAGNOSES.get(r["bug"], ""))
    return "\n".join(lines) + "\n"


def write_section(res: dict, doc=None) -> None:
    """Replace the catch section of docs/performance.md (up to the next ``## `` heading)."""
    from .report import DOC
    path = doc or DOC
    text = path.read_text()
    start = text.find(HEADING)
    if start < 0:
        return
    nxt = re.search(r"^## ", text[start + len(HEADING):], flags=re.M)
    end = start + len(HEADING) + nxt.start() if nxt else len(text)
    path.write_text(text[:start] + section(res) + "\n" + text[end:])


def _hook_report() -> None:
    """After ``benchmarks.report.write`` (what ``python -m benchmarks`` calls to regenerate
    docs/performance.md), write this module's catch section over the report's own."""
    from . import report
    if getattr(report.write, "catch_section", False):
        return
    original = report.write

    def write(results: dict) -> None:
        original(results)
        res = results.get("catch")
        if res and res.get("rows") and all("profiles" in r for r in res["rows"]):
            write_section(res)

    write.catch_section = True
    report.write = write


_hook_report()


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m benchmarks.catch", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--profiles", default=None,
                   help=f"comma-separated, of default, ci, thorough (default: "
                   f"{','.join(CATCH_PROFILES)}, or $CATCH_PROFILES)")
    p.add_argument("--only", nargs="+", default=None, metavar="NAME", help="these bugs only")
    p.add_argument("--thorough-all", action="store_true",
                   help="thorough on every bug, not only on those default or ci missed")
    p.add_argument("--quick", action="store_true", help="one seed per profile")
    p.add_argument("--no-write", action="store_true",
                   help="print only; leave docs/perf/results.json and docs/performance.md alone")
    p.add_argument("--json", default=None, metavar="FILE", help="also write the results here")
    p.add_argument("--progress", default=None, metavar="FILE",
                   help="keep every finished check here; rerun with it to resume")
    args = p.parse_args(argv)
    profiles = tuple(x.strip() for x in args.profiles.split(",")) if args.profiles else None
    meta = {**machine(), "quick": args.quick}
    res = run(Mode.of(args.quick), profiles, args.only, args.thorough_all, args.progress)
    res["meta"] = meta
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(res, fh, indent=1, sort_keys=True)
    if args.no_write:
        print(section(res))
        return 0
    results = load_results()
    if args.only and "catch" in results:        # merge: the other bugs keep their rows
        keep = {r["bug"]: r for r in results["catch"].get("rows", [])}
        for r in res["rows"]:
            keep[r["bug"]] = r
        order = [b["spec"].split(":")[1] for b in bugs()]
        res["rows"] = [keep[n] for n in order if n in keep]
    results["catch"] = res
    save_results(results)           # this group's entry; the other groups' are left as they are
    write_section(res)              # this section only: the rest of the file is not regenerated
    say("wrote the catch section of docs/performance.md and docs/perf/results.json")
    return 0


if __name__ == "__main__":
    sys.exit(main())
