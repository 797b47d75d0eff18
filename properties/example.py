"""The one example type every strategy draws and every property checks.

An :class:`Example` is a mesh with exact positions (dyadic where an implementation must see
them exactly), its triangulation, how it was built, and what is known about it by
construction: the classification of its surface (topology properties), its Euler
characteristic (curvature), a distinguished vertex of a vertex star, vertices used by no
face (inserted into the arrays an implementation receives), and drawn data on it (a
boundary set, functions).  :meth:`Example.arrays` is exactly what an implementation
receives; :attr:`Example.surface` the exact surface the reference computes on.

Three constructors say where an example comes from:

* :meth:`Example.of_triangulation`: combinatorics with a known classification (the
  positions matter only to implementations that want points: abstract surfaces such as
  RP^2 get distinct points on the moment curve);
* :meth:`Example.of_surface`: a polyhedral surface with float coordinates and its chi;
* :meth:`Example.of_mesh`: positions and a face list (Laplacian, Delaunay, mesh files).

An example is immutable; the values derived from it alone (float arrays, the exact
surface, exact reference values: :meth:`derived`) are computed once per content in a
process (:mod:`.memo`) and are not pickled (a replayable counterexample stays short).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..reference.combinatorics import Classification, Triangulation
from ..reference.polyhedral import PolyhedralSurface

from . import memo

__all__ = ["Example", "surface_key"]


def surface_key(positions, faces) -> tuple:
    """The :data:`.memo.DRAWN` key of the exact surface of these positions and faces."""
    return ("mesh surface", tuple(positions), tuple(tuple(f) for f in faces))


class _Hashed(tuple):
    """A tuple that computes its hash once: a memo key of exact positions (hashing hundreds
    of Fractions) is looked up several times per example."""

    def __hash__(self):
        try:
            return self._hash
        except AttributeError:
            self._hash = tuple.__hash__(self)
            return self._hash


def _as_arrays(mesh):
    V, F = mesh
    return (np.array(V, dtype=np.float64).reshape(-1, 3), np.array(F, dtype=np.int64).reshape(-1, 3))


@dataclass(frozen=True)
class Example:
    """A drawn (or given) mesh and what is known about it (see the module docstring).

    ``positions``: exact points, one per vertex of the surface; ``faces``: vertex triples.
    ``expected``: the classification known by construction; ``chi``: the Euler
    characteristic of the surface built; ``vertex``, ``kind``, ``params``: the
    distinguished vertex of a vertex star, how it was built ("convex", "planar",
    "saddle", "folded") and what else the construction fixed; ``isolated``: pairs
    (index, position) of vertices used by no face, inserted at those indices of the
    arrays an implementation receives (the reference never sees them); ``boundary``: a
    drawn vertex set a Dirichlet-type property fixes; ``values``, ``second``: drawn
    functions on the vertices.
    """

    positions: tuple
    faces: tuple
    recipe: str = ""
    expected: Classification | None = None
    chi: int | None = None
    vertex: int | None = None
    kind: str | None = None
    params: tuple = ()
    isolated: tuple = ()
    boundary: tuple = ()
    values: tuple = ()
    second: tuple = ()
    _given: Triangulation | None = field(default=None, compare=False, repr=False)
    _cache: dict = field(default_factory=dict, compare=False, repr=False)

    # -- constructors ------------------------------------------------------------------------

    @classmethod
    def of_triangulation(cls, triangulation: Triangulation, positions, expected,
                         recipe: str) -> "Example":
        """Combinatorics whose classification ``expected`` is known by construction."""
        return cls(tuple(positions), tuple(triangulation.faces), recipe, expected=expected,
                   _given=triangulation)

    @classmethod
    def of_surface(cls, surface: PolyhedralSurface, chi: int, recipe: str, arrays=None,
                   **known) -> "Example":
        """A polyhedral surface with float coordinates (an implementation sees them exactly)
        and its Euler characteristic ``chi``; ``known``: vertex, kind, params, isolated;
        ``arrays``: (V, F) as :meth:`arrays` gives them, when the caller has them (a mesh
        file's floats)."""
        x = cls(tuple(surface.positions), tuple(surface.triangulation.faces), recipe, chi=chi,
                _given=surface.triangulation, **known)
        x._cache["surface"] = surface
        if arrays is not None:
            x._cache["arrays"] = arrays
        return x

    @classmethod
    def of_mesh(cls, positions, faces, recipe: str, boundary=(), values=(),
                second=()) -> "Example":
        """Exact (dyadic) positions and a face list, with drawn data on them."""
        return cls(tuple(positions), tuple(tuple(f) for f in faces), recipe, boundary=boundary,
                   values=values, second=second)

    def with_data(self, **changes) -> "Example":
        """The same mesh with other drawn data (``boundary``, ``values``, ``second``,
        ``isolated``, ``recipe``), sharing the exact surface."""
        from dataclasses import replace
        x = replace(self, _cache={}, **changes)
        kept = ("surface", "mesh key") + (() if "isolated" in changes else ("arrays",))
        x._cache.update((k, self._cache[k]) for k in kept if k in self._cache)
        return x

    # -- the mesh ------------------------------------------------------------------------------

    @property
    def n(self) -> int:
        """Vertices of the surface (without the isolated ones)."""
        return len(self.positions)

    @property
    def triangulation(self) -> Triangulation:
        t = self._given
        if t is None:
            t = self._cache.get("triangulation")
            if t is None:
                t = self._cache["triangulation"] = self.surface.triangulation
        return t

    @property
    def surface(self) -> PolyhedralSurface:
        """The exact surface, built once per content in this process (:data:`.memo.DRAWN`; a
        mesh file's is put there by ``application.meshes.MeshExamples``, which built it already)."""
        s = self._cache.get("surface")
        if s is None:
            if self._given is not None:
                s = PolyhedralSurface(self._given, self.positions)
            else:
                s = memo.DRAWN.shared(surface_key(self.positions, self.faces),
                                      lambda: PolyhedralSurface.from_arrays(self.positions,
                                                                            self.faces))
            self._cache["surface"] = s
        return s

    @property
    def vertices(self) -> list[list[float]]:
        return [[float(x) for x in p] for p in self.positions]

    @property
    def layout(self) -> list[int]:
        """Array index of each surface vertex (the identity without isolated vertices)."""
        if "layout" not in self._cache:
            taken = {i for i, _ in self.isolated}
            n = self.n + len(taken)
            self._cache["layout"] = [i for i in range(n) if i not in taken]
        return self._cache["layout"]

    @property
    def surface_mesh(self):
        """(V, F) of the surface alone (no isolated vertices): the reference's indexing."""
        return self.vertices, [list(f) for f in self.faces]

    @property
    def mesh(self):
        """(V, F) as lists: exactly what an implementation receives."""
        if not self.isolated:
            return self.surface_mesh
        at = self.layout
        V = [None] * (len(at) + len(self.isolated))
        for v, p in zip(at, self.vertices):
            V[v] = p
        for i, p in self.isolated:
            V[i] = [float(x) for x in p]
        return V, [[at[v] for v in f] for f in self.faces]

    @property
    def exact_mesh(self):
        """(points, faces) as lists, indexed as :attr:`mesh`, with the exact coordinates
        the floats of :meth:`arrays` were made from: the isolated vertices in their places,
        nothing built (a face list that leaves a vertex unused has no surface to build)."""
        if not self.isolated:
            return [list(p) for p in self.positions], [list(f) for f in self.faces]
        at = self.layout
        P = [None] * (len(at) + len(self.isolated))
        for v, p in zip(at, self.positions):
            P[v] = list(p)
        for i, p in self.isolated:
            P[i] = list(p)
        return P, [[at[v] for v in f] for f in self.faces]

    def arrays(self):
        """(V float64 n x 3, F int64 m x 3), exactly what an implementation receives: new
        arrays each call (a drawn example is shared by the checks of every implementation in
        a worker, and a caller may work in place on them)."""
        if "arrays" not in self._cache:
            self._cache["arrays"] = _as_arrays(self.mesh)
        V, F = self._cache["arrays"]
        return V.copy(), F.copy()

    def surface_arrays(self):
        """The float arrays of the surface alone, indexed as the reference (for bounds):
        new arrays each call, as :meth:`arrays`."""
        if not self.isolated:
            return self.arrays()
        if "surface arrays" not in self._cache:
            self._cache["surface arrays"] = _as_arrays(self.surface_mesh)
        V, F = self._cache["surface arrays"]
        return V.copy(), F.copy()

    # -- values derived from the example alone -----------------------------------------------

    @property
    def mesh_key(self) -> tuple:
        """(positions, faces) as a memo key whose hash is computed once (hashing a million
        Fractions takes seconds, and every check asks for the exact values by it)."""
        if "mesh key" not in self._cache:
            self._cache["mesh key"] = _Hashed((self.positions, self.faces))
        return self._cache["mesh key"]

    @property
    def content(self) -> tuple:
        """What the example is, as a hashable value: exact positions, faces, isolated
        vertices, chi and the distinguished vertex and kind (the key of :meth:`derived`)."""
        if "content" not in self._cache:
            self._cache["content"] = _Hashed((self.positions, self.faces, self.isolated,
                                              self.chi, self.vertex, self.kind, self.params))
        return self._cache["content"]

    def derived(self, name: str, compute):
        """``compute(self)``, computed once per content in this process (:mod:`.memo`):
        for values of the example alone (exact reference values, float geometry of the
        bounds), which every implementation's check of the same example needs."""
        return memo.shared((name, self.content), lambda: compute(self))

    def __getstate__(self):
        # the cache (float arrays, exact values) is rebuilt on demand: not pickled
        state = {k: getattr(self, k) for k in self.__dataclass_fields__}
        state["_cache"] = {}
        return state

    def __setstate__(self, state):
        for k, v in state.items():
            object.__setattr__(self, k, v)

    def __repr__(self) -> str:
        return (f"Example({self.recipe}; V={self.n}, F={len(self.faces)}, "
                f"faces={[list(f) for f in self.faces]})")
