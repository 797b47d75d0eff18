"""Simplicial minimal surfaces (II), section 4.5 of the notes: D4.9, R4.10, A4.23, exact."""

from fractions import Fraction

from hypothesis import given, settings

from ddg_oracle.reference import surfaces
from ddg_oracle.reference.delaunay import is_delaunay
from ddg_oracle.reference.dirichlet import neighbour_convex_combination
from ddg_oracle.reference.laplacian import cotan_laplacian
from ddg_oracle.reference.minimal import (area_decrease_certificate, area_enclosure,
                               delaunay_minimal_surface_step, delaunay_neighbour_hull,
                               figure_3_7_star, is_minimal_narrow, is_minimal_wide,
                               minimal_surface_step)
from ddg_oracle.reference.polyhedral import PolyhedralSurface

from tests.test_dirichlet import _small_surfaces


def _flat_non_delaunay():
    """A flat kite fan around vertex 0: the edge 0-1 sees two angles of about 108 degrees."""
    return PolyhedralSurface.from_arrays(
        [(0, 0, 0), (3, 0, 0), (1, 1, 0), (-3, 0, 0), (1, -1, 0)],
        [(0, 1, 2), (0, 2, 3), (0, 3, 4), (0, 4, 1)])


def test_D4_9_planar_meshes_are_minimal_wide_and_narrow_iff_delaunay():
    grid = surfaces.grid(3, 2)                           # squares: Delaunay (cocircular)
    assert is_delaunay(grid) and is_minimal_narrow(grid) and is_minimal_wide(grid)
    s = _flat_non_delaunay()
    assert not is_delaunay(s)
    assert is_minimal_wide(s)                            # linear precision of the Delaunay operator
    assert not is_minimal_narrow(s)
    lifted = s.with_positions([(x, y, Fraction(1) if v == 0 else 0)
                               for v, (x, y, _) in enumerate(s.positions)])
    assert not is_minimal_wide(lifted) and not is_minimal_narrow(lifted)


def test_R4_10_figure_3_7_star_a_step_of_A4_23_respects_the_maximum_principle():
    s, cot_step, outside = figure_3_7_star()
    assert outside                                       # A3.6 leaves the convex hull (P3.10)
    assert not is_minimal_wide(s)
    delaunay, new = delaunay_minimal_surface_step(s)
    assert is_delaunay(delaunay)
    # vertex 0 is harmonic for the new operator: a convex combination of its Delaunay neighbours
    lam = neighbour_convex_combination(cotan_laplacian(delaunay), 0)
    assert all(w >= 0 for w in lam.values()) and sum(lam.values()) == 1
    for k in range(3):
        assert sum((w * new[j][k] for j, w in lam.items()), Fraction(0)) == new[0][k]
    # the spike (vertex 1) is no Delaunay neighbour of 0 any more: its edge was flipped away
    assert 1 not in {j for j, w in lam.items() if w}
    assert min(p[2] for j, p in enumerate(new) if j in lam) <= new[0][2]
    cert = area_decrease_certificate(s, new, domain=delaunay)
    assert cert.holds and cert.strict
    lo, hi = area_enclosure(delaunay.triangulation, new, bits=40)
    assert hi < cert.area_before.interval(64)[0]         # the new area is certainly smaller


def test_R4_10_narrow_sense_vertex_in_hull_of_delaunay_neighbours():
    # a symmetric saddle star: harmonic by symmetry, its four triangles are Delaunay
    s = PolyhedralSurface.from_arrays(
        [(0, 0, 0), (2, 0, 1), (0, 2, -1), (-2, 0, 1), (0, -2, -1)],
        [(0, 1, 2), (0, 2, 3), (0, 3, 4), (0, 4, 1)])
    assert is_minimal_narrow(s) and is_minimal_wide(s)
    lam = delaunay_neighbour_hull(s, 0)
    assert set(lam) == {1, 2, 3, 4} and all(w > 0 for w in lam.values())
    assert sum(lam.values()) == 1
    assert all(sum((w * s.positions[j][k] for j, w in lam.items()), Fraction(0)) == 0
               for k in range(3))


@settings(max_examples=10, deadline=None)
@given(_small_surfaces())
def test_A4_23_one_step_does_not_increase_the_area(s):
    delaunay, new = delaunay_minimal_surface_step(s)
    assert is_delaunay(delaunay)
    t = delaunay.triangulation
    L = cotan_laplacian(delaunay)
    for i in range(t.n_vertices):
        if t.is_boundary_vertex(i):
            assert tuple(new[i]) == tuple(s.positions[i])
        else:
            assert all(sum((v * new[j][k] for j, v in L.row(i).items()), Fraction(0)) == 0
                       for k in range(3))
    cert = area_decrease_certificate(s, new, domain=delaunay)
    assert cert.holds
    lo, _ = area_enclosure(t, new, bits=40)
    assert lo <= cert.energy_after[1] <= cert.area_before.interval(64)[1]
    if is_delaunay(s):                                   # no flip: the same step as A3.6
        assert new == minimal_surface_step(s)


def test_A4_23_without_change_of_combinatorics_is_A3_6_on_delaunay_input():
    s = PolyhedralSurface.from_arrays(
        [(0, 0, 2), (2, 0, 0), (1, 2, 1), (-1, 2, 0), (-2, 0, 1), (-1, -2, 0), (1, -2, 1)],
        [(0, 1 + t, 1 + (t + 1) % 6) for t in range(6)])
    delaunay, new = delaunay_minimal_surface_step(s)
    assert is_delaunay(s) and delaunay.triangulation.faces == s.triangulation.faces
    assert new == minimal_surface_step(s)
