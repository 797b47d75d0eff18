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
