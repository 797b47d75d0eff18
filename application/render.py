"""A picture of a (counterexample) mesh with the offending element highlighted.

matplotlib with the Agg backend (no display needed), a 3D view of the faces (a
planar mesh: 2-D axes);
the element -- a vertex, an edge, a face or a corner, see
:func:`ddg_oracle.application.causes.element_ids` -- is drawn in red.  Small meshes get vertex
numbers.  A large mesh is cut down to the faces within two rings of the
element, so the picture shows where the problem is.
"""

from __future__ import annotations

import textwrap

import numpy as np

RING_LIMIT = 400            # faces above which only the neighbourhood of the element is drawn
LABEL_LIMIT = 40            # vertices up to which every vertex is numbered


def _neighbourhood(F: np.ndarray, seeds: set[int], rings: int = 2) -> np.ndarray:
    keep = np.zeros(len(F), dtype=bool)
    verts = set(seeds)
    for _ in range(rings):
        keep = np.isin(F, list(verts)).any(axis=1)
        verts = set(F[keep].ravel().tolist())
    return keep


def _on_mesh(element: dict, n_vertices: int, n_faces: int) -> dict:
    """``element`` if every index it holds is in the mesh, else {} (the picture is then
    drawn with nothing highlighted rather than not at all: a property naming an element
    of another mesh is a bug of that property, not a reason to lose the report).

    >>> _on_mesh({"edge": [3, 4]}, 4, 2), _on_mesh({"face": 1, "corner": 2}, 4, 2)
    ({}, {'face': 1, 'corner': 2})
    """
    ok = (all(0 <= v < n_vertices for v in element.get("edge", []))
          and 0 <= element.get("vertex", 0) < n_vertices
          and 0 <= element.get("face", 0) < n_faces and 0 <= element.get("corner", 0) < 3)
    return element if ok else {}


def render_mesh(path, V, F, element: dict | None = None, title: str = "") -> None:
    """Write a PNG of mesh (V, F) to ``path`` with ``element`` highlighted.

    ``element``: {"vertex": i} | {"edge": [i, j]} | {"face": f} | {"face": f, "corner": c}
    or None.
    """
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

    V = np.asarray(V, dtype=np.float64).reshape(-1, 3)
    F = np.asarray(F, dtype=np.int64).reshape(-1, 3)
    element = _on_mesh(element or {}, len(V), len(F))
    seeds: set[int] = set()
    if "vertex" in element:
        seeds.add(element["vertex"])
    if "edge" in element:
        seeds.update(element["edge"])
    if "face" in element and 0 <= element["face"] < len(F):
        seeds.update(F[element["face"]].tolist())
    faces = np.arange(len(F))
    if len(F) > RING_LIMIT and seeds:
        faces = np.flatnonzero(_neighbourhood(F, seeds))
        title += f" (the {len(faces)} faces within two rings of the element, of {len(F)})"
    used = np.unique(F[faces])
    fig = plt.figure(figsize=(6, 6), dpi=100)
    red = [element["vertex"]] if "vertex" in element else []
    if "corner" in element and "face" in element:
        red.append(int(F[element["face"], element["corner"]]))
    lines = []
    if "edge" in element:
        lines.append(V[element["edge"]])
    if "face" in element and 0 <= element["face"] < len(F):
        a, b, c = F[element["face"]]
        lines += [V[[a, b]], V[[b, c]], V[[c, a]]]     # its outline shows through other faces
    colours = np.tile([0.80, 0.85, 0.92, 0.55], (len(faces), 1))
    if "face" in element:
        colours[faces == element["face"]] = [0.9, 0.2, 0.2, 0.8]
    if np.ptp(V[used][:, 2]) == 0:
        # a planar mesh: 2-D axes, no z
        from matplotlib.collections import LineCollection, PolyCollection
        ax = fig.add_subplot()
        ax.add_collection(PolyCollection(V[F[faces]][:, :, :2], facecolors=colours,
                                         edgecolors=(0.3, 0.3, 0.4, 0.8), linewidths=0.6))
        if lines:
            ax.add_collection(LineCollection([seg[:, :2] for seg in lines], colors="red",
                                             linewidths=2.5, zorder=5))
        if red:
            ax.scatter(*V[red][:, :2].T, color="red", s=60, zorder=6)
        if len(used) <= LABEL_LIMIT:
            for v in used:
                ax.text(*V[v][:2], f" {v}", fontsize=8,
                        color="red" if v in red or v in seeds else "black")
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.set_xlabel("x")
        ax.set_ylabel("y")
    else:
        # drawn in order, so the element (added last) shows through the faces in front of it
        ax = fig.add_subplot(projection="3d", computed_zorder=False)
        ax.add_collection3d(Poly3DCollection(V[F[faces]], facecolors=colours,
                                             edgecolors=(0.3, 0.3, 0.4, 0.8), linewidths=0.6))
        if lines:
            ax.add_collection3d(Line3DCollection(lines, colors="red", linewidths=2.5, zorder=5))
        if red:
            ax.scatter(*V[red].T, color="red", s=60, depthshade=False, zorder=6)
        if len(used) <= LABEL_LIMIT:
            for v in used:
                ax.text(*V[v], f" {v}", fontsize=8,
                        color="red" if v in red or v in seeds else "black")
        lo, hi = V[used].min(axis=0), V[used].max(axis=0)
        centre, half = (lo + hi) / 2, max(float((hi - lo).max()) / 2, 1e-300)
        for set_lim, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
            set_lim(c - half, c + half)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_zlabel("z")
    ax.set_title("\n".join(textwrap.wrap(title, 80)), fontsize=8)
    fig.tight_layout()
    fig.savefig(path, metadata={"Software": None})
    plt.close(fig)
