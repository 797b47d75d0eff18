"""Peak memory of reading a mesh file (issue 45, item 4): ``python -m benchmarks meshread``.

The benchmark writes a wavy grid surface (float64 coordinates printed as ``repr``, the way an
exporter that round-trips writes them) as OBJ, OFF, ASCII PLY and binary PLY of about 5, 30
and 100 MB (``--quick``: 1 and 5 MB) into a temporary directory, and reads each one with
``ddg_oracle.application.meshfiles.read_mesh`` in a fresh interpreter.  The peak is that interpreter's
``ru_maxrss`` from ``os.wait4`` in a small wrapper process (``_PEAK`` of
tests/test_hostile.py): a process forked from a big parent starts with the parent's
high-water mark, a wrapper's child with the wrapper's few MB.  The same interpreter doing
everything but the read (imports, ``stat`` of the file) is the baseline.

Reported per file: size, peak RSS, peak / size, (peak - baseline) / size (what the read
itself costs; the issue's target: at most 10x, so that the default 2 GiB size limit cannot
exhaust a machine), wall seconds (of the reading interpreter, start to end).  Figures go into docs/faults.md (section "Reading a mesh file").
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from .common import ROOT, Mode, machine, say

FORMATS = ("obj", "off", "ply-ascii", "ply-binary")
SIZES_MB = (5, 30, 100)
QUICK_SIZES_MB = (1, 5)
TARGET = 10.0                        # peak RSS at most this many times the file size

#: the child: read the mesh (argv[1]) unless argv[2] == "baseline"; prints nothing
_READ = ("import os, sys\n"
         "from ddg_oracle.application.meshfiles import read_mesh\n"
         "os.stat(sys.argv[1])\n"
         "if sys.argv[2] != 'baseline':\n"
         "    V, F = read_mesh(sys.argv[1])\n"
         "    assert len(F) > 0\n")


def _peak_wrapper() -> str:
    """The wrapper that reports a child's exit code and peak RSS (KiB): tests/test_hostile.py's."""
    try:
        from tests.test_hostile import _PEAK
        return _PEAK
    except ImportError:                      # the tests are not shipped with an installed copy
        return ("import os, subprocess, sys\n"
                "p = subprocess.Popen(sys.argv[1:], stdout=subprocess.DEVNULL)\n"
                "_, status, usage = os.wait4(p.pid, 0)\n"
                "print(os.waitstatus_to_exitcode(status), usage.ru_maxrss)\n")


# --- the meshes ------------------------------------------------------------------------------

def _grid(n: int):
    """An n x n grid of vertices on a wavy surface, 2 (n-1)^2 triangles: (V float64 (n^2, 3),
    F int64 (2 (n-1)^2, 3)), consistently oriented."""
    import numpy as np
    u = np.linspace(0.0, 1.0, n)
    x, y = np.meshgrid(u, u, indexing="ij")
    z = 0.1 * np.sin(7.3 * x) * np.cos(5.1 * y)
    V = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    i, j = np.meshgrid(np.arange(n - 1), np.arange(n - 1), indexing="ij")
    a = (i * n + j).ravel()
    b, c, d = a + n, a + 1, a + n + 1
    F = np.concatenate([np.stack([a, b, c], 1), np.stack([c, b, d], 1)])
    return V, F


def _rows(V, F, vertex: str, face: str, base: int):
    """Text lines of V and F (repr floats), in chunks, without one string of the whole file."""
    step = 50_000
    for s in range(0, len(V), step):
        yield "".join(vertex % " ".join(map(repr, row)) for row in V[s:s + step].tolist())
    for s in range(0, len(F), step):
        yield "".join(face % " ".join(map(str, row)) for row in (F[s:s + step] + base).tolist())


def write_mesh(path, V, F, fmt: str) -> None:
    """Write (V, F) as ``fmt`` (one of FORMATS) to ``path``."""
    import numpy as np
    with open(path, "wb") as fh:
        if fmt == "obj":
            for chunk in _rows(V, F, "v %s\n", "f %s\n", 1):
                fh.write(chunk.encode())
        elif fmt == "off":
            fh.write(f"OFF\n{len(V)} {len(F)} 0\n".encode())
            for chunk in _rows(V, F, "%s\n", "3 %s\n", 0):
                fh.write(chunk.encode())
        elif fmt.startswith("ply"):
            binary = fmt == "ply-binary"
            fh.write(("ply\nformat " + ("binary_little_endian" if binary else "ascii")
                      + f" 1.0\nelement vertex {len(V)}\nproperty double x\nproperty double y\n"
                      f"property double z\nelement face {len(F)}\n"
                      "property list uchar int vertex_indices\nend_header\n").encode())
            if binary:
                fh.write(np.ascontiguousarray(V, "<f8").tobytes())
                rows = np.zeros(len(F), dtype=[("k", "u1"), ("i", "<i4", 3)])
                rows["k"], rows["i"] = 3, F
                fh.write(rows.tobytes())
            else:
                for chunk in _rows(V, F, "%s\n", "3 %s\n", 0):
                    fh.write(chunk.encode())
        else:
            raise ValueError(f"unknown format {fmt!r}")


def _bytes_per_vertex(fmt: str) -> float:
    """About how many bytes of ``fmt`` a grid vertex (with its 2 triangles) takes."""
    if fmt == "ply-binary":
        return 24 + 2 * 13
    return {"obj": 60 + 2 * 22, "off": 58 + 2 * 22}.get(fmt, 58 + 2 * 22)


def make_file(directory, fmt: str, megabytes: float) -> Path:
    """A grid mesh of about ``megabytes`` MB as ``fmt`` in ``directory``."""
    n = max(3, int(math.sqrt(megabytes * 1e6 / _bytes_per_vertex(fmt))))
    V, F = _grid(n)
    ext = {"obj": "obj", "off": "off"}.get(fmt, "ply")
    path = Path(directory) / f"grid-{fmt}-{megabytes:g}MB.{ext}"
    write_mesh(path, V, F, fmt)
    return path


# --- the measurement ----------------------------------------------------------------------------

def _peak_kib(path, what: str) -> tuple[int, int, float]:
    """(exit code, peak RSS KiB, wall seconds) of a fresh interpreter reading ``path``
    (``what`` = "read") or only importing (``"baseline"``)."""
    t0 = time.monotonic()
    out = subprocess.run([sys.executable, "-c", _peak_wrapper(), sys.executable, "-c", _READ,
                          str(path), what], capture_output=True, text=True, cwd=ROOT,
                         env={**os.environ, "DDG_MESH_SIZE_LIMIT": "4G"})
    wall = time.monotonic() - t0
    try:
        rc, kib = map(int, out.stdout.split())
    except ValueError:
        raise RuntimeError(f"the peak wrapper printed {out.stdout!r} ({out.stderr[-500:]})")
    return rc, kib, wall


def measure(path) -> dict:
    """Peak memory of ``read_mesh(path)`` in a fresh interpreter: {"bytes", "peak_mb",
    "baseline_mb", "ratio" (peak / size), "net_ratio" ((peak - baseline) / size), "seconds",
    "exit"}."""
    size = os.path.getsize(path)
    _, base, _ = _peak_kib(path, "baseline")
    rc, peak, wall = _peak_kib(path, "read")
    return {"bytes": size, "peak_mb": peak / 1024, "baseline_mb": base / 1024,
            "ratio": peak * 1024 / size, "net_ratio": (peak - base) * 1024 / size,
            "seconds": wall, "exit": rc}


def run(mode: Mode) -> dict:
    sizes = QUICK_SIZES_MB if mode.quick else SIZES_MB
    rows = []
    with tempfile.TemporaryDirectory(prefix="ddg-meshread-") as tmp:
        for mb in sizes:
            for fmt in FORMATS:
                path = make_file(tmp, fmt, mb)
                r = {"format": fmt, "target_mb": mb, **measure(path)}
                path.unlink()
                rows.append(r)
                say(f"  meshread {fmt:10} {r['bytes'] / 1e6:7.1f} MB  peak {r['peak_mb']:8.1f} MB"
                    f"  {r['ratio']:5.1f}x  (read alone {r['net_ratio']:5.1f}x)"
                    f"  {r['seconds']:5.1f} s  exit {r['exit']}")
    result = {"rows": rows, "target": TARGET, "command": _command(mode)}
    print(table(result))
    write_doc(result)
    return result


def _command(mode: Mode) -> str:
    return "python -m benchmarks meshread" + (" --quick" if mode.quick else "") + " --no-write"


def table(result: dict) -> str:
    lines = ["| format | file MB | peak RSS MB | peak / size | (peak - baseline) / size | "
             "seconds | read within 10x |", "|---|---:|---:|---:|---:|---:|---|"]
    for r in result["rows"]:
        # the read's own memory: the interpreter's baseline is not the file's doing
        ok = "yes" if r["exit"] == 0 and r["net_ratio"] <= result["target"] else \
            ("no" if r["exit"] == 0 else f"exit {r['exit']}")
        lines.append(f"| {r['format']} | {r['bytes'] / 1e6:.1f} | {r['peak_mb']:.0f} | "
                     f"{r['ratio']:.1f}x | {r['net_ratio']:.1f}x | {r['seconds']:.1f} | {ok} |")
    return "\n".join(lines)


def write_doc(result: dict) -> None:
    from .faults import replace_section
    m = machine()
    body = (f"`{result['command']}`: commit {m['commit']}, {m['date']}, "
            f"load {_uptime_load()} (uptime) at the end, {m['cpus']} CPUs, "
            f"Python {m['python']}.  Baseline (interpreter and imports, no read): "
            f"{result['rows'][0]['baseline_mb']:.0f} MB.\n\n" + table(result) + "\n")
    replace_section("meshread", body)


def _uptime_load() -> str:
    try:
        out = subprocess.run(["uptime"], capture_output=True, text=True, timeout=5).stdout
        return out.rsplit("load average:", 1)[1].strip()
    except (OSError, IndexError, subprocess.SubprocessError):
        return "-"


if __name__ == "__main__":
    sys.exit(0 if run(Mode.of(True)) else 1)
