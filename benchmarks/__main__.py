"""``python -m benchmarks [GROUP ...] [--quick] [--all] [--runs N] [--no-write] [--gc-paused]``.

Groups: cotan, flips, r3, hypothesis (the default set), egregium (T2.5 and Gauss-Bonnet decided
exactly after intrinsic flips of float meshes, the zero test as it is and as it was), lazy (the
exact intrinsic Delaunay of float meshes, eager and lazy, beside libigl's float one), real (the exact reference on
PyMeshLab's sample meshes and generated fans), dirichlet (the certified Dirichlet
enclosure on float meshes up to 30,000 vertices, and exact elimination's limit), suite (the test suite and one
check), main (``ddg-oracle check`` three times and with ci: the main job's time), meshcheck
(``ddg-oracle check --mesh`` on PyMeshLab's bunnies, every implementation and libigl), large
(``check --mesh`` on bunny.obj loop-subdivided twice, 898,752 faces: wall, CPU and peak memory;
long), catch (the time
to catch each planted bug under the default profile), sidebyside (this checkout's numbers
against another version's, ``--base-python``), mutation (mutmut on the core modules of
reference/, the mutation score per module; long, docs/mutation.md), knockout (every public
reference function replaced by generic wrong versions of its result, killed or not by the
reference's tests; long, docs/knockout.md), faults (the fault suite:
hostile cases per area, handled or badly; docs/faults.md), meshread (peak memory of reading a
mesh file against its size; docs/faults.md)."""

from __future__ import annotations

import argparse
import sys

from . import (catch, cotan, dirichlet, faults, flips, knockout, large, meshread, mutation,
               real, report, sidebyside, suite)
from .common import Mode, load_results, machine, save_results, say

GROUPS = {
    "cotan": cotan.run,
    "flips": flips.run,
    "r3": flips.run_r3,
    "egregium": flips.run_egregium,
    "lazy": flips.run_lazy,
    "real": real.run,
    "dirichlet": dirichlet.run,
    "hypothesis": suite.run_hypothesis,
    "suite": suite.run_suite,
    "main": suite.run_main,
    "meshcheck": suite.run_mesh_checks,
    "large": large.run,
    "catch": catch.run,
    "sidebyside": sidebyside.run,
    "mutation": mutation.run,
    "knockout": knockout.run_group,
    "faults": faults.run,
    "meshread": meshread.run,
    "survey": __import__("benchmarks.survey", fromlist=["run"]).run,
}
# not part of --all
ONLY_NAMED = ("sidebyside", "mutation", "knockout", "faults", "meshread", "survey", "large")
DEFAULT = ["cotan", "flips", "r3", "hypothesis"]


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m benchmarks", description=__doc__)
    p.add_argument("groups", nargs="*", choices=[[], *GROUPS], metavar="GROUP",
                   help=f"any of {', '.join(GROUPS)} (default: {' '.join(DEFAULT)})")
    p.add_argument("--quick", action="store_true", help="smaller meshes, fewer runs (< 1 min)")
    p.add_argument("--all", action="store_true", help="every group, the suite timings too")
    p.add_argument("--runs", type=int, default=None, help="at most this many runs per timing")
    p.add_argument("--no-write", action="store_true",
                   help="print only; leave docs/performance.md and docs/perf/ alone")
    p.add_argument("--gc-paused", action="store_true",
                   help="pause the garbage collector around each timed run (as timeit does; "
                   "implies --no-write)")
    p.add_argument("--base-python", default=None,
                   help="sidebyside: an interpreter whose environment has the other version")
    p.add_argument("--rounds", type=int, default=2, help="sidebyside: alternating rounds")
    args = p.parse_args(argv)
    if args.gc_paused:
        args.no_write = True          # numbers of another method: never into the docs
    groups = [g for g in GROUPS if g not in ONLY_NAMED] if args.all else (args.groups or DEFAULT)
    mode = Mode.of(args.quick, args.runs, args.gc_paused)
    results = load_results()
    for g in groups:
        say(f"{g} ({'quick' if mode.quick else 'default'})")
        meta = {**machine(), "quick": mode.quick}          # the load average at the start
        res = (GROUPS[g](mode, args.base_python, args.rounds) if g == "sidebyside"
               else GROUPS[g](mode))
        res["meta"] = meta
        results[g] = res
    if not args.no_write:
        save_results(results)
        report.write(results)
        say(f"wrote {report.DOC.relative_to(report.ROOT)} and docs/perf/")
    return 0


if __name__ == "__main__":
    sys.exit(main())
