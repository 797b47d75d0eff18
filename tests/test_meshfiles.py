"""Mesh files: round trips, and every malformed file gives one clear MeshFileError."""

import struct

import pytest
from hypothesis import given, strategies as st

from ddg_oracle.application.meshfiles import MeshFileError, read_mesh, write_obj
from ddg_oracle.reference import surfaces

V0, F0 = surfaces.icosahedron().to_arrays()


def _off(V, F):
    return "OFF\n%d %d 0\n" % (len(V), len(F)) + "".join(
        " ".join(map(repr, p)) + "\n" for p in V) + "".join(
        "3 %d %d %d\n" % tuple(f) for f in F)


def _ply_binary(V, F):
    head = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty double x\n"
            "property double y\nproperty double z\nelement face %d\n"
            "property list uchar int vertex_indices\nend_header\n" % (len(V), len(F))).encode()
    body = b"".join(struct.pack("<3d", *p) for p in V)
    body += b"".join(struct.pack("<B3i", 3, *f) for f in F)
    return head + body


def _stl_binary(V, F):
    out = b"\0" * 80 + struct.pack("<I", len(F))
    for f in F:
        out += struct.pack("<12fH", 0, 0, 0, *(x for i in f for x in V[i]), 0)
    return out


def _write(tmp_path, name, content):
    p = tmp_path / name
    p.write_bytes(content.encode() if isinstance(content, str) else content)
    return p


def test_round_trips_in_every_format(tmp_path):
    write_obj(tmp_path / "m.obj", V0, F0)
    assert read_mesh(tmp_path / "m.obj") == (V0, F0)
    assert read_mesh(_write(tmp_path, "m.off", _off(V0, F0))) == (V0, F0)
    assert read_mesh(_write(tmp_path, "m.ply", _ply_binary(V0, F0))) == (V0, F0)
    # STL is a soup in float32: icosahedron coordinates (0, +-1, +-8/5) are merged back
    V, F = read_mesh(_write(tmp_path, "m.stl", _stl_binary(V0, F0)))
    assert len(V) == len(V0) and len(F) == len(F0)
    assert [[float(struct.unpack("f", struct.pack("f", x))[0]) for x in V0[i]] for i in F0[0]] == \
        [V[i] for i in F[0]]


BAD = {
    "index out of range": ("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "index out of range"),
    "zero index": ("m.obj", "v 0 0 0\nf 0 1 2\n", "start at 1"),
    "quad": ("m.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n", "4 corners"),
    "text coordinate": ("m.obj", "v 0 zero 0\n", "'zero' is not a number"),
    "nan coordinate": ("m.obj", "v 0 nan 0\n", "non-finite"),
    "float index": ("m.obj", "v 0 0 0\nf 1.5 2 3\n", "not an integer index"),
    "no faces": ("m.obj", "v 0 0 0\n", "no faces"),
    "truncated off": ("m.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n", "truncated"),
    "off without header": ("m.off", "3 1 0\n", "missing the OFF header"),
    "truncated ply": ("m.ply", _ply_binary(V0, F0)[:-7], "truncated"),
    "ply bad format": ("m.ply", b"ply\nformat xml 1.0\nend_header\n", "unsupported PLY format"),
    "truncated stl": ("m.stl", _stl_binary(V0, F0)[:200], "truncated binary STL"),
    "binary junk as obj": ("m.obj", b"\xff\xfe\x00garbage", "not a text file"),
    "unknown extension": ("m.xyz", "1 2 3", "unknown mesh format"),
}


@pytest.mark.parametrize("kind", sorted(BAD))
def test_malformed_files_give_one_clear_error(tmp_path, kind):
    name, content, message = BAD[kind]
    with pytest.raises(MeshFileError, match=message) as err:
        read_mesh(_write(tmp_path, name, content))
    assert str(err.value).startswith(str(tmp_path))          # names the file


def test_missing_file(tmp_path):
    with pytest.raises(MeshFileError, match="cannot read"):
        read_mesh(tmp_path / "absent.obj")


VALID = {"obj": None, "off": _off(V0, F0).encode(), "ply": _ply_binary(V0, F0),
         "stl": _stl_binary(V0, F0)}


@given(st.sampled_from(sorted(VALID)), st.one_of(
    st.binary(max_size=300).map(lambda b: ("random", b)),
    st.tuples(st.integers(0, 10 ** 6), st.binary(min_size=1, max_size=8)).map(lambda t: ("mutate", t))))
def test_fuzz_readers_give_a_mesh_or_a_clear_error(tmp_path_factory, ext, case):
    kind, payload = case
    if kind == "random":
        data = payload
    else:
        base = VALID[ext] or "".join(["v %r %r %r\n" % tuple(p) for p in V0] +
                                     ["f %d %d %d\n" % tuple(i + 1 for i in f) for f in F0]).encode()
        at, junk = payload
        at %= len(base)
        data = base[:at] + junk + base[at + len(junk):]
    p = tmp_path_factory.mktemp("fuzz") / f"m.{ext}"
    p.write_bytes(data)
    try:
        V, F = read_mesh(p)
    except MeshFileError:
        return
    assert F and all(0 <= i < len(V) for f in F for i in f) and all(len(f) == 3 for f in F)


@pytest.mark.parametrize("name,text,words", [
    ("under.obj", "v 1_0 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n", "'1_0' is not a number"),
    ("wide.obj", "v 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 \uff13\n", "not an integer index"),
    ("four.off", "4OFF\n3 1 0\n0 0 0 0\n1 0 0 5\n0 1 0 7\n3 0 1 2\n", "more than 3 dimensions"),
])
def test_a_number_no_writer_means_is_refused_not_read_as_another(tmp_path, name, text, words):
    """Python's float() read "1_0" as 10 and int() a full-width digit as 3; 4OFF's fourth
    coordinate was dropped: each a silently different mesh (a helper's mesh files)."""
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    with pytest.raises(MeshFileError, match=words):
        read_mesh(str(path))


def test_a_ply_comment_naming_end_header_is_a_comment(tmp_path):
    """The reader took the first "end_header" anywhere, and refused this file as faceless."""
    path = tmp_path / "c.ply"
    path.write_text("ply\nformat ascii 1.0\ncomment made with the end_header tool\n"
                    "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                    "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    V, F = read_mesh(str(path))[:2]
    assert len(V) == 3 and [list(f) for f in F] == [[0, 1, 2]]
