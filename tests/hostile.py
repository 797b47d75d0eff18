"""A corpus of hostile inputs, generated here (no binary files kept in the repository).

Used by tests/test_hostile.py and tests/test_fuzz_readers.py, and importable by
any other test (``from tests.hostile import FILE_CASES, write``), e.g. to check
that the command line answers each bad mesh file with one line and exit 2.

What is an error and what is valid input (the reference's decisions):

- errors at construction (``PolyhedralSurface.from_arrays``,
  ``Triangulation.from_faces``, ``PiecewiseFlatSurface``): anything that is not
  a simplicial surface with finite real coordinates: bad shapes and dtypes,
  non-integer, negative or out-of-range indices, a vertex repeated in a face,
  non-manifold edges and vertices, unreferenced vertices, no faces or no
  vertices, NaN and infinities, lengths violating the strict triangle
  inequality;
- valid at construction, an error where a quantity needs it: zero-area faces
  (collinear or coincident vertices) raise ``DegenerateFace`` from the metric
  and everything built on it (angles, cotan weights, areas), while the
  combinatorics (Euler characteristic, orientability) still answers;
  inconsistently oriented faces are a valid (perhaps non-orientable) surface,
  but signed quantities (dihedral angles, mean curvature) raise an
  ``InputError`` naming the edge;
- valid, computed exactly: huge (1e300) and tiny (1e-300) coordinates;
  positions in R^2 or R^4 (the reference takes any dimension >= 2; the
  adapters take R^3 only).

The adapters' array check (``ddg_oracle.protocol.arrays.checked_arrays``) rejects only what
a library cannot survive or would misread (shapes, dtypes, index range, NaN);
mesh-level problems go through to the library, whose handling is what a check
observes.  ``ArrayCase.adapter_error`` records that.

API
---
``ARRAY_CASES``      (V, F) arrays: :class:`ArrayCase`
``TRIANGULATION_CASES`` face lists with an optional vertex count: :class:`FacesCase`
``LENGTH_CASES``     lengths for ``PiecewiseFlatSurface``: :class:`LengthCase`
``FILE_CASES``       malformed mesh files, ``read_mesh`` raises ``MeshFileError``: :class:`FileCase`
``MESH_FILE_CASES``  well-formed files of bad meshes: ``read_mesh`` reads them,
                     the reference rejects them: :class:`FileCase` with ``error``
``valid_files()``    {variant: (file name, bytes)}: the icosahedron in every
                     format and variant (seeds for mutation fuzzing)
``write(case, dir)`` writes a :class:`FileCase` into ``dir``; returns the path
``obj``, ``off``, ``ply_ascii``, ``ply_binary``, ``stl_ascii``, ``stl_binary``
                     encoders ``(V, F) -> bytes``
"""

from __future__ import annotations

import struct
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ddg_oracle.application.meshfiles import MeshFileError
from ddg_oracle.reference import errors as E
from ddg_oracle.reference import surfaces

# --- base meshes ---------------------------------------------------------------

TET_V, TET_F = surfaces.tetrahedron().to_arrays()       # consistently oriented, outward
ICO_V, ICO_F = surfaces.icosahedron().to_arrays()


def _with(rows, i, row):
    rows = [list(r) for r in rows]
    rows[i] = row
    return rows


# --- arrays ---------------------------------------------------------------------


@dataclass(frozen=True)
class ArrayCase:
    name: str
    V: Any
    F: Any
    error: type | None              # PolyhedralSurface.from_arrays raises this (None: valid)
    words: tuple[str, ...] = ()     # fragments its message contains (case-insensitive)
    adapter_error: type | None = None   # ddg_oracle.protocol.arrays.checked_arrays raises this
    adapter_words: tuple[str, ...] = ()
    geometry_error: type | None = None  # valid input whose metric quantities raise this
    geometry_words: tuple[str, ...] = ()


_NAN, _INF = float("nan"), float("inf")

ARRAY_CASES = (
    ArrayCase("index out of range", TET_V, _with(TET_F, 1, [0, 1, 9]),
              E.IndexOutOfRange, ("face 1, corner 2", "9", "n_vertices = 4"),
              E.IndexOutOfRange, ("face 1, corner 2", "9", "4")),
    ArrayCase("index far out of range (uint64 above 2**63)", TET_V,
              np.array(_with(TET_F, 3, [1, 2, 2 ** 63 + 5]), dtype=np.uint64),
              E.IndexOutOfRange, ("face 3, corner 2", str(2 ** 63 + 5)),
              E.IndexOutOfRange, ("face 3, corner 2", str(2 ** 63 + 5))),
    ArrayCase("negative index", TET_V, _with(TET_F, 1, [0, -1, 3]),
              E.NegativeIndex, ("face 1, corner 1", "-1"),
              E.NegativeIndex, ("face 1, corner 1", "-1")),
    ArrayCase("float index", TET_V, _with(TET_F, 0, [0, 2.5, 1]),
              E.NonIntegerIndex, ("face 0, corner 1", "2.5", "not an integer"),
              E.NonIntegerIndex, ("float64", "face 0, corner 1", "2.5")),
    ArrayCase("integral floats as indices", TET_V, np.array(TET_F, dtype=float),
              E.NonIntegerIndex, ("face 0, corner 0", "float"),
              E.NonIntegerIndex, ("dtype float64", "integers")),
    ArrayCase("NaN index", TET_V, _with(TET_F, 2, [0, _NAN, 2]),
              E.NonIntegerIndex, ("face 2, corner 1", "nan"),
              E.NonIntegerIndex, ("face 2, corner 1", "nan")),
    ArrayCase("boolean indices", TET_V, np.array(TET_F, dtype=bool),
              E.NonIntegerIndex, ("face 0, corner 0", "bool"),
              E.NonIntegerIndex, ("dtype bool",)),
    ArrayCase("string index", TET_V, _with(TET_F, 0, [0, "2", 1]),
              E.NonIntegerIndex, ("face 0, corner 1", "'2'"),
              E.NonIntegerIndex, ("dtype <u", "integers")),
    ArrayCase("repeated index in a face", TET_V, _with(TET_F, 0, [0, 2, 2]),
              E.RepeatedVertexInFace, ("face 0", "repeats vertex 2")),
    ArrayCase("zero-area face (collinear vertices)",
              [[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 0, 1]], TET_F, None,
              geometry_error=E.DegenerateFace,
              geometry_words=("degenerate face 0", "collinear", "zero area")),
    ArrayCase("coincident vertices", [[0, 0, 0], [0, 0, 0], [0, 1, 0], [0, 0, 1]], TET_F, None,
              geometry_error=E.DegenerateFace,
              geometry_words=("vertices 1 and 0", "length zero", "coincident")),
    ArrayCase("NaN coordinate", _with(TET_V, 1, [1, _NAN, 0]), TET_F,
              E.NonFiniteValue, ("nan", "vertex 1, coordinate 1"),
              E.NonFiniteValue, ("nan", "vertex 1, coordinate 1")),
    ArrayCase("infinite coordinate", _with(TET_V, 3, [0, 0, _INF]), TET_F,
              E.NonFiniteValue, ("inf", "vertex 3, coordinate 2"),
              E.NonFiniteValue, ("inf", "vertex 3, coordinate 2")),
    ArrayCase("minus infinity in a float32 array",
              np.array(_with(TET_V, 2, [-_INF, 1, 0]), dtype=np.float32), TET_F,
              E.NonFiniteValue, ("-inf", "vertex 2, coordinate 0"),
              E.NonFiniteValue, ("-inf", "vertex 2, coordinate 0")),
    ArrayCase("non-manifold edge", TET_V + [[1, 1, 1]], [[0, 1, 2], [0, 1, 3], [1, 0, 4]],
              E.NonManifoldEdge, ("non-manifold edge", "(0, 1)", "faces 0, 1, 2")),
    ArrayCase("non-manifold vertex (bowtie)",
              [[0, 0, 0], [1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0]], [[0, 1, 2], [0, 3, 4]],
              E.NonManifoldVertex, ("non-manifold vertex 0", "2 separate fans")),
    ArrayCase("inconsistent orientation", TET_V, _with(TET_F, 0, [0, 1, 2]), None),
    ArrayCase("unreferenced vertex", TET_V + [[5, 5, 5]], TET_F,
              E.UnreferencedVertex, ("vertex 4", "used by no face")),
    ArrayCase("no faces", TET_V, [], E.EmptyMesh, ("no faces",),
              E.EmptyMesh, ("no faces",)),
    ArrayCase("no faces (0 x 3 array)", TET_V, np.zeros((0, 3), dtype=np.int64),
              E.EmptyMesh, ("no faces",), E.EmptyMesh, ("no faces",)),
    ArrayCase("no vertices", [], TET_F, E.EmptyMesh, ("no vertex positions",),
              E.EmptyMesh, ("no vertices",)),
    ArrayCase("faces with 2 columns", TET_V, [[0, 1], [1, 2]],
              E.BadShape, ("face 0", "row of 3 vertex indices"),
              E.BadShape, ("m x 3", "(2, 2)")),
    ArrayCase("faces as a flat list", TET_V, [0, 1, 2],
              E.BadShape, ("face 0", "row of 3 vertex indices"),
              E.BadShape, ("m x 3", "(3,)")),
    ArrayCase("faces as a 3-d array", TET_V, np.zeros((2, 3, 3), dtype=np.int64),
              E.BadShape, ("face 0, corner 0", "m x 3 array"),
              E.BadShape, ("m x 3", "(2, 3, 3)")),
    ArrayCase("faces None", TET_V, None, E.BadShape, ("faces must be",),
              E.BadShape, ("m x 3",)),
    ArrayCase("positions as a flat list", [0.0, 1.0, 2.0, 3.0], TET_F,
              E.BadShape, ("vertex 0", "sequence of coordinates"),
              E.BadShape, ("n x 3", "(4,)")),
    ArrayCase("positions with 1 column", [[0.0], [1.0], [2.0], [3.0]], TET_F,
              E.BadShape, ("vertex 0", "1 coordinate"),
              E.BadShape, ("n x 3", "(4, 1)")),
    ArrayCase("ragged positions", _with(TET_V, 1, [1, 0]), TET_F,
              E.BadShape, ("vertex 1 has 2 coordinates",),
              E.BadShape, ("not a rectangular array",)),
    ArrayCase("positions None", None, TET_F, E.BadShape, ("positions",),
              E.BadShape, ("n x 3",)),
    ArrayCase("text coordinate", _with(TET_V, 0, ["a", 0, 0]), TET_F,
              E.NotANumber, ("vertex 0, coordinate 0", "'a'"),
              E.NotANumber, ("dtype", "real numbers")),
    ArrayCase("complex coordinates", np.array(TET_V, dtype=complex), TET_F,
              E.NotANumber, ("vertex 0, coordinate 0", "complex"),
              E.NotANumber, ("complex128",)),
    ArrayCase("positions in R^2", [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], [[0, 1, 2]], None,
              adapter_error=E.BadShape, adapter_words=("n x 3", "(3, 2)")),
    ArrayCase("positions in R^4", [p + [1.0] for p in TET_V], TET_F, None,
              adapter_error=E.BadShape, adapter_words=("n x 3", "(4, 4)")),
    ArrayCase("huge coordinates (1e300)", [[x * 1e300 for x in p] for p in TET_V], TET_F, None),
    ArrayCase("tiny coordinates (1e-300)", [[x * 1e-300 for x in p] for p in TET_V], TET_F, None),
    ArrayCase("uint8 indices", TET_V, np.array(TET_F, dtype=np.uint8), None),
)


# --- face lists -----------------------------------------------------------------


@dataclass(frozen=True)
class FacesCase:
    name: str
    faces: Any
    n_vertices: Any
    error: type
    words: tuple[str, ...]


TRIANGULATION_CASES = (
    FacesCase("vertex count not an integer", TET_F, 4.5, E.NonIntegerIndex, ("n_vertices", "4.5")),
    FacesCase("negative vertex count", [[0, 1, 2]], -1, E.NegativeIndex, ("n_vertices", "-1")),
    FacesCase("index beyond the vertex count", TET_F, 3, E.IndexOutOfRange,
              ("corner", "3", "n_vertices = 3")),
    # a stray index must not make the reference build tables of 10**12 entries
    FacesCase("stray huge index", [[0, 1, 10 ** 12]], None, E.UnreferencedVertex,
              ("vertex 2", "used by no face", "n_vertices = 1000000000001")),
    FacesCase("huge vertex count", TET_F, 10 ** 15, E.UnreferencedVertex,
              ("vertex 4", "used by no face")),
    FacesCase("faces as a string", "0 1 2", None, E.BadShape, ("faces must be",)),
    FacesCase("faces as a number", 7, None, E.BadShape, ("faces must be", "int")),
)


# --- edge lengths ---------------------------------------------------------------


@dataclass(frozen=True)
class LengthCase:
    name: str
    faces: Any                      # face list of the triangulation
    values: Any                     # one per edge (edges numbered by first occurrence)
    squared: bool                   # True: PiecewiseFlatSurface(t, values); False: from_lengths
    error: type
    words: tuple[str, ...]


_TRI = [[0, 1, 2]]
_TWO = [[0, 1, 2], [1, 0, 3]]       # edges: 01, 12, 20, 03, 31

LENGTH_CASES = (
    LengthCase("violated triangle inequality", _TRI, [1, 1, 5], True,
               E.TriangleInequalityViolated, ("face 0", "strict triangle inequality", "-5")),
    LengthCase("violated in the second face", _TWO, [4, 4, 4, 1, 36], True,
               E.TriangleInequalityViolated, ("face 1", "strict triangle inequality")),
    LengthCase("flat triangle (equality)", _TRI, [1, 1, 2], False,
               E.TriangleInequalityViolated, ("face 0", "16 a^2 = 0")),
    LengthCase("zero squared length", _TRI, [0, 1, 1], True,
               E.TriangleInequalityViolated, ("edge 0", "<= 0")),
    LengthCase("negative squared length", _TRI, [1, -1, 1], True,
               E.TriangleInequalityViolated, ("edge 1", "-1 <= 0")),
    LengthCase("negative length", _TRI, [1, 1, -1], False,
               E.TriangleInequalityViolated, ("edge 2", "length -1 <= 0")),
    LengthCase("NaN length", _TRI, [1, _NAN, 1], False, E.NonFiniteValue, ("nan", "edge 1")),
    LengthCase("infinite squared length", _TRI, [_INF, 1, 1], True,
               E.NonFiniteValue, ("inf", "edge 0")),
    LengthCase("text length", _TRI, [1, "one", 1], False, E.NotANumber, ("edge 1", "'one'")),
    LengthCase("too few lengths", _TRI, [1, 1], True, E.BadShape, ("2 squared lengths for 3 edges",)),
    LengthCase("lengths None", _TRI, None, False, E.BadShape, ("lengths must be a sequence",)),
    LengthCase("lengths as a string", _TRI, "111", True, E.BadShape, ("must be a sequence",)),
)


# --- encoders -------------------------------------------------------------------


def obj(V, F) -> bytes:
    return ("".join("v %r %r %r\n" % tuple(p) for p in V)
            + "".join("f %d %d %d\n" % tuple(i + 1 for i in f) for f in F)).encode()


def off(V, F) -> bytes:
    return ("OFF\n%d %d 0\n" % (len(V), len(F)) + "".join(" ".join(map(repr, p)) + "\n" for p in V)
            + "".join("3 %d %d %d\n" % tuple(f) for f in F)).encode()


def _ply_header(fmt, nv, nf, coord="double", index="int"):
    return ("ply\nformat %s 1.0\ncomment hostile corpus\nelement vertex %d\nproperty %s x\n"
            "property %s y\nproperty %s z\nelement face %d\n"
            "property list uchar %s vertex_indices\nend_header\n"
            % (fmt, nv, coord, coord, coord, nf, index)).encode()


def ply_ascii(V, F) -> bytes:
    return (_ply_header("ascii", len(V), len(F))
            + "".join("%r %r %r\n" % tuple(p) for p in V).encode()
            + "".join("3 %d %d %d\n" % tuple(f) for f in F).encode())


def ply_binary(V, F, big_endian: bool = False) -> bytes:
    o = ">" if big_endian else "<"
    fmt = "binary_big_endian" if big_endian else "binary_little_endian"
    return (_ply_header(fmt, len(V), len(F))
            + b"".join(struct.pack(o + "3d", *p) for p in V)
            + b"".join(struct.pack(o + "B3i", 3, *f) for f in F))


def stl_binary(V, F, header: bytes = b"") -> bytes:
    out = header.ljust(80, b"\0")[:80] + struct.pack("<I", len(F))
    for f in F:
        out += struct.pack("<12fH", 0, 0, 0, *(x for i in f for x in V[i]), 0)
    return out


def stl_ascii(V, F) -> bytes:
    s = "solid hostile\n"
    for f in F:
        s += ("facet normal 0 0 0\n outer loop\n"
              + "".join("  vertex %r %r %r\n" % tuple(V[i]) for i in f)
              + " endloop\nendfacet\n")
    return (s + "endsolid hostile\n").encode()


def valid_files() -> dict[str, tuple[str, bytes]]:
    """The icosahedron in every supported format and variant: {variant: (file name, bytes)}."""
    V, F = ICO_V, ICO_F
    return {
        "obj": ("m.obj", obj(V, F)),
        "off": ("m.off", off(V, F)),
        "off-counts-on-the-header-line": ("m.off", off(V, F).replace(b"OFF\n", b"OFF ", 1)),
        "ply-ascii": ("m.ply", ply_ascii(V, F)),
        "ply-binary-le": ("m.ply", ply_binary(V, F)),
        "ply-binary-be": ("m.ply", ply_binary(V, F, big_endian=True)),
        "stl-ascii": ("m.stl", stl_ascii(V, F)),
        "stl-binary": ("m.stl", stl_binary(V, F)),
        # binary STL whose header starts like an ASCII one (common in the wild)
        "stl-binary-solid-header": ("m.stl", stl_binary(V, F, b"solid exported facet normals")),
    }


# --- files ----------------------------------------------------------------------


@dataclass(frozen=True)
class FileCase:
    name: str
    filename: str
    content: bytes
    words: tuple[str, ...] = ()     # fragments of the message (case-insensitive)
    error: type = MeshFileError     # MESH_FILE_CASES: the reference's error instead


def _b(s) -> bytes:
    return s if isinstance(s, bytes) else s.encode()


_TRIANGLE = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
_OFF_HEAD = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n"
_PLYB = ply_binary(ICO_V, ICO_F)
_STLB = stl_binary(ICO_V, ICO_F)
_ONE = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]


def _ply_tri(header_extra="", body=b"", fmt="ascii", vertex_props=("float x", "float y", "float z"),
             face_prop="list uchar int vertex_indices", nv=3, nf=1):
    head = ("ply\nformat %s 1.0\nelement vertex %d\n" % (fmt, nv)
            + "".join("property %s\n" % p for p in vertex_props)
            + "element face %d\nproperty %s\n%send_header\n" % (nf, face_prop, header_extra))
    return head.encode() + _b(body)


_PLY_TRI_BODY = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"

FILE_CASES = tuple(FileCase(n, f, _b(c), w) for n, f, c, w in (
    # OBJ
    ("obj: index out of range", "m.obj", _TRIANGLE + "f 1 2 4\n", ("face 0", "vertex 3", "out of range")),
    ("obj: zero index", "m.obj", _TRIANGLE + "f 0 1 2\n", ("line 4", "start at 1")),
    ("obj: relative index before the first vertex", "m.obj", _TRIANGLE + "f -1 -2 -4\n",
     ("line 4", "relative index -4")),
    ("obj: quad", "m.obj", _TRIANGLE + "v 1 1 0\nf 1 2 4 3\n", ("line 5", "4 corners")),
    ("obj: segment", "m.obj", _TRIANGLE + "f 1 2\n", ("line 4", "2 corners")),
    ("obj: text coordinate", "m.obj", "v 0 zero 0\n", ("line 1", "'zero' is not a number")),
    ("obj: NaN coordinate", "m.obj", "v 0 nan 0\n", ("line 1", "non-finite")),
    ("obj: overflowing coordinate", "m.obj", "v 0 1e400 0\n", ("line 1", "non-finite")),
    ("obj: vertex with 2 coordinates", "m.obj", "v 0 1\n", ("line 1", "3 coordinates")),
    ("obj: float index", "m.obj", _TRIANGLE + "f 1.5 2 3\n", ("line 4", "not an integer index")),
    ("obj: no faces", "m.obj", _TRIANGLE, ("no faces",)),
    ("obj: empty file", "m.obj", "", ("no faces",)),
    ("obj: binary junk", "m.obj", b"\xff\xfe\x00garbage", ("not a text file", "byte 0")),
    # OFF
    ("off: missing header", "m.off", "3 1 0\n", ("line 1", "missing the off header")),
    ("off: empty file", "m.off", "", ("missing the off header",)),
    ("off: truncated after the header", "m.off", "OFF\n", ("truncated after the header",)),
    ("off: truncated body", "m.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n", ("truncated", "3 vertices")),
    ("off: negative count", "m.off", "OFF\n-3 1 0\n", ("line 2", "negative count -3")),
    ("off: count not an integer", "m.off", "OFF\nthree 1 0\n", ("line 2", "'three'")),
    ("off: one count only", "m.off", "OFF\n3\n", ("line 2", "expected 2 counts")),
    ("off: quad", "m.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
     ("line 7", "4 corners")),
    ("off: face promises more corners", "m.off", _OFF_HEAD + "3 0 1\n", ("line 6", "promises 3")),
    ("off: negative corner count", "m.off", _OFF_HEAD + "-3 0 1 2\n", ("line 6", "negative count")),
    ("off: NaN coordinate", "m.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n",
     ("line 4", "non-finite")),
    ("off: index out of range", "m.off", _OFF_HEAD + "3 0 1 3\n", ("face 0", "out of range")),
    # PLY
    ("ply: not a ply file", "m.ply", "solid x\n", ("not a ply file",)),
    ("ply: unsupported format", "m.ply", b"ply\nformat xml 1.0\nend_header\n",
     ("unsupported ply format", "'xml'")),
    ("ply: truncated binary", "m.ply", _PLYB[:-7], ("truncated at byte", "face 19")),
    ("ply: truncated ascii", "m.ply", _ply_tri(body="0 0 0\n1 0 0\n0 1 0\n3 0 1\n"),
     ("truncated while reading face 0",)),
    ("ply: negative element count", "m.ply", _ply_tri(nv=-3), ("line 3", "negative count -3")),
    ("ply: element count larger than the file", "m.ply", _ply_tri(nv=10 ** 12),
     ("1000000000000 vertex rows", "cannot fit")),
    ("ply: property line without a name", "m.ply", _ply_tri(header_extra="property float\n"),
     ("malformed property line",)),
    ("ply: unknown property type", "m.ply", _ply_tri(header_extra="property quaternion w\n"),
     ("unknown property type",)),
    ("ply: property before any element", "m.ply", b"ply\nformat ascii 1.0\nproperty float x\nend_header\n",
     ("line 3", "property before any element")),
    ("ply: float vertex indices", "m.ply",
     _ply_tri(face_prop="list uchar float vertex_indices", body=_PLY_TRI_BODY),
     ("vertex_indices must be a list of integers", "float")),
    ("ply: vertex indices not a list", "m.ply", _ply_tri(face_prop="int vertex_indices"),
     ("vertex_indices must be a list of integers",)),
    ("ply: vertex without z", "m.ply", _ply_tri(vertex_props=("float x", "float y")),
     ("vertex element lacks property 'z'",)),
    ("ply: coordinate declared as a list", "m.ply",
     _ply_tri(vertex_props=("float x", "float y", "list uchar float z")),
     ("vertex property 'z' is a list",)),
    ("ply: face without vertex_indices", "m.ply", _ply_tri(face_prop="list uchar int corners"),
     ("face element lacks vertex_indices",)),
    ("ply: negative list length", "m.ply",
     _ply_tri(fmt="binary_little_endian", face_prop="list char int vertex_indices",
              body=struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<b", -3)),
     ("face 0", "bad list length -3")),
    ("ply: text in an ascii number", "m.ply", _ply_tri(body="0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n"),
     ("vertex 1", "'zero' is not a number")),
    ("ply: NaN in binary", "m.ply",
     _ply_tri(fmt="binary_little_endian",
              body=struct.pack("<9f", 0, 0, 0, 1, float("nan"), 0, 0, 1, 0) + struct.pack("<B3i", 3, 0, 1, 2)),
     ("non-finite value in vertex 1",)),
    ("ply: quad", "m.ply", _ply_tri(body="0 0 0\n1 0 0\n0 1 0\n4 0 1 2 2\n"), ("face 0", "4 corners")),
    ("ply: index out of range", "m.ply", _ply_tri(body="0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"),
     ("face 0", "vertex 7", "out of range")),
    # STL
    ("stl: truncated binary", "m.stl", _STLB[:200], ("truncated binary stl", "20 triangles")),
    ("stl: shorter than its header", "m.stl", b"\0" * 50, ("truncated binary stl", "50 bytes")),
    ("stl: no triangles", "m.stl", b"\0" * 80 + struct.pack("<I", 0), ("no faces",)),
    ("stl: NaN in binary", "m.stl",
     b"\0" * 80 + struct.pack("<I", 1) + struct.pack("<12fH", 0, 0, 0, 0, 0, 0, 1, float("nan"), 0, 0, 1, 0, 0),
     ("triangle 0", "non-finite")),
    ("stl: ascii truncated inside a facet", "m.stl",
     "solid x\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n", ("truncated inside a facet",)),
    ("stl: ascii facet with 4 vertices", "m.stl",
     "solid x\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
     "vertex 1 1 0\nendloop\nendfacet\nendsolid\n", ("line 8", "4 corners")),
    ("stl: ascii vertex with 2 coordinates", "m.stl",
     "solid x\nfacet normal 0 0 0\nouter loop\nvertex 0 0\n", ("line 4", "3 coordinates")),
    ("stl: ascii NaN", "m.stl",
     "solid x\nfacet normal 0 0 0\nouter loop\nvertex 0 nan 0\n", ("line 4", "non-finite")),
    # any format
    ("unknown extension", "m.xyz", "1 2 3", ("unknown mesh format", "'.xyz'")),
))

MESH_FILE_CASES = (
    FileCase("obj: repeated vertex in a face", "m.obj", _b(_TRIANGLE + "f 1 2 2\n"),
             ("face 0", "repeats vertex 1"), E.RepeatedVertexInFace),
    FileCase("obj: non-manifold edge", "m.obj",
             _b(obj(TET_V + [[1.0, 1.0, 1.0]], [[0, 1, 2], [0, 1, 3], [1, 0, 4]])),
             ("non-manifold edge", "(0, 1)"), E.NonManifoldEdge),
    FileCase("obj: unreferenced vertex", "m.obj", _b(_TRIANGLE + "v 5 5 5\nf 1 2 3\n"),
             ("vertex 3", "used by no face"), E.UnreferencedVertex),
    FileCase("off: non-manifold vertex", "m.off",
             off([[0.0, 0, 0], [1.0, 0, 0], [0.0, 1, 0], [-1.0, 0, 0], [0.0, -1, 0]],
                 [[0, 1, 2], [0, 3, 4]]), ("non-manifold vertex 0",), E.NonManifoldVertex),
    # an STL triangle with two equal corners: merging makes the face repeat a vertex
    FileCase("stl: degenerate triangle", "m.stl", stl_binary(_ONE + [[0.0, 0.0, 0.0]], [[0, 1, 3]]),
             ("face 0", "repeats vertex 0"), E.RepeatedVertexInFace),
)


def write(case: FileCase, directory) -> Path:
    """Write ``case`` into ``directory`` under its file name; returns the path."""
    path = Path(directory) / case.filename
    path.write_bytes(case.content)
    return path


# --- paths that must not hang or exhaust memory --------------------------------------------------
# what `ddg-oracle check --mesh PATH` and `ddg-oracle compare PATH` must answer with one line on
# stderr and exit 2, within seconds and a few hundred MB (tests/test_hostile.py)


def hostile_paths(directory) -> dict[str, tuple[str, str]]:
    """{what: (path, words the one-line error must contain)}, made in ``directory``."""
    import os
    directory = Path(directory)
    fifo = directory / "pipe.obj"
    os.mkfifo(fifo)
    zero = directory / "x.obj"
    zero.symlink_to("/dev/zero")
    (directory / "dir.ply").mkdir()
    empty = directory / "empty-elements.ply"
    empty.write_bytes(b"ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
                      b"property float y\nproperty float z\nelement face 0\n"
                      b"property list uchar int vertex_indices\nend_header\n0 0 0\n3 0 1 2\n")
    noprop = directory / "no-properties.ply"
    noprop.write_bytes(b"ply\nformat ascii 1.0\nelement junk 50\nelement vertex 3\n"
                       b"property float x\nproperty float y\nproperty float z\nend_header\n")
    dup = directory / "duplicated-face.obj"
    dup.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 2 1 3\n")
    return {
        "/dev/urandom": ("/dev/urandom", "a device"),
        "a FIFO": (str(fifo), "a FIFO"),
        "/dev/zero named x.obj": (str(zero), "a device"),
        "a directory": (str(directory / "dir.ply"), "a directory"),
        "empty PLY elements with a body": (str(empty), "no faces"),
        "a PLY element with rows and no property": (str(noprop), "no property"),
        "a duplicated (opposite) face": (str(dup), "faces 0 and 2 are one triangle"),
    }
