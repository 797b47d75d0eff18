"""Rational-metric strategies: flat tori, polycube surfaces, random intrinsic flips."""

from fractions import Fraction

import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from ddg_oracle.properties.metrics import flat_tori, polycube, polycube_surfaces, randomly_flipped
from ddg_oracle.reference.delaunay import flip_to_delaunay, harmonic_index, is_delaunay, laplace_beltrami
from ddg_oracle.reference.exact import Surd
from ddg_oracle.reference.laplacian import cotan_weights


def _rational(x):
    return isinstance(x, Fraction) or (isinstance(x, Surd) and x.is_rational())


@settings(max_examples=20, deadline=None)
@given(polycube_surfaces(max_genus=3))
def test_polycubes_have_the_genus_they_are_built_with_and_rational_metrics(s):
    t = s.triangulation
    c = t.classify()
    assert c.orientable and c.boundary_components == 0
    assert t.euler_characteristic() == 2 - 2 * c.genus
    m = s.metric()
    assert all(a == Fraction(1, 2) for a in m.areas)               # right isosceles halves
    assert all(x in (1, 2) for x in m.squared_lengths)
    assert is_delaunay(m)                                           # every square is cocircular
    assert set(cotan_weights(m).values()) <= {0, Fraction(1, 2), 1}      # cot 0 or 1 per corner


def test_polycube_genus_sequence():
    assert [polycube(g).triangulation.classify().genus for g in range(4)] == [0, 1, 2, 3]


@settings(max_examples=15, deadline=None)
@given(randomly_flipped(flat_tori(), max_flips=30))
def test_flipped_flat_tori_stay_rational_and_flat(m):
    assert all(_rational(x) for x in m.squared_lengths) and all(_rational(a) for a in m.areas)
    d, log = flip_to_delaunay(m)
    assert is_delaunay(d) and all(_rational(x) for x in d.squared_lengths)
    assert all(r.h_after < r.h_before for r in log)                 # C4.19 on every flip
    assert _rational(harmonic_index(d))
    L = laplace_beltrami(m)
    n = m.triangulation.n_vertices
    assert all(_rational(L[i, j]) for i in range(n) for j in range(n))


@settings(max_examples=8, deadline=None)
@given(randomly_flipped(polycube_surfaces(max_genus=1).map(lambda s: s.metric()), max_flips=30))
def test_flipped_polycubes_return_to_the_same_operator(m):
    d, _ = flip_to_delaunay(m)
    assert is_delaunay(d)
    # R4.9: one Laplace-Beltrami operator, whatever triangulation the metric came in
    t = m.triangulation
    g = polycube(1 if t.n_vertices == 32 else 0)
    assert laplace_beltrami(m) == laplace_beltrami(g.metric())


_coordinates = st.one_of(
    st.fractions(max_denominator=40).map(lambda x: x * 7),          # any denominators
    st.floats(-1e6, 1e6, allow_nan=False).map(Fraction),            # dyadic, as from floats
    st.integers(-3, 3).map(lambda k: Fraction(k, 2 ** 60)))          # tiny


@settings(suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])
@given(st.sampled_from(["tetrahedron", "octahedron", "torus", "disk"]), st.data())
def test_metric_of_points_is_the_definition(name, data):
    # metric_of computes on integers over common denominators and builds the metric as valid
    # by construction: the same squared lengths and areas as the definition (Fractions, then
    # the constructor's own Heron check), or the same refusal of a degenerate face
    from ddg_oracle.reference import surfaces
    from ddg_oracle.reference.errors import DegenerateFace
    from ddg_oracle.reference.exact import sqrt
    from ddg_oracle.reference.metric import PiecewiseFlatSurface, metric_of
    t = {"tetrahedron": surfaces.tetrahedron, "octahedron": surfaces.octahedron,
         "torus": lambda: surfaces.torus(3, 3), "disk": lambda: surfaces.disk(4)}[name]().triangulation
    dim = data.draw(st.integers(2, 4))
    pts = [tuple(data.draw(_coordinates) for _ in range(dim)) for _ in range(t.n_vertices)]
    sq = [sum((a - b) ** 2 for a, b in zip(pts[i], pts[j]))
          for i, j in map(t.edge_vertices, range(t.n_edges))]
    four = []
    for i, j, k in t.faces:
        u = [b - a for a, b in zip(pts[i], pts[j])]
        v = [b - a for a, b in zip(pts[i], pts[k])]
        four.append(sum(x * x for x in u) * sum(x * x for x in v) - sum(x * y for x, y in zip(u, v)) ** 2)
    if 0 in sq or 0 in four:
        with pytest.raises(DegenerateFace):
            metric_of(pts, t)
        return
    want = PiecewiseFlatSurface(t, sq, [sqrt(x) / 2 for x in four])
    got = metric_of(pts, t)
    assert got.squared_lengths == want.squared_lengths and got.areas == want.areas
    assert all(type(a) is type(b) for a, b in zip(got.areas, want.areas))
