"""``ddg-oracle``: check implementations against the exact reference; print the catalog.

Exit codes: 0 all good, 1 a property failed (or the table is not true),
2 bad usage or bad input (one line on stderr, no traceback).
"""

from __future__ import annotations

import argparse
import sys
import time

from reference.errors import InputError


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="ddg-oracle", description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)

    c = sub.add_parser("check", help="run every property against implementations")
    c.add_argument("--impl", action="append", metavar="NAME|module:object",
                   help="implementation to check (repeatable; default: every installed one)")
    c.add_argument("--profile", default="default", help="Hypothesis profile: default, ci, thorough")
    c.add_argument("--seed", type=int, default=None, help="Hypothesis seed")
    c.add_argument("--only", action="append", metavar="ID", help="only these catalog IDs")
    c.add_argument("--timeout", type=float, default=60.0,
                   help="seconds per call of a checked implementation before it is killed "
                        "and reported as hanging (default 60)")

    t = sub.add_parser("theorems", help="print the traceability table")
    t.add_argument("--check", action="store_true",
                   help="exit 1 unless every named function, property and test exists "
                        "and every row of a claimed chapter is verified")

    args = parser.parse_args(argv)
    try:
        if args.command == "check":
            return _check(args)
        return _theorems(args)
    except (InputError, ValueError) as e:
        print(f"ddg-oracle: error: {e}", file=sys.stderr)
        return 2


def _theorems(args) -> int:
    from properties import traceability
    claimed, entries = traceability.load()
    width = max(len(e.id) for e in entries)
    print(f"{'ID'.ljust(width)}  {'status':9}  reference / property")
    for e in entries:
        ref = ", ".join(r.split(":")[-1] for r in e.reference) or "-"
        prop = ", ".join(p.split(":")[-1] for p in e.property) or "-"
        print(f"{e.id.ljust(width)}  {e.status:9}  {ref} / {prop}")
    counts = {s: sum(e.status == s for e in entries) for s in traceability.STATUSES}
    print(f"\n{len(entries)} rows: " + ", ".join(f"{n} {s}" for s, n in counts.items())
          + f"; claimed chapters: {', '.join(map(str, claimed)) or 'none'}")
    if not args.check:
        return 0
    problems = traceability.check()
    for p in problems:
        print(f"NOT TRUE: {p}", file=sys.stderr)
    if problems:
        return 1
    print("traceability table: true")
    return 0


def _check(args) -> int:
    from oracles.implementations import available, load_implementation
    from properties.protocol import implementation_name
    from properties.registry import all_properties
    from properties.runner import describe, run_properties

    from oracles.isolation import Isolated
    specs = args.impl or available()
    # The exact reference runs in this process; everything else in a worker
    # process, so a segfault or a hang becomes a reported result.
    impls = [load_implementation(s) if s == "reference" else Isolated(s, timeout=args.timeout)
             for s in specs]
    only = set(args.only) if args.only else None
    props = [p for p in all_properties() if only is None or p.id in only]
    if only:
        unknown = only - {p.id for p in props}
        if unknown:
            raise ValueError(f"no property for catalog ID(s) {', '.join(sorted(unknown))}")
    total = len(props) * len(impls)
    done = 0
    t0 = time.perf_counter()
    results = []

    def progress(r):
        nonlocal done
        done += 1
        bar = "#" * (20 * done // total)
        print(f"\r[{bar:<20}] {done}/{total} {r.implementation}: {r.property_id:<12}",
              end="", file=sys.stderr, flush=True)

    try:
        for impl in impls:
            results += run_properties(impl, args.profile, only, args.seed, on_result=progress)
    finally:
        for impl in impls:
            if isinstance(impl, Isolated):
                impl.close()
    print(file=sys.stderr)

    names = [implementation_name(i) for i in impls]
    width = max(len(p.id) + len(p.name) + 5 for p in props)
    colw = max(28, *(len(n) for n in names))
    print("property".ljust(width) + "".join(n.ljust(colw) for n in names))
    cell = {(r.property_id, r.implementation): r for r in results}
    for p in props:
        row = f"{p.id} ({p.name})".ljust(width)
        row += "".join(cell[(p.id, n)].summary().ljust(colw) for n in names)
        print(row)
    bad = [r for r in results if not r.ok]
    for r in bad:
        print("\n" + describe(r))
    print(f"\n{len(results)} checks in {time.perf_counter() - t0:.1f} s: "
          f"{sum(r.ok for r in results)} ok, {len(bad)} not ok (profile {args.profile})")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
