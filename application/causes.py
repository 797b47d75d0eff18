"""Root causes of failures: what a failing result blames and why (issue 42's diagnosis,
issue 40's grouping), shared by the terminal report (:mod:`ddg_oracle.application.report`), the HTML
page (:mod:`ddg_oracle.application.html_report`) and the pytest plugin.

* :func:`element_ids`: the mesh element a failure names (a vertex, an edge, a face corner);
* :func:`blamed_methods`, :func:`wrong_answer`: the protocol methods a failure blames and
  their wrong answer on the counterexample;
* :func:`convention_hint`: the convention of the vocabulary under which the answer agrees
  (and no other answer of the example breaks); :func:`group_hint`: a root cause's, only
  when every diagnosed member shares it;
* :func:`root_causes`: failures grouped by implementation and blamed methods, crashes by
  message, smallest counterexample first.
"""

from __future__ import annotations

import numbers
import re
from dataclasses import dataclass


_PATTERNS = [
    (re.compile(r"face (\d+), corner (\d+)"), lambda m: {"face": int(m[1]), "corner": int(m[2])}),
    (re.compile(r"\(now (\d+)\)"), lambda m: {"vertex": int(m[1])}),
    (re.compile(r"edge \((\d+), (\d+)\)"), lambda m: {"edge": [int(m[1]), int(m[2])]}),
    (re.compile(r"\bvertex (\d+)"), lambda m: {"vertex": int(m[1])}),
    (re.compile(r"\brow (\d+)"), lambda m: {"vertex": int(m[1])}),
    (re.compile(r"\bface (\d+)"), lambda m: {"face": int(m[1])}),
    (re.compile(r"^\((\d+), (\d+)\)$"), lambda m: {"edge": [int(m[1]), int(m[2])]}),
]


def element_ids(element) -> dict | None:
    """The mesh element a failure names, as {"vertex": i}, {"edge": [i, j]}, {"face": f} or
    {"face": f, "corner": c}; None if it names none.

    >>> element_ids("face 3, corner 1"), element_ids((2, 5)), element_ids((4, 4))
    ({'face': 3, 'corner': 1}, {'edge': [2, 5]}, {'vertex': 4})
    >>> element_ids("vertex 0 (now 7)"), element_ids("boundary vertex 2"), element_ids("chi = 2")
    ({'vertex': 7}, {'vertex': 2}, None)
    """
    if element is None or isinstance(element, bool):
        return None
    if isinstance(element, numbers.Integral):
        return {"vertex": int(element)}
    if isinstance(element, (tuple, list)) and len(element) == 2 and \
            all(isinstance(v, numbers.Integral) for v in element):
        i, j = int(element[0]), int(element[1])
        return {"vertex": i} if i == j else {"edge": [i, j]}
    text = str(element)
    for pattern, build in _PATTERNS:
        m = pattern.search(text)
        if m:
            return build(m)
    return None


@dataclass
class Cause:
    """Failures of one implementation that one protocol method explains (a root cause), or
    crashes of one implementation with one message: ``members`` are result indices, the
    smallest counterexample first."""

    implementation: str
    methods: tuple                # the protocol methods blamed (empty: not known)
    members: list
    where: str | None = None      # the wrong answer on the smallest counterexample
    message: str | None = None    # a crash's message

    @property
    def first(self) -> int:
        return self.members[0]


def counterexample_faces(r) -> int:
    """The number of faces of a result's counterexample (very large when it has none)."""
    return len(r.mesh[1]) if r.mesh is not None else 1 << 30


def blamed_methods(r) -> tuple:
    """The protocol methods a failing result blames: those whose answer on the
    counterexample differs from the exact one (its diagnosis); else the method its message
    names ("cotan_laplacian has non-finite entries", "solve_dirichlet: ..."); else the
    methods its property calls."""
    from ..protocol.methods import METHODS
    from ..properties.registry import PROPERTIES
    wrong = [d["quantity"] for d in (r.diagnosis or []) if d["status"] in ("DIFFERS", "crashed")]
    if wrong:
        return tuple(wrong)
    text = r.failure.message if r.failure is not None else (r.error or "")
    named = [m for m in METHODS if re.match(rf"{m}\b", text)]
    if named:
        return (named[0],)
    p = PROPERTIES.get(r.property_id)
    order = list(METHODS)
    return tuple(sorted(p.methods, key=order.index)) if p is not None else ()


def _where(r, methods) -> str | None:
    """The first wrong answer among ``methods`` in ``r``'s diagnosis, as a line, or None."""
    for d in r.diagnosis or []:
        if d["quantity"] in methods and d["status"] == "DIFFERS":
            worst = d.get("worst")
            units = "" if worst is None else (" (inf x the bound)" if worst == float("inf")
                                              else f" ({worst:.3g} x the bound)")
            at = f" at {d['where']}" if d["where"] else ""
            return (f"{d['quantity']}{at}: expected {d['expected']}, observed "
                    f"{d['observed']}{units}" + (f" [{d['note']}]" if d.get("note") else ""))
    return None


def convention_hint(r) -> str | None:
    """When a failing result's wrong answer agrees with the exact one under a convention
    of the vocabulary (``properties.conventions``; the diagnosis tried each), what to
    declare: "cotan_laplacian agrees under laplacian=negative (the matrix is -L ...):
    declare conventions = {'laplacian': 'negative'}"; else None."""
    from ..properties.conventions import declaration_text, parse
    rows = r.diagnosis or []
    for d in rows:
        names = d.get("explained_by") or []
        if d["status"] == "DIFFERS" and names:
            key, _, value = names[0].partition("=")
            try:
                value = float(value) if key == "regularization" else value
                c = parse({key: value})
            except ValueError:
                continue
            if any(e["status"] == "agrees" and c[0].applies(e["quantity"]) for e in rows):
                # a method the convention changes agrees as it is: declaring it would make
                # that one wrong (area_gradient doubled beside a right Laplacian)
                return None
            return (f"{d['quantity']} agrees with the exact answer under {names[0]} "
                    f"({c[0].about}): if that is your convention, declare "
                    f"{declaration_text(c)}")
    return None


def group_hint(results, members) -> str | None:
    """The convention hint of a root cause's results: the one every member with a
    differing, diagnosed answer shares; None when one of them has another or none (a real
    bug that agrees with a convention on one small example, as doubling the interior
    weights only does on a closed tetrahedron, must not be called a convention)."""
    hints, unexplained = set(), False
    for k in members:
        r = results[k]
        differing = [d for d in (r.diagnosis or []) if d["status"] == "DIFFERS"]
        if not differing:
            continue
        h = convention_hint(r)
        if h is None:
            unexplained = True
        else:
            hints.add(h.split(": if that is", 1)[0].split(" under ", 1)[1])
    if unexplained or len(hints) != 1:
        return None
    return next(h for k in members if (h := convention_hint(results[k])))


def wrong_answer(r) -> str | None:
    """The wrong answer a failing result's diagnosis shows for the methods it blames
    ("cotan_laplacian at entry (0, 1): expected -0.5, observed 0.5 (...)"), or None."""
    return _where(r, blamed_methods(r)) if r.diagnosis else None


def _crash_message(r) -> str:
    # the first line, numbers in the text (addresses, sizes, seconds) as one form
    first = (r.error or "").splitlines()[0] if r.error else ""
    return re.sub(r"\d+(\.\d+)?(e[-+]?\d+)?", "N", first)


def root_causes(results) -> tuple[list, list]:
    """(failure causes, crash groups): FAILED results grouped by implementation and the
    protocol methods they blame (:func:`blamed_methods`), crashes by implementation and
    message; each group's members sorted by counterexample size, largest groups first."""
    from ..properties.runner import CRASHED, FAILED
    groups: dict = {}
    crashes: dict = {}
    for k, r in enumerate(results):
        if r.status == FAILED:
            groups.setdefault((r.implementation, blamed_methods(r)), []).append(k)
        elif r.status == CRASHED:
            crashes.setdefault((r.implementation, _crash_message(r)), []).append(k)
    causes = []
    for (impl, methods), members in groups.items():
        members.sort(key=lambda k: (counterexample_faces(results[k]), k))
        where = next((w for k in members if (w := _where(results[k], methods))), None)
        causes.append(Cause(impl, methods, members, where=where))
    crashed = []
    for (impl, message), members in crashes.items():
        members.sort(key=lambda k: (counterexample_faces(results[k]), k))
        crashed.append(Cause(impl, (), members, message=results[members[0]].error))
    by_size = lambda c: (-len(c.members), c.first)          # noqa: E731
    return sorted(causes, key=by_size), sorted(crashed, key=by_size)
