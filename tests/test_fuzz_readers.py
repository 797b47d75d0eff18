"""Fuzzing the mesh readers and the input validation with Hypothesis.

Random bytes, format-shaped random text, and mutated valid files of every
format and variant (tests/hostile.py ``valid_files``) must give a mesh or one
``MeshFileError``; random arrays must give a surface or an ``InputError``;
nothing else, and never a hang: each example runs under a hard time limit
(:func:`ddg_oracle.properties.profiles.example_time_limit`) and Hypothesis's deadline.

Budget: a fixed multiple of the loaded profile's ``max_examples`` (default
25 -> 200 files per test, ``ci`` 60 -> 480 and derandomized, ``thorough``
1000 -> 8000).
"""

import struct
from datetime import timedelta

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from ddg_oracle.protocol.arrays import checked_arrays
from ddg_oracle.application.meshfiles import MeshFileError, read_mesh
from ddg_oracle.properties.profiles import example_time_limit
from ddg_oracle.reference import PiecewiseFlatSurface, PolyhedralSurface, Triangulation
from ddg_oracle.reference.curvature import angle_defects
from ddg_oracle.reference.errors import InputError
from ddg_oracle.reference.laplacian import cotan_laplacian
from tests.hostile import valid_files

_base = settings.default                    # the profile conftest.py / --hypothesis-profile loaded
FUZZ_FILES = settings(_base, max_examples=8 * _base.max_examples, deadline=timedelta(seconds=5))
FUZZ_ARRAYS = settings(_base, max_examples=4 * _base.max_examples, deadline=timedelta(seconds=5))
HARD_LIMIT = 20.0                           # seconds: a hang fails the example, then shrinks

VALID = valid_files()
EXTENSIONS = (".obj", ".off", ".ply", ".stl")

# Tokens that reach the readers' corners: counts and indices at type limits,
# non-finite numbers, header keywords, separators.
TOKENS = [b"-1", b"0", b"3", b"4", b"nan", b"-inf", b"1e400", b"4294967295", b"2147483648",
          b"99999999999999999999", b"1.5", b"-", b"/", b"//", b"#", b"\n", b"\r\n", b" ", b"\t",
          b"\xff", b"\xef\xbb\xbf", b"\x00\x00\x00\x00", b"v", b"f", b"OFF", b"COFF", b"ply",
          b"format ascii 1.0\n", b"format binary_big_endian 1.0\n",
          b"element vertex 4294967295\n", b"element face 0\n", b"property list uchar float x\n",
          b"property list int int vertex_indices\n", b"property double\n", b"end_header\n",
          b"solid", b"facet", b"outer loop", b"vertex", b"endloop", b"endfacet",
          struct.pack("<I", 2 ** 32 - 1), struct.pack("<I", 1), struct.pack("<i", -1),
          struct.pack("<f", float("nan")), struct.pack("<d", float("inf")),
          struct.pack(">d", float("nan"))]


@pytest.fixture(scope="module")
def scratch(tmp_path_factory):
    return tmp_path_factory.mktemp("fuzz")


def _read(directory, filename: str, data: bytes):
    path = directory / filename
    path.write_bytes(data)
    with example_time_limit(f"read_mesh({filename}, {len(data)} bytes)", seconds=HARD_LIMIT):
        try:
            V, F = read_mesh(path)
        except MeshFileError as e:
            message = str(e)
            assert message.startswith(str(path)) and "\n" not in message, message
            return None
    # a mesh: finite coordinates, triangles, indices in range, at least one face
    assert F and all(len(p) == 3 and all(isinstance(x, float) and x == x and abs(x) != float("inf")
                                         for x in p) for p in V)
    assert all(len(f) == 3 and all(isinstance(i, int) and 0 <= i < len(V) for i in f) for f in F)
    return V, F


@st.composite
def mutated_files(draw):
    """A valid file of some format and variant, with one to four mutations."""
    variant = draw(st.sampled_from(sorted(VALID)))
    filename, original = VALID[variant]
    data = bytearray(original)
    for _ in range(draw(st.integers(1, 4))):
        at = draw(st.integers(0, len(data)))
        op = draw(st.sampled_from(["replace", "insert", "delete", "truncate", "duplicate"]))
        if op == "replace":
            junk = draw(st.binary(min_size=1, max_size=8))
            data[at:at + len(junk)] = junk
        elif op == "insert":
            data[at:at] = draw(st.sampled_from(TOKENS) | st.binary(min_size=1, max_size=8))
        elif op == "delete":
            del data[at:at + draw(st.integers(1, 32))]
        elif op == "truncate":
            del data[at:]
        else:
            data[at:at] = data[at:at + draw(st.integers(1, 64))]
    return filename, bytes(data)


@FUZZ_FILES
@given(mutated_files())
def test_mutated_valid_files_give_a_mesh_or_one_clear_error(scratch, case):
    _read(scratch, *case)


@FUZZ_FILES
@given(st.sampled_from(EXTENSIONS), st.binary(max_size=400))
def test_random_bytes_give_a_mesh_or_one_clear_error(scratch, ext, data):
    _read(scratch, "m" + ext, data)


_PREFIX = {".obj": [b"v 0 0 0\n", b"f 1 2 3\n"], ".off": [b"OFF\n"],
           ".ply": [b"ply\nformat ascii 1.0\n", b"ply\nformat binary_little_endian 1.0\n"],
           ".stl": [b"solid x\nfacet normal 0 0 0\nouter loop\n", b"\0" * 80]}


@FUZZ_FILES
@given(st.sampled_from(EXTENSIONS).flatmap(lambda ext: st.tuples(
    st.just(ext), st.sampled_from(_PREFIX[ext]),
    st.lists(st.sampled_from(TOKENS) | st.binary(max_size=6), max_size=40))))
def test_format_shaped_token_soup_gives_a_mesh_or_one_clear_error(scratch, case):
    ext, prefix, parts = case
    _read(scratch, "m" + ext, prefix + b" ".join(parts))


# PLY headers from its grammar, with wrong words mixed in: element counts,
# property types and list declarations are where a header can lie.
_ply_type = st.sampled_from(["uchar", "int", "uint", "float", "double", "char", "short",
                             "quaternion"])
_ply_name = st.sampled_from(["x", "y", "z", "vertex_indices", "vertex_index", "red"])
_ply_property = st.one_of(
    st.builds("property {} {}".format, _ply_type, _ply_name),
    st.builds("property list {} {} {}".format, _ply_type, _ply_type, _ply_name),
    st.sampled_from(["property", "property float", "property list uchar int", "comment x"]))
_ply_element = st.builds(
    lambda name, count, props: "\n".join([f"element {name} {count}"] + props),
    st.sampled_from(["vertex", "face", "edge"]),
    st.one_of(st.integers(-1, 4), st.just(10 ** 12)),
    st.lists(_ply_property, max_size=4))
_ascii_body = st.lists(st.sampled_from(["0", "1", "2", "3", "-1", "0.5", "nan", "1e999", "x"]),
                       max_size=40).map(" ".join).map(str.encode)


@FUZZ_FILES
@given(st.sampled_from(["ascii", "binary_little_endian", "binary_big_endian", "xml"]),
       st.lists(_ply_element, max_size=3),
       st.one_of(_ascii_body, st.binary(max_size=120)))
def test_ply_headers_from_the_grammar_give_a_mesh_or_one_clear_error(scratch, fmt, elements, body):
    header = "\n".join(["ply", f"format {fmt} 1.0"] + elements + ["end_header", ""])
    _read(scratch, "m.ply", header.encode() + body)


# --- validation --------------------------------------------------------------------

_numbers = st.one_of(
    st.integers(-3, 8), st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([1e300, -1e300, 1e-300, 5e-324, 2.0 ** 1000, 0.5, -0.0]))
_index = st.one_of(st.integers(-2, 7), st.integers(-2, 7), st.integers(-2, 7),
                   st.floats(allow_nan=True), st.booleans(), st.sampled_from([2 ** 63 + 1, "1", None]))


def _rows(element, widths=st.integers(0, 4)):
    # mostly rectangular, sometimes ragged
    return widths.flatmap(lambda w: st.lists(st.one_of(
        st.lists(element, min_size=w, max_size=w), st.lists(element, max_size=5)), max_size=8))


@st.composite
def hostile_arrays(draw):
    """(V, F) as lists, sometimes as numpy arrays of a random dtype."""
    V = draw(_rows(_numbers, st.sampled_from([3, 3, 3, 2, 4, 1])))
    F = draw(_rows(_index, st.sampled_from([3, 3, 3, 2, 4])))
    if draw(st.booleans()):
        try:
            F = np.array(F, dtype=draw(st.sampled_from([None, np.int64, np.uint8, np.float64, object])))
        except (ValueError, TypeError, OverflowError):
            pass                        # not representable: keep the list
    if draw(st.booleans()):
        try:
            with np.errstate(over="ignore"):        # 1e300 as float32 is inf: fine, hostile
                V = np.array(V, dtype=draw(st.sampled_from([None, np.float64, np.float32, object])))
        except (ValueError, TypeError, OverflowError):
            pass
    return V, F


@FUZZ_ARRAYS
@given(hostile_arrays())
def test_random_arrays_give_a_surface_or_an_input_error(arrays):
    V, F = arrays
    with example_time_limit("PolyhedralSurface.from_arrays", seconds=HARD_LIMIT):
        try:
            s = PolyhedralSurface.from_arrays(V, F)
        except InputError:
            pass
        else:
            s.triangulation.validate()
            try:
                angle_defects(s)
                cotan_laplacian(s)
            except InputError:          # zero-area faces: DegenerateFace
                pass
        try:
            Va, Fa = checked_arrays(V, F)
        except InputError:
            pass
        else:
            assert Va.shape[1] == 3 and Fa.shape[1] == 3 and np.isfinite(Va).all()
            assert 0 <= Fa.min() and Fa.max() < len(Va)


@FUZZ_ARRAYS
@given(st.lists(st.tuples(st.integers(0, 6), st.integers(0, 6), st.integers(0, 6)),
                min_size=1, max_size=10),
       st.one_of(st.none(), st.integers(0, 9)))
def test_random_face_lists_give_a_triangulation_or_an_input_error(faces, n):
    with example_time_limit("Triangulation.from_faces", seconds=HARD_LIMIT):
        try:
            t = Triangulation.from_faces(faces, n_vertices=n)
        except InputError:
            return
        t.validate()
        assert t.euler_characteristic() == t.n_vertices - t.n_edges + t.n_faces
        assert sum(map(len, t.boundary_loops())) == sum(
            t.is_boundary_edge(e) for e in range(t.n_edges))


@FUZZ_ARRAYS
@given(st.lists(st.one_of(st.integers(-2, 6), st.fractions(), _numbers), min_size=3, max_size=6),
       st.booleans())
def test_random_lengths_give_a_flat_surface_or_an_input_error(values, squared):
    t = Triangulation.from_faces([[0, 1, 2], [1, 0, 3]])         # 5 edges
    build = PiecewiseFlatSurface if squared else PiecewiseFlatSurface.from_lengths
    with example_time_limit("PiecewiseFlatSurface", seconds=HARD_LIMIT):
        try:
            s = build(t, values)
        except InputError:
            return
        assert len(values) == 5 and all(s.area(f) > 0 for f in range(2))
