"""Meshes given by the user, read and made the one example every property and quantity
takes on them (``ddg-oracle check --mesh``, ``compare``, ``survey``, the test vectors).

A mesh argument is:

* a path to an OBJ, OFF, PLY or STL file (:func:`ddg_oracle.application.meshfiles.read_mesh`);
* a directory: every such file below it (a corpus; one that cannot be read is
  skipped with a note);
* ``pymeshlab:`` -- every sample mesh shipped inside the installed PyMeshLab
  package (``pymeshlab/tests/sample_meshes``), or ``pymeshlab:NAME`` one of them;
* ``cgal:``, ``pyvista:``, ``compas:`` -- every mesh of a corpus fetched once by
  ``ddg-oracle corpus fetch`` (:mod:`ddg_oracle.application.corpus`), or ``cgal:NAME`` one of
  them (its file name or its path in the corpus).  Their polygon faces are triangulated,
  with a note.

The reference needs every vertex to lie in a face: unreferenced vertices are
removed (the remaining ones renumbered in order) with a note.  A mesh the
reference cannot take (non-manifold, a zero-area face, ...) raises the
reference's typed error; named files (and ``pymeshlab:NAME``, ``cgal:NAME``) are then a
usage error (exit 2), the meshes of a set (a directory, ``pymeshlab:``, ``cgal:``) are
skipped with a note.  :class:`MeshExamples` turns a mesh into its
:class:`~ddg_oracle.properties.example.Example` once, with the facts the properties'
requirements read.
"""

from __future__ import annotations

import math
import pickle
from dataclasses import dataclass, field
from pathlib import Path

from ..properties.enclosures import nondegenerate
from ..reference.errors import InputError

from . import corpus
from .meshfiles import MeshFileError, read_mesh

SAMPLE_PREFIX = "pymeshlab:"
#: peak memory of :func:`load` over the file's size: 38x measured on a 4.8 MB OBJ (a
#: frozenset per face and PolyhedralSurface.from_arrays; docs/faults.md), with a margin
LOAD_PEAK = 48
MESH_SUFFIXES = (".obj", ".off", ".ply", ".stl")


# --- mesh arguments -------------------------------------------------------------------------------


def sample_mesh_dir() -> Path:
    """``pymeshlab/tests/sample_meshes`` of the installed PyMeshLab (InputError if absent)."""
    try:
        import pymeshlab
    except ImportError:
        raise InputError("pymeshlab: sample meshes need the pymeshlab package") from None
    d = Path(pymeshlab.__file__).parent / "tests" / "sample_meshes"
    if not d.is_dir():
        raise InputError(f"pymeshlab: no sample meshes in this installation ({d})")
    return d


def sample_meshes() -> list[Path]:
    """Every mesh file PyMeshLab ships (sorted by path)."""
    d = sample_mesh_dir()
    return sorted(p for p in d.rglob("*") if p.suffix.lower() in MESH_SUFFIXES)


def resolve(args: list[str]) -> list[tuple[str, Path, bool]]:
    """(display name, path, strict) per mesh argument; strict: a named file, whose problems
    are errors, vs a sample mesh found by ``pymeshlab:``, which is skipped with a note."""
    out = []
    for a in args:
        if a.startswith(SAMPLE_PREFIX):
            name = a[len(SAMPLE_PREFIX):]
            d = sample_mesh_dir()
            if not name:
                out += [(f"{SAMPLE_PREFIX}{p.relative_to(d)}", p, False) for p in sample_meshes()]
                continue
            p = d / name
            if not p.is_file():
                names = ", ".join(str(q.relative_to(d)) for q in sample_meshes())
                raise MeshFileError(f"{a}: no such sample mesh (PyMeshLab ships {names})")
            out.append((a, p, True))
        elif a.startswith(corpus.PREFIXES):
            out += corpus.resolve(a)                # cgal: every corpus mesh, cgal:NAME one
        elif Path(a).is_dir():
            # a corpus: every mesh file below it, sorted; one that cannot be read is
            # skipped with a note, as a sample mesh is
            found = sorted(p for p in Path(a).rglob("*")
                           if p.suffix.lower() in MESH_SUFFIXES and p.is_file())
            if not found:
                raise MeshFileError(f"{a}: a directory with no mesh file "
                                    f"({', '.join(MESH_SUFFIXES)}) in it")
            out += [(str(p), p, False) for p in found]
        else:
            out.append((a, Path(a), True))
    return out


@dataclass
class MeshInput:
    """A mesh as read, with unreferenced vertices removed (``note`` says so).
    ``triangulation``: F's validated triangulation, pickled (or None): a worker process
    that checks the mesh unpickles it instead of validating F again (898,752 faces: 0.9 s
    instead of 5.7 s; 30 MB where the object takes 660)."""

    name: str
    V: list
    F: list
    note: str | None = None
    triangulation: bytes | None = field(default=None, repr=False, compare=False)

    def surface(self, V=None):
        """The surface of ``V`` (default: the mesh's positions) on F's triangulation."""
        from ..reference.polyhedral import PolyhedralSurface
        V = self.V if V is None else V
        if self.triangulation is None:
            return PolyhedralSurface.from_arrays(V, self.F)
        return PolyhedralSurface(pickle.loads(self.triangulation), V)


def load(name: str, path: Path) -> MeshInput:
    """Read and validate for the reference (typed InputError naming the problem).  A corpus
    mesh (``cgal:``, ``pyvista:``, ``compas:``) has its polygons triangulated (``corpus.triangulate_polygon``), with a
    note.  A file whose reading and validation would not fit in the memory left is refused
    first (:data:`LOAD_PEAK`)."""
    from .files import require_memory
    require_memory(path, LOAD_PEAK, "reading it and validating it for the exact reference")
    if name.startswith(corpus.PREFIXES):
        V, F, polygons = corpus.read_triangulated(path)
    else:
        (V, F), polygons = read_mesh(path), None
    first: dict = {}
    for k, f in enumerate(F):
        key = frozenset(f)
        if key in first and len(key) == 3:
            same = "the same" if list(F[first[key]]) == list(f) else "the opposite"
            raise MeshFileError(f"{name}: faces {first[key]} and {k} are one triangle "
                                f"{sorted(key)} ({same} orientation): a duplicated face")
        first.setdefault(key, k)
    used = sorted({i for f in F for i in f})
    note = None
    if len(used) < len(V):
        new = {v: k for k, v in enumerate(used)}
        note = (f"{len(V) - len(used)} unreferenced vertices removed (first: "
                f"{next(v for v in range(len(V)) if v not in new)}); the rest renumbered in order")
        V = [V[v] for v in used]
        F = [[new[i] for i in f] for f in F]
    if polygons:
        note = polygons if note is None else f"{polygons}; {note}"
    try:
        from ..reference.polyhedral import PolyhedralSurface
        s = PolyhedralSurface.from_arrays(V, F)           # a manifold triangulation
        if not nondegenerate(V, F):
            s.metric()                  # names the zero-area face (exactly), or passes
    except InputError as e:
        after = " (faces numbered after the fan triangulation)" if polygons else ""
        raise type(e)(f"{name}: {e}{after}") from None
    return MeshInput(name, V, F, note, pickle.dumps(s.triangulation))


def as_read_by(mesh: MeshInput, epsilon: float) -> MeshInput:
    """``mesh`` as an implementation declaring machine epsilon ``epsilon`` reads it: its
    coordinates rounded to that precision's input format
    (:func:`~ddg_oracle.properties.precision.format_of`; float32 for 2**-23), so that its
    answers are compared with the exact values of the input it computes with, not with
    those of coordinates it cannot hold (whose rounding alone moved MeshLib's corner
    angles on cgal:fold.off by 6 times their float32 bound).  The same object for float64
    or when every coordinate is representable; InputError when the rounded mesh is no
    longer a valid surface (a face collapsed by the rounding)."""
    from ..properties.precision import format_of, rounded_to
    fmt = format_of(epsilon)
    if fmt.bits == 53:
        return mesh
    V = [[rounded_to(fmt, float(x)) for x in p] for p in mesh.V]
    if any(math.isinf(x) for p in V for x in p):
        raise InputError(f"{mesh.name}: a coordinate is beyond the {fmt.name} range")
    if V == [[float(x) for x in p] for p in mesh.V]:
        return mesh
    try:
        s = mesh.surface(V)
        if not nondegenerate(V, mesh.F):
            s.metric()          # a face the rounding collapsed (cgal-style far meshes), as load
    except InputError as e:
        raise InputError(f"{mesh.name} rounded to {fmt.name} (as this implementation reads "
                         f"it): {e}") from None
    note = f"coordinates rounded to {fmt.name}"
    return MeshInput(mesh.name, V, mesh.F, note if mesh.note is None else f"{mesh.note}; {note}",
                     mesh.triangulation)


def load_all(args: list[str], warn=None) -> list[MeshInput]:
    """Every mesh the arguments name; named files raise, skipped samples go to ``warn``."""
    meshes = []
    for name, path, strict in resolve(args):
        try:
            meshes.append(load(name, path))
        except InputError as e:
            if strict:
                raise
            if warn is not None:
                warn(f"skipped {name}: {e}".replace(f"{name}: {name}: ", f"{name}: "))
            continue
        if meshes[-1].note and warn is not None:
            warn(f"{name}: {meshes[-1].note}")
    return meshes


# --- the example built from one mesh -------------------------------------------------------------


@dataclass
class MeshExamples:
    """The mesh's :class:`~ddg_oracle.properties.example.Example` and its facts, built once
    (its exact values are cached on it, so every property and implementation shares them)."""

    mesh: MeshInput
    _cache: dict = field(default_factory=dict, repr=False)

    def _get(self, key, build):
        if key not in self._cache:
            self._cache[key] = build()
        return self._cache[key]

    @property
    def surface(self):
        from ..properties import memo
        from ..properties.example import surface_key
        from ..properties.views import given_float_positions

        def build():
            s = self.mesh.surface()
            # the example's surface is this one (the same exact positions and faces): its
            # metric is computed once per process
            memo.DRAWN.shared(surface_key(s.positions, self.mesh.F), lambda: s)
            if s.dimension == 3 and self.floats is not None:
                given_float_positions(s, self.floats)
            return s
        return self._get("surface", build)

    @property
    def facts(self) -> dict:
        """What the requirements of a file check (properties.registry.REQUIREMENTS) read."""
        def build():
            t = self.surface.triangulation
            glued = [t.edge_halfedges(e) for e in range(t.n_edges)]
            return dict(n=t.n_vertices, faces=t.n_faces, chi=t.euler_characteristic(),
                        boundary=len(t.boundary_loops()), orientable=t.is_orientable(),
                        oriented=not any(h2 >= 0 and t.reversed_gluing(h) for h, h2 in glued),
                        components=len(t.components()))
        return self._get("facts", build)

    def example(self):
        """The one example every property and quantity takes: the exact surface, its chi and
        (for a connected mesh) its classification."""
        from ..properties.example import Example
        from ..reference.combinatorics import Classification

        def build():
            t, f = self.surface.triangulation, self.facts
            cls = t.classify() if f["components"] == 1 else \
                Classification(f["orientable"], -1, f["boundary"], f["chi"])
            import numpy as np
            F = np.asarray(self.mesh.F, dtype=np.int64).reshape(-1, 3)
            x = Example.of_surface(self.surface, f["chi"], self.mesh.name,
                                   arrays=None if self.floats is None else (self.floats, F))
            return x.with_data(expected=cls)
        return self._get("example", build)

    @property
    def floats(self):
        """The positions as an (n, 3) float64 array when every coordinate is a float (a
        mesh file's: they are the surface's exact positions), else None; read-only."""
        def build():
            import numpy as np
            V = self.mesh.V
            if not V or {type(x) for p in V for x in p} != {float} or \
                    {len(p) for p in V} != {3}:
                return None
            # + 0.0: a file's -0.0 is the exact 0, whose float is +0.0 (the sign of a zero
            # can change what an implementation computes: atan2, 1 / x)
            out = np.asarray(V, dtype=np.float64) + 0.0
            out.flags.writeable = False
            return out
        return self._get("floats", build)


def file_properties(only=None) -> list:
    """The properties that run on a given mesh file (``on_mesh`` declared), in order."""
    from ..properties.registry import all_properties
    return [p for p in all_properties() if p.on_mesh is not None
            and (only is None or p.id in only)]


def run_mesh_properties(examples: MeshExamples, impl, only=None, counterpart=None,
                        convention=None) -> list:
    """Every property that runs on a mesh file (or ``only`` those IDs) on one mesh: not
    applicable, saying why, where the mesh does not meet its requirements."""
    from ..properties.registry import unmet
    from ..properties.runner import NOT_APPLICABLE, Result, run_on_example
    from ..protocol.methods import implementation_name

    results = []
    for p in file_properties(only):
        why = unmet(p.on_mesh, examples.facts)
        if why:
            results.append(Result(p.id, p.name, implementation_name(impl), NOT_APPLICABLE,
                                  source=examples.mesh.name, note=why))
            continue
        results.append(run_on_example(p, impl, examples.example(), examples.mesh.name,
                                      counterpart=counterpart, convention=convention))
    return results
