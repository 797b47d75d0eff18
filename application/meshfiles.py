"""Reading triangle meshes from OBJ, OFF, PLY (ascii, binary) and STL (ascii, binary).

Coordinates are parsed as float64, the numbers a library reading the same file
sees (they are then exact dyadic rationals for the reference).  Every problem
raises :class:`MeshFileError` naming the file, the line (or byte offset) and
what is wrong; never a traceback for expected bad input.  Polygons with more
than three corners are rejected rather than silently triangulated (a fan
triangulation would change the mesh under test).  STL stores a triangle soup:
vertices with equal coordinates are merged (so -0.0 and 0.0 are one vertex),
in order of first appearance.  A binary STL whose 80-byte header happens to
start with ``solid`` is recognised by its size (84 + 50 x triangles).

What a reader checks is the file: syntax, counts, truncation, finite numbers,
integer indices in range, triangles only, at least one face.  What it does not
check is the mesh: repeated vertices in a face, non-manifold edges or
vertices, unreferenced vertices and zero-area faces come through, and the
reference rejects them (``PolyhedralSurface.from_arrays`` raises the typed
error naming the face or vertex).  Every error is a :class:`MeshFileError`
(an :class:`~ddg_oracle.reference.errors.InputError`); the readers are fuzzed with random
and mutated files (tests/test_fuzz_readers.py).
"""

from __future__ import annotations

import math
import os
import re
import struct
from pathlib import Path

from ..reference.errors import InputError


class MeshFileError(InputError):
    """A mesh file that cannot be read: which file, where, and why."""


#: Environment variable: the largest mesh file read, in bytes (``2G``, ``500M``, ...).
SIZE_ENV = "DDG_MESH_SIZE_LIMIT"
DEFAULT_SIZE_LIMIT = 2 << 30


def size_limit() -> int:
    """Bytes a mesh file may have: ``$DDG_MESH_SIZE_LIMIT`` (``2G``, ``500M``, ``123``), else
    2 GiB."""
    raw = os.environ.get(SIZE_ENV, "").strip().upper()
    if not raw:
        return DEFAULT_SIZE_LIMIT
    units = {"K": 1 << 10, "M": 1 << 20, "G": 1 << 30, "T": 1 << 40}
    number, unit = (raw[:-1], units[raw[-1]]) if raw[-1] in units else (raw, 1)
    try:
        return int(float(number) * unit)
    except ValueError:
        raise MeshFileError(f"{SIZE_ENV}={raw!r} is not a size (use e.g. 2G, 500M)") from None


def read_mesh(path) -> tuple[list[list[float]], list[list[int]]]:
    """(V, F) of a mesh file, by its extension (.obj, .off, .ply, .stl).

    Only regular files are read (a device such as /dev/urandom, a FIFO or a
    directory is refused before it is opened: reading one may never end), and
    only up to :func:`size_limit` bytes; the readers then make progress on every
    line and check every count against the file's size before allocating."""
    from .files import read_bytes
    path = Path(path)
    limit = size_limit()
    data = read_bytes(path, "a mesh file", limit, MeshFileError,
                      limit_hint=f"raise it with {SIZE_ENV}=SIZE")
    readers = {".obj": _obj, ".off": _off, ".ply": _ply, ".stl": _stl}
    reader = readers.get(path.suffix.lower())
    if reader is None:
        raise MeshFileError(f"{path}: unknown mesh format {path.suffix!r} "
                            f"(use one of {', '.join(readers)})")
    V, F = reader(data, str(path))
    _check(V, F, str(path))
    return V, F


#: characters (bytes) split at a time: the lines (tokens) of one chunk are alive at once, not
#: the file's (a list of a 100 MB file's lines takes about twice its size)
_CHUNK = 1 << 20


def _text(data: bytes, name: str):
    """The lines of ``data`` as ``str.splitlines`` gives them, one chunk at a time."""
    try:
        text = data.decode("utf-8-sig")                  # -sig: drop a byte order mark
    except UnicodeDecodeError as e:
        raise MeshFileError(f"{name}: not a text file (byte {e.start} is not UTF-8)") from None
    return _lines(text)


def _lines(text: str):
    start = 0
    while start < len(text):
        end = text.find("\n", start + _CHUNK)     # a chunk ends with a line: the same lines
        end = len(text) if end < 0 else end + 1
        yield from text[start:end].splitlines()
        start = end


def _shared(i: int, ints: list) -> int:
    """Vertex index ``i`` as the one int object ``ints[i]`` when in range: a face holds 3
    pointers, not 3 new ints (28 bytes each beyond 256), a third of a mesh's memory."""
    return ints[i] if 0 <= i < len(ints) else i


#: a number as C's strtod and the file formats write it, in ASCII: Python's float() also
#: takes "1_0" (as 10), full-width digits and surrounding spaces, which no writer means
_NUMBER = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?\Z")
_INTEGER = re.compile(r"[+-]?[0-9]+\Z")
_NON_FINITE = re.compile(r"[+-]?(?:inf|infinity|nan)\Z", re.IGNORECASE)


def _float(tok: str, name: str, where: str) -> float:
    if _NON_FINITE.match(tok):
        raise MeshFileError(f"{name}:{where}: non-finite coordinate {tok!r}")
    if not _NUMBER.match(tok):
        raise MeshFileError(f"{name}:{where}: {tok!r} is not a number")
    x = float(tok)
    if not math.isfinite(x):
        raise MeshFileError(f"{name}:{where}: non-finite coordinate {tok!r}")
    return x


def _int(tok: str, name: str, where: str) -> int:
    if not _INTEGER.match(tok):
        raise MeshFileError(f"{name}:{where}: {tok!r} is not an integer index")
    return int(tok)


def _triangle(corners: list[int], name: str, where: str) -> list[int]:
    if len(corners) != 3:
        raise MeshFileError(f"{name}:{where}: a face with {len(corners)} corners; "
                            "only triangles are accepted")
    return corners


def _obj(data: bytes, name: str):
    V, F, ints = [], [], []
    for n, line in enumerate(_text(data, name), 1):
        parts = line.split("#", 1)[0].split()
        if not parts:
            continue
        where = f"line {n}"
        if parts[0] == "v":
            if len(parts) < 4:
                raise MeshFileError(f"{name}:{where}: a vertex needs 3 coordinates")
            V.append([_float(t, name, where) for t in parts[1:4]])
            ints.append(len(ints))
        elif parts[0] == "f":
            corners = []
            for t in parts[1:]:
                i = _int(t.split("/")[0], name, where)
                if i == 0:
                    raise MeshFileError(f"{name}:{where}: OBJ indices start at 1, got 0")
                if i < -len(V):
                    raise MeshFileError(f"{name}:{where}: relative index {i} points before the "
                                        f"first vertex ({len(V)} vertices so far)")
                corners.append(_shared(i - 1 if i > 0 else len(V) + i, ints))  # < 0: relative
            F.append(_triangle(corners, name, where))
    return V, F


def _count(tok: str, name: str, where: str) -> int:
    n = _int(tok, name, where)
    if n < 0:
        raise MeshFileError(f"{name}:{where}: negative count {n}")
    return n


def _header_counts(tokens, name, where, k):
    if len(tokens) < k:
        raise MeshFileError(f"{name}:{where}: expected {k} counts, got {len(tokens)}")
    return [_count(t, name, where) for t in tokens[:k]]


def _off(data: bytes, name: str):
    def lines():                               # (line number, tokens) of non-empty lines
        for n, line in enumerate(_text(data, name), 1):
            p = line.split("#", 1)[0].split()
            if p:
                yield n, p
    rest = lines()
    n0, head = next(rest, (0, [""]))
    if not head[0].endswith("OFF"):
        raise MeshFileError(f"{name}:line 1: missing the OFF header")
    if "4" in head[0] or head[0].startswith("n"):
        # 4OFF, nOFF: points of R^4 or R^n (reading three coordinates dropped the others)
        raise MeshFileError(f"{name}:line 1: {head[0]} holds points of more than 3 "
                            "dimensions: not a surface in R^3")
    skip = 1                                   # lines before the body: the header
    if len(head) > 1:                          # "OFF nv nf ne" on one line
        n, counts = n0, head[1:]
    else:
        n, counts = next(rest, (None, None))
        skip = 2
        if counts is None:
            raise MeshFileError(f"{name}: truncated after the header")
    nv, nf = _header_counts(counts, name, f"line {n}", 2)[:2]
    n_body = sum(1 for _ in lines()) - skip    # counted first, as a list's length was
    if n_body < nv + nf:
        raise MeshFileError(f"{name}: truncated: header promises {nv} vertices and {nf} faces, "
                            f"file has {n_body} data lines")
    body = lines()
    for _ in range(skip):
        next(body)
    V = []
    for _, (n, p) in zip(range(nv), body):
        if len(p) < 3:
            raise MeshFileError(f"{name}:line {n}: a vertex needs 3 coordinates")
        V.append([_float(t, name, f"line {n}") for t in p[:3]])
    F, ints = [], list(range(len(V)))
    for _, (n, p) in zip(range(nf), body):
        k = _count(p[0], name, f"line {n}")
        if len(p) < k + 1:
            raise MeshFileError(f"{name}:line {n}: face promises {k} corners, has {len(p) - 1}")
        F.append(_triangle([_shared(_int(t, name, f"line {n}"), ints) for t in p[1:k + 1]],
                           name, f"line {n}"))
    return V, F


_PLY_TYPES = {"char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h", "int16": "h",
              "ushort": "H", "uint16": "H", "int": "i", "int32": "i", "uint": "I",
              "uint32": "I", "float": "f", "float32": "f", "double": "d", "float64": "d"}


def _ply(data: bytes, name: str):
    # the line that is "end_header" (a comment may mention the word before it)
    found = re.search(rb"^end_header[ \t]*\r?$", data, re.MULTILINE)
    end = found.start() if found else -1
    if not data.startswith(b"ply") or end < 0:
        raise MeshFileError(f"{name}: not a PLY file (missing 'ply' or 'end_header')")
    header = data[:end].decode("ascii", "replace").splitlines()
    body_start = data.index(b"\n", end) + 1 if b"\n" in data[end:] else len(data)
    fmt = None
    elements = []                              # [name, count, [(prop, type, list types)]]
    for n, line in enumerate(header, 1):
        p = line.split()
        if not p:
            continue
        if p[0] == "format":
            fmt = p[1] if len(p) > 1 else None
        elif p[0] == "element":
            if len(p) != 3:
                raise MeshFileError(f"{name}:line {n}: malformed element line")
            count = _count(p[2], name, f"line {n}")
            if count > len(data):       # every row takes at least one byte or token
                raise MeshFileError(f"{name}:line {n}: {count} {p[1]} rows cannot fit in "
                                    f"a file of {len(data)} bytes (truncated?)")
            elements.append([p[1], count, []])
        elif p[0] == "property":
            if not elements:
                raise MeshFileError(f"{name}:line {n}: property before any element")
            if len(p) < 3:
                raise MeshFileError(f"{name}:line {n}: malformed property line {line!r}")
            if p[1] == "list":
                if len(p) != 5 or p[2] not in _PLY_TYPES or p[3] not in _PLY_TYPES:
                    raise MeshFileError(f"{name}:line {n}: malformed list property")
                elements[-1][2].append((p[4], p[3], p[2]))
            else:
                if len(p) != 3 or p[1] not in _PLY_TYPES:
                    raise MeshFileError(f"{name}:line {n}: unknown property type {line!r}")
                elements[-1][2].append((p[2], p[1], None))
    if fmt not in ("ascii", "binary_little_endian", "binary_big_endian"):
        raise MeshFileError(f"{name}: unsupported PLY format {fmt!r}")
    for ename, count, props in elements:
        if count and not props:
            raise MeshFileError(f"{name}: element {ename!r} has {count} rows but no property: "
                                "its rows take no bytes (malformed header)")
        kinds = {pname: (t, list_t) for pname, t, list_t in props}
        if ename == "vertex" and count:
            for axis in "xyz":
                if axis not in kinds:
                    raise MeshFileError(f"{name}: vertex element lacks property '{axis}'")
                if kinds[axis][1] is not None:
                    raise MeshFileError(f"{name}: vertex property '{axis}' is a list, "
                                        "expected a number")
        if ename == "face" and count:
            idx = kinds.get("vertex_indices", kinds.get("vertex_index"))
            if idx is None:
                raise MeshFileError(f"{name}: face element lacks vertex_indices")
            if idx[1] is None or _PLY_TYPES[idx[0]] in "fd":
                raise MeshFileError(f"{name}: face vertex_indices must be a list of integers, "
                                    f"declared as {'list ' + idx[1] + ' ' if idx[1] else ''}"
                                    f"{idx[0]}")
    if fmt == "ascii":
        def ascii_tokens(start):               # a chunk at a time, cut after a newline
            while start < len(data):
                end = data.find(b"\n", start + _CHUNK)
                end = len(data) if end < 0 else end + 1
                yield from data[start:end].decode("ascii", "replace").split()
                start = end
        tokens = ascii_tokens(body_start)
        def read(t, what):
            try:
                tok = next(tokens)
            except StopIteration:
                raise MeshFileError(f"{name}: truncated while reading {what}") from None
            return float(_float(tok, name, what)) if _PLY_TYPES[t] in "fd" else _int(tok, name, what)
    else:
        order = "<" if fmt == "binary_little_endian" else ">"
        pos = [body_start]
        def read(t, what):
            code = order + _PLY_TYPES[t]
            size = struct.calcsize(code)
            if pos[0] + size > len(data):
                raise MeshFileError(f"{name}: truncated at byte {pos[0]} while reading {what}")
            (x,) = struct.unpack_from(code, data, pos[0])
            pos[0] += size
            if isinstance(x, float) and not math.isfinite(x):
                raise MeshFileError(f"{name}: non-finite value in {what}")
            return x
    V, F, ints = [], [], []
    for ename, count, props in elements:
        for r in range(count):
            what = f"{ename} {r}"
            row = {}
            for pname, t, list_t in props:
                if list_t is None:
                    row[pname] = read(t, what)
                else:
                    k = read(list_t, what)
                    if not isinstance(k, int) or k < 0 or k > 1 << 20:
                        raise MeshFileError(f"{name}: {what}: bad list length {k}")
                    row[pname] = [read(t, what) for _ in range(k)]
            if ename == "vertex":
                V.append([float(row["x"]), float(row["y"]), float(row["z"])])
            elif ename == "face":      # properties checked against the header above
                idx = row.get("vertex_indices", row.get("vertex_index"))
                if len(ints) < len(V):
                    ints = list(range(len(V)))
                F.append(_triangle([_shared(i, ints) for i in idx], name, what))
    return V, F


def _stl(data: bytes, name: str):
    binary_size = len(data) >= 84 and len(data) == 84 + 50 * struct.unpack_from("<I", data, 80)[0]
    if data[:5] == b"solid" and b"facet" in data[:1024] and not binary_size:
        return _stl_ascii(data, name)
    if len(data) < 84:
        raise MeshFileError(f"{name}: truncated binary STL ({len(data)} bytes, header is 84)")
    (n,) = struct.unpack_from("<I", data, 80)
    if len(data) < 84 + 50 * n:
        raise MeshFileError(f"{name}: truncated binary STL: {n} triangles need "
                            f"{84 + 50 * n} bytes, file has {len(data)}")
    soup = []
    for t in range(n):
        vals = struct.unpack_from("<12f", data, 84 + 50 * t)
        corners = [vals[3:6], vals[6:9], vals[9:12]]
        for c in corners:
            if not all(math.isfinite(x) for x in c):
                raise MeshFileError(f"{name}: triangle {t} has a non-finite coordinate")
        soup.append(corners)
    return _merge(soup)


def _stl_ascii(data: bytes, name: str):
    soup, current = [], []
    for n, line in enumerate(_text(data, name), 1):
        p = line.split()
        if p[:1] == ["vertex"]:
            if len(p) != 4:
                raise MeshFileError(f"{name}:line {n}: a vertex needs 3 coordinates")
            current.append(tuple(_float(t, name, f"line {n}") for t in p[1:]))
        elif p[:1] == ["endloop"]:
            _triangle(list(range(len(current))), name, f"line {n}")
            soup.append(current)
            current = []
    if current:
        raise MeshFileError(f"{name}: truncated inside a facet")
    return _merge(soup)


def _merge(soup):
    index, V, F = {}, [], []
    for tri in soup:
        face = []
        for c in tri:
            key = tuple(c)
            if key not in index:
                index[key] = len(V)
                V.append([float(x) for x in c])
            face.append(index[key])
        F.append(face)
    return V, F


def _check(V, F, name: str) -> None:
    if not F:
        raise MeshFileError(f"{name}: no faces")
    for f, face in enumerate(F):
        for i in face:
            if not 0 <= i < len(V):
                raise MeshFileError(f"{name}: face {f} uses vertex {i}, but there are "
                                    f"{len(V)} vertices (index out of range)")


def write_obj(path, V, F) -> None:
    """Write (V, F) as OBJ with repr floats (round-trips exactly)."""
    with open(path, "w", encoding="utf-8") as fh:
        for p in V:
            fh.write("v " + " ".join(repr(float(x)) for x in p) + "\n")
        for f in F:
            fh.write("f " + " ".join(str(int(i) + 1) for i in f) + "\n")
