"""Conventions as data (issue 42): an implementation that follows a library's convention
declares it in one line and passes; one that does not declare it fails, and the report
names the convention under which its answer agrees.

Each implementation here is examples/numpy_mesh.py's correct numpy code with one
convention of the vocabulary applied to its answers, the way the library does it.
"""

from __future__ import annotations

import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from ddg_oracle.application.cli import main
from ddg_oracle.application.compare import compare_mesh
from ddg_oracle.application.meshes import MeshInput
from ddg_oracle.oracles.exact_reference import ReferenceImplementation
from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.conventions import (PRESETS, VOCABULARY, barycentric_areas,
                                               declaration_text, mixed_areas, parse)
from ddg_oracle.properties.profiles import profile
from ddg_oracle.properties.runner import FAILED, PASSED, TIE, run_property
from ddg_oracle.application.jobs import with_diagnosis
from ddg_oracle.application.causes import convention_hint
from examples.numpy_mesh import NumpyMesh

ROOT = Path(__file__).resolve().parent.parent


def _boundary(F, n):
    from ddg_oracle.properties.conventions import boundary_vertices
    return boundary_vertices(F, n)


class NegativeL(NumpyMesh):
    """libigl's cotmatrix: -L."""
    name = "negative-L"

    def cotan_laplacian(self, V, F):
        return -super().cotan_laplacian(V, F)


class FullWeights(NumpyMesh):
    """CGAL's and OpenMesh's edge weight cot a + cot b: 2 L, and twice the gradient."""
    name = "full-weights"

    def cotan_laplacian(self, V, F):
        return 2 * super().cotan_laplacian(V, F)

    def area_gradient(self, V, F):
        return 2 * super().area_gradient(V, F)


class TwoPiAtBoundary(NumpyMesh):
    """libigl's gaussian_curvature: 2 pi - angle sum at boundary vertices too."""
    name = "two-pi-boundary"

    def angle_defects(self, V, F):
        K = np.array(super().angle_defects(V, F), dtype=float)
        return K + np.pi * _boundary(F, len(K))


class PointwiseBarycentric(NumpyMesh):
    """VTK's Gaussian curvature: the defect per a third of the incident area."""
    name = "pointwise-barycentric"

    def angle_defects(self, V, F):
        K = np.array(super().angle_defects(V, F), dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            return K / barycentric_areas(V, F)


class PointwiseMixed(NumpyMesh):
    """Meyer et al.'s Gaussian curvature: the defect per mixed Voronoi area."""
    name = "pointwise-mixed"

    def angle_defects(self, V, F):
        K = np.array(super().angle_defects(V, F), dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            return K / mixed_areas(V, F)


class Regularized(NumpyMesh):
    """The DDG course's laplaceMatrix: L + 1e-8 I."""
    name = "regularized"

    def cotan_laplacian(self, V, F):
        import scipy.sparse as sp
        L = super().cotan_laplacian(V, F)
        return L + 1e-8 * sp.identity(L.shape[0])


class DropsUnused(NumpyMesh):
    """LaPy's TriaMesh: the vertices no face uses are removed and the rest renumbered."""
    name = "drops-unused"

    def cotan_laplacian(self, V, F):
        V, F = np.asarray(V, float), np.asarray(F, dtype=np.int64)
        used, G = np.unique(F, return_inverse=True)
        return super().cotan_laplacian(V[used], G.reshape(F.shape))


DECLARED = [
    (NegativeL, {"laplacian": "negative"}, ["D3.1", "T3.6"]),
    (FullWeights, {"weights": "full"}, ["D3.1", "T3.6", "R3.3"]),
    (TwoPiAtBoundary, {"boundary_defect": "two_pi"}, ["R2.4", "T2.5"]),
    (PointwiseBarycentric, {"curvature": "per_barycentric_area"}, ["R2.4", "T2.5"]),
    (PointwiseMixed, {"curvature": "per_mixed_area"}, ["R2.4", "T2.5"]),
    (Regularized, {"regularization": 1e-8}, ["D3.1"]),
    (DropsUnused, {"unused_vertices": "dropped"}, ["D3.1"]),
]


def _declaring(cls, declaration):
    return type(cls.__name__ + "Declared", (cls,), {"conventions": declaration})


def _run(impl, pid):
    prop = PROPERTIES[pid]
    # a fixed seed: a reproducible verdict (D3.1 draws a vertex used by no face in about
    # 38 of 40 seeded runs, so an unseeded run would miss DropsUnused now and then)
    return with_diagnosis(run_property(prop, impl, profile("default"), seed=0), prop, impl)


@pytest.mark.parametrize("cls, declaration, pids", DECLARED,
                         ids=[c.__name__ for c, _, _ in DECLARED])
def test_declared_convention_passes(cls, declaration, pids):
    impl = _declaring(cls, declaration)()
    for pid in pids:
        r = _run(impl, pid)
        assert r.status in (PASSED, TIE), (pid, r.status, r.error)


@pytest.mark.parametrize("cls, declaration, pids", DECLARED,
                         ids=[c.__name__ for c, _, _ in DECLARED])
def test_undeclared_convention_fails_and_is_named(cls, declaration, pids):
    r = _run(cls(), pids[0])
    assert r.status == FAILED, (pids[0], r.status)
    hint = convention_hint(r)
    key, value = next(iter(declaration.items()))
    assert hint is not None, r.diagnosis
    assert f"{key}={value:g}" if key == "regularization" else f"{key}={value}" in hint
    assert declaration_text(parse(declaration)) in hint


def test_a_bug_is_not_explained_by_a_convention():
    """A wrong corner is no convention: the report names none (no false hint)."""
    from examples.numpy_cotan import WrongCorner

    class Wrong(WrongCorner):
        name = "wrong-corner"
    r = _run(Wrong(), "D3.1")
    assert r.status == FAILED
    assert convention_hint(r) is None


def test_a_declared_convention_the_answer_does_not_follow_fails():
    """Declaring -L for a positive L is not a free pass: the mapped answer is wrong."""
    impl = _declaring(NumpyMesh, {"laplacian": "negative"})()
    assert _run(impl, "D3.1").status == FAILED


def test_pointwise_curvature_without_area_is_declined_not_failed():
    """A vertex whose faces have no area has no pointwise curvature: the map declines the
    example (OutsideDomain) rather than failing on K / 0."""
    from ddg_oracle.properties.conventions import to_reference
    from ddg_oracle.protocol.methods import OutsideDomain
    V = np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0]], float)
    F = np.array([[0, 1, 2]])
    with pytest.raises(OutsideDomain, match="vertex 0"):
        to_reference(parse({"curvature": "per_barycentric_area"}), "angle_defects",
                     np.full(4, np.inf), V, F)


def test_compare_maps_declared_conventions_and_explains_undeclared_ones():
    V = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0.5]]
    F = [[0, 1, 2], [1, 3, 2]]
    mesh = MeshInput("two-triangles", V, F)
    ref = ReferenceImplementation()
    declared = type("Declared", (NegativeL,), {"conventions": {"laplacian": "negative"},
                                                "name": "declared"})()
    rows = {(c.implementation, c.quantity): c
            for c in compare_mesh(mesh, [declared, NegativeL()], ref,
                                  methods=["cotan_laplacian"])}
    assert rows[("negative-L", "cotan_laplacian")].status == "DIFFERS"
    assert rows[("negative-L", "cotan_laplacian")].explained_by == ("laplacian=negative",)
    agreeing = [c for c in rows.values() if c.status == "agrees"]
    assert len(agreeing) == 1


def test_presets_parse_and_cover_only_the_vocabulary():
    for name, d in PRESETS.items():
        parsed = parse(name)
        assert {c.key for c in parsed} == set(d), name
    assert [c.name for c in parse({"preset": "libigl", "boundary_defect": "two_pi"})] == \
        ["laplacian=negative", "boundary_defect=two_pi"]


@pytest.mark.parametrize("bad, message", [
    ("igl", "no preset 'igl'"),
    ({"laplacian": "minus"}, "laplacian is one of negative"),
    ({"sign": "negative"}, "no convention 'sign'"),
    ({"regularization": 2}, "small positive number"),
    (["laplacian"], "preset name or {key: value}"),
])
def test_a_malformed_declaration_is_named(bad, message):
    with pytest.raises(ValueError, match=message.replace("{", r"\{").replace("}", r"\}")):
        parse(bad)


def test_the_command_refuses_a_malformed_declaration_in_one_line(tmp_path, capsys,
                                                                   monkeypatch):
    (tmp_path / "badconv.py").write_text(textwrap.dedent("""
        from examples.numpy_mesh import NumpyMesh
        class Bad(NumpyMesh):
            conventions = {"laplacian": "minus"}
    """))
    monkeypatch.syspath_prepend(str(tmp_path))
    rc = main(["check", "--impl", "badconv:Bad", "--only", "D3.1"])
    out, err = capsys.readouterr()
    assert rc == 2
    assert len(err.strip().splitlines()) == 1 and "laplacian is one of negative" in err


def test_an_executable_declares_a_preset_in_its_handshake(tmp_path):
    """A program of the executable protocol says {"conventions": "libigl"} and its -L is
    mapped; a preset that does not exist stops the run with the program named."""
    from ddg_oracle.oracles.executable import DriverFailed, Executable
    driver = tmp_path / "neg.py"
    driver.write_text(textwrap.dedent(f"""
        import sys
        sys.path.insert(0, {str(tmp_path.parent)!r})
        from ddg_oracle.oracles.executable import serve
        from examples.numpy_mesh import NumpyMesh
        class Neg(NumpyMesh):
            name = "neg"
            conventions = sys.argv[1]
            def cotan_laplacian(self, V, F):
                return -super().cotan_laplacian(V, F)
        serve(Neg())
    """))
    import examples
    root = str(__import__("pathlib").Path(examples.__file__).resolve().parent.parent)
    env_path = f"PYTHONPATH={root}"
    impl = Executable(["env", env_path, sys.executable, str(driver), "libigl"], timeout=60)
    try:
        assert impl.conventions == "libigl"
        r = run_property(PROPERTIES["D3.1"], impl, profile("default"))
        assert r.status in (PASSED, TIE), r.error
    finally:
        impl.close()
    with pytest.raises(DriverFailed, match="no preset 'igl'"):
        bad = Executable(["env", env_path, sys.executable, str(driver), "igl"], timeout=60)
        bad.close()


def test_every_convention_is_documented():
    """docs/conventions.md names every key, value and preset of the vocabulary."""
    from pathlib import Path
    text = (Path(__file__).resolve().parent.parent / "docs" / "conventions.md").read_text()
    for key, values in VOCABULARY.items():
        for value in values:
            assert f'"{key}": "{value}"' in text, (key, value)
    for name in PRESETS:
        assert f'"{name}"' in text, name
    assert '"regularization"' in text


def test_the_diagnosis_names_the_convention_on_a_mesh_with_an_unused_vertex():
    """A counterexample with a vertex of no face (D3.1 draws them) was diagnosed only for
    unused_vertices=dropped: -L there got no hint.  The rows and columns of the used
    vertices are compared on the mesh without the others, in the mesh's own numbers."""
    from ddg_oracle.application.compare import diagnose
    V = [[5.0, 5, 5], [0.0, 0, 0], [1.0, 0, 0], [0.0, 1, 0]]
    rows = diagnose((V, [[1, 2, 3]]), NegativeL(), ["cotan_laplacian"])
    assert [(r["status"], r["explained_by"]) for r in rows] == [("DIFFERS", ["laplacian=negative"])]
    assert rows[0]["where"] in ("entry (1, 2)", "entry (1, 3)", "entry (2, 3)",
                                "entry (1, 1)", "entry (2, 2)", "entry (3, 3)")
    assert diagnose((V, [[1, 2, 3]]), _declaring(NegativeL, {"laplacian": "negative"})(),
                    ["cotan_laplacian"])[0]["status"] == "agrees"


class MixedAreaAtItsBound(ReferenceImplementation):
    """A pointwise curvature: the exact angle defects (correctly rounded) divided by a mixed
    Voronoi area 0.9 of L3.7's derived bound above the exact one, an area L3.7 accepts."""
    name = "mixed-area-at-its-bound"
    conventions = {"curvature": "per_mixed_area"}

    def angle_defects(self, V, F):
        from ddg_oracle.properties.harness import Exact
        from ddg_oracle.properties.strategies import mesh_case
        D = np.asarray(super().angle_defects(V, F), dtype=float)
        X = Exact.of(mesh_case(np.asarray(V).tolist(), np.asarray(F).tolist(), "the input"))
        A = np.zeros(len(D))
        A[X.keep] = X.vertex_areas("vertex_areas_voronoi")
        with np.errstate(divide="ignore", invalid="ignore"):
            return D / (A + 0.9 * X.vertex_area_bounds[0])


@pytest.mark.parametrize("pid", ["D2.2", "T2.6", "R2.4"])
def test_a_pointwise_curvature_over_an_area_within_its_bound_passes(pid):
    # the map multiplies K back by a float area: the defects' bounds add both areas' error
    # (within L3.7's bound each); without it, this failed D2.2 at 1.29 x, T2.6 at 3.3 x and
    # R2.4 at 7.4 x the bound in 3 examples (PyGEL3D once D2.2 at 1.38 x on a needle)
    r = run_property(PROPERTIES[pid], MixedAreaAtItsBound(), profile("default"), seed=0)
    assert r.status == PASSED and r.examples == 25, (r.status, r.failure)


def test_compare_widens_the_bound_of_a_pointwise_curvature_as_the_properties_do():
    # the unit tetrahedron: D2.2's shrunk counterexample of MixedAreaAtItsBound before the
    # bounds counted the area (1.29 x the bound)
    V = [[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
    F = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
    [row] = compare_mesh(MeshInput("tetrahedron", V, F), [MixedAreaAtItsBound()],
                         ReferenceImplementation(), methods=["angle_defects"])
    assert row.status == "agrees", (row.status, row.worst)


def test_verify_widens_the_written_bounds_of_a_pointwise_curvature(capsys):
    # the test vectors' bounds are written for the reference's convention: verify widens
    # them for the declared map as the properties do (26 of the 36 angle_defects cases
    # failed without it)
    rc = main(["verify", str(ROOT / "vectors"), "--impl",
               "tests.test_conventions:MixedAreaAtItsBound"])
    out = capsys.readouterr().out
    assert rc == 0 and " 0 FAIL" in out, out


def test_the_widening_leaves_a_vertex_of_no_face_alone_and_is_never_nan():
    from ddg_oracle.properties.conventions import parse
    from ddg_oracle.properties.harness import widened
    from ddg_oracle.properties.strategies import mesh_case
    V = [[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [5, 5, 5]]      # vertex 4: no face
    case = mesh_case(V, [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], "tetrahedron and a point")
    K = np.array([1.0, 1.0, 1.0, 1.0, 2 * np.pi])
    tol = np.full(5, 1e-15)
    for bound in (tol, np.zeros(5)):
        wide = widened(parse({"curvature": "per_mixed_area"}), "angle_defects", K, case, bound)
        assert not np.isnan(wide).any() and wide[4] == bound[4]
        assert (wide[:4] > bound[:4]).all() and np.isfinite(wide[:4]).all()
    assert widened(parse("libigl"), "angle_defects", K, case, tol) is tol


# --- an input the implementation rounds itself: the DDG course's unit radius --------------------


def _unit_radius(V):
    # the DDG course's loader: centred at the mean, the farthest vertex at distance 1, in place
    V = np.array(V, dtype=np.float64)
    V -= V.mean(axis=0)
    V /= np.max(np.linalg.norm(V, axis=1))
    return V


class UnitRadius(NumpyMesh):
    """Course code: every method computes on its input rescaled by the course's loader."""
    name = "unit-radius"
    conventions = {"input_scale": "unit_radius"}


for _method in ("area", "vertex_areas_barycentric", "area_gradient", "edge_mean_curvature",
                "angle_defects", "corner_angles", "cotan_laplacian"):
    setattr(UnitRadius, _method, lambda self, V, F, _m=_method:
            getattr(super(UnitRadius, self), _m)(_unit_radius(V), F))


class UnitRadiusAreaBug(UnitRadius):
    """The same with a bug: areas 1e-9 too large (relative)."""
    name = "unit-radius-bug"

    def vertex_areas_barycentric(self, V, F):
        return super().vertex_areas_barycentric(V, F) * (1 + 1e-9)

    def area(self, V, F):
        return super().area(V, F) * (1 + 1e-9)


#: the shrunk counterexamples of a helper's hostile probe: a small mesh beside a vertex of
#: no face at distance 1 (the loader's radius), so the rescaling rounds the mesh relative to
#: the far point; before the bounds counted that rounding, L3.7 failed at 3.09e4 x, T3.9 at
#: 1.72 x, R2.5 at 1.54 x and D2.3 at 1.07 x the bound
_TINY = 2.0 ** -24
FAR_POINT = {
    "L3.7": ([[1.0, 1, 1], [0, 0, 0], [4 * _TINY, 0, 0], [0, _TINY / 4, 0], [0, -_TINY / 4, 0]],
             [[1, 2, 3], [2, 1, 4]]),
    "T3.9": ([[0.0, 0, 0], [1e-3, 0, 0], [0, 1e-3, 0], [0, 0, 1e-3], [1.0, 1, 1]],
             [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]),
}


@pytest.mark.parametrize("pid", ["L3.7", "T3.9", "R2.5", "D2.3", "D2.2", "D3.1"])
def test_an_input_rescaled_by_the_course_loader_passes_when_declared(pid):
    r = run_property(PROPERTIES[pid], UnitRadius(), profile("default"), seed=0)
    assert r.status in (PASSED, TIE), (pid, r.status, r.error)


@pytest.mark.parametrize("pid", sorted(FAR_POINT))
def test_a_far_point_sets_the_radius_and_its_rounding_is_counted(pid):
    from ddg_oracle.properties.runner import run_on_example
    from ddg_oracle.properties.strategies import mesh_case
    V, F = FAR_POINT[pid]
    r = run_on_example(PROPERTIES[pid], UnitRadius(), mesh_case(V, F, "a far point"), "probe")
    assert r.status == PASSED, (r.status, r.error)


def test_the_rescaling_widening_still_fails_a_bug():
    for pid in ("L3.7", "R2.5"):
        r = run_property(PROPERTIES[pid], UnitRadiusAreaBug(), profile("default"), seed=0)
        assert r.status == FAILED, (pid, r.status)


def test_a_rescaling_that_resolves_nothing_declines_the_example_not_crashes():
    # a 1e-17 tetrahedron beside a point at distance 1: the loader's rounding collapses it
    # (NumpyMesh then divides by a zero area); nothing can be judged, nothing is failed
    from ddg_oracle.properties.calls import Watched
    from ddg_oracle.protocol.methods import OutsideDomain
    t = 1.3877787807814457e-17
    V = [[0.0, 0, 0], [t, 0, 0], [0, t, 0], [0, 0, t], [1.0, 1, 1]]
    F = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
    with pytest.raises(OutsideDomain, match="cannot resolve"):
        Watched(UnitRadius(), "T3.9").area_gradient(np.array(V), np.array(F))
    assert np.isfinite(Watched(NumpyMesh(), "T3.9").area_gradient(np.array(V), np.array(F))).all()


def test_compare_and_verify_count_the_rescaling():
    # compare reads files without their unused vertices: the far point is a far face here
    V, F = FAR_POINT["L3.7"]
    V, F = V + [[1.0, 1.5, 1], [1.5, 1, 1]], F + [[0, 5, 6]]
    rows = compare_mesh(MeshInput("far face", V, F), [UnitRadius()], ReferenceImplementation(),
                        methods=["vertex_areas_barycentric", "area_gradient"])
    assert {r.status for r in rows} <= {"agrees"}, [(r.quantity, r.status, r.worst) for r in rows]
    rc = main(["verify", str(ROOT / "vectors"), "--impl", "tests.test_conventions:UnitRadius"])
    assert rc == 0


class UnitRadiusInPlace(NumpyMesh):
    """The course's loader working on the V it is given, in place (V is the call's own)."""
    name = "unit-radius-in-place"
    conventions = {"input_scale": "unit_radius"}

    @staticmethod
    def _load(V):
        V -= V.mean(axis=0)
        V /= np.max(np.linalg.norm(V, axis=1))
        return V

    def area(self, V, F):
        return super().area(self._load(V), F)

    def edge_mean_curvature(self, V, F):
        return super().edge_mean_curvature(self._load(V), F)

    def angle_defects(self, V, F):
        return super().angle_defects(self._load(V), F)


def test_a_convention_maps_from_the_input_as_given_not_as_left_in_place():
    # the map's scale was read from V after the call: an implementation rescaling V in place
    # left radius 1, its correct area 0.9 was not scaled back (2.0), in process only (the
    # command's isolated worker holds a copy)
    from ddg_oracle.properties.calls import Watched
    V, F = np.array([[0.0, 0, 0], [2, 0, 0], [0, 2, 0]]), np.array([[0, 1, 2]])
    assert Watched(UnitRadiusInPlace(), "R2.5").area(V, F) == pytest.approx(2.0, rel=1e-14)
    r = run_property(PROPERTIES["R2.5"], UnitRadiusInPlace(), profile("default"), seed=0)
    assert r.status in (PASSED, TIE), (r.status, r.error)


def test_a_rescaling_call_outside_a_check_leaves_the_process_epsilon_alone():
    # the widening of a call lasts to the end of the check it is part of; a call outside any
    # (a user's own test, compare's answers) once set the process default for good: every
    # later bound in that pytest worker was infinite
    from ddg_oracle.properties.calls import Watched
    from ddg_oracle.protocol.methods import FLOAT64_EPSILON, at_machine_epsilon, eps
    V, F = FAR_POINT["L3.7"]
    Watched(UnitRadius(), "L3.7").vertex_areas_barycentric(np.array(V), np.array(F))
    assert eps() == FLOAT64_EPSILON
    with at_machine_epsilon(FLOAT64_EPSILON):
        Watched(UnitRadius(), "L3.7").vertex_areas_barycentric(np.array(V), np.array(F))
        assert eps() > 1e6 * FLOAT64_EPSILON
    assert eps() == FLOAT64_EPSILON


class UnitRadius32Raises(UnitRadius):
    """A float32 course implementation whose Laplacian raises (a bug of its own)."""
    name = "unit-radius-32-raises"
    machine_epsilon = 2.0 ** -23

    def cotan_laplacian(self, V, F):
        raise IndexError("index 7 is out of bounds")


def test_a_crash_is_declined_only_where_the_rescaling_may_collapse_an_edge():
    # float32, a triangle of edge 1e-4 beside a unit one: the bounds are infinite there
    # (e' > 2^-7) but the rescaling keeps ~10 bits of every edge; the crash is the
    # implementation's.  It was declined ("not applicable", exit 0) from e' > 2^-7 on
    from ddg_oracle.properties.calls import Watched, raised_by_implementation
    from ddg_oracle.protocol.methods import OutsideDomain
    V = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [5, 5, 5], [5 + 1e-4, 5, 5], [5, 5 + 1e-4, 5]])
    F = np.array([[0, 1, 2], [3, 4, 5]])
    with pytest.raises(IndexError) as err:
        Watched(UnitRadius32Raises(), "D3.1").cotan_laplacian(V, F)
    assert raised_by_implementation(err.value)
    V[4:] = V[3] + (V[4:] - V[3]) * 1e-14            # now 1e-18: the rescaling collapses it
    with pytest.raises(OutsideDomain, match="cannot resolve"):
        Watched(UnitRadius32Raises(), "D3.1").cotan_laplacian(V, F)


class IntrinsicOnUsedVertices(ReferenceImplementation):
    """LaPy-like: the intrinsic Delaunay triangulation and Laplacian of the used vertices
    only, renumbered in order; declared."""
    name = "intrinsic-on-used-vertices"
    conventions = {"unused_vertices": "dropped"}

    @staticmethod
    def _used(V, F):
        V, F = np.asarray(V, float), np.asarray(F)
        used, inverse = np.unique(F, return_inverse=True)
        return V[used], inverse.reshape(F.shape)

    def intrinsic_delaunay_triangulation(self, V, F):
        return super().intrinsic_delaunay_triangulation(*self._used(V, F))

    def intrinsic_delaunay_laplacian(self, V, F):
        return super().intrinsic_delaunay_laplacian(*self._used(V, F))


def test_dropped_unused_vertices_cover_the_intrinsic_triangulation_too():
    # the declaration mapped the Laplacian back and not the triangulation's faces: A4.13
    # failed such an implementation ("the angle sum at vertex 0 changed", 5.2e13 x) once its
    # examples drew unused vertices
    for pid in ("A4.13", "D4.8 / R4.9"):
        r = run_property(PROPERTIES[pid], IntrinsicOnUsedVertices(), profile("default"), seed=0)
        assert r.status in (PASSED, TIE), (pid, r.status, r.error)


def test_unit_radius_maps_a_large_mean_curvature_answer_in_linear_time():
    """The map of a per-edge answer under input_scale = unit_radius computed the scale once
    per edge (O(E V): 95 s on the 56k-face bunny in `survey`'s convention diagnosis); now
    once per answer."""
    import time
    from ddg_oracle.properties.conventions import _scale, parse, to_reference
    rng = np.random.default_rng(0)
    V = rng.random((30000, 3))
    F = np.array([[0, 1, 2]])
    H = {(i, i + 1): float(i) for i in range(90000)}
    t = time.process_time()
    out = to_reference(parse({"input_scale": "unit_radius"}), "edge_mean_curvature", H, V, F)
    assert time.process_time() - t < 2.0
    s = _scale(V)
    assert out[(7, 8)] == 7.0 / s and len(out) == len(H)
