"""Shared checks of the optional peers' adapters (gpytoolbox, robust-laplacian, potpourri3d)
against the exact reference, with the bounds the properties derive.

Each check takes an adapter and a named mesh, computes the truth with the
reference on exactly the floats the adapter receives (``PolyhedralSurface.from_arrays``
takes every float as a dyadic rational), and compares with the bound the
corresponding property uses: ``corner_tolerances`` / ``vertex_tolerances`` /
``edge_mean_curvature_tolerances`` / ``area_tolerance`` of
``ddg_oracle.properties.curvature`` (D2.6, D2.2 + R2.4, D2.3, R2.5), the entry bounds
``Exact(...).B`` of ``ddg_oracle.properties.harness`` (D3.1), ``Exact.vertex_area_bounds`` (L3.7)
and ``DelaunayExact(...).B`` of ``ddg_oracle.properties.delaunay`` (D4.8).  The bounds
are derived there from machine epsilon and the conditioning of each quantity.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from ddg_oracle.properties.bounds import (area_tolerance, corner_tolerances,
                                          edge_mean_curvature_tolerances, vertex_tolerances)
from ddg_oracle.properties.strategies import floated
from ddg_oracle.properties.delaunay_exact import DelaunayExact
from ddg_oracle.properties.harness import Exact
from ddg_oracle.properties.strategies import Example
from ddg_oracle.reference import surfaces
from ddg_oracle.reference import curvature as ref_curvature
from ddg_oracle.reference import laplacian as ref_laplacian

MESHES = {
    "cube": surfaces.cube,
    "tetrahedron": surfaces.tetrahedron,
    "icosahedron": surfaces.icosahedron,
    "torus(5,4)": lambda: surfaces.torus(5, 4),
    "genus_surface(1)": lambda: surfaces.genus_surface(1),   # reflex (concave) edges
    "disk(6)": lambda: surfaces.disk(6),
    "disk(3)": lambda: surfaces.disk(3),                     # 120-degree (obtuse) corners
    "grid(3,3)": lambda: surfaces.grid(3, 3),
    "annulus(5)": lambda: surfaces.annulus(5),
    "mobius_strip(5)": lambda: surfaces.mobius_strip(5),
}
CLOSED = ["cube", "tetrahedron", "icosahedron", "torus(5,4)", "genus_surface(1)"]


def jittered_torus():
    """surfaces.torus(5, 4) with every coordinate moved by up to ~0.1 (a fixed seed): closed,
    its intrinsic Delaunay triangulation needs flips, and no four vertices are cocircular
    (the unjittered torus has exactly cocircular quads, where Delaunay triangulations differ
    by a zero-weight diagonal)."""
    V, F = surfaces.torus(5, 4).to_arrays()
    V = np.array(V, dtype=np.float64)
    V = V + 0.05 * np.random.default_rng(1).standard_normal(V.shape)
    return V, np.array(F, dtype=np.int64)
ORIENTABLE = [k for k in MESHES if k != "mobius_strip(5)"]


def arrays(name):
    """(V float64, F int64) of a named mesh, its coordinates rounded to floats once."""
    V, F = MESHES[name]().to_arrays()
    return np.array(V, dtype=np.float64), np.array(F, dtype=np.int64)


def curvature_case(name) -> Example:
    s = floated(MESHES[name]())
    return Example.of_surface(s, s.triangulation.euler_characteristic(), name)


def mesh_case(V, F, recipe="") -> Example:
    """The Example of exactly these float arrays (positions as dyadic Fractions)."""
    return Example.of_mesh(tuple(tuple(Fraction(float(x)) for x in p) for p in V),
                    tuple(tuple(int(v) for v in f) for f in F), recipe)


def cyclic(loop):
    loop = [int(v) for v in loop]
    k = loop.index(min(loop))
    return tuple(loop[k:] + loop[:k])


# --- checks: each asserts the adapter's value is within the property's bound ------------------


def check_euler_characteristic(impl, name):
    V, F = arrays(name)
    assert impl.euler_characteristic(V, F) == MESHES[name]().triangulation.euler_characteristic()


def check_corner_angles(impl, name):
    case = curvature_case(name)
    V, F = case.arrays()
    got = np.asarray(impl.corner_angles(V, F))
    want = np.array([[float(a) for a in face] for face in ref_curvature.corner_angles(case.surface)])
    assert got.shape == want.shape
    err, tol = np.abs(got - want), corner_tolerances(case)
    assert np.all(err <= tol), float(np.max(err / tol))


def exact_angle_defects(surface) -> np.ndarray:
    """2 pi - angle sum at interior vertices, pi - angle sum (turning angle) at boundary ones."""
    m = surface.metric()
    exact = {**ref_curvature.angle_defects(m), **ref_curvature.turning_angles(m)}
    return np.array([float(exact[v]) for v in range(surface.n_vertices)])


def check_angle_defects(impl, name):
    case = curvature_case(name)
    V, F = case.arrays()
    got = np.asarray(impl.angle_defects(V, F))
    err = np.abs(got - exact_angle_defects(case.surface))
    tol = vertex_tolerances(case, corner_tolerances(case))
    assert np.all(err <= tol), float(np.max(err / tol))


def check_edge_mean_curvature(impl, name):
    case = curvature_case(name)
    V, F = case.arrays()
    got = impl.edge_mean_curvature(V, F)
    t = case.triangulation
    want = {tuple(sorted(t.edge_vertices(e))): float(h)
            for e, h in ref_curvature.mean_curvature(case.surface).items()}
    assert set(got) == set(want)            # the interior edges, keys (i, j) with i < j
    tol = edge_mean_curvature_tolerances(case)
    for e, h in want.items():
        assert abs(got[e] - h) <= tol[e], (e, got[e], h, tol[e])


def check_area(impl, name):
    case = curvature_case(name)
    V, F = case.arrays()
    want = float(case.surface.metric().total_area())
    assert abs(impl.area(V, F) - want) <= area_tolerance(case)


def check_cotan_laplacian(impl, name):
    V, F = arrays(name)
    X = Exact(mesh_case(V, F, name))
    got = impl.cotan_laplacian(V, F).toarray()
    assert got.shape == (X.n, X.n)
    assert np.all(np.abs(got - X.Lf) <= X.B), float(np.max(np.abs(got - X.Lf) - X.B))


def check_vertex_areas(impl, name, kind):
    """kind "barycentric" or "voronoi" (Meyer et al.'s mixed areas)."""
    V, F = arrays(name)
    X = Exact(mesh_case(V, F, name))
    vb, bb = X.vertex_area_bounds
    exact = getattr(ref_laplacian, f"vertex_areas_{kind}")(X.surface)
    want = np.array([float(a) for a in exact])
    got = np.asarray(getattr(impl, f"vertex_areas_{kind}")(V, F))
    bound = bb if kind == "barycentric" else vb
    assert got.shape == want.shape
    assert np.all(np.abs(got - want) <= bound), float(np.max(np.abs(got - want) / bound))


def check_intrinsic_delaunay_laplacian(impl, case):
    """``case``: a mesh name or a Example; the truth is the exact operator of the reference's
    flip algorithm, the bound D4.8's (flip amplification included)."""
    if isinstance(case, str):
        case = mesh_case(*arrays(case), case)
    V, F = case.arrays()
    D = DelaunayExact(case)
    got = impl.intrinsic_delaunay_laplacian(V, F).toarray()
    assert got.shape == D.Lf.shape
    assert np.all(np.abs(got - D.Lf) <= D.B), float(np.max(np.abs(got - D.Lf) - D.B))


def python_calls(fn, *args, caller: str) -> int:
    """How many Python-level functions the code of file ``caller`` calls while ``fn(*args)``
    runs (``sys.setprofile``'s "call" events: C functions such as ``math.atan2`` are
    "c_call" and not counted; a library's own Python code calling itself is not counted)."""
    import gc
    import sys
    import warnings
    n = 0

    def count(frame, event, arg):
        nonlocal n
        n += event == "call" and frame.f_back is not None and \
            frame.f_back.f_code.co_filename == caller

    # no collection and no warning shown inside: a finalizer the collector runs, or the
    # warning machinery, would count as called from the frame that happened to be running
    gc.collect()
    gc.disable()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sys.setprofile(count)
        try:
            fn(*args)
        finally:
            sys.setprofile(None)
            gc.enable()
    return n


def check_array_methods(impl, methods):
    """The Python functions each method of the adapter (of ``(V, F)``) calls are not more on
    20,000 faces than on 800: it hands the library arrays and works on arrays.  A loop in
    Python over the edges made libigl's edge_mean_curvature take over 120 s on 900k faces,
    which the check reports as libigl hanging."""
    import inspect
    caller = inspect.getsourcefile(type(impl))
    small, large = (surfaces.grid(n, n).to_arrays() for n in (20, 100))
    methods = [m for m in methods if len(inspect.signature(getattr(impl, m)).parameters) == 2]
    assert methods
    calls = {m: [python_calls(getattr(impl, m), *a, caller=caller) for a in (small, large)]
             for m in methods}
    grown = {m: c for m, c in calls.items() if c[1] > c[0]}
    assert not grown, f"Python calls on 800 and 20,000 faces: {grown}"
    assert sum(c[0] for c in calls.values()) > 0            # the profile saw the adapter
