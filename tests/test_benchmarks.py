"""The side-by-side benchmark reads back the lines the benchmark groups print."""

from benchmarks.sidebyside import parse

LINES = """\
cotan (default)
  cotan icosphere      80 reference fast path              weights      0.0002 s
  cotan bunny       56172 reference public cotan_weights   weights      0.1744 s
  curvature bunny10k_textured   9999 Gauss-Bonnet decision  fast path     0.0267 s
  flips  20000 in place    12915 flips    2.499 s
  r3 icosphere / 256     80    43 flips    0.053 s
  real bunny10k_textured.obj: 2065 flips 2.87 s (0 exact decreases), angle sums kept: None
  real fan 128, exactly planar                     128 faces  exact   0.00  signs   0.01  floats   0.02  undecided 0  zero tests 1
"""


def test_every_timing_line_is_read_with_its_key():
    got = parse(LINES)
    assert got == {
        ("cotan", "icosphere", 80, "reference fast path", "weights"): 0.0002,
        ("cotan", "bunny", 56172, "reference public cotan_weights", "weights"): 0.1744,
        ("curvature", "bunny10k_textured", 9999, "Gauss-Bonnet decision", "fast path"): 0.0267,
        ("flips", "torus", 20000, "in place", ""): 2.499,
        ("r3", "icosphere / 256", 80, "flips", ""): 0.053,
        ("real", "bunny10k_textured.obj", 0, "intrinsic Delaunay", ""): 2.87,
        ("real", "fan 128, exactly planar", 128, "", "exact"): 0.0,
        ("real", "fan 128, exactly planar", 128, "", "signs"): 0.01,
        ("real", "fan 128, exactly planar", 128, "", "floats"): 0.02,
    }


def _row(key, before, after, paused=None):
    r = {"key": key, "before": before, "after": after}
    if paused:
        r["paused_before"], r["paused_after"] = paused
    return r


def test_the_side_by_side_summary_counts_lines_as_the_bar_reads_them():
    """Lines under 10 ms are left out; a line more than 10% slower is counted as such,
    and apart when it is within 10% with the collector paused; none slower says so."""
    from benchmarks.report import _sidebyside
    peer = ["cotan", "icosphere", 80, "numpy (float64)", "weights"]
    mine = ["cotan", "icosphere", 80, "reference fast path", "weights"]
    res = {"base": "a", "this": "b", "rounds": 2, "meta": {}}
    rows = [_row(peer, 0.10, 0.104), _row(mine, 0.10, 0.08),
            _row(mine[:3] + ["x", "y"], 0.001, 1.0),
            _row(mine[:3] + ["slow", "gc"], 0.10, 0.12, (0.10, 0.105)),
            _row(mine[:3] + ["slow", "code"], 0.10, 0.12, (0.10, 0.12))]
    text = "\n".join(_sidebyside(dict(res, rows=rows)))
    assert "(the peers, 1 lines) moved by 1.04 to 1.04" in text
    assert ("1 of 4 lines within 10%, 1 faster, 2 slower, 1 of them within 10% with the "
            "collector paused" in text)
    assert "x / y" not in text and "slow / code | 0.1000 | 0.1200 | 1.20" in text
    text = "\n".join(_sidebyside(dict(res, rows=rows[:2])))
    assert "1 of 2 lines within 10%, 1 faster, none slower;" in text


def test_a_knockout_patches_the_function_object_and_undo_restores_it():
    """benchmarks/knockout_plugin.py switches a wrong version on in the function object
    itself (a name imported elsewhere sees it too); undo() gives the original back."""
    from fractions import Fraction

    from benchmarks.knockout_plugin import knock_out, wrong_drop, wrong_last
    from ddg_oracle.reference import surfaces
    from ddg_oracle.reference.combinatorics import Triangulation
    from ddg_oracle.reference.curvature import total_curvature
    from ddg_oracle.reference.exact import pi

    s = surfaces.octahedron()
    right, chi = total_curvature(s), s.triangulation.euler_characteristic()
    assert right == 4 * pi and chi == 2
    p = knock_out("ddg_oracle.reference.curvature:total_curvature:value")
    q = knock_out("ddg_oracle.reference.combinatorics:Triangulation.euler_characteristic:value")
    try:
        assert total_curvature(s) == 4 * pi + pi * Fraction(1, 3)
        assert s.triangulation.euler_characteristic() == 3
    finally:
        p.undo()
        q.undo()
    assert total_curvature(s) == right and Triangulation.euler_characteristic(s.triangulation) == 2
    assert wrong_last((1, [Fraction(1), True])) == (1, [Fraction(1), False])
    assert wrong_last({"a": 1, "b": 2.0}) == {"a": 1, "b": 2.0 * (1 + 2**-10) + 2**-10}
    assert wrong_drop([1, 2, 3]) == [1, 2] and len(wrong_drop({1, 2, 3})) == 2
    # a dataclass: its first (value) or last (last) field that can be made wrong
    from dataclasses import astuple

    from benchmarks.knockout_plugin import kind, wrong_value
    c = surfaces.torus(3, 3).triangulation.classify()
    assert kind(c) == "dataclass" and astuple(c) == (True, 1, 0, 0)
    assert astuple(wrong_value(c)) == (False, 1, 0, 0)
    assert astuple(wrong_last(c)) == (True, 1, 0, 1)


def test_a_hand_written_wrong_version_patches_the_function_and_undo_restores_it():
    """benchmarks/knockout_hand.py's wrong versions switch on in the function object itself,
    a generator function's too (cube_belt_twist), and count the results they change."""
    from benchmarks.knockout_hand import HAND_WRITTEN, knock_out_by_hand
    from benchmarks.knockout_plugin import STATS
    from ddg_oracle.reference import surfaces
    from ddg_oracle.reference.curvature import vertex_type
    from ddg_oracle.reference.triangulations import cube_belt_twist

    assert all(h.doc and h.key.count(":") == 2 for h in HAND_WRITTEN.values())
    torus = surfaces.torus(8, 6)
    right = [vertex_type(torus, v) for v in range(6)]
    assert set(right) == {"elliptic", "hyperbolic"}
    STATS.update(calls=0, changed=0)
    p = knock_out_by_hand("curvature:vertex_type:sign_reversed")
    q = knock_out_by_hand("triangulations:cube_belt_twist:one_fewer")
    try:
        swap = {"elliptic": "hyperbolic", "hyperbolic": "elliptic"}
        assert [vertex_type(torus, v) for v in range(6)] == [swap[r] for r in right]
        assert len(list(cube_belt_twist(3))) == 3
        assert STATS == {"calls": 7, "changed": 7}
    finally:
        p.undo()
        q.undo()
    assert [vertex_type(torus, v) for v in range(6)] == right
    assert len(list(cube_belt_twist(3))) == 4


def test_a_knockout_that_must_be_killed_is_killed_in_a_child():
    """One child pytest run with the plugin: euler_characteristic off by one fails
    tests/test_surfaces.py; with no knockout it passes."""
    from benchmarks.knockout import run_knockout

    spec = "ddg_oracle.reference.combinatorics:Triangulation.euler_characteristic:value"
    res = run_knockout(spec, ["tests/test_surfaces.py"], timeout=120)
    assert res["status"] == "killed", res
    assert res["by"].startswith("FAILED tests/test_surfaces.py")


def test_a_hand_written_knockout_is_switched_on_in_a_child_by_its_own_plugin():
    """benchmarks/knockout_hand.py is a pytest plugin of its own (the knockout plugin does not
    import it): a child run with DDG_KNOCKOUT_HAND fails the test that sees the mistake,
    and counts the calls it changed."""
    from benchmarks.knockout import run_knockout

    res = run_knockout("curvature:vertex_type:sign_reversed",
                       ["tests/test_curvature.py::test_D2_2_vertex_types_on_a_torus"],
                       timeout=120, hand=True)
    assert res["status"] == "killed", res
    assert res["changed"] >= 1 and res["calls"] >= res["changed"], res


def test_knockout_variants_change_sparse_matrices_and_surfaces():
    """The wrong versions of the objects most reference functions return: a SparseMatrix
    with its last stored entry + 1/3, a PolyhedralSurface with its last vertex moved."""
    from fractions import Fraction

    from benchmarks.knockout_plugin import kind, wrong_value
    from ddg_oracle.reference import surfaces
    from ddg_oracle.reference.laplacian import cotan_laplacian
    s = surfaces.tetrahedron()
    L = cotan_laplacian(s)
    W = wrong_value(L)
    changed = [(i, j) for i in range(4) for j in range(4) if W.row(i).get(j) != L.row(i).get(j)]
    assert kind(L) == "SparseMatrix" and changed == [(3, 3)]
    assert W.row(3)[3] - L.row(3)[3] == Fraction(1, 3)
    t = wrong_value(s)
    assert kind(s) == "PolyhedralSurface" and t.positions[:-1] == s.positions[:-1]
    assert t.positions[-1][0] - s.positions[-1][0] == Fraction(1, 3)
