"""Chapter 1 properties: Euler characteristic and the classification of surfaces.

Each property takes an implementation (see :mod:`ddg_oracle.protocol.methods`) and an
example drawn from its strategy.  The truth comes from how the example was
built (genus, crosscaps, holes), never from the implementation under test.
"""

from __future__ import annotations

from collections import Counter

from hypothesis import strategies as st

from ..reference.combinatorics import connected_sum

from ..protocol.methods import capabilities
from .registry import PropertyFailure, prop, quantity
from .strategies import (Example, annuli, apply_moves, closed_surfaces, extend_positions,
                         mobius_strips, named_surfaces, orientation_traps, surface_moves,
                         triangulated_surfaces)


def _call(impl, method: str, case: Example):
    V, F = case.arrays()
    return getattr(impl, method)(V, F)


def _mesh(case: Example):
    return case.mesh                    # what the implementation received, isolated vertices too


@prop("D1.6", "euler_characteristic(V, F) equals chi = 2 - 2g - k (2 - h - k) of the surface built "
      "(additive over components; a vertex used by no face counts 1)",
      needs={"euler_characteristic"}, on_mesh=(),
      strategy=lambda: triangulated_surfaces(reversed=True, components=2, isolated=2))
def euler_characteristic_of_known_surfaces(impl, case: Example):
    chi = int(_call(impl, "euler_characteristic", case))
    if chi != case.expected.euler_characteristic:
        raise PropertyFailure("D1.6", impl, "wrong Euler characteristic", mesh=_mesh(case),
                              expected=case.expected.euler_characteristic, observed=chi)


@prop("R1.5", "chi is unchanged by edge flips, edge splits and 1-to-4 subdivision",
      needs={"euler_characteristic"},
      on_mesh=None,
      strategy=lambda: st.tuples(triangulated_surfaces(moves=False, reversed=True, components=1,
                                                       isolated=2), surface_moves()))
def euler_characteristic_is_invariant(impl, example):
    case, moves = example
    t = apply_moves(case.triangulation, moves)
    refined = Example.of_triangulation(t, extend_positions(t, case.positions), case.expected,
                                       case.recipe + f" then {moves}").with_data(
        isolated=case.isolated)
    before = int(_call(impl, "euler_characteristic", case))
    after = int(_call(impl, "euler_characteristic", refined))
    if before != after:
        raise PropertyFailure("R1.5", impl, f"chi changed under {moves}", mesh=_mesh(refined),
                              expected=before, observed=after)


@prop("X1.4", "disk 1, sphere 2, torus 0, double torus -2 (and annulus 0, Möbius strip 0)",
      needs={"euler_characteristic"}, on_mesh=None, strategy=named_surfaces)
def euler_characteristic_of_named_surfaces(impl, case: Example):
    chi = int(_call(impl, "euler_characteristic", case))
    if chi != case.expected.euler_characteristic:
        raise PropertyFailure("X1.4", impl, f"wrong Euler characteristic of the {case.recipe}",
                              mesh=_mesh(case), expected=case.expected.euler_characteristic,
                              observed=chi)


@prop("CS", "chi(M # N) = chi(M) + chi(N) - 2 and chi(M minus a disk) = chi(M) - 1",
      needs={"euler_characteristic"},
      on_mesh=None,
      strategy=lambda: st.tuples(closed_surfaces(max_genus=2, reversed=True),
                                 closed_surfaces(max_genus=2), st.integers(0, 1 << 16)))
def connected_sum_lowers_chi_by_two(impl, example):
    a, b, where = example
    s = a.triangulation
    ab = connected_sum(s, b.triangulation)
    summed = Example.of_triangulation(ab, extend_positions(ab, a.positions), a.expected, f"({a.recipe}) # ({b.recipe})")
    ca, cb, cab = (int(_call(impl, "euler_characteristic", c)) for c in (a, b, summed))
    if cab != ca + cb - 2:
        raise PropertyFailure("CS", impl, "chi(M # N) != chi(M) + chi(N) - 2", mesh=_mesh(summed),
                              expected=ca + cb - 2, observed=cab)
    f = where % s.n_faces
    holed_t = s.remove_face(f)
    holed = Example.of_triangulation(holed_t, a.positions, a.expected, a.recipe + f" minus face {f}")
    ch = int(_call(impl, "euler_characteristic", holed))
    if ch != ca - 1:
        raise PropertyFailure("CS", impl, f"chi(M minus face {f}) != chi(M) - 1",
                              mesh=_mesh(holed), expected=ca - 1, observed=ch)


@prop("T1.1 / C1.2", "a closed surface's orientability and genus match how it was built: "
      "g handles (orientable) or h crosscaps (non-orientable); a union of surfaces is "
      "orientable iff each is; a vertex used by no face changes neither (an implementation "
      "without genus: its orientability alone)",
      needs={"is_orientable"}, also={"genus"},
      on_mesh=("closed", "connected"),
      strategy=lambda: st.one_of(closed_surfaces(max_genus=3, reversed=True, components=1,
                                                 isolated=1), orientation_traps()))
def classification_of_closed_surfaces(impl, case: Example):
    orientable = bool(_call(impl, "is_orientable", case))
    if orientable != case.expected.orientable:
        raise PropertyFailure("T1.1 / C1.2", impl, "wrong orientability", mesh=_mesh(case),
                              expected=case.expected.orientable, observed=orientable)
    if case.expected.genus is None or "genus" not in capabilities(impl):
        return                          # several components: no one genus to ask for
    g = int(_call(impl, "genus", case))
    if g != case.expected.genus:
        what = "genus" if orientable else "number of crosscaps (the genus of a non-orientable surface)"
        raise PropertyFailure("T1.1 / C1.2", impl, f"wrong {what}", mesh=_mesh(case),
                              expected=case.expected.genus, observed=g)


@prop("R1.6", "with k boundary loops, orientable: chi = 2 - 2g - k, k and g as built (and its "
      "non-orientable twin chi = 2 - h - k, h crosscaps); the loops run along the boundary "
      "edges, each once, on every component (an implementation without genus: g as built)",
      needs={"euler_characteristic", "boundary_loops"}, also={"genus"},
      on_mesh=("orientable", "connected"),
      strategy=lambda: st.one_of(mobius_strips(), annuli(),
                                 triangulated_surfaces(max_holes=3, reversed=True, isolated=1,
                                                       components=2)))
def boundary_loops_and_genus(impl, case: Example):
    loops = _call(impl, "boundary_loops", case)
    k = len(loops)
    if k != case.expected.boundary_components:
        raise PropertyFailure("R1.6", impl, "wrong number of boundary loops", mesh=_mesh(case),
                              expected=case.expected.boundary_components, observed=k)
    # each loop's consecutive pairs (the last to the first): every boundary edge once and
    # nothing else (a set of them let a loop traced past its start, or twice, pass)
    walked = Counter(tuple(sorted(e)) for loop in loops
                     for e in zip(loop, list(loop[1:]) + list(loop[:1])))
    t, at = case.triangulation, case.layout            # surface vertex -> array index
    truth = {tuple(sorted(at[v] for v in t.edge_vertices(e)))
             for e in range(t.n_edges) if t.is_boundary_edge(e)}
    if set(walked) != truth:
        raise PropertyFailure("R1.6", impl, "boundary loops do not run along the boundary edges",
                              mesh=_mesh(case), expected=sorted(truth), observed=sorted(walked))
    again = sorted(e for e, n in walked.items() if n > 1)
    if again:
        raise PropertyFailure("R1.6", impl, f"a boundary loop runs along edge {again[0]} "
                              f"{walked[again[0]]} times: each loop is a simple cycle, every "
                              "boundary edge once", mesh=_mesh(case), element=f"edge {again[0]}",
                              expected=len(truth), observed=sum(len(x) for x in loops))
    if case.expected.genus is None:
        return      # several components (their loops checked above): no one genus or chi formula
    # chi counts a vertex used by no face as a point (D1.6); the surface's is without it
    chi = int(_call(impl, "euler_characteristic", case)) - len(case.isolated or ())
    # the genus as built when the implementation has none: its loops and chi are still
    # checked (Lagrange's boundary_loops bug, F-lagrange-1, was out of reach otherwise)
    g = int(_call(impl, "genus", case)) if "genus" in capabilities(impl) else case.expected.genus
    handles = 2 if case.expected.orientable else 1      # a handle counts 2, a crosscap 1
    if g != case.expected.genus:
        what = "genus" if handles == 2 else "number of crosscaps (the genus of a non-orientable surface)"
        raise PropertyFailure("R1.6", impl, f"wrong {what}: chi = {chi} and k = {k} give "
                              f"{(2 - chi - k) // handles}", mesh=_mesh(case),
                              expected=case.expected.genus, observed=g)
    if chi != 2 - handles * g - k:
        formula = "2 - 2g - k" if handles == 2 else "2 - h - k"
        raise PropertyFailure("R1.6", impl, f"chi != {formula}", mesh=_mesh(case),
                              expected=(case.expected.euler_characteristic, case.expected.genus),
                              observed=(chi, g))


# --- how the topology methods' answers compare on a given mesh (compare, vectors) -------------

quantity("euler_characteristic")
quantity("boundary_loops")
quantity("is_orientable")
quantity("genus", requires=("connected",))
