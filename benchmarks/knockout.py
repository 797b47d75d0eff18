"""Function-level knockout benchmark of the exact reference (issue 44): for every public
function of ``ddg_oracle.reference`` (all modules, ``exact.*`` included; the public methods
of its public classes too, properties included; not the exception classes of errors.py)
and every wrong version of it that fits its results (benchmarks/knockout_plugin.py:
``value``, ``last``, ``drop``, ``skip``), run the reference's tests with that wrong version
switched on and record whether some test fails (killed) or all pass (survived).

1. A recording run (all reference test files, every target wrapped by a recorder that
   leaves results alone) gives, per target, the kinds of result it returns (hence its
   variants) and the test files that call it.
2. A sanity check: one knockout that must be killed is, and the tests pass with none.
3. Screening: each knockout in a fresh ``python -m pytest -x`` child on the test files
   that called the function (most calls first).  Functions no reference test calls are
   listed as such (no wrong version of them can fail a test).
4. Confirmation: a survivor is run again on *all* the reference test files (the verdict).

Every child: ``nice -n 10``, one at a time, ``-p no:cacheprovider --hypothesis-seed=0``,
``DDG_HYPOTHESIS_DATABASE=none``, ``PYTHONHASHSEED=0``, ``CI`` unset, a timeout (counted as
killed, listed apart).

``python -m benchmarks.knockout [MODULE ...] [--variants ...] [--no-write] [--quick]``
(MODULE: ``cotangents``, ``exact.surds``, ...; ``--quick``: the first module only).
``python -m benchmarks knockout`` runs them all.  Results: docs/knockout.md and
docs/perf/knockout.json.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

from .common import ROOT, Mode, machine, say
from .knockout_plugin import (ENV, HAND_ENV, PACKAGE, RECORD_ENV, STATS_ENV, VARIANTS,
                              VARIANTS_OF_KIND, reference_modules, targets_of)

JSON = ROOT / "docs" / "perf" / "knockout.json"
DOC = ROOT / "docs" / "knockout.md"
PLUGIN = "benchmarks.knockout_plugin"
HAND_PLUGIN = "benchmarks.knockout_hand"      # switches a hand-written one on (DDG_KNOCKOUT_HAND)
TIMEOUT = 300.0
NEW_TESTS = "tests/test_knockouts.py"      # the tests written for this benchmark's survivors

# The reference's tests: the test files that import ddg_oracle.reference and exercise it,
# in-process and fast (about 90 s together on an idle core).  Left out: the CLI, driver,
# C++/JS, peer-oracle, report, mesh-file, packaging and subprocess tests, and the property
# suites of the oracle (they test the oracle's statements, through the reference).
REFERENCE_TESTS = [
    "tests/test_angles.py", "tests/test_combinatorics.py", "tests/test_curvature.py",
    "tests/test_delaunay.py", "tests/test_dirichlet.py", "tests/test_dirichlet_certificate.py",
    "tests/test_doctests.py", "tests/test_errata_proofs.py", "tests/test_fast_paths.py",
    "tests/test_fidelity_reference.py", "tests/test_intervals.py", "tests/test_intrinsic.py",
    "tests/test_laplacian.py", "tests/test_metrics.py", "tests/test_minimal_delaunay.py",
    "tests/test_mutants_combinatorics.py", "tests/test_mutants_cotangents.py",
    "tests/test_mutants_curvature.py", "tests/test_mutants_delaunay.py",
    "tests/test_mutants_intrinsic.py", "tests/test_mutants_laplacian.py",
    "tests/test_mutants_surfaces.py", "tests/test_planar.py", "tests/test_rippa.py",
    "tests/test_sparse.py", "tests/test_surds.py", "tests/test_surfaces.py",
    "tests/test_zero_test.py",
]
# tests left out as slow (none since 0ea2e8c made exact ranks fast; the committed run at
# 7de75da left out T2.10's rigidity test, then minutes alone: its data says so)
DESELECT: list[str] = []
_FIRST_RUN_DESELECT = ["tests/test_fidelity_reference.py::test_T2_10_is_infinitesimally_rigid_both_ways"]
# the sanity check: a knockout that must be killed, on a small file
SANITY = ("ddg_oracle.reference.combinatorics:Triangulation.euler_characteristic:value",
          ["tests/test_combinatorics.py"])


def reference_tests(baseline: bool = False) -> list[str]:
    files = list(REFERENCE_TESTS)
    if not baseline and (ROOT / NEW_TESTS).exists():
        files.append(NEW_TESTS)
    return files


def short(module: str) -> str:
    return module[len(PACKAGE) + 1:]


def full(module: str) -> str:
    return module if module.startswith(PACKAGE) else f"{PACKAGE}.{module}"


# -- children ------------------------------------------------------------------------------------

def _env(**extra) -> dict:
    env = {k: v for k, v in os.environ.items()
           if k not in ("CI", ENV, HAND_ENV, RECORD_ENV, "PYTEST_ADDOPTS", "PYTEST_XDIST_WORKER")}
    env.update(DDG_HYPOTHESIS_DATABASE="none", PYTHONHASHSEED="0", **extra)
    return env


def _pytest(files, env, timeout, stop_first=True):
    cmd = ["nice", "-n", "10", sys.executable, "-m", "pytest", "-q", "-rfE",
           "-p", "no:cacheprovider", "-p", PLUGIN, "-p", HAND_PLUGIN,
           "--hypothesis-seed=0", "-W", "ignore",
           *[a for d in DESELECT for a in ("--deselect", d)],
           *(["-x"] if stop_first else []), *files]
    t0 = time.monotonic()
    try:
        p = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True,
                           timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, time.monotonic() - t0, ""
    return p.returncode, time.monotonic() - t0, p.stdout + p.stderr


def _first_failure(out: str) -> str:
    for line in out.splitlines():
        if line.startswith(("FAILED ", "ERROR ")):
            return line[:200]
    return ""


def run_knockout(spec: str | None, files, timeout: float = TIMEOUT, hand: bool = False) -> dict:
    """One child: ``spec`` (MODULE:QUALNAME:VARIANT, or None; with ``hand`` a hand-written
    wrong version's MODULE:QUALNAME:NAME, benchmarks/knockout_hand.py) on ``files`` with ``-x``.
    status: killed (a test failed, or a test module failed to import), survived, timeout,
    or broken (pytest itself or the plugin failed: not a verdict)."""
    with tempfile.TemporaryDirectory(prefix="ddg-knockout-") as tmp:
        stats = Path(tmp) / "stats.json"
        env = _env(**({HAND_ENV if hand else ENV: spec, STATS_ENV: str(stats)} if spec else {}))
        rc, secs, out = _pytest(files, env, timeout)
        changed = json.loads(stats.read_text()) if stats.exists() else None
    if rc is None:
        status = "timeout"
    elif rc == 0:
        status = "survived"
    elif rc in (1, 2) and _first_failure(out):
        status = "killed"
    else:
        status = "broken"
    res = {"status": status, "seconds": round(secs, 1), "by": _first_failure(out)}
    if changed is not None:        # calls of the function, results the variant changed
        res.update(calls=changed["calls"], changed=changed["changed"])
    if status == "broken":
        res["output"] = out[-2000:]
    return res


def record(files, timeout: float = 1800.0) -> dict:
    """The recording run: per target, the kinds of result and the callers."""
    with tempfile.TemporaryDirectory(prefix="ddg-knockout-") as tmp:
        path = Path(tmp) / "record.json"
        rc, secs, out = _pytest(files, _env(**{RECORD_ENV: str(path)}), timeout,
                                stop_first=False)
        if rc != 0 or not path.exists():
            raise SystemExit(f"the recording run failed (rc {rc}):\n{out[-3000:]}")
        data = json.loads(path.read_text())
    data["seconds"] = round(secs, 1)
    return data


def caller_files(tests: list[str], files: list[str]) -> list[str]:
    """The test files among ``files`` whose tests (or module import) called the target, the
    file with the most calling tests first."""
    n = Counter()
    for t in tests:
        t = t[len("collect:"):] if t.startswith("collect:") else t
        n[t.split("::", 1)[0]] += 1
    return sorted((f for f in files if n[f]), key=lambda f: (-n[f], files.index(f)))


def variants_of(kinds: dict) -> tuple[list[str], list[str]]:
    """(the variants that fit the observed results, the kinds no variant fits).  ``skip``
    only for a function that returned None every time."""
    vs, other = set(), []
    for k in kinds:
        if k == "None":
            continue
        if k in VARIANTS_OF_KIND:
            vs.update(VARIANTS_OF_KIND[k])
        else:
            other.append(k[len("other:"):] if k.startswith("other:") else k)
    if set(kinds) == {"None"}:
        vs.add("skip")
    return [v for v in VARIANTS if v in vs], sorted(other)


# -- the benchmark ------------------------------------------------------------------------------

def sanity(files) -> dict:
    spec, small = SANITY
    killed = run_knockout(spec, small)
    clean = run_knockout(None, small)
    say(f"  knockout sanity: {spec} {killed['status']}; no knockout {clean['status']}")
    if killed["status"] != "killed" or clean["status"] != "survived":
        raise SystemExit(f"knockout sanity check failed: {killed} / {clean}")
    return {"knockout": spec, "files": small, "killed": killed, "clean": clean}


def plan(modules, rec: dict, variants, files) -> tuple[list[dict], list[dict]]:
    """The knockouts to run, and the targets that get none (with the reason)."""
    runs, idle = [], []
    for m in modules:
        for qualname, how in targets_of(m):
            key = f"{m}:{qualname}"
            base = {"module": short(m), "target": qualname, "how": how}
            if key in rec["unpatchable"]:
                idle.append({**base, "why": "unpatchable: " + rec["unpatchable"][key]})
                continue
            seen = rec["seen"].get(key)
            if not seen:
                idle.append({**base, "why": "not called by any reference test"})
                continue
            vs, other = variants_of(seen["kinds"])
            vs = [v for v in vs if v in variants]
            if other:
                idle.append({**base, "why": "not perturbable: returns " + ", ".join(other),
                             "partly": bool(vs)})
            if not vs and not other:
                idle.append({**base, "why": "returns None, sometimes something else"})
            callers = caller_files(seen["tests"], files)
            for v in vs:
                runs.append({**base, "variant": v, "kinds": sorted(seen["kinds"]),
                             "files": callers})
    return runs, idle


def run_all(runs: list[dict], files, timeout: float = TIMEOUT, confirm: bool = True,
            done=None) -> None:
    """Screen each knockout (``r["screen"]``; skipped when already there) and confirm its
    survivors on all ``files`` (``r["confirm"]``); ``done()`` after each one."""
    t_start = time.monotonic()
    for i, r in enumerate(runs, 1):
        spec = f"{PACKAGE}.{r['module']}:{r['target']}:{r['variant']}"
        res = r.get("screen")
        if res is None:
            res = r["screen"] = run_knockout(spec, r["files"] or files, timeout)
        elif not (confirm and res["status"] == "survived" and "confirm" not in r):
            continue
        if res["status"] == "survived" and confirm and set(r["files"]) != set(files):
            ordered = r["files"] + [f for f in files if f not in r["files"]]
            res = r["confirm"] = run_knockout(spec, ordered, timeout)
        r["status"] = res["status"]
        r["by"] = res["by"]
        if "changed" in res:
            r["calls"], r["changed"] = res["calls"], res["changed"]
        if done is not None:
            done()
        if res["status"] == "broken":
            say(f"  BROKEN {spec}:\n{res.get('output', '')}")
        say(f"  [{i}/{len(runs)} {time.monotonic() - t_start:5.0f} s] {r['status']:8} {spec} "
            f"({res['seconds']} s) {r['by'][:90]}")


def summary(runs, idle, modules) -> list[dict]:
    rows = []
    for m in modules:
        sm = short(m)
        rr = [r for r in runs if r["module"] == sm]
        ii = [t for t in idle if t["module"] == sm]
        c = Counter(r["status"] for r in rr)
        rows.append({"module": sm, "targets": len(targets_of(m)),
                     "knocked_out": len({r["target"] for r in rr}), "variants": len(rr),
                     "killed": c["killed"], "timeout": c["timeout"],
                     "survived": c["survived"], "broken": c["broken"],
                     "not_called": sum(t["why"].startswith("not called") for t in ii),
                     "not_perturbable": sum(t["why"].startswith(("not perturbable",
                                                                  "unpatchable", "returns"))
                                            and not t.get("partly") for t in ii)})
    return rows


def table(rows) -> str:
    head = ("| module | public functions | knocked out | variants | killed | timeout | "
            "survived | not called | not perturbable |\n"
            "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    lines = [head]
    tot = Counter()
    for r in rows:
        lines.append(f"| {r['module']} | {r['targets']} | {r['knocked_out']} | {r['variants']} | "
                     f"{r['killed']} | {r['timeout']} | {r['survived']} | {r['not_called']} | "
                     f"{r['not_perturbable']} |")
        tot.update({k: v for k, v in r.items() if k != "module"})
    lines.append(f"| **all** | {tot['targets']} | {tot['knocked_out']} | {tot['variants']} | "
                 f"{tot['killed']} | {tot['timeout']} | {tot['survived']} | {tot['not_called']} | "
                 f"{tot['not_perturbable']} |")
    return "\n".join(lines)


def run(mode: Mode, modules=None, variants=VARIANTS, baseline: bool = False,
        confirm: bool = True, timeout: float = TIMEOUT, partial: Path | None = None,
        resume: Path | None = None) -> dict:
    all_modules = reference_modules()
    modules = [full(m) for m in modules] if modules else all_modules
    if mode.quick:
        modules = modules[:1]
    files = reference_tests(baseline)
    t0 = time.monotonic()
    rec = record(files)
    say(f"  knockout: recorded {len(rec['seen'])} targets called, in {rec['seconds']} s")
    check = sanity(files)
    runs, idle = plan(modules, rec, variants, files)
    say(f"  knockout: {len(runs)} knockouts of {len({(r['module'], r['target']) for r in runs})} "
        f"functions in {len(modules)} modules")
    if resume is not None:           # the knockouts an earlier, stopped run screened
        old = {(r["module"], r["target"], r["variant"]): r
               for r in json.loads(resume.read_text())["runs"] if "screen" in r}
        for r in runs:
            o = old.get((r["module"], r["target"], r["variant"]))
            if o is not None:
                r.update({k: o[k] for k in ("screen", "status", "by", "confirm", "calls",
                                            "changed") if k in o})
        say(f"  knockout: {sum('screen' in r for r in runs)} screened already ({resume})")
    done = None
    if partial is not None:          # every result so far, in case the run is stopped
        def done():
            partial.write_text(json.dumps({"runs": runs, "idle": idle}, indent=1))
    run_all(runs, files, timeout, confirm, done)
    rows = summary(runs, idle, modules)
    print(table(rows))
    return {"rows": rows, "runs": runs, "idle": idle, "sanity": check, "files": files,
            "deselect": DESELECT,
            "recording_seconds": rec["seconds"], "seconds": round(time.monotonic() - t0),
            "modules": [short(m) for m in modules], "variants": list(variants),
            "baseline": baseline}


def run_group(mode: Mode) -> dict:
    """``python -m benchmarks knockout``: every module (``--quick``: the first); only the
    per-module rows go to docs/perf/results.json (``python -m benchmarks.knockout`` keeps
    every knockout in docs/perf/knockout.json)."""
    res = run(mode)
    return {k: res[k] for k in ("rows", "seconds", "modules", "files")}


def rerun(mode: Mode, before: dict, timeout: float = TIMEOUT, confirm: bool = True) -> dict:
    """The survivors of ``before`` again (timeouts count as killed), on the current tests
    (with tests/test_knockouts.py): the *after* numbers."""
    files = reference_tests(False)
    t0 = time.monotonic()
    rec = record(files)
    check = sanity(files)
    runs = []
    for r in before["runs"]:
        if r["status"] in ("survived", "broken"):
            key = f"{PACKAGE}.{r['module']}:{r['target']}"
            seen = rec["seen"].get(key, {"tests": []})
            runs.append({k: r[k] for k in ("module", "target", "how", "variant", "kinds")}
                        | {"files": caller_files(seen["tests"], files)})
    # the functions no test called before: their variants, if a test calls them now
    for t in before["idle"]:
        seen = rec["seen"].get(f"{PACKAGE}.{t['module']}:{t['target']}")
        if t["why"].startswith("not called") and seen:
            vs, other = variants_of(seen["kinds"])
            t["now"] = ("called; not perturbable: returns " + ", ".join(other)) if other \
                else "called"
            for v in vs:
                runs.append({k: t[k] for k in ("module", "target", "how")}
                            | {"variant": v, "kinds": sorted(seen["kinds"]),
                               "files": caller_files(seen["tests"], files), "was": "not called"})
    run_all(runs, files, timeout, confirm)
    return {"runs": runs, "sanity": check, "files": files, "seconds": round(time.monotonic() - t0)}


# -- the page --------------------------------------------------------------------------------------

# Why each knockout left alive survives: "module:target" or "module:target:variant" -> one line.
WHY: dict[str, str] = {
    "delaunay:flip_to_delaunay:last":
        "returns `(surface, log)`; the log's last element is a `FlipRecord` (not "
        "perturbable) and an empty log has none, so no call is changed (`drop` is killed).",
    "combinatorics:Triangulation.validate:skip":
        "a real gap: every reference test calls `validate()` on a valid triangulation, none "
        "on broken tables (the constructors check them first); "
        "`test_validate_raises_on_each_broken_invariant` builds broken ones with `_trusted`.",
    "planar:empty_disk_violations:last":
        "the triples' last element is the reason, a string (not perturbable), and the "
        "list is empty on every Delaunay input; `drop` is killed.",
    "planar:all_triangulations:last":
        "a list of surfaces (not perturbable): nothing to change; `drop` is killed.",
    "planar:quad_tessellation_faces:last":
        "a real gap: one test (ER-20) reads one face of one point set, not the last "
        "face's `acute`; `test_quad_tessellation_faces_are_orthogonal_kites_crossing_iff_acute` "
        "checks every face against the notes' identities and recomputed distances.",
    "rigidity:rigidity_matrix:last":
        "a real gap: the matrix was only read through its rank (30 for the icosahedron, "
        "unchanged by one entry + 1/3) and by the slow, deselected T2.10 rigidity test; "
        "`test_rigidity_matrix_rows_are_the_edge_vectors` checks every entry.",
    "surfaces:convex_hull:value":
        "a real gap: the tests read the hull's faces and orientations from the input points, "
        "never its positions; `test_convex_hull_keeps_the_given_points_as_its_vertices` "
        "kills it (checked by hand with the plugin, not in the stored after-run).",
    "sparse:negative_direction:last":
        "equivalent: the contract is *some* x with x^T A x < 0, and the tests check exactly "
        "that; the 15 results changed (last entry + 1/3) all stayed witnesses.",
}


def _why(r) -> str:
    why = (WHY.get(f"{r['module']}:{r['target']}:{r['variant']}")
           or WHY.get(f"{r['module']}:{r['target']}"))
    if r.get("changed") == 0:
        lead = (f"never switched on: the variant fits none of its {r['calls']} results "
                f"in the tests")
        return f"{lead} ({why})" if why else lead + "."
    return why or "(not looked at)"


def _spec(r) -> str:
    return f"`{r['module']}.{r['target']}` `{r['variant']}`"


def page(data: dict) -> str:
    """docs/knockout.md from docs/perf/knockout.json."""
    meta = data["meta"]
    modules = [full(m) for m in data["modules"]]
    valid = {(short(m), q) for m in modules for q, _ in targets_of(m)}
    data = {**data, "idle": [t for t in data["idle"] if (t["module"], t["target"]) in valid]}
    rows = [r for r in summary(data["runs"], data["idle"], modules) if r["targets"]]
    after = data.get("after")
    fixed = {}
    if after:
        fixed = {(r["module"], r["target"], r["variant"]): r["status"] for r in after["runs"]}
    out = [PAGE_HEAD.format(n_files=len(data["files"]), files=", ".join(
        f"`{Path(f).stem}`" for f in data["files"]), deselect=", ".join(
        f"`{d.split('::')[1]}`" for d in data.get("deselect", _FIRST_RUN_DESELECT)) or "none", timeout=int(data.get("timeout", TIMEOUT)))]
    out.append("## Commands, commit, date, load\n")
    out.append("```bash\n" + data.get("command", "python -m benchmarks.knockout") + "\n```\n")
    parts = [meta] + data.get("parts", [])[1:]
    for m in parts:
        out.append(f"* run: commit `{m['commit']}`, {m['date']} (UTC), Python {m['python']}, "
                   f"{m['cpus']} CPUs, load average (1 min) {m['load']} at the start")
    if not data.get("confirmed"):
        out.append("* the run was made with `--no-confirm` (screening only, on the files "
                   "that called each function: a test that never calls a function can fail "
                   "on its wrong version only through state shared across test files); "
                   "`python -m benchmarks.knockout --confirm` re-runs the survivors on all "
                   "the files, not done for lack of time")
    if data.get("confirmed"):
        c = data["confirmed"]
        out.append(f"* confirmation of the survivors (`--confirm`): {c['date']}, load {c['load']}")
    if after:
        m = after["meta"]
        out.append(f"* after (`--after`, with `{NEW_TESTS}`): commit `{m['commit']}`, {m['date']}, "
                   f"load {m['load']}, {after['seconds']} s")
    out.append(f"* wall time of the run: {data['seconds']} s (the recording run "
               f"{data['recording_seconds']} s of it); the machine (2 cores) was shared "
               "with other sessions.\n")
    out.append("## Results\n")
    out.append("Per module: public functions (and methods) looked at, those knocked out "
               "(some variant fits their results), the knockouts run (function x variant), "
               "their verdicts before the tests of this page, and the functions no variant "
               "could be run on (never called by a reference test; returns only objects no "
               "generic perturbation fits).\n")
    out.append(table(rows) + "\n")
    surv = [r for r in data["runs"] if r["status"] not in ("killed", "timeout")]
    slow = [r for r in data["runs"] if r["status"] == "timeout"]
    c = Counter(r["status"] for r in data["runs"])
    line = (f"Before: {len(data['runs'])} knockouts, {c['killed']} killed, {c['timeout']} "
            f"timeout, {c['survived']} survived")
    if after:
        a = Counter(r["status"] for r in after["runs"] if not r.get("was"))
        new = [r for r in after["runs"] if r.get("was")]
        line += (f".  After (`{NEW_TESTS}` added; the survivors re-run): {a['killed']} more "
                 f"killed, {a['survived']} still alive; of the functions no test called before, "
                 f"{len(new)} knockouts run now, "
                 f"{sum(r['status'] == 'killed' for r in new)} killed")
    out.append(line + ".\n")
    out.append("## Survivors\n")
    out.append("Each with why no test fails on it (after: its verdict with the new tests).\n")
    for r in sorted(surv, key=lambda r: (r["module"], r["target"], r["variant"])):
        now = fixed.get((r["module"], r["target"], r["variant"]))
        tag = f" **{now} after**" if now else ""
        out.append(f"* {_spec(r)} ({r['status']}){tag}: {_why(r)}")
    out.append("")
    out.append(f"Timeouts (counted as killed; {int(data.get('timeout', TIMEOUT))} s on files "
               "that take seconds): " + ", ".join(_spec(r) for r in slow) + ".  A wrong "
               "enclosure (or a rational taken for irrational) makes the exact sign's "
               "refinement loop: it never narrows onto the wrong value, so it never decides.\n")
    out.append("## Not knocked out\n")
    groups: dict = {}
    for t in data["idle"]:
        groups.setdefault(t["why"], []).append(t)
    for why in sorted(groups):
        ts = groups[why]
        names = ", ".join(f"`{t['module']}.{t['target']}`" + (" (its other results are)" if
                          t.get("partly") else "") + (f" ({t['now']} now)" if t.get("now")
                                                      else "") for t in ts)
        out.append(f"* **{why}** ({len(ts)}): {names}")
    out.append("")
    out.append(PAGE_TAIL)
    return "\n".join(out)


PAGE_HEAD = """# Knockout benchmark of the exact reference

Issue 44: *every public reference function has a test that can fail on a plausible wrong
version of it.*  `benchmarks/knockout.py` replaces each public function of
`ddg_oracle.reference` (every module, `exact.*` included, and the public methods and
properties of its public classes; not the exception classes of `errors.py`, nor the
members of the `typing.Protocol` interfaces `HalfedgeMesh` and `Metric`, which have no
body) by generic wrong versions of its own result, one at a time, runs the reference's
tests, and records whether some test fails (*killed*) or all pass (*survived*).  Unlike
mutation testing (docs/mutation.md: one operator changed inside a function, on six core
modules), a knockout asks whether the tests look at a function's *result* at all.

## Tool and set-up

* **Wrong versions** (benchmarks/knockout_plugin.py), decided from each call's result:
  `value` a number made wrong by its type (`bool` negated, `int` + 1, `Fraction` + 1/3,
  `float` x (1 + 2^-10) + 2^-10, a `Surd` (a lazy `CotanSum` too) + 1/3, an `Angle` or
  `AngleLength` + pi/3, an `Interval` shifted by 1/3); `last` a tuple or list with its
  last element made wrong (recursively: a number by `value`, a tuple, list or dict by
  `last`, a set by `drop`), a dict with its last key's value made wrong;
  `drop` a tuple or list without its last element, a set without one element; `skip`
  the function returns None without running its body (for functions that always return
  None).  A call whose result the variant does not fit (another type, an empty tuple, a
  perturbation that raises) returns the original result: the wrapper never crashes.
  Results of other types (surfaces, triangulations, sparse matrices, strings, ...) are
  *not perturbable* and listed below; no variant of them was run.  `drop` on a result of
  fixed shape (a pair unpacked by its caller) is caught by any caller that unpacks it:
  a weak variant, counted as it comes.  Each knockout also counts the calls of the
  function and the results it changed: a survivor that changed none was never switched
  on (its variant fits none of the results the tests produce).
* **Switching one on**: a fresh child `python -m pytest -p benchmarks.knockout_plugin`
  per knockout, the environment naming it (`DDG_KNOCKOUT=MODULE:QUALNAME:VARIANT`); at
  `pytest_configure`, before any test module is imported, the function object itself gets
  a wrapper's `__code__` (`(*args, **kwargs)`, calling a copy of the original made with
  `types.FunctionType(code, globals, name, defaults, closure)` and perturbing), so every
  `from .module import name` sees it; methods, static and class methods, properties and
  `cached_property` through their functions, `lru_cache` functions through `__wrapped__`
  and `cache_clear()`.  Functions with free variables get a wrapper with the same ones.
* **Which variants**: a recording run first (all the test files below, every function
  wrapped by a recorder that leaves results alone) gives, per function, the kinds of
  result it returned and the test files that called it.
* **Which tests**: the reference's test files, the {n_files} in-process test files that
  import `ddg_oracle.reference` and exercise it: {files}.  Left out: the CLI, driver
  (C++, JS, misbehaving), peer-oracle, HTML report, mesh-file, packaging, survey and
  subprocess tests, and the property suites of the oracle.  Deselected as slow (minutes
  alone): {deselect}.  Each knockout is screened with `-x` on the files that called the
  function (most calls first); a survivor is run again on all these files (the verdict).
* Every child: `nice -n 10`, one at a time, `-q -p no:cacheprovider
  --hypothesis-seed=0`, `DDG_HYPOTHESIS_DATABASE=none`, `PYTHONHASHSEED=0`, `CI` unset
  (the default profile), a timeout of {timeout} s (counted as killed, listed apart).
  Before the loop a sanity check: one knockout that must be killed
  (`Triangulation.euler_characteristic` + 1 on `tests/test_combinatorics.py`) is, and the
  same file passes with none; the recording run must pass too.
"""

PAGE_TAIL = """## Tests added

`tests/test_knockouts.py` (in the normal suite; under a second).  Each assertion compares
with something computed another way, never with a value copied from the code under test:

* `test_validate_raises_on_each_broken_invariant`: `Triangulation.validate` on tables
  built unchecked (`Triangulation._trusted`, from a disk's pickled defining data) with one
  invariant broken at a time (a gluing's reversed flag flipped, a halfedge in two edges,
  an edge left out) and on a bowtie (a vertex in two fans): each raises; the valid data
  passes.  Kills `validate` `skip`.
* `test_root_sum_at_least_against_surds`: `geodesics.root_sum_at_least` (no reference
  test called it; `tests/test_statements.py` checks two cases through the oracle's
  statements) against the exact `Surd` comparison, equality cases included.
* `test_lifted_hull_facets_are_the_empty_circle_triangles`: `planar.is_lifted_hull_facet`
  (R4.2; never called) against the empty-circumcircle test by `in_circle`, on random
  rational points and on cocircular ones.
* `test_sparse_diagonal_holds_its_values_on_the_diagonal` and
  `test_from_lengths_squares_each_edge_length` (`SparseMatrix.diagonal`,
  `PiecewiseFlatSurface.from_lengths`: never called; their results are not perturbable,
  so they are tested but not measured here).
* `test_quad_tessellation_faces_are_orthogonal_kites_crossing_iff_acute`: every face of
  R4.1's quad tessellation on random rational points: the Voronoi segment orthogonal to
  its edge and equidistant from both ends (recomputed), `crossing == acute`, both values
  seen.  Kills `quad_tessellation_faces` `last`.
* `test_rigidity_matrix_rows_are_the_edge_vectors`: every entry of the rigidity matrix of
  a jittered octahedron against `p_i - p_j`.  Kills `rigidity_matrix` `last`.

## Notes

* `reference/` did not change between the run and the after run (`git log -- reference/`:
  last commit `7de75da`, before the run started; HEAD moved meanwhile through other
  people's commits that do not touch it).  Two earlier attempts were discarded: the
  reference changed under the first (`rounded_root_sum` moved from `exact.rationals` to
  `exact.surds` mid-run), and it used a 300 s timeout.
* Killed, but first by something indirect (with `-x` the first failure ends the run, so
  other tests may catch them too): `exact.intervals.top_bit` and `terms_top_bit`
  (`value`) by their module's doctests, after 19 and 40 s; `Unfolding.convexity` `drop`
  and `shared_denominator` `drop` by a test module failing to import (it computes with
  them at import time).
"""


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m benchmarks.knockout", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("modules", nargs="*", metavar="MODULE",
                   help="reference modules (cotangents, exact.surds, ...; default: all)")
    p.add_argument("--variants", nargs="+", choices=VARIANTS, default=list(VARIANTS))
    p.add_argument("--no-write", action="store_true", help=f"print only; leave {JSON.name} alone")
    p.add_argument("--quick", action="store_true", help="the first module only")
    p.add_argument("--baseline", action="store_true",
                   help=f"leave {NEW_TESTS} out (the tests as they were before it)")
    p.add_argument("--no-confirm", action="store_true",
                   help="do not re-run survivors on all the reference test files")
    p.add_argument("--after", action="store_true",
                   help="re-run the survivors of the stored run with the current tests "
                   "(stored as its 'after')")
    p.add_argument("--confirm", action="store_true",
                   help="confirm the unconfirmed survivors of the stored run (after a run "
                   "with --no-confirm) on all the reference test files")
    p.add_argument("--partial", type=Path, default=None,
                   help="write every result so far to this file after each knockout")
    p.add_argument("--page", action="store_true",
                   help=f"only write {DOC.relative_to(ROOT)} from {JSON.relative_to(ROOT)}")
    p.add_argument("--resume", type=Path, default=None,
                   help="take the knockouts already screened from a --partial file")
    p.add_argument("--timeout", type=float, default=TIMEOUT)
    args = p.parse_args(argv)
    if args.page:
        DOC.write_text(page(json.loads(JSON.read_text())))
        say(f"  wrote {DOC.relative_to(ROOT)}")
        return 0
    mode = Mode.of(args.quick)
    meta = machine()
    stored = json.loads(JSON.read_text()) if JSON.exists() else {}
    if args.confirm:
        runs = stored["runs"]
        files = stored["files"]

        def save():
            if not args.no_write:
                _save(stored, quiet=True)
        run_all(runs, files, args.timeout, True, save)
        modules = [full(m) for m in stored["modules"]]
        stored["rows"] = summary(runs, stored["idle"], modules)
        stored["confirmed"] = {**machine(), "seconds": None}
        print(table(stored["rows"]))
        save()
        return 0
    if args.after:
        res = rerun(mode, stored, args.timeout, not args.no_confirm)
        res["meta"] = meta
        say(f"  knockout after: {Counter(r['status'] for r in res['runs'])}")
        if not args.no_write:
            stored["after"] = res
            _save(stored)
        return 0
    res = run(mode, args.modules, args.variants, args.baseline, not args.no_confirm,
              args.timeout, args.partial, args.resume)
    res["meta"] = meta
    res["timeout"] = args.timeout
    res["command"] = " ".join(["python -m benchmarks.knockout",
                               *(argv if argv is not None else sys.argv[1:])])
    if not args.no_write:
        if stored.get("runs") and set(args.modules or []) and not args.quick:
            # a run of some modules: merge into the stored run of the others
            keep = [r for r in stored["runs"] if r["module"] not in res["modules"]]
            res["runs"] = keep + res["runs"]
            res["idle"] = [t for t in stored["idle"] if t["module"] not in res["modules"]] \
                + res["idle"]
            res["rows"] = [r for r in stored["rows"] if r["module"] not in res["modules"]] \
                + res["rows"]
            res["modules"] = [r["module"] for r in res["rows"]]
            res.setdefault("parts", stored.get("parts", [stored.get("meta")]))
            res["parts"].append(meta)
        if args.resume is not None and stored.get("after"):
            res["after"] = stored["after"]      # the survivors' re-run still stands
        _save(res)
    return 0


def _save(data: dict, quiet: bool = False) -> None:
    JSON.parent.mkdir(parents=True, exist_ok=True)
    JSON.write_text(json.dumps(data, indent=1) + "\n")
    if not quiet:
        say(f"  wrote {JSON.relative_to(ROOT)}")


if __name__ == "__main__":
    sys.exit(main())
