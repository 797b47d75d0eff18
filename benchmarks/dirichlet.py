"""Exact Dirichlet problems on float meshes (issue 18, item 4): the certified enclosure at
size (``reference.dirichlet_certificate``), and where exact elimination with irrational
weights (``reference.dirichlet.solve_dirichlet``) stops."""

from __future__ import annotations

import multiprocessing as mp
import time

from .common import Mode, median_time, say

#: lifted triangular lattices (k x k squares, two triangles each): (k + 1)^2 vertices
SIZES = (44, 89, 172)
QUICK_SIZES = (44, 89)
#: exact elimination with irrational weights: unknowns tried, seconds allowed each
EXACT_UNKNOWNS = (1, 2, 3)
EXACT_LIMIT = 60.0


def lifted_lattice(k: int):
    """``(V, F, boundary)``: the k x k grid sheared into nearly equilateral triangles and
    lifted by a float bump ``z = 0.1 sin(3x) cos(2y)`` (scaled to the unit square), so the
    cotan weights are irrational (a planar mesh's are rational: 16 area^2 is a square) and
    all positive (every angle stays far from pi/2's neighbourhood of 0 weight)."""
    import math
    from ddg_oracle.reference import surfaces
    g = surfaces.grid(k, k)
    V = []
    for x, y, _ in g.positions:
        u, w = (float(x) - 0.5 * float(y)) / k, float(y) * 0.8660254037844386 / k
        V.append([u, w, 0.1 * math.sin(3 * u) * math.cos(2 * w)])
    t = g.triangulation
    return V, [list(f) for f in t.faces], [v for v in range(t.n_vertices)
                                           if t.is_boundary_vertex(v)]


def _float_solves(L, c):
    """The candidate and ``v`` (``L_II v = 1``) by scipy's sparse LU on L's float view."""
    import numpy as np
    import scipy.sparse.linalg as sla
    A = L.to_scipy().tocsr()
    n = A.shape[0]
    B = sorted(c)
    I = [i for i in range(n) if i not in c]
    AII = A[I][:, I].tocsc()
    u, v = np.zeros(n), np.zeros(n)
    u[B] = [float(c[i]) for i in B]
    u[I] = sla.spsolve(AII, -A[I][:, B] @ u[B])
    v[I] = sla.spsolve(AII, np.ones(len(I)))
    return u.tolist(), v.tolist()


def _exact_solve(unknowns: int, out) -> None:
    """solve_dirichlet on a 7 x 7 lifted lattice with ``unknowns`` adjacent interior
    vertices (grown from one by breadth-first search)."""
    from ddg_oracle.reference.dirichlet import solve_dirichlet
    from ddg_oracle.reference.laplacian import cotan_laplacian
    from ddg_oracle.reference.polyhedral import PolyhedralSurface
    V, F, hull = lifted_lattice(6)
    L = cotan_laplacian(PolyhedralSurface.from_arrays(V, F))
    interior = [i for i in range(len(V)) if i not in set(hull)]
    inner = interior[:1]
    for i in inner:                      # breadth-first: the list grows while read
        inner += [j for j in sorted(L.row(i)) if j in interior and j not in inner]
    inner = inner[:unknowns]
    c = {i: (i % 5) / 4 for i in range(len(V)) if i not in inner}
    t0 = time.process_time()
    solve_dirichlet(L, c)
    out.put(time.process_time() - t0)


def run(mode: Mode) -> dict:
    from ddg_oracle.reference.dirichlet_certificate import certify_dirichlet
    from ddg_oracle.reference.laplacian import cotan_laplacian
    from ddg_oracle.reference.polyhedral import PolyhedralSurface
    rows = []
    for k in QUICK_SIZES if mode.quick else SIZES:
        V, F, hull = lifted_lattice(k)
        n = len(V)
        t_lap, _, L = median_time(cotan_laplacian, mode,
                                  setup=lambda: PolyhedralSurface.from_arrays(V, F))
        c = {i: V[i][0] ** 2 - V[i][1] ** 2 for i in hull}
        t0 = time.process_time()
        u, v = _float_solves(L, c)
        t_float = time.process_time() - t0
        t_cert, _, e = median_time(lambda: certify_dirichlet(L, c, u, v), mode)
        rows.append({"vertices": n, "faces": len(F), "unknowns": n - len(hull),
                     "laplacian_s": t_lap, "float_s": t_float, "certify_s": t_cert,
                     "bits": e.bits, "max_radius": float(max(e.radius))})
        say(f"  dirichlet {n:6} vertices {len(F):6} faces  Laplacian {t_lap:6.2f}  floats "
            f"{t_float:6.2f}  certify {t_cert:6.2f} s  max radius {float(max(e.radius)):.2g}")
    exact = []
    ctx = mp.get_context("spawn")
    for k in EXACT_UNKNOWNS:
        q = ctx.Queue()
        p = ctx.Process(target=_exact_solve, args=(k, q))
        p.start()
        p.join(EXACT_LIMIT)
        if p.is_alive():
            p.kill()
            p.join()
            seconds = None
        else:
            seconds = q.get() if not q.empty() else None
        exact.append({"unknowns": k, "seconds": seconds, "limit": EXACT_LIMIT})
        say(f"  dirichlet exact elimination, {k} unknowns: "
            + (f"{seconds:.2f} s" if seconds is not None else f"not done in {EXACT_LIMIT:.0f} s"))
    return {"rows": rows, "exact": exact}
