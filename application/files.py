"""The one way ddg-oracle reads a file it is given: regular files only, and a size limit.

A device (``/dev/zero``), a FIFO or a directory given where a file is expected would make
a plain ``read()`` never end, or read gigabytes; every file the command reads (meshes,
answers files, test-vector corpora, report directories' state) goes through
:func:`read_bytes`, which refuses those in one line before opening them and reads at
most ``limit`` bytes of the rest.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from ..reference.errors import InputError

#: the largest JSON file (answers, corpus files, a report's state) read: 256 MiB
JSON_LIMIT = 256 << 20


def kind_of(mode: int) -> str:
    """What a file that is not a regular file is, in words."""
    return ("a directory" if stat.S_ISDIR(mode) else
            "a FIFO (named pipe)" if stat.S_ISFIFO(mode) else
            "a device" if stat.S_ISCHR(mode) or stat.S_ISBLK(mode) else
            "a socket" if stat.S_ISSOCK(mode) else "not a regular file")


def read_bytes(path, what: str, limit: int, error=InputError, limit_hint: str = "") -> bytes:
    """The bytes of the regular file ``path`` (``what`` names it in errors), at most
    ``limit``; ``error`` (an InputError) for anything else, in one line.

    >>> read_bytes("/dev/zero", "an answers file", 1 << 20)
    Traceback (most recent call last):
    ...
    ddg_oracle.reference.errors.InputError: /dev/zero: cannot read an answers file: it is a device, not a regular file
    """
    path = Path(path)
    try:
        info = os.stat(path)
    except OSError as e:
        raise error(f"{path}: cannot read {what}: {e.strerror or e}") from None
    if not stat.S_ISREG(info.st_mode):
        raise error(f"{path}: cannot read {what}: it is {kind_of(info.st_mode)}, not a "
                    "regular file")
    hint = f" ({limit_hint})" if limit_hint else ""
    if info.st_size > limit:
        raise error(f"{path}: {info.st_size:,} bytes, over the limit of {limit:,} for "
                    f"{what}{hint}")
    try:
        with open(path, "rb") as fh:
            # the size stat saw, not the limit: read(limit + 1) reserves the whole limit (2
            # GiB for a mesh) up front, a MemoryError under ulimit -v for a 20-face file; a
            # file that grew since stat is still read only up to the limit
            data = fh.read(info.st_size + 1)
            while len(data) <= limit:
                more = fh.read(min(1 << 20, limit + 1 - len(data)))
                if not more:
                    break
                data += more
    except OSError as e:
        raise error(f"{path}: cannot read {what}: {e.strerror or e}") from None
    if len(data) > limit:
        raise error(f"{path}: over the limit of {limit:,} bytes for {what}{hint}")
    return data


def read_text(path, what: str, limit: int = JSON_LIMIT, error=InputError) -> str:
    """:func:`read_bytes` decoded as UTF-8 (a file that is not: ``error``)."""
    data = read_bytes(path, what, limit, error)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise error(f"{path}: {what} is not UTF-8 text ({e.reason} at byte {e.start})") from None


def write_atomically(path, text: str) -> None:
    """Write ``text`` to ``path`` through a temporary file beside it, renamed into place:
    a reader (or a run interrupted while writing) sees the old file or the whole new one,
    never a part."""
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        with open(tmp, "w", encoding="utf-8") as fh:
            fh.write(text)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


def available_memory() -> int | None:
    """Bytes this process may still allocate: the kernel's MemAvailable (Linux), or less
    under an address-space limit (``ulimit -v``); None where neither is known."""
    have = None
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    have = int(line.split()[1]) * 1024
                    break
    except (OSError, ValueError):
        pass
    try:
        import resource
        soft, _ = resource.getrlimit(resource.RLIMIT_AS)
        if soft != resource.RLIM_INFINITY:
            with open("/proc/self/statm", encoding="ascii") as fh:
                used = int(fh.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
            room = max(soft - used, 0)
            have = room if have is None else min(have, room)
    except (ImportError, OSError, ValueError):
        pass
    return have


def require_memory(path, factor: float, what: str, error=InputError) -> None:
    """``error`` in one line, before any parsing, if ``what`` (whose peak is about
    ``factor`` times the file's size, as measured by ``python -m benchmarks meshread``)
    would need more memory than this process has: a file well under the size limit must
    not exhaust the machine (or be killed by the kernel midway)."""
    path = Path(path)
    try:
        need = int(factor * os.stat(path).st_size)
    except OSError:
        return                              # the reader names the problem
    have = available_memory()
    if have is not None and need > have:
        raise error(f"{path}: {what} needs about {need / 2 ** 30:.2f} GiB of memory ({factor:g} "
                    f"x its {os.stat(path).st_size:,} bytes), {have / 2 ** 30:.2f} GiB available")

