"""Generic surfaces for the mutant-killing tests (issue 40, item 6; docs/mutation.md).

The reference's older tests lean on grids, regular solids and flat tori, where every face
has the same area, every vertex the same cone angle, every edge the same weight: a mutant
that swaps two faces' areas, or two corners, computes the same numbers there.  The
surfaces built here break those symmetries: rational jitter (denominators 7, 11, 13: not
powers of two, so the scales of the integer routes are not either), cone points, unequal
areas, obtuse corners and non-Delaunay edges, boundary, non-orientable surfaces with and
without positions, per-face denominators (one coordinate with a 200-bit denominator),
planar positions (dimension 2), and intrinsic surfaces after flips (irrational squared
lengths).  The tests below check that they are generic in those ways, computed
independently (floats from the positions), so that the other test_mutants_* files can rely
on it.
"""

from __future__ import annotations

import math
import random
from fractions import Fraction

from ddg_oracle.reference import surfaces
from ddg_oracle.reference.intrinsic import IntrinsicTriangulation
from ddg_oracle.reference.metric import PiecewiseFlatSurface
from ddg_oracle.reference.polyhedral import PolyhedralSurface

DENOMINATORS = (7, 11, 13)


def jittered(s: PolyhedralSurface, seed: int, amount=Fraction(1, 8), dens=DENOMINATORS,
             dims=None) -> PolyhedralSurface:
    """``s`` with every coordinate moved by a random rational of size <= ``amount``
    (``dims``: only these coordinates)."""
    rng = random.Random(seed)
    out = []
    for p in s.positions:
        q = []
        for k, x in enumerate(p):
            if dims is None or k in dims:
                d = rng.choice(dens)
                x = x + amount * Fraction(rng.randint(-d, d), d)
            q.append(x)
        out.append(tuple(q))
    return s.with_positions(out)


def hilly_grid(m: int, n: int, seed: int, amount=Fraction(2, 5)) -> PolyhedralSurface:
    """A grid with boundary, jittered strongly in the plane (obtuse corners, negative
    cotan weights, non-Delaunay edges) and given random heights (cone points)."""
    s = jittered(surfaces.grid(m, n), seed, amount, dims=(0, 1))
    return jittered(s, seed + 1, Fraction(1, 2), dims=(2,))


def planar(s: PolyhedralSurface) -> PolyhedralSurface:
    """The same surface with its first two coordinates only (dimension 2)."""
    return s.with_positions([p[:2] for p in s.positions])


def huge_denominator(s: PolyhedralSurface, v: int = 0) -> PolyhedralSurface:
    """One coordinate of vertex ``v`` moved by 1 / (a 200-bit odd number): no common
    denominator of the coordinates is small enough to share (one per face instead)."""
    pos = [list(p) for p in s.positions]
    pos[v][0] += Fraction(1, (1 << 200) + 297)
    return s.with_positions(pos)


def random_lengths(t, seed: int, dens=(3, 5, 7)) -> PiecewiseFlatSurface:
    """An intrinsic surface on the triangulation ``t``: squared lengths drawn from
    [1, 3/2] (so every triangle inequality holds strictly: lengths in [1, 1.23])."""
    rng = random.Random(seed)
    sq = []
    for _ in range(t.n_edges):
        d = rng.choice(dens)
        sq.append(1 + Fraction(rng.randint(0, 4 * d), 8 * d))
    return PiecewiseFlatSurface(t, sq)


def flipped(m: PiecewiseFlatSurface, seed: int, flips: int = 6) -> PiecewiseFlatSurface:
    """``m`` after up to ``flips`` random intrinsic flips (irrational squared lengths)."""
    rng = random.Random(seed)
    w = IntrinsicTriangulation(m)
    done = 0
    for e in rng.sample(range(m.triangulation.n_edges), m.triangulation.n_edges):
        if done == flips:
            break
        if w.is_flippable(e):
            w.flip(e)
            done += 1
    return w.surface()


def polyhedral_cases():
    """(name, PolyhedralSurface): closed and with boundary, orientable and not, 3-d and
    planar, shared and per-face denominators."""
    return [
        ("icosahedron", jittered(surfaces.icosahedron(), 1)),
        ("octahedron", jittered(surfaces.octahedron(), 2, Fraction(1, 4))),
        ("torus", jittered(surfaces.torus(4, 3), 3)),
        ("mobius", jittered(surfaces.mobius_strip(5), 4)),
        ("disk", jittered(surfaces.disk(6), 5, Fraction(1, 6))),
        ("hilly grid", hilly_grid(3, 3, 6)),
        ("planar grid", planar(hilly_grid(3, 2, 7))),
        ("per-face denominators", huge_denominator(jittered(surfaces.octahedron(), 8))),
        ("annulus", jittered(surfaces.annulus(5), 9, Fraction(1, 6))),
    ]


def intrinsic_cases():
    """(name, PiecewiseFlatSurface) with rational squared lengths: non-orientable closed
    surfaces without positions, and a cone-shaped tetrahedron."""
    from ddg_oracle.reference.combinatorics import Triangulation
    tet = Triangulation.from_faces([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
    return [
        ("klein bottle", random_lengths(surfaces.klein_bottle(3, 3), 11)),
        ("projective plane", random_lengths(surfaces.projective_plane(), 12)),
        ("tetrahedron", random_lengths(tet, 13)),
        ("mobius lengths", random_lengths(surfaces.mobius_strip(4).triangulation, 14)),
    ]


def all_cases():
    return polyhedral_cases() + intrinsic_cases()


# --- independent float geometry ------------------------------------------------------------


def float_corner_angles(s: PolyhedralSurface) -> list[tuple[float, float, float]]:
    """The corner angles of every face from float positions (atan2 of |u x v| and u.v)."""
    out = []
    for face in s.triangulation.faces:
        P = [[float(x) for x in s.positions[v]] + [0.0] * (3 - s.dimension) for v in face]
        angles = []
        for c in range(3):
            o, a, b = P[c], P[(c + 1) % 3], P[(c + 2) % 3]
            u = [x - y for x, y in zip(a, o)]
            v = [x - y for x, y in zip(b, o)]
            cr = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
            angles.append(math.atan2(math.sqrt(sum(x * x for x in cr)), sum(x * y for x, y in zip(u, v))))
        out.append(tuple(angles))
    return out


def float_lengths_angles(m: PiecewiseFlatSurface) -> list[tuple[float, float, float]]:
    """The corner angles of every face from float squared lengths (law of cosines)."""
    out = []
    for f in range(m.triangulation.n_faces):
        l0, l1, l2 = (float(x) for x in m.face_squared_lengths(f))   # |01|^2, |12|^2, |20|^2
        sides = ((l0, l2, l1), (l0, l1, l2), (l1, l2, l0))          # adjacent, adjacent, opposite
        out.append(tuple(math.acos((a + b - o) / (2 * math.sqrt(a * b))) for a, b, o in sides))
    return out


# --- the surfaces are generic ----------------------------------------------------------


def _face_area_floats(m: PiecewiseFlatSurface) -> list[float]:
    return [float(a) for a in m.areas]


def test_the_cases_are_generic():
    kinds = set()
    for name, s in all_cases():
        m = s.metric() if isinstance(s, PolyhedralSurface) else s
        t = m.triangulation
        areas = _face_area_floats(m)
        assert len(set(areas)) == len(areas), name           # unequal areas, all of them
        angles = (float_corner_angles(s) if isinstance(s, PolyhedralSurface)
                  else float_lengths_angles(m))
        sums = [0.0] * t.n_vertices
        for face, a in zip(t.faces, angles):
            for v, x in zip(face, a):
                sums[v] += x
        boundary = t.boundary_vertices()
        cones = [v for v in range(t.n_vertices) if v not in boundary
                 and abs(sums[v] - 2 * math.pi) > 1e-6]
        if cones:
            kinds.add("cone points")
        if boundary:
            kinds.add("boundary")
        if not t.is_orientable():
            kinds.add("non-orientable")
        if any(x > math.pi / 2 + 1e-9 for a in angles for x in a):
            kinds.add("obtuse")
    assert kinds == {"cone points", "boundary", "non-orientable", "obtuse"}


def test_float_angles_of_the_two_routes_agree():
    # the two independent float routes (positions, lengths) agree: a check of the helpers
    for name, s in polyhedral_cases():
        a = float_corner_angles(s)
        b = float_lengths_angles(s.metric())
        assert all(math.isclose(x, y, abs_tol=1e-9) for p, q in zip(a, b) for x, y in zip(p, q)), name


def test_flips_make_irrational_squared_lengths():
    m = flipped(jittered(surfaces.icosahedron(), 1).metric(), 3)
    assert any(not isinstance(x, Fraction) for x in m.squared_lengths)
